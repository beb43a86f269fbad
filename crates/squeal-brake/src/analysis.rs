//! Section 3 of the paper as one call: the damping of eqs (12)–(13) with the coalescing pair
//! picked automatically or by index, the friction sweep, and the Hopf point.

use crate::equilibrium::NewtonOptions;
use crate::error::BrakeError;
use crate::modal::Damping;
use crate::model::Brake;
use crate::spectrum::Reference;
use crate::sweep::{
    Sweep, SweepOptions, SweepProgress, reference, reference_redamped, sweep_after,
    sweep_to_hopf_with, sweep_with,
};

/// Which two modes of the frictionless basis get eq (13)'s `D1`, `D2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PairChoice {
    /// The two modes that coalesce at the first in-band Hopf point of a sweep with the global
    /// damping only: `D1` on the one that stays stable, `D2` on the one that goes unstable
    /// (the paper's "Mode 1" and "Mode 2").
    Auto,
    /// Frictionless mode numbers (0-based) of Mode 1 and Mode 2.
    Modes(usize, usize),
}

/// The damping of eqs (12)–(13): a global modal ratio on every mode plus ratios on the pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DampingSpec {
    /// Modal damping ratio ζ on every frictionless mode: `D_jj = 2 ζ ω_j`.
    pub global_ratio: f64,
    /// Which two modes get `pair_ratios`.
    pub pair: PairChoice,
    /// Modal damping ratios `ζ1`, `ζ2` added on Mode 1 and Mode 2: `D_jj += 2 ζ ω_j`.
    pub pair_ratios: [f64; 2],
}

/// A linear stability analysis (complex eigenvalues against friction): the damping used, the
/// pair, the sweep. The stability of a limit cycle is `squeal_chbm::floquet::CycleStability`.
#[derive(Clone, Debug)]
pub struct LinearStability {
    /// The damping of the final sweep, its extras as `D_jj` values (s⁻¹) on the pair.
    pub damping: Damping,
    /// Frictionless mode numbers (0-based) of Mode 1 (stays stable) and Mode 2 (goes
    /// unstable), when known.
    pub pair: Option<(usize, usize)>,
    /// The frictionless reference of the final sweep, with that damping.
    pub reference: Reference,
    /// The friction sweep with that damping, and its Hopf point.
    pub sweep: Sweep,
    /// The sweep that named the pair ([`PairChoice::Auto`] with pair damping), before this
    /// one: its points and wall time (for benchmarks; the numbers do not depend on it).
    pub naming: Option<(usize, std::time::Duration)>,
}

/// The frictionless mode a tracked branch starts from: the largest modal coordinate of its
/// vector at the first sweep point.
pub fn basis_mode_of_branch(s: &Sweep, branch: usize) -> usize {
    largest(&branch_energy(s, branch))
}

/// The squared modal coordinates of `branch`'s vector at the first sweep point.
fn branch_energy(s: &Sweep, branch: usize) -> Vec<f64> {
    let j = s.branches[branch][0];
    s.points[0]
        .spectrum
        .modal(j)
        .iter()
        .map(|q| q.norm_sqr())
        .collect()
}

/// The index of the largest entry (the first of equals; 0 when empty).
fn largest(v: &[f64]) -> usize {
    let mut best = (f64::NEG_INFINITY, 0);
    for (i, &x) in v.iter().enumerate() {
        if x > best.0 {
            best = (x, i);
        }
    }
    best.1
}

/// The two distinct frictionless modes a coalescing pair of branches starts from: each
/// branch's largest modal coordinate, or, when both are the same mode (a sweep that starts
/// above μ = 0, where the pair's vectors already mix the two modes), the distinct pair
/// `(i, j)` of largest `|q_a,i|² + |q_b,j|²`. From μ = 0 the vectors are single modes and this
/// is [`basis_mode_of_branch`] of each.
pub fn basis_modes_of_pair(s: &Sweep, a: usize, b: usize) -> (usize, usize) {
    let (ea, eb) = (branch_energy(s, a), branch_energy(s, b));
    let (ia, ib) = (largest(&ea), largest(&eb));
    if ia != ib || ea.len() < 2 || eb.len() != ea.len() {
        return (ia, ib);
    }
    // The other mode of the pair: the runner-up of one branch, taken where it costs least.
    let second = |e: &[f64]| {
        let mut r = e.to_vec();
        if let Some(x) = r.get_mut(ia) {
            *x = f64::NEG_INFINITY;
        }
        largest(&r)
    };
    let (ja, jb) = (second(&ea), second(&eb));
    if ea[ia] + eb[jb] >= ea[ja] + eb[ib] {
        (ia, jb)
    } else {
        (ja, ib)
    }
}

