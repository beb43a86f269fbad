//! The branch of limit cycles born at the Hopf point (issue 10, item 2): every periodic
//! solution of the brake's harmonic balance (eq 26 on the condensed brake, eq 34) as the
//! friction coefficient, or another parameter, changes — stable or not.
//!
//! **Why a branch.** CHBM (eqs 46–48) finds one cycle per μ from a guessed start, and near μ0
//! its constraint `Re λ = 0` is nearly met by the static solution itself. When the Hopf point
//! is subcritical (a positive first Lyapunov coefficient, [`squeal_brake::criticality`]) the
//! cycles born at μ0 exist *below* μ0, are unstable there, and turn at a fold `μ_fold` into
//! the large stable cycles a time integration settles on: squeal is possible from `μ_fold`
//! on after a large enough disturbance, and spontaneous from μ0. Only the whole branch shows
//! this.
//!
//! **Equations.** The unknowns are `z = [U~, ω, p]`: the Fourier coefficients of the nonlinear
//! dofs (eq 25), the frequency and the parameter. The `L + 1` equations are eq (26) on the
//! condensed brake (the same [`squeal_brake::harmonic`] pieces as CHBM, divided by the static
//! force level) and the phase condition `U1s[d] = 0` on the pad's normal dof `d` that moves
//! most. CHBM's constraint is not needed: on a branch `Re λ = 0` holds at every harmonic
//! balance root. The curve is followed by [`squeal_hbm::continuation`] (pseudo-arclength, so
//! it goes through folds), the unknowns scaled by the smallest static penetration, ω0 and the
//! parameter's start value.
//!
//! **Start.** At a small distance `ε` from μ0 on the side where the normal form
//! ([`NormalForm::radius_squared`]) has a cycle, the guess is the equilibrium plus the normal
//! form's first harmonic at the normal form's frequency. It is corrected with its amplitude
//! `U1c[d]` held fixed (μ free), then the branch grows from it. The Hopf point itself (zero
//! amplitude, μ0, ω0) is the branch's first point, from the linear analysis.
//!
//! **Harmonics.** Fixed, or adapted ([`Harmonics::Adaptive`]): when the highest harmonic holds
//! more than a fraction `tolerance` of the oscillation's energy (the sum over the nonlinear
//! dofs of the squared amplitudes of harmonics `1..=H`), two more harmonics are added and the
//! point is corrected again before the branch goes on.

use crate::cycle::Cycle;
use crate::solve::{ChbmError, force_scale_at, phase_dof};
use faer::c64;
use squeal_brake::criticality::NormalForm;
use squeal_brake::harmonic::{CondensedStiffness, ContactForce, condensed_load};
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::continuation::{self, ContinuationOptions, Control, Family, HbFamily, Point, Stop};
use squeal_hbm::{HarmonicBalance, HarmonicLayout, HbmError, Part, PhaseCondition, RowScales};
use std::time::{Duration, Instant};

mod measures;
#[allow(unused_imports)]
use measures::*;
pub use measures::{pair_cycles, truncation};

/// The harmonic balance of the condensed brake.
pub type BrakeHb = HarmonicBalance<CondensedStiffness, ContactForce>;

/// How many harmonics the branch uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Harmonics {
    /// The same number everywhere.
    Fixed(usize),
    /// From `start`, two more whenever the highest harmonic's share of the oscillation energy
    /// exceeds `tolerance`, up to `max`.
    Adaptive {
        /// Harmonics at the Hopf point.
        start: usize,
        /// Most harmonics.
        max: usize,
        /// Largest share of the energy allowed in the highest harmonic.
        tolerance: f64,
    },
}

impl Harmonics {
    fn start(self) -> usize {
        match self {
            Harmonics::Fixed(h) => h,
            Harmonics::Adaptive { start, .. } => start,
        }
    }
}

/// The parameter along the branch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Parameter {
    /// The friction coefficient μ.
    Friction,
    /// The piston load, as a factor on the scene's.
    LoadScale,
}

impl Parameter {
    /// Its name for tables (`mu`, `load_scale`).
    pub fn name(self) -> &'static str {
        match self {
            Parameter::Friction => "mu",
            Parameter::LoadScale => "load_scale",
        }
    }
}

