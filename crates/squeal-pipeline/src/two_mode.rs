//! `squeal chbm --two-mode`: the generalized CHBM at a friction level where two modes are
//! unstable (issue 24, item 2): each unstable mode's CHBM cycle with Hill's verdict
//! ([`squeal_chbm::multi::periodic`]), the two-mode torus ([`squeal_chbm::multi::quasi`]) with
//! its two constraints and its Lyapunov exponents ([`squeal_chbm::torus_stability`]), and which
//! of them attracts. Written to `<out>/chbm/two_mode.txt`.

use crate::Pipeline;
use crate::branch_torus::lyapunov_defaults;
use crate::error::PipelineError;
use faer::c64;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::ChbmOptions;
use squeal_chbm::floquet::HillOptions;
use squeal_chbm::multi::periodic::{ModeCycle, Verdict, mode_cycles, verdict};
use squeal_chbm::multi::quasi::{TwoModeOptions, TwoModeTorus, torus_constraints, two_mode_torus};
use squeal_chbm::multi::unstable_modes;
use squeal_chbm::torus_stability::torus_lyapunov;
use squeal_hbm::torus::lyapunov::LyapunovSpectrum;
use std::f64::consts::TAU;
use std::fmt::Write as _;
use std::path::Path;
use std::time::{Duration, Instant};

/// The generalized CHBM's answer at one friction level.
#[derive(Debug)]
pub struct TwoModeReport {
    /// The friction coefficient.
    pub mu: f64,
    /// Every in-band unstable eigenvalue there, largest growth first.
    pub lambdas: Vec<c64>,
    /// Each unstable mode's CHBM cycle (the two of largest growth).
    pub cycles: Vec<ModeCycle>,
    /// What the cycles' stability says.
    pub verdict: Verdict,
    /// The torus of the two modes, or why there is none.
    pub torus: Result<TwoModeTorus, String>,
    /// Its constraints `λ_j` (generalized CHBM, eq 47 per mode).
    pub constraints: Option<Result<Vec<c64>, String>>,
    /// Its Lyapunov exponents.
    pub lyapunov: Option<Result<LyapunovSpectrum, String>>,
    /// Wall time.
    pub time: Duration,
}

/// The generalized CHBM at `mu` on the pipeline's brake with `harmonics` harmonics per cycle.
pub fn two_mode(p: &Pipeline, mu: f64, harmonics: usize) -> Result<TwoModeReport, PipelineError> {
    let t0 = Instant::now();
    let m = p.model()?;
    let st = p.stability()?;
    let mut starts = unstable_modes(&m.brake, &st.reference, mu, &m.sweep.band, &m.sweep.newton)?;
    let lambdas: Vec<c64> = starts.iter().map(|s| s.lambda).collect();
    starts.truncate(2);
    let mb = ModalBrake::new(&m.brake, &st.reference, mu);
    let mut opts = ChbmOptions::default();
    opts.harmonics = harmonics;
    let cycles = mode_cycles(
        &mb,
        &starts,
        &opts,
        &squeal_chbm::RESTART_AMPLITUDES,
        &HillOptions::default(),
    )?;
    let verdict = verdict(&cycles);
    let torus = if starts.len() < 2 {
        Err(format!("only {} unstable mode at mu = {mu}", starts.len()))
    } else {
        let sols = [Some(&cycles[0].solution), Some(&cycles[1].solution)];
        let topts = TwoModeOptions {
            truncation: squeal_hbm::torus::Truncation::Box(harmonics, harmonics),
            ..TwoModeOptions::default()
        };
        two_mode_torus(&mb, &starts, sols, &topts).map_err(|e| e.to_string())
    };
    let (constraints, lyapunov) = match &torus {
        Ok(t) => (
            Some(torus_constraints(&mb, t, &starts, 32).map_err(|e| e.to_string())),
            Some(
                torus_lyapunov(&mb, &t.basis, &t.point, &lyapunov_defaults())
                    .map_err(|e| e.to_string()),
            ),
        ),
        Err(_) => (None, None),
    };
    Ok(TwoModeReport {
        mu,
        lambdas,
        cycles,
        verdict,
        torus,
        constraints,
        lyapunov,
        time: t0.elapsed(),
    })
}

