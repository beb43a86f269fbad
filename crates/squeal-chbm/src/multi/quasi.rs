//! The quasi-periodic answer of the generalized CHBM with two unstable modes: a torus whose two
//! base frequencies start from the two unstable eigenvalues' (derivation in [`crate::multi`]).
//!
//! **Which equations.** The generalized CHBM for two unstable modes at μ writes the motion with
//! one base frequency per mode, `x(t) = X(ω_1 t, ω_2 t)`, and asks the two-frequency harmonic
//! balance (eq 46 on the 2-D Fourier basis of [`squeal_hbm::torus`]) together with one
//! constraint per unstable eigenvalue, `Re λ_j = 0` (eq 47 once per mode), `λ_j` followed from
//! the static `λ_j⁰` (eq 22) through the linearization of the motion
//! ([`super::linearization`]). [`crate::multi`] shows that at every root of the balance whose
//! first harmonic `X_j` at `ω_j` is not zero, `iω_j` is an eigenvalue of the linearization
//! corrected to reproduce the force's fundamentals: the constraint holds exactly, for any
//! truncation. The constraints add no condition at such roots; in CHBM they keep the
//! least-squares solve away from the roots where a mode has no amplitude (the static solution,
//! or the other mode's cycle), where `Re λ_j ≠ 0`. So the solutions of the generalized CHBM
//! with both amplitudes non-zero are exactly the roots of the torus balance with both first
//! harmonics non-zero, and this module solves the latter (a square Newton system, the same
//! equations as the torus branch of [`crate::torus`]): unknowns the coefficients in the
//! reduced contact coordinates, `ω_1`, `ω_2`; rows the balance and two phase conditions, the
//! sine of `(1, 0)` and of `(0, 1)` on the reduced coordinate where each mode moves most; μ
//! held. A root is accepted only when both first harmonics are non-zero, and
//! [`torus_constraints`] evaluates the two constraints on it (they must vanish: the check of
//! the argument above, in the paper's terms).
//!
//! **Start** (eq 48 once per mode): either the superposition of the two modes' CHBM cycles
//! ([`super::periodic::mode_cycles`]), cycle `j`'s harmonic `h` placed on the wave `h e_j` and
//! the means added as deviations from the static solution, or, when a cycle did not converge,
//! the static solution plus each unstable eigenvector scaled as eq (48) scales one (its largest
//! normal motion against the smallest static penetration), mode by mode. Both are scaled by each of
//! [`TwoModeOptions::amplitudes`] in turn until Newton converges to a root with both modes
//! moving. A two-mode torus that this misses can be reached by [`follow_two_mode`] in μ from
//! one that converged.
//!
//! **Which attractor.** A one-mode cycle attracts when Hill's exponents are all negative
//! ([`super::periodic`]); the torus attracts when its Lyapunov exponents across it are negative
//! ([`crate::torus_stability`]). The report of both decides which motion the brake settles on.

use super::linearization::{MultiLinearization, Sample};
use super::periodic::eigenvalues_under;
use crate::solve::{ChbmSolution, ChbmStart, Outcome};
use crate::torus::{
    BrakeFamily, TorusError, TorusOptions, TorusPoint, family, modal_harmonics, reduce_cycle,
    summary, weights,
};
use faer::{Mat, c64};
use squeal_brake::harmonic::ContactForce;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::continuation::{self, ContinuationOptions, Control, Point};
use squeal_hbm::torus::{TorusBasis, Truncation};
use squeal_hbm::{HarmonicLayout, HbmError, Part};
use std::f64::consts::PI;

