//! Penalty contact with a friction coefficient that depends on the sliding speed.
//!
//! The normal force is eq (8)'s cubic penalty, `F_n = k_l δ + k_nl δ³` when closed. The
//! friction coefficient changes with the slip velocity `v` of the disc surface under the pad
//! (the falling part of Stribeck's curve, in an exponential form common in studies of friction
//! oscillators):
//!
//! `μ(v) = μ s(v)`, `s(v) = r + (1 - r)(1 - e^(-v/v0))`,
//!
//! i.e. `μ(v) = μ_s + (μ_d - μ_s)(1 - e^(-v/v0))` with the swept friction level `μ = μ_d` (the
//! coefficient at high sliding speed), `μ_s = r μ_d` at rest and `v0` the speed over which it
//! moves from one to the other. Then
//!
//! `F_t = μ s(v) F_n`,  `∂F_t/∂δ = μ s(v) k_t`,  `∂F_t/∂v = μ s'(v) F_n`,  `∂F_t/∂μ = s(v) F_n`,
//!
//! with `s'(v) = (1 - r) e^(-v/v0) / v0`. The model stays in permanent sliding (`v > 0`, checked
//! on every cycle by `squeal_chbm::physics::sliding_margin`): `s` is the curve's branch for a
//! disc outrunning the pad.
//!
//! **What the slope does.** Linearized about the equilibrium, where `v = V` (the disc's
//! surface speed at the pair), the friction force gains `∂F_t/∂v · h·x'`: a damping
//! `μ s'(V) F_n h hᵀ` along the sliding direction (see [`crate::linearized`]). For `r > 1` the
//! coefficient falls with speed, `s'(V) < 0`, and this damping is negative: it feeds energy into
//! every mode that moves the pad tangentially, and the brake turns unstable at a lower friction
//! level than with the constant coefficient `μ s(V)` of the same steady sliding. For `r < 1`
//! the curve rises and the extra damping is positive. `r = 1` is [`super::PenaltyCoulomb`]
//! exactly (`s ≡ 1`, `s' ≡ 0`). `crates/squeal-brake/tests/brake/friction_law.rs` checks the Hopf
//! point of a 2-dof pad against the closed form `μ* = c v0 e^(V/v0) / ((r - 1) N)`, and
//! `crates/squeal-pipeline/tests/pipeline/contact_law.rs` the direction of the change on the bundled
//! brake.

use super::{ContactLaw, Kinematics, Parameter, Response, speed_shaped_response};

/// Penalty contact (eq 8) with the speed-dependent friction of the module documentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VelocityDependent {
    /// `k_l` (N/m).
    pub k_linear: f64,
    /// `k_nl` (N/m³).
    pub k_cubic: f64,
    /// `r = μ_s / μ_d` (dimensionless).
    pub static_ratio: f64,
    /// `v0` (m/s).
    pub decay_speed: f64,
}

impl VelocityDependent {
    /// `s(v) = μ(v) / μ` and its derivative `s'(v)` (s/m).
    pub fn shape(&self, v: f64) -> (f64, f64) {
        let e = (-v / self.decay_speed).exp();
        let r = self.static_ratio;
        (r + (1.0 - r) * (1.0 - e), (1.0 - r) * e / self.decay_speed)
    }
}

impl ContactLaw for VelocityDependent {
    fn response(&self, mu: f64, k: &Kinematics) -> Response {
        let shape = self.shape(k.slip_velocity);
        speed_shaped_response(mu, k, self.k_linear, self.k_cubic, shape)
    }

    fn uses_slip_velocity(&self) -> bool {
        true
    }

    fn name(&self) -> String {
        "cubic penalty contact (eq 8), friction falling or rising with the sliding speed".into()
    }

    fn parameters(&self) -> Vec<Parameter> {
        vec![
            ("k_l", self.k_linear, "N/m"),
            ("k_nl", self.k_cubic, "N/m^3"),
            ("mu_s/mu_d", self.static_ratio, "-"),
            ("v0", self.decay_speed, "m/s"),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_finite_differences_and_ratio_one_is_coulomb() {
        let law = VelocityDependent {
            k_linear: 2e6,
            k_cubic: 3e15,
            static_ratio: 1.4,
            decay_speed: 0.5,
        };
        let (mu, d, v) = (0.4, 1.3e-5, 0.7);
        let at = |v: f64| {
            law.response(
                mu,
                &Kinematics {
                    penetration: d,
                    slip_velocity: v,
                    ..Kinematics::default()
                },
            )
        };
        let h = 1e-6;
        let fd = (at(v + h).tangential - at(v - h).tangential) / (2.0 * h);
        let an = at(v).tangential_derivatives[2];
        // Central differences of an exponential in v/v0: truncation (h/v0)²/6 ≈ 7e-13 relative.
        assert!((fd / an - 1.0).abs() < 1e-8, "{fd} vs {an}");
        // A falling curve: the slope is negative.
        assert!(an < 0.0);
        let coulomb = super::super::PenaltyCoulomb {
            k_linear: 2e6,
            k_cubic: 3e15,
        };
        let one = VelocityDependent {
            static_ratio: 1.0,
            ..law
        };
        let k = Kinematics {
            penetration: d,
            slip_velocity: v,
            ..Kinematics::default()
        };
        // s ≡ 1 and s' ≡ 0 exactly when r = 1: the same response to the last bit.
        assert_eq!(one.response(mu, &k), coulomb.response(mu, &k));
    }
}
