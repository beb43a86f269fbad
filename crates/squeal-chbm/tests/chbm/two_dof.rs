//! Independent checks of CHBM and of the time-integration reference on the 2-dof
//! mode-coupling friction oscillator (`tests/chbm/common/oscillator.rs`, the path of
//! `examples/friction_oscillator.rs` by hand; issue #6, item 9): a pair whose normal is dof 1 (eq 8's
//! `F = k_l δ + k_nl δ³`, δ = x1 - g0) and whose friction acts along `-e0` (coupling
//! `-μ k_t` in `K[0][1]`). The cubic term hardens the contact as the vibration grows; with
//! the stiffnesses chosen a stiffer contact raises the flutter threshold, so the Hopf point
//! is supercritical and, near it, the limit cycle's amplitude squared grows linearly with
//! `μ - μ0` (normal form of the Hopf bifurcation).

use super::common;

use common::oscillator::{self as example, KL, KNL};
use common::{Model, growth, hopf, model, normal_form_of, start, subcritical};
use faer::c64;
use squeal_brake::equilibrium::{NewtonOptions, static_equilibrium};
use squeal_brake::harmonic::{BrakeEigen, ContactForce};
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::cycle::relative_errors;
use squeal_chbm::timeint::{TiOptions, integrate_to_limit_cycle};
use squeal_chbm::{ChbmOptions, Outcome, RESTART_AMPLITUDES, check_jacobian, solve_with_restarts};
use squeal_hbm::{
    Aft, DescribingFunction, HarmonicLayout, LinearizedEigen, Part, reference_jacobian,
};

#[test]
fn the_example_runs_and_agrees_with_the_bisected_hopf_point() {
    // The example's μ0 (sweep + Newton refinement) against bisection on the dense spectrum:
    // both resolve μ0 to ~1e-9 relative.
    let m = model(KL, KNL);
    let mu0 = example::hopf(&m.brake, &m.reference);
    assert!((mu0 / hopf(&m) - 1.0).abs() < 1e-7, "{mu0} vs {}", hopf(&m));
    let s = example::limit_cycle(&m.brake, &m.reference, 1.001 * mu0, 3).unwrap();
    assert_eq!(s.outcome, Outcome::LimitCycle);
}

#[test]
fn the_facade_gives_the_hand_built_numbers() {
    // `squeal_chbm::system` from M, C = 20 I, K and the pair against the hand-built path: the
    // same pieces, except that the facade's modal damping is Φᵀ C Φ (20 to round-off, kept
    // diagonal) where the hand-built one is exactly 20; μ0 to the sweep's 1e-8 bracket, the
    // cycle to LM's 1e-9 of the force scale (plus what μ0's 1e-8 moves).
    use squeal_chbm::{Contact, FrictionSystem};
    let m = model(KL, KNL);
    let c = faer::Mat::from_fn(2, 2, |i, j| if i == j { example::C } else { 0.0 });
    let pair =
        Contact::penalty_coulomb(&[(1, 1.0)], &[(0, -1.0)], KL, KNL).initial_gap(-example::GAP);
    let sys = FrictionSystem::builder(m.brake.m.clone(), c, m.brake.k.clone())
        .contact(pair)
        .build()
        .unwrap();
    let d = sys
        .reference()
        .damping
        .diagonal()
        .expect("C = 20 I stays diagonal");
    assert!(
        d.iter().all(|x| (x / example::C - 1.0).abs() < 1e-14),
        "{d:?}"
    );
    let mu0 = example::hopf(&m.brake, &m.reference);
    let h = sys.hopf().unwrap();
    assert!((h.mu0 - mu0).abs() < 2e-8, "{} vs {mu0}", h.mu0);
    let by_hand = example::limit_cycle(&m.brake, &m.reference, 1.001 * mu0, 3).unwrap();
    let facade = sys.limit_cycle(1.001 * mu0).unwrap();
    assert_eq!(facade.outcome, Outcome::LimitCycle);
    let (a, b) = (facade.amplitude(1, 1), by_hand.amplitude(1, 1));
    assert!((a / b - 1.0).abs() < 1e-7, "{a:e} vs {b:e}");
    assert!((facade.omega / by_hand.omega - 1.0).abs() < 1e-10);
}

