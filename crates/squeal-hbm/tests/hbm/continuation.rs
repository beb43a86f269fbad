//! Pseudo-arclength continuation through a fold, against closed forms and time integration.
//!
//! The oscillator `x'' - (mu + x^2 - beta x^4) x' + x = 0` has a subcritical Hopf point at
//! `mu = 0` (negative damping `-mu` turns positive through zero while the cubic term `x^2 x'`
//! pumps energy into larger motions). With one harmonic, `x = A cos(wt)`, the harmonic balance
//! equations are solved in closed form: the cosine balance gives `w = 1` (the force is odd in
//! time and has no cosine part) and the sine balance is the energy balance over a cycle,
//!
//! `mu <sin^2> + A^2 <cos^2 sin^2> - beta A^4 <cos^4 sin^2> = mu/2 + A^2/8 - beta A^4/16 = 0`,
//!
//! so `mu(A) = beta A^4 / 8 - A^2 / 4`: the branch leaves `mu = 0` towards negative `mu`,
//! turns at the fold `A = 1/sqrt(beta)`, `mu = -1/(8 beta)`, and comes back through `mu = 0`
//! at `A = sqrt(2/beta)`. The continuation must follow it through the fold, where `mu` is
//! not a function of the branch any more.

use faer::Mat;
use squeal_hbm::continuation::{
    Branch, ContinuationOptions, Control, HbFamily, Stop, continue_branch,
};
use squeal_hbm::{
    HarmonicBalance, HarmonicLayout, LocalJacobian, MckStiffness, NonlinearForce, PhaseCondition,
    RowScales,
};

const BETA: f64 = 1.0;
/// Harmonics after the switch.
const H: usize = 21;

/// `f = -(mu + x^2 - beta x^4) x'`, with `mu` the continuation parameter.
struct Pump {
    mu: f64,
    pattern: Vec<(usize, usize)>,
}

impl NonlinearForce for Pump {
    fn n_dofs(&self) -> usize {
        1
    }
    fn pattern(&self) -> &[(usize, usize)] {
        &self.pattern
    }
    fn depends_on_velocity(&self) -> bool {
        true
    }
    fn eval(&self, x: &[f64], v: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>) {
        let (x, v) = (x[0], v[0]);
        let g = self.mu + x * x - BETA * x.powi(4);
        f[0] = -g * v;
        if let Some(j) = jac {
            j.dfdx[0] = -(2.0 * x - 4.0 * BETA * x.powi(3)) * v;
            j.dfdxdot[0] = -g;
        }
    }
}

fn build(h: usize) -> Result<HarmonicBalance<MckStiffness, Pump>, squeal_hbm::HbmError> {
    let one = Mat::from_fn(1, 1, |_, _| 1.0);
    let zero = Mat::<f64>::zeros(1, 1);
    let layout = HarmonicLayout::new(1, h)?;
    let linear = MckStiffness::new(one.as_ref(), zero.as_ref(), one.as_ref())?;
    let force = Pump {
        mu: 0.0,
        pattern: vec![(0, 0)],
    };
    HarmonicBalance::new(layout, linear, force, vec![0.0; layout.len()], None)
}

fn family(h: usize) -> impl squeal_hbm::continuation::Family {
    HbFamily::new(
        build,
        |hb: &mut HarmonicBalance<MckStiffness, Pump>, mu: f64| {
            hb.force_mut().mu = mu;
            Ok(())
        },
        h,
        PhaseCondition::FirstSineZero { dof: 0 },
        RowScales::default(),
        1e-6,
    )
    .unwrap()
}

fn mu_of(a: f64) -> f64 {
    BETA * a.powi(4) / 8.0 - a * a / 4.0
}

/// The one-harmonic start `[U0, U1c, U1s, w, mu]` at amplitude `a`, on the branch.
fn start(a: f64) -> Vec<f64> {
    vec![0.0, a, 0.0, 1.0, mu_of(a)]
}

fn follow(
    opts: &ContinuationOptions,
    observer: impl FnMut(&squeal_hbm::continuation::Point) -> Control,
) -> Branch {
    let mut fam = family(1);
    let z0 = start(0.3);
    let up = [0.0, 1.0, 0.0, 0.0, 0.0];
    continue_branch(
        &mut fam,
        &z0,
        &up,
        |l| vec![1.0; l.len() + 2],
        opts,
        observer,
    )
    .unwrap()
}

