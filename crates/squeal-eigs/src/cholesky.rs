//! Sparse Cholesky factorization A = P^T L L^T P with a fill-reducing
//! ordering (nested dissection by default, or AMD; see [`crate::ordering`]),
//! wrapping faer 0.24's supernodal/simplicial sparse Cholesky. Solves with a
//! supernodal factor run through [`crate::trisolve`] (subtree-parallel,
//! thread-count independent bits); a simplicial one (small problems) through
//! faer's solve, in fixed blocks of columns.
//!
//! Used for K_II (constraint modes, eq. 3 of Coudeyras et al. 2009) and for
//! K - sigma M (the shift-invert operator of the fixed-interface modes, eqs. 4-5).

use crate::EigError;
use crate::ordering::{FillOrdering, nested_dissection};
use crate::sparse::{check_pair, check_symmetric, shifted, sym_matvec};
use crate::trisolve::{self, SolvePlan};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{LltError, LltRegularization};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Col, Conj, Mat, MatMut, MatRef, Par, Side};
use rayon::prelude::*;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Right-hand-side columns per task in the multi-RHS solves (fixed so that
/// the result bits do not depend on the thread count).
const RHS_BLOCK: usize = 16;

/// Options of the Cholesky factorization.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct CholeskyOptions {
    /// A pivot L_jj^2 smaller than this times the diagonal entry A_jj it came
    /// from means that all but the last ~12 digits cancelled: the matrix is
    /// singular to working precision (e.g. K_II of a part that is not held)
    /// and is reported as [`EigError::NotPositiveDefinite`]. A well-posed
    /// matrix has every such ratio above 1/cond(A).
    pub singular_pivot_ratio: f64,
    /// Parallelism of faer's dense kernels inside the factorization.
    pub par: Par,
    /// Fill-reducing ordering (default: nested dissection).
    pub ordering: FillOrdering,
}

impl Default for CholeskyOptions {
    fn default() -> Self {
        Self {
            singular_pivot_ratio: 1e-12,
            par: faer::get_global_parallelism(),
            ordering: FillOrdering::default(),
        }
    }
}

/// What the factorization cost.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FactorStats {
    /// Order of the matrix.
    pub n: usize,
    /// Stored entries of A (both triangles).
    pub nnz_a: usize,
    /// Nonzeros of the factor L (lower triangle including the diagonal).
    pub nnz_l: usize,
    /// Values stored for L (supernodal storage keeps dense diagonal blocks, so
    /// this is a bit above `nnz_l`).
    pub stored_l: usize,
    /// Bytes held by the factor: values, indices and the ordering.
    pub factor_bytes: usize,
    /// Floating-point operations of the numeric factorization, sum over the
    /// columns j of L of c_j^2 (c_j: nonzeros of column j, diagonal included;
    /// the usual count of multiplies and adds of a sparse Cholesky).
    pub flops: f64,
    /// Whether faer chose its supernodal (blocked) variant.
    pub supernodal: bool,
    /// Subtree tasks of the parallel triangular solves (0: serial).
    pub solve_tasks: usize,
    /// Fraction of the factor's entries outside those subtrees (solved in
    /// order, parallel only inside large supernodes).
    pub solve_top_fraction: f64,
    /// Ordering + symbolic analysis time.
    pub symbolic_time: Duration,
    /// Of which the fill-reducing ordering.
    pub ordering_time: Duration,
    /// Numeric factorization time.
    pub numeric_time: Duration,
}

/// The symbolic side of a Cholesky factor: fill-reducing ordering,
/// supernodes, the task split of its solves and the pattern it was made
/// for. It outlives the factor's values ([`SparseCholesky::into_analysis`]),
/// so that another matrix of the same pattern (a refactorization, the LBL^T
/// of a Sturm count) can be factored without a new analysis.
#[derive(Debug, Clone)]
pub struct FactorAnalysis {
    symbolic: Arc<SymbolicCholesky<usize>>,
    /// Task split of the supernodal solves (None: simplicial factor).
    plan: Option<Arc<SolvePlan>>,
    /// Hash of the factored matrix's pattern (see [`pattern_hash`]).
    pattern: u64,
    n: usize,
    nnz_a: usize,
}

impl FactorAnalysis {
    /// The fill-reducing permutation (`perm[new] = old`), if any.
    pub fn permutation(&self) -> Option<&[usize]> {
        self.symbolic.perm().map(|p| p.arrays().0)
    }

