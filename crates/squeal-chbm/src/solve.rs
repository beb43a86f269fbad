//! Eqs (46)–(48) for the brake: CHBM is [`squeal_hbm::solve_chbm`] (the constrained
//! autonomous harmonic balance with `f2 = Re λ`, eq 47) on the brake's condensed linear part
//! and contact force ([`squeal_brake::harmonic`]); this module starts it from the unstable mode
//! (eq 48), climbs the harmonic ladder, recovers every dof (eq 35) and says what was found.
//!
//! **Residual.** `f1` (eq 46) is the condensed harmonic balance residual scaled by the static
//! force level; the phase condition `U1s[d] = 0` (one pad contact dof `d` that moves in the
//! unstable mode) removes the time-shift invariance; `f2` is `Re λ / ω0` of the eigenvalue
//! followed through the describing-function linearization of the cycle, times a weight. At
//! every root of the harmonic balance `f2 = 0` exactly, while at the static solution
//! `f2 = Re λ > 0`: `[f1; phase; f2]` has an exact zero at the limit cycle only.
//!
//! **Harmonic ladder.** From eq (48) the solve converges when the guess's amplitude `p` is
//! near the limit cycle's. With [`ChbmOptions::ladder`] (default) it first solves with one
//! harmonic, whose basin is wide, then with all harmonics from that solution.

use crate::cycle::Cycle;
use faer::c64;
use squeal_brake::harmonic::{
    BrakeEigen, CondensedStiffness, ContactForce, condensed_load, recover,
};
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::lm::{LmIteration, LmOptions, LmStop};
use squeal_hbm::{
    Aft, HarmonicBalance, HarmonicLayout, HbmError, NonlinearForce, PhaseCondition, ReLambda,
    RowScales, initial_guess, reference_jacobian, solve_chbm,
};
use std::time::{Duration, Instant};

/// Errors of a CHBM solve (a solve that runs but does not converge is not an error: see
/// [`Outcome`]).
#[derive(Debug, thiserror::Error)]
pub enum ChbmError {
    /// The harmonic balance machinery of [`squeal_hbm`] refused the problem or failed in it
    /// (layout, AFT samples, a non-positive start frequency, the eigenvalue lost, ...).
    #[error(transparent)]
    Hbm(#[from] HbmError),
    /// [`ChbmOptions::harmonics`] is 0.
    #[error("CHBM needs at least one harmonic")]
    NoHarmonics,
    /// [`ChbmStart::mode`] or [`ChbmStart::equilibrium`] does not hold one value per dof of
    /// the modal brake.
    #[error("the start's mode and equilibrium must cover the brake's {expected} dofs (got {got})")]
    StartSize {
        /// The modal brake's number of dofs.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// Eq (48) cannot be scaled: the start's mode has no normal motion at any pair, or some
    /// pair is open at the equilibrium (the smallest static penetration is ≤ 0).
    #[error(
        "the unstable mode does not move the contact, or every pair is open at equilibrium: eq (48) has no start"
    )]
    NoContactMotion,
    /// [`ChbmOptions::amplitude`] is not a finite positive number (the value given).
    #[error("the initial amplitude must be a positive number (got {0})")]
    BadAmplitude(f64),
    /// [`solve_with_restarts`] was given no amplitude.
    #[error("no initial amplitude to try")]
    NoAmplitudes,
    /// The normal form has no cycle on either side of μ0 (its `Re c1` or `dRe λ/dμ` is zero).
    #[error(
        "the Hopf point's normal form gives no branch of limit cycles (Re c1 or dRe(lambda)/dmu is zero; a linear contact law, k_nl = 0, gives Re c1 = 0: add a cubic contact stiffness)"
    )]
    NoBranch,
    /// The first cycle of a branch, near the Hopf point, could not be converged.
    #[error(
        "the first limit cycle of the branch (next to the Hopf point) did not converge; try a larger start offset"
    )]
    BranchStart,
}

