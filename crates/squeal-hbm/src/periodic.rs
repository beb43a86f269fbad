//! A periodic motion as a truncated Fourier series, eq. (23), in the layout of eq. (25): the
//! one periodic-coefficients type of the workspace (harmonic balance results, the cycle
//! measures, the steady state of a time integration), and [`FourierSums`], which accumulates
//! such coefficients from equally spaced samples.

use std::f64::consts::PI;

use faer::c64;

use crate::HbmError;
use crate::layout::{HarmonicLayout, Part};

/// `x_d(t) = U0c_d + Σ_k (Ukc_d cos(k ω t) + Uks_d sin(k ω t))` for `n` dofs.
#[derive(Clone, Debug, PartialEq)]
pub struct Periodic {
    layout: HarmonicLayout,
    /// Fundamental angular frequency ω (rad/s).
    pub omega: f64,
    /// Coefficients in the layout of eq. (25): dof `d` of block `b` at `b n + d`.
    pub coeffs: Vec<f64>,
}

impl Periodic {
    /// From coefficients in `layout`'s order.
    pub fn new(layout: HarmonicLayout, omega: f64, coeffs: Vec<f64>) -> Result<Self, HbmError> {
        layout.check_len("periodic coefficients", coeffs.len())?;
        Ok(Self {
            layout,
            omega,
            coeffs,
        })
    }

    /// The zero motion.
    pub fn zeros(layout: HarmonicLayout, omega: f64) -> Self {
        Self {
            layout,
            omega,
            coeffs: vec![0.0; layout.len()],
        }
    }

    /// The layout of the coefficients.
    pub fn layout(&self) -> HarmonicLayout {
        self.layout
    }

    /// Number of dofs.
    pub fn n_dofs(&self) -> usize {
        self.layout.n_dofs()
    }

    /// Highest harmonic `H`.
    pub fn harmonics(&self) -> usize {
        self.layout.n_harmonics()
    }

    /// Frequency in Hz.
    pub fn frequency_hz(&self) -> f64 {
        self.omega / (2.0 * PI)
    }

    /// Period `2π/ω`.
    pub fn period(&self) -> f64 {
        2.0 * PI / self.omega
    }

    /// Mean `U0c_d`.
    pub fn mean(&self, d: usize) -> f64 {
        self.coeffs[d]
    }

    /// `(Ukc_d, Uks_d)` of harmonic `k ≥ 1` (zero above `H`).
    pub fn harmonic(&self, k: usize, d: usize) -> (f64, f64) {
        match (
            self.layout.index(k, Part::Cos, d),
            self.layout.index(k, Part::Sin, d),
        ) {
            (Some(c), Some(s)) if k > 0 => (self.coeffs[c], self.coeffs[s]),
            _ => (0.0, 0.0),
        }
    }

    /// `|U0c_d|` for `k = 0`, else `sqrt(Ukc_d² + Uks_d²)`.
    pub fn amplitude(&self, d: usize, k: usize) -> f64 {
        if k == 0 {
            return self.mean(d).abs();
        }
        let (c, s) = self.harmonic(k, d);
        c.hypot(s)
    }

    /// Harmonic `k` of dof `d` as the complex amplitude `X = Ukc - i Uks`, so that the
    /// harmonic is `Re(X e^{i k ω t})`.
    pub fn complex(&self, k: usize, d: usize) -> c64 {
        let (c, s) = self.harmonic(k, d);
        c64::new(c, -s)
    }

    /// `x_d` at phase `θ = ω t`.
    pub fn value_at(&self, d: usize, theta: f64) -> f64 {
        let mut v = self.mean(d);
        for k in 1..=self.harmonics() {
            let (c, s) = self.harmonic(k, d);
            let (sn, cs) = (k as f64 * theta).sin_cos();
            v += c * cs + s * sn;
        }
        v
    }

    /// The time derivative `dx/dt` as a periodic motion of the same layout.
    pub fn derivative(&self) -> Periodic {
        let n = self.n_dofs();
        let mut v = vec![0.0; self.coeffs.len()];
        for k in 1..=self.harmonics() {
            let kw = k as f64 * self.omega;
            for d in 0..n {
                let (c, s) = self.harmonic(k, d);
                v[(2 * k - 1) * n + d] = kw * s;
                v[2 * k * n + d] = -kw * c;
            }
        }
        Periodic {
            layout: self.layout,
            omega: self.omega,
            coeffs: v,
        }
    }

