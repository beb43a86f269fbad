//! What the unstable mode is made of ([`squeal_brake::participation`]): at the Hopf point and at
//! every friction value of the sweep where its branch is unstable, its kinetic-energy shares
//! by part, by frictionless mode of the assembled brake and by each part's reduced coordinate
//! (Craig–Bampton constraint modes and fixed-interface modes), with frequencies and the disc's
//! nodal diameters (`contributions.csv`, `contributions_reduced.csv`,
//! `contributions_sweep.csv`, `contributions.json`, the bar chart `contributions.svg`/`.png`).

use crate::error::{Result, json_text};
use crate::model::Model;
use crate::pictures::nodal_diameters;
use crate::shapes::{Meshes, expand};
use faer::c64;
use squeal_brake::analysis::LinearStability as Stability;
use squeal_brake::participation::{dof_shares, modal_shares, part_sums, physical};
use squeal_reduce::rom::DofLabel;
use squeal_report::Table;
use std::fmt::Write as _;
use std::path::Path;

/// How many contributors the text, the JSON and the chart list.
pub const TOP: usize = 8;

/// One contributor: a frictionless mode or a part's reduced coordinate.
#[derive(Clone, Debug, PartialEq)]
pub struct Contributor {
    /// `mode 23` or `disc fixed-interface mode 12` or `pad constraint modes`.
    pub name: String,
    /// Its part (reduced coordinates) or `brake` (frictionless modes).
    pub part: String,
    /// Its frequency (Hz): the frictionless or fixed-interface frequency; `None` for
    /// constraint modes.
    pub frequency_hz: Option<f64>,
    /// Its share of the mode's kinetic energy.
    pub share: f64,
    /// The complex coefficient scaled so that the largest is 1 (frictionless modes).
    pub coefficient: Option<c64>,
    /// The disc's nodal diameters in it, when classified.
    pub nodal_diameters: Option<usize>,
}

/// A complex mode's make-up.
#[derive(Clone, Debug, PartialEq)]
pub struct Contributions {
    /// Friction value and frequency (Hz) of the mode.
    pub mu: f64,
    pub frequency_hz: f64,
    /// Each part's kinetic-energy share (disc first).
    pub parts: Vec<(String, f64)>,
    /// Every frictionless mode, largest share first.
    pub modes: Vec<Contributor>,
    /// Every reduced coordinate, the constraint modes of each part as one row, largest share
    /// first.
    pub reduced: Vec<Contributor>,
}

/// The parts' names and dof ranges, disc first.
fn parts(m: &Model) -> Vec<(String, std::ops::Range<usize>)> {
    std::iter::once(("disc".to_string(), m.layout.disc.clone()))
        .chain(m.layout.pads.iter().cloned())
        .collect()
}

/// The make-up of the complex mode with modal coordinates `q` (lifted) at `mu`.
pub fn of_mode(m: &Model, st: &Stability, mu: f64, lambda: c64, q: &[c64]) -> Contributions {
    let basis = &st.reference.basis;
    let shares = modal_shares(q);
    let mut modes: Vec<Contributor> = (0..q.len())
        .map(|j| Contributor {
            name: format!("mode {}", j + 1),
            part: "brake".into(),
            frequency_hz: Some(basis.omega[j] / std::f64::consts::TAU),
            share: shares.energy[j],
            coefficient: Some(shares.coefficients[j]),
            nodal_diameters: None,
        })
        .collect();
    modes.sort_by(|a, b| b.share.total_cmp(&a.share));
    let x = physical(&basis.phi, q);
    let c = dof_shares(&m.brake.m, &x);
    let ps = parts(m);
    let sums = part_sums(&c, &ps.iter().map(|p| p.1.clone()).collect::<Vec<_>>());
    let mut reduced = Vec::new();
    for (name, r) in &ps {
        let Some(part) = m.rom.part(name) else {
            continue;
        };
        let mut constraint = 0.0;
        // An interface reduction changed the part's coordinates ([reduction] interface): its
        // labels no longer name them (their count differs), so the part is one contributor.
        if part.info.dofs.len() != r.len() {
            reduced.push(Contributor {
                name: format!("{name} (interface-reduced coordinates)"),
                part: name.clone(),
                frequency_hz: None,
                share: c[r.clone()].iter().sum(),
                coefficient: None,
                nodal_diameters: None,
            });
            continue;
        }
        for (k, label) in part.info.dofs.iter().enumerate() {
            match label {
                DofLabel::Mode { mode } => reduced.push(Contributor {
                    name: format!("{name} fixed-interface mode {}", mode + 1),
                    part: name.clone(),
                    frequency_hz: part.info.fixed_interface_hz.get(*mode).copied(),
                    share: c[r.start + k],
                    coefficient: None,
                    nodal_diameters: None,
                }),
                _ => constraint += c[r.start + k],
            }
        }
        reduced.push(Contributor {
            name: format!("{name} constraint modes"),
            part: name.clone(),
            frequency_hz: None,
            share: constraint,
            coefficient: None,
            nodal_diameters: None,
        });
    }
    reduced.sort_by(|a, b| b.share.total_cmp(&a.share));
    Contributions {
        mu,
        frequency_hz: lambda.im / std::f64::consts::TAU,
        parts: ps.into_iter().map(|p| p.0).zip(sums).collect(),
        modes,
        reduced,
    }
}

