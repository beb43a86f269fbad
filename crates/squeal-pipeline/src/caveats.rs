//! What a stability result rests on: the cases where μ0 says more about a modelling or a
//! numerical choice than about the brake, said next to the result (issue 20, item 4).
//!
//! - **An undamped model.** Without damping the friction coupling of two modes is a
//!   coalescence (a Krein collision): at μ0 two eigenvalues meet on the imaginary axis and
//!   split into `λ = ± s √(μ − μ0) + i ω`, so that `Re λ` has no finite slope at μ0 (any slope
//!   printed is that of the sweep's step) and the two modes of the pair grow and decay alike:
//!   which of them is "the unstable mode" is not defined by the model. The critical
//!   eigenvalue is double, so neither the sensitivities (first-order perturbation of a simple
//!   eigenvalue: not computed) nor the Hopf normal form (printed as indicative) apply.
//! - **A near-degenerate pair.** Two frictionless modes closer than
//!   [`NEAR_DEGENERATE_SPLIT`] of their frequency (a disc's doublet that the pads barely
//!   split) are coupled by any friction: the smaller their split, the smaller μ0, and the split
//!   itself is set by the mesh, the contact discretization and the kept modes rather than by
//!   the design. μ0 then moves with those knobs; `squeal study --kind convergence` shows by how much.
//! - **A Hopf point near the top of the valid band.** The reduced model's frequencies are
//!   converged up to the band's top (`valid_max_hz`, set by the kept modes); a Hopf point above
//!   [`BAND_TOP_FRACTION`] of it rests on the modes that the truncation treats worst.

use crate::model::Model;
use crate::reduce::ModeChoice;
use squeal_brake::analysis::LinearStability as Stability;
use std::fmt;

/// Relative split `|f2 − f1| / ((f1 + f2)/2)` of the coalescing pair below which its coupling
/// rests on the split more than on the friction (1 %: the doublets of a symmetric disc split by
/// its pads are 1e-4 to 1e-3 apart; the bundled brake's pair 7 %).
pub const NEAR_DEGENERATE_SPLIT: f64 = 0.01;

/// Fraction of the valid band's top above which a Hopf point is flagged.
pub const BAND_TOP_FRACTION: f64 = 0.8;

/// A warning attached to a stability result.
#[derive(Clone, Debug, PartialEq)]
pub enum Caveat {
    /// No damping at all: the Hopf point is a coalescence.
    Undamped,
    /// The coalescing pair is split by less than [`NEAR_DEGENERATE_SPLIT`].
    NearDegenerate {
        /// 1-based frictionless mode numbers.
        modes: (usize, usize),
        /// Their frequencies (Hz).
        hz: (f64, f64),
        /// `|f2 − f1| / ((f1 + f2)/2)`.
        split: f64,
    },
    /// The Hopf frequency is above [`BAND_TOP_FRACTION`] of the valid band's top.
    NearBandTop { hopf_hz: f64, valid_max_hz: f64 },
}

impl Caveat {
    /// A short name for tables and JSON.
    pub fn key(&self) -> &'static str {
        match self {
            Caveat::Undamped => "undamped",
            Caveat::NearDegenerate { .. } => "near_degenerate_pair",
            Caveat::NearBandTop { .. } => "near_band_top",
        }
    }
}

impl fmt::Display for Caveat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Caveat::Undamped => write!(
                f,
                "the model has no damping: mu0 is a coalescence, where Re(lambda) grows like sqrt(mu - mu0) (no finite slope), the two modes of the pair grow and decay alike, and the Hopf normal form (criticality, branch) assumes a simple eigenvalue, which a coalescence is not: take them as indicative; give [damping] to model the brake's"
            ),
            Caveat::NearDegenerate { modes, hz, split } => write!(
                f,
                "the coalescing modes #{} ({:.1} Hz) and #{} ({:.1} Hz) are {:.3} % apart (below {} %): any friction couples them, and mu0 rests on their split, which the mesh, the contact discretization and the kept modes set (mu0 is about proportional to it: a relative error e in either frequency moves mu0 by about {:.0} e, relative); check it with squeal stability --full or squeal study --kind convergence",
                modes.0,
                hz.0,
                modes.1,
                hz.1,
                100.0 * split,
                100.0 * NEAR_DEGENERATE_SPLIT,
                1.0 / split
            ),
            Caveat::NearBandTop {
                hopf_hz,
                valid_max_hz,
            } => write!(
                f,
                "the Hopf frequency {hopf_hz:.0} Hz is above {:.0} % of the valid band's top ({valid_max_hz:.0} Hz): it rests on the modes the reduction treats worst; keep more modes",
                100.0 * BAND_TOP_FRACTION
            ),
        }
    }
}

