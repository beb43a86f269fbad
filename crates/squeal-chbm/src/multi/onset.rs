//! Where a further mode goes unstable: the friction value `μ0'` of a crossing other than the
//! sweep's Hopf point (which the sweep refines only for the first in-band crossing), and the
//! criticality there (the first Lyapunov coefficient of [`squeal_brake::criticality`]).
//!
//! The generalized CHBM ([`crate::multi`]) has a two-mode answer near the friction level where
//! the second mode's eigenvalue crosses: just past it, on the first mode's cycle, the second
//! mode's Floquet exponent crosses too (a Neimark–Sacker point of the first branch) and the
//! two-mode torus is born there. Whether it is born small and stable is the same question as
//! for one mode: the second Hopf point's `l1` (Kuznetsov, eq 5.39) says whether that mode's own
//! cycles grow from zero past it (`l1 < 0`) or exist before it (`l1 > 0`).
//!
//! **The bisection.** Between the sweep's bracket `[μ_lo, μ_hi]` (the mode stable at `μ_lo`,
//! unstable at `μ_hi`), the static equilibrium and the dense spectrum at the midpoint; the
//! crossing mode is the eigenvalue with `Im λ > 0` nearest the one followed at the previous
//! step (frequency first: a crossing is a slow change of `λ`); the half where `Re λ` changes
//! sign is kept until the bracket is `tol` of `μ` wide.

use crate::start::StartError;
use faer::c64;
use squeal_brake::Brake;
use squeal_brake::criticality::{NormalForm, normal_form};
use squeal_brake::equilibrium::{NewtonOptions, static_equilibrium};
use squeal_brake::spectrum::{Reference, spectrum};

/// A refined crossing.
#[derive(Clone, Debug)]
pub struct Onset {
    /// The middle of the final bracket.
    pub mu0: f64,
    /// The final bracket (stable at its lower end, unstable at its upper).
    pub bracket: (f64, f64),
    /// The crossing eigenvalue at the upper end.
    pub lambda: c64,
    /// The Hopf normal form there (`l1`, criticality), or why it failed.
    pub normal_form: Result<NormalForm, String>,
}

/// The crossing eigenvalue at `mu`: the one with `Im λ > 0` nearest `target`.
fn crossing_eigenvalue(
    brake: &Brake,
    reference: &Reference,
    mu: f64,
    target: c64,
    newton: &NewtonOptions,
) -> Result<c64, StartError> {
    let eq = static_equilibrium(brake, mu, None, newton)?;
    let sp = spectrum(brake, reference, &eq)?;
    sp.values
        .iter()
        .copied()
        .filter(|v| v.im > 0.0)
        .min_by(|a, b| (a - target).norm().total_cmp(&(b - target).norm()))
        .ok_or(StartError::Stable { mu })
}

/// Refines the crossing of the mode near `frequency_hz` inside `[mu_lo, mu_hi]` to `tol`
/// (relative) by bisection, and its normal form (module docs). Fails when the equilibrium or a
/// spectrum fails, or when the mode is not stable at `mu_lo` and unstable at `mu_hi`
/// ([`StartError::Stable`] at `mu_hi`).
pub fn refine_onset(
    brake: &Brake,
    reference: &Reference,
    (mu_lo, mu_hi): (f64, f64),
    frequency_hz: f64,
    newton: &NewtonOptions,
    tol: f64,
) -> Result<Onset, StartError> {
    let mut target = c64::new(0.0, std::f64::consts::TAU * frequency_hz);
    let mut hi_l = crossing_eigenvalue(brake, reference, mu_hi, target, newton)?;
    let lo_l = crossing_eigenvalue(brake, reference, mu_lo, hi_l, newton)?;
    if hi_l.re <= 0.0 || lo_l.re > 0.0 {
        return Err(StartError::Stable { mu: mu_hi });
    }
    target = hi_l;
    let (mut lo, mut hi) = (mu_lo, mu_hi);
    while hi - lo > tol * hi {
        let mid = 0.5 * (lo + hi);
        let l = crossing_eigenvalue(brake, reference, mid, target, newton)?;
        target = l;
        if l.re > 0.0 {
            (hi, hi_l) = (mid, l);
        } else {
            lo = mid;
        }
    }
    let mu0 = 0.5 * (lo + hi);
    let nf = normal_form(brake, reference, mu0, hi_l, newton).map_err(|e| e.to_string());
    Ok(Onset {
        mu0,
        bracket: (lo, hi),
        lambda: hi_l,
        normal_form: nf,
    })
}
