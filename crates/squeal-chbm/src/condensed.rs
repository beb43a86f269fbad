//! Harmonic balance condensed on the nonlinear dofs, eqs (30)–(35), through the modal
//! receptance of the brake.
//!
//! In the coordinates of [`squeal_brake::modal_brake`] the linear part is
//! `M x'' + C x' + K' x` with `K' = K + K_s`, diagonal in the modal basis. For harmonic `k`
//! its dynamic stiffness is `Z(kω) = K' - (kω)² M + i kω C` (eq 28 as a complex matrix acting on
//! `U_kc - i U_ks`), and the Schur complement of eq (32) on the nonlinear dofs is the inverse of
//! the receptance's nonlinear block:
//!
//! `Λ_eq,k = (Φ_n diag(1 / (ω_j² - (kω)² + i kω d_j)) Φ_nᵀ)⁻¹`,
//!
//! an `n_nl × n_nl` inverse instead of a factorization of the linear block `Λ_ln,ln`. The springs
//! `K_s` moved into the linear part are taken out of the nonlinear force
//! ([`crate::contact`]), so `Λ_eq U + F_nl(U) - K_s U` is exactly eq (34)'s residual.
//! Eq (33)'s condensed load (static only: the piston) is `F_eq = Λ_eq,0 (K'⁻¹ F_piston)_n`.
//!
//! Eq (35) as printed, `U_ln = Λ_ln,ln⁻¹ (F_out,ln - Λ_ln,ln U_nl)`, has a typo: the second
//! `Λ_ln,ln` must be `Λ_ln,nl` (the coupling block: the second row of eq (30) is
//! `Λ_ln,ln U_ln + Λ_ln,nl U_nl = F_out,ln`). [`recover`] computes the same thing modally:
//! `q_k = diag(1/den_j(kω)) (Φᵀ F_piston δ_k0 - Φ_nᵀ G_k)`, `x = Φ q`, with `G` the harmonics of
//! the nonlinear force, which also returns the nonlinear dofs themselves (a check).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor as lu_factor, inverse as lu_inverse};
use faer::linalg::matmul::matmul;
use faer::perm::PermRef;
use faer::{Accum, Mat, MatMut, Par, c64};
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::{DynamicStiffness, HarmonicLayout, Part};

/// `Λ_eq(ω)` of eq (32) for harmonics `0..=H`, cached for the last ω.
///
/// `Λ_eq,0` does not depend on ω and is computed once. For `k >= 1` a change of ω costs one
/// real product `[Φ_n diag(Re r_k); Φ_n diag(Im r_k)]_k Φ_nᵀ` for all harmonics at once and
/// an `n_nl × n_nl` complex inverse per harmonic. The Jacobian's `(dΛ_eq/dω) U` is applied by
/// matrix–vector products ([`Self::add_omega_derivative`]), never as a matrix. All products
/// are sequential: the blocks are small (`n_nl = 36` on the brake), and thread hand-offs cost
/// more than they save.
pub struct CondensedStiffness {
    phi_n: Mat<f64>,
    omega_j: Vec<f64>,
    damping: Vec<f64>,
    harmonics: usize,
    cached: Option<f64>,
    z: Vec<Mat<c64>>,
    /// Scratch: scaled copies of `Φ_n` stacked by harmonic (`2 H n_nl × n`), their product with
    /// `Φ_nᵀ`, and the LU factor and permutations of one block.
    scaled: Mat<f64>,
    product: Mat<f64>,
    lu: Mat<c64>,
    perm: (Vec<usize>, Vec<usize>),
    mem: MemBuffer,
}

impl CondensedStiffness {
    pub fn new(mb: &ModalBrake, harmonics: usize) -> Self {
        let (nn, n) = (mb.phi_n.nrows(), mb.omega.len());
        let scratch = lu_factor::lu_in_place_scratch::<usize, c64>(nn, nn, Par::Seq, default())
            .or(lu_inverse::inverse_scratch::<usize, c64>(nn, Par::Seq));
        let mut s = Self {
            phi_n: mb.phi_n.clone(),
            omega_j: mb.omega.clone(),
            damping: mb.damping.clone(),
            harmonics,
            cached: None,
            z: vec![Mat::zeros(nn, nn); harmonics + 1],
            scaled: Mat::zeros(2 * harmonics.max(1) * nn, n),
            product: Mat::zeros(2 * harmonics.max(1) * nn, nn),
            lu: Mat::zeros(nn, nn),
            perm: (vec![0; nn], vec![0; nn]),
            mem: MemBuffer::new(scratch),
        };
        // Λ_eq,0 = (Φ_n diag(1/ω_j²) Φ_nᵀ)⁻¹, real and independent of ω.
        let (h0, _) = s.receptance(0, 0.0);
        s.lu.copy_from(&h0);
        s.invert_lu_into(0);
        s
    }

