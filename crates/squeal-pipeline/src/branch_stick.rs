//! `squeal branch` where the pads stick (issue 24, item 4): when the scene gives the disc's
//! speed and a cycle of the permanent-sliding branch has a sliding margin below 1, the branch
//! is continued from the last cycle that still slides with every pair's element made to stick
//! (regularized Coulomb, [`squeal_chbm::stick_branch`]) and every such cycle is recomputed at
//! its μ. The summary, `branch.json` (`stick_slip`) and `branch_stick.csv` say which cycles
//! were recomputed, with which law, their margins and how much frequency, amplitude and
//! stability changed.

use crate::branch::BranchAnalysis;
use crate::model::{Log, Model};
use squeal_brake::analysis::LinearStability;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::branch::BranchOptions;
use squeal_chbm::physics::SlidingMargin;
pub use squeal_chbm::stick_branch::{StickBranch, StickCycle, StickOptions};
use squeal_chbm::stick_branch::{branch_margins, follow_sticking};
use squeal_report::Table;
use squeal_report::format::fmt_sig;
use std::fmt::Write as _;

/// The sliding margins along a branch and, where one falls below 1, the sticking part.
pub struct StickRun {
    /// The sliding margin of every point of the permanent-sliding branch.
    pub margins: Vec<SlidingMargin>,
    /// The branch with sticking contact (`None`: every margin is at least 1, or it failed and
    /// the failure was logged).
    pub sticking: Option<StickBranch>,
    /// The recomputed cycles with exact stick–slip, when the scene asks for it
    /// (`[contact] stick_slip = "dlft"`, [`crate::branch_dlft`]).
    pub dlft: Option<Vec<crate::branch_dlft::DlftRow>>,
}

/// The margins and the sticking part of the branch of `a` (`None`: the scene gives no disc
/// speed, or the margins could not be measured, which is logged).
pub fn recompute(
    m: &Model,
    st: &LinearStability,
    a: &BranchAnalysis,
    opts: &BranchOptions,
    stick: &StickOptions,
    log: Log,
) -> Option<StickRun> {
    if m.disc.is_none() || m.brake.pairs.iter().any(|p| p.surface_speed.is_none()) {
        return None;
    }
    let mb = ModalBrake::new(&m.brake, &st.reference, a.mu0());
    let margins = match branch_margins(&mb, &a.branch) {
        Ok(g) => g,
        Err(e) => {
            log(&format!(
                "stick-slip: the sliding margins could not be measured: {e}"
            ));
            return None;
        }
    };
    let sticking = match follow_sticking(&mb, &a.branch, opts, stick) {
        Ok(s) => s,
        Err(e) => {
            log(&format!(
                "stick-slip: the branch with sticking contact could not be computed: {e}"
            ));
            None
        }
    };
    Some(StickRun {
        margins,
        sticking,
        dlft: None,
    })
}

/// The law's description for reports.
fn law_text(s: &StickBranch) -> String {
    format!(
        "regularized Coulomb (each pair's element F_t(|v|) tanh(v/v_reg)), v_reg = {} m/s ({} of the slowest pair's disc speed {} m/s), {} harmonics, {} samples",
        fmt_sig(s.regularization_speed, 3),
        fmt_sig(s.regularization_speed / s.slowest_surface_speed, 3),
        fmt_sig(s.slowest_surface_speed, 4),
        s.harmonics,
        s.samples
    )
}

/// The loudest pair's peak-to-peak closure of the permanent-sliding point and of its
/// recomputed cycle, on the same pair (m).
fn closures(a: &BranchAnalysis, c: &StickCycle) -> (usize, f64, Option<f64>) {
    let (pair, p2p) = a.branch.points[c.point].loudest();
    let stick = c.cycle.as_ref().map(|s| s.pairs[pair].peak_to_peak());
    (pair, p2p, stick)
}

