//! `squeal stability`: the paper's section 3 for a scene: static equilibrium, complex
//! eigenvalues against friction (Figure 2), the Hopf point μ0 and the unstable mode shape.

use crate::output::{PartFields, normalize_mode, write_brake_vtu};
use crate::scene::{Scene, parse_range};
use crate::setup::{Setup, default_out, setup};
use anyhow::{Context, Result};
use clap::Args;
use squeal_brake::analysis::{Stability, stability};
use squeal_report::format::fmt_sig;
use squeal_report::{Annotation, Dash, Figure, Panel, Rgb, Series, Table, write_svg_and_png};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

#[derive(Args)]
pub struct StabilityArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// Friction values "start:end:count" (default: the scene's [stability] mu, else 0:1:201)
    #[arg(long)]
    pub mu: Option<String>,
    /// Output folder (default: out/<scene name>)
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Skip the VTU files of the equilibrium and mode shape
    #[arg(long)]
    pub no_vtu: bool,
}

pub fn run(args: StabilityArgs) -> Result<ExitCode> {
    let scene = Scene::read(&args.scene)?;
    let out = args.out.clone().unwrap_or_else(|| default_out(&args.scene));
    let s = setup(&scene, &out, true)?;
    let mus = match &args.mu {
        Some(r) => parse_range(r).map_err(anyhow::Error::msg).context("--mu")?,
        None => scene.mu_values()?,
    };
    print_pairs(&s);
    let t = Instant::now();
    let st = stability(&s.brake, &s.damping, &mus, &s.sweep).context("stability analysis")?;
    let elapsed = t.elapsed();
    let dir = out.join("stability");
    print_summary(&s, &st, elapsed.as_secs_f64());
    write_tables(&dir, &s, &st)?;
    write_figures(&dir, &st, &s)?;
    if !args.no_vtu {
        write_shapes(&dir, &s, &st)?;
    }
    println!("results in {}", dir.display());
    Ok(ExitCode::SUCCESS)
}

fn print_pairs(s: &Setup) {
    println!("contact pairs (disc point, pad point, distance, area, k_l, k_nl):");
    for p in &s.pairs {
        println!(
            "  {:>2} {:>2}  {:.1e} m  {} m^2  {:.4e} N/m  {:.4e} N/m^3",
            p.disc_point + 1,
            p.pad_point + 1,
            p.distance,
            p.area.map_or("-".into(), |a| format!("{a:.4e}")),
            p.k_linear,
            p.k_cubic
        );
    }
    println!(
        "piston force {:.1} N on {} piston dofs",
        s.params.piston_force,
        s.brake.f_piston.iter().filter(|f| **f != 0.0).count()
    );
}

/// Kinetic-energy share of the disc in a mode `x` (reduced brake coordinates).
pub fn disc_share(s: &Setup, x: &[faer::c64]) -> f64 {
    let m = &s.brake.m;
    let energy = |r: std::ops::Range<usize>| -> f64 {
        let mut e = 0.0;
        for i in r.clone() {
            for j in r.clone() {
                e += (x[i].conj() * x[j]).re * m[(i, j)];
            }
        }
        e
    };
    let (d, p) = (energy(s.layout.disc.clone()), energy(s.layout.pad.clone()));
    d / (d + p).max(f64::MIN_POSITIVE)
}

fn print_summary(s: &Setup, st: &Stability, seconds: f64) {
    let sw = &st.sweep;
    let eq0 = &st.reference.equilibrium;
    println!(
        "equilibrium at mu = 0: {} Newton iterations, relative residual {:.1e}, {} of {} pairs closed, penetrations {:.1}..{:.1} um",
        eq0.iterations,
        eq0.residual,
        eq0.closed_pairs(),
        eq0.penetrations.len(),
        eq0.penetrations
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min)
            * 1e6,
        eq0.penetrations
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max)
            * 1e6
    );
    println!(
        "sweep: {} friction values {}..{} in {:.2} s; valid band up to {:.0} Hz{}",
        sw.points.len(),
        sw.points[0].equilibrium.mu,
        sw.points[sw.points.len() - 1].equilibrium.mu,
        seconds,
        s.sweep.band.valid_max_hz,
        s.sweep.band.user.map_or(String::new(), |(a, b)| format!(
            ", user band {a:.0}..{b:.0} Hz"
        ))
    );
    let outside: Vec<_> = sw.crossings.iter().filter(|c| !c.in_band).collect();
    for c in &sw.crossings {
        println!(
            "  crossing: branch {} unstable from mu in [{:.4}, {:.4}] at {:.0} Hz{}",
            c.branch,
            c.mu_lo,
            c.mu_hi,
            c.frequency_hz,
            if c.in_band {
                ""
            } else {
                "  (outside the band: not physical for this model)"
            }
        );
    }
    match &sw.hopf {
        Some(h) => {
            let x = h.point.spectrum.shape(&st.reference.basis, h.index);
            println!(
                "Hopf point mu0 = {:.8} (bracket [{:.10}, {:.10}], {} refinements) at {:.2} Hz; disc share of the unstable mode's kinetic energy {:.0}%",
                h.mu0,
                h.bracket.0,
                h.bracket.1,
                h.evaluations,
                h.frequency_hz,
                100.0 * disc_share(s, &x)
            );
            if let Some((m1, m2)) = st.pair {
                let f = |m: usize| st.reference.basis.omega[m] / (2.0 * std::f64::consts::PI);
                println!(
                    "coalescing pair (frictionless modes): Mode 1 = #{} at {:.1} Hz (stays stable), Mode 2 = #{} at {:.1} Hz (goes unstable)",
                    m1 + 1,
                    f(m1),
                    m2 + 1,
                    f(m2)
                );
            }
        }
        None => println!("no Hopf point in the band over this friction range"),
    }
    if !outside.is_empty() {
        println!(
            "{} crossing(s) outside the band are reported above but do not define mu0",
            outside.len()
        );
    }
}