    /// Numeric factorization of a matrix with the analysed pattern.
    pub fn factorize(
        &self,
        a: SparseColMatRef<'_, usize, f64>,
        opts: &CholeskyOptions,
    ) -> Result<SparseCholesky, EigError> {
        check_symmetric(a, "A")?;
        if a.nrows() != self.n || a.compute_nnz() != self.nnz_a {
            return Err(EigError::DimensionMismatch {
                what: "refactorize: pattern differs from the analysed one".into(),
            });
        }
        let times = (Duration::ZERO, Duration::ZERO);
        let analysis = (self.symbolic.clone(), self.plan.clone());
        SparseCholesky::numeric(analysis, a, times, opts)
    }

    /// The supernodal symbolic analysis, if it is supernodal and was made
    /// for a matrix with exactly the pattern `pattern` (then another matrix
    /// of that pattern, e.g. K - b M for a Sturm count, can be factored with
    /// it).
    pub(crate) fn supernodal_analysis_of(
        &self,
        pattern: SymbolicSparseColMatRef<'_, usize>,
    ) -> Option<&SymbolicCholesky<usize>> {
        let supernodal = matches!(self.symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_));
        let same = pattern.nrows() == self.n
            && pattern.compute_nnz() == self.nnz_a
            && pattern_hash(pattern) == self.pattern;
        (supernodal && same).then_some(&*self.symbolic)
    }
}

/// A sparse Cholesky factor of a symmetric positive definite matrix.
#[derive(Debug, Clone)]
pub struct SparseCholesky {
    analysis: FactorAnalysis,
    values: Vec<f64>,
    stats: FactorStats,
}

impl SparseCholesky {
    /// Factorizes a symmetric positive definite `a` (both triangles stored;
    /// only the lower one is read by the factorization) with default options.
    pub fn factorize(a: SparseColMatRef<'_, usize, f64>) -> Result<Self, EigError> {
        Self::factorize_with(a, &CholeskyOptions::default())
    }

    /// Factorizes `a`: AMD ordering and symbolic analysis, then numeric.
    pub fn factorize_with(
        a: SparseColMatRef<'_, usize, f64>,
        opts: &CholeskyOptions,
    ) -> Result<Self, EigError> {
        check_symmetric(a, "A")?;
        let t0 = Instant::now();
        let (symbolic, ordering_time) = analyze(a.symbolic(), opts.ordering)?;
        let times = (t0.elapsed(), ordering_time);
        Self::numeric(analysed(symbolic), a, times, opts)
    }

    /// Factorizes K - sigma M (the shift-invert operator of the generalized problem).
    pub fn factorize_shifted(
        k: SparseColMatRef<'_, usize, f64>,
        m: SparseColMatRef<'_, usize, f64>,
        sigma: f64,
        opts: &CholeskyOptions,
    ) -> Result<Self, EigError> {
        check_pair(k, m)?;
        let a = shifted(k, m, sigma)?;
        let t0 = Instant::now();
        let (symbolic, ordering_time) = analyze(a.symbolic(), opts.ordering)?;
        let times = (t0.elapsed(), ordering_time);
        Self::numeric(analysed(symbolic), a.as_ref(), times, opts)
    }

    /// Numeric factorization of a matrix with the same pattern as the one this
    /// factor was made from, reusing the ordering and symbolic analysis.
    pub fn refactorize(
        &self,
        a: SparseColMatRef<'_, usize, f64>,
        opts: &CholeskyOptions,
    ) -> Result<Self, EigError> {
        self.analysis.factorize(a, opts)
    }

    /// The symbolic analysis.
    pub fn analysis(&self) -> &FactorAnalysis {
        &self.analysis
    }

    /// The symbolic analysis, the factor's values freed.
    pub fn into_analysis(self) -> FactorAnalysis {
        self.analysis
    }

