//! Floquet multipliers of a DLFT stick–slip cycle by the monodromy with saltation matrices
//! (`squeal_chbm::stick_floquet`) against an independent reference: central finite
//! differences of the fixed-time flow map over one period of an event-driven integration of
//! the exact law (classical Runge–Kutta in each phase, switches located by bisection to
//! 1e-15 s: the reference of `dlft_two_dof.rs`), on the 2-dof friction oscillator of Hoffmann
//! et al. (2002) at μ = 0.6, V = 0.01 m/s, where the mass sticks about a third of each period.

use super::common;

use common::belt::{C, M, MU, N0, V, balance, event, normal, rk4, stiffness, stuck_force};
use faer::{Mat, c64};
use squeal_chbm::stick_floquet::{
    LinearPart, StickSlipCycle, StickSlipFloquetOptions, StickSlipModel, stick_slip_floquet,
};
use squeal_hbm::*;
use std::f64::consts::PI;

/// The event-driven flow over `duration` from `(s, stick, sign)`; with `onsets` the stick
/// onsets met.
fn flow(
    mut s: [f64; 4],
    mut stick: bool,
    mut sign: f64,
    duration: f64,
    dt: f64,
    onsets: &mut Vec<f64>,
) -> ([f64; 4], bool, f64) {
    let mut t = 0.0;
    while t < duration {
        let step = dt.min(duration - t);
        let next = rk4(&s, step, stick, sign);
        if event(&next, stick, sign) < 0.0 {
            let (mut lo, mut hi) = (0.0, step);
            while hi - lo > 1e-15 {
                let mid = 0.5 * (lo + hi);
                if event(&rk4(&s, mid, stick, sign), stick, sign) < 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            s = rk4(&s, hi, stick, sign);
            t += hi;
            if stick {
                stick = false;
                sign = stuck_force(&s).signum();
            } else if stuck_force(&s).abs() <= MU * normal(s[1]) {
                stick = true;
                s[2] = V;
                onsets.push(t);
            } else {
                sign = -sign;
            }
        } else {
            s = next;
            t += step;
        }
    }
    (s, stick, sign)
}

/// The settled cycle: period (between two stick onsets), a state in mid-slip, and `(t, x, y)`
/// over one period from a stick onset.
struct Reference {
    period: f64,
    start: [f64; 4],
    sign: f64,
    path: Vec<(f64, f64, f64)>,
}

fn reference(dt: f64) -> Reference {
    let mut onsets = Vec::new();
    let (s, stick, sign) = flow([1e-5, 0.0, 0.0, 0.0], false, 1.0, 20.0, dt, &mut onsets);
    // Run on to the next two stick onsets.
    let mut on = Vec::new();
    let (mut s, mut stick, mut sign, mut t) = (s, stick, sign, 0.0);
    while on.len() < 3 {
        let mut o = Vec::new();
        (s, stick, sign) = flow(s, stick, sign, dt, dt, &mut o);
        on.extend(o.iter().map(|x| x + t));
        t += dt;
    }
    let period = on[2] - on[1];
    // From the last onset (state s at time t, past on[2]) forward to mid-slip: the stick lasts
    // about a third of the period, so 2/3 of a period after the onset the mass slides.
    let mut o = Vec::new();
    let back = t - on[2];
    let (mid, st, sg) = flow(s, stick, sign, 0.66 * period - back, dt, &mut o);
    assert!(!st, "the start must slide");
    // The path over one period from the start (for the Fourier coefficients).
    let mut path = Vec::new();
    let (mut p, mut pst, mut psg, mut pt) = (mid, st, sg, 0.0);
    path.push((0.0, p[0], p[1]));
    while pt < period {
        let h = dt.min(period - pt);
        (p, pst, psg) = flow(p, pst, psg, h, dt, &mut Vec::new());
        pt += h;
        path.push((pt, p[0], p[1]));
    }
    Reference {
        period,
        start: mid,
        sign: sg,
        path,
    }
}

fn coeffs(r: &Reference, h: usize) -> Vec<f64> {
    let nb = 2 * h + 1;
    let mut c = vec![0.0; 2 * nb];
    for w in r.path.windows(2) {
        let (a, b) = (w[0], w[1]);
        let dt = b.0 - a.0;
        for (d, (va, vb)) in [(a.1, b.1), (a.2, b.2)].into_iter().enumerate() {
            let ta = 2.0 * PI * a.0 / r.period;
            let tb = 2.0 * PI * b.0 / r.period;
            c[d] += 0.5 * dt * (va + vb) / r.period;
            for k in 1..=h {
                let kf = k as f64;
                c[(2 * k - 1) * 2 + d] +=
                    dt * (va * (kf * ta).cos() + vb * (kf * tb).cos()) / r.period;
                c[2 * k * 2 + d] += dt * (va * (kf * ta).sin() + vb * (kf * tb).sin()) / r.period;
            }
        }
    }
    c
}

/// Multipliers of a real 4×4 matrix, modulus descending.
fn multipliers(m: &Mat<f64>) -> Vec<c64> {
    let e = m.eigen().unwrap();
    let s = e.S();
    let mut v: Vec<c64> = (0..m.nrows()).map(|i| s[i]).collect();
    v.sort_by(|a, b| b.norm().total_cmp(&a.norm()));
    v
}

#[test]
fn saltation_monodromy_matches_finite_differences_of_the_event_driven_flow() {
    let dt = 5e-6;
    let r = reference(dt);
    // Central differences of the flow over one period, step 1e-7 of each state's scale
    // (displacements ~1e-3 m, velocities ~0.05 m/s).
    let scale = [1e-3, 1e-3, 5e-2, 5e-2];
    let mut fd = Mat::<f64>::zeros(4, 4);
    for (j, sc) in scale.iter().enumerate() {
        let h = 1e-7 * sc;
        let mut plus = r.start;
        plus[j] += h;
        let mut minus = r.start;
        minus[j] -= h;
        let (a, ..) = flow(plus, false, r.sign, r.period, dt, &mut Vec::new());
        let (b, ..) = flow(minus, false, r.sign, r.period, dt, &mut Vec::new());
        for i in 0..4 {
            fd[(i, j)] = (a[i] - b[i]) / (2.0 * h);
        }
    }
    let ref_mult = multipliers(&fd);
    println!("reference period {:.12} s", r.period);
    println!("finite differences: {ref_mult:?}");
    for h in [20usize, 30] {
        let mut ssb = balance(h, 3.0e3);
        let u0 = coeffs(&r, h);
        let sol = solve_stick_slip(
            &mut ssb,
            PhaseCondition::FirstSineZero { dof: 0 },
            &u0,
            2.0 * PI / r.period,
            N0,
            &LmOptions::default(),
        )
        .unwrap();
        let mut res = vec![0.0; ssb.layout().len()];
        ssb.residual(&sol.coeffs, sol.omega, &mut res).unwrap();
        let states = ssb.states().to_vec();
        let predicted = ssb.predicted_multipliers().to_vec();
        let model = StickSlipModel {
            stiffness: LinearPart::Dense(stiffness()),
            damping: LinearPart::Diagonal(vec![C / M; 2]),
            lift: Mat::identity(2, 2),
            smooth_jacobian: Box::new(|_: &[f64]| Mat::zeros(2, 2)),
            contacts: ssb.contacts_mut().to_vec(),
        };
        let cycle = StickSlipCycle {
            layout: ssb.layout(),
            u: &sol.coeffs,
            omega: sol.omega,
            states: &states,
            predicted: &predicted,
        };
        let f = stick_slip_floquet(&model, &cycle, &StickSlipFloquetOptions::default()).unwrap();
        let mut mult: Vec<c64> = f.exponents.iter().map(|e| e.multiplier).collect();
        mult.sort_by(|a, b| b.norm().total_cmp(&a.norm()));
        println!(
            "H {h}: period error {:.2e}, multipliers {mult:?}, trivial error {:.2e} 1/s, integration {:.2e} 1/s, switches {:?}, {:.2} s",
            sol.period() / r.period - 1.0,
            f.trivial_error,
            f.integration_error,
            f.switches,
            f.time.as_secs_f64()
        );
        let d: Vec<f64> = mult
            .iter()
            .zip(&ref_mult)
            .map(|(a, b)| (a - b).norm())
            .collect();
        println!(
            "  |Δρ| (modulus order) = {:.2e} {:.2e} {:.2e} {:.2e}",
            d[0], d[1], d[2], d[3]
        );
        // Measured (H = 20, 30): trivial 1.30e-3, 1.15e-3; leading 2.4e-4, 3.9e-4; third
        // (-0.546) 1.1e-2, 7.9e-3; the stick's zero multiplier 1.2e-8 (the finite differences'
        // own size, step 1e-7). The tolerances are the DLFT cycle's truncation: its switch
        // times (from 1024-2048 samples of series truncated at H) and Jacobians carry errors
        // of order 1e-3 of the period, to which the third multiplier, the most contracted
        // phase of the slip, is the most sensitive. The integration's own error (Richardson,
        // 1e-4 1/s in the exponents) is far below.
        assert!(d[0] < 2e-3, "H {h}: trivial multiplier off by {:e}", d[0]);
        assert!(d[1] < 1e-3, "H {h}: leading multiplier off by {:e}", d[1]);
        assert!(d[2] < 2e-2, "H {h}: third multiplier off by {:e}", d[2]);
        assert!(d[3] < 1e-6, "H {h}: zero multiplier off by {:e}", d[3]);
        assert_eq!(f.switches.stick_entries, 1, "H {h}: one stick phase");
        assert!(f.integration_error < 1e-3, "H {h}: integration error");
    }
}
