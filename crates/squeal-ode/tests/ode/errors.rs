//! Failure modes: every one ends in a typed error, never a silent answer.

use super::common;

use common::{Linear, complex_pair};
use faer::MatMut;
use squeal_ode::{
    Atol, Bdf, BdfOptions, FixedStep, OdeError, OdeSystem, SteadyOptions, run_to_steady_state,
    solve,
};

/// y' = y^2, y(0) = 1: y = 1/(1 - t) blows up at t = 1.
struct BlowUp;
impl OdeSystem for BlowUp {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[0] * y[0];
    }
    fn jacobian(&self, _t: f64, y: &[f64], mut jac: MatMut<'_, f64>) {
        jac[(0, 0)] = 2.0 * y[0];
    }
}

/// Finite only for t <= 0.5.
struct NanAfterHalf;
impl OdeSystem for NanAfterHalf {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, t: f64, _y: &[f64], dy: &mut [f64]) {
        dy[0] = if t > 0.5 { f64::NAN } else { 1.0 };
    }
    fn jacobian(&self, _t: f64, _y: &[f64], mut jac: MatMut<'_, f64>) {
        jac[(0, 0)] = 0.0;
    }
}

/// Jacobian with a NaN entry.
struct NanJacobian;
impl OdeSystem for NanJacobian {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = -y[0];
    }
    fn jacobian(&self, _t: f64, _y: &[f64], mut jac: MatMut<'_, f64>) {
        jac[(0, 0)] = f64::NAN;
    }
}

/// The blow-up at t = 1 stops the run with a step-size or Newton error at
/// t in [0.999, 1): the solution there exceeds 1e3, far past rtol control.
#[test]
fn blow_up_is_an_error() {
    let opts = {
        let mut o = BdfOptions::default();
        o.rtol = 1e-6;
        o.atol = Atol::Scalar(1e-9);
        o
    };
    let err = solve(BlowUp, 0.0, &[1.0], &[2.0], &opts).unwrap_err();
    let t = match err {
        OdeError::StepSizeTooSmall { t, .. }
        | OdeError::NewtonFailure { t, .. }
        | OdeError::NonFinite { t, .. } => t,
        other => panic!("unexpected {other:?}"),
    };
    assert!((0.999..1.0).contains(&t), "stopped at {t}");
}

