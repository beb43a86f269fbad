//! Thick-restart Lanczos (Wu & Simon, SIAM J. Matrix Anal. Appl. 22, 2000)
//! in shift-invert mode for K phi = lambda M phi.
//!
//! The operator OP = (K - sigma M)^-1 M is self-adjoint in the M inner
//! product <x, y>_M = x^T M y; its eigenvalues theta = 1 / (lambda - sigma)
//! are largest for the lambda nearest above sigma (Ericsson & Ruhe, Math.
//! Comp. 35, 1980). The basis V is kept M-orthonormal by full
//! reorthogonalization (classical Gram-Schmidt applied twice, "CGS2"), with
//! M V stored beside V so that each step costs one solve and one product
//! with M. At a restart the wanted Ritz vectors (and more, up to half the
//! free space, as ARPACK's dsaup2 does) are kept; the projected matrix is
//! then diagonal with an arrow row, and the expansion continues from the
//! last residual vector. A Ritz pair (theta, y) is converged when the
//! estimate |beta_m s_m| of ||OP y - theta y||_M is at most tol * |theta|
//! (ARPACK's criterion).

use crate::EigError;
use crate::cholesky::SparseCholesky;
use crate::constraint::Projector;
use crate::sparse::{
    combination, inner, project, subtract_combination, sym_matmul, sym_matvec, update_rows,
};
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::SparseColMatRef;
use faer::{Accum, Col, ColRef, Mat, MatMut, MatRef};
use std::cell::Cell;
use std::time::{Duration, Instant};

/// Eigenvectors already found (M-orthonormal columns X) and M X: the
/// operator is deflated to P OP with P = I - X X^T M, whose spectrum is that
/// of OP with the found eigenvalues replaced by zero ("locking").
pub(crate) struct Locked {
    /// Locked vectors.
    pub x: Mat<f64>,
    /// M times the locked vectors.
    pub mx: Mat<f64>,
}

/// Solves with a factorization of K - sigma M: a Cholesky factor (sigma
/// below the spectrum) or an LBL^T one (sigma inside it, spectrum slicing).
pub(crate) trait ShiftSolve {
    /// Order of the factored matrix.
    fn order(&self) -> usize;
    /// B <- (K - sigma M)^-1 B.
    fn solve_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), EigError>;
}

impl ShiftSolve for SparseCholesky {
    fn order(&self) -> usize {
        self.n()
    }

    fn solve_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), EigError> {
        SparseCholesky::solve_in_place(self, rhs)
    }
}

/// The shift-invert operator: a factor of K - sigma M, M itself, optionally
/// constraints C x = 0 (the operator is then P (K - sigma M)^-1 M, see
/// [`crate::constraint`]) and locked vectors to deflate.
pub(crate) struct ShiftInvert<'a> {
    /// Mass matrix (both triangles stored).
    pub m: SparseColMatRef<'a, usize, f64>,
    /// Factor of K - sigma M.
    pub factor: &'a dyn ShiftSolve,
    /// Constraints on the eigenvectors, projected with the same factor.
    pub constraint: Option<&'a Projector>,
    /// Vectors to deflate, if any.
    pub locked: Option<Locked>,
    /// Wall time spent in the triangular solves (accumulated).
    pub solve_time: Cell<Duration>,
    /// Wall time spent in products with M (accumulated).
    pub mass_time: Cell<Duration>,
    /// Wall time spent on Ritz pairs of the projected matrix and restarts.
    pub ritz_time: Cell<Duration>,
}

