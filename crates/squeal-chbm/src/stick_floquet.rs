//! Stability of exact stick–slip (DLFT) limit cycles: Floquet multipliers of the non-smooth
//! law itself, from the monodromy matrix of the variational equations of the Filippov system
//! along the cycle with saltation matrices at its switches (issue 24, item 4).
//!
//! **Method.** Leine & Nijmeijer, *Dynamics and Bifurcations of Non-Smooth Mechanical Systems*
//! (Springer 2004), ch. 3–4, and Leine, van Campen & van de Vrande, "Bifurcations in nonlinear
//! discontinuous systems", Nonlinear Dyn. 23 (2000) 105–164: the fundamental solution of the
//! linearized system is integrated along the periodic solution phase by phase, and at every
//! switching time it is multiplied by the saltation matrix
//! `S = I + (f₊ − f₋) nᵀ / (nᵀ f₋)` (`n` the switching surface's normal, `f∓` the vector fields
//! before and after); the monodromy matrix is the product over one period, its eigenvalues the
//! Floquet multipliers. Hill's method would need the Fourier series of Jacobians that jump
//! (slip against stick), which converge like `1/k`; the monodromy with saltation treats the
//! jumps exactly and needs only the cycle's states between switches.
//!
//! **The system.** Coordinates `q` (`n`, the mass the identity: modal coordinates for the
//! brake), nonlinear dofs `x_n = L q`:
//!
//! `q'' + C q' + K q + Lᵀ (G(x_n) + Σ_p φ_p h_p) = f`,
//!
//! `G` the smooth (frictionless) contact force, and per friction pair `p` the force `φ_p h_p`
//! (`squeal_hbm::FrictionContact`: slip velocity `γ_p = V_p + h_p·x_n'`, normal load
//! `N_p(δ_p)`, `δ_p = g_p·x_n + δ0_p`, one coefficient μ). Per pair and phase:
//!
//! - **open** (`δ_p ≤ 0`): no force, `N = N' = 0` — as the smooth monodromy handles it (the
//!   closure's kink is a breakpoint of the integration, the field is continuous there);
//! - **slip** (`φ_p = μ N_p(δ_p) s_p`, `s_p = ±1` fixed in the phase): the Jacobian of the
//!   friction force is `μ s_p N'(δ_p) h_p g_pᵀ`, no velocity term;
//! - **stick** (`γ_p = 0`): `φ_p` is the constraint's multiplier. With `B = Lᵀ H_s` (the stuck
//!   pairs' `b_p = Lᵀ h_p`), the constrained acceleration is `P (f − …)`,
//!   `P = I − B (BᵀB)⁻¹ Bᵀ` (the Filippov sliding field on the intersection of the switching
//!   surfaces `γ_p = 0`), and so is the variational one: `y'' = P (−C y' − K y − Lᵀ J L y)`,
//!   `J = ∂G/∂x_n` plus the sliding pairs' friction terms. `Bᵀ y'` stays zero.
//!
//! **Saltation matrices** (state `(y, y')`, surface `γ_p = 0`, normal `n = (0, b_p)`):
//!
//! - *into stick* (a pair's `γ` reaches 0 with its sticking force inside the cone):
//!   `f₊ − f₋ = (0, Δa)`, `Δa` in the span of the stuck set's `B` with `Bᵀ a₊ = 0`, and
//!   `nᵀ f₋ = γ'₋`; the product `Δa b_pᵀ / γ'₋` does not depend on `γ'₋`, and for a perturbation
//!   that already met the other stuck pairs' constraints it is exactly the projection
//!   `y' ← P₊ y'` onto the new stuck set's constraints (position unchanged). A 1-dof stick–slip
//!   cycle therefore has a zero multiplier: sticking forgets the velocity.
//! - *out of stick* (the multiplier reaches `±μ N`): with one coefficient (`μ_s = μ`, the only
//!   case the brake's DLFT supports) the sliding force equals the multiplier at the exit, the
//!   field is continuous and `S = I` (Leine & Nijmeijer, section 3.5: the exit of a sliding
//!   mode is a point where the Filippov field meets `f₊` or `f₋`).
//! - *slip reversal* (`γ_p` crosses 0 while `|multiplier| > μ N`, a transversal crossing):
//!   `Δa = P_s (2 μ N s₋ b_p)` (the stuck set's projection `P_s`) and
//!   `S = I + (0, Δa) (0, b_p)ᵀ / γ'₋`. `γ'₋` (before the crossing) is not available from the
//!   truncated series, whose derivative at a jump of `γ'` converges to the mid value; so
//!   `γ'₋ = h_p·x_n''(t_c) − b_p·Δa / 2`. A reversal whose `γ'₋` so estimated has the wrong
//!   sign is not transversal (grazing): it is counted and given `S = I`.
//! - *open ↔ closed*: `N` is continuous (`N(0) = 0`), so is the field: `S = I`.
//!
//! **Phases from the DLFT cycle.** Each pair's state at each time sample of the balance (its
//! clamp: stick where `|a| ≤ μ N`, `a` the predicted multiplier, eq S2 of
//! `squeal_hbm::stick_slip`; open where `δ ≤ 0`; slip with the sign of `a` otherwise). Where it
//! changes between samples `j` and `j + 1`, the switching time is refined by linear
//! interpolation of the quantity that crosses zero: `|a| − μ N` (stick ↔ slip; at a sliding
//! sample it is `ε |γ|`), `γ` (reversal) or `δ` (open ↔ closed): its error is second order in
//! the sample spacing `T/N` for the truncated series' smooth signals, below the truncation's own
//! smearing of a transition over about `T/(2H)` (with 24 harmonics and 1024 samples, about
//! 1 % of the period against 0.1 % for a sample).
//!
//! **Integration.** Between switches the linear equations `Y' = A(t) Y` of the whole `2n × 2n`
//! fundamental matrix are integrated on an even grid (`steps` per period, split at
//! every switch) by the two-stage, L-stable SDIRK method of order 2
//! (`γ = 1 − 1/√2`; stiffly accurate, so stiff modes' multipliers go to 0 and do not pose as
//! spurious ones near the unit circle, as they would with the trapezoidal rule), and the
//! result is Richardson-extrapolated from `m` and `2m` steps per period (order 4 on each
//! smooth phase). The per-column BDF of [`crate::floquet::monodromy`] is the smooth law's
//! independent check and takes 3–6 min per cycle of the coarse brake (docs/verification.md);
//! here the coupling `A(t) − A₀` has rank at most `n_nl` (it acts through `Lᵀ`), so each stage
//! solve is the constant linear part's (`I + γh C + γ²h² K`, diagonal for the brake) plus a
//! Woodbury correction of size `n_nl`, a few seconds per cycle of the coarse brake.

