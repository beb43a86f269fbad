//! The cubic fit of a compression curve (eq (8)'s k_l, k_nl) and the friction-range syntax.

use super::*;

/// `p = κ_l δ + κ_nl δ³` fitted by least squares to `(δ_i, p_i)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    pub linear: f64,
    pub cubic: f64,
    /// RMS of the pressure residual relative to the largest pressure.
    pub relative_rms: f64,
}

/// Least-squares fit of `p = a d + b d³` (2×2 normal equations).
pub fn fit_cubic(d: &[f64], p: &[f64]) -> Option<Fit> {
    let (mut s11, mut s13, mut s33, mut t1, mut t3) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (&x, &y) in d.iter().zip(p) {
        let x3 = x * x * x;
        s11 += x * x;
        s13 += x * x3;
        s33 += x3 * x3;
        t1 += x * y;
        t3 += x3 * y;
    }
    let det = s11 * s33 - s13 * s13;
    if !(det.is_finite() && det.abs() > 1e-300) {
        return None;
    }
    let a = (t1 * s33 - t3 * s13) / det;
    let b = (s11 * t3 - s13 * t1) / det;
    let pmax = p
        .iter()
        .map(|x| x.abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let rms = (d
        .iter()
        .zip(p)
        .map(|(&x, &y)| (a * x + b * x.powi(3) - y).powi(2))
        .sum::<f64>()
        / d.len() as f64)
        .sqrt();
    Some(Fit {
        linear: a,
        cubic: b,
        relative_rms: rms / pmax,
    })
}

/// `"start..end/count"` → `count` evenly spaced values from `start` to `end`, both included
/// (MATLAB's `linspace(start, end, count)`), e.g. `0..1/201`: friction coefficients, so a
/// negative start is refused.
///
/// The colon form `a:b:c` is refused with a message: it reads as `start:end:count` here but as
/// `start:step:end` in MATLAB, so `0:0.5:100` would silently sweep 0–0.5.
pub fn parse_range(s: &str) -> std::result::Result<Vec<f64>, String> {
    let example = "e.g. 0..1/201 for 201 values from 0 to 1";
    if s.contains(':') {
        return Err(format!(
            "'{s}': the colon form is ambiguous (start:end:count, or MATLAB's start:step:end); write start..end/count, {example}"
        ));
    }
    let bad = || format!("'{s}' is not start..end/count ({example})");
    let (span, count) = s.split_once('/').ok_or_else(bad)?;
    let (a, b) = span.split_once("..").ok_or_else(bad)?;
    let a: f64 = a.trim().parse().map_err(|_| bad())?;
    let b: f64 = b.trim().parse().map_err(|_| bad())?;
    let n: usize = count.trim().parse().map_err(|_| bad())?;
    if !(a.is_finite() && b.is_finite()) {
        return Err(format!("'{s}': start and end must be finite numbers"));
    }
    if b <= a {
        return Err(format!("'{s}': start must be below end"));
    }
    checks::non_negative_mus(&[a]).map_err(|e| format!("'{s}': {e}"))?;
    if !(2..=100_000).contains(&n) {
        return Err(format!("'{s}': count must be between 2 and 100000"));
    }
    Ok((0..n)
        .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
        .collect())
}
