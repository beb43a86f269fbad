//! A panel's data made ready to draw: series in axis coordinates, category grids, bar slots,
//! axis ranges (with the notes on what was left out).

use super::*;

/// A series ready to draw: colour and marker fixed, points in plotting space (`None` breaks
/// the line).
pub(super) struct Prepared<'a> {
    pub(super) src: &'a Series,
    pub(super) color: Rgb,
    pub(super) marker: Marker,
    pub(super) pts: Vec<Option<(f64, f64)>>,
}

/// A category grid ready to draw: cell edges in plotting space.
pub(super) struct PreparedGrid<'a> {
    pub(super) src: &'a CategoryGrid,
    pub(super) xe: Vec<f64>,
    pub(super) ye: Vec<f64>,
    pub(super) colors: Vec<Rgb>,
    pub(super) any_missing: bool,
}

/// The panel's data in plotting space, with notes on what was left out.
pub(super) struct PanelData<'a> {
    pub(super) series: Vec<Prepared<'a>>,
    pub(super) grid: Option<PreparedGrid<'a>>,
    pub(super) notes: Vec<String>,
    pub(super) footnotes: Vec<String>,
    /// Width of one bar group (plotting space) and the number of bar series.
    pub(super) bar_slot: f64,
    pub(super) bar_count: usize,
    /// Axis ranges in plotting space.
    pub(super) xr: (f64, f64),
    pub(super) yr: (f64, f64),
}

pub(super) fn prepare_series<'a>(panel: &'a Panel, name: &str, out: &mut PanelData<'a>) {
    let (mut auto_color, mut auto_marker) = (0usize, 0usize);
    for s in &panel.series {
        let color = s.color.unwrap_or_else(|| {
            auto_color += 1;
            palette_color(auto_color - 1)
        });
        let draws_markers = matches!(s.kind, SeriesKind::Markers | SeriesKind::LineMarkers);
        let marker = match s.marker {
            Some(m) => m,
            None if draws_markers => {
                auto_marker += 1;
                MARKERS[(auto_marker - 1) % MARKERS.len()]
            }
            None => Marker::Circle,
        };
        let (mut nonfinite, mut off_log) = (0usize, 0usize);
        let pts: Vec<Option<(f64, f64)>> = s
            .points
            .iter()
            .map(|&(x, y)| {
                if !x.is_finite() || !y.is_finite() {
                    nonfinite += 1;
                    return None;
                }
                let p = to_axis(panel.x_scale, x).zip(to_axis(panel.y_scale, y));
                if p.is_none() {
                    off_log += 1;
                }
                p
            })
            .collect();
        let label = if s.name.is_empty() {
            "(unnamed)"
        } else {
            s.name.as_str()
        };
        if nonfinite > 0 {
            out.notes.push(format!(
                "{name}: series '{label}': {nonfinite} of {} points are NaN or infinite and were skipped",
                s.points.len()
            ));
            out.footnotes
                .push(format!("'{label}': {nonfinite} NaN/inf points skipped"));
        }
        if off_log > 0 {
            out.notes.push(format!(
                "{name}: series '{label}': {off_log} of {} points are <= 0 on a log axis and were skipped",
                s.points.len()
            ));
            out.footnotes.push(format!(
                "'{label}': {off_log} points ≤ 0 not shown (log axis)"
            ));
        }
        if pts.iter().all(Option::is_none) {
            if !s.points.is_empty() {
                out.notes.push(format!(
                    "{name}: series '{label}' has no point that can be drawn and was dropped"
                ));
                out.footnotes
                    .push(format!("'{label}' dropped: no drawable point"));
            }
            continue;
        }
        out.series.push(Prepared {
            src: s,
            color,
            marker,
            pts,
        });
    }
}

/// Cell edges from strictly increasing centres in plotting space (halfway between centres;
/// the outer cells as wide as their neighbours; a lone centre gets a unit-wide cell).
pub(super) fn cell_edges(c: &[f64]) -> Vec<f64> {
    match c {
        [] => Vec::new(),
        [a] => vec![a - 0.5, a + 0.5],
        _ => {
            let n = c.len();
            let mut e = Vec::with_capacity(n + 1);
            e.push(c[0] - (c[1] - c[0]) / 2.0);
            e.extend(c.windows(2).map(|w| (w[0] + w[1]) / 2.0));
            e.push(c[n - 1] + (c[n - 1] - c[n - 2]) / 2.0);
            e
        }
    }
}

