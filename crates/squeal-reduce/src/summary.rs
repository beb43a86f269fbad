//! The reduction's summary as text: sizes, the timings per stage and part, the lowest
//! fixed-interface frequencies and the checks of eqs 5–7 (what `squeal reduce` prints).

use crate::brake::{BrakeReport, ModeChoice};
use crate::craig_bampton::{Stage, hz};
use crate::rom::ReducedModel;
use std::fmt::{self, Write};
use std::time::Duration;

/// Fixed-interface frequencies listed per part.
const FREQUENCIES_SHOWN: usize = 20;

/// The whole summary of a reduction whose file took `write_time` to write.
pub fn summary_text(model: &ReducedModel, report: &BrakeReport, write_time: Duration) -> String {
    let mut s = String::new();
    // Writing into a String cannot fail.
    let _ = write_summary(&mut s, model, report, write_time);
    s
}

fn write_summary(
    s: &mut String,
    model: &ReducedModel,
    report: &BrakeReport,
    write_time: Duration,
) -> fmt::Result {
    writeln!(s, "reduced brake: {} dofs", model.size())?;
    sizes(s, model, report)?;
    writeln!(s)?;
    timings(s, report, write_time)?;
    writeln!(s)?;
    frequencies(s, model)?;
    writeln!(s)?;
    checks(s, model, report)
}

/// One line per part: mesh, free dofs, boundary and modal dofs, the factor's size.
fn sizes(s: &mut String, model: &ReducedModel, report: &BrakeReport) -> fmt::Result {
    for (part, r) in model.parts.iter().zip(&report.parts) {
        let red = &r.reduce;
        writeln!(
            s,
            "  {:<5} {} ({} nodes, {} free dofs): {} boundary + {} modes = {} dofs; factor of K_II {} nonzeros ({:.0} MB)",
            part.info.name,
            r.mesh.path,
            r.mesh.nodes,
            red.free_dofs,
            red.boundary_dofs,
            red.modes,
            part.size(),
            red.nnz_factor,
            red.factor_bytes as f64 / 1e6
        )?;
        for w in &r.warnings {
            writeln!(s, "        warning: {w}")?;
        }
    }
    let choice = model.parts.first().and_then(|p| p.info.build.as_ref());
    if let Some(ModeChoice::Auto { fmax_hz, factor }) = choice.map(|b| b.modes) {
        writeln!(
            s,
            "  modes: all fixed-interface modes below {factor} x {fmax_hz} Hz = {} Hz",
            factor * fmax_hz
        )?;
    }
    Ok(())
}

/// Seconds per stage (rows) and part (columns), the file's writing and the total.
fn timings(s: &mut String, report: &BrakeReport, write_time: Duration) -> fmt::Result {
    writeln!(s, "timings (s)")?;
    write!(s, "  {:<24}", "stage")?;
    for p in &report.parts {
        write!(s, " {:>8}", p.name)?;
    }
    writeln!(s, " {:>8}", "total")?;
    for stage in Stage::ALL.into_iter().filter(|&st| st != Stage::Write) {
        let times: Vec<f64> = report
            .parts
            .iter()
            .map(|p| p.time(stage).as_secs_f64())
            .collect();
        write!(s, "  {:<24}", stage.label())?;
        for t in &times {
            write!(s, " {t:>8.2}")?;
        }
        writeln!(s, " {:>8.2}", times.iter().sum::<f64>())?;
    }
    let width = 9 * report.parts.len() + 8;
    let write = write_time.as_secs_f64();
    writeln!(s, "  {:<24} {write:>width$.2}", Stage::Write.label())?;
    let all = (report.total + write_time).as_secs_f64();
    writeln!(s, "  {:<24} {all:>width$.2}", "all")
}

/// The lowest fixed-interface frequencies of each part, side by side.
fn frequencies(s: &mut String, model: &ReducedModel) -> fmt::Result {
    writeln!(s, "lowest fixed-interface frequencies (Hz)")?;
    write!(s, "  {:>4}", "mode")?;
    for p in &model.parts {
        write!(s, " {:>12}", p.info.name)?;
    }
    writeln!(s)?;
    let longest = model.parts.iter().map(|p| p.info.fixed_interface_hz.len());
    let rows = longest.max().unwrap_or(0).min(FREQUENCIES_SHOWN);
    for i in 0..rows {
        write!(s, "  {:>4}", i + 1)?;
        for p in &model.parts {
            match p.info.fixed_interface_hz.get(i) {
                Some(f) => write!(s, " {f:>12.2}")?,
                None => write!(s, " {:>12}", "-")?,
            }
        }
        writeln!(s)?;
    }
    Ok(())
}

/// Eq 6's zero coupling, eq 7's unit modal mass, the eigenpairs' backward errors, the Sturm
/// count, the eigensolver's work, and the contact pairing.
fn checks(s: &mut String, model: &ReducedModel, report: &BrakeReport) -> fmt::Result {
    writeln!(s, "checks")?;
    for (part, r) in model.parts.iter().zip(&report.parts) {
        let red = &r.reduce;
        let sturm = match red.sturm {
            Some((bound, count)) => {
                format!("{count} eigenvalues below {:.1} Hz, as found", hz(bound))
            }
            None => "not checked".into(),
        };
        writeln!(s, "  {}", part.info.name)?;
        let coupling = red.coupling;
        writeln!(
            s,
            "    K_CN coupling ||K_CN|| / ||K||      {coupling:.2e}  (eq 6: zero)"
        )?;
        let deviation = red.modal_mass_deviation;
        writeln!(
            s,
            "    modal mass deviation max|M_NN - I| {deviation:.2e}  (before re-orthonormalization)"
        )?;
        writeln!(
            s,
            "    largest eigen backward error       {:.2e}",
            red.max_residual
        )?;
        writeln!(s, "    Sturm count                        {sturm}")?;
        let e = &red.eig;
        writeln!(
            s,
            "    eigensolver: {} solves with the factor (block {}, basis {}, {} restarts), {:.2} s of solves, Sturm check {:.2} s",
            e.operator_applications,
            e.block,
            e.ncv,
            e.restarts,
            e.operator_time.as_secs_f64(),
            e.sturm_time.as_secs_f64()
        )?;
    }
    let worst = report.pairs.iter().map(|p| p.distance).fold(0.0, f64::max);
    // The nodal interface pairs by projection, with no tolerance (recorded as 0).
    let how = if report.pairing_tolerance > 0.0 {
        format!("tolerance {:.2e} m", report.pairing_tolerance)
    } else {
        "each pad face node with its projection on the disc face".to_string()
    };
    writeln!(
        s,
        "  contact pairs: {} disc/pad points paired, farthest {:.2e} m apart ({how})",
        report.pairs.len(),
        worst,
    )
}
