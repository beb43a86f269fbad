//! The contact pairs and the equilibrium as `squeal stability` tells them: how each pair's initial gap was set, and the equilibrium's table and text.

use super::*;

/// Where the pairs' initial gaps come from, in words.
pub fn gap_source(m: &Model) -> &'static str {
    match m.params.initial_gaps {
        InitialGaps::Geometric => "measured from the geometry",
        InitialGaps::Uniform(_) => "given in the scene ([contact] initial_gap)",
        InitialGaps::PerPair(_) => "given per pair in the scene ([contact] initial_gap)",
        InitialGaps::Closed => {
            "closed ([contact] close_initial_gaps = true): set to zero, adjusted from the geometry's"
        }
    }
}

/// [`gap_source`], with the largest adjustment when the gaps were closed.
pub fn gap_description(m: &Model) -> String {
    let largest = m
        .pairs
        .iter()
        .map(|p| adjustment(m, p).abs())
        .fold(0.0, f64::max);
    match m.params.initial_gaps {
        InitialGaps::Closed => format!(
            "{} (the largest adjustment {:.3e} m)",
            gap_source(m),
            largest
        ),
        _ => gap_source(m).to_string(),
    }
}

/// How far `close_initial_gaps` moved a pair's gap (m): its geometric gap when the gaps are
/// closed, 0 otherwise (a gap given in the scene replaces the geometric one, it adjusts
/// nothing).
pub fn adjustment(m: &Model, pair: &squeal_brake::assemble::Pairing) -> f64 {
    match m.params.initial_gaps {
        InitialGaps::Closed => pair.geometric_gap,
        _ => 0.0,
    }
}

/// The equilibrium pair by pair: points, geometric gap, initial gap used, the adjustment
/// of `close_initial_gaps`, closure
/// (penetration) and normal force, in SI units (`equilibrium.csv`).
pub fn equilibrium_table(m: &Model, eq: &Equilibrium) -> Table {
    let mut t = Table::new([
        "pair",
        "disc_point",
        "pad_point",
        "geometric_gap_m",
        "initial_gap_m",
        "gap_closed_by_m",
        "closure_m",
        "normal_force_n",
        "pad",
    ]);
    for (p, pair) in m.pairs.iter().enumerate() {
        t.push_row([
            (p + 1).to_string(),
            (pair.disc_point + 1).to_string(),
            (pair.pad_point + 1).to_string(),
            format!("{:e}", pair.geometric_gap),
            format!("{:e}", pair.initial_gap),
            format!("{:e}", adjustment(m, pair)),
            format!("{:e}", eq.penetrations[p]),
            format!("{:e}", eq.normal_forces[p]),
            pair.pad.clone(),
        ]);
    }
    t
}

/// The equilibrium's lines `squeal stability` prints: how it was solved, then each pair's
/// initial gap, closure and normal force.
pub fn equilibrium_text(m: &Model, eq: &Equilibrium) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "equilibrium at mu = {}: {} load step(s) ({} halved), {} Newton iterations, relative residual {:.1e}, {} of {} pairs closed, contact force {:.1} N of {:.1} N; initial gaps {}",
        eq.mu,
        eq.load_steps,
        eq.rejected_load_steps,
        eq.iterations,
        eq.residual,
        eq.closed_pairs(),
        eq.penetrations.len(),
        eq.total_normal_force(),
        m.params.piston_force * m.layout.pads.len() as f64,
        gap_description(m)
    );
    if m.layout.pads.len() > 1 {
        // Each pad carries the clamp force; the disc takes their difference.
        let per_pad: Vec<String> = m
            .layout
            .pads
            .iter()
            .map(|(name, _)| {
                let f: f64 = m
                    .pairs
                    .iter()
                    .zip(&eq.normal_forces)
                    .filter(|(p, _)| p.pad == *name)
                    .map(|(_, f)| f)
                    .sum();
                format!("{name} {f:.3} N")
            })
            .collect();
        let _ = writeln!(
            out,
            "  pad resultants (each should be the clamp force {:.3} N): {}",
            m.params.piston_force,
            per_pad.join(", ")
        );
    }
    out.push_str(&clamp_warning(m, eq));
    if m.pairs.len() > LISTED_PAIRS {
        out.push_str(&equilibrium_summary(m, eq));
        return out;
    }
    let _ = writeln!(
        out,
        "  pair  initial gap (um)  closure (um)  normal force (N)"
    );
    for (p, pair) in m.pairs.iter().enumerate() {
        let _ = writeln!(
            out,
            "  {:>4}  {:>16.3}  {:>12.3}  {:>16.2}{}",
            p + 1,
            pair.initial_gap * 1e6,
            eq.penetrations[p] * 1e6,
            eq.normal_forces[p],
            if eq.penetrations[p] > 0.0 {
                ""
            } else {
                "  open"
            }
        );
    }
    out
}

/// How far a pad's contact resultant may be from its clamp force before the run warns.
const CLAMP_TOLERANCE: f64 = 0.01;

/// A `warning:` line when a pad's contact resultant at the equilibrium differs from the clamp
/// force by more than [`CLAMP_TOLERANCE`]: the clamp then also goes through something else
/// (a connector or spring on the load path, a support), and the contact stiffness is that of
/// another load. Empty when every pad carries its clamp force.
fn clamp_warning(m: &Model, eq: &Equilibrium) -> String {
    let resultants: Vec<(&str, f64)> = pad_names(m)
        .into_iter()
        .map(|name| {
            let f: f64 = m
                .pairs
                .iter()
                .zip(&eq.normal_forces)
                .filter(|(p, _)| p.pad == name)
                .map(|(_, f)| f)
                .sum();
            (name, f)
        })
        .collect();
    off_clamp_warning(&resultants, m.params.piston_force)
}

