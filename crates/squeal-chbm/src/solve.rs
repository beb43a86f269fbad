//! Eqs (46)–(48): the unknowns `(U~_nl, ω)`, the residual `[f1; phase; f2]`, the initial guess
//! from the unstable mode, and the Levenberg–Marquardt solve.
//!
//! **Residual.** `f1` (eq 46) is the condensed harmonic balance residual scaled by the static
//! load's norm; the phase condition `U1s[d] = 0` (one pad contact dof `d` that moves in the
//! unstable mode) removes the time-shift invariance; `f2` (eq 47) is `Re λ / ω0` of the tracked
//! eigenvalue of the equivalent linearization, times a weight. It is signed (its square is
//! `|Re λ|²`), which keeps the least-squares problem smooth.
//!
//! **Why the constraint works.** At the static solution `f1 = 0` but `Re λ > 0` (it is
//! unstable), so with `f2` the static point is not a zero of the residual. With the fundamental
//! fit of [`crate::constraint::Fit`], `f2 = 0` holds exactly at every root of the harmonic
//! balance, so `[f1; phase; f2]` has an exact zero at the limit cycle and Levenberg–Marquardt
//! converges on both `eps1` and `eps2` (with the literal stiffness-only fit `f2` is only nearly
//! zero there, and the solve ends at a least-squares compromise: reported as not converged).
//!
//! **Harmonic ladder.** From eq (48) the solve converges when the guess's amplitude `p` is near
//! the limit cycle's. With [`ChbmOptions::ladder`] (default) it first solves with one harmonic,
//! whose basin is wide, then with all harmonics from that solution.

use crate::condensed::{CondensedStiffness, condensed_load, recover};
use crate::constraint::{
    Eigenproblem, EquivalentLinearization, Fit, Tracked, equivalent_linearization,
};
use crate::contact::ContactForce;
use faer::reborrow::ReborrowMut;
use faer::{Mat, MatMut, c64};
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::lm::{self, LeastSquaresProblem, LmError, LmIteration, LmOptions, LmStop};
use squeal_hbm::{HarmonicBalance, HarmonicLayout, HbmError, NonlinearForce, Part};
use std::time::{Duration, Instant};

/// Errors of a CHBM solve (a solve that runs but does not converge is not an error: see
/// [`Outcome`]).
#[derive(Debug, thiserror::Error)]
pub enum ChbmError {
    #[error(transparent)]
    Hbm(#[from] HbmError),
    #[error("{0}")]
    Invalid(String),
}

/// Options of [`solve`].
#[derive(Clone, Debug, PartialEq)]
pub struct ChbmOptions {
    pub harmonics: usize,
    /// AFT time samples (default: [`squeal_hbm::default_samples`]).
    pub samples: Option<usize>,
    /// Initial amplitude `p` of eq (48): the largest normal motion of the contact pairs in the
    /// guess, as a fraction of the smallest static penetration.
    pub amplitude: f64,
    /// Weight of `f2` in stage 1.
    pub weight: f64,
    /// Converged when `||f1|| <= eps1 ||F_eq||` ...
    pub eps1: f64,
    /// ... and `|Re λ| <= eps2 ω`.
    pub eps2: f64,
    pub max_iterations: usize,
    /// Harmonic ladder: solve with one harmonic first (from eq 48), then with all of them
    /// from that solution (the paper's "starting from previous results").
    pub ladder: bool,
    /// The equivalent linearization of eq (45).
    pub fit: Fit,
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
            fit: Fit::Fundamental,
        }
    }
}

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
    /// `f1` converged but `|Re λ| > eps2 ω` at the root.
    LimitCycleUnconstrained,
    /// The solver landed on the static (trivial) solution.
    Static,
    /// No convergence.
    NotConverged,
}