    /// Shifts the motion in time: afterwards it describes `x(t + φ/ω)`.
    pub fn shift_phase(&mut self, phi: f64) {
        // The length always matches the layout (checked at construction).
        let _ = self.layout.shift_phase(&mut self.coeffs, phi);
    }

    /// The phase of the first harmonic of dof `d` (`atan2(U1s, U1c)`).
    pub fn first_phase(&self, d: usize) -> f64 {
        let (c, s) = self.harmonic(1, d);
        s.atan2(c)
    }

    /// The dofs `dofs` only (same harmonics and frequency).
    pub fn restrict(&self, dofs: &[usize]) -> Result<Periodic, HbmError> {
        let layout = HarmonicLayout::new(dofs.len(), self.harmonics())?;
        let n = self.n_dofs();
        let mut coeffs = Vec::with_capacity(layout.len());
        for b in 0..layout.n_blocks() {
            coeffs.extend(dofs.iter().map(|&d| self.coeffs[b * n + d]));
        }
        Ok(Periodic {
            layout,
            omega: self.omega,
            coeffs,
        })
    }

    /// The same motion with `h` harmonics: higher ones dropped, missing ones zero.
    pub fn with_harmonics(&self, h: usize) -> Result<Periodic, HbmError> {
        let layout = HarmonicLayout::new(self.n_dofs(), h)?;
        let mut coeffs = vec![0.0; layout.len()];
        let m = coeffs.len().min(self.coeffs.len());
        coeffs[..m].copy_from_slice(&self.coeffs[..m]);
        Ok(Periodic {
            layout,
            omega: self.omega,
            coeffs,
        })
    }
}

/// Accumulates the Fourier coefficients of a signal of `n` dofs from the samples at
/// `t_j = t0 + j T / N` over `cycles` periods (`j = 0 .. N·cycles - 1`): the discrete Fourier
/// sums `a0 = (1/M) Σ y_j`, `ak = (2/M) Σ y_j cos(k θ_j)`, `bk = (2/M) Σ y_j sin(k θ_j)`,
/// `θ_j = 2π j / N`, `M = N·cycles` (the trapezoidal rule on whole periods, exact for the
/// harmonics below `N/2`). Only the running sums are stored.
#[derive(Clone, Debug)]
pub struct FourierSums {
    layout: HarmonicLayout,
    per_cycle: usize,
    total: usize,
    t0: f64,
    period: f64,
    next: usize,
    cos: Vec<f64>,
    sin: Vec<f64>,
    sums: Vec<f64>,
}

impl FourierSums {
    /// Sums for `n_dofs` dofs, `harmonics` harmonics, `per_cycle` samples a period over
    /// `cycles` periods starting at `t0`. `per_cycle` must exceed `2 harmonics`.
    pub fn new(
        n_dofs: usize,
        harmonics: usize,
        per_cycle: usize,
        cycles: usize,
        t0: f64,
        period: f64,
    ) -> Result<Self, HbmError> {
        let layout = HarmonicLayout::new(n_dofs, harmonics)?;
        if per_cycle <= 2 * harmonics {
            return Err(HbmError::TooFewSamples {
                n_samples: per_cycle,
                n_harmonics: harmonics,
                min: 2 * harmonics + 1,
            });
        }
        let angle = |j: usize| 2.0 * PI * j as f64 / per_cycle as f64;
        Ok(Self {
            layout,
            per_cycle,
            total: per_cycle * cycles.max(1),
            t0,
            period,
            next: 0,
            cos: (0..per_cycle).map(|j| angle(j).cos()).collect(),
            sin: (0..per_cycle).map(|j| angle(j).sin()).collect(),
            sums: vec![0.0; layout.len()],
        })
    }

    /// The time of the next sample, `None` when all are in.
    pub fn next_time(&self) -> Option<f64> {
        (self.next < self.total)
            .then(|| self.t0 + self.next as f64 * self.period / self.per_cycle as f64)
    }

