//! The `"system"` interface reduction of a brake with further parts: the bundled corner with
//! its caliper and bracket (`meshes/corner/brake_caliper.toml`: six connectors, the pistons on
//! the vibration only) and with the outboard abutments tied to the bracket
//! (`meshes/corner/brake_tied.toml`: a tie between parts whose master is a pad), each against
//! the same scene with the unreduced interface.
//!
//! The reference is the unreduced-interface brake itself (the same Craig–Bampton parts,
//! connectors, tie and pairs): the interface-reduced brake is its Rayleigh–Ritz projection on
//! the disc's and the pads' face bases, the further parts' dofs and the pads' coupling and tie
//! points kept whole, so (a) with every real mode of the brake in the face basis it is the same
//! brake in other coordinates (frequencies to round-off: a connector or a tie projected wrong,
//! or dropped, would move them by orders of magnitude more), (b) with fewer no frictionless
//! frequency is below the unreduced one, rank by rank, and (c) the scene's μ0 agrees.

use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::interface_system::system_vectors;
use squeal_brake::modal::Damping;
use squeal_brake::sweep::reference;
use squeal_pipeline::interface::at_count;
use squeal_pipeline::interface_system::face_bases;
use squeal_pipeline::model::{Model, build, quiet};
use squeal_scene::Scene;
use std::path::PathBuf;

/// A bundled corner scene (`brake_caliper` or `brake_tied`), with `[reduction] interface` as
/// written there (`"none"`).
fn scene(name: &str) -> Scene {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../../meshes/corner/{name}.toml"));
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.contains("interface = \"none\""),
        "{name}: the unreduced interface"
    );
    Scene::parse(&path, text).unwrap()
}

/// The frictionless brake's natural frequencies (Hz), ascending.
fn frequencies(m: &Model) -> Vec<f64> {
    let damping = Damping {
        global_ratio: 0.0,
        extra: vec![],
    };
    let r = reference(&m.brake, &damping, &NewtonOptions::default()).unwrap();
    r.basis
        .omega
        .iter()
        .map(|w| w / std::f64::consts::TAU)
        .collect()
}

/// The smallest and the largest `reduced / unreduced − 1` of the unreduced brake's frequencies
/// below `fmax` (Hz), rank by rank.
fn errors(unreduced: &[f64], reduced: &[f64], fmax: f64) -> (f64, f64) {
    unreduced
        .iter()
        .zip(reduced)
        .filter(|(a, _)| **a <= fmax)
        .map(|(a, b)| b / a - 1.0)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        })
}

/// The unreduced-interface model of `name`, and the interface-reduced ones on the face motion
/// of its lowest `modes` real modes (with the friction residuals of those in the band):
/// `(dofs, smallest error, largest error)` of the frequencies below the band's top for each.
fn check(name: &str, levels: &[usize]) -> (Model, Vec<(Model, f64, f64)>) {
    let out = std::env::temp_dir().join(format!("squeal-ifparts-{name}-{}", std::process::id()));
    let full = build(&scene(name), &out, &quiet).unwrap();
    assert!(!full.rom.bodies().is_empty() && full.interface.is_none());
    let fmax = 16000.0;
    let f_full = frequencies(&full);
    let vectors = system_vectors(&full.brake, &full.sweep.newton, fmax).unwrap();
    let in_band = vectors.residuals.ncols();
    assert_eq!(
        vectors.modes.omega.len(),
        full.brake.size(),
        "all the modes"
    );
    let mut out = Vec::new();
    for &modes in levels {
        let modes = modes.max(in_band).min(full.brake.size());
        let bases = face_bases(&full, &vectors, modes, in_band).unwrap();
        let m = at_count(&full, &bases, usize::MAX).unwrap();
        let f = frequencies(&m);
        assert_eq!(f.len(), m.brake.size());
        let (lo, hi) = errors(&f_full, &f, fmax);
        eprintln!(
            "{name}: {modes} brake modes + {in_band} residuals: {} dofs of {}, {} frequencies below {fmax} Hz within {lo:+.2e} .. {hi:+.2e}",
            m.brake.size(),
            full.brake.size(),
            f_full.iter().filter(|f| **f <= fmax).count()
        );
        out.push((m, lo, hi));
    }
    (full, out)
}

