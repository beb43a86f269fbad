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

mod draw;
mod layout;
mod prepare;

use draw::*;
use layout::*;
use prepare::*;

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
