//! Global assembly of the sparse stiffness `K` and consistent mass `M` over the free dofs.
//!
//! Both matrices are stored with both triangles (`SparseColMat<usize, f64>`, sorted row
//! indices). The sparsity pattern is built once from the connectivity: the node graph (nodes
//! sharing an element) expanded to free dofs; `K` couples every free direction of neighbouring
//! nodes, `M` (which is `m_ab I₃` per element) only equal directions. Values are then filled
//! element chunk by element chunk: element matrices in parallel, then each node's columns in
//! parallel, adding the contributions of the node's elements in ascending element order. Every
//! entry is therefore the same sum in the same order whatever the thread count, and `K`, `M`
//! are symmetric bit for bit. Memory is proportional to the number of nonzeros.
//!
//! The element matrices are computed block by block ([`squeal_mesh::Blocks::visit`]) by the
//! generic local assembly of [`crate::element`], sized per element type (`3N × 3N` and
//! `N × N`); blocks follow each other in element index order, so the sums are the same
//! whatever the mix of kinds.
//!
//! Each tet10 element's stiffness rule depends on its own coordinates only
//! ([`AssemblyOptions::stiffness_rule_for`]): the 4-point rule for straight-sided elements
//! (the same bits as before curved elements had their own rule), the 24-point rule for curved
//! ones (see [`crate::element`] for why and how accurate). The choice does not depend on the
//! thread count either. The other kinds use their own full rules
//! ([`squeal_element::ReferenceElement::stiffness_rule`], `mass_rule`), or the reduced one
//! where [`AssemblyOptions::reduced_integration`] asks for it.

use crate::dofmap::DofMap;
use crate::element::{ElementCoords, mass_scalar_of, stiffness_of, volume_of};
use crate::error::FeError;
use crate::material::MaterialTable;
use crate::quadrature::Quadrature;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use rayon::prelude::*;
use squeal_element::{ElementKind, ReferenceElement};
use squeal_mesh::{BlockVisitor, Mesh};

/// Quadrature rules used by [`assemble_with`], and which elements count as curved.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct AssemblyOptions {
    /// Stiffness rule of straight-sided elements. Default: [`Quadrature::four_point`], exact
    /// for them.
    pub stiffness_rule: Quadrature,
    /// Stiffness rule of curved elements, whose integrand is rational (see
    /// [`crate::element`]). Default: [`Quadrature::twenty_four_point`] (degree 6).
    pub curved_stiffness_rule: Quadrature,
    /// An element is curved when a midside node lies farther than this from its edge's
    /// midpoint, relative to the edge's length ([`squeal_mesh::tet10::midside_offset`]).
    /// Default: [`STRAIGHT_TOLERANCE`]. `f64::INFINITY` integrates every element with
    /// `stiffness_rule`.
    pub straight_tolerance: f64,
    /// Default: [`Quadrature::fourteen_point`], exact for straight-sided elements.
    pub mass_rule: Quadrature,
    /// Integrate the stiffness of the element kinds that have a reduced rule (the 20-node
    /// hexahedron's 2×2×2) with it. Default `false`: see [`squeal_element::hex20`] for its
    /// hourglass modes.
    pub reduced_integration: bool,
}

/// Default [`AssemblyOptions::straight_tolerance`]: 1e-8.
///
/// The 4-point rule's relative stiffness error on an element whose midside nodes are off by
/// `δ` (relative to the edge) is first order, `0.31 δ` on an element of the coarse disc
/// (`tests/fe/curved.rs`), so an element taken as straight at this tolerance is integrated to
/// about 3e-9, below the 24-point rule's error on the curved elements of the bundled meshes. Coordinates written with 16–17
/// significant digits put the midside nodes of straight elements 1e-17 to 1e-13 off (the
/// bundled meshes); a file written with 6 digits puts them up to ~1e-5 off, and its elements
/// are integrated as curved, which costs time, not accuracy.
pub const STRAIGHT_TOLERANCE: f64 = 1e-8;

