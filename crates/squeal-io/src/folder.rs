//! An output folder shared by runs: a lock for a run's duration, a manifest of which run wrote
//! which file, and the refusal to write into a folder of a user's own files.
//!
//! [`begin`] takes the folder for one run of a command:
//!
//! - the lock `.squeal-lock` (an advisory lock on the file, released by the kernel when the
//!   process ends, whatever ends it): a second run into the same folder while one runs is
//!   refused, naming the lock's host and pid. A lock file left by a process that is gone
//!   (Ctrl-C) on this machine is taken over. One left by another machine (a shared folder) is
//!   reported, never taken over: whether that run still writes cannot be told from here.
//! - the manifest `squeal-manifest.json`, written atomically: every run (command, scene and
//!   its SHA-256, host, pid, start, end, how it ended) and, for every file, the run that last
//!   wrote it. It is rewritten as each file is written ([`crate::atomic_write`] tells it), so
//!   a run stopped midway leaves a manifest that says which files are its and that it did not
//!   finish.
//! - the refusal: a folder holding files that no run of the manifest wrote (a user's own
//!   `index.md`, with `-o .`) is not written into unless the caller says so (`--force`).
//!
//! [`earlier_files`] then lists the files of earlier runs that this run has not rewritten (or
//! used, [`record_reused`]): the report marks them as not this run's. [`finish`] records how
//! the run ended and releases the lock.

use crate::IoError;
use crate::host::{self, Identity};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fs::{self, File};
use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The manifest's file name in the output folder.
pub const MANIFEST: &str = "squeal-manifest.json";
/// The lock's file name in the output folder.
pub const LOCK: &str = ".squeal-lock";
/// The manifest's format, its first field.
const FORMAT: &str = "squeal output manifest 1";
/// How many runs the manifest remembers (the files' runs are always kept).
const KEEP_RUNS: usize = 50;

/// Why a run may not write into a folder.
#[derive(Debug, thiserror::Error)]
pub enum FolderError {
    /// Another run holds the lock.
    #[error(
        "{}: another squeal run is writing into this folder (host {}, pid {}, since {}: {}); wait for it to end or choose another output folder",
        lock.display(), holder.host, holder.pid, holder.started, holder.command
    )]
    Locked { lock: PathBuf, holder: Box<Holder> },
    /// The lock file of a run on another machine (or an earlier boot of this one).
    #[error(
        "{}: a squeal run on host {} (pid {}, since {}: {}) holds this folder, and whether it still runs cannot be told from this machine; if it has ended, remove the lock file",
        lock.display(), holder.host, holder.pid, holder.started, holder.command
    )]
    LockedElsewhere { lock: PathBuf, holder: Box<Holder> },
    /// The folder holds files no squeal run wrote.
    #[error(
        "{}: this folder holds {total} file(s) that no squeal run wrote ({}{}); this run could replace them: choose another output folder, or give --force to write here anyway",
        dir.display(), files.join(", "), if *total > files.len() { ", ..." } else { "" }
    )]
    Unclaimed {
        dir: PathBuf,
        files: Vec<String>,
        total: usize,
    },
    /// The manifest does not read.
    #[error(
        "{}: not a squeal manifest ({message}); remove it, or give --force to start a new one",
        path.display()
    )]
    Manifest { path: PathBuf, message: String },
    #[error(transparent)]
    Io(#[from] IoError),
}

/// Who holds a lock, as its file says.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Holder {
    pub host: String,
    pub boot: String,
    pub pid_ns: String,
    pub pid: u32,
    pub started: String,
    pub command: String,
}

impl Holder {
    fn identity(&self) -> Identity {
        Identity {
            host: self.host.clone(),
            boot: self.boot.clone(),
            pid_ns: self.pid_ns.clone(),
            pid: self.pid,
        }
    }
}

/// What a run is, for the manifest.
#[derive(Clone, Debug, Default)]
pub struct RunInfo {
    /// The command line.
    pub command: String,
    /// The scene file, and its SHA-256.
    pub scene: Option<(PathBuf, String)>,
}