/// First-harmonic amplitude of the normal dof, CHBM with `h` harmonics.
fn chbm_amplitude(m: &Model, mu: f64, h: usize) -> (f64, f64) {
    let mb = ModalBrake::new(&m.brake, &m.reference, mu);
    let (s, ..) = solve_with_restarts(
        &mb,
        &start(m, mu),
        &{
            let mut o = ChbmOptions::default();
            o.harmonics = h;
            o
        },
        &RESTART_AMPLITUDES,
    )
    .unwrap();
    assert_eq!(s.outcome, Outcome::LimitCycle, "CHBM at mu = {mu}");
    (s.amplitude(1, 1), s.omega)
}

fn ti(m: &Model, mu: f64) -> squeal_chbm::timeint::TiSteady {
    let mb = ModalBrake::new(&m.brake, &m.reference, mu);
    let st = start(m, mu);
    let run = integrate_to_limit_cycle(&mb, st.lambda, &st.mode, &st.equilibrium, &{
        let mut o = TiOptions::default();
        // Near the Hopf point the amplitude is set by a balance of growth rates of a
        // fraction of 1 s⁻¹, and the integrator's numerical damping shifts it: at rtol 1e-8
        // the amplitude at 1.001 μ0 was 3.4e-4 off CHBM's, at 1e-10 7e-6 (and CHBM did not
        // move). The 2-dof model is cheap enough for the tight tolerance.
        o.rtol = 1e-10;
        // No lightly damped high modes here: the higher orders are stable and cheaper.
        o.max_order = 5;
        o.perturbation = 0.05;
        o.harmonics = 5;
        o.samples_per_cycle = 64;
        o.drift_tol = 1e-7;
        o.steady_rtol = 1e-5;
        o.max_cycles = 20_000.0;
        o
    })
    .unwrap();
    run.steady
        .unwrap_or_else(|| panic!("no steady cycle at mu = {mu}: {:?}", run.failure))
}

#[test]
fn hardening_contact_stabilizes_the_coupled_mode() {
    // Supercriticality needs dRe λ/dk_t < 0 at the Hopf point: a stiffer contact (what the
    // cubic term gives a growing vibration) must stabilize the unstable mode.
    let m = model(KL, KNL);
    let mu0 = hopf(&m);
    let eq = static_equilibrium(&m.brake, mu0, None, &NewtonOptions::default()).unwrap();
    let delta = eq.penetrations[0];
    let kt = KL + 3.0 * KNL * delta * delta;
    // The same tangent stiffness ±1 % as a linear contact at the same penetration.
    let stiffer = model(1.01 * kt - 3.0 * KNL * delta * delta, KNL);
    let softer = model(0.99 * kt - 3.0 * KNL * delta * delta, KNL);
    let slope = (growth(&stiffer, mu0) - growth(&softer, mu0)) / (0.02 * kt);
    assert!(slope < 0.0, "dRe/dk = {slope}");
}

#[test]
fn amplitude_squared_grows_linearly_with_friction_in_both_methods() {
    let m = model(KL, KNL);
    let mu0 = hopf(&m);
    // Re λ grows by about 3.7 s⁻¹ per per cent of friction while a vibration of half the
    // static penetration only takes 1.4 s⁻¹ off it: the cycle stays in contact (amplitude
    // below the penetration) only within a few tenths of a per cent of μ0.
    let eps = [0.0005, 0.001, 0.002];
    let chbm: Vec<f64> = eps
        .iter()
        .map(|e| chbm_amplitude(&m, mu0 * (1.0 + e), 3).0.powi(2) / e)
        .collect();
    let tis: Vec<f64> = eps
        .iter()
        .map(|e| {
            let s = ti(&m, mu0 * (1.0 + e));
            s.cycle.amplitude(1, 1).powi(2) / e
        })
        .collect();
    eprintln!("A²/ε: CHBM {chbm:?}, TI {tis:?}");
    for v in [&chbm, &tis] {
        // Normal form: A² = a ε (1 + b ε + ...); over ε = 1..4 % the ratio may drift by
        // O(ε) relative, a few per cent, while a subcritical or non-Hopf branch would not
        // give a constant ratio at all.
        let spread = (v[2] - v[0]).abs() / v[0];
        assert!(spread < 0.1, "A²/ε not constant: {v:?}");
    }
    for (a, b) in chbm.iter().zip(&tis) {
        // Same limit cycle by two methods: the 3-harmonic truncation and BDF at rtol 1e-10
        // agree in A² to 4e-5 here (measured; the motion is nearly harmonic, and the
        // remaining gap is the integrator's): asserted at 1e-3.
        assert!((a / b - 1.0).abs() < 1e-3, "CHBM {a} vs TI {b}");
    }
}

