//! Report folders: `index.md` and a self-contained `index.html` (inline CSS, figures by
//! relative path, SVG preferred over PNG) listing figures and tables by section, plus one CSV
//! per table (`table-1.csv`, ...) for spreadsheets and MATLAB.

use crate::table::{Table, html_escape};
use crate::{Notes, ReportError, with_suffix};
use std::path::{Component, Path, PathBuf};

/// One section of a report.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Section {
    pub heading: String,
    /// Paragraphs separated by blank lines (Markdown is passed through to `index.md`; the HTML
    /// shows it as plain text).
    pub text: String,
    /// Figure files relative to the report folder, with captions: a stem (`figs/fig2`, as given
    /// to [`crate::write_svg_and_png`]) or a file name. A stem or a `.png` is shown as the
    /// `.svg` beside it when that exists, with a link to the PNG.
    pub figures: Vec<(PathBuf, String)>,
    /// Tables with captions.
    pub tables: Vec<(Table, String)>,
}

/// A report: title, introduction, sections.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Report {
    pub title: String,
    pub intro: String,
    pub sections: Vec<Section>,
}

/// A figure as the index shows it: the file displayed and the other format, if present.
struct Shown {
    display: String,
    alternative: Option<String>,
}

/// Rejects absolute paths and `..`: the report folder must be movable as a whole.
fn check_relative(p: &Path) -> Result<(), ReportError> {
    let ok = !p.as_os_str().is_empty()
        && p.components()
            .all(|c| matches!(c, Component::Normal(_) | Component::CurDir));
    if ok {
        Ok(())
    } else {
        Err(ReportError::FigurePath(p.to_path_buf()))
    }
}

/// The file to show for figure `p` (relative to `dir`), preferring SVG.
fn resolve(dir: &Path, p: &Path, notes: &mut Notes) -> Result<Shown, ReportError> {
    check_relative(p)?;
    let ext = p
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (svg, png) = match ext.as_deref() {
        Some("svg") => (p.to_path_buf(), p.with_extension("png")),
        Some("png") => (p.with_extension("svg"), p.to_path_buf()),
        // Another existing file (a JPEG, say) is shown as it is.
        Some(_) if dir.join(p).is_file() => {
            return Ok(Shown {
                display: url(p),
                alternative: None,
            });
        }
        // Otherwise a stem, possibly with dots in it ("mu0.25").
        _ => (with_suffix(p, "svg"), with_suffix(p, "png")),
    };
    let (has_svg, has_png) = (dir.join(&svg).is_file(), dir.join(&png).is_file());
    Ok(match (has_svg, has_png) {
        (true, true) => Shown {
            display: url(&svg),
            alternative: Some(url(&png)),
        },
        (true, false) => Shown {
            display: url(&svg),
            alternative: None,
        },
        (false, true) => Shown {
            display: url(&png),
            alternative: None,
        },
        (false, false) => {
            notes.push(format!(
                "figure file {} is missing (looked for .svg and .png)",
                p.display()
            ));
            Shown {
                display: url(if ext.as_deref() == Some("png") {
                    &png
                } else {
                    &svg
                }),
                alternative: None,
            }
        }
    })
}