impl ShiftInvert<'_> {
    /// Order of the matrices.
    pub fn n(&self) -> usize {
        self.m.nrows()
    }

    /// Dimension of the space the deflated operator acts on.
    pub fn dim(&self) -> usize {
        let locked = self.locked.as_ref().map_or(0, |l| l.x.ncols());
        let constrained = self.constraint.map_or(0, Projector::len);
        self.n().saturating_sub(locked + constrained)
    }

    /// y = M x.
    pub fn mass(&self, x: ColRef<'_, f64>) -> Col<f64> {
        let t0 = Instant::now();
        let mut y = Col::zeros(self.n());
        sym_matvec(self.m, x, y.as_mut());
        add_time(&self.mass_time, t0);
        y
    }

    /// y = P (K - sigma M)^-1 b, where b = M x for OP x.
    pub fn solve(&self, b: ColRef<'_, f64>) -> Result<Col<f64>, EigError> {
        let mut y = b.to_owned();
        let t0 = Instant::now();
        self.factor.solve_in_place(y.as_mat_mut())?;
        add_time(&self.solve_time, t0);
        self.deflate(y.as_mat_mut());
        Ok(y)
    }

    /// Y = M X for a block of columns.
    pub fn mass_block(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        let t0 = Instant::now();
        let y = sym_matmul(self.m, x);
        add_time(&self.mass_time, t0);
        y
    }

    /// Y = P (K - sigma M)^-1 B for a block of right-hand sides (B = M X for OP X).
    pub fn solve_block(&self, b: MatRef<'_, f64>) -> Result<Mat<f64>, EigError> {
        let t0 = Instant::now();
        let mut y = b.to_owned();
        self.factor.solve_in_place(y.as_mut())?;
        add_time(&self.solve_time, t0);
        self.deflate(y.as_mut());
        Ok(y)
    }

    /// Y <- P Y: into null(C) if constrained, then Y - X (M X)^T Y (twice:
    /// one pass leaves rounding-level components along the locked vectors X).
    pub fn deflate(&self, mut y: MatMut<'_, f64>) {
        if let Some(c) = self.constraint {
            c.project(y.rb_mut());
        }
        if let Some(l) = &self.locked {
            for _ in 0..2 {
                let h = inner(l.mx.as_ref(), y.rb());
                update_rows(y.rb_mut(), l.x.as_ref(), h.as_ref(), Accum::Add, -1.0);
            }
        }
    }
}

/// Told the Ritz values theta (descending) and their residual estimates
/// whenever a Lanczos method has them; returns true once it wants no more.
pub(crate) type Watch<'w> = &'w mut dyn FnMut(&[f64], &[f64]) -> bool;

/// Residual estimate to which the guard pairs (wanted beyond the first
/// `nsharp`, only to place the Sturm bound in a gap) are converged: their
/// Ritz values are then accurate to about its square.
pub(crate) const GUARD_TOL: f64 = 1e-6;

/// Wanted Ritz pairs (the first `nwant`) whose residual estimate meets the
/// tolerance: `tol` for the first `nsharp`, [`GUARD_TOL`] (or `tol` if
/// looser) for the guards.
pub(crate) fn converged_count(estimates: &[f64], nsharp: usize, nwant: usize, tol: f64) -> usize {
    let guard = tol.max(GUARD_TOL);
    (0..nwant.min(estimates.len()))
        .filter(|&i| estimates[i] <= if i < nsharp { tol } else { guard })
        .count()
}

/// The error of a run that stopped with `converged` of `requested` pairs
/// converged, with the wanted pairs' residual estimates.
pub(crate) fn not_converged(
    estimates: &[f64],
    requested: usize,
    converged: usize,
    iterations: usize,
) -> EigError {
    let residuals = estimates.to_vec();
    let worst = residuals.iter().copied().fold(0.0, f64::max);
    EigError::NotConverged {
        converged,
        requested,
        iterations,
        residuals,
        worst,
    }
}

/// Adds the time since `t0` to a clock.
pub(crate) fn add_time(clock: &Cell<Duration>, t0: Instant) {
    clock.set(clock.get() + t0.elapsed());
}

/// Parameters of one Lanczos run.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LanczosParams {
    /// Eigenpairs wanted (largest theta).
    pub nwant: usize,
    /// Of which the first are wanted to `tol`, the others are guards.
    pub nsharp: usize,
    /// Basis size before a restart (ncv), nwant < ncv <= n, or ncv = n.
    pub ncv: usize,
    /// Relative tolerance on ||OP y - theta y||_M / |theta|.
    pub tol: f64,
    /// Maximum number of restart cycles.
    pub max_iter: usize,
    /// Seed of the start vector.
    pub seed: u64,
}

/// Result of a converged Lanczos run.
#[derive(Debug, Clone)]
pub(crate) struct LanczosOutcome {
    /// Ritz values theta, descending (nwant of them).
    pub theta: Vec<f64>,
    /// Ritz vectors, M-orthonormal, in the order of `theta`.
    pub vectors: Mat<f64>,
    /// Restart cycles done (the first expansion counts as one).
    pub iterations: usize,
    /// Applications of OP (solves).
    pub applications: usize,
}

