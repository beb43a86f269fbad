//! Stability of a limit cycle from its Floquet exponents (issue 10, item 3), two independent
//! ways: Hill's method on the harmonic balance, and the monodromy matrix of the variational
//! equations integrated over one period.
//!
//! **Variational equations.** In the modal coordinates of [`ModalBrake`] a perturbation `y` of
//! the cycle `x*(t)` obeys
//!
//! `y'' + D y' + Ω² y + Φ_nᵀ (J_x(t) Φ_n y + J_v(t) Φ_n y') = 0`,
//!
//! with `J_x = ∂G/∂x_n`, `J_v = ∂G/∂x_n'` the Jacobians of the reduced contact force
//! `G = F_nl - K_s x_n` ([`ModalBrake::reduced_jacobians`]) along the cycle: `T`-periodic,
//! `T = 2π/ω`. Floquet: its solutions are `e^{σt} p(t)` with `p` periodic; the multipliers are
//! `ρ = e^{σT}`. One exponent is always zero (the time shift of the autonomous cycle, the
//! *trivial* exponent); the cycle is stable when every other exponent has `Re σ < 0`. A real
//! multiplier leaving the unit circle through +1 is a fold, through −1 a period doubling, and
//! a complex pair leaving it a Neimark–Sacker bifurcation (the cycle turns quasi-periodic).
//!
//! **Hill's method.** With `p(t) = Σ_{k=-H..H} p_k e^{ikωt}` and
//! `J(t) = Σ_m Ĵ_m e^{imωt}` (discrete Fourier transform on the harmonic balance's time
//! samples, so that Hill's matrix at `σ = 0` *is* the harmonic balance Jacobian and the trivial
//! exponent is zero to the solution's tolerance), harmonic balance of the variational
//! equations gives the quadratic eigenproblem
//!
//! `Q(σ) p = [Δ(σ + ikω) p_k + Φ_nᵀ Σ_j (Ĵx_{k-j} + (σ + ijω) Ĵv_{k-j}) Φ_n p_j]_k = 0`,
//!
//! `Δ(s) = s² I + s D + Ω²`, i.e. `Q(σ) = σ² I + σ M1 + M0`, solved in its first-order form
//! `[[0, I], [-M0, -M1]]` (size `2 n (2H + 1)`). Every exponent appears `2H + 1` times, shifted
//! by `ikω`; the **sorting rule** keeps the copy in the strip `|Im σ| ≤ ω/2` (Lazarus & Thomas
//! 2010: the copy whose eigenvector is centred on the cycle's harmonics), which holds one copy of
//! each exponent whose mode lies below `(H + ½) ω`. The exponents near the imaginary axis are
//! found by shift-invert Arnoldi at `N_c` shifts `σ_c = i (c + ½) ω / (2 N_c)` on the upper half
//! of the strip (the lower half holds the conjugates). The contact coupling has low rank: each
//! pair's force acts along its normal `g` and tangent `h` and depends on `δ = g·x` (and on
//! `g·x'`, `h·x'` for a velocity-dependent law), so `J = Q_E C(t) Q_Rᵀ` with `Q_E` spanning the
//! `g`s and `h`s and `Q_R` the `g`s (rank 9 for the bundled brake's 9 pairs, against 36
//! nonlinear dofs). Each solve with `Q(σ_c) = B + U Ĉ V` (`B` block diagonal of
//! `Δ(σ_c + ikω)`, diagonal for modal damping; `U = Φ̂ᵀ Q̂_E`, `V = Q̂_Rᵀ Φ̂`) is then a solve with
//! `B` and the Woodbury correction `Q⁻¹ = B⁻¹ - B⁻¹ U Ĉ (I + V B⁻¹ U Ĉ)⁻¹ V B⁻¹`, whose
//! capacitance of size `q_R (2H + 1)` is factored once per shift. Its blocks `V B⁻¹ U` are the
//! receptances `Φ_R Δ_k⁻¹ Φ_Eᵀ = Σ_j φ_R,j φ_E,jᵀ / Δ_jj(σ_c + ikω)` (`Φ_R = Q_Rᵀ Φ_n`,
//! `Φ_E = Q_Eᵀ Φ_n`): with modal damping, those of every harmonic are one product of the
//! modes' pair products `φ_R,j φ_E,jᵀ` with the table of `1/Δ_jj`. With the blocks of a Krylov
//! vector as the columns of an `n × (2H + 1)` matrix, `V y` and `U c` are one matrix product
//! each. The Ritz values converged in a disk around each shift cover the cell of the strip
//! around it; the region where *every* exponent was found is reported
//! ([`HillFloquet::coverage`]).
//!
//! **Monodromy.** The `2n` columns of the identity are integrated over one period through the
//! variational equations (first-order form, `J` evaluated on the cycle's Fourier series at
//! each time) by the BDF integrator of [`squeal_ode`]; the multipliers are the eigenvalues of
//! the resulting monodromy matrix: all `2n`, independent of Hill's truncation and sorting.

use faer::linalg::matmul::matmul;
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::{Accum, Mat, MatMut, MatRef, Par, c64};
use rayon::prelude::*;
use squeal_brake::dynamics::state_jacobian;
use squeal_brake::harmonic::ModalSolver;
use squeal_brake::modal_brake::ModalBrake;
use squeal_eigs::arnoldi::{Arnoldi, RitzPair};
use squeal_hbm::{HarmonicLayout, HbmError, Part};
use squeal_ode::{Atol, Bdf, BdfOptions, OdeSystem};
use std::borrow::Cow;
use std::f64::consts::PI;
use std::time::{Duration, Instant};

