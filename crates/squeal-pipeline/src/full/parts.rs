//! The scene's items beyond the disc, the pads and their contact in the full model: the
//! further parts (`[parts.<name>]`), the connectors between coupling sets, and the dampers.
//! Supports with stiffness, `[[springs]]`, ties and restraints in node frames are in each
//! part's `K'` already ([`squeal_reduce::unreduced`]: the reduction's own assembly).
//!
//! **Connectors.** A connector joins the six mean-motion coordinates `r_a = C_a u_a` of a
//! coupling set of one part (RBE3, `*COUPLING, *DISTRIBUTING`; [`squeal_reduce::coupling`]) to
//! those of another part, `r_b = C_b u_b`, or to ground, through a 6-dof spring (CBUSH) of
//! stiffness `K_c` (12 × 12, or 6 × 6 to ground; `connection_stiffness`, about the points'
//! centroids). Its energy is `½ rᵀ K_c r` with `r = [C_a u_a; C_b u_b]`, so the full model's
//! stiffness gains `Cᵀ K_c C`, `C` the rows of both ends on the full model's coordinates. The
//! rows are the reduction's own (`coupling_rows`, the same weights and `J⁻¹`), and the
//! centroids the reduced model's points: the reduced brake adds `K_c` on the same six
//! coordinates of each end, which its Craig–Bampton bases keep exactly (`C B = [I 0]`, the
//! constraint modes), so the reduced brake is this model projected on the bases — the same
//! model, not a penalty or a multipoint constraint standing for it. Neither was chosen: the
//! coupling is an interpolation (the set's mean motion), not a rigid link, and `K_c` is the
//! connector's own finite stiffness, so there is nothing to penalise or eliminate.
//!
//! **Dampers.** A damper's terms `c (w · u̇)²` ([`squeal_reduce::dampers`]) on the part's kept
//! coordinates give `C_d`, stacked as `K` and `M` are; the reduced brake's physical damping is
//! `Bᵀ C_d B` of the same terms, so the quadratic problem `λ² M + λ (C(μ) + C_d) + K_t(μ)` is
//! the reduced one's unreduced.

use super::{FullPart, full_error, push_block};
use crate::error::Result;
use crate::model::Model;
use crate::parts::SceneParts;
use faer::sparse::{SparseColMat, Triplet};
use squeal_reduce::brake::{BrakeInputs, LoadedPart};
use squeal_reduce::coupling::{Connection, CouplingSet, End, MeanMotion, connection_stiffness};
use squeal_reduce::dampers::Damper;
use squeal_scene::Scene;
use std::collections::BTreeMap;

/// Sparse rows on the full model's coordinates.
type Rows = Vec<Vec<(usize, f64)>>;

/// The mesh of part `name`: the disc, a pad or a further part.
pub(super) fn loaded<'a>(parts: &'a SceneParts, name: &str) -> Result<&'a LoadedPart> {
    parts
        .part(name)
        .or_else(|| parts.bodies.iter().find(|b| b.0 == name).map(|b| &b.1))
        .ok_or_else(|| full_error(format!("no mesh for the part {name}")))
}

