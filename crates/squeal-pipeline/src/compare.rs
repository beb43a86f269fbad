//! Issue #6's comparison of the Constrained Harmonic Balance Method against BDF time
//! integration of the full brake — the paper's Tables 1–2 and Figures 4–5 for our brake, a
//! speed–accuracy chart, and (optionally) where each method fails.
//!
//! Error definitions (also in every CSV header): both cycles are aligned in time on the first
//! harmonic of the reference's most moving contact dof; the relative error is the RMS over one
//! cycle (in phase ωt) and over the dofs of `x_method - x_reference`, mean included, divided by
//! the RMS of the reference's oscillation; the same for velocities; "all" is every physical dof
//! of the reduced brake, "contact" the dofs the contact forces act on.

use crate::Pipeline;
use crate::chbm::point_dof;
use crate::error::{PipelineError, Result, json_text};
use crate::model::{Log, Model};
use squeal_brake::analysis::LinearStability as Stability;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::compare::{
    CellOutcome, CompareOptions, Comparison, GridCell, GridModel, GridOptions, TiCell, TiRow,
    compare_at_with, robustness,
};
use squeal_chbm::cycle::RelativeErrors;
use squeal_chbm::timeint::TiOptions;
use squeal_chbm::{ChbmOptions, ChbmStart};
use squeal_report::format::{fmt_sci, fmt_sig};
use squeal_report::{
    Annotation, Category, CategoryGrid, Dash, Figure, Layout, Panel, Rgb, Scale, Series, Table,
    write_svg_and_png,
};
use std::path::Path;

/// What to compare and how: the friction levels (multiples of μ0), CHBM's harmonics, the time
/// integrations' tolerances and start, and whether to map robustness.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareSettings {
    pub mu_ratios: Vec<f64>,
    pub harmonics: Vec<usize>,
    pub rtols: Vec<f64>,
    pub reference_rtol: f64,
    /// Initial perturbation along the unstable mode, as a fraction of the smallest static
    /// penetration.
    pub perturbation: f64,
    pub max_order: usize,
    pub grid: bool,
}

impl Default for CompareSettings {
    fn default() -> Self {
        let ti = TiOptions::default();
        Self {
            mu_ratios: vec![1.01, 1.1],
            harmonics: CompareOptions::default().harmonics,
            rtols: CompareOptions::default().rtols,
            reference_rtol: CompareOptions::default().reference_rtol,
            perturbation: ti.perturbation,
            max_order: ti.max_order,
            grid: false,
        }
    }
}

impl CompareSettings {
    /// Checks every value before any work.
    pub fn validate(&self) -> Result<()> {
        if self.mu_ratios.is_empty() || self.mu_ratios.iter().any(|r| !(*r > 1.0 && *r <= 10.0)) {
            return Err(PipelineError::input(
                "--mu-ratio",
                "values must be in (1, 10]: the brake is stable below mu0",
            ));
        }
        if self.harmonics.is_empty() || self.harmonics.iter().any(|h| !(1..=50).contains(h)) {
            return Err(PipelineError::input(
                "--harmonics",
                "values must be between 1 and 50",
            ));
        }
        let tol_ok = |t: f64| t.is_finite() && (1e-12..=1e-2).contains(&t);
        if !tol_ok(self.reference_rtol) || self.rtols.iter().any(|t| !tol_ok(*t)) {
            return Err(PipelineError::input(
                "tolerances",
                "must be between 1e-12 and 1e-2",
            ));
        }
        if self.reference_rtol > 1e-3 {
            return Err(PipelineError::input(
                "--reference-rtol",
                "must be at most 1e-3 (its error is estimated by a run at 10 times it)",
            ));
        }
        if !(self.perturbation.is_finite() && self.perturbation > 0.0 && self.perturbation <= 10.0)
        {
            return Err(PipelineError::input("--perturbation", "must be in (0, 10]"));
        }
        if !(1..=5).contains(&self.max_order) {
            return Err(PipelineError::input(
                "--max-order",
                "must be between 1 and 5",
            ));
        }
        Ok(())
    }
}

/// One friction level of a comparison, for the report.
#[derive(Clone, Debug)]
pub struct CompareLevel {
    /// μ / μ0.
    pub ratio: f64,
    /// μ.
    pub mu: f64,
    /// Folder of this level's files, relative to the comparison folder (`mu_1.010`).
    pub folder: String,
    /// The paper's Table 1 for this brake: errors against the reference.
    pub table1: Table,
    /// The paper's Table 2: cost and storage.
    pub table2: Table,
    /// What did not converge, in full (the tables give it in short).
    pub failures: Vec<String>,
    /// The files written into `folder`.
    pub files: Vec<String>,
}

/// What a comparison computed: each level's tables and failures, and the JSON summary
/// written as `summary.json`.
#[derive(Clone, Debug)]
pub struct CompareSummary {
    pub levels: Vec<CompareLevel>,
    /// How the errors are defined.
    pub error_definition: &'static str,
    pub json: serde_json::Value,
}

