//! The 2-dof friction oscillator built by hand from the brake's pieces (a [`ContactPair`] of
//! every field, the frictionless reference, the sweep, the start, the modal brake, CHBM with
//! restarts): the path `examples/friction_oscillator.rs` replaces with
//! `squeal_chbm::system`, kept here because the tests pin its numbers and check the facade
//! against it.
//!
//! Theory. Two dofs, `x0` tangential and `x1` normal, `M = I`, `C = c I`,
//! `K = [[k11, k12], [k12, k22]]`, and one contact pair whose penetration is `δ = x1 - g0`, `g0 = -GAP`
//! (a preload keeps it closed) with the paper's element (eqs 8–9): a cubic penalty force
//! `F_n = k_l δ + k_nl δ³` along the normal and Coulomb friction `F_t = μ F_n` along `-e0`.
//! Friction puts `-μ k_t` into `K[0][1]` only: the stiffness becomes non-symmetric, the two
//! modes approach each other as μ grows and coalesce (mode coupling) at the Hopf point μ0,
//! where a pair of eigenvalues crosses into the right half plane. Above μ0 the vibration grows
//! until the cubic contact hardens enough to stop it: a limit cycle, found here by CHBM.
//! With these stiffnesses a stiffer contact raises the flutter threshold, so the bifurcation
//! is supercritical: the cycle's squared amplitude grows linearly with `μ - μ0` (the Hopf
//! normal form), which `tests/chbm/two_dof.rs` checks against time integration.

use faer::Mat;
use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::modal::Damping;
use squeal_brake::modal_brake::ModalBrake;
use squeal_brake::spectrum::Reference;
use squeal_brake::sweep::{Band, SweepOptions, reference, sweep};
use squeal_brake::{Brake, ContactPair, PenaltyCoulomb};
use squeal_chbm::start::start_at;
use squeal_chbm::{ChbmOptions, ChbmSolution, RESTART_AMPLITUDES, solve_with_restarts};
use std::sync::Arc;

pub const M: f64 = 1.0;
pub const C: f64 = 20.0;
pub const K11: f64 = 1.0e6;
pub const K12: f64 = 1.0e5;
pub const K22: f64 = 1.0e6;
pub const GAP: f64 = 2.0e-4;
pub const KL: f64 = 3.0e5;
pub const KNL: f64 = 7.5e11;

/// The oscillator with contact stiffnesses `k_linear` (N/m) and `k_cubic` (N/m³).
pub fn brake(k_linear: f64, k_cubic: f64) -> Brake {
    let pair = ContactPair {
        disc_point: 0,
        pad_point: 0,
        position: [0.0; 3],
        normal_direction: [0.0, 1.0, 0.0],
        sliding_direction: [-1.0, 0.0, 0.0],
        normal: vec![(1, 1.0)],
        tangent: vec![(0, -1.0)],
        initial_gap: -GAP,
        surface_speed: None,
        law: Arc::new(PenaltyCoulomb { k_linear, k_cubic }),
    };
    Brake {
        m: Mat::from_fn(2, 2, |i, j| if i == j { M } else { 0.0 }),
        k: Mat::from_fn(2, 2, |i, j| [[K11, K12], [K12, K22]][i][j]),
        f_piston: vec![0.0, 0.0],
        c: None,
        k_vibration: None,
        pairs: vec![pair],
    }
}

/// The frictionless reference with the damping `c` on both modes (eq 12).
pub fn frictionless(brake: &Brake) -> Reference {
    let damping = Damping {
        global_ratio: 0.0,
        extra: vec![(0, C / M), (1, C / M)],
    };
    // The oscillator is held by its springs and the preload: Newton cannot fail here.
    reference(brake, &damping, &NewtonOptions::default()).expect("the oscillator is held")
}

/// Every frequency counts: no band limits the Hopf point.
pub fn band() -> Band {
    Band {
        valid_max_hz: f64::INFINITY,
        user: None,
    }
}

/// The Hopf point μ0 from a friction sweep over 0..2 and its refinement.
pub fn hopf(brake: &Brake, reference: &Reference) -> f64 {
    let mus: Vec<f64> = (0..=40).map(|k| 0.05 * k as f64).collect();
    let opts = {
        let mut o = SweepOptions::default();
        o.band = band();
        o
    };
    let s = sweep(brake, reference, &mus, &opts).expect("the sweep runs");
    s.hopf.expect("a Hopf point below mu = 2").mu0
}

/// The limit cycle at `mu` by CHBM with `harmonics` harmonics, from the unstable mode there.
pub fn limit_cycle(
    brake: &Brake,
    reference: &Reference,
    mu: f64,
    harmonics: usize,
) -> Result<ChbmSolution, Box<dyn std::error::Error>> {
    let start = start_at(
        brake,
        reference,
        mu,
        &band(),
        &NewtonOptions::default(),
        None,
    )?;
    let mb = ModalBrake::new(brake, reference, mu);
    let opts = {
        let mut o = ChbmOptions::default();
        o.harmonics = harmonics;
        o
    };
    Ok(solve_with_restarts(&mb, &start, &opts, &RESTART_AMPLITUDES)?.0)
}
