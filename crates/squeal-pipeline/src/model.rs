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
use squeal_brake::assemble::{
    BrakeParams, DiscRotation, InitialGaps, Layout, Pairing, SlidingRule, Stiffness, assemble,
};
use squeal_brake::contact::LawSpec;
use squeal_brake::sweep::{Band, SweepOptions};
use squeal_chbm::physics::DiscSpeed;
use squeal_fe::frames::RotationAxis;
use squeal_mesh::Mesh;
use squeal_mesh::units::UnitSystem;
use squeal_reduce::brake::{
    BrakeInputs, Freshness, ModeChoice, PadInput, PairingTolerance, PartInput, freshness,
};
use squeal_reduce::craig_bampton::Stage;
use squeal_reduce::rom::{InterfaceKind, ReducedModel};
use squeal_scene::{ContactLawSetting, GapSetting, Interface, Key, Scene, Sliding};
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
    /// Where the modal damping ratio comes from: `file:line` of `[damping] global_ratio`, or
    /// that it is the default (the scene leaves it out).
    pub damping_from: String,
    pub sweep: SweepOptions,
    /// Meshes of the parts, as files.
    pub disc_mesh: PathBuf,
    /// The pads' names and mesh files, in the brake's order.
    pub pad_meshes: Vec<(String, PathBuf)>,
    /// The disc's speed from the scene's `[rotation]` (or `[disc]`), for the sliding check of
    /// every cycle.
    pub disc: Option<DiscSpeed>,
    /// The unit system the mesh files are written in (`[units]`): [`Model::read_mesh`]
    /// converts them to SI.
    pub units: UnitSystem,
    /// What `[reduction] interface` kept and why (`None`: the contact faces' nodal dofs).
    pub interface: Option<crate::interface::InterfaceSummary>,
    /// Normal forms already computed ([`crate::stability::normal_form`]): each stage of a run
    /// asks for the one at μ0, and each is a dense eigendecomposition of the whole brake.
    pub(crate) normal_forms: NormalFormCache,
}

/// Normal forms by the Hopf point they were computed at (μ0 and the eigenvalue's guess, bit
/// for bit: another sweep with another μ0 gets its own).
#[derive(Default)]
pub(crate) struct NormalFormCache(
    std::sync::Mutex<Vec<([u64; 3], squeal_brake::criticality::NormalForm)>>,
);

