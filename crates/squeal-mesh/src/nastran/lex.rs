//! The cards of a bulk data file and of the files it includes: comments dropped (name
//! comments kept), lines split into fields in free, small or large field format, continuation
//! lines joined to their card, `INCLUDE` expanded in place, `BEGIN BULK` and `ENDDATA` obeyed.

use crate::inp::IncludeResolver;
use crate::inp::lex::{decode, normalize};
use crate::{Location, MeshError, Warning};
use std::path::{Path, PathBuf};

/// Deepest nesting of `INCLUDE` (a loop through differently spelled paths ends here).
const MAX_INCLUDE_DEPTH: usize = 32;
/// Most `INCLUDE` expansions in one read.
const MAX_INCLUDES: usize = 10_000;

/// A place in one of the read files: source index and 1-based line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Loc {
    pub src: u32,
    pub line: u32,
}

/// One data field of a card: its text (trimmed, possibly empty) and the line it is on.
#[derive(Clone, Debug)]
pub(super) struct Field {
    pub text: String,
    pub loc: Loc,
}

/// A card with its continuation lines: the name (upper case, without the large-field `*`)
/// and the data fields, eight per logical line (field 2 of the first line is `fields[0]`,
/// field 2 of the first continuation is `fields[8]`; a large-field line pair holds eight).
#[derive(Clone, Debug)]
pub(super) struct Card {
    pub name: String,
    pub loc: Loc,
    pub fields: Vec<Field>,
}

impl Card {
    /// Field `i` (0 = the card's field 2), empty past the last.
    pub fn get(&self, i: usize) -> &str {
        self.fields.get(i).map_or("", |f| f.text.as_str())
    }

    /// Where field `i` is (the card's first line past the last field).
    pub fn loc_of(&self, i: usize) -> Loc {
        self.fields.get(i).map_or(self.loc, |f| f.loc)
    }
}

/// What a name comment names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Named {
    /// A property (`$HMNAME PROP id "name"`, `$ Femap Property id : name`).
    Property,
    /// A material (`$HMNAME MAT id "name"`, `$ Femap Material id : name`).
    Material,
    /// A set (`$HMSET id type "name"`), with HyperMesh's type (1 nodes, 2 elements).
    Set(u32),
}

/// All files read, their cards in reading order, and the names comments give.
#[derive(Debug, Default)]
pub(super) struct Lexed {
    pub sources: Vec<PathBuf>,
    pub cards: Vec<Card>,
    pub names: Vec<(Named, u64, String, Loc)>,
}

