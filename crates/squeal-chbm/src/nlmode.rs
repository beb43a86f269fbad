//! Complex nonlinear modes of a friction system by the extended periodic motion concept
//! (EPMC; Krack, "Nonlinear modal analysis of nonconservative systems: extension of the
//! periodic motion concept", Computers & Structures 154, 2015; NLvib's `HB_residual`,
//! analysis type `'nma'`): the squeal mode at a fixed μ continued in its amplitude, with its
//! frequency ω and modal damping ratio ζ as unknowns.
//!
//! **The artificial damping.** The brake's eq (11), `M x'' + C x' + K x + F_nl(x, x') = F`, has
//! no periodic motion of the squeal mode at a given amplitude unless that amplitude is a limit
//! cycle: below it the motion grows, above it decays. The EPMC adds the term that makes every
//! amplitude periodic,
//!
//! `M x'' + (C - 2ζω M) x' + K x + F_nl(x, x') = F`,
//!
//! a viscous damping proportional to the **mass** matrix, of rate `-2ζω` (NLvib:
//! `D = D - 2 Om del M`). Why mass-proportional: writing the decaying motion as
//! `x = e^{-ζωt} y` with `y` periodic turns `M x''` into `M (y'' - 2ζω y' + ζ²ω² y)`; the term
//! `-2ζω M y'` is the leading one, the others (`ζ²ω² M y`, `-ζω C y`) are of second order in
//! the damping and dropped. For a linear system with mass-proportional `C` (or none) the
//! linear limit is exact (module [`linear`]: `ω²`, `ζ` from `λ (λ + c)`); in general it differs
//! from the eigenvalue by `O(ζ |D| / ω)`. At `ζ = 0` the term vanishes: **every motion with
//! `ζ = 0` is an exact periodic solution of eq (11)**, i.e. a limit cycle, whatever the
//! approximation elsewhere. In modal coordinates (`Φᵀ M Φ = I`, eq 12) the term shifts the
//! modal damping `D` by `-2ζω I`.
//!
//! **The equations.** The motion is the truncated series of eq (23) on the nonlinear dofs; the
//! linear dofs are condensed exactly as for CHBM (eq 32), with the shifted damping in each
//! harmonic's `Δ_k = Ω² - (kω)² + ikω (D - 2ζω I)`: the harmonic balance residual `f1` of
//! eq (34) (`Λ_eq(ω, ζ) U + F~_nl(U, ω) - F_eq`, `F~_nl` by the AFT of eq 29). The unknowns are
//! `[U~, ω, ζ]`; two equations join the `(2H + 1) n_nl` of `f1`:
//!
//! * phase: `U1s[d] = 0` on the contact normal dof `d` of largest motion in the mode;
//! * amplitude: `|q_1| = a`, where `q_1 = Δ_1⁻¹ Φ_nᵀ Λ_eq,1 (U1c - i U1s)` is the complex
//!   fundamental of **every** mode (eq 35 for `k = 1`) and `|q_1|² = q_1ᴴ (ΦᵀMΦ) q_1`: the
//!   fundamental's modal mass, as NLvib's normalization `Ψ_1ᴴ M Ψ_1 = 1` with `Q = a Ψ`. The
//!   modal amplitude `a` (m·kg^½) is the continuation parameter, on a logarithmic scale.
//!
//! The system is square; it is solved by Levenberg–Marquardt (module [`epmc`]: the analytic
//! Jacobian). The static rows of `f1` are scaled by the static force level (as CHBM's), the
//! harmonics' rows by the motion's own force level, that level times the motion's largest
//! displacement over the smallest static penetration: the tolerance then means the same
//! relative accuracy at every amplitude (with the static scale alone, a motion 1e-5 of the
//! penetration would meet any tolerance at its first guess). As `a → 0` the force tends to its tangent and `(ω, ζ)` to the linear mode of
//! [`linear`], which is where the continuation starts (`U1 = a ψ`).
//!
//! **What it gives.** `ω(a)`, `ζ(a)` and the harmonics `U~(a)`: one computation, all
//! amplitudes. A limit cycle of the brake at this μ is a root of `ζ(a)`; it is refined by
//! regula falsi (Illinois) in `ln a` on `ζ`, each evaluation an EPMC solve, until
//! `|ζ| <= 1e-13`. It is stable when `dζ/da > 0` there (a larger motion is damped, a smaller one
//! grows). Near `a = 0`, `ζ(a) = ζ0 + ζ2 a² + O(a⁴)` (harmonic balance is odd in the
//! amplitude's sign up to a time shift); `ζ2 > 0` means the cycles that the normal form's cubic
//! term predicts exist where the equilibrium is unstable (`ζ0 < 0`): **supercritical**, the
//! sign of `-l1` (`l1` the first Lyapunov coefficient, [`squeal_brake::criticality`]).

