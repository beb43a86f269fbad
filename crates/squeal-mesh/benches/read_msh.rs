//! Read time of the Gmsh `.msh` reader (`squeal_mesh::msh::read`, from a warm file cache):
//! AMfe's bar (MSH 2.2 ASCII, 34,545 nodes, 22,432 tet10) and, when present, the bundled fine
//! disc `meshes/disc_fine.msh` (MSH 4.1). Target: 60k nodes well under a second.
//!
//!   cargo bench -p squeal-mesh --bench read_msh

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::path::{Path, PathBuf};

fn files() -> Vec<PathBuf> {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let candidates = [
        crate_dir.join("tests/data/outside/amfe-bar_Tet10_fine.msh"),
        crate_dir.join("../../meshes/disc_fine.msh"),
    ];
    candidates.into_iter().filter(|p| p.exists()).collect()
}

fn read_msh(c: &mut Criterion) {
    let mut group = c.benchmark_group("read_msh");
    group.sample_size(20);
    for path in files() {
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let mesh = squeal_mesh::msh::read(&path).map(|r| r.mesh);
        if let Ok(mesh) = &mesh {
            println!(
                "{name}: {} nodes, {} tet10",
                mesh.num_nodes(),
                mesh.num_elements()
            );
        }
        group.bench_function(name, |b| {
            b.iter(|| squeal_mesh::msh::read(black_box(&path)))
        });
    }
    group.finish();
}

criterion_group!(benches, read_msh);
criterion_main!(benches);
