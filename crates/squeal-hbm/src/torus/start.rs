//! The start of a torus branch at a Neimark–Sacker point of a branch of periodic solutions.
//!
//! Near the bifurcation the torus is the cycle plus a small modulation along the critical
//! Floquet solution: with the cycle `x*(θ1)` (frequency `ω1`) and the critical exponent
//! `σ = i Ω` (`|Ω| < ω1/2`), the variational equations have the solution
//! `Re(e^{iΩt} p(ω1 t))`, `p` periodic, so
//!
//! `X(θ1, θ2) ≈ x*(θ1) + ε Re(p(θ1) e^{iθ2})`,  `ω2 = Ω`,
//!
//! whose modulation lives on the elements with `|k2| = 1`. Linearizing the torus equations
//! about the cycle embedded as `U*` (elements `(k, 0)`) decouples those elements from the
//! others (the force's Jacobian along the cycle depends on `θ1` only, so it couples `k_a` with
//! `k_b` only through `k_a ± k_b` of zero second component): their block `J1(ω1, ω2)` of the
//! Jacobian is the real form of Hill's matrix at `σ = iω2` (the Floquet analysis in harmonic
//! balance form), singular exactly at the Neimark–Sacker point. Its near-null vector, by
//! inverse iteration, is `p`; at a point near the bifurcation (parameter and `Ω` interpolated
//! between two cycles) it is the direction of the least singular value, which is what the
//! corrector needs. The guess `U* + ε p` is rotated in `θ2` to meet the second phase
//! condition; the caller corrects it with the modulation's amplitude held at `ε` and the
//! parameter free ([`crate::continuation::correct_point`]), then follows the branch.

use faer::Mat;
use faer::linalg::solvers::Solve;

use super::balance::{TorusBalance, TorusPhase};
use super::force::TorusForce;
use super::linear::TorusLinear;
use crate::HbmError;
use crate::layout::{HarmonicLayout, Part};

/// Inverse iterations for the critical Floquet vector.
pub const INVERSE_ITERATIONS: usize = 12;

/// A torus guess next to a cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct TorusStart {
    /// `[U, ω1, ω2]`.
    pub z: Vec<f64>,
    /// The phase conditions: `(1, 0)` on the cycle's phase dof, and the largest sine of the
    /// modulation.
    pub phase: TorusPhase,
    /// Index in `U` of the modulation's cosine that carries the amplitude `ε`.
    pub amplitude_index: usize,
    /// `||J1 p|| / ||J1 p_0||` after the inverse iterations, `p_0` the start vector: how near
    /// singular `J1` is along `p` (small at the bifurcation).
    pub null_residual: f64,
}

/// The cycle `cycle` (layout `layout`, `ω1`) embedded in the torus basis of `balance`, plus the
/// modulation of amplitude `amplitude` along the near-null vector of `J1(ω1, ω2)` (module
/// docs); `phase_dof` is the cycle's phase condition dof (`U1s[phase_dof] = 0`).
pub fn start_from_cycle<L: TorusLinear, F: TorusForce>(
    balance: &mut TorusBalance<L, F>,
    cycle: &[f64],
    layout: HarmonicLayout,
    omega: [f64; 2],
    phase_dof: usize,
    amplitude: f64,
) -> Result<TorusStart, HbmError> {
    layout.check_len("cycle coefficients", cycle.len())?;
    let basis = balance.basis().clone();
    let n = basis.n_dofs();
    if layout.n_dofs() != n {
        return Err(HbmError::Dimension {
            what: "cycle dofs",
            expected: n,
            got: layout.n_dofs(),
        });
    }
    if !(amplitude.is_finite() && amplitude > 0.0) {
        return Err(HbmError::BadScale {
            what: "modulation amplitude",
            value: amplitude,
        });
    }
    let mut u = vec![0.0; basis.len()];
    for k in 0..=layout.n_harmonics() {
        let Some((e, _)) = basis.element([k as i64, 0]) else {
            continue;
        };
        for part in [Part::Cos, Part::Sin] {
            for i in 0..n {
                if let (Some(a), Some(b)) = (layout.index(k, part, i), basis.index(e, part, i)) {
                    u[b] = cycle[a];
                }
            }
        }
    }
    let e1 = basis
        .element([1, 0])
        .map(|e| e.0)
        .ok_or(HbmError::BadOption(
            "the torus basis needs the wave number (1, 0)",
        ))?;
    // The modulation's unknowns: every block of an element with |k2| = 1.
    let sub: Vec<usize> = (1..basis.n_waves())
        .filter(|&e| basis.wave(e)[1].abs() == 1)
        .flat_map(|e| [Part::Cos, Part::Sin].map(|p| (e, p)))
        .flat_map(|(e, p)| {
            let b = &basis;
            (0..n).filter_map(move |i| b.index(e, p, i))
        })
        .collect();
    if sub.is_empty() {
        return Err(HbmError::BadOption(
            "the torus basis has no wave number with |k2| = 1",
        ));
    }
    let len = basis.len();
    let mut jac = Mat::<f64>::zeros(len, len);
    let (mut w1, mut w2) = (vec![0.0; len], vec![0.0; len]);
    balance.jacobian(&u, omega, jac.as_mut(), [&mut w1, &mut w2])?;
    let j1 = Mat::<f64>::from_fn(sub.len(), sub.len(), |a, b| jac[(sub[a], sub[b])]);
    let lu = j1.partial_piv_lu();
    let ns = sub.len();
    let mut v = Mat::<f64>::from_fn(ns, 1, |i, _| 1.0 + (i % 7) as f64 / 7.0);
    let norm = |m: &Mat<f64>| m.norm_l2();
    let start_residual = norm(&(&j1 * &v)) / norm(&v);
    for _ in 0..INVERSE_ITERATIONS {
        v = lu.solve(&v);
        let s = norm(&v);
        if !(s.is_finite() && s > 0.0) {
            return Err(HbmError::SingularTangent);
        }
        for i in 0..ns {
            v[(i, 0)] /= s;
        }
    }
    let null_residual = norm(&(&j1 * &v)) / start_residual.max(f64::MIN_POSITIVE);
    let mut p = vec![0.0; len];
    for (a, &idx) in sub.iter().enumerate() {
        p[idx] = v[(a, 0)];
    }
    // The modulation's largest element and dof carry the phase and the amplitude.
    let (mut best, mut e2, mut d2) = (0.0, 0, 0);
    for e in (1..basis.n_waves()).filter(|&e| basis.wave(e)[1].abs() == 1) {
        for i in 0..n {
            let a = basis.amplitude(&p, e, i).unwrap_or(0.0);
            if a > best {
                (best, e2, d2) = (a, e, i);
            }
        }
    }
    let (ic, is) = (
        basis.index(e2, Part::Cos, d2).unwrap_or(0),
        basis.index(e2, Part::Sin, d2).unwrap_or(0),
    );
    let k2 = basis.wave(e2)[1] as f64;
    let turn = p[is].atan2(p[ic]) / k2;
    basis.shift_phase(&mut p, [0.0, turn])?;
    p[is] = 0.0;
    let scale = amplitude / p[ic];
    for (ui, pi) in u.iter_mut().zip(&p) {
        *ui += scale * pi;
    }
    let mut z = u;
    z.extend_from_slice(&omega);
    Ok(TorusStart {
        z,
        phase: TorusPhase {
            conditions: [(e1, phase_dof), (e2, d2)],
        },
        amplitude_index: ic,
        null_residual,
    })
}
