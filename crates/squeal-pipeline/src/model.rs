//! From a scene to the objects of the analyses: the reduced model (cached in a `.rom` file and
//! rebuilt when its meshes or options change), the brake of eq (11) with its contact elements,
//! its damping and the band its results are valid in.
//!
//! The scene's values become model parameters here: the contact stiffnesses per unit area of
//! eq (8) (given, or fitted to the pad's compression curve by [`squeal_scene::fit_cubic`]),
//! the piston force (line pressure × piston area), and the valid band (up to the lower of the
//! parts' highest kept fixed-interface frequencies).

use crate::error::{PipelineError, Result};
use squeal_brake::Brake;
use squeal_brake::analysis::{DampingSpec, PairChoice};
use squeal_brake::assemble::{BrakeParams, Layout, Pairing, Stiffness, assemble};
use squeal_brake::sweep::{Band, SweepOptions};
use squeal_chbm::physics::DiscSpeed;
use squeal_mesh::Mesh;
use squeal_mesh::units::UnitSystem;
use squeal_reduce::brake::{
    BrakeInputs, Freshness, ModeChoice, PairingTolerance, freshness, reduce_brake_loaded,
};
use squeal_reduce::craig_bampton::Stage;
use squeal_reduce::rom::{InterfaceKind, ReducedModel};
use squeal_scene::Scene;
use std::path::{Path, PathBuf};

/// Everything an analysis of the scene needs.
pub struct Model {
    pub rom: ReducedModel,
    pub rom_path: PathBuf,
    pub brake: Brake,
    pub layout: Layout,
    pub pairs: Vec<Pairing>,
    pub params: BrakeParams,
    pub damping: DampingSpec,
    pub sweep: SweepOptions,
    /// Meshes of the parts, as files.
    pub disc_mesh: PathBuf,
    pub pad_mesh: PathBuf,
    /// The disc's rotation from the scene's `[disc]`, for the sliding check of every cycle.
    pub disc: Option<DiscSpeed>,
    /// The unit system the mesh files are written in (`[units]`): [`Model::read_mesh`]
    /// converts them to SI.
    pub units: UnitSystem,
}

impl Model {
    /// A part's mesh file read and converted to SI, its reader's warnings passed to `log`.
    pub fn read_mesh(&self, path: &Path, log: Log) -> Result<Mesh> {
        let mut mesh = read_mesh(path, log)?;
        self.units.to_si(&mut mesh);
        Ok(mesh)
    }
}

/// What the pipeline tells its caller while it works (the CLI prints it).
pub type Log<'a> = &'a (dyn Fn(&str) + Sync);

/// A log that says nothing.
pub fn quiet(_: &str) {}

/// The reduction inputs of a scene before its meshes are read: the bundled layout (disc
/// clamped on `CLAMP`, pad held in plane on `ABUTMENT`, pistons on `PISTON`, contact on
/// `CONTACT` / `CONTACT_FACE`) on the scene's meshes, interface and mode count.
/// [`crate::parts::brake_inputs`] puts in the sets, materials and units of the scene.
pub fn brake_inputs(scene: &Scene) -> BrakeInputs {
    let m = &scene.file.model;
    let mut inputs = BrakeInputs::bundled(scene.resolve(&m.disc), scene.resolve(&m.pad));
    inputs.interface = if m.interface.get_ref() == "node" {
        InterfaceKind::Node
    } else {
        InterfaceKind::Patch
    };
    inputs.modes = ModeChoice::Fixed(*m.modes.get_ref());
    inputs
}

/// Where the scene's reduced model is kept: its `[model] rom`, else `<out>/brake.rom`.
pub fn rom_path(scene: &Scene, out: &Path) -> PathBuf {
    match &scene.file.model.rom {
        Some(p) => scene.resolve(p),
        None => out.join("brake.rom"),
    }
}

/// Checks the outputs of a scene before any work: `out` is a folder that can be written (made
/// if missing), and the reduced model's file ends in `.rom` and is neither the scene nor one
/// of its meshes.
pub fn check_outputs(scene: &Scene, out: &Path) -> Result<()> {
    squeal_io::require_folder(out)?;
    let rom = rom_path(scene, out);
    squeal_io::require_extension(&rom, "rom", "the reduced model (.rom)")?;
    let m = &scene.file.model;
    let (disc, pad) = (scene.resolve(&m.disc), scene.resolve(&m.pad));
    squeal_io::refuse_inputs(
        &rom,
        &[
            (&scene.path, "scene file"),
            (&disc, "disc mesh"),
            (&pad, "pad mesh"),
        ],
    )?;
    squeal_io::check_writable(out)?;
    if let Some(dir) = rom.parent().filter(|d| !d.as_os_str().is_empty()) {
        squeal_io::check_writable(dir)?;
    }
    Ok(())
}

