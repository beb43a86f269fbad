//! `squeal study --shard i/n` and `--merge` on the bundled brake's coarse meshes: the merged
//! tables and figures are the unsplit run's, byte for byte; the merge refuses missing, mixed,
//! stale and inconsistent shards; bad `--shard` values are usage errors.

use super::common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The bundled scene on the coarse meshes (absolute paths), written to `dir`.
fn coarse_scene(dir: &Path) -> PathBuf {
    let path = dir.join("brake_coarse.toml");
    std::fs::write(&path, common::bundled_scene("coarse")).unwrap();
    path
}

/// Runs `squeal`, which must succeed.
fn squeal(args: &[&str]) {
    let out = common::squeal(args);
    assert!(
        out.status.success(),
        "squeal {args:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Runs `squeal`, which must fail with exit code `code`; its stderr.
fn squeal_fails(args: &[&str], code: i32) -> String {
    let out = common::squeal(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(code), "squeal {args:?}:\n{err}");
    err
}

/// Every file under `dir` (path relative to it -> bytes), outside the folders `skip`.
fn files(dir: &Path, skip: &[&str]) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut all = BTreeMap::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                if !skip.iter().any(|s| p.file_name().unwrap() == *s) {
                    todo.push(p);
                }
            } else {
                let rel = p.strip_prefix(dir).unwrap().to_path_buf();
                all.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    all
}

/// The outputs of two runs are the same files with the same bytes: the merge and the unsplit
/// run share the writer, and every value goes through the shard files with its bits.
fn assert_same_files(whole: &Path, merged: &Path, skip: &[&str], expected: usize) {
    let (a, b) = (files(whole, skip), files(merged, skip));
    assert_eq!(
        a.keys().collect::<Vec<_>>(),
        b.keys().collect::<Vec<_>>(),
        "other files"
    );
    assert_eq!(a.len(), expected, "{:?}", a.keys());
    for (name, bytes) in &a {
        assert!(*bytes == b[name], "{} differs", name.display());
    }
}

#[test]
fn three_shards_merge_to_the_unsplit_study_byte_for_byte_and_bad_shards_are_refused() {
    let dir = common::temp_dir("shards", "all");
    let scene = coarse_scene(&dir);
    let scene = scene.to_str().unwrap();
    let (whole, split) = (dir.join("whole"), dir.join("split"));
    // Coarse: the nominal sweep finds mu0 = 0.46 on 11 values; every study and writer runs.
    let study = [
        "study",
        scene,
        "--kind",
        "all",
        "--mu",
        "0..0.5/11",
        "--out",
    ];
    let with = |out: &Path, extra: &[&str]| -> Vec<String> {
        study
            .iter()
            .map(|s| s.to_string())
            .chain([out.to_str().unwrap().to_string()])
            .chain(extra.iter().map(|s| s.to_string()))
            .collect()
    };
    let run = |args: Vec<String>| squeal(&args.iter().map(String::as_str).collect::<Vec<_>>());
    let fails =
        |args: Vec<String>| squeal_fails(&args.iter().map(String::as_str).collect::<Vec<_>>(), 1);
    run(with(&whole, &[]));
    // The shards load the unsplit run's reduction instead of reducing again.
    std::fs::create_dir_all(&split).unwrap();
    std::fs::copy(whole.join("brake.rom"), split.join("brake.rom")).unwrap();
    for i in 1..=3 {
        run(with(&split, &["--shard", &format!("{i}/3")]));
    }
    run(with(&split, &["--merge"]));
    // Coupled modes (2 files), pressure, stiffness, damping (5 each), paradox (5).
    assert_same_files(&whole.join("study"), &split.join("study"), &["shards"], 22);

    let shards = split.join("study/shards");
    let merged = files(&split.join("study"), &["shards"]);
    // A missing shard is named.
    let s2 = shards.join("all-2-of-3.json");
    let aside = dir.join("aside.json");
    std::fs::rename(&s2, &aside).unwrap();
    let e = fails(with(&split, &["--merge"]));
    assert!(e.contains("shard 2/3 of the all study missing"), "{e}");
    std::fs::rename(&aside, &s2).unwrap();
    // Shards of two splits in one folder.
    let other = shards.join("all-1-of-2.json");
    std::fs::copy(shards.join("all-1-of-3.json"), &other).unwrap();
    let e = fails(with(&split, &["--merge"]));
    assert!(e.contains("splits into 2 and 3 shards"), "{e}");
    std::fs::remove_file(&other).unwrap();
    // Other friction values than the shards'.
    let e = squeal_fails(
        &[
            "study",
            scene,
            "--kind",
            "all",
            "--mu",
            "0..0.5/12",
            "--out",
            split.to_str().unwrap(),
            "--merge",
        ],
        1,
    );
    assert!(e.contains("other friction values"), "{e}");
    // A shard whose nominal Hopf point differs by one unit in the last place from shard 1's.
    let s3 = shards.join("all-3-of-3.json");
    let text = std::fs::read_to_string(&s3).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mu0 = &mut v["nominal"]["outcome"]["mu0"];
    *mu0 = serde_json::json!(f64::from_bits(mu0.as_f64().unwrap().to_bits() + 1));
    std::fs::write(&s3, serde_json::to_string(&v).unwrap()).unwrap();
    let e = fails(with(&split, &["--merge"]));
    assert!(
        e.contains("all-3-of-3.json") && e.contains("differs from shard 1"),
        "{e}"
    );
    std::fs::write(&s3, text.clone()).unwrap();
    // A shard computed by another version of squeal.
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["squeal_version"] = serde_json::json!("squeal 0.0.1");
    std::fs::write(&s3, serde_json::to_string(&v).unwrap()).unwrap();
    let e = fails(with(&split, &["--merge"]));
    assert!(
        e.contains("all-3-of-3.json") && e.contains("computed by squeal 0.0.1"),
        "{e}"
    );
    std::fs::write(&s3, text).unwrap();
    // The scene changed since the shards ran.
    let mut edited = std::fs::read_to_string(scene).unwrap();
    edited.push_str("# edited\n");
    std::fs::write(scene, edited).unwrap();
    let e = fails(with(&split, &["--merge"]));
    assert!(e.contains("stale shard: the scene file has changed"), "{e}");
    // The refused merges wrote nothing.
    assert!(files(&split.join("study"), &["shards"]) == merged);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_mesh_study_splits_by_level_and_merges_to_the_unsplit_one() {
    let dir = common::temp_dir("shards", "mesh");
    let scene = coarse_scene(&dir);
    let (whole, split) = (dir.join("whole"), dir.join("split"));
    let run = |out: &Path, extra: &[&str]| {
        let mut args = vec![
            "study",
            scene.to_str().unwrap(),
            "--kind",
            "mesh",
            "--levels",
            "coarse",
            "--mu",
            "0..0.5/11",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend(extra);
        squeal(&args);
    };
    run(&whole, &[]);
    // The shards load the unsplit run's reductions (patch and node contact).
    let mesh = split.join("study/mesh");
    std::fs::create_dir_all(&mesh).unwrap();
    for f in ["brake_coarse_patch.rom", "brake_coarse_node.rom"] {
        std::fs::copy(whole.join("study/mesh").join(f), mesh.join(f)).unwrap();
    }
    // One level for two shards: shard 2 has no unit, and the merge still takes it.
    run(&split, &["--shard", "1/2"]);
    run(&split, &["--shard", "2/2"]);
    run(&split, &["--merge"]);
    // mesh.csv, .md, .svg, .png (the cached reductions in study/mesh are not outputs).
    assert_same_files(
        &whole.join("study"),
        &split.join("study"),
        &["shards", "mesh"],
        4,
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_shard_values_are_usage_errors_naming_the_argument() {
    // clap checks --shard before any file is read: the scene need not exist.
    for (bad, says) in [
        ("0/3", "numbered from 1"),
        ("4/3", "no shard 4 of 3"),
        ("3/0", "at least 1"),
        ("2", "not i/n"),
        ("x/2", "not a whole number"),
    ] {
        let e = squeal_fails(&["study", "none.toml", "--shard", bad], 2);
        assert!(e.contains("--shard") && e.contains(says), "{bad}: {e}");
    }
    let e = squeal_fails(&["study", "none.toml", "--shard", "1/2", "--merge"], 2);
    assert!(e.contains("cannot be used with"), "{e}");
}
