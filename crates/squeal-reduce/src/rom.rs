//! The reduced-model file (`.rom`): one versioned format for the reduced brake.
//!
//! The container is the [safetensors](https://github.com/huggingface/safetensors) layout:
//! an 8-byte little-endian header length `N`, `N` bytes of JSON describing each array
//! (`dtype`, `shape`, byte range), then the arrays' raw little-endian bytes, row-major.
//! The JSON's `__metadata__.squeal` entry holds this module's [`RomHeader`] as a JSON string:
//! format name and version, tool version, and for each part the mesh it came from (path and
//! SHA-256), materials, restraints, interface model, retained points with coordinates, the
//! label of every reduced dof, and the fixed-interface frequencies.
//!
//! Arrays, for each part `p` (`disc`, `pad`):
//! - `p.K`, `p.M` — reduced stiffness and mass (eqs 6–7), `n x n`, F64;
//! - `p.basis` — the Craig–Bampton basis `[T_C T_phi]` on the part's free dofs,
//!   `n_free x n`, F64 (present unless the model was written without it);
//! - `p.dof_node`, `p.dof_dir` — the mesh node id (U64) and direction (U8, 0 = x) of each
//!   basis row, so that `u_mesh = basis @ q` can be put back on the mesh.
//!
//! Reading from Python with numpy alone is shown in `docs/rom-format.md`.

use faer::Mat;
use safetensors::tensor::{Dtype, Metadata, TensorInfo};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::io::Write;
use std::path::{Path, PathBuf};

mod arrays;
mod read;
pub use arrays::sha256_file;
#[allow(unused_imports)]
use arrays::*;
pub use read::read_header;

/// Name of the format in the header.
pub const FORMAT: &str = "squeal-rom";
/// Version of the format written by this code; readers refuse newer versions.
/// Version 2 added `has_basis` and `build` to each part; version 3 each part's `role`, each
/// point's `normal` and `surface`, node-interface points' tributary `area`, and dofs along a
/// point's normal (`along`). Version 4 added parts of role `body` (a caliper, a bracket),
/// points of role `coupling` (a node set's mean motion, six dofs: three translations and
/// three `rotation` dofs) and the header's `connections` between parts
/// ([`crate::coupling`]), and later, still version 4, points of role `tie` and the header's
/// `ties` between parts ([`crate::part_tie`]; absent from files without them, so those read
/// as before). Files of versions 1 to 3 still read (their parts are a disc and
/// pads); a scene reduces them again ([`crate::brake::freshness`]).
pub const VERSION: u32 = 4;

/// Largest JSON header accepted when reading (the header of the fine brake is about 20 kB).
const MAX_HEADER_BYTES: u64 = 64 << 20;

/// Errors reading or writing a reduced-model file.
#[derive(Debug, thiserror::Error)]
pub enum RomError {
    /// The reason is in the message and is not also a `source()` (an error chain printed with
    /// `{:#}` would otherwise show it twice).
    #[error("{}: {error}", path.display())]
    Io {
        /// The file that could not be read.
        path: PathBuf,
        /// What the operating system said.
        error: std::io::Error,
    },
    /// The file could not be written (it is written atomically, through a temporary file).
    #[error(transparent)]
    Write(#[from] squeal_io::IoError),
    /// The arrays do not match the checksum the file records, or hold a value that is not
    /// finite: the file changed after it was written.
    #[error(
        "{}: damaged reduced-model file: {message} (a scene's run reduces the meshes again; else delete the file and reduce again)",
        path.display()
    )]
    Damaged {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// The file is not a reduced-model file, or is truncated or damaged.
    #[error("{}: not a reduced-model file: {message}", path.display())]
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// The file was written by a newer squeal, in a format version this one does not read.
    #[error("{}: format version {found} is newer than this squeal reads ({VERSION})", path.display())]
    Version {
        /// The file.
        path: PathBuf,
        /// The version it declares.
        found: u32,
    },
    /// The model could not be turned into the file's bytes (header JSON or arrays).
    #[error("cannot serialize the reduced model: {0}")]
    Serialize(String),
}