/// The comparisons at every friction level of `settings` (and the robustness map) of the
/// pipeline `p`'s brake, written to `dir`; returns the summary (also written as
/// `dir/summary.json`). `first` is the start and modal brake at the first level when the
/// caller has them already. The time integrations and CHBM solves are told to `p`'s progress.
pub fn run(
    p: &Pipeline,
    first: Option<(ChbmStart, ModalBrake)>,
    settings: &CompareSettings,
    dir: &Path,
) -> Result<CompareSummary> {
    settings.validate()?;
    let (m, st, mu0) = (p.model()?, p.stability()?, p.mu0()?);
    let (log, progress) = (p.log(), p.progress());
    // The integrations' Fourier averages keep at least as many harmonics as CHBM's largest
    // (at least 20), so that the reference does not truncate what it judges.
    let ti_harmonics = settings
        .harmonics
        .iter()
        .copied()
        .max()
        .unwrap_or(1)
        .max(20);
    let opts = CompareOptions {
        harmonics: settings.harmonics.clone(),
        ti: TiOptions {
            perturbation: settings.perturbation,
            max_order: settings.max_order,
            harmonics: ti_harmonics,
            samples_per_cycle: TiOptions::default()
                .samples_per_cycle
                .max(4 * ti_harmonics + 8),
            ..TiOptions::default()
        },
        rtols: settings.rtols.clone(),
        reference_rtol: settings.reference_rtol,
        reference_drift_tol: REFERENCE_DRIFT_TOL,
        disc: m.disc,
        ..CompareOptions::default()
    };
    let mut summary = Vec::new();
    let mut levels = Vec::new();
    let mut first = first;
    let steps = opts.steps().len() * settings.mu_ratios.len();
    progress.begin("CHBM against BDF", steps);
    let mut guess: Option<Vec<f64>> = None;
    for &ratio in &settings.mu_ratios {
        let mu = ratio * mu0;
        let (start, mb) = match first.take() {
            Some(f) if (f.1.mu - mu).abs() <= 1e-12 * mu.abs() => f,
            _ => crate::chbm::start(m, st, mu, guess.as_deref())?,
        };
        guess = Some(start.equilibrium.clone());
        log(&format!(
            "\n== mu = {:.6} ({ratio} mu0): reference BDF at rtol {:e} (continued on the steady cycle of a rtol {:e} run; a rtol {:e} run estimates its error), then {} more tolerances and {} CHBM solves",
            mb.mu,
            settings.reference_rtol,
            opts.seed_rtol,
            opts.check_factor * settings.reference_rtol,
            settings.rtols.len(),
            settings.harmonics.len()
        ));
        let c = compare_at_with(&mb, &start, &opts, &mut |step| {
            progress.item(&format!("{ratio} mu0: {step}"))
        })?;
        let folder = format!("mu_{ratio:.3}");
        let files = write_comparison(&dir.join(&folder), m, &c, ratio, log)?;
        summary.push(comparison_json(&c, ratio, &files));
        levels.push(CompareLevel {
            ratio,
            mu: c.mu,
            folder,
            table1: table1(&c),
            table2: table2(&c),
            failures: failures(&c),
            files,
        });
    }
    progress.end();
    let mut grid_json = serde_json::Value::Null;
    if settings.grid {
        grid_json = run_grid(dir, m, st, mu0, settings, log)?;
    }
    let json = serde_json::json!({
        "mu0": mu0,
        "error_definition": ERROR_DEFINITION,
        "comparisons": summary,
        "robustness": grid_json,
    });
    squeal_io::atomic_write_bytes(
        &dir.join("summary.json"),
        json_text(&json, "the comparison summary")?.as_bytes(),
    )?;
    Ok(CompareSummary {
        levels,
        error_definition: ERROR_DEFINITION,
        json,
    })
}

/// Every method that gave no limit cycle, with the full reason.
fn failures(c: &Comparison) -> Vec<String> {
    let mut out = Vec::new();
    for r in &c.chbm {
        if r.solution.outcome != squeal_chbm::Outcome::LimitCycle {
            out.push(format!(
                "CHBM with {} harmonics: {}",
                r.harmonics, r.solution.outcome
            ));
        }
    }
    for r in std::iter::once(&c.reference).chain(&c.ti) {
        if r.run.steady.is_none() {
            out.push(format!(
                "BDF time integration at rtol {:e}{}: {}",
                r.rtol,
                if std::ptr::eq(r, &c.reference) {
                    " (the reference)"
                } else {
                    ""
                },
                r.run
                    .failure
                    .as_ref()
                    .map_or("no steady cycle".to_string(), |f| f.to_string())
            ));
        }
    }
    out
}

/// A failure's first clause (up to its first ": "), for a table cell; the full text is in the
/// failures list.
fn short(reason: &str) -> &str {
    reason.split(": ").next().unwrap_or(reason)
}

const ERROR_DEFINITION: &str = "cycles aligned in time on the first harmonic of the reference's most moving contact dof; relative error = RMS over one cycle (in phase) and over the dofs of x_method - x_reference (mean included) / RMS of the reference's oscillation (mean removed); velocity likewise; 'all' = every physical dof, 'contact' = the dofs the contact forces act on; reference = BDF at the reference tolerance, continued from the steady cycle of a looser run; its estimated own error = (difference from a run at check_factor x its tolerance) / (check_factor^(2/3) - 1), the BDF2 phase error growing like rtol^(2/3)";

fn pct(x: f64) -> String {
    fmt_sig(100.0 * x, 3)
}

