//! Two unstable modes of the bundled brake at one friction level: the generalized CHBM's
//! periodic part (one CHBM cycle per unstable mode, Hill's verdict on each, the other modes'
//! eigenvalues under each cycle's averaged linearization; `squeal_chbm::multi`) and the
//! reference, a BDF run from the equilibrium perturbed along both modes with the spectrum of
//! its record in windows.
//!
//! `cargo run --release -p squeal-pipeline --example two_mode -- [scene.toml] [mu]
//! [transient_s] [record_s] [windows] [cycles|run|both|torus] [harmonics]` (defaults:
//! `meshes/brake.toml`, 0.9, 0.5, 0.5, 4, both, 3). `torus`: the generalized CHBM's answer of
//! `squeal chbm --two-mode` ([`squeal_pipeline::two_mode`]; the torus on the box of
//! `harmonics` in each angle) and, when the two-mode torus converged, its
//! check against BDF started on it ([`squeal_chbm::multi::check::time_check`], defaults: 100
//! periods of `ω1` dropped, 400 recorded at 64 samples; issue 24 item 5: both frequencies within
//! 1e-4, the swing envelope within 1 %). The medium bundled brake has its second unstable mode (2879 Hz, 3
//! nodal diameters) from μ ≈ 0.79 on, with the squeal mode (4 kHz) unstable from μ0 = 0.4556.

use squeal_chbm::floquet::HillOptions;
use squeal_chbm::multi::check::{TimeCheckOptions, time_check};
use squeal_chbm::multi::periodic::{mode_cycles, verdict};
use squeal_chbm::multi::reference::{MultiRunOptions, integrate_modes};
use squeal_chbm::multi::unstable_modes;
use squeal_chbm::{ChbmOptions, RESTART_AMPLITUDES};
use squeal_pipeline::Pipeline;
use squeal_pipeline::model::quiet;
use squeal_scene::Scene;
use std::f64::consts::PI;
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, d: &str| args.get(i).cloned().unwrap_or_else(|| d.to_string());
    let scene_path = PathBuf::from(arg(0, "meshes/brake.toml"));
    let mu: f64 = arg(1, "0.9").parse()?;
    let transient: f64 = arg(2, "0.5").parse()?;
    let record: f64 = arg(3, "0.5").parse()?;
    let windows: usize = arg(4, "4").parse()?;
    let what = arg(5, "both");
    let scene = Scene::read(&scene_path)?;
    if what == "torus" {
        return torus(scene, mu, arg(6, "3").parse()?);
    }
    let out = std::env::temp_dir().join("squeal-two-mode");
    std::fs::create_dir_all(&out)?;
    // The sweep the CLI runs by default (0..1.2 in steps of 0.01, and on to mu), for the
    // reference and damping of `squeal stability`.
    let top = mu.max(1.2);
    let count = (top / 0.01).round() as usize;
    let mus: Vec<f64> = (0..=count).map(|k| top * k as f64 / count as f64).collect();
    let p = Pipeline::new(scene, out, &quiet)?.with_mus(mus)?;
    let m = p.model()?;
    let st = p.stability()?;
    let starts = unstable_modes(&m.brake, &st.reference, mu, &m.sweep.band, &m.sweep.newton)?;
    println!("mu = {mu}: {} unstable mode(s) in the band", starts.len());
    for (j, s) in starts.iter().enumerate() {
        println!(
            "  mode {}: Re lambda = {:.4} 1/s, f = {:.4} Hz",
            j + 1,
            s.lambda.re,
            s.lambda.im / (2.0 * PI)
        );
    }
    let mb = squeal_brake::modal_brake::ModalBrake::new(&m.brake, &st.reference, mu);
    if what != "run" {
        let t = std::time::Instant::now();
        let opts = {
            let mut o = ChbmOptions::default();
            o.harmonics = 3;
            o
        };
        let cycles = mode_cycles(
            &mb,
            &starts,
            &opts,
            &RESTART_AMPLITUDES,
            &HillOptions::default(),
        )?;
        for c in &cycles {
            let s = &c.solution;
            print!(
                "cycle of mode {}: {} ({} harmonics), f = {:.6} Hz",
                c.mode + 1,
                s.outcome,
                s.harmonics,
                s.omega / (2.0 * PI)
            );
            match &c.floquet {
                Some(Ok(f)) => {
                    let lead = f.leading().map(|e| e.sigma);
                    print!(", Hill: {}", f.stability());
                    if let Some(l) = lead {
                        print!(" (leading exponent {:.4} {:+.4}i 1/s)", l.re, l.im);
                    }
                }
                Some(Err(e)) => print!(", Hill failed: {e}"),
                None => {}
            }
            println!();
            if let Some(o) = &c.others {
                for (k, l) in o.iter().enumerate() {
                    println!(
                        "    mode {} under this cycle's averaged linearization: Re lambda = {:.4} 1/s, f = {:.4} Hz",
                        k + 1,
                        l.re,
                        l.im / (2.0 * PI)
                    );
                }
            }
        }
        println!(
            "verdict: {} ({:.1} s)",
            verdict(&cycles),
            t.elapsed().as_secs_f64()
        );
    }
    if what != "cycles" {
        let opts = MultiRunOptions {
            transient,
            record,
            windows,
            ..MultiRunOptions::default()
        };
        let run = integrate_modes(&mb, &starts, &opts)?;
        println!(
            "time integration (BDF rtol {}, order <= {}): {} steps, {:.1} s wall, sampled at {:.1} Hz, pair {} observed{}",
            opts.rtol,
            opts.max_order,
            run.stats.steps,
            run.wall.as_secs_f64(),
            run.rate,
            run.pair + 1,
            run.failure
                .as_ref()
                .map(|e| format!(", stopped early: {e}"))
                .unwrap_or_default()
        );
        for w in &run.windows {
            println!(
                "  window {:.4}..{:.4} s: envelope of the normal penetration {:.4e}..{:.4e} m",
                w.from, w.to, w.envelope.0, w.envelope.1
            );
            for pk in w.peaks.iter().take(8) {
                println!("    {:.5} Hz  {:.4e} m", pk.frequency, pk.amplitude);
            }
        }
    }
    Ok(())
}

