//! Where and how loud the brake squeals (issue 10): the branch of limit cycles born at the Hopf
//! point, followed in μ through its folds ([`squeal_chbm::branch`]), each cycle's stability
//! from its Floquet exponents by Hill's method ([`squeal_chbm::bifurcation`]), and what
//! `squeal branch` writes: `branch.csv`, `branch.json` and the bifurcation diagram.
//!
//! **The squeal range.** Above μ0 the equilibrium is unstable: squeal starts by itself. Where
//! the branch has stable cycles below μ0 (a subcritical Hopf point turned at a fold), the brake
//! squeals there too once a disturbance is large enough to reach them: from the lowest
//! friction with a stable cycle, normally the fold μ_fold. Between μ_fold and μ0 the unstable
//! cycles of the branch are the threshold between the two.

use crate::error::{PipelineError, Result, json_text};
use crate::model::{Log, Model};
use crate::stability;
use squeal_brake::analysis::LinearStability;
use squeal_brake::criticality::{Criticality, DEGENERATE_HINT, NormalForm};
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::bifurcation::{
    Bifurcation, BifurcationKind, BranchWithHill, bifurcations, cycle_of,
    follow_from_hopf_with_hill,
};
/// The branch's options, as the command line and researchers set them.
pub use squeal_chbm::branch::{BranchOptions, Harmonics};
use squeal_chbm::branch::{BranchPoint, LimitCycleBranch, cycles_at};
pub use squeal_chbm::floquet::HillOptions;
use squeal_chbm::floquet::hill as hill_exponents;
use squeal_chbm::floquet::{CycleStability as Stability, FloquetError, HillFloquet};
use squeal_report::format::fmt_sig;
use squeal_report::{
    Annotation, Dash, Figure, Layout, Marker, Panel, Rgb, Series, Table, write_svg_and_png,
};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

/// A branch with the stability of each of its cycles.
pub struct BranchAnalysis {
    /// The Hopf point's normal form (μ0, ω0, the first Lyapunov coefficient).
    pub normal_form: NormalForm,
    /// The followed branch.
    pub branch: LimitCycleBranch,
    /// Hill's exponents at each point (or why they could not be computed).
    pub floquet: Vec<std::result::Result<HillFloquet, FloquetError>>,
    /// Stability changes between consecutive points.
    pub bifurcations: Vec<Bifurcation>,
    /// Wall time the Floquet analyses took after the continuation ended (they run alongside
    /// it, on the other threads: [`follow_from_hopf_with_hill`]).
    pub floquet_time: Duration,
    /// The cycles at the friction values asked for ([`analyse`]'s `at`).
    pub at: Vec<CycleAt>,
    /// Each point's A-weighted level at the microphone (dB(A), [`crate::sound::branch_levels`]);
    /// empty when not computed.
    pub levels: Vec<f64>,
    /// The microphone the levels are taken at (m), when they were computed.
    pub microphone: Option<[f64; 3]>,
    /// The torus branches from the Neimark–Sacker points ([`crate::branch_torus`]); empty
    /// when not followed.
    pub tori: Vec<crate::branch_torus::TorusRun>,
    /// Where the sliding margin falls below 1: the branch with sticking contact and the
    /// recomputed cycles ([`crate::branch_stick`]); `None` when not computed.
    pub stick: Option<crate::branch_stick::StickRun>,
    /// A second mode unstable inside the branch's range and the generalized CHBM's answer
    /// past its onset ([`crate::branch_two_mode`]); `None` when there is none.
    pub two_mode: Option<crate::branch_two_mode::SecondMode>,
}

/// A cycle of the branch at a friction value asked for.
pub struct CycleAt {
    /// The friction value.
    pub mu: f64,
    /// Index of the branch point before it.
    pub after_point: usize,
    /// The cycle.
    pub cycle: BranchPoint,
    /// Its Floquet exponents.
    pub floquet: std::result::Result<HillFloquet, FloquetError>,
}

