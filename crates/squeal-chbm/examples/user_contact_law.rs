//! A contact law written by the user: Kelvin–Voigt contact (a spring and a dashpot along the
//! normal) with Coulomb friction, plugged into the friction system, and its Hopf point checked
//! against Hurwitz's criterion.
//!
//! The law. While closed (`δ > 0`), `F_n = k_l δ + c_n δ'` and `F_t = μ F_n`; open, both are
//! zero. A law answers, at the pair's state `(δ, δ', v)` and friction level μ, the two forces
//! and their derivatives `[∂/∂δ, ∂/∂δ', ∂/∂v]` (`squeal_brake::contact::Response`): here
//! `∂F_n = [k_l, c_n, 0]`, `∂F_t = μ ∂F_n`, and `∂F_t/∂μ = F_n`. It says it reads `δ'`
//! (`uses_penetration_rate`), so the linearization gains the damping `∂F/∂x'` (eq 19's
//! counterpart for velocities). Nothing else changes: equilibrium, sweep, Hopf refinement,
//! CHBM and time integration all call the law through the same trait.
//!
//! The closed form. The oscillator of `friction_oscillator.rs` (`M = I`, `C = c I`,
//! `K = [[k11, k12], [k12, k22]]`, the pair along `g = e1`, friction along `h = -e0`) with this
//! linear law is linear while closed: with `(g + μ h) gᵀ` the matrix whose column 1 is
//! `(-μ, 1)`, the linearization is exactly
//!
//! `K_eff = [[k11, k12 - μ k_l], [k12, k22 + k_l]]`, `C_eff = [[c, -μ c_n], [0, c + c_n]]`,
//!
//! and `det(λ² I + λ C_eff + K_eff) = λ⁴ + a3 λ³ + a2 λ² + a1 λ + a0` with
//! `a3 = 2c + c_n`, `a2 = k11 + k22 + k_l + c (c + c_n)`,
//! `a1 = c (k22 + k_l) + (c + c_n) k11 + μ c_n k12`, `a0 = k11 (k22 + k_l) - k12 (k12 - μ k_l)`.
//! Hurwitz: all roots are in the left half-plane iff every `a_i > 0` and
//! `Δ3 = a3 a2 a1 - a1² - a3² a0 > 0`; a pair crosses the imaginary axis where `Δ3 = 0`, at
//! `ω0² = a1 / a3`. The root of `Δ3(μ)` by bisection is the reference for μ0 — polynomial
//! arithmetic, independent of the sweep's eigensolvers.
//!
//! Run: `cargo run --release -p squeal-chbm --example user_contact_law`.

use faer::Mat;
use squeal_brake::contact::{ContactLaw, Kinematics, Parameter, Response};
use squeal_chbm::{Contact, FrictionSystem, SystemError};

const C: f64 = 20.0;
const K: [[f64; 2]; 2] = [[1.0e6, 1.0e5], [1.0e5, 1.0e6]];
const KL: f64 = 3.0e5;

/// Kelvin–Voigt contact with Coulomb friction.
#[derive(Debug)]
pub struct KelvinVoigt {
    /// `k_l` (N/m).
    pub stiffness: f64,
    /// `c_n` (N s/m).
    pub damping: f64,
}

impl ContactLaw for KelvinVoigt {
    fn response(&self, mu: f64, s: &Kinematics) -> Response {
        if s.penetration <= 0.0 {
            return Response::default();
        }
        let f = self.stiffness * s.penetration + self.damping * s.penetration_rate;
        let d = [self.stiffness, self.damping, 0.0];
        Response {
            normal: f,
            tangential: mu * f,
            normal_derivatives: d,
            tangential_derivatives: d.map(|x| mu * x),
            tangential_mu: f,
        }
    }

    fn uses_penetration_rate(&self) -> bool {
        true
    }

    fn name(&self) -> String {
        "Kelvin-Voigt contact, Coulomb friction".into()
    }

    fn parameters(&self) -> Vec<Parameter> {
        vec![
            ("k_l", self.stiffness, "N/m"),
            ("c_n", self.damping, "N s/m"),
        ]
    }
}

/// The Hopf point (μ0, frequency in Hz) with contact damping `c_n` (N s/m).
pub fn run(c_n: f64) -> Result<(f64, f64), SystemError> {
    let law = KelvinVoigt {
        stiffness: KL,
        damping: c_n,
    };
    let pair = Contact::new(&[(1, 1.0)], &[(0, -1.0)], law).initial_gap(-2.0e-4);
    let m = Mat::<f64>::identity(2, 2);
    let c = Mat::from_fn(2, 2, |i, j| if i == j { C } else { 0.0 });
    let system = FrictionSystem::builder(m, c, Mat::from_fn(2, 2, |i, j| K[i][j]))
        .contact(pair)
        .build()?;
    let h = system.hopf()?;
    Ok((h.mu0, h.frequency_hz))
}

/// Hurwitz's `Δ3(μ)` and `ω² = a1/a3` of the module documentation.
pub fn hurwitz(mu: f64, c_n: f64) -> (f64, f64) {
    let ([k11, k12], k22) = (K[0], K[1][1]);
    let a3 = 2.0 * C + c_n;
    let a2 = k11 + k22 + KL + C * (C + c_n);
    let a1 = C * (k22 + KL) + (C + c_n) * k11 + mu * c_n * k12;
    let a0 = k11 * (k22 + KL) - k12 * (k12 - mu * KL);
    (a3 * a2 * a1 - a1 * a1 - a3 * a3 * a0, a1 / a3)
}

/// The root of `Δ3` in `[0, 2]` by bisection, and the frequency (Hz) there.
pub fn hurwitz_hopf(c_n: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (0.0, 2.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if hurwitz(mid, c_n).0 > 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    let mu = 0.5 * (lo + hi);
    (mu, hurwitz(mu, c_n).1.sqrt() / (2.0 * std::f64::consts::PI))
}

#[allow(dead_code)]
fn main() -> Result<(), SystemError> {
    println!(
        "{:>8} {:>14} {:>14} {:>12}",
        "c_n", "mu0", "Hurwitz", "f0 (Hz)"
    );
    for c_n in [0.0, 20.0, 50.0] {
        let (mu0, f0) = run(c_n)?;
        println!(
            "{c_n:>8} {mu0:>14.10} {:>14.10} {f0:>12.6}",
            hurwitz_hopf(c_n).0
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_users_law_gives_the_hurwitz_hopf_point() {
        for c_n in [0.0, 50.0] {
            let (mu0, f0) = run(c_n).unwrap();
            let (exact, f_exact) = hurwitz_hopf(c_n);
            // The sweep refines μ0 to a bracket of 1e-8 (SweepOptions::mu_tolerance); the
            // threshold 64 ε ω_max shifts the root by ~1e-12; bisection on Δ3 is exact to
            // round-off of a polynomial of size ~1e18 (relative 1e-15).
            assert!(
                (mu0 - exact).abs() < 2e-8,
                "c_n {c_n}: mu0 {mu0} vs {exact}"
            );
            // The frequency at the refined μ0, ~1e-8 off in μ: dω/dμ ~ 1e5 rad/s per unit μ at
            // most here, so 1e-6 relative.
            assert!((f0 / f_exact - 1.0).abs() < 1e-6, "f0 {f0} vs {f_exact}");
        }
    }
}
