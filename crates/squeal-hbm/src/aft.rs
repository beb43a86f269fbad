//! Alternating frequency-time scheme, eq. (29):
//! `U~ --FFT^-1--> x(t_j), xdot(t_j) --> f_nl(x, xdot)(t_j) --FFT--> F~_nl`,
//! with the Jacobians `dF~/dU~` and `dF~/domega` obtained analytically through the same
//! transforms.
//!
//! # Time samples
//! The period is sampled at `t_j = j T / N`, `j = 0..N-1` (phase `theta_j = 2 pi j / N`).
//! Time-domain arrays are sample-major: value `i` of sample `j` is at `j * n + i`.
//!
//! # Discrete transforms
//! `x(theta_j)` is eq. (23) evaluated exactly (inverse FFT of the Hermitian spectrum
//! `X[k] = (Ukc - i Uks) / 2`). The forward projection is the discrete Fourier sum
//! `F0 = (1/N) sum_j f_j`, `Fkc = (2/N) sum_j f_j cos(k theta_j)`,
//! `Fks = (2/N) sum_j f_j sin(k theta_j)`, the exact inverse of the synthesis for every
//! trigonometric polynomial of degree `< N/2`; hence the requirement `N >= 2 H + 1`.
//!
//! # Aliasing and the choice of `N`
//! If `f(x(t))` is a polynomial of degree `p` in `x`, `xdot`, it contains harmonics up to
//! `p H`. Sampling folds harmonic `m` onto `|m - l N|`; harmonics `H < m <= p H` stay
//! off the retained band `0..=H` iff `N - p H > H`, i.e.
//! `N >= (p + 1) H + 1` ([`min_samples_exact`]; `4 H + 1` for the cubic contact). Getting
//! every harmonic of `f` unaliased, up to `p H`, would take `N >= 2 p H + 1` (`6 H + 1`),
//! but harmonic balance only needs the retained band. With `N` below the bound the lowest
//! folded harmonic is `N - p H`: e.g. `x = cos`, `f = x^3`, `N = 4`
//! puts `cos 3 theta` onto `cos theta` and the first-harmonic coefficient reads
//! `3/4 + 1/4 = 1` instead of `3/4` (tested).
//!
//! The unilateral penalty contact of the brake (eq. 8: force zero when open) is not a
//! polynomial: its force has a kink where the gap closes, so its Fourier coefficients decay
//! only like `1/m^2` and some aliasing remains for every `N` (the folded error decays like
//! `N^-2`). [`default_samples`] therefore takes twice the cubic bound, rounded up to a power
//! of two for the FFT: `N = next_pow2(max(2 (4 H + 1), 16))`, i.e. 16, 32, 64, 64, 128, 128
//! for `H` = 1, 3, 5, 7, 9, 10. Raise it when contact opens for a short part of the cycle.
//!
//! # Analytic Jacobian
//! `F~ = E f(D U~)` with `D` the synthesis and `E` the projection, so
//! `dF~_(a,i) / dU~_(b,k) = sum_j E[a, j] g_ik(theta_j) D[j, b]` with `g_ik = df_i/dx_k`
//! sampled, plus the velocity term with `df_i/dxdot_k` and `d xdot / dU~ = omega D'`.
//! Products of trigonometric functions reduce every such sum to the discrete Fourier sums
//! `Gc(m) = sum_j g_j cos(m theta_j)`, `Gs(m) = sum_j g_j sin(m theta_j)` for
//! `m <= 2 H < N`, e.g. `sum_j g cos(a theta) cos(b theta) = (Gc(a - b) + Gc(a + b)) / 2`.
//! These identities hold sample by sample, so the result is the exact derivative of the
//! discrete map (aliasing included), for one FFT per pattern entry instead of a
//! `(2H+1) x N x (2H+1)` product.

use std::sync::Arc;

use faer::MatMut;
use faer::reborrow::ReborrowMut;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use crate::HbmError;
use crate::force::{LocalJacobian, NonlinearForce, validate_pattern};
use crate::layout::{HarmonicLayout, Part};

/// Upper bound on the number of time samples `N`.
pub const MAX_SAMPLES: usize = 1 << 20;

