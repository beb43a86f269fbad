//! Exact continuation of the eigenpairs of the linearized brake (eqs 20–22) from one state to
//! the next, with the low-rank form `T(λ) = λ² I + λ D + Ω² + U(λ) Vᵀ` of
//! [`crate::linearized`]: the one eigenvalue iteration of the crate, used by the friction
//! sweep, the Hopf refinement and the CHBM constraint.
//!
//! Each eigenpair `(λ, x, y)` (right and left vectors, `T(λ) x = 0`, `yᴴ T(λ) = 0`) is carried
//! to the new `U` by the two-sided Rayleigh functional iteration for nonlinear eigenproblems
//! (Schreiber 2008; Lancaster 1961): a Newton step on `yᴴ T(λ) x = 0` predicts λ from the old
//! vectors, then each iteration takes one step of nonlinear inverse iteration on both sides,
//! `x ← T(λ)⁻¹ T'(λ) x`, `y ← T(λ)⁻ᴴ T'(λ)ᴴ y`, and the Newton step
//! `λ ← λ - yᴴ T(λ) x / yᴴ T'(λ) x` (locally cubic). It stops when both residuals
//! `||T(λ) x||`, `||T(λ)ᴴ y||` are at round-off relative to `||T(λ)||`: λ is then an eigenvalue
//! to the accuracy of a backward-stable dense solver. Solves with `T(λ)` cost `O(n P²)`.
//!
//! A continued spectrum is accepted only if it passes checks that a lost or duplicated
//! eigenvalue cannot pass ([`validate`]): every branch converged, stays in the upper half plane
//! and correlates with its previous vector; no two branches hold the same eigenpair; and the
//! sum of all `2n` eigenvalues and of their squares equal `tr A` and `tr A²` of the state
//! matrix, known in closed form.

use crate::linearized::{Coupling, LinearizedBrake};
use faer::c64;
use rayon::prelude::*;

/// One eigenvalue with its right and left vectors (modal coordinates, unit 2-norm).
#[derive(Clone, Debug, PartialEq)]
pub struct Eigenpair {
    /// The eigenvalue `λ = a + iω` (eq 22; s⁻¹ and rad/s).
    pub lambda: c64,
    /// Right vector `x`, `T(λ) x = 0`.
    pub right: Vec<c64>,
    /// Left vector `y`, `yᴴ T(λ) = 0`.
    pub left: Vec<c64>,
}

/// Controls of the continuation of eigenpairs in friction (not to be confused with
/// `squeal_hbm::continuation::ContinuationOptions`, the arclength continuation of periodic
/// solutions).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct EigenContinuationOptions {
    /// Converged when `||T(λ) x|| <= residual_tolerance · ||T(λ)||` (and the same for `y`).
    pub residual_tolerance: f64,
    /// Inverse-iteration steps allowed per eigenpair and friction step.
    pub max_iterations: usize,
    /// A branch must keep `MAC >= min_correlation` between consecutive points.
    pub min_correlation: f64,
    /// Halvings of a friction step allowed before falling back to the dense solver there.
    pub max_halvings: usize,
    /// Every `check_every` points the continued eigenvalues are compared with a dense
    /// eigen-decomposition (0: never).
    pub check_every: usize,
    /// Relative agreement required by that comparison.
    pub check_tolerance: f64,
}

impl Default for EigenContinuationOptions {
    fn default() -> Self {
        Self {
            residual_tolerance: 1e-12,
            max_iterations: 8,
            min_correlation: 0.5,
            max_halvings: 6,
            check_every: 50,
            check_tolerance: 1e-8,
        }
    }
}

fn finite(z: c64) -> bool {
    z.re.is_finite() && z.im.is_finite()
}

/// `v / ||v||`, or `None` if that is not finite.
fn normalized(mut v: Vec<c64>) -> Option<Vec<c64>> {
    let norm = v.iter().map(|a| a.norm_sqr()).sum::<f64>().sqrt();
    if !(norm.is_finite() && norm > 0.0) {
        return None;
    }
    let inv = 1.0 / norm;
    for a in &mut v {
        *a *= inv;
    }
    Some(v)
}

/// `|aᴴ b|²` for unit vectors: the modal assurance criterion.
pub fn correlation(a: &[c64], b: &[c64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| p.conj() * q)
        .sum::<c64>()
        .norm_sqr()
}

