//! The sensitivities of the unstable eigenvalue and of μ0 ([`squeal_brake::sensitivity`]) on
//! the bundled coarse brake, against central finite differences of the full computation
//! ([`squeal_brake::sensitivity::recompute`]: the brake changed, its frictionless reference and
//! modal damping formed again, the equilibrium solved again, the eigenpair continued, the Hopf
//! point found again by Newton's method), extrapolated by Richardson from the steps h and 2h;
//! every parameter of the ranked table (the contact stiffness of all pairs and of each pair,
//! the piston load, each part's modulus and density, the damping of all modes and of each) in
//! its four rates (μ0, Re λ, Im λ, the frequency at the moved Hopf point), and the friction
//! coefficient's `dλ/dμ`; and the contributions' sums.
use super::common;

use faer::c64;
use squeal_brake::Brake;
use squeal_brake::continuation::converge;
use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::equilibrium::static_equilibrium;
use squeal_brake::linearized::LinearizedBrake;
use squeal_brake::sensitivity::{
    HopfState, Parameter, Sensitivities, damping_ratios, hopf_state, recompute,
};
use squeal_brake::spectrum::Reference;
use squeal_pipeline::stability::sensitivities::parameters;
use squeal_pipeline::stability::{analyse, contributions, threshold};
use std::f64::consts::TAU;

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

/// Central differences with step `h` of what a parameter moves: `λ` at the fixed μ0, μ0
/// itself and the frequency (Hz) at the moved Hopf point.
struct Central {
    dlambda: c64,
    dmu0: f64,
    dfrequency_hz: f64,
}

fn central(
    brake: &Brake,
    reference: &Reference,
    state: &HopfState,
    p: &Parameter,
    h: f64,
    newton: &NewtonOptions,
) -> Central {
    let zeta = damping_ratios(reference).unwrap();
    let opts = squeal_brake::continuation::EigenContinuationOptions::default();
    let at = |s: f64| {
        let (b, z) = changed(brake, &zeta, p, s);
        recompute(&b, &z, reference, state, newton, &opts).unwrap()
    };
    let (plus, minus) = (at(h), at(-h));
    let d = |a: f64, b: f64| (a - b) / (2.0 * h);
    Central {
        dlambda: (plus.0 - minus.0) / (2.0 * h),
        dmu0: d(plus.1.mu, minus.1.mu),
        dfrequency_hz: d(plus.1.pair.lambda.im, minus.1.pair.lambda.im) / TAU,
    }
}

/// Central differences with relative step `h` of `λ` in the friction coefficient at μ0
/// (`μ0 dλ/dμ`): the equilibrium solved again at `μ0 (1 ± h)`, the eigenpair continued.
fn central_friction(
    brake: &Brake,
    lr: &LinearizedBrake,
    state: &HopfState,
    h: f64,
    newton: &NewtonOptions,
) -> c64 {
    let opts = squeal_brake::continuation::EigenContinuationOptions::default();
    let at = |s: f64| {
        let mu = state.mu * (1.0 + s);
        let eq = static_equilibrium(brake, mu, Some(&state.equilibrium.x), newton).unwrap();
        let c = lr.coupling(brake, &eq);
        converge(lr, &c, &state.pair, &opts).unwrap().0.lambda
    };
    (at(h) - at(-h)) / (2.0 * h)
}

/// The reference a derivative is judged by: Richardson's extrapolation of the central
/// differences at steps h and 2h, `(4 FD(h) − FD(2h))/3`, whose truncation is O(h⁴) (1e-16
/// relative at h = 1e-4) against FD(h)'s O(h²).
fn richardson(fd: f64, fd2: f64) -> f64 {
    (4.0 * fd - fd2) / 3.0
}

