//! The brake as harmonic balance sees it (eqs 26–35): its contact force as a
//! [`NonlinearForce`], its linear part condensed on the nonlinear dofs as a
//! [`DynamicStiffness`], and the eigenvalue that CHBM's constraint follows as a
//! [`LinearizedEigen`] on the one linearization of [`crate::linearized`].
//!
//! **Condensation.** In the coordinates of [`crate::modal_brake`] the linear part is
//! `M x'' + C x' + K' x` with `K' = K + K_s`, whose modal dynamic stiffness at `λ` is
//! `Δ(λ) = λ² I + λ D + Ω²` (diagonal when `D` is). For harmonic `k` (`λ = i k ω`) the Schur
//! complement of eq (32) on the nonlinear dofs is the inverse of the receptance's nonlinear
//! block,
//!
//! `Λ_eq,k = (Φ_n Δ(ikω)⁻¹ Φ_nᵀ)⁻¹`,
//!
//! an `n_nl × n_nl` inverse instead of a factorization of the linear block `Λ_ln,ln`. The
//! springs `K_s` moved into the linear part are taken out of the nonlinear force
//! ([`ContactForce`]), so `Λ_eq U + F_nl(U) - K_s U` is exactly eq (34)'s residual. Eq (33)'s
//! condensed load (static only: the piston) is `F_eq = Λ_eq,0 (K'⁻¹ F_piston)_n`.
//!
//! Eq (35) as printed, `U_ln = Λ_ln,ln⁻¹ (F_out,ln - Λ_ln,ln U_nl)`, has a typo: the second
//! `Λ_ln,ln` must be `Λ_ln,nl` (the coupling block: the second row of eq (30) is
//! `Λ_ln,ln U_ln + Λ_ln,nl U_nl = F_out,ln`). [`recover`] computes the same thing modally:
//! `q_k = Δ(ikω)⁻¹ (Φᵀ F_piston δ_k0 - Φ_nᵀ G_k)`, `x = Φ q`, with `G` the harmonics of the
//! nonlinear force, which also returns the nonlinear dofs themselves (a check).

use crate::continuation::{EigenContinuationOptions, Eigenpair, converge, seed};
use crate::damping::ModalDamping;
use crate::linearized::{Coupling, LinearizedBrake};
use crate::modal::ModalBasis;
use crate::modal_brake::ModalBrake;
use crate::spectrum::spectrum_of;
use faer::linalg::matmul::matmul;
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::{Accum, Mat, MatMut, MatRef, Par, c64};
use squeal_hbm::{
    DynamicStiffness, EigenTrack, HarmonicLayout, HbmError, LinearUpdate, LinearizedEigen,
    LocalJacobian, NonlinearForce, Part,
};
use std::collections::BTreeMap;

/// `G(x_n, x_n') = F_nl - K_s x_n` on the nonlinear dofs for the AFT scheme of eq (29).
pub struct ContactForce {
    mb: ModalBrake,
    pattern: Vec<(usize, usize)>,
    index: BTreeMap<(usize, usize), usize>,
    /// `(pattern index, -K_s[r][c])`.
    springs: Vec<(usize, f64)>,
    velocity: bool,
}