/// Controls of [`follow_from_hopf`] and [`follow_from_point`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct BranchOptions {
    /// Harmonics along the branch.
    pub harmonics: Harmonics,
    /// AFT samples per period (default: [`squeal_hbm::default_samples`] of the harmonics).
    pub samples: Option<usize>,
    /// The branch ends when the parameter leaves `[range.0, range.1]` times its start value
    /// (μ0 from the Hopf point).
    pub range: (f64, f64),
    /// Relative distance `|μ/μ0 - 1|` of the first computed cycle from the Hopf point.
    pub start_offset: f64,
    /// The branch ends when a pair's peak-to-peak closure exceeds this (m).
    pub max_closure: Option<f64>,
    /// Step control, tolerances and the point budget of the continuation (its
    /// `parameter_range` is set from `range`).
    pub continuation: ContinuationOptions,
}

impl Default for BranchOptions {
    fn default() -> Self {
        Self {
            harmonics: Harmonics::Adaptive {
                start: 3,
                max: 15,
                tolerance: 1e-6,
            },
            samples: None,
            range: (0.5, 1.3),
            start_offset: 1e-4,
            max_closure: None,
            continuation: continuation_in_mu(400),
        }
    }
}

/// The continuation settings of a branch in μ/μ0 (cycles or tori): steps of 0.02 μ0 at most
/// 0.1, four corrector iterations aimed at, twelve at most, converged to 1e-9; at most
/// `max_points` points.
pub(crate) fn continuation_in_mu(max_points: usize) -> ContinuationOptions {
    let mut o = ContinuationOptions::default();
    o.initial_step = 0.02;
    o.min_step = 1e-6;
    o.max_step = 0.1;
    o.target_iterations = 4;
    o.max_iterations = 12;
    o.tolerance = 1e-9;
    o.step_tolerance = 1e-9;
    o.parameter_range = (f64::NEG_INFINITY, f64::INFINITY);
    o.max_points = max_points;
    o
}

/// One pair's normal closure (penetration `δ`, positive when closed) over a cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairCycle {
    /// Mean of `δ` (m).
    pub mean: f64,
    /// Smallest `δ` (m; negative: the pair opens).
    pub min: f64,
    /// Largest `δ` (m).
    pub max: f64,
    /// Fraction of the period with `δ <= 0`, from the roots of the continuous series
    /// ([`crate::physics::open_fractions`]).
    pub open_fraction: f64,
}

impl PairCycle {
    /// `max - min` (m).
    pub fn peak_to_peak(&self) -> f64 {
        self.max - self.min
    }
}

/// Samples per period on which [`PairCycle`]'s mean and extremes are measured (the series is
/// evaluated exactly at each; the open fraction is from the roots instead).
pub const PAIR_SAMPLES: usize = 1024;

/// One point of a branch.
#[derive(Clone, Debug, PartialEq)]
pub struct BranchPoint {
    /// The parameter.
    pub parameter: f64,
    /// ω (rad/s).
    pub omega: f64,
    /// Harmonics of `nl_coeffs`.
    pub harmonics: usize,
    /// Fourier coefficients of the nonlinear dofs (eq 25).
    pub nl_coeffs: Vec<f64>,
    /// Each pair's closure over the cycle.
    pub pairs: Vec<PairCycle>,
    /// Share of the oscillation energy in the highest harmonic.
    pub truncation: f64,
    /// The parameter's component of the branch's unit tangent (scaled): its sign change marks
    /// a fold.
    pub parameter_rate: f64,
    /// Newton iterations that converged the point, and the final residual (scaled).
    pub iterations: usize,
    /// `||R||` over the force scale.
    pub residual: f64,
}

impl BranchPoint {
    /// Frequency (Hz).
    pub fn frequency_hz(&self) -> f64 {
        self.omega / (2.0 * std::f64::consts::PI)
    }

    /// The pair of largest peak-to-peak closure and that closure (m).
    pub fn loudest(&self) -> (usize, f64) {
        self.pairs
            .iter()
            .enumerate()
            .map(|(i, p)| (i, p.peak_to_peak()))
            .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a })
    }

    /// The largest open fraction over the pairs.
    pub fn largest_open_fraction(&self) -> f64 {
        self.pairs
            .iter()
            .map(|p| p.open_fraction)
            .fold(0.0, f64::max)
    }
}

