//! The sweep's redo when the Hopf refinement loses its mode (`squeal_brake::sweep::RESWEEPS`,
//! `SweepStats::resweeps`), on a 4-dof brake small enough to check by hand.
//!
//! **The brake.** Dofs 0 and 1 are the 2-dof mode-coupling model of `two_dof.rs` (unit masses,
//! `K = [[k11, k12 − μ kH], [k12, k22]]` with the contact pair's normal on dof 1 and its
//! friction on dof 0); dofs 2 and 3 are two oscillators of their own (`ω_z1²`, `ω_z2²` on the
//! diagonal, no coupling, no contact): their modes never move with μ and never mix with the
//! pair. Every mode gets the same modal damping `d` (s⁻¹), so `C = d I` and the pair's Hopf
//! point is the 2-dof closed form
//!
//! `μ_c = [(k11 − k22)² + 4 k12² + 2 d² (k11 + k22)] / (4 kH k12)`, at `ω² = (k11 + k22)/2`,
//!
//! untouched by the two oscillators (the characteristic polynomial factors).
//!
//! **The lost mode.** With `k11 = 1e6`, `k12 = 1e5`, `k22 = 1.2e6`, `kH = 2e5`, `d = 10`, the
//! pair's frequencies at μ = 0.5 are 1000 and 1095 rad/s, and past the coalescence (μ = 1) they
//! meet at 1049 rad/s and split in real part. The oscillators sit next to each at 0.5: 1005 and
//! 1090 rad/s. Sweeping 0, 0.5, 1.5, 2, the crossing lies in [0.5, 1.5]: the branches are
//! matched as a whole (an assignment: each oscillator to itself, the pair to the pair), but the
//! refinement follows each of the pair's modes from 0.5 on its own by the same cost (1 − MAC +
//! the eigenvalue distance over 5 % of |λ|, the latter capped at 1): a pair mode that moved by
//! more than 5 % and changed its shape costs more than an oscillator 0.5 % away with an
//! orthogonal shape, so both followed modes land on the oscillators, stable at both ends of the
//! bracket, and the refinement ends with `HopfNotResolved`. The sweep is then redone with seven
//! values inserted into [0.5, 1.5], where the steps are short enough for the pair to be
//! followed, and gives the closed form's μ_c.

use faer::Mat;
use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::modal::Damping;
use squeal_brake::sweep::{SweepMethod, SweepOptions, reference, sweep};
use squeal_brake::{Brake, ContactPair, PenaltyCoulomb};
use std::sync::Arc;

const K11: f64 = 1.0e6;
const K12: f64 = 1.0e5;
const K22: f64 = 1.2e6;
const KH: f64 = 2.0e5;
/// The modal damping of every mode (s⁻¹).
const D: f64 = 10.0;

/// The 4-dof brake of the module docs, the oscillators at `wz` (rad/s).
fn brake(wz: [f64; 2]) -> Brake {
    let m = Mat::from_fn(4, 4, |i, j| if i == j { 1.0 } else { 0.0 });
    let k = Mat::from_fn(4, 4, |i, j| match (i, j) {
        (0, 0) => K11,
        (0, 1) | (1, 0) => K12,
        // The contact's normal spring kH completes K22.
        (1, 1) => K22 - KH,
        (2, 2) => wz[0] * wz[0],
        (3, 3) => wz[1] * wz[1],
        _ => 0.0,
    });
    let pair = ContactPair {
        disc_point: 0,
        pad_point: 0,
        position: [0.0; 3],
        normal_direction: [0.0, 1.0, 0.0],
        sliding_direction: [-1.0, 0.0, 0.0],
        normal: vec![(1, 1.0)],
        tangent: vec![(0, -1.0)],
        // An initial interference keeps the contact closed at every μ.
        initial_gap: -1e-3,
        surface_speed: None,
        law: Arc::new(PenaltyCoulomb {
            k_linear: KH,
            k_cubic: 0.0,
        }),
    };
    Brake {
        m,
        k,
        f_piston: vec![0.0; 4],
        c: None,
        k_vibration: None,
        pairs: vec![pair],
    }
}

/// The closed-form Hopf point of the pair (module docs).
fn mu_c() -> f64 {
    ((K11 - K22).powi(2) + 4.0 * K12 * K12 + 2.0 * D * D * (K11 + K22)) / (4.0 * KH * K12)
}

/// The sweep of `mus` with `method` on the brake with oscillators at `wz`.
fn swept(
    wz: [f64; 2],
    mus: &[f64],
    method: SweepMethod,
) -> Result<squeal_brake::sweep::Sweep, squeal_brake::BrakeError> {
    let b = brake(wz);
    let damping = Damping {
        global_ratio: 0.0,
        extra: (0..4).map(|j| (j, D)).collect(),
    };
    let r = reference(&b, &damping, &NewtonOptions::default()).expect("reference");
    let mut o = SweepOptions::default();
    o.method = method;
    sweep(&b, &r, mus, &o)
}

#[test]
fn a_refinement_that_loses_its_mode_is_redone_and_finds_the_closed_form_onset() {
    let exact = mu_c();
    let f_exact = ((K11 + K22) / 2.0).sqrt() / std::f64::consts::TAU;
    for method in [SweepMethod::Dense, SweepMethod::Continuation] {
        let s = swept([1005.0, 1090.0], &[0.0, 0.5, 1.5, 2.0], method)
            .unwrap_or_else(|e| panic!("{method:?}: {e}"));
        // Measured: redone once (Dense and Continuation alike), 11 friction values.
        assert_eq!(s.stats.resweeps, 1, "{method:?}");
        assert_eq!(s.points.len(), 11, "{method:?}");
        let h = s.hopf.as_ref().expect("a Hopf point");
        // The bracket is closed to the sweep's mu_tolerance (1e-8, absolute) and μ0 is its
        // middle; the instability threshold 64 ε ω_max moves the root by ~1e-13. Measured
        // -4.78e-9 (Dense and Continuation).
        assert!(
            (h.mu0 - exact).abs() < 1e-8,
            "{method:?}: mu0 {} against the closed form {exact} ({:+e})",
            h.mu0,
            h.mu0 - exact
        );
        // At the Hopf point of C = d I the frequency is sqrt((k11 + k22)/2) exactly; the
        // bracket's width moves it by ~1e-9 relative.
        assert!(
            (h.frequency_hz / f_exact - 1.0).abs() < 1e-7,
            "{method:?}: {} Hz against {f_exact} Hz",
            h.frequency_hz
        );
    }
}

#[test]
fn without_the_oscillators_next_to_the_pair_the_same_sweep_is_not_redone() {
    // The control: the oscillators far from the pair (500 and 2000 rad/s), the same friction
    // values: the refinement follows the pair in the coarse bracket, no redo, the same onset.
    let exact = mu_c();
    let s = swept([500.0, 2000.0], &[0.0, 0.5, 1.5, 2.0], SweepMethod::Dense).expect("sweep");
    assert_eq!(s.stats.resweeps, 0);
    let h = s.hopf.as_ref().expect("a Hopf point");
    assert!((h.mu0 - exact).abs() < 1e-8, "{} vs {exact}", h.mu0);
}