/// Errors of the Floquet analysis.
#[derive(Debug, thiserror::Error)]
pub enum FloquetError {
    /// The cycle's coefficients do not fit its layout, or the layout is invalid.
    #[error(transparent)]
    Hbm(#[from] HbmError),
    /// A dense eigenvalue decomposition did not converge.
    #[error("the {what} eigenvalue decomposition did not converge")]
    Eigen {
        /// Which one.
        what: &'static str,
    },
    /// The time integration of the variational equations failed.
    #[error("the variational equations could not be integrated: {0}")]
    Ode(#[from] squeal_ode::OdeError),
    /// An option is out of range.
    #[error("invalid Floquet option: {0}")]
    BadOption(&'static str),
}

/// One Floquet exponent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exponent {
    /// `σ` (s⁻¹ and rad/s), `|Im σ| ≤ ω/2`.
    pub sigma: c64,
    /// `ρ = e^{σT}`.
    pub multiplier: c64,
    /// Whether this is the trivial exponent (the cycle's time shift).
    pub trivial: bool,
}

/// A cycle: the nonlinear dofs' Fourier coefficients and the frequency.
#[derive(Clone, Copy, Debug)]
pub struct CycleRef<'a> {
    /// Layout of `u` (nonlinear dofs).
    pub layout: HarmonicLayout,
    /// Coefficients (eq 25).
    pub u: &'a [f64],
    /// ω (rad/s).
    pub omega: f64,
    /// Time samples per period on which the harmonic balance evaluated the force (Hill's
    /// Jacobian harmonics come from the same samples).
    pub samples: usize,
}

/// Options of [`hill`].
#[derive(Clone, Debug, PartialEq)]
pub struct HillOptions {
    /// Harmonics of the perturbation (`None`: the cycle's). More than the cycle's measures the
    /// truncation's effect on the exponents.
    pub harmonics: Option<usize>,
    /// Every exponent with `Re σ > -coverage · ω` is wanted: the strip's upper half is cut into
    /// cells of that half-height, one shift-invert centre each. The default 0.01 finds every
    /// multiplier with `|ρ| > e^{-2π · 0.01} = 0.939`, all that a verdict or a bifurcation
    /// needs; it is also the fastest on the bundled brake (fewer Arnoldi steps per cell
    /// outweigh the 25 cells instead of 13 at 0.02: `cargo bench -p squeal-pipeline --bench
    /// branch -- level=medium coverage=c`, docs/benchmarks.md), with the same verdicts and the
    /// largest multipliers within 2.3e-10 of 0.02's.
    pub coverage: f64,
    /// Largest Krylov dimension per shift.
    pub max_krylov: usize,
    /// A Ritz pair is accepted when its exponent's error estimate (residual over `|θ|²`) is
    /// below this times ω.
    pub tolerance: f64,
}

impl Default for HillOptions {
    fn default() -> Self {
        Self {
            harmonics: None,
            coverage: 0.01,
            max_krylov: 120,
            tolerance: 1e-10,
        }
    }
}

/// Hill's method's result.
#[derive(Clone, Debug)]
pub struct HillFloquet {
    /// The exponents found, `Re σ` descending (conjugates included, one per pair for real ones).
    pub exponents: Vec<Exponent>,
    /// Every exponent with `Re σ > -coverage` in the strip was found (s⁻¹; below the asked
    /// coverage when a cell's Krylov space reached its largest dimension first).
    pub coverage: f64,
    /// `|σ|` of the trivial exponent (zero in exact arithmetic: the method's error scale), s⁻¹.
    pub trivial_error: f64,
    /// Harmonics of the perturbation.
    pub harmonics: usize,
    /// Solves with `Q(σ_c)` (Arnoldi steps) over all shifts.
    pub solves: usize,
    /// Wall time.
    pub time: Duration,
}

impl HillFloquet {
    /// The non-trivial exponent of largest real part.
    pub fn leading(&self) -> Option<Exponent> {
        self.exponents.iter().copied().find(|e| !e.trivial)
    }

    /// The largest multiplier modulus over the non-trivial exponents.
    pub fn largest_multiplier(&self) -> f64 {
        self.leading().map_or(0.0, |e| e.multiplier.norm())
    }

    /// Stable, unstable, or marginal when the leading exponent is within the method's error
    /// ([`HillFloquet::trivial_error`]) of zero.
    pub fn stability(&self) -> CycleStability {
        classify(self.leading().map(|e| e.sigma.re), self.trivial_error)
    }
}

/// The verdict on a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CycleStability {
    /// Every non-trivial exponent has a negative real part beyond the error.
    Stable,
    /// One has a positive real part beyond the error.
    Unstable,
    /// The largest is within the method's error of zero (at a bifurcation).
    Marginal,
}

impl std::fmt::Display for CycleStability {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            CycleStability::Stable => "stable",
            CycleStability::Unstable => "unstable",
            CycleStability::Marginal => "marginal",
        })
    }
}

fn classify(leading: Option<f64>, error: f64) -> CycleStability {
    match leading {
        None => CycleStability::Stable,
        Some(re) if re > error => CycleStability::Unstable,
        Some(re) if re < -error => CycleStability::Stable,
        Some(_) => CycleStability::Marginal,
    }
}

