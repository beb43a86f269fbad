//! Contact elements: the force law of one disc–pad contact pair, behind one interface.
//!
//! A pair's state is three scalars ([`Kinematics`]): the penetration `δ = g·x + gap`
//! (positive when the pad presses into the disc: eq (8)'s `U_i - U_j` along the normal), its
//! rate `δ' = g·x'`, and the slip velocity `v = V + h·x'` of the disc surface under the pad
//! along the pair's sliding direction `s` (`V` the surface speed of the rotating disc there,
//! `h` holding `+s` on the disc point's dofs and `-s` on the pad point's). A contact element
//! returns the normal force `F_n` (pushing the pad out of the disc) and the tangential
//! (friction) force `F_t` (the disc dragging the pad along `s`), with their derivatives with
//! respect to the three scalars and to the friction level μ ([`Response`]). As internal forces
//! on the left of eq (11), a pair contributes
//!
//! `F_p(x, x') = F_n g + F_t h`,
//!
//! and its Jacobians are
//! `∂F_p/∂x = (F_n,δ g + F_t,δ h) gᵀ`,
//! `∂F_p/∂x' = (F_n,δ' g + F_t,δ' h) gᵀ + (F_n,v g + F_t,v h) hᵀ`.
//!
//! Everything else — equilibrium, linearization, harmonic balance, time integration — calls
//! the element through [`ContactLaw`], so a new law is one new type implementing it. The first
//! element is the paper's ([`PenaltyCoulomb`], eqs 8–10): cubic penalty contact with Coulomb
//! friction in permanent sliding. A velocity-dependent friction coefficient or a regularized
//! stick–slip law depends on `v` (and then the linearization gains a damping part, see
//! [`crate::linearized`]); `crates/squeal-brake/tests/friction_law.rs` adds one such element
//! without touching any other file.

use std::fmt::Debug;
use std::sync::Arc;

/// The state of one contact pair.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Kinematics {
    /// `δ` (m), positive when closed.
    pub penetration: f64,
    /// `δ'` (m/s).
    pub penetration_rate: f64,
    /// `v` (m/s): slip velocity of the disc surface under the pad along the sliding direction.
    pub slip_velocity: f64,
}

/// Forces of a contact element and their first derivatives.
///
/// Derivatives are listed as `[∂/∂δ, ∂/∂δ', ∂/∂v]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Response {
    /// `F_n` (N): pushes the pad away from the disc along the normal (0 when open).
    pub normal: f64,
    /// `F_t` (N): the disc drags the pad along the sliding direction.
    pub tangential: f64,
    /// `[∂F_n/∂δ (N/m), ∂F_n/∂δ' (N·s/m), ∂F_n/∂v (N·s/m)]`.
    pub normal_derivatives: [f64; 3],
    /// `[∂F_t/∂δ (N/m), ∂F_t/∂δ' (N·s/m), ∂F_t/∂v (N·s/m)]`.
    pub tangential_derivatives: [f64; 3],
    /// `∂F_t/∂μ` (N) at fixed kinematics (the normal force does not depend on μ).
    pub tangential_mu: f64,
}

impl Response {
    /// Whether any force depends on the velocities (then the linearization has damping).
    pub fn has_velocity_terms(&self) -> bool {
        self.normal_derivatives[1..]
            .iter()
            .chain(&self.tangential_derivatives[1..])
            .any(|d| *d != 0.0)
    }
}

/// A named parameter of a contact element, for reports: `(name, value, unit)`.
pub type Parameter = (&'static str, f64, &'static str);

/// The force law of one contact pair (see the module documentation for the conventions).
pub trait ContactLaw: Debug + Send + Sync {
    /// Forces and derivatives at friction level `mu` in state `k`.
    fn response(&self, mu: f64, k: &Kinematics) -> Response;

    /// Whether the forces depend on the slip velocity (then the disc speed must be known).
    fn uses_slip_velocity(&self) -> bool {
        false
    }

    /// Whether the forces depend on the penetration rate (contact damping).
    fn uses_penetration_rate(&self) -> bool {
        false
    }

    /// A short description, e.g. `cubic penalty (eq 8), Coulomb friction (eq 9)`.
    fn name(&self) -> String;

    /// The law's parameters, for reports.
    fn parameters(&self) -> Vec<Parameter>;
}

/// A shared contact element (pairs are cloned with the brake; laws are not).
pub type Law = Arc<dyn ContactLaw>;

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

/// Any element with its forces (normal and tangential alike) multiplied by `factor`: the
/// contact-stiffness factor of the parametric studies (Table 5), for any law.
#[derive(Debug)]
pub struct Scaled {
    /// The element whose forces are scaled.
    pub inner: Law,
    /// The factor on every force, derivative and force parameter (dimensionless).
    pub factor: f64,
}

impl ContactLaw for Scaled {
    fn response(&self, mu: f64, k: &Kinematics) -> Response {
        let r = self.inner.response(mu, k);
        let s = self.factor;
        Response {
            normal: s * r.normal,
            tangential: s * r.tangential,
            normal_derivatives: r.normal_derivatives.map(|d| s * d),
            tangential_derivatives: r.tangential_derivatives.map(|d| s * d),
            tangential_mu: s * r.tangential_mu,
        }
    }

    fn uses_slip_velocity(&self) -> bool {
        self.inner.uses_slip_velocity()
    }

    fn uses_penetration_rate(&self) -> bool {
        self.inner.uses_penetration_rate()
    }

    fn name(&self) -> String {
        format!("{} x {}", self.factor, self.inner.name())
    }

    fn parameters(&self) -> Vec<Parameter> {
        self.inner
            .parameters()
            .into_iter()
            .map(|(n, v, u)| (n, v * self.factor, u))
            .collect()
    }
}

/// `law` with its forces times `factor` (a factor of 1 returns the law itself).
pub fn scaled(law: &Law, factor: f64) -> Law {
    if factor == 1.0 {
        return law.clone();
    }
    Arc::new(Scaled {
        inner: law.clone(),
        factor,
    })
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

    #[test]
    fn scaling_multiplies_every_force_and_derivative() {
        let law: Law = Arc::new(PenaltyCoulomb {
            k_linear: 2e6,
            k_cubic: 3e15,
        });
        let s = scaled(&law, 1.3);
        let k = Kinematics {
            penetration: 1e-5,
            ..Kinematics::default()
        };
        let (a, b) = (law.response(0.5, &k), s.response(0.5, &k));
        assert_eq!(b.normal, 1.3 * a.normal);
        assert_eq!(
            b.tangential_derivatives[0],
            1.3 * a.tangential_derivatives[0]
        );
        assert!(Arc::ptr_eq(&scaled(&law, 1.0), &law));
    }
}
