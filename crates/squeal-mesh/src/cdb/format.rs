//! The Fortran format lines of a `.cdb` block (`(3i9,6e21.13e3)`, `(19i9)`, `(8i10)`) and
//! the fixed-width fields they describe.

/// The kind of a field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Int,
    Real,
}

/// The fields of one line, in order: kind and width in characters.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Format {
    pub fields: Vec<(Kind, usize)>,
}

/// Most fields one format line may describe (CDWRITE writes at most 19).
const MAX_FIELDS: usize = 64;
/// Widest field read (CDWRITE writes at most 21 characters).
const MAX_WIDTH: usize = 64;

impl Format {
    /// Parses `(3i9,6e21.13e3)`: groups `[count]letter width[.digits[e exponent digits]]`,
    /// letters `i` (integer) and `e`, `f`, `g`, `d` (real), any case.
    pub fn parse(line: &str) -> Result<Format, String> {
        let bad = || {
            format!(
                "expected a Fortran format line such as (3i9,6e21.13e3), found '{}'",
                line.chars().take(40).collect::<String>()
            )
        };
        let inner = line
            .trim()
            .strip_prefix('(')
            .and_then(|s| s.strip_suffix(')'))
            .ok_or_else(bad)?;
        let mut fields = Vec::new();
        for group in inner.split(',') {
            let g = group.trim().to_ascii_lowercase();
            let digits = g.bytes().take_while(u8::is_ascii_digit).count();
            let count: usize = if digits == 0 {
                1
            } else {
                g[..digits].parse().map_err(|_| bad())?
            };
            let rest = &g[digits..];
            let kind = match rest.as_bytes().first() {
                Some(b'i') => Kind::Int,
                Some(b'e' | b'f' | b'g' | b'd') => Kind::Real,
                _ => return Err(bad()),
            };
            let w = rest[1..].bytes().take_while(u8::is_ascii_digit).count();
            let width: usize = rest[1..1 + w].parse().map_err(|_| bad())?;
            let tail = &rest[1 + w..];
            let tail_ok = tail.is_empty()
                || (tail.starts_with('.')
                    && tail[1..]
                        .split('e')
                        .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()))
                    && tail[1..].split('e').count() <= 2);
            if width == 0 || width > MAX_WIDTH || !tail_ok {
                return Err(bad());
            }
            if fields.len() + count > MAX_FIELDS {
                return Err(format!(
                    "the format line {} describes more than {MAX_FIELDS} fields",
                    line.trim()
                ));
            }
            fields.extend(std::iter::repeat_n((kind, width), count));
        }
        if fields.is_empty() {
            return Err(bad());
        }
        Ok(Format { fields })
    }

    /// Number of leading integer fields.
    pub fn ints(&self) -> usize {
        self.fields.iter().take_while(|f| f.0 == Kind::Int).count()
    }

    /// The text of each field of `line` (trimmed; `None` past the line's end, as CDWRITE
    /// leaves trailing zero coordinates out). An error if a field boundary splits a character.
    pub fn split<'l>(&self, line: &'l str) -> Result<Vec<Option<&'l str>>, String> {
        let mut out = Vec::with_capacity(self.fields.len());
        let mut at = 0;
        for &(_, w) in &self.fields {
            if at >= line.len() {
                out.push(None);
                continue;
            }
            let end = (at + w).min(line.len());
            let s = line
                .get(at..end)
                .ok_or("a non-ASCII character inside a fixed-width field")?;
            out.push(Some(s.trim()).filter(|s| !s.is_empty()));
            at = end;
        }
        if at < line.trim_end().len() {
            return Err(format!(
                "the line is longer than its format ({} characters) allows: '{}'",
                at,
                line.chars().take(40).collect::<String>()
            ));
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_of_cdwrite() {
        let f = Format::parse("(3i9,6e21.13e3)").unwrap();
        assert_eq!(f.fields.len(), 9);
        assert_eq!(f.ints(), 3);
        assert_eq!(f.fields[3], (Kind::Real, 21));
        assert_eq!(Format::parse("(19i9)").unwrap().fields.len(), 19);
        assert_eq!(
            Format::parse("(8I10)").unwrap().fields,
            vec![(Kind::Int, 10); 8]
        );
        assert_eq!(Format::parse("(1i9,3e20.9e3)").unwrap().ints(), 1);
        assert!(Format::parse("3i9").is_err());
        assert!(Format::parse("(3x9)").is_err());
        assert!(Format::parse("(99999i9)").is_err());
        assert!(Format::parse("(i0)").is_err());
        let line = "        1        0        0 1.0000000000000E+00";
        let v = f.split(line).unwrap();
        assert_eq!(v[0], Some("1"));
        assert_eq!(v[3], Some("1.0000000000000E+00"));
        assert_eq!(v[4], None);
        assert!(f.split(&"1".repeat(200)).is_err());
    }
}
