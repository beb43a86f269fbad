//! Exact Coulomb stick–slip on the brake's pairs: the dynamic Lagrangian frequency–time method
//! (DLFT; Nacivet, Pierre, Thouverez & Jézéquel, JSV 265, 2003) as a contact law of the brake's
//! condensed harmonic balance.
//!
//! The pointwise elements of this module's siblings give a pair's forces from its state
//! `(δ, δ', v)`. Exact Coulomb friction cannot be one: while a pair sticks its tangential force
//! is whatever keeps the slip velocity at zero, a Lagrange multiplier of the whole balance. DLFT
//! predicts that multiplier from the harmonic balance's own residual and corrects it in the
//! time domain; the generic method (equations S1–S4, Jacobian, transitions) is
//! `squeal_hbm::stick_slip`, verified on the mass on a belt and the 2-dof friction oscillator
//! against event-driven integration. This module gives it the brake.
//!
//! **The brake's residual without friction.** Eq (34) of the CHBM paper on the nonlinear dofs
//! `x_n` is `R(U~, ω) = Λ_eq(ω) U~ + G~(U~) - F~_eq` with `G = Σ_p (F_n,p g_p + F_t,p h_p) - K_s
//! x_n` ([`crate::harmonic::ContactForce`]). Its friction part `Σ_p F_t,p h_p` is removed by
//! evaluating the same elements at μ = 0 (their normal force does not depend on μ, and neither
//! do `K_s`, the condensation `Λ_eq` nor the load `F_eq`):
//!
//! `R_r(U~, ω) = Λ_eq(ω) U~ + G~_{μ=0}(U~) - F~_eq`,                                      (D1)
//!
//! the brake's residual with frictionless pairs, condensed on the contact coordinates.
//!
//! **The pairs as friction contacts.** Pair `p` becomes one DLFT contact with direction
//! `h_p` (`+s` on the disc point's dofs, `-s` on the pad point's: [`crate::contact`]), counter-face
//! speed `V_p` (the disc's surface speed at the pair), and normal load eq (8)'s cubic penalty
//! `N_p = k_l δ + k_nl δ³` of the closure `δ = g_p·x_n - g0_p` (0 when open):
//!
//! `R(U~, ω) = R_r(U~, ω) + Σ_p h_p ⊗ Φ~_p`,                                           (D2)
//!
//! `Φ~_p` the Fourier coefficients of the friction force `φ_p(t)`, obtained sample by sample
//! from the predicted multiplier (`w_p = h_p / |h_p|²`)
//!
//! `a_p(t) = -w_p·r_r(t) + ε_p γ_p(t)`,  `γ_p = V_p + h_p·x_n'`,                        (D3)
//!
//! `φ_p = a_p` (stick) where `|a_p| ≤ μ N_p`, `φ_p = μ N_p sign a_p` (slip) elsewhere.    (D4)
//!
//! At a stick sample where the residual vanishes `γ_p = 0`: the pair moves with the disc,
//! carrying the multiplier `-w_p·r_r`; at a slip sample `sign(a_p)(|a_p| - μ N_p) = ε_p γ_p`, so
//! the force opposes the slip for any `ε_p > 0`. No regularization velocity enters: with a
//! regularized law `μ N tanh(γ / v_reg)` ([`super::Sticking`]) the cycles must approach these
//! as `v_reg → 0` (measured in docs/stick_slip.md).
//!
//! (D4) is applied as written, sample by sample without memory (the clamp of
//! `squeal_hbm::stick_slip`, "One coefficient: the clamp"): the brake's pairs have one
//! coefficient, and the generic relay (breakaway tested on the sticking force without the
//! penalty, sticking on `a_p`) kept a memory between the two tests that made the residual jump
//! under a change of μ of 1e-5 (measured: relative residual 1.4e-8 at the converged 1.0452 μ0
//! cycle, 1.0e2 at μ (1 + 1e-5) from the same coefficients), so Levenberg–Marquardt reached
//! the cycles past 1.05 μ0 only from starts within about 1e-4. The clamp is continuous and
//! semismooth; its Jacobian on each sample's piece is a generalized (B-subdifferential)
//! Jacobian, and the solve converges from the permanent-sliding cycle and along μ
//! (docs/stick_slip.md, "Past 1.05 μ0").
//!
//! **Which DLFT.** Nacivet et al. penalize the relative *displacement* increment; on a disc the
//! relative displacement `x - V t` is not periodic, the relative velocity is, so the penalty is
//! on `γ` (the velocity-level form of Krack & Gross, *Harmonic Balance for Nonlinear Vibration
//! Problems*, 2019, NLvib's `HB_residual_friction1D`; `squeal_hbm::stick_slip`, Why DLFT).
//!
//! **The penalty ε.** Any positive ε gives the same converged cycle; its size sets how the
//! prediction weighs the velocity error against the residual. Default: the static stiffness of
//! the condensed brake along the pair's direction over the cycle's angular frequency,
//! `ε_p = (h_pᵀ Λ_eq,0 h_p / |h_p|⁴) / ω`, the impedance `k / ω` of the pair's coordinate
//! ([`default_epsilon`]).
//!
//! **Which elements.** DLFT imposes Coulomb's law with one coefficient: the pair's element must
//! be eq (8)'s penalty with `F_t = μ F_n` while sliding and no contact damping (the paper's
//! element, possibly scaled). [`friction_contacts`] checks this on the element itself and refuses
//! other laws with [`DlftError::NotCoulomb`].

