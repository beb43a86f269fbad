//! The keyword interpreter: fills one [`Store`] per scope (model/assembly level, part,
//! instance) from the lexed lines, then flattens the stores into a [`MeshBuilder`].

use super::INSTANCE_STRIDE;
use super::fields::{fields, label, real, real_or_zero};
use super::lex::{DataLine, Item, Keyword, Lexed, Loc, excerpt};
use super::store::{Kind, SectionRef, Store};
use super::transform::{Placement, Rotation};
use crate::{Elastic, Location, Material, MeshBuilder, MeshError, ReadMesh, Warning};
use squeal_element::ElementKind;
use std::collections::{BTreeSet, HashMap};

/// Most members one `GENERATE` range may name: more than a mesh can index (`u32`).
const MAX_GENERATE: u64 = u32::MAX as u64;

/// Where in the model structure the current keyword is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Context {
    Model,
    Part(usize),
    Assembly,
    Instance(usize),
}

/// Which store a keyword writes to (or resolves labels and set names in).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Target {
    /// Model and assembly level: labels are final ids.
    Global,
    Part(usize),
    Instance(usize),
}

struct Part {
    name: String,
    store: Store,
    loc: Loc,
    instanced: bool,
}

struct Instance {
    name: String,
    store: Store,
    placement: Placement,
    loc: Loc,
}

struct MaterialDef {
    name: String,
    material: Material,
}

/// One element record (possibly continued over several lines).
struct Record {
    id: u64,
    nodes: [u64; 20],
    /// Number of node ids in the record (only the first 20 are kept).
    count: usize,
    first: Loc,
    last: Loc,
}

/// A warning given once per distinct key, with a count patched in at the end.
struct Repeated {
    index: usize,
    count: usize,
    stem: String,
    tail: &'static str,
}

pub(super) struct Reader<'a> {
    lx: &'a Lexed,
    pos: usize,
    context: Context,
    global: Store,
    parts: Vec<Part>,
    instances: Vec<Instance>,
    assembly: Option<Loc>,
    materials: Vec<MaterialDef>,
    /// The material that `*ELASTIC` / `*DENSITY` complete.
    material: Option<usize>,
    warnings: Vec<Warning>,
    repeated: HashMap<String, Repeated>,
}

/// Whether an element type is a 10-node tetrahedron: `C3D10` and its variants (`C3D10M`,
/// `C3D10H`, `C3D10HS`, `C3D10I`, ...), which share its geometry and node order.
#[cfg(test)]
fn is_tet10(ty: &str) -> bool {
    solid_kind(ty) == Some(ElementKind::Tet10)
}

/// The solid kind of an element type: `C3D10` and its variants (`C3D10M`, `C3D10H`,
/// `C3D10HS`, `C3D10I`, ...), `C3D20` and `C3D20R` and their variants (`C3D20H`,
/// `C3D20RH`, ...), `C3D15` and its variants but the variable-node `C3D15V`: each shares its
/// base element's geometry and node order (Abaqus's order is the canonical one).
fn solid_kind(ty: &str) -> Option<ElementKind> {
    let variant = |base: &str| {
        ty.strip_prefix(base)
            .is_some_and(|rest| rest.chars().all(|c| c.is_ascii_alphabetic()))
    };
    if variant("C3D10") {
        Some(ElementKind::Tet10)
    } else if variant("C3D20") {
        Some(ElementKind::Hex20)
    } else if variant("C3D15") && !ty.contains('V') {
        Some(ElementKind::Wedge15)
    } else {
        None
    }
}

/// Node count of common element types squeal skips, so that their records can be delimited
/// even with a stray trailing comma; `None` for types not listed (then a record continues
/// exactly while its lines end with a comma).
fn other_node_count(ty: &str) -> Option<usize> {
    const TABLE: &[(&str, usize)] = &[
        ("C3D20", 20),
        ("C3D15", 15),
        ("C3D8", 8),
        ("C3D6", 6),
        ("C3D4", 4),
        ("DC3D10", 10),
        ("DC3D20", 20),
        ("DC3D8", 8),
        ("DC3D4", 4),
        ("STRI65", 6),
        ("STRI3", 3),
        ("S9", 9),
        ("S8", 8),
        ("S6", 6),
        ("S4", 4),
        ("S3", 3),
        ("M3D9", 9),
        ("M3D8", 8),
        ("M3D6", 6),
        ("M3D4", 4),
        ("M3D3", 3),
        ("CPS8", 8),
        ("CPE8", 8),
        ("CAX8", 8),
        ("CPS6", 6),
        ("CPE6", 6),
        ("CAX6", 6),
        ("CPS4", 4),
        ("CPE4", 4),
        ("CAX4", 4),
        ("CPS3", 3),
        ("CPE3", 3),
        ("CAX3", 3),
        ("B31", 2),
        ("B32", 3),
        ("B33", 2),
        ("T3D2", 2),
        ("T3D3", 3),
    ];
    TABLE.iter().find_map(|&(prefix, n)| {
        let rest = ty.strip_prefix(prefix)?;
        (rest.is_empty() || rest.starts_with(|c: char| c.is_ascii_alphabetic())).then_some(n)
    })
}

