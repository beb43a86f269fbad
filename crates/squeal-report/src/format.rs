//! Number formatting with an explicit number of significant digits, for tables and labels.
//!
//! Rounding is Rust's exact decimal rounding of the binary value (`format!("{:.*e}")`), so
//! `fmt_sig(0.125, 2)` is `"0.12"` (ties to even on the exact value) and never drifts with the
//! platform. Non-finite values print as `NaN`, `inf`, `-inf`.

/// Significant digits are clamped to this range (an `f64` carries 15-17).
const MAX_DIGITS: usize = 17;

/// `x` rounded to `digits` significant digits, as (negative, the digits, decimal exponent of
/// the first digit): `1234.5, 3 -> (false, "123", 3)`.
fn decompose(x: f64, digits: usize) -> (bool, String, i32) {
    let digits = digits.clamp(1, MAX_DIGITS);
    let s = format!("{:.*e}", digits - 1, x.abs());
    let (mantissa, exp) = s.split_once('e').unwrap_or((s.as_str(), "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let ds: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    (x.is_sign_negative() && x != 0.0, ds, exp)
}

fn non_finite(x: f64) -> Option<String> {
    if x.is_nan() {
        Some("NaN".into())
    } else if x.is_infinite() {
        Some(if x > 0.0 { "inf".into() } else { "-inf".into() })
    } else {
        None
    }
}

/// Places the decimal point in `ds` so that its first digit has weight `10^exp`.
fn place_point(ds: &str, exp: i32) -> String {
    let n = ds.len() as i32;
    if exp < 0 {
        format!("0.{}{}", "0".repeat((-exp - 1) as usize), ds)
    } else if exp + 1 >= n {
        format!("{}{}", ds, "0".repeat((exp + 1 - n) as usize))
    } else {
        let (a, b) = ds.split_at((exp + 1) as usize);
        format!("{a}.{b}")
    }
}

fn signed(negative: bool, s: String) -> String {
    if negative { format!("-{s}") } else { s }
}

/// `x` with `digits` significant digits (trailing zeros kept, they are significant): plain
/// decimal when `1e-3 <= |x| < 1e5`, else scientific. `fmt_sig(1234.5678, 3) == "1230"`,
/// `fmt_sig(2.5e-7, 2) == "2.5e-7"`.
pub fn fmt_sig(x: f64, digits: usize) -> String {
    if let Some(s) = non_finite(x) {
        return s;
    }
    if x == 0.0 {
        return place_point(&"0".repeat(digits.clamp(1, MAX_DIGITS)), 0);
    }
    let (neg, ds, exp) = decompose(x, digits);
    if (-3..5).contains(&exp) {
        signed(neg, place_point(&ds, exp))
    } else {
        fmt_sci(x, digits)
    }
}

/// Scientific notation with `digits` significant digits: `fmt_sci(-0.000123456, 3) == "-1.23e-4"`.
pub fn fmt_sci(x: f64, digits: usize) -> String {
    if let Some(s) = non_finite(x) {
        return s;
    }
    let (neg, ds, exp) = decompose(x, digits);
    signed(neg, format!("{}e{}", place_point(&ds, 0), exp))
}

/// Engineering notation (exponent a multiple of 3) with `digits` significant digits:
/// `fmt_eng(12345.0, 3) == "12.3e3"`, `fmt_eng(0.5, 2) == "500e-3"`, `fmt_eng(7.0, 2) == "7.0"`.
pub fn fmt_eng(x: f64, digits: usize) -> String {
    if let Some(s) = non_finite(x) {
        return s;
    }
    let (neg, ds, exp) = decompose(x, digits);
    let e3 = exp.div_euclid(3) * 3;
    let body = place_point(&ds, exp - e3);
    if e3 == 0 {
        signed(neg, body)
    } else {
        signed(neg, format!("{body}e{e3}"))
    }
}

/// SI prefix and unit with `digits` significant digits: `fmt_si(12345.0, 3, "Hz") == "12.3 kHz"`,
/// `fmt_si(2.5e-6, 2, "m") == "2.5 µm"`. Outside femto..tera it falls back to [`fmt_eng`].
pub fn fmt_si(x: f64, digits: usize, unit: &str) -> String {
    const PREFIXES: [&str; 10] = ["f", "p", "n", "µ", "m", "", "k", "M", "G", "T"];
    if let Some(s) = non_finite(x) {
        return format!("{s} {unit}").trim_end().to_string();
    }
    let (neg, ds, exp) = decompose(x, digits);
    let e3 = exp.div_euclid(3) * 3;
    let idx = e3 / 3 + 5;
    let text = match usize::try_from(idx).ok().and_then(|i| PREFIXES.get(i)) {
        Some(p) if x != 0.0 => format!("{} {p}{unit}", signed(neg, place_point(&ds, exp - e3))),
        _ => format!("{} {unit}", fmt_eng(x, digits)),
    };
    text.trim_end().to_string()
}

/// `x` as a percentage with `digits` significant digits: `fmt_percent(0.1234, 2) == "12%"`.
pub fn fmt_percent(x: f64, digits: usize) -> String {
    match non_finite(x) {
        Some(s) => s,
        None => format!("{}%", fmt_sig(x * 100.0, digits)),
    }
}

/// `value` with exactly `decimals` digits after the point, without a minus sign on zero.
pub fn fmt_fixed(value: f64, decimals: usize) -> String {
    if let Some(s) = non_finite(value) {
        return s;
    }
    let s = format!("{:.*}", decimals.min(MAX_DIGITS), value);
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// An integer written with Unicode superscript digits: `superscript(-3) == "⁻³"`.
pub fn superscript(n: i32) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::new();
    if n < 0 {
        s.push('⁻');
    }
    for c in n.unsigned_abs().to_string().chars() {
        let d = c.to_digit(10).unwrap_or(0) as usize;
        s.push(SUP[d]);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    // All expected strings below are worked out by hand from the decimal value; they are
    // exact, so the comparisons are exact.
    #[test]
    fn significant_digits() {
        assert_eq!(fmt_sig(1234.5678, 3), "1230");
        assert_eq!(fmt_sig(1234.5678, 6), "1234.57");
        assert_eq!(fmt_sig(0.0012345, 2), "0.0012");
        assert_eq!(fmt_sig(-1.5, 4), "-1.500");
        assert_eq!(fmt_sig(99999.0, 2), "1.0e5");
        assert_eq!(fmt_sig(2.5e-7, 2), "2.5e-7");
        assert_eq!(fmt_sig(0.0, 3), "0.00");
        assert_eq!(fmt_sig(f64::NAN, 3), "NaN");
        assert_eq!(fmt_sig(f64::NEG_INFINITY, 3), "-inf");
        assert_eq!(fmt_sig(9.96, 2), "10");
    }

    #[test]
    fn scientific_engineering_si() {
        assert_eq!(fmt_sci(-0.000123456, 3), "-1.23e-4");
        assert_eq!(fmt_sci(1.0, 1), "1e0");
        assert_eq!(fmt_eng(12345.0, 3), "12.3e3");
        assert_eq!(fmt_eng(0.5, 2), "500e-3");
        assert_eq!(fmt_eng(7.0, 2), "7.0");
        assert_eq!(fmt_eng(-123456.0, 2), "-120e3");
        assert_eq!(fmt_si(12345.0, 3, "Hz"), "12.3 kHz");
        assert_eq!(fmt_si(2.5e-6, 2, "m"), "2.5 µm");
        assert_eq!(fmt_si(999.96, 4, "Hz"), "1.000 kHz");
        assert_eq!(fmt_si(3.0e20, 2, "N"), "300e18 N");
        assert_eq!(fmt_percent(0.1234, 2), "12%");
        assert_eq!(fmt_fixed(-0.0001, 2), "0.00");
        assert_eq!(superscript(-12), "⁻¹²");
    }
}
