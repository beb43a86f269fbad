//! A run's hold on its output folder: the lock, the check that the folder holds no user's
//! files (unless forced) and the run in the folder's manifest ([`squeal_io::folder`]); and its
//! release with how the run ended. Every command that writes into an output folder takes it
//! here first, before any work.

use crate::error::{PipelineError, Result};
use std::path::Path;

pub use squeal_io::folder::remove_earlier;
/// Ctrl-C: a run's folder marked interrupted and its lock released before the process ends.
pub use squeal_io::interrupt;

/// Takes the output folder `out` of the scene file `scene` for the command line `command`
/// (`force`: write over files the folder's manifest does not list). Returns the notes to show
/// (earlier runs found, stale locks taken over).
pub fn take(scene: &Path, out: &Path, command: String, force: bool) -> Result<Vec<String>> {
    let sha = squeal_reduce::rom::sha256_file(scene).map_err(|error| PipelineError::Rom {
        path: scene.to_path_buf(),
        error,
    })?;
    let info = squeal_io::folder::RunInfo {
        command,
        scene: Some((scene.to_path_buf(), sha)),
    };
    Ok(squeal_io::folder::begin(out, &info, force)?)
}

/// Releases every folder this process took, recording `status` ("finished", "failed: …") in
/// their manifests.
pub fn release_all(status: &str) {
    squeal_io::folder::finish(None, status);
}
