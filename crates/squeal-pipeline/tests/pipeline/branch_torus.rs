//! `squeal branch` past the Neimark–Sacker point on the coarse bundled brake (issue 24,
//! item 1): the branch stage with the torus plan writes the torus rows, and each row is the
//! torus that `squeal_chbm::torus::torus_at` computes independently at its μ (a fresh
//! correction at fixed μ from the interpolated neighbours, on the same basis and grid).

use super::common;

use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::torus::{TorusOptions, torus_at};
use squeal_hbm::torus::Truncation;
use squeal_hbm::torus::lyapunov::TorusStability;
use squeal_pipeline::branch::BranchOptions;
use squeal_pipeline::branch_torus::TorusPlan;
use squeal_pipeline::{Pipeline, model::quiet, stages};

#[test]
fn coarse_brake_branch_continues_onto_the_torus() {
    faer::set_global_parallelism(faer::Par::Seq);
    let out = std::env::temp_dir().join(format!(
        "squeal-test-branch-torus-coarse-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&out);
    let p = Pipeline::new(common::bundled_scene("coarse"), out.clone(), &quiet).unwrap();
    let mut opts = BranchOptions::default();
    // The coarse brake's NS point is at 1.105 mu0; 1.14 mu0 keeps the test short.
    opts.range = (0.5, 1.14);
    let plan = TorusPlan {
        max_points: 12,
        ..TorusPlan::default()
    };
    let a = stages::branch_stage_with(&p, &opts, &[], &plan)
        .unwrap()
        .expect("the coarse brake has a Hopf point");
    assert!(
        !a.tori.is_empty(),
        "the coarse brake has a Neimark-Sacker point"
    );
    let run = &a.tori[0];
    let b = run.result.as_ref().expect("the torus branch converges");
    assert!(b.points.len() >= 4, "only {} tori", b.points.len());
    assert_eq!(run.stability.len(), b.points.len());

    // The CSV has one row per torus, with the frequencies and envelope of the points.
    let csv = std::fs::read_to_string(out.join("branch").join("branch_torus.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), b.points.len());
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for (row, pt) in rows.iter().zip(&b.points) {
        let f: f64 = row[col("f2_hz")].parse().unwrap();
        assert_eq!(
            f,
            pt.frequencies_hz()[1],
            "the CSV prints the value exactly"
        );
        assert!(!row[col("stability")].is_empty());
    }
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(out.join("branch").join("branch.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(
        json["tori"][0]["points"].as_array().unwrap().len(),
        b.points.len()
    );

    // A row against torus_at at its μ (the middle torus): both are Newton-converged solutions
    // of the same equations at the same μ, the difference is the corrector's tolerance (1e-9
    // on the scaled residual), so frequencies agree to ~1e-10 and the envelope (measured alike
    // on 300 fast periods) to ~1e-7 relative.
    let st = p.stability().unwrap();
    let m = p.model().unwrap();
    let mb = ModalBrake::new(&m.brake, &st.reference, a.mu0());
    let i = b.points.len() / 2;
    let pt = &b.points[i];
    let q = torus_at(&mb, b, pt.mu, None, Some(b.grid), &TorusOptions::default()).unwrap();
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs();
    for k in 0..2 {
        let e = rel(q.omega[k], pt.omega[k]);
        assert!(e < 1e-8, "f{}: {e:.2e}", k + 1);
    }
    let (pair, e) = pt.loudest();
    let eq = q.pairs[pair].envelope;
    eprintln!(
        "torus {i} at {:.5} mu0: f {:?} Hz; torus_at rel. differences f1 {:.1e} f2 {:.1e} swing {:.1e} {:.1e}",
        pt.mu / a.mu0(),
        pt.frequencies_hz(),
        rel(q.omega[0], pt.omega[0]),
        rel(q.omega[1], pt.omega[1]),
        rel(eq.swing_min, e.swing_min),
        rel(eq.swing_max, e.swing_max)
    );
    assert!(rel(eq.swing_min, e.swing_min) < 1e-5);
    assert!(rel(eq.swing_max, e.swing_max) < 1e-5);

    // Stability: every torus got its exponents; print them for the record.
    for (pt, s) in run.points() {
        let s = s.as_ref().expect("the exponents are computed");
        eprintln!(
            "  {:.5} mu0: exponents {:?} 1/s, transverse {:.3} +- {:.3}: {}",
            pt.mu / a.mu0(),
            s.exponents,
            s.transverse(),
            s.uncertainty(),
            s.stability()
        );
        assert!(s.stability() != TorusStability::Unstable || s.transverse() > 0.0);
    }

    // The first angle's truncation at the same μ, on one grid (256 × 32: no aliasing change
    // between the bases) and on each basis' default grid. Measured: f1 converges (7.4e-6 from
    // H to H + 2, 1.3e-6 from H + 2 to H + 4) but f2 does not settle below ~1e-4 at these
    // orders (1.3e-5, then 7.7e-5: the closure's opening makes the series converge slowly), so
    // the default stays Box(H, 2): asserted, f1's changes shrink and f2 moves by less than
    // 1e-4 (the verification's tolerance on both frequencies) over H..H + 4.
    let h = b.basis.truncation().max_orders().0;
    let (mut f1, mut f2) = (Vec::new(), Vec::new());
    for (t, grid) in [
        (Truncation::Box(h, 2), Some([256, 32])),
        (Truncation::Box(h + 2, 2), Some([256, 32])),
        (Truncation::Box(h + 4, 2), Some([256, 32])),
        (Truncation::Box(h + 2, 2), None),
        (Truncation::Box(h + 4, 2), None),
    ] {
        let q = torus_at(&mb, b, pt.mu, Some(t), grid, &TorusOptions::default()).unwrap();
        let e = q.pairs[pair].envelope;
        eprintln!(
            "{t:?} grid {grid:?}: f1 {:.6} Hz, f2 {:.6} Hz, swing {:.4}..{:.4} um",
            q.frequencies_hz()[0],
            q.frequencies_hz()[1],
            1e6 * e.swing_min,
            1e6 * e.swing_max
        );
        f2.push(q.omega[1]);
        f1.push(q.omega[0]);
    }
    eprintln!(
        "changes on 256 x 32, H -> H+2 and H+2 -> H+4: f1 {:.2e} {:.2e}, f2 {:.2e} {:.2e}",
        rel(f1[1], f1[0]),
        rel(f1[2], f1[1]),
        rel(f2[1], f2[0]),
        rel(f2[2], f2[1])
    );
    assert!(rel(f1[2], f1[1]) < rel(f1[1], f1[0]));
    for x in &f2 {
        assert!(rel(*x, f2[0]) < 1e-4, "f2 {x} against {}", f2[0]);
    }
}
