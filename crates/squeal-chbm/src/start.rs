//! Where a CHBM solve or a time integration starts at friction μ: the static equilibrium of
//! eq (14) and the most unstable mode of the linearization there (eqs 20–22), inside a band.

use crate::solve::ChbmStart;
use squeal_brake::Brake;
use squeal_brake::equilibrium::{NewtonOptions, static_equilibrium};
use squeal_brake::spectrum::{Reference, spectrum};
use squeal_brake::sweep::Band;

/// Why there is no start at this μ.
#[derive(Debug, thiserror::Error)]
pub enum StartError {
    /// The static equilibrium or the complex eigenvalues at μ could not be computed.
    #[error(transparent)]
    Brake(#[from] squeal_brake::BrakeError),
    /// No in-band mode has a positive real part at μ.
    #[error("the brake is stable at mu = {mu} in the band: no limit cycle to compute")]
    Stable {
        /// The friction coefficient asked.
        mu: f64,
    },
}

/// Equilibrium at `mu` (Newton from `guess` if given) and the in-band mode of largest positive
/// real part.
pub fn start_at(
    brake: &Brake,
    reference: &Reference,
    mu: f64,
    band: &Band,
    newton: &NewtonOptions,
    guess: Option<&[f64]>,
) -> Result<ChbmStart, StartError> {
    let eq = static_equilibrium(brake, mu, guess, newton)?;
    let sp = spectrum(brake, reference, &eq)?;
    let j = (0..sp.values.len())
        .filter(|&j| band.contains(sp.frequency_hz(j)) && sp.values[j].re > 0.0)
        .max_by(|&a, &b| sp.values[a].re.total_cmp(&sp.values[b].re))
        .ok_or(StartError::Stable { mu })?;
    Ok(ChbmStart {
        lambda: sp.values[j],
        mode: sp.shape(&reference.basis, j),
        equilibrium: eq.x,
    })
}

/// Equilibrium at `mu` and the in-band mode whose frequency is nearest `omega` (rad/s), stable
/// or not: the start of a CHBM solve from a known cycle of frequency `omega` (a branch cycle,
/// below μ0 too, where no mode is unstable).
pub fn start_near(
    brake: &Brake,
    reference: &Reference,
    mu: f64,
    band: &Band,
    newton: &NewtonOptions,
    omega: f64,
) -> Result<ChbmStart, StartError> {
    let eq = static_equilibrium(brake, mu, None, newton)?;
    let sp = spectrum(brake, reference, &eq)?;
    let j = (0..sp.values.len())
        .filter(|&j| band.contains(sp.frequency_hz(j)) && sp.values[j].im > 0.0)
        .min_by(|&a, &b| {
            (sp.values[a].im - omega)
                .abs()
                .total_cmp(&(sp.values[b].im - omega).abs())
        })
        .ok_or(StartError::Stable { mu })?;
    Ok(ChbmStart {
        lambda: sp.values[j],
        mode: sp.shape(&reference.basis, j),
        equilibrium: eq.x,
    })
}
