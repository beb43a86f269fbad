//! One scene, one limit cycle: `squeal chbm scene.toml` and `squeal run scene.toml` compute the
//! scene's cycle (`[chbm]`: 1.02 μ0 with 3 harmonics in the bundled scene) the same way —
//! along the branch from the Hopf point — and write the same Fourier coefficients, bit for bit.

use super::common;
use common::{bundled_scene, run_ok, temp_dir};

#[test]
fn chbm_and_run_give_the_same_cycle_bit_for_bit() {
    let dir = temp_dir("cycle", "same");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, bundled_scene("coarse")).unwrap();
    let s = scene.to_str().unwrap();
    let out = dir.join("out");
    let o = out.to_str().unwrap();

    let run = run_ok(&["run", s, "--no-compare", "-o", o]);
    assert!(run.contains("(1.0200 mu0), along the branch"), "{run}");
    let coefficients = out.join("chbm/coefficients.csv");
    let from_run = std::fs::read(&coefficients).unwrap();
    let json_run = std::fs::read_to_string(out.join("chbm/chbm.json")).unwrap();

    let chbm = run_ok(&["chbm", s, "-o", o, "--no-vtu"]);
    assert!(chbm.contains("(1.0200 mu0), along the branch"), "{chbm}");
    assert!(chbm.contains("CHBM starts from cycle 1 (stable)"), "{chbm}");
    let from_chbm = std::fs::read(&coefficients).unwrap();
    // Every coefficient is written in Rust's shortest round-trip form, so equal files are
    // equal bits.
    assert!(
        from_run == from_chbm,
        "squeal run and squeal chbm wrote different coefficients"
    );
    let harmonics = |j: &str| {
        let v: serde_json::Value = serde_json::from_str(j).unwrap();
        (
            v["harmonics"].as_u64(),
            v["mu"].as_f64(),
            v["converged"].as_bool(),
        )
    };
    let json_chbm = std::fs::read_to_string(out.join("chbm/chbm.json")).unwrap();
    assert_eq!(harmonics(&json_run), harmonics(&json_chbm));
    assert_eq!(harmonics(&json_run).0, Some(3));
    assert_eq!(harmonics(&json_run).2, Some(true));
    std::fs::remove_dir_all(&dir).ok();
}
