//! Levenberg-Marquardt on standard test functions (Moré, Garbow & Hillstrom, "Testing
//! unconstrained optimization software", ACM TOMS 7, 1981) with known minima.

use std::convert::Infallible;

use faer::MatMut;
use squeal_hbm::lm::{self, LeastSquaresProblem, LmError, LmOptions, LmStop};

/// A problem from closures for the residual and the Jacobian.
struct Closure<R, J> {
    n: usize,
    m: usize,
    r: R,
    j: J,
}

impl<R, J> LeastSquaresProblem for Closure<R, J>
where
    R: FnMut(&[f64], &mut [f64]),
    J: FnMut(&[f64], MatMut<'_, f64>),
{
    type Error = Infallible;
    fn n_params(&self) -> usize {
        self.n
    }
    fn n_residuals(&self) -> usize {
        self.m
    }
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), Infallible> {
        (self.r)(z, r);
        Ok(())
    }
    fn jacobian(&mut self, z: &[f64], jac: MatMut<'_, f64>) -> Result<(), Infallible> {
        (self.j)(z, jac);
        Ok(())
    }
}

/// Default options with only the absolute residual criterion (`||r|| <= 1e-10`).
fn absolute_only() -> LmOptions {
    {
        let mut o = LmOptions::default();
        o.rel_tol = 0.0;
        o
    }
}

fn rosenbrock() -> impl LeastSquaresProblem<Error = Infallible> {
    Closure {
        n: 2,
        m: 2,
        r: |x: &[f64], r: &mut [f64]| {
            r[0] = 10.0 * (x[1] - x[0] * x[0]);
            r[1] = 1.0 - x[0];
        },
        j: |x: &[f64], mut j: MatMut<'_, f64>| {
            j[(0, 0)] = -20.0 * x[0];
            j[(0, 1)] = 10.0;
            j[(1, 0)] = -1.0;
            j[(1, 1)] = 0.0;
        },
    }
}

#[test]
fn rosenbrock_reaches_its_minimum() {
    // MGH #1 from (-1.2, 1): minimum 0 at (1, 1). J is nonsingular there with
    // ||J^-1|| ~ 1, so ||r|| <= 1e-10 pins x to about 1e-10; 1e-9 leaves margin.
    let report = lm::solve(&mut rosenbrock(), &[-1.2, 1.0], &absolute_only()).unwrap();
    assert!(report.stop.is_converged());
    assert!(report.residual_norm <= 1e-10);
    assert!(
        (report.x[0] - 1.0).abs() < 1e-9 && (report.x[1] - 1.0).abs() < 1e-9,
        "{:?}",
        report.x
    );
    // History: one entry per trial, accepted residual norms never increase.
    assert_eq!(report.history.len(), report.iterations);
    let accepted: Vec<f64> = report
        .history
        .iter()
        .filter(|h| h.accepted)
        .map(|h| h.residual_norm)
        .collect();
    assert_eq!(accepted.len(), report.accepted_steps);
    assert!(accepted.windows(2).all(|w| w[1] < w[0]));
    println!(
        "Rosenbrock: {} trials, {} accepted",
        report.iterations, report.accepted_steps
    );
    // Gauss–Newton first (an LU of the square J while lambda <= 1e-3): the same root to the
    // same 1e-9 (the residual tolerance pins it either way), at least one Gauss–Newton trial
    // (recorded with damping 0) accepted, and no more trials than the damped iteration's.
    let mut o = absolute_only();
    o.newton_damping = 1e-3;
    let gn = lm::solve(&mut rosenbrock(), &[-1.2, 1.0], &o).unwrap();
    assert!(gn.stop.is_converged() && gn.residual_norm <= 1e-10);
    assert!(
        (gn.x[0] - 1.0).abs() < 1e-9 && (gn.x[1] - 1.0).abs() < 1e-9,
        "{:?}",
        gn.x
    );
    let newton_accepted = gn
        .history
        .iter()
        .filter(|h| h.damping == 0.0 && h.accepted)
        .count();
    println!(
        "Rosenbrock, Gauss-Newton first: {} trials, {newton_accepted} Gauss-Newton accepted",
        gn.iterations
    );
    assert!(newton_accepted >= 1);
    assert!(gn.iterations <= report.iterations);
}