#[test]
fn one_harmonic_branch_goes_through_the_fold_on_the_closed_form() {
    let opts = {
        let mut o = ContinuationOptions::default();
        o.initial_step = 0.05;
        o.max_step = 0.1;
        o.parameter_range = (-0.5, 0.1);
        o
    };
    let branch = follow(&opts, |_| Control::Continue);
    assert_eq!(branch.stop, Stop::ParameterRange, "{}", branch.stop);
    let n = branch.points.len();
    println!(
        "{n} points; last mu {:.4}",
        branch.points[n - 1].parameter()
    );
    let mut folds = 0;
    for (i, p) in branch.points.iter().enumerate() {
        let a = p.z[1];
        // Tolerance: Newton stops at ||R|| <= 1e-9 with a step below 1e-10; the closed form
        // is exact for one harmonic, so the points sit on it to about that level (measured
        // 2e-15 or less).
        assert!(
            (p.parameter() - mu_of(a)).abs() < 1e-9,
            "point {i}: A {a} mu {}",
            p.parameter()
        );
        assert!((p.omega() - 1.0).abs() < 1e-9, "point {i}: w {}", p.omega());
        assert!(p.z[0].abs() < 1e-12 && p.z[2].abs() < 1e-12);
        if i > 0 && branch.points[i - 1].parameter_rate() * p.parameter_rate() < 0.0 {
            folds += 1;
            // The fold lies between these two points: A = 1 within the step.
            let a0 = branch.points[i - 1].z[1];
            assert!(a0 <= 1.0 && a >= 1.0, "fold bracket [{a0}, {a}]");
        }
    }
    // Exactly one fold, and the branch came back through mu = 0 beyond A = sqrt(2).
    assert_eq!(folds, 1);
    let last = &branch.points[n - 1];
    assert!(last.z[1] > 2f64.sqrt() && last.parameter() > 0.1);
    // The amplitude grows monotonically: the branch never turned back on itself.
    assert!(branch.points.windows(2).all(|w| w[1].z[1] > w[0].z[1]));
}

/// RK4 on `x'' = (mu + x^2 - beta x^4) x' - x` from `(x, v)` for `t` in `n` steps.
fn rk4(mu: f64, mut y: [f64; 2], t: f64, n: usize) -> [f64; 2] {
    let f = |y: [f64; 2]| {
        let (x, v) = (y[0], y[1]);
        [v, (mu + x * x - BETA * x.powi(4)) * v - x]
    };
    let h = t / n as f64;
    for _ in 0..n {
        let k1 = f(y);
        let k2 = f([y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]]);
        let k3 = f([y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]]);
        let k4 = f([y[0] + h * k3[0], y[1] + h * k3[1]]);
        for i in 0..2 {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    y
}

#[test]
fn harmonics_raised_along_the_branch_match_time_integration() {
    // From one harmonic, the observer asks for H = 21 once the amplitude passes 0.8; the
    // branch then continues with them. The end point's cycle (A = 1.46, beyond the fold),
    // integrated over its own period by RK4, must come back to its start. The harmonics decay
    // slowly on this strongly nonlinear cycle (|U9| = 1e-3 at A = 1.5), hence the 21.
    let opts = {
        let mut o = ContinuationOptions::default();
        o.initial_step = 0.05;
        o.max_step = 0.1;
        o.parameter_range = (-0.5, -0.02);
        o
    };
    let mut switched = false;
    let branch = follow(&opts, |p| {
        if !switched && p.z[1] > 0.8 {
            switched = true;
            Control::Harmonics(H)
        } else {
            Control::Continue
        }
    });
    assert_eq!(branch.stop, Stop::ParameterRange, "{}", branch.stop);
    let last = branch.points.last().unwrap();
    assert_eq!(last.harmonics, H);
    let layout = HarmonicLayout::new(1, H).unwrap();
    let u = &last.z[..layout.len()];
    let (w, mu) = (last.omega(), last.parameter());
    let (mut x0, mut v0) = ([0.0], [0.0]);
    layout.displacement_at(u, 0.0, &mut x0).unwrap();
    layout.velocity_at(u, w, 0.0, &mut v0).unwrap();
    let period = 2.0 * std::f64::consts::PI / w;
    let y = rk4(mu, [x0[0], v0[0]], period, 20_000);
    let gap = ((y[0] - x0[0]).powi(2) + (y[1] - v0[0]).powi(2)).sqrt();
    println!(
        "end: mu {mu:.5}, w {w:.8}, A {:.6}, closing gap {gap:.2e}",
        u[1]
    );
    // Measured 3.3e-7 (the H = 21 truncation; RK4's own error at 20k steps is ~1e-12).
    assert!(gap < 1e-5, "closing gap {gap:.2e}");
    // The higher harmonics moved the frequency off the one-harmonic value 1.
    assert!((w - 1.0).abs() > 1e-4, "w {w}");
}
