//! The reference of issue #6 (item 5): time integration of the full nonlinear brake (every
//! mode of [`ModalBrake`], eq 11 as [`BrakeDynamics`]) from the static equilibrium perturbed
//! along the unstable mode until the steady limit cycle, with the variable-step BDF of
//! [`squeal_ode`] (the paper's "variable order solver").
//!
//! **Start.** `x = x_eq + ε Re ψ`, `x' = ε Re(λ ψ)`: the real solution `ε Re(ψ e^{λt})` of the
//! linearization at `t = 0`, with `ε` such that the contact pair moving most has a normal
//! amplitude of [`TiOptions::perturbation`] times the smallest static penetration (the same
//! `p` as the CHBM guess of eq 48).
//!
//! **Tolerances.** The error test is `rms(err_i / (atol_i + rtol |y_i|)) <= 1`. Modal
//! coordinates are mass-normalized, so a unit of any `q_j` is worth the same in physical
//! displacement: one absolute tolerance `atol_q = atol_factor · rtol · Q` for every `q_j`, with
//! `Q` the largest modal coordinate of the unstable mode scaled to move the contact by its
//! static penetration (the size of the oscillation to resolve), and `atol_v = ω₀ atol_q` for
//! the velocities, which are `ω` times larger.
//!
//! **Steady state.** Cycles are delimited by the upward zero crossings of the penetration rate
//! of the pair that moves most (its mean is exactly zero on a periodic orbit). A first
//! detection needs the periods and peak-to-peaks (max - min) of the last
//! [`TiOptions::steady_cycles`] cycles to agree within [`TiOptions::steady_rtol`]; single-cycle
//! measures carry the integrator's noise (about `30 rtol` relative at order 2), so this
//! tolerance cannot be tight. From then on the Fourier coefficients of every state are averaged
//! over blocks of [`TiOptions::confirm_cycles`] periods (sampled at the window's mean period),
//! and two consecutive blocks are compared (phase-aligned relative RMS difference of every dof,
//! [`crate::cycle::relative_errors`]): near the Hopf point the approach to the limit cycle is
//! slow and the amplitude still creeps when the spread test first passes, so the integration
//! goes on, block after block, until that drift is below [`TiOptions::drift_tol`]. Only the
//! running block's sums and one record per cycle are kept, never the history.

use crate::cycle::{Cycle, relative_errors};
use faer::c64;
use squeal_brake::dynamics::BrakeDynamics;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::{FourierSums, HarmonicLayout, HbmError, Periodic};
use squeal_ode::{
    Atol, Bdf, BdfOptions, BdfStats, CycleRecord, OdeError, OscillationMonitor, SteadyOptions,
};
use std::f64::consts::PI;
use std::time::{Duration, Instant};

/// Options of [`integrate_to_limit_cycle`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct TiOptions {
    /// Relative tolerance of the BDF error test.
    pub rtol: f64,
    /// `atol_q = atol_factor · rtol · Q` (module docs).
    pub atol_factor: f64,
    /// Highest BDF order (2: A-stable; orders 3–5 fight the lightly damped high modes).
    pub max_order: usize,
    /// Initial normal amplitude of the most moving pair, as a fraction of the smallest static
    /// penetration.
    pub perturbation: f64,
    /// Relative spread of periods and amplitudes over `steady_cycles` cycles.
    pub steady_rtol: f64,
    /// Consecutive cycles whose periods and amplitudes must agree for a first detection.
    pub steady_cycles: usize,
    /// Cycles of each Fourier average taken once steady; two consecutive averages are compared.
    pub confirm_cycles: usize,
    /// Largest accepted relative change between two consecutive averages.
    pub drift_tol: f64,
    /// Harmonics kept in the Fourier averages of the cycle.
    pub harmonics: usize,
    /// Samples per period of the Fourier averages (more than `2 harmonics`).
    pub samples_per_cycle: usize,
    /// Give up after this many periods of the unstable mode.
    pub max_cycles: f64,
    /// Give up after this many accepted steps.
    pub max_steps: usize,
}

impl Default for TiOptions {
    fn default() -> Self {
        Self {
            rtol: 1e-6,
            atol_factor: 1.0,
            max_order: 2,
            perturbation: 0.5,
            steady_rtol: 1e-4,
            steady_cycles: 10,
            confirm_cycles: 20,
            drift_tol: 1e-4,
            harmonics: 10,
            samples_per_cycle: 128,
            max_cycles: 5000.0,
            max_steps: 20_000_000,
        }
    }
}

