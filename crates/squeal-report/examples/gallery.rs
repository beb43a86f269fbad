//! Writes one sample of each kind of squeal figure (SVG and PNG) and a report folder indexing
//! them, with made-up but realistically shaped data.
//!
//! `cargo run --release -p squeal-report --example gallery -- /tmp/squeal-gallery`

use squeal_report::format::{fmt_si, fmt_sig};
use squeal_report::{
    Annotation, Category, CategoryGrid, Dash, Figure, Layout, LegendPosition, Panel, Report, Rgb,
    Scale, Section, Series, Table, write_svg_and_png,
};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

/// Figure 2 of the paper: real parts (a) and frequencies (b) of the modes against friction.
fn stability() -> Figure {
    let mus: Vec<f64> = (0..=60).map(|i| 0.5 * i as f64 / 60.0).collect();
    let mu0 = 0.2;
    // Two modes that coalesce at mu0, one that stays stable.
    let split = |mu: f64| {
        if mu > mu0 {
            4000.0 * (mu - mu0).sqrt()
        } else {
            0.0
        }
    };
    let real = |mu: f64, sign: f64| -15.0 + sign * split(mu);
    let freq = |mu: f64, sign: f64| {
        let gap = if mu < mu0 {
            300.0 * ((mu0 - mu) / mu0).sqrt()
        } else {
            0.0
        };
        2900.0 + 500.0 * mu + sign * gap
    };
    let mode = |f: &dyn Fn(f64) -> f64| mus.iter().map(|&m| (m, f(m))).collect::<Vec<_>>();
    let a = Panel {
        title: "(a) Real parts".into(),
        x_label: "Friction coefficient μ".into(),
        y_label: "Real part [1/s]".into(),
        series: vec![
            Series::line("mode 1", mode(&|m| real(m, 1.0))),
            Series::line("mode 2", mode(&|m| real(m, -1.0))).with_dash(Dash::Dashed),
            Series::line("mode 3", mode(&|m| -40.0 - 30.0 * m)).with_dash(Dash::DashDot),
        ],
        annotations: vec![
            Annotation::HLine {
                y: 0.0,
                label: "Re = 0".into(),
                dash: Dash::Dotted,
            },
            Annotation::VLine {
                x: mu0,
                label: "μ0 (Hopf)".into(),
                dash: Dash::Dashed,
            },
        ],
        ..Panel::default()
    };
    let b = Panel {
        title: "(b) Frequencies".into(),
        x_label: "Friction coefficient μ".into(),
        y_label: "Frequency [Hz]".into(),
        series: vec![
            Series::line("mode 1", mode(&|m| freq(m, 1.0))),
            Series::line("mode 2", mode(&|m| freq(m, -1.0))).with_dash(Dash::Dashed),
            Series::line("mode 3", mode(&|m| 5200.0 + 900.0 * m)).with_dash(Dash::DashDot),
        ],
        annotations: vec![Annotation::VLine {
            x: mu0,
            label: "μ0".into(),
            dash: Dash::Dashed,
        }],
        legend: LegendPosition::None,
        ..Panel::default()
    };
    Figure {
        title: "Stability analysis: modes against friction".into(),
        panels: vec![a, b],
        ..Figure::default()
    }
}

/// Figure 4: limit cycles, time integration against CHBM with 1, 2, 3, 10 harmonics.
fn limit_cycles() -> Figure {
    let cycle = |harmonics: usize, wobble: f64| -> Vec<(f64, f64)> {
        (0..=400)
            .map(|i| {
                let t = 2.0 * PI * i as f64 / 400.0;
                let mut x = 2.0e-6 * t.cos();
                let mut v = -2.0e-6 * 2.0 * PI * 3000.0 * t.sin();
                for k in 2..=harmonics {
                    let a = wobble * 0.6e-6 / (k * k) as f64;
                    x += a * (k as f64 * t).cos();
                    v -= a * 2.0 * PI * 3000.0 * k as f64 * (k as f64 * t).sin();
                }
                (x, v)
            })
            .collect()
    };
    let mut series = vec![Series::line("time integration", cycle(12, 1.0)).with_color(Rgb::BLACK)];
    series[0].line_width = 2.6;
    for (h, dash) in [
        (1, Dash::Dotted),
        (2, Dash::DashDot),
        (3, Dash::Dashed),
        (10, Dash::Solid),
    ] {
        series.push(
            Series::line(
                format!("CHBM, {h} harmonic{}", if h > 1 { "s" } else { "" }),
                cycle(h, 1.0),
            )
            .with_dash(dash),
        );
    }
    let panel = Panel {
        title: "Limit cycle at the pad centre node, μ = 0.3".into(),
        x_label: "Tangential displacement [m]".into(),
        y_label: "Tangential velocity [m/s]".into(),
        series,
        legend: LegendPosition::Outside,
        ..Panel::default()
    };
    Figure {
        panel_size: (780, 480),
        ..Figure::single("", panel)
    }
}

