//! The extended periodic motion concept's harmonic balance on the condensed brake: the linear
//! part with the artificial damping `-2ζω M ẋ` ([`EpmcStiffness`]) and the residual
//! `[f1; phase; amplitude]` in the unknowns `[U~, ω, ζ]` ([`EpmcProblem`]). The derivation is in
//! the parent module; the derivatives used here are:
//!
//! * the shifted damping `D' = D + s I` with `s = -2ζω` (the modal mass is `I`), so
//!   `∂/∂ω = ∂/∂ω|_{D'} - 2ζ ∂/∂s` and `∂/∂ζ = -2ω ∂/∂s`;
//! * with `Δ_k = Ω² - (kω)² + ikω D'` and `Λ_k = (Φ_n Δ_k⁻¹ Φ_nᵀ)⁻¹` (eq 32),
//!   `∂(Λ_k v)/∂s = Λ_k Φ_n Δ_k⁻¹ (ikω) Δ_k⁻¹ Φ_nᵀ Λ_k v` (from `dΛ = -Λ dH Λ`,
//!   `dH = -Φ_n Δ⁻¹ dΔ Δ⁻¹ Φ_nᵀ`, `dΔ_k/ds = ikω`);
//! * the modal first harmonic `q = T v`, `T = Δ_1⁻¹ Φ_nᵀ Λ_1` (eq 35 for `k = 1`: the motion of
//!   every mode that the nonlinear dofs' `v = U1c - i U1s` carries), and for `θ = ω, ζ`
//!   `dq/dθ = -(p - T Φ_n p)`, `p = Δ_1⁻¹ (∂Δ_1/∂θ) q`, with
//!   `∂Δ_1/∂ω = -2ω - 4iζω + iD`, `∂Δ_1/∂ζ = -2iω²`.

use faer::reborrow::ReborrowMut;
use faer::{Mat, MatMut, c64};
use squeal_brake::damping::ModalDamping;
use squeal_brake::harmonic::{CondensedStiffness, ContactForce, ModalSolver};
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::lm::LeastSquaresProblem;
use squeal_hbm::{DynamicStiffness, HarmonicBalance, HarmonicLayout, HbmError, Part};

/// `Λ_eq(ω)` of eq (32) with the modal damping `D - 2ζω I`: [`CondensedStiffness`] rebuilt for
/// each `(ω, ζ)` (its `Λ_eq,0` does not depend on either).
pub struct EpmcStiffness {
    mb: ModalBrake,
    base: ModalDamping,
    harmonics: usize,
    zeta: f64,
    cached: Option<(f64, f64, CondensedStiffness)>,
}

impl EpmcStiffness {
    /// For the modal brake `mb` and harmonics `0..=harmonics`, with `ζ = 0`.
    pub fn new(mb: &ModalBrake, harmonics: usize) -> Self {
        Self {
            mb: mb.clone(),
            base: mb.damping.clone(),
            harmonics,
            zeta: 0.0,
            cached: None,
        }
    }

    /// Sets the modal damping ratio ζ of the artificial term.
    pub fn set_zeta(&mut self, zeta: f64) {
        self.zeta = zeta;
    }

    /// The condensed stiffness at `(ω, ζ)`.
    fn at(&mut self, omega: f64) -> &mut CondensedStiffness {
        let fresh = matches!(&self.cached, Some((w, z, _)) if *w == omega && *z == self.zeta);
        if !fresh {
            let s = -2.0 * self.zeta * omega;
            let shift: Vec<(usize, f64)> = (0..self.mb.modes()).map(|j| (j, s)).collect();
            self.mb.damping = self.base.with_added(&shift);
            let mut cs = CondensedStiffness::new(&self.mb, self.harmonics);
            cs.update(omega);
            self.cached = Some((omega, self.zeta, cs));
        }
        match &mut self.cached {
            Some((_, _, cs)) => cs,
            None => unreachable!("set just above"),
        }
    }

    /// The modal solver `Δ_k⁻¹` at `ikω` with the shifted damping (after [`Self::at`]).
    fn solver(&self, k: usize, omega: f64) -> ModalSolver {
        ModalSolver::new(
            &self.mb.omega,
            &self.mb.damping,
            c64::new(0.0, k as f64 * omega),
        )
    }

