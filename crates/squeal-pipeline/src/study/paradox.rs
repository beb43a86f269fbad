//! The damping-induced destabilization at vanishing friction (the "paradox" study): the
//! scene's damping on the coalescing pair with and without the global part, and none, and the
//! growth of the other in-band modes at small friction (moved from `study.rs` unchanged).

use super::record::{F, GrowthRecord, ParadoxRecord};
use crate::error::{Context, PipelineError, Result};
use crate::model::{Log, Model};
use squeal_brake::analysis::{DampingSpec, PairChoice, basis_mode_of_branch, stability};
use squeal_brake::studies::{GrowthRow, log_slope, other_mode_growth, small_friction_grid};
use squeal_report::format::{fmt_sci, fmt_sig};
use squeal_report::{Dash, Figure, Panel, Scale, Series, Table, palette_color, write_svg_and_png};
use std::path::Path;

/// The friction values of the paradox study: the small-friction grid, then the sweep's values
/// above it (to see the pair's own crossing).
pub(super) fn paradox_grid(mus: &[f64]) -> Vec<f64> {
    let mut g = small_friction_grid();
    let top = g[g.len() - 1];
    g.extend(mus.iter().copied().filter(|m| *m > top * (1.0 + 1e-12)));
    g
}

/// Damping case `i` of the paradox study ([`shard::PARADOX_CASES`] of them): the scene's
/// damping on the nominal pair, the pair's alone, none.
fn paradox_spec(s: &Model, pair: (usize, usize), i: usize) -> Result<(&'static str, DampingSpec)> {
    let nominal = DampingSpec {
        pair: PairChoice::Modes(pair.0, pair.1),
        ..s.damping
    };
    Ok(match i {
        0 => ("global + pair (scene)", nominal),
        1 => (
            "pair only (no global part)",
            DampingSpec {
                global_ratio: 0.0,
                ..nominal
            },
        ),
        2 => (
            "undamped",
            DampingSpec {
                global_ratio: 0.0,
                pair_ratios: [0.0, 0.0],
                ..nominal
            },
        ),
        _ => {
            return Err(PipelineError::input(
                "paradox study",
                format!("no damping case {}", i + 1),
            ));
        }
    })
}

/// Runs damping case `i` of the paradox study over the friction values `grid`.
pub(super) fn paradox_case(
    s: &Model,
    pair: (usize, usize),
    grid: &[f64],
    i: usize,
) -> Result<ParadoxRecord> {
    let (label, spec) = paradox_spec(s, pair, i)?;
    let st = stability(&s.brake, &spec, grid, &s.sweep)
        .with_context(|| format!("paradox study, {label}"))?;
    let rows = other_mode_growth(&s.brake, &st, &s.sweep)?;
    let hopf = st.sweep.hopf.as_ref().map(|h| {
        let m = basis_mode_of_branch(&st.sweep, h.branch);
        (F(h.mu0), F(h.frequency_hz), m, m == pair.0 || m == pair.1)
    });
    Ok(ParadoxRecord {
        label: label.into(),
        global_ratio: F(spec.global_ratio),
        pair_ratios: spec.pair_ratios.map(F),
        rows: rows.iter().map(GrowthRecord::from).collect(),
        hopf,
    })
}

