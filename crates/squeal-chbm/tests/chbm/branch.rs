//! Branches of limit cycles and their Floquet stability on the 2-dof friction oscillator
//! (`tests/chbm/common/oscillator.rs`), each checked against something independent: the
//! normal form at the Hopf point, CHBM at a branch point's friction, BDF time integration of the
//! full equations on either side of the fold, and two Floquet methods (Hill's and the monodromy
//! matrix) against each other and against Liouville's formula.

use super::common;

use common::oscillator::{KL, KNL};
use common::{Model, model, normal_form_of, subcritical};
use faer::c64;
use squeal_brake::criticality::NormalForm;
use squeal_brake::dynamics::BrakeDynamics;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::bifurcation::{
    BifurcationKind, bifurcations, cycle_of, follow_from_hopf_with_hill, hill_along,
};
use squeal_chbm::branch::{
    BranchOptions, BranchPoint, Harmonics, LimitCycleBranch, cycles_at, follow_from_hopf,
    full_cycle,
};
use squeal_chbm::floquet::{CycleStability, HillOptions, MonodromyOptions, hill, monodromy};
use squeal_hbm::HarmonicLayout;

fn branch(m: &Model, harmonics: Harmonics) -> (NormalForm, ModalBrake, LimitCycleBranch) {
    let nf = normal_form_of(m);
    let mb = ModalBrake::new(&m.brake, &m.reference, nf.mu0);
    let opts = {
        let mut o = BranchOptions::default();
        o.harmonics = harmonics;
        o.range = (0.3, 1.5);
        o
    };
    let b = follow_from_hopf(&mb, &nf, &opts).unwrap();
    (nf, mb, b)
}

fn with_mu(mb: &ModalBrake, mu: f64) -> ModalBrake {
    let mut m = mb.clone();
    m.mu = mu;
    m
}

/// The cycle of `p` (all dofs nonlinear on this oscillator) at phase 0: displacement and
/// velocity, physical.
/// BDF (rtol 1e-10) of the full equations at `mu` from the modal state `y0` for `periods`
/// periods of `omega`: the peak-to-peak of dof 1 over the last five periods, and the final
/// modal state (the modal basis is the frictionless one at every μ).
fn settle(m: &Model, mu: f64, y0: &[f64], omega: f64, periods: f64) -> (f64, Vec<f64>) {
    use squeal_ode::{Atol, Bdf, BdfOptions};
    let mb = ModalBrake::new(&m.brake, &m.reference, mu);
    let sys = BrakeDynamics::new(&mb);
    let period = 2.0 * std::f64::consts::PI / omega;
    let opts = {
        let mut o = BdfOptions::default();
        o.rtol = 1e-9;
        o.atol = Atol::Scalar(1e-12);
        o.max_order = 5;
        o
    };
    let mut bdf = Bdf::new(&sys, 0.0, y0, periods * period, &opts).unwrap();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut y = vec![0.0; 4];
    let mut t = (periods - 5.0) * period;
    while !bdf.is_finished() {
        bdf.step().unwrap();
        while t <= bdf.t() {
            bdf.interpolate(t, &mut y).unwrap();
            let x1 = mb.physical(&y[..2])[1];
            lo = lo.min(x1);
            hi = hi.max(x1);
            t += period / 256.0;
        }
    }
    bdf.interpolate(periods * period, &mut y).unwrap();
    (hi - lo, y)
}

/// The modal state at phase 0 of the cycle of `p` (every dof of the oscillator is nonlinear).
fn cycle_state(mb: &ModalBrake, p: &BranchPoint) -> Vec<f64> {
    assert_eq!(mb.nl(), 2, "every dof of the oscillator is nonlinear");
    let layout = HarmonicLayout::new(2, p.harmonics).unwrap();
    let (mut x, mut v) = (vec![0.0; 2], vec![0.0; 2]);
    layout.displacement_at(&p.nl_coeffs, 0.0, &mut x).unwrap();
    layout
        .velocity_at(&p.nl_coeffs, p.omega, 0.0, &mut v)
        .unwrap();
    let (mut xp, mut vp) = (vec![0.0; 2], vec![0.0; 2]);
    for (k, &d) in mb.nl_dofs.iter().enumerate() {
        xp[d] = x[k];
        vp[d] = v[k];
    }
    BrakeDynamics::state_from_physical(mb, &xp, &vp).unwrap()
}

