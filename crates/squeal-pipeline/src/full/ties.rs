//! Ties between separately reduced parts (`[[ties]]` with `master_part`) in the full model.
//!
//! The reduced brake eliminates each slave node's three boundary dofs by the congruence
//! `q = T q_r`, `T = [I; W]`, on the assembled reduced model ([`squeal_reduce::part_tie`]:
//! `u_s = Σ_i N_i(ξ_s) u_i`, the master face's shape functions at the slave node's projection).
//! The full model does the same on its stacked parts: the same projection
//! ([`squeal_reduce::part_tie::project_ties`], so the same weights and tolerance rules), each
//! slave node's dof along `x`, `y`, `z` replaced by the weighted rows of its masters' dofs
//! along the same direction (each a row on the master part's kept coordinates,
//! [`squeal_reduce::unreduced::Coordinates::along`]), and
//!
//! `K' = Tᵀ K T`, `M' = Tᵀ M T`, `C' = Tᵀ C T`, `g' = Tᵀ g`
//!
//! for the stiffness (the connectors' `Cᵀ K_c C` in it), the mass, the dampers and each contact
//! pair's vectors. Each part's Craig–Bampton basis `B_p` holds the tie's nodes exactly (they
//! are boundary coordinates, `u_b = q_b`), so `diag(B_p)` maps the reduced brake's `T` onto
//! this one: the tied reduced brake is the tied full model projected on the stacked bases
//! (Rayleigh–Ritz), as without ties. A slave node must be a plain node of its part (three
//! free dofs in the global axes: the reduction refuses a restrained one, and one in its own
//! axes or tied inside its part is refused here); a master direction held by a restraint is
//! refused likewise (the reduction keeps every master node's three dofs as boundary dofs).

use super::{FullPart, full_error};
use crate::error::Result;
use crate::parts::SceneParts;
use faer::sparse::{SparseColMat, Triplet};
use squeal_brake::model::SparseVec;
use squeal_mesh::Mesh;
use squeal_reduce::brake::BrakeInputs;
use squeal_reduce::part_tie::project_ties;
use squeal_reduce::unreduced::Coordinates;
use std::collections::{BTreeMap, HashMap};

/// The congruence `u = T u_r` of the ties between parts on the stacked full model (module
/// docs): each stacked dof's row of `T`.
#[derive(Clone, Debug, PartialEq)]
pub struct FullTies {
    /// Stacked size (before the elimination).
    pub stacked: usize,
    /// Size after it.
    pub size: usize,
    /// Row `i` of `T`: `(kept dof, weight)`; a kept dof's row is itself with weight 1.
    rows: Vec<Vec<(usize, f64)>>,
    /// Slave nodes eliminated.
    pub slave_nodes: usize,
}

/// The unit vector along axis `d`.
fn axis(d: usize) -> [f64; 3] {
    let mut w = [0.0; 3];
    w[d] = 1.0;
    w
}