impl Lexed {
    pub fn path(&self, loc: Loc) -> &Path {
        &self.sources[loc.src as usize]
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
    let mut lexer = Lexer {
        resolver,
        out: Lexed::default(),
        chain: vec![(normalize(path), path.to_path_buf())],
        expansions: 0,
        ended: false,
    };
    lexer.out.sources.push(path.to_path_buf());
    let text = decode(text, path)?;
    lexer.source(0, &text, true)?;
    Ok(lexer.out)
}

/// Upper case, blanks collapsed to one space.
fn words(line: &str) -> String {
    line.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_ascii_uppercase()
}

/// Whether a line is `BEGIN BULK` (any case and spacing).
fn is_begin_bulk(line: &str) -> bool {
    let w = words(line.split('$').next().unwrap_or(""));
    w == "BEGIN BULK" || w.starts_with("BEGIN BULK ") || w == "BEGINBULK"
}

/// Expands tabs to the next multiple of 8 columns (Nastran's rule for fixed-format lines).
fn expand_tabs(line: &str) -> String {
    let mut out = String::with_capacity(line.len() + 8);
    let mut col = 0;
    for c in line.chars() {
        if c == '\t' {
            let next = (col / 8 + 1) * 8;
            out.extend(std::iter::repeat_n(' ', next - col));
            col = next;
        } else {
            out.push(c);
            col += 1;
        }
    }
    out
}

/// Columns `from..to` of a fixed-format line (by characters), trimmed.
fn columns(chars: &[char], from: usize, to: usize) -> String {
    let to = to.min(chars.len());
    if from >= to {
        return String::new();
    }
    chars[from..to]
        .iter()
        .collect::<String>()
        .trim()
        .to_string()
}

/// The first field and the data fields of one line: free field if it has a comma, else
/// small or large fixed field. Data fields are padded to 8 (small) or 4 (large).
fn split_line(line: &str) -> Result<(String, Vec<String>), String> {
    if line.contains(',') {
        let mut parts = line.split(',').map(|s| s.trim().to_string());
        let first = parts.next().unwrap_or_default();
        let per = if first.ends_with('*') { 4 } else { 8 };
        let mut data: Vec<String> = parts.collect();
        if data.len() > per + 1 {
            return Err(format!(
                "a free-field line holds at most {} fields (the card name, {per} data fields and a continuation mark); found {}: continue the card on a line starting with ','",
                per + 2,
                data.len() + 1
            ));
        }
        data.truncate(per);
        data.resize(per, String::new());
        return Ok((first, data));
    }
    let expanded = expand_tabs(line);
    let chars: Vec<char> = expanded.chars().collect();
    let first = columns(&chars, 0, 8);
    let (per, width) = if first.ends_with('*') {
        (4, 16)
    } else {
        (8, 8)
    };
    let data = (0..per)
        .map(|k| columns(&chars, 8 + k * width, 8 + (k + 1) * width))
        .collect();
    Ok((first, data))
}

/// The 1-based number of the last line if the text ends inside it (content other than a `$`
/// comment and no line break after it): the sign of a file cut off mid-line.
fn unterminated_last_line(text: &str) -> Option<u32> {
    let (before, last) = match text.rfind('\n') {
        Some(i) => (&text[..=i], &text[i + 1..]),
        None => ("", text),
    };
    let last = last.trim();
    if last.is_empty() || last.starts_with('$') {
        return None;
    }
    let breaks = before.bytes().filter(|&b| b == b'\n').count();
    Some(u32::try_from(breaks + 1).unwrap_or(u32::MAX))
}

/// A name comment: `$HMNAME PROP 1 "LINING"`, `$HMSET 3 1 "PISTON"`, `$ Femap Material 2 :
/// STEEL`.
fn name_comment(comment: &str) -> Option<(Named, u64, String)> {
    let body = comment.trim_start_matches('$');
    let quoted = |s: &str| -> Option<String> {
        let start = s.find('"')? + 1;
        let end = start + s[start..].find('"')?;
        Some(s[start..end].trim().to_string())
    };
    let leading_int = |s: &str| -> Option<(u64, usize)> {
        let t = s.trim_start();
        let skip = s.len() - t.len();
        let n = t.bytes().take_while(u8::is_ascii_digit).count();
        Some((t[..n].parse().ok()?, skip + n))
    };
    let upper = body.to_ascii_uppercase();
    if let Some(rest) = upper.strip_prefix("HMNAME ") {
        let rest_raw = &body["HMNAME ".len()..];
        let kind_end = rest.find(|c: char| !c.is_ascii_alphabetic())?;
        let named = match &rest[..kind_end] {
            "PROP" | "PROPS" => Named::Property,
            "MAT" | "MATS" => Named::Material,
            _ => return None,
        };
        let (id, used) = leading_int(&rest_raw[kind_end..])?;
        let name = quoted(&rest_raw[kind_end + used..])?;
        return (!name.is_empty()).then_some((named, id, name));
    }
    if let Some(rest) = upper.strip_prefix("HMSET ") {
        let rest_raw = &body["HMSET ".len()..];
        let (id, used) = leading_int(rest)?;
        let (ty, used2) = leading_int(&rest[used..])?;
        let name = quoted(&rest_raw[used + used2..])?;
        let ty = u32::try_from(ty).ok()?;
        return (!name.is_empty()).then_some((Named::Set(ty), id, name));
    }
    let t = upper.trim_start();
    if t.starts_with("FEMAP ") {
        for (word, named) in [
            (" PROPERTY ", Named::Property),
            (" MATERIAL ", Named::Material),
        ] {
            if let Some(at) = t.find(word) {
                let raw = body.trim_start();
                let after = &raw[at + word.len()..];
                let (id, used) = leading_int(after)?;
                let name = after[used..].trim_start().strip_prefix(':')?.trim();
                return (!name.is_empty()).then(|| (named, id, name.to_string()));
            }
        }
    }
    None
}

struct Lexer<'r> {
    resolver: &'r dyn IncludeResolver,
    out: Lexed,
    /// Files being read, outermost first: (normalised path, path as written).
    chain: Vec<(PathBuf, PathBuf)>,
    expansions: usize,
    /// `ENDDATA` was read: nothing after it is bulk data.
    ended: bool,
}

