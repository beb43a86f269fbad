//! The `"system"` interface basis from the full finite-element model's system vectors
//! ([`squeal_pipeline::full::system`]) against today's, from the Craig–Bampton brake with every
//! contact-face dof kept (`squeal_brake::interface_system`), on a scene with nodal contact:
//! each basis's time and peak resident memory, size, in-band frequencies and μ0 over the
//! scene's friction values. Both keep the level of the in-band modes with their friction
//! residuals and the two static vectors. (docs/reduction.md, "System vectors from the full
//! model".)
//!
//! `cargo run --release -p squeal-pipeline --example full_system -- SCENE OUT`: the scene is
//! reduced with `[reduction] interface = "none"` appended (its `.rom` written under `OUT`).

use squeal_brake::interface_system::system_vectors_to;
use squeal_pipeline::full::full_brake;
use squeal_pipeline::full::system::full_system_vectors;
use squeal_pipeline::interface::at_count;
use squeal_pipeline::interface_system::face_bases;
use squeal_pipeline::model::{Model, build};
use squeal_pipeline::parts::{brake_inputs, load_parts};
use squeal_scene::Scene;
use std::path::PathBuf;
use std::time::Instant;

type Error = Box<dyn std::error::Error>;

/// The peak resident set (GB) since the last [`reset_peak`] (Linux `VmHWM`), or NaN.
fn peak_gb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find(|l| l.starts_with("VmHWM:")).and_then(|l| {
                l.split_whitespace()
                    .nth(1)
                    .and_then(|k| k.parse::<f64>().ok())
            })
        })
        .map_or(f64::NAN, |kb| kb / 1024.0 / 1024.0)
}

/// Resets `VmHWM` to the current resident set (Linux `clear_refs` 5).
fn reset_peak() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// The in-band frequencies (Hz) of the frictionless model, below `top`.
fn in_band_hz(m: &Model, top: f64) -> Result<Vec<f64>, Error> {
    let damping = squeal_brake::modal::Damping {
        global_ratio: 0.0,
        extra: vec![],
    };
    let r = squeal_brake::sweep::reference(&m.brake, &damping, &m.sweep.newton)?;
    Ok(r.basis
        .omega
        .iter()
        .map(|w| w / std::f64::consts::TAU)
        .filter(|f| *f <= top)
        .collect())
}

fn main() -> Result<(), Error> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [scene, out] = args.as_slice() else {
        return Err("usage: full_system SCENE OUT".into());
    };
    let path = PathBuf::from(scene);
    let mut text = std::fs::read_to_string(&path)?;
    text.push_str("\n[reduction]\ninterface = \"none\"\n");
    let scene = Scene::parse(&path, text)?;
    let log = |s: &str| eprintln!("{s}");
    let t = Instant::now();
    let model = build(&scene, &PathBuf::from(out), &log)?;
    println!(
        "unreduced-interface brake: {} dofs in {:.1} s, peak {:.2} GB",
        model.brake.size(),
        t.elapsed().as_secs_f64(),
        peak_gb()
    );
    let b = model.sweep.band;
    let top = b
        .user
        .map_or(b.valid_max_hz, |(_, hi)| hi.min(b.valid_max_hz));
    let mus = scene.mu_values()?;

    reset_peak();
    let t = Instant::now();
    let v = system_vectors_to(&model.brake, &model.sweep.newton, top, top)?;
    let r = v.residuals.ncols();
    let m1 = at_count(&model, &face_bases(&model, &v, r, r)?, usize::MAX)?;
    println!(
        "reduced brake's vectors: {r} in-band modes, basis {} dofs, {:.1} s, peak {:.2} GB",
        m1.brake.size(),
        t.elapsed().as_secs_f64(),
        peak_gb()
    );
    drop(v);

    reset_peak();
    let t = Instant::now();
    let parts = load_parts(&scene, &log)?;
    let inputs = brake_inputs(&scene, &parts)?;
    let fe = full_brake(&parts, &inputs, &model)?;
    let built = t.elapsed().as_secs_f64();
    let fv = full_system_vectors(&parts, &inputs, &fe, &model, top, top)?;
    let m2 = at_count(
        &model,
        &fv.face_bases(&model, fv.in_band, fv.in_band)?,
        usize::MAX,
    )?;
    println!(
        "full model's vectors: {} full dofs (built in {built:.1} s), {} in-band modes in {:.1} s, basis {} dofs, {:.1} s in all, peak {:.2} GB",
        fv.dofs,
        fv.in_band,
        fv.seconds,
        m2.brake.size(),
        t.elapsed().as_secs_f64(),
        peak_gb()
    );
    drop((fe, parts, inputs));
    let fe_hz: Vec<f64> = fv.omega.iter().map(|w| w / std::f64::consts::TAU).collect();
    let (f0, f1, f2) = (
        in_band_hz(&model, top)?,
        in_band_hz(&m1, top)?,
        in_band_hz(&m2, top)?,
    );
    let worst = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (y / x - 1.0).abs())
            .fold(0.0, f64::max)
    };
    println!(
        "in-band frequencies: unreduced interface {} (against full {:.2e}), reduced-vector basis {} (against unreduced {:.2e}), full-vector basis {} (against unreduced {:.2e}, against full {:.2e})",
        f0.len(),
        worst(&fe_hz, &f0),
        f1.len(),
        worst(&f0, &f1),
        f2.len(),
        worst(&f0, &f2),
        worst(&fe_hz, &f2)
    );
    for (name, m) in [("reduced-vector basis", &m1), ("full-vector basis", &m2)] {
        let t = Instant::now();
        let st = squeal_pipeline::stability::analyse(m, &mus)?;
        match st.sweep.hopf {
            Some(h) => println!(
                "{name}: mu0 = {:.8} at {:.4} Hz ({:.1} s)",
                h.mu0,
                h.frequency_hz,
                t.elapsed().as_secs_f64()
            ),
            None => println!("{name}: no Hopf point"),
        }
    }
    Ok(())
}
