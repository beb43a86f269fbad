//! A periodic motion of every physical dof as Fourier coefficients (eq 23), the common ground
//! on which CHBM and time integration are compared (issue #6, item 6), and the measures of the
//! comparison:
//!
//! - **Phase alignment.** Both cycles are autonomous, so their time origins are arbitrary: the
//!   approximation is shifted in time so that the first harmonic of a reference dof has the
//!   reference's phase ([`Cycle::align_to`]).
//! - **Relative errors** ([`relative_errors`]): RMS over one cycle (in phase `θ = ωt`, so two
//!   cycles of slightly different frequency are compared shape against shape) and over a set
//!   of dofs of `x_approx(θ) - x_ref(θ)`, mean included, divided by the RMS of the reference's
//!   oscillation `x_ref(θ) - x̄_ref` over the same dofs; the same for velocities. By Parseval
//!   these are sums of squared coefficients: exact, no sampling.
//! - **Power per harmonic**, eq (49): `P_j = ½ Σ_i (a_ij² + b_ij²)`, and the ratio of eq (50),
//!   `R_j = P_j / P_temporal` with `P_temporal = Σ_{j≥1} P_j` of the reference.
//! - **Energy balance** ([`energy_balance`]): over a periodic motion the work of the friction
//!   forces equals the energy dissipated by the modal damping (the normal contact forces, the
//!   springs and the constant piston load do no net work over a closed cycle).

use faer::Mat;
use faer::linalg::solvers::Solve;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::{HarmonicLayout, HbmError, Periodic};
use std::f64::consts::PI;

/// A periodic motion of every dof: displacements and velocities as two [`Periodic`] series of
/// one layout and frequency. A harmonic balance cycle has velocities by differentiation
/// ([`Cycle::from_displacement`]); a time integration measures its own.
#[derive(Clone, Debug, PartialEq)]
pub struct Cycle {
    /// Displacements, in the layout of eq (25) over every dof.
    pub x: Periodic,
    /// Velocities, in the same layout and at the same frequency.
    pub v: Periodic,
}

impl Cycle {
    /// From displacements; velocities by differentiating the series.
    pub fn from_displacement(x: Periodic) -> Self {
        let v = x.derivative();
        Self { x, v }
    }

    /// From displacement coefficients in the layout of eq (25) over `n_dofs` dofs.
    pub fn from_coefficients(
        harmonics: usize,
        omega: f64,
        n_dofs: usize,
        x: Vec<f64>,
    ) -> Result<Self, HbmError> {
        let layout = HarmonicLayout::new(n_dofs, harmonics)?;
        Ok(Self::from_displacement(Periodic::new(layout, omega, x)?))
    }

    /// Harmonics kept.
    pub fn harmonics(&self) -> usize {
        self.x.harmonics()
    }

    /// Number of dofs.
    pub fn n_dofs(&self) -> usize {
        self.x.n_dofs()
    }

    /// ω (rad/s).
    pub fn omega(&self) -> f64 {
        self.x.omega
    }

    /// Frequency in Hz.
    pub fn frequency_hz(&self) -> f64 {
        self.x.frequency_hz()
    }

    /// Mean of dof `d`.
    pub fn mean(&self, d: usize) -> f64 {
        self.x.mean(d)
    }

    /// Amplitude of harmonic `k` of dof `d`'s displacement (`|mean|` for `k = 0`).
    pub fn amplitude(&self, d: usize, k: usize) -> f64 {
        self.x.amplitude(d, k)
    }

    /// Shifts the time origin by `φ / ω`: `x(θ) ← x(θ + φ)`.
    pub fn shift_phase(&mut self, phi: f64) {
        self.x.shift_phase(phi);
        self.v.shift_phase(phi);
    }

    /// Shifts this cycle in time so that the first harmonic of dof `d` has the phase of
    /// `reference`'s; returns the shift φ (rad of the fundamental).
    pub fn align_to(&mut self, reference: &Cycle, d: usize) -> f64 {
        // a cos θ + b sin θ = A cos(θ - atan2(b, a)).
        let phi = self.x.first_phase(d) - reference.x.first_phase(d);
        self.shift_phase(phi);
        phi
    }

    /// Value of dof `d` at phase θ (`velocity` picks the velocity series).
    pub fn value_at(&self, d: usize, theta: f64, velocity: bool) -> f64 {
        if velocity {
            self.v.value_at(d, theta)
        } else {
            self.x.value_at(d, theta)
        }
    }

