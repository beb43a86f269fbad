//! Figures written as SVG and PNG: well-formed files of the right size, data drawn where the
//! axes say, skipped points reported, identical bytes on every run.

use squeal_report::{
    Annotation, Category, CategoryGrid, Figure, LegendPosition, Panel, ReportError, Rgb, Scale,
    Series, SeriesKind, render_png, render_svg, write_svg_and_png,
};
use std::path::PathBuf;

/// A fresh folder under the system temp dir.
fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("squeal-report-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn points(node: roxmltree::Node) -> Vec<(f64, f64)> {
    node.attribute("points")
        .unwrap()
        .split_whitespace()
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// Polylines drawn in `color` (`#RRGGBB`).
fn polylines(doc: &roxmltree::Document, color: &str) -> Vec<Vec<(f64, f64)>> {
    doc.descendants()
        .filter(|n| n.has_tag_name("polyline") && n.attribute("stroke") == Some(color))
        .map(points)
        .collect()
}

/// The plot frame: the unfilled rectangle with the frame colour, as (x0, y0, x1, y1).
fn frame(doc: &roxmltree::Document) -> (f64, f64, f64, f64) {
    let r = doc
        .descendants()
        .find(|n| n.has_tag_name("rect") && n.attribute("stroke") == Some("#3C3C3C"))
        .expect("frame rectangle");
    let a = |k: &str| r.attribute(k).unwrap().parse::<f64>().unwrap();
    (a("x"), a("y"), a("x") + a("width"), a("y") + a("height"))
}

fn texts(doc: &roxmltree::Document) -> Vec<String> {
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| n.text().unwrap_or("").trim().to_string())
        .collect()
}

fn unit_panel(series: Vec<Series>) -> Panel {
    Panel {
        x_range: Some((0.0, 1.0)),
        y_range: Some((0.0, 1.0)),
        series,
        legend: LegendPosition::None,
        ..Panel::default()
    }
}

const SERIES_RGB: Rgb = Rgb(1, 2, 3);

#[test]
fn svg_is_well_formed_and_sized() {
    let fig = Figure {
        title: "Two panels & a <title>".into(),
        panels: vec![Panel::default(), Panel::default()],
        ..Figure::default()
    };
    let (svg, _) = render_svg(&fig).unwrap();
    let doc = roxmltree::Document::parse(&svg).expect("SVG parses as XML");
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    // Two 560 px panels side by side; the height adds the title band (19 px font x 1.8).
    assert_eq!(root.attribute("width"), Some("1120"));
    assert_eq!(root.attribute("height"), Some("454"));
    assert!(texts(&doc).contains(&"Two panels & a <title>".to_string()));
}

#[test]
fn data_lands_on_the_frame_corners() {
    // A diagonal from (0,0) to (1,1) on unit axes must join the frame's lower-left and
    // upper-right corners. Both are rounded to whole internal units (a quarter pixel)
    // independently, hence the tolerance of one unit.
    let fig = Figure::single(
        "",
        unit_panel(vec![
            Series::line("d", vec![(0.0, 0.0), (1.0, 1.0)]).with_color(SERIES_RGB),
        ]),
    );
    let (svg, notes) = render_svg(&fig).unwrap();
    assert!(notes.is_empty(), "{notes:?}");
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let (x0, y0, x1, y1) = frame(&doc);
    let lines = polylines(&doc, "#010203");
    let line = lines
        .iter()
        .find(|l| l.len() == 2 && (l[0].1 - l[1].1).abs() > 10.0)
        .expect("data line");
    assert!(
        (line[0].0 - x0).abs() <= 1.0 && (line[0].1 - y1).abs() <= 1.0,
        "{line:?} vs {x0},{y1}"
    );
    assert!(
        (line[1].0 - x1).abs() <= 1.0 && (line[1].1 - y0).abs() <= 1.0,
        "{line:?} vs {x1},{y0}"
    );
}

