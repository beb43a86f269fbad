//! `squeal compare`: issue #6's comparison of the Constrained Harmonic Balance Method against
//! BDF time integration of the full brake — the paper's Tables 1–2 and Figures 4–5 for our
//! brake, a speed–accuracy chart, and (with `--grid`) where each method fails. The work and
//! the files are [`squeal_pipeline::compare`]'s; this command parses and prints.

use crate::commands::stability::pipeline;
use anyhow::Result;
use clap::Args;
use squeal_pipeline::Pipeline;
use squeal_pipeline::compare::{self, CompareSettings};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Clone)]
pub struct CompareArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// Friction levels as multiples of the Hopf point mu0 (comma-separated)
    #[arg(long, value_delimiter = ',', default_values_t = CompareSettings::default().mu_ratios)]
    pub mu_ratio: Vec<f64>,
    /// Harmonics of the CHBM solves (comma-separated)
    #[arg(long, value_delimiter = ',', default_values_t = CompareSettings::default().harmonics)]
    pub harmonics: Vec<usize>,
    /// Tolerances of the time integrations on the speed-accuracy chart (comma-separated)
    #[arg(long, value_delimiter = ',', default_values_t = CompareSettings::default().rtols)]
    pub rtol: Vec<f64>,
    /// Tolerance of the reference time integration (continued from the steady cycle of a rtol
    /// 1e-6 run; a run at 10 times this tolerance estimates its own error)
    #[arg(long, default_value_t = CompareSettings::default().reference_rtol)]
    pub reference_rtol: f64,
    /// Initial perturbation of the time integration along the unstable mode, as a fraction of
    /// the smallest static penetration
    #[arg(long, default_value_t = CompareSettings::default().perturbation)]
    pub perturbation: f64,
    /// Highest BDF order of the time integrations
    #[arg(long, default_value_t = CompareSettings::default().max_order)]
    pub max_order: usize,
    /// Also map where CHBM converges over mu/mu0 x initial amplitude x harmonics, and the time
    /// integration over the same mu (slow: minutes)
    #[arg(long)]
    pub grid: bool,
    /// Output folder (default: out/<scene name>)
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
            grid: self.grid,
        }
    }
}

pub fn run(args: CompareArgs) -> Result<ExitCode> {
    let settings = args.settings();
    settings.validate()?;
    let p = pipeline(&args.scene, &args.out, &None)?;
    write(&p, &settings, None)?;
    Ok(ExitCode::SUCCESS)
}

/// Runs the comparison of `p` (reusing `first`, the start at the first level, when given) into
/// `<out>/compare`; returns its summary.
pub fn write(
    p: &Pipeline,
    settings: &CompareSettings,
    first: Option<(
        squeal_chbm::ChbmStart,
        squeal_brake::modal_brake::ModalBrake,
    )>,
) -> Result<serde_json::Value> {
    let mu0 = p.mu0()?;
    let dir = p.out.join("compare");
    let t = std::time::Instant::now();
    let summary = compare::run(
        p.model()?,
        p.stability()?,
        mu0,
        first,
        settings,
        &dir,
        p.log(),
    )?;
    p.record("comparison", t.elapsed().as_secs_f64());
    println!("\nresults in {}", dir.display());
    Ok(summary)
}
