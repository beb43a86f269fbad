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
//! each torus' Lyapunov exponents), and prints each torus' verdict. Options: `spp=N`,
//! `periods=N`, `transient=N` (the exponents' fewest RK4 steps per fast period, counted and
//! dropped fast periods; default 32, 200, 20), and `compare=1`: each torus' exponents also by
//! the standard method with the reference's controls (twice the steps and four times the
//! record: 64 steps per period, 800 periods after 80) and by the transverse method
//! ([`squeal_chbm::torus_stability::torus_transverse`]; `carry=0|1`, `ttransient=N`,
//! `max=N`, `min=N`, `margin=X`, `vectors=N` its controls), the tangent defect of the torus,
//! and the differences (`noref=1`: the standard method's own record stands in for the
//! reference). `dump=PATH` writes every number of the diagram in full (module docs of `dump`).

#[path = "../tests/pipeline/common/mod.rs"]
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
    let mut plan = TorusPlan::default();
    if let Some(lo) = plan.lyapunov.as_mut() {
        let num = |name: &str, d: usize| arg(name).map_or(d, |s| s.parse().unwrap());
        lo.steps_per_period = num("spp", lo.steps_per_period);
        lo.periods = num("periods", lo.periods);
        lo.transient = num("transient", lo.transient);
    }
    let t0 = Instant::now();
    let a = branch::analyse(m, st, &opts, &Hill::default(), &[], &quiet)
        .unwrap()
        .unwrap();
    let t_branch = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let log = |s: &str| eprintln!("{s}");
    let tori = branch_torus::follow(m, st, &a, &opts, &plan, &log);
    let t_tori = t1.elapsed().as_secs_f64();
    println!(
        "{level} brake as squeal branch: branch with Hill {t_branch:.2} s, {} torus branches with Lyapunov exponents {t_tori:.2} s, whole {:.2} s",
        tori.len(),
        t_branch + t_tori
    );
    println!(
        "| NS (mu0) | mu/mu0 | f1 (Hz) | f2 (Hz) | swing min..max (um) | exponents (1/s) | largest across +- error (1/s) | RK4 steps | stability |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
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
                    format!("{} | {}", s.steps, s.stability()),
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
    if let Some(path) = arg("dump") {
        std::fs::write(&path, dump(&a, &tori)).unwrap();
        eprintln!("every number of the diagram written to {path}");
    }
    if arg("compare").is_some() {
        compare(m, st, a.mu0(), &tori);
    }
}

