//! The broken-scene corpus (`tests/data/broken`, also the seeds of the `scene` fuzz target):
//! each file must fail to read, or fail in the accessor a command calls first, with an error
//! that names the file, the line where the bad value is (where there is one) and what is
//! wrong, as `MANIFEST` lists. Never a panic.

use squeal_scene::Scene;
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/broken")
        .join(name)
}

/// The first error reading `path` and then asking what `squeal run` asks of a scene.
fn first_error(path: &Path) -> Option<String> {
    let scene = match Scene::read(path) {
        Ok(s) => s,
        Err(e) => return Some(e.to_string()),
    };
    let checks = [
        scene.mu_values().err(),
        scene.stiffness().err(),
        scene.pair().err(),
        scene.rotation().err(),
        scene.normal().err(),
        scene.sliding().err(),
        scene.disc_angular_speed().err(),
    ];
    checks.into_iter().flatten().next().map(|e| e.to_string())
}

#[test]
fn every_broken_scene_says_where_and_what() {
    let manifest = std::fs::read_to_string(data("MANIFEST")).unwrap();
    let mut listed = Vec::new();
    for line in manifest
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
    {
        let fields: Vec<&str> = line.split(" | ").map(str::trim).collect();
        let [file, place, fragment] = fields[..] else {
            panic!("MANIFEST line {line:?}: expected file | where | fragment");
        };
        listed.push(file.to_string());
        let path = data(file);
        let Some(message) = first_error(&path) else {
            panic!("{file} read without an error");
        };
        // The message starts with `file:line:` (a value, or `file:line:column:` for the
        // TOML syntax), or `file: ` for the file as a whole.
        let expected = match place.rsplit_once(':') {
            Some((f, "-")) => format!("{}: ", data(f).display()),
            Some((f, n)) => format!("{}:{n}:", data(f).display()),
            None => panic!("MANIFEST: where {place:?} is not FILE:LINE or FILE:-"),
        };
        assert!(
            message.starts_with(&expected),
            "{file}: expected the error at {place}, got: {message}"
        );
        assert!(
            message.contains(fragment),
            "{file}: expected {fragment:?} in: {message}"
        );
    }
    // Every file of the corpus is listed, so none is silently skipped.
    let mut files: Vec<String> = std::fs::read_dir(data(""))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|f| f != "MANIFEST")
        .collect();
    files.sort();
    listed.sort();
    assert_eq!(files, listed, "MANIFEST and the folder disagree");
}

/// Prints the errors, for writing MANIFEST entries (`-- --ignored --nocapture`).
#[test]
#[ignore = "a listing, not a check"]
fn print_errors() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(data(""))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    for f in files {
        println!("{}: {:?}", f.display(), first_error(&f));
    }
}

/// Values possible but far from a brake read with a warning at their line (issue 22): the
/// scene is `damping.toml` with its fault removed and one implausible value.
#[test]
fn implausible_values_warn_with_file_line_and_key() {
    // damping.toml is the bundled scene (without its comments) with one fault, mended here.
    let path = data("damping.toml");
    let base = std::fs::read_to_string(&path)
        .unwrap()
        .replace("global_ratio = -0.01", "global_ratio = 0.01");
    let clean = Scene::parse(&path, base.clone()).unwrap();
    assert_eq!(clean.plausibility_warnings().unwrap(), Vec::<String>::new());
    for (old, new, line, says) in [
        (
            "line_pressure_bar = 11.94",
            "line_pressure_bar = 400",
            14,
            "piston.line_pressure_bar: 400 bar is above",
        ),
        (
            "global_ratio = 0.01",
            "global_ratio = 0.5",
            17,
            "damping.global_ratio: 0.5 is 50 % modal damping",
        ),
        (
            "normal = [0.0, 0.0, 1.0]",
            "normal = [0.0, 0.0, 1.0]\ninitial_gap = 1.0",
            9,
            "contact.initial_gap: a gap of 1e0 m",
        ),
        (
            "mu = \"0..1/201\"",
            "mu = \"0..3/201\"",
            21,
            "stability.mu: the sweep reaches mu = 3",
        ),
    ] {
        let text = base.replace(old, new);
        let s = Scene::parse(&path, text).unwrap();
        let w = s.plausibility_warnings().unwrap();
        assert_eq!(w.len(), 1, "{new}: {w:?}");
        let at = format!("{}:{line}: ", path.display());
        assert!(w[0].starts_with(&at) && w[0].contains(says), "{new}: {w:?}");
    }
}

/// A cubic stiffness of -0 is a linear law: it reaches the model as +0 (no minus sign that
/// the positivity check let through).
#[test]
fn a_cubic_stiffness_of_minus_zero_is_zero() {
    let path = data("damping.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("global_ratio = -0.01", "global_ratio = 0.01")
        .replace(
            "compression_curve = { closure_um = [5, 10, 15, 20, 25, 30, 35, 40], pressure_mpa = [0.065, 0.145, 0.255, 0.410, 0.625, 0.915, 1.295, 1.780] }",
            "k_linear_per_area = 1.25e10\nk_cubic_per_area = -0.0",
        );
    let (kl, knl, _) = Scene::parse(&path, text).unwrap().stiffness().unwrap();
    assert_eq!(kl, 1.25e10);
    assert!(knl == 0.0 && knl.is_sign_positive(), "{knl}");
}
