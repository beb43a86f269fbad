//! Output files for squeal.
//!
//! Every file squeal writes goes through [`atomic_write`]: the bytes go to a temporary file in
//! the destination's folder, which is flushed, synced and then renamed over the destination.
//! A crash or an error mid-write leaves the previous file (or no file) in place, never half a
//! file.
//!
//! [`mtx`] writes and reads MatrixMarket coordinate and array files, the exchange format that
//! MATLAB (`mmread`), SciPy (`scipy.io.mmread`) and Julia read.

pub mod csv;
pub mod folder;
pub mod guard;
pub mod host;
pub mod interrupt;
pub mod mtx;

pub use guard::{OutputError, check_writable, refuse_inputs, require_extension, require_folder};

use std::fs;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// An output error: which file and what went wrong.
///
/// The message is complete in `Display` (the file, then the operating system's reason) and the
/// `io::Error` is a plain field, not a `source()`: an error chain printed with `{:#}` (anyhow)
/// would otherwise show the reason twice.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    #[error("cannot write {}: {error}", path.display())]
    Write { path: PathBuf, error: io::Error },
    #[error("cannot read {}: {error}", path.display())]
    Read { path: PathBuf, error: io::Error },
    #[error("{path}:{line}: {message}")]
    Parse {
        path: PathBuf,
        line: usize,
        message: String,
    },
}

/// Writes a file atomically: `fill` writes into a buffered temporary file beside `path`, which
/// replaces `path` only once everything was written and synced.
///
/// Parent folders are created as needed. On error (or a panic in `fill`) the temporary file
/// is removed and `path` is untouched. The temporary file is
/// `.NAME.tmp-HOST-BOOT-PIDNS-PID-UNIQUE` in the destination's folder ([`host::Identity`]); a
/// process killed mid-write (Ctrl-C) leaves it behind, so each write first removes the
/// temporary files in its folder whose writer is provably gone ([`remove_stale_temps`]).
pub fn atomic_write<F>(path: &Path, fill: F) -> Result<(), IoError>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    let tracked = write_file(path, fill, true, true)?;
    folder::record_written(path);
    // Off the interrupt registry only once the manifest knows the file ([`interrupt`]).
    drop(tracked);
    Ok(())
}

/// [`atomic_write`] without telling the run folder ([`folder`]) about the file: for the
/// folder's own manifest. `sync`: flush the file to the disk before the rename.
pub(crate) fn write_replacing<F>(path: &Path, fill: F, sync: bool) -> Result<(), IoError>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    write_file(path, fill, sync, false).map(|_| ())
}

/// The write of [`atomic_write`] and [`write_replacing`]; `track`: registered with
/// [`interrupt`] (an output file, refused once the run is being stopped).
fn write_file<F>(
    path: &Path,
    fill: F,
    sync: bool,
    track: bool,
) -> Result<Option<interrupt::Tracked>, IoError>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    let wrap = |error| IoError::Write {
        path: path.to_path_buf(),
        error,
    };
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    fs::create_dir_all(&dir).map_err(wrap)?;
    remove_stale_temps(&dir);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut tmp = TempFile {
        path: dir.join(temp_name(&name)),
        keep: false,
    };
    let tracked = match track {
        true => Some(interrupt::register(&tmp.path, path).map_err(wrap)?),
        false => None,
    };
    let file = fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&tmp.path)
        .map_err(wrap)?;
    let mut w = BufWriter::new(file);
    let result = (|| {
        fill(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        if sync {
            file.sync_all()?;
        }
        match &tracked {
            Some(t) => interrupt::rename(t, &tmp.path, path),
            None => fs::rename(&tmp.path, path),
        }
    })();
    // Renamed: nothing left to remove. Otherwise dropping `tmp` removes the temporary file.
    tmp.keep = result.is_ok();
    result.map(|_| tracked).map_err(wrap)
}

/// A temporary file that is removed when dropped (on an error, or a panic in the filler)
/// unless `keep` was set.
struct TempFile {
    path: PathBuf,
    keep: bool,
}

impl Drop for TempFile {
    fn drop(&mut self) {
        if !self.keep {
            let _ = fs::remove_file(&self.path);
        }
    }
}

/// Temporary files older than this (by their last write) are leftovers, whoever wrote them,
/// when they cannot be attributed (the older `.NAME.tmp-PID` names) or come from a host of
/// this host's name: a live write streams into its file and keeps it younger.
pub const STALE_AGE: std::time::Duration = std::time::Duration::from_secs(24 * 3600);

/// The temporary file name of [`atomic_write`] for destination `name`:
/// `.NAME.tmp-HOST-BOOT-PIDNS-PID-UNIQUE`, the writer's [`host::Identity`] and a part unique
/// within the process (two threads writing one destination do not share a file). A long
/// `NAME` is cut so that the whole stays within 255 bytes.
pub(crate) fn temp_name(name: &str) -> String {
    use std::sync::atomic::{AtomicU64, Ordering};
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.subsec_nanos());
    temp_name_for(name, host::this_process(), &format!("{n:x}x{nanos:08x}"))
}

