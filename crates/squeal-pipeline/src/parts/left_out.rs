//! Where the further parts (`[parts.<name>]`: a caliper, a bracket) are not carried yet, said
//! in the output rather than left out silently: the pictures and VTU files draw the disc and
//! the pads only, the sound radiates from them only, and a mesh study moves only their meshes
//! from level to level. Each is a warning line (the result stands for the disc and the pads,
//! which is what it says) or a refusal (a study whose levels would not be what they claim).

use crate::error::{PipelineError, Result};
use squeal_reduce::rom::ReducedModel;

/// The further parts' names of a reduced model, joined for a message (`caliper, bracket`);
/// `None` without any.
fn names(rom: &ReducedModel) -> Option<String> {
    let bodies: Vec<&str> = rom.bodies().iter().map(|p| p.info.name.as_str()).collect();
    (!bodies.is_empty()).then(|| bodies.join(", "))
}

/// The warning of `what` (e.g. `the pictures and VTU files`) leaving out the further parts of
/// `rom`, `None` without any.
pub fn left_out(rom: &ReducedModel, what: &str) -> Option<String> {
    names(rom).map(|n| {
        format!(
            "warning: {what} leave out the further parts ({n}): they carry the disc and the pads only"
        )
    })
}

/// Refuses a mesh study of a scene with further parts: the levels move the disc's and the
/// pads' meshes only, the further parts would stay on the scene's own mesh at every level.
pub fn refuse_levels(scene: &squeal_scene::Scene) -> Result<()> {
    let bodies: Vec<String> = scene
        .bodies()
        .into_iter()
        .map(|(n, _)| format!("[parts.{n}]"))
        .collect();
    match bodies.is_empty() {
        true => Ok(()),
        false => Err(PipelineError::input(
            "--kind mesh",
            format!(
                "{}: a mesh study moves the disc's and the pads' meshes from level to level, not those of {}, which would stay on the scene's mesh at every level: study the scene without them",
                scene.path.display(),
                bodies.join(", ")
            ),
        )),
    }
}