/// A fold (turning point) of the branch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fold {
    /// The parameter at the fold.
    pub parameter: f64,
    /// ω there (rad/s).
    pub omega: f64,
    /// The loudest pair's peak-to-peak closure there (m).
    pub closure: f64,
    /// Index of the branch point just before it.
    pub after_point: usize,
    /// Whether the fold was located to [`FOLD_TOLERANCE`] (otherwise: between two points).
    pub refined: bool,
}

/// `|dp/ds|` (scaled tangent component) at which a fold counts as located.
pub const FOLD_TOLERANCE: f64 = 1e-8;

/// The Hopf point a branch starts from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HopfStart {
    /// μ0.
    pub mu0: f64,
    /// ω0 (rad/s).
    pub omega0: f64,
    /// The first Lyapunov coefficient.
    pub l1: f64,
}

/// A followed branch of limit cycles.
#[derive(Clone, Debug)]
pub struct LimitCycleBranch {
    /// The parameter along it.
    pub parameter: Parameter,
    /// The Hopf point it starts from (branches in μ from μ0).
    pub hopf: Option<HopfStart>,
    /// The converged cycles, in order along the branch (the Hopf point is not one of them).
    pub points: Vec<BranchPoint>,
    /// Its folds.
    pub folds: Vec<Fold>,
    /// Why it ended.
    pub stop: Stop,
    /// The nonlinear dof of the phase condition.
    pub phase_dof: usize,
    /// Wall time.
    pub time: Duration,
}

/// The harmonic balance of `mb` with `harmonics` harmonics.
pub fn brake_harmonic_balance(
    mb: &ModalBrake,
    harmonics: usize,
    samples: Option<usize>,
) -> Result<BrakeHb, HbmError> {
    let layout = HarmonicLayout::new(mb.nl(), harmonics)?;
    let stiffness = CondensedStiffness::new(mb, harmonics);
    let f_eq = condensed_load(mb, &stiffness, &layout);
    HarmonicBalance::new(
        layout,
        stiffness,
        ContactForce::new(mb),
        f_eq,
        samples.map(|s| s.max(squeal_hbm::default_samples(harmonics))),
    )
}

/// The brake's family: its harmonic balance with a parameter.
struct BrakeFamily<'a> {
    mb: &'a ModalBrake,
    parameter: Parameter,
    samples: Option<usize>,
    /// Block 0 of the condensed load at the scene's load (for [`Parameter::LoadScale`]).
    load: Vec<f64>,
}

impl BrakeFamily<'_> {
    fn build(&self, h: usize) -> Result<BrakeHb, HbmError> {
        brake_harmonic_balance(self.mb, h, self.samples)
    }

    /// The continuation family over this brake with `h` harmonics to start with, the phase
    /// condition on nonlinear dof `phase_dof` and the row scales `sc`.
    fn continuation(
        &self,
        h: usize,
        phase_dof: usize,
        sc: RowScales,
    ) -> Result<impl Family + '_, HbmError> {
        HbFamily::new(
            |h| self.build(h),
            |hb: &mut BrakeHb, p| self.set(hb, p),
            h,
            PhaseCondition::FirstSineZero { dof: phase_dof },
            sc,
            1e-7,
        )
    }

    fn set(&self, hb: &mut BrakeHb, p: f64) -> Result<(), HbmError> {
        if !p.is_finite() {
            return Err(HbmError::Parameter {
                value: p,
                why: "not a finite number".into(),
            });
        }
        match self.parameter {
            Parameter::Friction => hb.force_mut().set_mu(p),
            Parameter::LoadScale => {
                let f = hb.external_force_mut();
                for (v, l) in f.iter_mut().zip(&self.load) {
                    *v = p * l;
                }
            }
        }
        Ok(())
    }
}

/// The static level of the residual rows and the displacement scale of the phase row, from the
/// equilibrium's nonlinear dofs.
fn scales(mb: &ModalBrake, x_eq: &[f64], load: &[f64]) -> RowScales {
    let x_scale = mb
        .pairs
        .iter()
        .map(|p| p.penetration(x_eq))
        .filter(|d| *d > 0.0)
        .fold(f64::INFINITY, f64::min);
    RowScales {
        force: force_scale_at(mb, x_eq, load),
        phase: if x_scale.is_finite() { x_scale } else { 1e-6 },
    }
}

