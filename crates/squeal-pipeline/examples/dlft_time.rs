//! Exact stick–slip (DLFT) on the coarse bundled brake at 3 km/h against time integration of
//! the regularized law at shrinking regularization velocities (issue 24, items 4–5;
//! docs/stick_slip.md, "DLFT against time integration").
//!
//! `cargo run --release -p squeal-pipeline --example dlft_time -- [ratios] [fractions] [rtol]
//! [record_cycles] [start] [starts]` (defaults `1.0452` (μ/μ0, comma separated), `0.05,0.025,0.0125,
//! 0.00625` (v_reg as fractions of the slowest pair's disc speed), `1e-7`, `40`, `dlft`, none);
//! `starts` first solves DLFT as squeal does, from the CHBM cycle and then the regularized
//! cycles walked down in `v_reg` (`squeal_chbm::stick_dlft_starts`).
//!
//! At each μ: the CHBM cycle (permanent sliding, as `squeal chbm --mu-ratio` solves it), the
//! DLFT cycle from it (24 harmonics, `squeal_pipeline::cycle_stick`), then for each `v_reg`:
//! the regularized balance's cycle (24 harmonics, each from the previous `v_reg`'s) and the
//! BDF integration of the full brake with that law ([`squeal_chbm::stick_orbit`]) started from
//! the DLFT cycle (`start = dlft`) or from the regularized cycle (`start = reg`), to its steady
//! cycle and a record of `record_cycles` periods. When the integration is steady its cycle
//! also starts a DLFT solve. Everything is printed; nothing is written.
//!
//! `starts` = `walk`: instead, DLFT at the first ratio from its CHBM cycle, then continued in μ
//! through the other ratios (`squeal_chbm::stick_dlft_walk`), each from the last two converged
//! cycles; one line per ratio (no time integration). With `DLFT_CONTINUITY` set in the
//! environment it first prints the DLFT balance's residual at the first cycle's coefficients at
//! μ (1 + dμ) for dμ = 0, 1e-5, 1e-4 (before any iteration and after 5): whether the balance is
//! continuous in μ.

use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::bifurcation::cycle_of;
use squeal_chbm::branch::BranchPoint;
use squeal_chbm::floquet::{HillOptions, hill};
use squeal_chbm::stick_branch::{StickOptions, sticking_brake, surface_speeds};
use squeal_chbm::stick_dlft::{DlftOptions, dlft_cycle, regularized_cycle};
use squeal_chbm::stick_dlft_starts::{START_FRACTIONS, dlft_from_starts};
use squeal_chbm::stick_orbit::{OrbitOptions, integrate_orbit, steady_point};
use squeal_chbm::{ChbmOptions, RESTART_AMPLITUDES};
use squeal_hbm::{HarmonicLayout, PhaseCondition};
use squeal_pipeline::Pipeline;
use squeal_pipeline::model::quiet;
use squeal_scene::{Scene, StickSlipSetting};
use std::path::PathBuf;
use std::time::Instant;

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// `meshes/brake.toml` on its coarse meshes at `kmh` on a 0.3 m wheel.
fn coarse_scene(kmh: f64) -> Res<Scene> {
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
        .replacen(
            "# vehicle_speed_kmh = 5.0",
            &format!("vehicle_speed_kmh = {kmh:?}"),
            1,
        )
        .replacen("# rolling_radius = 0.3", "rolling_radius = 0.3", 1);
    Ok(Scene::parse(&path, text)?)
}

/// `(df/f, dp2p/p2p)` of `q` against `r` on `pair`.
fn diff(q: &BranchPoint, r: &BranchPoint, pair: usize) -> (f64, f64) {
    (
        q.omega / r.omega - 1.0,
        q.pairs[pair].peak_to_peak() / r.pairs[pair].peak_to_peak() - 1.0,
    )
}

/// Pairs with a non-zero fraction, as `pair:percent`.
fn fractions(v: &[f64]) -> String {
    let s: Vec<String> = v
        .iter()
        .enumerate()
        .filter(|(_, f)| **f > 0.0)
        .map(|(i, f)| format!("{i}:{:.2}%", 100.0 * f))
        .collect();
    if s.is_empty() {
        "none".into()
    } else {
        s.join(" ")
    }
}

