//! The brake of eq (11) in its frictionless modal coordinates, restricted to what the
//! nonlinear analyses (harmonic balance, time integration) need.
//!
//! With `Φ` the undamped, frictionless modes of `(K_t0, M)` ([`crate::modal`]), where
//! `K_t0 = K + K_s` and `K_s = Σ_p k_t(δ_p⁰) g_p g_pᵀ` is the contact tangent stiffness at the
//! frictionless equilibrium, eq (11) is exactly
//!
//! `q'' + D q' + Ω² q + Φ_nᵀ (F_nl(x_n) - K_s x_n) = Φᵀ F_piston`, with `x = Φ q`,
//!
//! where `x_n = Φ_n q` are the nonlinear dofs (those the contact and friction forces act on)
//! and `Φ_n` the corresponding rows of `Φ`. Moving `K_s` into the linear part makes that part
//! non-singular (the pad is held by its springs) and diagonal, and `D` of eq (12) is diagonal
//! in the same basis. The nonlinear force sees only the `n_nl` nonlinear dofs.

use crate::model::{Brake, contact_law};
use crate::spectrum::Reference;
use faer::Mat;

/// One contact pair on the nonlinear dofs' local numbering.
#[derive(Clone, Debug, PartialEq)]
pub struct LocalPair {
    /// `δ = g · x_n + gap`.
    pub normal: Vec<(usize, f64)>,
    /// Friction force `μ F_c h`.
    pub tangent: Vec<(usize, f64)>,
    pub gap: f64,
    pub k_linear: f64,
    pub k_cubic: f64,
    /// Tangent stiffness at the frictionless equilibrium (its part of `K_s`).
    pub k_reference: f64,
}

impl LocalPair {
    /// Penetration at local displacements `x_n`.
    pub fn penetration(&self, xn: &[f64]) -> f64 {
        self.gap + self.normal.iter().map(|&(i, g)| g * xn[i]).sum::<f64>()
    }
}

/// The brake in modal coordinates.
#[derive(Clone, Debug)]
pub struct ModalBrake {
    pub mu: f64,
    /// Natural frequencies ω_j of the frictionless brake (rad/s).
    pub omega: Vec<f64>,
    /// Modal damping `D_jj` (s⁻¹).
    pub damping: Vec<f64>,
    /// Full modal matrix (physical dofs × modes), for recovering all dofs.
    pub phi: Mat<f64>,
    /// Physical index of each nonlinear dof.
    pub nl_dofs: Vec<usize>,
    /// Rows of `Φ` at the nonlinear dofs (`n_nl × n`).
    pub phi_n: Mat<f64>,
    pub pairs: Vec<LocalPair>,
    /// `K_s` on the nonlinear dofs (`n_nl × n_nl`, symmetric).
    pub k_s: Mat<f64>,
    /// Modal piston load `Φᵀ F_piston`.
    pub load: Vec<f64>,
}

impl ModalBrake {
    /// Builds the modal brake at friction `mu` from a brake and its frictionless reference.
    pub fn new(brake: &Brake, reference: &Reference, mu: f64) -> Self {
        let nl_dofs = brake.nonlinear_dofs();
        let local = |d: usize| nl_dofs.binary_search(&d).unwrap_or(0);
        let nn = nl_dofs.len();
        let n = brake.size();
        let phi = reference.basis.phi.clone();
        let phi_n = Mat::from_fn(nn, n, |i, j| phi[(nl_dofs[i], j)]);
        let x0 = &reference.equilibrium.x;
        let mut k_s = Mat::zeros(nn, nn);
        let pairs = brake
            .pairs
            .iter()
            .map(|p| {
                let (_, kt) = contact_law(p.penetration(x0), p.k_linear, p.k_cubic);
                let normal: Vec<(usize, f64)> =
                    p.normal.iter().map(|&(d, g)| (local(d), g)).collect();
                for &(a, ga) in &normal {
                    for &(b, gb) in &normal {
                        k_s[(a, b)] += kt * ga * gb;
                    }
                }
                LocalPair {
                    normal,
                    tangent: p.tangent.iter().map(|&(d, h)| (local(d), h)).collect(),
                    gap: p.gap,
                    k_linear: p.k_linear,
                    k_cubic: p.k_cubic,
                    k_reference: kt,
                }
            })
            .collect();
        let load = (0..n)
            .map(|j| (0..n).map(|i| phi[(i, j)] * brake.f_piston[i]).sum())
            .collect();
        Self {
            mu,
            omega: reference.basis.omega.clone(),
            damping: reference.damping.clone(),
            phi,
            nl_dofs,
            phi_n,
            pairs,
            k_s,
            load,
        }
    }

    /// Number of modes (= physical dofs).
    pub fn modes(&self) -> usize {
        self.omega.len()
    }

    /// Number of nonlinear dofs.
    pub fn nl(&self) -> usize {
        self.nl_dofs.len()
    }

    /// `F_nl(x_n) - K_s x_n` on the nonlinear dofs (eq 10 minus the springs moved into the
    /// linear part), added to `out`.
    pub fn add_reduced_force(&self, xn: &[f64], out: &mut [f64]) {
        for p in &self.pairs {
            let (f, _) = contact_law(p.penetration(xn), p.k_linear, p.k_cubic);
            for &(i, g) in &p.normal {
                out[i] += f * g;
            }
            for &(i, h) in &p.tangent {
                out[i] += self.mu * f * h;
            }
        }
        let nn = self.nl();
        for i in 0..nn {
            out[i] -= (0..nn).map(|j| self.k_s[(i, j)] * xn[j]).sum::<f64>();
        }
    }

    /// Jacobian of [`Self::add_reduced_force`] added to `jac` (`n_nl × n_nl`).
    pub fn add_reduced_jacobian(&self, xn: &[f64], jac: &mut Mat<f64>) {
        for p in &self.pairs {
            let (_, kt) = contact_law(p.penetration(xn), p.k_linear, p.k_cubic);
            for &(c, gc) in &p.normal {
                for &(r, gr) in &p.normal {
                    jac[(r, c)] += kt * gr * gc;
                }
                for &(r, hr) in &p.tangent {
                    jac[(r, c)] += self.mu * kt * hr * gc;
                }
            }
        }
        for i in 0..self.nl() {
            for j in 0..self.nl() {
                jac[(i, j)] -= self.k_s[(i, j)];
            }
        }
    }

    /// Physical displacements `x = Φ q`.
    pub fn physical(&self, q: &[f64]) -> Vec<f64> {
        let n = self.modes();
        (0..n)
            .map(|i| (0..n).map(|j| self.phi[(i, j)] * q[j]).sum())
            .collect()
    }

    /// Nonlinear-dof displacements `x_n = Φ_n q`.
    pub fn nonlinear_part(&self, q: &[f64], xn: &mut [f64]) {
        let n = self.modes();
        for (i, v) in xn.iter_mut().enumerate() {
            *v = (0..n).map(|j| self.phi_n[(i, j)] * q[j]).sum();
        }
    }
}
