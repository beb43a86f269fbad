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
pub mod guard;
pub mod mtx;

pub use guard::{OutputError, check_writable, refuse_inputs, require_extension, require_folder};

use std::fs::{self, File};
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
/// is removed and `path` is untouched. The temporary file is `.NAME.tmp-PID` in the
/// destination's folder; a process killed mid-write (Ctrl-C) leaves it behind, so each write
/// first removes the temporary files of this scheme in its folder whose process is gone
/// ([`remove_stale_temps`]).
pub fn atomic_write<F>(path: &Path, fill: F) -> Result<(), IoError>
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
        path: dir.join(temp_name(&name, std::process::id())),
        keep: false,
    };
    let file = File::create(&tmp.path).map_err(wrap)?;
    let mut w = BufWriter::new(file);
    let result = (|| {
        fill(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        fs::rename(&tmp.path, path)
    })();
    // Renamed: nothing left to remove. Otherwise dropping `tmp` removes the temporary file.
    tmp.keep = result.is_ok();
    result.map_err(wrap)
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

/// The temporary file name of [`atomic_write`] for destination `name` and process `pid`.
fn temp_name(name: &str, pid: u32) -> String {
    format!(".{name}.tmp-{pid}")
}

/// The process id in a temporary file name of [`atomic_write`]'s scheme, `.NAME.tmp-PID`.
fn temp_pid(file_name: &str) -> Option<u32> {
    let (stem, pid) = file_name.strip_prefix('.')?.rsplit_once(".tmp-")?;
    if stem.is_empty() || pid.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    pid.parse().ok()
}

/// Whether process `pid` is alive (Linux: `/proc/PID` exists). Where this cannot be told,
/// every process counts as alive, so nothing is removed.
fn process_alive(pid: u32) -> bool {
    if cfg!(target_os = "linux") {
        Path::new("/proc").join(pid.to_string()).exists()
    } else {
        true
    }
}

/// Removes the files of `dir` named `.NAME.tmp-PID` (the temporary files of [`atomic_write`])
/// whose process is no longer alive: the leftovers of a write that was killed. A live
/// process's file (another squeal writing into the same folder) is left alone, and so is
/// everything else; errors are ignored (the cleanup is a courtesy, never a reason to fail a
/// write). A process id reused by a new process only delays the removal to a later write.
pub fn remove_stale_temps(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    let own = std::process::id();
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(temp_pid) else {
            continue;
        };
        let is_file = entry.file_type().is_ok_and(|t| t.is_file());
        if is_file && pid != own && !process_alive(pid) {
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
        assert_eq!(temp_pid(&temp_name("a.txt", 42)), Some(42));
        assert_eq!(temp_pid(".x.tmp-7"), Some(7));
        for other in [
            "x.tmp-7",
            "..tmp-7",
            ".x.tmp-",
            ".x.tmp-+7",
            ".x.tmp-7a",
            ".x.tmp",
        ] {
            assert_eq!(temp_pid(other), None, "{other}");
        }
    }

    /// A temporary file of a process that is gone (as Ctrl-C leaves it) is removed by the next
    /// write into the folder; one of a live process and other files are kept.
    #[cfg(target_os = "linux")]
    #[test]
    fn the_next_write_removes_stale_temporary_files() {
        let dir = scratch("stale");
        // A process that has exited (its pid is free until reused), and a pid above the
        // kernel's limit (PID_MAX_LIMIT = 2^22), which no process has.
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let exited = child.id();
        child.wait().unwrap();
        let live = std::os::unix::process::parent_id();
        let stale = [temp_name("a.txt", exited), temp_name("b.csv", u32::MAX)];
        let kept = [
            temp_name("c.txt", live),
            "notes.tmp-1".to_string(),
            ".d.tmp-x1".to_string(),
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
