//! The subtree-parallel supernodal solves: thread-count independent bits,
//! backward stable, and the same solutions as the simplicial path.

use faer::Mat;
use faer::sparse::SparseColMatRef;
use squeal_eigs::model_problems::box_vector;
use squeal_eigs::{CholeskyOptions, FillOrdering, SparseCholesky};

use super::common;
use common::in_pool;

/// Normwise backward error max_j ||A x_j - b_j|| / (||A||_1 ||x_j|| + ||b_j||).
fn backward_error(a: SparseColMatRef<'_, usize, f64>, x: &Mat<f64>, b: &Mat<f64>) -> f64 {
    let norm_a = (0..a.ncols())
        .map(|j| a.val_of_col(j).iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let r = a * x - b;
    (0..x.ncols())
        .map(|j| r.col(j).norm_l2() / (norm_a * x.col(j).norm_l2() + b.col(j).norm_l2()))
        .fold(0.0, f64::max)
}

fn rhs(n: usize, cols: usize) -> Mat<f64> {
    Mat::from_fn(n, cols, |i, j| ((i * 31 + j * 17) % 23) as f64 - 11.0)
}

#[test]
fn supernodal_solves_are_thread_count_independent_and_backward_stable() {
    let p = box_vector([20, 20, 19], [1.0, 1.0, 0.9]);
    let n = p.k.nrows();
    let f = SparseCholesky::factorize(p.k.as_ref()).unwrap();
    let s = f.stats();
    // The parallel path must really run, with several subtrees and a top part
    // whose first separator is tall enough for the row-parallel panel updates.
    assert!(s.supernodal, "faer chose a simplicial factor");
    assert!(s.solve_tasks >= 8, "{} subtree tasks", s.solve_tasks);
    assert!(s.solve_top_fraction > 0.0 && s.solve_top_fraction < 1.0);
    // 27 columns: a group of 16 and one of 11 padded to 16; 3 padded to 4; 1 alone.
    for cols in [1, 3, 27] {
        let b = rhs(n, cols);
        let x: Vec<Mat<f64>> = [1, 2, 3]
            .into_iter()
            .map(|t| in_pool(t, |_| f.solve(b.as_ref()).unwrap()))
            .collect();
        // Exact: the split into subtrees and row chunks does not depend on the pool.
        assert!(x[0] == x[1] && x[1] == x[2], "{cols} columns differ");
        let err = backward_error(p.k.as_ref(), &x[0], &b);
        // Tolerance: a backward-stable Cholesky solve, ~n^(1/2) eps.
        assert!(err < 1e-14, "{cols} columns: backward error {err:e}");
    }
    // Exact: a column gets the same bits alone and inside groups of any width (the lanes of
    // the kernels do not mix).
    let b = rhs(n, 27);
    let x = f.solve(b.as_ref()).unwrap();
    for j in [0, 7, 16, 26] {
        let mut c = b.col(j).to_owned();
        f.solve_col_in_place(&mut c).unwrap();
        assert_eq!(c.as_ref(), x.col(j), "column {j}");
    }
}

#[test]
fn supernodal_and_simplicial_solves_are_both_backward_stable() {
    // Nested dissection gives a supernodal factor here, AMD on a small
    // problem a simplicial one (faer decides by the flops per entry).
    let p = box_vector([14, 13, 12], [1.0, 0.9, 0.8]);
    let n = p.k.nrows();
    let nd = SparseCholesky::factorize(p.k.as_ref()).unwrap();
    let small = box_vector([4, 3, 3], [1.0, 0.9, 0.8]);
    let amd = SparseCholesky::factorize_with(small.k.as_ref(), &{
        let mut o = CholeskyOptions::default();
        o.ordering = FillOrdering::Amd;
        o
    })
    .unwrap();
    assert!(nd.stats().supernodal && !amd.stats().supernodal);
    let b = rhs(n, 8);
    let x = nd.solve(b.as_ref()).unwrap();
    // Tolerance: as above.
    assert!(backward_error(p.k.as_ref(), &x, &b) < 1e-14);
    let b = rhs(small.k.nrows(), 8);
    let x = amd.solve(b.as_ref()).unwrap();
    assert!(backward_error(small.k.as_ref(), &x, &b) < 1e-14);
}
