//! The generalized CHBM's reference: time integration of the whole brake (every mode of
//! [`ModalBrake`], the variable-step BDF of [`squeal_ode`] as in [`crate::timeint`]) from the
//! static solution perturbed along *every* unstable mode, and the spectrum of what it settles
//! on.
//!
//! **Start.** `x = x_eq + Σ_j ε_j Re ψ_j`, `x' = Σ_j ε_j Re(λ_j ψ_j)`, each `ε_j` the
//! [`TiStart::from_mode`] amplitude of mode `j` alone (its most moving pair's normal amplitude
//! is [`MultiRunOptions::perturbation`] times the smallest static penetration).
//!
//! **Record.** After [`MultiRunOptions::transient`] seconds, the normal penetration of every
//! pair is sampled at a fixed rate (the BDF's dense output) for [`MultiRunOptions::record`]
//! seconds, cut into [`MultiRunOptions::windows`] equal windows. Each window's spectrum is a
//! Hann-windowed DFT (`rustfft`); its peaks (local maxima above [`MultiRunOptions::floor`]
//! of the largest) are refined by maximizing the windowed discrete-time Fourier transform
//! `|Σ w_n s_n e^{-2πi f t_n}|` over `f` within a bin (golden section to `1e-9` of a bin), and
//! the amplitude of a sinusoid is `2 |S(f)| / Σ w_n`. For an isolated stationary sinusoid this
//! estimate is exact up to the other peaks' leakage (the Hann window's side lobes fall as
//! `1/Δf³`). Comparing the windows says whether a component is steady, grows or dies out.
//! The envelope of a window is the smallest and largest of the signal's local maxima
//! (deviation from the window's mean; each maximum refined by a parabola through three samples).

use crate::solve::ChbmStart;
use crate::timeint::{TiError, TiStart};
use rustfft::FftPlanner;
use rustfft::num_complex::Complex;
use squeal_brake::dynamics::BrakeDynamics;
use squeal_brake::modal_brake::ModalBrake;
use squeal_ode::{Atol, Bdf, BdfOptions, BdfStats, OdeError};
use std::f64::consts::PI;
use std::time::{Duration, Instant};

/// Options of [`integrate_modes`].
#[derive(Clone, Debug, PartialEq)]
pub struct MultiRunOptions {
    /// Relative tolerance of the BDF error test.
    pub rtol: f64,
    /// Highest BDF order.
    pub max_order: usize,
    /// Initial normal amplitude of each mode's most moving pair, as a fraction of the smallest
    /// static penetration.
    pub perturbation: f64,
    /// Time integrated before the record (s).
    pub transient: f64,
    /// Length of the record (s).
    pub record: f64,
    /// Samples per period of the fastest unstable mode.
    pub samples_per_period: usize,
    /// Windows the record is cut into.
    pub windows: usize,
    /// Peaks below this fraction of a window's largest are not reported.
    pub floor: f64,
    /// Give up after this many accepted steps.
    pub max_steps: usize,
}

impl Default for MultiRunOptions {
    fn default() -> Self {
        Self {
            rtol: 1e-6,
            max_order: 2,
            perturbation: 0.05,
            transient: 0.5,
            record: 0.5,
            samples_per_period: 16,
            windows: 4,
            floor: 1e-3,
            max_steps: 50_000_000,
        }
    }
}

/// One spectral peak.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Peak {
    /// Frequency (Hz).
    pub frequency: f64,
    /// Amplitude of the sinusoid (m).
    pub amplitude: f64,
}

/// One window of the record, for one pair.
#[derive(Clone, Debug, PartialEq)]
pub struct Window {
    /// Start and end time (s).
    pub from: f64,
    /// See `from`.
    pub to: f64,
    /// Peaks, largest first.
    pub peaks: Vec<Peak>,
    /// Smallest and largest local maximum of the deviation from the mean (m).
    pub envelope: (f64, f64),
}

/// The run and its spectra.
#[derive(Clone, Debug)]
pub struct MultiRun {
    /// Initial amplitude factors `ε_j`.
    pub epsilons: Vec<f64>,
    /// Sampling rate (Hz).
    pub rate: f64,
    /// The pair whose record moved most (largest standard deviation over the record).
    pub pair: usize,
    /// That pair's windows.
    pub windows: Vec<Window>,
    /// Every pair's windows (pair order).
    pub pairs: Vec<Vec<Window>>,
    /// Why the run stopped early, if it did.
    pub failure: Option<OdeError>,
    /// The integrator's counters.
    pub stats: BdfStats,
    /// Wall time.
    pub wall: Duration,
}