impl Default for AssemblyOptions {
    fn default() -> Self {
        Self {
            stiffness_rule: Quadrature::four_point(),
            curved_stiffness_rule: Quadrature::twenty_four_point(),
            straight_tolerance: STRAIGHT_TOLERANCE,
            mass_rule: Quadrature::fourteen_point(),
            reduced_integration: false,
        }
    }
}

impl AssemblyOptions {
    /// The stiffness rule of the element with coordinates `x`: the curved rule when its
    /// midside offset exceeds the tolerance (or is not a number).
    pub fn stiffness_rule_for(&self, x: &ElementCoords) -> &Quadrature {
        let offset = squeal_mesh::tet10::midside_offset(x);
        if offset <= self.straight_tolerance {
            &self.stiffness_rule
        } else {
            &self.curved_stiffness_rule
        }
    }

    /// The stiffness and mass rules of the other element kinds: `None` for tet10 (whose
    /// rules are the fields above, chosen per element).
    fn rules_of<E: ReferenceElement<N>, const N: usize>(&self) -> Option<(Quadrature, Quadrature)> {
        if E::KIND == ElementKind::Tet10 {
            return None;
        }
        let reduced = self
            .reduced_integration
            .then(E::reduced_stiffness_rule)
            .flatten();
        Some((reduced.unwrap_or_else(E::stiffness_rule), E::mass_rule()))
    }
}

/// Stiffness (N/m) and mass (kg) over the free dofs of a [`DofMap`].
#[derive(Clone, Debug)]
pub struct System {
    pub k: SparseColMat<usize, f64>,
    pub m: SparseColMat<usize, f64>,
}

impl System {
    /// Number of free dofs (rows and columns of `k` and `m`).
    pub fn num_dofs(&self) -> usize {
        self.k.nrows()
    }

    /// Stored entries of `K` (both triangles).
    pub fn nnz_k(&self) -> usize {
        self.k.val().len()
    }

    /// Stored entries of `M` (both triangles).
    pub fn nnz_m(&self) -> usize {
        self.m.val().len()
    }
}

/// Elements processed per chunk: the element-matrix buffer (about 2 MB for tet10) stays in
/// cache while the chunk's nodes gather from it. The result does not depend on it.
const CHUNK: usize = 256;

/// [`assemble_with`] with the default rules.
pub fn assemble(
    mesh: &Mesh,
    materials: &MaterialTable,
    dofmap: &DofMap,
) -> Result<System, FeError> {
    assemble_with(mesh, materials, dofmap, &AssemblyOptions::default())
}

/// Assembles `K = Σ_e K_e` and `M = Σ_e M_e` over the free dofs of `dofmap` (restrained dofs
/// eliminated), in parallel on the current rayon pool, bit-for-bit identical for any number of
/// threads.
pub fn assemble_with(
    mesh: &Mesh,
    materials: &MaterialTable,
    dofmap: &DofMap,
    options: &AssemblyOptions,
) -> Result<System, FeError> {
    check_inputs(mesh, materials, dofmap)?;
    let graph = NodeGraph::new(mesh);
    let pattern = Pattern::new(&graph, dofmap);
    let (k_val, m_val) = fill_values(mesh, materials, dofmap, options, &graph, &pattern)?;
    let n = dofmap.num_free();
    let k_sym = SymbolicSparseColMat::new_checked(n, n, pattern.k_col_ptr, None, pattern.k_rows);
    let m_sym = SymbolicSparseColMat::new_checked(n, n, pattern.m_col_ptr, None, pattern.m_rows);
    Ok(System {
        k: SparseColMat::new(k_sym, k_val),
        m: SparseColMat::new(m_sym, m_val),
    })
}

