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

mod types;
#[allow(unused_imports)]
use types::*;

mod sets;

mod assembly;

mod materials;

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
                    "node {id} of instance {} is placed at ({}, {}, {}), not a finite point",
                    prefix.trim_end_matches('.'),
                    y[0],
                    y[1],
                    y[2]
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
mod tests;
