//! Linear validation: exponentials, convergence order, oscillator damping,
//! growth rate of a slightly unstable mode.

use super::common;

use common::{Linear, complex_pair, complex_pair_exact};
use squeal_ode::{Atol, Bdf, BdfOptions, FixedStep, OscillationMonitor, SteadyOptions, solve};

fn opts(rtol: f64, atol: f64) -> BdfOptions {
    {
        let mut o = BdfOptions::default();
        o.rtol = rtol;
        o.atol = Atol::Scalar(atol);
        o
    }
}

/// y' = lambda y for real lambda (decaying, stiff, growing) against exp.
/// For this scalar linear equation a relative perturbation is carried
/// unchanged by the flow, so the relative global error is at most the sum of
/// the local relative errors: <= steps x rtol (atol is negligible here).
/// It must also be a small multiple of rtol: < 100 rtol (measured <= 48 for
/// lambda = -1000 at rtol 1e-8 and t = 10/1000, where y = e^{-10}; the
/// ratio grows slowly as rtol falls because the step count grows).
#[test]
fn real_exponentials() {
    for &(lambda, t_end) in &[(-1.0, 5.0), (-1000.0, 0.01), (0.7, 5.0)] {
        for &rtol in &[1e-4, 1e-6, 1e-8] {
            let sys = Linear {
                a: vec![vec![lambda]],
            };
            let t_out: Vec<f64> = (1..=10).map(|k| t_end * k as f64 / 10.0).collect();
            let sol = solve(&sys, 0.0, &[1.0], &t_out, &opts(rtol, rtol * 1e-6)).unwrap();
            let mut worst: f64 = 0.0;
            for (t, y) in sol.t.iter().zip(&sol.y) {
                let exact = (lambda * t).exp();
                worst = worst.max((y[0] - exact).abs() / exact / rtol);
            }
            println!(
                "lambda {lambda} rtol {rtol:e}: worst rel error / rtol = {worst:.2}, {} steps",
                sol.stats.steps
            );
            assert!(
                worst < sol.stats.steps as f64,
                "lambda {lambda} rtol {rtol}: {worst}"
            );
            assert!(worst < 100.0, "lambda {lambda} rtol {rtol}: {worst} rtol");
        }
    }
}

/// Complex pair lambda = -0.1 +- 2 pi i (a damped oscillation) over 5
/// periods, evaluated by dense output at 1000 points between steps.
/// Bounds: (1) the flow is contractive, so the global error is at most the
/// sum of the local errors, each <= rtol (weighted RMS, |y| <= 1, so <= sqrt 2
/// rtol per component): worst <= sqrt(2) * steps * rtol; (2) within a factor
/// 2 of scipy 1.17.1 `solve_ivp(method="BDF")`, the same method implemented
/// independently (worst errors 7.52e-4, 1.74e-5, 3.87e-7 for the same
/// problem, tolerances and output points; the factor covers the different
/// step-size hysteresis).
#[test]
fn complex_pair_dense_output() {
    let (a, b) = (-0.1, 2.0 * std::f64::consts::PI);
    let scipy = [(1e-5, 7.52e-4), (1e-7, 1.74e-5), (1e-9, 3.87e-7)];
    for &(rtol, scipy_worst) in &scipy {
        let sys = complex_pair(a, b);
        let t_out: Vec<f64> = (1..=1000).map(|k| 5.0 * k as f64 / 1000.0).collect();
        let sol = solve(&sys, 0.0, &[1.0, 0.0], &t_out, &opts(rtol, rtol)).unwrap();
        let mut worst: f64 = 0.0;
        for (t, y) in sol.t.iter().zip(&sol.y) {
            let e = complex_pair_exact(a, b, *t);
            worst = worst.max((y[0] - e[0]).abs().max((y[1] - e[1]).abs()));
        }
        println!(
            "complex pair rtol {rtol:e}: worst error {worst:e} ({:.0} rtol), {:?}",
            worst / rtol,
            sol.stats
        );
        let bound = 2f64.sqrt() * sol.stats.steps as f64 * rtol;
        assert!(
            worst < bound,
            "rtol {rtol}: worst error {worst:e} > {bound:e}"
        );
        assert!(
            worst < 2.0 * scipy_worst && worst > 0.5 * scipy_worst,
            "rtol {rtol}: worst error {worst:e} vs scipy {scipy_worst:e}"
        );
    }
}

