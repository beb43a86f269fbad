//! The bundled corner with its caliper and bracket (`meshes/corner/brake_caliper.toml`): its
//! pistons act on the vibration only (`vibration_only = true`, a pressure-controlled clamp),
//! its fingers in the static solve too.
//!
//! Asserted: each pad presses on the disc with the clamp force (the pistons' force pair is the
//! only static axial path between the pads and the floating caliper, so to Newton's tolerance,
//! 1e-6 allowed; the run's own check warns beyond 1 %), where the same scene without the key
//! (stiff pistons in the static solve) loses most of it; the frictionless frequencies equal
//! those of the brake with the pistons' stiffness everywhere linearized at the equilibrium of
//! the brake without it (an independent static solve; 1e-9 relative: the same matrices, the
//! equilibria equal to Newton's 1e-10).

use squeal_brake::equilibrium::{NewtonOptions, static_equilibrium};
use squeal_brake::modal::{Damping, modal_basis};
use squeal_brake::sweep::reference;
use squeal_pipeline::model::{Model, build, quiet};
use squeal_scene::Scene;
use std::path::PathBuf;

fn scene(vibration_only: bool) -> Scene {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes/corner/brake_caliper.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.contains("vibration_only = true"),
        "the bundled scene's pistons"
    );
    let text = match vibration_only {
        true => text,
        false => text.replace("vibration_only = true", "vibration_only = false"),
    };
    Scene::parse(&path, text).unwrap()
}

fn built(vibration_only: bool) -> Model {
    let out = std::env::temp_dir().join(format!(
        "squeal-caliper-{vibration_only}-{}",
        std::process::id()
    ));
    match build(&scene(vibration_only), &out, &quiet) {
        Ok(m) => m,
        Err(e) => panic!("{e}"),
    }
}

/// Each pad's share of the contact's normal force at μ = 0 (N), inboard then outboard.
fn resultants(m: &Model) -> Vec<f64> {
    let eq = static_equilibrium(&m.brake, 0.0, None, &NewtonOptions::default()).unwrap();
    ["inboard", "outboard"]
        .iter()
        .map(|pad| {
            m.pairs
                .iter()
                .zip(&eq.normal_forces)
                .filter(|(p, _)| p.pad == *pad)
                .map(|(_, f)| f)
                .sum()
        })
        .collect()
}

#[test]
fn the_pistons_act_on_the_vibration_and_the_clamp_reaches_the_pads() {
    let m = built(true);
    assert!(
        m.brake.k_vibration.is_some(),
        "the pistons' stiffness kept apart"
    );
    // 11.94 bar on 2.513e-3 m^2.
    let clamp = 11.94e5 * 2.513e-3;
    let r = resultants(&m);
    eprintln!(
        "vibration_only: inboard {:.4} N, outboard {:.4} N of {clamp:.4} N",
        r[0], r[1]
    );
    for f in &r {
        assert!((f - clamp).abs() <= 1e-6 * clamp, "{f} N of {clamp} N");
    }
    let stiff = resultants(&built(false));
    eprintln!(
        "in the static solve too: inboard {:.4} N, outboard {:.4} N",
        stiff[0], stiff[1]
    );
    assert!(stiff.iter().all(|f| *f < 0.5 * clamp), "{stiff:?}");
    // The spectrum at μ = 0 against the brake with the pistons everywhere, linearized at the
    // equilibrium of the brake without them.
    let kv = m.brake.k_vibration.clone().unwrap();
    let everywhere = squeal_brake::Brake {
        k_vibration: None,
        ..m.brake.clone()
    };
    let without = squeal_brake::Brake {
        k: &m.brake.k - &kv,
        k_vibration: None,
        ..m.brake.clone()
    };
    let damping = Damping {
        global_ratio: m.damping.global_ratio,
        extra: vec![],
    };
    let r = reference(&m.brake, &damping, &NewtonOptions::default()).unwrap();
    let e0 = static_equilibrium(&without, 0.0, None, &NewtonOptions::default()).unwrap();
    let basis = modal_basis(&everywhere.m, &everywhere.tangent_stiffness(&e0.x, 0.0)).unwrap();
    let mut worst: f64 = 0.0;
    for (a, b) in r.basis.omega.iter().zip(&basis.omega) {
        worst = worst.max((a - b).abs() / b);
    }
    eprintln!(
        "{} dofs; frequencies within {worst:.2e} of the stiff brake about the soft equilibrium",
        r.basis.omega.len()
    );
    assert!(worst <= 1e-9, "{worst}");
}
