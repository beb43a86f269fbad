//! `squeal reduce`: Craig–Bampton reduction of a disc and a pad to the reduced brake.

use crate::progress::StageBars;
use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use squeal_eigs::Backend;
use squeal_pipeline::parts::{SceneParts, brake_inputs, load_parts};
use squeal_reduce::brake::{
    BrakeInputs, DEFAULT_AUTO_FACTOR, ModeChoice, reduce_brake, reduce_brake_loaded,
};
use squeal_reduce::craig_bampton::Stage;
use squeal_reduce::rom::{InterfaceKind, ReducedModel};
use squeal_reduce::summary::summary_text;
use squeal_scene::Scene;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

#[derive(Args)]
pub struct ReduceArgs {
    /// Disc mesh (.inp or .msh)
    #[arg(required_unless_present = "scene")]
    pub disc: Option<PathBuf>,
    /// Pad mesh (.inp or .msh)
    #[arg(required_unless_present = "scene")]
    pub pad: Option<PathBuf>,
    /// Reduce the brake of a scene file instead (its meshes, pads, sets, units, materials,
    /// rotation, interface and modes; --backend, --no-basis, --export and -o still apply): the
    /// way to reduce a brake with several pads
    #[arg(long, conflicts_with_all = ["disc", "pad"])]
    pub scene: Option<PathBuf>,
    /// Output reduced model (.rom)
    #[arg(short, long, default_value = "brake.rom")]
    pub output: PathBuf,
    /// Contact interface: "patch" (each contact point is the mean motion of a ninth of the
    /// contact face), "node" (one mesh node per contact point, as in the paper) or "nodal"
    /// (every node of the pad's contact face, paired with its projection on the disc's)
    #[arg(long, value_enum, default_value_t = Interface::Patch)]
    pub interface: Interface,
    /// Fixed-interface modes per part: a number, or "auto" with --fmax
    #[arg(long, default_value = "50")]
    pub modes: String,
    /// With --modes auto: highest frequency of interest (Hz); the modes below
    /// --factor x fmax are kept
    #[arg(long)]
    pub fmax: Option<f64>,
    /// With --modes auto: multiple of --fmax below which modes are kept
    #[arg(long, default_value_t = DEFAULT_AUTO_FACTOR)]
    pub factor: f64,
    /// Eigensolver: "lanczos" (pure Rust) or "arpack" (needs a build with the
    /// squeal-reduce/arpack feature)
    #[arg(long, value_enum, default_value_t = EigBackend::Lanczos)]
    pub backend: EigBackend,
    /// Also write K and M of each part as MatrixMarket files beside the output
    #[arg(long, value_enum)]
    pub export: Option<Export>,
    /// Leave the bases out of the .rom (smaller, but results cannot be put back on the meshes)
    #[arg(long)]
    pub no_basis: bool,
    /// Patch grid of the contact face, radial x angular
    #[arg(long, default_value = "3x3")]
    pub grid: String,
    /// The disc's axis direction X,Y,Z: the patch grid is cut about it, the pad's ABUTMENT is
    /// held in the plane normal to it (a scene's [rotation] axis)
    #[arg(
        long,
        default_value = "0,0,1",
        value_name = "X,Y,Z",
        allow_hyphen_values = true
    )]
    pub axis: String,
    /// A point X,Y,Z of the disc's axis (m)
    #[arg(
        long,
        default_value = "0,0,0",
        value_name = "X,Y,Z",
        allow_hyphen_values = true
    )]
    pub axis_point: String,
    /// Direction X,Y,Z of the pistons' dofs (the contact normal); default: the axis
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub normal: Option<String>,
    #[command(flatten)]
    pub materials: crate::commands::fe::MaterialArgs,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Interface {
    Patch,
    Node,
    Nodal,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum EigBackend {
    Lanczos,
    Arpack,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Export {
    Mtx,
}

pub fn run(args: ReduceArgs) -> Result<ExitCode> {
    // faer's dense kernels follow the global parallelism and their bits depend on the thread
    // count; the large sparse factorizations get rayon's pool explicitly (BrakeInputs::par)
    // and do not. So the .rom is the same bits for any --threads.
    faer::set_global_parallelism(faer::Par::Seq);
    squeal_io::require_extension(&args.output, "rom", "the reduced model (.rom)")?;
    // A scene's meshes are read here, to choose their sets; the others by the reduction.
    let (inputs, loaded) = match args.scene.as_deref() {
        Some(path) => {
            let (mut inputs, parts) = scene_parts(path)?;
            inputs.backend = backend(args.backend);
            inputs.keep_basis = !args.no_basis;
            (inputs, Some(parts))
        }
        None => (inputs(&args)?, None),
    };
    let mut read: Vec<(&Path, &str)> = vec![(inputs.disc.mesh.as_path(), "disc mesh")];
    read.extend(
        inputs
            .pads
            .iter()
            .map(|p| (p.part.mesh.as_path(), "pad mesh")),
    );
    if let Some(path) = &args.scene {
        read.push((path.as_path(), "scene file"));
    }
    squeal_io::refuse_inputs(&args.output, &read)?;
    if let Some(dir) = args.output.parent().filter(|d| !d.as_os_str().is_empty()) {
        squeal_io::check_writable(dir)?;
    }
    let mut bars = StageBars::default();
    let mut tell = |part: &str, stage: Stage| bars.start(part, stage.label());
    let (model, report) = match loaded {
        Some(parts) => reduce_brake_loaded(
            &inputs,
            parts.disc,
            parts.pads.into_iter().map(|p| p.1).collect(),
            &mut tell,
        ),
        None => reduce_brake(&inputs, &mut tell),
    }
    .context("reducing the brake")?;
    bars.start("brake", Stage::Write.label());
    let t = Instant::now();
    model
        .write(&args.output)
        .with_context(|| format!("writing {}", args.output.display()))?;
    let exported = match args.export {
        Some(Export::Mtx) => export_mtx(&model, &args.output)?,
        None => Vec::new(),
    };
    let write_time = t.elapsed();
    bars.finish();
    println!();
    print!("{}", summary_text(&model, &report, write_time));
    let backend = model.parts.first().and_then(|p| p.info.build.as_ref());
    let megabytes = std::fs::metadata(&args.output).map_or(0.0, |m| m.len() as f64 / 1e6);
    println!();
    println!(
        "wrote {} ({} dofs, {} backend, {megabytes:.1} MB)",
        args.output.display(),
        model.size(),
        backend.map_or("?", |b| b.backend.as_str()),
    );
    for path in exported {
        println!("wrote {}", path.display());
    }
    Ok(ExitCode::SUCCESS)
}

/// A scene's parts (read, sets chosen) and reduction inputs.
fn scene_parts(path: &Path) -> Result<(BrakeInputs, SceneParts)> {
    let scene = Scene::read(path)?;
    let parts = load_parts(&scene, &|m: &str| eprintln!("{m}"))?;
    let inputs = brake_inputs(&scene, &parts)?;
    Ok((inputs, parts))
}

fn backend(b: EigBackend) -> Backend {
    match b {
        EigBackend::Lanczos => Backend::Lanczos,
        EigBackend::Arpack => Backend::Arpack,
    }
}

/// `X,Y,Z` as three finite numbers.
fn parse_vector(option: &str, text: &str) -> Result<[f64; 3]> {
    let v: Vec<f64> = text
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .with_context(|| format!("{option} {text}: expected three numbers X,Y,Z"))?;
    match <[f64; 3]>::try_from(v) {
        Ok(v) if v.iter().all(|x| x.is_finite()) => Ok(v),
        _ => bail!("{option} {text}: expected three finite numbers X,Y,Z"),
    }
}

/// The brake inputs from the command line: the bundled setup on the given meshes, turned to
/// the given axis and normal.
fn inputs(args: &ReduceArgs) -> Result<BrakeInputs> {
    let direction = parse_vector("--axis", &args.axis)?;
    let origin = parse_vector("--axis-point", &args.axis_point)?;
    let normal = match &args.normal {
        Some(n) => parse_vector("--normal", n)?,
        None => direction,
    };
    let (Some(disc), Some(pad)) = (&args.disc, &args.pad) else {
        bail!("give the disc and pad meshes, or --scene");
    };
    let mut inputs = BrakeInputs::bundled(disc, pad)
        .about(squeal_reduce::interface::Axis { origin, direction }, normal)
        .map_err(|e| anyhow::anyhow!("--axis/--normal: {e}"))?;
    inputs.interface = match args.interface {
        Interface::Patch => InterfaceKind::Patch,
        Interface::Node => InterfaceKind::Node,
        Interface::Nodal => InterfaceKind::Nodal,
    };
    inputs.backend = backend(args.backend);
    inputs.keep_basis = !args.no_basis;
    inputs.modes = if args.modes.eq_ignore_ascii_case("auto") {
        let Some(fmax) = args.fmax else {
            bail!("--modes auto needs --fmax (the highest frequency of interest, Hz)");
        };
        ModeChoice::Auto {
            fmax_hz: fmax,
            factor: args.factor,
        }
    } else {
        if args.fmax.is_some() {
            bail!("--fmax goes with --modes auto");
        }
        let n = args
            .modes
            .parse::<usize>()
            .with_context(|| format!("--modes {}: expected a number or \"auto\"", args.modes))?;
        ModeChoice::Fixed(n)
    };
    inputs.grid = parse_grid(&args.grid)?;
    for (set, material) in args.materials.overrides()? {
        let mut used = false;
        let (disc_part, pads) = (&mut inputs.disc, &mut inputs.pads);
        for (path, part) in [(disc, disc_part), (pad, &mut pads[0].part)] {
            if mesh_has_element_set(path, &set)? {
                part.material_overrides.push((set.clone(), material));
                used = true;
            }
        }
        if !used {
            bail!("--material {set}=...: neither mesh has an element set named {set}");
        }
    }
    inputs.validate()?;
    Ok(inputs)
}

fn parse_grid(text: &str) -> Result<[usize; 2]> {
    let parse = || -> Option<[usize; 2]> {
        let (a, b) = text.split_once(['x', 'X'])?;
        Some([a.trim().parse().ok()?, b.trim().parse().ok()?])
    };
    parse().with_context(|| format!("--grid {text}: expected RADIALxANGULAR, e.g. 3x3"))
}

/// Whether a mesh file has an element set (read only for `--material`).
fn mesh_has_element_set(path: &Path, set: &str) -> Result<bool> {
    let read =
        squeal_mesh::read(path).with_context(|| format!("reading mesh {}", path.display()))?;
    Ok(read.mesh.element_set(set).is_some())
}

/// The MatrixMarket files of `--export mtx`, beside the .rom and named after it.
fn export_mtx(model: &ReducedModel, output: &Path) -> Result<Vec<PathBuf>> {
    let dir = output.parent().unwrap_or(Path::new(""));
    let stem = output
        .file_stem()
        .map_or("brake".into(), |s| s.to_string_lossy());
    squeal_reduce::export::write_matrix_market(model, dir, &stem)
        .with_context(|| format!("exporting {} as MatrixMarket", output.display()))
}