use crate::floquet::{CycleStability, Exponent, FloquetError};
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par, c64};
use squeal_hbm::{ContactState, FrictionContact, HarmonicLayout};
use std::f64::consts::PI;
use std::time::{Duration, Instant};

pub mod brake;
mod switches;
mod variational;

use switches::{Phase, Switch, pair_signals, state_at, switches};
use variational::Phases;

/// A matrix of the linear part: diagonal (the brake's modal `Ω²`, `D`) or dense.
#[derive(Clone, Debug)]
pub enum LinearPart {
    /// `diag(d)`.
    Diagonal(Vec<f64>),
    /// Dense `n × n`.
    Dense(Mat<f64>),
}

impl LinearPart {
    fn size(&self) -> usize {
        match self {
            LinearPart::Diagonal(d) => d.len(),
            LinearPart::Dense(m) => m.nrows(),
        }
    }

    /// `self · y`.
    fn apply(&self, y: &Mat<f64>) -> Mat<f64> {
        match self {
            LinearPart::Diagonal(d) => Mat::from_fn(y.nrows(), y.ncols(), |i, j| d[i] * y[(i, j)]),
            LinearPart::Dense(m) => mm(m, y),
        }
    }

    fn dense(&self) -> Mat<f64> {
        match self {
            LinearPart::Diagonal(d) => {
                Mat::from_fn(d.len(), d.len(), |i, j| if i == j { d[i] } else { 0.0 })
            }
            LinearPart::Dense(m) => m.clone(),
        }
    }
}

/// `∂G/∂x_n` of the smooth force as a function of `x_n`.
pub type SmoothJacobian<'a> = Box<dyn Fn(&[f64]) -> Mat<f64> + Sync + 'a>;