/// [`clamp_warning`] from each pad's contact resultant `(name, N)` and the clamp force.
fn off_clamp_warning(resultants: &[(&str, f64)], clamp: f64) -> String {
    if clamp <= 0.0 {
        return String::new();
    }
    let off: Vec<String> = resultants
        .iter()
        .filter(|(_, f)| (f / clamp - 1.0).abs() > CLAMP_TOLERANCE)
        .map(|(name, f)| {
            let who = if name.is_empty() { "the pad" } else { name };
            format!("{who} {f:.1} N")
        })
        .collect();
    if off.is_empty() {
        return String::new();
    }
    format!(
        "warning: the contact carries {} of the clamp force {clamp:.1} N per pad: part of the clamp goes another way (a connector, spring or support on the load path: a connector's stiffness acts in the static solve too), so the contact stiffness and mu0 are those of another load\n",
        off.join(", ")
    )
}

/// Above this many contact pairs `squeal stability` prints one summary line per pad instead
/// of a line per pair (the pairs are in `equilibrium.csv` and `summary.json`).
pub const LISTED_PAIRS: usize = 40;

/// The pads' names in the order of the pairs (one unnamed pad: `""`).
fn pad_names(m: &Model) -> Vec<&str> {
    let mut names: Vec<&str> = Vec::new();
    for p in &m.pairs {
        if !names.contains(&p.pad.as_str()) {
            names.push(&p.pad);
        }
    }
    names
}

/// The range `[min, max]` of `values` as text with `unit` and the format `f`.
fn range(values: impl Iterator<Item = f64>, f: impl Fn(f64) -> String) -> String {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if lo > hi {
        return "-".into();
    }
    format!("{} .. {}", f(lo), f(hi))
}

/// The pairs as formed, one line per pad: count, largest projection distance, total area,
/// the geometric gaps' range and each law parameter's range.
pub fn formed_summary(m: &Model) -> String {
    let mut out = format!(
        "contact pairs: {} (a line per pad; every pair in equilibrium.csv and summary.json)\n",
        m.pairs.len()
    );
    for name in pad_names(m) {
        let pairs: Vec<_> = m.pairs.iter().filter(|p| p.pad == name).collect();
        let distance = pairs.iter().map(|p| p.distance).fold(0.0, f64::max);
        let area: f64 = pairs.iter().filter_map(|p| p.area).sum();
        let params = pairs.first().map_or(Vec::new(), |p| p.law.parameters());
        let laws: Vec<String> = params
            .iter()
            .enumerate()
            .map(|(k, (what, _, unit))| {
                let vals = pairs.iter().map(|p| p.law.parameters()[k].1);
                format!("{what} {} {unit}", range(vals, |v| format!("{v:.4e}")))
            })
            .collect();
        let _ = writeln!(
            out,
            "  {}{} pairs, projection distance <= {:.1e} m, area {:.4e} m^2, geometric gap {} m; {}",
            if name.is_empty() {
                String::new()
            } else {
                format!("{name}: ")
            },
            pairs.len(),
            distance,
            area,
            range(pairs.iter().map(|p| p.geometric_gap), |v| format!(
                "{v:+.1e}"
            )),
            laws.join(", ")
        );
    }
    out
}

/// The equilibrium's pairs, one line per pad: closed pairs, the initial gaps', closures' and
/// normal forces' ranges.
fn equilibrium_summary(m: &Model, eq: &Equilibrium) -> String {
    let mut out = String::new();
    for name in pad_names(m) {
        let ids: Vec<usize> = (0..m.pairs.len())
            .filter(|&p| m.pairs[p].pad == name)
            .collect();
        let closed = ids.iter().filter(|&&p| eq.penetrations[p] > 0.0).count();
        let _ = writeln!(
            out,
            "  {}{} of {} pairs closed; initial gap {} um, closure {} um, normal force {} N (every pair in equilibrium.csv)",
            if name.is_empty() {
                String::new()
            } else {
                format!("{name}: ")
            },
            closed,
            ids.len(),
            range(
                ids.iter().map(|&p| m.pairs[p].initial_gap * 1e6),
                |v| format!("{v:.3}")
            ),
            range(ids.iter().map(|&p| eq.penetrations[p] * 1e6), |v| format!(
                "{v:.3}"
            )),
            range(ids.iter().map(|&p| eq.normal_forces[p]), |v| format!(
                "{v:.2}"
            )),
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::off_clamp_warning;

    #[test]
    fn a_pad_off_its_clamp_force_by_more_than_one_percent_is_warned_about() {
        // The caliper corner's two cases: soft connectors (2996.4 N of 3000.5 N, 0.14 % off:
        // quiet) and stiff ones (165.7 N: warned, naming the pad); 1 % is the limit.
        let clamp = 3000.522;
        assert_eq!(
            off_clamp_warning(&[("inboard", 2996.366), ("outboard", 2996.366)], clamp),
            ""
        );
        let w = off_clamp_warning(&[("inboard", 165.7), ("outboard", 2996.366)], clamp);
        assert!(
            w.starts_with(
                "warning: the contact carries inboard 165.7 N of the clamp force 3000.5 N"
            ),
            "{w}"
        );
        assert!(!w.contains("outboard"), "{w}");
        assert!(!off_clamp_warning(&[("", 0.989 * clamp)], clamp).is_empty());
        assert!(off_clamp_warning(&[("", 0.991 * clamp)], clamp).is_empty());
        assert_eq!(off_clamp_warning(&[("", 0.0)], 0.0), "");
    }
}
