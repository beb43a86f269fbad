//! Where each method fails: CHBM over friction levels, initial amplitudes and harmonics, and
//! the time integration over the same friction levels (`squeal compare --grid`).

use super::CompareSettings;
use super::tables::pct;
use crate::error::Result;
use crate::model::{Log, Model};
use squeal_brake::analysis::LinearStability as Stability;
use squeal_chbm::ChbmOptions;
use squeal_chbm::compare::{CellOutcome, GridCell, GridModel, GridOptions, TiCell, robustness};
use squeal_chbm::timeint::TiOptions;
use squeal_report::format::fmt_sig;
use squeal_report::{
    Category, CategoryGrid, Figure, Layout, Panel, Rgb, Scale, Table, write_svg_and_png,
};
use std::path::Path;

/// The robustness map and the time integration over the same μ.
pub(super) fn run_grid(
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
    let opts = {
        let mut o = GridOptions::default();
        o.harmonics = settings.harmonics.clone();
        o.chbm = ChbmOptions::default();
        o.ti = {
            let mut o = TiOptions::default();
            o.rtol = 1e-6;
            o.perturbation = settings.perturbation;
            o.max_order = settings.max_order;
            o.max_cycles = 2000.0;
            o
        };
        o
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