/// The non-smooth system (module docs): mass the identity.
pub struct StickSlipModel<'a> {
    /// `K` (`n × n`).
    pub stiffness: LinearPart,
    /// `C` (`n × n`).
    pub damping: LinearPart,
    /// `L` (`n_nl × n`): `x_n = L q`.
    pub lift: Mat<f64>,
    /// `∂G/∂x_n` (`n_nl × n_nl`) of the smooth (frictionless) force at `x_n`.
    pub smooth_jacobian: SmoothJacobian<'a>,
    /// The friction pairs (one coefficient each).
    pub contacts: Vec<FrictionContact>,
}

/// A DLFT cycle with its per-sample contact states.
#[derive(Clone, Copy, Debug)]
pub struct StickSlipCycle<'a> {
    /// Layout of `u` (nonlinear dofs).
    pub layout: HarmonicLayout,
    /// Fourier coefficients of `x_n`.
    pub u: &'a [f64],
    /// ω (rad/s).
    pub omega: f64,
    /// Each contact's stick/slip state at the balance's time samples
    /// (`squeal_hbm::StickSlipBalance::states`).
    pub states: &'a [Vec<ContactState>],
    /// Each contact's predicted multiplier at the same samples
    /// (`squeal_hbm::StickSlipBalance::predicted_multipliers`).
    pub predicted: &'a [Vec<f64>],
}

/// Options of [`stick_slip_floquet`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct StickSlipFloquetOptions {
    /// SDIRK steps per period of the coarser of the two runs (the finer has twice as many;
    /// both also stop at every switch); at least 16.
    pub steps: usize,
}

impl Default for StickSlipFloquetOptions {
    fn default() -> Self {
        Self { steps: 512 }
    }
}

/// The switches met over one period.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SwitchCounts {
    /// Into stick (projection).
    pub stick_entries: usize,
    /// Out of stick (identity).
    pub stick_exits: usize,
    /// Transversal slip reversals (rank-one saltation).
    pub reversals: usize,
    /// Reversals found not transversal (identity).
    pub grazing: usize,
    /// Open ↔ closed (identity).
    pub open_close: usize,
}

/// The result of [`stick_slip_floquet`].
#[derive(Clone, Debug)]
pub struct StickSlipFloquet {
    /// All `2n` exponents `ln ρ / T` (principal logarithm), `Re σ` descending; the multiplier
    /// nearest 1 is marked trivial.
    pub exponents: Vec<Exponent>,
    /// `|ln ρ_trivial| / T` (0 in exact arithmetic), s⁻¹.
    pub trivial_error: f64,
    /// The leading non-trivial exponent's change between the finer run and the extrapolated
    /// one (the integration's error estimate), s⁻¹.
    pub integration_error: f64,
    /// The switches per period.
    pub switches: SwitchCounts,
    /// Integration steps of the finer run.
    pub steps: usize,
    /// Wall time.
    pub time: Duration,
}

impl StickSlipFloquet {
    /// The non-trivial exponent of largest real part.
    pub fn leading(&self) -> Option<Exponent> {
        self.exponents.iter().copied().find(|e| !e.trivial)
    }

    /// The error scale of the exponents: the larger of the trivial exponent's distance from 0
    /// and the integration's estimate.
    pub fn error(&self) -> f64 {
        self.trivial_error.max(self.integration_error)
    }

    /// Stable, unstable, or marginal when the leading exponent's real part is within
    /// [`Self::error`] of zero.
    pub fn stability(&self) -> CycleStability {
        match self.leading().map(|e| e.sigma.re) {
            None => CycleStability::Stable,
            Some(re) if re > self.error() => CycleStability::Unstable,
            Some(re) if re < -self.error() => CycleStability::Stable,
            Some(_) => CycleStability::Marginal,
        }
    }
}

fn mm(a: &Mat<f64>, b: &Mat<f64>) -> Mat<f64> {
    let mut c = Mat::zeros(a.nrows(), b.ncols());
    matmul(
        c.as_mut(),
        Accum::Replace,
        a.as_ref(),
        b.as_ref(),
        1.0,
        Par::Seq,
    );
    c
}

/// `aᵀ b`.
fn mtm(a: &Mat<f64>, b: &Mat<f64>) -> Mat<f64> {
    let mut c = Mat::zeros(a.ncols(), b.ncols());
    matmul(
        c.as_mut(),
        Accum::Replace,
        a.transpose(),
        b.as_ref(),
        1.0,
        Par::Seq,
    );
    c
}

