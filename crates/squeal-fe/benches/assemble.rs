//! Assembly of K and M: a structured tet10 box of 59,319 nodes and, when present and
//! readable, the bundled fine brake meshes (meshes/disc_fine.inp, meshes/pad_fine.inp), on a
//! rayon pool of 1 and of 2 threads.
//!
//! Before criterion's timings, a table gives per case the best wall time of three runs with
//! its CPU time (all threads), and the peak resident memory of the first run (VmHWM from
//! /proc/self/status after resetting it through /proc/self/clear_refs; the mesh itself is
//! already resident and counted in "before").
//!
//! `nice cargo bench -p squeal-fe --bench assemble`

use criterion::{Criterion, criterion_group, criterion_main};
use squeal_fe::{DofMap, ElasticMaterial, MaterialTable, Restraint, System, assemble};
use squeal_mesh::Mesh;
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

struct Case {
    name: String,
    mesh: Mesh,
    materials: MaterialTable,
    dofs: DofMap,
}

fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    // (2·19 + 1)³ = 59,319 nodes, 41,154 elements.
    let mesh = squeal_mesh::generate::box_tet10([0.3, 0.3, 0.3], [19, 19, 19]);
    let materials =
        MaterialTable::uniform(&mesh, ElasticMaterial::isotropic(125e9, 0.26, 7200.0)).unwrap();
    let dofs = DofMap::new(&mesh, &[Restraint::clamp("ZMIN")]).unwrap();
    out.push(Case {
        name: "box_59k".into(),
        mesh,
        materials,
        dofs,
    });
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
    for (file, restraint) in [
        ("disc_fine.inp", Restraint::clamp("CLAMP")),
        (
            "pad_fine.inp",
            Restraint::set("ABUTMENT", [true, true, false]),
        ),
    ] {
        let Ok(read) = squeal_mesh::read(&root.join(file)) else {
            eprintln!("skipping {file}: not present or not readable");
            continue;
        };
        let mesh = read.mesh;
        let (Ok(materials), Ok(dofs)) = (
            MaterialTable::from_mesh(&mesh, &[]),
            DofMap::new(&mesh, &[restraint]),
        ) else {
            eprintln!("skipping {file}: materials or sets missing");
            continue;
        };
        out.push(Case {
            name: file.trim_end_matches(".inp").into(),
            mesh,
            materials,
            dofs,
        });
    }
    out
}

/// CPU time (user + system, all threads) of this process in seconds, from /proc/self/stat
/// (fields 14 and 15, in clock ticks of 1/100 s): the machine is shared, so wall time alone
/// depends on the load.
fn cpu_seconds() -> f64 {
    let Ok(s) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    let Some(close) = s.rfind(')') else {
        return 0.0;
    };
    let f: Vec<&str> = s[close + 1..].split_whitespace().collect();
    let tick = |i: usize| f.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.0);
    (tick(11) + tick(12)) / 100.0
}

/// A line of /proc/self/status in kB.
fn status_kb(key: &str) -> Option<u64> {
    let text = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = text.lines().find(|l| l.starts_with(key))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

fn run(case: &Case) -> System {
    assemble(&case.mesh, &case.materials, &case.dofs).unwrap()
}

fn table(cases: &[Case]) {
    println!(
        "| case | nodes | elements | free dofs | nnz K | nnz M | threads | wall (s) | cpu (s) | peak RSS (MB) | before (MB) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for case in cases {
        for threads in [1, 2] {
            let p = pool(threads);
            // Reset the high-water mark to the current RSS (Linux >= 4.0).
            let reset = std::fs::write("/proc/self/clear_refs", "5").is_ok();
            let before = status_kb("VmRSS:").unwrap_or(0);
            let (t, c) = (Instant::now(), cpu_seconds());
            let sys = p.install(|| run(case));
            let (mut secs, mut cpu) = (t.elapsed().as_secs_f64(), cpu_seconds() - c);
            let peak = if reset {
                status_kb("VmHWM:").unwrap_or(0)
            } else {
                0
            };
            // Best wall time of three runs: the machine is shared.
            for _ in 0..2 {
                let (t, c) = (Instant::now(), cpu_seconds());
                drop(black_box(p.install(|| run(case))));
                if t.elapsed().as_secs_f64() < secs {
                    (secs, cpu) = (t.elapsed().as_secs_f64(), cpu_seconds() - c);
                }
            }
            println!(
                "| {} | {} | {} | {} | {} | {} | {threads} | {secs:.3} | {cpu:.2} | {:.0} | {:.0} |",
                case.name,
                case.mesh.num_nodes(),
                case.mesh.num_elements(),
                sys.num_dofs(),
                sys.nnz_k(),
                sys.nnz_m(),
                peak as f64 / 1024.0,
                before as f64 / 1024.0
            );
        }
    }
}

fn bench(c: &mut Criterion) {
    let cases = cases();
    table(&cases);
    let mut group = c.benchmark_group("assemble");
    group.sample_size(10);
    for case in &cases {
        for threads in [1, 2] {
            let p = pool(threads);
            group.bench_function(format!("{}/threads={threads}", case.name), |b| {
                b.iter(|| black_box(p.install(|| run(case))))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