impl NormalFormCache {
    fn lock(
        &self,
    ) -> std::sync::MutexGuard<'_, Vec<([u64; 3], squeal_brake::criticality::NormalForm)>> {
        self.0
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// The normal form at `key`, computed by `make` the first time.
    pub(crate) fn get_or_try<E>(
        &self,
        key: [u64; 3],
        make: impl FnOnce() -> std::result::Result<squeal_brake::criticality::NormalForm, E>,
    ) -> std::result::Result<squeal_brake::criticality::NormalForm, E> {
        if let Some((_, nf)) = self.lock().iter().find(|(k, _)| *k == key) {
            return Ok(nf.clone());
        }
        let nf = make()?;
        self.lock().push((key, nf.clone()));
        Ok(nf)
    }
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
/// clamped on `CLAMP`, pad held on `ABUTMENT` in the plane normal to the disc's axis, pistons
/// on `PISTON` pushing along the contact normal, contact on `CONTACT` / `CONTACT_FACE` cut into
/// patches about the axis) on the scene's meshes, interface and mode count. The axis is
/// `[rotation]`'s (without one, the line along `[contact] normal`, or z, through `[disc]
/// axis_origin` or the origin); the pistons' direction is `[contact] normal`, else the axis.
/// [`crate::parts::brake_inputs`] puts in the sets, materials and units of the scene.
pub fn brake_inputs(scene: &Scene) -> Result<BrakeInputs> {
    let normal = scene.normal()?;
    let axis = scene_axis(scene)?;
    let direction = axis.direction;
    let pads = scene.pad_meshes()?;
    let mut inputs = BrakeInputs::bundled(scene.disc_mesh(), pads[0].1.clone());
    inputs.pads = pads
        .iter()
        .map(|(name, path)| PadInput {
            name: name.clone(),
            part: PartInput::pad(path.clone()),
        })
        .collect();
    inputs.disc.elset = scene.disc_elset();
    for pad in &mut inputs.pads {
        pad.part.elset = scene.pad_elset(&pad.name);
    }
    let mut inputs = inputs.about(axis, normal.unwrap_or(direction))?;
    inputs.interface = match scene.interface()? {
        Interface::Node => InterfaceKind::Node,
        Interface::Nodal => InterfaceKind::Nodal,
        Interface::Patch => InterfaceKind::Patch,
    };
    inputs.modes = ModeChoice::Fixed(scene.modes_per_part());
    Ok(inputs)
}

/// The disc's axis of a scene: `[rotation]`'s, else the line along `[contact] normal` (or z)
/// through the origin.
pub fn scene_axis(scene: &Scene) -> Result<squeal_reduce::interface::Axis> {
    let (origin, direction) = match scene.rotation()? {
        Some(r) => (r.point, r.axis),
        None => ([0.0; 3], scene.normal()?.unwrap_or([0.0, 0.0, 1.0])),
    };
    Ok(squeal_reduce::interface::Axis { origin, direction })
}

/// Where the scene's reduced model is kept: its `[model] rom`, else `<out>/brake.rom`.
pub fn rom_path(scene: &Scene, out: &Path) -> PathBuf {
    scene.rom_file().unwrap_or_else(|| out.join("brake.rom"))
}

/// Checks the outputs of a scene before any work: `out` is a folder that can be written (made
/// if missing), and the reduced model's file ends in `.rom` and is neither the scene nor one
/// of its meshes.
pub fn check_outputs(scene: &Scene, out: &Path) -> Result<()> {
    squeal_io::require_folder(out)?;
    let rom = rom_path(scene, out);
    squeal_io::require_extension(&rom, "rom", "the reduced model (.rom)")?;
    let files = scene.input_files()?;
    let inputs: Vec<(&Path, &str)> = files
        .iter()
        .map(|(p, w)| (p.as_path(), w.as_str()))
        .collect();
    squeal_io::refuse_inputs(&rom, &inputs)?;
    squeal_io::check_writable(out)?;
    if let Some(dir) = rom.parent().filter(|d| !d.as_os_str().is_empty()) {
        squeal_io::check_writable(dir)?;
    }
    Ok(())
}

/// Loads the scene's reduced model, or reduces the meshes (and stores the result) when it is
/// missing or stale (other meshes, by SHA-256, other options, another tool version).
pub fn reduced_model(scene: &Scene, out: &Path, log: Log) -> Result<(ReducedModel, PathBuf)> {
    let (rom, rom_path, unwritten) = reduced_model_unwritten(scene, out, log)?;
    if let Some(kept) = unwritten {
        store(&rom, &rom_path, &kept, log)?;
    }
    Ok((rom, rom_path))
}

/// Writes a freshly reduced model to `rom_path` (atomically: squeal-io's `atomic_write*`
/// under `ReducedModel::write`) and forgets the parts kept in `kept` by an earlier run.
pub fn store(rom: &ReducedModel, rom_path: &Path, kept: &Path, log: Log) -> Result<()> {
    rom.write(rom_path).map_err(|error| PipelineError::Rom {
        path: rom_path.to_path_buf(),
        error,
    })?;
    // The whole model holds them now.
    if let Err(e) = squeal_reduce::brake::forget_kept(kept) {
        log(&format!("warning: cannot remove {}: {e}", kept.display()));
    }
    Ok(())
}

/// [`reduced_model`] without its write: a model just reduced comes with the folder of kept
/// parts, to be passed to [`store`] (which [`build`] runs beside the interface reduction);
/// `None` when the model was read from its file.
pub fn reduced_model_unwritten(
    scene: &Scene,
    out: &Path,
    log: Log,
) -> Result<(ReducedModel, PathBuf, Option<PathBuf>)> {
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
                // This run's model, though an earlier run wrote the file.
                squeal_io::folder::record_reused(&rom_path);
                return Ok((rom, rom_path, None));
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
    crate::restraints::check_held(scene, &parts, &inputs)?;
    log(&format!(
        "reduced model: reducing {} ...",
        parts_by_mesh(
            &inputs
                .parts()
                .iter()
                .map(|(name, p)| (*name, p.mesh.as_path()))
                .collect::<Vec<_>>()
        )
    ));
    let t = std::time::Instant::now();
    // Finished part reductions are kept beside the model when another part fails, and taken
    // up by the next run (squeal_reduce::brake::reduce_brake_keeping).
    let kept = squeal_reduce::brake::kept_dir(&rom_path);
    let (rom, report) = squeal_reduce::brake::reduce_brake_keeping(
        &inputs,
        parts.disc,
        parts.pads.into_iter().chain(parts.bodies).map(|p| p.1).collect(),
        Some(&kept),
        &mut |part: &str, stage: Stage| {
            log(&format!("  {part}: {}", stage.label()));
        },
    )
    .inspect_err(|_| {
        if kept.exists() {
            log(&format!(
                "reduced model: the parts that finished are kept in {}; the next run takes them instead of reducing them again",
                kept.display()
            ));
        }
    })?;
    for p in report.parts.iter().filter(|p| p.reused) {
        log(&format!(
            "  {}: taken from {} (kept by an earlier run)",
            p.name,
            kept.display()
        ));
    }
    log(&format!(
        "  reduced to {} dofs in {:.1} s",
        rom.size(),
        t.elapsed().as_secs_f64()
    ));
    Ok((rom, rom_path, Some(kept)))
}

/// The disc's rotation of the scene (`[rotation]`, or the older `[disc]`) as the brake takes
/// it.
pub fn disc_rotation(scene: &Scene) -> Result<Option<DiscRotation>> {
    let Some(r) = scene.rotation()? else {
        return Ok(None);
    };
    let axis = RotationAxis::new(r.point, r.axis)
        .map_err(|e| PipelineError::input("[rotation]", e.to_string()))?;
    Ok(Some(DiscRotation {
        axis,
        sense: r.sense,
        angular_speed: r.angular_speed,
    }))
}

/// The brake's parameters from the scene: the normal it gives (a check on the mesh's), how
/// the disc slides, its rotation, the contact stiffness per unit area (eq 8), the contact law,
/// pairing tolerance, piston force and the pairs' initial gaps.
pub fn brake_params(scene: &Scene) -> Result<BrakeParams> {
    let (kl, knl, _) = scene.stiffness()?;
    Ok(BrakeParams {
        normal: scene.normal()?,
        sliding: match scene.sliding()? {
            Sliding::Tangent => SlidingRule::Tangent,
            Sliding::Global(d) => SlidingRule::Global(d),
        },
        rotation: disc_rotation(scene)?,
        stiffness: Stiffness::PerArea {
            linear: kl,
            cubic: knl,
            point_area: scene.point_area()?,
        },
        law: match scene.contact_law()? {
            ContactLawSetting::PenaltyCoulomb => LawSpec::PenaltyCoulomb,
            ContactLawSetting::VelocityDependent {
                static_ratio,
                decay_speed,
            } => LawSpec::VelocityDependent {
                static_ratio,
                decay_speed,
            },
            ContactLawSetting::RegularizedCoulomb {
                regularization_speed,
                static_ratio,
                static_speed,
            } => LawSpec::RegularizedCoulomb {
                regularization_speed,
                static_ratio,
                static_speed,
            },
        },
        pairing_tolerance: PairingTolerance::Absolute(scene.pairing_tolerance()?),
        piston_force: scene.piston_force()?,
        initial_gaps: match scene.initial_gaps()? {
            GapSetting::Geometric => InitialGaps::Geometric,
            GapSetting::Uniform(g) => InitialGaps::Uniform(g),
            GapSetting::PerPair(g) => InitialGaps::PerPair(g),
            GapSetting::Closed => InitialGaps::Closed,
        },
    })
}

/// The disc's speed the scene gives (`[rotation]` or `[disc]`), `None` without one.
pub fn disc_speed(scene: &Scene) -> Result<Option<DiscSpeed>> {
    let Some(r) = scene.rotation()? else {
        return Ok(None);
    };
    Ok(r.angular_speed.map(|w| DiscSpeed {
        angular_speed: w,
        origin: r.point,
        axis: r.axis,
    }))
}

/// The damping of eqs (12)–(13) the scene asks for.
pub fn damping_spec(scene: &Scene) -> Result<DampingSpec> {
    Ok(DampingSpec {
        global_ratio: scene.damping_global_ratio(),
        pair: match scene.pair()? {
            None => PairChoice::Auto,
            Some((a, b)) => PairChoice::Modes(a, b),
        },
        pair_ratios: scene.damping_pair_ratios().unwrap_or([0.0, 0.0]),
    })
}

/// Where the scene's modal damping ratio comes from, for outputs: `file:line` of `[damping]
/// global_ratio`, or the default's note.
pub fn damping_from(scene: &Scene) -> String {
    scene.origin(Key::DampingGlobalRatio)
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
    {
        let mut o = SweepOptions::default();
        o.band = Band {
            valid_max_hz: valid_max_hz(rom),
            user: scene.band_hz(),
        };
        o
    }
}

/// The brake of a scene on a reduced model.
pub fn model_on(scene: &Scene, rom: ReducedModel, rom_path: PathBuf) -> Result<Model> {
    model_or_rom(scene, rom, rom_path).map_err(|b| b.0)
}

/// [`model_on`], giving the reduced model back with the error (so that a model just reduced
/// is still written when the scene's brake cannot be formed on it).
fn model_or_rom(
    scene: &Scene,
    rom: ReducedModel,
    rom_path: PathBuf,
) -> std::result::Result<Model, Box<(PipelineError, ReducedModel)>> {
    let formed = (|| -> Result<_> {
        let params = brake_params(scene)?;
        let (brake, layout, pairs) = assemble(&rom, &params).map_err(|e| at_scene_key(scene, e))?;
        Ok((
            params,
            brake,
            layout,
            pairs,
            damping_spec(scene)?,
            scene.pad_meshes()?,
            disc_speed(scene)?,
            scene.units()?,
        ))
    })();
    let (params, brake, layout, pairs, damping, pad_meshes, disc, units) = match formed {
        Ok(f) => f,
        Err(e) => return Err(Box::new((e, rom))),
    };
    Ok(Model {
        sweep: sweep_options(scene, &rom),
        damping,
        damping_from: damping_from(scene),
        rom,
        rom_path,
        brake,
        layout,
        pairs,
        params,
        disc_mesh: scene.disc_mesh(),
        pad_meshes,
        disc,
        units,
        interface: None,
        normal_forms: Default::default(),
    })
}

/// A brake error that a scene key caused, at the key's file and line: the initial gaps'
/// count (`[contact] initial_gap`) and a normal the mesh disagrees with (`[contact] normal`).
fn at_scene_key(scene: &Scene, e: squeal_brake::BrakeError) -> PipelineError {
    use squeal_brake::BrakeError;
    match &e {
        BrakeError::GapCount { .. } => scene.error_at_key(Key::InitialGap, &e).into(),
        BrakeError::NormalDisagrees { .. } => scene.error_at_key(Key::ContactNormal, &e).into(),
        _ => e.into(),
    }
}

/// A stability error that `[damping] pair` caused (modes the brake does not have), at the
/// key's file and line.
pub fn at_damping_key(scene: &Scene, e: PipelineError) -> PipelineError {
    use squeal_brake::BrakeError;
    match e {
        PipelineError::Brake(
            b @ (BrakeError::ModeOutOfRange { .. } | BrakeError::PairOutOfRange { .. }),
        ) => scene.error_at_key(Key::DampingPair, b).into(),
        other => other,
    }
}

/// The reduced model (cached) and the brake of a scene.
///
/// A model just reduced is written to its `.rom` on a thread of its own while the interface
/// reduction runs (the fine ventilated brake's 7.3 GB took 15 s of the run on the critical
/// path: docs/benchmarks.md); the write is joined before the model is returned, so a run
/// reports success only with its `.rom` complete, and a failed write fails the run as
/// before (the file is written atomically: never a partial one).
pub fn build(scene: &Scene, out: &Path, log: Log) -> Result<Model> {
    let (rom, rom_path, unwritten) = reduced_model_unwritten(scene, out, log)?;
    let Some(kept) = unwritten else {
        return crate::interface::apply(
            scene,
            model_before_interface(scene, rom, rom_path, log)?,
            log,
        );
    };
    // A model just reduced is stored whatever the scene's brake makes of it (as before: the
    // next run takes it up).
    let stored_with = |e: PipelineError, rom: &ReducedModel, path: &Path| -> PipelineError {
        match store(rom, path, &kept, log) {
            Ok(()) => e,
            Err(w) => w,
        }
    };
    let mut model = match model_or_rom(scene, rom, rom_path) {
        Ok(m) => m,
        Err(b) => {
            let (e, rom) = *b;
            let path = self::rom_path(scene, out);
            return Err(stored_with(e, &rom, &path));
        }
    };
    if let Err(e) = crate::dampers::apply(scene, &mut model, log) {
        return Err(stored_with(e, &model.rom, &model.rom_path));
    }
    let (reduced, written) = std::thread::scope(|s| {
        let writer = s.spawn(|| store(&model.rom, &model.rom_path, &kept, log));
        let reduced = crate::interface::apply_to(scene, &model, log);
        let written = writer
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (reduced, written)
    });
    written?;
    Ok(reduced?.unwrap_or(model))
}

/// The model of a reduced model read from its file, before the interface reduction: the
/// brake formed and the scene's dampers on it.
fn model_before_interface(
    scene: &Scene,
    rom: ReducedModel,
    rom_path: PathBuf,
    log: Log,
) -> Result<Model> {
    let mut model = model_on(scene, rom, rom_path)?;
    crate::dampers::apply(scene, &mut model, log)?;
    Ok(model)
}

/// The default output folder of a scene: `out/` and the scene's path relative to the working
/// directory without its extension, so that scenes of one name in different folders do not
/// share a folder (`meshes/brake.toml` → `out/meshes/brake`, `meshes/two_pad/brake.toml` →
/// `out/meshes/two_pad/brake`, `brake.toml` → `out/brake`). A scene outside the working
/// directory: `out/<its folder's name>/<its stem>`.
pub fn default_out(scene: &Path) -> PathBuf {
    let stem = scene
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    let canon = |p: &Path| std::fs::canonicalize(p).ok();
    let inside = std::env::current_dir()
        .ok()
        .and_then(|d| canon(&d))
        .zip(canon(scene))
        .and_then(|(cwd, s)| s.strip_prefix(&cwd).ok().map(Path::to_path_buf));
    let rel = match inside {
        Some(rel) => rel.with_file_name(&stem),
        None => {
            let folder = canon(scene)
                .as_deref()
                .and_then(Path::parent)
                .and_then(Path::file_name)
                .map(PathBuf::from)
                .unwrap_or_default();
            folder.join(&stem)
        }
    };
    PathBuf::from("out").join(rel)
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

/// The parts to reduce, each mesh named once after the parts it holds, in the parts' order:
/// `disc (disc.inp) and pad (pad.inp)`, or `disc, pad_in, pad_out (corner.bdf) and shim
/// (shim.inp)` for an assembly file with its parts as element sets.
fn parts_by_mesh(parts: &[(&str, &std::path::Path)]) -> String {
    let mut groups: Vec<(&std::path::Path, Vec<&str>)> = Vec::new();
    for &(name, mesh) in parts {
        match groups.iter_mut().find(|(m, _)| *m == mesh) {
            Some((_, names)) => names.push(name),
            None => groups.push((mesh, vec![name])),
        }
    }
    let items: Vec<String> = groups
        .iter()
        .map(|(mesh, names)| format!("{} ({})", names.join(", "), mesh.display()))
        .collect();
    match items.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => items.join(""),
    }
}

#[cfg(test)]
mod parts_by_mesh_tests {
    use super::parts_by_mesh;
    use std::path::Path;

    /// Each mesh is named once (the fine corner's `.bdf` was named three times in the line).
    #[test]
    fn each_mesh_is_named_once() {
        let corner = Path::new("corner.bdf");
        let line = parts_by_mesh(&[
            ("disc", corner),
            ("pad_in", corner),
            ("shim", Path::new("shim.inp")),
            ("pad_out", corner),
        ]);
        assert_eq!(
            line,
            "disc, pad_in, pad_out (corner.bdf) and shim (shim.inp)"
        );
        let line = parts_by_mesh(&[("disc", Path::new("d.inp")), ("pad", Path::new("p.inp"))]);
        assert_eq!(line, "disc (d.inp) and pad (p.inp)");
        assert_eq!(parts_by_mesh(&[("disc", corner)]), "disc (corner.bdf)");
    }
}
