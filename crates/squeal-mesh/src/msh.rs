//! Gmsh `.msh` reader: MSH 2.2 and 4.1, ASCII and binary (either byte order).
//!
//! Reference: Gmsh reference manual, section "MSH file format" (version 4.1, with the MSH 2
//! description in its legacy formats appendix).
//!
//! # Why not `mshio`
//! The reader is written here on nom's number parsers rather than on the `mshio` crate: `mshio`
//! reads MSH 4.1 only (the AMfe test meshes and many users' files are 2.2), ignores
//! `$PhysicalNames` (which is where the set names come from), does not say on which line or byte
//! a file went wrong, and is no longer maintained. The format itself is small: `$Section` ...
//! `$EndSection` blocks whose contents are counted. A cursor over the bytes (module `cursor`)
//! that reads lines, whitespace-separated fields (nom's `u64`, `i32` and `double` text parsers)
//! and binary integers and doubles (nom's `i32`, `u64`, `f64` in the file's byte order) covers
//! it.
//!
//! # What becomes what
//! - Nodes: every node of `$Nodes` (MSH 4.1: all entity blocks; parametric coordinates are
//!   read and dropped).
//! - Elements: the quadratic solids, types 11 (10-node tetrahedron), 17 (20-node hexahedron),
//!   18 (15-node prism) and 19 (13-node pyramid), each permuted into its canonical ordering
//!   with its `GMSH_TO_CANONICAL` ([`squeal_element::ReferenceElement`]). Elements of lower
//!   dimension (points 15, lines 1 and 8, triangles 2 and 9, quadrangles, ...) only feed node
//!   sets. Other 3D types (4-node tetrahedra, 8-node hexahedra, 27-node hexahedra, ...) are
//!   skipped, with one warning per type.
//! - Sets, from physical groups: a group of dimension 3 becomes an element set (its tet10); a
//!   group of dimension 0, 1 or 2 becomes a node set holding every node of the group's
//!   *elements* (in MSH 4.1 this includes the nodes on the entity's boundary, which the entity's
//!   own node block does not hold). An element belongs to a group through its physical tag (MSH
//!   2.2: the first element tag, 0 meaning none) or through its entity's physical tags (MSH 4.1,
//!   `$Entities`). Groups without a `$PhysicalNames` entry are named `PHYSICAL_<dim>_<tag>`
//!   (e.g. `PHYSICAL_2_5`). Groups that share a name feed one set: node sets are shared by
//!   dimensions 0 to 2, so a curve and a surface both named `fixed` give one node set `fixed`
//!   (with a warning); a volume and a surface both named `pad` give an element set `pad` and a
//!   node set `pad`, which do not clash.
//! - MSH 2 writes an element once per physical group it belongs to, each time under a new
//!   number. A solid record whose nodes repeat an earlier one's is therefore the same element:
//!   it joins the new group under its first number instead of being added twice (one warning
//!   counts them).
//! - Other sections (`$NodeData`, `$ElementData`, `$Periodic`, `$Parametrizations`,
//!   `$PartitionedEntities`, `$Comments`, ...) are skipped with one warning each.
//!
//! # Errors
//! [`MeshError::Invalid`] with [`Location::Line`] in ASCII files and [`Location::Byte`] in
//! binary ones, and what was expected there: truncated files (including a file that ends
//! before its `$Nodes` or `$Elements` section), missing `$End...` lines, bad numbers, element
//! lines with the wrong number of nodes for their type, unknown element types, declared counts
//! larger than the rest of the file can hold (nothing is allocated from a count before that
//! check), and MSH versions other than 2.x and 4.1. Every section is counted or closed, so a
//! file cut anywhere before its final line break is an error (the test
//! `truncations_never_panic` cuts eight files at ~400 places each). A file without 10-node
//! tetrahedra is an error of [`read`] and a warning of [`parse`] (see [`crate`]). Node tags
//! that elements or sets reference but `$Nodes` never defines are not errors here: the
//! [`MeshBuilder`] lists them in [`crate::Mesh::dangling`].

mod cursor;
pub mod types;
mod v2;
mod v4;

use crate::tet10::GMSH_TO_CANONICAL;
use crate::{Location, MeshBuilder, MeshError, ReadMesh, Warning};
use cursor::{Cursor, Line, quote};
use squeal_element::ElementKind;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;
use types::{ElementType, TET10};

