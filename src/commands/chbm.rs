//! `squeal chbm`: the brake's limit cycle by the Constrained Harmonic Balance Method
//! (sections 4–5 of the paper).

use crate::output::{PartFields, write_brake_vtu};
use crate::scene::Scene;
use crate::setup::{Setup, default_out, setup};
use anyhow::{Context, Result, bail};
use clap::Args;

use squeal_brake::analysis::{Stability, stability};
use squeal_brake::equilibrium::static_equilibrium;
use squeal_brake::modal_brake::ModalBrake;
use squeal_brake::spectrum::spectrum;
use squeal_chbm::constraint::Fit;
use squeal_chbm::{ChbmOptions, ChbmSolution, ChbmStart, Outcome, solve};
use squeal_report::{Figure, Panel, Scale, Series, Table, write_svg_and_png};
use std::path::{Path, PathBuf};
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
    /// omitted, 0.5, 1, 2 and 0.25 are tried in turn until one converges
    #[arg(long)]
    pub amplitude: Option<f64>,
    /// Start all harmonics from eq (48) directly instead of from the one-harmonic solution
    #[arg(long)]
    pub plain: bool,
    /// Equivalent linearization: fundamental (default) or samples (eq 45's stiffness-only fit)
    #[arg(long, default_value = "fundamental")]
    pub fit: String,
    /// Output folder (default: out/<scene name>)
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Skip the VTU time series of the limit cycle
    #[arg(long)]
    pub no_vtu: bool,
}

/// What a CHBM run needs from the stability analysis.
pub struct Prepared {
    pub setup: Setup,
    #[allow(dead_code)]
    pub stability: Stability,
    pub mu: f64,
    pub start: ChbmStart,
    pub modal: ModalBrake,
}

/// Stability analysis (for the damping pair and μ0), then the unstable mode at μ.
pub fn prepare(
    scene: &Scene,
    out: &Path,
    mu: Option<f64>,
    mu_ratio: Option<f64>,
) -> Result<Prepared> {
    let s = setup(scene, out, true)?;
    let mus = scene.mu_values()?;
    let st = stability(&s.brake, &s.damping, &mus, &s.sweep).context("stability analysis")?;
    let mu0 = st.sweep.hopf.as_ref().map(|h| h.mu0);
    let mu = match (mu, mu_ratio, mu0) {
        (Some(m), _, _) => m,
        (None, Some(r), Some(m0)) => r * m0,
        (None, Some(_), None) => {
            bail!("--mu-ratio needs a Hopf point, and the sweep found none in the band")
        }
        (None, None, _) => *scene
            .file
            .friction
            .mu
            .as_ref()
            .context("give --mu, --mu-ratio, or [friction] mu in the scene")?
            .get_ref(),
    };
    if let Some(m0) = mu0 {
        println!(
            "Hopf point mu0 = {m0:.6}; limit cycle at mu = {mu:.6} ({:.4} mu0)",
            mu / m0
        );
    }
    let eq =
        static_equilibrium(&s.brake, mu, None, &s.sweep.newton).context("static equilibrium")?;
    let sp = spectrum(&s.brake, &st.reference, &eq).context("eigenvalues at mu")?;
    let unstable = (0..sp.values.len())
        .filter(|&j| s.sweep.band.contains(sp.frequency_hz(j)) && sp.values[j].re > 0.0)
        .max_by(|&a, &b| sp.values[a].re.total_cmp(&sp.values[b].re));
    let Some(j) = unstable else {
        bail!(
            "the brake is stable at mu = {mu} in the band (mu0 = {}): there is no limit cycle to compute",
            mu0.map_or("none".into(), |m| format!("{m:.6}"))
        );
    };
    println!(
        "unstable mode at mu: lambda = {:.3} + {:.3}i (growth {:.3} 1/s, {:.2} Hz)",
        sp.values[j].re,
        sp.values[j].im,
        sp.values[j].re,
        sp.frequency_hz(j)
    );
    let start = ChbmStart {
        lambda: sp.values[j],
        mode: sp.shape(&st.reference.basis, j),
        equilibrium: eq.x.clone(),
    };
    let modal = ModalBrake::new(&s.brake, &st.reference, mu);
    Ok(Prepared {
        setup: s,
        stability: st,
        mu,
        start,
        modal,
    })
}

