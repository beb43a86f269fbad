//! Draws a [`Figure`] on any plotters backend (SVG string or RGB buffer).
//!
//! plotters is used as a drawing surface only (paths, rectangles, text); the axes, ticks,
//! legend and clipping are laid out here in pixels, so the same code serves linear and log axes,
//! category grids and bar groups, and the output is the same bits on every run.

use crate::ReportError;
use crate::font::{FAMILY, text_size};
use crate::geom::{Px, Rect, clip_polyline, dash_polyline, m4_decimate};
use crate::model::{
    Annotation, CategoryGrid, Dash, Figure, Layout, LegendPosition, MARKERS, Marker, Panel, Rgb,
    Scale, Series, SeriesKind, palette_color,
};
use crate::ticks::{AxisTicks, Tick, linear_ticks, log_ticks};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Panel sizes accepted, in SVG pixels (smaller leaves no room for a plot; larger is a mistake).
const MIN_PANEL: (u32, u32) = (160, 120);
const MAX_PANEL: u32 = 8000;
/// Largest image accepted, in pixels (an RGB buffer of 3 bytes per pixel: 192 MB).
const MAX_PIXELS: u64 = 64_000_000;
/// Longest series drawn with markers on every point in a line-and-markers series.
const MAX_LINE_MARKERS: usize = 40;
/// Most footnotes printed under one panel (all of them are returned as notes).
const MAX_FOOTNOTES: usize = 3;

const FRAME: Rgb = Rgb(60, 60, 60);
const GRID_MAJOR: Rgb = Rgb(222, 222, 222);
const GRID_MINOR: Rgb = Rgb(240, 240, 240);
const TEXT: Rgb = Rgb(20, 20, 20);
const NOTE: Rgb = Rgb(120, 120, 120);
const REFERENCE: Rgb = Rgb(80, 80, 80);
const MISSING_CELL: Rgb = Rgb(235, 235, 235);

/// Font sizes and lengths at scale 1 (SVG pixels).
struct Sizes {
    /// Pixels per SVG pixel.
    scale: f64,
    fig_title: f64,
    title: f64,
    axis: f64,
    tick: f64,
    legend: f64,
    note: f64,
    annot: f64,
    pad: f64,
    tick_len: f64,
    marker: f64,
}

impl Sizes {
    fn scaled(s: f64) -> Sizes {
        Sizes {
            scale: s,
            fig_title: 19.0 * s,
            title: 17.0 * s,
            axis: 15.5 * s,
            tick: 14.0 * s,
            legend: 14.0 * s,
            note: 12.5 * s,
            annot: 14.0 * s,
            pad: 8.0 * s,
            tick_len: 5.0 * s,
            marker: 4.0 * s,
        }
    }
}

/// The image size in pixels of `fig` at `scale`, after checking the figure's dimensions.
pub(crate) fn figure_pixels(fig: &Figure, scale: f64) -> Result<(u32, u32), ReportError> {
    let bad = |m: String| Err(ReportError::InvalidFigure(m));
    if fig.panels.is_empty() {
        return bad("a figure needs at least one panel".into());
    }
    let (w, h) = fig.panel_size;
    if w < MIN_PANEL.0 || h < MIN_PANEL.1 || w > MAX_PANEL || h > MAX_PANEL {
        return bad(format!(
            "panel size {w} x {h} px is outside {} x {} .. {MAX_PANEL} x {MAX_PANEL}",
            MIN_PANEL.0, MIN_PANEL.1
        ));
    }
    if !(0.25..=16.0).contains(&scale) {
        return bad(format!("scale {scale} is outside 0.25 .. 16"));
    }
    let (cols, rows) = grid_shape(fig);
    let title_h = if fig.title.is_empty() {
        0.0
    } else {
        title_band(1.0)
    };
    let width = (f64::from(w) * cols as f64 * scale).round();
    let height = ((f64::from(h) * rows as f64 + title_h) * scale).round();
    if width * height > MAX_PIXELS as f64 {
        return bad(format!(
            "{width} x {height} px is more than {MAX_PIXELS} pixels"
        ));
    }
    Ok((width as u32, height as u32))
}

/// Height of the figure title band at scale `s`.
fn title_band(s: f64) -> f64 {
    Sizes::scaled(s).fig_title * 1.8
}

/// Columns and rows of the panel arrangement.
fn grid_shape(fig: &Figure) -> (usize, usize) {
    let n = fig.panels.len().max(1);
    let cols = match fig.layout {
        Layout::Row => n,
        Layout::Column => 1,
        Layout::Grid { columns } => columns.clamp(1, n),
    };
    (cols, n.div_ceil(cols))
}

