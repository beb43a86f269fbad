//! Two-dimensional alternating frequency-time scheme: eq. (29) on a grid of the two torus
//! angles, with its analytic Jacobians.
//!
//! # Grid
//! `θ_j = (2π j1 / N1, 2π j2 / N2)`, sample `j = j1 N2 + j2`; time-domain arrays are
//! sample-major (value `i` of sample `j` at `j n + i`). `X(θ_j)` is the series of
//! [`super::TorusBasis`] evaluated exactly: the inverse two-dimensional FFT (rows of length
//! `N2`, then columns of length `N1`, both by `rustfft`) of the Hermitian spectrum
//! `S[k mod N] = (Uc_k - i Us_k) / 2`, `S[-k mod N] = conj`. The projection
//! `F0 = (1/N) Σ_j f_j`, `Fc_k = (2/N) Σ_j f_j cos(k·θ_j)`, `Fs_k = (2/N) Σ_j f_j sin(k·θ_j)`
//! (`N = N1 N2`) inverts it when no two kept wave numbers, nor a kept one and the negative of
//! another, are congruent modulo `(N1, N2)`: `N_r >= 2 H_r + 1` with `H_r` the largest
//! `|k_r|` kept.
//!
//! # Aliasing
//! A polynomial force of degree `p` holds wave numbers up to `p H_r` in each direction; they
//! fold onto `m_r - l N_r` and stay off the kept ones when `N_r >= (p + 1) H_r + 1` in each
//! direction (the one-angle rule of [`crate::aft`] applied to each angle). The default grid is
//! [`crate::default_samples`] of each direction's largest order, twice the cubic bound, for the
//! same reason as for one angle (a contact's kink aliases at every `N`).
//!
//! # Analytic Jacobian
//! As for one angle, `F = E f(D U)`, and the product of two basis functions reduces to
//! functions of `k_a ± k_b`: `Σ_j g cos(a·θ) cos(b·θ) = (Gc(a - b) + Gc(a + b)) / 2` etc. with
//! `Gc(m) - i Gs(m) = Σ_j g_j e^{-i m·θ_j}` read from one two-dimensional FFT of each pattern
//! entry's samples `g = ∂f_i/∂x_k`. The velocity `ẋ = ω1 ∂X/∂θ1 + ω2 ∂X/∂θ2` makes basis
//! function `b` contribute through its time derivative (`cos -> -w_b sin`, `sin -> w_b cos`,
//! `w_b = k_b·ω`), and `∂F/∂ω_r = E[(∂f/∂ẋ) ∂X/∂θ_r]`. The result is the exact derivative of
//! the discrete map.

use std::sync::Arc;

use faer::MatMut;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use super::basis::TorusBasis;
use super::force::{TorusForce, check_pattern};
use crate::HbmError;
use crate::aft::{MAX_SAMPLES, MAX_TIME_VALUES};
use crate::force::LocalJacobian;

/// The default grid of a basis: [`crate::default_samples`] of each direction's largest order.
pub fn default_grid(basis: &TorusBasis) -> [usize; 2] {
    let (h1, h2) = basis.truncation().max_orders();
    [crate::default_samples(h1), crate::default_samples(h2)]
}

/// What a synthesis produces.
#[derive(Clone, Copy)]
enum Synthesis {
    Value,
    /// `∂/∂θ_r`.
    Angle(usize),
}

/// The 2-D AFT engine of one basis, one force size and one grid (buffers allocated once).
pub struct TorusAft {
    basis: TorusBasis,
    grid: [usize; 2],
    ffts: [[Arc<dyn Fft<f64>>; 2]; 2],
    scratch: Vec<Complex<f64>>,
    spectrum: Vec<Complex<f64>>,
    column: Vec<Complex<f64>>,
    /// Spectrum index of each wave number and of its negative.
    index: Vec<[usize; 2]>,
    x: Vec<f64>,
    xt: [Vec<f64>; 2],
    xdot: Vec<f64>,
    f: Vec<f64>,
    dfdx: Vec<f64>,
    dfdxdot: Vec<f64>,
    work: Vec<f64>,
    /// Spectrum indices of `k_a - k_b` and `k_a + k_b` for element pairs `(a, b)`, `a E + b`.
    pairs: Vec<[usize; 2]>,
}

