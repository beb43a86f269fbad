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
