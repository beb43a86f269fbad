//! Issue #24, item 4: limit cycles of the brake with exact Coulomb stick–slip (DLFT,
//! `squeal_brake::contact::dlft`), at fixed μ.
//!
//! **What is solved.** The brake's condensed harmonic balance with every pair's friction as a
//! DLFT contact (docs/stick_slip.md, eqs D1–D4): unknowns the nonlinear dofs' Fourier
//! coefficients `U~` and ω, equations (D2) plus the phase condition `U1s[dof] = 0`, solved by
//! Levenberg–Marquardt (`squeal_hbm::solve_stick_slip`) at the μ of a cycle of the branch,
//! started from that cycle (the regularized law's, [`crate::stick_branch`], or the
//! permanent-sliding one). The rows are divided by the largest pair's normal force of the
//! guess, so the converged residual is relative to the clamp's force per pair.
//!
//! **Why at fixed μ and not continued.** The DLFT residual is piecewise smooth (the stick/slip
//! pattern of the samples changes with `U~`), and its stability would need Hill's method on
//! a non-smooth law; the branch's pseudo-arclength continuation and Floquet exponents stay on
//! the regularized law, and DLFT recomputes its cycles. The regularized cycles are the
//! starting guesses; their distance to the DLFT ones as `v_reg → 0` is the convergence that
//! docs/stick_slip.md measures.

use crate::branch::{BranchPoint, pair_cycles, truncation};
use crate::physics::SlidingMargin;
use crate::stick_branch::{StickError, point_margin, surface_speeds};
use squeal_brake::contact::dlft::{BrakeDlft, brake_dlft, set_mu};
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::{HarmonicLayout, LmOptions, PhaseCondition, solve_stick_slip};

/// Controls of [`dlft_cycle`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct DlftOptions {
    /// Harmonics (`None`: the guess's).
    pub harmonics: Option<usize>,
    /// Time samples of the friction forces per period (`None`: `16 (2H + 1)` to a power of
    /// two, `squeal_hbm::default_stick_slip_samples`).
    pub samples: Option<usize>,
    /// Factor on the default penalty ε of every pair (`squeal_brake::contact::dlft::
    /// default_epsilon`); any positive value gives the same converged cycle.
    pub epsilon_factor: f64,
    /// Levenberg–Marquardt's controls.
    pub lm: LmOptions,
}

impl Default for DlftOptions {
    /// Levenberg–Marquardt with a Gauss–Newton step first while the damping is at most its
    /// initial value ([`NEWTON_DAMPING`]).
    fn default() -> Self {
        let mut lm = LmOptions::default();
        lm.newton_damping = NEWTON_DAMPING;
        Self {
            harmonics: None,
            samples: None,
            epsilon_factor: 1.0,
            lm,
        }
    }
}

/// The damping up to which [`dlft_cycle`]'s Levenberg–Marquardt solve tries a Gauss–Newton
/// step (one LU factorization of the square Jacobian) before the damped one
/// (`squeal_hbm::LmOptions::newton_damping`): its initial damping, 1e-3, so every solve starts
/// with Gauss–Newton steps and goes back to them when the damping has come down. The damped
/// step's normal equations cost about twice the LU (`J^T J` and its Cholesky factor against
/// `n^3/3` for `n` = 1765 on the coarse brake); docs/stick_slip.md, "Gauss–Newton first",
/// has the cycles and times before and after.
pub const NEWTON_DAMPING: f64 = 1e-3;

/// A limit cycle with exact stick–slip.
#[derive(Clone, Debug)]
pub struct DlftCycle {
    /// The cycle (parameter μ; `parameter_rate` 0: not on a continuation).
    pub point: BranchPoint,
    /// Fraction of the period each pair sticks (carries a force inside Coulomb's cone).
    pub stick_fractions: Vec<f64>,
    /// The cycle's sliding margin (below 1 where the pair outruns the disc; a pair that sticks
    /// has margin 1 to the solve's accuracy).
    pub margin: SlidingMargin,
    /// Fraction of the period each pair is closed and slides backwards (`δ > 0`, `γ < 0`: the
    /// friction reverses), on [`crate::branch::PAIR_SAMPLES`] samples.
    pub reversed_fractions: Vec<f64>,
    /// ε of every pair (N·s/m).
    pub epsilon: Vec<f64>,
    /// Time samples of the friction forces.
    pub samples: usize,
    /// Whether Levenberg–Marquardt met its residual tolerance, or stopped short of it (its
    /// iteration limit, a small step or gradient) with the balance residual at most 1e-9 and
    /// the phase condition met to 1e-6 rad ([`DlftCycle::phase_error`]). `false`: neither;
    /// the residual and phase error say how far.
    pub converged: bool,
    /// The phase condition's row `|U1s[dof]|` relative to the first harmonic's amplitude
    /// `|U1|` of the phase dof: the cycle's shift in time from the phase condition, in radians
    /// of the first harmonic.
    pub phase_error: f64,
}

