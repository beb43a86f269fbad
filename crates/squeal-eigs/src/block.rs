//! Block thick-restart Lanczos (block Krylov-Schur: Zhou & Saad, Numer.
//! Algorithms 47, 2008; thick restart of Wu & Simon, SIAM J. Matrix Anal.
//! Appl. 22, 2000) in shift-invert mode for K phi = lambda M phi.
//!
//! The operator OP = (K - sigma M)^-1 M is applied to `block` vectors at
//! once: one sparse triangular solve pair with several right-hand sides
//! reads the factor once for all of them, which costs several times less per
//! vector than single solves (memory bandwidth), and a block finds up to
//! `block` copies of a multiple eigenvalue without relying on rounding.
//!
//! The basis V is M-orthonormal (block classical Gram-Schmidt against the
//! basis, repeated when the Daniel-Gragg-Kaufman-Stewart criterion asks for
//! it, then column by column inside the new block). M V is not stored: the
//! inner products are taken as V^T (M W) with M W recomputed after each pass
//! (a product with the sparse M costs less than reading a second n x ncv
//! matrix), which also halves the memory of the basis. The projected matrix T = V^T M OP V is filled from
//! the orthogonalization coefficients: OP V_j = V H + V_(j+1) R. Rayleigh-Ritz
//! on T gives Ritz pairs (theta, y = V s); with C the coupling of the basis to
//! the next block, ||OP y - theta y||_M = ||C s||_2, and a pair is converged
//! when that is at most tol |theta| (ARPACK's criterion). At a restart the
//! wanted Ritz vectors (and more, up to half the free space) are kept and the
//! projected matrix becomes diagonal with an arrow block (C S).
//!
//! A column of a new block that is numerically dependent on the basis is
//! replaced by a pseudo-random vector orthogonalized against the basis (and
//! the locked vectors); its coupling is zero. Rayleigh-Ritz stays exact for
//! any basis since T is always V^T M OP V. When no independent vector is
//! left (tiny problems), the caller falls back to single-vector Lanczos.

use crate::EigError;
use crate::lanczos::{
    LanczosOutcome, ShiftInvert, Watch, add_time, converged_count, not_converged, start_vector,
};
use crate::sparse::{combination, dot, inner, update_rows};
use faer::reborrow::Reborrow;
use faer::{Accum, Mat, Side};
use std::time::Instant;

/// Parameters of one block Lanczos run.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BlockParams {
    /// Eigenpairs wanted (largest theta).
    pub nwant: usize,
    /// Of which the first are wanted to `tol`, the others are guards.
    pub nsharp: usize,
    /// Want the Ritz values largest in magnitude (OP indefinite: a shift
    /// inside the spectrum) instead of the largest.
    pub by_magnitude: bool,
    /// Basis size at which a restart happens (nwant + block <= ncv).
    pub ncv: usize,
    /// Vectors per block.
    pub block: usize,
    /// Relative tolerance on ||OP y - theta y||_M / |theta|.
    pub tol: f64,
    /// Maximum number of restart cycles.
    pub max_iter: usize,
    /// Seed of the start block.
    pub seed: u64,
}

/// Basis of the block method: V (n x cap), T (cap x cap) and M times the
/// block appended last (the next one to expand).
struct Basis {
    v: Mat<f64>,
    t: Mat<f64>,
    m_last: Mat<f64>,
}

/// Tolerance of the dependence test: a column whose M-norm fell below this
/// fraction of its norm before orthogonalization is rounding noise.
const DEPENDENT: f64 = 1e-12;