#[test]
fn the_subcritical_branch_starts_on_the_normal_form_below_mu0() {
    // l1 > 0: the cycles born at μ0 exist below it. The first computed cycle, at 1e-4 from μ0,
    // against the normal form's first harmonic (an O(ε) asymptote; measured: closure 2.4e-4,
    // frequency 9e-9 relative).
    let m = subcritical();
    let (nf, _, b) = branch(&m, BranchOptions::default().harmonics);
    assert!(nf.l1 > 0.0, "{}", nf.l1);
    let p0 = &b.points[0];
    assert!(p0.parameter < nf.mu0);
    let xm = nf.first_harmonic(p0.parameter).unwrap();
    let phi = &m.reference.basis.phi;
    let x1: c64 = (0..2).map(|j| xm[j] * phi[(1, j)]).sum();
    let closure = p0.loudest().1;
    assert!(
        (closure / (2.0 * x1.norm()) - 1.0).abs() < 1e-3,
        "{closure} vs {}",
        2.0 * x1.norm()
    );
    assert!((p0.omega / nf.omega_at(p0.parameter) - 1.0).abs() < 1e-7);
    assert_eq!(p0.largest_open_fraction(), 0.0, "small cycles keep contact");
}

#[test]
fn the_fold_is_where_time_integration_loses_the_stable_cycle() {
    // The branch (15 harmonics; the fold moves by 5e-6 μ0 from 7 to 25 harmonics) turns at
    // μ_fold ≈ 0.98882 μ0, where the contact starts to open. BDF of the full equations: the
    // cycle grown from a small disturbance at 1.01 μ0 is carried down in μ (400 periods per
    // step, each from the last state); it survives 3e-4 μ0 above the fold, where the
    // equilibrium is stable too (hysteresis), and collapses onto the equilibrium 3e-4 μ0 below.
    // (Measured: alive at 0.9890, gone at 0.9885 μ0.)
    let m = subcritical();
    let (nf, mb, b) = branch(&m, Harmonics::Fixed(15));
    let fold = b.folds[0].parameter / nf.mu0;
    assert!((0.985..0.995).contains(&fold), "{fold}");
    let omega = b.points[0].omega;
    let (grown, mut y) = settle(
        &m,
        1.01 * nf.mu0,
        &cycle_state(&mb, &b.points[0]),
        omega,
        1500.0,
    );
    assert!(grown > 1e-4, "the cycle at 1.01 mu0 reached {grown:e}");
    for r in [0.995, 0.992, 0.990, fold + 3e-4] {
        let (a, yn) = settle(&m, r * nf.mu0, &y, omega, 400.0);
        assert!(a > 1e-4, "the stable cycle at {r} mu0 was lost ({a:e})");
        y = yn;
    }
    let (a, _) = settle(&m, (fold - 3e-4) * nf.mu0, &y, omega, 400.0);
    assert!(a < 1e-8, "below the fold the motion decays ({a:e})");
}

