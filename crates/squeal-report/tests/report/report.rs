//! Report folders: index.md and index.html reference the figures (SVG preferred) and hold the
//! tables; the HTML is balanced and self-contained; each table also goes to a CSV file.

use squeal_report::{
    Figure, Panel, Report, ReportError, Section, Series, Table, markdown_to_html, write_svg_and_png,
};
use std::path::PathBuf;

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("squeal-report-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Checks that every opened HTML element is closed in order (void elements excepted);
/// returns the first mismatch.
fn html_balanced(html: &str) -> Result<(), String> {
    const VOID: [&str; 4] = ["meta", "img", "br", "!doctype"];
    let mut stack: Vec<String> = Vec::new();
    let mut rest = html;
    while let Some(start) = rest.find('<') {
        let end = rest[start..].find('>').ok_or("unterminated tag")? + start;
        let tag = &rest[start + 1..end];
        rest = &rest[end + 1..];
        let name: String = tag
            .trim_start_matches('/')
            .chars()
            .take_while(|c| !c.is_whitespace())
            .collect::<String>()
            .to_ascii_lowercase();
        if VOID.contains(&name.as_str()) {
            continue;
        }
        if tag.starts_with('/') {
            match stack.pop() {
                Some(open) if open == name => {}
                other => return Err(format!("</{name}> closes {other:?}")),
            }
        } else {
            stack.push(name);
        }
    }
    if stack.is_empty() {
        Ok(())
    } else {
        Err(format!("unclosed: {stack:?}"))
    }
}

fn modes_table() -> Table {
    let mut t = Table::new(["mode", "f [Hz]"]);
    t.push_row(["1", "2905"]);
    t.push_row(["2 <pad & disc>", "3110"]);
    t
}

fn sample_report(figures: Vec<(PathBuf, String)>) -> Report {
    Report {
        title: "Squeal <study> & co".into(),
        intro: "First paragraph\ncontinues here.\n\nSecond paragraph.".into(),
        sections: vec![
            Section {
                heading: "Stability".into(),
                text: "Modes against friction.".into(),
                figures,
                tables: vec![(modes_table(), "Unstable modes".into())],
                after: String::new(),
            },
            Section {
                heading: "Limit cycles".into(),
                ..Section::default()
            },
        ],
    }
}

#[test]
fn report_folder_indexes_figures_and_tables() {
    let dir = temp_dir("folder");
    let fig = Figure::single(
        "f",
        Panel {
            series: vec![Series::line("a", vec![(0.0, 1.0), (1.0, 2.0)])],
            ..Panel::default()
        },
    );
    write_svg_and_png(&fig, &dir.join("figs/fig 2")).unwrap();
    let report = sample_report(vec![(PathBuf::from("figs/fig 2"), "Real parts".into())]);
    let notes = report.write(&dir).unwrap();
    assert!(notes.is_empty(), "{notes:?}");

    let md = std::fs::read_to_string(dir.join("index.md")).unwrap();
    assert!(md.starts_with("# Squeal <study> & co\n"), "{md}");
    assert!(md.contains("![Figure 1](figs/fig%202.svg)"), "{md}");
    assert!(
        md.contains("**Figure 1.** Real parts ([PNG](figs/fig%202.png))"),
        "{md}"
    );
    assert!(
        md.contains("First paragraph\ncontinues here.\n\nSecond paragraph."),
        "{md}"
    );
    assert!(md.contains("| 2 <pad & disc> | 3110 |"), "{md}");

    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    html_balanced(&html).unwrap();
    assert!(html.contains("<title>Squeal &lt;study&gt; &amp; co</title>"));
    assert!(html.contains("<img src=\"figs/fig%202.svg\""), "{html}");
    assert!(html.contains("<a href=\"figs/fig%202.png\">PNG</a>"));
    assert!(html.contains("<td>2 &lt;pad &amp; disc&gt;</td>"));
    assert!(html.contains("<a href=\"#s2\">Limit cycles</a>"));
    // Self-contained: inline CSS, nothing fetched from elsewhere.
    assert!(
        html.contains("<style>")
            && !html.contains("<link")
            && !html.contains("<script")
            && !html.contains("http")
    );

    let csv = std::fs::read_to_string(dir.join("table-1.csv")).unwrap();
    assert_eq!(csv, modes_table().to_csv());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn missing_figures_are_reported_and_png_only_is_used() {
    let dir = temp_dir("missing");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("only.png"), b"not really a png").unwrap();
    let report = sample_report(vec![
        (PathBuf::from("absent"), "never written".into()),
        (PathBuf::from("only"), "PNG only".into()),
    ]);
    let notes = report.write(&dir).unwrap();
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert!(notes[0].contains("absent"));
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    assert!(html.contains("<img src=\"only.png\""), "{html}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn figure_paths_must_stay_inside_the_report() {
    let dir = temp_dir("escape");
    for bad in ["/etc/passwd", "../outside.svg", "a/../../b.svg", ""] {
        let report = sample_report(vec![(PathBuf::from(bad), "x".into())]);
        assert!(
            matches!(report.write(&dir), Err(ReportError::FigurePath(_))),
            "{bad} accepted"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn balance_checker_catches_errors() {
    // The checker itself must be able to fail.
    assert!(html_balanced("<p><b>x</p></b>").is_err());
    assert!(html_balanced("<section><p>x</p>").is_err());
    assert!(html_balanced("<p>a<img src=\"x\"><br></p>").is_ok());
}

#[test]
fn stems_with_dots_find_their_svg() {
    let dir = temp_dir("dots");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("mu0.25.svg"), b"<svg/>").unwrap();
    let report = sample_report(vec![(PathBuf::from("mu0.25"), "at mu = 0.25".into())]);
    let notes = report.write(&dir).unwrap();
    assert!(notes.is_empty(), "{notes:?}");
    let md = std::fs::read_to_string(dir.join("index.md")).unwrap();
    assert!(md.contains("![Figure 1](mu0.25.svg)"), "{md}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The Markdown of section texts is rendered in the HTML: paragraphs, `- ` lists, code, bold,
/// emphasis and links; everything else is escaped, and a lone asterisk stays an asterisk.
#[test]
fn markdown_is_rendered_in_the_html() {
    let html = markdown_to_html(
        "A `x<1` and **bold**, *em*, 2 * 3\nand [the CSV](a%20b.csv).\n\n- one <b>\n- two",
    );
    assert_eq!(
        html,
        "<p>A <code>x&lt;1</code> and <strong>bold</strong>, <em>em</em>, 2 * 3 and \
         <a href=\"a%20b.csv\">the CSV</a>.</p>\n<ul>\n<li>one &lt;b&gt;</li>\n<li>two</li>\n</ul>\n"
    );
}
