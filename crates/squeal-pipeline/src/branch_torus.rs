//! Past the Neimark–Sacker points (issue 24, item 1): `squeal branch` follows the torus branch
//! born at each Neimark–Sacker point of the branch of limit cycles ([`squeal_chbm::torus`]),
//! gives each torus' stability from its Lyapunov exponents
//! ([`squeal_chbm::torus_stability`]), and writes `branch_torus.csv`, the `tori` of
//! `branch.json` and the torus band of the diagram.
//!
//! **What a torus row says.** μ; both frequencies `f1` (the squeal's carrier, near the cycle's
//! frequency) and `f2` (the modulation, near `|Im σ|/2π` of the critical Floquet exponent at
//! the NS point); for each pair the closure's extremes and the envelope of its peak-to-peak
//! swing over one fast period (smallest and largest over 300 fast periods of the flow); the
//! scaled residual and Newton iterations of the quasi-periodic harmonic balance; the stability
//! verdict with the largest exponent across the torus and its error.
//!
//! **Failures.** A torus branch that does not start (no torus near the cycle at the NS point)
//! or whose continuation fails is reported as such, with the reason, and has no rows and no
//! curve: only converged tori are results. A torus whose exponents could not be computed is a
//! row with the stability "not computed" and the reason.

use crate::branch::{BranchAnalysis, BranchOptions};
use crate::model::{Log, Model};
use rayon::prelude::*;
use squeal_brake::analysis::LinearStability;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::bifurcation::{Bifurcation, BifurcationKind};
use squeal_chbm::torus::{TorusBranch, TorusOptions, follow_torus};
use squeal_chbm::torus_stability::torus_lyapunov;
/// The tori's 2-D Fourier basis, as the command line sets it.
pub use squeal_hbm::torus::Truncation;
use squeal_hbm::torus::lyapunov::{LyapunovOptions, LyapunovSpectrum};
use squeal_report::format::fmt_sig;
use squeal_report::{Dash, Panel, Rgb, Series, Table};
use std::fmt::Write as _;
use std::time::{Duration, Instant};

/// Whether and how `squeal branch` continues past the Neimark–Sacker points.
#[derive(Clone, Debug, PartialEq)]
pub struct TorusPlan {
    /// Follow the tori at all.
    pub enabled: bool,
    /// The 2-D basis (`None`: [`default_truncation`] of the cycle at the NS point).
    pub truncation: Option<Truncation>,
    /// Most tori on each torus branch.
    pub max_points: usize,
    /// The Lyapunov exponents' controls; `None`: the tori's stability is not computed.
    pub lyapunov: Option<LyapunovOptions>,
}

impl Default for TorusPlan {
    fn default() -> Self {
        Self {
            enabled: true,
            truncation: None,
            max_points: 60,
            lyapunov: Some(lyapunov_defaults()),
        }
    }
}

impl TorusPlan {
    /// No torus branch (what `squeal run` does).
    pub fn off() -> Self {
        Self {
            enabled: false,
            ..Self::default()
        }
    }
}

/// The Lyapunov controls `squeal branch` uses: 4 exponents over 200 fast periods after 20.
pub fn lyapunov_defaults() -> LyapunovOptions {
    LyapunovOptions {
        exponents: 4,
        periods: 200,
        transient: 20,
        ..LyapunovOptions::default()
    }
}

/// The default basis at a cycle of `harmonics` harmonics: a box of the cycle's harmonics in
/// the fast angle and 2 in the slow one (docs/torus.md: the convergence study).
pub fn default_truncation(harmonics: usize) -> Truncation {
    Truncation::Box(harmonics, 2)
}

/// The torus branch from one Neimark–Sacker point.
pub struct TorusRun {
    /// The Neimark–Sacker point.
    pub ns: Bifurcation,
    /// The branch, or why it failed.
    pub result: Result<TorusBranch, String>,
    /// Each torus' exponents (in the order of the branch's points), or why they failed.
    pub stability: Vec<Result<LyapunovSpectrum, String>>,
    /// Wall time of the exponents.
    pub stability_time: Duration,
}

impl TorusRun {
    /// The converged tori with their stability, in order.
    pub fn points(
        &self,
    ) -> impl Iterator<
        Item = (
            &squeal_chbm::torus::TorusPoint,
            &Result<LyapunovSpectrum, String>,
        ),
    > {
        self.result
            .as_ref()
            .map(|b| b.points.iter().zip(&self.stability))
            .into_iter()
            .flatten()
    }
}

