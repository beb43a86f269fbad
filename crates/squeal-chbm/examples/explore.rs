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
    let rom = ReducedModel::read(Path::new("/tmp/out_coarse/brake.rom")).unwrap();
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
    if std::env::var("TI").is_ok() {
        use squeal_brake::dynamics::BrakeDynamics;
        use squeal_ode::{Atol, Bdf, BdfOptions, SteadyOptions, run_to_steady_state};
        let n = mb.modes();
        let mphi = &brake.m * &mb.phi;
        let proj = |x: &[f64]| -> Vec<f64> {
            (0..n)
                .map(|j| (0..n).map(|i| mphi[(i, j)] * x[i]).sum())
                .collect()
        };
        let pen0 = eq
            .penetrations
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let psi = &start.mode;
        let gmax = brake
            .pairs
            .iter()
            .map(|p| {
                p.normal
                    .iter()
                    .map(|&(i, g)| psi[i] * g)
                    .sum::<faer::c64>()
                    .norm()
            })
            .fold(0.0, f64::max);
        let eps = 0.1 * pen0 / gmax;
        let x: Vec<f64> = (0..n).map(|i| eq.x[i] + eps * psi[i].re).collect();
        let v: Vec<f64> = (0..n).map(|i| eps * (start.lambda * psi[i]).re).collect();
        let y0 = BrakeDynamics::state(&proj(&x), &proj(&v));
        let sys = BrakeDynamics { brake: &mb };
        let rtol: f64 = std::env::var("TI").unwrap().parse().unwrap_or(1e-6);
        let o = BdfOptions {
            rtol,
            atol: Atol::Scalar(rtol * 1e-6),
            max_order: 2,
            max_steps: 50_000_000,
            ..Default::default()
        };
        let t_end = 10.0;
        let mut bdf = Bdf::new(&sys, 0.0, &y0, t_end, &o).unwrap();
        let pair = &mb.pairs[4];
        let level = pair.penetration(
            &(0..mb.nl())
                .map(|i| eq.x[mb.nl_dofs[i]])
                .collect::<Vec<_>>(),
        );
        let so = SteadyOptions {
            level,
            rtol: 1e-6,
            cycles: 20,
            harmonics: 10,
            samples_per_cycle: 128,
            subdivisions: 4,
            min_amplitude: 1e-12,
        };
        let t = std::time::Instant::now();
        let obs = |y: &[f64]| {
            let mut xn = vec![0.0; mb.nl()];
            mb.nonlinear_part(&y[..n], &mut xn);
            pair.penetration(&xn)
        };
        match run_to_steady_state(&mut bdf, obs, &so) {
            Ok(ss) => eprintln!(
                "TI steady: f = {:.4} Hz, amp p2p {:.3e} (static pen {:.3e}), cycles {}, t {:.4} s, wall {:.1?}, stats {:?}",
                1.0 / ss.period,
                ss.amplitude,
                level,
                ss.cycles,
                ss.t_start,
                t.elapsed(),
                bdf.stats()
            ),
            Err(e) => eprintln!(
                "TI failed: {e} after {:.1?} t = {}, stats {:?}",
                t.elapsed(),
                bdf.t(),
                bdf.stats()
            ),
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
