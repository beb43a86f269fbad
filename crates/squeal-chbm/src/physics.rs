//! Issue #10, item 8: the physical checks a limit cycle of the model takes for granted.
//!
//! **Open fractions.** A pair is open where its penetration `δ(θ) = g · x(θ) - g0` (`g0` the pair's initial gap) is not
//! positive. On a cycle `δ` is a trigonometric polynomial of the cycle's degree `H`, so its
//! open set is bounded by its roots: [`open_fractions`] brackets them on a grid of
//! `16 (2H + 1)` phases (a polynomial of degree `H` has at most `2H` roots per period) and
//! refines each by bisection to round-off, instead of counting samples (which resolves an
//! open fraction only to one sample).
//!
//! **Permanent sliding.** The model's friction force keeps one sign: the disc surface must
//! outrun the pad's tangential vibration at every pair, `V_p > max_θ |h_p · x'(θ)|`.
//! [`sliding_margin`] returns `V_p / max |h_p · x'|` per pair; below 1 the pair would stick
//! for part of the cycle, and stick–slip is outside the model.

use crate::cycle::Cycle;
use squeal_brake::modal_brake::ModalBrake;
use squeal_brake::model::ContactPair;
use squeal_hbm::HbmError;
use std::f64::consts::PI;

/// Penetration of `pair` at phase θ of `nl`, the cycle restricted to the nonlinear dofs.
fn penetration_at(pair: &ContactPair, nl: &Cycle, theta: f64) -> f64 {
    pair.normal
        .iter()
        .map(|&(k, a)| a * nl.value_at(k, theta, false))
        .sum::<f64>()
        - pair.initial_gap
}

/// Tangential velocity `h_p · x'(θ)` of `pair`.
fn tangential_velocity_at(pair: &ContactPair, nl: &Cycle, theta: f64) -> f64 {
    pair.tangent
        .iter()
        .map(|&(k, a)| a * nl.value_at(k, theta, true))
        .sum()
}

/// The phase grid of the module docs: `16 (2H + 1)` points over one period.
fn grid(nl: &Cycle) -> usize {
    16 * (2 * nl.harmonics() + 1)
}

/// Fraction of the period each pair of `mb` is open (`δ ≤ 0`) on the cycle `c` (every
/// physical dof), from the roots of the continuous penetration (module docs).
pub fn open_fractions(mb: &ModalBrake, c: &Cycle) -> Result<Vec<f64>, HbmError> {
    open_fractions_of(&mb.pairs, &mb.nl_dofs, c)
}

/// [`open_fractions`] of `pairs`, whose dof indices are positions in `nl_dofs` (the dofs of `c`
/// they act on).
pub fn open_fractions_of(
    pairs: &[ContactPair],
    nl_dofs: &[usize],
    c: &Cycle,
) -> Result<Vec<f64>, HbmError> {
    let nl = c.restrict(nl_dofs)?;
    let n = grid(&nl);
    let step = 2.0 * PI / n as f64;
    Ok(pairs
        .iter()
        .map(|p| {
            let f = |th: f64| penetration_at(p, &nl, th);
            // Whole open intervals counted apart, so that an always open pair gives exactly 1.
            let (mut whole, mut part) = (0usize, 0.0);
            let (mut a, mut fa) = (0.0, f(0.0));
            for i in 1..=n {
                let b = i as f64 * step;
                let fb = f(b);
                match (fa <= 0.0, fb <= 0.0) {
                    (true, true) => whole += 1,
                    (false, false) => {}
                    (oa, _) => {
                        let r = bisect(&f, a, b, fa);
                        part += if oa { r - a } else { b - r };
                    }
                }
                (a, fa) = (b, fb);
            }
            (whole as f64 / n as f64 + part / (2.0 * PI)).clamp(0.0, 1.0)
        })
        .collect())
}

