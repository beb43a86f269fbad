//! `squeal branch` with `[contact] stick_slip = "dlft"` (issue 24, item 4): every cycle the
//! branch recomputes because its sliding margin is below 1 ([`crate::branch_stick`]) is also
//! solved with exact Coulomb stick–slip (the dynamic Lagrangian frequency–time method,
//! [`squeal_chbm::stick_dlft::dlft_cycle`], 24 harmonics), at its μ, in order of μ: the first
//! from the permanent-sliding cycle, each next one continued in μ from the last two converged
//! ([`squeal_chbm::stick_dlft_walk`]), and when that stops short from the permanent-sliding
//! and the regularized cycle ([`squeal_chbm::stick_dlft_starts`]). The summary prints one line per cycle: frequency and loudest closure with their
//! changes against permanent sliding, how long the pairs stick, and whether the solve met its
//! tolerance, with the starts tried when it did not (docs/stick_slip.md).

use crate::branch::BranchAnalysis;
use crate::model::Model;
use squeal_brake::analysis::LinearStability;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::branch::BranchPoint;
use squeal_chbm::stick_dlft::{DlftCycle, DlftOptions};
use squeal_chbm::stick_dlft_starts::dlft_from_starts;
use squeal_chbm::stick_dlft_walk::{WalkOptions, dlft_walk};
use squeal_scene::StickSlipSetting;
use std::fmt::Write as _;
use std::time::Instant;

/// The regularized starts `squeal branch` and `squeal chbm` try after the permanent-sliding
/// cycle, as fractions of the slowest pair's disc speed: the branch's own V/20 only. Walking
/// further down ([`squeal_chbm::stick_dlft_starts::START_FRACTIONS`], to V/320) reached no DLFT
/// cycle on the coarse brake at 1.0540 and 1.0649 μ0 and cost about 40 s per cycle that stops
/// short (docs/stick_slip.md, "Past 1.05 μ0").
pub const DLFT_STARTS: [f64; 1] = [0.05];

/// Harmonics of the DLFT cycles (the sticking branch's).
const HARMONICS: usize = 24;

/// One recomputed cycle of the branch with DLFT.
pub struct DlftRow {
    /// Index of the permanent-sliding branch's point.
    pub point: usize,
    /// Its μ.
    pub mu: f64,
    /// The DLFT cycle, or why it could not be set up.
    pub cycle: Result<DlftCycle, String>,
    /// When the cycle stopped short: why, and the starts tried
    /// ([`squeal_chbm::stick_dlft_starts::StartedDlft::reason`]); empty when converged.
    pub reason: String,
    /// DLFT solves spent on it (walk steps and starts).
    pub solves: usize,
    /// Wall time spent on it (s).
    pub seconds: f64,
}

/// The DLFT cycles at the points of `a` the sticking branch recomputes (`None`: the scene does
/// not ask for DLFT, or nothing is recomputed).
pub fn recompute(
    m: &Model,
    st: &LinearStability,
    a: &BranchAnalysis,
    law: StickSlipSetting,
) -> Option<Vec<DlftRow>> {
    let StickSlipSetting::Dlft { epsilon_factor } = law else {
        return None;
    };
    let s = a.stick.as_ref()?.sticking.as_ref()?;
    let mb = ModalBrake::new(&m.brake, &st.reference, a.mu0());
    let mut o = DlftOptions::default();
    o.harmonics = Some(HARMONICS);
    o.epsilon_factor = epsilon_factor;
    // The last two converged cycles, each carrying its μ: the walk's starts.
    let mut done: Vec<BranchPoint> = Vec::new();
    let mut rows = Vec::new();
    for c in &s.cycles {
        let t = Instant::now();
        let (cycle, reason, solves) = match one_cycle(&mb, c.mu, a, c.point, &o, &done) {
            Ok((d, reason, solves)) => (Ok(d), reason, solves),
            Err(e) => (Err(e.to_string()), String::new(), 0),
        };
        if let Ok(d) = &cycle
            && d.converged
        {
            done.push(d.point.clone());
            if done.len() > 2 {
                done.remove(0);
            }
        }
        rows.push(DlftRow {
            point: c.point,
            mu: c.mu,
            cycle,
            reason,
            solves,
            seconds: t.elapsed().as_secs_f64(),
        });
    }
    Some(rows)
}

/// The DLFT cycle at `mu` (the branch's point `point`): continued in μ from the converged
/// cycles `done` when there are any ([`dlft_walk`]), else (or when the walk stops short) from
/// the permanent-sliding cycle and the regularized start ([`dlft_from_starts`]). With the
/// reason when it stopped short and the number of DLFT solves.
fn one_cycle(
    mb: &ModalBrake,
    mu: f64,
    a: &BranchAnalysis,
    point: usize,
    o: &DlftOptions,
    done: &[BranchPoint],
) -> Result<(DlftCycle, String, usize), squeal_chbm::stick_branch::StickError> {
    let phase = a.branch.phase_dof;
    let mut solves = 0;
    if !done.is_empty() {
        let w = dlft_walk(mb, done, mu, phase, o, &WalkOptions::default())?;
        solves += w.solves.len();
        if let (true, Some(d)) = (w.reached, w.cycle) {
            return Ok((d, String::new(), solves));
        }
    }
    let d = dlft_from_starts(mb, mu, &a.branch.points[point], phase, o, &DLFT_STARTS)?;
    solves += d.tried.len();
    let reason = d.reason();
    Ok((d.cycle, reason, solves))
}

/// The summary's lines on the DLFT cycles.
pub fn text(a: &BranchAnalysis, rows: &[DlftRow]) -> String {
    let mu0 = a.mu0();
    let mut out = format!(
        "  the same cycles with exact Coulomb stick-slip (dynamic Lagrangian frequency-time method, Nacivet et al. 2003; {HARMONICS} harmonics, projection onto the friction cone as a clamp; the first cycle from the permanent-sliding one, each next continued in mu from the last converged ones, else from the permanent-sliding and the V/20 regularized cycle; no stability computed for these cycles):\n"
    );
    for r in rows {
        let p = &a.branch.points[r.point];
        let (pair, p2p) = p.loudest();
        let _ = match &r.cycle {
            Err(e) => writeln!(
                out,
                "    point {} ({:.5} mu0): not computed: {e}",
                r.point,
                r.mu / mu0
            ),
            Ok(d) => {
                let q = &d.point;
                let most = d.stick_fractions.iter().copied().fold(0.0, f64::max);
                writeln!(
                    out,
                    "    point {} ({:.5} mu0): {:.4} Hz ({:+.2e}), pair {} {:.3} um ({:+.2} %), margin {:.3}, pairs stick up to {:.1} % of the period, residual {:.1e}, {} solves, {:.1} s{}",
                    r.point,
                    r.mu / mu0,
                    q.frequency_hz(),
                    q.omega / p.omega - 1.0,
                    pair + 1,
                    q.pairs[pair].peak_to_peak() * 1e6,
                    100.0 * (q.pairs[pair].peak_to_peak() / p2p - 1.0),
                    d.margin.min,
                    100.0 * most,
                    q.residual,
                    r.solves,
                    r.seconds,
                    if d.converged {
                        String::new()
                    } else {
                        format!(
                            "; NOT converged (relative residual {:.1e}; {}): approximate",
                            q.residual, r.reason
                        )
                    }
                )
            }
        };
    }
    out
}