/// The steady cycle found.
#[derive(Clone, Debug)]
pub struct TiSteady {
    /// Fourier coefficients of every physical dof averaged over the last
    /// [`TiOptions::confirm_cycles`] periods (velocities from the integrated velocities, not
    /// by differentiation).
    pub cycle: Cycle,
    /// Its period (s).
    pub period: f64,
    /// Cycles completed when accepted, and the time then.
    pub cycles: usize,
    /// Time (s) when accepted.
    pub t: f64,
    /// Relative change of the cycle over the last `confirm_cycles` cycles.
    pub drift: f64,
    /// Detections needed until the drift was small enough.
    pub detections: usize,
}

/// One time integration: the steady cycle or why there is none, with the integrator's
/// counters and one record per cycle.
#[derive(Clone, Debug)]
pub struct TiRun {
    /// The steady cycle, `None` when not reached.
    pub steady: Option<TiSteady>,
    /// Why not: the integrator's error, or [`OdeError::NotSteady`] at the limits.
    pub failure: Option<OdeError>,
    /// The integrator's counters (steps, rejections, ...).
    pub stats: BdfStats,
    /// Wall time of the run.
    pub wall: Duration,
    /// Every completed cycle of the observable (start, period, extrema).
    pub history: Vec<CycleRecord>,
    /// Time reached (s).
    pub t_end: f64,
    /// State dimension (for the storage a full history would take).
    pub dim: usize,
    /// Initial amplitude factor ε of the unstable mode.
    pub epsilon: f64,
    /// `(time, drift)` of every comparison of two consecutive Fourier averages.
    pub drifts: Vec<(f64, f64)>,
    /// The state where the run ended, with the scales of its start (see
    /// [`TiRun::continuation`]).
    end: TiStart,
}

impl TiRun {
    /// A start at the state where this run ended, with the same tolerance and monitor scales
    /// (for [`integrate_from`]): a tighter integration then begins on this run's cycle.
    pub fn continuation(&self) -> TiStart {
        self.end.clone()
    }

    /// Bytes a stored history of every accepted step would take (`steps × dim` doubles plus
    /// the times), as the paper's Table 2 counts for the temporal integration.
    pub fn history_bytes(&self) -> usize {
        self.stats
            .steps
            .saturating_mul(self.dim + 1)
            .saturating_mul(8)
    }
}

/// Why the integration could not start.
#[derive(Debug, thiserror::Error)]
pub enum TiError {
    /// The integrator or the steady-state monitor could not be set up (invalid options, a
    /// non-finite start, ...).
    #[error(transparent)]
    Ode(#[from] OdeError),
    /// The Fourier averages rejected the options (samples per cycle not above twice the
    /// harmonics, ...).
    #[error(transparent)]
    Hbm(#[from] HbmError),
    /// The mode or the equilibrium does not hold one value per dof of the modal brake.
    #[error("the mode and the equilibrium must cover the brake's {expected} dofs (got {got})")]
    Dimension {
        /// The modal brake's number of dofs.
        expected: usize,
        /// The shorter of the two lengths given.
        got: usize,
    },
    /// The start cannot be scaled: the mode has no normal motion at any pair, or some pair is
    /// open at the equilibrium (the smallest static penetration is ≤ 0).
    #[error(
        "the unstable mode does not move the contact, or every pair is open at equilibrium: no perturbation along it can start a limit cycle"
    )]
    NoContactMotion,
    /// [`TiOptions::perturbation`] is not a finite positive number (the value given).
    #[error("the initial perturbation must be a positive number (got {0})")]
    BadPerturbation(f64),
    /// The modal matrix `Φ` is singular: the physical start has no modal coordinates.
    #[error("the modal matrix is singular")]
    SingularModes,
}