impl TorusAft {
    /// The engine on an `N1 × N2` grid; needs `N_r >= 2 H_r + 1`.
    pub fn new(basis: TorusBasis, grid: [usize; 2]) -> Result<Self, HbmError> {
        let (h1, h2) = basis.truncation().max_orders();
        for (nr, hr) in grid.iter().zip([h1, h2]) {
            if *nr < 2 * hr + 1 {
                return Err(HbmError::TooFewSamples {
                    n_samples: *nr,
                    n_harmonics: hr,
                    min: 2 * hr + 1,
                });
            }
        }
        let total = grid[0].saturating_mul(grid[1]);
        if total > MAX_SAMPLES || total.saturating_mul(basis.n_dofs()) > MAX_TIME_VALUES {
            return Err(HbmError::TooManySamples {
                n_samples: total,
                per_sample: basis.n_dofs(),
                limit: MAX_TIME_VALUES,
            });
        }
        let mut planner = FftPlanner::new();
        let ffts = [
            [
                planner.plan_fft_forward(grid[0]),
                planner.plan_fft_inverse(grid[0]),
            ],
            [
                planner.plan_fft_forward(grid[1]),
                planner.plan_fft_inverse(grid[1]),
            ],
        ];
        let scratch_len = ffts
            .iter()
            .flatten()
            .map(|f| f.get_inplace_scratch_len())
            .max()
            .unwrap_or(0);
        let spec = |k: [i64; 2]| {
            let m1 = k[0].rem_euclid(grid[0] as i64) as usize;
            let m2 = k[1].rem_euclid(grid[1] as i64) as usize;
            m1 * grid[1] + m2
        };
        let index = basis
            .waves()
            .iter()
            .map(|k| [spec(*k), spec([-k[0], -k[1]])])
            .collect();
        let w = basis.waves();
        let mut pairs = Vec::with_capacity(w.len() * w.len());
        for a in w {
            for b in w {
                pairs.push([
                    spec([a[0] - b[0], a[1] - b[1]]),
                    spec([a[0] + b[0], a[1] + b[1]]),
                ]);
            }
        }
        let zero = Complex::new(0.0, 0.0);
        Ok(Self {
            basis,
            grid,
            ffts,
            scratch: vec![zero; scratch_len],
            spectrum: Vec::new(),
            column: vec![zero; total],
            index,
            x: Vec::new(),
            xt: [Vec::new(), Vec::new()],
            xdot: Vec::new(),
            f: Vec::new(),
            dfdx: Vec::new(),
            dfdxdot: Vec::new(),
            work: Vec::new(),
            pairs,
        })
    }

    /// The basis.
    pub fn basis(&self) -> &TorusBasis {
        &self.basis
    }

    /// `[N1, N2]`.
    pub fn grid(&self) -> [usize; 2] {
        self.grid
    }

    fn n_samples(&self) -> usize {
        self.grid[0] * self.grid[1]
    }

    /// `X(θ_j)` at every grid sample into `x` (`N n` values, sample-major).
    pub fn coeffs_to_samples(&mut self, u: &[f64], x: &mut [f64]) -> Result<(), HbmError> {
        self.basis.check_len("coefficients", u.len())?;
        let expected = self.n_samples() * self.basis.n_dofs();
        if x.len() != expected {
            return Err(HbmError::Dimension {
                what: "torus samples",
                expected,
                got: x.len(),
            });
        }
        self.synthesize(u, Synthesis::Value);
        self.read_samples(x, self.basis.n_dofs());
        Ok(())
    }

    /// The projection of `width`-valued samples (`N width`, sample-major) onto the basis
    /// (`width` values per block).
    pub fn samples_to_coeffs(
        &mut self,
        values: &[f64],
        width: usize,
        out: &mut [f64],
    ) -> Result<(), HbmError> {
        let n = self.n_samples();
        if values.len() != n * width || out.len() != width * self.basis.n_blocks() {
            return Err(HbmError::Dimension {
                what: "torus samples or coefficients",
                expected: n * width,
                got: values.len(),
            });
        }
        self.transform(values, width);
        self.read_coeffs(width, out);
        Ok(())
    }

