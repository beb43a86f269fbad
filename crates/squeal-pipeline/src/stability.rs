//! The paper's section 3 for a scene: static equilibrium, complex eigenvalues against friction
//! (Figure 2), the Hopf point μ0 and the unstable mode shape; the tables, figures and shapes
//! `squeal stability` writes.

use crate::caveats::{caveats, caveats_text, undamped};
use crate::error::{Result, json_text};
use crate::model::Model;
use crate::progress::Progress;
use squeal_brake::analysis::LinearStability as Stability;
use squeal_brake::assemble::InitialGaps;
use squeal_brake::criticality::{Criticality, NormalForm, pair_closure};
use squeal_brake::equilibrium::Equilibrium;
use squeal_report::Table;
use squeal_report::format::fmt_sig;
use std::fmt::Write as _;
use std::path::Path;

mod pairs;
#[allow(unused_imports)]
use pairs::*;
pub use pairs::{adjustment, equilibrium_table, equilibrium_text, gap_description, gap_source};

/// The stability analysis of the model over `mus`: the damping of eqs (12)–(13) with the
/// coalescing pair picked as the scene asks, the sweep and the Hopf point.
pub fn analyse(m: &Model, mus: &[f64]) -> Result<Stability> {
    analyse_with(m, mus, &crate::progress::Silent)
}

/// [`analyse`], each sweep a step of `progress` with one item per friction value.
pub fn analyse_with(m: &Model, mus: &[f64], progress: &dyn Progress) -> Result<Stability> {
    // One item per friction value, whatever the sweep reports at once.
    let last = std::sync::atomic::AtomicUsize::new(0);
    let tell = |done: usize, total: usize| {
        if done == 0 {
            progress.begin("sweep", total);
            progress.item(&format!("0/{total} mu values"));
        }
        let before = last.swap(done, std::sync::atomic::Ordering::Relaxed);
        for k in before.min(done) + 1..=done {
            progress.item(&format!("{k}/{total} mu values"));
        }
        if done == total {
            progress.end();
        }
    };
    let st = squeal_brake::analysis::stability_with(&m.brake, &m.damping, mus, &m.sweep, &tell);
    progress.end();
    Ok(st?)
}

/// The Hopf normal form at μ0 (criticality and the branch's asymptote), when there is a Hopf
/// point.
pub fn normal_form(m: &Model, st: &Stability) -> Result<Option<NormalForm>> {
    let Some(h) = &st.sweep.hopf else {
        return Ok(None);
    };
    let guess = h.point.spectrum.values[h.index];
    let key = [h.mu0.to_bits(), guess.re.to_bits(), guess.im.to_bits()];
    let nf = m.normal_forms.get_or_try(key, || {
        squeal_brake::criticality::normal_form(
            &m.brake,
            &st.reference,
            h.mu0,
            guess,
            &m.sweep.newton,
        )
    })?;
    Ok(Some(nf))
}

