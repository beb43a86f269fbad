//! Issue #6, items 6–7: CHBM against the time integration of [`crate::timeint`] at one
//! friction level (the paper's Tables 1–2 and Figures 4–5), and where each method fails over a
//! grid of friction levels and initial amplitudes.
//!
//! Everything here is computation returning plain data; the `squeal compare` command turns it
//! into tables and figures. Error measures are those of [`crate::cycle`]: phase-aligned on the
//! reference's most moving contact dof, relative RMS over the cycle, on all physical dofs and
//! on the nonlinear (contact) dofs.
//!
//! **The reference** (issue #22) is the periodic orbit of the reduced brake by shooting
//! ([`crate::shooting`]), started from the CHBM cycle with the most harmonics (or, when no
//! CHBM solve converged, from the steady cycle of the tightest time integration that settled),
//! with its own error stated. The time integrations from the perturbed equilibrium to the
//! steady cycle at the user's tolerances ([`CompareOptions::rtols`]) are the cost side of the
//! paper's comparison; each is judged against the reference, and one that found no steady
//! cycle is reported as failed, with no measures.

use crate::cycle::{
    Cycle, EnergyBalance, RelativeErrors, energy_balance, harmonic_power, relative_errors,
};
use crate::physics::{DiscSpeed, SlidingMargin, sliding_margin};
use crate::shooting::{
    ShootingReference, ShootingReferenceError, ShootingReferenceOptions, shooting_reference,
};
use crate::solve::{
    ChbmError, ChbmOptions, ChbmSolution, ChbmStart, Outcome, RESTART_AMPLITUDES, solve,
    solve_with_restarts,
};
use crate::start::start_at;
use crate::timeint::{TiError, TiOptions, TiRun, integrate_to_limit_cycle};
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
    /// No cycle to start the reference from: no CHBM solve converged to a limit cycle and no
    /// time integration settled.
    #[error(
        "no start for the reference: no CHBM solve gave a limit cycle and no time integration reached a steady cycle"
    )]
    NoStart,
    /// The shooting reference failed.
    #[error("the reference limit cycle: {0}")]
    Reference(#[from] ShootingReferenceError),
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
#[non_exhaustive]
pub struct CompareOptions {
    /// Harmonics of the CHBM solves (Table 1's columns).
    pub harmonics: Vec<usize>,
    /// Base CHBM options (the harmonics and amplitude are set per solve).
    pub chbm: ChbmOptions,
    /// Initial amplitudes `p` tried in turn until a limit cycle converges.
    pub amplitudes: Vec<f64>,
    /// Base time-integration options (`rtol` set per run).
    pub ti: TiOptions,
    /// Tolerances of the time integrations from the perturbed equilibrium (the cost side).
    pub rtols: Vec<f64>,
    /// The shooting reference every error is measured against.
    pub reference: ShootingReferenceOptions,
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
            rtols: vec![1e-5, 1e-6, 1e-7],
            reference: ShootingReferenceOptions::default(),
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
    /// Its measures against the reference (`None` if no steady cycle: a failed run).
    pub measures: Option<Measures>,
}

/// Where the shooting reference started.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ReferenceStart {
    /// From the CHBM cycle with this many harmonics.
    Chbm(usize),
    /// From the steady cycle of the time integration at this tolerance.
    Integration(f64),
}

impl std::fmt::Display for ReferenceStart {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Chbm(h) => write!(f, "the CHBM cycle with {h} harmonics"),
            Self::Integration(r) => write!(f, "the steady cycle of BDF rtol {r:e}"),
        }
    }
}

/// A full comparison at one friction level.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// Friction coefficient of the modal brake.
    pub mu: f64,
    /// The shooting reference and its stated own error.
    pub reference: ShootingReference,
    /// Where the reference's Newton iteration started.
    pub reference_start: ReferenceStart,
    /// The reference cycle's own measures (errors zero; power, energy, open fractions,
    /// sliding margin).
    pub reference_measures: Measures,
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

/// CHBM with each number of harmonics and the time integrations at each tolerance, all
/// measured against the shooting reference, at the friction of `mb` (module docs).
pub fn compare_at(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &CompareOptions,
) -> Result<Comparison, CompareError> {
    compare_at_with(mb, start, opts, &|_| {})
}

/// One run of a comparison, announced by [`compare_at_with`] as it starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CompareStep {
    /// A CHBM solve with this many harmonics.
    Chbm(usize),
    /// A BDF run from the perturbed equilibrium at this tolerance.
    Integration(f64),
    /// The shooting reference at this tolerance (and its check).
    Reference(f64),
}