/// How a part's contact points are tied to its mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum InterfaceKind {
    /// Each contact point is one mesh node (the paper's model).
    Node,
    /// Each contact point is the area-weighted mean motion of a patch of the contact face.
    Patch,
    /// Every node of the pad's friction face is a contact point, paired with the point of the
    /// disc face it projects onto, whose motion is the disc face's shape functions there
    /// applied to the disc face's nodes ([`crate::interface::nodal`]).
    Nodal,
}

impl InterfaceKind {
    /// The name the scene file uses (`[model] interface`), as the `.rom` header spells it.
    pub fn name(self) -> &'static str {
        match self {
            InterfaceKind::Node => "node",
            InterfaceKind::Patch => "patch",
            InterfaceKind::Nodal => "nodal",
        }
    }
}

/// What a part is in the brake.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PartRole {
    /// The disc: clamped at the hub, its contact points on the faces the pads press on.
    Disc,
    /// A pad: contact points on its friction face, loaded on its back (pistons or fingers).
    Pad,
    /// Any further part (a caliper, a bracket, a knuckle): no contact with the disc, tied to
    /// the other parts by [`crate::coupling::Connection`]s at its coupling points (version 4).
    Body,
}

/// What a retained interface point is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PointRole {
    /// A contact point: where the part touches the other part.
    Contact,
    /// A piston point: where the piston load enters the pad (its dof along the normal is
    /// kept).
    Piston,
    /// A node of the disc's contact face kept as a boundary point (nodal interface): the disc's
    /// contact points are combinations of these ([`InterfacePoint::projected`]); on a pad, a
    /// node of an 8-node friction face that is no contact point itself, whose Gauss points
    /// combine it ([`InterfacePoint::combines`]).
    Face,
    /// A node set's mean motion ([`crate::coupling`]): three translations and three rotations,
    /// where a connection to another part or to ground acts (version 4).
    Coupling,
    /// A node of a tie between parts, its three dofs kept ([`crate::part_tie`]).
    Tie,
}

/// A retained interface point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct InterfacePoint {
    /// Contact or piston point.
    pub role: PointRole,
    /// The mesh node id (node interface and piston points).
    pub node_id: Option<u64>,
    /// The patch number, 1-based (patch interface).
    pub patch: Option<usize>,
    /// Coordinates: the node's, or the patch's centroid.
    pub position: [f64; 3],
    /// Area the point stands for (m²): the patch's (patch interface), the node's tributary
    /// area on the contact face (node interface, from version 3), a piston footprint's.
    pub area: Option<f64>,
    /// Unit outward normal of the part's surface at the point (the area-weighted mean over the
    /// patch, the node's tributary cell or the footprint); for a piston point, the direction
    /// of its dof. Absent in files before version 3.
    #[serde(default)]
    pub normal: Option<[f64; 3]>,
    /// The contact surface of a disc contact point: the name of the pad it faces (a disc
    /// braked by two pads has one surface per pad). Absent on pads and in one-pad files.
    #[serde(default)]
    pub surface: Option<String>,
    /// A disc contact point of the nodal interface: the pad node projected onto the disc face
    /// here, and the disc face points whose combination is this point's motion. Such a point
    /// has no dofs of its own. Absent for every other point (and so from the files of the
    /// other interfaces).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub projected: Option<Projected>,
    /// A pad contact point of the nodal interface at a Gauss point of an 8-node face
    /// ([`crate::interface::quad_contact`]): `(point index, weight)` over the pad's points
    /// whose dofs it combines (its face's eight nodes, kept as [`PointRole::Contact`] or
    /// [`PointRole::Face`] points), `u = Σ w u_k`, the face's shape functions there. Such a
    /// point has no dofs of its own. Absent for every other point.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub combines: Option<Vec<(usize, f64)>>,
}

/// Where a pad node of the nodal interface lands on the disc face
/// ([`crate::interface::nodal`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Projected {
    /// The pad (its part name) and the index of its contact point projected here.
    pub pad: String,
    /// Index of the pad's contact point among the pad part's points.
    pub pad_point: usize,
    /// `(point index, weight)` over the disc's [`PointRole::Face`] points: the point moves as
    /// `r = Σ w u`, the disc face's shape functions at the projected point (weights summing to
    /// 1).
    pub weights: Vec<(usize, f64)>,
    /// How far (m) the pad node lies outside the disc face's triangles, measured in the face:
    /// 0 when its projection falls inside them, else the distance from the foot of its
    /// projection on the face's plane to the nearest point of the face boundary, where it is
    /// put.
    pub outside: f64,
}