pub fn options(args: &ChbmArgs) -> Result<ChbmOptions> {
    let fit = match args.fit.as_str() {
        "fundamental" => Fit::Fundamental,
        "samples" => Fit::Samples,
        other => bail!("--fit '{other}': expected 'fundamental' or 'samples'"),
    };
    if args.harmonics == 0 || args.harmonics > 50 {
        bail!("--harmonics must be between 1 and 50");
    }
    Ok(ChbmOptions {
        harmonics: args.harmonics,
        samples: args.samples,
        amplitude: args.amplitude.unwrap_or(AMPLITUDES[0]),
        ladder: !args.plain,
        fit,
        ..ChbmOptions::default()
    })
}

pub fn run(args: ChbmArgs) -> Result<ExitCode> {
    let scene = Scene::read(&args.scene)?;
    let out = args.out.clone().unwrap_or_else(|| default_out(&args.scene));
    let opts = options(&args)?;
    let p = prepare(&scene, &out, args.mu, args.mu_ratio)?;
    let amplitudes: Vec<f64> = args.amplitude.map_or(AMPLITUDES.to_vec(), |a| vec![a]);
    let sol = solve_with_restarts(&p, &opts, &amplitudes)?;
    print_solution(&p, &sol);
    let dir = out.join("chbm");
    write_solution(&dir, &p, &sol)?;
    if !args.no_vtu
        && matches!(
            sol.outcome,
            Outcome::LimitCycle | Outcome::LimitCycleUnconstrained
        )
    {
        let vtm = write_cycle_vtu(&dir, &p, &sol, 24)?;
        println!("limit cycle for ParaView (24 frames): {}", vtm.display());
    }
    println!("results in {}", dir.display());
    Ok(if matches!(sol.outcome, Outcome::LimitCycle) {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(3)
    })
}

/// Initial amplitudes tried in turn when none is given.
pub const AMPLITUDES: [f64; 4] = [0.5, 1.0, 2.0, 0.25];

/// Solves from each initial amplitude in turn until a limit cycle converges; returns the first
/// converged solution, or the last attempt.
pub fn solve_with_restarts(
    p: &Prepared,
    opts: &ChbmOptions,
    amplitudes: &[f64],
) -> Result<ChbmSolution> {
    let mut last = None;
    for &a in amplitudes {
        let o = ChbmOptions {
            amplitude: a,
            ..opts.clone()
        };
        let sol = solve(&p.modal, &p.start, &o).context("CHBM")?;
        if matches!(sol.outcome, Outcome::LimitCycle) {
            if amplitudes.len() > 1 {
                println!("(initial amplitude p = {a} of the smallest static penetration)");
            }
            return Ok(sol);
        }
        println!("from initial amplitude p = {a}: {}", sol.outcome);
        last = Some(sol);
    }
    last.context("no initial amplitude to try")
}

/// Physical dof of a point's direction in the brake (disc or pad).
pub fn point_dof(
    p: &Prepared,
    part: &str,
    role_contact_index: usize,
    direction: u8,
) -> Option<usize> {
    let rp = p.setup.rom.part(part)?;
    let offset = if part == "disc" {
        p.setup.layout.disc.start
    } else {
        p.setup.layout.pad.start
    };
    let point = rp
        .info
        .points
        .iter()
        .enumerate()
        .filter(|(_, pt)| pt.role == squeal_reduce::rom::PointRole::Contact)
        .nth(role_contact_index)?
        .0;
    rp.info
        .dofs
        .iter()
        .position(|l| *l == squeal_reduce::rom::DofLabel::Point { point, direction })
        .map(|d| offset + d)
}

