//! `squeal stability --full` for a scene: the full model built from the scene's meshes, its
//! eigenvalues in the band at a friction value or its μ0 over the sweep against the reduced
//! brake's, written to `<out>/stability/full.txt`.

use super::full_brake;
use super::onset::{
    FullOnset, FullOptions, comparison_text, full_onset, mode_band, pair_split, reduced_onset,
    spectrum_at, split_text,
};
use crate::Pipeline;
use crate::error::Result;
use crate::model::Model;
use crate::parts::{brake_inputs, load_parts};
use std::f64::consts::TAU;
use std::fmt::Write as _;
use std::time::Instant;

/// The band the full model is searched in (Hz): the scene's band below the reduced model's
/// valid limit, as the reduced sweep's μ0 is defined (the whole valid band without one).
pub fn band_of(m: &Model) -> (f64, f64) {
    let b = m.sweep.band;
    let (lo, hi) = b.user.unwrap_or((0.0, b.valid_max_hz));
    (lo, hi.min(b.valid_max_hz))
}

/// Whether the full model's first onset `f` is another mode than the reduced brake's `r`
/// (farther than the options' `mode_width` from its frequency, or the reduced brake has none).
fn other_mode(r: Option<&super::onset::ReducedOnset>, f: &FullOnset, opts: &FullOptions) -> bool {
    r.is_none_or(|r| (f.frequency_hz / r.frequency_hz - 1.0).abs() > opts.mode_width)
}

/// The full model's check of `p`'s scene: at `at` (a friction value) its eigenvalues in the
/// band, else its μ0 against the reduced brake's over the pipeline's friction values. Writes
/// the whole text to `<out>/stability/full.txt` and returns it without its first line, the
/// model's size, which already went to `p`'s log when the model was assembled (each spectrum
/// is a line of the log too).
pub fn full_check(p: &Pipeline, at: Option<f64>) -> Result<String> {
    let log = p.log();
    let m = p.model()?;
    let t = Instant::now();
    let parts = load_parts(&p.scene, log)?;
    let inputs = brake_inputs(&p.scene, &parts)?;
    let full = full_brake(&parts, &inputs, m)?.with_dampers(&p.scene, &parts)?;
    let sizes: Vec<String> = full
        .parts
        .iter()
        .map(|q| format!("{} {}", q.name, q.unreduced.num_free()))
        .collect();
    let tied = full.ties.as_ref().map_or(String::new(), |t| {
        format!(
            "; {} slave nodes tied between parts eliminated ({} stacked dofs)",
            t.slave_nodes, t.stacked
        )
    });
    let mut out = String::new();
    let _ = writeln!(
        out,
        "full model: {} dofs ({}{tied}), {} contact pairs, assembled in {:.1} s; reduced brake {} dofs",
        full.size(),
        sizes.join(", "),
        full.normal.len(),
        t.elapsed().as_secs_f64(),
        m.brake.size()
    );
    log(out.trim_end());
    let header = out.len();
    let band = band_of(m);
    let opts = FullOptions::default();
    match at {
        Some(mu) => {
            let tell =
                |done: usize, total: usize| log(&format!("full model: shift {done} of {total}"));
            let (s, _) = spectrum_at(&full, m, mu, band, None, &opts.quadratic, &tell)?;
            let _ = writeln!(
                out,
                "eigenvalues of the full model at mu = {mu} in {:.0}..{:.0} Hz (and their conjugates), {} shifts, {} solves, {:.1} s:",
                band.0, band.1, s.eigs.shifts, s.eigs.steps, s.seconds
            );
            let _ = writeln!(
                out,
                "  #  frequency (Hz)   Re lambda (1/s)   backward error"
            );
            for (k, e) in s.eigs.pairs.iter().enumerate() {
                let _ = writeln!(
                    out,
                    "{:3}  {:14.4}  {:+16.6e}  {:.1e}{}",
                    k + 1,
                    e.value.im / TAU,
                    e.value.re,
                    e.backward_error,
                    if e.value.re > opts.unstable * e.value.norm() {
                        "  unstable"
                    } else {
                        ""
                    }
                );
            }
        }
        None => {
            log("reduced brake without modal damping: sweep");
            let r = reduced_onset(m, &p.mus)?;
            let f = full_onset(&full, m, &p.mus, band, &opts, log)?;
            let mode = match &r {
                Some(r) => {
                    let near = mode_band(r.frequency_hz, band, &opts);
                    log(&format!(
                        "full model: the reduced brake's unstable mode, {:.0}..{:.0} Hz",
                        near.0, near.1
                    ));
                    full_onset(&full, m, &p.mus, near, &opts, log)?
                }
                None => None,
            };
            let _ = writeln!(out, "band {:.0}..{:.0} Hz", band.0, band.1);
            out.push_str(&comparison_text(r.as_ref(), f.as_ref(), mode.as_ref()));
            // The undamped onset is often a near-degenerate pair, whose μ0 amplifies every
            // frequency error (the scene's damped run may not name it): said here too.
            let pair = r.as_ref().and_then(|r| r.pair);
            if let Some(c) = pair.and_then(|(m, hz)| crate::caveats::near_degenerate(m, hz)) {
                let _ = writeln!(out, "  warning (reduced brake, undamped): {c}");
            }
            if let Some(f) = f.as_ref().filter(|f| other_mode(r.as_ref(), f, &opts)) {
                out.push_str(&split_text(&pair_split(&full, m, f.frequency_hz, &opts)?));
            }
        }
    }
    let path = p.out.join("stability").join("full.txt");
    squeal_io::atomic_write(&path, |w| w.write_all(out.as_bytes()))?;
    let _ = writeln!(out, "written to {}", path.display());
    Ok(out.split_off(header))
}
