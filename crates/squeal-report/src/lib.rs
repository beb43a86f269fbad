//! Plots, tables and report folders for squeal.
//!
//! * Plots: describe a [`Figure`] as plain data (panels of [`Series`], reference lines, point
//!   labels, category grids for robustness maps) and write it with [`write_svg`], [`write_png`]
//!   or [`write_svg_and_png`]. Log axes tick at decades; linear axes share an engineering
//!   multiplier (x10³) so kHz and µm read well. Points that cannot be drawn (NaN, inf, <= 0 on a
//!   log axis) are skipped, reported in the returned notes and in a footnote under the panel.
//! * Tables: [`Table`] renders as aligned text, Markdown, HTML and CSV; [`format`](mod@format) has the
//!   number formatters with explicit significant digits.
//! * Reports: [`Report`] writes `index.md` and a self-contained `index.html` into a folder.
//!
//! Text uses an embedded DejaVu Sans (no system font or fontconfig is needed), and every file is
//! written atomically with [`squeal_io::atomic_write`].
//!
//! ```no_run
//! use squeal_report::{Annotation, Dash, Figure, Panel, Report, Section, Series, Table};
//! use std::path::Path;
//!
//! // Figure 2 (a) of Coudeyras et al. 2009: real parts against friction.
//! let mus: Vec<f64> = (0..=50).map(|i| 0.01 * i as f64).collect();
//! let panel = Panel {
//!     title: "(a) Real parts".into(),
//!     x_label: "Friction coefficient μ".into(),
//!     y_label: "Real part [1/s]".into(),
//!     series: vec![
//!         Series::line("mode 1", mus.iter().map(|&m| (m, 100.0 * (m - 0.2))).collect()),
//!         Series::line("mode 2", mus.iter().map(|&m| (m, -100.0 * m)).collect()).with_dash(Dash::Dashed),
//!     ],
//!     annotations: vec![
//!         Annotation::HLine { y: 0.0, label: "Re = 0".into(), dash: Dash::Dotted },
//!         Annotation::VLine { x: 0.2, label: "μ0".into(), dash: Dash::Dashed },
//!     ],
//!     ..Panel::default()
//! };
//! let dir = Path::new("out/report");
//! let notes = squeal_report::write_svg_and_png(&Figure::single("Stability", panel), &dir.join("fig2"))?;
//! for n in notes {
//!     eprintln!("note: {n}"); // points that could not be drawn (NaN, <= 0 on a log axis)
//! }
//! let mut modes = Table::new(["mode", "f [Hz]"]);
//! modes.push_row(["1", "2905"]);
//! let report = Report {
//!     title: "Brake squeal study".into(),
//!     intro: String::new(),
//!     sections: vec![Section {
//!         heading: "Stability".into(),
//!         text: "Modes against friction.".into(),
//!         figures: vec![("fig2".into(), "Real parts".into())],
//!         tables: vec![(modes.align_numbers_right(), "Unstable modes".into())],
//!         ..Section::default()
//!     }],
//! };
//! report.write(dir)?; // index.md, index.html, table-1.csv
//! # Ok::<(), squeal_report::ReportError>(())
//! ```

mod font;
pub mod format;
mod geom;
pub mod model;
pub mod raster;
mod render;
pub mod report;
pub mod table;
mod ticks;

pub use model::{
    Annotation, Category, CategoryGrid, Dash, Figure, Layout, LegendPosition, MARKERS, Marker,
    PALETTE, Panel, Rgb, Scale, Series, SeriesKind, palette_color,
};
pub use report::{Report, Section, markdown_to_html};
pub use table::{Align, Table};

use plotters::prelude::*;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// What can go wrong when writing a figure, table or report.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    #[error(transparent)]
    Io(#[from] squeal_io::IoError),
    #[error("invalid figure: {0}")]
    InvalidFigure(String),
    #[error("drawing failed: {0}")]
    Draw(String),
    #[error("PNG encoding failed: {0}")]
    Png(String),
    #[error("the embedded font could not be loaded")]
    Font,
    #[error("figure path '{0}' must be relative and stay inside the report folder")]
    FigurePath(PathBuf),
}

/// Notes about data that was left out of a figure (one line each, naming panel and series).
pub type Notes = Vec<String>;

/// Internal units per SVG pixel: coordinates and stroke widths are whole numbers in plotters'
/// SVG output, so drawing at 4x (shown at 1x through the `viewBox`) keeps curves smooth and
/// widths within an eighth of a pixel.
const SVG_UNITS_PER_PX: f64 = 4.0;

