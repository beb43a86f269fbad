//! `--mic x,y,z`: the microphones of `squeal branch`, `squeal chbm` and `squeal run`, in
//! metres in the meshes' frame, repeatable, in place of the default microphone
//! ([`squeal_pipeline::sound::default_microphone`]).

use anyhow::Result;
use squeal_pipeline::Pipeline;

/// The help text of `--mic`.
pub const HELP: &str = "Microphone position x,y,z in metres in the meshes' frame (repeat for more; default: 0.5 m from the disc's centre, 45 degrees off its axis towards the pad)";

/// Puts the microphones into `p` after checking them against its brake (before any long
/// computation: the reduced model is built or read, the meshes read).
pub fn apply(p: &mut Pipeline, mics: &[[f64; 3]]) -> Result<()> {
    if mics.is_empty() {
        return Ok(());
    }
    let m = p.model()?;
    squeal_pipeline::sound::check_microphones(&p.scene, m, mics, p.log())?;
    p.sound.microphones = mics.to_vec();
    Ok(())
}
