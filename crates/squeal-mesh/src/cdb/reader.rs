//! The command interpreter of a `.cdb` file: the element type table, the node, element and
//! component blocks, and the material properties, into a [`MeshBuilder`].

use super::format::Format;
use crate::nastran::{int, real};
use crate::{Elastic, Location, Material, MeshBuilder, MeshError, ReadMesh, Warning};
use squeal_element::ElementKind;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// SOLID186 (and SOLID95) in its brick form: I J K L M N O P, then Q R S T on the edges
/// I-J, J-K, K-L, L-I, U V W X on M-N, N-O, O-P, P-M, Y Z A B on I-M, J-N, K-O, L-P (Ansys
/// Element Reference, SOLID186): squeal's (Abaqus C3D20's) order.
const BRICK: [usize; 20] = [
    0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19,
];
/// The prism form, K = L = S, O = P = W, A = B: triangles I J K and M N O, edges Q (I-J),
/// R (J-K), T (K-I), U (M-N), V (N-O), X (O-M), Y (I-M), Z (J-N), A (K-O).
const PRISM: [usize; 15] = [0, 1, 2, 4, 5, 6, 8, 9, 11, 12, 13, 15, 16, 17, 18];
/// The pyramid form, M = N = O = P = U = V = W = X (the apex): base I J K L, edges Q R S T
/// on the base, Y Z A B to the apex.
const PYRAMID: [usize; 13] = [0, 1, 2, 3, 4, 8, 9, 10, 11, 16, 17, 18, 19];
/// The tetrahedron form, K = L = S, M = ... = X (the apex), A = B: I J K M, edges Q (I-J),
/// R (J-K), T (K-I), Y (I-M), Z (J-M), A (K-M).
const TETRAHEDRON: [usize; 10] = [0, 1, 2, 4, 8, 9, 11, 16, 17, 18];

/// The form of a 20-node SOLID186 record, from its repeated nodes.
fn solid186_form(n: &[u64]) -> Option<(ElementKind, &'static [usize])> {
    let same = |idx: &[usize]| idx.iter().all(|&i| n[i] == n[idx[0]]);
    let apex = same(&[4, 5, 6, 7, 12, 13, 14, 15]);
    let collapsed_k = same(&[2, 3, 10]);
    let (kind, map): (ElementKind, &'static [usize]) = if apex && collapsed_k && n[18] == n[19] {
        (ElementKind::Tet10, &TETRAHEDRON)
    } else if apex {
        (ElementKind::Pyramid13, &PYRAMID)
    } else if collapsed_k && same(&[6, 7, 14]) && n[18] == n[19] {
        (ElementKind::Wedge15, &PRISM)
    } else {
        (ElementKind::Hex20, &BRICK)
    };
    // The chosen nodes must be distinct, and every node of the record one of them.
    let chosen: Vec<u64> = map.iter().map(|&i| n[i]).collect();
    let mut sorted = chosen.clone();
    sorted.sort_unstable();
    sorted.dedup();
    (sorted.len() == chosen.len() && n.iter().all(|v| sorted.binary_search(v).is_ok()))
        .then_some((kind, map))
}

/// What squeal does with an element type number (ET table).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Type {
    /// SOLID186, SOLID95: 20 nodes, with the degenerate forms.
    Solid186,
    /// SOLID187, SOLID92: 10-node tetrahedron, squeal's order.
    Solid187,
    /// Any other element: skipped.
    Other(u32),
}

fn element_type(name: &str) -> Option<Type> {
    let upper = name.trim().to_ascii_uppercase();
    let number: u32 = upper
        .strip_prefix("SOLID")
        .unwrap_or(&upper)
        .parse()
        .ok()
        .or_else(|| {
            upper
                .trim_start_matches(|c: char| c.is_ascii_alphabetic())
                .parse()
                .ok()
        })?;
    Some(match number {
        186 | 95 => Type::Solid186,
        187 | 92 => Type::Solid187,
        n => Type::Other(n),
    })
}

/// Material properties as the file gives them (first temperature).
#[derive(Default)]
struct Props {
    values: BTreeMap<String, f64>,
    line: usize,
}