/// The values of `K` and `M` in the layout of `pattern`: block by block and chunk by chunk,
/// the element matrices in parallel, then every node of the chunk adds them to its own
/// columns in parallel.
fn fill_values(
    mesh: &Mesh,
    materials: &MaterialTable,
    dofmap: &DofMap,
    options: &AssemblyOptions,
    graph: &NodeGraph,
    pattern: &Pattern,
) -> Result<(Vec<f64>, Vec<f64>), FeError> {
    let mut k_val = vec![0.0; pattern.k_rows.len()];
    let mut m_val = vec![0.0; pattern.m_rows.len()];
    let k_start: Vec<usize> = pattern.layout.iter().map(|l| l.k_start).collect();
    let m_start: Vec<usize> = pattern.layout.iter().map(|l| l.m_start).collect();
    let mut filler = Filler {
        mesh,
        materials,
        dofmap,
        options,
        graph,
        pattern,
        k_slices: split_by_start(&mut k_val, &k_start),
        m_slices: split_by_start(&mut m_val, &m_start),
        cursor: vec![0usize; mesh.num_nodes()],
    };
    mesh.blocks.visit(&mut filler)?;
    drop(filler);
    Ok((k_val, m_val))
}

/// The state of [`fill_values`] carried from block to block.
struct Filler<'a, 'v> {
    mesh: &'a Mesh,
    materials: &'a MaterialTable,
    dofmap: &'a DofMap,
    options: &'a AssemblyOptions,
    graph: &'a NodeGraph,
    pattern: &'a Pattern,
    k_slices: Vec<&'v mut [f64]>,
    m_slices: Vec<&'v mut [f64]>,
    /// Per node, the position in its incidence list reached so far.
    cursor: Vec<usize>,
}

impl BlockVisitor for Filler<'_, '_> {
    type Error = FeError;

    fn block<E: ReferenceElement<N>, const N: usize>(
        &mut self,
        first: usize,
        conn: &[[u32; N]],
    ) -> Result<(), FeError> {
        if conn.is_empty() {
            return Ok(());
        }
        let rules = self.options.rules_of::<E, N>();
        let (kn, mn) = (9 * N * N, N * N);
        let chunk = CHUNK.min(conn.len());
        let mut k_buf = vec![0.0; chunk * kn];
        let mut m_buf = vec![0.0; chunk * mn];
        for c0 in (0..conn.len()).step_by(CHUNK) {
            let c1 = (c0 + CHUNK).min(conn.len());
            let statuses: Vec<Result<(), FeError>> = k_buf[..(c1 - c0) * kn]
                .par_chunks_mut(kn)
                .zip(m_buf[..(c1 - c0) * mn].par_chunks_mut(mn))
                .enumerate()
                .map(|(i, (ke, me))| {
                    let e = c0 + i;
                    element_matrices::<E, N>(self, rules.as_ref(), &conn[e], first + e, ke, me)
                })
                .collect();
            // The first error in element order.
            statuses.into_iter().collect::<Result<(), FeError>>()?;
            let ctx = ScatterContext {
                dofmap: self.dofmap,
                graph: self.graph,
                pattern: self.pattern,
                conn: &conn[c0..c1],
                k_buf: &k_buf,
                m_buf: &m_buf,
            };
            // Only the nodes of this chunk's elements have anything to add.
            let (lo, hi) = node_range(&conn[c0..c1]);
            self.k_slices[lo..hi]
                .par_iter_mut()
                .zip(self.m_slices[lo..hi].par_iter_mut())
                .zip(self.cursor[lo..hi].par_iter_mut())
                .enumerate()
                .for_each(|(i, ((ks, ms), cur))| {
                    ctx.scatter_node(lo + i, first + c0, first + c1, cur, ks, ms)
                });
        }
        Ok(())
    }
}

/// The range `lo..hi` of node indices used by `elements`.
fn node_range<const N: usize>(elements: &[[u32; N]]) -> (usize, usize) {
    let nodes = elements.iter().flatten().map(|&v| v as usize);
    let lo = nodes.clone().min().unwrap_or(0);
    let hi = nodes.max().map_or(0, |v| v + 1);
    (lo, hi)
}

