//! The linearized brake of eqs (20)–(21) as a quadratic eigenproblem with a low-rank coupling:
//! the one linearization the sweep, the continuation of eigenpairs, the Hopf refinement and
//! the CHBM constraint all use.
//!
//! In the frictionless modal coordinates of [`crate::modal`] (`Φᵀ M Φ = I`, `Φᵀ K_t0 Φ = Ω²`,
//! `Φᵀ C Φ = D`) the brake linearized about a state is
//!
//! `T(λ) q = (λ² I + λ D + Ω² + U(λ) Vᵀ) q = 0`,  `U(λ) = U₀ + λ U₁`,
//!
//! because the linearization differs from the frictionless reference only through the contact
//! pairs. With the derivatives of each pair's element ([`crate::contact`]) at the state,
//! `K_t - K_t0 = Σ_p [(F_n,δ - k0_p) g_p + F_t,δ h_p] g_pᵀ` and
//! `C_NL = Σ_p (F_n,δ' g_p + F_t,δ' h_p) g_pᵀ + (F_n,v g_p + F_t,v h_p) h_pᵀ`, so with
//! `v_p = Φᵀ g_p`, `w_p = Φᵀ h_p` the columns of `V` are the `v_p` (and the `w_p` when an
//! element depends on the slip velocity), and those of `U₀`, `U₁`
//!
//! - `(F_n,δ - k0_p) v_p + F_t,δ w_p` and `F_n,δ' v_p + F_t,δ' w_p` (for column `v_p`),
//! - `0` and `F_n,v v_p + F_t,v w_p` (for column `w_p`),
//!
//! with `k0_p` the pair's normal stiffness at the reference. For the paper's element
//! `U₁ = 0` and `u_p = (k_p - k0_p) v_p + μ k_p w_p`: a rank of `P` (the number of pairs).
//! A [`Coupling`] can also hold any `U₀`, `U₁`, `V` (the describing-function update of the
//! CHBM constraint acts on the nonlinear dofs, `V = Φ_nᵀ`).
//!
//! When `D` is diagonal, `T(λ)` is a diagonal plus a rank-`r` matrix: products with it cost
//! `O(n r)` and solves `O(n r²)` ([`Factor`]), instead of the `O(n³)` of a dense
//! factorization, which is the fallback for a full `D` ([`crate::damping::ModalDamping`]).

use crate::contact::Response;
use crate::damping::ModalDamping;
use crate::equilibrium::Equilibrium;
use crate::error::BrakeError;
use crate::model::Brake;
use crate::spectrum::Reference;
use faer::linalg::solvers::Solve;
use faer::{Mat, c64};

mod factor;
#[allow(unused_imports)]
use factor::*;
pub use factor::{Bordered, DenseFactor, Factor};

/// The fixed part of `T(λ)`: `Ω`, `D`, `Φᵀ g_p`, `Φᵀ h_p` and the reference stiffnesses.
#[derive(Clone, Debug)]
pub struct LinearizedBrake {
    /// ω_j (rad/s).
    pub omega: Vec<f64>,
    /// The modal damping `D` of eq (12) (s⁻¹).
    pub damping: ModalDamping,
    /// `Φᵀ g_p` and `Φᵀ h_p`, column-major `n × P`.
    vg: Vec<f64>,
    vh: Vec<f64>,
    /// `k0_p`: `∂F_n/∂δ` of each pair at the reference.
    k0: Vec<f64>,
    /// `max ω_j²` and `max |D_ij|`: the scale of `T(λ)` for relative residuals.
    omega2_max: f64,
    damping_max: f64,
}