impl std::fmt::Display for Outcome {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Outcome::LimitCycle => "limit cycle (converged on eps1 and eps2)",
            Outcome::LimitCycleUnconstrained => {
                "limit cycle of the harmonic balance, but |Re lambda| above eps2"
            }
            Outcome::Static => "static solution (the oscillation died out): not a limit cycle",
            Outcome::NotConverged => "not converged",
        })
    }
}

/// One residual evaluation of the solve (for the histories of Figures 6–7).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Evaluation {
    /// Harmonics of the solve that made it (the ladder's first solve has one).
    pub harmonics: usize,
    /// `||f1|| / ||F_eq||`.
    pub f1: f64,
    pub re_lambda: f64,
    pub omega: f64,
}

/// A CHBM result.
#[derive(Clone, Debug)]
pub struct ChbmSolution {
    pub outcome: Outcome,
    pub harmonics: usize,
    pub samples: usize,
    pub omega: f64,
    /// Fourier coefficients of the nonlinear dofs (layout of eq 25).
    pub nl_coeffs: Vec<f64>,
    /// Fourier coefficients of every physical dof (eq 35), same layout over all dofs.
    pub coeffs: Vec<f64>,
    pub nl_dofs: Vec<usize>,
    /// `||f1|| / ||F_eq||` and `Re λ` at the solution.
    pub f1: f64,
    pub re_lambda: f64,
    pub lambda: c64,
    /// LM trial steps (all solves of the ladder).
    pub iterations: usize,
    pub stop: Option<LmStop>,
    pub lm_history: Vec<LmIteration>,
    pub evaluations: Vec<Evaluation>,
    pub open_fraction: Vec<f64>,
    /// Relative change of `F~_nl` when the samples are doubled (aliasing check).
    pub aliasing: f64,
    /// Largest `|x_n - U_n|` of the recovered nonlinear dofs relative to their amplitude.
    pub recovery_error: f64,
    pub time: Duration,
}