/// Rayleigh–Ritz on the corner with caliper and bracket: every real mode of the brake in the
/// face bases gives the unreduced brake back; the in-band modes with their residuals bound it
/// from above and give its μ0.
#[test]
fn caliper_corner_on_the_system_basis() {
    let (full, levels) = check("brake_caliper", &[0, usize::MAX]);
    let (reduced, lo, hi) = &levels[0];
    let (_, lo_all, hi_all) = &levels[1];
    // Every mode of the brake: the same brake in other coordinates (each face basis square
    // and invertible). Measured −9.5e-12 .. +5.2e-12 (the dense eigensolves of a brake whose
    // connectors reach 1e9 N/m); asserted 1e-9, far below what a connector's spring or the
    // caliper's mass left out of the projection would move.
    assert!(
        lo_all.abs() <= 1e-9 && hi_all.abs() <= 1e-9,
        "{lo_all:e} {hi_all:e}"
    );
    // The in-band modes with their friction residuals and the static vectors (625 of 1094
    // dofs): no frequency below the unreduced one (−1e-9 for the same round-off), and the
    // in-band ones reproduced (they are in the span): measured +5.3e-14 .. +7.5e-8, asserted
    // 1e-6 as on the one-pad brake (`interface_modes`). Before the static vectors were kept
    // exactly (`face_basis_keeping`): −9.5e-7 .. +5.3e-7, the equilibrium's normal forces off
    // by 2.8e-2 N of 107 N, so the bound failed.
    assert!(*lo >= -1e-9, "{lo:e}");
    assert!(*hi <= 1e-6, "{hi:e}");
    assert!(
        reduced.brake.size() < full.brake.size() * 2 / 3,
        "{} of {}",
        reduced.brake.size(),
        full.brake.size()
    );
    // μ0 of the scene (1 % modal damping) on both: measured 0.45980009 at 3362.720 Hz
    // unreduced (as `squeal stability meshes/corner/brake_caliper.toml`), 0.45980400 at
    // 3362.722 Hz on this basis (+8.5e-6, +4.6e-7). Asserted 1e-4 relative: the one-pad
    // brake's system basis agrees to 3e-5 with the unreduced interface; the caliper and the
    // bracket move this brake's μ0 from 0.1763 without them (`meshes/corner/brake.toml`) to
    // 0.4598, so a connector or the caliper's mass carried wrong shows far above it.
    //
    // The brake under test (the system basis) is swept over the scene's whole grid (0..1/41),
    // so an onset of its own below the reference's would show. The reference (1094 dofs) is
    // swept over the scene's own points from 0.40 to 0.50 only: the bracket of its onset,
    // [0.450, 0.475], is the same two points as on the whole grid, and its μ0 came out the
    // same to the 8 digits printed (0.45980009 at 3362.720 Hz both ways; its first onset over
    // the whole grid). The two sweeps took 56.6 s with the whole grid for both, 37.2 s so (one
    // thread, 2026-11-28, load average 2.6 and 3.1).
    let mus = scene("brake_caliper").mu_values().unwrap();
    let near: Vec<f64> = mus
        .iter()
        .copied()
        .filter(|&m| (0.40 - 1e-12..=0.50 + 1e-12).contains(&m))
        .collect();
    assert_eq!(near.len(), 5, "{near:?}");
    let hopf = |m: &Model, mus: &[f64]| {
        let st = squeal_pipeline::stability::analyse(m, mus).unwrap();
        let h = st.sweep.hopf.expect("a Hopf point");
        (h.mu0, h.frequency_hz)
    };
    let (mu_full, f_full) = hopf(&full, &near);
    let (mu, f) = hopf(reduced, &mus);
    eprintln!(
        "brake_caliper: mu0 {mu_full:.8} at {f_full:.3} Hz unreduced, {mu:.8} at {f:.3} Hz on the system basis ({:+.2e}, {:+.2e})",
        mu / mu_full - 1.0,
        f / f_full - 1.0
    );
    assert!((mu / mu_full - 1.0).abs() <= 1e-4, "{mu} {mu_full}");
    assert!((f / f_full - 1.0).abs() <= 1e-4, "{f} {f_full}");
}

/// The same on the corner whose outboard abutments are tied to the bracket: the tie's slave
/// nodes (on the bracket) follow master nodes on the pad that the face basis keeps whole.
#[test]
fn tied_corner_on_the_system_basis() {
    let (full, levels) = check("brake_tied", &[0, usize::MAX]);
    assert!(!full.rom.ties.is_empty());
    let (_, lo, hi) = &levels[0];
    let (_, lo_all, hi_all) = &levels[1];
    // As on the caliper corner, and for the same reasons. Measured: every mode −6.6e-12 ..
    // +3.6e-11; the in-band level (721 of 1172 dofs) +6.2e-14 .. +2.9e-8 (before the static
    // vectors were kept exactly: −5.8e-7 .. +9.3e-7).
    assert!(
        lo_all.abs() <= 1e-9 && hi_all.abs() <= 1e-9,
        "{lo_all:e} {hi_all:e}"
    );
    assert!(*lo >= -1e-9, "{lo:e}");
    assert!(*hi <= 1e-6, "{hi:e}");
}