/// Draws the whole figure on `area` (already sized by [`figure_pixels`]); returns the notes
/// about skipped data.
///
/// `raster` draws thick lines as polygons placed to sub-pixel accuracy (plotters' own thick
/// paths round their offsets to whole pixels, which thins diagonal lines by up to 30 %).
pub(crate) fn draw_figure<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    fig: &Figure,
    s: f64,
    raster: bool,
) -> Result<Vec<String>, ReportError> {
    let p = Painter {
        area,
        s,
        z: Sizes::scaled(s),
        raster,
    };
    area.fill(&WHITE).map_err(draw_err)?;
    let top = if fig.title.is_empty() {
        0.0
    } else {
        title_band(s)
    };
    let (cols, _) = grid_shape(fig);
    let (pw, ph) = (
        f64::from(fig.panel_size.0) * s,
        f64::from(fig.panel_size.1) * s,
    );
    if !fig.title.is_empty() {
        let (w, _) = area.dim_in_pixel();
        p.text_fit(
            (&fig.title, ""),
            (f64::from(w) / 2.0, top / 2.0),
            p.z.fig_title,
            f64::from(w) - 2.0 * p.z.pad,
            (HPos::Center, VPos::Center),
            false,
        )?;
    }
    let mut notes = Vec::new();
    for (i, panel) in fig.panels.iter().enumerate() {
        let origin = ((i % cols) as f64 * pw, top + (i / cols) as f64 * ph);
        let name = if panel.title.is_empty() {
            format!("panel {}", i + 1)
        } else {
            format!("panel '{}'", panel.title)
        };
        let cell = Rect {
            x0: origin.0,
            y0: origin.1,
            x1: origin.0 + pw,
            y1: origin.1 + ph,
        };
        notes.extend(draw_panel(&p, panel, cell, &name)?);
    }
    area.present().map_err(draw_err)?;
    Ok(notes)
}

fn draw_err<E: std::error::Error + Send + Sync>(
    e: plotters::drawing::DrawingAreaErrorKind<E>,
) -> ReportError {
    ReportError::Draw(e.to_string())
}

fn rgb(c: Rgb) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

fn ipt(p: Px) -> (i32, i32) {
    (p.0.round() as i32, p.1.round() as i32)
}

/// Drawing primitives in pixels on one drawing area.
struct Painter<'a, DB: DrawingBackend> {
    area: &'a DrawingArea<DB, Shift>,
    s: f64,
    z: Sizes,
    raster: bool,
}

impl<DB: DrawingBackend> Painter<'_, DB> {
    fn text(
        &self,
        text: &str,
        at: Px,
        size: f64,
        color: Rgb,
        anchor: (HPos, VPos),
    ) -> Result<(), ReportError> {
        self.text_styled(text, at, size, color, anchor, false)
    }

    /// Text anchored at `at`; `vertical` rotates it to read bottom-up (y-axis labels).
    fn text_styled(
        &self,
        text: &str,
        at: Px,
        size: f64,
        color: Rgb,
        anchor: (HPos, VPos),
        vertical: bool,
    ) -> Result<(), ReportError> {
        if text.is_empty() {
            return Ok(());
        }
        let mut font = FontDesc::new(FAMILY, size, FontStyle::Normal);
        if vertical {
            font = font.transform(FontTransform::Rotate270);
        }
        let color = rgb(color);
        let style = TextStyle::from(font)
            .color(&color)
            .pos(Pos::new(anchor.0, anchor.1));
        self.area.draw_text(text, &style, ipt(at)).map_err(draw_err)
    }

    /// Text shrunk or shortened to at most `max_w` pixels long ([`fit_text`]).
    fn text_fit(
        &self,
        text: (&str, &str),
        at: Px,
        size: f64,
        max_w: f64,
        anchor: (HPos, VPos),
        vertical: bool,
    ) -> Result<(), ReportError> {
        let (t, sz) = fit_text(text.0, text.1, size, max_w);
        self.text_styled(&t, at, sz, TEXT, anchor, vertical)
    }

    fn polyline(&self, pts: &[Px], color: Rgb, width: f64) -> Result<(), ReportError> {
        if self.raster && width > 1.5 {
            return self.thick_polyline(pts, color, width);
        }
        let mut ip: Vec<(i32, i32)> = Vec::with_capacity(pts.len());
        for &p in pts {
            let q = ipt(p);
            if ip.last() != Some(&q) {
                ip.push(q);
            }
        }
        if ip.len() < 2 {
            return Ok(());
        }
        let style = ShapeStyle::from(&rgb(color)).stroke_width(width.round().max(1.0) as u32);
        self.area
            .draw(&PathElement::new(ip, style))
            .map_err(draw_err)
    }

    /// A thick line as one quadrilateral per segment (butt ends) with round joins.
    fn thick_polyline(&self, pts: &[Px], color: Rgb, width: f64) -> Result<(), ReportError> {
        let h = width / 2.0;
        for w in pts.windows(2) {
            let (a, b) = (w[0], w[1]);
            let len = (b.0 - a.0).hypot(b.1 - a.1);
            if len.is_nan() || len <= 1e-9 {
                continue;
            }
            let n = (-(b.1 - a.1) / len * h, (b.0 - a.0) / len * h);
            let quad = [
                (a.0 + n.0, a.1 + n.1),
                (b.0 + n.0, b.1 + n.1),
                (b.0 - n.0, b.1 - n.1),
                (a.0 - n.0, a.1 - n.1),
            ];
            self.polygon(&quad, color)?;
        }
        let style = ShapeStyle::from(&rgb(color)).filled();
        for &v in pts.iter().skip(1).take(pts.len().saturating_sub(2)) {
            self.area
                .draw(&Circle::new(ipt(v), h.round() as i32, style))
                .map_err(draw_err)?;
        }
        Ok(())
    }

    fn rect(
        &self,
        r: &Rect,
        fill: Option<Rgb>,
        stroke: Option<(Rgb, f64)>,
    ) -> Result<(), ReportError> {
        let corners = [ipt((r.x0, r.y0)), ipt((r.x1, r.y1))];
        if let Some(c) = fill {
            self.area
                .draw(&Rectangle::new(corners, ShapeStyle::from(&rgb(c)).filled()))
                .map_err(draw_err)?;
        }
        if let Some((c, w)) = stroke {
            let style = ShapeStyle::from(&rgb(c)).stroke_width(w.round().max(1.0) as u32);
            self.area
                .draw(&Rectangle::new(corners, style))
                .map_err(draw_err)?;
        }
        Ok(())
    }

    fn polygon(&self, pts: &[Px], color: Rgb) -> Result<(), ReportError> {
        let ip: Vec<(i32, i32)> = pts.iter().map(|&p| ipt(p)).collect();
        self.area
            .draw(&Polygon::new(ip, ShapeStyle::from(&rgb(color)).filled()))
            .map_err(draw_err)
    }

    /// A line with a dash pattern (pattern lengths scale with the figure).
    fn dashed(&self, pts: &[Px], color: Rgb, width: f64, dash: Dash) -> Result<(), ReportError> {
        let pattern: Vec<f64> = dash_pattern(dash).iter().map(|l| l * self.s).collect();
        for piece in dash_polyline(pts, &pattern) {
            self.polyline(&piece, color, width)?;
        }
        Ok(())
    }

    fn marker(&self, at: Px, shape: Marker, color: Rgb) -> Result<(), ReportError> {
        let r = self.z.marker;
        let (x, y) = at;
        match shape {
            Marker::Circle => {
                let style = ShapeStyle::from(&rgb(color)).filled();
                self.area
                    .draw(&Circle::new(ipt(at), r.round() as i32, style))
                    .map_err(draw_err)
            }
            Marker::Square => {
                let q = r * 0.9;
                self.rect(
                    &Rect {
                        x0: x - q,
                        y0: y - q,
                        x1: x + q,
                        y1: y + q,
                    },
                    Some(color),
                    None,
                )
            }
            Marker::Triangle => self.polygon(
                &[
                    (x, y - 1.2 * r),
                    (x + 1.1 * r, y + 0.8 * r),
                    (x - 1.1 * r, y + 0.8 * r),
                ],
                color,
            ),
            Marker::Diamond => self.polygon(
                &[(x, y - 1.3 * r), (x + r, y), (x, y + 1.3 * r), (x - r, y)],
                color,
            ),
            Marker::Cross => {
                let w = 1.8 * self.s;
                self.polyline(&[(x - r, y - r), (x + r, y + r)], color, w)?;
                self.polyline(&[(x - r, y + r), (x + r, y - r)], color, w)
            }
            Marker::Plus => {
                let w = 1.8 * self.s;
                let q = 1.2 * r;
                self.polyline(&[(x - q, y), (x + q, y)], color, w)?;
                self.polyline(&[(x, y - q), (x, y + q)], color, w)
            }
        }
    }
}

