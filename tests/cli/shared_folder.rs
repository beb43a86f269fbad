//! Issue 22, lost work: two writers in one folder from different PID namespaces (containers,
//! or the hosts of a cluster sharing a folder). The issue's reproduction with `unshare --pid`:
//! the atomic writer of the time removed every `.NAME.tmp-PID` file whose pid was not alive in
//! its own namespace, so a write in one namespace deleted the other's file mid-write, whose
//! rename then failed with "No such file or directory" (a 10 s reduction lost).
//!
//! Here writer A (`squeal fe export` of the fine pad, a 57 MB stiffness file) runs in a PID
//! namespace of its own, as pid 10 or so there; it is stopped (SIGSTOP) while its temporary file
//! exists. Writer B (`squeal mesh convert`) then writes into the same folder from another new
//! namespace, where it is pid 1 and A's pid names no process. A is continued: its write must
//! end with the complete file. Needs `unshare` with user and PID namespaces (util-linux; root or
//! unprivileged user namespaces): where it does not run, the test prints why and passes.

use super::common;

use common::{root, temp_dir};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The arguments that run a command in new user, PID and mount namespaces with their own
/// `/proc` (so that pids are looked up in the new namespace, as in a container).
const UNSHARE: [&str; 5] = ["-r", "--pid", "--fork", "--mount-proc", "--"];

/// Why `unshare` cannot be used here, if it cannot.
fn unshare_unavailable() -> Option<String> {
    match Command::new("unshare").args(UNSHARE).arg("true").output() {
        Err(e) => Some(format!("unshare does not start: {e}")),
        Ok(o) if !o.status.success() => Some(format!(
            "unshare {} true failed: {}",
            UNSHARE.join(" "),
            String::from_utf8_lossy(&o.stderr).trim()
        )),
        Ok(_) => None,
    }
}

/// The temporary files of the atomic writer in `dir`.
fn temps(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .map(|d| {
            d.flatten()
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| n.starts_with('.') && n.contains(".tmp-"))
                .collect()
        })
        .unwrap_or_default()
}

/// Sends `signal` (`STOP`, `CONT`) to the process group `pgid`.
fn signal_group(signal: &str, pgid: u32) {
    let ok = Command::new("kill")
        .args([&format!("-{signal}"), "--", &format!("-{pgid}")])
        .status()
        .unwrap()
        .success();
    assert!(ok, "kill -{signal} -{pgid}");
}

/// The fields of a temporary file's name `.NAME.tmp-HOST-BOOT-PIDNS-PID-UNIQUE`: (pid
/// namespace, pid).
fn writer_of(temp: &str) -> (String, u32) {
    let tail = temp.rsplit_once(".tmp-").unwrap().1;
    let f: Vec<&str> = tail.rsplitn(5, '-').collect();
    (f[2].to_string(), f[1].parse().unwrap())
}

/// The lines of a MatrixMarket coordinate file after its header, and the count its size line
/// announces.
fn mtx_entries(path: &Path) -> (usize, usize) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('%'));
    let size: Vec<usize> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    (lines.count(), size[2])
}

#[cfg(target_os = "linux")]
#[test]
fn a_write_in_another_pid_namespace_is_left_alone() {
    use std::os::unix::process::CommandExt;
    if let Some(why) = unshare_unavailable() {
        eprintln!("skipped: {why}; the two-namespace reproduction needs unshare");
        return;
    }
    let squeal = env!("CARGO_BIN_EXE_squeal");
    let dir = temp_dir("shared", "pidns");
    let shared: PathBuf = dir.join("shared");
    std::fs::create_dir_all(&shared).unwrap();
    let pad_fine = root().join("meshes/pad_fine.inp");
    // Writer A: a few processes first, so that squeal is not pid 1 of its namespace; `exit $?`
    // keeps the shell from replacing itself with squeal.
    let script =
        "for i in 1 2 3 4 5 6 7 8; do /bin/true; done; \"$0\" fe export \"$1\" -o \"$2\"; exit $?";
    let mut a = Command::new("unshare")
        .args(UNSHARE)
        .args(["sh", "-c", script, squeal])
        .arg(&pad_fine)
        .arg(&shared)
        .process_group(0)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let pgid = a.id();
    // Stop A while one of its temporary files exists (it writes K, M, then the dof map).
    let t = Instant::now();
    let temp = loop {
        assert!(
            t.elapsed() < Duration::from_secs(120),
            "writer A never wrote"
        );
        if a.try_wait().unwrap().is_some() {
            panic!("writer A finished before a temporary file of its was seen: use a larger mesh");
        }
        if !temps(&shared).is_empty() {
            signal_group("STOP", pgid);
            match temps(&shared).pop() {
                Some(t) => break t,
                // Renamed between the look and the signal: on to its next file.
                None => signal_group("CONT", pgid),
            }
        }
        std::thread::sleep(Duration::from_micros(200));
    };
    let (a_ns, a_pid) = writer_of(&temp);
    let own_ns = std::fs::read_link("/proc/self/ns/pid").unwrap();
    assert!(
        !own_ns.to_string_lossy().contains(&a_ns),
        "writer A is in this test's PID namespace ({temp})"
    );
    // B is pid 1 of a namespace of one process: A's pid names no process there.
    assert!(
        a_pid > 1,
        "writer A is pid {a_pid} of its namespace ({temp})"
    );

    // Writer B, in another new PID namespace, writes into the same folder.
    let b = Command::new("unshare")
        .args(UNSHARE)
        .arg(squeal)
        .args(["mesh", "convert"])
        .arg(root().join("meshes/pad_coarse.inp"))
        .arg(shared.join("pad.vtu"))
        .output()
        .unwrap();
    let kept = shared.join(&temp).is_file();
    signal_group("CONT", pgid);
    let a = a.wait_with_output().unwrap();
    let a_err = String::from_utf8_lossy(&a.stderr);
    assert!(
        b.status.success(),
        "writer B: {}",
        String::from_utf8_lossy(&b.stderr)
    );
    assert!(kept, "writer B removed writer A's file {temp} mid-write");
    assert!(a.status.success(), "writer A failed: {a_err}");
    // A's files are whole: every entry its header announces.
    for m in ["pad_fine_K.mtx", "pad_fine_M.mtx"] {
        let (lines, announced) = mtx_entries(&shared.join(m));
        assert_eq!(lines, announced, "{m}");
    }
    assert!(shared.join("pad.vtu").is_file() && shared.join("pad_fine_dofs.csv").is_file());
    assert!(temps(&shared).is_empty(), "{:?}", temps(&shared));
    eprintln!(
        "writer A (pid {a_pid} of PID namespace {a_ns}) kept {temp} while writer B wrote; both finished"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
