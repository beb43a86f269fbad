//! Eq (11) as a first-order system for time integration, in the modal coordinates of
//! [`crate::modal_brake`]: with `y = [q; v]`,
//!
//! `q' = v`, `v' = Φᵀ F_piston - D v - Ω² q - Φ_nᵀ G(Φ_n q, Φ_n v)`, `G = F_nl - K_s x_n`,
//!
//! and the analytic Jacobian `[[0, I], [-(Ω² + Φ_nᵀ (K_NL - K_s) Φ_n), -(D + Φ_nᵀ C_NL Φ_n)]]`,
//! where `K_NL`, `C_NL` are the contact elements' Jacobians of eqs (18)–(19) (zero for open
//! pairs; `C_NL = 0` unless an element depends on the velocities). The right-hand side costs
//! `O(n n_nl)` (`O(n²)` with a full modal damping); the Jacobian `O(n² n_nl)`.

use crate::modal_brake::ModalBrake;
use faer::linalg::solvers::Solve;
use faer::{Mat, MatMut};
use squeal_ode::OdeSystem;
use std::cell::RefCell;

/// Scratch vectors of one right-hand side evaluation (`x_n`, `v_n`, `G`, `D v`).
#[derive(Default)]
struct Scratch {
    xn: Vec<f64>,
    vn: Vec<f64>,
    g: Vec<f64>,
    dv: Vec<f64>,
}

/// The brake's equations of motion for [`squeal_ode`].
pub struct BrakeDynamics<'a> {
    /// The brake in modal coordinates whose eq (11) this is.
    pub brake: &'a ModalBrake,
    scratch: RefCell<Scratch>,
}

impl<'a> BrakeDynamics<'a> {
    /// The equations of motion of `brake`, state `y = [q; q']` of dimension `2 n`.
    pub fn new(brake: &'a ModalBrake) -> Self {
        Self {
            brake,
            scratch: RefCell::new(Scratch::default()),
        }
    }

    /// State `[q; v]` of modal displacements and velocities.
    pub fn state(q: &[f64], v: &[f64]) -> Vec<f64> {
        q.iter().chain(v).copied().collect()
    }

    /// State `[q; v]` of physical displacements `x` and velocities `v`: `q = Φ⁻¹ x`
    /// (one LU of the square modal matrix). `None` if the lengths differ from the brake's
    /// dofs or `Φ` is singular.
    pub fn state_from_physical(brake: &ModalBrake, x: &[f64], v: &[f64]) -> Option<Vec<f64>> {
        let n = brake.modes();
        if x.len() != n || v.len() != n || brake.phi.nrows() != n || brake.phi.ncols() != n {
            return None;
        }
        let rhs = Mat::from_fn(n, 2, |i, j| if j == 0 { x[i] } else { v[i] });
        let sol = brake.phi.partial_piv_lu().solve(&rhs);
        let y: Vec<f64> = (0..n)
            .map(|i| sol[(i, 0)])
            .chain((0..n).map(|i| sol[(i, 1)]))
            .collect();
        y.iter().all(|v| v.is_finite()).then_some(y)
    }
}

impl OdeSystem for BrakeDynamics<'_> {
    fn dim(&self) -> usize {
        2 * self.brake.modes()
    }

    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let mb = self.brake;
        let (n, nn) = (mb.modes(), mb.nl());
        let (q, v) = y.split_at(n);
        let mut s = self.scratch.borrow_mut();
        let Scratch { xn, vn, g, dv } = &mut *s;
        xn.resize(nn, 0.0);
        g.clear();
        g.resize(nn, 0.0);
        dv.resize(n, 0.0);
        mb.nonlinear_part(q, xn);
        let velocity = mb.velocity_dependent();
        if velocity {
            vn.resize(nn, 0.0);
            mb.nonlinear_part(v, vn);
        }
        mb.add_reduced_force(xn, velocity.then_some(&vn[..]), g);
        mb.damping.apply(v, dv);
        for j in 0..n {
            dy[j] = v[j];
            let coupling: f64 = (0..nn).map(|i| mb.phi_n[(i, j)] * g[i]).sum();
            dy[n + j] = mb.load[j] - dv[j] - mb.omega[j] * mb.omega[j] * q[j] - coupling;
        }
    }

    fn jacobian(&self, _t: f64, y: &[f64], jac: MatMut<'_, f64>) {
        let mb = self.brake;
        let (n, nn) = (mb.modes(), mb.nl());
        let mut xn = vec![0.0; nn];
        mb.nonlinear_part(&y[..n], &mut xn);
        let vn = mb.velocity_dependent().then(|| {
            let mut vn = vec![0.0; nn];
            mb.nonlinear_part(&y[n..], &mut vn);
            vn
        });
        let (kg, cg) = mb.reduced_jacobians(&xn, vn.as_deref());
        // Φ_nᵀ kg Φ_n in two products (and the same for cg).
        let project = |m: &Mat<f64>| mb.phi_n.transpose() * (m * &mb.phi_n);
        let block = project(&kg);
        let damping_block = cg.as_ref().map(project);
        state_jacobian(mb, &block, damping_block.as_ref(), jac);
    }
}

/// The first-order Jacobian `[[0, I], [−Ω² − K, −D − C]]` of the modal brake's state
/// `[q; q']`, with the contact's modal stiffness block `k = Φ_nᵀ J_x Φ_n` and, for a
/// velocity-dependent element, its damping block `c = Φ_nᵀ J_v Φ_n` (`n × n` each).
pub fn state_jacobian(
    mb: &ModalBrake,
    k: &Mat<f64>,
    c: Option<&Mat<f64>>,
    mut jac: MatMut<'_, f64>,
) {
    let n = mb.modes();
    jac.fill(0.0);
    for j in 0..n {
        jac[(j, n + j)] = 1.0;
        for i in 0..n {
            jac[(n + j, i)] = -k[(j, i)];
            jac[(n + j, n + i)] = -mb.damping.entry(j, i) - c.map_or(0.0, |b| b[(j, i)]);
        }
        jac[(n + j, j)] -= mb.omega[j] * mb.omega[j];
    }
}
