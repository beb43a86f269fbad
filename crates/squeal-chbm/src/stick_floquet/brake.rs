//! The brake's DLFT cycles ([`crate::stick_dlft::DlftCycle`]) as [`super::StickSlipModel`]s:
//! modal coordinates (`K = Ω²`, `C = D`, `L = Φ_n`), the smooth force the pairs' normal
//! penalty less `K_s` (the brake's own Jacobian at μ = 0,
//! [`squeal_brake::modal_brake::ModalBrake::reduced_jacobians`]), and every pair a DLFT
//! friction contact ([`squeal_brake::contact::dlft::brake_dlft`]) whose per-sample states and
//! predicted multipliers come from the balance evaluated at the cycle itself.

use super::{
    LinearPart, StickSlipCycle, StickSlipFloquet, StickSlipFloquetOptions, StickSlipModel,
    stick_slip_floquet,
};
use crate::floquet::FloquetError;
use crate::stick_dlft::DlftCycle;
use squeal_brake::contact::dlft::{DlftError, brake_dlft, set_mu};
use squeal_brake::damping::ModalDamping;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::{HarmonicLayout, HbmError};

/// Why the stability of a DLFT cycle could not be computed.
#[derive(Debug, thiserror::Error)]
pub enum DlftFloquetError {
    /// The brake's DLFT balance.
    #[error(transparent)]
    Dlft(#[from] DlftError),
    /// Its evaluation.
    #[error(transparent)]
    Hbm(#[from] HbmError),
    /// The monodromy matrix.
    #[error(transparent)]
    Floquet(#[from] FloquetError),
}

/// The brake as a [`StickSlipModel`] with the pairs of a DLFT balance at `mu`
/// (`harmonics`, `samples`, `epsilon` as the cycle was solved with).
pub fn brake_model<'a>(
    mb: &'a ModalBrake,
    contacts: Vec<squeal_hbm::FrictionContact>,
) -> StickSlipModel<'a> {
    let mut mb0 = mb.clone();
    mb0.mu = 0.0;
    let damping = match &mb.damping {
        ModalDamping::Diagonal(d) => LinearPart::Diagonal(d.clone()),
        full => LinearPart::Dense(full.to_dense()),
    };
    StickSlipModel {
        stiffness: LinearPart::Diagonal(mb.omega.iter().map(|w| w * w).collect()),
        damping,
        lift: mb.phi_n.clone(),
        smooth_jacobian: Box::new(move |x: &[f64]| mb0.reduced_jacobians(x, None).0),
        contacts,
    }
}

/// Floquet exponents of the brake's DLFT cycle `cycle` of the non-smooth law
/// ([`super::stick_slip_floquet`]).
pub fn dlft_floquet(
    mb: &ModalBrake,
    cycle: &DlftCycle,
    opts: &StickSlipFloquetOptions,
) -> Result<StickSlipFloquet, DlftFloquetError> {
    let p = &cycle.point;
    let mut b = brake_dlft(
        mb,
        p.harmonics,
        Some(cycle.samples),
        Some(&cycle.epsilon),
        p.omega,
    )?;
    set_mu(&mut b, p.parameter);
    let layout = HarmonicLayout::new(mb.nl(), p.harmonics)?;
    let mut r = vec![0.0; layout.len()];
    b.residual(&p.nl_coeffs, p.omega, &mut r)?;
    let states = b.states().to_vec();
    let predicted = b.predicted_multipliers().to_vec();
    let contacts = b.contacts_mut().to_vec();
    let model = brake_model(mb, contacts);
    let c = StickSlipCycle {
        layout,
        u: &p.nl_coeffs,
        omega: p.omega,
        states: &states,
        predicted: &predicted,
    };
    Ok(stick_slip_floquet(&model, &c, opts)?)
}