/// Branches shown in the figures: the pair first, then in-band branches within ±25% of the
/// Hopf frequency (or all in-band branches that ever go unstable when there is no Hopf point).
fn shown_branches(st: &Stability, band_max: f64) -> Vec<usize> {
    let sw = &st.sweep;
    let mut out = Vec::new();
    if let Some(h) = &sw.hopf {
        out.push(h.branch);
        if let Some(p) = h.partner {
            out.push(p);
        }
        for b in 0..sw.branches.len() {
            let f = sw.points[0].spectrum.frequency_hz(sw.branches[b][0]);
            if !out.contains(&b) && (f / h.frequency_hz - 1.0).abs() < 0.25 && f < band_max {
                out.push(b);
            }
        }
    } else {
        for c in &sw.crossings {
            if !out.contains(&c.branch) {
                out.push(c.branch);
            }
        }
    }
    out
}

fn write_tables(dir: &Path, s: &Setup, st: &Stability) -> Result<()> {
    let sw = &st.sweep;
    let mut all = Table::new([
        "mu",
        "branch",
        "real_part_per_s",
        "frequency_hz",
        "in_band",
        "unstable",
    ]);
    for (k, p) in sw.points.iter().enumerate() {
        for b in 0..sw.branches.len() {
            let l = sw.value(b, k);
            let f = p.spectrum.frequency_hz(sw.branches[b][k]);
            all.push_row([
                format!("{}", p.equilibrium.mu),
                b.to_string(),
                format!("{:e}", l.re),
                format!("{f}"),
                (s.sweep.band.contains(f) as u8).to_string(),
                ((l.re > 0.0) as u8).to_string(),
            ]);
        }
    }
    all.write_csv(&dir.join("branches.csv"))?;
    let shown = shown_branches(st, s.sweep.band.valid_max_hz);
    let mut header = vec!["mu".to_string()];
    for b in &shown {
        header.push(format!("re_b{b}"));
        header.push(format!("f_hz_b{b}"));
    }
    header.push("unstable_in_band".into());
    header.push("unstable_outside_band".into());
    let mut t = Table::new(header);
    for (k, p) in sw.points.iter().enumerate() {
        let mut row = vec![format!("{}", p.equilibrium.mu)];
        for &b in &shown {
            row.push(format!("{:e}", sw.value(b, k).re));
            row.push(format!("{}", p.spectrum.frequency_hz(sw.branches[b][k])));
        }
        let (mut inb, mut outb) = (0, 0);
        for j in 0..p.spectrum.values.len() {
            if p.spectrum.values[j].re > 0.0 {
                if s.sweep.band.contains(p.spectrum.frequency_hz(j)) {
                    inb += 1;
                } else {
                    outb += 1;
                }
            }
        }
        row.push(inb.to_string());
        row.push(outb.to_string());
        t.push_row(row);
    }
    t.write_csv(&dir.join("stability.csv"))?;
    let summary = serde_json::json!({
        "mu0": sw.hopf.as_ref().map(|h| h.mu0),
        "frequency_hz": sw.hopf.as_ref().map(|h| h.frequency_hz),
        "bracket": sw.hopf.as_ref().map(|h| [h.bracket.0, h.bracket.1]),
        "refinements": sw.hopf.as_ref().map(|h| h.evaluations),
        "pair_modes_1based": st.pair.map(|(a, b)| [a + 1, b + 1]),
        "crossings": sw.crossings.iter().map(|c| serde_json::json!({
            "branch": c.branch, "mu_lo": c.mu_lo, "mu_hi": c.mu_hi, "frequency_hz": c.frequency_hz, "in_band": c.in_band
        })).collect::<Vec<_>>(),
        "valid_band_max_hz": s.sweep.band.valid_max_hz,
        "user_band_hz": s.sweep.band.user.map(|(a, b)| [a, b]),
        "equilibrium_mu0": {
            "iterations": st.reference.equilibrium.iterations,
            "relative_residual": st.reference.equilibrium.residual,
            "penetrations_m": st.reference.equilibrium.penetrations,
        },
        "rom": s.rom_path.display().to_string(),
    });
    squeal_io::atomic_write_bytes(
        &dir.join("summary.json"),
        serde_json::to_string_pretty(&summary)?.as_bytes(),
    )?;
    Ok(())
}

