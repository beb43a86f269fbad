//! The convergence study's outputs: the verdicts and the table on screen (verdict first),
//! `convergence.csv` and `.md`, `convergence.json`, and the figure of μ0 against each knob's
//! levels (`convergence.svg`, `.png`).

use super::{Knob, LevelResult, Study};
use crate::error::{Result, json_text};
use crate::model::Log;
use squeal_report::format::fmt_sig;
use squeal_report::{Figure, Layout, Panel, Series, Table, write_svg_and_png};
use std::path::Path;

fn opt(x: Option<f64>, digits: usize) -> String {
    x.map_or("-".into(), |v| fmt_sig(v, digits))
}

/// `disc 0.62, pad 0.38`.
fn energy_text(l: &LevelResult) -> String {
    l.shape.as_ref().map_or("-".into(), |s| {
        s.energy
            .iter()
            .map(|(p, e)| format!("{p} {e:.3}"))
            .collect::<Vec<_>>()
            .join(", ")
    })
}

/// The growth-rate column's header, with its friction.
fn growth_header(study: &Study) -> String {
    study.growth_mu.map_or("growth_per_s".into(), |m| {
        format!("growth_per_s_at_mu_{}", fmt_sig(m, 4))
    })
}

/// One row per level of each knob (the base repeated at the head of each).
pub fn table(study: &Study) -> Table {
    let growth = growth_header(study);
    let mut t = Table::new([
        "knob",
        "level",
        "reduced_dofs",
        "nodes",
        "contact_pairs",
        "mu0",
        "frequency_hz",
        growth.as_str(),
        "mu0_change",
        "mac_vs_previous",
        "nodal_diameters",
        "kinetic_energy_share",
    ]);
    for k in &study.knobs {
        let mut prev: Option<f64> = None;
        for (j, &i) in k.levels.iter().enumerate() {
            let l = &study.levels[i];
            let change = l.mu0.zip(prev).map_or("-".into(), |(a, b)| {
                format!("{:+.3}%", 100.0 * (a / b - 1.0))
            });
            t.push_row([
                k.knob.name().to_string(),
                l.setting.label(k.knob, study.base_modes),
                l.dofs.to_string(),
                l.nodes.to_string(),
                l.pairs.to_string(),
                l.mu0.map_or_else(
                    || {
                        if l.note
                            .as_deref()
                            .is_some_and(|n| n.starts_with("the analysis failed"))
                        {
                            "failed".into()
                        } else {
                            "none".into()
                        }
                    },
                    |m| fmt_sig(m, 6),
                ),
                opt(l.frequency_hz, 6),
                opt(study.growth_mu.and_then(|m| l.growth_at(m)), 4),
                change,
                opt(k.mac[j], 4),
                l.shape
                    .as_ref()
                    .and_then(|s| s.nodal_diameters)
                    .map_or("-".into(), |n| n.to_string()),
                energy_text(l),
            ]);
            prev = l.mu0;
        }
    }
    t.align_numbers_right()
}

/// The verdicts as lines: the overall one, then one per knob.
pub fn verdict_text(study: &Study) -> String {
    let mut s = format!("Convergence of the Hopf point: {}\n", study.overall.1);
    for k in &study.knobs {
        s.push_str(&format!("  {}: {}\n", k.knob.name(), k.verdict.text));
    }
    s
}