/// Every number of the diagram (cycles, Hill's exponents, folds, bifurcations, tori, their
/// exponents) in Rust's shortest round-trip form: two dumps are the same text exactly when the
/// numbers are the same bits (`dump=PATH`; compare two runs with `cmp`).
fn dump(
    a: &squeal_pipeline::branch::BranchAnalysis,
    tori: &[squeal_pipeline::branch_torus::TorusRun],
) -> String {
    use std::fmt::Write as _;
    let mut out = String::new();
    let v = |x: &[f64]| {
        x.iter()
            .map(|x| format!("{x:e}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    for (p, f) in a.branch.points.iter().zip(&a.floquet) {
        let _ = writeln!(
            out,
            "cycle mu {:e} omega {:e} h {} it {} res {:e} coeffs {}",
            p.parameter,
            p.omega,
            p.harmonics,
            p.iterations,
            p.residual,
            v(&p.nl_coeffs)
        );
        if let Ok(f) = f {
            for e in &f.exponents {
                let _ = writeln!(out, "  hill {:e} {:e}", e.sigma.re, e.sigma.im);
            }
        }
    }
    for f in &a.branch.folds {
        let _ = writeln!(out, "fold mu {:e}", f.parameter);
    }
    for b in &a.bifurcations {
        let _ = writeln!(
            out,
            "bifurcation {} after {} mu {:e} sigma {:e} {:e}",
            b.kind, b.after_point, b.parameter, b.exponent.sigma.re, b.exponent.sigma.im
        );
    }
    for run in tori {
        let _ = writeln!(out, "torus branch from {:e}", run.ns.parameter);
        if let Err(e) = &run.result {
            let _ = writeln!(out, "  failed: {e}");
        }
        for (p, s) in run.points() {
            let _ = writeln!(
                out,
                "torus mu {:e} omega {} it {} res {:e} coeffs {}",
                p.mu,
                v(&p.omega),
                p.iterations,
                p.residual,
                v(&p.coeffs)
            );
            for c in &p.pairs {
                let e = c.envelope;
                let _ = writeln!(
                    out,
                    "  pair {}",
                    v(&[e.min, e.max, e.swing_min, e.swing_max])
                );
            }
            match s {
                Ok(s) => {
                    let _ = writeln!(
                        out,
                        "  exponents {} second half {} steps {} verdict {}",
                        v(&s.exponents),
                        v(&s.second_half),
                        s.steps,
                        s.stability()
                    );
                }
                Err(e) => {
                    let _ = writeln!(out, "  exponents failed: {e}");
                }
            }
        }
    }
    out
}

/// Each torus' exponents by the standard method, today's controls and the reference's, against
/// the transverse exponents (module docs).
fn compare(
    m: &squeal_pipeline::model::Model,
    st: &squeal_brake::analysis::LinearStability,
    mu0: f64,
    tori: &[squeal_pipeline::branch_torus::TorusRun],
) {
    use squeal_chbm::torus_stability::torus_lyapunov;
    use squeal_hbm::torus::lyapunov::LyapunovOptions;
    let mb = ModalBrake::new(&m.brake, &st.reference, mu0);
    use squeal_hbm::torus::transverse::TransverseOptions;
    let mut topts = TransverseOptions::default();
    {
        let num = |name: &str, d: usize| arg(name).map_or(d, |s| s.parse().unwrap());
        topts.max_periods = num("max", topts.max_periods);
        topts.exponents = num("vectors", topts.exponents);
        topts.transient = num("ttransient", topts.transient);
        topts.min_periods = num("min", topts.min_periods);
        topts.margin = arg("margin").map_or(topts.margin, |s| s.parse().unwrap());
        if let Some(c) = arg("carry") {
            topts.carry_tangents = c == "1";
        }
    }
    let reference = LyapunovOptions {
        exponents: 4,
        periods: 800,
        transient: 80,
        steps_per_period: 64,
        max_rate: None,
    };
    println!(
        "| mu/mu0 | transverse method: largest +- error | standard (4 exponents, 200 periods) | reference (64 steps/period, 800 periods) | new - reference | today - reference | verdicts new / today / reference |"
    );
    println!("|---|---|---|---|---|---|---|");
    let (mut worst, mut agree, mut n, mut t_today, mut t_ref) = (0.0f64, 0, 0, 0.0, 0.0);
    for run in tori {
        let Ok(b) = &run.result else { continue };
        for (p, s) in run.points() {
            let Ok(td) = s else { continue };
            let s = squeal_chbm::torus_stability::torus_transverse(
                &mb,
                &b.basis,
                Some(b.grid),
                p,
                &topts,
            )
            .unwrap();
            let mut flow =
                squeal_chbm::torus_stability::BrakeTangentFlow::new(&mb, &b.basis, Some(b.grid), p)
                    .unwrap();
            let defect: Vec<String> = [[0.0, 0.0], [1.0, 2.0], [2.5, 4.0]]
                .iter()
                .map(|&th| {
                    let d = squeal_hbm::torus::transverse::tangent_defect(&mut flow, p.omega, th)
                        .unwrap();
                    format!("{:.1}/{:.1}", d[0], d[1])
                })
                .collect();
            eprintln!(
                "{:.5} mu0: tangent defect |dT/dt - J T|/|T| (1/s) at 3 angles: {}",
                p.mu / mu0,
                defect.join(", ")
            );
            t_today += run.stability_time.as_secs_f64() / run.stability.len().max(1) as f64;
            let t = Instant::now();
            let rf = if arg("noref").is_some() {
                td.clone()
            } else {
                torus_lyapunov(&mb, &b.basis, p, &reference).unwrap()
            };
            t_ref += t.elapsed().as_secs_f64();
            let d = s.transverse() - rf.transverse();
            worst = worst.max(d.abs() / (s.uncertainty() + rf.uncertainty()));
            n += 1;
            if s.stability() == rf.stability() {
                agree += 1;
            }
            println!(
                "| {:.5} | {:.2} +- {:.2} ({} periods) | {:.2} +- {:.2} | {:.2} +- {:.2} (exponents {}) | {:.2} | {:.2} | {} / {} / {} |",
                p.mu / mu0,
                s.transverse(),
                s.uncertainty(),
                s.periods,
                td.transverse(),
                td.uncertainty(),
                rf.transverse(),
                rf.uncertainty(),
                rf.exponents
                    .iter()
                    .map(|x| format!("{x:.2}"))
                    .collect::<Vec<_>>()
                    .join(", "),
                d,
                td.transverse() - rf.transverse(),
                s.stability(),
                td.stability(),
                rf.stability()
            );
        }
    }
    println!(
        "{n} tori: verdicts new = reference on {agree}; largest |new - reference| / (error new + error reference) = {worst:.3}; today's method {t_today:.2} s, reference {t_ref:.2} s"
    );
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
