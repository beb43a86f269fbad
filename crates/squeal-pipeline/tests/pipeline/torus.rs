//! The coarse bundled brake past its Neimark–Sacker point: the torus of the quasi-periodic
//! harmonic balance (`squeal_chbm::torus`) against a long BDF time integration of the full
//! modal equations started on it (issue 24, item 5).
//!
//! The reference is independent of the harmonic balance: it integrates eq (11) in all 316
//! modal states with squeal-ode's variable-order BDF at rtol 1e-8 (its dispersion is orders
//! below the tolerances asserted), and measures the loudest pair's closure with the same
//! spectral-peak and envelope measures as the torus' signal.

use super::common;

use squeal_brake::dynamics::BrakeDynamics;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::bifurcation::{BifurcationKind, bifurcations, follow_from_hopf_with_hill};
use squeal_chbm::branch::BranchOptions;
use squeal_chbm::floquet::HillOptions;
use squeal_chbm::torus::{
    TorusOptions, TorusPoint, closures_along_flow, follow_torus, modal_state, torus_at,
};
use squeal_hbm::torus::Truncation;
use squeal_hbm::torus::measure::{envelope, peak_frequency};
use squeal_ode::{Atol, Bdf, BdfOptions};
use squeal_pipeline::{Pipeline, model::quiet, stability};

/// Samples per fast period of the recorded signals.
const SAMPLES: usize = 64;
/// Fast periods integrated before the record starts, and recorded.
const TRANSIENT: usize = 100;
const RECORD: usize = 400;

