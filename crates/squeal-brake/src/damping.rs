//! The damping of the brake in its frictionless modal coordinates, eq (12): `Φᵀ C Φ = D`.
//!
//! The paper's `D` is diagonal (a ratio per mode, eq 13); [`ModalDamping::Diagonal`] keeps
//! that case fast (`T(λ)` of the linearized brake is then a diagonal plus a low-rank matrix,
//! see [`crate::linearized`]). [`ModalDamping::Full`] admits any `D`, e.g. a physical damping
//! matrix `C` projected on the modes (`D = Φᵀ C Φ`), which is not diagonal when the parts'
//! loss factors differ; the analyses then fall back on dense linear algebra.
//!
//! **Physical dampers.** Viscous dampers between node sets or to ground (`[[dampers]]`) make a
//! physical damping matrix `C_phys` on the parts' meshes; the Craig–Bampton basis `T` of each
//! part projects it, `Ĉ = Tᵀ C_phys T`, as eqs (6)–(7) project `K` and `M`, and the reduced
//! brake carries it ([`crate::model::Brake::c`]). In the frictionless modal coordinates it
//! adds `Φᵀ Ĉ Φ` to eq (12)'s `D` ([`ModalDamping::plus_projected`]): eq (11) reads
//! `M ẍ + (C_modal + Ĉ) ẋ + K x + F_nl = F` with `C_modal = M Φ D_modal Φᵀ M`. `Φᵀ Ĉ Φ` is
//! full in general (a damper couples the modes whose shapes move its ends), so `D` becomes
//! [`ModalDamping::Full`]. This is done once, where the reference forms `D`
//! ([`crate::sweep::reference`]): the complex eigenvalues, the Hopf point, the harmonic
//! balance, the time integration and the Floquet analyses all take `D` from there.
//!
//! First-order check: for a mass-normalized mode `φ_j` of frequency `ω_j` with
//! `D_modal = 0`, a small `Ĉ` moves its eigenvalue `±i ω_j` by
//! `Δλ = −½ φ_jᵀ Ĉ φ_j + O(|Ĉ|²)` (the quadratic eigenproblem `(λ² + λ D + Ω²) q = 0`
//! differentiated at `D = 0`: `2 λ dλ + λ D_jj = 0`).

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

    /// `D + Φᵀ C Φ` (symmetrized), full: a physical damping matrix `C` on the dofs of which
    /// `Φ`'s rows are (module docs).
    pub fn plus_projected(&self, phi: &Mat<f64>, c: &Mat<f64>) -> ModalDamping {
        let p = phi.transpose() * (c * phi);
        let n = self.size();
        ModalDamping::Full(Mat::from_fn(n, n, |i, j| {
            self.entry(i, j) + 0.5 * (p[(i, j)] + p[(j, i)])
        }))
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

    #[test]
    fn a_projected_damping_matrix_adds_phi_t_c_phi() {
        // Φ = [[1, 1], [0, 2]], C = [[2, -1], [-1, 3]]: Φᵀ C Φ = [[2, 0], [0, 10]] (by hand:
        // C Φ = [[2, 0], [-1, 5]], Φᵀ (C Φ) = [[2, 0], [0, 10]]); all exact in binary.
        let phi = Mat::from_fn(2, 2, |i, j| [[1.0, 1.0], [0.0, 2.0]][i][j]);
        let c = Mat::from_fn(2, 2, |i, j| [[2.0, -1.0], [-1.0, 3.0]][i][j]);
        let d = ModalDamping::Diagonal(vec![0.5, 0.25]).plus_projected(&phi, &c);
        assert!(d.diagonal().is_none());
        for (i, j, want) in [(0, 0, 2.5), (0, 1, 0.0), (1, 0, 0.0), (1, 1, 10.25)] {
            assert_eq!(d.entry(i, j), want, "({i}, {j})");
        }
    }
}
