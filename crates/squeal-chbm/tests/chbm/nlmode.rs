//! The nonlinear mode (extended periodic motion concept, `squeal_chbm::nlmode`) on the 2-dof
//! oscillator's variants of `tests/chbm/common`: the criticality read from ζ(a) against the
//! Lyapunov coefficient on the subcritical variant (the supercritical one is in
//! `examples/nonlinear_mode.rs`), and the small-amplitude limit against the dense linear mode
//! when the damping is not mass-proportional (where it is not the eigenvalue itself).

use super::common;

use common::{normal_form_of, start, subcritical};
use squeal_brake::criticality::Criticality;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::nlmode::{NlModeOptions, nonlinear_mode};

#[test]
fn the_subcritical_oscillator_reads_subcritical() {
    // l1 = +8.4 (tests/chbm/common): ζ must fall with the amplitude above μ0. The first two
    // points (1e-2 and 2e-2 of the opening amplitude) resolve ζ2 a² ~ 1e-7 against LM's
    // ~1e-10 on ζ.
    let m = subcritical();
    let nf = normal_form_of(&m);
    assert_eq!(nf.criticality(), Criticality::Subcritical);
    let mu = 1.01 * nf.mu0;
    let start = start(&m, mu);
    let mb = ModalBrake::new(&m.brake, &m.reference, mu);
    let opts = {
        let mut o = NlModeOptions::default();
        o.amplitudes = vec![1e-2, 2e-2, 4e-2];
        o
    };
    let mode = nonlinear_mode(&mb, &start, &opts).unwrap();
    assert_eq!(mode.points.len(), 3);
    assert!(mode.zeta2().unwrap() < 0.0);
    assert_eq!(mode.criticality(), nf.criticality());
}

#[test]
fn with_non_proportional_damping_the_small_amplitude_limit_is_the_linear_mode() {
    // C = [[20, 5], [5, 60]]: the continuation at 1e-5 of the opening amplitude (the cubic
    // share ~1e-12) against the dense fixed point of `nlmode::linear` to LM's ~1e-10; the
    // eigenvalue's κ = -λ(λ + c) no longer applies (no single c), and the module documents the
    // O(ζ |D| / ω) gap.
    use squeal_chbm::{Contact, FrictionSystem};
    let c = faer::Mat::from_fn(2, 2, |i, j| [[20.0, 5.0], [5.0, 60.0]][i][j]);
    let k = faer::Mat::from_fn(2, 2, |i, j| [[1.0e6, 1.0e5], [1.0e5, 1.0e6]][i][j]);
    let pair = Contact::penalty_coulomb(&[(1, 1.0)], &[(0, -1.0)], 3.0e5, 7.5e11);
    let sys = FrictionSystem::builder(faer::Mat::identity(2, 2), c, k)
        .contact(pair.initial_gap(-2.0e-4))
        .build()
        .unwrap();
    let mu0 = sys.hopf().unwrap().mu0;
    let opts = {
        let mut o = NlModeOptions::default();
        o.amplitudes = vec![1e-5, 2e-5];
        o
    };
    let mode = sys.nonlinear_mode(1.02 * mu0, &opts).unwrap();
    for p in &mode.points {
        assert!((p.omega / mode.linear.omega - 1.0).abs() < 1e-8);
        assert!((p.zeta - mode.linear.zeta).abs() < 1e-9);
    }
}
