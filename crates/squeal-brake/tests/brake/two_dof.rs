//! A 2-dof mode-coupling model built through the brake's own code paths (contact pair,
//! equilibrium, modal damping, spectrum, sweep, Hopf refinement) against the closed-form
//! flutter threshold of `M = m I`, `C = c I`, `K = [[k11, k12 - μ kH], [k21, k22]]`:
//!
//! `μ_c = [(k11 - k22)² + 4 k12 k21 + 2 c² (k11 + k22) / m] / (4 kH k21)`,
//!
//! at frequency `ω² = (k11 + k22) / (2m)` (from `det(m λ² + c λ + K) = 0` with `λ = iω`).

use faer::Mat;
use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::modal::Damping;
use squeal_brake::sweep::{SweepOptions, reference, sweep};
use squeal_brake::{Brake, ContactPair, ModalDamping, PenaltyCoulomb};
use std::sync::Arc;

struct Case {
    m: f64,
    c: f64,
    k11: f64,
    k12: f64,
    k22: f64,
    kh: f64,
}

impl Case {
    fn mu_c(&self) -> f64 {
        let (k11, k12, k21, k22) = (self.k11, self.k12, self.k12, self.k22);
        ((k11 - k22).powi(2) + 4.0 * k12 * k21 + 2.0 * self.c.powi(2) * (k11 + k22) / self.m)
            / (4.0 * self.kh * k21)
    }

    /// dof 0 is the "tangential" dof, dof 1 the "normal" one: the pair's normal `g = e1` adds
    /// `kH` to K[1][1] (so the linear part carries `k22 - kH`), and friction along `h = -e0`
    /// adds `-μ kH` to K[0][1]. An initial interference keeps the contact closed.
    fn brake(&self) -> Brake {
        let m = Mat::from_fn(2, 2, |i, j| if i == j { self.m } else { 0.0 });
        let k = Mat::from_fn(2, 2, |i, j| {
            [[self.k11, self.k12], [self.k12, self.k22 - self.kh]][i][j]
        });
        let pair = ContactPair {
            disc_point: 0,
            pad_point: 0,
            position: [0.0; 3],
            normal_direction: [0.0, 1.0, 0.0],
            sliding_direction: [-1.0, 0.0, 0.0],
            normal: vec![(1, 1.0)],
            tangent: vec![(0, -1.0)],
            initial_gap: -1e-3,
            surface_speed: None,
            law: Arc::new(PenaltyCoulomb {
                k_linear: self.kh,
                k_cubic: 0.0,
            }),
        };
        Brake {
            m,
            k,
            f_piston: vec![0.0, 0.0],
            c: None,
            k_vibration: None,
            pairs: vec![pair],
        }
    }
}

/// Sweeps 0..2 μc and returns (μ0, frequency) of the refined Hopf point.
fn hopf(case: &Case) -> (f64, f64) {
    let brake = case.brake();
    let d = case.c / case.m;
    let damping = Damping {
        global_ratio: 0.0,
        extra: vec![(0, d), (1, d)],
    };
    let newton = NewtonOptions::default();
    let reference = reference(&brake, &damping, &newton).unwrap();
    let exact = case.mu_c();
    let mus: Vec<f64> = (0..=40).map(|k| 2.0 * exact * k as f64 / 40.0).collect();
    let opts = {
        let mut o = SweepOptions::default();
        o.mu_tolerance = 1e-13 * exact;
        o
    };
    let s = sweep(&brake, &reference, &mus, &opts).unwrap();
    for p in &s.points {
        assert!(p.equilibrium.penetrations[0] > 0.0, "contact opened");
    }
    let h = s.hopf.as_ref().expect("no Hopf point found");
    (h.mu0, h.frequency_hz)
}

#[test]
fn hopf_point_matches_the_closed_form_flutter_threshold() {
    let cases = [
        Case {
            m: 1.0,
            c: 50.0,
            k11: 1.0e6,
            k12: 1.0e5,
            k22: 1.2e6,
            kh: 2.0e5,
        },
        Case {
            m: 0.3,
            c: 12.0,
            k11: 4.0e6,
            k12: 3.0e5,
            k22: 3.1e6,
            kh: 9.0e5,
        },
        Case {
            m: 2.0,
            c: 150.0,
            k11: 7.0e6,
            k12: -4.0e5,
            k22: 8.0e6,
            kh: -1.5e6,
        },
    ];
    for (n, case) in cases.iter().enumerate() {
        let exact = case.mu_c();
        let (mu0, f0) = hopf(case);
        // Damped: the two eigenvalues are apart at the Hopf point (the coalescence came
        // earlier), so Re λ(μ) is smooth and computed to ~ε ω there; the bracket is closed to
        // 1e-13 μc and the instability threshold (64 ε ω_max) shifts the root by ~1e-13.
        assert!(
            (mu0 / exact - 1.0).abs() < 1e-10,
            "case {n}: mu0 {mu0} vs {exact} ({:e})",
            mu0 / exact - 1.0
        );
        let f = ((case.k11 + case.k22) / (2.0 * case.m)).sqrt() / (2.0 * std::f64::consts::PI);
        assert!((f0 / f - 1.0).abs() < 1e-9, "case {n}: f {f0} vs {f}");
    }
}