/// Follows the torus branch from every Neimark–Sacker point of `a` (a branch of `m` in μ with
/// the options `opts`), each to the branch's μ range, with each torus' stability.
pub fn follow(
    m: &Model,
    st: &LinearStability,
    a: &BranchAnalysis,
    opts: &BranchOptions,
    plan: &TorusPlan,
    log: Log,
) -> Vec<TorusRun> {
    if !plan.enabled {
        return Vec::new();
    }
    let mu0 = a.mu0();
    let mb = ModalBrake::new(&m.brake, &st.reference, mu0);
    // The torus branches are independent, and so is every torus' stability: both run in
    // parallel (rayon keeps the order), each one computed as on one thread, so the results are
    // the same bits for any number of threads.
    let ns: Vec<&Bifurcation> = a
        .bifurcations
        .iter()
        .filter(|b| b.kind == BifurcationKind::NeimarkSacker)
        .collect();
    ns.into_par_iter()
        .map(|ns| follow_one(&mb, a, opts, plan, ns, log))
        .collect()
}

fn follow_one(
    mb: &ModalBrake,
    a: &BranchAnalysis,
    opts: &BranchOptions,
    plan: &TorusPlan,
    ns: &Bifurcation,
    log: Log,
) -> TorusRun {
    let mu0 = a.mu0();
    let harmonics = a.branch.points[ns.after_point].harmonics;
    let mut topts = TorusOptions {
        truncation: Some(plan.truncation.unwrap_or(default_truncation(harmonics))),
        ..TorusOptions::default()
    };
    topts.continuation.max_points = plan.max_points;
    topts.continuation.parameter_range = (opts.range.0 * mu0, opts.range.1 * mu0);
    log(&format!(
        "torus branch from the Neimark-Sacker point at mu = {:.6} ({:.5} mu0, second frequency {:.2} Hz) ...",
        ns.parameter,
        ns.parameter / mu0,
        ns.torus_frequency_hz()
    ));
    let result = follow_torus(mb, &a.branch, opts, ns, &topts).map_err(|e| e.to_string());
    let mut run = TorusRun {
        ns: *ns,
        result,
        stability: Vec::new(),
        stability_time: Duration::ZERO,
    };
    let b = match &run.result {
        Ok(b) => b,
        Err(e) => {
            log(&format!(
                "  torus branch from {:.5} mu0 failed: {e}",
                ns.parameter / mu0
            ));
            return run;
        }
    };
    log(&format!(
        "  torus branch from {:.5} mu0: {} tori in {:.2} s on {} ({} unknowns), ended because {}",
        ns.parameter / mu0,
        b.points.len(),
        b.time.as_secs_f64(),
        truncation_text(b.basis.truncation()),
        b.basis.len() + 3,
        b.stop
    ));
    let t = Instant::now();
    run.stability = b
        .points
        .par_iter()
        .map(|p| match &plan.lyapunov {
            Some(lo) => torus_lyapunov(mb, &b.basis, p, lo).map_err(|e| e.to_string()),
            None => Err("not asked for".into()),
        })
        .collect();
    run.stability_time = t.elapsed();
    if plan.lyapunov.is_some() {
        log(&format!(
            "  torus branch from {:.5} mu0: Lyapunov exponents of {} tori in {:.2} s",
            ns.parameter / mu0,
            b.points.len(),
            run.stability_time.as_secs_f64()
        ));
    }
    run
}

/// `Box(h1, h2)` or `total order n` in words.
pub fn truncation_text(t: Truncation) -> String {
    match t {
        Truncation::Box(a, b) => format!("the box |k1| <= {a}, |k2| <= {b}"),
        Truncation::TotalOrder(n) => format!("total order |k1| + |k2| <= {n}"),
    }
}

/// The verdict of a torus' exponents in words, and its numbers.
fn verdict(s: &Result<LyapunovSpectrum, String>) -> (String, Option<(f64, f64)>) {
    match s {
        Ok(s) => (
            s.stability().to_string(),
            Some((s.transverse(), s.uncertainty())),
        ),
        Err(e) => (format!("not computed: {e}"), None),
    }
}