fn print_solution(p: &Prepared, s: &ChbmSolution) {
    let f = s.omega / (2.0 * std::f64::consts::PI);
    println!(
        "CHBM, {} harmonics, {} time samples: {}",
        s.harmonics, s.samples, s.outcome
    );
    println!(
        "  frequency {:.4} Hz ({:+.4} Hz from the unstable mode's {:.4} Hz)",
        f,
        f - p.start.lambda.im / (2.0 * std::f64::consts::PI),
        p.start.lambda.im / (2.0 * std::f64::consts::PI)
    );
    println!(
        "  residuals: ||f1||/||F_eq|| = {:.2e}, Re lambda = {:.2e} 1/s (|Re|/omega = {:.1e}); {} LM iterations ({:?}) in {:.1} ms",
        s.f1,
        s.re_lambda,
        s.re_lambda.abs() / s.omega,
        s.iterations,
        s.stop,
        s.time.as_secs_f64() * 1e3
    );
    println!(
        "  checks: aliasing (2x samples) {:.1e}, recovery of the nonlinear dofs {:.1e}",
        s.aliasing, s.recovery_error
    );
    let open: Vec<String> = s
        .open_fraction
        .iter()
        .enumerate()
        .filter(|(_, f)| **f > 0.0)
        .map(|(i, f)| format!("pair {} open {:.0}% of the cycle", i + 1, f * 100.0))
        .collect();
    println!(
        "  contact: {}",
        if open.is_empty() {
            "closed over the whole cycle".into()
        } else {
            open.join(", ")
        }
    );
    let mut t = Table::new(["dof", "mean (um)", "H1 (um)", "H2 (um)", "H3 (um)"]);
    for (name, part, dir) in [
        ("pad contact 5, normal", "pad", 2u8),
        ("disc contact 5, normal", "disc", 2),
        ("pad contact 5, sliding", "pad", 0),
    ] {
        if let Some(d) = point_dof(p, part, 4, dir) {
            let mut row = vec![name.to_string()];
            for k in 0..=3.min(s.harmonics) {
                row.push(format!("{:.4}", s.amplitude(d, k) * 1e6));
            }
            t.push_row(row);
        }
    }
    print!("{}", t.to_text());
}

fn write_solution(dir: &Path, p: &Prepared, s: &ChbmSolution) -> Result<()> {
    let n = p.setup.brake.size();
    let mut coeffs = Table::new(["dof", "harmonic", "cos", "sin"]);
    for d in 0..n {
        coeffs.push_row([
            d.to_string(),
            "0".into(),
            format!("{:e}", s.coeffs[d]),
            "0".into(),
        ]);
        for k in 1..=s.harmonics {
            coeffs.push_row([
                d.to_string(),
                k.to_string(),
                format!("{:e}", s.coeffs[(2 * k - 1) * n + d]),
                format!("{:e}", s.coeffs[2 * k * n + d]),
            ]);
        }
    }
    coeffs.write_csv(&dir.join("coefficients.csv"))?;
    let mut hist = Table::new([
        "evaluation",
        "harmonics",
        "f1_relative",
        "re_lambda",
        "omega",
    ]);
    for (i, e) in s.evaluations.iter().enumerate() {
        hist.push_row([
            i.to_string(),
            e.harmonics.to_string(),
            format!("{:e}", e.f1),
            format!("{:e}", e.re_lambda),
            format!("{}", e.omega),
        ]);
    }
    hist.write_csv(&dir.join("history.csv"))?;
    let json = serde_json::json!({
        "outcome": s.outcome.to_string(),
        "converged": matches!(s.outcome, Outcome::LimitCycle),
        "mu": p.mu,
        "harmonics": s.harmonics,
        "samples": s.samples,
        "frequency_hz": s.omega / (2.0 * std::f64::consts::PI),
        "omega": s.omega,
        "f1_relative": s.f1,
        "re_lambda": s.re_lambda,
        "iterations": s.iterations,
        "time_ms": s.time.as_secs_f64() * 1e3,
        "open_fraction": s.open_fraction,
        "aliasing": s.aliasing,
        "layout": "coefficients[b * n + dof], blocks b = [0c, 1c, 1s, 2c, 2s, ...] (eq 25); x(t) = sum_k Ukc cos(k w t) + Uks sin(k w t)",
        "dofs": n,
        "coefficients": s.coeffs,
    });
    squeal_io::atomic_write_bytes(
        &dir.join("chbm.json"),
        serde_json::to_string_pretty(&json)?.as_bytes(),
    )?;
    // Figures: limit cycles, histories, power per harmonic.
    let mut panels = Vec::new();
    for (title, part) in [
        ("(a) pad contact point 5, normal", "pad"),
        ("(b) disc contact point 5, normal", "disc"),
    ] {
        if let Some(d) = point_dof(p, part, 4, 2) {
            panels.push(Panel {
                title: title.into(),
                x_label: "displacement (m)".into(),
                y_label: "velocity (m/s)".into(),
                series: vec![Series::line(
                    format!("CHBM {} harmonics", s.harmonics),
                    cycle_points(s, d, 256),
                )],
                ..Panel::default()
            });
        }
    }
    write_svg_and_png(
        &Figure {
            title: "Limit cycles (paper Figure 4)".into(),
            panels,
            ..Figure::default()
        },
        &dir.join("limit_cycles"),
    )?;
    let res: Vec<(f64, f64)> = s
        .evaluations
        .iter()
        .enumerate()
        .map(|(i, e)| (i as f64, e.f1))
        .collect();
    let rel: Vec<(f64, f64)> = s
        .evaluations
        .iter()
        .enumerate()
        .map(|(i, e)| (i as f64, e.re_lambda))
        .collect();
    let fig = Figure {
        title: "Convergence (paper Figures 6-7)".into(),
        panels: vec![
            Panel {
                title: "(a) real part of the tracked eigenvalue".into(),
                x_label: "residual evaluation".into(),
                y_label: "Re(lambda) (1/s)".into(),
                series: vec![Series::line_markers("Re lambda", rel)],
                ..Panel::default()
            },
            Panel {
                title: "(b) harmonic balance residual".into(),
                x_label: "residual evaluation".into(),
                y_label: "||f1|| / ||F_eq||".into(),
                y_scale: Scale::Log,
                series: vec![Series::line_markers("f1", res)],
                ..Panel::default()
            },
        ],
        ..Figure::default()
    };
    write_svg_and_png(&fig, &dir.join("convergence"))?;
    Ok(())
}

