//! The comparison's reference on the bundled coarse brake (issue #22): the brake's periodic
//! orbit by shooting at 1.1 μ0, where the contact opens for about a third of the cycle. Its
//! periodicity residual, its Floquet check (the multiplier 1: `M f = f` along the orbit) and
//! its stated own error are read from `summary.json`, and the reference must be more accurate
//! than the CHBM cycles it judges.

use super::common;

use common::{bundled_scene, run_ok, temp_dir};

fn number(v: &serde_json::Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing in {v}"))
}

#[test]
fn the_coarse_brakes_reference_orbit_is_periodic_and_keeps_the_multiplier_one() {
    let dir = temp_dir("compare", "reference");
    let scene = dir.join("brake.toml");
    std::fs::write(&scene, bundled_scene("coarse")).unwrap();
    let out = dir.join("out");
    run_ok(&[
        "compare",
        scene.to_str().unwrap(),
        "--mu-ratio",
        "1.1",
        "--harmonics",
        "3,10",
        "--rtol",
        "1e-6",
        "-o",
        out.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(out.join("compare/summary.json")).unwrap();
    let s: serde_json::Value = serde_json::from_str(&text).unwrap();
    let c = &s["comparisons"][0];
    let r = &c["reference"];
    eprintln!("{r:#}");
    // Newton stops at a relative periodicity residual of 300 rtol = 3e-8
    // (ShootingReferenceOptions::tol_factor; 9.9e-9 measured with 100 rtol).
    let residual = number(r, "periodicity_residual");
    assert!(residual <= 3e-8, "periodicity residual {residual}");
    // The multiplier 1: |M f - f| / |f| along the orbit, one column of the variational
    // equations at rtol 1e-10 over one period. It is about the periodicity residual times the
    // ratio of the stiff modes' rates to the cycle's (2e-6 measured on the medium brake for
    // residuals of 2e-9 and 9e-9; 1.3e-6 on the coarse one); 1e-4 allows the residual's 3e-8
    // bound times 3e3.
    let tangent = number(r, "floquet_tangent_error");
    assert!(tangent < 1e-4, "M f - f: {tangent}");
    // The reference's stated own error (its difference from the orbit at rtol 1e-9) is far
    // below what it judges: a tenth of CHBM 10H's displacement error at most.
    let stated = number(&r["estimated_error_all"], "err_disp");
    let chbm10 = number(&c["chbm"][1], "err_disp_all");
    assert!(stated < 0.1 * chbm10, "stated {stated}, CHBM 10H {chbm10}");
    let _ = std::fs::remove_dir_all(&dir);
}