/// CHBM with 5 harmonics against the BDF reference at `mu`: the relative errors of the
/// cycle, aligned in phase on dof 1.
fn chbm_against_time_integration(m: &Model, mu: f64) -> squeal_chbm::cycle::RelativeErrors {
    let reference = ti(m, mu);
    let mb = ModalBrake::new(&m.brake, &m.reference, mu);
    let (s, ..) = solve_with_restarts(
        &mb,
        &start(m, mu),
        &{
            let mut o = ChbmOptions::default();
            o.harmonics = 5;
            o
        },
        &RESTART_AMPLITUDES,
    )
    .unwrap();
    assert_eq!(s.outcome, Outcome::LimitCycle);
    let mut c = s.cycle().unwrap();
    c.align_to(&reference.cycle, 1);
    relative_errors(&c, &reference.cycle, &[0, 1])
}

#[test]
fn chbm_matches_time_integration_on_the_two_dof_model() {
    let m = model(KL, KNL);
    let mu0 = hopf(&m);
    let mu = 1.001 * mu0;
    let e = chbm_against_time_integration(&m, mu);
    eprintln!("{e:?}");
    // Measured: about 8e-6 in displacement and velocity, 2e-9 in frequency (BDF5 at rtol
    // 1e-10; at 1e-8 the displacement error was 3.4e-4, the integrator's). Five harmonics
    // of a nearly harmonic cycle leave < 1e-6 of the motion out. Asserted with margin.
    assert!(e.displacement < 1e-4, "{e:?}");
    assert!(e.velocity < 1e-4, "{e:?}");
    assert!(e.frequency_relative.abs() < 1e-7, "{e:?}");
}

#[test]
fn equivalent_linearization_is_the_tangent_one_at_zero_amplitude() {
    let m = model(KL, KNL);
    let mu = 1.02 * hopf(&m);
    let st = start(&m, mu);
    let mb = ModalBrake::new(&m.brake, &m.reference, mu);
    let layout = HarmonicLayout::new(mb.nl(), 3).unwrap();
    let force = ContactForce::new(&mb);
    let x0: Vec<f64> = mb.nl_dofs.iter().map(|&d| st.equilibrium[d]).collect();
    let (k0, c0) = reference_jacobian(&force, &x0);
    for amplitude in [0.0, 1e-9] {
        // The equilibrium as a cycle, with (for the second case) a tiny first harmonic.
        let mut u = vec![0.0; layout.len()];
        for (i, &d) in mb.nl_dofs.iter().enumerate() {
            u[i] = st.equilibrium[d];
            if let Some(k) = layout.index(1, Part::Cos, i) {
                u[k] = amplitude * st.mode[d].re;
            }
        }
        let mut aft = Aft::new(layout, 32).unwrap();
        let mut f = vec![0.0; layout.len()];
        aft.forces(&force, &u, st.lambda.im, &mut f).unwrap();
        let df = DescribingFunction::new(&layout, &u, st.lambda.im, &f, &k0, &c0);
        let t = BrakeEigen::new(&mb, None)
            .track(&df.update(&k0, &c0), st.lambda * c64::new(1.0, 1e-4))
            .unwrap();
        // The stability analysis' eigenvalue comes from a dense eigensolver on the tangent
        // linearization; the tracked one from the describing function. At zero amplitude
        // the describing function is the tangent linearization exactly; at 1e-9 m the cubic
        // term changes it by 3 k_nl A²/4 ~ 1e-13 relative.
        assert!(
            (t.lambda - st.lambda).norm() < 1e-9 * st.lambda.norm(),
            "amplitude {amplitude}: {} vs {}",
            t.lambda,
            st.lambda
        );
    }
}

