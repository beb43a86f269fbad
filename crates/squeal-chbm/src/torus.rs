//! Quasi-periodic squeal past a Neimark–Sacker point (issue 24, item 1): the brake's torus
//! branch by the quasi-periodic harmonic balance of [`squeal_hbm::torus`].
//!
//! **Where it starts.** Along the branch of limit cycles ([`crate::branch`]) Hill's method
//! ([`crate::floquet`]) finds where a complex pair of Floquet multipliers leaves the unit circle
//! ([`crate::bifurcation`]): a Neimark–Sacker point `μ_NS`, with the critical exponent
//! `σ = α + iΩ` (`|Ω| < ω/2`). Past it the cycle is unstable and, for a supercritical
//! bifurcation, a torus `x(t) = X(ω1 t, ω2 t)` grows from it with `ω1 ≈ ω` and `ω2 ≈ |Ω|`
//! ([`squeal_hbm::torus::start_from_cycle`] gives the start: the cycle plus the critical
//! Floquet vector, found from the same equations).
//!
//! **Reduced coordinates.** The brake's contact force depends on the nonlinear dofs `x_n` only
//! through the normal gaps (`g_pᵀ x_n`, and the tangential motions `h_pᵀ x_n` for a
//! velocity-dependent law) and acts along the normals and tangents, so with `Q_R` and `Q_E`
//! orthonormal bases of those spans, `G(x_n) = Q_E c(Q_Rᵀ x_n)` (the springs `K_s` moved into
//! the linear part lie in `{g} ⊗ {g}` too), the factorization [`crate::floquet`]'s Woodbury
//! solve uses. Multiplying the condensed balance of eq (34) for a frequency `w`,
//! `Λ_eq(w) X + G(X) = F_eq`, by the receptance `H(iw) = Λ_eq(w)⁻¹ = Φ_n Δ(iw)⁻¹ Φ_nᵀ` and
//! projecting on `Q_R` gives equations in `y = Q_Rᵀ x_n` alone:
//!
//! `y_e + Q_Rᵀ H(i w_e) Q_E c_e(y) = Q_Rᵀ x_static δ_e0`,
//!
//! the receptance form of [`squeal_hbm::torus::TorusLinear`] (`A = I`, `B = Q_Rᵀ H Q_E`).
//! It is equivalent to eq (34): `X_e = H(iw_e)(F_eq,e - Q_E c_e)` solves eq (34) whenever `y`
//! solves the reduced equations, because then `Q_Rᵀ X = y`. The unknowns per Fourier element
//! are `q_R` (9 on the bundled brake's 9 pairs) instead of `n_nl` (36): the dense Jacobian of
//! a torus with a hundred elements is ~1000 square instead of ~4000. With diagonal modal
//! damping `B(w) = Σ_j (Q_Rᵀ φ_j)(Q_Eᵀ φ_j)ᵀ / Δ_jj(iw)` over the modes.
//!
//! **What a torus point reports.** Both frequencies, and for each pair the closure
//! `δ_p = g_pᵀ x_n = g_pᵀ Q_R y` along the torus' flow: its overall extremes and its amplitude
//! envelope, the smallest and largest peak-to-peak swing over one fast period
//! ([`squeal_hbm::torus::measure::envelope`], the same measure a time integration gets).
//!
//! **Stability of the tori.** By their Lyapunov exponents along the known flow:
//! [`crate::torus_stability`] (the method and why not a quasi-periodic Floquet analysis:
//! [`squeal_hbm::torus::lyapunov`]).

use crate::bifurcation::{Bifurcation, BifurcationKind};
use crate::branch::{BranchOptions, BranchPoint, LimitCycleBranch, cycles_at};
use crate::solve::ChbmError;
use faer::c64;
use squeal_brake::harmonic::ModalSolver;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::continuation::{self, ContinuationOptions, Control, Point, Stop};
use squeal_hbm::torus::measure::{Envelope, envelope};
use squeal_hbm::torus::{
    TorusBalance, TorusBasis, TorusFamily, TorusPhase, TorusScales, Truncation, start_from_cycle,
};
use squeal_hbm::{HarmonicLayout, HbmError};
use std::time::{Duration, Instant};

