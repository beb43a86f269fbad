//! Helpers shared by the end-to-end tests: the repository root, a per-test temporary folder,
//! the `squeal` binary, and the bundled scene pointed at another mesh level.

#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh folder under the system's temporary folder, unique to this test process.
pub fn temp_dir(prefix: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("squeal-{prefix}-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs the `squeal` binary built for these tests.
pub fn squeal(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_squeal"))
        .args(args)
        .output()
        .unwrap()
}

/// Runs the `squeal` binary and returns its standard output; fails the test, with both
/// outputs, when it exits non-zero.
pub fn run_ok(args: &[&str]) -> String {
    let out = squeal(args);
    assert!(
        out.status.success(),
        "squeal {args:?} failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The text of `meshes/brake.toml` with its disc and pad meshes at `level`, as absolute paths
/// (so the scene can be written elsewhere; the mesh study finds the other levels by the
/// `_<level>` suffix).
pub fn bundled_scene(level: &str) -> String {
    let text = std::fs::read_to_string(root().join("meshes/brake.toml")).unwrap();
    let meshes = root().join("meshes");
    let mut replaced = 0;
    let out: Vec<String> = text
        .lines()
        .map(|l| {
            for part in ["disc", "pad"] {
                if l.starts_with(&format!("{part} = ")) {
                    replaced += 1;
                    let mesh = meshes.join(format!("{part}_{level}.inp"));
                    return format!("{part} = {:?}", mesh.display().to_string());
                }
            }
            l.to_string()
        })
        .collect();
    // A test must not silently run the scene's own (medium) meshes.
    assert_eq!(replaced, 2, "meshes/brake.toml lost its disc/pad lines");
    out.join("\n") + "\n"
}

/// The text of `meshes/two_pad/brake.toml` with its meshes at `level`, as absolute paths.
pub fn two_pad_scene(level: &str) -> String {
    let two = root().join("meshes/two_pad");
    let abs = |p: PathBuf| format!("{:?}", p.display().to_string());
    let text = std::fs::read_to_string(two.join("brake.toml")).unwrap();
    let out = text
        .replace(
            "\"disc_medium.inp\"",
            &abs(two.join(format!("disc_{level}.inp"))),
        )
        .replace(
            "\"../pad_medium.inp\"",
            &abs(root().join(format!("meshes/pad_{level}.inp"))),
        )
        .replace(
            "\"outboard_medium.inp\"",
            &abs(two.join(format!("outboard_{level}.inp"))),
        );
    // A test must not silently run the scene's own (medium) meshes.
    assert!(
        !out.contains("_medium.inp"),
        "meshes/two_pad/brake.toml lost its mesh lines"
    );
    out
}
