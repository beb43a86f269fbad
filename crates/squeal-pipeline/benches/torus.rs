//! The bundled brake's diagram past the Neimark–Sacker point (issue 24, item 1): the branch of
//! limit cycles with Hill's multipliers from the Hopf point to 1.3 μ0, its Neimark–Sacker
//! points, and the torus branch from the first one, timed. A bench binary printing a table, not
//! a timed test.
//!
//! `cargo bench -p squeal-pipeline --bench torus` (options after `--`: `level=coarse` or
//! `medium` (default), `h2=N` (the basis' order in the second angle, default 2), `h1=N` (in
//! the first, default the cycle's harmonics), `points=N` (tori at the most, default 30),
//! `step=s` (the torus continuation's largest step, default 0.1)).
//!
//! With `pipeline=1` it times instead what `squeal branch` computes (without the sound
//! levels and files): `branch::analyse` (the branch with Hill's multipliers) and
//! `branch_torus::follow` with the default plan (every Neimark–Sacker point's torus branch,
//! each torus' Lyapunov exponents), and prints each torus' verdict.

#[path = "../tests/common/mod.rs"]
mod common;

use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::bifurcation::{BifurcationKind, bifurcations, follow_from_hopf_with_hill};
use squeal_chbm::branch::BranchOptions;
use squeal_chbm::floquet::HillOptions;
use squeal_chbm::torus::{TorusOptions, follow_torus};
use squeal_hbm::torus::Truncation;
use squeal_pipeline::{Pipeline, model::quiet, stability};
use std::time::Instant;

fn arg(name: &str) -> Option<String> {
    std::env::args().find_map(|a| a.strip_prefix(&format!("{name}=")).map(String::from))
}

/// What `squeal branch` computes, timed (module docs).
fn as_squeal_branch(p: &Pipeline, level: &str) {
    use squeal_pipeline::branch::{self, HillOptions as Hill};
    use squeal_pipeline::branch_torus::{self, TorusPlan};
    let (m, st) = (p.model().unwrap(), p.stability().unwrap());
    let opts = BranchOptions::default();
    let t0 = Instant::now();
    let a = branch::analyse(m, st, &opts, &Hill::default(), &[], &quiet)
        .unwrap()
        .unwrap();
    let t_branch = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let log = |s: &str| eprintln!("{s}");
    let tori = branch_torus::follow(m, st, &a, &opts, &TorusPlan::default(), &log);
    let t_tori = t1.elapsed().as_secs_f64();
    println!(
        "{level} brake as squeal branch: branch with Hill {t_branch:.2} s, {} torus branches with Lyapunov exponents {t_tori:.2} s, whole {:.2} s",
        tori.len(),
        t_branch + t_tori
    );
    println!(
        "| NS (mu0) | mu/mu0 | f1 (Hz) | f2 (Hz) | swing min..max (um) | exponents (1/s) | transverse +- error (1/s) | stability |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for run in &tori {
        match &run.result {
            Err(e) => println!("| {:.5} | failed: {e} |||||||", run.ns.parameter / a.mu0()),
            Ok(b) => eprintln!(
                "torus branch {:.2} s, exponents {:.2} s",
                b.time.as_secs_f64(),
                run.stability_time.as_secs_f64()
            ),
        }
        for (pt, s) in run.points() {
            let (_, e) = pt.loudest();
            let f = pt.frequencies_hz();
            let (ex, tr, v) = match s {
                Ok(s) => (
                    s.exponents
                        .iter()
                        .map(|x| format!("{x:.2}"))
                        .collect::<Vec<_>>()
                        .join(", "),
                    format!("{:.2} +- {:.2}", s.transverse(), s.uncertainty()),
                    s.stability().to_string(),
                ),
                Err(e) => (String::new(), String::new(), e.clone()),
            };
            println!(
                "| {:.5} | {:.5} | {:.3} | {:.3} | {:.3}..{:.3} | {ex} | {tr} | {v} |",
                run.ns.parameter / a.mu0(),
                pt.mu / a.mu0(),
                f[0],
                f[1],
                1e6 * e.swing_min,
                1e6 * e.swing_max
            );
        }
    }
}

