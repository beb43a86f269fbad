//! A second unstable mode inside the branch's friction range (issue 24, item 2): `squeal
//! branch` follows one mode's cycles from the Hopf point, but where the friction sweep shows a
//! second in-band mode going unstable while the first still is, the brake's answer there is
//! the generalized CHBM's ([`crate::two_mode`]), not the branch's cycle alone.
//!
//! From the sweep's crossings: the first in-band crossing of another branch than the Hopf
//! point's whose bracket lies inside the computed branch's μ range and at whose upper end the
//! Hopf mode is unstable too. Its onset is refined and its criticality computed
//! ([`squeal_chbm::multi::onset`]); the two-mode answer is then computed just past it, at
//! `μ0' (1 + 5e-5)`: a two-mode torus is born near the second onset, and on the two-pad brake
//! of docs/verification.md ("A brake with both modes supercritical") it exists only within
//! about 1e-4 of `μ0'` above it (its branch folds there).

use crate::Pipeline;
use crate::branch::BranchAnalysis;
use crate::two_mode::{TwoModeReport, report_text, two_mode};
use squeal_brake::analysis::LinearStability;
use squeal_brake::sweep::Crossing;
use squeal_chbm::multi::onset::{Onset, refine_onset};
use std::fmt::Write as _;

/// Where past the second onset the two-mode answer is computed (relative to `μ0'`).
pub const PAST_ONSET: f64 = 5e-5;

/// The second mode and the generalized CHBM's answer past its onset.
#[derive(Debug)]
pub struct SecondMode {
    /// The sweep's crossing.
    pub crossing: Crossing,
    /// The refined onset and its criticality, or why not.
    pub onset: Result<Onset, String>,
    /// The generalized CHBM's answer past it, or why not.
    pub answer: Result<TwoModeReport, String>,
}

/// The first in-band crossing of another mode inside the branch's μ range while the Hopf
/// mode is unstable (module docs).
pub fn second_crossing(st: &LinearStability, a: &BranchAnalysis) -> Option<Crossing> {
    let sweep = &st.sweep;
    let hopf = sweep.hopf.as_ref()?;
    let (lo, hi) = a
        .branch
        .points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
            (l.min(p.parameter), h.max(p.parameter))
        });
    sweep
        .crossings
        .iter()
        .find(|c| {
            let first_unstable = sweep
                .branches
                .get(hopf.branch)
                .and_then(|b| b.get(c.k + 1))
                .and_then(|&j| sweep.points[c.k + 1].spectrum.values.get(j))
                .is_some_and(|l| l.re > 0.0);
            c.in_band
                && c.branch != hopf.branch
                && Some(c.branch) != hopf.partner
                && c.mu_hi > lo
                && c.mu_lo < hi
                && first_unstable
        })
        .cloned()
}

/// The second mode of `a`'s branch and the two-mode answer past its onset, `None` when the
/// sweep shows none (module docs).
pub fn run(p: &Pipeline, st: &LinearStability, a: &BranchAnalysis) -> Option<SecondMode> {
    let crossing = second_crossing(st, a)?;
    let m = match p.model() {
        Ok(m) => m,
        Err(e) => {
            return Some(SecondMode {
                crossing,
                onset: Err(e.to_string()),
                answer: Err("the model failed".into()),
            });
        }
    };
    let onset = refine_onset(
        &m.brake,
        &st.reference,
        (crossing.mu_lo, crossing.mu_hi),
        crossing.frequency_hz,
        &m.sweep.newton,
        1e-9,
    )
    .map_err(|e| e.to_string());
    let answer = match &onset {
        Ok(o) => two_mode(p, o.bracket.1 * (1.0 + PAST_ONSET), 3).map_err(|e| e.to_string()),
        Err(e) => Err(format!("the onset was not refined: {e}")),
    };
    Some(SecondMode {
        crossing,
        onset,
        answer,
    })
}