mod contact;
use contact::contact_spaces;
pub use contact::{BrakeReceptance, ReducedContact};

/// Errors of the torus branch.
#[derive(Debug, thiserror::Error)]
pub enum TorusError {
    /// The harmonic balance failed.
    #[error(transparent)]
    Hbm(#[from] HbmError),
    /// The branch of cycles failed.
    #[error(transparent)]
    Chbm(#[from] ChbmError),
    /// The bifurcation given is not a Neimark–Sacker point.
    #[error("a torus starts at a Neimark-Sacker point, not at a {0}")]
    NotNeimarkSacker(BifurcationKind),
    /// No cycle of the branch at the bifurcation's parameter.
    #[error("the branch has no cycle at mu = {0:.6} to start the torus from")]
    NoCycle(f64),
    /// The start could not be corrected onto a torus.
    #[error(
        "no torus near the cycle at mu = {mu:.6}: the correction with the modulation's amplitude fixed did not converge"
    )]
    Start {
        /// The bifurcation's parameter.
        mu: f64,
    },
    /// Newton did not converge to a torus on which both unstable modes move.
    #[error(
        "no two-mode torus at mu = {mu:.6}: Newton from the start (each mode's cycle or eigenvector, at every trial amplitude) converged to no torus on which both modes move"
    )]
    TwoModeStart {
        /// The friction coefficient.
        mu: f64,
    },
}

/// The brake's torus equations.
pub type BrakeTorus = TorusBalance<BrakeReceptance, ReducedContact>;

/// The brake's torus equations on `basis` (in the reduced coordinates of `mb`) on `grid`.
pub fn brake_torus(
    mb: &ModalBrake,
    truncation: Truncation,
    grid: Option<[usize; 2]>,
) -> Result<BrakeTorus, HbmError> {
    let (qe, qr) = contact_spaces(mb);
    let basis = TorusBasis::new(qr.ncols(), truncation)?;
    let linear = BrakeReceptance::new(mb, &qe, &qr);
    // y_static = Q_Rᵀ Φ_n Ω⁻² Φᵀ F_piston.
    let q_static: Vec<f64> = (0..mb.modes())
        .map(|j| mb.load[j] / (mb.omega[j] * mb.omega[j]))
        .collect();
    let mut f_ext = vec![0.0; basis.len()];
    for (i, v) in f_ext.iter_mut().enumerate().take(qr.ncols()) {
        *v = (0..mb.modes())
            .map(|j| linear.phi_r[(i, j)] * q_static[j])
            .sum();
    }
    let force = ReducedContact::new(mb, qe, qr);
    TorusBalance::new(basis, linear, force, f_ext, grid)
}

/// The reduced coordinates `Q_Rᵀ` of a cycle's nonlinear-dof coefficients, block by block.
pub(crate) fn reduce_cycle(force: &ReducedContact, layout: &HarmonicLayout, u: &[f64]) -> Vec<f64> {
    let (nn, nr) = (layout.n_dofs(), force.qr.ncols());
    let mut out = Vec::with_capacity(nr * layout.n_blocks());
    for b in 0..layout.n_blocks() {
        let blk = &u[b * nn..(b + 1) * nn];
        out.extend((0..nr).map(|k| (0..nn).map(|i| force.qr[(i, k)] * blk[i]).sum::<f64>()));
    }
    out
}