/// The make-up at the Hopf point (the mode at the upper end of its bracket).
pub fn at_hopf(m: &Model, st: &Stability) -> Option<Contributions> {
    let h = st.sweep.hopf.as_ref()?;
    let sp = &h.point.spectrum;
    Some(of_mode(
        m,
        st,
        h.mu0,
        sp.values[h.index],
        &sp.modal(h.index),
    ))
}

/// The make-up of the Hopf branch at every swept friction value where it is unstable.
pub fn along_sweep(m: &Model, st: &Stability) -> Vec<Contributions> {
    let Some(h) = &st.sweep.hopf else {
        return Vec::new();
    };
    let tau = super::threshold(m, st);
    let sw = &st.sweep;
    (0..sw.points.len())
        .filter(|&k| sw.value(h.branch, k).re > tau)
        .map(|k| {
            let j = sw.branches[h.branch][k];
            let sp = &sw.points[k].spectrum;
            of_mode(m, st, sp.mu, sp.values[j], &sp.modal(j))
        })
        .collect()
}

/// Classifies the disc's motion in the first `TOP` contributors by nodal diameters (the disc
/// part of a frictionless mode, or a disc fixed-interface mode expanded on its mesh). Left
/// unclassified when the meshes or the basis are not at hand.
pub fn classify(m: &Model, st: &Stability, c: &mut Contributions, meshes: &Meshes) {
    let Some(disc) = m.rom.part("disc") else {
        return;
    };
    let r = m.layout.disc.clone();
    let phi = &st.reference.basis.phi;
    let nd = |x: Vec<f64>| -> Option<usize> {
        let u = expand(disc, &meshes.disc, &m.disc_mesh, &x).ok()?;
        let u: Vec<c64> = u.iter().map(|v| c64::new(*v, 0.0)).collect();
        nodal_diameters(&meshes.disc, &u).map(|n| n.dominant)
    };
    for k in 0..TOP.min(c.modes.len()) {
        let j: usize = c.modes[k].name[5..].parse::<usize>().unwrap_or(1) - 1;
        c.modes[k].nodal_diameters = nd(r.clone().map(|i| phi[(i, j)]).collect());
    }
    for k in 0..TOP.min(c.reduced.len()) {
        if c.reduced[k].part != "disc" {
            continue;
        }
        let Some(mode) = c.reduced[k]
            .name
            .strip_prefix("disc fixed-interface mode ")
            .and_then(|s| s.parse::<usize>().ok())
        else {
            continue;
        };
        let Some(col) = disc
            .info
            .dofs
            .iter()
            .position(|d| *d == DofLabel::Mode { mode: mode - 1 })
        else {
            continue;
        };
        c.reduced[k].nodal_diameters = nd((0..r.len()).map(|i| (i == col) as u8 as f64).collect());
    }
}

fn describe(c: &Contributor) -> String {
    let f = c
        .frequency_hz
        .map_or(String::new(), |f| format!(" at {f:.1} Hz"));
    let nd = c
        .nodal_diameters
        .map_or(String::new(), |n| format!(", disc {n} ND"));
    format!("{}{f}{nd} {:.1}%", c.name, 100.0 * c.share)
}

/// The lines `squeal stability` prints: by part, then the first three frictionless modes and
/// reduced coordinates.
pub fn text(c: &Contributions) -> String {
    let mut out = String::new();
    let parts: Vec<String> = c
        .parts
        .iter()
        .map(|(n, s)| format!("{n} {:.1}%", 100.0 * s))
        .collect();
    let _ = writeln!(
        out,
        "unstable mode at mu0 ({:.2} Hz), shares of its kinetic energy: by part {}",
        c.frequency_hz,
        parts.join(", ")
    );
    let list = |v: &[Contributor]| {
        v.iter()
            .take(3)
            .map(describe)
            .collect::<Vec<_>>()
            .join("; ")
    };
    let _ = writeln!(out, "  frictionless modes of the brake: {}", list(&c.modes));
    let _ = writeln!(out, "  reduced coordinates: {}", list(&c.reduced));
    out
}

fn rows(t: &mut Table, mu: f64, v: &[Contributor]) {
    for (k, c) in v.iter().enumerate() {
        t.push_row([
            format!("{mu}"),
            (k + 1).to_string(),
            c.name.clone(),
            c.part.clone(),
            c.frequency_hz.map_or(String::new(), |f| format!("{f}")),
            format!("{:e}", c.share),
            c.coefficient
                .map_or(String::new(), |z| format!("{:e}", z.re)),
            c.coefficient
                .map_or(String::new(), |z| format!("{:e}", z.im)),
            c.nodal_diameters.map_or(String::new(), |n| n.to_string()),
        ]);
    }
}

const HEADER: [&str; 9] = [
    "mu",
    "rank",
    "contributor",
    "part",
    "frequency_hz",
    "energy_share",
    "coefficient_re",
    "coefficient_im",
    "nodal_diameters",
];

