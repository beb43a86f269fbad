//! Prints a table of friction-sweep time against reduced size: the bundled scene
//! (`meshes/brake.toml`) on its coarse meshes, reduced with a given interface and number of
//! fixed-interface modes per part, swept over 201 friction values by each method asked for.
//!
//! `cargo bench -p squeal-pipeline --bench sweep_scaling -- [GRID:MODES[:METHODS]]...`
//! with GRID the contact patches `RxA` (radial x angular; the scene's is 3x3: 9 pairs), MODES
//! the fixed-interface modes per part and METHODS a `+`-separated list of `projected`,
//! `continuation`, `dense`, `auto` (default `projected`), then optionally `:cut=F,comp=Z,terms=T,tol=E`
//! (the projection's first cut-off over the band's top, compression of its correction vectors,
//! most correction terms, tolerance of its check; `rq=0` refines the Hopf point with whole
//! decompositions, the former way, instead of Rayleigh iteration). More modes grow the reduced brake
//! with the number of eigenvalues in the band nearly fixed; a finer grid grows it with the
//! contact (three interface dofs per patch and part, one pair per patch).
//!
//! A case may instead name a scene file, `PATH.toml[:METHODS[:TWEAKS]]` (e.g. the ventilated
//! brake with nodal contact), swept with its global modal damping (no pair damping) and its band; `n=N` among the tweaks sets
//! the number of friction values (default 201). Its interface reduction (nodal contact's
//! default `"system"`) is printed with the time of each level tried.

#[path = "../tests/pipeline/common/mod.rs"]
mod common;

use squeal_brake::Brake;
use squeal_brake::equilibrium::{NewtonOptions, static_equilibrium};
use squeal_brake::modal::{Damping, modal_basis};
use squeal_brake::spectrum::Reference;
use squeal_brake::sweep::{SweepMethod, sweep};
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

