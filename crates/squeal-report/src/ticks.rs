//! Axis ticks: "nice" linear steps (1, 2, 2.5, 5 x 10^k) with a shared engineering multiplier
//! (x10³, x10⁻⁶) when numbers would otherwise be long, and decades on log axes.
//!
//! All positions are in the axis' plotting space: the value itself on linear axes, its base-10
//! logarithm on log axes.

use crate::format::{fmt_fixed, superscript};

/// One labelled tick.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Tick {
    pub pos: f64,
    pub label: String,
}

/// Ticks of one axis.
#[derive(Clone, Debug, PartialEq, Default)]
pub(crate) struct AxisTicks {
    pub major: Vec<Tick>,
    /// Unlabelled positions (short tick marks; light grid lines on log axes).
    pub minor: Vec<f64>,
    /// Shared factor of the tick labels, e.g. `"×10³"`, to append to the axis label.
    pub multiplier: Option<String>,
}

/// Largest number of ticks any axis generates (keeps drawing bounded whatever the range).
const MAX_TICKS: f64 = 200.0;

/// The smallest step of the form {1, 2, 2.5, 5} x 10^k that is at least `raw`.
pub(crate) fn nice_step(raw: f64) -> f64 {
    let mag = 10f64.powf(raw.log10().floor());
    for m in [1.0, 2.0, 2.5, 5.0] {
        if m * mag >= raw * (1.0 - 1e-9) {
            return m * mag;
        }
    }
    10.0 * mag
}

/// Number of decimals needed to print multiples of `step` exactly (at most 12).
fn decimals_for(step: f64) -> usize {
    (0..=12)
        .find(|&d| {
            let s = step * 10f64.powi(d as i32);
            (s - s.round()).abs() <= 1e-6 * s.abs().max(1.0)
        })
        .unwrap_or(12)
}

/// Linear ticks on `[lo, hi]` with at most about `max_count` labelled ticks.
pub(crate) fn linear_ticks(lo: f64, hi: f64, max_count: usize) -> AxisTicks {
    let span = hi - lo;
    if !span.is_finite() || span <= 0.0 {
        return AxisTicks::default();
    }
    let step = nice_step(span / max_count.max(1) as f64);
    let first = (lo / step - 1e-9).ceil();
    let last = (hi / step + 1e-9).floor();
    if !(last - first).is_finite() || last - first >= MAX_TICKS {
        return AxisTicks::default();
    }
    let m = lo.abs().max(hi.abs());
    let e = if m >= 1e4 || (m < 1e-2 && m > 0.0) {
        (m.log10() / 3.0).floor() as i32 * 3
    } else {
        0
    };
    let scale = 10f64.powi(e);
    let decimals = decimals_for(step / scale);
    let mut major = Vec::new();
    let mut i = first;
    while i <= last {
        let v = i * step;
        let v = if v.abs() < step * 1e-9 { 0.0 } else { v };
        major.push(Tick {
            pos: v,
            label: fmt_fixed(v / scale, decimals),
        });
        i += 1.0;
    }
    let minor_div = if (step / 10f64.powf(step.log10().floor()) - 2.0).abs() < 1e-9 {
        4.0
    } else {
        5.0
    };
    let minor_step = step / minor_div;
    let mut minor = Vec::new();
    let mut j = (lo / minor_step - 1e-9).ceil();
    while j * minor_step <= hi + minor_step * 1e-9 && (minor.len() as f64) < MAX_TICKS * 5.0 {
        let r = j / minor_div;
        if (r - r.round()).abs() > 1e-9 {
            minor.push(j * minor_step);
        }
        j += 1.0;
    }
    let multiplier = (e != 0).then(|| format!("×10{}", superscript(e)));
    AxisTicks {
        major,
        minor,
        multiplier,
    }
}

/// A log tick as (mantissa 1..9, decade): `mantissa x 10^decade`.
type LogTick = (u32, i32);

/// Label of `mantissa x 10^decade` on a log axis: plain (`0.01`, `200`) or as a power (`10⁻⁶`,
/// `2×10⁻⁶`).
fn log_label(mantissa: u32, decade: i32, plain: bool) -> String {
    if plain {
        let ds = mantissa.to_string();
        let n = decade;
        if n < 0 {
            format!("0.{}{}", "0".repeat((-n - 1) as usize), ds)
        } else {
            format!("{}{}", ds, "0".repeat(n as usize))
        }
    } else if mantissa == 1 {
        format!("10{}", superscript(decade))
    } else {
        format!("{mantissa}×10{}", superscript(decade))
    }
}

