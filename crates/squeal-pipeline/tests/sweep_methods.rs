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

#[test]
fn the_sweep_to_the_hopf_point_is_the_whole_sweeps_beginning() {
    // `sweep_to_hopf` (the preliminary sweep that names the coalescing pair) must stop right
    // after the first in-band crossing with the same points, bit for bit, and the same Hopf
    // point and partner as the whole sweep: it runs the same continuation and only stops.
    use squeal_brake::sweep::sweep_to_hopf;
    let c = common::coarse();
    let mus = common::mus(0.0, 1.0, 101);
    let opts = common::options(c);
    let whole = sweep(&c.model.brake, &c.reference, &mus, &opts).unwrap();
    let early = sweep_to_hopf(&c.model.brake, &c.reference, &mus, &opts).unwrap();
    let first = whole.crossings.iter().find(|x| x.in_band).unwrap();
    assert_eq!(
        early.points.len(),
        first.k + 2,
        "ends at the point after the crossing"
    );
    for (k, (a, b)) in early.points.iter().zip(&whole.points).enumerate() {
        assert_eq!(a.spectrum.values, b.spectrum.values, "point {k}");
    }
    let (he, hw) = (early.hopf.unwrap(), whole.hopf.unwrap());
    assert_eq!(he.mu0.to_bits(), hw.mu0.to_bits());
    assert_eq!((he.branch, he.partner), (hw.branch, hw.partner));
}
