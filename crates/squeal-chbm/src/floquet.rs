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

mod monodromy;
#[allow(unused_imports)]
use monodromy::*;
pub use monodromy::{MonodromyFloquet, MonodromyOptions, monodromy, monodromy_matrix};

mod hill_matrix;
#[allow(unused_imports)]
use hill_matrix::*;

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
#[non_exhaustive]
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
pub(crate) fn contact_bases(mb: &ModalBrake) -> (Mat<f64>, Mat<f64>) {
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
