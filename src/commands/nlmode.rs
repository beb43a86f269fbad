//! `squeal nlmode`: the squeal mode's complex nonlinear mode (extended periodic motion
//! concept) at a few friction values: frequency and modal damping against the modal
//! amplitude, and the limit cycles where the damping vanishes; with `--compare`, those cycles
//! against the branch of `squeal branch` at the same μ.

use crate::commands::stability::pipeline;
use anyhow::{Context, Result, bail};
use clap::Args;
use squeal_pipeline::branch::{BranchOptions, Harmonics, HillOptions};
use squeal_pipeline::nlmode::{NlModeOptions, log_spaced};
use squeal_pipeline::{branch, nlmode};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Clone)]
pub struct NlModeArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// Friction values (comma list, e.g. 0.47,0.5); default: --at
    #[arg(long, value_delimiter = ',')]
    pub mu: Vec<f64>,
    /// Friction values as multiples of mu0 (comma list), when --mu is not given
    #[arg(long, value_delimiter = ',', default_values_t = vec![1.01, 1.05, 1.1])]
    pub at: Vec<f64>,
    /// Modal amplitudes "FROM:TO:N", fractions of the amplitude at which the linear mode opens
    /// its first contact pair, N values log-spaced
    #[arg(long, default_value = "0.01:2:40")]
    pub amplitudes: String,
    /// Harmonics of the motion
    #[arg(long, default_value_t = 3)]
    pub harmonics: usize,
    /// Also follow the branch of limit cycles (same harmonics) and compare its cycles at these
    /// friction values with the nonlinear modes' zero-damping points
    #[arg(long)]
    pub compare: bool,
    /// Output folder (default: out/ and the scene's path from the working directory without
    /// .toml: out/meshes/brake for meshes/brake.toml)
    #[arg(long, short)]
    pub out: Option<PathBuf>,
}

/// `FROM:TO:N` as N log-spaced fractions.
fn amplitudes(text: &str) -> Result<Vec<f64>> {
    let parts: Vec<&str> = text.split(':').collect();
    let bad = || format!("--amplitudes takes FROM:TO:N, e.g. 0.01:2:40 (got {text})");
    let [from, to, n] = parts[..] else {
        bail!(bad());
    };
    let from: f64 = from.trim().parse().with_context(bad)?;
    let to: f64 = to.trim().parse().with_context(bad)?;
    let n: usize = n.trim().parse().with_context(bad)?;
    if !(from > 0.0 && to > from && to.is_finite() && (2..=10_000).contains(&n)) {
        bail!(
            "{}: FROM and TO positive with TO above FROM, N from 2 to 10000",
            bad()
        );
    }
    Ok(log_spaced(from, to, n))
}

pub fn run(args: NlModeArgs) -> Result<ExitCode> {
    if !(1..=50).contains(&args.harmonics) {
        bail!(
            "--harmonics must be between 1 and 50 (got {})",
            args.harmonics
        );
    }
    if let Some(v) = args
        .mu
        .iter()
        .chain(&args.at)
        .find(|v| !(v.is_finite() && **v > 0.0))
    {
        bail!("--mu and --at take positive values (got {v})");
    }
    let opts = {
        let mut o = NlModeOptions::default();
        o.harmonics = args.harmonics;
        o.amplitudes = amplitudes(&args.amplitudes)?;
        o
    };
    let p = pipeline(&args.scene, &args.out, &None)?;
    let m = p.model()?;
    let st = p.stability().context("stability analysis")?;
    let Some(mu0) = st.sweep.hopf.as_ref().map(|h| h.mu0) else {
        println!("no Hopf point in the band of the friction sweep: no squeal mode to follow");
        return Ok(ExitCode::from(3));
    };
    let mus: Vec<f64> = if args.mu.is_empty() {
        args.at.iter().map(|r| r * mu0).collect()
    } else {
        args.mu.clone()
    };
    let t = std::time::Instant::now();
    let Some(mut a) = nlmode::analyse(m, st, &mus, &opts, p.log())? else {
        return Ok(ExitCode::from(3));
    };
    p.record("nonlinear modes", t.elapsed().as_secs_f64());
    if args.compare {
        let t = std::time::Instant::now();
        let bo = {
            let mut o = BranchOptions::default();
            o.harmonics = Harmonics::Fixed(args.harmonics);
            o.range = (0.5, 1.05 * mus.iter().fold(1.3f64, |m, v| m.max(v / mu0)));
            o
        };
        let b = branch::analyse(m, st, &bo, &HillOptions::default(), &mus, p.log())?
            .context("the branch of limit cycles")?;
        p.record("branch for the comparison", t.elapsed().as_secs_f64());
        a.checks = nlmode::compare(&a, &b);
    }
    print!("{}", nlmode::summary_text(&a));
    let dir = p.out.join("nlmode");
    nlmode::write(&dir, &a)?;
    println!("results in {}", dir.display());
    Ok(ExitCode::SUCCESS)
}
