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
    Isotropic {
        /// Young's modulus E (Pa).
        young: f64,
        /// Poisson's ratio ν (dimensionless).
        poisson: f64,
    },
    /// Abaqus `TYPE=ENGINEERING CONSTANTS` in the global axes: E1, E2, E3, nu12, nu13, nu23,
    /// G12, G13, G23.
    EngineeringConstants {
        /// Young's moduli `[E1, E2, E3]` along the global axes (Pa).
        e: [f64; 3],
        /// Poisson's ratios `[ν12, ν13, ν23]` (dimensionless).
        nu: [f64; 3],
        /// Shear moduli `[G12, G13, G23]` (Pa).
        g: [f64; 3],
    },
}

/// A material: elastic constants and density (kg/m^3), each present if the file gives it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Material {
    /// The elastic constants (`*ELASTIC`), `None` if the file gives none.
    pub elastic: Option<Elastic>,
    /// The mass density (kg/m^3) from `*DENSITY`, `None` if the file gives none.
    pub density: Option<f64>,
}

/// An element set made of a material.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Section {
    /// Name of the element set (a key of [`Mesh::element_sets`], matched ASCII
    /// case-insensitively by [`Mesh::element_set`]).
    pub element_set: String,
    /// Name of the material (a key of [`Mesh::materials`], which may lack it: the file named a
    /// material it never defined).
    pub material: String,
}

/// A reference to an id that does not exist in the file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Dangling {
    /// An element names a node that was never defined; the element is dropped.
    ElementNode {
        /// File id of the dropped element.
        element: u64,
        /// File id of the node it names.
        node: u64,
    },
    /// A node set names a node that was never defined; the member is dropped.
    NodeSetMember {
        /// Name of the node set.
        set: String,
        /// File id of the missing node.
        node: u64,
    },
    /// An element set names an element that was never defined; the member is dropped.
    ElementSetMember {
        /// Name of the element set.
        set: String,
        /// File id of the missing element.
        element: u64,
    },
}

impl Mesh {
    /// Number of nodes (used by an element or not).
    pub fn num_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Number of tet10 elements kept (those naming a missing node are not counted).
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

    /// For each node index, whether at least one element uses it.
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

    /// Coordinates of element `e`'s ten nodes in canonical order; panics if `e` is not below
    /// [`Mesh::num_elements`].
    pub fn element_coords(&self, e: usize) -> [[f64; 3]; 10] {
        let c = &self.elements[e];
        std::array::from_fn(|i| self.nodes[c[i] as usize])
    }
}
