//! The comparison's tables (the paper's Tables 1–2, the long-form measures, eq (50)'s power
//! ratios) and the notes printed with them; [`write_comparison`] writes them with the figures.

use super::figures::{figure4, figure5, growth, speed_accuracy};
use crate::error::Result;
use crate::model::{Log, Model};
use squeal_chbm::compare::{Comparison, TiRow};
use squeal_report::format::{fmt_sci, fmt_sig};
use squeal_report::{Table, write_svg_and_png};
use std::path::Path;

/// How the errors are defined (in every CSV header and the report).
pub const ERROR_DEFINITION: &str = "cycles aligned in time on the first harmonic of the reference's most moving contact dof; relative error = RMS over one cycle (in phase) and over the dofs of x_method - x_reference (mean included) / RMS of the reference's oscillation (mean removed); velocity likewise; 'all' = every physical dof, 'contact' = the dofs the contact forces act on; reference = the periodic orbit of the reduced brake by shooting (Newton on the start and the period, BDF at the reference tolerance), started from the CHBM cycle with the most harmonics; its stated own error = its difference from the same orbit solved at 10 x that tolerance (an upper bound: the BDF's error falls with the tolerance); a time integration that found no steady cycle is reported as failed, with no measures";

pub(super) fn pct(x: f64) -> String {
    fmt_sig(100.0 * x, 3)
}

/// Table 1's analogue: rows of quantities, a column per method; a failed time integration
/// says so in every row.
pub(super) fn table1(c: &Comparison) -> Table {
    let mut header = vec!["".to_string()];
    header.extend(c.chbm.iter().map(|r| format!("CHBM {}H", r.harmonics)));
    header.extend(c.ti.iter().map(|r| format!("BDF {:e}", r.rtol)));
    header.push(format!(
        "reference (shooting {:e}): stated own error",
        c.reference.reference.rtol
    ));
    let mut t = Table::new(header);
    let (a, k, rm) = (
        &c.reference.all,
        &c.reference.contact,
        &c.reference_measures,
    );
    let own = [
        pct(a.displacement),
        pct(a.velocity),
        pct(k.displacement),
        pct(k.velocity),
        format!("±{}", fmt_sig(a.frequency_hz.abs(), 3)),
        format!("±{}", pct(a.frequency_relative.abs())),
        pct(max(&rm.open_fraction)),
        margin(rm),
    ];
    let chbm = |f: &dyn Fn(&squeal_chbm::compare::ChbmRow) -> String| {
        c.chbm.iter().map(f).collect::<Vec<_>>()
    };
    let ti = |f: &dyn Fn(&squeal_chbm::compare::Measures) -> String| {
        c.ti.iter()
            .map(|r| r.measures.as_ref().map_or("failed".into(), f))
            .collect::<Vec<_>>()
    };
    let rows: [(&str, Vec<String>, Vec<String>); 8] = [
        (
            "displacement error, all dofs (%)",
            chbm(&|r| pct(r.measures.all.displacement)),
            ti(&|m| pct(m.all.displacement)),
        ),
        (
            "velocity error, all dofs (%)",
            chbm(&|r| pct(r.measures.all.velocity)),
            ti(&|m| pct(m.all.velocity)),
        ),
        (
            "displacement error, contact dofs (%)",
            chbm(&|r| pct(r.measures.contact.displacement)),
            ti(&|m| pct(m.contact.displacement)),
        ),
        (
            "velocity error, contact dofs (%)",
            chbm(&|r| pct(r.measures.contact.velocity)),
            ti(&|m| pct(m.contact.velocity)),
        ),
        (
            "frequency difference (Hz)",
            chbm(&|r| fmt_sig(r.measures.all.frequency_hz, 3)),
            ti(&|m| fmt_sig(m.all.frequency_hz, 3)),
        ),
        (
            "frequency difference (%)",
            chbm(&|r| pct(r.measures.all.frequency_relative)),
            ti(&|m| pct(m.all.frequency_relative)),
        ),
        (
            "largest open fraction of a pair (%)",
            chbm(&|r| pct(max(&r.measures.open_fraction))),
            ti(&|m| pct(max(&m.open_fraction))),
        ),
        (
            "sliding margin: disc speed / peak tangential velocity",
            chbm(&|r| margin(&r.measures)),
            ti(&margin),
        ),
    ];
    for ((name, a, b), o) in rows.into_iter().zip(own) {
        let mut row = vec![name.to_string()];
        row.extend(a);
        row.extend(b);
        row.push(o);
        t.push_row(row);
    }
    t.align_numbers_right()
}