/// Where squeal can occur along the computed branch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SquealRange {
    /// μ0: beyond it the equilibrium is unstable.
    pub spontaneous_from: f64,
    /// The lowest friction with a stable cycle on the branch (a fold's, when the stable part
    /// starts at one), if any stable cycle was found.
    pub with_disturbance_from: Option<f64>,
    /// Whether `with_disturbance_from` is a fold of the branch (else: the lowest stable point).
    pub at_fold: bool,
}

impl BranchAnalysis {
    /// μ0.
    pub fn mu0(&self) -> f64 {
        self.normal_form.mu0
    }

    /// The verdict on point `i` (`None` when its analysis failed).
    pub fn stability(&self, i: usize) -> Option<Stability> {
        self.floquet.get(i)?.as_ref().ok().map(|f| f.stability())
    }

    /// The pair with the largest peak-to-peak closure anywhere on the branch (0-based).
    pub fn loudest_pair(&self) -> usize {
        let mut best = (0, 0.0);
        for p in &self.branch.points {
            let (i, c) = p.loudest();
            if c > best.1 {
                best = (i, c);
            }
        }
        best.0
    }

    /// Where squeal can occur.
    pub fn squeal_range(&self) -> SquealRange {
        let stable: Vec<usize> = (0..self.branch.points.len())
            .filter(|&i| self.stability(i) == Some(Stability::Stable))
            .collect();
        let lowest = stable.iter().copied().min_by(|&a, &b| {
            self.branch.points[a]
                .parameter
                .total_cmp(&self.branch.points[b].parameter)
        });
        let mut range = SquealRange {
            spontaneous_from: self.mu0(),
            with_disturbance_from: lowest.map(|i| self.branch.points[i].parameter),
            at_fold: false,
        };
        if let (Some(i), Some(mut mu)) = (lowest, range.with_disturbance_from) {
            // A fold next to the lowest stable point bounds the stable part.
            for f in &self.branch.folds {
                let near = f.after_point + 1 == i || f.after_point == i;
                if near && f.parameter < mu {
                    mu = f.parameter;
                    range.at_fold = true;
                }
            }
            range.with_disturbance_from = Some(mu);
        }
        range
    }
}

/// Follows the branch of `m` from its Hopf point and computes each cycle's Floquet exponents
/// (on the other threads while the continuation goes on), and the cycles at each friction
/// value of `at` (every crossing of the branch). `Ok(None)` when the sweep found no Hopf
/// point.
pub fn analyse(
    m: &Model,
    st: &LinearStability,
    opts: &BranchOptions,
    hill: &HillOptions,
    at: &[f64],
    log: Log,
) -> Result<Option<BranchAnalysis>> {
    let Some(nf) = stability::normal_form(m, st)? else {
        return Ok(None);
    };
    if nf.criticality() == Criticality::Degenerate {
        return Err(PipelineError::input("the Hopf point", DEGENERATE_HINT));
    }
    let mb = ModalBrake::new(&m.brake, &st.reference, nf.mu0);
    let BranchWithHill {
        branch,
        floquet,
        floquet_tail: floquet_time,
    } = follow_from_hopf_with_hill(&mb, &nf, opts, hill)?;
    log(&format!(
        "branch: {} cycles in {:.2} s ({}), Floquet exponents by Hill's method alongside, \
         done {:.2} s after it",
        branch.points.len(),
        branch.time.as_secs_f64(),
        branch.stop,
        floquet_time.as_secs_f64()
    ));
    let bifurcations = bifurcations(&branch, &floquet);
    let mut cycles = Vec::new();
    for &mu in at {
        for (after_point, cycle) in cycles_at(&mb, &branch, mu, opts)? {
            let mut mbp = mb.clone();
            mbp.mu = mu;
            let floquet =
                cycle_of(&mb, &cycle, opts.samples).and_then(|c| hill_exponents(&mbp, &c, hill));
            cycles.push(CycleAt {
                mu,
                after_point,
                cycle,
                floquet,
            });
        }
    }
    Ok(Some(BranchAnalysis {
        normal_form: nf,
        branch,
        floquet,
        bifurcations,
        floquet_time,
        at: cycles,
        levels: Vec::new(),
        microphone: None,
        tori: Vec::new(),
        stick: None,
        two_mode: None,
    }))
}

