//! Checks of a reduced part: its natural frequencies with the boundary coordinates fixed or
//! free, and the definiteness of `K̂` and `M̂` (eqs 6–7).

use crate::craig_bampton::{ReduceError, hz};
use crate::rom::{DofLabel, ReducedPart};
use faer::{Mat, Side};
use squeal_eigs::dense::cholesky_lower;

/// What the boundary coordinates of a reduced part do in a frequency check.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Boundary {
    /// Held at zero: only the modal block `K̂_NN`, `M̂_NN` remains (eqs 4–5, exact by
    /// construction when the modes were solved to convergence).
    Fixed,
    /// Free: the whole `K̂`, `M̂`; the approximation Craig–Bampton makes.
    Free,
}

/// Eigenvalues `λ` of the dense symmetric pencil `K x = λ M x` (`M` positive definite),
/// ascending: `M = L Lᵀ`, then the eigenvalues of `L⁻¹ K L⁻ᵀ`.
pub fn dense_eigenvalues(k: &Mat<f64>, m: &Mat<f64>, part: &str) -> Result<Vec<f64>, ReduceError> {
    let invalid = |what: &str| ReduceError::Invalid {
        part: part.into(),
        what: what.into(),
    };
    let n = k.nrows();
    if k.ncols() != n || m.nrows() != n || m.ncols() != n {
        return Err(invalid("K and M are not square matrices of one size"));
    }
    let l =
        cholesky_lower(m).ok_or_else(|| invalid("the reduced mass is not positive definite"))?;
    // X = L⁻¹ K, then A = L⁻¹ Xᵀ = L⁻¹ K L⁻ᵀ (K symmetric).
    let x = forward_solve(&l, k);
    let a = forward_solve(&l, &x.transpose().to_owned());
    let a = Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    a.self_adjoint_eigenvalues(Side::Lower)
        .map_err(|_| invalid("the dense eigensolver did not converge"))
}

/// Solves `L X = B` for lower-triangular `L`.
fn forward_solve(l: &Mat<f64>, b: &Mat<f64>) -> Mat<f64> {
    let n = l.nrows();
    let mut x = b.clone();
    for c in 0..x.ncols() {
        for i in 0..n {
            let mut s = x[(i, c)];
            for k in 0..i {
                s -= l[(i, k)] * x[(k, c)];
            }
            x[(i, c)] = s / l[(i, i)];
        }
    }
    x
}

/// The reduced dofs of a part that are modal amplitudes (`q_φ`).
pub fn modal_dofs(part: &ReducedPart) -> Vec<usize> {
    part.info
        .dofs
        .iter()
        .enumerate()
        .filter(|(_, d)| matches!(d, DofLabel::Mode { .. }))
        .map(|(i, _)| i)
        .collect()
}

/// Natural frequencies (Hz, ascending) of a reduced part with its boundary coordinates fixed
/// or free.
pub fn reduced_frequencies(
    part: &ReducedPart,
    boundary: Boundary,
) -> Result<Vec<f64>, ReduceError> {
    let keep: Vec<usize> = match boundary {
        Boundary::Free => (0..part.size()).collect(),
        Boundary::Fixed => modal_dofs(part),
    };
    let sub = |a: &Mat<f64>| Mat::from_fn(keep.len(), keep.len(), |i, j| a[(keep[i], keep[j])]);
    let values = dense_eigenvalues(&sub(&part.k), &sub(&part.m), &part.info.name)?;
    Ok(values.into_iter().map(hz).collect())
}

/// Definiteness of a reduced part's matrices.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Definiteness {
    /// `max |A - Aᵀ| / max |A|` of `K̂` and of `M̂`.
    pub k_asymmetry: f64,
    /// The same for `M̂`.
    pub m_asymmetry: f64,
    /// Smallest and largest eigenvalue of `M̂`.
    pub m_min: f64,
    /// Largest eigenvalue of `M̂`.
    pub m_max: f64,
    /// Smallest and largest eigenvalue of `K̂`.
    pub k_min: f64,
    /// Largest eigenvalue of `K̂`.
    pub k_max: f64,
    /// Eigenvalues of `K̂` below `1e-9 max` in absolute value: the rigid motions left free.
    pub k_zero: usize,
}

/// Symmetry and eigenvalue range of `K̂` and `M̂`.
pub fn definiteness(part: &ReducedPart) -> Result<Definiteness, ReduceError> {
    let name = &part.info.name;
    let dense_failed = || ReduceError::Invalid {
        part: name.clone(),
        what: "the dense eigensolver did not converge".into(),
    };
    let m = part
        .m
        .self_adjoint_eigenvalues(Side::Lower)
        .map_err(|_| dense_failed())?;
    let k = part
        .k
        .self_adjoint_eigenvalues(Side::Lower)
        .map_err(|_| dense_failed())?;
    let first = |v: &[f64]| v.first().copied().unwrap_or(0.0);
    let last = |v: &[f64]| v.last().copied().unwrap_or(0.0);
    let k_max = last(&k);
    Ok(Definiteness {
        k_asymmetry: asymmetry(&part.k),
        m_asymmetry: asymmetry(&part.m),
        m_min: first(&m),
        m_max: last(&m),
        k_min: first(&k),
        k_max,
        // Relative 1e-9: rigid-body eigenvalues of K̂ are round-off of ||K̂|| (about 1e-13
        // of it); the softest elastic one is 1e-6 or more of the stiffest here.
        k_zero: k.iter().filter(|v| v.abs() <= 1e-9 * k_max).count(),
    })
}

/// `max |A - Aᵀ| / max |A|`.
fn asymmetry(a: &Mat<f64>) -> f64 {
    let n = a.nrows();
    let mut worst: f64 = 0.0;
    let mut scale: f64 = 0.0;
    for i in 0..n {
        for j in 0..n {
            worst = worst.max((a[(i, j)] - a[(j, i)]).abs());
            scale = scale.max(a[(i, j)].abs());
        }
    }
    worst / scale.max(f64::MIN_POSITIVE)
}
