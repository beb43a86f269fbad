//! Spectrum slicing: the lowest eigenpairs of K phi = lambda M phi found
//! over several shifts, the shifted block Lanczos method of Grimes, Lewis &
//! Simon (SIAM J. Matrix Anal. Appl. 15, 1994) in a simple form.
//!
//! With one shift sigma below the spectrum, shift-invert Lanczos sees the
//! eigenvalues as theta = 1 / (lambda - sigma): a wide band of wanted
//! eigenvalues is compressed towards zero at its top, and a basis of
//! 3 nwant vectors orthogonalized in full costs n nwant^2 per restart. Here
//! each shift finds at most `slice` new pairs, those nearest to it:
//!
//! 1. The first shift is the caller's (a Cholesky factor, sigma below the
//!    spectrum): the lowest `slice` pairs plus guards.
//! 2. The next shift sigma' is put in a gap of the values found so far,
//!    below the top `guard` of them, and K - sigma' M is factored by LBL^T
//!    on the first factor's analysis. Its inertia counts the eigenvalues
//!    below sigma' (with constraints: nu(A) - nu(C A^-1 C^T), see
//!    [`crate::constraint`]). If all of them have been found, everything
//!    below sigma' is verified (the trust interval of Grimes et al.); if the
//!    nev lowest lie below a verified shift, the search ends.
//! 3. Otherwise block Lanczos runs with OP = (K - sigma' M)^-1 M, deflated
//!    by the pairs found (M-orthogonal complement, "locking"), for the Ritz
//!    values largest in magnitude: the eigenvalues nearest sigma' on both
//!    sides, which include any missed below it. Back to 2.
//!
//! The last shift placed in a gap above the nev-th value is the Sturm
//! check. Every pair is converged to the tolerance (no loose guards: the
//! pairs found are locked for the next shifts).

use crate::EigError;
use crate::block::{BlockParams, block_lanczos};
use crate::cholesky::SparseCholesky;
use crate::constraint::{ConstrainedFactor, Projector};
use crate::inertia::{Lblt, constrained_count};
use crate::lanczos::{Locked, ShiftInvert, ShiftSolve};
use crate::solver::{
    EigOptions, EigStats, FactoredPencil, Modes, default_ncv, merge, normalize, residuals,
    sturm_bound,
};
use crate::sparse::{shifted, sym_matmul};
use faer::Mat;
use faer::sparse::SparseColMatRef;
use std::time::Instant;

/// Shifts at most, as a multiple of the slices nev needs.
const SHIFTS_PER_SLICE: usize = 3;

/// The current shift's factorization: the caller's Cholesky factor or an
/// LBL^T of K - sigma M with its constraint projector.
struct Shift<'a> {
    sigma: f64,
    lblt: Option<Lblt<'a>>,
    projector: Option<Projector>,
}

