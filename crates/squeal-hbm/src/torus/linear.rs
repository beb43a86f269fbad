//! The linear part of a quasi-periodic harmonic balance, element by element in frequency.
//!
//! Each element `e` of [`super::TorusBasis`] moves at one angular frequency `w = k_e·ω`, so a
//! linear time-invariant part acts on it as on one harmonic of eq. (26) at `w`. Written for a
//! complex amplitude `X = Uc - i Us` (`x = Re(X e^{iwt})`) the equations of element `e` are
//!
//! `A(w) X + B(w) F = E`,
//!
//! with `F = Fc - i Fs` the force's coefficients and `E` the external load (static: element 0
//! only). The real rows are `Rc = Re(·)`, `Rs = -Im(·)`. Two forms are covered:
//!
//! - dynamic stiffness: `A(w) = K - w² M + i w C`, `B = I` (eqs. 27-28; [`MckTorus`]);
//! - receptance: `A = I`, `B(w) = P H(iw) Q` with `H` a receptance between the force's
//!   directions `Q` and the coordinates `P` it depends on (the reduced brake of
//!   `squeal_chbm::torus`), for which the unknowns are only the coordinates the force sees.
//!
//! `w` takes either sign (`k1 ω1 + k2 ω2` with `k2 < 0`); for a real system `A(-w) = conj A(w)`.

use faer::{Mat, MatMut, MatRef, c64};

use crate::HbmError;
use crate::linear::MckStiffness;

/// `A(w)`, `B(w)` and their `w`-derivatives, written by [`TorusLinear::blocks`] (every entry).
pub struct LinearBlocks<'a> {
    /// `A(w)` (`n × n`).
    pub a: MatMut<'a, c64>,
    /// `dA/dw`.
    pub da: MatMut<'a, c64>,
    /// `B(w)` (`n × m`; ignored when [`TorusLinear::force_map_is_identity`]).
    pub b: MatMut<'a, c64>,
    /// `dB/dw`.
    pub db: MatMut<'a, c64>,
}

/// A linear part acting element by element (module docs).
pub trait TorusLinear {
    /// `n`: unknowns per block.
    fn n_dofs(&self) -> usize;

    /// `m`: force components per block.
    fn n_forces(&self) -> usize;

    /// True when `B = I` (`m = n`), so that the force enters the rows as it is.
    fn force_map_is_identity(&self) -> bool {
        false
    }

    /// The blocks at the angular frequency `w`.
    fn blocks(&mut self, w: f64, out: LinearBlocks<'_>);
}

/// `M x'' + C x' + K x + f = f_ext`: `A(w) = K - w² M + i w C`, `B = I`.
#[derive(Clone, Debug)]
pub struct MckTorus {
    m: Mat<f64>,
    c: Mat<f64>,
    k: Mat<f64>,
}

impl MckTorus {
    /// From dense square `M`, `C`, `K` of equal size with finite entries (`M` may be zero: a
    /// first-order system `C x' + K x + f = 0`).
    pub fn new(
        m: MatRef<'_, f64>,
        c: MatRef<'_, f64>,
        k: MatRef<'_, f64>,
    ) -> Result<Self, HbmError> {
        // The same checks as the one-angle dynamic stiffness.
        let checked = MckStiffness::new(m, c, k)?;
        Ok(Self {
            m: checked.mass().to_owned(),
            c: checked.damping().to_owned(),
            k: checked.stiffness().to_owned(),
        })
    }
}

impl TorusLinear for MckTorus {
    fn n_dofs(&self) -> usize {
        self.m.nrows()
    }

    fn n_forces(&self) -> usize {
        self.m.nrows()
    }

    fn force_map_is_identity(&self) -> bool {
        true
    }

    fn blocks(&mut self, w: f64, mut out: LinearBlocks<'_>) {
        let n = self.m.nrows();
        for j in 0..n {
            for i in 0..n {
                let (m, c, k) = (self.m[(i, j)], self.c[(i, j)], self.k[(i, j)]);
                out.a[(i, j)] = c64::new(k - w * w * m, w * c);
                out.da[(i, j)] = c64::new(-2.0 * w * m, c);
                out.b[(i, j)] = c64::new(if i == j { 1.0 } else { 0.0 }, 0.0);
                out.db[(i, j)] = c64::new(0.0, 0.0);
            }
        }
    }
}