#[test]
fn analytic_jacobian_matches_finite_differences() {
    let m = model(KL, KNL);
    let mu = 1.05 * hopf(&m);
    let mb = ModalBrake::new(&m.brake, &m.reference, mu);
    let st = start(&m, mu);
    for h in [1, 3] {
        let (w1, w2) = check_jacobian(&mb, &st, &{
            let mut o = ChbmOptions::default();
            o.harmonics = h;
            o.amplitude = 0.5;
            o
        })
        .unwrap();
        // Central differences with relative steps 1e-6: truncation ~1e-12 and round-off
        // ~1e-16 / 1e-6 = 1e-10 relative to each row's scale, but the rows of the small
        // harmonics see the differences of large ones: measured 1.2e-6 (f1, H = 3) and
        // 5e-9 (f2). A wrong derivative term is O(1).
        assert!(
            w1 < 1e-5 && w2 < 1e-6,
            "H = {h}: f1 rows {w1:e}, f2 row {w2:e}"
        );
    }
}

#[test]
fn a_full_modal_damping_matrix_agrees_between_chbm_and_time_integration() {
    // Physical damping C = [[20, 8], [8, 30]] is not proportional: D = Φᵀ C Φ is a full
    // matrix, so the condensed stiffness, the eigenvalue tracking and the time integration
    // all take their dense paths. CHBM against BDF at rtol 1e-10 at 1.001 μ0.
    let mut m = model(KL, KNL);
    let c = faer::Mat::from_fn(2, 2, |i, j| [[20.0, 8.0], [8.0, 30.0]][i][j]);
    let phi = &m.reference.basis.phi;
    let d = phi.transpose() * &c * phi;
    assert!(d[(0, 1)].abs() > 1.0, "{d:?}");
    m.reference.damping = squeal_brake::ModalDamping::Full(d);
    let mu = 1.001 * hopf(&m);
    let e = chbm_against_time_integration(&m, mu);
    // As for the diagonal damping above (8e-6 measured there): the dense paths compute the
    // same quantities.
    assert!(e.displacement < 1e-4, "{e:?}");
    assert!(e.frequency_relative.abs() < 1e-7, "{e:?}");
}

#[test]
fn the_lyapunov_coefficient_predicts_the_supercritical_branch() {
    // Supercritical (l1 < 0): the normal form's first harmonic of the normal dof against
    // CHBM's at 0.05 % above μ0. The asymptote is exact to first order in ε = μ/μ0 - 1; the
    // CHBM ratio A²/ε drifts by 0.2 % from ε = 5e-4 to 2e-3 (the O(ε) term), so at 5e-4 the two
    // must agree to well under 1 %.
    let m = model(KL, KNL);
    let nf = normal_form_of(&m);
    assert_eq!(
        nf.criticality(),
        squeal_brake::criticality::Criticality::Supercritical
    );
    let mu = 1.0005 * nf.mu0;
    let x = nf.first_harmonic(mu).expect("a cycle above mu0");
    let phi = &m.reference.basis.phi;
    let predicted = (0..2).map(|j| x[j] * phi[(1, j)]).sum::<c64>().norm();
    let s = example::limit_cycle(&m.brake, &m.reference, mu, 5).unwrap();
    let measured = s.amplitude(1, 1);
    let reference = ti(&m, mu);
    let integrated = reference.cycle.amplitude(1, 1);
    eprintln!(
        "first harmonic of x1: normal form {predicted:e}, CHBM {measured:e}, BDF {integrated:e}"
    );
    assert!(
        (predicted / measured - 1.0).abs() < 1e-2,
        "{predicted} vs {measured}"
    );
    assert!(
        (predicted / integrated - 1.0).abs() < 1e-2,
        "{predicted} vs {integrated}"
    );
    let f = nf.omega_at(mu);
    assert!((f / s.omega - 1.0).abs() < 1e-5, "omega {f} vs {}", s.omega);
}