/// Where an integration starts: a modal state `[q; q']` and the scales of its tolerances and
/// of its steady-state monitor (module docs). [`TiStart::from_mode`] builds the perturbed
/// equilibrium; [`TiRun::continuation`] the state where a run ended, with the same scales, so
/// that a tighter run can go on from a looser one's steady cycle instead of from the
/// equilibrium.
#[derive(Clone, Debug, PartialEq)]
pub struct TiStart {
    /// Initial modal state `[q; q']` (length twice the modes).
    pub y0: Vec<f64>,
    /// Row `w` with `w · q' = δ'` of the most moving pair (the monitor's observable).
    observable: Vec<f64>,
    /// Modal displacement scale `Q` of the absolute tolerances.
    q_scale: f64,
    /// Initial amplitude factor ε of the unstable mode.
    epsilon: f64,
    /// `|Im λ|` of the unstable mode (rad/s): velocity tolerances and the time limit.
    omega0: f64,
    /// `|δ'|` of the first start: cycles below a millionth of it never count as steady.
    rate_scale: f64,
}

impl TiStart {
    /// `x = x_eq + ε Re ψ`, `x' = ε Re(λ ψ)` (module docs), with ε such that the pair moving
    /// most has a normal amplitude of `perturbation` times the smallest static penetration.
    pub fn from_mode(
        mb: &ModalBrake,
        lambda: c64,
        mode: &[c64],
        equilibrium: &[f64],
        perturbation: f64,
    ) -> Result<Self, TiError> {
        let n = mb.modes();
        if mode.len() != n || equilibrium.len() != n {
            return Err(TiError::Dimension {
                expected: n,
                got: mode.len().min(equilibrium.len()),
            });
        }
        let psi_n: Vec<c64> = mb.nl_dofs.iter().map(|&d| mode[d]).collect();
        let x_n: Vec<f64> = mb.nl_dofs.iter().map(|&d| equilibrium[d]).collect();
        let (mut best, mut gmax, mut pen) = (0, 0.0f64, f64::INFINITY);
        for (i, p) in mb.pairs.iter().enumerate() {
            let g: c64 = p.normal.iter().map(|&(k, a)| psi_n[k] * a).sum();
            if g.norm() > gmax {
                (best, gmax) = (i, g.norm());
            }
            let d = p.penetration(&x_n);
            if d > 0.0 {
                pen = pen.min(d);
            }
        }
        if !(gmax > 0.0 && pen > 0.0 && pen.is_finite()) {
            return Err(TiError::NoContactMotion);
        }
        if !(perturbation.is_finite() && perturbation > 0.0) {
            return Err(TiError::BadPerturbation(perturbation));
        }
        let unit = pen / gmax;
        let epsilon = perturbation * unit;
        let x: Vec<f64> = (0..n)
            .map(|i| equilibrium[i] + epsilon * mode[i].re)
            .collect();
        let v: Vec<f64> = (0..n).map(|i| epsilon * (lambda * mode[i]).re).collect();
        let y0 = BrakeDynamics::state_from_physical(mb, &x, &v).ok_or(TiError::SingularModes)?;
        // Q: the mode's largest modal coordinate for a contact motion of one penetration.
        let re: Vec<f64> = mode.iter().map(|z| z.re).collect();
        let im: Vec<f64> = mode.iter().map(|z| z.im).collect();
        let qm = BrakeDynamics::state_from_physical(mb, &re, &im).ok_or(TiError::SingularModes)?;
        let q_scale = unit * (0..n).map(|j| qm[j].hypot(qm[n + j])).fold(0.0, f64::max);
        let pair = &mb.pairs[best];
        let observable: Vec<f64> = (0..n)
            .map(|j| pair.normal.iter().map(|&(i, g)| g * mb.phi_n[(i, j)]).sum())
            .collect();
        let rate_scale = (0..n).map(|j| observable[j] * y0[n + j]).sum::<f64>().abs();
        Ok(Self {
            y0,
            observable,
            q_scale,
            epsilon,
            omega0: lambda.im.abs(),
            rate_scale,
        })
    }

    /// Initial amplitude factor ε of the unstable mode (of the first start, for a
    /// continuation).
    pub fn epsilon(&self) -> f64 {
        self.epsilon
    }

    /// The absolute tolerances [`integrate_from`] gives the BDF from this start with `opts`
    /// (module docs: `atol_q` on the displacements, `ω₀ atol_q` on the velocities).
    pub fn atol(&self, opts: &TiOptions) -> Vec<f64> {
        let n = self.y0.len() / 2;
        let atol_q = opts.atol_factor * opts.rtol * self.q_scale;
        (0..2 * n)
            .map(|i| if i < n { atol_q } else { atol_q * self.omega0 })
            .collect()
    }
}