/// The contact Jacobians at one time of the cycle: `J_x` and, when the
/// element depends on velocity, `J_v` (nonlinear dofs).
type JacobianSample = (Mat<f64>, Option<Mat<f64>>);

/// `J_x`, `J_v` (nonlinear dofs) at each of `samples` times of the cycle.
fn jacobian_samples(
    mb: &ModalBrake,
    cycle: &CycleRef<'_>,
    samples: usize,
) -> Result<Vec<JacobianSample>, FloquetError> {
    let nn = cycle.layout.n_dofs();
    cycle
        .layout
        .check_len("cycle coefficients", cycle.u.len())?;
    let velocity = mb.velocity_dependent();
    let mut out = Vec::with_capacity(samples);
    let (mut x, mut v) = (vec![0.0; nn], vec![0.0; nn]);
    for s in 0..samples {
        let theta = 2.0 * PI * s as f64 / samples as f64;
        cycle.layout.displacement_at(cycle.u, theta, &mut x)?;
        cycle
            .layout
            .velocity_at(cycle.u, cycle.omega, theta, &mut v)?;
        out.push(mb.reduced_jacobians(&x, velocity.then_some(&v[..])));
    }
    Ok(out)
}

/// Orthonormal columns spanning `vectors` (dense, length `n`), by Gram–Schmidt twice,
/// dropping dependent ones.
fn orthonormal(vectors: &[Vec<f64>], n: usize) -> Mat<f64> {
    let mut cols: Vec<Vec<f64>> = Vec::new();
    for v in vectors {
        let mut w = v.clone();
        let n0 = w.iter().map(|a| a * a).sum::<f64>().sqrt();
        for _ in 0..2 {
            for c in &cols {
                let d: f64 = c.iter().zip(&w).map(|(a, b)| a * b).sum();
                w.iter_mut().zip(c).for_each(|(a, b)| *a -= d * b);
            }
        }
        let nw = w.iter().map(|a| a * a).sum::<f64>().sqrt();
        if nw > 1e-10 * n0 && nw > 0.0 {
            cols.push(w.into_iter().map(|a| a / nw).collect());
        }
    }
    Mat::from_fn(n, cols.len(), |i, j| cols[j][i])
}

/// The column and row spaces of the contact Jacobians: each pair's force acts along its normal
/// `g` and tangent `h` and depends on `δ = g·x` (and, for a velocity-dependent law, on
/// `g·x'`, `h·x'`), so `J_x = Q_E C_x Q_Rᵀ`, `J_v = Q_E C_v Q_Rᵀ` with `Q_E` spanning
/// `{g, h}` and `Q_R` spanning `{g}` (`{g, h}` with velocity terms). The springs `K_s` lie in
/// `{g} ⊗ {g}`.
fn contact_bases(mb: &ModalBrake) -> (Mat<f64>, Mat<f64>) {
    let nn = mb.nl();
    let dense = |sv: &[(usize, f64)]| {
        let mut v = vec![0.0; nn];
        for &(i, a) in sv {
            v[i] += a;
        }
        v
    };
    let g: Vec<Vec<f64>> = mb.pairs.iter().map(|p| dense(&p.normal)).collect();
    let gh: Vec<Vec<f64>> = mb
        .pairs
        .iter()
        .flat_map(|p| [dense(&p.normal), dense(&p.tangent)])
        .collect();
    let qe = orthonormal(&gh, nn);
    let qr = if mb.velocity_dependent() {
        qe.clone()
    } else {
        orthonormal(&g, nn)
    };
    (qe, qr)
}

/// The harmonics `Ĉ_m`, `m = -2H..=2H` (index `m + 2H`), of sampled matrices.
fn harmonics_of(samples: &[Mat<f64>], h: usize) -> Vec<Mat<c64>> {
    let ns = samples.len();
    let (r, c) = (samples[0].nrows(), samples[0].ncols());
    (0..=4 * h)
        .map(|idx| {
            let m = idx as f64 - 2.0 * h as f64;
            let mut out = Mat::<c64>::zeros(r, c);
            for (s, js) in samples.iter().enumerate() {
                let th = -m * 2.0 * PI * s as f64 / ns as f64;
                let e = c64::new(th.cos(), th.sin()) / ns as f64;
                for j in 0..c {
                    for i in 0..r {
                        out[(i, j)] += e * js[(i, j)];
                    }
                }
            }
            out
        })
        .collect()
}

/// A real matrix as a complex one.
fn complex(m: &Mat<f64>) -> Mat<c64> {
    Mat::from_fn(m.nrows(), m.ncols(), |i, j| c64::new(m[(i, j)], 0.0))
}

/// Hill's operator of a cycle: the pieces of `Q(σ)`, with the contact coupling in its low-rank
/// form `Φ̂ᵀ Q̂_E Ĉ(σ) Q̂_Rᵀ Φ̂`.
struct Hill<'a> {
    mb: &'a ModalBrake,
    h: usize,
    omega: f64,
    /// `Q_Eᵀ Φ_n` (`q_E × n`), `Q_Rᵀ Φ_n` (`q_R × n`) and `Φ_n` (`n_nl × n`), as complex
    /// matrices for the products with the Krylov vectors.
    phi_e: Mat<c64>,
    phi_r: Mat<c64>,
    phi_n: Mat<c64>,
    /// `Ĉx_m`, `Ĉv_m` (`q_E × q_R`) for `m = -2H..=2H`.
    cx: Vec<Mat<c64>>,
    cv: Option<Vec<Mat<c64>>>,
    /// `Ĉ`, when it does not depend on σ (no `Ĉv`): the same for every shift.
    fixed_core: Option<Mat<c64>>,
    /// Row `i + q_R l` holds `(Q_Rᵀ Φ_n)_ij (Q_Eᵀ Φ_n)_lj` over the modes `j`: with a diagonal
    /// `Δ_k⁻¹`, the receptance `Φ_R Δ_k⁻¹ Φ_Eᵀ` of every harmonic is one product with it.
    pair_products: Mat<c64>,
}

