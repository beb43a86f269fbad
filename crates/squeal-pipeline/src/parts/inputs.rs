//! The reduction's inputs from the scene and the chosen sets: each part's restraints, contact points and pistons, and the pads' pairing with the disc.

use super::*;

/// The reduction inputs of a scene on its parts: the bundled layout (disc clamped, pad held
/// in plane on its abutments with the pistons' normal dof kept) with the chosen sets, the
/// scene's materials and units, interface and mode count.
///
/// Pistons chosen as faces (footprints such as `circles`) are each reduced to one coordinate,
/// the area-weighted mean motion of the footprint along the normal, on which the piston's
/// share of the clamp force acts (spread over the footprint by area); pistons picked one node
/// each (`points`) and a node set's nodes keep their nodes' normal dofs. A piece of a load
/// rule with several nodes but no boundary face (a union of node sets without faces) is
/// refused: a footprint needs faces to spread its load over.
pub fn brake_inputs(scene: &Scene, parts: &SceneParts) -> Result<BrakeInputs> {
    for c in parts.sets.iter() {
        if footprint_names(c).is_none() {
            continue;
        }
        if let Some((k, p)) = c
            .pieces
            .iter()
            .enumerate()
            .find(|(_, p)| p.nodes.len() > 1 && p.faces.is_empty())
        {
            return Err(set_error(
                &c.key,
                match &c.origin {
                    Origin::Scene(at) => at,
                    _ => "scene",
                },
                format!(
                    "piston {} selects {} nodes but no boundary face: a piston's footprint is the faces it presses on (e.g. circles = [{{ centre = [x, y, z], diameter = d }}, ...] with facing), or give piston points (a node set, or points = [[x, y, z], ...])",
                    k + 1,
                    p.nodes.len()
                ),
            ));
        }
    }
    let mut inputs = crate::model::brake_inputs(scene)?;
    let name = |key: &str| parts.set(key).map(|c| c.name.clone()).unwrap_or_default();
    let clamp = name("sets.disc.clamp");
    inputs.disc.restraints = vec![Restraint::clamp(&clamp)];
    if let Some(hold) = scene.clamp_hold()? {
        apply_hold(&mut inputs.disc, &clamp, &hold);
    }
    inputs.disc.material_overrides = overrides_for(&parts.materials, &parts.disc.mesh);
    inputs.disc.units = parts.units;
    let count = inputs.pads.len();
    inputs.disc.extra_surfaces.clear();
    for (i, pad) in inputs.pads.iter_mut().enumerate() {
        let chosen = |k: usize| pad_set(&parts.sets, &pad.name, k, i, count);
        let key = |k: usize| chosen(k).map(|c| c.name.clone()).unwrap_or_default();
        let p = &mut pad.part;
        p.contact_face_set = key(0);
        p.piston_set = Some(key(1));
        p.piston_footprints = chosen(1).and_then(footprint_names).unwrap_or_default();
        // The abutments stay held as `model::brake_inputs` holds `ABUTMENT`: in the plane
        // normal to the disc's axis (in skew node axes when the axis is skew), now on the
        // chosen nodes.
        let abutments = key(2);
        for r in &mut p.restraints {
            if r.nodes == NodeSelection::Set("ABUTMENT".into()) {
                r.nodes = NodeSelection::Set(abutments.clone());
            }
        }
        for (set, _) in &mut p.skew_restraints {
            if set == "ABUTMENT" {
                set.clone_from(&abutments);
            }
        }
        if let Some(hold) = scene.abutments_hold(&pad.name)? {
            apply_hold(p, &abutments, &hold);
        }
        if let Some((_, loaded)) = parts.pads.iter().find(|(n, _)| *n == pad.name) {
            p.material_overrides = overrides_for(&parts.materials, &loaded.mesh);
        }
        p.units = parts.units;
        let disc_face = key(3);
        let disc_contact = disc_contact_set(scene, &pad.name, i);
        if i == 0 {
            inputs.disc.contact_face_set = disc_face;
            inputs.disc.contact_set = disc_contact;
            inputs.disc.facing = (count > 1).then(|| pad.name.clone());
        } else {
            inputs.disc.extra_surfaces.push(ContactSurface {
                facing: Some(pad.name.clone()),
                contact_set: disc_contact,
                contact_face_set: disc_face,
            });
        }
    }
    inputs.grid = scene.patch_grid()?;
    add_bodies(scene, parts, &mut inputs)?;
    add_supports_and_ties(scene, parts, &mut inputs)?;
    Ok(inputs)
}