/// Reads a Gmsh `.msh` file (MSH 2.2 or 4.1, ASCII or binary): a mesh file, so a file without
/// 10-node tetrahedra is an error (see [`crate`]).
pub fn read(path: &Path) -> Result<ReadMesh, MeshError> {
    let bytes = crate::file::read_bytes(path)?;
    crate::require_tet10(parse(&bytes, path)?)
}

/// Parses the bytes of a `.msh` file; `path` only names the file in errors and warnings. A file
/// without 10-node tetrahedra gives its mesh with a warning.
pub fn parse(bytes: &[u8], path: &Path) -> Result<ReadMesh, MeshError> {
    let mut cursor = Cursor::new(bytes, path);
    let version = read_format(&mut cursor)?;
    let mut reader = Reader::new(cursor, version);
    while let Some(line) = reader.cur.next_nonblank() {
        reader.section(line)?;
    }
    for (seen, name) in [
        (reader.seen_nodes, "$Nodes"),
        (reader.seen_elements, "$Elements"),
    ] {
        if !seen {
            return Err(reader.cur.error(
                reader.cur.here(),
                format!("unexpected end of file: no {name} section"),
            ));
        }
    }
    Ok(reader.finish())
}

/// The MSH versions this reader reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Version {
    /// 2.0, 2.1 and 2.2 (the same layout; 2.2 is what Gmsh writes).
    V2,
    /// 4.1.
    V4,
}

/// Reads `$MeshFormat`: the version, ASCII or binary, and for binary files the byte order.
fn read_format(cur: &mut Cursor<'_>) -> Result<Version, MeshError> {
    let first = cur
        .next_nonblank()
        .ok_or_else(|| cur.error(Location::File, "empty file: expected $MeshFormat"))?;
    if first.trimmed() != b"$MeshFormat" {
        let message = if first.trimmed().starts_with(b"$NOD") {
            "MSH version 1 file ($NOD): not supported; in Gmsh, set Mesh.MshFileVersion = 4.1 and save again"
                .to_string()
        } else {
            format!(
                "not a Gmsh .msh file: expected $MeshFormat, found `{}`",
                quote(first.trimmed())
            )
        };
        return Err(cur.error(cur.at(&first), message));
    }
    let mut f = cur.expect_fields("the format line (version file-type data-size)")?;
    let token = f.token("the MSH version")?;
    let version = match token {
        b"4.1" => Version::V4,
        b"2" | b"2.0" | b"2.1" | b"2.2" => Version::V2,
        _ => {
            return Err(f.error(format!(
                "unsupported MSH version {}: this reader reads versions 2.2 and 4.1 \
                 (in Gmsh, set Mesh.MshFileVersion = 4.1 and save again)",
                quote(token)
            )));
        }
    };
    let file_type = f.u64("the file type (0 ASCII, 1 binary)")?;
    let data_size = f.u64("the data size")?;
    f.end("the format line")?;
    match file_type {
        0 => {}
        1 => {
            if data_size != 8 {
                return Err(f.error(format!(
                    "binary data size {data_size} is not supported (expected 8: 8-byte doubles and size_t)"
                )));
            }
            cur.binary = true;
            cur.byte_order_mark()?;
        }
        _ => {
            return Err(f.error(format!(
                "expected the file type 0 (ASCII) or 1 (binary), found {file_type}"
            )));
        }
    }
    cur.expect_end("MeshFormat")?;
    Ok(version)
}

/// Whose elements a member list holds: `(dimension, tag)` of a physical group in MSH 2, of an
/// entity in MSH 4.1.
type Owner = (i32, i32);

/// What the elements of one owner contribute to sets.
#[derive(Debug, Default)]
struct Members {
    /// Tet10 element ids.
    elements: Vec<u64>,
    /// Node ids of lower-dimensional elements.
    nodes: Vec<u64>,
}

/// Elements of a skipped type: how many, and where the first was.
#[derive(Clone, Copy, Debug)]
struct Skipped {
    count: u64,
    first: Location,
}

