//! The ARPACK backend (feature `arpack`) against the pure-Rust Lanczos and closed forms.
#![cfg(feature = "arpack")]

use squeal_eigs::model_problems::{
    Ends, bar, bar_eigenvalues, box_scalar, box_scalar_eigenvalues, box_vector,
};
use squeal_eigs::{Backend, EigOptions, lowest_modes};

use super::common;
use common::rel;

fn both(
    k: &faer::sparse::SparseColMat<usize, f64>,
    m: &faer::sparse::SparseColMat<usize, f64>,
    nev: usize,
    shift: f64,
) -> (Vec<f64>, Vec<f64>) {
    let lan = {
        let mut o = EigOptions::default();
        o.shift = shift;
        o
    };
    let arp = {
        let mut o = lan;
        o.backend = Backend::Arpack;
        o
    };
    let a = lowest_modes(k.as_ref(), m.as_ref(), nev, &lan).unwrap();
    let b = lowest_modes(k.as_ref(), m.as_ref(), nev, &arp).unwrap();
    assert!(b.residuals.iter().all(|&r| r < 1e-9), "{:?}", b.residuals);
    (a.values, b.values)
}

#[test]
fn backends_agree_on_a_vector_box() {
    let p = box_vector([8, 7, 6], [1.0, 0.8, 0.6]);
    let (a, b) = both(&p.k, &p.m, 40, 0.0);
    for (i, (x, y)) in a.iter().zip(&b).enumerate() {
        // Tolerance: both converge to residual 1e-10, eigenvalue error ~1e-20;
        // 1e-9 is the agreement asked of the two backends.
        assert!(rel(*x, *y) < 1e-9, "mode {i}: {x} vs {y}");
    }
}

#[test]
fn backends_agree_on_multiple_eigenvalues() {
    let dims = [9, 9, 9];
    let lengths = [1.0, 1.0, 1.0];
    let p = box_scalar(dims, lengths);
    let exact = box_scalar_eigenvalues(dims, lengths);
    let (a, b) = both(&p.k, &p.m, 30, 0.0);
    for i in 0..30 {
        // Tolerance: as above, and against the closed form.
        assert!(rel(a[i], b[i]) < 1e-9, "mode {i}: {} vs {}", a[i], b[i]);
        assert!(
            rel(b[i], exact[i]) < 1e-9,
            "mode {i}: {} vs {}",
            b[i],
            exact[i]
        );
    }
}

#[test]
fn arpack_free_free_bar_with_negative_shift() {
    let p = bar(200, 1.0, Ends::Free);
    let exact = bar_eigenvalues(200, 1.0, Ends::Free);
    let (a, b) = both(&p.k, &p.m, 5, -1.0);
    // Tolerance: the rigid value is zero to rounding (see the Lanczos test).
    assert!(b[0].abs() < 1e-9 * exact[1] && a[0].abs() < 1e-9 * exact[1]);
    for i in 1..5 {
        assert!(rel(a[i], b[i]) < 1e-9 && rel(b[i], exact[i]) < 1e-10);
    }
}