    fn numeric(
        (symbolic, plan): Analysis,
        a: SparseColMatRef<'_, usize, f64>,
        (symbolic_time, ordering_time): (Duration, Duration),
        opts: &CholeskyOptions,
    ) -> Result<Self, EigError> {
        let t0 = Instant::now();
        let len = symbolic.len_val();
        let mut values = Vec::new();
        values
            .try_reserve_exact(len)
            .map_err(|_| EigError::Factorization {
                what: format!("cannot allocate {len} factor values"),
            })?;
        values.resize(len, 0.0);
        let par = opts.par;
        let req = symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default());
        let mut mem = MemBuffer::try_new(req).map_err(|_| EigError::Factorization {
            what: "cannot allocate factorization workspace".into(),
        })?;
        let result = symbolic.factorize_numeric_llt::<f64>(
            &mut values,
            a,
            Side::Lower,
            LltRegularization::default(),
            par,
            MemStack::new(&mut mem),
            Default::default(),
        );
        let perm_fwd = symbolic.perm().map(|p| p.arrays().0.to_vec());
        let to_input = |j: usize| {
            perm_fwd
                .as_ref()
                .and_then(|f| f.get(j).copied())
                .unwrap_or(j)
        };
        if let Err(LltError::NonPositivePivot { index }) = result {
            return Err(EigError::NotPositiveDefinite {
                column: to_input(index),
            });
        }
        let numeric_time = t0.elapsed();
        let (nnz_l, flops, pivots) = pivots_and_counts(&symbolic, &values);
        let diag = diagonal(a);
        for (j, &p) in pivots.iter().enumerate() {
            let col = to_input(j);
            if p * p <= opts.singular_pivot_ratio * diag[col].abs() {
                return Err(EigError::NotPositiveDefinite { column: col });
            }
        }
        let stats = FactorStats {
            n: a.nrows(),
            nnz_a: a.compute_nnz(),
            nnz_l,
            stored_l: len,
            factor_bytes: factor_bytes(&symbolic, len),
            flops,
            supernodal: matches!(symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_)),
            solve_tasks: plan.as_ref().map_or(0, |p| p.shape().0),
            solve_top_fraction: plan.as_ref().map_or(1.0, |p| p.shape().1),
            symbolic_time,
            ordering_time,
            numeric_time,
        };
        let analysis = FactorAnalysis {
            symbolic,
            plan,
            pattern: pattern_hash(a.symbolic()),
            n: stats.n,
            nnz_a: stats.nnz_a,
        };
        Ok(Self {
            analysis,
            values,
            stats,
        })
    }

    /// Order of the factored matrix.
    pub fn n(&self) -> usize {
        self.stats.n
    }

    /// Sizes and timings.
    pub fn stats(&self) -> FactorStats {
        self.stats
    }

    /// The fill-reducing permutation (`perm[new] = old`), if any.
    pub fn permutation(&self) -> Option<&[usize]> {
        self.analysis.permutation()
    }

    /// Solves A X = B in place for all columns of `rhs`, in parallel over
    /// subtrees of the elimination tree and groups of columns; the result
    /// bits do not depend on the thread count.
    pub fn solve_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), EigError> {
        if rhs.nrows() != self.n() {
            return Err(EigError::DimensionMismatch {
                what: format!(
                    "right-hand side has {} rows, factor is {}",
                    rhs.nrows(),
                    self.n()
                ),
            });
        }
        let a = &self.analysis;
        if let (Some(plan), SymbolicCholeskyRaw::Supernodal(symbolic)) = (&a.plan, a.symbolic.raw())
        {
            let identity: Vec<usize>;
            let inv = match a.symbolic.perm() {
                Some(p) => p.arrays().1,
                None => {
                    identity = (0..self.n()).collect();
                    &identity
                }
            };
            let factor = trisolve::Factor {
                symbolic,
                values: &self.values,
            };
            trisolve::solve(plan, factor, inv, rhs);
            return Ok(());
        }
        let mut blocks = Vec::new();
        let mut rest = rhs;
        while rest.ncols() > 0 {
            let w = RHS_BLOCK.min(rest.ncols());
            let (left, right) = rest.split_at_col_mut(w);
            blocks.push(left);
            rest = right;
        }
        blocks.into_par_iter().try_for_each(|b| self.solve_block(b))
    }

    /// Solves one block of columns sequentially with faer's solve.
    fn solve_block(&self, rhs: MatMut<'_, f64>) -> Result<(), EigError> {
        let symbolic = &self.analysis.symbolic;
        let req = symbolic.solve_in_place_scratch::<f64>(rhs.ncols(), Par::Seq);
        let mut mem = MemBuffer::try_new(req).map_err(|_| EigError::Factorization {
            what: "cannot allocate solve workspace".into(),
        })?;
        LltRef::new(symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            Par::Seq,
            MemStack::new(&mut mem),
        );
        Ok(())
    }

    /// Returns X = A^-1 B.
    pub fn solve(&self, rhs: MatRef<'_, f64>) -> Result<Mat<f64>, EigError> {
        let mut x = rhs.to_owned();
        self.solve_in_place(x.as_mut())?;
        Ok(x)
    }

    /// Solves one column in place.
    pub fn solve_col_in_place(&self, rhs: &mut Col<f64>) -> Result<(), EigError> {
        self.solve_in_place(rhs.as_mat_mut())
    }

    /// Eq. (3): constraint modes X = -K_II^-1 K_IB for all boundary columns at
    /// once, with this factor being the one of K_II. `k_ib` is the sparse
    /// interior-boundary block (n_I x n_B); the result is dense n_I x n_B.
    pub fn constraint_modes(
        &self,
        k_ib: SparseColMatRef<'_, usize, f64>,
    ) -> Result<Mat<f64>, EigError> {
        if k_ib.nrows() != self.n() {
            return Err(EigError::DimensionMismatch {
                what: format!("K_IB has {} rows, K_II is {}", k_ib.nrows(), self.n()),
            });
        }
        let n = self.n();
        let nb = k_ib.ncols();
        let mut x = try_zeros(n, nb)?;
        for j in 0..nb {
            for (i, &v) in k_ib.row_idx_of_col(j).zip(k_ib.val_of_col(j)) {
                x[(i, j)] -= v;
            }
        }
        self.solve_in_place(x.as_mut())?;
        Ok(x)
    }

    /// Relative error ||x - A_f^-1 A x|| / ||x|| for a fixed test vector x,
    /// where A_f is the factored matrix: checks that this factor belongs to `a`.
    pub fn mismatch(&self, a: SparseColMatRef<'_, usize, f64>) -> Result<f64, EigError> {
        let n = self.n();
        if a.nrows() != n {
            return Err(EigError::DimensionMismatch {
                what: format!("matrix is {}x{}, factor is {n}", a.nrows(), a.ncols()),
            });
        }
        let x = Col::<f64>::from_fn(n, |i| 1.0 + ((i * 7919) % 101) as f64 / 101.0);
        let mut y = Col::<f64>::zeros(n);
        sym_matvec(a, x.as_ref(), y.as_mut());
        self.solve_col_in_place(&mut y)?;
        let err = (&y - &x).norm_l2() / x.norm_l2();
        Ok(err)
    }
}