/// What `squeal branch` prints about the tori.
pub fn summary_text(a: &BranchAnalysis) -> String {
    let mut out = String::new();
    let mu0 = a.mu0();
    for run in &a.tori {
        let _ = write!(
            out,
            "torus branch from the Neimark-Sacker point at mu = {:.6} ({:.5} mu0): ",
            run.ns.parameter,
            run.ns.parameter / mu0
        );
        let b = match &run.result {
            Ok(b) => b,
            Err(e) => {
                let _ = writeln!(out, "FAILED, no torus computed: {e}");
                continue;
            }
        };
        let _ = writeln!(
            out,
            "{} tori in {:.2} s on {}, ended because {}; stability by Lyapunov exponents in {:.2} s",
            b.points.len(),
            b.time.as_secs_f64(),
            truncation_text(b.basis.truncation()),
            b.stop,
            run.stability_time.as_secs_f64()
        );
        let mut t = Table::new([
            "mu/mu0",
            "f1 (Hz)",
            "f2 (Hz)",
            "pair",
            "swing min..max (um)",
            "lambda (1/s)",
            "stability",
        ]);
        let points: Vec<_> = run.points().collect();
        for i in crate::branch::shown_points(points.len(), 12) {
            let (p, s) = points[i];
            let (pair, e) = p.loudest();
            let f = p.frequencies_hz();
            let (v, num) = verdict(s);
            t.push_row([
                format!("{:.5}", p.mu / mu0),
                format!("{:.3}", f[0]),
                format!("{:.3}", f[1]),
                (pair + 1).to_string(),
                format!(
                    "{}..{}",
                    fmt_sig(1e6 * e.swing_min, 4),
                    fmt_sig(1e6 * e.swing_max, 4)
                ),
                num.map_or("-".into(), |(l, u)| {
                    format!("{} +- {}", fmt_sig(l, 3), fmt_sig(u, 2))
                }),
                v,
            ]);
        }
        out.push_str(&t.to_text());
    }
    out
}

/// `branch_torus.csv`: one row per torus of every torus branch.
pub fn table(a: &BranchAnalysis) -> Table {
    let n_pairs = a
        .tori
        .iter()
        .flat_map(|r| r.points())
        .map(|(p, _)| p.pairs.len())
        .next()
        .unwrap_or(0);
    let mut header: Vec<String> = [
        "torus_branch",
        "ns_mu",
        "point",
        "mu",
        "mu_over_mu0",
        "f1_hz",
        "f2_hz",
        "loudest_pair",
        "residual",
        "newton_iterations",
        "stability",
        "transverse_exponent_per_s",
        "exponent_error_per_s",
        "exponents_per_s",
    ]
    .map(String::from)
    .to_vec();
    for k in 1..=n_pairs {
        for q in [
            "swing_min_m",
            "swing_max_m",
            "closure_min_m",
            "closure_max_m",
        ] {
            header.push(format!("pair{k}_{q}"));
        }
    }
    let mut t = Table::new(header);
    for (r, run) in a.tori.iter().enumerate() {
        for (i, (p, s)) in run.points().enumerate() {
            let (v, num) = verdict(s);
            let f = p.frequencies_hz();
            let mut row = vec![
                (r + 1).to_string(),
                format!("{}", run.ns.parameter),
                i.to_string(),
                format!("{}", p.mu),
                format!("{}", p.mu / a.mu0()),
                format!("{}", f[0]),
                format!("{}", f[1]),
                (p.loudest().0 + 1).to_string(),
                format!("{:e}", p.residual),
                p.iterations.to_string(),
                v,
                num.map_or(String::new(), |(l, _)| format!("{l:e}")),
                num.map_or(String::new(), |(_, u)| format!("{u:e}")),
                s.as_ref().map_or(String::new(), |s| {
                    let e: Vec<String> = s.exponents.iter().map(|x| format!("{x:e}")).collect();
                    e.join(" ")
                }),
            ];
            for c in &p.pairs {
                let e = c.envelope;
                row.extend([e.swing_min, e.swing_max, e.min, e.max].map(|x| format!("{x:e}")));
            }
            t.push_row(row);
        }
    }
    t
}

/// The `tori` of `branch.json`.
pub fn json(a: &BranchAnalysis) -> serde_json::Value {
    let runs: Vec<serde_json::Value> = a
        .tori
        .iter()
        .map(|run| {
            let head = serde_json::json!({
                "ns_mu": run.ns.parameter,
                "ns_second_frequency_hz": run.ns.torus_frequency_hz(),
                "stability_method": "Lyapunov exponents of the linearized modal equations along the torus (RK4, Gram-Schmidt every step; Benettin et al. 1980); stable when the largest exponent across the torus is below minus its error",
            });
            let mut obj = head.as_object().cloned().unwrap_or_default();
            match &run.result {
                Err(e) => {
                    obj.insert("failed".into(), e.clone().into());
                }
                Ok(b) => {
                    obj.insert("truncation".into(), truncation_text(b.basis.truncation()).into());
                    obj.insert("grid".into(), serde_json::json!(b.grid));
                    obj.insert("stop".into(), b.stop.to_string().into());
                    obj.insert("continuation_seconds".into(), b.time.as_secs_f64().into());
                    obj.insert(
                        "stability_seconds".into(),
                        run.stability_time.as_secs_f64().into(),
                    );
                    let pts: Vec<serde_json::Value> =
                        run.points().map(|(p, s)| point_json(a, p, s)).collect();
                    obj.insert("points".into(), pts.into());
                }
            }
            serde_json::Value::Object(obj)
        })
        .collect();
    runs.into()
}

