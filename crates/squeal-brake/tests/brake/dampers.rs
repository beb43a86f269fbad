//! The brake's physical damping matrix `Brake::c` (the dampers of `[[dampers]]`, projected by
//! the parts' bases) through the brake's own code paths: `sweep::reference` adds `Φᵀ C Φ` to the
//! modal damping once, and the spectrum, the sweep and the Hopf point see it.
//!
//! - One dof on a spring and a dashpot: `λ = −c/(2m) ± i √(k/m − c²/(4m²))`, with and without a
//!   modal damping ratio beside it.
//! - Small dampers on a 3-dof chain: `Re Δλ_j = −½ φ_jᵀ C φ_j` to first order (mass-normalized
//!   modes), the remainder shrinking as `|C|²`.
//! - A 2-dof mode-coupling brake with `C` full in the modes: its Hopf point against the
//!   Routh–Hurwitz condition of `det(λ² I + λ C + K_t(μ)) = 0`.

use faer::{Mat, c64};
use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::modal::Damping;
use squeal_brake::spectrum::spectrum;
use squeal_brake::sweep::{SweepOptions, reference, sweep};
use squeal_brake::{Brake, ContactPair, PenaltyCoulomb};
use std::sync::Arc;

/// The contact stiffness on dof 0 (N/m).
const KH: f64 = 5.0e5;

/// A brake of stiffness `k` (contact included), mass `m`, dampers `c`: one contact pair on dof
/// 0, closed by an interference, carries `KH` of `k[(0, 0)]` (the reference needs a closed
/// contact); at μ = 0 it is a linear spring.
fn linear(m: Mat<f64>, k: Mat<f64>, c: Option<Mat<f64>>) -> Brake {
    let n = m.nrows();
    let pair = ContactPair {
        disc_point: 0,
        pad_point: 0,
        position: [0.0; 3],
        normal_direction: [0.0, 0.0, 1.0],
        sliding_direction: [1.0, 0.0, 0.0],
        normal: vec![(0, 1.0)],
        tangent: vec![(0, 1.0)],
        initial_gap: -1e-3,
        surface_speed: None,
        law: Arc::new(PenaltyCoulomb {
            k_linear: KH,
            k_cubic: 0.0,
        }),
    };
    let mut k = k;
    k[(0, 0)] -= KH;
    Brake {
        m,
        k,
        f_piston: vec![0.0; n],
        c,
        k_vibration: None,
        pairs: vec![pair],
    }
}

/// The eigenvalues with `Im λ >= 0` of the brake at rest, with the modal damping `damping`.
fn eigenvalues(brake: &Brake, damping: &Damping) -> Vec<c64> {
    let r = reference(brake, damping, &NewtonOptions::default()).unwrap();
    spectrum(brake, &r, &r.equilibrium).unwrap().values
}

#[test]
fn one_dof_on_a_spring_and_a_dashpot_has_the_closed_form_eigenvalue() {
    let (m, k): (f64, f64) = (0.7, 3.0e6); // k: spring and contact together
    let w = (k / m).sqrt();
    for (zeta, modal) in [(0.05f64, 0.0f64), (0.3, 0.0), (0.05, 0.02)] {
        let c = 2.0 * zeta * (k * m).sqrt();
        let brake = linear(
            Mat::from_fn(1, 1, |_, _| m),
            Mat::from_fn(1, 1, |_, _| k),
            Some(Mat::from_fn(1, 1, |_, _| c)),
        );
        let damping = Damping {
            global_ratio: modal,
            extra: vec![],
        };
        let l = eigenvalues(&brake, &damping)[0];
        // The modal ratio adds 2 ζ_m ω to D = c/m: the ratios add.
        let z = zeta + modal;
        let exact = c64::new(-z * w, w * (1.0 - z * z).sqrt());
        // A 2 x 2 state matrix scaled by ω: eigenvalues to a few ε |λ|.
        assert!(
            (l - exact).norm() < 1e-13 * exact.norm(),
            "zeta {zeta} + {modal}: {l} vs {exact}"
        );
    }
}

/// A 3-mass chain, grounded at both ends: masses 1, 2, 1.5 kg, springs 1e6, 2e6, 1.5e6, 3e6 N/m.
fn chain() -> (Mat<f64>, Mat<f64>) {
    let m = Mat::from_fn(3, 3, |i, j| if i == j { [1.0, 2.0, 1.5][i] } else { 0.0 });
    let s = [1.0e6, 2.0e6, 1.5e6, 3.0e6];
    let k = Mat::from_fn(3, 3, |i, j| {
        if i == j {
            s[i] + s[i + 1]
        } else if i.abs_diff(j) == 1 {
            -s[i.max(j)]
        } else {
            0.0
        }
    });
    (m, k)
}

