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
use crate::cholesky::{FactorAnalysis, analyze_with};
use crate::constraint::Constraints;
use crate::lanczos::ShiftSolve;
use crate::ordering::nested_dissection;
use crate::sparse::{check_pair, check_symmetric, shifted};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::SparseColMatRef;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, IntranodeLbltRef, SymbolicCholesky, SymbolicCholeskyRaw,
};
use faer::{Conj, Mat, MatMut, Par, Side};

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
    Ok(Lblt::factorize(a, faer::get_global_parallelism(), None)?.inertia())
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
    count_below_unchecked(k, m, sigma, faer::get_global_parallelism(), None, None)
}

/// [`count_below`] for the pencil constrained to C x = 0: the number of
/// eigenvalues of K phi = lambda M phi + C^T mu, C phi = 0 below `sigma`.
pub fn count_below_constrained(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    constraints: &Constraints,
    sigma: f64,
) -> Result<usize, EigError> {
    check_pair(k, m)?;
    if constraints.n() != k.nrows() {
        return Err(EigError::DimensionMismatch {
            what: format!(
                "constraints on vectors of length {}, K is {}",
                constraints.n(),
                k.nrows()
            ),
        });
    }
    let par = faer::get_global_parallelism();
    count_below_unchecked(k, m, sigma, par, None, Some(constraints))
}

/// [`count_below`] without the input checks (the caller has done them),
/// reusing what it can of `factor`, the analysis of a Cholesky factor of
/// K - sigma' M (its supernodes if the pattern is the same, else its
/// permutation; any permutation keeps the inertia; `None`: nested dissection
/// of K - sigma M), with optional constraints.
pub(crate) fn count_below_unchecked(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    sigma: f64,
    par: Par,
    factor: Option<&FactorAnalysis>,
    constraints: Option<&Constraints>,
) -> Result<usize, EigError> {
    if !sigma.is_finite() {
        return Err(EigError::InvalidOption {
            what: format!("Sturm bound {sigma} is not finite"),
        });
    }
    let a = shifted(k, m, sigma)?;
    let lblt = Lblt::factorize(a.as_ref(), par, factor)?;
    let i = lblt.inertia();
    if i.zero > 0 {
        return Err(EigError::SingularShift { sigma });
    }
    let Some(c) = constraints.filter(|c| !c.is_empty()) else {
        return Ok(i.negative);
    };
    let y = lblt.solve(c.transpose_dense(), par)?;
    let s = c.apply(y.as_ref());
    constrained_count(i.negative, &s, sigma)
}

/// The constrained Sturm count nu(A) - nu(S) from nu(A) and S = C A^-1 C^T
/// (symmetrized here); a singular S (the shift is a constrained eigenvalue)
/// is an error.
pub(crate) fn constrained_count(
    negative: usize,
    s: &Mat<f64>,
    sigma: f64,
) -> Result<usize, EigError> {
    let p = s.nrows();
    let s = Mat::from_fn(p, p, |i, j| 0.5 * (s[(i, j)] + s[(j, i)]));
    let ev = s
        .self_adjoint_eigenvalues(Side::Lower)
        .map_err(|_| EigError::DenseEigen)?;
    if ev.iter().any(|&e| e == 0.0 || !e.is_finite()) {
        return Err(EigError::SingularShift { sigma });
    }
    let below = ev.iter().filter(|&&e| e < 0.0).count();
    // nu(A) >= nu(S) for full-rank constraints; less means rounding broke
    // the count near an eigenvalue: report the shift as singular.
    negative
        .checked_sub(below)
        .ok_or(EigError::SingularShift { sigma })
}

impl ShiftSolve for Lblt<'_> {
    fn order(&self) -> usize {
        self.fwd.len()
    }

    /// faer's solve, sequential (its parallel kernels need not give the same
    /// bits for every thread count; these solves feed eigenvectors).
    fn solve_in_place(&self, mut rhs: MatMut<'_, f64>) -> Result<(), EigError> {
        let x = self.solve(rhs.to_owned(), Par::Seq)?;
        rhs.copy_from(&x);
        Ok(())
    }
}