/// Table 1's analogue: rows of quantities, a column per method.
fn table1(c: &Comparison) -> Table {
    let mut header = vec!["".to_string()];
    header.extend(c.chbm.iter().map(|r| format!("CHBM {}H", r.harmonics)));
    header.extend(c.ti.iter().map(|r| format!("BDF {:e}", r.rtol)));
    header.push(format!("BDF {:e}: est. own error", c.reference.rtol));
    let mut t = Table::new(header);
    let est = |f: &dyn Fn(&RelativeErrors) -> String, contact: bool| {
        let e = if contact {
            &c.estimate.contact
        } else {
            &c.estimate.all
        };
        e.as_ref().map_or("-".into(), f)
    };
    let own = [
        est(&|e| pct(e.displacement), false),
        est(&|e| pct(e.velocity), false),
        est(&|e| pct(e.displacement), true),
        est(&|e| pct(e.velocity), true),
        est(&|e| format!("±{}", fmt_sig(e.frequency_hz.abs(), 3)), false),
        est(&|e| format!("±{}", pct(e.frequency_relative.abs())), false),
        c.reference
            .measures
            .as_ref()
            .map_or("-".into(), |m| pct(max(&m.open_fraction))),
        c.reference.measures.as_ref().map_or("-".into(), margin),
    ];
    let chbm = |f: &dyn Fn(&squeal_chbm::compare::ChbmRow) -> String| {
        c.chbm.iter().map(f).collect::<Vec<_>>()
    };
    let ti = |f: &dyn Fn(&squeal_chbm::compare::Measures) -> String| {
        c.ti.iter()
            .map(|r| r.measures.as_ref().map_or("-".into(), f))
            .collect::<Vec<_>>()
    };
    let rows: [(&str, Vec<String>, Vec<String>); 8] = [
        (
            "displacement error, all dofs (%)",
            chbm(&|r| pct(r.measures.all.displacement)),
            ti(&|m| pct(m.all.displacement)),
        ),
        (
            "velocity error, all dofs (%)",
            chbm(&|r| pct(r.measures.all.velocity)),
            ti(&|m| pct(m.all.velocity)),
        ),
        (
            "displacement error, contact dofs (%)",
            chbm(&|r| pct(r.measures.contact.displacement)),
            ti(&|m| pct(m.contact.displacement)),
        ),
        (
            "velocity error, contact dofs (%)",
            chbm(&|r| pct(r.measures.contact.velocity)),
            ti(&|m| pct(m.contact.velocity)),
        ),
        (
            "frequency difference (Hz)",
            chbm(&|r| fmt_sig(r.measures.all.frequency_hz, 3)),
            ti(&|m| fmt_sig(m.all.frequency_hz, 3)),
        ),
        (
            "frequency difference (%)",
            chbm(&|r| pct(r.measures.all.frequency_relative)),
            ti(&|m| pct(m.all.frequency_relative)),
        ),
        (
            "largest open fraction of a pair (%)",
            chbm(&|r| pct(max(&r.measures.open_fraction))),
            ti(&|m| pct(max(&m.open_fraction))),
        ),
        (
            "sliding margin: disc speed / peak tangential velocity",
            chbm(&|r| margin(&r.measures)),
            ti(&margin),
        ),
    ];
    for ((name, a, b), o) in rows.into_iter().zip(own) {
        let mut row = vec![name.to_string()];
        row.extend(a);
        row.extend(b);
        row.push(o);
        t.push_row(row);
    }
    t.align_numbers_right()
}

/// The smallest sliding margin of a cycle, `-` without a disc speed, `!` below 1.
fn margin(m: &squeal_chbm::compare::Measures) -> String {
    m.sliding.as_ref().map_or("-".into(), |g| {
        format!(
            "{}{}",
            fmt_sig(g.min, 3),
            if g.sliding() { "" } else { " !" }
        )
    })
}

fn max(v: &[f64]) -> f64 {
    v.iter().copied().fold(0.0, f64::max)
}

/// Table 2's analogue: cost and storage of every method.
fn table2(c: &Comparison) -> Table {
    let mut t = Table::new([
        "method",
        "outcome",
        "iterations / steps",
        "wall time (s)",
        "storage (bytes)",
        "cycles to steady",
        "rejected steps",
        "LU factorizations",
        "energy balance (in-out)/out",
    ]);
    for r in &c.chbm {
        let s = &r.solution;
        t.push_row([
            format!("CHBM {}H", r.harmonics),
            if s.outcome == squeal_chbm::Outcome::LimitCycle {
                "limit cycle".into()
            } else {
                s.outcome.to_string()
            },
            r.iterations.to_string(),
            fmt_sig(r.wall.as_secs_f64(), 3),
            s.storage_bytes().to_string(),
            "-".into(),
            "-".into(),
            "-".into(),
            fmt_sci(r.measures.energy.relative, 2),
        ]);
    }
    let e = &c.estimate;
    if e.seed.rtol != c.reference.rtol {
        t.push_row(ti_cost_row(&e.seed, " (reference: seed)"));
    }
    if e.check.rtol != e.seed.rtol && e.check.rtol != c.reference.rtol {
        t.push_row(ti_cost_row(&e.check, " (reference: check)"));
    }
    t.push_row(ti_cost_row(&c.reference, " (reference)"));
    if let Some(u) = &e.unsteady {
        t.push_row(ti_cost_row(u, " (asked reference)"));
    }
    for r in &c.ti {
        t.push_row(ti_cost_row(r, ""));
    }
    t.align_numbers_right()
}

