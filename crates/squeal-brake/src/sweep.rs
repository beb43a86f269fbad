//! Friction sweeps: equilibrium and spectrum at each μ, modes tracked into branches, and the
//! Hopf point `μ0` (the first crossing of a real part through zero inside the band the model
//! can speak for), refined by root finding.
//!
//! Two methods ([`SweepMethod`]):
//! - [`SweepMethod::Continuation`] (default): a dense eigen-decomposition at the first point
//!   only; from there every eigenpair is continued exactly to the next μ
//!   ([`crate::continuation`], `O(n² P)` per point instead of `O(n³)`), so each branch is
//!   followed by construction. A continued spectrum that fails its checks makes the step be
//!   halved, and after [`EigenContinuationOptions::max_halvings`] halvings the point is computed by
//!   the dense solver and matched by correlation. Every
//!   [`EigenContinuationOptions::check_every`] points the continued eigenvalues are compared with a
//!   dense solve. The Hopf point is refined by Newton's method on `Re λ(μ)` with the exact
//!   derivative from the left and right eigenvectors ([`crate::hopf`]).
//! - [`SweepMethod::Dense`]: a dense eigen-decomposition at every point (in parallel), modes
//!   tracked by correlation and assignment ([`crate::tracking`]), the Hopf point by the
//!   Illinois variant of regula falsi.
//! - [`SweepMethod::Projected`]: the brake projected on its frictionless modes up to a cut-off
//!   above the band, the cut-off chosen by convergence against the unprojected eigenvalues
//!   ([`crate::projected`]); then as the dense method on the small projected problem, the
//!   Hopf point refined by Rayleigh iteration on the two followed eigenpairs
//!   ([`crate::projected_hopf`]). Its cost grows as the cube of the number of kept modes, not
//!   of the reduced size.
//! - [`SweepMethod::Auto`] (the default): continuation up to [`PROJECT_ABOVE`] dofs, the
//!   projection above, where continuing every eigenpair costs `O(n⁴)` per sweep.

use crate::continuation::EigenContinuationOptions;
use crate::equilibrium::{Equilibrium, NewtonOptions, static_equilibrium};
use crate::error::BrakeError;
use crate::linearized::LinearizedBrake;
use crate::modal::{Damping, modal_basis};
use crate::model::Brake;
use crate::projected::{Projection, ProjectionOptions};
use crate::spectrum::{Reference, Spectrum, spectrum};
use crate::sweep_continued::continued_points;
pub(crate) use crate::sweep_continued::{State, Walker, sweep_point};
use crate::tracking::match_modes;
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// The frequency band a result is trusted in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Band {
    /// Highest frequency the reduced model represents: by default the lower of the parts'
    /// highest kept fixed-interface frequencies. Eigenvalues above it are reported but never
    /// define μ0.
    pub valid_max_hz: f64,
    /// A user band (e.g. the squeal band 1–16 kHz), also required for μ0.
    pub user: Option<(f64, f64)>,
}

impl Band {
    /// Whether `f` (Hz) is inside the valid band and the user band.
    pub fn contains(&self, f: f64) -> bool {
        f <= self.valid_max_hz && self.user.is_none_or(|(lo, hi)| f >= lo && f <= hi)
    }
}

/// How the spectra of a sweep are computed (see the module documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SweepMethod {
    /// Dense eigen-decomposition at every point, tracking by correlation.
    Dense,
    /// Exact continuation of every eigenpair, dense solves only to start and to check.
    Continuation,
    /// Projection on the frictionless modes below a converged cut-off, dense solves of the
    /// projected problem ([`crate::projected`]).
    Projected,
    /// [`SweepMethod::Continuation`] for brakes of up to [`PROJECT_ABOVE`] dofs (the bundled
    /// brakes: their pinned numbers are the continuation's), [`SweepMethod::Projected`]
    /// above.
    #[default]
    Auto,
}

