//! CHBM on the coarse bundled brake (158 dofs): harmonics × harmonic ladder at 1.01 μ0 and
//! 1.1 μ0, with LM iterations, best-of-N wall time and a per-call cost breakdown.
//!
//! `cargo bench -p squeal-pipeline --bench chbm` (options after `--`: `reps=N` (5), `H=1,3,5,10`,
//! `ratios=1.01,1.1`, `restarts` to also time the CLI's amplitude restarts for H = 1,2,3,5,10).
//!
//! The brake is the bundled scene on the coarse meshes built by the production builder
//! (`tests/pipeline/common`: patch contact, 3 kN, 1 % modal damping) with the scene's pair damping
//! (0.1 % on the two coalescing modes, picked automatically), as `squeal chbm` sets it up; the
//! start at μ is [`squeal_chbm::start::start_at`] with the unstable mode of largest growth in
//! the band.

#[path = "../tests/pipeline/common/mod.rs"]
mod common;

use common::best;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::{Accum, Par};
use squeal_brake::analysis::stability;
use squeal_brake::harmonic::{BrakeEigen, CondensedStiffness, ContactForce};
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::start::start_at;
use squeal_chbm::{ChbmOptions, ChbmSolution, ChbmStart, Outcome, RESTART_AMPLITUDES, solve};
use squeal_hbm::{Aft, DescribingFunction, HarmonicLayout, LinearizedEigen, reference_jacobian};
use std::time::Instant;

/// The CLI's initial amplitudes.
const AMPLITUDES: [f64; 4] = RESTART_AMPLITUDES;

fn short(o: Outcome) -> &'static str {
    match o {
        Outcome::LimitCycle => "cycle",
        Outcome::LimitCycleUnconstrained => "unconstr.",
        Outcome::Static => "static",
        Outcome::NotConverged => "not conv.",
    }
}