/// The six rows of `end` on the full model's coordinates (its part's offset added), and the
/// reduced model's centroid of the point, checked against the set's on the mesh.
fn end_rows(
    end: &End,
    c: &Connection,
    full: &[FullPart],
    parts: &SceneParts,
    inputs: &BrakeInputs,
    model: &Model,
) -> Result<(Rows, [f64; 3])> {
    let what = |e: &dyn std::fmt::Display| {
        full_error(format!(
            "connector {}: the {}'s set {}: {e}",
            c.name, end.part, end.set
        ))
    };
    let fp = full
        .iter()
        .find(|p| p.name == end.part)
        .ok_or_else(|| what(&"no such part in the full model"))?;
    let mesh = &loaded(parts, &end.part)?.mesh;
    let input = inputs
        .parts()
        .into_iter()
        .find(|p| p.0 == end.part)
        .ok_or_else(|| what(&"no such part in the inputs"))?
        .1;
    let point = model
        .rom
        .part(&end.part)
        .and_then(|p| p.info.points.get(end.point))
        .ok_or_else(|| what(&"no coupling point in the reduced model"))?;
    let mean = MeanMotion::of(mesh, &end.set).map_err(|e| what(&e))?;
    if mean.centroid != point.position {
        return Err(what(
            &"its centroid on the mesh is not the reduced model's point: was it reduced from another mesh or set? Reduce again",
        ));
    }
    let load = input.couplings.iter().any(|k| k.set == end.set && k.load);
    let coupling = [CouplingSet {
        set: end.set.clone(),
        load,
        nodal: false,
    }];
    let rows = fp
        .unreduced
        .coupling_rows(mesh, &fp.spec, &coupling)
        .map_err(|e| what(&e))?;
    let rows = rows
        .into_iter()
        .map(|r| r.into_iter().map(|(i, v)| (fp.offset + i, v)).collect())
        .collect();
    Ok((rows, point.position))
}

/// `Cᵀ K_c C` of every connection of the reduced model (module docs), as triplets.
pub(super) fn connector_triplets(
    full: &[FullPart],
    parts: &SceneParts,
    inputs: &BrakeInputs,
    model: &Model,
    out: &mut Vec<Triplet<usize, usize, f64>>,
) -> Result<()> {
    for c in &model.rom.connections {
        let (mut rows, ca) = end_rows(&c.a, c, full, parts, inputs, model)?;
        let cb = match &c.b {
            Some(b) => {
                let (rb, cb) = end_rows(b, c, full, parts, inputs, model)?;
                rows.extend(rb);
                Some(cb)
            }
            None => None,
        };
        let kc = connection_stiffness(c, ca, cb);
        // The rows dense on the union of their coordinates, then Rᵀ (K_c R).
        let mut index: BTreeMap<usize, usize> = BTreeMap::new();
        for &(i, _) in rows.iter().flatten() {
            let next = index.len();
            index.entry(i).or_insert(next);
        }
        let n = index.len();
        let mut r = vec![vec![0.0; n]; rows.len()];
        for (k, row) in rows.iter().enumerate() {
            for &(i, v) in row {
                r[k][index[&i]] += v;
            }
        }
        let kr: Vec<Vec<f64>> = kc
            .iter()
            .map(|krow| {
                (0..n)
                    .map(|q| krow.iter().zip(&r).map(|(a, rr)| a * rr[q]).sum())
                    .collect()
            })
            .collect();
        for (&gq, &q) in &index {
            for (&gp, &p) in &index {
                let v: f64 = r.iter().zip(&kr).map(|(rr, m)| rr[p] * m[q]).sum();
                if v != 0.0 {
                    out.push(Triplet::new(gp, gq, v));
                }
            }
        }
    }
    Ok(())
}

/// The stacked damping `C_d` of the scene's dampers on the full model (module docs); `None`
/// without any.
pub(super) fn damping(
    scene: &Scene,
    full: &[FullPart],
    parts: &SceneParts,
) -> Result<Option<SparseColMat<usize, f64>>> {
    let specs = scene.dampers()?;
    if specs.is_empty() {
        return Ok(None);
    }
    let mut t = Vec::new();
    for fp in full {
        let dampers: Vec<Damper> = crate::dampers::part_dampers(&specs, parts, &fp.name);
        if dampers.is_empty() {
            continue;
        }
        let mesh = &loaded(parts, &fp.name)?.mesh;
        let c = fp
            .unreduced
            .damping(mesh, &dampers)
            .map_err(|e| full_error(format!("the {}'s dampers: {e}", fp.name)))?;
        push_block(&c, fp.offset, &mut t);
    }
    let n = full.last().map_or(0, |p| p.offset + p.unreduced.num_free());
    SparseColMat::try_new_from_triplets(n, n, &t)
        .map(Some)
        .map_err(|e| full_error(format!("stacking the dampers: {e}")))
}
