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

/// The first screen: key numbers, the unstable modes, the inputs and the Hopf mode's picture.
fn summary_section(r: &RunResults<'_>, modes: &[(Unstable, Option<ModePicture>)]) -> Section {
    let st = r.stability;
    let m = r.model;
    let sw = &st.sweep;
    let mut key = Table::new(["", "value"]);
    match &sw.hopf {
        Some(h) => {
            key.push_row([
                "Hopf point μ0 (onset of squeal)".to_string(),
                format!("{} at {:.1} Hz", fmt_sig(h.mu0, 5), h.frequency_hz),
            ]);
            if let Some((a, b)) = st.pair {
                let f = |j: usize| st.reference.basis.omega[j] / std::f64::consts::TAU;
                key.push_row([
                    "coalescing modes (frictionless)".to_string(),
                    format!(
                        "#{} at {:.0} Hz (stays stable) and #{} at {:.0} Hz (goes unstable)",
                        a + 1,
                        f(a),
                        b + 1,
                        f(b)
                    ),
                ]);
            }
            if let Ok(Some(nf)) = crate::stability::normal_form(m, st) {
                key.push_row([
                    "Hopf bifurcation".to_string(),
                    format!(
                        "{} (first Lyapunov coefficient {:+.3e}){}",
                        nf.criticality(),
                        nf.l1,
                        if nf.criticality() == squeal_brake::criticality::Criticality::Subcritical
                        {
                            ": limit cycles exist below μ0, a large enough disturbance starts squeal there"
                        } else {
                            ""
                        }
                    ),
                ]);
            }
        }
        None => key.push_row([
            "Hopf point μ0".to_string(),
            format!(
                "none in the band over μ = {}..{}",
                fmt_sig(sw.points[0].equilibrium.mu, 3),
                fmt_sig(sw.points[sw.points.len() - 1].equilibrium.mu, 3)
            ),
        ]),
    }
    if let Some(b) = r.branch {
        let range = b.squeal_range();
        key.push_row([
            "squeal possible (branch of limit cycles)".to_string(),
            match range.with_disturbance_from {
                Some(m) if m < b.mu0() => format!(
                    "by itself from μ0 = {}; after a large enough disturbance from μ = {} ({} μ0{})",
                    fmt_sig(b.mu0(), 5),
                    fmt_sig(m, 5),
                    fmt_sig(m / b.mu0(), 5),
                    if range.at_fold { ", the fold" } else { "" }
                ),
                Some(_) => format!("by itself from μ0 = {}", fmt_sig(b.mu0(), 5)),
                None => format!(
                    "by itself from μ0 = {}; no stable limit cycle on the computed branch",
                    fmt_sig(b.mu0(), 5)
                ),
            },
        ]);
    }
    key.push_row([
        "unstable modes in the band".to_string(),
        if modes.is_empty() {
            "none".to_string()
        } else {
            modes
                .iter()
                .map(|(u, _)| {
                    format!(
                        "{:.0} Hz from μ ≈ {}",
                        u.frequency_hz,
                        fmt_sig(u.onset_mu, 3)
                    )
                })
                .collect::<Vec<_>>()
                .join("; ")
        },
    ]);
    if let Some(lc) = r.chbm
        && lc.cycle().is_none()
    {
        key.push_row([
            "limit cycle (CHBM)".to_string(),
            format!("none at μ = {}: {}", fmt_sig(lc.mu, 5), no_cycle_reason(lc)),
        ]);
    }
    if let Some((mu, s)) = r.chbm.and_then(|lc| lc.cycle().map(|s| (lc.mu, s))) {
        let f = s.omega / std::f64::consts::TAU;
        let hopf_f = sw.hopf.as_ref().map(|h| h.frequency_hz);
        key.push_row([
            "limit cycle (CHBM)".to_string(),
            format!(
                "at μ = {}{}: {}, {:.1} Hz{}",
                fmt_sig(mu, 5),
                sw.hopf.as_ref().map_or(String::new(), |h| format!(
                    " ({} μ0)",
                    fmt_sig(mu / h.mu0, 4)
                )),
                s.outcome.label(),
                f,
                hopf_f.map_or(String::new(), |h| format!(
                    " ({:+.1} Hz from the Hopf frequency)",
                    f - h
                ))
            ),
        ]);
        let motion = pair_motion(m, s);
        if let Some(&(p, c, _, _)) = motion.iter().max_by(|a, b| a.1.total_cmp(&b.1)) {
            key.push_row([
                "largest closure amplitude at a contact".to_string(),
                format!("{:.2} µm (pair {})", c * 1e6, p + 1),
            ]);
        }
        if let Some(&(p, _, v, _)) = motion.iter().max_by(|a, b| a.2.total_cmp(&b.2)) {
            key.push_row([
                "largest sliding-velocity amplitude at a contact".to_string(),
                format!("{:.1} mm/s (pair {})", v * 1e3, p + 1),
            ]);
        }
        let open: Vec<String> = motion
            .iter()
            .filter(|x| x.3 > 0.0)
            .map(|x| format!("pair {}: {}", x.0 + 1, pct(x.3)))
            .collect();
        key.push_row([
            "contact open over the cycle".to_string(),
            if open.is_empty() {
                "never: every pair stays closed".into()
            } else {
                format!("{} (the other pairs stay closed)", open.join(", "))
            },
        ]);
    }

    let mut unstable = Table::new([
        "mode",
        "unstable from",
        "frequency at onset (Hz)",
        "growth rate Re λ at μ = max (1/s)",
        "damping ratio ζ there (%)",
        "nodal diameters",
    ]);
    for (u, pic) in modes {
        let (mu_end, re, zeta) = growth_at_end(st, u.branch);
        unstable.push_row([
            u.label.clone(),
            u.onset.clone(),
            format!("{:.1}", u.frequency_hz),
            format!("{} (μ = {})", fmt_sig(re, 3), fmt_sig(mu_end, 3)),
            fmt_sig(100.0 * zeta, 3),
            pic.as_ref()
                .and_then(|p| p.nodal.as_ref())
                .map_or("-".into(), |n| n.dominant.to_string()),
        ]);
    }

    let mut inputs = Table::new(["input", "value"]);
    for part in &m.rom.parts {
        inputs.push_row([
            format!("{} mesh", part.info.name),
            format!(
                "{} ({} nodes, {} tet10 elements)",
                part.info.mesh.path, part.info.mesh.nodes, part.info.mesh.elements
            ),
        ]);
        for mat in &part.info.materials {
            inputs.push_row([
                format!("{} material {}", part.info.name, mat.name),
                describe_material(&mat.material),
            ]);
        }
    }
    let (line_pressure_bar, piston_area) = r.scene.piston_pressure_and_area();
    inputs.push_row([
        "clamp force".to_string(),
        format!(
            "{:.0} N ({} bar on {} m² of piston)",
            m.params.piston_force,
            fmt_sig(line_pressure_bar, 4),
            fmt_sig(piston_area, 4)
        ),
    ]);
    if let Ok((kl, knl, fit)) = r.scene.stiffness() {
        inputs.push_row([
            "contact stiffness per area (eq 8)".to_string(),
            format!(
                "k_l = {:.3e} Pa/m, k_nl = {:.3e} Pa/m³{}",
                kl,
                knl,
                if fit.is_some() {
                    " (fitted to the pad's compression curve)"
                } else {
                    ""
                }
            ),
        ]);
    }
    inputs.push_row([
        "contact".to_string(),
        format!(
            "{} pairs, {} interface; friction along the sliding direction",
            m.pairs.len(),
            r.scene.interface().map_or("?", |i| i.name())
        ),
    ]);
    inputs.push_row([
        "damping (eqs 12-13)".to_string(),
        format!(
            "ζ = {} % on every mode{}",
            fmt_sig(100.0 * m.damping.global_ratio, 3),
            match st.pair {
                Some((a, b)) => format!(
                    ", plus ζ1 = {} % on #{} and ζ2 = {} % on #{}",
                    fmt_sig(100.0 * m.damping.pair_ratios[0], 3),
                    a + 1,
                    fmt_sig(100.0 * m.damping.pair_ratios[1], 3),
                    b + 1
                ),
                None => String::new(),
            }
        ),
    ]);
    inputs.push_row([
        "reduced brake".to_string(),
        format!(
            "{} dofs (Craig–Bampton, {} fixed-interface modes per part), valid up to {:.0} Hz",
            m.brake.size(),
            r.scene.modes_per_part(),
            m.sweep.band.valid_max_hz
        ),
    ]);

    let mut figures = Vec::new();
    if let Some((u, Some(p))) = modes.first() {
        figures.push((
            PathBuf::from(PICTURES).join(&p.file),
            format!(
                "The {} at {:.0} Hz: three-quarter view, the disc from above (pad hidden), the brake from the side; colour: displacement magnitude over its largest (viridis, dark = 0, yellow = 1), shape exaggerated",
                u.label, u.frequency_hz
            ),
        ));
    }
    Section {
        heading: "Key numbers".into(),
        text: String::new(),
        figures,
        tables: vec![
            (key.align_numbers_right(), "What this brake does".into()),
            (
                unstable.align_numbers_right(),
                "Every mode that goes unstable in the band (ζ < 0: the vibration grows)".into(),
            ),
            (inputs, "Inputs".into()),
        ],
        after: String::new(),
    }
}

