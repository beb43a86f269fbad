//! The paper's contact element, eqs (8)–(10): cubic penalty contact with Coulomb friction in
//! permanent sliding.
//!
//! Eq (8) gives the normal force of a closed pair as a cubic in the penetration `δ`,
//! `F_n = k_l δ + k_nl δ³` for `δ > 0` and 0 when open: the linear part is the pad's small-load
//! stiffness, the cubic part its stiffening under load (fitted to a compression curve by the
//! scene). Eq (9) is Coulomb's law in permanent sliding: the disc's surface always outruns the
//! pad, so the friction force keeps its sign and `F_t = μ F_n`, independent of the velocities.
//! With the conventions of [`crate::contact`] the derivatives are
//! `∂F_n/∂δ = k_t = k_l + 3 k_nl δ²`, `∂F_t/∂δ = μ k_t`, `∂F_t/∂μ = F_n`, and none in `δ'` or
//! `v`: the linearization (eqs 18–19) has a non-symmetric stiffness and no damping part.

use super::{ContactLaw, Kinematics, Parameter, Response};

/// Eq (8): `F_c = k_l δ + k_nl δ³` for `δ > 0`, else 0, with its tangent `dF_c/dδ`.
pub fn cubic_penalty(delta: f64, k_linear: f64, k_cubic: f64) -> (f64, f64) {
    if delta > 0.0 {
        (
            k_linear * delta + k_cubic * delta.powi(3),
            k_linear + 3.0 * k_cubic * delta * delta,
        )
    } else {
        (0.0, 0.0)
    }
}

/// The response of eq (8)'s penalty with friction `F_t = μ s(v) F_n`, where `s(v)` and
/// `ds/dv` (`shape`) say how the coefficient changes with the slip velocity `v`: the laws
/// whose friction depends on the sliding speed differ only in `s`.
pub fn speed_shaped_response(
    mu: f64,
    k: &Kinematics,
    k_linear: f64,
    k_cubic: f64,
    (s, ds): (f64, f64),
) -> Response {
    let (f, kt) = cubic_penalty(k.penetration, k_linear, k_cubic);
    Response {
        normal: f,
        tangential: mu * s * f,
        normal_derivatives: [kt, 0.0, 0.0],
        tangential_derivatives: [mu * s * kt, 0.0, mu * ds * f],
        tangential_mu: s * f,
    }
}

/// The paper's contact element, eqs (8)–(10): cubic penalty contact `F_n = k_l δ + k_nl δ³`
/// (zero when open) and Coulomb friction in permanent sliding `F_t = μ F_n`, independent of
/// the velocities.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PenaltyCoulomb {
    /// `k_l` (N/m).
    pub k_linear: f64,
    /// `k_nl` (N/m³).
    pub k_cubic: f64,
}

impl ContactLaw for PenaltyCoulomb {
    fn response(&self, mu: f64, k: &Kinematics) -> Response {
        let (f, kt) = cubic_penalty(k.penetration, self.k_linear, self.k_cubic);
        Response {
            normal: f,
            tangential: mu * f,
            normal_derivatives: [kt, 0.0, 0.0],
            tangential_derivatives: [mu * kt, 0.0, 0.0],
            tangential_mu: f,
        }
    }

    fn name(&self) -> String {
        "cubic penalty contact (eq 8), Coulomb friction in permanent sliding (eq 9)".into()
    }

    fn parameters(&self) -> Vec<Parameter> {
        vec![
            ("k_l", self.k_linear, "N/m"),
            ("k_nl", self.k_cubic, "N/m^3"),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn open_contact_carries_no_force() {
        assert_eq!(cubic_penalty(-1e-9, 1e6, 1e15), (0.0, 0.0));
        assert_eq!(cubic_penalty(0.0, 1e6, 1e15), (0.0, 0.0));
        let (f, k) = cubic_penalty(1e-5, 1e6, 1e15);
        assert!((f - (10.0 + 1e-15 * 1e15)).abs() < 1e-12 && (k - (1e6 + 3e5)).abs() < 1e-6);
    }

    #[test]
    fn penalty_coulomb_derivatives_match_finite_differences() {
        let law = PenaltyCoulomb {
            k_linear: 2e6,
            k_cubic: 3e15,
        };
        let (mu, d) = (0.4, 1.3e-5);
        let at = |delta: f64, mu: f64| {
            law.response(
                mu,
                &Kinematics {
                    penetration: delta,
                    ..Kinematics::default()
                },
            )
        };
        let r = at(d, mu);
        let h = 1e-10;
        let (p, m) = (at(d + h, mu), at(d - h, mu));
        // Central differences of a cubic: truncation k_nl h² ≈ 3e-5 N/m against k ≈ 2.5e6 N/m.
        for (fd, an) in [
            ((p.normal - m.normal) / (2.0 * h), r.normal_derivatives[0]),
            (
                (p.tangential - m.tangential) / (2.0 * h),
                r.tangential_derivatives[0],
            ),
        ] {
            assert!((fd - an).abs() < 1e-6 * an.abs(), "{fd} vs {an}");
        }
        // F_t is linear in μ: the difference quotient is exact up to round-off.
        let dmu = (at(d, mu + 1e-3).tangential - at(d, mu - 1e-3).tangential) / 2e-3;
        assert!((dmu - r.tangential_mu).abs() < 1e-9 * r.tangential_mu);
        assert!(!r.has_velocity_terms());
    }
}
