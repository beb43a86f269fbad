//! A position in the bytes of a `.msh` file: text lines, whitespace-separated fields, and
//! binary integers and doubles in the file's byte order, each read with a nom number parser.
//!
//! Every read names what it expected, so that an error says where (line for ASCII files, byte
//! offset for binary files) and what was wanted there.

use crate::{Location, MeshError};
use nom::Parser;
use nom::combinator::all_consuming;
use nom::number::Endianness;
use std::path::Path;

/// Longest piece of the file quoted in an error message.
const QUOTE_MAX: usize = 40;

/// One line of the file, without its line ending.
#[derive(Clone, Copy, Debug)]
pub(super) struct Line<'a> {
    pub text: &'a [u8],
    /// 1-based line number (meaningful in ASCII files).
    pub number: usize,
    /// Byte offset of the line's first byte.
    pub start: usize,
}

impl<'a> Line<'a> {
    /// The line without surrounding whitespace.
    pub fn trimmed(&self) -> &'a [u8] {
        self.text.trim_ascii()
    }

    pub fn is_blank(&self) -> bool {
        self.trimmed().is_empty()
    }
}

/// The bytes of a file and a read position.
pub(super) struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// 1-based number of the line starting at `pos` (kept while reading lines; binary reads
    /// leave it stale, which is why binary files report byte offsets).
    line: usize,
    file: &'a Path,
    /// Report byte offsets rather than line numbers.
    pub binary: bool,
    /// Byte order of binary numbers.
    pub endian: Endianness,
}

impl<'a> Cursor<'a> {
    pub fn new(bytes: &'a [u8], file: &'a Path) -> Self {
        Cursor {
            bytes,
            pos: 0,
            line: 1,
            file,
            binary: false,
            endian: Endianness::Little,
        }
    }

    pub fn file(&self) -> &'a Path {
        self.file
    }

    /// Bytes not read yet.
    pub fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    /// Where the cursor is.
    pub fn here(&self) -> Location {
        if self.binary {
            Location::Byte(self.pos as u64)
        } else {
            Location::Line(self.line)
        }
    }

    /// Where a line is.
    pub fn at(&self, line: &Line<'_>) -> Location {
        if self.binary {
            Location::Byte(line.start as u64)
        } else {
            Location::Line(line.number)
        }
    }

    /// An error at `location`.
    pub fn error(&self, location: Location, message: impl Into<String>) -> MeshError {
        MeshError::invalid(self.file, location, message)
    }

    /// The next line (possibly blank), or `None` at the end of the file.
    pub fn next_line(&mut self) -> Option<Line<'a>> {
        if self.pos >= self.bytes.len() {
            return None;
        }
        let rest = &self.bytes[self.pos..];
        let len = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        let mut text = &rest[..len];
        if let [head @ .., b'\r'] = text {
            text = head;
        }
        let line = Line {
            text,
            number: self.line,
            start: self.pos,
        };
        self.pos = (self.pos + len + 1).min(self.bytes.len());
        self.line += 1;
        Some(line)
    }

    /// The next line that is not blank, or `None` at the end of the file.
    pub fn next_nonblank(&mut self) -> Option<Line<'a>> {
        loop {
            let line = self.next_line()?;
            if !line.is_blank() {
                return Some(line);
            }
        }
    }

    /// The next non-blank line; at the end of the file, an error naming what was expected.
    pub fn expect_line(&mut self, what: &str) -> Result<Line<'a>, MeshError> {
        match self.next_nonblank() {
            Some(line) => Ok(line),
            None => Err(self.error(
                self.here(),
                format!("unexpected end of file: expected {what}"),
            )),
        }
    }

    /// The fields of the next non-blank line.
    pub fn expect_fields(&mut self, what: &str) -> Result<Fields<'a>, MeshError> {
        let line = self.expect_line(what)?;
        Ok(Fields::new(line, self.at(&line), self.file))
    }

    /// Reads the line closing section `name` (`$End<name>`).
    pub fn expect_end(&mut self, name: &str) -> Result<(), MeshError> {
        let line = self.expect_line(&format!("$End{name}"))?;
        if line.trimmed() == format!("$End{name}").as_bytes() {
            Ok(())
        } else {
            Err(self.error(
                self.at(&line),
                format!("expected $End{name}, found `{}`", quote(line.trimmed())),
            ))
        }
    }

    /// Fails unless `count` items of at least `min_bytes` each fit in the rest of the file; the
    /// count is then safe to allocate for.
    pub fn check_count(
        &self,
        count: u64,
        min_bytes: u64,
        what: &str,
        location: Location,
    ) -> Result<usize, MeshError> {
        let fits = count
            .checked_mul(min_bytes)
            .is_some_and(|need| need <= self.remaining() as u64);
        match usize::try_from(count) {
            Ok(n) if fits => Ok(n),
            _ => Err(self.error(
                location,
                format!(
                    "{count} {what} declared, but the {} bytes left in the file cannot hold them \
                     (a truncated file or a wrong count)",
                    self.remaining()
                ),
            )),
        }
    }

    /// Skips `n` bytes of binary data.
    pub fn skip(&mut self, n: u64, what: &str) -> Result<(), MeshError> {
        match usize::try_from(n) {
            Ok(n) if n <= self.remaining() => {
                self.pos += n;
                Ok(())
            }
            _ => Err(self.truncated(what)),
        }
    }

    fn truncated(&self, what: &str) -> MeshError {
        self.error(
            self.here(),
            format!("unexpected end of file: expected {what}"),
        )
    }

    /// Runs a nom binary parser at the cursor.
    fn binary<T>(
        &mut self,
        parser: impl FnOnce(&'a [u8]) -> nom::IResult<&'a [u8], T, ()>,
        what: &str,
    ) -> Result<T, MeshError> {
        let input = &self.bytes[self.pos..];
        match parser(input) {
            Ok((rest, value)) => {
                self.pos += input.len() - rest.len();
                Ok(value)
            }
            Err(_) => Err(self.truncated(what)),
        }
    }

    /// Binary files write the `int` 1 after the format line: its bytes give the byte order.
    pub fn byte_order_mark(&mut self) -> Result<(), MeshError> {
        let at = self.here();
        let mark = self.binary(
            nom::number::complete::le_i32,
            "the byte-order mark (the int 1)",
        )?;
        self.endian = match mark {
            1 => Endianness::Little,
            0x0100_0000 => Endianness::Big,
            _ => {
                return Err(self.error(
                    at,
                    format!("expected the byte-order mark (the int 1, little- or big-endian), found {mark:#010x}"),
                ));
            }
        };
        Ok(())
    }

    /// A binary 4-byte signed integer (C `int`).
    pub fn int(&mut self, what: &str) -> Result<i32, MeshError> {
        self.binary(nom::number::complete::i32(self.endian), what)
    }

    /// A binary 4-byte `int` that must not be negative (counts, MSH 2.2 tags).
    pub fn uint(&mut self, what: &str) -> Result<u64, MeshError> {
        let at = self.here();
        let v = self.int(what)?;
        u64::try_from(v).map_err(|_| self.error(at, format!("expected {what}, found negative {v}")))
    }

    /// A binary 8-byte unsigned integer (C `size_t` on 64-bit machines, MSH 4.1).
    pub fn size(&mut self, what: &str) -> Result<u64, MeshError> {
        self.binary(nom::number::complete::u64(self.endian), what)
    }

    /// A binary 8-byte double that must be finite.
    pub fn double(&mut self, what: &str) -> Result<f64, MeshError> {
        let at = self.here();
        let v = self.binary(nom::number::complete::f64(self.endian), what)?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.error(at, format!("expected {what}, found {v}")))
        }
    }
}

