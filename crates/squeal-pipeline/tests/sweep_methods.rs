//! The two sweep methods against each other on the coarse bundled brake (158 dofs, 316
//! eigenvalues per friction value): continuation of eigenpairs (the default) must give the
//! dense eigen-decomposition's eigenvalues, branch by branch, the same crossings and the same
//! Hopf point.

mod common;

use squeal_brake::sweep::{SweepMethod, SweepOptions, sweep};

#[test]
fn continuation_agrees_with_dense_eigen_decompositions() {
    let c = common::coarse();
    let mus = common::mus(0.0, 1.0, 101);
    let cont = common::options(c);
    let dense = SweepOptions {
        method: SweepMethod::Dense,
        ..cont
    };
    let sc = sweep(&c.model.brake, &c.reference, &mus, &cont).unwrap();
    let sd = sweep(&c.model.brake, &c.reference, &mus, &dense).unwrap();
    assert_eq!(sc.branches.len(), sd.branches.len());
    // Continuation converges each eigenpair to a residual at round-off relative to ||T(λ)||,
    // as backward stable as the dense solver: measured 3.4e-14 relative on this brake (the
    // sweep_table bench). 1e-9 leaves room for a conditioned pair near a coalescence; a
    // swapped branch or a lost eigenvalue is off by O(1).
    let mut worst = 0.0f64;
    for k in 0..mus.len() {
        for br in 0..sc.branches.len() {
            let (a, b) = (sc.value(br, k), sd.value(br, k));
            worst = worst.max((a - b).norm() / b.norm());
        }
    }
    eprintln!("largest relative eigenvalue difference: {worst:.2e}");
    assert!(worst < 1e-9, "{worst:e}");
    assert_eq!(sc.crossings.len(), sd.crossings.len());
    for (a, b) in sc.crossings.iter().zip(&sd.crossings) {
        assert_eq!((a.branch, a.k, a.in_band), (b.branch, b.k, b.in_band));
    }
    let (hc, hd) = (sc.hopf.unwrap(), sd.hopf.unwrap());
    // Both refine μ0 to a bracket of 1e-8 (SweepOptions::mu_tolerance).
    assert!((hc.mu0 - hd.mu0).abs() < 2e-8, "{} vs {}", hc.mu0, hd.mu0);
    assert!((hc.frequency_hz / hd.frequency_hz - 1.0).abs() < 1e-8);
}
