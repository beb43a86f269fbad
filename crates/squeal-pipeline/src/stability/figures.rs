//! The stability analysis' pictures: the paper's Figure 3 (real parts and frequencies against
//! μ) and the equilibria and unstable mode on the meshes for ParaView.

use super::{other_instabilities, shown_branches};
use crate::error::Result;
use crate::model::{Log, Model};
use crate::shapes::{Meshes, PartFields, normalize_mode, write_brake_vtu};
use squeal_brake::analysis::LinearStability as Stability;
use squeal_report::format::fmt_sig;
use squeal_report::{Annotation, Dash, Figure, Panel, Rgb, Series, write_svg_and_png};
use std::path::{Path, PathBuf};

/// The stability figure's width in CSS pixels: a report column in an 800 px wide window
/// (about 770 px) shows it at full size.
pub const STABILITY_WIDTH: u32 = 760;

/// The stability figure (paper Figure 2) as SVG and PNG.
pub fn write_figures(dir: &Path, st: &Stability, s: &Model) -> Result<()> {
    let sw = &st.sweep;
    let shown = shown_branches(st, s.sweep.band.valid_max_hz);
    let mut re = Panel {
        title: "(a) real parts".into(),
        x_label: "friction coefficient μ".into(),
        y_label: "Re λ (1/s)".into(),
        // The same series as panel (b), whose legend sits outside: none here to hide a curve.
        legend: squeal_report::LegendPosition::None,
        ..Panel::default()
    };
    let mut fr = Panel {
        title: "(b) frequencies".into(),
        x_label: "friction coefficient μ".into(),
        y_label: "frequency (Hz)".into(),
        legend: squeal_report::LegendPosition::Outside,
        ..Panel::default()
    };
    let others = other_instabilities(st);
    let mut k_other = 0;
    for (i, &b) in shown.iter().enumerate() {
        let f0 = sw.points[0].spectrum.frequency_hz(sw.branches[b][0]);
        let crossing = others.iter().find(|c| c.branch == b);
        let hopf_pair = sw.hopf.is_some()
            && i < 2
            && !(i == 1 && sw.hopf.as_ref().and_then(|h| h.partner).is_none());
        let name = match (i, sw.hopf.as_ref(), crossing) {
            (0, Some(h), _) => format!(
                "Mode 2, unstable from μ0 = {}, {:.0} Hz",
                fmt_sig(h.mu0, 4),
                h.frequency_hz
            ),
            (1, Some(_), _) if hopf_pair => {
                format!("Mode 1, coalescing partner ({f0:.0} Hz at μ = 0)")
            }
            (_, _, Some(c)) => format!(
                "unstable from μ ≈ {}, {:.0} Hz",
                fmt_sig(0.5 * (c.mu_lo + c.mu_hi), 3),
                c.frequency_hz
            ),
            _ => format!("stable mode, {f0:.0} Hz at μ = 0"),
        };
        let re_pts: Vec<(f64, f64)> = (0..sw.points.len())
            .map(|k| (sw.points[k].equilibrium.mu, sw.value(b, k).re))
            .collect();
        let f_pts: Vec<(f64, f64)> = (0..sw.points.len())
            .map(|k| {
                (
                    sw.points[k].equilibrium.mu,
                    sw.points[k].spectrum.frequency_hz(sw.branches[b][k]),
                )
            })
            .collect();
        let (mut a, mut c) = (
            Series::line(name.clone(), re_pts),
            Series::line(name, f_pts),
        );
        if crossing.is_some() {
            // Every further instability in a colour of its own, dashed.
            let colour = squeal_report::palette_color(3 + k_other);
            k_other += 1;
            a = a.with_color(colour).with_dash(Dash::DashDot);
            c = c.with_color(colour).with_dash(Dash::DashDot);
        } else if i >= 2 || !hopf_pair && i > 0 {
            a = a.with_color(Rgb::GREY).with_dash(Dash::Dotted);
            c = c.with_color(Rgb::GREY).with_dash(Dash::Dotted);
        }
        re.series.push(a);
        fr.series.push(c);
    }
    re.annotations.push(Annotation::HLine {
        y: 0.0,
        label: String::new(),
        dash: Dash::Dashed,
    });
    if let Some(h) = &sw.hopf {
        let label = format!("μ0 = {}", fmt_sig(h.mu0, 4));
        re.annotations.push(Annotation::VLine {
            x: h.mu0,
            label: label.clone(),
            dash: Dash::Dashed,
        });
        fr.annotations.push(Annotation::VLine {
            x: h.mu0,
            label,
            dash: Dash::Dashed,
        });
    }
    // (a) over (b), each as wide as a report's column: side by side (1120 px) the figure was
    // shrunk to 0.69 in an 800 px window, its text to 8 px and panel (b), beside its legend,
    // to 86 px wide (issue 22).
    let fig = Figure {
        title: "Stability against friction (the paper's Figure 2)".into(),
        panels: vec![re, fr],
        layout: squeal_report::Layout::Column,
        panel_size: (STABILITY_WIDTH, 380),
        ..Figure::default()
    };
    write_svg_and_png(&fig, &dir.join("stability"))?;
    Ok(())
}

/// The equilibria and the unstable mode on both meshes (`shapes.vtm` for ParaView); returns
/// the `.vtm` path.
pub fn write_shapes(dir: &Path, s: &Model, st: &Stability, log: Log) -> Result<PathBuf> {
    let meshes = Meshes::read(s, log)?;
    let mut fields = vec![PartFields {
        name: "equilibrium_frictionless",
        brake: st.reference.equilibrium.x.clone(),
    }];
    if let Some(h) = &st.sweep.hopf {
        let x = normalize_mode(&h.point.spectrum.shape(&st.reference.basis, h.index));
        fields.push(PartFields {
            name: "equilibrium_hopf",
            brake: h.point.equilibrium.x.clone(),
        });
        fields.push(PartFields {
            name: "unstable_mode_real",
            brake: x.iter().map(|v| v.re).collect(),
        });
        fields.push(PartFields {
            name: "unstable_mode_imag",
            brake: x.iter().map(|v| v.im).collect(),
        });
    }
    write_brake_vtu(dir, "shapes", &meshes.parts(s)?, &fields)
}