pub(super) struct Reader<'a> {
    path: &'a Path,
    lines: Vec<&'a str>,
    pos: usize,
    types: HashMap<u64, Type>,
    props: BTreeMap<u64, Props>,
    b: MeshBuilder,
    by_material: BTreeMap<u64, Vec<u64>>,
    warnings: Vec<Warning>,
    once: BTreeMap<String, (usize, usize, String)>,
    blocks: usize,
}

/// Commands that set up the session or the solution, skipped without a warning.
fn quiet(cmd: &str) -> bool {
    cmd.starts_with(['/', '*', '!'])
        || matches!(
            cmd,
            "KEYOPT"
                | "FINISH"
                | "NUMOFF"
                | "TYPE"
                | "MAT"
                | "REAL"
                | "SECNUM"
                | "ESYS"
                | "CSYS"
                | "MPTEMP"
                | "EXTOPT"
                | "N"
                | "EN"
                | "E"
                | "ANTYPE"
        )
}

impl<'a> Reader<'a> {
    pub fn new(text: &'a str, path: &'a Path) -> Self {
        // The piece after the last line break is no line.
        let body = text.strip_suffix('\n').unwrap_or(text);
        Self {
            path,
            lines: body.split('\n').map(|l| l.trim_end_matches('\r')).collect(),
            pos: 0,
            types: HashMap::new(),
            props: BTreeMap::new(),
            b: MeshBuilder::new(),
            by_material: BTreeMap::new(),
            warnings: Vec::new(),
            once: BTreeMap::new(),
            blocks: 0,
        }
    }

    fn err(&self, line: usize, message: impl Into<String>) -> MeshError {
        MeshError::invalid(self.path, Location::Line(line), message)
    }

    fn note(&mut self, key: &str, line: usize, stem: impl FnOnce() -> String) {
        self.once
            .entry(key.to_string())
            .and_modify(|e| e.1 += 1)
            .or_insert_with(|| (line, 1, stem()));
    }

    /// The next line and its 1-based number.
    fn next_line(&mut self) -> Option<(usize, &'a str)> {
        let l = *self.lines.get(self.pos)?;
        self.pos += 1;
        Some((self.pos, l))
    }

    pub fn run(mut self) -> Result<ReadMesh, MeshError> {
        while let Some((line, text)) = self.next_line() {
            let t = text.trim();
            if t.is_empty() || t.starts_with('!') {
                continue;
            }
            let args: Vec<&str> = t
                .split('!')
                .next()
                .unwrap_or("")
                .split(',')
                .map(str::trim)
                .collect();
            let cmd = args[0].to_ascii_uppercase();
            match cmd.as_str() {
                "ET" => self.et(&args, line)?,
                "NBLOCK" => self.nblock(line)?,
                "EBLOCK" => self.eblock(&args, line)?,
                "CMBLOCK" => self.cmblock(&args, line)?,
                "MPDATA" | "MP" => self.mpdata(&cmd, &args, line)?,
                c if quiet(c) => {}
                _ => {
                    let c = cmd.clone();
                    self.note(&format!("cmd {c}"), line, || format!("skipped the command {c}: squeal reads ET, NBLOCK, EBLOCK, CMBLOCK, MPDATA and MP"));
                }
            }
        }
        if self.blocks == 0 {
            return Err(self.err(1, "expected an Ansys .cdb file (as CDWRITE writes it) with NBLOCK and EBLOCK, found neither"));
        }
        self.finish()
    }

    /// `ET, ITYPE, ENAME` (ENAME a number such as 186 or a name such as SOLID186).
    fn et(&mut self, args: &[&str], line: usize) -> Result<(), MeshError> {
        let id = args.get(1).and_then(|s| int(s)).filter(|&v| v > 0);
        let ty = args.get(2).and_then(|s| element_type(s));
        match (id, ty) {
            (Some(id), Some(ty)) => {
                self.types.insert(id as u64, ty);
                Ok(())
            }
            _ => Err(self.err(line, format!("expected 'ET, type number, element name or number' (such as ET,1,186), found '{}'", shown(&args.join(","))))),
        }
    }

    /// The format line after a block command.
    fn format(&mut self, what: &str, line: usize) -> Result<(usize, Format), MeshError> {
        let (l, text) = self.next_line().ok_or_else(|| {
            self.err(
                line,
                format!("the file ends after {what}, before its format line"),
            )
        })?;
        Format::parse(text)
            .map(|f| (l, f))
            .map_err(|m| self.err(l, m))
    }

