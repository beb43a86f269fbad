//! Tables of text cells rendered as aligned plain text (terminal), Markdown, HTML and CSV.
//!
//! Cells are strings: format numbers with [`crate::format`] (explicit significant digits) so
//! every rendering shows the same digits. Ragged rows are padded with empty cells.

use crate::ReportError;
use crate::format::fmt_sig;
use std::path::Path;

/// Horizontal alignment of a column.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Align {
    #[default]
    Left,
    Right,
    Center,
}

/// A table: a header row, body rows, and one alignment per column (missing ones: left).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Table {
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
    pub align: Vec<Align>,
}

impl Table {
    /// An empty table with this header.
    pub fn new<S: Into<String>>(header: impl IntoIterator<Item = S>) -> Table {
        Table {
            header: header.into_iter().map(Into::into).collect(),
            ..Table::default()
        }
    }

    /// A table of numbers, each with `digits` significant digits, right-aligned.
    pub fn numeric<S: Into<String>>(
        header: impl IntoIterator<Item = S>,
        rows: &[Vec<f64>],
        digits: usize,
    ) -> Table {
        let mut t = Table::new(header);
        for r in rows {
            t.push_row(r.iter().map(|&v| fmt_sig(v, digits)));
        }
        t.align = vec![Align::Right; t.columns()];
        t
    }

    /// Appends a row.
    pub fn push_row<S: Into<String>>(&mut self, row: impl IntoIterator<Item = S>) {
        self.rows.push(row.into_iter().map(Into::into).collect());
    }

    /// The same table with these column alignments.
    pub fn with_align(mut self, align: Vec<Align>) -> Table {
        self.align = align;
        self
    }

    /// Right-aligns every column whose non-empty body cells all read as numbers.
    pub fn align_numbers_right(mut self) -> Table {
        let n = self.columns();
        self.align.resize(n, Align::Left);
        for c in 0..n {
            let mut cells = self
                .rows
                .iter()
                .map(|r| r.get(c).map_or("", |s| s.trim()))
                .filter(|s| !s.is_empty());
            let mut any = false;
            let numeric = cells.all(|s| {
                any = true;
                looks_numeric(s)
            });
            if numeric && any {
                self.align[c] = Align::Right;
            }
        }
        self
    }

    /// Number of columns: the longest of the header and the rows.
    pub fn columns(&self) -> usize {
        self.rows
            .iter()
            .map(Vec::len)
            .chain([self.header.len()])
            .max()
            .unwrap_or(0)
    }

    fn align_of(&self, c: usize) -> Align {
        self.align.get(c).copied().unwrap_or_default()
    }

    /// Row `r` padded to `n` cells, with line breaks turned into spaces.
    fn padded(row: &[String], n: usize) -> Vec<String> {
        (0..n)
            .map(|c| {
                row.get(c)
                    .map_or(String::new(), |s| s.replace(['\r', '\n'], " "))
            })
            .collect()
    }