/// The scene's `[[supports]]`, `[[ties]]` and `[[springs]]` on their parts, by the node sets chosen for them
/// ([`SceneParts::assembly_sets`]).
fn add_supports_and_ties(
    scene: &Scene,
    parts: &SceneParts,
    inputs: &mut BrakeInputs,
) -> Result<()> {
    let name_of = |key: &str| {
        parts
            .assembly_sets
            .iter()
            .find(|c| c.key == key)
            .map(|c| c.name.clone())
            .unwrap_or_default()
    };
    for s in scene.supports()? {
        if let Some(p) = part_mut(inputs, &s.part) {
            p.supports.push(squeal_reduce::tie::Support {
                set: name_of(&s.set.key),
                stiffness: s.stiffness,
            });
        }
    }
    for t in scene.ties()? {
        if let Some(master_part) = &t.master_part {
            let tie = squeal_reduce::part_tie::PartTieInput {
                slave: (t.part.clone(), name_of(&t.slave.key)),
                master: (master_part.clone(), name_of(&t.master.key)),
                tolerance: t.tolerance,
            };
            super::bodies::keep_tie_sets(inputs, &tie);
            // A pad tied on its abutments is held there by the tie, not by their restraint.
            let count = inputs.pads.len();
            for (i, pad) in inputs.pads.iter_mut().enumerate() {
                let abutments = pad_set(&parts.sets, &pad.name, 2, i, count).map(|c| &c.name);
                for (part, set) in [&tie.slave, &tie.master] {
                    if *part == pad.name && abutments == Some(set) {
                        pad.part
                            .restraints
                            .retain(|r| r.nodes != NodeSelection::Set(set.clone()));
                        pad.part.skew_restraints.retain(|r| r.0 != *set);
                        pad.part.axis_restraints.retain(|r| r.0 != *set);
                    }
                }
            }
            inputs.part_ties.push(tie);
            continue;
        }
        if let Some(p) = part_mut(inputs, &t.part) {
            p.ties.push(squeal_reduce::tie::Tie {
                slave: name_of(&t.slave.key),
                master: name_of(&t.master.key),
                tolerance: t.tolerance,
            });
        }
    }
    for s in scene.springs()? {
        if let Some(p) = part_mut(inputs, &s.part) {
            p.springs.push(squeal_reduce::springs::Spring {
                set: name_of(&s.set.key),
                to: s.to.as_ref().map(|to| name_of(&to.key)),
                stiffness: s.stiffness,
                axes: s.axes,
                spread: match s.spread {
                    squeal_scene::springs::SpringSpread::Mean => {
                        squeal_reduce::springs::Spread::Mean
                    }
                    squeal_scene::springs::SpringSpread::Area => {
                        squeal_reduce::springs::Spread::Area
                    }
                    squeal_scene::springs::SpringSpread::Normal => {
                        squeal_reduce::springs::Spread::Normal
                    }
                },
            });
        }
    }
    Ok(())
}

/// The chosen set `k` of [`PAD_SETS`] of pad `pad`, the `index`-th of `count`: chosen under
/// its own key (`pad_key`, or its `[pads.<pad>]` key), or under the shared key ([sets.pad] for
/// every pad; [sets.disc] contact_face for the first pad's disc face only).
pub(super) fn pad_set<'a>(
    sets: &'a [ChosenSet],
    pad: &str,
    k: usize,
    index: usize,
    count: usize,
) -> Option<&'a ChosenSet> {
    let part = if k == 3 { "disc" } else { pad };
    let own = format!("pads.{pad}.{}", PAD_SETS[k].1);
    sets.iter().filter(|c| c.part == part).find(|c| {
        c.key == pad_key(k, pad, count)
            || c.key == own
            || (c.key == PAD_SETS[k].0 && (k < 3 || index == 0))
    })
}

/// The disc's node set of contact points under pad `pad`, the `index`-th (node interface):
/// its `[pads.<pad>] disc_contact`, else `CONTACT` for the first pad and `CONTACT_<PAD>` for
/// the others.
pub(super) fn disc_contact_set(scene: &Scene, pad: &str, index: usize) -> String {
    match scene
        .file
        .pads
        .get(pad)
        .and_then(|t| t.disc_contact.as_ref())
    {
        Some(c) => c.get_ref().clone(),
        None if index == 0 => "CONTACT".into(),
        None => format!("CONTACT_{}", pad.to_uppercase()),
    }
}

/// Holds node set `set` of `part` in the directions `hold` instead of its present restraints:
/// global directions along a coordinate axis (to 1e-12) as a plain restraint, other global
/// directions exactly in skew node axes, directions relative to the disc's axis (axial,
/// radial, tangential at each node) likewise; all three axis directions are the plain clamp.
pub fn apply_hold(part: &mut PartInput, set: &str, hold: &[Hold]) {
    part.restraints
        .retain(|r| r.nodes != NodeSelection::Set(set.into()));
    part.skew_restraints.retain(|r| r.0 != set);
    part.axis_restraints.retain(|r| r.0 != set);
    let mut plain = [false; 3];
    let mut skew = Vec::new();
    let mut axis = Vec::new();
    for h in hold {
        match *h {
            Hold::Axial => axis.push(AxisDirection::Axial),
            Hold::Radial => axis.push(AxisDirection::Radial),
            Hold::Tangential => axis.push(AxisDirection::Tangential),
            Hold::Global(d) => {
                match (0..3).find(|&k| (0..3).all(|e| e == k || d[e].abs() <= 1e-12)) {
                    Some(k) => plain[k] = true,
                    None => skew.push(d),
                }
            }
        }
    }
    axis.sort_by_key(|a| *a as u8);
    axis.dedup();
    if axis.len() == 3 {
        plain = [true; 3];
        axis.clear();
    }
    if plain.iter().any(|&p| p) {
        part.restraints.push(Restraint::set(set, plain));
    }
    if !skew.is_empty() {
        part.skew_restraints.push((set.to_string(), skew));
    }
    if !axis.is_empty() {
        part.axis_restraints.push((set.to_string(), axis));
    }
}