    /// The force's coefficients `F(U, ω)` (`m` per block) into `out`.
    pub fn forces<F: TorusForce + ?Sized>(
        &mut self,
        force: &F,
        u: &[f64],
        omega: [f64; 2],
        out: &mut [f64],
    ) -> Result<(), HbmError> {
        let m = self.check_force(force, u, out)?;
        self.sample_motion(u, omega, force.depends_on_velocity());
        let n = self.basis.n_dofs();
        self.f.clear();
        self.f.resize(self.n_samples() * m, 0.0);
        for j in 0..self.n_samples() {
            force.eval(
                &self.x[j * n..(j + 1) * n],
                &self.xdot[j * n..(j + 1) * n],
                &mut self.f[j * m..(j + 1) * m],
                None,
            );
        }
        finite(&self.f, m)?;
        let f = std::mem::take(&mut self.f);
        self.transform(&f, m);
        self.f = f;
        self.read_coeffs(m, out);
        Ok(())
    }

    /// [`Self::forces`] with `jac_u = ∂F/∂U` (`m B × n B`, `B` blocks, overwritten) and
    /// `jac_omega[r] = ∂F/∂ω_r` (overwritten).
    pub fn forces_and_jacobian<F: TorusForce + ?Sized>(
        &mut self,
        force: &F,
        u: &[f64],
        omega: [f64; 2],
        out: &mut [f64],
        mut jac_u: MatMut<'_, f64>,
        jac_omega: [&mut [f64]; 2],
    ) -> Result<(), HbmError> {
        let m = self.check_force(force, u, out)?;
        let (n, nb, ns) = (self.basis.n_dofs(), self.basis.n_blocks(), self.n_samples());
        if jac_u.nrows() != m * nb || jac_u.ncols() != n * nb {
            return Err(HbmError::Dimension {
                what: "dF/dU (rows x cols)",
                expected: m * n * nb * nb,
                got: jac_u.nrows() * jac_u.ncols(),
            });
        }
        let velocity = force.depends_on_velocity();
        let nnz = force.pattern().len();
        self.sample_motion(u, omega, velocity);
        self.f.clear();
        self.f.resize(ns * m, 0.0);
        for v in [&mut self.dfdx, &mut self.dfdxdot] {
            v.clear();
            v.resize(ns * nnz, 0.0);
        }
        for j in 0..ns {
            let jac = LocalJacobian {
                dfdx: &mut self.dfdx[j * nnz..(j + 1) * nnz],
                dfdxdot: &mut self.dfdxdot[j * nnz..(j + 1) * nnz],
            };
            force.eval(
                &self.x[j * n..(j + 1) * n],
                &self.xdot[j * n..(j + 1) * n],
                &mut self.f[j * m..(j + 1) * m],
                Some(jac),
            );
        }
        finite(&self.f, m)?;
        finite(&self.dfdx, nnz.max(1))?;
        finite(&self.dfdxdot, nnz.max(1))?;
        let f = std::mem::take(&mut self.f);
        self.transform(&f, m);
        self.f = f;
        self.read_coeffs(m, out);

        jac_u.fill(0.0);
        let d = std::mem::take(&mut self.dfdx);
        self.transform(&d, nnz);
        self.dfdx = d;
        self.add_products(force.pattern(), None, jac_u.as_mut());
        let [j1, j2] = jac_omega;
        if velocity {
            let d = std::mem::take(&mut self.dfdxdot);
            self.transform(&d, nnz);
            self.add_products(force.pattern(), Some(omega), jac_u.as_mut());
            for (r, jr) in [(0, j1), (1, j2)] {
                self.work.clear();
                self.work.resize(ns * m, 0.0);
                for j in 0..ns {
                    for (p, &(i, k)) in force.pattern().iter().enumerate() {
                        self.work[j * m + i] += d[j * nnz + p] * self.xt[r][j * n + k];
                    }
                }
                let w = std::mem::take(&mut self.work);
                self.transform(&w, m);
                self.work = w;
                self.read_coeffs(m, jr);
            }
            self.dfdxdot = d;
        } else {
            j1.fill(0.0);
            j2.fill(0.0);
        }
        Ok(())
    }

