//! Parametric studies of the brake's stability, as in sections 6.2–6.4 of Coudeyras, Sinou &
//! Nacivet (2009), and the measures that tell which modes couple.
//!
//! - Cases ([`Case`]): factors on the nominal piston force (Table 4), on both contact
//!   stiffnesses `k_l`, `k_nl` of eq (8) (Table 5), and on the pair damping `D1`, `D2` of
//!   eq (13) (Table 6). [`run_cases`] runs them in parallel and keeps what the tables and the
//!   Figures 9–11 (a, b) need ([`CaseOutcome`]).
//! - Damping-induced destabilization ([`other_mode_growth`]): with damping on the coalescing
//!   pair only, every undamped mode `j` picks up, to second order in the friction coupling `ΔK`
//!   of eq (20) in modal coordinates, the real part of [`second_order_real_part`] (a
//!   Ziegler-type paradox: circulatory forces plus non-uniform damping).
//! - Shapes: circumferential orders of the disc's out-of-plane motion on a circle
//!   ([`circumferential_orders`]: the dominant order is the number of nodal diameters), the
//!   pad's out-of-plane profile along its length ([`pad_profile`]), and the kinetic-energy
//!   share of a set of dofs ([`energy_share`]).

use crate::analysis::{DampingSpec, LinearStability, PairChoice, basis_mode_of_branch, stability};
use crate::error::BrakeError;
use crate::linearized::LinearizedBrake;
use crate::model::Brake;
use crate::sweep::{Crossing, Sweep, SweepOptions, default_threshold};
use faer::{Mat, c64};
use rayon::prelude::*;
use std::f64::consts::PI;
use std::ops::Range;

/// One case of a parametric study, as factors on the nominal brake.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// Case number as in the paper's Tables 4–6 (1 is the nominal brake).
    pub number: usize,
    /// Short label, e.g. `0.8 P0` or `D1/D2 = 1/5`.
    pub label: String,
    /// Factor on the piston force (Table 4: 0.8, 1, 1.2).
    pub pressure: f64,
    /// Factor on both contact stiffnesses `k_l`, `k_nl` (Table 5: 0.7, 1, 1.3).
    pub stiffness: f64,
    /// `D1`, `D2` of eq (13) in units of the nominal pair damping ratios (Table 6).
    pub pair_factors: [f64; 2],
}

impl Default for Case {
    /// The nominal brake (case 1 of every table).
    fn default() -> Self {
        Self {
            number: 1,
            label: "nominal".into(),
            pressure: 1.0,
            stiffness: 1.0,
            pair_factors: [1.0, 1.0],
        }
    }
}

/// Table 4: piston pressure `P0` (case 1), `0.8 P0` (case 5), `1.2 P0` (case 6).
pub fn pressure_cases() -> Vec<Case> {
    [(1, "P0", 1.0), (5, "0.8 P0", 0.8), (6, "1.2 P0", 1.2)]
        .into_iter()
        .map(|(number, label, pressure)| Case {
            number,
            label: label.into(),
            pressure,
            ..Case::default()
        })
        .collect()
}

/// Table 5: contact stiffness `ks` (case 1), `0.7 ks` (case 7), `1.3 ks` (case 8).
pub fn stiffness_cases() -> Vec<Case> {
    [(1, "ks", 1.0), (7, "0.7 ks", 0.7), (8, "1.3 ks", 1.3)]
        .into_iter()
        .map(|(number, label, stiffness)| Case {
            number,
            label: label.into(),
            stiffness,
            ..Case::default()
        })
        .collect()
}

/// Table 6: `D1/D2` = 1/1, 5/5, 10/10 (equally damped, cases 1–3), 1/2, 1/5 (Mode 2 more
/// damped, cases 4–5), 2/1, 5/1 (Mode 1 more damped, cases 6–7).
pub fn damping_cases() -> Vec<Case> {
    [
        (1.0, 1.0),
        (5.0, 5.0),
        (10.0, 10.0),
        (1.0, 2.0),
        (1.0, 5.0),
        (2.0, 1.0),
        (5.0, 1.0),
    ]
    .into_iter()
    .enumerate()
    .map(|(i, (d1, d2))| Case {
        number: i + 1,
        label: format!("D1/D2 = {d1}/{d2}"),
        pair_factors: [d1, d2],
        ..Case::default()
    })
    .collect()
}

fn positive(value: f64, what: &'static str) -> Result<(), BrakeError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(BrakeError::NotPositive { what, value })
    }
}