pub(super) fn prepare_grid<'a>(
    panel: &'a Panel,
    name: &str,
) -> Result<Option<PreparedGrid<'a>>, ReportError> {
    let Some(g) = &panel.grid else {
        return Ok(None);
    };
    let bad = |m: String| {
        Err(ReportError::InvalidFigure(format!(
            "{name}: category grid: {m}"
        )))
    };
    let axis = |v: &[f64], scale: Scale, which: &str| -> Result<Vec<f64>, ReportError> {
        let t: Option<Vec<f64>> = v.iter().map(|&x| to_axis(scale, x)).collect();
        match t {
            Some(t) if t.windows(2).all(|w| w[1] > w[0]) => Ok(t),
            _ => Err(ReportError::InvalidFigure(format!(
                "{name}: category grid: {which} values must be finite, strictly increasing (and > 0 on a log axis)"
            ))),
        }
    };
    let xt = axis(&g.x, panel.x_scale, "x")?;
    let yt = axis(&g.y, panel.y_scale, "y")?;
    let expected = g.x.len().checked_mul(g.y.len());
    if expected != Some(g.cells.len()) {
        return bad(format!(
            "{} cells given for {} x {} centres",
            g.cells.len(),
            g.x.len(),
            g.y.len()
        ));
    }
    if let Some(k) = g.cells.iter().flatten().find(|&&k| k >= g.categories.len()) {
        return bad(format!(
            "category {k} used but only {} categories given",
            g.categories.len()
        ));
    }
    let colors = g
        .categories
        .iter()
        .enumerate()
        .map(|(i, c)| c.color.unwrap_or(palette_color(i)))
        .collect();
    Ok(Some(PreparedGrid {
        src: g,
        xe: cell_edges(&xt),
        ye: cell_edges(&yt),
        colors,
        any_missing: g.cells.iter().any(Option::is_none),
    }))
}

/// Width of one bar group: the smallest gap between distinct bar x positions (1 if only one).
pub(super) fn bar_slot(series: &[Prepared]) -> (f64, usize) {
    let mut xs: Vec<f64> = series
        .iter()
        .filter(|p| p.src.kind == SeriesKind::Bars)
        .flat_map(|p| p.pts.iter().flatten().map(|q| q.0))
        .collect();
    let count = series
        .iter()
        .filter(|p| p.src.kind == SeriesKind::Bars)
        .count();
    xs.sort_by(f64::total_cmp);
    let gap = xs
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|&d| d > 0.0)
        .fold(f64::INFINITY, f64::min);
    (if gap.is_finite() { gap } else { 1.0 }, count)
}

/// What decides one axis' range.
pub(super) struct AxisData {
    /// The panel's fixed range, if any.
    pub(super) user: Option<(f64, f64)>,
    pub(super) scale: Scale,
    /// Data coordinates (plotting space), padded by 4 %.
    pub(super) data: Vec<f64>,
    /// Coordinates shown exactly (category grid edges).
    pub(super) fixed: Vec<f64>,
    /// Bars: a range starting at zero stays there.
    pub(super) keep_zero: bool,
}

/// The axis range in plotting space: the user's range if usable, else the data's extent with
/// 4 % padding (bars keep their zero baseline, grids their edges).
pub(super) fn axis_range(a: &AxisData, what: &str, notes: &mut Vec<String>) -> (f64, f64) {
    let (scale, keep_zero) = (a.scale, a.keep_zero);
    if let Some((lo, hi)) = a.user {
        match (to_axis(scale, lo), to_axis(scale, hi)) {
            (Some(lo), Some(hi)) if hi > lo => return (lo, hi),
            _ => notes.push(format!(
                "{what} range ({lo}, {hi}) is not usable on this axis and was ignored"
            )),
        }
    }
    let extent = |v: &[f64]| -> Option<(f64, f64)> {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (lo <= hi).then_some((lo, hi))
    };
    let padded = extent(&a.data).map(|(lo, hi)| {
        let (lo, hi) = widen(lo, hi, scale);
        let pad = 0.04 * (hi - lo);
        let lo2 = if keep_zero && scale == Scale::Linear && lo >= 0.0 {
            (lo - pad).max(0.0)
        } else {
            lo - pad
        };
        (lo2, hi + pad)
    });
    let all: Vec<f64> = padded
        .iter()
        .flat_map(|&(a, b)| [a, b])
        .chain(a.fixed.iter().copied())
        .collect();
    match extent(&all).map(|(lo, hi)| widen(lo, hi, scale)) {
        Some((lo, hi)) if (hi - lo).is_finite() => (lo, hi),
        Some(_) => {
            notes.push(format!(
                "{what} values span more than f64 can subtract; axis shown as 0..1"
            ));
            (0.0, 1.0)
        }
        None => (0.0, 1.0),
    }
}

