//! The scene's `[[dampers]]` on the reduced brake: each part's dampers projected by its
//! Craig–Bampton basis (`squeal_reduce::dampers`, `Ĉ = Tᵀ C T`), stacked as the parts' `K̂`
//! and `M̂` are ([`squeal_brake::assemble`]'s layout), into the brake's physical damping
//! matrix [`squeal_brake::Brake::c`]. The reference adds it to the modal damping once
//! (`squeal_brake::damping`), so every analysis of the model sees it.
//!
//! A damper changes no reduction: the `.rom` stays fresh when only `[[dampers]]` change, and
//! the meshes are read again (with the sets the scene chooses) to project them.

use crate::error::{PipelineError, Result};
use crate::model::{Log, Model};
use faer::Mat;
use squeal_reduce::dampers::{Damper, Spread, reduced_damping};
use squeal_scene::Scene;
use squeal_scene::springs::SpringSpread;

fn damper_error(message: impl std::fmt::Display) -> PipelineError {
    PipelineError::input("[[dampers]]", message)
}

/// Puts the scene's dampers into `model.brake.c` (nothing without any).
pub fn apply(scene: &Scene, model: &mut Model, log: Log) -> Result<()> {
    let specs = scene.dampers()?;
    if specs.is_empty() {
        return Ok(());
    }
    let parts = crate::parts::load_parts(scene, log)?;
    refuse_body_dampers(&specs, &parts)?;
    let n = model.brake.size();
    let mut c = Mat::<f64>::zeros(n, n);
    for (name, loaded) in parts.all() {
        let dampers = part_dampers(&specs, &parts, name);
        if dampers.is_empty() {
            continue;
        }
        let part = model
            .rom
            .part(name)
            .ok_or_else(|| damper_error(format!("the reduced model has no part {name}")))?;
        if part.info.mesh.sha256 != loaded.info.sha256 {
            return Err(damper_error(format!(
                "the {name}'s mesh {} is not the one its reduced model was made from: reduce again",
                loaded.info.path
            )));
        }
        let range = if name == "disc" {
            model.layout.disc.clone()
        } else {
            model
                .layout
                .pads
                .iter()
                .find(|p| p.0 == name)
                .map(|p| p.1.clone())
                .ok_or_else(|| damper_error(format!("the brake has no part {name}")))?
        };
        let cp = reduced_damping(&loaded.mesh, part, &dampers)
            .map_err(|e| damper_error(format!("the {name}: {e}")))?;
        if cp.nrows() != range.len() {
            return Err(damper_error(format!(
                "the {name}'s damping has {} dofs, its place in the brake {}",
                cp.nrows(),
                range.len()
            )));
        }
        for j in 0..cp.ncols() {
            for i in 0..cp.nrows() {
                c[(range.start + i, range.start + j)] += cp[(i, j)];
            }
        }
        log(&format!(
            "dampers: {} on the {name}, projected on its {} reduced dofs",
            dampers.len(),
            cp.nrows()
        ));
    }
    model.brake.c = Some(c);
    Ok(())
}

/// The scene's dampers on part `name`, their sets by the names chosen for them
/// ([`crate::parts::SceneParts::assembly_sets`]).
pub fn part_dampers(
    specs: &[squeal_scene::dampers::DamperSpec],
    parts: &crate::parts::SceneParts,
    name: &str,
) -> Vec<Damper> {
    let name_of = |key: &str| {
        parts
            .assembly_sets
            .iter()
            .find(|c| c.key == key)
            .map(|c| c.name.clone())
            .unwrap_or_default()
    };
    specs
        .iter()
        .filter(|d| d.part == name)
        .map(|d| Damper {
            set: name_of(&d.set.key),
            to: d.to.as_ref().map(|to| name_of(&to.key)),
            damping: d.damping,
            axes: d.axes,
            spread: match d.spread {
                SpringSpread::Mean => Spread::Mean,
                SpringSpread::Area => Spread::Area,
                SpringSpread::Normal => Spread::Normal,
            },
        })
        .collect()
}

/// Refuses a damper on a further part (`[parts.<name>]`): the brake's damping is projected on
/// the disc's and the pads' bases only, so it would be left out of every analysis.
fn refuse_body_dampers(
    specs: &[squeal_scene::dampers::DamperSpec],
    parts: &crate::parts::SceneParts,
) -> Result<()> {
    match specs
        .iter()
        .find(|d| parts.bodies.iter().any(|b| b.0 == d.part))
    {
        Some(d) => Err(damper_error(format!(
            "a damper on the further part {} (dampers.part = \"{}\"): dampers are projected on the disc's and the pads' Craig–Bampton bases only, so it would be left out of the model; put it on the disc or a pad, or leave it out",
            d.part, d.part
        ))),
        None => Ok(()),
    }
}