/// The state of one parse.
struct Reader<'a> {
    cur: Cursor<'a>,
    version: Version,
    builder: MeshBuilder,
    warnings: Vec<Warning>,
    /// `$PhysicalNames`: `(dim, tag)` to name.
    names: BTreeMap<(i32, i32), String>,
    /// MSH 4.1 `$Entities`: `(dim, tag)` of an entity to its physical tags.
    entity_groups: BTreeMap<(i32, i32), Vec<i32>>,
    members: BTreeMap<Owner, Members>,
    skipped: BTreeMap<i32, Skipped>,
    /// MSH 2: canonical connectivity of each tet10 read, to its id (see the module doc).
    tets_seen: HashMap<[u64; 10], u64>,
    /// MSH 2: the same for the other solid kinds.
    others_seen: HashMap<Vec<u64>, u64>,
    repeated_tets: Option<Skipped>,
    seen_nodes: bool,
    seen_elements: bool,
}

impl<'a> Reader<'a> {
    fn new(cur: Cursor<'a>, version: Version) -> Self {
        Reader {
            cur,
            version,
            builder: MeshBuilder::new(),
            warnings: Vec::new(),
            names: BTreeMap::new(),
            entity_groups: BTreeMap::new(),
            members: BTreeMap::new(),
            skipped: BTreeMap::new(),
            tets_seen: HashMap::new(),
            others_seen: HashMap::new(),
            repeated_tets: None,
            seen_nodes: false,
            seen_elements: false,
        }
    }

    fn warn(&mut self, location: Location, message: impl Into<String>) {
        self.warnings.push(Warning {
            file: self.cur.file().to_path_buf(),
            location,
            message: message.into(),
        });
    }

    /// Reads the section that `header` opens.
    fn section(&mut self, header: Line<'a>) -> Result<(), MeshError> {
        let at = self.cur.at(&header);
        let Some(name) = header.trimmed().strip_prefix(b"$") else {
            return Err(self.cur.error(
                at,
                format!(
                    "expected a section header such as $Nodes, found `{}`",
                    quote(header.trimmed())
                ),
            ));
        };
        if name.starts_with(b"End") {
            return Err(self.cur.error(
                at,
                format!("`${}` closes a section that was never opened", quote(name)),
            ));
        }
        self.seen_nodes |= name == b"Nodes";
        self.seen_elements |= name == b"Elements";
        match (name, self.version) {
            (b"PhysicalNames", _) => self.read_physical_names(),
            (b"Entities", Version::V4) => v4::read_entities(self),
            (b"Nodes", Version::V2) => v2::read_nodes(self),
            (b"Nodes", Version::V4) => v4::read_nodes(self),
            (b"Elements", Version::V2) => v2::read_elements(self),
            (b"Elements", Version::V4) => v4::read_elements(self),
            _ => self.skip_section(name, at),
        }
    }

    /// Skips an unknown section up to its `$End` line, with a warning.
    fn skip_section(&mut self, name: &[u8], at: Location) -> Result<(), MeshError> {
        let end = [b"$End", name].concat();
        loop {
            match self.cur.next_line() {
                Some(line) if line.trimmed() == end.as_slice() => break,
                Some(_) => {}
                None => {
                    return Err(self.cur.error(
                        at,
                        format!(
                            "section ${} is never closed: missing ${}",
                            quote(name),
                            quote(&end[1..])
                        ),
                    ));
                }
            }
        }
        let hint = if name == b"PartitionedEntities" {
            " (physical groups of partition entities are lost: save the mesh unpartitioned)"
        } else {
            ""
        };
        self.warn(
            at,
            format!(
                "skipped section ${}: squeal reads $MeshFormat, $PhysicalNames, $Entities, $Nodes and $Elements{hint}",
                quote(name)
            ),
        );
        Ok(())
    }

