//! Spectrum slicing (several shifts) against one shift, closed forms and a
//! constrained reference, and its thread-count independence.

use squeal_eigs::model_problems::{box_scalar, box_scalar_eigenvalues, box_vector};
use squeal_eigs::{
    ConstrainedFactor, Constraints, EigOptions, SparseCholesky, count_below,
    count_below_constrained, lowest_modes, lowest_modes_constrained,
};

use super::common;
use common::{in_pool, orthonormality_error, rel};

fn sliced(slice: usize) -> EigOptions {
    {
        let mut o = EigOptions::default();
        o.slice = slice;
        o
    }
}

#[test]
fn several_shifts_find_the_modes_one_shift_finds() {
    // A cube-like box: multiple eigenvalues, some at the slice boundaries.
    let dims = [10, 9, 9];
    let lengths = [1.0, 0.9, 0.9];
    let p = box_scalar(dims, lengths);
    let exact = box_scalar_eigenvalues(dims, lengths);
    let nev = 70;
    let one = lowest_modes(p.k.as_ref(), p.m.as_ref(), nev, &sliced(0)).unwrap();
    let many = lowest_modes(p.k.as_ref(), p.m.as_ref(), nev, &sliced(20)).unwrap();
    eprintln!(
        "one shift: {} solves; {} shifts: {} solves",
        one.stats.operator_applications, many.stats.shifts, many.stats.operator_applications
    );
    assert_eq!(one.stats.shifts, 1);
    assert!(many.stats.shifts >= 3, "{} shifts", many.stats.shifts);
    for (i, (&got, &want)) in many.values.iter().zip(&exact).enumerate() {
        // Tolerance: residual tolerance 1e-10 gives eigenvalue errors ~1e-20
        // relative; 1e-10 leaves room for rounding in the factors.
        assert!(rel(got, want) < 1e-10, "mode {i}: {got} vs {want}");
        assert!(rel(got, one.values[i]) < 1e-10, "mode {i}");
    }
    // Tolerance: locked pairs and each shift's basis are M-orthonormal to rounding.
    assert!(orthonormality_error(p.m.as_ref(), &many.vectors) < 1e-10);
    assert!(
        many.residuals.iter().all(|&r| r < 1e-10),
        "{:?}",
        many.residuals
    );
    // The last verified shift is the Sturm check: exact count there.
    let (bound, count) = many.stats.sturm.unwrap();
    assert!(count >= nev && bound > many.values[nev - 1]);
    assert_eq!(
        count_below(p.k.as_ref(), p.m.as_ref(), bound).unwrap(),
        count
    );
}

#[test]
fn several_shifts_with_constraints_match_one_shift() {
    let p = box_vector([7, 6, 6], [1.0, 0.8, 0.7]);
    let n = p.k.nrows();
    let rows: Vec<Vec<(usize, f64)>> = (0..4)
        .map(|r| (0..10).map(|k| (3 * (20 * r + k) + r % 3, 0.1)).collect())
        .collect();
    let c = Constraints::new(n, rows).unwrap();
    let factor = SparseCholesky::factorize(p.k.as_ref()).unwrap();
    let cf = ConstrainedFactor::new(&factor, &c).unwrap();
    let nev = 45;
    let one = lowest_modes_constrained(p.k.as_ref(), p.m.as_ref(), &cf, nev, &sliced(0)).unwrap();
    let many = lowest_modes_constrained(p.k.as_ref(), p.m.as_ref(), &cf, nev, &sliced(15)).unwrap();
    assert!(many.stats.shifts >= 3, "{} shifts", many.stats.shifts);
    for (i, (&got, &want)) in many.values.iter().zip(&one.values).enumerate() {
        // Tolerance: as above.
        assert!(rel(got, want) < 1e-10, "mode {i}");
    }
    // Tolerance: every shift's operator projects into null(C) to rounding.
    let cx = c.apply(many.vectors.as_ref());
    assert!(cx.norm_max() < 1e-12 * many.vectors.norm_max());
    let (bound, count) = many.stats.sturm.unwrap();
    let exact = count_below_constrained(p.k.as_ref(), p.m.as_ref(), &c, bound).unwrap();
    assert_eq!(exact, count);
}

#[test]
fn slicing_does_not_depend_on_the_thread_count() {
    let p = box_vector([6, 6, 5], [1.0, 0.9, 0.8]);
    let run = |threads: usize| {
        in_pool(threads, |par| {
            let opts = {
                let mut o = EigOptions::default();
                o.par = par;
                o.slice = 16;
                o
            };
            lowest_modes(p.k.as_ref(), p.m.as_ref(), 40, &opts).unwrap()
        })
    };
    let a = run(1);
    assert!(a.stats.shifts >= 3);
    for t in [2, 3] {
        let b = run(t);
        // Exact: determinism is a bitwise property.
        assert_eq!(a.values, b.values);
        assert_eq!(a.vectors, b.vectors);
    }
}
