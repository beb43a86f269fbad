//! The Hopf point μ0 of a sweep by Newton's method on `Re λ(μ) = τ`, one eigenpair continued
//! exactly from μ to μ ([`crate::continuation`]), kept inside the bracket of the crossing.
//!
//! Where two modes coalesce (mode coupling) their eigenvalues meet at one frequency and split
//! in real part; the identity of "the branch" across the split is then a matter of tracking
//! between two sweep points, and following one of the two eigenvalues can jump from the one
//! that goes unstable to the one that does not. The function whose root is sought is
//! therefore the larger real part of the crossing branch and its partner, both continued:
//! continuous through the coalescence, and the unstable one's above it. A bracket that closes
//! on a jump of that function (it is not a root) is refused.
//!
//! The derivative is exact: with right and left vectors `x`, `y` of `T(λ; μ)`,
//! `dλ/dμ = -yᴴ (∂T/∂μ) x / yᴴ T'(λ) x` (first-order perturbation of a simple eigenvalue),
//! where `∂T/∂μ = (∂U/∂μ) Vᵀ` holds the friction coupling and the change of the contact
//! elements' responses along the equilibrium path ([`LinearizedBrake::mu_rates`]). Each Newton point is
//! moved past the root by a quarter of the tolerance, so that once Newton has converged the
//! next evaluation lands on the other side and closes the bracket.
//!
//! Without continued eigenpairs (the dense and projected sweeps, or a continuation that fails)
//! the crossing is refined by the Illinois variant of regula falsi on the same function, the
//! branches followed by correlation (`regula_falsi`).

use crate::continuation::{Eigenpair, converge, seed};
use crate::equilibrium::Equilibrium;
use crate::error::BrakeError;
use crate::linearized::{Coupling, LinearizedBrake};
use crate::model::Brake;
use crate::spectrum::{Reference, Spectrum};
use crate::sweep::{Crossing, Hopf, State, Sweep, SweepOptions, SweepPoint, Walker, partner};
use crate::tracking::mac;
use faer::c64;
use rayon::prelude::*;

/// The tracked branches at one friction value: `f = max Re λ - τ` over them and `df/dμ`
/// of the larger.
struct Eval {
    eq: Equilibrium,
    c: Coupling,
    /// The crossing branch and its partner (when it has one).
    pairs: Vec<Eigenpair>,
    /// Which of `pairs` has the larger real part.
    top: usize,
    f: f64,
    slope: f64,
}

impl Eval {
    fn mu(&self) -> f64 {
        self.eq.mu
    }
}

/// `Re dλ/dμ` of an eigenpair at coupling `c`.
fn slope(brake: &Brake, lr: &LinearizedBrake, c: &Coupling, p: &Eigenpair) -> f64 {
    // The coupling is the brake's own (it cannot fail); without rates the refinement falls
    // back on regula falsi (a NaN slope gives no Newton step).
    let Ok((du0, du1)) = lr.mu_rates(brake, c) else {
        return f64::NAN;
    };
    let (_, den) = lr.rayleigh(c, p.lambda, &p.right, &p.left);
    let num = lr.coupling_derivative(c, &du0, du1.as_deref(), p.lambda, &p.right, &p.left);
    (-num / den).re
}

fn eval(
    brake: &Brake,
    lr: &LinearizedBrake,
    eq: Equilibrium,
    c: Coupling,
    pairs: Vec<Eigenpair>,
    tau: f64,
) -> Eval {
    let top = (0..pairs.len())
        .max_by(|&a, &b| {
            pairs[a]
                .lambda
                .re
                .total_cmp(&pairs[b].lambda.re)
                .then(b.cmp(&a))
        })
        .unwrap_or(0);
    let s = slope(brake, lr, &c, &pairs[top]);
    Eval {
        f: pairs[top].lambda.re - tau,
        slope: s,
        eq,
        c,
        pairs,
        top,
    }
}

impl Eval {
    fn pair(&self) -> &Eigenpair {
        &self.pairs[self.top]
    }
}

/// Column `j` of a spectrum's modes.
fn mode(point: &SweepPoint, j: usize) -> Vec<c64> {
    let m = &point.spectrum.modes;
    (0..m.nrows()).map(|i| m[(i, j)]).collect()
}

/// The tracked branches at sweep point `k`, polished with their left vectors.
fn at_point(w: &Walker, sweep: &Sweep, branches: &[usize], k: usize, tau: f64) -> Eval {
    let point = &sweep.points[k];
    let c = w.lr.coupling(w.brake, &point.equilibrium);
    let pairs = branches
        .iter()
        .map(|&b| {
            let j = sweep.branches[b][k];
            seed(
                w.lr,
                &c,
                point.spectrum.values[j],
                mode(point, j),
                &w.opts.continuation,
            )
        })
        .collect();
    eval(w.brake, w.lr, point.equilibrium.clone(), c, pairs, tau)
}

