//! The nonlinear force of a quasi-periodic harmonic balance: `f(x, ẋ)` from `n` inputs to `m`
//! outputs, evaluated pointwise on the torus grid.
//!
//! A square force (`m = n`) is a [`NonlinearForce`]; [`Square`] lends it to the torus. The
//! outputs may differ from the inputs when the linear part maps the force back through a
//! frequency-dependent matrix (the receptance form of [`super::TorusLinear`]): a contact force
//! that depends on the normal gaps only and acts along normals and tangents is then a map from
//! the gaps to the force components.

use crate::HbmError;
use crate::force::{LocalJacobian, NonlinearForce};

/// A pointwise force `f: (x, ẋ) ∈ R^n × R^n -> R^m` with sparse local Jacobians.
pub trait TorusForce {
    /// `n`, the length of `x` and `ẋ`.
    fn n_inputs(&self) -> usize;

    /// `m`, the length of `f`.
    fn n_outputs(&self) -> usize;

    /// Entries `(i, k)` (`i < m`, `k < n`) of `∂f/∂x` and `∂f/∂ẋ` that may be nonzero, no
    /// duplicates.
    fn pattern(&self) -> &[(usize, usize)];

    /// Whether `f` depends on `ẋ`.
    fn depends_on_velocity(&self) -> bool;

    /// `f(x, ẋ)` (and the local Jacobians in pattern order); `f` and the Jacobian slices
    /// arrive zeroed.
    fn eval(&self, x: &[f64], xdot: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>);
}

/// A square [`NonlinearForce`] as a [`TorusForce`].
pub struct Square<F>(pub F);

impl<F: NonlinearForce> TorusForce for Square<F> {
    fn n_inputs(&self) -> usize {
        self.0.n_dofs()
    }

    fn n_outputs(&self) -> usize {
        self.0.n_dofs()
    }

    fn pattern(&self) -> &[(usize, usize)] {
        self.0.pattern()
    }

    fn depends_on_velocity(&self) -> bool {
        self.0.depends_on_velocity()
    }

    fn eval(&self, x: &[f64], xdot: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>) {
        self.0.eval(x, xdot, f, jac)
    }
}

/// Checks the pattern of `force`: inside `m × n`, no entry twice.
pub(crate) fn check_pattern<F: TorusForce + ?Sized>(force: &F) -> Result<(), HbmError> {
    let (m, n) = (force.n_outputs(), force.n_inputs());
    if let Some(&(row, col)) = force.pattern().iter().find(|&&(r, c)| r >= m || c >= n) {
        return Err(HbmError::PatternOutOfRange {
            row,
            col,
            n_dofs: m.max(n),
        });
    }
    let mut sorted = force.pattern().to_vec();
    sorted.sort_unstable();
    if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
        return Err(HbmError::PatternDuplicate {
            row: w[0].0,
            col: w[0].1,
        });
    }
    Ok(())
}