/// One run in the manifest.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    pub id: u64,
    pub command: String,
    pub scene: Option<String>,
    pub scene_sha256: Option<String>,
    pub host: String,
    pub pid: u32,
    pub started: String,
    pub ended: Option<String>,
    /// `running` while it runs (and after a kill), then `finished`, `failed: ...`, or
    /// `interrupted` (found running by a later run that took its stale lock).
    pub status: String,
    /// Files of earlier runs this run used as they were (a reduced model still up to date).
    #[serde(default)]
    pub reused: Vec<String>,
}

/// One file in the manifest: the run that last wrote it, and when.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FileRecord {
    pub run: u64,
    pub written: String,
}

/// The manifest of an output folder.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    pub format: String,
    pub runs: Vec<RunRecord>,
    /// Relative paths (`/`-separated) to their writer.
    pub files: BTreeMap<String, FileRecord>,
}

impl Default for Manifest {
    fn default() -> Self {
        Self {
            format: FORMAT.into(),
            runs: Vec::new(),
            files: BTreeMap::new(),
        }
    }
}

impl Manifest {
    /// The manifest of `dir`, empty when there is none.
    pub fn read(dir: &Path) -> Result<Self, FolderError> {
        let path = dir.join(MANIFEST);
        let text = match fs::read_to_string(&path) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Self::default()),
            Err(error) => return Err(IoError::Read { path, error }.into()),
        };
        let m: Manifest = serde_json::from_str(&text).map_err(|e| FolderError::Manifest {
            path: path.clone(),
            message: e.to_string(),
        })?;
        if m.format != FORMAT {
            return Err(FolderError::Manifest {
                path,
                message: format!(
                    "format '{}', not '{FORMAT}': the folder was written by another version of \
                     squeal; write to a fresh folder",
                    m.format
                ),
            });
        }
        Ok(m)
    }

    fn write(&self, dir: &Path, sync: bool) -> Result<(), IoError> {
        let text = serde_json::to_string_pretty(self).unwrap_or_default();
        crate::write_replacing(&dir.join(MANIFEST), |w| w.write_all(text.as_bytes()), sync)
    }

    fn run_mut(&mut self, id: u64) -> Option<&mut RunRecord> {
        self.runs.iter_mut().find(|r| r.id == id)
    }
}

/// A file of an earlier run that this run did not rewrite.
#[derive(Clone, Debug, PartialEq)]
pub struct EarlierFile {
    pub path: String,
    pub run: u64,
    pub written: String,
}

/// The runs of this process and their folders.
struct Active {
    dir: PathBuf,
    id: u64,
    manifest: Manifest,
    lock: File,
}

static ACTIVE: Mutex<Vec<Active>> = Mutex::new(Vec::new());

fn active() -> std::sync::MutexGuard<'static, Vec<Active>> {
    ACTIVE.lock().unwrap_or_else(|e| e.into_inner())
}

/// The time now, UTC, as `2026-11-27T12:34:56Z`.
pub fn now_utc() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    utc(secs)
}

/// Unix seconds as an ISO 8601 UTC time (H. Hinnant's civil-from-days).
fn utc(secs: u64) -> String {
    let (days, rest) = ((secs / 86_400) as i64, secs % 86_400);
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rest / 3600,
        rest / 60 % 60,
        rest % 60
    )
}

