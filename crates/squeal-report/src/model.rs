//! The plain data a figure is made of: [`Figure`] holds [`Panel`]s, a panel holds [`Series`],
//! [`Annotation`]s and optionally a [`CategoryGrid`] (a robustness map).
//!
//! Nothing here draws; `render` turns these structs into SVG or PNG.

/// An sRGB colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rgb(pub u8, pub u8, pub u8);

impl Rgb {
    pub const BLACK: Rgb = Rgb(0, 0, 0);
    pub const GREY: Rgb = Rgb(110, 110, 110);

    /// Mixes this colour with white; `amount = 0` keeps it, `1` gives white.
    pub fn tint(self, amount: f64) -> Rgb {
        let a = amount.clamp(0.0, 1.0);
        let mix = |c: u8| (f64::from(c) + (255.0 - f64::from(c)) * a).round() as u8;
        Rgb(mix(self.0), mix(self.1), mix(self.2))
    }
}

/// The Okabe-Ito palette (Okabe & Ito 2008, "Color Universal Design"), distinguishable with
/// the common colour-vision deficiencies; ordered so that the first lines contrast well on white.
pub const PALETTE: [Rgb; 8] = [
    Rgb(0, 114, 178),   // blue
    Rgb(213, 94, 0),    // vermillion
    Rgb(0, 158, 115),   // bluish green
    Rgb(204, 121, 167), // reddish purple
    Rgb(230, 159, 0),   // orange
    Rgb(86, 180, 233),  // sky blue
    Rgb(0, 0, 0),       // black
    Rgb(240, 228, 66),  // yellow
];

/// Colour of the `i`-th automatically coloured series (the palette, repeated).
pub fn palette_color(i: usize) -> Rgb {
    PALETTE[i % PALETTE.len()]
}

/// How the panels of a figure are arranged.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Layout {
    /// All panels side by side (the paper's Figure 2: (a) and (b)).
    #[default]
    Row,
    /// All panels stacked.
    Column,
    /// Row by row, `columns` panels per row.
    Grid { columns: usize },
}

/// A figure: a title over one or more panels, written as one SVG or PNG file.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    pub title: String,
    pub panels: Vec<Panel>,
    pub layout: Layout,
    /// Size of one panel in SVG pixels (CSS px).
    pub panel_size: (u32, u32),
    /// PNG pixels per SVG pixel (2 gives crisp images on high-density screens and in print).
    pub png_scale: f64,
}

impl Default for Figure {
    fn default() -> Self {
        Figure {
            title: String::new(),
            panels: Vec::new(),
            layout: Layout::Row,
            panel_size: (560, 420),
            png_scale: 2.0,
        }
    }
}

impl Figure {
    /// A figure with one panel and default sizes.
    pub fn single(title: impl Into<String>, panel: Panel) -> Figure {
        Figure {
            title: title.into(),
            panels: vec![panel],
            ..Figure::default()
        }
    }
}

/// Axis scale.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Scale {
    #[default]
    Linear,
    /// Base-10 logarithmic: ticks at decades; points `<= 0` are skipped (and reported).
    Log,
}

/// Where a panel's legend goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LegendPosition {
    /// The inside corner that covers the fewest data points; outside (right) for category grids.
    #[default]
    Auto,
    UpperRight,
    UpperLeft,
    LowerRight,
    LowerLeft,
    /// To the right of the plot area (the plot area gets narrower).
    Outside,
    /// No legend.
    None,
}

/// One plotting panel: axes, series, reference lines and labels, and optionally a category grid
/// drawn underneath the series.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_scale: Scale,
    pub y_scale: Scale,
    /// Fixed axis range `(min, max)`; `None` fits the data.
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
    /// Tick positions with their labels, replacing the automatic ticks (e.g. harmonic numbers,
    /// or named parameter values). Empty: automatic.
    pub x_ticks: Vec<(f64, String)>,
    pub y_ticks: Vec<(f64, String)>,
    pub series: Vec<Series>,
    pub annotations: Vec<Annotation>,
    pub legend: LegendPosition,
    /// A categorical map (e.g. robustness: converged / diverged / ...) under the series.
    pub grid: Option<CategoryGrid>,
}

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SeriesKind {
    #[default]
    Line,
    Markers,
    /// A line with markers; on long series only about 20 evenly spread markers are drawn.
    LineMarkers,
    /// Vertical bars from zero (linear y) or from the bottom of the axis (log y). Several bar
    /// series in one panel are grouped side by side at each x.
    Bars,
}