/// Reduced size (dofs) above which [`SweepMethod::Auto`] projects. The bundled brakes have
/// 158 (one pad) and 266 (two pads) dofs; continuing every eigenpair of a 482-dof brake took
/// 12-14 minutes (issue 20), projecting it seconds (docs/benchmarks.md).
pub const PROJECT_ABOVE: usize = 300;

impl SweepMethod {
    /// The method used on a brake of `n` dofs ([`SweepMethod::Auto`] resolved).
    pub fn resolve(self, n: usize) -> SweepMethod {
        match self {
            SweepMethod::Auto if n > PROJECT_ABOVE => SweepMethod::Projected,
            SweepMethod::Auto => SweepMethod::Continuation,
            m => m,
        }
    }
}

/// Controls of a sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SweepOptions {
    /// Where a crossing may define μ0 ([`Band::contains`] at its frequency).
    pub band: Band,
    /// Controls of the static equilibrium at every friction value.
    pub newton: NewtonOptions,
    /// Width of the final bracket around μ0.
    pub mu_tolerance: f64,
    /// Spectrum evaluations allowed in the refinement.
    pub max_refinements: usize,
    /// A mode counts as unstable when `Re λ > threshold` (s⁻¹). `None`: `64 ε ω_max`, just
    /// above the eigensolver's round-off on an undamped mode (its error is about `ε ω_max` for
    /// the scaled state matrix of [`crate::spectrum`]). The Hopf point is the root of
    /// `Re λ - threshold`, shifted from that of `Re λ` by `threshold / (dRe λ/dμ)`.
    pub threshold: Option<f64>,
    /// How the spectra are computed.
    pub method: SweepMethod,
    /// Controls of [`SweepMethod::Continuation`].
    pub continuation: EigenContinuationOptions,
    /// Controls of [`SweepMethod::Projected`].
    pub projection: ProjectionOptions,
}

impl Default for SweepOptions {
    fn default() -> Self {
        Self {
            band: Band {
                valid_max_hz: f64::INFINITY,
                user: None,
            },
            newton: NewtonOptions::default(),
            mu_tolerance: 1e-8,
            max_refinements: 80,
            threshold: None,
            method: SweepMethod::default(),
            continuation: EigenContinuationOptions::default(),
            projection: ProjectionOptions::default(),
        }
    }
}

/// What a sweep's spectra cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SweepStats {
    /// Dense eigen-decompositions with vectors (the dense method's every point; the
    /// continuation's first point and fallbacks).
    pub dense: usize,
    /// Dense eigenvalue-only checks of continued spectra.
    pub checks: usize,
    /// Continued spectra accepted (sweep points and the extra points of halved steps).
    pub continued: usize,
    /// Continued spectra rejected (the step was then halved or computed dense).
    pub rejected: usize,
    /// Inverse-iteration steps over all branches and points.
    pub iterations: usize,
    /// Evaluations of a projected sweep's Hopf refinement that were whole decompositions
    /// instead of Rayleigh iterations ([`crate::projected_hopf`]).
    pub refinement_whole: usize,
    /// Times the sweep was redone with friction values inserted into the bracket of a
    /// crossing whose Hopf refinement lost its mode (at most [`RESWEEPS`]).
    pub resweeps: usize,
}

/// Wall time of a sweep's phases, for benchmarks (`crates/squeal-pipeline/benches`): not
/// part of the result (the numbers do not depend on it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SweepTimings {
    /// Choosing and checking the projection ([`SweepMethod::Projected`]; zero otherwise).
    pub projection: Duration,
    /// The equilibria of the sweep points, when found apart from the spectra (the projected
    /// and dense methods; the continuation's are in `spectra`).
    pub equilibria: Duration,
    /// The spectra of the sweep points (with the continuation, the whole walk).
    pub spectra: Duration,
    /// Tracking the branches by correlation (the projected and dense methods).
    pub tracking: Duration,
    /// Refining the Hopf point.
    pub refinement: Duration,
}

/// Equilibrium and spectrum at one μ.
#[derive(Clone, Debug)]
pub struct SweepPoint {
    /// The static equilibrium of eq (14) at this μ.
    pub equilibrium: Equilibrium,
    /// The complex eigenvalues and modes of the brake linearized there (eqs 20–22).
    pub spectrum: Spectrum,
}