fn point_json(
    a: &BranchAnalysis,
    p: &squeal_chbm::torus::TorusPoint,
    s: &Result<LyapunovSpectrum, String>,
) -> serde_json::Value {
    let (v, num) = verdict(s);
    serde_json::json!({
        "mu": p.mu,
        "mu_over_mu0": p.mu / a.mu0(),
        "frequencies_hz": p.frequencies_hz(),
        "residual": p.residual,
        "newton_iterations": p.iterations,
        "swing_min_m": p.pairs.iter().map(|c| c.envelope.swing_min).collect::<Vec<_>>(),
        "swing_max_m": p.pairs.iter().map(|c| c.envelope.swing_max).collect::<Vec<_>>(),
        "closure_min_m": p.pairs.iter().map(|c| c.envelope.min).collect::<Vec<_>>(),
        "closure_max_m": p.pairs.iter().map(|c| c.envelope.max).collect::<Vec<_>>(),
        "stability": v,
        "transverse_exponent_per_s": num.map(|x| x.0),
        "exponent_error_per_s": num.map(|x| x.1),
        "exponents_per_s": s.as_ref().ok().map(|s| s.exponents.clone()),
    })
}

/// Colours of the torus band: stable, unstable, not decided.
const TORUS: [Rgb; 3] = [Rgb(44, 160, 44), Rgb(255, 127, 14), Rgb(127, 127, 127)];

fn colour(s: &Result<LyapunovSpectrum, String>) -> (usize, &'static str) {
    use squeal_hbm::torus::lyapunov::TorusStability as T;
    match s.as_ref().map(|s| s.stability()) {
        Ok(T::Attracting) => (0, "torus, stable: swing min..max"),
        Ok(T::Unstable) => (1, "torus, unstable: swing min..max"),
        _ => (2, "torus, not decided: swing min..max"),
    }
}

/// Adds the tori to the diagram: in `amp` (the loudest `pair`'s peak-to-peak closure) the
/// band between the smallest and the largest swing over a fast period, one colour per
/// stability verdict; in `freq` the carrier `f1`; and a panel of the modulation `f2`
/// (`None` without tori).
pub fn add_to_figure(
    a: &BranchAnalysis,
    pair: usize,
    amp: &mut Panel,
    freq: &mut Panel,
) -> Option<Panel> {
    let mut f2 = Panel {
        title: "(e) torus: modulation frequency f2".into(),
        x_label: "friction coefficient mu".into(),
        y_label: "f2 (Hz)".into(),
        legend: squeal_report::LegendPosition::None,
        ..Panel::default()
    };
    let mut named = [false; 3];
    for run in &a.tori {
        let points: Vec<_> = run.points().collect();
        // Runs of one verdict, each sharing its last point with the next run's first so that
        // the band is unbroken.
        let n = points.len();
        let mut i = 0;
        while i < n {
            let (k, name) = colour(points[i].1);
            let mut j = i;
            while j + 1 < n && colour(points[j + 1].1).0 == k {
                j += 1;
            }
            let seg = &points[i..=(j + 1).min(n - 1)];
            i = j + 1;
            let name = if named[k] { "" } else { name };
            named[k] = true;
            let line = |f: &dyn Fn(&squeal_chbm::torus::TorusPoint) -> f64| {
                seg.iter().map(|(p, _)| (p.mu, f(p))).collect::<Vec<_>>()
            };
            let c = TORUS[k];
            let (lo, hi) = (
                line(&|p| 1e6 * p.pairs[pair].envelope.swing_min),
                line(&|p| 1e6 * p.pairs[pair].envelope.swing_max),
            );
            amp.series.push(
                Series::line(name, hi)
                    .with_color(c)
                    .with_dash(Dash::DashDot),
            );
            amp.series
                .push(Series::line("", lo).with_color(c).with_dash(Dash::DashDot));
            freq.series.push(
                Series::line("", line(&|p| p.frequencies_hz()[0]))
                    .with_color(c)
                    .with_dash(Dash::DashDot),
            );
            f2.series.push(
                Series::line("", line(&|p| p.frequencies_hz()[1]))
                    .with_color(c)
                    .with_dash(Dash::DashDot),
            );
        }
    }
    (!f2.series.is_empty()).then_some(f2)
}