pub mod epmc;
pub mod linear;

use crate::solve::{ChbmStart, force_scale_at, phase_dof};
use epmc::{EpmcProblem, EpmcScales, EpmcStiffness};
use faer::c64;
use linear::{LinearMode, LinearModeError, linear_mode};
use squeal_brake::criticality::Criticality;
use squeal_brake::harmonic::{CondensedStiffness, ContactForce, condensed_load};
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::lm::{LmError, LmOptions, solve as lm_solve};
use squeal_hbm::{HarmonicBalance, HarmonicLayout, HbmError};
use std::time::{Duration, Instant};

/// Why a nonlinear mode could not be computed (a continuation that stops early is not an
/// error: see [`NonlinearMode::stopped`]).
#[derive(Debug, thiserror::Error)]
pub enum NlModeError {
    /// The harmonic balance machinery refused the problem.
    #[error(transparent)]
    Hbm(#[from] HbmError),
    /// The linear mode at the equilibrium.
    #[error(transparent)]
    Linear(#[from] LinearModeError),
    /// No harmonic asked for.
    #[error("the nonlinear mode needs at least one harmonic")]
    NoHarmonics,
    /// The amplitudes are not positive, finite and increasing.
    #[error(
        "the amplitudes must be positive, finite and increasing (got {0}): give e.g. 0.01..2 as fractions of the opening amplitude"
    )]
    BadAmplitudes(String),
    /// The start's sizes do not match the modal brake, or the mode does not move a closed pair.
    #[error(
        "the mode does not move a closed contact pair (or the start does not fit the brake): no opening amplitude to scale the mode by"
    )]
    NoContactMotion,
    /// The first point (smallest amplitude) did not converge.
    #[error(
        "the nonlinear mode did not converge at its smallest amplitude a = {a:.4e}: start from a smaller amplitude"
    )]
    FirstPoint {
        /// The amplitude.
        a: f64,
    },
}

/// Options of [`nonlinear_mode`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct NlModeOptions {
    /// Harmonics `H` (default 3, as CHBM's).
    pub harmonics: usize,
    /// AFT samples (default [`squeal_hbm::default_samples`]).
    pub samples: Option<usize>,
    /// The amplitudes `a` as fractions of the opening amplitude (the `a` at which the linear
    /// mode opens its first contact pair), increasing (default 40 points from 0.01 to 2,
    /// log-spaced).
    pub amplitudes: Vec<f64>,
    /// Levenberg–Marquardt's tolerance on the scaled residual (default 1e-10).
    pub tolerance: f64,
    /// LM trial steps per point (default 60).
    pub max_iterations: usize,
    /// Halvings of a failed step in `ln a` before the continuation stops (default 4).
    pub max_halvings: usize,
}

/// `n` log-spaced values from `from` to `to`.
pub fn log_spaced(from: f64, to: f64, n: usize) -> Vec<f64> {
    let n = n.max(2);
    (0..n)
        .map(|i| (from.ln() + (to / from).ln() * i as f64 / (n - 1) as f64).exp())
        .collect()
}

impl Default for NlModeOptions {
    fn default() -> Self {
        Self {
            harmonics: 3,
            samples: None,
            amplitudes: log_spaced(0.01, 2.0, 40),
            tolerance: 1e-10,
            max_iterations: 60,
            max_halvings: 4,
        }
    }
}

/// One point of the nonlinear mode.
#[derive(Clone, Debug, PartialEq)]
pub struct NlModePoint {
    /// Modal amplitude `a = |q_1|` (m·kg^½).
    pub a: f64,
    /// ω (rad/s).
    pub omega: f64,
    /// Modal damping ratio ζ (negative: the motion grows).
    pub zeta: f64,
    /// `|r|` of the scaled residual at the solution.
    pub residual: f64,
    /// LM trial steps.
    pub iterations: usize,
    /// Fourier coefficients of the nonlinear dofs (eq 25).
    pub coeffs: Vec<f64>,
}

/// A limit cycle read from the nonlinear mode: a root of `ζ(a)`.
#[derive(Clone, Debug, PartialEq)]
pub struct ZeroDamping {
    /// The point at `ζ ≈ 0`.
    pub point: NlModePoint,
    /// `dζ/da` there from the bracketing points (> 0: a stable cycle).
    pub slope: f64,
    /// EPMC solves of the refinement.
    pub solves: usize,
}