/// What `squeal branch` prints: the Hopf point, the branch's end, the folds, bifurcations and
/// the squeal range, and a table of about 20 points.
pub fn summary_text(a: &BranchAnalysis) -> String {
    let mut out = String::new();
    let mu0 = a.mu0();
    let b = &a.branch;
    let _ = writeln!(
        out,
        "Hopf point mu0 = {:.6} at {:.2} Hz, first Lyapunov coefficient {:+.3e}: {}",
        mu0,
        a.normal_form.omega0 / std::f64::consts::TAU,
        a.normal_form.l1,
        match a.normal_form.criticality() {
            Criticality::Subcritical =>
                "subcritical (the cycles born at mu0 exist below it and are unstable there)",
            Criticality::Supercritical => "supercritical (small stable cycles grow from mu0)",
            Criticality::Degenerate => DEGENERATE_HINT,
        }
    );
    let failed = a.floquet.iter().filter(|f| f.is_err()).count();
    let _ = writeln!(
        out,
        "branch: {} cycles in {:.2} s, Floquet exponents alongside, done {:.2} s after it{}; it ended because {}",
        b.points.len(),
        b.time.as_secs_f64(),
        a.floquet_time.as_secs_f64(),
        if failed > 0 {
            format!(" ({failed} points without: their analysis failed)")
        } else {
            String::new()
        },
        b.stop
    );
    for f in &b.folds {
        let _ = writeln!(
            out,
            "  fold at mu = {:.6} ({:.5} mu0), {:.2} Hz, closure {} um peak to peak{}",
            f.parameter,
            f.parameter / mu0,
            f.omega / std::f64::consts::TAU,
            fmt_sig(f.closure * 1e6, 3),
            if f.refined {
                ""
            } else {
                " (between two points: the branch turns where a contact opens)"
            }
        );
    }
    for bi in &a.bifurcations {
        let extra = if bi.kind == BifurcationKind::NeimarkSacker {
            format!(", second frequency {:.1} Hz", bi.torus_frequency_hz())
        } else {
            String::new()
        };
        let _ = writeln!(
            out,
            "  stability changes near mu = {:.6} ({:.5} mu0): {}{extra}; unstable exponents {} -> {}",
            bi.parameter,
            bi.parameter / mu0,
            bi.kind,
            bi.unstable.0,
            bi.unstable.1
        );
    }
    let r = a.squeal_range();
    let _ = writeln!(
        out,
        "squeal: spontaneous from mu0 = {:.6}; {}",
        r.spontaneous_from,
        match r.with_disturbance_from {
            Some(m) if m < mu0 => format!(
                "after a large enough disturbance from mu = {:.6} ({:.5} mu0{}), where the branch has stable cycles",
                m,
                m / mu0,
                if r.at_fold { ", the fold" } else { "" }
            ),
            Some(m) => format!(
                "the lowest stable cycle on the branch is at mu = {m:.6} ({:.5} mu0)",
                m / mu0
            ),
            None => "no stable cycle on the computed branch".into(),
        }
    );
    let pair = a.loudest_pair();
    for c in &a.at {
        let (i, p2p) = c.cycle.loudest();
        let verdict = match &c.floquet {
            Ok(f) => format!(
                "{}, largest multiplier {:.5}",
                f.stability(),
                f.largest_multiplier()
            ),
            Err(e) => format!("stability not computed: {e}"),
        };
        let _ = writeln!(
            out,
            "  cycle at mu = {:.6} ({:.5} mu0), after point {}: {:.4} Hz, pair {} {} um peak to peak, open {:.0}%, {} harmonics; {verdict}",
            c.mu,
            c.mu / mu0,
            c.after_point,
            c.cycle.frequency_hz(),
            i + 1,
            fmt_sig(p2p * 1e6, 4),
            100.0 * c.cycle.largest_open_fraction(),
            c.cycle.harmonics
        );
    }
    let mut t = Table::new([
        "point",
        "mu/mu0",
        "f (Hz)",
        "H",
        &format!("pair {} p2p (um)", pair + 1),
        "open",
        "max |rho|",
        "Hill error (1/s)",
        "stability",
    ]);
    for i in shown_points(b.points.len(), 20) {
        let p = &b.points[i];
        let (rho, err, verdict) = match &a.floquet[i] {
            Ok(f) => (
                format!("{:.5}", f.largest_multiplier()),
                fmt_sig(f.trivial_error, 2),
                f.stability().to_string(),
            ),
            Err(e) => ("-".into(), "-".into(), format!("not computed: {e}")),
        };
        t.push_row([
            i.to_string(),
            format!("{:.5}", p.parameter / mu0),
            format!("{:.2}", p.frequency_hz()),
            p.harmonics.to_string(),
            fmt_sig(p.pairs[pair].peak_to_peak() * 1e6, 4),
            format!("{:.0}%", 100.0 * p.largest_open_fraction()),
            rho,
            err,
            verdict,
        ]);
    }
    if !a.levels.is_empty() {
        t = with_levels(t, a, &shown_points(b.points.len(), 20).collect::<Vec<_>>());
        out.push_str(&crate::sound::squeal_level_text(a, &a.levels));
    }
    out.push_str(&t.to_text());
    out.push_str(&crate::branch_torus::summary_text(a));
    out.push_str(&crate::branch_stick::summary_text(a));
    out.push_str(&crate::branch_two_mode::summary_text(a.two_mode.as_ref()));
    out
}