fn ti_cost_row(r: &TiRow, role: &str) -> Vec<String> {
    let st = &r.run.stats;
    vec![
        format!("BDF {:e}{role}", r.rtol),
        match (&r.run.steady, &r.run.failure) {
            (Some(s), _) => format!("steady (drift {})", fmt_sci(s.drift, 1)),
            (None, Some(f)) => format!("failed: {}", short(&f.to_string())),
            (None, None) => "no steady cycle".into(),
        },
        st.steps.to_string(),
        fmt_sig(r.run.wall.as_secs_f64(), 3),
        r.run.history_bytes().to_string(),
        r.run
            .steady
            .as_ref()
            .map_or("-".into(), |s| s.cycles.to_string()),
        (st.rejected_error + st.rejected_newton).to_string(),
        st.lu_decomps.to_string(),
        r.measures
            .as_ref()
            .map_or("-".into(), |m| fmt_sci(m.energy.relative, 2)),
    ]
}

/// Long-form CSV of every method's measures.
fn measures_csv(c: &Comparison) -> Table {
    let slide = |m: Option<&squeal_chbm::compare::Measures>| {
        m.and_then(|m| m.sliding.as_ref())
            .map_or(String::new(), |g| format!("{:e}", g.min))
    };
    let mut t = Table::new([
        "method",
        "harmonics",
        "rtol",
        "outcome",
        "frequency_hz",
        "dfreq_hz",
        "dfreq_rel",
        "err_disp_all",
        "err_vel_all",
        "err_disp_contact",
        "err_vel_contact",
        "iterations_or_steps",
        "wall_s",
        "storage_bytes",
        "energy_balance_rel",
        "max_open_fraction",
        "initial_amplitude_p",
        "sliding_margin",
    ]);
    for r in &c.chbm {
        let m = &r.measures;
        t.push_row([
            "chbm".into(),
            r.harmonics.to_string(),
            "".into(),
            r.solution.outcome.label().to_string(),
            format!("{}", r.cycle.frequency_hz()),
            format!("{:e}", m.all.frequency_hz),
            format!("{:e}", m.all.frequency_relative),
            format!("{:e}", m.all.displacement),
            format!("{:e}", m.all.velocity),
            format!("{:e}", m.contact.displacement),
            format!("{:e}", m.contact.velocity),
            r.iterations.to_string(),
            format!("{:e}", r.wall.as_secs_f64()),
            r.solution.storage_bytes().to_string(),
            format!("{:e}", m.energy.relative),
            format!("{}", max(&m.open_fraction)),
            format!("{}", r.amplitude),
            slide(Some(m)),
        ]);
    }
    let e = &c.estimate;
    let rows = [
        ("bdf_seed", Some(&e.seed)),
        ("bdf_check", Some(&e.check)),
        ("bdf_reference", Some(&c.reference)),
        ("bdf_asked_reference_unsteady", e.unsteady.as_ref()),
    ];
    let rows = rows
        .into_iter()
        .filter_map(|(m, r)| r.map(|r| (m, r)))
        .chain(c.ti.iter().map(|r| ("bdf", r)));
    for (method, r) in rows {
        let (freq, m) = (
            r.cycle.as_ref().map(|c| c.frequency_hz()),
            r.measures.as_ref(),
        );
        let num = |f: Option<f64>| f.map_or(String::new(), |v| format!("{v:e}"));
        t.push_row([
            method.into(),
            "".into(),
            format!("{:e}", r.rtol),
            if r.run.steady.is_some() {
                "steady".into()
            } else {
                "no steady cycle".into()
            },
            num(freq),
            num(m.map(|m| m.all.frequency_hz)),
            num(m.map(|m| m.all.frequency_relative)),
            num(m.map(|m| m.all.displacement)),
            num(m.map(|m| m.all.velocity)),
            num(m.map(|m| m.contact.displacement)),
            num(m.map(|m| m.contact.velocity)),
            r.run.stats.steps.to_string(),
            format!("{:e}", r.run.wall.as_secs_f64()),
            r.run.history_bytes().to_string(),
            num(m.map(|m| m.energy.relative)),
            num(m.map(|m| max(&m.open_fraction))),
            format!("{}", r.run.epsilon),
            slide(m),
        ]);
    }
    if let (Some(a), Some(k)) = (&e.all, &e.contact) {
        let mut row = vec![
            "bdf_reference_estimated_error".to_string(),
            "".into(),
            format!("{:e}", c.reference.rtol),
            "Estimate".into(),
            "".into(),
            format!("{:e}", a.frequency_hz),
            format!("{:e}", a.frequency_relative),
            format!("{:e}", a.displacement),
            format!("{:e}", a.velocity),
            format!("{:e}", k.displacement),
            format!("{:e}", k.velocity),
            e.steps(&c.reference).to_string(),
            format!("{:e}", e.wall(&c.reference).as_secs_f64()),
        ];
        row.extend(std::iter::repeat_n(String::new(), 5));
        t.push_row(row);
    }
    t
}

/// A warning naming the cycles whose sliding margin is below 1.
fn sliding_warning(c: &Comparison) -> Option<String> {
    let mut bad = Vec::new();
    for r in &c.chbm {
        if r.measures.sliding.as_ref().is_some_and(|g| !g.sliding()) {
            bad.push(format!("CHBM {}H", r.harmonics));
        }
    }
    for r in std::iter::once(&c.reference).chain(&c.ti) {
        let m = r.measures.as_ref().and_then(|m| m.sliding.as_ref());
        if m.is_some_and(|g| !g.sliding()) {
            bad.push(format!("BDF {:e}", r.rtol));
        }
    }
    (!bad.is_empty()).then(|| {
        format!(
            "WARNING: sliding margin below 1 for {}: the pad's tangential vibration outruns the disc surface, so the pad sticks for part of the cycle; stick-slip is outside the model (permanent sliding).",
            bad.join(", ")
        )
    })
}