/// Controls of [`follow_torus`].
#[derive(Clone, Debug, PartialEq)]
pub struct TorusOptions {
    /// The basis: by default a box of the start cycle's harmonics in `θ1` and 2 in `θ2`.
    pub truncation: Option<Truncation>,
    /// The AFT grid (default: [`squeal_hbm::torus::default_grid`]).
    pub grid: Option<[usize; 2]>,
    /// The modulation's amplitude at the start, as a fraction of the cycle's first harmonic on
    /// the phase dof.
    pub start_amplitude: f64,
    /// Fast periods of the flow on which a point's envelope is measured, and samples per fast
    /// period.
    pub envelope_periods: usize,
    /// Samples per fast period of the envelope.
    pub envelope_samples: usize,
    /// The continuation: steps, tolerances, point budget; its parameter range is μ's.
    pub continuation: ContinuationOptions,
}

impl Default for TorusOptions {
    fn default() -> Self {
        Self {
            truncation: None,
            grid: None,
            start_amplitude: 0.02,
            envelope_periods: 300,
            envelope_samples: 64,
            continuation: crate::branch::continuation_in_mu(60),
        }
    }
}

/// One pair's closure on a torus.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairTorus {
    /// Closure `δ` extremes and the envelope of its peak-to-peak swing over one fast period (m).
    pub envelope: Envelope,
}

/// One point of a torus branch.
#[derive(Clone, Debug, PartialEq)]
pub struct TorusPoint {
    /// μ.
    pub mu: f64,
    /// `ω1`, `ω2` (rad/s).
    pub omega: [f64; 2],
    /// Coefficients of the reduced coordinates (basis of the branch).
    pub coeffs: Vec<f64>,
    /// Each pair's closure.
    pub pairs: Vec<PairTorus>,
    /// Newton iterations and the final residual (scaled).
    pub iterations: usize,
    /// `||R||`.
    pub residual: f64,
    /// μ's component of the unit tangent.
    pub parameter_rate: f64,
}

impl TorusPoint {
    /// Both frequencies (Hz).
    pub fn frequencies_hz(&self) -> [f64; 2] {
        self.omega.map(|w| w / (2.0 * std::f64::consts::PI))
    }

    /// The pair of largest swing and its envelope.
    pub fn loudest(&self) -> (usize, Envelope) {
        let mut best = 0;
        for (i, p) in self.pairs.iter().enumerate() {
            if p.envelope.swing_max > self.pairs[best].envelope.swing_max {
                best = i;
            }
        }
        (best, self.pairs[best].envelope)
    }
}

/// A followed torus branch.
#[derive(Clone, Debug)]
pub struct TorusBranch {
    /// The Neimark–Sacker point it starts from.
    pub start: Bifurcation,
    /// The basis (reduced coordinates).
    pub basis: TorusBasis,
    /// The AFT grid.
    pub grid: [usize; 2],
    /// The converged tori, in order.
    pub points: Vec<TorusPoint>,
    /// `||J1 p|| / ||J1 p0||` of the start's Floquet vector ([`squeal_hbm::torus::TorusStart`]).
    pub null_residual: f64,
    /// The phase conditions, as `(wave number, dof)`: `Us = 0` there.
    pub phase: [([i64; 2], usize); 2],
    /// The displacement level of the rows and unknowns (the start cycle's first harmonic on
    /// the phase dof, m).
    pub scale: f64,
    /// Why the branch ended.
    pub stop: Stop,
    /// Wall time.
    pub time: Duration,
}