/// The largest first-harmonic closure over the pairs of the normal form's cycle at `mu` (m),
/// with the pair (0-based).
pub fn loudest_closure(
    m: &Model,
    st: &Stability,
    nf: &NormalForm,
    mu: f64,
) -> Option<(usize, f64)> {
    let x = nf.first_harmonic(mu)?;
    m.brake
        .pairs
        .iter()
        .enumerate()
        .map(|(p, pair)| (p, pair_closure(pair, &st.reference.basis.phi, &x).norm()))
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// The normal form's lines: the verdict, `l1`, and the branch's asymptote.
pub fn criticality_text(m: &Model, st: &Stability, nf: &NormalForm) -> String {
    let mut out = String::new();
    // Undamped, μ0 is a coalescence: Re λ goes like √(μ − μ0), with no finite slope.
    let slope = if undamped(st) {
        "no finite dRe(lambda)/dmu (undamped coalescence)".to_string()
    } else {
        format!("dRe(lambda)/dmu = {:.4e} 1/s", nf.dlambda_dmu.re)
    };
    let _ = writeln!(
        out,
        "Hopf point is {}: first Lyapunov coefficient l1 = {:.4e} (Re c1 = {:.4e} 1/s), {slope}",
        nf.criticality(),
        nf.l1,
        nf.c1.re,
    );
    // The asymptote: closure amplitude of the loudest pair per square root of |μ/μ0 - 1|.
    let eps = 1e-3;
    let side = if nf.radius_squared(nf.mu0 * (1.0 + eps)).is_some() {
        1.0
    } else {
        -1.0
    };
    let mu = nf.mu0 * (1.0 + side * eps);
    if let Some((p, a)) = loudest_closure(m, st, nf, mu) {
        let _ = writeln!(
            out,
            "  small-amplitude branch: limit cycles for mu {} mu0, pair {} closure amplitude {:.3} um x sqrt(|mu/mu0 - 1| / 1e-3), frequency {:+.3} Hz per 0.1 % of mu",
            if side > 0.0 { "above" } else { "below" },
            p + 1,
            a * 1e6,
            (nf.omega_at(nf.mu0 * 1.001) - nf.omega0) / std::f64::consts::TAU
        );
    }
    if nf.criticality() == Criticality::Degenerate {
        let _ = writeln!(out, "  ({})", squeal_brake::criticality::DEGENERATE_HINT);
    }
    if nf.criticality() == Criticality::Subcritical {
        let _ = writeln!(
            out,
            "  (subcritical: below mu0 the equilibrium is stable but a large enough disturbance can start squeal; `squeal branch` follows the cycles)"
        );
    }
    out
}

/// The contact pairs as formed: points, distance, area and element parameters, one line per
/// pair up to 40 pairs; beyond, one summary line per pad (nodal contact
/// on a fine mesh has thousands of pairs: every pair is in `equilibrium.csv` and
/// `summary.json`).
pub fn pairs_text(s: &Model) -> String {
    let mut out = String::new();
    if s.pairs.len() > pairs::LISTED_PAIRS {
        out.push_str(&pairs::formed_summary(s));
    } else {
        let _ = writeln!(
            out,
            "contact pairs (disc point, pad point, distance, area, geometric gap, k_l, k_nl):"
        );
        let mut pad = "";
        for p in &s.pairs {
            if s.layout.pads.len() > 1 && p.pad != pad {
                pad = &p.pad;
                let _ = writeln!(out, "  {pad}:");
            }
            let params: Vec<String> = p
                .law
                .parameters()
                .iter()
                .map(|(_, v, unit)| format!("{v:.4e} {unit}"))
                .collect();
            let _ = writeln!(
                out,
                "  {:>2} {:>2}  {:.1e} m  {} m^2  {:+.1e} m  {}",
                p.disc_point + 1,
                p.pad_point + 1,
                p.distance,
                p.area.map_or("-".into(), |a| format!("{a:.4e}")),
                p.geometric_gap,
                params.join("  ")
            );
        }
    }
    let _ = writeln!(
        out,
        "piston force {:.1} N on {} piston dofs{}",
        s.params.piston_force,
        s.brake.f_piston.iter().filter(|f| **f != 0.0).count(),
        if s.layout.pads.len() > 1 {
            format!(
                " (the clamp force on each of the {} pads: {})",
                s.layout.pads.len(),
                s.layout
                    .pads
                    .iter()
                    .map(|p| p.0.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        } else {
            String::new()
        }
    );
    out
}

/// Kinetic-energy share of the disc in a mode `x` (reduced brake coordinates).
pub fn disc_share(s: &Model, x: &[faer::c64]) -> f64 {
    part_shares(s, x).first().map_or(0.0, |p| p.1)
}

/// Kinetic-energy share `x_pᴴ M_pp x_p / Σ` of each part (disc, then the pads, then the
/// further parts together) in a mode `x` (reduced brake coordinates; the parts are not
/// coupled through M).
pub fn part_shares(s: &Model, x: &[faer::c64]) -> Vec<(String, f64)> {
    let m = &s.brake.m;
    let energy = |r: std::ops::Range<usize>| -> f64 {
        let mut e = 0.0;
        for i in r.clone() {
            for j in r.clone() {
                e += (x[i].conj() * x[j]).re * m[(i, j)];
            }
        }
        e
    };
    let mut parts: Vec<(String, f64)> =
        std::iter::once(("disc".to_string(), s.layout.disc.clone()))
            .chain(s.layout.pads.iter().cloned())
            .map(|(name, r)| (name, energy(r)))
            .collect();
    // The further parts' dofs follow the pads' (`[parts.<name>]`): their energy counts in the
    // total, as one share, so that the disc's and the pads' are not overstated.
    let rest = s.layout.all_pads().end..m.nrows();
    if !rest.is_empty() {
        let names: Vec<&str> = s
            .rom
            .bodies()
            .iter()
            .map(|p| p.info.name.as_str())
            .collect();
        parts.push((
            format!("further parts ({})", names.join(", ")),
            energy(rest),
        ));
    }
    let total = parts
        .iter()
        .map(|p| p.1)
        .sum::<f64>()
        .max(f64::MIN_POSITIVE);
    parts.into_iter().map(|(n, e)| (n, e / total)).collect()
}

/// `; kinetic energy: disc 3%, inboard 50%, outboard 47%` for a brake with several pads
/// (empty with one: the disc's share says it all).
fn shares_text(s: &Model, x: &[faer::c64]) -> String {
    if s.layout.pads.len() < 2 {
        return String::new();
    }
    let parts: Vec<String> = part_shares(s, x)
        .iter()
        .map(|(n, e)| format!("{n} {:.0}%", 100.0 * e))
        .collect();
    format!(" (by part: {})", parts.join(", "))
}

/// What the sweep found, as the lines `squeal stability` prints.
pub fn summary_text(s: &Model, st: &Stability, seconds: f64) -> String {
    let mut out = String::new();
    let sw = &st.sweep;
    out.push_str(&equilibrium_text(s, &st.reference.equilibrium));
    let _ = writeln!(out, "{}", damping_text(s, st));
    if let Some(i) = &s.interface {
        out.push_str(&i.text());
    }
    let _ = writeln!(
        out,
        "sweep: {} friction values {}..{} in {:.2} s; valid band up to {:.0} Hz{}",
        sw.points.len(),
        sw.points[0].equilibrium.mu,
        sw.points[sw.points.len() - 1].equilibrium.mu,
        seconds,
        s.sweep.band.valid_max_hz,
        s.sweep.band.user.map_or(String::new(), |(a, b)| format!(
            ", user band {a:.0}..{b:.0} Hz"
        ))
    );
    let t = &sw.timings;
    let _ = writeln!(
        out,
        "  sweep time: {}final sweep: projection {:.2} s, equilibria {:.2} s, spectra {:.2} s, tracking {:.2} s, Hopf refinement {:.2} s",
        st.naming.map_or(String::new(), |(n, d)| format!(
            "pair-naming sweep ({n} values) {:.2} s; ",
            d.as_secs_f64()
        )),
        t.projection.as_secs_f64(),
        t.equilibria.as_secs_f64(),
        t.spectra.as_secs_f64(),
        t.tracking.as_secs_f64(),
        t.refinement.as_secs_f64()
    );
    if sw.stats.resweeps > 0 {
        let _ = writeln!(
            out,
            "  the sweep was redone {} time(s) with friction values inserted into the bracket of the first crossing: its Hopf refinement had lost the mode (the modes could not be followed across the step)",
            sw.stats.resweeps
        );
    }
    out.push_str(&crate::caveats::kept_modes_text(s));
    let outside: Vec<_> = sw.crossings.iter().filter(|c| !c.in_band).collect();
    for c in sw.crossings.iter().filter(|c| c.in_band) {
        let _ = writeln!(
            out,
            "  crossing: branch {} unstable from mu in [{:.4}, {:.4}] at {:.0} Hz",
            c.branch, c.mu_lo, c.mu_hi, c.frequency_hz,
        );
    }
    match &sw.hopf {
        Some(h) => {
            let x = h.point.spectrum.shape(&st.reference.basis, h.index);
            let _ = writeln!(
                out,
                "Hopf point mu0 = {:.8} (bracket [{:.10}, {:.10}], {} refinements) at {:.2} Hz; disc share of the unstable mode's kinetic energy {:.0}%{}",
                h.mu0,
                h.bracket.0,
                h.bracket.1,
                h.evaluations,
                h.frequency_hz,
                100.0 * disc_share(s, &x),
                shares_text(s, &x)
            );
            if let Some((m1, m2)) = st.pair {
                let f = |m: usize| st.reference.basis.omega[m] / (2.0 * std::f64::consts::PI);
                let mode = |m: usize| -> Vec<faer::c64> {
                    let phi = &st.reference.basis.phi;
                    (0..phi.nrows())
                        .map(|i| faer::c64::new(phi[(i, m)], 0.0))
                        .collect()
                };
                // Undamped, the two modes of a coalescence grow and decay alike.
                let (stays, goes) = if undamped(st) {
                    ("", " (undamped: which of the two grows is not defined)")
                } else {
                    (" (stays stable)", " (goes unstable)")
                };
                let _ = writeln!(
                    out,
                    "coalescing pair (frictionless modes): Mode 1 = #{} at {:.1} Hz{stays}{}, Mode 2 = #{} at {:.1} Hz{goes}{}",
                    m1 + 1,
                    f(m1),
                    shares_text(s, &mode(m1)),
                    m2 + 1,
                    f(m2),
                    shares_text(s, &mode(m2))
                );
            }
        }
        None => {
            let _ = writeln!(out, "no Hopf point in the band over this friction range");
        }
    }
    if !outside.is_empty() {
        let _ = writeln!(out, "{}", outside_band_text(&s.sweep.band, outside.len()));
    }
    out.push_str(&caveats_text(&caveats(s, st)));
    out
}

/// The one line that stands for the `n` crossings outside `band`: listed one by one (53 to 66
/// of them on a fine model) they buried the crossings in the band (issue 22). Names the band:
/// the model's valid band, and the scene's `band_hz` when given.
pub fn outside_band_text(band: &squeal_brake::sweep::Band, n: usize) -> String {
    format!(
        "{n} crossing(s) outside the band (the model's valid band up to {:.0} Hz{}) do not define mu0 and are not listed here: stability/summary.json lists them",
        band.valid_max_hz,
        band.user.map_or(String::new(), |(a, b)| format!(
            ", the scene's band_hz {a:.0}..{b:.0} Hz"
        ))
    )
}

/// What the sweep says of squeal, in one line.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// No mode in the band is unstable at any friction value swept: no squeal in this range.
    Stable { from: f64, to: f64 },
    /// The equilibrium goes unstable at the Hopf point μ0, at this frequency.
    Squeals { mu0: f64, frequency_hz: f64 },
    /// A mode in the band is unstable already at the first friction value (no crossing: no
    /// Hopf point in the range).
    UnstableFromStart { mu: f64, frequency_hz: f64 },
}

impl Verdict {
    /// Whether the brake is stable over the whole range.
    pub fn is_stable(&self) -> bool {
        matches!(self, Verdict::Stable { .. })
    }
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Verdict::Stable { from, to } => write!(
                f,
                "stable for mu in [{}, {}]: no mode in the band goes unstable, no squeal in this range",
                short(from),
                short(to)
            ),
            Verdict::Squeals { mu0, frequency_hz } => write!(
                f,
                "squeals from mu0 = {} at {:.1} Hz (the Hopf point)",
                fmt_sig(mu0, 6),
                frequency_hz
            ),
            Verdict::UnstableFromStart { mu, frequency_hz } => write!(
                f,
                "unstable already at mu = {} at {:.1} Hz (no Hopf point in this range: start the sweep lower)",
                fmt_sig(mu, 4),
                frequency_hz
            ),
        }
    }
}