/// Fixed order k and fixed step h, started from the exact history: the
/// global error at t = 2 behaves like h^k. The slope of log(err) against
/// log(h) over h = 2/25 ... 2/200 must be k +- 0.3 (pre-asymptotic terms
/// and, for k = 5 at the smallest h, rounding shift it by < 0.2).
#[test]
fn convergence_order_fixed_step() {
    let (a, b) = (-0.5, 2.0);
    let t_end = 2.0;
    for ndf in [false, true] {
        for k in 1..=5 {
            let mut logs = Vec::new();
            for &n in &[25usize, 50, 100, 200] {
                let h = t_end / n as f64;
                let opts = {
                    let mut o = BdfOptions::default();
                    o.ndf = ndf;
                    o.fixed_step = Some(FixedStep { h, order: k });
                    o
                };
                let past: Vec<Vec<f64>> = (0..=k)
                    .map(|j| complex_pair_exact(a, b, -(j as f64) * h).to_vec())
                    .collect();
                let mut bdf =
                    Bdf::with_history(complex_pair(a, b), 0.0, &past, t_end, &opts).unwrap();
                while !bdf.is_finished() {
                    bdf.step().unwrap();
                }
                assert_eq!(bdf.stats().steps, n, "fixed step count");
                let e = complex_pair_exact(a, b, t_end);
                let y = bdf.y();
                let err = ((y[0] - e[0]).powi(2) + (y[1] - e[1]).powi(2)).sqrt();
                logs.push((h.ln(), err.ln()));
            }
            let slope = fit_slope(&logs);
            println!("ndf {ndf} order {k}: slope {slope:.3}");
            assert!(
                (slope - k as f64).abs() < 0.3,
                "ndf {ndf} order {k}: slope {slope}"
            );
        }
    }
}

fn fit_slope(p: &[(f64, f64)]) -> f64 {
    let n = p.len() as f64;
    let mx = p.iter().map(|q| q.0).sum::<f64>() / n;
    let my = p.iter().map(|q| q.1).sum::<f64>() / n;
    let sxy: f64 = p.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
    let sxx: f64 = p.iter().map(|q| (q.0 - mx).powi(2)).sum();
    sxy / sxx
}

/// Harmonic oscillator x'' + x = 0 over 100 periods: amplitude and phase
/// error against rtol. BDF/NDF damp undamped oscillations (numerical
/// dissipation); the error is ~1000-10000 rtol over 100 periods because it
/// accumulates over all steps. Bounds: (1) at most the sum of the local
/// errors, sqrt(2) * steps * rtol (the flow is an isometry); (2) within a
/// factor 2 of scipy 1.17.1 `solve_ivp(method="BDF")` on the same problem
/// (amplitude errors 1.07e-1, 3.30e-3, 7.58e-5, 1.66e-6; phase errors
/// 7.32e-2, 9.27e-4, 9.66e-6, 9.79e-8), the same method implemented
/// independently. Prints the table.
#[test]
fn harmonic_oscillator_damping() {
    let two_pi = 2.0 * std::f64::consts::PI;
    let t_end = 100.0 * two_pi;
    let scipy = [
        (1e-4, 1.07e-1, 7.32e-2),
        (1e-6, 3.30e-3, 9.27e-4),
        (1e-8, 7.58e-5, 9.66e-6),
        (1e-10, 1.66e-6, 9.79e-8),
    ];
    println!("rtol      amplitude error   phase error (rad)  steps/period");
    for &(rtol, scipy_amp, scipy_phase) in &scipy {
        let sys = complex_pair(0.0, 1.0);
        let sol = solve(&sys, 0.0, &[1.0, 0.0], &[t_end], &opts(rtol, rtol)).unwrap();
        let y = &sol.y[0];
        let amp_err = (y[0].hypot(y[1]) - 1.0).abs();
        let phase = y[1].atan2(y[0]).abs(); // exact: 100 * 2 pi = 0 mod 2 pi
        println!(
            "{rtol:8.0e}  {amp_err:15.3e}  {phase:17.3e}  {:8.1}",
            sol.stats.steps as f64 / 100.0
        );
        let bound = 2f64.sqrt() * sol.stats.steps as f64 * rtol;
        assert!(
            amp_err < bound,
            "rtol {rtol}: amplitude error {amp_err:e} > {bound:e}"
        );
        assert!(
            phase < bound,
            "rtol {rtol}: phase error {phase:e} > {bound:e}"
        );
        assert!(
            amp_err < 2.0 * scipy_amp && amp_err > 0.5 * scipy_amp,
            "rtol {rtol}: amplitude error {amp_err:e} vs scipy {scipy_amp:e}"
        );
        assert!(
            phase < 2.0 * scipy_phase,
            "rtol {rtol}: phase error {phase:e} vs scipy {scipy_phase:e}"
        );
    }
}