/// `text` followed by `suffix` at `size`, made to fit `max_w` pixels: first shrunk down to
/// 75 % of `size`, then `text` shortened with an ellipsis (the suffix is kept whole).
fn fit_text(text: &str, suffix: &str, size: f64, max_w: f64) -> (String, f64) {
    let width = |t: &str, sz: f64| text_size(t, sz).0;
    let whole = format!("{text}{suffix}");
    let full = width(&whole, size);
    if full <= max_w {
        return (whole, size);
    }
    let smaller = (size * max_w / full).max(0.75 * size);
    if width(&whole, smaller) <= max_w {
        return (whole, smaller);
    }
    let chars: Vec<char> = text.chars().take(400).collect();
    for n in (0..chars.len()).rev() {
        let t = format!("{}…{suffix}", chars[..n].iter().collect::<String>());
        if width(&t, smaller) <= max_w {
            return (t, smaller);
        }
    }
    (suffix.to_string(), smaller)
}

/// On/off lengths of a dash pattern at scale 1.
fn dash_pattern(dash: Dash) -> &'static [f64] {
    match dash {
        Dash::Solid => &[],
        Dash::Dashed => &[8.0, 5.0],
        Dash::Dotted => &[2.0, 3.5],
        Dash::DashDot => &[9.0, 4.0, 2.0, 4.0],
    }
}

/// A value in the axis' plotting space (log10 on log axes), if it can be shown there.
fn to_axis(scale: Scale, v: f64) -> Option<f64> {
    match scale {
        _ if !v.is_finite() => None,
        Scale::Linear => Some(v),
        Scale::Log if v > 0.0 => Some(v.log10()),
        Scale::Log => None,
    }
}

/// A series ready to draw: colour and marker fixed, points in plotting space (`None` breaks
/// the line).
struct Prepared<'a> {
    src: &'a Series,
    color: Rgb,
    marker: Marker,
    pts: Vec<Option<(f64, f64)>>,
}

/// A category grid ready to draw: cell edges in plotting space.
struct PreparedGrid<'a> {
    src: &'a CategoryGrid,
    xe: Vec<f64>,
    ye: Vec<f64>,
    colors: Vec<Rgb>,
    any_missing: bool,
}

/// The panel's data in plotting space, with notes on what was left out.
struct PanelData<'a> {
    series: Vec<Prepared<'a>>,
    grid: Option<PreparedGrid<'a>>,
    notes: Vec<String>,
    footnotes: Vec<String>,
    /// Width of one bar group (plotting space) and the number of bar series.
    bar_slot: f64,
    bar_count: usize,
    /// Axis ranges in plotting space.
    xr: (f64, f64),
    yr: (f64, f64),
}