/// Sweeps `mus` with the damping of `spec` (a preliminary sweep picks the pair when
/// [`PairChoice::Auto`] needs it).
pub fn stability(
    brake: &Brake,
    spec: &DampingSpec,
    mus: &[f64],
    opts: &SweepOptions,
) -> Result<LinearStability, BrakeError> {
    stability_with(brake, spec, mus, opts, &|_, _| {})
}

/// [`stability`], telling `progress` how far each sweep is.
pub fn stability_with(
    brake: &Brake,
    spec: &DampingSpec,
    mus: &[f64],
    opts: &SweepOptions,
    progress: SweepProgress,
) -> Result<LinearStability, BrakeError> {
    let newton: NewtonOptions = opts.newton;
    let global = Damping {
        global_ratio: spec.global_ratio,
        extra: vec![],
    };
    let has_pair_damping = spec.pair_ratios.iter().any(|r| *r != 0.0);
    let mut naming = None;
    let (pair, preliminary) = match spec.pair {
        PairChoice::Modes(a, b) => (Some((a, b)), None),
        PairChoice::Auto => {
            let start = std::time::Instant::now();
            let r = reference(brake, &global, &newton)?;
            // With pair damping this sweep only names the pair: it may stop at the Hopf point.
            let s = if has_pair_damping {
                sweep_to_hopf_with(brake, &r, mus, opts, progress)?
            } else {
                sweep_with(brake, &r, mus, opts, progress)?
            };
            naming = Some((s.points.len(), start.elapsed()));
            let pair = s
                .hopf
                .as_ref()
                .and_then(|h| h.partner.map(|p| basis_modes_of_pair(&s, p, h.branch)));
            (pair, Some((r, s)))
        }
    };
    if has_pair_damping && pair.is_none() {
        // No Hopf point in the band over the whole range with the global damping alone: no
        // pair coalesces, so the pair damping names no modes and is not applied. That the
        // brake is stable there is the answer, not an error.
        return match preliminary {
            Some((reference, sweep)) if sweep.hopf.is_none() => Ok(LinearStability {
                damping: global,
                pair: None,
                reference,
                sweep,
                naming: None,
            }),
            _ => Err(BrakeError::NoPairFound),
        };
    }
    let damping = match (pair, has_pair_damping) {
        (Some((m1, m2)), true) => Damping {
            global_ratio: spec.global_ratio,
            extra: vec![(m1, 0.0), (m2, 0.0)],
        },
        _ => global.clone(),
    };
    if let (Some((r, s)), false) = (&preliminary, has_pair_damping) {
        return Ok(LinearStability {
            damping,
            pair,
            reference: r.clone(),
            sweep: s.clone(),
            naming: None,
        });
    }
    // The preliminary sweep's frictionless equilibrium and modes serve again (they do not
    // depend on the damping): the same bits as solving them anew.
    let mut reference = match &preliminary {
        Some((r, _)) => reference_redamped(brake, r, &damping)?,
        None => reference(brake, &damping, &newton)?,
    };
    if let Some((m1, m2)) = pair {
        let n = reference.basis.omega.len();
        if m1 >= n || m2 >= n {
            return Err(BrakeError::PairOutOfRange {
                first: m1 + 1,
                second: m2 + 1,
                modes: n,
            });
        }
        // The extras are ratios of each mode's own frequency.
        let w = &reference.basis.omega;
        reference.damping = reference.damping.with_added(&[
            (m1, 2.0 * spec.pair_ratios[0] * w[m1]),
            (m2, 2.0 * spec.pair_ratios[1] * w[m2]),
        ]);
    }
    let damping = Damping {
        global_ratio: spec.global_ratio,
        extra: pair
            .map(|(m1, m2)| {
                vec![
                    (m1, 2.0 * spec.pair_ratios[0] * reference.basis.omega[m1]),
                    (m2, 2.0 * spec.pair_ratios[1] * reference.basis.omega[m2]),
                ]
            })
            .unwrap_or_default(),
    };
    // The preliminary sweep's static equilibria at the same friction values serve again
    // (crate::sweep::sweep_after: the same bits).
    let sweep = match &preliminary {
        Some((_, before)) => sweep_after(brake, &reference, mus, opts, progress, before)?,
        None => sweep_with(brake, &reference, mus, opts, progress)?,
    };
    Ok(LinearStability {
        damping,
        pair,
        reference,
        sweep,
        naming,
    })
}