/// Controls of [`two_mode_torus`].
#[derive(Clone, Debug, PartialEq)]
pub struct TwoModeOptions {
    /// The 2-D basis (default: a box of 3 harmonics in each angle).
    pub truncation: Truncation,
    /// The AFT grid (default: [`squeal_hbm::torus::default_grid`]).
    pub grid: Option<[usize; 2]>,
    /// Factors on the start's oscillating part, tried in turn (on both modes, or, when one
    /// starts from its cycle and the other from its eigenvector, on the eigenvector only).
    pub amplitudes: Vec<f64>,
    /// The Newton corrector (its tolerance and iteration limit) and, for
    /// [`follow_two_mode`], the continuation.
    pub continuation: ContinuationOptions,
    /// Fast periods and samples per fast period of each point's envelope.
    pub envelope_periods: usize,
    /// See `envelope_periods`.
    pub envelope_samples: usize,
}

impl Default for TwoModeOptions {
    fn default() -> Self {
        let mut continuation = crate::branch::continuation_in_mu(60);
        continuation.max_iterations = 40;
        Self {
            truncation: Truncation::Box(3, 3),
            grid: None,
            amplitudes: vec![1.0, 0.7, 0.5, 1.4, 0.3, 0.1, 0.03],
            continuation,
            envelope_periods: 300,
            envelope_samples: 64,
        }
    }
}

impl TwoModeOptions {
    fn torus_options(&self) -> TorusOptions {
        TorusOptions {
            truncation: Some(self.truncation),
            grid: self.grid,
            envelope_periods: self.envelope_periods,
            envelope_samples: self.envelope_samples,
            continuation: self.continuation.clone(),
            ..TorusOptions::default()
        }
    }
}

/// What the start was made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TwoModeGuess {
    /// The superposition of the two modes' CHBM cycles.
    Cycles,
    /// The static solution plus both unstable eigenvectors (eq 48 scaling).
    Eigenvectors,
    /// One mode's CHBM cycle and the other's eigenvector (its cycle did not converge).
    Mixed,
    /// The previous torus of a branch in μ.
    Branch,
}

impl std::fmt::Display for TwoModeGuess {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Cycles => "the two modes' CHBM cycles superposed",
            Self::Eigenvectors => "the two unstable eigenvectors (eq 48)",
            Self::Mixed => "one mode's CHBM cycle and the other's eigenvector",
            Self::Branch => "the previous torus of the branch",
        })
    }
}

/// A torus of two unstable modes.
#[derive(Clone, Debug, PartialEq)]
pub struct TwoModeTorus {
    /// μ, both frequencies (`ω_1` continues the first start's eigenvalue, `ω_2` the second's),
    /// the coefficients, each pair's closure envelope.
    pub point: TorusPoint,
    /// The basis (reduced contact coordinates).
    pub basis: TorusBasis,
    /// The AFT grid.
    pub grid: [usize; 2],
    /// The phase conditions, as `(wave number, reduced coordinate)`.
    pub phase: [([i64; 2], usize); 2],
    /// The rows' and unknowns' displacement level (m).
    pub scale: f64,
    /// The pair whose closure swings most, and its closure's first harmonic at `ω_1` and at
    /// `ω_2` (amplitudes, m): how much each mode moves the contact.
    pub pair: usize,
    /// See `pair`.
    pub first_harmonics: [f64; 2],
    /// The start it converged from, and the factor on the start's oscillation.
    pub guess: TwoModeGuess,
    /// See `guess`.
    pub guess_amplitude: f64,
}

/// The reduced coordinates `Q_Rᵀ x_n` of physical dofs `x` (the nonlinear ones picked).
fn reduce_dofs(mb: &ModalBrake, qr: &Mat<f64>, x: &[c64]) -> Vec<c64> {
    let xn: Vec<c64> = mb.nl_dofs.iter().map(|&d| x[d]).collect();
    (0..qr.ncols())
        .map(|k| (0..xn.len()).map(|i| xn[i] * qr[(i, k)]).sum())
        .collect()
}

/// Index of the largest modulus.
fn largest(v: &[c64]) -> usize {
    (0..v.len())
        .max_by(|&a, &b| v[a].norm().total_cmp(&v[b].norm()))
        .unwrap_or(0)
}