impl Lexer<'_> {
    fn source(&mut self, src: u32, text: &str, top: bool) -> Result<(), MeshError> {
        if let Some(line) = unterminated_last_line(text) {
            return Err(self.out.error(
                Loc { src, line },
                "the file ends inside this line (no line break after it): it looks cut off, \
                 and a cut-off number or card cannot be told from a complete one. \
                 If the file is complete, end its last line with a line break",
            ));
        }
        let lines: Vec<&str> = text.split('\n').collect();
        // The top file's bulk data starts after BEGIN BULK if it has one (before it are the
        // executive and case control sections); an included file is bulk data throughout.
        let mut i = match top {
            true => lines
                .iter()
                .position(|l| is_begin_bulk(l))
                .map_or(0, |k| k + 1),
            false => 0,
        };
        while i < lines.len() && !self.ended {
            let loc = Loc {
                src,
                line: u32::try_from(i + 1).unwrap_or(u32::MAX),
            };
            let raw = lines[i].trim_end_matches('\r');
            i += 1;
            let trimmed = raw.trim_start();
            if trimmed.starts_with('$') {
                if let Some((named, id, name)) = name_comment(trimmed) {
                    self.out.names.push((named, id, name, loc));
                }
                continue;
            }
            // Only lines starting with I, E or B can be INCLUDE, ENDDATA or BEGIN BULK.
            let special = trimmed.starts_with(['I', 'i', 'E', 'e', 'B', 'b']);
            let upper = if special {
                words(trimmed)
            } else {
                String::new()
            };
            if upper.starts_with("INCLUDE") && !upper.starts_with("INCLUDE*") {
                let (name, used) = include_name(&lines[i - 1..]).ok_or_else(|| {
                    self.out.error(loc, "INCLUDE needs a file name in single quotes: INCLUDE 'file.bdf' (an unclosed quote runs to the end of the file)")
                })?;
                i += used - 1;
                self.include(&name, loc)?;
                continue;
            }
            if upper == "ENDDATA" || upper.starts_with("ENDDATA ") {
                self.ended = true;
                break;
            }
            if special && is_begin_bulk(raw) {
                continue;
            }
            let content = raw.split('$').next().unwrap_or("");
            if content.trim().is_empty() {
                continue;
            }
            self.line(content, loc)?;
        }
        Ok(())
    }

    /// One line with content: a new card or a continuation of the last one.
    fn line(&mut self, content: &str, loc: Loc) -> Result<(), MeshError> {
        let (first, data) = split_line(content).map_err(|m| self.out.error(loc, m))?;
        let continuation = first.is_empty() || first.starts_with(['+', '*']);
        let fields = data.into_iter().map(|text| Field { text, loc });
        if continuation {
            let Some(card) = self.out.cards.last_mut() else {
                return Err(self.out.error(
                    loc,
                    "a continuation line (its first field is blank or starts with '+' or '*') with no card before it",
                ));
            };
            card.fields.extend(fields);
            return Ok(());
        }
        let name = first.trim_end_matches('*').to_ascii_uppercase();
        if !name.starts_with(|c: char| c.is_ascii_alphabetic())
            || !name.chars().all(|c| c.is_ascii_alphanumeric())
        {
            let shown: String = first.chars().take(16).collect();
            return Err(self.out.error(
                loc,
                format!("expected a bulk data card name (letters and digits, such as GRID), found '{shown}'"),
            ));
        }
        self.out.cards.push(Card {
            name,
            loc,
            fields: fields.collect(),
        });
        Ok(())
    }

    /// Reads an included file, relative to the folder of the file that includes it.
    fn include(&mut self, name: &str, loc: Loc) -> Result<(), MeshError> {
        let here = self.out.path(loc);
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
                .error(loc, format!("include loop: {}", names.join(" -> "))));
        }
        if self.chain.len() >= MAX_INCLUDE_DEPTH {
            return Err(self.out.error(
                loc,
                format!("includes are nested more than {MAX_INCLUDE_DEPTH} deep"),
            ));
        }
        self.expansions += 1;
        if self.expansions > MAX_INCLUDES {
            return Err(self
                .out
                .error(loc, format!("more than {MAX_INCLUDES} files included")));
        }
        let bytes = self.resolver.read(&path).map_err(|e| {
            self.out.error(
                loc,
                format!(
                    "cannot read included file {}: {e} (an INCLUDE is relative to the folder of the file that holds it)",
                    path.display()
                ),
            )
        })?;
        let text = decode(&bytes, &path)?;
        let src = u32::try_from(self.out.sources.len())
            .map_err(|_| self.out.error(loc, "too many included files"))?;
        self.out.sources.push(path.clone());
        self.chain.push((norm, path));
        self.source(src, &text, false)?;
        self.chain.pop();
        Ok(())
    }
}