    /// `∂(Λ_eq U)/∂s` for the damping shift `s` (module documentation).
    pub fn shift_derivative(&mut self, layout: &HarmonicLayout, omega: f64, u: &[f64]) -> Vec<f64> {
        let nn = layout.n_dofs();
        let mut out = vec![0.0; layout.len()];
        self.at(omega);
        for k in 1..=layout.n_harmonics().min(self.harmonics) {
            let (rc, rs) = (
                layout.block_range(2 * k - 1).start,
                layout.block_range(2 * k).start,
            );
            let v: Vec<c64> = (0..nn).map(|i| c64::new(u[rc + i], -u[rs + i])).collect();
            let lk = self.block(k);
            let w = matvec(&lk, &v);
            let solver = self.solver(k, omega);
            let mut y = solver.solve_vec(&self.phi_t_times(&w));
            for v in &mut y {
                *v *= c64::new(0.0, k as f64 * omega);
            }
            solver.solve_in_place(&mut y);
            let e = matvec(&lk, &self.phi_times(&y));
            for i in 0..nn {
                out[rc + i] += e[i].re;
                out[rs + i] -= e[i].im;
            }
        }
        out
    }

    fn block(&mut self, k: usize) -> Mat<c64> {
        match &self.cached {
            Some((_, _, cs)) => cs.block(k).clone(),
            None => unreachable!("callers run `at` first"),
        }
    }

    /// `Φ_nᵀ w`.
    fn phi_t_times(&self, w: &[c64]) -> Vec<c64> {
        let phi = &self.mb.phi_n;
        (0..phi.ncols())
            .map(|j| (0..phi.nrows()).map(|i| w[i] * phi[(i, j)]).sum())
            .collect()
    }

    /// `Φ_n y`.
    fn phi_times(&self, y: &[c64]) -> Vec<c64> {
        let phi = &self.mb.phi_n;
        (0..phi.nrows())
            .map(|i| (0..phi.ncols()).map(|j| y[j] * phi[(i, j)]).sum())
            .collect()
    }

    /// The modal first harmonic `q = T v` and `T = Δ_1⁻¹ Φ_nᵀ Λ_1` (`n × n_nl`).
    pub fn modal_first_harmonic(
        &mut self,
        layout: &HarmonicLayout,
        omega: f64,
        u: &[f64],
    ) -> (Vec<c64>, Mat<c64>) {
        let nn = layout.n_dofs();
        self.at(omega);
        let l1 = self.block(1);
        let phi = &self.mb.phi_n;
        let b = Mat::<c64>::from_fn(phi.ncols(), nn, |j, c| {
            (0..nn).map(|i| l1[(i, c)] * phi[(i, j)]).sum()
        });
        let t = self.solver(1, omega).solve(b.as_ref());
        let (rc, rs) = (layout.block_range(1).start, layout.block_range(2).start);
        let v: Vec<c64> = (0..nn).map(|i| c64::new(u[rc + i], -u[rs + i])).collect();
        (matvec(&t, &v), t)
    }

    /// `dq/dθ` for `θ = ω` and `θ = ζ` at `(ω, ζ)` (module documentation).
    fn modal_rates(&mut self, omega: f64, q: &[c64], t: &Mat<c64>) -> [Vec<c64>; 2] {
        self.at(omega);
        let n = q.len();
        let (re, im): (Vec<f64>, Vec<f64>) = q.iter().map(|v| (v.re, v.im)).unzip();
        let (mut dre, mut dim) = (vec![0.0; n], vec![0.0; n]);
        self.base.apply(&re, &mut dre);
        self.base.apply(&im, &mut dim);
        let z = self.zeta;
        let d_omega: Vec<c64> = (0..n)
            .map(|j| {
                q[j] * c64::new(-2.0 * omega, -4.0 * z * omega)
                    + c64::new(dre[j], dim[j]) * c64::new(0.0, 1.0)
            })
            .collect();
        let d_zeta: Vec<c64> = q
            .iter()
            .map(|v| v * c64::new(0.0, -2.0 * omega * omega))
            .collect();
        let solver = self.solver(1, omega);
        [d_omega, d_zeta].map(|dd| {
            let p = solver.solve_vec(&dd);
            let back = matvec(t, &self.phi_times(&p));
            p.iter().zip(&back).map(|(p, b)| b - p).collect()
        })
    }
}

fn matvec(m: &Mat<c64>, v: &[c64]) -> Vec<c64> {
    (0..m.nrows())
        .map(|i| (0..m.ncols()).map(|j| m[(i, j)] * v[j]).sum())
        .collect()
}

impl DynamicStiffness for EpmcStiffness {
    fn n_dofs(&self) -> usize {
        self.mb.nl()
    }

    fn add_apply(&mut self, layout: &HarmonicLayout, omega: f64, u: &[f64], out: &mut [f64]) {
        self.at(omega).add_apply(layout, omega, u, out);
    }