impl std::fmt::Display for CompareStep {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Chbm(h) => write!(f, "CHBM, {h} harmonics"),
            Self::Integration(r) => write!(f, "BDF rtol {r:e}"),
            Self::Reference(r) => write!(f, "reference by shooting, BDF rtol {r:e}"),
        }
    }
}

impl CompareOptions {
    /// The runs [`compare_at_with`] announces, each once (in this order when they run one
    /// after the other; with several threads the integrations start beside the CHBM solves).
    pub fn steps(&self) -> Vec<CompareStep> {
        let mut steps: Vec<CompareStep> = self
            .harmonics
            .iter()
            .map(|&h| CompareStep::Chbm(h))
            .collect();
        steps.extend(self.rtols.iter().map(|&r| CompareStep::Integration(r)));
        steps.push(CompareStep::Reference(self.reference.rtol));
        steps
    }
}

/// One CHBM solve before it is measured: harmonics, solution, the amplitude that converged,
/// wall time and trial steps of all the attempts.
type Solve = (usize, ChbmSolution, f64, Duration, usize);

/// The CHBM solves, unaligned.
fn chbm_solves(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &CompareOptions,
    step: &(dyn Fn(CompareStep) + Sync),
) -> Result<Vec<Solve>, CompareError> {
    let mut out = Vec::new();
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
        out.push((h, solution, amplitude, wall, iterations));
    }
    Ok(out)
}

/// The CHBM solve the reference starts from: the limit cycle with the most harmonics.
fn best_chbm(chbm: &[Solve]) -> Option<&Solve> {
    chbm.iter()
        .filter(|c| c.1.outcome == Outcome::LimitCycle)
        .max_by_key(|c| c.0)
}

/// The reference's start when no CHBM solve gave a limit cycle: the steady cycle of the
/// tightest integration that settled.
fn integration_start(ti: &[TiRow]) -> Result<(Cycle, ReferenceStart), CompareError> {
    let tightest = ti
        .iter()
        .filter(|r| r.run.steady.is_some())
        .min_by(|a, b| a.rtol.total_cmp(&b.rtol));
    match tightest.and_then(|r| r.run.steady.as_ref().map(|s| (r.rtol, s))) {
        Some((rtol, s)) => Ok((s.cycle.clone(), ReferenceStart::Integration(rtol))),
        None => Err(CompareError::NoStart),
    }
}

/// The shooting reference from `from`, phase-fixed on its most moving contact dof.
fn reference_from(
    mb: &ModalBrake,
    from: &Cycle,
    opts: &CompareOptions,
    step: &(dyn Fn(CompareStep) + Sync),
) -> Result<(ShootingReference, usize), CompareError> {
    step(CompareStep::Reference(opts.reference.rtol));
    let phase_dof = from.strongest_dof(&mb.nl_dofs).unwrap_or(0);
    Ok((
        shooting_reference(mb, from, phase_dof, &opts.reference)?,
        phase_dof,
    ))
}

/// The CHBM solves, then the reference from the one with the most harmonics (`None` when no
/// solve gave a limit cycle: the reference then waits for the integrations).
type Chain = (
    Vec<Solve>,
    Option<(ShootingReference, usize, ReferenceStart)>,
);

fn chbm_then_reference(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &CompareOptions,
    step: &(dyn Fn(CompareStep) + Sync),
) -> Result<Chain, CompareError> {
    let solves = chbm_solves(mb, start, opts, step)?;
    let reference = match best_chbm(&solves) {
        Some((h, s, ..)) => {
            let (r, phase_dof) = reference_from(mb, &s.cycle()?, opts, step)?;
            Some((r, phase_dof, ReferenceStart::Chbm(*h)))
        }
        None => None,
    };
    Ok((solves, reference))
}

/// [`compare_at`], telling `step` each run (of [`CompareOptions::steps`]) as it starts: for a
/// progress display over runs that take up to minutes each.
pub fn compare_at_with(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &CompareOptions,
    step: &(dyn Fn(CompareStep) + Sync),
) -> Result<Comparison, CompareError> {
    let mut out = compare_levels(&[(mb, start)], opts, &|_, s| step(s))?;
    out.pop().ok_or(CompareError::NoStart)
}

/// The result of one run of [`compare_levels`].
enum Run {
    Chain(Result<Chain, CompareError>),
    /// The integration at `opts.rtols[k]`.
    Ti(usize, Result<TiRow, CompareError>),
}

