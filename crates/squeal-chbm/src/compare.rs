//! Issue #6, items 6–7: CHBM against the time integration of [`crate::timeint`] at one
//! friction level (the paper's Tables 1–2 and Figures 4–5), and where each method fails over a
//! grid of friction levels and initial amplitudes.
//!
//! Everything here is computation returning plain data; the `squeal compare` command turns it
//! into tables and figures. Error measures are those of [`crate::cycle`]: phase-aligned on the
//! reference's most moving contact dof, relative RMS over the cycle, on all physical dofs and
//! on the nonlinear (contact) dofs.

use crate::cycle::{
    Cycle, EnergyBalance, RelativeErrors, energy_balance, harmonic_power, relative_errors,
};
use crate::physics::{DiscSpeed, SlidingMargin, sliding_margin};
use crate::solve::{
    ChbmError, ChbmOptions, ChbmSolution, ChbmStart, Outcome, RESTART_AMPLITUDES, solve,
    solve_with_restarts,
};
use crate::start::start_at;
use crate::timeint::{TiError, TiOptions, TiRun, integrate_from, integrate_to_limit_cycle};
use squeal_brake::Brake;
use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::modal_brake::ModalBrake;
use squeal_brake::spectrum::Reference;
use squeal_brake::sweep::Band;
use std::f64::consts::PI;
use std::time::{Duration, Instant};