/// The smallest sliding margin of a cycle, `-` without a disc speed, `!` below 1.
pub(super) fn margin(m: &squeal_chbm::compare::Measures) -> String {
    m.sliding.as_ref().map_or("-".into(), |g| {
        format!(
            "{}{}",
            fmt_sig(g.min, 3),
            if g.sliding() { "" } else { " !" }
        )
    })
}

pub(super) fn max(v: &[f64]) -> f64 {
    v.iter().copied().fold(0.0, f64::max)
}

/// Table 2's analogue: cost and storage of every method.
pub(super) fn table2(c: &Comparison) -> Table {
    let mut t = Table::new([
        "method",
        "outcome",
        "iterations / steps",
        "wall time (s)",
        "storage (bytes)",
        "cycles to steady",
        "rejected steps",
        "LU factorizations",
        "energy balance (in-out)/out",
    ]);
    for r in &c.chbm {
        let s = &r.solution;
        t.push_row([
            format!("CHBM {}H", r.harmonics),
            if s.outcome == squeal_chbm::Outcome::LimitCycle {
                "limit cycle".into()
            } else {
                s.outcome.to_string()
            },
            r.iterations.to_string(),
            fmt_sig(r.wall.as_secs_f64(), 3),
            s.storage_bytes().to_string(),
            "-".into(),
            "-".into(),
            "-".into(),
            fmt_sci(r.measures.energy.relative, 2),
        ]);
    }
    let r = &c.reference;
    t.push_row([
        format!("reference: shooting {:e}", r.reference.rtol),
        format!(
            "periodic orbit (residual {})",
            fmt_sci(r.reference.residual(), 1)
        ),
        r.steps().to_string(),
        fmt_sig(r.wall().as_secs_f64(), 3),
        "-".into(),
        "-".into(),
        "-".into(),
        format!(
            "{} monodromies",
            r.reference.monodromies + r.check.monodromies
        ),
        fmt_sci(c.reference_measures.energy.relative, 2),
    ]);
    for r in &c.ti {
        t.push_row(ti_cost_row(r, ""));
    }
    t.align_numbers_right()
}

/// A failure's first clause (up to its first ": "), for a table cell; the full text is in the
/// failures list.
fn short(reason: &str) -> &str {
    reason.split(": ").next().unwrap_or(reason)
}

/// A time integration's cost; a failed run says so and gives only what it spent.
fn ti_cost_row(r: &TiRow, role: &str) -> Vec<String> {
    let st = &r.run.stats;
    vec![
        format!("BDF {:e}{role}", r.rtol),
        match (&r.run.steady, &r.run.failure) {
            (Some(s), _) => format!("steady (drift {})", fmt_sci(s.drift, 1)),
            (None, Some(f)) => format!("failed: {}", short(&f.to_string())),
            (None, None) => "no steady cycle".into(),
        },
        st.steps.to_string(),
        fmt_sig(r.run.wall.as_secs_f64(), 3),
        r.run.history_bytes().to_string(),
        r.run
            .steady
            .as_ref()
            .map_or("-".into(), |s| s.cycles.to_string()),
        (st.rejected_error + st.rejected_newton).to_string(),
        st.lu_decomps.to_string(),
        r.measures
            .as_ref()
            .map_or("-".into(), |m| fmt_sci(m.energy.relative, 2)),
    ]
}

