//! The connections between parts in the reduced brake: springs between two parts' coupling
//! points (a node set's mean translation and rotation, six reduced dofs each) or from one to
//! ground, and the reaction of the clamp force where a connection carries it
//! ([`squeal_reduce::coupling`] derives both).
//!
//! Each connection adds `K_c = Dᵀ T D + E_θᵀ R E_θ` on its ends' twelve (six to ground) dofs to
//! the brake's `K` of eq (11): the brake stays linear outside the disc–pad contact, so every
//! analysis (stability, CHBM, branch) runs on it unchanged. A connection that carries the
//! clamp force (a piston between the caliper and a pad) applies to its second end the force
//! opposite to the one `F_piston` puts on the pad's load point, at that point (so the moment
//! `(c_a − c_b) × (−F)` on the second end's rotations): the pressure in the bore pushes the
//! caliper back as hard as it pushes the pad.
//!
//! A connection that acts on the vibration only (`vibration_only`: a piston's seal and fluid
//! column) adds its `K_c` to `K` and to `K_vib` (`Brake::k_vibration`), which the static
//! equilibrium and the 0th harmonic take back out ([`crate::vibration_only`]).

use crate::error::BrakeError;
use faer::Mat;
use squeal_element::geometry::cross;
use squeal_reduce::coupling::{End, connection_stiffness};
use squeal_reduce::rom::{DofLabel, ReducedModel, ReducedPart};

/// The brake dofs of an end's six coordinates (translations x, y, z, rotations about x, y, z)
/// and its centroid; `parts` are the brake's parts in the order of their dofs.
fn end_dofs(
    name: &str,
    end: &End,
    parts: &[&ReducedPart],
) -> Result<([usize; 6], [f64; 3]), BrakeError> {
    let missing = |what: String| BrakeError::Connection {
        name: name.into(),
        what,
    };
    let mut start = 0;
    let mut found = None;
    for p in parts {
        if p.info.name == end.part {
            found = Some((*p, start));
            break;
        }
        start += p.size();
    }
    let (part, start) = found.ok_or_else(|| missing(format!("no part '{}'", end.part)))?;
    let point = part.info.points.get(end.point).ok_or_else(|| {
        missing(format!(
            "part '{}' has no point {} (set {})",
            end.part,
            end.point + 1,
            end.set
        ))
    })?;
    let mut dofs = [usize::MAX; 6];
    for (k, label) in part.info.dofs.iter().enumerate() {
        match *label {
            DofLabel::Point { point, direction } if point == end.point && direction < 3 => {
                dofs[usize::from(direction)] = start + k;
            }
            DofLabel::Rotation { point, axis } if point == end.point && axis < 3 => {
                dofs[3 + usize::from(axis)] = start + k;
            }
            _ => {}
        }
    }
    if dofs.contains(&usize::MAX) {
        return Err(missing(format!(
            "point {} of part '{}' (set {}) does not keep its six mean-motion dofs",
            end.point + 1,
            end.part,
            end.set
        )));
    }
    Ok((dofs, point.position))
}

/// Adds every connection of `rom` to `k`, those acting on the vibration only to `k_vibration`
/// as well (made when the first comes), and the reactions of those carrying the clamp force
/// to `f` (module docs); `parts` are the brake's parts in the order of their dofs.
pub fn add_connections(
    rom: &ReducedModel,
    parts: &[&ReducedPart],
    k: &mut Mat<f64>,
    k_vibration: &mut Option<Mat<f64>>,
    f: &mut [f64],
) -> Result<(), BrakeError> {
    for c in &rom.connections {
        let (a, ca) = end_dofs(&c.name, &c.a, parts)?;
        let b =
            c.b.as_ref()
                .map(|b| end_dofs(&c.name, b, parts))
                .transpose()?;
        let kc = connection_stiffness(c, ca, b.map(|x| x.1));
        let dofs: Vec<usize> = a
            .iter()
            .chain(b.iter().flat_map(|x| x.0.iter()))
            .copied()
            .collect();
        for (i, &di) in dofs.iter().enumerate() {
            for (j, &dj) in dofs.iter().enumerate() {
                k[(di, dj)] += kc[i][j];
            }
        }
        if c.vibration_only {
            let kv = k_vibration.get_or_insert_with(|| Mat::zeros(k.nrows(), k.ncols()));
            for (i, &di) in dofs.iter().enumerate() {
                for (j, &dj) in dofs.iter().enumerate() {
                    kv[(di, dj)] += kc[i][j];
                }
            }
        }
        if c.load {
            let (b, cb) = b.ok_or_else(|| BrakeError::Connection {
                name: c.name.clone(),
                what: "it carries the clamp force but has no second end to react it".into(),
            })?;
            // The force F_piston puts on the pad's load point, reacted at that point.
            let force: [f64; 3] = std::array::from_fn(|d| f[a[d]]);
            let arm = [ca[0] - cb[0], ca[1] - cb[1], ca[2] - cb[2]];
            let moment = cross(arm, force);
            for d in 0..3 {
                f[b[d]] -= force[d];
                f[b[3 + d]] -= moment[d];
            }
        }
    }
    Ok(())
}

/// Eliminates the ties between parts of `rom` from the assembled brake (`K`, `M`, `F_piston`,
/// `K_vib`, `C`): the congruence `q = T q_r` of [`squeal_reduce::part_tie`], `K' = Tᵀ K T`,
/// `M' = Tᵀ M T`, `f' = Tᵀ f`. The slave dofs are on further parts, after every pad's dofs
/// (`first_body`), so the contact pairs' and the load's dofs keep their places.
pub fn eliminate_ties(
    rom: &ReducedModel,
    parts: &[&ReducedPart],
    first_body: usize,
    brake: &mut crate::model::Brake,
) -> Result<(), BrakeError> {
    if rom.ties.is_empty() {
        return Ok(());
    }
    let mut offsets = Vec::with_capacity(parts.len());
    let mut start = 0;
    for p in parts {
        offsets.push((p.info.name.as_str(), start, *p));
        start += p.size();
    }
    let find = |name: &str| offsets.iter().find(|o| o.0 == name);
    let offset = |name: &str| find(name).map(|o| o.1);
    let dof = |name: &str, point: usize, d: usize| {
        find(name).and_then(|o| {
            o.2.info.dofs.iter().position(|l| {
                matches!(*l, DofLabel::Point { point: q, direction } if q == point && usize::from(direction) == d)
            })
        })
    };
    let n = brake.size();
    let t = squeal_reduce::part_tie::TieTransform::new(n, &rom.ties, &offset, &dof).map_err(
        |what| BrakeError::Connection {
            name: "ties between parts".into(),
            what,
        },
    )?;
    if let Some((s, _)) = t.slaves.iter().find(|(s, _)| *s < first_body) {
        return Err(BrakeError::Connection {
            name: "ties between parts".into(),
            what: format!(
                "slave dof {s} is on the disc or a pad: the slave of a tie between parts must be a further part ([parts.<name>])"
            ),
        });
    }
    brake.k = t.congruence(&brake.k);
    brake.m = t.congruence(&brake.m);
    brake.f_piston = t.reduce_vector(&brake.f_piston);
    if let Some(kv) = &brake.k_vibration {
        brake.k_vibration = Some(t.congruence(kv));
    }
    if let Some(c) = &brake.c {
        brake.c = Some(t.congruence(c));
    }
    Ok(())
}
