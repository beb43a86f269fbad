//! Timing of the DLFT solves on the coarse bundled brake at 3 km/h (docs/stick_slip.md,
//! "The DLFT cycles' cost"; docs/benchmarks.md).
//!
//! `cargo run --release -p squeal-pipeline --example dlft_bench -- [ratios]` (default
//! `1.0452,1.0540`): the CHBM cycle at the first μ/μ0, the DLFT cycle from it (24 harmonics,
//! as `squeal chbm` solves it), then DLFT continued in μ through the other ratios
//! (`squeal_chbm::stick_dlft_walk`). Prints every cycle's frequency and loudest closure to 17
//! digits, its residual, the solves and the time of each part, and a checksum of the
//! coefficients' bits, to compare builds.

use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::branch::BranchPoint;
use squeal_chbm::stick_dlft::{DlftOptions, dlft_cycle};
use squeal_chbm::stick_dlft_walk::{WalkOptions, dlft_walk};
use squeal_chbm::{ChbmOptions, RESTART_AMPLITUDES};
use squeal_hbm::{HarmonicLayout, PhaseCondition};
use squeal_pipeline::Pipeline;
use squeal_pipeline::model::quiet;
use squeal_scene::{Scene, StickSlipSetting};
use std::path::PathBuf;
use std::time::Instant;

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// `meshes/brake.toml` on its coarse meshes at 3 km/h on a 0.3 m wheel.
fn coarse_scene() -> Res<Scene> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes/brake.toml");
    let text: String = std::fs::read_to_string(&path)?
        .lines()
        .map(|l| {
            for part in ["disc", "pad"] {
                if l.starts_with(&format!("{part} = ")) {
                    return format!("{part} = \"{part}_coarse.inp\"\n");
                }
            }
            format!("{l}\n")
        })
        .collect::<String>()
        .replacen("# vehicle_speed_kmh = 5.0", "vehicle_speed_kmh = 3.0", 1)
        .replacen("# rolling_radius = 0.3", "rolling_radius = 0.3", 1);
    Ok(Scene::parse(&path, text)?)
}

/// Stuck samples of each pair (of 1024), from its fraction of the period.
fn samples(f: &[f64]) -> String {
    let v: Vec<String> = f.iter().map(|x| format!("{:.0}", x * 1024.0)).collect();
    v.join(" ")
}