/// Whether `(λ, x, y)` is an eigenpair of `T` to `tol` relative residual on both sides.
fn converged(lr: &LinearizedBrake, c: &Coupling, l: c64, x: &[c64], y: &[c64], tol: f64) -> bool {
    let bound = tol * lr.scale(c, l);
    let (rx, ry) = lr.residual_norms(c, l, x, y);
    rx <= bound && ry <= bound
}

/// Carries `start` to the coupling `c` by the two-sided Rayleigh functional iteration. Returns
/// the converged pair and the inverse-iteration steps taken, or `None` when it does not
/// converge in `max_iterations` steps or leaves the neighbourhood of `start`.
pub fn converge(
    lr: &LinearizedBrake,
    c: &Coupling,
    start: &Eigenpair,
    opts: &EigenContinuationOptions,
) -> Option<(Eigenpair, usize)> {
    let mut l = start.lambda;
    let mut x = start.right.clone();
    let mut y = start.left.clone();
    let (num, den) = lr.rayleigh(c, l, &x, &y);
    let predicted = l - num / den;
    if finite(predicted) {
        l = predicted;
    }
    for it in 1..=opts.max_iterations {
        let f = lr.factor(c, l);
        let bx = lr.apply_derivative(c, l, &x);
        let by = lr.apply_derivative_adjoint(c, l, &y);
        x = normalized(f.solve(lr, c, &bx))?;
        y = normalized(f.solve_adjoint(lr, c, &by))?;
        let (num, den) = lr.rayleigh(c, l, &x, &y);
        l -= num / den;
        if !finite(l) || (l - start.lambda).norm() > 0.5 * start.lambda.norm() {
            return None;
        }
        if converged(lr, c, l, &x, &y, opts.residual_tolerance) {
            return Some((
                Eigenpair {
                    lambda: l,
                    right: x,
                    left: y,
                },
                it,
            ));
        }
    }
    None
}

/// Polishes an eigenpair of a dense solver (eigenvalue and right vector) into a full
/// [`Eigenpair`] at the same coupling: the left vector comes from inverse iteration started at
/// `conj(x)` (exact when `T` is symmetric, at μ = 0). If the iteration fails or drifts from the
/// dense eigenvalue by more than `1e-8 |λ|`, the dense pair is kept with that start as its left
/// vector (the next continuation step then refines it).
pub fn seed(
    lr: &LinearizedBrake,
    c: &Coupling,
    lambda: c64,
    right: Vec<c64>,
    opts: &EigenContinuationOptions,
) -> Eigenpair {
    let left: Vec<c64> = right.iter().map(|v| v.conj()).collect();
    let start = Eigenpair {
        lambda,
        right,
        left,
    };
    match converge(lr, c, &start, opts) {
        Some((p, _)) if (p.lambda - lambda).norm() <= 1e-8 * lambda.norm() => p,
        _ => start,
    }
}

/// Carries every branch to the coupling `c` (in parallel: each branch is computed alone, so
/// the result does not depend on the thread count). `None` if any branch fails; else the pairs
/// and the total inverse-iteration steps.
pub fn continue_all(
    lr: &LinearizedBrake,
    c: &Coupling,
    from: &[Eigenpair],
    opts: &EigenContinuationOptions,
) -> Option<(Vec<Eigenpair>, usize)> {
    let out: Vec<Option<(Eigenpair, usize)>> = from
        .par_iter()
        .with_min_len(8)
        .map(|p| converge(lr, c, p, opts))
        .collect();
    let mut pairs = Vec::with_capacity(out.len());
    let mut steps = 0;
    for r in out {
        let (p, s) = r?;
        pairs.push(p);
        steps += s;
    }
    Some((pairs, steps))
}

/// Why a continued spectrum was rejected.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rejection {
    /// A branch left the upper half plane (its conjugate is the one the dense solver keeps).
    LowerHalfPlane {
        /// The branch (0-based).
        branch: usize,
    },
    /// A branch's vector lost its correlation with the previous point's.
    Correlation {
        /// The branch (0-based).
        branch: usize,
        /// Its MAC with the previous vector, below
        /// [`EigenContinuationOptions::min_correlation`].
        mac: f64,
    },
    /// Two branches hold the same eigenpair.
    Duplicate {
        /// The lower of the two branches (0-based).
        a: usize,
        /// The higher of the two branches (0-based).
        b: usize,
    },
    /// `Σ λ` or `Σ λ²` over the `2n` eigenvalues disagrees with `tr A` or `tr A²`.
    Trace {
        /// The sum over the continued eigenvalues and their conjugates (s⁻¹ or s⁻²).
        sum: f64,
        /// The trace it should equal.
        expected: f64,
    },
}

