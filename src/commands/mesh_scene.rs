//! `squeal mesh info --scene scene.toml [--vtu sets.vtu]`: what a scene selects on its meshes
//! (the sets of `[sets]`, by name, by geometry or by default; the unit system; the materials
//! by element set), with counts, areas and centroids, and a VTU of both parts with each
//! selected set as a point flag for ParaView.

use anyhow::Result;
use squeal_pipeline::parts::load_parts;
use squeal_pipeline::scene_sets;
use squeal_scene::Scene;
use std::path::Path;
use std::process::ExitCode;

pub fn info(path: &Path, vtu: Option<&Path>) -> Result<ExitCode> {
    let scene = Scene::read(path)?;
    if let Some(v) = vtu {
        scene_sets::check_vtu_output(&scene, v)?;
    }
    let parts = load_parts(&scene, &|m: &str| eprintln!("{m}"))?;
    print!("{}", scene_sets::text(path, &parts));
    if let Some(v) = vtu {
        scene_sets::write_vtu(&parts, v)?;
        println!(
            "wrote {} (both parts; each set as the point flag set:<part>:<key>, each part as the cell flag set:<part>)",
            v.display()
        );
    }
    Ok(ExitCode::SUCCESS)
}