/// The largest pair normal force at the mean of `u` (N), a force scale of the brake.
/// A DLFT cycle whose balance residual, relative to the largest static normal force of a
/// pair, is at most this is converged, whatever stopped the solver: 1e-9 is a thousand times
/// the round-off of the AFT sums measured on the coarse brake (1e-12) and far below the
/// regularization errors it judges (1e-5 and up, docs/stick_slip.md).
const ACCEPTED_RESIDUAL: f64 = 1e-9;

/// A solve that stopped short of Levenberg–Marquardt's own tolerance (its iteration limit, a
/// small step) is accepted on [`ACCEPTED_RESIDUAL`] only if its phase row, relative to the
/// first harmonic's amplitude of the phase dof ([`DlftCycle::phase_error`], a shift in time in
/// radians), is at most this. The sampled balance is invariant to a shift in time by less than
/// the sample spacing (2π/1024 = 6.1e-3 rad at 24 harmonics) except where a sample crosses a
/// transition, so a cycle off its phase condition by a fraction of a sample can have an exact
/// balance and one stuck sample more: at 1.0540 μ0 on the coarse brake at 3 km/h such a cycle
/// was 1.7e-3 rad off (a quarter of a sample) and 4.1e-7 in frequency from the cycle on its
/// phase condition (docs/stick_slip.md, "The two cycles at 1.0540 μ0"). 1e-6 rad is 1.6e-4 of
/// a sample; a converged solve's phase row is met to round-off (each Gauss–Newton step solves
/// that linear row exactly).
const ACCEPTED_PHASE: f64 = 1e-6;

fn force_scale(mb: &ModalBrake, u: &[f64]) -> f64 {
    let x0 = &u[..mb.nl()];
    mb.pairs
        .iter()
        .map(|p| p.response(x0, None, 0.0).normal.abs())
        .fold(0.0, f64::max)
        .max(1e-12)
}

/// Fraction of the period each pair of `mb` is closed with a negative slip velocity, for the
/// cycle `u` of angular frequency `omega`.
pub fn reversed_fractions(
    mb: &ModalBrake,
    layout: &HarmonicLayout,
    u: &[f64],
    omega: f64,
) -> Result<Vec<f64>, StickError> {
    let n = crate::branch::PAIR_SAMPLES;
    surface_speeds(mb)?;
    let (mut x, mut v) = (vec![0.0; layout.n_dofs()], vec![0.0; layout.n_dofs()]);
    let mut out = vec![0.0; mb.pairs.len()];
    for j in 0..n {
        let theta = 2.0 * std::f64::consts::PI * j as f64 / n as f64;
        layout.displacement_at(u, theta, &mut x)?;
        layout.velocity_at(u, omega, theta, &mut v)?;
        for (p, o) in mb.pairs.iter().zip(out.iter_mut()) {
            let slip = p.surface_speed.unwrap_or(0.0)
                + p.tangent.iter().map(|&(i, h)| h * v[i]).sum::<f64>();
            if p.penetration(&x) > 0.0 && slip < 0.0 {
                *o += 1.0 / n as f64;
            }
        }
    }
    Ok(out)
}

/// The brake's DLFT balance for the guess `g` at `mu` with `opts`.
fn balance(
    mb: &ModalBrake,
    mu: f64,
    g: &BranchPoint,
    opts: &DlftOptions,
) -> Result<(BrakeDlft, Vec<f64>), StickError> {
    if !(opts.epsilon_factor.is_finite() && opts.epsilon_factor > 0.0) {
        return Err(StickError::BadOption("epsilon factor must be positive"));
    }
    let h = opts.harmonics.unwrap_or(g.harmonics);
    let mut b = brake_dlft(mb, h, opts.samples, None, g.omega)?;
    set_mu(&mut b, mu);
    let mut eps = Vec::new();
    for c in b.contacts_mut() {
        c.epsilon *= opts.epsilon_factor;
        eps.push(c.epsilon);
    }
    Ok((b, eps))
}