/// The names of the four rates checked for each parameter.
const RATES: [&str; 4] = ["dmu0/ds", "dRe(lambda)/ds", "dIm(lambda)/ds", "df0/ds"];

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
    // Exact scalings: the whole mass times f scales λ by 1/√f at equal ratios ζ_j, every
    // stiffness and force times f (parts, contact, load) scales λ by √f with the equilibrium
    // unchanged; neither moves μ0. So the parts' densities' rates sum to zero, and so do the
    // parts' moduli, the contact stiffness and the load (round-off of rates ~0.1: 1e-12).
    let np = m.brake.pairs.len();
    let mu0 = |p: &Parameter| s.rate(p).dmu0.unwrap();
    let density =
        mu0(&Parameter::Density(m.layout.disc.clone())) + mu0(&Parameter::Density(m.layout.pad()));
    let stiffness = mu0(&Parameter::Stiffness(m.layout.disc.clone()))
        + mu0(&Parameter::Stiffness(m.layout.pad()))
        + mu0(&Parameter::ContactStiffness((0..np).collect()))
        + mu0(&Parameter::PistonLoad);
    eprintln!("scaling identities: densities {density:e}, stiffnesses and load {stiffness:e}");
    assert!(density.abs() < 1e-12 && stiffness.abs() < 1e-12);

    // The friction coefficient: dλ/dμ at μ0 (the rate of μ0 itself is not defined).
    let r = s.rate(&Parameter::Friction);
    let (fd, fd2) = (
        central_friction(&m.brake, &lr, &state, 1e-4, &newton),
        central_friction(&m.brake, &lr, &state, 2e-4, &newton),
    );
    let reference = c64::new(richardson(fd.re, fd2.re), richardson(fd.im, fd2.im));
    let (e_re, e_im) = (
        (r.dlambda.re - reference.re).abs() / reference.re.abs(),
        (r.dlambda.im - reference.im).abs() / reference.im.abs(),
    );
    eprintln!(
        "friction: mu0 dRe/dmu {:.8e} fd {:.8e} (rel {e_re:.1e}); mu0 dIm/dmu {:.8e} fd {:.8e} (rel {e_im:.1e})",
        r.dlambda.re, reference.re, r.dlambda.im, reference.im
    );
    assert!(e_re < 1e-5 && e_im < 1e-5, "friction: {r:?} vs {reference}");
    assert!((r.dfrequency_hz - r.dlambda.im / TAU).abs() <= 1e-12 * r.dfrequency_hz.abs());

    // Every row of the ranked table `squeal stability` writes: the contact stiffness of all
    // pairs and of each, the piston load, each part's modulus and density, the damping ratio
    // of every mode together and of each mode.
    let rows = parameters(m, &st);
    assert_eq!(rows.len(), 1 + np + 1 + 4 + 1 + lr.size());
    // Step 1e-4: truncation ~ h² (1e-8 relative, extrapolated away), the equilibria's
    // (1e-13) and eigenpairs' (residual 1e-12) errors over the step ~ 1e-9 of the rates'
    // scale.
    let checked: Vec<(String, [f64; 4], [f64; 4])> = rows
        .iter()
        .map(|(name, _, p)| {
            let r = s.rate(p);
            let f1 = central(&m.brake, &st.reference, &state, p, 1e-4, &newton);
            let f2 = central(&m.brake, &st.reference, &state, p, 2e-4, &newton);
            let analytic = [r.dmu0.unwrap(), r.dlambda.re, r.dlambda.im, r.dfrequency_hz];
            let reference = [
                richardson(f1.dmu0, f2.dmu0),
                richardson(f1.dlambda.re, f2.dlambda.re),
                richardson(f1.dlambda.im, f2.dlambda.im),
                richardson(f1.dfrequency_hz, f2.dfrequency_hz),
            ];
            (name.clone(), analytic, reference)
        })
        .collect();
    // Relative 1e-5 (the issue's), or, for a rate too small for that, 1e-9 of the largest
    // rate of its kind: a distant mode's damping moves λ by ȳ_j x_j, the product of two tiny
    // components that the eigenvectors' residual 1e-12 gives to about 1e-12 of the largest.
    let largest: [f64; 4] =
        std::array::from_fn(|k| checked.iter().map(|c| c.2[k].abs()).fold(0.0, f64::max));
    let mut floored = [0usize; 4];
    let mut worst = [0.0f64; 4];
    let mut small = [0.0f64; 4];
    for (name, analytic, reference) in &checked {
        for k in 0..4 {
            let err = (analytic[k] - reference[k]).abs();
            let relative = err / reference[k].abs();
            if relative >= 1e-5 {
                floored[k] += 1;
                small[k] = small[k].max(reference[k].abs() / largest[k]);
                assert!(
                    err <= 1e-9 * largest[k],
                    "{name}: {} {:e} vs {:e} (differences)",
                    RATES[k],
                    analytic[k],
                    reference[k]
                );
            } else {
                worst[k] = worst[k].max(relative);
            }
        }
        if reference[0].abs() > 1e-2 * largest[0] {
            let rel: Vec<String> = (0..4)
                .map(|k| {
                    let e = (analytic[k] - reference[k]).abs() / reference[k].abs();
                    format!(
                        "{} {:.8e} fd {:.8e} (rel {e:.1e})",
                        RATES[k], analytic[k], reference[k]
                    )
                })
                .collect();
            eprintln!("{name}: {}", rel.join("; "));
        }
    }
    for k in 0..4 {
        eprintln!(
            "{}: {} of {} parameters within relative 1e-5 (largest {:.1e}), {} small ones (at most {:.1e} of the largest) within 1e-9 of the largest {:.3e}",
            RATES[k],
            checked.len() - floored[k],
            checked.len(),
            worst[k],
            floored[k],
            small[k],
            largest[k]
        );
    }
    // Every rate of μ0 and of the frequency larger than 1e-4 of the largest is held to the
    // issue's relative 1e-5.
    for (name, analytic, reference) in &checked {
        for k in [0, 3] {
            if reference[k].abs() > 1e-4 * largest[k] {
                let e = (analytic[k] - reference[k]).abs() / reference[k].abs();
                assert!(e < 1e-5, "{name}: {} relative {e:e}", RATES[k]);
            }
        }
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