    /// Receptance `H_nn(kω)` and `dH_nn/dω` on the nonlinear dofs:
    /// `Φ_n diag(r) Φ_nᵀ` as real products for the real and imaginary parts of `r`.
    pub fn receptance(&self, k: usize, omega: f64) -> (Mat<c64>, Mat<c64>) {
        let (nn, n) = (self.phi_n.nrows(), self.omega_j.len());
        let mut scaled = Mat::<f64>::zeros(4 * nn, n);
        for j in 0..n {
            let (r, dr) = self.modal_receptance(k, omega, j);
            for (b, v) in [r.re, r.im, dr.re, dr.im].into_iter().enumerate() {
                for i in 0..nn {
                    scaled[(b * nn + i, j)] = self.phi_n[(i, j)] * v;
                }
            }
        }
        let mut p = Mat::<f64>::zeros(4 * nn, nn);
        matmul(
            p.as_mut(),
            Accum::Replace,
            scaled.as_ref(),
            self.phi_n.transpose(),
            1.0,
            Par::Seq,
        );
        let h = Mat::from_fn(nn, nn, |i, j| c64::new(p[(i, j)], p[(nn + i, j)]));
        let dh = Mat::from_fn(nn, nn, |i, j| {
            c64::new(p[(2 * nn + i, j)], p[(3 * nn + i, j)])
        });
        (h, dh)
    }

    /// Mode `j`'s receptance `r = 1 / (ω_j² - (kω)² + i kω d_j)` and `dr/dω`.
    fn modal_receptance(&self, k: usize, omega: f64, j: usize) -> (c64, c64) {
        let kf = k as f64;
        let w = kf * omega;
        let den = c64::new(self.omega_j[j].powi(2) - w * w, w * self.damping[j]);
        let r = c64::new(1.0, 0.0) / den;
        // d(1/den)/dω = -k (-2w + i d_j) / den².
        let dr = -(c64::new(-2.0 * w, self.damping[j]) * kf) * r * r;
        (r, dr)
    }

    /// `[Φ_n diag(Re r_k); Φ_n diag(Im r_k)]_{k=1..H} Φ_nᵀ` into `product`: the real and
    /// imaginary parts of the receptances `H_nn(kω)`.
    fn stacked_receptance(&mut self, omega: f64) {
        let (nn, n) = (self.phi_n.nrows(), self.omega_j.len());
        for k in 1..=self.harmonics {
            let row = 2 * (k - 1) * nn;
            for j in 0..n {
                let (v, _) = self.modal_receptance(k, omega, j);
                let col = self.phi_n.col(j);
                for i in 0..nn {
                    self.scaled[(row + i, j)] = col[i] * v.re;
                    self.scaled[(row + nn + i, j)] = col[i] * v.im;
                }
            }
        }
        let rows = 2 * self.harmonics * nn;
        matmul(
            self.product.as_mut().subrows_mut(0, rows),
            Accum::Replace,
            self.scaled.as_ref().subrows(0, rows),
            self.phi_n.transpose(),
            1.0,
            Par::Seq,
        );
    }

