//! `squeal chbm`'s single DLFT cycle past the reach of its direct starts (issue 24, item 4;
//! docs/stick_slip.md, "`squeal chbm` and `squeal run`'s single cycle").
//!
//! **Why.** From the 3-harmonic CHBM cycle (and from the V/20 regularized cycle) at μ, DLFT's
//! Levenberg–Marquardt solve reaches the exact stick–slip cycle only while the pads barely
//! stick: on the coarse bundled brake at 3 km/h up to about 1.05 μ0 (sliding margin about
//! 0.96), not at 1.054 μ0 and above. `squeal branch` reaches every cycle to 1.31 μ0 by
//! continuing DLFT in μ from the last converged cycle ([`squeal_chbm::stick_dlft_walk`]). The
//! single cycle has no converged cycle below it, so it makes one.
//!
//! **What.** [`walk_from_below`] looks for a lower μ where DLFT converges from that μ's own CHBM
//! cycle: it solves CHBM at `μ (1 - f)` for `f` in [`BELOW`] in turn (above the Hopf point),
//! skips those whose permanent-sliding cycle has a sliding margin below [`MARGIN_TO_TRY`] (the
//! pads stick there too much for the direct start; each such DLFT attempt would cost up to 200
//! Levenberg–Marquardt iterations), and solves DLFT from the first other one. From the first
//! that converges it walks to μ with [`squeal_chbm::stick_dlft_walk::dlft_walk`], the branch's
//! own walk and options. A cycle the walk returns is as exact as any (the walk's steps are
//! ordinary DLFT solves with the converged-residual rule, 1e-9 of the largest static pair
//! force); when no lower μ converges or the walk stops short, the caller fails with the report
//! instead of giving an approximate cycle.

use crate::model::{Model, quiet};
use squeal_brake::analysis::LinearStability as Stability;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::branch::BranchPoint;
use squeal_chbm::stick_branch::point_margin;
use squeal_chbm::stick_dlft::{DlftCycle, DlftOptions, dlft_cycle};
use squeal_chbm::stick_dlft_walk::{WalkOptions, dlft_walk};
use squeal_chbm::{ChbmOptions, Outcome, RESTART_AMPLITUDES};
use squeal_hbm::{HarmonicLayout, PhaseCondition};

/// The lower μ tried as the walk's start, as fractions below the requested μ, nearest first:
/// fine near μ (a CHBM solve costs about a second, a DLFT walk step several), then every 2 %
/// to 30 %, so that the first tried at or above [`MARGIN_TO_TRY`] lies within 2 % of μ above
/// where the margin crosses it: the walk from there is shorter. The list ended at 16 % with
/// 12 % and 16 % next to each other; on the coarse bundled brake at 3 km/h, whose sliding
/// margin is at least [`MARGIN_TO_TRY`] only below about 1.04 μ0, that reached no start above
/// about 1.19 μ0 (none at 1.3 μ0) and at 1.15 μ0 started from 1.012 μ0 (margin 1.070)
/// (docs/stick_slip.md). Lower μ at or below the Hopf point are not tried (there the branch of
/// a subcritical Hopf point has a second, small cycle).
pub const BELOW: [f64; 21] = [
    0.005, 0.01, 0.015, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.10, 0.12, 0.14, 0.16, 0.18,
    0.20, 0.22, 0.24, 0.26, 0.28, 0.30,
];

/// The smallest sliding margin of a lower μ's permanent-sliding cycle for which DLFT is tried
/// from it: on the coarse bundled brake at 3 km/h DLFT converged from the sliding cycle at
/// margins 1.022, 0.983 and 0.965 and stopped short at 0.956 (1.0436 μ0) and below
/// (docs/stick_slip.md).
pub const MARGIN_TO_TRY: f64 = 0.97;

/// How the single cycle was reached by a walk in μ.
#[derive(Clone, Debug, Default)]
pub struct SingleWalk {
    /// The lower μ tried for the walk's start, in order, with what happened there.
    pub starts: Vec<(f64, String)>,
    /// The μ the walk started from (DLFT converged there from its CHBM cycle), if any.
    pub from_mu: Option<f64>,
    /// The walk's DLFT solves: μ, relative residual, converged.
    pub solves: Vec<(f64, f64, bool)>,
    /// Whether the walk reached the requested μ with a converged cycle.
    pub reached: bool,
}

