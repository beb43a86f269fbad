//! Penalty contact with regularized Coulomb friction: a smooth element that sticks and slips.
//!
//! The paper's element (eq 9) keeps the friction force at `μ F_n` in one direction: it holds
//! while the disc's surface outruns the pad (permanent sliding, a sliding margin above 1). When
//! the pad's tangential vibration velocity reaches the disc's, the slip velocity `v` of the disc
//! under the pad passes through zero and Coulomb's law makes the force set-valued there
//! (`|F_t| ≤ μ_s F_n` while stuck). This element replaces the sign of `v` by a smooth step:
//!
//! `F_t = μ F_n s(|v|) tanh(v / v_reg)`,  `s(v) = 1 + (r - 1) e^(-v / v_s)`,
//!
//! with `F_n = k_l δ + k_nl δ³` eq (8)'s penalty, `v_reg` the regularization velocity, `r = μ_s/μ`
//! the static coefficient over the kinetic one and `v_s` the speed over which the coefficient
//! falls from `μ_s` to `μ` (`r = 1`: one coefficient, `s ≡ 1`). "Sticking" is then slow creep:
//! the contact carries a force `|F_t| < μ_s F_n` at a slip velocity of order `v_reg`; the force
//! reaches 99.9 % of `μ F_n` at `|v| = 3.8 v_reg`. As `v_reg → 0` (and `v_s → 0` with
//! `v_reg ≪ v_s`) the element tends to Coulomb's law with static and kinetic coefficients:
//! `crates/squeal-chbm/tests/chbm/stick_slip_belt.rs` measures the convergence of the mass-on-belt
//! cycle to its closed form.
//!
//! **Default** `v_reg = 1 mm/s` ([`DEFAULT_REGULARIZATION_SPEED`]), a common choice in the
//! brake and friction-oscillator literature (1e-4 to 1e-3 m/s): it is below the disc surface
//! speed of a crawling car (0.5 m/s at 5 km/h on the bundled brake) by 500 times, so in
//! permanent sliding (slip velocity above `4 v_reg` everywhere) the element's force equals the
//! paper's to `1 - tanh(4) ≈ 7e-4` relative and to round-off once `v > 19 v_reg`. Its Jacobian
//! `∂F_t/∂v ≈ μ F_n / v_reg` near `v = 0` is stiff: time integration needs an implicit scheme
//! (BDF), and harmonic balance needs many harmonics to resolve the transitions; the exact
//! alternative for harmonic balance is `squeal_hbm::stick_slip` (dynamic Lagrangian).
//!
//! Derivatives (conventions of [`crate::contact`]): with `τ = tanh(v / v_reg)`,
//! `∂F_t/∂δ = μ k_t s τ`, `∂F_t/∂v = μ F_n (s'(|v|) sign(v) τ + s (1 - τ²) / v_reg)`,
//! `∂F_t/∂μ = F_n s τ`, `s'(v) = -(r - 1) e^(-v/v_s) / v_s`.

use super::{ContactLaw, Kinematics, Parameter, Response, speed_shaped_response};

/// The default regularization velocity `v_reg` (m/s).
pub const DEFAULT_REGULARIZATION_SPEED: f64 = 1.0e-3;

/// Penalty contact (eq 8) with the regularized Coulomb friction of the module documentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegularizedCoulomb {
    /// `k_l` (N/m).
    pub k_linear: f64,
    /// `k_nl` (N/m³).
    pub k_cubic: f64,
    /// `v_reg` (m/s), > 0.
    pub regularization_speed: f64,
    /// `r = μ_s / μ` (dimensionless, ≥ 1; 1 for one coefficient).
    pub static_ratio: f64,
    /// `v_s` (m/s), > 0: the speed over which the coefficient falls from `μ_s` to `μ`.
    pub static_speed: f64,
}

impl RegularizedCoulomb {
    /// One coefficient (`r = 1`) with the regularization velocity `v_reg`.
    pub fn coulomb(k_linear: f64, k_cubic: f64, regularization_speed: f64) -> Self {
        Self {
            k_linear,
            k_cubic,
            regularization_speed,
            static_ratio: 1.0,
            static_speed: 10.0 * regularization_speed,
        }
    }

    /// The friction force over `μ F_n`, `s(|v|) tanh(v / v_reg)`, and its derivative in `v`.
    pub fn shape(&self, v: f64) -> (f64, f64) {
        let t = (v / self.regularization_speed).tanh();
        let e = (-v.abs() / self.static_speed).exp();
        let s = 1.0 + (self.static_ratio - 1.0) * e;
        let ds = -(self.static_ratio - 1.0) * e / self.static_speed * v.signum();
        (
            s * t,
            ds * t + s * (1.0 - t * t) / self.regularization_speed,
        )
    }
}

impl ContactLaw for RegularizedCoulomb {
    fn response(&self, mu: f64, k: &Kinematics) -> Response {
        let shape = self.shape(k.slip_velocity);
        speed_shaped_response(mu, k, self.k_linear, self.k_cubic, shape)
    }

    fn uses_slip_velocity(&self) -> bool {
        true
    }

    fn name(&self) -> String {
        "cubic penalty contact (eq 8), regularized Coulomb friction mu F_n s(|v|) tanh(v/v_reg) (sticks and slips)".into()
    }

    fn parameters(&self) -> Vec<Parameter> {
        vec![
            ("k_l", self.k_linear, "N/m"),
            ("k_nl", self.k_cubic, "N/m^3"),
            ("v_reg", self.regularization_speed, "m/s"),
            ("mu_s/mu", self.static_ratio, "-"),
            ("v_s", self.static_speed, "m/s"),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivative_matches_finite_differences_and_fast_sliding_is_coulomb() {
        let law = RegularizedCoulomb {
            k_linear: 2e6,
            k_cubic: 3e15,
            regularization_speed: 1e-3,
            static_ratio: 1.3,
            static_speed: 1e-2,
        };
        for v in [-2e-2, -1e-3, 3e-4, 2e-3, 5e-2] {
            let h = 1e-8;
            let fd = (law.shape(v + h).0 - law.shape(v - h).0) / (2.0 * h);
            let an = law.shape(v).1;
            // Central differences: truncation (h / v_reg)² ≈ 1e-10 relative, round-off
            // 1e-16 / h ≈ 1e-8 of the shape's unit scale.
            assert!(
                (fd - an).abs() < 1e-6 * an.abs().max(1.0),
                "{v}: {fd} vs {an}"
            );
        }
        // Odd in v, μ_s at creep speeds between v_reg and v_s, μ at fast sliding.
        assert_eq!(law.shape(-2e-3).0, -law.shape(2e-3).0);
        let peak = law.shape(4e-3).0;
        assert!(peak > 1.2 && peak < 1.3, "{peak}");
        // At v = 0.5 m/s (5 km/h on the bundled brake): tanh(500) = 1 and e^(-50) ≈ 2e-22.
        let coulomb = RegularizedCoulomb::coulomb(2e6, 3e15, DEFAULT_REGULARIZATION_SPEED);
        assert_eq!(coulomb.shape(0.5).0, 1.0);
        let k = Kinematics {
            penetration: 1e-5,
            slip_velocity: 0.5,
            ..Kinematics::default()
        };
        let r = coulomb.response(0.4, &k);
        let pc = super::super::PenaltyCoulomb {
            k_linear: 2e6,
            k_cubic: 3e15,
        }
        .response(0.4, &k);
        assert_eq!((r.normal, r.tangential), (pc.normal, pc.tangential));
    }
}
