//! Finished part reductions kept when another part's reduction fails, and taken up again by
//! the next run.
//!
//! The parts of a brake are reduced side by side ([`reduce_brake_keeping`]); when one of them
//! fails (a tie that does not close, a part of two bodies, an eigensolver that does not
//! converge) after others have finished, the finished ones are written, each as a one-part
//! `.rom`, into the folder [`kept_dir`] beside the model's file (`brake.rom.parts/disc.rom`),
//! before the error is returned. The next reduction takes a part from there instead of
//! reducing it again when the kept file stands for the part as now asked for: by the same test
//! as a whole model's freshness ([`super::freshness`]): the same tool version, the same mesh
//! by SHA-256, the same interface and the same build record (restraints, sets, options,
//! ties, supports, springs), and a basis when one is asked for. A kept part is taken as
//! reduced, before the nodal interface's projections are attached (those are redone). The
//! caller removes the folder once the whole model is written ([`forget_kept`]).

use super::*;

/// The folder of kept part reductions of the model at `rom`: `<rom>.parts`.
pub fn kept_dir(rom: &Path) -> PathBuf {
    let mut name = rom.file_name().unwrap_or_default().to_os_string();
    name.push(".parts");
    rom.with_file_name(name)
}

/// The kept file of part `name` in `dir`.
fn kept_file(dir: &Path, name: &str) -> PathBuf {
    dir.join(format!("{name}.rom"))
}

/// The kept reduction of part `name` (`input` of `inputs`, its mesh hashing to `hash`) in
/// `dir`, when there is one that stands for it (module docs); `None` otherwise (missing,
/// stale or unreadable: reduced again).
pub(super) fn take_kept(
    dir: &Path,
    name: &str,
    input: &PartInput,
    inputs: &BrakeInputs,
    hash: &str,
) -> Option<ReducedPart> {
    let path = kept_file(dir, name);
    let header = read_header(&path).ok()?;
    let [info] = header.parts.as_slice() else {
        return None;
    };
    if header.tool_version != TOOL_VERSION
        || header.version < VERSION
        || info.name != name
        || !part_reasons(info, name, input, inputs, hash).is_empty()
    {
        return None;
    }
    ReducedModel::read(&path).ok()?.parts.pop()
}

/// Writes each finished part into `dir` (made if missing) as a one-part `.rom`; returns the
/// files written.
pub(super) fn keep_parts(dir: &Path, parts: &[&ReducedPart]) -> Result<Vec<PathBuf>, ReduceError> {
    std::fs::create_dir_all(dir).map_err(|e| {
        ReduceError::Options(format!(
            "cannot make {} to keep the finished reductions: {e}",
            dir.display()
        ))
    })?;
    let mut written = Vec::with_capacity(parts.len());
    for part in parts {
        let path = kept_file(dir, &part.info.name);
        let model = ReducedModel {
            tool_version: TOOL_VERSION.into(),
            parts: vec![(*part).clone()],
            connections: Vec::new(),
            ties: Vec::new(),
        };
        model.write(&path)?;
        written.push(path);
    }
    Ok(written)
}

/// The report of part `name` taken from the kept reductions instead of reduced.
pub(super) fn reused_report(name: &str, loaded: LoadedPart) -> PartReport {
    PartReport {
        name: name.into(),
        mesh: loaded.info,
        warnings: loaded.warnings,
        read_time: loaded.read_time,
        reduce: ReduceReport::default(),
        reused: true,
    }
}

/// Removes the kept reductions in `dir` (none there is not an error).
pub fn forget_kept(dir: &Path) -> std::io::Result<()> {
    match std::fs::remove_dir_all(dir) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(e),
        _ => Ok(()),
    }
}