/// `Q(σ_s)⁻¹` by Woodbury, for one shift.
struct ShiftSolver<'h> {
    sigma: c64,
    /// `Δ(σ_s + ikω)` per harmonic `k = -H..=H`.
    modal: Vec<ModalSolver>,
    /// `Ĉ(σ_s)` (`q_E (2H+1) × q_R (2H+1)`): [`Hill`]'s own when it does not depend on σ.
    core: Cow<'h, Mat<c64>>,
    /// LU of `I + V B⁻¹ U Ĉ` (`q_R (2H+1)` square).
    capacitance: PartialPivLu<c64>,
}

impl<'a> Hill<'a> {
    fn new(mb: &'a ModalBrake, cycle: &CycleRef<'_>, h: usize) -> Result<Self, FloquetError> {
        let samples = cycle
            .samples
            .max(squeal_hbm::default_samples(h))
            .max(4 * h + 1);
        // Pad the cycle to h harmonics if the perturbation has more.
        let nn = cycle.layout.n_dofs();
        let layout = HarmonicLayout::new(nn, h.max(cycle.layout.n_harmonics()))?;
        cycle
            .layout
            .check_len("cycle coefficients", cycle.u.len())?;
        let mut u = vec![0.0; layout.len()];
        u[..cycle.u.len()].copy_from_slice(cycle.u);
        let padded = CycleRef {
            layout,
            u: &u,
            omega: cycle.omega,
            samples,
        };
        let js = jacobian_samples(mb, &padded, samples)?;
        let (mut qe, mut qr) = contact_bases(mb);
        // The factorization is exact for the laws of squeal-brake; a law that breaks it falls
        // back on the full nonlinear dofs.
        let exact = js.iter().all(|(jx, jv)| {
            let ok = |m: &Mat<f64>| {
                let back = &qe * (qe.transpose() * m * &qr) * qr.transpose();
                (&back - m).norm_l2() <= 1e-10 * m.norm_l2().max(f64::MIN_POSITIVE)
            };
            ok(jx) && jv.as_ref().is_none_or(ok)
        });
        if !exact {
            qe = Mat::identity(nn, nn);
            qr = Mat::identity(nn, nn);
        }
        let core = |m: &Mat<f64>| qe.transpose() * m * &qr;
        let cx: Vec<Mat<f64>> = js.iter().map(|(a, _)| core(a)).collect();
        let cv: Option<Vec<Mat<f64>>> = js
            .iter()
            .map(|(_, b)| b.as_ref().map(core))
            .collect::<Option<Vec<_>>>();
        let phi_e = complex(&(qe.transpose() * &mb.phi_n));
        let phi_r = complex(&(qr.transpose() * &mb.phi_n));
        let (nqe, nqr) = (phi_e.nrows(), phi_r.nrows());
        let pair_products = Mat::from_fn(nqr * nqe, mb.modes(), |row, j| {
            phi_r[(row % nqr, j)] * phi_e[(row / nqr, j)]
        });
        let mut hill = Self {
            mb,
            h,
            omega: cycle.omega,
            phi_e,
            phi_r,
            phi_n: complex(&mb.phi_n),
            cx: harmonics_of(&cx, h),
            cv: cv.map(|v| harmonics_of(&v, h)),
            fixed_core: None,
            pair_products,
        };
        if hill.cv.is_none() {
            hill.fixed_core = Some(hill.core(c64::new(0.0, 0.0)));
        }
        Ok(hill)
    }

    fn blocks(&self) -> usize {
        2 * self.h + 1
    }

    fn n(&self) -> usize {
        self.mb.modes()
    }

    /// `k` of block `b`.
    fn k(&self, b: usize) -> f64 {
        b as f64 - self.h as f64
    }

    /// `Ĉ(σ)`: block `(k, j)` is `Ĉx_{k-j} + (σ + ijω) Ĉv_{k-j}`.
    fn core(&self, sigma: c64) -> Mat<c64> {
        let (qe, qr) = (self.phi_e.nrows(), self.phi_r.nrows());
        let nb = self.blocks();
        let mut out = Mat::<c64>::zeros(qe * nb, qr * nb);
        for bk in 0..nb {
            for bj in 0..nb {
                let m = bk + 2 * self.h - bj;
                let s = sigma + c64::new(0.0, self.k(bj) * self.omega);
                for j in 0..qr {
                    for i in 0..qe {
                        let mut v = self.cx[m][(i, j)];
                        if let Some(cv) = &self.cv {
                            v += s * cv[m][(i, j)];
                        }
                        out[(bk * qe + i, bj * qr + j)] = v;
                    }
                }
            }
        }
        out
    }