fn main() -> Res<()> {
    faer::set_global_parallelism(faer::Par::Seq);
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, d: &str| args.get(i).cloned().unwrap_or_else(|| d.to_string());
    let list = |s: String| -> Res<Vec<f64>> {
        s.split(',')
            .map(|x| x.trim().parse::<f64>().map_err(Into::into))
            .collect()
    };
    let ratios = list(arg(0, "1.0452"))?;
    let fracs = list(arg(1, "0.05,0.025,0.0125,0.00625"))?;
    let rtol: f64 = arg(2, "1e-7").parse()?;
    let record: usize = arg(3, "40").parse()?;
    let from_dlft = arg(4, "dlft") == "dlft";
    let out = std::env::temp_dir().join("squeal-dlft-time");
    let p = Pipeline::new(coarse_scene(3.0)?, out, &quiet)?;
    let (m, st) = (p.model()?, p.stability()?);
    let mu0 = p.mu0()?;
    let samples = StickOptions::default().samples_for(24);
    if arg(5, "") == "walk" {
        return walk(m, st, mu0, &ratios);
    }
    for r in ratios {
        let mu = r * mu0;
        let t = Instant::now();
        let (start, mb) = squeal_pipeline::chbm::start(m, st, mu, None)?;
        let (sol, _) = squeal_pipeline::chbm::solve_with_restarts(
            &mb,
            &start,
            &ChbmOptions::default(),
            &RESTART_AMPLITUDES,
            &quiet,
        )?;
        let law = StickSlipSetting::Dlft {
            epsilon_factor: 1.0,
        };
        let c = squeal_pipeline::cycle_stick::recompute(m, st, law, mu, &sol)?
            .ok_or("the margin is not below 1")?;
        let d = &c.cycle;
        let (pair, _) = d.loudest();
        println!(
            "mu/mu0 {r}: sliding f {:.5} Hz, margin {:.4}; DLFT f {:.5} Hz, p2p {:.4} um, residual {:.1e}, converged {}, stick {} ({:.1} s)",
            c.sliding.frequency_hz(),
            c.margin.min,
            d.frequency_hz(),
            d.pairs[pair].peak_to_peak() * 1e6,
            d.residual,
            c.converged,
            fractions(c.stick_fractions.as_deref().unwrap_or(&[])),
            t.elapsed().as_secs_f64()
        );
        let mb = ModalBrake::new(&m.brake, &st.reference, mu);
        let v_min = surface_speeds(&mb)?
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        let layout = HarmonicLayout::new(mb.nl(), d.harmonics)?;
        let PhaseCondition::FirstSineZero { dof } =
            PhaseCondition::strongest_dof(&layout, &d.nl_coeffs)?;
        if arg(5, "") == "starts" {
            // DLFT from the CHBM cycle and, when that stops short, from the regularized cycles
            // walked down in v_reg (`squeal_chbm::stick_dlft_starts`), as squeal does.
            let mut o = DlftOptions::default();
            o.harmonics = Some(24);
            let t = Instant::now();
            let s = dlft_from_starts(&mb, mu, &c.sliding, dof, &o, &START_FRACTIONS)?;
            let e = &s.cycle;
            println!(
                "  DLFT from starts: f {:.5} Hz, p2p {:.4} um, residual {:.1e}, converged {}, stick {}, reversed {}, tried {:?} ({:.1} s) {}",
                e.point.frequency_hz(),
                e.point.pairs[pair].peak_to_peak() * 1e6,
                e.point.residual,
                e.converged,
                fractions(&e.stick_fractions),
                fractions(&e.reversed_fractions),
                s.tried,
                t.elapsed().as_secs_f64(),
                s.reason()
            );
        }
        // The exact cycle: DLFT from the CHBM cycle, or (when that stops short) from the first
        // steady integrated cycle.
        let mut exact = c.converged.then(|| c.cycle.clone());
        let mut rows = Vec::new();
        let mut guess = c.sliding.clone();
        for &f in &fracs {
            let v_reg = f * v_min;
            let mut o = DlftOptions::default();
            o.samples = Some(samples);
            o.harmonics = Some(24);
            let t = Instant::now();
            let (q, ok) = regularized_cycle(&mb, mu, v_reg, &guess, dof, &o)?;
            println!(
                "  V*{f}: regularized HB f {:.5} Hz, converged {ok} ({:.1} s)",
                q.frequency_hz(),
                t.elapsed().as_secs_f64()
            );
            let smb = sticking_brake(&mb, v_reg)?;
            // Hill's exponents of the regularized cycle (the branch's stability method).
            let mut mbp = smb.clone();
            mbp.mu = mu;
            let t = Instant::now();
            let h = hill(
                &mbp,
                &cycle_of(&smb, &q, Some(samples))?,
                &HillOptions::default(),
            )?;
            println!(
                "    Hill: leading exponent {:.3e} 1/s ({}), trivial error {:.1e}, coverage {:.0} ({:.1} s)",
                h.leading().map_or(f64::NAN, |e| e.sigma.re),
                h.stability(),
                h.trivial_error,
                h.coverage,
                t.elapsed().as_secs_f64()
            );
            let mut oo = OrbitOptions::default();
            oo.ti.rtol = rtol;
            oo.ti.max_cycles = 800.0;
            oo.record_cycles = record;
            let from = match (&exact, from_dlft) {
                (Some(e), true) => e,
                _ => &q,
            };
            let t = Instant::now();
            let orbit = integrate_orbit(&smb, v_reg, from, Some(samples), &oo)?;
            let ch = &orbit.check;
            let reg_period = 2.0 * std::f64::consts::PI / q.omega;
            match (ch.ti_period, ch.ti_closure) {
                (Some(tp), Some(tc)) => println!(
                    "    BDF steady after {} cycles: period {:+.2e}, p2p {:+.2e} vs regularized HB; drift {:.1e}; {} steps",
                    ch.run.steady.as_ref().map_or(0, |s| s.cycles),
                    tp / reg_period - 1.0,
                    tc / q.pairs[pair].peak_to_peak() - 1.0,
                    ch.run.steady.as_ref().map_or(0.0, |s| s.drift),
                    ch.run.stats.steps,
                ),
                _ => println!(
                    "    BDF NOT steady: {} ({} cycles, {} steps)",
                    ch.run
                        .failure
                        .as_ref()
                        .map_or("no failure".to_string(), |e| e.to_string()),
                    ch.run.history.len(),
                    ch.run.stats.steps
                ),
            }
            match &orbit.record {
                Ok(rec) => println!(
                    "    record {} cycles: period {:.10e} s (spread {:.1e}), p2p {:.4} um (spread {:.1e}); stuck {}; reversed {}; open {}; {} steps ({:.1} s)",
                    rec.periods.len(),
                    rec.mean_period(),
                    rec.period_spread(),
                    rec.mean_closure() * 1e6,
                    rec.closure_spread(),
                    fractions(&rec.stuck),
                    fractions(&rec.reversed),
                    fractions(&rec.open),
                    orbit.record_steps,
                    t.elapsed().as_secs_f64()
                ),
                Err(e) => println!("    record failed: {e}"),
            }
            if let Ok(rec) = &orbit.record {
                for (k, runs) in rec.patterns.iter().enumerate() {
                    if runs.iter().any(|r| r.0 != 'f') {
                        let s: Vec<String> = runs
                            .iter()
                            .map(|(c, f)| format!("{c} {:.2}%", 100.0 * f))
                            .collect();
                        println!("      pair {k} over the last period: {}", s.join(", "));
                    }
                }
            }
            if exact.is_none()
                && let Some(g) = steady_point(&mb, mu, ch, dof)?
            {
                let mut o = DlftOptions::default();
                o.harmonics = Some(24);
                let t = Instant::now();
                let e = dlft_cycle(&mb, mu, &g, dof, &o)?;
                println!(
                    "    DLFT from the integrated cycle: f {:.5} Hz, p2p {:.4} um, residual {:.1e}, converged {}, stick {}, reversed {} ({:.1} s)",
                    e.point.frequency_hz(),
                    e.point.pairs[pair].peak_to_peak() * 1e6,
                    e.point.residual,
                    e.converged,
                    fractions(&e.stick_fractions),
                    fractions(&e.reversed_fractions),
                    t.elapsed().as_secs_f64()
                );
                if e.converged {
                    exact = Some(e.point);
                }
            }
            rows.push((f, q.clone(), orbit));
            guess = q;
        }
        let Some(d) = exact else {
            println!("  no converged DLFT cycle at mu/mu0 {r}");
            continue;
        };
        let hb_period = 2.0 * std::f64::consts::PI / d.omega;
        let p2p = d.pairs[pair].peak_to_peak();
        println!(
            "  against DLFT (f {:.5} Hz, period {:.10e} s, p2p {:.4} um):",
            d.frequency_hz(),
            hb_period,
            p2p * 1e6
        );
        for (f, q, orbit) in &rows {
            let (df, dp) = diff(q, &d, pair);
            let (tp, tc) = match &orbit.record {
                Ok(rec) => (
                    rec.mean_period() / hb_period - 1.0,
                    rec.mean_closure() / p2p - 1.0,
                ),
                Err(_) => (f64::NAN, f64::NAN),
            };
            println!(
                "  | V/{:.0} | HB {df:+.2e} f, {dp:+.2e} p2p | BDF {:+.2e} f, {tc:+.2e} p2p |",
                1.0 / f,
                -tp / (1.0 + tp)
            );
        }
    }
    Ok(())
}

