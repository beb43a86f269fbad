//! Tied (bonded) interfaces inside a part, and supports with stiffness.
//!
//! **Ties.** A brake corner's parts are bonded to each other: a shim to a pad's backplate, an
//! underlayer to the lining. A tie makes every node of the slave surface move with the point
//! of the master surface it projects onto, `u_s = Σ_i N_i(ξ_s) u_i`, with `N_i` the master
//! face's quadratic shape functions at the projection `ξ_s` (the closest point, found by the
//! nodal contact's projection, [`crate::interface::nodal::Surface::project`]). The meshes need
//! not match: the tie is surface to surface by projection, so a shim meshed finer or coarser
//! than the backplate ties all the same; on matching meshes each slave node projects onto a
//! master node (`N_i = 1` there) and the tie is the shared node of one mesh.
//!
//! The constraints are eliminated, not penalised: the tied parts are one part of the
//! reduction (their meshes merged, e.g. several element sets of one assembly file, each with
//! its own nodes), and the slave nodes' dofs are replaced by their masters' in the
//! congruence `K' = Tᵀ K T`, `M' = Tᵀ M T` ([`squeal_fe::frames::DofTransform::with_ties`]),
//! before the Craig–Bampton reduction of the merged part. This is exact for the constraint
//! (no penalty stiffness to choose, no ill-conditioning, no error of order `k_elem / k_pen`),
//! and the reduction of a tied part is that of one part: a tied two-part block on matching
//! meshes gives the block meshed as one, to round-off. Penalty springs were not chosen: their
//! error falls only as `1/k_pen` while the factor's conditioning grows with it, and a tied
//! part would need its own choice of `k_pen` against its elements' stiffness.
//!
//! A slave node must lie on the master surface: its distance to it, and how far its
//! projection falls beyond the surface's edge, must be under the tie's tolerance (default
//! 1 % of the master face's extent, which admits the faceting of one curved surface meshed
//! twice). A slave node that is itself a master node (a shared node) is left as it is. Slave
//! nodes must not be restrained, kept as boundary nodes, or masters of another tie.
//!
//! A tie between two separately reduced parts (`[[ties]]` with `master_part`) keeps both faces
//! as boundary dofs and eliminates the same projection's constraints on the assembled reduced
//! model instead ([`crate::part_tie`]).
//!
//! **Supports.** A support is a spring to ground on a node set, with a stiffness per global
//! direction `[k_x, k_y, k_z]` (N/m, the set's total): a piston's seal, a caliper finger, a
//! bracket mount, or a pad held over its back face. It acts on the vibration about the
//! equilibrium: `K += Σ_n k_n e_d e_dᵀ` on the set's nodes, before the reduction, so that the
//! reduced stiffness and the fixed-interface modes see it and a part held only by supports is
//! held (its `K_II` is positive definite). The set's total is shared among its nodes in
//! proportion to their tributary areas when the set is a face (the nodal contact's areas,
//! [`crate::interface::nodal::face_nodes`]: a uniform foundation `k / A` per unit area,
//! whatever the mesh), else equally. A rigid part of mass `m` on supports of total `k` along
//! a direction moves at `ω² = k / m` along it.

use crate::error::ReduceError;
use crate::interface::InterfaceError;
use crate::interface::nodal::{Surface, face_nodes};
use squeal_mesh::Mesh;
use std::collections::BTreeMap;

/// A tied interface inside a part: the nodes of `slave` move with the face `master`.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Tie {
    /// Node set of the slave surface (each of its nodes is tied).
    pub slave: String,
    /// Node set of the master face (its boundary faces are the surface projected on).
    pub master: String,
    /// Largest distance from a slave node to the master surface (m); `None`: 1 % of the
    /// master face's extent.
    pub tolerance: Option<f64>,
}

/// A spring to ground on a node set.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Support {
    /// The node set.
    pub set: String,
    /// Total stiffness along x, y, z (N/m), shared over the set's nodes (module docs).
    pub stiffness: [f64; 3],
}