fn prepare_series<'a>(panel: &'a Panel, name: &str, out: &mut PanelData<'a>) {
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
fn cell_edges(c: &[f64]) -> Vec<f64> {
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

fn prepare_grid<'a>(panel: &'a Panel, name: &str) -> Result<Option<PreparedGrid<'a>>, ReportError> {
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
fn bar_slot(series: &[Prepared]) -> (f64, usize) {
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
struct AxisData {
    /// The panel's fixed range, if any.
    user: Option<(f64, f64)>,
    scale: Scale,
    /// Data coordinates (plotting space), padded by 4 %.
    data: Vec<f64>,
    /// Coordinates shown exactly (category grid edges).
    fixed: Vec<f64>,
    /// Bars: a range starting at zero stays there.
    keep_zero: bool,
}

/// The axis range in plotting space: the user's range if usable, else the data's extent with
/// 4 % padding (bars keep their zero baseline, grids their edges).
fn axis_range(a: &AxisData, what: &str, notes: &mut Vec<String>) -> (f64, f64) {
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
fn widen(lo: f64, hi: f64, scale: Scale) -> (f64, f64) {
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

fn prepare_panel<'a>(panel: &'a Panel, name: &str) -> Result<PanelData<'a>, ReportError> {
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

/// Maps plotting space to pixels inside the plot rectangle.
struct Frame {
    r: Rect,
    xr: (f64, f64),
    yr: (f64, f64),
}

impl Frame {
    fn px(&self, x: f64) -> f64 {
        self.r.x0 + (x - self.xr.0) / (self.xr.1 - self.xr.0) * self.r.width()
    }

    fn py(&self, y: f64) -> f64 {
        self.r.y1 - (y - self.yr.0) / (self.yr.1 - self.yr.0) * self.r.height()
    }

    fn map(&self, p: (f64, f64)) -> Px {
        (self.px(p.0), self.py(p.1))
    }
}

/// Ticks for one axis: the panel's own labels if given, else automatic ones.
fn axis_ticks(
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
fn axis_title(label: &str, ticks: &AxisTicks) -> (String, String) {
    match (&ticks.multiplier, label.is_empty()) {
        (Some(m), true) => (String::new(), m.clone()),
        (Some(m), false) => (label.to_string(), format!("  ({m})")),
        (None, _) => (label.to_string(), String::new()),
    }
}

/// One legend line.
enum Sample {
    Line {
        color: Rgb,
        dash: Dash,
        width: f64,
        marker: Option<Marker>,
    },
    Block(Rgb),
}

struct Legend {
    entries: Vec<(String, Sample)>,
    w: f64,
    h: f64,
    row: f64,
}

fn build_legend(d: &PanelData, z: &Sizes, s: f64) -> Option<Legend> {
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
type Obstacles = Vec<Rect>;

/// Where a panel's plot rectangle goes and what its axes show.
struct PanelLayout {
    f: Frame,
    x_ticks: AxisTicks,
    y_ticks: AxisTicks,
    x_title: (String, String),
    y_title: (String, String),
    tick_h: f64,
    xlabel_h: f64,
    ylabel_w: f64,
    foot_h: f64,
}

/// Lays out a panel in `cell`, leaving `legend_right` pixels free right of the plot.
fn layout_panel(
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

/// Draws one panel inside `cell`; returns its notes.
fn draw_panel<DB: DrawingBackend>(
    p: &Painter<DB>,
    panel: &Panel,
    cell: Rect,
    name: &str,
) -> Result<Vec<String>, ReportError> {
    let z = &p.z;
    let s = p.s;
    let d = prepare_panel(panel, name)?;
    let mut legend = if panel.legend == LegendPosition::None {
        None
    } else {
        build_legend(&d, z, s)
    };
    let mut outside = match panel.legend {
        LegendPosition::Outside => true,
        LegendPosition::Auto => {
            d.grid.is_some() || legend.as_ref().is_some_and(|l| l.entries.len() > 8)
        }
        _ => false,
    };
    let legend_right = match (&legend, outside) {
        (Some(l), true) => l.w + 2.0 * z.pad,
        _ => 0.0,
    };
    let footnotes: Vec<String> = if d.footnotes.len() > MAX_FOOTNOTES {
        let mut f = d.footnotes[..MAX_FOOTNOTES - 1].to_vec();
        f.push(format!(
            "... and {} more notes",
            d.footnotes.len() - (MAX_FOOTNOTES - 1)
        ));
        f
    } else {
        d.footnotes.clone()
    };

    let mut lay = layout_panel(panel, &d, cell, legend_right, footnotes.len(), z, name)?;
    // Auto: an inside legend that would hide more than 2 % of the ink goes outside instead,
    // if the plot keeps at least 60 % of its width.
    let mut ink = ink_points(&lay.f, &d, panel, 3.0 * s);
    if let (Some(l), false, LegendPosition::Auto) = (&legend, outside, panel.legend) {
        let (_, covered) = legend_origin(l, &lay.f, &ink, panel, false, z);
        if covered as f64 > 0.02 * ink.len() as f64 {
            let wide = layout_panel(panel, &d, cell, l.w + 2.0 * z.pad, footnotes.len(), z, name);
            if let Some(wide) = wide.ok().filter(|w| w.f.r.width() >= 0.6 * lay.f.r.width()) {
                lay = wide;
                outside = true;
                ink = ink_points(&lay.f, &d, panel, 3.0 * s);
            }
        }
    }
    let PanelLayout {
        f,
        x_ticks,
        y_ticks,
        x_title,
        y_title,
        tick_h,
        xlabel_h,
        ylabel_w,
        foot_h,
    } = lay;

    draw_grid_lines(p, &f, &x_ticks, &y_ticks, panel)?;
    if let Some(g) = &d.grid {
        draw_cells(p, &f, g)?;
    }
    draw_bars(p, &f, &d, panel.y_scale)?;
    for ps in &d.series {
        draw_series(p, &f, ps)?;
    }
    let mut obstacles: Obstacles = Vec::new();
    draw_reference_lines(p, &f, panel, &mut obstacles)?;
    draw_axes(p, &f, &x_ticks, &y_ticks)?;

    // Legend: outside, a fixed corner, or the corner covering the fewest points.
    if let Some(l) = legend.take() {
        let (at, _) = legend_origin(&l, &f, &ink, panel, outside, z);
        let r = Rect {
            x0: at.0,
            y0: at.1,
            x1: at.0 + l.w,
            y1: at.1 + l.h,
        };
        draw_legend(p, &l, r)?;
        obstacles.push(r);
    }
    draw_point_labels(p, &f, panel, &ink, &mut obstacles)?;

    // Texts around the plot, centred on it and kept inside the panel.
    let cx = (f.r.x0 + f.r.x1) / 2.0;
    let room = 2.0 * (cx - cell.x0).min(cell.x1 - cx) - 2.0 * z.pad;
    let centre = (HPos::Center, VPos::Center);
    if !panel.title.is_empty() {
        let at = (cx, cell.y0 + z.pad + z.title * 0.8);
        p.text_fit((&panel.title, ""), at, z.title, room, centre, false)?;
    }
    let xt_y = f.r.y1 + z.tick_len + 3.0 * s;
    let xl_y = xt_y + tick_h + xlabel_h * 0.5;
    p.text_fit(
        (&x_title.0, &x_title.1),
        (cx, xl_y),
        z.axis,
        room,
        centre,
        false,
    )?;
    let yl_x = cell.x0 + z.pad + ylabel_w * 0.5;
    let y_room = f.r.height() + 2.0 * z.tick;
    p.text_fit(
        (&y_title.0, &y_title.1),
        (yl_x, (f.r.y0 + f.r.y1) / 2.0),
        z.axis,
        y_room,
        centre,
        true,
    )?;
    for (k, note) in footnotes.iter().enumerate() {
        let y = cell.y1 - z.pad - foot_h + (k as f64 + 0.5) * z.note * 1.3;
        let (t, size) = fit_text(note, "", z.note, cell.width() - 2.0 * z.pad);
        p.text(
            &t,
            (cell.x0 + z.pad, y),
            size,
            NOTE,
            (HPos::Left, VPos::Center),
        )?;
    }
    if d.series.is_empty() && d.grid.is_none() {
        let c = ((f.r.x0 + f.r.x1) / 2.0, (f.r.y0 + f.r.y1) / 2.0);
        p.text(
            "no data to show",
            c,
            z.axis,
            NOTE,
            (HPos::Center, VPos::Center),
        )?;
    }
    Ok(d.notes)
}

/// Automatic x ticks thinned until their labels fit side by side.
fn fit_x_ticks(panel: &Panel, xr: (f64, f64), plot_w: f64, z: &Sizes) -> AxisTicks {
    let mut count = ((plot_w / (z.tick * 4.5)) as usize).clamp(2, 12);
    loop {
        let t = axis_ticks(&panel.x_ticks, panel.x_scale, xr, count);
        let widest = t
            .major
            .iter()
            .map(|t| text_size(&t.label, z.tick).0)
            .fold(0.0, f64::max);
        let fits = (widest + z.tick) * t.major.len() as f64 <= plot_w;
        if fits || count <= 2 || !panel.x_ticks.is_empty() {
            return t;
        }
        count -= 1;
    }
}

fn draw_grid_lines<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    xt: &AxisTicks,
    yt: &AxisTicks,
    panel: &Panel,
) -> Result<(), ReportError> {
    let w = p.s.max(1.0);
    if panel.x_scale == Scale::Log {
        for &x in &xt.minor {
            p.polyline(&[(f.px(x), f.r.y0), (f.px(x), f.r.y1)], GRID_MINOR, w)?;
        }
    }
    if panel.y_scale == Scale::Log {
        for &y in &yt.minor {
            p.polyline(&[(f.r.x0, f.py(y)), (f.r.x1, f.py(y))], GRID_MINOR, w)?;
        }
    }
    for t in &xt.major {
        p.polyline(
            &[(f.px(t.pos), f.r.y0), (f.px(t.pos), f.r.y1)],
            GRID_MAJOR,
            w,
        )?;
    }
    for t in &yt.major {
        p.polyline(
            &[(f.r.x0, f.py(t.pos)), (f.r.x1, f.py(t.pos))],
            GRID_MAJOR,
            w,
        )?;
    }
    Ok(())
}

fn draw_cells<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    g: &PreparedGrid,
) -> Result<(), ReportError> {
    let nx = g.src.x.len();
    for (k, cell) in g.src.cells.iter().enumerate() {
        let (ix, iy) = (k % nx, k / nx);
        let r = Rect {
            x0: f.px(g.xe[ix]),
            x1: f.px(g.xe[ix + 1]),
            y0: f.py(g.ye[iy + 1]),
            y1: f.py(g.ye[iy]),
        };
        let Some(r) = r.intersect(&f.r) else { continue };
        let color = cell.map_or(MISSING_CELL, |c| g.colors[c]);
        let border =
            (r.width() > 8.0 * p.s && r.height() > 8.0 * p.s).then_some((Rgb(255, 255, 255), p.s));
        p.rect(&r, Some(color), border)?;
    }
    Ok(())
}

fn draw_bars<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    d: &PanelData,
    y_scale: Scale,
) -> Result<(), ReportError> {
    if d.bar_count == 0 {
        return Ok(());
    }
    let width = d.bar_slot * 0.8 / d.bar_count as f64;
    let base = match y_scale {
        Scale::Linear => f.py(0.0_f64.clamp(f.yr.0, f.yr.1)),
        Scale::Log => f.r.y1,
    };
    for (j, ps) in d
        .series
        .iter()
        .filter(|ps| ps.src.kind == SeriesKind::Bars)
        .enumerate()
    {
        let offset = (j as f64 - (d.bar_count as f64 - 1.0) / 2.0) * width;
        for &(x, y) in ps.pts.iter().flatten() {
            let (xa, xb) = (
                f.px(x + offset - width / 2.0),
                f.px(x + offset + width / 2.0),
            );
            let yv = f.py(y);
            let r = Rect {
                x0: xa,
                x1: xb,
                y0: yv.min(base),
                y1: yv.max(base),
            };
            if let Some(r) = r.intersect(&f.r) {
                p.rect(&r, Some(ps.color), None)?;
            }
        }
    }
    Ok(())
}

/// Pixel polylines of a series: split at skipped points, long time histories reduced to four
/// points per pixel column ([`m4_decimate`]), clipped to the plot rectangle.
fn series_pieces(f: &Frame, ps: &Prepared) -> Vec<Vec<Px>> {
    let mut pieces = Vec::new();
    let mut run: Vec<Px> = Vec::new();
    for q in &ps.pts {
        match q {
            Some(q) => run.push(f.map(*q)),
            None if !run.is_empty() => pieces.push(std::mem::take(&mut run)),
            None => {}
        }
    }
    if !run.is_empty() {
        pieces.push(run);
    }
    let columns = f.r.width().max(1.0);
    for piece in &mut pieces {
        let monotone = piece.windows(2).all(|w| w[1].0 >= w[0].0);
        if piece.len() as f64 > 4.0 * columns && monotone {
            *piece = m4_decimate(piece);
        }
    }
    pieces
        .iter()
        .flat_map(|piece| clip_polyline(piece, &f.r))
        .collect()
}

fn draw_series<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    ps: &Prepared,
) -> Result<(), ReportError> {
    let kind = ps.src.kind;
    if matches!(kind, SeriesKind::Line | SeriesKind::LineMarkers) {
        let width = ps.src.line_width.clamp(0.5, 20.0) * p.s;
        for piece in series_pieces(f, ps) {
            p.dashed(&piece, ps.color, width, ps.src.dash)?;
        }
    }
    if matches!(kind, SeriesKind::Markers | SeriesKind::LineMarkers) {
        let valid: Vec<(f64, f64)> = ps.pts.iter().flatten().copied().collect();
        let n = valid.len();
        let step_through = kind == SeriesKind::LineMarkers && n > MAX_LINE_MARKERS;
        let picks: Vec<usize> = if step_through {
            (0..20).map(|i| i * (n - 1) / 19).collect()
        } else {
            (0..n).collect()
        };
        for i in picks {
            let at = f.map(valid[i]);
            if f.r.contains(at) {
                p.marker(at, ps.marker, ps.color)?;
            }
        }
    }
    Ok(())
}

fn draw_reference_lines<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    panel: &Panel,
    obstacles: &mut Obstacles,
) -> Result<(), ReportError> {
    let z = &p.z;
    let w = 1.4 * p.s;
    for a in &panel.annotations {
        match a {
            Annotation::VLine { x, label, dash } => {
                let Some(x) = to_axis(panel.x_scale, *x).filter(|x| *x >= f.xr.0 && *x <= f.xr.1)
                else {
                    continue;
                };
                let px = f.px(x);
                p.dashed(&[(px, f.r.y0), (px, f.r.y1)], REFERENCE, w, *dash)?;
                let at = (px + 4.0 * p.s, f.r.y0 + 4.0 * p.s);
                let (tw, th) = text_size(label, z.annot);
                let fits = at.0 + tw <= f.r.x1;
                let (x0, anchor) = if fits {
                    (at.0, HPos::Left)
                } else {
                    (px - 4.0 * p.s, HPos::Right)
                };
                p.text(
                    label,
                    (x0, at.1 + th / 2.0),
                    z.annot,
                    REFERENCE,
                    (anchor, VPos::Center),
                )?;
                let bx = if fits { x0 } else { x0 - tw };
                obstacles.push(Rect {
                    x0: bx,
                    y0: at.1,
                    x1: bx + tw,
                    y1: at.1 + th,
                });
            }
            Annotation::HLine { y, label, dash } => {
                let Some(y) = to_axis(panel.y_scale, *y).filter(|y| *y >= f.yr.0 && *y <= f.yr.1)
                else {
                    continue;
                };
                let py = f.py(y);
                p.dashed(&[(f.r.x0, py), (f.r.x1, py)], REFERENCE, w, *dash)?;
                let (tw, th) = text_size(label, z.annot);
                let above = py - th - 3.0 * p.s >= f.r.y0;
                let cy = if above {
                    py - 3.0 * p.s - th / 2.0
                } else {
                    py + 3.0 * p.s + th / 2.0
                };
                let x1 = f.r.x1 - 4.0 * p.s;
                p.text(
                    label,
                    (x1, cy),
                    z.annot,
                    REFERENCE,
                    (HPos::Right, VPos::Center),
                )?;
                obstacles.push(Rect {
                    x0: x1 - tw,
                    y0: cy - th / 2.0,
                    x1,
                    y1: cy + th / 2.0,
                });
            }
            Annotation::Label { .. } => {}
        }
    }
    Ok(())
}

