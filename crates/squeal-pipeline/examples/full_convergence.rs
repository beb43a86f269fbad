//! The reduced brake's μ0 and unstable frequency against the full finite-element model
//! (`squeal stability --full`, [`squeal_pipeline::full`]) as the kept fixed-interface modes
//! grow: the convergence table of docs/reduction.md, "Reduced against full: the kept modes".
//!
//! `cargo run --release -p squeal-pipeline --example full_convergence -- SCENE LEVEL INTERFACE
//! CHOICES [first] [doublet=LO..HI]`, e.g. `meshes/brake.toml coarse patch 25,50,100,200`:
//! CHOICES a comma list of mode counts per part (`50`) or multiples of the band's top below
//! which every mode is kept (`x2`: [`ModeChoice::Auto`]). Each reduced brake is swept undamped
//! over the scene's friction values; the full model's onset of each distinct unstable mode
//! (within ±5 % of its frequency) is found once (the full model and the static equilibrium
//! do not depend on the kept modes: the constraint modes make the static response exact).
//! `first` also finds the full model's first onset over the whole band (slow: 11 band-wide
//! spectra and a bisection). `band=2500..3500` restricts the reduced sweep's band and the
//! full model's search to that band (Hz): the onset of one mode as the kept modes grow, when
//! another one goes unstable first. `doublet=12000..13000` prints the eigenvalues at μ = 0 of the
//! full model and of each reduced brake in that band (Hz): the split of a near-degenerate
//! pair.

use squeal_brake::analysis::stability;
use squeal_pipeline::full::full_brake;
use squeal_pipeline::full::onset::{
    FullOnset, FullOptions, full_onset, mode_band, reduced_onset, spectrum_at, undamped,
};
use squeal_pipeline::full::run::band_of;
use squeal_pipeline::model::{Model, model_on, quiet};
use squeal_pipeline::parts::{brake_inputs, load_parts};
use squeal_reduce::brake::{ModeChoice, reduce_brake_loaded};
use squeal_scene::{Interface, Scene};
use std::f64::consts::TAU;
use std::path::PathBuf;
use std::time::Instant;

type Error = Box<dyn std::error::Error>;

/// One row of the table.
struct Row {
    choice: String,
    dofs: usize,
    disc_modes: usize,
    valid_hz: f64,
    mu0: Option<f64>,
    hz: Option<f64>,
    seconds: f64,
}

fn choice_of(s: &str, band_top: f64) -> Result<ModeChoice, Error> {
    Ok(match s.strip_prefix('x') {
        Some(f) => ModeChoice::Auto {
            fmax_hz: band_top,
            factor: f.parse()?,
        },
        None => ModeChoice::Fixed(s.parse()?),
    })
}

fn interface_of(s: &str) -> Result<Interface, Error> {
    Ok(match s {
        "patch" => Interface::Patch,
        "nodal" => Interface::Nodal,
        "node" => Interface::Node,
        other => return Err(format!("no interface {other}").into()),
    })
}

/// The reduced brake's eigenvalues at μ = 0 with frequencies in `band` (Hz).
fn reduced_band(model: &Model, band: (f64, f64)) -> Result<Vec<f64>, Error> {
    let st = stability(&model.brake, &undamped(), &[0.0], &model.sweep)?;
    let s = &st.sweep.points[0].spectrum;
    Ok(s.values
        .iter()
        .map(|l| l.im / TAU)
        .filter(|f| *f >= band.0 && *f <= band.1)
        .collect())
}