/// Options of [`solve`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct ChbmOptions {
    /// Harmonics `H` of the Fourier series of eq (23) (at least 1).
    pub harmonics: usize,
    /// AFT time samples (default: [`squeal_hbm::default_samples`]).
    pub samples: Option<usize>,
    /// Initial amplitude `p` of eq (48): the largest normal motion of the contact pairs in the
    /// guess, as a fraction of the smallest static penetration.
    pub amplitude: f64,
    /// Weight of `f2`.
    pub weight: f64,
    /// Converged when `||f1|| <= eps1` times the force scale (the larger of `||F_eq||` and the
    /// norm of the static contact forces) ...
    pub eps1: f64,
    /// ... and `|Re λ| <= eps2 ω`.
    pub eps2: f64,
    /// Levenberg–Marquardt trial steps allowed in each solve (each rung of the ladder).
    pub max_iterations: usize,
    /// Harmonic ladder: solve with one harmonic first (from eq 48), then with all of them
    /// from that solution (the paper's "starting from previous results").
    pub ladder: bool,
}

impl Default for ChbmOptions {
    fn default() -> Self {
        Self {
            harmonics: 3,
            samples: None,
            amplitude: 0.3,
            weight: 1.0,
            eps1: 1e-9,
            eps2: 1e-3,
            max_iterations: 200,
            ladder: true,
        }
    }
}

/// The initial amplitudes `p` tried in turn when none is given: the one list of the crate.
pub const RESTART_AMPLITUDES: [f64; 4] = [0.5, 1.0, 2.0, 0.25];

/// Where the solve starts: the stability analysis at the same μ.
#[derive(Clone, Debug)]
pub struct ChbmStart {
    /// Eigenvalue of the unstable mode of the tangent linearization (eq 22).
    pub lambda: c64,
    /// Its shape on all physical dofs.
    pub mode: Vec<c64>,
    /// Static equilibrium at this μ (eq 14), physical dofs.
    pub equilibrium: Vec<f64>,
}

/// What the solve found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// A limit cycle, both `f1` and `f2` within tolerance.
    LimitCycle,
    /// `f1` converged but `|Re λ| > eps2 ω` at the root (the eigenvalue followed is not the
    /// one at `iω`).
    LimitCycleUnconstrained,
    /// The solver landed on the static (trivial) solution.
    Static,
    /// No convergence.
    NotConverged,
}

impl Outcome {
    /// A short label for tables and a full sentence for messages.
    fn texts(self) -> (&'static str, &'static str) {
        match self {
            Outcome::LimitCycle => ("limit cycle", "limit cycle (converged on eps1 and eps2)"),
            Outcome::LimitCycleUnconstrained => (
                "HB root, |Re lambda| > eps2",
                "limit cycle of the harmonic balance, but |Re lambda| above eps2",
            ),
            Outcome::Static => (
                "static solution",
                "static solution (the oscillation died out): not a limit cycle",
            ),
            Outcome::NotConverged => ("not converged", "not converged"),
        }
    }

    /// A short label for tables (`limit cycle`, `static solution`, ...).
    pub fn label(self) -> &'static str {
        self.texts().0
    }
}

impl std::fmt::Display for Outcome {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.texts().1)
    }
}

/// One residual evaluation of the solve (for the histories of Figures 6–7).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Evaluation {
    /// Harmonics of the solve that made it (the ladder's first solve has one).
    pub harmonics: usize,
    /// `||f1||` over the force scale (see [`ChbmOptions::eps1`]).
    pub f1: f64,
    /// `Re λ` (s⁻¹) of the followed eigenvalue there.
    pub re_lambda: f64,
    /// ω (rad/s) there.
    pub omega: f64,
}

