//! The reduction on its own (`squeal reduce`): the Craig–Bampton reduced brake of a scene, or
//! of a disc and a pad given as meshes with the bundled layout, written to a `.rom` (and, on
//! request, its matrices as MatrixMarket files). The command line fills a [`ReduceRequest`]
//! from its flags and prints the [`Reduced`] it gets back; the order of the work, the checks
//! of the outputs and the files written are decided here.

use crate::error::{PipelineError, Result};
use crate::model::Log;
use crate::parts::{brake_inputs, load_parts};
use squeal_reduce::brake::{BrakeInputs, reduce_brake};
use squeal_reduce::interface::Axis;
use squeal_reduce::summary::summary_text;
use squeal_scene::Scene;
use std::path::{Path, PathBuf};
use std::time::Instant;

pub use squeal_eigs::Backend;
pub use squeal_fe::ElasticMaterial;
pub use squeal_reduce::brake::{DEFAULT_AUTO_FACTOR, ModeChoice};
pub use squeal_reduce::craig_bampton::Stage;
pub use squeal_reduce::rom::{InterfaceKind, ReducedModel};

/// A disc and a pad given as meshes, in the bundled layout (disc clamped on `CLAMP`, pad held
/// on `ABUTMENT`, pistons on `PISTON`, contact on `CONTACT`), turned to an axis.
#[derive(Clone, Debug)]
pub struct MeshPair {
    pub disc: PathBuf,
    pub pad: PathBuf,
    /// The disc's axis: a point on it and its direction.
    pub axis_point: [f64; 3],
    pub axis_direction: [f64; 3],
    /// The pistons' direction (the contact normal); `None`: the axis.
    pub normal: Option<[f64; 3]>,
    pub interface: InterfaceKind,
    pub modes: ModeChoice,
    /// The patch grid, radial × angular.
    pub grid: [usize; 2],
    /// Materials of element sets that replace the meshes' own (a Gmsh file carries none).
    pub materials: Vec<(String, ElasticMaterial)>,
}

/// What to reduce.
#[derive(Clone, Debug)]
pub enum ReduceSource {
    /// A scene file: its meshes, pads, sets, units, materials, rotation, interface and modes.
    Scene(PathBuf),
    /// Two meshes in the bundled layout.
    Meshes(MeshPair),
}

/// A reduction to run: what, with which eigensolver, and where the results go.
#[derive(Clone, Debug)]
pub struct ReduceRequest {
    pub source: ReduceSource,
    /// The `.rom` to write.
    pub output: PathBuf,
    pub backend: Backend,
    /// Keep the bases in the `.rom` (needed to put results back on the meshes).
    pub keep_basis: bool,
    /// Also write each part's reduced K and M as MatrixMarket files beside the `.rom`.
    pub export_mtx: bool,
}

/// A finished reduction: the model, what was written and the summary to show.
pub struct Reduced {
    pub model: ReducedModel,
    /// The reduction's summary (parts, modes, timings).
    pub summary: String,
    /// The `.rom` written and its size in bytes.
    pub output: PathBuf,
    pub bytes: u64,
    /// The MatrixMarket files written.
    pub exported: Vec<PathBuf>,
    /// The eigensolver that ran.
    pub backend: String,
}