fn summary(mb: &ModalBrake, p: &Point) -> Result<BranchPoint, HbmError> {
    let layout = HarmonicLayout::new(mb.nl(), p.harmonics)?;
    let u = &p.z[..layout.len()];
    Ok(BranchPoint {
        parameter: p.parameter(),
        omega: p.omega(),
        harmonics: p.harmonics,
        nl_coeffs: u.to_vec(),
        pairs: pair_cycles(mb, &layout, u),
        truncation: truncation(&layout, u),
        parameter_rate: p.parameter_rate(),
        iterations: p.iterations,
        residual: p.residual,
    })
}

/// The unknowns' weights: the inverse of the static penetration for `U~`, of ω0 for ω and of
/// the start parameter for `p`.
fn weights(x_scale: f64, omega0: f64, p0: f64) -> impl Fn(&HarmonicLayout) -> Vec<f64> {
    move |layout: &HarmonicLayout| {
        let mut w = vec![1.0 / x_scale; layout.len() + 2];
        w[layout.len()] = 1.0 / omega0;
        w[layout.len() + 1] = 1.0 / p0.abs().max(f64::MIN_POSITIVE);
        w
    }
}

/// The branch of limit cycles in μ born at the Hopf point of `nf`, on the modal brake `mb`
/// (its own μ is not used).
pub fn follow_from_hopf(
    mb: &ModalBrake,
    nf: &NormalForm,
    opts: &BranchOptions,
) -> Result<LimitCycleBranch, ChbmError> {
    follow_from_hopf_observed(mb, nf, opts, &mut |_| {})
}

/// [`follow_from_hopf`], telling `on_point` each point as the continuation accepts it (in
/// order: the `i`-th call is `points[i]` of the result, except that a last point left by a
/// failed correction after a change of harmonics is not told).
pub fn follow_from_hopf_observed(
    mb: &ModalBrake,
    nf: &NormalForm,
    opts: &BranchOptions,
    on_point: &mut dyn FnMut(&BranchPoint),
) -> Result<LimitCycleBranch, ChbmError> {
    let t0 = Instant::now();
    let nn = mb.nl();
    let h = opts.harmonics.start();
    if h == 0 {
        return Err(ChbmError::NoHarmonics);
    }
    // The side of μ0 where the normal form has a cycle.
    let mu0 = nf.mu0;
    let mu_s = [1.0 + opts.start_offset, 1.0 - opts.start_offset]
        .into_iter()
        .map(|r| r * mu0)
        .find(|&m| nf.radius_squared(m).is_some())
        .ok_or(ChbmError::NoBranch)?;
    let x_modal = nf.first_harmonic(mu_s).ok_or(ChbmError::NoBranch)?;
    let x_eq: Vec<f64> = mb.nl_dofs.iter().map(|&d| nf.equilibrium.x[d]).collect();
    let layout = HarmonicLayout::new(nn, h)?;
    let mut u = vec![0.0; layout.len()];
    u[..nn].copy_from_slice(&x_eq);
    for i in 0..nn {
        let xi: c64 = (0..mb.modes()).map(|j| x_modal[j] * mb.phi_n[(i, j)]).sum();
        // Re(X e^{iθ}) = Re X cos θ - Im X sin θ.
        u[layout.block_range(1).start + i] = xi.re;
        u[layout.block_range(2).start + i] = -xi.im;
    }
    let d = phase_dof(mb, &u, &layout);
    layout.align_phase(&mut u, d)?;
    let omega_s = nf.omega_at(mu_s);
    let mut z0 = u;
    z0.push(omega_s);
    z0.push(mu_s);

    let family = BrakeFamily {
        mb,
        parameter: Parameter::Friction,
        samples: opts.samples,
        load: Vec::new(),
    };
    let sc = scales(mb, &x_eq, family.build(h)?.external_force());
    let mut hb_family = family.continuation(h, d, sc)?;
    let wf = weights(sc.phase, nf.omega0, mu0);
    // Correct with the amplitude U1c[d] fixed; the tangent points to growing amplitude.
    let ic = layout.index(1, Part::Cos, d).ok_or(ChbmError::NoBranch)?;
    let mut row = vec![0.0; z0.len()];
    row[ic] = 1.0;
    let copts = {
        let mut o = opts.continuation.clone();
        o.parameter_range = (opts.range.0 * mu0, opts.range.1 * mu0);
        o
    };
    let start = continuation::correct_point(
        &mut hb_family,
        &z0,
        &row,
        z0[ic],
        &wf(&layout),
        &row,
        &copts,
    )?
    .ok_or(ChbmError::BranchStart)?;
    let mut branch = run(
        mb,
        &mut hb_family,
        start,
        &wf,
        &copts,
        opts,
        Parameter::Friction,
        on_point,
    )?;
    branch.hopf = Some(HopfStart {
        mu0,
        omega0: nf.omega0,
        l1: nf.l1,
    });
    branch.phase_dof = d;
    branch.time = t0.elapsed();
    Ok(branch)
}