/// `T(λ)`'s coupling at one state: `U₀`, `U₁`, `V`, and what made them.
#[derive(Clone, Debug)]
pub struct Coupling {
    /// Friction coefficient μ of the state.
    pub mu: f64,
    /// Each pair's element response at the state (empty for a general update).
    pub responses: Vec<Response>,
    /// Each pair's penetration at the state (empty for a general update).
    pub penetration: Vec<f64>,
    /// Rank `r` (columns of `U₀`, `U₁`, `V`).
    rank: usize,
    /// Column-major `n × r`.
    v: Vec<f64>,
    u0: Vec<f64>,
    u1: Option<Vec<f64>>,
    /// `||U₀||_F + ||U₁||_F` and `||V||_F`, for the scale of `T`.
    u_norm: f64,
    v_norm: f64,
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

impl Coupling {
    /// A general coupling `(U₀ + λ U₁) Vᵀ` from column-major `n × r` arrays.
    pub fn from_columns(
        mu: f64,
        v: Vec<f64>,
        u0: Vec<f64>,
        u1: Option<Vec<f64>>,
        n: usize,
    ) -> Coupling {
        let rank = v.len().checked_div(n).unwrap_or(0);
        let u_norm = norm(&u0) + u1.as_deref().map_or(0.0, norm);
        Coupling {
            mu,
            responses: Vec::new(),
            penetration: Vec::new(),
            rank,
            v_norm: norm(&v),
            v,
            u0,
            u1,
            u_norm,
        }
    }

    /// Rank `r` of the coupling.
    pub fn rank(&self) -> usize {
        self.rank
    }

    /// `V`, `U₀` and `U₁` (when not zero), column-major `n × r`.
    pub fn columns(&self) -> (&[f64], &[f64], Option<&[f64]>) {
        (&self.v, &self.u0, self.u1.as_deref())
    }

    /// Whether `U₁ ≠ 0` (the state has damping terms: velocity-dependent elements, or the
    /// damping part of a describing function).
    pub fn has_damping(&self) -> bool {
        self.u1.is_some()
    }

    /// Column `p` of `V`.
    fn v_col(&self, p: usize) -> &[f64] {
        let n = self.v.len() / self.rank.max(1);
        &self.v[p * n..(p + 1) * n]
    }
}

impl LinearizedBrake {
    /// The linearization of `brake` about `reference`. Fails when `reference.kt0` is not the
    /// brake's tangent stiffness at `reference.equilibrium` with μ = 0 (the reference belongs
    /// to another brake) or the sizes disagree.
    pub fn new(brake: &Brake, reference: &Reference) -> Result<Self, BrakeError> {
        let n = brake.size();
        let basis = &reference.basis;
        for (what, got) in [
            ("modal basis", basis.omega.len()),
            ("modal damping", reference.damping.size()),
            ("reference equilibrium", reference.equilibrium.x.len()),
        ] {
            if got != n {
                return Err(BrakeError::Dimension {
                    what,
                    expected: n,
                    got,
                });
            }
        }
        let x0 = &reference.equilibrium.x;
        let k0: Vec<f64> = brake
            .pairs
            .iter()
            .map(|p| p.response(x0, None, 0.0).normal_derivatives[0])
            .collect();
        consistent(brake, reference, &k0)?;
        let np = brake.pairs.len();
        let phi = &basis.phi;
        let mut vg = vec![0.0; n * np];
        let mut vh = vec![0.0; n * np];
        for (p, pair) in brake.pairs.iter().enumerate() {
            for j in 0..n {
                vg[p * n + j] = pair.normal.iter().map(|&(i, g)| g * phi[(i, j)]).sum();
                vh[p * n + j] = pair.tangent.iter().map(|&(i, s)| s * phi[(i, j)]).sum();
            }
        }
        Ok(Self {
            omega2_max: basis.omega.iter().map(|w| w * w).fold(0.0, f64::max),
            damping_max: reference.damping.max_abs(),
            omega: basis.omega.clone(),
            damping: reference.damping.clone(),
            vg,
            vh,
            k0,
        })
    }

    /// The modal part alone (`Ω`, `D`), for couplings built elsewhere
    /// ([`Coupling::from_columns`]); it has no contact pairs.
    pub fn modal(omega: Vec<f64>, damping: ModalDamping) -> Self {
        Self {
            omega2_max: omega.iter().map(|w| w * w).fold(0.0, f64::max),
            damping_max: damping.max_abs(),
            omega,
            damping,
            vg: Vec::new(),
            vh: Vec::new(),
            k0: Vec::new(),
        }
    }

