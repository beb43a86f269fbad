//! How loud the limit cycles of the bundled brake are (issue 23), and how long the sound of one
//! cycle takes: the branch from the Hopf point (default options), each cycle's full-field
//! coefficients (eq 35, [`squeal_chbm::branch::full_cycle`]), its surface velocity and its sound
//! ([`squeal_pipeline::sound`]) at the default microphone.
//!
//! `cargo bench -p squeal-pipeline --bench sound` (options after `--`: `level=coarse` or
//! `medium` (default), `reps=N` (20): best-of-N times of one cycle's steps).

#[path = "../tests/pipeline/common/mod.rs"]
mod common;

use common::best;

use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::branch::{BranchOptions, follow_from_hopf, full_cycle};
use squeal_pipeline::sound::{BrakeSurface, SoundOptions};
use squeal_pipeline::{Pipeline, model::quiet, stability};
use std::time::Instant;

fn arg(name: &str) -> Option<String> {
    std::env::args().find_map(|a| a.strip_prefix(&format!("{name}=")).map(String::from))
}

fn main() {
    faer::set_global_parallelism(faer::Par::Seq);
    let level = arg("level").unwrap_or_else(|| "medium".into());
    let reps: usize = arg("reps").map_or(20, |s| s.parse().unwrap());
    let out = std::env::temp_dir().join(format!("squeal-bench-sound-{level}"));
    let p = Pipeline::new(common::bundled_scene(&level), out, &quiet).unwrap();
    let t = Instant::now();
    let (m, st) = (p.model().unwrap(), p.stability().unwrap());
    eprintln!("{level} brake and sweep in {:.1?}", t.elapsed());
    let nf = stability::normal_form(m, st).unwrap().unwrap();
    let mb = ModalBrake::new(&m.brake, &st.reference, nf.mu0);
    let opts = BranchOptions::default();
    let branch = follow_from_hopf(&mb, &nf, &opts).unwrap();
    let t = Instant::now();
    let surface = BrakeSurface::new(&p.scene, m, &quiet).unwrap();
    let t_surface = t.elapsed().as_secs_f64();
    let so = SoundOptions::default();
    println!(
        "{level} brake: {} dofs, radiating faces {}, quadrature points {}, microphone ({:.3}, {:.3}, {:.3}) m; surface built in {:.1} ms",
        m.brake.size(),
        surface
            .faces_per_part
            .iter()
            .map(|(n, f)| format!("{n} {f}"))
            .collect::<Vec<_>>()
            .join(", "),
        surface.surface.points.len(),
        surface.microphone[0],
        surface.microphone[1],
        surface.microphone[2],
        t_surface * 1e3
    );
    println!(
        "branch: {} cycles, mu0 = {:.6}, {}",
        branch.points.len(),
        nf.mu0,
        branch.stop
    );
    println!(
        "| point | mu | mu/mu0 | f (Hz) | H | closure p2p (um) | Rayleigh dB(A) | monopole dB(A) | ERP dB re 1 pW | ERP dB(A) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let mut above: Vec<f64> = Vec::new();
    for (i, pt) in branch.points.iter().enumerate() {
        let c = full_cycle(&mb, pt, opts.samples).unwrap();
        let s = surface
            .cycle_sound(&c, pt.harmonics, pt.omega, &so)
            .unwrap();
        if s.rayleigh_dba[0] >= squeal_pipeline::sound::SQUEAL_DBA {
            above.push(pt.parameter);
        }
        println!(
            "| {i} | {:.6} | {:.5} | {:.2} | {} | {:.4} | {:.1} | {:.1} | {:.1} | {:.1} |",
            pt.parameter,
            pt.parameter / nf.mu0,
            pt.frequency_hz(),
            pt.harmonics,
            pt.loudest().1 * 1e6,
            s.rayleigh_dba[0],
            s.monopole_dba[0],
            s.erp_db,
            s.erp_dba
        );
    }
    if let (Some(lo), Some(hi)) = (
        above.iter().copied().reduce(f64::min),
        above.iter().copied().reduce(f64::max),
    ) {
        println!("above 70 dB(A) (Rayleigh) from mu = {lo:.6} to {hi:.6}");
    } else {
        println!("no cycle above 70 dB(A) (Rayleigh)");
    }
    // One cycle, timed: the last point of the branch.
    let pt = branch.points.last().unwrap();
    let (t_full, c) = best(reps, || full_cycle(&mb, pt, opts.samples).unwrap());
    let (t_vel, _) = best(reps, || {
        surface.velocities(&c, pt.harmonics, pt.omega).unwrap()
    });
    let (t_sound, _) = best(reps, || {
        surface
            .cycle_sound(&c, pt.harmonics, pt.omega, &so)
            .unwrap()
    });
    println!(
        "one cycle ({} harmonics), best of {reps}: full-field coefficients {:.2} ms, surface velocities {:.2} ms, velocities + sound {:.2} ms, total {:.2} ms",
        pt.harmonics,
        t_full * 1e3,
        t_vel * 1e3,
        t_sound * 1e3,
        (t_full + t_sound) * 1e3
    );
}