/// Line pattern.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Dash {
    #[default]
    Solid,
    Dashed,
    Dotted,
    DashDot,
}

/// Marker shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    Circle,
    Square,
    Triangle,
    Diamond,
    Cross,
    Plus,
}

/// Marker shapes in the order automatic markers use them.
pub const MARKERS: [Marker; 6] = [
    Marker::Circle,
    Marker::Square,
    Marker::Triangle,
    Marker::Diamond,
    Marker::Cross,
    Marker::Plus,
];

/// A named set of `(x, y)` points. Non-finite points are skipped (a line is broken there).
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend text; an empty name keeps the series out of the legend.
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub kind: SeriesKind,
    pub dash: Dash,
    /// `None`: the next palette colour (counting only automatically coloured series).
    pub color: Option<Rgb>,
    /// `None`: the next marker shape (counting only series that draw markers).
    pub marker: Option<Marker>,
    /// Line width in SVG pixels.
    pub line_width: f64,
}

impl Default for Series {
    fn default() -> Self {
        Series {
            name: String::new(),
            points: Vec::new(),
            kind: SeriesKind::Line,
            dash: Dash::Solid,
            color: None,
            marker: None,
            line_width: 1.8,
        }
    }
}

impl Series {
    /// A solid line.
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            ..Series::default()
        }
    }

    /// Markers only.
    pub fn markers(name: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            kind: SeriesKind::Markers,
            ..Series::default()
        }
    }

    /// A line with markers.
    pub fn line_markers(name: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            kind: SeriesKind::LineMarkers,
            ..Series::default()
        }
    }

    /// Bars.
    pub fn bars(name: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            kind: SeriesKind::Bars,
            ..Series::default()
        }
    }

    /// The same series with another line pattern.
    pub fn with_dash(mut self, dash: Dash) -> Series {
        self.dash = dash;
        self
    }

    /// The same series with a fixed colour.
    pub fn with_color(mut self, color: Rgb) -> Series {
        self.color = Some(color);
        self
    }

    /// The same series with a fixed marker shape.
    pub fn with_marker(mut self, marker: Marker) -> Series {
        self.marker = Some(marker);
        self
    }
}

/// Text and reference lines drawn over the data.
#[derive(Clone, Debug, PartialEq)]
pub enum Annotation {
    /// A vertical line across the panel at `x`, labelled at its top (e.g. "μ0").
    VLine { x: f64, label: String, dash: Dash },
    /// A horizontal line across the panel at `y`, labelled at its right end (e.g. "Re = 0").
    HLine { y: f64, label: String, dash: Dash },
    /// Text beside the point `at`, placed where it overlaps no earlier label (for labelled
    /// points; draw the points themselves as a [`SeriesKind::Markers`] series).
    Label { at: (f64, f64), text: String },
}

/// One outcome of a categorical map.
#[derive(Clone, Debug, PartialEq)]
pub struct Category {
    pub name: String,
    /// `None`: the category's index in the palette.
    pub color: Option<Rgb>,
}

/// A grid of categorical outcomes over two parameters (a robustness map).
///
/// `x` and `y` are the cell centres, strictly increasing; cell edges lie halfway between
/// neighbouring centres (in the axis' scale, so geometric means on log axes).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct CategoryGrid {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// Row by row from the lowest `y`: `cells[iy * x.len() + ix]` indexes `categories`;
    /// `None` is a cell that was not computed (drawn blank, listed as "not computed").
    pub cells: Vec<Option<usize>>,
    pub categories: Vec<Category>,
}