    /// Number of modes `n`.
    pub fn size(&self) -> usize {
        self.omega.len()
    }

    /// `Φᵀ g_p` and `Φᵀ h_p` of every pair, column-major `n × P`: the directions the contact
    /// forces act along, in modal coordinates.
    pub fn contact_columns(&self) -> (&[f64], &[f64]) {
        (&self.vg, &self.vh)
    }

    /// Number of contact pairs `P`.
    pub fn pairs(&self) -> usize {
        self.k0.len()
    }

    /// The coupling of the brake linearized at rest at the equilibrium `eq` (eqs 18–20).
    pub fn coupling(&self, brake: &Brake, eq: &Equilibrium) -> Coupling {
        let responses: Vec<Response> = brake
            .pairs
            .iter()
            .map(|p| p.response(&eq.x, None, eq.mu))
            .collect();
        let penetration = brake.pairs.iter().map(|p| p.penetration(&eq.x)).collect();
        self.coupling_of(eq.mu, responses, penetration)
    }

    /// The coupling for given pair responses (module documentation).
    pub fn coupling_of(
        &self,
        mu: f64,
        responses: Vec<Response>,
        penetration: Vec<f64>,
    ) -> Coupling {
        let (n, np) = (self.size(), self.pairs());
        let velocity_columns = responses
            .iter()
            .any(|r| r.normal_derivatives[2] != 0.0 || r.tangential_derivatives[2] != 0.0);
        let damped = responses.iter().any(Response::has_velocity_terms);
        let rank = if velocity_columns { 2 * np } else { np };
        let mut v = self.vg.clone();
        if velocity_columns {
            v.extend_from_slice(&self.vh);
        }
        let mut u0 = vec![0.0; n * rank];
        let mut u1 = damped.then(|| vec![0.0; n * rank]);
        for (p, r) in responses.iter().enumerate() {
            let [n_d, n_r, n_v] = r.normal_derivatives;
            let [t_d, t_r, t_v] = r.tangential_derivatives;
            for j in 0..n {
                let (g, h) = (self.vg[p * n + j], self.vh[p * n + j]);
                u0[p * n + j] = (n_d - self.k0[p]) * g + t_d * h;
                if let Some(u1) = u1.as_mut() {
                    u1[p * n + j] = n_r * g + t_r * h;
                    if velocity_columns {
                        u1[(np + p) * n + j] = n_v * g + t_v * h;
                    }
                }
            }
        }
        let mut c = Coupling::from_columns(mu, v, u0, u1, n);
        c.responses = responses;
        c.penetration = penetration;
        c
    }

    /// `ΔK = U₀ Vᵀ` and `ΔC = U₁ Vᵀ` as dense `n × n` matrices (for the dense
    /// eigen-decomposition of the state matrix).
    pub fn dense_change(&self, c: &Coupling) -> (Mat<f64>, Option<Mat<f64>>) {
        let n = self.size();
        let product = |u: &[f64]| {
            Mat::from_fn(n, n, |i, j| {
                (0..c.rank).map(|p| u[p * n + i] * c.v[p * n + j]).sum()
            })
        };
        (product(&c.u0), c.u1.as_deref().map(product))
    }

    /// `δ_j(λ) = λ² + D_jj λ + ω_j²`, the diagonal of `T(λ)` without the coupling.
    pub fn delta(&self, j: usize, l: c64) -> c64 {
        l * l + l * self.damping.diagonal_entry(j) + self.omega[j] * self.omega[j]
    }

    /// A bound on `||T(λ)||` for relative residuals.
    pub fn scale(&self, c: &Coupling, l: c64) -> f64 {
        let a = l.norm();
        a * a + self.damping_max * a + self.omega2_max + c.u_norm * (1.0 + a) * c.v_norm
    }

    /// `Mᵀ x` for a column-major `n × r` matrix `M` (`x` complex).
    fn project(&self, m: &[f64], x: &[c64]) -> Vec<c64> {
        m.chunks_exact(self.size())
            .map(|col| {
                let (mut re, mut im) = (0.0, 0.0);
                for (a, xj) in col.iter().zip(x) {
                    re += a * xj.re;
                    im += a * xj.im;
                }
                c64::new(re, im)
            })
            .collect()
    }