    /// `jac += Λ_eq` and `d_omega += ∂(Λ_eq U)/∂ω` at fixed ζ (the shift's share included).
    fn add_jacobian(
        &mut self,
        layout: &HarmonicLayout,
        omega: f64,
        u: &[f64],
        jac: MatMut<'_, f64>,
        d_omega: &mut [f64],
    ) {
        self.at(omega).add_jacobian(layout, omega, u, jac, d_omega);
        let ds = self.shift_derivative(layout, omega, u);
        let z = self.zeta;
        for (d, s) in d_omega.iter_mut().zip(&ds) {
            *d -= 2.0 * z * s;
        }
    }
}

/// The scales of [`EpmcProblem`]'s rows.
#[derive(Clone, Copy, Debug)]
pub struct EpmcScales {
    /// Force scale of the static rows (block 0) of the harmonic balance (N).
    pub force: f64,
    /// Force scale of the harmonics' rows (N): the motion's own force level, so that the
    /// tolerance means the same at every amplitude.
    pub dynamic: f64,
    /// Displacement scale of the phase row (m).
    pub phase: f64,
}

/// `[f1 / force; U1s[d] / phase; |q_1| / a - 1]` in `[U~, ω, ζ]` at the modal amplitude `a`.
pub struct EpmcProblem<'a> {
    hb: &'a mut HarmonicBalance<EpmcStiffness, ContactForce>,
    phase_index: usize,
    amplitude: f64,
    scales: EpmcScales,
    jac_omega: Vec<f64>,
}

impl<'a> EpmcProblem<'a> {
    /// The problem at modal amplitude `amplitude`, the phase fixed on nonlinear dof `phase_dof`.
    pub fn new(
        hb: &'a mut HarmonicBalance<EpmcStiffness, ContactForce>,
        phase_dof: usize,
        amplitude: f64,
        scales: EpmcScales,
    ) -> Result<Self, HbmError> {
        let layout = hb.layout();
        let phase_index =
            layout
                .index(1, Part::Sin, phase_dof)
                .ok_or(HbmError::BadPhaseCondition {
                    dof: phase_dof,
                    n_dofs: layout.n_dofs(),
                    n_harmonics: layout.n_harmonics(),
                })?;
        Ok(Self {
            jac_omega: vec![0.0; layout.len()],
            hb,
            phase_index,
            amplitude,
            scales,
        })
    }

    /// The scale of harmonic balance row `i` (`n` dofs per block).
    fn row_scale(&self, i: usize, n: usize) -> f64 {
        if i < n {
            self.scales.force
        } else {
            self.scales.dynamic
        }
    }

    fn split(z: &[f64], len: usize) -> (&[f64], f64, f64) {
        (&z[..len], z[len], z[len + 1])
    }
}

impl LeastSquaresProblem for EpmcProblem<'_> {
    type Error = HbmError;

    fn n_params(&self) -> usize {
        self.hb.layout().len() + 2
    }

    fn n_residuals(&self) -> usize {
        self.hb.layout().len() + 2
    }

    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), HbmError> {
        let layout = self.hb.layout();
        let len = layout.len();
        let (u, omega, zeta) = Self::split(z, len);
        if !(omega.is_finite() && omega > 0.0 && zeta.is_finite()) {
            r.fill(f64::NAN);
            return Ok(());
        }
        self.hb.linear_mut().set_zeta(zeta);
        match self.hb.residual(u, omega, &mut r[..len]) {
            Ok(()) => {}
            Err(HbmError::NonFiniteForce { .. }) => {
                r.fill(f64::NAN);
                return Ok(());
            }
            Err(e) => return Err(e),
        }
        let nn = layout.n_dofs();
        for (i, v) in r[..len].iter_mut().enumerate() {
            *v /= self.row_scale(i, nn);
        }
        r[len] = u[self.phase_index] / self.scales.phase;
        let (q, _) = self.hb.linear_mut().modal_first_harmonic(&layout, omega, u);
        r[len + 1] = norm(&q) / self.amplitude - 1.0;
        Ok(())
    }

    fn jacobian(&mut self, z: &[f64], mut jac: MatMut<'_, f64>) -> Result<(), HbmError> {
        let layout = self.hb.layout();
        let (len, nn) = (layout.len(), layout.n_dofs());
        let (u, omega, zeta) = Self::split(z, len);
        jac.fill(0.0);
        self.hb.linear_mut().set_zeta(zeta);
        self.hb.jacobian(
            u,
            omega,
            jac.rb_mut().submatrix_mut(0, 0, len, len),
            &mut self.jac_omega,
        )?;
        let ds = self.hb.linear_mut().shift_derivative(&layout, omega, u);
        for i in 0..len {
            let inv = 1.0 / self.row_scale(i, nn);
            for j in 0..len {
                jac[(i, j)] *= inv;
            }
            jac[(i, len)] = self.jac_omega[i] * inv;
            jac[(i, len + 1)] = -2.0 * omega * ds[i] * inv;
        }
        jac[(len, self.phase_index)] = 1.0 / self.scales.phase;
        // |q| = sqrt(qᴴq): d|q| = Re(qᴴ dq) / |q|.
        let st = self.hb.linear_mut();
        let (q, t) = st.modal_first_harmonic(&layout, omega, u);
        let s = norm(&q).max(f64::MIN_POSITIVE) * self.amplitude;
        let (rc, rs) = (layout.block_range(1).start, layout.block_range(2).start);
        for c in 0..nn {
            let g: c64 = (0..q.len()).map(|m| q[m].conj() * t[(m, c)]).sum();
            // dv/dU1c = e_c, dv/dU1s = -i e_c.
            jac[(len + 1, rc + c)] = g.re / s;
            jac[(len + 1, rs + c)] = g.im / s;
        }
        let [dq_omega, dq_zeta] = st.modal_rates(omega, &q, &t);
        let dot = |dq: &[c64]| {
            q.iter()
                .zip(dq)
                .map(|(a, b)| (a.conj() * b).re)
                .sum::<f64>()
        };
        jac[(len + 1, len)] = dot(&dq_omega) / s;
        jac[(len + 1, len + 1)] = dot(&dq_zeta) / s;
        Ok(())
    }
}

