//! The nonlinear force `f_nl(x, xdot)` evaluated at one time sample, with its local Jacobians.

use crate::HbmError;

/// Local Jacobians at one time sample, stored in the order of [`NonlinearForce::pattern`]:
/// `dfdx[p] = d f_i / d x_k` and `dfdxdot[p] = d f_i / d xdot_k` for `(i, k) = pattern[p]`.
pub struct LocalJacobian<'a> {
    /// `d f / d x` in pattern order. Arrives zeroed.
    pub dfdx: &'a mut [f64],
    /// `d f / d xdot` in pattern order. Arrives zeroed; ignored when the force does not
    /// depend on velocity.
    pub dfdxdot: &'a mut [f64],
}

/// A nonlinear force `f_nl(x, xdot)` on `n` dofs, evaluated pointwise in time by the AFT
/// scheme of eq. (29).
///
/// The Jacobian is sparse: [`Self::pattern`] lists the `(row, col)` entries that may be
/// nonzero in `d f / d x` or `d f / d xdot` (one shared list). For the brake of the paper a
/// contact pair couples four dofs (tangential `x` and normal `z` of the pad node and of the
/// disc node), and the force depends on the normal gap only, so each pair contributes the
/// 4 rows x 2 columns `(x_i, z_i, x_j, z_j) x (z_i, z_j)`. The AFT Jacobian costs one FFT per
/// pattern entry, so a tight pattern is what makes it fast.
pub trait NonlinearForce {
    /// Number of dofs `n` (length of `x`, `xdot` and `f`).
    fn n_dofs(&self) -> usize;

    /// Structurally nonzero entries `(i, k)` of the local Jacobians, each `< n`, no duplicates.
    fn pattern(&self) -> &[(usize, usize)];

    /// Whether `f` depends on `xdot`. When false the velocity samples are not computed,
    /// `dfdxdot` is ignored and `dF~/domega = 0`.
    fn depends_on_velocity(&self) -> bool;

    /// Evaluates `f = f_nl(x, xdot)` at one time sample; fills the local Jacobians if `jac`
    /// is `Some`. `f` and the Jacobian slices arrive zeroed, so implementations may either
    /// assign or accumulate.
    fn eval(&self, x: &[f64], xdot: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>);
}

/// A [`NonlinearForce`] built from a closure, for small systems and tests.
///
/// ```
/// use squeal_hbm::{FnForce, LocalJacobian};
/// // Duffing spring f = g x^3 on one dof.
/// let g = 0.5;
/// let duffing = FnForce::new(1, vec![(0, 0)], false, move |x: &[f64], _v: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>| {
///     f[0] = g * x[0].powi(3);
///     if let Some(j) = jac {
///         j.dfdx[0] = 3.0 * g * x[0] * x[0];
///     }
/// });
/// ```
pub struct FnForce<G> {
    n_dofs: usize,
    pattern: Vec<(usize, usize)>,
    velocity: bool,
    func: G,
}

impl<G> FnForce<G>
where
    G: Fn(&[f64], &[f64], &mut [f64], Option<LocalJacobian<'_>>),
{
    /// Wraps `func(x, xdot, f, jac)` acting on `n_dofs` dofs with Jacobian pattern `pattern`.
    /// The pattern is checked when the force is handed to [`crate::Aft`] or
    /// [`crate::HarmonicBalance`].
    pub fn new(
        n_dofs: usize,
        pattern: Vec<(usize, usize)>,
        depends_on_velocity: bool,
        func: G,
    ) -> Self {
        Self {
            n_dofs,
            pattern,
            velocity: depends_on_velocity,
            func,
        }
    }
}

impl<G> NonlinearForce for FnForce<G>
where
    G: Fn(&[f64], &[f64], &mut [f64], Option<LocalJacobian<'_>>),
{
    fn n_dofs(&self) -> usize {
        self.n_dofs
    }

    fn pattern(&self) -> &[(usize, usize)] {
        &self.pattern
    }

    fn depends_on_velocity(&self) -> bool {
        self.velocity
    }

    fn eval(&self, x: &[f64], xdot: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>) {
        (self.func)(x, xdot, f, jac)
    }
}

/// Checks that every pattern entry is inside `n x n` and that none is repeated.
pub(crate) fn validate_pattern(pattern: &[(usize, usize)], n_dofs: usize) -> Result<(), HbmError> {
    if let Some(&(row, col)) = pattern.iter().find(|&&(r, c)| r >= n_dofs || c >= n_dofs) {
        return Err(HbmError::PatternOutOfRange { row, col, n_dofs });
    }
    let mut sorted = pattern.to_vec();
    sorted.sort_unstable();
    if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
        return Err(HbmError::PatternDuplicate {
            row: w[0].0,
            col: w[0].1,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pattern_checks() {
        assert!(validate_pattern(&[(0, 1), (1, 0)], 2).is_ok());
        assert!(matches!(
            validate_pattern(&[(0, 2)], 2),
            Err(HbmError::PatternOutOfRange { row: 0, col: 2, .. })
        ));
        assert!(matches!(
            validate_pattern(&[(1, 1), (0, 0), (1, 1)], 2),
            Err(HbmError::PatternDuplicate { row: 1, col: 1 })
        ));
    }
}
