//! The contact sets' checks and the pairing of the disc's and pads' contact points (by patch or node), with their projections.

use super::*;
use squeal_element::geometry::{norm, sub};

/// Checks a part's node sets before any work: every set named exists and is not empty, and
/// no boundary node (contact node or face node, piston node along the normal) is restrained
/// in a direction it keeps.
pub fn check_sets(
    mesh: &Mesh,
    name: &str,
    input: &PartInput,
    inputs: &BrakeInputs,
) -> Result<(), ReduceError> {
    let set = |s: &str| -> Result<&[u32], ReduceError> {
        let nodes = mesh
            .node_set(s)
            .ok_or_else(|| InterfaceError::MissingSet(s.into()))?;
        if nodes.is_empty() {
            return Err(InterfaceError::EmptySet(s.into()).into());
        }
        refuse_shortened_set(mesh, s)?;
        Ok(nodes)
    };
    let surfaces = input.surfaces();
    let mut boundary: Vec<(&str, &[u32], [bool; 3])> = Vec::new();
    for s in &surfaces {
        let contact_set = match inputs.interface {
            InterfaceKind::Node => &s.contact_set,
            InterfaceKind::Patch | InterfaceKind::Nodal => &s.contact_face_set,
        };
        boundary.push((contact_set, set(contact_set)?, [true; 3]));
    }
    let mut dirs = [false; 3];
    match inputs.piston_direction {
        None => dirs[inputs.normal_direction.min(2)] = true,
        Some(n) => (0..3).for_each(|d| dirs[d] = n[d] != 0.0),
    }
    for p in input.piston_set.iter().chain(&input.piston_footprints) {
        boundary.push((p, set(p)?, dirs));
    }
    for (s, _) in &input.skew_restraints {
        set(s)?;
    }
    for (s, _) in &input.axis_restraints {
        set(s)?;
    }
    for r in &input.restraints {
        let held: &[u32] = match &r.nodes {
            NodeSelection::Set(s) => set(s)?,
            NodeSelection::Indices(v) => v,
        };
        let mut held = held.to_vec();
        held.sort_unstable();
        for (bset, nodes, kept) in &boundary {
            for &n in nodes.iter() {
                let Ok(_) = held.binary_search(&n) else {
                    continue;
                };
                if let Some(d) = (0..3).find(|&d| kept[d] && r.directions[d]) {
                    return Err(ReduceError::BoundaryRestrained {
                        part: name.into(),
                        set: (*bset).into(),
                        node: mesh.node_ids.get(n as usize).copied().unwrap_or(0),
                        position: mesh.nodes.get(n as usize).copied().unwrap_or_default(),
                        direction: ['x', 'y', 'z'][d],
                    });
                }
            }
        }
    }
    Ok(())
}

/// Positions of the contact points of one contact surface of a part, in the order of its
/// reduced dofs: the `CONTACT` nodes (node interface), the patch centroids (patch
/// interface) or the contact face's nodes (nodal interface: the pad's contact points, the
/// disc's face points).
pub fn contact_positions(
    mesh: &Mesh,
    input: &ContactSurface,
    inputs: &BrakeInputs,
) -> Result<Vec<[f64; 3]>, ReduceError> {
    Ok(match inputs.interface {
        InterfaceKind::Node => contact_nodes(mesh, &input.contact_set, &inputs.axis)?
            .into_iter()
            .map(|n| mesh.nodes[n as usize])
            .collect(),
        InterfaceKind::Nodal => face_nodes(mesh, &input.contact_face_set)?
            .into_iter()
            .map(|n| mesh.nodes[n.node as usize])
            .collect(),
        InterfaceKind::Patch => patches(
            mesh,
            &input.contact_face_set,
            inputs.grid[0],
            inputs.grid[1],
            &inputs.axis,
        )?
        .into_iter()
        .map(|p| p.centroid)
        .collect(),
    })
}

/// One pad's nodal pairs, by node id, ready to be attached to the reduced parts.
pub(super) struct PadProjection {
    /// The pad's name.
    pub(super) pad: String,
    /// The disc surface it faces (`None`: the brake's only pad).
    pub(super) facing: Option<String>,
    /// Each pad contact point's node id (a Gauss point's: its face's first node) and its
    /// pair.
    pub(super) pairs: Vec<(u64, NodalPair)>,
    /// The disc face's node ids by mesh index.
    pub(super) disc_ids: Vec<u64>,
}

/// The nodal interface's projections: every pad's face nodes onto the disc face under it
/// ([`crate::interface::nodal::project_pad`]).
pub(super) fn nodal_projections(
    inputs: &BrakeInputs,
    loaded: &[LoadedPart],
) -> Result<Vec<PadProjection>, ReduceError> {
    let surfaces = inputs.disc.surfaces();
    let disc = &loaded[0].mesh;
    let mut out = Vec::with_capacity(inputs.pads.len());
    for (pad, part) in inputs.pads.iter().zip(&loaded[1..]) {
        let k = inputs
            .disc
            .surface_index(&pad.name, inputs.pads.len())
            .ok_or_else(|| ReduceError::Options(format!("no disc surface faces {}", pad.name)))?;
        let pad_face = &pad.part.contact_face_set;
        let pairs = project_pad(disc, &surfaces[k].contact_face_set, &part.mesh, pad_face)?;
        out.push(PadProjection {
            pad: pad.name.clone(),
            facing: surfaces[k].facing.clone(),
            pairs: pairs
                .into_iter()
                .map(|p| (part.mesh.node_ids[p.pad.nodes[0].0 as usize], p))
                .collect(),
            disc_ids: disc.node_ids.clone(),
        });
    }
    Ok(out)
}