impl ContactForce {
    /// The contact force of `mb` (a copy of it is kept), with the sparsity pattern of its
    /// Jacobians on the nonlinear dofs.
    pub fn new(mb: &ModalBrake) -> Self {
        let mut index: BTreeMap<(usize, usize), usize> = BTreeMap::new();
        let velocity = mb.velocity_dependent();
        for p in &mb.pairs {
            // Every structural entry of the pair's Jacobians (module `contact`).
            let support: Vec<usize> = p.normal.iter().chain(&p.tangent).map(|e| e.0).collect();
            let cols: Vec<usize> = if velocity {
                support.clone()
            } else {
                p.normal.iter().map(|e| e.0).collect()
            };
            for &r in &support {
                for &c in &cols {
                    index.insert((r, c), 0);
                }
            }
        }
        let nn = mb.nl();
        for r in 0..nn {
            for c in 0..nn {
                if mb.k_s[(r, c)] != 0.0 {
                    index.insert((r, c), 0);
                }
            }
        }
        let pattern: Vec<(usize, usize)> = index.keys().copied().collect();
        for (k, v) in index.values_mut().enumerate() {
            *v = k;
        }
        let springs = (0..nn)
            .flat_map(|r| (0..nn).map(move |c| (r, c)))
            .filter(|&(r, c)| mb.k_s[(r, c)] != 0.0)
            .map(|(r, c)| (index[&(r, c)], -mb.k_s[(r, c)]))
            .collect();
        Self {
            mb: mb.clone(),
            pattern,
            index,
            springs,
            velocity,
        }
    }

    /// The modal brake whose force this is.
    pub fn modal_brake(&self) -> &ModalBrake {
        &self.mb
    }

    /// Sets the friction coefficient μ of the force (a continuation parameter: the springs
    /// `K_s` and the pattern do not depend on it).
    pub fn set_mu(&mut self, mu: f64) {
        self.mb.mu = mu;
    }
}

impl NonlinearForce for ContactForce {
    fn n_dofs(&self) -> usize {
        self.mb.nl()
    }

    fn pattern(&self) -> &[(usize, usize)] {
        &self.pattern
    }

    fn depends_on_velocity(&self) -> bool {
        self.velocity
    }

    fn eval(&self, x: &[f64], xdot: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>) {
        let v = self.velocity.then_some(xdot);
        self.mb.add_reduced_force(x, v, f);
        if let Some(j) = jac {
            for p in &self.mb.pairs {
                let r = p.response(x, v, self.mb.mu);
                p.jacobian_terms(&r, |row, col, dx, dv| {
                    // Entries outside the pattern are structurally zero for this element.
                    if let Some(&k) = self.index.get(&(row, col)) {
                        j.dfdx[k] += dx;
                        j.dfdxdot[k] += dv;
                    }
                });
            }
            for &(idx, v) in &self.springs {
                j.dfdx[idx] += v;
            }
        }
    }
}

/// `Δ(λ)⁻¹ b` for the modal dynamic stiffness `Δ(λ) = λ² I + λ D + Ω²`: elementwise for a
/// diagonal `D`, by an LU factorization otherwise.
pub enum ModalSolver {
    /// `1 / Δ_jj(λ)` per mode.
    Diagonal(Vec<c64>),
    /// The LU factors of `Δ(λ)`.
    Full(PartialPivLu<c64>),
}

impl ModalSolver {
    /// The solver at `l` for the natural frequencies `omega` (rad/s) and the damping.
    pub fn new(omega: &[f64], damping: &ModalDamping, l: c64) -> Self {
        let n = omega.len();
        match damping.diagonal() {
            Some(d) => ModalSolver::Diagonal(
                (0..n)
                    .map(|j| c64::new(1.0, 0.0) / (l * l + l * d[j] + omega[j] * omega[j]))
                    .collect(),
            ),
            None => ModalSolver::Full(
                Mat::<c64>::from_fn(n, n, |i, j| {
                    let mut v = l * damping.entry(i, j);
                    if i == j {
                        v += l * l + omega[i] * omega[i];
                    }
                    v
                })
                .partial_piv_lu(),
            ),
        }
    }

    /// `Δ⁻¹ B` for the columns of `b` (`n × m`).
    pub fn solve(&self, b: MatRef<'_, c64>) -> Mat<c64> {
        match self {
            ModalSolver::Diagonal(r) => Mat::from_fn(b.nrows(), b.ncols(), |i, j| r[i] * b[(i, j)]),
            ModalSolver::Full(lu) => lu.solve(b),
        }
    }