/// Runs the block method. `Ok(None)`: the basis cannot be extended by an
/// independent vector (the problem is too small for this basis size).
/// `watch` is told the Ritz values after every block step (from a basis of
/// nwant + block vectors on) until it says it has seen enough, and at the end
/// of every cycle.
pub(crate) fn block_lanczos(
    op: &ShiftInvert<'_>,
    p: &BlockParams,
    watch: Watch<'_>,
) -> Result<Option<LanczosOutcome>, EigError> {
    let n = op.n();
    let b = p.block;
    let cap = p.ncv + b;
    if b == 0 || p.nwant == 0 || p.nwant + b > p.ncv {
        return Err(EigError::InvalidOption {
            what: format!(
                "block Lanczos needs nev + block <= ncv: nev {}, block {b}, ncv {}",
                p.nwant, p.ncv
            ),
        });
    }
    if cap + b > op.dim() {
        return Ok(None);
    }
    let mut basis = Basis {
        v: Mat::zeros(n, cap),
        t: Mat::zeros(cap, cap),
        m_last: Mat::zeros(n, b),
    };
    let mut seed = p.seed;
    let mut applications = 0usize;
    // Start block: OP applied to pseudo-random vectors (in the range of OP).
    let mut r = Mat::<f64>::zeros(n, b);
    for c in 0..b {
        r.col_mut(c)
            .copy_from(start_vector(n, seed.wrapping_add(c as u64)));
    }
    seed = seed.wrapping_add(b as u64);
    let mr = op.mass_block(r.as_ref());
    let w = op.solve_block(mr.as_ref())?;
    applications += b;
    if append_block(op, &mut basis, 0, w, &mut seed)?.is_none() {
        return Ok(None);
    }
    let (mut size, mut top) = (0usize, b);
    // Restart cycles, the current one included.
    let mut iterations = 1usize;
    let mut watched = false;
    loop {
        let w = op.solve_block(basis.m_last.as_ref())?;
        applications += b;
        let Some(()) = expand(op, &mut basis, size, top, w, &mut seed)? else {
            return Ok(None);
        };
        size = top;
        top += b;
        let full = top + b > cap;
        if size < p.nwant + b && !full {
            continue;
        }
        // Ritz pairs after every block step (converged ones end the expansion early) and
        // at the end of a cycle.
        let t0 = Instant::now();
        let (theta, s) = ritz_pairs(basis.t.submatrix(0, 0, size, size))?;
        let (theta, s) = match p.by_magnitude {
            true => by_magnitude(theta, s),
            false => (theta, s),
        };
        let (coupling, estimates) = residual_estimates(&basis.t, &theta, &s, size, b);
        add_time(&op.ritz_time, t0);
        if !watched {
            watched = watch(&theta, &estimates);
        }
        let nconv = converged(&estimates, p);
        if nconv == p.nwant {
            let out = outcome(&basis, &theta, &s, size, p.nwant);
            return Ok(Some(LanczosOutcome {
                iterations,
                applications,
                ..out
            }));
        }
        if !full {
            continue;
        }
        if iterations >= p.max_iter {
            return Err(not_converged(
                &estimates[..p.nwant],
                p.nwant,
                nconv,
                iterations,
            ));
        }
        iterations += 1;
        let keep = (p.nwant + nconv.min((size - p.nwant) / 2)).clamp(1, cap - 2 * b);
        let t0 = Instant::now();
        restart(&mut basis, &s, &theta, &coupling, size, keep, b);
        add_time(&op.ritz_time, t0);
        size = keep;
        top = keep + b;
    }
}

/// Wanted Ritz pairs whose residual estimate meets the tolerance.
fn converged(estimates: &[f64], p: &BlockParams) -> usize {
    converged_count(estimates, p.nsharp, p.nwant, p.tol)
}

/// The `nwant` Ritz pairs y = V s of a basis of `size` vectors (the counts
/// left at zero).
fn outcome(
    basis: &Basis,
    theta: &[f64],
    s: &Mat<f64>,
    size: usize,
    nwant: usize,
) -> LanczosOutcome {
    LanczosOutcome {
        theta: theta[..nwant].to_vec(),
        vectors: combination(basis.v.subcols(0, size), s.subcols(0, nwant)),
        iterations: 0,
        applications: 0,
    }
}

/// The coupling C S of the Ritz vectors to the next block and the residual
/// estimates ||C s_i|| / |theta_i| = ||OP y_i - theta_i y_i||_M / |theta_i|.
fn residual_estimates(
    t: &Mat<f64>,
    theta: &[f64],
    s: &Mat<f64>,
    size: usize,
    b: usize,
) -> (Mat<f64>, Vec<f64>) {
    let coupling = t.submatrix(size, 0, b, size) * s.as_ref();
    let estimates = (0..size)
        .map(|i| coupling.col(i).norm_l2() / theta[i].abs().max(f64::MIN_POSITIVE))
        .collect();
    (coupling, estimates)
}