fn describe_material(m: &squeal_fe::ElasticMaterial) -> String {
    use squeal_fe::ElasticMaterial as E;
    match *m {
        E::Isotropic {
            young,
            poisson,
            density,
        } => format!(
            "E = {} GPa, ν = {}, ρ = {} kg/m³",
            fmt_sig(young / 1e9, 4),
            fmt_sig(poisson, 3),
            fmt_sig(density, 4)
        ),
        E::TransverselyIsotropic {
            young_plane,
            young_axial,
            density,
            ..
        } => format!(
            "transversely isotropic, E_plane = {} GPa, E_axial = {} GPa, ρ = {} kg/m³",
            fmt_sig(young_plane / 1e9, 4),
            fmt_sig(young_axial / 1e9, 4),
            fmt_sig(density, 4)
        ),
        E::Orthotropic { e, density, .. } => format!(
            "orthotropic, E = {}, {}, {} GPa, ρ = {} kg/m³",
            fmt_sig(e[0] / 1e9, 3),
            fmt_sig(e[1] / 1e9, 3),
            fmt_sig(e[2] / 1e9, 3),
            fmt_sig(density, 4)
        ),
    }
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
    } else if modes.is_empty() {
        "No mode goes unstable in the band.".to_string()
    } else {
        "The mode pictures need the meshes and the bases of the reduced model; they could not \
         be made for this run (see the messages of `squeal run`)."
            .to_string()
    };
    let _ = r;
    Section {
        heading: "Mode shapes".into(),
        text,
        figures,
        tables: vec![(
            t,
            "Nodal-diameter classification of the unstable modes".into(),
        )],
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
    for c in &sw.crossings {
        t.push_row([
            format!("crossing at {:.0} Hz", c.frequency_hz),
            format!(
                "μ in [{}, {}]{}",
                fmt_sig(c.mu_lo, 4),
                fmt_sig(c.mu_hi, 4),
                if c.in_band {
                    ""
                } else {
                    " (outside the band: not physical for this model)"
                }
            ),
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

fn chbm_section(
    r: &RunResults<'_>,
    meshes: Option<&Meshes>,
    pics: &Path,
    log: Log,
) -> Result<Option<Section>> {
    let Some(lc) = r.chbm else {
        return Ok(None);
    };
    let heading = "Limit cycle (CHBM, sections 4-5)".to_string();
    let Some(s) = lc.cycle() else {
        return Ok(Some(Section {
            heading,
            text: format!(
                "No limit cycle at the scene's friction μ = {}: {}.",
                fmt_sig(lc.mu, 6),
                no_cycle_reason(lc)
            ),
            figures: Vec::new(),
            tables: Vec::new(),
            after: String::new(),
        }));
    };
    let mu = lc.mu;
    let m = r.model;
    let mut figures = Vec::new();
    if let Some(meshes) = meshes {
        match write_cycle_animation(pics, "cycle", m, meshes, s, 20) {
            Ok((file, scale)) => figures.push((
                PathBuf::from(PICTURES).join(file),
                format!(
                    "The limit cycle, animated (one period in 20 frames, displacements about the mean exaggerated {scale:.0} times; colour: oscillation magnitude over its largest). The same cycle for ParaView: [chbm/cycle.pvd](chbm/cycle.pvd)"
                ),
            )),
            Err(e) => log(&format!("report: the animation failed: {e}")),
        }
    }
    figures.push((
        PathBuf::from("chbm/limit_cycles"),
        "Phase portraits of a pad and a disc contact point, normal direction (the paper's Figure 4)".into(),
    ));
    figures.push((
        PathBuf::from("chbm/convergence"),
        "Convergence of Re λ (a) and of the harmonic-balance residual (b); the dashed line marks the switch from one harmonic to all (the paper's Figures 6-7)".into(),
    ));
    let mut t = Table::new(["quantity", "value"]);
    let f = s.omega / std::f64::consts::TAU;
    for (label, value) in [
        ("friction μ", fmt_sig(mu, 6)),
        ("harmonics", s.harmonics.to_string()),
        ("frequency (Hz)", fmt_sig(f, 8)),
        ("‖f1‖ / ‖F_eq‖", fmt_sig(s.f1, 3)),
        ("Re λ (1/s)", fmt_sig(s.re_lambda, 3)),
        ("Levenberg–Marquardt iterations", s.iterations.to_string()),
        ("time (ms)", fmt_sig(s.time.as_secs_f64() * 1e3, 3)),
        ("outcome", s.outcome.to_string()),
    ] {
        t.push_row([label.to_string(), value]);
    }
    let mut pairs = Table::new([
        "pair",
        "closure amplitude (µm)",
        "sliding-velocity amplitude (mm/s)",
        "open over the cycle (%)",
    ]);
    for (p, c, v, open) in pair_motion(m, s) {
        pairs.push_row([
            (p + 1).to_string(),
            format!("{:.3}", c * 1e6),
            format!("{:.2}", v * 1e3),
            format!("{:.1}", 100.0 * open),
        ]);
    }
    let stability = lc.chosen.map_or(String::new(), |i| {
        format!(
            " It was reached along the branch of limit cycles from the Hopf point; its Floquet stability (Hill's method): {}.",
            lc.crossings[i].verdict()
        )
    });
    Ok(Some(Section {
        heading,
        text: format!(
            "The periodic self-excited vibration at the scene's friction ([chbm] in the scene), by the Constrained Harmonic \
             Balance Method.{stability} Amplitudes are half the peak-to-peak relative \
             motion of the pad and disc points of each pair (normal: closure; tangential: \
             sliding velocity). Files: [chbm/coefficients.csv](chbm/coefficients.csv) (Fourier \
             coefficients of every dof), [chbm/chbm.json](chbm/chbm.json)."
        ),
        figures,
        tables: vec![
            (
                pairs.align_numbers_right(),
                "The limit cycle at each contact pair".into(),
            ),
            (t, "CHBM solution".into()),
        ],
        after: String::new(),
    }))
}

fn branch_section(branch: Option<&crate::branch::BranchAnalysis>) -> Section {
    let Some(a) = branch else {
        return Section {
            heading: "Branch of limit cycles".into(),
            text:
                "The branch of limit cycles was not followed in this run (`squeal branch` does it)."
                    .into(),
            ..Section::default()
        };
    };
    let b = &a.branch;
    let mu0 = a.mu0();
    let mut events = Table::new(["event", "μ", "μ/μ0", "details"]);
    for f in &b.folds {
        events.push_row([
            "fold".to_string(),
            fmt_sig(f.parameter, 6),
            fmt_sig(f.parameter / mu0, 6),
            format!(
                "{:.1} Hz, pair closure {} µm peak to peak{}",
                f.omega / std::f64::consts::TAU,
                fmt_sig(f.closure * 1e6, 3),
                if f.refined {
                    ""
                } else {
                    "; between two points (a contact opens there)"
                }
            ),
        ]);
    }
    for bi in &a.bifurcations {
        let kind = match bi.kind {
            squeal_chbm::bifurcation::BifurcationKind::Fold => "stability change: fold".to_string(),
            squeal_chbm::bifurcation::BifurcationKind::PeriodDoubling => {
                "stability change: period doubling".to_string()
            }
            squeal_chbm::bifurcation::BifurcationKind::NeimarkSacker => format!(
                "stability change: Neimark–Sacker, second frequency {:.0} Hz",
                bi.torus_frequency_hz()
            ),
        };
        events.push_row([
            kind,
            fmt_sig(bi.parameter, 6),
            fmt_sig(bi.parameter / mu0, 6),
            format!(
                "unstable Floquet exponents {} → {}",
                bi.unstable.0, bi.unstable.1
            ),
        ]);
    }
    let pair = a.loudest_pair();
    let mut pts = Table::new([
        "μ/μ0",
        "frequency (Hz)",
        "harmonics",
        &format!("pair {} closure p2p (µm)", pair + 1),
        "largest open fraction (%)",
        "largest |multiplier|",
        "stability",
    ]);
    let n = b.points.len();
    for i in crate::branch::shown_points(n, 12) {
        let p = &b.points[i];
        let (rho, verdict) = match &a.floquet[i] {
            Ok(f) => (
                format!("{:.5}", f.largest_multiplier()),
                f.stability().to_string(),
            ),
            Err(e) => ("–".into(), format!("not computed ({e})")),
        };
        pts.push_row([
            format!("{:.5}", p.parameter / mu0),
            format!("{:.1}", p.frequency_hz()),
            p.harmonics.to_string(),
            fmt_sig(p.pairs[pair].peak_to_peak() * 1e6, 4),
            format!("{:.0}", 100.0 * p.largest_open_fraction()),
            rho,
            verdict,
        ]);
    }
    Section {
        heading: "Branch of limit cycles and their stability".into(),
        text: format!(
            "Every periodic vibration born at the Hopf point, followed in μ through its folds by \
             pseudo-arclength continuation of the harmonic balance (harmonics adapted along the \
             branch), each with its Floquet multipliers by Hill's method: a cycle is stable when \
             every multiplier lies inside the unit circle. {} cycles in {:.1} s, multipliers \
             alongside, done {:.1} s after them; the branch ended because {}. Files: [branch/branch.csv](branch/branch.csv), \
             [branch/branch.json](branch/branch.json).",
            n,
            b.time.as_secs_f64(),
            a.floquet_time.as_secs_f64(),
            b.stop
        ),
        figures: vec![(
            PathBuf::from("branch/branch"),
            "Bifurcation diagram: the loudest pair's peak-to-peak closure (a, and near μ0 in b), \
             the frequency (c) and the largest open fraction (d) against μ; stable cycles solid, \
             unstable dashed"
                .into(),
        )],
        tables: vec![
            (
                events,
                "Folds and stability changes along the branch".into(),
            ),
            (
                pts.align_numbers_right(),
                "Cycles along the branch (a selection; every one is in branch.csv)".into(),
            ),
        ],
        after: "Hill's method's own error is the trivial exponent's distance from zero (column \
                hill_error_per_s of branch.csv); a cycle whose leading exponent is within it is \
                reported as marginal."
            .into(),
    }
}

fn compare_section(compare: Option<&CompareSummary>) -> Section {
    let Some(c) = compare else {
        return Section {
            heading: "CHBM against time integration".into(),
            text: "Not run (`squeal run --no-compare`): `squeal compare` makes it.".into(),
            ..Section::default()
        };
    };
    let mut figures = Vec::new();
    let mut tables = Vec::new();
    let mut after = String::new();
    for l in &c.levels {
        let dir = PathBuf::from("compare").join(&l.folder);
        figures.push((
            dir.join("limit_cycles"),
            format!(
                "At {} μ0: CHBM's limit cycles over the reference limit cycle (the paper's Figure 4)",
                fmt_sig(l.ratio, 4)
            ),
        ));
        figures.push((
            dir.join("speed_accuracy"),
            format!("At {} μ0: wall time against error", fmt_sig(l.ratio, 4)),
        ));
        tables.push((
            l.table1.clone(),
            format!(
                "At {} μ0 (μ = {}): errors against the reference limit cycle (the paper's Table 1)",
                fmt_sig(l.ratio, 4),
                fmt_sig(l.mu, 6)
            ),
        ));
        tables.push((
            l.table2.clone(),
            format!(
                "At {} μ0: cost and storage (the paper's Table 2)",
                fmt_sig(l.ratio, 4)
            ),
        ));
        if !l.failures.is_empty() {
            after.push_str(&format!(
                "What did not converge at {} μ0:\n\n",
                fmt_sig(l.ratio, 4)
            ));
            for f in &l.failures {
                after.push_str(&format!("- {f}\n"));
            }
            after.push('\n');
        }
        let links: Vec<String> = l
            .files
            .iter()
            .map(|f| format!("[{f}]({})", dir.join(f).display()))
            .collect();
        after.push_str(&format!(
            "Files at {} μ0: {}.\n\n",
            fmt_sig(l.ratio, 4),
            links.join(", ")
        ));
    }
    Section {
        heading: "CHBM against time integration".into(),
        text: format!(
            "CHBM and variable-step BDF time integration of the whole brake (from the unstable \
             equilibrium to its steady cycle, at the tolerances a user would choose) checked \
             against the reference limit cycle, the brake's periodic orbit by shooting with its \
             own error stated. Errors: {}.",
            c.error_definition
        ),
        figures,
        tables,
        after,
    }
}

/// Whether `rel` (a `/`-separated path in the output folder) is a file of the report itself:
/// `index.html`, `index.md`, the tables' `table-N.csv` and the pictures in `report/`.
pub fn is_report_file(rel: &str) -> bool {
    rel == "index.html"
        || rel == "index.md"
        || (rel.starts_with("table-") && rel.ends_with(".csv") && !rel.contains('/'))
        || rel.starts_with(&format!("{PICTURES}/"))
}

/// Links to `files`, grouped by folder, one Markdown list item per folder.
fn links_by_folder(mut files: Vec<String>, label: impl Fn(&str) -> String) -> String {
    // By folder, then name: a sub-folder's files must not split its parent's list.
    files.sort_by_key(|f| {
        let p = Path::new(f);
        (
            p.parent().map(Path::to_path_buf),
            p.file_name().map(|n| n.to_os_string()),
        )
    });
    let mut by_folder: Vec<(String, Vec<String>)> = Vec::new();
    for f in files {
        let folder = Path::new(&f)
            .parent()
            .map(|p| p.display().to_string())
            .unwrap_or_default();
        match by_folder.last_mut() {
            Some((d, v)) if *d == folder => v.push(f),
            _ => by_folder.push((folder, vec![f])),
        }
    }
    let mut text = String::new();
    for (folder, files) in by_folder {
        let links: Vec<String> = files
            .iter()
            .map(|f| {
                let name = Path::new(f)
                    .file_name()
                    .map(|n| n.to_string_lossy().into_owned())
                    .unwrap_or_default();
                format!("[{name}]({}){}", url_path(f), label(f))
            })
            .collect();
        let label = if folder.is_empty() {
            "this folder".to_string()
        } else {
            format!("`{folder}/`")
        };
        text.push_str(&format!("- {label}: {}\n", links.join(", ")));
    }
    text
}

/// Every file of the output folder, as links grouped by folder (the report's own files
/// excepted: they are this page, its Markdown twin and the tables' CSV files linked from their
/// captions). The files an earlier run wrote and this run did not (the output folder's
/// manifest, [`squeal_io::folder`]) are listed apart, with their run: they are not this run's
/// results.
fn files_section(out: &Path) -> Section {
    let mut files = Vec::new();
    list_files(out, Path::new(""), &mut files);
    let earlier = squeal_io::folder::earlier_files(out);
    let is_earlier = |f: &String| earlier.iter().any(|e| e.path == url_like(f));
    let (old, own): (Vec<String>, Vec<String>) = files.into_iter().partition(is_earlier);
    let mut text = format!(
        "Every file of this run, relative to this page (CSV opens in a spreadsheet, SVG and \
         PNG in a browser, `.vtm`, `.vtu` and `.pvd` in ParaView, `.rom` with \
         `tools/rom/read_rom.py`):\n\n{}",
        links_by_folder(own, |_| String::new())
    );
    if !old.is_empty() {
        let run_of = |f: &str| {
            earlier
                .iter()
                .find(|e| e.path == url_like(f))
                .map_or(String::new(), |e| {
                    format!(" (run {}, {})", e.run, e.written)
                })
        };
        text.push_str(&format!(
            "\n**Not from this run:** these files were written by earlier runs into this folder \
             and not rewritten by this one, so they may describe another scene or other \
             settings (`{}` says which run wrote each):\n\n{}",
            squeal_io::folder::MANIFEST,
            links_by_folder(old, run_of)
        ));
    }
    Section {
        heading: "Files".into(),
        text,
        ..Section::default()
    }
}

/// A relative path with `/` separators, as the manifest keeps it.
fn url_like(p: &str) -> String {
    p.replace('\\', "/")
}

/// A relative path with `/` separators and unsafe bytes percent-encoded.
fn url_path(p: &str) -> String {
    let mut out = String::new();
    for b in p.replace('\\', "/").bytes() {
        if b.is_ascii_alphanumeric() || b"-_.~/".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

fn list_files(root: &Path, rel: &Path, out: &mut Vec<String>) {
    let Ok(entries) = std::fs::read_dir(root.join(rel)) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') {
            continue;
        }
        let path = rel.join(&name);
        match e.file_type() {
            Ok(t) if t.is_dir() => list_files(root, &path, out),
            Ok(t) if t.is_file() => {
                let own = rel.as_os_str().is_empty() && is_report_file(&name);
                if !own {
                    out.push(path.display().to_string());
                }
            }
            _ => {}
        }
    }
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