/// Integrates the brake from its equilibrium perturbed along every mode of `starts` (module
/// docs) and analyses the record.
pub fn integrate_modes(
    mb: &ModalBrake,
    starts: &[ChbmStart],
    opts: &MultiRunOptions,
) -> Result<MultiRun, TiError> {
    let t0 = Instant::now();
    let n = mb.modes();
    let first = starts.first().ok_or(TiError::NoContactMotion)?;
    let mut x = first.equilibrium.clone();
    let mut v = vec![0.0; n];
    let mut epsilons = Vec::new();
    for s in starts {
        let ti = TiStart::from_mode(mb, s.lambda, &s.mode, &s.equilibrium, opts.perturbation)?;
        let e = ti.epsilon();
        for i in 0..n {
            x[i] += e * s.mode[i].re;
            v[i] += e * (s.lambda * s.mode[i]).re;
        }
        epsilons.push(e);
    }
    let y0 = BrakeDynamics::state_from_physical(mb, &x, &v).ok_or(TiError::SingularModes)?;
    // Tolerance scale: the largest modal coordinate of the perturbation, over the
    // perturbation factor (the size of a motion of one static penetration).
    let mut dx = x.clone();
    for (d, e) in dx.iter_mut().zip(&first.equilibrium) {
        *d -= e;
    }
    let qd =
        BrakeDynamics::state_from_physical(mb, &dx, &vec![0.0; n]).ok_or(TiError::SingularModes)?;
    let q_scale = qd[..n].iter().fold(0.0f64, |a, b| a.max(b.abs())) / opts.perturbation;
    let w_max = starts.iter().map(|s| s.lambda.im.abs()).fold(0.0, f64::max);
    let atol: Vec<f64> = (0..2 * n)
        .map(|i| opts.rtol * q_scale * if i < n { 1.0 } else { w_max })
        .collect();
    let bdf_opts = {
        let mut o = BdfOptions::default();
        o.rtol = opts.rtol;
        o.atol = Atol::PerComponent(atol);
        o.max_order = opts.max_order;
        o.max_steps = opts.max_steps;
        o
    };
    let t_end = opts.transient + opts.record;
    let sys = BrakeDynamics::new(mb);
    let mut bdf = Bdf::new(&sys, 0.0, &y0, t_end, &bdf_opts)?;
    // Rows w_p with w_p · q = g_p · x_n.
    let rows: Vec<Vec<f64>> = mb
        .pairs
        .iter()
        .map(|p| {
            (0..n)
                .map(|j| p.normal.iter().map(|&(i, g)| g * mb.phi_n[(i, j)]).sum())
                .collect()
        })
        .collect();
    let rate = opts.samples_per_period as f64 * w_max / (2.0 * PI);
    let count = (opts.record * rate).floor() as usize;
    let mut records: Vec<Vec<f64>> = vec![Vec::with_capacity(count); rows.len()];
    let mut y = vec![0.0; 2 * n];
    let mut next = 0usize;
    let mut failure = None;
    while next < count {
        if let Err(e) = bdf.step() {
            failure = Some(e);
            break;
        }
        while next < count {
            let t = opts.transient + next as f64 / rate;
            if t > bdf.t() {
                break;
            }
            if let Err(e) = bdf.interpolate(t.max(bdf.t_prev()), &mut y) {
                failure = Some(e);
                break;
            }
            for (r, w) in records.iter_mut().zip(&rows) {
                r.push((0..n).map(|j| w[j] * y[j]).sum());
            }
            next += 1;
        }
        if failure.is_some() || bdf.is_finished() {
            break;
        }
    }
    let spread = |r: &[f64]| {
        let m = r.iter().sum::<f64>() / r.len().max(1) as f64;
        r.iter().map(|v| (v - m) * (v - m)).sum::<f64>()
    };
    let pair = (0..records.len())
        .max_by(|&a, &b| spread(&records[a]).total_cmp(&spread(&records[b])))
        .unwrap_or(0);
    let pairs: Vec<Vec<Window>> = records
        .iter()
        .map(|rec| windows_of(rec, rate, opts))
        .collect();
    let windows = pairs.get(pair).cloned().unwrap_or_default();
    Ok(MultiRun {
        epsilons,
        rate,
        pair,
        windows,
        pairs,
        failure,
        stats: *bdf.stats(),
        wall: t0.elapsed(),
    })
}