/// The brake of a case: the piston force of eq (11) times `pressure`, and each pair's contact
/// forces (for eq (8), `k_l` and `k_nl`) times `stiffness`.
pub fn scaled_brake(brake: &Brake, pressure: f64, stiffness: f64) -> Result<Brake, BrakeError> {
    positive(pressure, "pressure factor")?;
    positive(stiffness, "contact stiffness factor")?;
    let mut b = brake.with_contact_scale(stiffness);
    for f in &mut b.f_piston {
        *f *= pressure;
    }
    Ok(b)
}

/// The damping of a case, eqs (12)–(13): the nominal global ratio, and the nominal pair ratios
/// times the case's `D1`, `D2` factors, on `pair` when given (else on the nominal's choice).
pub fn case_damping(
    nominal: &DampingSpec,
    case: &Case,
    pair: Option<(usize, usize)>,
) -> Result<DampingSpec, BrakeError> {
    for f in case.pair_factors {
        if !(f.is_finite() && f >= 0.0) {
            return Err(BrakeError::Negative {
                what: "pair damping factor",
                value: f,
            });
        }
    }
    Ok(DampingSpec {
        global_ratio: nominal.global_ratio,
        pair: pair.map_or(nominal.pair, |(a, b)| PairChoice::Modes(a, b)),
        pair_ratios: [
            nominal.pair_ratios[0] * case.pair_factors[0],
            nominal.pair_ratios[1] * case.pair_factors[1],
        ],
    })
}

/// A tracked branch over a sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct BranchCurve {
    /// The frictionless mode (0-based) the branch starts from.
    pub basis_mode: usize,
    /// The sweep's friction values.
    pub mu: Vec<f64>,
    /// Eigenvalue `λ = a + iω` (eq 22) at each μ.
    pub values: Vec<c64>,
}

impl BranchCurve {
    fn of(sweep: &Sweep, branch: usize) -> BranchCurve {
        BranchCurve {
            basis_mode: basis_mode_of_branch(sweep, branch),
            mu: sweep.points.iter().map(|p| p.equilibrium.mu).collect(),
            values: (0..sweep.points.len())
                .map(|k| sweep.value(branch, k))
                .collect(),
        }
    }
}

/// What a case's tables and figures need from its stability analysis.
#[derive(Clone, Debug, PartialEq)]
pub struct CaseOutcome {
    /// The case.
    pub case: Case,
    /// The refined Hopf point μ0, when the sweep has one.
    pub mu0: Option<f64>,
    /// Frequency (Hz) of the unstable mode at μ0, when there is a Hopf point.
    pub frequency_hz: Option<f64>,
    /// Frictionless modes (0-based) of Mode 1 (stays stable) and Mode 2 (goes unstable).
    pub pair: Option<(usize, usize)>,
    /// Their frictionless frequencies (Hz).
    pub pair_hz: Option<(f64, f64)>,
    /// The branch that goes unstable (Mode 2), when found.
    pub unstable: Option<BranchCurve>,
    /// The partner branch (Mode 1), when found.
    pub partner: Option<BranchCurve>,
    /// Every upward crossing of the sweep.
    pub crossings: Vec<Crossing>,
}

/// Branches of Mode 2 and Mode 1: the Hopf point's branch and partner, or else the branches
/// that start from the pair's frictionless modes.
pub fn pair_branches(st: &LinearStability) -> (Option<usize>, Option<usize>) {
    let sw = &st.sweep;
    if let Some(h) = &sw.hopf {
        return (Some(h.branch), h.partner);
    }
    let find = |m: usize| (0..sw.branches.len()).find(|&b| basis_mode_of_branch(sw, b) == m);
    match st.pair {
        Some((m1, m2)) => (find(m2), find(m1)),
        None => (None, None),
    }
}

/// Extracts a case's outcome from its stability analysis.
pub fn outcome(case: &Case, st: &LinearStability) -> CaseOutcome {
    let sw = &st.sweep;
    let (unstable, partner) = pair_branches(st);
    let hz = |m: usize| st.reference.basis.omega[m] / (2.0 * PI);
    CaseOutcome {
        case: case.clone(),
        mu0: sw.hopf.as_ref().map(|h| h.mu0),
        frequency_hz: sw.hopf.as_ref().map(|h| h.frequency_hz),
        pair: st.pair,
        pair_hz: st.pair.map(|(a, b)| (hz(a), hz(b))),
        unstable: unstable.map(|b| BranchCurve::of(sw, b)),
        partner: partner.map(|b| BranchCurve::of(sw, b)),
        crossings: sw.crossings.clone(),
    }
}

