//! `"system"`'s level chosen by a cheap convergence test: the in-band eigenvalues of two
//! consecutive levels compared at a few friction values, instead of a whole stability sweep of
//! each level.
//!
//! # The test
//!
//! Level `i` is the brake projected on the face basis `T_i` (`crate::interface_system`); the
//! levels are nested (`span T_i ⊂ span T_(i+1)`: the in-band modes, then their friction
//! residuals, then more modes), so each is a Rayleigh–Ritz projection of the next, and of the
//! unreduced-interface brake. At the friction values `μ_c` of the sweep's first, middle and last
//! point, each level's static equilibrium (eq (14), the level's own) and the eigenvalues of its
//! brake linearized there (eqs (20)–(22), the scene's global damping; dense, eigenvalues only)
//! are computed, and
//!
//! `δ_i = max over μ_c and over the in-band λ of either level of |λ - λ'| / |λ|`,
//!
//! `λ'` the nearest eigenvalue of the other level at the same `μ_c`, measures how much level
//! `i` moved from level `i - 1`. The first level with `δ_i <= tolerance` is kept (the larger of
//! the two that agree), else the last. The tolerance (`[reduction] interface_tolerance`,
//! default [`squeal_scene::reduction::DEFAULT_SYSTEM_TOLERANCE`], 5e-3) bounds the change of
//! every in-band frequency and growth rate at the checked friction values, relative to `|λ|`;
//! μ0 moves much less. Measured from the in-band modes alone to those with their friction
//! residuals: `δ` = 2.1e-3, 1.5e-4, 2.6e-4 on the coarse one-pad, coarse ventilated and medium
//! ventilated nodal brakes, while μ0 moved by 2.2e-4, 7e-5, 6e-6; the next levels of the medium
//! brake (749, 1462, 2031, 2276 dofs) moved by 1.7e-4, 1.4e-5, 1.2e-5, 4.6e-6: the largest
//! changes are of eigenvalues far from the onset (at μ = 0.5 and 1), which converge as slowly
//! as a modal truncation, so a tolerance near the projected sweep's own (1e-5) would keep most
//! of the unreduced brake for a μ0 that has long settled (docs/reduction.md, "The default with
//! nodal contact").
//!
//! What it checks: the whole in-band spectrum at both ends and the middle of the sweep, where
//! the sweep's μ0 comes from. What it does not: the eigenvalues between the checked friction
//! values (the levels' eigenvalues are smooth in μ away from a coalescence) and μ0 itself; the
//! kept level's sweep reports μ0 as any sweep does.
//!
//! # Cost
//!
//! Per level: the level's frictionless modal basis (a dense symmetric eigenproblem of its size
//! `n_i`), three equilibria (dense Newton steps of size `n_i`) and three eigenvalue-only dense
//! decompositions of the `2 n_i` state matrix: seconds at `n_i` of a few hundred, against a
//! whole projected sweep (its truncation check, 41 or more spectra and the Hopf refinement) per
//! level before.

use crate::error::Result;
use crate::interface::{Candidate, Head, InterfaceLevel};
use crate::model::{Log, Model};
use faer::c64;
use squeal_brake::equilibrium::{Equilibrium, static_equilibrium};
use squeal_brake::linearized::LinearizedBrake;
use squeal_brake::modal::Damping;
use squeal_brake::spectrum::eigenvalues_of;
use squeal_brake::sweep::{Band, reference};
use std::time::Instant;

/// The friction values the levels are compared at: the first, middle and last of `mus`.
pub fn check_mus(mus: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = match mus.len() {
        0 => Vec::new(),
        n => vec![mus[0], mus[(n - 1) / 2], mus[n - 1]],
    };
    out.dedup();
    out
}

/// The eigenvalues (`Im λ >= 0`) of `model`'s brake at each of `mus`, linearized at its own
/// equilibria, with the scene's global modal damping.
pub fn eigenvalues_at(model: &Model, mus: &[f64]) -> Result<Vec<Vec<c64>>> {
    let brake = &model.brake;
    let newton = &model.sweep.newton;
    let damping = Damping {
        global_ratio: model.damping.global_ratio,
        extra: Vec::new(),
    };
    let r = reference(brake, &damping, newton)?;
    let lin = LinearizedBrake::new(brake, &r)?;
    let mut last: Option<Equilibrium> = None;
    let mut out = Vec::with_capacity(mus.len());
    for &mu in mus {
        // From the previous check's state, else by the load ramp from scratch.
        let from = last.as_ref().map(|e| e.x.as_slice());
        let eq = match static_equilibrium(brake, mu, from, newton) {
            Ok(eq) => eq,
            Err(_) => static_equilibrium(brake, mu, None, newton)?,
        };
        let (dk, dc) = lin.dense_change(&lin.coupling(brake, &eq));
        out.push(eigenvalues_of(&r.basis, &r.damping, &dk, dc.as_ref())?);
        last = Some(eq);
    }
    Ok(out)
}