fn main() {
    faer::set_global_parallelism(faer::Par::Seq);
    let level = arg("level").unwrap_or_else(|| "medium".into());
    let out = std::env::temp_dir().join(format!("squeal-bench-torus-{level}"));
    let p = Pipeline::new(common::bundled_scene(&level), out, &quiet).unwrap();
    let t = Instant::now();
    let (m, st) = (p.model().unwrap(), p.stability().unwrap());
    eprintln!(
        "{level} brake and sweep in {:.1?} (not timed below)",
        t.elapsed()
    );
    if arg("pipeline").is_some() {
        as_squeal_branch(&p, &level);
        return;
    }
    let nf = stability::normal_form(m, st).unwrap().unwrap();
    let mb = ModalBrake::new(&m.brake, &st.reference, nf.mu0);

    let t0 = Instant::now();
    let opts = BranchOptions::default();
    let b = follow_from_hopf_with_hill(&mb, &nf, &opts, &HillOptions::default()).unwrap();
    let t_branch = t0.elapsed().as_secs_f64();
    let bifs = bifurcations(&b.branch, &b.floquet);
    let folds = &b.branch.folds;
    println!(
        "{level} brake: mu0 = {:.6}, {} cycles to {:.4} mu0, {} folds (first at {:.5} mu0), branch with Hill {t_branch:.2} s",
        nf.mu0,
        b.branch.points.len(),
        b.branch
            .points
            .last()
            .map_or(f64::NAN, |p| p.parameter / nf.mu0),
        folds.len(),
        folds.first().map_or(f64::NAN, |f| f.parameter / nf.mu0),
    );
    for bf in &bifs {
        println!(
            "  {} at {:.5} mu0, sigma = {:+.3} {:+.3}i, second frequency {:.2} Hz",
            bf.kind,
            bf.parameter / nf.mu0,
            bf.exponent.sigma.re,
            bf.exponent.sigma.im,
            bf.torus_frequency_hz()
        );
    }
    let Some(ns) = bifs
        .iter()
        .find(|x| x.kind == BifurcationKind::NeimarkSacker)
    else {
        println!("no Neimark-Sacker point on the branch");
        return;
    };
    let mut topts = TorusOptions::default();
    topts.continuation.max_points = arg("points").map_or(30, |s| s.parse().unwrap());
    topts.continuation.max_step = arg("step").map_or(0.1, |s| s.parse().unwrap());
    topts.continuation.parameter_range = (0.5 * nf.mu0, 1.3 * nf.mu0);
    let cycle_h = b.branch.points[ns.after_point].harmonics;
    let h1: usize = arg("h1").map_or(cycle_h, |s| s.parse().unwrap());
    let h2: usize = arg("h2").map_or(2, |s| s.parse().unwrap());
    topts.truncation = Some(Truncation::Box(h1, h2));
    let t1 = Instant::now();
    let tb = follow_torus(&mb, &b.branch, &opts, ns, &topts);
    let t_torus = t1.elapsed().as_secs_f64();
    let tb = match tb {
        Ok(tb) => tb,
        Err(e) => {
            println!("torus branch failed after {t_torus:.2} s: {e}");
            return;
        }
    };
    println!(
        "torus branch: basis Box({h1}, {h2}), {} elements, {} unknowns, grid {}x{}, start null residual {:.2e}, {} points in {t_torus:.2} s ({})",
        tb.basis.n_waves(),
        tb.basis.len(),
        tb.grid[0],
        tb.grid[1],
        tb.null_residual,
        tb.points.len(),
        tb.stop
    );
    println!(
        "| mu/mu0 | f1 (Hz) | f2 (Hz) | pair | swing min (um) | swing max (um) | closure min..max (um) | iterations |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for p in &tb.points {
        let (pair, e) = p.loudest();
        let f = p.frequencies_hz();
        println!(
            "| {:.5} | {:.3} | {:.3} | {pair} | {:.3} | {:.3} | {:.3}..{:.3} | {} |",
            p.mu / nf.mu0,
            f[0],
            f[1],
            1e6 * e.swing_min,
            1e6 * e.swing_max,
            1e6 * e.min,
            1e6 * e.max,
            p.iterations
        );
    }
    println!(
        "whole diagram (branch with Hill, then the torus branch): {:.2} s",
        t_branch + t_torus
    );
}