fn temp_name_for(name: &str, who: &host::Identity, unique: &str) -> String {
    let tail = format!(
        ".tmp-{}-{}-{}-{}-{unique}",
        who.host, who.boot, who.pid_ns, who.pid
    );
    let mut cut = name.len().min(250usize.saturating_sub(tail.len()));
    while !name.is_char_boundary(cut) {
        cut -= 1;
    }
    format!(".{}{tail}", &name[..cut])
}

/// A temporary file of [`atomic_write`]'s schemes, by its name.
#[derive(Debug, PartialEq, Eq)]
pub(crate) enum Temp {
    /// `.NAME.tmp-HOST-BOOT-PIDNS-PID-UNIQUE`: its writer.
    Named(host::Identity),
    /// `.NAME.tmp-PID`, written by earlier versions: the pid of an unknown host.
    Legacy(u32),
}

pub(crate) fn parse_temp(file_name: &str) -> Option<Temp> {
    let (stem, tail) = file_name.strip_prefix('.')?.rsplit_once(".tmp-")?;
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    if stem.is_empty() {
        return None;
    }
    if digits(tail) {
        return tail.parse().ok().map(Temp::Legacy);
    }
    let mut f = tail.rsplitn(5, '-');
    let (unique, pid, pid_ns, boot, host) = (f.next()?, f.next()?, f.next()?, f.next()?, f.next()?);
    let hex = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_hexdigit());
    let ok = unique.bytes().all(|b| b.is_ascii_alphanumeric())
        && !unique.is_empty()
        && digits(pid)
        && digits(pid_ns)
        && hex(boot)
        && !host.is_empty()
        && host.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_');
    if !ok {
        return None;
    }
    Some(Temp::Named(host::Identity {
        host: host.into(),
        boot: boot.into(),
        pid_ns: pid_ns.into(),
        pid: pid.parse().ok()?,
    }))
}

/// Whether a temporary file of [`atomic_write`] may be removed: its writer is provably gone
/// (this host, this kernel, this PID namespace, no such process), or it is older than
/// [`STALE_AGE`] and not from another host. Another host's file is never removed: its pid
/// means nothing here.
fn is_stale(temp: &Temp, age: Option<std::time::Duration>) -> bool {
    let old = age.is_some_and(|a| a > STALE_AGE);
    match temp {
        Temp::Named(who) => who.is_gone() || (old && who.host == host::this_process().host),
        Temp::Legacy(_) => old,
    }
}

/// Removes the temporary files of [`atomic_write`] in `dir` that are leftovers of a write
/// that was killed (`is_stale`): on a folder shared by several hosts or containers, a file
/// whose writer cannot be looked up here is left alone, and so is everything else; errors are
/// ignored (the cleanup is a courtesy, never a reason to fail a write).
pub fn remove_stale_temps(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(temp) = name.to_str().and_then(parse_temp) else {
            continue;
        };
        let Ok(meta) = entry.metadata() else {
            continue;
        };
        let age = meta.modified().ok().and_then(|t| t.elapsed().ok());
        if meta.is_file() && is_stale(&temp, age) {
            let _ = fs::remove_file(entry.path());
        }
    }
}

