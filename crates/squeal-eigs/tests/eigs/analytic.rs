//! Eigenvalues, Sturm counts and factor solves against closed-form references.

use faer::Mat;
use faer::sparse::{SparseColMat, Triplet};
use squeal_eigs::model_problems::{
    Ends, bar, bar_eigenvalues, box_scalar, box_scalar_eigenvalues, box_vector,
};
use squeal_eigs::{
    EigError, EigOptions, SparseCholesky, count_below, inertia, lowest_modes,
    lowest_modes_with_factor, shifted, sturm_check,
};

use super::common;
use common::{in_pool, orthonormality_error, rel};

#[test]
fn fixed_fixed_bar_matches_closed_form() {
    let (n_el, len) = (400, 2.0);
    let p = bar(n_el, len, Ends::Fixed);
    let exact = bar_eigenvalues(n_el, len, Ends::Fixed);
    let modes = lowest_modes(p.k.as_ref(), p.m.as_ref(), 12, &EigOptions::default()).unwrap();
    for (i, (&got, &want)) in modes.values.iter().zip(&exact).enumerate() {
        // Tolerance: residual tolerance 1e-10 gives eigenvalue errors ~1e-20
        // relative; 1e-10 leaves room for rounding in the factor (cond ~ 1e5).
        assert!(rel(got, want) < 1e-10, "mode {i}: {got} vs {want}");
    }
    // Tolerance: M-orthonormality is kept by CGS2 to rounding, ~1e-14.
    assert!(orthonormality_error(p.m.as_ref(), &modes.vectors) < 1e-10);
    // Tolerance: backward errors are about tol = 1e-10 or below.
    assert!(
        modes.residuals.iter().all(|&r| r < 1e-9),
        "{:?}",
        modes.residuals
    );
    assert_eq!(modes.stats.sturm.map(|s| s.1), Some(12));
}

#[test]
fn square_grid_finds_both_copies_of_double_eigenvalues() {
    let dims = [14, 14, 1];
    let lengths = [1.0, 1.0, 0.5];
    let p = box_scalar(dims, lengths);
    let exact = box_scalar_eigenvalues(dims, lengths);
    let nev = 20;
    // The reference must really contain multiple eigenvalues, else the test proves nothing.
    let doubles = exact[..nev]
        .windows(2)
        .filter(|w| rel(w[1], w[0]) < 1e-12)
        .count();
    assert!(
        doubles >= 6,
        "only {doubles} double eigenvalues among the first {nev}"
    );
    let modes = lowest_modes(p.k.as_ref(), p.m.as_ref(), nev, &EigOptions::default()).unwrap();
    for (i, (&got, &want)) in modes.values.iter().zip(&exact).enumerate() {
        // Tolerance: as for the bar; a missed copy shifts the list and fails by O(10%).
        assert!(rel(got, want) < 1e-10, "mode {i}: {got} vs {want}");
    }
    assert!(orthonormality_error(p.m.as_ref(), &modes.vectors) < 1e-10);
}

#[test]
fn cube_finds_triple_and_sixfold_eigenvalues() {
    let dims = [9, 9, 9];
    let lengths = [1.0, 1.0, 1.0];
    let p = box_scalar(dims, lengths);
    let exact = box_scalar_eigenvalues(dims, lengths);
    let nev = 30;
    let mut max_mult = 1;
    let mut run = 1;
    for w in exact[..nev].windows(2) {
        run = if rel(w[1], w[0]) < 1e-12 { run + 1 } else { 1 };
        max_mult = max_mult.max(run);
    }
    assert!(max_mult >= 6, "largest multiplicity {max_mult}");
    let modes = lowest_modes(p.k.as_ref(), p.m.as_ref(), nev, &EigOptions::default()).unwrap();
    for (i, (&got, &want)) in modes.values.iter().zip(&exact).enumerate() {
        // Tolerance: as for the bar.
        assert!(rel(got, want) < 1e-10, "mode {i}: {got} vs {want}");
    }
    assert!(orthonormality_error(p.m.as_ref(), &modes.vectors) < 1e-10);
}