use super::Kinematics;
use crate::harmonic::{CondensedStiffness, ContactForce, condensed_load};
use crate::modal_brake::ModalBrake;
use crate::model::ContactPair;
use squeal_hbm::{
    FrictionContact, HarmonicBalance, HarmonicLayout, HbmError, NormalLoad, StickSlipBalance,
};

/// The brake's harmonic balance with DLFT friction on every pair.
pub type BrakeDlft = StickSlipBalance<CondensedStiffness, ContactForce>;

/// Why the brake cannot be given DLFT contacts.
#[derive(Debug, thiserror::Error)]
pub enum DlftError {
    /// A pair has no disc surface speed.
    #[error(
        "contact pair {pair} has no disc surface speed: give the disc's speed ([rotation] rpm, or vehicle_speed_kmh with rolling_radius) for exact stick-slip"
    )]
    NoSurfaceSpeed {
        /// The pair (1-based).
        pair: usize,
    },
    /// A pair's element is not the penalty with Coulomb friction of one coefficient.
    #[error(
        "contact pair {pair}: exact stick-slip (DLFT) needs eq (8)'s cubic penalty with Coulomb friction F_t = mu F_n and no contact damping, but the element is {law}; use law = \"penalty-coulomb\" in [contact]"
    )]
    NotCoulomb {
        /// The pair (1-based).
        pair: usize,
        /// The element's name.
        law: String,
    },
    /// A DLFT option out of range.
    #[error("exact stick-slip (DLFT): {0}")]
    BadOption(&'static str),
    /// The harmonic balance.
    #[error(transparent)]
    Hbm(#[from] HbmError),
}

/// `(k_l, k_nl)` of a pair whose element is eq (8)'s penalty with Coulomb friction, checked on
/// the element's responses at two closures, sliding at two speeds.
fn coulomb_penalty(p: &ContactPair, pair: usize) -> Result<(f64, f64), DlftError> {
    let bad = || DlftError::NotCoulomb {
        pair,
        law: p.law.name(),
    };
    let params = p.law.parameters();
    let get = |name: &str| params.iter().find(|q| q.0 == name).map(|q| q.1);
    let (Some(kl), Some(knl)) = (get("k_l"), get("k_nl")) else {
        return Err(bad());
    };
    if !(kl.is_finite() && knl.is_finite() && kl > 0.0 && knl >= 0.0)
        || p.law.uses_penetration_rate()
    {
        return Err(bad());
    }
    // The closures at which the check runs: 1 µm and 30 µm, both ends of the brake's range.
    for (d, v) in [(1e-6, 0.01), (3e-5, 3.0)] {
        let r = p.law.response(
            0.5,
            &Kinematics {
                penetration: d,
                penetration_rate: 0.0,
                slip_velocity: v,
            },
        );
        let n = kl * d + knl * d * d * d;
        // 1e-12: the same formula evaluated by the element, to round-off.
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-300);
        if !close(r.normal, n) || !close(r.tangential, 0.5 * n) {
            return Err(bad());
        }
    }
    Ok((kl, knl))
}

/// Every pair of `mb` as a DLFT friction contact (module docs, D2–D4), at `mb.mu`, with the
/// penalty `epsilon` (N·s/m, one per pair).
pub fn friction_contacts(
    mb: &ModalBrake,
    epsilon: &[f64],
) -> Result<Vec<FrictionContact>, DlftError> {
    if epsilon.len() != mb.pairs.len() || epsilon.iter().any(|e| !(e.is_finite() && *e > 0.0)) {
        return Err(DlftError::BadOption(
            "one positive finite penalty epsilon per pair",
        ));
    }
    mb.pairs
        .iter()
        .zip(epsilon)
        .enumerate()
        .map(|(i, (p, &eps))| {
            let speed = p
                .surface_speed
                .ok_or(DlftError::NoSurfaceSpeed { pair: i + 1 })?;
            let (k_linear, k_cubic) = coulomb_penalty(p, i + 1)?;
            Ok(FrictionContact {
                direction: p.tangent.clone(),
                sliding_speed: speed,
                normal: NormalLoad::Penalty {
                    normal: p.normal.clone(),
                    offset: -p.initial_gap,
                    k_linear,
                    k_cubic,
                },
                mu: mb.mu,
                static_ratio: 1.0,
                epsilon: eps,
                contact_mass: 0.0,
            })
        })
        .collect()
}

