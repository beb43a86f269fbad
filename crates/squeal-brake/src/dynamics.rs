//! Eq (11) as a first-order system for time integration, in the modal coordinates of
//! [`crate::modal_brake`]: with `y = [q; v]`,
//!
//! `q' = v`, `v' = Φᵀ F_piston - D v - Ω² q - Φ_nᵀ G(Φ_n q)`, `G = F_nl - K_s x_n`,
//!
//! and the analytic Jacobian `[[0, I], [-(Ω² + Φ_nᵀ (K_NL - K_s) Φ_n), -D]]`, where `K_NL` is the
//! contact and friction Jacobian of eqs (18)–(19) (zero for open pairs). The right-hand side
//! costs `O(n n_nl)`; the Jacobian `O(n² n_nl)`.

use crate::modal_brake::ModalBrake;
use faer::MatMut;
use squeal_ode::OdeSystem;

/// The brake's equations of motion for [`squeal_ode`].
pub struct BrakeDynamics<'a> {
    pub brake: &'a ModalBrake,
}

impl BrakeDynamics<'_> {
    /// State of a physical displacement `x` and velocity `v` (modal projection
    /// `q = Φ⁻¹ x = Φᵀ M x` needs `M`; callers pass modal coordinates directly instead).
    pub fn state(q: &[f64], v: &[f64]) -> Vec<f64> {
        q.iter().chain(v).copied().collect()
    }
}

impl OdeSystem for BrakeDynamics<'_> {
    fn dim(&self) -> usize {
        2 * self.brake.modes()
    }

    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let mb = self.brake;
        let n = mb.modes();
        let (q, v) = y.split_at(n);
        let mut xn = vec![0.0; mb.nl()];
        mb.nonlinear_part(q, &mut xn);
        let mut g = vec![0.0; mb.nl()];
        mb.add_reduced_force(&xn, &mut g);
        for j in 0..n {
            dy[j] = v[j];
            let coupling: f64 = (0..mb.nl()).map(|i| mb.phi_n[(i, j)] * g[i]).sum();
            dy[n + j] =
                mb.load[j] - mb.damping[j] * v[j] - mb.omega[j] * mb.omega[j] * q[j] - coupling;
        }
    }

    fn jacobian(&self, _t: f64, y: &[f64], mut jac: MatMut<'_, f64>) {
        let mb = self.brake;
        let (n, nn) = (mb.modes(), mb.nl());
        let mut xn = vec![0.0; nn];
        mb.nonlinear_part(&y[..n], &mut xn);
        let mut kg = faer::Mat::<f64>::zeros(nn, nn);
        mb.add_reduced_jacobian(&xn, &mut kg);
        // Φ_nᵀ kg Φ_n in two products.
        let kphi = &kg * &mb.phi_n;
        let block = mb.phi_n.transpose() * &kphi;
        for r in 0..2 * n {
            for c in 0..2 * n {
                jac[(r, c)] = 0.0;
            }
        }
        for j in 0..n {
            jac[(j, n + j)] = 1.0;
            jac[(n + j, n + j)] = -mb.damping[j];
            for c in 0..n {
                jac[(n + j, c)] = -block[(j, c)];
            }
            jac[(n + j, j)] -= mb.omega[j] * mb.omega[j];
        }
    }
}
