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

use crate::damping::ModalDamping;
use crate::model::{Brake, ContactPair, add_contact_forces, contact_jacobians};
use crate::spectrum::Reference;
use faer::Mat;

/// The brake in modal coordinates.
#[derive(Clone, Debug)]
pub struct ModalBrake {
    /// Friction coefficient μ of the contact forces.
    pub mu: f64,
    /// Natural frequencies ω_j of the frictionless brake (rad/s).
    pub omega: Vec<f64>,
    /// Modal damping `D` (s⁻¹).
    pub damping: ModalDamping,
    /// Full modal matrix (physical dofs × modes), for recovering all dofs.
    pub phi: Mat<f64>,
    /// Physical index of each nonlinear dof.
    pub nl_dofs: Vec<usize>,
    /// Rows of `Φ` at the nonlinear dofs (`n_nl × n`).
    pub phi_n: Mat<f64>,
    /// The contact pairs on the nonlinear dofs' local numbering.
    pub pairs: Vec<ContactPair>,
    /// Each pair's normal stiffness `∂F_n/∂δ` (N/m) at the frictionless equilibrium (its part
    /// of `K_s`).
    pub k_reference: Vec<f64>,
    /// `K_s` on the nonlinear dofs (`n_nl × n_nl`, symmetric).
    pub k_s: Mat<f64>,
    /// Modal piston load `Φᵀ F_piston` (`Φᵀ (F_piston + K_vib x_0)` with a vibration-only
    /// stiffness `K_vib`: its time-domain rest position, [`crate::vibration_only`]).
    pub load: Vec<f64>,
    /// The 0th harmonic's static flexibility when the brake has a vibration-only stiffness
    /// ([`crate::vibration_only`]); `None`: `Ω⁻²`.
    pub statics: Option<crate::vibration_only::ModalStatics>,
}

impl ModalBrake {
    /// Builds the modal brake at friction `mu` from a brake and its frictionless reference.
    pub fn new(brake: &Brake, reference: &Reference, mu: f64) -> Self {
        let nl_dofs = brake.nonlinear_dofs();
        let nn = nl_dofs.len();
        let n = brake.size();
        let phi = reference.basis.phi.clone();
        let phi_n = Mat::from_fn(nn, n, |i, j| phi[(nl_dofs[i], j)]);
        let x0 = &reference.equilibrium.x;
        // Every pair dof is in `nl_dofs` by construction, so the search always succeeds.
        let local = |d: usize| nl_dofs.partition_point(|&e| e < d);
        let pairs: Vec<ContactPair> = brake.pairs.iter().map(|p| p.renumbered(local)).collect();
        let k_reference: Vec<f64> = brake
            .pairs
            .iter()
            .map(|p| p.response(x0, None, 0.0).normal_derivatives[0])
            .collect();
        let mut k_s = Mat::zeros(nn, nn);
        for (p, &k) in pairs.iter().zip(&k_reference) {
            for &(a, ga) in &p.normal {
                for &(b, gb) in &p.normal {
                    k_s[(a, b)] += k * ga * gb;
                }
            }
        }
        let modal = |f: &[f64]| -> Vec<f64> {
            (0..n)
                .map(|j| (0..n).map(|i| phi[(i, j)] * f[i]).sum())
                .collect()
        };
        let load = modal(&brake.f_piston);
        let (load, statics) = match &brake.k_vibration {
            None => (load, None),
            Some(kv) => {
                let statics = crate::vibration_only::ModalStatics::new(
                    &phi,
                    &phi_n,
                    &reference.basis.omega,
                    kv,
                    &load,
                );
                // The time domain's rest position of the spring: the reference's x_0.
                let mut f = brake.f_piston.clone();
                for (i, fi) in f.iter_mut().enumerate() {
                    *fi += (0..n).map(|j| kv[(i, j)] * x0[j]).sum::<f64>();
                }
                (modal(&f), Some(statics))
            }
        };
        Self {
            mu,
            omega: reference.basis.omega.clone(),
            damping: reference.damping.clone(),
            phi,
            nl_dofs,
            phi_n,
            pairs,
            k_reference,
            k_s,
            load,
            statics,
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

    /// `F_nl(x_n, x_n') - K_s x_n` on the nonlinear dofs (eq 10 minus the springs moved into
    /// the linear part), added to `out`.
    pub fn add_reduced_force(&self, xn: &[f64], vn: Option<&[f64]>, out: &mut [f64]) {
        add_contact_forces(&self.pairs, xn, vn, self.mu, out);
        let nn = self.nl();
        for i in 0..nn {
            out[i] -= (0..nn).map(|j| self.k_s[(i, j)] * xn[j]).sum::<f64>();
        }
    }

    /// Jacobians of [`Self::add_reduced_force`] (`n_nl × n_nl`): with respect to `x_n`, and
    /// with respect to `x_n'` when an element depends on the velocities.
    pub fn reduced_jacobians(
        &self,
        xn: &[f64],
        vn: Option<&[f64]>,
    ) -> (Mat<f64>, Option<Mat<f64>>) {
        let (kx, kv) = contact_jacobians(&self.pairs, self.nl(), xn, vn, self.mu, false);
        (kx - &self.k_s, kv)
    }

    /// Physical displacements `x = Φ q`.
    pub fn physical(&self, q: &[f64]) -> Vec<f64> {
        let n = self.modes();
        (0..n)
            .map(|i| (0..n).map(|j| self.phi[(i, j)] * q[j]).sum())
            .collect()
    }

    /// Nonlinear-dof values `x_n = Φ_n q` (displacements or velocities).
    pub fn nonlinear_part(&self, q: &[f64], xn: &mut [f64]) {
        let n = self.modes();
        for (i, v) in xn.iter_mut().enumerate() {
            *v = (0..n).map(|j| self.phi_n[(i, j)] * q[j]).sum();
        }
    }

    /// Whether any contact element depends on the velocities.
    pub fn velocity_dependent(&self) -> bool {
        self.pairs
            .iter()
            .any(|p| p.law.uses_slip_velocity() || p.law.uses_penetration_rate())
    }
}