/// The exact stick–slip cycle of `mb` at `mu`, from the cycle `guess` (any harmonics: padded
/// or truncated) with the phase condition on `phase_dof`.
pub fn dlft_cycle(
    mb: &ModalBrake,
    mu: f64,
    guess: &BranchPoint,
    phase_dof: usize,
    opts: &DlftOptions,
) -> Result<DlftCycle, StickError> {
    let speeds = surface_speeds(mb)?;
    let (mut b, epsilon) = balance(mb, mu, guess, opts)?;
    let layout: HarmonicLayout = b.layout();
    let mut u0 = vec![0.0; layout.len()];
    let m = guess.nl_coeffs.len().min(u0.len());
    u0[..m].copy_from_slice(&guess.nl_coeffs[..m]);
    let scale = force_scale(mb, &u0);
    let phase = PhaseCondition::FirstSineZero { dof: phase_dof };
    let len = layout.len();
    // A stop short of the tolerance keeps its last iterate: the residual says how far it is.
    let (coeffs, omega, iterations, converged) =
        match solve_stick_slip(&mut b, phase, &u0, guess.omega, scale, &opts.lm) {
            Ok(s) => (s.coeffs, s.omega, s.report.iterations, true),
            Err(squeal_hbm::HbmError::NotConverged { report }) => (
                report.x[..len].to_vec(),
                report.x[len],
                report.iterations,
                false,
            ),
            Err(e) => return Err(e.into()),
        };
    // The states of the solution itself (the last evaluation may be a rejected trial).
    let mut r = vec![0.0; len];
    b.residual(&coeffs, omega, &mut r)?;
    let residual = r.iter().map(|v| v * v).sum::<f64>().sqrt() / scale;
    // Levenberg–Marquardt judges the stacked rows, phase row (in metres) included, and can run
    // to its step limit on a cycle whose balance is already exact: the cycle is judged by its
    // own balance residual, relative to the largest static normal force of a pair.
    // The phase condition, too (ACCEPTED_PHASE): the balance alone accepts a cycle shifted in
    // time by a fraction of a sample.
    let PhaseCondition::FirstSineZero { dof } = phase;
    let phase_error = match layout.amplitude(&coeffs, 1, dof) {
        Some(a) if a > 0.0 => coeffs[phase.index(&layout)?].abs() / a,
        _ => f64::INFINITY,
    };
    let converged = converged || (residual <= ACCEPTED_RESIDUAL && phase_error <= ACCEPTED_PHASE);
    let mut mbp = mb.clone();
    mbp.mu = mu;
    let point = BranchPoint {
        parameter: mu,
        omega,
        harmonics: layout.n_harmonics(),
        pairs: pair_cycles(&mbp, &layout, &coeffs),
        truncation: truncation(&layout, &coeffs),
        nl_coeffs: coeffs,
        parameter_rate: 0.0,
        iterations,
        residual,
    };
    let margin = point_margin(&mbp, &point, &speeds)?;
    let reversed_fractions = reversed_fractions(mb, &layout, &point.nl_coeffs, point.omega)?;
    Ok(DlftCycle {
        reversed_fractions,
        stick_fractions: b.stick_fractions(),
        margin,
        epsilon,
        samples: b.n_samples(),
        converged,
        phase_error,
        point,
    })
}

/// The regularized cycle of `mb` at `mu` with every pair made to stick at `v_reg`
/// ([`crate::stick_branch::sticking_brake`]), with `opts`' harmonics (`None`: the guess's), AFT samples
/// and Levenberg–Marquardt controls (its ε is not used; nor its Gauss–Newton steps),
/// from `guess` (padded or truncated), at fixed μ: for the convergence of the regularized law
/// towards DLFT as `v_reg → 0` (docs/stick_slip.md). The rows are scaled as [`dlft_cycle`]'s.
pub fn regularized_cycle(
    mb: &ModalBrake,
    mu: f64,
    v_reg: f64,
    guess: &BranchPoint,
    phase_dof: usize,
    opts: &DlftOptions,
) -> Result<(BranchPoint, bool), StickError> {
    let mut smb = crate::stick_branch::sticking_brake(mb, v_reg)?;
    smb.mu = mu;
    let harmonics = opts.harmonics.unwrap_or(guess.harmonics);
    let mut hb = crate::branch::brake_harmonic_balance(&smb, harmonics, opts.samples)?;
    let layout = hb.layout();
    let mut z0 = vec![0.0; layout.len()];
    let m = guess.nl_coeffs.len().min(z0.len());
    z0[..m].copy_from_slice(&guess.nl_coeffs[..m]);
    layout.align_phase(&mut z0, phase_dof)?;
    let scales = squeal_hbm::RowScales {
        force: force_scale(mb, &z0),
        phase: 1e-6,
    };
    z0.push(guess.omega);
    let phase = PhaseCondition::FirstSineZero { dof: phase_dof };
    let mut problem = squeal_hbm::AutonomousProblem::constrained(
        &mut hb,
        phase,
        squeal_hbm::Unconstrained,
        scales,
    )?;
    // The damped iteration alone (no Gauss–Newton steps, whatever `opts` says): the
    // regularized cycles and their figures stay what they were (docs/stick_slip.md; with
    // Gauss–Newton steps first the V/20 start at 1.0649 μ0 did not converge in 40 iterations).
    let mut lm = opts.lm.clone();
    lm.newton_damping = 0.0;
    let (report, converged) = match squeal_hbm::lm::solve(&mut problem, &z0, &lm) {
        Ok(r) => (r, true),
        Err(squeal_hbm::LmError::NotConverged { report }) => (*report, false),
        Err(squeal_hbm::LmError::Problem(e)) => return Err(e.into()),
        Err(_) => return Err(StickError::BadOption("Levenberg-Marquardt failed to start")),
    };
    let len = layout.len();
    let u = report.x[..len].to_vec();
    let point = BranchPoint {
        parameter: mu,
        omega: report.x[len],
        harmonics: layout.n_harmonics(),
        pairs: pair_cycles(&smb, &layout, &u),
        truncation: truncation(&layout, &u),
        nl_coeffs: u,
        parameter_rate: 0.0,
        iterations: report.iterations,
        residual: report.residual_norm,
    };
    Ok((point, converged))
}
