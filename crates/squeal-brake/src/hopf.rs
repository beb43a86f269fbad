//! The Hopf point μ0 of a sweep by Newton's method on `Re λ(μ) = τ`, one eigenpair continued
//! exactly from μ to μ ([`crate::continuation`]), kept inside the bracket of the crossing.
//!
//! The derivative is exact: with right and left vectors `x`, `y` of `T(λ; μ)`,
//! `dλ/dμ = -yᴴ (∂T/∂μ) x / yᴴ T'(λ) x` (first-order perturbation of a simple eigenvalue),
//! where `∂T/∂μ = (∂U/∂μ) Vᵀ` holds the friction coupling and the change of the contact
//! stiffnesses along the equilibrium path ([`LowRank::stiffness_rates`]). Each Newton point is
//! moved past the root by a quarter of the tolerance, so that once Newton has converged the
//! next evaluation lands on the other side and closes the bracket.

use crate::continuation::{Eigenpair, converge, seed};
use crate::equilibrium::Equilibrium;
use crate::error::BrakeError;
use crate::lowrank::{Coupling, LowRank};
use crate::model::Brake;
use crate::spectrum::Reference;
use crate::sweep::{Crossing, Hopf, State, Sweep, SweepOptions, SweepPoint, Walker, partner};
use faer::c64;
use rayon::prelude::*;

/// The tracked branch at one friction value: `f = Re λ - τ` and `df/dμ`.
struct Eval {
    eq: Equilibrium,
    c: Coupling,
    pair: Eigenpair,
    f: f64,
    slope: f64,
}

impl Eval {
    fn mu(&self) -> f64 {
        self.eq.mu
    }
}

/// `Re dλ/dμ` of an eigenpair at coupling `c`.
fn slope(lr: &LowRank, c: &Coupling, p: &Eigenpair) -> f64 {
    let dk = lr.stiffness_rates(c);
    let (_, den) = lr.rayleigh(c, p.lambda, &p.right, &p.left);
    (-lr.mu_derivative(c, &dk, &p.right, &p.left) / den).re
}

fn eval(lr: &LowRank, eq: Equilibrium, c: Coupling, pair: Eigenpair, tau: f64) -> Eval {
    let s = slope(lr, &c, &pair);
    Eval {
        f: pair.lambda.re - tau,
        slope: s,
        eq,
        c,
        pair,
    }
}

/// Column `j` of a spectrum's modes.
fn mode(point: &SweepPoint, j: usize) -> Vec<c64> {
    let m = &point.spectrum.modes;
    (0..m.nrows()).map(|i| m[(i, j)]).collect()
}

/// The tracked branch at sweep point `k`, polished with its left vector.
fn at_point(w: &Walker, sweep: &Sweep, branch: usize, k: usize, tau: f64) -> Eval {
    let point = &sweep.points[k];
    let j = sweep.branches[branch][k];
    let c = w.lr.coupling(w.brake, &point.equilibrium);
    let pair = seed(
        w.lr,
        &c,
        point.spectrum.values[j],
        mode(point, j),
        &w.opts.continuation,
    );
    eval(w.lr, point.equilibrium.clone(), c, pair, tau)
}

/// The branch at `mu`, continued from `from`; `None` if the continuation fails.
fn evaluate(w: &Walker, mu: f64, from: &Eval, tau: f64) -> Result<Option<Eval>, BrakeError> {
    let eq = w.equilibrium(mu, &from.eq)?;
    let c = w.lr.coupling(w.brake, &eq);
    Ok(converge(w.lr, &c, &from.pair, &w.opts.continuation)
        .map(|(pair, _)| eval(w.lr, eq, c, pair, tau)))
}

/// The next friction value to evaluate: Newton from the latest evaluation, moved a quarter
/// tolerance past the root; regula falsi when that leaves the bracket; bisection when the
/// bracket shrank by less than half over the last two evaluations.
fn next_mu(lo: &Eval, hi: &Eval, cur: &Eval, tol: f64, slow: bool) -> f64 {
    let (a, b) = (lo.mu(), hi.mu());
    let mid = 0.5 * (a + b);
    if slow {
        return mid;
    }
    let nudge = if cur.f > 0.0 { -0.25 * tol } else { 0.25 * tol };
    let newton = cur.mu() - cur.f / cur.slope + nudge;
    if newton.is_finite() && newton > a && newton < b {
        return newton;
    }
    let falsi = (a * hi.f - b * lo.f) / (hi.f - lo.f);
    let w = b - a;
    if falsi.is_finite() && falsi > a + 0.01 * w && falsi < b - 0.01 * w {
        falsi
    } else {
        mid
    }
}

