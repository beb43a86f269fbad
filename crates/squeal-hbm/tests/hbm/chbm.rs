//! The Constrained Harmonic Balance Method on systems with known answers: van der Pol's cycle
//! (the example `chbm_van_der_pol`, run here), the secant property of the describing-function
//! linearization on a 2-dof force, and the analytic gradient of `f2` against differences.

use super::common;

#[path = "../../examples/chbm_van_der_pol.rs"]
mod van_der_pol_example;

use common::*;
use faer::{Mat, c64};
use squeal_hbm::lm::LeastSquaresProblem;
use squeal_hbm::*;

/// Hairer, Nørsett & Wanner's period of van der Pol's cycle for ε = 1.
const T_REF: f64 = 6.663_286_859_323_13;

#[test]
fn chbm_finds_van_der_pols_cycle_from_a_small_start() {
    // 15 harmonics: the series converges exponentially; the measured period error is 4e-12
    // relative, asserted 1e-9. The start has amplitude 0.2 of the cycle's 2: plain harmonic
    // balance can fall back on x = 0 from there, CHBM must not.
    let (t, a, re, _) = van_der_pol_example::van_der_pol(1.0, 15).unwrap();
    assert!((t / T_REF - 1.0).abs() < 1e-9, "period {t}");
    assert!(a > 2.0 && a < 2.03, "first harmonic {a}");
    // At a root Re λ is exactly zero (the describing function reproduces the fundamental);
    // LM stops at 1e-12, so Re λ is below that times Im λ.
    assert!(re.abs() < 1e-11, "Re lambda {re}");
    // ε = 0.1: the first-order cycle 2 cos t, period 2π (1 + ε²/16) to O(ε⁴) = 1e-4 relative.
    let (t, a, _, _) = van_der_pol_example::van_der_pol(0.1, 3).unwrap();
    let predicted = 2.0 * std::f64::consts::PI * (1.0 + 0.01 / 16.0);
    assert!(
        (t / predicted - 1.0).abs() < 1e-5,
        "period {t} vs {predicted}"
    );
    assert!((a - 2.0).abs() < 1e-3, "amplitude {a}");
}

/// A 2-dof force with stiffness and velocity terms coupling both dofs.
fn two_dof_force() -> impl NonlinearForce {
    FnForce::new(
        2,
        vec![(0, 0), (0, 1), (1, 0), (1, 1)],
        true,
        |x: &[f64], v: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>| {
            f[0] = 2.0 * x[0].powi(3) + 0.5 * x[1] * x[1] * v[0];
            f[1] = x[0] * x[1] + 0.3 * x[1].powi(3) + 0.2 * v[1] * x[0] * x[0];
            if let Some(j) = jac {
                j.dfdx[0] = 6.0 * x[0] * x[0];
                j.dfdx[1] = x[1] * v[0];
                j.dfdx[2] = x[1] + 0.4 * v[1] * x[0];
                j.dfdx[3] = x[0] + 0.9 * x[1] * x[1];
                j.dfdxdot[0] = 0.5 * x[1] * x[1];
                j.dfdxdot[3] = 0.2 * x[0] * x[0];
            }
        },
    )
}

fn two_dof_hb(h: usize) -> HarmonicBalance<MckStiffness, impl NonlinearForce> {
    let layout = HarmonicLayout::new(2, h).unwrap();
    let m = Mat::from_fn(2, 2, |i, j| [[1.0, 0.1], [0.1, 2.0]][i][j]);
    let c = Mat::from_fn(2, 2, |i, j| [[-0.05, 0.0], [0.0, 0.02]][i][j]);
    let k = Mat::from_fn(2, 2, |i, j| [[1.0, 0.3], [-0.2, 2.5]][i][j]);
    let linear = MckStiffness::new(m.as_ref(), c.as_ref(), k.as_ref()).unwrap();
    HarmonicBalance::new(
        layout,
        linear,
        two_dof_force(),
        vec![0.0; layout.len()],
        None,
    )
    .unwrap()
}

