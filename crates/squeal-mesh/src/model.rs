//! The mesh: nodes, quadratic solid elements in one block per kind, named sets and materials.

use squeal_element::{ElementKind, Hex20, Pyramid13, ReferenceElement, Tet10, Wedge15};
use std::collections::{BTreeMap, HashMap};

/// A mesh of quadratic solid elements (10-node tetrahedra, 20-node hexahedra, 15-node
/// wedges, 13-node pyramids).
///
/// Nodes and elements are stored densely (index `0..n`); their ids in the source file, which
/// need be neither consecutive nor start at 1, are kept beside them. Elements are stored in
/// one block per kind ([`Blocks`]); an element's index runs over the blocks in the order
/// tet10, hex20, wedge15, pyramid13, so in a tet10 mesh it is the position in
/// `blocks.tet10`. Connectivity holds node *indices* in each kind's canonical ordering
/// ([`squeal_element::ReferenceElement`]; Abaqus C3D10 = VTK quadratic tetra for tet10),
/// whatever the file's own ordering was.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Coordinates of each node.
    pub nodes: Vec<[f64; 3]>,
    /// The file's id of each node.
    pub node_ids: Vec<u64>,
    /// Connectivity (node indices, canonical ordering) of the elements, by kind.
    pub blocks: Blocks,
    /// The file's id of each element, in element index order (block after block).
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

/// The elements of a mesh, one block per kind, in element index order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Blocks {
    /// 10-node tetrahedra (element indices `0..tet10.len()`).
    pub tet10: Vec<[u32; 10]>,
    /// 20-node hexahedra (next).
    pub hex20: Vec<[u32; 20]>,
    /// 15-node wedges (next).
    pub wedge15: Vec<[u32; 15]>,
    /// 13-node pyramids (last).
    pub pyramid13: Vec<[u32; 13]>,
}

/// Code run on each block with its element type: [`Blocks::visit`].
pub trait BlockVisitor {
    /// What stops the visit.
    type Error;
    /// Visits the block of element type `E`, whose first element has index `first`.
    fn block<E: ReferenceElement<N>, const N: usize>(
        &mut self,
        first: usize,
        conn: &[[u32; N]],
    ) -> Result<(), Self::Error>;
}

impl Blocks {
    /// Number of elements of all kinds.
    pub fn len(&self) -> usize {
        self.tet10.len() + self.hex20.len() + self.wedge15.len() + self.pyramid13.len()
    }

    /// Whether there is no element.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Number of elements of one kind.
    pub fn count(&self, kind: ElementKind) -> usize {
        match kind {
            ElementKind::Tet10 => self.tet10.len(),
            ElementKind::Hex20 => self.hex20.len(),
            ElementKind::Wedge15 => self.wedge15.len(),
            ElementKind::Pyramid13 => self.pyramid13.len(),
        }
    }

    /// Index of the first element of a kind (its block's offset).
    pub fn first(&self, kind: ElementKind) -> usize {
        ElementKind::ALL
            .iter()
            .take_while(|k| **k != kind)
            .map(|k| self.count(*k))
            .sum()
    }

    /// The kinds present, in block order, with their index ranges.
    pub fn kinds(&self) -> Vec<(ElementKind, std::ops::Range<usize>)> {
        let mut out = Vec::new();
        let mut start = 0;
        for kind in ElementKind::ALL {
            let n = self.count(kind);
            if n > 0 {
                out.push((kind, start..start + n));
            }
            start += n;
        }
        out
    }

    /// The kind of element `e` and its node indices; `None` past the last element.
    pub fn get(&self, e: usize) -> Option<(ElementKind, &[u32])> {
        let mut i = e;
        for kind in ElementKind::ALL {
            let n = self.count(kind);
            if i < n {
                let conn: &[u32] = match kind {
                    ElementKind::Tet10 => &self.tet10[i],
                    ElementKind::Hex20 => &self.hex20[i],
                    ElementKind::Wedge15 => &self.wedge15[i],
                    ElementKind::Pyramid13 => &self.pyramid13[i],
                };
                return Some((kind, conn));
            }
            i -= n;
        }
        None
    }

