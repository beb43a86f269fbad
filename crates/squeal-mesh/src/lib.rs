//! Tet10 meshes for squeal.
//!
//! - [`model`]: the mesh every later stage reads ([`Mesh`]): nodes, 10-node tetrahedra in one
//!   canonical node ordering ([`tet10::EDGES`]), named node and element sets, materials.
//! - [`inp`], [`msh`], [`nastran`] and [`cdb`]: readers for Abaqus/CalculiX `.inp`, Gmsh
//!   `.msh` (2.2 and 4.1, ASCII and binary), Nastran bulk data (`.bdf`, `.nas`, `.dat`) and
//!   Ansys `.cdb`; [`read`] picks one by the file's extension.
//!
//! # A file without 10-node tetrahedra
//! Abaqus and Gmsh themselves open a file of nodes only, or of other element types (Gmsh
//! shows it, Abaqus/CAE imports it). squeal reads a mesh to analyse it, and a mesh without
//! tet10 elements has no stiffness and no mass: every later number would be zero or
//! meaningless. So reading a mesh *file* ([`read`], [`inp::read`], [`msh::read`]) without a
//! single tet10 is an error, which lists the element types that were skipped (a first-order
//! mesh, shells) and says that a file cut off before its elements reads like this. Parsing
//! text held in memory ([`inp::parse`], [`msh::parse`], for fragments and tests) gives the
//! mesh with a warning instead.
//! - [`part`]: the sub-mesh of one element set of an assembly file, and the bodies (connected
//!   components of elements) a file holds.
//! - [`quality`]: inverted or badly curved elements, missing nodes, duplicate coordinates,
//!   unused nodes, empty sets.
//! - [`vtu`]: VTK XML unstructured grids (quadratic tetra, cell type 24) with point and cell
//!   fields, and `.pvd` collections for time series, for ParaView.
//! - [`generate`]: structured tet10 meshes of boxes, for tests and convergence studies.
//! - [`select`]: sets chosen by geometry (boundary faces on a cylinder or plane, by normal,
//!   in a box; nodes on a surface or in a box), with their counts, areas and centroids.
//! - [`units`]: consistent unit systems (SI, mm-t-s, ...), conversion of a mesh to SI and
//!   warnings when its numbers look like another system's.

#![warn(missing_docs)]

pub mod builder;
pub mod cdb;
pub mod error;
pub mod file;
pub mod generate;
pub mod inp;
pub mod model;
pub mod msh;
pub mod nastran;
pub mod part;
pub mod quality;
pub mod select;
pub mod units;
pub mod vtu;

pub use builder::MeshBuilder;
pub use error::{Location, MeshError, Warning};
pub use model::{BlockVisitor, Blocks, Dangling, Elastic, Material, Mesh, NotTet10, Section};
pub use squeal_element::ElementKind;
/// The 10-node tetrahedron (its reference element lives in `squeal-element`).
pub use squeal_element::tet10;

use std::path::Path;

/// A mesh as read from a file, with the reader's warnings (skipped keywords, skipped
/// non-tetrahedral elements, ...).
#[derive(Clone, Debug)]
pub struct ReadMesh {
    /// The mesh, with the file's ids resolved to dense indices and the elements in canonical
    /// node order.
    pub mesh: Mesh,
    /// What the reader skipped or doubted without failing, each with its file and place.
    pub warnings: Vec<Warning>,
}

/// The warning of a parse that found no tet10 element, and the start of [`read`]'s error.
pub(crate) const NO_TET10: &str = "no quadratic solid element (Abaqus C3D10, C3D20, C3D20R, C3D15; Gmsh types 11, 17, 18, 19; Nastran CTETRA, CHEXA, CPENTA, CPYRAM with edge grids; Ansys SOLID186, SOLID187) in the file";

/// A mesh file must hold tet10 elements (see the module documentation): the error names the
/// file and repeats the warnings about skipped element types.
pub(crate) fn require_tet10(read: ReadMesh) -> Result<ReadMesh, MeshError> {
    if read.mesh.num_elements() > 0 {
        return Ok(read);
    }
    let Some(empty) = read.warnings.iter().find(|w| w.message == NO_TET10) else {
        return Ok(read);
    };
    let skipped: String = read
        .warnings
        .iter()
        .filter(|w| w.message.starts_with("skipped ") && w.message.contains(" of type "))
        .map(|w| format!("; {}", w.message))
        .collect();
    Err(MeshError::invalid(
        empty.file.clone(),
        Location::File,
        format!(
            "{NO_TET10}, which has {} nodes{skipped}. squeal analyses meshes of quadratic solids only; \
             a file cut off before its elements also reads like this: check that it is complete",
            read.mesh.num_nodes()
        ),
    ))
}

/// Reads a mesh file, choosing the reader by extension: `.inp` (Abaqus/CalculiX), `.msh`
/// (Gmsh 2.2 / 4.1, ASCII or binary), `.bdf`, `.nas`, `.dat` (Nastran bulk data) or `.cdb`
/// (Ansys, as CDWRITE writes it).
pub fn read(path: &Path) -> Result<ReadMesh, MeshError> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("inp") => inp::read(path),
        Some("msh") => msh::read(path),
        Some("bdf" | "nas" | "dat") => nastran::read(path),
        Some("cdb") => cdb::read(path),
        _ => Err(MeshError::UnknownFormat {
            file: path.to_path_buf(),
        }),
    }
}
