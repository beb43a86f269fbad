//! The scene's `[parts.<name>]` (a caliper, a bracket) and `[[connectors]]` as reduction
//! inputs: each further part read in the scene's units, each connector's sets kept as coupling
//! points of their parts (six mean-motion dofs each, `squeal_reduce::coupling`).
//!
//! Two sets of a pad change meaning when a connector names them:
//!
//! - its load set (`load`, the pistons or fingers): the pad's load point becomes the set's mean
//!   motion (instead of its nodes' or footprints' normal dofs), the clamp force acts there, and
//!   the connector carries it: its other end (the caliper's bore or fingers) is pushed back;
//! - its abutments (`abutments`): the pad is no longer held there; the connector to the
//!   bracket holds it, with the stiffness it gives (0 along the axis: a free slide).

use super::*;
use squeal_reduce::brake::PadInput;
use squeal_reduce::coupling::{ConnectionInput, CouplingSet};

/// Reads the scene's `[parts.<name>]` meshes (their element sets of their files) in `units`,
/// the readers' warnings to `log`.
pub(super) fn load_bodies(
    scene: &Scene,
    units: &UnitSystem,
    log: Log,
) -> Result<Vec<(String, LoadedPart)>> {
    let mut out = Vec::new();
    for (name, path) in scene.bodies() {
        let loaded = load_part_of(&scene.resolve(&path), &scene.body_elset(&name), units)?;
        for w in &loaded.warnings {
            log(&format!("warning: {name}: {w}"));
        }
        out.push((name, loaded));
    }
    Ok(out)
}

/// The error of connector `name`.
fn connector_error(scene: &Scene, name: &str, message: impl std::fmt::Display) -> PipelineError {
    PipelineError::Input {
        what: "scene connectors",
        message: format!("{}: {name}: {message}", scene.path.display()),
    }
}

/// Adds the scene's further parts and its connectors to `inputs` (module docs).
pub fn add_bodies(scene: &Scene, parts: &SceneParts, inputs: &mut BrakeInputs) -> Result<()> {
    for (name, loaded) in &parts.bodies {
        let mut part = PartInput::pad(loaded.info.path.clone());
        part.mesh = scene.resolve(
            &scene
                .bodies()
                .into_iter()
                .find(|b| b.0 == *name)
                .map(|b| b.1)
                .unwrap_or_default(),
        );
        part.restraints.clear();
        part.contact_set.clear();
        part.contact_face_set.clear();
        part.piston_set = None;
        part.elset = scene.body_elset(name);
        part.units = parts.units;
        part.material_overrides = overrides_for(&parts.materials, &loaded.mesh);
        inputs.bodies.push(PadInput {
            name: name.clone(),
            part,
        });
    }
    let name_of = |key: &str| {
        parts
            .assembly_sets
            .iter()
            .find(|c| c.key == key)
            .map(|c| c.name.clone())
            .unwrap_or_default()
    };
    let count = inputs.pads.len();
    // Each pad's load set and abutments, as chosen (before any connector changes them).
    let loads: Vec<(String, Option<String>)> = inputs
        .pads
        .iter()
        .map(|p| (p.name.clone(), p.part.piston_set.clone()))
        .collect();
    let abutments: Vec<(String, String)> = inputs
        .pads
        .iter()
        .enumerate()
        .filter_map(|(i, p)| {
            pad_set(&parts.sets, &p.name, 2, i, count).map(|c| (p.name.clone(), c.name.clone()))
        })
        .collect();
    let is_load = |end: &(String, String)| {
        loads
            .iter()
            .any(|(p, s)| *p == end.0 && s.as_deref() == Some(end.1.as_str()))
    };
    for c in scene.connectors()? {
        let mut a = (c.part.clone(), name_of(&c.set.key));
        let mut b = c.to.as_ref().map(|(p, r)| (p.clone(), name_of(&r.key)));
        if b.as_ref().is_some_and(&is_load) {
            std::mem::swap(&mut a, b.as_mut().expect("checked just above"));
        }
        let load = is_load(&a);
        if load && b.is_none() {
            return Err(connector_error(
                scene,
                &c.name,
                format!(
                    "it holds the {}'s load set {} to ground: the clamp force pushes the pad there and needs another part to push back (give to_part and to_set, e.g. the caliper's bore)",
                    a.0, a.1
                ),
            ));
        }
        for (end, load) in std::iter::once((&a, load)).chain(b.iter().map(|e| (e, false))) {
            let Some(part) = part_mut(inputs, &end.0) else {
                continue;
            };
            if !part.couplings.iter().any(|k| k.set == end.1) {
                part.couplings.push(CouplingSet {
                    set: end.1.clone(),
                    load,
                    nodal: false,
                });
            }
            if load {
                part.piston_set = None;
                part.piston_footprints.clear();
            }
            if abutments.iter().any(|x| x.0 == end.0 && x.1 == end.1) {
                part.restraints
                    .retain(|r| r.nodes != NodeSelection::Set(end.1.clone()));
                part.skew_restraints.retain(|r| r.0 != end.1);
                part.axis_restraints.retain(|r| r.0 != end.1);
            }
        }
        inputs.connections.push(ConnectionInput {
            name: c.name.clone(),
            a,
            b,
            stiffness: c.stiffness,
            rotational: c.rotational,
            axes: c.axes,
            load,
            vibration_only: c.vibration_only,
        });
    }
    Ok(())
}

/// Keeps both sets of a tie between parts node by node in their parts' reductions (`nodal`
/// coupling sets, [`squeal_reduce::part_tie`]).
pub(super) fn keep_tie_sets(inputs: &mut BrakeInputs, tie: &squeal_reduce::part_tie::PartTieInput) {
    for (part, set) in [&tie.slave, &tie.master] {
        if let Some(p) = part_mut(inputs, part)
            && !p.couplings.iter().any(|k| k.set == *set && k.nodal)
        {
            p.couplings.push(CouplingSet {
                set: set.clone(),
                load: false,
                nodal: true,
            });
        }
    }
}
