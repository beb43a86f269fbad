//! Restraints along directions that are not coordinate axes: a pad held radially and
//! tangentially about a disc axis that is not a coordinate axis, a node held only along a
//! surface normal. Abaqus writes them as a boundary condition in a `*TRANSFORM` system, Ansys
//! as a `D` on a rotated node; here as the same thing.
//!
//! Each node with a skew restraint gets its own orthonormal axes `R` (rows `e_1, e_2, e_3`),
//! the first `k` spanning the restrained directions; its displacement is `u = Σ_j q_j e_j` and
//! the restrained `q_1..q_k` are dropped. With `T` the map from the kept coordinates to the
//! free dofs of an ordinary [`DofMap`] (identity on every other node), the held system is
//! `K' = Tᵀ K T`, `M' = Tᵀ M T`: exact, not a penalty. A node whose restrained directions are
//! coordinate axes (to 1e-12), or all three directions, is restrained by deleting its dofs as
//! usual ([`Restraint`]), so a restraint that happens to be axis-aligned gives the bits of the
//! plain path.
//!
//! The directions a brake is held and slides in come from its rotation axis
//! ([`RotationAxis`]): axial, radial and tangential at each point, the tangential one being the
//! direction the disc's surface moves in there (the convention of Abaqus' `*MOTION` and
//! Ansys' `CMROTATE`), so nothing assumes the disc turns about z or through the origin.

use crate::assembly::System;
use crate::dofmap::{DofMap, Restraint};
use crate::error::FeError;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Mat, MatRef};
use squeal_element::geometry::{cross, dot, unit};
use squeal_mesh::Mesh;
use std::collections::BTreeMap;

/// Zero displacement of node `node` (index) along `direction` (need not be unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkewRestraint {
    /// Node index.
    pub node: u32,
    /// The restrained direction.
    pub direction: [f64; 3],
}

/// A node's own axes: rows `e_1..e_3`, the first `held` restrained.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeFrame {
    /// Orthonormal rows.
    pub axes: [[f64; 3]; 3],
    /// How many of the first axes are restrained (0 to 2; 0: a node that keeps all three
    /// motions, in axes of its own, e.g. a piston node whose first axis is a skew normal).
    pub held: usize,
}

/// How every node is held: restraints by deletion (on coordinate axes), and the nodes that
/// need their own axes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HeldNodes {
    /// Restraints to give [`DofMap::new`]: the caller's, plus the skew restraints that turned
    /// out to be along coordinate axes.
    pub restraints: Vec<Restraint>,
    /// Nodes with their own axes, by node index.
    pub frames: BTreeMap<u32, NodeFrame>,
}

/// Relative tolerance under which a direction counts as a coordinate axis, and a direction
/// as already spanned by the others.
const AXIS_TOLERANCE: f64 = 1e-12;
const RANK_TOLERANCE: f64 = 1e-9;

/// The coordinate axis `a` is along (to [`AXIS_TOLERANCE`]), if any.
fn coordinate_axis(a: [f64; 3]) -> Option<usize> {
    (0..3).find(|&d| (0..3).all(|e| e == d || a[e].abs() <= AXIS_TOLERANCE))
}