fn check_inputs(mesh: &Mesh, materials: &MaterialTable, dofmap: &DofMap) -> Result<(), FeError> {
    check_materials(mesh, materials)?;
    if dofmap.num_nodes() != mesh.num_nodes() {
        return Err(FeError::DofMapMismatch {
            map: dofmap.num_nodes(),
            mesh: mesh.num_nodes(),
        });
    }
    let n = mesh.num_nodes();
    for (e, el) in mesh.blocks.iter().enumerate() {
        if let Some(&node) = el.iter().find(|&&v| v as usize >= n) {
            return Err(FeError::BadConnectivity {
                element: mesh.element_ids[e],
                node,
                num_nodes: n,
            });
        }
    }
    Ok(())
}

/// The table has one valid entry index per element.
fn check_materials(mesh: &Mesh, materials: &MaterialTable) -> Result<(), FeError> {
    if materials.element_entry.len() != mesh.num_elements() {
        return Err(FeError::TableMismatch {
            table: materials.element_entry.len(),
            mesh: mesh.num_elements(),
        });
    }
    let entries = materials.entries.len();
    match materials
        .element_entry
        .iter()
        .position(|&i| i as usize >= entries)
    {
        Some(e) => Err(FeError::MaterialIndex {
            element: mesh.element_ids[e],
            index: materials.element_entry[e],
            entries,
        }),
        None => Ok(()),
    }
}

/// Stiffness and scalar mass of element `e` (nodes `conn`) into the buffers; `rules` are
/// the element kind's (`None` for tet10, whose rules are chosen per element).
fn element_matrices<E: ReferenceElement<N>, const N: usize>(
    f: &Filler<'_, '_>,
    rules: Option<&(Quadrature, Quadrature)>,
    conn: &[u32; N],
    e: usize,
    ke: &mut [f64],
    me: &mut [f64],
) -> Result<(), FeError> {
    let x = f.mesh.coords(conn);
    let entry = &f.materials.entries[f.materials.element_entry[e] as usize];
    let wrap = FeError::in_element(f.mesh.element_ids[e]);
    let (k_rule, m_rule) = match rules {
        Some((k, m)) => (k, m),
        None => {
            let tet: [[f64; 3]; 10] = std::array::from_fn(|i| x[i]);
            (f.options.stiffness_rule_for(&tet), &f.options.mass_rule)
        }
    };
    stiffness_of::<E, N>(&x, &entry.elasticity, k_rule, ke).map_err(wrap)?;
    mass_scalar_of::<E, N>(&x, entry.material.density(), m_rule, me).map_err(wrap)?;
    Ok(())
}

/// Node-to-element incidence and node-to-node adjacency, as compressed lists (ascending).
struct NodeGraph {
    elem_ptr: Vec<usize>,
    elems: Vec<u32>,
    nbr_ptr: Vec<usize>,
    nbrs: Vec<u32>,
}

impl NodeGraph {
    fn new(mesh: &Mesh) -> Self {
        let n = mesh.num_nodes();
        // Counting sort of (node, element) pairs by node; elements stay ascending.
        let mut elem_ptr = vec![0usize; n + 1];
        for el in mesh.blocks.iter() {
            for (a, &v) in el.iter().enumerate() {
                if !el[..a].contains(&v) {
                    elem_ptr[v as usize + 1] += 1;
                }
            }
        }
        for i in 0..n {
            elem_ptr[i + 1] += elem_ptr[i];
        }
        let mut fill = elem_ptr.clone();
        let mut elems = vec![0u32; elem_ptr[n]];
        for (e, el) in mesh.blocks.iter().enumerate() {
            for (a, &v) in el.iter().enumerate() {
                if !el[..a].contains(&v) {
                    elems[fill[v as usize]] = e as u32;
                    fill[v as usize] += 1;
                }
            }
        }
        let lists: Vec<Vec<u32>> = (0..n)
            .into_par_iter()
            .map(|node| {
                let mut v: Vec<u32> = elems[elem_ptr[node]..elem_ptr[node + 1]]
                    .iter()
                    .flat_map(|&e| mesh.blocks.get(e as usize).map_or(&[][..], |(_, c)| c))
                    .copied()
                    .collect();
                v.sort_unstable();
                v.dedup();
                v
            })
            .collect();
        let mut nbr_ptr = Vec::with_capacity(n + 1);
        nbr_ptr.push(0);
        for l in &lists {
            nbr_ptr.push(nbr_ptr[nbr_ptr.len() - 1] + l.len());
        }
        let nbrs = lists.concat();
        Self {
            elem_ptr,
            elems,
            nbr_ptr,
            nbrs,
        }
    }