/// The meaning of one reduced dof.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum DofLabel {
    /// Physical motion of interface point `point` (index into `points`) along `direction`
    /// (0 = x, 1 = y, 2 = z): a constraint-mode coordinate.
    Point {
        /// Index of the point in [`PartInfo::points`].
        point: usize,
        /// Direction: 0 = x, 1 = y, 2 = z.
        direction: u8,
    },
    /// Amplitude of fixed-interface mode `mode` (0-based, ascending frequency).
    Mode {
        /// Mode number, 0-based, in ascending frequency.
        mode: usize,
    },
    /// Motion of interface point `point` along the unit vector `direction` (a piston pushing
    /// along a pad normal that is not a coordinate axis).
    Along {
        /// Index of the point in [`PartInfo::points`].
        point: usize,
        /// Unit vector of the motion.
        direction: [f64; 3],
    },
    /// Rotation (rad) of coupling point `point` about coordinate axis `axis` (0 = x): the
    /// least-squares rigid rotation of its node set ([`crate::coupling`], version 4).
    Rotation {
        /// Index of the point in [`PartInfo::points`].
        point: usize,
        /// Axis: 0 = x, 1 = y, 2 = z.
        axis: u8,
    },
}

/// The mesh a part was reduced from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeshInfo {
    /// The mesh file's path, as given.
    pub path: String,
    /// SHA-256 of the file's bytes (hex), to tell whether the mesh changed since.
    pub sha256: String,
    /// Number of nodes in the mesh.
    pub nodes: usize,
    /// Number of elements in the mesh.
    pub elements: usize,
}

impl MeshInfo {
    /// A mesh built in memory, not read from a file: `name` as its path, no hash, no counts.
    pub fn in_memory(name: &str) -> Self {
        Self {
            path: name.into(),
            sha256: String::new(),
            nodes: 0,
            elements: 0,
        }
    }
}

/// A material as used by a part's elements.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MaterialInfo {
    /// The mesh's material name, or the element set of an override.
    pub name: String,
    /// Elements made of it.
    pub elements: usize,
    /// Its constants (`type`: `isotropic`, `transversely_isotropic` or `orthotropic`).
    pub material: squeal_fe::ElasticMaterial,
}

/// A restraint applied before reduction.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RestraintInfo {
    /// The restrained node set (`(nodes)` for nodes given by index).
    pub node_set: String,
    /// Restrained directions x, y, z.
    pub directions: [bool; 3],
    /// Number of nodes restrained.
    pub nodes: usize,
}

/// Everything about a part except its arrays.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PartInfo {
    /// The part's name (`disc`, or the pad's name).
    pub name: String,
    /// Disc or pad; absent before version 3, where the part named `disc` is the disc and
    /// every other part a pad ([`PartInfo::role`]).
    #[serde(default, rename = "role")]
    pub role_field: Option<PartRole>,
    /// The mesh the part was reduced from.
    pub mesh: MeshInfo,
    /// Node or patch interface.
    pub interface: InterfaceKind,
    /// The materials of its elements.
    pub materials: Vec<MaterialInfo>,
    /// The restraints applied before reduction.
    pub restraints: Vec<RestraintInfo>,
    /// The retained interface points (contact, then piston), indexed by [`DofLabel`].
    pub points: Vec<InterfacePoint>,
    /// The meaning of each reduced dof, in the order of the rows of `K̂` and `M̂`:
    /// the boundary coordinates first, then the fixed-interface modes.
    pub dofs: Vec<DofLabel>,
    /// Fixed-interface natural frequencies (Hz) of the kept modes, ascending.
    pub fixed_interface_hz: Vec<f64>,
    /// Free dofs of the full part (rows of the basis).
    pub full_dofs: usize,
    /// Whether the file holds the part's basis (`p.basis`, `p.dof_node`, `p.dof_dir`).
    #[serde(default)]
    pub has_basis: bool,
    /// The options the part was reduced with, to tell whether the file is still valid for
    /// given inputs (see [`crate::brake::freshness`]); absent in files made part by part.
    #[serde(default)]
    pub build: Option<BuildRecord>,
}

