//! Issue 22 leftovers: a Ctrl-C (SIGINT) or a closed output pipe (`| head -1`) leaves no
//! partial file and no stale lock in the output folder, and `stability.csv` says the damping it
//! used.

use super::common;

use common::{bundled_scene, root, squeal, temp_dir};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// `squeal stability` of the coarse bundled scene over `mu`, into `out` of a fresh folder named
/// after `name`, standard output to `stdout`, standard error piped: the run, its folder and
/// the scene.
fn start_stability(name: &str, mu: &str, stdout: Stdio) -> (Child, PathBuf, PathBuf) {
    let dir = temp_dir("interrupt", name);
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, bundled_scene("coarse")).unwrap();
    let out = dir.join("out");
    let child = Command::new(env!("CARGO_BIN_EXE_squeal"))
        .args(["stability", scene.to_str().unwrap(), "--mu", mu])
        .args(["--no-vtu", "-o", out.to_str().unwrap()])
        .current_dir(root())
        .stdout(stdout)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    (child, dir, scene)
}

/// `squeal stability scene --mu 0..0.1/3 --no-vtu -o out` to its end (about 2 s).
fn quick_stability(scene: &Path, out: &Path) -> std::process::Output {
    squeal(&[
        "stability",
        scene.to_str().unwrap(),
        "--mu",
        "0..0.1/3",
        "--no-vtu",
        "-o",
        out.to_str().unwrap(),
    ])
}

/// The manifest of the output folder `out` of a stopped run, which must leave neither its
/// lock nor a temporary file.
fn left_clean(out: &Path) -> serde_json::Value {
    let names: Vec<String> = std::fs::read_dir(out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(!names.iter().any(|n| n == ".squeal-lock"), "{names:?}");
    assert!(!names.iter().any(|n| n.contains(".tmp-")), "{names:?}");
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("squeal-manifest.json")).unwrap())
            .unwrap();
    assert!(manifest["runs"][0]["ended"].is_string(), "{manifest}");
    manifest
}

/// Before: `squeal stability` died of the signal (no exit status), leaving `.squeal-lock` and
/// a manifest that still said "running" (and any `.NAME.tmp-...` file being written). Now it
/// exits 130, the lock is gone, no temporary file is left, the manifest says the run was
/// interrupted, and every file in the folder is one the manifest knows (so the next run needs
/// no --force).
#[cfg(unix)]
#[test]
fn ctrl_c_leaves_no_partial_output_and_no_lock() {
    // A long sweep, so that the signal comes while the run works (reduction, then sweep).
    let (mut child, dir, _) = start_stability("sigint", "0..1/20001", Stdio::null());
    let out = dir.join("out");
    let t = Instant::now();
    while !out.join(".squeal-lock").exists() {
        assert!(
            t.elapsed() < Duration::from_secs(60),
            "the run never took its folder"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(1500));
    assert!(
        child.try_wait().unwrap().is_none(),
        "the run ended before the signal: make its sweep longer"
    );
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(130), "{:?}: {err}", o.status);
    assert!(err.contains("interrupted (Ctrl-C)"), "{err}");

    let manifest = left_clean(&out);
    let status = manifest["runs"][0]["status"].as_str().unwrap();
    assert!(status.contains("interrupted"), "{status}");
    // Every file left (recursively) is one the manifest says this run wrote.
    let mut stack = vec![out.clone()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
                continue;
            }
            let rel = p
                .strip_prefix(&out)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            if rel != "squeal-manifest.json" {
                assert_eq!(manifest["files"][&rel]["run"], 1, "{rel}: {manifest}");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `squeal stability ... | head -1`: the reader takes the first line and closes the pipe.
/// Before: the next `println!` panicked on EPIPE ("thread 'main' panicked at ...stdio.rs:
/// failed printing to stdout: Broken pipe", a backtrace with RUST_BACKTRACE), the exit status
/// was 101 and the folder kept `.squeal-lock` and a manifest saying "running". Now the run
/// stops as on Ctrl-C: exit 141 (128 + SIGPIPE), one line on standard error without Rust's
/// panic text, no lock, no temporary file, the manifest says the run was interrupted because
/// the standard output was closed.
#[cfg(unix)]
#[test]
fn a_closed_output_pipe_ends_the_run_cleanly() {
    use std::io::BufRead;
    let (mut child, dir, scene) = start_stability("pipe", "0..0.1/3", Stdio::piped());
    let out = dir.join("out");
    let mut first = String::new();
    std::io::BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    // The reader is dropped here: the pipe is closed after the first line, as `head -1` does.
    assert!(first.starts_with("reduced model"), "{first}");
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(141), "{:?}: {err}", o.status);
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: the standard output was closed before the run ended"),
        "{err}"
    );
    for bad in ["panicked", "stdio.rs", "os error", "stack backtrace"] {
        assert!(!err.contains(bad), "{bad}: {err}");
    }
    let manifest = left_clean(&out);
    assert_eq!(
        manifest["runs"][0]["status"], "interrupted (the standard output was closed)",
        "{manifest}"
    );
    // The next run into the folder needs no --force and finds no unfinished run.
    let o = quick_stability(&scene, &out);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(!err.contains("did not finish"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Before: stability.csv's columns were mu, the branches and the unstable counts; the damping
/// of the sweep (eqs 12-13) was said in the summary and summary.json only. Now its last column
/// is the ratio on every mode, as the scene gives it (meshes/brake.toml: 0.01).
#[test]
fn stability_csv_says_the_damping_used() {
    let dir = temp_dir("interrupt", "damping");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, bundled_scene("coarse")).unwrap();
    let out = dir.join("out");
    let o = quick_stability(&scene, &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(out.join("stability/stability.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let k = header
        .iter()
        .position(|h| *h == "damping_ratio_all_modes")
        .unwrap_or_else(|| panic!("{header:?}"));
    for l in lines {
        let v: f64 = l.split(',').nth(k).unwrap().parse().unwrap();
        assert_eq!(v, 0.01, "{l}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
