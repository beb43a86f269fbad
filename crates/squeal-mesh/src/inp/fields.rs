//! Fields of a data line and the numbers in them (parsed with nom).

use nom::Parser;
use nom::combinator::all_consuming;
use nom::number::complete::double;

/// The comma-separated fields of a (trimmed) data line, each trimmed. One trailing comma is
/// ignored (`1, 2,` has two fields); an empty line has none.
pub(super) fn fields(line: &str) -> impl Iterator<Item = &str> {
    let body = line.strip_suffix(',').unwrap_or(line);
    let n = if body.trim().is_empty() {
        0
    } else {
        usize::MAX
    };
    body.split(',').map(str::trim).take(n)
}

/// A label (node or element id): a non-negative decimal integer.
pub(super) fn label(s: &str) -> Option<u64> {
    all_consuming(nom::character::complete::u64::<&str, nom::error::Error<&str>>)
        .parse(s)
        .ok()
        .map(|(_, v)| v)
}

/// A finite real number: `1`, `1.`, `.5`, `-2.5e-3`, and the Fortran exponent `1.0D+05`.
pub(super) fn real(s: &str) -> Option<f64> {
    let parse = |t: &str| {
        all_consuming(double::<&str, nom::error::Error<&str>>)
            .parse(t)
            .ok()
            .map(|(_, v)| v)
    };
    let v = match parse(s) {
        Some(v) => v,
        None if s.contains(['d', 'D']) => parse(&s.replace(['d', 'D'], "e"))?,
        None => return None,
    };
    v.is_finite().then_some(v)
}

/// A real field where an empty field means zero (Abaqus: "blank fields are zero").
pub(super) fn real_or_zero(s: &str) -> Option<f64> {
    if s.is_empty() { Some(0.0) } else { real(s) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_ignore_one_trailing_comma() {
        assert_eq!(fields("1, 2 ,3,").collect::<Vec<_>>(), ["1", "2", "3"]);
        assert_eq!(fields("1,,3").collect::<Vec<_>>(), ["1", "", "3"]);
        assert_eq!(fields(",").count(), 0);
        assert_eq!(fields("").count(), 0);
    }

    #[test]
    fn numbers_in_abaqus_spellings() {
        assert_eq!(real("210000."), Some(210000.0));
        assert_eq!(real(".3"), Some(0.3));
        assert_eq!(real("7.8E-9"), Some(7.8e-9));
        assert_eq!(real("-1.5d+02"), Some(-150.0));
        assert_eq!(real("nan"), None);
        assert_eq!(real("1e999"), None);
        assert_eq!(real("1.2.3"), None);
        assert_eq!(real(""), None);
        assert_eq!(real_or_zero(""), Some(0.0));
        assert_eq!(label("123"), Some(123));
        assert_eq!(label("-1"), None);
        assert_eq!(label("1.0"), None);
        assert_eq!(label("99999999999999999999"), None);
    }
}