/// Writes `bytes` to `path` atomically.
pub fn atomic_write_bytes(path: &Path, bytes: &[u8]) -> Result<(), IoError> {
    atomic_write(path, |w| w.write_all(bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_write_keeps_previous_file() {
        let dir = std::env::temp_dir().join(format!("squeal-io-test-{}", std::process::id()));
        let path = dir.join("a.txt");
        atomic_write_bytes(&path, b"first").unwrap();
        let err = atomic_write(&path, |w| {
            w.write_all(b"partial")?;
            Err(io::Error::other("simulated crash"))
        });
        assert!(err.is_err());
        assert_eq!(fs::read(&path).unwrap(), b"first");
        // No temporary file left behind.
        let leftovers: Vec<_> = fs::read_dir(&dir).unwrap().filter_map(Result::ok).collect();
        assert_eq!(leftovers.len(), 1);
        fs::remove_dir_all(&dir).unwrap();
    }

    /// A fresh, empty folder for one test.
    fn scratch(test: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("squeal-io-{test}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_panic_in_fill_removes_the_temporary_file() {
        let dir = scratch("panic");
        let path = dir.join("a.txt");
        let caught = std::panic::catch_unwind(|| {
            let _ = atomic_write(&path, |w| {
                w.write_all(b"partial")?;
                panic!("simulated bug in a writer");
            });
        });
        assert!(caught.is_err());
        assert!(names(&dir).is_empty(), "{:?}", names(&dir));
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn temporary_names_are_recognised() {
        let me = host::this_process();
        assert_eq!(
            parse_temp(&temp_name("a.txt")),
            Some(Temp::Named(me.clone()))
        );
        let other = host::Identity {
            host: "node_7".into(),
            boot: "0123456789ab".into(),
            pid_ns: "4026531836".into(),
            pid: 42,
        };
        let name = temp_name_for("a-b.tmp-3.txt", &other, "1x2f");
        assert_eq!(
            name,
            ".a-b.tmp-3.txt.tmp-node_7-0123456789ab-4026531836-42-1x2f"
        );
        assert_eq!(parse_temp(&name), Some(Temp::Named(other.clone())));
        // A long destination name is cut: the whole stays a legal file name.
        let long = temp_name_for(&"é".repeat(200), &other, "1");
        assert!(long.len() <= 255 && long.ends_with("-42-1"), "{long}");
        assert_eq!(parse_temp(".x.tmp-7"), Some(Temp::Legacy(7)));
        for bad in [
            "x.tmp-7",
            "..tmp-7",
            ".x.tmp-",
            ".x.tmp-+7",
            ".x.tmp-7a",
            ".x.tmp",
            ".x.tmp-h-0g-1-2-3",
            ".x.tmp-h.x-0a-1-2-3",
            ".x.tmp--0a-1-2-3",
        ] {
            assert_eq!(parse_temp(bad), None, "{bad}");
        }
    }

    /// Issue 22: on a folder shared by several hosts (NFS under Slurm) or PID namespaces, a
    /// temporary file whose pid is free here may be another machine's write in progress. It
    /// is left alone: another host's (whatever its pid), one of another PID namespace or
    /// kernel, and one of the older `.NAME.tmp-PID` names that cannot be attributed (until it
    /// is a day old). A temporary file of this host, kernel and namespace whose process is
    /// gone (as Ctrl-C leaves it) is removed by the next write into the folder.
    #[cfg(target_os = "linux")]
    #[test]
    fn only_this_hosts_stale_temporary_files_are_removed() {
        let dir = scratch("stale");
        // A process that has exited (its pid is free until reused), and a pid above the
        // kernel's limit (PID_MAX_LIMIT = 2^22), which no process has.
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let exited = child.id();
        child.wait().unwrap();
        let me = host::this_process().clone();
        let dead = |pid| host::Identity { pid, ..me.clone() };
        let live = dead(std::os::unix::process::parent_id());
        let elsewhere = host::Identity {
            host: format!("not_{}", me.host),
            ..dead(u32::MAX)
        };
        let other_ns = host::Identity {
            pid_ns: "1".into(),
            ..dead(u32::MAX)
        };
        let stale = [
            temp_name_for("a.txt", &dead(exited), "0"),
            temp_name_for("b.csv", &dead(u32::MAX), "1"),
        ];
        let kept = [
            temp_name_for("c.txt", &live, "2"),
            temp_name_for("d.txt", &elsewhere, "3"),
            temp_name_for("f.txt", &other_ns, "4"),
            format!(".g.txt.tmp-{exited}"),
            "notes.tmp-1".to_string(),
            ".h.tmp-x1".to_string(),
        ];
        for n in stale.iter().chain(&kept) {
            fs::write(dir.join(n), b"left over").unwrap();
        }
        atomic_write_bytes(&dir.join("e.txt"), b"new").unwrap();
        let mut expect: Vec<String> = kept.to_vec();
        expect.push("e.txt".to_string());
        expect.sort();
        assert_eq!(names(&dir), expect);
        fs::remove_dir_all(&dir).unwrap();
    }

    /// Past [`STALE_AGE`] a leftover is removed unless another host wrote it.
    #[test]
    fn old_leftovers_are_removed_unless_another_hosts() {
        let me = host::this_process();
        let day = Some(STALE_AGE + std::time::Duration::from_secs(1));
        let hour = Some(std::time::Duration::from_secs(3600));
        let other = host::Identity {
            host: format!("not_{}", me.host),
            ..me.clone()
        };
        let mine_alive = Temp::Named(me.clone());
        assert!(is_stale(&Temp::Legacy(7), day));
        assert!(!is_stale(&Temp::Legacy(7), hour));
        assert!(is_stale(&mine_alive, day));
        assert!(!is_stale(&mine_alive, hour));
        assert!(!is_stale(&Temp::Named(other), day));
    }

    /// Counts how often `piece` appears in `text`.
    fn count(text: &str, piece: &str) -> usize {
        text.matches(piece).count()
    }

    /// The operating system's reason appears once in the message and in the `{:#}` chain, and
    /// the file is named.
    #[test]
    fn os_errors_are_printed_once() {
        let dir = scratch("os-error");
        let missing = dir.join("missing.mtx");
        let err = mtx::read(&missing).unwrap_err();
        let os = std::fs::read(&missing).unwrap_err().to_string();
        for shown in [err.to_string(), format!("{:#}", anyhow::Error::from(err))] {
            assert_eq!(count(&shown, &os), 1, "{shown}");
            assert!(shown.contains("missing.mtx"), "{shown}");
        }
        // A folder where a file is: the write fails before any temporary file exists.
        fs::write(dir.join("plain"), b"").unwrap();
        let err = atomic_write_bytes(&dir.join("plain/out.txt"), b"x").unwrap_err();
        let shown = format!("{:#}", anyhow::Error::from(err));
        let os = fs::create_dir_all(dir.join("plain"))
            .unwrap_err()
            .to_string();
        assert_eq!(count(&shown, &os), 1, "{shown}");
        assert!(shown.contains("out.txt"), "{shown}");
        fs::remove_dir_all(&dir).unwrap();
    }
}
