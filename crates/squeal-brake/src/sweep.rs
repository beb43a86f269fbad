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

use crate::continuation::{
    EigenContinuationOptions, Eigenpair, agrees_with, continue_all, seed, validate,
};
use crate::equilibrium::{Equilibrium, NewtonOptions, static_equilibrium};
use crate::error::BrakeError;
use crate::linearized::{Coupling, LinearizedBrake};
use crate::modal::{Damping, modal_basis};
use crate::model::Brake;
use crate::spectrum::{Reference, Spectrum, eigenvalues_of, spectrum, spectrum_of};
use crate::tracking::{mac, match_modes};
use faer::{Mat, c64};
use rayon::prelude::*;

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
    #[default]
    Continuation,
}

/// Controls of a sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
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
}

impl Sweep {
    /// Eigenvalue of branch `b` at point `k`.
    pub fn value(&self, b: usize, k: usize) -> faer::c64 {
        self.points[k].spectrum.values[self.branches[b][k]]
    }
}

/// The frictionless reference of eq (12): equilibrium at μ = 0, modal basis, damping.
pub fn reference(
    brake: &Brake,
    damping: &Damping,
    newton: &NewtonOptions,
) -> Result<Reference, BrakeError> {
    let eq = static_equilibrium(brake, 0.0, None, newton)?;
    let kt0 = brake.tangent_stiffness(&eq.x, 0.0);
    let basis = modal_basis(&brake.m, &kt0)?;
    let d = damping.modal(&basis)?;
    Ok(Reference {
        equilibrium: eq,
        kt0,
        basis,
        damping: d,
    })
}

/// Sweeps `mus` (ascending): equilibria by continuation, spectra by the method of `opts`,
/// branches, crossings, and the refined Hopf point.
pub fn sweep(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
) -> Result<Sweep, BrakeError> {
    sweep_until(brake, reference, mus, opts, false)
}

/// [`sweep`] up to the first in-band crossing only: with continuation the points end at the
/// first one past it (the same points as the whole sweep's up to there), which is all the Hopf
/// point and its coalescing partner need; the dense method sweeps all of `mus`.
pub fn sweep_to_hopf(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
) -> Result<Sweep, BrakeError> {
    sweep_until(brake, reference, mus, opts, true)
}

