//! The library's second contact element, [`VelocityDependent`]: penalty contact with a friction
//! coefficient that falls with the sliding speed (Stribeck's velocity weakening),
//!
//! `μ(v) = μ (r + (1 - r)(1 - e^(-v/v0)))`,
//!
//! i.e. `μ_s + (μ_d - μ_s)(1 - e^(-v/v0))` with the swept friction level `μ = μ_d` (the
//! coefficient at high sliding speed) and `μ_s = r μ_d` at rest. The equilibrium, the
//! linearization (which gains a damping part, `∂F_t/∂v`), the sweep, the Hopf refinement,
//! harmonic balance and time integration all reach it through `ContactLaw`; it was written in
//! this file first and moved into `squeal_brake::contact::velocity_dependent` unchanged.
//!
//! The model has a closed-form answer. Two dofs of a pad on a rigid disc, `x0` tangential
//! (spring `k_t`, damper `c`) and `x1` normal (spring `k_n`), a pair with normal `+e1` and
//! sliding direction `-e0`, pressed by a load `L` of which the contact carries
//! `N = L k_l / (k_l + k_n)` (the rest goes through `k_n`), the disc surface moving at `V`. The friction force on dof 0 is
//! `-F_t = -μ(V - ẋ0) N` (`h = -e0`: the slip velocity is `V - ẋ0`), so linearized about the
//! equilibrium the tangential dof sees the extra damping `∂F_t/∂v · (h·h) = μ'(V) N`:
//! negative for a falling curve. The normal dof does not feel the tangential one, so the
//! tangential mode is unstable exactly when `c + μ'(V) N < 0`, with
//! `μ'(V) = -μ (1 - r) e^(-V/v0) / v0`: the Hopf point is
//!
//! `μ* = c v0 e^(V/v0) / ((1 - r) N)`, at the frequency `sqrt(k_t / m) / 2π`.

use faer::Mat;
use squeal_brake::contact::VelocityDependent;
use squeal_brake::equilibrium::{NewtonOptions, static_equilibrium};
use squeal_brake::modal::Damping;
use squeal_brake::spectrum::spectrum;
use squeal_brake::sweep::{Band, SweepOptions, reference, sweep};
use squeal_brake::{Brake, BrakeError, ContactPair};
use std::sync::Arc;

const M: f64 = 1.0;
const C: f64 = 4.0;
const KT: f64 = 4.0e6;
const KN: f64 = 1.0e7;
const LOAD: f64 = 500.0;
const RATIO: f64 = 1.6;
const V0: f64 = 0.5;

fn brake(speed: Option<f64>) -> Brake {
    let law = VelocityDependent {
        k_linear: KL,
        k_cubic: 0.0,
        static_ratio: RATIO,
        decay_speed: V0,
    };
    Brake {
        m: Mat::from_fn(2, 2, |i, j| if i == j { M } else { 0.0 }),
        k: Mat::from_fn(2, 2, |i, j| [[KT, 0.0], [0.0, KN]][i][j]),
        // The load presses the pad (dof 1, normal +e1) on the disc: along -n.
        f_piston: vec![0.0, -LOAD],
        c: None,
        k_vibration: None,
        pairs: vec![ContactPair {
            disc_point: 0,
            pad_point: 0,
            position: [0.0; 3],
            normal_direction: [0.0, 1.0, 0.0],
            sliding_direction: [-1.0, 0.0, 0.0],
            // The "disc" is ground: only the pad's dofs appear, with the pad's signs.
            normal: vec![(1, -1.0)],
            tangent: vec![(0, 1.0)],
            initial_gap: 0.0,
            surface_speed: speed,
            law: Arc::new(law),
        }],
    }
}

const KL: f64 = 2.0e7;

/// The contact's share of the load at equilibrium.
fn normal_force() -> f64 {
    LOAD * KL / (KL + KN)
}

/// `μ*` of the module documentation.
fn closed_form(speed: f64) -> f64 {
    C * V0 * (speed / V0).exp() / ((RATIO - 1.0).abs() * normal_force())
}

#[test]
fn a_law_that_needs_the_disc_speed_says_so() {
    let b = brake(None);
    assert!(matches!(
        b.validate(),
        Err(BrakeError::NoSurfaceSpeed { pair: 1, .. })
    ));
    let damping = Damping {
        global_ratio: 0.0,
        extra: vec![],
    };
    let reference = reference(&brake(Some(1.0)), &damping, &NewtonOptions::default()).unwrap();
    let e = sweep(&b, &reference, &[0.0, 0.1], &SweepOptions::default());
    assert!(
        matches!(e, Err(BrakeError::NoSurfaceSpeed { pair: 1, .. })),
        "{e:?}"
    );
}

#[test]
fn velocity_weakening_friction_destabilizes_at_the_closed_form_threshold() {
    // μ_s > μ_d (RATIO > 1) is a falling curve; at V = 0.4 m/s the threshold is
    // μ* = 4 · 0.5 · e^0.8 / (0.6 · 333.3) = 0.02226.
    for speed in [0.4, 0.8] {
        let b = brake(Some(speed));
        let damping = Damping {
            global_ratio: 0.0,
            extra: vec![(0, C / M), (1, C / M)],
        };
        let r = reference(&b, &damping, &NewtonOptions::default()).unwrap();
        let exact = closed_form(speed);
        let mus: Vec<f64> = (0..=40).map(|k| 2.0 * exact * k as f64 / 40.0).collect();
        let opts = {
            let mut o = SweepOptions::default();
            o.band = Band {
                valid_max_hz: f64::INFINITY,
                user: None,
            };
            o.mu_tolerance = 1e-12 * exact;
            o
        };
        let s = sweep(&b, &r, &mus, &opts).unwrap();
        let h = s.hopf.as_ref().expect("a Hopf point below 2 mu*");
        // The Hopf refinement follows Re λ(μ), whose derivative comes from the element's
        // responses by central differences along the equilibrium path (exact here: F_t is
        // linear in μ and the normal force does not depend on it). The bracket closes to
        // 1e-12 μ*; the instability threshold (64 ε ω_max) shifts the root by ~1e-14.
        assert!(
            (h.mu0 / exact - 1.0).abs() < 1e-9,
            "V = {speed}: mu0 {} vs {exact}",
            h.mu0
        );
        // The damping of the tangential mode vanishes there: λ = i sqrt(k_t / m).
        let f = (KT / M).sqrt() / (2.0 * std::f64::consts::PI);
        assert!(
            (h.frequency_hz / f - 1.0).abs() < 1e-9,
            "{} vs {f}",
            h.frequency_hz
        );
        // Above μ* the tangential mode grows at Re λ = -(c + μ'(V) N) / 2m.
        let eq = static_equilibrium(&b, 1.5 * exact, None, &NewtonOptions::default()).unwrap();
        let sp = spectrum(&b, &r, &eq).unwrap();
        let growth = sp
            .values
            .iter()
            .map(|v| v.re)
            .fold(f64::NEG_INFINITY, f64::max);
        let slope = 1.5 * exact * (RATIO - 1.0) * (-speed / V0).exp() / V0;
        let expected = -(C - slope * normal_force()) / (2.0 * M);
        // A dense eigensolver on a 4×4 state matrix: ~1e-12 of ω_max absolute.
        assert!(
            (growth - expected).abs() < 1e-9 * (KN / M).sqrt(),
            "growth {growth} vs {expected}"
        );
    }
}