    /// `$PhysicalNames`: lines `dim tag "name"` (ASCII in binary files too).
    fn read_physical_names(&mut self) -> Result<(), MeshError> {
        let mut f = self.cur.expect_fields("the number of physical names")?;
        let n = f.u64("the number of physical names")?;
        f.end("the number of physical names")?;
        // The shortest entry, `0 1 ""`, takes 7 bytes with its newline.
        let n = self.cur.check_count(n, 7, "physical names", f.location)?;
        for _ in 0..n {
            let mut f = self
                .cur
                .expect_fields("a physical name (dim tag \"name\")")?;
            let dim = f.i32("the dimension of a physical group")?;
            let tag = f.i32("the tag of a physical group")?;
            let quoted = f.rest();
            let name = match quoted {
                [b'"', inner @ .., b'"'] => String::from_utf8_lossy(inner).into_owned(),
                _ => {
                    return Err(f.error(format!(
                        "expected a name in double quotes, found `{}`",
                        quote(quoted)
                    )));
                }
            };
            if !name.is_empty() {
                self.names.insert((dim, tag), name);
            }
        }
        self.cur.expect_end("PhysicalNames")
    }

    /// One element record, whatever the version: a tet10 becomes an element, another 3D type is
    /// skipped, a lower-dimensional one feeds the node sets of `owner`'s groups.
    fn element(
        &mut self,
        id: u64,
        kind: &ElementType,
        owner: Option<Owner>,
        nodes: &[u64],
        at: Location,
    ) -> Result<(), MeshError> {
        if kind.code == TET10 {
            return self.tet10(id, owner, nodes, at);
        }
        if let Some(solid) = ElementKind::from_gmsh_type(kind.code) {
            return self.solid(id, solid, owner, nodes, at);
        }
        if self.builder.has_element(id) {
            return Err(self.cur.error(at, format!("element {id} is defined twice")));
        }
        self.builder.skip_element(id);
        if kind.dim == 3 {
            let entry = self.skipped.entry(kind.code).or_insert(Skipped {
                count: 0,
                first: at,
            });
            entry.count += 1;
        } else if let Some(owner) = owner {
            self.members
                .entry(owner)
                .or_default()
                .nodes
                .extend_from_slice(nodes);
        }
        Ok(())
    }

    fn tet10(
        &mut self,
        id: u64,
        owner: Option<Owner>,
        nodes: &[u64],
        at: Location,
    ) -> Result<(), MeshError> {
        let canonical: [u64; 10] = std::array::from_fn(|i| nodes[GMSH_TO_CANONICAL[i]]);
        let first = (self.version == Version::V2)
            .then(|| self.tets_seen.get(&canonical).copied())
            .flatten();
        self.settle(id, first, owner, at, |r| {
            r.builder.add_element(id, canonical)?;
            if r.version == Version::V2 {
                r.tets_seen.insert(canonical, id);
            }
            Ok(())
        })?;
        Ok(())
    }

    /// A hex20, wedge15 or pyramid13 record: as [`Reader::tet10`], through the builder's
    /// typed elements.
    fn solid(
        &mut self,
        id: u64,
        kind: ElementKind,
        owner: Option<Owner>,
        nodes: &[u64],
        at: Location,
    ) -> Result<(), MeshError> {
        let canonical: Vec<u64> = kind.gmsh_to_canonical().iter().map(|&i| nodes[i]).collect();
        let first = (self.version == Version::V2)
            .then(|| self.others_seen.get(&canonical).copied())
            .flatten();
        self.settle(id, first, owner, at, |r| {
            r.builder.add_typed(id, kind, &canonical)?;
            if r.version == Version::V2 {
                r.others_seen.insert(canonical, id);
            }
            Ok(())
        })?;
        Ok(())
    }

    /// A solid record read under number `id`: a repeat of element `first` (MSH 2, counted
    /// once in a warning) joins the owner's groups under that number, a new one is added by
    /// `add`. Returns the number the element goes by.
    fn settle(
        &mut self,
        id: u64,
        first: Option<u64>,
        owner: Option<Owner>,
        at: Location,
        add: impl FnOnce(&mut Self) -> Result<(), String>,
    ) -> Result<u64, MeshError> {
        let id = match first {
            Some(first) => {
                self.repeated_tets
                    .get_or_insert(Skipped {
                        count: 0,
                        first: at,
                    })
                    .count += 1;
                first
            }
            None => {
                add(self).map_err(|m| self.cur.error(at, m))?;
                id
            }
        };
        if let Some(owner) = owner {
            self.members.entry(owner).or_default().elements.push(id);
        }
        Ok(id)
    }

