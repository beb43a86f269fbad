//! `squeal stability`: the paper's section 3 for a scene: static equilibrium, complex
//! eigenvalues against friction (Figure 2), the Hopf point μ0 and the unstable mode shape.

use crate::progress::{BARS, say};
use anyhow::{Context, Result};
use clap::Args;
use squeal_pipeline::model::default_out;
use squeal_pipeline::{Pipeline, stability, stages};
use squeal_scene::{Scene, parse_range};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

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
    /// Also solve the full finite-element brake (no reduction: every contact pair's
    /// linearized springs and friction on the meshes) and compare its mu0 and frequency with
    /// the reduced brake's, both without modal damping; written to <out>/stability/full.txt
    #[arg(long)]
    pub full: bool,
    /// With --full: only the full model's eigenvalues in the band at this friction value
    #[arg(long, requires = "full")]
    pub full_mu: Option<f64>,
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

/// Takes the output folder `out` of `scene` for this command ([`squeal_pipeline::folder::take`]): its lock,
/// the check that it holds no user's files (unless `--force`) and this run in its manifest.
pub fn take_folder(scene: &Path, out: &Path) -> Result<()> {
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let force = crate::commands::FORCE.load(std::sync::atomic::Ordering::Relaxed);
    for note in squeal_pipeline::folder::take(scene, out, command, force)? {
        eprintln!("note: {note}");
    }
    Ok(())
}

pub fn run(args: StabilityArgs) -> Result<ExitCode> {
    let p = pipeline(&args.scene, &args.out, &args.mu)?;
    write(&p, !args.no_vtu)?;
    if args.full {
        if let Some(mu) = args.full_mu.filter(|mu| !mu.is_finite() || *mu < 0.0) {
            anyhow::bail!("--full-mu {mu}: give a friction coefficient, a finite number >= 0");
        }
        let text = squeal_pipeline::full::run::full_check(&p, args.full_mu)
            .context("the full-model check (--full)")?;
        print!("{text}");
    }
    Ok(ExitCode::SUCCESS)
}

/// Runs the stability stage of `p` into `<out>/stability` ([`stages::stability_stage`]);
/// returns its verdict.
pub fn write(p: &Pipeline, vtu: bool) -> Result<stability::Verdict> {
    Ok(stages::stability_stage(p, vtu)?)
}