impl HeldNodes {
    /// Sorts the restraints: every node keeps the caller's `restraints`; a node with skew
    /// restraints gets the span of its directions (with the coordinate directions the caller's
    /// restraints hold it in) as deleted dofs when that span is coordinate axes or everything,
    /// else as a [`NodeFrame`].
    pub fn new(
        mesh: &Mesh,
        restraints: &[Restraint],
        skew: &[SkewRestraint],
    ) -> Result<Self, FeError> {
        let mut by_node: BTreeMap<u32, Vec<[f64; 3]>> = BTreeMap::new();
        for s in skew {
            if s.node as usize >= mesh.num_nodes() {
                return Err(FeError::NodeOutOfRange {
                    index: s.node,
                    num_nodes: mesh.num_nodes(),
                });
            }
            let d = unit(s.direction).ok_or(FeError::BadDirection { node: s.node })?;
            by_node.entry(s.node).or_default().push(d);
        }
        // The coordinate directions the caller's restraints already hold each such node in.
        let mut global_dirs: BTreeMap<u32, [bool; 3]> = BTreeMap::new();
        for r in restraints {
            let nodes = r.nodes.nodes(mesh)?;
            for n in nodes {
                if by_node.contains_key(n) {
                    let g = global_dirs.entry(*n).or_default();
                    for d in 0..3 {
                        g[d] |= r.directions[d];
                    }
                }
            }
        }
        let mut out = HeldNodes {
            restraints: restraints.to_vec(),
            frames: BTreeMap::new(),
        };
        let mut by_axes: BTreeMap<[bool; 3], Vec<u32>> = BTreeMap::new();
        for (node, dirs) in by_node {
            // Gram-Schmidt: the coordinate directions first (exact unit vectors), then the
            // skew ones; a direction inside the span of those before it adds nothing.
            let held = global_dirs.get(&node).copied().unwrap_or_default();
            let mut basis: Vec<[f64; 3]> = (0..3)
                .filter(|&d| held[d])
                .map(|d| {
                    let mut e = [0.0; 3];
                    e[d] = 1.0;
                    e
                })
                .collect();
            for d in dirs {
                let mut v = d;
                for b in &basis {
                    let c = dot(v, *b);
                    for i in 0..3 {
                        v[i] -= c * b[i];
                    }
                }
                if dot(v, v).sqrt() > RANK_TOLERANCE
                    && let Some(u) = unit(v)
                {
                    basis.push(u);
                }
            }
            let axes: Option<Vec<usize>> = basis.iter().map(|b| coordinate_axis(*b)).collect();
            match (basis.len(), axes) {
                (3, _) => by_axes.entry([true; 3]).or_default().push(node),
                (_, Some(axes)) => {
                    let mut mask = [false; 3];
                    for a in axes {
                        mask[a] = true;
                    }
                    by_axes.entry(mask).or_default().push(node);
                }
                (k, None) => {
                    let axes = complete(&basis);
                    out.frames.insert(node, NodeFrame { axes, held: k });
                }
            }
        }
        for (mask, nodes) in by_axes {
            out.restraints.push(Restraint::nodes(nodes, mask));
        }
        Ok(out)
    }

    /// Whether any node has its own axes (else [`Self::restraints`] is all there is).
    pub fn has_frames(&self) -> bool {
        !self.frames.is_empty()
    }
}

/// A right-handed orthonormal basis `[e1, e2, e3]` with `e1` the unit `a` (e.g. an axis, `e2`
/// and `e3` spanning the plane normal to it); for a coordinate axis, `e2` and `e3` are
/// coordinate axes exactly.
pub fn orthonormal_completion(a: [f64; 3]) -> [[f64; 3]; 3] {
    complete(&[a])
}

/// An orthonormal basis whose first vectors are `basis` (one or two orthonormal vectors).
fn complete(basis: &[[f64; 3]]) -> [[f64; 3]; 3] {
    let e1 = basis[0];
    let e2 = match basis.get(1) {
        Some(&e2) => e2,
        None => {
            // The coordinate axis least along e1, made orthogonal to it.
            let k = (0..3)
                .min_by(|&a, &b| e1[a].abs().total_cmp(&e1[b].abs()))
                .unwrap_or(0);
            let mut a = [0.0; 3];
            a[k] = 1.0;
            let c = dot(a, e1);
            unit([a[0] - c * e1[0], a[1] - c * e1[1], a[2] - c * e1[2]]).unwrap_or(a)
        }
    };
    let e3 = cross(e1, e2);
    [e1, e2, e3]
}

/// The map from the kept coordinates (the "new" free dofs) to the free dofs of a [`DofMap`]
/// built with [`HeldNodes::restraints`].
#[derive(Clone, Debug)]
pub struct DofTransform {
    /// For every old free dof: its new dof (nodes without a frame), or `None`.
    new_of_old: Vec<Option<usize>>,
    /// Old free dof of each direction of each framed node, and the new dof and axis of each
    /// kept coordinate.
    framed: BTreeMap<u32, FramedNode>,
    /// Tied (slave) nodes: their old free dofs and, per direction, the kept coordinates
    /// their motion is made of ([`DofTransform::with_ties`]).
    slaves: BTreeMap<u32, SlaveNode>,
    num_new: usize,
}

#[derive(Clone, Debug)]
struct SlaveNode {
    old: [Option<usize>; 3],
    /// Per direction: `(new dof, weight)`.
    rows: [Vec<(usize, f64)>; 3],
}