    /// `NBLOCK`: `(3i9,6e21.13e3)` lines of node number, two integers, X, Y, Z and three
    /// rotation angles (trailing zeros may be left out), up to `N,R5.3,LOC,-1` or `-1`.
    fn nblock(&mut self, line: usize) -> Result<(), MeshError> {
        self.blocks += 1;
        let (fl, f) = self.format("NBLOCK", line)?;
        let ints = f.ints();
        if ints == 0 || f.fields.len() < ints + 3 {
            return Err(self.err(fl, "an NBLOCK format needs an integer field (the node number) and three real fields (X, Y, Z)"));
        }
        loop {
            let (l, text) = self.next_line().ok_or_else(|| {
                self.err(
                    line,
                    "the file ends inside this NBLOCK (no N,R5.3,LOC,-1 or -1 line ends it)",
                )
            })?;
            if text.trim_start().to_ascii_uppercase().starts_with("N,") {
                return Ok(());
            }
            let v = f.split(text).map_err(|m| self.err(l, m))?;
            let id = match v[0].map(int) {
                Some(Some(-1)) => return Ok(()),
                Some(Some(id)) if id > 0 => id as u64,
                _ => {
                    return Err(self.err(
                        l,
                        format!(
                            "expected a node line (node number, then coordinates), found '{}'",
                            shown(text)
                        ),
                    ));
                }
            };
            let mut x = [0.0; 6];
            for (k, slot) in x.iter_mut().enumerate() {
                let Some(Some(s)) = v.get(ints + k) else {
                    continue;
                };
                *slot = real(s).ok_or_else(|| {
                    self.err(
                        l,
                        format!("node {id}: expected a number, found '{}'", shown(s)),
                    )
                })?;
            }
            if x[3..].iter().any(|&a| a != 0.0) {
                self.note("rotated", l, || "the nodal coordinate systems (rotation angles of NBLOCK) are ignored: squeal reads no loads or constraints from the file and takes displacements in the global axes".into());
            }
            self.b
                .add_node(id, [x[0], x[1], x[2]])
                .map_err(|m| self.err(l, m))?;
        }
    }

    /// `EBLOCK, 19, SOLID`: records of 11 attributes (material, type, real, section,
    /// system, birth/death, solid model, shape, node count, unused, element number) and the
    /// nodes, over as many lines as the format's field count needs; `-1` ends it. A block
    /// in the other (surface) layout is skipped.
    fn eblock(&mut self, args: &[&str], line: usize) -> Result<(), MeshError> {
        self.blocks += 1;
        let (fl, f) = self.format("EBLOCK", line)?;
        let per_line = f.fields.len();
        if f.ints() != per_line || per_line < 11 {
            return Err(self.err(
                fl,
                "an EBLOCK format has integer fields only, at least 11 (such as (19i9))",
            ));
        }
        let solid = args.get(2).is_some_and(|s| s.eq_ignore_ascii_case("SOLID"));
        loop {
            let (l, text) = self.next_line().ok_or_else(|| {
                self.err(
                    line,
                    "the file ends inside this EBLOCK (no -1 line ends it)",
                )
            })?;
            let first = self.ints(&f, text, l)?;
            if first.first() == Some(&-1) {
                return Ok(());
            }
            if !solid {
                let n = first.len();
                self.note("surface", l, || format!("skipped an EBLOCK in the non-solid layout (surface, contact or beam elements; {n} fields a line)"));
                continue;
            }
            if first.len() < 11 {
                return Err(self.err(l, format!("an EBLOCK record starts with 11 attributes (material, type, ..., element number), found {} numbers", first.len())));
            }
            let count = usize::try_from(first[8])
                .ok()
                .filter(|&c| c <= 20)
                .ok_or_else(|| {
                    self.err(
                        l,
                        format!(
                            "element {}: expected a node count of 1 to 20 (field 9), found {}",
                            first[10], first[8]
                        ),
                    )
                })?;
            let mut nodes: Vec<i64> = first[11..].to_vec();
            while nodes.len() < count {
                let (l2, t2) = self.next_line().ok_or_else(|| {
                    self.err(
                        l,
                        format!("the file ends inside the record of element {}", first[10]),
                    )
                })?;
                nodes.extend(self.ints(&f, t2, l2)?);
            }
            if nodes.len() != count || nodes.iter().any(|&n| n <= 0) {
                return Err(self.err(l, format!("element {} has {} node numbers (not all positive); its record says {count}", first[10], nodes.len())));
            }
            self.element(&first, &nodes, l)?;
        }
    }

