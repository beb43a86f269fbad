//! Numbers in bulk data fields: integers and reals, with Nastran's implied exponent.

/// A real number: `1.5`, `1.`, `.5`, `-2.5E-3`, `1.0D+05`, and Nastran's implied exponent
/// `1.-3` (= 1.0E-3), `2.1+11`, `-.5-2`. An integer (`3`) is read as a real too (Nastran
/// refuses it in a real field; every writer squeal knows puts the point). `None` for anything
/// else, and for infinities and NaN.
pub(crate) fn real(s: &str) -> Option<f64> {
    let s = s.trim();
    if s.is_empty()
        || !s.bytes().all(|b| {
            b.is_ascii_digit() || matches!(b, b'.' | b'+' | b'-' | b'e' | b'E' | b'd' | b'D')
        })
    {
        return None;
    }
    let mut t = s.replace(['d', 'D'], "E");
    // An implied exponent: a sign after the first character not preceded by E.
    if let Some(i) = t.bytes().enumerate().skip(1).find_map(|(i, b)| {
        (matches!(b, b'+' | b'-') && !matches!(t.as_bytes()[i - 1], b'E' | b'e')).then_some(i)
    }) {
        t.insert(i, 'E');
    }
    let v: f64 = t.parse().ok()?;
    v.is_finite().then_some(v)
}

/// A real field where blank means `default`.
pub(crate) fn real_or(s: &str, default: f64) -> Option<f64> {
    if s.trim().is_empty() {
        Some(default)
    } else {
        real(s)
    }
}

/// An integer: optional sign and decimal digits.
pub(crate) fn int(s: &str) -> Option<i64> {
    let s = s.trim();
    let digits = s.strip_prefix(['+', '-']).unwrap_or(s);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    s.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nastran_reals() {
        assert_eq!(real("1.-3"), Some(1.0e-3));
        assert_eq!(real("2.1+11"), Some(2.1e11));
        assert_eq!(real("-.5-2"), Some(-0.5e-2));
        assert_eq!(real("+1.5"), Some(1.5));
        assert_eq!(real("7.85E-9"), Some(7.85e-9));
        assert_eq!(real("7.85e+3"), Some(7.85e3));
        assert_eq!(real("1.0D+05"), Some(1.0e5));
        assert_eq!(real("1."), Some(1.0));
        assert_eq!(real("3"), Some(3.0));
        assert_eq!(real("0.01231920804111597"), Some(0.01231920804111597));
        for bad in [
            "", "nan", "inf", "1.2.3", "1.0E", "1e999", "+", "-", ".", "1.0-", "1,0",
        ] {
            assert_eq!(real(bad), None, "{bad}");
        }
        assert_eq!(real_or(" ", 0.0), Some(0.0));
        assert_eq!(int("12"), Some(12));
        assert_eq!(int("-1"), Some(-1));
        assert_eq!(int("1.0"), None);
        assert_eq!(int("THRU"), None);
        assert_eq!(int("99999999999999999999"), None);
    }
}
