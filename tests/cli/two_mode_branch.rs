//! `squeal branch` on a brake with a second unstable mode inside the branch's range (issue 24,
//! item 2): the coarse two-pad brake of `meshes/two_pad/two_mode_coarse.toml`, whose 4070 Hz
//! mode goes unstable at μ0 = 0.23545 and 2880 Hz mode at 0.23771, both supercritically
//! (docs/verification.md, "A brake with both modes supercritical"). The report names the
//! second mode with its refined onset and criticality, and gives the generalized CHBM's
//! two-mode torus just past it (also written to `branch/two_mode.txt`).

use super::common;

use common::{root, run_ok, temp_dir};

/// The number after `key` in `text`, up to the next space.
fn number_after(text: &str, key: &str) -> f64 {
    let at = text
        .find(key)
        .unwrap_or_else(|| panic!("{key} missing in\n{text}"))
        + key.len();
    text[at..]
        .split_whitespace()
        .next()
        .unwrap()
        .trim_end_matches([',', ';'])
        .parse()
        .unwrap()
}

#[test]
fn branch_report_gives_the_two_mode_answer_past_the_second_onset() {
    let out = temp_dir("two-mode", "branch");
    let scene = root().join("meshes/two_pad/two_mode_coarse.toml");
    let text = run_ok(&[
        "branch",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--max-ratio",
        "1.02",
        "--no-torus",
    ]);
    assert!(
        text.contains("second unstable mode inside the branch's range: 2880 Hz"),
        "{text}"
    );
    // The onset by bisection to 1e-9 of μ (measured 0.23771043; `crates/squeal-pipeline/tests/pipeline/two_mode_brake.rs`
    // checks the bisection against the sweep's own refinement to 1e-7).
    let onset = number_after(&text, "onset mu0' = ");
    assert!((onset - 0.23771043).abs() < 1e-7, "{onset}");
    assert!(text.contains("supercritical"), "{text}");
    // The two-mode torus at μ0' (1 + 5e-5): measured f1 = 4054.265701 Hz, f2 = 2879.796179 Hz;
    // the onset's bracket (1e-9 wide) moves μ, and the frequencies by at most 3e-9 relative.
    let f1 = number_after(&text, "f1 = ");
    let f2 = number_after(&text, "f2 = ");
    assert!((f1 / 4054.265701 - 1.0).abs() < 1e-7, "{f1}");
    assert!((f2 / 2879.796179 - 1.0).abs() < 1e-7, "{f2}");
    let file = std::fs::read_to_string(out.join("branch").join("two_mode.txt")).unwrap();
    assert!(file.contains("two-mode torus"), "{file}");
    // branch.json carries the same answer: the same numbers as the text, not rounded.
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(out.join("branch").join("branch.json")).unwrap(),
    )
    .unwrap();
    let two = &json["two_mode"];
    let mu0 = two["onset"]["mu0"].as_f64().unwrap();
    assert!((mu0 - onset).abs() < 1e-8, "{mu0} against {onset}");
    let f = &two["answer"]["torus"]["frequencies_hz"];
    assert!((f[0].as_f64().unwrap() - f1).abs() < 1e-6, "{f}");
    assert!((f[1].as_f64().unwrap() - f2).abs() < 1e-6, "{f}");
    assert_eq!(two["onset"]["criticality"], "supercritical", "{two}");
}