/// Eigenpairs of the projected matrix T, largest first. T is scaled to unit
/// max-norm first: faer's symmetric eigensolver is accurate to rounding
/// relative to that scale, while the entries of T are 1 / (lambda - sigma),
/// tiny in SI units (e.g. 1e-9 s^2 for a brake disc).
pub(crate) fn ritz_pairs(t: faer::MatRef<'_, f64>) -> Result<(Vec<f64>, Mat<f64>), EigError> {
    let size = t.nrows();
    let scale = (0..size)
        .flat_map(|j| (0..size).map(move |i| (i, j)))
        .fold(0.0f64, |a, (i, j)| a.max(t[(i, j)].abs()));
    let scale = if scale > 0.0 && scale.is_finite() {
        scale
    } else {
        1.0
    };
    let scaled = Mat::<f64>::from_fn(size, size, |i, j| t[(i, j)] / scale);
    let evd = scaled
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| EigError::DenseEigen)?;
    // faer sorts ascending: reverse to get the largest theta first.
    let theta: Vec<f64> = (0..size).rev().map(|i| evd.S()[i] * scale).collect();
    let s = Mat::<f64>::from_fn(size, size, |r, c| evd.U()[(r, size - 1 - c)]);
    Ok((theta, s))
}

/// Ritz pairs reordered by |theta| descending (ties keep their order).
fn by_magnitude(theta: Vec<f64>, s: Mat<f64>) -> (Vec<f64>, Mat<f64>) {
    let mut order: Vec<usize> = (0..theta.len()).collect();
    order.sort_by(|&a, &b| theta[b].abs().total_cmp(&theta[a].abs()));
    let t = order.iter().map(|&i| theta[i]).collect();
    let s = Mat::from_fn(s.nrows(), s.ncols(), |r, c| s[(r, order[c])]);
    (t, s)
}

/// One block step: `w` = OP V[size..top] is orthogonalized against the
/// basis V[0..top] and appended as V[top..top+b]; fills T.
fn expand(
    op: &ShiftInvert<'_>,
    basis: &mut Basis,
    size: usize,
    top: usize,
    w: Mat<f64>,
    seed: &mut u64,
) -> Result<Option<()>, EigError> {
    let b = w.ncols();
    let Some((h, r)) = append_block(op, basis, top, w, seed)? else {
        return Ok(None);
    };
    for c in 0..b {
        for i in 0..size {
            basis.t[(i, size + c)] = h[(i, c)];
            basis.t[(size + c, i)] = h[(i, c)];
        }
        for d in 0..b {
            // The diagonal block is symmetric in exact arithmetic.
            let x = 0.5 * (h[(size + d, c)] + h[(size + c, d)]);
            basis.t[(size + d, size + c)] = x;
        }
        for d in 0..b {
            basis.t[(top + d, size + c)] = r[(d, c)];
            basis.t[(size + c, top + d)] = r[(d, c)];
        }
    }
    Ok(Some(()))
}

