//! The projected sweep's Hopf refinement by Rayleigh iteration on the two followed eigenpairs
//! (squeal-brake's `projected_hopf`, the default) against the former one with a whole dense
//! eigen-decomposition at each evaluation (the reference: it sees every eigenvalue), on the
//! coarse bundled brake projected (158 dofs; its projection keeps 105 modes + 18 vectors).

use super::common;

use squeal_brake::sweep::{SweepMethod, sweep};

#[test]
fn rayleigh_refinement_gives_the_whole_decompositions_hopf_point() {
    let c = common::coarse();
    let mus = common::mus(0.0, 1.0, 101);
    let mut whole = common::options(c);
    whole.method = SweepMethod::Projected;
    whole.projection.rayleigh_refinement = false;
    let mut first = whole;
    first.projection.rayleigh_refinement = true;
    let sw = sweep(&c.model.brake, &c.reference, &mus, &whole).unwrap();
    let sf = sweep(&c.model.brake, &c.reference, &mus, &first).unwrap();
    // The sweep points do not depend on how the Hopf point is refined: same bits.
    for (k, (a, b)) in sf.points.iter().zip(&sw.points).enumerate() {
        assert_eq!(a.spectrum.values, b.spectrum.values, "point {k}");
    }
    assert_eq!(sf.branches, sw.branches);
    let (hf, hw) = (sf.hopf.unwrap(), sw.hopf.unwrap());
    eprintln!(
        "mu0 {} vs {} ({} vs {} evaluations), {} vs {} Hz",
        hf.mu0, hw.mu0, hf.evaluations, hw.evaluations, hf.frequency_hz, hw.frequency_hz
    );
    // Same branches followed, same mode at the end.
    assert_eq!((hf.branch, hf.partner), (hw.branch, hw.partner));
    assert_eq!(hf.index, hw.index);
    // Rayleigh iteration stops at a residual of round-off (1e3 ε ‖H‖), as backward stable as
    // the dense solver, so the real parts differ by round-off (about ε ω_max / |dRe λ/dμ| in
    // μ, far below the 1e-8 bracket): regula falsi takes the same steps up to round-off and
    // both brackets close on the same root, μ0 within the bracket width 1e-8
    // (SweepOptions::mu_tolerance); a different followed eigenvalue would move it by O(Δμ). The frequency at the bracket's upper
    // end moves with μ by |dω/dμ| 1e-8 at most, ~1e-4 rad/s on 2.6e4: 1e-8 relative.
    assert!((hf.mu0 - hw.mu0).abs() < 1e-8, "{} vs {}", hf.mu0, hw.mu0);
    assert!((hf.frequency_hz / hw.frequency_hz - 1.0).abs() < 1e-8);
    assert_eq!(
        hf.point.spectrum.values.len(),
        hw.point.spectrum.values.len()
    );
    eprintln!(
        "whole decompositions in the refinement: {} of {}",
        sf.stats.refinement_whole, hf.evaluations
    );
    // The Hopf point's spectrum is whole again (every mode's shape, unit norm).
    let sp = &hf.point.spectrum;
    for j in 0..sp.values.len() {
        let norm: f64 = (0..sp.modes.nrows())
            .map(|i| sp.modes[(i, j)].norm_sqr())
            .sum();
        assert!((norm - 1.0).abs() < 1e-12, "mode {j}: {norm}");
    }
}
