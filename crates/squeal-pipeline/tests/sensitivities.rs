//! The sensitivities of the unstable eigenvalue and of μ0 ([`squeal_brake::sensitivity`]) on
//! the bundled coarse brake, against central finite differences of the full computation
//! ([`squeal_brake::sensitivity::recompute`]: the brake changed, its frictionless reference and
//! modal damping formed again, the equilibrium solved again, the eigenpair continued, the Hopf
//! point found again by Newton's method), and the contributions' sums.

mod common;

use faer::c64;
use squeal_brake::Brake;
use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::linearized::LinearizedBrake;
use squeal_brake::sensitivity::{
    HopfState, Parameter, Sensitivities, damping_ratios, hopf_state, recompute,
};
use squeal_brake::spectrum::Reference;
use squeal_pipeline::stability::{analyse, contributions, threshold};

/// The brake and the ratios with parameter `p` changed by the relative amount `s`.
fn changed(brake: &Brake, zeta: &[f64], p: &Parameter, s: f64) -> (Brake, Vec<f64>) {
    let mut b = brake.clone();
    let mut z = zeta.to_vec();
    let f = 1.0 + s;
    match p {
        Parameter::Friction => unreachable!("friction is checked apart"),
        Parameter::PistonLoad => b.f_piston.iter_mut().for_each(|v| *v *= f),
        Parameter::ContactStiffness(list) => {
            for &q in list {
                b.pairs[q].law = squeal_brake::contact::scaled(&b.pairs[q].law, f);
            }
        }
        Parameter::ModalDamping(list) => list.iter().for_each(|&j| z[j] *= f),
        Parameter::Stiffness(r) => {
            for i in r.clone() {
                for j in r.clone() {
                    b.k[(i, j)] *= f;
                }
            }
        }
        Parameter::Density(r) => {
            for i in r.clone() {
                for j in r.clone() {
                    b.m[(i, j)] *= f;
                }
            }
        }
    }
    (b, z)
}

/// Central differences of `(λ at μ0, μ0)` with step `h`.
fn central(
    brake: &Brake,
    reference: &Reference,
    state: &HopfState,
    p: &Parameter,
    h: f64,
    newton: &NewtonOptions,
) -> (c64, f64) {
    let zeta = damping_ratios(reference).unwrap();
    let opts = squeal_brake::continuation::EigenContinuationOptions::default();
    let at = |s: f64| {
        let (b, z) = changed(brake, &zeta, p, s);
        recompute(&b, &z, reference, state, newton, &opts).unwrap()
    };
    let (plus, minus) = (at(h), at(-h));
    (
        (plus.0 - minus.0) / (2.0 * h),
        (plus.1.mu - minus.1.mu) / (2.0 * h),
    )
}

