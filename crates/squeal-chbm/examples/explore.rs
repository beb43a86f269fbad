use squeal_brake::analysis::{DampingSpec, PairChoice, stability};
use squeal_brake::assemble::{BrakeParams, Stiffness, assemble};
use squeal_brake::equilibrium::static_equilibrium;
use squeal_brake::modal_brake::ModalBrake;
use squeal_brake::spectrum::spectrum;
use squeal_brake::sweep::{Band, SweepOptions};
use squeal_chbm::{ChbmOptions, ChbmStart, solve};
use squeal_reduce::rom::ReducedModel;
use std::path::Path;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let ratio: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(1.05);
    let harmonics: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3);
    let rom_path = std::env::var("ROM").unwrap_or("/tmp/h13/out/brake.rom".into());
    let rom = ReducedModel::read(Path::new(&rom_path)).unwrap();
    let params = BrakeParams {
        normal: [0.0, 0.0, 1.0],
        sliding: [1.0, 0.0, 0.0],
        stiffness: Stiffness::PerArea {
            linear: 1.25e10,
            cubic: 2.0e19,
            point_area: None,
        },
        pairing_tolerance: 1e-3,
        piston_force: 3000.0,
    };
    let (brake, _, _) = assemble(&rom, &params).unwrap();
    let spec = DampingSpec {
        global_ratio: 0.01,
        pair: PairChoice::Modes(12, 13),
        pair_ratios: [0.001, 0.001],
    };
    let opts = SweepOptions {
        band: Band {
            valid_max_hz: 20000.0,
            user: Some((1000.0, 16000.0)),
        },
        ..Default::default()
    };
    let mus: Vec<f64> = (0..=40).map(|k| 0.3 + 0.3 * k as f64 / 40.0).collect();
    let st = stability(&brake, &spec, &mus, &opts).unwrap();
    let h = st.sweep.hopf.as_ref().unwrap();
    let mu = ratio * h.mu0;
    eprintln!(
        "mu0 {:.6} f0 {:.2}; CHBM at mu = {mu:.6}",
        h.mu0, h.frequency_hz
    );
    let eq = static_equilibrium(&brake, mu, Some(&h.point.equilibrium.x), &opts.newton).unwrap();
    let sp = spectrum(&brake, &st.reference, &eq).unwrap();
    let j = (0..sp.values.len())
        .filter(|&j| opts.band.contains(sp.frequency_hz(j)))
        .max_by(|&a, &b| sp.values[a].re.total_cmp(&sp.values[b].re))
        .unwrap();
    eprintln!(
        "unstable eigenvalue {:?} ({:.2} Hz)",
        sp.values[j],
        sp.frequency_hz(j)
    );
    let start = ChbmStart {
        lambda: sp.values[j],
        mode: sp.shape(&st.reference.basis, j),
        equilibrium: eq.x.clone(),
    };
    let mb = ModalBrake::new(&brake, &st.reference, mu);
    let amps: Vec<f64> = args
        .get(3)
        .map(|s| s.split(",").map(|x| x.parse().unwrap()).collect())
        .unwrap_or(vec![0.3]);
    if let Ok(rtol) = std::env::var("TI") {
        use squeal_chbm::timeint::{TiOptions, integrate_to_limit_cycle};
        let env = |k: &str, d: f64| -> f64 {
            std::env::var(k)
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(d)
        };
        let o = TiOptions {
            rtol: rtol.parse().unwrap_or(1e-6),
            atol_factor: env("ATOL", 1.0),
            max_order: env("ORDER", 2.0) as usize,
            perturbation: env("PERT", 0.5),
            steady_rtol: env("SRTOL", 1e-5),
            drift_tol: env("DRIFT", 1e-5),
            max_cycles: env("CYCLES", 5000.0),
            ..Default::default()
        };
        let run = integrate_to_limit_cycle(&mb, start.lambda, &start.mode, &start.equilibrium, &o)
            .unwrap();
        let st = run.stats;
        eprintln!(
            "TI rtol {:e}: wall {:.1?}, t {:.4} s, steps {} ({:.0}/cycle), rejected {}+{}, lu {}, jac {}, newton {}, rhs {}, orders {:?}",
            o.rtol,
            run.wall,
            run.t_end,
            st.steps,
            st.steps as f64 / run.history.len().max(1) as f64,
            st.rejected_error,
            st.rejected_newton,
            st.lu_decomps,
            st.jac_evals,
            st.newton_iters,
            st.rhs_evals,
            st.order_histogram
        );
        eprintln!("drifts {:?}", run.drifts);
        if let Some(f) = &run.failure {
            eprintln!("TI failed: {f}");
        }
        if let Some(s) = &run.steady {
            eprintln!(
                "TI steady: f = {:.5} Hz after {} cycles (t {:.4}), drift {:.2e}, detections {}",
                1.0 / s.period,
                s.cycles,
                s.t,
                s.drift,
                s.detections
            );
            let eb = squeal_chbm::cycle::energy_balance(&mb, &s.cycle, 1024);
            eprintln!("energy balance {:?}", eb);
            let ho = ChbmOptions {
                harmonics: 10,
                amplitude: 0.5,
                ..Default::default()
            };
            let sol = solve(&mb, &start, &ho).unwrap();
            let mut c = sol.cycle();
            let d = s.cycle.strongest_dof(&mb.nl_dofs);
            c.align_to(&s.cycle, d);
            let all: Vec<usize> = (0..mb.modes()).collect();
            eprintln!(
                "H=10 vs TI: {:?} nl {:?}",
                squeal_chbm::cycle::relative_errors(&c, &s.cycle, &all),
                squeal_chbm::cycle::relative_errors(&c, &s.cycle, &mb.nl_dofs)
            );
        }
        let every = (run.history.len() / 30).max(1);
        let tail = run.history.len().saturating_sub(12);
        for r in run
            .history
            .iter()
            .step_by(every)
            .chain(&run.history[tail..])
        {
            eprintln!(
                "  t {:.4} T {:.6e} amp {:.4e}",
                r.t_start,
                r.period,
                r.amplitude()
            );
        }
    }
    for h in [1usize, 3] {
        let o = ChbmOptions {
            harmonics: h,
            amplitude: 0.5,
            ..Default::default()
        };
        eprintln!(
            "jacobian check H={h}: {:?}",
            squeal_chbm::check_jacobian(&mb, &start, &o).unwrap()
        );
    }
    for amp in amps {
        let weight: f64 = std::env::var("W")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(1.0);
        let plain = std::env::var("PLAIN").is_ok();
        let o = ChbmOptions {
            harmonics,
            amplitude: amp,
            weight,
            ladder: !plain,
            ..Default::default()
        };
        let t = std::time::Instant::now();
        let s = solve(&mb, &start, &o).unwrap();
        eprintln!(
            "H={harmonics} p={amp}: {} in {:.1?}: f = {:.4} Hz, f1 {:.2e}, Re {:.3e}, iters {} stop {:?}, open {:?}, alias {:.1e}, recov {:.1e}",
            s.outcome,
            t.elapsed(),
            s.omega / (2.0 * std::f64::consts::PI),
            s.f1,
            s.re_lambda,
            s.iterations,
            s.stop,
            s.open_fraction
                .iter()
                .map(|x| (x * 100.0).round())
                .collect::<Vec<_>>(),
            s.aliasing,
            s.recovery_error
        );
        let nd = mb.nl_dofs[0];
        eprintln!(
            "   amplitude of nl dof {nd}: {:?}",
            (0..=harmonics)
                .map(|k| s.amplitude(nd, k))
                .collect::<Vec<_>>()
        );
    }
}