/// Relative closeness of two eigenvalues below which they may be one eigenvalue found twice.
const DUPLICATE: f64 = 1e-6;
/// Trace checks: tolerance relative to `Σ |λ|` and `Σ |λ|²`, far above the round-off of the
/// sums (`~n ε`) and far below the change a lost eigenvalue makes.
const TRACE: f64 = 1e-10;

/// Checks a continued spectrum `next` against the previous one and the traces of `A`.
pub fn validate(
    lr: &LinearizedBrake,
    c: &Coupling,
    prev: &[Eigenpair],
    next: &[Eigenpair],
    opts: &EigenContinuationOptions,
) -> Result<(), Rejection> {
    for (b, p) in next.iter().enumerate() {
        if p.lambda.im <= 0.0 {
            return Err(Rejection::LowerHalfPlane { branch: b });
        }
        let mac = correlation(&prev[b].right, &p.right);
        if mac < opts.min_correlation {
            return Err(Rejection::Correlation { branch: b, mac });
        }
    }
    duplicates(next)?;
    traces(lr, c, next)
}

/// No two branches on one eigenpair: eigenvalues within [`DUPLICATE`] with correlated vectors.
fn duplicates(pairs: &[Eigenpair]) -> Result<(), Rejection> {
    let mut order: Vec<usize> = (0..pairs.len()).collect();
    order.sort_by(|&a, &b| pairs[a].lambda.im.total_cmp(&pairs[b].lambda.im));
    for (i, &a) in order.iter().enumerate() {
        let la = pairs[a].lambda;
        let reach = DUPLICATE * la.norm();
        for &b in &order[i + 1..] {
            let lb = pairs[b].lambda;
            if lb.im - la.im > reach {
                break;
            }
            if (lb - la).norm() <= reach && correlation(&pairs[a].right, &pairs[b].right) > 0.5 {
                return Err(Rejection::Duplicate {
                    a: a.min(b),
                    b: a.max(b),
                });
            }
        }
    }
    Ok(())
}

/// `2 Σ Re λ = tr A` and `2 Σ Re λ² = tr A²` (each λ stands for itself and its conjugate).
fn traces(lr: &LinearizedBrake, c: &Coupling, pairs: &[Eigenpair]) -> Result<(), Rejection> {
    let (tr_a, tr_a2) = lr.traces(c);
    let s1: f64 = 2.0 * pairs.iter().map(|p| p.lambda.re).sum::<f64>();
    let s2: f64 = 2.0 * pairs.iter().map(|p| (p.lambda * p.lambda).re).sum::<f64>();
    let m1: f64 = pairs.iter().map(|p| p.lambda.norm()).sum();
    let m2: f64 = pairs.iter().map(|p| p.lambda.norm_sqr()).sum();
    if (s1 - tr_a).abs() > TRACE * 2.0 * m1 {
        return Err(Rejection::Trace {
            sum: s1,
            expected: tr_a,
        });
    }
    if (s2 - tr_a2).abs() > TRACE * 2.0 * m2 {
        return Err(Rejection::Trace {
            sum: s2,
            expected: tr_a2,
        });
    }
    Ok(())
}

/// Whether each continued eigenvalue has its own dense eigenvalue within `tol |λ|`.
pub fn agrees_with(pairs: &[Eigenpair], dense: &[c64], tol: f64) -> bool {
    let mut used = vec![false; dense.len()];
    for p in pairs {
        let mut best: Option<(f64, usize)> = None;
        for (i, d) in dense.iter().enumerate() {
            let e = (*d - p.lambda).norm();
            if !used[i] && best.is_none_or(|(b, _)| e < b) {
                best = Some((e, i));
            }
        }
        match best {
            Some((e, i)) if e <= tol * p.lambda.norm() => used[i] = true,
            _ => return false,
        }
    }
    true
}