/// Frequency, loudest closure (17 digits), residual and an FNV checksum of the coefficients.
fn line(p: &BranchPoint) -> String {
    let (pair, _) = p.loudest();
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for v in p.nl_coeffs.iter().chain([&p.omega]) {
        h = (h ^ v.to_bits()).wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!(
        "f {:.17e} Hz, p2p {:.17e} m, residual {:.2e}, bits {h:016x}",
        p.frequency_hz(),
        p.pairs[pair].peak_to_peak(),
        p.residual
    )
}

fn main() -> Res<()> {
    faer::set_global_parallelism(faer::Par::Seq);
    let ratios: Vec<f64> = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "1.0452,1.0540".into())
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()?;
    let out = std::env::temp_dir().join("squeal-dlft-bench");
    let t = Instant::now();
    let p = Pipeline::new(coarse_scene()?, out, &quiet)?;
    let (m, st) = (p.model()?, p.stability()?);
    let mu0 = p.mu0()?;
    let mu = ratios[0] * mu0;
    let (start, mb) = squeal_pipeline::chbm::start(m, st, mu, None)?;
    let (sol, _) = squeal_pipeline::chbm::solve_with_restarts(
        &mb,
        &start,
        &ChbmOptions::default(),
        &RESTART_AMPLITUDES,
        &quiet,
    )?;
    println!(
        "model, mu0 and CHBM cycle: {:.2} s",
        t.elapsed().as_secs_f64()
    );
    let law = StickSlipSetting::Dlft {
        epsilon_factor: 1.0,
    };
    let t = Instant::now();
    let c = squeal_pipeline::cycle_stick::recompute(m, st, law, mu, &sol)?
        .ok_or("the margin is not below 1")?;
    let mut first = c.cycle.clone();
    println!(
        "DLFT at {} mu0 from the CHBM cycle: {} ({} iterations, {:.2} s)",
        ratios[0],
        line(&first),
        first.iterations,
        t.elapsed().as_secs_f64()
    );
    if let Some(f) = &c.stick_fractions {
        println!("  stuck samples per pair: {}", samples(f));
    }
    if !c.reason.is_empty() {
        println!("  direct starts: {}", c.reason);
    }
    if let Some(w) = &c.walk {
        println!("  walked from below: {}", w.text(mu0, "mu0"));
    }
    if !c.converged {
        return Err("DLFT did not converge at the first ratio".into());
    }
    first.parameter = mu;
    let mb = ModalBrake::new(&m.brake, &st.reference, mu0);
    let layout = HarmonicLayout::new(mb.nl(), first.harmonics)?;
    let PhaseCondition::FirstSineZero { dof } =
        PhaseCondition::strongest_dof(&layout, &first.nl_coeffs)?;
    let mut o = DlftOptions::default();
    o.harmonics = Some(24);
    if std::env::var("DLFT_BENCH_DAMPED").is_ok() {
        // The walk's and re-solves' Levenberg-Marquardt without Gauss-Newton steps first (the
        // direct start keeps `squeal chbm`'s options).
        o.lm.newton_damping = 0.0;
    }
    if std::env::var("DLFT_BENCH_RESOLVE").is_ok() {
        // The direct cycle solved again from itself (docs/stick_slip.md: the two 1.0540 mu0
        // cycles).
        let n = mb.nl();
        println!(
            "  phase row U1s[{dof}] = {:.3e} m (U1c {:.3e} m)",
            first.nl_coeffs[2 * n + dof],
            first.nl_coeffs[n + dof]
        );
        let again = dlft_cycle(&mb, mu, &first, dof, &o)?;
        println!(
            "  solved again from itself: {} ({} iterations, phase error {:.2e} rad), stuck samples {}",
            line(&again.point),
            again.point.iterations,
            again.phase_error,
            samples(&again.stick_fractions)
        );
    }
    let mut prev = vec![first];
    for &r in &ratios[1..] {
        let t = Instant::now();
        let w = dlft_walk(&mb, &prev, r * mu0, dof, &o, &WalkOptions::default())?;
        let e = w.cycle.as_ref().ok_or("no walk step converged")?;
        println!(
            "walk to {r} mu0 ({}, {} solves): {} ({:.2} s)",
            if w.reached { "reached" } else { "STOPPED" },
            w.solves.len(),
            line(&e.point),
            t.elapsed().as_secs_f64()
        );
        println!("  stuck samples per pair: {}", samples(&e.stick_fractions));
        println!("  phase error {:.2e} rad", e.phase_error);
        let solves: Vec<String> = w
            .solves
            .iter()
            .map(|(m, r, ok)| format!("{:.5} {r:.1e}{}", m / mu0, if *ok { "" } else { " short" }))
            .collect();
        println!("  solves (mu/mu0, residual): {}", solves.join(", "));
        let mut q = e.point.clone();
        q.parameter = r * mu0;
        if std::env::var("DLFT_BENCH_RESOLVE").is_ok() {
            // The walked cycle solved again from itself: does Levenberg-Marquardt stay put?
            let n = mb.nl();
            println!(
                "  phase row U1s[{dof}] = {:.3e} m (U1c {:.3e} m)",
                q.nl_coeffs[2 * n + dof],
                q.nl_coeffs[n + dof]
            );
            let again = dlft_cycle(&mb, r * mu0, &q, dof, &o)?;
            println!(
                "  solved again from itself: {} ({} iterations, phase error {:.2e} rad), stuck samples {}",
                line(&again.point),
                again.point.iterations,
                again.phase_error,
                samples(&again.stick_fractions)
            );
        }
        prev = vec![q];
    }
    Ok(())
}
