//! `squeal stability`: the paper's section 3 for a scene: static equilibrium, complex
//! eigenvalues against friction (Figure 2), the Hopf point μ0 and the unstable mode shape.

use crate::progress::{BARS, say};
use anyhow::{Context, Result};
use clap::Args;
use squeal_pipeline::model::default_out;
use squeal_pipeline::{Pipeline, stability};
use squeal_scene::{Scene, parse_range};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

#[derive(Args)]
pub struct StabilityArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// Friction values "start..end/count": count values from start to end, e.g. 0..1/201
    /// (default: the scene's [stability] mu, else 0..1/201)
    #[arg(long)]
    pub mu: Option<String>,
    /// Output folder (default: out/ and the scene's path from the working directory without
    /// .toml: out/meshes/brake for meshes/brake.toml)
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Skip the VTU files of the equilibrium and mode shape
    #[arg(long)]
    pub no_vtu: bool,
}

/// The pipeline of a scene with the friction values of `--mu` (or the scene's).
pub fn pipeline<'a>(
    scene: &Path,
    out: &Option<PathBuf>,
    mu: &Option<String>,
) -> Result<Pipeline<'a>> {
    let s = Scene::read(scene)?;
    let out = out.clone().unwrap_or_else(|| default_out(scene));
    let p = Pipeline::new(s, out, &say)?.with_progress(&BARS);
    let p = match mu {
        Some(r) => p.with_mus(parse_range(r).map_err(anyhow::Error::msg).context("--mu")?)?,
        None => p,
    };
    take_folder(&p.scene.path, &p.out)?;
    Ok(p)
}

/// Takes the output folder `out` of `scene` for this command ([`squeal_io::folder::begin`]): its lock,
/// the check that it holds no user's files (unless `--force`) and this run in its manifest.
pub fn take_folder(scene: &Path, out: &Path) -> Result<()> {
    let sha =
        squeal_reduce::rom::sha256_file(scene).with_context(|| scene.display().to_string())?;
    let info = squeal_io::folder::RunInfo {
        command: std::env::args().collect::<Vec<_>>().join(" "),
        scene: Some((scene.to_path_buf(), sha)),
    };
    let force = crate::commands::FORCE.load(std::sync::atomic::Ordering::Relaxed);
    for note in squeal_io::folder::begin(out, &info, force)? {
        eprintln!("note: {note}");
    }
    Ok(())
}

pub fn run(args: StabilityArgs) -> Result<ExitCode> {
    let p = pipeline(&args.scene, &args.out, &args.mu)?;
    write(&p, !args.no_vtu)?;
    Ok(ExitCode::SUCCESS)
}

/// Runs the stability stage of `p` and writes its outputs to `<out>/stability`.
/// The verdict comes first: a stable brake ("stable for mu in [a, b]") is an answer, not an
/// error. Returns it.
pub fn write(p: &Pipeline, vtu: bool) -> Result<stability::Verdict> {
    let m = p.model()?;
    let t = Instant::now();
    let st = p.stability().context("stability analysis")?;
    let verdict = stability::verdict(m, st);
    println!("{verdict}");
    print!("{}", stability::pairs_text(m));
    let dir = p.out.join("stability");
    print!(
        "{}",
        stability::summary_text(m, st, t.elapsed().as_secs_f64())
    );
    match stability::normal_form(m, st) {
        Ok(Some(nf)) => print!("{}", stability::criticality_text(m, st, &nf)),
        Ok(None) => {}
        Err(e) => println!("criticality of the Hopf point not computed: {e}"),
    }
    stability::write_tables(&dir, m, st)?;
    stability::write_figures(&dir, st, m)?;
    print!("{}", stability::write_makeup(&dir, m, st, p.log())?);
    if vtu {
        let vtm = stability::write_shapes(&dir, m, st, p.log())?;
        println!("mode shape and equilibria for ParaView: {}", vtm.display());
    }
    println!("results in {}", dir.display());
    Ok(verdict)
}