/// A CHBM result.
#[derive(Clone, Debug)]
pub struct ChbmSolution {
    /// What the solve found.
    pub outcome: Outcome,
    /// Harmonics of the solve that produced it (1 when the ladder stopped at its first rung).
    pub harmonics: usize,
    /// AFT time samples per period.
    pub samples: usize,
    /// Fundamental frequency ω (rad/s).
    pub omega: f64,
    /// Fourier coefficients of the nonlinear dofs (layout of eq 25).
    pub nl_coeffs: Vec<f64>,
    /// Fourier coefficients of every physical dof (eq 35), same layout over all dofs.
    pub coeffs: Vec<f64>,
    /// Physical index of each nonlinear dof, in the order of `nl_coeffs`' blocks.
    pub nl_dofs: Vec<usize>,
    /// `||f1||` over the force scale at the solution (see [`ChbmOptions::eps1`]).
    pub f1: f64,
    /// `Re λ` (s⁻¹) of the followed eigenvalue at the solution.
    pub re_lambda: f64,
    /// The followed eigenvalue of the cycle's describing-function linearization (s⁻¹, rad/s).
    pub lambda: c64,
    /// LM trial steps (all solves of the ladder).
    pub iterations: usize,
    /// Why the last Levenberg–Marquardt solve stopped.
    pub stop: LmStop,
    /// Levenberg–Marquardt iterations of all solves of the ladder.
    pub lm_history: Vec<LmIteration>,
    /// Every residual evaluation of all solves of the ladder.
    pub evaluations: Vec<Evaluation>,
    /// Fraction of the period each pair is open, from the roots of the continuous penetration
    /// of the solution's series ([`crate::physics::open_fractions`]), not from the AFT samples.
    pub open_fraction: Vec<f64>,
    /// Relative change of `F~_nl` when the samples are doubled (aliasing check).
    pub aliasing: f64,
    /// Largest `|x_n - U_n|` of the recovered nonlinear dofs relative to their amplitude.
    pub recovery_error: f64,
    /// Wall time of the whole solve, ladder included.
    pub time: Duration,
}

impl ChbmSolution {
    /// The cycle of every physical dof (velocities by differentiating eq 23).
    pub fn cycle(&self) -> Result<Cycle, HbmError> {
        let n = self.coeffs.len() / (2 * self.harmonics + 1);
        Cycle::from_coefficients(self.harmonics, self.omega, n, self.coeffs.clone())
    }

    /// Bytes of what CHBM stores: the Fourier coefficients of the nonlinear dofs and ω (every
    /// other dof follows from them by eq 35).
    pub fn storage_bytes(&self) -> usize {
        (self.nl_coeffs.len() + 1) * 8
    }

    /// Harmonic `k` amplitude of physical dof `d` (`|mean|` for `k = 0`).
    pub fn amplitude(&self, d: usize, k: usize) -> f64 {
        let n = self.coeffs.len() / (2 * self.harmonics + 1);
        if k == 0 {
            return self.coeffs[d].abs();
        }
        self.coeffs[(2 * k - 1) * n + d].hypot(self.coeffs[2 * k * n + d])
    }
}

/// Solves eqs (46)–(47) from the unstable mode of the stability analysis (eq 48), through the
/// one-harmonic solution first when [`ChbmOptions::ladder`] is set.
pub fn solve(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &ChbmOptions,
) -> Result<ChbmSolution, ChbmError> {
    let t0 = Instant::now();
    if !opts.ladder || opts.harmonics == 1 {
        return solve_from(mb, start, opts, None);
    }
    let first = solve_from(
        mb,
        start,
        &ChbmOptions {
            harmonics: 1,
            ..opts.clone()
        },
        None,
    )?;
    if !matches!(
        first.outcome,
        Outcome::LimitCycle | Outcome::LimitCycleUnconstrained
    ) {
        let mut s = first;
        s.time = t0.elapsed();
        return Ok(s);
    }
    let mut s = solve_from(mb, start, opts, Some(&first))?;
    let mut evaluations = first.evaluations.clone();
    evaluations.extend(s.evaluations);
    s.evaluations = evaluations;
    s.iterations += first.iterations;
    let mut history = first.lm_history.clone();
    history.extend(s.lm_history);
    s.lm_history = history;
    s.time = t0.elapsed();
    Ok(s)
}

