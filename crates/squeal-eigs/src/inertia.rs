//! Sturm sequence check: the number of eigenvalues of K phi = lambda M phi
//! below a bound b equals the number of negative eigenvalues of K - b M
//! (Sylvester's law of inertia, M positive definite), read from a
//! symmetric-indefinite factorization P (K - b M) P^T = L B L^T.
//!
//! faer 0.24 offers, for sparse matrices, LDL^T without pivoting and an
//! "intranode" LBL^T: Bunch-Kaufman pivoting with 1x1 and 2x2 blocks inside
//! each supernode. Any symmetric permutation keeps the inertia, so the
//! intranode pivoting is sound; it only limits the pivot choice (a supernode
//! with no acceptable pivot takes a small one), which can hurt stability in
//! extreme cases but does not change the counting rule. We force the
//! supernodal variant: faer's simplicial path silently falls back to
//! unpivoted LDL^T. The inertia of B is read block by block: a 1x1 block d
//! counts by its sign; a 2x2 block [a s; s c] has one negative and one
//! positive eigenvalue if ac - s^2 < 0, else two of the sign of a + c.

use crate::EigError;
use crate::cholesky::analyze_with;
use crate::ordering::nested_dissection;
use crate::sparse::{check_pair, check_symmetric, shifted};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::SparseColMatRef;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{CholeskySymbolicParams, SymbolicCholeskyRaw};
use faer::{Par, Side};

/// Counts of negative, zero and positive eigenvalues of a symmetric matrix.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Inertia {
    /// Negative eigenvalues.
    pub negative: usize,
    /// Zero eigenvalues (exactly singular pivots).
    pub zero: usize,
    /// Positive eigenvalues.
    pub positive: usize,
}

/// Inertia of a symmetric matrix (both triangles stored) from faer's
/// supernodal intranode LBL^T factorization.
pub fn inertia(a: SparseColMatRef<'_, usize, f64>) -> Result<Inertia, EigError> {
    check_symmetric(a, "A")?;
    inertia_unchecked(a, faer::get_global_parallelism(), None)
}

/// Sturm count: the number of eigenvalues of K phi = lambda M phi strictly
/// below `sigma` (negative eigenvalues of K - sigma M). An exactly singular
/// K - sigma M (sigma is an eigenvalue to working precision) is an error.
pub fn count_below(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    sigma: f64,
) -> Result<usize, EigError> {
    check_pair(k, m)?;
    count_below_unchecked(k, m, sigma, faer::get_global_parallelism(), None)
}

/// [`count_below`] without the input checks (the caller has done them),
/// with a fill-reducing permutation (`perm[new] = old`) to reuse, e.g. the
/// one of a Cholesky factor of K - sigma' M (any permutation keeps the
/// inertia; `None`: nested dissection of K - sigma M).
pub(crate) fn count_below_unchecked(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    sigma: f64,
    par: Par,
    perm: Option<&[usize]>,
) -> Result<usize, EigError> {
    if !sigma.is_finite() {
        return Err(EigError::InvalidOption {
            what: format!("Sturm bound {sigma} is not finite"),
        });
    }
    let a = shifted(k, m, sigma)?;
    let i = inertia_unchecked(a.as_ref(), par, perm)?;
    if i.zero > 0 {
        return Err(EigError::SingularShift { sigma });
    }
    Ok(i.negative)
}

fn inertia_unchecked(
    a: SparseColMatRef<'_, usize, f64>,
    par: Par,
    perm: Option<&[usize]>,
) -> Result<Inertia, EigError> {
    let n = a.nrows();
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        ..Default::default()
    };
    let own;
    let perm = match perm {
        Some(p) => p,
        None => {
            own = nested_dissection(a.symbolic())?;
            &own
        }
    };
    let symbolic = analyze_with(a.symbolic(), Some(perm), params)?;
    let SymbolicCholeskyRaw::Supernodal(sn) = symbolic.raw() else {
        return Err(EigError::Factorization {
            what: "expected a supernodal symbolic factorization".into(),
        });
    };
    let len = symbolic.len_val();
    let alloc_err = |what: &str| EigError::Factorization {
        what: format!("cannot allocate {what}"),
    };
    let mut values = Vec::new();
    values
        .try_reserve_exact(len)
        .map_err(|_| alloc_err("LBL^T values"))?;
    values.resize(len, 0.0);
    let mut subdiag = vec![0.0; n];
    let mut fwd = vec![0usize; n];
    let mut inv = vec![0usize; n];
    let req = symbolic.factorize_numeric_intranode_lblt_scratch::<f64>(par, Default::default());
    let mut mem = MemBuffer::try_new(req).map_err(|_| alloc_err("LBL^T workspace"))?;
    symbolic.factorize_numeric_intranode_lblt::<f64>(
        &mut values,
        &mut subdiag,
        &mut fwd,
        &mut inv,
        a,
        Side::Lower,
        par,
        MemStack::new(&mut mem),
        Default::default(),
    );
    let begin = sn.supernode_begin();
    let end = sn.supernode_end();
    let cpv = sn.col_ptr_for_val();
    let nnz_per = sn.nnz_per_super();
    let mut out = Inertia::default();
    for s in 0..sn.n_supernodes() {
        let start = begin[s];
        let ncols = end[s] - start;
        let nrows = ncols + nnz_per[s];
        let block = &values[cpv[s]..cpv[s + 1]];
        let d = |c: usize| block[c * nrows + c];
        let mut c = 0;
        while c < ncols {
            let off = subdiag[start + c];
            if off == 0.0 || c + 1 == ncols {
                add_1x1(&mut out, d(c));
                c += 1;
            } else {
                add_2x2(&mut out, d(c), off, d(c + 1));
                c += 2;
            }
        }
    }
    Ok(out)
}

fn add_1x1(out: &mut Inertia, d: f64) {
    if d < 0.0 {
        out.negative += 1;
    } else if d > 0.0 {
        out.positive += 1;
    } else {
        out.zero += 1;
    }
}

fn add_2x2(out: &mut Inertia, a: f64, s: f64, c: f64) {
    let det = a * c - s * s;
    if det < 0.0 {
        out.negative += 1;
        out.positive += 1;
    } else if det > 0.0 {
        if a + c < 0.0 {
            out.negative += 2;
        } else {
            out.positive += 2;
        }
    } else {
        out.zero += 1;
        add_1x1(out, a + c);
    }
}
