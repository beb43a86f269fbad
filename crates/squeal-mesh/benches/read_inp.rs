//! Read time of the Abaqus `.inp` reader (`squeal_mesh::inp::read`, warm file cache).
//!
//! - `disc_fine.inp`: the bundled fine disc (45,578 nodes, 26,488 tet10), when present;
//! - `brake_fine_assembly.inp`: the bundled fine disc and pad (60,606 nodes) as two parts,
//!   each an `*INCLUDE` of the bundled file, instanced in an assembly (renumbering, sets);
//! - without the bundled meshes (or with `SQUEAL_BENCH_GENERATED=1`), `box_59k.inp`: a
//!   generated 19x19x19-cell box (59,319 nodes, 41,154 tet10) written to a temporary folder.
//!
//! Target: a 60k-node mesh in well under a second.
//!
//!   cargo bench -p squeal-mesh --bench read_inp

use criterion::{Criterion, criterion_group, criterion_main};
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::{Path, PathBuf};

/// A fresh temporary folder for generated files.
fn temp_dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("squeal-bench-read-inp-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary folder");
    dir
}

/// An assembly of the bundled fine disc and pad, included as parts.
fn brake_assembly(meshes: &Path, dir: &Path) -> Option<PathBuf> {
    let disc = meshes.join("disc_fine.inp").canonicalize().ok()?;
    let pad = meshes.join("pad_fine.inp").canonicalize().ok()?;
    let text = format!(
        "*PART, NAME=DISC\n*INCLUDE, INPUT={}\n*END PART\n*PART, NAME=PAD\n*INCLUDE, INPUT={}\n*END PART\n\
         *ASSEMBLY, NAME=BRAKE\n*INSTANCE, NAME=DISC-1, PART=DISC\n*END INSTANCE\n\
         *INSTANCE, NAME=PAD-1, PART=PAD\n0., 0., 0.001\n*END INSTANCE\n*END ASSEMBLY\n",
        disc.display(),
        pad.display()
    );
    let path = dir.join("brake_fine_assembly.inp");
    std::fs::write(&path, text).ok()?;
    Some(path)
}

/// A generated box of 59,319 nodes written as a flat `.inp` file.
fn generated_box(dir: &Path) -> PathBuf {
    let m = squeal_mesh::generate::box_tet10([1.0, 1.0, 1.0], [19, 19, 19]);
    let mut s = String::from("*NODE, NSET=NALL\n");
    for (id, x) in m.node_ids.iter().zip(&m.nodes) {
        let _ = writeln!(s, "{id}, {:.17e}, {:.17e}, {:.17e}", x[0], x[1], x[2]);
    }
    s.push_str("*ELEMENT, TYPE=C3D10, ELSET=ALL\n");
    for (id, el) in m.element_ids.iter().zip(&m.blocks.tet10) {
        let _ = write!(s, "{id}");
        for &n in el {
            let _ = write!(s, ", {}", m.node_ids[n as usize]);
        }
        s.push('\n');
    }
    let path = dir.join("box_59k.inp");
    std::fs::write(&path, s).expect("write the generated mesh");
    path
}

fn files(dir: &Path) -> Vec<PathBuf> {
    let meshes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
    let disc = meshes.join("disc_fine.inp");
    if !disc.exists() || std::env::var_os("SQUEAL_BENCH_GENERATED").is_some() {
        return vec![generated_box(dir)];
    }
    let mut out = vec![disc];
    out.extend(brake_assembly(&meshes, dir));
    out
}

fn read_inp(c: &mut Criterion) {
    let dir = temp_dir();
    let mut group = c.benchmark_group("read_inp");
    group.sample_size(20);
    for path in files(&dir) {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        match squeal_mesh::inp::read(&path) {
            Ok(r) => println!(
                "{name}: {} nodes, {} tet10",
                r.mesh.num_nodes(),
                r.mesh.num_elements()
            ),
            Err(e) => {
                println!("{name}: not benchmarked: {e}");
                continue;
            }
        }
        group.bench_function(name, |b| {
            b.iter(|| squeal_mesh::inp::read(black_box(&path)))
        });
    }
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

/// The quality checks every part's mesh now passes before a reduction (issue 22: what
/// `mesh info` calls an ERROR, the reduction refuses), on the fine disc: their cost against
/// reading the file.
fn quality_check(c: &mut Criterion) {
    let disc = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/disc_fine.inp");
    let Ok(read) = squeal_mesh::inp::read(&disc) else {
        println!("disc_fine.inp: not benchmarked");
        return;
    };
    let mut group = c.benchmark_group("quality_check");
    group.sample_size(20);
    let opts = squeal_mesh::quality::QualityOptions::default();
    group.bench_function("disc_fine.inp", |b| {
        b.iter(|| squeal_mesh::quality::check(black_box(&read.mesh), &opts))
    });
    group.finish();
}

criterion_group!(benches, read_inp, quality_check);
criterion_main!(benches);