/// Errors of a comparison.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// A time integration could not start.
    #[error("time integration: {0}")]
    Ti(#[from] TiError),
    /// The reference integration ended without a steady cycle (why, in words).
    #[error("the reference time integration found no steady cycle: {0}")]
    NoReference(String),
    /// A CHBM solve stopped with an error (not merely unconverged).
    #[error("CHBM with {harmonics} harmonics: {source}")]
    Chbm {
        /// Harmonics of the solve.
        harmonics: usize,
        /// Its error.
        source: ChbmError,
    },
    /// A cycle could not be built or measured (its layout or dofs do not fit).
    #[error("the cycle measures: {0}")]
    Measures(#[from] squeal_hbm::HbmError),
}

/// Options of [`compare_at`].
#[derive(Clone, Debug, PartialEq)]
pub struct CompareOptions {
    /// Harmonics of the CHBM solves (Table 1's columns).
    pub harmonics: Vec<usize>,
    /// Base CHBM options (the harmonics and amplitude are set per solve).
    pub chbm: ChbmOptions,
    /// Initial amplitudes `p` tried in turn until a limit cycle converges.
    pub amplitudes: Vec<f64>,
    /// Base time-integration options (`rtol` set per run).
    pub ti: TiOptions,
    /// Tolerances of the time integrations placed on the speed–accuracy chart.
    pub rtols: Vec<f64>,
    /// Tolerance of the reference integration every error is measured against. The reference
    /// is not integrated from the equilibrium at this tolerance: a run at
    /// [`CompareOptions::seed_rtol`] reaches the steady cycle, a run at
    /// `check_factor · reference_rtol` continues from its end, and the reference continues from
    /// the end of that one ([`ReferenceEstimate`]).
    pub reference_rtol: f64,
    /// Tolerance of the run from the perturbed equilibrium to the steady cycle, where the
    /// tighter runs of the reference start.
    pub seed_rtol: f64,
    /// The check run's tolerance is `check_factor · reference_rtol`; their difference estimates
    /// the reference's own error ([`ReferenceEstimate`]).
    pub check_factor: f64,
    /// Largest relative change between two consecutive Fourier averages of the check and
    /// reference runs ([`TiOptions::drift_tol`]); it must stay above their noise (about
    /// `50 rtol`, from the periods measured on single cycles).
    pub reference_drift_tol: f64,
    /// Periods after which a check or reference run that has not settled gives up.
    pub reference_max_cycles: f64,
    /// The disc's rotation, for the sliding margin of every cycle (none: not checked).
    pub disc: Option<DiscSpeed>,
}

impl Default for CompareOptions {
    fn default() -> Self {
        Self {
            harmonics: vec![1, 2, 3, 5, 10],
            chbm: ChbmOptions::default(),
            amplitudes: RESTART_AMPLITUDES.to_vec(),
            ti: TiOptions::default(),
            rtols: vec![1e-5, 1e-6],
            reference_rtol: 1e-10,
            seed_rtol: 1e-6,
            check_factor: 10.0,
            reference_drift_tol: 1e-7,
            reference_max_cycles: 600.0,
            disc: None,
        }
    }
}

/// Measures of one cycle against the reference.
#[derive(Clone, Debug)]
pub struct Measures {
    /// On every physical dof.
    pub all: RelativeErrors,
    /// On the nonlinear (contact) dofs.
    pub contact: RelativeErrors,
    /// Eq (49) per harmonic (index `j - 1`), on every dof.
    pub power: Vec<f64>,
    /// Power balance over the cycle: friction input against modal damping.
    pub energy: EnergyBalance,
    /// Fraction of the cycle each pair is open.
    pub open_fraction: Vec<f64>,
    /// The disc's surface speed over the pads' tangential vibration
    /// ([`crate::physics::sliding_margin`]; `None` without [`CompareOptions::disc`]).
    pub sliding: Option<SlidingMargin>,
}

/// One CHBM solve of the comparison.
#[derive(Clone, Debug)]
pub struct ChbmRow {
    /// Harmonics of the solve.
    pub harmonics: usize,
    /// Initial amplitude that converged (or the last one tried).
    pub amplitude: f64,
    /// The solve's result (its `time` is the last attempt's only).
    pub solution: ChbmSolution,
    /// The cycle, aligned on the reference.
    pub cycle: Cycle,
    /// Its measures against the reference.
    pub measures: Measures,
    /// Wall time of all the attempts (restarts included).
    pub wall: Duration,
    /// Levenberg–Marquardt trial steps of all the attempts.
    pub iterations: usize,
}

/// One time integration of the comparison.
#[derive(Clone, Debug)]
pub struct TiRow {
    /// Relative tolerance of the integration.
    pub rtol: f64,
    /// The integration.
    pub run: TiRun,
    /// Its steady cycle aligned on the reference (`None` if no steady cycle).
    pub cycle: Option<Cycle>,
    /// Its measures against the reference (`None` if no steady cycle).
    pub measures: Option<Measures>,
}

/// How the reference was reached and how far it is estimated to be from the exact cycle of
/// the reduced model.
///
/// The global error of the order-2 BDF on a limit cycle is mostly a phase (frequency) error
/// growing like `rtol^(2/3)` (local error `∝ h³ = rtol`, global `∝ h²`): measured on the
/// coarse brake at 1.01 μ0, the frequency errors at rtol 1e-6 and 1e-7 against a 20-harmonic
/// CHBM are in the ratio 4.66 = 10^0.67. With the check run at `f · rtol`, the reference's
/// own error is then `|c_check - c_ref| / (f^(2/3) - 1)` (Richardson), which is what
/// [`ReferenceEstimate::all`] and [`ReferenceEstimate::contact`] hold.
#[derive(Clone, Debug)]
pub struct ReferenceEstimate {
    /// The run from the perturbed equilibrium to the steady cycle at
    /// [`CompareOptions::seed_rtol`] (its history shows the growth of the oscillation).
    pub seed: TiRow,
    /// The run at `check_factor · reference_rtol` continued from the seed's end (the seed when
    /// that one is the reference, see [`ReferenceEstimate::unsteady`]); its measures are its raw
    /// difference from the reference (`None` when it found no steady cycle).
    pub check: TiRow,
    /// `1 / ((rtol_check / rtol_reference)^(2/3) - 1)`: the raw difference times this is the
    /// estimate.
    pub scale: f64,
    /// The run at [`CompareOptions::reference_rtol`] when it found no steady cycle within
    /// [`CompareOptions::reference_max_cycles`]: the reference is then the check run, checked
    /// against the seed (or the seed itself, without an estimate, when the check found none
    /// either).
    pub unsteady: Option<TiRow>,
    /// Estimated error of the reference on every physical dof (`None` without a steady check).
    pub all: Option<RelativeErrors>,
    /// Estimated error of the reference on the contact dofs.
    pub contact: Option<RelativeErrors>,
}

impl ReferenceEstimate {
    /// The distinct runs the reference took: seed, check, reference and the unsteady run at
    /// the asked tolerance (each once, by tolerance).
    fn runs<'a>(&'a self, reference: &'a TiRow) -> Vec<&'a TiRow> {
        let mut out: Vec<&TiRow> = Vec::new();
        let candidates = [Some(&self.seed), Some(&self.check), Some(reference)];
        for r in candidates
            .into_iter()
            .chain([self.unsteady.as_ref()])
            .flatten()
        {
            if out.iter().all(|o| o.rtol != r.rtol) {
                out.push(r);
            }
        }
        out
    }

    /// Wall time of all the runs the reference took.
    pub fn wall(&self, reference: &TiRow) -> Duration {
        self.runs(reference).iter().map(|r| r.run.wall).sum()
    }

    /// Accepted steps of all the runs the reference took.
    pub fn steps(&self, reference: &TiRow) -> usize {
        self.runs(reference).iter().map(|r| r.run.stats.steps).sum()
    }
}

fn scaled(e: &RelativeErrors, s: f64) -> RelativeErrors {
    RelativeErrors {
        displacement: e.displacement * s,
        velocity: e.velocity * s,
        frequency_hz: e.frequency_hz * s,
        frequency_relative: e.frequency_relative * s,
    }
}

/// A full comparison at one friction level.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// Friction coefficient of the modal brake.
    pub mu: f64,
    /// The reference integration at [`CompareOptions::reference_rtol`] (continued from the
    /// check run's end), measured against itself.
    pub reference: TiRow,
    /// The runs before the reference and its estimated own error.
    pub estimate: ReferenceEstimate,
    /// The integrations at each of [`CompareOptions::rtols`], in that order.
    pub ti: Vec<TiRow>,
    /// The CHBM solves with each of [`CompareOptions::harmonics`], in that order.
    pub chbm: Vec<ChbmRow>,
    /// Physical dof of the phase alignment.
    pub phase_dof: usize,
    /// Total power of the reference's oscillation, `P_temporal` of eq (50).
    pub power_reference: f64,
}

