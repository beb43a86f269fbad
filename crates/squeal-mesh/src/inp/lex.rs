//! Lines of an `.inp` file and of the files it includes: blank lines and `**` comments
//! dropped, keyword lines parsed (with nom) into name and parameters, `*INCLUDE` expanded in
//! place, so that data lines may continue across an include (`*NODE` followed by
//! `*INCLUDE, INPUT=nodes.inp` is common).

use super::IncludeResolver;
use crate::{Location, MeshError, Warning};
use nom::branch::alt;
use nom::bytes::complete::take_till;
use nom::character::complete::{char, space0};
use nom::combinator::{all_consuming, opt};
use nom::multi::many0;
use nom::sequence::{delimited, preceded, terminated};
use nom::{IResult, Parser};
use std::borrow::Cow;
use std::path::{Component, Path, PathBuf};
use std::rc::Rc;

/// Deepest nesting of `*INCLUDE` (a loop through differently spelled paths ends here).
pub(super) const MAX_INCLUDE_DEPTH: usize = 32;
/// Most `*INCLUDE` expansions in one read (bounds a file that includes another many times
/// over, which includes another many times over, ...).
pub(super) const MAX_INCLUDES: usize = 10_000;

/// Keywords whose `INPUT=file` parameter reads their data lines from another file.
const DATA_KEYWORDS: [&str; 4] = ["NODE", "ELEMENT", "NSET", "ELSET"];

/// A place in one of the read files: source index and 1-based line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Loc {
    pub src: u32,
    pub line: u32,
}

/// One file read: the top-level file or an included one.
#[derive(Debug)]
pub(super) struct Source {
    pub path: PathBuf,
    pub text: Rc<str>,
}

/// A keyword parameter: `NAME` (upper case, blanks removed) and its value, if any (as written,
/// quotes removed, outer blanks trimmed).
#[derive(Clone, Debug)]
pub(super) struct Param {
    pub name: String,
    pub value: Option<String>,
}

/// A keyword line (with its continuation lines).
#[derive(Clone, Debug)]
pub(super) struct Keyword {
    /// Upper case, blanks collapsed: `SOLID SECTION`, for messages.
    pub name: String,
    /// Upper case, blanks removed: `SOLIDSECTION`, for matching (Abaqus ignores blanks).
    pub key: String,
    pub params: Vec<Param>,
    pub loc: Loc,
}

impl Keyword {
    pub fn param(&self, name: &str) -> Option<&Param> {
        self.params.iter().find(|p| p.name == name)
    }

    /// Whether a parameter is present (`GENERATE`).
    pub fn flag(&self, name: &str) -> bool {
        self.param(name).is_some()
    }
}

/// A data line: where it is and the byte range of its trimmed text in its source.
#[derive(Clone, Copy, Debug)]
pub(super) struct DataLine {
    pub loc: Loc,
    pub start: usize,
    pub end: usize,
}

#[derive(Debug)]
pub(super) enum Item {
    Keyword(Box<Keyword>),
    Data(DataLine),
}

/// All files read and their lines, in reading order.
#[derive(Debug)]
pub(super) struct Lexed {
    pub sources: Vec<Source>,
    pub items: Vec<Item>,
}

impl Lexed {
    pub fn text(&self, d: &DataLine) -> &str {
        &self.sources[d.loc.src as usize].text[d.start..d.end]
    }

    pub fn path(&self, loc: Loc) -> &Path {
        &self.sources[loc.src as usize].path
    }

    pub fn error(&self, loc: Loc, message: impl Into<String>) -> MeshError {
        MeshError::invalid(self.path(loc), Location::Line(loc.line as usize), message)
    }

    pub fn warning(&self, loc: Loc, message: impl Into<String>) -> Warning {
        Warning {
            file: self.path(loc).to_path_buf(),
            location: Location::Line(loc.line as usize),
            message: message.into(),
        }
    }
}

/// Reads `text` (the file at `path`) and everything it includes.
pub(super) fn lex(
    text: &[u8],
    path: &Path,
    resolver: &dyn IncludeResolver,
) -> Result<Lexed, MeshError> {
    let text = decode(text, path)?;
    let mut lexer = Lexer {
        resolver,
        out: Lexed {
            sources: vec![Source {
                path: path.to_path_buf(),
                text,
            }],
            items: Vec::new(),
        },
        chain: vec![(normalize(path), path.to_path_buf())],
        expansions: 0,
    };
    lexer.source(0)?;
    Ok(lexer.out)
}

