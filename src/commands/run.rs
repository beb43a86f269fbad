//! `squeal run`: the whole pipeline on a scene — reduction, stability, CHBM limit cycle and its
//! comparison with time integration — and a report folder whose `index.html` / `index.md` shows
//! every figure and table.
//!
//! Each stage is the command of the same name run into one output folder; the report is then
//! built from the files they wrote, so `squeal run` shows exactly what the single commands give.

use crate::commands::{chbm, compare, stability};
use crate::scene::Scene;
use crate::setup::{default_out, reduced_model};
use anyhow::{Context, Result};
use clap::Args;
use squeal_report::{Report, Section, Table};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

#[derive(Args)]
pub struct RunArgs {
    /// Scene file (TOML), e.g. meshes/brake.toml
    pub scene: PathBuf,
    /// Output folder (default: out/<scene name>)
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Skip the comparison with time integration (the slowest stage)
    #[arg(long)]
    pub no_compare: bool,
}

pub fn run(args: RunArgs) -> Result<ExitCode> {
    let t0 = Instant::now();
    let scene = Scene::read(&args.scene)?;
    let out = args.out.clone().unwrap_or_else(|| default_out(&args.scene));
    let mut timings: Vec<(&str, f64)> = Vec::new();

    println!("== 1. reduced model");
    let t = Instant::now();
    let (rom, rom_path) = reduced_model(&scene, &out, true)?;
    timings.push(("reduction (or cached model)", t.elapsed().as_secs_f64()));

    println!("\n== 2. stability");
    let t = Instant::now();
    stability::run(stability::StabilityArgs {
        scene: args.scene.clone(),
        mu: None,
        out: Some(out.clone()),
        no_vtu: false,
    })?;
    timings.push(("stability", t.elapsed().as_secs_f64()));

    println!("\n== 3. limit cycle (CHBM)");
    let t = Instant::now();
    let chbm_args = chbm::ChbmArgs {
        scene: args.scene.clone(),
        mu: None,
        mu_ratio: Some(*scene.file.chbm.mu_ratio.get_ref()),
        harmonics: *scene.file.chbm.harmonics.get_ref(),
        samples: None,
        amplitude: None,
        plain: false,
        fit: "fundamental".into(),
        out: Some(out.clone()),
        no_vtu: false,
    };
    let chbm_code = chbm::run(chbm_args)?;
    timings.push(("CHBM", t.elapsed().as_secs_f64()));

    if !args.no_compare {
        println!("\n== 4. CHBM against time integration");
        let t = Instant::now();
        compare::run(compare::CompareArgs {
            out: Some(out.clone()),
            ..compare::CompareArgs::for_scene(args.scene.clone())?
        })?;
        timings.push(("comparison", t.elapsed().as_secs_f64()));
    }

    let report = build_report(&scene, &out, &rom_path, rom.size(), &timings)?;
    let notes = report.write(&out).context("writing the report")?;
    for n in notes {
        eprintln!("report: {n}");
    }
    println!(
        "\nreport: {} ({:.1} s in all)",
        out.join("index.html").display(),
        t0.elapsed().as_secs_f64()
    );
    Ok(chbm_code)
}

fn read_json(path: &Path) -> Option<serde_json::Value> {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok())
}

fn num(v: &serde_json::Value, key: &str, digits: usize) -> String {
    v.get(key)
        .and_then(serde_json::Value::as_f64)
        .map_or("-".into(), |x| squeal_report::format::fmt_sig(x, digits))
}

