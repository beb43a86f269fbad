//! The equilibria of a projected sweep ([`crate::projected`]): Newton's method for eq (14)
//! with its steps solved in the modal basis, `K_t⁻¹ b = Φ T(0)⁻¹ Φᵀ b` (a diagonal plus
//! rank-`P` solve, [`crate::linearized`]), or by dense LU steps where those are cheaper (a
//! brake with as many contact pairs as a third of its dofs: `dense_steps_cheaper`), each
//! from the linear extrapolation of the two equilibria before it (module documentation of
//! [`crate::projected`]).

use crate::equilibrium::{Equilibrium, NewtonOptions, static_equilibrium, static_equilibrium_with};
use crate::error::BrakeError;
use crate::linearized::LinearizedBrake;
use crate::model::Brake;
use crate::spectrum::Reference;
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par, c64};

/// The equilibrium at `mu` from `from` (from scratch without), its Newton steps solved in the
/// modal basis (module documentation); the dense steps of [`static_equilibrium`] when that
/// fails.
pub(crate) fn equilibrium(
    brake: &Brake,
    reference: &Reference,
    lr: &LinearizedBrake,
    mu: f64,
    from: Option<&[f64]>,
    newton: &NewtonOptions,
) -> Result<Equilibrium, BrakeError> {
    // The frictionless equilibrium is a start as good as any for the first friction value,
    // and spares the load ramp's dense steps.
    let from = from.unwrap_or(reference.equilibrium.x.as_slice());
    match modal_newton(brake, lr, reference, mu, from, newton) {
        Ok(eq) => Ok(eq),
        Err(_) => static_equilibrium(brake, mu, Some(from), newton),
    }
}

/// The state at `mu` extrapolated linearly from the equilibria `last` and `before` it: the
/// path `x(μ)` is smooth while the contact does not change, and the extrapolation's error
/// (`O(Δμ²)`) saves the sweep's Newton iterations one of two.
pub(crate) fn predicted(last: &Equilibrium, before: &Equilibrium, mu: f64) -> Vec<f64> {
    let s = (mu - last.mu) / (last.mu - before.mu);
    last.x
        .iter()
        .zip(&before.x)
        .map(|(a, b)| a + s * (a - b))
        .collect()
}

/// Newton's method for the equilibrium at `mu` from `x`, its steps solved in the modal basis
/// (no dense fallback), or by dense LU steps where those are cheaper ([`dense_steps_cheaper`]).
pub(crate) fn modal_newton(
    brake: &Brake,
    lr: &LinearizedBrake,
    reference: &Reference,
    mu: f64,
    x: &[f64],
    newton: &NewtonOptions,
) -> Result<Equilibrium, BrakeError> {
    if dense_steps_cheaper(lr) {
        return static_equilibrium(brake, mu, Some(x), newton);
    }
    let phi = &reference.basis.phi;
    let solve = |x: &[f64], b: &[f64]| modal_tangent_solve(brake, lr, phi, mu, x, b);
    static_equilibrium_with(brake, mu, Some(x), newton, Some(&solve))
}

/// Whether a Newton step by a dense LU of the `n × n` tangent stiffness (`2/3 n³` flops) is
/// cheaper than the modal step's factorization of `T(0)` as the diagonal plus the coupling of
/// rank `r >= P` ([`crate::linearized`]: a complex bordered system of size about `r`, factored
/// with its adjoint, about `21 r³`): so when `r > 0.3 n`, as on an interface-reduced brake
/// with nodal contact (510 dofs, 360 pairs on the medium ventilated brake), where the modal
/// steps took 4.5 s of a 41-point sweep's equilibria (docs/benchmarks.md).
fn dense_steps_cheaper(lr: &LinearizedBrake) -> bool {
    let (n, r) = (lr.size() as f64, lr.pairs() as f64);
    21.0 * r.powi(3) > 2.0 / 3.0 * n.powi(3)
}

/// `K_t(x)⁻¹ b = Φ T(0)⁻¹ Φᵀ b`, `None` when not finite.
fn modal_tangent_solve(
    brake: &Brake,
    lr: &LinearizedBrake,
    phi: &Mat<f64>,
    mu: f64,
    x: &[f64],
    b: &[f64],
) -> Option<Vec<f64>> {
    let n = b.len();
    let responses = brake
        .pairs
        .iter()
        .map(|p| p.response(x, None, mu))
        .collect();
    let c = lr.coupling_of(mu, responses, Vec::new());
    // Φᵀ b and Φ y as blocked products (sequential: the bits do not depend on the thread
    // count); a pass over the n x n basis is the cost of a step.
    let product = |a: faer::MatRef<'_, f64>, v: &[f64]| -> Mat<f64> {
        let mut out = Mat::<f64>::zeros(a.nrows(), 1);
        matmul(
            out.as_mut(),
            Accum::Replace,
            a,
            faer::ColRef::from_slice(v).as_mat(),
            1.0,
            Par::Seq,
        );
        out
    };
    let pb = product(phi.transpose(), b);
    let q: Vec<c64> = (0..n).map(|j| c64::new(pb[(j, 0)], 0.0)).collect();
    let y = lr.factor(&c, c64::new(0.0, 0.0)).solve(lr, &c, &q);
    let y_re: Vec<f64> = y.iter().map(|v| v.re).collect();
    let dx = product(phi.as_ref(), &y_re);
    let dx: Vec<f64> = (0..n).map(|i| dx[(i, 0)]).collect();
    dx.iter().all(|v| v.is_finite()).then_some(dx)
}
