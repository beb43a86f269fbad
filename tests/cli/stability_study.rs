//! End-to-end tests of `squeal study` on the bundled brake with its coarse meshes: the
//! damping-induced destabilization at small friction against second-order perturbation
//! theory and the modal damping ratio, and the mesh study's patch model against
//! `squeal stability`.

use super::common;

use std::path::PathBuf;
use std::process::Output;

fn temp_dir(name: &str) -> PathBuf {
    common::temp_dir("study", name)
}

/// The bundled scene on the coarse meshes (absolute paths), written to `dir`.
fn coarse_scene(dir: &std::path::Path) -> PathBuf {
    let path = dir.join("brake_coarse.toml");
    std::fs::write(&path, common::bundled_scene("coarse")).unwrap();
    path
}

/// Runs `squeal`, which must succeed.
fn squeal(args: &[&str]) -> Output {
    let out = common::squeal(args);
    assert!(
        out.status.success(),
        "squeal {args:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Rows of a CSV file as maps from the header's names.
fn csv(path: &std::path::Path) -> Vec<std::collections::BTreeMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|s| s.trim_matches('"').to_string())
        .collect();
    lines
        .map(|l| {
            header
                .iter()
                .cloned()
                .zip(l.split(',').map(|s| s.trim_matches('"').to_string()))
                .collect()
        })
        .collect()
}

fn num(row: &std::collections::BTreeMap<String, String>, key: &str) -> f64 {
    row[key]
        .parse()
        .unwrap_or_else(|_| panic!("{key} = {} is not a number", row[key]))
}

#[test]
fn pair_damping_alone_destabilizes_the_other_modes_as_perturbation_theory_predicts() {
    let dir = temp_dir("paradox");
    let scene = coarse_scene(&dir);
    let out = dir.join("out");
    squeal(&[
        "study",
        scene.to_str().unwrap(),
        "--kind",
        "paradox",
        // Coarse: the nominal sweep only has to find the pair (mu0 = 0.46 on these meshes);
        // the paradox study adds its own small-friction grid.
        "--mu",
        "0..0.5/11",
        "--out",
        out.to_str().unwrap(),
    ]);
    let rows = csv(&out.join("study/paradox.csv"));
    let pick = |case: &str, mu: f64| {
        rows.iter()
            .find(|r| r["case"].starts_with(case) && (num(r, "mu") - mu).abs() < 1e-12)
            .unwrap_or_else(|| panic!("no row {case} at mu = {mu}"))
    };
    for mu in [1e-3, 2e-3, 5e-3, 1e-2] {
        // Pair damping only: the undamped modes go unstable at vanishing friction, with the
        // growth that second-order perturbation in the friction coupling predicts. Its error is
        // of relative order |ΔK| / (ω_k² - ω_j²) (≈ mu here) plus the modes' near-degeneracy;
        // 10% bounds both at mu <= 0.01.
        let r = pick("pair only", mu);
        let (got, pred) = (
            num(r, "max_re_over_abs_other_modes"),
            num(r, "second_order_prediction"),
        );
        assert!(got > 0.0, "mu {mu}: {got}");
        assert!(
            (got / pred - 1.0).abs() < 0.1,
            "mu {mu}: {got} vs predicted {pred}"
        );
        // With the scene's 1% global damping on every mode the other modes keep
        // Re/|λ| = -ζ = -0.01 to within the friction's second-order change (< 5% of ζ).
        let r = pick("global + pair", mu);
        let g = num(r, "max_re_over_abs_other_modes");
        assert!((g + 0.01).abs() < 5e-4, "mu {mu}: {g}");
        assert_eq!(num(r, "unstable_other_modes_in_band"), 0.0);
    }
    // Undamped at mu = 0: eq (21) with D = 0 and symmetric stiffness has imaginary
    // eigenvalues; the eigensolver's error is ~ε ω_max, ~1e-11 relative to a 4 kHz mode.
    let r = pick("undamped", 0.0);
    assert!(num(r, "max_re_over_abs_other_modes").abs() < 1e-9);
    // Growth of second order: slope 2 of ln(Re/|λ|) against ln mu over 1e-3..1e-2.
    let summary = csv(&out.join("study/paradox_summary.csv"));
    let s = summary
        .iter()
        .find(|r| r["case"].starts_with("pair only"))
        .unwrap();
    let slope = num(s, "slope_log_re_vs_log_mu");
    assert!((slope - 2.0).abs() < 0.1, "slope {slope}");
    assert_eq!(s["is_the_pair"], "no");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_mesh_study_reproduces_the_stability_command_on_the_same_meshes() {
    // Same meshes, interface, damping and friction grid through two code paths (the mesh
    // study's cached per-level reduction and `squeal stability`): the Hopf points agree to the
    // refinement's bracket (1e-8), up to the reduction's round-off.
    let dir = temp_dir("mesh");
    let scene = coarse_scene(&dir);
    let out = dir.join("out");
    let s = out.to_str().unwrap();
    squeal(&[
        "study",
        scene.to_str().unwrap(),
        "--kind",
        "mesh",
        "--levels",
        "coarse",
        "--mu",
        "0..0.5/11",
        "--out",
        s,
    ]);
    squeal(&[
        "stability",
        scene.to_str().unwrap(),
        "--mu",
        "0..0.5/11",
        "--out",
        s,
        "--no-vtu",
    ]);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("stability/summary.json")).unwrap())
            .unwrap();
    let mu0 = summary["mu0"].as_f64().unwrap();
    let rows = csv(&out.join("study/mesh.csv"));
    let patch = rows.iter().find(|r| r["interface"] == "patch").unwrap();
    let m = num(patch, "mu0");
    assert!((m - mu0).abs() < 1e-6, "mesh study {m} vs stability {mu0}");
    // The node-contact brake of the same level exists and was analysed.
    assert!(rows.iter().any(|r| r["interface"] == "node"));
    let _ = std::fs::remove_dir_all(&dir);
}