/// A real part crossing the instability threshold `τ` ([`SweepOptions::threshold`]) upward
/// between two consecutive sweep points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// The branch that crosses (index into [`Sweep::branches`]).
    pub branch: usize,
    /// Sweep points bracketing the crossing: `k` below (`Re λ <= τ`), `k + 1` above.
    pub k: usize,
    /// μ at point `k`.
    pub mu_lo: f64,
    /// μ at point `k + 1`.
    pub mu_hi: f64,
    /// Frequency at the upper point.
    pub frequency_hz: f64,
    /// Whether that frequency is in [`SweepOptions::band`] (only in-band crossings define
    /// μ0).
    pub in_band: bool,
}

/// The refined Hopf point.
#[derive(Clone, Debug)]
pub struct Hopf {
    /// The Hopf point μ0: the middle of `bracket`.
    pub mu0: f64,
    /// Frequency of the mode that goes unstable, at μ0 (the coalescence frequency).
    pub frequency_hz: f64,
    /// Branch that goes unstable.
    pub branch: usize,
    /// The branch followed with it through the refinement (the other one of the coalescing
    /// pair), when the sweep has one.
    pub partner: Option<usize>,
    /// Final bracket `[μ-, μ+]` with the mode stable at μ- and unstable at μ+, and
    /// `Re λ - threshold` at its ends.
    pub bracket: (f64, f64),
    /// `Re λ - τ` (s⁻¹) of the larger of the two followed modes at `μ-` (≤ 0) and `μ+` (> 0).
    pub real_part_at_bracket: (f64, f64),
    /// Spectrum evaluations used by the refinement.
    pub evaluations: usize,
    /// Equilibrium and spectrum at the upper end of the bracket.
    pub point: SweepPoint,
    /// Index of the mode that goes unstable in `point.spectrum`.
    pub index: usize,
}

/// A sweep: its points, the branches, every upward crossing, and μ0.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// Equilibrium and spectrum at each friction value, in the order swept.
    pub points: Vec<SweepPoint>,
    /// `branches[b][k]`: index of branch `b` in `points[k].spectrum`.
    pub branches: Vec<Vec<usize>>,
    /// Every upward crossing of the threshold, ordered by μ then frequency.
    pub crossings: Vec<Crossing>,
    /// The refined first in-band crossing; `None` when no crossing is in band.
    pub hopf: Option<Hopf>,
    /// What the spectra cost.
    pub stats: SweepStats,
    /// With [`SweepMethod::Projected`]: the modes kept and how the truncation was checked.
    pub projection: Option<Projection>,
    /// Wall time of each phase.
    pub timings: SweepTimings,
}

impl Sweep {
    /// Eigenvalue of branch `b` at point `k`.
    pub fn value(&self, b: usize, k: usize) -> faer::c64 {
        self.points[k].spectrum.values[self.branches[b][k]]
    }
}

/// The frictionless reference of eq (12): equilibrium at μ = 0, modal basis, damping (the
/// modal damping of `damping` plus the brake's physical dampers projected on the modes,
/// [`crate::damping`]).
pub fn reference(
    brake: &Brake,
    damping: &Damping,
    newton: &NewtonOptions,
) -> Result<Reference, BrakeError> {
    let eq = static_equilibrium(brake, 0.0, None, newton)?;
    let kt0 = brake.tangent_stiffness(&eq.x, 0.0);
    let basis = modal_basis(&brake.m, &kt0)?;
    with_damping(brake, eq, kt0, basis, damping)
}

/// The frictionless reference of `before` (its equilibrium, tangent stiffness and modal basis,
/// which do not depend on the damping) with the damping of `damping`: what [`reference()`] gives
/// for it, without solving the equilibrium and the modes again.
pub fn reference_redamped(
    brake: &Brake,
    before: &Reference,
    damping: &Damping,
) -> Result<Reference, BrakeError> {
    with_damping(
        brake,
        before.equilibrium.clone(),
        before.kt0.clone(),
        before.basis.clone(),
        damping,
    )
}

