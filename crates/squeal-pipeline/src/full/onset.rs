//! The full model's complex eigenvalues in the band at a friction value, its Hopf point μ0,
//! and both against the reduced brake's (`squeal stability --full`).
//!
//! **Spectrum at μ.** The reduced brake's static equilibrium at μ gives each pair's element
//! response; the full model linearized there ([`super::FullBrake::linearized`]) has its
//! eigenvalues `λ` with `Im λ / 2π` in the band found by [`eigs_on_segment`]: every one with
//! `|Re λ|` up to the options' strip, or the search fails.
//!
//! **μ0.** A mode is unstable when `Re λ > unstable × |λ|` (relative `1e-9` by default: 100
//! times the eigensolver's tolerance on a simple eigenvalue, `1e-11 |λ|`; measured on stable
//! modes: below `1e-12 |λ|`; next to a coalescence the nearly defective pair's error grows
//! like `ε / d` with `d` the pair's distance, which matters only where `d` is below `1e-7 |λ|`,
//! a negligible width of μ). The friction values of the sweep, thinned to at most `scan_points`, are scanned
//! in order over the whole band until one has an unstable mode; μ0 is then bracketed by
//! bisection between the last stable and the first unstable value, each step solving only a
//! narrow segment around the unstable modes (their frequency ±`track_width`), until the
//! bracket is narrower than `mu_tolerance × μ`. Undamped, `Re λ` grows like
//! `c √(μ − μ0)` past a coalescence, so the threshold moves μ0 by `(unstable |λ| / c)²`. The
//! coefficient can be small: on the coarse bundled brake a disc doublet at 12.4 kHz coalesces
//! with `c` ≈ 1.6 1/s, where a threshold of `1e-6 |λ|` (0.078 1/s) moved μ0 by 2.5e-3 and
//! `1e-9 |λ|` moves it by 2.5e-9.
//!
//! **Against the reduced brake.** The reduced brake is swept over the same friction values
//! without the modal damping of eqs (12)–(13) (defined on its own modes, it has no
//! full-model counterpart) and its μ0 and frequency are compared with the full model's twice:
//! the full model's first onset over the whole band (which may be another mode: a pair the
//! reduction does not reproduce goes unstable first), and the onset of the reduced brake's
//! unstable mode, the full model searched only within `mode_width` of its frequency (the
//! Craig–Bampton error of that mode's μ0).
//!
//! **When the first onsets differ.** Undamped, a pair of modes `ω1 < ω2` coupled by friction
//! coalesces where the coupling closes their gap: for the pair alone `λ² + ω1²`, `λ² + ω2²`
//! with a friction coupling `μ κ₁₂`, `μ κ₂₁` off the diagonal (of opposite signs: the friction
//! stiffness is not symmetric), `ω² = (ω1² + ω2²)/2 ± √(((ω2² − ω1²)/2)² + μ² κ₁₂ κ₂₁)` turns
//! complex at `μ0 = |ω2² − ω1²| / (2 √(−κ₁₂ κ₂₁)) ≈ ω δ / √(−κ₁₂ κ₂₁)` with `δ = ω2 − ω1`:
//! proportional to the split. A
//! near-degenerate disc doublet (split `δ`, a few 1e-6 of its frequency on the bundled coarse
//! brake) therefore has a μ0 whose relative error is the relative error of `δ`, and the
//! reduced brake's split is off by the Craig–Bampton errors of the two modes, which do not
//! cancel: matching such a μ0 to 1e-3 needs the two frequencies to `1e-3 δ`. When the full
//! model's first onset is another mode than the reduced brake's, [`pair_split`] gives the two
//! modes nearest its frequency at μ = 0 in both models, so the output says which split is off.

use super::FullBrake;
use crate::error::{PipelineError, Result};
use crate::model::{Log, Model};
use faer::c64;
use squeal_brake::analysis::{DampingSpec, PairChoice};
use squeal_brake::equilibrium::{Equilibrium, static_equilibrium};
use squeal_eigs::quadratic::{QuadraticOptions, QuadraticPencil, SegmentEigs, eigs_on_segment};
use std::f64::consts::TAU;
use std::time::Instant;