/// The start's parts in reduced coordinates: the static solution `y0` and, per mode, its
/// harmonics `h = 0..=H` (complex, `y = Re Σ Y_h e^{ihθ}`, the mean as a deviation from `y0`).
struct Parts {
    y0: Vec<f64>,
    modes: [Vec<Vec<c64>>; 2],
}

fn cycle_parts(
    mb: &ModalBrake,
    force: &crate::torus::ReducedContact,
    y0: &[f64],
    c: &ChbmSolution,
) -> Result<Vec<Vec<c64>>, HbmError> {
    let layout = HarmonicLayout::new(mb.nl(), c.harmonics)?;
    let y = reduce_cycle(force, &layout, &c.nl_coeffs);
    let nr = y0.len();
    let mut out = vec![(0..nr).map(|i| c64::new(y[i] - y0[i], 0.0)).collect()];
    for h in 1..=c.harmonics {
        out.push(
            (0..nr)
                .map(|i| c64::new(y[(2 * h - 1) * nr + i], -y[2 * h * nr + i]))
                .collect(),
        );
    }
    Ok(out)
}

fn eigenvector_part(mb: &ModalBrake, qr: &Mat<f64>, s: &ChbmStart) -> Vec<Vec<c64>> {
    let psi = reduce_dofs(mb, qr, &s.mode);
    let x0: Vec<f64> = mb.nl_dofs.iter().map(|&d| s.equilibrium[d]).collect();
    let psin: Vec<c64> = mb.nl_dofs.iter().map(|&d| s.mode[d]).collect();
    let (mut dmax, mut pen) = (0.0f64, f64::INFINITY);
    for p in &mb.pairs {
        let g: c64 = p.normal.iter().map(|&(i, a)| psin[i] * a).sum();
        dmax = dmax.max(2.0 * g.norm());
        let d = p.penetration(&x0);
        if d > 0.0 {
            pen = pen.min(d);
        }
    }
    let p = if dmax > 0.0 && pen.is_finite() {
        pen / dmax
    } else {
        0.0
    };
    vec![
        vec![c64::new(0.0, 0.0); psi.len()],
        psi.iter().map(|v| v * p).collect(),
    ]
}

/// The coefficients of the start on `basis`, mode `j`'s oscillation scaled by `factors[j]`, each mode's phase
/// turned so that its first harmonic is real on its phase coordinate `d[j]`.
fn start_coeffs(basis: &TorusBasis, parts: &Parts, factors: [f64; 2], d: [usize; 2]) -> Vec<f64> {
    let nr = parts.y0.len();
    let mut u = vec![0.0; basis.len()];
    u[..nr].copy_from_slice(&parts.y0);
    for (j, m) in parts.modes.iter().enumerate() {
        let a = factors[j];
        let z = m[1][d[j]];
        let rot = if z.norm() > 0.0 {
            z.conj() / z.norm()
        } else {
            c64::new(1.0, 0.0)
        };
        for (h, yh) in m.iter().enumerate() {
            if h == 0 {
                for i in 0..nr {
                    u[i] += a * yh[i].re;
                }
                continue;
            }
            let mut k = [0i64; 2];
            k[j] = h as i64;
            let Some((e, _)) = basis.element(k) else {
                continue;
            };
            // Rotating θ_j by φ multiplies harmonic h by e^{ihφ}.
            let r = (0..h).fold(c64::new(1.0, 0.0), |acc, _| acc * rot);
            for i in 0..nr {
                let v = yh[i] * r * a;
                if let (Some(ic), Some(is)) =
                    (basis.index(e, Part::Cos, i), basis.index(e, Part::Sin, i))
                {
                    u[ic] = v.re;
                    u[is] = -v.im;
                }
            }
        }
    }
    u
}

