//! Stopping a run cleanly on an interrupt (Ctrl-C, SIGINT): no partial output, no stale lock.
//!
//! Every [`crate::atomic_write`] of this process is registered here while it runs: its
//! temporary file, its destination, and whether it has been renamed into place. [`stop`]
//! (called by the command line's signal handler, on a thread of its own) then, holding the
//! registry so that no write starts or completes meanwhile:
//!
//! 1. refuses every later write (an error saying the run was interrupted);
//! 2. removes the temporary files of the writes under way (the destinations keep their
//!    previous content), and records in the manifest the files already renamed into place;
//! 3. records every active run as interrupted in its folder's manifest and releases its lock
//!    ([`crate::folder::finish`]);
//! 4. ends the process with exit status 130 (128 + SIGINT, the shell's convention).
//!
//! The rename into place happens under the registry's lock, so a file is either still a
//! temporary file (removed) or in place and known to the manifest.

use std::collections::BTreeMap;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// The exit status after an interrupt: 128 + SIGINT.
pub const EXIT_STATUS: i32 = 130;

struct Entry {
    temp: PathBuf,
    target: PathBuf,
    renamed: bool,
}

struct Registry {
    stopping: bool,
    next: u64,
    entries: BTreeMap<u64, Entry>,
}

static REGISTRY: Mutex<Registry> = Mutex::new(Registry {
    stopping: false,
    next: 0,
    entries: BTreeMap::new(),
});

fn registry() -> MutexGuard<'static, Registry> {
    REGISTRY.lock().unwrap_or_else(PoisonError::into_inner)
}

fn interrupted() -> io::Error {
    io::Error::new(
        io::ErrorKind::Interrupted,
        "the run was interrupted (Ctrl-C): nothing more is written",
    )
}

/// A write under way; dropping it takes it off the registry.
pub(crate) struct Tracked(u64);

impl Drop for Tracked {
    fn drop(&mut self) {
        registry().entries.remove(&self.0);
    }
}

/// Registers a write of `target` through `temp` (before `temp` is created); an error once the
/// run is being stopped.
pub(crate) fn register(temp: &Path, target: &Path) -> io::Result<Tracked> {
    let mut r = registry();
    if r.stopping {
        return Err(interrupted());
    }
    let id = r.next;
    r.next += 1;
    r.entries.insert(
        id,
        Entry {
            temp: temp.to_path_buf(),
            target: target.to_path_buf(),
            renamed: false,
        },
    );
    Ok(Tracked(id))
}

/// Renames the write's temporary file into place, unless the run is being stopped.
pub(crate) fn rename(t: &Tracked, temp: &Path, target: &Path) -> io::Result<()> {
    let mut r = registry();
    if r.stopping {
        return Err(interrupted());
    }
    fs::rename(temp, target)?;
    if let Some(e) = r.entries.get_mut(&t.0) {
        e.renamed = true;
    }
    Ok(())
}

/// Stops this process's runs (module docs) with `status` in their manifests (e.g.
/// `interrupted (Ctrl-C)`) and exits with [`EXIT_STATUS`].
pub fn stop(status: &str) -> ! {
    let mut r = registry();
    r.stopping = true;
    for e in r.entries.values() {
        if e.renamed {
            crate::folder::record_written(&e.target);
        } else {
            let _ = fs::remove_file(&e.temp);
        }
    }
    crate::folder::finish(None, status);
    // The registry stays locked: no write completes before the process ends.
    std::process::exit(EXIT_STATUS)
}