/// The node interface's contact points where a mesh has no node set of them: on each contact
/// face (the disc's under each pad, each pad's friction face) the face's node nearest each
/// patch centroid of the `[sets] patch_grid` about the rotation axis, in patch order, added
/// to the mesh as the set the reduction reads (`CONTACT`, or `CONTACT_<NAME>` on the disc
/// under a further pad, or the pad's `disc_contact`). Returns them as chosen sets.
pub(super) fn contact_points_by_geometry(
    scene: &Scene,
    sets: &[ChosenSet],
    disc: &mut Mesh,
    pads: &mut [(&str, &mut Mesh)],
) -> Result<Vec<ChosenSet>> {
    let axis = crate::model::scene_axis(scene)?;
    let grid = scene.patch_grid()?;
    let count = pads.len();
    let mut out = Vec::new();
    for i in 0..count {
        let name = pads[i].0.to_string();
        let face = |k: usize| pad_set(sets, &name, k, i, count).map(|c| c.name.clone());
        let jobs: [(&str, Option<String>, String); 2] = [
            ("disc", face(3), disc_contact_set(scene, &name, i)),
            (name.as_str(), face(0), "CONTACT".into()),
        ];
        for (part, face, contact) in jobs {
            let mesh: &mut Mesh = if part == "disc" {
                &mut *disc
            } else {
                &mut *pads[i].1
            };
            let Some(face) = face else { continue };
            if mesh.node_set(&contact).is_some() {
                continue;
            }
            let key = if count == 1 {
                format!(
                    "sets.{}.contact",
                    if part == "disc" { "disc" } else { "pad" }
                )
            } else if part == "disc" {
                format!("pads.{name}.disc_contact")
            } else {
                format!("pads.{name}.contact")
            };
            let nodes = nearest_to_patches(mesh, &face, grid, &axis)
                .map_err(|e| set_error(&key, "default", e))?;
            mesh.node_sets.insert(contact.clone(), nodes.clone());
            out.push(ChosenSet {
                part: part.to_string(),
                key,
                name: contact,
                origin: Origin::Default,
                description: format!(
                    "the nodes of {face} nearest its {} x {} patch centroids",
                    grid[0], grid[1]
                ),
                by_geometry: true,
                pieces: vec![Selection {
                    nodes,
                    faces: Vec::new(),
                }],
            });
        }
    }
    Ok(out)
}

/// The node of face set `face` nearest each patch centroid of the `grid` about `axis`, in
/// patch order; an error when two patches share their nearest node (a grid finer than the
/// face's nodes).
pub(super) fn nearest_to_patches(
    mesh: &Mesh,
    face: &str,
    grid: [usize; 2],
    axis: &squeal_reduce::interface::Axis,
) -> std::result::Result<Vec<u32>, String> {
    let patches = squeal_reduce::interface::patches(mesh, face, grid[0], grid[1], axis)
        .map_err(|e| e.to_string())?;
    let candidates = mesh
        .node_set(face)
        .ok_or_else(|| format!("no node set {face}"))?;
    let mut out: Vec<u32> = Vec::with_capacity(patches.len());
    for p in &patches {
        let d = |n: u32| {
            let x = mesh.nodes[n as usize];
            (0..3).map(|k| (x[k] - p.centroid[k]).powi(2)).sum::<f64>()
        };
        let best = candidates
            .iter()
            .copied()
            .min_by(|&a, &b| d(a).total_cmp(&d(b)).then(a.cmp(&b)))
            .ok_or_else(|| format!("{face} has no nodes"))?;
        if out.contains(&best) {
            return Err(format!(
                "patches of the {} x {} grid share their nearest node: the grid is finer than the face's nodes",
                grid[0], grid[1]
            ));
        }
        out.push(best);
    }
    Ok(out)
}

/// The part named `name` of `inputs` (`disc`, a pad's or a body's name).
pub(super) fn part_mut<'a>(
    inputs: &'a mut BrakeInputs,
    name: &str,
) -> Option<&'a mut squeal_reduce::brake::PartInput> {
    if name == "disc" {
        return Some(&mut inputs.disc);
    }
    inputs
        .pads
        .iter_mut()
        .chain(inputs.bodies.iter_mut())
        .find(|p| p.name == name)
        .map(|p| &mut p.part)
}
