//! The bundled brake corner (`meshes/corner/brake.toml`, issue 21 item 6): one Abaqus file
//! holding a ventilated disc in hex20 and wedge15 (8-node contact faces), two pads of tet10
//! with shims tied to the backplates, a caliper and a bracket (in the file, not yet in the
//! scene); the same model as Nastran bulk data (`corner_coarse.bdf`). Both are made by
//! `tools/mesh/corner_meshes.py`.
//!
//! Asserted: every node of each pad's friction face is paired with the disc's quadrilateral
//! face under it, with the pads' lumped areas summing to the pad face (60 degrees of the
//! annulus 95..145 mm, to the faceting of its arcs); the reduced matrices and frictionless
//! frequencies of the .inp and the .bdf are the same bits (the same mesh index for index: the
//! readers keep each format's node order), so their Hopf points are; the Hopf point lies in
//! the scene's band.

use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::modal::Damping;
use squeal_brake::sweep::reference;
use squeal_pipeline::model::{Model, build, quiet};
use squeal_scene::Scene;
use std::path::PathBuf;

fn corner_scene(file: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes/corner/brake.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("corner_coarse.inp", file);
    Scene::parse(&path, text).unwrap()
}

fn built(file: &str) -> Model {
    let out = std::env::temp_dir().join(format!("squeal-corner-{file}-{}", std::process::id()));
    match build(&corner_scene(file), &out, &quiet) {
        Ok(m) => m,
        Err(e) => panic!("{file}: {e}"),
    }
}

/// The frictionless frequencies (Hz) of the reduced brake.
fn frequencies(m: &Model) -> Vec<f64> {
    let damping = Damping {
        global_ratio: m.damping.global_ratio,
        extra: vec![],
    };
    let r = reference(&m.brake, &damping, &NewtonOptions::default()).unwrap();
    r.basis
        .omega
        .iter()
        .map(|w| w / (2.0 * std::f64::consts::PI))
        .collect()
}

#[test]
fn the_coarse_corner_pairs_its_pads_and_its_bdf_gives_the_same_bits() {
    // Bits compared: faer's dense kernels sequential, as `squeal` runs them (with faer's
    // default, parallel, their bits may vary: `squeal_reduce::brake::BrakeInputs::par`).
    faer::set_global_parallelism(faer::Par::Seq);
    let inp = built("corner_coarse.inp");
    // Each pad's friction face: 2 x 6 quadrilateral cells of six tetrahedra, 5 x 13 nodes, of
    // which the 3 x 7 cell corners carry no share of the pressure (the consistent loads of
    // 6-node triangles, crates/squeal-reduce/src/interface/nodal.rs): 44 contact points.
    for pad in ["inboard", "outboard"] {
        let pairs: Vec<_> = inp.pairs.iter().filter(|p| p.pad == pad).collect();
        assert_eq!(pairs.len(), 44, "{pad}");
        let area: f64 = pairs.iter().map(|p| p.area.unwrap_or(0.0)).sum();
        // 60 degrees of the annulus 95..145 mm; the pad's arcs are quadratic edges of 10
        // degrees (half-angle a = 0.087 rad), whose segments miss the circle's by O(a^4) of
        // the area (bounded by 6e-5; measured 1.9e-6): 1e-5 allowed.
        let exact = 0.5 * 60f64.to_radians() * (0.145f64.powi(2) - 0.095f64.powi(2));
        eprintln!(
            "{pad}: {} pairs, area {area:.9e} against {exact:.9e}",
            pairs.len()
        );
        assert!(
            (area / exact - 1.0).abs() < 1e-5,
            "{pad}: {area} vs {exact}"
        );
    }
    // The scene's friction values up to 0.2 (its 0..1/41 grid's first nine): μ0, the first
    // onset, is the same crossing as over the whole grid (the same points below it and the
    // same bracket [0.175, 0.2]): measured 0.176314167 at 3311.130 Hz against 0.176314169 at
    // 3311.130 Hz over the whole grid (1e-8 apart: the end of the Hopf refinement). The 32
    // points above it made this test 45.5 s instead of 13.8 s on one thread (2026-11-28, load
    // average 3.8).
    let mus: Vec<f64> = corner_scene("corner_coarse.inp")
        .mu_values()
        .unwrap()
        .into_iter()
        .filter(|&m| m <= 0.2 + 1e-12)
        .collect();
    assert_eq!(mus.len(), 9, "{mus:?}");
    let st = squeal_pipeline::stability::analyse(&inp, &mus).unwrap();
    let hopf = st
        .sweep
        .hopf
        .expect("the coarse corner has a Hopf point in 0..0.2");
    eprintln!(
        "corner: mu0 {:.9} at {:.3} Hz; {} dofs",
        hopf.mu0,
        hopf.frequency_hz,
        inp.brake.k.nrows()
    );
    assert!(
        (1000.0..=16000.0).contains(&hopf.frequency_hz),
        "{}",
        hopf.frequency_hz
    );
    let bdf = built("corner_coarse.bdf");
    // The same mesh index for index: the same reduced matrices, bit for bit, so the same
    // frictionless frequencies and the same Hopf point (the sweep is deterministic).
    for (p, q) in inp.rom.parts.iter().zip(&bdf.rom.parts) {
        assert_eq!(p.info.full_dofs, q.info.full_dofs, "{}", p.info.name);
        assert!(
            p.k == q.k && p.m == q.m,
            "{}: reduced matrices differ",
            p.info.name
        );
    }
    let (fa, fb) = (frequencies(&inp), frequencies(&bdf));
    eprintln!(
        "frictionless: {} frequencies, lowest {:.3} Hz",
        fa.len(),
        fa.first().copied().unwrap_or(f64::NAN)
    );
    assert_eq!(fa.len(), fb.len());
    assert!(
        fa.iter().zip(&fb).all(|(a, b)| a.to_bits() == b.to_bits()),
        "frictionless frequencies of the .inp and the .bdf differ"
    );
}
