//! The linear part `Lambda(omega) U~` of the harmonic balance equations, eqs. (26)-(28).

use faer::{Mat, MatMut, MatRef};

use crate::HbmError;
use crate::layout::HarmonicLayout;

/// A block-diagonal dynamic stiffness `Lambda(omega)` acting on the multi-harmonic vector:
/// block 0 maps `U0c`, and each harmonic `k` has a `2n x 2n` block mapping `(Ukc, Uks)`.
///
/// [`MckStiffness`] implements eq. (27)-(28) from dense `M`, `C`, `K`. The condensed
/// stiffness `Lambda_eq(omega)` of eq. (32) has the same block structure, so it can
/// implement this trait and reuse [`crate::HarmonicBalance`] unchanged.
pub trait DynamicStiffness {
    /// Number of dofs `n` of one block.
    fn n_dofs(&self) -> usize;

    /// `out += Lambda(omega) u` (both of layout length). Takes `&mut self` so that an
    /// implementation can cache `omega`-dependent factorizations (a condensed stiffness).
    fn add_apply(&mut self, layout: &HarmonicLayout, omega: f64, u: &[f64], out: &mut [f64]);

    /// `jac += Lambda(omega)` (square, layout length) and
    /// `d_omega += (d Lambda / d omega) u`.
    fn add_jacobian(
        &mut self,
        layout: &HarmonicLayout,
        omega: f64,
        u: &[f64],
        jac: MatMut<'_, f64>,
        d_omega: &mut [f64],
    );
}

/// Eq. (27)-(28) for `M x'' + C x' + K x`: block 0 is `K`; harmonic `k` is
/// `[[K - (k w)^2 M, k w C], [-k w C, K - (k w)^2 M]]` acting on `(Ukc, Uks)`.
#[derive(Clone, Debug)]
pub struct MckStiffness {
    m: Mat<f64>,
    c: Mat<f64>,
    k: Mat<f64>,
}

impl MckStiffness {
    /// From dense square `M`, `C`, `K` of equal size with finite entries. No symmetry is
    /// assumed (friction makes `K` non-symmetric).
    pub fn new(
        m: MatRef<'_, f64>,
        c: MatRef<'_, f64>,
        k: MatRef<'_, f64>,
    ) -> Result<Self, HbmError> {
        let n = m.nrows();
        for (what, a) in [
            ("mass matrix", m),
            ("damping matrix", c),
            ("stiffness matrix", k),
        ] {
            if a.nrows() != n || a.ncols() != n {
                return Err(HbmError::Dimension {
                    what,
                    expected: n * n,
                    got: a.nrows() * a.ncols(),
                });
            }
            if !a.is_all_finite() {
                return Err(HbmError::NonFiniteInput { what });
            }
        }
        if n == 0 {
            return Err(HbmError::NoDofs);
        }
        Ok(Self {
            m: m.to_owned(),
            c: c.to_owned(),
            k: k.to_owned(),
        })
    }

    /// The mass matrix `M`.
    pub fn mass(&self) -> MatRef<'_, f64> {
        self.m.as_ref()
    }

    /// The damping matrix `C`.
    pub fn damping(&self) -> MatRef<'_, f64> {
        self.c.as_ref()
    }

    /// The stiffness matrix `K`.
    pub fn stiffness(&self) -> MatRef<'_, f64> {
        self.k.as_ref()
    }
}

/// `out += alpha A x` for a dense column-major `A`.
fn gemv_add(out: &mut [f64], a: MatRef<'_, f64>, x: &[f64], alpha: f64) {
    for (j, &xj) in x.iter().enumerate() {
        let s = alpha * xj;
        if s == 0.0 {
            continue;
        }
        for (i, o) in out.iter_mut().enumerate() {
            *o += a[(i, j)] * s;
        }
    }
}

/// `jac[r0 + i, c0 + j] += alpha A[i, j]`.
fn add_block(jac: &mut MatMut<'_, f64>, r0: usize, c0: usize, a: MatRef<'_, f64>, alpha: f64) {
    if alpha == 0.0 {
        return;
    }
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            jac[(r0 + i, c0 + j)] += alpha * a[(i, j)];
        }
    }
}

impl DynamicStiffness for MckStiffness {
    fn n_dofs(&self) -> usize {
        self.m.nrows()
    }

    fn add_apply(&mut self, layout: &HarmonicLayout, omega: f64, u: &[f64], out: &mut [f64]) {
        let n = layout.n_dofs();
        gemv_add(&mut out[..n], self.k.as_ref(), &u[..n], 1.0);
        for k in 1..=layout.n_harmonics() {
            let kw = k as f64 * omega;
            let (rc, rs) = (layout.block_range(2 * k - 1), layout.block_range(2 * k));
            let (uc, us) = (&u[rc.clone()], &u[rs.clone()]);
            let (head, tail) = out.split_at_mut(rs.start);
            let (oc, os) = (&mut head[rc], &mut tail[..n]);
            for (o, x) in [(&mut *oc, uc), (&mut *os, us)] {
                gemv_add(o, self.k.as_ref(), x, 1.0);
                gemv_add(o, self.m.as_ref(), x, -kw * kw);
            }
            gemv_add(oc, self.c.as_ref(), us, kw);
            gemv_add(os, self.c.as_ref(), uc, -kw);
        }
    }

    fn add_jacobian(
        &mut self,
        layout: &HarmonicLayout,
        omega: f64,
        u: &[f64],
        mut jac: MatMut<'_, f64>,
        d_omega: &mut [f64],
    ) {
        let n = layout.n_dofs();
        add_block(&mut jac, 0, 0, self.k.as_ref(), 1.0);
        for k in 1..=layout.n_harmonics() {
            let kf = k as f64;
            let kw = kf * omega;
            let (c0, s0) = ((2 * k - 1) * n, 2 * k * n);
            for r0 in [c0, s0] {
                add_block(&mut jac, r0, r0, self.k.as_ref(), 1.0);
                add_block(&mut jac, r0, r0, self.m.as_ref(), -kw * kw);
            }
            add_block(&mut jac, c0, s0, self.c.as_ref(), kw);
            add_block(&mut jac, s0, c0, self.c.as_ref(), -kw);

            let (uc, us) = (&u[c0..c0 + n], &u[s0..s0 + n]);
            let (head, tail) = d_omega.split_at_mut(s0);
            let (dc, ds) = (&mut head[c0..], &mut tail[..n]);
            gemv_add(dc, self.m.as_ref(), uc, -2.0 * kf * kw);
            gemv_add(dc, self.c.as_ref(), us, kf);
            gemv_add(ds, self.m.as_ref(), us, -2.0 * kf * kw);
            gemv_add(ds, self.c.as_ref(), uc, -kf);
        }
    }
}