/// The reference of the equilibrium `eq`, its tangent `kt0` and modes `basis` with `damping`.
fn with_damping(
    brake: &Brake,
    eq: Equilibrium,
    kt0: faer::Mat<f64>,
    basis: crate::modal::ModalBasis,
    damping: &Damping,
) -> Result<Reference, BrakeError> {
    let mut d = damping.modal(&basis)?;
    // The dampers' physical damping, projected on the modes (crate::damping).
    if let Some(c) = &brake.c {
        if c.nrows() != basis.phi.nrows() || c.ncols() != basis.phi.nrows() {
            return Err(BrakeError::Dimension {
                what: "damping matrix",
                expected: basis.phi.nrows(),
                got: c.nrows().max(c.ncols()),
            });
        }
        d = d.plus_projected(&basis.phi, c);
    }
    Ok(Reference {
        equilibrium: eq,
        kt0,
        basis,
        damping: d,
    })
}

/// Told `(points done, points in all)` as a sweep goes (from the sweeping thread).
pub type SweepProgress<'a> = &'a (dyn Fn(usize, usize) + Sync);

/// Sweeps `mus` (ascending): equilibria by continuation, spectra by the method of `opts`,
/// branches, crossings, and the refined Hopf point.
pub fn sweep(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
) -> Result<Sweep, BrakeError> {
    sweep_until(brake, reference, mus, opts, false, &|_, _| {})
}

/// [`sweep`], telling `progress` how far it is.
pub fn sweep_with(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
    progress: SweepProgress,
) -> Result<Sweep, BrakeError> {
    sweep_until(brake, reference, mus, opts, false, progress)
}

/// [`sweep`] up to the first in-band crossing only: with continuation the points end at the
/// first one past it, with the projected method at the end of the chunk of friction values
/// that holds it (the same points as the whole sweep's up to there), which is all the Hopf
/// point and its coalescing partner need; the dense method sweeps all of `mus`.
pub fn sweep_to_hopf(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
) -> Result<Sweep, BrakeError> {
    sweep_until(brake, reference, mus, opts, true, &|_, _| {})
}

/// [`sweep_to_hopf`], telling `progress` how far it is.
pub fn sweep_to_hopf_with(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
    progress: SweepProgress,
) -> Result<Sweep, BrakeError> {
    sweep_until(brake, reference, mus, opts, true, progress)
}

/// [`sweep_with`] taking the static equilibria `before` found where it would find them again:
/// `before` is a sweep of the same brake from the same frictionless equilibrium and modes
/// (`reference` of [`reference_redamped`] from its reference) with other damping, over
/// friction values of which `mus` repeats a first part. The projected sweep's equilibria
/// (those of its points and of its truncation check) are each found by Newton's method from a
/// start made of the equilibria before it and the frictionless one, with steps that do not
/// read the damping (dense LU steps, or the modal steps' `T(0)`, in which the damping enters
/// multiplied by `λ = 0`): at the same friction values after the same equilibria they are the
/// same bits, and are taken from `before` instead of solved again. The other methods and the
/// Hopf refinement (whose friction values depend on the spectra) solve their own.
pub(crate) fn sweep_after(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
    progress: SweepProgress,
    before: &Sweep,
) -> Result<Sweep, BrakeError> {
    sweep_at_depth(
        brake,
        reference,
        mus,
        opts,
        false,
        progress,
        0,
        Some(before),
    )
}

fn sweep_until(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
    to_hopf: bool,
    progress: SweepProgress,
) -> Result<Sweep, BrakeError> {
    sweep_at_depth(brake, reference, mus, opts, to_hopf, progress, 0, None)
}

/// How many times a sweep is redone with friction values inserted into the bracket of a
/// crossing whose refinement lost its mode ([`BrakeError::HopfNotResolved`]).
pub const RESWEEPS: usize = 2;