/// Takes the lock of `dir`: the lock file's advisory lock, then this process's identity
/// written into it. Returns the lock file and a note when a dead run's lock was taken over.
fn take_lock(dir: &Path, command: &str) -> Result<(File, Option<String>), FolderError> {
    let path = dir.join(LOCK);
    let wrap = |error| IoError::Write {
        path: path.clone(),
        error,
    };
    // The file may be removed by its holder between our open and our lock: then the lock is
    // on a file no one else sees, and the path is tried again.
    for _ in 0..8 {
        let mut file = fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(wrap)?;
        // Some(true): locked by us; Some(false): held by a live process of a machine that
        // shares the lock; None: the file system has no locks, the file's contents decide.
        let locked = match file.try_lock() {
            Ok(()) => Some(true),
            Err(fs::TryLockError::WouldBlock) => Some(false),
            Err(fs::TryLockError::Error(_)) => None,
        };
        let mut text = String::new();
        let _ = file.read_to_string(&mut text);
        let holder: Option<Holder> = serde_json::from_str(&text).ok();
        let unknown = || Holder {
            host: "?".into(),
            started: "?".into(),
            command: "?".into(),
            ..Holder::default()
        };
        if locked == Some(false) {
            return Err(FolderError::Locked {
                lock: path,
                holder: Box::new(holder.unwrap_or_else(unknown)),
            });
        }
        if !same_file(&file, &path) {
            continue;
        }
        let mut note = None;
        if !text.trim().is_empty() {
            let h = holder.unwrap_or_else(unknown);
            let me = host::this_process();
            // On this kernel the advisory lock proves its holder gone; on another machine (or
            // an earlier boot of this one: the same cannot be told apart) it proves nothing
            // over a shared file system.
            if h.boot != me.boot || me.boot == "0" {
                return Err(FolderError::LockedElsewhere {
                    lock: path,
                    holder: Box::new(h),
                });
            }
            if locked.is_none() && !h.identity().is_gone() {
                return Err(FolderError::Locked {
                    lock: path,
                    holder: Box::new(h),
                });
            }
            note = Some(format!(
                "took over the lock of a run that is gone (host {}, pid {}, since {}: {})",
                h.host, h.pid, h.started, h.command
            ));
        }
        let me = host::this_process();
        let holder = Holder {
            host: me.host.clone(),
            boot: me.boot.clone(),
            pid_ns: me.pid_ns.clone(),
            pid: me.pid,
            started: now_utc(),
            command: command.into(),
        };
        let text = serde_json::to_string(&holder).unwrap_or_default();
        file.set_len(0).map_err(wrap)?;
        file.rewind().map_err(wrap)?;
        file.write_all(text.as_bytes()).map_err(wrap)?;
        file.sync_all().map_err(wrap)?;
        return Ok((file, note));
    }
    Err(IoError::Write {
        path,
        error: std::io::Error::other("the lock file kept changing"),
    }
    .into())
}