#[test]
fn coarse_brake_torus_matches_time_integration() {
    faer::set_global_parallelism(faer::Par::Seq);
    let out = std::env::temp_dir().join(format!("squeal-test-torus-coarse-{}", std::process::id()));
    let p = Pipeline::new(common::bundled_scene("coarse"), out, &quiet).unwrap();
    let (m, st) = (p.model().unwrap(), p.stability().unwrap());
    let nf = stability::normal_form(m, st).unwrap().unwrap();
    let mb = ModalBrake::new(&m.brake, &st.reference, nf.mu0);
    let opts = BranchOptions::default();
    let b = follow_from_hopf_with_hill(&mb, &nf, &opts, &HillOptions::default()).unwrap();
    let bifs = bifurcations(&b.branch, &b.floquet);
    let ns = bifs
        .iter()
        .find(|x| x.kind == BifurcationKind::NeimarkSacker)
        .expect("the coarse brake's branch has a Neimark-Sacker point");
    let mut topts = TorusOptions::default();
    topts.continuation.parameter_range = (0.5 * nf.mu0, 1.14 * nf.mu0);
    let tb = follow_torus(&mb, &b.branch, &opts, ns, &topts).unwrap();
    let mu = 1.12 * nf.mu0;
    let h1 = tb.basis.truncation().max_orders().0;

    // Convergence with the 2-D order, at the same μ.
    let mut table = Vec::new();
    for t in [
        Truncation::Box(h1, 1),
        Truncation::Box(h1, 2),
        Truncation::Box(h1, 3),
        Truncation::Box(h1 + 2, 2),
    ] {
        let q = torus_at(&mb, &tb, mu, Some(t), None, &topts).unwrap();
        let (pair, e) = q.loudest();
        eprintln!(
            "{t:?}: f1 {:.6} Hz, f2 {:.6} Hz, pair {pair} swing {:.4}..{:.4} um",
            q.frequencies_hz()[0],
            q.frequencies_hz()[1],
            1e6 * e.swing_min,
            1e6 * e.swing_max
        );
        table.push(q);
    }
    let torus: &TorusPoint = &table[1];
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();

    // BDF from the torus' state at θ = 0.
    let mut mbm = mb.clone();
    mbm.mu = mu;
    let y0 = modal_state(
        &mbm,
        tb.basis.truncation(),
        Some(tb.grid),
        &torus.coeffs,
        torus.omega,
        [0.0, 0.0],
    )
    .unwrap();
    let sys = BrakeDynamics::new(&mbm);
    let period = 2.0 * std::f64::consts::PI / torus.omega[0];
    let dt = period / SAMPLES as f64;
    let scale = y0.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let bdf_opts = {
        let mut o = BdfOptions::default();
        o.rtol = 1e-8;
        o.atol = Atol::Scalar(1e-8 * scale);
        o.max_order = 5;
        o
    };
    let t_end = (TRANSIENT + RECORD) as f64 * period;
    let mut bdf = Bdf::new(&sys, 0.0, &y0, t_end, &bdf_opts).unwrap();
    let (pair, _) = torus.loudest();
    let n = mbm.modes();
    let mut y = vec![0.0; 2 * n];
    let mut xn = vec![0.0; mbm.nl()];
    let mut signal = Vec::with_capacity(RECORD * SAMPLES);
    let mut j = 0;
    let start = Instant::now();
    while !bdf.is_finished() {
        bdf.step().unwrap();
        loop {
            let t = (TRANSIENT * SAMPLES + j) as f64 * dt;
            if t > bdf.t() || j >= RECORD * SAMPLES {
                break;
            }
            bdf.interpolate(t, &mut y).unwrap();
            mbm.nonlinear_part(&y[..n], &mut xn);
            signal.push(mbm.pairs[pair].penetration(&xn));
            j += 1;
        }
    }
    eprintln!(
        "BDF: {} steps over {} fast periods in {:.1?}",
        bdf.stats().steps,
        TRANSIENT + RECORD,
        start.elapsed()
    );
    let w = torus.omega;
    let f1 = peak_frequency(&signal, dt, w[0], 0.3 * w[1]).unwrap();
    let f12 = peak_frequency(&signal, dt, w[0] + w[1], 0.3 * w[1]).unwrap();
    let f2 = f12 - f1;
    let e_bdf = envelope(&signal, dt, period).unwrap();
    // The torus' own signal, measured alike.
    let hb = closures_along_flow(&mbm, &tb.basis, &torus.coeffs, w, dt, RECORD * SAMPLES).unwrap();
    let e_hb = envelope(&hb[pair], dt, period).unwrap();
    let g1 = peak_frequency(&hb[pair], dt, w[0], 0.3 * w[1]).unwrap();
    let g2 = peak_frequency(&hb[pair], dt, w[0] + w[1], 0.3 * w[1]).unwrap() - g1;
    eprintln!(
        "torus: f1 {:.6} Hz, f2 {:.6} Hz (its own signal's peaks {:.6}, {:.6}); BDF peaks f1 {:.6} Hz, f2 {:.6} Hz",
        w[0] / std::f64::consts::TAU,
        w[1] / std::f64::consts::TAU,
        g1 / std::f64::consts::TAU,
        g2 / std::f64::consts::TAU,
        f1 / std::f64::consts::TAU,
        f2 / std::f64::consts::TAU
    );
    eprintln!(
        "swing: torus {:.4}..{:.4} um, BDF {:.4}..{:.4} um; closure torus {:.4}..{:.4}, BDF {:.4}..{:.4} um",
        1e6 * e_hb.swing_min,
        1e6 * e_hb.swing_max,
        1e6 * e_bdf.swing_min,
        1e6 * e_bdf.swing_max,
        1e6 * e_hb.min,
        1e6 * e_hb.max,
        1e6 * e_bdf.min,
        1e6 * e_bdf.max
    );
    // The measure itself, on the torus' own signal (whose frequencies are known exactly):
    // the peaks' leakage bias stays below a tenth of the tolerance asserted on the BDF run.
    assert!(
        rel(g1, w[0]) < 1e-5,
        "the spectral measure is biased: {g1} vs {}",
        w[0]
    );
    assert!(
        rel(g2, w[1]) < 1e-5,
        "the spectral measure is biased: {g2} vs {}",
        w[1]
    );
    // The tolerances: both frequencies within 1e-4, the envelope within 1 %.
    assert!(rel(f1, w[0]) < 1e-4, "f1: {f1} vs {}", w[0]);
    assert!(rel(f2, w[1]) < 1e-4, "f2: {f2} vs {}", w[1]);
    assert!(rel(e_bdf.swing_max, e_hb.swing_max) < 0.01);
    assert!(rel(e_bdf.swing_min, e_hb.swing_min) < 0.01);
    // Convergence with the 2-D order (measured when this test was written: Box(7, 3) against
    // Box(7, 2) 4.1e-7 in f1, 1.05e-6 in f2; Box(9, 2) against Box(7, 2) 1.4e-6 and 8.4e-5):
    // bounds five times those, to catch a change of the method, not a statement of accuracy.
    assert!(rel(table[2].omega[0], torus.omega[0]) < 2e-6);
    assert!(rel(table[2].omega[1], torus.omega[1]) < 5e-6);
    assert!(rel(table[3].omega[0], torus.omega[0]) < 7e-6);
    assert!(rel(table[3].omega[1], torus.omega[1]) < 4.2e-4);
}

use std::time::Instant;
