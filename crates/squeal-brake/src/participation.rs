//! What the unstable mode is made of: a complex mode `x = Φ q` of the linearized brake
//! expressed in the frictionless modes `Φ` of the assembled brake and in the reduced
//! coordinates of each part (its Craig–Bampton constraint modes and fixed-interface modes).
//!
//! **Frictionless modes.** With `Φᵀ M Φ = I` ([`crate::modal`]) the mode's kinetic-energy
//! norm is `xᴴ M x = Σ_j |q_j|²`, so the energy fractions `e_j = |q_j|² / Σ_k |q_k|²` are
//! non-negative and sum to 1: mode `j`'s share of the complex mode's kinetic energy (the
//! modal mass participation of a real mode, for a complex one). The complex coefficients
//! `q_j` themselves, scaled so that the largest is 1 (real), are the counterpart of Ansys'
//! complex mode contribution coefficients (QRDOPT's CMCC: "the components of the complex
//! mode's vector in the basis of the symmetric normal modes", Mechanical APDL Structural
//! Analysis Guide §3.7.5), whose normalization differs by that one complex factor.
//!
//! **Reduced coordinates.** The reduced mass `M` is block-diagonal over the parts but not
//! diagonal within a part (a Craig–Bampton `M̂` couples constraint and fixed-interface
//! modes), so energies do not split dof by dof. The split used is
//! `c_i = Re(x̄_i (M x)_i) / xᴴ M x`: it sums to 1 exactly over the dofs and, over each part,
//! to that part's kinetic-energy fraction `x_Pᴴ M_PP x_P / xᴴ M x` (the cross terms
//! `M_bm` are shared evenly between the two coordinates they join); a single coordinate's
//! share can be slightly negative where it moves against its neighbours.

use faer::{Mat, c64};
use std::ops::Range;

/// A mode's share by frictionless mode.
#[derive(Clone, Debug, PartialEq)]
pub struct ModalShares {
    /// `e_j = |q_j|² / Σ|q|²`, summing to 1.
    pub energy: Vec<f64>,
    /// `q_j / q_max`: the coefficients scaled so that the largest is 1 (CMCC-like).
    pub coefficients: Vec<c64>,
}

/// Shares of a complex mode with modal coordinates `q` (on a mass-normalized basis).
pub fn modal_shares(q: &[c64]) -> ModalShares {
    let total: f64 = q.iter().map(|v| v.norm_sqr()).sum();
    let energy = q
        .iter()
        .map(|v| v.norm_sqr() / total.max(f64::MIN_POSITIVE))
        .collect();
    let big = q
        .iter()
        .copied()
        .max_by(|a, b| a.norm_sqr().total_cmp(&b.norm_sqr()))
        .unwrap_or(c64::new(1.0, 0.0));
    let inv = if big.norm_sqr() > 0.0 {
        c64::new(1.0, 0.0) / big
    } else {
        c64::new(1.0, 0.0)
    };
    ModalShares {
        energy,
        coefficients: q.iter().map(|v| v * inv).collect(),
    }
}

/// `c_i = Re(x̄_i (M x)_i) / xᴴ M x` for every reduced dof (module documentation).
pub fn dof_shares(m: &Mat<f64>, x: &[c64]) -> Vec<f64> {
    let n = x.len();
    let mx: Vec<c64> = (0..n)
        .map(|i| (0..n).map(|j| x[j] * m[(i, j)]).sum())
        .collect();
    let parts: Vec<f64> = (0..n).map(|i| (x[i].conj() * mx[i]).re).collect();
    let total: f64 = parts.iter().sum();
    parts
        .iter()
        .map(|p| p / total.max(f64::MIN_POSITIVE))
        .collect()
}

/// The sum of `shares` over each range (a part's dofs).
pub fn part_sums(shares: &[f64], parts: &[Range<usize>]) -> Vec<f64> {
    parts
        .iter()
        .map(|r| shares[r.clone()].iter().sum())
        .collect()
}

/// Physical reduced vector `x = Φ q`.
pub fn physical(phi: &Mat<f64>, q: &[c64]) -> Vec<c64> {
    (0..phi.nrows())
        .map(|i| (0..phi.ncols()).map(|j| q[j] * phi[(i, j)]).sum())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modal::modal_basis;

    /// A 6-dof two-part pencil with a coupled (non-diagonal) mass in each part: the shares sum
    /// to 1 and the parts' sums equal their kinetic-energy fractions, to round-off (1e-14:
    /// sums of six terms of order 1).
    #[test]
    fn shares_sum_to_one_and_to_the_parts_energies() {
        let n = 6;
        let m = Mat::from_fn(n, n, |i, j| {
            let same = (i < 3) == (j < 3);
            if i == j {
                1.0 + 0.1 * i as f64
            } else if same {
                0.2 / (1.0 + (i + j) as f64)
            } else {
                0.0
            }
        });
        let k = Mat::from_fn(n, n, |i, j| {
            if i == j {
                3.0 + i as f64
            } else if i.abs_diff(j) == 1 {
                -1.0
            } else {
                0.0
            }
        });
        let b = modal_basis(&m, &k).unwrap();
        let q: Vec<c64> = (0..n)
            .map(|j| c64::new((j as f64 * 0.7).sin(), (j as f64 * 1.3).cos()))
            .collect();
        let s = modal_shares(&q);
        assert!((s.energy.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        let x = physical(&b.phi, &q);
        let c = dof_shares(&m, &x);
        assert!((c.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        // xᴴ M x = Σ|q|² (mass-normalized basis).
        let xmx: f64 = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| (x[i].conj() * x[j]).re * m[(i, j)])
            .sum();
        let qq: f64 = q.iter().map(|v| v.norm_sqr()).sum();
        assert!((xmx / qq - 1.0).abs() < 1e-13, "{xmx} vs {qq}");
        let parts = part_sums(&c, &[0..3, 3..6]);
        let energy = |r: Range<usize>| -> f64 {
            r.clone()
                .flat_map(|i| r.clone().map(move |j| (i, j)))
                .map(|(i, j)| (x[i].conj() * x[j]).re * m[(i, j)])
                .sum::<f64>()
                / xmx
        };
        assert!((parts[0] - energy(0..3)).abs() < 1e-14);
        assert!((parts[1] - energy(3..6)).abs() < 1e-14);
    }
}
