//! `squeal branch` where the pads stick (issue 24, item 4), on the coarse bundled brake.

mod common;

use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::stick_branch::{StickOptions, follow_sticking};
use squeal_pipeline::branch::BranchOptions;
use squeal_pipeline::{Pipeline, model::quiet, stages};
use squeal_scene::Scene;

/// The coarse bundled scene at `kmh` on a 0.3 m wheel.
fn scene(kmh: f64) -> Scene {
    let base = common::bundled_scene("coarse");
    let text = base
        .text
        .replacen(
            "# vehicle_speed_kmh = 5.0",
            &format!("vehicle_speed_kmh = {kmh:?}"),
            1,
        )
        .replacen("# rolling_radius = 0.3", "rolling_radius = 0.3", 1);
    assert_ne!(text, base.text, "meshes/brake.toml lost its speed lines");
    Scene::parse(&base.path, text).unwrap()
}

#[test]
fn coarse_brake_at_5_kmh_sticks_and_the_branch_is_recomputed() {
    faer::set_global_parallelism(faer::Par::Seq);
    let out = std::env::temp_dir().join("squeal-test-stick-coarse-5");
    let _ = std::fs::remove_dir_all(&out);
    let p = Pipeline::new(scene(5.0), out.clone(), &quiet).unwrap();
    let opts = BranchOptions::default();
    let a = stages::branch_stage(&p, &opts, &[])
        .unwrap()
        .expect("the coarse brake has a Hopf point");
    eprintln!("{}", squeal_pipeline::branch::summary_text(&a));
    let s = a
        .stick
        .as_ref()
        .and_then(|r| r.sticking.as_ref())
        .expect("the margin falls below 1 at 5 km/h");
    for (i, m) in s.margins.iter().enumerate() {
        eprintln!(
            "point {i}: mu/mu0 {:.5} margin {:.4}",
            a.branch.points[i].parameter / a.mu0(),
            m.min
        );
    }
    // Convergence in v_reg and in the harmonics at the recomputed cycles.
    let m = p.model().unwrap();
    let st = p.stability().unwrap();
    let mb = ModalBrake::new(&m.brake, &st.reference, a.mu0());
    for (reg, h) in [(0.05, 36), (0.025, 24), (0.025, 36)] {
        let mut o = StickOptions::default();
        o.regularization = reg;
        o.harmonics = h;
        let t = std::time::Instant::now();
        let r = follow_sticking(&mb, &a.branch, &opts, &o).unwrap().unwrap();
        eprintln!(
            "v_reg/V {reg}, H {h}: {} points ({}), {:.1} s",
            r.branch.points.len(),
            r.branch.stop,
            t.elapsed().as_secs_f64()
        );
        for (c, c0) in r.cycles.iter().zip(&s.cycles) {
            let (pair, _) = a.branch.points[c.point].loudest();
            if let (Some(q), Some(q0)) = (&c.cycle, &c0.cycle) {
                eprintln!(
                    "  point {}: f {:.4} (ref {:.4}, {:+.2e}), p2p {:.4} um (ref {:.4}, {:+.2e}), margin {:.4}",
                    c.point,
                    q.frequency_hz(),
                    q0.frequency_hz(),
                    q.omega / q0.omega - 1.0,
                    q.pairs[pair].peak_to_peak() * 1e6,
                    q0.pairs[pair].peak_to_peak() * 1e6,
                    q.pairs[pair].peak_to_peak() / q0.pairs[pair].peak_to_peak() - 1.0,
                    c.stick_margin.as_ref().map_or(f64::NAN, |m| m.min)
                );
            }
        }
    }
}

#[test]
fn a_stable_sticking_cycle_at_3_kmh_against_time_integration() {
    faer::set_global_parallelism(faer::Par::Seq);
    let out = std::env::temp_dir().join("squeal-test-stick-coarse-3");
    let _ = std::fs::remove_dir_all(&out);
    let p = Pipeline::new(scene(3.0), out.clone(), &quiet).unwrap();
    let mut opts = BranchOptions::default();
    opts.range = (0.5, 1.08);
    let a = stages::branch_stage(&p, &opts, &[])
        .unwrap()
        .expect("the coarse brake has a Hopf point");
    eprintln!("{}", squeal_pipeline::branch::summary_text(&a));
    let s = a
        .stick
        .as_ref()
        .and_then(|r| r.sticking.as_ref())
        .expect("the margin falls below 1 at 3 km/h");
    let m = p.model().unwrap();
    let st = p.stability().unwrap();
    let mb = ModalBrake::new(&m.brake, &st.reference, a.mu0());
    let smb = squeal_chbm::stick_branch::sticking_brake(&mb, s.regularization_speed).unwrap();
    let c = s
        .cycles
        .iter()
        .rev()
        .find(|c| {
            matches!(&c.floquet, Some(Ok(f)) if f.stability() == squeal_chbm::floquet::CycleStability::Stable)
        })
        .expect("a stable sticking cycle");
    let q = c.cycle.as_ref().unwrap();
    for rtol in [1e-6, 1e-7] {
        let mut o = squeal_chbm::timeint::TiOptions::default();
        o.rtol = rtol;
        o.harmonics = 24;
        o.samples_per_cycle = 128;
        let t = std::time::Instant::now();
        let r = squeal_chbm::stick_check::check_against_integration(&smb, q, Some(s.samples), &o)
            .unwrap();
        eprintln!(
            "point {} (mu/mu0 {:.5}, margin {:.4}), rtol {rtol}: HB period {:.9e} p2p {:.5e}; TI period {:?} p2p {:?}; {} steps, {:.1} s, failure {:?}",
            c.point,
            c.mu / a.mu0(),
            c.stick_margin.as_ref().unwrap().min,
            r.hb_period,
            r.hb_closure,
            r.ti_period,
            r.ti_closure,
            r.run.stats.steps,
            t.elapsed().as_secs_f64(),
            r.run.failure
        );
    }
}
