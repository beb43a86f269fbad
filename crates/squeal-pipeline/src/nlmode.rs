//! `squeal nlmode`: the squeal mode's complex nonlinear mode at a few friction values
//! ([`squeal_chbm::nlmode`], the extended periodic motion concept): its frequency and modal
//! damping against the modal amplitude, and the limit cycles where the damping vanishes,
//! checked against the branch of `squeal branch` when asked. Writes `nlmode.csv`,
//! `nlmode.json` and the figure `nlmode.svg`/`.png`.

use crate::branch::BranchAnalysis;
use crate::error::{PipelineError, Result, json_text};
use crate::model::{Log, Model};
use crate::stability;
use squeal_brake::analysis::LinearStability as Stability;
use squeal_brake::criticality::NormalForm;
use squeal_chbm::nlmode::{NlModeOptions, NonlinearMode, nonlinear_mode};
use squeal_hbm::HarmonicLayout;
use squeal_report::format::fmt_sig;
use squeal_report::{Annotation, Dash, Figure, Layout, Panel, Scale, Series, Table};
use std::f64::consts::TAU;
use std::fmt::Write as _;
use std::path::Path;

/// The nonlinear mode at one friction value.
pub struct NlModeAt {
    /// μ.
    pub mu: f64,
    /// The mode.
    pub mode: NonlinearMode,
}

/// A limit cycle of the nonlinear mode against the branch's cycle at the same μ.
#[derive(Clone, Debug, PartialEq)]
pub struct BranchCheck {
    /// μ.
    pub mu: f64,
    /// ω of the nonlinear mode's root of ζ and of the branch's cycle (rad/s).
    pub omega: (f64, f64),
    /// First-harmonic amplitude of the phase dof (m), nonlinear mode and branch.
    pub amplitude: (f64, f64),
    /// Harmonics of the branch's cycle.
    pub harmonics: usize,
}

impl BranchCheck {
    /// `|ω_mode / ω_branch - 1|`.
    pub fn frequency_error(&self) -> f64 {
        (self.omega.0 / self.omega.1 - 1.0).abs()
    }

    /// `|A_mode / A_branch - 1|`.
    pub fn amplitude_error(&self) -> f64 {
        (self.amplitude.0 / self.amplitude.1 - 1.0).abs()
    }
}

/// The nonlinear modes of a scene.
pub struct NlModeAnalysis {
    /// The Hopf point's normal form (μ0 and the first Lyapunov coefficient).
    pub normal_form: NormalForm,
    /// One mode per friction value.
    pub modes: Vec<NlModeAt>,
    /// The comparison with the branch (empty unless [`compare`] ran).
    pub checks: Vec<BranchCheck>,
}

/// The nonlinear mode of the squeal mode (the most unstable in the band) at each `mus`;
/// `None` when the sweep has no Hopf point.
pub fn analyse(
    m: &Model,
    st: &Stability,
    mus: &[f64],
    opts: &NlModeOptions,
    log: Log,
) -> Result<Option<NlModeAnalysis>> {
    let Some(nf) = stability::normal_form(m, st)? else {
        return Ok(None);
    };
    let mut modes = Vec::new();
    for &mu in mus {
        let (start, mb) = crate::chbm::start(m, st, mu, None)?;
        let mode = nonlinear_mode(&mb, &start, opts).map_err(|e| {
            PipelineError::input("the nonlinear mode", format!("at mu = {mu}: {e}"))
        })?;
        log(&format!(
            "nonlinear mode at mu = {mu}: {} points, {} limit cycle(s), {:.2} s",
            mode.points.len(),
            mode.cycles.len(),
            mode.time.as_secs_f64()
        ));
        modes.push(NlModeAt { mu, mode });
    }
    Ok(Some(NlModeAnalysis {
        normal_form: nf,
        modes,
        checks: Vec::new(),
    }))
}

/// First-harmonic amplitude of nonlinear dof `d` in coefficients of `harmonics` harmonics.
fn first_harmonic(coeffs: &[f64], harmonics: usize, d: usize) -> Option<f64> {
    let layout = HarmonicLayout::new(coeffs.len() / (2 * harmonics + 1), harmonics).ok()?;
    layout.amplitude(coeffs, 1, d)
}

