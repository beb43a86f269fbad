//! Small dense factorizations written out by hand where faer's kernels do not do what is
//! needed: a textbook Cholesky that reports a non-positive pivot instead of regularizing it
//! (the reduction's mass and interface-mode checks), and a scaled complex LU that floors a zero
//! pivot as inverse iteration wants (the linearized brake's bordered solves). Everything else
//! dense (LU, QR, eigendecompositions) is faer's.

use faer::{Mat, c64};

/// Lower Cholesky factor `L` of a small symmetric positive definite matrix (`A = L Lᵀ`,
/// textbook column order), or `None` at a pivot that is not positive.
pub fn cholesky_lower(a: &Mat<f64>) -> Option<Mat<f64>> {
    let n = a.nrows();
    let mut l = Mat::<f64>::zeros(n, n);
    for j in 0..n {
        let mut d = a[(j, j)];
        for k in 0..j {
            d -= l[(j, k)] * l[(j, k)];
        }
        if !(d > 0.0 && d.is_finite()) {
            return None;
        }
        let d = d.sqrt();
        l[(j, j)] = d;
        for i in j + 1..n {
            let mut s = a[(i, j)];
            for k in 0..j {
                s -= l[(i, k)] * l[(j, k)];
            }
            l[(i, j)] = s / d;
        }
    }
    Some(l)
}

/// A small dense complex LU factorization with partial pivoting, after scaling rows and then
/// columns to unit largest entry (by powers of two, which round nothing): the bordered matrix
/// mixes entries of order `ω²`, `k_p` and 1. A zero pivot is replaced by `ε` times the largest
/// entry, as inverse iteration does at an exact eigenvalue: the solve then returns a large
/// multiple of the null vector, which is what is wanted.
pub struct SmallLu {
    n: usize,
    a: Vec<c64>,
    perm: Vec<usize>,
    row_scale: Vec<f64>,
    col_scale: Vec<f64>,
}

/// `|Re z| + |Im z|`: a norm as good as `|z|` for pivoting and scaling, without a square root.
pub fn abs1(z: c64) -> f64 {
    z.re.abs() + z.im.abs()
}

/// The power of two nearest to `1 / m` (1 for a zero or non-finite `m`).
pub fn inverse_power_of_two(m: f64) -> f64 {
    if m > 0.0 && m.is_finite() {
        (-m.log2().round()).exp2()
    } else {
        1.0
    }
}

impl SmallLu {
    pub fn new(n: usize, mut a: Vec<c64>) -> Self {
        let row_scale: Vec<f64> = (0..n)
            .map(|i| inverse_power_of_two((0..n).map(|j| abs1(a[i * n + j])).fold(0.0, f64::max)))
            .collect();
        for i in 0..n {
            for j in 0..n {
                a[i * n + j] *= row_scale[i];
            }
        }
        let col_scale: Vec<f64> = (0..n)
            .map(|j| inverse_power_of_two((0..n).map(|i| abs1(a[i * n + j])).fold(0.0, f64::max)))
            .collect();
        for i in 0..n {
            for j in 0..n {
                a[i * n + j] *= col_scale[j];
            }
        }
        let floor = f64::EPSILON;
        let mut perm: Vec<usize> = (0..n).collect();
        for k in 0..n {
            let mut piv = k;
            for i in k + 1..n {
                if abs1(a[i * n + k]) > abs1(a[piv * n + k]) {
                    piv = i;
                }
            }
            if piv != k {
                for col in 0..n {
                    a.swap(k * n + col, piv * n + col);
                }
                perm.swap(k, piv);
            }
            if abs1(a[k * n + k]) < floor {
                a[k * n + k] = c64::new(floor, 0.0);
            }
            let inv = c64::new(1.0, 0.0) / a[k * n + k];
            for i in k + 1..n {
                let f = a[i * n + k] * inv;
                a[i * n + k] = f;
                for col in k + 1..n {
                    let v = a[k * n + col];
                    a[i * n + col] -= f * v;
                }
            }
        }
        Self {
            n,
            a,
            perm,
            row_scale,
            col_scale,
        }
    }

    pub fn solve(&self, b: &mut [c64]) {
        let n = self.n;
        let mut x: Vec<c64> = self
            .perm
            .iter()
            .map(|&i| b[i] * self.row_scale[i])
            .collect();
        for i in 0..n {
            for k in 0..i {
                let v = x[k];
                x[i] -= self.a[i * n + k] * v;
            }
        }
        for i in (0..n).rev() {
            for k in i + 1..n {
                let v = x[k];
                x[i] -= self.a[i * n + k] * v;
            }
            x[i] /= self.a[i * n + i];
        }
        for (i, v) in x.iter().enumerate() {
            b[i] = *v * self.col_scale[i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factors_reproduce_their_matrices() {
        // A = L Lᵀ with L exact in binary: the factor must come back to round-off.
        let l = Mat::from_fn(3, 3, |i, j| {
            [[2.0, 0.0, 0.0], [1.0, 3.0, 0.0], [0.5, -1.0, 4.0]][i][j]
        });
        let a = &l * l.transpose();
        let got = cholesky_lower(&a).expect("positive definite");
        assert!((&got - &l).norm_max() < 1e-15, "{got:?}");
        let indefinite = Mat::from_fn(2, 2, |i, j| [[1.0, 2.0], [2.0, 1.0]][i][j]);
        assert!(cholesky_lower(&indefinite).is_none());
        // A complex system with entries of very different scales (the bordered matrix's ω², k_p
        // and 1): the scaled LU solves it to round-off relative to the solution.
        let m = [
            [c64::new(4e8, 1e3), c64::new(1.0, 0.0), c64::new(0.0, 2.0)],
            [c64::new(2.0, 0.0), c64::new(3e-2, 0.0), c64::new(1.0, 1.0)],
            [c64::new(0.0, 1.0), c64::new(5e7, 0.0), c64::new(7.0, 0.0)],
        ];
        let x = [c64::new(1.0, -1.0), c64::new(2.0, 0.5), c64::new(-3.0, 0.0)];
        let mut b: Vec<c64> = (0..3)
            .map(|i| (0..3).map(|j| m[i][j] * x[j]).sum())
            .collect();
        let lu = SmallLu::new(3, m.iter().flatten().copied().collect());
        lu.solve(&mut b);
        for k in 0..3 {
            assert!((b[k] - x[k]).norm() < 1e-12 * 3.0, "x[{k}] = {}", b[k]);
        }
    }
}