#[test]
fn free_free_bar_with_negative_shift_finds_the_rigid_mode() {
    let (n_el, len) = (300, 1.0);
    let p = bar(n_el, len, Ends::Free);
    let exact = bar_eigenvalues(n_el, len, Ends::Free);
    let opts = {
        let mut o = EigOptions::default();
        o.shift = -1.0;
        o
    };
    let modes = lowest_modes(p.k.as_ref(), p.m.as_ref(), 6, &opts).unwrap();
    // Tolerance: the zero eigenvalue is found to rounding of the shifted
    // operator, ~1e-16 * |shift| and cond; 1e-9 of the first flexible one.
    assert!(
        modes.values[0].abs() < 1e-9 * exact[1],
        "rigid {}",
        modes.values[0]
    );
    for (i, (got, want)) in modes.values.iter().zip(&exact).enumerate().skip(1) {
        // Tolerance: as for the fixed-fixed bar.
        assert!(rel(*got, *want) < 1e-10, "mode {i}: {got} vs {want}");
    }
    // The rigid mode of a free bar is uniform: phi = 1 / sqrt(total mass) = 1.
    let phi0 = modes.vectors.col(0);
    let mean = phi0.iter().sum::<f64>() / phi0.nrows() as f64;
    for &v in phi0.iter() {
        // Tolerance: eigenvector error ~ residual / gap ~ 1e-10 * lambda_1 / lambda_1.
        assert!(
            (v - mean).abs() < 1e-7 && (mean.abs() - 1.0).abs() < 1e-7,
            "{v} {mean}"
        );
    }
}

#[test]
fn singular_stiffness_is_not_positive_definite() {
    let p = bar(50, 1.0, Ends::Free);
    let err = SparseCholesky::factorize(p.k.as_ref()).unwrap_err();
    assert!(
        matches!(err, EigError::NotPositiveDefinite { .. }),
        "{err:?}"
    );
    let err = lowest_modes(p.k.as_ref(), p.m.as_ref(), 3, &EigOptions::default()).unwrap_err();
    assert!(
        matches!(err, EigError::NotPositiveDefinite { .. }),
        "{err:?}"
    );
}

#[test]
fn shift_above_lowest_eigenvalue_is_rejected() {
    let p = bar(100, 1.0, Ends::Fixed);
    let exact = bar_eigenvalues(100, 1.0, Ends::Fixed);
    let opts = {
        let mut o = EigOptions::default();
        o.shift = 0.5 * (exact[0] + exact[1]);
        o
    };
    let err = lowest_modes(p.k.as_ref(), p.m.as_ref(), 3, &opts).unwrap_err();
    assert!(
        matches!(err, EigError::NotPositiveDefinite { .. }),
        "{err:?}"
    );
}

#[test]
fn sturm_counts_match_closed_form_everywhere_in_the_spectrum() {
    let dims = [7, 6, 5];
    let lengths = [1.0, 0.9, 0.7];
    let p = box_scalar(dims, lengths);
    let exact = box_scalar_eigenvalues(dims, lengths);
    let n = exact.len();
    for &j in &[1usize, 5, 17, 60, 105, 150, n - 1] {
        let (a, b) = (exact[j - 1], exact[j]);
        if rel(b, a) < 1e-9 {
            continue;
        }
        let bound = 0.5 * (a + b);
        // Exact: the count is an integer; any error is a wrong inertia.
        assert_eq!(
            count_below(p.k.as_ref(), p.m.as_ref(), bound).unwrap(),
            j,
            "bound {bound}"
        );
    }
    assert_eq!(
        count_below(p.k.as_ref(), p.m.as_ref(), exact[0] * 0.5).unwrap(),
        0
    );
    assert_eq!(
        count_below(p.k.as_ref(), p.m.as_ref(), exact[n - 1] * 1.5).unwrap(),
        n
    );
}

#[test]
fn inertia_of_indefinite_vector_problem_matches_dense_eigenvalues() {
    // Second, independent algorithm: dense symmetric eigenvalues of K - s M.
    let p = box_vector([4, 3, 3], [1.0, 0.8, 0.6]);
    // Shift at the mean eigenvalue trace(K) / trace(M): mid-spectrum.
    let (kd, md) = (p.k.as_ref().to_dense(), p.m.as_ref().to_dense());
    let s = (0..kd.nrows()).map(|i| kd[(i, i)]).sum::<f64>()
        / (0..md.nrows()).map(|i| md[(i, i)]).sum::<f64>();
    let a = shifted(p.k.as_ref(), p.m.as_ref(), s).unwrap();
    let dense = a.as_ref().to_dense();
    let ev = dense.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
    let neg = ev.iter().filter(|&&x| x < 0.0).count();
    let min_abs = ev.iter().fold(f64::INFINITY, |m, x| m.min(x.abs()));
    assert!(
        neg > 0 && neg < ev.len() && min_abs > 1e-8,
        "neg {neg} min |ev| {min_abs}"
    );
    let i = inertia(a.as_ref()).unwrap();
    // Exact integer counts.
    assert_eq!((i.negative, i.zero, i.positive), (neg, 0, ev.len() - neg));
}