/// Checks that a file is text: UTF-8 without control characters other than tab, CR, LF and
/// form feed. The error names the first offending line.
pub(crate) fn decode(bytes: &[u8], path: &Path) -> Result<Rc<str>, MeshError> {
    let line_of = |offset: usize| 1 + bytes[..offset].iter().filter(|&&b| b == b'\n').count();
    let text = std::str::from_utf8(bytes).map_err(|e| {
        MeshError::invalid(
            path,
            Location::Line(line_of(e.valid_up_to())),
            "expected text, found bytes that are not UTF-8 (is this a binary file?)",
        )
    })?;
    if let Some(i) = bytes
        .iter()
        .position(|&b| (b < 0x20 && !matches!(b, b'\t' | b'\n' | b'\r' | 0x0c)) || b == 0x7f)
    {
        return Err(MeshError::invalid(
            path,
            Location::Line(line_of(i)),
            format!(
                "expected text, found the control character 0x{:02x} (is this a binary file?)",
                bytes[i]
            ),
        ));
    }
    Ok(Rc::from(text))
}

/// Lexical normalisation (`a/./b/../c` -> `a/c`) used to recognise an include loop.
pub(crate) fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                if matches!(out.components().next_back(), Some(Component::Normal(_))) {
                    out.pop();
                } else {
                    out.push("..");
                }
            }
            other => out.push(other.as_os_str()),
        }
    }
    out
}

fn is_blank(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\r' | '\x0c')
}

/// Content lines of one source: `(line number, start, end)` of the trimmed text, skipping
/// blank and comment lines.
#[derive(Clone)]
struct Lines<'t> {
    text: &'t str,
    pos: usize,
    line: u32,
}

impl Iterator for Lines<'_> {
    type Item = (u32, usize, usize);

    fn next(&mut self) -> Option<Self::Item> {
        while self.pos < self.text.len() {
            let rest = &self.text[self.pos..];
            let len = rest.find('\n').unwrap_or(rest.len());
            let raw = &rest[..len];
            let start = self.pos;
            self.pos += (len + 1).min(rest.len());
            self.line = self.line.saturating_add(1);
            let trimmed = raw.trim_matches(is_blank);
            if trimmed.is_empty() || trimmed.starts_with("**") {
                continue;
            }
            let s = start + (trimmed.as_ptr() as usize - raw.as_ptr() as usize);
            return Some((self.line, s, s + trimmed.len()));
        }
        None
    }
}

/// The 1-based number of the last line of `text` if the text ends inside it: the line has
/// content other than a `**` comment and no line break follows it. Every tool that writes
/// `.inp` files ends its last line, so such a line is the sign of a file cut off mid-line
/// (a copy or a download interrupted, a full disk).
fn unterminated_last_line(text: &str) -> Option<u32> {
    let (before, last) = match text.rfind('\n') {
        Some(i) => (&text[..=i], &text[i + 1..]),
        None => ("", text),
    };
    let last = last.trim_matches(is_blank);
    if last.is_empty() || last.starts_with("**") {
        return None;
    }
    let breaks = before.bytes().filter(|&b| b == b'\n').count();
    Some(u32::try_from(breaks + 1).unwrap_or(u32::MAX))
}

struct Lexer<'r> {
    resolver: &'r dyn IncludeResolver,
    out: Lexed,
    /// Files being read, outermost first: (normalised path, path as written).
    chain: Vec<(PathBuf, PathBuf)>,
    expansions: usize,
}