/// The torus of the two unstable modes `starts` (two, from [`super::unstable_modes`]) of
/// `mb`'s brake at `mb.mu`, each mode started from its CHBM cycle in `cycles` when that
/// converged, else from its eigenvector (module docs).
pub fn two_mode_torus(
    mb: &ModalBrake,
    starts: &[ChbmStart],
    cycles: [Option<&ChbmSolution>; 2],
    opts: &TwoModeOptions,
) -> Result<TwoModeTorus, TorusError> {
    let [s1, s2] = starts else {
        return Err(
            HbmError::BadOption("the two-mode torus needs exactly two unstable modes").into(),
        );
    };
    let balance = crate::torus::brake_torus(mb, opts.truncation, opts.grid)?;
    let basis = balance.basis().clone();
    let force = balance.force();
    let qr = force.qr().to_owned();
    let xeq: Vec<c64> = s1.equilibrium.iter().map(|&v| c64::new(v, 0.0)).collect();
    let y0: Vec<f64> = reduce_dofs(mb, &qr, &xeq).iter().map(|v| v.re).collect();
    let part =
        |c: Option<&ChbmSolution>, s: &ChbmStart| -> Result<(Vec<Vec<c64>>, f64), HbmError> {
            match c {
                Some(c) if c.outcome == Outcome::LimitCycle => {
                    Ok((cycle_parts(mb, force, &y0, c)?, c.omega))
                }
                _ => Ok((eigenvector_part(mb, &qr, s), s.lambda.im)),
            }
        };
    let (p1, w1) = part(cycles[0], s1)?;
    let (p2, w2) = part(cycles[1], s2)?;
    let from_cycle = cycles.map(|c| c.is_some_and(|c| c.outcome == Outcome::LimitCycle));
    let guess = match from_cycle {
        [true, true] => TwoModeGuess::Cycles,
        [false, false] => TwoModeGuess::Eigenvectors,
        _ => TwoModeGuess::Mixed,
    };
    let (modes, omega) = ([p1, p2], [w1, w2]);
    let parts = Parts { y0, modes };
    let d = [largest(&parts.modes[0][1]), largest(&parts.modes[1][1])];
    let scale = parts.modes[0][1][d[0]]
        .norm()
        .max(parts.modes[1][1][d[1]].norm())
        .max(f64::MIN_POSITIVE);
    let phase = [([1, 0], d[0]), ([0, 1], d[1])];
    let mut fam = family(mb, opts.truncation, opts.grid, phase, scale)?;
    let grid = fam.balance().aft_mut().grid();
    let l = basis.len();
    let topts = opts.torus_options();
    for &a in &opts.amplitudes {
        // A converged cycle is kept as it is when the other mode starts from its eigenvector.
        let factors = match guess {
            TwoModeGuess::Mixed => from_cycle.map(|c| if c { 1.0 } else { a }),
            _ => [a, a],
        };
        let mut z = start_coeffs(&basis, &parts, factors, d);
        z.extend([omega[0], omega[1], mb.mu]);
        let Some(p) = correct_at_mu(&mut fam, &z, scale, &topts.continuation)? else {
            continue;
        };
        let point = summary(mb, &basis, &p, &topts)?;
        let Some(t) = accept(mb, &basis, grid, phase, scale, point, guess, a)? else {
            continue;
        };
        debug_assert_eq!(t.point.coeffs.len(), l);
        return Ok(t);
    }
    Err(TorusError::TwoModeStart { mu: mb.mu })
}

/// Newton at fixed μ (`z`'s last entry) from `z`.
fn correct_at_mu(
    fam: &mut BrakeFamily,
    z: &[f64],
    scale: f64,
    copts: &ContinuationOptions,
) -> Result<Option<Point>, HbmError> {
    let n = z.len();
    let mut row = vec![0.0; n];
    row[n - 1] = 1.0;
    let w = weights(scale, z[n - 3], z[n - 1])(&HarmonicLayout::new(n - 3, 0)?);
    continuation::correct_point(fam, z, &row, z[n - 1], &w, &row, copts)
}