/// Takes every sample of `sums` due by the end of `bdf`'s last step (its dense output).
fn take<S: squeal_ode::OdeSystem>(
    sums: &mut FourierSums,
    bdf: &Bdf<S>,
    y: &mut [f64],
) -> Result<(), OdeError> {
    while let Some(t) = sums.next_time() {
        if t > bdf.t() {
            break;
        }
        bdf.interpolate(t.max(bdf.t_prev()), y)?;
        sums.add(y);
    }
    Ok(())
}

/// Physical displacement and velocity coefficients (`x = Φ q`, `x' = Φ v`) of the modal
/// state's averaged Fourier coefficients.
fn physical(mb: &ModalBrake, sums: &FourierSums) -> Result<Cycle, HbmError> {
    physical_cycle(mb, &sums.periodic())
}

/// Physical displacement and velocity coefficients (`x = Φ q`, `x' = Φ v`) of the Fourier
/// series of a modal state `[q; v]`.
pub(crate) fn physical_cycle(mb: &ModalBrake, state: &Periodic) -> Result<Cycle, HbmError> {
    let n = mb.modes();
    state
        .layout()
        .check_len("modal state", 2 * n * state.layout().n_blocks())?;
    let layout = HarmonicLayout::new(n, state.harmonics())?;
    let (mut x, mut v) = (vec![0.0; layout.len()], vec![0.0; layout.len()]);
    for b in 0..layout.n_blocks() {
        for j in 0..n {
            let (cq, cv) = (state.coeffs[b * 2 * n + j], state.coeffs[b * 2 * n + n + j]);
            for d in 0..n {
                let p = mb.phi[(d, j)];
                x[b * n + d] += p * cq;
                v[b * n + d] += p * cv;
            }
        }
    }
    Ok(Cycle {
        x: Periodic::new(layout, state.omega, x)?,
        v: Periodic::new(layout, state.omega, v)?,
    })
}

/// The sums of one block of [`TiOptions::confirm_cycles`] periods from `t0`.
fn new_sums(dim: usize, opts: &TiOptions, t0: f64, period: f64) -> Result<FourierSums, OdeError> {
    FourierSums::new(
        dim,
        opts.harmonics,
        opts.samples_per_cycle,
        opts.confirm_cycles,
        t0,
        period,
    )
    .map_err(|_| OdeError::InvalidOption {
        name: "samples_per_cycle",
        reason: "must exceed twice the harmonics".into(),
    })
}

/// Mean period of the monitor's window (its spread is below the steady tolerance).
fn mean_period(window: &[CycleRecord]) -> f64 {
    window.iter().map(|r| r.period).sum::<f64>() / window.len().max(1) as f64
}

/// Phase-aligned relative change between two detections (on every dof).
fn drift(a: &Cycle, b: &Cycle, dof: usize) -> f64 {
    let mut b = b.clone();
    b.align_to(a, dof);
    let all: Vec<usize> = (0..a.n_dofs()).collect();
    let e = relative_errors(&b, a, &all);
    e.displacement
        .max(e.velocity)
        .max(e.frequency_relative.abs())
}

/// Integrates the brake from its equilibrium perturbed along the unstable mode `(λ, ψ)` until
/// the steady limit cycle (module docs). A failure of the integrator or no steady state within
/// the limits is reported in [`TiRun::failure`], with the counters so far.
pub fn integrate_to_limit_cycle(
    mb: &ModalBrake,
    lambda: c64,
    mode: &[c64],
    equilibrium: &[f64],
    opts: &TiOptions,
) -> Result<TiRun, TiError> {
    // The Fourier averages' options, checked before any work.
    FourierSums::new(
        2 * mb.modes(),
        opts.harmonics,
        opts.samples_per_cycle,
        1,
        0.0,
        1.0,
    )?;
    let s = TiStart::from_mode(mb, lambda, mode, equilibrium, opts.perturbation)?;
    integrate_from(mb, &s, opts)
}