#[test]
fn hill_finds_the_fold_and_the_stable_part_of_the_branch() {
    // Unstable from μ0 to the fold (one real multiplier > 1), stable after it up to the second
    // fold, where a real multiplier leaves through +1 again: both stability changes are folds,
    // at the continuation's folds (first: between two points at a nonsmooth turn, measured
    // 1.9e-4 μ0 apart; second: refined, 3.6e-5).
    let m = subcritical();
    let (nf, mb, b) = branch(&m, BranchOptions::default().harmonics);
    let fl = hill_along(&mb, &b, None, &HillOptions::default());
    let first = b.folds[0].after_point;
    for (i, f) in fl.iter().enumerate().take(b.folds[1].after_point) {
        let f = f.as_ref().unwrap();
        let expected = if i <= first {
            CycleStability::Unstable
        } else {
            CycleStability::Stable
        };
        // Marginal: within Hill's own error of zero (with few harmonics and open contact).
        assert!(
            f.stability() == expected || f.stability() == CycleStability::Marginal,
            "point {i}: {} ({:?})",
            f.stability(),
            f.leading()
        );
    }
    let bi = bifurcations(&b, &fl);
    assert!(bi.len() >= 2, "{bi:?}");
    for (k, tol) in [(0, 5e-4), (1, 1e-4)] {
        assert_eq!(bi[k].kind, BifurcationKind::Fold, "{:?}", bi[k]);
        assert_eq!(bi[k].after_point, b.folds[k].after_point);
        assert!(
            (bi[k].parameter - b.folds[k].parameter).abs() < tol * nf.mu0,
            "{:?} vs {:?}",
            bi[k],
            b.folds[k]
        );
    }
}

#[test]
fn hill_alongside_the_continuation_gives_the_same_bits_as_after_it() {
    // The overlapped analysis hands each point to another thread as the continuation accepts
    // it: the same branch and exponents as the continuation then `hill_along`, with one thread
    // (the tasks wait for the continuation) and with two.
    let m = subcritical();
    let (nf, mb, b) = branch(&m, BranchOptions::default().harmonics);
    let opts = {
        let mut o = BranchOptions::default();
        o.range = (0.3, 1.5);
        o
    };
    let hill = HillOptions::default();
    let after = hill_along(&mb, &b, None, &hill);
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let o = pool.install(|| follow_from_hopf_with_hill(&mb, &nf, &opts, &hill).unwrap());
        assert_eq!(o.branch.points, b.points, "{threads} threads");
        assert_eq!(o.floquet.len(), after.len());
        for (i, (a, c)) in o.floquet.iter().zip(&after).enumerate() {
            let (a, c) = (a.as_ref().unwrap(), c.as_ref().unwrap());
            assert_eq!(a.exponents, c.exponents, "point {i}, {threads} threads");
        }
    }
}

#[test]
fn hill_and_the_monodromy_matrix_agree_within_hills_error() {
    let m = subcritical();
    let (_, mb, b) = branch(&m, BranchOptions::default().harmonics);
    // Closed contact (a smooth cycle): agreement to the BDF's error (measured 3.6e-7), and
    // Liouville's formula, the sum of all exponents = -tr D (measured 5.5e-8 relative).
    let p = &b.points[5];
    assert_eq!(p.largest_open_fraction(), 0.0);
    let mbp = with_mu(&mb, p.parameter);
    let c = cycle_of(&mb, p, None).unwrap();
    let mono = monodromy(&mbp, &c, &MonodromyOptions::default()).unwrap();
    let trace = mb.damping.trace();
    let sum: f64 = mono.exponents.iter().map(|e| e.sigma.re).sum();
    assert!((sum + trace).abs() < 1e-6 * trace, "{sum} vs -{trace}");
    let hf = hill(&mbp, &c, &{
        let mut o = HillOptions::default();
        o.harmonics = Some(2 * p.harmonics);
        o
    })
    .unwrap();
    let (h, mo) = (hf.leading().unwrap().sigma, mono.leading().unwrap().sigma);
    assert!((h - mo).norm() < 1e-5 * mo.norm(), "{h} vs {mo}");
    // Open contact 34% of the period: the Jacobian jumps, Hill converges like 1/H and its
    // trivial exponent's distance from zero bounds its error at every H (measured |Δσ| 1.9,
    // 0.65, 0.018 against bounds 4.5, 1.6, 0.032 at 5, 10, 20 harmonics).
    let p = &b.points[20];
    assert!(p.largest_open_fraction() > 0.3);
    let mbp = with_mu(&mb, p.parameter);
    let c = cycle_of(&mb, p, None).unwrap();
    let mono = monodromy(&mbp, &c, &MonodromyOptions::default()).unwrap();
    let sum: f64 = mono.exponents.iter().map(|e| e.sigma.re).sum();
    assert!((sum + trace).abs() < 1e-6 * trace, "{sum} vs -{trace}");
    let mo = mono.leading().unwrap().sigma;
    let mut last = f64::INFINITY;
    for h in [p.harmonics, 2 * p.harmonics, 4 * p.harmonics] {
        let hf = hill(&mbp, &c, &{
            let mut o = HillOptions::default();
            o.harmonics = Some(h);
            o
        })
        .unwrap();
        let d = (hf.leading().unwrap().sigma - mo).norm();
        assert!(d <= hf.trivial_error, "H {h}: {d} > {}", hf.trivial_error);
        assert!(d < last, "H {h}: {d} did not improve on {last}");
        last = d;
    }
}

