//! faer's dense kernels on rayon's threads where their bits do not depend on the thread count:
//! the LU with partial pivoting, the Cholesky and Bunch–Kaufman `L B Lᵀ` factorizations,
//! triangular solves of several right-hand sides and matrix products of several columns.
//!
//! The command line runs faer's kernels sequentially (`faer::set_global_parallelism(Par::Seq)`
//! in `src/main.rs`): some of them split a reduction among threads, so their sums would depend
//! on the thread count. Not these, read in faer 0.24's source and checked bit for bit
//! (`tests::kernels_give_the_same_bits_on_any_thread_count`):
//!
//! - a product of more than one column (faer's `gemm`, or its x86 kernels) splits its work by
//!   blocks of the *output*: each entry is summed over the same depth blocks (their size set
//!   by the depth and the caches, not by the threads) in the same order;
//! - the recursive factorizations and triangular solves recurse on the same block sizes
//!   whatever the parallelism, and reach the threads only through such products (and row
//!   swaps, which do not compute);
//! - a product with a *single* column (faer's `matvec` on a column-major matrix) does split
//!   its depth among the threads and adds the pieces: not used here (one right-hand side is
//!   solved sequentially, [`Lu::solve`]).
//!
//! So a thread count of 1, 2 or 16 gives the same factors, and every use here gives the bits
//! the sequential kernels give (the thread pool is the one the command line bounds,
//! `--threads`). Below [`PARALLEL_FROM`] rows the sequential kernels are used: a task costs
//! more than it saves.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatMut, MatRef, Par};

/// Rows from which the kernels here run on rayon's threads.
pub const PARALLEL_FROM: usize = 512;

/// The parallelism for an `n`-row problem: rayon's threads (as many as its pool has) from
/// [`PARALLEL_FROM`] rows, else sequential.
pub fn par_for(n: usize) -> Par {
    if n >= PARALLEL_FROM && rayon::current_num_threads() > 1 {
        Par::rayon(0)
    } else {
        Par::Seq
    }
}