fn draw_axes<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    xt: &AxisTicks,
    yt: &AxisTicks,
) -> Result<(), ReportError> {
    let z = &p.z;
    let w = p.s.max(1.0);
    p.rect(&f.r, None, Some((FRAME, w)))?;
    for t in &xt.major {
        let x = f.px(t.pos);
        p.polyline(&[(x, f.r.y1), (x, f.r.y1 + z.tick_len)], FRAME, w)?;
        p.text(
            &t.label,
            (x, f.r.y1 + z.tick_len + 3.0 * p.s),
            z.tick,
            TEXT,
            (HPos::Center, VPos::Top),
        )?;
    }
    for &x in &xt.minor {
        let x = f.px(x);
        p.polyline(&[(x, f.r.y1), (x, f.r.y1 + z.tick_len * 0.6)], FRAME, w)?;
    }
    for t in &yt.major {
        let y = f.py(t.pos);
        p.polyline(&[(f.r.x0 - z.tick_len, y), (f.r.x0, y)], FRAME, w)?;
        p.text(
            &t.label,
            (f.r.x0 - z.tick_len - 4.0 * p.s, y),
            z.tick,
            TEXT,
            (HPos::Right, VPos::Center),
        )?;
    }
    for &y in &yt.minor {
        let y = f.py(y);
        p.polyline(&[(f.r.x0 - z.tick_len * 0.6, y), (f.r.x0, y)], FRAME, w)?;
    }
    Ok(())
}