/// Upper bound on `N` times the values stored per sample (each time-domain buffer stays
/// below 128 MiB).
pub const MAX_TIME_VALUES: usize = 1 << 24;

/// Smallest `N` for which AFT returns the exact harmonics `0..=H` of a force that is a
/// polynomial of degree `degree` in `x` and `xdot`: `N = (degree + 1) H + 1`, and never
/// below `2 H + 1` (see the module docs for the derivation).
pub fn min_samples_exact(n_harmonics: usize, degree: usize) -> usize {
    let exact = degree
        .saturating_add(1)
        .saturating_mul(n_harmonics)
        .saturating_add(1);
    exact.max(2 * n_harmonics + 1)
}

/// Default number of time samples: twice the exact bound of a cubic force, rounded up to a
/// power of two, at least 16: `N = next_pow2(max(2 (4 H + 1), 16))` (module docs explain why).
pub fn default_samples(n_harmonics: usize) -> usize {
    let cubic = min_samples_exact(n_harmonics, 3);
    cubic
        .saturating_mul(2)
        .max(16)
        .checked_next_power_of_two()
        .unwrap_or(usize::MAX)
}

/// Read-only view of the time samples of the last AFT evaluation (sample-major).
///
/// This is what an equivalent linearization (eq. 45) needs: `x`, `xdot` and `f` at every
/// `t_j`, and the local Jacobians in pattern order.
#[derive(Clone, Copy, Debug)]
pub struct TimeSamples<'a> {
    /// Number of samples `N`.
    pub n_samples: usize,
    /// Number of dofs `n`.
    pub n_dofs: usize,
    /// Number of pattern entries of the local Jacobians.
    pub n_pattern: usize,
    /// `x_i(t_j)` at `j * n + i`.
    pub x: &'a [f64],
    /// `xdot_i(t_j)` at `j * n + i` (zeros when the force does not depend on velocity).
    pub xdot: &'a [f64],
    /// `f_i(t_j)` at `j * n + i`.
    pub f: &'a [f64],
    /// `df/dx` at `j * n_pattern + p` (valid after a Jacobian evaluation only).
    pub dfdx: &'a [f64],
    /// `df/dxdot` at `j * n_pattern + p` (valid after a Jacobian evaluation of a
    /// velocity-dependent force only).
    pub dfdxdot: &'a [f64],
}

/// Whether a synthesis produces the signal or its phase derivative `d/dtheta`.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Synthesis {
    Value,
    PhaseDerivative,
}

/// AFT engine for one [`HarmonicLayout`] and sample count `N`: FFT plans and every buffer
/// are allocated up front (Jacobian buffers on first use), so repeated evaluations do not
/// allocate.
pub struct Aft {
    layout: HarmonicLayout,
    n_samples: usize,
    forward: Arc<dyn Fft<f64>>,
    inverse: Arc<dyn Fft<f64>>,
    scratch: Vec<Complex<f64>>,
    spectrum: Vec<Complex<f64>>,
    x: Vec<f64>,
    x_theta: Vec<f64>,
    xdot: Vec<f64>,
    f: Vec<f64>,
    omega_work: Vec<f64>,
    dfdx: Vec<f64>,
    dfdxdot: Vec<f64>,
    gc: Vec<f64>,
    gs: Vec<f64>,
    checked_pattern: Vec<(usize, usize)>,
}

impl Aft {
    /// AFT with `n_samples` time samples per period. Needs `2 H + 1 <= N <= MAX_SAMPLES`
    /// and `N n <= MAX_TIME_VALUES`.
    pub fn new(layout: HarmonicLayout, n_samples: usize) -> Result<Self, HbmError> {
        let n = layout.n_dofs();
        let min = 2 * layout.n_harmonics() + 1;
        if n_samples < min {
            return Err(HbmError::TooFewSamples {
                n_samples,
                n_harmonics: layout.n_harmonics(),
                min,
            });
        }
        check_time_size(n_samples, n)?;
        let mut planner = FftPlanner::new();
        let forward = planner.plan_fft_forward(n_samples);
        let inverse = planner.plan_fft_inverse(n_samples);
        let scratch_len = forward
            .get_inplace_scratch_len()
            .max(inverse.get_inplace_scratch_len());
        let zero = Complex::new(0.0, 0.0);
        let values = n_samples * n;
        Ok(Self {
            layout,
            n_samples,
            forward,
            inverse,
            scratch: vec![zero; scratch_len],
            spectrum: vec![zero; values],
            x: vec![0.0; values],
            x_theta: vec![0.0; values],
            xdot: vec![0.0; values],
            f: vec![0.0; values],
            omega_work: vec![0.0; values],
            dfdx: Vec::new(),
            dfdxdot: Vec::new(),
            gc: vec![0.0; 2 * layout.n_harmonics() + 1],
            gs: vec![0.0; 2 * layout.n_harmonics() + 1],
            checked_pattern: Vec::new(),
        })
    }

