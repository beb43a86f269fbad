//! Whether the scene's restraints hold every part, checked before any reduction work: the
//! rigid-body motions a part's restraints leave free ([`squeal_reduce::held`]: the null space
//! of the restraint and boundary rows on the six rigid-body motions), named with the scene
//! keys that set those restraints and what to add there.
//!
//! Without it an under-restrained pad failed at the factorization of its interior stiffness,
//! after the disc's reduction (whose result was thrown away), with no motion named.

use crate::error::{PipelineError, Result};
use crate::parts::{ChosenSet, Origin, SceneParts, pad_key};
use squeal_reduce::ReduceError;
use squeal_reduce::brake::BrakeInputs;
use squeal_reduce::held::not_held;
use squeal_scene::Scene;

/// Refuses the first part of `inputs` (disc, then the pads) whose restraints and boundary
/// coordinates leave a rigid-body motion free: the message names the motions (axis and a point
/// of it), the scene keys that hold the part (with their `file:line`) and what to add.
pub fn check_held(scene: &Scene, parts: &SceneParts, inputs: &BrakeInputs) -> Result<()> {
    let loaded = parts.all();
    for ((name, input), (_, part)) in inputs.parts().into_iter().zip(loaded) {
        let spec = inputs.spec(name, input, part.info.clone());
        let free = squeal_reduce::brake::free_motions_coupled(&part.mesh, &spec, &input.couplings)
            .map_err(|e| ReduceError::InMesh {
                path: input.mesh.clone(),
                error: Box::new(e),
            })?;
        if free.is_empty() {
            continue;
        }
        let shown = not_held(&spec, &free);
        return Err(PipelineError::Input {
            what: "scene restraints",
            message: format!(
                "{}: {}: {shown}. In the scene: {}",
                scene.path.display(),
                input.mesh.display(),
                scene_hint(name, parts, inputs.pads.len())
            ),
        });
    }
    Ok(())
}

/// Where a chosen set comes from, for the message.
fn origin(c: &ChosenSet) -> String {
    match &c.origin {
        Origin::Scene(at) => format!("{} ({at})", c.key),
        Origin::Mesh => format!("{} (the mesh's node set {})", c.key, c.name),
        Origin::Default => format!("{} (default: {})", c.key, c.description),
    }
}

/// The keys that hold part `name` and what to add to them.
fn scene_hint(name: &str, parts: &SceneParts, pads: usize) -> String {
    if name == "disc" {
        let clamp = parts
            .set("sets.disc.clamp")
            .map_or("sets.disc.clamp".into(), origin);
        return format!(
            "the disc is held by {clamp}, in the directions of sets.disc.clamp_hold (all by default): clamp a set that holds the motions above (a hub face or bolt circle), or let clamp_hold hold all three directions"
        );
    }
    let key = |k: usize| {
        parts
            .set(&pad_key(k, name, pads))
            .or_else(|| parts.set(&pad_key(k, name, 1)))
            .map_or(pad_key(k, name, pads), origin)
    };
    let hold = if pads == 1 {
        "sets.pad.abutments_hold".to_string()
    } else {
        format!("pads.{name}.abutments_hold")
    };
    format!(
        "the {name} is held by {} in the directions of {hold} (radial and tangential by default) and pressed by {}; give the pistons as several footprints or points (circles = [...] or points = [...], one per piston, away from the axes above), or hold abutments away from those axes along the axis too ({hold} = [\"axial\", \"radial\", \"tangential\"]), or back the pad with a stiffness over a face ([[supports]], or [[springs]] with spread = \"area\")",
        key(2),
        key(1)
    )
}