/// `t` with a column of the levels of `points` (its rows in order).
fn with_levels(mut t: Table, a: &BranchAnalysis, points: &[usize]) -> Table {
    t.header.push("dB(A)".to_string());
    for (row, &i) in t.rows.iter_mut().zip(points) {
        row.push(a.levels.get(i).map_or("-".into(), |l| format!("{l:.1}")));
    }
    t
}

/// About `rows` evenly spread indices of `n` points for a table, always with the last one.
pub fn shown_points(n: usize, rows: usize) -> impl Iterator<Item = usize> {
    let stride = n.div_ceil(rows.max(1)).max(1);
    (0..n).filter(move |i| i % stride == 0 || i + 1 == n)
}

/// `branch.csv`: one row per cycle.
pub fn table(a: &BranchAnalysis) -> Table {
    let b = &a.branch;
    let n_pairs = b.points.first().map_or(0, |p| p.pairs.len());
    let mut header: Vec<String> = [
        "point",
        b.parameter.name(),
        "mu_over_mu0",
        "frequency_hz",
        "harmonics",
        "loudest_pair",
        "loudest_closure_p2p_m",
        "largest_open_fraction",
        "largest_multiplier",
        "leading_exponent_re_per_s",
        "leading_exponent_im_rad_per_s",
        "hill_error_per_s",
        "stability",
        "truncation",
        "residual",
        "newton_iterations",
    ]
    .map(String::from)
    .to_vec();
    for k in 0..n_pairs {
        header.push(format!("pair{}_closure_p2p_m", k + 1));
        header.push(format!("pair{}_open_fraction", k + 1));
    }
    if !a.levels.is_empty() {
        header.push("level_dba_rayleigh".into());
    }
    let mut t = Table::new(header);
    for (i, p) in b.points.iter().enumerate() {
        let (i_loud, c_loud) = p.loudest();
        let mut row = vec![
            i.to_string(),
            format!("{}", p.parameter),
            format!("{}", p.parameter / a.mu0()),
            format!("{}", p.frequency_hz()),
            p.harmonics.to_string(),
            (i_loud + 1).to_string(),
            format!("{c_loud:e}"),
            format!("{}", p.largest_open_fraction()),
        ];
        match &a.floquet[i] {
            Ok(f) => {
                let lead = f.leading();
                row.push(format!("{}", f.largest_multiplier()));
                row.push(lead.map_or(String::new(), |e| format!("{:e}", e.sigma.re)));
                row.push(lead.map_or(String::new(), |e| format!("{:e}", e.sigma.im)));
                row.push(format!("{:e}", f.trivial_error));
                row.push(f.stability().to_string());
            }
            Err(_) => {
                row.extend(["", "", "", ""].map(String::from));
                row.push("not computed".into());
            }
        }
        row.push(format!("{:e}", p.truncation));
        row.push(format!("{:e}", p.residual));
        row.push(p.iterations.to_string());
        for c in &p.pairs {
            row.push(format!("{:e}", c.peak_to_peak()));
            row.push(format!("{}", c.open_fraction));
        }
        if !a.levels.is_empty() {
            row.push(a.levels.get(i).map_or(String::new(), |l| format!("{l}")));
        }
        t.push_row(row);
    }
    t
}

