//! Tied (bonded) interfaces *between* separately reduced parts: a shim reduced as a part of its
//! own and bonded to its pad's backplate, a caliper housing bonded to its bracket, a bracket
//! bolted to the knuckle.
//!
//! A tie inside one part ([`crate::tie`]) merges the meshes and eliminates the slave dofs before
//! the Craig–Bampton reduction. Between two parts, each reduced on its own, the natural form
//! for Craig–Bampton keeps both tied surfaces as physical boundary dofs and eliminates the
//! constraint on the assembled reduced model:
//!
//! 1. **Boundary.** Every node of the slave set `S` (on the slave part `s`) and of the master
//!    set `M` (on the master part `m`) keeps its three dofs as boundary coordinates of its
//!    part's reduction (a coupling set kept node by node, [`crate::coupling::CouplingSet`]
//!    `nodal`: [`crate::rom::PointRole::Tie`] points, [`crate::rom::DofLabel::Point`] dofs).
//!    The constraint modes of eq (3) make these coordinates exact: `u_b = q_b` on each part,
//!    whatever fixed-interface modes are kept.
//! 2. **Projection.** Each slave node `x_k` is projected onto the master face (the closest
//!    point, [`crate::interface::nodal::Surface::project`]), giving the master face's quadratic
//!    shape functions there, `N_i(ξ_k)`, and the constraint `u_k = Σ_i N_i(ξ_k) u_i` on the
//!    three directions alike. The meshes need not match: on matching meshes each slave node
//!    lands on a master node (`N_i = 1` there) and the tie is the shared node of one mesh;
//!    otherwise the slave interpolates the master face (surface to surface by projection). The
//!    tolerance rules are [`crate::tie`]'s: a slave node farther than the tolerance from the
//!    master surface, or beyond its edge by more, is refused (default 1 % of the master set's
//!    extent).
//! 3. **Elimination.** On the assembled reduced model, `q = [q_r; q_s]` with `q_s` the slave
//!    nodes' boundary dofs and `q_r` every other dof (the masters' among them), the constraint
//!    is `q_s = W q_r` (`W` the weights, three rows per slave node). The congruence
//!
//!    `q = T q_r`,  `T = [I; W]`,  `K' = Tᵀ K T`, `M' = Tᵀ M T`, `f' = Tᵀ f`
//!
//!    removes the slave dofs exactly: it is the Galerkin projection of the assembled model on
//!    the motions that satisfy the tie, so no penalty stiffness is chosen and none limits the
//!    conditioning (a penalty's error falls only as `1/k_pen`). Each part's basis `B_p` (eq 6)
//!    holds `u_p = B_p q_p`, so the tied reduced model is the full tied model (slave nodes
//!    eliminated by the same `W` on the full meshes) projected on `diag(B_p) T`. With every
//!    fixed-interface mode kept, `B_p` spans the part's whole space and the tied reduced
//!    model's frequencies are the full tied model's to round-off; on matching meshes, the one
//!    mesh's (`cargo test --release -p squeal-reduce --test reduce part_ties::`).
//!
//! The slave part must be a further part (`[parts.<name>]`): its dofs follow the disc's and the
//! pads' in the brake, so removing some leaves the contact's and the load's dofs where they
//! are. The master may be any part. A slave node may not be restrained (its boundary dof
//! would be held: [`crate::ReduceError::BoundaryRestrained`]), be tied twice, or be a master of
//! another tie between parts (chained constraints).

use crate::interface::InterfaceError;
use crate::interface::nodal::Surface;
use crate::rom::{PointRole, ReducedPart};
use serde::{Deserialize, Serialize};
use squeal_mesh::Mesh;
use std::collections::BTreeMap;

/// A tie between two parts as given: the slave set on one part, the master face on another.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PartTieInput {
    /// The slave's part (a further part) and node set.
    pub slave: (String, String),
    /// The master's part and node set (its boundary faces are the surface projected on).
    pub master: (String, String),
    /// Largest distance from a slave node to the master surface (m); `None`: 1 % of the
    /// master set's extent.
    pub tolerance: Option<f64>,
}

/// A slave node's constraint: its point in the slave part, and the master part's points with
/// their weights `N_i(ξ)`, summing to 1.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TieLink {
    /// The slave node's point (index into the slave part's points).
    pub slave: usize,
    /// `(master point, weight)`.
    pub masters: Vec<(usize, f64)>,
}