/// Long-form CSV of every method's measures.
fn measures_csv(c: &Comparison) -> Table {
    let slide = |m: Option<&squeal_chbm::compare::Measures>| {
        m.and_then(|m| m.sliding.as_ref())
            .map_or(String::new(), |g| format!("{:e}", g.min))
    };
    let mut t = Table::new([
        "method",
        "harmonics",
        "rtol",
        "outcome",
        "frequency_hz",
        "dfreq_hz",
        "dfreq_rel",
        "err_disp_all",
        "err_vel_all",
        "err_disp_contact",
        "err_vel_contact",
        "iterations_or_steps",
        "wall_s",
        "storage_bytes",
        "energy_balance_rel",
        "max_open_fraction",
        "initial_amplitude_p",
        "sliding_margin",
    ]);
    for r in &c.chbm {
        let m = &r.measures;
        t.push_row([
            "chbm".into(),
            r.harmonics.to_string(),
            "".into(),
            r.solution.outcome.label().to_string(),
            format!("{}", r.cycle.frequency_hz()),
            format!("{:e}", m.all.frequency_hz),
            format!("{:e}", m.all.frequency_relative),
            format!("{:e}", m.all.displacement),
            format!("{:e}", m.all.velocity),
            format!("{:e}", m.contact.displacement),
            format!("{:e}", m.contact.velocity),
            r.iterations.to_string(),
            format!("{:e}", r.wall.as_secs_f64()),
            r.solution.storage_bytes().to_string(),
            format!("{:e}", m.energy.relative),
            format!("{}", max(&m.open_fraction)),
            format!("{}", r.amplitude),
            slide(Some(m)),
        ]);
    }
    let rows = c.ti.iter().map(|r| ("bdf", r));
    for (method, r) in rows {
        let (freq, m) = (
            r.cycle.as_ref().map(|c| c.frequency_hz()),
            r.measures.as_ref(),
        );
        let num = |f: Option<f64>| f.map_or(String::new(), |v| format!("{v:e}"));
        t.push_row([
            method.into(),
            "".into(),
            format!("{:e}", r.rtol),
            if r.run.steady.is_some() {
                "steady".into()
            } else {
                "no steady cycle".into()
            },
            num(freq),
            num(m.map(|m| m.all.frequency_hz)),
            num(m.map(|m| m.all.frequency_relative)),
            num(m.map(|m| m.all.displacement)),
            num(m.map(|m| m.all.velocity)),
            num(m.map(|m| m.contact.displacement)),
            num(m.map(|m| m.contact.velocity)),
            r.run.stats.steps.to_string(),
            format!("{:e}", r.run.wall.as_secs_f64()),
            r.run.history_bytes().to_string(),
            num(m.map(|m| m.energy.relative)),
            num(m.map(|m| max(&m.open_fraction))),
            format!("{}", r.run.epsilon),
            slide(m),
        ]);
    }
    let r = &c.reference;
    let (a, k) = (&r.all, &r.contact);
    let rm = &c.reference_measures;
    t.push_row([
        "shooting_reference".to_string(),
        "".into(),
        format!("{:e}", r.reference.rtol),
        "periodic orbit".into(),
        format!("{}", r.reference.cycle.frequency_hz()),
        "0".into(),
        "0".into(),
        "0".into(),
        "0".into(),
        "0".into(),
        "0".into(),
        r.steps().to_string(),
        format!("{:e}", r.wall().as_secs_f64()),
        "".into(),
        format!("{:e}", rm.energy.relative),
        format!("{}", max(&rm.open_fraction)),
        "".into(),
        slide(Some(rm)),
    ]);
    let mut row = vec![
        "shooting_reference_stated_error".to_string(),
        "".into(),
        format!("{:e}", r.check.rtol),
        "difference from the check solve".into(),
        "".into(),
        format!("{:e}", a.frequency_hz),
        format!("{:e}", a.frequency_relative),
        format!("{:e}", a.displacement),
        format!("{:e}", a.velocity),
        format!("{:e}", k.displacement),
        format!("{:e}", k.velocity),
    ];
    row.extend(std::iter::repeat_n(String::new(), 7));
    t.push_row(row);
    t
}

/// A warning naming the cycles whose sliding margin is below 1.
fn sliding_warning(c: &Comparison) -> Option<String> {
    let mut bad = Vec::new();
    for r in &c.chbm {
        if r.measures.sliding.as_ref().is_some_and(|g| !g.sliding()) {
            bad.push(format!("CHBM {}H", r.harmonics));
        }
    }
    if c.reference_measures
        .sliding
        .as_ref()
        .is_some_and(|g| !g.sliding())
    {
        bad.push("the reference".into());
    }
    for r in &c.ti {
        let m = r.measures.as_ref().and_then(|m| m.sliding.as_ref());
        if m.is_some_and(|g| !g.sliding()) {
            bad.push(format!("BDF {:e}", r.rtol));
        }
    }
    (!bad.is_empty()).then(|| {
        format!(
            "WARNING: sliding margin below 1 for {}: the pad's tangential vibration outruns the disc surface, so the pad sticks for part of the cycle; stick-slip is outside the model (permanent sliding).",
            bad.join(", ")
        )
    })
}

