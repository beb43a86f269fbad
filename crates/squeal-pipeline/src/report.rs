//! The report of `squeal run`: `index.html` and `index.md` in the output folder, from the
//! results computed in this run (never read back from files), with the pictures it needs in
//! `report/`.
//!
//! The first screen holds the numbers an NVH engineer asks for first (the Hopf point, every
//! unstable mode in the band, the limit cycle at the contacts, the inputs) and the unstable
//! mode's picture; then the mode shapes, the stability figures, the limit cycle and its
//! animation, the comparison with time integration and a link to every file of the run.

use crate::compare::CompareSummary;
use crate::error::Result;
use crate::model::{Log, Model};
use crate::pictures::{ModePicture, write_cycle_animation, write_mode_picture};
use crate::shapes::Meshes;
use squeal_brake::analysis::LinearStability as Stability;
use squeal_chbm::ChbmSolution;
use squeal_report::format::fmt_sig;
use squeal_report::{
    Annotation, Dash, Figure, Panel, Report, Section, Series, Table, write_svg_and_png,
};
use squeal_scene::Scene;
use std::path::{Path, PathBuf};

mod files;
pub use files::is_report_file;
#[allow(unused_imports)]
use files::*;

mod cycles;
#[allow(unused_imports)]
use cycles::*;

mod summary;
#[allow(unused_imports)]
use summary::*;

/// What `squeal run` computed, for its report.
pub struct RunResults<'a> {
    pub scene: &'a Scene,
    pub model: &'a Model,
    pub stability: &'a Stability,
    /// The branch of limit cycles with their stability, when it was followed.
    pub branch: Option<&'a crate::branch::BranchAnalysis>,
    /// The scene's limit cycle, when the run computed it (shown as a result only when CHBM
    /// converged to a limit cycle).
    pub chbm: Option<&'a crate::cycle::LimitCycle>,
    /// The comparison with time integration, when it ran.
    pub compare: Option<&'a CompareSummary>,
    /// Wall time of each stage (s).
    pub timings: &'a [(String, f64)],
    /// How the limit cycle's sound is estimated (its microphones).
    pub sound: &'a crate::sound::SoundOptions,
}

mod makeup;

/// Folder of the report's own pictures, inside the output folder.
pub const PICTURES: &str = "report";

/// The report of a run in `out` (the output folder): writes its pictures into
/// `out/report/` and returns the report, whose [`Report::write`] then writes `index.html`
/// and `index.md` into `out`.
pub fn build(r: &RunResults<'_>, out: &Path, log: Log) -> Result<Report> {
    let pics = out.join(PICTURES);
    std::fs::create_dir_all(&pics).map_err(|error| crate::PipelineError::File {
        what: "creating the folder",
        path: pics.clone(),
        error,
    })?;
    let scene = r.scene;
    let title = scene
        .file
        .title
        .clone()
        .unwrap_or_else(|| "squeal report".into());
    // The pictures need the meshes and the bases; without them the report says so.
    let meshes = match Meshes::read(r.model, log) {
        Ok(m) if r.model.rom.parts.iter().all(|p| p.basis.is_some()) => Some(m),
        Ok(_) => None,
        Err(e) => {
            log(&format!("report: no mode pictures ({e})"));
            None
        }
    };
    let modes = mode_pictures(r, meshes.as_ref(), &pics, log);
    let mut sections = vec![summary_section(r, &modes)];
    sections.push(modes_section(r, &modes));
    sections.push(equilibrium_section(r));
    sections.push(stability_section(r, &pics)?);
    sections.extend(makeup::section(r, meshes.as_ref(), &pics)?);
    if crate::stability::verdict(r.model, r.stability).is_stable() {
        sections.push(Section {
            heading: "Limit cycles".into(),
            text: "Not computed: no mode goes unstable over the friction range swept, so there \
                   is no Hopf point for a branch of limit cycles to start from, nor a limit \
                   cycle for CHBM or time integration to find."
                .into(),
            ..Section::default()
        });
    } else {
        sections.push(branch_section(r.branch));
        if let Some(s) = chbm_section(r, meshes.as_ref(), &pics, log)? {
            sections.push(s);
        }
        sections.push(compare_section(r.compare));
    }
    sections.push(files_section(out));
    sections.push(timings_section(r));
    Ok(Report {
        title,
        intro: format!(
            "{}\n\nMade by `squeal run` from the scene `{}`, following Coudeyras, Sinou & Nacivet (2009), \
             *The Constrained Harmonic Balance Method*. The same report as Markdown: [index.md](index.md).",
            verdict_text(r, &modes),
            scene.path.display()
        ),
        sections,
    })
}