/// Runs one case: the nominal brake scaled by the case's factors, the nominal damping with
/// the case's pair factors (on `pair` when given), swept over `mus`.
pub fn run_case(
    brake: &Brake,
    nominal: &DampingSpec,
    case: &Case,
    pair: Option<(usize, usize)>,
    mus: &[f64],
    opts: &SweepOptions,
) -> Result<CaseOutcome, BrakeError> {
    let b = scaled_brake(brake, case.pressure, case.stiffness)?;
    let spec = case_damping(nominal, case, pair)?;
    let st = stability(&b, &spec, mus, opts)?;
    Ok(outcome(case, &st))
}

/// Runs the cases in parallel (rayon); results in the order of `cases`, bit-identical for
/// any thread count (each case is computed independently).
pub fn run_cases(
    brake: &Brake,
    nominal: &DampingSpec,
    cases: &[Case],
    pair: Option<(usize, usize)>,
    mus: &[f64],
    opts: &SweepOptions,
) -> Vec<Result<CaseOutcome, BrakeError>> {
    cases
        .par_iter()
        .map(|c| run_case(brake, nominal, c, pair, mus, opts))
        .collect()
}

/// The friction values of the small-friction study: 0, then 1, 2, 5 × 10⁻⁴ … 10⁻¹.
pub fn small_friction_grid() -> Vec<f64> {
    let mut mus = vec![0.0];
    for e in -4..=-1 {
        for m in [1.0, 2.0, 5.0] {
            let v = m * 10f64.powi(e);
            if v <= 0.1 + 1e-15 {
                mus.push(v);
            }
        }
    }
    mus
}

/// Second-order perturbation of the eigenvalue `λ ≈ iω_j` of `q'' + D q' + (Ω² + ΔK) q = 0`
/// (eq 20 in the frictionless modal coordinates, `D` diagonal):
///
/// `Re λ_j ≈ -d_j/2 - Σ_{k≠j} ΔK_jk ΔK_kj d_k / (2 [(ω_k² - ω_j²)² + ω_j² d_k²])`.
///
/// It follows from eliminating `q_k ≈ -ΔK_kj q_j / (λ² + λ d_k + ω_k²)` in row `j` at
/// `λ = iω_j`; it is exact to second order in `ΔK` for an undamped mode (`d_j = 0`). Friction
/// makes `ΔK` non-symmetric, so `ΔK_jk ΔK_kj` can be negative: the damping `d_k` of another
/// mode then destabilizes mode `j`.
pub fn second_order_real_part(omega: &[f64], d: &[f64], dk: &Mat<f64>, j: usize) -> f64 {
    let wj2 = omega[j] * omega[j];
    let mut s = -0.5 * d[j];
    for k in 0..omega.len() {
        if k == j || d[k] == 0.0 {
            continue;
        }
        let gap = omega[k] * omega[k] - wj2;
        s -= dk[(j, k)] * dk[(k, j)] * d[k] / (2.0 * (gap * gap + wj2 * d[k] * d[k]));
    }
    s
}

/// The growth of the modes outside the coalescing pair at one friction value.
#[derive(Clone, Debug, PartialEq)]
pub struct GrowthRow {
    /// Friction coefficient of the sweep point.
    pub mu: f64,
    /// Largest `Re λ / |λ|` over the in-band modes outside the pair (`-ζ` of a damped mode).
    pub max_ratio: f64,
    /// That mode's `Re λ` (s⁻¹).
    pub real_part: f64,
    /// Frequency (Hz) of that mode.
    pub frequency_hz: f64,
    /// Frictionless mode (0-based) the most unstable branch starts from.
    pub basis_mode: usize,
    /// In-band modes outside the pair with `Re λ` above the instability threshold.
    pub unstable: usize,
    /// [`second_order_real_part`] of that mode over `|λ|`.
    pub predicted_ratio: f64,
}

