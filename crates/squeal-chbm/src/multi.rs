//! Several unstable modes at one friction level: the generalized CHBM of Coudeyras, Nacivet &
//! Sinou ("Periodic and quasi-periodic solutions for multi-instabilities involved in brake
//! squeal", JSV 328, 2009, 520–540): the periodic part, the constraints, and the
//! quasi-periodic answer ([`quasi`], on the torus method of `squeal_hbm::torus`).
//!
//! **The constraint, one per unstable eigenvalue.** CHBM (section 4 of the paper) adds to the
//! harmonic balance (46) the condition (47) that the eigenvalue `λ` of the system linearized
//! over the motion (eqs 36–45) which continues the static solution's unstable eigenvalue has
//! `Re λ = 0`: the motion neither grows nor decays along that mode. With `m` unstable
//! eigenvalues `λ_1⁰ … λ_m⁰` at the static solution (eq 22), the generalized method asks the
//! same of each: the motion is `x(t) = x0 + Σ_j Re(X_j e^{iω_j t}) + …` with one base
//! frequency `ω_j` and one amplitude (the first harmonic `X_j`) per unstable mode, all unknown,
//! and the `m` constraints `Re λ_j = 0`, each `λ_j` followed from `λ_j⁰` through the
//! linearization of the current motion. As many unknown frequencies as constraints: the
//! answer is periodic (`m = 1`, or the other modes' amplitudes zero, or frequencies locked to
//! rational ratios) or quasi-periodic on an `m`-torus otherwise.
//!
//! **The linearization over a multi-frequency motion** ([`linearization`]). `J̄(s) = K̄ + s C̄`
//! is the force's tangent Jacobian averaged over the motion's samples (the zeroth Fourier
//! coefficient of `∂f/∂x`, `∂f/∂ẋ`: the first-order averaging of a perturbation at a
//! frequency that does not resonate with the motion). It is corrected, as little as possible,
//! so that it reproduces the force's fundamental at every base frequency:
//! `N(iω_j) X_j = F_j` for each `j` with `X_j ≠ 0`. With `a_j = F_j - J̄(iω_j) X_j` and
//! `Δ = [N_K - K̄, ω_s (N_C - C̄)]` (`ω_s` the first frequency, a scale), each condition is
//! two real rows of `Δ B = A`, `B`'s columns `[Re X_j; -r_j Im X_j]`, `[Im X_j; r_j Re X_j]`
//! (`r_j = ω_j/ω_s`) and `A`'s `[Re a_j, Im a_j]`; the least-norm `Δ = A (BᵀB)⁻¹ Bᵀ` is a
//! rank-`2m` update. For one frequency it is the describing function of
//! [`squeal_hbm::DescribingFunction`] (which takes the static Jacobian `J₀` as reference).
//! At a root of the harmonic balance the rows of harmonic `ω_j` read `Z(iω_j) X_j + F_j = 0`,
//! so `[Z(iω_j) + N(iω_j)] X_j = 0`: `iω_j` is an eigenvalue and its constraint is met
//! exactly, for any truncation. For a mode with no amplitude (`X_k = 0`) nothing is
//! corrected along it and `λ_k` is the averaged linearization's: its sign says whether the
//! motion of the other modes lets mode `k` grow.
//!
//! **The periodic case** ([`periodic`]). A periodic answer is a CHBM cycle of one unstable mode
//! `j` (the others at zero amplitude) that attracts: every other unstable mode decays on it.
//! Each unstable mode's cycle is computed by CHBM from its own eigenvector (eq 48); its
//! stability is Hill's Floquet analysis ([`crate::floquet`]), and the other modes'
//! `Re λ_k` under the cycle's averaged linearization say the same in the paper's terms. One
//! stable cycle: that mode wins and the answer is periodic. None: every mode grows on every
//! other's cycle, the answer is quasi-periodic (both amplitudes nonzero) and needs the torus
//! harmonic balance with the `m` constraints of [`linearization::ModeConstraints`]. Several:
//! the brake is multistable and the start decides.
//!
//! **The reference** ([`mod@reference`]): time integration of the whole brake from the static
//! solution perturbed along every unstable mode, and the spectrum of its steady state
//! (frequencies, amplitudes, whether one mode dies out).
//!
//! **The quasi-periodic case** ([`quasi`]): the torus balance with one base frequency per mode,
//! both amplitudes unknown and one phase condition per angle; its roots where both modes move
//! are the generalized CHBM's solutions (the constraints hold there exactly, as shown above),
//! and [`quasi::torus_constraints`] evaluates them on the root as a check. Started from the
//! mode cycles of [`periodic`] where they converged, else from eq (48) once per mode. The
//! constraint rows' gradient is not written: the solve does not need them (see [`quasi`]).
//! [`check`] compares a torus with a BDF run started on it.

pub mod check;
pub mod linearization;
pub mod onset;
pub mod periodic;
pub mod quasi;
pub mod reference;

use crate::solve::ChbmStart;
use crate::start::StartError;
use squeal_brake::Brake;
use squeal_brake::equilibrium::{NewtonOptions, static_equilibrium};
use squeal_brake::spectrum::{Reference, spectrum};
use squeal_brake::sweep::Band;

/// Every in-band unstable mode at `mu` (one per conjugate pair, `Im λ > 0`), largest growth
/// first, each with the static equilibrium: the starts of the generalized CHBM.
pub fn unstable_modes(
    brake: &Brake,
    reference: &Reference,
    mu: f64,
    band: &Band,
    newton: &NewtonOptions,
) -> Result<Vec<ChbmStart>, StartError> {
    let eq = static_equilibrium(brake, mu, None, newton)?;
    let sp = spectrum(brake, reference, &eq)?;
    let mut js: Vec<usize> = (0..sp.values.len())
        .filter(|&j| {
            band.contains(sp.frequency_hz(j)) && sp.values[j].re > 0.0 && sp.values[j].im > 0.0
        })
        .collect();
    js.sort_by(|&a, &b| sp.values[b].re.total_cmp(&sp.values[a].re));
    if js.is_empty() {
        return Err(StartError::Stable { mu });
    }
    Ok(js
        .into_iter()
        .map(|j| ChbmStart {
            lambda: sp.values[j],
            mode: sp.shape(&reference.basis, j),
            equilibrium: eq.x.clone(),
        })
        .collect())
}