    fn shift(&self, sigma: c64) -> ShiftSolver<'_> {
        let nb = self.blocks();
        let (qe, qr) = (self.phi_e.nrows(), self.phi_r.nrows());
        let modal: Vec<ModalSolver> = (0..nb)
            .map(|b| {
                ModalSolver::new(
                    &self.mb.omega,
                    &self.mb.damping,
                    sigma + c64::new(0.0, self.k(b) * self.omega),
                )
            })
            .collect();
        // V B⁻¹ U, block diagonal: Φ_R Δ_k⁻¹ Φ_Eᵀ (q_R × q_E, column-major), column k of
        // `receptances`.
        let n = self.n();
        let inverses: Option<Vec<&[c64]>> = modal
            .iter()
            .map(|s| match s {
                ModalSolver::Diagonal(d) => Some(&d[..]),
                ModalSolver::Full(_) => None,
            })
            .collect();
        let receptances = match inverses {
            Some(d) => &self.pair_products * Mat::from_fn(n, nb, |j, k| d[k][j]),
            None => {
                let mut out = Mat::<c64>::zeros(qr * qe, nb);
                for (k, s) in modal.iter().enumerate() {
                    let rk = &self.phi_r * s.solve(self.phi_e.transpose());
                    for l in 0..qe {
                        for i in 0..qr {
                            out[(i + qr * l, k)] = rk[(i, l)];
                        }
                    }
                }
                out
            }
        };
        let core = match &self.fixed_core {
            Some(c) => Cow::Borrowed(c),
            None => Cow::Owned(self.core(sigma)),
        };
        let r = qr * nb;
        let mut c = Mat::<c64>::identity(r, r);
        for bk in 0..nb {
            let rk = Mat::<c64>::from_fn(qr, qe, |i, l| receptances[(i + qr * l, bk)]);
            let rows = core.subrows(bk * qe, qe);
            let prod = &rk * rows;
            for i in 0..qr {
                for j in 0..r {
                    c[(bk * qr + i, j)] += prod[(i, j)];
                }
            }
        }
        ShiftSolver {
            sigma,
            modal,
            core,
            capacitance: c.partial_piv_lu(),
        }
    }

    /// `(I ⊗ M) y` blockwise for a `q × n` matrix `m`: with the blocks of `y` as the columns of
    /// an `n × (2H+1)` matrix `Y`, the columns of `M Y`.
    fn reduce(&self, m: &Mat<c64>, y: &[c64]) -> Vec<c64> {
        let (q, nb) = (m.nrows(), self.blocks());
        let mut out = vec![c64::new(0.0, 0.0); q * nb];
        matmul(
            MatMut::from_column_major_slice_mut(&mut out, q, nb),
            Accum::Replace,
            m,
            MatRef::from_column_major_slice(y, self.n(), nb),
            c64::new(1.0, 0.0),
            Par::Seq,
        );
        out
    }

    /// `(I ⊗ Mᵀ) c` blockwise: the columns of `Mᵀ C`.
    fn expand(&self, m: &Mat<c64>, c: &[c64]) -> Vec<c64> {
        let (q, n, nb) = (m.nrows(), self.n(), self.blocks());
        let mut out = vec![c64::new(0.0, 0.0); n * nb];
        matmul(
            MatMut::from_column_major_slice_mut(&mut out, n, nb),
            Accum::Replace,
            m.transpose(),
            MatRef::from_column_major_slice(c, q, nb),
            c64::new(1.0, 0.0),
            Par::Seq,
        );
        out
    }

    /// The nonlinear dofs of each block, `Φ̂ y`.
    fn to_nl(&self, y: &[c64]) -> Vec<c64> {
        self.reduce(&self.phi_n, y)
    }

    /// `x ← B⁻¹ x`, block by block.
    fn modal_solve(&self, s: &ShiftSolver, x: &mut [c64]) {
        for (xb, solver) in x.chunks_exact_mut(self.n()).zip(&s.modal) {
            solver.solve_in_place(xb);
        }
    }

    /// `Q(σ_s)⁻¹ r = y - B⁻¹ U Ĉ (I + V B⁻¹ U Ĉ)⁻¹ V y`, `y = B⁻¹ r` (Woodbury).
    fn solve_q(&self, s: &ShiftSolver, r: &[c64]) -> Vec<c64> {
        let mut y = r.to_vec();
        self.modal_solve(s, &mut y);
        let mut t = self.reduce(&self.phi_r, &y);
        let rr = t.len();
        s.capacitance
            .solve_in_place(MatMut::from_column_major_slice_mut(&mut t, rr, 1));
        let core = &*s.core;
        let mut c = vec![c64::new(0.0, 0.0); core.nrows()];
        matmul(
            MatMut::from_column_major_slice_mut(&mut c, core.nrows(), 1),
            Accum::Replace,
            core,
            MatRef::from_column_major_slice(&t, rr, 1),
            c64::new(1.0, 0.0),
            Par::Seq,
        );
        let mut be = self.expand(&self.phi_e, &c);
        self.modal_solve(s, &mut be);
        for (a, b) in y.iter_mut().zip(&be) {
            *a -= b;
        }
        y
    }

    /// `M1 b` (`M1 = blockdiag(2ikω I + D) + Φ̂ᵀ Ĵv Φ̂`).
    fn m1(&self, b: &[c64]) -> Vec<c64> {
        let n = self.n();
        let mut out = vec![c64::new(0.0, 0.0); b.len()];
        for blk in 0..self.blocks() {
            let ik = c64::new(0.0, 2.0 * self.k(blk) * self.omega);
            for i in 0..n {
                let mut v = ik * b[blk * n + i];
                match self.mb.damping.diagonal() {
                    Some(d) => v += d[i] * b[blk * n + i],
                    None => {
                        for j in 0..n {
                            v += self.mb.damping.entry(i, j) * b[blk * n + j];
                        }
                    }
                }
                out[blk * n + i] = v;
            }
        }
        if let Some(cv) = &self.cv {
            let (qe, qr) = (self.phi_e.nrows(), self.phi_r.nrows());
            let t = self.reduce(&self.phi_r, b);
            let nb = self.blocks();
            let mut c = vec![c64::new(0.0, 0.0); qe * nb];
            for bk in 0..nb {
                for bj in 0..nb {
                    let m = bk + 2 * self.h - bj;
                    for i in 0..qe {
                        for j in 0..qr {
                            c[bk * qe + i] += cv[m][(i, j)] * t[bj * qr + j];
                        }
                    }
                }
            }
            for (o, e) in out.iter_mut().zip(self.expand(&self.phi_e, &c)) {
                *o += e;
            }
        }
        out
    }

    /// `(A - σ_s)⁻¹ [b1; b2]` for the first-order form `A = [[0, I], [-M0, -M1]]`:
    /// `w1 = Q(σ_s)⁻¹ (-b2 - (M1 + σ_s) b1)`, `w2 = b1 + σ_s w1`.
    fn shift_invert(&self, s: &ShiftSolver, b: &[c64]) -> Vec<c64> {
        let half = b.len() / 2;
        let (b1, b2) = b.split_at(half);
        let m1b = self.m1(b1);
        let r: Vec<c64> = (0..half)
            .map(|i| -b2[i] - m1b[i] - s.sigma * b1[i])
            .collect();
        let w1 = self.solve_q(s, &r);
        let mut out = w1.clone();
        out.extend((0..half).map(|i| b1[i] + s.sigma * w1[i]));
        out
    }
}

