//! A 20-node hexahedral pad with nodal contact: the bundled one-pad brake's pad meshed in
//! C3D20 (`meshes/hex_pad/pad_coarse.inp`, written by `tools/mesh/hex_pad.py --level coarse`:
//! 5 x 4 elements on its friction face, one through the lining) on the bundled coarse tet10
//! disc. Its friction face has 8-node faces only, so its contact points are their 2 × 2
//! Gauss points (`squeal_reduce::interface::quad_contact`), each a combination of its face's
//! eight nodes, all of which the pad's reduction keeps.

use squeal_pipeline::model::{build, quiet};
use squeal_reduce::rom::PointRole;
use squeal_scene::Scene;
use std::path::PathBuf;

/// `meshes/brake.toml` with the coarse disc, the hex20 pad and nodal contact, read as if it
/// were `meshes/brake_hex_pad.toml`.
fn hex_pad_scene() -> Scene {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
    let mut text = std::fs::read_to_string(dir.join("brake.toml")).unwrap();
    for (from, to) in [
        ("disc = \"disc_medium.inp\"", "disc = \"disc_coarse.inp\""),
        (
            "pad = \"pad_medium.inp\"",
            "pad = \"hex_pad/pad_coarse.inp\"",
        ),
        ("interface = \"patch\"", "interface = \"nodal\""),
    ] {
        assert!(text.contains(from), "brake.toml lost '{from}'");
        text = text.replacen(from, to, 1);
    }
    Scene::parse(&dir.join("brake_hex_pad.toml"), text).unwrap()
}

#[test]
fn a_hex20_pad_pairs_its_gauss_points_and_keeps_every_face_node() {
    let scene = hex_pad_scene();
    let out = std::env::temp_dir().join(format!("squeal-hexpad-{}", std::process::id()));
    let m = build(&scene, &out, &quiet).unwrap();
    let pad = m.rom.part("pad").unwrap();
    let count = |role: PointRole, combined: bool| {
        pad.info
            .points
            .iter()
            .filter(|p| p.role == role && p.combines.is_some() == combined)
            .count()
    };
    // 20 faces of 8 nodes, 79 nodes in all (11 x 9 grid points less the 20 face centres):
    // every node kept as a face point, none a contact point itself; 4 Gauss points a face.
    assert_eq!(count(PointRole::Face, false), 79);
    assert_eq!(count(PointRole::Contact, false), 0);
    assert_eq!(count(PointRole::Contact, true), 80);
    assert_eq!(m.pairs.len(), 80);
    for p in pad.info.points.iter().filter_map(|p| p.combines.as_ref()) {
        assert_eq!(p.len(), 8);
        let sum: f64 = p.iter().map(|w| w.1).sum();
        assert!((sum - 1.0).abs() < 1e-14, "{sum}");
        assert!(
            p.iter()
                .all(|&(k, _)| pad.info.points[k].role == PointRole::Face)
        );
    }
    // The pairs' areas sum to the sector's, 50° of r = 85..135 mm, to the error of the
    // faces' quadratic arcs (12.5° each) and of the 2 × 2 rule on them: measured −4.71e-6,
    // asserted 1e-5. The faces are flat and touch (z = 20 mm): every gap is round-off.
    let area: f64 = m.pairs.iter().map(|p| p.area.unwrap()).sum();
    let sector = 50f64.to_radians() * (0.135f64.powi(2) - 0.085f64.powi(2)) / 2.0;
    let gap = m
        .pairs
        .iter()
        .map(|p| p.geometric_gap.abs())
        .fold(0.0, f64::max);
    eprintln!(
        "hex20 pad: {} pairs, area {area:.9e} (sector {sector:.9e}, {:+.2e}), largest |gap| {gap:.1e} m",
        m.pairs.len(),
        area / sector - 1.0
    );
    assert!((area / sector - 1.0).abs() < 1e-5);
    assert!(gap < 1e-15, "{gap:e}");
    // μ0 on mu = 0.3..0.6/31 (the scene's default "system" interface reduction): measured
    // 0.39475346 at 4118.59 Hz (`squeal stability` on this scene, 2026-11-28), against
    // 0.39641105 at 4116.71 Hz with the bundled tet10 coarse pad on the same disc (−0.42 %):
    // two meshes of one pad agree to their discretization error. With the lumped areas on the
    // 8-node faces (the rule before) the hex20 pad gave 0.37614224 at 4063.98 Hz (−5.1 %).
    // Asserted: 1e-6 relative of the measured value (the Hopf bracket is 1e-8; the sweep's
    // friction values differ from the run's), and within 1 % of the tet10 pad's (the lumped
    // rule fails it).
    let mus: Vec<f64> = (0..31).map(|i| 0.3 + 0.01 * i as f64).collect();
    let st = squeal_pipeline::stability::analyse(&m, &mus).unwrap();
    let h = st.sweep.hopf.expect("a Hopf point in mu = 0.3..0.6");
    eprintln!("hex20 pad: mu0 = {:.8} at {:.2} Hz", h.mu0, h.frequency_hz);
    assert!((h.mu0 / 0.39475346 - 1.0).abs() <= 1e-6, "{}", h.mu0);
    assert!((h.mu0 / 0.39641105 - 1.0).abs() <= 1e-2, "{}", h.mu0);
    assert!(
        (h.frequency_hz / 4118.59 - 1.0).abs() <= 1e-5,
        "{}",
        h.frequency_hz
    );
    std::fs::remove_dir_all(&out).ok();
}
