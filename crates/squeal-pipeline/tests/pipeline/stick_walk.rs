//! Exact stick–slip (DLFT) past 1.05 μ0 on the coarse bundled brake at 3 km/h (issue 24, item
//! 4; docs/stick_slip.md, "Past 1.05 μ0"): with the projection onto the friction cone as a
//! clamp, DLFT continued in μ from the converged 1.0452 μ0 cycle reaches the 1.0540 and 1.0649
//! μ0 cycles (which the relay reached only from integrated cycles within about 1e-4), and the
//! time integration of the regularized law, started from each, settles on a periodic orbit
//! within the regularization's own error of them; and the stability of the 1.0452 and 1.0540
//! μ0 cycles by the Floquet analysis of the non-smooth law (`squeal_chbm::stick_floquet`:
//! monodromy of the Filippov system's variational equations with saltation matrices at the
//! stick/slip switches) against what was known before it: the limit of the regularized law's
//! Hill exponents as `v_reg → 0` and the BDF runs that settle on these cycles (stable). The
//! Floquet test was `stick_floquet.rs`, which computed the same CHBM cycle, DLFT cycle and
//! walk to 1.0540 μ0 again.
//!
//! Two more tests on the same brake, run alongside (the test harness runs a binary's tests on
//! the machine's cores; as binaries of their own they ran one after the other, each building
//! the brake): the regularized law's integrated orbits approach the DLFT cycle at 1.0452 μ0
//! (was `stick_time.rs`), and `squeal chbm`'s single DLFT cycle at 1.0649 μ0 walked in μ from
//! below to the cycle of the walk above (was `stick_chbm_walk.rs`).

use super::common;

use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::floquet::CycleStability;
use squeal_chbm::stick_branch::{StickOptions, sticking_brake, surface_speeds};
use squeal_chbm::stick_dlft::{DlftCycle, DlftOptions, dlft_cycle, regularized_cycle};
use squeal_chbm::stick_dlft_walk::{WalkOptions, dlft_walk};
use squeal_chbm::stick_floquet::StickSlipFloquetOptions;
use squeal_chbm::stick_floquet::brake::dlft_floquet;
use squeal_chbm::stick_orbit::{OrbitOptions, integrate_orbit, steady_point};
use squeal_hbm::{HarmonicLayout, PhaseCondition};
use squeal_pipeline::{Pipeline, model::quiet};
use squeal_scene::StickSlipSetting;

