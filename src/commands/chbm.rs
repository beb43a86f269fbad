//! `squeal chbm`: the brake's limit cycle by the Constrained Harmonic Balance Method
//! (sections 4–5 of the paper).

use crate::commands::stability::pipeline;
use anyhow::{Context, Result, bail};
use clap::Args;
use squeal_chbm::{ChbmOptions, ChbmSolution, Outcome, RESTART_AMPLITUDES};
use squeal_pipeline::{Pipeline, chbm};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Clone)]
pub struct ChbmArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// Friction coefficient (default: the scene's [friction] mu)
    #[arg(long, conflicts_with = "mu_ratio")]
    pub mu: Option<f64>,
    /// Friction as a multiple of the Hopf point mu0
    #[arg(long)]
    pub mu_ratio: Option<f64>,
    /// Harmonics of the Fourier series (eq 23)
    #[arg(long, default_value_t = 3)]
    pub harmonics: usize,
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
}

/// CHBM's options from the command line, checked.
pub fn options(harmonics: usize, samples: Option<usize>, plain: bool) -> Result<ChbmOptions> {
    if harmonics == 0 || harmonics > 50 {
        bail!("--harmonics must be between 1 and 50");
    }
    Ok(ChbmOptions {
        harmonics,
        samples,
        ladder: !plain,
        ..ChbmOptions::default()
    })
}

/// Checks the friction arguments before any work.
pub fn check_friction(mu: Option<f64>, mu_ratio: Option<f64>, guessed: bool) -> Result<()> {
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
    if let Some(r) = mu_ratio
        && guessed
        && r <= 1.0
    {
        bail!(
            "--mu-ratio {r}: a guessed start must be above 1 (it starts from the mode that is unstable above the Hopf point mu0); without --guessed-start CHBM starts from the branch of limit cycles, below mu0 too"
        );
    }
    Ok(())
}

pub fn run(args: ChbmArgs) -> Result<ExitCode> {
    let opts = options(args.harmonics, args.samples, args.plain)?;
    let guessed = args.guessed_start || args.amplitude.is_some();
    check_friction(args.mu, args.mu_ratio, guessed)?;
    if let Some(a) = args.amplitude
        && !(a.is_finite() && a > 0.0)
    {
        bail!("--amplitude {a}: must be a positive number");
    }
    let p = pipeline(&args.scene, &args.out, &None)?;
    let sol = if guessed {
        let amplitudes: Vec<f64> = args
            .amplitude
            .map_or(RESTART_AMPLITUDES.to_vec(), |a| vec![a]);
        Some(solve(
            &p,
            args.mu,
            args.mu_ratio,
            &opts,
            &amplitudes,
            !args.no_vtu,
        )?)
    } else {
        solve_on_branch(&p, args.mu, args.mu_ratio, &opts, !args.no_vtu)?
    };
    Ok(match sol {
        Some(s) if s.outcome == Outcome::LimitCycle => ExitCode::SUCCESS,
        _ => ExitCode::from(3),
    })
}

/// CHBM at the friction asked for, started from the branch of limit cycles there (every
/// crossing listed with its stability; the first stable one chosen); `None` when the branch
/// does not reach that friction.
pub fn solve_on_branch(
    p: &Pipeline,
    mu: Option<f64>,
    mu_ratio: Option<f64>,
    opts: &ChbmOptions,
    vtu: bool,
) -> Result<Option<ChbmSolution>> {
    let mu = friction(p, mu, mu_ratio)?;
    let m = p.model()?;
    let st = p.stability()?;
    let mu0 = p
        .mu0()
        .context("the branch of limit cycles starts at the Hopf point")?;
    println!(
        "Hopf point mu0 = {mu0:.6}; limit cycle at mu = {mu:.6} ({:.4} mu0), along the branch from the Hopf point",
        mu / mu0
    );
    let t = std::time::Instant::now();
    let (crossings, chosen) = chbm::solve_along_branch(m, st, mu, opts, p.log())?;
    p.record("CHBM along the branch", t.elapsed().as_secs_f64());
    if crossings.is_empty() {
        println!(
            "the branch of limit cycles ({} harmonics) does not reach mu = {mu:.6}: the brake has no limit cycle of this branch there (see squeal branch for where it has)",
            opts.harmonics
        );
        return Ok(None);
    }
    print!("{}", chbm::crossings_text(mu, &crossings));
    let Some((i, start, sol)) = chosen else {
        return Ok(None);
    };
    println!(
        "CHBM starts from cycle {} ({})",
        i + 1,
        crossings[i].verdict()
    );
    write_solution(p, mu, &start, &sol, vtu)?;
    Ok(Some(sol))
}

/// Prints a solution and writes it to `<out>/chbm`.
fn write_solution(
    p: &Pipeline,
    mu: f64,
    start: &squeal_chbm::ChbmStart,
    sol: &ChbmSolution,
    vtu: bool,
) -> Result<()> {
    let m = p.model()?;
    print!("{}", chbm::solution_text(m, start, sol));
    let dir = p.out.join("chbm");
    chbm::write_solution(&dir, m, mu, sol)?;
    if vtu
        && matches!(
            sol.outcome,
            Outcome::LimitCycle | Outcome::LimitCycleUnconstrained
        )
    {
        let pvd = chbm::write_cycle_vtu(&dir, m, sol, 24, p.log())?;
        println!("limit cycle for ParaView (24 frames): {}", pvd.display());
    }
    println!("results in {}", dir.display());
    Ok(())
}

/// The friction of the limit cycle: `mu`, else `mu_ratio` × μ0, else the scene's.
fn friction(p: &Pipeline, mu: Option<f64>, mu_ratio: Option<f64>) -> Result<f64> {
    Ok(match (mu, mu_ratio) {
        (Some(m), _) => m,
        (None, Some(r)) => r * p.mu0().context("--mu-ratio")?,
        (None, None) => *p
            .scene
            .file
            .friction
            .mu
            .as_ref()
            .context("give --mu, --mu-ratio, or [friction] mu in the scene")?
            .get_ref(),
    })
}

/// Solves CHBM on the pipeline's brake at the friction asked and writes the results to
/// `<out>/chbm`.
pub fn solve(
    p: &Pipeline,
    mu: Option<f64>,
    mu_ratio: Option<f64>,
    opts: &ChbmOptions,
    amplitudes: &[f64],
    vtu: bool,
) -> Result<ChbmSolution> {
    let mu = friction(p, mu, mu_ratio)?;
    p.model()?;
    if let Some(h) = &p.stability()?.sweep.hopf {
        println!(
            "Hopf point mu0 = {:.6}; limit cycle at mu = {mu:.6} ({:.4} mu0)",
            h.mu0,
            mu / h.mu0
        );
    }
    let (start, modal) = p.chbm_start(mu).context("the start at mu")?;
    println!(
        "unstable mode at mu: lambda = {:.3} + {:.3}i (growth {:.3} 1/s, {:.2} Hz)",
        start.lambda.re,
        start.lambda.im,
        start.lambda.re,
        start.lambda.im / std::f64::consts::TAU
    );
    let t = std::time::Instant::now();
    let (sol, a) = chbm::solve_with_restarts(&modal, &start, opts, amplitudes, p.log())?;
    p.record("CHBM", t.elapsed().as_secs_f64());
    if sol.outcome == Outcome::LimitCycle && amplitudes.len() > 1 {
        println!("(initial amplitude p = {a} of the smallest static penetration)");
    }
    write_solution(p, mu, &start, &sol, vtu)?;
    Ok(sol)
}