/// A damper `c1` between masses 1 and 3 and `c2` from mass 2 to ground.
fn dashpots(scale: f64) -> Mat<f64> {
    let (c1, c2) = (4.0 * scale, 2.5 * scale);
    Mat::from_fn(3, 3, |i, j| match (i, j) {
        (0, 0) | (2, 2) => c1,
        (0, 2) | (2, 0) => -c1,
        (1, 1) => c2,
        _ => 0.0,
    })
}

#[test]
fn small_dampers_move_each_eigenvalue_by_half_phi_c_phi() {
    let (m, k) = chain();
    let undamped = reference(
        &linear(m.clone(), k.clone(), None),
        &Damping::default(),
        &NewtonOptions::default(),
    )
    .unwrap();
    let phi = &undamped.basis.phi;
    let mut errors = Vec::new();
    for scale in [1.0, 0.5] {
        let c = dashpots(scale);
        let values = eigenvalues(
            &linear(m.clone(), k.clone(), Some(c.clone())),
            &Damping::default(),
        );
        let mut worst: f64 = 0.0;
        for (j, l) in values.iter().enumerate() {
            let pj = phi.col(j);
            let first: f64 = (0..3)
                .flat_map(|a| (0..3).map(move |b| (a, b)))
                .map(|(a, b)| pj[a] * c[(a, b)] * pj[b])
                .sum::<f64>()
                * -0.5;
            let w = undamped.basis.omega[j];
            // Re λ moves at first order; Im λ at second only, by terms ~ D_jk² / (ω_j Δω)
            // with |D| ~ 1 1/s and modes ~1e3 rad/s apart (measured 1.3e-6 of ω; asserted
            // 1e-5).
            assert!(
                (l.re / first - 1.0).abs() < 1e-3 && (l.im / w - 1.0).abs() < 1e-5,
                "mode {j}: {l} against first order {first} and omega {w}"
            );
            worst = worst.max((l.re - first).abs() / first.abs());
        }
        errors.push(worst);
    }
    // The second-order term of λ_j, −λ_j Σ_k D_jk² / (2 (ω_k² − ω_j²)), is imaginary (λ_j =
    // i ω_j at zeroth order): Re λ's remainder is third order, so relative to Re Δλ = O(|C|)
    // it is O(|C|²) and falls to a quarter when C is halved (asserted 0.2..0.3: higher orders
    // move it by O(|C|) of itself).
    let ratio = errors[1] / errors[0];
    eprintln!(
        "first-order remainder {:.3e}, {:.3e} (ratio {ratio:.4})",
        errors[0], errors[1]
    );
    assert!((0.2..0.3).contains(&ratio), "{errors:?}");
}

#[test]
fn a_physical_damping_matrix_gives_the_routh_hurwitz_threshold() {
    // The 2-dof mode-coupling brake of tests/brake/two_dof.rs (M = I, K_t = [[k11, k12 - μ kH],
    // [k12, k22]]) with C = [[c1, c12], [c12, c2]] on the brake: D = Φᵀ C Φ, full, formed by
    // the reference itself.
    let (k11, k12, k22, kh) = (1.0e6, 1.0e5, 1.2e6, 2.0e5);
    let (c1, c2, c12) = (30.0, 80.0, 10.0);
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
            k_linear: kh,
            k_cubic: 0.0,
        }),
    };
    let brake = Brake {
        m: Mat::identity(2, 2),
        k: Mat::from_fn(2, 2, |i, j| [[k11, k12], [k12, k22 - kh]][i][j]),
        f_piston: vec![0.0; 2],
        c: Some(Mat::from_fn(2, 2, |i, j| [[c1, c12], [c12, c2]][i][j])),
        k_vibration: None,
        pairs: vec![pair],
    };
    let r = reference(&brake, &Damping::default(), &NewtonOptions::default()).unwrap();
    assert!(r.damping.diagonal().is_none() && r.damping.entry(0, 1).abs() > 1.0);
    let delta3 = |mu: f64| {
        let (k00, k01, k10, k11) = (k11, k12 - mu * kh, k12, k22);
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
    // As tests/brake/two_dof.rs with the same D set by hand: dense eigenvalues to ~ε ω, a bracket of
    // 1e-13 μ*; asserted 1e-10.
    assert!((h.mu0 / exact - 1.0).abs() < 1e-10, "{} vs {exact}", h.mu0);
    let f = delta3(exact).1.sqrt() / (2.0 * std::f64::consts::PI);
    assert!(
        (h.frequency_hz / f - 1.0).abs() < 1e-9,
        "{} vs {f}",
        h.frequency_hz
    );
}
