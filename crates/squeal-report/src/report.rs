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
    /// Paragraphs separated by blank lines, in Markdown: passed through to `index.md`, and
    /// rendered in `index.html` ([`markdown_to_html`]: paragraphs, `- ` lists, `` `code` ``,
    /// `**bold**`, `*emphasis*`, `[links](url)`).
    pub text: String,
    /// Figure files relative to the report folder, with captions: a stem (`figs/fig2`, as given
    /// to [`crate::write_svg_and_png`]) or a file name. A stem or a `.png` is shown as the
    /// `.svg` beside it when that exists, with a link to the PNG.
    pub figures: Vec<(PathBuf, String)>,
    /// Tables with captions.
    pub tables: Vec<(Table, String)>,
    /// Markdown shown after the figures and tables (notes, lists of files).
    pub after: String,
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

/// Blocks of `text` separated by blank lines, each line trimmed.
fn blocks(text: &str) -> Vec<Vec<&str>> {
    let mut out = Vec::new();
    let mut cur: Vec<&str> = Vec::new();
    for line in text.lines() {
        if line.trim().is_empty() {
            if !cur.is_empty() {
                out.push(std::mem::take(&mut cur));
            }
        } else {
            cur.push(line.trim());
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

/// The Markdown `text` as HTML: blocks separated by blank lines become paragraphs, or lists
/// when every line of the block starts with `- `; inline `` `code` ``, `**bold**`,
/// `*emphasis*` and `[text](url)` are rendered, everything else is escaped.
pub fn markdown_to_html(text: &str) -> String {
    let mut out = String::new();
    for block in blocks(text) {
        if block.iter().all(|l| l.starts_with("- ")) {
            out.push_str("<ul>\n");
            for l in block {
                out.push_str(&format!("<li>{}</li>\n", inline_html(&l[2..])));
            }
            out.push_str("</ul>\n");
        } else {
            out.push_str(&format!("<p>{}</p>\n", inline_html(&block.join(" "))));
        }
    }
    out
}

/// Inline Markdown of one paragraph as HTML.
fn inline_html(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    'scan: while let Some(c) = rest.chars().next() {
        // `code`
        if c == '`'
            && let Some(end) = rest[1..].find('`')
        {
            out.push_str(&format!("<code>{}</code>", html_escape(&rest[1..1 + end])));
            rest = &rest[end + 2..];
            continue;
        }
        // [text](url)
        if c == '['
            && let Some(close) = rest.find("](")
            && let Some(end) = rest[close..].find(')')
        {
            let label = &rest[1..close];
            let href = &rest[close + 2..close + end];
            if !label.contains('[') && !href.contains(' ') {
                out.push_str(&format!(
                    "<a href=\"{}\">{}</a>",
                    html_escape(href),
                    inline_html(label)
                ));
                rest = &rest[close + end + 1..];
                continue;
            }
        }
        // **bold**, *emphasis* (not a lone asterisk, as in "2 * 3")
        for (mark, tag) in [("**", "strong"), ("*", "em")] {
            if rest.starts_with(mark)
                && rest[mark.len()..]
                    .chars()
                    .next()
                    .is_some_and(|n| !n.is_whitespace())
                && let Some(end) = rest[mark.len()..].find(mark)
                && end > 0
            {
                let inner = &rest[mark.len()..mark.len() + end];
                out.push_str(&format!("<{tag}>{}</{tag}>", inline_html(inner)));
                rest = &rest[2 * mark.len() + end..];
                continue 'scan;
            }
        }
        out.push_str(&html_escape(&c.to_string()));
        rest = &rest[c.len_utf8()..];
    }
    out
}

/// Blocks of Markdown as written (lines kept, so lists stay lists).
fn paragraphs_raw(text: &str) -> Vec<String> {
    blocks(text).into_iter().map(|b| b.join("\n")).collect()
}

const CSS: &str = "body{font-family:system-ui,-apple-system,'Segoe UI',Roboto,'DejaVu Sans',sans-serif;\
color:#1a1a1a;margin:0;background:#fafafa}main{max-width:1100px;margin:0 auto;padding:1.5rem 2rem;background:#fff}\
h1{font-size:1.7rem;border-bottom:2px solid #0072b2;padding-bottom:.3rem}h2{font-size:1.3rem;margin-top:2.2rem}\
nav ol{padding-left:1.4rem}figure{margin:1.2rem 0}figure img{max-width:100%;height:auto;border:1px solid #ddd}\
figcaption{font-size:.92rem;color:#444;margin-top:.3rem}table{border-collapse:collapse;font-size:.92rem;\
font-variant-numeric:tabular-nums;margin:.4rem 0}th,td{border:1px solid #ccc;padding:.25rem .6rem}\
th{background:#f0f4f8}tbody tr:nth-child(even){background:#f8f8f8}a{color:#0072b2}\
.scroll{overflow-x:auto;max-width:100%}code{font-size:.9em;background:#f3f3f3;padding:0 .2em}\
section:first-of-type table{font-size:1rem}section:first-of-type td:first-child{color:#333}\
@media (max-width:900px){main{padding:1rem .8rem}body{font-size:16px}}";

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
        for p in paragraphs_raw(&self.intro) {
            md.push_str(&format!("{p}\n\n"));
        }
        let (mut nf, mut nt) = (0, 0);
        for s in &self.sections {
            md.push_str(&format!("## {}\n\n", s.heading.trim()));
            for p in paragraphs_raw(&s.text) {
                md.push_str(&format!("{p}\n\n"));
            }
            for (path, caption) in &s.figures {
                nf += 1;
                let shown = resolve(dir, path, &mut notes)?;
                md.push_str(&format!(
                    "![Figure {nf}]({})\n\n**Figure {nf}.** {}",
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
                    "**Table {nt}.** {} ([CSV]({}))\n\n",
                    caption.trim(),
                    table_csv_name(nt)
                ));
                md.push_str(&table.to_markdown());
                md.push('\n');
            }
            for p in paragraphs_raw(&s.after) {
                md.push_str(&format!("{p}\n\n"));
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
        h.push_str(&markdown_to_html(&self.intro));
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
            h.push_str(&markdown_to_html(&s.text));
            for (path, caption) in &s.figures {
                nf += 1;
                let shown = resolve(dir, path, &mut notes)?;
                let alt = html_escape(caption.trim());
                let cap = inline_html(caption.trim());
                h.push_str(&format!(
                    "<figure id=\"figure-{nf}\">\n<img src=\"{}\" alt=\"{alt}\">\n<figcaption><b>Figure {nf}.</b> {cap}",
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
                    "<figure id=\"table-{nt}\">\n<figcaption><b>Table {nt}.</b> {} (<a href=\"{}\">CSV</a>)</figcaption>\n<div class=\"scroll\">{}</div></figure>\n",
                    inline_html(caption.trim()),
                    table_csv_name(nt),
                    table.to_html()
                ));
            }
            h.push_str(&markdown_to_html(&s.after));
            h.push_str("</section>\n");
        }
        h.push_str("</main>\n</body>\n</html>\n");
        Ok((h, notes))
    }
}