fn dot(a: &[c64], b: &[c64]) -> c64 {
    a.iter().zip(b).map(|(x, y)| x.conj() * y).sum()
}

/// The complex Fourier coefficients `ikω U_k` (`k = -H..=H`) of the cycle's velocity on the
/// nonlinear dofs: the trivial Floquet vector's nonlinear part.
fn cycle_velocity(cycle: &CycleRef<'_>, h: usize) -> Vec<c64> {
    let nn = cycle.layout.n_dofs();
    let mut out = vec![c64::new(0.0, 0.0); nn * (2 * h + 1)];
    for k in 1..=h.min(cycle.layout.n_harmonics()) {
        for i in 0..nn {
            let c = cycle
                .layout
                .index(k, Part::Cos, i)
                .map_or(0.0, |x| cycle.u[x]);
            let s = cycle
                .layout
                .index(k, Part::Sin, i)
                .map_or(0.0, |x| cycle.u[x]);
            // x = c cos kθ + s sin kθ = Re((c - i s) e^{ikθ}): U_k = (c - i s)/2, U_-k = conj.
            let uk = c64::new(c, -s) * 0.5;
            let w = k as f64 * cycle.omega;
            out[(h + k) * nn + i] = c64::new(0.0, w) * uk;
            out[(h - k) * nn + i] = c64::new(0.0, -w) * uk.conj();
        }
    }
    out
}

