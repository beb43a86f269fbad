//! Linear-elastic finite elements for squeal: 10-node tetrahedra, stiffness and consistent
//! mass, sparse parallel assembly.
//!
//! - [`quadrature`]: rules on the reference tetrahedron (degree 2 for the stiffness of
//!   straight-sided elements, degree 6 for curved ones, degree 5 for mass, collapsed Gauss of
//!   any degree).
//! - [`material`]: isotropic, transversely isotropic and orthotropic elasticity (Abaqus
//!   conventions), and the material of each element from the mesh's sections and overrides.
//! - [`element`]: element stiffness, mass, volume and strain of the isoparametric tet10.
//! - [`dofmap`]: free dofs after restraints, node-major.
//! - [`frames`]: restraints along directions that are not coordinate axes (nodes with
//!   their own axes, as Abaqus' `*TRANSFORM`, exact by congruence), and the axial, radial and
//!   tangential directions of a rotation axis anywhere in space (the tangent is the sliding
//!   direction of the disc's surface).
//! - [`assembly`]: global `K` and `M` as faer sparse matrices (both triangles), deterministic
//!   for any thread count; volume, mass and size summaries.
//! - [`export`]: MatrixMarket files with the dof map as CSV.
//!
//! ```no_run
//! use squeal_fe::{DofMap, ElasticMaterial, MaterialTable, Restraint, assemble};
//! let mesh = squeal_mesh::generate::box_tet10([1.0, 0.1, 0.1], [10, 1, 1]);
//! let steel = ElasticMaterial::isotropic(210e9, 0.3, 7850.0);
//! let materials = MaterialTable::uniform(&mesh, steel)?;
//! let dofs = DofMap::new(&mesh, &[Restraint::clamp("XMIN")])?;
//! let system = assemble(&mesh, &materials, &dofs)?;
//! # Ok::<(), squeal_fe::FeError>(())
//! ```

// Index loops mirror the formulas (B, C, Voigt pairs); iterator rewrites would hide them.
#![allow(clippy::needless_range_loop)]

pub mod assembly;
pub mod dofmap;
pub mod element;
pub mod error;
pub mod export;
pub mod frames;
pub mod material;
/// Quadrature rules on the reference elements (in `squeal-element`).
pub use squeal_element::quadrature;

pub use assembly::{
    AssemblyOptions, STRAIGHT_TOLERANCE, Summary, System, assemble, assemble_with, mesh_volume,
    total_mass,
};
pub use dofmap::{DofMap, DofStatus, NodeSelection, Restraint};
pub use element::{
    element_mass, element_mass_scalar, element_stiffness, element_volume, mass_scalar_of,
    stiffness_of, strain_at, strain_of, volume_of,
};
pub use error::{ElementError, FeError, MaterialError};
pub use export::write_matrix_market;
pub use material::{ElasticMaterial, MaterialEntry, MaterialTable, Voigt6};
pub use quadrature::Quadrature;
pub use squeal_element::{ElementKind, Hex20, Pyramid13, ReferenceElement, Tet10, Wedge15};