/// The torus if both modes move on it (first harmonics above 1e-6 of the scale).
#[allow(clippy::too_many_arguments)]
fn accept(
    mb: &ModalBrake,
    basis: &TorusBasis,
    grid: [usize; 2],
    phase: [([i64; 2], usize); 2],
    scale: f64,
    point: TorusPoint,
    guess: TwoModeGuess,
    a: f64,
) -> Result<Option<TwoModeTorus>, HbmError> {
    if !(point.omega[0] > 0.0 && point.omega[1] > 0.0) {
        return Ok(None);
    }
    let (pair, _) = point.loudest();
    let first = [
        closure_harmonic(mb, basis, &point.coeffs, pair, [1, 0])?,
        closure_harmonic(mb, basis, &point.coeffs, pair, [0, 1])?,
    ];
    let moving = |k: [i64; 2]| {
        basis.element(k).is_some_and(|(e, _)| {
            (0..basis.n_dofs())
                .any(|i| basis.amplitude(&point.coeffs, e, i).unwrap_or(0.0) > 1e-6 * scale)
        })
    };
    if !(moving([1, 0]) && moving([0, 1])) {
        return Ok(None);
    }
    Ok(Some(TwoModeTorus {
        point,
        basis: basis.clone(),
        grid,
        phase,
        scale,
        pair,
        first_harmonics: first,
        guess,
        guess_amplitude: a,
    }))
}

/// The amplitude of pair `pair`'s closure harmonic `k` on the torus `coeffs`.
fn closure_harmonic(
    mb: &ModalBrake,
    basis: &TorusBasis,
    coeffs: &[f64],
    pair: usize,
    k: [i64; 2],
) -> Result<f64, HbmError> {
    let (_, qr) = crate::floquet::contact_bases(mb);
    let Some((e, _)) = basis.element(k) else {
        return Ok(0.0);
    };
    let g: Vec<f64> = (0..qr.ncols())
        .map(|c| {
            mb.pairs[pair]
                .normal
                .iter()
                .map(|&(i, a)| a * qr[(i, c)])
                .sum()
        })
        .collect();
    let part = |p| -> f64 {
        (0..g.len())
            .map(|i| g[i] * basis.index(e, p, i).map_or(0.0, |j| coeffs[j]))
            .sum()
    };
    Ok(part(Part::Cos).hypot(part(Part::Sin)))
}

/// The torus branch in μ from `torus` (a two-mode torus) until μ leaves `range` or the
/// continuation stops: each point a [`TwoModeTorus`] (its guess [`TwoModeGuess::Branch`]).
pub fn follow_two_mode(
    mb: &ModalBrake,
    torus: &TwoModeTorus,
    range: (f64, f64),
    opts: &TwoModeOptions,
) -> Result<Vec<TwoModeTorus>, TorusError> {
    let mut mbp = mb.clone();
    mbp.mu = torus.point.mu;
    let mut fam = family(
        &mbp,
        torus.basis.truncation(),
        Some(torus.grid),
        torus.phase,
        torus.scale,
    )?;
    let mut z = torus.point.coeffs.clone();
    z.extend([torus.point.omega[0], torus.point.omega[1], torus.point.mu]);
    let mut topts = opts.torus_options();
    topts.continuation.parameter_range = range;
    let Some(p0) = correct_at_mu(&mut fam, &z, torus.scale, &topts.continuation)? else {
        return Err(TorusError::TwoModeStart { mu: torus.point.mu });
    };
    let w = weights(torus.scale, torus.point.omega[0], torus.point.mu);
    let (mut out, mut failure) = (Vec::new(), None);
    continuation::continue_from(&mut fam, p0, &w, &topts.continuation, |p| {
        let r = summary(mb, &torus.basis, p, &topts).and_then(|pt| {
            accept(
                mb,
                &torus.basis,
                torus.grid,
                torus.phase,
                torus.scale,
                pt,
                TwoModeGuess::Branch,
                1.0,
            )
        });
        match r {
            Ok(Some(t)) => {
                out.push(t);
                Control::Continue
            }
            Ok(None) => {
                Control::Stop("a mode's amplitude vanished: the torus ends on a cycle".into())
            }
            Err(e) => {
                failure = Some(e);
                Control::Stop("a torus point could not be summarized".into())
            }
        }
    })?;
    match failure {
        Some(e) => Err(e.into()),
        None => Ok(out),
    }
}

