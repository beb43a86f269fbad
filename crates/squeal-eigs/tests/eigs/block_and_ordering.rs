//! The block Lanczos path and the nested-dissection ordering against closed
//! forms, the single-vector solver and AMD.

use faer::Mat;
use faer::sparse::{SparseColMat, Triplet};
use squeal_eigs::model_problems::{
    Ends, bar, bar_eigenvalues, box_scalar, box_scalar_eigenvalues, box_vector,
};
use squeal_eigs::{
    CholeskyOptions, EigOptions, FillOrdering, SparseCholesky, count_below, lowest_modes,
};

use super::common;
use common::{in_pool, orthonormality_error, rel};

fn block_opts(block_size: usize) -> EigOptions {
    {
        let mut o = EigOptions::default();
        o.block_size = block_size;
        o
    }
}

#[test]
fn block_lanczos_matches_closed_form_on_a_box() {
    let dims = [10, 9, 8];
    let lengths = [1.0, 0.9, 0.8];
    let p = box_scalar(dims, lengths);
    let exact = box_scalar_eigenvalues(dims, lengths);
    let modes = lowest_modes(p.k.as_ref(), p.m.as_ref(), 20, &block_opts(8)).unwrap();
    // The block path must really have run, else this test proves nothing about it.
    assert_eq!(modes.stats.block, 8);
    for (i, (&got, &want)) in modes.values.iter().zip(&exact).enumerate() {
        // Tolerance: residual tolerance 1e-10 gives eigenvalue errors ~1e-20
        // relative; 1e-10 leaves room for rounding in the factor.
        assert!(rel(got, want) < 1e-10, "mode {i}: {got} vs {want}");
    }
    // Tolerance: M-orthonormality is kept by CGS2 to rounding, ~1e-14.
    assert!(orthonormality_error(p.m.as_ref(), &modes.vectors) < 1e-10);
}

#[test]
fn block_lanczos_finds_sixfold_eigenvalues_in_one_round() {
    let dims = [9, 9, 9];
    let lengths = [1.0, 1.0, 1.0];
    let p = box_scalar(dims, lengths);
    let exact = box_scalar_eigenvalues(dims, lengths);
    let nev = 30;
    let sixfold = exact[..nev].windows(6).any(|w| rel(w[5], w[0]) < 1e-12);
    assert!(sixfold, "the reference has no sixfold eigenvalue");
    let modes = lowest_modes(p.k.as_ref(), p.m.as_ref(), nev, &block_opts(8)).unwrap();
    assert_eq!(modes.stats.block, 8);
    // A block of 8 holds every copy of a sixfold eigenvalue: no locked restart.
    assert_eq!(modes.stats.rounds, 1);
    for (i, (&got, &want)) in modes.values.iter().zip(&exact).enumerate() {
        // Tolerance: as above; a missed copy shifts the list by O(10%).
        assert!(rel(got, want) < 1e-10, "mode {i}: {got} vs {want}");
    }
}

#[test]
fn block_and_single_vector_lanczos_agree() {
    let p = box_vector([8, 7, 6], [1.0, 0.8, 0.6]);
    let a = lowest_modes(p.k.as_ref(), p.m.as_ref(), 40, &block_opts(1)).unwrap();
    let b = lowest_modes(p.k.as_ref(), p.m.as_ref(), 40, &block_opts(16)).unwrap();
    assert_eq!((a.stats.block, b.stats.block), (1, 16));
    for (i, (x, y)) in a.values.iter().zip(&b.values).enumerate() {
        // Tolerance: both converge to residual 1e-10, eigenvalue error ~1e-20.
        assert!(rel(*x, *y) < 1e-9, "mode {i}: {x} vs {y}");
    }
}

#[test]
fn block_lanczos_with_a_negative_shift_finds_the_rigid_mode() {
    let p = bar(300, 1.0, Ends::Free);
    let exact = bar_eigenvalues(300, 1.0, Ends::Free);
    let opts = {
        let mut o = block_opts(4);
        o.shift = -1.0;
        o
    };
    let modes = lowest_modes(p.k.as_ref(), p.m.as_ref(), 6, &opts).unwrap();
    assert_eq!(modes.stats.block, 4);
    // Tolerance: the rigid value is zero to rounding relative to w_1^2.
    assert!(modes.values[0].abs() < 1e-9 * exact[1]);
    for (i, (&got, &want)) in modes.values.iter().zip(&exact).enumerate().skip(1) {
        assert!(rel(got, want) < 1e-10, "mode {i}: {got} vs {want}");
    }
}