/// The default penalty of every pair at the angular frequency `omega` (module docs, The
/// penalty ε): `(h_pᵀ Λ_eq,0 h_p / |h_p|⁴) / ω`.
pub fn default_epsilon(mb: &ModalBrake, stiffness: &CondensedStiffness, omega: f64) -> Vec<f64> {
    let z0 = stiffness.static_block();
    mb.pairs
        .iter()
        .map(|p| {
            let n2: f64 = p.tangent.iter().map(|e| e.1 * e.1).sum();
            let k: f64 = p
                .tangent
                .iter()
                .flat_map(|&(i, a)| p.tangent.iter().map(move |&(j, b)| a * b * z0[(i, j)].re))
                .sum();
            k / (n2 * n2) / omega
        })
        .collect()
}

/// The brake `mb` with frictionless elements (μ = 0): the pointwise part of (D1).
pub fn frictionless(mb: &ModalBrake) -> ModalBrake {
    let mut out = mb.clone();
    out.mu = 0.0;
    out
}

/// The brake's harmonic balance with DLFT friction on every pair at `mb.mu` (module docs):
/// `harmonics` harmonics, `samples` time samples of the friction forces (`None`: the generic
/// default, `16 (2H + 1)` to a power of two), the penalty ε of every pair (`None`:
/// [`default_epsilon`] at `omega`).
pub fn brake_dlft(
    mb: &ModalBrake,
    harmonics: usize,
    samples: Option<usize>,
    epsilon: Option<&[f64]>,
    omega: f64,
) -> Result<BrakeDlft, DlftError> {
    if !(omega.is_finite() && omega > 0.0) {
        return Err(DlftError::BadOption(
            "the angular frequency must be positive",
        ));
    }
    let layout = HarmonicLayout::new(mb.nl(), harmonics)?;
    let free = frictionless(mb);
    let stiffness = CondensedStiffness::new(&free, harmonics);
    let eps = match epsilon {
        Some(e) => e.to_vec(),
        None => default_epsilon(mb, &stiffness, omega),
    };
    let contacts = friction_contacts(mb, &eps)?;
    let f_eq = condensed_load(&free, &stiffness, &layout);
    let hb = HarmonicBalance::new(
        layout,
        stiffness,
        ContactForce::new(&free),
        f_eq,
        samples.map(|s| s.max(squeal_hbm::default_samples(harmonics))),
    )?;
    let mut b = StickSlipBalance::new(hb, contacts, samples)?;
    // One coefficient (μ_s = μ): (D4) is the plain clamp, continuous and semismooth
    // (`squeal_hbm::stick_slip`, "One coefficient: the clamp").
    b.set_clamp(true);
    Ok(b)
}

/// Sets the friction coefficient of every DLFT contact of `b` (a continuation parameter).
pub fn set_mu(b: &mut BrakeDlft, mu: f64) {
    for c in b.contacts_mut() {
        c.mu = mu;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{PenaltyCoulomb, RegularizedCoulomb};
    use std::sync::Arc;

    fn pair(law: crate::contact::Law) -> ContactPair {
        ContactPair {
            disc_point: 0,
            pad_point: 0,
            position: [0.0; 3],
            normal_direction: [0.0, 0.0, 1.0],
            sliding_direction: [1.0, 0.0, 0.0],
            normal: vec![(1, 1.0)],
            tangent: vec![(0, 1.0)],
            initial_gap: 0.0,
            surface_speed: Some(1.0),
            law,
        }
    }

    #[test]
    fn the_paper_element_is_accepted_and_a_regularized_one_refused() {
        let k = (2.0e8, 3.0e18);
        let p = pair(Arc::new(PenaltyCoulomb {
            k_linear: k.0,
            k_cubic: k.1,
        }));
        // The stiffnesses come back exactly: they are read from the element's parameters.
        assert_eq!(coulomb_penalty(&p, 1).unwrap(), k);
        let q = pair(Arc::new(RegularizedCoulomb {
            k_linear: k.0,
            k_cubic: k.1,
            regularization_speed: 1.0,
            static_ratio: 1.0,
            static_speed: 10.0,
        }));
        // tanh(0.01 / 1) is far from 1: not Coulomb's law in sliding.
        let e = coulomb_penalty(&q, 3).unwrap_err().to_string();
        assert!(e.contains("pair 3") && e.contains("penalty-coulomb"), "{e}");
    }
}