#[test]
fn lines_leaving_the_range_are_clipped_at_the_frame() {
    // y = 0.5 from x = 0 to 2 with x shown on [0, 1]: the line must stop at the right edge,
    // half-way up (rounding tolerance of one internal unit as above).
    let fig = Figure::single(
        "",
        unit_panel(vec![
            Series::line("h", vec![(0.0, 0.5), (2.0, 0.5)]).with_color(SERIES_RGB),
        ]),
    );
    let (svg, _) = render_svg(&fig).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let (x0, y0, x1, y1) = frame(&doc);
    let lines = polylines(&doc, "#010203");
    let line = lines
        .iter()
        .find(|l| (l[0].0 - x0).abs() <= 1.0)
        .expect("data line");
    let end = line[line.len() - 1];
    assert!(
        (end.0 - x1).abs() <= 1.0,
        "line ends at x = {} instead of the frame edge {x1}",
        end.0
    );
    assert!((end.1 - (y0 + y1) / 2.0).abs() <= 1.0);
}

#[test]
fn log_axis_skips_non_positive_points_and_says_so() {
    let pts = vec![
        (-1.0, 1.0),
        (0.0, 2.0),
        (1.0, 3.0),
        (10.0, 4.0),
        (100.0, 5.0),
    ];
    let panel = Panel {
        x_scale: Scale::Log,
        series: vec![Series::line("sweep", pts).with_color(SERIES_RGB)],
        legend: LegendPosition::None,
        ..Panel::default()
    };
    let fig = Figure::single("", panel);
    let (svg, notes) = render_svg(&fig).unwrap();
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert!(
        notes[0].contains("2 of 5 points are <= 0 on a log axis"),
        "{}",
        notes[0]
    );
    let doc = roxmltree::Document::parse(&svg).unwrap();
    assert!(
        texts(&doc)
            .iter()
            .any(|t| t.contains("2 points ≤ 0 not shown")),
        "no footnote"
    );
    let lines = polylines(&doc, "#010203");
    assert_eq!(lines.len(), 1);
    let l = &lines[0];
    assert_eq!(l.len(), 3, "only x = 1, 10, 100 are drawn");
    // Decades are equally spaced on a log axis; whole-unit rounding of each end allows 1 unit.
    assert!(
        ((l[1].0 - l[0].0) - (l[2].0 - l[1].0)).abs() <= 1.0,
        "{l:?}"
    );
    // Decade ticks are labelled 1, 10, 100.
    let t = texts(&doc);
    for label in ["1", "10", "100"] {
        assert!(
            t.iter().any(|s| s == label),
            "tick {label} missing from {t:?}"
        );
    }
}

#[test]
fn nan_only_figure_is_drawn_with_a_note() {
    let panel = Panel {
        series: vec![Series::line(
            "broken",
            vec![(f64::NAN, 1.0), (2.0, f64::INFINITY)],
        )],
        ..Panel::default()
    };
    let fig = Figure::single("all NaN", panel);
    let (svg, notes) = render_svg(&fig).unwrap();
    assert!(
        notes
            .iter()
            .any(|n| n.contains("2 of 2 points are NaN or infinite")),
        "{notes:?}"
    );
    assert!(
        notes
            .iter()
            .any(|n| n.contains("'broken' has no point that can be drawn and was dropped"))
    );
    let doc = roxmltree::Document::parse(&svg).unwrap();
    assert!(texts(&doc).contains(&"no data to show".to_string()));
    let (png, png_notes) = render_png(&fig).unwrap();
    assert_eq!(png_notes, notes);
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"));
}

#[test]
fn nan_breaks_a_line() {
    let pts = vec![
        (0.0, 0.0),
        (0.25, 0.5),
        (0.5, f64::NAN),
        (0.75, 0.5),
        (1.0, 1.0),
    ];
    let fig = Figure::single(
        "",
        unit_panel(vec![Series::line("gap", pts).with_color(SERIES_RGB)]),
    );
    let (svg, notes) = render_svg(&fig).unwrap();
    assert!(notes[0].contains("1 of 5 points are NaN"), "{notes:?}");
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let lines: Vec<_> = polylines(&doc, "#010203")
        .into_iter()
        .filter(|l| l.len() == 2)
        .collect();
    // Two pieces of two points each, not one line through the gap.
    assert_eq!(lines.len(), 2, "{lines:?}");
}