/// Integrates the brake from `start` until the steady limit cycle, as
/// [`integrate_to_limit_cycle`] does from the perturbed equilibrium ([`TiOptions::perturbation`]
/// is not used: the start is given).
pub fn integrate_from(mb: &ModalBrake, s: &TiStart, opts: &TiOptions) -> Result<TiRun, TiError> {
    let t0 = Instant::now();
    let n = mb.modes();
    if s.y0.len() != 2 * n || s.observable.len() != n {
        return Err(TiError::Dimension {
            expected: n,
            got: s.observable.len().min(s.y0.len() / 2),
        });
    }
    FourierSums::new(2 * n, opts.harmonics, opts.samples_per_cycle, 1, 0.0, 1.0)?;
    let atol = s.atol(opts);
    let bdf_opts = {
        let mut o = BdfOptions::default();
        o.rtol = opts.rtol;
        o.atol = Atol::PerComponent(atol);
        o.max_order = opts.max_order;
        o.max_steps = opts.max_steps;
        o
    };
    let period0 = 2.0 * PI / s.omega0;
    let t_end = opts.max_cycles * period0;
    let sys = BrakeDynamics::new(mb);
    let mut bdf = Bdf::new(&sys, 0.0, &s.y0, t_end, &bdf_opts)?;
    let w = s.observable.clone();
    let observable = move |y: &[f64]| (0..n).map(|j| w[j] * y[n + j]).sum::<f64>();
    // A cycle must be at least a millionth of the initial rate amplitude to count.
    let rate0 = s.rate_scale;
    let steady_opts = {
        let mut o = SteadyOptions::default();
        o.level = 0.0;
        o.rtol = opts.steady_rtol;
        o.cycles = opts.steady_cycles;
        o.harmonics = opts.harmonics;
        o.samples_per_cycle = opts.samples_per_cycle;
        o.subdivisions = 4;
        o.min_amplitude = 1e-6 * rate0;
        o.observable = "normal penetration rate of the most moving contact pair".into();
        o.unit = "m/s".into();
        o
    };
    let mut monitor = OscillationMonitor::new(2 * n, observable, &steady_opts)?;
    let mut history = Vec::new();
    let mut failure = None;
    let mut steady = None;
    let mut sums: Option<FourierSums> = None;
    let mut previous: Option<Cycle> = None;
    let mut detections = 0;
    let mut drifts = Vec::new();
    let mut y = vec![0.0; 2 * n];
    let result: Result<(), OdeError> = (|| {
        monitor.observe(&bdf)?;
        while !bdf.is_finished() {
            bdf.step()?;
            let before = monitor.cycles_completed();
            let found = monitor.observe(&bdf)?;
            if monitor.cycles_completed() > before
                && let Some(r) = monitor.window().back()
            {
                history.push(*r);
            }
            if sums.is_none() && found.is_some() {
                let window: Vec<CycleRecord> = monitor.window().iter().copied().collect();
                sums = Some(new_sums(2 * n, opts, bdf.t(), mean_period(&window))?);
            }
            let Some(acc) = sums.as_mut() else { continue };
            take(acc, &bdf, &mut y)?;
            if !acc.complete() {
                continue;
            }
            detections += 1;
            let cycle = physical(mb, acc).map_err(|_| OdeError::InvalidOption {
                name: "harmonics",
                reason: "too many harmonics for the brake's dofs".into(),
            })?;
            let next_t0 = acc.end_time();
            if let Some(prev) = &previous {
                let dof = prev.strongest_dof(&mb.nl_dofs).unwrap_or(0);
                let d = drift(prev, &cycle, dof);
                drifts.push((bdf.t(), d));
                if d <= opts.drift_tol {
                    steady = Some(TiSteady {
                        period: 2.0 * PI / cycle.omega(),
                        cycle,
                        cycles: monitor.cycles_completed(),
                        t: bdf.t(),
                        drift: d,
                        detections,
                    });
                    return Ok(());
                }
            }
            previous = Some(cycle);
            // The next average starts where this one ended, with the latest mean period.
            let window: Vec<CycleRecord> = monitor.window().iter().copied().collect();
            let mut next = new_sums(2 * n, opts, next_t0, mean_period(&window))?;
            take(&mut next, &bdf, &mut y)?;
            sums = Some(next);
        }
        Err(monitor.not_steady(bdf.t()))
    })();
    if let Err(e) = result {
        failure = Some(e);
    }
    Ok(TiRun {
        steady,
        failure,
        stats: *bdf.stats(),
        wall: t0.elapsed(),
        history,
        t_end: bdf.t(),
        dim: 2 * n,
        epsilon: s.epsilon,
        drifts,
        end: TiStart {
            y0: bdf.y().to_vec(),
            ..s.clone()
        },
    })
}