/// A symbolic factorization and, if supernodal, the task split of its solves.
type Analysis = (Arc<SymbolicCholesky<usize>>, Option<Arc<SolvePlan>>);

fn analysed(symbolic: SymbolicCholesky<usize>) -> Analysis {
    let plan = match symbolic.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => Some(Arc::new(SolvePlan::new(s))),
        SymbolicCholeskyRaw::Simplicial(_) => None,
    };
    (Arc::new(symbolic), plan)
}

/// A zeroed n x m matrix, or an error instead of an abort when the memory is not there.
pub(crate) fn try_zeros(n: usize, m: usize) -> Result<Mat<f64>, EigError> {
    let count = n
        .checked_mul(m)
        .ok_or_else(|| EigError::DimensionMismatch {
            what: format!("{n} x {m} overflows"),
        })?;
    let mut probe: Vec<f64> = Vec::new();
    probe
        .try_reserve_exact(count)
        .map_err(|_| EigError::Factorization {
            what: format!("cannot allocate a {n} x {m} dense matrix"),
        })?;
    drop(probe);
    Ok(Mat::zeros(n, m))
}

/// Fill-reducing ordering and symbolic analysis of a symmetric pattern
/// (both triangles given). Returns the analysis and the ordering time.
pub(crate) fn analyze(
    pattern: SymbolicSparseColMatRef<'_, usize>,
    ordering: FillOrdering,
) -> Result<(SymbolicCholesky<usize>, Duration), EigError> {
    let t0 = Instant::now();
    let perm = match ordering {
        FillOrdering::Amd => None,
        FillOrdering::NestedDissection => Some(nested_dissection(pattern)?),
    };
    let ordering_time = t0.elapsed();
    let symbolic = analyze_with(pattern, perm.as_deref(), CholeskySymbolicParams::default())?;
    // AMD runs inside faer's symbolic analysis.
    let ordering_time = match ordering {
        FillOrdering::Amd => t0.elapsed(),
        FillOrdering::NestedDissection => ordering_time,
    };
    Ok((symbolic, ordering_time))
}

