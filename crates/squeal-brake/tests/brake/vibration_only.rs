//! A stiffness that acts on the vibration about the equilibrium only (`Brake::k_vibration`,
//! a hydraulic piston: `squeal_brake::vibration_only`) on a five-dof brake: disc (x, z), pad
//! (x, z) and caliper (z), the pad pressed on the disc by the clamp force `F` and the caliper
//! pushed back; a stiff piston spring between the pad and the caliper.
//!
//! - The clamp: with the piston on the vibration only, the contact carries `F` (the pad is
//!   held along the normal by the contact alone); with the piston in the static solve too,
//!   the caliper's loop takes most of it.
//! - The linearized brake: its spectrum (μ = 0 and μ = 0.4) equals, to round-off, that of the
//!   brake with the piston spring everywhere linearized at the equilibrium of the brake
//!   without the piston (an independent static solve).
//! - The harmonic balance's 0th harmonic: the condensed load and the recovery of eqs (33)
//!   and (35) give back the static equilibrium (without the piston), not the stiff one.

use faer::Mat;
use squeal_brake::equilibrium::{NewtonOptions, static_equilibrium};
use squeal_brake::harmonic::{CondensedStiffness, condensed_load, recover};
use squeal_brake::modal::{Damping, modal_basis};
use squeal_brake::modal_brake::ModalBrake;
use squeal_brake::spectrum::{Reference, spectrum};
use squeal_brake::sweep::reference;
use squeal_brake::{Brake, ContactPair, PenaltyCoulomb};
use squeal_hbm::HarmonicLayout;
use std::sync::Arc;

/// The clamp force (N).
const F: f64 = 3000.0;
/// The piston's stiffness (N/m): a fluid column's, 5e7 (docs/reduction.md).
const K_PISTON: f64 = 5.0e7;

/// The piston spring between pad z (dof 3) and caliper z (dof 4).
fn piston() -> Mat<f64> {
    let mut k = Mat::zeros(5, 5);
    for (a, b, s) in [(3, 3, 1.0), (4, 4, 1.0), (3, 4, -1.0), (4, 3, -1.0)] {
        k[(a, b)] = s * K_PISTON;
    }
    k
}

/// The brake with the piston spring `piston` in `K` (times `with`) and, when `vibration`,
/// kept as its vibration-only part.
fn brake(with: f64, vibration: bool) -> Brake {
    let mut k = Mat::zeros(5, 5);
    // Disc: x and z coupled (so that friction moves the normal state), held to ground.
    k[(0, 0)] = 1.0e8;
    k[(1, 1)] = 5.0e7;
    k[(0, 1)] = 2.0e7;
    k[(1, 0)] = 2.0e7;
    // Pad: held in-plane by its abutment, free along the normal but for the contact.
    k[(2, 2)] = 2.0e7;
    // Caliper: on its mounts.
    k[(4, 4)] = 2.0e8;
    let kp = piston();
    let k = &k + &kp * with;
    let pair = ContactPair {
        disc_point: 0,
        pad_point: 0,
        position: [0.0; 3],
        normal_direction: [0.0, 0.0, 1.0],
        sliding_direction: [1.0, 0.0, 0.0],
        normal: vec![(1, 1.0), (3, -1.0)],
        tangent: vec![(0, 1.0), (2, -1.0)],
        initial_gap: 0.0,
        surface_speed: None,
        law: Arc::new(PenaltyCoulomb {
            k_linear: 2.0e7,
            k_cubic: 2.0e15,
        }),
    };
    Brake {
        m: Mat::from_fn(5, 5, |i, j| {
            if i == j {
                [2.0, 2.0, 0.5, 0.5, 1.5][i]
            } else {
                0.0
            }
        }),
        k,
        // The pad pushed towards the disc (-z), the caliper pushed back.
        f_piston: vec![0.0, 0.0, 0.0, -F, F],
        c: None,
        k_vibration: vibration.then_some(kp),
        pairs: vec![pair],
    }
}

fn newton() -> NewtonOptions {
    NewtonOptions::default()
}

/// The contact carries the clamp force (to Newton's 1e-10) with the piston on the vibration
/// only, and less than half of it with the same piston in the static solve.
#[test]
fn the_clamp_force_reaches_the_contact() {
    let only = static_equilibrium(&brake(1.0, true), 0.0, None, &newton()).unwrap();
    assert!(
        (only.total_normal_force() - F).abs() <= 1e-9 * F,
        "{}",
        only.total_normal_force()
    );
    let both = static_equilibrium(&brake(1.0, false), 0.0, None, &newton()).unwrap();
    assert!(
        both.total_normal_force() < 0.5 * F,
        "{}",
        both.total_normal_force()
    );
}