/// A tie between two reduced parts, resolved to their points (module docs).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PartTie {
    /// The tie as given.
    pub input: PartTieInput,
    /// One link per slave node, in the order of the slave part's points.
    pub links: Vec<TieLink>,
}

/// Why a tie between parts cannot be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PartTieError {
    /// A part the tie names is not in the model.
    #[error(
        "tie of {slave_set} on {slave_part} to {master_set} on {master_part}: '{part}' is not a part (the parts: {have})"
    )]
    NoPart {
        /// Slave part.
        slave_part: String,
        /// Slave set.
        slave_set: String,
        /// Master part.
        master_part: String,
        /// Master set.
        master_set: String,
        /// The missing part.
        part: String,
        /// The parts there are.
        have: String,
    },
    /// The slave part is the disc or a pad.
    #[error(
        "tie of {slave_set} on {slave_part} to {master_set} on {master_part}: the slave must be on a further part ([parts.<name>]), not on the disc or a pad (make {slave_part}'s set the master and the other the slave)"
    )]
    SlaveNotBody {
        /// Slave part.
        slave_part: String,
        /// Slave set.
        slave_set: String,
        /// Master part.
        master_part: String,
        /// Master set.
        master_set: String,
    },
    /// Both sets are on one part.
    #[error(
        "tie of {slave_set} to {master_set}: both are on part '{part}' (a tie inside a part leaves master_part out)"
    )]
    SamePart {
        /// The part.
        part: String,
        /// Slave set.
        slave_set: String,
        /// Master set.
        master_set: String,
    },
    /// A slave node lies off the master surface.
    #[error(
        "tie of {slave_set} on {slave_part} to {master_set} on {master_part}: slave node {node} at ({:.6e}, {:.6e}, {:.6e}) m lies {distance:.3e} m from the master surface ({outside:.3e} m beyond its edge), more than the tie's tolerance {tolerance:.3e} m: the surfaces do not touch there (check that the two sets face each other, that both meshes are in the same units and position, or give a larger tolerance)",
        position[0], position[1], position[2]
    )]
    OffSurface {
        /// Slave part.
        slave_part: String,
        /// Slave set.
        slave_set: String,
        /// Master part.
        master_part: String,
        /// Master set.
        master_set: String,
        /// The slave node's id.
        node: u64,
        /// Its position (m).
        position: [f64; 3],
        /// Its distance to the master surface (m).
        distance: f64,
        /// How far its projection lies beyond the surface's edge (m).
        outside: f64,
        /// The tolerance (m).
        tolerance: f64,
    },
    /// A slave node is tied twice.
    #[error(
        "node {node} of part '{part}' is a slave of two ties ({first} and {second}): tie it once"
    )]
    TiedTwice {
        /// The part.
        part: String,
        /// The node's id.
        node: u64,
        /// The first tie's slave set.
        first: String,
        /// The second's.
        second: String,
    },
    /// A node is a slave of one tie and a master of another.
    #[error(
        "node {node} of part '{part}' is a slave of one tie and on the master set {master_set} of another: make each surface the master of its ties or the slave, not both"
    )]
    Chained {
        /// The part.
        part: String,
        /// The node's id.
        node: u64,
        /// The master set it is on.
        master_set: String,
    },
    /// A node of a tie has no boundary point in its reduced part (a model reduced without the
    /// tie's sets).
    #[error(
        "part '{part}' keeps no boundary point for node {node} of the tie's set {set}: the model was reduced without this tie (reduce again)"
    )]
    NoPoint {
        /// The part.
        part: String,
        /// The node's id.
        node: u64,
        /// The set.
        set: String,
    },
}

impl From<PartTieError> for crate::ReduceError {
    fn from(e: PartTieError) -> Self {
        crate::ReduceError::PartTie(Box::new(e))
    }
}

/// The slave nodes' projections of one tie: `(slave node id, [(master node id, weight)])`.
pub type Projected = Vec<(u64, Vec<(u64, f64)>)>;