/// The comparisons at several friction levels (`levels[i]`: its modal brake and CHBM start),
/// telling `step(i, run)` each run as it starts.
///
/// The runs are independent but for the reference, which starts from the CHBM solves (or,
/// without a CHBM limit cycle, from the integrations): each level's CHBM solves and reference
/// are one run, each time integration another, and they go side by side, each alone on one
/// thread ([`crate::alone`]), the CHBM-and-reference runs first (the longest), then the
/// integrations from the tightest tolerance. So `step` may be called from several threads
/// and in another order than [`CompareOptions::steps`]; the results are the same bits for
/// any number of threads, and every wall time is the run's own one-thread cost.
pub fn compare_levels(
    levels: &[(&ModalBrake, &ChbmStart)],
    opts: &CompareOptions,
    step: &(dyn Fn(usize, CompareStep) + Sync),
) -> Result<Vec<Comparison>, CompareError> {
    use crate::alone::{Job, run_alone};
    let mut rtols: Vec<(usize, f64)> = opts.rtols.iter().copied().enumerate().collect();
    rtols.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut jobs: Vec<Job<'_, (usize, Run)>> = Vec::new();
    for (i, &(mb, start)) in levels.iter().enumerate() {
        jobs.push(Box::new(move || {
            let step = |s| step(i, s);
            (i, Run::Chain(chbm_then_reference(mb, start, opts, &step)))
        }));
    }
    for &(k, rtol) in &rtols {
        for (i, &(mb, start)) in levels.iter().enumerate() {
            jobs.push(Box::new(move || {
                step(i, CompareStep::Integration(rtol));
                (i, Run::Ti(k, ti_row(mb, start, &opts.ti, rtol)))
            }));
        }
    }
    let mut chains: Vec<Option<Chain>> = (0..levels.len()).map(|_| None).collect();
    // Each level's integrations in the order of `opts.rtols`, as the tables list them.
    let mut ti: Vec<Vec<Option<TiRow>>> = (0..levels.len())
        .map(|_| (0..opts.rtols.len()).map(|_| None).collect())
        .collect();
    for (i, run) in run_alone(jobs) {
        match run {
            Run::Chain(c) => chains[i] = Some(c?),
            Run::Ti(k, r) => ti[i][k] = Some(r?),
        }
    }
    let mut out = Vec::with_capacity(levels.len());
    for (i, (chain, ti)) in chains.into_iter().zip(ti).enumerate() {
        let ti = ti.into_iter().flatten().collect();
        let (solves, reference) = chain.ok_or(CompareError::NoStart)?;
        let (mb, _) = levels[i];
        out.push(measured(mb, opts, solves, reference, ti, &|s| step(i, s))?);
    }
    Ok(out)
}

/// One level's comparison from its runs: the reference (from the integrations if no CHBM
/// solve gave it), and every cycle aligned on it and measured.
fn measured(
    mb: &ModalBrake,
    opts: &CompareOptions,
    solves: Vec<Solve>,
    reference: Option<(ShootingReference, usize, ReferenceStart)>,
    mut ti: Vec<TiRow>,
    step: &(dyn Fn(CompareStep) + Sync),
) -> Result<Comparison, CompareError> {
    let (reference, phase_dof, reference_start) = match reference {
        Some(r) => r,
        None => {
            let (from, reference_start) = integration_start(&ti)?;
            let (r, phase_dof) = reference_from(mb, &from, opts, step)?;
            (r, phase_dof, reference_start)
        }
    };
    let ref_cycle = &reference.reference.cycle;
    let disc = opts.disc.as_ref();
    let reference_measures = measures(mb, ref_cycle, ref_cycle, disc)?;
    let all: Vec<usize> = (0..mb.modes()).collect();
    let power_reference: f64 = harmonic_power(ref_cycle, &all).iter().sum();
    for row in &mut ti {
        if let Some(s) = &row.run.steady {
            let mut c = s.cycle.clone();
            c.align_to(ref_cycle, phase_dof);
            row.measures = Some(measures(mb, &c, ref_cycle, disc)?);
            row.cycle = Some(c);
        }
    }
    let mut chbm = Vec::new();
    for (harmonics, solution, amplitude, wall, iterations) in solves {
        let mut cycle = solution.cycle()?;
        cycle.align_to(ref_cycle, phase_dof);
        let measures = measures(mb, &cycle, ref_cycle, disc)?;
        chbm.push(ChbmRow {
            harmonics,
            amplitude,
            solution,
            cycle,
            measures,
            wall,
            iterations,
        });
    }
    Ok(Comparison {
        mu: mb.mu,
        reference,
        reference_start,
        reference_measures,
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
#[non_exhaustive]
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
