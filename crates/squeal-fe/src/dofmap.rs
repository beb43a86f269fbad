//! Degrees of freedom: three per node, node-major (`global dof = 3 node + direction`), minus
//! restrained ones and those of nodes no element uses. The remaining ("free") dofs are numbered
//! in increasing global order, so the free numbering is node-major too.

use crate::error::FeError;
use squeal_mesh::Mesh;

/// Which nodes a restraint applies to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum NodeSelection {
    /// A node set of the mesh, by name (ASCII case-insensitive).
    Set(String),
    /// Node indices (not file ids).
    Indices(Vec<u32>),
}

impl NodeSelection {
    /// The selected node indices of `mesh`; a set the mesh does not have is
    /// [`FeError::UnknownNodeSet`].
    pub fn nodes<'a>(&'a self, mesh: &'a Mesh) -> Result<&'a [u32], FeError> {
        match self {
            NodeSelection::Set(name) => mesh
                .node_set(name)
                .ok_or_else(|| FeError::UnknownNodeSet(name.clone())),
            NodeSelection::Indices(ix) => Ok(ix),
        }
    }
}

/// Zero displacement in the chosen directions (`[x, y, z]`) at the chosen nodes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Restraint {
    pub nodes: NodeSelection,
    pub directions: [bool; 3],
}

impl Restraint {
    /// All three directions of a node set (a clamp).
    pub fn clamp(set: &str) -> Self {
        Self {
            nodes: NodeSelection::Set(set.to_string()),
            directions: [true; 3],
        }
    }

    /// Some directions of a node set (e.g. a pad's abutment in x and y: `[true, true, false]`).
    pub fn set(set: &str, directions: [bool; 3]) -> Self {
        Self {
            nodes: NodeSelection::Set(set.to_string()),
            directions,
        }
    }

    /// Some directions of nodes given by index.
    pub fn nodes(indices: Vec<u32>, directions: [bool; 3]) -> Self {
        Self {
            nodes: NodeSelection::Indices(indices),
            directions,
        }
    }
}

/// What became of a (node, direction).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DofStatus {
    /// A free dof, with its index.
    Free(usize),
    /// Restrained by a [`Restraint`].
    Restrained,
    /// The node is used by no element (or does not exist).
    Unused,
}

/// Used by an element and not restrained; replaced by the free dof's number at the end.
const PENDING: u32 = 0;
const RESTRAINED: u32 = u32::MAX;
const UNUSED: u32 = u32::MAX - 1;
/// Largest number of free dofs the compact `u32` table can hold.
const MAX_DOFS: usize = (u32::MAX - 2) as usize;

/// The map between free dofs and (node, direction), both ways.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DofMap {
    /// Per global dof `3 node + dir`: the free dof, or `RESTRAINED` / `UNUSED`.
    free_of_global: Vec<u32>,
    /// Per free dof: its global dof.
    global_of_free: Vec<usize>,
    /// File id of each node, for export.
    node_ids: Vec<u64>,
}

impl DofMap {
    /// Numbers the free dofs of `mesh` under `restraints`. Errors on an unknown node set, a
    /// node index out of range, or a mesh too large for the table.
    pub fn new(mesh: &Mesh, restraints: &[Restraint]) -> Result<Self, FeError> {
        let n = mesh.num_nodes();
        if n > MAX_DOFS / 3 {
            return Err(FeError::TooManyNodes {
                nodes: n,
                max: MAX_DOFS / 3,
            });
        }
        let mut state = vec![UNUSED; 3 * n];
        for (e, el) in mesh.blocks.iter().enumerate() {
            for &node in el {
                let i = node as usize;
                if i >= n {
                    return Err(FeError::BadConnectivity {
                        element: mesh.element_ids[e],
                        node,
                        num_nodes: n,
                    });
                }
                state[3 * i..3 * i + 3].fill(PENDING);
            }
        }
        for r in restraints {
            let nodes = r.nodes.nodes(mesh)?;
            for &node in nodes {
                let i = node as usize;
                if i >= n {
                    return Err(FeError::NodeOutOfRange {
                        index: node,
                        num_nodes: n,
                    });
                }
                for d in (0..3).filter(|&d| r.directions[d]) {
                    if state[3 * i + d] != UNUSED {
                        state[3 * i + d] = RESTRAINED;
                    }
                }
            }
        }
        let mut global_of_free = Vec::new();
        for (g, s) in state.iter_mut().enumerate() {
            if *s == PENDING {
                *s = global_of_free.len() as u32;
                global_of_free.push(g);
            }
        }
        Ok(Self {
            free_of_global: state,
            global_of_free,
            node_ids: mesh.node_ids.clone(),
        })
    }

    /// Number of free dofs.
    pub fn num_free(&self) -> usize {
        self.global_of_free.len()
    }

    /// Number of nodes of the mesh the map was built for.
    pub fn num_nodes(&self) -> usize {
        self.free_of_global.len() / 3
    }

    /// Number of restrained dofs (of nodes used by elements).
    pub fn num_restrained(&self) -> usize {
        self.free_of_global
            .iter()
            .filter(|&&s| s == RESTRAINED)
            .count()
    }

    /// Status of direction `dir` (0..3) of node index `node`.
    pub fn status(&self, node: u32, dir: usize) -> DofStatus {
        if dir >= 3 {
            return DofStatus::Unused;
        }
        match self.free_of_global.get(3 * node as usize + dir) {
            Some(&RESTRAINED) => DofStatus::Restrained,
            Some(&UNUSED) | None => DofStatus::Unused,
            Some(&f) => DofStatus::Free(f as usize),
        }
    }

    /// The free dof of `(node, dir)`, if it is free.
    pub fn free_dof(&self, node: u32, dir: usize) -> Option<usize> {
        match self.status(node, dir) {
            DofStatus::Free(f) => Some(f),
            _ => None,
        }
    }

    /// The `(node index, direction)` of a free dof.
    pub fn node_dir(&self, free: usize) -> Option<(u32, usize)> {
        let g = *self.global_of_free.get(free)?;
        Some(((g / 3) as u32, g % 3))
    }

    /// The file id of a node index.
    pub fn node_id(&self, node: u32) -> Option<u64> {
        self.node_ids.get(node as usize).copied()
    }

    /// Free dofs of a node's three directions.
    pub fn node_dofs(&self, node: u32) -> [Option<usize>; 3] {
        std::array::from_fn(|d| self.free_dof(node, d))
    }

    /// Scatters a free-dof vector into a per-node displacement field (zero where not free).
    pub fn expand(&self, free: &[f64]) -> Vec<[f64; 3]> {
        let mut out = vec![[0.0; 3]; self.num_nodes()];
        for (f, &g) in self.global_of_free.iter().enumerate() {
            out[g / 3][g % 3] = free.get(f).copied().unwrap_or(0.0);
        }
        out
    }

    /// Gathers the free dofs of a per-node field (the inverse of [`Self::expand`] on free
    /// dofs).
    pub fn restrict(&self, field: &[[f64; 3]]) -> Vec<f64> {
        self.global_of_free
            .iter()
            .map(|&g| field.get(g / 3).map_or(0.0, |u| u[g % 3]))
            .collect()
    }
}