#[test]
fn undamped_hopf_point_is_the_coalescence() {
    // Without damping the Hopf point is the coalescence itself: an exceptional point, where the
    // eigenvalue is defective and any eigensolver's error grows like ε ||A|| / (separation of
    // the pair). Just below μc the pair is 134 sqrt(μc - μ) rad/s apart, so round-off shows up
    // as a spurious real part ~1e-9 s⁻¹ within a few 1e-6 of μc. The refinement follows the
    // larger real part of the two coalescing eigenvalues (either may carry the instability),
    // so the larger of two such errors counts: measured 5.5e-6 relative, asserted 1e-5.
    let case = Case {
        m: 1.0,
        c: 0.0,
        k11: 1.0e6,
        k12: 1.0e5,
        k22: 1.2e6,
        kh: 2.0e5,
    };
    let (mu0, f0) = hopf(&case);
    assert!(
        (mu0 / case.mu_c() - 1.0).abs() < 1e-5,
        "mu0 {mu0} vs {}",
        case.mu_c()
    );
    let f = ((case.k11 + case.k22) / 2.0f64).sqrt() / (2.0 * std::f64::consts::PI);
    // Within Δμ of the coalescence the pair's frequencies differ by ±67 sqrt(Δμ) rad/s: with
    // Δμ up to 1e-5 that is up to 2e-4 of the frequency (measured 1.5e-4).
    assert!((f0 / f - 1.0).abs() < 3e-4, "f {f0} vs {f}");
}

#[test]
fn frictionless_undamped_spectrum_is_imaginary() {
    let case = Case {
        m: 1.0,
        c: 0.0,
        k11: 1.0e6,
        k12: 1.0e5,
        k22: 1.2e6,
        kh: 2.0e5,
    };
    let brake = case.brake();
    let reference = reference(&brake, &Damping::default(), &NewtonOptions::default()).unwrap();
    let s = sweep(&brake, &reference, &[0.0], &SweepOptions::default()).unwrap();
    for l in &s.points[0].spectrum.values {
        // Round-off of a backward-stable eigensolver on a matrix of norm ~ω.
        assert!(l.re.abs() < 1e-12 * l.im, "{l:?}");
    }
}

#[test]
fn a_full_modal_damping_matrix_gives_the_routh_hurwitz_threshold() {
    // Physical damping C = [[c1, c12], [c12, c2]] is not diagonal in the modes of K_t0: the
    // modal damping D = Φᵀ C Φ is a full matrix, and the sweep takes the dense path. Its Hopf
    // point against the Routh-Hurwitz condition of det(λ² I + λ C + K_t(μ)) = 0,
    // a4 λ⁴ + a3 λ³ + a2 λ² + a1 λ + a0, which crosses when
    // Δ3 = a3 a2 a1 - a1² a4 - a3² a0 = 0, at ω² = a1 / a3 (independent of every eigensolver).
    let case = Case {
        m: 1.0,
        c: 0.0,
        k11: 1.0e6,
        k12: 1.0e5,
        k22: 1.2e6,
        kh: 2.0e5,
    };
    let (c1, c2, c12) = (30.0, 80.0, 10.0);
    let brake = case.brake();
    let mut r = reference(&brake, &Damping::default(), &NewtonOptions::default()).unwrap();
    let phi = &r.basis.phi;
    let c = faer::Mat::from_fn(2, 2, |i, j| [[c1, c12], [c12, c2]][i][j]);
    let d = phi.transpose() * &c * phi;
    assert!(
        d[(0, 1)].abs() > 1.0,
        "the modal damping must be full: {d:?}"
    );
    r.damping = ModalDamping::Full(d);
    // Routh-Hurwitz on the physical coefficients (K_t: k11, k12 - μ kH; k12, k22).
    let delta3 = |mu: f64| {
        let (k00, k01, k10, k11) = (case.k11, case.k12 - mu * case.kh, case.k12, case.k22);
        let a3 = c1 + c2;
        let a2 = k00 + k11 + c1 * c2 - c12 * c12;
        let a1 = c1 * k11 + c2 * k00 - c12 * (k01 + k10);
        let a0 = k00 * k11 - k01 * k10;
        (a3 * a2 * a1 - a1 * a1 - a3 * a3 * a0, a1 / a3)
    };
    let (mut lo, mut hi) = (0.0, 2.0);
    assert!(delta3(lo).0 > 0.0 && delta3(hi).0 < 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if delta3(mid).0 > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let exact = 0.5 * (lo + hi);
    let mus: Vec<f64> = (0..=40).map(|k| 2.0 * exact * k as f64 / 40.0).collect();
    let opts = {
        let mut o = SweepOptions::default();
        o.mu_tolerance = 1e-13 * exact;
        o
    };
    let s = sweep(&brake, &r, &mus, &opts).unwrap();
    let h = s.hopf.as_ref().expect("no Hopf point");
    // Dense state-matrix eigenvalues (backward stable, ~ε ω) and a bracket of 1e-13 μ*: the
    // threshold shifts the root by ~1e-13; asserted 1e-10.
    assert!((h.mu0 / exact - 1.0).abs() < 1e-10, "{} vs {exact}", h.mu0);
    let f = delta3(exact).1.sqrt() / (2.0 * std::f64::consts::PI);
    assert!(
        (h.frequency_hz / f - 1.0).abs() < 1e-9,
        "{} vs {f}",
        h.frequency_hz
    );
    // The continuation was not used: it needs a diagonal D.
    assert_eq!(s.stats.continued, 0);
}
