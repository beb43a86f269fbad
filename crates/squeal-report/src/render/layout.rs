//! Where things go in a panel: the plot frame, ticks and axis titles, the legend's size and
//! place.

use super::*;

/// Maps plotting space to pixels inside the plot rectangle.
pub(super) struct Frame {
    pub(super) r: Rect,
    pub(super) xr: (f64, f64),
    pub(super) yr: (f64, f64),
}

impl Frame {
    pub(super) fn px(&self, x: f64) -> f64 {
        self.r.x0 + (x - self.xr.0) / (self.xr.1 - self.xr.0) * self.r.width()
    }

    pub(super) fn py(&self, y: f64) -> f64 {
        self.r.y1 - (y - self.yr.0) / (self.yr.1 - self.yr.0) * self.r.height()
    }

    pub(super) fn map(&self, p: (f64, f64)) -> Px {
        (self.px(p.0), self.py(p.1))
    }
}

/// Ticks for one axis: the panel's own labels if given, else automatic ones.
pub(super) fn axis_ticks(
    manual: &[(f64, String)],
    scale: Scale,
    range: (f64, f64),
    max_count: usize,
) -> AxisTicks {
    if !manual.is_empty() {
        let major = manual
            .iter()
            .filter_map(|(v, l)| {
                to_axis(scale, *v).map(|pos| Tick {
                    pos,
                    label: l.clone(),
                })
            })
            .filter(|t| {
                t.pos >= range.0 - 1e-9 * (range.1 - range.0)
                    && t.pos <= range.1 + 1e-9 * (range.1 - range.0)
            })
            .collect();
        return AxisTicks {
            major,
            minor: Vec::new(),
            multiplier: None,
        };
    }
    match scale {
        Scale::Linear => linear_ticks(range.0, range.1, max_count),
        Scale::Log => log_ticks(range.0, range.1, max_count),
    }
}

/// Axis label with the shared tick multiplier appended.
/// Axis label and the shared tick multiplier to append, kept apart so that shortening a long
/// label never cuts the multiplier.
pub(super) fn axis_title(label: &str, ticks: &AxisTicks) -> (String, String) {
    match (&ticks.multiplier, label.is_empty()) {
        (Some(m), true) => (String::new(), m.clone()),
        (Some(m), false) => (label.to_string(), format!("  ({m})")),
        (None, _) => (label.to_string(), String::new()),
    }
}

/// One legend line.
pub(super) enum Sample {
    Line {
        color: Rgb,
        dash: Dash,
        width: f64,
        marker: Option<Marker>,
    },
    Block(Rgb),
}

pub(super) struct Legend {
    pub(super) entries: Vec<(String, Sample)>,
    pub(super) w: f64,
    pub(super) h: f64,
    pub(super) row: f64,
}

pub(super) fn build_legend(d: &PanelData, z: &Sizes, s: f64) -> Option<Legend> {
    let mut entries = Vec::new();
    for p in d.series.iter().filter(|p| !p.src.name.is_empty()) {
        let sample = match p.src.kind {
            SeriesKind::Bars => Sample::Block(p.color),
            SeriesKind::Line => Sample::Line {
                color: p.color,
                dash: p.src.dash,
                width: p.src.line_width,
                marker: None,
            },
            SeriesKind::Markers => Sample::Line {
                color: p.color,
                dash: p.src.dash,
                width: 0.0,
                marker: Some(p.marker),
            },
            SeriesKind::LineMarkers => Sample::Line {
                color: p.color,
                dash: p.src.dash,
                width: p.src.line_width,
                marker: Some(p.marker),
            },
        };
        entries.push((p.src.name.clone(), sample));
    }
    if let Some(g) = &d.grid {
        for (c, &col) in g.src.categories.iter().zip(&g.colors) {
            entries.push((c.name.clone(), Sample::Block(col)));
        }
        if g.any_missing {
            entries.push(("not computed".into(), Sample::Block(MISSING_CELL)));
        }
    }
    if entries.is_empty() {
        return None;
    }
    let text_w = entries
        .iter()
        .map(|(n, _)| text_size(n, z.legend).0)
        .fold(0.0, f64::max);
    let row = z.legend * 1.45;
    Some(Legend {
        w: 2.0 * z.pad + 30.0 * s + 6.0 * s + text_w,
        h: 2.0 * z.pad + row * entries.len() as f64,
        row,
        entries,
    })
}

/// The label boxes of a panel's texts, so that later ones avoid earlier ones.
pub(super) type Obstacles = Vec<Rect>;

/// Where a panel's plot rectangle goes and what its axes show.
pub(super) struct PanelLayout {
    pub(super) f: Frame,
    pub(super) x_ticks: AxisTicks,
    pub(super) y_ticks: AxisTicks,
    pub(super) x_title: (String, String),
    pub(super) y_title: (String, String),
    pub(super) tick_h: f64,
    pub(super) xlabel_h: f64,
    pub(super) ylabel_w: f64,
    pub(super) foot_h: f64,
}

/// Lays out a panel in `cell`, leaving `legend_right` pixels free right of the plot.
pub(super) fn layout_panel(
    panel: &Panel,
    d: &PanelData,
    cell: Rect,
    legend_right: f64,
    n_footnotes: usize,
    z: &Sizes,
    name: &str,
) -> Result<PanelLayout, ReportError> {
    let s = z.scale;
    let (xr, yr) = (d.xr, d.yr);
    // Vertical layout first: the y ticks depend only on the plot height.
    let title_h = if panel.title.is_empty() {
        z.pad
    } else {
        z.title * 1.6
    };
    let top = cell.y0 + z.pad + title_h;
    let tick_h = z.tick * 1.25;
    let xlabel_h = if panel.x_label.is_empty() {
        0.0
    } else {
        z.axis * 1.5
    };
    let foot_h = n_footnotes as f64 * z.note * 1.3;
    let bottom = cell.y1 - z.pad - foot_h - xlabel_h - tick_h - z.tick_len - 3.0 * s;
    let plot_h = bottom - top;
    let y_ticks = axis_ticks(
        &panel.y_ticks,
        panel.y_scale,
        yr,
        ((plot_h / (z.tick * 2.6)) as usize).clamp(2, 10),
    );
    let y_title = axis_title(&panel.y_label, &y_ticks);
    let y_tick_w = y_ticks
        .major
        .iter()
        .map(|t| text_size(&t.label, z.tick).0)
        .fold(0.0, f64::max);
    let ylabel_w = if y_title.0.is_empty() && y_title.1.is_empty() {
        0.0
    } else {
        z.axis * 1.5
    };
    let left = cell.x0 + z.pad + ylabel_w + y_tick_w + z.tick_len + 5.0 * s;
    let right = cell.x1 - z.pad - legend_right - 8.0 * s;
    let plot_w = right - left;
    if plot_w < 40.0 * s || plot_h < 40.0 * s {
        return Err(ReportError::InvalidFigure(format!(
            "{name}: no room left for the plot (panel too small for its labels and legend)"
        )));
    }
    let x_ticks = fit_x_ticks(panel, xr, plot_w, z);
    let x_title = axis_title(&panel.x_label, &x_ticks);
    let f = Frame {
        r: Rect {
            x0: left,
            y0: top,
            x1: right,
            y1: bottom,
        },
        xr,
        yr,
    };

    Ok(PanelLayout {
        f,
        x_ticks,
        y_ticks,
        x_title,
        y_title,
        tick_h,
        xlabel_h,
        ylabel_w,
        foot_h,
    })
}