impl ZeroDamping {
    /// Stable when a larger motion is damped (`dζ/da > 0`).
    pub fn stable(&self) -> bool {
        self.slope > 0.0
    }
}

/// The nonlinear mode at one μ.
#[derive(Clone, Debug)]
pub struct NonlinearMode {
    /// The brake's eigenvalue it started from (s⁻¹, rad/s).
    pub lambda: c64,
    /// The linear limit (module [`linear`]).
    pub linear: LinearMode,
    /// The amplitude at which the linear mode opens its first pair.
    pub opening_amplitude: f64,
    /// The nonlinear dof of the phase condition.
    pub phase_dof: usize,
    /// Harmonics and AFT samples.
    pub harmonics: usize,
    /// AFT samples per period.
    pub samples: usize,
    /// The points, by increasing amplitude.
    pub points: Vec<NlModePoint>,
    /// The limit cycles (roots of ζ), by increasing amplitude.
    pub cycles: Vec<ZeroDamping>,
    /// Why the continuation stopped before the last amplitude asked, if it did.
    pub stopped: Option<String>,
    /// Wall time.
    pub time: Duration,
}

impl NonlinearMode {
    /// `ζ2 = dζ/d(a²)` from the first two points (the small-amplitude slope).
    pub fn zeta2(&self) -> Option<f64> {
        let [p, q] = [self.points.first()?, self.points.get(1)?];
        Some((q.zeta - p.zeta) / (q.a * q.a - p.a * p.a))
    }

    /// The Hopf point's criticality read from [`Self::zeta2`]: super when ζ grows with the
    /// amplitude.
    pub fn criticality(&self) -> Criticality {
        match self.zeta2() {
            Some(s) if s > 0.0 => Criticality::Supercritical,
            Some(s) if s < 0.0 => Criticality::Subcritical,
            _ => Criticality::Degenerate,
        }
    }
}

/// The pieces shared by every solve of one continuation.
struct Setup {
    hb: HarmonicBalance<EpmcStiffness, ContactForce>,
    layout: HarmonicLayout,
    phase_dof: usize,
    force: f64,
    /// `max |ψ|` on the nonlinear dofs per unit modal amplitude (the phase row's scale).
    psi_max: f64,
    /// The smallest static penetration of a closed pair (m).
    penetration: f64,
    options: LmOptions,
}

impl Setup {
    /// One EPMC solve at amplitude `a` from `z0 = [U~, ω, ζ]`.
    fn solve(&mut self, a: f64, z0: &[f64]) -> Result<Option<NlModePoint>, NlModeError> {
        // The harmonics' rows in the motion's own force level: the static force times the
        // motion's largest displacement over the smallest static penetration.
        let scales = EpmcScales {
            force: self.force,
            dynamic: self.force * (a * self.psi_max / self.penetration).min(1.0),
            phase: a * self.psi_max,
        };
        let mut problem = EpmcProblem::new(&mut self.hb, self.phase_dof, a, scales)?;
        let report = match lm_solve(&mut problem, z0, &self.options) {
            Ok(r) => r,
            // A predictor off the mode (a trial with a non-finite force at the start, or no
            // convergence) is a failed step, halved by the caller.
            Err(
                LmError::NotConverged { .. }
                | LmError::NonFiniteStart
                | LmError::NonFiniteJacobian { .. },
            ) => return Ok(None),
            Err(LmError::Problem(e)) => return Err(e.into()),
            Err(LmError::BadOption(s) | LmError::BadSize(s)) => {
                return Err(HbmError::BadOption(s).into());
            }
        };
        let len = self.layout.len();
        let z = &report.x;
        Ok(Some(NlModePoint {
            a,
            omega: z[len],
            zeta: z[len + 1],
            residual: report.residual_norm,
            iterations: report.iterations,
            coeffs: z[..len].to_vec(),
        }))
    }
}

/// `[U~, ω, ζ]` of a point.
fn unknowns(p: &NlModePoint) -> Vec<f64> {
    let mut z = p.coeffs.clone();
    z.extend([p.omega, p.zeta]);
    z
}