#[test]
fn a_supercritical_branch_point_is_the_cycle_chbm_finds_there() {
    // l1 < 0: the branch leaves μ0 upwards. Its cycle at 1.005 μ0 (corrected from the two
    // points around it with μ fixed) is the one CHBM (the
    // constrained Levenberg-Marquardt solve from the unstable mode, another algorithm on the
    // same 5-harmonic equations) finds the same cycle: measured 8.6e-13 in ω, 1.3e-11 in the
    // first harmonic of the normal dof.
    let m = model(KL, KNL);
    let (nf, mb, b) = branch(&m, Harmonics::Fixed(5));
    assert!(nf.l1 < 0.0 && b.points[0].parameter > nf.mu0);
    let opts = {
        let mut o = BranchOptions::default();
        o.harmonics = Harmonics::Fixed(5);
        o
    };
    let at = cycles_at(&mb, &b, 1.005 * nf.mu0, &opts).unwrap();
    // The branch grows to 1.0143 mu0 and folds back when the contact opens: it crosses 1.005
    // mu0 before its first fold and again after it (and once more further along).
    assert!(at.len() >= 2 && at[0].0 < b.folds[0].after_point && at[1].0 >= b.folds[0].after_point);
    let p = &at[0].1;
    assert_eq!(p.parameter, 1.005 * nf.mu0);
    let mbp = ModalBrake::new(&m.brake, &m.reference, p.parameter);
    let (s, ..) = squeal_chbm::solve_with_restarts(
        &mbp,
        &common::start(&m, p.parameter),
        &{
            let mut o = squeal_chbm::ChbmOptions::default();
            o.harmonics = 5;
            o
        },
        &squeal_chbm::RESTART_AMPLITUDES,
    )
    .unwrap();
    assert_eq!(s.outcome, squeal_chbm::Outcome::LimitCycle);
    assert!((s.omega / p.omega - 1.0).abs() < 1e-8);
    let layout = HarmonicLayout::new(2, 5).unwrap();
    let k = mb.nl_dofs.iter().position(|&d| d == 1).unwrap();
    let a = layout.amplitude(&p.nl_coeffs, 1, k).unwrap();
    assert!(
        (s.amplitude(1, 1) / a - 1.0).abs() < 1e-8,
        "{} vs {a}",
        s.amplitude(1, 1)
    );
}

#[test]
fn full_cycle_recovers_the_nonlinear_dofs_of_a_branch_point() {
    // Eq (35) applied to the harmonic balance's own force returns, on the nonlinear dofs, the
    // coefficients the branch converged (an identity at a harmonic balance root, to its
    // residual); on the oscillator every dof is nonlinear, so all of them are checked.
    let m = subcritical();
    let (_, mb, b) = branch(&m, BranchOptions::default().harmonics);
    for idx in [5, 20] {
        let p = &b.points[idx];
        let full = full_cycle(&mb, p, None).unwrap();
        let scale = p.nl_coeffs.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let nn = mb.nl();
        for blk in 0..2 * p.harmonics + 1 {
            for (i, &d) in mb.nl_dofs.iter().enumerate() {
                let (r, u) = (full[blk * mb.modes() + d], p.nl_coeffs[blk * nn + i]);
                assert!(
                    (r - u).abs() < 1e-8 * scale,
                    "point {idx} block {blk} dof {d}: {r} vs {u}"
                );
            }
        }
    }
}