/// The branches at `mu`, continued from `from`; `None` if the continuation fails.
fn evaluate(w: &Walker, mu: f64, from: &Eval, tau: f64) -> Result<Option<Eval>, BrakeError> {
    let eq = w.equilibrium(mu, &from.eq)?;
    let c = w.lr.coupling(w.brake, &eq);
    let mut pairs = Vec::with_capacity(from.pairs.len());
    for p in &from.pairs {
        match converge(w.lr, &c, p, &w.opts.continuation) {
            Some((q, _)) => pairs.push(q),
            None => return Ok(None),
        }
    }
    Ok(Some(eval(w.brake, w.lr, eq, c, pairs, tau)))
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
    lr: &LinearizedBrake,
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
    let mut branches = vec![c.branch];
    branches.extend(partner(sweep, c));
    // Both ends continued from the lower sweep point, so that the two branches keep their
    // identities across the bracket.
    let mut lo = at_point(&w, sweep, &branches, c.k, tau);
    let Some(mut hi) = evaluate(&w, c.mu_hi, &lo, tau)? else {
        return Ok(None);
    };
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
    // A root, not a jump: across the final bracket f changes by about its slope times the
    // width (a jump of the tracked eigenvalue would leave a finite gap).
    let width = hi.mu() - lo.mu();
    let expected = 10.0 * lo.slope.abs().max(hi.slope.abs()) * width;
    if hi.f - lo.f > expected + 1e-9 * hi.pair().lambda.norm() {
        return Ok(None);
    }
    let Some((point, index, branch)) = upper_point(&mut w, sweep, c, branches[hi.top], &hi)? else {
        return Ok(None);
    };
    Ok(Some(Hopf {
        mu0: 0.5 * (lo.mu() + hi.mu()),
        frequency_hz: hi.pair().lambda.im / (2.0 * std::f64::consts::PI),
        branch,
        partner: branches
            .iter()
            .copied()
            .find(|&b| b != branch)
            .or_else(|| partner(sweep, c).filter(|&b| b != branch)),
        bracket: (lo.mu(), hi.mu()),
        real_part_at_bracket: (lo.f, hi.f),
        evaluations,
        point,
        index,
    }))
}

/// The full spectrum at the upper end of the bracket, every branch continued from the nearer
/// sweep point of the crossing, with the index in it of the refinement's eigenvalue and the
/// branch that holds it (`branch` when the identities did not swap). `None` if no branch
/// holds it there.
fn upper_point(
    w: &mut Walker,
    sweep: &Sweep,
    c: &Crossing,
    branch: usize,
    hi: &Eval,
) -> Result<Option<(SweepPoint, usize, usize)>, BrakeError> {
    let k_hi = c.k + 1;
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
    // The branch whose eigenvalue is the refinement's (the identities may have swapped).
    let target = hi.pair().lambda;
    let Some(found) = (0..state.pairs.len())
        .filter(|&b| (state.pairs[b].lambda - target).norm() <= 1e-8 * target.norm())
        .min_by_key(|&b| (b != branch, b))
    else {
        return Ok(None);
    };
    // The same eigenpair as the refinement's, to the last bit.
    state.pairs[found] = hi.pair().clone();
    let (point, position) = crate::sweep::sweep_point(&state);
    Ok(Some((point, position[found], found)))
}

/// The equilibrium at a friction value from a given state.
pub(crate) type EquilibriumAt<'a> = dyn Fn(f64, &[f64]) -> Result<Equilibrium, BrakeError> + 'a;

/// Finds, in a new spectrum, the mode continuing a tracked one (best eigenvector correlation,
/// ties broken by eigenvalue distance).
fn follow(from: &Spectrum, j: usize, to: &Spectrum) -> usize {
    let l = from.values[j];
    let mut best = (f64::INFINITY, 0);
    for i in 0..to.values.len() {
        let d = (to.values[i] - l).norm() / (0.05 * l.norm()).max(f64::MIN_POSITIVE);
        let c = (1.0 - mac(from, j, to, i)) + d.min(1.0);
        if c < best.0 {
            best = (c, i);
        }
    }
    best.1
}

/// The largest change of the real part across a closed bracket of `width` in μ that still
/// counts as a root, for an eigenvalue of modulus `size`: `1e-6 |λ|` where `Re λ` crosses zero
/// with a finite slope (a Hopf point of a damped brake: over a bracket of 1e-8 the change is
/// the slope times 1e-8, far below), or `0.1 |λ| √width` where it rises as a square root (the
/// coalescence of an undamped pair, `Re λ ≈ s √(μ − μ0)`, whose change over any bracket
/// straddling μ0 is up to `s √width`; `s` is a fraction of `|λ|`, 0.045 |λ| on the bundled
/// brake's 4.1 kHz pair). A jump between two modes does not shrink with the bracket and
/// exceeds both once the bracket is closed.
fn resolved_jump(size: f64, width: f64) -> f64 {
    (1e-6 * size).max(0.1 * size * width.max(0.0).sqrt())
}