/// The guess at `a` from the points before it: the secant in `ln a` through the last two, or
/// the last one with its oscillating part scaled by the amplitude ratio.
fn predict(points: &[NlModePoint], a: f64, n_static: usize) -> Vec<f64> {
    let last = &points[points.len() - 1];
    if points.len() >= 2 {
        let prev = &points[points.len() - 2];
        let t = (a / last.a).ln() / (last.a / prev.a).ln();
        let (z1, z0) = (unknowns(last), unknowns(prev));
        return z1.iter().zip(&z0).map(|(b, a)| b + t * (b - a)).collect();
    }
    let mut z = unknowns(last);
    let r = a / last.a;
    let len = last.coeffs.len();
    for v in &mut z[n_static..len] {
        *v *= r;
    }
    z
}

/// The complex nonlinear mode of the modal brake `mb` at its μ, from the mode of `start` (its
/// equilibrium and eigenvalue: the squeal mode by [`crate::start::start_at`]), continued over
/// `opts.amplitudes`, with its limit cycles refined.
pub fn nonlinear_mode(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &NlModeOptions,
) -> Result<NonlinearMode, NlModeError> {
    let t0 = Instant::now();
    check_amplitudes(&opts.amplitudes)?;
    if opts.harmonics == 0 {
        return Err(NlModeError::NoHarmonics);
    }
    if start.equilibrium.len() != mb.modes() {
        return Err(NlModeError::NoContactMotion);
    }
    let nn = mb.nl();
    let x_n0: Vec<f64> = mb.nl_dofs.iter().map(|&d| start.equilibrium[d]).collect();
    let linear = linear_mode(mb, &x_n0, start.lambda)?;
    let layout = HarmonicLayout::new(nn, opts.harmonics)?;
    // The mode on the nonlinear dofs, ψ = Φ_n q (|q| = 1).
    let psi: Vec<c64> = (0..nn)
        .map(|i| {
            (0..mb.modes())
                .map(|j| linear.shape[j] * mb.phi_n[(i, j)])
                .sum()
        })
        .collect();
    let (opening, penetration, mut guess) = first_guess(mb, &layout, &x_n0, &psi)?;
    let d = phase_dof(mb, &guess, &layout);
    let rot = psi[d].conj() / psi[d].norm();
    for i in 0..nn {
        let v = psi[i] * rot;
        guess[nn + i] = v.re;
        guess[2 * nn + i] = -v.im;
    }
    let f_eq = condensed_load(mb, &CondensedStiffness::new(mb, opts.harmonics), &layout);
    let force = force_scale_at(mb, &x_n0, &f_eq);
    let hb = HarmonicBalance::new(
        layout,
        EpmcStiffness::new(mb, opts.harmonics),
        ContactForce::new(mb),
        f_eq,
        opts.samples,
    )?;
    let samples = hb.aft().n_samples();
    let mut setup = Setup {
        hb,
        layout,
        phase_dof: d,
        force,
        psi_max: psi.iter().map(|v| v.norm()).fold(0.0, f64::max),
        penetration,
        options: {
            let mut o = LmOptions::default();
            o.abs_tol = opts.tolerance;
            o.rel_tol = 0.0;
            o.max_iterations = opts.max_iterations;
            o
        },
    };
    let amplitudes: Vec<f64> = opts.amplitudes.iter().map(|f| f * opening).collect();
    let (points, stopped) =
        continue_over(&mut setup, &amplitudes, guess, &linear, opts.max_halvings)?;
    let cycles = zero_crossings(&mut setup, &points)?;
    Ok(NonlinearMode {
        lambda: start.lambda,
        linear,
        opening_amplitude: opening,
        phase_dof: d,
        harmonics: opts.harmonics,
        samples,
        points,
        cycles,
        stopped,
        time: t0.elapsed(),
    })
}

fn check_amplitudes(a: &[f64]) -> Result<(), NlModeError> {
    let ok = !a.is_empty()
        && a.iter().all(|v| v.is_finite() && *v > 0.0)
        && a.windows(2).all(|w| w[1] > w[0]);
    if ok {
        Ok(())
    } else {
        let list: Vec<String> = a.iter().map(|v| format!("{v}")).collect();
        Err(NlModeError::BadAmplitudes(list.join(", ")))
    }
}