/// Each pair's closure `δ_p = g_pᵀ Q_R y` sampled along the torus' flow from `θ = 0`.
pub fn closures_along_flow(
    mb: &ModalBrake,
    basis: &TorusBasis,
    coeffs: &[f64],
    omega: [f64; 2],
    dt: f64,
    samples: usize,
) -> Result<Vec<Vec<f64>>, HbmError> {
    basis.check_len("torus coefficients", coeffs.len())?;
    let (_, qr) = contact_spaces(mb);
    let nr = qr.ncols();
    // The pairs' closure coefficients: one scalar series per pair.
    let rows: Vec<Vec<f64>> = mb
        .pairs
        .iter()
        .map(|p| {
            (0..nr)
                .map(|k| p.normal.iter().map(|&(i, g)| g * qr[(i, k)]).sum())
                .collect()
        })
        .collect();
    // The pairs' series as one basis of as many dofs as pairs (in groups that fit the
    // largest basis): each sample's sines and cosines are computed once for the group, and
    // each pair's value is summed in the same order as on its own (the same bits as a scalar
    // evaluation per pair, at a ninth of the trigonometry on the bundled brake's 9 pairs).
    let np = mb.pairs.len();
    let mut out = vec![Vec::with_capacity(samples); np];
    let group = (squeal_hbm::MAX_COEFFICIENTS / basis.n_blocks()).max(1);
    for (g, (rows, pairs)) in rows.chunks(group).zip(mb.pairs.chunks(group)).enumerate() {
        let m = rows.len();
        let multi_basis = TorusBasis::new(m, basis.truncation())?;
        // `multi[b * m + p]`: pair `p`'s coefficient of block `b`.
        let multi: Vec<f64> = (0..basis.n_blocks())
            .flat_map(|b| rows.iter().zip(pairs).map(move |(r, p)| (b, r, p)))
            .map(|(b, r, p)| {
                let v: f64 = (0..nr).map(|k| r[k] * coeffs[b * nr + k]).sum();
                // The closure δ = gap offset + g·x: the offset enters the mean.
                if b == 0 { v - p.initial_gap } else { v }
            })
            .collect();
        let mut val = vec![0.0; m];
        let outs = &mut out[g * group..g * group + m];
        for j in 0..samples {
            let t = j as f64 * dt;
            multi_basis.displacement_at(&multi, [omega[0] * t, omega[1] * t], &mut val)?;
            for (o, v) in outs.iter_mut().zip(&val) {
                o.push(*v);
            }
        }
    }
    Ok(out)
}