/// The verdict, first thing on the page (Markdown, one list): does the brake squeal, from
/// which μ and at what frequency, what the branch of limit cycles adds, and the limit cycle
/// at the scene's μ.
fn verdict_text(r: &RunResults<'_>, modes: &[(Unstable, Option<ModePicture>)]) -> String {
    use crate::stability::{Verdict, verdict};
    let v = verdict(r.model, r.stability);
    let mut lines = vec![match v {
        Verdict::Stable { from, to } => format!(
            "**Verdict: no squeal for μ in [{}, {}].** No mode in the band goes unstable over \
             this friction range, so there is no limit cycle: the branch, CHBM and the \
             comparison with time integration were not run.",
            crate::stability::short(from),
            crate::stability::short(to)
        ),
        Verdict::Squeals { mu0, frequency_hz } => format!(
            "**Verdict: this brake squeals** from μ0 = {} (the Hopf point) at {:.1} Hz{}.",
            fmt_sig(mu0, 5),
            frequency_hz,
            match modes.len() {
                0 | 1 => String::new(),
                _ => format!(
                    "; other instabilities in the band: {}",
                    modes[1..]
                        .iter()
                        .map(|(u, _)| format!(
                            "{:.0} Hz from μ ≈ {}",
                            u.frequency_hz,
                            fmt_sig(u.onset_mu, 3)
                        ))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            }
        ),
        Verdict::UnstableFromStart { mu, frequency_hz } => format!(
            "**Verdict: unstable already at μ = {}** ({:.1} Hz): no Hopf point in the range \
             swept; sweep from a lower μ to find where squeal starts.",
            fmt_sig(mu, 4),
            frequency_hz
        ),
    }];
    if let Some(b) = r.branch
        && let Some(m) = b.squeal_range().with_disturbance_from
        && m < b.mu0()
    {
        lines.push(format!(
            "Below μ0 a large enough disturbance can start squeal from μ = {} ({} μ0): the \
             branch of limit cycles has stable cycles there.",
            fmt_sig(m, 5),
            fmt_sig(m / b.mu0(), 4)
        ));
    }
    if let Some(lc) = r.chbm
        && lc.cycle().is_none()
    {
        lines.push(format!(
            "No limit cycle at the scene's μ = {}: {}.",
            fmt_sig(lc.mu, 5),
            no_cycle_reason(lc)
        ));
    }
    if let Some((mu, s)) = r.chbm.and_then(|lc| lc.cycle().map(|s| (lc.mu, s))) {
        let ratio = r.stability.sweep.hopf.as_ref().map_or(String::new(), |h| {
            format!(" = {} μ0, the scene's `[chbm]`", fmt_sig(mu / h.mu0, 4))
        });
        let closure = pair_motion(r.model, s)
            .into_iter()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map_or(String::new(), |(p, c, _, _)| {
                format!(
                    ", largest closure amplitude {:.2} µm (pair {})",
                    c * 1e6,
                    p + 1
                )
            });
        lines.push(format!(
            "Limit cycle at μ = {}{ratio}: {}, {:.1} Hz{closure}{}.",
            fmt_sig(mu, 5),
            s.outcome.label(),
            s.omega / std::f64::consts::TAU,
            makeup::cycle_level(r, s)
        ));
    }
    lines.join("\n\n")
}

/// A mode that goes unstable in the band.
struct Unstable {
    label: String,
    branch: usize,
    /// Where it starts: μ0 for the Hopf mode, the bracket of the crossing otherwise.
    onset: String,
    onset_mu: f64,
    frequency_hz: f64,
    /// The mode at the first sweep point past its onset (brake coordinates).
    shape: Vec<faer::c64>,
}

fn unstable_modes(st: &Stability) -> Vec<Unstable> {
    let sw = &st.sweep;
    let mut out = Vec::new();
    if let Some(h) = &sw.hopf {
        out.push(Unstable {
            label: "Hopf mode".into(),
            branch: h.branch,
            onset: format!("μ0 = {}", fmt_sig(h.mu0, 6)),
            onset_mu: h.mu0,
            frequency_hz: h.frequency_hz,
            shape: h.point.spectrum.shape(&st.reference.basis, h.index),
        });
    }
    for c in &crate::stability::other_instabilities(st) {
        let k = c.k + 1;
        out.push(Unstable {
            label: match out.len() + 1 {
                1 => "first instability".to_string(),
                2 => "second instability".to_string(),
                3 => "third instability".to_string(),
                n => format!("instability {n}"),
            },
            branch: c.branch,
            onset: format!("μ in [{}, {}]", fmt_sig(c.mu_lo, 4), fmt_sig(c.mu_hi, 4)),
            onset_mu: 0.5 * (c.mu_lo + c.mu_hi),
            frequency_hz: c.frequency_hz,
            shape: sw.points[k]
                .spectrum
                .shape(&st.reference.basis, sw.branches[c.branch][k]),
        });
    }
    out
}

/// Each unstable mode's picture (when the meshes could be read).
fn mode_pictures(
    r: &RunResults<'_>,
    meshes: Option<&Meshes>,
    pics: &Path,
    log: Log,
) -> Vec<(Unstable, Option<ModePicture>)> {
    unstable_modes(r.stability)
        .into_iter()
        .enumerate()
        .map(|(i, u)| {
            let pic = meshes.and_then(|m| {
                match write_mode_picture(pics, &format!("mode_{}", i + 1), r.model, m, &u.shape) {
                    Ok(p) => Some(p),
                    Err(e) => {
                        log(&format!(
                            "report: the picture of the {} failed: {e}",
                            u.label
                        ));
                        None
                    }
                }
            });
            (u, pic)
        })
        .collect()
}

/// Growth rate and damping ratio of branch `b` at the last sweep point.
fn growth_at_end(st: &Stability, b: usize) -> (f64, f64, f64) {
    let sw = &st.sweep;
    let k = sw.points.len() - 1;
    let l = sw.value(b, k);
    (
        sw.points[k].equilibrium.mu,
        l.re,
        -l.re / l.norm().max(f64::MIN_POSITIVE),
    )
}

/// Per contact pair over the cycle: half the peak-to-peak relative normal displacement
/// `g_p · x` (m), of the relative sliding velocity `h_p · x'` (m/s), each along the pair's own
/// normal and sliding direction, and the open fraction.
fn pair_motion(m: &Model, s: &ChbmSolution) -> Vec<(usize, f64, f64, f64)> {
    const SAMPLES: usize = 256;
    let half_range = |v: &[f64]| {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(*x), b.max(*x))
            });
        0.5 * (hi - lo)
    };
    // Σ_k a_k x_k(θ) (or its velocity) over a sparse vector of the brake's dofs.
    let combined = |vec: &[(usize, f64)], velocity: bool| -> Vec<f64> {
        let mut out = vec![0.0; SAMPLES + 1];
        for &(d, a) in vec {
            for (o, (x, v)) in out.iter_mut().zip(crate::chbm::cycle_points(s, d, SAMPLES)) {
                *o += a * if velocity { v } else { x };
            }
        }
        out
    };
    m.brake
        .pairs
        .iter()
        .enumerate()
        .map(|(p, pair)| {
            let closure = half_range(&combined(&pair.normal, false));
            let sliding = half_range(&combined(&pair.tangent, true));
            let open = s.open_fraction.get(p).copied().unwrap_or(f64::NAN);
            (p, closure, sliding, open)
        })
        .collect()
}

