//! Issue 22: runs into one output folder neither mix nor destroy files unseen.

use super::*;

fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("squeal-folder-{test}-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn info(command: &str) -> RunInfo {
    RunInfo {
        command: command.into(),
        scene: Some((PathBuf::from("brake.toml"), "ab12".into())),
    }
}

/// A folder with a user's own `index.md` is refused (naming the file, the lock released);
/// `force` writes there, and the user's file stays unclaimed.
#[test]
fn a_users_files_are_not_written_over_unless_forced() {
    let dir = scratch("users");
    fs::write(dir.join("index.md"), b"my notes").unwrap();
    fs::create_dir_all(dir.join("data")).unwrap();
    fs::write(dir.join("data/table-1.csv"), b"1,2").unwrap();
    let e = begin(&dir, &info("squeal run brake.toml -o ."), false).unwrap_err();
    let text = e.to_string();
    assert!(
        text.contains("2 file(s) that no squeal run wrote (data/table-1.csv, index.md)")
            && text.contains("--force"),
        "{text}"
    );
    assert!(!dir.join(LOCK).exists() && !dir.join(MANIFEST).exists());
    begin(&dir, &info("squeal run brake.toml -o . --force"), true).unwrap();
    crate::atomic_write_bytes(&dir.join("index.html"), b"report").unwrap();
    finish(Some(&dir), "finished");
    let m = Manifest::read(&dir).unwrap();
    assert_eq!(m.files.keys().collect::<Vec<_>>(), ["index.html"]);
    assert_eq!(m.runs.len(), 1);
    assert_eq!(m.runs[0].status, "finished");
    assert_eq!(m.runs[0].scene_sha256.as_deref(), Some("ab12"));
    assert!(m.runs[0].ended.is_some());
    assert!(!dir.join(LOCK).exists());
    fs::remove_dir_all(&dir).unwrap();
}

/// The manifest claims what each run wrote: a second run is allowed into the folder, and the
/// files of the first that it did not rewrite (nor reuse) are listed as earlier files.
#[test]
fn files_of_an_earlier_run_are_told_apart() {
    let dir = scratch("earlier");
    begin(&dir, &info("squeal run a"), false).unwrap();
    for f in ["index.md", "compare/table1.csv", "brake.rom"] {
        crate::atomic_write_bytes(&dir.join(f), b"run 1").unwrap();
    }
    // A file outside the folder is not the run's.
    let outside = scratch("earlier-outside");
    crate::atomic_write_bytes(&outside.join("x.txt"), b"x").unwrap();
    finish(Some(&dir), "finished");

    begin(&dir, &info("squeal run a --no-compare"), false).unwrap();
    crate::atomic_write_bytes(&dir.join("index.md"), b"run 2").unwrap();
    record_reused(&dir.join("brake.rom"));
    let earlier = earlier_files(&dir);
    assert_eq!(earlier.len(), 1, "{earlier:?}");
    assert_eq!(earlier[0].path, "compare/table1.csv");
    assert_eq!(earlier[0].run, 1);
    // Removing picks only earlier runs' files: never this run's, never a user's.
    fs::write(dir.join("mine.csv"), b"user").unwrap();
    let removed = remove_earlier(&dir, |p| p.ends_with(".csv") || p == "index.md");
    assert_eq!(removed, ["compare/table1.csv"]);
    assert!(dir.join("mine.csv").is_file() && dir.join("index.md").is_file());
    fs::remove_file(dir.join("mine.csv")).unwrap();
    crate::atomic_write_bytes(&dir.join("compare/table1.csv"), b"run 2").unwrap();
    finish(Some(&dir), "finished");
    let m = Manifest::read(&dir).unwrap();
    assert_eq!(m.files["index.md"].run, 2);
    assert_eq!(m.files["compare/table1.csv"].run, 2);
    assert_eq!(m.runs[1].reused, ["brake.rom"]);
    assert!(earlier_files(&dir).is_empty(), "no run active");
    fs::remove_dir_all(&dir).unwrap();
    fs::remove_dir_all(&outside).unwrap();
}

/// A second run into a folder while one runs is refused, naming the lock's host and pid.
#[test]
fn a_second_run_into_a_busy_folder_is_refused() {
    let dir = scratch("busy");
    begin(&dir, &info("squeal run first"), false).unwrap();
    let e = begin(&dir, &info("squeal run second"), false).unwrap_err();
    let me = host::this_process();
    let text = e.to_string();
    assert!(matches!(e, FolderError::Locked { .. }), "{text}");
    assert!(
        text.contains(&format!("host {}, pid {}", me.host, me.pid))
            && text.contains("squeal run first"),
        "{text}"
    );
    finish(Some(&dir), "finished");
    begin(&dir, &info("squeal run third"), false).unwrap();
    finish(Some(&dir), "finished");
    fs::remove_dir_all(&dir).unwrap();
}

fn write_lock(dir: &Path, h: &Holder) {
    fs::write(dir.join(LOCK), serde_json::to_string(h).unwrap()).unwrap();
}

/// A lock left by a process of this machine that is gone (Ctrl-C) is taken over, and its
/// run, still marked running in the manifest, is marked interrupted. Another machine's lock
/// is reported and left in place.
#[cfg(target_os = "linux")]
#[test]
fn a_dead_runs_lock_is_taken_over_and_another_hosts_is_reported() {
    let dir = scratch("stale-lock");
    let me = host::this_process();
    let dead = Holder {
        host: me.host.clone(),
        boot: me.boot.clone(),
        pid_ns: me.pid_ns.clone(),
        pid: u32::MAX,
        started: "2026-11-27T10:00:00Z".into(),
        command: "squeal run killed".into(),
    };
    begin(&dir, &info("squeal run killed"), false).unwrap();
    crate::atomic_write_bytes(&dir.join("a.csv"), b"half a run").unwrap();
    // As a kill leaves it: the run never finished and its lock file stays, holder gone.
    {
        let mut runs = active();
        let i = runs
            .iter()
            .position(|a| a.dir == fs::canonicalize(&dir).unwrap());
        let a = runs.remove(i.unwrap());
        drop(a.lock);
    }
    write_lock(&dir, &dead);
    let notes = begin(&dir, &info("squeal run next"), false).unwrap();
    assert!(
        notes[0].contains("took over the lock") && notes[0].contains("squeal run killed"),
        "{notes:?}"
    );
    assert!(notes[1].contains("did not finish"), "{notes:?}");
    assert_eq!(earlier_files(&dir)[0].path, "a.csv");
    finish(Some(&dir), "finished");
    let m = Manifest::read(&dir).unwrap();
    assert_eq!(m.runs[0].status, "interrupted");

    let elsewhere = Holder {
        host: "node_7".into(),
        boot: "0123456789ab".into(),
        ..dead
    };
    write_lock(&dir, &elsewhere);
    let e = begin(&dir, &info("squeal run here"), false).unwrap_err();
    let text = e.to_string();
    assert!(
        matches!(e, FolderError::LockedElsewhere { .. }) && text.contains("host node_7 (pid"),
        "{text}"
    );
    assert_eq!(
        serde_json::from_str::<Holder>(&fs::read_to_string(dir.join(LOCK)).unwrap()).unwrap(),
        elsewhere
    );
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn times_are_utc() {
    assert_eq!(utc(0), "1970-01-01T00:00:00Z");
    // 2026-11-27 12:34:56 UTC (date -u -d @1795782896).
    assert_eq!(utc(1_795_782_896), "2026-11-27T12:34:56Z");
    assert_eq!(utc(951_782_400), "2000-02-29T00:00:00Z");
}