/// Adds to the reduced disc one contact point per pad contact point (a face node, or a Gauss
/// point of an 8-node face), at its projection, moving
/// as the disc face's shape functions there combine the disc's face points; returns the
/// pairs (disc and pad contact point indices among each part's contact points).
pub(super) fn attach_projections(
    parts: &mut [ReducedPart],
    projections: Vec<PadProjection>,
) -> Result<Vec<PointPair>, ReduceError> {
    let invalid = |what: String| ReduceError::Invalid {
        part: "brake".into(),
        what,
    };
    let (disc, pads) = parts
        .split_first_mut()
        .ok_or_else(|| invalid("no disc".into()))?;
    let mut pairs = Vec::new();
    let mut disc_contacts = 0;
    for (proj, pad) in projections.into_iter().zip(pads.iter()) {
        let index = |part: &ReducedPart, role: PointRole, surface: &Option<String>| {
            part.info
                .points
                .iter()
                .enumerate()
                .filter(|(_, p)| p.role == role && &p.surface == surface)
                .filter_map(|(i, p)| p.node_id.map(|id| (id, i)))
                .collect::<std::collections::HashMap<u64, usize>>()
        };
        let face = index(disc, PointRole::Face, &proj.facing);
        let pad_contacts: Vec<usize> = (0..pad.info.points.len())
            .filter(|&i| pad.info.points[i].role == PointRole::Contact)
            .collect();
        // The pad's contact points are the pairs' pad points in the same order (both are
        // `quad_contact::contact_points` of the pad's face): checked by position.
        if pad_contacts.len() != proj.pairs.len() {
            return Err(invalid(format!(
                "the {} has {} contact points, its face {} pairs",
                proj.pad,
                pad_contacts.len(),
                proj.pairs.len()
            )));
        }
        for (&pad_point, (id, pair)) in pad_contacts.iter().zip(proj.pairs) {
            let lost = |what: &str, id: u64| invalid(format!("{what} node {id} was not kept"));
            if pad.info.points[pad_point].position != pair.pad.position {
                return Err(lost(&format!("{} face", proj.pad), id));
            }
            let weights = pair
                .projection
                .weights
                .iter()
                .map(|&(n, w)| {
                    let id = proj.disc_ids[n as usize];
                    face.get(&id)
                        .map(|&i| (i, w))
                        .ok_or_else(|| lost("disc face", id))
                })
                .collect::<Result<Vec<_>, _>>()?;
            disc.info.points.push(InterfacePoint {
                role: PointRole::Contact,
                node_id: None,
                patch: None,
                position: pair.projection.point,
                area: Some(pair.pad.area),
                normal: Some(pair.projection.normal),
                surface: proj.facing.clone(),
                projected: Some(Projected {
                    pad: proj.pad.clone(),
                    pad_point,
                    weights,
                    outside: pair.projection.outside,
                }),
                combines: None,
            });
            pairs.push(PointPair {
                disc_point: disc_contacts,
                pad_point: pad_contacts.partition_point(|&i| i < pad_point),
                distance: pair.projection.distance,
            });
            disc_contacts += 1;
        }
    }
    Ok(pairs)
}

/// How close a disc contact point and a pad contact point must be to pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PairingTolerance {
    /// A distance in the mesh's length unit.
    Absolute(f64),
    /// A fraction of the smallest distance between two of the disc's contact points (the
    /// patch size; any distance when the disc has a single point).
    Relative(f64),
}

/// Pairs each disc contact point with the nearest pad contact point not yet taken, which must
/// lie within `tolerance`. Returns the pairs and the tolerance as a distance. This is the one
/// pairing of the workspace: the reduction checks with it that the parts face each other, and
/// the brake model pairs its points with it.
pub fn pair_contact_points(
    disc: &[[f64; 3]],
    pad: &[[f64; 3]],
    tolerance: PairingTolerance,
) -> Result<(Vec<PointPair>, f64), ReduceError> {
    if disc.len() != pad.len() || disc.is_empty() {
        return Err(ReduceError::ContactCountMismatch {
            disc: disc.len(),
            pad: pad.len(),
        });
    }
    let tolerance = match tolerance {
        PairingTolerance::Absolute(d) => d,
        PairingTolerance::Relative(f) => {
            let mut spacing = f64::INFINITY;
            for (i, a) in disc.iter().enumerate() {
                for b in &disc[i + 1..] {
                    spacing = spacing.min(norm(sub(*a, *b)));
                }
            }
            f * spacing
        }
    };
    let mut taken = vec![false; pad.len()];
    let mut pairs = Vec::with_capacity(disc.len());
    for (i, &x) in disc.iter().enumerate() {
        let nearest = (0..pad.len())
            .filter(|&j| !taken[j])
            .map(|j| (j, norm(sub(x, pad[j]))))
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        match nearest {
            Some((j, d)) if d <= tolerance => {
                taken[j] = true;
                pairs.push(PointPair {
                    disc_point: i,
                    pad_point: j,
                    distance: d,
                });
            }
            other => {
                return Err(ReduceError::NoPartner {
                    point: i + 1,
                    position: x,
                    nearest: other.map_or(f64::INFINITY, |o| o.1),
                    tolerance,
                });
            }
        }
    }
    Ok((pairs, tolerance))
}

/// The coordinate axis the unit `a` is along (other components within 1e-12), if any.
pub(super) fn coordinate_axis(a: [f64; 3]) -> Option<usize> {
    (0..3).find(|&d| (0..3).all(|e| e == d || a[e].abs() <= 1e-12))
}
