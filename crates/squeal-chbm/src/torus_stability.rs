//! The stability of the brake's tori (issue 24, item 1): their Lyapunov exponents
//! ([`squeal_hbm::torus::lyapunov`]) from the linearized modal equations along the torus.
//!
//! The modal equations (eq 11 with the springs moved into the linear part) are
//! `q̈ + D q̇ + Ω² q + Φ_nᵀ G(Φ_n q, Φ_n q̇) = Φᵀ F`; in the state `(q, q̇)` their Jacobian is
//! `J = [[0, I], [-Ω² - Φ_nᵀ K Φ_n, -D - Φ_nᵀ C Φ_n]]` with `K = ∂G/∂x_n`, `C = ∂G/∂ẋ_n` — the
//! Jacobian [`squeal_brake::dynamics::BrakeDynamics`] gives a time integration. On the torus
//! the contact sees the nonlinear dofs only through `y = Q_Rᵀ x_n` (the reduced coordinates of
//! [`crate::torus`]), so `K` and `C` are evaluated at `x_n = Q_R y(θ)`,
//! `ẋ_n = Q_R ẏ(θ)`, with `y(θ)` and `ẏ(θ)` from the torus' Fourier series, and
//! `Φ_nᵀ K Φ_n = (Φ_nᵀ Q_E)(Q_Eᵀ K Q_R)(Q_Rᵀ Φ_n)`: a product by `J` costs `O(n (q_R + q_E))`
//! instead of `O(n²)`. The exponents come out in 1/s.

use crate::torus::TorusPoint;
use faer::Mat;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::HbmError;
use squeal_hbm::torus::TorusBasis;
use squeal_hbm::torus::lyapunov::{
    LyapunovOptions, LyapunovSpectrum, TorusVariational, lyapunov_exponents,
};

/// The brake's modal equations linearized along a torus (module docs).
pub struct BrakeVariational {
    mb: ModalBrake,
    basis: TorusBasis,
    coeffs: Vec<f64>,
    omega: [f64; 2],
    qr: Mat<f64>,
    qe: Mat<f64>,
    /// `Q_Rᵀ Φ_n` (`q_R × n`) and `Φ_nᵀ Q_E` (`n × q_E`).
    pr: Mat<f64>,
    pe: Mat<f64>,
    /// `Q_Eᵀ K Q_R` and `Q_Eᵀ C Q_R` at the current angles.
    k: Mat<f64>,
    c: Option<Mat<f64>>,
}

impl BrakeVariational {
    /// The linearization of `mb`'s brake (at the torus' μ) along the torus `point` on `basis`.
    pub fn new(mb: &ModalBrake, basis: &TorusBasis, point: &TorusPoint) -> Result<Self, HbmError> {
        basis.check_len("torus coefficients", point.coeffs.len())?;
        let mut mb = mb.clone();
        mb.mu = point.mu;
        let (qe, qr) = crate::floquet::contact_bases(&mb);
        if qr.ncols() != basis.n_dofs() {
            return Err(HbmError::BadOption(
                "the torus' basis does not match the brake's reduced contact coordinates",
            ));
        }
        let pr = qr.transpose() * &mb.phi_n;
        let pe = mb.phi_n.transpose() * &qe;
        let (ne, nr) = (qe.ncols(), qr.ncols());
        Ok(Self {
            basis: basis.clone(),
            coeffs: point.coeffs.clone(),
            omega: point.omega,
            k: Mat::zeros(ne, nr),
            c: None,
            mb,
            qr,
            qe,
            pr,
            pe,
        })
    }

    fn lift(&self, y: &[f64]) -> Vec<f64> {
        (0..self.qr.nrows())
            .map(|i| (0..y.len()).map(|k| self.qr[(i, k)] * y[k]).sum())
            .collect()
    }

    /// `out -= Φ_nᵀ Q_E m Q_Rᵀ Φ_n v`.
    fn subtract_coupling(&self, m: &Mat<f64>, v: &[f64], out: &mut [f64]) {
        let n = v.len();
        let a: Vec<f64> = (0..self.pr.nrows())
            .map(|r| (0..n).map(|j| self.pr[(r, j)] * v[j]).sum())
            .collect();
        let b: Vec<f64> = (0..m.nrows())
            .map(|e| (0..a.len()).map(|r| m[(e, r)] * a[r]).sum())
            .collect();
        for (j, o) in out.iter_mut().enumerate() {
            *o -= (0..b.len()).map(|e| self.pe[(j, e)] * b[e]).sum::<f64>();
        }
    }
}

impl TorusVariational for BrakeVariational {
    fn dim(&self) -> usize {
        2 * self.mb.modes()
    }

    fn set_angles(&mut self, theta: [f64; 2]) -> Result<(), HbmError> {
        let nr = self.basis.n_dofs();
        let (mut y, mut ydot) = (vec![0.0; nr], vec![0.0; nr]);
        self.basis.displacement_at(&self.coeffs, theta, &mut y)?;
        let x = self.lift(&y);
        let v = if self.mb.velocity_dependent() {
            self.basis
                .velocity_at(&self.coeffs, self.omega, theta, &mut ydot)?;
            Some(self.lift(&ydot))
        } else {
            None
        };
        let (kx, kv) = self.mb.reduced_jacobians(&x, v.as_deref());
        self.k = self.qe.transpose() * &kx * &self.qr;
        self.c = kv.map(|m| self.qe.transpose() * &m * &self.qr);
        Ok(())
    }

    fn apply(&self, v: &[f64], out: &mut [f64]) {
        let n = self.mb.modes();
        let (q, qd) = v.split_at(n);
        let (oq, ov) = out.split_at_mut(n);
        oq.copy_from_slice(qd);
        self.mb.damping.apply(qd, ov);
        for j in 0..n {
            ov[j] = -ov[j] - self.mb.omega[j] * self.mb.omega[j] * q[j];
        }
        self.subtract_coupling(&self.k, q, ov);
        if let Some(c) = &self.c {
            self.subtract_coupling(c, qd, ov);
        }
    }
}

/// The Lyapunov exponents of the torus `point` (on `basis`) of `mb`'s brake, in 1/s.
pub fn torus_lyapunov(
    mb: &ModalBrake,
    basis: &TorusBasis,
    point: &TorusPoint,
    opts: &LyapunovOptions,
) -> Result<LyapunovSpectrum, HbmError> {
    let mut sys = BrakeVariational::new(mb, basis, point)?;
    lyapunov_exponents(&mut sys, point.omega, opts)
}