/// Pixels covered by the panel's data and reference lines, sampled every few pixels: what a
/// legend or a label should not hide.
fn ink_points(f: &Frame, d: &PanelData, panel: &Panel, spacing: f64) -> Vec<Px> {
    let mut ink = Vec::new();
    let mut sample = |pts: &[Px]| {
        for w in pts.windows(2) {
            let n = ((w[1].0 - w[0].0).hypot(w[1].1 - w[0].1) / spacing)
                .ceil()
                .min(10_000.0) as usize;
            for k in 0..n.max(1) {
                let t = k as f64 / n.max(1) as f64;
                ink.push((
                    w[0].0 + t * (w[1].0 - w[0].0),
                    w[0].1 + t * (w[1].1 - w[0].1),
                ));
            }
        }
        ink.extend(pts.last());
    };
    for ps in &d.series {
        match ps.src.kind {
            SeriesKind::Line | SeriesKind::LineMarkers => {
                for piece in series_pieces(f, ps) {
                    sample(&piece);
                }
            }
            SeriesKind::Markers => {
                for &q in ps.pts.iter().flatten() {
                    sample(&[f.map(q)]);
                }
            }
            SeriesKind::Bars => {
                for &q in ps.pts.iter().flatten() {
                    let top = f.map(q);
                    sample(&[top, (top.0, f.r.y1)]);
                }
            }
        }
    }
    for a in &panel.annotations {
        match a {
            Annotation::VLine { x, .. } => {
                if let Some(x) = to_axis(panel.x_scale, *x) {
                    sample(&[(f.px(x), f.r.y0), (f.px(x), f.r.y1)]);
                }
            }
            Annotation::HLine { y, .. } => {
                if let Some(y) = to_axis(panel.y_scale, *y) {
                    sample(&[(f.r.x0, f.py(y)), (f.r.x1, f.py(y))]);
                }
            }
            Annotation::Label { at, .. } => {
                if let Some(q) = to_axis(panel.x_scale, at.0).zip(to_axis(panel.y_scale, at.1)) {
                    sample(&[f.map(q)]);
                }
            }
        }
    }
    ink.retain(|&q| f.r.contains(q));
    ink
}