/// Refines crossing `c` of a continued sweep. `None` when the continuation fails somewhere
/// (the caller then refines with dense spectra).
pub(crate) fn refine(
    brake: &Brake,
    reference: &Reference,
    lr: &LowRank,
    sweep: &Sweep,
    c: &Crossing,
    opts: &SweepOptions,
    tau: f64,
) -> Result<Option<Hopf>, BrakeError> {
    let mut w = Walker {
        brake,
        reference,
        lr,
        opts,
        stats: Default::default(),
    };
    let mut lo = at_point(&w, sweep, c.branch, c.k, tau);
    let mut hi = at_point(&w, sweep, c.branch, c.k + 1, tau);
    if !(lo.f <= 0.0 && hi.f > 0.0) {
        return Ok(None);
    }
    let mut cur_is_hi = hi.f.abs() < lo.f.abs();
    let mut widths = vec![hi.mu() - lo.mu()];
    let mut evaluations = 0;
    while hi.mu() - lo.mu() > opts.mu_tolerance && evaluations < opts.max_refinements {
        let slow = widths.len() >= 3 && widths[widths.len() - 1] > 0.5 * widths[widths.len() - 3];
        let cur = if cur_is_hi { &hi } else { &lo };
        let mu = next_mu(&lo, &hi, cur, opts.mu_tolerance, slow);
        let from = if mu - lo.mu() <= hi.mu() - mu {
            &lo
        } else {
            &hi
        };
        let Some(e) = evaluate(&w, mu, from, tau)? else {
            return Ok(None);
        };
        evaluations += 1;
        cur_is_hi = e.f > 0.0;
        if cur_is_hi {
            hi = e;
        } else {
            lo = e;
        }
        widths.push(hi.mu() - lo.mu());
    }
    let Some((point, index)) = upper_point(&mut w, sweep, c, &hi)? else {
        return Ok(None);
    };
    Ok(Some(Hopf {
        mu0: 0.5 * (lo.mu() + hi.mu()),
        frequency_hz: hi.pair.lambda.im / (2.0 * std::f64::consts::PI),
        branch: c.branch,
        partner: partner(sweep, c),
        bracket: (lo.mu(), hi.mu()),
        real_part_at_bracket: (lo.f, hi.f),
        evaluations,
        point,
        index,
    }))
}

/// The full spectrum at the upper end of the bracket and the branch's index in it: the sweep
/// point itself if the bracket kept it, else every branch continued from the nearer sweep
/// point of the crossing. `None` if the tracked branch is not found there.
fn upper_point(
    w: &mut Walker,
    sweep: &Sweep,
    c: &Crossing,
    hi: &Eval,
) -> Result<Option<(SweepPoint, usize)>, BrakeError> {
    let k_hi = c.k + 1;
    if hi.mu() == sweep.points[k_hi].equilibrium.mu {
        return Ok(Some((
            sweep.points[k_hi].clone(),
            sweep.branches[c.branch][k_hi],
        )));
    }
    let k = if hi.mu() - c.mu_lo <= c.mu_hi - hi.mu() {
        c.k
    } else {
        k_hi
    };
    let point = &sweep.points[k];
    let base_c = w.lr.coupling(w.brake, &point.equilibrium);
    let pairs: Vec<Eigenpair> = (0..sweep.branches.len())
        .into_par_iter()
        .map(|b| {
            let j = sweep.branches[b][k];
            let right = mode(point, j);
            seed(
                w.lr,
                &base_c,
                point.spectrum.values[j],
                right,
                &w.opts.continuation,
            )
        })
        .collect();
    let base = State {
        eq: point.equilibrium.clone(),
        c: base_c,
        pairs,
    };
    let mut state = w.step_to(&base, hi.eq.clone(), hi.c.clone())?;
    let tracked = &mut state.pairs[c.branch];
    if (tracked.lambda - hi.pair.lambda).norm() > 1e-8 * hi.pair.lambda.norm() {
        return Ok(None);
    }
    // The same eigenpair as the refinement's, to the last bit.
    *tracked = hi.pair.clone();
    let (point, position) = crate::sweep::sweep_point(&state);
    Ok(Some((point, position[c.branch])))
}