    fn check_force<F: TorusForce + ?Sized>(
        &self,
        force: &F,
        u: &[f64],
        out: &[f64],
    ) -> Result<usize, HbmError> {
        if force.n_inputs() != self.basis.n_dofs() {
            return Err(HbmError::Dimension {
                what: "torus force inputs",
                expected: self.basis.n_dofs(),
                got: force.n_inputs(),
            });
        }
        check_pattern(force)?;
        self.basis.check_len("coefficients", u.len())?;
        let m = force.n_outputs();
        let expected = m * self.basis.n_blocks();
        if out.len() != expected {
            return Err(HbmError::Dimension {
                what: "force coefficients",
                expected,
                got: out.len(),
            });
        }
        let per = m.max(force.pattern().len()).max(self.basis.n_dofs());
        if self.n_samples().saturating_mul(per) > MAX_TIME_VALUES {
            return Err(HbmError::TooManySamples {
                n_samples: self.n_samples(),
                per_sample: per,
                limit: MAX_TIME_VALUES,
            });
        }
        Ok(m)
    }

    /// `x`, and with velocity `∂X/∂θ_r` and `ẋ = Σ ω_r ∂X/∂θ_r`, at the samples.
    fn sample_motion(&mut self, u: &[f64], omega: [f64; 2], velocity: bool) {
        let (n, ns) = (self.basis.n_dofs(), self.n_samples());
        let mut x = std::mem::take(&mut self.x);
        x.resize(ns * n, 0.0);
        self.synthesize(u, Synthesis::Value);
        self.read_samples(&mut x, n);
        self.x = x;
        self.xdot.clear();
        self.xdot.resize(ns * n, 0.0);
        for r in 0..2 {
            let mut xt = std::mem::take(&mut self.xt[r]);
            xt.clear();
            xt.resize(ns * n, 0.0);
            if velocity {
                self.synthesize(u, Synthesis::Angle(r));
                self.read_samples(&mut xt, n);
                for (v, d) in self.xdot.iter_mut().zip(&xt) {
                    *v += omega[r] * d;
                }
            }
            self.xt[r] = xt;
        }
    }

    /// Loads the Hermitian spectrum of every dof and applies the inverse 2-D FFT.
    fn synthesize(&mut self, u: &[f64], mode: Synthesis) {
        let (n, ns) = (self.basis.n_dofs(), self.n_samples());
        self.spectrum.clear();
        self.spectrum.resize(n * ns, Complex::new(0.0, 0.0));
        for i in 0..n {
            let s = &mut self.spectrum[i * ns..(i + 1) * ns];
            if let Synthesis::Value = mode {
                s[0] = Complex::new(u[i], 0.0);
            }
            for (e, k) in self.basis.waves().iter().enumerate().skip(1) {
                let half = Complex::new(0.5 * u[(2 * e - 1) * n + i], -0.5 * u[2 * e * n + i]);
                let z = match mode {
                    Synthesis::Value => half,
                    Synthesis::Angle(r) => half * Complex::new(0.0, k[r] as f64),
                };
                let [p, q] = self.index[e];
                s[p] = z;
                s[q] = z.conj();
            }
        }
        self.fft2(n, 1);
    }

    fn read_samples(&self, out: &mut [f64], width: usize) {
        let ns = self.n_samples();
        for (c, s) in self.spectrum[..width * ns].chunks_exact(ns).enumerate() {
            for (j, z) in s.iter().enumerate() {
                out[j * width + c] = z.re;
            }
        }
    }

    /// Forward 2-D FFT of `width` sample-major signals into `spectrum[c N + m]`.
    fn transform(&mut self, values: &[f64], width: usize) {
        let ns = self.n_samples();
        self.spectrum.clear();
        self.spectrum.resize(width * ns, Complex::new(0.0, 0.0));
        for (c, s) in self.spectrum.chunks_exact_mut(ns).enumerate() {
            for (j, z) in s.iter_mut().enumerate() {
                *z = Complex::new(values[j * width + c], 0.0);
            }
        }
        if width > 0 {
            self.fft2(width, 0);
        }
    }