/// Whether a damping has no damping at all (no modal damping, and no dampers: the
/// reference's `D` is zero).
pub fn undamped(st: &Stability) -> bool {
    st.damping.global_ratio == 0.0
        && st.damping.extra.iter().all(|&(_, d)| d == 0.0)
        && st.reference.damping.max_abs() == 0.0
}

/// The caveats of a stability result (none when it has no Hopf point).
pub fn caveats(m: &Model, st: &Stability) -> Vec<Caveat> {
    let Some(h) = &st.sweep.hopf else {
        return Vec::new();
    };
    let mut out = Vec::new();
    if undamped(st) {
        out.push(Caveat::Undamped);
    }
    if let Some((m1, m2)) = st.pair {
        let hz = |j: usize| st.reference.basis.omega[j] / std::f64::consts::TAU;
        if let Some(c) = near_degenerate((m1 + 1, m2 + 1), (hz(m1), hz(m2))) {
            out.push(c);
        }
    }
    let valid_max_hz = m.sweep.band.valid_max_hz;
    if h.frequency_hz > BAND_TOP_FRACTION * valid_max_hz {
        out.push(Caveat::NearBandTop {
            hopf_hz: h.frequency_hz,
            valid_max_hz,
        });
    }
    out
}

/// The near-degenerate caveat of a pair of modes, when their split is below
/// [`NEAR_DEGENERATE_SPLIT`].
pub fn near_degenerate(modes: (usize, usize), hz: (f64, f64)) -> Option<Caveat> {
    let split = (hz.1 - hz.0).abs() / (0.5 * (hz.0 + hz.1));
    (split < NEAR_DEGENERATE_SPLIT).then_some(Caveat::NearDegenerate { modes, hz, split })
}

/// What the reduced model kept and why, one line: each part's fixed-interface modes, the
/// highest kept frequency, and the rule that chose them. The reduced brake's μ0 against the
/// full model with the kept modes: docs/reduction.md, "Reduced against full: the kept modes".
pub fn kept_modes_text(m: &Model) -> String {
    let parts: Vec<String> = m
        .rom
        .parts
        .iter()
        .map(|p| {
            let hz = &p.info.fixed_interface_hz;
            format!(
                "{} {} (up to {:.0} Hz)",
                p.info.name,
                hz.len(),
                hz.last().copied().unwrap_or(0.0)
            )
        })
        .collect();
    let build = m.rom.parts.first().and_then(|p| p.info.build.as_ref());
    let rule = match build.map(|b| b.modes) {
        Some(ModeChoice::Fixed(n)) => format!("the {n} lowest of each part"),
        Some(ModeChoice::Auto { fmax_hz, factor }) => {
            format!("every mode below {factor} x {fmax_hz:.0} Hz")
        }
        None => "as the reduced model was made".to_string(),
    };
    format!(
        "kept fixed-interface modes: {} ({rule}); squeal stability --full measures what they cost mu0\n",
        parts.join(", ")
    )
}

/// The caveats as lines `warning: ...`, empty when there are none.
pub fn caveats_text(caveats: &[Caveat]) -> String {
    caveats.iter().map(|c| format!("warning: {c}\n")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_doublet_split_by_less_than_one_percent_is_flagged_and_the_bundled_pair_is_not() {
        // The third-party disc of issue 20: a 5-diameter doublet 0.6 Hz apart at 6474 Hz.
        let c = near_degenerate((21, 22), (6474.0, 6474.6)).expect("flagged");
        let Caveat::NearDegenerate { split, .. } = c else {
            panic!("{c:?}")
        };
        assert!((split - 0.6 / 6474.3).abs() < 1e-12, "{split}");
        // The bundled medium brake's pair: modes #13 and #14 at 3861 and 4145 Hz (7.1 %).
        assert_eq!(near_degenerate((13, 14), (3861.0, 4145.0)), None);
        // 1.1 % apart: not flagged; 0.9 %: flagged.
        assert_eq!(near_degenerate((1, 2), (1000.0, 1011.06)), None);
        assert!(near_degenerate((1, 2), (1000.0, 1009.04)).is_some());
    }
}