/// Controls of the full model's search.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct FullOptions {
    /// The quadratic eigensolver's controls (over the whole band).
    pub quadratic: QuadraticOptions,
    /// Friction values scanned over the whole band, at most (thinned from the sweep's).
    pub scan_points: usize,
    /// Relative width of μ0's final bracket.
    pub mu_tolerance: f64,
    /// `Re λ > unstable |λ|`: an unstable mode.
    pub unstable: f64,
    /// Half-width of the segment around the unstable modes in the bisection, relative to
    /// their frequency.
    pub track_width: f64,
    /// Half-width of the band around the reduced brake's unstable mode, relative to its
    /// frequency, in which the full model's onset of that mode is searched.
    pub mode_width: f64,
}

impl Default for FullOptions {
    fn default() -> Self {
        Self {
            quadratic: QuadraticOptions::default(),
            scan_points: 11,
            mu_tolerance: 1e-6,
            unstable: 1e-9,
            track_width: 0.02,
            mode_width: 0.05,
        }
    }
}

/// The full model's eigenvalues in a band at one friction value.
#[derive(Clone, Debug)]
pub struct FullSpectrum {
    /// μ.
    pub mu: f64,
    /// The band (Hz).
    pub band_hz: (f64, f64),
    /// The eigenpairs with `Im λ / 2π` in the band, by frequency.
    pub eigs: SegmentEigs,
    /// Wall time (s).
    pub seconds: f64,
}

impl FullSpectrum {
    /// The eigenvalues.
    pub fn values(&self) -> Vec<c64> {
        self.eigs.pairs.iter().map(|p| p.value).collect()
    }

    /// The unstable eigenvalues (`Re λ > unstable |λ|`).
    pub fn unstable(&self, unstable: f64) -> Vec<c64> {
        self.values()
            .into_iter()
            .filter(|l| l.re > unstable * l.norm())
            .collect()
    }
}

/// The full model's Hopf point.
#[derive(Clone, Debug)]
pub struct FullOnset {
    /// μ0: the middle of the final bracket.
    pub mu0: f64,
    /// The last stable and the first unstable friction value.
    pub bracket: (f64, f64),
    /// The unstable mode's frequency at the bracket's top (Hz).
    pub frequency_hz: f64,
    /// Its `Re λ` there (1/s).
    pub growth: f64,
    /// Spectra computed (over the band and around the mode).
    pub evaluations: usize,
    /// Wall time (s).
    pub seconds: f64,
}

/// The reduced brake's Hopf point swept without modal damping.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReducedOnset {
    /// μ0.
    pub mu0: f64,
    /// Its frequency (Hz).
    pub frequency_hz: f64,
    /// Wall time (s).
    pub seconds: f64,
    /// The coalescing pair's frictionless modes (1-based) and frequencies (Hz), when the sweep
    /// names it (for the near-degenerate caveat, `crate::caveats::near_degenerate`).
    pub pair: Option<((usize, usize), (f64, f64))>,
}

/// The full model's spectrum with `Im λ / 2π` in `band_hz` at friction `mu`, linearized about
/// the reduced brake's equilibrium there (`start`: a nearby one to start Newton from).
/// Returns the equilibrium too.
pub fn spectrum_at(
    full: &FullBrake,
    model: &Model,
    mu: f64,
    band_hz: (f64, f64),
    start: Option<&Equilibrium>,
    opts: &QuadraticOptions,
    progress: &dyn Fn(usize, usize),
) -> Result<(FullSpectrum, Equilibrium)> {
    let t = Instant::now();
    let eq = static_equilibrium(
        &model.brake,
        mu,
        start.map(|e| e.x.as_slice()),
        &model.sweep.newton,
    )?;
    let responses: Vec<_> = model
        .brake
        .pairs
        .iter()
        .map(|p| p.response(&eq.x, None, mu))
        .collect();
    let (k, c) = full.linearized(&responses)?;
    let pencil = QuadraticPencil::new(k.as_ref(), c.as_ref().map(|c| c.as_ref()), full.m.as_ref())?;
    let eigs = eigs_on_segment(&pencil, TAU * band_hz.0, TAU * band_hz.1, opts, progress)?;
    let spectrum = FullSpectrum {
        mu,
        band_hz,
        eigs,
        seconds: t.elapsed().as_secs_f64(),
    };
    Ok((spectrum, eq))
}