impl FullTies {
    /// The ties of `inputs` on the stacked parts `full` (their meshes in `parts`); `None`
    /// without any.
    pub(super) fn new(
        parts: &SceneParts,
        inputs: &BrakeInputs,
        full: &[FullPart],
    ) -> Result<Option<Self>> {
        if inputs.part_ties.is_empty() {
            return Ok(None);
        }
        let meshes: Vec<(&str, &Mesh)> = full
            .iter()
            .map(|p| Ok((p.name.as_str(), &super::parts::loaded(parts, &p.name)?.mesh)))
            .collect::<Result<_>>()?;
        let bodies: Vec<&str> = inputs.bodies.iter().map(|b| b.name.as_str()).collect();
        let projected = project_ties(&inputs.part_ties, &meshes, &bodies)
            .map_err(|e| full_error(format!("the ties between parts: {e}")))?;
        let coordinates: Vec<Coordinates> =
            full.iter().map(|p| p.unreduced.coordinates()).collect();
        let index: Vec<HashMap<u64, u32>> = meshes
            .iter()
            .map(|(_, m)| {
                let ids = m.node_ids.iter().enumerate();
                ids.map(|(i, &id)| (id, i as u32)).collect()
            })
            .collect();
        let part = |name: &str| {
            full.iter().position(|p| p.name == name).ok_or_else(|| {
                full_error(format!("the tie's part {name} is not in the full model"))
            })
        };
        // The row of node `id` of part `k` along axis `d` on the stacked dofs.
        let row = |k: usize, id: u64, d: usize, what: &str| -> Result<Vec<(usize, f64)>> {
            let node = index[k].get(&id).copied().ok_or_else(|| {
                full_error(format!(
                    "the {what} node {id} is not in the {}",
                    full[k].name
                ))
            })?;
            let r = coordinates[k].along(node, axis(d)).ok_or_else(|| {
                full_error(format!(
                    "the {what} node {id} of the {} is held along {} or tied inside its part: a tie between parts needs its nodes free",
                    full[k].name,
                    ["x", "y", "z"][d]
                ))
            })?;
            Ok(r.into_iter()
                .map(|(i, v)| (full[k].offset + i, v))
                .collect())
        };
        let stacked = full.last().map_or(0, |p| p.offset + p.unreduced.num_free());
        // Slave dof -> its masters' stacked dofs and weights.
        let mut slave_of: BTreeMap<usize, Vec<(usize, f64)>> = BTreeMap::new();
        let mut slave_nodes = 0;
        for (tie, links) in inputs.part_ties.iter().zip(&projected) {
            let (s, m) = (part(&tie.slave.0)?, part(&tie.master.0)?);
            for (slave, masters) in links {
                slave_nodes += 1;
                for d in 0..3 {
                    let sr = row(s, *slave, d, "slave")?;
                    let [(i, w)] = sr[..] else {
                        return Err(full_error(format!(
                            "the slave node {slave} of the {} is in its own axes: a tie between parts needs it in the global axes",
                            tie.slave.0
                        )));
                    };
                    if w != 1.0 {
                        return Err(full_error(format!(
                            "the slave node {slave} of the {} is in its own axes",
                            tie.slave.0
                        )));
                    }
                    let mut to: Vec<(usize, f64)> = Vec::new();
                    for &(mid, n) in masters {
                        to.extend(
                            row(m, mid, d, "master")?
                                .into_iter()
                                .map(|(j, v)| (j, n * v)),
                        );
                    }
                    if slave_of.insert(i, to).is_some() {
                        return Err(full_error(format!("the node {slave} is tied twice")));
                    }
                }
            }
        }
        let mut new_of = vec![usize::MAX; stacked];
        let mut size = 0;
        for (i, slot) in new_of.iter_mut().enumerate() {
            if !slave_of.contains_key(&i) {
                *slot = size;
                size += 1;
            }
        }
        let mut rows: Vec<Vec<(usize, f64)>> = new_of.iter().map(|&j| vec![(j, 1.0)]).collect();
        for (s, masters) in slave_of {
            let mut r = Vec::with_capacity(masters.len());
            for (j, w) in masters {
                match new_of[j] {
                    usize::MAX => {
                        return Err(full_error(
                            "a master dof of a tie between parts is a slave of another (chained ties)",
                        ));
                    }
                    k => r.push((k, w)),
                }
            }
            rows[s] = r;
        }
        Ok(Some(Self {
            stacked,
            size,
            rows,
            slave_nodes,
        }))
    }

    /// `Tᵀ A T` of a stacked matrix given as triplets.
    pub fn congruence(&self, a: &[Triplet<usize, usize, f64>]) -> Result<SparseColMat<usize, f64>> {
        let mut out = Vec::with_capacity(a.len());
        for t in a {
            for &(i, wi) in &self.rows[t.row] {
                for &(j, wj) in &self.rows[t.col] {
                    out.push(Triplet::new(i, j, wi * wj * t.val));
                }
            }
        }
        SparseColMat::try_new_from_triplets(self.size, self.size, &out)
            .map_err(|e| full_error(format!("eliminating the ties between parts: {e}")))
    }

    /// `Tᵀ g` of a stacked sparse vector.
    pub fn reduce(&self, g: &SparseVec) -> SparseVec {
        let mut out: BTreeMap<usize, f64> = BTreeMap::new();
        for &(i, v) in g {
            for &(j, w) in &self.rows[i] {
                *out.entry(j).or_insert(0.0) += w * v;
            }
        }
        out.into_iter().collect()
    }

    /// `u = T u_r`: the motion of every stacked dof from the kept ones.
    pub fn expand(&self, u: &[f64]) -> Vec<f64> {
        self.rows
            .iter()
            .map(|r| r.iter().map(|&(j, w)| w * u[j]).sum())
            .collect()
    }
}
