//! Stopping a run cleanly on an interrupt (Ctrl-C, SIGINT), a closed output pipe or a panic: no
//! partial output, no stale lock.
//!
//! Every [`crate::atomic_write`] of this process is registered here while it runs: its
//! temporary file, its destination, and whether it has been renamed into place. [`stop`]
//! (called by the command line's signal handler, on a thread of its own) and [`stop_with`]
//! (called by its panic hook, on the panicking thread) then, holding the registry so that no
//! write starts or completes meanwhile:
//!
//! 1. refuses every later write (an error saying the run was interrupted);
//! 2. removes the temporary files of the writes under way (the destinations keep their
//!    previous content), and records in the manifest the files already renamed into place;
//! 3. records every active run as interrupted in its folder's manifest and releases its lock
//!    ([`crate::folder::finish`]);
//! 4. ends the process with exit status 130 (128 + SIGINT, the shell's convention), or the
//!    status the caller gives.
//!
//! On the panic path the registry and the folders' state are taken with [`lock_within`]: a
//! panic while this thread held one of them must not turn into a hang. Past the wait the step
//! is skipped; the kernel still releases the folder's advisory lock when the process ends, and
//! the next run takes the lock over and marks this run as interrupted.
//!
//! The rename into place happens under the registry's lock, so a file is either still a
//! temporary file (removed) or in place and known to the manifest.

use std::collections::BTreeMap;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError, TryLockError};
use std::time::{Duration, Instant};

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

/// How long the panic path waits for a lock that another thread holds (a manifest being
/// written takes milliseconds).
pub const LOCK_WAIT: Duration = Duration::from_secs(2);

/// `m` locked, waiting at most `wait` for another holder (a poisoned lock is taken as it is);
/// `None` past the wait, or at once if this thread may hold it (`WouldBlock` for the whole
/// wait is the same answer either way).
pub fn lock_within<T>(m: &Mutex<T>, wait: Duration) -> Option<MutexGuard<'_, T>> {
    let start = Instant::now();
    loop {
        match m.try_lock() {
            Ok(g) => return Some(g),
            Err(TryLockError::Poisoned(p)) => return Some(p.into_inner()),
            Err(TryLockError::WouldBlock) if start.elapsed() < wait => {
                std::thread::sleep(Duration::from_millis(5));
            }
            Err(TryLockError::WouldBlock) => return None,
        }
    }
}

/// Stops this process's runs (module docs) with `status` in their manifests (e.g.
/// `interrupted (Ctrl-C)`) and exits with [`EXIT_STATUS`].
pub fn stop(status: &str) -> ! {
    stop_with(status, EXIT_STATUS)
}

/// [`stop`] with the exit status `code`: for a closed output pipe or a panic. Waits at most
/// [`LOCK_WAIT`] for each lock (module docs).
pub fn stop_with(status: &str, code: i32) -> ! {
    // Held until the process ends: no write completes meanwhile.
    let _held = lock_within(&REGISTRY, LOCK_WAIT).map(|mut r| {
        r.stopping = true;
        for e in r.entries.values() {
            if e.renamed {
                crate::folder::record_written_within(&e.target, LOCK_WAIT);
            } else {
                let _ = fs::remove_file(&e.temp);
            }
        }
        r
    });
    crate::folder::finish_within(status, LOCK_WAIT);
    std::process::exit(code)
}
