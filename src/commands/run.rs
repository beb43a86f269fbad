//! `squeal run`: the whole pipeline on a scene — reduction, stability, the branch of limit
//! cycles with their stability, CHBM limit cycle and its comparison with time integration — and a report folder whose `index.html` / `index.md` shows
//! every figure and table. One [`squeal_pipeline::Pipeline`] carries the stages: the reduced
//! model, the brake and the friction sweep are computed once and shared by all of them. The
//! order of the stages is [`squeal_pipeline::stages::run`]'s; this command fills its plan.

use crate::commands::stability;
use anyhow::Result;
use clap::Args;
use squeal_pipeline::compare::CompareSettings;
use squeal_pipeline::stages::{self, RunPlan};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Args)]
pub struct RunArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// Output folder (default: out/ and the scene's path from the working directory without
    /// .toml: out/meshes/brake for meshes/brake.toml)
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Skip the comparison with time integration (the slowest stage)
    #[arg(long)]
    pub no_compare: bool,
    /// Friction levels of the comparison, as multiples of mu0 (a comma-separated list)
    #[arg(long, value_delimiter = ',', default_value = "1.01,1.1")]
    pub compare_mu_ratio: Vec<f64>,
    /// Tolerances of the comparison's time integrations to the steady cycle (a
    /// comma-separated list; the reference is the periodic orbit by shooting)
    #[arg(long, value_delimiter = ',', default_value = "1e-5,1e-6,1e-7")]
    pub compare_rtol: Vec<f64>,
    #[arg(long, value_name = "X,Y,Z", help = crate::commands::mic::HELP, allow_hyphen_values = true, value_parser = squeal_pipeline::sound::parse_microphone)]
    pub mic: Vec<[f64; 3]>,
}

pub fn run(args: RunArgs) -> Result<ExitCode> {
    let t0 = Instant::now();
    let settings = CompareSettings {
        mu_ratios: args.compare_mu_ratio.clone(),
        rtols: args.compare_rtol.clone(),
        ..CompareSettings::default()
    };
    settings.validate()?;
    let mut p = stability::pipeline(&args.scene, &args.out, &None)?;
    crate::commands::mic::apply(&mut p, &args.mic)?;
    let plan = RunPlan {
        compare: (!args.no_compare).then_some(settings),
        ..RunPlan::of_scene(&p)?
    };
    let done = stages::run(&p, &plan)?;
    for n in done.report_notes {
        eprintln!("report: {n}");
    }
    println!(
        "\nreport: {} ({:.1} s in all)\n{}",
        p.out.join("index.html").display(),
        t0.elapsed().as_secs_f64(),
        done.verdict
    );
    Ok(match &done.cycle {
        Some(c) if c.cycle().is_none() => ExitCode::from(3),
        _ => ExitCode::SUCCESS,
    })
}
