//! The branch of limit cycles with its Floquet stability (issue 10) on the bundled brake: the
//! continuation and Hill's method timed separately, with one and with all threads, then both
//! overlapped as `squeal branch` runs them (`follow_from_hopf_with_hill`: each cycle's Hill
//! analysis on another thread while the continuation goes on), for the default step and for a
//! finer one that gives about 100 cycles.
//!
//! `cargo bench -p squeal-pipeline --bench branch` (options after `--`: `level=coarse` or
//! `medium`, `reps=N` (1), `step=s` (the finer maximum step, default 0.035: 102 cycles on the
//! medium brake), `coverage=c` (Hill's strip coverage, default 0.01) and `tolerance=t` (its
//! Ritz acceptance, default 1e-10): with other values each cycle's verdict and largest
//! multiplier are compared with the defaults').

#[path = "../tests/pipeline/common/mod.rs"]
mod common;

use common::best;

use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::bifurcation::{follow_from_hopf_with_hill, hill_along};
use squeal_chbm::branch::{BranchOptions, follow_from_hopf};
use squeal_chbm::floquet::HillOptions;
use squeal_pipeline::{Pipeline, model::quiet, stability};
use std::time::Instant;

fn arg(name: &str) -> Option<String> {
    std::env::args().find_map(|a| a.strip_prefix(&format!("{name}=")).map(String::from))
}

fn main() {
    // As the CLI: dense kernels sequential, so that results do not depend on the thread count.
    faer::set_global_parallelism(faer::Par::Seq);
    let level = arg("level").unwrap_or_else(|| "coarse".into());
    let reps: usize = arg("reps").map_or(1, |s| s.parse().unwrap());
    let out = std::env::temp_dir().join(format!("squeal-bench-branch-{level}"));
    let p = Pipeline::new(common::bundled_scene(&level), out, &quiet).unwrap();
    let t = Instant::now();
    let (m, st) = (p.model().unwrap(), p.stability().unwrap());
    eprintln!("{level} brake and sweep in {:.1?}", t.elapsed());
    let nf = stability::normal_form(m, st).unwrap().unwrap();
    let mb = ModalBrake::new(&m.brake, &st.reference, nf.mu0);
    let threads = rayon::current_num_threads();
    println!(
        "{level} brake, {} modes, mu0 = {:.6}, {threads} threads available",
        mb.modes(),
        nf.mu0
    );
    println!(
        "| max step | cycles | harmonics | continuation (s) | Hill, 1 thread (s) | Hill, {threads} threads (s) | per cycle (ms, {threads} threads) | both overlapped, {threads} threads (s) |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let fine: f64 = arg("step").map_or(0.035, |s| s.parse().unwrap());
    for max_step in [0.1, fine] {
        let mut opts = BranchOptions::default();
        opts.continuation.max_step = max_step;
        let (tc, b) = best(reps, || follow_from_hopf(&mb, &nf, &opts).unwrap());
        let mut h = HillOptions::default();
        if let Some(c) = arg("coverage") {
            h.coverage = c.parse().unwrap();
        }
        if let Some(t) = arg("tolerance") {
            h.tolerance = t.parse().unwrap();
        }
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let (t1, f1) = best(reps, || one.install(|| hill_along(&mb, &b, None, &h)));
        let (tn, fnn) = best(reps, || hill_along(&mb, &b, None, &h));
        // Same bits for any thread count.
        let differ = f1
            .iter()
            .zip(&fnn)
            .filter(|(a, c)| a.as_ref().unwrap().exponents != c.as_ref().unwrap().exponents)
            .count();
        assert_eq!(
            differ, 0,
            "exponents of {differ} cycles depend on the thread count"
        );
        if h.coverage != HillOptions::default().coverage
            || h.tolerance != HillOptions::default().tolerance
        {
            let reference = hill_along(&mb, &b, None, &HillOptions::default());
            let (mut verdicts, mut worst) = (0, 0.0f64);
            for (a, r) in fnn.iter().zip(&reference) {
                let (a, r) = (a.as_ref().unwrap(), r.as_ref().unwrap());
                verdicts += usize::from(a.stability() != r.stability());
                worst = worst.max((a.largest_multiplier() - r.largest_multiplier()).abs());
            }
            println!(
                "coverage {}, tolerance {:e}: {verdicts} verdicts differ from the defaults'; largest multiplier moduli differ by at most {worst:.1e}",
                h.coverage, h.tolerance
            );
        }
        // The continuation and Hill's method overlapped: the same branch and exponents.
        let (to, o) = best(reps, || {
            follow_from_hopf_with_hill(&mb, &nf, &opts, &h).unwrap()
        });
        assert_eq!(o.branch.points, b.points, "the overlapped branch differs");
        let same = o
            .floquet
            .iter()
            .zip(&fnn)
            .all(|(a, c)| a.as_ref().unwrap().exponents == c.as_ref().unwrap().exponents);
        assert!(same, "the overlapped exponents differ from hill_along's");
        let (hmin, hmax) = b.points.iter().fold((usize::MAX, 0), |(lo, hi), p| {
            (lo.min(p.harmonics), hi.max(p.harmonics))
        });
        println!(
            "| {max_step} | {} | {hmin}-{hmax} | {tc:.2} | {t1:.2} | {tn:.2} | {:.0} | {to:.2} |",
            b.points.len(),
            1e3 * tn / b.points.len() as f64
        );
    }
}