#[test]
fn dlft_continued_past_1_05_mu0_matches_the_time_integration() {
    faer::set_global_parallelism(faer::Par::Seq);
    let out = std::env::temp_dir().join(format!("squeal-test-stick-walk-3-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let p = Pipeline::new(common::bundled_scene_at_speed(3.0), out, &quiet).unwrap();
    let (m, st) = (p.model().unwrap(), p.stability().unwrap());
    let mu0 = p.mu0().unwrap();
    let mu = 1.0452 * mu0;
    let sol = common::chbm_cycle(&p, mu);
    let law = StickSlipSetting::Dlft {
        epsilon_factor: 1.0,
    };
    let c = squeal_pipeline::cycle_stick::recompute(m, st, law, mu, &sol)
        .unwrap()
        .expect("the margin is below 1 at 3 km/h");
    assert!(c.converged, "DLFT at 1.0452 mu0 from the CHBM cycle");
    let mb = ModalBrake::new(&m.brake, &st.reference, mu0);
    let layout = HarmonicLayout::new(mb.nl(), 24).unwrap();
    let PhaseCondition::FirstSineZero { dof } =
        PhaseCondition::strongest_dof(&layout, &c.cycle.nl_coeffs).unwrap();
    let (pair, _) = c.cycle.loudest();
    let v_min = surface_speeds(&mb)
        .unwrap()
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    let samples = StickOptions::default().samples_for(24);
    let mut o = DlftOptions::default();
    o.harmonics = Some(24);
    // The cycle at 1.0452 mu0 as a DLFT cycle (its stick fractions and switches, for the
    // Floquet analysis): solved again from the converged one.
    let first = dlft_cycle(&mb, mu, &c.cycle, dof, &o).unwrap();
    assert!(first.converged);
    let mut floquet = vec![(1.0452, first)];
    let mut prev = vec![c.cycle.clone()];
    // DLFT (relay projection) from the integrated V/320 and V/160 cycles, the example
    // `dlft_time`: 3972.83618 and 3963.67791 Hz.
    for (ratio, f_relay) in [(1.0540, 3972.83618), (1.0649, 3963.67791)] {
        let t = std::time::Instant::now();
        let w = dlft_walk(&mb, &prev, ratio * mu0, dof, &o, &WalkOptions::default()).unwrap();
        let d = w.cycle.expect("a converged step");
        eprintln!(
            "{ratio} mu0: {:.9} Hz, p2p {:.6} um, residual {:.1e}, stick {:?}, {} solves ({:.1} s)",
            d.point.frequency_hz(),
            d.point.pairs[pair].peak_to_peak() * 1e6,
            d.point.residual,
            d.stick_fractions,
            w.solves.len(),
            t.elapsed().as_secs_f64()
        );
        // Reached and converged (the solve's own rule: 1e-9 of the largest static pair force).
        assert!(w.reached && d.converged && d.point.residual <= 1e-9);
        // The relay's cycle, where it converged from the integrated cycles: TOL_RELAY.
        assert!(
            (d.point.frequency_hz() / f_relay - 1.0).abs() < TOL_RELAY,
            "{} Hz against {f_relay}",
            d.point.frequency_hz()
        );
        if ratio < 1.06 || floquet_mu().contains(&ratio) {
            floquet.push((ratio, d.clone()));
        }
        if ratio == 1.0540 {
            same_cycle_from_the_chbm_start(&p, ratio * mu0, &d);
        }
        // The time integration of the regularized law at V/80, from the DLFT cycle.
        let v_reg = 0.0125 * v_min;
        let smb = sticking_brake(&mb, v_reg).unwrap();
        let mut opts = OrbitOptions::default();
        opts.record_cycles = 10;
        opts.ti.max_cycles = 800.0;
        let mut q = d.point.clone();
        q.parameter = ratio * mu0;
        let mut smb_mu = smb.clone();
        smb_mu.mu = ratio * mu0;
        let orbit = integrate_orbit(&smb_mu, v_reg, &q, Some(samples), &opts).unwrap();
        let rec = orbit.record.as_ref().unwrap();
        let df = d.point.omega * rec.mean_period() / (2.0 * std::f64::consts::PI) - 1.0;
        let dp = rec.mean_closure() / d.point.pairs[pair].peak_to_peak() - 1.0;
        eprintln!(
            "  BDF V/80 minus DLFT {:+.2e} f, {dp:+.2e} p2p; spreads {:.1e} {:.1e}; stuck {:?} ({:.1} s)",
            -df,
            rec.period_spread(),
            rec.closure_spread(),
            rec.stuck,
            t.elapsed().as_secs_f64()
        );
        // Periodic (integrator noise 1.4e-5 to 2.5e-5 over 19 cycles, docs/stick_slip.md).
        assert!(rec.period_spread() < 1e-4 && rec.closure_spread() < 1e-4);
        // Within the regularization's error at V/80 (first order in v_reg; measured against the
        // relay's DLFT at 1.0649 mu0: +1.74e-4 in frequency, -3.1e-3 in closure) plus the
        // integrator's 2e-5.
        assert!(df.abs() < 3e-4 && dp.abs() < 5e-3, "{df:e} {dp:e}");
        // The pairs DLFT finds stuck are the ones the integration holds near zero slip.
        for (k, &s) in d.stick_fractions.iter().enumerate() {
            if s > 0.03 {
                assert!(
                    rec.stuck[k] > 0.5 * s,
                    "pair {k}: {} against {s}",
                    rec.stuck[k]
                );
            }
        }
        prev.push(d.point.clone());
        if prev.len() > 2 {
            prev.remove(0);
        }
    }
    stable_with_the_regularized_limit_exponents(&mb, &floquet);
}

/// Extra cycles for the Floquet analysis (`STICK_FLOQUET_MU=1.0649`: the third cycle of
/// docs/stick_slip.md; 1.0452 and 1.0540 mu0 are always analysed).
fn floquet_mu() -> Vec<f64> {
    std::env::var("STICK_FLOQUET_MU").map_or(vec![], |s| {
        s.split(',').map(|x| x.parse::<f64>().unwrap()).collect()
    })
}

/// The DLFT cycles (mu/mu0, cycle) are stable with the exact law, and their leading exponent
/// is the regularized law's limit within the analysis' error.
fn stable_with_the_regularized_limit_exponents(mb: &ModalBrake, cycles: &[(f64, DlftCycle)]) {
    // The limit of the regularized law's leading Hill exponent as v_reg -> 0 (V/160 or V/320,
    // docs/stick_slip.md): -55.85, -53.1, -49.3 1/s.
    let limit = |r: f64| {
        if r < 1.05 {
            -55.85
        } else if r < 1.06 {
            -53.1
        } else {
            -49.3
        }
    };
    let steps = std::env::var("STICK_FLOQUET_STEPS").map_or(512, |s| s.parse().unwrap());
    let mut fo = StickSlipFloquetOptions::default();
    fo.steps = steps;
    for (ratio, d) in cycles {
        let f = dlft_floquet(mb, d, &fo).unwrap();
        let e = f.leading().unwrap();
        eprintln!(
            "{ratio} mu0: {:.5} Hz, stick {:.2?}, leading {:+.3} {:+.1}i 1/s (|rho| {:.6}), trivial error {:.2e}, integration {:.2e} 1/s, {:?}, {} steps, {:.1} s",
            d.point.frequency_hz(),
            d.stick_fractions,
            e.sigma.re,
            e.sigma.im,
            e.multiplier.norm(),
            f.trivial_error,
            f.integration_error,
            f.switches,
            f.steps,
            f.time.as_secs_f64()
        );
        for x in f.exponents.iter().take(8) {
            eprintln!("   {:+.3} {:+.1}i {}", x.sigma.re, x.sigma.im, x.trivial);
        }
        // Stable beyond the method's error (the trivial exponent's distance from 0 and the
        // integration's estimate).
        assert_eq!(f.stability(), CycleStability::Stable);
        // Measured (512 steps per period, the default; at 256 the trivial error at 1.0452 mu0
        // is 0.64 1/s): 1.0452 mu0, no pair sticks: -55.786 against the limit -55.85 (the
        // regularized law's V/80 -> V/160 step moved it by 0.05), trivial error 0.13 1/s;
        // 1.0540 mu0: -56.48 against -53.1, trivial error 7.6 1/s. Tolerance: the exact law's
        // exponent and the regularized limit agree within the exact analysis' own error (the
        // trivial exponent's distance from 0, the DLFT truncation's inconsistency at the
        // switches) plus 0.5 1/s for the regularized limit's convergence.
        let d = e.sigma.re - limit(*ratio);
        assert!(
            d.abs() <= f.error() + 0.5,
            "{ratio} mu0: leading {:+.3} against {}",
            e.sigma.re,
            limit(*ratio)
        );
        if *ratio < 1.05 {
            assert!(
                f.trivial_error < 0.5,
                "no stick: trivial error {:e}",
                f.trivial_error
            );
        }
    }
}

/// Exact stick–slip (DLFT) against time integration of the regularized law (issue 24, items
/// 4–5; docs/stick_slip.md "DLFT against time integration"): the integrated orbit is
/// periodic, its own law's balance matches it to the integrator's error, its cycle starts the
/// DLFT solve, and the integrated orbit approaches the DLFT cycle as `v_reg` shrinks. The
/// longer study (V/20 to V/160, three μ) is the example `dlft_time`.
#[test]
fn integrated_regularized_orbits_approach_the_dlft_cycle_at_3_kmh() {
    faer::set_global_parallelism(faer::Par::Seq);
    let out = std::env::temp_dir().join(format!("squeal-test-stick-time-3-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let p = Pipeline::new(common::bundled_scene_at_speed(3.0), out, &quiet).unwrap();
    let (m, st) = (p.model().unwrap(), p.stability().unwrap());
    // The second cycle the branch recomputes at 3 km/h (margin 0.95): stable, the pads near
    // sticking.
    let mu = 1.0452 * p.mu0().unwrap();
    let sol = common::chbm_cycle(&p, mu);
    // The regularized cycle at V/20, 24 harmonics (as `squeal chbm` recomputes it).
    let c = squeal_pipeline::cycle_stick::recompute(m, st, StickSlipSetting::Regularized, mu, &sol)
        .unwrap()
        .expect("the margin is below 1 at 3 km/h");
    assert!(c.converged);
    let mb = ModalBrake::new(&m.brake, &st.reference, mu);
    let v_min = surface_speeds(&mb)
        .unwrap()
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    let samples = StickOptions::default().samples_for(24);
    let layout = HarmonicLayout::new(mb.nl(), 24).unwrap();
    let PhaseCondition::FirstSineZero { dof } =
        PhaseCondition::strongest_dof(&layout, &c.cycle.nl_coeffs).unwrap();
    let (pair, _) = c.cycle.loudest();
    let mut opts = OrbitOptions::default();
    opts.record_cycles = 10;
    opts.ti.max_cycles = 800.0;
    let mut exact = None;
    let mut errors = Vec::new();
    let mut q = c.cycle.clone();
    for frac in [0.05, 0.0125] {
        let v_reg = frac * v_min;
        if frac != 0.05 {
            let mut o = DlftOptions::default();
            o.samples = Some(samples);
            let (r, ok) = regularized_cycle(&mb, mu, v_reg, &q, dof, &o).unwrap();
            assert!(ok);
            q = r;
        }
        let smb = sticking_brake(&mb, v_reg).unwrap();
        let t = std::time::Instant::now();
        let orbit = integrate_orbit(&smb, v_reg, &q, Some(samples), &opts).unwrap();
        let rec = orbit.record.as_ref().unwrap();
        let ti_period = orbit.check.ti_period.expect("steady");
        let hb_period = 2.0 * std::f64::consts::PI / q.omega;
        eprintln!(
            "V*{frac}: BDF period {:+.2e}, record {:+.2e} (spread {:.1e}), p2p {:+.2e} (spread {:.1e}) vs its own law's balance; stuck {:?} ({:.1} s)",
            ti_period / hb_period - 1.0,
            rec.mean_period() / hb_period - 1.0,
            rec.period_spread(),
            rec.mean_closure() / q.pairs[pair].peak_to_peak() - 1.0,
            rec.closure_spread(),
            rec.stuck,
            t.elapsed().as_secs_f64()
        );
        // Periodic: every recorded cycle's period and closure within 1e-4 of the others
        // (measured 1.6e-5 to 2.5e-5 and 3.6e-5 to 4.8e-5, the integrator's noise at rtol 1e-7).
        assert!(rec.period_spread() < 1e-4 && rec.closure_spread() < 1e-4);
        // The same law's balance (24 harmonics, converged to 1e-6 in them) matches the
        // integration to the integrator's error at rtol 1e-7: measured 1.1e-5 to 1.7e-5 in
        // period and 1e-5 to 8e-5 in closure from V/20 to V/160; the regularization's own
        // effect is 6e-4 and 1e-2.
        assert!((rec.mean_period() / hb_period - 1.0).abs() < 3e-5);
        assert!((rec.mean_closure() / q.pairs[pair].peak_to_peak() - 1.0).abs() < 2e-4);
        if exact.is_none() {
            // DLFT from the integrated cycle's 24 harmonics converges (from the 3-harmonic CHBM
            // cycle it stops at a residual of 9e-3).
            let g = steady_point(&mb, mu, &orbit.check, dof).unwrap().unwrap();
            let mut o = DlftOptions::default();
            o.harmonics = Some(24);
            let d = dlft_cycle(&mb, mu, &g, dof, &o).unwrap();
            eprintln!(
                "DLFT from the integrated cycle: {:.5} Hz, residual {:.1e}, stick {:?}",
                d.point.frequency_hz(),
                d.point.residual,
                d.stick_fractions
            );
            assert!(
                d.converged && d.point.residual < 1e-9,
                "{}",
                d.point.residual
            );
            exact = Some(d.point);
        }
        let d = exact.as_ref().unwrap();
        let df = d.omega * rec.mean_period() / (2.0 * std::f64::consts::PI) - 1.0;
        let dp = rec.mean_closure() / d.pairs[pair].peak_to_peak() - 1.0;
        eprintln!(
            "V*{frac}: integrated minus DLFT {:+.2e} f, {dp:+.2e} p2p",
            -df
        );
        errors.push((df.abs(), dp.abs()));
    }
    // The integrated orbit approaches DLFT as v_reg shrinks: V/20 -> V/80 divides both errors by
    // more than 4 (measured 6.1e-4 -> 5.8e-5 in frequency, 1.15e-2 -> 1.8e-3 in closure), and
    // at V/80 they are below 1e-4 and 2.5e-3.
    assert!(errors[1].0 < errors[0].0 / 4.0 && errors[1].1 < errors[0].1 / 4.0);
    assert!(errors[1].0 < 1e-4 && errors[1].1 < 2.5e-3, "{errors:?}");
}

/// `squeal chbm`'s single DLFT cycle past 1.05 μ0: DLFT stops short from the CHBM cycle and
/// the V/20 start at 1.0649 μ0, and the single-cycle path continues it in μ from below
/// (`squeal_pipeline::cycle_walk`) to the cycle `squeal branch`'s walk reaches at the same μ.
#[test]
fn the_single_cycle_walks_past_1_05_mu0_to_the_branch_cycle() {
    faer::set_global_parallelism(faer::Par::Seq);
    let out = std::env::temp_dir().join(format!("squeal-test-chbm-walk-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let p = Pipeline::new(common::bundled_scene_at_speed(3.0), out, &quiet).unwrap();
    let (m, st) = (p.model().unwrap(), p.stability().unwrap());
    let mu0 = p.mu0().unwrap();
    let mu = 1.0649 * mu0;
    let t = std::time::Instant::now();
    let sol = common::chbm_cycle(&p, mu);
    let law = StickSlipSetting::Dlft {
        epsilon_factor: 1.0,
    };
    let mut c = squeal_pipeline::cycle_stick::recompute(m, st, law, mu, &sol)
        .unwrap()
        .expect("the margin is below 1 at 3 km/h");
    // Its stability with the exact law, as `squeal chbm` prints it.
    squeal_pipeline::cycle_stick::add_stability(m, st, &mut c);
    let text = squeal_pipeline::cycle_stick::text(&c);
    eprintln!("{text}({:.1} s)", t.elapsed().as_secs_f64());
    // Stable, and the leading exponent the regularized law's limit as v_reg -> 0 (-49.3 1/s
    // at 1.0649 mu0, docs/stick_slip.md) within the analysis' own error plus 0.5 1/s, the
    // tolerance of `stable_with_the_regularized_limit_exponents` above.
    let (f, _) = c.stability.as_ref().expect("a converged DLFT cycle");
    let f = f.as_ref().unwrap();
    let e = f.leading().unwrap();
    assert_eq!(f.stability(), CycleStability::Stable, "{text}");
    assert!((e.sigma.re + 49.3).abs() <= f.error() + 0.5, "{text}");
    assert!(
        text.contains("stability with the exact law: stable"),
        "{text}"
    );
    // The direct starts (40 iterations each) stop short there (measured: relative residuals
    // 9.0e-3 from the CHBM cycle, 9.6e-3 from V/20), so the cycle must come from the walk.
    // (At 1.0540 mu0 they stop short too, since the phase row is required: the first test.)
    let w = c.walk.as_ref().expect("continued in mu from below");
    assert!(w.reached && c.converged, "{text}");
    assert!(text.contains("continued in mu from below"), "{text}");
    // Converged by the rule every DLFT cycle is judged by: 1e-9 of the largest pair force.
    assert!(c.cycle.residual <= 1e-9, "residual {:e}", c.cycle.residual);
    // `squeal branch`'s walk at 1.0649 mu0 (the same DLFT balance continued in mu from the
    // 1.0452 mu0 cycle through 1.0540 mu0, the first test above): 3963.848174289 Hz,
    // 46.068279 um on pair 7 (0-based 6), measured 2026-11-28 with the Gauss-Newton steps and
    // the phase rule. Both are roots of the same balance reached by different walks, each to
    // a residual below 1e-12 with its phase condition met to round-off: measured 1.5e-10 apart
    // in frequency, the same closure to the printed digits. Tolerance 1e-9 in frequency and
    // 1e-7 in closure (the printed digits' rounding, 1.1e-8, and such roots' spread); before
    // the phase rule the roots accepted at the walks' iteration limits spread by 4.7e-8 and
    // 9.6e-7, and the tolerances were 2e-7 and 1e-5.
    let (pair, _) = c.sliding.loudest();
    let f = c.cycle.frequency_hz();
    let p2p = c.cycle.pairs[pair].peak_to_peak() * 1e6;
    let (f_walk, p2p_walk) = (3963.848174289, 46.068279);
    eprintln!(
        "f {f:.9} Hz ({:+.2e}), p2p pair {} {p2p:.6} um ({:+.2e})",
        f / f_walk - 1.0,
        pair + 1,
        p2p / p2p_walk - 1.0
    );
    assert_eq!(pair, 6, "the loudest pair");
    assert!((f / f_walk - 1.0).abs() < 1e-9, "{f}");
    assert!((p2p / p2p_walk - 1.0).abs() < 1e-7, "{p2p}");
}

/// `squeal chbm`'s single cycle at `mu` (1.0540 μ0) against the walk's `walked` there. Until
/// 2026-11-28 the direct start from the CHBM cycle was accepted there on its balance residual
/// (1.6e-12) at the iteration limit with the phase condition missed by a quarter of a sample
/// (1.7e-3 rad), one stuck sample more on pair 3 and 4.1e-7 in frequency from the walked cycle
/// (docs/stick_slip.md, "The two cycles at 1.0540 μ0"). Now `dlft_cycle` also requires the
/// phase row (1e-6 rad) of a solve that stopped short, the direct starts stop short there
/// (2.5e-3 from the CHBM cycle, 6.6e-4 from V/20) and the cycle is walked from 1.0329 μ0:
/// measured 1.9e-11 from the walk from 1.0452 μ0 in frequency, the same stuck samples.
/// Tolerance 1e-9 in frequency and 1e-8 in closure: the residuals (below 1e-11 relative) leave
/// the roots about 1e-10 apart (a re-solve moved them 2e-10 before), and one stuck sample
/// more moves the cycle by 4.1e-7 and 7e-6.
fn same_cycle_from_the_chbm_start(p: &Pipeline, mu: f64, walked: &DlftCycle) {
    let t = std::time::Instant::now();
    let (m, st) = (p.model().unwrap(), p.stability().unwrap());
    let sol = common::chbm_cycle(p, mu);
    let law = StickSlipSetting::Dlft {
        epsilon_factor: 1.0,
    };
    let c = squeal_pipeline::cycle_stick::recompute(m, st, law, mu, &sol)
        .unwrap()
        .expect("the margin is below 1 at 3 km/h");
    let (pair, _) = walked.point.loudest();
    let df = c.cycle.omega / walked.point.omega - 1.0;
    let dp = c.cycle.pairs[pair].peak_to_peak() / walked.point.pairs[pair].peak_to_peak() - 1.0;
    eprintln!(
        "  squeal chbm's single cycle there: {:.9} Hz ({df:+.2e}, closure {dp:+.2e}), stuck {:?}, walked from below: {} ({:.1} s)",
        c.cycle.frequency_hz(),
        c.stick_fractions,
        c.walk.is_some(),
        t.elapsed().as_secs_f64()
    );
    assert!(c.converged && c.cycle.residual <= 1e-9);
    assert!(df.abs() < 1e-9 && dp.abs() < 1e-8, "{df:e} {dp:e}");
}

/// The clamp's cycle against the relay's, in frequency: measured 3.3e-5 (1.0540 mu0) and
/// 4.3e-5 (1.0649 mu0). The two discrete balances differ at the samples of the transitions
/// (24 harmonics across a stick phase); the integrated orbits' limit in v_reg lies within 1e-5
/// of the clamp's (docs/stick_slip.md), and stick-slip itself moves the cycle by 1e-3.
const TOL_RELAY: f64 = 6e-5;