/// The windows of one pair's record.
fn windows_of(rec: &[f64], rate: f64, opts: &MultiRunOptions) -> Vec<Window> {
    let per = rec.len() / opts.windows.max(1);
    (0..opts.windows.max(1))
        .filter(|_| per >= 8)
        .map(|k| {
            let s = &rec[k * per..(k + 1) * per];
            let from = opts.transient + (k * per) as f64 / rate;
            Window {
                from,
                to: from + per as f64 / rate,
                peaks: peaks(s, rate, opts.floor),
                envelope: envelope(s),
            }
        })
        .collect()
}

/// Peaks refined per window: the largest bins only (each refinement costs about 60
/// evaluations of the transform).
const MAX_PEAKS: usize = 12;

/// `|Σ w_n (s_n - mean) e^{-2πi f n / rate}|` with the Hann window `w`.
fn dtft(s: &[f64], mean: f64, rate: f64, f: f64) -> f64 {
    let len = s.len();
    let (mut re, mut im) = (0.0, 0.0);
    let step = 2.0 * PI * f / rate;
    for (k, v) in s.iter().enumerate() {
        let w = 0.5 - 0.5 * (2.0 * PI * k as f64 / len as f64).cos();
        let a = step * k as f64;
        re += w * (v - mean) * a.cos();
        im -= w * (v - mean) * a.sin();
    }
    re.hypot(im)
}

/// The peaks of a record sampled at `rate` (module docs), largest first (at most the
/// twelve largest).
pub fn peaks(s: &[f64], rate: f64, floor: f64) -> Vec<Peak> {
    let len = s.len();
    if len < 8 {
        return Vec::new();
    }
    let mean = s.iter().sum::<f64>() / len as f64;
    let mut buf: Vec<Complex<f64>> = s
        .iter()
        .enumerate()
        .map(|(k, v)| {
            let w = 0.5 - 0.5 * (2.0 * PI * k as f64 / len as f64).cos();
            Complex::new(w * (v - mean), 0.0)
        })
        .collect();
    FftPlanner::new().plan_fft_forward(len).process(&mut buf);
    let mag: Vec<f64> = buf[..len / 2].iter().map(|c| c.norm()).collect();
    let top = mag.iter().copied().fold(0.0, f64::max);
    let wsum: f64 = (0..len)
        .map(|k| 0.5 - 0.5 * (2.0 * PI * k as f64 / len as f64).cos())
        .sum();
    let bin = rate / len as f64;
    let mut bins: Vec<usize> = (2..mag.len().saturating_sub(1))
        .filter(|&k| mag[k] > mag[k - 1] && mag[k] >= mag[k + 1] && mag[k] > floor * top)
        .collect();
    bins.sort_by(|&a, &b| mag[b].total_cmp(&mag[a]));
    bins.truncate(MAX_PEAKS);
    let mut out: Vec<Peak> = bins
        .into_iter()
        .map(|k| {
            // Golden section on |S(f)| in [f_k - bin, f_k + bin].
            let (mut a, mut b) = ((k as f64 - 1.0) * bin, (k as f64 + 1.0) * bin);
            let g = 0.5 * (5f64.sqrt() - 1.0);
            let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
            let (mut fc, mut fd) = (dtft(s, mean, rate, c), dtft(s, mean, rate, d));
            while b - a > 1e-9 * bin {
                if fc > fd {
                    (b, d, fd) = (d, c, fc);
                    c = b - g * (b - a);
                    fc = dtft(s, mean, rate, c);
                } else {
                    (a, c, fc) = (c, d, fd);
                    d = a + g * (b - a);
                    fd = dtft(s, mean, rate, d);
                }
            }
            let f = 0.5 * (a + b);
            Peak {
                frequency: f,
                amplitude: 2.0 * dtft(s, mean, rate, f) / wsum,
            }
        })
        .collect();
    out.sort_by(|p, q| q.amplitude.total_cmp(&p.amplitude));
    out
}

/// Smallest and largest local maximum of `s - mean(s)`, each refined by a parabola.
pub fn envelope(s: &[f64]) -> (f64, f64) {
    let mean = s.iter().sum::<f64>() / s.len().max(1) as f64;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 1..s.len().saturating_sub(1) {
        let (a, b, c) = (s[k - 1] - mean, s[k] - mean, s[k + 1] - mean);
        if b > a && b >= c && b > 0.0 {
            let den = a - 2.0 * b + c;
            let top = if den < 0.0 {
                b - 0.125 * (a - c) * (a - c) / den
            } else {
                b
            };
            lo = lo.min(top);
            hi = hi.max(top);
        }
    }
    (lo, hi)
}
