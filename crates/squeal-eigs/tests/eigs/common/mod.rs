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

/// Runs `f` in a rayon pool of `threads` threads, with faer's parallelism set
/// to match (sequential for one thread).
pub fn in_pool<T: Send>(threads: usize, f: impl FnOnce(faer::Par) -> T + Send) -> T {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let par = if threads == 1 {
            faer::Par::Seq
        } else {
            faer::Par::rayon(threads)
        };
        f(par)
    })
}