/// Floquet exponents of the cycle by Hill's method (see the module docs).
pub fn hill(
    mb: &ModalBrake,
    cycle: &CycleRef<'_>,
    opts: &HillOptions,
) -> Result<HillFloquet, FloquetError> {
    let t0 = Instant::now();
    if !(opts.coverage > 0.0 && opts.coverage <= 0.25) || opts.max_krylov < 8 {
        return Err(FloquetError::BadOption(
            "Hill's coverage must be in (0, 0.25] of ω and the Krylov dimension at least 8",
        ));
    }
    let h = opts.harmonics.unwrap_or(cycle.layout.n_harmonics());
    let hill = Hill::new(mb, cycle, h)?;
    let len = 2 * hill.n() * hill.blocks();
    let omega = cycle.omega;
    let shifts = (1.0 / (4.0 * opts.coverage)).ceil() as usize;
    let half_height = omega / (4.0 * shifts as f64);
    let wanted = opts.coverage * omega;
    let need = (wanted * wanted + half_height * half_height).sqrt();
    let max_krylov = opts.max_krylov.min(len);
    let velocity = cycle_velocity(cycle, h);
    let mac = |x: &[c64]| {
        let nl = hill.to_nl(&x[..x.len() / 2]);
        let d = dot(&velocity, &nl).norm_sqr();
        d / (dot(&velocity, &velocity).norm() * dot(&nl, &nl).norm()).max(f64::MIN_POSITIVE)
    };
    // (σ, MAC with the cycle's velocity)
    let mut found: Vec<(c64, f64)> = Vec::new();
    let mut arnoldi = Arnoldi::new(len, max_krylov);
    let mut coverage = f64::INFINITY;
    let mut solves = 0;
    for c in 0..shifts {
        let centre = c64::new(0.0, (2 * c + 1) as f64 * half_height);
        let s = hill.shift(centre);
        let op = |b: &[c64]| hill.shift_invert(&s, b);
        let (lo, hi) = (
            2.0 * c as f64 * half_height,
            2.0 * (c + 1) as f64 * half_height,
        );
        arnoldi.restart();
        // The Ritz values are checked after 12 steps and every 4 more (a check, an
        // eigendecomposition of the small Hessenberg matrix, costs far less than the steps a
        // coarser schedule would take beyond convergence). Not before 12: with 8 the disk test
        // passed in cells where an exponent had not yet entered the Krylov space (medium brake,
        // coverage 0.005: 12 of 102 verdicts wrong).
        let mut check = 12.min(max_krylov);
        loop {
            while arnoldi.steps() < check && !arnoldi.is_invariant() {
                arnoldi.step(&op);
            }
            let ritz = arnoldi.ritz().map_err(|_| FloquetError::Eigen {
                what: "Arnoldi Hessenberg",
            })?;
            // Converged Ritz values as exponents; the nearest unconverged one bounds the disk
            // in which every exponent was found.
            let mut radius = f64::INFINITY;
            let mut cell = Vec::new();
            for RitzPair {
                value: theta,
                residual: res,
                coefficients: y,
            } in ritz
            {
                if theta.norm() == 0.0 {
                    continue;
                }
                let sigma = centre + c64::new(1.0, 0.0) / theta;
                // The error of σ = σ_c + 1/θ is about res / |θ|².
                if res / theta.norm_sqr() <= opts.tolerance * omega {
                    // Real exponents (and those on the strip's edge) come out with an Im part
                    // of round-off size, of either sign.
                    let slack = 1e-9 * omega;
                    let above = sigma.im >= lo || (c == 0 && sigma.im >= -slack);
                    let below = sigma.im < hi || (c + 1 == shifts && sigma.im <= hi + slack);
                    if above && below {
                        let near_zero = sigma.norm() < 0.05 * omega;
                        let m = if near_zero {
                            mac(&arnoldi.vector(&y))
                        } else {
                            0.0
                        };
                        cell.push((sigma, m));
                    }
                } else {
                    radius = radius.min((sigma - centre).norm());
                }
            }
            if radius >= need || arnoldi.steps() >= max_krylov || arnoldi.is_invariant() {
                let r = radius.min(need);
                let covered = if r > half_height {
                    (r * r - half_height * half_height).sqrt()
                } else {
                    0.0
                };
                coverage = coverage.min(covered);
                found.extend(cell);
                break;
            }
            check = (check + 4).min(max_krylov);
        }
        solves += arnoldi.steps();
    }
    // The trivial exponent: the eigenvector most parallel to the cycle's velocity.
    let trivial_index = found
        .iter()
        .enumerate()
        .filter(|(_, (s, _))| s.norm() < 0.05 * omega)
        .max_by(|a, b| a.1.1.total_cmp(&b.1.1))
        .map(|(i, _)| i);
    let period = 2.0 * PI / omega;
    let mut exponents = Vec::new();
    let mut trivial_error = 0.0;
    for (i, (sigma, _)) in found.iter().enumerate() {
        let trivial = Some(i) == trivial_index;
        if trivial {
            trivial_error = sigma.norm();
        }
        let mut push = |s: c64, trivial: bool| {
            exponents.push(Exponent {
                sigma: s,
                multiplier: (s * period).exp(),
                trivial,
            });
        };
        push(*sigma, trivial);
        // The conjugate, unless the exponent is real (to the tolerance).
        if sigma.im.abs() > 1e-9 * omega {
            push(sigma.conj(), false);
        }
    }
    exponents.sort_by(|a, b| b.sigma.re.total_cmp(&a.sigma.re));
    Ok(HillFloquet {
        exponents,
        coverage,
        trivial_error,
        harmonics: h,
        solves,
        time: t0.elapsed(),
    })
}

/// The variational equations in first-order form `[y; y']' = A(t) [y; y']`.
struct Variational<'a> {
    mb: &'a ModalBrake,
    cycle: CycleRef<'a>,
    velocity: bool,
}

impl Variational<'_> {
    fn jacobians(&self, t: f64) -> (Mat<f64>, Option<Mat<f64>>) {
        let nn = self.mb.nl();
        let (mut x, mut v) = (vec![0.0; nn], vec![0.0; nn]);
        let theta = self.cycle.omega * t;
        // The layout and length were checked by `monodromy`.
        let _ = self
            .cycle
            .layout
            .displacement_at(self.cycle.u, theta, &mut x);
        let _ = self
            .cycle
            .layout
            .velocity_at(self.cycle.u, self.cycle.omega, theta, &mut v);
        self.mb
            .reduced_jacobians(&x, self.velocity.then_some(&v[..]))
    }

    /// `Φ_nᵀ J Φ_n` (modal, `n × n`).
    fn modal(&self, j: &Mat<f64>) -> Mat<f64> {
        let pn = &self.mb.phi_n;
        let jp = j * pn;
        pn.transpose() * &jp
    }
}