/// For each sweep point, the most unstable in-band mode outside the pair and the number of
/// unstable ones (the threshold is the sweep's, [`default_threshold`] unless `opts` gives one),
/// with the second-order prediction for that mode.
pub fn other_mode_growth(
    brake: &Brake,
    st: &LinearStability,
    opts: &SweepOptions,
) -> Result<Vec<GrowthRow>, BrakeError> {
    let sw = &st.sweep;
    let r = &st.reference;
    let d = r
        .damping
        .diagonal()
        .ok_or(BrakeError::NeedsDiagonalDamping {
            analysis: "the second-order damping paradox estimate",
        })?;
    let lin = LinearizedBrake::new(brake, r)?;
    let tau = opts.threshold.unwrap_or_else(|| default_threshold(r));
    let pair: Vec<usize> = st.pair.map_or(vec![], |(a, b)| vec![a, b]);
    let others: Vec<usize> = (0..sw.branches.len())
        .filter(|&b| !pair.contains(&basis_mode_of_branch(sw, b)))
        .collect();
    let mut rows = Vec::with_capacity(sw.points.len());
    for (k, p) in sw.points.iter().enumerate() {
        let in_band = |b: usize| {
            opts.band
                .contains(p.spectrum.frequency_hz(sw.branches[b][k]))
        };
        let ratio = |b: usize| {
            let l = sw.value(b, k);
            l.re / l.norm().max(f64::MIN_POSITIVE)
        };
        let Some(worst) = others
            .iter()
            .copied()
            .filter(|&b| in_band(b))
            .max_by(|&a, &b| ratio(a).total_cmp(&ratio(b)).then(b.cmp(&a)))
        else {
            continue;
        };
        let unstable = others
            .iter()
            .filter(|&&b| in_band(b) && sw.value(b, k).re > tau)
            .count();
        let (dk, _) = lin.dense_change(&lin.coupling(brake, &p.equilibrium));
        let j = basis_mode_of_branch(sw, worst);
        let predicted = second_order_real_part(&r.basis.omega, d, &dk, j);
        rows.push(GrowthRow {
            mu: p.equilibrium.mu,
            max_ratio: ratio(worst),
            real_part: sw.value(worst, k).re,
            frequency_hz: p.spectrum.frequency_hz(sw.branches[worst][k]),
            basis_mode: j,
            unstable,
            predicted_ratio: predicted / sw.value(worst, k).norm().max(f64::MIN_POSITIVE),
        });
    }
    Ok(rows)
}

