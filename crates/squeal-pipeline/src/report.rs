//! The report of `squeal run`: `index.html` and `index.md` in the output folder, from the
//! results computed in this run (never read back from files).

use crate::model::Model;
use squeal_brake::analysis::Stability;
use squeal_chbm::ChbmSolution;
use squeal_report::format::fmt_sig;
use squeal_report::{Report, Section, Table};
use squeal_scene::Scene;
use std::path::PathBuf;

/// What `squeal run` computed, for its report.
pub struct RunResults<'a> {
    pub scene: &'a Scene,
    pub model: &'a Model,
    pub stability: &'a Stability,
    /// The friction and the CHBM solution, when a limit cycle was computed.
    pub chbm: Option<(f64, &'a ChbmSolution)>,
    /// The comparison's summary, when it ran.
    pub compare: Option<&'a serde_json::Value>,
    /// Wall time of each stage (s).
    pub timings: &'a [(String, f64)],
}

/// The report of a run.
pub fn build(r: &RunResults<'_>) -> Report {
    let scene = r.scene;
    let title = scene
        .file
        .title
        .clone()
        .unwrap_or_else(|| "squeal report".into());
    let mut sections = Vec::new();
    let mut model = Table::new(["item", "value"]);
    model.push_row(["scene".to_string(), scene.path.display().to_string()]);
    model.push_row([
        "disc mesh".to_string(),
        r.model.disc_mesh.display().to_string(),
    ]);
    model.push_row([
        "pad mesh".to_string(),
        r.model.pad_mesh.display().to_string(),
    ]);
    model.push_row([
        "interface".to_string(),
        scene.file.model.interface.get_ref().clone(),
    ]);
    model.push_row(["reduced dofs".to_string(), r.model.brake.size().to_string()]);
    model.push_row([
        "reduced model".to_string(),
        r.model.rom_path.display().to_string(),
    ]);
    sections.push(Section {
        heading: "Model".into(),
        text: String::new(),
        figures: vec![],
        tables: vec![(model, "The reduced brake".into())],
    });

    let sw = &r.stability.sweep;
    let mut t = Table::new(["quantity", "value"]);
    match &sw.hopf {
        Some(h) => {
            t.push_row(["Hopf point mu0".to_string(), fmt_sig(h.mu0, 6)]);
            t.push_row([
                "frequency at mu0 (Hz)".to_string(),
                fmt_sig(h.frequency_hz, 6),
            ]);
        }
        None => t.push_row(["Hopf point mu0".to_string(), "none in the band".to_string()]),
    }
    t.push_row([
        "valid band up to (Hz)".to_string(),
        fmt_sig(r.model.sweep.band.valid_max_hz, 5),
    ]);
    t.push_row([
        "coalescing modes (frictionless numbers)".to_string(),
        r.stability
            .pair
            .map_or("-".into(), |(a, b)| format!("{}, {}", a + 1, b + 1)),
    ]);
    sections.push(Section {
        heading: "Stability (section 3)".into(),
        text: "Real parts and frequencies of the coupling modes against friction; the Hopf point mu0 is the first \
               crossing of a real part through zero inside the band the model can speak for. The unstable mode \
               shape and the equilibria are in stability/shapes.vtm (ParaView)."
            .into(),
        figures: vec![(
            PathBuf::from("stability/stability"),
            "Figure 2: real parts and frequencies against mu".into(),
        )],
        tables: vec![(t, "Hopf point".into())],
    });

    if let Some((mu, s)) = r.chbm {
        let mut t = Table::new(["quantity", "value"]);
        let f = s.omega / (2.0 * std::f64::consts::PI);
        for (label, value) in [
            ("friction mu", fmt_sig(mu, 6)),
            ("harmonics", s.harmonics.to_string()),
            ("frequency (Hz)", fmt_sig(f, 8)),
            ("||f1|| / ||F_eq||", fmt_sig(s.f1, 3)),
            ("Re lambda (1/s)", fmt_sig(s.re_lambda, 3)),
            ("LM iterations", s.iterations.to_string()),
            ("time (ms)", fmt_sig(s.time.as_secs_f64() * 1e3, 3)),
            ("outcome", s.outcome.to_string()),
        ] {
            t.push_row([label.to_string(), value]);
        }
        sections.push(Section {
            heading: "Limit cycle (CHBM, sections 4-5)".into(),
            text: "The animated cycle on both meshes is chbm/cycle.pvd (ParaView: open, then Warp By Vector on 'oscillation').".into(),
            figures: vec![
                (PathBuf::from("chbm/limit_cycles"), "Figure 4: limit cycles at a pad and a disc contact point".into()),
                (PathBuf::from("chbm/convergence"), "Figures 6-7: convergence of Re(lambda) and of the residual".into()),
            ],
            tables: vec![(t, "CHBM solution".into())],
        });
    }

    if let Some(c) = r.compare {
        let mut figures = Vec::new();
        if let Some(list) = c.get("comparisons").and_then(|v| v.as_array()) {
            for entry in list {
                let Some(ratio) = entry.get("mu_ratio").and_then(|v| v.as_f64()) else {
                    continue;
                };
                figures.push((
                    PathBuf::from(format!("compare/mu_{ratio:.3}/limit_cycles")),
                    format!("CHBM over the time integration at {ratio} mu0"),
                ));
            }
        }
        sections.push(Section {
            heading: "CHBM against time integration".into(),
            text: "Tables 1-2 of the paper for this brake are in compare/mu_*/table1.csv and table2.csv.".into(),
            figures,
            tables: vec![],
        });
    }

    let mut t = Table::new(["stage", "wall time (s)"]);
    for (s, x) in r.timings {
        t.push_row([s.to_string(), format!("{x:.2}")]);
    }
    sections.push(Section {
        heading: "Timings".into(),
        text: String::new(),
        figures: vec![],
        tables: vec![(t, "Wall time per stage".into())],
    });
    Report {
        title,
        intro: "Made by `squeal run`: Coudeyras, Sinou & Nacivet (2009), The Constrained Harmonic Balance Method, for this scene.".into(),
        sections,
    }
}