fn main() -> Result<(), Error> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize| args.get(i).cloned().ok_or("SCENE LEVEL INTERFACE CHOICES");
    let mut scene = Scene::read(&PathBuf::from(arg(0)?))?.variant()?;
    scene.set_mesh_level(&arg(1)?)?;
    scene.set_interface(interface_of(&arg(2)?)?);
    let first = args.iter().any(|a| a == "first");
    let doublet: Option<(f64, f64)> = args
        .iter()
        .find_map(|a| a.strip_prefix("doublet="))
        .map(|r| -> Result<(f64, f64), Error> {
            let (a, b) = r.split_once("..").ok_or("doublet=LO..HI")?;
            Ok((a.parse()?, b.parse()?))
        })
        .transpose()?;
    let only: Option<(f64, f64)> = args
        .iter()
        .find_map(|a| a.strip_prefix("band="))
        .map(|r| -> Result<(f64, f64), Error> {
            let (a, b) = r.split_once("..").ok_or("band=LO..HI")?;
            Ok((a.parse()?, b.parse()?))
        })
        .transpose()?;
    let mus = scene.mu_values()?;
    let log = |s: &str| eprintln!("{s}");
    let t = Instant::now();
    let parts = load_parts(&scene, &quiet)?;
    let inputs0 = brake_inputs(&scene, &parts)?;
    eprintln!("meshes read in {:.1} s", t.elapsed().as_secs_f64());
    let band_top = scene.band_hz().map_or(16000.0, |b| b.1);
    let mut rows = Vec::new();
    let mut full = None;
    let mut onsets: Vec<FullOnset> = Vec::new();
    let opts = FullOptions::default();
    let mut doublet_lines = Vec::new();
    for c in arg(3)?.split(',') {
        let mut inputs = inputs0.clone();
        inputs.modes = choice_of(c, band_top)?;
        let t = Instant::now();
        let (rom, _) = reduce_brake_loaded(
            &inputs,
            parts.disc.clone(),
            parts.pads.iter().map(|p| p.1.clone()).collect(),
            &mut |_, _| {},
        )?;
        let mut model = model_on(&scene, rom, PathBuf::from("in-memory.rom"))?;
        if only.is_some() {
            model.sweep.band.user = only;
        }
        let reduce_s = t.elapsed().as_secs_f64();
        let r = reduced_onset(&model, &mus)?;
        let disc_modes = model
            .rom
            .part("disc")
            .map_or(0, |p| p.info.fixed_interface_hz.len());
        eprintln!(
            "{c}: {} dofs, disc {disc_modes} modes, valid below {:.0} Hz, reduced in {reduce_s:.1} s, mu0 {:?} at {:?} Hz, sweep {:.1} s",
            model.brake.size(),
            model.sweep.band.valid_max_hz,
            r.map(|r| r.mu0),
            r.map(|r| r.frequency_hz),
            r.map_or(0.0, |r| r.seconds)
        );
        if full.is_none() {
            let t = Instant::now();
            let f = full_brake(&parts, &inputs, &model)?;
            eprintln!(
                "full model {} dofs, built in {:.1} s",
                f.size(),
                t.elapsed().as_secs_f64()
            );
            if first {
                let band = band_of(&model);
                if let Some(o) = full_onset(&f, &model, &mus, band, &opts, &log)? {
                    eprintln!(
                        "full model, first onset in {:.0}..{:.0} Hz: mu0 {:.7} at {:.3} Hz, growth {:.3e} 1/s at {:.7}, {:.1} s",
                        band.0, band.1, o.mu0, o.frequency_hz, o.growth, o.bracket.1, o.seconds
                    );
                    onsets.push(o);
                }
            }
            if let Some(d) = doublet {
                let (s, _) = spectrum_at(&f, &model, 0.0, d, None, &opts.quadratic, &|_, _| {})?;
                let hz: Vec<String> = s
                    .values()
                    .iter()
                    .map(|l| format!("{:.3}", l.im / TAU))
                    .collect();
                doublet_lines.push(format!("full: {}", hz.join(" ")));
            }
            full = Some(f);
        }
        if let Some(d) = doublet {
            let hz: Vec<String> = reduced_band(&model, d)?
                .iter()
                .map(|f| format!("{f:.3}"))
                .collect();
            doublet_lines.push(format!("{c}: {}", hz.join(" ")));
        }
        if let (Some(r), Some(f)) = (&r, &full) {
            let known = onsets
                .iter()
                .any(|o| (o.frequency_hz / r.frequency_hz - 1.0).abs() < 0.01);
            if !known {
                let near = mode_band(r.frequency_hz, band_of(&model), &opts);
                if let Some(o) = full_onset(f, &model, &mus, near, &opts, &log)? {
                    eprintln!(
                        "full model near {:.0} Hz: mu0 {:.7} at {:.3} Hz, {:.1} s",
                        r.frequency_hz, o.mu0, o.frequency_hz, o.seconds
                    );
                    onsets.push(o);
                }
            }
        }
        rows.push(Row {
            choice: c.to_string(),
            dofs: model.brake.size(),
            disc_modes,
            valid_hz: model.sweep.band.valid_max_hz,
            mu0: r.map(|r| r.mu0),
            hz: r.map(|r| r.frequency_hz),
            seconds: r.map_or(0.0, |r| r.seconds),
        });
    }
    println!(
        "| modes | reduced dofs | disc modes | valid below (Hz) | reduced mu0 | Hz | full mu0 | Hz | mu0 reduced/full - 1 | Hz reduced/full - 1 | reduced sweep (s) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for r in &rows {
        let o = r.hz.and_then(|hz| {
            onsets
                .iter()
                .find(|o| (o.frequency_hz / hz - 1.0).abs() < 0.01)
        });
        let cell = |v: Option<f64>, d: usize| v.map_or("none".to_string(), |v| format!("{v:.d$}"));
        let rel = |a: Option<f64>, b: Option<f64>| match (a, b) {
            (Some(a), Some(b)) => format!("{:+.2e}", a / b - 1.0),
            _ => "-".into(),
        };
        println!(
            "| {} | {} | {} | {:.0} | {} | {} | {} | {} | {} | {} | {:.1} |",
            r.choice,
            r.dofs,
            r.disc_modes,
            r.valid_hz,
            cell(r.mu0, 7),
            cell(r.hz, 3),
            cell(o.map(|o| o.mu0), 7),
            cell(o.map(|o| o.frequency_hz), 3),
            rel(r.mu0, o.map(|o| o.mu0)),
            rel(r.hz, o.map(|o| o.frequency_hz)),
            r.seconds
        );
    }
    for o in &onsets {
        println!(
            "full onset: mu0 {:.7} in [{:.8}, {:.8}] at {:.3} Hz, growth {:.3e} 1/s, {} spectra, {:.1} s",
            o.mu0, o.bracket.0, o.bracket.1, o.frequency_hz, o.growth, o.evaluations, o.seconds
        );
    }
    for l in &doublet_lines {
        println!("{l}");
    }
    Ok(())
}
