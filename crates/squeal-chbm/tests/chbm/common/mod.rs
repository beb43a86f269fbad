//! The 2-dof friction oscillator built by hand (`oscillator.rs`) and the independent
//! references the tests share (Hopf point by bisection, normal form, the subcritical variant).
#![allow(dead_code)]

pub mod belt;
pub mod oscillator;

use oscillator::{KL, KNL, band, brake, frictionless};
use squeal_brake::Brake;
use squeal_brake::equilibrium::{NewtonOptions, static_equilibrium};
use squeal_brake::spectrum::{Reference, spectrum};
use squeal_chbm::ChbmStart;
use squeal_chbm::start::start_at;

pub struct Model {
    pub brake: Brake,
    pub reference: Reference,
}

pub fn model(k_linear: f64, k_cubic: f64) -> Model {
    let b = brake(k_linear, k_cubic);
    let reference = frictionless(&b);
    Model {
        brake: b,
        reference,
    }
}

/// Largest real part of the linearization at the equilibrium at μ.
pub fn growth(m: &Model, mu: f64) -> f64 {
    let eq = static_equilibrium(&m.brake, mu, None, &NewtonOptions::default()).unwrap();
    let sp = spectrum(&m.brake, &m.reference, &eq).unwrap();
    sp.values
        .iter()
        .map(|v| v.re)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// μ0 by bisection on the largest real part (independent of the sweep code).
pub fn hopf(m: &Model) -> f64 {
    let (mut lo, mut hi) = (0.0, 5.0);
    assert!(growth(m, lo) < 0.0 && growth(m, hi) > 0.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if growth(m, mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The Hopf normal form of the oscillator with contact stiffnesses `(kl, knl)`.
pub fn normal_form_of(m: &Model) -> squeal_brake::criticality::NormalForm {
    let mu0 = hopf(m);
    let eq = static_equilibrium(&m.brake, mu0, None, &NewtonOptions::default()).unwrap();
    let sp = spectrum(&m.brake, &m.reference, &eq).unwrap();
    let guess = sp
        .values
        .iter()
        .copied()
        .max_by(|a, b| a.re.total_cmp(&b.re))
        .unwrap();
    squeal_brake::criticality::normal_form(
        &m.brake,
        &m.reference,
        mu0,
        guess,
        &NewtonOptions::default(),
    )
    .unwrap()
}

/// The subcritical variant: K = [[1e6, 2e5], [2e5, 8e5]] (l1 = +8.4, μ0 = 0.665).
pub fn subcritical() -> Model {
    let mut b = brake(KL, KNL);
    b.k = faer::Mat::from_fn(2, 2, |i, j| [[1.0e6, 2.0e5], [2.0e5, 0.8e6]][i][j]);
    let reference = frictionless(&b);
    Model {
        brake: b,
        reference,
    }
}

/// Where CHBM starts at μ (the unstable mode of largest growth).
pub fn start(m: &Model, mu: f64) -> ChbmStart {
    start_at(
        &m.brake,
        &m.reference,
        mu,
        &band(),
        &NewtonOptions::default(),
        None,
    )
    .unwrap()
}