/// The frictionless reference as [`squeal_brake::sweep::reference`] makes it, each phase
/// timed: equilibrium, modal basis, modal damping (s).
fn timed_reference(brake: &Brake, damping: &Damping) -> (Reference, [f64; 3]) {
    let t = Instant::now();
    let eq = static_equilibrium(brake, 0.0, None, &NewtonOptions::default()).expect("equilibrium");
    let kt0 = brake.tangent_stiffness(&eq.x, 0.0);
    let t_eq = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let basis = modal_basis(&brake.m, &kt0).expect("modal basis");
    let t_basis = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let d = damping.modal(&basis).expect("modal damping");
    let t_damping = t.elapsed().as_secs_f64();
    let r = Reference {
        equilibrium: eq,
        kt0,
        basis,
        damping: d,
    };
    (r, [t_eq, t_basis, t_damping])
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
        let scene_file = case
            .split(':')
            .next()
            .filter(|p| p.ends_with(".toml"))
            .map(std::path::PathBuf::from);
        if scene_file.is_some() {
            it.next();
        }
        let grid = if scene_file.is_some() {
            None
        } else {
            it.next()
        }
        .and_then(|g| g.split_once('x'))
        .and_then(|(a, b)| Some((a.parse().ok()?, b.parse().ok()?)))
        .unwrap_or((3, 3));
        let modes: usize = if scene_file.is_some() {
            0
        } else {
            it.next().and_then(|m| m.parse().ok()).unwrap_or(50)
        };
        let methods = it.next().unwrap_or("projected");
        // Projection options: `cut=F` (first cut-off / band top), `comp=Z` (compression of
        // the correction vectors), `terms=T`, comma-separated.
        let tweaks = it.next().unwrap_or("");
        let out = std::env::temp_dir().join(format!(
            "squeal-sweep-scaling-{}x{}-{modes}",
            grid.0, grid.1
        ));
        let the_scene = match &scene_file {
            Some(path) => {
                let text = std::fs::read_to_string(path).expect("the scene file reads");
                Scene::parse(path, text).expect("the scene parses")
            }
            None => scene(grid, modes),
        };
        let out = match &scene_file {
            Some(path) => std::env::temp_dir().join(format!(
                "squeal-sweep-scaling-{}",
                path.file_stem()
                    .map_or("scene".into(), |s| s.to_string_lossy())
            )),
            None => out,
        };
        let t = Instant::now();
        let model = build(&the_scene, &out, &quiet).expect("the model builds");
        eprintln!("{case}: model built in {:.1?}", t.elapsed());
        // What an interface reduction kept and why (nodal contact's default), with its levels'
        // times.
        if let Some(i) = &model.interface {
            eprint!("{}", i.text());
        }
        let brake = &model.brake;
        let damping = Damping {
            global_ratio: model.damping.global_ratio,
            extra: vec![],
        };
        let (r, phases) = timed_reference(brake, &damping);
        let t_ref: f64 = phases.iter().sum();
        eprintln!(
            "  reference: equilibrium {:.2} s, modal basis {:.2} s, damping {:.2} s",
            phases[0], phases[1], phases[2]
        );
        let points = tweaks
            .split(',')
            .filter_map(|t| t.split_once('='))
            .find(|(k, _)| *k == "n")
            .map_or(201, |(_, v)| v.parse().expect("n=N: a count"));
        let mus = common::mus(0.0, 1.0, points);
        for method in methods.split('+') {
            let m = match method {
                "dense" => SweepMethod::Dense,
                "continuation" => SweepMethod::Continuation,
                "auto" => SweepMethod::Auto,
                _ => SweepMethod::Projected,
            };
            let mut opts = {
                let mut o = model.sweep;
                o.method = m;
                o
            };
            for (key, value) in tweaks.split(',').filter_map(|t| t.split_once('=')) {
                let v: f64 = value.parse().expect("a number");
                match key {
                    "cut" => opts.projection.first_cutoff = v,
                    "comp" => opts.projection.compression = v,
                    "terms" => opts.projection.correction_terms = v as usize,
                    "tol" => opts.projection.tolerance = v,
                    "rq" => opts.projection.rayleigh_refinement = v != 0.0,
                    "n" => {}
                    _ => panic!("unknown projection option {key}"),
                }
            }
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
                "| {} | {modes} | {} | {} | {method} {tweaks} | {ts:.2} | {t_ref:.2} | {in_band} | {kept} | {mu0:.10} | {f0:.5} |",
                scene_file
                    .as_ref()
                    .map_or(format!("{}x{}", grid.0, grid.1), |p| p
                        .file_stem()
                        .map_or("scene".into(), |s| s.to_string_lossy().into_owned())),
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
            let newton: usize = s.points.iter().map(|p| p.equilibrium.iterations).sum();
            eprintln!("  Newton iterations over the points: {newton}");
            if let Some(h) = &s.hopf {
                // The normal form at μ0 the pipeline computes after the sweep.
                let t = Instant::now();
                let guess = faer::c64::new(0.0, std::f64::consts::TAU * h.frequency_hz);
                let nf =
                    squeal_brake::criticality::normal_form(brake, &r, h.mu0, guess, &opts.newton);
                eprintln!(
                    "  normal form at mu0: {:.2} s, l1 = {}",
                    t.elapsed().as_secs_f64(),
                    nf.map_or_else(|e| e.to_string(), |nf| format!("{:.6e}", nf.l1))
                );
            }
            let p = &s.timings;
            eprintln!(
                "  phases (s): projection {:.2}, equilibria {:.2}, spectra {:.2}, tracking {:.2}, refinement {:.2} ({} evaluations)",
                p.projection.as_secs_f64(),
                p.equilibria.as_secs_f64(),
                p.spectra.as_secs_f64(),
                p.tracking.as_secs_f64(),
                p.refinement.as_secs_f64(),
                s.hopf.as_ref().map_or(0, |h| h.evaluations)
            );
        }
    }
}
