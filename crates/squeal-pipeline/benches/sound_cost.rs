//! Issue 23's goal: the sound of every cycle of the branch, the unstable mode's contributions
//! and the sensitivities together add less than 20 % to `squeal branch`'s work, on the
//! bundled (medium) brake. Each repetition makes a fresh pipeline (the reduced model read
//! from its cache) and times, in the order `squeal branch` and `squeal stability` run them:
//!
//! - the friction sweep (`Pipeline::stability`) and the branch of limit cycles with its
//!   Floquet stability ([`branch::analyse`]): what `squeal branch` computes without sound;
//! - the sound of every cycle of the branch ([`sound::branch_levels_or_log`]: the radiating
//!   surface built, each cycle's full field, ERP and levels at the microphone);
//! - the contributions at μ0 and along the sweep with the contributors' nodal diameters
//!   (the meshes read: [`contributions`]), and the sensitivities ([`sensitivities::compute`]).
//!
//! `cargo bench -p squeal-pipeline --bench sound_cost` (after `--`: `level=coarse` or `medium`
//! (default), `reps=N` (3): best of N of each step).

#[path = "../tests/pipeline/common/mod.rs"]
mod common;

use squeal_pipeline::branch::{self, BranchOptions, HillOptions};
use squeal_pipeline::stability::{contributions, sensitivities};
use squeal_pipeline::{Pipeline, model::quiet, shapes::Meshes, sound};
use std::time::Instant;

fn arg(name: &str) -> Option<String> {
    std::env::args().find_map(|a| a.strip_prefix(&format!("{name}=")).map(String::from))
}

fn secs(t: Instant) -> f64 {
    t.elapsed().as_secs_f64()
}

/// One repetition: `[model read, sweep, branch, sound, contributions, sensitivities]` (s) and
/// the branch's cycle count.
fn once(level: &str, out: &std::path::Path) -> ([f64; 6], usize) {
    let p = Pipeline::new(common::bundled_scene(level), out.to_path_buf(), &quiet).unwrap();
    let t = Instant::now();
    let m = p.model().unwrap();
    let t_model = secs(t);
    let t = Instant::now();
    let st = p.stability().unwrap();
    let t_sweep = secs(t);
    let t = Instant::now();
    let opts = BranchOptions::default();
    let a = branch::analyse(m, st, &opts, &HillOptions::default(), &[], &quiet)
        .unwrap()
        .expect("the bundled brake has a Hopf point");
    let t_branch = secs(t);
    let t = Instant::now();
    let (levels, _) =
        sound::branch_levels_or_log(&p.scene, m, st, &a, opts.samples, &p.sound, &quiet);
    let t_sound = secs(t);
    assert_eq!(levels.len(), a.branch.points.len());
    let t = Instant::now();
    let mut c = contributions::at_hopf(m, st).unwrap();
    let meshes = Meshes::read(m, &quiet).unwrap();
    contributions::classify(m, st, &mut c, &meshes);
    let along = contributions::along_sweep(m, st);
    let t_contrib = secs(t);
    let t = Instant::now();
    let r = sensitivities::compute(m, st).unwrap().unwrap();
    let t_sens = secs(t);
    assert!(!along.is_empty() && !r.rows.is_empty());
    (
        [t_model, t_sweep, t_branch, t_sound, t_contrib, t_sens],
        a.branch.points.len(),
    )
}

fn main() {
    faer::set_global_parallelism(faer::Par::Seq);
    let level = arg("level").unwrap_or_else(|| "medium".into());
    let reps: usize = arg("reps").map_or(3, |s| s.parse().unwrap());
    let out = std::env::temp_dir().join(format!("squeal-bench-sound-cost-{level}"));
    // A first pipeline reduces (or reads) the model into `out`; not timed.
    let p = Pipeline::new(common::bundled_scene(&level), out.clone(), &quiet).unwrap();
    p.model().unwrap();
    let mut best = [f64::INFINITY; 6];
    let mut cycles = 0;
    for _ in 0..reps {
        let (t, n) = once(&level, &out);
        cycles = n;
        for k in 0..6 {
            best[k] = best[k].min(t[k]);
        }
    }
    let names = [
        "reduced model read from its cache",
        "friction sweep (stability)",
        "branch of limit cycles and their Floquet stability",
        "sound of every cycle of the branch",
        "contributions at mu0 and along the sweep",
        "sensitivities (174 parameters)",
    ];
    println!("{level} brake, {cycles} cycles on the branch, best of {reps}:");
    println!("| step | time (s) |");
    println!("|---|---|");
    for (n, t) in names.iter().zip(best) {
        println!("| {n} | {t:.3} |");
    }
    let base: f64 = best[..3].iter().sum();
    let added: f64 = best[3..].iter().sum();
    println!(
        "squeal branch's work without them (model, sweep, branch) {base:.3} s; sound + contributions + sensitivities {added:.3} s: {:.1} % added (goal 20 %)",
        100.0 * added / base
    );
}
