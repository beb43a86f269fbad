//! Prints a table of friction-sweep time against reduced size: the bundled scene
//! (`meshes/brake.toml`) on its coarse meshes, reduced with a given interface and number of
//! fixed-interface modes per part, swept over 201 friction values by each method asked for.
//!
//! `cargo bench -p squeal-pipeline --bench sweep_scaling -- [GRID:MODES[:METHODS]]...`
//! with GRID the contact patches `RxA` (radial x angular; the scene's is 3x3: 9 pairs), MODES
//! the fixed-interface modes per part and METHODS a `+`-separated list of `projected`,
//! `continuation`, `dense`, `auto` (default `projected`). More modes grow the reduced brake
//! with the number of eigenvalues in the band nearly fixed; a finer grid grows it with the
//! contact (three interface dofs per patch and part, one pair per patch).

#[path = "../tests/common/mod.rs"]
mod common;

use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::modal::Damping;
use squeal_brake::sweep::{SweepMethod, reference, sweep};
use squeal_pipeline::model::{build, quiet};
use squeal_scene::Scene;
use std::time::Instant;

/// The bundled scene on the coarse meshes with a `grid` of patches and `modes` per part.
fn scene(grid: (usize, usize), modes: usize) -> Scene {
    let path = common::meshes().join("brake.toml");
    let text = std::fs::read_to_string(&path).expect("meshes/brake.toml");
    let text: String = text
        .lines()
        .map(|l| {
            let l = if l.starts_with("disc = ") {
                "disc = \"disc_coarse.inp\"".to_string()
            } else if l.starts_with("pad = ") {
                "pad = \"pad_coarse.inp\"".to_string()
            } else if l.starts_with("modes = ") {
                format!("modes = {modes}")
            } else {
                l.to_string()
            };
            l + "\n"
        })
        .collect::<String>()
        + &format!("\n[sets]\npatch_grid = [{}, {}]\n", grid.0, grid.1);
    let name = format!("brake_coarse_{}x{}_{modes}.toml", grid.0, grid.1);
    Scene::parse(&common::meshes().join(name), text).expect("the edited scene parses")
}

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let cases: Vec<String> = if args.is_empty() {
        vec!["3x3:50:projected+continuation".into()]
    } else {
        args
    };
    println!(
        "| patches | modes/part | reduced dofs | pairs | method | sweep (s) | reference (s) | in band | kept | mu0 | f0 (Hz) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for case in cases {
        let mut it = case.split(':');
        let grid = it
            .next()
            .and_then(|g| g.split_once('x'))
            .and_then(|(a, b)| Some((a.parse().ok()?, b.parse().ok()?)))
            .unwrap_or((3, 3));
        let modes: usize = it.next().and_then(|m| m.parse().ok()).unwrap_or(50);
        let methods = it.next().unwrap_or("projected");
        let out = std::env::temp_dir().join(format!(
            "squeal-sweep-scaling-{}x{}-{modes}",
            grid.0, grid.1
        ));
        let t = Instant::now();
        let model = build(&scene(grid, modes), &out, &quiet).expect("the model builds");
        eprintln!("{case}: model built in {:.1?}", t.elapsed());
        let brake = &model.brake;
        let t = Instant::now();
        let damping = Damping {
            global_ratio: model.damping.global_ratio,
            extra: vec![],
        };
        let r = reference(brake, &damping, &NewtonOptions::default()).expect("reference");
        let t_ref = t.elapsed().as_secs_f64();
        let mus = common::mus(0.0, 1.0, 201);
        for method in methods.split('+') {
            let m = match method {
                "dense" => SweepMethod::Dense,
                "continuation" => SweepMethod::Continuation,
                "auto" => SweepMethod::Auto,
                _ => SweepMethod::Projected,
            };
            let opts = {
                let mut o = model.sweep;
                o.method = m;
                o
            };
            let t = Instant::now();
            let s = sweep(brake, &r, &mus, &opts).expect("the sweep");
            let ts = t.elapsed().as_secs_f64();
            let in_band = s.points[0]
                .spectrum
                .values
                .iter()
                .filter(|l| opts.band.contains(l.im / std::f64::consts::TAU))
                .count();
            let kept = s.projection.as_ref().map_or(brake.size().to_string(), |p| {
                format!("{} + {}", p.kept_modes, p.residual_vectors)
            });
            let (mu0, f0) = s
                .hopf
                .as_ref()
                .map_or((f64::NAN, f64::NAN), |h| (h.mu0, h.frequency_hz));
            println!(
                "| {}x{} | {modes} | {} | {} | {method} | {ts:.2} | {t_ref:.2} | {in_band} | {kept} | {mu0:.8} | {f0:.3} |",
                grid.0,
                grid.1,
                brake.size(),
                brake.pairs.len()
            );
            if let Some(p) = &s.projection {
                for t in &p.trials {
                    eprintln!(
                        "  trial: {} modes to {:.0} Hz + {} vectors: deviation {:.2e}",
                        t.kept_modes, t.cutoff_hz, t.residual_vectors, t.deviation
                    );
                }
                eprintln!(
                    "  checked at mu {:?}: {} in-band eigenvalues",
                    p.checked_mus, p.checked_values
                );
            }
            eprintln!("  stats: {:?}", s.stats);
        }
    }
}