/// Integrates the oscillator at `mu` from its equilibrium plus `Re(X e^{iωt})` at t = 0 (the
/// normal form's first harmonic `X`, physical, times `factor`) for `periods` periods, and
/// returns the ratio of the closure's oscillation amplitude over the last five periods to
/// that over the first five.
fn envelope_ratio(
    m: &Model,
    nf: &squeal_brake::criticality::NormalForm,
    mu: f64,
    x: &[c64],
    factor: f64,
    periods: f64,
) -> f64 {
    use squeal_brake::dynamics::BrakeDynamics;
    use squeal_ode::{Atol, Bdf, BdfOptions};
    let eq = static_equilibrium(&m.brake, mu, None, &NewtonOptions::default()).unwrap();
    let mb = ModalBrake::new(&m.brake, &m.reference, mu);
    let w = nf.omega_at(mu);
    let x0: Vec<f64> = (0..2).map(|i| eq.x[i] + factor * x[i].re).collect();
    let v0: Vec<f64> = (0..2)
        .map(|i| factor * (c64::new(0.0, w) * x[i]).re)
        .collect();
    let y0 = BrakeDynamics::state_from_physical(&mb, &x0, &v0).unwrap();
    let sys = BrakeDynamics::new(&mb);
    let period = 2.0 * std::f64::consts::PI / w;
    let opts = {
        let mut o = BdfOptions::default();
        o.rtol = 1e-10;
        o.atol = Atol::Scalar(1e-16);
        o.max_order = 5;
        o
    };
    let mut bdf = Bdf::new(&sys, 0.0, &y0, periods * period, &opts).unwrap();
    let closure = |y: &[f64]| {
        let x = mb.physical(&y[..2]);
        x[1] - eq.x[1]
    };
    let (mut first, mut last) = (0.0f64, 0.0f64);
    let mut y = vec![0.0; 4];
    let mut t = 0.0;
    while !bdf.is_finished() {
        bdf.step().unwrap();
        while t <= bdf.t() {
            bdf.interpolate(t, &mut y).unwrap();
            let a = closure(&y).abs();
            if t < 5.0 * period {
                first = first.max(a);
            }
            if t > (periods - 5.0) * period {
                last = last.max(a);
            }
            t += period / 64.0;
        }
    }
    last / first
}

#[test]
fn the_lyapunov_coefficient_says_subcritical_and_time_integration_agrees() {
    // l1 > 0: the branch leaves μ0 to lower friction, where it is the threshold between
    // decay and growth (an unstable cycle). At μ = 0.998 μ0 the equilibrium is stable; started
    // at 0.7 of the normal form's cycle the motion decays, at 1.4 it grows. (The normal form's
    // amplitude is right to O(ε) = 0.2 %, far inside that margin.)
    let m = subcritical();
    let nf = normal_form_of(&m);
    assert_eq!(
        nf.criticality(),
        squeal_brake::criticality::Criticality::Subcritical
    );
    assert!(
        nf.radius_squared(1.001 * nf.mu0).is_none(),
        "no cycle above mu0"
    );
    let mu = 0.998 * nf.mu0;
    let xm = nf.first_harmonic(mu).expect("a cycle below mu0");
    let phi = &m.reference.basis.phi;
    let x: Vec<c64> = (0..2)
        .map(|i| (0..2).map(|j| xm[j] * phi[(i, j)]).sum())
        .collect();
    let decays = envelope_ratio(&m, &nf, mu, &x, 0.7, 300.0);
    let grows = envelope_ratio(&m, &nf, mu, &x, 1.4, 300.0);
    eprintln!("envelope ratio after 300 periods: 0.7 x cycle {decays:.3}, 1.4 x cycle {grows:.3}");
    assert!(decays < 0.9, "{decays}");
    assert!(grows > 1.1, "{grows}");
}