    /// Block `k` of `product` as a complex matrix.
    fn product_block(&self, k: usize) -> impl Fn(usize, usize) -> c64 + '_ {
        let nn = self.phi_n.nrows();
        let row = 2 * (k - 1) * nn;
        move |i, j| c64::new(self.product[(row + i, j)], self.product[(row + nn + i, j)])
    }

    /// `z[k] = lu⁻¹` (LU with partial pivoting, sequential).
    fn invert_lu_into(&mut self, k: usize) {
        let stack = MemStack::new(&mut self.mem);
        let (fwd, bwd) = (&mut self.perm.0, &mut self.perm.1);
        let (_, perm) =
            lu_factor::lu_in_place(self.lu.as_mut(), fwd, bwd, Par::Seq, stack, default());
        let perm: PermRef<'_, usize> = perm;
        let stack = MemStack::new(&mut self.mem);
        lu_inverse::inverse(
            self.z[k].as_mut(),
            self.lu.as_ref(),
            self.lu.as_ref(),
            perm,
            Par::Seq,
            stack,
        );
    }

    /// Updates `Λ_eq,k` for ω (eq 32: the inverse of the receptance's nonlinear block).
    pub fn update(&mut self, omega: f64) {
        if self.cached == Some(omega) {
            return;
        }
        if self.harmonics > 0 {
            self.stacked_receptance(omega);
        }
        for k in 1..=self.harmonics {
            let nn = self.phi_n.nrows();
            let block = self.product_block(k);
            let h = Mat::from_fn(nn, nn, block);
            self.lu.copy_from(&h);
            self.invert_lu_into(k);
        }
        self.cached = Some(omega);
    }

    /// `d_omega += (dΛ_eq/dω) u` at the cached ω, block by block without forming
    /// `dΛ_eq,k/dω = -Λ_eq,k (dH_k/dω) Λ_eq,k`: for `v = U_kc - i U_ks`,
    /// `-Λ_eq,k Φ_n diag(dr_k/dω) Φ_nᵀ Λ_eq,k v` by matrix–vector products (`dΛ_eq,0/dω = 0`).
    fn add_omega_derivative(&self, layout: &HarmonicLayout, u: &[f64], d_omega: &mut [f64]) {
        let Some(omega) = self.cached else {
            return;
        };
        let (nn, n) = (self.phi_n.nrows(), self.omega_j.len());
        let matvec = |m: &Mat<c64>, v: &[c64]| -> Vec<c64> {
            (0..nn)
                .map(|i| (0..nn).map(|j| m[(i, j)] * v[j]).sum())
                .collect()
        };
        for k in 1..=self.harmonics.min(layout.n_harmonics()) {
            let (Some(bc), Some(bs)) = (layout.block(k, Part::Cos), layout.block(k, Part::Sin))
            else {
                continue;
            };
            let (rc, rs) = (layout.block_range(bc), layout.block_range(bs));
            let v: Vec<c64> = (0..nn)
                .map(|i| c64::new(u[rc.start + i], -u[rs.start + i]))
                .collect();
            let a = matvec(&self.z[k], &v);
            // Φ_n diag(dr) Φ_nᵀ a.
            let mut d = vec![c64::new(0.0, 0.0); nn];
            for j in 0..n {
                let col = self.phi_n.col(j);
                let b: c64 = (0..nn).map(|i| a[i] * col[i]).sum();
                let c = b * self.modal_receptance(k, omega, j).1;
                for i in 0..nn {
                    d[i] += c * col[i];
                }
            }
            let e = matvec(&self.z[k], &d);
            for i in 0..nn {
                // y = -e is the complex y_kc - i y_ks.
                d_omega[rc.start + i] -= e[i].re;
                d_omega[rs.start + i] += e[i].im;
            }
        }
    }

    /// `Λ_eq,k` (complex) at the cached ω.
    pub fn block(&self, k: usize) -> &Mat<c64> {
        &self.z[k]
    }
}

fn default<T: Default>() -> T {
    T::default()
}

/// Applies complex blocks to the layout: block 0 real, harmonic `k` as `[[A, B], [-B, A]]` on
/// `(U_kc, U_ks)` for `Z = A + iB`.
fn apply(layout: &HarmonicLayout, z: &[Mat<c64>], u: &[f64], out: &mut [f64]) {
    let n = layout.n_dofs();
    for k in 0..=layout.n_harmonics() {
        let zk = &z[k];
        if k == 0 {
            let b0 = layout.block_range(0);
            for i in 0..n {
                out[b0.start + i] += (0..n).map(|j| zk[(i, j)].re * u[b0.start + j]).sum::<f64>();
            }
            continue;
        }
        let (Some(bc), Some(bs)) = (layout.block(k, Part::Cos), layout.block(k, Part::Sin)) else {
            continue;
        };
        let (rc, rs) = (layout.block_range(bc), layout.block_range(bs));
        for i in 0..n {
            let (mut yc, mut ys) = (0.0, 0.0);
            for j in 0..n {
                let (a, b) = (zk[(i, j)].re, zk[(i, j)].im);
                let (uc, us) = (u[rc.start + j], u[rs.start + j]);
                yc += a * uc + b * us;
                ys += -b * uc + a * us;
            }
            out[rc.start + i] += yc;
            out[rs.start + i] += ys;
        }
    }
}