/// M-orthonormalizes the block `w` against V[0..at] and within itself and
/// stores it as V[at..at+b]: w = V[0..at] H + V[at..at+b] R with R upper
/// triangular. Returns (H, R), or None if no independent vector was found.
#[allow(clippy::type_complexity)]
fn append_block(
    op: &ShiftInvert<'_>,
    basis: &mut Basis,
    at: usize,
    mut w: Mat<f64>,
    seed: &mut u64,
) -> Result<Option<(Mat<f64>, Mat<f64>)>, EigError> {
    let b = w.ncols();
    let mut mw = op.mass_block(w.as_ref());
    let before: Vec<f64> = (0..b)
        .map(|c| dot(w.col(c), mw.col(c)).max(0.0).sqrt())
        .collect();
    let mut h = Mat::<f64>::zeros(at, b);
    for _ in 0..2 {
        if at == 0 {
            break;
        }
        let hp = inner(basis.v.subcols(0, at), mw.as_ref());
        update_rows(
            w.as_mut(),
            basis.v.subcols(0, at),
            hp.as_ref(),
            Accum::Add,
            -1.0,
        );
        // M W from W itself (not updated by the combinations, against drift).
        mw = op.mass_block(w.as_ref());
        h += &hp;
        // Daniel-Gragg-Kaufman-Stewart criterion: a second pass only if a
        // column lost more than 1 - 1/sqrt(2) of its M-norm (Pythagoras).
        let enough = (0..b).all(|c| {
            let removed: f64 = (0..at).map(|i| h[(i, c)] * h[(i, c)]).sum();
            before[c] * before[c] - removed > 0.5 * before[c] * before[c]
        });
        if enough {
            break;
        }
    }
    let mut r = Mat::<f64>::zeros(b, b);
    for c in 0..b {
        let mut norm = orthogonalize_in_block(&mut w, &mut mw, c, &mut r);
        if norm.is_nan() || norm <= DEPENDENT * before[c] {
            // Dependent column: a fresh pseudo-random direction, coupling zero.
            let mut found = false;
            for _ in 0..3 {
                *seed = seed.wrapping_add(1);
                let mut x = Mat::<f64>::zeros(op.n(), 1);
                x.col_mut(0).copy_from(start_vector(op.n(), *seed));
                op.deflate(x.as_mut());
                for _ in 0..2 {
                    let mx = op.mass_block(x.as_ref());
                    let hp = inner(basis.v.subcols(0, at), mx.as_ref());
                    update_rows(
                        x.as_mut(),
                        basis.v.subcols(0, at),
                        hp.as_ref(),
                        Accum::Add,
                        -1.0,
                    );
                }
                let fresh_before = x.col(0).norm_l2();
                w.col_mut(c).copy_from(x.col(0));
                let mx = op.mass_block(x.as_ref());
                mw.col_mut(c).copy_from(mx.col(0));
                let fresh_before = {
                    let mnorm = dot(w.col(c), mw.col(c)).max(0.0).sqrt();
                    if mnorm > 0.0 { mnorm } else { fresh_before }
                };
                let mut scratch = Mat::<f64>::zeros(b, b);
                norm = orthogonalize_in_block(&mut w, &mut mw, c, &mut scratch);
                if norm > 1e-8 * fresh_before {
                    found = true;
                    break;
                }
            }
            if !found {
                return Ok(None);
            }
            // Couplings to the columns before it stay; its own is zero.
            r[(c, c)] = 0.0;
        }
        let inv = 1.0 / norm;
        w.col_mut(c).iter_mut().for_each(|x| *x *= inv);
        mw.col_mut(c).iter_mut().for_each(|x| *x *= inv);
    }
    // M W kept by the in-block combinations (at most b of them per column).
    basis.m_last = mw;
    basis.v.subcols_mut(at, b).copy_from(&w);
    Ok(Some((h, r)))
}

/// Classical Gram-Schmidt (twice) of column c of the block against its
/// columns 0..c in the M inner product, keeping M W by the same
/// combinations; records the coefficients in column c of R and returns the
/// remaining M-norm (stored as R[c, c]).
fn orthogonalize_in_block(w: &mut Mat<f64>, mw: &mut Mat<f64>, c: usize, r: &mut Mat<f64>) -> f64 {
    for _ in 0..2 {
        if c == 0 {
            break;
        }
        let h = inner(mw.subcols(0, c), w.subcols(c, 1));
        for m in [&mut *w, &mut *mw] {
            let (left, right) = m.as_mut().split_at_col_mut(c);
            update_rows(
                right.subcols_mut(0, 1),
                left.rb(),
                h.as_ref(),
                Accum::Add,
                -1.0,
            );
        }
        for d in 0..c {
            r[(d, c)] += h[(d, 0)];
        }
    }
    let norm = dot(w.col(c), mw.col(c)).max(0.0).sqrt();
    r[(c, c)] = norm;
    norm
}

/// Thick restart: V[0..keep] = V S[.., 0..keep], the next block moves to
/// V[keep..keep+b], T = diag(theta) with the arrow block C S.
fn restart(
    basis: &mut Basis,
    s: &Mat<f64>,
    theta: &[f64],
    coupling: &Mat<f64>,
    size: usize,
    keep: usize,
    b: usize,
) {
    let kept = combination(basis.v.subcols(0, size), s.subcols(0, keep));
    basis.v.subcols_mut(0, keep).copy_from(&kept);
    // The next block (M of it stays in m_last) moves down.
    let next = basis.v.subcols(size, b).to_owned();
    basis.v.subcols_mut(keep, b).copy_from(&next);
    basis.t.fill(0.0);
    for i in 0..keep {
        basis.t[(i, i)] = theta[i];
        for d in 0..b {
            basis.t[(keep + d, i)] = coupling[(d, i)];
            basis.t[(i, keep + d)] = coupling[(d, i)];
        }
    }
}