const REFERENCE_DRIFT_TOL: f64 = 1e-7;

/// One paragraph on the reference: its own estimated error and what it cost.
fn reference_note(c: &Comparison) -> String {
    let e = &c.estimate;
    let mut head = format!(
        "Reference: BDF rtol {:e}, continued from the steady cycle of rtol {:e} (through rtol {:e}); {} steps, {} s in all.",
        c.reference.rtol,
        e.seed.rtol,
        e.check.rtol,
        e.steps(&c.reference),
        fmt_sig(e.wall(&c.reference).as_secs_f64(), 3)
    );
    if let Some(u) = &e.unsteady {
        let last = u
            .run
            .drifts
            .last()
            .map_or("none".into(), |d| fmt_sci(d.1, 1));
        head = format!(
            "WARNING: the run at the asked reference tolerance {:e} found no steady cycle ({}; last drift between 20-cycle averages {last}, asked {}); the reference is the tightest steady run.\n{head}",
            u.rtol,
            u.run
                .failure
                .as_ref()
                .map_or("no reason given".into(), |f| f.to_string()),
            fmt_sci(REFERENCE_DRIFT_TOL, 1),
        );
    }
    match (&e.all, &e.contact) {
        (Some(a), Some(k)) => {
            let worst = c
                .chbm
                .iter()
                .filter(|r| r.measures.all.displacement < 3.0 * a.displacement)
                .map(|r| format!("{}H", r.harmonics))
                .collect::<Vec<_>>();
            format!(
                "{head}\nIts estimated own error (difference from rtol {:e} x {}): displacement {} %, velocity {} % (all dofs), {} %, {} % (contact dofs), frequency {} Hz ({} %).{}",
                e.check.rtol,
                fmt_sig(e.scale, 3),
                pct(a.displacement),
                pct(a.velocity),
                pct(k.displacement),
                pct(k.velocity),
                fmt_sig(a.frequency_hz.abs(), 3),
                pct(a.frequency_relative.abs()),
                if worst.is_empty() {
                    String::new()
                } else {
                    format!(
                        "\nWARNING: the displacement errors of CHBM {} are within 3x the reference's own error: they measure the reference too.",
                        worst.join(", ")
                    )
                }
            )
        }
        _ => format!(
            "{head}\nIts own error is not estimated: the check run at rtol {:e} found no steady cycle.",
            e.check.rtol
        ),
    }
}

/// Writes tables and figures of one comparison; returns the files written (relative names).
fn write_comparison(
    dir: &Path,
    m: &Model,
    c: &Comparison,
    ratio: f64,
    log: Log,
) -> Result<Vec<String>> {
    let t1 = table1(c);
    let t2 = table2(c);
    log(&format!(
        "\nTable 1 analogue at {ratio} mu0 (reference: BDF rtol {:e}; errors relative RMS, phase-aligned):\n{}",
        c.reference.rtol,
        t1.to_text()
    ));
    log(&reference_note(c));
    if let Some(w) = sliding_warning(c) {
        log(&w);
    }
    log(&format!("\nTable 2 analogue:\n{}", t2.to_text()));
    t1.write_csv(&dir.join("table1.csv"))?;
    t2.write_csv(&dir.join("table2.csv"))?;
    measures_csv(c).write_csv(&dir.join("measures.csv"))?;
    power_csv(c).write_csv(&dir.join("power_ratio.csv"))?;
    let mut files = vec![
        "table1.csv".to_string(),
        "table2.csv".into(),
        "measures.csv".into(),
        "power_ratio.csv".into(),
    ];
    for (stem, fig) in [
        ("limit_cycles", figure4(m, c, ratio)),
        ("power_ratio", figure5(c, ratio)),
        ("speed_accuracy", speed_accuracy(c, ratio)),
        ("ti_growth", growth(c, ratio)),
    ] {
        write_svg_and_png(&fig, &dir.join(stem))?;
        files.push(format!("{stem}.svg"));
    }
    Ok(files)
}

/// Eqs (49)–(50): `R_j = P_j / P_temporal` for every method and harmonic.
fn power_csv(c: &Comparison) -> Table {
    let mut t = Table::new(["method", "harmonic", "power_P_j", "ratio_R_j"]);
    let total = c.power_reference.max(f64::MIN_POSITIVE);
    if let Some(m) = &c.reference.measures {
        for (j, pj) in m.power.iter().enumerate() {
            t.push_row([
                format!("BDF {:e}", c.reference.rtol),
                (j + 1).to_string(),
                format!("{pj:e}"),
                format!("{:e}", pj / total),
            ]);
        }
    }
    for r in &c.chbm {
        for (j, pj) in r.measures.power.iter().enumerate() {
            t.push_row([
                format!("CHBM {}H", r.harmonics),
                (j + 1).to_string(),
                format!("{pj:e}"),
                format!("{:e}", pj / total),
            ]);
        }
    }
    t
}

const DASHES: [Dash; 4] = [Dash::Dashed, Dash::DashDot, Dash::Dotted, Dash::Solid];
const BLACK: Rgb = Rgb(0, 0, 0);