impl OdeSystem for Variational<'_> {
    fn dim(&self) -> usize {
        2 * self.mb.modes()
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.mb.modes();
        let nn = self.mb.nl();
        let (q, v) = y.split_at(n);
        let (jx, jv) = self.jacobians(t);
        let pn = &self.mb.phi_n;
        let xn: Vec<f64> = (0..nn)
            .map(|i| (0..n).map(|j| pn[(i, j)] * q[j]).sum())
            .collect();
        let vn: Vec<f64> = (0..nn)
            .map(|i| (0..n).map(|j| pn[(i, j)] * v[j]).sum())
            .collect();
        let mut g: Vec<f64> = (0..nn)
            .map(|i| (0..nn).map(|j| jx[(i, j)] * xn[j]).sum())
            .collect();
        if let Some(jv) = &jv {
            for (i, gi) in g.iter_mut().enumerate() {
                *gi += (0..nn).map(|j| jv[(i, j)] * vn[j]).sum::<f64>();
            }
        }
        dy[..n].copy_from_slice(v);
        for k in 0..n {
            let mut a = -self.mb.omega[k].powi(2) * q[k];
            match self.mb.damping.diagonal() {
                Some(d) => a -= d[k] * v[k],
                None => {
                    a -= (0..n)
                        .map(|j| self.mb.damping.entry(k, j) * v[j])
                        .sum::<f64>()
                }
            }
            a -= (0..nn).map(|i| pn[(i, k)] * g[i]).sum::<f64>();
            dy[n + k] = a;
        }
    }

    fn jacobian(&self, t: f64, _y: &[f64], jac: faer::MatMut<'_, f64>) {
        let (jx, jv) = self.jacobians(t);
        let kv = jv.as_ref().map(|m| self.modal(m));
        state_jacobian(self.mb, &self.modal(&jx), kv.as_ref(), jac);
    }
}

/// The monodromy matrix's result.
#[derive(Clone, Debug)]
pub struct MonodromyFloquet {
    /// All `2n` exponents (principal logarithms of the multipliers over `T`), `Re σ`
    /// descending.
    pub exponents: Vec<Exponent>,
    /// BDF steps over all columns.
    pub steps: usize,
    /// Wall time.
    pub time: Duration,
}

impl MonodromyFloquet {
    /// The non-trivial exponent of largest real part.
    pub fn leading(&self) -> Option<Exponent> {
        self.exponents.iter().copied().find(|e| !e.trivial)
    }
}

/// Options of [`monodromy`]: the BDF tolerances of each column's integration.
#[derive(Clone, Debug, PartialEq)]
pub struct MonodromyOptions {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance (the columns start as unit vectors).
    pub atol: f64,
    /// Highest BDF order.
    pub max_order: usize,
}

impl Default for MonodromyOptions {
    fn default() -> Self {
        Self {
            rtol: 1e-10,
            atol: 1e-12,
            max_order: 5,
        }
    }
}

/// The monodromy matrix of the variational equations along `cycle`, each of its `2n` columns
/// integrated over one period by [`squeal_ode`]'s BDF (in parallel; the bits do not depend on
/// the thread count), and the BDF steps over all columns.
pub fn monodromy_matrix(
    mb: &ModalBrake,
    cycle: &CycleRef<'_>,
    opts: &MonodromyOptions,
) -> Result<(Mat<f64>, usize), FloquetError> {
    cycle
        .layout
        .check_len("cycle coefficients", cycle.u.len())?;
    let sys = Variational {
        mb,
        cycle: *cycle,
        velocity: mb.velocity_dependent(),
    };
    let dim = sys.dim();
    let period = 2.0 * PI / cycle.omega;
    let bdf_opts = BdfOptions {
        rtol: opts.rtol,
        atol: Atol::Scalar(opts.atol),
        max_order: opts.max_order,
        ..BdfOptions::default()
    };
    let columns: Vec<Result<(Vec<f64>, usize), FloquetError>> = (0..dim)
        .into_par_iter()
        .map(|c| {
            let mut y0 = vec![0.0; dim];
            y0[c] = 1.0;
            let mut bdf = Bdf::new(&sys, 0.0, &y0, period, &bdf_opts)?;
            while !bdf.is_finished() {
                bdf.step()?;
            }
            Ok((bdf.y().to_vec(), bdf.stats().steps))
        })
        .collect();
    let mut m = Mat::<f64>::zeros(dim, dim);
    let mut steps = 0;
    for (c, col) in columns.into_iter().enumerate() {
        let (y, s) = col?;
        steps += s;
        for (i, v) in y.iter().enumerate() {
            m[(i, c)] = *v;
        }
    }
    Ok((m, steps))
}

/// Floquet multipliers from the monodromy matrix of the variational equations
/// ([`monodromy_matrix`]).
pub fn monodromy(
    mb: &ModalBrake,
    cycle: &CycleRef<'_>,
    opts: &MonodromyOptions,
) -> Result<MonodromyFloquet, FloquetError> {
    let t0 = Instant::now();
    let (m, steps) = monodromy_matrix(mb, cycle, opts)?;
    let dim = m.nrows();
    let period = 2.0 * PI / cycle.omega;
    let evd = m.eigen().map_err(|_| FloquetError::Eigen {
        what: "monodromy matrix",
    })?;
    let s = evd.S();
    let mut exponents: Vec<Exponent> = (0..dim)
        .map(|i| {
            let rho = s[i];
            Exponent {
                sigma: rho.ln() / period,
                multiplier: rho,
                trivial: false,
            }
        })
        .collect();
    // The trivial multiplier: the one nearest 1.
    if let Some(i) = (0..dim).min_by(|&a, &b| {
        (exponents[a].multiplier - 1.0)
            .norm()
            .total_cmp(&(exponents[b].multiplier - 1.0).norm())
    }) {
        exponents[i].trivial = true;
    }
    exponents.sort_by(|a, b| b.sigma.re.total_cmp(&a.sigma.re));
    Ok(MonodromyFloquet {
        exponents,
        steps,
        time: t0.elapsed(),
    })
}