/// The root of `f` in `[a, b]` where it changes sign (`f(a) = fa`), to round-off.
fn bisect(f: &dyn Fn(f64) -> f64, mut a: f64, mut b: f64, fa: f64) -> f64 {
    let open_a = fa <= 0.0;
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if (f(m) <= 0.0) == open_a {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// How fast the disc turns and about which axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiscSpeed {
    /// Angular speed Ω (rad/s).
    pub angular_speed: f64,
    /// A point of the axis (m).
    pub origin: [f64; 3],
    /// Unit direction of the axis.
    pub axis: [f64; 3],
}

impl DiscSpeed {
    /// The disc's surface speed at every pair: `|Ω|` times the pair's distance from the axis.
    pub fn surface_speeds(&self, pairs: &[ContactPair]) -> Vec<f64> {
        pairs
            .iter()
            .map(|p| {
                let r: [f64; 3] = std::array::from_fn(|i| p.position[i] - self.origin[i]);
                let along: f64 = (0..3).map(|i| r[i] * self.axis[i]).sum();
                let radial = (0..3)
                    .map(|i| (r[i] - along * self.axis[i]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                self.angular_speed.abs() * radial
            })
            .collect()
    }
}

/// Whether the disc outruns the pad's tangential vibration at every pair of a cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct SlidingMargin {
    /// `max_θ |h_p · x'(θ)|` per pair (m/s).
    pub max_tangential_velocity: Vec<f64>,
    /// `V_p / max |h_p · x'|` per pair (infinite for a pair that does not move).
    pub margins: Vec<f64>,
    /// The smallest margin and its pair; below 1 the pair sticks for part of the cycle.
    pub min: f64,
    /// Index of the pair of [`SlidingMargin::min`].
    pub pair: usize,
}

impl SlidingMargin {
    /// Permanent sliding holds at every pair (`min > 1`).
    pub fn sliding(&self) -> bool {
        self.min > 1.0
    }
}

/// Largest `|h_p · x'(θ)|` of `pair`: the grid's largest sample refined by the parabola through
/// it and its neighbours (relative error far below the grid's `(π H / n)²`).
fn max_tangential_velocity(pair: &ContactPair, nl: &Cycle) -> f64 {
    let n = grid(nl);
    let step = 2.0 * PI / n as f64;
    let g = |i: isize| tangential_velocity_at(pair, nl, i as f64 * step).abs();
    let (mut best, mut at) = (0.0, 0isize);
    for i in 0..n as isize {
        let v = g(i);
        if v > best {
            (best, at) = (v, i);
        }
    }
    let (l, m, r) = (g(at - 1), best, g(at + 1));
    let den = l - 2.0 * m + r;
    if den < 0.0 {
        let t = (0.5 * (l - r) / den).clamp(-1.0, 1.0);
        let th = (at as f64 + t) * step;
        best = best.max(tangential_velocity_at(pair, nl, th).abs());
    }
    best
}

/// The sliding margin of the cycle `c` (every physical dof) of `mb` with the disc turning at
/// `disc` (module docs).
pub fn sliding_margin(
    mb: &ModalBrake,
    c: &Cycle,
    disc: &DiscSpeed,
) -> Result<SlidingMargin, HbmError> {
    sliding_margin_of(&mb.pairs, &mb.nl_dofs, c, &disc.surface_speeds(&mb.pairs))
}

/// [`sliding_margin`] of `pairs`, whose dof indices are positions in `nl_dofs`.
pub fn sliding_margin_of(
    pairs: &[ContactPair],
    nl_dofs: &[usize],
    c: &Cycle,
    speeds: &[f64],
) -> Result<SlidingMargin, HbmError> {
    let nl = c.restrict(nl_dofs)?;
    let vmax: Vec<f64> = pairs
        .iter()
        .map(|p| max_tangential_velocity(p, &nl))
        .collect();
    let margins: Vec<f64> = vmax
        .iter()
        .zip(speeds)
        .map(|(&v, &s)| if v > 0.0 { s / v } else { f64::INFINITY })
        .collect();
    let (pair, min) = margins
        .iter()
        .copied()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0, f64::INFINITY));
    Ok(SlidingMargin {
        max_tangential_velocity: vmax,
        margins,
        min,
        pair,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use squeal_brake::contact::PenaltyCoulomb;
    use std::sync::Arc;

    /// A pair closing on dof 0 (`δ = x0 + closure`, initial gap `-closure`) and sliding along
    /// dof 1, 0.1 m from the z axis.
    fn pair(closure: f64) -> ContactPair {
        ContactPair {
            disc_point: 0,
            pad_point: 0,
            position: [0.06, 0.08, 0.01],
            normal_direction: [0.0, 0.0, 1.0],
            sliding_direction: [1.0, 0.0, 0.0],
            normal: vec![(0, 1.0)],
            tangent: vec![(1, 1.0)],
            initial_gap: -closure,
            surface_speed: None,
            law: Arc::new(PenaltyCoulomb {
                k_linear: 1.0,
                k_cubic: 0.0,
            }),
        }
    }

    /// Two dofs: `x0 = a1 cos θ + a3 cos 3θ + b2 sin 2θ`, `x1 = c sin θ`, at ω.
    fn cycle(a1: f64, a3: f64, b2: f64, c: f64, omega: f64) -> Cycle {
        let h = 3;
        let mut x = vec![0.0; 2 * (2 * h + 1)];
        // Entry `i` of block `b` at `2 b + i` (eq 25): block 1 cos θ, 2 sin θ, 4 sin 2θ, 5 cos 3θ.
        x[2] = a1;
        x[2 * 2 + 1] = c;
        x[2 * 4] = b2;
        x[2 * 5] = a3;
        Cycle::from_coefficients(h, omega, 2, x).unwrap()
    }

    #[test]
    fn open_fraction_is_exact_on_a_cosine_and_matches_dense_sample_counting() {
        // gap + A cos θ ≤ 0 on 1 - acos(-gap/A)/π of the period: 1/3 for gap/A = 1/2; bisection
        // to round-off, so 1e-12.
        let c = cycle(2e-6, 0.0, 0.0, 0.0, 1.0);
        let f = open_fractions_of(&[pair(1e-6)], &[0, 1], &c).unwrap()[0];
        assert!((f - 1.0 / 3.0).abs() < 1e-12, "{f}");
        // With second and third harmonics (four boundaries per period): sample counting on
        // 10^6 phases is off by at most one sample per boundary, so 4e-6 bounds the difference.
        let c = cycle(2e-6, 0.7e-6, 0.5e-6, 0.0, 1.0);
        let f = open_fractions_of(&[pair(1e-6)], &[0, 1], &c).unwrap()[0];
        let n = 1_000_000;
        let counted = (0..n)
            .filter(|&s| 1e-6 + c.value_at(0, 2.0 * PI * s as f64 / n as f64, false) <= 0.0)
            .count() as f64
            / n as f64;
        assert!((f - counted).abs() < 4e-6, "{f} against {counted}");
        assert!(f > 0.05 && f < 0.95, "{f}");
        // Closed all along, and open all along.
        let shut = open_fractions_of(&[pair(1e-5)], &[0, 1], &c).unwrap()[0];
        let open = open_fractions_of(&[pair(-1e-5)], &[0, 1], &c).unwrap()[0];
        assert_eq!((shut, open), (0.0, 1.0));
    }

    #[test]
    fn sliding_margin_is_surface_speed_over_peak_tangential_velocity() {
        // x1 = c sin θ at ω: peak tangential velocity c ω = 1e-5 · 2e4 = 0.2 m/s; the pair sits
        // 0.1 m from the z axis, so 30 rad/s give 3 m/s and a margin of 15. The parabola through
        // the grid's peak is exact to (step)^4, far below the 1e-9 asked.
        let c = cycle(1e-6, 0.0, 0.0, 1e-5, 2e4);
        let pairs = [pair(1e-6)];
        let disc = DiscSpeed {
            angular_speed: -30.0,
            origin: [0.0, 0.0, 5.0],
            axis: [0.0, 0.0, 1.0],
        };
        let speeds = disc.surface_speeds(&pairs);
        assert!((speeds[0] - 3.0).abs() < 1e-12, "{speeds:?}");
        let m = sliding_margin_of(&pairs, &[0, 1], &c, &speeds).unwrap();
        assert!(
            (m.max_tangential_velocity[0] - 0.2).abs() < 1e-9 * 0.2,
            "{m:?}"
        );
        assert!((m.min - 15.0).abs() < 1e-8 * 15.0 && m.sliding(), "{m:?}");
        let slow = sliding_margin_of(&pairs, &[0, 1], &c, &[0.1]).unwrap();
        assert!((slow.min - 0.5).abs() < 1e-9 && !slow.sliding(), "{slow:?}");
    }
}
