//! `squeal study`: the parametric stability studies of the paper's sections 6.2–6.4 (piston
//! pressure, contact stiffness, modal damping: Tables 4–6, Figures 9–11 (a, b)), the
//! damping-induced destabilization at vanishing friction, the mesh-convergence study, and the
//! identification of the modes that couple at μ0 ([`squeal_pipeline::study`]).

use crate::progress::say;
use anyhow::{Context, Result};
use clap::Args;
use squeal_pipeline::model::default_out;
use squeal_pipeline::study::{self, Kind as StudyKind};
use squeal_scene::{Scene, parse_range};
use std::path::PathBuf;
use std::process::ExitCode;

/// A study's name on the command line, with its help.
fn kind_parser() -> clap::builder::PossibleValuesParser {
    clap::builder::PossibleValuesParser::new(
        StudyKind::CHOICES
            .iter()
            .map(|(_, name, help)| clap::builder::PossibleValue::new(*name).help(*help)),
    )
}

#[derive(Args)]
pub struct StudyArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// Which study
    #[arg(long, value_parser = kind_parser(), default_value = "all")]
    pub kind: String,
    /// Output folder (default: out/<scene name>); results go to <out>/study
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Friction values "start..end/count": count values from start to end, e.g. 0..1/201
    /// (default: the scene's [stability] mu, else 0..1/201)
    #[arg(long)]
    pub mu: Option<String>,
    /// Mesh levels of --kind mesh: the scene's mesh files must end in _<level> (e.g.
    /// disc_medium.inp), the other levels are found by replacing it
    #[arg(long, value_delimiter = ',', default_value = "coarse,medium,fine")]
    pub levels: Vec<String>,
}

pub fn run(args: StudyArgs) -> Result<ExitCode> {
    let scene = Scene::read(&args.scene)?;
    let out = args.out.clone().unwrap_or_else(|| default_out(&args.scene));
    squeal_pipeline::model::check_outputs(&scene, &out)?;
    let mus = match &args.mu {
        Some(r) => parse_range(r).map_err(anyhow::Error::msg).context("--mu")?,
        None => scene.mu_values()?,
    };
    let kind = StudyKind::CHOICES
        .iter()
        .find(|c| c.1 == args.kind)
        .map(|c| c.0)
        .context("--kind")?;
    study::run(&scene, &out, kind, &mus, &args.levels, &say)?;
    println!("results in {}", out.join("study").display());
    Ok(ExitCode::SUCCESS)
}