/// Projects each slave node of `tie` onto the master face (module docs), `slave_mesh` and
/// `master_mesh` the two parts' meshes; refuses a node off the surface.
pub fn project_tie(
    tie: &PartTieInput,
    slave_mesh: &Mesh,
    master_mesh: &Mesh,
) -> Result<Projected, crate::ReduceError> {
    let (sp, ss) = &tie.slave;
    let (mp, ms) = &tie.master;
    let surface = Surface::new(master_mesh, ms)?;
    let master = master_mesh
        .node_set(ms)
        .ok_or_else(|| InterfaceError::MissingSet(ms.clone()))?;
    let slave = slave_mesh
        .node_set(ss)
        .ok_or_else(|| InterfaceError::MissingSet(ss.clone()))?;
    if slave.is_empty() {
        return Err(InterfaceError::EmptySet(ss.clone()).into());
    }
    let tolerance = tie
        .tolerance
        .unwrap_or_else(|| 0.01 * crate::tie::extent(master_mesh, master));
    let mut out = Vec::with_capacity(slave.len());
    for &s in slave {
        let x = slave_mesh.nodes[s as usize];
        let p = surface.project(x);
        if p.distance > tolerance || p.outside > tolerance {
            return Err(PartTieError::OffSurface {
                slave_part: sp.clone(),
                slave_set: ss.clone(),
                master_part: mp.clone(),
                master_set: ms.clone(),
                node: slave_mesh.node_ids[s as usize],
                position: x,
                distance: p.distance,
                outside: p.outside,
                tolerance,
            }
            .into());
        }
        let weights = p
            .weights
            .iter()
            .map(|&(n, w)| (master_mesh.node_ids[n as usize], w))
            .collect();
        out.push((slave_mesh.node_ids[s as usize], weights));
    }
    Ok(out)
}

/// Checks the ties of `ties` against each other and the parts: `bodies` the further parts'
/// names, `parts` every part's name; a slave tied twice or also a master is refused (module
/// docs). `sets` gives a tie's set's node ids (part, set).
pub fn check_ties(
    ties: &[PartTieInput],
    parts: &[&str],
    bodies: &[&str],
    sets: &dyn Fn(&str, &str) -> Vec<u64>,
) -> Result<(), crate::ReduceError> {
    let mut slaves: BTreeMap<(&str, u64), &str> = BTreeMap::new();
    for t in ties {
        let (sp, ss) = &t.slave;
        let (mp, ms) = &t.master;
        for p in [sp, mp] {
            if !parts.contains(&p.as_str()) {
                return Err(PartTieError::NoPart {
                    slave_part: sp.clone(),
                    slave_set: ss.clone(),
                    master_part: mp.clone(),
                    master_set: ms.clone(),
                    part: p.clone(),
                    have: parts.join(", "),
                }
                .into());
            }
        }
        if sp == mp {
            return Err(PartTieError::SamePart {
                part: sp.clone(),
                slave_set: ss.clone(),
                master_set: ms.clone(),
            }
            .into());
        }
        if !bodies.contains(&sp.as_str()) {
            return Err(PartTieError::SlaveNotBody {
                slave_part: sp.clone(),
                slave_set: ss.clone(),
                master_part: mp.clone(),
                master_set: ms.clone(),
            }
            .into());
        }
        for node in sets(sp, ss) {
            if let Some(first) = slaves.insert((sp.as_str(), node), ss.as_str()) {
                return Err(PartTieError::TiedTwice {
                    part: sp.clone(),
                    node,
                    first: first.to_string(),
                    second: ss.clone(),
                }
                .into());
            }
        }
    }
    for t in ties {
        let (mp, ms) = &t.master;
        if let Some(node) = sets(mp, ms)
            .into_iter()
            .find(|n| slaves.contains_key(&(mp.as_str(), *n)))
        {
            return Err(PartTieError::Chained {
                part: mp.clone(),
                node,
                master_set: ms.clone(),
            }
            .into());
        }
    }
    Ok(())
}

/// The tie points of `part` by node id.
fn tie_points(part: &ReducedPart) -> BTreeMap<u64, usize> {
    part.info
        .points
        .iter()
        .enumerate()
        .filter(|(_, p)| p.role == PointRole::Tie)
        .filter_map(|(i, p)| p.node_id.map(|id| (id, i)))
        .collect()
}

