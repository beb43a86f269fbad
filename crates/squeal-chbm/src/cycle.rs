//! A periodic motion of every physical dof as Fourier coefficients (eq 23), the common ground
//! on which CHBM and time integration are compared (issue #6, item 6), and the measures of the
//! comparison:
//!
//! - **Phase alignment.** Both cycles are autonomous, so their time origins are arbitrary: the
//!   approximation is shifted in time so that the first harmonic of a reference dof has the
//!   reference's phase ([`CycleCoefficients::align_to`]).
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
use std::f64::consts::PI;

/// Fourier coefficients of a periodic motion of `n` dofs, in the block layout of eq (25):
/// value of dof `d` in block `b` at `[b * n + d]`, blocks `[0c, 1c, 1s, 2c, 2s, ...]`, so that
/// `x_d(t) = Σ_k U_kc cos(kωt) + U_ks sin(kωt)`.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleCoefficients {
    pub harmonics: usize,
    /// Angular frequency ω (rad/s).
    pub omega: f64,
    pub n_dofs: usize,
    /// Displacements.
    pub x: Vec<f64>,
    /// Velocities.
    pub v: Vec<f64>,
}

impl CycleCoefficients {
    /// From displacement coefficients; velocities by differentiating the series.
    pub fn from_displacement(harmonics: usize, omega: f64, n_dofs: usize, x: Vec<f64>) -> Self {
        let mut v = vec![0.0; x.len()];
        for k in 1..=harmonics {
            let kw = k as f64 * omega;
            for d in 0..n_dofs {
                let (c, s) = (x[(2 * k - 1) * n_dofs + d], x[2 * k * n_dofs + d]);
                v[(2 * k - 1) * n_dofs + d] = kw * s;
                v[2 * k * n_dofs + d] = -kw * c;
            }
        }
        Self {
            harmonics,
            omega,
            n_dofs,
            x,
            v,
        }
    }

    /// Frequency in Hz.
    pub fn frequency_hz(&self) -> f64 {
        self.omega / (2.0 * PI)
    }

    /// `(cos, sin)` coefficients of harmonic `k ≥ 1` of dof `d` (zero above `harmonics`).
    pub fn harmonic(&self, values: &[f64], k: usize, d: usize) -> (f64, f64) {
        if k == 0 || k > self.harmonics {
            return (0.0, 0.0);
        }
        (
            values[(2 * k - 1) * self.n_dofs + d],
            values[2 * k * self.n_dofs + d],
        )
    }

    /// Mean of dof `d`.
    pub fn mean(&self, d: usize) -> f64 {
        self.x[d]
    }

    /// Amplitude of harmonic `k` of dof `d`'s displacement (`|mean|` for `k = 0`).
    pub fn amplitude(&self, d: usize, k: usize) -> f64 {
        if k == 0 {
            return self.x[d].abs();
        }
        let (c, s) = self.harmonic(&self.x, k, d);
        c.hypot(s)
    }

    /// Shifts the time origin by `φ / ω`: `x(θ) ← x(θ + φ)`.
    pub fn shift_phase(&mut self, phi: f64) {
        let n = self.n_dofs;
        for k in 1..=self.harmonics {
            let (s, c) = (k as f64 * phi).sin_cos();
            for values in [&mut self.x, &mut self.v] {
                for d in 0..n {
                    let (a, b) = (values[(2 * k - 1) * n + d], values[2 * k * n + d]);
                    // a cos(k(θ+φ)) + b sin(k(θ+φ)) = (a c + b s) cos kθ + (b c - a s) sin kθ.
                    values[(2 * k - 1) * n + d] = a * c + b * s;
                    values[2 * k * n + d] = b * c - a * s;
                }
            }
        }
    }

    /// Shifts this cycle in time so that the first harmonic of dof `d` has the phase of
    /// `reference`'s; returns the shift φ (rad of the fundamental).
    pub fn align_to(&mut self, reference: &CycleCoefficients, d: usize) -> f64 {
        let (a, b) = self.harmonic(&self.x, 1, d);
        let (ar, br) = reference.harmonic(&reference.x, 1, d);
        // a cos θ + b sin θ = A cos(θ - atan2(b, a)).
        let phi = b.atan2(a) - br.atan2(ar);
        self.shift_phase(phi);
        phi
    }