#[derive(Clone, Debug)]
struct FramedNode {
    old: [Option<usize>; 3],
    /// `(new dof, axis e_j)` of the kept coordinates.
    kept: Vec<(usize, [f64; 3])>,
}

impl DofTransform {
    /// The transform of `dofmap` (built with `held.restraints`) under `held.frames`.
    pub fn new(dofmap: &DofMap, held: &HeldNodes) -> Self {
        Self::with_ties(dofmap, held, &BTreeMap::new())
    }

    /// The transform of `dofmap` under `held.frames` and the multi-point constraints `ties`:
    /// each tied (slave) node moves as `u_s = Σ_i w_i u_i` of its master nodes `(i, w_i)`
    /// (a tie's shape-function weights at the slave's projection), direction by direction,
    /// and keeps no coordinate of its own. A master's restrained direction contributes
    /// nothing (it does not move); a master in its own axes contributes its kept coordinates.
    /// Masters must not be slaves themselves and slaves must have no frame (the caller checks
    /// both). `Tᵀ K T` is then the exact stiffness of the tied parts (the constraints
    /// eliminated, not penalised).
    pub fn with_ties(
        dofmap: &DofMap,
        held: &HeldNodes,
        ties: &BTreeMap<u32, Vec<(u32, f64)>>,
    ) -> Self {
        let n_old = dofmap.num_free();
        let mut new_of_old = vec![None; n_old];
        let mut framed: BTreeMap<u32, FramedNode> = BTreeMap::new();
        let mut next = 0;
        for f in 0..n_old {
            let Some((node, dir)) = dofmap.node_dir(f) else {
                continue;
            };
            if ties.contains_key(&node) {
                continue;
            }
            match held.frames.get(&node) {
                None => {
                    new_of_old[f] = Some(next);
                    next += 1;
                }
                Some(frame) => {
                    let entry = framed.entry(node).or_insert_with(|| {
                        let kept = (frame.held..3)
                            .map(|j| {
                                next += 1;
                                (next - 1, frame.axes[j])
                            })
                            .collect();
                        FramedNode {
                            old: [None; 3],
                            kept,
                        }
                    });
                    entry.old[dir] = Some(f);
                }
            }
        }
        let mut t = Self {
            new_of_old,
            framed,
            slaves: BTreeMap::new(),
            num_new: next,
        };
        let mut slaves = BTreeMap::new();
        let mut row = Vec::new();
        for (&node, masters) in ties {
            let old = dofmap.node_dofs(node);
            let rows = std::array::from_fn(|dir| {
                let mut out: Vec<(usize, f64)> = Vec::new();
                for &(m, w) in masters {
                    let Some(mo) = dofmap.free_dof(m, dir) else {
                        continue;
                    };
                    t.row(mo, Some((m, dir)), &mut row);
                    out.extend(row.iter().map(|&(n, v)| (n, w * v)));
                }
                out
            });
            slaves.insert(node, SlaveNode { old, rows });
        }
        t.slaves = slaves;
        t
    }

    /// Number of kept coordinates (rows and columns of the held system).
    pub fn num_free(&self) -> usize {
        self.num_new
    }

    /// The kept coordinates of a node with its own axes: `(new dof, axis e_j)` for each
    /// kept axis; `None` for a node without a frame.
    pub fn kept(&self, node: u32) -> Option<&[(usize, [f64; 3])]> {
        self.framed.get(&node).map(|f| f.kept.as_slice())
    }

    /// The kept coordinate of old free dof `old` of a node without a frame.
    pub fn new_dof(&self, old: usize) -> Option<usize> {
        self.new_of_old.get(old).copied().flatten()
    }

    /// `T[old, ·]`: the kept coordinates old free dof `old` moves with, and their weights.
    fn row(&self, old: usize, node_dir: Option<(u32, usize)>, out: &mut Vec<(usize, f64)>) {
        out.clear();
        if let Some(n) = self.new_dof(old) {
            out.push((n, 1.0));
        } else if let Some((node, dir)) = node_dir
            && let Some(sl) = self.slaves.get(&node)
        {
            out.extend_from_slice(&sl.rows[dir]);
        } else if let Some((node, dir)) = node_dir
            && let Some(fr) = self.framed.get(&node)
        {
            for &(n, axis) in &fr.kept {
                if axis[dir] != 0.0 {
                    out.push((n, axis[dir]));
                }
            }
        }
    }