/// `tie`'s projections resolved to the reduced parts' tie points.
pub fn resolve_tie(
    tie: &PartTieInput,
    projected: &Projected,
    slave: &ReducedPart,
    master: &ReducedPart,
) -> Result<PartTie, crate::ReduceError> {
    let (sp, mp) = (tie_points(slave), tie_points(master));
    let point = |map: &BTreeMap<u64, usize>, part: &ReducedPart, set: &str, node: u64| {
        map.get(&node).copied().ok_or_else(|| {
            crate::ReduceError::from(PartTieError::NoPoint {
                part: part.info.name.clone(),
                node,
                set: set.to_string(),
            })
        })
    };
    let mut links = Vec::with_capacity(projected.len());
    for (s, weights) in projected {
        let masters = weights
            .iter()
            .map(|&(m, w)| Ok((point(&mp, master, &tie.master.1, m)?, w)))
            .collect::<Result<Vec<_>, crate::ReduceError>>()?;
        links.push(TieLink {
            slave: point(&sp, slave, &tie.slave.1, *s)?,
            masters,
        });
    }
    links.sort_by_key(|l| l.slave);
    Ok(PartTie {
        input: tie.clone(),
        links,
    })
}

/// Why the ties stored in a `.rom` are not those of `inputs` (empty when they are).
pub fn tie_reasons(stored: &[PartTie], inputs: &[PartTieInput]) -> Vec<String> {
    let same =
        stored.len() == inputs.len() && stored.iter().zip(inputs).all(|(s, i)| s.input == *i);
    match same {
        true => Vec::new(),
        false => vec![format!(
            "ties between parts differ ({} in the file, {} asked for, or their sets or tolerances changed)",
            stored.len(),
            inputs.len()
        )],
    }
}

/// The congruence `q = T q_r` of the module docs on an assembled model of `n` dofs: the slave
/// dofs and, for each, its masters' dofs and weights.
#[derive(Clone, Debug, PartialEq)]
pub struct TieTransform {
    /// Size before the elimination.
    pub n: usize,
    /// The kept dofs, ascending: kept dof `j` is old dof `kept[j]`.
    pub kept: Vec<usize>,
    /// Each slave dof, with `(kept index, weight)` of its masters.
    pub slaves: Vec<(usize, Vec<(usize, f64)>)>,
}

impl TieTransform {
    /// The congruence of `ties` on a model whose parts' dofs start at `offsets` (part name,
    /// offset); `dof(part, point, direction)` gives a point's dof within its part.
    pub fn new(
        n: usize,
        ties: &[PartTie],
        offset: &dyn Fn(&str) -> Option<usize>,
        dof: &dyn Fn(&str, usize, usize) -> Option<usize>,
    ) -> Result<Self, String> {
        let at = |part: &str, point: usize, d: usize| -> Result<usize, String> {
            match (offset(part), dof(part, point, d)) {
                (Some(o), Some(k)) => Ok(o + k),
                _ => Err(format!(
                    "point {} of part '{part}' keeps no dof along {} (reduce again)",
                    point + 1,
                    ["x", "y", "z"][d]
                )),
            }
        };
        // Old slave dof -> old master dofs.
        let mut slave_of: BTreeMap<usize, Vec<(usize, f64)>> = BTreeMap::new();
        for tie in ties {
            for link in &tie.links {
                for d in 0..3 {
                    let s = at(&tie.input.slave.0, link.slave, d)?;
                    let masters = link
                        .masters
                        .iter()
                        .map(|&(m, w)| Ok((at(&tie.input.master.0, m, d)?, w)))
                        .collect::<Result<Vec<_>, String>>()?;
                    if slave_of.insert(s, masters).is_some() {
                        return Err(format!("dof {s} is tied twice"));
                    }
                }
            }
        }
        let kept: Vec<usize> = (0..n).filter(|i| !slave_of.contains_key(i)).collect();
        let mut new_of = vec![usize::MAX; n];
        for (j, &i) in kept.iter().enumerate() {
            new_of[i] = j;
        }
        let mut slaves = Vec::with_capacity(slave_of.len());
        for (s, masters) in slave_of {
            let m = masters
                .into_iter()
                .map(|(i, w)| match new_of[i] {
                    usize::MAX => Err(format!("dof {i} is a master and a slave")),
                    j => Ok((j, w)),
                })
                .collect::<Result<Vec<_>, String>>()?;
            slaves.push((s, m));
        }
        Ok(Self { n, kept, slaves })
    }