    /// `(x(θ_j), v(θ_j))` of dof `d` at `samples + 1` phases over one cycle (closed curve).
    pub fn phase_portrait(&self, d: usize, samples: usize) -> Vec<(f64, f64)> {
        (0..=samples)
            .map(|j| {
                let th = 2.0 * PI * j as f64 / samples.max(1) as f64;
                (self.value_at(d, th, false), self.value_at(d, th, true))
            })
            .collect()
    }

    /// The dof among `among` with the largest first harmonic (the reference dof of the phase
    /// alignment); `None` when `among` is empty.
    pub fn strongest_dof(&self, among: &[usize]) -> Option<usize> {
        among
            .iter()
            .copied()
            .max_by(|&a, &b| self.amplitude(a, 1).total_cmp(&self.amplitude(b, 1)))
    }

    /// The cycle restricted to some dofs.
    pub fn restrict(&self, dofs: &[usize]) -> Result<Cycle, HbmError> {
        Ok(Cycle {
            x: self.x.restrict(dofs)?,
            v: self.v.restrict(dofs)?,
        })
    }
}

/// Relative errors of an approximation against a reference cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RelativeErrors {
    /// RMS of `x_approx - x_ref` over the cycle and the dofs, over the RMS of the reference's
    /// oscillation.
    pub displacement: f64,
    /// The same for velocities.
    pub velocity: f64,
    /// `f_approx - f_ref` (Hz).
    pub frequency_hz: f64,
    /// `(f_approx - f_ref) / f_ref`.
    pub frequency_relative: f64,
}

/// Mean square over one cycle of the difference of two series on `dofs` (Parseval), and the
/// mean square of `b`'s oscillating part.
fn mean_squares(a: &Periodic, b: &Periodic, dofs: &[usize]) -> (f64, f64) {
    let h = a.harmonics().max(b.harmonics());
    let (mut diff, mut osc) = (0.0, 0.0);
    for &d in dofs {
        diff += (a.mean(d) - b.mean(d)).powi(2);
        for k in 1..=h {
            let (ac, as_) = a.harmonic(k, d);
            let (bc, bs) = b.harmonic(k, d);
            diff += 0.5 * ((ac - bc).powi(2) + (as_ - bs).powi(2));
            osc += 0.5 * (bc * bc + bs * bs);
        }
    }
    (diff, osc)
}

/// Errors of `approx` against `reference` over `dofs` (both already phase-aligned; see
/// [`Cycle::align_to`]). Dofs are physical indices of both.
pub fn relative_errors(approx: &Cycle, reference: &Cycle, dofs: &[usize]) -> RelativeErrors {
    let ratio = |(d, o): (f64, f64)| (d / o.max(f64::MIN_POSITIVE)).sqrt();
    let displacement = ratio(mean_squares(&approx.x, &reference.x, dofs));
    let velocity = ratio(mean_squares(&approx.v, &reference.v, dofs));
    let (fa, fr) = (approx.frequency_hz(), reference.frequency_hz());
    RelativeErrors {
        displacement,
        velocity,
        frequency_hz: fa - fr,
        frequency_relative: (fa - fr) / fr,
    }
}

/// Eq (49): `P_j = ½ Σ_i (a_ij² + b_ij²)` over `dofs` for `j = 1..=harmonics` (index `j - 1`).
pub fn harmonic_power(c: &Cycle, dofs: &[usize]) -> Vec<f64> {
    (1..=c.harmonics())
        .map(|k| {
            dofs.iter()
                .map(|&d| {
                    let (a, b) = c.x.harmonic(k, d);
                    0.5 * (a * a + b * b)
                })
                .sum()
        })
        .collect()
}

/// Power balance of a periodic motion of the brake (mean over one cycle, W).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnergyBalance {
    /// Mean power of the contact and friction forces on the structure, `⟨-ẋ_nᵀ G(x_n)⟩`
    /// (the normal forces and springs average to zero: this is the friction's input).
    pub input: f64,
    /// Mean power dissipated by the modal damping, `⟨q'ᵀ D q'⟩ = Σ_j D_j Σ_k |V_jk|² / 2`.
    pub dissipated: f64,
    /// `(input - dissipated) / dissipated`.
    pub relative: f64,
}

