//! Measures shared by the eigensolver tests.

#![allow(dead_code)]

use faer::Mat;
use faer::sparse::SparseColMatRef;

/// `|a - b| / |b|`.
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

/// max |Phi^T M Phi - I|.
pub fn orthonormality_error(m: SparseColMatRef<'_, usize, f64>, phi: &Mat<f64>) -> f64 {
    let g = phi.transpose() * (m * phi);
    let mut worst = 0.0f64;
    for i in 0..g.nrows() {
        for j in 0..g.ncols() {
            let target = if i == j { 1.0 } else { 0.0 };
            worst = worst.max((g[(i, j)] - target).abs());
        }
    }
    worst
}