#[test]
fn block_lanczos_replaces_dependent_directions() {
    // K = diag(1, 2, 3) each repeated 30 times, M = I: a block Krylov space
    // of 8 start vectors saturates at 3 x 8 = 24 dimensions, below the
    // basis size, so dependent directions must be replaced.
    let n = 90;
    let kt: Vec<Triplet<usize, usize, f64>> = (0..n)
        .map(|i| Triplet::new(i, i, 1.0 + (i % 3) as f64))
        .collect();
    let mt: Vec<Triplet<usize, usize, f64>> = (0..n).map(|i| Triplet::new(i, i, 1.0)).collect();
    let k = SparseColMat::try_new_from_triplets(n, n, &kt).unwrap();
    let m = SparseColMat::try_new_from_triplets(n, n, &mt).unwrap();
    let opts = {
        let mut o = block_opts(8);
        o.sturm_check = false;
        o
    };
    let modes = lowest_modes(k.as_ref(), m.as_ref(), 5, &opts).unwrap();
    assert_eq!(modes.stats.block, 8);
    for &v in &modes.values {
        // Tolerance: an exact eigenvalue of a diagonal pencil, to rounding.
        assert!(rel(v, 1.0) < 1e-12, "{v}");
    }
    assert!(orthonormality_error(m.as_ref(), &modes.vectors) < 1e-10);
}

#[test]
fn nested_dissection_fills_less_than_amd_and_solves_the_same() {
    let p = box_vector([14, 13, 12], [1.0, 0.9, 0.8]);
    let factor = |ordering| {
        let opts = {
            let mut o = CholeskyOptions::default();
            o.ordering = ordering;
            o
        };
        SparseCholesky::factorize_with(p.k.as_ref(), &opts).unwrap()
    };
    let nd = factor(FillOrdering::NestedDissection);
    let amd = factor(FillOrdering::Amd);
    let perm = nd.permutation().unwrap();
    let mut seen = vec![false; perm.len()];
    for &i in perm {
        assert!(!seen[i], "index {i} twice");
        seen[i] = true;
    }
    // George (1973): on 3-D grids nested dissection's fill grows as n^(4/3)
    // against AMD's faster growth; at this size ND is already below AMD.
    assert!(
        nd.stats().nnz_l < amd.stats().nnz_l,
        "ND {} vs AMD {}",
        nd.stats().nnz_l,
        amd.stats().nnz_l
    );
    let n = p.k.nrows();
    let b = Mat::<f64>::from_fn(n, 3, |i, j| ((i * 31 + j * 17) % 23) as f64 - 11.0);
    let x_nd = nd.solve(b.as_ref()).unwrap();
    let x_amd = amd.solve(b.as_ref()).unwrap();
    let diff = (&x_nd - &x_amd).norm_l2() / x_amd.norm_l2();
    // Tolerance: two backward-stable solves of a matrix with cond ~1e3.
    assert!(diff < 1e-11, "{diff}");
}

#[test]
fn nested_dissection_and_factor_do_not_depend_on_the_thread_count() {
    let p = box_vector([12, 12, 11], [1.0, 1.0, 0.9]);
    let run = |threads: usize| {
        in_pool(threads, |par| {
            let opts = {
                let mut o = CholeskyOptions::default();
                o.par = par;
                o
            };
            let f = SparseCholesky::factorize_with(p.k.as_ref(), &opts).unwrap();
            let b = Mat::<f64>::from_fn(p.k.nrows(), 40, |i, j| ((i + 3 * j) % 7) as f64);
            (
                f.permutation().unwrap().to_vec(),
                f.solve(b.as_ref()).unwrap(),
            )
        })
    };
    let (a, b) = (run(1), run(2));
    // Exact: determinism is a bitwise property.
    assert_eq!(a.0, b.0);
    assert_eq!(a.1, b.1);
}

#[test]
fn sturm_count_with_nested_dissection_matches_closed_form() {
    let dims = [11, 10, 9];
    let lengths = [1.0, 0.9, 0.8];
    let p = box_scalar(dims, lengths);
    let exact = box_scalar_eigenvalues(dims, lengths);
    for j in [1usize, 17, 60, 400] {
        let bound = 0.5 * (exact[j - 1] + exact[j]);
        // Exact: Sylvester's law of inertia; the bounds sit in spectral gaps.
        assert_eq!(count_below(p.k.as_ref(), p.m.as_ref(), bound).unwrap(), j);
    }
}

#[test]
fn sturm_check_beside_the_iteration_counts_what_a_check_after_it_counts() {
    let p = box_vector([8, 7, 6], [1.0, 0.8, 0.6]);
    let nev = 40;
    let modes = lowest_modes(p.k.as_ref(), p.m.as_ref(), nev, &block_opts(8)).unwrap();
    // The bound came from Ritz values during the iteration.
    assert!(modes.stats.sturm_beside);
    let (bound, count) = modes.stats.sturm.unwrap();
    assert!(bound > modes.values[nev - 1] && count >= nev);
    // Exact: the same inertia counted by the public entry point.
    assert_eq!(
        count_below(p.k.as_ref(), p.m.as_ref(), bound).unwrap(),
        count
    );
}