/// Fraction of `samples` phases of the cycle where each pair is open, by counting (the
/// measures use the roots of [`crate::physics::open_fractions`] instead; this is its check).
pub fn open_fraction(
    mb: &ModalBrake,
    c: &Cycle,
    samples: usize,
) -> Result<Vec<f64>, squeal_hbm::HbmError> {
    let nl = c.restrict(&mb.nl_dofs)?;
    let samples = samples.max(1);
    let mut open = vec![0usize; mb.pairs.len()];
    let mut xn = vec![0.0; mb.nl()];
    for s in 0..samples {
        let th = 2.0 * PI * s as f64 / samples as f64;
        for (i, x) in xn.iter_mut().enumerate() {
            *x = nl.value_at(i, th, false);
        }
        for (o, p) in open.iter_mut().zip(&mb.pairs) {
            if p.penetration(&xn) <= 0.0 {
                *o += 1;
            }
        }
    }
    Ok(open.iter().map(|&o| o as f64 / samples as f64).collect())
}

fn measures(
    mb: &ModalBrake,
    c: &Cycle,
    reference: &Cycle,
    disc: Option<&DiscSpeed>,
) -> Result<Measures, CompareError> {
    let all: Vec<usize> = (0..c.n_dofs()).collect();
    Ok(Measures {
        sliding: disc.map(|d| sliding_margin(mb, c, d)).transpose()?,
        all: relative_errors(c, reference, &all),
        contact: relative_errors(c, reference, &mb.nl_dofs),
        power: harmonic_power(c, &all),
        energy: energy_balance(mb, c, 1024)?,
        open_fraction: crate::physics::open_fractions(mb, c)?,
    })
}

