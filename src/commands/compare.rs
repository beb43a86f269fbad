//! `squeal compare`: issue #6's comparison of the Constrained Harmonic Balance Method against
//! BDF time integration of the full brake — the paper's Tables 1–2 and Figures 4–5 for our
//! brake, a speed–accuracy chart, and (with `--grid`) where each method fails — both judged
//! against the brake's periodic orbit by shooting (issue #22). The work and
//! the files are [`squeal_pipeline::compare`]'s; this command parses and prints.

use crate::commands::stability::pipeline;
use anyhow::Result;
use clap::Args;
use squeal_pipeline::Pipeline;
use squeal_pipeline::compare::CompareSettings;
use squeal_pipeline::stages;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Clone)]
pub struct CompareArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// Friction levels as multiples of the Hopf point mu0, a comma-separated list without
    /// spaces, e.g. 1.01,1.05,1.1
    #[arg(long, value_delimiter = ',', default_value = "1.01,1.1")]
    pub mu_ratio: Vec<f64>,
    /// Harmonics of the CHBM solves, a comma-separated list, e.g. 1,3,5
    #[arg(long, value_delimiter = ',', default_value = "1,2,3,5,10")]
    pub harmonics: Vec<usize>,
    /// Tolerances of the time integrations from the unstable equilibrium to the steady cycle
    /// (the cost side of the comparison; one that finds no steady cycle is reported as failed),
    /// a comma-separated list
    #[arg(long, value_delimiter = ',', default_value = "1e-5,1e-6,1e-7")]
    pub rtol: Vec<f64>,
    /// BDF tolerance of the reference limit cycle, found by shooting (Newton on the start and
    /// the period) from CHBM's cycle; a solve at 10 times this tolerance states its error
    #[arg(long, default_value = "1e-10")]
    pub reference_rtol: f64,
    /// Initial perturbation of the time integration along the unstable mode, as a fraction of
    /// the smallest static penetration
    #[arg(long, default_value_t = CompareSettings::default().perturbation)]
    pub perturbation: f64,
    /// Highest BDF order of the time integrations
    #[arg(long, default_value_t = CompareSettings::default().max_order)]
    pub max_order: usize,
    /// Periods after which a time integration that has not settled is reported as failed
    #[arg(long, default_value_t = CompareSettings::default().max_cycles)]
    pub max_cycles: f64,
    /// Also map where CHBM converges over mu/mu0 x initial amplitude x harmonics, and the time
    /// integration over the same mu (slow: minutes)
    #[arg(long)]
    pub grid: bool,
    /// Output folder (default: out/ and the scene's path from the working directory without
    /// .toml: out/meshes/brake for meshes/brake.toml)
    #[arg(long, short)]
    pub out: Option<PathBuf>,
}

impl CompareArgs {
    fn settings(&self) -> CompareSettings {
        CompareSettings {
            mu_ratios: self.mu_ratio.clone(),
            harmonics: self.harmonics.clone(),
            rtols: self.rtol.clone(),
            reference_rtol: self.reference_rtol,
            perturbation: self.perturbation,
            max_order: self.max_order,
            max_cycles: self.max_cycles,
            grid: self.grid,
        }
    }
}

pub fn run(args: CompareArgs) -> Result<ExitCode> {
    let settings = args.settings();
    settings.validate()?;
    let p = pipeline(&args.scene, &args.out, &None)?;
    write(&p, &settings)?;
    Ok(ExitCode::SUCCESS)
}

/// Runs the comparison of `p` into `<out>/compare` ([`stages::compare_stage`]); returns its
/// summary.
pub fn write(
    p: &Pipeline,
    settings: &CompareSettings,
) -> Result<squeal_pipeline::compare::CompareSummary> {
    Ok(stages::compare_stage(p, settings)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: CompareArgs,
    }

    /// The defaults shown by `--help` (written as text, so the list syntax reads as typed) are
    /// the library's defaults.
    #[test]
    fn help_defaults_are_the_library_defaults() {
        let cli = Cli::try_parse_from(["compare", "scene.toml"]).unwrap();
        assert_eq!(cli.args.settings(), CompareSettings::default());
        let cli = Cli::try_parse_from(["compare", "s.toml", "--mu-ratio", "1.02,1.2"]).unwrap();
        assert_eq!(cli.args.mu_ratio, vec![1.02, 1.2]);
    }
}
