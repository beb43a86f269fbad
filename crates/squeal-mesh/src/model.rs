//! The mesh: nodes, canonical tet10 elements, named sets and materials.

use std::collections::{BTreeMap, HashMap};

/// A mesh of 10-node tetrahedra.
///
/// Nodes and elements are stored densely (index `0..n`); their ids in the source file, which
/// need be neither consecutive nor start at 1, are kept beside them. Element connectivity holds
/// node *indices* in the canonical ordering of [`crate::tet10`] (Abaqus C3D10 = VTK quadratic
/// tetra), whatever the file's own ordering was.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Coordinates of each node.
    pub nodes: Vec<[f64; 3]>,
    /// The file's id of each node.
    pub node_ids: Vec<u64>,
    /// Connectivity (node indices, canonical ordering) of each element.
    pub elements: Vec<[u32; 10]>,
    /// The file's id of each element.
    pub element_ids: Vec<u64>,
    /// Named node sets: sorted, unique node indices.
    pub node_sets: BTreeMap<String, Vec<u32>>,
    /// Named element sets: sorted, unique element indices.
    pub element_sets: BTreeMap<String, Vec<u32>>,
    /// Materials by name.
    pub materials: BTreeMap<String, Material>,
    /// Which material each element set is made of (Abaqus `*SOLID SECTION`).
    pub sections: Vec<Section>,
    /// References to ids the file never defined. Elements that reference a missing node are not
    /// in `elements`; they are listed here and reported as errors by [`crate::quality`].
    pub dangling: Vec<Dangling>,
}

/// Linear elastic constants as a file states them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Elastic {
    /// Young's modulus (Pa) and Poisson's ratio.
    Isotropic { young: f64, poisson: f64 },
    /// Abaqus `TYPE=ENGINEERING CONSTANTS` in the global axes: E1, E2, E3, nu12, nu13, nu23,
    /// G12, G13, G23.
    EngineeringConstants {
        e: [f64; 3],
        nu: [f64; 3],
        g: [f64; 3],
    },
}

/// A material: elastic constants and density (kg/m^3), each present if the file gives it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Material {
    pub elastic: Option<Elastic>,
    pub density: Option<f64>,
}

/// An element set made of a material.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Section {
    pub element_set: String,
    pub material: String,
}

/// A reference to an id that does not exist in the file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Dangling {
    /// An element names a node that was never defined; the element is dropped.
    ElementNode { element: u64, node: u64 },
    /// A node set names a node that was never defined; the member is dropped.
    NodeSetMember { set: String, node: u64 },
    /// An element set names an element that was never defined; the member is dropped.
    ElementSetMember { set: String, element: u64 },
}

impl Mesh {
    pub fn num_nodes(&self) -> usize {
        self.nodes.len()
    }

    pub fn num_elements(&self) -> usize {
        self.elements.len()
    }

    /// Map from file node id to node index.
    pub fn node_index_map(&self) -> HashMap<u64, u32> {
        self.node_ids
            .iter()
            .enumerate()
            .map(|(i, &id)| (id, i as u32))
            .collect()
    }

    /// Node set by name, ASCII case-insensitive (Abaqus names are case-insensitive).
    pub fn node_set(&self, name: &str) -> Option<&[u32]> {
        self.node_sets
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(name))
            .map(|(_, v)| v.as_slice())
    }

    /// Element set by name, ASCII case-insensitive.
    pub fn element_set(&self, name: &str) -> Option<&[u32]> {
        self.element_sets
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(name))
            .map(|(_, v)| v.as_slice())
    }

    /// The material name of each element, from the sections (`None` where no section covers
    /// the element). When sections overlap, the last one wins, as in Abaqus.
    pub fn element_materials(&self) -> Vec<Option<&str>> {
        let mut out = vec![None; self.elements.len()];
        for s in &self.sections {
            if let Some(set) = self.element_set(&s.element_set) {
                for &e in set {
                    out[e as usize] = Some(s.material.as_str());
                }
            }
        }
        out
    }

    /// Nodes used by at least one element.
    pub fn used_nodes(&self) -> Vec<bool> {
        let mut used = vec![false; self.nodes.len()];
        for el in &self.elements {
            for &n in el {
                used[n as usize] = true;
            }
        }
        used
    }

    /// Axis-aligned bounding box `(min, max)` of the nodes; `None` for an empty mesh.
    pub fn bounding_box(&self) -> Option<([f64; 3], [f64; 3])> {
        let first = *self.nodes.first()?;
        let mut lo = first;
        let mut hi = first;
        for p in &self.nodes {
            for d in 0..3 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
        Some((lo, hi))
    }

    /// Element coordinates in canonical order.
    pub fn element_coords(&self, e: usize) -> [[f64; 3]; 10] {
        let c = &self.elements[e];
        std::array::from_fn(|i| self.nodes[c[i] as usize])
    }
}