fn ti_row(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &TiOptions,
    rtol: f64,
) -> Result<TiRow, CompareError> {
    let o = TiOptions {
        rtol,
        ..opts.clone()
    };
    let run = integrate_to_limit_cycle(mb, start.lambda, &start.mode, &start.equilibrium, &o)?;
    Ok(TiRow {
        rtol,
        run,
        cycle: None,
        measures: None,
    })
}

fn steady_cycle(run: &TiRun) -> Result<Cycle, CompareError> {
    match (&run.steady, &run.failure) {
        (Some(s), _) => Ok(s.cycle.clone()),
        (None, f) => Err(CompareError::NoReference(
            f.as_ref()
                .map_or("no reason given".into(), |e| e.to_string()),
        )),
    }
}

/// The options of a run continued on a steady cycle at `rtol`.
fn continued(opts: &CompareOptions, rtol: f64) -> TiOptions {
    TiOptions {
        rtol,
        drift_tol: opts.reference_drift_tol,
        max_cycles: opts.reference_max_cycles,
        ..opts.ti.clone()
    }
}

/// CHBM with each number of harmonics and the time integrations at each tolerance, all
/// measured against the reference integration, at the friction of `mb`. The reference is
/// reached in three runs ([`ReferenceEstimate`]): the seed from the perturbed equilibrium at
/// [`CompareOptions::seed_rtol`], the check at `check_factor · reference_rtol` from the seed's
/// end, the reference at [`CompareOptions::reference_rtol`] from the check's end.
pub fn compare_at(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &CompareOptions,
) -> Result<Comparison, CompareError> {
    compare_at_with(mb, start, opts, &mut |_| {})
}

/// One run of a comparison, announced by [`compare_at_with`] as it starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CompareStep {
    /// The reference's seed: BDF from the perturbed equilibrium at this tolerance.
    Seed(f64),
    /// The check run continued from the seed's steady cycle at this tolerance.
    Check(f64),
    /// The reference run continued from the check's steady cycle at this tolerance.
    Reference(f64),
    /// A BDF run from the perturbed equilibrium at this tolerance (Table 1).
    Integration(f64),
    /// A CHBM solve with this many harmonics.
    Chbm(usize),
}

impl std::fmt::Display for CompareStep {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Seed(r) => write!(f, "reference seed, BDF rtol {r:e}"),
            Self::Check(r) => write!(f, "reference check, BDF rtol {r:e}"),
            Self::Reference(r) => write!(f, "reference, BDF rtol {r:e}"),
            Self::Integration(r) => write!(f, "BDF rtol {r:e}"),
            Self::Chbm(h) => write!(f, "CHBM, {h} harmonics"),
        }
    }
}

impl CompareOptions {
    /// The runs [`compare_at_with`] announces, in order.
    pub fn steps(&self) -> Vec<CompareStep> {
        let mut steps = vec![
            CompareStep::Seed(self.seed_rtol),
            CompareStep::Check(self.check_factor * self.reference_rtol),
            CompareStep::Reference(self.reference_rtol),
        ];
        // A tolerance equal to the seed's reuses the seed's run.
        let rtols = self.rtols.iter().filter(|&&r| r != self.seed_rtol);
        steps.extend(rtols.map(|&r| CompareStep::Integration(r)));
        steps.extend(self.harmonics.iter().map(|&h| CompareStep::Chbm(h)));
        steps
    }
}

