//! Hill's matrix of a cycle: the harmonic-balance Jacobian with the Floquet exponent as a shift, and its shift-invert solves (eq (18) made linear about the cycle).

use super::*;

/// Hill's operator of a cycle: the pieces of `Q(σ)`, with the contact coupling in its low-rank
/// form `Φ̂ᵀ Q̂_E Ĉ(σ) Q̂_Rᵀ Φ̂`.
pub(super) struct Hill<'a> {
    pub(super) mb: &'a ModalBrake,
    pub(super) h: usize,
    pub(super) omega: f64,
    /// `Q_Eᵀ Φ_n` (`q_E × n`), `Q_Rᵀ Φ_n` (`q_R × n`) and `Φ_n` (`n_nl × n`), as complex
    /// matrices for the products with the Krylov vectors.
    pub(super) phi_e: Mat<c64>,
    pub(super) phi_r: Mat<c64>,
    pub(super) phi_n: Mat<c64>,
    /// `Ĉx_m`, `Ĉv_m` (`q_E × q_R`) for `m = -2H..=2H`.
    pub(super) cx: Vec<Mat<c64>>,
    pub(super) cv: Option<Vec<Mat<c64>>>,
    /// `Ĉ`, when it does not depend on σ (no `Ĉv`): the same for every shift.
    pub(super) fixed_core: Option<Mat<c64>>,
    /// Row `i + q_R l` holds `(Q_Rᵀ Φ_n)_ij (Q_Eᵀ Φ_n)_lj` over the modes `j`: with a diagonal
    /// `Δ_k⁻¹`, the receptance `Φ_R Δ_k⁻¹ Φ_Eᵀ` of every harmonic is one product with it.
    pub(super) pair_products: Mat<c64>,
}

/// `Q(σ_s)⁻¹` by Woodbury, for one shift.
pub(super) struct ShiftSolver<'h> {
    pub(super) sigma: c64,
    /// `Δ(σ_s + ikω)` per harmonic `k = -H..=H`.
    pub(super) modal: Vec<ModalSolver>,
    /// `Ĉ(σ_s)` (`q_E (2H+1) × q_R (2H+1)`): [`Hill`]'s own when it does not depend on σ.
    pub(super) core: Cow<'h, Mat<c64>>,
    /// LU of `I + V B⁻¹ U Ĉ` (`q_R (2H+1)` square).
    pub(super) capacitance: PartialPivLu<c64>,
}

impl<'a> Hill<'a> {
    pub(super) fn new(
        mb: &'a ModalBrake,
        cycle: &CycleRef<'_>,
        h: usize,
    ) -> Result<Self, FloquetError> {
        let samples = cycle
            .samples
            .max(squeal_hbm::default_samples(h))
            .max(4 * h + 1);
        // Pad the cycle to h harmonics if the perturbation has more.
        let nn = cycle.layout.n_dofs();
        let layout = HarmonicLayout::new(nn, h.max(cycle.layout.n_harmonics()))?;
        cycle
            .layout
            .check_len("cycle coefficients", cycle.u.len())?;
        let mut u = vec![0.0; layout.len()];
        u[..cycle.u.len()].copy_from_slice(cycle.u);
        let padded = CycleRef {
            layout,
            u: &u,
            omega: cycle.omega,
            samples,
        };
        let js = jacobian_samples(mb, &padded, samples)?;
        let (mut qe, mut qr) = contact_bases(mb);
        // The factorization is exact for the laws of squeal-brake; a law that breaks it falls
        // back on the full nonlinear dofs.
        let exact = js.iter().all(|(jx, jv)| {
            let ok = |m: &Mat<f64>| {
                let back = &qe * (qe.transpose() * m * &qr) * qr.transpose();
                (&back - m).norm_l2() <= 1e-10 * m.norm_l2().max(f64::MIN_POSITIVE)
            };
            ok(jx) && jv.as_ref().is_none_or(ok)
        });
        if !exact {
            qe = Mat::identity(nn, nn);
            qr = Mat::identity(nn, nn);
        }
        let core = |m: &Mat<f64>| qe.transpose() * m * &qr;
        let cx: Vec<Mat<f64>> = js.iter().map(|(a, _)| core(a)).collect();
        let cv: Option<Vec<Mat<f64>>> = js
            .iter()
            .map(|(_, b)| b.as_ref().map(core))
            .collect::<Option<Vec<_>>>();
        let phi_e = complex(&(qe.transpose() * &mb.phi_n));
        let phi_r = complex(&(qr.transpose() * &mb.phi_n));
        let (nqe, nqr) = (phi_e.nrows(), phi_r.nrows());
        let pair_products = Mat::from_fn(nqr * nqe, mb.modes(), |row, j| {
            phi_r[(row % nqr, j)] * phi_e[(row / nqr, j)]
        });
        let mut hill = Self {
            mb,
            h,
            omega: cycle.omega,
            phi_e,
            phi_r,
            phi_n: complex(&mb.phi_n),
            cx: harmonics_of(&cx, h),
            cv: cv.map(|v| harmonics_of(&v, h)),
            fixed_core: None,
            pair_products,
        };
        if hill.cv.is_none() {
            hill.fixed_core = Some(hill.core(c64::new(0.0, 0.0)));
        }
        Ok(hill)
    }