/// DLFT at `ratios[0]` μ0 from its CHBM cycle, then walked in μ through the other ratios.
fn walk(
    m: &squeal_pipeline::model::Model,
    st: &squeal_brake::analysis::LinearStability,
    mu0: f64,
    ratios: &[f64],
) -> Res<()> {
    use squeal_chbm::stick_dlft_walk::{WalkOptions, dlft_walk};
    let t0 = Instant::now();
    let mu = ratios[0] * mu0;
    let (start, mb) = squeal_pipeline::chbm::start(m, st, mu, None)?;
    let (sol, _) = squeal_pipeline::chbm::solve_with_restarts(
        &mb,
        &start,
        &ChbmOptions::default(),
        &RESTART_AMPLITUDES,
        &quiet,
    )?;
    let law = StickSlipSetting::Dlft {
        epsilon_factor: 1.0,
    };
    let c = squeal_pipeline::cycle_stick::recompute(m, st, law, mu, &sol)?
        .ok_or("the margin is not below 1")?;
    if !c.converged {
        return Err("DLFT did not converge at the first ratio".into());
    }
    let mut first = c.cycle.clone();
    first.parameter = mu;
    let (pair, _) = first.loudest();
    let mb = ModalBrake::new(&m.brake, &st.reference, mu0);
    let layout = HarmonicLayout::new(mb.nl(), first.harmonics)?;
    let PhaseCondition::FirstSineZero { dof } =
        PhaseCondition::strongest_dof(&layout, &first.nl_coeffs)?;
    println!(
        "mu/mu0 {}: DLFT f {:.5} Hz, p2p {:.4} um, residual {:.1e} ({:.1} s with the CHBM cycle)",
        ratios[0],
        first.frequency_hz(),
        first.pairs[pair].peak_to_peak() * 1e6,
        first.residual,
        t0.elapsed().as_secs_f64()
    );
    let mut o = DlftOptions::default();
    o.harmonics = Some(24);
    if std::env::var("DLFT_CONTINUITY").is_ok() {
        for (k, dm) in [(0usize, 0.0), (0, 1e-5), (0, 1e-4), (5, 0.0), (5, 1e-4)] {
            let mut oo = o.clone();
            oo.lm.max_iterations = k;
            let d = squeal_chbm::stick_dlft::dlft_cycle(&mb, mu * (1.0 + dm), &first, dof, &oo)?;
            println!(
                "debug iterations {k} dmu {dm}: residual {:.2e}, converged {}, f {:.6}",
                d.point.residual,
                d.converged,
                d.point.frequency_hz()
            );
        }
    }
    let mut prev = vec![first];
    for &r in &ratios[1..] {
        let t = Instant::now();
        let w = dlft_walk(&mb, &prev, r * mu0, dof, &o, &WalkOptions::default())?;
        let tried: Vec<String> = w
            .solves
            .iter()
            .map(|(m, res, ok)| format!("{:.5}{}{res:.0e}", m / mu0, if *ok { ":" } else { "!" }))
            .collect();
        let Some(e) = &w.cycle else {
            println!("mu/mu0 {r}: no step converged; solves {}", tried.join(" "));
            break;
        };
        println!(
            "mu/mu0 {r}: {} at {:.5} mu0, f {:.5} Hz, p2p {:.4} um, residual {:.1e}, stick {}, reversed {}, margin {:.3}, {} solves ({:.1} s): {}",
            if w.reached { "reached" } else { "STOPPED" },
            e.point.parameter / mu0,
            e.point.frequency_hz(),
            e.point.pairs[pair].peak_to_peak() * 1e6,
            e.point.residual,
            fractions(&e.stick_fractions),
            fractions(&e.reversed_fractions),
            e.margin.min,
            w.solves.len(),
            t.elapsed().as_secs_f64(),
            tried.join(" ")
        );
        if !w.reached {
            break;
        }
        let mut p = e.point.clone();
        p.parameter = r * mu0;
        prev.push(p);
        if prev.len() > 2 {
            prev.remove(0);
        }
    }
    println!("total {:.1} s", t0.elapsed().as_secs_f64());
    Ok(())
}