/// Whether the open `file` is the file at `path` now.
fn same_file(file: &File, path: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        match (file.metadata(), fs::metadata(path)) {
            (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    {
        let _ = (file, path);
        path.exists()
    }
}

/// Whether `name` (a file name in the folder) is the folder's own bookkeeping: the manifest,
/// the lock, a temporary file of [`crate::atomic_write`].
fn bookkeeping(name: &str) -> bool {
    name == MANIFEST
        || name == LOCK
        || name.starts_with(".squeal-probe-")
        || crate::parse_temp(name).is_some()
}

/// Every file under `dir` that the manifest does not list, as relative `/`-separated paths.
fn unclaimed(dir: &Path, m: &Manifest) -> Vec<String> {
    let mut out = Vec::new();
    let mut stack = vec![PathBuf::new()];
    while let Some(rel) = stack.pop() {
        let Ok(entries) = fs::read_dir(dir.join(&rel)) else {
            continue;
        };
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            let path = rel.join(&name);
            match e.file_type() {
                // A study's shards write there at once from several machines, untracked.
                Ok(t) if t.is_dir() && slash(&path) == "study/shards" => {}
                Ok(t) if t.is_dir() => stack.push(path),
                Ok(_) if rel.as_os_str().is_empty() && bookkeeping(&name) => {}
                Ok(_) if crate::parse_temp(&name).is_some() => {}
                // A reduced model copied in as a cache: read only if its hashes match the
                // scene's, else rebuilt (squeal's own format, never a user's document).
                Ok(_) if name.ends_with(".rom") => {}
                Ok(_) => {
                    let key = slash(&path);
                    if !m.files.contains_key(&key) {
                        out.push(key);
                    }
                }
                Err(_) => {}
            }
        }
    }
    out.sort();
    out
}

fn slash(p: &Path) -> String {
    p.components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect::<Vec<_>>()
        .join("/")
}

/// Takes `dir` (created if missing) for a run: its lock, the check that it holds no file a
/// squeal run did not write (skipped with `force`), and the run's entry in the manifest.
/// Returns notes for the user (a stale lock taken over, an earlier run that did not finish).
/// Until [`finish`], every file [`crate::atomic_write`] writes under `dir` is recorded as
/// this run's.
pub fn begin(dir: &Path, info: &RunInfo, force: bool) -> Result<Vec<String>, FolderError> {
    let wrap = |error| IoError::Write {
        path: dir.to_path_buf(),
        error,
    };
    fs::create_dir_all(dir).map_err(wrap)?;
    let canon = fs::canonicalize(dir).map_err(wrap)?;
    let (lock, note) = take_lock(&canon, &info.command)?;
    // Until the run is registered, an error must release the lock (the file goes with it).
    let release = |e: FolderError| {
        let _ = fs::remove_file(canon.join(LOCK));
        e
    };
    let mut notes: Vec<String> = note.into_iter().collect();
    let mut m = match Manifest::read(&canon) {
        Ok(m) => m,
        Err(e @ FolderError::Manifest { .. }) if !force => return Err(release(e)),
        Err(FolderError::Manifest { .. }) => Manifest::default(),
        Err(e) => return Err(release(e)),
    };
    if !force {
        let files = unclaimed(&canon, &m);
        if !files.is_empty() {
            return Err(release(FolderError::Unclaimed {
                dir: dir.to_path_buf(),
                total: files.len(),
                files: files.into_iter().take(5).collect(),
            }));
        }
    }
    // We hold the lock: a run still marked running was stopped.
    for r in m.runs.iter_mut().filter(|r| r.status == "running") {
        r.status = "interrupted".into();
        notes.push(format!(
            "the earlier run {} ({}, started {}) did not finish: its files are marked as its own",
            r.id, r.command, r.started
        ));
    }
    let id = m.runs.iter().map(|r| r.id).max().unwrap_or(0) + 1;
    let me = host::this_process();
    m.runs.push(RunRecord {
        id,
        command: info.command.clone(),
        scene: info.scene.as_ref().map(|s| s.0.display().to_string()),
        scene_sha256: info.scene.as_ref().map(|s| s.1.clone()),
        host: me.host.clone(),
        pid: me.pid,
        started: now_utc(),
        ended: None,
        status: "running".into(),
        reused: Vec::new(),
    });
    let drop_from = m.runs.len().saturating_sub(KEEP_RUNS);
    let keep: std::collections::BTreeSet<u64> = m.files.values().map(|f| f.run).collect();
    let mut i = 0;
    m.runs.retain(|r| {
        i += 1;
        i > drop_from || keep.contains(&r.id)
    });
    m.write(&canon, true).map_err(|e| release(e.into()))?;
    active().push(Active {
        dir: canon,
        id,
        manifest: m,
        lock,
    });
    Ok(notes)
}

/// The active run whose folder holds `path`, with `path` relative to it.
fn find<'a>(runs: &'a mut [Active], path: &Path) -> Option<(&'a mut Active, String)> {
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let full = fs::canonicalize(parent).ok()?.join(path.file_name()?);
    runs.iter_mut().find_map(|a| {
        let rel = full.strip_prefix(&a.dir).ok()?;
        let key = slash(rel);
        (!key.is_empty() && !bookkeeping(&key)).then_some((a, key))
    })
}

/// Records that `path` was just written by this process (called by
/// [`crate::atomic_write`]): the active run of its folder, if any, claims it.
pub fn record_written(path: &Path) {
    record(active(), path);
}

/// [`record_written`] waiting at most `wait` for the folders' state (the panic path,
/// [`crate::interrupt::stop_with`]).
pub(crate) fn record_written_within(path: &Path, wait: std::time::Duration) {
    if let Some(runs) = crate::interrupt::lock_within(&ACTIVE, wait) {
        record(runs, path);
    }
}

fn record(mut runs: std::sync::MutexGuard<'_, Vec<Active>>, path: &Path) {
    if runs.is_empty() {
        return;
    }
    if let Some((a, key)) = find(&mut runs, path) {
        a.manifest.files.insert(
            key,
            FileRecord {
                run: a.id,
                written: now_utc(),
            },
        );
        let _ = a.manifest.write(&a.dir, false);
    }
}