impl ChbmSolution {
    /// The cycle of every physical dof (velocities by differentiating eq 23).
    pub fn cycle(&self) -> crate::cycle::CycleCoefficients {
        let n = self.coeffs.len() / (2 * self.harmonics + 1);
        crate::cycle::CycleCoefficients::from_displacement(
            self.harmonics,
            self.omega,
            n,
            self.coeffs.clone(),
        )
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

/// The least-squares problem of eqs (46)–(47).
struct Problem {
    hb: HarmonicBalance<CondensedStiffness, ContactForce>,
    eig: Eigenproblem,
    mb: ModalBrake,
    layout: HarmonicLayout,
    phase: usize,
    f_scale: f64,
    x_scale: f64,
    w_scale: f64,
    weight: f64,
    fit: Fit,
    lambda: c64,
    last: Option<(Vec<f64>, EquivalentLinearization, Tracked)>,
    evaluations: Vec<Evaluation>,
    r1: Vec<f64>,
    /// `dr1/dω` of the Jacobian (scratch).
    jw: Vec<f64>,
}

impl Problem {
    fn len(&self) -> usize {
        self.layout.len()
    }

    /// Equivalent linearization and tracked eigenvalue at the samples of the last AFT call.
    fn constraint(&mut self, z: &[f64]) -> Result<(EquivalentLinearization, Tracked), HbmError> {
        let omega = z[self.len()];
        let eql = equivalent_linearization(
            &self.mb,
            &self.layout,
            &self.hb.aft().samples(),
            omega,
            self.fit,
        );
        let tracked = match self.eig.track(&eql.k, &eql.c, self.lambda) {
            Ok(t) => t,
            Err(e) => {
                // Fall back on the full spectrum: the eigenvalue nearest the last one.
                let near = full_spectrum(&self.eig, &self.mb, &eql)
                    .into_iter()
                    .min_by(|a, b| {
                        (a - self.lambda)
                            .norm()
                            .total_cmp(&(b - self.lambda).norm())
                    })
                    .unwrap_or(self.lambda);
                self.eig.track(&eql.k, &eql.c, near).map_err(|_| {
                    let _ = e;
                    HbmError::NonFiniteInput {
                        what: "tracked eigenvalue",
                    }
                })?
            }
        };
        self.lambda = tracked.lambda;
        let _ = z;
        Ok((eql, tracked))
    }
}

impl LeastSquaresProblem for Problem {
    type Error = HbmError;

    fn n_params(&self) -> usize {
        self.len() + 1
    }

    fn n_residuals(&self) -> usize {
        self.len() + 1 + usize::from(self.weight > 0.0)
    }

    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), HbmError> {
        let l = self.len();
        let (u, omega) = (&z[..l], z[l]);
        self.hb.residual(u, omega, &mut self.r1)?;
        let mut f1 = 0.0;
        for i in 0..l {
            r[i] = self.r1[i] / self.f_scale;
            f1 += r[i] * r[i];
        }
        r[l] = u[self.phase] / self.x_scale;
        let (eql, tracked) = self.constraint(z)?;
        if self.weight > 0.0 {
            r[l + 1] = self.weight * tracked.lambda.re / self.w_scale;
        }
        self.evaluations.push(Evaluation {
            harmonics: self.layout.n_harmonics(),
            f1: f1.sqrt(),
            re_lambda: tracked.lambda.re,
            omega,
        });
        self.last = Some((z.to_vec(), eql, tracked));
        Ok(())
    }

    fn jacobian(&mut self, z: &[f64], mut jac: MatMut<'_, f64>) -> Result<(), HbmError> {
        let l = self.len();
        let (u, omega) = (&z[..l], z[l]);
        // The f1 block is written in place and scaled after.
        self.hb.jacobian(
            u,
            omega,
            jac.rb_mut().submatrix_mut(0, 0, l, l),
            &mut self.jw,
        )?;
        let inv = 1.0 / self.f_scale;
        for j in 0..l {
            for v in jac.rb_mut().col_mut(j).subrows_mut(0, l).iter_mut() {
                *v *= inv;
            }
        }
        for i in 0..l {
            jac[(i, l)] = self.jw[i] * inv;
        }
        for j in 0..=l {
            jac[(l, j)] = 0.0;
        }
        jac[(l, self.phase)] = 1.0 / self.x_scale;
        if self.weight > 0.0 {
            // The constraint at z: LM asks for the Jacobian at the last accepted trial, whose
            // residual call already evaluated it (the AFT samples then and now are those of z).
            let cached = self.last.take().filter(|(zl, _, _)| zl.as_slice() == z);
            let (eql, tracked) = match cached {
                Some((_, eql, tracked)) => (eql, tracked),
                None => self.constraint(z)?,
            };
            for j in 0..l {
                let mut d = 0.0;
                for p in 0..eql.k.len() {
                    d += tracked.dlambda_dk[p].re * eql.dk[p][j]
                        + tracked.dlambda_dc[p].re * eql.dc[p][j];
                }
                jac[(l + 1, j)] = self.weight * d / self.w_scale;
            }
            // The fit depends on ω through c = Im κ / ω only.
            let dw: f64 = (0..eql.k.len())
                .map(|p| tracked.dlambda_dc[p].re * eql.dc_domega[p])
                .sum();
            jac[(l + 1, l)] = self.weight * dw / self.w_scale;
            self.last = Some((z.to_vec(), eql, tracked));
        }
        Ok(())
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

/// One CHBM solve, from eq (48) or from a solution with fewer harmonics.
pub fn solve_from(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &ChbmOptions,
    previous: Option<&ChbmSolution>,
) -> Result<ChbmSolution, ChbmError> {
    let t0 = Instant::now();
    let nn = mb.nl();
    if opts.harmonics == 0 {
        return Err(ChbmError::Invalid("at least one harmonic is needed".into()));
    }
    if start.mode.len() != mb.modes() || start.equilibrium.len() != mb.modes() {
        return Err(ChbmError::Invalid(
            "the start's mode and equilibrium must cover every dof".into(),
        ));
    }
    let layout = HarmonicLayout::new(nn, opts.harmonics)?;
    let mut stiffness = CondensedStiffness::new(mb, opts.harmonics);
    let omega0 = start.lambda.im;
    stiffness.update(omega0);
    let f_eq = condensed_load(mb, &mut stiffness, &layout);
    let force = ContactForce::new(mb);
    let hb = HarmonicBalance::new(layout, stiffness, force, f_eq.clone(), opts.samples)?;
    let samples = hb.aft().n_samples();
    let (z0, omega0) = match previous {
        None => (initial_guess(mb, start, &layout, opts.amplitude)?, omega0),
        Some(p) => {
            // Pad the lower-order solution with zero harmonics (the layouts share their leading blocks).
            let mut u = vec![0.0; layout.len()];
            let m = p.nl_coeffs.len().min(u.len());
            u[..m].copy_from_slice(&p.nl_coeffs[..m]);
            (u, p.omega)
        }
    };
    let phase = layout
        .index(1, Part::Sin, phase_dof(mb, &z0, &layout))
        .unwrap_or(0);
    let f_scale = force_scale(mb, start, &f_eq);
    let x_scale = mb
        .pairs
        .iter()
        .map(|p| p.penetration(&z0[..nn]))
        .fold(f64::INFINITY, f64::min)
        .abs()
        .max(1e-12);
    let mut problem = Problem {
        hb,
        eig: Eigenproblem::new(mb),
        mb: mb.clone(),
        layout,
        phase,
        f_scale,
        x_scale,
        w_scale: omega0.abs().max(f64::MIN_POSITIVE),
        weight: opts.weight,
        fit: opts.fit,
        lambda: previous.map_or(start.lambda, |p| p.lambda),
        last: None,
        evaluations: Vec::new(),
        r1: vec![0.0; layout.len()],
        jw: vec![0.0; layout.len()],
    };
    let mut z = z0.clone();
    z.push(omega0);
    let lm_opts = LmOptions {
        abs_tol: opts.eps1,
        rel_tol: 0.0,
        max_iterations: opts.max_iterations,
        accept_stationary: true,
        ..LmOptions::default()
    };
    let (z1, stop, iterations, lm_history) = run(&mut problem, &z, &lm_opts);
    z = z1;
    // Final evaluation at z (residual, samples, constraint).
    let l = layout.len();
    let mut r = vec![0.0; problem.n_residuals()];
    problem.residual(&z, &mut r)?;
    let f1 = (0..l).map(|i| r[i] * r[i]).sum::<f64>().sqrt();
    let (_, eql, tracked) = problem
        .last
        .clone()
        .ok_or_else(|| ChbmError::Invalid("no evaluation".into()))?;
    let omega = z[l];
    let u = z[..l].to_vec();
    // Aliasing: the same force coefficients with twice the samples.
    let aliasing = aliasing_check(mb, &layout, &u, omega, samples)?;
    let g = problem.hb_force_coefficients(&u, omega)?;
    let coeffs = recover(mb, opts.harmonics, omega, &g, &layout);
    let recovery_error = recovery_error(&layout, &u, &coeffs, &mb.nl_dofs, mb.modes());
    let amp: f64 = (0..nn)
        .map(|i| layout.amplitude(&u, 1, i).unwrap_or(0.0))
        .fold(0.0, f64::max);
    let amp0: f64 = (0..nn)
        .map(|i| layout.amplitude(&z0, 1, i).unwrap_or(0.0))
        .fold(0.0, f64::max);
    let converged_f1 = f1 <= opts.eps1;
    let outcome = if amp <= 1e-6 * amp0 {
        Outcome::Static
    } else if !converged_f1 {
        Outcome::NotConverged
    } else if tracked.lambda.re.abs() <= opts.eps2 * omega.abs() {
        Outcome::LimitCycle
    } else {
        Outcome::LimitCycleUnconstrained
    };
    Ok(ChbmSolution {
        outcome,
        harmonics: opts.harmonics,
        samples,
        omega,
        nl_coeffs: u,
        coeffs,
        nl_dofs: mb.nl_dofs.clone(),
        f1,
        re_lambda: tracked.lambda.re,
        lambda: tracked.lambda,
        iterations,
        stop,
        lm_history,
        evaluations: problem.evaluations,
        open_fraction: eql.open_fraction,
        aliasing,
        recovery_error,
        time: t0.elapsed(),
    })
}

/// Eigenvalues (upper half plane) of `J` for a given equivalent linearization, by a dense
/// eigen-decomposition of the state matrix: the check and fallback of the tracking.
pub fn full_spectrum(
    eig: &Eigenproblem,
    mb: &ModalBrake,
    eql: &EquivalentLinearization,
) -> Vec<c64> {
    let n = mb.modes();
    let (dk, dc) = eig.modal_change(&eql.k, &eql.c);
    let a = Mat::<f64>::from_fn(2 * n, 2 * n, |i, j| match (i < n, j < n) {
        (true, true) => 0.0,
        (true, false) => f64::from(u8::from(i == j - n)),
        (false, true) => -(if i - n == j { mb.omega[j].powi(2) } else { 0.0 } + dk[(i - n, j)]),
        (false, false) => -(if i == j { mb.damping[i - n] } else { 0.0 } + dc[(i - n, j - n)]),
    });
    match a.eigen() {
        Ok(e) => (0..2 * n)
            .map(|i| e.S()[i])
            .filter(|v| v.im > 0.0)
            .collect(),
        Err(_) => Vec::new(),
    }
}

impl Problem {
    /// `F~_nl - K_s U` (the force seen by the condensed problem) at `(u, ω)`.
    fn hb_force_coefficients(&mut self, u: &[f64], omega: f64) -> Result<Vec<f64>, HbmError> {
        let mut g = vec![0.0; self.len()];
        let force = ContactForce::new(&self.mb);
        self.hb.aft_mut().forces(&force, u, omega, &mut g)?;
        Ok(g)
    }
}

/// Runs LM; a non-converged run returns its last iterate (the caller classifies it).
fn run(
    problem: &mut Problem,
    z: &[f64],
    opts: &LmOptions,
) -> (Vec<f64>, Option<LmStop>, usize, Vec<LmIteration>) {
    match lm::solve(problem, z, opts) {
        Ok(rep) => (rep.x, Some(rep.stop), rep.iterations, rep.history),
        Err(LmError::NotConverged { report }) => (
            report.x,
            Some(report.stop),
            report.iterations,
            report.history,
        ),
        Err(_) => (z.to_vec(), None, 0, Vec::new()),
    }
}

/// Eq (48): `Y0 = p (Ψ e^{λt} + Ψ̄ e^{λ̄t})` over one period, as Fourier coefficients of the
/// nonlinear dofs around the static equilibrium: `U0 = x0`, `U1c = 2p Re Ψ`, `U1s = -2p Im Ψ`.
fn initial_guess(
    mb: &ModalBrake,
    start: &ChbmStart,
    layout: &HarmonicLayout,
    amplitude: f64,
) -> Result<Vec<f64>, ChbmError> {
    let nn = mb.nl();
    let psi: Vec<c64> = mb.nl_dofs.iter().map(|&d| start.mode[d]).collect();
    let x0: Vec<f64> = mb.nl_dofs.iter().map(|&d| start.equilibrium[d]).collect();
    let (mut dmax, mut pen) = (0.0f64, f64::INFINITY);
    for p in &mb.pairs {
        let g: c64 = p.normal.iter().map(|&(i, a)| psi[i] * a).sum();
        dmax = dmax.max(2.0 * g.norm());
        pen = pen.min(p.penetration(&x0));
    }
    let positive = |v: f64| v > 0.0; // false for NaN too
    if !positive(dmax) || !positive(pen) {
        return Err(ChbmError::Invalid(
            "the unstable mode does not move the contact, or the contact is open at equilibrium"
                .into(),
        ));
    }
    let p = amplitude * pen / dmax;
    let mut u = vec![0.0; layout.len()];
    for i in 0..nn {
        u[i] = x0[i];
        if let (Some(c), Some(s)) = (layout.index(1, Part::Cos, i), layout.index(1, Part::Sin, i)) {
            u[c] = 2.0 * p * psi[i].re;
            u[s] = -2.0 * p * psi[i].im;
        }
    }
    let d = phase_dof(mb, &u, layout);
    layout.align_phase(&mut u, d)?;
    Ok(u)
}

/// The normal dof of a pair with the largest first harmonic.
fn phase_dof(mb: &ModalBrake, u: &[f64], layout: &HarmonicLayout) -> usize {
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

fn aliasing_check(
    mb: &ModalBrake,
    layout: &HarmonicLayout,
    u: &[f64],
    omega: f64,
    samples: usize,
) -> Result<f64, ChbmError> {
    let force = ContactForce::new(mb);
    let mut a = squeal_hbm::Aft::new(*layout, samples)?;
    let mut b = squeal_hbm::Aft::new(*layout, 2 * samples)?;
    let (mut fa, mut fb) = (vec![0.0; layout.len()], vec![0.0; layout.len()]);
    a.forces(&force, u, omega, &mut fa)?;
    b.forces(&force, u, omega, &mut fb)?;
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
    let scale = (0..u.len())
        .filter(|i| *i >= nn)
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

/// Largest relative difference between the analytic Jacobian of the stage-1 residual
/// `[f1; phase; f2]` and central finite differences, at the initial guess (eq 48): for tests
/// and diagnostics. Returns `(worst over the f1 rows, worst over the f2 row)`.
/// The force scale of `f1`'s tolerance: the larger of the condensed static load and the
/// static contact forces. A brake held only by a preloading gap (no piston force) has a zero
/// load but not zero contact forces.
fn force_scale(mb: &ModalBrake, start: &ChbmStart, f_eq: &[f64]) -> f64 {
    let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
    let x: Vec<f64> = mb.nl_dofs.iter().map(|&d| start.equilibrium[d]).collect();
    let mut f = vec![0.0; x.len()];
    ContactForce::new(mb).eval(&x, &vec![0.0; x.len()], &mut f, None);
    norm(f_eq).max(norm(&f)).max(f64::MIN_POSITIVE)
}

pub fn check_jacobian(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &ChbmOptions,
) -> Result<(f64, f64), ChbmError> {
    let nn = mb.nl();
    let layout = HarmonicLayout::new(nn, opts.harmonics)?;
    let mut stiffness = CondensedStiffness::new(mb, opts.harmonics);
    let omega0 = start.lambda.im;
    stiffness.update(omega0);
    let f_eq = condensed_load(mb, &mut stiffness, &layout);
    let hb = HarmonicBalance::new(
        layout,
        stiffness,
        ContactForce::new(mb),
        f_eq.clone(),
        opts.samples,
    )?;
    let z0 = initial_guess(mb, start, &layout, opts.amplitude)?;
    let phase = layout
        .index(1, Part::Sin, phase_dof(mb, &z0, &layout))
        .unwrap_or(0);
    let mut problem = Problem {
        hb,
        eig: Eigenproblem::new(mb),
        mb: mb.clone(),
        layout,
        phase,
        f_scale: force_scale(mb, start, &f_eq),
        x_scale: 1e-6,
        w_scale: omega0,
        weight: 1.0,
        fit: opts.fit,
        lambda: start.lambda,
        last: None,
        evaluations: Vec::new(),
        r1: vec![0.0; layout.len()],
        jw: vec![0.0; layout.len()],
    };
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