/// The `nev` lowest eigenpairs by spectrum slicing (see the module
/// documentation); `factor` is the Cholesky factor of K - opts.shift M.
pub(crate) fn solve_sliced(
    pencil: FactoredPencil<'_>,
    nev: usize,
    opts: &EigOptions,
) -> Result<Modes, EigError> {
    let FactoredPencil {
        k,
        m,
        factor,
        constrained,
    } = pencil;
    let t0 = Instant::now();
    let n = k.nrows();
    let (constraints, dim) = (pencil.constraints(), pencil.dim());
    let target = (nev + opts.guard).min(dim);
    let max_shifts = SHIFTS_PER_SLICE * target.div_ceil(opts.slice) + 2;
    let mut stats = EigStats::default();
    let (mut values, mut vectors) = (Vec::<f64>::new(), Mat::<f64>::zeros(n, 0));
    // Everything below trust.0 has been found: trust.1 eigenvalues.
    let mut trust = (opts.shift, 0usize);
    let mut shift = Shift {
        sigma: opts.shift,
        lblt: None,
        projector: None,
    };
    let mut first = true;
    loop {
        if !first {
            // The inertia at this shift checks every value found below it.
            let count = shift_count(&shift)?;
            let found = values.iter().filter(|&&v| v < shift.sigma).count();
            if count == found {
                trust = (shift.sigma, count);
            }
            if trust.1 >= nev {
                break;
            }
        }
        if stats.shifts >= max_shifts {
            return Err(EigError::MissedEigenvalues {
                bound: trust.0,
                expected: target,
                found: trust.1,
            });
        }
        stats.shifts += 1;
        let (solve, projector): (&dyn ShiftSolve, Option<&Projector>) = match &shift.lblt {
            None => (factor, constrained.map(ConstrainedFactor::projector)),
            Some(l) => (l, shift.projector.as_ref()),
        };
        let locked = (vectors.ncols() > 0).then(|| Locked {
            mx: sym_matmul(m, vectors.as_ref()),
            x: vectors.clone(),
        });
        let op = ShiftInvert {
            m,
            factor: solve,
            constraint: projector,
            locked,
            solve_time: Default::default(),
            mass_time: Default::default(),
            ritz_time: Default::default(),
        };
        // New pairs for this shift (at least the guards, to find any missed below it).
        let want = target
            .saturating_sub(values.len())
            .min(opts.slice)
            .max(opts.guard.max(1));
        let nwant = (want + opts.guard).min(op.dim());
        let ncv = default_ncv(nwant, opts).min(op.dim());
        let block = opts.block_size.min(ncv.saturating_sub(nwant)).max(1);
        let params = BlockParams {
            nwant,
            nsharp: nwant,
            by_magnitude: !first,
            ncv,
            block,
            tol: opts.tol,
            max_iter: opts.max_iter,
            seed: opts.seed.wrapping_add(stats.shifts as u64),
        };
        let out = block_lanczos(&op, &params, &mut |_, _| true)?.ok_or_else(|| {
            EigError::InvalidOption {
                what: format!("spectrum slicing needs a basis of {ncv} + {block} vectors"),
            }
        })?;
        stats.iterations += out.iterations;
        stats.operator_applications += out.applications;
        stats.operator_time += op.solve_time.get();
        stats.mass_time += op.mass_time.get();
        stats.ritz_time += op.ritz_time.get();
        stats.block = block;
        stats.ncv = stats.ncv.max(ncv);
        let new_values = out.theta.iter().map(|t| shift.sigma + 1.0 / t).collect();
        let (v2, x2) = normalize(m, new_values, out.vectors);
        (values, vectors) = merge(values, vectors, v2, x2);
        // The next shift: in a gap below the top `guard` values found (they are checked
        // again from there), or in the gap above the nev-th once there are enough.
        let at = match values.len() >= target {
            true => nev,
            false => values.len().saturating_sub(opts.guard).max(trust.1 + 1),
        };
        let (sigma, _) = sturm_bound(&values, at.min(values.len()));
        let t = Instant::now();
        shift = factor_shift(k, m, factor, constraints, sigma, opts)?;
        stats.sturm_time += t.elapsed();
        first = false;
    }
    stats.solve_time = t0.elapsed();
    stats.computed = values.len();
    stats.rounds = stats.shifts;
    stats.sturm = Some(trust);
    stats.time = t0.elapsed();
    let kept = vectors.subcols(0, nev).to_owned();
    let residuals = residuals(k, m, constraints, &values[..nev], &kept)?;
    Ok(Modes {
        values: values[..nev].to_vec(),
        vectors: kept,
        residuals,
        guard_values: values[nev..].to_vec(),
        stats,
    })
}

/// LBL^T of K - sigma M on the analysis of `factor`, with the constraint
/// projector on it. A shift that hits an eigenvalue (a zero pivot) is moved
/// up by a relative 1e-9 (still in the gap it was placed in).
fn factor_shift<'a>(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    factor: &'a SparseCholesky,
    constraints: Option<&crate::constraint::Constraints>,
    sigma: f64,
    opts: &EigOptions,
) -> Result<Shift<'a>, EigError> {
    let mut sigma = sigma;
    for _ in 0..2 {
        let a = shifted(k, m, sigma)?;
        let lblt = Lblt::factorize(a.as_ref(), opts.par, Some(factor.analysis()))?;
        if lblt.inertia().zero == 0 {
            let projector = match constraints {
                Some(c) if !c.is_empty() => Some(Projector::new(c, &lblt, false)?),
                _ => None,
            };
            return Ok(Shift {
                sigma,
                lblt: Some(lblt),
                projector,
            });
        }
        sigma += 1e-9 * sigma.abs().max(f64::MIN_POSITIVE);
    }
    Err(EigError::SingularShift { sigma })
}

/// Eigenvalues below the shift: nu(K - sigma M), less nu(C A^-1 C^T) with
/// constraints.
fn shift_count(shift: &Shift<'_>) -> Result<usize, EigError> {
    let Some(lblt) = &shift.lblt else {
        return Ok(0);
    };
    let negative = lblt.inertia().negative;
    match &shift.projector {
        None => Ok(negative),
        Some(p) => constrained_count(negative, p.schur(), shift.sigma),
    }
}