    fn incident(&self, node: usize) -> &[u32] {
        &self.elems[self.elem_ptr[node]..self.elem_ptr[node + 1]]
    }

    fn neighbors(&self, node: usize) -> &[u32] {
        &self.nbrs[self.nbr_ptr[node]..self.nbr_ptr[node + 1]]
    }
}

/// Where a node's columns live in the value arrays.
#[derive(Clone, Copy, Debug, Default)]
struct NodeLayout {
    /// Offset of the node's first `K` column.
    k_start: usize,
    /// Rows per `K` column (the same for the node's free directions).
    k_count: usize,
    /// Offset of the node's first `M` column.
    m_start: usize,
    /// Rows of the `M` column of each direction (0 if the direction is not free).
    m_count: [usize; 3],
    /// The node and all its neighbours have their three directions free, so the rows of the
    /// `j`-th neighbour sit at `3 j .. 3 j + 3` in each `K` column and at `j` in each `M` column.
    regular: bool,
}

/// Column pointers and row indices of `K` and `M`, with per-node layout.
struct Pattern {
    layout: Vec<NodeLayout>,
    k_col_ptr: Vec<usize>,
    k_rows: Vec<usize>,
    m_col_ptr: Vec<usize>,
    m_rows: Vec<usize>,
}

impl Pattern {
    fn new(graph: &NodeGraph, dofmap: &DofMap) -> Self {
        let n = dofmap.num_nodes();
        let free: Vec<[Option<usize>; 3]> = (0..n as u32).map(|v| dofmap.node_dofs(v)).collect();
        let nfree = |v: usize| free[v].iter().flatten().count();
        let mut layout = vec![NodeLayout::default(); n];
        let mut k_col_ptr = vec![0usize];
        let mut m_col_ptr = vec![0usize];
        let (mut k_off, mut m_off) = (0usize, 0usize);
        for (v, lay) in layout.iter_mut().enumerate() {
            let nbrs = graph.neighbors(v);
            lay.k_start = k_off;
            lay.m_start = m_off;
            if nfree(v) == 0 {
                continue;
            }
            lay.k_count = nbrs.iter().map(|&w| nfree(w as usize)).sum();
            lay.regular = lay.k_count == 3 * nbrs.len() && nfree(v) == 3;
            for d in (0..3).filter(|&d| free[v][d].is_some()) {
                lay.m_count[d] = nbrs
                    .iter()
                    .filter(|&&w| free[w as usize][d].is_some())
                    .count();
                k_off += lay.k_count;
                m_off += lay.m_count[d];
                k_col_ptr.push(k_off);
                m_col_ptr.push(m_off);
            }
        }
        let mut k_rows = vec![0usize; k_off];
        let mut m_rows = vec![0usize; m_off];
        {
            let k_start: Vec<usize> = layout.iter().map(|l| l.k_start).collect();
            let m_start: Vec<usize> = layout.iter().map(|l| l.m_start).collect();
            let mut k_slices = split_by_start(&mut k_rows, &k_start);
            let mut m_slices = split_by_start(&mut m_rows, &m_start);
            k_slices
                .par_iter_mut()
                .zip(m_slices.par_iter_mut())
                .enumerate()
                .for_each(|(v, (ks, ms))| {
                    let nbrs = graph.neighbors(v);
                    let mut ki = 0;
                    let mut mi = 0;
                    for d in (0..3).filter(|&d| free[v][d].is_some()) {
                        for &w in nbrs {
                            for r in free[w as usize].iter().flatten() {
                                ks[ki] = *r;
                                ki += 1;
                            }
                            if let Some(r) = free[w as usize][d] {
                                ms[mi] = r;
                                mi += 1;
                            }
                        }
                    }
                });
        }
        Self {
            layout,
            k_col_ptr,
            k_rows,
            m_col_ptr,
            m_rows,
        }
    }
}