/// One paragraph on the reference: how it was found, its stated own error and what it cost.
fn reference_note(c: &Comparison) -> String {
    let r = &c.reference;
    let (a, k) = (&r.all, &r.contact);
    let floquet = r.floquet.map_or(String::new(), |f| {
        format!(
            " Floquet check: the multiplier 1 holds to {} (|M f - f| / |f| along the orbit, 0 on the exact orbit); Newton's monodromy has its multiplier nearest 1 at {} off and the largest other of modulus {} ({}).",
            fmt_sci(f.tangent_error, 1),
            fmt_sci((f.trivial - 1.0).norm(), 1),
            fmt_sig(f.leading, 6),
            if f.leading < 1.0 {
                "the cycle attracts"
            } else {
                "the cycle repels"
            }
        )
    });
    let worst = c
        .chbm
        .iter()
        .filter(|h| h.measures.all.displacement < 3.0 * a.displacement)
        .map(|h| format!("{}H", h.harmonics))
        .collect::<Vec<_>>();
    format!(
        "Reference: the periodic orbit by shooting (Newton on the start and the period, {} steps from {}), BDF rtol {:e}: periodicity residual {}, {} Newton monodromies, {} BDF steps, {} s in all.{floquet}\nIts stated own error (difference from the same orbit solved at rtol {:e}, an upper bound): displacement {} %, velocity {} % (all dofs), {} %, {} % (contact dofs), frequency {} Hz ({} %).{}",
        r.reference.residuals.len() - 1,
        c.reference_start,
        r.reference.rtol,
        fmt_sci(r.reference.residual(), 1),
        r.reference.monodromies + r.check.monodromies,
        r.steps(),
        fmt_sig(r.wall().as_secs_f64(), 3),
        r.check.rtol,
        pct(a.displacement),
        pct(a.velocity),
        pct(k.displacement),
        pct(k.velocity),
        fmt_sig(a.frequency_hz.abs(), 3),
        pct(a.frequency_relative.abs()),
        if worst.is_empty() {
            String::new()
        } else {
            format!(
                "\nWARNING: the displacement errors of CHBM {} are within 3x the reference's own error: they measure the reference too.",
                worst.join(", ")
            )
        }
    )
}

/// Writes tables and figures of one comparison; returns the files written (relative names).
pub(super) fn write_comparison(
    dir: &Path,
    m: &Model,
    c: &Comparison,
    ratio: f64,
    log: Log,
) -> Result<Vec<String>> {
    let t1 = table1(c);
    let t2 = table2(c);
    log(&format!(
        "\nTable 1 analogue at {ratio} mu0 (reference: the periodic orbit by shooting, BDF rtol {:e}; errors relative RMS, phase-aligned):\n{}",
        c.reference.reference.rtol,
        t1.to_text()
    ));
    log(&reference_note(c));
    if let Some(w) = sliding_warning(c) {
        log(&w);
    }
    log(&format!("\nTable 2 analogue:\n{}", t2.to_text()));
    t1.write_csv(&dir.join("table1.csv"))?;
    t2.write_csv(&dir.join("table2.csv"))?;
    measures_csv(c).write_csv(&dir.join("measures.csv"))?;
    power_csv(c).write_csv(&dir.join("power_ratio.csv"))?;
    let mut files = vec![
        "table1.csv".to_string(),
        "table2.csv".into(),
        "measures.csv".into(),
        "power_ratio.csv".into(),
    ];
    for (stem, fig) in [
        ("limit_cycles", figure4(m, c, ratio)),
        ("power_ratio", figure5(c, ratio)),
        ("speed_accuracy", speed_accuracy(c, ratio)),
        ("ti_growth", growth(c, ratio)),
    ] {
        write_svg_and_png(&fig, &dir.join(stem))?;
        files.push(format!("{stem}.svg"));
    }
    Ok(files)
}

/// Eqs (49)–(50): `R_j = P_j / P_temporal` for every method and harmonic.
fn power_csv(c: &Comparison) -> Table {
    let mut t = Table::new(["method", "harmonic", "power_P_j", "ratio_R_j"]);
    let total = c.power_reference.max(f64::MIN_POSITIVE);
    {
        for (j, pj) in c.reference_measures.power.iter().enumerate() {
            t.push_row([
                format!("shooting {:e}", c.reference.reference.rtol),
                (j + 1).to_string(),
                format!("{pj:e}"),
                format!("{:e}", pj / total),
            ]);
        }
    }
    for r in &c.chbm {
        for (j, pj) in r.measures.power.iter().enumerate() {
            t.push_row([
                format!("CHBM {}H", r.harmonics),
                (j + 1).to_string(),
                format!("{pj:e}"),
                format!("{:e}", pj / total),
            ]);
        }
    }
    t
}