/// The tie constraints of `ties` on `mesh`: each slave node and its masters' weights.
pub fn tie_constraints(
    mesh: &Mesh,
    ties: &[Tie],
) -> Result<BTreeMap<u32, Vec<(u32, f64)>>, ReduceError> {
    let mut out: BTreeMap<u32, Vec<(u32, f64)>> = BTreeMap::new();
    for tie in ties {
        let surface = Surface::new(mesh, &tie.master)?;
        let master = mesh
            .node_set(&tie.master)
            .ok_or_else(|| InterfaceError::MissingSet(tie.master.clone()))?;
        let slave = mesh
            .node_set(&tie.slave)
            .ok_or_else(|| InterfaceError::MissingSet(tie.slave.clone()))?;
        let tolerance = tie.tolerance.unwrap_or_else(|| 0.01 * extent(mesh, master));
        for &s in slave {
            if master.binary_search(&s).is_ok() {
                continue;
            }
            let p = surface.project(mesh.nodes[s as usize]);
            if p.distance > tolerance || p.outside > tolerance {
                return Err(tie_error(
                    tie,
                    format!(
                        "slave node {} lies {:.3e} m from the master surface ({:.3e} m beyond its edge), more than the tie's tolerance {tolerance:.3e} m: the surfaces do not touch there (check the sets, or give a larger tolerance)",
                        mesh.node_ids[s as usize], p.distance, p.outside
                    ),
                ));
            }
            if out.insert(s, p.weights).is_some() {
                return Err(tie_error(
                    tie,
                    format!(
                        "node {} is a slave of two ties: tie it once",
                        mesh.node_ids[s as usize]
                    ),
                ));
            }
        }
    }
    // A master that is itself a slave would chain the constraints.
    for masters in out.values() {
        if let Some(&(m, _)) = masters.iter().find(|(m, _)| out.contains_key(m)) {
            return Err(ReduceError::Options(format!(
                "node {} is a master of one tie and a slave of another: make each surface the master of its ties or the slave, not both",
                mesh.node_ids[m as usize]
            )));
        }
    }
    Ok(out)
}

fn tie_error(tie: &Tie, message: String) -> ReduceError {
    ReduceError::Options(format!(
        "tie of {} (slave) to {} (master): {message}",
        tie.slave, tie.master
    ))
}

/// The diagonal of the bounding box of `nodes`.
pub(crate) fn extent(mesh: &Mesh, nodes: &[u32]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &n in nodes {
        let x = mesh.nodes[n as usize];
        for d in 0..3 {
            lo[d] = lo[d].min(x[d]);
            hi[d] = hi[d].max(x[d]);
        }
    }
    (0..3).map(|d| (hi[d] - lo[d]).powi(2)).sum::<f64>().sqrt()
}

/// Each supported node's spring stiffness along x, y, z (N/m): the supports' totals shared
/// over their sets (module docs), summed where sets overlap, in node order.
pub fn support_springs(
    mesh: &Mesh,
    supports: &[Support],
) -> Result<BTreeMap<u32, [f64; 3]>, ReduceError> {
    let mut out: BTreeMap<u32, [f64; 3]> = BTreeMap::new();
    for s in supports {
        if s.stiffness.iter().any(|k| !(k.is_finite() && *k >= 0.0)) {
            return Err(ReduceError::Options(format!(
                "support on {}: stiffness [{}, {}, {}] N/m must be zero or positive",
                s.set, s.stiffness[0], s.stiffness[1], s.stiffness[2]
            )));
        }
        let nodes = mesh
            .node_set(&s.set)
            .ok_or_else(|| InterfaceError::MissingSet(s.set.clone()))?;
        // A face: shares by tributary area; else (or a set without faces) equal shares.
        let shares: Vec<(u32, f64)> = match face_nodes(mesh, &s.set) {
            Ok(face) if !face.is_empty() => {
                let total: f64 = face.iter().map(|f| f.area).sum();
                face.iter().map(|f| (f.node, f.area / total)).collect()
            }
            _ => nodes
                .iter()
                .map(|&n| (n, 1.0 / nodes.len() as f64))
                .collect(),
        };
        for (n, w) in shares {
            let k = out.entry(n).or_insert([0.0; 3]);
            for d in 0..3 {
                k[d] += w * s.stiffness[d];
            }
        }
    }
    Ok(out)
}