/// `|v|` of a complex vector.
pub fn norm(v: &[c64]) -> f64 {
    v.iter().map(|x| x.norm_sqr()).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Contact, FrictionSystem};
    use squeal_brake::harmonic::condensed_load;

    /// The analytic Jacobian of [`EpmcProblem`] against central differences on the 2-dof
    /// oscillator (non-proportional damping, so the `D` terms count), at a motion with every
    /// harmonic nonzero and ζ ≠ 0. Central differences with a step of 1e-6 of each unknown's
    /// size are accurate to ~1e-8 of the row's scale.
    #[test]
    fn the_jacobian_is_the_derivative_of_the_residual() {
        let m = Mat::<f64>::identity(2, 2);
        let c = Mat::from_fn(2, 2, |i, j| [[20.0, 5.0], [5.0, 60.0]][i][j]);
        let k = Mat::from_fn(2, 2, |i, j| [[1.0e6, 1.0e5], [1.0e5, 1.0e6]][i][j]);
        let pair = Contact::penalty_coulomb(&[(1, 1.0)], &[(0, -1.0)], 3.0e5, 7.5e11);
        let sys = FrictionSystem::builder(m, c, k)
            .contact(pair.initial_gap(-2.0e-4))
            .build()
            .unwrap();
        let mb = ModalBrake::new(sys.brake(), sys.reference(), 1.2);
        let h = 3;
        let layout = HarmonicLayout::new(2, h).unwrap();
        let f_eq = condensed_load(&mb, &CondensedStiffness::new(&mb, h), &layout);
        let mut hb = HarmonicBalance::new(
            layout,
            EpmcStiffness::new(&mb, h),
            ContactForce::new(&mb),
            f_eq,
            None,
        )
        .unwrap();
        let scales = EpmcScales {
            force: 60.0,
            dynamic: 3.0,
            phase: 1e-5,
        };
        let mut p = EpmcProblem::new(&mut hb, 1, 3e-5, scales).unwrap();
        let len = layout.len();
        let mut z: Vec<f64> = (0..len)
            .map(|i| 1e-5 * (1.0 + 0.37 * i as f64).sin() / (1 + i / 2) as f64)
            .collect();
        z[1] = 2.1e-4;
        z.extend([1090.0, -3.2e-3]);
        let n = len + 2;
        let mut jac = Mat::<f64>::zeros(n, n);
        p.jacobian(&z, jac.as_mut()).unwrap();
        let (mut rp, mut rm) = (vec![0.0; n], vec![0.0; n]);
        let mut worst: f64 = 0.0;
        for j in 0..n {
            let step = 1e-6 * z[j].abs().max(1e-9);
            let (mut zp, mut zm) = (z.clone(), z.clone());
            zp[j] += step;
            zm[j] -= step;
            p.residual(&zp, &mut rp).unwrap();
            p.residual(&zm, &mut rm).unwrap();
            for i in 0..n {
                let row = (0..n)
                    .map(|c| (jac[(i, c)] * z[c]).abs())
                    .fold(0.0, f64::max)
                    .max(f64::MIN_POSITIVE);
                let fd = (rp[i] - rm[i]) / (2.0 * step);
                worst = worst.max((fd - jac[(i, j)]).abs() * z[j].abs() / row);
            }
        }
        assert!(worst < 1e-6, "worst relative Jacobian error {worst:e}");
    }
}