/// Splits `data` into one slice per node: node `i` gets `start[i]..start[i + 1]` (the last
/// node runs to the end).
fn split_by_start<'a, T>(mut data: &'a mut [T], start: &[usize]) -> Vec<&'a mut [T]> {
    let mut out = Vec::with_capacity(start.len());
    for i in 0..start.len() {
        let end = start.get(i + 1).copied().unwrap_or(start[i] + data.len());
        let (head, tail) = std::mem::take(&mut data).split_at_mut(end - start[i]);
        out.push(head);
        data = tail;
    }
    out
}

/// What a node needs to add its elements' contributions to its own columns: the chunk's
/// connectivity and element matrices (row-major `3N × 3N` and `N × N`, one after the other).
struct ScatterContext<'a, const N: usize> {
    dofmap: &'a DofMap,
    graph: &'a NodeGraph,
    pattern: &'a Pattern,
    conn: &'a [[u32; N]],
    k_buf: &'a [f64],
    m_buf: &'a [f64],
}

impl<const N: usize> ScatterContext<'_, N> {
    /// Adds, in ascending element order, the contributions of the node's elements in
    /// `c0..c1` (element indices of the chunk) to the node's columns `ks` (of `K`) and `ms`
    /// (of `M`). `cursor` is the position in the node's incidence list reached so far.
    fn scatter_node(
        &self,
        node: usize,
        c0: usize,
        c1: usize,
        cursor: &mut usize,
        ks: &mut [f64],
        ms: &mut [f64],
    ) {
        let incident = self.graph.incident(node);
        let (kn, mn) = (9 * N * N, N * N);
        while let Some(&e) = incident.get(*cursor) {
            let e = e as usize;
            if e >= c1 {
                break;
            }
            *cursor += 1;
            if !ks.is_empty() {
                let i = e - c0;
                let ke = &self.k_buf[i * kn..(i + 1) * kn];
                let me = &self.m_buf[i * mn..(i + 1) * mn];
                self.scatter_element(node, &self.conn[i], ke, me, ks, ms);
            }
        }
    }

    fn scatter_element(
        &self,
        node: usize,
        conn: &[u32; N],
        ke: &[f64],
        me: &[f64],
        ks: &mut [f64],
        ms: &mut [f64],
    ) {
        let Some(a) = conn.iter().position(|&v| v as usize == node) else {
            return;
        };
        let n3 = 3 * N;
        let lay = &self.pattern.layout[node];
        // Element matrices are symmetric bit for bit: row `3a + d` is column `3a + d`.
        if lay.regular {
            let nbrs = self.graph.neighbors(node);
            let n = nbrs.len();
            for (b, &other) in conn.iter().enumerate() {
                let j = nbrs.partition_point(|&w| w < other);
                for d in 0..3 {
                    let start = (3 * a + d) * n3 + 3 * b;
                    let row = &ke[start..start + 3];
                    let base = d * lay.k_count + 3 * j;
                    for (t, v) in row.iter().enumerate() {
                        ks[base + t] += v;
                    }
                    ms[d * n + j] += me[a * N + b];
                }
            }
            return;
        }
        let dofs_n = self.dofmap.node_dofs(node as u32);
        let k_rows = &self.pattern.k_rows[lay.k_start..lay.k_start + lay.k_count];
        for (b, &other) in conn.iter().enumerate() {
            let dofs_m = self.dofmap.node_dofs(other);
            let Some(first) = dofs_m.iter().flatten().next() else {
                continue;
            };
            // The rows of `other` are consecutive in every column of `node`.
            let o = k_rows.partition_point(|&r| r < *first);
            let mut m_col_start = 0;
            for (col, d) in (0..3).filter(|&d| dofs_n[d].is_some()).enumerate() {
                let base = col * lay.k_count + o;
                for (j, d2) in (0..3).filter(|&d2| dofs_m[d2].is_some()).enumerate() {
                    ks[base + j] += ke[(3 * a + d) * n3 + 3 * b + d2];
                }
                if let Some(r) = dofs_m[d] {
                    let s = lay.m_start + m_col_start;
                    let pos =
                        self.pattern.m_rows[s..s + lay.m_count[d]].partition_point(|&x| x < r);
                    ms[m_col_start + pos] += me[a * N + b];
                }
                m_col_start += lay.m_count[d];
            }
        }
    }
}

