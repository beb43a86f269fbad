//! Caveats said with the stability result: the damped bundled brake has none; the same brake
//! without damping is flagged, prints no slope at its coalescence, does not call one mode of
//! the pair "the unstable one", and is told that its coalescing pair is near-degenerate.

use super::common;
use common::{bundled_scene, run_ok, temp_dir};

fn stability(name: &str, scene_text: &str) -> (String, serde_json::Value) {
    let dir = temp_dir("caveats", name);
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, scene_text).unwrap();
    let out = dir.join("out");
    let text = run_ok(&[
        "stability",
        scene.to_str().unwrap(),
        "--no-vtu",
        "-o",
        out.to_str().unwrap(),
    ]);
    let json = std::fs::read_to_string(out.join("stability/summary.json")).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    (text, serde_json::from_str(&json).unwrap())
}

#[test]
fn an_undamped_coalescence_is_flagged_and_the_damped_brake_is_not() {
    let damped = bundled_scene("coarse");
    let (text, json) = stability("damped", &damped);
    assert!(!text.contains("warning:"), "{text}");
    assert_eq!(json["caveats"].as_array().map(Vec::len), Some(0), "{json}");
    assert!(text.contains("dRe(lambda)/dmu = "), "{text}");
    assert!(text.contains("(goes unstable)"), "{text}");

    let undamped = damped
        .replace("global_ratio = 0.01", "global_ratio = 0.0")
        .replace("pair_ratios = [0.001, 0.001]", "pair_ratios = [0.0, 0.0]");
    assert_ne!(undamped, damped, "the bundled scene's damping keys moved");
    let (text, json) = stability("undamped", &undamped);
    assert!(text.contains("warning: the model has no damping"), "{text}");
    assert!(text.contains("no finite dRe(lambda)/dmu"), "{text}");
    // No slope anywhere: the sensitivities (first-order perturbation of a simple eigenvalue)
    // are not attempted at a double one.
    assert!(!text.contains("dRe(lambda)/dmu = "), "{text}");
    assert!(
        text.contains("sensitivities of mu0 not computed: at an undamped coalescence"),
        "{text}"
    );
    assert!(!text.contains("(goes unstable)"), "{text}");
    let kinds: Vec<&str> = json["caveats"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|c| c["kind"].as_str())
        .collect();
    // Damped, the coarse brake turns unstable at mu0 = 0.4617 on the disc's 4-diameter doublet
    // (#13, #14, 7 % apart). Undamped, the 3-diameter doublet goes first: modes #7 and #8 at
    // 2930.2 and 2953.1 Hz, 0.78 % apart, coalesce at mu0 = 0.2637 (measured): the case the
    // near-degenerate caveat is for, and it fires.
    assert_eq!(kinds, ["undamped", "near_degenerate_pair"], "{json}");
    let mu0 = json["mu0"].as_f64().unwrap();
    // The bracket of the Hopf point is 7e-9 wide.
    assert!((mu0 - 0.263688).abs() < 1e-5, "mu0 = {mu0}");
    assert!(
        text.contains("#8 (2953.1 Hz) and #7 (2930.2 Hz) are 0.777 % apart"),
        "{text}"
    );
}