    /// `Δ⁻¹ b` for one vector.
    pub fn solve_vec(&self, b: &[c64]) -> Vec<c64> {
        let mut x = b.to_vec();
        self.solve_in_place(&mut x);
        x
    }

    /// `b ← Δ⁻¹ b` for one vector, without allocating.
    pub fn solve_in_place(&self, b: &mut [c64]) {
        match self {
            ModalSolver::Diagonal(r) => {
                for (x, ri) in b.iter_mut().zip(r) {
                    *x *= ri;
                }
            }
            ModalSolver::Full(lu) => {
                let n = b.len();
                lu.solve_in_place(MatMut::from_column_major_slice_mut(b, n, 1));
            }
        }
    }
}

/// `Λ_eq(ω)` of eq (32) for harmonics `0..=H`, cached for the last ω.
///
/// `Λ_eq,0` does not depend on ω and is computed once. For `k >= 1` a change of ω costs the
/// receptances `Φ_n Δ(ikω)⁻¹ Φ_nᵀ` (with a diagonal `D`, one real product for all harmonics
/// at once) and an `n_nl × n_nl` complex inverse per harmonic. The Jacobian's
/// `(dΛ_eq/dω) U` is applied by matrix–vector products, never as a matrix. All products are
/// sequential: the blocks are small (`n_nl = 36` on the brake), and thread hand-offs cost more
/// than they save.
pub struct CondensedStiffness {
    phi_n: Mat<f64>,
    omega_j: Vec<f64>,
    damping: ModalDamping,
    harmonics: usize,
    cached: Option<f64>,
    z: Vec<Mat<c64>>,
    /// Scratch of the diagonal path: `Φ_n` scaled per harmonic (`2 H n_nl × n`) and its
    /// product with `Φ_nᵀ`.
    scaled: Mat<f64>,
    product: Mat<f64>,
    /// The modal solvers at `ikω` of the full-damping path (one per harmonic).
    solvers: Vec<ModalSolver>,
}

impl CondensedStiffness {
    /// The condensed stiffness of `mb` for harmonics `0..=harmonics`, with `Λ_eq,0` computed;
    /// the others wait for [`CondensedStiffness::update`].
    pub fn new(mb: &ModalBrake, harmonics: usize) -> Self {
        let (nn, n) = (mb.phi_n.nrows(), mb.omega.len());
        let diagonal = mb.damping.diagonal().is_some();
        let rows = if diagonal {
            2 * harmonics.max(1) * nn
        } else {
            0
        };
        let mut s = Self {
            phi_n: mb.phi_n.clone(),
            omega_j: mb.omega.clone(),
            damping: mb.damping.clone(),
            harmonics,
            cached: None,
            z: vec![Mat::zeros(nn, nn); harmonics + 1],
            scaled: Mat::zeros(rows, if diagonal { n } else { 0 }),
            product: Mat::zeros(rows, if diagonal { nn } else { 0 }),
            solvers: Vec::new(),
        };
        // Λ_eq,0 = (Φ_n Ω⁻² Φ_nᵀ)⁻¹, real and independent of ω (Ω⁻² → S with a
        // vibration-only stiffness, crate::vibration_only).
        let h0 = match &mb.statics {
            Some(st) => {
                let h = st.receptance(&mb.phi_n);
                Mat::from_fn(nn, nn, |i, j| c64::new(h[(i, j)], 0.0))
            }
            None => s.receptance(c64::new(0.0, 0.0)),
        };
        s.z[0] = invert(&h0);
        s
    }

    /// `Λ_eq,0`, the static condensed stiffness (real, stored as complex).
    pub fn static_block(&self) -> &Mat<c64> {
        &self.z[0]
    }

    /// `H_nn(λ) = Φ_n Δ(λ)⁻¹ Φ_nᵀ`.
    pub fn receptance(&self, l: c64) -> Mat<c64> {
        let solver = ModalSolver::new(&self.omega_j, &self.damping, l);
        self.receptance_with(&solver)
    }

