//! Any permanent-sliding element made to stick: its friction force for a slip velocity `v`
//! taken at `|v|` and turned by the smooth sign `tanh(v / v_reg)`.
//!
//! The laws of eq (9) kind ([`super::PenaltyCoulomb`], [`super::VelocityDependent`], and any
//! of them [`super::Scaled`] by a contact-stiffness factor) assume the disc's surface always
//! outruns the pad: `v > 0`, so the friction force keeps one direction. Where a cycle's
//! sliding margin falls below 1 (`crate`'s users measure it, `squeal_chbm::physics`) the slip
//! velocity `v = V + h·x'` reaches zero and turns negative for part of the period, and the
//! element's force must change direction with it. [`Sticking`] wraps such an element `F_t(δ,
//! δ', v)` into
//!
//! `F_t^s(δ, δ', v) = F_t(δ, δ', |v|) tanh(v / v_reg)`,
//!
//! the odd extension of the inner law regularized over `v_reg`: for the paper's element it is
//! exactly [`super::RegularizedCoulomb`] with one coefficient (`μ F_n tanh(v / v_reg)`), for a
//! velocity-dependent one the same coefficient curve in both directions. The normal force is
//! the inner element's at `|v|`. While the disc outruns the pad by more than `19 v_reg`
//! (`tanh(19) = 1` in double precision) the wrapped element gives the inner one's forces bit
//! for bit: a branch switched to it at a cycle of margin above 1 starts on the same cycle.
//!
//! Derivatives (conventions of [`crate::contact`]), with `τ = tanh(v / v_reg)`, `σ = sign v`
//! and the inner response `r` at `|v|`:
//! `∂F_t^s/∂δ = τ ∂F_t/∂δ`, `∂F_t^s/∂δ' = τ ∂F_t/∂δ'`,
//! `∂F_t^s/∂v = σ τ ∂F_t/∂v + F_t (1 - τ²) / v_reg`, `∂F_t^s/∂μ = τ ∂F_t/∂μ`,
//! `∂F_n^s/∂v = σ ∂F_n/∂v`.

use super::{ContactLaw, Kinematics, Law, Parameter, Response};

/// A permanent-sliding element made to stick and slip (module documentation).
#[derive(Clone, Debug)]
pub struct Sticking {
    /// The element in permanent sliding (`v > 0`).
    pub inner: Law,
    /// `v_reg` (m/s), > 0.
    pub regularization_speed: f64,
}

impl ContactLaw for Sticking {
    fn response(&self, mu: f64, k: &Kinematics) -> Response {
        let v = k.slip_velocity;
        let r = self.inner.response(
            mu,
            &Kinematics {
                slip_velocity: v.abs(),
                ..*k
            },
        );
        let tau = (v / self.regularization_speed).tanh();
        let sigma = if v < 0.0 { -1.0 } else { 1.0 };
        let [td, tr, tv] = r.tangential_derivatives;
        let [nd, nr, nv] = r.normal_derivatives;
        Response {
            normal: r.normal,
            tangential: tau * r.tangential,
            normal_derivatives: [nd, nr, sigma * nv],
            tangential_derivatives: [
                tau * td,
                tau * tr,
                sigma * tau * tv + r.tangential * (1.0 - tau * tau) / self.regularization_speed,
            ],
            tangential_mu: tau * r.tangential_mu,
        }
    }

    fn uses_slip_velocity(&self) -> bool {
        true
    }

    fn uses_penetration_rate(&self) -> bool {
        self.inner.uses_penetration_rate()
    }

    fn name(&self) -> String {
        format!(
            "{}, made to stick: F_t(|v|) tanh(v/v_reg)",
            self.inner.name()
        )
    }

    fn parameters(&self) -> Vec<Parameter> {
        let mut p = self.inner.parameters();
        p.push(("v_reg", self.regularization_speed, "m/s"));
        p
    }
}

#[cfg(test)]
mod tests {
    use super::super::{PenaltyCoulomb, RegularizedCoulomb, VelocityDependent, scaled};
    use super::*;
    use std::sync::Arc;

    fn at(law: &dyn ContactLaw, d: f64, rate: f64, v: f64) -> Response {
        law.response(
            0.45,
            &Kinematics {
                penetration: d,
                penetration_rate: rate,
                slip_velocity: v,
            },
        )
    }

    #[test]
    fn on_the_paper_element_it_is_the_regularized_coulomb_law() {
        let pc: Law = Arc::new(PenaltyCoulomb {
            k_linear: 2e6,
            k_cubic: 3e15,
        });
        let s = Sticking {
            inner: pc.clone(),
            regularization_speed: 2e-3,
        };
        let rc = RegularizedCoulomb::coulomb(2e6, 3e15, 2e-3);
        for v in [-0.3, -1e-3, 0.0, 4e-4, 5e-3, 0.5] {
            let (a, b) = (at(&s, 1.2e-5, 0.0, v), at(&rc, 1.2e-5, 0.0, v));
            // The same formula evaluated in another order: round-off.
            for (x, y) in [
                (a.tangential, b.tangential),
                (a.tangential_derivatives[0], b.tangential_derivatives[0]),
                (a.tangential_derivatives[2], b.tangential_derivatives[2]),
                (a.tangential_mu, b.tangential_mu),
            ] {
                assert!((x - y).abs() <= 1e-14 * y.abs().max(1.0), "{v}: {x} vs {y}");
            }
        }
        // Far above v_reg the inner element's forces bit for bit (tanh(250) = 1).
        assert_eq!(at(&s, 1.2e-5, 0.0, 0.5), at(pc.as_ref(), 1.2e-5, 0.0, 0.5));
    }

    #[test]
    fn derivatives_match_finite_differences_on_a_scaled_velocity_dependent_element() {
        let vd: Law = Arc::new(VelocityDependent {
            k_linear: 2e6,
            k_cubic: 3e15,
            static_ratio: 1.2,
            decay_speed: 0.05,
        });
        let s = Sticking {
            inner: scaled(&vd, 1.3),
            regularization_speed: 1e-3,
        };
        let (d, rate) = (1.1e-5, 0.0);
        for v in [-2e-2, -7e-4, 3e-4, 2e-3, 0.2] {
            let r = at(&s, d, rate, v);
            let hv = 1e-8;
            let fdv = (at(&s, d, rate, v + hv).tangential - at(&s, d, rate, v - hv).tangential)
                / (2.0 * hv);
            let hd = 1e-10;
            let fdd = (at(&s, d + hd, rate, v).tangential - at(&s, d - hd, rate, v).tangential)
                / (2.0 * hd);
            // Central differences: truncation (h / v_reg)² ≈ 1e-10 in v and k_nl h² / k_t
            // ≈ 1e-11 in δ relative, round-off 1e-16 F / h far below 1e-6 of the slopes.
            for (fd, an) in [
                (fdv, r.tangential_derivatives[2]),
                (fdd, r.tangential_derivatives[0]),
            ] {
                assert!(
                    (fd - an).abs() < 1e-6 * an.abs().max(1.0),
                    "{v}: {fd} vs {an}"
                );
            }
            // Odd in v.
            assert_eq!(at(&s, d, rate, -v).tangential, -r.tangential);
        }
    }
}
