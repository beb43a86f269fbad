//! `squeal reduce`: Craig–Bampton reduction of a disc and a pad to the reduced brake.

use crate::progress::StageBars;
use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use squeal_pipeline::reduce::{
    Backend, DEFAULT_AUTO_FACTOR, InterfaceKind, MeshPair, ModeChoice, ReduceRequest, ReduceSource,
    Stage, reduce,
};
use std::path::PathBuf;
use std::process::ExitCode;

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
    let source = match &args.scene {
        Some(path) => ReduceSource::Scene(path.clone()),
        None => ReduceSource::Meshes(mesh_pair(&args)?),
    };
    let request = ReduceRequest {
        source,
        output: args.output.clone(),
        backend: match args.backend {
            EigBackend::Lanczos => Backend::Lanczos,
            EigBackend::Arpack => Backend::Arpack,
        },
        keep_basis: !args.no_basis,
        export_mtx: args.export == Some(Export::Mtx),
    };
    let mut bars = StageBars::default();
    let mut tell = |part: &str, stage: Stage| bars.start(part, stage.label());
    let done =
        reduce(&request, &|m: &str| eprintln!("{m}"), &mut tell).context("reducing the brake")?;
    bars.finish();
    println!();
    print!("{}", done.summary);
    println!();
    println!(
        "wrote {} ({} dofs, {} backend, {:.1} MB)",
        done.output.display(),
        done.model.size(),
        done.backend,
        done.bytes as f64 / 1e6
    );
    for path in done.exported {
        println!("wrote {}", path.display());
    }
    Ok(ExitCode::SUCCESS)
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

/// The two meshes and their layout from the command line.
fn mesh_pair(args: &ReduceArgs) -> Result<MeshPair> {
    let (Some(disc), Some(pad)) = (&args.disc, &args.pad) else {
        bail!("give the disc and pad meshes, or --scene");
    };
    let modes = if args.modes.eq_ignore_ascii_case("auto") {
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
    Ok(MeshPair {
        disc: disc.clone(),
        pad: pad.clone(),
        axis_point: parse_vector("--axis-point", &args.axis_point)?,
        axis_direction: parse_vector("--axis", &args.axis)?,
        normal: args
            .normal
            .as_ref()
            .map(|n| parse_vector("--normal", n))
            .transpose()?,
        interface: match args.interface {
            Interface::Patch => InterfaceKind::Patch,
            Interface::Node => InterfaceKind::Node,
            Interface::Nodal => InterfaceKind::Nodal,
        },
        modes,
        grid: parse_grid(&args.grid)?,
        materials: args.materials.overrides()?,
    })
}

fn parse_grid(text: &str) -> Result<[usize; 2]> {
    let parse = || -> Option<[usize; 2]> {
        let (a, b) = text.split_once(['x', 'X'])?;
        Some([a.trim().parse().ok()?, b.trim().parse().ok()?])
    };
    parse().with_context(|| format!("--grid {text}: expected RADIALxANGULAR, e.g. 3x3"))
}
