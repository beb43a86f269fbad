//! Reference solid elements for squeal: the quadratic tetrahedron, hexahedron, wedge and
//! pyramid on their reference domains, with their quadrature rules.
//!
//! - [`mod@reference`]: the [`ReferenceElement`] trait (nodes, shape functions and gradients,
//!   faces, quadrature, VTK and Gmsh node orders), [`ElementKind`] for run-time dispatch,
//!   and the generic Jacobian, volume and quality measures.
//! - [`tet10`], [`hex20`], [`wedge15`], [`pyramid13`]: the elements.
//! - [`quadrature`]: the rules on each reference domain.
//!
//! The mesh crate (node orders, quality, output) and the finite-element crate (element
//! matrices, assembly) both build on this crate, so each element is written down once.

#![warn(missing_docs)]
// Index loops mirror the formulas (J, cofactors); iterator rewrites would hide them.
#![allow(clippy::needless_range_loop)]

pub mod geometry;
pub mod hex20;
pub mod pyramid13;
pub mod quadrature;
pub mod reference;
pub mod tet10;
pub mod wedge15;

pub use hex20::Hex20;
pub use pyramid13::Pyramid13;
pub use quadrature::{Quadrature, QuadratureError};
pub use reference::{ElementKind, Face, FaceKind, ReferenceElement, det3, jacobian};
pub use tet10::Tet10;
pub use wedge15::Wedge15;