    /// Aligned plain text: columns two spaces apart, the header underlined with dashes.
    pub fn to_text(&self) -> String {
        let n = self.columns();
        let header = Self::padded(&self.header, n);
        let body: Vec<Vec<String>> = self.rows.iter().map(|r| Self::padded(r, n)).collect();
        let widths: Vec<usize> = (0..n)
            .map(|c| {
                body.iter()
                    .map(|r| r[c].chars().count())
                    .chain([header[c].chars().count()])
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        let line = |cells: &[String]| -> String {
            let parts: Vec<String> = cells
                .iter()
                .enumerate()
                .map(|(c, s)| pad(s, widths[c], self.align_of(c)))
                .collect();
            parts.join("  ").trim_end().to_string()
        };
        let mut out = String::new();
        if !self.header.is_empty() {
            out.push_str(&line(&header));
            out.push('\n');
            let rule: Vec<String> = widths.iter().map(|&w| "-".repeat(w)).collect();
            out.push_str(&rule.join("  "));
            out.push('\n');
        }
        for r in &body {
            out.push_str(&line(r));
            out.push('\n');
        }
        out
    }

    /// A GitHub-flavoured Markdown table (`|` in cells escaped).
    pub fn to_markdown(&self) -> String {
        let n = self.columns();
        let row = |cells: Vec<String>| -> String {
            let esc: Vec<String> = cells.iter().map(|s| s.replace('|', "\\|")).collect();
            format!("| {} |\n", esc.join(" | "))
        };
        let mut out = row(Self::padded(&self.header, n));
        let rule: Vec<&str> = (0..n)
            .map(|c| match self.align_of(c) {
                Align::Left => ":---",
                Align::Right => "---:",
                Align::Center => ":---:",
            })
            .collect();
        out.push_str(&format!("| {} |\n", rule.join(" | ")));
        for r in &self.rows {
            out.push_str(&row(Self::padded(r, n)));
        }
        out
    }

    /// An HTML `<table>` (text escaped, alignment as inline style).
    pub fn to_html(&self) -> String {
        let n = self.columns();
        let style = |c: usize| match self.align_of(c) {
            Align::Left => "",
            Align::Right => " style=\"text-align:right\"",
            Align::Center => " style=\"text-align:center\"",
        };
        let mut out = String::from("<table>\n");
        if !self.header.is_empty() {
            out.push_str("<thead><tr>");
            for (c, h) in Self::padded(&self.header, n).iter().enumerate() {
                out.push_str(&format!("<th{}>{}</th>", style(c), html_escape(h)));
            }
            out.push_str("</tr></thead>\n");
        }
        out.push_str("<tbody>\n");
        for r in &self.rows {
            out.push_str("<tr>");
            for (c, v) in Self::padded(r, n).iter().enumerate() {
                out.push_str(&format!("<td{}>{}</td>", style(c), html_escape(v)));
            }
            out.push_str("</tr>\n");
        }
        out.push_str("</tbody>\n</table>\n");
        out
    }

    /// CSV (RFC 4180 quoting: fields with commas, quotes, line breaks or edge spaces are quoted).
    pub fn to_csv(&self) -> String {
        let n = self.columns();
        let mut out = String::new();
        let rows = std::iter::once(&self.header)
            .filter(|h| !h.is_empty())
            .chain(&self.rows);
        for r in rows {
            let cells: Vec<String> = (0..n)
                .map(|c| csv_field(r.get(c).map_or("", String::as_str)))
                .collect();
            out.push_str(&cells.join(","));
            out.push('\n');
        }
        out
    }

    /// Writes [`Table::to_csv`] to `path` atomically.
    pub fn write_csv(&self, path: &Path) -> Result<(), ReportError> {
        squeal_io::atomic_write_bytes(path, self.to_csv().as_bytes())?;
        Ok(())
    }
}

/// True for cells like `12`, `-3.5e-4`, `1.2e3`, `NaN`, `inf`, `12%`.
fn looks_numeric(s: &str) -> bool {
    let s = s.strip_suffix('%').unwrap_or(s);
    s.parse::<f64>().is_ok()
}

fn pad(s: &str, width: usize, align: Align) -> String {
    let fill = width.saturating_sub(s.chars().count());
    match align {
        Align::Left => format!("{s}{}", " ".repeat(fill)),
        Align::Right => format!("{}{s}", " ".repeat(fill)),
        Align::Center => format!("{}{s}{}", " ".repeat(fill / 2), " ".repeat(fill - fill / 2)),
    }
}

fn csv_field(s: &str) -> String {
    let needs = s.contains([',', '"', '\n', '\r']) || s.starts_with(' ') || s.ends_with(' ');
    if needs {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Escapes text for HTML element content and attribute values.
pub fn html_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Table {
        let mut t = Table::new(["mode", "f [Hz]", "Re"]);
        t.push_row(["1", "1234.5", "-0.12"]);
        t.push_row(["pad|disc", "987", "3.4e-3"]);
        t.push_row(["short"]);
        t.align_numbers_right()
    }

    // The expected renderings are written out by hand; exact string comparison.
    #[test]
    fn text_is_aligned() {
        let expected = "\
mode      f [Hz]      Re
--------  ------  ------
1         1234.5   -0.12
pad|disc     987  3.4e-3
short
";
        assert_eq!(sample().to_text(), expected);
    }

    #[test]
    fn markdown_escapes_pipes_and_marks_alignment() {
        let md = sample().to_markdown();
        let lines: Vec<&str> = md.lines().collect();
        assert_eq!(lines[0], "| mode | f [Hz] | Re |");
        assert_eq!(lines[1], "| :--- | ---: | ---: |");
        assert_eq!(lines[3], "| pad\\|disc | 987 | 3.4e-3 |");
        assert_eq!(lines[4], "| short |  |  |");
    }

    #[test]
    fn csv_round_trips_awkward_fields() {
        let mut t = Table::new(["a", "b"]);
        t.push_row(["x,y", "say \"hi\""]);
        assert_eq!(t.to_csv(), "a,b\n\"x,y\",\"say \"\"hi\"\"\"\n");
    }

    #[test]
    fn html_escapes() {
        let mut t = Table::new(["<b>"]);
        t.push_row(["a & b"]);
        let h = t.to_html();
        assert!(h.contains("<th>&lt;b&gt;</th>"), "{h}");
        assert!(h.contains("<td>a &amp; b</td>"), "{h}");
    }

    #[test]
    fn numeric_table_uses_significant_digits() {
        let t = Table::numeric(["x", "y"], &[vec![1.0 / 3.0, 12345.678]], 3);
        assert_eq!(t.rows[0], ["0.333", "12300"]);
        assert_eq!(t.align, [Align::Right, Align::Right]);
    }
}