/// `(x(t), x'(t))` of dof `d` over one period.
pub fn cycle_points(s: &ChbmSolution, d: usize, samples: usize) -> Vec<(f64, f64)> {
    let n = s.coeffs.len() / (2 * s.harmonics + 1);
    (0..=samples)
        .map(|j| {
            let th = 2.0 * std::f64::consts::PI * j as f64 / samples as f64;
            let mut x = s.coeffs[d];
            let mut v = 0.0;
            for k in 1..=s.harmonics {
                let (c, sn) = (s.coeffs[(2 * k - 1) * n + d], s.coeffs[2 * k * n + d]);
                let kf = k as f64;
                x += c * (kf * th).cos() + sn * (kf * th).sin();
                v += s.omega * kf * (-c * (kf * th).sin() + sn * (kf * th).cos());
            }
            (x, v)
        })
        .collect()
}

/// Writes `frames` snapshots of the limit cycle on both meshes and a `.pvd` collection.
fn write_cycle_vtu(dir: &Path, p: &Prepared, s: &ChbmSolution, frames: usize) -> Result<PathBuf> {
    let disc = crate::commands::mesh::read_mesh(&p.setup.disc_mesh)?.mesh;
    let pad = crate::commands::mesh::read_mesh(&p.setup.pad_mesh)?.mesh;
    let (Some(dp), Some(pp)) = (p.setup.rom.part("disc"), p.setup.rom.part("pad")) else {
        bail!("the reduced model lacks a disc or a pad part");
    };
    let n = p.setup.brake.size();
    let period = 2.0 * std::f64::consts::PI / s.omega;
    let mut entries = Vec::new();
    let frames_dir = dir.join("cycle");
    for f in 0..frames {
        let th = 2.0 * std::f64::consts::PI * f as f64 / frames as f64;
        let x: Vec<f64> = (0..n)
            .map(|d| {
                let mut v = s.coeffs[d];
                for k in 1..=s.harmonics {
                    let kf = k as f64;
                    v += s.coeffs[(2 * k - 1) * n + d] * (kf * th).cos()
                        + s.coeffs[2 * k * n + d] * (kf * th).sin();
                }
                v
            })
            .collect();
        let mean: Vec<f64> = (0..n).map(|d| s.coeffs[d]).collect();
        let dynamic: Vec<f64> = x.iter().zip(&mean).map(|(a, b)| a - b).collect();
        let stem = format!("cycle_{f:03}");
        let fields = [
            PartFields {
                name: "displacement",
                brake: x,
            },
            PartFields {
                name: "oscillation",
                brake: dynamic,
            },
        ];
        write_brake_vtu(
            &frames_dir,
            &stem,
            [
                (dp, &disc, p.setup.layout.disc.clone()),
                (pp, &pad, p.setup.layout.pad.clone()),
            ],
            &fields,
        )?;
        entries.push((
            period * f as f64 / frames as f64,
            format!("cycle/{stem}.vtm"),
        ));
    }
    let pvd = dir.join("cycle.pvd");
    squeal_mesh::vtu::write_pvd(&pvd, &entries)?;
    Ok(pvd)
}