    pub(super) fn blocks(&self) -> usize {
        2 * self.h + 1
    }

    pub(super) fn n(&self) -> usize {
        self.mb.modes()
    }

    /// `k` of block `b`.
    pub(super) fn k(&self, b: usize) -> f64 {
        b as f64 - self.h as f64
    }

    /// `Ĉ(σ)`: block `(k, j)` is `Ĉx_{k-j} + (σ + ijω) Ĉv_{k-j}`.
    pub(super) fn core(&self, sigma: c64) -> Mat<c64> {
        let (qe, qr) = (self.phi_e.nrows(), self.phi_r.nrows());
        let nb = self.blocks();
        let mut out = Mat::<c64>::zeros(qe * nb, qr * nb);
        for bk in 0..nb {
            for bj in 0..nb {
                let m = bk + 2 * self.h - bj;
                let s = sigma + c64::new(0.0, self.k(bj) * self.omega);
                for j in 0..qr {
                    for i in 0..qe {
                        let mut v = self.cx[m][(i, j)];
                        if let Some(cv) = &self.cv {
                            v += s * cv[m][(i, j)];
                        }
                        out[(bk * qe + i, bj * qr + j)] = v;
                    }
                }
            }
        }
        out
    }

    pub(super) fn shift(&self, sigma: c64) -> ShiftSolver<'_> {
        let nb = self.blocks();
        let (qe, qr) = (self.phi_e.nrows(), self.phi_r.nrows());
        let modal: Vec<ModalSolver> = (0..nb)
            .map(|b| {
                ModalSolver::new(
                    &self.mb.omega,
                    &self.mb.damping,
                    sigma + c64::new(0.0, self.k(b) * self.omega),
                )
            })
            .collect();
        // V B⁻¹ U, block diagonal: Φ_R Δ_k⁻¹ Φ_Eᵀ (q_R × q_E, column-major), column k of
        // `receptances`.
        let n = self.n();
        let inverses: Option<Vec<&[c64]>> = modal
            .iter()
            .map(|s| match s {
                ModalSolver::Diagonal(d) => Some(&d[..]),
                ModalSolver::Full(_) => None,
            })
            .collect();
        let receptances = match inverses {
            Some(d) => &self.pair_products * Mat::from_fn(n, nb, |j, k| d[k][j]),
            None => {
                let mut out = Mat::<c64>::zeros(qr * qe, nb);
                for (k, s) in modal.iter().enumerate() {
                    let rk = &self.phi_r * s.solve(self.phi_e.transpose());
                    for l in 0..qe {
                        for i in 0..qr {
                            out[(i + qr * l, k)] = rk[(i, l)];
                        }
                    }
                }
                out
            }
        };
        let core = match &self.fixed_core {
            Some(c) => Cow::Borrowed(c),
            None => Cow::Owned(self.core(sigma)),
        };
        let r = qr * nb;
        let mut c = Mat::<c64>::identity(r, r);
        for bk in 0..nb {
            let rk = Mat::<c64>::from_fn(qr, qe, |i, l| receptances[(i + qr * l, bk)]);
            let rows = core.subrows(bk * qe, qe);
            let prod = &rk * rows;
            for i in 0..qr {
                for j in 0..r {
                    c[(bk * qr + i, j)] += prod[(i, j)];
                }
            }
        }
        ShiftSolver {
            sigma,
            modal,
            core,
            capacitance: c.partial_piv_lu(),
        }
    }

    /// `(I ⊗ M) y` blockwise for a `q × n` matrix `m`: with the blocks of `y` as the columns of
    /// an `n × (2H+1)` matrix `Y`, the columns of `M Y`.
    pub(super) fn reduce(&self, m: &Mat<c64>, y: &[c64]) -> Vec<c64> {
        let (q, nb) = (m.nrows(), self.blocks());
        let mut out = vec![c64::new(0.0, 0.0); q * nb];
        matmul(
            MatMut::from_column_major_slice_mut(&mut out, q, nb),
            Accum::Replace,
            m,
            MatRef::from_column_major_slice(y, self.n(), nb),
            c64::new(1.0, 0.0),
            Par::Seq,
        );
        out
    }

    /// `(I ⊗ Mᵀ) c` blockwise: the columns of `Mᵀ C`.
    pub(super) fn expand(&self, m: &Mat<c64>, c: &[c64]) -> Vec<c64> {
        let (q, n, nb) = (m.nrows(), self.n(), self.blocks());
        let mut out = vec![c64::new(0.0, 0.0); n * nb];
        matmul(
            MatMut::from_column_major_slice_mut(&mut out, n, nb),
            Accum::Replace,
            m.transpose(),
            MatRef::from_column_major_slice(c, q, nb),
            c64::new(1.0, 0.0),
            Par::Seq,
        );
        out
    }

    /// The nonlinear dofs of each block, `Φ̂ y`.
    pub(super) fn to_nl(&self, y: &[c64]) -> Vec<c64> {
        self.reduce(&self.phi_n, y)
    }

    /// `x ← B⁻¹ x`, block by block.
    pub(super) fn modal_solve(&self, s: &ShiftSolver, x: &mut [c64]) {
        for (xb, solver) in x.chunks_exact_mut(self.n()).zip(&s.modal) {
            solver.solve_in_place(xb);
        }
    }

    /// `Q(σ_s)⁻¹ r = y - B⁻¹ U Ĉ (I + V B⁻¹ U Ĉ)⁻¹ V y`, `y = B⁻¹ r` (Woodbury).
    pub(super) fn solve_q(&self, s: &ShiftSolver, r: &[c64]) -> Vec<c64> {
        let mut y = r.to_vec();
        self.modal_solve(s, &mut y);
        let mut t = self.reduce(&self.phi_r, &y);
        let rr = t.len();
        s.capacitance
            .solve_in_place(MatMut::from_column_major_slice_mut(&mut t, rr, 1));
        let core = &*s.core;
        let mut c = vec![c64::new(0.0, 0.0); core.nrows()];
        matmul(
            MatMut::from_column_major_slice_mut(&mut c, core.nrows(), 1),
            Accum::Replace,
            core,
            MatRef::from_column_major_slice(&t, rr, 1),
            c64::new(1.0, 0.0),
            Par::Seq,
        );
        let mut be = self.expand(&self.phi_e, &c);
        self.modal_solve(s, &mut be);
        for (a, b) in y.iter_mut().zip(&be) {
            *a -= b;
        }
        y
    }

    /// `M1 b` (`M1 = blockdiag(2ikω I + D) + Φ̂ᵀ Ĵv Φ̂`).
    pub(super) fn m1(&self, b: &[c64]) -> Vec<c64> {
        let n = self.n();
        let mut out = vec![c64::new(0.0, 0.0); b.len()];
        for blk in 0..self.blocks() {
            let ik = c64::new(0.0, 2.0 * self.k(blk) * self.omega);
            for i in 0..n {
                let mut v = ik * b[blk * n + i];
                match self.mb.damping.diagonal() {
                    Some(d) => v += d[i] * b[blk * n + i],
                    None => {
                        for j in 0..n {
                            v += self.mb.damping.entry(i, j) * b[blk * n + j];
                        }
                    }
                }
                out[blk * n + i] = v;
            }
        }
        if let Some(cv) = &self.cv {
            let (qe, qr) = (self.phi_e.nrows(), self.phi_r.nrows());
            let t = self.reduce(&self.phi_r, b);
            let nb = self.blocks();
            let mut c = vec![c64::new(0.0, 0.0); qe * nb];
            for bk in 0..nb {
                for bj in 0..nb {
                    let m = bk + 2 * self.h - bj;
                    for i in 0..qe {
                        for j in 0..qr {
                            c[bk * qe + i] += cv[m][(i, j)] * t[bj * qr + j];
                        }
                    }
                }
            }
            for (o, e) in out.iter_mut().zip(self.expand(&self.phi_e, &c)) {
                *o += e;
            }
        }
        out
    }

    /// `(A - σ_s)⁻¹ [b1; b2]` for the first-order form `A = [[0, I], [-M0, -M1]]`:
    /// `w1 = Q(σ_s)⁻¹ (-b2 - (M1 + σ_s) b1)`, `w2 = b1 + σ_s w1`.
    pub(super) fn shift_invert(&self, s: &ShiftSolver, b: &[c64]) -> Vec<c64> {
        let half = b.len() / 2;
        let (b1, b2) = b.split_at(half);
        let m1b = self.m1(b1);
        let r: Vec<c64> = (0..half)
            .map(|i| -b2[i] - m1b[i] - s.sigma * b1[i])
            .collect();
        let w1 = self.solve_q(s, &r);
        let mut out = w1.clone();
        out.extend((0..half).map(|i| b1[i] + s.sigma * w1[i]));
        out
    }
}