/// The whitespace-separated fields of one line, read left to right.
pub(super) struct Fields<'a> {
    rest: &'a [u8],
    pub line: Line<'a>,
    pub location: Location,
    file: &'a Path,
}

impl<'a> Fields<'a> {
    pub fn new(line: Line<'a>, location: Location, file: &'a Path) -> Self {
        Fields {
            rest: line.text,
            line,
            location,
            file,
        }
    }

    pub fn error(&self, message: impl Into<String>) -> MeshError {
        MeshError::invalid(self.file, self.location, message)
    }

    /// The next field, if any.
    pub fn next_token(&mut self) -> Option<&'a [u8]> {
        let start = self.rest.iter().position(|b| !b.is_ascii_whitespace())?;
        let rest = &self.rest[start..];
        let len = rest
            .iter()
            .position(u8::is_ascii_whitespace)
            .unwrap_or(rest.len());
        self.rest = &rest[len..];
        Some(&rest[..len])
    }

    /// The next field; a missing one is an error naming what was expected.
    pub fn token(&mut self, what: &str) -> Result<&'a [u8], MeshError> {
        self.next_token()
            .ok_or_else(|| self.error(format!("expected {what}, found end of line")))
    }

    /// The text after the fields read so far, trimmed.
    pub fn rest(&self) -> &'a [u8] {
        self.rest.trim_ascii()
    }

    /// Number of fields not read yet.
    pub fn count_left(&self) -> usize {
        let mut probe = Fields {
            rest: self.rest,
            line: self.line,
            location: self.location,
            file: self.file,
        };
        std::iter::from_fn(|| probe.next_token()).count()
    }

    fn number<T>(&mut self, what: &str, parse: fn(&'a [u8]) -> Option<T>) -> Result<T, MeshError> {
        let token = self.token(what)?;
        parse(token).ok_or_else(|| self.error(format!("expected {what}, found `{}`", quote(token))))
    }

    /// A non-negative integer.
    pub fn u64(&mut self, what: &str) -> Result<u64, MeshError> {
        self.number(what, |t| {
            all_consuming(nom::character::complete::u64::<_, ()>)
                .parse(t)
                .ok()
                .map(|r| r.1)
        })
    }

    /// A signed 32-bit integer.
    pub fn i32(&mut self, what: &str) -> Result<i32, MeshError> {
        self.number(what, |t| {
            all_consuming(nom::character::complete::i32::<_, ()>)
                .parse(t)
                .ok()
                .map(|r| r.1)
        })
    }

    /// A finite floating-point number.
    pub fn f64(&mut self, what: &str) -> Result<f64, MeshError> {
        self.number(what, |t| {
            all_consuming(nom::number::complete::double::<_, ()>)
                .parse(t)
                .ok()
                .map(|r| r.1)
                .filter(|v| v.is_finite())
        })
    }

    /// Fails if the line has fields left.
    pub fn end(&mut self, what: &str) -> Result<(), MeshError> {
        match self.next_token() {
            None => Ok(()),
            Some(t) => Err(self.error(format!("unexpected `{}` after {what}", quote(t)))),
        }
    }
}

/// A piece of the file for an error message: lossy UTF-8, shortened.
pub(super) fn quote(bytes: &[u8]) -> String {
    let cut = &bytes[..bytes.len().min(QUOTE_MAX)];
    let mut s: String = String::from_utf8_lossy(cut)
        .chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect();
    if bytes.len() > QUOTE_MAX {
        s.push_str("...");
    }
    s
}