/// The generalized CHBM's answer at `mu` and, on a two-mode torus, its BDF check.
fn torus(scene: Scene, mu: f64, harmonics: usize) -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::temp_dir().join("squeal-two-mode-torus");
    std::fs::create_dir_all(&out)?;
    let p = Pipeline::new(scene, out, &quiet)?;
    let r = squeal_pipeline::two_mode::two_mode(&p, mu, harmonics)?;
    print!("{}", squeal_pipeline::two_mode::report_text(&r));
    let Ok(t) = &r.torus else {
        return Ok(());
    };
    let m = p.model()?;
    let st = p.stability()?;
    let mb = squeal_brake::modal_brake::ModalBrake::new(&m.brake, &st.reference, mu);
    let opts = TimeCheckOptions::default();
    let c = time_check(&mb, t, &opts)?;
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    println!(
        "BDF (rtol {}, order <= {}) from the torus at theta = 0, {} periods of f1 dropped, {} recorded at {} samples: {} steps, {:.1} s",
        opts.rtol,
        opts.max_order,
        opts.transient,
        opts.record,
        opts.samples,
        c.steps,
        c.wall.as_secs_f64()
    );
    let w = t.point.omega;
    for (j, &wj) in w.iter().enumerate() {
        println!(
            "  pair {} peak near f{}: BDF {:.6} Hz, torus signal {:.6} Hz, torus {:.6} Hz; BDF against the torus {:.2e}, the measure's own {:.2e}",
            c.pair + 1,
            j + 1,
            c.bdf_omega[j] / (2.0 * PI),
            c.torus_peaks[j] / (2.0 * PI),
            wj / (2.0 * PI),
            rel(c.bdf_omega[j], wj),
            rel(c.torus_peaks[j], wj)
        );
    }
    let (b, h) = (&c.bdf_envelope, &c.torus_envelope);
    println!(
        "  swing over one period of f1: BDF {:.5e}..{:.5e} m, torus {:.5e}..{:.5e} m; relative {:.2e} (smallest), {:.2e} (largest)",
        b.swing_min,
        b.swing_max,
        h.swing_min,
        h.swing_max,
        rel(b.swing_min, h.swing_min),
        rel(b.swing_max, h.swing_max)
    );
    println!(
        "  closure: BDF {:.5e}..{:.5e} m, torus {:.5e}..{:.5e} m",
        b.min, b.max, h.min, h.max
    );
    Ok(())
}