/// `id, x[, y[, z]]` (blank or missing coordinates are zero; up to three more fields, the
/// normal direction Abaqus allows, are read and ignored).
fn node_line(text: &str) -> Result<(u64, [f64; 3]), String> {
    const WHAT: [&str; 6] = ["x", "y", "z", "normal x", "normal y", "normal z"];
    let mut it = fields(text);
    let first = it
        .next()
        .ok_or("expected a node line 'id, x, y[, z]', found an empty line")?;
    let id = label(first).ok_or_else(|| {
        format!(
            "expected a node id (a non-negative integer), found '{}'",
            excerpt(first)
        )
    })?;
    let mut x = [0.0; 3];
    let mut n = 0;
    for f in it {
        let Some(what) = WHAT.get(n) else {
            return Err(format!(
                "node {id} has more than 6 numbers after its id; expected 'id, x, y[, z]' (and at most a normal)"
            ));
        };
        let v = real_or_zero(f).ok_or_else(|| {
            format!(
                "expected the {what} coordinate of node {id} as a number, found '{}'",
                excerpt(f)
            )
        })?;
        if n < 3 {
            x[n] = v;
        }
        n += 1;
    }
    if n == 0 {
        return Err(format!(
            "node {id} has no coordinates: expected 'id, x, y[, z]'"
        ));
    }
    Ok((id, x))
}

impl<'a> Reader<'a> {
    pub fn new(lx: &'a Lexed) -> Self {
        Self {
            lx,
            pos: 0,
            context: Context::Model,
            global: Store::default(),
            parts: Vec::new(),
            instances: Vec::new(),
            assembly: None,
            materials: Vec::new(),
            material: None,
            warnings: Vec::new(),
            repeated: HashMap::new(),
        }
    }

    /// Interprets every line, then flattens.
    pub fn run(mut self) -> Result<ReadMesh, MeshError> {
        let lx = self.lx;
        while let Some(item) = lx.items.get(self.pos) {
            self.pos += 1;
            match item {
                Item::Data(d) => {
                    return Err(self.err(
                        d.loc,
                        format!(
                            "expected a keyword line (starting with '*'), found the data line '{}'",
                            excerpt(lx.text(d))
                        ),
                    ));
                }
                Item::Keyword(kw) => self.keyword(kw)?,
            }
        }
        self.check_closed()?;
        self.finish()
    }

    fn err(&self, loc: Loc, message: impl Into<String>) -> MeshError {
        self.lx.error(loc, message)
    }

    fn warn(&mut self, loc: Loc, message: impl Into<String>) {
        self.warnings.push(self.lx.warning(loc, message));
    }

    /// A warning given once per `key`, at its first occurrence: `stem`, then the number of
    /// occurrences (patched in at the end) if more than one, then `tail`.
    fn warn_once(&mut self, key: String, loc: Loc, stem: String, tail: &'static str) {
        if let Some(r) = self.repeated.get_mut(&key) {
            r.count += 1;
            return;
        }
        let message = format!("{stem}{tail}");
        self.repeated.insert(
            key,
            Repeated {
                index: self.warnings.len(),
                count: 1,
                stem,
                tail,
            },
        );
        self.warn(loc, message);
    }

