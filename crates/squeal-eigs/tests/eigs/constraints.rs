//! Eigenvectors constrained to C x = 0: the projected shift-invert operator,
//! the constraint modes and the constrained Sturm count, against a dense
//! null-space reference.

use faer::linalg::solvers::DenseSolveCore;
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::{Mat, Par, Side};
use squeal_eigs::model_problems::{Pencil, box_vector};
use squeal_eigs::{
    ConstrainedFactor, Constraints, EigError, EigOptions, SparseCholesky, count_below_constrained,
    lowest_modes_constrained,
};

use super::common;
use common::rel;

/// Three "patch" rows averaging one component over a block of nodes each,
/// and one row tying two components of a node (like a piston).
fn patch_rows(n: usize) -> Vec<Vec<(usize, f64)>> {
    let mut rows = Vec::new();
    for (start, comp) in [(30, 0), (90, 1), (150, 2)] {
        let nodes = 12;
        rows.push(
            (0..nodes)
                .map(|k| {
                    (
                        3 * (start / 3 + k) + comp,
                        1.0 / nodes as f64 + 0.01 * k as f64,
                    )
                })
                .filter(|&(i, _)| i < n)
                .collect(),
        );
    }
    rows.push(vec![(3 * 70, 1.0), (3 * 70 + 1, -0.5)]);
    rows
}

fn dense(a: faer::sparse::SparseColMatRef<'_, usize, f64>) -> Mat<f64> {
    a.to_dense()
}

/// Eigenvalues of Z^T K Z x = lambda Z^T M Z x with Z an orthonormal basis
/// of null(C), ascending (dense, from a QR of C^T).
fn null_space_eigenvalues(p: &Pencil, c: &Constraints) -> Vec<f64> {
    let ct = c.transpose_dense();
    let (n, q) = (ct.nrows(), ct.ncols());
    let full_q = ct.qr().compute_Q();
    let z = full_q.subcols(q, n - q).to_owned();
    let kz = z.transpose() * dense(p.k.as_ref()) * &z;
    let mz = z.transpose() * dense(p.m.as_ref()) * &z;
    let l = mz.llt(Side::Lower).unwrap().L().to_owned();
    let mut x = kz.clone();
    solve_lower_triangular_in_place(l.as_ref(), x.as_mut(), Par::Seq);
    let mut y = x.transpose().to_owned();
    solve_lower_triangular_in_place(l.as_ref(), y.as_mut(), Par::Seq);
    let y = Mat::from_fn(y.nrows(), y.ncols(), |i, j| 0.5 * (y[(i, j)] + y[(j, i)]));
    y.self_adjoint_eigenvalues(Side::Lower).unwrap()
}

#[test]
fn constrained_modes_match_a_dense_null_space_reference() {
    let p = box_vector([6, 5, 5], [1.0, 0.8, 0.6]);
    let n = p.k.nrows();
    let c = Constraints::new(n, patch_rows(n)).unwrap();
    let exact = null_space_eigenvalues(&p, &c);
    let factor = SparseCholesky::factorize(p.k.as_ref()).unwrap();
    let cf = ConstrainedFactor::new(&factor, &c).unwrap();
    let nev = 25;
    for block_size in [1, 8] {
        let opts = {
            let mut o = EigOptions::default();
            o.block_size = block_size;
            o
        };
        let modes = lowest_modes_constrained(p.k.as_ref(), p.m.as_ref(), &cf, nev, &opts).unwrap();
        assert_eq!(modes.stats.block, block_size);
        for (i, (&got, &want)) in modes.values.iter().zip(&exact).enumerate() {
            // Tolerance: residual tolerance 1e-10 gives eigenvalue errors
            // ~1e-20 relative; the dense reference is accurate to ~1e-13.
            assert!(
                rel(got, want) < 1e-10,
                "block {block_size} mode {i}: {got} vs {want}"
            );
        }
        let cx = c.apply(modes.vectors.as_ref());
        // Tolerance: every basis vector is projected into null(C) to rounding.
        assert!(
            cx.norm_max() < 1e-12 * modes.vectors.norm_max(),
            "C phi = {:e}",
            cx.norm_max()
        );
        // Tolerance: the solver's own limit is 1e4 tol; converged pairs are far below.
        assert!(
            modes.residuals.iter().all(|&r| r < 1e-10),
            "{:?}",
            modes.residuals
        );
        // The Sturm check counted the constrained eigenvalues below its bound.
        let (bound, count) = modes.stats.sturm.unwrap();
        assert_eq!(count, exact.iter().filter(|&&v| v < bound).count());
    }
}

#[test]
fn constrained_sturm_counts_match_the_reference() {
    let p = box_vector([6, 5, 5], [1.0, 0.8, 0.6]);
    let n = p.k.nrows();
    let c = Constraints::new(n, patch_rows(n)).unwrap();
    let exact = null_space_eigenvalues(&p, &c);
    for j in [1usize, 7, 40, 200] {
        let bound = 0.5 * (exact[j - 1] + exact[j]);
        // Exact: inertia counts, bounds in spectral gaps.
        let count = count_below_constrained(p.k.as_ref(), p.m.as_ref(), &c, bound).unwrap();
        assert_eq!(count, j, "bound between eigenvalues {j} and {}", j + 1);
    }
}

#[test]
fn constraint_modes_meet_their_constraint_with_least_energy() {
    let p = box_vector([6, 5, 5], [1.0, 0.8, 0.6]);
    let n = p.k.nrows();
    let c = Constraints::new(n, patch_rows(n)).unwrap();
    let factor = SparseCholesky::factorize(p.k.as_ref()).unwrap();
    let cf = ConstrainedFactor::new(&factor, &c).unwrap();
    let q = c.len();
    let psi = cf.correction(Mat::<f64>::identity(q, q).as_ref()).unwrap();
    let cpsi = c.apply(psi.as_ref());
    // Tolerance: C X S^-1 = S S^-1 = I up to the conditioning of S (~1e2 here).
    assert!((&cpsi - Mat::<f64>::identity(q, q)).norm_max() < 1e-12);
    // K psi = C^T mu: the residual of K psi has no part outside range(C^T).
    let ct = c.transpose_dense();
    let kpsi = &p.k * &psi;
    let mu = (ct.transpose() * &ct).partial_piv_lu().inverse() * (ct.transpose() * &kpsi);
    let r = &kpsi - &ct * &mu;
    assert!(r.norm_max() < 1e-10 * kpsi.norm_max(), "{:e}", r.norm_max());
}

#[test]
fn dependent_constraint_rows_are_an_error() {
    let p = box_vector([4, 4, 4], [1.0, 1.0, 1.0]);
    let n = p.k.nrows();
    let row = vec![(3, 0.5), (9, 0.5)];
    let doubled: Vec<(usize, f64)> = row.iter().map(|&(i, v)| (i, 2.0 * v)).collect();
    let c = Constraints::new(n, vec![row, doubled]).unwrap();
    let factor = SparseCholesky::factorize(p.k.as_ref()).unwrap();
    assert!(matches!(
        ConstrainedFactor::new(&factor, &c),
        Err(EigError::DependentConstraints { row: 1 })
    ));
    assert!(matches!(
        Constraints::new(n, vec![vec![(n, 1.0)]]),
        Err(EigError::DimensionMismatch { .. })
    ));
}
