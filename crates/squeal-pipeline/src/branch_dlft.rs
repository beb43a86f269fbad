//! `squeal branch` with `[contact] stick_slip = "dlft"` (issue 24, item 4): every cycle the
//! branch recomputes because its sliding margin is below 1 ([`crate::branch_stick`]) is also
//! solved with exact Coulomb stick–slip (the dynamic Lagrangian frequency–time method,
//! [`squeal_chbm::stick_dlft::dlft_cycle`], 24 harmonics), at its μ, in order of μ: the first
//! from the permanent-sliding cycle, each next one continued in μ from the last two converged
//! ([`squeal_chbm::stick_dlft_walk`]), and when that stops short from the permanent-sliding
//! and the regularized cycle ([`squeal_chbm::stick_dlft_starts`]). The summary prints one line per cycle: frequency and loudest closure with their
//! changes against permanent sliding, how long the pairs stick, and whether the solve met its
//! tolerance, with the starts tried when it did not (docs/stick_slip.md). Every converged cycle
//! also gets its stability under the exact law: the Floquet multipliers of the non-smooth
//! system's monodromy with saltation matrices at its stick/slip switches
//! ([`squeal_chbm::stick_floquet`]), printed and written to `branch_dlft.csv` and
//! `branch.json` (`stick_slip.dlft`).

use crate::branch::BranchAnalysis;
use crate::model::Model;
use squeal_brake::analysis::LinearStability;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::branch::BranchPoint;
use squeal_chbm::stick_dlft::{DlftCycle, DlftOptions};
use squeal_chbm::stick_dlft_starts::dlft_from_starts;
use squeal_chbm::stick_dlft_walk::{WalkOptions, dlft_walk};
use squeal_chbm::stick_floquet::StickSlipFloquet;
use squeal_chbm::stick_floquet::brake::dlft_floquet;
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
    /// Its stability under the exact law (converged cycles only), or why it is not known.
    pub stability: Result<StickSlipFloquet, String>,
    /// Wall time of the stability (s).
    pub stability_seconds: f64,
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
        let seconds = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let stability = match &cycle {
            Ok(d) if d.converged => {
                dlft_floquet(&mb, d, &Default::default()).map_err(|e| e.to_string())
            }
            Ok(_) => Err("the cycle did not converge".to_string()),
            Err(_) => Err("no cycle".to_string()),
        };
        rows.push(DlftRow {
            point: c.point,
            mu: c.mu,
            cycle,
            reason,
            solves,
            seconds,
            stability,
            stability_seconds: t.elapsed().as_secs_f64(),
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
        "  the same cycles with exact Coulomb stick-slip (dynamic Lagrangian frequency-time method, Nacivet et al. 2003; {HARMONICS} harmonics, projection onto the friction cone as a clamp; the first cycle from the permanent-sliding one, each next continued in mu from the last converged ones, else from the permanent-sliding and the V/20 regularized cycle; stability of the exact law by the monodromy of the non-smooth variational equations with saltation matrices at the stick/slip switches, Leine & Nijmeijer 2004):\n"
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
                    "    point {} ({:.5} mu0): {:.4} Hz ({:+.2e}), pair {} {:.3} um ({:+.2} %), margin {:.3}, pairs stick up to {:.1} % of the period, residual {:.1e}, {} solves, {:.1} s{}; {}",
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
                    },
                    stability_text(r)
                )
            }
        };
    }
    out
}

/// The stability's words on one row.
fn stability_text(r: &DlftRow) -> String {
    match &r.stability {
        Err(e) => format!("stability not computed ({e})"),
        Ok(f) => floquet_words(f, r.stability_seconds),
    }
}

/// A DLFT cycle's exact-law Floquet verdict in words, with the leading exponent, its
/// multiplier's modulus, the analysis' error and its time `seconds`: a branch row's, and
/// `squeal chbm`'s single cycle's (`crate::cycle_stick`).
pub(crate) fn floquet_words(f: &StickSlipFloquet, seconds: f64) -> String {
    match f.leading() {
        Some(e) => format!(
            "{} (leading Floquet exponent {:+.2} {:+.1}i 1/s, |multiplier| {:.5}, error {:.1e} 1/s; {seconds:.1} s)",
            f.stability(),
            e.sigma.re,
            e.sigma.im.abs(),
            e.multiplier.norm(),
            f.error(),
        ),
        None => format!("{}", f.stability()),
    }
}

/// `(verdict, Re σ, |Im σ|, |ρ|, error)` of a row's stability.
fn stability_fields(r: &DlftRow) -> Option<(String, f64, f64, f64, f64)> {
    let f = r.stability.as_ref().ok()?;
    let e = f.leading()?;
    Some((
        f.stability().to_string(),
        e.sigma.re,
        e.sigma.im.abs(),
        e.multiplier.norm(),
        f.error(),
    ))
}

/// `branch.json`'s `stick_slip.dlft`: one object per DLFT cycle.
pub fn json(rows: &[DlftRow]) -> serde_json::Value {
    serde_json::Value::Array(
        rows.iter()
            .map(|r| {
                let c = r.cycle.as_ref().ok();
                let s = stability_fields(r);
                serde_json::json!({
                    "point": r.point,
                    "mu": r.mu,
                    "frequency_hz": c.map(|d| d.point.frequency_hz()),
                    "residual": c.map(|d| d.point.residual),
                    "converged": c.map(|d| d.converged),
                    "largest_stick_fraction": c.map(|d| d.stick_fractions.iter().copied().fold(0.0, f64::max)),
                    "stability": s.as_ref().map(|v| v.0.clone()),
                    "leading_exponent_re_per_s": s.as_ref().map(|v| v.1),
                    "leading_exponent_im_rad_per_s": s.as_ref().map(|v| v.2),
                    "largest_multiplier": s.as_ref().map(|v| v.3),
                    "exponent_error_per_s": s.as_ref().map(|v| v.4),
                    "stability_note": r.stability.as_ref().err(),
                })
            })
            .collect(),
    )
}

/// `branch_dlft.csv`: one row per DLFT cycle.
pub fn table(rows: &[DlftRow]) -> squeal_report::Table {
    let mut t = squeal_report::Table::new([
        "point",
        "mu",
        "frequency_hz",
        "residual",
        "converged",
        "largest_stick_fraction",
        "stability",
        "leading_exponent_re_per_s",
        "leading_exponent_im_rad_per_s",
        "largest_multiplier",
        "exponent_error_per_s",
    ]);
    for r in rows {
        let c = r.cycle.as_ref().ok();
        let s = stability_fields(r);
        let opt = |v: Option<f64>| v.map_or(String::new(), |x| format!("{x:e}"));
        t.push_row([
            r.point.to_string(),
            format!("{}", r.mu),
            c.map_or(String::new(), |d| format!("{}", d.point.frequency_hz())),
            opt(c.map(|d| d.point.residual)),
            c.map_or(String::new(), |d| d.converged.to_string()),
            opt(c.map(|d| d.stick_fractions.iter().copied().fold(0.0, f64::max))),
            s.as_ref()
                .map_or("not computed".to_string(), |v| v.0.clone()),
            opt(s.as_ref().map(|v| v.1)),
            opt(s.as_ref().map(|v| v.2)),
            opt(s.as_ref().map(|v| v.3)),
            opt(s.as_ref().map(|v| v.4)),
        ]);
    }
    t
}