/// At most `count` of `mus` (ascending), evenly thinned, the first and last kept.
pub fn thinned(mus: &[f64], count: usize) -> Vec<f64> {
    if mus.len() <= count.max(2) {
        return mus.to_vec();
    }
    let count = count.max(2);
    (0..count)
        .map(|k| mus[(k * (mus.len() - 1)) / (count - 1)])
        .collect()
}

/// One line of progress about a spectrum.
fn spectrum_line(s: &FullSpectrum, what: &str, opts: &FullOptions) -> String {
    let worst = s
        .values()
        .iter()
        .map(|l| l.re / l.norm())
        .fold(f64::NEG_INFINITY, f64::max);
    format!(
        "full model, mu = {:.6} ({what}): {} eigenvalues in {:.0}..{:.0} Hz, {} shifts, {} solves, max Re/|lambda| {:.2e}{}, backward error {:.1e}, {:.1} s",
        s.mu,
        s.eigs.pairs.len(),
        s.band_hz.0,
        s.band_hz.1,
        s.eigs.shifts,
        s.eigs.steps,
        worst,
        if worst > opts.unstable {
            " (unstable)"
        } else {
            ""
        },
        s.eigs.worst_backward_error,
        s.seconds
    )
}

/// The band of the unstable modes of `s`, widened by `width` of their frequencies (Hz).
fn tracked_band(s: &FullSpectrum, opts: &FullOptions) -> (f64, f64) {
    let f: Vec<f64> = s
        .unstable(opts.unstable)
        .iter()
        .map(|l| l.im / TAU)
        .collect();
    let lo = f.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = f.iter().copied().fold(0.0, f64::max);
    (
        (lo * (1.0 - opts.track_width)).max(0.0),
        hi * (1.0 + opts.track_width),
    )
}

/// The full model's μ0 over `mus` (ascending) in `band_hz` (module docs), `log` told each
/// spectrum; `None` when no scanned friction value has an unstable mode in the band.
pub fn full_onset(
    full: &FullBrake,
    model: &Model,
    mus: &[f64],
    band_hz: (f64, f64),
    opts: &FullOptions,
    log: Log,
) -> Result<Option<FullOnset>> {
    let t = Instant::now();
    let quiet = |_: usize, _: usize| {};
    let mut evaluations = 0;
    let mut last: Option<(f64, Equilibrium)> = None;
    let mut found = None;
    for &mu in &thinned(mus, opts.scan_points) {
        let start = last.as_ref().map(|l| &l.1);
        let (s, eq) = spectrum_at(full, model, mu, band_hz, start, &opts.quadratic, &quiet)?;
        evaluations += 1;
        log(&spectrum_line(&s, "band", opts));
        if !s.unstable(opts.unstable).is_empty() {
            found = Some((s, eq));
            break;
        }
        last = Some((mu, eq));
    }
    let Some((mut top, mut top_eq)) = found else {
        return Ok(None);
    };
    let (mut lo, mut lo_eq) = match last {
        Some(l) => l,
        None => {
            return Err(PipelineError::input(
                "the full model",
                format!(
                    "already unstable at the first friction value {}: start the sweep lower",
                    top.mu
                ),
            ));
        }
    };
    let band = tracked_band(&top, opts);
    let mut q = opts.quadratic;
    while top.mu - lo > opts.mu_tolerance * top.mu {
        let mu = 0.5 * (lo + top.mu);
        let growth = top
            .unstable(opts.unstable)
            .iter()
            .map(|l| l.re)
            .fold(0.0, f64::max);
        q.strip = opts.quadratic.strip.max(2.0 * growth);
        q.cell = q.cell.min(0.5 * TAU * (band.1 - band.0));
        let (s, eq) = spectrum_at(full, model, mu, band, Some(&lo_eq), &q, &quiet)?;
        evaluations += 1;
        log(&spectrum_line(&s, "tracking", opts));
        if s.unstable(opts.unstable).is_empty() {
            (lo, lo_eq) = (mu, eq);
        } else {
            (top, top_eq) = (s, eq);
        }
    }
    let _ = top_eq;
    let mode = top
        .unstable(opts.unstable)
        .into_iter()
        .max_by(|a, b| a.re.total_cmp(&b.re))
        .unwrap_or_default();
    Ok(Some(FullOnset {
        mu0: 0.5 * (lo + top.mu),
        bracket: (lo, top.mu),
        frequency_hz: mode.im / TAU,
        growth: mode.re,
        evaluations,
        seconds: t.elapsed().as_secs_f64(),
    }))
}

