//! The bundled brake's diagram past the Neimark–Sacker point (issue 24, item 1): the branch of
//! limit cycles with Hill's multipliers from the Hopf point to 1.3 μ0, its Neimark–Sacker
//! points, and the torus branch from the first one, timed. A bench binary printing a table, not
//! a timed test.
//!
//! `cargo bench -p squeal-pipeline --bench torus` (options after `--`: `level=coarse` or
//! `medium` (default), `h2=N` (the basis' order in the second angle, default 2), `h1=N` (in
//! the first, default the cycle's harmonics), `points=N` (tori at the most, default 30),
//! `step=s` (the torus continuation's largest step, default 0.1)).

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
