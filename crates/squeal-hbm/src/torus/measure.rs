//! What is measured on a quasi-periodic signal, the same way on a time series (a time
//! integration) and on a torus solution's signal along its flow: the amplitude envelope and
//! the frequencies of spectral peaks.
//!
//! **Envelope.**
//! A quasi-periodic signal `s(t) = S(ω1 t, ω2 t)` swings over one fast period `T1 = 2π/ω1` by
//! `A(t) = max - min of s over [t, t + T1]`, which varies with the slow phase: the envelope is
//! the range `[min_t A, max_t A]` of these peak-to-peak swings over every window start `t` (a
//! sliding window, so that the measure does not depend on where the record starts), together
//! with the signal's overall extremes. On a long enough record of a quasi-periodic signal
//! (irrational `ω2/ω1`) both tend to their values over the whole torus.

/// Extremes and per-period swings of a sampled signal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Envelope {
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Smallest peak-to-peak swing over one fast period.
    pub swing_min: f64,
    /// Largest peak-to-peak swing over one fast period.
    pub swing_max: f64,
}

/// The envelope of `s` sampled every `dt` with the fast period `period`; `None` when the record
/// is shorter than two periods or the period is below two samples.
pub fn envelope(s: &[f64], dt: f64, period: f64) -> Option<Envelope> {
    let w = (period / dt).round() as usize;
    if w < 2 || s.len() < 2 * w {
        return None;
    }
    let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
    for &v in s {
        min = min.min(v);
        max = max.max(v);
    }
    let (mut swing_min, mut swing_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for start in 0..=s.len() - w {
        let win = &s[start..start + w];
        let hi = win.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let lo = win.iter().copied().fold(f64::INFINITY, f64::min);
        swing_min = swing_min.min(hi - lo);
        swing_max = swing_max.max(hi - lo);
    }
    Some(Envelope {
        min,
        max,
        swing_min,
        swing_max,
    })
}

/// The frequency (rad/s) of the largest spectral peak of `s` (sampled every `dt`) within
/// `guess ± half_width`: the maximum of the windowed discrete-time Fourier transform
/// `|Σ_j w_j (s_j - s̄) e^{-iωjdt}|` with the squared Hann window `w = sin⁴(πj/(n-1))`,
/// scanned at an eighth of the record's resolution `2π/T`, then refined by golden-section
/// search to `1e-12 ω`. The squared Hann window's sidelobes fall like the fifth power of the
/// distance (the plain Hann window's like the third: on the brake's torus, whose carrier is 30
/// resolutions from the sideband `ω1 + ω2` and far stronger, the plain window's leakage moved
/// the sideband by 3e-5 of `ω2`), so a tone a few resolutions from the others (at least four:
/// the main lobe is twice the Hann window's) is located to far better than the resolution.
/// `None` for fewer than 16 samples or a non-positive width.
pub fn peak_frequency(s: &[f64], dt: f64, guess: f64, half_width: f64) -> Option<f64> {
    let n = s.len();
    if n < 16 || !(half_width > 0.0 && dt > 0.0) {
        return None;
    }
    let mean = s.iter().sum::<f64>() / n as f64;
    let w: Vec<f64> = s
        .iter()
        .enumerate()
        .map(|(j, v)| {
            let h = 0.5 - 0.5 * (2.0 * std::f64::consts::PI * j as f64 / (n - 1) as f64).cos();
            h * h * (v - mean)
        })
        .collect();
    let power = |omega: f64| {
        let (st, ct) = (omega * dt).sin_cos();
        let (mut re, mut im) = (0.0, 0.0);
        let (mut c, mut sn) = (1.0f64, 0.0f64);
        for (j, v) in w.iter().enumerate() {
            re += v * c;
            im -= v * sn;
            (c, sn) = (c * ct - sn * st, sn * ct + c * st);
            if j % 4096 == 4095 {
                // Exact restart: the rotation's round-off does not accumulate.
                let (a, b) = (omega * dt * (j + 1) as f64).sin_cos();
                (c, sn) = (b, a);
            }
        }
        re * re + im * im
    };
    let step = 2.0 * std::f64::consts::PI / (n as f64 * dt) / 8.0;
    let count = (2.0 * half_width / step).ceil() as usize;
    let (mut best, mut best_p) = (guess, f64::NEG_INFINITY);
    for i in 0..=count {
        let om = guess - half_width + i as f64 * step;
        let p = power(om);
        if p > best_p {
            (best, best_p) = (om, p);
        }
    }
    let (mut a, mut b) = (best - step, best + step);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
    let (mut p1, mut p2) = (power(x1), power(x2));
    while b - a > 1e-12 * best.abs().max(step) {
        if p1 > p2 {
            (b, x2, p2) = (x2, x1, p1);
            x1 = b - g * (b - a);
            p1 = power(x1);
        } else {
            (a, x1, p1) = (x1, x2, p2);
            x2 = a + g * (b - a);
            p2 = power(x2);
        }
    }
    Some(0.5 * (a + b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn beating_signal() {
        // (1 + 0.2 cos(Ω t)) cos(t): swings from 2 × 0.8 to 2 × 1.2. Sampled at 2π/400 over
        // 300 periods, the window's extremes miss the true ones by at most the modulation's
        // drift over one period plus the sampling error, 0.2 × 2π (Ω/1) ≈ 0.08 here at worst;
        // the values seen are within 2 %.
        let dt = 2.0 * std::f64::consts::PI / 400.0;
        let omega = 0.0731;
        let s: Vec<f64> = (0..400 * 300)
            .map(|j| {
                let t = j as f64 * dt;
                (1.0 + 0.2 * (omega * t).cos()) * t.cos()
            })
            .collect();
        let e = envelope(&s, dt, 2.0 * std::f64::consts::PI).unwrap();
        assert!((e.max - 1.2).abs() < 1e-3, "{}", e.max);
        assert!((e.swing_max - 2.4).abs() < 0.05, "{}", e.swing_max);
        assert!((e.swing_min - 1.6).abs() < 0.05, "{}", e.swing_min);
        assert!(envelope(&s[..500], dt, 2.0 * std::f64::consts::PI).is_none());
        // The carrier at 1 and the sidebands 1 ± Ω, 11 resolutions away: the carrier's peak
        // is found within 1e-7 (leakage of the sidebands through the Hann sidelobes).
        let f = peak_frequency(&s, dt, 1.001, 0.01).unwrap();
        assert!((f - 1.0).abs() < 1e-7, "{f}");
    }
}
