//! `squeal reduce`: Craig–Bampton reduction of a disc and a pad to the reduced brake.

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use squeal_eigs::Backend;
use squeal_fe::ElasticMaterial;
use squeal_reduce::brake::{
    BrakeInputs, BrakeReport, DEFAULT_AUTO_FACTOR, ModeChoice, reduce_brake,
};
use squeal_reduce::craig_bampton::Stage;
use squeal_reduce::rom::{DofLabel, InterfaceKind, ReducedModel, ReducedPart};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

#[derive(Args)]
pub struct ReduceArgs {
    /// Disc mesh (.inp or .msh)
    pub disc: PathBuf,
    /// Pad mesh (.inp or .msh)
    pub pad: PathBuf,
    /// Output reduced model (.rom)
    #[arg(short, long, default_value = "brake.rom")]
    pub output: PathBuf,
    /// Contact interface: "patch" (each contact point is the mean motion of a ninth of the
    /// contact face) or "node" (one mesh node per contact point, as in the paper)
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
    /// Material of an element set, isotropic: SET=E,nu,rho (Pa, -, kg/m^3); overrides the
    /// mesh's section (a .msh mesh has none). Repeat for several sets.
    #[arg(long = "material", value_name = "SET=E,NU,RHO")]
    pub materials: Vec<String>,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Interface {
    Patch,
    Node,
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
    squeal_io::refuse_inputs(
        &args.output,
        &[(&args.disc, "disc mesh"), (&args.pad, "pad mesh")],
    )?;
    let inputs = inputs(&args)?;
    if let Some(dir) = args.output.parent().filter(|d| !d.as_os_str().is_empty()) {
        squeal_io::check_writable(dir)?;
    }
    let mut bars = StageBars::default();
    let (model, report) = reduce_brake(&inputs, &mut |part, stage| bars.start(part, stage))
        .context("reducing the brake")?;
    bars.start("brake", Stage::Write);
    let t = Instant::now();
    model
        .write(&args.output)
        .with_context(|| format!("writing {}", args.output.display()))?;
    if args.export == Some(Export::Mtx) {
        export_mtx(&model, &args.output)?;
    }
    let write_time = t.elapsed();
    bars.finish();
    print_summary(&model, &report, write_time, &args.output)?;
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

/// The brake inputs from the command line: the bundled setup on the given meshes, turned to
/// the given axis and normal.
fn inputs(args: &ReduceArgs) -> Result<BrakeInputs> {
    let direction = parse_vector("--axis", &args.axis)?;
    let origin = parse_vector("--axis-point", &args.axis_point)?;
    let normal = match &args.normal {
        Some(n) => parse_vector("--normal", n)?,
        None => direction,
    };
    let mut inputs = BrakeInputs::bundled(&args.disc, &args.pad)
        .about(squeal_reduce::interface::Axis { origin, direction }, normal)
        .map_err(|e| anyhow::anyhow!("--axis/--normal: {e}"))?;
    inputs.interface = match args.interface {
        Interface::Patch => InterfaceKind::Patch,
        Interface::Node => InterfaceKind::Node,
    };
    inputs.backend = match args.backend {
        EigBackend::Lanczos => Backend::Lanczos,
        EigBackend::Arpack => Backend::Arpack,
    };
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
    for text in &args.materials {
        let (set, material) = parse_material(text)?;
        let mut used = false;
        for (path, part) in [(&args.disc, &mut inputs.disc), (&args.pad, &mut inputs.pad)] {
            if mesh_has_element_set(path, &set)? {
                part.material_overrides.push((set.clone(), material));
                used = true;
            }
        }
        if !used {
            bail!("--material {text}: neither mesh has an element set named {set}");
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

fn parse_material(text: &str) -> Result<(String, ElasticMaterial)> {
    let parse = || -> Option<(String, ElasticMaterial)> {
        let (set, values) = text.split_once('=')?;
        let v: Vec<f64> = values
            .split(',')
            .map(|x| x.trim().parse().ok())
            .collect::<Option<_>>()?;
        let [e, nu, rho] = v[..] else { return None };
        Some((
            set.trim().to_string(),
            ElasticMaterial::isotropic(e, nu, rho),
        ))
    };
    parse().with_context(|| {
        format!("--material {text}: expected SET=E,nu,rho, e.g. DISC=125e9,0.26,7200")
    })
}

/// Whether a mesh file has an element set (read only for `--material`).
fn mesh_has_element_set(path: &Path, set: &str) -> Result<bool> {
    let read =
        squeal_mesh::read(path).with_context(|| format!("reading mesh {}", path.display()))?;
    Ok(read.mesh.element_set(set).is_some())
}

/// One spinner per stage, finished with its time when the next stage starts.
#[derive(Default)]
struct StageBars {
    current: Option<ProgressBar>,
}

impl StageBars {
    fn start(&mut self, part: &str, stage: Stage) {
        self.finish();
        let bar = ProgressBar::new_spinner();
        let style =
            ProgressStyle::with_template("{spinner} {prefix:<5} {msg:<24} {elapsed_precise}")
                .unwrap_or_else(|_| ProgressStyle::default_spinner());
        bar.set_style(style);
        bar.set_prefix(part.to_string());
        bar.set_message(stage.label());
        bar.enable_steady_tick(Duration::from_millis(120));
        self.current = Some(bar);
    }

    fn finish(&mut self) {
        if let Some(bar) = self.current.take() {
            let style = ProgressStyle::with_template("  {prefix:<5} {msg:<24} {elapsed_precise}")
                .unwrap_or_else(|_| ProgressStyle::default_spinner());
            bar.set_style(style);
            bar.finish();
        }
    }
}

/// `<stem>.<part>.K.mtx`, `.M.mtx` (dense MatrixMarket arrays) and `.dofs.csv` per part.
fn export_mtx(model: &ReducedModel, output: &Path) -> Result<()> {
    let stem = output.with_extension("");
    for part in &model.parts {
        let name = &part.info.name;
        let base = format!("{}.{name}", stem.display());
        for (what, mat) in [("K", &part.k), ("M", &part.m)] {
            let path = PathBuf::from(format!("{base}.{what}.mtx"));
            let n = mat.nrows();
            let values: Vec<f64> = (0..n * n).map(|k| mat[(k % n, k / n)]).collect();
            let comment = format!(
                "squeal reduced {what} of part {name} (eq {}); dof labels in {base}.dofs.csv",
                if what == "K" { 6 } else { 7 }
            );
            squeal_io::mtx::write_dense(&path, n, n, &values, &comment)
                .with_context(|| format!("writing {}", path.display()))?;
        }
        let path = PathBuf::from(format!("{base}.dofs.csv"));
        squeal_io::atomic_write(&path, |w| write_dof_labels(w, part))
            .with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(())
}

/// One line per reduced dof: index (1-based, as in the .mtx), kind, point or mode, direction,
/// point coordinates.
fn write_dof_labels(w: &mut dyn Write, part: &ReducedPart) -> std::io::Result<()> {
    writeln!(w, "dof,kind,point,mode,direction,x,y,z")?;
    for (i, label) in part.info.dofs.iter().enumerate() {
        match *label {
            DofLabel::Point { point, direction } => {
                let p = &part.info.points[point];
                let role = format!("{:?}", p.role).to_lowercase();
                let [x, y, z] = p.position;
                let d = ["x", "y", "z"].get(direction as usize).unwrap_or(&"?");
                writeln!(w, "{},{role},{},,{d},{x:e},{y:e},{z:e}", i + 1, point + 1)?;
            }
            DofLabel::Along { point, direction } => {
                let p = &part.info.points[point];
                let role = format!("{:?}", p.role).to_lowercase();
                let [x, y, z] = p.position;
                let [a, b, c] = direction;
                writeln!(
                    w,
                    "{},{role},{},,along {a:.6} {b:.6} {c:.6},{x:e},{y:e},{z:e}",
                    i + 1,
                    point + 1
                )?;
            }
            DofLabel::Mode { mode } => writeln!(w, "{},mode,,{},,,,", i + 1, mode + 1)?,
        }
    }
    Ok(())
}

fn print_summary(
    model: &ReducedModel,
    report: &BrakeReport,
    write_time: Duration,
    output: &Path,
) -> Result<()> {
    println!();
    println!("reduced brake: {} dofs", model.size());
    for (part, r) in model.parts.iter().zip(&report.parts) {
        let red = &r.reduce;
        println!(
            "  {:<5} {} ({} nodes, {} free dofs): {} boundary + {} modes = {} dofs; factor of K_II {} nonzeros ({:.0} MB)",
            part.info.name,
            r.mesh.path,
            r.mesh.nodes,
            red.free_dofs,
            red.boundary_dofs,
            red.modes,
            part.size(),
            red.nnz_factor,
            red.factor_bytes as f64 / 1e6
        );
        for w in &r.warnings {
            println!("        warning: {w}");
        }
    }
    if let Some(ModeChoice::Auto { fmax_hz, factor }) = model
        .parts
        .first()
        .and_then(|p| p.info.build.as_ref())
        .map(|b| b.modes)
    {
        println!(
            "  modes: all fixed-interface modes below {factor} x {fmax_hz} Hz = {} Hz",
            factor * fmax_hz
        );
    }
    println!();
    print_timings(report, write_time);
    println!();
    print_frequencies(model);
    println!();
    println!("checks");
    for (part, r) in model.parts.iter().zip(&report.parts) {
        let red = &r.reduce;
        let sturm = match red.sturm {
            Some((bound, count)) => format!(
                "{count} eigenvalues below {:.1} Hz, as found",
                squeal_reduce::craig_bampton::hz(bound)
            ),
            None => "not checked".into(),
        };
        println!("  {}", part.info.name);
        println!(
            "    K_CN coupling ||K_CN|| / ||K||      {:.2e}  (eq 6: zero)",
            red.coupling
        );
        println!(
            "    modal mass deviation max|M_NN - I| {:.2e}  (before re-orthonormalization)",
            red.modal_mass_deviation
        );
        println!(
            "    largest eigen backward error       {:.2e}",
            red.max_residual
        );
        println!("    Sturm count                        {sturm}");
        let e = &red.eig;
        println!(
            "    eigensolver: {} solves with the factor (block {}, basis {}, {} restarts), {:.2} s of solves, Sturm check {:.2} s",
            e.operator_applications,
            e.block,
            e.ncv,
            e.restarts,
            e.operator_time.as_secs_f64(),
            e.sturm_time.as_secs_f64()
        );
    }
    let worst = report.pairs.iter().map(|p| p.distance).fold(0.0, f64::max);
    println!(
        "  contact pairs: {} disc/pad points paired, farthest {:.2e} m apart (tolerance {:.2e} m)",
        report.pairs.len(),
        worst,
        report.pairing_tolerance
    );
    let backend = model
        .parts
        .first()
        .and_then(|p| p.info.build.as_ref())
        .map_or("?", |b| b.backend.as_str());
    println!();
    println!(
        "wrote {} ({} dofs, {} backend, {:.1} MB)",
        output.display(),
        model.size(),
        backend,
        std::fs::metadata(output).map_or(0.0, |m| m.len() as f64 / 1e6)
    );
    Ok(())
}

fn print_timings(report: &BrakeReport, write_time: Duration) {
    println!("timings (s)");
    let names: Vec<&str> = report.parts.iter().map(|p| p.name.as_str()).collect();
    print!("  {:<24}", "stage");
    for n in &names {
        print!(" {n:>8}");
    }
    println!(" {:>8}", "total");
    for stage in Stage::ALL {
        if stage == Stage::Write {
            continue;
        }
        let times: Vec<f64> = report
            .parts
            .iter()
            .map(|p| p.time(stage).as_secs_f64())
            .collect();
        print!("  {:<24}", stage.label());
        for t in &times {
            print!(" {t:>8.2}");
        }
        println!(" {:>8.2}", times.iter().sum::<f64>());
    }
    println!(
        "  {:<24} {:>width$.2}",
        Stage::Write.label(),
        write_time.as_secs_f64(),
        width = 9 * names.len() + 8
    );
    println!(
        "  {:<24} {:>width$.2}",
        "all",
        (report.total + write_time).as_secs_f64(),
        width = 9 * names.len() + 8
    );
}

fn print_frequencies(model: &ReducedModel) {
    const SHOWN: usize = 20;
    println!("lowest fixed-interface frequencies (Hz)");
    print!("  {:>4}", "mode");
    for p in &model.parts {
        print!(" {:>12}", p.info.name);
    }
    println!();
    let rows = model
        .parts
        .iter()
        .map(|p| p.info.fixed_interface_hz.len())
        .max()
        .unwrap_or(0)
        .min(SHOWN);
    for i in 0..rows {
        print!("  {:>4}", i + 1);
        for p in &model.parts {
            match p.info.fixed_interface_hz.get(i) {
                Some(f) => print!(" {f:>12.2}"),
                None => print!(" {:>12}", "-"),
            }
        }
        println!();
    }
}
