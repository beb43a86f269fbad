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