/// CHBM from each amplitude in turn until a limit cycle converges; returns the solution, the
/// amplitude it came from, the wall time and the LM iterations of all attempts.
pub fn solve_with_restarts(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &ChbmOptions,
    amplitudes: &[f64],
) -> Result<(ChbmSolution, f64, Duration, usize), ChbmError> {
    let t0 = Instant::now();
    let mut iterations = 0;
    let mut last = None;
    for &a in amplitudes {
        let o = ChbmOptions {
            amplitude: a,
            ..opts.clone()
        };
        let s = solve(mb, start, &o)?;
        iterations += s.iterations;
        let done = s.outcome == Outcome::LimitCycle;
        last = Some((s, a));
        if done {
            break;
        }
    }
    let (s, a) = last.ok_or(ChbmError::NoAmplitudes)?;
    Ok((s, a, t0.elapsed(), iterations))
}

/// The pieces of one solve: the harmonic balance on the brake, its phase condition and scales.
struct Setup {
    hb: HarmonicBalance<CondensedStiffness, ContactForce>,
    layout: HarmonicLayout,
    phase: PhaseCondition,
    scales: RowScales,
    z0: Vec<f64>,
    omega0: f64,
}

/// A cycle CHBM starts from instead of eq (48): the nonlinear dofs' Fourier coefficients (any
/// number of harmonics: padded with zeros or truncated to the solve's), the frequency, and the
/// eigenvalue the constraint follows.
#[derive(Clone, Copy, Debug)]
pub struct Guess<'a> {
    /// Coefficients of the nonlinear dofs (eq 25).
    pub nl_coeffs: &'a [f64],
    /// ω (rad/s).
    pub omega: f64,
    /// The eigenvalue of the equivalent linearization to follow (`i ω` on a cycle).
    pub lambda: c64,
}

fn setup(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &ChbmOptions,
    previous: Option<Guess<'_>>,
    align: bool,
) -> Result<Setup, ChbmError> {
    let nn = mb.nl();
    if opts.harmonics == 0 {
        return Err(ChbmError::NoHarmonics);
    }
    for got in [start.mode.len(), start.equilibrium.len()] {
        if got != mb.modes() {
            return Err(ChbmError::StartSize {
                expected: mb.modes(),
                got,
            });
        }
    }
    let layout = HarmonicLayout::new(nn, opts.harmonics)?;
    let mut stiffness = CondensedStiffness::new(mb, opts.harmonics);
    let omega0 = start.lambda.im;
    stiffness.update(omega0);
    let f_eq = condensed_load(mb, &stiffness, &layout);
    let force = ContactForce::new(mb);
    let hb = HarmonicBalance::new(layout, stiffness, force, f_eq.clone(), opts.samples)?;
    let (z0, omega0) = match previous {
        None => (guess(mb, start, &layout, opts.amplitude)?, omega0),
        Some(p) => {
            // Pad the lower-order solution with zero harmonics (the layouts share their
            // leading blocks).
            let mut u = vec![0.0; layout.len()];
            let m = p.nl_coeffs.len().min(u.len());
            u[..m].copy_from_slice(&p.nl_coeffs[..m]);
            if align {
                // A cycle from elsewhere (a branch) has its own phase: shift it onto this
                // solve's phase condition so that a root of the same equations stays put.
                let d = phase_dof(mb, &u, &layout);
                layout.align_phase(&mut u, d)?;
            }
            (u, p.omega)
        }
    };
    let phase = PhaseCondition::FirstSineZero {
        dof: phase_dof(mb, &z0, &layout),
    };
    let x_scale = mb
        .pairs
        .iter()
        .map(|p| p.penetration(&z0[..nn]))
        .fold(f64::INFINITY, f64::min)
        .abs()
        .max(1e-12);
    Ok(Setup {
        scales: RowScales {
            force: force_scale(mb, start, &f_eq),
            phase: x_scale,
        },
        hb,
        layout,
        phase,
        z0,
        omega0,
    })
}