    /// The integers of one line of an integer block.
    fn ints(&self, f: &Format, text: &str, l: usize) -> Result<Vec<i64>, MeshError> {
        let v = f.split(text).map_err(|m| self.err(l, m))?;
        let mut out = Vec::with_capacity(v.len());
        for s in v.into_iter().flatten() {
            out.push(int(s).ok_or_else(|| {
                self.err(l, format!("expected an integer, found '{}'", shown(s)))
            })?);
        }
        Ok(out)
    }

    fn element(&mut self, attrs: &[i64], nodes: &[i64], l: usize) -> Result<(), MeshError> {
        let id = u64::try_from(attrs[10])
            .ok()
            .filter(|&v| v > 0)
            .ok_or_else(|| {
                self.err(
                    l,
                    format!(
                        "expected a positive element number (field 11), found {}",
                        attrs[10]
                    ),
                )
            })?;
        let ty = u64::try_from(attrs[1])
            .ok()
            .and_then(|t| self.types.get(&t))
            .copied()
            .ok_or_else(|| {
                self.err(
                    l,
                    format!(
                        "element {id} has type {}, which no ET command defines (before this line)",
                        attrs[1]
                    ),
                )
            })?;
        let n: Vec<u64> = nodes.iter().map(|&v| v as u64).collect();
        let (kind, canonical): (ElementKind, Vec<u64>) = match ty {
            Type::Solid187 if n.len() == 10 => (ElementKind::Tet10, n.clone()),
            Type::Solid186 if n.len() == 20 => {
                let (kind, map) = solid186_form(&n).ok_or_else(|| self.err(l, format!("SOLID186 element {id} repeats nodes in none of Ansys's patterns (brick; prism K = L = S, O = P = W, A = B; pyramid M = N = O = P = U = V = W = X; tetrahedron both)")))?;
                (kind, map.iter().map(|&i| n[i]).collect())
            }
            Type::Solid186 | Type::Solid187 => {
                return Err(self.err(l, format!("element {id} has {} nodes; SOLID186 has 20 and SOLID187 10 (squeal reads the quadratic solids with all their midside nodes)", n.len())));
            }
            Type::Other(t) => {
                self.b.skip_element(id);
                self.note(&format!("type {t}"), l, || format!("skipped elements of type {t}: squeal reads SOLID186 (with its prism, pyramid and tetrahedron forms) and SOLID187"));
                return Ok(());
            }
        };
        self.b
            .add_typed(id, kind, &canonical)
            .map_err(|m| self.err(l, m))?;
        let mat = u64::try_from(attrs[0]).unwrap_or(0);
        self.by_material.entry(mat).or_default().push(id);
        Ok(())
    }