/// The continuation with the observer that adapts the harmonics and ends at the closure
/// limit (each accepted point told to `on_point`), then the folds located.
#[allow(clippy::too_many_arguments)]
fn run<F: Family>(
    mb: &ModalBrake,
    family: &mut F,
    start: Point,
    wf: &impl Fn(&HarmonicLayout) -> Vec<f64>,
    copts: &ContinuationOptions,
    opts: &BranchOptions,
    parameter: Parameter,
    on_point: &mut dyn FnMut(&BranchPoint),
) -> Result<LimitCycleBranch, ChbmError> {
    let mut failure: Option<HbmError> = None;
    let raw = continuation::continue_from(family, start, wf, copts, |p| {
        let s = match summary(mb, p) {
            Ok(s) => s,
            Err(e) => {
                failure = Some(e);
                return Control::Stop("the point could not be summarized".into());
            }
        };
        if let Harmonics::Adaptive { max, tolerance, .. } = opts.harmonics
            && s.truncation > tolerance
            && p.harmonics + 2 <= max
        {
            return Control::Harmonics(p.harmonics + 2);
        }
        let closure = s.loudest().1;
        // Continue or stop: either way the continuation keeps this point.
        on_point(&s);
        match opts.max_closure {
            Some(m) if closure > m => Control::Stop(format!(
                "a pair's peak-to-peak closure {closure:.3e} m passed the limit {m:.3e} m"
            )),
            _ => Control::Continue,
        }
    })?;
    if let Some(e) = failure {
        return Err(e.into());
    }
    let points = raw
        .points
        .iter()
        .map(|p| summary(mb, p))
        .collect::<Result<Vec<_>, _>>()?;
    let folds = locate_folds(mb, family, &raw.points, &points, wf, copts)?;
    Ok(LimitCycleBranch {
        parameter,
        hopf: None,
        points,
        folds,
        stop: raw.stop,
        phase_dof: 0,
        time: Duration::ZERO,
    })
}