/// Two dofs, one slightly unstable mode (sigma = +0.02, omega = 1) and one
/// damped mode (sigma = -0.5, omega = 2.9), mixed by a non-orthogonal change
/// of variables. Once the damped mode has died out, the peaks of x1 grow like
/// e^{sigma t}: the rate fitted through successive peaks (located by the
/// oscillation monitor on the dense output) matches sigma within 1e-4
/// (rtol 1e-9: the peaks are exact to ~1e-8 relative, over a 15-unit span of
/// ln-amplitude change 0.3 that is ~1e-7 absolute on the rate; the 1e-4
/// leaves room for the e^{-0.5 t} mode, < e^{-20} at the first peak used).
#[test]
fn growth_rate_from_peaks() {
    let (s1, w1, s2, w2) = (0.02, 1.0, -0.5, 2.9);
    // Modal block matrix in z = (u1, v1, u2, v2), then y = P z.
    let m = [
        [s1, -w1, 0.0, 0.0],
        [w1, s1, 0.0, 0.0],
        [0.0, 0.0, s2, -w2],
        [0.0, 0.0, w2, s2],
    ];
    let p = [
        [1.0, 0.3, 0.5, 0.0],
        [0.2, 1.0, 0.0, 0.4],
        [0.6, 0.0, 1.0, 0.1],
        [0.0, 0.5, 0.3, 1.0],
    ];
    let pinv = invert4(p);
    let mut a = vec![vec![0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            a[i][j] = (0..4)
                .flat_map(|k| (0..4).map(move |l| (k, l)))
                .map(|(k, l)| p[i][k] * m[k][l] * pinv[l][j])
                .sum();
        }
    }
    let sys = Linear { a };
    let opts = opts(1e-9, 1e-12);
    let mut bdf = Bdf::new(&sys, 0.0, &[1.0, 0.0, 1.0, 0.0], 120.0, &opts).unwrap();
    let steady = SteadyOptions::default();
    let mut mon = OscillationMonitor::new(4, |y: &[f64]| y[0], &steady).unwrap();
    mon.observe(&bdf).unwrap();
    let mut peaks = Vec::new();
    let mut seen = 0;
    while !bdf.is_finished() {
        bdf.step().unwrap();
        mon.observe(&bdf).unwrap();
        if mon.cycles_completed() > seen {
            seen = mon.cycles_completed();
            let r = *mon.window().back().unwrap();
            if r.t_max > 40.0 {
                peaks.push((r.t_max, r.max.ln()));
            }
        }
    }
    assert!(peaks.len() >= 10, "only {} peaks", peaks.len());
    let rate = fit_slope(&peaks);
    println!(
        "growth rate {rate:.8} (eigenvalue real part {s1}) from {} peaks",
        peaks.len()
    );
    assert!((rate - s1).abs() < 1e-4, "rate {rate}");
    // Successive periods equal 2 pi / omega_1 (linear system: exact).
    let r = mon.window().back().unwrap();
    assert!(
        (r.period - 2.0 * std::f64::consts::PI / w1).abs() < 1e-6,
        "period {}",
        r.period
    );
}

fn invert4(a: [[f64; 4]; 4]) -> [[f64; 4]; 4] {
    // Gauss-Jordan with partial pivoting on [A | I].
    let mut m = [[0.0; 8]; 4];
    for i in 0..4 {
        m[i][..4].copy_from_slice(&a[i]);
        m[i][4 + i] = 1.0;
    }
    for c in 0..4 {
        let p = (c..4)
            .max_by(|&x, &y| m[x][c].abs().total_cmp(&m[y][c].abs()))
            .unwrap();
        m.swap(c, p);
        let d = m[c][c];
        for v in m[c].iter_mut() {
            *v /= d;
        }
        for r in 0..4 {
            if r != c {
                let f = m[r][c];
                let row = m[c];
                for (v, w) in m[r].iter_mut().zip(row) {
                    *v -= f * w;
                }
            }
        }
    }
    let mut inv = [[0.0; 4]; 4];
    for i in 0..4 {
        inv[i].copy_from_slice(&m[i][4..]);
    }
    inv
}