    /// 2-D FFT (`dir` 0 forward, 1 inverse, unnormalized) of the first `width` signals of the
    /// spectrum: rows of length `N2`, then columns of length `N1` through a transposed copy.
    fn fft2(&mut self, width: usize, dir: usize) {
        let [n1, n2] = self.grid;
        let ns = n1 * n2;
        let data = &mut self.spectrum[..width * ns];
        self.ffts[1][dir].process_with_scratch(data, &mut self.scratch);
        for s in data.chunks_exact_mut(ns) {
            for j1 in 0..n1 {
                for j2 in 0..n2 {
                    self.column[j2 * n1 + j1] = s[j1 * n2 + j2];
                }
            }
            self.ffts[0][dir].process_with_scratch(&mut self.column, &mut self.scratch);
            for j1 in 0..n1 {
                for j2 in 0..n2 {
                    s[j1 * n2 + j2] = self.column[j2 * n1 + j1];
                }
            }
        }
    }

    /// Coefficients (`width` per block) from the forward spectrum.
    fn read_coeffs(&self, width: usize, out: &mut [f64]) {
        let ns = self.n_samples();
        let inv = 1.0 / ns as f64;
        for (i, s) in self.spectrum[..width * ns].chunks_exact(ns).enumerate() {
            out[i] = s[0].re * inv;
            for e in 1..self.basis.n_waves() {
                let z = s[self.index[e][0]];
                out[(2 * e - 1) * width + i] = 2.0 * z.re * inv;
                out[2 * e * width + i] = -2.0 * z.im * inv;
            }
        }
    }

    /// Adds `E diag(g) D` (displacement, `omega = None`) or `E diag(g) D'` (velocity) of every
    /// pattern entry, whose spectra are loaded.
    fn add_products(
        &self,
        pattern: &[(usize, usize)],
        omega: Option<[f64; 2]>,
        mut jac: MatMut<'_, f64>,
    ) {
        let ne = self.basis.n_waves();
        let (n, ns) = (self.basis.n_dofs(), self.n_samples());
        let m = jac.nrows() / self.basis.n_blocks();
        let inv = 1.0 / ns as f64;
        let freq: Vec<f64> = (0..ne)
            .map(|e| omega.map_or(0.0, |w| self.basis.frequency(e, w)))
            .collect();
        for (p, &(i, k)) in pattern.iter().enumerate() {
            let s = &self.spectrum[p * ns..(p + 1) * ns];
            for ea in 0..ne {
                let weight = if ea == 0 { inv } else { 2.0 * inv };
                let (rc, rs) = ((2 * ea).saturating_sub(1) * m + i, 2 * ea * m + i);
                for eb in 0..ne {
                    let [im, ip] = self.pairs[ea * ne + eb];
                    let (gcm, gsm) = (s[im].re, -s[im].im);
                    let (gcp, gsp) = (s[ip].re, -s[ip].im);
                    let cc = 0.5 * weight * (gcm + gcp);
                    let cs = 0.5 * weight * (gsp - gsm);
                    let sc = 0.5 * weight * (gsp + gsm);
                    let ss = 0.5 * weight * (gcm - gcp);
                    let (cc_col, cs_col) = ((2 * eb).saturating_sub(1) * n + k, 2 * eb * n + k);
                    match omega {
                        None => {
                            jac[(rc, cc_col)] += cc;
                            if eb > 0 {
                                jac[(rc, cs_col)] += cs;
                            }
                            if ea > 0 {
                                jac[(rs, cc_col)] += sc;
                                if eb > 0 {
                                    jac[(rs, cs_col)] += ss;
                                }
                            }
                        }
                        Some(_) if eb > 0 => {
                            // cos_b' = -w_b sin_b, sin_b' = w_b cos_b.
                            let wb = freq[eb];
                            jac[(rc, cc_col)] -= wb * cs;
                            jac[(rc, cs_col)] += wb * cc;
                            if ea > 0 {
                                jac[(rs, cc_col)] -= wb * ss;
                                jac[(rs, cs_col)] += wb * sc;
                            }
                        }
                        Some(_) => {}
                    }
                }
            }
        }
    }
}

fn finite(values: &[f64], width: usize) -> Result<(), HbmError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(p) => Err(HbmError::NonFiniteForce { sample: p / width }),
        None => Ok(()),
    }
}