/// Modal coefficients `q = Φ⁻¹ x` of physical coefficients (all blocks at once).
pub fn to_modal(mb: &ModalBrake, values: &[f64]) -> Vec<f64> {
    let n = mb.modes();
    let blocks = values.len() / n.max(1);
    let rhs = Mat::from_fn(n, blocks, |i, b| values[b * n + i]);
    let q = mb.phi.partial_piv_lu().solve(&rhs);
    let mut out = vec![0.0; values.len()];
    for b in 0..blocks {
        for i in 0..n {
            out[b * n + i] = q[(i, b)];
        }
    }
    out
}

/// The power balance of a cycle of every physical dof of `mb`, with the contact forces
/// sampled at `samples` phases (a few hundred resolve the contact's kinks to ~1e-5).
pub fn energy_balance(
    mb: &ModalBrake,
    c: &Cycle,
    samples: usize,
) -> Result<EnergyBalance, HbmError> {
    let n = mb.modes();
    let nn = mb.nl();
    let qv = to_modal(mb, &c.v.coeffs);
    // ⟨q'ᵀ D q'⟩ = Σ_k ½ (Re V_kᵀ D Re V_k + Im V_kᵀ D Im V_k) for any (symmetric part of) D.
    let mut dissipated = 0.0;
    let mut dv = vec![0.0; n];
    for k in 1..=c.harmonics() {
        for part in [2 * k - 1, 2 * k] {
            let vk = &qv[part * n..(part + 1) * n];
            mb.damping.apply(vk, &mut dv);
            dissipated += 0.5 * vk.iter().zip(&dv).map(|(a, b)| a * b).sum::<f64>();
        }
    }
    let nl = c.restrict(&mb.nl_dofs)?;
    let samples = samples.max(4 * c.harmonics() + 4);
    let (mut xn, mut vn, mut g) = (vec![0.0; nn], vec![0.0; nn], vec![0.0; nn]);
    let mut input = 0.0;
    for s in 0..samples {
        let th = 2.0 * PI * s as f64 / samples as f64;
        for i in 0..nn {
            xn[i] = nl.value_at(i, th, false);
            vn[i] = nl.value_at(i, th, true);
        }
        g.fill(0.0);
        mb.add_reduced_force(&xn, Some(&vn), &mut g);
        input -= (0..nn).map(|i| g[i] * vn[i]).sum::<f64>();
    }
    input /= samples as f64;
    Ok(EnergyBalance {
        input,
        dissipated,
        relative: (input - dissipated) / dissipated.max(f64::MIN_POSITIVE),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_dofs() -> Cycle {
        // x0 = 1 + 2 cos θ + 0.5 sin 2θ, x1 = -cos θ + 3 sin θ.
        let x = vec![1.0, 0.0, 2.0, -1.0, 0.0, 3.0, 0.0, 0.0, 0.5, 0.0];
        Cycle::from_coefficients(2, 10.0, 2, x).unwrap()
    }

    #[test]
    fn phase_shift_is_a_time_shift() {
        let c = two_dofs();
        let mut s = c.clone();
        s.shift_phase(0.7);
        for th in [0.0, 1.0, 2.5] {
            for d in 0..2 {
                for vel in [false, true] {
                    // Trigonometric identities: exact up to round-off of values ~10.
                    assert!((s.value_at(d, th, vel) - c.value_at(d, th + 0.7, vel)).abs() < 1e-12);
                }
            }
        }
        // Aligning the shifted copy back recovers the original coefficients.
        s.align_to(&c, 0);
        for (a, b) in s.x.coeffs.iter().zip(&c.x.coeffs) {
            assert!((a - b).abs() < 1e-12);
        }
    }

    #[test]
    fn errors_by_parseval_match_sampled_rms() {
        let r = two_dofs();
        let mut x = r.x.coeffs.clone();
        x[2] += 0.1;
        x[0] -= 0.05;
        let a = Cycle::from_coefficients(2, 10.0, 2, x).unwrap();
        let e = relative_errors(&a, &r, &[0, 1]);
        // Sampled RMS with 64 points is exact for trigonometric polynomials of degree 2.
        let m = 64;
        let (mut num, mut den) = (0.0, 0.0);
        for j in 0..m {
            let th = 2.0 * PI * j as f64 / m as f64;
            for d in 0..2 {
                num += (a.value_at(d, th, false) - r.value_at(d, th, false)).powi(2);
                den += (r.value_at(d, th, false) - r.mean(d)).powi(2);
            }
        }
        assert!((e.displacement - (num / den).sqrt()).abs() < 1e-14);
        assert_eq!(e.frequency_hz, 0.0);
    }
}