impl SingleWalk {
    /// One paragraph for the terminal (μ as ratios to `mu_ref`, named `ref_name`).
    pub fn text(&self, mu_ref: f64, ref_name: &str) -> String {
        let starts: Vec<String> = self
            .starts
            .iter()
            .map(|(m, what)| format!("{:.5} {ref_name}: {what}", m / mu_ref))
            .collect();
        let solves: Vec<String> = self
            .solves
            .iter()
            .map(|(m, r, ok)| {
                format!(
                    "{:.5} {ref_name} {r:.1e}{}",
                    m / mu_ref,
                    if *ok {
                        ""
                    } else {
                        " (stopped short, step halved)"
                    }
                )
            })
            .collect();
        let mut s = format!("lower mu tried for a start: {}", starts.join("; "));
        if let Some(from) = self.from_mu {
            s += &format!(
                "; walked in mu from {:.5} {ref_name} in {} DLFT solves (mu, relative residual): {}",
                from / mu_ref,
                self.solves.len(),
                solves.join(", ")
            );
        }
        s
    }

    /// The same as JSON (μ absolute).
    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({
            "starts": self.starts.iter().map(|(m, w)| serde_json::json!({"mu": m, "outcome": w})).collect::<Vec<_>>(),
            "from_mu": self.from_mu,
            "solves": self.solves.iter().map(|(m, r, ok)| serde_json::json!({"mu": m, "relative_residual": r, "converged": ok})).collect::<Vec<_>>(),
            "reached": self.reached,
        })
    }
}

/// The CHBM cycle of `m` at `mu` as a branch point, with its phase dof, or why not.
fn sliding_cycle(
    m: &Model,
    st: &Stability,
    mu: f64,
) -> Result<(ModalBrake, BranchPoint, usize), String> {
    let (start, mb) = crate::chbm::start(m, st, mu, None).map_err(|e| e.to_string())?;
    let (sol, _) = crate::chbm::solve_with_restarts(
        &mb,
        &start,
        &ChbmOptions::default(),
        &RESTART_AMPLITUDES,
        &quiet,
    )
    .map_err(|e| e.to_string())?;
    if sol.outcome != Outcome::LimitCycle {
        return Err(format!("no CHBM limit cycle ({})", sol.outcome));
    }
    let point = crate::cycle_stick::as_point(&mb, mu, &sol).map_err(|e| e.to_string())?;
    let layout = HarmonicLayout::new(mb.nl(), sol.harmonics).map_err(|e| e.to_string())?;
    let PhaseCondition::FirstSineZero { dof } =
        PhaseCondition::strongest_dof(&layout, &sol.nl_coeffs).map_err(|e| e.to_string())?;
    Ok((mb, point, dof))
}

/// The DLFT cycle of the brake `mb` at `mu` reached by a walk in μ from a lower μ where DLFT
/// converges from its own CHBM cycle (module docs), with `opts` (harmonics, samples, ε). The
/// cycle is `Some` only when the walk reached `mu` converged.
pub fn walk_from_below(
    m: &Model,
    st: &Stability,
    mb: &ModalBrake,
    mu: f64,
    opts: &DlftOptions,
) -> Result<(Option<DlftCycle>, SingleWalk), String> {
    let mut report = SingleWalk::default();
    let speeds = squeal_chbm::stick_branch::surface_speeds(mb).map_err(|e| e.to_string())?;
    let mu0 = st.sweep.hopf.as_ref().map(|h| h.mu0);
    for f in BELOW {
        let below = mu * (1.0 - f);
        if mu0.is_some_and(|m0| below <= m0) {
            report
                .starts
                .push((below, "at or below the Hopf point, not tried".to_string()));
            break;
        }
        let (mbl, point, dof) = match sliding_cycle(m, st, below) {
            Ok(c) => c,
            Err(e) => {
                report.starts.push((below, e));
                continue;
            }
        };
        let margin = point_margin(&mbl, &point, &speeds).map_err(|e| e.to_string())?;
        if margin.min < MARGIN_TO_TRY {
            report.starts.push((
                below,
                format!(
                    "sliding margin {:.3} below {MARGIN_TO_TRY}, not tried",
                    margin.min
                ),
            ));
            continue;
        }
        let d = dlft_cycle(mb, below, &point, dof, opts).map_err(|e| e.to_string())?;
        if !d.converged {
            report.starts.push((
                below,
                format!(
                    "sliding margin {:.3}, DLFT stopped short (relative residual {:.1e})",
                    margin.min, d.point.residual
                ),
            ));
            continue;
        }
        report.starts.push((
            below,
            format!(
                "sliding margin {:.3}, DLFT converged (relative residual {:.1e})",
                margin.min, d.point.residual
            ),
        ));
        report.from_mu = Some(below);
        let mut first = d.point;
        first.parameter = below;
        let w = dlft_walk(mb, &[first], mu, dof, opts, &WalkOptions::default())
            .map_err(|e| e.to_string())?;
        report.solves = w.solves;
        report.reached = w.reached;
        return Ok((w.cycle.filter(|_| w.reached), report));
    }
    Ok((None, report))
}
