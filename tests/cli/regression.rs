//! Headline results of the bundled coarse brake, pinned before the core restructuring (issue 9)
//! so that it provably changes no number: the Hopf point μ0 and its frequency, the second
//! crossing, and the CHBM limit cycle at 1.01 μ0 with 3 and 10 harmonics.
//!
//! The values were first pinned with the code of commit f709a63 (before the restructuring) by
//! exactly these commands, and the restructured code reproduced them within these tolerances.
//! They were pinned again once, when curved tet10 elements got an exact stiffness rule
//! (issue 12: the old 4-point rule is exact only for straight elements), which moved the
//! model itself: μ0 0.4617136858 → 0.4618226613 (+2.36e-4), its frequency 4061.1585 →
//! 4061.4806 Hz, the second crossing 0.7744594185 → 0.7743371648 at 2951.02 → 2951.58 Hz,
//! CHBM at 1.01 μ0 4006.4751 → 4006.7783 Hz (3 harmonics) and 4006.5917 → 4006.8951 Hz (10).
//! Each tolerance says what it allows for: these are round-off and solver-tolerance bounds, not
//! modelling allowances.

use super::common;

use common::{bundled_scene, run_ok, squeal, temp_dir};
use std::path::Path;

/// μ0 and its frequency: `squeal stability` refines μ0 to a bracket of 1e-8 (5.0e-9 measured).
const MU0: f64 = 0.461_822_661_259_084_17;
const MU0_HZ: f64 = 4_061.480_623_728_935_4;
/// The second crossing (branch of the 2951 Hz mode), refined as the first crossing of a sweep
/// over [0.770, 0.775] with the coalescing pair given as modes 14 and 13 (which "auto" picks).
const MU1: f64 = 0.774_337_164_8;
const MU1_HZ: f64 = 2_951.58;
/// CHBM at 1.01 μ0: frequency and the largest first-harmonic amplitude over the 158 reduced
/// dofs (m), with 3 and with 10 harmonics.
const CHBM_MU: f64 = 0.466_440_887_871_675_04;
const CHBM: [(usize, f64, f64); 2] = [
    (3, 4_006.778_289_407_489, 2.127_116_234_139_730_4e-5),
    (10, 4_006.895_130_657_160_7, 2.124_555_317_780_356_3e-5),
];

fn json(path: &Path) -> serde_json::Value {
    let text =
        std::fs::read_to_string(path).unwrap_or_else(|e| panic!("reading {}: {e}", path.display()));
    serde_json::from_str(&text).unwrap()
}

fn number(v: &serde_json::Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing in {v}"))
}