/// Per element, `f(e, volume)` in element order, each with the element kind's own volume
/// `Σ_q w_q det J_q`: tet10 with `tet10_rule`, the others with their mass rules (exact for
/// elements with straight edges).
struct Volumes<'a, F> {
    mesh: &'a Mesh,
    tet10_rule: &'a Quadrature,
    f: F,
}

impl<F: FnMut(usize, f64)> BlockVisitor for Volumes<'_, F> {
    type Error = FeError;

    fn block<E: ReferenceElement<N>, const N: usize>(
        &mut self,
        first: usize,
        conn: &[[u32; N]],
    ) -> Result<(), FeError> {
        let own = E::mass_rule();
        let rule = if E::KIND == ElementKind::Tet10 {
            self.tet10_rule
        } else {
            &own
        };
        for (i, c) in conn.iter().enumerate() {
            let e = first + i;
            let v = volume_of::<E, N>(&self.mesh.coords(c), rule)
                .map_err(FeError::in_element(self.mesh.element_ids[e]))?;
            (self.f)(e, v);
        }
        Ok(())
    }
}

/// Volume of the mesh, `Σ_e ∫ det J` with `rule` for tet10 elements and each other kind's
/// mass rule (summed in element order).
pub fn mesh_volume(mesh: &Mesh, rule: &Quadrature) -> Result<f64, FeError> {
    let mut v = 0.0;
    mesh.blocks.visit(&mut Volumes {
        mesh,
        tet10_rule: rule,
        f: |_, ve| v += ve,
    })?;
    Ok(v)
}

/// Total mass `Σ_e ρ_e V_e` (kg) including restrained nodes' share, summed in element order.
pub fn total_mass(
    mesh: &Mesh,
    materials: &MaterialTable,
    rule: &Quadrature,
) -> Result<f64, FeError> {
    check_materials(mesh, materials)?;
    let mut m = 0.0;
    mesh.blocks.visit(&mut Volumes {
        mesh,
        tet10_rule: rule,
        f: |e, v| {
            let rho = materials.entries[materials.element_entry[e] as usize]
                .material
                .density();
            m += rho * v;
        },
    })?;
    Ok(m)
}

/// Cheap figures for the CLI to print.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    pub nodes: usize,
    pub elements: usize,
    pub free_dofs: usize,
    pub restrained_dofs: usize,
    pub nnz_k: usize,
    pub nnz_m: usize,
    /// m³
    pub volume: f64,
    /// kg
    pub mass: f64,
}

impl Summary {
    pub fn new(
        mesh: &Mesh,
        materials: &MaterialTable,
        dofmap: &DofMap,
        system: &System,
    ) -> Result<Self, FeError> {
        // Degree 5: exact for det J, which is cubic on curved elements.
        let rule = Quadrature::fourteen_point();
        Ok(Self {
            nodes: mesh.num_nodes(),
            elements: mesh.num_elements(),
            free_dofs: dofmap.num_free(),
            restrained_dofs: dofmap.num_restrained(),
            nnz_k: system.nnz_k(),
            nnz_m: system.nnz_m(),
            volume: mesh_volume(mesh, &rule)?,
            mass: total_mass(mesh, materials, &rule)?,
        })
    }
}

impl std::fmt::Display for Summary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} nodes, {} elements, {} free dofs ({} restrained), K {} nonzeros, M {} nonzeros, \
             volume {:.6e} m^3, mass {:.6e} kg",
            self.nodes,
            self.elements,
            self.free_dofs,
            self.restrained_dofs,
            self.nnz_k,
            self.nnz_m,
            self.volume,
            self.mass
        )
    }
}