/// The largest relative distance `|λ - λ'| / |λ|` from an in-band eigenvalue of either set to
/// the nearest of the other, over the checked friction values (module documentation).
pub fn change(a: &[Vec<c64>], b: &[Vec<c64>], band: &Band) -> f64 {
    let tau = std::f64::consts::TAU;
    let one_way = |from: &[c64], to: &[c64]| -> f64 {
        from.iter()
            .filter(|l| band.contains(l.im / tau))
            .map(|l| {
                to.iter()
                    .map(|m| (l - m).norm() / l.norm().max(f64::MIN_POSITIVE))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    a.iter()
        .zip(b)
        .map(|(x, y)| one_way(x, y).max(one_way(y, x)))
        .fold(0.0, f64::max)
}

/// `"auto"` by the cheap test: builds each candidate of `levels` in turn (nested, ascending),
/// compares its in-band eigenvalues at [`check_mus`] with the one before, and keeps the first
/// that moved by at most `tolerance`, else the last.
pub fn auto(
    model: &Model,
    mus: &[f64],
    log: Log,
    head: Head,
    levels: impl Iterator<Item = Result<Candidate>>,
    tolerance: f64,
    what: &str,
) -> Result<Model> {
    let checked = check_mus(mus);
    let mut done: Vec<InterfaceLevel> = Vec::new();
    let mut previous: Option<Vec<Vec<c64>>> = None;
    let mut kept: Option<(Model, String)> = None;
    for c in levels {
        let t = Instant::now();
        let c = c?;
        let values = eigenvalues_at(&c.model, &checked)?;
        let moved = previous
            .as_ref()
            .map(|p| change(p, &values, &c.model.sweep.band));
        let level = InterfaceLevel {
            kept: c.kept,
            basis: c.basis,
            dofs: c.model.brake.size(),
            hopf: None,
            swept: false,
            change: moved,
            seconds: t.elapsed().as_secs_f64(),
        };
        log(&format!(
            "  {}, {} dofs: {} ({:.1} s)",
            level.basis,
            level.dofs,
            moved.map_or("first level".into(), |d| format!(
                "in-band eigenvalues moved by {d:.2e} (relative) from the level before"
            )),
            level.seconds
        ));
        done.push(level);
        let settled = moved.is_some_and(|d| d <= tolerance);
        kept = Some((c.model, String::new()));
        if let (true, Some(d)) = (settled, moved) {
            let why = format!(
                "the first of {what} whose in-band eigenvalues at mu = {} moved by at most the tolerance from the level before: {d:.2e} <= {tolerance:e} (relative, [reduction] interface_tolerance)",
                list(&checked)
            );
            kept = kept.map(|(m, _)| (m, why));
            break;
        }
        previous = Some(values);
    }
    let (mut m, mut reason) = kept.ok_or(crate::error::PipelineError::NoPart { part: "disc" })?;
    if reason.is_empty() {
        reason = format!(
            "none of {what} moved by less than {tolerance:e} from the one before at mu = {}: the last kept (the most the basis offers)",
            list(&checked)
        );
    }
    m.interface = Some(head.summary(model.brake.size(), Some(tolerance), done, reason, checked));
    Ok(m)
}

/// `0, 0.5, 1`.
fn list(mus: &[f64]) -> String {
    mus.iter()
        .map(|m| format!("{m}"))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn check_mus_are_the_ends_and_the_middle() {
        assert_eq!(check_mus(&[0.0, 0.25, 0.5, 0.75, 1.0]), vec![0.0, 0.5, 1.0]);
        assert_eq!(check_mus(&[0.3]), vec![0.3]);
        assert!(check_mus(&[]).is_empty());
    }

    /// The change is the worse of the two directions: an in-band eigenvalue missing from one
    /// level counts with its distance to the nearest one there.
    #[test]
    fn change_matches_each_in_band_eigenvalue_both_ways() {
        let band = Band {
            valid_max_hz: f64::INFINITY,
            user: Some((1000.0, 2000.0)),
        };
        let w = |f: f64| c64::new(-1.0, std::f64::consts::TAU * f);
        let a = vec![vec![w(1500.0), w(5000.0)]];
        let b = vec![vec![w(1500.0 * (1.0 + 1e-6)), w(5000.0)]];
        let d = change(&a, &b, &band);
        // |Δλ| = 2π 1.5e-3 rad/s against |λ| = 2π 1500: 1e-6 to round-off of the products.
        assert!((d - 1e-6).abs() <= 1e-12, "{d:e}");
        // An eigenvalue in band in one level only: its distance to the nearest of the other.
        let c = vec![vec![w(1500.0), w(1800.0), w(5000.0)]];
        let d = change(&a, &c, &band);
        assert!((d - 300.0 / 1800.0).abs() <= 1e-6, "{d:e}");
    }
}