/// The symbolic analysis of an LBL^T: borrowed from a Cholesky factor or made.
enum Analysis<'a> {
    Borrowed(&'a SymbolicCholesky<usize>),
    Owned(Box<SymbolicCholesky<usize>>),
}

/// faer's supernodal intranode LBL^T factorization of a symmetric matrix.
pub(crate) struct Lblt<'a> {
    symbolic: Analysis<'a>,
    values: Vec<f64>,
    subdiag: Vec<f64>,
    fwd: Vec<usize>,
    inv: Vec<usize>,
}

impl<'a> Lblt<'a> {
    pub(crate) fn factorize(
        a: SparseColMatRef<'_, usize, f64>,
        par: Par,
        factor: Option<&'a FactorAnalysis>,
    ) -> Result<Self, EigError> {
        let n = a.nrows();
        let symbolic = match factor.and_then(|f| f.supernodal_analysis_of(a.symbolic())) {
            Some(s) => Analysis::Borrowed(s),
            None => {
                let params = CholeskySymbolicParams {
                    supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                    ..Default::default()
                };
                let perm = match factor.and_then(FactorAnalysis::permutation) {
                    Some(p) => p.to_vec(),
                    None => nested_dissection(a.symbolic())?,
                };
                Analysis::Owned(Box::new(analyze_with(a.symbolic(), Some(&perm), params)?))
            }
        };
        let sym = match &symbolic {
            Analysis::Borrowed(s) => *s,
            Analysis::Owned(s) => s,
        };
        if !matches!(sym.raw(), SymbolicCholeskyRaw::Supernodal(_)) {
            return Err(EigError::Factorization {
                what: "expected a supernodal symbolic factorization".into(),
            });
        }
        let len = sym.len_val();
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
        let req = sym.factorize_numeric_intranode_lblt_scratch::<f64>(par, Default::default());
        let mut mem = MemBuffer::try_new(req).map_err(|_| alloc_err("LBL^T workspace"))?;
        sym.factorize_numeric_intranode_lblt::<f64>(
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
        Ok(Self {
            symbolic,
            values,
            subdiag,
            fwd,
            inv,
        })
    }

    fn symbolic(&self) -> &SymbolicCholesky<usize> {
        match &self.symbolic {
            Analysis::Borrowed(s) => s,
            Analysis::Owned(s) => s,
        }
    }

    /// The inertia of B, block by block.
    pub(crate) fn inertia(&self) -> Inertia {
        let mut out = Inertia::default();
        let SymbolicCholeskyRaw::Supernodal(sn) = self.symbolic().raw() else {
            return out;
        };
        let begin = sn.supernode_begin();
        let end = sn.supernode_end();
        let cpv = sn.col_ptr_for_val();
        let nnz_per = sn.nnz_per_super();
        for s in 0..sn.n_supernodes() {
            let start = begin[s];
            let ncols = end[s] - start;
            let nrows = ncols + nnz_per[s];
            let block = &self.values[cpv[s]..cpv[s + 1]];
            let d = |c: usize| block[c * nrows + c];
            let mut c = 0;
            while c < ncols {
                let off = self.subdiag[start + c];
                if off == 0.0 || c + 1 == ncols {
                    add_1x1(&mut out, d(c));
                    c += 1;
                } else {
                    add_2x2(&mut out, d(c), off, d(c + 1));
                    c += 2;
                }
            }
        }
        out
    }

    /// A^-1 B.
    fn solve(&self, mut b: Mat<f64>, par: Par) -> Result<Mat<f64>, EigError> {
        let n = self.fwd.len();
        let sym = self.symbolic();
        let req = sym.solve_in_place_scratch::<f64>(b.ncols(), par);
        let mut mem = MemBuffer::try_new(req).map_err(|_| EigError::Factorization {
            what: "cannot allocate an LBL^T solve workspace".into(),
        })?;
        let perm = PermRef::new_checked(&self.fwd, &self.inv, n);
        IntranodeLbltRef::new(sym, &self.values, &self.subdiag, perm).solve_in_place_with_conj(
            Conj::No,
            b.as_mut(),
            par,
            MemStack::new(&mut mem),
        );
        Ok(b)
    }
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