/// Folds between consecutive points where the parameter's tangent component changes sign,
/// located by the secant method on that component along the arclength from the point before
/// (each trial point corrected on the branch), when both points have the same harmonics.
fn locate_folds<F: Family>(
    mb: &ModalBrake,
    family: &mut F,
    raw: &[Point],
    points: &[BranchPoint],
    wf: &impl Fn(&HarmonicLayout) -> Vec<f64>,
    copts: &ContinuationOptions,
) -> Result<Vec<Fold>, ChbmError> {
    let mut folds = Vec::new();
    for i in 1..raw.len() {
        let (a, b) = (&raw[i - 1], &raw[i]);
        if a.parameter_rate() * b.parameter_rate() >= 0.0 {
            continue;
        }
        let fallback = Fold {
            parameter: if a.parameter_rate() > 0.0 {
                a.parameter().max(b.parameter())
            } else {
                a.parameter().min(b.parameter())
            },
            omega: 0.5 * (a.omega() + b.omega()),
            closure: 0.5 * (points[i - 1].loudest().1 + points[i].loudest().1),
            after_point: i - 1,
            refined: false,
        };
        if a.harmonics != b.harmonics {
            folds.push(fallback);
            continue;
        }
        if family.layout().n_harmonics() != a.harmonics {
            family.set_harmonics(a.harmonics)?;
        }
        let w = wf(&family.layout());
        let row: Vec<f64> = a.tangent.iter().zip(&w).map(|(t, w)| t * w).collect();
        let base: f64 = row.iter().zip(&a.z).map(|(r, z)| r * z).sum();
        // Arclength of b from a along a's tangent, and the rates at both ends.
        let sb: f64 = row.iter().zip(&b.z).map(|(r, z)| r * z).sum::<f64>() - base;
        let (mut s0, mut r0) = (0.0, a.parameter_rate());
        let (mut s1, mut r1) = (sb, b.parameter_rate());
        let mut best: Option<Point> = None;
        for _ in 0..30 {
            // Secant, kept inside the bracket (bisection when it leaves it).
            let mut s = s0 - r0 * (s1 - s0) / (r1 - r0);
            if !(s > s0.min(s1) && s < s0.max(s1)) {
                s = 0.5 * (s0 + s1);
            }
            let guess: Vec<f64> = (0..a.z.len())
                .map(|k| a.z[k] + s * a.tangent[k] / w[k])
                .collect();
            let Some(p) =
                continuation::correct_point(family, &guess, &row, base + s, &w, &a.tangent, copts)?
            else {
                break;
            };
            let r = p.parameter_rate();
            if (r > 0.0) == (r0 > 0.0) {
                (s0, r0) = (s, r);
            } else {
                (s1, r1) = (s, r);
            }
            let done = r.abs() <= FOLD_TOLERANCE;
            best = Some(p);
            if done {
                break;
            }
        }
        match best {
            Some(p) if p.parameter_rate().abs() <= FOLD_TOLERANCE => {
                let s = summary(mb, &p)?;
                folds.push(Fold {
                    parameter: s.parameter,
                    omega: s.omega,
                    closure: s.loudest().1,
                    after_point: i - 1,
                    refined: true,
                });
            }
            _ => folds.push(fallback),
        }
    }
    Ok(folds)
}

/// The branch in `parameter` through a converged cycle `point` of `mb` (e.g. a point of a
/// branch in μ, then followed in the load), in the direction of growing (`direction > 0`) or
/// shrinking parameter. For [`Parameter::LoadScale`] the start value is 1 (the scene's load) and
/// μ is the point's; for [`Parameter::Friction`] it is the point's μ.
pub fn follow_from_point(
    mb: &ModalBrake,
    point: &BranchPoint,
    phase_dof: usize,
    parameter: Parameter,
    direction: f64,
    opts: &BranchOptions,
) -> Result<LimitCycleBranch, ChbmError> {
    let t0 = Instant::now();
    let mut mbp = mb.clone();
    if parameter == Parameter::LoadScale {
        mbp.mu = point.parameter;
    }
    let p0 = match parameter {
        Parameter::Friction => point.parameter,
        Parameter::LoadScale => 1.0,
    };
    let h = point.harmonics;
    let layout = HarmonicLayout::new(mbp.nl(), h)?;
    layout.check_len("branch point coefficients", point.nl_coeffs.len())?;
    let x_eq = point.nl_coeffs[..mbp.nl()].to_vec();
    let mut family = BrakeFamily {
        mb: &mbp,
        parameter,
        samples: opts.samples,
        load: Vec::new(),
    };
    let hb0 = family.build(h)?;
    family.load = hb0.external_force().to_vec();
    let sc = scales(&mbp, &x_eq, hb0.external_force());
    let mut hb_family = family.continuation(h, phase_dof, sc)?;
    let wf = weights(sc.phase, point.omega, p0);
    let mut z0 = point.nl_coeffs.clone();
    z0.push(point.omega);
    z0.push(p0);
    let n = z0.len();
    let mut row = vec![0.0; n];
    row[n - 1] = 1.0;
    let along: Vec<f64> = row.iter().map(|v| v * direction.signum()).collect();
    let copts = {
        let mut o = opts.continuation.clone();
        o.parameter_range = (opts.range.0 * p0, opts.range.1 * p0);
        o
    };
    let start =
        continuation::correct_point(&mut hb_family, &z0, &row, p0, &wf(&layout), &along, &copts)?
            .ok_or(ChbmError::BranchStart)?;
    let mut branch = run(
        &mbp,
        &mut hb_family,
        start,
        &wf,
        &copts,
        opts,
        parameter,
        &mut |_| {},
    )?;
    branch.phase_dof = phase_dof;
    branch.time = t0.elapsed();
    Ok(branch)
}