#[test]
fn sensitivities_match_finite_differences_on_the_coarse_brake() {
    let c = common::coarse();
    let m = &c.model;
    let st = analyse(m, &common::mus(0.0, 1.0, 101)).unwrap();
    let h = st
        .sweep
        .hopf
        .as_ref()
        .expect("the coarse brake has a Hopf point");
    // Tight equilibria: the differences divide their error by the step.
    let newton = {
        let mut o = m.sweep.newton;
        o.tolerance = 1e-13;
        o
    };
    let lr = LinearizedBrake::new(&m.brake, &st.reference).unwrap();
    let tau = threshold(m, &st);
    let state = hopf_state(&m.brake, &lr, h, tau, &newton, &m.sweep.continuation).unwrap();
    assert!(
        (state.mu - h.mu0).abs() <= m.sweep.mu_tolerance,
        "polished {} vs swept {}",
        state.mu,
        h.mu0
    );
    let s = Sensitivities::new(&m.brake, &st.reference, &lr, &state).unwrap();
    let (m1, m2) = st.pair.expect("a coalescing pair");
    let np = m.brake.pairs.len();
    let params = [
        Parameter::ContactStiffness((0..np).collect()),
        Parameter::ContactStiffness(vec![0]),
        Parameter::PistonLoad,
        Parameter::Stiffness(m.layout.disc.clone()),
        Parameter::Stiffness(m.layout.pad()),
        Parameter::Density(m.layout.disc.clone()),
        Parameter::Density(m.layout.pad()),
        Parameter::ModalDamping((0..lr.size()).collect()),
        Parameter::ModalDamping(vec![m2]),
        Parameter::ModalDamping(vec![m1]),
    ];
    // Exact scalings: the whole mass times f scales λ by 1/√f at equal ratios ζ_j, every
    // stiffness and force times f (parts, contact, load) scales λ by √f with the equilibrium
    // unchanged; neither moves μ0. So the parts' densities' rates sum to zero, and so do the
    // parts' moduli, the contact stiffness and the load (round-off of rates ~0.1: 1e-12).
    let mu0 = |p: &Parameter| s.rate(p).dmu0.unwrap();
    let density = mu0(&params[5]) + mu0(&params[6]);
    let stiffness = mu0(&params[3]) + mu0(&params[4]) + mu0(&params[0]) + mu0(&params[2]);
    eprintln!("scaling identities: densities {density:e}, stiffnesses and load {stiffness:e}");
    assert!(density.abs() < 1e-12 && stiffness.abs() < 1e-12);
    for p in &params {
        let r = s.rate(p);
        let dmu0 = r.dmu0.unwrap();
        // Step 1e-4: truncation ~ h² (1e-8 relative), the equilibria's and eigenpairs'
        // round-off ~ 1e-15 / h (1e-11); the difference with twice the step shows the
        // differences' own error.
        let (dl, dm) = central(&m.brake, &st.reference, &state, p, 1e-4, &newton);
        let (dl2, dm2) = central(&m.brake, &st.reference, &state, p, 2e-4, &newton);
        let fd_err = (dm - dm2).abs() / dm.abs();
        let err_mu0 = (dmu0 - dm).abs() / dm.abs();
        let err_re = (r.dlambda.re - dl.re).abs() / dl.re.abs();
        let err_im = (r.dlambda.im - dl.im).abs() / dl.im.abs().max(dl.re.abs());
        eprintln!(
            "{p:?}: dmu0/ds {dmu0:.8e} fd {dm:.8e} (rel {err_mu0:.1e}, fd h/2h {fd_err:.1e}); dRe/ds {:.8e} fd {:.8e} (rel {err_re:.1e}); dIm/ds rel {err_im:.1e}; fd(2h) re {:.3e}",
            r.dlambda.re, dl.re, dl2.re
        );
        // Relative 1e-5, or three times the differences' own error where that is larger
        // (a parameter that barely moves μ0 has a difference dominated by round-off).
        let tol = 1e-5f64.max(3.0 * fd_err);
        assert!(err_mu0 < tol, "{p:?}: dmu0/ds {dmu0:e} vs {dm:e}");
        assert!(err_re < tol, "{p:?}: dRe/ds {} vs {}", r.dlambda.re, dl.re);
        assert!(err_im < tol, "{p:?}: dIm/ds {} vs {}", r.dlambda.im, dl.im);
    }
}

#[test]
fn contributions_sum_to_one_by_mode_by_part_and_by_reduced_coordinate() {
    let c = common::coarse();
    let m = &c.model;
    let st = analyse(m, &common::mus(0.0, 1.0, 101)).unwrap();
    let k = contributions::at_hopf(m, &st).expect("a Hopf point");
    // Sums of ~160 terms of order 1: round-off ~ 1e-14.
    let sum = |v: &[contributions::Contributor]| v.iter().map(|c| c.share).sum::<f64>();
    assert!((sum(&k.modes) - 1.0).abs() < 1e-13);
    assert!((sum(&k.reduced) - 1.0).abs() < 1e-13);
    let parts: f64 = k.parts.iter().map(|p| p.1).sum();
    assert!((parts - 1.0).abs() < 1e-13);
    // Each part's reduced coordinates sum to its kinetic-energy share, as the report's
    // `part_shares` computes it.
    let h = st.sweep.hopf.as_ref().unwrap();
    let x = h.point.spectrum.shape(&st.reference.basis, h.index);
    let shares = squeal_pipeline::stability::part_shares(m, &x);
    for (name, share) in &k.parts {
        let own: f64 = k
            .reduced
            .iter()
            .filter(|c| c.part == *name)
            .map(|c| c.share)
            .sum();
        let reference = shares.iter().find(|s| s.0 == *name).unwrap().1;
        assert!(
            (own - share).abs() < 1e-13 && (share - reference).abs() < 1e-12,
            "{name}: {own} {share} {reference}"
        );
    }
    // The first frictionless contributor is one of the coalescing pair.
    let (m1, m2) = st.pair.unwrap();
    let first: usize = k.modes[0].name[5..].parse().unwrap();
    assert!(
        first == m1 + 1 || first == m2 + 1,
        "first contributor {first}, pair {} {}",
        m1 + 1,
        m2 + 1
    );
}