/// Least-squares slope of `ln y` against `ln x` over the points with both positive.
pub fn log_slope(x: &[f64], y: &[f64]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = x
        .iter()
        .zip(y)
        .filter(|(a, b)| **a > 0.0 && **b > 0.0)
        .map(|(a, b)| (a.ln(), b.ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Shares of the circumferential orders `0..=max_order` in a field sampled around a circle.
#[derive(Clone, Debug, PartialEq)]
pub struct OrderSpectrum {
    /// `shares[n]`: the part of the field's mean square in `cos nθ`, `sin nθ` (both
    /// directions of travel); the rest is in higher orders.
    pub shares: Vec<f64>,
    /// Largest angular gap between samples (radians): orders above about `π / gap` are
    /// unresolved.
    pub max_gap: f64,
}

impl OrderSpectrum {
    /// The order with the largest share, and its share.
    pub fn dominant(&self) -> (usize, f64) {
        let mut best = (0, f64::NEG_INFINITY);
        for (n, &s) in self.shares.iter().enumerate() {
            if s > best.1 {
                best = (n, s);
            }
        }
        best
    }
}

/// Interpolation points of the circumferential Fourier analysis.
const RING_SAMPLES: usize = 360;

/// Fourier analysis of `values` at `angles` (radians) around a full circle: the samples are
/// interpolated linearly (periodically) onto 360 equally spaced angles, whose discrete Fourier
/// coefficients `c_n` give each order's share `(|c_n|² + |c_-n|²) / mean square`. For a disc
/// mode, the dominant order of the out-of-plane motion is its number of nodal diameters.
pub fn circumferential_orders(
    angles: &[f64],
    values: &[c64],
    max_order: usize,
) -> Result<OrderSpectrum, BrakeError> {
    if angles.len() != values.len() || angles.len() < 4 {
        return Err(BrakeError::Samples {
            what: "a circumferential analysis",
            needed: 4,
            positions: angles.len(),
            values: values.len(),
        });
    }
    if max_order >= RING_SAMPLES / 2 {
        return Err(BrakeError::OrderTooHigh {
            asked: max_order,
            max: RING_SAMPLES / 2 - 1,
        });
    }
    let mut s: Vec<(f64, c64)> = angles
        .iter()
        .zip(values)
        .map(|(a, v)| (a.rem_euclid(2.0 * PI), *v))
        .collect();
    if s.iter()
        .any(|(a, v)| !(a.is_finite() && v.re.is_finite() && v.im.is_finite()))
    {
        return Err(BrakeError::NonFiniteSample {
            what: "a circumferential analysis",
        });
    }
    s.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = s.len();
    let gap = |i: usize| {
        if i + 1 < n {
            s[i + 1].0 - s[i].0
        } else {
            s[0].0 + 2.0 * PI - s[n - 1].0
        }
    };
    let max_gap = (0..n).map(gap).fold(0.0, f64::max);
    let grid: Vec<c64> = (0..RING_SAMPLES)
        .map(|g| periodic_interpolation(&s, 2.0 * PI * g as f64 / RING_SAMPLES as f64))
        .collect();
    let mean_square = grid.iter().map(|v| v.norm_sqr()).sum::<f64>() / RING_SAMPLES as f64;
    let coefficient = |order: i64| -> c64 {
        let mut c = c64::new(0.0, 0.0);
        for (g, v) in grid.iter().enumerate() {
            let t = -2.0 * PI * (order * g as i64) as f64 / RING_SAMPLES as f64;
            c += v * c64::new(t.cos(), t.sin());
        }
        c / RING_SAMPLES as f64
    };
    let shares = (0..=max_order as i64)
        .map(|o| {
            let e = if o == 0 {
                coefficient(0).norm_sqr()
            } else {
                coefficient(o).norm_sqr() + coefficient(-o).norm_sqr()
            };
            e / mean_square.max(f64::MIN_POSITIVE)
        })
        .collect();
    Ok(OrderSpectrum { shares, max_gap })
}

/// Linear interpolation at angle `t` in samples sorted by angle on `[0, 2π)`, wrapping around.
fn periodic_interpolation(s: &[(f64, c64)], t: f64) -> c64 {
    let n = s.len();
    // First sample at or after t; the one before it (cyclically) starts the interval.
    let hi = s.partition_point(|p| p.0 < t);
    let (a, b) = if hi == 0 || hi == n {
        (n - 1, 0)
    } else {
        (hi - 1, hi)
    };
    let (ta, mut tb) = (s[a].0, s[b].0);
    let mut tt = t;
    if tb <= ta {
        tb += 2.0 * PI;
        if tt < ta {
            tt += 2.0 * PI;
        }
    }
    let w = if tb > ta { (tt - ta) / (tb - ta) } else { 0.0 };
    s[a].1 * (1.0 - w) + s[b].1 * w
}

/// The pad's out-of-plane motion along its length.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// Sign changes along the length (values under 5% of the largest are skipped): 0 for a
    /// bounce, 1 for rocking (or a first bending with one node), 2 for the first free-free
    /// bending.
    pub sign_changes: usize,
    /// Part of the mean square carried by the best straight line (rigid bounce and rocking);
    /// the rest is bending.
    pub rigid_share: f64,
}

/// Profile of a (complex) displacement `w` at positions `s` along the pad: the phase is turned
/// to make the real part largest (`arg Σ w² / 2`), then the real part is analysed.
pub fn pad_profile(s: &[f64], w: &[c64]) -> Result<Profile, BrakeError> {
    if s.len() != w.len() || s.len() < 3 {
        return Err(BrakeError::Samples {
            what: "a pad profile",
            needed: 3,
            positions: s.len(),
            values: w.len(),
        });
    }
    let sum_sq = w.iter().fold(c64::new(0.0, 0.0), |acc, v| acc + v * v);
    let phase = 0.5 * sum_sq.im.atan2(sum_sq.re);
    let turn = c64::new(phase.cos(), -phase.sin());
    let mut p: Vec<(f64, f64)> = s.iter().zip(w).map(|(x, v)| (*x, (v * turn).re)).collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0));
    let big = p.iter().map(|q| q.1.abs()).fold(0.0, f64::max);
    let mut sign_changes = 0;
    let mut last = 0.0f64;
    for q in &p {
        if q.1.abs() < 0.05 * big {
            continue;
        }
        if last != 0.0 && q.1.signum() != last.signum() {
            sign_changes += 1;
        }
        last = q.1;
    }
    let n = p.len() as f64;
    let (mx, my) = (
        p.iter().map(|q| q.0).sum::<f64>() / n,
        p.iter().map(|q| q.1).sum::<f64>() / n,
    );
    let sxx: f64 = p.iter().map(|q| (q.0 - mx).powi(2)).sum();
    let slope = if sxx > 0.0 {
        p.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum::<f64>() / sxx
    } else {
        0.0
    };
    let total: f64 = p.iter().map(|q| q.1 * q.1).sum();
    let residual: f64 = p
        .iter()
        .map(|q| (q.1 - my - slope * (q.0 - mx)).powi(2))
        .sum();
    Ok(Profile {
        sign_changes,
        rigid_share: if total > 0.0 {
            1.0 - residual / total
        } else {
            0.0
        },
    })
}

