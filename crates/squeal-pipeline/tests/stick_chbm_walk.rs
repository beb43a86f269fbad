//! `squeal chbm`'s single DLFT cycle past 1.05 μ0 (issue 24, item 4): on the coarse bundled
//! brake at 3 km/h DLFT stops short from the CHBM cycle and the V/20 start at 1.0649 μ0, and
//! the single-cycle path continues it in μ from below (`squeal_pipeline::cycle_walk`) to the
//! cycle `squeal branch`'s walk reaches at the same μ.

mod common;

use squeal_pipeline::{Pipeline, model::quiet};
use squeal_scene::StickSlipSetting;

#[test]
fn the_single_cycle_walks_past_1_05_mu0_to_the_branch_cycle() {
    faer::set_global_parallelism(faer::Par::Seq);
    let out = std::env::temp_dir().join("squeal-test-chbm-walk");
    let _ = std::fs::remove_dir_all(&out);
    let p = Pipeline::new(common::bundled_scene_at_speed(3.0), out, &quiet).unwrap();
    let (m, st) = (p.model().unwrap(), p.stability().unwrap());
    let mu0 = p.mu0().unwrap();
    let mu = 1.0649 * mu0;
    let t = std::time::Instant::now();
    let sol = common::chbm_cycle(&p, mu);
    let law = StickSlipSetting::Dlft {
        epsilon_factor: 1.0,
    };
    let c = squeal_pipeline::cycle_stick::recompute(m, st, law, mu, &sol)
        .unwrap()
        .expect("the margin is below 1 at 3 km/h");
    let text = squeal_pipeline::cycle_stick::text(&c);
    eprintln!("{text}({:.1} s)", t.elapsed().as_secs_f64());
    // The direct starts (40 iterations each) stop short there (measured: relative residuals
    // 9.0e-3 from the CHBM cycle, 9.6e-3 from V/20), so the cycle must come from the walk.
    // (At 1.0540 mu0 the CHBM start converges with the clamp.)
    let w = c.walk.as_ref().expect("continued in mu from below");
    assert!(w.reached && c.converged, "{text}");
    assert!(text.contains("continued in mu from below"), "{text}");
    // Converged by the rule every DLFT cycle is judged by: 1e-9 of the largest pair force.
    assert!(c.cycle.residual <= 1e-9, "residual {:e}", c.cycle.residual);
    // `squeal branch`'s walk at 1.0649 mu0 (the same DLFT balance continued in mu from the
    // 1.0452 mu0 cycle through 1.0540 mu0; docs/stick_slip.md, "Continuation in mu",
    // `tests/stick_walk.rs`): 3963.84817 Hz, 46.0683 um on pair 7 (0-based 6). Both are roots
    // of the same balance with residuals <= 1e-9 reached by different walks; tolerance 2e-7
    // in frequency and 1e-5 in closure: the printed digits' rounding (1.3e-9, 1.1e-6) plus the
    // spread of such roots (measured from a walk from 1.0223 mu0: 4.7e-8 and 9.6e-7).
    let (pair, _) = c.sliding.loudest();
    let f = c.cycle.frequency_hz();
    let p2p = c.cycle.pairs[pair].peak_to_peak() * 1e6;
    eprintln!(
        "f {f:.8} Hz ({:+.2e}), p2p pair {} {p2p:.6} um ({:+.2e})",
        f / 3963.84817 - 1.0,
        pair + 1,
        p2p / 46.0683 - 1.0
    );
    assert_eq!(pair, 6, "the loudest pair");
    assert!((f / 3963.84817 - 1.0).abs() < 2e-7, "{f}");
    assert!((p2p / 46.0683 - 1.0).abs() < 1e-5, "{p2p}");
}