#[test]
fn kilohertz_axis_uses_a_shared_multiplier() {
    let panel = Panel {
        x_label: "Frequency [Hz]".into(),
        x_range: Some((0.0, 20000.0)),
        series: vec![Series::line("f", vec![(0.0, 0.0), (20000.0, 1.0)])],
        ..Panel::default()
    };
    let (svg, _) = render_svg(&Figure::single("", panel)).unwrap();
    let t = texts(&roxmltree::Document::parse(&svg).unwrap());
    assert!(t.contains(&"Frequency [Hz]  (×10³)".to_string()), "{t:?}");
    // The y axis spans 0..1, so ticks reading 10 and 20 can only be the x axis in kHz.
    let shown = |v: f64| t.iter().any(|s| s.parse::<f64>() == Ok(v));
    assert!(shown(10.0) && shown(20.0), "{t:?}");
    assert!(!shown(20000.0), "{t:?}");
}

#[test]
fn automatic_legend_avoids_the_data() {
    // All data in the upper-right quarter: the legend must not go there.
    let pts: Vec<(f64, f64)> = (0..20)
        .map(|i| (0.6 + 0.02 * i as f64, 0.6 + 0.02 * i as f64))
        .collect();
    let panel = Panel {
        legend: LegendPosition::Auto,
        ..unit_panel(vec![Series::markers("cloud", pts)])
    };
    let fig = Figure::single("", panel);
    let (svg, _) = render_svg(&fig).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let (x0, _, x1, _) = frame(&doc);
    let legend = doc
        .descendants()
        .find(|n| n.has_tag_name("rect") && n.attribute("stroke") == Some("#BEBEBE"))
        .expect("legend box");
    let lx: f64 = legend.attribute("x").unwrap().parse().unwrap();
    assert!(lx < (x0 + x1) / 2.0, "legend at x = {lx}, frame {x0}..{x1}");
}

#[test]
fn category_grid_draws_one_cell_per_outcome() {
    let colors = [Rgb(10, 20, 30), Rgb(40, 50, 60)];
    let grid = CategoryGrid {
        x: vec![1.0, 2.0],
        y: vec![1.0, 2.0],
        cells: vec![Some(0), Some(1), Some(1), Some(0)],
        categories: colors
            .iter()
            .map(|&c| Category {
                name: format!("{c:?}"),
                color: Some(c),
            })
            .collect(),
    };
    let panel = Panel {
        grid: Some(grid),
        legend: LegendPosition::None,
        ..Panel::default()
    };
    let (svg, _) = render_svg(&Figure::single("", panel)).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let cells: Vec<(f64, f64)> = doc
        .descendants()
        .filter(|n| {
            n.has_tag_name("rect")
                && matches!(n.attribute("fill"), Some("#0A141E") | Some("#28323C"))
        })
        .map(|n| {
            (
                n.attribute("width").unwrap().parse().unwrap(),
                n.attribute("height").unwrap().parse().unwrap(),
            )
        })
        .collect();
    assert_eq!(cells.len(), 4);
    // The grid fills the auto-ranged axes exactly, so the four cells have the same size
    // (up to the whole-unit rounding of their corners).
    for c in &cells {
        assert!(
            (c.0 - cells[0].0).abs() <= 1.0 && (c.1 - cells[0].1).abs() <= 1.0,
            "{cells:?}"
        );
    }
}

#[test]
fn bad_figures_are_errors_not_panics() {
    let empty = Figure::default();
    assert!(matches!(
        render_svg(&empty),
        Err(ReportError::InvalidFigure(_))
    ));
    let huge = Figure {
        panel_size: (100_000, 100_000),
        ..Figure::single("", Panel::default())
    };
    assert!(matches!(
        render_png(&huge),
        Err(ReportError::InvalidFigure(_))
    ));
    let nan_scale = Figure {
        png_scale: f64::NAN,
        ..Figure::single("", Panel::default())
    };
    assert!(matches!(
        render_png(&nan_scale),
        Err(ReportError::InvalidFigure(_))
    ));
    let grid = CategoryGrid {
        x: vec![1.0, 2.0],
        y: vec![1.0],
        cells: vec![Some(0)],
        categories: vec![],
    };
    let bad_grid = Figure::single(
        "",
        Panel {
            grid: Some(grid),
            ..Panel::default()
        },
    );
    assert!(matches!(
        render_svg(&bad_grid),
        Err(ReportError::InvalidFigure(_))
    ));
    let unsorted = CategoryGrid {
        x: vec![2.0, 1.0],
        y: vec![1.0],
        cells: vec![None, None],
        categories: vec![],
    };
    let bad_axis = Figure::single(
        "",
        Panel {
            grid: Some(unsorted),
            ..Panel::default()
        },
    );
    assert!(matches!(
        render_svg(&bad_axis),
        Err(ReportError::InvalidFigure(_))
    ));
}