    /// The size after the elimination.
    pub fn size(&self) -> usize {
        self.kept.len()
    }

    /// `Tᵀ A T` of a square `n × n` matrix.
    pub fn congruence(&self, a: &faer::Mat<f64>) -> faer::Mat<f64> {
        // A T: the kept columns, plus each slave column times its weights on its masters'.
        let r = self.size();
        let mut at = faer::Mat::from_fn(self.n, r, |i, j| a[(i, self.kept[j])]);
        for (s, masters) in &self.slaves {
            for &(j, w) in masters {
                for i in 0..self.n {
                    at[(i, j)] += w * a[(i, *s)];
                }
            }
        }
        // Tᵀ (A T): the same on the rows.
        let mut out = faer::Mat::from_fn(r, r, |i, j| at[(self.kept[i], j)]);
        for (s, masters) in &self.slaves {
            for &(i, w) in masters {
                for j in 0..r {
                    out[(i, j)] += w * at[(*s, j)];
                }
            }
        }
        out
    }

    /// `Tᵀ f` of a vector of size `n`.
    pub fn reduce_vector(&self, f: &[f64]) -> Vec<f64> {
        let mut out: Vec<f64> = self.kept.iter().map(|&i| f[i]).collect();
        for (s, masters) in &self.slaves {
            for &(j, w) in masters {
                out[j] += w * f[*s];
            }
        }
        out
    }

    /// `q = T q_r`: the motion of every dof from the kept ones.
    pub fn expand(&self, q: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.n];
        for (j, &i) in self.kept.iter().enumerate() {
            out[i] = q[j];
        }
        for (s, masters) in &self.slaves {
            out[*s] = masters.iter().map(|&(j, w)| w * q[j]).sum();
        }
        out
    }
}

/// The ties between parts of a brake's inputs, checked and projected before any reduction:
/// `meshes` every part's name and mesh (disc, pads, bodies), `bodies` the further parts'
/// names. One projection per tie, in order.
pub fn project_ties(
    ties: &[PartTieInput],
    meshes: &[(&str, &Mesh)],
    bodies: &[&str],
) -> Result<Vec<Projected>, crate::ReduceError> {
    if ties.is_empty() {
        return Ok(Vec::new());
    }
    let names: Vec<&str> = meshes.iter().map(|m| m.0).collect();
    let mesh = |part: &str| meshes.iter().find(|m| m.0 == part).map(|m| m.1);
    let sets = |part: &str, set: &str| -> Vec<u64> {
        mesh(part)
            .and_then(|m| m.node_set(set).map(|s| (m, s)))
            .map(|(m, s)| s.iter().map(|&n| m.node_ids[n as usize]).collect())
            .unwrap_or_default()
    };
    check_ties(ties, &names, bodies, &sets)?;
    ties.iter()
        .map(|t| match (mesh(&t.slave.0), mesh(&t.master.0)) {
            (Some(s), Some(m)) => project_tie(t, s, m),
            _ => Err(crate::ReduceError::Options(format!(
                "tie of {} on {}: no mesh for a part",
                t.slave.1, t.slave.0
            ))),
        })
        .collect()
}

/// The projected ties resolved to the reduced parts' points, in order.
pub fn resolve_ties(
    ties: &[PartTieInput],
    projected: &[Projected],
    parts: &[ReducedPart],
) -> Result<Vec<PartTie>, crate::ReduceError> {
    let part = |name: &str| parts.iter().find(|p| p.info.name == name);
    ties.iter()
        .zip(projected)
        .map(|(t, p)| match (part(&t.slave.0), part(&t.master.0)) {
            (Some(s), Some(m)) => resolve_tie(t, p, s, m),
            _ => Err(PartTieError::NoPart {
                slave_part: t.slave.0.clone(),
                slave_set: t.slave.1.clone(),
                master_part: t.master.0.clone(),
                master_set: t.master.1.clone(),
                part: if part(&t.slave.0).is_none() {
                    t.slave.0.clone()
                } else {
                    t.master.0.clone()
                },
                have: parts
                    .iter()
                    .map(|p| p.info.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
            }
            .into()),
        })
        .collect()
}
