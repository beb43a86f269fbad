//! The report's section on what the unstable mode is made of and what moves μ0, from the
//! results of this run ([`crate::stability::contributions`],
//! [`crate::stability::sensitivities`]).

use super::{PICTURES, RunResults};
use crate::error::Result;
use crate::shapes::Meshes;
use crate::stability::{contributions, sensitivities};
use squeal_report::format::fmt_sig;
use squeal_report::{Section, Table};
use std::path::Path;

/// Rows of the report's sensitivity table.
const SENSITIVITY_ROWS: usize = 10;

fn contributors_table(v: &[contributions::Contributor]) -> Table {
    let mut t = Table::new([
        "contributor",
        "frequency (Hz)",
        "disc nodal diameters",
        "share of the kinetic energy",
    ]);
    for c in v.iter().take(contributions::TOP) {
        t.push_row([
            c.name.clone(),
            c.frequency_hz.map_or("-".into(), |f| format!("{f:.1}")),
            c.nodal_diameters.map_or("-".into(), |n| n.to_string()),
            format!("{:.1} %", 100.0 * c.share),
        ]);
    }
    t
}

/// The section, `None` without a Hopf point. Writes the bar chart into the report's pictures.
pub fn section(
    r: &RunResults<'_>,
    meshes: Option<&Meshes>,
    pics: &Path,
) -> Result<Option<Section>> {
    let (m, st) = (r.model, r.stability);
    let Some(mut c) = contributions::at_hopf(m, st) else {
        return Ok(None);
    };
    if let Some(meshes) = meshes {
        contributions::classify(m, st, &mut c, meshes);
    }
    contributions::write_chart(pics, &c)?;
    let parts: Vec<String> = c
        .parts
        .iter()
        .map(|(n, s)| format!("{n} {:.1} %", 100.0 * s))
        .collect();
    let mut text = format!(
        "The unstable mode at μ0 ({:.1} Hz) in the frictionless modes of the assembled brake and \
         in each part's Craig–Bampton coordinates (constraint modes, fixed-interface modes): \
         shares of its kinetic energy, `|q_j|² / Σ|q|²` on the mass-normalized modes (the \
         complex coefficients, Ansys' CMCC up to one complex factor, are in \
         [stability/contributions.csv](stability/contributions.csv)). By part: {}.",
        c.frequency_hz,
        parts.join(", ")
    );
    let mut tables = vec![
        (
            contributors_table(&c.modes),
            "Frictionless modes of the brake".to_string(),
        ),
        (
            contributors_table(&c.reduced),
            "Reduced coordinates of the parts".to_string(),
        ),
    ];
    // Undamped, μ0 is a coalescence (a double eigenvalue): no slope, no sensitivities.
    let ranked = if crate::caveats::undamped(st) {
        None
    } else {
        match sensitivities::compute(m, st) {
            // Dampers make D full: the sensitivities are not computed (the stability stage's
            // text says so), the report goes on without them.
            Err(crate::error::PipelineError::Brake(
                squeal_brake::BrakeError::NeedsDiagonalDamping { .. },
            )) => None,
            other => other?,
        }
    };
    if let Some(s) = ranked {
        let mut t = Table::new([
            "change by +1 %",
            "μ0 moves by",
            "Re λ moves by (1/s)",
            "f0 moves by (Hz)",
        ]);
        for row in s.rows.iter().take(SENSITIVITY_ROWS) {
            let d = row.mu0_per_percent();
            t.push_row([
                row.name.clone(),
                format!("{} ({:+.3} %)", fmt_sig(d, 4), 100.0 * d / s.state.mu),
                fmt_sig(0.01 * row.rate.dlambda.re, 4),
                fmt_sig(0.01 * row.rate.dfrequency_hz, 4),
            ]);
        }
        text.push_str(&format!(
            "\n\nWhat moves μ0: derivatives from the left and right eigenvectors at the Hopf \
             point, the static equilibrium's change included (a larger μ0 is a quieter brake). \
             dRe λ/dμ = {} 1/s there. Every parameter: \
             [stability/sensitivities.csv](stability/sensitivities.csv).",
            fmt_sig(s.dlambda_dmu.re, 4)
        ));
        tables.push((t, "What moves μ0".to_string()));
    }
    Ok(Some(Section {
        heading: "What the unstable mode is made of, and what moves μ0".into(),
        text,
        figures: vec![(
            Path::new(PICTURES).join("contributions"),
            "Shares of the unstable mode's kinetic energy at μ0: (a) by frictionless mode, (b) by reduced coordinate".into(),
        )],
        tables,
        ..Section::default()
    }))
}

/// `, 84.2 dB(A) at the microphone (x, y, z) m (squeal by SAE J2521's 70 dB(A))` for the
/// limit cycle of the run (Rayleigh integral, the run's first microphone), or why not.
pub fn cycle_level(r: &RunResults<'_>, sol: &squeal_chbm::ChbmSolution) -> String {
    use crate::sound::{BrakeSurface, SQUEAL_DBA, SoundOptions};
    let level = BrakeSurface::new(r.scene, r.model, &crate::model::quiet).and_then(|s| {
        let mic = s.first_microphone(r.sound);
        let opts = SoundOptions {
            microphones: vec![mic],
            ..r.sound.clone()
        };
        let snd = s.cycle_sound(&sol.coeffs, sol.harmonics, sol.omega, &opts)?;
        Ok((snd.rayleigh_dba.first().copied(), mic))
    });
    match level {
        Ok((Some(l), mic)) => format!(
            ", **{l:.1} dB(A)** at the microphone ({:.3}, {:.3}, {:.3}) m ({} SAE J2521's {SQUEAL_DBA} dB(A))",
            mic[0],
            mic[1],
            mic[2],
            if l >= SQUEAL_DBA {
                "squeal by"
            } else {
                "below"
            }
        ),
        Ok((None, _)) => String::new(),
        Err(e) => format!(" (its sound not computed: {e})"),
    }
}
