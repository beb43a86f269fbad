//! Whether a cached reduced model still answers its inputs, and if not, why (the header's input hashes and build record against the scene's).

use super::*;
use crate::rom::PartInfo;

/// Whether a `.rom` file can stand for given inputs.
#[derive(Clone, Debug, PartialEq)]
pub enum Freshness {
    /// Made from the same mesh files (by SHA-256) with the same options and tool version.
    Fresh,
    /// No file at that path.
    Missing,
    /// The reasons it cannot be used.
    Stale(Vec<String>),
}

/// Whether the `.rom` at `path` matches `inputs`: the meshes' SHA-256, every recorded
/// option, the tool version and (if `inputs.keep_basis`) the presence of the bases.
/// Reads only the file's header; an unreadable file is stale, an unreadable mesh an error.
pub fn freshness(path: &Path, inputs: &BrakeInputs) -> Result<Freshness, ReduceError> {
    if !path.exists() {
        return Ok(Freshness::Missing);
    }
    let header = match read_header(path) {
        Ok(h) => h,
        Err(e @ (RomError::Format { .. } | RomError::Version { .. } | RomError::Io { .. })) => {
            return Ok(Freshness::Stale(vec![e.to_string()]));
        }
        Err(e) => return Err(e.into()),
    };
    let hashes = inputs
        .parts()
        .iter()
        .map(|(_, p)| sha256_file(&p.mesh))
        .collect::<Result<Vec<_>, _>>()?;
    let reasons = stale_reasons(&header, inputs, &hashes);
    Ok(if reasons.is_empty() {
        Freshness::Fresh
    } else {
        Freshness::Stale(reasons)
    })
}

/// Why a header does not match `inputs` whose mesh files hash to `hashes` (disc, then the
/// pads in order); empty if it matches.
pub fn stale_reasons(header: &RomHeader, inputs: &BrakeInputs, hashes: &[String]) -> Vec<String> {
    let mut reasons = Vec::new();
    if header.version < VERSION {
        reasons.push(format!(
            "written in format version {}, this is version {VERSION} (points with areas and normals)",
            header.version
        ));
    }
    if header.tool_version != TOOL_VERSION {
        reasons.push(format!(
            "made by {}, this is {TOOL_VERSION}",
            header.tool_version
        ));
    }
    let parts = inputs.parts();
    if header.parts.len() != parts.len() {
        reasons.push(format!(
            "{} parts, expected {} ({})",
            header.parts.len(),
            parts.len(),
            parts.iter().map(|p| p.0).collect::<Vec<_>>().join(", ")
        ));
    }
    for ((name, input), hash) in parts.into_iter().zip(hashes) {
        match header.parts.iter().find(|p| p.name == name) {
            None => reasons.push(format!("no part named {name}")),
            Some(info) => reasons.extend(part_reasons(info, name, input, inputs, hash)),
        }
    }
    reasons.extend(connection_reasons(&header.connections, inputs));
    reasons.extend(crate::part_tie::tie_reasons(
        &header.ties,
        &inputs.part_ties,
    ));
    reasons
}

/// Why part `info` of a file does not stand for part `name` of `inputs` (`input`, whose mesh
/// hashes to `hash`): mesh, interface, build record, basis; empty if it does.
pub(super) fn part_reasons(
    info: &PartInfo,
    name: &str,
    input: &PartInput,
    inputs: &BrakeInputs,
    hash: &str,
) -> Vec<String> {
    let mut reasons = Vec::new();
    if info.mesh.sha256 != hash {
        reasons.push(format!(
            "{name}: mesh {} changed (SHA-256 {} in the file, {} now)",
            input.mesh.display(),
            short(&info.mesh.sha256),
            short(hash)
        ));
    }
    if info.interface != inputs.interface {
        reasons.push(format!(
            "{name}: interface \"{}\" in the file, \"{}\" asked for ([model] interface)",
            info.interface.name(),
            inputs.interface.name()
        ));
    }
    match &info.build {
        None => reasons.push(format!("{name}: the file does not record its options")),
        Some(b) => {
            let want = inputs.record(input);
            if *b != want {
                reasons.push(format!(
                    "{name}: options differ ({})",
                    record_differences(b, &want).join("; ")
                ));
            }
        }
    }
    if inputs.keep_basis && !info.has_basis {
        reasons.push(format!("{name}: the file holds no basis"));
    }
    reasons
}

pub(super) fn short(hash: &str) -> &str {
    hash.get(..12).unwrap_or(hash)
}

/// The fields in which two records differ, as `field: file -> asked`.
pub(super) fn record_differences(file: &BuildRecord, want: &BuildRecord) -> Vec<String> {
    let a = serde_json::to_value(file).unwrap_or_default();
    let b = serde_json::to_value(want).unwrap_or_default();
    let (Some(a), Some(b)) = (a.as_object(), b.as_object()) else {
        return vec!["record".into()];
    };
    b.iter()
        .filter(|(k, v)| a.get(*k) != Some(v))
        .map(|(k, v)| {
            let old = a.get(k).map_or("-".to_string(), |o| o.to_string());
            format!("{k}: {old} -> {v}")
        })
        // A key only the file has (an optional field the wanted record leaves out).
        .chain(
            a.iter()
                .filter(|(k, _)| !b.contains_key(*k))
                .map(|(k, v)| format!("{k}: {v} -> -")),
        )
        .collect()
}