    fn receptance_with(&self, solver: &ModalSolver) -> Mat<c64> {
        let phi_t = self.phi_n.transpose();
        let b = Mat::<c64>::from_fn(phi_t.nrows(), phi_t.ncols(), |i, j| {
            c64::new(phi_t[(i, j)], 0.0)
        });
        let x = solver.solve(b.as_ref());
        let nn = self.phi_n.nrows();
        Mat::from_fn(nn, nn, |i, j| {
            (0..self.omega_j.len())
                .map(|m| x[(m, j)] * self.phi_n[(i, m)])
                .sum()
        })
    }

    /// Mode `j`'s receptance `r = 1 / δ_j(ikω)` and `dr/dω` (diagonal `D`).
    fn modal_receptance(&self, d: &[f64], k: usize, omega: f64, j: usize) -> (c64, c64) {
        let kf = k as f64;
        let w = kf * omega;
        let den = c64::new(self.omega_j[j].powi(2) - w * w, w * d[j]);
        let r = c64::new(1.0, 0.0) / den;
        // d(1/den)/dω = -k (-2w + i d_j) / den².
        let dr = -(c64::new(-2.0 * w, d[j]) * kf) * r * r;
        (r, dr)
    }

    /// `[Φ_n diag(Re r_k); Φ_n diag(Im r_k)]_{k=1..H} Φ_nᵀ` into `product` (diagonal `D`).
    fn stacked_receptance(&mut self, d: &[f64], omega: f64) {
        let (nn, n) = (self.phi_n.nrows(), self.omega_j.len());
        for k in 1..=self.harmonics {
            let row = 2 * (k - 1) * nn;
            for j in 0..n {
                let (v, _) = self.modal_receptance(d, k, omega, j);
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

    /// Updates `Λ_eq,k` for ω (eq 32: the inverse of the receptance's nonlinear block).
    pub fn update(&mut self, omega: f64) {
        if self.cached == Some(omega) {
            return;
        }
        let nn = self.phi_n.nrows();
        match self.damping.diagonal().map(<[f64]>::to_vec) {
            Some(d) => {
                if self.harmonics > 0 {
                    self.stacked_receptance(&d, omega);
                }
                for k in 1..=self.harmonics {
                    let row = 2 * (k - 1) * nn;
                    let h = Mat::from_fn(nn, nn, |i, j| {
                        c64::new(self.product[(row + i, j)], self.product[(row + nn + i, j)])
                    });
                    self.z[k] = invert(&h);
                }
            }
            None => {
                self.solvers = (1..=self.harmonics)
                    .map(|k| {
                        ModalSolver::new(
                            &self.omega_j,
                            &self.damping,
                            c64::new(0.0, k as f64 * omega),
                        )
                    })
                    .collect();
                for k in 1..=self.harmonics {
                    let h = self.receptance_with(&self.solvers[k - 1]);
                    self.z[k] = invert(&h);
                }
            }
        }
        self.cached = Some(omega);
    }

    /// `Φ_n (dΔ(ikω)⁻¹/dω) Φ_nᵀ a` for harmonic `k` at the cached ω.
    fn receptance_rate(&self, k: usize, omega: f64, a: &[c64]) -> Vec<c64> {
        let (nn, n) = (self.phi_n.nrows(), self.omega_j.len());
        let b: Vec<c64> = (0..n)
            .map(|j| (0..nn).map(|i| a[i] * self.phi_n[(i, j)]).sum())
            .collect();
        let c: Vec<c64> = match self.damping.diagonal() {
            Some(d) => (0..n)
                .map(|j| b[j] * self.modal_receptance(d, k, omega, j).1)
                .collect(),
            None => {
                // d(Δ⁻¹)/dω = -Δ⁻¹ (dΔ/dω) Δ⁻¹, dΔ/dω = -2 k² ω I + i k D.
                let solver = &self.solvers[k - 1];
                let y = solver.solve_vec(&b);
                let kf = k as f64;
                let mut dy = vec![c64::new(0.0, 0.0); n];
                for (i, v) in dy.iter_mut().enumerate() {
                    *v = y[i] * (-2.0 * kf * kf * omega)
                        + (0..n).map(|j| y[j] * self.damping.entry(i, j)).sum::<c64>()
                            * c64::new(0.0, kf);
                }
                solver.solve_vec(&dy).into_iter().map(|v| -v).collect()
            }
        };
        (0..nn)
            .map(|i| (0..n).map(|j| c[j] * self.phi_n[(i, j)]).sum())
            .collect()
    }

    /// `d_omega += (dΛ_eq/dω) u` at the cached ω, block by block without forming
    /// `dΛ_eq,k/dω = -Λ_eq,k (dH_k/dω) Λ_eq,k` (`dΛ_eq,0/dω = 0`).
    fn add_omega_derivative(&self, layout: &HarmonicLayout, u: &[f64], d_omega: &mut [f64]) {
        let Some(omega) = self.cached else {
            return;
        };
        let nn = self.phi_n.nrows();
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
            let d = self.receptance_rate(k, omega, &a);
            let e = matvec(&self.z[k], &d);
            for i in 0..nn {
                // y = -e is the complex y_kc - i y_ks.
                d_omega[rc.start + i] -= e[i].re;
                d_omega[rs.start + i] += e[i].im;
            }
        }
    }

    /// `Λ_eq,k` (complex) at the cached ω; `k` at most the harmonics it was built for.
    pub fn block(&self, k: usize) -> &Mat<c64> {
        &self.z[k]
    }
}

/// The inverse of a small complex matrix by LU with partial pivoting.
fn invert(h: &Mat<c64>) -> Mat<c64> {
    let n = h.nrows();
    h.partial_piv_lu().solve(Mat::<c64>::identity(n, n))
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
    stiffness: &CondensedStiffness,
    layout: &HarmonicLayout,
) -> Vec<f64> {
    let n = mb.nl();
    let xn: Vec<f64> = match &mb.statics {
        Some(st) => st.load_on_nonlinear(&mb.phi_n),
        None => (0..n)
            .map(|i| {
                (0..mb.modes())
                    .map(|j| mb.phi_n[(i, j)] * mb.load[j] / mb.omega[j].powi(2))
                    .sum()
            })
            .collect(),
    };
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
pub fn recover(mb: &ModalBrake, omega: f64, g: &[f64], layout_nl: &HarmonicLayout) -> Vec<f64> {
    let harmonics = layout_nl.n_harmonics();
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
        let rhs: Vec<c64> = (0..n)
            .map(|j| {
                let mut r = c64::new(if k == 0 { mb.load[j] } else { 0.0 }, 0.0);
                for i in 0..nn {
                    r -= gk[i] * mb.phi_n[(i, j)];
                }
                r
            })
            .collect();
        let q = match (&mb.statics, k) {
            (Some(st), 0) => {
                let g0: Vec<f64> = gk.iter().map(|v| v.re).collect();
                st.mean(&g0).into_iter().map(|v| c64::new(v, 0.0)).collect()
            }
            _ => ModalSolver::new(&mb.omega, &mb.damping, c64::new(0.0, w)).solve_vec(&rhs),
        };
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

/// The eigenvalue that CHBM's constraint follows, on the brake's one linearization: `T(λ) =
/// Δ(λ) + Φ_nᵀ (N_K + λ N_C) Φ_n` with the describing-function update `N` on the nonlinear
/// dofs, as the coupling `U₀ = Φ_nᵀ N_K`, `U₁ = Φ_nᵀ N_C`, `V = Φ_nᵀ` of
/// [`crate::linearized`], followed from one evaluation to the next by the same two-sided
/// Rayleigh functional iteration as the friction sweep ([`crate::continuation`]). When that
/// fails (a large change of the cycle between two evaluations), the eigenvalue nearest the
/// last one is taken from a dense decomposition of the state matrix.
pub struct BrakeEigen {
    lin: LinearizedBrake,
    basis: ModalBasis,
    phi_n: Mat<f64>,
    mu: f64,
    last: Option<Eigenpair>,
    /// The reference's row basis, kept from one call to the next.
    reference: Option<ReferenceBasis>,
    /// Inverse-iteration steps of the continuation, over all calls.
    pub iterations: usize,
    /// Times the continuation failed and the eigenvalue was taken from a dense decomposition.
    pub dense_restarts: usize,
    options: EigenContinuationOptions,
}

impl BrakeEigen {
    /// For a modal brake, starting at the eigenpair `start` (modal coordinates) when known.
    pub fn new(mb: &ModalBrake, start: Option<Eigenpair>) -> Self {
        let basis = ModalBasis {
            phi: Mat::identity(mb.modes(), mb.modes()),
            omega: mb.omega.clone(),
        };
        Self {
            lin: LinearizedBrake::modal(mb.omega.clone(), mb.damping.clone()),
            basis,
            phi_n: mb.phi_n.clone(),
            mu: mb.mu,
            last: start,
            reference: None,
            iterations: 0,
            dense_restarts: 0,
            options: EigenContinuationOptions::default(),
        }
    }

    /// The coupling of `N_K + λ N_C` on the nonlinear dofs, compressed to its rank. With `B`
    /// an orthonormal basis of the rows of `[N_K; N_C]`, `N_K = (N_K B) Bᵀ` and
    /// `N_C = (N_C B) Bᵀ`, so `V = Φ_nᵀ B`, `U₀ = Φ_nᵀ N_K B`, `U₁ = Φ_nᵀ N_C B`. `B` is the
    /// basis of the reference's rows (from a thin SVD of `[K₀; C₀]`, dropping singular values
    /// below `1e-13` of the largest, which round-off makes anyway; computed once per
    /// reference) extended by the correction's right factor, orthogonalized against it. The
    /// describing-function update has the rank of the contact's Jacobian plus two (`P + 2`
    /// for `P` pairs, a quarter of the nonlinear dofs on the brake), and the bordered solves
    /// cost the square of the rank.
    fn coupling(&mut self, update: &LinearUpdate<'_>) -> Coupling {
        let (nn, n) = (self.phi_n.nrows(), self.phi_n.ncols());
        let fresh = self
            .reference
            .as_ref()
            .is_some_and(|r| r.k0.as_ref() == update.k0 && r.c0.as_ref() == update.c0);
        if !fresh {
            self.reference = None;
        }
        let reference = self
            .reference
            .get_or_insert_with(|| ReferenceBasis::new(update.k0, update.c0));
        // The correction's right columns, made orthogonal to the basis (twice, for accuracy).
        let mut basis = reference.basis.clone();
        for c in 0..update.right.ncols() {
            let mut q: Vec<f64> = (0..nn).map(|i| update.right[(i, c)]).collect();
            let size = q.iter().map(|v| v * v).sum::<f64>().sqrt();
            for _ in 0..2 {
                for b in 0..basis.ncols() {
                    let d: f64 = (0..nn).map(|i| basis[(i, b)] * q[i]).sum();
                    for (i, v) in q.iter_mut().enumerate() {
                        *v -= d * basis[(i, b)];
                    }
                }
            }
            let rest = q.iter().map(|v| v * v).sum::<f64>().sqrt();
            if rest > 1e-13 * size {
                let r = basis.ncols();
                basis = Mat::from_fn(
                    nn,
                    r + 1,
                    |i, k| if k < r { basis[(i, k)] } else { q[i] / rest },
                );
            }
        }
        let (n_k, n_c) = update.dense();
        let damped = (0..nn).any(|i| (0..nn).any(|p| n_c[(i, p)] != 0.0));
        let pt = self.phi_n.transpose();
        let flat = |m: Mat<f64>| -> Vec<f64> {
            (0..m.ncols())
                .flat_map(|c| (0..m.nrows()).map(move |r| (r, c)))
                .map(|(r, c)| m[(r, c)])
                .collect()
        };
        let v = flat(pt * &basis);
        let u0 = flat(pt * (&n_k * &basis));
        let u1 = damped.then(|| flat(pt * (&n_c * &basis)));
        Coupling::from_columns(self.mu, v, u0, u1, n)
    }

    /// The dense spectrum's eigenpair nearest `to`.
    fn dense(&self, c: &Coupling, to: c64) -> Result<Eigenpair, HbmError> {
        let lost = |why: String| HbmError::EigenvalueLost { from: to, why };
        let (dk, dc) = self.lin.dense_change(c);
        let sp = spectrum_of(&self.basis, &self.lin.damping, &dk, dc.as_ref(), c.mu)
            .map_err(|e| lost(e.to_string()))?;
        let j = (0..sp.values.len())
            .min_by(|&a, &b| {
                (sp.values[a] - to)
                    .norm()
                    .total_cmp(&(sp.values[b] - to).norm())
            })
            .ok_or_else(|| lost("the linearization has no eigenvalue".into()))?;
        let right: Vec<c64> = (0..sp.modes.nrows()).map(|r| sp.modes[(r, j)]).collect();
        Ok(seed(&self.lin, c, sp.values[j], right, &self.options))
    }
}

impl LinearizedEigen for BrakeEigen {
    fn track(&mut self, update: &LinearUpdate<'_>, guess: c64) -> Result<EigenTrack, HbmError> {
        let c = self.coupling(update);
        let pair = match self
            .last
            .as_ref()
            .and_then(|p| converge(&self.lin, &c, p, &self.options))
        {
            Some((p, steps)) => {
                self.iterations += steps;
                p
            }
            None => {
                self.dense_restarts += 1;
                let to = self.last.as_ref().map_or(guess, |p| p.lambda);
                self.dense(&c, to)?
            }
        };
        let (_, slope) = self.lin.rayleigh(&c, pair.lambda, &pair.right, &pair.left);
        let restrict = |v: &[c64]| -> Vec<c64> {
            (0..self.phi_n.nrows())
                .map(|i| (0..v.len()).map(|j| v[j] * self.phi_n[(i, j)]).sum())
                .collect()
        };
        let track = EigenTrack {
            lambda: pair.lambda,
            right: restrict(&pair.right),
            left: restrict(&pair.left),
            slope,
        };
        self.last = Some(pair);
        Ok(track)
    }
}

/// An orthonormal basis of the rows of a reference `[K₀; C₀]`, with the reference it is of.
struct ReferenceBasis {
    k0: Mat<f64>,
    c0: Mat<f64>,
    basis: Mat<f64>,
}

impl ReferenceBasis {
    fn new(k0: MatRef<'_, f64>, c0: MatRef<'_, f64>) -> Self {
        let nn = k0.nrows();
        let stacked = Mat::from_fn(2 * nn, nn, |i, j| {
            if i < nn { k0[(i, j)] } else { c0[(i - nn, j)] }
        });
        let basis = match stacked.thin_svd() {
            Ok(svd) => {
                let s = svd.S();
                let top = (0..nn).map(|k| s[k].abs()).fold(0.0, f64::max);
                let r = (0..nn).filter(|&k| s[k].abs() > 1e-13 * top).count();
                svd.V().subcols(0, r).to_owned()
            }
            // Without a decomposition, the identity basis (no compression) is exact.
            Err(_) => Mat::identity(nn, nn),
        };
        Self {
            k0: k0.to_owned(),
            c0: c0.to_owned(),
            basis,
        }
    }
}