#[test]
fn sturm_check_reports_a_dropped_eigenvalue() {
    let dims = [10, 10, 1];
    let lengths = [1.0, 1.0, 0.5];
    let p = box_scalar(dims, lengths);
    let exact = box_scalar_eigenvalues(dims, lengths);
    let (bound, count) = sturm_check(p.k.as_ref(), p.m.as_ref(), &exact[..12], 8).unwrap();
    assert!(bound > exact[count - 1] && bound < exact[count]);
    // Drop one eigenvalue below the nev-th one: the count must expose it.
    let mut missing: Vec<f64> = exact[..12].to_vec();
    missing.remove(3);
    let err = sturm_check(p.k.as_ref(), p.m.as_ref(), &missing, 8).unwrap_err();
    match err {
        EigError::MissedEigenvalues {
            expected, found, ..
        } => assert_eq!(expected, found + 1),
        other => panic!("{other:?}"),
    }
}

#[test]
fn factor_reuse_matches_fresh_factorization_and_detects_a_wrong_factor() {
    let p = box_scalar([8, 7, 6], [1.0, 0.9, 0.8]);
    let opts = EigOptions::default();
    let fresh = lowest_modes(p.k.as_ref(), p.m.as_ref(), 10, &opts).unwrap();
    let f = SparseCholesky::factorize(p.k.as_ref()).unwrap();
    let reused = lowest_modes_with_factor(p.k.as_ref(), p.m.as_ref(), &f, 10, &opts).unwrap();
    for (a, b) in fresh.values.iter().zip(&reused.values) {
        // Tolerance: same algorithm, same matrix; only rounding differs.
        assert!(rel(*a, *b) < 1e-12);
    }
    let shifted_opts = {
        let mut o = EigOptions::default();
        o.shift = -50.0;
        o
    };
    let err =
        lowest_modes_with_factor(p.k.as_ref(), p.m.as_ref(), &f, 10, &shifted_opts).unwrap_err();
    assert!(matches!(err, EigError::FactorMismatch { .. }), "{err:?}");
}

#[test]
fn constraint_modes_of_a_bar_are_linear() {
    // Interior nodes 1..n of a bar fixed at node n+1, boundary node 0 moved by
    // 1: the static solution is linear, u(x_i) = 1 - i / (n + 1).
    let n_el = 60;
    let h = 1.0 / n_el as f64;
    let p = bar(n_el, 1.0, Ends::Fixed);
    let n = p.k.nrows();
    let k_ib = SparseColMat::try_new_from_triplets(n, 1, &[Triplet::new(0, 0, -1.0 / h)]).unwrap();
    let f = SparseCholesky::factorize(p.k.as_ref()).unwrap();
    let x = f.constraint_modes(k_ib.as_ref()).unwrap();
    for i in 0..n {
        let exact = 1.0 - (i + 1) as f64 / n_el as f64;
        // Tolerance: direct solve of a cond ~ 1e3 system: rounding only.
        assert!(
            (x[(i, 0)] - exact).abs() < 1e-12,
            "{i}: {} vs {exact}",
            x[(i, 0)]
        );
    }
    let s = f.stats();
    assert_eq!(s.n, n);
    // A tridiagonal matrix has a tridiagonal factor under AMD: nnz(L) = 2n - 1.
    assert_eq!(s.nnz_l, 2 * n - 1);
}