/// The band (Hz) around the reduced brake's unstable mode at `frequency_hz` in which its onset
/// is searched in the full model, inside `band`.
pub fn mode_band(frequency_hz: f64, band: (f64, f64), opts: &FullOptions) -> (f64, f64) {
    let lo = (frequency_hz * (1.0 - opts.mode_width)).max(band.0);
    let hi = (frequency_hz * (1.0 + opts.mode_width)).min(band.1);
    (lo, hi)
}

/// No modal damping at all (module docs: it has no full-model counterpart).
pub fn undamped() -> DampingSpec {
    DampingSpec {
        global_ratio: 0.0,
        pair: PairChoice::Auto,
        pair_ratios: [0.0, 0.0],
    }
}

/// The reduced brake's μ0 over `mus` without modal damping (module docs).
pub fn reduced_onset(model: &Model, mus: &[f64]) -> Result<Option<ReducedOnset>> {
    let t = Instant::now();
    let st = squeal_brake::analysis::stability(&model.brake, &undamped(), mus, &model.sweep)?;
    let hz = |j: usize| st.reference.basis.omega[j] / TAU;
    let pair = st.pair.map(|(a, b)| ((a + 1, b + 1), (hz(a), hz(b))));
    Ok(st.sweep.hopf.map(|h| ReducedOnset {
        mu0: h.mu0,
        frequency_hz: h.frequency_hz,
        seconds: t.elapsed().as_secs_f64(),
        pair,
    }))
}

/// The two modes nearest a frequency at μ = 0, in the full model and in the reduced brake
/// (module docs, "When the first onsets differ").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairSplit {
    /// The onset's frequency (Hz).
    pub onset_hz: f64,
    /// The full model's two eigenfrequencies nearest it at μ = 0 (Hz), ascending.
    pub full_hz: Option<(f64, f64)>,
    /// The reduced brake's two frictionless frequencies nearest it (Hz), ascending.
    pub reduced_hz: Option<(f64, f64)>,
}

/// The two of `hz` nearest `f`, ascending.
fn nearest_two(hz: &[f64], f: f64) -> Option<(f64, f64)> {
    let mut by: Vec<f64> = hz.to_vec();
    by.sort_by(|a, b| (a - f).abs().total_cmp(&(b - f).abs()));
    match by[..] {
        [a, b, ..] => Some((a.min(b), a.max(b))),
        _ => None,
    }
}

/// The split of the pair at `onset_hz` at μ = 0: the full model's spectrum within
/// `track_width` of it and the reduced brake's frictionless modes.
pub fn pair_split(
    full: &FullBrake,
    model: &Model,
    onset_hz: f64,
    opts: &FullOptions,
) -> Result<PairSplit> {
    let band = (
        onset_hz * (1.0 - opts.track_width),
        onset_hz * (1.0 + opts.track_width),
    );
    let (s, _) = spectrum_at(full, model, 0.0, band, None, &opts.quadratic, &|_, _| {})?;
    let full_hz: Vec<f64> = s.values().iter().map(|l| l.im / TAU).collect();
    let st = squeal_brake::analysis::stability(&model.brake, &undamped(), &[0.0], &model.sweep)?;
    let reduced_hz: Vec<f64> = st.reference.basis.omega.iter().map(|w| w / TAU).collect();
    Ok(PairSplit {
        onset_hz,
        full_hz: nearest_two(&full_hz, onset_hz),
        reduced_hz: nearest_two(&reduced_hz, onset_hz),
    })
}

