//! Issue 21, item 4: a pad pressed over its whole back face with that face held in-plane (as
//! the vendor demo does) is not held: pitch and roll are free. Before, `squeal stability`
//! reduced the disc, then failed at the pad's factorization with "the interior stiffness K_II
//! is singular ... (check its restraints: ...)", naming no motion, and threw the disc's
//! reduction away. Now it stops before any reduction with the free motions, the scene keys
//! that hold the pad (file:line) and what to add.

use super::common;

use common::{bundled_scene, squeal, temp_dir};

/// The coarse pad's back face is the plane z = 35 mm.
const BACK_FACE: &str =
    "{ facing = [0, 0, 1], plane = { point = [0, 0, 0.035], normal = [0, 0, 1] } }";

#[test]
fn an_under_restrained_pad_is_refused_before_any_reduction_with_its_free_motions_named() {
    let dir = temp_dir("restraints", "pitch-roll");
    let scene = dir.join("scene.toml");
    let text = format!(
        "{}\n[sets.pad]\npistons = {BACK_FACE}\nabutments = {BACK_FACE}\n",
        bundled_scene("coarse")
    );
    std::fs::write(&scene, &text).unwrap();
    let line = |key: &str| {
        1 + text
            .lines()
            .position(|l| l.starts_with(key))
            .expect("the key is in the scene")
    };
    let out = dir.join("out");
    let o = squeal(&[
        "stability",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(1), "{err}");
    // The free motions: rotations about x and y (the pad's pitch and roll) through the back
    // face (z = 0.035 m).
    for says in [
        "pad: the part is not held",
        "2 rigid-body motion(s) free",
        "rotation about x through (",
        "rotation about y through (",
        "0.035000) m",
        &format!("sets.pad.pistons ({}:{}", scene.display(), line("pistons")),
        &format!(
            "sets.pad.abutments ({}:{}",
            scene.display(),
            line("abutments")
        ),
        "pad_coarse.inp",
        "several footprints or points",
    ] {
        assert!(err.contains(says), "{says}: {err}");
    }
    // No Rust debug dump, and no reduction work before the refusal.
    assert!(!err.contains("Set(") && !err.contains("K_II"), "{err}");
    assert!(!err.contains("disc: assemble"), "{err}");
    assert!(!out.join("brake.rom").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