fn contributor_json(c: &Contributor) -> serde_json::Value {
    serde_json::json!({
        "name": c.name, "part": c.part, "frequency_hz": c.frequency_hz,
        "energy_share": c.share,
        "coefficient": c.coefficient.map(|z| [z.re, z.im]),
        "nodal_diameters": c.nodal_diameters,
    })
}

/// `contributions.csv` (frictionless modes), `contributions_reduced.csv` (reduced
/// coordinates), `contributions_sweep.csv` (by part and the first three modes at every
/// unstable friction value) and `contributions.json`.
pub fn write(dir: &Path, c: &Contributions, sweep: &[Contributions]) -> Result<()> {
    let mut t = Table::new(HEADER);
    rows(&mut t, c.mu, &c.modes);
    t.write_csv(&dir.join("contributions.csv"))?;
    let mut t = Table::new(HEADER);
    rows(&mut t, c.mu, &c.reduced);
    t.write_csv(&dir.join("contributions_reduced.csv"))?;
    let mut header = vec!["mu".to_string(), "frequency_hz".to_string()];
    header.extend(c.parts.iter().map(|p| format!("share_{}", p.0)));
    for k in 1..=3 {
        header.push(format!("mode_{k}"));
        header.push(format!("mode_{k}_share"));
    }
    let mut t = Table::new(header);
    for s in sweep {
        let mut row = vec![format!("{}", s.mu), format!("{}", s.frequency_hz)];
        row.extend(s.parts.iter().map(|p| format!("{:e}", p.1)));
        for m in s.modes.iter().take(3) {
            row.push(m.name[5..].to_string());
            row.push(format!("{:e}", m.share));
        }
        t.push_row(row);
    }
    t.write_csv(&dir.join("contributions_sweep.csv"))?;
    let json = serde_json::json!({
        "mu": c.mu,
        "frequency_hz": c.frequency_hz,
        "normalization": "energy fractions: |q_j|^2 / sum |q|^2 on the mass-normalized frictionless modes (sum 1); reduced coordinates Re(conj(x_i) (M x)_i) / x^H M x (sum 1, each part's sum its kinetic-energy share); coefficients q_j / q_max (Ansys CMCC up to one complex factor)",
        "parts": c.parts.iter().map(|(n, s)| serde_json::json!({"part": n, "energy_share": s})).collect::<Vec<_>>(),
        "modes": c.modes.iter().take(TOP).map(contributor_json).collect::<Vec<_>>(),
        "reduced": c.reduced.iter().take(TOP).map(contributor_json).collect::<Vec<_>>(),
        "unstable_friction_values": sweep.len(),
    });
    squeal_io::atomic_write_bytes(
        &dir.join("contributions.json"),
        json_text(&json, "the mode contributions")?.as_bytes(),
    )?;
    Ok(())
}

/// A short tick label: `23` for frictionless mode 23, `d12` / `p7` for fixed-interface modes
/// of the disc / a pad, `dC` / `pC` for their constraint modes.
fn tick(c: &Contributor) -> String {
    let number = c.name.rsplit(' ').next().unwrap_or("");
    let initial = c.part.chars().next().unwrap_or('?');
    match (c.part.as_str(), c.frequency_hz) {
        ("brake", _) => number.to_string(),
        (_, None) => format!("{initial}C"),
        _ => format!("{initial}{number}"),
    }
}

/// `contributions.svg` / `.png`: the first [`TOP`] frictionless modes and reduced coordinates
/// as bars of their kinetic-energy share.
pub fn write_chart(dir: &Path, c: &Contributions) -> Result<()> {
    use squeal_report::{Figure, LegendPosition, Panel, Series, write_svg_and_png};
    let panel = |title: &str, x_label: &str, v: &[Contributor]| {
        let top: Vec<&Contributor> = v.iter().take(TOP).collect();
        Panel {
            title: title.into(),
            x_label: x_label.into(),
            y_label: "share of the kinetic energy (%)".into(),
            x_ticks: top
                .iter()
                .enumerate()
                .map(|(k, c)| ((k + 1) as f64, tick(c)))
                .collect(),
            x_range: Some((0.3, top.len() as f64 + 0.7)),
            series: vec![Series::bars(
                "share",
                top.iter()
                    .enumerate()
                    .map(|(k, c)| ((k + 1) as f64, 100.0 * c.share))
                    .collect(),
            )],
            legend: LegendPosition::None,
            ..Panel::default()
        }
    };
    let fig = Figure {
        title: format!(
            "What the unstable mode is made of at μ0 = {:.5} ({:.1} Hz)",
            c.mu, c.frequency_hz
        ),
        panels: vec![
            panel(
                "(a) frictionless modes of the brake",
                "mode number",
                &c.modes,
            ),
            panel(
                "(b) reduced coordinates",
                "d/p: disc/pad fixed-interface mode; C: constraint modes",
                &c.reduced,
            ),
        ],
        ..Figure::default()
    };
    write_svg_and_png(&fig, &dir.join("contributions"))?;
    Ok(())
}