/// Figure 4: limit cycles of a pad and a disc contact normal dof, CHBM over the reference.
fn figure4(m: &Model, c: &Comparison, ratio: f64) -> Figure {
    let mut panels = Vec::new();
    for (title, part) in [
        (
            format!(
                "(a) {} contact point 5, normal",
                crate::chbm::first_pad_label(m)
            ),
            "pad",
        ),
        ("(b) disc contact point 5, normal".to_string(), "disc"),
    ] {
        let Some(d) = point_dof(m, part, 4, 2) else {
            continue;
        };
        let mut series = Vec::new();
        if let Some(rc) = &c.reference.cycle {
            series.push(
                Series::line(
                    format!("BDF {:e}", c.reference.rtol),
                    rc.phase_portrait(d, 256),
                )
                .with_color(BLACK),
            );
            series[0].line_width = 3.0;
        }
        for (i, r) in c.chbm.iter().enumerate() {
            series.push(
                Series::line(
                    format!("CHBM {}H", r.harmonics),
                    r.cycle.phase_portrait(d, 256),
                )
                .with_dash(DASHES[i % DASHES.len()]),
            );
        }
        panels.push(Panel {
            title,
            x_label: "displacement (m)".into(),
            y_label: "velocity (m/s)".into(),
            series,
            ..Panel::default()
        });
    }
    Figure {
        title: format!("Limit cycles at {ratio} mu0, CHBM over time integration (paper Figure 4)"),
        panels,
        ..Figure::default()
    }
}

/// Figure 5: power ratio per harmonic, eqs (49)–(50).
fn figure5(c: &Comparison, ratio: f64) -> Figure {
    let total = c.power_reference.max(f64::MIN_POSITIVE);
    let bars = |name: String, power: &[f64]| {
        Series::bars(
            name,
            power
                .iter()
                .enumerate()
                .map(|(j, pj)| ((j + 1) as f64, pj / total))
                .collect(),
        )
    };
    let mut series = Vec::new();
    if let Some(m) = &c.reference.measures {
        series.push(bars(format!("BDF {:e}", c.reference.rtol), &m.power).with_color(BLACK));
    }
    for r in &c.chbm {
        series.push(bars(format!("CHBM {}H", r.harmonics), &r.measures.power));
    }
    let hmax = c.chbm.iter().map(|r| r.harmonics).max().unwrap_or(1);
    Figure::single(
        format!("Power ratio per harmonic at {ratio} mu0 (paper Figure 5, eqs 49-50)"),
        Panel {
            title: "R_j = P_j / P_temporal".into(),
            x_label: "harmonic j".into(),
            y_label: "power ratio R_j".into(),
            y_scale: Scale::Log,
            x_ticks: (1..=hmax).map(|j| (j as f64, j.to_string())).collect(),
            series,
            ..Panel::default()
        },
    )
}

/// Wall time against displacement error (log-log), CHBM per H and BDF per tolerance.
fn speed_accuracy(c: &Comparison, ratio: f64) -> Figure {
    let mut annotations = Vec::new();
    let chbm: Vec<(f64, f64)> = c
        .chbm
        .iter()
        .map(|r| {
            let pt = (r.wall.as_secs_f64(), r.measures.all.displacement);
            annotations.push(Annotation::Label {
                at: pt,
                text: format!("{}H", r.harmonics),
            });
            pt
        })
        .collect();
    let ti: Vec<(f64, f64)> =
        c.ti.iter()
            .filter_map(|r| {
                let m = r.measures.as_ref()?;
                let pt = (r.run.wall.as_secs_f64(), m.all.displacement);
                annotations.push(Annotation::Label {
                    at: pt,
                    text: format!("rtol {:e}", r.rtol),
                });
                Some(pt)
            })
            .collect();
    annotations.push(Annotation::VLine {
        x: c.reference.run.wall.as_secs_f64(),
        label: format!("reference BDF {:e}", c.reference.rtol),
        dash: Dash::Dotted,
    });
    Figure::single(
        format!("Speed against accuracy at {ratio} mu0"),
        Panel {
            title: format!(
                "displacement error (all dofs) against BDF rtol {:e}",
                c.reference.rtol
            ),
            x_label: "wall time (s)".into(),
            y_label: "relative displacement error".into(),
            x_scale: Scale::Log,
            y_scale: Scale::Log,
            series: vec![
                Series::markers("CHBM", chbm),
                Series::markers("BDF time integration", ti),
            ],
            annotations,
            ..Panel::default()
        },
    )
}

/// The reference integration's growth to the limit cycle: peak-to-peak penetration rate per
/// cycle.
fn growth(c: &Comparison, ratio: f64) -> Figure {
    let pts: Vec<(f64, f64)> = c
        .estimate
        .seed
        .run
        .history
        .iter()
        .map(|r| (r.t_start, r.amplitude()))
        .collect();
    Figure::single(
        format!("Time integration to the limit cycle at {ratio} mu0"),
        Panel {
            title: "peak-to-peak penetration rate of the most moving pair, per cycle".into(),
            x_label: "time (s)".into(),
            y_label: "peak-to-peak (m/s)".into(),
            series: vec![Series::line(format!("BDF {:e}", c.estimate.seed.rtol), pts)],
            ..Panel::default()
        },
    )
}

