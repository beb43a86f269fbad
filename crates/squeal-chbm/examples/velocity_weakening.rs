//! Friction that falls with the sliding speed destabilizes a pad with no mode coupling at all:
//! the library's velocity-dependent law and its closed-form Hopf point.
//!
//! The law (`squeal_brake::contact::VelocityDependent`): penalty contact `F_n = k_l δ` and
//! `F_t = μ s(v) F_n` with `s(v) = r + (1 - r)(1 - e^(-v/v0))`: the coefficient is `r μ` at rest
//! and `μ` at high sliding speed `v`. For `r > 1` it falls with speed (Stribeck).
//!
//! The system. A pad on a rigid disc: `x0` tangential (spring `k_t`, damper `c`), `x1` normal
//! (spring `k_n`, damper `c`), unit masses. The pair closes when the pad moves down (`δ = -x1`,
//! `g = -e1`); the disc's surface slides along `s = -e0` at speed `V`, so `h = -s = e0` on the
//! pad's dof and the slip velocity is `v = V + x0'`. A load `L` presses the pad on the disc;
//! the contact carries `N = L k_l / (k_l + k_n)`, the rest goes through `k_n`.
//!
//! Linearized about the steady sliding state, the friction force `F_t h` on the left of the
//! equations of motion is to first order `μ s(V) N + μ s'(V) N x0'` on `x0`: a damping
//! `μ s'(V) N` added to `c`. The normal dof does not feel the tangential one (`∂F_n/∂x0 = 0`), so the
//! tangential mode is unstable exactly when `c + μ s'(V) N < 0`, with
//! `s'(V) = -(r - 1) e^(-V/v0) / v0`: the Hopf point is
//!
//! `μ* = c v0 e^(V/v0) / ((r - 1) N)`, at the frequency `sqrt(k_t) / 2π`.
//!
//! No coalescence of modes is needed: this is the "negative damping" mechanism of squeal, the
//! other one besides the paper's mode coupling.
//!
//! Run: `cargo run --release -p squeal-chbm --example velocity_weakening`.

use faer::Mat;
use squeal_brake::contact::VelocityDependent;
use squeal_chbm::{Contact, FrictionSystem, SystemError};

// Damping c (N s/m), stiffnesses k_t, k_n, k_l (N/m), load L (N), r = μ_s/μ_d, v0 (m/s).
const C: f64 = 4.0;
const KT: f64 = 4.0e6;
const KN: f64 = 1.0e7;
const KL: f64 = 2.0e7;
const LOAD: f64 = 500.0;
const R: f64 = 1.6;
const V0: f64 = 0.5;

/// The Hopf point (μ0, frequency in Hz) at disc surface speed `speed` (m/s).
pub fn run(speed: f64) -> Result<(f64, f64), SystemError> {
    let law = VelocityDependent {
        k_linear: KL,
        k_cubic: 0.0,
        static_ratio: R,
        decay_speed: V0,
    };
    let pair = Contact::new(&[(1, -1.0)], &[(0, 1.0)], law).surface_speed(speed);
    let m = Mat::<f64>::identity(2, 2);
    let c = Mat::from_fn(2, 2, |i, j| if i == j { C } else { 0.0 });
    let k = Mat::from_fn(2, 2, |i, j| [[KT, 0.0], [0.0, KN]][i][j]);
    let mut system = FrictionSystem::builder(m, c, k)
        .contact(pair)
        .load(vec![0.0, -LOAD])
        .build()?;
    system.settings.sweep.mu_tolerance = 1e-14;
    let h = system.hopf()?;
    Ok((h.mu0, h.frequency_hz))
}

/// `μ*` of the module documentation.
pub fn closed_form(speed: f64) -> f64 {
    let normal_force = LOAD * KL / (KL + KN);
    C * V0 * (speed / V0).exp() / ((R - 1.0) * normal_force)
}

#[allow(dead_code)]
fn main() -> Result<(), SystemError> {
    println!(
        "{:>8} {:>14} {:>14} {:>10}",
        "V (m/s)", "mu0", "closed form", "f0 (Hz)"
    );
    for speed in [0.2, 0.4, 0.8] {
        let (mu0, f0) = run(speed)?;
        println!(
            "{speed:>8} {mu0:>14.10} {:>14.10} {f0:>10.4}",
            closed_form(speed)
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hopf_point_is_the_closed_form_one() {
        for speed in [0.4, 0.8] {
            let (mu0, f0) = run(speed).unwrap();
            let exact = closed_form(speed);
            // The Newton refinement closes the bracket to 1e-14 (absolute, μ* ~ 0.02-0.06);
            // the instability threshold 64 ε ω_max shifts the root by ~1e-14 relative; the
            // derivative in μ is exact (F_t is linear in μ). 1e-9 relative leaves room for both.
            assert!(
                (mu0 / exact - 1.0).abs() < 1e-9,
                "V = {speed}: mu0 {mu0} vs {exact}"
            );
            // At μ* the tangential mode is undamped: λ = i sqrt(k_t).
            let f = KT.sqrt() / (2.0 * std::f64::consts::PI);
            assert!((f0 / f - 1.0).abs() < 1e-9, "{f0} vs {f}");
        }
        // Faster sliding leaves the falling part of the curve: a higher threshold.
        assert!(closed_form(0.8) > closed_form(0.4));
    }
}
