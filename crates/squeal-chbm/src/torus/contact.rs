//! The brake's torus equations in reduced coordinates (module docs of [`crate::torus`]): the
//! contact force `c(y) = Q_Eᵀ G(Q_R y)` and the receptance `B(w) = Q_Rᵀ H(iw) Q_E`.

use faer::{Mat, c64};
use squeal_brake::harmonic::ModalSolver;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::LocalJacobian;
use squeal_hbm::torus::{LinearBlocks, TorusForce, TorusLinear};

/// `(Q_E, Q_R)` of `mb` (module docs): the same spaces as Hill's Woodbury solve.
pub(crate) fn contact_spaces(mb: &ModalBrake) -> (Mat<f64>, Mat<f64>) {
    crate::floquet::contact_bases(mb)
}

/// The contact force in reduced coordinates: `c(y) = Q_Eᵀ G(Q_R y)` (module docs).
pub struct ReducedContact {
    mb: ModalBrake,
    qe: Mat<f64>,
    pub(crate) qr: Mat<f64>,
    pattern: Vec<(usize, usize)>,
    velocity: bool,
    /// `K_s` row-major (`n_nl × n_nl`).
    springs: Vec<f64>,
}

/// Rows of `K_s` [`ReducedContact::reduced_force`] sums together.
const ROWS: usize = 4;

impl ReducedContact {
    pub(crate) fn new(mb: &ModalBrake, qe: Mat<f64>, qr: Mat<f64>) -> Self {
        let pattern = (0..qe.ncols())
            .flat_map(|i| (0..qr.ncols()).map(move |k| (i, k)))
            .collect();
        let k = &mb.k_s;
        let springs = (0..k.nrows())
            .flat_map(|i| (0..k.ncols()).map(move |j| k[(i, j)]))
            .collect();
        Self {
            velocity: mb.velocity_dependent(),
            mb: mb.clone(),
            qe,
            qr,
            pattern,
            springs,
        }
    }

    /// `out += G(x_n)`: the contact forces minus the springs `K_s x_n`, the bits of
    /// [`ModalBrake::add_reduced_force`] (each row's sum in the same order, from `-0.0` as
    /// `Sum` for `f64`), with [`ROWS`] rows of `K_s` summed side by side.
    pub(crate) fn reduced_force(&self, x: &[f64], v: Option<&[f64]>, out: &mut [f64]) {
        squeal_brake::model::add_contact_forces(&self.mb.pairs, x, v, self.mb.mu, out);
        let nn = x.len();
        let mut rows = self.springs.chunks_exact(ROWS * nn);
        let mut outs = out.chunks_exact_mut(ROWS);
        for (block, o) in (&mut rows).zip(&mut outs) {
            let mut acc = [-0.0; ROWS];
            for (j, xj) in x.iter().enumerate() {
                for l in 0..ROWS {
                    acc[l] += block[l * nn + j] * xj;
                }
            }
            o.iter_mut().zip(&acc).for_each(|(o, a)| *o -= a);
        }
        for (row, o) in rows.remainder().chunks_exact(nn).zip(outs.into_remainder()) {
            *o -= row.iter().zip(x).map(|(a, b)| a * b).sum::<f64>();
        }
    }

    /// Sets μ.
    pub fn set_mu(&mut self, mu: f64) {
        self.mb.mu = mu;
    }

    /// `Q_R`: the reduced coordinates are `y = Q_Rᵀ x_n`.
    pub(crate) fn qr(&self) -> &Mat<f64> {
        &self.qr
    }

    fn lift(&self, y: &[f64]) -> Vec<f64> {
        (0..self.qr.nrows())
            .map(|i| (0..y.len()).map(|k| self.qr[(i, k)] * y[k]).sum())
            .collect()
    }
}

impl TorusForce for ReducedContact {
    fn n_inputs(&self) -> usize {
        self.qr.ncols()
    }

    fn n_outputs(&self) -> usize {
        self.qe.ncols()
    }

    fn pattern(&self) -> &[(usize, usize)] {
        &self.pattern
    }