/// Samples of the torus `t` on an `n × n` grid of the angles, on the nonlinear dofs (the
/// modal motion of [`modal_harmonics`] through `Φ_n`), with both phases.
pub fn torus_samples(mb: &ModalBrake, t: &TwoModeTorus, n: usize) -> Result<Vec<Sample>, HbmError> {
    let mut mbp = mb.clone();
    mbp.mu = t.point.mu;
    let (basis, q) = modal_harmonics(
        &mbp,
        t.basis.truncation(),
        Some(t.grid),
        &t.point.coeffs,
        t.point.omega,
    )?;
    let modes = mbp.modes();
    let mut out = Vec::with_capacity(n * n);
    let (mut qx, mut qv) = (vec![0.0; modes], vec![0.0; modes]);
    let (mut x, mut v) = (vec![0.0; mbp.nl()], vec![0.0; mbp.nl()]);
    for i in 0..n {
        for j in 0..n {
            let th = [
                2.0 * PI * i as f64 / n as f64,
                2.0 * PI * j as f64 / n as f64,
            ];
            qx.fill(0.0);
            qv.fill(0.0);
            for (e, qe) in q.iter().enumerate() {
                let k = basis.wave(e);
                let w = basis.frequency(e, t.point.omega);
                let ph = k[0] as f64 * th[0] + k[1] as f64 * th[1];
                let rot = c64::new(ph.cos(), ph.sin());
                for m in 0..modes {
                    let z = qe[m] * rot;
                    qx[m] += z.re;
                    qv[m] -= w * z.im;
                }
            }
            mbp.nonlinear_part(&qx, &mut x);
            mbp.nonlinear_part(&qv, &mut v);
            out.push(Sample {
                x: x.clone(),
                v: v.clone(),
                phases: th.to_vec(),
            });
        }
    }
    Ok(out)
}

/// The generalized CHBM's two eigenvalues `λ_j` on the torus `t` (module docs): each followed
/// from its static value `starts[j].lambda` to the torus' linearization (`n × n` samples of the
/// angles). At a root both have `Re λ_j = 0` and `Im λ_j = ω_j`, to the solve's tolerance.
pub fn torus_constraints(
    mb: &ModalBrake,
    t: &TwoModeTorus,
    starts: &[ChbmStart],
    n: usize,
) -> Result<Vec<c64>, HbmError> {
    let mut mbp = mb.clone();
    mbp.mu = t.point.mu;
    let force = ContactForce::new(&mbp);
    let samples = torus_samples(&mbp, t, n)?;
    let lambdas0: Vec<c64> = starts.iter().map(|s| s.lambda).collect();
    let lin = MultiLinearization::from_samples(&force, &t.point.omega, &samples).map_err(|e| {
        HbmError::EigenvalueLost {
            from: lambdas0.first().copied().unwrap_or(c64::new(0.0, 0.0)),
            why: e.to_string(),
        }
    })?;
    let x0: Vec<f64> = match starts.first() {
        Some(s) => mbp.nl_dofs.iter().map(|&d| s.equilibrium[d]).collect(),
        None => return Ok(Vec::new()),
    };
    eigenvalues_under(&mbp, &force, &lin, &x0, &lambdas0)
}
