//! A part's coupling sets as boundary rows: six per set, its mean translation and rotation
//! ([`crate::coupling`]), each a constraint row held by a footprint spring (module docs).

use super::*;
use crate::coupling::{CouplingSet, MeanMotion};

/// The rows of `couplings` appended to `points` and `rows` (after the contact and piston
/// points, in the order given): one point each, of role [`PointRole::Coupling`] (or
/// [`PointRole::Piston`] for a pad's load set), with dofs `x, y, z` ([`DofLabel::Point`]) and
/// rotations about `x, y, z` ([`DofLabel::Rotation`]).
pub(crate) fn coupling_rows(
    mesh: &Mesh,
    dofmap: &FreeDofs,
    spec: &PartSpec,
    couplings: &[CouplingSet],
    points: &mut Vec<InterfacePoint>,
    rows: &mut Vec<Row>,
) -> Result<(), ReduceError> {
    nodal_rows(mesh, dofmap, spec, couplings, points, rows)?;
    for coupling in couplings.iter().filter(|c| !c.nodal) {
        let mean = MeanMotion::of(mesh, &coupling.set)?;
        let p = points.len();
        points.push(InterfacePoint {
            role: if coupling.load {
                PointRole::Piston
            } else {
                PointRole::Coupling
            },
            node_id: None,
            patch: None,
            position: mean.centroid,
            area: mean.area,
            normal: mean.normal,
            surface: None,
            projected: None,
            combines: None,
        });
        for (k, motion) in mean.rows(mesh).into_iter().enumerate() {
            let mut entries = Vec::new();
            for (node, c) in motion {
                let size = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
                if size == 0.0 {
                    continue;
                }
                let along = dofmap.along(node, c.map(|x| x / size)).ok_or_else(|| {
                    ReduceError::BoundaryRestrained {
                        part: spec.name.clone(),
                        set: coupling.set.clone(),
                        node: mesh.node_ids[node as usize],
                        position: mesh.nodes[node as usize],
                        direction: AXES[(0..3)
                            .max_by(|&a, &b| c[a].abs().total_cmp(&c[b].abs()))
                            .unwrap_or(0)],
                    }
                })?;
                entries.extend(along.into_iter().map(|(dof, v)| (dof, v * size)));
            }
            let label = match k {
                0..3 => point_label(p, k),
                _ => DofLabel::Rotation {
                    point: p,
                    axis: (k - 3) as u8,
                },
            };
            rows.push(Row {
                point: p,
                label,
                entries,
                footprint: true,
            });
        }
    }
    Ok(())
}

/// The rows of the `nodal` coupling sets (the sets of ties between parts,
/// [`crate::part_tie`]): each node, once however many sets hold it, a point of role
/// [`PointRole::Tie`] with its three dofs `x, y, z` kept as they are (as a contact node's).
fn nodal_rows(
    mesh: &Mesh,
    dofmap: &FreeDofs,
    spec: &PartSpec,
    couplings: &[CouplingSet],
    points: &mut Vec<InterfacePoint>,
    rows: &mut Vec<Row>,
) -> Result<(), ReduceError> {
    let mut seen = std::collections::BTreeSet::new();
    for coupling in couplings.iter().filter(|c| c.nodal) {
        let nodes = mesh
            .node_set(&coupling.set)
            .ok_or_else(|| InterfaceError::MissingSet(coupling.set.clone()))?;
        if nodes.is_empty() {
            return Err(InterfaceError::EmptySet(coupling.set.clone()).into());
        }
        for &node in nodes {
            if !seen.insert(node) {
                continue;
            }
            let p = points.len();
            points.push(InterfacePoint {
                role: PointRole::Tie,
                node_id: Some(mesh.node_ids[node as usize]),
                patch: None,
                position: mesh.nodes[node as usize],
                area: None,
                normal: None,
                surface: None,
                projected: None,
                combines: None,
            });
            for d in 0..3 {
                let dof =
                    dofmap
                        .free_dof(node, d)
                        .ok_or_else(|| ReduceError::BoundaryRestrained {
                            part: spec.name.clone(),
                            set: coupling.set.clone(),
                            node: mesh.node_ids[node as usize],
                            position: mesh.nodes[node as usize],
                            direction: AXES[d],
                        })?;
                rows.push(Row {
                    point: p,
                    label: point_label(p, d),
                    entries: vec![(dof, 1.0)],
                    footprint: false,
                });
            }
        }
    }
    Ok(())
}