fn sweep_until(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
    to_hopf: bool,
) -> Result<Sweep, BrakeError> {
    check_ascending(mus)?;
    brake.validate()?;
    let lin = LinearizedBrake::new(brake, reference)?;
    // Continuation needs the diagonal-plus-low-rank form (diagonal damping); a full modal
    // damping matrix is swept densely.
    let low_rank = (opts.method == SweepMethod::Continuation
        && reference.damping.diagonal().is_some())
    .then_some(&lin);
    let tau = opts
        .threshold
        .unwrap_or_else(|| default_threshold(reference));
    let stop = to_hopf.then_some(tau);
    let (points, branches, stats) = match low_rank {
        Some(lr) => continued_points(brake, reference, lr, mus, opts, stop)?,
        None => dense_points(brake, reference, mus, opts)?,
    };
    let crossings = crossings(&points, &branches, opts, tau);
    let mut sweep = Sweep {
        points,
        branches,
        crossings,
        hopf: None,
        stats,
    };
    if let Some(first) = sweep.crossings.iter().find(|c| c.in_band).copied() {
        let continued = match low_rank {
            Some(lr) => crate::hopf::refine(brake, reference, lr, &sweep, &first, opts, tau)?,
            None => None,
        };
        sweep.hopf = match continued {
            Some(h) => Some(h),
            None => Some(refine(brake, reference, &sweep, &first, opts, tau)?),
        };
    }
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
type SweptPoints = (Vec<SweepPoint>, Vec<Vec<usize>>, SweepStats);

/// Points and branches with [`SweepMethod::Dense`].
fn dense_points(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
) -> Result<SweptPoints, BrakeError> {
    let mut equilibria = Vec::with_capacity(mus.len());
    let mut start: Option<Vec<f64>> = None;
    for &mu in mus {
        let eq = static_equilibrium(brake, mu, start.as_deref(), &opts.newton)?;
        start = Some(eq.x.clone());
        equilibria.push(eq);
    }
    let spectra: Vec<Spectrum> = equilibria
        .par_iter()
        .map(|eq| spectrum(brake, reference, eq))
        .collect::<Result<_, _>>()?;
    let points: Vec<SweepPoint> = equilibria
        .into_iter()
        .zip(spectra)
        .map(|(equilibrium, spectrum)| SweepPoint {
            equilibrium,
            spectrum,
        })
        .collect();
    let branches = track(&points);
    let stats = SweepStats {
        dense: points.len(),
        ..SweepStats::default()
    };
    Ok((points, branches, stats))
}

/// Points and branches with [`SweepMethod::Continuation`].
/// The continued points of `mus`; with `stop_at = Some(τ)` they end at the first point where a
/// branch has crossed `Re λ = τ` in the band since the previous one.
fn continued_points(
    brake: &Brake,
    reference: &Reference,
    lr: &LinearizedBrake,
    mus: &[f64],
    opts: &SweepOptions,
    stop_at: Option<f64>,
) -> Result<SweptPoints, BrakeError> {
    let mut walker = Walker {
        brake,
        reference,
        lr,
        opts,
        stats: SweepStats::default(),
    };
    let check_every = opts.continuation.check_every;
    let mut state = walker.start(mus[0])?;
    let mut points = Vec::with_capacity(mus.len());
    let mut branches: Vec<Vec<usize>> = vec![Vec::with_capacity(mus.len()); state.pairs.len()];
    for (k, &mu) in mus.iter().enumerate() {
        if k > 0 {
            let mut next = walker.step(&state, mu)?;
            if check_every > 0 && k % check_every == 0 {
                walker.check(&mut next, &state)?;
            }
            state = next;
        }
        let (point, position) = sweep_point(&state);
        for (b, br) in branches.iter_mut().enumerate() {
            br.push(position[b]);
        }
        points.push(point);
        if let Some(tau) = stop_at
            && crossed_in_band(&points, &branches, opts, tau)
        {
            break;
        }
    }
    Ok((points, branches, walker.stats))
}

/// Whether a branch crossed `Re λ = τ` in the band between the last two points (the test of
/// [`crossings`] on the last interval).
fn crossed_in_band(
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

/// A point of the continuation: equilibrium, coupling, and eigenpairs by branch.
pub(crate) struct State {
    pub eq: Equilibrium,
    pub c: Coupling,
    pub pairs: Vec<Eigenpair>,
}

/// The sweep point of a state (eigenvalues ascending in frequency, as [`spectrum_of`] orders
/// them) and the position of each branch in it.
pub(crate) fn sweep_point(state: &State) -> (SweepPoint, Vec<usize>) {
    let pairs = &state.pairs;
    let n = pairs.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        pairs[a]
            .lambda
            .im
            .total_cmp(&pairs[b].lambda.im)
            .then(a.cmp(&b))
    });
    let mut position = vec![0; n];
    for (i, &b) in order.iter().enumerate() {
        position[b] = i;
    }
    let rows = pairs.first().map_or(0, |p| p.right.len());
    let spectrum = Spectrum {
        mu: state.eq.mu,
        values: order.iter().map(|&b| pairs[b].lambda).collect(),
        modes: Mat::from_fn(rows, n, |i, j| pairs[order[j]].right[i]),
    };
    let point = SweepPoint {
        equilibrium: state.eq.clone(),
        spectrum,
    };
    (point, position)
}

/// Eigenpairs as a [`Spectrum`] in branch order (for matching by correlation).
fn branch_spectrum(mu: f64, pairs: &[Eigenpair]) -> Spectrum {
    let rows = pairs.first().map_or(0, |p| p.right.len());
    Spectrum {
        mu,
        values: pairs.iter().map(|p| p.lambda).collect(),
        modes: Mat::from_fn(rows, pairs.len(), |i, j| pairs[j].right[i]),
    }
}

/// Walks the friction values: equilibria, continued eigenpairs, halvings and fallbacks.
pub(crate) struct Walker<'a> {
    pub brake: &'a Brake,
    pub reference: &'a Reference,
    pub lr: &'a LinearizedBrake,
    pub opts: &'a SweepOptions,
    pub stats: SweepStats,
}

