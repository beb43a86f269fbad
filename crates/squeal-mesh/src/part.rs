//! Parts of an assembly file: the sub-mesh of one element set, and the bodies a mesh holds.
//!
//! CAE tools export a whole assembly (disc, pads, shims, caliper) as one file with each part
//! an element set. [`Mesh::part`] cuts one out: its elements (in the file's order, block by
//! block), the nodes they use (in the file's order), the node and element sets restricted to
//! them (a set that covers nodes of several parts, such as a `CONTACT_FACE` holding the disc's
//! and the pad's face nodes, gives each part its own share; a set with nothing in the part is
//! dropped) and the materials its sections name. Because the order of the nodes and elements
//! is kept, a part cut from a combined file is the same mesh, index for index, as the part
//! written alone (only the file ids differ when the combined file renumbers them), and every
//! later number is the same bit for bit.
//!
//! [`bodies`] finds the connected components of the elements (two elements are connected
//! when they share a node): what `squeal mesh info` reports as the bodies of a file, with the
//! element sets that cover each.

use crate::model::{Blocks, Dangling, Mesh};
use std::collections::BTreeMap;

/// Why a part cannot be cut out of a mesh.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PartError {
    /// The mesh has no element set of that name.
    #[error("no element set {name} (the file's element sets: {known})")]
    NoSet {
        /// The name asked for.
        name: String,
        /// The element sets the mesh has, comma separated.
        known: String,
    },
    /// The element set holds no element.
    #[error("element set {name} is empty")]
    Empty {
        /// The name asked for.
        name: String,
    },
}

/// One body of a mesh: a connected component of its elements.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// Number of elements.
    pub elements: usize,
    /// Number of nodes its elements use.
    pub nodes: usize,
    /// The file id of its first element.
    pub first_element: u64,
    /// The element sets holding all of its elements (`true`) or some of them (`false`).
    pub sets: Vec<(String, bool)>,
}

impl Mesh {
    /// The part of element set `name` (ASCII case-insensitive): its elements, the nodes they
    /// use, the sets restricted to them and the materials of its sections (module docs).
    pub fn part(&self, name: &str) -> Result<Mesh, PartError> {
        self.part_of_sets(&[name.to_string()])
    }

    /// The part made of the element sets `names` together (a pad and the shim tied to it):
    /// [`Mesh::part`] of their union.
    pub fn part_of_sets(&self, names: &[String]) -> Result<Mesh, PartError> {
        let mut keep_element = vec![false; self.num_elements()];
        for name in names {
            let set = self.element_set(name).ok_or_else(|| PartError::NoSet {
                name: name.to_string(),
                known: self
                    .element_sets
                    .keys()
                    .cloned()
                    .collect::<Vec<_>>()
                    .join(", "),
            })?;
            if set.is_empty() {
                return Err(PartError::Empty { name: name.into() });
            }
            for &e in set {
                if let Some(k) = keep_element.get_mut(e as usize) {
                    *k = true;
                }
            }
        }
        Ok(self.sub_mesh(&keep_element))
    }

    /// The mesh of the elements `keep[e]`, with the nodes they use (module docs).
    pub fn sub_mesh(&self, keep: &[bool]) -> Mesh {
        let mut used = vec![false; self.num_nodes()];
        for (e, conn) in self.blocks.iter().enumerate() {
            if keep.get(e).copied().unwrap_or(false) {
                for &n in conn {
                    used[n as usize] = true;
                }
            }
        }
        // Old node index -> new, in the file's order.
        let mut new_node = vec![u32::MAX; self.num_nodes()];
        let mut nodes = Vec::new();
        let mut node_ids = Vec::new();
        for (i, _) in used.iter().enumerate().filter(|(_, u)| **u) {
            new_node[i] = nodes.len() as u32;
            nodes.push(self.nodes[i]);
            node_ids.push(self.node_ids[i]);
        }
        let mut blocks = Blocks::default();
        let mut new_element = vec![u32::MAX; self.num_elements()];
        let mut element_ids = Vec::new();
        for (e, (kind, conn)) in (0..self.num_elements())
            .filter_map(|e| self.blocks.get(e).map(|k| (e, k)))
            .filter(|(e, _)| keep.get(*e).copied().unwrap_or(false))
        {
            let mapped: Vec<u32> = conn.iter().map(|&n| new_node[n as usize]).collect();
            new_element[e] = element_ids.len() as u32;
            blocks.push(kind, &mapped);
            element_ids.push(self.element_ids[e]);
        }
        let restrict = |sets: &BTreeMap<String, Vec<u32>>, map: &[u32]| {
            sets.iter()
                .filter_map(|(name, members)| {
                    let kept: Vec<u32> = members
                        .iter()
                        .filter_map(|&m| map.get(m as usize).copied())
                        .filter(|&m| m != u32::MAX)
                        .collect();
                    (!kept.is_empty()).then(|| (name.clone(), kept))
                })
                .collect::<BTreeMap<_, _>>()
        };
        let node_sets = restrict(&self.node_sets, &new_node);
        let element_sets = restrict(&self.element_sets, &new_element);
        let sections: Vec<_> = self
            .sections
            .iter()
            .filter(|s| {
                element_sets
                    .keys()
                    .any(|k| k.eq_ignore_ascii_case(&s.element_set))
            })
            .cloned()
            .collect();
        let materials = self
            .materials
            .iter()
            .filter(|(name, _)| sections.iter().any(|s| s.material == **name))
            .map(|(n, m)| (n.clone(), *m))
            .collect();
        // A missing member of a set the part keeps is still reported (the reduction refuses
        // such a set); the others belong to other parts.
        let dangling = self
            .dangling
            .iter()
            .filter(|d| match d {
                Dangling::NodeSetMember { set, .. } => node_sets.contains_key(set),
                Dangling::ElementSetMember { set, .. } => element_sets.contains_key(set),
                Dangling::ElementNode { .. } => false,
            })
            .cloned()
            .collect();
        Mesh {
            nodes,
            node_ids,
            blocks,
            element_ids,
            node_sets,
            element_sets,
            materials,
            sections,
            dangling,
        }
    }
}