/// Opens up an empty or numerically flat range so that ticks and pixels are well defined.
pub(super) fn widen(lo: f64, hi: f64, scale: Scale) -> (f64, f64) {
    let m = lo.abs().max(hi.abs());
    if hi - lo > 1e-9 * m && hi > lo {
        return (lo, hi);
    }
    let d = match scale {
        Scale::Log => 0.5,
        Scale::Linear if m == 0.0 => 1.0,
        Scale::Linear => 0.1 * m,
    };
    let c = 0.5 * (lo + hi);
    (c - d, c + d)
}

pub(super) fn prepare_panel<'a>(
    panel: &'a Panel,
    name: &str,
) -> Result<PanelData<'a>, ReportError> {
    let mut d = PanelData {
        series: Vec::new(),
        grid: prepare_grid(panel, name)?,
        notes: Vec::new(),
        footnotes: Vec::new(),
        bar_slot: 1.0,
        bar_count: 0,
        xr: (0.0, 1.0),
        yr: (0.0, 1.0),
    };
    prepare_series(panel, name, &mut d);
    (d.bar_slot, d.bar_count) = bar_slot(&d.series);
    let (mut xs, mut ys) = (Vec::new(), Vec::new());
    for p in &d.series {
        for &(x, y) in p.pts.iter().flatten() {
            if p.src.kind == SeriesKind::Bars {
                xs.extend([x - d.bar_slot / 2.0, x + d.bar_slot / 2.0]);
            } else {
                xs.push(x);
            }
            ys.push(y);
        }
    }
    let keep_zero = d.bar_count > 0;
    if keep_zero && panel.y_scale == Scale::Linear {
        ys.push(0.0);
    }
    for a in &panel.annotations {
        let (x, y, text) = match a {
            Annotation::VLine { x, label, .. } => (Some(*x), None, label),
            Annotation::HLine { y, label, .. } => (None, Some(*y), label),
            Annotation::Label { at, text } => (Some(at.0), Some(at.1), text),
        };
        let tx = x.map(|v| to_axis(panel.x_scale, v));
        let ty = y.map(|v| to_axis(panel.y_scale, v));
        if tx == Some(None) || ty == Some(None) {
            d.notes.push(format!(
                "{name}: annotation '{text}' is at a NaN, infinite or (log axis) non-positive coordinate and was left out"
            ));
            continue;
        }
        xs.extend(tx.flatten());
        ys.extend(ty.flatten());
    }
    let edges = |e: &[f64]| {
        e.first()
            .into_iter()
            .chain(e.last())
            .copied()
            .collect::<Vec<f64>>()
    };
    let (gx, gy) = match &d.grid {
        Some(g) => (edges(&g.xe), edges(&g.ye)),
        None => (Vec::new(), Vec::new()),
    };
    let x = AxisData {
        user: panel.x_range,
        scale: panel.x_scale,
        data: xs,
        fixed: gx,
        keep_zero: false,
    };
    let y = AxisData {
        user: panel.y_range,
        scale: panel.y_scale,
        data: ys,
        fixed: gy,
        keep_zero,
    };
    let mut notes = std::mem::take(&mut d.notes);
    d.xr = axis_range(&x, &format!("{name}: x"), &mut notes);
    d.yr = axis_range(&y, &format!("{name}: y"), &mut notes);
    d.notes = notes;
    Ok(d)
}