/// The equilibrium is that of the brake without the piston (to 1e-12 of its size: two
/// Newton solutions of one problem at 1e-10), and the spectrum is that of the brake with the
/// piston everywhere linearized there (1e-10 relative: the same matrices up to the
/// equilibrium's round-off).
#[test]
fn the_spectrum_is_the_stiff_brake_about_the_soft_equilibrium() {
    let only = brake(1.0, true);
    let without = brake(0.0, false);
    let everywhere = brake(1.0, false);
    let r = reference(&only, &Damping::default(), &newton()).unwrap();
    let e0 = static_equilibrium(&without, 0.0, None, &newton()).unwrap();
    let size = e0.x.iter().fold(0.0, |a: f64, b| a.max(b.abs()));
    for (a, b) in r.equilibrium.x.iter().zip(&e0.x) {
        assert!((a - b).abs() <= 1e-12 * size, "{a} vs {b}");
    }
    // μ = 0: the natural frequencies of (K + K_p + K_NL(x0), M).
    let kt0 = everywhere.tangent_stiffness(&e0.x, 0.0);
    let basis = modal_basis(&everywhere.m, &kt0).unwrap();
    for (a, b) in r.basis.omega.iter().zip(&basis.omega) {
        assert!((a - b).abs() <= 1e-10 * b, "{a} vs {b} rad/s");
    }
    // The piston matters: without it the frequencies differ by far more.
    let soft = modal_basis(&without.m, &without.tangent_stiffness(&e0.x, 0.0)).unwrap();
    assert!((soft.omega[4] - basis.omega[4]).abs() > 1e-3 * basis.omega[4]);
    // μ = 0.4: the complex eigenvalues at the vibration-only brake's equilibrium.
    let mu = 0.4;
    let eq = static_equilibrium(&only, mu, None, &newton()).unwrap();
    let eq_without = static_equilibrium(&without, mu, None, &newton()).unwrap();
    let got = spectrum(&only, &r, &eq).unwrap().values;
    let stiff_reference = Reference {
        equilibrium: e0.clone(),
        kt0: kt0.clone(),
        damping: r.damping.clone(),
        basis,
    };
    let want = spectrum(&everywhere, &stiff_reference, &eq_without)
        .unwrap()
        .values;
    assert_eq!(got.len(), want.len());
    for w in &want {
        let near = got
            .iter()
            .map(|g| (g - w).norm())
            .fold(f64::INFINITY, f64::min);
        assert!(near <= 1e-10 * w.norm(), "{w}: nearest at {near}");
    }
}

/// The 0th harmonic of the harmonic balance: the condensed load (eq 33) and the recovery
/// (eq 35) of a motionless state give back the static equilibrium at μ = 0.4 (1e-9 of its
/// size: the modal flexibility's round-off), which the stiff piston would move by far more.
#[test]
fn the_mean_is_the_static_equilibrium() {
    let only = brake(1.0, true);
    let r = reference(&only, &Damping::default(), &newton()).unwrap();
    let mu = 0.4;
    let eq = static_equilibrium(&only, mu, None, &newton()).unwrap();
    let mb = ModalBrake::new(&only, &r, mu);
    let nn = mb.nl();
    let xn: Vec<f64> = mb.nl_dofs.iter().map(|&d| eq.x[d]).collect();
    // Λ_eq,0 x_n + G(x_n) = F_eq: the condensed 0th-harmonic equation (eq 34) at rest.
    let layout = HarmonicLayout::new(nn, 1).unwrap();
    let cs = CondensedStiffness::new(&mb, 1);
    let f_eq = condensed_load(&mb, &cs, &layout);
    let mut g = vec![0.0; nn];
    mb.add_reduced_force(&xn, None, &mut g);
    let z0 = cs.block(0);
    for i in 0..nn {
        let lhs: f64 = (0..nn).map(|j| z0[(i, j)].re * xn[j]).sum::<f64>() + g[i];
        assert!(
            (lhs - f_eq[i]).abs() <= 1e-9 * F,
            "row {i}: {lhs} vs {}",
            f_eq[i]
        );
    }
    // Eq (35): every dof's mean from G.
    let mut gh = vec![0.0; layout.len()];
    gh[..nn].copy_from_slice(&g);
    let all = recover(&mb, 1000.0, &gh, &layout);
    let size = eq.x.iter().fold(0.0, |a: f64, b| a.max(b.abs()));
    for (d, (a, x)) in all.iter().zip(&eq.x).take(5).enumerate() {
        assert!((a - x).abs() <= 1e-9 * size, "dof {d}: {a} vs {x}");
    }
    let stiff = static_equilibrium(&brake(1.0, false), mu, None, &newton()).unwrap();
    assert!((stiff.x[3] - eq.x[3]).abs() > 1e-2 * size);
}