    /// `Tᵀ X T` for a symmetric sparse `X` over the old free dofs (both triangles stored),
    /// symmetric bit for bit. Entries between nodes without frames are copied unchanged.
    pub fn congruence(
        &self,
        dofmap: &DofMap,
        x: &SparseColMat<usize, f64>,
    ) -> SparseColMat<usize, f64> {
        let xr = x.as_ref();
        let n_old = x.ncols();
        // Columns of T: old dofs and weights of each new dof.
        let mut t_cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); self.num_new];
        let node_dir: Vec<Option<(u32, usize)>> = (0..n_old).map(|f| dofmap.node_dir(f)).collect();
        let mut row = Vec::new();
        for old in 0..n_old {
            self.row(old, node_dir[old], &mut row);
            for &(n, w) in &row {
                t_cols[n].push((old, w));
            }
        }
        let is_framed_new = {
            let mut v = vec![false; self.num_new];
            for fr in self.framed.values() {
                for &(n, _) in &fr.kept {
                    v[n] = true;
                }
            }
            v
        };
        let mut col_ptr = Vec::with_capacity(self.num_new + 1);
        let mut row_idx: Vec<usize> = Vec::new();
        let mut val: Vec<f64> = Vec::new();
        col_ptr.push(0);
        let mut acc: BTreeMap<usize, f64> = BTreeMap::new();
        for c in 0..self.num_new {
            acc.clear();
            for &(old_c, wc) in &t_cols[c] {
                for (r, &v) in xr.row_idx_of_col(old_c).zip(xr.val_of_col(old_c)) {
                    self.row(r, node_dir[r], &mut row);
                    for &(nr, wr) in &row {
                        let term = if wc == 1.0 && wr == 1.0 {
                            v
                        } else {
                            wr * v * wc
                        };
                        *acc.entry(nr).or_insert(0.0) += term;
                    }
                }
            }
            for (&r, &v) in &acc {
                row_idx.push(r);
                val.push(v);
            }
            col_ptr.push(row_idx.len());
        }
        // Symmetric bits: an entry touching a framed coordinate is the mean of the two sums.
        let lookup = |r: usize, c: usize, col_ptr: &[usize], row_idx: &[usize], val: &[f64]| {
            let (a, b) = (col_ptr[c], col_ptr[c + 1]);
            row_idx[a..b]
                .binary_search(&r)
                .map(|k| val[a + k])
                .unwrap_or(0.0)
        };
        let mut sym = val.clone();
        for c in 0..self.num_new {
            for k in col_ptr[c]..col_ptr[c + 1] {
                let r = row_idx[k];
                if r != c && (!self.slaves.is_empty() || is_framed_new[r] || is_framed_new[c]) {
                    sym[k] = 0.5 * (val[k] + lookup(c, r, &col_ptr, &row_idx, &val));
                }
            }
        }
        SparseColMat::new(
            SymbolicSparseColMat::new_checked(self.num_new, self.num_new, col_ptr, None, row_idx),
            sym,
        )
    }

    /// The held system `Tᵀ K T`, `Tᵀ M T`.
    pub fn system(&self, dofmap: &DofMap, system: &System) -> System {
        System {
            k: self.congruence(dofmap, &system.k),
            m: self.congruence(dofmap, &system.m),
        }
    }

    /// `T X`: rows of the kept coordinates back on the old free dofs (a framed node's
    /// coordinates as displacements along x, y, z).
    pub fn expand_rows(&self, x: MatRef<'_, f64>, n_old: usize) -> Mat<f64> {
        let mut out = Mat::<f64>::zeros(n_old, x.ncols());
        for (old, new) in self.new_of_old.iter().enumerate() {
            if let Some(n) = new {
                for j in 0..x.ncols() {
                    out[(old, j)] = x[(*n, j)];
                }
            }
        }
        for fr in self.framed.values() {
            for (dir, old) in fr.old.iter().enumerate() {
                let Some(old) = old else { continue };
                for j in 0..x.ncols() {
                    out[(*old, j)] = fr.kept.iter().map(|&(n, a)| a[dir] * x[(n, j)]).sum();
                }
            }
        }
        for sl in self.slaves.values() {
            for (dir, old) in sl.old.iter().enumerate() {
                let Some(old) = old else { continue };
                for j in 0..x.ncols() {
                    out[(*old, j)] = sl.rows[dir].iter().map(|&(n, w)| w * x[(n, j)]).sum();
                }
            }
        }
        out
    }
}

