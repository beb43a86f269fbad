//! `squeal branch`: where and how loud the brake squeals. The branch of limit cycles from the
//! Hopf point in μ, through its folds, with each cycle's Floquet stability (issue 10), and past
//! each Neimark–Sacker point the torus branch with each torus' stability (issue 24).

use crate::commands::stability::pipeline;
use anyhow::{Result, bail};
use clap::Args;

use squeal_pipeline::branch::{BranchOptions, Harmonics};
use squeal_pipeline::branch_torus::{TorusPlan, Truncation};
use squeal_pipeline::{Pipeline, branch, stages};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Clone)]
pub struct BranchArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// The branch ends below this multiple of mu0
    #[arg(long, default_value_t = 0.5)]
    pub min_ratio: f64,
    /// The branch ends above this multiple of mu0
    #[arg(long, default_value_t = 1.3)]
    pub max_ratio: f64,
    /// Use this many harmonics everywhere (default: from 3, two more wherever the highest
    /// holds more than 1e-6 of the vibration's energy, up to --max-harmonics)
    #[arg(long)]
    pub harmonics: Option<usize>,
    /// Most harmonics of the adaptive choice
    #[arg(long, default_value_t = 15)]
    pub max_harmonics: usize,
    /// Most cycles on the branch
    #[arg(long, default_value_t = 400)]
    pub max_points: usize,
    /// Also report the branch's cycles at these multiples of mu0 (comma list, e.g. 0.998,1.01):
    /// every crossing, each with its stability
    #[arg(long, value_delimiter = ',')]
    pub at: Vec<f64>,
    /// Output folder (default: out/ and the scene's path from the working directory without
    /// .toml: out/meshes/brake for meshes/brake.toml)
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Stop at the Neimark-Sacker points (default: follow the torus branch born at each, with
    /// each torus' stability from its Lyapunov exponents)
    #[arg(long)]
    pub no_torus: bool,
    /// The tori's 2-D Fourier basis as the box |k1| <= H1, |k2| <= H2 (default: H1 the
    /// cycle's harmonics at the Neimark-Sacker point, H2 = 2)
    #[arg(long, value_name = "H1,H2", value_delimiter = ',')]
    pub torus_box: Vec<usize>,
    /// Most tori on each torus branch
    #[arg(long, default_value_t = 60)]
    pub torus_points: usize,
    /// Skip the tori's Lyapunov exponents (their stability is then "not computed")
    #[arg(long)]
    pub no_torus_stability: bool,
    #[arg(long, value_name = "X,Y,Z", help = crate::commands::mic::HELP, allow_hyphen_values = true, value_parser = squeal_pipeline::sound::parse_microphone)]
    pub mic: Vec<[f64; 3]>,
}

/// The branch's options from the command line, checked before any work.
pub fn options(args: &BranchArgs) -> Result<BranchOptions> {
    let (lo, hi) = (args.min_ratio, args.max_ratio);
    if !(lo.is_finite() && hi.is_finite() && 0.0 < lo && lo < 1.0 && hi > 1.0) {
        bail!("--min-ratio must be in (0, 1) and --max-ratio above 1 (got {lo} and {hi})");
    }
    let check = |h: usize, name: &str| {
        if (1..=50).contains(&h) {
            Ok(h)
        } else {
            bail!("{name} must be between 1 and 50 (got {h})")
        }
    };
    let harmonics = match args.harmonics {
        Some(h) => Harmonics::Fixed(check(h, "--harmonics")?),
        None => Harmonics::Adaptive {
            start: 3.min(check(args.max_harmonics, "--max-harmonics")?),
            max: args.max_harmonics,
            tolerance: 1e-6,
        },
    };
    if let Some(r) = args.at.iter().find(|r| !(r.is_finite() && **r > 0.0)) {
        bail!("--at takes positive multiples of mu0 (got {r})");
    }
    if args.max_points < 2 {
        bail!("--max-points must be at least 2");
    }
    let mut o = {
        let mut o = BranchOptions::default();
        o.harmonics = harmonics;
        o.range = (lo, hi);
        o
    };
    o.continuation.max_points = args.max_points;
    Ok(o)
}

/// The torus plan from the command line, checked before any work.
pub fn torus_plan(args: &BranchArgs) -> Result<TorusPlan> {
    let mut plan = TorusPlan {
        enabled: !args.no_torus,
        ..TorusPlan::default()
    };
    match args.torus_box[..] {
        [] => {}
        [h1, h2] if (1..=50).contains(&h1) && (1..=20).contains(&h2) => {
            plan.truncation = Some(Truncation::Box(h1, h2))
        }
        _ => bail!(
            "--torus-box takes two orders H1,H2 with H1 in 1..=50 and H2 in 1..=20 (got {})",
            args.torus_box
                .iter()
                .map(|h| h.to_string())
                .collect::<Vec<_>>()
                .join(",")
        ),
    }
    if args.torus_points < 2 {
        bail!("--torus-points must be at least 2");
    }
    plan.max_points = args.torus_points;
    if args.no_torus_stability {
        plan.lyapunov = None;
    }
    Ok(plan)
}

pub fn run(args: BranchArgs) -> Result<ExitCode> {
    let opts = options(&args)?;
    let plan = torus_plan(&args)?;
    let mut p = pipeline(&args.scene, &args.out, &None)?;
    crate::commands::mic::apply(&mut p, &args.mic)?;
    Ok(if write(&p, &opts, &args.at, &plan)?.is_some() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(3)
    })
}

/// Follows the branch of `p` and writes `<out>/branch`, with the cycles at `at` × μ0 and the
/// torus branches of `plan` ([`stages::branch_stage_with`]); `None` when there is no Hopf
/// point.
pub fn write(
    p: &Pipeline,
    opts: &BranchOptions,
    at: &[f64],
    plan: &TorusPlan,
) -> Result<Option<branch::BranchAnalysis>> {
    Ok(stages::branch_stage_with(p, opts, at, plan)?)
}
