//! `squeal study`: the parametric stability studies of the paper's sections 6.2–6.4 (piston
//! pressure, contact stiffness, modal damping: Tables 4–6, Figures 9–11 (a, b)), the
//! damping-induced destabilization at vanishing friction, the mesh-convergence study, and the
//! identification of the modes that couple at μ0 ([`squeal_pipeline::study`]).

use crate::commands::stability::say;
use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use squeal_pipeline::model::default_out;
use squeal_pipeline::study::{self, Kind as StudyKind};
use squeal_scene::{Scene, parse_range};
use std::path::PathBuf;
use std::process::ExitCode;

/// Which study to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Kind {
    /// Piston pressure 0.8, 1, 1.2 of nominal (paper Table 4, Figure 9)
    Pressure,
    /// Both contact stiffnesses 0.7, 1, 1.3 of nominal (Table 5, Figure 10)
    Stiffness,
    /// Pair damping D1/D2 of Table 6 (Figure 11)
    Damping,
    /// Damping on the pair alone vs with the global part, at vanishing friction
    Paradox,
    /// mu0 on the coarse, medium and fine meshes, patch and node contact (slow)
    Mesh,
    /// pressure, stiffness, damping and paradox (not mesh)
    All,
}

impl From<Kind> for StudyKind {
    fn from(k: Kind) -> Self {
        match k {
            Kind::Pressure => StudyKind::Pressure,
            Kind::Stiffness => StudyKind::Stiffness,
            Kind::Damping => StudyKind::Damping,
            Kind::Paradox => StudyKind::Paradox,
            Kind::Mesh => StudyKind::Mesh,
            Kind::All => StudyKind::All,
        }
    }
}

#[derive(Args)]
pub struct StudyArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// Which study
    #[arg(long, value_enum, default_value = "all")]
    pub kind: Kind,
    /// Output folder (default: out/<scene name>); results go to <out>/study
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Friction values "start:end:count" (default: the scene's [stability] mu, else 0:1:201)
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
    let mus = match &args.mu {
        Some(r) => parse_range(r).map_err(anyhow::Error::msg).context("--mu")?,
        None => scene.mu_values()?,
    };
    study::run(&scene, &out, args.kind.into(), &mus, &args.levels, &say)?;
    println!("results in {}", out.join("study").display());
    Ok(ExitCode::SUCCESS)
}
