//! A complex Arnoldi factorization `op V_m = V_{m+1} H_m` for shift-invert eigensolvers of
//! non-symmetric problems, grown a step at a time and restarted from scratch (moved here from
//! `squeal_chbm::floquet`, which used it for Hill's method, so that the full-model quadratic
//! eigensolver of [`crate::quadratic`] shares it).
//!
//! Each new vector is orthogonalized twice by classical Gram–Schmidt written as two
//! matrix–vector products (`c = Vᴴ w`, `w ← w − V c`), which keeps the basis orthonormal to
//! round-off ("twice is enough", Giraud, Langou & Rozložník 2005). The Ritz pairs of `H_m`
//! (`H_m y = θ y`) come with the residual estimate `‖op x − θ x‖ = β |y_m|`, `β = h_{m+1,m}`,
//! `x = V_m y` (Saad, *Numerical Methods for Large Eigenvalue Problems*, 2011, §6.2).
//! Everything is sequential and starts from a fixed pseudo-random vector: the bits do not
//! depend on the thread count.

use crate::EigError;
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatMut, MatRef, Par, c64};

/// A deterministic start vector (xorshift), the same for every run and thread count.
pub fn start_vector(len: usize) -> Vec<c64> {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    (0..len).map(|_| c64::new(next(), next())).collect()
}

/// One Ritz pair of an [`Arnoldi`] factorization.
#[derive(Clone, Debug)]
pub struct RitzPair {
    /// The Ritz value θ (an eigenvalue estimate of the operator).
    pub value: c64,
    /// The residual estimate `‖op x − θ x‖` of the unit Ritz vector `x`.
    pub residual: f64,
    /// The coefficients `y` (unit norm) of `x = V_m y`.
    pub coefficients: Vec<c64>,
}

/// An Arnoldi factorization `op V_m = V_{m+1} H_m` (see the module docs).
pub struct Arnoldi {
    /// Basis, column-major, `m + 1` columns of `len` (grown as the steps go: most uses
    /// converge long before the largest dimension, so its storage is never allocated whole).
    v: Vec<c64>,
    len: usize,
    /// Hessenberg, `(max + 1) × max`.
    h: Mat<c64>,
    /// Steps taken.
    m: usize,
    /// The Krylov space is invariant (the Ritz values are exact).
    invariant: bool,
}

impl Arnoldi {
    /// A factorization of vectors of length `len` that can grow to `max` steps, started.
    pub fn new(len: usize, max: usize) -> Self {
        let mut a = Self {
            v: Vec::new(),
            len,
            h: Mat::zeros(max + 1, max),
            m: 0,
            invariant: false,
        };
        a.restart();
        a
    }

    /// Starts again from the start vector, keeping the storage of the basis.
    pub fn restart(&mut self) {
        let q = start_vector(self.len);
        let nq = q.iter().map(|x| x.norm_sqr()).sum::<f64>().sqrt();
        self.v.clear();
        self.v.extend(q.iter().map(|x| x / nq));
        self.h.fill(c64::new(0.0, 0.0));
        self.m = 0;
        self.invariant = false;
    }

    /// Steps taken since the last restart.
    pub fn steps(&self) -> usize {
        self.m
    }

    /// Whether the Krylov space became invariant (no further step is possible or needed).
    pub fn is_invariant(&self) -> bool {
        self.invariant
    }

    /// The largest number of steps.
    pub fn max_steps(&self) -> usize {
        self.h.ncols()
    }

    /// One step: `w = op(v_m)` orthogonalized against the basis.
    pub fn step(&mut self, op: &dyn Fn(&[c64]) -> Vec<c64>) {
        let j = self.m;
        let len = self.len;
        let mut w = op(&self.v[j * len..(j + 1) * len]);
        let basis = MatRef::from_column_major_slice(&self.v[..(j + 1) * len], len, j + 1);
        let mut c = vec![c64::new(0.0, 0.0); j + 1];
        for _ in 0..2 {
            // c = Vᴴ w, w ← w - V c.
            matmul(
                MatMut::from_column_major_slice_mut(&mut c, j + 1, 1),
                Accum::Replace,
                basis.adjoint(),
                MatRef::from_column_major_slice(&w, len, 1),
                c64::new(1.0, 0.0),
                Par::Seq,
            );
            matmul(
                MatMut::from_column_major_slice_mut(&mut w, len, 1),
                Accum::Add,
                basis,
                MatRef::from_column_major_slice(&c, j + 1, 1),
                c64::new(-1.0, 0.0),
                Par::Seq,
            );
            for (i, ci) in c.iter().enumerate() {
                self.h[(i, j)] += ci;
            }
        }
        let nw = faer::ColRef::from_slice(&w).norm_l2();
        self.h[(j + 1, j)] = c64::new(nw, 0.0);
        self.m += 1;
        let scale = (0..=j).map(|i| self.h[(i, j)].norm()).fold(nw, f64::max);
        // A NaN norm also ends the basis (it is not > the threshold).
        if nw.partial_cmp(&(1e-13 * scale)) != Some(std::cmp::Ordering::Greater) {
            self.invariant = true;
            return;
        }
        self.v.extend(w.iter().map(|x| x / nw));
    }

    /// Ritz values with residual estimates, and the coefficients of their vectors. Fails
    /// ([`EigError::DenseEigen`]) when the dense eigensolver of `H_m` does not converge.
    pub fn ritz(&self) -> Result<Vec<RitzPair>, EigError> {
        let m = self.m;
        let hm = self.h.submatrix(0, 0, m, m).to_owned();
        let evd = hm.eigen().map_err(|_| EigError::DenseEigen)?;
        let (s, u) = (evd.S(), evd.U());
        let beta = if self.invariant {
            0.0
        } else {
            self.h[(m, m - 1)].norm()
        };
        Ok((0..m)
            .map(|k| {
                let y: Vec<c64> = (0..m).map(|i| u[(i, k)]).collect();
                let ny = y.iter().map(|x| x.norm_sqr()).sum::<f64>().sqrt();
                let y: Vec<c64> = y.iter().map(|x| x / ny).collect();
                RitzPair {
                    value: s[k],
                    residual: beta * y[m - 1].norm(),
                    coefficients: y,
                }
            })
            .collect())
    }

    /// The Ritz vector `V_m y` of coefficients `y`.
    pub fn vector(&self, y: &[c64]) -> Vec<c64> {
        let mut x = vec![c64::new(0.0, 0.0); self.len];
        for (c, v) in y.iter().zip(self.v.chunks_exact(self.len)) {
            for (xi, vi) in x.iter_mut().zip(v) {
                *xi += c * vi;
            }
        }
        x
    }
}