impl Lexer<'_> {
    fn source(&mut self, src: u32) -> Result<(), MeshError> {
        let text = Rc::clone(&self.out.sources[src as usize].text);
        if let Some(line) = unterminated_last_line(&text) {
            return Err(self.out.error(
                Loc { src, line },
                "the file ends inside this line (no line break after it): it looks cut off, \
                 and a cut-off number or record cannot be told from a complete one. \
                 If the file is complete, end its last line with a line break",
            ));
        }
        let mut lines = Lines {
            text: &text,
            pos: 0,
            line: 0,
        };
        while let Some((line, start, end)) = lines.next() {
            let loc = Loc { src, line };
            let s = &text[start..end];
            if !s.starts_with('*') {
                self.out
                    .items
                    .push(Item::Data(DataLine { loc, start, end }));
                continue;
            }
            // A keyword line ending with a comma continues on the next line, if that line
            // holds parameters (starts with a letter or a quoted name); otherwise the comma
            // is taken as a stray one and the next line as data.
            let mut joined = Cow::Borrowed(s);
            while joined.ends_with(',') {
                let mut ahead = lines.clone();
                match ahead.next() {
                    Some((_, s2, e2))
                        if text[s2..e2].starts_with(|c: char| c.is_alphabetic() || c == '"') =>
                    {
                        joined.to_mut().push_str(&text[s2..e2]);
                        lines = ahead;
                    }
                    _ => break,
                }
            }
            let kw = parse_keyword(&joined, loc).map_err(|m| self.out.error(loc, m))?;
            if kw.key == "INCLUDE" {
                self.include(&kw)?;
                continue;
            }
            let input = if DATA_KEYWORDS.contains(&kw.key.as_str()) {
                kw.param("INPUT").cloned()
            } else {
                None
            };
            self.out.items.push(Item::Keyword(Box::new(kw.clone())));
            if let Some(p) = input {
                self.include_param(&kw, &p)?;
            }
        }
        Ok(())
    }

    /// `*INCLUDE, INPUT=file`.
    fn include(&mut self, kw: &Keyword) -> Result<(), MeshError> {
        match kw.param("INPUT") {
            Some(p) => self.include_param(kw, p),
            None => Err(self.out.error(kw.loc, "*INCLUDE needs INPUT=file")),
        }
    }

    /// Reads the file named by an `INPUT=` parameter, relative to the folder of the file
    /// holding the keyword, and lexes it in place.
    fn include_param(&mut self, kw: &Keyword, p: &Param) -> Result<(), MeshError> {
        let name = match p.value.as_deref() {
            Some(v) if !v.is_empty() => v,
            _ => {
                return Err(self.out.error(
                    kw.loc,
                    format!("*{} needs INPUT=file, found INPUT without a file", kw.name),
                ));
            }
        };
        let here = self.out.path(kw.loc);
        let path = here.parent().unwrap_or(Path::new("")).join(name);
        let norm = normalize(&path);
        if let Some(i) = self.chain.iter().position(|(n, _)| *n == norm) {
            let names: Vec<String> = self.chain[i..]
                .iter()
                .map(|(_, p)| p.display().to_string())
                .chain([path.display().to_string()])
                .collect();
            return Err(self
                .out
                .error(kw.loc, format!("include loop: {}", names.join(" -> "))));
        }
        if self.chain.len() >= MAX_INCLUDE_DEPTH {
            return Err(self.out.error(
                kw.loc,
                format!("includes are nested more than {MAX_INCLUDE_DEPTH} deep"),
            ));
        }
        self.expansions += 1;
        if self.expansions > MAX_INCLUDES {
            return Err(self
                .out
                .error(kw.loc, format!("more than {MAX_INCLUDES} files included")));
        }
        let bytes = self.resolver.read(&path).map_err(|e| {
            self.out.error(
                kw.loc,
                format!("cannot read included file {}: {e}", path.display()),
            )
        })?;
        let text = decode(&bytes, &path)?;
        let src = u32::try_from(self.out.sources.len())
            .map_err(|_| self.out.error(kw.loc, "too many included files"))?;
        self.out.sources.push(Source {
            path: path.clone(),
            text,
        });
        self.chain.push((norm, path));
        self.source(src)?;
        self.chain.pop();
        Ok(())
    }
}

type Raw<'a> = (&'a str, Vec<(&'a str, Option<&'a str>)>);

/// `"name"` with optional blanks after it.
fn quoted(input: &str) -> IResult<&str, &str> {
    terminated(
        delimited(char('"'), take_till(|c| c == '"'), char('"')),
        space0,
    )
    .parse(input)
}

/// A parameter value: quoted, or everything up to the next comma.
fn value(input: &str) -> IResult<&str, &str> {
    preceded(space0, alt((quoted, take_till(|c| c == ',')))).parse(input)
}

/// `NAME` or `NAME = value`.
fn param(input: &str) -> IResult<&str, (&str, Option<&str>)> {
    (
        take_till(|c| c == ',' || c == '='),
        opt(preceded(char('='), value)),
    )
        .parse(input)
}