#[test]
fn powell_singular_reaches_its_minimum() {
    // MGH #13 from (3, -1, 0, 1): minimum 0 at the origin, where J is singular (rank 2),
    // so convergence is only linear and x is determined to about sqrt(||r||): with
    // ||r|| <= 1e-10 every |x_i| <= 1e-4 is the honest bound.
    let s5 = 5f64.sqrt();
    let s10 = 10f64.sqrt();
    let mut p = Closure {
        n: 4,
        m: 4,
        r: move |x: &[f64], r: &mut [f64]| {
            r[0] = x[0] + 10.0 * x[1];
            r[1] = s5 * (x[2] - x[3]);
            r[2] = (x[1] - 2.0 * x[2]).powi(2);
            r[3] = s10 * (x[0] - x[3]).powi(2);
        },
        j: move |x: &[f64], mut j: MatMut<'_, f64>| {
            j.fill(0.0);
            j[(0, 0)] = 1.0;
            j[(0, 1)] = 10.0;
            j[(1, 2)] = s5;
            j[(1, 3)] = -s5;
            let a = 2.0 * (x[1] - 2.0 * x[2]);
            j[(2, 1)] = a;
            j[(2, 2)] = -2.0 * a;
            let b = 2.0 * s10 * (x[0] - x[3]);
            j[(3, 0)] = b;
            j[(3, 3)] = -b;
        },
    };
    let report = lm::solve(&mut p, &[3.0, -1.0, 0.0, 1.0], &absolute_only()).unwrap();
    assert!(report.residual_norm <= 1e-10);
    assert!(report.x.iter().all(|v| v.abs() < 1e-4), "{:?}", report.x);
    println!(
        "Powell singular: {} trials, |r| = {:e}",
        report.iterations, report.residual_norm
    );
    // Gauss–Newton first, with J singular at the root: the damped step takes over where the
    // LU's step fails; the same bounds.
    let mut o = absolute_only();
    o.newton_damping = 1e-3;
    let gn = lm::solve(&mut p, &[3.0, -1.0, 0.0, 1.0], &o).unwrap();
    assert!(gn.residual_norm <= 1e-10);
    assert!(gn.x.iter().all(|v| v.abs() < 1e-4), "{:?}", gn.x);
    println!(
        "Powell singular, Gauss-Newton first: {} trials",
        gn.iterations
    );
}

fn freudenstein_roth() -> impl LeastSquaresProblem<Error = Infallible> {
    Closure {
        n: 2,
        m: 2,
        r: |x: &[f64], r: &mut [f64]| {
            r[0] = -13.0 + x[0] + ((5.0 - x[1]) * x[1] - 2.0) * x[1];
            r[1] = -29.0 + x[0] + ((x[1] + 1.0) * x[1] - 14.0) * x[1];
        },
        j: |x: &[f64], mut j: MatMut<'_, f64>| {
            j[(0, 0)] = 1.0;
            j[(0, 1)] = 10.0 * x[1] - 3.0 * x[1] * x[1] - 2.0;
            j[(1, 0)] = 1.0;
            j[(1, 1)] = 3.0 * x[1] * x[1] + 2.0 * x[1] - 14.0;
        },
    }
}

