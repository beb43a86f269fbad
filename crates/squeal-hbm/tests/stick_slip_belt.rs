//! The mass on a moving belt, `m x'' + k x = F`, with Coulomb friction of static coefficient
//! `μ_s` and kinetic `μ_k` under the load `N`: harmonic balance with exact stick–slip (DLFT,
//! `squeal_hbm::stick_slip`) against the closed-form stick–slip cycle.
//!
//! Closed form (Popp & Stelter 1990; den Hartog). With `x_k = μ_k N / k`, `x_s = μ_s N / k`,
//! `ω0 = sqrt(k/m)`, `d0 = x_s - x_k`: the mass sticks and moves with the belt (`x' = V`) until
//! the spring force reaches the static limit at `x = x_s`; it then slips, harmonic about the
//! kinetic offset, `x = x_k + A cos θ`, `x'/ω0 = -A sin θ`, `A = sqrt(d0² + (V/ω0)²)`, from
//! `θ = -α` to `θ = π + α` (`α = atan2(V/ω0, d0)`), where its velocity is back to `V` at
//! `x = x_k - d0`; it sticks again and rides the belt back to `x_s`. Hence
//! `T = (π + 2α)/ω0 + 2 d0 / V`, peak-to-peak `2A`, mean `x_k` (the stick ramp is symmetric
//! about `x_k`, the slip arc's cosine integrates to zero), stick fraction `2 d0 / (V T)`.

use faer::Mat;
use squeal_hbm::*;
use std::f64::consts::PI;

const M: f64 = 1.0;
const K: f64 = 1.0e4;
const N: f64 = 10.0;
const MU_K: f64 = 0.3;
const MU_S: f64 = 0.4;
const V: f64 = 0.01;

struct Exact {
    period: f64,
    amplitude: f64,
    mean: f64,
    stick_fraction: f64,
}

fn exact() -> Exact {
    let w0 = (K / M).sqrt();
    let (xk, xs) = (MU_K * N / K, MU_S * N / K);
    let d0 = xs - xk;
    let alpha = (V / w0).atan2(d0);
    let period = (PI + 2.0 * alpha) / w0 + 2.0 * d0 / V;
    Exact {
        period,
        amplitude: (d0 * d0 + (V / w0).powi(2)).sqrt(),
        mean: xk,
        stick_fraction: 2.0 * d0 / V / period,
    }
}