/// The opening amplitude (the smallest static penetration over the largest normal motion of a
/// pair per unit modal amplitude), that penetration, and `[x_n0, Re ψ, -Im ψ, 0, ...]` per unit amplitude.
fn first_guess(
    mb: &ModalBrake,
    layout: &HarmonicLayout,
    x_n0: &[f64],
    psi: &[c64],
) -> Result<(f64, f64, Vec<f64>), NlModeError> {
    let nn = layout.n_dofs();
    let (mut dmax, mut pen) = (0.0f64, f64::INFINITY);
    for p in &mb.pairs {
        let g: c64 = p.normal.iter().map(|&(i, a)| psi[i] * a).sum();
        dmax = dmax.max(g.norm());
        let d = p.penetration(x_n0);
        if d > 0.0 {
            pen = pen.min(d);
        }
    }
    if !(dmax > 0.0 && pen > 0.0 && pen.is_finite()) {
        return Err(NlModeError::NoContactMotion);
    }
    let mut u = vec![0.0; layout.len()];
    u[..nn].copy_from_slice(x_n0);
    for i in 0..nn {
        u[nn + i] = psi[i].re;
        u[2 * nn + i] = -psi[i].im;
    }
    Ok((pen / dmax, pen, u))
}

/// The points over `amplitudes`, each from the prediction of the ones before; a failed step
/// is halved in `ln a` up to `max_halvings` times, then the continuation stops.
fn continue_over(
    setup: &mut Setup,
    amplitudes: &[f64],
    unit: Vec<f64>,
    linear: &LinearMode,
    max_halvings: usize,
) -> Result<(Vec<NlModePoint>, Option<String>), NlModeError> {
    let nn = setup.layout.n_dofs();
    let a0 = amplitudes[0];
    let mut z0 = unit;
    for v in &mut z0[nn..] {
        *v *= a0;
    }
    z0.extend([linear.omega, linear.zeta]);
    let first = setup
        .solve(a0, &z0)?
        .ok_or(NlModeError::FirstPoint { a: a0 })?;
    let mut points = vec![first];
    for &target in &amplitudes[1..] {
        let mut halvings = 0;
        loop {
            let last = points[points.len() - 1].a;
            let a = if halvings == 0 {
                target
            } else {
                last * (target / last).powf(0.5f64.powi(halvings as i32))
            };
            let z = predict(&points, a, nn);
            match setup.solve(a, &z)? {
                Some(p) => {
                    points.push(p);
                    if a == target {
                        break;
                    }
                    halvings = 0;
                }
                None if halvings < max_halvings => halvings += 1,
                None => {
                    let why = format!(
                        "no convergence from a = {last:.4e} towards {target:.4e} after {max_halvings} halvings of the step"
                    );
                    return Ok((points, Some(why)));
                }
            }
        }
    }
    Ok((points, None))
}

/// Every sign change of ζ between neighbouring points, refined by regula falsi (Illinois) in
/// `ln a` until `|ζ| <= 1e-13` (at most 40 solves).
fn zero_crossings(
    setup: &mut Setup,
    points: &[NlModePoint],
) -> Result<Vec<ZeroDamping>, NlModeError> {
    let mut cycles = Vec::new();
    for w in points.windows(2) {
        if w[0].zeta.signum() == w[1].zeta.signum() && w[1].zeta != 0.0 {
            continue;
        }
        let (mut lo, mut hi) = (w[0].clone(), w[1].clone());
        let (mut flo, mut fhi) = (lo.zeta, hi.zeta);
        let mut best = if lo.zeta.abs() < hi.zeta.abs() {
            lo.clone()
        } else {
            hi.clone()
        };
        let mut solves = 0;
        let mut side = 0i8;
        while best.zeta.abs() > 1e-13 && solves < 40 {
            let (x0, x1) = (lo.a.ln(), hi.a.ln());
            let x = x1 - fhi * (x1 - x0) / (fhi - flo);
            let a = x.exp();
            let t = (x - x0) / (x1 - x0);
            let (z0, z1) = (unknowns(&lo), unknowns(&hi));
            let z: Vec<f64> = z0.iter().zip(&z1).map(|(p, q)| p + t * (q - p)).collect();
            solves += 1;
            let Some(p) = setup.solve(a, &z)? else {
                break;
            };
            if p.zeta.abs() < best.zeta.abs() {
                best = p.clone();
            }
            if p.zeta.signum() == lo.zeta.signum() {
                lo = p;
                flo = lo.zeta;
                if side == -1 {
                    fhi *= 0.5;
                }
                side = -1;
            } else {
                hi = p;
                fhi = hi.zeta;
                if side == 1 {
                    flo *= 0.5;
                }
                side = 1;
            }
        }
        cycles.push(ZeroDamping {
            slope: (w[1].zeta - w[0].zeta) / (w[1].a - w[0].a),
            point: best,
            solves,
        });
    }
    Ok(cycles)
}