/// Each root of ζ against the branch's cycle at the same μ nearest in frequency (the branch
/// followed with `--at` at those μ).
pub fn compare(a: &NlModeAnalysis, branch: &BranchAnalysis) -> Vec<BranchCheck> {
    let mut out = Vec::new();
    for m in &a.modes {
        for c in &m.mode.cycles {
            let near = branch
                .at
                .iter()
                .filter(|b| (b.mu / m.mu - 1.0).abs() < 1e-12)
                .min_by(|x, y| {
                    let d = |b: &&crate::branch::CycleAt| (b.cycle.omega - c.point.omega).abs();
                    d(x).total_cmp(&d(y))
                });
            let Some(b) = near else { continue };
            let d = m.mode.phase_dof;
            let amp_mode = first_harmonic(&c.point.coeffs, m.mode.harmonics, d);
            let amp_branch = first_harmonic(&b.cycle.nl_coeffs, b.cycle.harmonics, d);
            if let (Some(x), Some(y)) = (amp_mode, amp_branch) {
                out.push(BranchCheck {
                    mu: m.mu,
                    omega: (c.point.omega, b.cycle.omega),
                    amplitude: (x, y),
                    harmonics: b.cycle.harmonics,
                });
            }
        }
    }
    out
}

/// What `squeal nlmode` prints.
pub fn summary_text(a: &NlModeAnalysis) -> String {
    let mut s = String::new();
    let nf = &a.normal_form;
    let _ = writeln!(
        s,
        "Hopf point mu0 = {} at {} Hz, l1 = {} ({})",
        fmt_sig(nf.mu0, 8),
        fmt_sig(nf.omega0 / TAU, 7),
        fmt_sig(nf.l1, 4),
        nf.criticality()
    );
    for m in &a.modes {
        let md = &m.mode;
        let _ = writeln!(
            s,
            "mu = {} ({} mu0): linear mode f = {} Hz, zeta = {}; {} points in {:.2} s; from the slope of zeta at small amplitude: {}",
            fmt_sig(m.mu, 8),
            fmt_sig(m.mu / nf.mu0, 6),
            fmt_sig(md.linear.omega / TAU, 9),
            fmt_sig(md.linear.zeta, 5),
            md.points.len(),
            md.time.as_secs_f64(),
            md.criticality()
        );
        if let Some(why) = &md.stopped {
            let _ = writeln!(s, "  stopped early: {why}");
        }
        for c in &md.cycles {
            let _ = writeln!(
                s,
                "  limit cycle (zeta = 0): a = {} m kg^0.5, f = {} Hz, {}",
                fmt_sig(c.point.a, 7),
                fmt_sig(c.point.omega / TAU, 10),
                if c.stable() { "stable" } else { "unstable" }
            );
        }
        if md.cycles.is_empty() {
            let _ = writeln!(
                s,
                "  no limit cycle in the amplitudes asked (zeta keeps its sign)"
            );
        }
    }
    for c in &a.checks {
        let _ = writeln!(
            s,
            "branch check at mu = {}: f {} Hz against {} Hz (relative {:.2e}), first harmonic {:.2e} relative ({} harmonics)",
            fmt_sig(c.mu, 8),
            fmt_sig(c.omega.0 / TAU, 10),
            fmt_sig(c.omega.1 / TAU, 10),
            c.frequency_error(),
            c.amplitude_error(),
            c.harmonics
        );
    }
    s
}

/// One row per point of every mode.
pub fn table(a: &NlModeAnalysis) -> Table {
    let h = a.modes.iter().map(|m| m.mode.harmonics).max().unwrap_or(0);
    let mut header: Vec<String> = [
        "mu",
        "mu_over_mu0",
        "a",
        "a_over_opening",
        "frequency_hz",
        "omega_rad_per_s",
        "zeta",
        "residual",
        "iterations",
    ]
    .map(String::from)
    .to_vec();
    for k in 1..=h {
        header.push(format!("h{k}_phase_dof_m"));
    }
    let mut t = Table::new(header);
    for m in &a.modes {
        let md = &m.mode;
        for p in &md.points {
            let mut row = vec![
                format!("{}", m.mu),
                format!("{}", m.mu / a.normal_form.mu0),
                format!("{:e}", p.a),
                format!("{}", p.a / md.opening_amplitude),
                format!("{}", p.omega / TAU),
                format!("{}", p.omega),
                format!("{:e}", p.zeta),
                format!("{:e}", p.residual),
                p.iterations.to_string(),
            ];
            let layout = HarmonicLayout::new(p.coeffs.len() / (2 * md.harmonics + 1), md.harmonics);
            for k in 1..=h {
                let v = layout
                    .as_ref()
                    .ok()
                    .and_then(|l| l.amplitude(&p.coeffs, k, md.phase_dof));
                row.push(v.map_or(String::new(), |v| format!("{v:e}")));
            }
            t.push_row(row);
        }
    }
    t
}