/// [`compare_at`], telling `step` each run (of [`CompareOptions::steps`]) as it starts: for a
/// progress display over runs that take up to minutes each.
pub fn compare_at_with(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &CompareOptions,
    step: &mut dyn FnMut(CompareStep),
) -> Result<Comparison, CompareError> {
    step(CompareStep::Seed(opts.seed_rtol));
    let seed = ti_row(mb, start, &opts.ti, opts.seed_rtol)?;
    steady_cycle(&seed.run)?;
    let check_rtol = opts.check_factor * opts.reference_rtol;
    step(CompareStep::Check(check_rtol));
    let check_run = integrate_from(mb, &seed.run.continuation(), &continued(opts, check_rtol))?;
    let from = if check_run.steady.is_some() {
        check_run.continuation()
    } else {
        seed.run.continuation()
    };
    step(CompareStep::Reference(opts.reference_rtol));
    let ref_run = integrate_from(mb, &from, &continued(opts, opts.reference_rtol))?;
    let row = |rtol: f64, run: TiRun| TiRow {
        rtol,
        run,
        cycle: None,
        measures: None,
    };
    // The reference is the tightest run with a steady cycle, checked against the next looser
    // one; a tight run that found none is kept to be reported.
    let (mut reference, check, unsteady) = if ref_run.steady.is_some() {
        (
            row(opts.reference_rtol, ref_run),
            row(check_rtol, check_run),
            None,
        )
    } else if check_run.steady.is_some() {
        (
            row(check_rtol, check_run),
            seed.clone(),
            Some(row(opts.reference_rtol, ref_run)),
        )
    } else {
        (
            seed.clone(),
            row(check_rtol, check_run),
            Some(row(opts.reference_rtol, ref_run)),
        )
    };
    let ref_cycle = steady_cycle(&reference.run)?;
    let phase_dof = ref_cycle.strongest_dof(&mb.nl_dofs).unwrap_or(0);
    reference.measures = Some(measures(mb, &ref_cycle, &ref_cycle, opts.disc.as_ref())?);
    reference.cycle = Some(ref_cycle.clone());
    let all: Vec<usize> = (0..mb.modes()).collect();
    let power_reference: f64 = harmonic_power(&ref_cycle, &all).iter().sum();
    let mut check = check;
    if check.rtol == reference.rtol {
        // Both the check and the reference are the seed: nothing to estimate from.
        check.run.steady = None;
    }
    if let Some(s) = &check.run.steady {
        let mut c = s.cycle.clone();
        c.align_to(&ref_cycle, phase_dof);
        check.measures = Some(measures(mb, &c, &ref_cycle, opts.disc.as_ref())?);
        check.cycle = Some(c);
    }
    let scale = 1.0 / ((check.rtol / reference.rtol).powf(2.0 / 3.0) - 1.0);
    let estimate = ReferenceEstimate {
        unsteady,
        all: check.measures.as_ref().map(|m| scaled(&m.all, scale)),
        contact: check.measures.as_ref().map(|m| scaled(&m.contact, scale)),
        seed,
        check,
        scale,
    };
    let mut ti = Vec::new();
    for &rtol in &opts.rtols {
        // The seed is the same run as one from the equilibrium at its tolerance.
        let mut row = if rtol == opts.seed_rtol {
            TiRow {
                rtol,
                run: estimate.seed.run.clone(),
                cycle: None,
                measures: None,
            }
        } else {
            step(CompareStep::Integration(rtol));
            ti_row(mb, start, &opts.ti, rtol)?
        };
        if let Some(s) = &row.run.steady {
            let mut c = s.cycle.clone();
            c.align_to(&ref_cycle, phase_dof);
            row.measures = Some(measures(mb, &c, &ref_cycle, opts.disc.as_ref())?);
            row.cycle = Some(c);
        }
        ti.push(row);
    }
    let mut chbm = Vec::new();
    for &h in &opts.harmonics {
        step(CompareStep::Chbm(h));
        let o = ChbmOptions {
            harmonics: h,
            ..opts.chbm.clone()
        };
        let (solution, amplitude, wall, iterations) =
            solve_with_restarts(mb, start, &o, &opts.amplitudes).map_err(|source| {
                CompareError::Chbm {
                    harmonics: h,
                    source,
                }
            })?;
        let mut cycle = solution.cycle()?;
        cycle.align_to(&ref_cycle, phase_dof);
        let m = measures(mb, &cycle, &ref_cycle, opts.disc.as_ref())?;
        chbm.push(ChbmRow {
            harmonics: h,
            amplitude,
            solution,
            cycle,
            measures: m,
            wall,
            iterations,
        });
    }
    Ok(Comparison {
        mu: mb.mu,
        reference,
        estimate,
        ti,
        chbm,
        phase_dof,
        power_reference,
    })
}