/// Records that this run used `path`, a file of an earlier run, as it is (a cached reduced
/// model found up to date): it is not stale for this run.
pub fn record_reused(path: &Path) {
    let mut runs = active();
    if let Some((a, key)) = find(&mut runs, path) {
        let id = a.id;
        if let Some(r) = a.manifest.run_mut(id)
            && !r.reused.contains(&key)
        {
            r.reused.push(key);
            let _ = a.manifest.write(&a.dir, false);
        }
    }
}

/// The files of `dir` that earlier runs wrote and the active run of `dir` has neither
/// rewritten nor used; empty when no run of this process has `dir`.
pub fn earlier_files(dir: &Path) -> Vec<EarlierFile> {
    let Ok(canon) = fs::canonicalize(dir) else {
        return Vec::new();
    };
    let runs = active();
    let Some(a) = runs.iter().find(|a| a.dir == canon) else {
        return Vec::new();
    };
    let reused = a
        .manifest
        .runs
        .iter()
        .find(|r| r.id == a.id)
        .map(|r| r.reused.clone())
        .unwrap_or_default();
    a.manifest
        .files
        .iter()
        .filter(|(k, f)| f.run != a.id && !reused.contains(k) && canon.join(k).is_file())
        .map(|(k, f)| EarlierFile {
            path: k.clone(),
            run: f.run,
            written: f.written.clone(),
        })
        .collect()
}

/// Removes the files of `dir` that earlier runs wrote, this run has not rewritten and `which`
/// picks (given their relative `/`-separated path): a report of an earlier run must not stay
/// beside this run's files when this run stops before writing its own. Files no run wrote
/// are never removed. Returns the paths removed.
pub fn remove_earlier(dir: &Path, which: impl Fn(&str) -> bool) -> Vec<String> {
    let earlier = earlier_files(dir);
    let Ok(canon) = fs::canonicalize(dir) else {
        return Vec::new();
    };
    let mut runs = active();
    let Some(a) = runs.iter_mut().find(|a| a.dir == canon) else {
        return Vec::new();
    };
    let mut removed = Vec::new();
    for f in earlier.into_iter().filter(|f| which(&f.path)) {
        if fs::remove_file(canon.join(&f.path)).is_ok() {
            a.manifest.files.remove(&f.path);
            removed.push(f.path);
        }
    }
    if !removed.is_empty() {
        let _ = a.manifest.write(&a.dir, false);
    }
    removed
}

/// Ends the run of `dir` (every run of this process with `None`): records `status`
/// (`finished`, or `failed: ...`) and the time, and releases the lock.
pub fn finish(dir: Option<&Path>, status: &str) {
    finish_runs(active(), dir, status);
}

/// [`finish`] of every run of this process, waiting at most `wait` for the folders' state
/// (the panic path, [`crate::interrupt::stop_with`]).
pub(crate) fn finish_within(status: &str, wait: std::time::Duration) {
    if let Some(runs) = crate::interrupt::lock_within(&ACTIVE, wait) {
        finish_runs(runs, None, status);
    }
}

fn finish_runs(mut runs: std::sync::MutexGuard<'_, Vec<Active>>, dir: Option<&Path>, status: &str) {
    let canon = dir.and_then(|d| fs::canonicalize(d).ok());
    let (done, kept): (Vec<Active>, Vec<Active>) = runs
        .drain(..)
        .partition(|a| dir.is_none() || canon.as_ref() == Some(&a.dir));
    *runs = kept;
    drop(runs);
    for mut a in done {
        let id = a.id;
        if let Some(r) = a.manifest.run_mut(id) {
            r.status = status.into();
            r.ended = Some(now_utc());
        }
        let _ = a.manifest.write(&a.dir, true);
        // Removed while still locked: a run waiting on this file retries on the path.
        let _ = fs::remove_file(a.dir.join(LOCK));
        let _ = a.lock.unlock();
    }
}

#[cfg(test)]
mod tests;