/// `a b` (the output split among threads: [`par_for`] of its rows and columns).
pub fn product(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> Mat<f64> {
    let mut c = Mat::zeros(a.nrows(), b.ncols());
    add_product(c.as_mut(), Accum::Replace, a, b, 1.0);
    c
}

/// `c = alpha a b` (`Replace`) or `c += alpha a b` (`Add`): on rayon's threads only for more
/// than one row and more than one column (module documentation: a single column, or a single
/// row that faer takes as a column of the transposed product, would split its sums).
pub fn add_product(
    c: MatMut<'_, f64>,
    accum: Accum,
    a: MatRef<'_, f64>,
    b: MatRef<'_, f64>,
    alpha: f64,
) {
    let par = if a.nrows() > 1 && b.ncols() > 1 {
        par_for(a.nrows().max(a.ncols()))
    } else {
        Par::Seq
    };
    matmul(c, accum, a, b, alpha, par);
}

/// An LU factorization with partial pivoting, `P A = L U`, factored on rayon's threads: the
/// same factors as faer's `Mat::partial_piv_lu` with sequential kernels, bit for bit, without
/// its separate copies of `L` and `U`.
pub struct Lu {
    /// `L` (unit, below the diagonal) and `U` (on and above it) in one matrix.
    lu: Mat<f64>,
    fwd: Vec<usize>,
    bwd: Vec<usize>,
}

impl Lu {
    /// The factorization of `a`.
    pub fn new(mut a: Mat<f64>) -> Self {
        use faer::linalg::lu::partial_pivoting::factor::{lu_in_place, lu_in_place_scratch};
        let (m, n) = a.shape();
        let par = par_for(n);
        let mut fwd = vec![0usize; m];
        let mut bwd = vec![0usize; m];
        let mut mem = MemBuffer::new(lu_in_place_scratch::<usize, f64>(m, n, par, default()));
        lu_in_place(
            a.as_mut(),
            &mut fwd,
            &mut bwd,
            par,
            MemStack::new(&mut mem),
            default(),
        );
        Self { lu: a, fwd, bwd }
    }

    /// `A⁻¹ b`, as faer's `PartialPivLu::solve` computes it with sequential kernels (the same
    /// bits): a single column sequentially (module documentation), several on rayon's
    /// threads.
    pub fn solve(&self, b: &Mat<f64>) -> Mat<f64> {
        use faer::linalg::lu::partial_pivoting::solve::{solve_in_place, solve_in_place_scratch};
        let n = self.lu.nrows();
        let par = if b.ncols() > 1 { par_for(n) } else { Par::Seq };
        let mut x = b.clone();
        // SAFETY: `fwd` and `bwd` are the permutation and its inverse the factorization made.
        let perm = unsafe { faer::perm::PermRef::new_unchecked(&self.fwd, &self.bwd, n) };
        let mut mem = MemBuffer::new(solve_in_place_scratch::<usize, f64>(n, b.ncols(), par));
        solve_in_place(
            self.lu.as_ref(),
            self.lu.as_ref(),
            perm,
            x.as_mut(),
            par,
            MemStack::new(&mut mem),
        );
        x
    }
}

/// `A⁻¹ b` by [`Lu`].
pub fn lu_solve(a: Mat<f64>, b: &Mat<f64>) -> Mat<f64> {
    Lu::new(a).solve(b)
}

/// The Cholesky factor `L` of `k` (`k = L Lᵀ`, zeros above the diagonal) factored on rayon's
/// threads, `None` when `k` is not positive definite: the same bits as faer's `Mat::llt` with
/// sequential kernels.
pub fn cholesky(k: &Mat<f64>) -> Option<Mat<f64>> {
    use faer::linalg::cholesky::llt::factor::{cholesky_in_place, cholesky_in_place_scratch};
    let n = k.nrows();
    let mut l = Mat::<f64>::zeros(n, n);
    l.copy_from_triangular_lower(k);
    let par = par_for(n);
    let mut mem = MemBuffer::new(cholesky_in_place_scratch::<f64>(n, par, default()));
    cholesky_in_place(
        l.as_mut(),
        Default::default(),
        par,
        MemStack::new(&mut mem),
        default(),
    )
    .ok()?;
    for j in 0..n {
        for i in 0..j {
            l[(i, j)] = 0.0;
        }
    }
    Some(l)
}

/// The block diagonal of the Bunch–Kaufman factorization `P A Pᵀ = L B Lᵀ` of the symmetric
/// `a` (its lower triangle read), factored on rayon's threads: `B`'s diagonal and
/// subdiagonal, as faer's `Mat::lblt` gives them with sequential kernels.
pub fn lblt_blocks(a: Mat<f64>) -> (Vec<f64>, Vec<f64>) {
    use faer::linalg::cholesky::lblt::factor::{cholesky_in_place, cholesky_in_place_scratch};
    let n = a.nrows();
    let mut l = a;
    let mut sub = Mat::<f64>::zeros(n, 1);
    let (mut fwd, mut bwd) = (vec![0usize; n], vec![0usize; n]);
    let par = par_for(n);
    let mut mem = MemBuffer::new(cholesky_in_place_scratch::<usize, f64>(n, par, default()));
    cholesky_in_place(
        l.as_mut(),
        sub.col_mut(0).as_diagonal_mut(),
        &mut fwd,
        &mut bwd,
        par,
        MemStack::new(&mut mem),
        default(),
    );
    let d = (0..n).map(|i| l[(i, i)]).collect();
    let e = (0..n).map(|i| sub[(i, 0)]).collect();
    (d, e)
}

fn default<T: faer::Auto<f64>>() -> faer::Spec<T, f64> {
    faer::Spec::new(T::auto())
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Side;

    /// Deterministic entries in `[-1, 1)`.
    fn entries(n: usize, m: usize, seed: u64) -> Mat<f64> {
        let mut next = crate::partial_modes::uniform(seed);
        Mat::from_fn(n, m, |_, _| next())
    }

    /// The problems of the test: a general `n × n` matrix, 9 and 1 right-hand sides, an SPD
    /// matrix (`A Aᵀ / n + I`) and a symmetric indefinite one (that less 1.2 I).
    fn problems(n: usize) -> [Mat<f64>; 5] {
        let a = entries(n, n, 1);
        let mut s = Mat::zeros(n, n);
        matmul(
            s.as_mut(),
            Accum::Replace,
            a.as_ref(),
            a.transpose(),
            1.0,
            Par::Seq,
        );
        let spd = Mat::from_fn(n, n, |i, j| {
            s[(i, j)] / n as f64 + f64::from(u8::from(i == j))
        });
        let indefinite = Mat::from_fn(n, n, |i, j| spd[(i, j)] - if i == j { 1.2 } else { 0.0 });
        [a, entries(n, 9, 2), entries(n, 1, 3), spd, indefinite]
    }

    fn bits(a: &Mat<f64>) -> Vec<u64> {
        (0..a.ncols())
            .flat_map(|j| (0..a.nrows()).map(move |i| (i, j)))
            .map(|(i, j)| a[(i, j)].to_bits())
            .collect()
    }

    /// Everything the module computes, as bits.
    fn outputs(n: usize) -> Vec<Vec<u64>> {
        let [a, b, one, spd, indefinite] = problems(n);
        let lu = Lu::new(a.clone());
        let l = cholesky(&spd).unwrap();
        let mut lx = b.clone();
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(
            l.as_ref(),
            lx.as_mut(),
            par_for(n),
        );
        let (d, e) = lblt_blocks(indefinite);
        vec![
            bits(&product(a.as_ref(), b.as_ref())),
            bits(&product(a.transpose(), b.as_ref())),
            bits(&product(b.transpose(), a.as_ref())),
            bits(&lu.lu),
            bits(&lu.solve(&b)),
            bits(&lu.solve(&one)),
            bits(&l),
            bits(&lx),
            d.iter().chain(&e).map(|v| v.to_bits()).collect(),
        ]
    }

    /// faer's own sequential results for the same problems.
    fn sequential(n: usize) -> Vec<Vec<u64>> {
        let [a, b, one, spd, indefinite] = problems(n);
        let seq = |x: MatRef<'_, f64>, y: MatRef<'_, f64>| {
            let mut c = Mat::zeros(x.nrows(), y.ncols());
            matmul(c.as_mut(), Accum::Replace, x, y, 1.0, Par::Seq);
            c
        };
        use faer::linalg::solvers::Solve;
        let plu = a.partial_piv_lu();
        // faer's L (unit) and U in one matrix, as `Lu` keeps them.
        let lu = Mat::from_fn(n, n, |i, j| {
            if i > j {
                plu.L()[(i, j)]
            } else {
                plu.U()[(i, j)]
            }
        });
        let l = spd.llt(Side::Lower).unwrap().L().to_owned();
        let mut lx = b.clone();
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(
            l.as_ref(),
            lx.as_mut(),
            Par::Seq,
        );
        let f = indefinite.lblt(Side::Lower);
        let (d, e) = (f.B_diag().column_vector(), f.B_subdiag().column_vector());
        vec![
            bits(&seq(a.as_ref(), b.as_ref())),
            bits(&seq(a.transpose(), b.as_ref())),
            bits(&seq(b.transpose(), a.as_ref())),
            bits(&lu),
            bits(&plu.solve(&b)),
            bits(&plu.solve(&one)),
            bits(&l),
            bits(&lx),
            d.iter().chain(e.iter()).map(|v| v.to_bits()).collect(),
        ]
    }

    /// The kernels on 1, 2 and 3 threads give faer's sequential bits, on sizes above
    /// [`PARALLEL_FROM`] where faer does split the work (and an odd size, for uneven blocks).
    #[test]
    fn kernels_give_the_same_bits_on_any_thread_count() {
        faer::set_global_parallelism(Par::Seq);
        for n in [PARALLEL_FROM, 1031] {
            let reference = sequential(n);
            for threads in [1, 2, 3] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let got = pool.install(|| outputs(n));
                for (k, (g, r)) in got.iter().zip(&reference).enumerate() {
                    assert!(g == r, "output {k}, n = {n}, {threads} threads: other bits");
                }
            }
        }
    }
}