/// The lines saying which split of [`PairSplit`] is off.
pub fn split_text(p: &PairSplit) -> String {
    let pair = |h: Option<(f64, f64)>| {
        h.map_or("none".to_string(), |(a, b)| {
            format!(
                "{a:.3} and {b:.3} Hz (split {:.2e})",
                (b - a) / (0.5 * (a + b))
            )
        })
    };
    format!(
        "  the full model's first onset ({:.1} Hz) is not the reduced brake's mode: at mu = 0 its two modes nearest it are {} in the full model, {} in the reduced brake; undamped, a pair coalesces at a friction proportional to its split, which the kept modes, the mesh and the contact discretization set (docs/reduction.md)\n",
        p.onset_hz,
        pair(p.full_hz),
        pair(p.reduced_hz)
    )
}

/// The table of the reduced brake's and the full model's μ0 and frequency, with the relative
/// differences `reduced / full − 1`.
pub fn comparison_text(
    reduced: Option<&ReducedOnset>,
    full: Option<&FullOnset>,
    mode: Option<&FullOnset>,
) -> String {
    let mut out = String::from(
        "reduced brake against the full model (both without modal damping):\n                     reduced          full             reduced/full - 1\n",
    );
    let cell = |v: Option<f64>| v.map_or("none".to_string(), |v| format!("{v:.7}"));
    let rel = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => format!("{:+.3e}", a / b - 1.0),
        _ => "-".to_string(),
    };
    for (what, r, f) in [
        (
            "mu0 (first in band)",
            reduced.map(|r| r.mu0),
            full.map(|f| f.mu0),
        ),
        (
            "  its frequency (Hz)",
            reduced.map(|r| r.frequency_hz),
            full.map(|f| f.frequency_hz),
        ),
        (
            "mu0 (reduced's mode)",
            reduced.map(|r| r.mu0),
            mode.map(|f| f.mu0),
        ),
        (
            "  its frequency (Hz)",
            reduced.map(|r| r.frequency_hz),
            mode.map(|f| f.frequency_hz),
        ),
    ] {
        out.push_str(&format!(
            "  {what:<20} {:<16} {:<16} {}\n",
            cell(r),
            cell(f),
            rel(r, f)
        ));
    }
    for (what, f) in [("first in band", full), ("reduced's mode", mode)] {
        let Some(f) = f else { continue };
        out.push_str(&format!(
            "  full model ({what}): mu0 in [{:.8}, {:.8}], growth rate {:.4e} 1/s at the bracket's top, {} spectra, {:.1} s\n",
            f.bracket.0, f.bracket.1, f.growth, f.evaluations, f.seconds
        ));
    }
    if let Some(r) = reduced {
        out.push_str(&format!("  reduced sweep: {:.1} s\n", r.seconds));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pair_nearest_an_onset_is_its_two_nearest_modes_in_order() {
        // The coarse brake's 12.4 kHz pair at mu = 0 (full model) and the 50-mode brake's
        // modes of the same ranks (docs/reduction.md).
        let full = [12430.162, 12430.242, 12676.111];
        assert_eq!(nearest_two(&full, 12430.201), Some((12430.162, 12430.242)));
        let reduced = [12871.0, 12623.708, 12471.163];
        assert_eq!(
            nearest_two(&reduced, 12430.201),
            Some((12471.163, 12623.708))
        );
        assert_eq!(nearest_two(&[1.0], 1.0), None);
        let text = split_text(&PairSplit {
            onset_hz: 12430.201,
            full_hz: nearest_two(&full, 12430.201),
            reduced_hz: None,
        });
        assert!(
            text.contains("12430.162 and 12430.242 Hz (split 6.44e-6) in the full model, none in the reduced brake"),
            "{text}"
        );
    }
}