/// Per-call costs (best of `reps`, µs) of the pieces of one LM iteration at the solution:
/// AFT forces and Jacobian, the condensed stiffness `Λ_eq(ω)` and `dΛ_eq/dω` for a new ω
/// (eq 32), the describing-function linearization of the cycle, the eigenvalue tracking, and
/// LM's normal equations and Cholesky factorization.
fn breakdown(mb: &ModalBrake, start: &ChbmStart, s: &ChbmSolution, reps: usize) -> [f64; 5] {
    let h = s.harmonics;
    let layout = HarmonicLayout::new(mb.nl(), h).unwrap();
    let force = ContactForce::new(mb);
    let mut aft = Aft::new(layout, s.samples).unwrap();
    let l = layout.len();
    let (mut f, mut jw) = (vec![0.0; l], vec![0.0; l]);
    let mut ju = faer::Mat::<f64>::zeros(l, l);
    let reps = reps * 4;
    let (t_aft, _) = best(reps, || {
        aft.forces_and_jacobian(&force, &s.nl_coeffs, s.omega, &mut f, ju.as_mut(), &mut jw)
            .unwrap()
    });
    let mut k = 0;
    let mut st = CondensedStiffness::new(mb, h);
    let (t_cond, _) = best(reps, || {
        k += 1;
        st.update(s.omega * (1.0 + 1e-9 * k as f64));
    });
    aft.forces(&force, &s.nl_coeffs, s.omega, &mut f).unwrap();
    let x0: Vec<f64> = mb.nl_dofs.iter().map(|&d| start.equilibrium[d]).collect();
    let (k0, c0) = reference_jacobian(&force, &x0);
    let (t_eql, df) = best(reps, || {
        DescribingFunction::new(&layout, &s.nl_coeffs, s.omega, &f, &k0, &c0)
    });
    let mut eig = BrakeEigen::new(mb, None);
    eig.track(&df.update(&k0, &c0), s.lambda).unwrap();
    let (t_track, _) = best(reps, || eig.track(&df.update(&k0, &c0), s.lambda).unwrap());
    // LM's linear algebra per iteration (lm.rs): `JᵀJ` of the `(l + 2) × (l + 1)` Jacobian
    // (lower triangle) and one Cholesky factorization of the damped matrix, same sizes.
    let (m, n) = (l + 2, l + 1);
    let jac = faer::Mat::<f64>::from_fn(m, n, |i, j| {
        ((i * 7 + j * 13) % 17) as f64 + f64::from(u8::from(i == j)) * 40.0
    });
    let mut jtj = faer::Mat::<f64>::zeros(n, n);
    let mut factor = faer::Mat::<f64>::zeros(n, n);
    let mut mem = MemBuffer::new(llt::factor::cholesky_in_place_scratch::<f64>(
        n,
        Par::Seq,
        Default::default(),
    ));
    let (t_lm, _) = best(reps, || {
        triangular::matmul(
            jtj.as_mut(),
            BlockStructure::TriangularLower,
            Accum::Replace,
            jac.transpose(),
            BlockStructure::Rectangular,
            jac.as_ref(),
            BlockStructure::Rectangular,
            1.0,
            Par::Seq,
        );
        factor.copy_from_triangular_lower(jtj.as_ref());
        for j in 0..n {
            factor[(j, j)] += 1e-3 * factor[(j, j)];
        }
        llt::factor::cholesky_in_place(
            factor.as_mut(),
            Default::default(),
            Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        )
        .unwrap();
    });
    [t_aft, t_cond, t_eql, t_track, t_lm].map(|t| t * 1e6)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |key: &str| {
        args.iter()
            .find_map(|a| a.strip_prefix(&format!("{key}=")).map(str::to_string))
    };
    let reps: usize = arg("reps").and_then(|s| s.parse().ok()).unwrap_or(5);
    let list = |key: &str, d: &str| -> Vec<String> {
        arg(key)
            .unwrap_or(d.into())
            .split(',')
            .map(str::to_string)
            .collect()
    };
    let hs: Vec<usize> = list("H", "1,3,5,10")
        .iter()
        .map(|s| s.parse().unwrap())
        .collect();
    let ratios: Vec<f64> = list("ratios", "1.01,1.1")
        .iter()
        .map(|s| s.parse().unwrap())
        .collect();
    let restarts = args.iter().any(|a| a == "restarts");
    let history = args.iter().any(|a| a == "history");

    let t = Instant::now();
    let c = common::coarse();
    let opts = common::options(c);
    let brake = &c.model.brake;
    let st = stability(brake, &c.model.damping, &common::mus(0.0, 1.0, 201), &opts).unwrap();
    let mu0 = st.sweep.hopf.as_ref().expect("no Hopf point").mu0;
    eprintln!(
        "coarse brake and stability in {:.1?}: mu0 = {mu0:.6}",
        t.elapsed()
    );

    for &ratio in &ratios {
        let mu = ratio * mu0;
        let start: ChbmStart =
            start_at(brake, &st.reference, mu, &opts.band, &opts.newton, None).unwrap();
        let mb = ModalBrake::new(brake, &st.reference, mu);
        println!(
            "\n{ratio} mu0 (mu = {mu:.6}): {} dofs, {} nonlinear; unstable lambda = {:.3}",
            mb.modes(),
            mb.nl(),
            start.lambda
        );
        println!(
            "{:>3} {:>6} {:>10} {:>5} {:>9} {:>12} {:>9} | per call (us): {:>7} {:>7} {:>6} {:>6} {:>7}",
            "H",
            "ladder",
            "outcome",
            "iters",
            "ms",
            "f (Hz)",
            "|f1|",
            "AFT+J",
            "Lam_eq",
            "descr.",
            "track",
            "JtJ+LL"
        );
        for &h in hs.iter().filter(|_| arg("profile").is_none()) {
            for ladder in [true, false] {
                if h == 1 && !ladder {
                    continue;
                }
                let o = {
                    let mut o = ChbmOptions::default();
                    o.harmonics = h;
                    o.amplitude = AMPLITUDES[0];
                    o.ladder = ladder;
                    o
                };
                let (t, s) = best(reps, || solve(&mb, &start, &o).unwrap());
                let b = breakdown(&mb, &start, &s, reps);
                if history {
                    for (e, v) in s.lm_history.iter().zip(&s.evaluations[1..]) {
                        eprintln!(
                            "  H{} it {:>3} |r| {:.3e} trial {:.3e} damping {:.2e} step {:.2e} rho {:.3} {} | f1 {:.2e} Re {:.3e} w {:.4}",
                            v.harmonics,
                            e.iteration,
                            e.residual_norm,
                            e.trial_residual_norm,
                            e.damping,
                            e.step_norm,
                            e.gain_ratio,
                            if e.accepted { "acc" } else { "rej" },
                            v.f1,
                            v.re_lambda,
                            v.omega
                        );
                    }
                }
                println!(
                    "{h:>3} {:>6} {:>10} {:>5} {:>9.2} {:>12.5} {:>9.1e} | {:>7.0} {:>7.0} {:>6.0} {:>6.0} {:>7.0}",
                    if ladder { "on" } else { "off" },
                    short(s.outcome),
                    s.iterations,
                    t * 1e3,
                    s.omega / (2.0 * std::f64::consts::PI),
                    s.f1,
                    b[0],
                    b[1],
                    b[2],
                    b[3],
                    b[4]
                );
            }
        }
        if let Some(n) = arg("profile").and_then(|s| s.parse::<usize>().ok()) {
            // Only the ladder solve of the first H, n times (for `perf record`).
            let o = {
                let mut o = ChbmOptions::default();
                o.harmonics = hs[0];
                o.amplitude = AMPLITUDES[0];
                o
            };
            let (t, s) = best(n, || solve(&mb, &start, &o).unwrap());
            println!(
                "profile: H = {}: {} iterations, best {:.2} ms",
                hs[0],
                s.iterations,
                t * 1e3
            );
            continue;
        }
        if restarts {
            println!("CLI amplitudes (ladder on), each on its own:");
            for h in [1, 2, 3, 5, 10] {
                let mut row = format!("{h:>3}:");
                for a in AMPLITUDES {
                    let o = {
                        let mut o = ChbmOptions::default();
                        o.harmonics = h;
                        o.amplitude = a;
                        o
                    };
                    let t = Instant::now();
                    let s = solve(&mb, &start, &o).unwrap();
                    row += &format!(
                        "  p={a}: {} {} it {:.1} ms {:.5} Hz;",
                        short(s.outcome),
                        s.iterations,
                        t.elapsed().as_secs_f64() * 1e3,
                        s.omega / (2.0 * std::f64::consts::PI)
                    );
                }
                println!("{row}");
            }
        }
    }
}