/// A direction relative to a rotation axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AxisDirection {
    /// Along the axis.
    Axial,
    /// Away from the axis, perpendicular to it.
    Radial,
    /// The direction of the rotation's motion (axis × radial).
    Tangential,
}

/// The axis a disc turns about: a point on it and its unit direction; the disc turns by the
/// right-hand rule about [`RotationAxis::axis`] (reverse the direction for the other sense).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotationAxis {
    point: [f64; 3],
    axis: [f64; 3],
}

impl RotationAxis {
    /// The axis through `point` along `direction` (need not be unit). Errors when either is
    /// not finite or the direction has zero length.
    pub fn new(point: [f64; 3], direction: [f64; 3]) -> Result<Self, FeError> {
        if !point.iter().all(|x| x.is_finite()) {
            return Err(FeError::BadAxis);
        }
        let axis = unit(direction).ok_or(FeError::BadAxis)?;
        Ok(Self { point, axis })
    }

    /// A point on the axis.
    pub fn point(&self) -> [f64; 3] {
        self.point
    }

    /// The unit axis; the rotation is right-handed about it.
    pub fn axis(&self) -> [f64; 3] {
        self.axis
    }

    /// The component of `p - point` perpendicular to the axis.
    fn arm(&self, p: [f64; 3]) -> [f64; 3] {
        let d = [
            p[0] - self.point[0],
            p[1] - self.point[1],
            p[2] - self.point[2],
        ];
        let along = dot(d, self.axis);
        std::array::from_fn(|i| d[i] - along * self.axis[i])
    }

    /// Distance of `p` from the axis.
    pub fn radius(&self, p: [f64; 3]) -> f64 {
        let r = self.arm(p);
        dot(r, r).sqrt()
    }

    /// The velocity at `p` of the disc turning at `omega` rad/s: `omega axis × (p - point)`.
    pub fn velocity(&self, p: [f64; 3], omega: f64) -> [f64; 3] {
        cross(self.axis, self.arm(p)).map(|v| omega * v)
    }

    /// The unit direction of kind `which` at `p`; `None` for radial and tangential directions
    /// of a point on the axis (within 1e-12 of the largest coordinate of `p` and the axis
    /// point), where they are undefined.
    pub fn direction(&self, which: AxisDirection, p: [f64; 3]) -> Option<[f64; 3]> {
        if which == AxisDirection::Axial {
            return Some(self.axis);
        }
        let r = self.arm(p);
        let scale = p
            .iter()
            .chain(&self.point)
            .fold(0.0f64, |m, x| m.max(x.abs()))
            .max(f64::MIN_POSITIVE);
        if dot(r, r).sqrt() <= AXIS_TOLERANCE * scale {
            return None;
        }
        let radial = unit(r)?;
        match which {
            AxisDirection::Radial => Some(radial),
            _ => unit(cross(self.axis, radial)),
        }
    }

    /// Axial, radial and tangential unit directions at `p` (a right-handed orthonormal
    /// triad), `None` on the axis.
    pub fn triad(&self, p: [f64; 3]) -> Option<[[f64; 3]; 3]> {
        Some([
            self.axis,
            self.direction(AxisDirection::Radial, p)?,
            self.direction(AxisDirection::Tangential, p)?,
        ])
    }

    /// Restraints of `nodes` of `mesh` along the directions `which` relative to the axis, for
    /// [`HeldNodes::new`]. Errors when a node index is out of range or a node lies on the axis
    /// (its radial and tangential directions are undefined).
    pub fn restraints(
        &self,
        mesh: &Mesh,
        nodes: &[u32],
        which: &[AxisDirection],
    ) -> Result<Vec<SkewRestraint>, FeError> {
        let mut out = Vec::with_capacity(nodes.len() * which.len());
        for &node in nodes {
            let p = *mesh
                .nodes
                .get(node as usize)
                .ok_or(FeError::NodeOutOfRange {
                    index: node,
                    num_nodes: mesh.num_nodes(),
                })?;
            for &w in which {
                let direction = self.direction(w, p).ok_or(FeError::BadDirection { node })?;
                out.push(SkewRestraint { node, direction });
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests;