    /// `(D x)_j`, complex `x`.
    fn apply_damping(&self, x: &[c64]) -> Vec<c64> {
        match &self.damping {
            ModalDamping::Diagonal(d) => x.iter().zip(d).map(|(a, b)| a * b).collect(),
            ModalDamping::Full(d) => (0..x.len())
                .map(|i| (0..x.len()).map(|j| x[j] * d[(i, j)]).sum())
                .collect(),
        }
    }

    /// `(Dᵀ y)_j`, complex `y`.
    fn apply_damping_transposed(&self, y: &[c64]) -> Vec<c64> {
        match &self.damping {
            ModalDamping::Diagonal(_) => self.apply_damping(y),
            ModalDamping::Full(d) => (0..y.len())
                .map(|i| (0..y.len()).map(|j| y[j] * d[(j, i)]).sum())
                .collect(),
        }
    }

    /// `U(λ) z = U₀ z + λ U₁ z` for `z` of length `r`.
    fn apply_u(&self, c: &Coupling, l: c64, z: &[c64]) -> Vec<c64> {
        let n = self.size();
        let mut out = vec![c64::new(0.0, 0.0); n];
        for (p, zp) in z.iter().enumerate() {
            let col0 = &c.u0[p * n..(p + 1) * n];
            for (o, a) in out.iter_mut().zip(col0) {
                *o += zp * a;
            }
            if let Some(u1) = &c.u1 {
                let lz = l * zp;
                for (o, a) in out.iter_mut().zip(&u1[p * n..(p + 1) * n]) {
                    *o += lz * a;
                }
            }
        }
        out
    }

    /// `T(λ) x`.
    pub fn apply(&self, c: &Coupling, l: c64, x: &[c64]) -> Vec<c64> {
        let z = self.project(&c.v, x);
        let dx = self.apply_damping(x);
        let uz = self.apply_u(c, l, &z);
        (0..self.size())
            .map(|j| (l * l + self.omega[j] * self.omega[j]) * x[j] + l * dx[j] + uz[j])
            .collect()
    }

    /// `T(λ)ᴴ y = (λ̄² + λ̄ Dᵀ + Ω² + V U(λ)ᴴ) y`.
    pub fn apply_adjoint(&self, c: &Coupling, l: c64, y: &[c64]) -> Vec<c64> {
        let lc = l.conj();
        let mut w = self.project(&c.u0, y);
        if let Some(u1) = &c.u1 {
            for (wp, a) in w.iter_mut().zip(self.project(u1, y)) {
                *wp += lc * a;
            }
        }
        let dy = self.apply_damping_transposed(y);
        let n = self.size();
        (0..n)
            .map(|j| {
                let vw: c64 = (0..c.rank).map(|p| w[p] * c.v[p * n + j]).sum();
                (lc * lc + self.omega[j] * self.omega[j]) * y[j] + lc * dy[j] + vw
            })
            .collect()
    }

    /// `T'(λ) x = (2λ + D) x + U₁ Vᵀ x`.
    pub fn apply_derivative(&self, c: &Coupling, l: c64, x: &[c64]) -> Vec<c64> {
        let mut out = self.apply_damping(x);
        for (o, xj) in out.iter_mut().zip(x) {
            *o += l * 2.0 * xj;
        }
        if let Some(u1) = &c.u1 {
            let z = self.project(&c.v, x);
            let n = self.size();
            for (p, zp) in z.iter().enumerate() {
                for (o, a) in out.iter_mut().zip(&u1[p * n..(p + 1) * n]) {
                    *o += zp * a;
                }
            }
        }
        out
    }

    /// `T'(λ)ᴴ y`.
    pub fn apply_derivative_adjoint(&self, c: &Coupling, l: c64, y: &[c64]) -> Vec<c64> {
        let mut out = self.apply_damping_transposed(y);
        for (o, yj) in out.iter_mut().zip(y) {
            *o += l.conj() * 2.0 * yj;
        }
        if let Some(u1) = &c.u1 {
            let w = self.project(u1, y);
            let n = self.size();
            for (o, j) in out.iter_mut().zip(0..n) {
                *o += (0..c.rank).map(|p| w[p] * c.v[p * n + j]).sum::<c64>();
            }
        }
        out
    }