/// Share of the kinetic energy `xᴴ M x` held by the dofs in `range` (a diagonal block of the
/// brake's block-diagonal mass matrix, e.g. the disc's).
pub fn energy_share(m: &Mat<f64>, x: &[c64], range: Range<usize>) -> f64 {
    let block = |r: Range<usize>| -> f64 {
        let mut e = 0.0;
        for i in r.clone() {
            for j in r.clone() {
                e += (x[i].conj() * x[j]).re * m[(i, j)];
            }
        }
        e
    };
    let n = x.len().min(m.nrows());
    let part = block(range.start.min(n)..range.end.min(n));
    let total = block(0..n);
    if total > 0.0 { part / total } else { 0.0 }
}

/// What a mode's shape shows, for telling which modes couple.
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeSummary {
    /// The mode's frequency (Hz).
    pub frequency_hz: f64,
    /// Share of the kinetic energy in the disc ([`energy_share`]).
    pub disc_energy: f64,
    /// Circumferential orders of the disc's out-of-plane motion on the mid-radius circle of its
    /// braking face ([`circumferential_orders`]).
    pub orders: OrderSpectrum,
    /// Out-of-plane part of the mean square motion of that circle's nodes.
    pub out_of_plane: f64,
    /// The pad's out-of-plane profile along its length ([`pad_profile`]).
    pub pad: Profile,
}

impl ShapeSummary {
    /// Number of nodal diameters: the dominant circumferential order.
    pub fn nodal_diameters(&self) -> usize {
        self.orders.dominant().0
    }

    /// The pad's motion in a word: `bounce` or `rocking` when a straight line carries at least
    /// 80% of its profile (no sign change, or some), else `bending`.
    pub fn pad_kind(&self) -> &'static str {
        match (self.pad.rigid_share >= 0.8, self.pad.sign_changes) {
            (true, 0) => "bounce",
            (true, _) => "rocking",
            (false, _) => "bending",
        }
    }

    /// One line: disc order and shares, pad motion.
    pub fn describe(&self) -> String {
        let (n, share) = self.orders.dominant();
        format!(
            "{:.1} Hz: disc {n} nodal diameter{} ({:.0}% of the braking-face circle's out-of-plane motion; out-of-plane {:.0}% of its motion), disc {:.0}% of the kinetic energy; pad {} ({:.0}% straight line, {} sign change{} along its length)",
            self.frequency_hz,
            if n == 1 { "" } else { "s" },
            100.0 * share,
            100.0 * self.out_of_plane,
            100.0 * self.disc_energy,
            self.pad_kind(),
            100.0 * self.pad.rigid_share,
            self.pad.sign_changes,
            if self.pad.sign_changes == 1 { "" } else { "s" },
        )
    }

    fn part(&self) -> String {
        if self.disc_energy >= 0.5 {
            format!(
                "a disc mode with {} nodal diameters (pad {})",
                self.nodal_diameters(),
                self.pad_kind()
            )
        } else {
            format!(
                "a pad {} mode (disc {} nodal diameters)",
                self.pad_kind(),
                self.nodal_diameters()
            )
        }
    }
}

/// Which modes couple, in words: the disc's `n`-nodal-diameter doublet when both modes show
/// the same dominant order with at least 30% of their kinetic energy in the disc, else each
/// mode as a disc mode (at least half of its energy in the disc) or a pad mode.
pub fn coupling(mode1: &ShapeSummary, mode2: &ShapeSummary) -> String {
    let (n1, n2) = (mode1.nodal_diameters(), mode2.nodal_diameters());
    if n1 == n2 && mode1.disc_energy >= 0.3 && mode2.disc_energy >= 0.3 {
        format!(
            "the disc's {n1}-nodal-diameter doublet, split and coupled by the pad (pad {} / {}; disc {:.0}% / {:.0}% of the kinetic energy)",
            mode1.pad_kind(),
            mode2.pad_kind(),
            100.0 * mode1.disc_energy,
            100.0 * mode2.disc_energy
        )
    } else {
        format!("{} with {}", mode1.part(), mode2.part())
    }
}

#[cfg(test)]
mod tests;