fn comparison_json(c: &Comparison, ratio: f64, files: &[String]) -> serde_json::Value {
    let chbm: Vec<_> = c
        .chbm
        .iter()
        .map(|r| {
            serde_json::json!({
                "harmonics": r.harmonics,
                "outcome": r.solution.outcome.to_string(),
                "frequency_hz": r.cycle.frequency_hz(),
                "dfreq_hz": r.measures.all.frequency_hz,
                "err_disp_all": r.measures.all.displacement,
                "err_vel_all": r.measures.all.velocity,
                "err_disp_contact": r.measures.contact.displacement,
                "err_vel_contact": r.measures.contact.velocity,
                "iterations": r.iterations,
                "wall_s": r.wall.as_secs_f64(),
                "storage_bytes": r.solution.storage_bytes(),
                "energy_balance": r.measures.energy.relative,
                "open_fraction": r.measures.open_fraction,
                "sliding_margin": r.measures.sliding.as_ref().map(|g| g.min),
            })
        })
        .collect();
    let ti: Vec<_> = [&c.estimate.seed, &c.estimate.check, &c.reference]
        .into_iter()
        .chain(&c.ti)
        .map(|r| {
            serde_json::json!({
                "rtol": r.rtol,
                "steady": r.run.steady.is_some(),
                "failure": r.run.failure.as_ref().map(|f| f.to_string()),
                "frequency_hz": r.cycle.as_ref().map(|c| c.frequency_hz()),
                "err_disp_all": r.measures.as_ref().map(|m| m.all.displacement),
                "err_vel_all": r.measures.as_ref().map(|m| m.all.velocity),
                "steps": r.run.stats.steps,
                "rejected": r.run.stats.rejected_error + r.run.stats.rejected_newton,
                "lu": r.run.stats.lu_decomps,
                "wall_s": r.run.wall.as_secs_f64(),
                "cycles": r.run.steady.as_ref().map(|s| s.cycles),
                "drift": r.run.steady.as_ref().map(|s| s.drift),
                "history_bytes": r.run.history_bytes(),
                "energy_balance": r.measures.as_ref().map(|m| m.energy.relative),
                "sliding_margin": r.measures.as_ref().and_then(|m| m.sliding.as_ref()).map(|g| g.min),
            })
        })
        .collect();
    serde_json::json!({
        "mu_ratio": ratio,
        "mu": c.mu,
        "folder": format!("mu_{ratio:.3}"),
        "files": files,
        "chbm": chbm,
        "time_integration": ti,
        "reference": reference_json(c),
    })
}

fn errors_json(e: &Option<RelativeErrors>) -> serde_json::Value {
    e.as_ref().map_or(serde_json::Value::Null, |e| {
        serde_json::json!({
            "err_disp": e.displacement,
            "err_vel": e.velocity,
            "dfreq_hz": e.frequency_hz,
            "dfreq_rel": e.frequency_relative,
        })
    })
}

/// The reference's tolerances, cost and estimated own error.
fn reference_json(c: &Comparison) -> serde_json::Value {
    let e = &c.estimate;
    serde_json::json!({
        "rtol": c.reference.rtol,
        "seed_rtol": e.seed.rtol,
        "check_rtol": e.check.rtol,
        "richardson_scale": e.scale,
        "asked_rtol_unsteady": e.unsteady.as_ref().map(|u| u.rtol),
        "estimated_error_all": errors_json(&e.all),
        "estimated_error_contact": errors_json(&e.contact),
        "steps": e.steps(&c.reference),
        "wall_s": e.wall(&c.reference).as_secs_f64(),
    })
}

/// The robustness map and the time integration over the same μ.
fn run_grid(
    dir: &Path,
    m: &Model,
    st: &Stability,
    mu0: f64,
    settings: &CompareSettings,
    log: Log,
) -> Result<serde_json::Value> {
    let model = GridModel {
        brake: &m.brake,
        reference: &st.reference,
        mu0,
        band: m.sweep.band,
        newton: m.sweep.newton,
    };
    let opts = GridOptions {
        harmonics: settings.harmonics.clone(),
        chbm: ChbmOptions::default(),
        ti: TiOptions {
            rtol: 1e-6,
            perturbation: settings.perturbation,
            max_order: settings.max_order,
            max_cycles: 2000.0,
            ..TiOptions::default()
        },
        ..GridOptions::default()
    };
    log(&format!(
        "\n== robustness: {} friction levels x {} initial amplitudes x {} harmonic counts, and BDF rtol 1e-6 at each level",
        opts.mu_ratios.len(),
        opts.amplitudes.len(),
        opts.harmonics.len()
    ));
    let (cells, ti) = robustness(&model, &opts, &mut |r| log(&format!("  {r} mu0 done")));
    let t = grid_table(&cells);
    t.write_csv(&dir.join("robustness.csv"))?;
    let tt = ti_grid_table(&ti);
    log(&format!("\nTime integration over mu:\n{}", tt.to_text()));
    tt.write_csv(&dir.join("robustness_ti.csv"))?;
    log(&grid_summary(&cells, &opts).to_text());
    write_svg_and_png(&grid_figure(&cells, &opts), &dir.join("robustness"))?;
    Ok(serde_json::json!({
        "files": ["robustness.csv", "robustness_ti.csv", "robustness.svg"],
        "mu_ratios": opts.mu_ratios,
        "amplitudes": opts.amplitudes,
        "harmonics": opts.harmonics,
    }))
}

/// Map categories: the outcomes, with limit cycles split by whether the contact opens.
fn category(c: &GridCell) -> usize {
    match c.outcome {
        CellOutcome::LimitCycle if c.open_fraction > 0.0 => 1,
        CellOutcome::LimitCycle => 0,
        CellOutcome::Unconstrained => 2,
        CellOutcome::Static => 3,
        CellOutcome::NotConverged => 4,
        CellOutcome::Failed => 5,
    }
}

