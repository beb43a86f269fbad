//! The report's first section: the verdict's numbers, the model, the materials and the run's settings.

use super::*;

/// The first screen: key numbers, the unstable modes, the inputs and the Hopf mode's picture.
pub(super) fn summary_section(
    r: &RunResults<'_>,
    modes: &[(Unstable, Option<ModePicture>)],
) -> Section {
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
                "The {} at {:.0} Hz: three-quarter view, the disc from above (pad hidden), the brake from the side; colour: displacement magnitude over the largest of its own part (viridis, dark = 0, yellow = 1; {}), shape exaggerated",
                u.label,
                u.frequency_hz,
                peaks_text(&p.peaks)
            ),
        ));
    }
    let mut tables = vec![(key.align_numbers_right(), "What this brake does".into())];
    // A table without rows says nothing: a stable brake gets the sentence instead.
    let text = match no_unstable_mode(r, modes) {
        Some(sentence) => sentence,
        None => {
            tables.push((
                unstable.align_numbers_right(),
                "Every mode that goes unstable in the band (ζ < 0: the vibration grows)".into(),
            ));
            String::new()
        }
    };
    tables.push((inputs, "Inputs".into()));
    Section {
        heading: "Key numbers".into(),
        text,
        figures,
        tables,
        after: String::new(),
    }
}

/// The sentence that stands for the tables of unstable modes when there is none: `None` when
/// some mode goes unstable. "Stable in [a, b]" only when the verdict says so: a sweep unstable
/// from its first point is not called stable.
pub(super) fn no_unstable_mode(
    r: &RunResults<'_>,
    modes: &[(Unstable, Option<ModePicture>)],
) -> Option<String> {
    use crate::stability::{Verdict, short, verdict};
    if !modes.is_empty() {
        return None;
    }
    Some(match verdict(r.model, r.stability) {
        Verdict::Stable { from, to } => format!(
            "The brake is stable for μ in [{}, {}]: no mode in the band goes unstable (every \
             eigenvalue has ζ ≥ 0 at every friction value swept).",
            short(from),
            short(to)
        ),
        _ => "No single mode could be followed as going unstable in the band (see the \
              stability section)."
            .to_string(),
    })
}

/// How the parts' colour scales compare: "each part on its own scale; largest displacement
/// relative to the pad's: disc 18 %".
fn peaks_text(peaks: &[(String, f64)]) -> String {
    let Some((top, _)) = peaks.iter().max_by(|a, b| a.1.total_cmp(&b.1)) else {
        return String::new();
    };
    let others: Vec<String> = peaks
        .iter()
        .filter(|(n, _)| n != top)
        .map(|(n, r)| format!("{n} {} %", fmt_sig(100.0 * r, 2)))
        .collect();
    format!(
        "each part on its own scale; largest displacement relative to the {top}'s: {}",
        others.join(", ")
    )
}

pub(super) fn describe_material(m: &squeal_fe::ElasticMaterial) -> String {
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