    /// AFT with [`default_samples`]`(H)` samples.
    pub fn with_default_samples(layout: HarmonicLayout) -> Result<Self, HbmError> {
        Self::new(layout, default_samples(layout.n_harmonics()))
    }

    /// The layout of the coefficient vectors.
    pub fn layout(&self) -> HarmonicLayout {
        self.layout
    }

    /// Number of time samples `N`.
    pub fn n_samples(&self) -> usize {
        self.n_samples
    }

    /// Time samples of the last [`Self::forces`] or [`Self::forces_and_jacobian`] call.
    pub fn samples(&self) -> TimeSamples<'_> {
        let n_pattern = self.checked_pattern.len();
        let jac_len = self.n_samples * n_pattern;
        TimeSamples {
            n_samples: self.n_samples,
            n_dofs: self.layout.n_dofs(),
            n_pattern,
            x: &self.x,
            xdot: &self.xdot,
            f: &self.f,
            dfdx: self.dfdx.get(..jac_len).unwrap_or(&[]),
            dfdxdot: self.dfdxdot.get(..jac_len).unwrap_or(&[]),
        }
    }

    /// Eq. (23) at the samples: `x[j n + i] = x_i(t_j)` from the coefficients `u`.
    pub fn coeffs_to_samples(&mut self, u: &[f64], x: &mut [f64]) -> Result<(), HbmError> {
        self.layout.check_len("coefficients", u.len())?;
        self.check_time_len("displacement samples", x.len())?;
        self.synthesize(u, Synthesis::Value, 1.0);
        self.spectrum_to_samples(x);
        Ok(())
    }

    /// Velocity at the samples: `xdot[j n + i] = d x_i / dt (t_j)`, which scales with `omega`.
    pub fn coeffs_to_velocity_samples(
        &mut self,
        u: &[f64],
        omega: f64,
        xdot: &mut [f64],
    ) -> Result<(), HbmError> {
        self.layout.check_len("coefficients", u.len())?;
        self.check_time_len("velocity samples", xdot.len())?;
        self.synthesize(u, Synthesis::PhaseDerivative, omega);
        self.spectrum_to_samples(xdot);
        Ok(())
    }

    /// Discrete Fourier projection of samples `values[j n + i]` onto the layout (the
    /// forward half of eq. 29). Exact inverse of [`Self::coeffs_to_samples`].
    pub fn samples_to_coeffs(&mut self, values: &[f64], u: &mut [f64]) -> Result<(), HbmError> {
        self.check_time_len("samples", values.len())?;
        self.layout.check_len("coefficients", u.len())?;
        let n = self.layout.n_dofs();
        self.transform_samples(values, n);
        self.spectrum_to_coeffs(u);
        Ok(())
    }

    /// Eq. (29): `F~_nl(U~, omega)` written to `out` (length of the layout).
    pub fn forces<F: NonlinearForce + ?Sized>(
        &mut self,
        force: &F,
        u: &[f64],
        omega: f64,
        out: &mut [f64],
    ) -> Result<(), HbmError> {
        self.check_force(force)?;
        self.layout.check_len("coefficients", u.len())?;
        self.layout.check_len("force coefficients", out.len())?;
        self.sample_motion(u, omega, force.depends_on_velocity());
        let n = self.layout.n_dofs();
        self.f.fill(0.0);
        for j in 0..self.n_samples {
            let r = j * n..(j + 1) * n;
            force.eval(
                &self.x[r.clone()],
                &self.xdot[r.clone()],
                &mut self.f[r],
                None,
            );
        }
        self.check_finite_forces()?;
        let f = std::mem::take(&mut self.f);
        self.transform_samples(&f, n);
        self.f = f;
        self.spectrum_to_coeffs(out);
        Ok(())
    }

    /// Eq. (29) with its analytic Jacobians: `out = F~_nl(U~, omega)`,
    /// `jac_u = dF~_nl / dU~` (square, layout length; every entry is overwritten) and
    /// `jac_omega = dF~_nl / domega` (zero unless the force depends on velocity).
    pub fn forces_and_jacobian<F: NonlinearForce + ?Sized>(
        &mut self,
        force: &F,
        u: &[f64],
        omega: f64,
        out: &mut [f64],
        mut jac_u: MatMut<'_, f64>,
        jac_omega: &mut [f64],
    ) -> Result<(), HbmError> {
        self.check_force(force)?;
        let len = self.layout.len();
        self.layout.check_len("coefficients", u.len())?;
        self.layout.check_len("force coefficients", out.len())?;
        self.layout.check_len("dF/domega", jac_omega.len())?;
        if jac_u.nrows() != len || jac_u.ncols() != len {
            return Err(HbmError::Dimension {
                what: "dF/dU (rows x cols)",
                expected: len * len,
                got: jac_u.nrows() * jac_u.ncols(),
            });
        }
        let velocity = force.depends_on_velocity();
        let n = self.layout.n_dofs();
        let nnz = force.pattern().len();
        self.ensure_jacobian_buffers(nnz);
        self.sample_motion(u, omega, velocity);
        self.evaluate_with_jacobian(force, nnz);
        self.check_finite_forces()?;
        if self
            .dfdx
            .iter()
            .chain(&self.dfdxdot)
            .any(|v| !v.is_finite())
        {
            return Err(HbmError::NonFiniteForce {
                sample: first_nonfinite_sample(&self.dfdx, nnz)
                    .or_else(|| first_nonfinite_sample(&self.dfdxdot, nnz))
                    .unwrap_or(0),
            });
        }

        let f = std::mem::take(&mut self.f);
        self.transform_samples(&f, n);
        self.f = f;
        self.spectrum_to_coeffs(out);

        jac_u.fill(0.0);
        let dfdx = std::mem::take(&mut self.dfdx);
        self.transform_samples(&dfdx, nnz);
        self.dfdx = dfdx;
        for (p, &(i, k)) in force.pattern().iter().enumerate() {
            self.load_products(p);
            self.add_displacement_block(i, k, jac_u.rb_mut());
        }

        if velocity {
            let dfdxdot = std::mem::take(&mut self.dfdxdot);
            self.transform_samples(&dfdxdot, nnz);
            self.dfdxdot = dfdxdot;
            for (p, &(i, k)) in force.pattern().iter().enumerate() {
                self.load_products(p);
                self.add_velocity_block(i, k, omega, jac_u.rb_mut());
            }
            self.omega_derivative_samples(force.pattern(), nnz);
            let w = std::mem::take(&mut self.omega_work);
            self.transform_samples(&w, n);
            self.omega_work = w;
            self.spectrum_to_coeffs(jac_omega);
        } else {
            jac_omega.fill(0.0);
        }
        Ok(())
    }

    fn check_force<F: NonlinearForce + ?Sized>(&mut self, force: &F) -> Result<(), HbmError> {
        let n = self.layout.n_dofs();
        if force.n_dofs() != n {
            return Err(HbmError::Dimension {
                what: "nonlinear force dofs",
                expected: n,
                got: force.n_dofs(),
            });
        }
        let pattern = force.pattern();
        if pattern != self.checked_pattern.as_slice() {
            validate_pattern(pattern, n)?;
            check_time_size(self.n_samples, pattern.len())?;
            self.checked_pattern.clear();
            self.checked_pattern.extend_from_slice(pattern);
        }
        Ok(())
    }

    fn ensure_jacobian_buffers(&mut self, nnz: usize) {
        let len = self.n_samples * nnz;
        if self.dfdx.len() != len {
            self.dfdx.resize(len, 0.0);
            self.dfdxdot.resize(len, 0.0);
        }
        let spec_len = self.n_samples * nnz.max(self.layout.n_dofs());
        if self.spectrum.len() < spec_len {
            self.spectrum.resize(spec_len, Complex::new(0.0, 0.0));
        }
    }

    /// Fills `x`, `x_theta = dx/dtheta` and `xdot = omega x_theta` at the samples.
    fn sample_motion(&mut self, u: &[f64], omega: f64, velocity: bool) {
        let mut x = std::mem::take(&mut self.x);
        self.synthesize(u, Synthesis::Value, 1.0);
        self.spectrum_to_samples(&mut x);
        self.x = x;
        if velocity {
            let mut xt = std::mem::take(&mut self.x_theta);
            self.synthesize(u, Synthesis::PhaseDerivative, 1.0);
            self.spectrum_to_samples(&mut xt);
            for (v, &d) in self.xdot.iter_mut().zip(&xt) {
                *v = omega * d;
            }
            self.x_theta = xt;
        } else {
            self.xdot.fill(0.0);
            self.x_theta.fill(0.0);
        }
    }

    fn evaluate_with_jacobian<F: NonlinearForce + ?Sized>(&mut self, force: &F, nnz: usize) {
        let n = self.layout.n_dofs();
        self.f.fill(0.0);
        self.dfdx.fill(0.0);
        self.dfdxdot.fill(0.0);
        for j in 0..self.n_samples {
            let r = j * n..(j + 1) * n;
            let q = j * nnz..(j + 1) * nnz;
            let jac = LocalJacobian {
                dfdx: &mut self.dfdx[q.clone()],
                dfdxdot: &mut self.dfdxdot[q],
            };
            force.eval(
                &self.x[r.clone()],
                &self.xdot[r.clone()],
                &mut self.f[r],
                Some(jac),
            );
        }
    }

    /// `omega_work[j n + i] = sum_k df_i/dxdot_k (t_j) dx_k/dtheta (t_j)`, whose projection is
    /// `dF~/domega`.
    fn omega_derivative_samples(&mut self, pattern: &[(usize, usize)], nnz: usize) {
        let n = self.layout.n_dofs();
        self.omega_work.fill(0.0);
        for j in 0..self.n_samples {
            for (p, &(i, k)) in pattern.iter().enumerate() {
                self.omega_work[j * n + i] += self.dfdxdot[j * nnz + p] * self.x_theta[j * n + k];
            }
        }
    }

    fn check_finite_forces(&self) -> Result<(), HbmError> {
        let n = self.layout.n_dofs();
        match first_nonfinite_sample(&self.f, n) {
            Some(sample) => Err(HbmError::NonFiniteForce { sample }),
            None => Ok(()),
        }
    }

    fn check_time_len(&self, what: &'static str, got: usize) -> Result<(), HbmError> {
        let expected = self.n_samples * self.layout.n_dofs();
        if got != expected {
            return Err(HbmError::Dimension {
                what,
                expected,
                got,
            });
        }
        Ok(())
    }

    /// Loads the Hermitian spectrum of eq. (23) (or of its `theta`-derivative), times
    /// `scale`, for every dof into `spectrum[i N + m]` and applies the inverse FFT.
    fn synthesize(&mut self, u: &[f64], mode: Synthesis, scale: f64) {
        let (n, nn, h) = (
            self.layout.n_dofs(),
            self.n_samples,
            self.layout.n_harmonics(),
        );
        let spec = &mut self.spectrum[..n * nn];
        spec.fill(Complex::new(0.0, 0.0));
        for (i, s) in spec.chunks_exact_mut(nn).enumerate() {
            if mode == Synthesis::Value {
                s[0] = Complex::new(scale * u[i], 0.0);
            }
            for k in 1..=h {
                let half = Complex::new(0.5 * u[(2 * k - 1) * n + i], -0.5 * u[2 * k * n + i]);
                let z = match mode {
                    Synthesis::Value => half * scale,
                    Synthesis::PhaseDerivative => half * Complex::new(0.0, scale * k as f64),
                };
                s[k] = z;
                s[nn - k] = z.conj();
            }
        }
        self.inverse.process_with_scratch(spec, &mut self.scratch);
    }

    fn spectrum_to_samples(&self, out: &mut [f64]) {
        let (n, nn) = (self.layout.n_dofs(), self.n_samples);
        for (i, s) in self.spectrum[..n * nn].chunks_exact(nn).enumerate() {
            for (j, z) in s.iter().enumerate() {
                out[j * n + i] = z.re;
            }
        }
    }

    /// Forward FFT of `width` sample-major signals `values[j width + c]` into
    /// `spectrum[c N + m] = sum_j values[j width + c] exp(-i m theta_j)`.
    fn transform_samples(&mut self, values: &[f64], width: usize) {
        let nn = self.n_samples;
        let spec = &mut self.spectrum[..width * nn];
        for (c, s) in spec.chunks_exact_mut(nn).enumerate() {
            for (j, z) in s.iter_mut().enumerate() {
                *z = Complex::new(values[j * width + c], 0.0);
            }
        }
        if width > 0 {
            self.forward.process_with_scratch(spec, &mut self.scratch);
        }
    }

    /// Reads the layout coefficients out of the forward spectrum of `n` signals:
    /// `U0 = Re S_0 / N`, `Ukc = 2 Re S_k / N`, `Uks = -2 Im S_k / N`.
    fn spectrum_to_coeffs(&self, u: &mut [f64]) {
        let (n, nn, h) = (
            self.layout.n_dofs(),
            self.n_samples,
            self.layout.n_harmonics(),
        );
        let inv = 1.0 / nn as f64;
        for (i, s) in self.spectrum[..n * nn].chunks_exact(nn).enumerate() {
            u[i] = s[0].re * inv;
            for k in 1..=h {
                u[(2 * k - 1) * n + i] = 2.0 * s[k].re * inv;
                u[2 * k * n + i] = -2.0 * s[k].im * inv;
            }
        }
    }

    /// Loads `Gc(m)`, `Gs(m)`, `m = 0..=2H`, of pattern entry `p` from the forward spectrum.
    fn load_products(&mut self, p: usize) {
        let nn = self.n_samples;
        let s = &self.spectrum[p * nn..(p + 1) * nn];
        for ((gc, gs), z) in self.gc.iter_mut().zip(self.gs.iter_mut()).zip(s) {
            *gc = z.re;
            *gs = -z.im;
        }
    }

    /// `sum_j E[a, j] g(theta_j) D[j, b]` for basis functions `a = (ka, pa)`, `b = (kb, pb)`
    /// from the loaded `Gc`, `Gs` (product-to-sum identities).
    fn projected_product(&self, (ka, pa): (usize, Part), (kb, pb): (usize, Part)) -> f64 {
        let gc = |m: isize| self.gc[m.unsigned_abs()];
        let gs = |m: isize| m.signum() as f64 * self.gs[m.unsigned_abs()];
        let (a, b) = (ka as isize, kb as isize);
        let half_sum = match (pa, pb) {
            (Part::Cos, Part::Cos) => 0.5 * (gc(a - b) + gc(a + b)),
            (Part::Cos, Part::Sin) => 0.5 * (gs(a + b) - gs(a - b)),
            (Part::Sin, Part::Cos) => 0.5 * (gs(a + b) + gs(a - b)),
            (Part::Sin, Part::Sin) => 0.5 * (gc(a - b) - gc(a + b)),
        };
        let weight = if ka == 0 { 1.0 } else { 2.0 };
        weight * half_sum / self.n_samples as f64
    }

    /// `jac[(a, i), (b, k)] += E diag(df_i/dx_k) D` for all block pairs.
    fn add_displacement_block(&self, i: usize, k: usize, mut jac: MatMut<'_, f64>) {
        let (n, blocks) = (self.layout.n_dofs(), self.layout.n_blocks());
        for b in 0..blocks {
            let Some(kind_b) = self.layout.block_kind(b) else {
                continue;
            };
            for a in 0..blocks {
                let Some(kind_a) = self.layout.block_kind(a) else {
                    continue;
                };
                jac[(a * n + i, b * n + k)] += self.projected_product(kind_a, kind_b);
            }
        }
    }

    /// `jac[(a, i), (b, k)] += omega E diag(df_i/dxdot_k) D'`, where `D'` is the phase
    /// derivative of the synthesis: `d cos(k theta) = -k sin`, `d sin(k theta) = k cos`.
    fn add_velocity_block(&self, i: usize, k: usize, omega: f64, mut jac: MatMut<'_, f64>) {
        let (n, blocks) = (self.layout.n_dofs(), self.layout.n_blocks());
        for b in 1..blocks {
            let Some((kb, pb)) = self.layout.block_kind(b) else {
                continue;
            };
            let (factor, derived) = match pb {
                Part::Cos => (-(kb as f64) * omega, (kb, Part::Sin)),
                Part::Sin => (kb as f64 * omega, (kb, Part::Cos)),
            };
            for a in 0..blocks {
                let Some(kind_a) = self.layout.block_kind(a) else {
                    continue;
                };
                jac[(a * n + i, b * n + k)] += factor * self.projected_product(kind_a, derived);
            }
        }
    }
}