fn json(study: &Study) -> serde_json::Value {
    let level = |k: Knob, j: usize, i: usize, mac: Option<f64>| {
        let l = &study.levels[i];
        serde_json::json!({
            "level": l.setting.label(k, study.base_modes),
            "contact": l.setting.contact.label(),
            "modes_per_part": l.setting.modes,
            "mesh_level": l.setting.level,
            "reduced_dofs": l.dofs,
            "nodes": l.nodes,
            "contact_pairs": l.pairs,
            "mu0": l.mu0,
            "frequency_hz": l.frequency_hz,
            "growth_per_s": study.growth_mu.and_then(|m| l.growth_at(m)),
            "mac_vs_previous": mac,
            "refinement": j,
            "nodal_diameters": l.shape.as_ref().and_then(|s| s.nodal_diameters),
            "kinetic_energy_share": l.shape.as_ref().map(|s| s.energy.iter().map(|(p, e)| serde_json::json!({"part": p, "share": e})).collect::<Vec<_>>()),
            "note": l.note,
        })
    };
    serde_json::json!({
        "tolerance": study.tolerance,
        "growth_mu": study.growth_mu,
        "overall": { "status": study.overall.0.name(), "text": study.overall.1 },
        "knobs": study.knobs.iter().map(|k| serde_json::json!({
            "knob": k.knob.name(),
            "verdict": {
                "status": k.verdict.status.name(),
                "text": k.verdict.text,
                "last_change": k.verdict.last_change,
                "rate": k.verdict.rate.map(|r| serde_json::json!({
                    "ratio": r.ratio, "oscillating": r.oscillating, "extrapolated_mu0": r.limit,
                })),
            },
            "levels": k.levels.iter().enumerate().map(|(j, &i)| level(k.knob, j, i, k.mac[j])).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    })
}

/// μ0 against reduced dofs (contact, modes) or mesh nodes (mesh), one panel per knob.
fn figure(study: &Study) -> Figure {
    let panels = study
        .knobs
        .iter()
        .enumerate()
        .map(|(n, k)| {
            let x = |l: &LevelResult| {
                if k.knob == Knob::Mesh {
                    l.nodes as f64
                } else {
                    l.dofs as f64
                }
            };
            let points = k
                .levels
                .iter()
                .map(|&i| &study.levels[i])
                .filter_map(|l| l.mu0.map(|m| (x(l), m)))
                .collect();
            Panel {
                title: format!(
                    "({}) {}: {}",
                    char::from(b'a' + (n as u8 % 26)),
                    k.knob.name(),
                    k.verdict.status.name()
                ),
                x_label: if k.knob == Knob::Mesh {
                    "nodes (all parts)"
                } else {
                    "reduced dofs"
                }
                .into(),
                y_label: "mu0".into(),
                series: vec![Series::line_markers(k.knob.name(), points)],
                ..Panel::default()
            }
        })
        .collect::<Vec<_>>();
    Figure {
        title: "Convergence of the Hopf point mu0 under refinement".into(),
        layout: Layout::Grid {
            columns: panels.len().min(3),
        },
        panels,
        ..Figure::default()
    }
}

/// Prints the verdicts, then the table, and writes the files.
pub fn write(study: &Study, dir: &Path, log: Log) -> Result<()> {
    let t = table(study);
    let v = verdict_text(study);
    log(&format!("\n{v}"));
    log(&t.to_text());
    for l in &study.levels {
        if let Some(n) = &l.note {
            log(&format!("{}: {n}", l.setting.key()));
        }
    }
    match study.growth_mu {
        Some(m) => log(&format!(
            "growth: Re(lambda) (1/s) of the branch that goes unstable, at mu = {}",
            fmt_sig(m, 4)
        )),
        None => log(
            "growth: no friction to evaluate it at (the base level has no Hopf point; give --growth-mu)",
        ),
    }
    t.write_csv(&dir.join("convergence.csv"))?;
    squeal_io::atomic_write_bytes(
        &dir.join("convergence.md"),
        format!("{}\n{}", v.replace('\n', "\n\n"), t.to_markdown()).as_bytes(),
    )?;
    squeal_io::atomic_write_bytes(
        &dir.join("convergence.json"),
        json_text(&json(study), "the convergence study")?.as_bytes(),
    )?;
    for n in write_svg_and_png(&figure(study), &dir.join("convergence"))? {
        log(&format!("note: {n}"));
    }
    Ok(())
}