/// The bodies of `mesh`: connected components of its elements through shared nodes, in the
/// order of their first element, each with the element sets that cover it.
pub fn bodies(mesh: &Mesh) -> Vec<Body> {
    let n = mesh.num_nodes();
    // Union-find on the nodes, joined along each element.
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn root(parent: &mut [u32], mut i: u32) -> u32 {
        while parent[i as usize] != i {
            let up = parent[parent[i as usize] as usize];
            parent[i as usize] = up;
            i = up;
        }
        i
    }
    for conn in mesh.blocks.iter() {
        for &m in &conn[1..] {
            let (a, b) = (root(&mut parent, conn[0]), root(&mut parent, m));
            if a != b {
                let (lo, hi) = if a < b { (a, b) } else { (b, a) };
                parent[hi as usize] = lo;
            }
        }
    }
    let mut body_of_root: BTreeMap<u32, usize> = BTreeMap::new();
    let mut body_of_element = Vec::with_capacity(mesh.num_elements());
    let mut out: Vec<Body> = Vec::new();
    let mut node_body = vec![usize::MAX; n];
    for (e, conn) in mesh.blocks.iter().enumerate() {
        let r = root(&mut parent, conn[0]);
        let k = *body_of_root.entry(r).or_insert_with(|| {
            out.push(Body {
                elements: 0,
                nodes: 0,
                first_element: mesh.element_ids.get(e).copied().unwrap_or(0),
                sets: Vec::new(),
            });
            out.len() - 1
        });
        out[k].elements += 1;
        for &m in conn {
            if node_body[m as usize] == usize::MAX {
                node_body[m as usize] = k;
                out[k].nodes += 1;
            }
        }
        body_of_element.push(k);
    }
    for (name, members) in &mesh.element_sets {
        let mut count = vec![0usize; out.len()];
        for &e in members {
            if let Some(&k) = body_of_element.get(e as usize) {
                count[k] += 1;
            }
        }
        for (k, c) in count.into_iter().enumerate().filter(|(_, c)| *c > 0) {
            let whole = c == out[k].elements;
            out[k].sets.push((name.clone(), whole));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::box_tet10;

    /// Two boxes side by side in one mesh, 1 m apart, as element sets `A` and `B`, with a
    /// node set over both.
    fn two_boxes() -> (Mesh, Mesh, Mesh) {
        let a = box_tet10([1.0, 1.0, 1.0], [2, 1, 1]);
        let mut b = box_tet10([1.0, 1.0, 1.0], [1, 2, 1]);
        for p in &mut b.nodes {
            p[0] += 2.0;
        }
        let mut m = a.clone();
        let offset = a.num_nodes() as u32;
        m.nodes.extend(&b.nodes);
        m.node_ids
            .extend(b.node_ids.iter().map(|i| i + 10 * offset as u64));
        let first = a.num_elements() as u32;
        for conn in &b.blocks.tet10 {
            m.blocks.tet10.push(conn.map(|n| n + offset));
        }
        m.element_ids
            .extend(b.element_ids.iter().map(|i| i + 10 * first as u64));
        m.element_sets.clear();
        m.element_sets.insert("A".into(), (0..first).collect());
        m.element_sets.insert(
            "B".into(),
            (first..first + b.num_elements() as u32).collect(),
        );
        m.node_sets.clear();
        for (name, nodes) in &a.node_sets {
            m.node_sets.insert(name.clone(), nodes.clone());
        }
        for (name, nodes) in &b.node_sets {
            m.node_sets
                .entry(name.clone())
                .or_default()
                .extend(nodes.iter().map(|n| n + offset));
        }
        (m, a, b)
    }

    #[test]
    fn a_part_cut_out_is_the_part_written_alone() {
        let (m, a, b) = two_boxes();
        let pa = m.part("a").unwrap();
        assert_eq!(pa.nodes, a.nodes);
        assert_eq!(pa.blocks, a.blocks);
        let pb = m.part("B").unwrap();
        assert_eq!(pb.nodes, b.nodes);
        assert_eq!(pb.blocks, b.blocks);
        // A set over both parts gives each its share.
        for (name, nodes) in &b.node_sets {
            assert_eq!(pb.node_set(name), Some(nodes.as_slice()), "{name}");
        }
        assert!(pb.element_set("A").is_none());
        let e = m.part("C").unwrap_err().to_string();
        assert!(e.contains("no element set C") && e.contains("A, B"), "{e}");
    }

    #[test]
    fn bodies_are_connected_components() {
        let (m, a, b) = two_boxes();
        let found = bodies(&m);
        assert_eq!(found.len(), 2);
        assert_eq!(found[0].elements, a.num_elements());
        assert_eq!(found[0].nodes, a.num_nodes());
        assert_eq!(found[1].elements, b.num_elements());
        assert_eq!(found[0].sets, vec![("A".to_string(), true)]);
        assert_eq!(found[1].sets, vec![("B".to_string(), true)]);
        assert_eq!(bodies(&a).len(), 1);
    }
}