/// Renders `fig` as an SVG document, `fig.panel_size` pixels per panel.
pub fn render_svg(fig: &Figure) -> Result<(String, Notes), ReportError> {
    if !font::ensure_registered() {
        return Err(ReportError::Font);
    }
    let (w, h) = render::figure_pixels(fig, 1.0)?;
    let (iw, ih) = render::figure_pixels(fig, SVG_UNITS_PER_PX)?;
    let mut svg = String::new();
    let notes = {
        let area = SVGBackend::with_string(&mut svg, (iw, ih)).into_drawing_area();
        render::draw_figure(&area, fig, SVG_UNITS_PER_PX, false)?
    };
    let inner = format!("<svg width=\"{iw}\" height=\"{ih}\"");
    let outer = format!("<svg width=\"{w}\" height=\"{h}\"");
    Ok((svg.replacen(&inner, &outer, 1), notes))
}

/// Renders `fig` as a PNG image at `fig.png_scale` pixels per SVG pixel.
///
/// The image is drawn at twice that resolution and averaged down 2 x 2 (anti-aliasing: plotters'
/// bitmap lines have hard edges).
pub fn render_png(fig: &Figure) -> Result<(Vec<u8>, Notes), ReportError> {
    if !font::ensure_registered() {
        return Err(ReportError::Font);
    }
    let scale = fig.png_scale;
    if !(0.25..=8.0).contains(&scale) {
        return Err(ReportError::InvalidFigure(format!(
            "png_scale {scale} is outside 0.25 .. 8"
        )));
    }
    let (big_w, big_h) = render::figure_pixels(fig, 2.0 * scale)?;
    let (w, h) = (big_w / 2, big_h / 2);
    let mut big = vec![255u8; 4 * w as usize * h as usize * 3];
    let notes = {
        let area = BitMapBackend::with_buffer(&mut big, (2 * w, 2 * h)).into_drawing_area();
        render::draw_figure(&area, fig, 2.0 * scale, true)?
    };
    let rgb = downsample_2x2(&big, w as usize, h as usize);
    Ok((encode_png(&rgb, w, h, scale)?, notes))
}

/// Averages each 2 x 2 block of an RGB image of `2w x 2h` pixels (rounding to nearest).
pub(crate) fn downsample_2x2(big: &[u8], w: usize, h: usize) -> Vec<u8> {
    let mut out = vec![0u8; w * h * 3];
    let stride = 2 * w * 3;
    for y in 0..h {
        for x in 0..w {
            for c in 0..3 {
                let i = 2 * y * stride + 2 * x * 3 + c;
                let sum = u32::from(big[i])
                    + u32::from(big[i + 3])
                    + u32::from(big[i + stride])
                    + u32::from(big[i + stride + 3]);
                out[(y * w + x) * 3 + c] = ((sum + 2) / 4) as u8;
            }
        }
    }
    out
}

/// PNG bytes of an RGB buffer, tagged with 96 dpi x `scale` so office programs size it as the SVG.
pub(crate) fn encode_png(rgb: &[u8], w: u32, h: u32, scale: f64) -> Result<Vec<u8>, ReportError> {
    let err = |e: png::EncodingError| ReportError::Png(e.to_string());
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let ppm = (96.0 / 0.0254 * scale).round() as u32;
    enc.set_pixel_dims(Some(png::PixelDimensions {
        xppu: ppm,
        yppu: ppm,
        unit: png::Unit::Meter,
    }));
    let mut writer = enc.write_header().map_err(err)?;
    writer.write_image_data(rgb).map_err(err)?;
    writer.finish().map_err(err)?;
    Ok(out)
}

/// Writes `fig` as an SVG file (atomically); returns the notes about skipped data.
pub fn write_svg(fig: &Figure, path: &Path) -> Result<Notes, ReportError> {
    let (svg, notes) = render_svg(fig)?;
    squeal_io::atomic_write_bytes(path, svg.as_bytes())?;
    Ok(notes)
}

/// Writes `fig` as a PNG file (atomically); returns the notes about skipped data.
pub fn write_png(fig: &Figure, path: &Path) -> Result<Notes, ReportError> {
    let (png, notes) = render_png(fig)?;
    squeal_io::atomic_write_bytes(path, &png)?;
    Ok(notes)
}

/// `stem` with `.ext` appended (`out/fig2` -> `out/fig2.svg`; an existing dot is kept).
pub fn with_suffix(stem: &Path, ext: &str) -> PathBuf {
    let mut s = OsString::from(stem.as_os_str());
    s.push(".");
    s.push(ext);
    PathBuf::from(s)
}

/// Writes `stem.svg` and `stem.png`; returns the notes about skipped data (the same for both).
pub fn write_svg_and_png(fig: &Figure, stem: &Path) -> Result<Notes, ReportError> {
    let notes = write_svg(fig, &with_suffix(stem, "svg"))?;
    write_png(fig, &with_suffix(stem, "png"))?;
    Ok(notes)
}