impl Walker<'_> {
    /// Equilibrium at `mu` by Newton's method from `from`.
    pub fn equilibrium(&self, mu: f64, from: &Equilibrium) -> Result<Equilibrium, BrakeError> {
        static_equilibrium(self.brake, mu, Some(&from.x), &self.opts.newton)
    }

    /// The first point: equilibrium from scratch, dense spectrum.
    fn start(&mut self, mu: f64) -> Result<State, BrakeError> {
        let eq = static_equilibrium(self.brake, mu, None, &self.opts.newton)?;
        let c = self.lr.coupling(self.brake, &eq);
        let pairs = self.dense(&c, None)?;
        Ok(State { eq, c, pairs })
    }

    /// Eigenpairs at `c` by the dense solver, in the branch order of `prev` (matched by
    /// correlation and eigenvalue distance, [`match_modes`]) or in ascending frequency.
    pub fn dense(
        &mut self,
        c: &Coupling,
        prev: Option<&[Eigenpair]>,
    ) -> Result<Vec<Eigenpair>, BrakeError> {
        self.stats.dense += 1;
        let (dk, dc) = self.lr.dense_change(c);
        let sp = spectrum_of(
            &self.reference.basis,
            &self.reference.damping,
            &dk,
            dc.as_ref(),
            c.mu,
        )?;
        let order: Vec<usize> = match prev {
            Some(p) => match_modes(&branch_spectrum(c.mu, p), &sp),
            None => (0..sp.values.len()).collect(),
        };
        let copts = &self.opts.continuation;
        Ok(order
            .par_iter()
            .map(|&i| {
                let right: Vec<c64> = (0..sp.modes.nrows()).map(|r| sp.modes[(r, i)]).collect();
                seed(self.lr, c, sp.values[i], right, copts)
            })
            .collect())
    }

    /// The next point at `mu`: continued from `from`, or dense when continuation fails.
    pub fn step(&mut self, from: &State, mu: f64) -> Result<State, BrakeError> {
        let eq = self.equilibrium(mu, &from.eq)?;
        let c = self.lr.coupling(self.brake, &eq);
        self.step_to(from, eq, c)
    }

    /// The next point at a given equilibrium and coupling.
    pub fn step_to(
        &mut self,
        from: &State,
        eq: Equilibrium,
        c: Coupling,
    ) -> Result<State, BrakeError> {
        let pairs = match self.advance(from, &eq, &c, 0)? {
            Some(p) => p,
            None => self.dense(&c, Some(&from.pairs))?,
        };
        Ok(State { eq, c, pairs })
    }

    /// Continues `from` to `(eq, c)`, halving the step while the result is rejected; `None`
    /// after [`EigenContinuationOptions::max_halvings`] halvings.
    fn advance(
        &mut self,
        from: &State,
        eq: &Equilibrium,
        c: &Coupling,
        depth: usize,
    ) -> Result<Option<Vec<Eigenpair>>, BrakeError> {
        let copts = &self.opts.continuation;
        if let Some((pairs, steps)) = continue_all(self.lr, c, &from.pairs, copts) {
            self.stats.iterations += steps;
            if validate(self.lr, c, &from.pairs, &pairs, copts).is_ok() {
                self.stats.continued += 1;
                return Ok(Some(pairs));
            }
        }
        self.stats.rejected += 1;
        if depth >= copts.max_halvings {
            return Ok(None);
        }
        let mid_eq = self.equilibrium(0.5 * (from.eq.mu + eq.mu), &from.eq)?;
        let mid_c = self.lr.coupling(self.brake, &mid_eq);
        let Some(pairs) = self.advance(from, &mid_eq, &mid_c, depth + 1)? else {
            return Ok(None);
        };
        let mid = State {
            eq: mid_eq,
            c: mid_c,
            pairs,
        };
        self.advance(&mid, eq, c, depth + 1)
    }

    /// Compares a continued point with a dense eigenvalue solve; on disagreement replaces it
    /// by the dense eigenpairs matched to `prev`.
    fn check(&mut self, state: &mut State, prev: &State) -> Result<(), BrakeError> {
        self.stats.checks += 1;
        let (dk, dc) = self.lr.dense_change(&state.c);
        let dense = eigenvalues_of(
            &self.reference.basis,
            &self.reference.damping,
            &dk,
            dc.as_ref(),
        )?;
        if !agrees_with(&state.pairs, &dense, self.opts.continuation.check_tolerance) {
            state.pairs = self.dense(&state.c, Some(&prev.pairs))?;
        }
        Ok(())
    }
}