/// Figure 5: power ratio per harmonic, for two friction levels.
fn power_ratios() -> Figure {
    let ratio = |mu: f64| {
        (1..=10)
            .map(|k| (k as f64, (-(k as f64) * (1.5 - mu)).exp() * 0.9))
            .collect::<Vec<_>>()
    };
    let lin = Panel {
        title: "(a) Linear scale".into(),
        x_label: "Harmonic".into(),
        y_label: "Power ratio".into(),
        series: vec![
            Series::bars("μ = 0.25", ratio(0.25)),
            Series::bars("μ = 0.40", ratio(0.4)),
        ],
        x_ticks: (1..=10).map(|k| (k as f64, k.to_string())).collect(),
        ..Panel::default()
    };
    let log = Panel {
        title: "(b) Log scale".into(),
        y_scale: Scale::Log,
        legend: LegendPosition::None,
        ..lin.clone()
    };
    Figure {
        title: "Power ratio per harmonic".into(),
        panels: vec![lin, log],
        ..Figure::default()
    }
}

/// Figures 6-7: convergence histories on a log axis (one run diverges and produces NaN).
fn convergence() -> Figure {
    let history = |rate: f64, n: usize| {
        (0..n)
            .map(|i| (i as f64, 1.0 * rate.powi(i as i32)))
            .collect::<Vec<_>>()
    };
    let mut diverged = history(0.8, 12);
    diverged
        .extend((12..16).map(|i| (i as f64, if i < 14 { 10f64.powi(i - 12) } else { f64::NAN })));
    let panel = Panel {
        title: "Newton iterations of the CHBM".into(),
        x_label: "Iteration".into(),
        y_label: "Residual norm".into(),
        y_scale: Scale::Log,
        series: vec![
            Series::line_markers("μ = 0.25", history(0.05, 8)),
            Series::line_markers("μ = 0.30", history(0.1, 11)),
            Series::line_markers("μ = 0.40 (diverged)", diverged),
        ],
        annotations: vec![Annotation::HLine {
            y: 1e-8,
            label: "tolerance 10⁻⁸".into(),
            dash: Dash::Dashed,
        }],
        ..Panel::default()
    };
    Figure::single("", panel)
}

/// Speed against accuracy, log-log, with labelled points.
fn speed_accuracy() -> Figure {
    let methods = [
        ("HBM 1", 0.05, 8e-2),
        ("HBM 2", 0.09, 2e-2),
        ("HBM 3", 0.15, 6e-3),
        ("HBM 5", 0.3, 9e-4),
        ("HBM 10", 0.9, 4e-5),
        ("Newmark dt=1e-6", 40.0, 3e-3),
        ("Newmark dt=1e-7", 380.0, 3e-5),
    ];
    let hbm: Vec<(f64, f64)> = methods.iter().take(5).map(|m| (m.1, m.2)).collect();
    let ode: Vec<(f64, f64)> = methods.iter().skip(5).map(|m| (m.1, m.2)).collect();
    let panel = Panel {
        title: "Cost against accuracy".into(),
        x_label: "Wall time [s]".into(),
        y_label: "Relative amplitude error".into(),
        x_scale: Scale::Log,
        y_scale: Scale::Log,
        series: vec![
            Series::line_markers("CHBM", hbm),
            Series::markers("time integration", ode),
        ],
        annotations: methods
            .iter()
            .map(|m| Annotation::Label {
                at: (m.1, m.2),
                text: m.0.into(),
            })
            .collect(),
        ..Panel::default()
    };
    Figure::single("", panel)
}