#[test]
fn coarse_brake_headline_numbers_are_unchanged() {
    let dir = temp_dir("regression", "coarse");
    let scene = dir.join("brake.toml");
    let text = bundled_scene("coarse");
    std::fs::write(&scene, &text).unwrap();
    let out = dir.join("out");
    let (scene_s, out_s) = (scene.to_str().unwrap(), out.to_str().unwrap());

    run_ok(&["stability", scene_s, "--out", out_s, "--no-vtu"]);
    let summary = json(&out.join("stability/summary.json"));
    let (mu0, f0) = (number(&summary, "mu0"), number(&summary, "frequency_hz"));
    // μ0 is the midpoint of a bracket narrower than 1e-8: any reordering of the arithmetic
    // moves it by far less than the bracket.
    assert!((mu0 - MU0).abs() < 1e-8, "mu0 = {mu0}, pinned {MU0}");
    // The frequency varies by ~60 Hz per unit μ near μ0 (4061.16 Hz at μ0, 4061.75 Hz at
    // 0.465): a 1e-8 change of μ0 moves it by ~1e-6 Hz. 1e-8 relative (4e-5 Hz) allows that.
    assert!(
        (f0 / MU0_HZ - 1.0).abs() < 1e-8,
        "f0 = {f0}, pinned {MU0_HZ}"
    );

    // The second crossing, refined by the same root finder.
    let pair_scene = dir.join("brake_pair.toml");
    std::fs::write(
        &pair_scene,
        text.replace("pair = \"auto\"", "pair = [14, 13]"),
    )
    .unwrap();
    let out2 = dir.join("out_second");
    std::fs::create_dir_all(&out2).unwrap();
    std::fs::copy(out.join("brake.rom"), out2.join("brake.rom")).unwrap();
    run_ok(&[
        "stability",
        pair_scene.to_str().unwrap(),
        "--mu",
        "0.77..0.775/11",
        "--out",
        out2.to_str().unwrap(),
        "--no-vtu",
    ]);
    let second = json(&out2.join("stability/summary.json"));
    let (mu1, f1) = (number(&second, "mu0"), number(&second, "frequency_hz"));
    // Bracket 5.5e-9 wide; the pinned value has 10 digits.
    assert!(
        (mu1 - MU1).abs() < 1e-8,
        "second crossing mu = {mu1}, pinned {MU1}"
    );
    // Pinned to the 6 digits printed (2951.58 Hz): 5e-3 Hz.
    assert!(
        (f1 - MU1_HZ).abs() < 5e-3,
        "second crossing f = {f1}, pinned {MU1_HZ}"
    );

    // The pins are CHBM from the guessed start (eq 48), as when they were taken. From the
    // branch (the default since issue 10) 10 harmonics give the same cycle (2e-11, the branch
    // test below); 3 harmonics on 32 AFT samples land on another root of the same sampled
    // equations, 4006.8500 Hz (1.8e-5 away: the open part of the cycle covers 3 samples at one
    // root and a little more at the other).
    for (h, f_pin, a_pin) in CHBM {
        let out_h = dir.join(format!("out_h{h}"));
        std::fs::create_dir_all(&out_h).unwrap();
        std::fs::copy(out.join("brake.rom"), out_h.join("brake.rom")).unwrap();
        run_ok(&[
            "chbm",
            scene_s,
            "--mu-ratio",
            "1.01",
            "--harmonics",
            &h.to_string(),
            "--guessed-start",
            "--out",
            out_h.to_str().unwrap(),
            "--no-vtu",
        ]);
        let c = json(&out_h.join("chbm/chbm.json"));
        let mu = number(&c, "mu");
        assert!(
            (mu - CHBM_MU).abs() < 1e-8,
            "CHBM mu = {mu}, pinned {CHBM_MU}"
        );
        let f = number(&c, "frequency_hz");
        // CHBM stops at ||f1|| <= 1e-9 ||F_eq|| (measured 4e-11): the cycle is a root of the
        // harmonic balance to that accuracy, which bounds its frequency to ~1e-9 relative.
        // 1e-7 relative (0.4 mHz) leaves room for a different iteration path to the same root.
        assert!(
            (f / f_pin - 1.0).abs() < 1e-7,
            "H = {h}: f = {f}, pinned {f_pin}"
        );
        let n = number(&c, "dofs") as usize;
        let coeffs: Vec<f64> = c["coefficients"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let a = (0..n)
            .map(|j| coeffs[n + j].hypot(coeffs[2 * n + j]))
            .fold(0.0, f64::max);
        // Same argument for the amplitude: 1e-6 relative.
        assert!(
            (a / a_pin - 1.0).abs() < 1e-6,
            "H = {h}: amplitude {a}, pinned {a_pin}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn coarse_brake_branch_folds_below_mu0_and_meets_chbm_at_1_01_mu0() {
    // `squeal branch` on the coarse brake with 10 harmonics up to 1.05 mu0 (issue 10).
    // Measured when written (2026-11-23): l1 = +0.51082 (subcritical), fold at
    // mu = 0.460646090293 (0.99745 mu0, contact closed, refined to a tangent component of
    // 1e-8: the adaptive 5-harmonic branch gives the same fold to 2e-13), and the cycle at
    // 1.01 mu0 at 4006.895130577 Hz, 2e-11 from CHBM's 10-harmonic cycle pinned above: the same
    // equations solved by another algorithm (continuation Newton against CHBM's constrained
    // Levenberg-Marquardt), so 1e-9 bounds their solver tolerances.
    let dir = temp_dir("regression", "branch");
    let scene = dir.join("brake.toml");
    std::fs::write(&scene, bundled_scene("coarse")).unwrap();
    let out = dir.join("out");
    let (scene_s, out_s) = (scene.to_str().unwrap(), out.to_str().unwrap());
    let text = run_ok(&[
        "branch",
        scene_s,
        "--out",
        out_s,
        "--harmonics",
        "10",
        "--max-ratio",
        "1.05",
        "--at",
        "1.01,0.998",
    ]);
    assert!(text.contains("subcritical"), "{text}");
    let b = json(&out.join("branch/branch.json"));
    let l1 = number(&b["hopf"], "first_lyapunov_coefficient");
    // l1 comes from second and third derivatives by central differences: 1e-4 relative.
    assert!((l1 / 0.510_816_6 - 1.0).abs() < 1e-4, "l1 = {l1}");
    let folds = b["folds"].as_array().unwrap();
    assert_eq!(folds.len(), 1, "{folds:?}");
    let fold = number(&folds[0], "mu");
    assert!(folds[0]["refined"].as_bool().unwrap());
    assert!(
        (fold / 0.460_646_090_29 - 1.0).abs() < 1e-8,
        "fold at {fold}"
    );
    assert_eq!(
        number(&b["squeal_range"], "with_disturbance_from_mu"),
        fold,
        "squeal after a disturbance from the fold"
    );
    let at = b["cycles_at"].as_array().unwrap();
    // 1.01 mu0 is crossed once (the stable part), 0.998 mu0 twice (unstable, then stable).
    assert_eq!(at.len(), 3, "{at:?}");
    let f = number(&at[0], "frequency_hz");
    assert!(
        (f / CHBM[1].1 - 1.0).abs() < 1e-9,
        "{f} vs CHBM {}",
        CHBM[1].1
    );
    let verdicts: Vec<&str> = at
        .iter()
        .map(|c| c["stability"].as_str().unwrap())
        .collect();
    assert_eq!(verdicts, ["stable", "unstable", "stable"]);
    for name in ["branch.csv", "branch.svg", "branch.png"] {
        assert!(out.join("branch").join(name).is_file(), "{name} missing");
    }
    // `squeal chbm` along the branch: below mu0, between the fold and mu0, it returns the
    // stable cycle of the two (4035.05 Hz, pair 7 23.0 um); below the fold there is none and
    // it says so with exit code 3 (no limit cycle).
    let text = run_ok(&[
        "chbm",
        scene_s,
        "--out",
        out_s,
        "--mu-ratio",
        "0.998",
        "--harmonics",
        "10",
        "--no-vtu",
    ]);
    assert!(text.contains("crosses mu = 0.460899 2 time(s)"), "{text}");
    assert!(text.contains("CHBM starts from cycle 2 (stable)"), "{text}");
    let c = json(&out.join("chbm/chbm.json"));
    let f = number(&c, "frequency_hz");
    assert!((f - 4035.0524).abs() < 1e-3, "{f}");
    let below = squeal(&[
        "chbm",
        scene_s,
        "--out",
        out_s,
        "--mu-ratio",
        "0.997",
        "--harmonics",
        "10",
        "--no-vtu",
    ]);
    assert_eq!(below.status.code(), Some(3));
    assert!(String::from_utf8_lossy(&below.stdout).contains("does not reach"));
    std::fs::remove_dir_all(&dir).ok();
}