/// Friction values inserted into such a bracket, evenly (an eighth of its width apart).
const RESWEEP_POINTS: usize = 7;

/// `mus` with [`RESWEEP_POINTS`] values inserted evenly between `lo` and `hi`.
fn inserted(mus: &[f64], lo: f64, hi: f64) -> Vec<f64> {
    let n = RESWEEP_POINTS + 1;
    let mut out: Vec<f64> = mus.to_vec();
    out.extend((1..n).map(|i| lo + (hi - lo) * i as f64 / n as f64));
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

#[allow(clippy::too_many_arguments)]
fn sweep_at_depth(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
    to_hopf: bool,
    progress: SweepProgress,
    depth: usize,
    before: Option<&Sweep>,
) -> Result<Sweep, BrakeError> {
    check_ascending(mus)?;
    brake.validate()?;
    let lin = LinearizedBrake::new(brake, reference)?;
    let method = opts.method.resolve(brake.size());
    // Continuation needs the diagonal-plus-low-rank form (diagonal damping); a full modal
    // damping matrix is swept densely.
    let low_rank = (method == SweepMethod::Continuation && reference.damping.diagonal().is_some())
        .then_some(&lin);
    let tau = opts
        .threshold
        .unwrap_or_else(|| default_threshold(reference));
    let stop = to_hopf.then_some(tau);
    progress(0, mus.len());
    let mut timings = SweepTimings::default();
    let t = Instant::now();
    let projection = match method {
        SweepMethod::Projected => {
            let checked = before.and_then(|b| b.projection.as_ref());
            Some(crate::projected::choose(
                brake, reference, &lin, mus, opts, checked,
            )?)
        }
        _ => None,
    };
    timings.projection = t.elapsed();
    let t = &mut timings;
    let (points, branches, stats) = match (&projection, low_rank) {
        (Some(p), _) => {
            let known = before.map_or(&[][..], |b| b.points.as_slice());
            crate::projected::points(
                brake, reference, &lin, p, mus, opts, stop, progress, t, known,
            )?
        }
        (None, Some(lr)) => {
            let start = Instant::now();
            let swept = continued_points(brake, reference, lr, mus, opts, stop, progress)?;
            t.spectra = start.elapsed();
            swept
        }
        (None, None) => dense_points(brake, reference, mus, opts, progress, t)?,
    };
    let start = Instant::now();
    let crossings = crossings(&points, &branches, opts, tau);
    let mut sweep = Sweep {
        points,
        branches,
        crossings,
        hopf: None,
        stats,
        projection: None,
        timings,
    };
    // Every in-band crossing of the first bracket that has one: two modes crossing between
    // the same two friction values are both refined and the lower onset is μ0 (the sort by
    // frequency inside a bracket says nothing about which crosses first).
    let first_bracket: Vec<Crossing> = match sweep.crossings.iter().find(|c| c.in_band) {
        Some(first) => sweep
            .crossings
            .iter()
            .filter(|c| c.in_band && c.k == first.k)
            .copied()
            .collect(),
        None => Vec::new(),
    };
    for first in first_bracket {
        let refined = (|| -> Result<(Hopf, usize), BrakeError> {
            let continued = match low_rank {
                Some(lr) => crate::hopf::refine(brake, reference, lr, &sweep, &first, opts, tau)?,
                None => None,
            };
            // A projected sweep's refinement carries the two followed eigenpairs by Rayleigh
            // iteration (crate::projected_hopf).
            let rayleigh_refinement = opts.projection.rayleigh_refinement;
            let followed = crate::projected_hopf::followed(&sweep, &first);
            let spectrum_at = |eq: &Equilibrium| match &projection {
                Some(p) if rayleigh_refinement => crate::projected_hopf::spectrum_near(
                    &lin,
                    p,
                    &lin.coupling(brake, eq),
                    &followed,
                ),
                Some(p) => crate::projected::spectrum(&lin, p, &lin.coupling(brake, eq)),
                None => spectrum(brake, reference, eq),
            };
            // The projection's equilibria take their Newton steps in the modal basis (a dense LU
            // of a large brake per step costs more than its projected spectrum).
            let equilibrium_at = |mu: f64, from: &[f64]| match &projection {
                Some(_) => crate::projected::equilibrium(
                    brake,
                    reference,
                    &lin,
                    mu,
                    Some(from),
                    &opts.newton,
                ),
                None => static_equilibrium(brake, mu, Some(from), &opts.newton),
            };
            Ok(match continued {
                Some(h) => (h, 0),
                None => {
                    let mut h = crate::hopf::regula_falsi(
                        &equilibrium_at,
                        &spectrum_at,
                        &sweep,
                        &first,
                        opts,
                        tau,
                    )?;
                    if let Some(p) = projection.as_ref().filter(|_| rayleigh_refinement) {
                        crate::projected_hopf::complete(brake, &lin, p, &mut h)?;
                    }
                    (h, followed.whole.get())
                }
            })
        })();
        // A refinement that lost its mode (the tracking between the bracket's two points
        // assigned the crossing to another eigenvalue than the one followed continuously):
        // the sweep is redone with values inserted into that bracket, so the tracking and
        // the crossing are decided on steps an eighth as wide; the result says how often
        // (`SweepStats::resweeps`). After [`RESWEEPS`] the error stands.
        let refined = match refined {
            Ok((h, whole)) => {
                sweep.stats.refinement_whole += whole;
                h
            }
            Err(BrakeError::HopfNotResolved { .. }) if depth < RESWEEPS => {
                let finer = inserted(mus, first.mu_lo, first.mu_hi);
                let mut s = sweep_at_depth(
                    brake,
                    reference,
                    &finer,
                    opts,
                    to_hopf,
                    progress,
                    depth + 1,
                    before,
                )?;
                s.stats.resweeps += 1;
                return Ok(s);
            }
            Err(e) => return Err(e),
        };
        if sweep.hopf.as_ref().is_none_or(|h| refined.mu0 < h.mu0) {
            sweep.hopf = Some(refined);
        }
    }
    sweep.projection = projection;
    sweep.timings.refinement = start.elapsed();
    Ok(sweep)
}

/// Checks that friction values are given, finite and strictly ascending:
/// [`BrakeError::NoFrictionValues`] for none, [`BrakeError::FrictionNotAscending`] at the
/// first value that is not.
pub fn check_ascending(mus: &[f64]) -> Result<(), BrakeError> {
    if mus.is_empty() {
        return Err(BrakeError::NoFrictionValues);
    }
    for (k, &m) in mus.iter().enumerate() {
        if !m.is_finite()
            || (k > 0 && m.partial_cmp(&mus[k - 1]) != Some(std::cmp::Ordering::Greater))
        {
            return Err(BrakeError::FrictionNotAscending {
                index: k + 1,
                value: m,
            });
        }
    }
    Ok(())
}

/// Points of a sweep, the branches tracked through them (pair index per point) and the
/// work counts.
pub(crate) type SweptPoints = (Vec<SweepPoint>, Vec<Vec<usize>>, SweepStats);

/// Points and branches with [`SweepMethod::Dense`].
pub(crate) fn dense_points(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
    progress: SweepProgress,
    timings: &mut SweepTimings,
) -> Result<SweptPoints, BrakeError> {
    let t = Instant::now();
    let mut equilibria = Vec::with_capacity(mus.len());
    let mut start: Option<Vec<f64>> = None;
    for &mu in mus {
        let eq = static_equilibrium(brake, mu, start.as_deref(), &opts.newton)?;
        start = Some(eq.x.clone());
        equilibria.push(eq);
    }
    timings.equilibria = t.elapsed();
    let t = Instant::now();
    // The equilibria are a small part of the work: the count moves once the spectra are done.
    let spectra: Vec<Spectrum> = equilibria
        .par_iter()
        .map(|eq| spectrum(brake, reference, eq))
        .collect::<Result<_, _>>()?;
    timings.spectra = t.elapsed();
    progress(mus.len(), mus.len());
    let points: Vec<SweepPoint> = equilibria
        .into_iter()
        .zip(spectra)
        .map(|(equilibrium, spectrum)| SweepPoint {
            equilibrium,
            spectrum,
        })
        .collect();
    let t = Instant::now();
    let branches = track(&points);
    timings.tracking = t.elapsed();
    let stats = SweepStats {
        dense: points.len(),
        ..SweepStats::default()
    };
    Ok((points, branches, stats))
}

/// Whether a branch crossed `Re λ = τ` in the band between the last two points (the test of
/// [`crossings`] on the last interval).
pub(crate) fn crossed_in_band(
    points: &[SweepPoint],
    branches: &[Vec<usize>],
    opts: &SweepOptions,
    tau: f64,
) -> bool {
    let [.., a, b] = points else {
        return false;
    };
    branches.iter().any(|br| {
        let (i, j) = (br[br.len() - 2], br[br.len() - 1]);
        a.spectrum.values[i].re <= tau
            && b.spectrum.values[j].re > tau
            && opts.band.contains(b.spectrum.frequency_hz(j))
    })
}

/// Branch indices: branch `b` starts as mode `b` of the first spectrum.
pub(crate) fn track(points: &[SweepPoint]) -> Vec<Vec<usize>> {
    track_by(points, match_modes)
}

/// [`track`] with a given matching of consecutive spectra.
pub(crate) fn track_by(
    points: &[SweepPoint],
    matching: fn(&Spectrum, &Spectrum) -> Vec<usize>,
) -> Vec<Vec<usize>> {
    let n = points[0].spectrum.values.len();
    let mut branches: Vec<Vec<usize>> = (0..n).map(|b| vec![b]).collect();
    for k in 1..points.len() {
        let m = matching(&points[k - 1].spectrum, &points[k].spectrum);
        for br in branches.iter_mut() {
            let prev = br[k - 1];
            br.push(m[prev]);
        }
    }
    branches
}

/// The default instability threshold `τ = 64 ε ω_max` (s⁻¹), with `ω_max` the highest
/// frequency (rad/s) of the reference's modal basis ([`SweepOptions::threshold`]).
pub fn default_threshold(reference: &Reference) -> f64 {
    let w = reference.basis.omega.iter().copied().fold(0.0, f64::max);
    64.0 * f64::EPSILON * w
}

/// Every upward crossing of a real part through the threshold `tau`, ordered by μ then
/// frequency.
fn crossings(
    points: &[SweepPoint],
    branches: &[Vec<usize>],
    opts: &SweepOptions,
    tau: f64,
) -> Vec<Crossing> {
    let mut out = Vec::new();
    for (b, br) in branches.iter().enumerate() {
        for k in 0..points.len().saturating_sub(1) {
            let lo = points[k].spectrum.values[br[k]];
            let hi = points[k + 1].spectrum.values[br[k + 1]];
            if lo.re <= tau && hi.re > tau {
                let f = points[k + 1].spectrum.frequency_hz(br[k + 1]);
                out.push(Crossing {
                    branch: b,
                    k,
                    mu_lo: points[k].equilibrium.mu,
                    mu_hi: points[k + 1].equilibrium.mu,
                    frequency_hz: f,
                    in_band: opts.band.contains(f),
                });
            }
        }
    }
    out.sort_by(|a, b| {
        a.mu_lo
            .total_cmp(&b.mu_lo)
            .then(a.frequency_hz.total_cmp(&b.frequency_hz))
    });
    out
}

/// The branch a crossing's branch coalesces with: the other branch nearest in frequency at the
/// upper point of the crossing (where the branch is tracked).
pub(crate) fn partner(sweep: &Sweep, c: &Crossing) -> Option<usize> {
    let k = c.k + 1;
    let distance = |b: usize| {
        (sweep.points[k].spectrum.frequency_hz(sweep.branches[b][k]) - c.frequency_hz).abs()
    };
    (0..sweep.branches.len())
        .filter(|&b| b != c.branch)
        .min_by(|&a, &b| distance(a).total_cmp(&distance(b)))
}
