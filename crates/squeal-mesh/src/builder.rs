//! [`MeshBuilder`]: what both readers fill while parsing, then turn into a [`Mesh`].
//!
//! Ids are the file's; the builder resolves them to dense indices in [`MeshBuilder::finish`],
//! where references to ids never defined become [`Dangling`] entries (reported by the quality
//! checks) rather than errors, so that one bad reference does not hide the rest of the file.

use crate::model::{Blocks, Dangling, Material, Mesh, Section};
use squeal_element::ElementKind;
use std::collections::{BTreeMap, HashMap, HashSet};

/// Collects nodes, elements, sets and materials by file id.
#[derive(Debug, Default)]
pub struct MeshBuilder {
    nodes: Vec<[f64; 3]>,
    node_ids: Vec<u64>,
    node_index: HashMap<u64, u32>,
    elements: Vec<(u64, [u64; 10])>,
    element_index: HashMap<u64, u32>,
    /// Elements of the other kinds, in file order (tet10 elements are kept apart, as fixed-size
    /// records, because meshes are mostly tet10).
    others: Vec<(u64, ElementKind, Vec<u64>)>,
    other_ids: HashSet<u64>,
    skipped_elements: HashSet<u64>,
    node_sets: BTreeMap<String, Vec<u64>>,
    element_sets: BTreeMap<String, Vec<u64>>,
    materials: BTreeMap<String, Material>,
    sections: Vec<Section>,
}

impl MeshBuilder {
    /// An empty builder.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a node. A second node with the same id is an error (the message says so; the
    /// reader adds the location).
    pub fn add_node(&mut self, id: u64, x: [f64; 3]) -> Result<(), String> {
        if self.node_index.contains_key(&id) {
            return Err(format!("node {id} is defined twice"));
        }
        self.node_index.insert(id, self.nodes.len() as u32);
        self.nodes.push(x);
        self.node_ids.push(id);
        Ok(())
    }

    /// Adds a tet10 element whose nodes (file ids) are already in canonical order.
    pub fn add_element(&mut self, id: u64, nodes: [u64; 10]) -> Result<(), String> {
        if self.has_element(id) {
            return Err(format!("element {id} is defined twice"));
        }
        self.element_index.insert(id, self.elements.len() as u32);
        self.elements.push((id, nodes));
        Ok(())
    }

    /// Adds an element of any kind whose nodes (file ids) are already in that kind's canonical
    /// order; an error if the id is taken or the node count is not the kind's.
    pub fn add_typed(&mut self, id: u64, kind: ElementKind, nodes: &[u64]) -> Result<(), String> {
        if nodes.len() != kind.nodes() {
            return Err(format!(
                "element {id} has {} nodes; a {kind} has {}",
                nodes.len(),
                kind.nodes()
            ));
        }
        if kind == ElementKind::Tet10 {
            let mut n = [0u64; 10];
            n.copy_from_slice(nodes);
            return self.add_element(id, n);
        }
        if self.has_element(id) {
            return Err(format!("element {id} is defined twice"));
        }
        self.other_ids.insert(id);
        self.others.push((id, kind, nodes.to_vec()));
        Ok(())
    }

    /// Records an element the reader skipped (a shell, a beam, ...), so that sets naming it
    /// drop it silently instead of reporting a missing element.
    pub fn skip_element(&mut self, id: u64) {
        self.skipped_elements.insert(id);
    }

    /// Whether a node id was defined.
    pub fn has_node(&self, id: u64) -> bool {
        self.node_index.contains_key(&id)
    }

    /// Whether an element id was defined (as an element of any kind or as a skipped one).
    pub fn has_element(&self, id: u64) -> bool {
        self.element_index.contains_key(&id)
            || self.other_ids.contains(&id)
            || self.skipped_elements.contains(&id)
    }

    /// Members (file element ids, as added, unsorted and possibly repeated) of an element set
    /// defined so far, or `None`. The name is matched exactly (case-sensitive).
    pub fn element_set_ids(&self, name: &str) -> Option<&[u64]> {
        self.element_sets.get(name).map(Vec::as_slice)
    }

    /// Members (file node ids, as added, unsorted and possibly repeated) of a node set defined
    /// so far, or `None`. The name is matched exactly (case-sensitive).
    pub fn node_set_ids(&self, name: &str) -> Option<&[u64]> {
        self.node_sets.get(name).map(Vec::as_slice)
    }

    /// Connectivity (file ids) of a tet10 element defined so far.
    pub fn element_nodes(&self, id: u64) -> Option<&[u64; 10]> {
        self.element_index
            .get(&id)
            .map(|&i| &self.elements[i as usize].1)
    }

    /// Adds members (file node ids) to a node set, creating it if needed (an empty set is
    /// kept: the quality checks report it).
    pub fn add_to_node_set(&mut self, name: &str, ids: impl IntoIterator<Item = u64>) {
        self.node_sets
            .entry(name.to_string())
            .or_default()
            .extend(ids);
    }

    /// Adds members (file element ids) to an element set, creating it if needed.
    pub fn add_to_element_set(&mut self, name: &str, ids: impl IntoIterator<Item = u64>) {
        self.element_sets
            .entry(name.to_string())
            .or_default()
            .extend(ids);
    }