    /// Value of dof `d` at phase θ (`velocity` picks the velocity series).
    pub fn value_at(&self, d: usize, theta: f64, velocity: bool) -> f64 {
        let values = if velocity { &self.v } else { &self.x };
        let mut s = values[d];
        for k in 1..=self.harmonics {
            let (c, sn) = self.harmonic(values, k, d);
            let (si, co) = (k as f64 * theta).sin_cos();
            s += c * co + sn * si;
        }
        s
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
    /// alignment).
    pub fn strongest_dof(&self, among: &[usize]) -> usize {
        among
            .iter()
            .copied()
            .max_by(|&a, &b| self.amplitude(a, 1).total_cmp(&self.amplitude(b, 1)))
            .unwrap_or(0)
    }

    /// Coefficients restricted to some dofs (same layout over those dofs).
    pub fn restrict(&self, dofs: &[usize]) -> CycleCoefficients {
        let (n, m) = (self.n_dofs, dofs.len());
        let blocks = 2 * self.harmonics + 1;
        let pick = |values: &[f64]| {
            let mut out = vec![0.0; blocks * m];
            for b in 0..blocks {
                for (i, &d) in dofs.iter().enumerate() {
                    out[b * m + i] = values[b * n + d];
                }
            }
            out
        };
        CycleCoefficients {
            harmonics: self.harmonics,
            omega: self.omega,
            n_dofs: m,
            x: pick(&self.x),
            v: pick(&self.v),
        }
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
fn mean_squares(
    a: &CycleCoefficients,
    av: &[f64],
    b: &CycleCoefficients,
    bv: &[f64],
    dofs: &[usize],
) -> (f64, f64) {
    let h = a.harmonics.max(b.harmonics);
    let (mut diff, mut osc) = (0.0, 0.0);
    for &d in dofs {
        diff += (av[d] - bv[d]).powi(2);
        for k in 1..=h {
            let (ac, as_) = a.harmonic(av, k, d);
            let (bc, bs) = b.harmonic(bv, k, d);
            diff += 0.5 * ((ac - bc).powi(2) + (as_ - bs).powi(2));
            osc += 0.5 * (bc * bc + bs * bs);
        }
    }
    (diff, osc)
}

/// Errors of `approx` against `reference` over `dofs` (both already phase-aligned; see
/// [`CycleCoefficients::align_to`]). Dofs are physical indices of both.
pub fn relative_errors(
    approx: &CycleCoefficients,
    reference: &CycleCoefficients,
    dofs: &[usize],
) -> RelativeErrors {
    let ratio = |(d, o): (f64, f64)| (d / o.max(f64::MIN_POSITIVE)).sqrt();
    let displacement = ratio(mean_squares(
        approx,
        &approx.x,
        reference,
        &reference.x,
        dofs,
    ));
    let velocity = ratio(mean_squares(
        approx,
        &approx.v,
        reference,
        &reference.v,
        dofs,
    ));
    let (fa, fr) = (approx.frequency_hz(), reference.frequency_hz());
    RelativeErrors {
        displacement,
        velocity,
        frequency_hz: fa - fr,
        frequency_relative: (fa - fr) / fr,
    }
}

/// Eq (49): `P_j = ½ Σ_i (a_ij² + b_ij²)` over `dofs` for `j = 1..=harmonics` (index `j - 1`).
pub fn harmonic_power(c: &CycleCoefficients, dofs: &[usize]) -> Vec<f64> {
    (1..=c.harmonics)
        .map(|k| {
            dofs.iter()
                .map(|&d| {
                    let (a, b) = c.harmonic(&c.x, k, d);
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
pub fn energy_balance(mb: &ModalBrake, c: &CycleCoefficients, samples: usize) -> EnergyBalance {
    let n = mb.modes();
    let nn = mb.nl();
    let qv = to_modal(mb, &c.v);
    let mut dissipated = 0.0;
    for j in 0..n {
        let mut ms = 0.0;
        for k in 1..=c.harmonics {
            let (a, b) = (qv[(2 * k - 1) * n + j], qv[2 * k * n + j]);
            ms += 0.5 * (a * a + b * b);
        }
        dissipated += mb.damping[j] * ms;
    }
    let nl = c.restrict(&mb.nl_dofs);
    let samples = samples.max(4 * c.harmonics + 4);
    let (mut xn, mut vn, mut g) = (vec![0.0; nn], vec![0.0; nn], vec![0.0; nn]);
    let mut input = 0.0;
    for s in 0..samples {
        let th = 2.0 * PI * s as f64 / samples as f64;
        for i in 0..nn {
            xn[i] = nl.value_at(i, th, false);
            vn[i] = nl.value_at(i, th, true);
        }
        g.fill(0.0);
        mb.add_reduced_force(&xn, &mut g);
        input -= (0..nn).map(|i| g[i] * vn[i]).sum::<f64>();
    }
    input /= samples as f64;
    EnergyBalance {
        input,
        dissipated,
        relative: (input - dissipated) / dissipated.max(f64::MIN_POSITIVE),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_dofs() -> CycleCoefficients {
        // x0 = 1 + 2 cos θ + 0.5 sin 2θ, x1 = -cos θ + 3 sin θ.
        let x = vec![1.0, 0.0, 2.0, -1.0, 0.0, 3.0, 0.0, 0.0, 0.5, 0.0];
        CycleCoefficients::from_displacement(2, 10.0, 2, x)
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
        for (a, b) in s.x.iter().zip(&c.x) {
            assert!((a - b).abs() < 1e-12);
        }
    }

    #[test]
    fn errors_by_parseval_match_sampled_rms() {
        let r = two_dofs();
        let mut a = r.clone();
        a.x[2] += 0.1;
        a.x[0] -= 0.05;
        a = CycleCoefficients::from_displacement(2, 10.0, 2, a.x);
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