/// `*NAME, PARAM=value, FLAG, ...`.
fn keyword_line(input: &str) -> IResult<&str, Raw<'_>> {
    preceded(
        char('*'),
        (take_till(|c| c == ','), many0(preceded(char(','), param))),
    )
    .parse(input)
}

/// Parses a keyword line into its normalised name and parameters.
fn parse_keyword(text: &str, loc: Loc) -> Result<Keyword, String> {
    let (_, (name, raw)) = all_consuming(keyword_line).parse(text).map_err(|_| {
        format!(
            "cannot read the keyword line '{}' (a quoted name followed by more text?)",
            excerpt(text)
        )
    })?;
    let name = name
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_ascii_uppercase();
    if name.is_empty() {
        return Err(format!(
            "expected a keyword name after '*', found '{}'",
            excerpt(text)
        ));
    }
    let key: String = name.chars().filter(|c| *c != ' ').collect();
    let mut params = Vec::with_capacity(raw.len());
    for (n, v) in raw {
        let pname: String = n
            .chars()
            .filter(|c| !c.is_whitespace())
            .collect::<String>()
            .to_ascii_uppercase();
        if pname.is_empty() {
            if v.is_some() {
                return Err(format!(
                    "expected a parameter name before '=' in '{}'",
                    excerpt(text)
                ));
            }
            continue;
        }
        let value = match v.map(|v| v.trim_matches(is_blank)) {
            Some(v) if v.starts_with('"') => {
                return Err(format!(
                    "unterminated quoted value of {pname} in '{}'",
                    excerpt(text)
                ));
            }
            other => other.map(str::to_string),
        };
        params.push(Param { name: pname, value });
    }
    Ok(Keyword {
        name,
        key,
        params,
        loc,
    })
}

/// At most 60 characters of `s`, for messages.
pub(super) fn excerpt(s: &str) -> Cow<'_, str> {
    const MAX: usize = 60;
    match s.char_indices().nth(MAX) {
        Some((i, _)) => Cow::Owned(format!("{}...", &s[..i])),
        None => Cow::Borrowed(s),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const AT: Loc = Loc { src: 0, line: 1 };

    #[test]
    fn keyword_lines_are_case_and_blank_insensitive() {
        let k = parse_keyword(
            "*Solid  Section, elset = Disc , Material=\"Grey, Iron\" ,DLOAD",
            AT,
        )
        .unwrap();
        assert_eq!(k.name, "SOLID SECTION");
        assert_eq!(k.key, "SOLIDSECTION");
        assert_eq!(k.params.len(), 3);
        assert_eq!(k.param("ELSET").unwrap().value.as_deref(), Some("Disc"));
        assert_eq!(
            k.param("MATERIAL").unwrap().value.as_deref(),
            Some("Grey, Iron")
        );
        assert!(k.flag("DLOAD") && k.param("DLOAD").unwrap().value.is_none());
    }

    #[test]
    fn bad_keyword_lines_are_errors() {
        assert!(parse_keyword("*", AT).is_err());
        assert!(parse_keyword("*NSET, NSET=\"open", AT).is_err());
        assert!(parse_keyword("*NSET, NSET=\"a\"b", AT).is_err());
        assert!(parse_keyword("*NSET, =a", AT).is_err());
    }

    #[test]
    fn a_last_line_without_line_break_is_found() {
        assert_eq!(unterminated_last_line("*NODE\n1, 0., 0., 0.\n"), None);
        assert_eq!(unterminated_last_line("*NODE\n1, 0., 0.\n  \t"), None);
        assert_eq!(unterminated_last_line("*NODE\n** a comment"), None);
        assert_eq!(unterminated_last_line(""), None);
        assert_eq!(unterminated_last_line("*NODE\n1, 0., 0."), Some(2));
        assert_eq!(unterminated_last_line("*NODE\r\n\r\n1, 0."), Some(3));
        assert_eq!(unterminated_last_line("*NO"), Some(1));
    }

    #[test]
    fn normalize_removes_dot_segments() {
        assert_eq!(
            normalize(Path::new("a/./b/../c.inp")),
            PathBuf::from("a/c.inp")
        );
        assert_eq!(normalize(Path::new("../x/../y")), PathBuf::from("../y"));
    }
}
