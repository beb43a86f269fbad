//! Tet10 meshes for squeal.
//!
//! - [`model`]: the mesh every later stage reads ([`Mesh`]): nodes, 10-node tetrahedra in one
//!   canonical node ordering ([`tet10::EDGES`]), named node and element sets, materials.
//! - [`inp`] and [`msh`]: readers for Abaqus/CalculiX `.inp` and Gmsh `.msh` (2.2 and 4.1,
//!   ASCII and binary); [`read`] picks one by the file's extension.
//! - [`quality`]: inverted or badly curved elements, missing nodes, duplicate coordinates,
//!   unused nodes, empty sets.
//! - [`vtu`]: VTK XML unstructured grids (quadratic tetra, cell type 24) with point and cell
//!   fields, and `.pvd` collections for time series, for ParaView.
//! - [`generate`]: structured tet10 meshes of boxes, for tests and convergence studies.

#![warn(missing_docs)]

pub mod builder;
pub mod error;
pub mod generate;
pub mod inp;
pub mod model;
pub mod msh;
pub mod quality;
pub mod tet10;
pub mod vtu;

pub use builder::MeshBuilder;
pub use error::{Location, MeshError, Warning};
pub use model::{Dangling, Elastic, Material, Mesh, Section};

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

/// Reads a mesh file, choosing the reader by extension: `.inp` (Abaqus/CalculiX) or `.msh`
/// (Gmsh 2.2 / 4.1, ASCII or binary).
pub fn read(path: &Path) -> Result<ReadMesh, MeshError> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("inp") => inp::read(path),
        Some("msh") => msh::read(path),
        _ => Err(MeshError::UnknownFormat {
            file: path.to_path_buf(),
        }),
    }
}