fn pct(x: f64) -> String {
    format!("{:.0} %", 100.0 * x)
}

fn modes_section(r: &RunResults<'_>, modes: &[(Unstable, Option<ModePicture>)]) -> Section {
    let mut figures = Vec::new();
    let mut t = Table::new(["mode", "frequency (Hz)", "nodal diameters of the disc"]);
    for (u, pic) in modes.iter().skip(1) {
        if let Some(p) = pic {
            figures.push((
                PathBuf::from(PICTURES).join(&p.file),
                format!(
                    "The {} at {:.0} Hz (same views and colours as Figure 1)",
                    u.label, u.frequency_hz
                ),
            ));
        }
    }
    for (u, pic) in modes {
        t.push_row([
            u.label.clone(),
            format!("{:.1}", u.frequency_hz),
            pic.as_ref()
                .and_then(|p| p.nodal.as_ref())
                .map_or("-".into(), |n| n.describe()),
        ]);
    }
    let text = if modes.iter().any(|(_, p)| p.is_some()) {
        "Each unstable mode as the real part of its complex shape, with the phase that makes its \
         largest component real. The mode shapes for ParaView (real and imaginary parts, on both \
         meshes) are in [stability/shapes.vtm](stability/shapes.vtm). Nodal diameters: the \
         out-of-plane motion of the disc's outer annulus, analysed over the angle."
            .to_string()
    } else if let Some(sentence) = summary::no_unstable_mode(r, modes) {
        sentence
    } else {
        "The mode pictures need the meshes and the bases of the reduced model; they could not \
         be made for this run (see the messages of `squeal run`)."
            .to_string()
    };
    let tables = match modes.is_empty() {
        true => Vec::new(),
        false => vec![(
            t,
            "Nodal-diameter classification of the unstable modes".into(),
        )],
    };
    Section {
        heading: "Mode shapes".into(),
        text,
        figures,
        tables,
        after: String::new(),
    }
}