/// The cycles of a branch in μ at exactly `mu`: wherever the branch crosses `mu` between two
/// points, the cycle interpolated between them and corrected by Newton with μ held fixed
/// (the point of lower harmonics is used alone when the two differ). Returns each with the
/// index of the point before it, in order along the branch; a folded branch crosses `mu`
/// more than once (the unstable and the stable cycle of a subcritical brake between μ_fold and
/// μ0). `parameter_rate` of a returned cycle is its tangent's μ component oriented along μ.
pub fn cycles_at(
    mb: &ModalBrake,
    branch: &LimitCycleBranch,
    mu: f64,
    opts: &BranchOptions,
) -> Result<Vec<(usize, BranchPoint)>, ChbmError> {
    if branch.parameter != Parameter::Friction || !mu.is_finite() {
        return Err(HbmError::Parameter {
            value: mu,
            why: "cycles at a friction value need a finite mu and a branch in friction".into(),
        }
        .into());
    }
    let Some(first) = branch.points.first() else {
        return Ok(Vec::new());
    };
    let family = BrakeFamily {
        mb,
        parameter: Parameter::Friction,
        samples: opts.samples,
        load: Vec::new(),
    };
    let x_eq = first.nl_coeffs[..mb.nl()].to_vec();
    let sc = scales(mb, &x_eq, family.build(first.harmonics)?.external_force());
    let mut hb_family = family.continuation(first.harmonics, branch.phase_dof, sc)?;
    let wf = weights(sc.phase, first.omega, mu);
    let copts = {
        let mut o = opts.continuation.clone();
        o.parameter_range = (f64::NEG_INFINITY, f64::INFINITY);
        o
    };
    let z_of = |p: &BranchPoint| {
        let mut z = p.nl_coeffs.clone();
        z.push(p.omega);
        z.push(p.parameter);
        z
    };
    let mut out = Vec::new();
    for i in 1..branch.points.len() {
        let (a, b) = (&branch.points[i - 1], &branch.points[i]);
        let (da, db) = (a.parameter - mu, b.parameter - mu);
        // A crossing; a point exactly at mu belongs to the interval that ends there.
        if da * db > 0.0 || da == 0.0 && i > 1 {
            continue;
        }
        let (guess, h) = if a.harmonics == b.harmonics {
            let s = if db != da { da / (da - db) } else { 0.5 };
            let (za, zb) = (z_of(a), z_of(b));
            let z: Vec<f64> = za.iter().zip(&zb).map(|(x, y)| x + s * (y - x)).collect();
            (z, a.harmonics)
        } else {
            let p = if a.harmonics < b.harmonics { a } else { b };
            (z_of(p), p.harmonics)
        };
        if hb_family.layout().n_harmonics() != h {
            hb_family.set_harmonics(h)?;
        }
        let w = wf(&hb_family.layout());
        let n = guess.len();
        let mut row = vec![0.0; n];
        row[n - 1] = 1.0;
        if let Some(p) =
            continuation::correct_point(&mut hb_family, &guess, &row, mu, &w, &row, &copts)?
        {
            out.push((i - 1, summary(mb, &p)?));
        }
    }
    Ok(out)
}

/// The Fourier coefficients of every dof (physical, layout of eq 25 over all `n` dofs) of a
/// cycle of a branch in friction, at its own μ on `mb`'s brake: the nonlinear force's
/// harmonics evaluated on `samples` AFT samples, then eq (35) for the linear dofs.
pub fn full_cycle(
    mb: &ModalBrake,
    point: &BranchPoint,
    samples: Option<usize>,
) -> Result<Vec<f64>, ChbmError> {
    let mut mbp = mb.clone();
    mbp.mu = point.parameter;
    let mut hb = brake_harmonic_balance(&mbp, point.harmonics, samples)?;
    let layout = hb.layout();
    layout.check_len("branch point coefficients", point.nl_coeffs.len())?;
    let mut r = vec![0.0; layout.len()];
    let eval = hb.evaluate(&point.nl_coeffs, point.omega, &mut r)?;
    let g = eval.force.to_vec();
    Ok(squeal_brake::harmonic::recover(
        &mbp,
        point.omega,
        &g,
        &layout,
    ))
}