    fn depends_on_velocity(&self) -> bool {
        self.velocity
    }

    fn eval(&self, y: &[f64], ydot: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>) {
        let x = self.lift(y);
        let v = self.velocity.then(|| self.lift(ydot));
        let mut g = vec![0.0; x.len()];
        self.reduced_force(&x, v.as_deref(), &mut g);
        let (qe, qr) = (&self.qe, &self.qr);
        for (i, fi) in f.iter_mut().enumerate() {
            *fi = (0..g.len()).map(|r| qe[(r, i)] * g[r]).sum();
        }
        if let Some(j) = jac {
            let (jx, jv) = self.mb.reduced_jacobians(&x, v.as_deref());
            let project = |m: &Mat<f64>, out: &mut [f64]| {
                let p = qe.transpose() * m * qr;
                for (o, &(i, k)) in out.iter_mut().zip(&self.pattern) {
                    *o = p[(i, k)];
                }
            };
            project(&jx, j.dfdx);
            if let Some(jv) = &jv {
                project(jv, j.dfdxdot);
            }
        }
    }
}

/// The brake's receptance between the contact directions: `A = I`,
/// `B(w) = Q_Rᵀ Φ_n Δ(iw)⁻¹ Φ_nᵀ Q_E` (module docs).
pub struct BrakeReceptance {
    mb: ModalBrake,
    /// `Q_Rᵀ Φ_n` (`q_R × modes`) and `Q_Eᵀ Φ_n` (`q_E × modes`).
    pub(crate) phi_r: Mat<f64>,
    phi_e: Mat<f64>,
}

impl BrakeReceptance {
    pub(crate) fn new(mb: &ModalBrake, qe: &Mat<f64>, qr: &Mat<f64>) -> Self {
        Self {
            mb: mb.clone(),
            phi_r: qr.transpose() * &mb.phi_n,
            phi_e: qe.transpose() * &mb.phi_n,
        }
    }
}

impl TorusLinear for BrakeReceptance {
    fn n_dofs(&self) -> usize {
        self.phi_r.nrows()
    }

    fn n_forces(&self) -> usize {
        self.phi_e.nrows()
    }

    fn blocks(&mut self, w: f64, mut out: LinearBlocks<'_>) {
        let (nr, ne, n) = (self.phi_r.nrows(), self.phi_e.nrows(), self.mb.modes());
        for i in 0..nr {
            for j in 0..nr {
                out.a[(i, j)] = c64::new(if i == j { 1.0 } else { 0.0 }, 0.0);
                out.da[(i, j)] = c64::new(0.0, 0.0);
            }
        }
        let l = c64::new(0.0, w);
        let solver = ModalSolver::new(&self.mb.omega, &self.mb.damping, l);
        // Δ⁻¹ Φ_Eᵀ and its w-derivative -Δ⁻¹ (dΔ/dw) Δ⁻¹ Φ_Eᵀ, dΔ/dw = -2w I + i D.
        let pe = Mat::<c64>::from_fn(n, ne, |j, c| c64::new(self.phi_e[(c, j)], 0.0));
        let x = solver.solve(pe.as_ref());
        let dd = Mat::<c64>::from_fn(n, ne, |i, c| {
            let mut v = x[(i, c)] * (-2.0 * w);
            match self.mb.damping.diagonal() {
                Some(d) => v += c64::new(0.0, d[i]) * x[(i, c)],
                None => {
                    for j in 0..n {
                        v += c64::new(0.0, self.mb.damping.entry(i, j)) * x[(j, c)];
                    }
                }
            }
            -v
        });
        let dx = solver.solve(dd.as_ref());
        for i in 0..nr {
            for c in 0..ne {
                let (mut b, mut db) = (c64::new(0.0, 0.0), c64::new(0.0, 0.0));
                for j in 0..n {
                    b += x[(j, c)] * self.phi_r[(i, j)];
                    db += dx[(j, c)] * self.phi_r[(i, j)];
                }
                out.b[(i, c)] = b;
                out.db[(i, c)] = db;
            }
        }
    }
}