fn belt(h: usize, epsilon: f64, samples: Option<usize>) -> StickSlipBalance<MckStiffness, impl NonlinearForce> {
    let layout = HarmonicLayout::new(1, h).unwrap();
    let s = |v: f64| Mat::from_fn(1, 1, |_, _| v);
    let linear = MckStiffness::new(s(M).as_ref(), s(0.0).as_ref(), s(K).as_ref()).unwrap();
    let none = FnForce::new(1, vec![], false, |_: &[f64], _: &[f64], _: &mut [f64], _: Option<LocalJacobian<'_>>| {});
    let hb = HarmonicBalance::new(layout, linear, none, vec![0.0; layout.len()], None).unwrap();
    let contact = FrictionContact {
        direction: vec![(0, -1.0)],
        sliding_speed: V,
        normal: NormalLoad::Constant(N),
        mu: MU_K,
        static_ratio: MU_S / MU_K,
        epsilon,
    };
    StickSlipBalance::new(hb, vec![contact], samples).unwrap()
}

/// The closed-form cycle at time `t` from the start of a slip phase.
fn exact_at(t: f64) -> f64 {
    let e = exact();
    let w0 = (K / M).sqrt();
    let (xk, xs) = (MU_K * N / K, MU_S * N / K);
    let d0 = xs - xk;
    let alpha = (V / w0).atan2(d0);
    let t_slip = (PI + 2.0 * alpha) / w0;
    let t = t.rem_euclid(e.period);
    if t < t_slip {
        xk + e.amplitude * (w0 * t - alpha).cos()
    } else {
        xk - d0 + V * (t - t_slip)
    }
}

/// Fourier coefficients (layout of eq. 25, one dof) of the closed-form cycle, by the
/// trapezoidal rule on 2^16 samples.
fn exact_coeffs(h: usize) -> Vec<f64> {
    let e = exact();
    let ns = 1 << 16;
    let mut c = vec![0.0; 2 * h + 1];
    for j in 0..ns {
        let th = 2.0 * PI * j as f64 / ns as f64;
        let x = exact_at(th / (2.0 * PI) * e.period);
        c[0] += x / ns as f64;
        for k in 1..=h {
            c[2 * k - 1] += 2.0 * x * (k as f64 * th).cos() / ns as f64;
            c[2 * k] += 2.0 * x * (k as f64 * th).sin() / ns as f64;
        }
    }
    c
}

fn solve(h: usize, epsilon: f64) -> (HbSolution, f64) {
    let mut ssb = belt(h, epsilon, None);
    let layout = ssb.layout();
    let e = exact();
    let u0 = exact_coeffs(h);
    let phase = PhaseCondition::FirstSineZero { dof: 0 };
    let sol = match solve_stick_slip(&mut ssb, phase, &u0, 2.0 * PI / e.period, N, &LmOptions::default()) {
        Ok(s) => s,
        Err(HbmError::NotConverged { report }) => { println!("NC h {h} eps {epsilon}: res {:e} (from {:e}) omega {} stop {}", report.residual_norm, report.initial_residual_norm, report.x[report.x.len()-1], report.stop); for it in report.history.iter().take(12) { println!("   {} {:e} {:e} {:e} {}", it.iteration, it.residual_norm, it.trial_residual_norm, it.damping, it.gain_ratio); } return (HbSolution { coeffs: report.x[..layout.len()].to_vec(), omega: report.x[layout.len()], report: *report }, 0.0); }
        Err(e) => panic!("{e}"),
    };
    let stick = ssb.stick_fractions()[0];
    (sol, stick)
}

#[test]
fn explore() {
    let e = exact();
    println!("exact T {} A {} mean {} stick {}", e.period, e.amplitude, e.mean, e.stick_fraction);
    for (h, eps) in [(5, 1e3), (10, 1e3), (20, 1e3), (40, 1e3), (40, 1e2), (40, 1e4), (80, 1e3)] {
        let (sol, stick) = solve(h, eps);
        let layout = HarmonicLayout::new(1, h).unwrap();
        let mut xs = vec![0.0];
        let (mut mx, mut mn) = (f64::MIN, f64::MAX);
        for j in 0..4096 {
            layout.displacement_at(&sol.coeffs, 2.0 * PI * j as f64 / 4096.0, &mut xs).unwrap();
            mx = mx.max(xs[0]);
            mn = mn.min(xs[0]);
        }
        println!("H {h}: T {:.6e} ({:.2e}) p2p/2 {:.2e} mean {:.2e} stick {:.4} iters {}", sol.period(), sol.period() / e.period - 1.0, (mx - mn) / 2.0 / e.amplitude - 1.0, sol.coeffs[0] / e.mean - 1.0, stick, sol.report.iterations);
    }
}

#[test]
fn jacobian_fd() {
    let h = 20;
    let mut ssb = belt(h, 1000.0, None);
    let layout = ssb.layout();
    let len = layout.len();
    let u = exact_coeffs(h);
    let om = 93.6;
    let mut j = Mat::zeros(len, len);
    let mut jo = vec![0.0; len];
    ssb.jacobian(&u, om, j.as_mut(), &mut jo).unwrap();
    let (mut rp, mut rm) = (vec![0.0; len], vec![0.0; len]);
    for c in 0..=len {
        let step = if c < len { 1e-11 } else { 1e-6 };
        let (mut up, mut um) = (u.clone(), u.clone());
        let (mut op, mut omm) = (om, om);
        if c < len { up[c] += step; um[c] -= step; } else { op += step; omm -= step; }
        ssb.residual(&up, op, &mut rp).unwrap();
        ssb.residual(&um, omm, &mut rm).unwrap();
        for i in 0..len {
            let fd = (rp[i] - rm[i]) / (2.0 * step);
            let an = if c < len { j[(i, c)] } else { jo[i] };
            if (fd - an).abs() > 1e-3 * (an.abs() + 1.0) && c < 3 {
                println!("({i},{c}) fd {fd} an {an}");
            }
        }
    }
}

#[test]
fn debug_a() {
    let h = 40;
    let e = exact();
    let c = exact_coeffs(h);
    let w = 2.0 * PI / e.period;
    let eps = 1000.0;
    let ns = 2048;
    let mut prev = "";
    for j in 0..ns {
        let th = 2.0 * PI * j as f64 / ns as f64;
        let (mut x, mut v, mut acc) = (c[0], 0.0, 0.0);
        for k in 1..=h {
            let kf = k as f64;
            let (s, co) = (kf * th).sin_cos();
            x += c[2 * k - 1] * co + c[2 * k] * s;
            v += kf * w * (-c[2 * k - 1] * s + c[2 * k] * co);
            acc -= (kf * w).powi(2) * (c[2 * k - 1] * co + c[2 * k] * s);
        }
        let a = M * acc + K * x + eps * (V - v);
        let st = if a.abs() <= MU_K * N { "stick" } else if a.abs() > MU_S * N { "slip" } else { "amb" };
        if st != prev || j % 128 == 0 {
            println!("j {j} x {x:.4e} v {v:.4e} a {a:.4} {st}");
            prev = st;
        }
    }
}

#[test]
fn ladder() {
    let e = exact();
    let mut prev: Option<(Vec<f64>, f64, usize)> = None;
    for h in [5, 10, 20, 40, 80] {
        let mut ssb = belt(h, 1000.0, None);
        let layout = ssb.layout();
        let (u0, w0) = match &prev {
            None => (exact_coeffs(h), 2.0 * PI / e.period),
            Some((u, w, hp)) => {
                let mut u0 = vec![0.0; layout.len()];
                u0[..2 * hp + 1].copy_from_slice(u);
                (u0, *w)
            }
        };
        let phase = PhaseCondition::FirstSineZero { dof: 0 };
        match solve_stick_slip(&mut ssb, phase, &u0, w0, N, &LmOptions { max_iterations: 400, ..LmOptions::default() }) {
            Ok(sol) => {
                println!("H {h}: T err {:.3e} mean err {:.3e} stick {:.4} (exact {:.4}) iters {}", sol.period() / e.period - 1.0, sol.coeffs[0] / e.mean - 1.0, ssb.stick_fractions()[0], e.stick_fraction, sol.report.iterations);
                prev = Some((sol.coeffs.clone(), sol.omega, h));
            }
            Err(HbmError::NotConverged { report }) => { println!("H {h} NC res {:e} from {:e}", report.residual_norm, report.initial_residual_norm); break; }
            Err(er) => panic!("{er}"),
        }
    }
}
