//! `squeal chbm`: the brake's limit cycle by the Constrained Harmonic Balance Method
//! (sections 4–5 of the paper).

use crate::commands::stability::pipeline;
use anyhow::{Result, bail};
use clap::Args;
use squeal_pipeline::chbm::RESTART_AMPLITUDES;
use squeal_pipeline::cycle::{CyclePlan, CycleStart, LimitCycle};
use squeal_pipeline::{Pipeline, stages};
use squeal_scene::CycleFriction;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Clone)]
pub struct ChbmArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// Friction coefficient (default: the scene's limit cycle, [chbm] mu or mu_ratio, else
    /// 1.02 mu0)
    #[arg(long, conflicts_with = "mu_ratio")]
    pub mu: Option<f64>,
    /// Friction as a multiple of the Hopf point mu0
    #[arg(long)]
    pub mu_ratio: Option<f64>,
    /// Harmonics of the Fourier series (eq 23) (default: the scene's [chbm] harmonics, else 3)
    #[arg(long)]
    pub harmonics: Option<usize>,
    /// AFT time samples per period (default grows with the harmonics)
    #[arg(long)]
    pub samples: Option<usize>,
    /// Initial amplitude p of eq (48), as a fraction of the smallest static penetration; when
    /// omitted, 0.5, 1, 2 and 0.25 are tried in turn until one converges (implies
    /// --guessed-start)
    #[arg(long)]
    pub amplitude: Option<f64>,
    /// Start from eq (48) (the unstable mode at a guessed amplitude) instead of from the branch
    /// of limit cycles followed from the Hopf point to mu
    #[arg(long)]
    pub guessed_start: bool,
    /// Start all harmonics from eq (48) directly instead of from the one-harmonic solution
    #[arg(long)]
    pub plain: bool,
    /// Output folder (default: out/ and the scene's path from the working directory without
    /// .toml: out/meshes/brake for meshes/brake.toml)
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Skip the VTU time series of the limit cycle
    #[arg(long)]
    pub no_vtu: bool,
    #[arg(long, value_name = "X,Y,Z", help = crate::commands::mic::HELP, allow_hyphen_values = true, value_parser = squeal_pipeline::sound::parse_microphone)]
    pub mic: Vec<[f64; 3]>,
    /// Where two modes are unstable at mu: the generalized CHBM (each mode's cycle with Hill's
    /// verdict, the two-mode quasi-periodic torus with its Lyapunov exponents) instead of one
    /// cycle; written to <out>/chbm/two_mode.txt
    #[arg(long)]
    pub two_mode: bool,
}

/// The limit cycle the command line asks for: the scene's ([`CyclePlan::of_scene`]) with the
/// flags given put in its place, checked before any work.
pub fn plan(p: &Pipeline, args: &ChbmArgs) -> Result<CyclePlan> {
    let mut plan = CyclePlan::of_scene(&p.scene)?;
    match (args.mu, args.mu_ratio) {
        (Some(m), _) => plan.at = CycleFriction::Mu(m),
        (None, Some(r)) => plan.at = CycleFriction::Ratio(r),
        (None, None) => {}
    }
    if let Some(h) = args.harmonics {
        if h == 0 || h > 50 {
            bail!("--harmonics must be between 1 and 50");
        }
        plan.options.harmonics = h;
    }
    plan.options.samples = args.samples;
    plan.options.ladder = !args.plain;
    if args.guessed_start || args.amplitude.is_some() {
        let amplitudes = args
            .amplitude
            .map_or(RESTART_AMPLITUDES.to_vec(), |a| vec![a]);
        plan.start = CycleStart::Guessed { amplitudes };
    }
    check_guessed(&plan, args.mu_ratio.is_some())?;
    Ok(plan)
}

/// Checks the friction arguments before any work.
pub fn check_friction(mu: Option<f64>, mu_ratio: Option<f64>) -> Result<()> {
    if let Some(m) = mu
        && !(m.is_finite() && m >= 0.0)
    {
        bail!("--mu {m}: the friction coefficient must be a number >= 0");
    }
    if let Some(r) = mu_ratio
        && !(r.is_finite() && r > 0.0)
    {
        bail!("--mu-ratio {r}: must be a positive multiple of the Hopf point mu0");
    }
    Ok(())
}

/// A guessed start needs a friction above the Hopf point (`flag`: the ratio is the command
/// line's, else the scene's).
fn check_guessed(plan: &CyclePlan, flag: bool) -> Result<()> {
    if let (CycleStart::Guessed { .. }, CycleFriction::Ratio(r)) = (&plan.start, plan.at)
        && r <= 1.0
    {
        let given = if flag {
            format!("--mu-ratio {r}")
        } else {
            format!("[chbm] mu_ratio = {r} (the scene's)")
        };
        bail!(
            "{given}: a guessed start must be above 1 (it starts from the mode that is unstable above the Hopf point mu0); without --guessed-start CHBM starts from the branch of limit cycles, below mu0 too"
        );
    }
    Ok(())
}

pub fn run(args: ChbmArgs) -> Result<ExitCode> {
    check_friction(args.mu, args.mu_ratio)?;
    if let Some(a) = args.amplitude
        && !(a.is_finite() && a > 0.0)
    {
        bail!("--amplitude {a}: must be a positive number");
    }
    let mut p = pipeline(&args.scene, &args.out, &None)?;
    let plan = plan(&p, &args)?;
    if args.two_mode {
        let mu = p.cycle_mu(plan.at)?;
        let r = squeal_pipeline::two_mode::two_mode(&p, mu, plan.options.harmonics)?;
        print!("{}", squeal_pipeline::two_mode::report_text(&r));
        squeal_pipeline::two_mode::write(&p.out.join("chbm"), &r)?;
        return Ok(if r.torus.is_ok() {
            ExitCode::SUCCESS
        } else {
            ExitCode::from(3)
        });
    }
    crate::commands::mic::apply(&mut p, &args.mic)?;
    let lc = solve(&p, &plan, !args.no_vtu)?;
    Ok(if lc.cycle().is_some() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(3)
    })
}

/// Computes the limit cycle of `plan`, prints how it was reached and what it is, and writes it
/// to `<out>/chbm` ([`stages::cycle_stage`]).
pub fn solve(p: &Pipeline, plan: &CyclePlan, vtu: bool) -> Result<LimitCycle> {
    Ok(stages::cycle_stage(p, plan, vtu)?)
}