/// The report's lines (empty without a second mode).
pub fn summary_text(s: Option<&SecondMode>) -> String {
    let Some(s) = s else {
        return String::new();
    };
    let mut out = String::new();
    let c = &s.crossing;
    let _ = write!(
        out,
        "second unstable mode inside the branch's range: {:.0} Hz unstable from mu in [{:.4}, {:.4}] while the branch's mode is unstable",
        c.frequency_hz, c.mu_lo, c.mu_hi
    );
    match &s.onset {
        Ok(o) => {
            let _ = write!(out, "; onset mu0' = {:.8}", o.mu0);
            match &o.normal_form {
                Ok(nf) => {
                    let _ = write!(
                        out,
                        ", first Lyapunov coefficient {:+.3e}: {}",
                        nf.l1,
                        nf.criticality()
                    );
                }
                Err(e) => {
                    let _ = write!(out, ", criticality not computed: {e}");
                }
            }
        }
        Err(e) => {
            let _ = write!(out, "; onset not refined: {e}");
        }
    }
    let _ = writeln!(
        out,
        "\n  the brake's answer there is the generalized CHBM's (also `squeal chbm SCENE --mu MU --two-mode`):"
    );
    match &s.answer {
        Ok(r) => {
            for l in report_text(r).lines() {
                let _ = writeln!(out, "  {l}");
            }
        }
        Err(e) => {
            let _ = writeln!(out, "  not computed: {e}");
        }
    }
    out
}

/// `branch.json`'s `two_mode`: the second mode's crossing, its refined onset and criticality,
/// and the generalized CHBM's answer past it, each part with its failure as text when it
/// failed (null without a second mode).
pub fn json(s: Option<&SecondMode>) -> serde_json::Value {
    let Some(s) = s else {
        return serde_json::Value::Null;
    };
    let c = &s.crossing;
    serde_json::json!({
        "crossing": {
            "frequency_hz": c.frequency_hz,
            "mu_bracket": [c.mu_lo, c.mu_hi],
        },
        "onset": match &s.onset {
            Ok(o) => serde_json::json!({
                "mu0": o.mu0,
                "mu_bracket": [o.bracket.0, o.bracket.1],
                "frequency_hz": o.lambda.im / std::f64::consts::TAU,
                "first_lyapunov_coefficient": o.normal_form.as_ref().ok().map(|nf| nf.l1),
                "criticality": match &o.normal_form {
                    Ok(nf) => nf.criticality().to_string(),
                    Err(e) => format!("not computed: {e}"),
                },
            }),
            Err(e) => serde_json::json!({ "failed": e }),
        },
        "answer": match &s.answer {
            Ok(r) => answer_json(r),
            Err(e) => serde_json::json!({ "failed": e }),
        },
    })
}

/// The generalized CHBM's answer as JSON: the unstable eigenvalues, each mode's cycle, the
/// verdict and the torus.
fn answer_json(r: &TwoModeReport) -> serde_json::Value {
    use std::f64::consts::TAU;
    let torus = match &r.torus {
        Ok(t) => {
            let f = t.point.frequencies_hz();
            let (pair, e) = t.point.loudest();
            serde_json::json!({
                "frequencies_hz": f,
                "truncation": crate::branch_torus::truncation_text(t.basis.truncation()),
                "pair": pair + 1,
                "closure_first_harmonics_m": t.first_harmonics,
                "swing_m": [e.swing_min, e.swing_max],
                "closure_m": [e.min, e.max],
                "constraints_per_s": r.constraints.as_ref().map(|c| match c {
                    Ok(l) => serde_json::json!(l.iter().map(|v| [v.re, v.im]).collect::<Vec<_>>()),
                    Err(e) => serde_json::json!({ "failed": e }),
                }),
                "lyapunov": r.lyapunov.as_ref().map(|l| match l {
                    Ok(s) => serde_json::json!({
                        "exponents_per_s": s.exponents,
                        "uncertainty_per_s": s.uncertainty(),
                        "stability": s.stability().to_string(),
                    }),
                    Err(e) => serde_json::json!({ "failed": e }),
                }),
            })
        }
        Err(e) => serde_json::json!({ "failed": e }),
    };
    serde_json::json!({
        "mu": r.mu,
        "unstable_eigenvalues": r.lambdas.iter().map(|l| serde_json::json!({
            "re_per_s": l.re,
            "frequency_hz": l.im / TAU,
        })).collect::<Vec<_>>(),
        "cycles": r.cycles.iter().map(|c| serde_json::json!({
            "mode": c.mode + 1,
            "outcome": c.solution.outcome.to_string(),
            "frequency_hz": c.solution.omega / TAU,
            "stability": match &c.floquet {
                Some(Ok(f)) => f.stability().to_string(),
                Some(Err(e)) => format!("Hill failed: {e}"),
                None => "no cycle".to_string(),
            },
        })).collect::<Vec<_>>(),
        "verdict": r.verdict.to_string(),
        "torus": torus,
    })
}