/// A figure with a bit of everything: lines, markers, bars, labels, reference lines.
fn busy_figure() -> Figure {
    let curve: Vec<(f64, f64)> = (0..200)
        .map(|i| (i as f64 * 0.05, (i as f64 * 0.05).sin()))
        .collect();
    let a = Panel {
        title: "(a)".into(),
        x_label: "t [s]".into(),
        y_label: "x [m]".into(),
        series: vec![
            Series::line("sin", curve.clone()),
            Series::line_markers("sin 2", curve),
        ],
        annotations: vec![
            Annotation::HLine {
                y: 0.0,
                label: "zero".into(),
                dash: Default::default(),
            },
            Annotation::Label {
                at: (1.0, 0.8),
                text: "peak".into(),
            },
        ],
        ..Panel::default()
    };
    let b = Panel {
        title: "(b)".into(),
        y_scale: Scale::Log,
        series: vec![Series::bars(
            "p",
            vec![(1.0, 0.5), (2.0, 0.05), (3.0, 0.005)],
        )],
        ..Panel::default()
    };
    Figure {
        title: "busy".into(),
        panels: vec![a, b],
        ..Figure::default()
    }
}

#[test]
fn same_figure_gives_identical_bytes_on_any_thread() {
    let fig = busy_figure();
    let (svg1, _) = render_svg(&fig).unwrap();
    let (png1, _) = render_png(&fig).unwrap();
    let other =
        std::thread::spawn(move || (render_svg(&fig).unwrap().0, render_png(&fig).unwrap().0));
    let (svg2, png2) = other.join().unwrap();
    assert!(svg1 == svg2, "SVG differs between runs");
    assert!(png1 == png2, "PNG differs between runs");
}

#[test]
fn png_has_the_requested_size_and_shows_the_data() {
    let fig = Figure {
        png_scale: 1.5,
        ..Figure::single(
            "",
            unit_panel(vec![
                Series::line("d", vec![(0.0, 0.2), (1.0, 0.8)]).with_color(SERIES_RGB),
            ]),
        )
    };
    let (png, _) = render_png(&fig).unwrap();
    let decoder = png::Decoder::new(std::io::Cursor::new(png));
    let mut reader = decoder.read_info().unwrap();
    let info = reader.info();
    // 560 x 420 px at 1.5 px per SVG px; 96 dpi x 1.5 = 144 dpi = 5669 px/m.
    assert_eq!((info.width, info.height), (840, 630));
    assert_eq!(info.pixel_dims.map(|d| d.xppu), Some(5669));
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let frame = reader.next_frame(&mut buf).unwrap();
    let rgb = &buf[..frame.line_size * frame.height as usize];
    // The line is 1.8 px x 1.5 = 2.7 px wide and about 800 px long: its pure-colour core
    // (what survives the 2 x 2 averaging at the edges) covers well over 500 pixels.
    let core = rgb.chunks(3).filter(|p| p == &[1, 2, 3]).count();
    assert!(core > 500, "only {core} pixels of the series colour");
}

#[test]
fn svg_and_png_files_are_written_without_leftovers() {
    let dir = temp_dir("write");
    let notes = write_svg_and_png(&busy_figure(), &dir.join("busy")).unwrap();
    assert!(notes.is_empty(), "{notes:?}");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["busy.png", "busy.svg"]);
    let svg = std::fs::read_to_string(dir.join("busy.svg")).unwrap();
    roxmltree::Document::parse(&svg).expect("written SVG parses");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn annotations_that_cannot_be_placed_are_noted() {
    let panel = Panel {
        y_scale: Scale::Log,
        series: vec![Series::line("a", vec![(0.0, 1.0), (1.0, 10.0)])],
        annotations: vec![
            Annotation::HLine {
                y: 0.0,
                label: "Re = 0".into(),
                dash: Default::default(),
            },
            Annotation::VLine {
                x: f64::NAN,
                label: "mu0".into(),
                dash: Default::default(),
            },
            Annotation::Label {
                at: (0.5, 3.0),
                text: "fine".into(),
            },
        ],
        ..Panel::default()
    };
    let (_, notes) = render_svg(&Figure::single("", panel)).unwrap();
    assert_eq!(notes.len(), 2, "{notes:?}");
    assert!(
        notes[0].contains("'Re = 0'") && notes[1].contains("'mu0'"),
        "{notes:?}"
    );
}