/// The report as text.
pub fn report_text(r: &TwoModeReport) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "generalized CHBM at mu = {}: {} unstable mode(s) in the band",
        r.mu,
        r.lambdas.len()
    );
    for (j, l) in r.lambdas.iter().enumerate() {
        let _ = writeln!(
            out,
            "  mode {}: Re lambda = {:.4} 1/s at {:.4} Hz",
            j + 1,
            l.re,
            l.im / TAU
        );
    }
    for c in &r.cycles {
        let s = &c.solution;
        let _ = write!(
            out,
            "cycle of mode {}: {}, {:.6} Hz",
            c.mode + 1,
            s.outcome,
            s.omega / TAU
        );
        match &c.floquet {
            Some(Ok(f)) => {
                let _ = write!(out, ", Hill: {}", f.stability());
                if let Some(e) = f.leading() {
                    let _ = write!(out, " (leading exponent {:.4} 1/s)", e.sigma.re);
                }
            }
            Some(Err(e)) => {
                let _ = write!(out, ", Hill failed: {e}");
            }
            None => {}
        }
        let _ = writeln!(out);
    }
    let _ = writeln!(out, "the cycles' verdict: {}", r.verdict);
    match &r.torus {
        Ok(t) => {
            let f = t.point.frequencies_hz();
            let (pair, e) = t.point.loudest();
            let _ = writeln!(
                out,
                "two-mode torus (from {}, x{}; basis {}): f1 = {:.6} Hz, f2 = {:.6} Hz; pair {}: closure first harmonics {:.4e} m at f1 and {:.4e} m at f2, swing over one period of f1 {:.4e}..{:.4e} m, closure {:.4e}..{:.4e} m",
                t.guess,
                t.guess_amplitude,
                crate::branch_torus::truncation_text(t.basis.truncation()),
                f[0],
                f[1],
                pair + 1,
                t.first_harmonics[0],
                t.first_harmonics[1],
                e.swing_min,
                e.swing_max,
                e.min,
                e.max
            );
            match &r.constraints {
                Some(Ok(l)) => {
                    let parts: Vec<String> = l
                        .iter()
                        .map(|v| format!("{:.2e} + {:.4}i 1/s", v.re, v.im))
                        .collect();
                    let _ = writeln!(
                        out,
                        "  constraints (eq 47 per mode, zero at a root): lambda = {}",
                        parts.join(", ")
                    );
                }
                Some(Err(e)) => {
                    let _ = writeln!(out, "  constraints not evaluated: {e}");
                }
                None => {}
            }
            match &r.lyapunov {
                Some(Ok(s)) => {
                    let ex: Vec<String> = s.exponents.iter().map(|v| format!("{v:.3}")).collect();
                    let _ = writeln!(
                        out,
                        "  Lyapunov exponents {} 1/s (uncertainty {:.3} 1/s): the torus is {}",
                        ex.join(", "),
                        s.uncertainty(),
                        s.stability()
                    );
                }
                Some(Err(e)) => {
                    let _ = writeln!(out, "  Lyapunov exponents failed: {e}");
                }
                None => {}
            }
        }
        Err(e) => {
            let _ = writeln!(out, "no two-mode torus: {e}");
        }
    }
    let _ = writeln!(out, "({:.1} s)", r.time.as_secs_f64());
    out
}

/// Writes `two_mode.txt` into `dir` (atomically).
pub fn write(dir: &Path, r: &TwoModeReport) -> Result<(), PipelineError> {
    std::fs::create_dir_all(dir).map_err(|error| PipelineError::File {
        what: "creating the output folder",
        path: dir.to_path_buf(),
        error,
    })?;
    squeal_io::atomic_write_bytes(&dir.join("two_mode.txt"), report_text(r).as_bytes())?;
    Ok(())
}
