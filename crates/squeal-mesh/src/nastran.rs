//! Nastran bulk data reader (`.bdf`, `.nas`, `.dat`).
//!
//! Reference: MSC Nastran Quick Reference Guide, "Bulk Data Entries" (the card layouts and
//! the field formats); NX/Simcenter Nastran and OptiStruct share them.
//!
//! # Format
//!
//! - The bulk data of the file is what follows `BEGIN BULK` (the executive and case control
//!   sections before it are skipped); a file without `BEGIN BULK` (an included file, a bulk
//!   data export) is bulk data throughout. `ENDDATA` ends it: nothing after is read.
//! - Each line is in free field (it has a comma: `GRID,1,,0.,0.,0.`), small field (ten 8
//!   character fields, the tenth a continuation mark) or large field (the card name ending
//!   with `*`, then four 16 character fields; its continuation starts with `*`); tabs jump to
//!   the next multiple of 8 columns; text after a `$` is a comment. A free-field line whose
//!   name ends with `*` holds four data fields.
//! - A line whose first field is blank or starts with `+` or `*` continues the card above it
//!   (continuation marks are not matched: every writer puts a continuation right after its
//!   card; sorted, out-of-place continuations are not read).
//! - Reals may have Nastran's implied exponent (`1.-3` = 1.0E-3, `2.1+11`) or a `D`
//!   exponent; an integer in a real field is read as a real.
//! - `INCLUDE 'file'` (the name may run over several lines inside its quotes) reads the
//!   file in place, relative to the folder of the file that holds the statement; an include
//!   loop or nesting deeper than 32 is an error.
//! - Cards may come in any order (a CTETRA before its grids, a PSOLID after its elements).
//!
//! # Cards read
//!
//! - `GRID ID CP X1 X2 X3 CD PS`: `CP` may name a `CORD2R`, `CORD2C` or `CORD2S` (which may
//!   be defined in another one, through `RID`); `CORD1R/C/S` (axes through three grids) and
//!   `CORD3G`/`CORD3R` are refused with an error when a grid uses them. `CD` (the
//!   displacement system) and `PS` (permanent constraints) are ignored with one warning:
//!   squeal reads no loads or constraints from the file. `GRDSET` with a default `CP` or
//!   `CD` is refused.
//! - `CTETRA` (10 grids), `CHEXA` (20), `CPENTA` (15), `CPYRAM` (13): `EID PID G1 ...`,
//!   `PID` blank meaning `EID` (Nastran's default). The grids are mapped to squeal's node
//!   order (the `HEXA` and `PENTA` tables of this module's reader: Nastran lists the edges of
//!   the second face after the vertical ones, Abaqus and squeal before). First-order elements
//!   (4, 8, 6, 5 grids) are skipped with one warning per card type; an element with some
//!   but not all edge grids is an error (squeal has no variable-node elements). Other
//!   elements (shells, beams, springs, rigid elements, masses) are skipped with one warning
//!   per card type.
//! - `PSOLID PID MID CORDM`: the elements of property `PID` form an element set, with a
//!   section linking it to material `MID`. A `CORDM` other than 0 is refused for a `MAT9`
//!   material (squeal takes material constants in the basic axes) and has no effect on an
//!   isotropic one.
//! - `MAT1 MID E G NU RHO A TREF GE`: two of `E`, `G`, `NU` give the third (Nastran's rule;
//!   `E` alone gives `NU = 0` with a warning); all three must agree to 1 %. `GE` is ignored
//!   with a warning (the scene gives the damping).
//! - `MAT9 MID G11 ... G66 RHO`: squeal's finite elements have no general anisotropic
//!   material, so a MAT9 is read as orthotropic engineering constants when it has no
//!   shear-extension or shear-shear coupling (G14, G15, G16, G24, ..., G56 all zero), and is
//!   refused otherwise. The conversion inverts the 3×3 normal block, so the constants agree
//!   with the card's to round-off, not bit for bit.
//! - `SET1 SID ID1 ID2 ...` (with `ID1 THRU ID2`): a node set.
//! - Everything else is skipped with one warning per card name.
//!
//! # Names
//!
//! Bulk data numbers its properties, materials and sets; squeal's scenes name them. A name
//! comment gives the name, as HyperMesh and Femap write them: `$HMNAME PROP 1 "LINING"`,
//! `$HMNAME MAT 2 "STEEL"`, `$HMSET 3 1 "PISTON"` (type 2 makes the `SET1` an element set),
//! `$ Femap Property 1 : LINING`, `$ Femap Material 2 : STEEL`. Without one, the element set
//! of property 7 is `PSOLID_7`, material 2 is `MAT_2` and set 3 is `SET1_3`.
//!
//! # Errors
//!
//! [`MeshError::Invalid`] with the file (the included file, if it is there) and the line of
//! the field at fault, saying what was expected and what to do: bad numbers, missing or extra
//! grids, duplicate ids, undefined or unreadable coordinate systems, inconsistent or coupled
//! materials, missing includes and include loops, a file cut off inside its last line, binary
//! files. Grids that elements or sets name but no `GRID` defines are listed in
//! [`crate::Mesh::dangling`] (an error of [`crate::quality`]).

mod coord;
mod lex;
mod number;
mod reader;

pub(crate) use number::{int, real};

use crate::inp::{FileSystem, IncludeResolver};
use crate::{Location, MeshError, ReadMesh};
use std::path::Path;

/// Reads a bulk data file and the files it includes: a mesh file, so a file without
/// quadratic solid elements is an error (see [`crate`]).
pub fn read(path: &Path) -> Result<ReadMesh, MeshError> {
    let bytes = crate::file::read_bytes(path)?;
    crate::require_tet10(parse(&bytes, path, &FileSystem)?)
}

/// Parses bulk data held in memory. `path` names the text in messages and is the folder
/// includes are relative to; `resolver` supplies included files. A text without quadratic
/// solid elements gives its mesh with a warning.
pub fn parse(
    text: &[u8],
    path: &Path,
    resolver: &dyn IncludeResolver,
) -> Result<ReadMesh, MeshError> {
    let lexed = lex::lex(text, path, resolver)?;
    if lexed.cards.is_empty() {
        return Err(MeshError::invalid(
            path,
            Location::File,
            "expected Nastran bulk data cards (GRID, CTETRA, ...), found none (a file with BEGIN BULK has its cards after it)",
        ));
    }
    reader::Reader::new(&lexed).run()
}