/// Loads the scene's reduced model, or reduces the meshes (and stores the result) when it is
/// missing or stale (other meshes, by SHA-256, other options, another tool version).
pub fn reduced_model(scene: &Scene, out: &Path, log: Log) -> Result<(ReducedModel, PathBuf)> {
    let rom_path = rom_path(scene, out);
    let parts = crate::parts::load_parts(scene, log)?;
    let inputs = crate::parts::brake_inputs(scene, &parts)?;
    match freshness(&rom_path, &inputs)? {
        Freshness::Fresh => match ReducedModel::read(&rom_path) {
            Ok(rom) => {
                log(&format!(
                    "reduced model: {} (up to date)",
                    rom_path.display()
                ));
                return Ok((rom, rom_path));
            }
            // A header that matches over arrays that do not read: rebuilt, not an error the
            // user must clear by deleting the file.
            Err(e) => log(&format!("reduced model: {e}; reducing again")),
        },
        Freshness::Stale(reasons) => log(&format!(
            "reduced model: {} is stale ({}); reducing again",
            rom_path.display(),
            reasons.join("; ")
        )),
        Freshness::Missing => {}
    }
    log(&format!(
        "reduced model: reducing {} and {} ...",
        inputs.disc.mesh.display(),
        inputs.pad.mesh.display()
    ));
    let t = std::time::Instant::now();
    let (rom, _) = reduce_brake_loaded(
        &inputs,
        parts.disc,
        parts.pad,
        &mut |part: &str, stage: Stage| {
            log(&format!("  {part}: {}", stage.label()));
        },
    )?;
    log(&format!(
        "  reduced to {} dofs in {:.1} s",
        rom.size(),
        t.elapsed().as_secs_f64()
    ));
    rom.write(&rom_path).map_err(|error| PipelineError::Rom {
        path: rom_path.clone(),
        error,
    })?;
    Ok((rom, rom_path))
}

/// The brake's parameters from the scene: normal, sliding direction, the contact stiffness
/// per unit area (eq 8), pairing tolerance and piston force.
pub fn brake_params(scene: &Scene) -> Result<BrakeParams> {
    let f = &scene.file;
    let (kl, knl, _) = scene.stiffness()?;
    Ok(BrakeParams {
        normal: *f.contact.normal.get_ref(),
        sliding: *f.friction.sliding_direction.get_ref(),
        stiffness: Stiffness::PerArea {
            linear: kl,
            cubic: knl,
            point_area: scene.point_area()?,
        },
        pairing_tolerance: PairingTolerance::Absolute(scene.pairing_tolerance()?),
        piston_force: scene.piston_force()?,
        surface_speed: None,
    })
}

/// The disc's rotation the scene gives (`[disc]`), `None` without one.
pub fn disc_speed(scene: &Scene) -> Result<Option<DiscSpeed>> {
    let Some(w) = scene.disc_angular_speed()? else {
        return Ok(None);
    };
    let (origin, axis) = scene.disc_axis()?;
    Ok(Some(DiscSpeed {
        angular_speed: w,
        origin,
        axis,
    }))
}

/// The damping of eqs (12)–(13) the scene asks for.
pub fn damping_spec(scene: &Scene) -> Result<DampingSpec> {
    let f = &scene.file;
    Ok(DampingSpec {
        global_ratio: *f.damping.global_ratio.get_ref(),
        pair: match scene.pair()? {
            None => PairChoice::Auto,
            Some((a, b)) => PairChoice::Modes(a, b),
        },
        pair_ratios: f
            .damping
            .pair_ratios
            .as_ref()
            .map_or([0.0, 0.0], |r| *r.get_ref()),
    })
}

/// The highest frequency the reduced model speaks for: the lower of the parts' highest kept
/// fixed-interface frequencies.
pub fn valid_max_hz(rom: &ReducedModel) -> f64 {
    rom.parts
        .iter()
        .filter_map(|p| p.info.fixed_interface_hz.last().copied())
        .fold(f64::INFINITY, f64::min)
}

/// Sweep options of the scene on a reduced model (band and defaults).
pub fn sweep_options(scene: &Scene, rom: &ReducedModel) -> SweepOptions {
    SweepOptions {
        band: Band {
            valid_max_hz: valid_max_hz(rom),
            user: scene
                .file
                .stability
                .band_hz
                .as_ref()
                .map(|b| (b.get_ref()[0], b.get_ref()[1])),
        },
        ..SweepOptions::default()
    }
}

/// The brake of a scene on a reduced model.
pub fn model_on(scene: &Scene, rom: ReducedModel, rom_path: PathBuf) -> Result<Model> {
    let params = brake_params(scene)?;
    let (brake, layout, pairs) = assemble(&rom, &params)?;
    let m = &scene.file.model;
    Ok(Model {
        sweep: sweep_options(scene, &rom),
        damping: damping_spec(scene)?,
        rom,
        rom_path,
        brake,
        layout,
        pairs,
        params,
        disc_mesh: scene.resolve(&m.disc),
        pad_mesh: scene.resolve(&m.pad),
        disc: disc_speed(scene)?,
        units: scene.units()?,
    })
}

/// The reduced model (cached) and the brake of a scene.
pub fn build(scene: &Scene, out: &Path, log: Log) -> Result<Model> {
    let (rom, rom_path) = reduced_model(scene, out, log)?;
    model_on(scene, rom, rom_path)
}

/// The default output folder of a scene: `out/<scene stem>`.
pub fn default_out(scene: &Path) -> PathBuf {
    let stem = scene
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    PathBuf::from("out").join(stem)
}

/// A mesh read, its reader's warnings passed to `log`.
pub fn read_mesh(path: &Path, log: Log) -> Result<Mesh> {
    let read = squeal_mesh::read(path).map_err(|error| PipelineError::Mesh {
        path: path.to_path_buf(),
        error,
    })?;
    for w in &read.warnings {
        log(&format!("warning: {w}"));
    }
    Ok(read.mesh)
}