impl DynamicStiffness for CondensedStiffness {
    fn n_dofs(&self) -> usize {
        self.phi_n.nrows()
    }

    fn add_apply(&mut self, layout: &HarmonicLayout, omega: f64, u: &[f64], out: &mut [f64]) {
        self.update(omega);
        apply(layout, &self.z, u, out);
    }

    fn add_jacobian(
        &mut self,
        layout: &HarmonicLayout,
        omega: f64,
        u: &[f64],
        mut jac: MatMut<'_, f64>,
        d_omega: &mut [f64],
    ) {
        self.update(omega);
        let n = layout.n_dofs();
        for k in 0..=layout.n_harmonics() {
            let zk = &self.z[k];
            if k == 0 {
                let b0 = layout.block_range(0).start;
                for i in 0..n {
                    for j in 0..n {
                        jac[(b0 + i, b0 + j)] += zk[(i, j)].re;
                    }
                }
                continue;
            }
            let (Some(bc), Some(bs)) = (layout.block(k, Part::Cos), layout.block(k, Part::Sin))
            else {
                continue;
            };
            let (c0, s0) = (layout.block_range(bc).start, layout.block_range(bs).start);
            for i in 0..n {
                for j in 0..n {
                    let (a, b) = (zk[(i, j)].re, zk[(i, j)].im);
                    jac[(c0 + i, c0 + j)] += a;
                    jac[(c0 + i, s0 + j)] += b;
                    jac[(s0 + i, c0 + j)] -= b;
                    jac[(s0 + i, s0 + j)] += a;
                }
            }
        }
        self.add_omega_derivative(layout, u, d_omega);
    }
}

/// Eq (33): the condensed static load `F_eq = Λ_eq,0 (K'⁻¹ F_piston)_n` in block 0 of a
/// layout-length vector.
pub fn condensed_load(
    mb: &ModalBrake,
    stiffness: &mut CondensedStiffness,
    layout: &HarmonicLayout,
) -> Vec<f64> {
    stiffness.update(stiffness.cached.unwrap_or(1.0));
    let n = mb.nl();
    let xn: Vec<f64> = (0..n)
        .map(|i| {
            (0..mb.modes())
                .map(|j| mb.phi_n[(i, j)] * mb.load[j] / mb.omega[j].powi(2))
                .sum()
        })
        .collect();
    let z0 = &stiffness.z[0];
    let mut f = vec![0.0; layout.len()];
    for i in 0..n {
        f[i] = (0..n).map(|j| z0[(i, j)].re * xn[j]).sum();
    }
    f
}

/// Eq (35), corrected: all dofs' Fourier coefficients from the nonlinear force's harmonics
/// `g` (of `F_nl - K_s x_n`, layout on the nonlinear dofs). Returns the physical
/// coefficients in the layout of eq (25) over all `n` dofs.
pub fn recover(
    mb: &ModalBrake,
    harmonics: usize,
    omega: f64,
    g: &[f64],
    layout_nl: &HarmonicLayout,
) -> Vec<f64> {
    let n = mb.modes();
    let nn = mb.nl();
    let blocks = 2 * harmonics + 1;
    let mut out = vec![0.0; blocks * n];
    for k in 0..=harmonics {
        let w = k as f64 * omega;
        // Complex G_k = G_kc - i G_ks on the nonlinear dofs.
        let gk: Vec<c64> = (0..nn)
            .map(|i| {
                if k == 0 {
                    c64::new(g[i], 0.0)
                } else {
                    let c = layout_nl.index(k, Part::Cos, i).map_or(0.0, |x| g[x]);
                    let s = layout_nl.index(k, Part::Sin, i).map_or(0.0, |x| g[x]);
                    c64::new(c, -s)
                }
            })
            .collect();
        let q: Vec<c64> = (0..n)
            .map(|j| {
                let mut rhs = c64::new(if k == 0 { mb.load[j] } else { 0.0 }, 0.0);
                for i in 0..nn {
                    rhs -= gk[i] * mb.phi_n[(i, j)];
                }
                rhs / c64::new(mb.omega[j].powi(2) - w * w, w * mb.damping[j])
            })
            .collect();
        for d in 0..n {
            let x: c64 = (0..n).map(|j| q[j] * mb.phi[(d, j)]).sum();
            if k == 0 {
                out[d] = x.re;
            } else {
                out[(2 * k - 1) * n + d] = x.re;
                out[2 * k * n + d] = -x.im;
            }
        }
    }
    out
}