/// Deterministic pseudo-random vector with entries in [-1, 1) (xorshift64*).
pub(crate) fn start_vector(n: usize, seed: u64) -> Col<f64> {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    Col::from_fn(n, |_| {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        let r = s.wrapping_mul(0x2545_F491_4F6C_DD1D);
        (r >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    })
}

/// Lanczos basis: V (M-orthonormal columns), M V, and the projected matrix T.
struct Basis {
    v: Mat<f64>,
    mv: Mat<f64>,
    t: Mat<f64>,
}

/// Outcome of orthogonalizing a new vector against the basis.
struct Orthogonalized {
    w: Col<f64>,
    mw: Col<f64>,
    coeffs: Vec<f64>,
    norm: f64,
}

/// Classical Gram-Schmidt with reorthogonalization (Daniel, Gragg, Kaufman
/// & Stewart, Math. Comp. 30, 1976) in the M inner product:
/// w <- w - V h with h = (M V)^T w, repeated while a pass removes more than
/// 1 - 1/sqrt(2) of the M-norm (at most 5 passes). The M-norm between passes
/// is updated by Pythagoras; at the end M w is recomputed from w (keeping
/// M V by the same recurrence as V would let its error grow geometrically).
fn orthogonalize(
    op: &ShiftInvert<'_>,
    basis: &Basis,
    cols: usize,
    mut w: Col<f64>,
    mw: Col<f64>,
) -> Orthogonalized {
    let v = basis.v.subcols(0, cols);
    let mv = basis.mv.subcols(0, cols);
    let mut coeffs = vec![0.0; cols];
    let mut norm2 = crate::sparse::dot(w.as_ref(), mw.as_ref()).max(0.0);
    for _ in 0..5 {
        if cols == 0 || norm2 == 0.0 {
            break;
        }
        let h = project(mv, w.as_ref());
        subtract_combination(w.as_mut(), v, &h);
        let removed: f64 = h.iter().map(|x| x * x).sum();
        for (c, x) in coeffs.iter_mut().zip(&h) {
            *c += x;
        }
        let after = (norm2 - removed).max(0.0);
        let enough = after > 0.5 * norm2;
        norm2 = after;
        if enough {
            break;
        }
    }
    let mw = op.mass(w.as_ref());
    let norm = crate::sparse::dot(w.as_ref(), mw.as_ref()).max(0.0).sqrt();
    Orthogonalized {
        w,
        mw,
        coeffs,
        norm,
    }
}

/// A basis vector and M times it.
type Direction = (Col<f64>, Col<f64>);

/// A fresh direction: OP applied to a pseudo-random vector, M-orthogonal to
/// the first `cols` basis vectors and M-normalized. None if nothing is left
/// (the basis spans the whole range of OP).
fn fresh_direction(
    op: &ShiftInvert<'_>,
    basis: &Basis,
    cols: usize,
    seed: u64,
    applications: &mut usize,
) -> Result<Option<Direction>, EigError> {
    let r = start_vector(op.n(), seed);
    let mr = op.mass(r.as_ref());
    let w = op.solve(mr.as_ref())?;
    *applications += 1;
    let mw = op.mass(w.as_ref());
    let before = crate::sparse::dot(w.as_ref(), mw.as_ref()).max(0.0).sqrt();
    let o = orthogonalize(op, basis, cols, w, mw);
    // Tolerance: after CGS2, a remainder below 1e-10 of the input is rounding noise.
    if o.norm.is_nan() || o.norm <= 1e-10 * before {
        return Ok(None);
    }
    Ok(Some((o.w / o.norm, o.mw / o.norm)))
}

/// Runs thick-restart Lanczos until the `nwant` largest Ritz values of OP
/// converge, or fails with the residual estimates reached.
pub(crate) fn thick_restart_lanczos(
    op: &ShiftInvert<'_>,
    p: &LanczosParams,
    watch: Watch<'_>,
) -> Result<LanczosOutcome, EigError> {
    let n = op.n();
    let m = p.ncv;
    let dim = op.dim();
    if p.nwant == 0 || p.nwant > m || m > dim || (p.nwant == m && m < dim) {
        return Err(EigError::InvalidOption {
            what: format!(
                "need 0 < nev < ncv <= n (or nev <= ncv = n): nev {}, ncv {m}, n {dim}",
                p.nwant
            ),
        });
    }
    let mut basis = Basis {
        v: Mat::zeros(n, m + 1),
        mv: Mat::zeros(n, m + 1),
        t: Mat::zeros(m, m),
    };
    let mut applications = 0usize;
    let mut seed = p.seed;
    let Some((v0, mv0)) = fresh_direction(op, &basis, 0, seed, &mut applications)? else {
        return Err(EigError::DimensionMismatch {
            what: "operator has an empty range".into(),
        });
    };
    basis.v.col_mut(0).copy_from(&v0);
    basis.mv.col_mut(0).copy_from(&mv0);
    let mut k = 0usize;
    let mut iterations = 0usize;
    let mut watched = false;
    loop {
        iterations += 1;
        let (size, beta) = expand(op, &mut basis, k, m, &mut seed, &mut applications)?;
        let (theta, s) = crate::block::ritz_pairs(basis.t.submatrix(0, 0, size, size))?;
        let estimates: Vec<f64> = (0..size)
            .map(|i| (beta * s[(size - 1, i)]).abs() / theta[i].abs().max(f64::MIN_POSITIVE))
            .collect();
        let wanted = p.nwant.min(size);
        if !watched {
            watched = watch(&theta, &estimates);
        }
        let nconv = converged_count(&estimates, p.nsharp, wanted, p.tol);
        if nconv == p.nwant {
            return Ok(LanczosOutcome {
                theta: theta[..p.nwant].to_vec(),
                vectors: combination(basis.v.subcols(0, size), s.subcols(0, p.nwant)),
                iterations,
                applications,
            });
        }
        if iterations >= p.max_iter || size < m {
            return Err(not_converged(
                &estimates[..wanted],
                p.nwant,
                nconv,
                iterations,
            ));
        }
        k = restart(&mut basis, &s, &theta, beta, p.nwant, nconv, m);
    }
}

/// Lanczos steps j = k .. m-1 (vector j is in place). Returns the basis size
/// reached (m, or less if the range of OP is exhausted) and beta, the M-norm
/// of the residual coupling the last basis vector to the next.
fn expand(
    op: &ShiftInvert<'_>,
    basis: &mut Basis,
    k: usize,
    m: usize,
    seed: &mut u64,
    applications: &mut usize,
) -> Result<(usize, f64), EigError> {
    let mut beta = 0.0;
    for j in k..m {
        let w = op.solve(basis.mv.col(j))?;
        *applications += 1;
        let mw = op.mass(w.as_ref());
        let before = crate::sparse::dot(w.as_ref(), mw.as_ref()).max(0.0).sqrt();
        let o = orthogonalize(op, basis, j + 1, w, mw);
        for (i, &c) in o.coeffs.iter().enumerate() {
            basis.t[(i, j)] = c;
            basis.t[(j, i)] = c;
        }
        // Tolerance: a residual below 1e-12 of OP v_j means an invariant
        // subspace (rounding level after CGS2): continue with a fresh direction.
        let (next, coupling) = if o.norm > 1e-12 * before {
            (Some((o.w / o.norm, o.mw / o.norm)), o.norm)
        } else {
            *seed = seed.wrapping_add(1);
            let fresh = if j + 1 < op.dim() {
                fresh_direction(op, basis, j + 1, *seed, applications)?
            } else {
                None
            };
            (fresh, 0.0)
        };
        beta = coupling;
        let Some((vn, mvn)) = next else {
            return Ok((j + 1, 0.0));
        };
        basis.v.col_mut(j + 1).copy_from(&vn);
        basis.mv.col_mut(j + 1).copy_from(&mvn);
        if j + 1 < m {
            basis.t[(j + 1, j)] = coupling;
            basis.t[(j, j + 1)] = coupling;
        }
    }
    Ok((m, beta))
}

/// Thick restart: keep the first `keep` Ritz vectors, make the projected
/// matrix diag(theta) with the arrow beta * s_m, and move the residual
/// vector to position `keep`. Returns `keep`.
fn restart(
    basis: &mut Basis,
    s: &Mat<f64>,
    theta: &[f64],
    beta: f64,
    nwant: usize,
    nconv: usize,
    m: usize,
) -> usize {
    let keep = (nwant + nconv.min((m - nwant) / 2)).clamp(1, m - 1);
    for x in [&mut basis.v, &mut basis.mv] {
        let kept = combination(x.subcols(0, m), s.subcols(0, keep));
        x.subcols_mut(0, keep).copy_from(&kept);
        // The residual vector moves to position keep.
        let (left, right) = x.as_mut().split_at_col_mut(m);
        left.col_mut(keep).copy_from(right.col(0));
    }
    basis.t.fill(0.0);
    for i in 0..keep {
        basis.t[(i, i)] = theta[i];
        basis.t[(keep, i)] = beta * s[(m - 1, i)];
        basis.t[(i, keep)] = beta * s[(m - 1, i)];
    }
    keep
}
