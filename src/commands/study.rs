//! `squeal study`: the parametric stability studies of the paper's sections 6.2–6.4 (piston
//! pressure, contact stiffness, modal damping: Tables 4–6, Figures 9–11 (a, b)), the
//! damping-induced destabilization at vanishing friction, the mesh-convergence study, and the
//! identification of the modes that couple at μ0 ([`squeal_pipeline::study`]); split into
//! shards for a batch scheduler (`--shard i/n`) and merged (`--merge`).

use crate::progress::say;
use anyhow::{Context, Result};
use clap::Args;
use squeal_pipeline::model::default_out;
use squeal_pipeline::study::convergence::{self, ContactLevel, Knob};
use squeal_pipeline::study::{self, Kind as StudyKind, Shard};
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
#[command(
    after_help = "On a cluster: run the study's shards as independent jobs (a Slurm job array, GNU \
parallel), each with the same options and --shard i/n (1-based: 1/n .. n/n), then the same command \
with --merge instead of --shard. The shards write <out>/study/shards/<kind>-<i>-of-<n>.json; the \
merge checks that all n are there, from one split, computed from this scene and meshes with these \
--mu and --levels, and writes the same tables and figures as the unsplit run, bit for bit. Units \
are dealt round-robin: unit u (0-based) to shard u mod n + 1; every shard but the mesh study's \
also computes the nominal sweep. README.md, \"Studies on a cluster\", has a Slurm script."
)]
pub struct StudyArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// Which study
    #[arg(long, value_parser = kind_parser(), default_value = "all")]
    pub kind: String,
    /// Output folder (default: out/ and the scene's path from the working directory without
    /// .toml: out/meshes/brake for meshes/brake.toml); results go to <out>/study
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Friction values "start..end/count": count values from start to end, e.g. 0..1/201
    /// (default: the scene's [stability] mu, else 0..1/201)
    #[arg(long)]
    pub mu: Option<String>,
    /// Mesh levels of --kind mesh (default coarse,medium,fine) and of --kind convergence (the
    /// first is the base of every knob; default: the scene's level, then each finer one on
    /// disk): the scene's mesh files must end in _<level> (e.g. disc_medium.inp), the other
    /// levels are found by replacing it
    #[arg(long, value_delimiter = ',')]
    pub levels: Vec<String>,
    /// --kind convergence: the knobs to refine, one at a time from the scene's settings
    #[arg(long, value_delimiter = ',', default_value = "contact,modes,mesh", value_parser = Knob::parse)]
    pub knobs: Vec<Knob>,
    /// --kind convergence: the contact levels after the scene's own, patch grids RxA (radial x
    /// angular) or nodal (default for a 3x3 scene: 3x5,5x5,nodal)
    #[arg(long, value_delimiter = ',', value_parser = ContactLevel::parse)]
    pub grids: Vec<ContactLevel>,
    /// --kind convergence: factors on the scene's kept modes per part after x1
    #[arg(long, value_delimiter = ',', default_value = "1.5,2")]
    pub mode_factors: Vec<f64>,
    /// --kind convergence: the friction of the growth-rate column (default: the scene's
    /// [chbm] friction, a ratio of it taken on the base level's mu0)
    #[arg(long)]
    pub growth_mu: Option<f64>,
    /// --kind convergence: the estimated relative error of the last level's mu0 (its last
    /// change, or what the observed rate says is still to come when larger) below which a knob
    /// has converged
    #[arg(long, default_value_t = squeal_pipeline::study::verdict::DEFAULT_TOLERANCE)]
    pub tolerance: f64,
    /// Compute only shard i of n (1-based, e.g. 2/4) and write it to
    /// <out>/study/shards/<kind>-<i>-of-<n>.json, for a batch scheduler; merge with --merge
    #[arg(long, value_name = "I/N", value_parser = Shard::parse, conflicts_with = "merge")]
    pub shard: Option<Shard>,
    /// Merge the shards in <out>/study/shards into the study's tables and figures (give the
    /// shards' --kind, --mu and --levels)
    #[arg(long)]
    pub merge: bool,
}

pub fn run(args: StudyArgs) -> Result<ExitCode> {
    let scene = Scene::read(&args.scene)?;
    let out = args.out.clone().unwrap_or_else(|| default_out(&args.scene));
    squeal_pipeline::model::check_outputs(&scene, &out)?;
    // The shards of one study write into one folder at once, by design, and the merge reads
    // what they (or a copy) left there: neither takes the folder.
    if args.shard.is_none() && !args.merge {
        super::stability::take_folder(&args.scene, &out)?;
    }
    let mus = match &args.mu {
        Some(r) => parse_range(r).map_err(anyhow::Error::msg).context("--mu")?,
        None => scene.mu_values()?,
    };
    let kind = StudyKind::CHOICES
        .iter()
        .find(|c| c.1 == args.kind)
        .map(|c| c.0)
        .context("--kind")?;
    let levels = if args.levels.is_empty() && kind != StudyKind::Convergence {
        ["coarse", "medium", "fine"].map(String::from).to_vec()
    } else {
        args.levels.clone()
    };
    if kind == StudyKind::Convergence && args.shard.is_none() && !args.merge {
        let opts = convergence::Options {
            knobs: args.knobs.clone(),
            contacts: (!args.grids.is_empty()).then(|| args.grids.clone()),
            mode_factors: args.mode_factors.clone(),
            levels,
            growth_mu: args.growth_mu,
            tolerance: args.tolerance,
        };
        let s = convergence::run(&scene, &out, &mus, &opts, &say)?;
        println!("{}", s.overall.1);
        println!("results in {}", out.join("study").display());
        return Ok(ExitCode::SUCCESS);
    }
    if args.merge {
        let n = study::merge(&scene, &out, kind, &mus, &levels, &say)?;
        println!(
            "merged {n} shards: results in {}",
            out.join("study").display()
        );
    } else if let Some(shard) = args.shard {
        let path = study::run_shard(&scene, &out, kind, &mus, &levels, shard, &say)?;
        println!(
            "shard {shard} in {}; when all {} are done: squeal study {} --kind {} ... --merge",
            path.display(),
            shard.count,
            args.scene.display(),
            args.kind
        );
    } else {
        study::run(&scene, &out, kind, &mus, &levels, &say)?;
        println!("results in {}", out.join("study").display());
    }
    Ok(ExitCode::SUCCESS)
}