/// A right-hand side that turns NaN at t > 0.5 stops the run with NonFinite
/// just before 0.5 (the step is halved down to 10 ulp of t, ~1e-15).
#[test]
fn nan_rhs_is_an_error() {
    let err = solve(NanAfterHalf, 0.0, &[0.0], &[1.0], &BdfOptions::default()).unwrap_err();
    match err {
        OdeError::NonFinite { what, t } => {
            assert_eq!(what, "right-hand side");
            assert!(t <= 0.5 && t > 0.5 - 1e-9, "t {t}");
        }
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn nan_jacobian_is_an_error() {
    let err = Bdf::new(NanJacobian, 0.0, &[1.0], 1.0, &BdfOptions::default()).err();
    assert_eq!(
        err,
        Some(OdeError::NonFinite {
            what: "Jacobian",
            t: 0.0
        })
    );
}

#[test]
fn too_many_steps() {
    let opts = {
        let mut o = BdfOptions::default();
        o.max_steps = 10;
        o
    };
    let err = solve(complex_pair(0.0, 1.0), 0.0, &[1.0, 0.0], &[100.0], &opts).unwrap_err();
    assert!(
        matches!(err, OdeError::TooManySteps { max_steps: 10, .. }),
        "{err:?}"
    );
}

#[test]
fn invalid_inputs() {
    let sys = complex_pair(0.0, 1.0);
    let o = BdfOptions::default();
    assert!(matches!(
        Bdf::new(&sys, 0.0, &[1.0], 1.0, &o).err(),
        Some(OdeError::DimensionMismatch {
            expected: 2,
            got: 1,
            ..
        })
    ));
    let bad_atol = {
        let mut o = BdfOptions::default();
        o.atol = Atol::PerComponent(vec![1e-6]);
        o
    };
    assert!(Bdf::new(&sys, 0.0, &[1.0, 0.0], 1.0, &bad_atol).is_err());
    let bad_order = {
        let mut o = BdfOptions::default();
        o.max_order = 6;
        o
    };
    assert!(Bdf::new(&sys, 0.0, &[1.0, 0.0], 1.0, &bad_order).is_err());
    assert!(Bdf::new(&sys, 1.0, &[1.0, 0.0], 0.0, &o).is_err());
    assert!(Bdf::new(&sys, 0.0, &[f64::NAN, 0.0], 1.0, &o).is_err());
    assert!(solve(&sys, 0.0, &[1.0, 0.0], &[], &o).is_err());
    assert!(solve(&sys, 0.0, &[1.0, 0.0], &[2.0, 1.0], &o).is_err());
}

/// Dense output only inside the last step; no step after the end.
#[test]
fn out_of_range_and_finished() {
    let sys = complex_pair(0.0, 1.0);
    let mut bdf = Bdf::new(&sys, 0.0, &[1.0, 0.0], 1.0, &BdfOptions::default()).unwrap();
    bdf.step().unwrap();
    let mut out = [0.0; 2];
    let beyond = bdf.t() + 0.1;
    assert!(matches!(
        bdf.interpolate(beyond, &mut out),
        Err(OdeError::OutOfRange { .. })
    ));
    while !bdf.is_finished() {
        bdf.step().unwrap();
    }
    assert_eq!(bdf.t(), 1.0);
    assert_eq!(bdf.step(), Err(OdeError::Finished { t_end: 1.0 }));
}

/// With one Newton iteration allowed, the convergence test (which needs a
/// rate, i.e. two iterations) cannot pass: a fixed-step run must fail with
/// NewtonFailure rather than accept an unconverged step.
#[test]
fn fixed_step_newton_failure() {
    let opts = {
        let mut o = BdfOptions::default();
        o.fixed_step = Some(FixedStep { h: 0.1, order: 1 });
        o.max_newton_iter = 1;
        o
    };
    let sys = Linear {
        a: vec![vec![-1.0]],
    };
    let mut bdf = Bdf::new(&sys, 0.0, &[1.0], 1.0, &opts).unwrap();
    assert!(matches!(bdf.step(), Err(OdeError::NewtonFailure { .. })));
}

/// A decaying oscillation never becomes steady: NotSteady at the end time.
#[test]
fn decaying_oscillation_is_not_steady() {
    let sys = complex_pair(-0.05, 1.0);
    let opts = {
        let mut o = BdfOptions::default();
        o.rtol = 1e-8;
        o.atol = Atol::Scalar(1e-10);
        o
    };
    let mut bdf = Bdf::new(&sys, 0.0, &[0.0, -1.0], 100.0, &opts).unwrap();
    let err =
        run_to_steady_state(&mut bdf, |y: &[f64]| y[1], &SteadyOptions::default()).unwrap_err();
    match err {
        OdeError::NotSteady { cycles, t, .. } => {
            assert_eq!(t, 100.0);
            // 100 / (2 pi) = 15.9 periods: 14 or 15 complete cycles.
            assert!((14..=15).contains(&cycles), "{cycles} cycles");
        }
        other => panic!("unexpected {other:?}"),
    }
}

/// Issue 22: the message said "last peak-to-peak amplitude 1.277e0" with no unit and no word
/// of what oscillated. It now names the observable, its unit and what the number is.
#[test]
fn not_steady_names_the_observable_its_unit_and_the_peak_to_peak() {
    let sys = complex_pair(-0.05, 1.0);
    let opts = {
        let mut o = BdfOptions::default();
        o.rtol = 1e-8;
        o.atol = Atol::Scalar(1e-10);
        o
    };
    let mut bdf = Bdf::new(&sys, 0.0, &[0.0, -1.0], 100.0, &opts).unwrap();
    let steady = {
        let mut o = SteadyOptions::default();
        o.observable = "velocity of the mass".into();
        o.unit = "m/s".into();
        o
    };
    let err = run_to_steady_state(&mut bdf, |y: &[f64]| y[1], &steady).unwrap_err();
    let OdeError::NotSteady {
        last_peak_to_peak, ..
    } = &err
    else {
        panic!("unexpected {err:?}");
    };
    let shown = err.to_string();
    assert!(
        shown.contains(&format!(
            "its velocity of the mass went {last_peak_to_peak:.3e} m/s from lowest to highest (peak-to-peak)"
        )),
        "{shown}"
    );
    assert!(!shown.contains("amplitude"), "{shown}");
}