/// One CHBM solve with `opts.harmonics` harmonics (no ladder), from eq (48), or from
/// `previous` (a solution with fewer harmonics, padded with zero harmonics) when given.
pub fn solve_from(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &ChbmOptions,
    previous: Option<&ChbmSolution>,
) -> Result<ChbmSolution, ChbmError> {
    let guess = previous.map(|p| Guess {
        nl_coeffs: &p.nl_coeffs,
        omega: p.omega,
        lambda: p.lambda,
    });
    solve_guessed(mb, start, opts, guess, false)
}

/// One CHBM solve with `opts.harmonics` harmonics (no ladder) from `guess` (e.g. a cycle of the
/// branch of limit cycles at this μ), or from eq (48) when there is none.
pub fn solve_from_guess(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &ChbmOptions,
    guess: Option<Guess<'_>>,
) -> Result<ChbmSolution, ChbmError> {
    solve_guessed(mb, start, opts, guess, true)
}

fn solve_guessed(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &ChbmOptions,
    previous: Option<Guess<'_>>,
    align: bool,
) -> Result<ChbmSolution, ChbmError> {
    let t0 = Instant::now();
    let Setup {
        mut hb,
        layout,
        phase,
        scales,
        z0,
        omega0,
    } = setup(mb, start, opts, previous, align)?;
    let samples = hb.aft().n_samples();
    let (k0, c0) = static_reference(mb, start, hb.force());
    let lambda = previous.map_or(start.lambda, |p| p.lambda);
    let constraint = ReLambda::new(
        BrakeEigen::new(mb, None),
        k0,
        c0,
        lambda,
        opts.weight,
        omega0.abs().max(f64::MIN_POSITIVE),
    )?;
    let lm_opts = {
        let mut o = LmOptions::default();
        o.abs_tol = opts.eps1;
        o.rel_tol = 0.0;
        o.max_iterations = opts.max_iterations;
        o.accept_stationary = true;
        o
    };
    let (result, _) = solve_chbm(&mut hb, phase, constraint, scales, &z0, omega0, &lm_opts)?;
    let l = layout.len();
    let z = &result.z;
    let (u, omega) = (z[..l].to_vec(), z[l]);
    let f1 = result
        .history
        .last()
        .map_or(f64::INFINITY, |h| h.harmonic_balance);
    // The force's coefficients and samples at the solution, from one explicit evaluation.
    let mut r = vec![0.0; l];
    let eval = hb.evaluate(&u, omega, &mut r)?;
    let g = eval.force.to_vec();
    let nl_cycle = Cycle::from_coefficients(opts.harmonics, omega, mb.nl(), u.clone())?;
    let nl_index: Vec<usize> = (0..mb.nl()).collect();
    let open_fraction = crate::physics::open_fractions_of(&mb.pairs, &nl_index, &nl_cycle)?;
    let aliasing = aliasing_check(hb.force(), &layout, &u, omega, samples)?;
    let coeffs = recover(mb, omega, &g, &layout);
    let recovery_error = recovery_error(&layout, &u, &coeffs, &mb.nl_dofs, mb.modes());
    let first = |v: &[f64]| {
        (0..mb.nl())
            .map(|i| layout.amplitude(v, 1, i).unwrap_or(0.0))
            .fold(0.0, f64::max)
    };
    let lambda = result.lambda;
    let outcome = if first(&u) <= 1e-6 * first(&z0) {
        Outcome::Static
    } else if f1 > opts.eps1 {
        Outcome::NotConverged
    } else if lambda.re.abs() <= opts.eps2 * omega.abs() {
        Outcome::LimitCycle
    } else {
        Outcome::LimitCycleUnconstrained
    };
    let evaluations = result
        .history
        .iter()
        .zip(&result.lambdas)
        .map(|(h, l)| Evaluation {
            harmonics: opts.harmonics,
            f1: h.harmonic_balance,
            re_lambda: l.re,
            omega: h.omega,
        })
        .collect();
    Ok(ChbmSolution {
        outcome,
        harmonics: opts.harmonics,
        samples,
        omega,
        nl_coeffs: u,
        coeffs,
        nl_dofs: mb.nl_dofs.clone(),
        f1,
        re_lambda: lambda.re,
        lambda,
        iterations: result.report.iterations,
        stop: result.report.stop,
        lm_history: result.report.history,
        evaluations,
        open_fraction,
        aliasing,
        recovery_error,
        time: t0.elapsed(),
    })
}