/// What `squeal branch` prints about stick–slip (nothing without a disc speed).
pub fn summary_text(a: &BranchAnalysis) -> String {
    let mut out = String::new();
    let Some(run) = &a.stick else {
        return out;
    };
    let mu0 = a.mu0();
    let Some(s) = &run.sticking else {
        if let Some((i, g)) = run
            .margins
            .iter()
            .enumerate()
            .min_by(|x, y| x.1.min.total_cmp(&y.1.min))
        {
            let _ = writeln!(
                out,
                "stick-slip: the sliding margin (disc surface speed / largest tangential vibration velocity) stays above 1 along the branch, smallest {:.3} at point {i} ({:.5} mu0, pair {}): permanent sliding (eq 9) holds, no cycle recomputed",
                g.min,
                a.branch.points[i].parameter / mu0,
                g.pair + 1
            );
        }
        return out;
    };
    let first = s
        .margins
        .iter()
        .position(|m| !m.sliding())
        .unwrap_or(s.start);
    let _ = writeln!(
        out,
        "stick-slip: the sliding margin (disc surface speed / largest tangential vibration velocity) falls below 1 at point {} (mu = {:.6}, {:.5} mu0, margin {:.3} at pair {}): the permanent-sliding law (eq 9) is not valid there",
        first,
        a.branch.points[first].parameter,
        a.branch.points[first].parameter / mu0,
        s.margins[first].min,
        s.margins[first].pair + 1
    );
    let _ = writeln!(
        out,
        "  branch continued from point {} (margin {:.3}) with {}: {} cycles in {:.2} s ({})",
        s.start,
        s.margins[s.start].min,
        law_text(s),
        s.branch.points.len(),
        s.time.as_secs_f64(),
        s.branch.stop
    );
    let t = cycles_table(a, s);
    let _ = writeln!(
        out,
        "  {} cycles of the branch recomputed with the sticking law (loudest pair's closure):",
        s.cycles.len()
    );
    out.push_str(&t.to_text());
    if let Some(rows) = &run.dlft {
        out.push_str(&crate::branch_dlft::text(a, rows));
    }
    out
}

/// The recomputed cycles: margin, frequency and closure before and after, the new margin and
/// the stability before -> after.
pub fn cycles_table(a: &BranchAnalysis, s: &StickBranch) -> Table {
    let mu0 = a.mu0();
    let mut t = Table::new([
        "point",
        "mu/mu0",
        "margin",
        "f sliding (Hz)",
        "f sticking (Hz)",
        "df/f",
        "p2p sliding (um)",
        "p2p sticking (um)",
        "change",
        "margin sticking",
        "stability sliding -> sticking",
    ]);
    for c in &s.cycles {
        let p = &a.branch.points[c.point];
        let (_, p2p, sp2p) = closures(a, c);
        let before = a
            .stability(c.point)
            .map_or("-".to_string(), |v| v.to_string());
        let after = match &c.floquet {
            Some(Ok(f)) => f.stability().to_string(),
            Some(Err(_)) => "not computed".into(),
            None => "-".into(),
        };
        let row = match &c.cycle {
            Some(q) => [
                format!("{:.4}", q.frequency_hz()),
                format!("{:+.2e}", q.omega / p.omega - 1.0),
                fmt_sig(sp2p.unwrap_or(f64::NAN) * 1e6, 4),
                format!("{:+.2}%", 100.0 * (sp2p.unwrap_or(f64::NAN) / p2p - 1.0)),
                c.stick_margin
                    .as_ref()
                    .map_or("-".into(), |m| format!("{:.3}", m.min)),
            ],
            None => [
                "not reached".to_string(),
                "-".into(),
                "-".into(),
                "-".into(),
                "-".into(),
            ],
        };
        let [fs, df, ps, ch, ms] = row;
        t.push_row([
            c.point.to_string(),
            format!("{:.5}", c.mu / mu0),
            format!("{:.3}", c.margin.min),
            format!("{:.4}", p.frequency_hz()),
            fs,
            df,
            fmt_sig(p2p * 1e6, 4),
            ps,
            ch,
            ms,
            format!("{before} -> {after}"),
        ]);
    }
    t
}