/// The eigenvalue map: damping ratio against frequency of the in-band eigenvalues at μ = 0,
/// just past μ0 and at the largest μ swept.
fn eigenvalue_map(r: &RunResults<'_>, pics: &Path) -> Result<PathBuf> {
    let sw = &r.stability.sweep;
    let band = r.model.sweep.band;
    let last = sw.points.len() - 1;
    let mut ks = vec![0];
    if let Some(h) = &sw.hopf
        && let Some(k) = sw.points.iter().position(|p| p.equilibrium.mu >= h.mu0)
        && k != 0
        && k != last
    {
        ks.push(k);
    }
    ks.push(last);
    let mut series = Vec::new();
    for k in ks {
        let p = &sw.points[k];
        let pts: Vec<(f64, f64)> = p
            .spectrum
            .values
            .iter()
            .enumerate()
            .filter(|(j, _)| band.contains(p.spectrum.frequency_hz(*j)))
            .map(|(j, l)| {
                (
                    p.spectrum.frequency_hz(j),
                    -100.0 * l.re / l.norm().max(f64::MIN_POSITIVE),
                )
            })
            .collect();
        series.push(Series::markers(
            format!("μ = {}", fmt_sig(p.equilibrium.mu, 4)),
            pts,
        ));
    }
    let fig = Figure::single(
        "Eigenvalues of the brake in the band",
        Panel {
            title: "damping ratio against frequency (below zero: unstable)".into(),
            x_label: "frequency (Hz)".into(),
            y_label: "damping ratio ζ = -Re λ / |λ| (%)".into(),
            series,
            annotations: vec![Annotation::HLine {
                y: 0.0,
                label: "ζ = 0".into(),
                dash: Dash::Dashed,
            }],
            legend: squeal_report::LegendPosition::Outside,
            ..Panel::default()
        },
    );
    let stem = pics.join("eigenvalues");
    write_svg_and_png(&fig, &stem)?;
    Ok(PathBuf::from(PICTURES).join("eigenvalues"))
}

/// The static equilibrium of eq (14) at μ = 0, pair by pair: initial gap, closure, force.
fn equilibrium_section(r: &RunResults<'_>) -> Section {
    let m = r.model;
    let eq = &r.stability.reference.equilibrium;
    let mut t = Table::new([
        "pair",
        "initial gap (µm)",
        "geometric gap (µm)",
        "closure at equilibrium (µm)",
        "normal force (N)",
    ]);
    for (p, pair) in m.pairs.iter().enumerate() {
        t.push_row([
            format!(
                "{}{}",
                p + 1,
                if eq.penetrations[p] > 0.0 {
                    ""
                } else {
                    " (open)"
                }
            ),
            format!("{:.3}", pair.initial_gap * 1e6),
            format!("{:.3}", pair.geometric_gap * 1e6),
            format!("{:.3}", eq.penetrations[p] * 1e6),
            format!("{:.2}", eq.normal_forces[p]),
        ]);
    }
    Section {
        heading: "Static equilibrium (eq 14)".into(),
        text: format!(
            "The brake pressed by the clamp force of {:.0} N at μ = {}: {} of {} pairs closed,              carrying {:.1} N together. Initial gaps (positive: open) {}; the clamp force was              ramped in {} load step(s) ({} halved) with {} Newton iterations in all, to a              relative residual of {:.1e}. A pair's closure is its penetration δ = g·x − g0              (positive: closed), its force eq (8)'s F = k_l δ + k_nl δ³. Table:              [stability/equilibrium.csv](stability/equilibrium.csv).",
            m.params.piston_force,
            eq.mu,
            eq.closed_pairs(),
            eq.penetrations.len(),
            eq.total_normal_force(),
            crate::stability::gap_description(m),
            eq.load_steps,
            eq.rejected_load_steps,
            eq.iterations,
            eq.residual
        ),
        figures: vec![],
        tables: vec![(
            t.align_numbers_right(),
            "Each contact pair at equilibrium".into(),
        )],
        after: String::new(),
    }
}

