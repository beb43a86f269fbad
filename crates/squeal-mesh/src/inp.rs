//! Abaqus / CalculiX `.inp` reader.
//!
//! # What is read
//!
//! Keywords and parameters are case-insensitive and blanks in them are ignored (`*Solid
//! Section, elset = Disc`); `**` comments and blank lines are skipped; a keyword line ending
//! with a comma continues on the next line when that line starts with a parameter name (a
//! letter or a quoted name); parameter values may be quoted (`NAME="Disc, cast"`).
//!
//! - `*HEADING` (its text lines skipped).
//! - `*NODE` (`NSET=`, `SYSTEM=R|C`): `id, x, y[, z]`, blank or missing coordinates are 0
//!   (CalculiX's own test files give nodes in the plane z = 0 with two coordinates, so a short
//!   node line inside a file cannot be refused; at the end of a file, see below).
//! - `*ELEMENT, TYPE=C3D10` and its variants (`C3D10M`, `C3D10H`, `C3D10HS`, `C3D10I`, ...:
//!   same geometry and node order, which is squeal's canonical order), `ELSET=`; a record is
//!   the id and 10 node ids and continues on the next line while a line ends with a comma.
//!   Other types (S8, C3D4, C3D20, B31, ...) are skipped with one warning per `*ELEMENT`
//!   block; sets may still name them.
//! - `*NSET` / `*ELSET` (with `GENERATE` ranges `start, end[, step]`, members mixing labels and
//!   set names, `INSTANCE=`); several definitions of one set accumulate. A `GENERATE` range
//!   takes the labels in it that are defined *before* its line (a warning counts the others);
//!   its work is bounded by the labels defined, and a range of more than `u32::MAX` members
//!   is an error.
//! - `*PART, NAME=` ... `*END PART`; `*ASSEMBLY` ... `*END ASSEMBLY`; `*INSTANCE, NAME=,
//!   PART=` with an optional translation line and rotation line (translation first, then the
//!   rotation about the axis a -> b by the right-hand rule) ... `*END INSTANCE`.
//! - `*INCLUDE, INPUT=file` (relative to the including file's folder; also `INPUT=` on
//!   `*NODE`, `*ELEMENT`, `*NSET`, `*ELSET` for their data lines). Included lines continue
//!   the keyword before the include.
//! - `*MATERIAL, NAME=` with `*ELASTIC` (`TYPE=ISOTROPIC`: E, nu; `TYPE=ENGINEERING
//!   CONSTANTS`: E1, E2, E3, nu12, nu13, nu23, G12, G13, G23 over two lines) and
//!   `*DENSITY`; `*SOLID SECTION, ELSET=, MATERIAL=`. Temperature-dependent data: the
//!   first values are used, with a warning.
//!
//! Any other keyword is skipped with its data lines: one warning per distinct keyword, at its
//! first occurrence, with the number of occurrences. Keywords that would move or generate
//! nodes (`*NGEN`, `*NFILL`, `*NCOPY`, `*NMAP`, `*ELGEN`, `*ELCOPY`, `*SYSTEM` with data) are
//! errors rather than silently wrong geometry.
//!
//! # Flattening parts and instances
//!
//! The mesh is one flat list of nodes and elements. Labels of different instances collide, so
//! when a file has instances the ids are renumbered by a fixed rule:
//!
//! - model- and assembly-level nodes and elements keep their labels; they come first in the
//!   mesh;
//! - the k-th `*INSTANCE` of the file (k = 1, 2, ...) contributes its part's nodes and
//!   elements with id `k * 10^10 + label` ([`INSTANCE_STRIDE`]), placed by its translation
//!   and rotation, after the previous instance's;
//! - labels inside parts, instances and the assembly must be below 10^10 (an error
//!   otherwise), so `id / 10^10` is the instance number and `id % 10^10` the label;
//! - a part's sets become `instance.set` (for example `Disc-1.Friction`); assembly-level sets
//!   (members given with `INSTANCE=` or as `instance.label` / `instance.set`) keep their
//!   name; a part's `*SOLID SECTION` applies to `instance.elset` of each instance;
//! - a part that is never instanced is not in the mesh (a warning says so).
//!
//! Files without `*INSTANCE` keep the file's labels unchanged.
//!
//! # Truncated files
//!
//! A file cut off mid-line (an interrupted copy, a full disk) would otherwise read: a node
//! line cut after its y takes z = 0, a node id or set member cut from `10` becomes `1`, a
//! keyword line cut inside a set name names another set. Every tool that writes `.inp` ends
//! its last line with a line break, so a file (or included file) whose last line has content
//! other than a `**` comment and no line break is an error at that line, before anything is
//! read. A file cut exactly at a line end cannot be told from a shorter complete file; if the
//! cut falls before the first C3D10 element, [`read`] fails (a mesh file without tet10, see
//! [`crate`]); if it falls later, the elements after it are missing and usually so are their
//! materials and sections, which the finite-element stage reports as elements without a
//! material, or nodes the elements name are missing ([`crate::Mesh::dangling`], an error of
//! [`crate::quality`]).
//!
//! # Errors
//!
//! Every error is [`MeshError::Invalid`] with the file (the included file, if it is there)
//! and [`Location::Line`], saying what was expected and what was found: truncated records,
//! bad numbers, wrong node counts, unsupported parameter values that matter, duplicate
//! labels, undefined sets and parts, missing includes, include loops, invalid UTF-8 or
//! control characters (binary files).

mod fields;
pub(crate) mod lex;
mod reader;
mod store;
mod transform;

use crate::{Location, MeshError, ReadMesh};
use std::path::Path;

/// Instance k's labels become `k * INSTANCE_STRIDE + label` (see the module documentation).
pub const INSTANCE_STRIDE: u64 = 10_000_000_000;

/// Supplies the files named by `*INCLUDE, INPUT=` (and `INPUT=` on data keywords).
pub trait IncludeResolver {
    /// The bytes of the file at `path` (already joined to the including file's folder).
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>>;
}

/// Reads included files from the file system.
#[derive(Clone, Copy, Debug, Default)]
pub struct FileSystem;

impl IncludeResolver for FileSystem {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        crate::file::read_limited(path)
    }
}

/// Resolves no include: every `*INCLUDE` is a "not found" error (for in-memory parsing).
#[derive(Clone, Copy, Debug, Default)]
pub struct NoIncludes;

impl IncludeResolver for NoIncludes {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        Err(std::io::Error::new(
            std::io::ErrorKind::NotFound,
            format!("{} is not available", path.display()),
        ))
    }
}

/// Reads an Abaqus / CalculiX `.inp` file and the files it includes: a mesh file, so a file
/// without C3D10 elements is an error (see [`crate`]).
pub fn read(path: &Path) -> Result<ReadMesh, MeshError> {
    let bytes = crate::file::read_bytes(path)?;
    crate::require_tet10(parse(&bytes, path, &FileSystem)?)
}

/// Parses `.inp` text held in memory. `path` names the text in messages and is the folder
/// includes are relative to; `resolver` supplies included files. A text without C3D10
/// elements gives its mesh with a warning.
pub fn parse(
    text: &[u8],
    path: &Path,
    resolver: &dyn IncludeResolver,
) -> Result<ReadMesh, MeshError> {
    let lexed = lex::lex(text, path, resolver)?;
    if lexed.items.is_empty() {
        return Err(MeshError::invalid(
            path,
            Location::File,
            "expected .inp keywords, found no keyword or data line",
        ));
    }
    reader::Reader::new(&lexed).run()
}