/// Log ticks on `[lo, hi]` (decades, i.e. log10 of the values): every decade (or every k-th
/// when there are many) labelled, with 2..9 as minor ticks; with fewer than three decade ticks,
/// 1-2-5 or 1..9 mantissas are labelled instead.
pub(crate) fn log_ticks(lo: f64, hi: f64, max_count: usize) -> AxisTicks {
    if !lo.is_finite() || !hi.is_finite() || hi <= lo {
        return AxisTicks::default();
    }
    let (lo, hi) = (lo.max(-330.0), hi.min(330.0));
    let eps = 1e-9;
    let d0 = lo.floor() as i32;
    let d1 = hi.floor() as i32;
    let inside = |v: f64| v >= lo - eps && v <= hi + eps;
    let candidates = |mantissas: &[u32]| -> Vec<LogTick> {
        let mut out = Vec::new();
        for d in d0..=d1 {
            for &m in mantissas {
                if inside(f64::from(m).log10() + f64::from(d)) {
                    out.push((m, d));
                }
            }
        }
        out
    };
    let decades = candidates(&[1]);
    let max_count = max_count.max(2);
    let (labelled, unlabelled): (Vec<LogTick>, Vec<LogTick>) = if decades.len() >= 3 {
        let k = decades.len().div_ceil(max_count) as i32;
        let (lab, rest): (Vec<_>, Vec<_>) = decades.iter().partition(|(_, d)| d.rem_euclid(k) == 0);
        let minor = if k == 1 {
            candidates(&[2, 3, 4, 5, 6, 7, 8, 9])
        } else {
            rest
        };
        (lab, minor)
    } else {
        let one_two_five = candidates(&[1, 2, 5]);
        let lab = if one_two_five.len() >= 3
            || candidates(&[1, 2, 3, 4, 5, 6, 7, 8, 9]).len() > max_count
        {
            one_two_five
        } else {
            candidates(&[1, 2, 3, 4, 5, 6, 7, 8, 9])
        };
        let minor = candidates(&[1, 2, 3, 4, 5, 6, 7, 8, 9])
            .into_iter()
            .filter(|c| !lab.contains(c))
            .collect();
        (lab, minor)
    };
    let plain = labelled.iter().all(|&(_, d)| (-3..5).contains(&d));
    let pos = |(m, d): LogTick| f64::from(m).log10() + f64::from(d);
    AxisTicks {
        major: labelled
            .iter()
            .map(|&c| Tick {
                pos: pos(c),
                label: log_label(c.0, c.1, plain),
            })
            .collect(),
        minor: unlabelled.into_iter().map(pos).collect(),
        multiplier: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(t: &AxisTicks) -> Vec<&str> {
        t.major.iter().map(|t| t.label.as_str()).collect()
    }

    // Expected tick sets are written out by hand from the 1-2-2.5-5 rule; exact comparisons.
    #[test]
    fn linear_kilohertz_axis_uses_shared_multiplier() {
        let t = linear_ticks(0.0, 20000.0, 6);
        assert_eq!(labels(&t), ["0", "5", "10", "15", "20"]);
        assert_eq!(t.multiplier.as_deref(), Some("×10³"));
    }

    #[test]
    fn linear_small_numbers() {
        let t = linear_ticks(-0.3, 0.6, 8);
        assert_eq!(labels(&t), ["-0.2", "0.0", "0.2", "0.4", "0.6"]);
        assert_eq!(t.multiplier, None);
        // 3.1e-6 / 6 = 5.2e-7 > 5e-7, so the step is 1e-6; with room for 8 it is 5e-7.
        let t = linear_ticks(0.0, 3.1e-6, 6);
        assert_eq!(labels(&t), ["0", "1", "2", "3"]);
        assert_eq!(t.multiplier.as_deref(), Some("×10⁻⁶"));
        let t = linear_ticks(0.0, 3.1e-6, 8);
        assert_eq!(
            labels(&t),
            ["0.0", "0.5", "1.0", "1.5", "2.0", "2.5", "3.0"]
        );
    }

    #[test]
    fn log_decades() {
        let t = log_ticks(-8.2, -1.9, 10);
        assert_eq!(
            labels(&t),
            ["10⁻⁸", "10⁻⁷", "10⁻⁶", "10⁻⁵", "10⁻⁴", "10⁻³", "10⁻²"]
        );
        // 2..9 in the six full decades 1e-8..1e-3 (48), plus 7e-9, 8e-9, 9e-9 above
        // 10^-8.2 = 6.3e-9; none of 2e-2.. lies below 10^-1.9 = 0.0126.
        assert_eq!(t.minor.len(), 6 * 8 + 3);
        let t = log_ticks(0.0, 3.0, 10);
        assert_eq!(labels(&t), ["1", "10", "100", "1000"]);
        // 20 decades with room for 6 labels: every 4th decade.
        let t = log_ticks(-10.0, 10.0, 6);
        assert_eq!(labels(&t), ["10⁻⁸", "10⁻⁴", "10⁰", "10⁴", "10⁸"]);
    }

    #[test]
    fn log_within_one_decade() {
        let t = log_ticks(200f64.log10(), 900f64.log10(), 8);
        assert_eq!(
            labels(&t),
            ["200", "300", "400", "500", "600", "700", "800", "900"]
        );
        let t = log_ticks(0.5f64.log10(), 30f64.log10(), 8);
        assert_eq!(labels(&t), ["0.5", "1", "2", "5", "10", "20"]);
    }
}