/// A friction value as the user wrote it: six significant digits, trailing zeros dropped
/// (`0`, `0.2`, `0.46182`).
pub fn short(x: f64) -> String {
    let s = fmt_sig(x, 6);
    if s.contains('.') && !s.contains('e') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// The verdict of a stability analysis: the Hopf point if there is one, else whether any
/// in-band mode is unstable (`Re λ > τ`, [`threshold`]) at any friction value swept.
pub fn verdict(m: &Model, st: &Stability) -> Verdict {
    let sw = &st.sweep;
    if let Some(h) = &sw.hopf {
        return Verdict::Squeals {
            mu0: h.mu0,
            frequency_hz: h.frequency_hz,
        };
    }
    let tau = threshold(m, st);
    for p in &sw.points {
        let unstable = (0..p.spectrum.values.len())
            .filter(|&j| p.spectrum.values[j].re > tau)
            .map(|j| p.spectrum.frequency_hz(j))
            .find(|&f| m.sweep.band.contains(f));
        if let Some(frequency_hz) = unstable {
            return Verdict::UnstableFromStart {
                mu: p.equilibrium.mu,
                frequency_hz,
            };
        }
    }
    Verdict::Stable {
        from: sw.points[0].equilibrium.mu,
        to: sw.points[sw.points.len() - 1].equilibrium.mu,
    }
}

/// The instability threshold of the sweep (s⁻¹): a mode counts as unstable when
/// `Re λ > τ`. With no threshold in the options it is `64 ε ω_max`
/// ([`squeal_brake::sweep::default_threshold`]), relative to the largest `|λ|` of the
/// spectrum: the eigensolver's round-off on an undamped mode is about `ε ω_max`, so real parts
/// of `1e-41` to `1e-16` s⁻¹ with zero damping are not instabilities.
pub fn threshold(m: &Model, st: &Stability) -> f64 {
    m.sweep
        .threshold
        .unwrap_or_else(|| squeal_brake::sweep::default_threshold(&st.reference))
}

/// Branches shown in the figures: the Hopf pair first, then every other in-band branch that
/// goes unstable over the sweep (the second instability too), then in-band branches within
/// ±25% of the Hopf frequency (or, with no Hopf point, every branch that crosses).
pub fn shown_branches(st: &Stability, band_max: f64) -> Vec<usize> {
    let sw = &st.sweep;
    let mut out = Vec::new();
    if let Some(h) = &sw.hopf {
        out.push(h.branch);
        if let Some(p) = h.partner {
            out.push(p);
        }
    }
    for c in sw
        .crossings
        .iter()
        .filter(|c| c.in_band || sw.hopf.is_none())
    {
        if !out.contains(&c.branch) {
            out.push(c.branch);
        }
    }
    if let Some(h) = &sw.hopf {
        for b in 0..sw.branches.len() {
            let f = sw.points[0].spectrum.frequency_hz(sw.branches[b][0]);
            if !out.contains(&b) && (f / h.frequency_hz - 1.0).abs() < 0.25 && f < band_max {
                out.push(b);
            }
        }
    }
    out
}

/// The in-band crossings other than the Hopf point's, one per branch (its first).
pub fn other_instabilities(st: &Stability) -> Vec<squeal_brake::sweep::Crossing> {
    let sw = &st.sweep;
    let hopf_branch = sw.hopf.as_ref().map(|h| h.branch);
    let mut seen = Vec::new();
    let mut out = Vec::new();
    for c in sw.crossings.iter().filter(|c| c.in_band) {
        if Some(c.branch) == hopf_branch || seen.contains(&c.branch) {
            continue;
        }
        seen.push(c.branch);
        out.push(*c);
    }
    out
}

/// The damping of eqs (12)-(13) the sweep used and where its ratio comes from (issue 22: a
/// default is said, not applied silently).
pub fn damping_text(s: &Model, st: &Stability) -> String {
    let d = &s.damping;
    let pair = match st.pair {
        Some((a, b)) if d.pair_ratios.iter().any(|r| *r != 0.0) => format!(
            ", plus {} and {} on the pair (modes {} and {})",
            d.pair_ratios[0],
            d.pair_ratios[1],
            a + 1,
            b + 1
        ),
        _ => String::new(),
    };
    format!(
        "damping: modal ratio {} ({} %) on every mode ({}){pair}",
        d.global_ratio,
        d.global_ratio * 100.0,
        s.damping_from
    )
}

/// The damping columns of `stability.csv`: `damping_ratio_all_modes`, and with extra damping
/// on the pair `damping_ratio_extra_mode<a>`, `damping_ratio_extra_mode<b>` (1-based modes).
fn damping_columns(s: &Model, st: &Stability) -> Vec<(String, f64)> {
    let d = &s.damping;
    let mut out = vec![("damping_ratio_all_modes".to_string(), d.global_ratio)];
    if let Some((a, b)) = st.pair
        && d.pair_ratios.iter().any(|r| *r != 0.0)
    {
        out.push((
            format!("damping_ratio_extra_mode{}", a + 1),
            d.pair_ratios[0],
        ));
        out.push((
            format!("damping_ratio_extra_mode{}", b + 1),
            d.pair_ratios[1],
        ));
    }
    out
}

/// `branches.csv`, `stability.csv` (with the damping used as its last columns),
/// `equilibrium.csv` (the frictionless equilibrium pair by pair) and `summary.json`.
pub fn write_tables(dir: &Path, s: &Model, st: &Stability) -> Result<()> {
    let sw = &st.sweep;
    let tau = threshold(s, st);
    let mut all = Table::new([
        "mu",
        "branch",
        "real_part_per_s",
        "frequency_hz",
        "in_band",
        "unstable",
    ]);
    for (k, p) in sw.points.iter().enumerate() {
        for b in 0..sw.branches.len() {
            let l = sw.value(b, k);
            let f = p.spectrum.frequency_hz(sw.branches[b][k]);
            all.push_row([
                format!("{}", p.equilibrium.mu),
                b.to_string(),
                format!("{:e}", l.re),
                format!("{f}"),
                (s.sweep.band.contains(f) as u8).to_string(),
                ((l.re > tau) as u8).to_string(),
            ]);
        }
    }
    all.write_csv(&dir.join("branches.csv"))?;
    let shown = shown_branches(st, s.sweep.band.valid_max_hz);
    let mut header = vec!["mu".to_string()];
    for b in &shown {
        header.push(format!("re_b{b}"));
        header.push(format!("f_hz_b{b}"));
    }
    header.push("unstable_in_band".into());
    header.push("unstable_outside_band".into());
    // The damping used (eqs 12-13), as the summary says it: the ratio on every mode, and the
    // pair's extra ratios when there are any (issue 22: the table must say what it assumed).
    let damping = damping_columns(s, st);
    header.extend(damping.iter().map(|d| d.0.clone()));
    let mut t = Table::new(header);
    for (k, p) in sw.points.iter().enumerate() {
        let mut row = vec![format!("{}", p.equilibrium.mu)];
        for &b in &shown {
            row.push(format!("{:e}", sw.value(b, k).re));
            row.push(format!("{}", p.spectrum.frequency_hz(sw.branches[b][k])));
        }
        let (mut inb, mut outb) = (0, 0);
        for j in 0..p.spectrum.values.len() {
            if p.spectrum.values[j].re > tau {
                if s.sweep.band.contains(p.spectrum.frequency_hz(j)) {
                    inb += 1;
                } else {
                    outb += 1;
                }
            }
        }
        row.push(inb.to_string());
        row.push(outb.to_string());
        row.extend(damping.iter().map(|d| d.1.to_string()));
        t.push_row(row);
    }
    t.write_csv(&dir.join("stability.csv"))?;
    equilibrium_table(s, &st.reference.equilibrium).write_csv(&dir.join("equilibrium.csv"))?;
    let summary = serde_json::json!({
        "mu0": sw.hopf.as_ref().map(|h| h.mu0),
        "frequency_hz": sw.hopf.as_ref().map(|h| h.frequency_hz),
        "bracket": sw.hopf.as_ref().map(|h| [h.bracket.0, h.bracket.1]),
        "refinements": sw.hopf.as_ref().map(|h| h.evaluations),
        "pair_modes_1based": st.pair.map(|(a, b)| [a + 1, b + 1]),
        "damping": {
            "global_ratio": s.damping.global_ratio,
            "global_ratio_from": s.damping_from,
            "pair_ratios": s.damping.pair_ratios,
            "text": damping_text(s, st),
        },
        "crossings": sw.crossings.iter().map(|c| serde_json::json!({
            "branch": c.branch, "mu_lo": c.mu_lo, "mu_hi": c.mu_hi, "frequency_hz": c.frequency_hz, "in_band": c.in_band
        })).collect::<Vec<_>>(),
        "valid_band_max_hz": s.sweep.band.valid_max_hz,
        "instability_threshold_per_s": tau,
        "instability_threshold": "a mode is unstable when Re(lambda) > this threshold, 64 eps omega_max: the eigensolver's round-off relative to the largest |lambda| of the spectrum",
        "user_band_hz": s.sweep.band.user.map(|(a, b)| [a, b]),
        "caveats": caveats(s, st).iter().map(|c| serde_json::json!({
            "kind": c.key(), "message": c.to_string()
        })).collect::<Vec<_>>(),
        "equilibrium_frictionless": {
            "mu": st.reference.equilibrium.mu,
            "iterations": st.reference.equilibrium.iterations,
            "load_steps": st.reference.equilibrium.load_steps,
            "rejected_load_steps": st.reference.equilibrium.rejected_load_steps,
            "relative_residual": st.reference.equilibrium.residual,
            "penetrations_m": st.reference.equilibrium.penetrations,
            "initial_gaps": gap_description(s),
            "pairs": s.pairs.iter().enumerate().map(|(p, pair)| serde_json::json!({
                "pair": p + 1,
                "geometric_gap_m": pair.geometric_gap,
                "initial_gap_m": pair.initial_gap,
                "gap_closed_by_m": adjustment(s, pair),
                "closure_m": st.reference.equilibrium.penetrations[p],
                "normal_force_n": st.reference.equilibrium.normal_forces[p],
            })).collect::<Vec<_>>(),
            "total_normal_force_n": st.reference.equilibrium.total_normal_force(),
        },
        "rom": s.rom_path.display().to_string(),
        "interface_reduction": s.interface.as_ref().map(|i| i.json()),
    });
    squeal_io::atomic_write_bytes(
        &dir.join("summary.json"),
        json_text(&summary, "the stability summary")?.as_bytes(),
    )?;
    Ok(())
}

mod figures;
pub use figures::{write_figures, write_shapes};

pub mod contributions;
pub mod sensitivities;

/// What the unstable mode is made of and what moves μ0 ([`contributions`],
/// [`sensitivities`]): writes their tables and chart into `dir` and returns the lines
/// `squeal stability` prints (empty without a Hopf point), with the wall time they took.
pub fn write_makeup(
    dir: &Path,
    m: &Model,
    st: &Stability,
    log: crate::model::Log,
) -> Result<String> {
    let t = std::time::Instant::now();
    let mut out = String::new();
    if let Some(mut c) = contributions::at_hopf(m, st) {
        match crate::shapes::Meshes::read(m, log) {
            Ok(meshes) => contributions::classify(m, st, &mut c, &meshes),
            Err(e) => log(&format!(
                "nodal diameters of the contributors not classified: {e}"
            )),
        }
        let sweep = contributions::along_sweep(m, st);
        contributions::write(dir, &c, &sweep)?;
        contributions::write_chart(dir, &c)?;
        out.push_str(&contributions::text(&c));
    }
    // The sensitivities need the unstable mode followed to the Hopf point; where that fails
    // (an undamped coalescence, a bracket too wide) the rest of the stage stands, and the
    // output says why they are missing.
    // Undamped, μ0 is a coalescence: the critical eigenvalue is double, first-order
    // perturbation (the sensitivities' dλ/ds) does not apply and no slope is printed.
    let computed = if undamped(st) && st.sweep.hopf.is_some() {
        let _ = writeln!(
            out,
            "sensitivities of mu0 not computed: at an undamped coalescence the critical eigenvalue is double and Re(lambda) has no finite derivative (give [damping] for them)"
        );
        Ok(None)
    } else {
        sensitivities::compute(m, st)
    };
    match computed {
        Ok(Some(r)) => {
            sensitivities::write(dir, &r)?;
            out.push_str(&sensitivities::text(&r, 10));
        }
        Ok(None) => {}
        Err(e) => {
            let _ = writeln!(out, "sensitivities of mu0 not computed: {e}");
        }
    }
    if !out.is_empty() {
        let _ = writeln!(
            out,
            "  (contributions and sensitivities in {:.2} s: contributions*.csv, sensitivities.csv, their .json)",
            t.elapsed().as_secs_f64()
        );
    }
    Ok(out)
}
