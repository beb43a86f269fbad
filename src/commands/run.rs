//! `squeal run`: the whole pipeline on a scene — reduction, stability, the branch of limit
//! cycles with their stability, CHBM limit cycle and its comparison with time integration — and a report folder whose `index.html` / `index.md` shows
//! every figure and table. One [`squeal_pipeline::Pipeline`] carries the stages: the reduced
//! model, the brake and the friction sweep are computed once and shared by all of them.

use crate::commands::{branch, chbm, compare, stability};
use anyhow::{Context, Result};
use clap::Args;
use squeal_pipeline::compare::CompareSettings;
use squeal_pipeline::cycle::CyclePlan;
use squeal_pipeline::report::{self, RunResults, build};
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
}

pub fn run(args: RunArgs) -> Result<ExitCode> {
    let t0 = Instant::now();
    let settings = CompareSettings {
        mu_ratios: args.compare_mu_ratio.clone(),
        rtols: args.compare_rtol.clone(),
        ..CompareSettings::default()
    };
    settings.validate()?;
    let p = stability::pipeline(&args.scene, &args.out, &None)?;
    let plan = CyclePlan::of_scene(&p.scene)?;
    // An earlier run's report must not describe this run's files if this run stops early.
    let removed = squeal_pipeline::folder::remove_earlier(&p.out, report::is_report_file);
    if !removed.is_empty() {
        println!(
            "removed the earlier run's report ({} files); this run writes its own at the end",
            removed.len()
        );
    }

    println!("== 1. reduced model");
    p.model()?;

    println!("\n== 2. stability");
    let verdict = stability::write(&p, true)?;
    let (mut branch, mut cycle, mut summary) = (None, None, None);
    if verdict.is_stable() {
        println!(
            "\n== 3-5. skipped: {verdict}; without a Hopf point there is no limit cycle to follow, \
             solve or compare"
        );
    } else {
        println!("\n== 3. branch of limit cycles and their stability");
        branch = branch::write(&p, &squeal_pipeline::branch::BranchOptions::default(), &[])?;

        println!("\n== 4. limit cycle (CHBM)");
        cycle = Some(chbm::solve(&p, &plan, true)?);

        if !args.no_compare {
            println!("\n== 5. CHBM against time integration");
            summary = Some(compare::write(&p, &settings)?);
        }
    }

    println!("\n== 6. report");
    let timings = p.timings();
    let results = RunResults {
        scene: &p.scene,
        model: p.model()?,
        stability: p.stability()?,
        branch: branch.as_ref(),
        chbm: cycle.as_ref(),
        compare: summary.as_ref(),
        timings: &timings,
    };
    let notes = build(&results, &p.out, p.log())
        .context("the report's pictures")?
        .write(&p.out)
        .context("writing the report")?;
    for n in notes {
        eprintln!("report: {n}");
    }
    println!(
        "\nreport: {} ({:.1} s in all)\n{verdict}",
        p.out.join("index.html").display(),
        t0.elapsed().as_secs_f64()
    );
    Ok(match &cycle {
        Some(c) if c.cycle().is_none() => ExitCode::from(3),
        _ => ExitCode::SUCCESS,
    })
}