    /// `yᴴ T(λ) x` and `yᴴ T'(λ) x`: the Rayleigh functional's Newton step is their ratio.
    pub fn rayleigh(&self, c: &Coupling, l: c64, x: &[c64], y: &[c64]) -> (c64, c64) {
        let Some(d) = self.damping.diagonal() else {
            let dot =
                |a: &[c64], b: &[c64]| a.iter().zip(b).map(|(p, q)| p.conj() * q).sum::<c64>();
            return (
                dot(y, &self.apply(c, l, x)),
                dot(y, &self.apply_derivative(c, l, x)),
            );
        };
        // The entries of `T x` and `T' x` one at a time, with the sums of `apply` and
        // `apply_derivative` in their order (the same bits, without the vectors).
        let n = self.size();
        let z = self.project(&c.v, x);
        let (mut num, mut den) = (c64::new(0.0, 0.0), c64::new(0.0, 0.0));
        for j in 0..n {
            let uz = coupled_entry(c, l, &z, j, n);
            let dx = x[j] * d[j];
            let tx = (l * l + self.omega[j] * self.omega[j]) * x[j] + l * dx + uz;
            let mut dtx = dx + l * 2.0 * x[j];
            if let Some(u1) = &c.u1 {
                for (p, zp) in z.iter().enumerate() {
                    dtx += zp * u1[p * n + j];
                }
            }
            let yc = y[j].conj();
            num += yc * tx;
            den += yc * dtx;
        }
        (num, den)
    }

    /// `||T(λ) x||` and `||T(λ)ᴴ y||`, with the sums of `apply` and `apply_adjoint` in their
    /// order (the same bits, without the vectors).
    pub fn residual_norms(&self, c: &Coupling, l: c64, x: &[c64], y: &[c64]) -> (f64, f64) {
        let norm = |v: &[c64]| v.iter().map(|a| a.norm_sqr()).sum::<f64>().sqrt();
        let Some(d) = self.damping.diagonal() else {
            return (
                norm(&self.apply(c, l, x)),
                norm(&self.apply_adjoint(c, l, y)),
            );
        };
        let n = self.size();
        let lc = l.conj();
        let z = self.project(&c.v, x);
        let mut w = self.project(&c.u0, y);
        if let Some(u1) = &c.u1 {
            for (wp, a) in w.iter_mut().zip(self.project(u1, y)) {
                *wp += lc * a;
            }
        }
        let (mut rx, mut ry) = (0.0, 0.0);
        for j in 0..n {
            let uz = coupled_entry(c, l, &z, j, n);
            let w2 = self.omega[j] * self.omega[j];
            let tx = (l * l + w2) * x[j] + l * (x[j] * d[j]) + uz;
            let vw: c64 = (0..c.rank).map(|p| w[p] * c.v[p * n + j]).sum();
            let ty = (lc * lc + w2) * y[j] + lc * (y[j] * d[j]) + vw;
            rx += tx.norm_sqr();
            ry += ty.norm_sqr();
        }
        (rx.sqrt(), ry.sqrt())
    }

    /// `yᴴ (∂T/∂θ) x` for a change `(dU₀, dU₁)` of the coupling (same `V`): the derivative of
    /// an eigenvalue along any parameter is `-yᴴ (∂T/∂θ) x / yᴴ T'(λ) x`.
    pub fn coupling_derivative(
        &self,
        c: &Coupling,
        du0: &[f64],
        du1: Option<&[f64]>,
        l: c64,
        x: &[c64],
        y: &[c64],
    ) -> c64 {
        let vx = self.project(&c.v, x);
        let mut uy: Vec<c64> = self.project(du0, y);
        if let Some(du1) = du1 {
            for (a, b) in uy.iter_mut().zip(self.project(du1, y)) {
                *a += l.conj() * b;
            }
        }
        uy.iter().zip(&vx).map(|(a, b)| a.conj() * b).sum()
    }