    /// `CMBLOCK, NAME, NODE|ELEM, COUNT` and `COUNT` integers (a negative one ends a range
    /// begun by the one before it).
    fn cmblock(&mut self, args: &[&str], line: usize) -> Result<(), MeshError> {
        let name = args
            .get(1)
            .filter(|s| !s.is_empty())
            .ok_or_else(|| self.err(line, "CMBLOCK needs a component name"))?
            .to_string();
        let entity = args
            .get(2)
            .map(|s| s.to_ascii_uppercase())
            .unwrap_or_default();
        let count = args
            .get(3)
            .and_then(|s| int(s))
            .and_then(|c| usize::try_from(c).ok())
            .ok_or_else(|| {
                self.err(
                    line,
                    "CMBLOCK needs 'CMBLOCK, name, NODE or ELEM, number of entries'",
                )
            })?;
        let (_, f) = self.format("CMBLOCK", line)?;
        let mut values: Vec<i64> = Vec::new();
        while values.len() < count {
            let (l, text) = self.next_line().ok_or_else(|| {
                self.err(
                    line,
                    format!(
                        "the file ends inside component {name} ({} of {count} entries read)",
                        values.len()
                    ),
                )
            })?;
            let v = self.ints(&f, text, l)?;
            if v.is_empty() {
                return Err(self.err(
                    l,
                    format!(
                        "component {name}: expected {count} entries, found an empty line after {}",
                        values.len()
                    ),
                ));
            }
            values.extend(v);
        }
        let mut ids: Vec<u64> = Vec::with_capacity(values.len());
        for (k, &v) in values.iter().enumerate() {
            if v > 0 {
                ids.push(v as u64);
                continue;
            }
            let from = match k.checked_sub(1).map(|p| values[p]) {
                Some(p) if p > 0 && v < 0 && -v >= p => p as u64,
                _ => return Err(self.err(line, format!("component {name}: entry {} is {v}, which is neither an id nor the end of a range after an id", k + 1))),
            };
            let to = v.unsigned_abs();
            if to - from > 10_000_000 {
                return Err(self.err(
                    line,
                    format!(
                        "component {name}: the range {from} to {to} has more than 10 million ids"
                    ),
                ));
            }
            ids.extend(from + 1..=to);
        }
        match entity.as_str() {
            "NODE" | "NODES" => self.b.add_to_node_set(&name, ids),
            "ELEM" | "ELEMENT" | "ELEMENTS" => self.b.add_to_element_set(&name, ids),
            other => {
                return Err(self.err(
                    line,
                    format!(
                        "CMBLOCK {name}: expected NODE or ELEM, found '{}'",
                        shown(other)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// `MPDATA, R5.0, LENGTH, LAB, MAT, STLOC, C1, ...` (as CDWRITE writes it),
    /// `MPDATA, LAB, MAT, STLOC, C1, ...` and `MP, LAB, MAT, C0, C1, ...`.
    fn mpdata(&mut self, cmd: &str, args: &[&str], line: usize) -> Result<(), MeshError> {
        let record = cmd == "MPDATA"
            && args
                .get(1)
                .is_some_and(|s| s.to_ascii_uppercase().starts_with('R'));
        let (lab, mat, stloc, values) = match (cmd, record) {
            ("MPDATA", true) => (args.get(3), args.get(4), args.get(5), args.get(6..)),
            ("MPDATA", false) => (args.get(1), args.get(2), args.get(3), args.get(4..)),
            _ => (args.get(1), args.get(2), Some(&"1"), args.get(3..)),
        };
        let bad = || {
            self.err(line, format!("expected '{cmd}, label, material, ...' with a positive material number, found '{}'", shown(&args.join(","))))
        };
        let lab = lab
            .map(|s| s.to_ascii_uppercase())
            .filter(|s| !s.is_empty())
            .ok_or_else(bad)?;
        let mat = mat
            .and_then(|s| int(s))
            .filter(|&m| m > 0)
            .ok_or_else(bad)? as u64;
        let stloc = stloc
            .map(|s| if s.is_empty() { 1 } else { int(s).unwrap_or(0) })
            .unwrap_or(1);
        let values: Vec<&str> = values
            .unwrap_or(&[])
            .iter()
            .copied()
            .filter(|s| !s.is_empty())
            .collect();
        let Some(first) = values.first() else {
            return Err(bad());
        };
        let v = real(first).ok_or_else(|| {
            self.err(
                line,
                format!(
                    "{cmd} {lab} of material {mat}: expected a number, found '{}'",
                    shown(first)
                ),
            )
        })?;
        let later = stloc > 1 || values.len() > 1;
        if later {
            self.note("temperature", line, || "temperature-dependent material properties (several MPDATA values or MP coefficients): squeal uses the first".into());
        }
        if stloc <= 1 {
            let p = self.props.entry(mat).or_default();
            p.values.insert(lab, v);
            p.line = line;
        }
        Ok(())
    }

    /// The isotropic material of the properties read: EX with NUXY or PRXY (equal for an
    /// isotropic material; Ansys's default 0.3 if neither), DENS.
    fn material(&mut self, mat: u64, p: &Props) -> Result<Material, MeshError> {
        let get = |k: &str| p.values.get(k).copied();
        let density = get("DENS");
        let Some(ex) = get("EX") else {
            return Ok(Material {
                elastic: None,
                density,
            });
        };
        for k in ["EY", "EZ"] {
            if get(k).is_some_and(|e| e != ex) {
                return Err(self.err(p.line, format!("material {mat} has {k} = {:e} besides EX = {ex:e}: orthotropic Ansys materials are not read; give an isotropic material or the scene's [materials]", get(k).unwrap_or(0.0))));
            }
        }
        let nu = match (get("PRXY"), get("NUXY")) {
            (Some(a), Some(b)) if a != b => return Err(self.err(p.line, format!("material {mat} has PRXY = {a} and NUXY = {b}: for an isotropic material they are equal"))),
            (Some(a), _) | (None, Some(a)) => a,
            (None, None) => {
                self.warnings.push(Warning { file: self.path.to_path_buf(), location: Location::Line(p.line), message: format!("material {mat} gives no Poisson's ratio: 0.3, Ansys's default") });
                0.3
            }
        };
        if let Some(g) = get("GXY") {
            let implied = ex / (2.0 * (1.0 + nu));
            if ((g - implied) / implied).abs() > 0.01 {
                return Err(self.err(p.line, format!("material {mat} has GXY = {g:e}, but EX / (2 (1 + PRXY)) = {implied:e}: squeal's isotropic material has two constants; leave GXY out")));
            }
        }
        Ok(Material {
            elastic: Some(Elastic::Isotropic {
                young: ex,
                poisson: nu,
            }),
            density,
        })
    }

    fn finish(mut self) -> Result<ReadMesh, MeshError> {
        let props = std::mem::take(&mut self.props);
        for (&mat, p) in &props {
            let m = self.material(mat, p)?;
            self.b.set_material(&format!("MAT_{mat}"), m);
        }
        for (mat, ids) in std::mem::take(&mut self.by_material) {
            let name = format!("MAT_{mat}");
            self.b.add_to_element_set(&name, ids);
            if props.contains_key(&mat) {
                self.b.add_section(&name, &name);
            } else {
                let w = format!(
                    "elements are made of material {mat}, which no MPDATA defines: they have no material"
                );
                self.warnings.push(Warning {
                    file: self.path.to_path_buf(),
                    location: Location::File,
                    message: w,
                });
            }
        }
        for (line, count, stem) in std::mem::take(&mut self.once).into_values() {
            let times = if count == 1 {
                "once".to_string()
            } else {
                format!("{count} times, the first here")
            };
            self.warnings.push(Warning {
                file: self.path.to_path_buf(),
                location: Location::Line(line),
                message: format!("{stem} ({times})"),
            });
        }
        if self.b.num_elements() == 0 {
            self.warnings.push(Warning {
                file: self.path.to_path_buf(),
                location: Location::File,
                message: crate::NO_TET10.to_string(),
            });
        }
        Ok(ReadMesh {
            mesh: self.b.finish(),
            warnings: self.warnings,
        })
    }
}

/// At most 40 characters, for messages.
fn shown(s: &str) -> String {
    s.trim().chars().take(40).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solid186_forms() {
        let brick: Vec<u64> = (1..=20).collect();
        assert_eq!(solid186_form(&brick).unwrap().0, ElementKind::Hex20);
        let mut prism = brick.clone();
        (prism[3], prism[10], prism[7], prism[14], prism[19]) = (3, 3, 7, 7, 19);
        assert_eq!(solid186_form(&prism).unwrap().0, ElementKind::Wedge15);
        let mut pyr = brick.clone();
        for i in [5, 6, 7, 12, 13, 14, 15] {
            pyr[i] = 5;
        }
        assert_eq!(solid186_form(&pyr).unwrap().0, ElementKind::Pyramid13);
        let mut tet = pyr.clone();
        (tet[3], tet[10], tet[19]) = (3, 3, 19);
        assert_eq!(solid186_form(&tet).unwrap().0, ElementKind::Tet10);
        let mut odd = brick.clone();
        odd[0] = 2;
        assert!(solid186_form(&odd).is_none());
        assert_eq!(element_type("186"), Some(Type::Solid186));
        assert_eq!(element_type("SOLID187"), Some(Type::Solid187));
        assert_eq!(element_type("SURF154"), Some(Type::Other(154)));
        assert_eq!(element_type("x"), None);
    }
}
