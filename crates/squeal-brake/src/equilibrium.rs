//! Eq (14): the static equilibrium `K x0 + F_nl(x0) = F_piston`, sliding at friction μ.
//!
//! **Closure and initial gaps.** Pair `p` closes by `δ_p = g_p · x - g0_p`, its relative
//! normal approach `g_p · x = n · (u_disc - u_pad)` less its initial gap `g0_p`
//! ([`ContactPair::initial_gap`](crate::model::ContactPair::initial_gap), positive when open;
//! stored as `gap = -g0`). The penalty law `F_c(δ) = k_l δ + k_nl δ³` for `δ > 0`, 0 otherwise
//! (eq 8), is continuous but only piecewise smooth: its tangent jumps from 0 to `k_l` at
//! `δ = 0`.
//!
//! **Continuation in the clamp force.** A brake whose pairs start open cannot be solved from
//! `x = 0` by Newton's method alone: until a pair touches, the pad moves freely along the
//! normal (the bundled pad is held in-plane only) and the residual does not fall. So eq (14)
//! is solved under a load `λ F_piston` ramped from `λ = 0` (`x = 0` is the equilibrium there)
//! to `λ = 1` in adaptive steps ([`NewtonOptions::first_load_step`], halved when Newton fails
//! at a step, doubled after an easy one), each step started from the previous equilibrium.
//! The first step is the whole load by default: a brake that Newton solves directly takes one
//! step, and its result is bit for bit the direct solution.
//!
//! **Newton at one load.** A backtracking line search on the residual norm, started "with the
//! contact closed": at the first iteration from `x = 0` open pairs use their linear stiffness
//! `k_l`, so that a start at zero penetration has a non-singular tangent. While every pair is
//! open the tangent is `K` alone, singular when the pad is free along the normal; there the
//! step uses `K` at full length if that reaches the open equilibrium (a pad held by springs:
//! one step, the open problem being linear) or lowers the residual with a pair closed, and
//! otherwise the closing stiffness `k_l` of every pair. (A pad free along the normal has a
//! `K` singular to round-off: its step is some 1e7 m along the free mode and "lowers" the
//! residual against the round-off stiffness there; those steps are refused.) A step with the closing
//! stiffness that does not lower the residual is still taken when it brings the nearest pair
//! closer, and lengthened to where the first pair touches (the penetrations are linear in `x`):
//! along a free mode the residual cannot fall before a pair touches, and these "approach"
//! steps cross a gap of any size in one or two iterations. Open and closed sets cannot cycle: every other step must lower the residual
//! norm, and when no step does the load step is halved, which starts Newton nearer to its
//! solution (the residual is continuous in `λ`).
//!
//! **When the brake cannot close.** If at the full load every pair is still open, the clamp
//! force is carried by the pad's restraints (springs, abutments) before the pad reaches the
//! disc: that open state *is* the equilibrium of this model, and it is reported as
//! [`BrakeError::GapsNotClosed`] with each pair's remaining opening. A load that pulls the pad
//! away is [`BrakeError::ContactOpen`].

use crate::error::{BrakeError, OpenPair};
use crate::model::Brake;
use faer::Mat;

/// Convergence controls of the Newton iteration and of the load continuation.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct NewtonOptions {
    /// Converged when `||K x + F_nl - λ F_piston|| <= tolerance * max(||λ F_piston||, ||F_nl||)`:
    /// relative to the forces being balanced (the contact forces carry the load even when a
    /// preload, not the piston, closes the contact).
    pub tolerance: f64,
    /// Newton iterations allowed per load step before [`BrakeError::NewtonFailed`].
    pub max_iterations: usize,
    /// Halvings of the step allowed by the line search.
    pub max_halvings: usize,
    /// The first load step of the continuation, as a fraction of the piston force in
    /// `(0, 1]`; 1 tries the full load at once.
    pub first_load_step: f64,
    /// The smallest load step (fraction of the piston force): when a step this small fails,
    /// the continuation stops with that step's error.
    pub min_load_step: f64,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 60,
            max_halvings: 40,
            first_load_step: 1.0,
            min_load_step: 1e-4,
        }
    }
}