/// Runs `request`: checks the outputs before any work (a `.rom`, over no input, in a folder
/// that can be written), reduces (telling `stage` as each part's stage starts), writes.
pub fn reduce(
    request: &ReduceRequest,
    log: Log,
    stage: &mut dyn FnMut(&str, Stage),
) -> Result<Reduced> {
    squeal_io::require_extension(&request.output, "rom", "the reduced model (.rom)")?;
    // A scene's meshes are read here, to choose their sets; the others by the reduction.
    let (inputs, loaded, scene_file) = match &request.source {
        ReduceSource::Scene(path) => {
            let scene = Scene::read(path)?;
            let parts = load_parts(&scene, log)?;
            let mut inputs = brake_inputs(&scene, &parts)?;
            inputs.backend = request.backend;
            inputs.keep_basis = request.keep_basis;
            (inputs, Some(parts), Some(path.as_path()))
        }
        ReduceSource::Meshes(pair) => (mesh_pair_inputs(pair, request)?, None, None),
    };
    // What each input is, named: `pad mesh` (`inboard pad mesh` with several pads), and a
    // further part's by its name (`caliper mesh`).
    let one_pad = inputs.pads.len() == 1;
    let labels: Vec<(&Path, String)> =
        std::iter::once((inputs.disc.mesh.as_path(), "disc mesh".into()))
            .chain(inputs.pads.iter().map(|p| {
                let what = match one_pad {
                    true => "pad mesh".to_string(),
                    false => format!("{} pad mesh", p.name),
                };
                (p.part.mesh.as_path(), what)
            }))
            .chain(
                inputs
                    .bodies
                    .iter()
                    .map(|b| (b.part.mesh.as_path(), format!("{} mesh", b.name))),
            )
            .collect();
    let mut read: Vec<(&Path, &str)> = labels.iter().map(|(p, w)| (*p, w.as_str())).collect();
    if let Some(path) = scene_file {
        read.push((path, "scene file"));
    }
    squeal_io::refuse_inputs(&request.output, &read)?;
    if let Some(dir) = request
        .output
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
    {
        squeal_io::check_writable(dir)?;
    }
    // Finished part reductions kept beside the output when another part fails, taken up by
    // the next run (squeal_reduce::brake::reduce_brake_keeping).
    let kept = squeal_reduce::brake::kept_dir(&request.output);
    let (model, report) = match loaded {
        Some(parts) => squeal_reduce::brake::reduce_brake_keeping(
            &inputs,
            parts.disc,
            parts
                .pads
                .into_iter()
                .chain(parts.bodies)
                .map(|p| p.1)
                .collect(),
            Some(&kept),
            stage,
        ),
        None => reduce_brake(&inputs, stage),
    }?;
    stage("brake", Stage::Write);
    let t = Instant::now();
    model
        .write(&request.output)
        .map_err(|error| PipelineError::Rom {
            path: request.output.clone(),
            error,
        })?;
    if let Err(e) = squeal_reduce::brake::forget_kept(&kept) {
        log(&format!("warning: cannot remove {}: {e}", kept.display()));
    }
    let exported = if request.export_mtx {
        export_mtx(&model, &request.output)?
    } else {
        Vec::new()
    };
    let summary = summary_text(&model, &report, t.elapsed());
    let backend = model
        .parts
        .first()
        .and_then(|p| p.info.build.as_ref())
        .map_or("?".to_string(), |b| b.backend.as_str().to_string());
    let bytes = std::fs::metadata(&request.output).map_or(0, |m| m.len());
    Ok(Reduced {
        model,
        summary,
        output: request.output.clone(),
        bytes,
        exported,
        backend,
    })
}

/// The reduction inputs of two meshes in the bundled layout.
fn mesh_pair_inputs(pair: &MeshPair, request: &ReduceRequest) -> Result<BrakeInputs> {
    let axis = Axis {
        origin: pair.axis_point,
        direction: pair.axis_direction,
    };
    let mut inputs = BrakeInputs::bundled(&pair.disc, &pair.pad)
        .about(axis, pair.normal.unwrap_or(pair.axis_direction))
        .map_err(|e| PipelineError::input("the axis and normal", e.to_string()))?;
    inputs.interface = pair.interface;
    inputs.backend = request.backend;
    inputs.keep_basis = request.keep_basis;
    inputs.modes = pair.modes;
    inputs.grid = pair.grid;
    for (set, material) in &pair.materials {
        let mut used = false;
        let (disc_part, pads) = (&mut inputs.disc, &mut inputs.pads);
        for (path, part) in [(&pair.disc, disc_part), (&pair.pad, &mut pads[0].part)] {
            if mesh_has_element_set(path, set)? {
                part.material_overrides.push((set.clone(), *material));
                used = true;
            }
        }
        if !used {
            return Err(PipelineError::input(
                "--material",
                format!("{set}=...: neither mesh has an element set named {set}"),
            ));
        }
    }
    inputs.validate()?;
    Ok(inputs)
}

/// Whether a mesh file has an element set (read only for the material overrides).
fn mesh_has_element_set(path: &Path, set: &str) -> Result<bool> {
    let read = squeal_mesh::read(path).map_err(|error| PipelineError::Mesh {
        path: path.to_path_buf(),
        error,
    })?;
    Ok(read.mesh.element_set(set).is_some())
}

/// The MatrixMarket files beside the `.rom`, named after it.
fn export_mtx(model: &ReducedModel, output: &Path) -> Result<Vec<PathBuf>> {
    let dir = output.parent().unwrap_or(Path::new(""));
    let stem = output
        .file_stem()
        .map_or("brake".into(), |s| s.to_string_lossy());
    squeal_reduce::export::write_matrix_market(model, dir, &stem).map_err(|error| {
        PipelineError::Rom {
            path: output.to_path_buf(),
            error,
        }
    })
}