/// The report's paragraph on stick-slip and the table of recomputed cycles (`None` without
/// a disc speed).
pub fn report_part(a: &BranchAnalysis) -> Option<(String, Option<Table>)> {
    a.stick.as_ref()?;
    let text = summary_text(a);
    let head: Vec<&str> = text
        .lines()
        .take_while(|l| !l.starts_with("point"))
        .filter(|l| !l.trim_start().ends_with("(loudest pair's closure):"))
        .map(str::trim)
        .collect();
    let table = a
        .stick
        .as_ref()
        .and_then(|r| r.sticking.as_ref())
        .map(|s| cycles_table(a, s));
    Some((head.join(" "), table))
}

/// `branch.json`'s `stick_slip` (null without a disc speed or when every cycle slides).
pub fn json(a: &BranchAnalysis) -> serde_json::Value {
    let Some(run) = &a.stick else {
        return serde_json::Value::Null;
    };
    let Some(s) = &run.sticking else {
        return serde_json::json!({
            "margins": run.margins.iter().map(|m| m.min).collect::<Vec<_>>(),
            "margin_pairs": run.margins.iter().map(|m| m.pair + 1).collect::<Vec<_>>(),
            "recomputed": false,
        });
    };
    serde_json::json!({
        "recomputed": true,
        "law": "regularized Coulomb: each pair's element F_t(|v|) tanh(v / v_reg)",
        "regularization_speed_m_per_s": s.regularization_speed,
        "slowest_surface_speed_m_per_s": s.slowest_surface_speed,
        "harmonics": s.harmonics,
        "samples": s.samples,
        "start_point": s.start,
        "margins": s.margins.iter().map(|m| m.min).collect::<Vec<_>>(),
        "margin_pairs": s.margins.iter().map(|m| m.pair + 1).collect::<Vec<_>>(),
        "sticking_branch_points": s.branch.points.len(),
        "sticking_branch_stop": s.branch.stop.to_string(),
        "cycles": s.cycles.iter().map(|c| {
            let p = &a.branch.points[c.point];
            let (pair, p2p, sp2p) = closures(a, c);
            serde_json::json!({
                "point": c.point,
                "mu": c.mu,
                "margin": c.margin.min,
                "frequency_hz_sliding": p.frequency_hz(),
                "frequency_hz_sticking": c.cycle.as_ref().map(|q| q.frequency_hz()),
                "loudest_pair": pair + 1,
                "closure_p2p_m_sliding": p2p,
                "closure_p2p_m_sticking": sp2p,
                "margin_sticking": c.stick_margin.as_ref().map(|m| m.min),
                "stability_sliding": a.stability(c.point).map(|v| v.to_string()),
                "stability_sticking": c.floquet.as_ref().and_then(|f| f.as_ref().ok()).map(|f| f.stability().to_string()),
                "largest_multiplier_sticking": c.floquet.as_ref().and_then(|f| f.as_ref().ok()).map(|f| f.largest_multiplier()),
            })
        }).collect::<Vec<_>>(),
        "dlft": run.dlft.as_ref().map(|rows| crate::branch_dlft::json(rows)),
    })
}

/// `branch_stick.csv`: one row per point of the sticking branch.
pub fn table(s: &StickBranch) -> Table {
    let mut t = Table::new([
        "point",
        "mu",
        "frequency_hz",
        "loudest_pair",
        "loudest_closure_p2p_m",
        "largest_open_fraction",
        "residual",
    ]);
    for (i, p) in s.branch.points.iter().enumerate() {
        let (pair, c) = p.loudest();
        t.push_row([
            i.to_string(),
            format!("{}", p.parameter),
            format!("{}", p.frequency_hz()),
            (pair + 1).to_string(),
            format!("{c:e}"),
            format!("{}", p.largest_open_fraction()),
            format!("{:e}", p.residual),
        ]);
    }
    t
}