    /// The node indices of every element, in element index order.
    pub fn iter(&self) -> impl Iterator<Item = &[u32]> + '_ {
        self.tet10
            .iter()
            .map(|c| &c[..])
            .chain(self.hex20.iter().map(|c| &c[..]))
            .chain(self.wedge15.iter().map(|c| &c[..]))
            .chain(self.pyramid13.iter().map(|c| &c[..]))
    }

    /// Runs `visitor` on each block in order (empty blocks included), stopping at its
    /// first error. Code written once for any element type runs through this.
    pub fn visit<V: BlockVisitor>(&self, visitor: &mut V) -> Result<(), V::Error> {
        let mut first = 0;
        visitor.block::<Tet10, 10>(first, &self.tet10)?;
        first += self.tet10.len();
        visitor.block::<Hex20, 20>(first, &self.hex20)?;
        first += self.hex20.len();
        visitor.block::<Wedge15, 15>(first, &self.wedge15)?;
        first += self.wedge15.len();
        visitor.block::<Pyramid13, 13>(first, &self.pyramid13)
    }

    /// Appends an element of `kind` (node indices in canonical order); `false`, and nothing
    /// added, if `conn` has the wrong length for the kind.
    pub fn push(&mut self, kind: ElementKind, conn: &[u32]) -> bool {
        fn put<const N: usize>(block: &mut Vec<[u32; N]>, conn: &[u32]) -> bool {
            match <[u32; N]>::try_from(conn) {
                Ok(c) => {
                    block.push(c);
                    true
                }
                Err(_) => false,
            }
        }
        match kind {
            ElementKind::Tet10 => put(&mut self.tet10, conn),
            ElementKind::Hex20 => put(&mut self.hex20, conn),
            ElementKind::Wedge15 => put(&mut self.wedge15, conn),
            ElementKind::Pyramid13 => put(&mut self.pyramid13, conn),
        }
    }
}

/// Code that reads 10-node tetrahedra only, given a mesh with other elements.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "{reader} reads 10-node tetrahedra only; this mesh has {count} element(s) of another \
     kind, the first a {kind} (element {element}): not yet supported"
)]
pub struct NotTet10 {
    /// What needs tet10 elements ("the contact interface", "the picture", ...).
    pub reader: String,
    /// The first other kind present.
    pub kind: ElementKind,
    /// How many elements are not tet10.
    pub count: usize,
    /// The file id of the first of them.
    pub element: u64,
}

impl Mesh {
    /// Number of nodes (used by an element or not).
    pub fn num_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Number of elements of all kinds kept (those naming a missing node are not counted).
    pub fn num_elements(&self) -> usize {
        self.blocks.len()
    }

    /// The tet10 elements, for code that reads tet10 meshes only; a [`NotTet10`] error
    /// naming `reader` if the mesh has elements of another kind.
    pub fn only_tet10(&self, reader: &str) -> Result<&[[u32; 10]], NotTet10> {
        let t = self.blocks.tet10.len();
        match self
            .blocks
            .kinds()
            .into_iter()
            .find(|(k, _)| *k != ElementKind::Tet10)
        {
            None => Ok(&self.blocks.tet10),
            Some((kind, range)) => Err(NotTet10 {
                reader: reader.to_string(),
                kind,
                count: self.blocks.len() - t,
                element: self.element_ids.get(range.start).copied().unwrap_or(0),
            }),
        }
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
        let mut out = vec![None; self.num_elements()];
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
        for el in self.blocks.iter() {
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

    /// Coordinates of tet10 element `e`'s ten nodes in canonical order; panics if `e` is not
    /// below `blocks.tet10.len()` (tet10 elements come first, so `e` is also the element's
    /// index in the mesh).
    pub fn element_coords(&self, e: usize) -> [[f64; 3]; 10] {
        self.coords(&self.blocks.tet10[e])
    }

    /// Coordinates of the nodes of one element's connectivity, in its order; panics on a node
    /// index past the last node.
    pub fn coords<const N: usize>(&self, conn: &[u32; N]) -> [[f64; 3]; N] {
        std::array::from_fn(|i| self.nodes[conn[i] as usize])
    }
}