const CATEGORIES: [(&str, Rgb); 6] = [
    ("limit cycle, contact closed", Rgb(44, 160, 44)),
    ("limit cycle, contact opens", Rgb(152, 223, 138)),
    ("HB root, |Re lambda| > eps2", Rgb(255, 187, 120)),
    ("static solution", Rgb(31, 119, 180)),
    ("not converged", Rgb(214, 39, 40)),
    ("failed", Rgb(127, 127, 127)),
];

fn grid_figure(cells: &[GridCell], opts: &GridOptions) -> Figure {
    let panels = opts
        .harmonics
        .iter()
        .map(|&h| {
            let mut grid_cells = vec![None; opts.mu_ratios.len() * opts.amplitudes.len()];
            for c in cells.iter().filter(|c| c.harmonics == h) {
                let ix = opts.mu_ratios.iter().position(|r| *r == c.mu_ratio);
                let iy = opts.amplitudes.iter().position(|a| *a == c.amplitude);
                if let (Some(ix), Some(iy)) = (ix, iy) {
                    grid_cells[iy * opts.mu_ratios.len() + ix] = Some(category(c));
                }
            }
            Panel {
                title: format!("{h} harmonic{}", if h == 1 { "" } else { "s" }),
                x_label: "mu / mu0".into(),
                y_label: "initial amplitude p".into(),
                x_scale: Scale::Log,
                y_scale: Scale::Log,
                grid: Some(CategoryGrid {
                    x: opts.mu_ratios.clone(),
                    y: opts.amplitudes.clone(),
                    cells: grid_cells,
                    categories: CATEGORIES
                        .iter()
                        .map(|(n, c)| Category {
                            name: (*n).into(),
                            color: Some(*c),
                        })
                        .collect(),
                }),
                ..Panel::default()
            }
        })
        .collect();
    Figure {
        title: "Where CHBM converges (ladder: one harmonic first), from eq (48) with amplitude p"
            .into(),
        panels,
        layout: Layout::Grid { columns: 3 },
        ..Figure::default()
    }
}

fn grid_table(cells: &[GridCell]) -> Table {
    let mut t = Table::new([
        "mu_ratio",
        "initial_amplitude_p",
        "harmonics",
        "outcome",
        "lm_iterations",
        "time_ms",
        "frequency_hz",
        "max_open_fraction",
    ]);
    for c in cells {
        t.push_row([
            format!("{}", c.mu_ratio),
            format!("{}", c.amplitude),
            c.harmonics.to_string(),
            c.outcome.label().to_string(),
            c.iterations.to_string(),
            fmt_sig(c.time.as_secs_f64() * 1e3, 3),
            format!("{}", c.frequency_hz),
            format!("{}", c.open_fraction),
        ]);
    }
    t
}

/// Per μ and H: how many amplitudes converge, and the median iterations of those.
fn grid_summary(cells: &[GridCell], opts: &GridOptions) -> Table {
    let mut header = vec!["mu/mu0".to_string()];
    header.extend(
        opts.harmonics
            .iter()
            .map(|h| format!("{h}H: converged/tried")),
    );
    header.push("open fraction (3H)".into());
    let mut t = Table::new(header);
    for &r in &opts.mu_ratios {
        let mut row = vec![format!("{r}")];
        for &h in &opts.harmonics {
            let these: Vec<&GridCell> = cells
                .iter()
                .filter(|c| c.mu_ratio == r && c.harmonics == h)
                .collect();
            let ok = these
                .iter()
                .filter(|c| c.outcome == CellOutcome::LimitCycle)
                .count();
            row.push(format!("{ok}/{}", these.len()));
        }
        let open = cells
            .iter()
            .filter(|c| c.mu_ratio == r && c.harmonics == 3 && c.outcome == CellOutcome::LimitCycle)
            .map(|c| c.open_fraction)
            .fold(f64::NAN, f64::max);
        row.push(if open.is_nan() {
            "-".into()
        } else {
            pct(open) + " %"
        });
        t.push_row(row);
    }
    t.align_numbers_right()
}

fn ti_grid_table(cells: &[TiCell]) -> Table {
    let mut t = Table::new([
        "mu/mu0",
        "result",
        "cycles",
        "steps",
        "rejected (error test)",
        "rejected (Newton)",
        "LU",
        "wall (s)",
        "frequency (Hz)",
        "max open fraction (%)",
    ]);
    for c in cells {
        let Some(run) = &c.run else {
            t.push_row(
                vec![
                    format!("{}", c.mu_ratio),
                    format!("no start: {}", c.failure.clone().unwrap_or_default()),
                ]
                .into_iter()
                .chain(std::iter::repeat_n("-".to_string(), 8)),
            );
            continue;
        };
        let st = &run.stats;
        t.push_row([
            format!("{}", c.mu_ratio),
            match (&run.steady, &c.failure) {
                (Some(_), _) => "steady".into(),
                (None, Some(f)) => format!("failed: {f}"),
                (None, None) => "no steady cycle".into(),
            },
            run.history.len().to_string(),
            st.steps.to_string(),
            st.rejected_error.to_string(),
            st.rejected_newton.to_string(),
            st.lu_decomps.to_string(),
            fmt_sig(run.wall.as_secs_f64(), 3),
            run.steady
                .as_ref()
                .map_or("-".into(), |s| fmt_sig(1.0 / s.period, 8)),
            if c.open_fraction.is_nan() {
                "-".into()
            } else {
                pct(c.open_fraction)
            },
        ]);
    }
    t
}
