//! What a cycle of the branch measures: the truncation of its harmonic series and each contact pair's closure over the period.

use super::*;

/// Energy share of the highest harmonic in `u`.
pub fn truncation(layout: &HarmonicLayout, u: &[f64]) -> f64 {
    let h = layout.n_harmonics();
    let energy = |k: usize| -> f64 {
        (0..layout.n_dofs())
            .map(|i| layout.amplitude(u, k, i).unwrap_or(0.0).powi(2))
            .sum()
    };
    let total: f64 = (1..=h).map(energy).sum();
    if total > 0.0 { energy(h) / total } else { 0.0 }
}

/// Each pair's closure over the cycle `u` (nonlinear dofs).
pub fn pair_cycles(mb: &ModalBrake, layout: &HarmonicLayout, u: &[f64]) -> Vec<PairCycle> {
    let nn = layout.n_dofs();
    let mut x = vec![0.0; nn];
    let mut out: Vec<PairCycle> = mb
        .pairs
        .iter()
        .map(|_| PairCycle {
            mean: 0.0,
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            open_fraction: 0.0,
        })
        .collect();
    for s in 0..PAIR_SAMPLES {
        let theta = 2.0 * std::f64::consts::PI * s as f64 / PAIR_SAMPLES as f64;
        // The layout matches `u` by construction; a mismatch leaves x at zero.
        if layout.displacement_at(u, theta, &mut x).is_err() {
            continue;
        }
        for (p, c) in mb.pairs.iter().zip(out.iter_mut()) {
            let d = p.penetration(&x);
            c.min = c.min.min(d);
            c.max = c.max.max(d);
            c.mean += d / PAIR_SAMPLES as f64;
            if d <= 0.0 {
                c.open_fraction += 1.0 / PAIR_SAMPLES as f64;
            }
        }
    }
    // The open fractions from the roots of the continuous penetration; the counted ones stay
    // only if the series cannot be built (a layout mismatch, as above).
    let nl: Vec<usize> = (0..nn).collect();
    let roots = Cycle::from_coefficients(layout.n_harmonics(), 1.0, nn, u.to_vec())
        .and_then(|c| crate::physics::open_fractions_of(&mb.pairs, &nl, &c));
    if let Ok(f) = roots {
        for (c, f) in out.iter_mut().zip(f) {
            c.open_fraction = f;
        }
    }
    out
}