impl PartInfo {
    /// The part's role: as recorded, else by name (`disc` is the disc, anything else a pad).
    pub fn role(&self) -> PartRole {
        self.role_field.unwrap_or(if self.name == "disc" {
            PartRole::Disc
        } else {
            PartRole::Pad
        })
    }
}

/// A contact surface of a part: the node sets of its contact points (node interface) and of
/// its contact face (patch interface), and the pad it faces. A disc braked by several pads
/// has one per pad; its contact points carry the pad's name as their
/// [`InterfacePoint::surface`].
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ContactSurface {
    /// The pad it faces (`None`: the brake's only pad).
    pub facing: Option<String>,
    /// Node set of the contact points (node interface).
    pub contact_set: String,
    /// Node set of the contact face (patch interface).
    pub contact_face_set: String,
}

impl ContactSurface {
    /// A part's contact surfaces: its own sets (`contact_set`, `contact_face_set`, facing
    /// `facing`) first, then the further ones, `extra`.
    pub fn list(
        facing: &Option<String>,
        contact_set: &str,
        contact_face_set: &str,
        extra: &[ContactSurface],
    ) -> Vec<ContactSurface> {
        std::iter::once(ContactSurface {
            facing: facing.clone(),
            contact_set: contact_set.to_string(),
            contact_face_set: contact_face_set.to_string(),
        })
        .chain(extra.iter().cloned())
        .collect()
    }
}

/// The options a part was reduced with, as given (before reading the mesh).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BuildRecord {
    /// Restraints: node set (or `nodes i,j,...` for indices) and restrained directions x, y, z.
    pub restraints: Vec<(String, [bool; 3])>,
    /// Material overrides (element set, material) applied after the mesh's sections.
    pub material_overrides: Vec<(String, squeal_fe::ElasticMaterial)>,
    /// Node set of the contact points (node interface).
    pub contact_set: String,
    /// Node set of the contact face (patch interface).
    pub contact_face_set: String,
    /// Node set of the piston nodes, if any.
    pub piston_set: Option<String>,
    /// The pistons' footprints, one node set each (absent when the pistons are the nodes of
    /// `piston_set`, and in older files).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub piston_footprints: Vec<String>,
    /// The pad the contact set faces, on a disc braked by several pads (absent otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub facing: Option<String>,
    /// The disc's further contact surfaces, one per further pad (absent with one pad).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub extra_surfaces: Vec<ContactSurface>,
    /// Patch grid `[radial, angular]`.
    pub grid: [usize; 2],
    /// The disc's axis, around which the patches are laid out.
    pub axis: crate::interface::Axis,
    /// Direction of the contact normal and of the piston dofs (0 = x, 1 = y, 2 = z), when
    /// they are along a coordinate axis.
    pub normal_direction: usize,
    /// The piston dofs' unit direction when it is not a coordinate axis (absent otherwise and
    /// in older files).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub piston_direction: Option<[f64; 3]>,
    /// Restraints along global directions that are not coordinate axes: node set and unit
    /// directions (absent when there are none, and in older files).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub skew_restraints: Vec<(String, Vec<[f64; 3]>)>,
    /// Restraints relative to the disc's axis: node set and directions (absent when there are
    /// none, and in older files).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub axis_restraints: Vec<(String, Vec<squeal_fe::frames::AxisDirection>)>,
    /// How many fixed-interface modes were asked for.
    pub modes: crate::brake::ModeChoice,
    /// Most fixed-interface modes a part may keep.
    pub max_modes: usize,
    /// Eigensolver backend (`lanczos` or `arpack`) and relative tolerance.
    pub backend: String,
    /// Relative tolerance of the eigensolver.
    pub eig_tol: f64,
    /// Modal block of `M̂` made the identity after the solve.
    pub orthonormalize: bool,
    /// The unit system the mesh file was written in and converted to SI from on reading
    /// (`None`: SI; absent from files of earlier versions, which read SI meshes only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub units: Option<String>,
    /// The element set of the mesh file the part is (absent for a whole file, and in older
    /// files).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub elset: Vec<String>,
    /// Tied interfaces inside the part (absent when there are none, and in older files).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ties: Vec<crate::tie::Tie>,
    /// Springs to ground (absent when there are none, and in older files).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub supports: Vec<crate::tie::Support>,
    /// Springs between node sets or to ground (absent when there are none, and in older
    /// files).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub springs: Vec<crate::springs::Spring>,
    /// Node sets kept as coupling points (absent when there are none, and in older files).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub couplings: Vec<crate::coupling::CouplingSet>,
}