    /// Adds or replaces a material.
    pub fn set_material(&mut self, name: &str, material: Material) {
        self.materials.insert(name.to_string(), material);
    }

    /// A material defined so far, to be completed (`*ELASTIC` after `*MATERIAL`, ...).
    pub fn material_mut(&mut self, name: &str) -> Option<&mut Material> {
        self.materials.get_mut(name)
    }

    /// States that an element set is made of a material.
    pub fn add_section(&mut self, element_set: &str, material: &str) {
        self.sections.push(Section {
            element_set: element_set.to_string(),
            material: material.to_string(),
        });
    }

    /// Number of nodes added so far.
    pub fn num_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Number of elements (of all kinds) added so far.
    pub fn num_elements(&self) -> usize {
        self.elements.len() + self.others.len()
    }

    /// Resolves ids to indices. Elements naming a missing node are dropped and listed in
    /// [`Mesh::dangling`], as are set members naming missing ids.
    pub fn finish(self) -> Mesh {
        let mut dangling = Vec::new();
        let mut blocks = Blocks::default();
        let total = self.num_elements();
        let mut element_ids = Vec::with_capacity(total);
        let mut kept_index = HashMap::with_capacity(total);
        let mut conn = Vec::with_capacity(20);
        let tets = self
            .elements
            .iter()
            .map(|(id, n)| (*id, ElementKind::Tet10, &n[..]));
        // Block order: tet10 first, then each other kind in turn, file order within a kind.
        let others = ElementKind::ALL[1..].iter().flat_map(|&kind| {
            self.others
                .iter()
                .filter(move |(_, k, _)| *k == kind)
                .map(|(id, k, n)| (*id, *k, &n[..]))
        });
        for (id, kind, nodes) in tets.chain(others) {
            conn.clear();
            for n in nodes {
                match self.node_index.get(n) {
                    Some(&i) => conn.push(i),
                    None => dangling.push(Dangling::ElementNode {
                        element: id,
                        node: *n,
                    }),
                }
            }
            if conn.len() == nodes.len() && blocks.push(kind, &conn) {
                kept_index.insert(id, element_ids.len() as u32);
                element_ids.push(id);
            }
        }
        let mut node_sets = BTreeMap::new();
        for (name, ids) in self.node_sets {
            let mut v: Vec<u32> = Vec::with_capacity(ids.len());
            for id in ids {
                match self.node_index.get(&id) {
                    Some(&i) => v.push(i),
                    None => dangling.push(Dangling::NodeSetMember {
                        set: name.clone(),
                        node: id,
                    }),
                }
            }
            v.sort_unstable();
            v.dedup();
            node_sets.insert(name, v);
        }
        let mut element_sets = BTreeMap::new();
        for (name, ids) in self.element_sets {
            let mut v: Vec<u32> = Vec::with_capacity(ids.len());
            for id in ids {
                match kept_index.get(&id) {
                    Some(&i) => v.push(i),
                    // Skipped (non-tet) elements and elements dropped for a missing node are
                    // already accounted for.
                    None if self.skipped_elements.contains(&id)
                        || self.element_index.contains_key(&id)
                        || self.other_ids.contains(&id) => {}
                    None => dangling.push(Dangling::ElementSetMember {
                        set: name.clone(),
                        element: id,
                    }),
                }
            }
            v.sort_unstable();
            v.dedup();
            element_sets.insert(name, v);
        }
        Mesh {
            nodes: self.nodes,
            node_ids: self.node_ids,
            blocks,
            element_ids,
            node_sets,
            element_sets,
            materials: self.materials,
            sections: self.sections,
            dangling,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolves_ids_and_reports_dangling_references() {
        let mut b = MeshBuilder::new();
        for (k, id) in [10u64, 20, 30, 40, 50, 60, 70, 80, 90, 100]
            .iter()
            .enumerate()
        {
            b.add_node(*id, [k as f64, 0.0, 0.0]).unwrap();
        }
        assert!(b.add_node(10, [0.0; 3]).is_err());
        b.add_element(7, [10, 20, 30, 40, 50, 60, 70, 80, 90, 100])
            .unwrap();
        b.add_element(8, [10, 20, 30, 40, 50, 60, 70, 80, 90, 999])
            .unwrap();
        b.skip_element(9);
        b.add_to_node_set("A", [30, 10, 10, 555]);
        b.add_to_element_set("E", [7, 8, 9, 11]);
        b.add_to_node_set("EMPTY", []);
        let m = b.finish();
        assert_eq!(m.blocks.tet10.len(), 1);
        assert_eq!(m.element_ids, vec![7]);
        assert_eq!(m.node_sets["A"], vec![0, 2]);
        assert_eq!(m.element_sets["E"], vec![0]);
        assert!(m.node_sets["EMPTY"].is_empty());
        assert_eq!(
            m.dangling,
            vec![
                Dangling::ElementNode {
                    element: 8,
                    node: 999
                },
                Dangling::NodeSetMember {
                    set: "A".into(),
                    node: 555
                },
                Dangling::ElementSetMember {
                    set: "E".into(),
                    element: 11
                },
            ]
        );
    }
}