/// The reference linearization `J₀` of the constraint: the contact force's Jacobians at the
/// static equilibrium of the start, on the nonlinear dofs (sizes checked by [`setup`]).
fn static_reference<F: NonlinearForce>(
    mb: &ModalBrake,
    start: &ChbmStart,
    force: &F,
) -> (faer::Mat<f64>, faer::Mat<f64>) {
    let x: Vec<f64> = mb.nl_dofs.iter().map(|&d| start.equilibrium[d]).collect();
    reference_jacobian(force, &x)
}

/// Eq (48): `Y0 = p (Ψ e^{λt} + Ψ̄ e^{λ̄t})` over one period, as Fourier coefficients of the
/// nonlinear dofs around the static equilibrium, with `p` the fraction `amplitude` of the
/// smallest static penetration over the largest normal motion of a pair in the mode.
fn guess(
    mb: &ModalBrake,
    start: &ChbmStart,
    layout: &HarmonicLayout,
    amplitude: f64,
) -> Result<Vec<f64>, ChbmError> {
    if !(amplitude.is_finite() && amplitude > 0.0) {
        return Err(ChbmError::BadAmplitude(amplitude));
    }
    let psi: Vec<c64> = mb.nl_dofs.iter().map(|&d| start.mode[d]).collect();
    let x0: Vec<f64> = mb.nl_dofs.iter().map(|&d| start.equilibrium[d]).collect();
    let (mut dmax, mut pen) = (0.0f64, f64::INFINITY);
    for p in &mb.pairs {
        let g: c64 = p.normal.iter().map(|&(i, a)| psi[i] * a).sum();
        dmax = dmax.max(2.0 * g.norm());
        let d = p.penetration(&x0);
        if d > 0.0 {
            pen = pen.min(d);
        }
    }
    let positive = |v: f64| v > 0.0; // false for NaN too
    if !positive(dmax) || !positive(pen) || !pen.is_finite() {
        return Err(ChbmError::NoContactMotion);
    }
    let p = amplitude * pen / dmax;
    // The phase dof of the mode itself (the guess's largest normal first harmonic).
    let mut u = initial_guess(layout, &x0, &psi, p, 0)?;
    let d = phase_dof(mb, &u, layout);
    layout.align_phase(&mut u, d)?;
    Ok(u)
}

/// The normal dof of a pair with the largest first harmonic.
pub(crate) fn phase_dof(mb: &ModalBrake, u: &[f64], layout: &HarmonicLayout) -> usize {
    let mut best = (0.0, 0);
    for p in &mb.pairs {
        for &(i, _) in &p.normal {
            let a = layout.amplitude(u, 1, i).unwrap_or(0.0);
            if a > best.0 {
                best = (a, i);
            }
        }
    }
    best.1
}

