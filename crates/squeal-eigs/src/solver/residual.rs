//! The checks of a computed eigenpair set: M-normalization and ordering, residuals and backward errors, and the Sturm count that no eigenvalue was missed below the bound.

use super::*;

/// Sorts ascending (ties keep the backend's order) and scales every vector to
/// unit M-norm.
pub(crate) fn normalize(
    m: SparseColMatRef<'_, usize, f64>,
    values: Vec<f64>,
    vectors: Mat<f64>,
) -> (Vec<f64>, Mat<f64>) {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let n = vectors.nrows();
    let mut out = Mat::from_fn(n, order.len(), |i, c| vectors[(i, order[c])]);
    for start in (0..order.len()).step_by(8) {
        let cols = 8.min(order.len() - start);
        let mx = sym_matmul(m, out.subcols(start, cols));
        for c in 0..cols {
            let x = out.col(start + c);
            let s = dot(x, mx.col(c)).max(f64::MIN_POSITIVE).sqrt();
            out.col_mut(start + c).iter_mut().for_each(|v| *v /= s);
        }
    }
    (order.iter().map(|&j| values[j]).collect(), out)
}

/// Normwise backward errors of the eigenpairs (see [`Modes::residuals`]).
pub fn backward_errors(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    values: &[f64],
    vectors: &Mat<f64>,
) -> Vec<f64> {
    // Without constraints nothing can fail.
    residuals(k, m, None, values, vectors).unwrap_or_default()
}

/// [`backward_errors`], with the constraint forces C^T mu taken out of each
/// residual first (least squares) when there are constraints.
pub(crate) fn residuals(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    constraints: Option<&Constraints>,
    values: &[f64],
    vectors: &Mat<f64>,
) -> Result<Vec<f64>, EigError> {
    let (nk, nm) = (norm1(k), norm1(m));
    let mut out = Vec::with_capacity(values.len());
    for start in (0..values.len()).step_by(8) {
        let cols = 8.min(values.len() - start);
        let x = vectors.subcols(start, cols);
        let kx = sym_matmul(k, x);
        let mx = sym_matmul(m, x);
        let mut r = Mat::from_fn(x.nrows(), cols, |i, c| {
            kx[(i, c)] - values[start + c] * mx[(i, c)]
        });
        if let Some(c) = constraints {
            c.remove_forces(r.as_mut())?;
        }
        for c in 0..cols {
            let lam = values[start + c];
            out.push(r.col(c).norm_l2() / ((nk + lam.abs() * nm) * x.col(c).norm_l2()));
        }
    }
    Ok(out)
}

/// Sturm check of computed eigenvalues `values` (ascending, all of them
/// from the lowest up, possibly more than `nev`): places a bound in the
/// first gap at or above the nev-th value and compares the number of
/// computed values below it with the inertia of K - bound M. Returns the
/// bound and the count, or [`EigError::MissedEigenvalues`].
pub fn sturm_check(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    values: &[f64],
    nev: usize,
) -> Result<(f64, usize), EigError> {
    sturm_check_with(k, m, values, nev, None, None)
}

/// [`sturm_check`] reusing the analysis of a Cholesky factor of
/// K - sigma M (see [`FactorAnalysis`]; the factor's values may be freed
/// first, as a caller short of memory does), for the pencil constrained to
/// C x = 0 if `constraints` are given.
pub fn sturm_check_with(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    values: &[f64],
    nev: usize,
    analysis: Option<&FactorAnalysis>,
    constraints: Option<&Constraints>,
) -> Result<(f64, usize), EigError> {
    check_pair(k, m)?;
    if nev == 0 || nev > values.len() || values.iter().any(|v| !v.is_finite()) {
        return Err(EigError::InvalidOption {
            what: format!("sturm_check: nev {nev} of {} finite values", values.len()),
        });
    }
    if constraints.is_some_and(|c| c.n() != k.nrows()) {
        return Err(EigError::DimensionMismatch {
            what: "constraints and K differ in size".into(),
        });
    }
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let (bound, _) = sturm_bound(&sorted, nev);
    let par = faer::get_global_parallelism();
    let count = count_below_unchecked(k, m, bound, par, analysis, constraints)?;
    compare_count(bound, count, &sorted)
}

/// Relative separation below which two computed eigenvalues are taken as
/// copies of one (multiple) eigenvalue when placing the Sturm bound.
pub(super) const SAME_EIGENVALUE: f64 = 1e-6;

/// Places the Sturm bound in the first gap of the computed (ascending)
/// spectrum at or above index nev - 1, halfway between the two eigenvalues;
/// returns the bound and how many computed eigenvalues lie below it. Without
/// such a gap among the computed values, the bound is just above the last one.
/// Eigenvalues below 1e-3 of the largest computed one are compared on that
/// absolute scale, so that rounding-level rigid-body values (w^2 ~ 0) are
/// taken as one multiple zero.
pub(crate) fn sturm_bound(values: &[f64], nev: usize) -> (f64, usize) {
    let vmax = values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for j in nev..values.len() {
        let (a, b) = (values[j - 1], values[j]);
        let scale = a.abs().max(b.abs()).max(1e-3 * vmax).max(f64::MIN_POSITIVE);
        if b - a > SAME_EIGENVALUE * scale {
            return (0.5 * (a + b), j);
        }
    }
    let last = values[values.len() - 1];
    let bump = SAME_EIGENVALUE * vmax.max(f64::MIN_POSITIVE);
    (last + bump, values.len())
}