/// Refines a crossing by the Illinois variant of regula falsi on the larger real part of the
/// crossing branch and its partner (as [`crate::hopf`] does, for the same reason: where two
/// modes coalesce, either may carry the instability), keeping a bracket. Both are followed by
/// correlation from the lower end of the bracket. `equilibrium_at(μ, from)`: the equilibrium at
/// μ from the state `from`.
pub(crate) fn regula_falsi(
    equilibrium_at: &EquilibriumAt<'_>,
    spectrum_at: &dyn Fn(&Equilibrium) -> Result<Spectrum, BrakeError>,
    sweep: &Sweep,
    c: &Crossing,
    opts: &SweepOptions,
    tau: f64,
) -> Result<Hopf, BrakeError> {
    let mut branches = vec![c.branch];
    branches.extend(partner(sweep, c));
    // One end: μ, the point, the followed modes' indices in it, the larger real part - τ and
    // which of them has it.
    struct End {
        mu: f64,
        point: SweepPoint,
        modes: Vec<usize>,
        f: f64,
        top: usize,
    }
    let end = |mu: f64, point: SweepPoint, modes: Vec<usize>| {
        let top = (0..modes.len())
            .max_by(|&a, &b| {
                let v = &point.spectrum.values;
                v[modes[a]].re.total_cmp(&v[modes[b]].re).then(b.cmp(&a))
            })
            .unwrap_or(0);
        let f = point.spectrum.values[modes[top]].re - tau;
        End {
            mu,
            point,
            modes,
            f,
            top,
        }
    };
    let follow_all = |from: &End, to: &Spectrum| -> Vec<usize> {
        from.modes
            .iter()
            .map(|&j| follow(&from.point.spectrum, j, to))
            .collect()
    };
    let lo_point = sweep.points[c.k].clone();
    let mut lo = end(
        c.mu_lo,
        lo_point,
        branches.iter().map(|&b| sweep.branches[b][c.k]).collect(),
    );
    let hi_point = sweep.points[c.k + 1].clone();
    let modes = follow_all(&lo, &hi_point.spectrum);
    let mut hi = end(c.mu_hi, hi_point, modes);
    let (mut f_lo, mut f_hi) = (lo.f, hi.f);
    let mut side = 0i8;
    let mut evaluations = 0;
    while hi.mu - lo.mu > opts.mu_tolerance && evaluations < opts.max_refinements {
        let mut mu = (lo.mu * f_hi - hi.mu * f_lo) / (f_hi - f_lo);
        // Keep well inside the bracket; fall back to bisection when regula falsi stalls.
        let width = hi.mu - lo.mu;
        if !mu.is_finite() || mu <= lo.mu + 0.01 * width || mu >= hi.mu - 0.01 * width {
            mu = 0.5 * (lo.mu + hi.mu);
        }
        let eq = equilibrium_at(mu, &lo.point.equilibrium.x)?;
        let sp = spectrum_at(&eq)?;
        let modes = follow_all(&lo, &sp);
        let e = end(
            mu,
            SweepPoint {
                equilibrium: eq,
                spectrum: sp,
            },
            modes,
        );
        evaluations += 1;
        if e.f > 0.0 {
            f_hi = e.f;
            hi = e;
            if side == 1 {
                f_lo *= 0.5;
            }
            side = 1;
        } else {
            f_lo = e.f;
            lo = e;
            if side == -1 {
                f_hi *= 0.5;
            }
            side = -1;
        }
    }
    let size = hi.point.spectrum.values[hi.modes[hi.top]].norm();
    if !(lo.f <= 0.0 && hi.f > 0.0) || hi.f - lo.f > resolved_jump(size, hi.mu - lo.mu) {
        return Err(BrakeError::HopfNotResolved {
            bracket: (lo.mu, hi.mu),
            real_parts: (lo.f + tau, hi.f + tau),
        });
    }
    let index = hi.modes[hi.top];
    Ok(Hopf {
        mu0: 0.5 * (lo.mu + hi.mu),
        frequency_hz: hi.point.spectrum.frequency_hz(index),
        branch: branches[hi.top],
        partner: branches.iter().copied().find(|&b| b != branches[hi.top]),
        bracket: (lo.mu, hi.mu),
        real_part_at_bracket: (lo.f, hi.f),
        evaluations,
        index,
        point: hi.point,
    })
}

#[cfg(test)]
mod tests {
    use super::resolved_jump;

    #[test]
    fn a_square_root_onset_is_a_root_and_a_jump_between_modes_is_not() {
        // The bundled brake's undamped 4.1 kHz pair: |λ| = 2.55e4 1/s, Re λ ≈ 1139 √(μ − μ0)
        // (0.111 1/s across the bracket of 9.5e-9 the refinement closed on).
        let (size, width): (f64, f64) = (2.55e4, 9.5e-9);
        assert!(1139.0 * width.sqrt() <= resolved_jump(size, width));
        // A damped Hopf point's finite slope (1.7e3 1/s per unit μ) over the same bracket.
        assert!(1.7e3 * width <= resolved_jump(size, width));
        // Two modes 1 1/s apart in real part: no bracket closes on them.
        assert!(1.0 > resolved_jump(size, width));
        // A jump of 1e-6 |λ| is a root at any width, as before.
        assert_eq!(resolved_jump(size, 0.0), 1e-6 * size);
    }
}
