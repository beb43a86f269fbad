//! The comparison's figures: the paper's Figures 4 (limit cycles) and 5 (power per
//! harmonic), speed against accuracy, and a time integration's growth to its cycle.

use crate::chbm::point_dof;
use crate::model::Model;
use squeal_chbm::compare::Comparison;
use squeal_report::{Annotation, Dash, Figure, Panel, Rgb, Scale, Series};

const DASHES: [Dash; 4] = [Dash::Dashed, Dash::DashDot, Dash::Dotted, Dash::Solid];
const BLACK: Rgb = Rgb(0, 0, 0);

/// Figure 4: limit cycles of a pad and a disc contact normal dof, CHBM over the reference.
pub(super) fn figure4(m: &Model, c: &Comparison, ratio: f64) -> Figure {
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
        let rc = &c.reference.reference.cycle;
        series.push(
            Series::line(
                format!("reference (shooting {:e})", c.reference.reference.rtol),
                rc.phase_portrait(d, 256),
            )
            .with_color(BLACK),
        );
        series[0].line_width = 3.0;
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
pub(super) fn figure5(c: &Comparison, ratio: f64) -> Figure {
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
    series.push(
        bars(
            format!("reference (shooting {:e})", c.reference.reference.rtol),
            &c.reference_measures.power,
        )
        .with_color(BLACK),
    );
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
pub(super) fn speed_accuracy(c: &Comparison, ratio: f64) -> Figure {
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
        x: c.reference.wall().as_secs_f64(),
        label: format!("reference (shooting {:e})", c.reference.reference.rtol),
        dash: Dash::Dotted,
    });
    Figure::single(
        format!("Speed against accuracy at {ratio} mu0"),
        Panel {
            title: format!(
                "displacement error (all dofs) against the reference (shooting {:e}); failed integrations not shown",
                c.reference.reference.rtol
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

/// Each time integration's growth to its limit cycle: peak-to-peak penetration rate per
/// cycle (a failed run too: its history is what it did).
pub(super) fn growth(c: &Comparison, ratio: f64) -> Figure {
    let series =
        c.ti.iter()
            .enumerate()
            .map(|(i, r)| {
                let pts = r
                    .run
                    .history
                    .iter()
                    .map(|h| (h.t_start, h.amplitude()))
                    .collect();
                let status = if r.run.steady.is_some() {
                    ""
                } else {
                    " (failed)"
                };
                Series::line(format!("BDF {:e}{status}", r.rtol), pts)
                    .with_dash(DASHES[i % DASHES.len()])
            })
            .collect();
    Figure::single(
        format!("Time integration to the limit cycle at {ratio} mu0"),
        Panel {
            title: "peak-to-peak penetration rate of the most moving pair, per cycle".into(),
            x_label: "time (s)".into(),
            y_label: "peak-to-peak (m/s)".into(),
            series,
            ..Panel::default()
        },
    )
}