/// The JSON header stored in `__metadata__.squeal`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RomHeader {
    /// Format name, [`FORMAT`].
    pub format: String,
    /// Format version, at most [`VERSION`].
    pub version: u32,
    /// The squeal that wrote the file ([`crate::brake::TOOL_VERSION`]).
    pub tool_version: String,
    /// The parts, in the order their dofs are stacked in the brake.
    pub parts: Vec<PartInfo>,
    /// CRC-32 (IEEE, as zlib's `crc32`) of the arrays' bytes, everything after the JSON
    /// table, as 8 lowercase hex digits: a reader refuses a file whose arrays changed after
    /// writing (a flipped bit). Absent from files written before it was added, which read
    /// without the check.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arrays_crc32: Option<String>,
    /// Springs between the parts' coupling points or to ground (version 4; absent when there
    /// are none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub connections: Vec<crate::coupling::Connection>,
    /// Ties between parts, eliminated on the assembled model ([`crate::part_tie`]; absent
    /// when there are none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ties: Vec<crate::part_tie::PartTie>,
}

/// The basis `[T_C T_phi]` on the part's free dofs, with each row's node id and direction.
#[derive(Clone, Debug, PartialEq)]
pub struct Basis {
    /// Mesh node id of each row.
    pub dof_node: Vec<u64>,
    /// Direction of each row: 0 = x, 1 = y, 2 = z.
    pub dof_dir: Vec<u8>,
    /// `n_free x n_reduced`.
    pub values: Mat<f64>,
}

/// A reduced part: its description, reduced K and M, and optionally its basis.
#[derive(Clone, Debug, PartialEq)]
pub struct ReducedPart {
    /// Everything about the part but its arrays.
    pub info: PartInfo,
    /// Reduced stiffness `K̂` (N/m on point dofs), eq (6).
    pub k: Mat<f64>,
    /// Reduced mass `M̂` (kg on point dofs), eq (7).
    pub m: Mat<f64>,
    /// The full-space basis, if it was kept.
    pub basis: Option<Basis>,
}

impl ReducedPart {
    /// Number of reduced dofs.
    pub fn size(&self) -> usize {
        self.k.nrows()
    }
}

/// A reduced model: the parts, in the order their dofs are stacked in the brake.
#[derive(Clone, Debug, PartialEq)]
pub struct ReducedModel {
    /// The squeal that made the model.
    pub tool_version: String,
    /// The parts.
    pub parts: Vec<ReducedPart>,
    /// Springs between the parts' coupling points or to ground ([`crate::coupling`]).
    pub connections: Vec<crate::coupling::Connection>,
    /// Ties between parts, eliminated on the assembled model ([`crate::part_tie`]).
    pub ties: Vec<crate::part_tie::PartTie>,
}

impl ReducedModel {
    /// The part called `name`.
    pub fn part(&self, name: &str) -> Option<&ReducedPart> {
        self.parts.iter().find(|p| p.info.name == name)
    }

    /// The pads, in the order of their dofs (the parts of role pad).
    pub fn pads(&self) -> Vec<&ReducedPart> {
        self.parts
            .iter()
            .filter(|p| p.info.role() == PartRole::Pad)
            .collect()
    }

    /// The parts of role body (a caliper, a bracket), in the order of their dofs.
    pub fn bodies(&self) -> Vec<&ReducedPart> {
        self.parts
            .iter()
            .filter(|p| p.info.role() == PartRole::Body)
            .collect()
    }

