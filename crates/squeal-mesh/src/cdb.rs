//! Ansys `.cdb` reader: the blocked format CDWRITE writes (Mechanical APDL and Workbench's
//! input files).
//!
//! Reference: Ansys Mechanical APDL Command Reference, NBLOCK, EBLOCK, CMBLOCK, MPDATA, ET;
//! Ansys Element Reference, SOLID186 and SOLID187 (node letters and degenerate forms).
//!
//! # What is read
//!
//! Commands are comma-separated, any case; `!` starts a comment.
//!
//! - `ET, ITYPE, ENAME`: the element type table (`ENAME` as `186` or `SOLID186`).
//! - `NBLOCK`, its Fortran format line (`(3i9,6e21.13e3)` or any other of integer fields
//!   then real fields) and node lines: node number, X, Y, Z (global Cartesian, as CDWRITE
//!   writes them; trailing zero coordinates left out are zero), up to `N,R5.3,LOC,-1` or a
//!   `-1` line. Nodal rotation angles are ignored with one warning (they orient the degrees of
//!   freedom, and squeal reads no loads or constraints from the file).
//! - `EBLOCK, 19, SOLID` with its format (`(19i9)`): per element, 11 attributes (material,
//!   type, real constant, section, system, birth/death, solid model, shape, node count,
//!   unused, element number) and its nodes, continued on the next line; `-1` ends the block.
//!   SOLID186 (and the older SOLID95) in its brick form is a hex20 in squeal's order; its
//!   degenerate forms (prism: K = L = S, O = P = W, A = B; pyramid: M = N = O = P = U = V = W
//!   = X; tetrahedron: both) become wedge15, pyramid13 and tet10, their nodes picked by the
//!   `PRISM`, `PYRAMID` and `TETRAHEDRON` tables of this module's reader. SOLID187 (and
//!   SOLID92) is a tet10 in squeal's order. Other element types (SOLID185, SURF154,
//!   CONTA174, TARGE170, ...) are skipped with one warning per type; an `EBLOCK` in the
//!   non-solid layout is skipped with one warning. Elements of material `n` form the
//!   element set `MAT_n`, with a section linking it to material `MAT_n`.
//! - `CMBLOCK, NAME, NODE|ELEM, COUNT` with its format (`(8i10)`): a node or element set of
//!   that name; a negative entry `-b` after `a` is the range `a` to `b`.
//! - `MPDATA` (CDWRITE's `MPDATA,R5.0,LENGTH,LAB,MAT,STLOC,C1,...` and the command form
//!   `MPDATA,LAB,MAT,STLOC,C1,...`) and `MP,LAB,MAT,C0`: `EX`, `NUXY` or `PRXY` (equal for an
//!   isotropic material; 0.3, Ansys's default, with a warning if neither), `DENS`, and `GXY`
//!   if consistent with them to 1 %; the first temperature's values (a warning says when
//!   there are more). `EY` or `EZ` other than `EX` (an orthotropic material) is refused:
//!   give the material in the scene's `[materials]`.
//! - Session and setup commands (`/PREP7`, `*SET`, `KEYOPT`, ...) are skipped silently; other
//!   commands with one warning each.
//!
//! SOLID186's default (`KEYOPT(2) = 0`) is uniform reduced integration; squeal integrates
//! every hex20 with the full 3×3×3 rule (see `squeal_element::hex20`).
//!
//! # Errors
//!
//! [`MeshError::Invalid`] with the file and the line, saying what was expected and what to
//! do: bad format lines, fields that are not numbers, lines longer than their format, blocks
//! the file ends inside, wrong node counts, elements of an undefined type, SOLID186 records
//! with repeated nodes in none of Ansys's patterns, duplicate numbers, refused materials, a
//! file without `NBLOCK` or `EBLOCK`. A file without quadratic solid elements is an error of
//! [`read`] and a warning of [`parse`] (see [`crate`]).

mod format;
mod reader;

use crate::{MeshError, ReadMesh};
use std::path::Path;

/// Reads a `.cdb` file: a mesh file, so a file without quadratic solid elements is an error
/// (see [`crate`]).
pub fn read(path: &Path) -> Result<ReadMesh, MeshError> {
    let bytes = crate::file::read_bytes(path)?;
    crate::require_tet10(parse(&bytes, path)?)
}

/// Parses `.cdb` text held in memory; `path` names it in messages. A text without quadratic
/// solid elements gives its mesh with a warning.
pub fn parse(bytes: &[u8], path: &Path) -> Result<ReadMesh, MeshError> {
    let text = crate::inp::lex::decode(bytes, path)?;
    // CDWRITE ends every line: a last line with content and no line break was cut off, and a
    // cut-off number cannot be told from a complete one.
    if let Some(last) = text
        .rfind('\n')
        .map_or(Some(&text[..]), |i| Some(&text[i + 1..]))
        && !last.trim().is_empty()
    {
        let line = text.bytes().filter(|&b| b == b'\n').count() + 1;
        return Err(MeshError::invalid(
            path,
            crate::Location::Line(line),
            "the file ends inside this line (no line break after it): it looks cut off. If the file is complete, end its last line with a line break",
        ));
    }
    reader::Reader::new(&text, path).run()
}
