//! `squeal study --kind convergence` on the bundled brake's coarse meshes, at a cheap setting:
//! two levels of the contact knob (3 × 3 → 3 × 5 patches) and of the modes knob (50 → 75 per
//! part), 31 friction values on 0.3…0.6. Checks the table's structure, that the base level is
//! the scene itself (the pinned coarse μ0), and that each verdict is the one its recorded
//! values call for.

use super::common;

use serde_json::Value;

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

#[test]
fn the_convergence_study_tabulates_each_knob_and_its_verdict_follows_the_recorded_values() {
    let dir = common::temp_dir("convergence", "coarse");
    let scene = dir.join("brake_coarse.toml");
    std::fs::write(&scene, common::bundled_scene("coarse")).unwrap();
    let out = dir.join("out");
    let (scene, outs) = (scene.to_str().unwrap(), out.to_str().unwrap());
    let args = [
        "study",
        scene,
        "--kind",
        "convergence",
        "--knobs",
        "contact,modes",
        "--grids",
        "3x5",
        "--mode-factors",
        "1.5",
        "--mu",
        "0.3..0.6/31",
        "--out",
        outs,
    ];
    let stdout = common::run_ok(&args);
    // Progress lines, then the verdict before the table.
    assert!(stdout.contains("level 3/3: "), "{stdout}");
    let verdict_at = stdout
        .find("Convergence of the Hopf point: ")
        .expect("verdict");
    let table_at = stdout.find("reduced_dofs").expect("table");
    assert!(verdict_at < table_at, "{stdout}");

    let study = out.join("study");
    for f in [
        "convergence.csv",
        "convergence.md",
        "convergence.json",
        "convergence.svg",
        "convergence.png",
    ] {
        assert!(study.join(f).is_file(), "{f} missing");
    }
    let csv = std::fs::read_to_string(study.join("convergence.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert!(
        lines[0].starts_with(
            "knob,level,reduced_dofs,nodes,contact_pairs,mu0,frequency_hz,growth_per_s_at_mu_"
        ),
        "{}",
        lines[0]
    );
    assert_eq!(lines.len(), 5, "header and two rows per knob:\n{csv}");

    let j: Value =
        serde_json::from_str(&std::fs::read_to_string(study.join("convergence.json")).unwrap())
            .unwrap();
    let knobs = j["knobs"].as_array().unwrap();
    let names: Vec<&str> = knobs.iter().map(|k| k["knob"].as_str().unwrap()).collect();
    assert_eq!(names, ["contact", "modes"]);
    let tol = num(&j["tolerance"]);
    assert_eq!(tol, 0.001);
    let labels = |k: &Value| -> Vec<String> {
        k["levels"]
            .as_array()
            .unwrap()
            .iter()
            .map(|l| l["level"].as_str().unwrap().to_string())
            .collect()
    };
    assert_eq!(labels(&knobs[0]), ["3x3 patches", "3x5 patches"]);
    assert_eq!(labels(&knobs[1]), ["50 modes (x1)", "75 modes (x1.5)"]);

    // The base level is the scene itself: the pinned coarse Hopf point (docs/verification.md,
    // 0.46182266 at 4061.48 Hz from `squeal stability` on the same sweep), to the pinned
    // digits (1e-8 absolute: 8 decimals given), and the same level heads both knobs.
    let base = &knobs[0]["levels"][0];
    assert!((num(&base["mu0"]) - 0.46182266).abs() < 1e-8, "{base}");
    assert!(
        (num(&base["frequency_hz"]) - 4061.48).abs() < 5e-3,
        "{base}"
    );
    assert_eq!(base["mu0"], knobs[1]["levels"][0]["mu0"]);
    assert_eq!(base["reduced_dofs"], knobs[1]["levels"][0]["reduced_dofs"]);
    // The scene's [chbm] mu_ratio 1.02 on the base mu0: the base grows there.
    let gmu = num(&j["growth_mu"]);
    assert!((gmu - 1.02 * num(&base["mu0"])).abs() < 1e-15, "{gmu}");
    assert!(num(&base["growth_per_s"]) > 0.0, "{base}");
    // A finer grid has more contact pairs and dofs; more modes more dofs, same pairs.
    let lv = |k: usize, i: usize| &knobs[k]["levels"][i];
    assert_eq!(base["contact_pairs"], 9);
    assert_eq!(lv(0, 1)["contact_pairs"], 15);
    assert!(num(&lv(0, 1)["reduced_dofs"]) > num(&base["reduced_dofs"]));
    assert_eq!(
        num(&lv(1, 1)["reduced_dofs"]) - num(&base["reduced_dofs"]),
        2.0 * 25.0
    );

    for k in knobs {
        let levels = k["levels"].as_array().unwrap();
        for l in levels {
            // The kinetic energy shares of the parts add up to 1: the brake's mass matrix is
            // block diagonal (the parts touch through springs only), so to round-off.
            let e: f64 = l["kinetic_energy_share"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| num(&p["share"]))
                .sum();
            assert!((e - 1.0).abs() < 1e-9, "{l}");
            assert!(l["nodal_diameters"].is_u64(), "{l}");
        }
        assert!(levels[0]["mac_vs_previous"].is_null());
        let mac = num(&levels[1]["mac_vs_previous"]);
        assert!((0.0..=1.0 + 1e-12).contains(&mac), "{mac}");
        // The verdict is the one the recorded values call for: with two levels the estimated
        // error is the relative change of mu0 (recomputed from the JSON's values, which read
        // back with their bits: to 1e-15); below the tolerance and the same unstable mode
        // (MAC >= 0.9) is converged, else not.
        let (m0, m1) = (num(&levels[0]["mu0"]), num(&levels[1]["mu0"]));
        let change = (m1 - m0) / m0;
        let v = &k["verdict"];
        assert!((num(&v["last_change"]) - change).abs() < 1e-15, "{v}");
        let expect = if change.abs() < tol && mac >= 0.9 {
            "converged"
        } else {
            "not converged"
        };
        assert_eq!(v["status"], expect, "{v}");
        assert!(v["rate"].is_null(), "two levels have no observed rate");
        let text = v["text"].as_str().unwrap();
        assert!(
            text.starts_with(&format!(
                "{expect}: mu0 moved {:.2} %",
                100.0 * change.abs()
            )),
            "{text}"
        );
    }
    let all_converged = knobs.iter().all(|k| k["verdict"]["status"] == "converged");
    let overall = j["overall"]["status"].as_str().unwrap();
    assert_eq!(
        overall,
        if all_converged {
            "converged"
        } else {
            "not converged"
        }
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_convergence_study_is_not_sharded_and_bad_levels_are_usage_errors() {
    let dir = common::temp_dir("convergence", "errors");
    let scene = dir.join("brake_coarse.toml");
    std::fs::write(&scene, common::bundled_scene("coarse")).unwrap();
    let s = scene.to_str().unwrap();
    let out = common::squeal(&[
        "study",
        s,
        "--kind",
        "convergence",
        "--shard",
        "1/2",
        "--out",
        dir.join("o").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("not split into shards") && err.contains("without --shard"),
        "{err}"
    );
    for (flag, bad, says) in [
        ("--grids", "3x0", "patch grid such as 3x5"),
        ("--knobs", "wheels", "contact, modes or mesh"),
    ] {
        let out = common::squeal(&["study", s, "--kind", "convergence", flag, bad]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(says), "{err}");
    }
    // A mesh level without files is named before any reduction.
    let out = common::squeal(&[
        "study",
        s,
        "--kind",
        "convergence",
        "--levels",
        "coarse,huge",
        "--out",
        dir.join("o").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("disc_huge.inp"), "{err}");
    assert!(!dir.join("o/study/convergence").exists(), "nothing reduced");
    let _ = std::fs::remove_dir_all(&dir);
}