/// A robustness map: outcome over friction and damping, with the Hopf boundary overlaid.
fn robustness() -> Figure {
    let mus: Vec<f64> = (0..12).map(|i| 0.1 + 0.04 * i as f64).collect();
    let etas: Vec<f64> = (0..9).map(|j| 10f64.powf(-4.0 + 0.25 * j as f64)).collect();
    let boundary = |eta: f64| 0.2 + 0.08 * (eta.log10() + 4.0);
    let mut cells = Vec::new();
    for &eta in &etas {
        for &mu in &mus {
            let b = boundary(eta);
            let c = if mu < b {
                Some(0)
            } else if mu < b + 0.15 {
                Some(1)
            } else if mu < b + 0.22 {
                Some(2)
            } else if (mu * 100.0) as i32 % 3 == 0 {
                None
            } else {
                Some(3)
            };
            cells.push(c);
        }
    }
    let cat = |n: &str| Category {
        name: n.into(),
        color: None,
    };
    let grid = CategoryGrid {
        x: mus,
        y: etas.clone(),
        cells,
        categories: vec![
            cat("stable"),
            cat("limit cycle (converged)"),
            cat("not converged"),
            cat("diverged"),
        ],
    };
    let panel = Panel {
        title: "Robustness of the CHBM".into(),
        x_label: "Friction coefficient μ".into(),
        y_label: "Modal damping η".into(),
        y_scale: Scale::Log,
        grid: Some(grid),
        series: vec![
            Series::line(
                "Hopf boundary",
                etas.iter().map(|&e| (boundary(e), e)).collect(),
            )
            .with_color(Rgb::BLACK)
            .with_dash(Dash::Dashed),
        ],
        ..Panel::default()
    };
    Figure {
        panel_size: (760, 460),
        ..Figure::single("", panel)
    }
}

/// Figures 9-11: a parameter study, amplitude against friction for several damping levels.
fn parameter_study() -> Figure {
    let panels = [
        ("(a) Disc", 1.0),
        ("(b) Pad", 0.6),
        ("(c) Caliper", 0.25),
        ("(d) Anchor", 0.1),
    ]
    .iter()
    .map(|&(title, scale)| Panel {
        title: title.into(),
        x_label: "μ".into(),
        y_label: "Amplitude [µm]".into(),
        series: [0.01, 0.02, 0.04]
            .iter()
            .map(|&eta| {
                let pts = (0..=15)
                    .map(|i| {
                        let mu = 0.2 + 0.02 * i as f64;
                        (mu, scale * 30.0 * ((mu - 0.2 - 10.0 * eta).max(0.0)).sqrt())
                    })
                    .collect();
                Series::line_markers(format!("η = {eta}"), pts)
            })
            .collect(),
        ..Panel::default()
    })
    .collect();
    Figure {
        title: "Parameter study: limit-cycle amplitude".into(),
        panels,
        layout: Layout::Grid { columns: 2 },
        ..Figure::default()
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "/tmp/squeal-gallery".into()),
    );
    let figures = [
        (
            "fig2-stability",
            stability(),
            "Real parts and frequencies of the modes against friction",
        ),
        (
            "fig4-limit-cycles",
            limit_cycles(),
            "Limit cycles: time integration against CHBM",
        ),
        (
            "fig5-power-ratios",
            power_ratios(),
            "Power ratio per harmonic",
        ),
        (
            "fig6-convergence",
            convergence(),
            "Convergence of the Newton iterations",
        ),
        ("speed-accuracy", speed_accuracy(), "Cost against accuracy"),
        (
            "robustness",
            robustness(),
            "Outcome of the CHBM over friction and damping",
        ),
        ("fig9-parameter-study", parameter_study(), "Parameter study"),
    ];
    let mut section = Section {
        heading: "Figures".into(),
        ..Section::default()
    };
    for (stem, fig, caption) in &figures {
        for note in write_svg_and_png(fig, &dir.join(stem))? {
            println!("note: {note}");
        }
        section
            .figures
            .push((PathBuf::from(stem), caption.to_string()));
    }
    let mut table = Table::new(["mode", "frequency", "real part [1/s]", "damping ratio"]);
    for (i, (f, re)) in [(2905.0, 12.5), (3110.0, -31.25), (5380.0, -47.0)]
        .iter()
        .enumerate()
    {
        table.push_row([
            (i + 1).to_string(),
            fmt_si(*f, 4, "Hz"),
            fmt_sig(*re, 3),
            fmt_sig(-re / (2.0 * PI * f), 2),
        ]);
    }
    let table = table.align_numbers_right();
    println!("{}", table.to_text());
    section.tables.push((table, "Modes at μ = 0.3".into()));
    let report = Report {
        title: "squeal report gallery".into(),
        intro: "One sample of each kind of figure.".into(),
        sections: vec![section],
    };
    for note in report.write(Path::new(&dir))? {
        println!("note: {note}");
    }
    println!("wrote {}", dir.display());
    Ok(())
}
