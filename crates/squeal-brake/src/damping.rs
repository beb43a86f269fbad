//! The damping of the brake in its frictionless modal coordinates, eq (12): `Φᵀ C Φ = D`.
//!
//! The paper's `D` is diagonal (a ratio per mode, eq 13); [`ModalDamping::Diagonal`] keeps
//! that case fast (`T(λ)` of the linearized brake is then a diagonal plus a low-rank matrix,
//! see [`crate::linearized`]). [`ModalDamping::Full`] admits any `D`, e.g. a physical damping
//! matrix `C` projected on the modes (`D = Φᵀ C Φ`), which is not diagonal when the parts'
//! loss factors differ; the analyses then fall back on dense linear algebra.

use faer::Mat;

/// `D = Φᵀ C Φ` (s⁻¹).
#[derive(Clone, Debug, PartialEq)]
pub enum ModalDamping {
    /// `D = diag(d)`.
    Diagonal(Vec<f64>),
    /// A full `n × n` matrix.
    Full(Mat<f64>),
}

impl ModalDamping {
    /// Number of modes.
    pub fn size(&self) -> usize {
        match self {
            ModalDamping::Diagonal(d) => d.len(),
            ModalDamping::Full(d) => d.nrows(),
        }
    }

    /// The diagonal, when `D` is diagonal.
    pub fn diagonal(&self) -> Option<&[f64]> {
        match self {
            ModalDamping::Diagonal(d) => Some(d),
            ModalDamping::Full(_) => None,
        }
    }

    /// Entry `(i, j)` of `D`.
    pub fn entry(&self, i: usize, j: usize) -> f64 {
        match self {
            ModalDamping::Diagonal(d) => {
                if i == j {
                    d[i]
                } else {
                    0.0
                }
            }
            ModalDamping::Full(d) => d[(i, j)],
        }
    }

    /// `D_jj`.
    pub fn diagonal_entry(&self, j: usize) -> f64 {
        self.entry(j, j)
    }

    /// `out_i = Σ_j D_ij v_j` (overwrites `out`).
    pub fn apply(&self, v: &[f64], out: &mut [f64]) {
        match self {
            ModalDamping::Diagonal(d) => {
                for ((o, di), vi) in out.iter_mut().zip(d).zip(v) {
                    *o = di * vi;
                }
            }
            ModalDamping::Full(d) => {
                for (i, o) in out.iter_mut().enumerate() {
                    *o = (0..v.len()).map(|j| d[(i, j)] * v[j]).sum();
                }
            }
        }
    }

    /// `D` as a dense matrix.
    pub fn to_dense(&self) -> Mat<f64> {
        let n = self.size();
        Mat::from_fn(n, n, |i, j| self.entry(i, j))
    }

    /// `D` with `extra` added to diagonal entries `(mode, value)`.
    pub fn with_added(&self, extra: &[(usize, f64)]) -> ModalDamping {
        let mut out = self.clone();
        for &(j, v) in extra {
            match &mut out {
                ModalDamping::Diagonal(d) => d[j] += v,
                ModalDamping::Full(d) => d[(j, j)] += v,
            }
        }
        out
    }

    /// The leading `m × m` block of `D` (the damping among the first `m` modes).
    pub fn leading(&self, m: usize) -> ModalDamping {
        match self {
            ModalDamping::Diagonal(d) => ModalDamping::Diagonal(d[..m].to_vec()),
            ModalDamping::Full(d) => ModalDamping::Full(d.subrows(0, m).subcols(0, m).to_owned()),
        }
    }

    /// Sum of the diagonal (`tr D`).
    pub fn trace(&self) -> f64 {
        (0..self.size()).map(|j| self.diagonal_entry(j)).sum()
    }

    /// `tr D²`.
    pub fn trace_of_square(&self) -> f64 {
        match self {
            ModalDamping::Diagonal(d) => d.iter().map(|x| x * x).sum(),
            ModalDamping::Full(d) => {
                let n = d.nrows();
                (0..n)
                    .flat_map(|i| (0..n).map(move |j| (i, j)))
                    .map(|(i, j)| d[(i, j)] * d[(j, i)])
                    .sum()
            }
        }
    }

    /// Largest `|D_ij|`.
    pub fn max_abs(&self) -> f64 {
        match self {
            ModalDamping::Diagonal(d) => d.iter().map(|x| x.abs()).fold(0.0, f64::max),
            ModalDamping::Full(d) => d.norm_max(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagonal_and_full_agree_on_a_diagonal_matrix() {
        let d = ModalDamping::Diagonal(vec![1.0, 2.0, 3.0]);
        let f = ModalDamping::Full(d.to_dense());
        let v = [0.5, -1.0, 2.0];
        let (mut a, mut b) = ([0.0; 3], [0.0; 3]);
        d.apply(&v, &mut a);
        f.apply(&v, &mut b);
        assert_eq!(a, b);
        assert_eq!(d.trace(), f.trace());
        assert_eq!(d.trace_of_square(), f.trace_of_square());
        assert_eq!(d.with_added(&[(1, 0.5)]).entry(1, 1), 2.5);
        assert_eq!(f.with_added(&[(1, 0.5)]).entry(1, 1), 2.5);
    }
}