fn write_figures(dir: &Path, st: &Stability, s: &Setup) -> Result<()> {
    let sw = &st.sweep;
    let shown = shown_branches(st, s.sweep.band.valid_max_hz);
    let mut re = Panel {
        title: "(a) real parts".into(),
        x_label: "friction coefficient mu".into(),
        y_label: "Re(lambda) (1/s)".into(),
        // The same series as panel (b), whose legend sits outside: none here to hide a curve.
        legend: squeal_report::LegendPosition::None,
        ..Panel::default()
    };
    let mut fr = Panel {
        title: "(b) frequencies".into(),
        x_label: "friction coefficient mu".into(),
        y_label: "frequency (Hz)".into(),
        legend: squeal_report::LegendPosition::Outside,
        ..Panel::default()
    };
    for (i, &b) in shown.iter().enumerate() {
        let name = match (i, sw.hopf.is_some()) {
            (0, true) => "unstable mode (Mode 2)".to_string(),
            (1, true) => "coalescing partner (Mode 1)".to_string(),
            _ => format!("branch {b}"),
        };
        let re_pts: Vec<(f64, f64)> = (0..sw.points.len())
            .map(|k| (sw.points[k].equilibrium.mu, sw.value(b, k).re))
            .collect();
        let f_pts: Vec<(f64, f64)> = (0..sw.points.len())
            .map(|k| {
                (
                    sw.points[k].equilibrium.mu,
                    sw.points[k].spectrum.frequency_hz(sw.branches[b][k]),
                )
            })
            .collect();
        let (mut a, mut c) = (
            Series::line(name.clone(), re_pts),
            Series::line(name, f_pts),
        );
        if i >= 2 {
            a = a.with_color(Rgb::GREY).with_dash(Dash::Dotted);
            c = c.with_color(Rgb::GREY).with_dash(Dash::Dotted);
        }
        re.series.push(a);
        fr.series.push(c);
    }
    re.annotations.push(Annotation::HLine {
        y: 0.0,
        label: String::new(),
        dash: Dash::Dashed,
    });
    if let Some(h) = &sw.hopf {
        let label = format!("mu0 = {}", fmt_sig(h.mu0, 4));
        re.annotations.push(Annotation::VLine {
            x: h.mu0,
            label: label.clone(),
            dash: Dash::Dashed,
        });
        fr.annotations.push(Annotation::VLine {
            x: h.mu0,
            label,
            dash: Dash::Dashed,
        });
    }
    let fig = Figure {
        title: "Stability against friction (paper Figure 2)".into(),
        panels: vec![re, fr],
        ..Figure::default()
    };
    write_svg_and_png(&fig, &dir.join("stability"))?;
    Ok(())
}

fn write_shapes(dir: &Path, s: &Setup, st: &Stability) -> Result<()> {
    let disc = crate::commands::mesh::read_mesh(&s.disc_mesh)?.mesh;
    let pad = crate::commands::mesh::read_mesh(&s.pad_mesh)?.mesh;
    let (Some(dp), Some(pp)) = (s.rom.part("disc"), s.rom.part("pad")) else {
        anyhow::bail!("the reduced model lacks a disc or a pad part");
    };
    let parts = |_: ()| {
        [
            (dp, &disc, s.layout.disc.clone()),
            (pp, &pad, s.layout.pad.clone()),
        ]
    };
    let mut fields = vec![PartFields {
        name: "equilibrium_mu0",
        brake: st.reference.equilibrium.x.clone(),
    }];
    if let Some(h) = &st.sweep.hopf {
        let x = normalize_mode(&h.point.spectrum.shape(&st.reference.basis, h.index));
        fields.push(PartFields {
            name: "equilibrium_hopf",
            brake: h.point.equilibrium.x.clone(),
        });
        fields.push(PartFields {
            name: "unstable_mode_real",
            brake: x.iter().map(|v| v.re).collect(),
        });
        fields.push(PartFields {
            name: "unstable_mode_imag",
            brake: x.iter().map(|v| v.im).collect(),
        });
    }
    let vtm = write_brake_vtu(dir, "shapes", parts(()), &fields)?;
    println!("mode shape and equilibria for ParaView: {}", vtm.display());
    Ok(())
}