#[test]
fn local_minimum_is_reported_as_not_converged() {
    // MGH #2 from (0.5, -2) is attracted to the local minimum f = sum r^2 = 48.9842...
    // at (11.41..., -0.8968...), not the root (5, 4). The solver must say so with a typed
    // error carrying the report. f at the local min is 48.98425367924 (MGH); the stop
    // happens once the scaled gradient is ~1e-12, so f agrees to ~1e-9 relative.
    let err = lm::solve(
        &mut freudenstein_roth(),
        &[0.5, -2.0],
        &LmOptions::default(),
    )
    .unwrap_err();
    let LmError::NotConverged { report } = err else {
        panic!("expected NotConverged, got {err:?}");
    };
    assert!(
        matches!(report.stop, LmStop::SmallGradient | LmStop::SmallStep),
        "{:?}",
        report.stop
    );
    let f = report.residual_norm * report.residual_norm;
    assert!((f - 48.98425367924).abs() < 1e-7 * 48.98, "f = {f}");
    assert!(
        (report.x[0] - 11.4128).abs() < 1e-3 && (report.x[1] + 0.896805).abs() < 1e-5,
        "{:?}",
        report.x
    );

    // The same stop is a success when the caller asks for a least-squares minimum.
    let options = {
        let mut o = LmOptions::default();
        o.accept_stationary = true;
        o
    };
    let report = lm::solve(&mut freudenstein_roth(), &[0.5, -2.0], &options).unwrap();
    assert!(!report.stop.is_converged());
}

#[test]
fn box_3d_overdetermined_reaches_zero_residual() {
    // MGH #12 with m = 10 residuals in 3 unknowns from (0, 10, 20): a consistent
    // overdetermined system with minimum 0 at (1, 10, 1). Nonsingular there (rank 3),
    // so ||r|| <= 1e-10 gives x to ~1e-8.
    let t: Vec<f64> = (1..=10).map(|i| 0.1 * i as f64).collect();
    let t2 = t.clone();
    let mut p = Closure {
        n: 3,
        m: 10,
        r: move |x: &[f64], r: &mut [f64]| {
            for (ri, &ti) in r.iter_mut().zip(&t) {
                *ri = (-ti * x[0]).exp()
                    - (-ti * x[1]).exp()
                    - x[2] * ((-ti).exp() - (-10.0 * ti).exp());
            }
        },
        j: move |x: &[f64], mut j: MatMut<'_, f64>| {
            for (i, &ti) in t2.iter().enumerate() {
                j[(i, 0)] = -ti * (-ti * x[0]).exp();
                j[(i, 1)] = ti * (-ti * x[1]).exp();
                j[(i, 2)] = -((-ti).exp() - (-10.0 * ti).exp());
            }
        },
    };
    let report = lm::solve(&mut p, &[0.0, 10.0, 20.0], &absolute_only()).unwrap();
    assert!(report.residual_norm <= 1e-10);
    let want = [1.0, 10.0, 1.0];
    for (x, w) in report.x.iter().zip(want) {
        assert!((x - w).abs() < 1e-6, "{:?}", report.x);
    }
}

#[test]
fn iteration_limit_is_a_typed_failure() {
    // Three trials cannot solve Rosenbrock from (-1.2, 1) (it needs about 20): the error
    // must say MaxIterations and carry a three-entry history.
    let options = {
        let mut o = LmOptions::default();
        o.max_iterations = 3;
        o
    };
    match lm::solve(&mut rosenbrock(), &[-1.2, 1.0], &options) {
        Err(LmError::NotConverged { report }) => {
            assert_eq!(report.stop, LmStop::MaxIterations);
            assert_eq!(report.history.len(), 3);
            assert!(report.residual_norm > 1e-3);
        }
        other => panic!("expected MaxIterations, got {other:?}"),
    }
    let bad = {
        let mut o = LmOptions::default();
        o.abs_tol = f64::NAN;
        o
    };
    assert!(matches!(
        lm::solve(&mut rosenbrock(), &[0.0, 0.0], &bad),
        Err(LmError::BadOption(_))
    ));
    assert!(matches!(
        lm::solve(&mut rosenbrock(), &[0.0], &LmOptions::default()),
        Err(LmError::BadSize(_))
    ));
}
