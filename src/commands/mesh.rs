//! `squeal mesh info` and `squeal mesh convert`.

use anyhow::{Result, bail};
use clap::Subcommand;
use squeal_pipeline::mesh_info::ReadMesh;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

#[derive(Subcommand)]
pub enum MeshCommand {
    /// Nodes, elements, sets, materials, volume and quality findings of each mesh; with
    /// --scene, the sets and materials a scene selects on its meshes
    Info {
        /// Mesh files (.inp or .msh)
        #[arg(required_unless_present = "scene", conflicts_with = "scene")]
        files: Vec<PathBuf>,
        /// List what a scene selects on its meshes ([sets], [units], [materials]): counts,
        /// areas and centroids of each set
        #[arg(long)]
        scene: Option<PathBuf>,
        /// With --scene: write both parts with the selected sets as point flags (.vtu, for
        /// ParaView)
        #[arg(long, requires = "scene")]
        vtu: Option<PathBuf>,
        /// List every id of each finding instead of the first few
        #[arg(long)]
        all_ids: bool,
        #[command(flatten)]
        materials: crate::commands::fe::MaterialArgs,
        #[command(flatten)]
        units: crate::commands::fe::UnitsArg,
    },
    /// Write a mesh as VTK XML (.vtu) for ParaView, with node and element sets as flags
    Convert {
        /// Input mesh (.inp or .msh)
        input: PathBuf,
        /// Output file (.vtu)
        output: PathBuf,
    },
}

pub fn run(cmd: MeshCommand) -> Result<ExitCode> {
    match cmd {
        MeshCommand::Info {
            files,
            scene: Some(scene),
            vtu,
            materials,
            units,
            ..
        } => {
            debug_assert!(files.is_empty());
            if units.units.is_some() {
                bail!("--units does not go with --scene: the scene's [units] system says it");
            }
            if !materials.materials.is_empty() {
                bail!(
                    "--material does not go with --scene: give the materials in the scene's [materials.<SET>]"
                );
            }
            crate::commands::mesh_scene::info(&scene, vtu.as_deref())
        }
        MeshCommand::Info {
            files,
            all_ids,
            materials,
            units,
            ..
        } => {
            let units = units.system()?;
            let overrides = materials.overrides_in(&units)?;
            // Everything is read and checked before anything is printed: a bad file or a
            // --material that fits none of the meshes is an error, not a footnote.
            let mut read = Vec::with_capacity(files.len());
            for f in &files {
                let t = Instant::now();
                let mut mesh = read_mesh(f)?;
                for w in squeal_pipeline::mesh_info::read_in(f, &mut mesh, &units) {
                    eprintln!("warning: {w}");
                }
                read.push((f, mesh, t.elapsed()));
            }
            for (set, _) in &overrides {
                if !read
                    .iter()
                    .any(|(_, r, _)| r.mesh.element_set(set).is_some())
                {
                    let known: Vec<&str> = read
                        .iter()
                        .flat_map(|(_, r, _)| r.mesh.element_sets.keys().map(String::as_str))
                        .collect();
                    bail!(
                        "--material {set}=...: no element set {set} in {} (element sets: {})",
                        files
                            .iter()
                            .map(|f| f.display().to_string())
                            .collect::<Vec<_>>()
                            .join(", "),
                        if known.is_empty() {
                            "none".to_string()
                        } else {
                            known.join(", ")
                        }
                    );
                }
            }
            let mut any_error = false;
            for (k, (f, mesh, elapsed)) in read.iter().enumerate() {
                if k > 0 {
                    println!();
                }
                let (text, errors) = squeal_pipeline::mesh_info::summary_text(
                    f, mesh, *elapsed, all_ids, &overrides, &units,
                )?;
                print!("{text}");
                any_error |= errors;
            }
            // 4, not 2: clap exits 2 on a usage error.
            Ok(if any_error {
                ExitCode::from(4)
            } else {
                ExitCode::SUCCESS
            })
        }
        MeshCommand::Convert { input, output } => {
            let read = squeal_pipeline::mesh_info::convert(&input, &output)?;
            for w in &read.warnings {
                eprintln!("warning: {w}");
            }
            println!(
                "wrote {} ({} nodes, {} elements)",
                output.display(),
                read.mesh.num_nodes(),
                read.mesh.num_elements()
            );
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// Reads a mesh and prints the reader's warnings to stderr.
pub fn read_mesh(path: &Path) -> Result<ReadMesh> {
    let read = squeal_pipeline::mesh_info::read_mesh(path)?;
    for w in &read.warnings {
        eprintln!("warning: {w}");
    }
    Ok(read)
}