/// A converged static equilibrium.
#[derive(Clone, Debug, PartialEq)]
pub struct Equilibrium {
    /// Friction coefficient μ the brake slides at.
    pub mu: f64,
    /// `x0` of eq (14).
    pub x: Vec<f64>,
    /// Newton iterations taken, over every load step (failed ones included).
    pub iterations: usize,
    /// Load steps of the continuation that converged (1 when the full load was solved at once;
    /// 1 also for a start from a given point, which is not ramped).
    pub load_steps: usize,
    /// Load steps that failed and were halved.
    pub rejected_load_steps: usize,
    /// Final `||K x + F_nl - F_piston|| / max(||F_piston||, ||F_nl||)`.
    pub residual: f64,
    /// Penetration `δ` of each pair at `x0` (m; positive: closed).
    pub penetrations: Vec<f64>,
    /// Normal contact force `F_n` of each pair at `x0` (N; 0 when open).
    pub normal_forces: Vec<f64>,
}

impl Equilibrium {
    /// Number of pairs in contact.
    pub fn closed_pairs(&self) -> usize {
        self.penetrations.iter().filter(|d| **d > 0.0).count()
    }

    /// The sum of the pairs' normal forces (N): the clamp force the contact carries.
    pub fn total_normal_force(&self) -> f64 {
        self.normal_forces.iter().sum()
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

fn max_penetration(brake: &Brake, x: &[f64]) -> f64 {
    brake
        .penetrations(x)
        .into_iter()
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The length `s >= 1` of an approach step from `x` to `x + s (end - x)`: on to where the
/// first approaching pair touches (`δ = 0`) when that lies beyond `end`; 1 when no pair
/// approaches.
fn approach_length(brake: &Brake, x: &[f64], end: &[f64]) -> f64 {
    let (d0, d1) = (brake.penetrations(x), brake.penetrations(end));
    let first_touch = d0
        .iter()
        .zip(&d1)
        .filter(|(a, b)| *b > *a)
        .map(|(a, b)| -a / (b - a))
        .fold(f64::INFINITY, f64::min);
    if first_touch.is_finite() {
        first_touch.max(1.0)
    } else {
        1.0
    }
}

/// Solves the Newton step's `K_t(x) dx = b` with the tangent of the pairs' own stiffness
/// (not the closing one of the first iteration from rest): `None` to use the dense LU of
/// `K + K_NL`. [`static_equilibrium_with`] takes one (e.g. a low-rank update of the
/// frictionless reference's modes, [`crate::projected`]); the step is the same to round-off.
pub type TangentSolve<'a> = &'a (dyn Fn(&[f64], &[f64]) -> Option<Vec<f64>> + Sync);

/// A Newton solution at one load.
struct Solved {
    x: Vec<f64>,
    residual: f64,
}

/// Newton's method for `K x + F_nl(x) = load F_piston` from `x` (module docs); `fresh` marks
/// a start from `x = 0` (its first iteration is taken with the contact closed). Returns the
/// iterations taken with the outcome.
fn newton_at(
    brake: &Brake,
    mu: f64,
    load: f64,
    mut x: Vec<f64>,
    fresh: bool,
    opts: &NewtonOptions,
    tangent: Option<TangentSolve>,
) -> (Result<Solved, BrakeError>, usize) {
    let n = brake.size();
    let force_scale = |x: &[f64]| {
        let mut f = vec![0.0; n];
        brake.add_nonlinear_force(x, None, mu, &mut f);
        (load * norm(&brake.f_piston))
            .max(norm(&f))
            .max(f64::MIN_POSITIVE)
    };
    let mut r = brake.static_residual_at(&x, mu, load);
    let mut rn = norm(&r);
    let mut scale = force_scale(&x);
    let mut it = 0;
    while rn > opts.tolerance * scale {
        if it == opts.max_iterations {
            let e = BrakeError::NewtonFailed {
                iterations: it,
                residual: rn / scale,
                tolerance: opts.tolerance,
            };
            return (Err(e), it);
        }
        let first = it == 0 && fresh;
        let all_open = brake.penetrations(&x).iter().all(|d| *d <= 0.0);
        // The tangents to try: the true one, then (every pair open) the closing stiffness.
        let closings: &[bool] = match (first, all_open) {
            (true, _) => &[true],
            (false, true) => &[false, true],
            (false, false) => &[false],
        };
        let mut accepted = false;
        for &closed in closings {
            let minus_r: Vec<f64> = r.iter().map(|v| -v).collect();
            let fast = tangent.filter(|_| !closed).and_then(|t| t(&x, &minus_r));
            let dx = match fast {
                Some(dx) => Mat::from_fn(n, 1, |i, _| dx[i]),
                None => {
                    let jac = &brake.k + brake.nonlinear_jacobian(&x, mu, closed).0;
                    let rhs = Mat::from_fn(n, 1, |i, _| minus_r[i]);
                    // faer's LU, factored on rayon's threads where large (the same bits:
                    // crate::dense_par).
                    crate::dense_par::lu_solve(jac, &rhs)
                }
            };
            if (0..n).any(|i| !dx[(i, 0)].is_finite()) {
                if closed {
                    return (Err(BrakeError::SingularTangent), it + 1);
                }
                continue;
            }
            let at = |x: &[f64], step: f64| -> Vec<f64> {
                (0..n).map(|i| x[i] + step * dx[(i, 0)]).collect()
            };
            // Backtracking line search on ||r||; the bare `K` of an all-open state only at
            // full length (its step is the open equilibrium, or far off when `K` is singular).
            let bare = all_open && !closed;
            let halvings = if bare { 0 } else { opts.max_halvings };
            let mut step = 1.0;
            for _ in 0..=halvings {
                let trial = at(&x, step);
                let rt = brake.static_residual_at(&trial, mu, load);
                let rtn = norm(&rt);
                let converged = rtn <= opts.tolerance * force_scale(&trial);
                // The bare K of an all-open state: only to the open equilibrium or into
                // contact. A near-singular K (a pad free along the normal) "lowers" the
                // residual by a step of 1e7 m against round-off stiffness.
                let sound =
                    !bare || converged || brake.penetrations(&trial).iter().any(|d| *d > 0.0);
                if sound && (rtn < rn || converged) {
                    scale = force_scale(&trial);
                    x = trial;
                    r = rt;
                    rn = rtn;
                    accepted = true;
                    break;
                }
                step *= 0.5;
            }
            if !accepted && closed && all_open {
                // An approach step: at least the whole step, and on to the first touch (the
                // penetrations are linear in x), if it brings the nearest pair closer.
                let trial = at(&x, approach_length(brake, &x, &at(&x, 1.0)));
                if max_penetration(brake, &trial) > max_penetration(brake, &x) {
                    r = brake.static_residual_at(&trial, mu, load);
                    rn = norm(&r);
                    scale = force_scale(&trial);
                    x = trial;
                    accepted = true;
                }
            }
            if accepted {
                break;
            }
        }
        it += 1;
        if !accepted {
            if brake.penetrations(&x).iter().all(|d| *d <= 0.0) {
                return (Err(BrakeError::ContactOpen), it);
            }
            let e = BrakeError::NewtonFailed {
                iterations: it,
                residual: rn / scale,
                tolerance: opts.tolerance,
            };
            return (Err(e), it);
        }
    }
    let residual = rn / scale;
    (Ok(Solved { x, residual }), it)
}

/// Solves eq (14) at friction `mu`: from `start` at the full load (a continuation in μ), or
/// with `start = None` by continuation in the clamp force from `x = 0` (module docs).
pub fn static_equilibrium(
    brake: &Brake,
    mu: f64,
    start: Option<&[f64]>,
    opts: &NewtonOptions,
) -> Result<Equilibrium, BrakeError> {
    static_equilibrium_with(brake, mu, start, opts, None)
}

/// [`static_equilibrium`] with the Newton steps from `start` solved by `tangent` where it
/// gives one ([`TangentSolve`]).
pub fn static_equilibrium_with(
    brake: &Brake,
    mu: f64,
    start: Option<&[f64]>,
    opts: &NewtonOptions,
    tangent: Option<TangentSolve>,
) -> Result<Equilibrium, BrakeError> {
    // A vibration-only stiffness is not in eq (14) ([`crate::vibration_only`]); the given
    // tangent solve knows only the whole `K`.
    let statics = crate::vibration_only::static_brake(brake);
    let (brake, tangent) = match &statics {
        Some(b) => (b, None),
        None => (brake, tangent),
    };
    let (solved, iterations, load_steps, rejected) = match start {
        Some(x0) => {
            let (s, it) = newton_at(brake, mu, 1.0, x0.to_vec(), false, opts, tangent);
            (s?, it, 1, 0)
        }
        None => load_ramp(brake, mu, opts)?,
    };
    let penetrations = brake.penetrations(&solved.x);
    if penetrations.iter().all(|d| *d <= 0.0) {
        return Err(open_at_full_load(brake, &solved.x));
    }
    let normal_forces = brake
        .pairs
        .iter()
        .map(|p| p.response(&solved.x, None, mu).normal)
        .collect();
    Ok(Equilibrium {
        mu,
        x: solved.x,
        iterations,
        load_steps,
        rejected_load_steps: rejected,
        residual: solved.residual,
        penetrations,
        normal_forces,
    })
}

/// The continuation in the clamp force: `(solution, iterations, steps, rejected steps)`.
fn load_ramp(
    brake: &Brake,
    mu: f64,
    opts: &NewtonOptions,
) -> Result<(Solved, usize, usize, usize), BrakeError> {
    let n = brake.size();
    let mut x = vec![0.0; n];
    let first = opts.first_load_step.max(opts.min_load_step).min(1.0);
    let (mut load, mut step) = (0.0f64, first);
    let (mut iterations, mut steps, mut rejected) = (0, 0, 0);
    loop {
        let target = if load + step >= 1.0 { 1.0 } else { load + step };
        let (outcome, it) = newton_at(brake, mu, target, x.clone(), steps == 0, opts, None);
        iterations += it;
        match outcome {
            Ok(s) => {
                steps += 1;
                load = target;
                if load == 1.0 {
                    return Ok((s, iterations, steps, rejected));
                }
                x = s.x;
                // An easy step (a quarter of the iterations allowed or fewer): a longer one.
                if it <= opts.max_iterations / 4 {
                    step *= 2.0;
                }
            }
            Err(e) => {
                rejected += 1;
                step *= 0.5;
                if step < opts.min_load_step {
                    return Err(e);
                }
            }
        }
    }
}

/// The error for an equilibrium `x` at the full load with every pair open: the restraints
/// carry the clamp force ([`BrakeError::GapsNotClosed`]), or, when every pair opened further
/// than it started, the load pulls the pad away ([`BrakeError::ContactOpen`]).
fn open_at_full_load(brake: &Brake, x: &[f64]) -> BrakeError {
    let pairs: Vec<OpenPair> = brake
        .pairs
        .iter()
        .enumerate()
        .map(|(p, pair)| OpenPair {
            pair: p + 1,
            initial_gap: pair.initial_gap,
            opening: -pair.penetration(x),
        })
        .collect();
    if pairs.iter().all(|p| p.opening > p.initial_gap) {
        return BrakeError::ContactOpen;
    }
    BrakeError::GapsNotClosed { pairs }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::PenaltyCoulomb;
    use crate::model::ContactPair;
    use std::sync::Arc;

    /// A pad (mass on a spring to ground? no: free in z) pressed on a disc held by a spring.
    fn pad_on_disc(force: f64) -> Brake {
        // dofs: 0 disc z (spring kd to ground), 1 pad z (free), 2 pad x (spring kx), 3 disc x.
        let kd = 1e8;
        let mut k = Mat::zeros(4, 4);
        k[(0, 0)] = kd;
        k[(2, 2)] = 5e7;
        k[(3, 3)] = 2e8;
        let pair = ContactPair {
            disc_point: 0,
            pad_point: 0,
            position: [0.0; 3],
            normal_direction: [0.0, 0.0, 1.0],
            sliding_direction: [1.0, 0.0, 0.0],
            normal: vec![(0, 1.0), (1, -1.0)],
            tangent: vec![(3, 1.0), (2, -1.0)],
            initial_gap: 0.0,
            surface_speed: None,
            law: Arc::new(PenaltyCoulomb {
                k_linear: 1e7,
                k_cubic: 1e17,
            }),
        };
        Brake {
            m: Mat::identity(4, 4),
            k,
            f_piston: vec![0.0, -force, 0.0, 0.0],
            c: None,
            k_vibration: None,
            pairs: vec![pair],
        }
    }

    #[test]
    fn equilibrium_balances_the_piston_force() {
        let force = 300.0;
        let b = pad_on_disc(force);
        let mu = 0.4;
        let eq = static_equilibrium(&b, mu, None, &NewtonOptions::default()).unwrap();
        assert!(eq.residual <= 1e-10);
        // Independent check: the contact force equals the piston force (the pad is free in z),
        // so k_l d + k_nl d^3 = F; solve the scalar cubic by bisection.
        let (mut lo, mut hi) = (0.0f64, 1e-3f64);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if 1e7 * mid + 1e17 * mid.powi(3) > force {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        // The cubic's root is found to round-off by 200 bisections.
        assert!(
            (eq.penetrations[0] - lo).abs() < 1e-12 * lo.max(1e-9) + 1e-18,
            "{} vs {lo}",
            eq.penetrations[0]
        );
        // Disc z: -F / kd (pushed down); friction: disc x = -mu F / k, pad x = +mu F / k.
        assert!((eq.x[0] + force / 1e8).abs() < 1e-12 * force / 1e8 * 1e3);
        assert!((eq.x[3] + mu * force / 2e8).abs() < 1e-9 * mu * force / 2e8);
        assert!((eq.x[2] - mu * force / 5e7).abs() < 1e-9 * mu * force / 5e7);
    }

    #[test]
    fn pulling_the_pad_away_is_an_error_not_an_answer() {
        let b = pad_on_disc(-300.0);
        let r = static_equilibrium(&b, 0.4, None, &NewtonOptions::default());
        assert!(
            matches!(
                r,
                Err(BrakeError::ContactOpen) | Err(BrakeError::SingularTangent)
            ),
            "{r:?}"
        );
    }

    /// A pad on a spring `k_s` to ground (one dof `u`, along the normal, away from the disc),
    /// pressed by `F` onto a rigid disc through pairs with initial gaps `g0`: the approach is
    /// `w = -u` and pair `p` closes by `δ_p = w - g0_p`.
    fn held_pad(force: f64, k_spring: f64, gaps: &[f64]) -> Brake {
        let pairs = gaps
            .iter()
            .map(|&g0| ContactPair {
                disc_point: 0,
                pad_point: 0,
                position: [0.0; 3],
                normal_direction: [0.0, 0.0, 1.0],
                sliding_direction: [1.0, 0.0, 0.0],
                normal: vec![(0, -1.0)],
                tangent: vec![],
                initial_gap: g0,
                surface_speed: None,
                law: Arc::new(PenaltyCoulomb {
                    k_linear: KL,
                    k_cubic: KNL,
                }),
            })
            .collect();
        Brake {
            m: Mat::identity(1, 1),
            k: Mat::from_fn(1, 1, |_, _| k_spring),
            f_piston: vec![-force],
            c: None,
            k_vibration: None,
            pairs,
        }
    }

    const KL: f64 = 1e7;
    const KNL: f64 = 1e17;

    /// The real root of `δ³ + p δ + q = 0` with `p > 0`, by Cardano's formula.
    fn cardano(p: f64, q: f64) -> f64 {
        let s = (q * q / 4.0 + p * p * p / 27.0).sqrt();
        (-q / 2.0 + s).cbrt() + (-q / 2.0 - s).cbrt()
    }

    /// The approach `w` solving `k_s w + Σ_p F_c(w - g0_p) = F`, by bisection to the last bit.
    fn bisect_approach(force: f64, k_spring: f64, gaps: &[f64]) -> f64 {
        let f = |w: f64| {
            k_spring * w
                + gaps
                    .iter()
                    .map(|g| crate::contact::cubic_penalty(w - g, KL, KNL).0)
                    .sum::<f64>()
                - force
        };
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..2000 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if f(mid) > 0.0 { hi = mid } else { lo = mid }
        }
        lo
    }

    fn ramped(first_load_step: f64) -> NewtonOptions {
        NewtonOptions {
            first_load_step,
            ..NewtonOptions::default()
        }
    }

    #[test]
    fn a_pad_on_a_spring_closes_its_gap_as_cardano_says() {
        // k_s g0 = 100 N of the 300 N go into the spring before the pair touches; then
        // k_nl δ³ + (k_s + k_l) δ + (k_s g0 - F) = 0.
        let (force, ks, g0) = (300.0, 1e6, 1e-4);
        let b = held_pad(force, ks, &[g0]);
        let exact = cardano((ks + KL) / KNL, (ks * g0 - force) / KNL);
        // Cardano against bisection: both at round-off of δ ≈ 1.2e-5 m (measured 1e-16 rel.).
        let bis = bisect_approach(force, ks, &[g0]) - g0;
        assert!((exact - bis).abs() < 1e-13 * exact, "{exact} vs {bis}");
        for step in [1.0, 0.1, 0.013] {
            let eq = static_equilibrium(&b, 0.0, None, &ramped(step)).unwrap();
            // The residual is 1e-10 of the 300 N balanced: δ to 1e-10 F / (k_l + k_s) ≈ 3e-15 m,
            // 2.5e-10 of δ; measured below 1e-13 relative. 1e-9 allows for the ramp's stop.
            let d = eq.penetrations[0];
            assert!(
                (d - exact).abs() < 1e-9 * exact,
                "step {step}: {d} vs {exact}"
            );
            // The pair carries what the spring does not: F - k_s (δ + g0), to the same accuracy.
            let fc = force - ks * (exact + g0);
            assert!((eq.normal_forces[0] - fc).abs() < 1e-9 * force);
            if step < 1.0 {
                // A real ramp: more than one step, every one converged.
                assert!(eq.load_steps > 1, "{eq:?}");
            }
            eprintln!(
                "first step {step}: {} load steps ({} rejected), {} Newton iterations, delta rel. err {:.1e}",
                eq.load_steps,
                eq.rejected_load_steps,
                eq.iterations,
                (d - exact).abs() / exact
            );
        }
    }

    #[test]
    fn a_second_pair_with_a_larger_gap_closes_only_under_enough_load() {
        // Gaps 20 and 60 um, k_s = 1e6 N/m: the second pair touches at
        // F = k_s 60e-6 + F_c(40e-6) = 60 + 400 + 6400 N = 6860 N.
        let (ks, gaps) = (1e6, [2e-5, 6e-5]);
        for (force, second_closed) in [(3000.0, false), (12000.0, true)] {
            let b = held_pad(force, ks, &gaps);
            let w = bisect_approach(force, ks, &gaps);
            for step in [1.0, 0.05] {
                let eq = static_equilibrium(&b, 0.0, None, &ramped(step)).unwrap();
                for (p, g) in gaps.iter().enumerate() {
                    // As above: the residual's 1e-10 relative is ~1e-14 m of closure; 1e-9 of
                    // the approach (measured below 1e-13).
                    assert!(
                        (eq.penetrations[p] - (w - g)).abs() < 1e-9 * w,
                        "F {force}, step {step}, pair {p}: {} vs {}",
                        eq.penetrations[p],
                        w - g
                    );
                }
                assert_eq!(eq.closed_pairs(), 1 + second_closed as usize);
                // The spring and the pairs share the clamp force (the residual's 1e-10).
                let total = ks * w + eq.total_normal_force();
                assert!((total - force).abs() < 1e-9 * force, "{total} vs {force}");
            }
        }
    }

    #[test]
    fn a_free_pad_with_a_gap_moves_through_it_and_presses_as_without() {
        // The pad of `pad_on_disc` is free along the normal: it travels through the gap rigidly
        // and the pair then carries the whole force, so δ is the zero-gap one and the pad sits
        // g0 further down. Today's Newton stopped here with "open at every pair".
        let force = 300.0;
        let closed =
            static_equilibrium(&pad_on_disc(force), 0.4, None, &NewtonOptions::default()).unwrap();
        // 0.1 mm and 10 mm: the approach steps go to the first touch, whatever the gap.
        for (g0, step) in [(1e-4, 1.0), (1e-4, 0.1), (1e-2, 1.0), (1e-2, 0.01)] {
            let mut b = pad_on_disc(force);
            b.pairs[0].initial_gap = g0;
            let eq = static_equilibrium(&b, 0.4, None, &ramped(step)).unwrap();
            // Both converged to 1e-10 of 300 N: δ (≈ 1.8e-5 m) to ~3e-15 m; 1e-9 relative.
            let d = eq.penetrations[0];
            assert!((d - closed.penetrations[0]).abs() < 1e-9 * d, "{d}");
            // The pad (dof 1) is g0 further towards the disc; the disc (dof 0) where it was.
            assert!((eq.x[1] - (closed.x[1] - g0)).abs() < 1e-9 * g0);
            assert!((eq.x[0] - closed.x[0]).abs() < 1e-9 * closed.x[0].abs());
            eprintln!(
                "free pad, gap {g0}, first step {step}: {} load steps, {} iterations",
                eq.load_steps, eq.iterations
            );
        }
    }

    #[test]
    fn a_gap_the_load_cannot_close_is_a_typed_error_with_the_openings() {
        // k_s g0 = 1e6 × 1e-4 = 100 N > 60 N: the spring holds the pad 60 um down, 40 um short.
        let (force, ks, g0) = (60.0, 1e6, 1e-4);
        let b = held_pad(force, ks, &[g0, 2.0 * g0]);
        for step in [1.0, 0.1] {
            match static_equilibrium(&b, 0.0, None, &ramped(step)) {
                Err(BrakeError::GapsNotClosed { pairs }) => {
                    assert_eq!(pairs.len(), 2);
                    // The open state is linear (K x = F): exact to round-off of 1e-4 m.
                    for (p, open) in pairs.iter().enumerate() {
                        let g = g0 * (p + 1) as f64;
                        assert_eq!((open.pair, open.initial_gap), (p + 1, g));
                        let want = g - force / ks;
                        assert!((open.opening - want).abs() < 1e-15, "{open:?}");
                    }
                    let text = BrakeError::GapsNotClosed { pairs }.to_string();
                    assert!(text.contains("pair 1 open by 40.000 um (initial gap 100.000 um)"));
                    assert!(text.contains("close_initial_gaps"), "{text}");
                }
                other => panic!("step {step}: {other:?}"),
            }
        }
        // Just enough load (k_s g0 and a little) closes the first pair.
        let eq = static_equilibrium(&held_pad(101.0, ks, &[g0]), 0.0, None, &ramped(1.0)).unwrap();
        assert_eq!(eq.closed_pairs(), 1);
    }
}