pub(crate) fn summary(
    mb: &ModalBrake,
    basis: &TorusBasis,
    p: &Point,
    opts: &TorusOptions,
) -> Result<TorusPoint, HbmError> {
    let l = basis.len();
    let omega = [p.z[l], p.z[l + 1]];
    let period = 2.0 * std::f64::consts::PI / omega[0];
    let dt = period / opts.envelope_samples as f64;
    let n = opts.envelope_periods * opts.envelope_samples;
    let signals = closures_along_flow(mb, basis, &p.z[..l], omega, dt, n)?;
    let pairs = signals
        .iter()
        .map(|s| {
            envelope(s, dt, period)
                .map(|envelope| PairTorus { envelope })
                .ok_or(HbmError::BadOption(
                    "a torus envelope needs at least two fast periods",
                ))
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(TorusPoint {
        mu: p.parameter(),
        omega,
        coeffs: p.z[..l].to_vec(),
        pairs,
        iterations: p.iterations,
        residual: p.residual,
        parameter_rate: p.parameter_rate(),
    })
}

/// The torus branch of `mb`'s brake born at the Neimark–Sacker point `ns` of `branch` (a
/// branch in μ from [`crate::branch::follow_from_hopf`], with `branch_opts` its options),
/// followed in μ.
pub fn follow_torus(
    mb: &ModalBrake,
    branch: &LimitCycleBranch,
    branch_opts: &BranchOptions,
    ns: &Bifurcation,
    opts: &TorusOptions,
) -> Result<TorusBranch, TorusError> {
    let t0 = Instant::now();
    if ns.kind != BifurcationKind::NeimarkSacker {
        return Err(TorusError::NotNeimarkSacker(ns.kind));
    }
    let mu = ns.parameter;
    let cycle = cycles_at(mb, branch, mu, branch_opts)?
        .into_iter()
        .min_by_key(|(i, _)| i.abs_diff(ns.after_point))
        .map(|(_, c)| c)
        .ok_or(TorusError::NoCycle(mu))?;
    let (family, start, basis, grid) = start_family(mb, &cycle, ns, opts)?;
    let mut family = family;
    let TorusStartPoint {
        point,
        null_residual,
        phase,
        scale,
    } = start;
    let weights = weights(scale, point.z[basis.len()], mu);
    let copts = opts.continuation.clone();
    let mut failure = None;
    let mut points = Vec::new();
    let raw =
        continuation::continue_from(
            &mut family,
            point.clone(),
            &weights,
            &copts,
            |p| match summary(mb, &basis, p, opts) {
                Ok(s) => {
                    points.push(s);
                    Control::Continue
                }
                Err(e) => {
                    failure = Some(e);
                    Control::Stop("a torus point could not be summarized".into())
                }
            },
        )?;
    if let Some(e) = failure {
        return Err(e.into());
    }
    Ok(TorusBranch {
        start: *ns,
        basis,
        grid,
        points,
        null_residual,
        phase,
        scale,
        stop: raw.stop,
        time: t0.elapsed(),
    })
}

/// The unknowns' weights: `1/scale` for `U`, `1/ω1` for both frequencies, `1/μ`.
pub(crate) fn weights(scale: f64, omega1: f64, mu: f64) -> impl Fn(&HarmonicLayout) -> Vec<f64> {
    move |layout: &HarmonicLayout| {
        let mut w = vec![1.0 / scale; layout.len() + 3];
        w[layout.len()] = 1.0 / omega1;
        w[layout.len() + 1] = 1.0 / omega1;
        w[layout.len() + 2] = 1.0 / mu;
        w
    }
}

struct TorusStartPoint {
    point: Point,
    null_residual: f64,
    phase: [([i64; 2], usize); 2],
    scale: f64,
}

/// The brake's family on `truncation` at the row level `scale` with the phase conditions
/// `phase` (wave numbers and dofs).
pub(crate) fn family(
    mb: &ModalBrake,
    truncation: Truncation,
    grid: Option<[usize; 2]>,
    phase: [([i64; 2], usize); 2],
    scale: f64,
) -> Result<BrakeFamily, HbmError> {
    let balance = brake_torus(mb, truncation, grid)?;
    let conditions = phase.map(|(k, d)| {
        balance
            .basis()
            .element(k)
            .map(|e| (e.0, d))
            .ok_or(HbmError::BadOption(
                "the basis lacks a phase condition's wave number",
            ))
    });
    let [a, b] = conditions;
    let scales = TorusScales {
        balance: scale,
        phase: scale,
    };
    TorusFamily::new(
        balance,
        set_mu as fn(&mut BrakeTorus, f64) -> Result<(), HbmError>,
        TorusPhase {
            conditions: [a?, b?],
        },
        scales,
        1e-7,
    )
}

pub(crate) type BrakeFamily =
    TorusFamily<BrakeReceptance, ReducedContact, fn(&mut BrakeTorus, f64) -> Result<(), HbmError>>;

fn set_mu(b: &mut BrakeTorus, mu: f64) -> Result<(), HbmError> {
    if !mu.is_finite() {
        return Err(HbmError::Parameter {
            value: mu,
            why: "not a finite number".into(),
        });
    }
    b.force_mut().set_mu(mu);
    Ok(())
}

/// The family at the cycle `cycle` of the NS point and its corrected first torus.
fn start_family(
    mb: &ModalBrake,
    cycle: &BranchPoint,
    ns: &Bifurcation,
    opts: &TorusOptions,
) -> Result<(BrakeFamily, TorusStartPoint, TorusBasis, [usize; 2]), TorusError> {
    let truncation = opts
        .truncation
        .unwrap_or(Truncation::Box(cycle.harmonics, 2));
    let mut mbp = mb.clone();
    mbp.mu = cycle.parameter;
    let mut balance = brake_torus(&mbp, truncation, opts.grid)?;
    let basis = balance.basis().clone();
    let grid = balance.aft_mut().grid();
    let layout = HarmonicLayout::new(mb.nl(), cycle.harmonics)?;
    let y = reduce_cycle(balance.force(), &layout, &cycle.nl_coeffs);
    let ylayout = HarmonicLayout::new(basis.n_dofs(), cycle.harmonics)?;
    // The phase dof: the largest first harmonic of y; the cycle rotated to meet it.
    let mut y = y;
    let d = (0..basis.n_dofs())
        .max_by(|&a, &b| {
            let amp = |i| ylayout.amplitude(&y, 1, i).unwrap_or(0.0);
            amp(a).total_cmp(&amp(b))
        })
        .unwrap_or(0);
    ylayout.align_phase(&mut y, d)?;
    let a1 = ylayout.amplitude(&y, 1, d).unwrap_or(0.0);
    let omega2 = ns.exponent.sigma.im.abs();
    let start = start_from_cycle(
        &mut balance,
        &y,
        ylayout,
        [cycle.omega, omega2],
        d,
        opts.start_amplitude * a1,
    )?;
    let scale = a1.max(f64::MIN_POSITIVE);
    let phase = start.phase.conditions.map(|(e, d)| (basis.wave(e), d));
    let mut family = family(&mbp, truncation, opts.grid, phase, scale)?;
    let mut z0 = start.z.clone();
    z0.push(cycle.parameter);
    let mut row = vec![0.0; z0.len()];
    row[start.amplitude_index] = 1.0;
    let l = basis.len();
    let w = weights(scale, cycle.omega, cycle.parameter)(&HarmonicLayout::new(l, 0)?);
    let point = continuation::correct_point(
        &mut family,
        &z0,
        &row,
        z0[start.amplitude_index],
        &w,
        &row,
        &opts.continuation,
    )?
    .ok_or(TorusError::Start { mu: ns.parameter })?;
    Ok((
        family,
        TorusStartPoint {
            point,
            null_residual: start.null_residual,
            phase,
            scale,
        },
        basis,
        grid,
    ))
}

/// The torus of `branch` at exactly `mu`, on the basis `truncation` (`None`: the branch's) and
/// grid `grid` (`None`: the default of the basis): the coefficients interpolated between the
/// two points whose μ brackets `mu` (first crossing along the branch), moved onto the basis by
/// wave number (elements the branch lacks start at zero), and corrected with μ held fixed.
pub fn torus_at(
    mb: &ModalBrake,
    branch: &TorusBranch,
    mu: f64,
    truncation: Option<Truncation>,
    grid: Option<[usize; 2]>,
    opts: &TorusOptions,
) -> Result<TorusPoint, TorusError> {
    let i = (1..branch.points.len())
        .find(|&i| (branch.points[i - 1].mu - mu) * (branch.points[i].mu - mu) <= 0.0)
        .ok_or(TorusError::NoCycle(mu))?;
    let (a, b) = (&branch.points[i - 1], &branch.points[i]);
    let s = if a.mu != b.mu {
        (mu - a.mu) / (b.mu - a.mu)
    } else {
        0.5
    };
    let lerp = |x: f64, y: f64| x + s * (y - x);
    let truncation = truncation.unwrap_or(branch.basis.truncation());
    let mut fam = family(mb, truncation, grid, branch.phase, branch.scale)?;
    let basis = fam.balance().basis().clone();
    let (old, n) = (&branch.basis, basis.n_dofs());
    let mut z = vec![0.0; basis.len() + 3];
    for (e, k) in old.waves().iter().enumerate() {
        let Some((f, _)) = basis.element(*k) else {
            continue;
        };
        for part in [squeal_hbm::Part::Cos, squeal_hbm::Part::Sin] {
            for d in 0..n {
                if let (Some(x), Some(y)) = (old.index(e, part, d), basis.index(f, part, d)) {
                    z[y] = lerp(a.coeffs[x], b.coeffs[x]);
                }
            }
        }
    }
    let l = basis.len();
    z[l] = lerp(a.omega[0], b.omega[0]);
    z[l + 1] = lerp(a.omega[1], b.omega[1]);
    z[l + 2] = mu;
    let mut row = vec![0.0; l + 3];
    row[l + 2] = 1.0;
    let w = weights(branch.scale, z[l], mu)(&HarmonicLayout::new(l, 0)?);
    let p = continuation::correct_point(&mut fam, &z, &row, mu, &w, &row, &opts.continuation)?
        .ok_or(TorusError::Start { mu })?;
    Ok(summary(mb, &basis, &p, opts)?)
}

/// The modal state `[q; q̇]` of the torus `coeffs` (reduced coordinates, basis `basis`) of
/// `mb`'s brake at the torus angles `theta`: each element's modal amplitudes
/// `q_e = Δ(iw_e)⁻¹ (Φᵀ F_piston δ_e0 - Φ_nᵀ Q_E c_e)` from the force's coefficients `c_e`
/// (the torus analogue of eq 35), summed at `theta`. A time integration started there starts on
/// the torus.
pub fn modal_state(
    mb: &ModalBrake,
    truncation: Truncation,
    grid: Option<[usize; 2]>,
    coeffs: &[f64],
    omega: [f64; 2],
    theta: [f64; 2],
) -> Result<Vec<f64>, HbmError> {
    let (basis, harmonics) = modal_harmonics(mb, truncation, grid, coeffs, omega)?;
    let n = mb.modes();
    let mut q = vec![0.0; n];
    let mut v = vec![0.0; n];
    for (e, qe_amp) in harmonics.iter().enumerate() {
        let w = basis.frequency(e, omega);
        let k = basis.wave(e);
        // x = Re(Q e^{i k·θ}), ẋ = Re(i w Q e^{i k·θ}).
        let phase = k[0] as f64 * theta[0] + k[1] as f64 * theta[1];
        let rot = c64::new(phase.cos(), phase.sin());
        for j in 0..n {
            let z = qe_amp[j] * rot;
            q[j] += z.re;
            v[j] += (c64::new(0.0, w) * z).re;
        }
    }
    q.extend(v);
    Ok(q)
}

/// Each Fourier element's modal amplitudes `q_e = Δ(iw_e)⁻¹ (Φᵀ F_piston δ_e0 - Φ_nᵀ Q_E c_e)`
/// of the torus `coeffs` (reduced coordinates) of `mb`'s brake, with the basis: the motion of
/// every mode is `q(θ) = Re Σ_e q_e e^{i k_e·θ}` (the torus analogue of eq 35).
pub fn modal_harmonics(
    mb: &ModalBrake,
    truncation: Truncation,
    grid: Option<[usize; 2]>,
    coeffs: &[f64],
    omega: [f64; 2],
) -> Result<(TorusBasis, Vec<Vec<c64>>), HbmError> {
    let mut balance = brake_torus(mb, truncation, grid)?;
    let basis = balance.basis().clone();
    let mut r = vec![0.0; basis.len()];
    balance.residual(coeffs, omega, &mut r)?;
    let c = balance.force_coefficients().to_vec();
    let (qe, _) = contact_spaces(mb);
    let (n, ne) = (mb.modes(), qe.ncols());
    // Φ_nᵀ Q_E (modes × q_E).
    let pe = mb.phi_n.transpose() * &qe;
    let mut out = Vec::with_capacity(basis.n_waves());
    for e in 0..basis.n_waves() {
        let w = basis.frequency(e, omega);
        let cplx: Vec<c64> = (0..ne)
            .map(|i| {
                let cc = c[(2 * e).saturating_sub(1) * ne + i];
                let cs = if e == 0 { 0.0 } else { c[2 * e * ne + i] };
                c64::new(cc, -cs)
            })
            .collect();
        let mut rhs: Vec<c64> = (0..n)
            .map(|j| -(0..ne).map(|i| cplx[i] * pe[(j, i)]).sum::<c64>())
            .collect();
        if e == 0 {
            for j in 0..n {
                rhs[j] += mb.load[j];
            }
        }
        let solver = ModalSolver::new(&mb.omega, &mb.damping, c64::new(0.0, w));
        out.push(solver.solve_vec(&rhs));
    }
    Ok((basis, out))
}