/// The file name of an `INCLUDE` statement starting at `lines[0]`: quoted (possibly over
/// several lines, the pieces joined without their outer blanks) or the rest of the line.
/// Returns the name and the number of lines used.
fn include_name(lines: &[&str]) -> Option<(String, usize)> {
    let first = lines.first()?.trim();
    let rest = first.get("INCLUDE".len()..)?.trim();
    let Some(open) = rest.strip_prefix('\'') else {
        let name = rest.split('$').next()?.trim();
        return (!name.is_empty()).then(|| (name.to_string(), 1));
    };
    let mut name = String::new();
    let mut piece = open;
    for (k, line) in lines.iter().enumerate() {
        if k > 0 {
            piece = line.trim();
        }
        if let Some(end) = piece.find('\'') {
            name.push_str(piece[..end].trim());
            return (!name.is_empty()).then_some((name, k + 1));
        }
        name.push_str(piece.trim());
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_in_the_three_formats() {
        let (f, d) = split_line("GRID,7,,1.5,2.,3.").unwrap();
        assert_eq!(
            (f.as_str(), &d[..4]),
            ("GRID", &["7", "", "1.5", "2."].map(String::from)[..])
        );
        assert_eq!(d.len(), 8);
        let (f, d) = split_line("GRID           7       0     1.5      2.      3.").unwrap();
        assert_eq!(
            (f.as_str(), &d[..5]),
            ("GRID", &["7", "0", "1.5", "2.", "3."].map(String::from)[..])
        );
        let (f, d) =
            split_line("GRID*                  7               0             1.5              2.")
                .unwrap();
        assert_eq!(
            (f.as_str(), d),
            (
                "GRID*",
                vec!["7".into(), "0".into(), "1.5".into(), "2.".into()]
            )
        );
        let (f, d) = split_line("GRID\t7\t\t1.5").unwrap();
        assert_eq!(
            (f.as_str(), &d[..3]),
            ("GRID", &["7", "", "1.5"].map(String::from)[..])
        );
        assert!(split_line("GRID,1,2,3,4,5,6,7,8,9,10").is_err());
    }

    #[test]
    fn name_comments() {
        assert_eq!(
            name_comment("$HMNAME PROP                   1\"LINING\""),
            Some((Named::Property, 1, "LINING".into()))
        );
        assert_eq!(
            name_comment("$HMNAME MAT 12 \"Steel, grade 1\" 4"),
            Some((Named::Material, 12, "Steel, grade 1".into()))
        );
        assert_eq!(
            name_comment("$HMSET        3        1 \"PISTON\""),
            Some((Named::Set(1), 3, "PISTON".into()))
        );
        assert_eq!(
            name_comment("$ Femap Property 4 : BACKPLATE"),
            Some((Named::Property, 4, "BACKPLATE".into()))
        );
        assert_eq!(name_comment("$ a comment"), None);
        assert_eq!(name_comment("$HMNAME COMP 1 \"X\""), None);
    }

    #[test]
    fn include_names() {
        assert_eq!(
            include_name(&["INCLUDE 'a.bdf'"]),
            Some(("a.bdf".into(), 1))
        );
        assert_eq!(
            include_name(&["include 'dir/", "  sub.bdf'", "GRID"]),
            Some(("dir/sub.bdf".into(), 2))
        );
        assert_eq!(include_name(&["INCLUDE b.bdf"]), Some(("b.bdf".into(), 1)));
        assert_eq!(include_name(&["INCLUDE 'open"]), None);
        assert_eq!(include_name(&["INCLUDE"]), None);
    }
}