#[test]
fn the_shooting_reference_states_an_error_that_bounds_its_own() {
    // compare_at's reference (issue 22) on the 2-dof model at 1.01 μ0: the periodic orbit by
    // shooting at rtol 1e-10, its stated error the difference from the orbit at 1e-9. The
    // contact law is a polynomial, so CHBM converges spectrally: 10 and 20 harmonics agree to
    // 1e-14 (measured), CHBM 20H is exact far below the integrator, and its distance from the
    // reference is the reference's own error, which the stated error must bound.
    use squeal_chbm::compare::{CompareOptions, ReferenceStart, compare_at};
    let m = model(KL, KNL);
    let mu = 1.01 * hopf(&m);
    let mb = ModalBrake::new(&m.brake, &m.reference, mu);
    let opts = {
        let mut o = CompareOptions::default();
        o.harmonics = vec![3, 10, 20];
        o.rtols = vec![];
        o
    };
    let c = compare_at(&mb, &start(&m, mu), &opts).unwrap();
    assert_eq!(c.reference_start, ReferenceStart::Chbm(20));
    let r = &c.reference;
    let (h3, h20) = (&c.chbm[0].measures.all, &c.chbm[2].measures.all);
    eprintln!(
        "stated {:?}\nresiduals {:?} (check {:?})\nfloquet {:?}\nCHBM 3H {h3:?}\nCHBM 20H {h20:?}",
        r.all, r.reference.residuals, r.check.residuals, r.floquet
    );
    assert_eq!(c.chbm[2].solution.outcome, Outcome::LimitCycle);
    // The bound: CHBM 20H (exact here) is within the stated error of the reference, in
    // displacement, velocity and frequency; and the bound is sharp to a factor 10. Measured:
    // actual 3.67e-7 (displacement and velocity), 1.65e-8 Hz; stated 1.73e-6, 5.3e-8 Hz (4.7x,
    // 3.2x). (Stated before both solves had to take two Newton steps: 4.9e-8, below the
    // actual error: the check had stopped at its start.)
    assert!(
        h20.displacement <= r.all.displacement,
        "{h20:?} vs {:?}",
        r.all
    );
    assert!(h20.velocity <= r.all.velocity, "{h20:?} vs {:?}", r.all);
    assert!(
        h20.frequency_hz.abs() <= r.all.frequency_hz.abs(),
        "{h20:?} vs {:?}",
        r.all
    );
    assert!(
        r.all.displacement <= 10.0 * h20.displacement,
        "{h20:?} vs {:?}",
        r.all
    );
    // CHBM 3H is 2.6e-6 off (a nearly harmonic cycle): the reference's stated error is below
    // it, but not by the factor 10 the brake shows (tests/cli/compare_reference.rs of the squeal package).
    assert!(r.all.displacement < h3.displacement, "{h3:?}");
    // Newton converged: periodicity residual below the asked 300 rtol = 3e-8.
    assert!(
        r.reference.residual() <= 3e-8,
        "{:?}",
        r.reference.residuals
    );
    // The multiplier 1: M f = f along the orbit to the integration's accuracy (rtol 1e-10 over
    // one period; 1e-7 allows the global error's growth over the period).
    let f = r.floquet.unwrap();
    assert!(f.tangent_error < 1e-7, "{f:?}");
    assert!(
        f.leading < 1.0,
        "the cycle attracts above a supercritical Hopf point: {f:?}"
    );
}

#[test]
fn a_time_integration_that_does_not_settle_is_reported_as_failed() {
    // Ten periods are too few for a steady cycle: the run is kept, with its failure and no
    // measures, and the reference still starts from CHBM (exact outcomes, no tolerance).
    use squeal_chbm::compare::{CompareOptions, ReferenceStart, compare_at_with};
    let m = model(KL, KNL);
    let mu = 1.01 * hopf(&m);
    let mb = ModalBrake::new(&m.brake, &m.reference, mu);
    let opts = {
        let mut o = CompareOptions::default();
        o.harmonics = vec![3];
        o.ti = {
            let mut o = TiOptions::default();
            o.perturbation = 0.05;
            o.harmonics = 5;
            o.samples_per_cycle = 64;
            o.max_cycles = 10.0;
            o
        };
        o.rtols = vec![1e-6];
        o
    };
    // Every run `steps` lists is announced once, before it starts (exact; the integrations
    // run beside the CHBM solves, so the order depends on the threads: compared as sets).
    let announced = std::sync::Mutex::new(Vec::new());
    let c = compare_at_with(&mb, &start(&m, mu), &opts, &|s| {
        announced.lock().unwrap().push(s)
    })
    .unwrap();
    let key = |s: &squeal_chbm::compare::CompareStep| format!("{s}");
    let mut announced = announced.into_inner().unwrap();
    let mut expected = opts.steps();
    announced.sort_by_key(key);
    expected.sort_by_key(key);
    assert_eq!(announced, expected);
    assert_eq!(
        announced.len(),
        3,
        "one CHBM solve, one integration, the reference"
    );
    assert_eq!(c.reference_start, ReferenceStart::Chbm(3));
    let ti = &c.ti[0];
    assert!(ti.run.steady.is_none() && ti.run.failure.is_some());
    assert!(ti.measures.is_none() && ti.cycle.is_none());
}