/// Top-left corner of the legend box, and how many ink samples it hides.
fn legend_origin(
    l: &Legend,
    f: &Frame,
    ink: &[Px],
    panel: &Panel,
    outside: bool,
    z: &Sizes,
) -> (Px, usize) {
    let inset = z.pad;
    let corner = |pos: LegendPosition| -> Px {
        let left = f.r.x0 + inset;
        let right = f.r.x1 - inset - l.w;
        let top = f.r.y0 + inset;
        let bottom = f.r.y1 - inset - l.h;
        match pos {
            LegendPosition::UpperLeft => (left, top),
            LegendPosition::LowerRight => (right, bottom),
            LegendPosition::LowerLeft => (left, bottom),
            _ => (right, top),
        }
    };
    let hidden = |at: Px| {
        let r = Rect {
            x0: at.0 - inset,
            y0: at.1 - inset,
            x1: at.0 + l.w + inset,
            y1: at.1 + l.h + inset,
        };
        ink.iter().filter(|&&q| r.contains(q)).count()
    };
    if outside {
        return ((f.r.x1 + 2.0 * z.pad, f.r.y0), 0);
    }
    if panel.legend != LegendPosition::Auto {
        let at = corner(panel.legend);
        return (at, hidden(at));
    }
    // Auto: the first corner (UR, UL, LR, LL) hiding the least ink.
    let candidates = [
        LegendPosition::UpperRight,
        LegendPosition::UpperLeft,
        LegendPosition::LowerRight,
        LegendPosition::LowerLeft,
    ];
    let mut best = (corner(LegendPosition::UpperRight), usize::MAX);
    for c in candidates {
        let at = corner(c);
        let covered = hidden(at);
        if covered < best.1 {
            best = (at, covered);
        }
    }
    best
}