/// Branch indices: branch `b` starts as mode `b` of the first spectrum.
fn track(points: &[SweepPoint]) -> Vec<Vec<usize>> {
    let n = points[0].spectrum.values.len();
    let mut branches: Vec<Vec<usize>> = (0..n).map(|b| vec![b]).collect();
    for k in 1..points.len() {
        let m = match_modes(&points[k - 1].spectrum, &points[k].spectrum);
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

/// Finds, in a new spectrum, the mode continuing a tracked one (best eigenvector correlation,
/// ties broken by eigenvalue distance).
fn follow(from: &Spectrum, j: usize, to: &Spectrum) -> usize {
    let l = from.values[j];
    let mut best = (f64::INFINITY, 0);
    for i in 0..to.values.len() {
        let d = (to.values[i] - l).norm() / (0.05 * l.norm()).max(f64::MIN_POSITIVE);
        let c = (1.0 - mac(from, j, to, i)) + d.min(1.0);
        if c < best.0 {
            best = (c, i);
        }
    }
    best.1
}

/// Refines a crossing by the Illinois variant of regula falsi on the larger real part of the
/// crossing branch and its partner (as [`crate::hopf`] does, for the same reason: where two
/// modes coalesce, either may carry the instability), keeping a bracket. Both are followed by
/// correlation from the lower end of the bracket.
fn refine(
    brake: &Brake,
    reference: &Reference,
    sweep: &Sweep,
    c: &Crossing,
    opts: &SweepOptions,
    tau: f64,
) -> Result<Hopf, BrakeError> {
    let mut branches = vec![c.branch];
    branches.extend(partner(sweep, c));
    // One end: μ, the point, the followed modes' indices in it, the larger real part - τ and
    // which of them has it.
    struct End {
        mu: f64,
        point: SweepPoint,
        modes: Vec<usize>,
        f: f64,
        top: usize,
    }
    let end = |mu: f64, point: SweepPoint, modes: Vec<usize>| {
        let top = (0..modes.len())
            .max_by(|&a, &b| {
                let v = &point.spectrum.values;
                v[modes[a]].re.total_cmp(&v[modes[b]].re).then(b.cmp(&a))
            })
            .unwrap_or(0);
        let f = point.spectrum.values[modes[top]].re - tau;
        End {
            mu,
            point,
            modes,
            f,
            top,
        }
    };
    let follow_all = |from: &End, to: &Spectrum| -> Vec<usize> {
        from.modes
            .iter()
            .map(|&j| follow(&from.point.spectrum, j, to))
            .collect()
    };
    let lo_point = sweep.points[c.k].clone();
    let mut lo = end(
        c.mu_lo,
        lo_point,
        branches.iter().map(|&b| sweep.branches[b][c.k]).collect(),
    );
    let hi_point = sweep.points[c.k + 1].clone();
    let modes = follow_all(&lo, &hi_point.spectrum);
    let mut hi = end(c.mu_hi, hi_point, modes);
    let (mut f_lo, mut f_hi) = (lo.f, hi.f);
    let mut side = 0i8;
    let mut evaluations = 0;
    while hi.mu - lo.mu > opts.mu_tolerance && evaluations < opts.max_refinements {
        let mut mu = (lo.mu * f_hi - hi.mu * f_lo) / (f_hi - f_lo);
        // Keep well inside the bracket; fall back to bisection when regula falsi stalls.
        let width = hi.mu - lo.mu;
        if !mu.is_finite() || mu <= lo.mu + 0.01 * width || mu >= hi.mu - 0.01 * width {
            mu = 0.5 * (lo.mu + hi.mu);
        }
        let eq = static_equilibrium(brake, mu, Some(&lo.point.equilibrium.x), &opts.newton)?;
        let sp = spectrum(brake, reference, &eq)?;
        let modes = follow_all(&lo, &sp);
        let e = end(
            mu,
            SweepPoint {
                equilibrium: eq,
                spectrum: sp,
            },
            modes,
        );
        evaluations += 1;
        if e.f > 0.0 {
            f_hi = e.f;
            hi = e;
            if side == 1 {
                f_lo *= 0.5;
            }
            side = 1;
        } else {
            f_lo = e.f;
            lo = e;
            if side == -1 {
                f_hi *= 0.5;
            }
            side = -1;
        }
    }
    if !(lo.f <= 0.0 && hi.f > 0.0)
        || hi.f - lo.f > 1e-6 * hi.point.spectrum.values[hi.modes[hi.top]].norm()
    {
        return Err(BrakeError::HopfNotResolved {
            bracket: (lo.mu, hi.mu),
            real_parts: (lo.f + tau, hi.f + tau),
        });
    }
    let index = hi.modes[hi.top];
    Ok(Hopf {
        mu0: 0.5 * (lo.mu + hi.mu),
        frequency_hz: hi.point.spectrum.frequency_hz(index),
        branch: branches[hi.top],
        partner: branches.iter().copied().find(|&b| b != branches[hi.top]),
        bracket: (lo.mu, hi.mu),
        real_part_at_bracket: (lo.f, hi.f),
        evaluations,
        index,
        point: hi.point,
    })
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
