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
//! the element through [`ContactLaw`], so a new law is one new type implementing it, in a file
//! of its own:
//!
//! - [`penalty_coulomb`]: the paper's element ([`PenaltyCoulomb`], eqs 8–10), cubic penalty
//!   contact with Coulomb friction in permanent sliding;
//! - [`velocity_dependent`]: the same penalty with a friction coefficient that changes with the
//!   sliding speed ([`VelocityDependent`]); it depends on `v`, so the linearization gains a
//!   damping part (see [`crate::linearized`]).
//! - [`regularized_coulomb`]: Coulomb friction with `tanh(v / v_reg)` in place of the sign of
//!   the slip velocity ([`RegularizedCoulomb`]), optionally with a static coefficient above the
//!   kinetic one: a smooth element that sticks and slips, for cycles whose sliding margin falls
//!   below 1.
//! - [`sticking`]: any of these permanent-sliding elements made to stick ([`Sticking`]): its
//!   friction force at `|v|` times `tanh(v / v_reg)`; `squeal branch` switches a brake's pairs
//!   to it where a cycle's sliding margin falls below 1 (`squeal_chbm::stick_branch`).
//!
//! Exact Coulomb stick–slip (no regularization velocity) is not a pointwise element: the
//! stuck force is a Lagrange multiplier of the whole harmonic balance. It lives in
//! `squeal_hbm::stick_slip` (dynamic Lagrangian frequency–time method, Nacivet et al., JSV 265,
//! 2003), verified against the mass on a belt's closed form and an event-driven integration of
//! the 2-dof friction oscillator (docs/verification.md, Stick–slip); [`dlft`] makes every pair
//! of the brake such a contact of its condensed harmonic balance (a scene's
//! `[contact] stick_slip = "dlft"`).
//!
//! A scene chooses one for every pair by a [`LawSpec`] (`[contact] law`); a law written
//! outside the crate (`crates/squeal-chbm/examples/user_contact_law.rs`) plugs in the same way
//! without touching any other file.

pub mod dlft;
pub mod penalty_coulomb;
pub mod regularized_coulomb;
pub mod sticking;
pub mod velocity_dependent;

pub use penalty_coulomb::{PenaltyCoulomb, cubic_penalty, speed_shaped_response};
pub use regularized_coulomb::{DEFAULT_REGULARIZATION_SPEED, RegularizedCoulomb};
pub use sticking::Sticking;
pub use velocity_dependent::VelocityDependent;

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

/// The contact law every pair gets, as a scene chooses it (`[contact] law`): its normal part
/// is always eq (8)'s cubic penalty with the pair's stiffnesses `k_l`, `k_nl`
/// ([`crate::assemble::Stiffness`]); the variants differ in the friction force.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum LawSpec {
    /// The paper's element, eqs (8)–(10): Coulomb friction `F_t = μ F_n` ([`PenaltyCoulomb`]).
    #[default]
    PenaltyCoulomb,
    /// Friction that changes with the sliding speed `v` ([`VelocityDependent`]):
    /// `F_t = μ s(v) F_n` with `s(v) = r + (1 - r)(1 - e^(-v/v0))`.
    VelocityDependent {
        /// `r = μ_s / μ_d`, the coefficient at rest over the one at high speed: above 1 the
        /// coefficient falls with speed (destabilizing), below 1 it rises.
        static_ratio: f64,
        /// `v0` (m/s): the speed over which the coefficient moves from `μ_s` to `μ_d`.
        decay_speed: f64,
    },
    /// Regularized Coulomb friction ([`RegularizedCoulomb`]):
    /// `F_t = μ F_n s(|v|) tanh(v / v_reg)`, `s(v) = 1 + (r - 1) e^(-v/v_s)`.
    RegularizedCoulomb {
        /// `v_reg` (m/s).
        regularization_speed: f64,
        /// `r = μ_s / μ` (1: one coefficient).
        static_ratio: f64,
        /// `v_s` (m/s).
        static_speed: f64,
    },
}

impl LawSpec {
    /// The element of a pair with penalty stiffnesses `k_linear` (N/m), `k_cubic` (N/m³).
    pub fn element(&self, k_linear: f64, k_cubic: f64) -> Law {
        match *self {
            LawSpec::PenaltyCoulomb => Arc::new(PenaltyCoulomb { k_linear, k_cubic }),
            LawSpec::VelocityDependent {
                static_ratio,
                decay_speed,
            } => Arc::new(VelocityDependent {
                k_linear,
                k_cubic,
                static_ratio,
                decay_speed,
            }),
            LawSpec::RegularizedCoulomb {
                regularization_speed,
                static_ratio,
                static_speed,
            } => Arc::new(RegularizedCoulomb {
                k_linear,
                k_cubic,
                regularization_speed,
                static_ratio,
                static_speed,
            }),
        }
    }

    /// Its name in a scene: `penalty-coulomb`, `velocity-dependent` or `regularized-coulomb`.
    pub fn scene_name(&self) -> &'static str {
        match self {
            LawSpec::PenaltyCoulomb => "penalty-coulomb",
            LawSpec::VelocityDependent { .. } => "velocity-dependent",
            LawSpec::RegularizedCoulomb { .. } => "regularized-coulomb",
        }
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