/// Symbolic analysis with a given permutation (`perm[new] = old`), or AMD
/// when `None`, and explicit faer parameters.
pub(crate) fn analyze_with(
    pattern: SymbolicSparseColMatRef<'_, usize>,
    perm: Option<&[usize]>,
    params: CholeskySymbolicParams<'_>,
) -> Result<SymbolicCholesky<usize>, EigError> {
    let fail = |what: String| EigError::Factorization { what };
    let n = pattern.nrows();
    let inv = match perm {
        Some(p) => {
            if p.len() != n {
                return Err(fail(format!(
                    "permutation of length {} for order {n}",
                    p.len()
                )));
            }
            let mut inv = vec![usize::MAX; n];
            for (new, &old) in p.iter().enumerate() {
                if old >= n || inv[old] != usize::MAX {
                    return Err(fail("ordering is not a permutation".into()));
                }
                inv[old] = new;
            }
            Some(inv)
        }
        None => None,
    };
    let ordering = match (perm, inv.as_deref()) {
        (Some(p), Some(i)) => SymmetricOrdering::Custom(PermRef::new_checked(p, i, n)),
        _ => SymmetricOrdering::Amd,
    };
    factorize_symbolic_cholesky(pattern, Side::Lower, ordering, params)
        .map_err(|e| fail(crate::faer_error::describe_faer(e)))
}

/// A 64-bit hash (FNV-1a over the column pointers and row indices) of a
/// sparse pattern, to recognise the pattern a symbolic analysis was made for.
fn pattern_hash(a: SymbolicSparseColMatRef<'_, usize>) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    let mut eat = |v: usize| {
        h = (h ^ v as u64).wrapping_mul(0x0000_0100_0000_01b3);
    };
    eat(a.nrows());
    for j in 0..a.ncols() {
        eat(usize::MAX);
        a.row_idx_of_col(j).for_each(&mut eat);
    }
    h
}

/// Diagonal entries of a (summing duplicates).
fn diagonal(a: SparseColMatRef<'_, usize, f64>) -> Vec<f64> {
    (0..a.ncols())
        .map(|j| {
            a.row_idx_of_col(j)
                .zip(a.val_of_col(j))
                .filter(|(i, _)| *i == j)
                .map(|(_, v)| *v)
                .sum()
        })
        .collect()
}

/// Diagonal pivots L_jj (permuted order), the true nonzero count of L and
/// the flop count sum_j c_j^2 of the factorization.
fn pivots_and_counts(symbolic: &SymbolicCholesky<usize>, values: &[f64]) -> (usize, f64, Vec<f64>) {
    match symbolic.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => {
            let cp = s.col_ptr();
            let ri = s.row_idx();
            let n = s.nrows();
            let piv = (0..n)
                .map(|j| {
                    (cp[j]..cp[j + 1])
                        .find(|&p| ri[p] == j)
                        .map_or(0.0, |p| values[p])
                })
                .collect();
            let flops = (0..n).map(|j| ((cp[j + 1] - cp[j]) as f64).powi(2)).sum();
            (s.len_val(), flops, piv)
        }
        SymbolicCholeskyRaw::Supernodal(s) => {
            let begin = s.supernode_begin();
            let end = s.supernode_end();
            let cpv = s.col_ptr_for_val();
            let nnz_per = s.nnz_per_super();
            let mut piv = Vec::with_capacity(s.nrows());
            let mut nnz = 0usize;
            let mut flops = 0.0;
            for sn in 0..s.n_supernodes() {
                let ncols = end[sn] - begin[sn];
                let nrows = ncols + nnz_per[sn];
                nnz += ncols * (ncols + 1) / 2 + ncols * nnz_per[sn];
                let block = &values[cpv[sn]..cpv[sn + 1]];
                for c in 0..ncols {
                    piv.push(block[c * nrows + c]);
                    flops += ((nrows - c) as f64).powi(2);
                }
            }
            (nnz, flops, piv)
        }
    }
}

/// Bytes of the factor: values, row indices, column pointers, permutation.
fn factor_bytes(symbolic: &SymbolicCholesky<usize>, len_val: usize) -> usize {
    let w = std::mem::size_of::<usize>();
    let idx = match symbolic.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => s.row_idx().len() + s.col_ptr().len(),
        SymbolicCholeskyRaw::Supernodal(s) => s.row_idx().len() + 4 * (s.n_supernodes() + 1),
    };
    len_val * 8 + (idx + 2 * symbolic.nrows()) * w
}
