//! What one scope defines, by the file's labels: a part, an instance (a copy of its part plus
//! what its `*INSTANCE` block adds), or the model and assembly level.

use super::lex::Loc;
use squeal_element::ElementKind;
use std::collections::{BTreeMap, BTreeSet, HashMap};

/// A named set: the spelling first seen and its members.
#[derive(Clone, Debug, Default)]
pub(super) struct NamedSet {
    pub name: String,
    pub ids: BTreeSet<u64>,
}

/// Sets by name, ASCII case-insensitive as in Abaqus; iteration is in name order.
#[derive(Clone, Debug, Default)]
pub(super) struct Sets {
    map: BTreeMap<String, NamedSet>,
}

impl Sets {
    pub fn get(&self, name: &str) -> Option<&NamedSet> {
        self.map.get(&name.to_ascii_uppercase())
    }

    /// The set of that name, created empty (with this spelling) if new.
    pub fn entry(&mut self, name: &str) -> &mut NamedSet {
        self.map
            .entry(name.to_ascii_uppercase())
            .or_insert_with(|| NamedSet {
                name: name.to_string(),
                ids: BTreeSet::new(),
            })
    }

    pub fn iter(&self) -> impl Iterator<Item = &NamedSet> {
        self.map.values()
    }
}

/// A `*SOLID SECTION` as written: element set and material names.
#[derive(Clone, Debug)]
pub(super) struct SectionRef {
    pub element_set: String,
    pub material: String,
    pub loc: Loc,
}

/// Which kind of id a set holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Node,
    Element,
}

impl Kind {
    pub fn noun(self) -> &'static str {
        match self {
            Kind::Node => "node",
            Kind::Element => "element",
        }
    }
}

/// Nodes, tet10 elements, skipped elements, sets and sections of one scope.
#[derive(Clone, Debug, Default)]
pub(super) struct Store {
    pub nodes: Vec<(u64, [f64; 3])>,
    node_loc: HashMap<u64, Loc>,
    /// Tet10 elements, nodes in canonical (= C3D10) order.
    pub elements: Vec<(u64, [u64; 10])>,
    /// Elements of the other solid kinds, nodes in canonical (= Abaqus) order.
    pub others: Vec<(u64, ElementKind, Vec<u64>)>,
    /// Labels of tet10 and skipped elements, in definition order.
    element_labels: Vec<u64>,
    element_loc: HashMap<u64, Loc>,
    /// Elements of other types, which the mesh leaves out.
    pub skipped: Vec<u64>,
    pub node_sets: Sets,
    pub element_sets: Sets,
    pub sections: Vec<SectionRef>,
}

impl Store {
    /// Adds a node; a label defined before gives the place of its first definition.
    pub fn add_node(&mut self, id: u64, x: [f64; 3], loc: Loc) -> Result<(), Loc> {
        if let Some(first) = self.node_loc.get(&id) {
            return Err(*first);
        }
        self.node_loc.insert(id, loc);
        self.nodes.push((id, x));
        Ok(())
    }

    /// Adds a solid element of a kind (its first `kind.nodes()` node ids), or, with
    /// `nodes == None`, records a skipped one.
    pub fn add_element(
        &mut self,
        id: u64,
        nodes: Option<(ElementKind, [u64; 20])>,
        loc: Loc,
    ) -> Result<(), Loc> {
        if let Some(first) = self.element_loc.get(&id) {
            return Err(*first);
        }
        self.element_loc.insert(id, loc);
        self.element_labels.push(id);
        match nodes {
            Some((ElementKind::Tet10, n)) => {
                let mut tet = [0u64; 10];
                tet.copy_from_slice(&n[..10]);
                self.elements.push((id, tet));
            }
            Some((kind, n)) => self.others.push((id, kind, n[..kind.nodes()].to_vec())),
            None => self.skipped.push(id),
        }
        Ok(())
    }

    pub fn has(&self, kind: Kind, id: u64) -> bool {
        match kind {
            Kind::Node => self.node_loc.contains_key(&id),
            Kind::Element => self.element_loc.contains_key(&id),
        }
    }

    /// Number of labels of that kind defined so far.
    pub fn count(&self, kind: Kind) -> usize {
        match kind {
            Kind::Node => self.nodes.len(),
            Kind::Element => self.element_labels.len(),
        }
    }

    /// Labels of that kind in definition order.
    pub fn labels(&self, kind: Kind) -> Box<dyn Iterator<Item = u64> + '_> {
        match kind {
            Kind::Node => Box::new(self.nodes.iter().map(|(id, _)| *id)),
            Kind::Element => Box::new(self.element_labels.iter().copied()),
        }
    }

    pub fn sets(&self, kind: Kind) -> &Sets {
        match kind {
            Kind::Node => &self.node_sets,
            Kind::Element => &self.element_sets,
        }
    }

    pub fn sets_mut(&mut self, kind: Kind) -> &mut Sets {
        match kind {
            Kind::Node => &mut self.node_sets,
            Kind::Element => &mut self.element_sets,
        }
    }
}