fn aliasing_check<F: NonlinearForce>(
    force: &F,
    layout: &HarmonicLayout,
    u: &[f64],
    omega: f64,
    samples: usize,
) -> Result<f64, ChbmError> {
    let mut a = Aft::new(*layout, samples)?;
    let mut b = Aft::new(*layout, 2 * samples)?;
    let (mut fa, mut fb) = (vec![0.0; layout.len()], vec![0.0; layout.len()]);
    a.forces(force, u, omega, &mut fa)?;
    b.forces(force, u, omega, &mut fb)?;
    let n = layout.n_dofs();
    // Compare the oscillating part (the static force dominates block 0).
    let num: f64 = (n..fa.len())
        .map(|i| (fa[i] - fb[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    let den: f64 = (n..fb.len())
        .map(|i| fb[i].powi(2))
        .sum::<f64>()
        .sqrt()
        .max(f64::MIN_POSITIVE);
    Ok(num / den)
}

fn recovery_error(
    layout: &HarmonicLayout,
    u: &[f64],
    coeffs: &[f64],
    nl: &[usize],
    n: usize,
) -> f64 {
    let nn = layout.n_dofs();
    let mut worst: f64 = 0.0;
    let scale = (nn..u.len())
        .map(|i| u[i].abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    for b in 0..layout.n_blocks() {
        for (i, &d) in nl.iter().enumerate() {
            worst = worst.max((coeffs[b * n + d] - u[b * nn + i]).abs() / scale);
        }
    }
    worst
}

/// The force scale of `f1`'s tolerance: the larger of the condensed static load and the
/// static contact forces. A brake held only by a preloading gap (no piston force) has a zero
/// load but not zero contact forces.
fn force_scale(mb: &ModalBrake, start: &ChbmStart, f_eq: &[f64]) -> f64 {
    let x: Vec<f64> = mb.nl_dofs.iter().map(|&d| start.equilibrium[d]).collect();
    force_scale_at(mb, &x, f_eq)
}

/// [`force_scale`] at the nonlinear dofs' static displacements `x`.
pub(crate) fn force_scale_at(mb: &ModalBrake, x: &[f64], f_eq: &[f64]) -> f64 {
    let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
    let mut f = vec![0.0; x.len()];
    ContactForce::new(mb).eval(x, &vec![0.0; x.len()], &mut f, None);
    norm(f_eq).max(norm(&f)).max(f64::MIN_POSITIVE)
}

/// Largest relative difference between the analytic Jacobian of the residual `[f1; phase; f2]`
/// and central finite differences, at the initial guess (eq 48): for tests and diagnostics.
/// Returns `(worst over the f1 rows, worst over the f2 row)`.
pub fn check_jacobian(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &ChbmOptions,
) -> Result<(f64, f64), ChbmError> {
    use faer::Mat;
    use squeal_hbm::AutonomousProblem;
    use squeal_hbm::lm::LeastSquaresProblem;
    let Setup {
        mut hb,
        layout,
        phase,
        scales,
        z0,
        omega0,
    } = setup(mb, start, opts, None, false)?;
    let (k0, c0) = static_reference(mb, start, hb.force());
    let constraint = ReLambda::new(BrakeEigen::new(mb, None), k0, c0, start.lambda, 1.0, omega0)?;
    let mut problem = AutonomousProblem::constrained(&mut hb, phase, constraint, scales)?;
    let mut z = z0;
    z.push(omega0);
    let (m, n) = (problem.n_residuals(), problem.n_params());
    let mut jac = Mat::<f64>::zeros(m, n);
    let mut r = vec![0.0; m];
    problem.residual(&z, &mut r)?;
    problem.jacobian(&z, jac.as_mut())?;
    let (mut rp, mut rm) = (vec![0.0; m], vec![0.0; m]);
    let (mut worst1, mut worst2) = (0.0f64, 0.0f64);
    let row_scale: Vec<f64> = (0..m)
        .map(|i| {
            (0..n)
                .map(|j| jac[(i, j)].abs() * z[j].abs().max(1e-9))
                .fold(0.0, f64::max)
        })
        .collect();
    for j in 0..n {
        let h = 1e-6 * z[j].abs().max(1e-9);
        let mut zp = z.clone();
        zp[j] += h;
        problem.residual(&zp, &mut rp)?;
        let mut zm = z.clone();
        zm[j] -= h;
        problem.residual(&zm, &mut rm)?;
        for i in 0..m {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            let err = (fd - jac[(i, j)]).abs() * z[j].abs().max(1e-9)
                / row_scale[i].max(f64::MIN_POSITIVE);
            if i == m - 1 {
                worst2 = worst2.max(err);
            } else if i < layout.len() {
                worst1 = worst1.max(err);
            }
        }
    }
    Ok((worst1, worst2))
}