/// What a CHBM solve of the robustness grid ended on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CellOutcome {
    /// A limit cycle ([`Outcome::LimitCycle`]).
    LimitCycle,
    /// Harmonic balance converged, `|Re λ|` above `eps2`.
    Unconstrained,
    /// The static solution ([`Outcome::Static`]).
    Static,
    /// No convergence ([`Outcome::NotConverged`]).
    NotConverged,
    /// The solve stopped with an error (e.g. the eigenvalue could not be followed).
    Failed,
}

impl CellOutcome {
    /// A short label for tables: [`Outcome::label`]'s, or `failed`.
    pub fn label(self) -> &'static str {
        match self {
            CellOutcome::LimitCycle => Outcome::LimitCycle.label(),
            CellOutcome::Unconstrained => Outcome::LimitCycleUnconstrained.label(),
            CellOutcome::Static => Outcome::Static.label(),
            CellOutcome::NotConverged => Outcome::NotConverged.label(),
            CellOutcome::Failed => "failed",
        }
    }
}

/// One CHBM solve of the grid.
#[derive(Clone, Debug)]
pub struct GridCell {
    /// Friction level as a ratio μ/μ0.
    pub mu_ratio: f64,
    /// Initial amplitude `p` of eq (48).
    pub amplitude: f64,
    /// Harmonics of the solve.
    pub harmonics: usize,
    /// What the solve ended on.
    pub outcome: CellOutcome,
    /// Levenberg–Marquardt trial steps (0 when the solve failed).
    pub iterations: usize,
    /// Wall time of the solve.
    pub time: Duration,
    /// Frequency `ω / 2π` (Hz) where the solve ended, converged or not; NaN when it failed.
    pub frequency_hz: f64,
    /// Largest fraction of the cycle any pair is open (0 when not a limit cycle).
    pub open_fraction: f64,
    /// Why the solve failed (for [`CellOutcome::Failed`]).
    pub error: Option<String>,
}

/// One time integration of the grid.
#[derive(Clone, Debug)]
pub struct TiCell {
    /// Friction level as a ratio μ/μ0.
    pub mu_ratio: f64,
    /// The integration; `None` when there is no start at this μ or it could not start.
    pub run: Option<TiRun>,
    /// Why there is no run or no steady cycle.
    pub failure: Option<String>,
    /// Largest fraction of the steady cycle any pair is open; NaN without a steady cycle.
    pub open_fraction: f64,
}

/// Options of [`robustness`].
#[derive(Clone, Debug, PartialEq)]
pub struct GridOptions {
    /// Friction levels as ratios μ/μ0.
    pub mu_ratios: Vec<f64>,
    /// Initial amplitudes `p` of eq (48), each solved alone (no restarts).
    pub amplitudes: Vec<f64>,
    /// Harmonics of the CHBM solves.
    pub harmonics: Vec<usize>,
    /// Base CHBM options (the harmonics and amplitude are set per cell).
    pub chbm: ChbmOptions,
    /// Options of the time integrations.
    pub ti: TiOptions,
    /// Run the time integration at each μ.
    pub with_ti: bool,
}

impl Default for GridOptions {
    fn default() -> Self {
        Self {
            mu_ratios: vec![1.01, 1.02, 1.05, 1.1, 1.2, 1.4, 1.7, 2.0],
            amplitudes: vec![0.1, 0.3, 0.5, 1.0, 2.0, 4.0],
            harmonics: vec![1, 2, 3, 5, 10],
            chbm: ChbmOptions::default(),
            ti: TiOptions {
                max_cycles: 2000.0,
                ..TiOptions::default()
            },
            with_ti: true,
        }
    }
}

/// The brake and where its analyses start, for [`robustness`].
pub struct GridModel<'a> {
    /// The reduced brake.
    pub brake: &'a Brake,
    /// Its frictionless reference (modes and damping).
    pub reference: &'a Reference,
    /// The Hopf point μ0 that [`GridOptions::mu_ratios`] multiply.
    pub mu0: f64,
    /// The band in which the unstable mode of each start is sought.
    pub band: Band,
    /// Controls of the static equilibria.
    pub newton: NewtonOptions,
}