/// A relative path as a URL: `/` separators, unsafe bytes percent-encoded.
fn url(p: &Path) -> String {
    let parts: Vec<String> = p
        .components()
        .filter_map(|c| match c {
            Component::Normal(s) => Some(s.to_string_lossy().into_owned()),
            _ => None,
        })
        .collect();
    let mut out = String::new();
    for b in parts.join("/").bytes() {
        if b.is_ascii_alphanumeric() || b"-_.~/".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// Name of the CSV file of the `n`-th table (1-based) of the report.
pub fn table_csv_name(n: usize) -> String {
    format!("table-{n}.csv")
}

fn paragraphs(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur: Vec<&str> = Vec::new();
    for line in text.lines() {
        if line.trim().is_empty() {
            if !cur.is_empty() {
                out.push(cur.join(" "));
                cur.clear();
            }
        } else {
            cur.push(line.trim());
        }
    }
    if !cur.is_empty() {
        out.push(cur.join(" "));
    }
    out
}

const CSS: &str = "body{font-family:system-ui,-apple-system,'Segoe UI',Roboto,'DejaVu Sans',sans-serif;\
color:#1a1a1a;margin:0;background:#fafafa}main{max-width:1100px;margin:0 auto;padding:1.5rem 2rem;background:#fff}\
h1{font-size:1.7rem;border-bottom:2px solid #0072b2;padding-bottom:.3rem}h2{font-size:1.3rem;margin-top:2.2rem}\
nav ol{padding-left:1.4rem}figure{margin:1.2rem 0}figure img{max-width:100%;height:auto;border:1px solid #ddd}\
figcaption{font-size:.92rem;color:#444;margin-top:.3rem}table{border-collapse:collapse;font-size:.92rem;\
font-variant-numeric:tabular-nums;margin:.4rem 0}th,td{border:1px solid #ccc;padding:.25rem .6rem}\
th{background:#f0f4f8}tbody tr:nth-child(even){background:#f8f8f8}a{color:#0072b2}";

impl Report {
    /// Writes `index.md`, `index.html` and the tables' CSV files into `dir` (created if
    /// needed), each atomically. Returns notes about figure files that do not exist (yet).
    pub fn write(&self, dir: &Path) -> Result<Notes, ReportError> {
        let (md, notes) = self.to_markdown(dir)?;
        let (html, _) = self.to_html(dir)?;
        let mut n = 0;
        for s in &self.sections {
            for (t, _) in &s.tables {
                n += 1;
                t.write_csv(&dir.join(table_csv_name(n)))?;
            }
        }
        squeal_io::atomic_write_bytes(&dir.join("index.md"), md.as_bytes())?;
        squeal_io::atomic_write_bytes(&dir.join("index.html"), html.as_bytes())?;
        Ok(notes)
    }

    /// The Markdown index; figure files are looked up in `dir`.
    pub fn to_markdown(&self, dir: &Path) -> Result<(String, Notes), ReportError> {
        let mut notes = Notes::new();
        let mut md = format!("# {}\n\n", self.title.trim());
        for p in paragraphs(&self.intro) {
            md.push_str(&format!("{p}\n\n"));
        }
        let (mut nf, mut nt) = (0, 0);
        for s in &self.sections {
            md.push_str(&format!("## {}\n\n", s.heading.trim()));
            for p in paragraphs(&s.text) {
                md.push_str(&format!("{p}\n\n"));
            }
            for (path, caption) in &s.figures {
                nf += 1;
                let shown = resolve(dir, path, &mut notes)?;
                md.push_str(&format!(
                    "![Figure {nf}]({})\n\n*Figure {nf}: {}*",
                    shown.display,
                    caption.trim()
                ));
                if let Some(alt) = &shown.alternative {
                    md.push_str(&format!(" ([PNG]({alt}))"));
                }
                md.push_str("\n\n");
            }
            for (table, caption) in &s.tables {
                nt += 1;
                md.push_str(&format!(
                    "**Table {nt}: {}** ([CSV]({}))\n\n",
                    caption.trim(),
                    table_csv_name(nt)
                ));
                md.push_str(&table.to_markdown());
                md.push('\n');
            }
        }
        Ok((md, notes))
    }

    /// The self-contained HTML index (inline CSS, no scripts); figure files are looked up in `dir`.
    pub fn to_html(&self, dir: &Path) -> Result<(String, Notes), ReportError> {
        let mut notes = Notes::new();
        let title = html_escape(self.title.trim());
        let mut h = format!(
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
             <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
             <title>{title}</title>\n<style>{CSS}</style>\n</head>\n<body>\n<main>\n<h1>{title}</h1>\n"
        );
        for p in paragraphs(&self.intro) {
            h.push_str(&format!("<p>{}</p>\n", html_escape(&p)));
        }
        if self.sections.len() > 1 {
            h.push_str("<nav><ol>\n");
            for (i, s) in self.sections.iter().enumerate() {
                h.push_str(&format!(
                    "<li><a href=\"#s{}\">{}</a></li>\n",
                    i + 1,
                    html_escape(s.heading.trim())
                ));
            }
            h.push_str("</ol></nav>\n");
        }
        let (mut nf, mut nt) = (0, 0);
        for (i, s) in self.sections.iter().enumerate() {
            h.push_str(&format!(
                "<section id=\"s{}\">\n<h2>{}</h2>\n",
                i + 1,
                html_escape(s.heading.trim())
            ));
            for p in paragraphs(&s.text) {
                h.push_str(&format!("<p>{}</p>\n", html_escape(&p)));
            }
            for (path, caption) in &s.figures {
                nf += 1;
                let shown = resolve(dir, path, &mut notes)?;
                let cap = html_escape(caption.trim());
                h.push_str(&format!(
                    "<figure>\n<img src=\"{}\" alt=\"Figure {nf}: {cap}\">\n<figcaption>Figure {nf}: {cap}",
                    html_escape(&shown.display)
                ));
                if let Some(alt) = &shown.alternative {
                    h.push_str(&format!(" (<a href=\"{}\">PNG</a>)", html_escape(alt)));
                }
                h.push_str("</figcaption>\n</figure>\n");
            }
            for (table, caption) in &s.tables {
                nt += 1;
                h.push_str(&format!(
                    "<figure>\n<figcaption>Table {nt}: {} (<a href=\"{}\">CSV</a>)</figcaption>\n{}</figure>\n",
                    html_escape(caption.trim()),
                    table_csv_name(nt),
                    table.to_html()
                ));
            }
            h.push_str("</section>\n");
        }
        h.push_str("</main>\n</body>\n</html>\n");
        Ok((h, notes))
    }
}