/// `nlmode.json`: per μ the linear limit, the points, the cycles; the branch checks.
pub fn json(a: &NlModeAnalysis) -> serde_json::Value {
    let nf = &a.normal_form;
    serde_json::json!({
        "method": "extended periodic motion concept (Krack 2015): artificial damping -2 zeta omega M xdot; |q1| = a (modal mass of the fundamental); U1s = 0 on the phase dof",
        "hopf": {
            "mu0": nf.mu0,
            "frequency_hz": nf.omega0 / TAU,
            "first_lyapunov_coefficient": nf.l1,
            "criticality": nf.criticality().to_string(),
        },
        "modes": a.modes.iter().map(|m| {
            let md = &m.mode;
            serde_json::json!({
                "mu": m.mu,
                "eigenvalue": [md.lambda.re, md.lambda.im],
                "linear": {"omega": md.linear.omega, "zeta": md.linear.zeta},
                "opening_amplitude": md.opening_amplitude,
                "harmonics": md.harmonics,
                "samples": md.samples,
                "phase_dof": md.phase_dof,
                "zeta2": md.zeta2(),
                "criticality_from_zeta": md.criticality().to_string(),
                "seconds": md.time.as_secs_f64(),
                "stopped": md.stopped,
                "points": md.points.iter().map(|p| serde_json::json!({
                    "a": p.a, "omega": p.omega, "zeta": p.zeta,
                    "residual": p.residual, "iterations": p.iterations,
                })).collect::<Vec<_>>(),
                "limit_cycles": md.cycles.iter().map(|c| serde_json::json!({
                    "a": c.point.a, "omega": c.point.omega, "frequency_hz": c.point.omega / TAU,
                    "zeta": c.point.zeta, "stable": c.stable(), "solves": c.solves,
                })).collect::<Vec<_>>(),
            })
        }).collect::<Vec<_>>(),
        "branch_checks": a.checks.iter().map(|c| serde_json::json!({
            "mu": c.mu,
            "omega_mode": c.omega.0, "omega_branch": c.omega.1,
            "frequency_relative_error": c.frequency_error(),
            "first_harmonic_mode_m": c.amplitude.0, "first_harmonic_branch_m": c.amplitude.1,
            "amplitude_relative_error": c.amplitude_error(),
            "harmonics": c.harmonics,
        })).collect::<Vec<_>>(),
    })
}

/// Frequency and damping against the modal amplitude (log scale), one curve per μ, the
/// roots of ζ marked.
pub fn figure(a: &NlModeAnalysis) -> Figure {
    let panel = |title: &str, y: &str| Panel {
        title: title.into(),
        x_label: "modal amplitude a (m kg^0.5)".into(),
        y_label: y.into(),
        x_scale: Scale::Log,
        legend: squeal_report::LegendPosition::UpperLeft,
        ..Panel::default()
    };
    let mut freq = panel("(a) frequency", "frequency (Hz)");
    let mut damp = panel("(b) modal damping ratio", "zeta");
    for m in &a.modes {
        let name = format!("mu = {}", fmt_sig(m.mu, 5));
        let p = &m.mode.points;
        freq.series.push(Series::line(
            &name,
            p.iter().map(|p| (p.a, p.omega / TAU)).collect(),
        ));
        damp.series.push(Series::line(
            name.as_str(),
            p.iter().map(|p| (p.a, p.zeta)).collect(),
        ));
        let roots: Vec<&_> = m.mode.cycles.iter().map(|c| &c.point).collect();
        if !roots.is_empty() {
            freq.series.push(Series::markers(
                "",
                roots.iter().map(|p| (p.a, p.omega / TAU)).collect(),
            ));
            damp.series.push(Series::markers(
                "",
                roots.iter().map(|p| (p.a, 0.0)).collect(),
            ));
        }
    }
    damp.annotations.push(Annotation::HLine {
        y: 0.0,
        label: "limit cycles".into(),
        dash: Dash::Dashed,
    });
    Figure {
        title: format!(
            "Nonlinear squeal mode (EPMC): mu0 = {}",
            fmt_sig(a.normal_form.mu0, 5)
        ),
        layout: Layout::Row,
        panels: vec![freq, damp],
        panel_size: (560, 380),
        ..Figure::default()
    }
}

/// Writes `nlmode.csv`, `nlmode.json` and `nlmode.svg`/`.png` into `dir`.
pub fn write(dir: &Path, a: &NlModeAnalysis) -> Result<()> {
    crate::study::create_dir(dir)?;
    table(a).write_csv(&dir.join("nlmode.csv"))?;
    squeal_io::atomic_write_bytes(
        &dir.join("nlmode.json"),
        json_text(&json(a), "the nonlinear modes")?.as_bytes(),
    )?;
    squeal_report::write_svg_and_png(&figure(a), &dir.join("nlmode"))?;
    Ok(())
}