/// The monodromy matrix with `steps` SDIRK steps per period (and one more at every switch).
fn monodromy_with(
    ph: &Phases<'_, '_>,
    cycle: &StickSlipCycle<'_>,
    sw: &[Switch],
    start: &[Phase],
    steps: usize,
    counts: &mut SwitchCounts,
) -> (Mat<f64>, usize) {
    let n = ph.n;
    let period = 2.0 * PI / cycle.omega;
    let h0 = period / steps as f64;
    let gam = 1.0 - std::f64::consts::FRAC_1_SQRT_2;
    let mut y = Mat::<f64>::identity(2 * n, 2 * n);
    let mut phase = start.to_vec();
    let mut stuck = ph.stuck(&phase);
    // Pairs stuck at t = 0: only perturbations that meet their constraints are states of the
    // system (the others' multipliers are 0).
    {
        let mut v = y.subrows(n, n).to_owned();
        ph.project(&stuck, &mut v);
        y.subrows_mut(n, n).copy_from(&v);
    }
    let mut t = 0.0;
    let mut next = 0;
    let mut taken = 0;
    *counts = SwitchCounts::default();
    for k in 1..=steps {
        let grid = if k == steps { period } else { k as f64 * h0 };
        loop {
            let target = match sw.get(next) {
                Some(s) if s.t < grid => s.t,
                _ => grid,
            };
            let h = target - t;
            if h > 1e-12 * period {
                // SDIRK2 (module docs).
                let c = gam * h;
                let s = ph.s_factor(c);
                let w1 = ph.coupling(cycle, &phase, &stuck, t + c);
                let k1 = ph.solve(&s, c, &w1, &ph.apply(&w1, &y));
                let w2 = ph.coupling(cycle, &phase, &stuck, t + h);
                let y2 = Mat::from_fn(2 * n, 2 * n, |i, j| {
                    y[(i, j)] + (1.0 - gam) * h * k1[(i, j)]
                });
                let k2 = ph.solve(&s, c, &w2, &ph.apply(&w2, &y2));
                for j in 0..2 * n {
                    for i in 0..2 * n {
                        y[(i, j)] += h * ((1.0 - gam) * k1[(i, j)] + gam * k2[(i, j)]);
                    }
                }
                taken += 1;
            }
            t = target;
            if target < grid {
                let s = sw[next];
                next += 1;
                switch(ph, cycle, &mut phase, &mut stuck, s, &mut y, counts);
            } else {
                break;
            }
        }
    }
    (y, taken)
}

/// Applies one switch's saltation matrix to `y` and updates the phases.
fn switch(
    ph: &Phases<'_, '_>,
    cycle: &StickSlipCycle<'_>,
    phase: &mut [Phase],
    stuck: &mut Option<(Mat<f64>, Mat<f64>)>,
    s: Switch,
    y: &mut Mat<f64>,
    counts: &mut SwitchCounts,
) {
    let n = ph.n;
    let from = phase[s.pair];
    phase[s.pair] = s.to;
    match (from, s.to) {
        (_, Phase::Stick) => {
            counts.stick_entries += 1;
            *stuck = ph.stuck(phase);
            let mut v = y.subrows(n, n).to_owned();
            ph.project(stuck, &mut v);
            y.subrows_mut(n, n).copy_from(&v);
        }
        (Phase::Stick, _) => {
            counts.stick_exits += 1;
            *stuck = ph.stuck(phase);
        }
        (Phase::Slip(sb), Phase::Slip(_)) => {
            let c = &ph.model.contacts[s.pair];
            let (x, v, a) = state_at(cycle, s.t);
            let (_, _, gmid, (load, _)) = pair_signals(c, &x, &v, &a);
            let bp = &ph.b[s.pair];
            let mut da = Mat::from_fn(n, 1, |i, _| 2.0 * c.mu * load * sb * bp[(i, 0)]);
            ph.project(stuck, &mut da);
            let bda: f64 = (0..n).map(|i| bp[(i, 0)] * da[(i, 0)]).sum();
            let gb = gmid - 0.5 * bda;
            // Before a transversal crossing from sign sb, γ' has the sign −sb.
            if load > 0.0 && gb * sb < 0.0 {
                counts.reversals += 1;
                let v = y.subrows(n, n).to_owned();
                let bv = mtm(bp, &v);
                let corr = mm(&da, &bv);
                for j in 0..2 * n {
                    for i in 0..n {
                        y[(n + i, j)] += corr[(i, j)] / gb;
                    }
                }
            } else if load > 0.0 {
                counts.grazing += 1;
            }
        }
        _ => counts.open_close += 1,
    }
}