/// Writes the paradox study from its damping cases (in order).
pub(super) fn write_paradox(cases: &[&ParadoxRecord], dir: &Path, log: Log) -> Result<()> {
    let small = small_friction_grid();
    let top = small[small.len() - 1] * (1.0 + 1e-12);
    let rows: Vec<Vec<GrowthRow>> = cases
        .iter()
        .map(|c| c.rows.iter().map(GrowthRecord::row).collect())
        .collect();
    let mut t = Table::new([
        "case",
        "mu",
        "max_re_over_abs_other_modes",
        "second_order_prediction",
        "re_per_s",
        "at_hz",
        "frictionless_mode",
        "unstable_other_modes_in_band",
    ]);
    for (c, rows) in cases.iter().zip(&rows) {
        for r in rows.iter().filter(|r| r.mu <= top) {
            t.push_row([
                c.label.clone(),
                fmt_sig(r.mu, 2),
                fmt_sci(r.max_ratio, 3),
                fmt_sci(r.predicted_ratio, 3),
                fmt_sci(r.real_part, 3),
                fmt_sig(r.frequency_hz, 5),
                format!("#{}", r.basis_mode + 1),
                r.unstable.to_string(),
            ]);
        }
    }
    let t = t.align_numbers_right();
    let mut summary = Table::new([
        "case",
        "global_ratio",
        "pair_ratios",
        "first_in_band_crossing_mu0",
        "at_hz",
        "frictionless_mode",
        "is_the_pair",
        "slope_log_re_vs_log_mu",
    ]);
    for (c, rows) in cases.iter().zip(&rows) {
        summary.push_row([
            c.label.clone(),
            fmt_sig(c.global_ratio.0, 2),
            format!(
                "{}/{}",
                fmt_sig(c.pair_ratios[0].0, 2),
                fmt_sig(c.pair_ratios[1].0, 2)
            ),
            c.hopf.map_or("none".into(), |h| fmt_sig(h.0.0, 6)),
            c.hopf.map_or("-".into(), |h| fmt_sig(h.1.0, 5)),
            c.hopf.map_or("-".into(), |h| format!("#{}", h.2 + 1)),
            c.hopf
                .map_or("-".into(), |h| if h.3 { "yes" } else { "no" }.into()),
            growth_slope(rows).map_or("-".into(), |v| fmt_sig(v, 3)),
        ]);
    }
    let summary = summary.align_numbers_right();
    log(
        "\nDamping on the coalescing pair (eq 13) with and without the global part: growth of the OTHER in-band modes at small friction (Re/|lambda| = -zeta when damped; > 0 is unstable)",
    );
    log(&t.to_text());
    log("first in-band crossing of each case (the mu0 a stability analysis would report):");
    log(&summary.to_text());
    t.write_csv(&dir.join("paradox.csv"))?;
    summary.write_csv(&dir.join("paradox_summary.csv"))?;
    squeal_io::atomic_write_bytes(
        &dir.join("paradox.md"),
        format!("{}\n{}", t.to_markdown(), summary.to_markdown()).as_bytes(),
    )?;
    let labelled: Vec<(&str, &[GrowthRow])> = cases
        .iter()
        .zip(&rows)
        .map(|(c, r)| (c.label.as_str(), r.as_slice()))
        .collect();
    paradox_figure(&labelled, top, &dir.join("paradox"))
}

/// Slope of ln(max Re/|λ|) against ln μ for μ in 1e-3..1e-2 (2 for second-order growth).
fn growth_slope(rows: &[GrowthRow]) -> Option<f64> {
    let r: Vec<&GrowthRow> = rows
        .iter()
        .filter(|r| r.mu >= 1e-3 * (1.0 - 1e-12) && r.mu <= 1e-2 * (1.0 + 1e-12))
        .collect();
    // Only a growth well above round-off (the undamped case's ~1e-16) has a slope.
    if r.iter().any(|r| r.max_ratio <= 1e-12) {
        return None;
    }
    let x: Vec<f64> = r.iter().map(|r| r.mu).collect();
    let y: Vec<f64> = r.iter().map(|r| r.max_ratio).collect();
    log_slope(&x, &y)
}

/// The growth of the other modes against μ, one colour per damping case (label, rows).
fn paradox_figure(cases: &[(&str, &[GrowthRow])], top: f64, stem: &Path) -> Result<()> {
    let mut p = Panel {
        title: "largest Re/|lambda| of the other in-band modes".into(),
        x_label: "friction coefficient mu".into(),
        y_label: "Re(lambda)/|lambda| (positive: unstable)".into(),
        x_scale: Scale::Log,
        y_scale: Scale::Log,
        ..Panel::default()
    };
    for (i, (label, rows)) in cases.iter().enumerate() {
        let rows: Vec<&GrowthRow> = rows.iter().filter(|r| r.mu > 0.0 && r.mu <= top).collect();
        if rows.iter().all(|r| r.max_ratio <= 0.0) {
            continue;
        }
        let color = palette_color(i);
        p.series.push(
            Series::line_markers(*label, rows.iter().map(|r| (r.mu, r.max_ratio)).collect())
                .with_color(color),
        );
        p.series.push(
            Series::line(
                format!("{label}: second-order prediction"),
                rows.iter().map(|r| (r.mu, r.predicted_ratio)).collect(),
            )
            .with_color(color)
            .with_dash(Dash::Dashed),
        );
    }
    let fig = Figure::single(
        "Damping on the pair only: the other modes grow like mu^2 (with the global part: Re/|lambda| = -zeta)",
        p,
    );
    // Non-positive values (the damped cases) cannot be drawn on a log axis: expected.
    write_svg_and_png(&fig, stem)?;
    Ok(())
}