    /// `dU₀/dμ`, `dU₁/dμ` (column-major like `U₀`, `U₁`) along the equilibrium path of the
    /// sweep, for a coupling made by [`LinearizedBrake::coupling`] (it reads the pairs'
    /// responses and penetrations, which [`Coupling::from_columns`] leaves empty: with pairs,
    /// such a coupling panics). The elements' responses change with μ directly and through
    /// the equilibrium, `K_t dx/dμ = -Σ_q F_t,μ h_q` (eq 14 differentiated;
    /// `Φᵀ K_t Φ = T(0)`), so `dδ/dμ = -Vᵀ T(0)⁻¹ Φᵀ H F_t,μ`. The
    /// elements' derivatives with respect to μ and δ are taken by central differences of their
    /// responses along that path (exact up to round-off for the paper's element, whose
    /// stiffness is quadratic in δ).
    pub fn mu_rates(
        &self,
        brake: &Brake,
        c: &Coupling,
    ) -> Result<(Vec<f64>, Option<Vec<f64>>), BrakeError> {
        let (n, np) = (self.size(), self.pairs());
        if c.responses.len() != np || c.penetration.len() != np || brake.pairs.len() != np {
            return Err(BrakeError::Dimension {
                what: "the coupling's pair responses (mu_rates needs a coupling of this brake)",
                expected: np,
                got: c.responses.len(),
            });
        }
        let zero = c64::new(0.0, 0.0);
        let b: Vec<c64> = (0..n)
            .map(|j| {
                let s: f64 = (0..np)
                    .map(|p| self.vh[p * n + j] * c.responses[p].tangential_mu)
                    .sum();
                c64::new(-s, 0.0)
            })
            .collect();
        let dx = self.factor(c, zero).solve(self, c, &b);
        let dd = self.project(&self.vg, &dx);
        let eps = 1e-4 * c.mu.abs().max(1e-2);
        let shifted = |s: f64| -> Vec<Response> {
            brake
                .pairs
                .iter()
                .enumerate()
                .map(|(p, pair)| {
                    let mut k = crate::contact::Kinematics {
                        penetration: c.penetration[p] + s * eps * dd[p].re,
                        ..Default::default()
                    };
                    k.slip_velocity = pair.surface_speed.unwrap_or(0.0);
                    pair.law.response(c.mu + s * eps, &k)
                })
                .collect()
        };
        let (plus, minus) = (
            self.coupling_of(c.mu + eps, shifted(1.0), c.penetration.clone()),
            self.coupling_of(c.mu - eps, shifted(-1.0), c.penetration.clone()),
        );
        let rate = |a: &[f64], b: &[f64]| -> Vec<f64> {
            a.iter()
                .zip(b)
                .map(|(p, m)| (p - m) / (2.0 * eps))
                .collect()
        };
        let du1 = match (&plus.u1, &minus.u1) {
            (Some(a), Some(b)) => Some(rate(a, b)),
            _ => None,
        };
        Ok((rate(&plus.u0, &minus.u0), du1))
    }

    /// The traces `tr A` and `tr A²` of the scaled state matrix of [`crate::spectrum`]
    /// `A = [[0, Ω], [-(Ω + ΔK Ω⁻¹), -(D + ΔC)]]`: the sums of its `2n` eigenvalues and of
    /// their squares. `tr A = -tr D - tr ΔC`, `tr A² = tr (D + ΔC)² - 2 Σ ω_j² - 2 tr ΔK`,
    /// with `tr ΔK = Σ_p u0_pᵀ v_p`, `tr ΔC = Σ_p u1_pᵀ v_p`.
    pub fn traces(&self, c: &Coupling) -> (f64, f64) {
        let n = self.size();
        let dotr = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let tr_dk = dotr(&c.u0, &c.v);
        let w2: f64 = self.omega.iter().map(|w| w * w).sum();
        let (tr_dc, tr_c2) = match &c.u1 {
            None => (0.0, self.damping.trace_of_square()),
            Some(u1) => {
                // tr (D + ΔC)² = tr D² + 2 Σ_p v_pᵀ D u1_p + Σ_pq (v_pᵀ u1_q)(v_qᵀ u1_p).
                let mut cross = 0.0;
                let mut scratch = vec![0.0; n];
                for p in 0..c.rank {
                    let col = &u1[p * n..(p + 1) * n];
                    self.damping.apply(col, &mut scratch);
                    cross += dotr(c.v_col(p), &scratch);
                }
                let vu = |p: usize, q: usize| dotr(c.v_col(p), &u1[q * n..(q + 1) * n]);
                let mut sq = 0.0;
                for p in 0..c.rank {
                    for q in 0..c.rank {
                        sq += vu(p, q) * vu(q, p);
                    }
                }
                (
                    dotr(u1, &c.v),
                    self.damping.trace_of_square() + 2.0 * cross + sq,
                )
            }
        };
        (
            -self.damping.trace() - tr_dc,
            tr_c2 - 2.0 * w2 - 2.0 * tr_dk,
        )
    }

