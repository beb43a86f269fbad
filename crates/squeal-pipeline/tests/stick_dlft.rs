//! Exact stick–slip (DLFT) on the coarse bundled brake at 3 km/h (issue 24, item 4): the
//! regularized law's cycles approach the DLFT ones as `v_reg → 0`.

mod common;

use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::branch::BranchPoint;
use squeal_chbm::stick_dlft::{DlftOptions, dlft_cycle, regularized_cycle};
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

/// `(df/f, d p2p / p2p)` of `q` against `r` on the pair `pair`.
fn diff(q: &BranchPoint, r: &BranchPoint, pair: usize) -> (f64, f64) {
    (
        q.omega / r.omega - 1.0,
        q.pairs[pair].peak_to_peak() / r.pairs[pair].peak_to_peak() - 1.0,
    )
}

#[test]
fn regularized_cycles_approach_the_dlft_ones_at_3_kmh() {
    faer::set_global_parallelism(faer::Par::Seq);
    let out = std::env::temp_dir().join("squeal-test-dlft-coarse-3");
    let _ = std::fs::remove_dir_all(&out);
    let p = Pipeline::new(scene(3.0), out.clone(), &quiet).unwrap();
    let mut opts = BranchOptions::default();
    opts.range = (0.5, 1.08);
    let t = std::time::Instant::now();
    let a = stages::branch_stage(&p, &opts, &[])
        .unwrap()
        .expect("the coarse brake has a Hopf point");
    eprintln!("branch stage {:.1} s", t.elapsed().as_secs_f64());
    let s = a
        .stick
        .as_ref()
        .and_then(|r| r.sticking.as_ref())
        .expect("the margin falls below 1 at 3 km/h");
    let m = p.model().unwrap();
    let st = p.stability().unwrap();
    let mb = ModalBrake::new(&m.brake, &st.reference, a.mu0());
    eprintln!("n_nl {}, pairs {}", mb.nl(), mb.pairs.len());
    let phase = a.branch.phase_dof;
    for c in &s.cycles {
        let Some(q) = c.cycle.as_ref() else { continue };
        let (pair, _) = q.loudest();
        let slide = &a.branch.points[c.point];
        let mut dl = Vec::new();
        for (h, g, name) in [(24, slide, "sliding"), (24, q, "reg V/20"), (36, slide, "sliding")] {
            let mut o = DlftOptions::default();
            o.harmonics = Some(h);
            let t = std::time::Instant::now();
            let d = dlft_cycle(&mb, c.mu, g, phase, &o).unwrap();
            let (df, dp) = diff(&d.point, q, pair);
            let (sf, sp) = diff(&d.point, slide, pair);
            eprintln!(
                "mu/mu0 {:.4} H {h} from {name}: DLFT f {:.5} Hz p2p {:.4} um, vs reg V/20 {df:+.2e} {dp:+.2e}, vs sliding {sf:+.2e} {sp:+.2e}; stick {:?} reversed {:?}, margin {:.4}, converged {} res {:.1e} it {} ({:.1} s)",
                c.mu / a.mu0(),
                d.point.frequency_hz(),
                d.point.pairs[pair].peak_to_peak() * 1e6,
                d.stick_fractions.iter().map(|x| format!("{x:.3}")).collect::<Vec<_>>(),
                d.reversed_fractions.iter().map(|x| format!("{x:.3}")).collect::<Vec<_>>(),
                d.margin.min,
                d.converged,
                d.point.residual,
                d.point.iterations,
                t.elapsed().as_secs_f64()
            );
            dl.push(d);
        }
        let d = &dl[0].point;
        let mut guess = q.clone();
        for frac in [0.05, 0.025, 0.0125, 0.00625] {
            let o = DlftOptions::default();
            let t = std::time::Instant::now();
            let (r, ok) =
                regularized_cycle(&mb, c.mu, frac * s.slowest_surface_speed, &guess, phase, &o)
                    .unwrap();
            let (df, dp) = diff(&r, d, pair);
            eprintln!(
                "   reg V*{frac}: f {:.5} Hz p2p {:.4} um, minus DLFT {df:+.2e} {dp:+.2e}, converged {ok} it {} ({:.1} s)",
                r.frequency_hz(),
                r.pairs[pair].peak_to_peak() * 1e6,
                r.iterations,
                t.elapsed().as_secs_f64()
            );
            guess = r;
        }
    }
}
