//! Reading a part's mesh for the reduction, and refusing meshes the reader flags as wrong.

use super::*;

/// The name of an eigensolver backend as written in files and on the command line.
pub fn backend_name(backend: Backend) -> &'static str {
    match backend {
        Backend::Lanczos => "lanczos",
        Backend::Arpack => "arpack",
    }
}

pub(super) fn selection_name(nodes: &NodeSelection) -> String {
    match nodes {
        NodeSelection::Set(s) => s.clone(),
        NodeSelection::Indices(v) => {
            let list: Vec<String> = v.iter().map(u32::to_string).collect();
            format!("nodes {}", list.join(","))
        }
    }
}

/// A part's mesh as read, with what the `.rom` records about the file.
#[derive(Clone, Debug)]
pub struct LoadedPart {
    /// The mesh.
    pub mesh: Mesh,
    /// Its path, SHA-256 and size, as the `.rom` records them.
    pub info: MeshInfo,
    /// The reader's warnings.
    pub warnings: Vec<String>,
    /// Time spent reading and hashing the file.
    pub read_time: Duration,
}

/// Reads a mesh file and hashes it; a mesh with errors ([`refuse_mesh_errors`]) is refused,
/// naming the file.
pub fn load_part(path: &Path) -> Result<LoadedPart, ReduceError> {
    let t = Instant::now();
    let read = squeal_mesh::read(path)?;
    refuse_mesh_errors(&read.mesh).map_err(|e| ReduceError::InMesh {
        path: path.to_path_buf(),
        error: Box::new(e),
    })?;
    let sha256 = sha256_file(path)?;
    let mesh = read.mesh;
    let info = MeshInfo {
        path: path.display().to_string(),
        sha256,
        nodes: mesh.num_nodes(),
        elements: mesh.num_elements(),
    };
    Ok(LoadedPart {
        info,
        warnings: read.warnings.iter().map(|w| w.to_string()).collect(),
        mesh,
        read_time: t.elapsed(),
    })
}

/// Refuses a mesh with what [`squeal_mesh::quality::check`] reports as an error (inverted
/// elements, elements naming a node the file never defines): what `squeal mesh info` calls
/// an ERROR, the reduction refuses.
pub fn refuse_mesh_errors(mesh: &Mesh) -> Result<(), ReduceError> {
    use squeal_mesh::quality::{QualityOptions, check};
    let report = check(mesh, &QualityOptions::default());
    let Some(first) = report.errors().next() else {
        return Ok(());
    };
    let mut ids: Vec<String> = first.ids.iter().take(12).map(u64::to_string).collect();
    if first.ids.len() > 12 {
        ids.push("...".into());
    }
    Err(ReduceError::MeshErrors {
        finding: first.message.clone(),
        ids: ids.join(" "),
    })
}

/// Refuses node set `set` of `mesh` when the file names in it nodes it never defines (the
/// reader drops such members).
pub fn refuse_shortened_set(mesh: &Mesh, set: &str) -> Result<(), ReduceError> {
    let missing: Vec<String> = mesh
        .dangling
        .iter()
        .filter_map(|d| match d {
            squeal_mesh::Dangling::NodeSetMember { set: s, node }
                if s.eq_ignore_ascii_case(set) =>
            {
                Some(node.to_string())
            }
            _ => None,
        })
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    Err(ReduceError::ShortenedSet {
        set: set.into(),
        count: missing.len(),
        ids: missing.join(" "),
    })
}

/// Reads a mesh file written in `units`, converts it to SI ([`UnitSystem::to_si`]) and adds
/// to its warnings those of [`squeal_mesh::units::plausibility`] (a size, modulus or density
/// that looks like another unit system's).
pub fn load_part_in(path: &Path, units: &UnitSystem) -> Result<LoadedPart, ReduceError> {
    let mut part = load_part(path)?;
    units.to_si(&mut part.mesh);
    part.warnings.extend(
        squeal_mesh::units::plausibility(&part.mesh, units)
            .into_iter()
            .map(|w| format!("{}: {w}", path.display())),
    );
    Ok(part)
}

/// [`load_part_in`] of the part made of element sets `elset` of an assembly file
/// ([`squeal_mesh::Mesh::part_of_sets`]: their elements, the nodes they use, the sets
/// restricted to them), or of the whole file when `elset` is empty. The `.rom` records the
/// file's hash and the part's node and element counts.
pub fn load_part_of(
    path: &Path,
    elset: &[String],
    units: &UnitSystem,
) -> Result<LoadedPart, ReduceError> {
    let mut part = load_part_in(path, units)?;
    if !elset.is_empty() {
        part.mesh = part
            .mesh
            .part_of_sets(elset)
            .map_err(|error| ReduceError::Part {
                path: path.to_path_buf(),
                error,
            })?;
        part.info.nodes = part.mesh.num_nodes();
        part.info.elements = part.mesh.num_elements();
    }
    Ok(part)
}