    /// Factors `T(λ)` for solves with it and with its adjoint: with a diagonal `D`, the
    /// bordered system of the modal diagonal and the rank-`r` coupling ([`Bordered`], `m + r`
    /// square with the 4 modes nearest λ) while `r` is below the size `n`; `T` itself, formed
    /// and LU-factored, once `r` reaches `n` (a brake with at least as many contact pairs as
    /// dofs: an interface-reduced nodal brake; smaller brakes keep their bits). Measured on the ventilated brake's coarse disc
    /// with 3.75 mm pads (527 dofs, 3058 pairs): two 3062-square textbook complex LUs per
    /// factor made the Hopf point's polish and sensitivities take 966.7 s of the run's
    /// 27.5 minutes (perf: `SmallLu::new` 41 %, `Bordered::new` 2 %). With a full `D`,
    /// always `T` itself.
    pub fn factor(&self, c: &Coupling, l: c64) -> Factor {
        let n = self.size();
        match self.damping.diagonal() {
            Some(d) if c.rank < n => Factor::Bordered(Bordered::new(self, c, d, l)),
            Some(d) => Factor::Dense(DenseFactor::low_rank(self, c, d, l)),
            None => Factor::Dense(DenseFactor::new(self, c, l)),
        }
    }
}

/// Entry `j` of the coupling's `Σ_p z_p (U₀ + λ U₁)_{p j}` (`n` dofs), with the sums in the
/// order `apply` takes them.
fn coupled_entry(c: &Coupling, l: c64, z: &[c64], j: usize, n: usize) -> c64 {
    let mut uz = c64::new(0.0, 0.0);
    for (p, zp) in z.iter().enumerate() {
        uz += zp * c.u0[p * n + j];
        if let Some(u1) = &c.u1 {
            uz += l * zp * u1[p * n + j];
        }
    }
    uz
}

/// Whether `reference.kt0` is `K + Σ k0_p g_p g_pᵀ` to round-off (a few ulps of the largest
/// entry: both are the same sums of the same terms).
fn consistent(brake: &Brake, reference: &Reference, k0: &[f64]) -> Result<(), BrakeError> {
    let n = brake.size();
    let kt0 = &reference.kt0;
    if kt0.nrows() != n || kt0.ncols() != n {
        return Err(BrakeError::Dimension {
            what: "reference tangent stiffness",
            expected: n,
            got: kt0.nrows(),
        });
    }
    let mut expected = brake.k.clone();
    for (p, pair) in brake.pairs.iter().enumerate() {
        for &(c, gc) in &pair.normal {
            for &(r, gr) in &pair.normal {
                expected[(r, c)] += k0[p] * gr * gc;
            }
        }
    }
    let mut scale = 0.0f64;
    let mut diff = 0.0f64;
    for j in 0..n {
        for i in 0..n {
            scale = scale.max(kt0[(i, j)].abs());
            diff = diff.max((kt0[(i, j)] - expected[(i, j)]).abs());
        }
    }
    if diff <= 1e-13 * scale {
        Ok(())
    } else {
        Err(BrakeError::ForeignReference {
            relative: diff / scale.max(f64::MIN_POSITIVE),
        })
    }
}