/// `branch.json`: the Hopf point, the squeal range, folds, bifurcations and every point.
pub fn json(a: &BranchAnalysis) -> serde_json::Value {
    let r = a.squeal_range();
    let b = &a.branch;
    serde_json::json!({
        "parameter": b.parameter.name(),
        "hopf": {
            "mu0": a.mu0(),
            "frequency_hz": a.normal_form.omega0 / std::f64::consts::TAU,
            "first_lyapunov_coefficient": a.normal_form.l1,
            "criticality": a.normal_form.criticality().to_string(),
        },
        "squeal_range": {
            "spontaneous_from_mu": r.spontaneous_from,
            "with_disturbance_from_mu": r.with_disturbance_from,
            "at_fold": r.at_fold,
        },
        "stop": b.stop.to_string(),
        "continuation_seconds": b.time.as_secs_f64(),
        "floquet_seconds_after_continuation": a.floquet_time.as_secs_f64(),
        "floquet_method": "Hill's method on the harmonic balance Jacobian; hill_error is the trivial exponent's distance from zero",
        "folds": b.folds.iter().map(|f| serde_json::json!({
            "mu": f.parameter,
            "frequency_hz": f.omega / std::f64::consts::TAU,
            "loudest_closure_p2p_m": f.closure,
            "after_point": f.after_point,
            "refined": f.refined,
        })).collect::<Vec<_>>(),
        "bifurcations": a.bifurcations.iter().map(|bi| serde_json::json!({
            "kind": match bi.kind {
                BifurcationKind::Fold => "fold",
                BifurcationKind::PeriodDoubling => "period_doubling",
                BifurcationKind::NeimarkSacker => "neimark_sacker",
            },
            "mu": bi.parameter,
            "after_point": bi.after_point,
            "exponent": [bi.exponent.sigma.re, bi.exponent.sigma.im],
            "unstable_before_after": [bi.unstable.0, bi.unstable.1],
        })).collect::<Vec<_>>(),
        "microphone_m": a.microphone,
        "tori": crate::branch_torus::json(a),
        "stick_slip": crate::branch_stick::json(a),
        "two_mode": crate::branch_two_mode::json(a.two_mode.as_ref()),
        "cycles_at": a.at.iter().map(|c| {
            let f = c.floquet.as_ref().ok();
            serde_json::json!({
                "mu": c.mu,
                "after_point": c.after_point,
                "frequency_hz": c.cycle.frequency_hz(),
                "harmonics": c.cycle.harmonics,
                "closure_p2p_m": c.cycle.pairs.iter().map(|p| p.peak_to_peak()).collect::<Vec<_>>(),
                "open_fraction": c.cycle.pairs.iter().map(|p| p.open_fraction).collect::<Vec<_>>(),
                "largest_multiplier": f.map(|f| f.largest_multiplier()),
                "stability": f.map_or("not computed".to_string(), |f| f.stability().to_string()),
            })
        }).collect::<Vec<_>>(),
        "points": b.points.iter().enumerate().map(|(i, p)| {
            let f = a.floquet[i].as_ref().ok();
            serde_json::json!({
                "mu": p.parameter,
                "mu_over_mu0": p.parameter / a.mu0(),
                "frequency_hz": p.frequency_hz(),
                "harmonics": p.harmonics,
                "closure_p2p_m": p.pairs.iter().map(|c| c.peak_to_peak()).collect::<Vec<_>>(),
                "open_fraction": p.pairs.iter().map(|c| c.open_fraction).collect::<Vec<_>>(),
                "largest_open_fraction": p.largest_open_fraction(),
                "largest_multiplier": f.map(|f| f.largest_multiplier()),
                "hill_error_per_s": f.map(|f| f.trivial_error),
                "stability": f.map_or("not computed".to_string(), |f| f.stability().to_string()),
                "truncation": p.truncation,
                "residual": p.residual,
                "level_dba_rayleigh": a.levels.get(i),
            })
        }).collect::<Vec<_>>(),
    })
}