fn draw_legend<DB: DrawingBackend>(
    p: &Painter<DB>,
    l: &Legend,
    r: Rect,
) -> Result<(), ReportError> {
    let z = &p.z;
    let s = p.s;
    p.rect(
        &r,
        Some(Rgb(255, 255, 255)),
        Some((Rgb(190, 190, 190), s.max(1.0))),
    )?;
    for (k, (name, sample)) in l.entries.iter().enumerate() {
        let cy = r.y0 + z.pad + (k as f64 + 0.5) * l.row;
        let (sx0, sx1) = (r.x0 + z.pad, r.x0 + z.pad + 30.0 * s);
        match sample {
            Sample::Line {
                color,
                dash,
                width,
                marker,
            } => {
                if *width > 0.0 {
                    p.dashed(&[(sx0, cy), (sx1, cy)], *color, width * s, *dash)?;
                }
                if let Some(m) = marker {
                    p.marker(((sx0 + sx1) / 2.0, cy), *m, *color)?;
                }
            }
            Sample::Block(color) => {
                let h = l.row * 0.32;
                p.rect(
                    &Rect {
                        x0: sx0 + 4.0 * s,
                        x1: sx1 - 4.0 * s,
                        y0: cy - h,
                        y1: cy + h,
                    },
                    Some(*color),
                    None,
                )?;
            }
        }
        p.text(
            name,
            (sx1 + 6.0 * s, cy),
            z.legend,
            TEXT,
            (HPos::Left, VPos::Center),
        )?;
    }
    Ok(())
}

fn draw_point_labels<DB: DrawingBackend>(
    p: &Painter<DB>,
    f: &Frame,
    panel: &Panel,
    ink: &[Px],
    obstacles: &mut Obstacles,
) -> Result<(), ReportError> {
    let z = &p.z;
    let gap = 5.0 * p.s;
    let labelled: Vec<(Px, &str)> = panel
        .annotations
        .iter()
        .filter_map(|a| match a {
            Annotation::Label { at, text } => to_axis(panel.x_scale, at.0)
                .zip(to_axis(panel.y_scale, at.1))
                .map(|q| f.map(q))
                .filter(|&q| f.r.contains(q))
                .map(|q| (q, text.as_str())),
            _ => None,
        })
        .collect();
    // The labelled points themselves are obstacles for every label.
    let r = z.marker + p.s;
    obstacles.extend(labelled.iter().map(|&(q, _)| Rect {
        x0: q.0 - r,
        y0: q.1 - r,
        x1: q.0 + r,
        y1: q.1 + r,
    }));
    for &(q, text) in &labelled {
        let (tw, th) = text_size(text, z.annot);
        // Right-above, right-below, left-above, left-below, right, left, above, below.
        let spots = [
            (q.0 + gap, q.1 - gap - th),
            (q.0 + gap, q.1 + gap),
            (q.0 - gap - tw, q.1 - gap - th),
            (q.0 - gap - tw, q.1 + gap),
            (q.0 + gap + 2.0 * p.s, q.1 - th / 2.0),
            (q.0 - gap - 2.0 * p.s - tw, q.1 - th / 2.0),
            (q.0 - tw / 2.0, q.1 - gap - th - 2.0 * p.s),
            (q.0 - tw / 2.0, q.1 + gap + 2.0 * p.s),
        ];
        // Cost: outside the plot or on another label is worst, then ink hidden; the first
        // spot wins ties.
        let cost = |b: &Rect| -> usize {
            let outside = if b.inside(&f.r) { 0 } else { 1_000_000 };
            let blocked = obstacles.iter().filter(|o| o.overlaps(b)).count() * 10_000;
            outside + blocked + ink.iter().filter(|&&i| b.contains(i)).count()
        };
        let mut best = (
            usize::MAX,
            Rect {
                x0: 0.0,
                y0: 0.0,
                x1: 0.0,
                y1: 0.0,
            },
        );
        for &(x, y) in &spots {
            let b = Rect {
                x0: x,
                y0: y,
                x1: x + tw,
                y1: y + th,
            };
            let c = cost(&b);
            if c < best.0 {
                best = (c, b);
            }
        }
        let chosen = best.1;
        p.text(
            text,
            (chosen.x0, (chosen.y0 + chosen.y1) / 2.0),
            z.annot,
            TEXT,
            (HPos::Left, VPos::Center),
        )?;
        obstacles.push(chosen);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_titles_are_shrunk_then_shortened_keeping_the_multiplier() {
        assert!(crate::font::ensure_registered());
        let label = "Tangential displacement of the pad centre node";
        let full = text_size(&format!("{label}  (×10⁻⁶)"), 20.0).0;
        // Room for 90 %: shrinking to 90 % of the size is enough (widths scale with the size,
        // up to the rounding of each glyph advance to whole pixels, hence the 2 px slack).
        let (t, size) = fit_text(label, "  (×10⁻⁶)", 20.0, 0.9 * full);
        assert_eq!(t, format!("{label}  (×10⁻⁶)"));
        assert!((15.0..20.0).contains(&size) && text_size(&t, size).0 <= 0.9 * full + 2.0);
        // Room for 40 %: at 75 % size it still does not fit, so the label is cut.
        let (t, size) = fit_text(label, "  (×10⁻⁶)", 20.0, 0.4 * full);
        assert_eq!(size, 15.0);
        assert!(
            t.ends_with("…  (×10⁻⁶)") && t.starts_with("Tangential"),
            "{t}"
        );
        assert!(text_size(&t, size).0 <= 0.4 * full, "{t}");
    }
}