    /// The physical tags of an owner's elements.
    fn groups_of<'s>(&'s self, owner: &'s Owner) -> &'s [i32] {
        match self.version {
            Version::V2 => std::slice::from_ref(&owner.1),
            Version::V4 => self.entity_groups.get(owner).map_or(&[], Vec::as_slice),
        }
    }

    /// Gathers the members of each physical group `(dim, tag)`, including declared groups
    /// without elements.
    fn gather_groups(&mut self) -> BTreeMap<(i32, i32), Members> {
        let mut groups: BTreeMap<(i32, i32), Members> = BTreeMap::new();
        for &key in self.names.keys() {
            groups.entry(key).or_default();
        }
        for (&(dim, _), tags) in &self.entity_groups {
            for &tag in tags {
                groups.entry((dim, tag)).or_default();
            }
        }
        // A node is shared by several elements of an owner: list it once before copying it
        // into each of the owner's groups.
        for members in self.members.values_mut() {
            members.nodes.sort_unstable();
            members.nodes.dedup();
        }
        let mut orphans = Vec::new();
        for (owner, members) in &self.members {
            if self.version == Version::V4 && !self.entity_groups.contains_key(owner) {
                orphans.push(*owner);
            }
            for &tag in self.groups_of(owner) {
                let group = groups.entry((owner.0, tag)).or_default();
                group.elements.extend_from_slice(&members.elements);
                group.nodes.extend_from_slice(&members.nodes);
            }
        }
        if let Some(&(dim, tag)) = orphans.first() {
            self.warn(
                Location::File,
                format!(
                    "entities missing from $Entities hold elements ({}, first: dimension {dim}, \
                     tag {tag}): their elements belong to no physical group",
                    orphans.len()
                ),
            );
        }
        groups
    }

    /// Turns physical groups into named sets (see the module doc).
    fn build_sets(&mut self) {
        let groups = self.gather_groups();
        // Name -> groups feeding it, per kind of set (false: node set, true: element set).
        let mut feeders: BTreeMap<(bool, String), Vec<(i32, i32)>> = BTreeMap::new();
        for ((dim, tag), members) in groups {
            let name = self
                .names
                .get(&(dim, tag))
                .cloned()
                .unwrap_or_else(|| format!("PHYSICAL_{dim}_{tag}"));
            match dim {
                3 => self.builder.add_to_element_set(&name, members.elements),
                0..=2 => self.builder.add_to_node_set(&name, members.nodes),
                _ => {
                    self.warn(
                        Location::File,
                        format!("physical group \"{name}\" has dimension {dim}: ignored"),
                    );
                    continue;
                }
            }
            feeders
                .entry((dim == 3, name))
                .or_default()
                .push((dim, tag));
        }
        for ((is_element_set, name), keys) in feeders {
            if keys.len() > 1 {
                let list: Vec<String> = keys
                    .iter()
                    .map(|(d, t)| format!("(dimension {d}, tag {t})"))
                    .collect();
                let kind = if is_element_set {
                    "element set"
                } else {
                    "node set"
                };
                self.warn(
                    Location::File,
                    format!(
                        "physical groups {} share the name \"{name}\": they form one {kind}",
                        list.join(", ")
                    ),
                );
            }
        }
    }

    /// Warnings that summarize the whole file, then the mesh.
    fn finish(mut self) -> ReadMesh {
        self.build_sets();
        let skipped = std::mem::take(&mut self.skipped);
        for (code, s) in skipped {
            let name = types::element_type(code).map_or("?", |t| t.name);
            let hint = if code == 4 {
                "; mesh with Mesh.ElementOrder = 2 (gmsh -order 2) to get type 11"
            } else {
                ""
            };
            self.warn(
                s.first,
                format!(
                    "skipped {} elements of type {code} ({name}): squeal reads only quadratic solids (types 11, 17, 18, 19){hint}",
                    s.count
                ),
            );
        }
        if let Some(r) = self.repeated_tets {
            self.warn(
                r.first,
                format!(
                    "{} solid element records repeat the nodes of an earlier element (MSH 2 writes an element once per \
                     physical group): each was read once, under the number of its first record",
                    r.count
                ),
            );
        }
        if self.builder.num_elements() == 0 {
            self.warn(Location::File, crate::NO_TET10);
        }
        ReadMesh {
            mesh: self.builder.finish(),
            warnings: self.warnings,
        }
    }
}