#[test]
fn legend_goes_outside_when_every_corner_hides_data() {
    // Markers on a 21 x 21 lattice cover the whole plot: no corner is free.
    let pts: Vec<(f64, f64)> = (0..441)
        .map(|k| ((k % 21) as f64 / 20.0, (k / 21) as f64 / 20.0))
        .collect();
    let panel = Panel {
        legend: LegendPosition::Auto,
        ..unit_panel(vec![Series::markers("lattice", pts)])
    };
    let (svg, _) = render_svg(&Figure::single("", panel)).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let (_, _, x1, _) = frame(&doc);
    let legend = doc
        .descendants()
        .find(|n| n.has_tag_name("rect") && n.attribute("stroke") == Some("#BEBEBE"))
        .expect("legend box");
    let lx: f64 = legend.attribute("x").unwrap().parse().unwrap();
    assert!(
        lx > x1,
        "legend at x = {lx} inside the frame ending at {x1}"
    );
}

#[test]
fn values_near_f64_max_do_not_break_the_axes() {
    let panel = Panel {
        series: vec![Series::line("huge", vec![(0.0, -1e308), (1.0, 1e308)])],
        ..Panel::default()
    };
    let fig = Figure::single("", panel);
    let (svg, notes) = render_svg(&fig).unwrap();
    assert!(
        notes.iter().any(|n| n.contains("span more than f64")),
        "{notes:?}"
    );
    roxmltree::Document::parse(&svg).unwrap();
    render_png(&fig).unwrap();
}

/// xorshift64*: a fixed pseudo-random sequence without a dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn pick<T: Copy>(&mut self, v: &[T]) -> T {
        v[(self.next() % v.len() as u64) as usize]
    }
}

#[test]
fn random_awkward_figures_never_panic() {
    // Values mixing ordinary numbers with the ones that break naive plotting code.
    let awkward = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        1e-300,
        5e-324,
        1e300,
        -1e300,
        f64::NAN,
        f64::INFINITY,
        3.7,
        1e-7,
        42.0,
    ];
    let kinds = [
        SeriesKind::Line,
        SeriesKind::Markers,
        SeriesKind::LineMarkers,
        SeriesKind::Bars,
    ];
    let scales = [Scale::Linear, Scale::Log];
    let legends = [
        LegendPosition::Auto,
        LegendPosition::Outside,
        LegendPosition::LowerLeft,
        LegendPosition::None,
    ];
    let mut rng = Rng(0x5EED);
    for case in 0..150 {
        let mut panel = Panel {
            title: "t".repeat((rng.next() % 3) as usize),
            x_label: "x".into(),
            x_scale: rng.pick(&scales),
            y_scale: rng.pick(&scales),
            legend: rng.pick(&legends),
            ..Panel::default()
        };
        if rng.next().is_multiple_of(4) {
            panel.x_range = Some((rng.pick(&awkward), rng.pick(&awkward)));
        }
        for s in 0..(rng.next() % 4) {
            let n = (rng.next() % 6) as usize;
            let pts = (0..n)
                .map(|_| (rng.pick(&awkward), rng.pick(&awkward)))
                .collect();
            panel.series.push(Series {
                name: format!("s{s}"),
                points: pts,
                kind: rng.pick(&kinds),
                ..Series::default()
            });
        }
        if rng.next().is_multiple_of(3) {
            panel.annotations.push(Annotation::Label {
                at: (rng.pick(&awkward), rng.pick(&awkward)),
                text: "p".into(),
            });
            panel.annotations.push(Annotation::VLine {
                x: rng.pick(&awkward),
                label: "v".into(),
                dash: Default::default(),
            });
        }
        let fig = Figure::single("", panel);
        let (svg, _) = render_svg(&fig).unwrap_or_else(|e| panic!("case {case}: {e}"));
        roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("case {case}: {e}"));
        if case % 15 == 0 {
            let fig = Figure {
                png_scale: 1.0,
                ..fig
            };
            render_png(&fig).unwrap_or_else(|e| panic!("case {case}: {e}"));
        }
    }
}