/// Runs of consecutive points with the same verdict, as `(verdict, first, last)` (a run shares
/// its end point with the next so that the curve is unbroken).
fn runs(a: &BranchAnalysis) -> Vec<(Option<Stability>, usize, usize)> {
    let mut out: Vec<(Option<Stability>, usize, usize)> = Vec::new();
    for i in 0..a.branch.points.len() {
        let s = a.stability(i);
        match out.last_mut() {
            Some(r) if r.0 == s => r.2 = i,
            Some(r) => {
                let start = r.2;
                out.push((s, start, i));
            }
            None => out.push((s, i, i)),
        }
    }
    out
}

/// The bifurcation diagram: (a) the loudest pair's peak-to-peak closure against μ, stable
/// solid, unstable dashed, not decided (within Hill's error) dotted, the Hopf point and the
/// folds marked, (b) the same near the Hopf point when the branch folds below it; (c) the
/// frequency and (d) the largest open fraction against μ.
pub fn figure(a: &BranchAnalysis) -> Figure {
    let pair = a.loudest_pair();
    let b = &a.branch;
    let mu0 = a.mu0();
    let f0 = a.normal_form.omega0 / std::f64::consts::TAU;
    let mut amp = Panel {
        title: format!("(a) pair {} closure, peak to peak", pair + 1),
        x_label: "friction coefficient mu".into(),
        y_label: "closure p2p (um)".into(),
        legend: squeal_report::LegendPosition::LowerRight,
        ..Panel::default()
    };
    let mut freq = Panel {
        title: "(c) frequency".into(),
        x_label: "friction coefficient mu".into(),
        y_label: "frequency (Hz)".into(),
        legend: squeal_report::LegendPosition::None,
        ..Panel::default()
    };
    let mut open = Panel {
        title: "(d) largest open fraction of the cycle".into(),
        x_label: "friction coefficient mu".into(),
        y_label: "open fraction".into(),
        legend: squeal_report::LegendPosition::None,
        ..Panel::default()
    };
    let mut named = [false; 3];
    for (verdict, first, last) in runs(a) {
        let (name, dash, color, k) = match verdict {
            Some(Stability::Stable) => ("stable", Dash::Solid, Rgb(31, 119, 180), 0),
            Some(Stability::Unstable) => ("unstable", Dash::Dashed, Rgb(214, 39, 40), 1),
            _ => ("not decided", Dash::Dotted, Rgb::GREY, 2),
        };
        let name = if named[k] { "" } else { name };
        named[k] = true;
        // The Hopf point begins the branch.
        let series = |f: &dyn Fn(usize) -> f64, at_hopf: f64| {
            let hopf = (first == 0).then_some((mu0, at_hopf));
            hopf.into_iter()
                .chain((first..=last).map(|i| (b.points[i].parameter, f(i))))
                .collect::<Vec<_>>()
        };
        let s_amp = series(&|i| b.points[i].pairs[pair].peak_to_peak() * 1e6, 0.0);
        let s_f = series(&|i| b.points[i].frequency_hz(), f0);
        let s_o = series(&|i| b.points[i].largest_open_fraction(), 0.0);
        amp.series
            .push(Series::line(name, s_amp).with_dash(dash).with_color(color));
        freq.series
            .push(Series::line("", s_f).with_dash(dash).with_color(color));
        open.series
            .push(Series::line("", s_o).with_dash(dash).with_color(color));
    }
    amp.series.push(
        Series::markers("Hopf point", vec![(mu0, 0.0)])
            .with_marker(Marker::Circle)
            .with_color(Rgb(0, 0, 0)),
    );
    if !b.folds.is_empty() {
        amp.series.push(
            Series::markers(
                "fold",
                b.folds
                    .iter()
                    .map(|f| (f.parameter, f.closure * 1e6))
                    .collect(),
            )
            .with_marker(Marker::Diamond)
            .with_color(Rgb(0, 0, 0)),
        );
    }
    let ns: Vec<(f64, f64)> = a
        .bifurcations
        .iter()
        .filter(|bi| bi.kind != BifurcationKind::Fold)
        .map(|bi| {
            // The closure interpolated to the crossing between its two points.
            let (p, q) = (&b.points[bi.after_point], &b.points[bi.after_point + 1]);
            let (cp, cq) = (p.pairs[pair].peak_to_peak(), q.pairs[pair].peak_to_peak());
            let s = if q.parameter != p.parameter {
                ((bi.parameter - p.parameter) / (q.parameter - p.parameter)).clamp(0.0, 1.0)
            } else {
                0.5
            };
            (bi.parameter, (cp + s * (cq - cp)) * 1e6)
        })
        .collect();
    if !ns.is_empty() {
        amp.series.push(
            Series::markers("period doubling / Neimark-Sacker", ns)
                .with_marker(Marker::Square)
                .with_color(Rgb(148, 103, 189)),
        );
    }
    for panel in [&mut amp, &mut freq, &mut open] {
        panel.annotations.push(Annotation::VLine {
            x: mu0,
            label: format!("mu0 = {}", fmt_sig(mu0, 4)),
            dash: Dash::Dashed,
        });
    }
    let range = a.squeal_range();
    let title = match range.with_disturbance_from {
        Some(m) if m < mu0 => format!(
            "Limit cycles against friction: squeal by itself from mu0 = {}, after a disturbance from mu = {}",
            fmt_sig(mu0, 4),
            fmt_sig(m, 4)
        ),
        _ => format!(
            "Limit cycles against friction: squeal by itself from mu0 = {}",
            fmt_sig(mu0, 4)
        ),
    };
    let torus_f2 = crate::branch_torus::add_to_figure(a, pair, &mut amp, &mut freq);
    let zoom = zoomed(&amp, a);
    let mut panels = vec![amp];
    panels.extend(zoom);
    panels.push(freq);
    panels.push(open);
    panels.extend(torus_f2);
    Figure {
        title,
        layout: Layout::Grid { columns: 2 },
        panels,
        panel_size: (560, 380),
        ..Figure::default()
    }
}