    /// Total reduced dofs.
    pub fn size(&self) -> usize {
        self.parts.iter().map(ReducedPart::size).sum()
    }

    /// Writes the model to `path` atomically, each array streamed into the file as it is
    /// converted (no copy of the whole file in memory).
    pub fn write(&self, path: &Path) -> Result<(), RomError> {
        let (header, arrays) = self.layout()?;
        squeal_io::atomic_write(path, |w| write_file(w, &header, &arrays))?;
        Ok(())
    }

    /// Serializes the model: the bytes [`ReducedModel::write`] writes.
    pub fn to_bytes(&self) -> Result<Vec<u8>, RomError> {
        let (header, arrays) = self.layout()?;
        let mut bytes =
            Vec::with_capacity(header.len() + arrays.iter().map(|(_, a)| a.len()).sum::<usize>());
        write_file(&mut bytes, &header, &arrays).map_err(|e| RomError::Serialize(e.to_string()))?;
        Ok(bytes)
    }

    /// The file's arrays in the order safetensors stores them and its header: the header's
    /// length (8 bytes, little-endian), then the JSON that names every array's type, shape and
    /// byte range, padded with spaces to a multiple of 8 bytes (what `safetensors::serialize`
    /// writes, bit for bit: tested).
    fn layout(&self) -> Result<(Vec<u8>, Vec<Named<'_>>), RomError> {
        let mut arrays: Vec<Named> = Vec::new();
        for p in &self.parts {
            let name = &p.info.name;
            arrays.push((format!("{name}.K"), Array::Mat(&p.k)));
            arrays.push((format!("{name}.M"), Array::Mat(&p.m)));
            if let Some(b) = &p.basis {
                arrays.push((format!("{name}.basis"), Array::Mat(&b.values)));
                let dof_node = b.dof_node.iter().flat_map(|v| v.to_le_bytes()).collect();
                arrays.push((format!("{name}.dof_node"), Array::U64(dof_node)));
                arrays.push((format!("{name}.dof_dir"), Array::U8(&b.dof_dir)));
            }
        }
        // safetensors' order: by type, widest first, then by name.
        arrays.sort_by(|(a, x), (b, y)| y.dtype().cmp(&x.dtype()).then(a.cmp(b)));
        // The checksum of the bytes the arrays will be written as, in this order.
        let mut crc = CrcWriter(crc32fast::Hasher::new());
        arrays
            .iter()
            .try_for_each(|(_, a)| a.write(&mut crc))
            .map_err(|e| RomError::Serialize(e.to_string()))?;
        let header = RomHeader {
            format: FORMAT.into(),
            version: VERSION,
            tool_version: self.tool_version.clone(),
            parts: self
                .parts
                .iter()
                .map(|p| PartInfo {
                    has_basis: p.basis.is_some(),
                    ..p.info.clone()
                })
                .collect(),
            arrays_crc32: Some(format!("{:08x}", crc.0.finalize())),
            connections: self.connections.clone(),
            ties: self.ties.clone(),
        };
        let json =
            serde_json::to_string(&header).map_err(|e| RomError::Serialize(e.to_string()))?;
        let mut offset = 0;
        let infos = arrays
            .iter()
            .map(|(name, a)| {
                let info = TensorInfo {
                    dtype: a.dtype(),
                    shape: a.shape(),
                    data_offsets: (offset, offset + a.len()),
                };
                offset += a.len();
                (name.clone(), info)
            })
            .collect();
        let meta = HashMap::from([("squeal".to_string(), json)]);
        let metadata =
            Metadata::new(Some(meta), infos).map_err(|e| RomError::Serialize(e.to_string()))?;
        let mut json =
            serde_json::to_vec(&metadata).map_err(|e| RomError::Serialize(e.to_string()))?;
        json.resize(json.len().next_multiple_of(8), b' ');
        let mut header = (json.len() as u64).to_le_bytes().to_vec();
        header.extend(json);
        Ok((header, arrays))
    }
}

/// An array of the file with its name.
type Named<'a> = (String, Array<'a>);
#[cfg(test)]
mod tests;