/// Exponents of a monodromy matrix over `period`, the trivial one marked.
fn exponents_of(m: &Mat<f64>, period: f64) -> Result<Vec<Exponent>, FloquetError> {
    let evd = m.eigen().map_err(|_| FloquetError::Eigen {
        what: "stick-slip monodromy matrix",
    })?;
    let s = evd.S();
    let dim = m.nrows();
    let mut e: Vec<Exponent> = (0..dim)
        .map(|i| {
            let rho = s[i];
            let sigma = if rho.norm() > 0.0 {
                rho.ln() / period
            } else {
                c64::new(f64::NEG_INFINITY, 0.0)
            };
            Exponent {
                sigma,
                multiplier: rho,
                trivial: false,
            }
        })
        .collect();
    if let Some(i) = (0..dim).min_by(|&a, &b| {
        (e[a].multiplier - 1.0)
            .norm()
            .total_cmp(&(e[b].multiplier - 1.0).norm())
    }) {
        e[i].trivial = true;
    }
    e.sort_by(|a, b| b.sigma.re.total_cmp(&a.sigma.re));
    Ok(e)
}

/// The monodromy matrix of the non-smooth variational equations along a DLFT cycle
/// (Richardson-extrapolated; module docs), its steps and switches.
pub fn stick_slip_monodromy(
    model: &StickSlipModel<'_>,
    cycle: &StickSlipCycle<'_>,
    opts: &StickSlipFloquetOptions,
) -> Result<(Mat<f64>, Mat<f64>, usize, SwitchCounts), FloquetError> {
    cycle
        .layout
        .check_len("cycle coefficients", cycle.u.len())?;
    let n = model.lift.ncols();
    if model.lift.nrows() != cycle.layout.n_dofs()
        || model.stiffness.size() != n
        || model.damping.size() != n
        || opts.steps < 16
        || !(cycle.omega.is_finite() && cycle.omega > 0.0)
    {
        return Err(FloquetError::BadOption(
            "the model's sizes must match the cycle, with at least 16 steps per period",
        ));
    }
    if model.contacts.iter().any(|c| c.static_ratio != 1.0) {
        return Err(FloquetError::BadOption(
            "the stick-slip Floquet analysis needs one friction coefficient per contact (static = kinetic): the saltation at the exit from stick is the identity only then",
        ));
    }
    let (sw, start) = switches(model, cycle)?;
    let ph = Phases::new(model);
    let mut counts = SwitchCounts::default();
    let (m1, _) = monodromy_with(&ph, cycle, &sw, &start, opts.steps, &mut counts);
    let (m2, steps) = monodromy_with(&ph, cycle, &sw, &start, 2 * opts.steps, &mut counts);
    let ext = Mat::from_fn(m1.nrows(), m1.ncols(), |i, j| {
        (4.0 * m2[(i, j)] - m1[(i, j)]) / 3.0
    });
    Ok((ext, m2, steps, counts))
}

/// Floquet exponents of a DLFT cycle of the non-smooth law (module docs).
pub fn stick_slip_floquet(
    model: &StickSlipModel<'_>,
    cycle: &StickSlipCycle<'_>,
    opts: &StickSlipFloquetOptions,
) -> Result<StickSlipFloquet, FloquetError> {
    let t0 = Instant::now();
    let (ext, fine, steps, switches) = stick_slip_monodromy(model, cycle, opts)?;
    let period = 2.0 * PI / cycle.omega;
    let exponents = exponents_of(&ext, period)?;
    let lead = |e: &[Exponent]| e.iter().find(|x| !x.trivial).map_or(0.0, |x| x.sigma.re);
    let fine_e = exponents_of(&fine, period)?;
    let integration_error = (lead(&exponents) - lead(&fine_e)).abs();
    let trivial_error = exponents
        .iter()
        .find(|e| e.trivial)
        .map_or(0.0, |e| e.sigma.norm());
    Ok(StickSlipFloquet {
        exponents,
        trivial_error,
        integration_error,
        switches,
        steps,
        time: t0.elapsed(),
    })
}