fn stability_section(r: &RunResults<'_>, pics: &Path) -> Result<Section> {
    let sw = &r.stability.sweep;
    let tau = crate::stability::threshold(r.model, r.stability);
    let mut t = Table::new(["quantity", "value"]);
    if let Some(h) = &sw.hopf {
        t.push_row([
            "Hopf point μ0".to_string(),
            format!(
                "{} (bracket {} to {})",
                fmt_sig(h.mu0, 8),
                fmt_sig(h.bracket.0, 10),
                fmt_sig(h.bracket.1, 10)
            ),
        ]);
        t.push_row([
            "frequency at μ0 (Hz)".to_string(),
            fmt_sig(h.frequency_hz, 6),
        ]);
    }
    t.push_row([
        "friction values swept".to_string(),
        format!(
            "{} from {} to {}",
            sw.points.len(),
            fmt_sig(sw.points[0].equilibrium.mu, 3),
            fmt_sig(sw.points[sw.points.len() - 1].equilibrium.mu, 3)
        ),
    ]);
    t.push_row([
        "band (Hz)".to_string(),
        match r.model.sweep.band.user {
            Some((a, b)) => format!(
                "{a:.0} to {b:.0} (the scene's), within the model's valid band up to {:.0} \
                 (the highest kept fixed-interface frequency)",
                r.model.sweep.band.valid_max_hz
            ),
            None => format!(
                "up to {:.0} (the model's valid band: the highest kept fixed-interface frequency)",
                r.model.sweep.band.valid_max_hz
            ),
        },
    ]);
    t.push_row([
        "instability threshold".to_string(),
        format!(
            "Re λ > {:.2e} 1/s (64 ε ω_max: the eigensolver's round-off relative to the largest |λ|)",
            tau
        ),
    ]);
    for c in sw.crossings.iter().filter(|c| c.in_band) {
        t.push_row([
            format!("crossing at {:.0} Hz", c.frequency_hz),
            format!("μ in [{}, {}]", fmt_sig(c.mu_lo, 4), fmt_sig(c.mu_hi, 4)),
        ]);
    }
    // One row for all the crossings outside the band: one each buried those in it.
    let outside = sw.crossings.iter().filter(|c| !c.in_band).count();
    if outside > 0 {
        t.push_row([
            "crossings outside the band".to_string(),
            crate::stability::outside_band_text(&r.model.sweep.band, outside).replace("mu0", "μ0"),
        ]);
    }
    let map = eigenvalue_map(r, pics)?;
    Ok(Section {
        heading: "Stability against friction (section 3)".into(),
        text: "Real parts and frequencies of the modes against the friction coefficient μ: every \
               mode that goes unstable in the band is drawn, in colour, with its frequency in the \
               legend; grey dotted lines are stable modes near the Hopf frequency. μ0 is the first \
               crossing of a real part through zero inside the band the reduced model speaks for. \
               Tables: [stability/stability.csv](stability/stability.csv) (the figure's curves and \
               the number of unstable modes at each μ), \
               [stability/branches.csv](stability/branches.csv) (every branch), \
               [stability/summary.json](stability/summary.json)."
            .into(),
        figures: vec![
            (
                PathBuf::from("stability/stability"),
                "Real parts (a) and frequencies (b) against μ (the paper's Figure 2)".into(),
            ),
            (
                map,
                "Damping ratio against frequency of every eigenvalue in the band at three friction values: the unstable modes are the points below ζ = 0".into(),
            ),
        ],
        tables: vec![(t, "The sweep and its crossings".into())],
        after: String::new(),
    })
}

fn timings_section(r: &RunResults<'_>) -> Section {
    let mut t = Table::new(["stage", "wall time (s)"]);
    for (s, x) in r.timings {
        t.push_row([s.to_string(), format!("{x:.2}")]);
    }
    Section {
        heading: "Timings".into(),
        tables: vec![(t.align_numbers_right(), "Wall time per stage".into())],
        ..Section::default()
    }
}

/// Why the run has no limit cycle to show: the branch does not reach μ, or what CHBM ended on.
fn no_cycle_reason(lc: &crate::cycle::LimitCycle) -> String {
    match &lc.solved {
        None => "the branch of limit cycles from the Hopf point does not reach it (squeal branch shows where it goes)".into(),
        Some((_, s)) => format!("CHBM ended on {} (not shown as a result)", s.outcome),
    }
}

#[cfg(test)]
mod tests;