fn point(layout: &HarmonicLayout) -> Vec<f64> {
    let mut rng = Rng::new(7);
    (0..layout.len()).map(|_| 0.3 * rng.next()).collect()
}

#[test]
fn the_describing_function_reproduces_the_fundamental_force() {
    // N(iω) X = F for any cycle (the secant property): to round-off of the O(1) entries.
    let mut hb = two_dof_hb(3);
    let layout = hb.layout();
    let u = point(&layout);
    let omega = 1.3;
    let mut r = vec![0.0; layout.len()];
    let force = hb.evaluate(&u, omega, &mut r).unwrap().force.to_vec();
    let (k0, c0) = reference_jacobian(&two_dof_force(), &u[..2]);
    let df = DescribingFunction::new(&layout, &u, omega, &force, &k0, &c0);
    let x: Vec<c64> = (0..2).map(|d| c64::new(u[2 + d], -u[4 + d])).collect();
    for i in 0..2 {
        let nx: c64 = (0..2)
            .map(|j| x[j] * c64::new(df.n_k[(i, j)], omega * df.n_c[(i, j)]))
            .sum();
        let f = c64::new(force[2 + i], -force[4 + i]);
        assert!((nx - f).norm() < 1e-14 * (1.0 + f.norm()), "{nx} vs {f}");
    }
}

#[test]
fn the_gradient_of_f2_matches_central_differences() {
    // The analytic row of f2 against central differences of the residual, at a point that is
    // not a solution. Steps of 1e-6 relative: truncation ~1e-12, rounding ~1e-10 of the row's
    // scale; asserted 1e-6 of it.
    let mut hb = two_dof_hb(2);
    let layout = hb.layout();
    let linear = MckStiffness::new(
        Mat::from_fn(2, 2, |i, j| [[1.0, 0.1], [0.1, 2.0]][i][j]).as_ref(),
        Mat::from_fn(2, 2, |i, j| [[-0.05, 0.0], [0.0, 0.02]][i][j]).as_ref(),
        Mat::from_fn(2, 2, |i, j| [[1.0, 0.3], [-0.2, 2.5]][i][j]).as_ref(),
    )
    .unwrap();
    let u = point(&layout);
    let (k0, c0) = reference_jacobian(&two_dof_force(), &[0.0, 0.0]);
    let constraint = ReLambda::new(
        DenseEigen::new(&linear),
        k0,
        c0,
        c64::new(0.02, 0.9),
        1.0,
        1.0,
    )
    .unwrap();
    let mut problem = AutonomousProblem::constrained(
        &mut hb,
        PhaseCondition::FirstSineZero { dof: 0 },
        constraint,
        RowScales::default(),
    )
    .unwrap();
    let mut z = u.clone();
    z.push(1.1);
    let (m, n) = (problem.n_residuals(), problem.n_params());
    let mut r = vec![0.0; m];
    problem.residual(&z, &mut r).unwrap();
    let mut jac = Mat::<f64>::zeros(m, n);
    problem.jacobian(&z, jac.as_mut()).unwrap();
    let scale = (0..n).map(|j| jac[(m - 1, j)].abs()).fold(0.0, f64::max);
    let (mut rp, mut rm) = (vec![0.0; m], vec![0.0; m]);
    for j in 0..n {
        let h = 1e-6 * z[j].abs().max(1e-3);
        let (mut zp, mut zm) = (z.clone(), z.clone());
        zp[j] += h;
        zm[j] -= h;
        problem.residual(&zp, &mut rp).unwrap();
        problem.residual(&zm, &mut rm).unwrap();
        let fd = (rp[m - 1] - rm[m - 1]) / (2.0 * h);
        assert!(
            (fd - jac[(m - 1, j)]).abs() < 1e-6 * scale,
            "column {j}: analytic {} vs differences {fd}",
            jac[(m - 1, j)]
        );
    }
}