    fn next_data(&mut self) -> Option<&'a DataLine> {
        match self.lx.items.get(self.pos) {
            Some(Item::Data(d)) => {
                self.pos += 1;
                Some(d)
            }
            _ => None,
        }
    }

    fn skip_data(&mut self) -> usize {
        let mut n = 0;
        while self.next_data().is_some() {
            n += 1;
        }
        n
    }

    fn keyword(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        let key = kw.key.as_str();
        let known = matches!(
            key,
            "HEADING"
                | "NODE"
                | "ELEMENT"
                | "NSET"
                | "ELSET"
                | "PART"
                | "ENDPART"
                | "ASSEMBLY"
                | "ENDASSEMBLY"
                | "INSTANCE"
                | "ENDINSTANCE"
                | "MATERIAL"
                | "SOLIDSECTION"
        );
        if known {
            // A material's options follow it up to the next keyword squeal reads.
            self.material = None;
        }
        match key {
            "HEADING" => {
                self.skip_data();
                Ok(())
            }
            "NODE" => self.node(kw),
            "ELEMENT" => self.element(kw),
            "NSET" => self.set(kw, Kind::Node),
            "ELSET" => self.set(kw, Kind::Element),
            "PART" => self.part(kw),
            "ENDPART" => self.end(kw, |c| matches!(c, Context::Part(_)), Context::Model, "*PART"),
            "ASSEMBLY" => self.assembly(kw),
            "ENDASSEMBLY" => self.end(kw, |c| c == Context::Assembly, Context::Model, "*ASSEMBLY"),
            "INSTANCE" => self.instance(kw),
            "ENDINSTANCE" => self.end(kw, |c| matches!(c, Context::Instance(_)), Context::Assembly, "*INSTANCE"),
            "MATERIAL" => self.material(kw),
            "ELASTIC" => self.elastic(kw),
            "DENSITY" => self.density(kw),
            "SOLIDSECTION" => self.solid_section(kw),
            "NGEN" | "NFILL" | "NCOPY" | "NMAP" | "ELGEN" | "ELCOPY" => Err(self.err(
                kw.loc,
                format!(
                    "*{} generates or moves nodes or elements, which squeal does not do: export the mesh with explicit *NODE and *ELEMENT data",
                    kw.name
                ),
            )),
            "SYSTEM" => match self.next_data() {
                Some(d) => Err(self.err(
                    d.loc,
                    "*SYSTEM (a local coordinate system for the nodes that follow) is not supported: export the nodes in global coordinates",
                )),
                None => Ok(()),
            },
            _ => {
                self.skip_data();
                let stem = format!("skipped *{} and its data lines", kw.name);
                let tail = ": squeal reads only nodes, elements, sets, materials and sections";
                self.warn_once(format!("keyword {key}"), kw.loc, stem, tail);
                Ok(())
            }
        }
    }

    /// Warns (once per keyword and parameter) about parameters a keyword does not use.
    fn check_params(&mut self, kw: &Keyword, known: &[&str]) {
        for p in &kw.params {
            if !known.contains(&p.name.as_str()) {
                let stem = format!("ignored the parameter {} of *{}", p.name, kw.name);
                self.warn_once(format!("param {} {}", kw.key, p.name), kw.loc, stem, "");
            }
        }
    }

    /// The value of a name parameter (`NSET=name`), if the parameter is present; present
    /// without a value is an error.
    fn name_param(&self, kw: &'a Keyword, p: &str) -> Result<Option<&'a str>, MeshError> {
        match kw.param(p) {
            None => Ok(None),
            Some(param) => match param.value.as_deref() {
                Some(v) if !v.is_empty() => Ok(Some(v)),
                _ => Err(self.err(
                    kw.loc,
                    format!("*{} needs {p}=name, found {p} without a name", kw.name),
                )),
            },
        }
    }

    fn required(&self, kw: &'a Keyword, p: &str) -> Result<&'a str, MeshError> {
        self.name_param(kw, p)?
            .ok_or_else(|| self.err(kw.loc, format!("*{} needs the parameter {p}=", kw.name)))
    }

    fn target(&self) -> Target {
        match self.context {
            Context::Model | Context::Assembly => Target::Global,
            Context::Part(p) => Target::Part(p),
            Context::Instance(i) => Target::Instance(i),
        }
    }

    fn store(&self, t: Target) -> &Store {
        match t {
            Target::Global => &self.global,
            Target::Part(p) => &self.parts[p].store,
            Target::Instance(i) => &self.instances[i].store,
        }
    }

    fn store_mut(&mut self, t: Target) -> &mut Store {
        match t {
            Target::Global => &mut self.global,
            Target::Part(p) => &mut self.parts[p].store,
            Target::Instance(i) => &mut self.instances[i].store,
        }
    }

    /// Labels inside parts, instances and the assembly must stay below the instance stride
    /// so that renumbered instances cannot collide (see the module documentation).
    fn check_label(&self, id: u64, loc: Loc) -> Result<(), MeshError> {
        if self.context != Context::Model && id >= INSTANCE_STRIDE {
            return Err(self.err(
                loc,
                format!(
                    "label {id} is too large: inside *PART and *ASSEMBLY labels must be below {INSTANCE_STRIDE} (instance k is renumbered k*{INSTANCE_STRIDE} + label)"
                ),
            ));
        }
        Ok(())
    }

    fn duplicate(&self, kind: Kind, id: u64, loc: Loc, first: Loc) -> MeshError {
        let noun = kind.noun();
        self.err(
            loc,
            format!(
                "{noun} {id} is defined twice (first at {}:{})",
                self.lx.path(first).display(),
                first.line
            ),
        )
    }

    /// Renumbering offset of instance `i` (the (i+1)-th `*INSTANCE`).
    fn offset(i: usize) -> u64 {
        (i as u64 + 1) * INSTANCE_STRIDE
    }

    /// The `*INSTANCE` line of an instance target (the first line for the others).
    fn instance_loc(&self, t: Target) -> Loc {
        match t {
            Target::Instance(i) => self.instances[i].loc,
            _ => Loc { src: 0, line: 1 },
        }
    }

    fn find_instance(&self, name: &str) -> Option<usize> {
        self.instances
            .iter()
            .position(|x| x.name.eq_ignore_ascii_case(name))
    }

    /// `*NODE`.
    fn node(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["NSET", "SYSTEM", "INPUT"]);
        let nset = self.name_param(kw, "NSET")?;
        let cylindrical = match self
            .name_param(kw, "SYSTEM")?
            .map(str::to_ascii_uppercase)
            .as_deref()
        {
            None | Some("R") => false,
            Some("C") => true,
            Some(v) => {
                return Err(self.err(
                    kw.loc,
                    format!("*NODE, SYSTEM={v} is not supported (expected R, rectangular, or C, cylindrical)"),
                ));
            }
        };
        let target = self.target();
        let mut ids = Vec::new();
        while let Some(d) = self.next_data() {
            let (id, mut x) = node_line(self.lx.text(d)).map_err(|m| self.err(d.loc, m))?;
            self.check_label(id, d.loc)?;
            if cylindrical {
                // Abaqus SYSTEM=C: r, theta (degrees), z.
                let (s, c) = x[1].to_radians().sin_cos();
                x = [x[0] * c, x[0] * s, x[2]];
            }
            if let Err(first) = self.store_mut(target).add_node(id, x, d.loc) {
                return Err(self.duplicate(Kind::Node, id, d.loc, first));
            }
            if nset.is_some() {
                ids.push(id);
            }
        }
        if let Some(name) = nset {
            self.store_mut(target).node_sets.entry(name).ids.extend(ids);
        }
        Ok(())
    }

    /// `*ELEMENT`: C3D10, C3D20(R) and C3D15 (and variants) kept, other types skipped with
    /// one warning.
    fn element(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["TYPE", "ELSET", "INPUT"]);
        let ty: String = self
            .required(kw, "TYPE")?
            .split_whitespace()
            .collect::<String>()
            .to_ascii_uppercase();
        let elset = self.name_param(kw, "ELSET")?;
        let solid = solid_kind(&ty);
        let tet = solid.is_some();
        let needed = solid
            .map(ElementKind::nodes)
            .or_else(|| other_node_count(&ty));
        let target = self.target();
        let mut ids = Vec::new();
        let mut skipped = 0usize;
        while let Some(d) = self.next_data() {
            let r = self.record(d, needed, tet, &ty)?;
            self.check_label(r.id, r.first)?;
            let nodes = if let Some(kind) = solid {
                let k = kind.nodes();
                if r.count != k {
                    let hint = if r.count < k {
                        " (a record continued on the next line must end with a comma)"
                    } else {
                        ""
                    };
                    return Err(self.err(
                        r.last,
                        format!(
                            "element {} has {} node ids; {ty} needs {k}{hint}",
                            r.id, r.count
                        ),
                    ));
                }
                for &n in &r.nodes[..k] {
                    self.check_label(n, r.last)?;
                }
                Some((kind, r.nodes))
            } else {
                skipped += 1;
                None
            };
            if let Err(first) = self.store_mut(target).add_element(r.id, nodes, r.first) {
                return Err(self.duplicate(Kind::Element, r.id, r.first, first));
            }
            if elset.is_some() {
                ids.push(r.id);
            }
        }
        if skipped > 0 {
            let s = if skipped == 1 { "" } else { "s" };
            self.warn(
                kw.loc,
                format!(
                    "skipped {skipped} element{s} of type {ty} (squeal uses only C3D10, C3D20, C3D20R and C3D15 elements)"
                ),
            );
        }
        if let Some(name) = elset {
            self.store_mut(target)
                .element_sets
                .entry(name)
                .ids
                .extend(ids);
        }
        Ok(())
    }

    /// Reads one element record: its lines continue while they end with a comma and fewer
    /// than `needed` node ids (if known) were read. Node ids are parsed only if `parse_nodes`.
    fn record(
        &mut self,
        first: &DataLine,
        needed: Option<usize>,
        parse_nodes: bool,
        ty: &str,
    ) -> Result<Record, MeshError> {
        let mut vals = [0u64; 21];
        let mut n = 0usize;
        let mut line = *first;
        loop {
            let text = self.lx.text(&line);
            for f in fields(text) {
                if n == 0 || (parse_nodes && n < vals.len()) {
                    vals[n] = label(f).ok_or_else(|| {
                        let m = if n == 0 {
                            format!("expected an element id (a non-negative integer), found '{}'", excerpt(f))
                        } else {
                            format!("expected node id {n} of element {} as a non-negative integer, found '{}'", vals[0], excerpt(f))
                        };
                        self.err(line.loc, m)
                    })?;
                }
                n += 1;
            }
            if n == 0 {
                return Err(self.err(
                    line.loc,
                    "expected an element line 'id, node, node, ...', found an empty line",
                ));
            }
            let continues = text.ends_with(',') && needed.is_none_or(|k| n < k + 1);
            if !continues {
                break;
            }
            match self.next_data() {
                Some(d) => line = *d,
                None => {
                    let of = needed.map(|k| format!(" of {k}")).unwrap_or_default();
                    return Err(self.err(
                        line.loc,
                        format!(
                            "truncated record: element {} ({ty}) ends with a comma, but no data line follows ({} node ids{of} read)",
                            vals[0],
                            n - 1
                        ),
                    ));
                }
            }
        }
        let mut nodes = [0u64; 20];
        nodes.copy_from_slice(&vals[1..]);
        Ok(Record {
            id: vals[0],
            nodes,
            count: n - 1,
            first: first.loc,
            last: line.loc,
        })
    }

    /// `*NSET` / `*ELSET`, with or without `GENERATE`, at part, instance or assembly level.
    fn set(&mut self, kw: &'a Keyword, kind: Kind) -> Result<(), MeshError> {
        let pname = match kind {
            Kind::Node => "NSET",
            Kind::Element => "ELSET",
        };
        self.check_params(
            kw,
            &[
                pname, "GENERATE", "INSTANCE", "UNSORTED", "INTERNAL", "INPUT", "ELSET",
            ],
        );
        let name = self.required(kw, pname)?;
        if kind == Kind::Node && kw.flag("ELSET") {
            return Err(self.err(
                kw.loc,
                "*NSET with ELSET= (the nodes of an element set) is not supported",
            ));
        }
        let generate = kw.flag("GENERATE");
        let dest = self.target();
        let (src, offset) = match self.name_param(kw, "INSTANCE")? {
            None => (dest, 0),
            Some(inst) => {
                if self.context != Context::Assembly {
                    return Err(self.err(kw.loc, "INSTANCE= names an instance only at assembly level (inside *ASSEMBLY, outside *INSTANCE)"));
                }
                let i = self.find_instance(inst).ok_or_else(|| {
                    self.err(
                        kw.loc,
                        format!("instance {inst} is not defined (before this line)"),
                    )
                })?;
                (Target::Instance(i), Self::offset(i))
            }
        };
        let mut members = BTreeSet::new();
        let mut missing = 0u64;
        while let Some(d) = self.next_data() {
            if generate {
                missing =
                    missing.saturating_add(self.generate(d, kind, src, offset, &mut members)?);
            } else {
                for f in fields(self.lx.text(d)) {
                    if !f.is_empty() {
                        self.member(f, kind, src, offset, d.loc, &mut members)?;
                    }
                }
            }
        }
        if missing > 0 {
            let noun = kind.noun();
            self.warn(
                kw.loc,
                format!("GENERATE ranges of set {name} name {missing} {noun} labels that are not defined (before this line): they are left out"),
            );
        }
        self.store_mut(dest)
            .sets_mut(kind)
            .entry(name)
            .ids
            .extend(members);
        Ok(())
    }

    /// One `start, end[, step]` line of a `GENERATE` set: adds the labels in the range that
    /// are defined in `src` and returns how many in the range are not. The work is bounded
    /// by the number of labels defined, not by the size of the range.
    fn generate(
        &mut self,
        d: &DataLine,
        kind: Kind,
        src: Target,
        offset: u64,
        out: &mut BTreeSet<u64>,
    ) -> Result<u64, MeshError> {
        let text = self.lx.text(d);
        let mut v = [0u64; 3];
        let mut n = 0;
        for f in fields(text) {
            if n == 3 {
                return Err(self.err(
                    d.loc,
                    format!(
                        "expected GENERATE data 'start, end[, step]', found '{}'",
                        excerpt(text)
                    ),
                ));
            }
            v[n] = label(f).ok_or_else(|| {
                self.err(d.loc, format!("expected GENERATE data 'start, end[, step]' as non-negative integers, found '{}'", excerpt(f)))
            })?;
            n += 1;
        }
        if n < 2 {
            return Err(self.err(
                d.loc,
                format!(
                    "expected GENERATE data 'start, end[, step]', found '{}'",
                    excerpt(text)
                ),
            ));
        }
        let (start, end, step) = (v[0], v[1], if n == 3 { v[2] } else { 1 });
        if step == 0 {
            return Err(self.err(d.loc, "GENERATE step is 0; expected a positive step"));
        }
        if end < start {
            return Err(self.err(
                d.loc,
                format!("GENERATE range ends ({end}) before it starts ({start})"),
            ));
        }
        // In u128: 0 to u64::MAX has 2^64 members, one more than a u64 holds.
        let members = u128::from(end - start) / u128::from(step) + 1;
        let count = match u64::try_from(members) {
            Ok(c) if c <= MAX_GENERATE => c,
            _ => {
                return Err(self.err(
                    d.loc,
                    format!("GENERATE range {start} to {end} step {step} has {members} members, more than the {MAX_GENERATE} a mesh can hold"),
                ));
            }
        };
        let store = self.store(src);
        let mut found = 0u64;
        if count <= store.count(kind) as u64 {
            let mut id = start;
            loop {
                if store.has(kind, id) {
                    out.insert(id + offset);
                    found += 1;
                }
                match id.checked_add(step) {
                    Some(next) if next <= end => id = next,
                    _ => break,
                }
            }
        } else {
            for id in store
                .labels(kind)
                .filter(|&id| id >= start && id <= end && (id - start) % step == 0)
            {
                out.insert(id + offset);
                found += 1;
            }
        }
        Ok(count.saturating_sub(found))
    }

    /// One member of a set's data line: a label, a set name, or (at assembly level)
    /// `instance.label` / `instance.set`.
    fn member(
        &self,
        token: &str,
        kind: Kind,
        src: Target,
        offset: u64,
        loc: Loc,
        out: &mut BTreeSet<u64>,
    ) -> Result<(), MeshError> {
        let noun = kind.noun();
        if token.starts_with(|c: char| c.is_ascii_digit() || matches!(c, '+' | '-' | '.')) {
            let id = label(token).ok_or_else(|| {
                self.err(
                    loc,
                    format!(
                        "expected a {noun} label or a set name, found '{}'",
                        excerpt(token)
                    ),
                )
            })?;
            if src != Target::Global {
                self.check_instance_label(id, loc)?;
            }
            out.insert(id + offset);
            return Ok(());
        }
        let name = token.trim_matches('"');
        if let Some(set) = self.store(src).sets(kind).get(name) {
            out.extend(set.ids.iter().map(|&v| v + offset));
            return Ok(());
        }
        if src == Target::Global
            && let Some((inst, rest)) = name.split_once('.')
            && let Some(i) = self.find_instance(inst)
        {
            let off = Self::offset(i);
            if let Some(id) = label(rest) {
                self.check_instance_label(id, loc)?;
                out.insert(id + off);
                return Ok(());
            }
            if let Some(set) = self.instances[i].store.sets(kind).get(rest) {
                out.extend(set.ids.iter().map(|&v| v + off));
                return Ok(());
            }
            return Err(self.err(
                loc,
                format!("instance {inst} has no {noun} set '{rest}' (before this line)"),
            ));
        }
        Err(self.err(
            loc,
            format!(
                "{noun} set '{}' is not defined (before this line)",
                excerpt(name)
            ),
        ))
    }

    fn check_instance_label(&self, id: u64, loc: Loc) -> Result<(), MeshError> {
        if id >= INSTANCE_STRIDE {
            return Err(self.err(
                loc,
                format!(
                    "label {id} is too large for a part or instance (at most {})",
                    INSTANCE_STRIDE - 1
                ),
            ));
        }
        Ok(())
    }

    /// `*END PART`, `*END ASSEMBLY`, `*END INSTANCE`.
    fn end(
        &mut self,
        kw: &Keyword,
        open: impl Fn(Context) -> bool,
        outer: Context,
        opener: &str,
    ) -> Result<(), MeshError> {
        if !open(self.context) {
            return Err(self.err(kw.loc, format!("*{} without an open {opener}", kw.name)));
        }
        self.context = outer;
        Ok(())
    }

    /// `*PART, NAME=`.
    fn part(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["NAME"]);
        if self.context != Context::Model {
            return Err(self.err(kw.loc, "*PART inside another *PART or *ASSEMBLY (close it with *END PART / *END ASSEMBLY first)"));
        }
        let name = self.required(kw, "NAME")?;
        if let Some(p) = self
            .parts
            .iter()
            .find(|p| p.name.eq_ignore_ascii_case(name))
        {
            return Err(self.err(
                kw.loc,
                format!(
                    "part {name} is defined twice (first at line {})",
                    p.loc.line
                ),
            ));
        }
        self.parts.push(Part {
            name: name.to_string(),
            store: Store::default(),
            loc: kw.loc,
            instanced: false,
        });
        self.context = Context::Part(self.parts.len() - 1);
        Ok(())
    }

    /// `*ASSEMBLY`.
    fn assembly(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["NAME"]);
        if self.context != Context::Model {
            return Err(self.err(kw.loc, "*ASSEMBLY inside a *PART or another *ASSEMBLY"));
        }
        if let Some(first) = self.assembly {
            return Err(self.err(
                kw.loc,
                format!("a second *ASSEMBLY (the first is at line {})", first.line),
            ));
        }
        self.assembly = Some(kw.loc);
        self.context = Context::Assembly;
        Ok(())
    }

    /// `*INSTANCE, NAME=, PART=` and its optional translation and rotation lines.
    fn instance(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["NAME", "PART", "INSTANCE", "LIBRARY"]);
        if self.context != Context::Assembly {
            return Err(self.err(
                kw.loc,
                "*INSTANCE outside *ASSEMBLY (or inside another *INSTANCE)",
            ));
        }
        if kw.flag("INSTANCE") || kw.flag("LIBRARY") {
            return Err(self.err(kw.loc, "instances imported from a previous analysis (INSTANCE=, LIBRARY=) are not supported"));
        }
        let name = self.required(kw, "NAME")?;
        let part = self.required(kw, "PART")?;
        if let Some(x) = self
            .instances
            .iter()
            .find(|x| x.name.eq_ignore_ascii_case(name))
        {
            return Err(self.err(
                kw.loc,
                format!(
                    "instance {name} is defined twice (first at line {})",
                    x.loc.line
                ),
            ));
        }
        let p = self
            .parts
            .iter()
            .position(|x| x.name.eq_ignore_ascii_case(part))
            .ok_or_else(|| {
                self.err(
                    kw.loc,
                    format!("part {part} is not defined (before this line)"),
                )
            })?;
        if (self.instances.len() as u64 + 1)
            .checked_mul(INSTANCE_STRIDE)
            .and_then(|o| o.checked_add(INSTANCE_STRIDE))
            .is_none()
        {
            return Err(self.err(kw.loc, "too many instances to renumber"));
        }
        let placement = self.placement()?;
        self.parts[p].instanced = true;
        let store = self.parts[p].store.clone();
        self.instances.push(Instance {
            name: name.to_string(),
            store,
            placement,
            loc: kw.loc,
        });
        self.context = Context::Instance(self.instances.len() - 1);
        Ok(())
    }

    /// The optional `*INSTANCE` data lines: translation, then rotation.
    fn placement(&mut self) -> Result<Placement, MeshError> {
        let mut p = Placement::default();
        if let Some(d) = self.next_data() {
            let t = self.reals::<3>(d, 0, "a translation 'x, y, z'")?;
            p.translation = t;
        }
        if let Some(d) = self.next_data() {
            let r = self.reals::<7>(d, 7, "a rotation 'ax, ay, az, bx, by, bz, angle'")?;
            if r[6] != 0.0 {
                p.rotation = Some(
                    Rotation::about_axis([r[0], r[1], r[2]], [r[3], r[4], r[5]], r[6]).ok_or_else(
                        || self.err(d.loc, "the rotation axis points a and b coincide"),
                    )?,
                );
            }
        }
        Ok(p)
    }

    /// Up to `N` reals (blank = 0) from a data line that must have at least `min` fields.
    fn reals<const N: usize>(
        &self,
        d: &DataLine,
        min: usize,
        what: &str,
    ) -> Result<[f64; N], MeshError> {
        let text = self.lx.text(d);
        let mut v = [0.0; N];
        let mut n = 0;
        for f in fields(text) {
            if n == N {
                return Err(self.err(
                    d.loc,
                    format!("expected {what}, found more numbers: '{}'", excerpt(text)),
                ));
            }
            v[n] = real_or_zero(f).ok_or_else(|| {
                self.err(d.loc, format!("expected {what}, found '{}'", excerpt(f)))
            })?;
            n += 1;
        }
        if n < min {
            return Err(self.err(d.loc, format!("expected {what}, found '{}'", excerpt(text))));
        }
        Ok(v)
    }

    /// `*MATERIAL, NAME=`.
    fn material(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["NAME"]);
        let name = self.required(kw, "NAME")?;
        if self
            .materials
            .iter()
            .any(|m| m.name.eq_ignore_ascii_case(name))
        {
            return Err(self.err(kw.loc, format!("material {name} is defined twice")));
        }
        self.materials.push(MaterialDef {
            name: name.to_string(),
            material: Material::default(),
        });
        self.material = Some(self.materials.len() - 1);
        Ok(())
    }

    fn current_material(&self, kw: &Keyword) -> Result<usize, MeshError> {
        self.material
            .ok_or_else(|| self.err(kw.loc, format!("*{} must follow *MATERIAL", kw.name)))
    }

    /// Reals of the data lines following a material option: at least `min` fields must be
    /// present on the first line(s); values are taken in order across lines until `want`
    /// are read. Returns the values and the number of lines left over (temperature
    /// dependence, which squeal ignores).
    fn option_values(
        &mut self,
        kw: &Keyword,
        want: usize,
        names: &[&str],
    ) -> Result<(Vec<f64>, usize), MeshError> {
        let mut vals = Vec::with_capacity(want);
        let mut extra = 0;
        while let Some(d) = self.next_data() {
            if vals.len() >= want {
                extra += 1;
                continue;
            }
            for f in fields(self.lx.text(d)) {
                if vals.len() == want {
                    break; // a temperature or field variable
                }
                let what = names[vals.len()];
                let v = if f.is_empty() {
                    None
                } else {
                    Some(real(f).ok_or_else(|| {
                        self.err(
                            d.loc,
                            format!("expected {what} as a number, found '{}'", excerpt(f)),
                        )
                    })?)
                };
                vals.push(v.unwrap_or(0.0));
            }
        }
        if vals.len() < want {
            return Err(self.err(
                kw.loc,
                format!(
                    "*{} needs {want} value{} ({}), found {}",
                    kw.name,
                    if want == 1 { "" } else { "s" },
                    names.join(", "),
                    vals.len()
                ),
            ));
        }
        Ok((vals, extra))
    }

    /// `*ELASTIC`: `TYPE=ISOTROPIC` (E, nu) or `TYPE=ENGINEERING CONSTANTS` (E1, E2, E3, nu12,
    /// nu13, nu23, G12, G13, G23 over two lines).
    fn elastic(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["TYPE", "MODULI", "DEPENDENCIES"]);
        let m = self.current_material(kw)?;
        let ty = self
            .name_param(kw, "TYPE")?
            .unwrap_or("ISOTROPIC")
            .split_whitespace()
            .collect::<String>()
            .to_ascii_uppercase();
        let elastic = match ty.as_str() {
            "ISOTROPIC" | "ISO" => {
                let (v, extra) = self.option_values(kw, 2, &["E", "nu"])?;
                self.warn_temperature(kw, extra);
                Elastic::Isotropic {
                    young: v[0],
                    poisson: v[1],
                }
            }
            "ENGINEERINGCONSTANTS" => {
                let names = [
                    "E1", "E2", "E3", "nu12", "nu13", "nu23", "G12", "G13", "G23",
                ];
                let (v, extra) = self.option_values(kw, 9, &names)?;
                self.warn_temperature(kw, extra);
                Elastic::EngineeringConstants {
                    e: [v[0], v[1], v[2]],
                    nu: [v[3], v[4], v[5]],
                    g: [v[6], v[7], v[8]],
                }
            }
            other => {
                return Err(self.err(
                    kw.loc,
                    format!("*ELASTIC, TYPE={other} is not supported (expected ISOTROPIC or ENGINEERING CONSTANTS)"),
                ));
            }
        };
        self.materials[m].material.elastic = Some(elastic);
        Ok(())
    }

    fn warn_temperature(&mut self, kw: &Keyword, extra_lines: usize) {
        if extra_lines > 0 {
            self.warn(kw.loc, format!("*{} has more data lines (temperature-dependent data?): squeal uses the first set of values", kw.name));
        }
    }

    /// `*DENSITY`.
    fn density(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["DEPENDENCIES"]);
        let m = self.current_material(kw)?;
        let (v, extra) = self.option_values(kw, 1, &["the density"])?;
        self.warn_temperature(kw, extra);
        self.materials[m].material.density = Some(v[0]);
        Ok(())
    }

    /// `*SOLID SECTION, ELSET=, MATERIAL=`.
    fn solid_section(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["ELSET", "MATERIAL", "ORIENTATION", "CONTROLS"]);
        if kw.flag("COMPOSITE") {
            return Err(self.err(kw.loc, "*SOLID SECTION, COMPOSITE is not supported"));
        }
        let elset = self.required(kw, "ELSET")?;
        let material = self.required(kw, "MATERIAL")?;
        if let Some(o) = self.name_param(kw, "ORIENTATION")? {
            self.warn(
                kw.loc,
                format!(
                    "ORIENTATION={o} ignored: squeal takes material constants in the global axes"
                ),
            );
        }
        self.skip_data();
        let t = self.target();
        self.store_mut(t).sections.push(SectionRef {
            element_set: elset.to_string(),
            material: material.to_string(),
            loc: kw.loc,
        });
        Ok(())
    }

    /// A file ending inside a part, assembly or instance is an error at its opening line.
    fn check_closed(&self) -> Result<(), MeshError> {
        let (loc, what) = match self.context {
            Context::Model => return Ok(()),
            Context::Part(p) => (
                self.parts[p].loc,
                format!("*PART {} is not closed by *END PART", self.parts[p].name),
            ),
            Context::Instance(i) => (
                self.instances[i].loc,
                format!(
                    "*INSTANCE {} is not closed by *END INSTANCE",
                    self.instances[i].name
                ),
            ),
            Context::Assembly => (
                self.assembly.unwrap_or(Loc { src: 0, line: 1 }),
                "*ASSEMBLY is not closed by *END ASSEMBLY".to_string(),
            ),
        };
        Err(self.err(loc, format!("the file ends, but {what}")))
    }

    /// Flattens the stores into one mesh: model/assembly level first (labels unchanged), then
    /// each instance in order (labels offset, coordinates placed, sets prefixed).
    fn finish(mut self) -> Result<ReadMesh, MeshError> {
        let mut b = MeshBuilder::new();
        for m in &self.materials {
            b.set_material(&m.name, m.material);
        }
        let mut late = Vec::new();
        self.flush(
            &mut b,
            Target::Global,
            0,
            &Placement::default(),
            "",
            &mut late,
        )?;
        for i in 0..self.instances.len() {
            let prefix = format!("{}.", self.instances[i].name);
            let placement = self.instances[i].placement;
            self.flush(
                &mut b,
                Target::Instance(i),
                Self::offset(i),
                &placement,
                &prefix,
                &mut late,
            )?;
        }
        for p in &self.parts {
            if !p.instanced {
                let (n, e) = (p.store.nodes.len(), p.store.count(Kind::Element));
                let w = format!(
                    "part {} is never instanced: its {n} node(s) and {e} element(s) are not in the mesh",
                    p.name
                );
                late.push(self.lx.warning(p.loc, w));
            }
        }
        for r in self.repeated.values() {
            let times = match r.count {
                1 => "once".to_string(),
                n => format!("{n} times, the first here"),
            };
            self.warnings[r.index].message = format!("{} ({times}){}", r.stem, r.tail);
        }
        self.warnings.extend(late);
        if b.num_elements() == 0 {
            let root = &self.lx.sources[0].path;
            self.warnings.push(Warning {
                file: root.clone(),
                location: Location::File,
                message: crate::NO_TET10.to_string(),
            });
        }
        Ok(ReadMesh {
            mesh: b.finish(),
            warnings: self.warnings,
        })
    }

    fn flush(
        &self,
        b: &mut MeshBuilder,
        t: Target,
        offset: u64,
        placement: &Placement,
        prefix: &str,
        warnings: &mut Vec<Warning>,
    ) -> Result<(), MeshError> {
        let store = self.store(t);
        let root = &self.lx.sources[0].path;
        let clash = |m: String| {
            MeshError::invalid(
                root,
                Location::File,
                format!(
                    "{m} after renumbering instances (instance k's labels become k*{INSTANCE_STRIDE} + label)"
                ),
            )
        };
        let identity = placement.is_identity();
        for &(id, x) in &store.nodes {
            let y = if identity { x } else { placement.apply(x) };
            if !y.iter().all(|v| v.is_finite()) {
                let w = format!(
                    "node {id} of instance {} is placed at {y:?}, not a finite point",
                    prefix.trim_end_matches('.')
                );
                return Err(self.err(self.instance_loc(t), w));
            }
            b.add_node(id + offset, y).map_err(clash)?;
        }
        for (id, nodes) in &store.elements {
            b.add_element(id + offset, nodes.map(|n| n + offset))
                .map_err(clash)?;
        }
        for (id, kind, nodes) in &store.others {
            let moved: Vec<u64> = nodes.iter().map(|n| n + offset).collect();
            b.add_typed(id + offset, *kind, &moved).map_err(clash)?;
        }
        for &id in &store.skipped {
            b.skip_element(id + offset);
        }
        for set in store.node_sets.iter() {
            b.add_to_node_set(
                &format!("{prefix}{}", set.name),
                set.ids.iter().map(|&v| v + offset),
            );
        }
        for set in store.element_sets.iter() {
            b.add_to_element_set(
                &format!("{prefix}{}", set.name),
                set.ids.iter().map(|&v| v + offset),
            );
        }
        for s in &store.sections {
            let elset = match store.element_sets.get(&s.element_set) {
                Some(set) => set.name.clone(),
                None => {
                    let w = format!(
                        "*SOLID SECTION names element set {}, which is not defined",
                        s.element_set
                    );
                    warnings.push(self.lx.warning(s.loc, w));
                    s.element_set.clone()
                }
            };
            let material = match self
                .materials
                .iter()
                .find(|m| m.name.eq_ignore_ascii_case(&s.material))
            {
                Some(m) => m.name.clone(),
                None => {
                    let w = format!(
                        "*SOLID SECTION names material {}, which is not defined",
                        s.material
                    );
                    warnings.push(self.lx.warning(s.loc, w));
                    s.material.clone()
                }
            };
            b.add_section(&format!("{prefix}{elset}"), &material);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn element_types() {
        for t in ["C3D10", "C3D10M", "C3D10H", "C3D10HS", "C3D10I", "C3D10MH"] {
            assert!(is_tet10(t), "{t}");
        }
        for t in ["C3D4", "C3D20", "DC3D10", "C3D100", "S8"] {
            assert!(!is_tet10(t), "{t}");
        }
        assert_eq!(other_node_count("S8R"), Some(8));
        assert_eq!(other_node_count("S4R5"), Some(4));
        assert_eq!(other_node_count("C3D20R"), Some(20));
        assert_eq!(other_node_count("C3D8I"), Some(8));
        assert_eq!(other_node_count("SPRINGA"), None);
        assert_eq!(other_node_count("S80"), None);
    }

    #[test]
    fn node_lines() {
        assert_eq!(node_line("7, 1., 2.").unwrap(), (7, [1.0, 2.0, 0.0]));
        assert_eq!(node_line("7, 1., , 3,").unwrap(), (7, [1.0, 0.0, 3.0]));
        assert_eq!(
            node_line("7, 1, 2, 3, 0, 0, 1").unwrap(),
            (7, [1.0, 2.0, 3.0])
        );
        assert!(node_line("7").is_err());
        assert!(node_line("7, 1, 2, 3, 0, 0, 1, 9").is_err());
        assert!(node_line("x, 1, 2").is_err());
        assert!(node_line("7, 1, two").is_err());
    }
}