    /// Adds the sample at [`Self::next_time`].
    pub fn add(&mut self, y: &[f64]) {
        let n = self.layout.n_dofs();
        let j = self.next % self.per_cycle;
        for (d, &yd) in y.iter().enumerate().take(n) {
            self.sums[d] += yd;
            for k in 1..=self.layout.n_harmonics() {
                let idx = (k * j) % self.per_cycle;
                self.sums[(2 * k - 1) * n + d] += yd * self.cos[idx];
                self.sums[2 * k * n + d] += yd * self.sin[idx];
            }
        }
        self.next += 1;
    }

    /// The time just after the last sample: `t0 + cycles · T`.
    pub fn end_time(&self) -> f64 {
        self.t0 + self.total as f64 * self.period / self.per_cycle as f64
    }

    /// Whether every sample is in.
    pub fn complete(&self) -> bool {
        self.next >= self.total
    }

    /// Starts again at `t0` with `period` (the sums are cleared).
    pub fn restart(&mut self, t0: f64, period: f64) {
        self.sums.fill(0.0);
        self.next = 0;
        self.t0 = t0;
        self.period = period;
    }

    /// The coefficients of the samples added so far (over whole periods once complete), with
    /// time origin `t0` and frequency `2π / period`.
    pub fn periodic(&self) -> Periodic {
        let n = self.layout.n_dofs();
        let m = self.next.max(1) as f64;
        let coeffs = self
            .sums
            .iter()
            .enumerate()
            .map(|(i, s)| if i < n { s / m } else { 2.0 * s / m })
            .collect();
        Periodic {
            layout: self.layout,
            omega: 2.0 * PI / self.period,
            coeffs,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_of_a_trigonometric_polynomial_are_exact() {
        // x(t) = 0.5 + 2 cos(ωt) - 3 sin(2ωt) on two dofs (the second doubled), 16 samples a
        // period over two periods: the discrete sums are exact up to round-off, here that of
        // the sample times t0 + j T/N with t0 = 30 T (phase errors ~30 ε 2π ≈ 4e-14).
        let (period, t0) = (0.01, 0.3);
        let w = 2.0 * PI / period;
        let mut f = FourierSums::new(2, 3, 16, 2, t0, period).unwrap();
        while let Some(t) = f.next_time() {
            let tau = t - t0;
            let x = 0.5 + 2.0 * (w * tau).cos() - 3.0 * (2.0 * w * tau).sin();
            f.add(&[x, 2.0 * x]);
        }
        let p = f.periodic();
        for (d, s) in [(0, 1.0), (1, 2.0)] {
            assert!((p.mean(d) - 0.5 * s).abs() < 1e-12);
            let (c1, s1) = p.harmonic(1, d);
            let (c2, s2) = p.harmonic(2, d);
            assert!((c1 - 2.0 * s).abs() < 1e-12 && s1.abs() < 1e-12);
            assert!(c2.abs() < 1e-12 && (s2 + 3.0 * s).abs() < 1e-12);
            assert!(p.amplitude(d, 3) < 1e-12);
        }
        assert!((p.omega - w).abs() < 1e-9 * w);
    }

    #[test]
    fn derivative_and_phase_shift_act_on_the_series() {
        let l = HarmonicLayout::new(1, 2).unwrap();
        let p = Periodic::new(l, 3.0, vec![1.0, 0.5, -0.25, 0.1, 0.2]).unwrap();
        let v = p.derivative();
        let (theta, h) = (0.7, 1e-6);
        let fd = (p.value_at(0, theta + h) - p.value_at(0, theta - h)) / (2.0 * h) * p.omega;
        // Central difference of a smooth series: truncation ~ h² |x'''| ≈ 1e-11.
        assert!((v.value_at(0, theta) - fd).abs() < 1e-8);
        let mut q = p.clone();
        q.shift_phase(0.4);
        assert!((q.value_at(0, theta) - p.value_at(0, theta + 0.4)).abs() < 1e-14);
        assert_eq!(p.complex(1, 0), c64::new(0.5, 0.25));
    }
}
