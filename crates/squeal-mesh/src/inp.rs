//! Abaqus / CalculiX `.inp` reader (being written).

use crate::{MeshError, ReadMesh};
use std::path::Path;

/// Reads an Abaqus `.inp` file.
pub fn read(path: &Path) -> Result<ReadMesh, MeshError> {
    Err(MeshError::invalid(path, crate::Location::File, "the .inp reader is not written yet"))
}