#[test]
fn multi_rhs_solve_matches_single_solves() {
    let p = box_vector([5, 4, 4], [1.0, 0.8, 0.6]);
    let f = SparseCholesky::factorize(p.k.as_ref()).unwrap();
    let n = p.k.nrows();
    let b = Mat::<f64>::from_fn(n, 37, |i, j| ((i * 31 + j * 17) % 23) as f64 - 11.0);
    let x = f.solve(b.as_ref()).unwrap();
    let r = p.k.as_ref() * &x - &b;
    // Tolerance: backward error of a Cholesky solve, ~1e-16 * cond (~1e3).
    assert!(r.norm_max() < 1e-10 * b.norm_max(), "{}", r.norm_max());
    for j in [0, 16, 36] {
        let mut c = b.col(j).to_owned();
        f.solve_col_in_place(&mut c).unwrap();
        // Exact: column blocks are solved by the same sequential code.
        assert_eq!(c.as_ref(), x.col(j));
    }
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let p = box_vector([6, 5, 5], [1.0, 0.8, 0.6]);
    let run = |threads: usize| {
        in_pool(threads, |par| {
            let opts = {
                let mut o = EigOptions::default();
                o.par = par;
                o
            };
            lowest_modes(p.k.as_ref(), p.m.as_ref(), 8, &opts).unwrap()
        })
    };
    let (a, b) = (run(1), run(2));
    // Exact: determinism is a bitwise property.
    assert_eq!(a.values, b.values);
    assert_eq!(a.vectors, b.vectors);
}

#[test]
fn non_convergence_is_an_error_with_residuals() {
    let p = box_scalar([12, 11, 10], [1.0, 0.9, 0.8]);
    let opts = {
        let mut o = EigOptions::default();
        o.max_iter = 1;
        o.ncv = Some(14);
        o
    };
    match lowest_modes(p.k.as_ref(), p.m.as_ref(), 10, &opts).unwrap_err() {
        EigError::NotConverged {
            residuals, worst, ..
        } => {
            assert_eq!(residuals.len(), 13);
            assert!(worst > opts.tol);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_inputs_give_typed_errors() {
    let p = bar(20, 1.0, Ends::Fixed);
    let n = p.k.nrows();
    // Upper triangle only, as in a MatrixMarket 'symmetric' file.
    let mut t = Vec::new();
    for j in 0..n {
        for (i, &v) in p.k.row_idx_of_col(j).zip(p.k.val_of_col(j)) {
            if i <= j {
                t.push(Triplet::new(i, j, v));
            }
        }
    }
    let upper = SparseColMat::try_new_from_triplets(n, n, &t).unwrap();
    let e = lowest_modes(upper.as_ref(), p.m.as_ref(), 2, &EigOptions::default()).unwrap_err();
    assert!(
        matches!(e, EigError::NotSymmetric { matrix: "K", .. }),
        "{e:?}"
    );
    let e = lowest_modes(p.k.as_ref(), p.m.as_ref(), n + 1, &EigOptions::default()).unwrap_err();
    assert!(matches!(e, EigError::TooManyRequested { .. }), "{e:?}");
    let mut nan = p.k.clone();
    nan.val_mut()[3] = f64::NAN;
    let e = lowest_modes(nan.as_ref(), p.m.as_ref(), 2, &EigOptions::default()).unwrap_err();
    assert!(matches!(e, EigError::NonFinite { .. }), "{e:?}");
    let small = bar(10, 1.0, Ends::Fixed);
    let e = lowest_modes(small.k.as_ref(), p.m.as_ref(), 2, &EigOptions::default()).unwrap_err();
    assert!(matches!(e, EigError::DimensionMismatch { .. }), "{e:?}");
    let mut zero_mass = p.m.clone();
    for v in zero_mass.val_mut() {
        *v = 0.0;
    }
    let e = lowest_modes(p.k.as_ref(), zero_mass.as_ref(), 2, &EigOptions::default()).unwrap_err();
    assert!(matches!(e, EigError::MassNotPositive { .. }), "{e:?}");
}

#[test]
fn whole_spectrum_of_a_tiny_problem() {
    // n smaller than the default basis: the Krylov space becomes the whole space.
    let p = bar(6, 1.0, Ends::Fixed);
    let exact = bar_eigenvalues(6, 1.0, Ends::Fixed);
    let modes = lowest_modes(p.k.as_ref(), p.m.as_ref(), 5, &EigOptions::default()).unwrap();
    for (got, want) in modes.values.iter().zip(&exact) {
        // Tolerance: full-space Rayleigh-Ritz is exact up to rounding.
        assert!(rel(*got, *want) < 1e-12);
    }
}

#[cfg(not(feature = "arpack"))]
#[test]
fn arpack_backend_without_feature_is_a_typed_error() {
    let p = bar(20, 1.0, Ends::Fixed);
    let opts = {
        let mut o = EigOptions::default();
        o.backend = squeal_eigs::Backend::Arpack;
        o
    };
    let e = lowest_modes(p.k.as_ref(), p.m.as_ref(), 2, &opts).unwrap_err();
    assert_eq!(e, EigError::BackendUnavailable("arpack"));
}