fn check_time_size(n_samples: usize, per_sample: usize) -> Result<(), HbmError> {
    let too_many = HbmError::TooManySamples {
        n_samples,
        per_sample,
        limit: MAX_TIME_VALUES,
    };
    if n_samples > MAX_SAMPLES {
        return Err(too_many);
    }
    match n_samples.checked_mul(per_sample) {
        Some(v) if v <= MAX_TIME_VALUES => Ok(()),
        _ => Err(too_many),
    }
}

fn first_nonfinite_sample(values: &[f64], width: usize) -> Option<usize> {
    if width == 0 {
        return None;
    }
    values
        .iter()
        .position(|v| !v.is_finite())
        .map(|p| p / width)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_rules() {
        // (p+1)H+1: 13 for a cubic, 10 for a quadratic; never below 2H+1 = 7.
        assert_eq!(min_samples_exact(3, 3), 13);
        assert_eq!(min_samples_exact(3, 1), 7);
        assert_eq!(min_samples_exact(3, 2), 10);
        assert_eq!(min_samples_exact(3, 0), 7);
        let table: Vec<usize> = [1, 3, 5, 7, 9, 10]
            .iter()
            .map(|&h| default_samples(h))
            .collect();
        assert_eq!(table, vec![16, 32, 64, 64, 128, 128]);
        for h in 0..40 {
            assert!(default_samples(h) >= min_samples_exact(h, 3));
        }
    }

    #[test]
    fn synthesis_and_projection_are_inverse() {
        // Round trip of an arbitrary coefficient vector; only rounding of O(1) values
        // through two FFTs of length 13, hence 1e-13.
        let layout = HarmonicLayout::new(3, 4).unwrap();
        let mut aft = Aft::new(layout, 13).unwrap();
        let u: Vec<f64> = (0..layout.len())
            .map(|i| ((i * 5 + 1) % 9) as f64 - 4.0)
            .collect();
        let mut x = vec![0.0; 13 * 3];
        aft.coeffs_to_samples(&u, &mut x).unwrap();
        let mut back = vec![0.0; layout.len()];
        aft.samples_to_coeffs(&x, &mut back).unwrap();
        for (a, b) in u.iter().zip(&back) {
            assert!((a - b).abs() < 1e-13, "{a} vs {b}");
        }
        // Samples agree with the direct series (eq. 23) at theta_j = 2 pi j / N.
        let mut xi = vec![0.0; 3];
        let mut vi = vec![0.0; 3];
        let mut xdot = vec![0.0; 13 * 3];
        aft.coeffs_to_velocity_samples(&u, 1.7, &mut xdot).unwrap();
        for j in 0..13 {
            let theta = 2.0 * std::f64::consts::PI * j as f64 / 13.0;
            layout.displacement_at(&u, theta, &mut xi).unwrap();
            layout.velocity_at(&u, 1.7, theta, &mut vi).unwrap();
            for i in 0..3 {
                assert!((x[j * 3 + i] - xi[i]).abs() < 1e-12);
                assert!((xdot[j * 3 + i] - vi[i]).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn too_few_samples_is_an_error() {
        let layout = HarmonicLayout::new(1, 3).unwrap();
        assert!(matches!(
            Aft::new(layout, 6),
            Err(HbmError::TooFewSamples { min: 7, .. })
        ));
        assert!(Aft::new(layout, 7).is_ok());
        assert!(Aft::new(layout, MAX_SAMPLES + 1).is_err());
    }
}
