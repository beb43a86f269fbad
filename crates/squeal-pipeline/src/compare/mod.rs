//! Issue #6's comparison of the Constrained Harmonic Balance Method against BDF time
//! integration of the full brake — the paper's Tables 1–2 and Figures 4–5 for our brake, a
//! speed–accuracy chart, and (optionally) where each method fails.
//!
//! Error definitions (also in every CSV header): both cycles are aligned in time on the first
//! harmonic of the reference's most moving contact dof; the relative error is the RMS over one
//! cycle (in phase ωt) and over the dofs of `x_method - x_reference`, mean included, divided by
//! the RMS of the reference's oscillation; the same for velocities; "all" is every physical dof
//! of the reduced brake, "contact" the dofs the contact forces act on.

mod figures;
mod grid;
mod tables;

use crate::Pipeline;
use crate::error::{PipelineError, Result, json_text};
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::ChbmStart;
use squeal_chbm::compare::{CompareOptions, Comparison, compare_levels};
use squeal_chbm::cycle::RelativeErrors;
use squeal_chbm::shooting::ShootingReferenceOptions;
use squeal_chbm::timeint::TiOptions;
use squeal_report::Table;
use std::path::Path;
pub use tables::ERROR_DEFINITION;

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
    /// Periods after which a time integration that has not settled is reported as failed.
    pub max_cycles: f64,
    pub grid: bool,
}