fn grid_cell(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &ChbmOptions,
    (mu_ratio, amplitude, harmonics): (f64, f64, usize),
) -> GridCell {
    let o = ChbmOptions {
        harmonics,
        amplitude,
        ..opts.clone()
    };
    let t0 = Instant::now();
    let mut cell = GridCell {
        mu_ratio,
        amplitude,
        harmonics,
        outcome: CellOutcome::Failed,
        iterations: 0,
        time: Duration::ZERO,
        frequency_hz: f64::NAN,
        open_fraction: 0.0,
        error: None,
    };
    match solve(mb, start, &o) {
        Ok(s) => {
            cell.outcome = match s.outcome {
                Outcome::LimitCycle => CellOutcome::LimitCycle,
                Outcome::LimitCycleUnconstrained => CellOutcome::Unconstrained,
                Outcome::Static => CellOutcome::Static,
                Outcome::NotConverged => CellOutcome::NotConverged,
            };
            cell.iterations = s.iterations;
            cell.frequency_hz = s.omega / (2.0 * PI);
            if cell.outcome == CellOutcome::LimitCycle {
                cell.open_fraction = s.open_fraction.iter().copied().fold(0.0, f64::max);
            }
        }
        Err(e) => cell.error = Some(e.to_string()),
    }
    cell.time = t0.elapsed();
    cell
}

/// CHBM over `μ/μ0 × p × H`, and the time integration at each μ (issue #6, item 7). A μ where
/// the brake has no start (stable, or no equilibrium) gives `Failed` cells and says why in
/// its [`TiCell`]. `progress` is called after each μ.
pub fn robustness(
    model: &GridModel<'_>,
    opts: &GridOptions,
    progress: &mut dyn FnMut(f64),
) -> (Vec<GridCell>, Vec<TiCell>) {
    let mut cells = Vec::new();
    let mut ti = Vec::new();
    for &r in &opts.mu_ratios {
        let mu = r * model.mu0;
        let start = start_at(
            model.brake,
            model.reference,
            mu,
            &model.band,
            &model.newton,
            None,
        );
        let start = match start {
            Ok(s) => s,
            Err(e) => {
                for &a in &opts.amplitudes {
                    for &h in &opts.harmonics {
                        cells.push(GridCell {
                            mu_ratio: r,
                            amplitude: a,
                            harmonics: h,
                            outcome: CellOutcome::Failed,
                            iterations: 0,
                            time: Duration::ZERO,
                            frequency_hz: f64::NAN,
                            open_fraction: 0.0,
                            error: Some(e.to_string()),
                        });
                    }
                }
                ti.push(TiCell {
                    mu_ratio: r,
                    run: None,
                    failure: Some(e.to_string()),
                    open_fraction: f64::NAN,
                });
                progress(r);
                continue;
            }
        };
        let mb = ModalBrake::new(model.brake, model.reference, mu);
        for &a in &opts.amplitudes {
            for &h in &opts.harmonics {
                cells.push(grid_cell(&mb, &start, &opts.chbm, (r, a, h)));
            }
        }
        if opts.with_ti {
            let cell = match integrate_to_limit_cycle(
                &mb,
                start.lambda,
                &start.mode,
                &start.equilibrium,
                &opts.ti,
            ) {
                Ok(run) => {
                    let open = run.steady.as_ref().map_or(f64::NAN, |s| {
                        crate::physics::open_fractions(&mb, &s.cycle)
                            .map_or(f64::NAN, |o| o.into_iter().fold(0.0, f64::max))
                    });
                    TiCell {
                        mu_ratio: r,
                        failure: run.failure.as_ref().map(|e| e.to_string()),
                        run: Some(run),
                        open_fraction: open,
                    }
                }
                Err(e) => TiCell {
                    mu_ratio: r,
                    run: None,
                    failure: Some(e.to_string()),
                    open_fraction: f64::NAN,
                },
            };
            ti.push(cell);
        }
        progress(r);
    }
    (cells, ti)
}