/// Panel (a) near the Hopf point and the folds below it, where a subcritical branch turns
/// (often within a percent of μ0, invisible at the full scale); `None` when no fold lies
/// below μ0.
fn zoomed(amp: &Panel, a: &BranchAnalysis) -> Option<Panel> {
    let mu0 = a.mu0();
    let lowest = a
        .branch
        .folds
        .iter()
        .map(|f| f.parameter)
        .filter(|m| *m < mu0)
        .fold(f64::INFINITY, f64::min);
    if !lowest.is_finite() {
        return None;
    }
    let w = mu0 - lowest;
    let (x0, x1) = (lowest - 0.5 * w, mu0 + 1.5 * w);
    let mut p = amp.clone();
    p.title = "(b) near the Hopf point".into();
    p.legend = squeal_report::LegendPosition::None;
    p.x_range = Some((x0, x1));
    for s in &mut p.series {
        s.points.retain(|(x, _)| (x0..=x1).contains(x));
    }
    p.series.retain(|s| !s.points.is_empty());
    Some(p)
}

/// Writes `branch.csv`, `branch.json` and `branch.svg`/`.png` into `dir`.
pub fn write(dir: &Path, a: &BranchAnalysis) -> Result<()> {
    crate::study::create_dir(dir)?;
    table(a).write_csv(&dir.join("branch.csv"))?;
    if !a.tori.is_empty() {
        crate::branch_torus::table(a).write_csv(&dir.join("branch_torus.csv"))?;
    }
    if let Some(s) = a.stick.as_ref().and_then(|r| r.sticking.as_ref()) {
        crate::branch_stick::table(s).write_csv(&dir.join("branch_stick.csv"))?;
    }
    if let Some(rows) = a.stick.as_ref().and_then(|r| r.dlft.as_ref()) {
        crate::branch_dlft::table(rows).write_csv(&dir.join("branch_dlft.csv"))?;
    }
    squeal_io::atomic_write_bytes(
        &dir.join("branch.json"),
        json_text(&json(a), "the branch")?.as_bytes(),
    )?;
    write_svg_and_png(&figure(a), &dir.join("branch"))?;
    Ok(())
}