impl Default for CompareSettings {
    fn default() -> Self {
        let ti = TiOptions::default();
        Self {
            mu_ratios: vec![1.01, 1.1],
            harmonics: CompareOptions::default().harmonics,
            rtols: CompareOptions::default().rtols,
            reference_rtol: CompareOptions::default().reference.rtol,
            perturbation: ti.perturbation,
            max_order: ti.max_order,
            max_cycles: TI_MAX_CYCLES,
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
        if self.reference_rtol > 1e-6 {
            return Err(PipelineError::input(
                "--reference-rtol",
                "must be at most 1e-6 (the reference must be more accurate than what it judges; its error is estimated by a solve at 10 times it)",
            ));
        }
        if !(self.perturbation.is_finite() && self.perturbation > 0.0 && self.perturbation <= 10.0)
        {
            return Err(PipelineError::input("--perturbation", "must be in (0, 10]"));
        }
        if !(self.max_cycles.is_finite() && (10.0..=1e6).contains(&self.max_cycles)) {
            return Err(PipelineError::input(
                "--max-cycles",
                "must be between 10 and 1e6 periods",
            ));
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
    // The integrations' Fourier averages and the reference keep at least as many harmonics
    // as CHBM's largest (at least 20), so that neither truncates what it judges.
    let ti_harmonics = settings
        .harmonics
        .iter()
        .copied()
        .max()
        .unwrap_or(1)
        .max(20);
    let mut reference = ShootingReferenceOptions::default();
    reference.rtol = settings.reference_rtol;
    reference.check_rtol = REFERENCE_CHECK_FACTOR * settings.reference_rtol;
    reference.harmonics = reference.harmonics.max(ti_harmonics);
    reference.samples = reference.samples.max(4 * ti_harmonics + 8);
    let opts = {
        let mut o = CompareOptions::default();
        o.harmonics = settings.harmonics.clone();
        o.ti = {
            let mut o = TiOptions::default();
            o.perturbation = settings.perturbation;
            o.max_order = settings.max_order;
            o.harmonics = ti_harmonics;
            o.samples_per_cycle = TiOptions::default()
                .samples_per_cycle
                .max(4 * ti_harmonics + 8);
            o.max_cycles = settings.max_cycles;
            o
        };
        o.rtols = settings.rtols.clone();
        o.reference = reference;
        o.disc = m.disc;
        o
    };
    let mut summary = Vec::new();
    let mut levels = Vec::new();
    let mut first = first;
    let steps = opts.steps().len() * settings.mu_ratios.len();
    progress.begin("CHBM against BDF", steps);
    // The starts follow one another (each from the last one's equilibrium); the comparisons
    // and their runs are independent and go side by side (`compare_levels`), each the same
    // bits as alone; the tables are written in the order of the friction levels.
    let mut guess: Option<Vec<f64>> = None;
    let mut runs = Vec::new();
    for &ratio in &settings.mu_ratios {
        let mu = ratio * mu0;
        let (start, mb) = match first.take() {
            Some(f) if (f.1.mu - mu).abs() <= 1e-12 * mu.abs() => f,
            _ => crate::chbm::start(m, st, mu, guess.as_deref())?,
        };
        guess = Some(start.equilibrium.clone());
        runs.push((ratio, start, mb));
    }
    let brakes: Vec<(&ModalBrake, &ChbmStart)> = runs.iter().map(|(_, s, mb)| (mb, s)).collect();
    let comparisons = compare_levels(&brakes, &opts, &|i, step| {
        progress.item(&format!("{} mu0: {step}", settings.mu_ratios[i]))
    })?;
    for ((ratio, _, mb), c) in runs.iter().zip(comparisons) {
        let ratio = *ratio;
        log(&format!(
            "\n== mu = {:.6} ({ratio} mu0): {} CHBM solves, {} BDF runs to the steady cycle, and the reference limit cycle by shooting (BDF rtol {:e}, checked at {:e})",
            mb.mu,
            settings.harmonics.len(),
            settings.rtols.len(),
            opts.reference.rtol,
            opts.reference.check_rtol,
        ));
        let folder = format!("mu_{ratio:.3}");
        let files = tables::write_comparison(&dir.join(&folder), m, &c, ratio, log)?;
        summary.push(comparison_json(&c, ratio, &files));
        levels.push(CompareLevel {
            ratio,
            mu: c.mu,
            folder,
            table1: tables::table1(&c),
            table2: tables::table2(&c),
            failures: failures(&c),
            files,
        });
    }
    progress.end();
    let mut grid_json = serde_json::Value::Null;
    if settings.grid {
        grid_json = grid::run_grid(dir, m, st, mu0, settings, log)?;
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
    for r in c.ti.iter().filter(|r| r.run.steady.is_none()) {
        out.push(format!(
            "BDF time integration at rtol {:e}: {}",
            r.rtol,
            r.run
                .failure
                .as_ref()
                .map_or("no steady cycle".to_string(), |f| f.to_string())
        ));
    }
    out
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
    let ti: Vec<_> = c
        .ti
        .iter()
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

fn errors_json(e: &RelativeErrors) -> serde_json::Value {
    serde_json::json!({
        "err_disp": e.displacement,
        "err_vel": e.velocity,
        "dfreq_hz": e.frequency_hz,
        "dfreq_rel": e.frequency_relative,
    })
}

/// The reference's tolerances, cost and stated own error.
fn reference_json(c: &Comparison) -> serde_json::Value {
    let r = &c.reference;
    serde_json::json!({
        "method": "shooting",
        "start": c.reference_start.to_string(),
        "rtol": r.reference.rtol,
        "check_rtol": r.check.rtol,
        "frequency_hz": r.reference.cycle.frequency_hz(),
        "period_s": r.reference.period,
        "periodicity_residual": r.reference.residual(),
        "residuals": r.reference.residuals,
        "check_periodicity_residual": r.check.residual(),
        "newton_monodromies": r.reference.monodromies + r.check.monodromies,
        "estimated_error_all": errors_json(&r.all),
        "estimated_error_contact": errors_json(&r.contact),
        "floquet_tangent_error": r.floquet.map(|f| f.tangent_error),
        "newton_trivial_multiplier": r.floquet.map(|f| [f.trivial.re, f.trivial.im]),
        "newton_leading_multiplier_modulus": r.floquet.map(|f| f.leading),
        "steps": r.steps(),
        "wall_s": r.wall().as_secs_f64(),
    })
}

/// Periods after which a time integration of the comparison that has not settled is reported
/// as failed: the runs that settle on the medium brake take 215-241 (1.01 and 1.1 μ0, rtol
/// 1e-5 and 1e-6); a BDF2 run at rtol 1e-5 at 1.1 μ0 had not settled after 5000.
const TI_MAX_CYCLES: f64 = 1000.0;

/// The check solve's tolerance over the reference's.
const REFERENCE_CHECK_FACTOR: f64 = 10.0;
