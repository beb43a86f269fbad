//! Rendering cost: a two-panel stability figure, a long time history, a 40 x 40 robustness map.
//!
//! `cargo bench -p squeal-report --bench render`

use criterion::{Criterion, criterion_group, criterion_main};
use squeal_report::{
    Category, CategoryGrid, Dash, Figure, Panel, Scale, Series, render_png, render_svg,
};
use std::hint::black_box;

fn stability() -> Figure {
    let mode = |k: f64| {
        (0..=60)
            .map(|i| (i as f64 / 120.0, k * (i as f64 / 10.0).sin()))
            .collect()
    };
    let panel = |title: &str| Panel {
        title: title.into(),
        x_label: "μ".into(),
        y_label: "Real part [1/s]".into(),
        series: vec![
            Series::line("mode 1", mode(1.0)),
            Series::line("mode 2", mode(-1.0)).with_dash(Dash::Dashed),
            Series::line("mode 3", mode(0.5)).with_dash(Dash::DashDot),
        ],
        ..Panel::default()
    };
    Figure {
        title: "stability".into(),
        panels: vec![panel("(a)"), panel("(b)")],
        ..Figure::default()
    }
}

fn time_history(n: usize) -> Figure {
    let pts = (0..n).map(|i| {
        let t = i as f64 * 1e-5;
        (
            t,
            (2.0 * std::f64::consts::PI * 3000.0 * t).sin() * (1.0 - (-t * 50.0).exp()),
        )
    });
    let panel = Panel {
        x_label: "t [s]".into(),
        y_label: "u [m]".into(),
        series: vec![Series::line("Newmark", pts.collect())],
        ..Panel::default()
    };
    Figure::single("", panel)
}

fn robustness(n: usize) -> Figure {
    let axis: Vec<f64> = (0..n)
        .map(|i| 10f64.powf(-3.0 + 2.0 * i as f64 / n as f64))
        .collect();
    let cells = (0..n * n)
        .map(|k| {
            if k % 17 == 0 {
                None
            } else {
                Some((k / n + k % n) % 3)
            }
        })
        .collect();
    let cat = |n: &str| Category {
        name: n.into(),
        color: None,
    };
    let grid = CategoryGrid {
        x: axis.clone(),
        y: axis,
        cells,
        categories: vec![cat("stable"), cat("limit cycle"), cat("diverged")],
    };
    let panel = Panel {
        x_scale: Scale::Log,
        y_scale: Scale::Log,
        grid: Some(grid),
        ..Panel::default()
    };
    Figure::single("", panel)
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("render");
    g.sample_size(10);
    for (name, fig) in [
        ("stability_2x3x61", stability()),
        ("time_history_100k", time_history(100_000)),
        ("robustness_40x40", robustness(40)),
    ] {
        g.bench_function(format!("{name}/svg"), |b| {
            b.iter(|| render_svg(black_box(&fig)).unwrap())
        });
        g.bench_function(format!("{name}/png"), |b| {
            b.iter(|| render_png(black_box(&fig)).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