fn build_report(
    scene: &Scene,
    out: &Path,
    rom: &Path,
    dofs: usize,
    timings: &[(&str, f64)],
) -> Result<Report> {
    let title = scene
        .file
        .title
        .clone()
        .unwrap_or_else(|| "squeal report".into());
    let mut sections = Vec::new();
    let mut model = Table::new(["item", "value"]);
    model.push_row(["scene".to_string(), scene.path.display().to_string()]);
    model.push_row([
        "disc mesh".to_string(),
        scene.resolve(&scene.file.model.disc).display().to_string(),
    ]);
    model.push_row([
        "pad mesh".to_string(),
        scene.resolve(&scene.file.model.pad).display().to_string(),
    ]);
    model.push_row([
        "interface".to_string(),
        scene.file.model.interface.get_ref().clone(),
    ]);
    model.push_row(["reduced dofs".to_string(), dofs.to_string()]);
    model.push_row(["reduced model".to_string(), rom.display().to_string()]);
    sections.push(Section {
        heading: "Model".into(),
        text: String::new(),
        figures: vec![],
        tables: vec![(model, "The reduced brake".into())],
    });

    let st = read_json(&out.join("stability/summary.json"));
    let mut t = Table::new(["quantity", "value"]);
    if let Some(v) = &st {
        t.push_row(["Hopf point mu0".to_string(), num(v, "mu0", 6)]);
        t.push_row([
            "frequency at mu0 (Hz)".to_string(),
            num(v, "frequency_hz", 6),
        ]);
        t.push_row([
            "valid band up to (Hz)".to_string(),
            num(v, "valid_band_max_hz", 5),
        ]);
        let pair = v
            .get("pair_modes_1based")
            .map(|p| p.to_string())
            .unwrap_or_else(|| "-".into());
        t.push_row(["coalescing modes (frictionless numbers)".to_string(), pair]);
    }
    sections.push(Section {
        heading: "Stability (section 3)".into(),
        text: "Real parts and frequencies of the coupling modes against friction; the Hopf point mu0 is the first \
               crossing of a real part through zero inside the band the model can speak for. The unstable mode \
               shape and the equilibria are in stability/shapes.vtm (ParaView)."
            .into(),
        figures: vec![(PathBuf::from("stability/stability"), "Figure 2: real parts and frequencies against mu".into())],
        tables: vec![(t, "Hopf point".into())],
    });

    let ch = read_json(&out.join("chbm/chbm.json"));
    let mut t = Table::new(["quantity", "value"]);
    if let Some(v) = &ch {
        for (label, key, d) in [
            ("friction mu", "mu", 6),
            ("harmonics", "harmonics", 3),
            ("frequency (Hz)", "frequency_hz", 8),
            ("||f1|| / ||F_eq||", "f1_relative", 3),
            ("Re lambda (1/s)", "re_lambda", 3),
            ("LM iterations", "iterations", 3),
            ("time (ms)", "time_ms", 3),
        ] {
            t.push_row([label.to_string(), num(v, key, d)]);
        }
        t.push_row([
            "outcome".to_string(),
            v.get("outcome")
                .and_then(|o| o.as_str())
                .unwrap_or("-")
                .to_string(),
        ]);
    }
    sections.push(Section {
        heading: "Limit cycle (CHBM, sections 4-5)".into(),
        text: "The animated cycle on both meshes is chbm/cycle.pvd (ParaView: open, then Warp By Vector on 'oscillation').".into(),
        figures: vec![
            (PathBuf::from("chbm/limit_cycles"), "Figure 4: limit cycles at a pad and a disc contact point".into()),
            (PathBuf::from("chbm/convergence"), "Figures 6-7: convergence of Re(lambda) and of the residual".into()),
        ],
        tables: vec![(t, "CHBM solution".into())],
    });

    let mut t = Table::new(["stage", "wall time (s)"]);
    for (s, x) in timings {
        t.push_row([s.to_string(), format!("{x:.2}")]);
    }
    sections.push(Section {
        heading: "Timings".into(),
        text: String::new(),
        figures: vec![],
        tables: vec![(t, "Wall time per stage".into())],
    });
    Ok(Report {
        title,
        intro: "Made by `squeal run`: Coudeyras, Sinou & Nacivet (2009), The Constrained Harmonic Balance Method, for this scene.".into(),
        sections,
    })
}
