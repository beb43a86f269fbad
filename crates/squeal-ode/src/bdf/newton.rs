//! The pieces of a BDF/NDF step: the method's coefficients (Shampine and Reichelt, Table 1), the difference-array rescaling matrix R, the weighted RMS norm and the Newton matrix I - c h J with its LU.

use super::*;

/// NDF/BDF coefficients of S&R Table 1 / scipy (index = order).
#[derive(Debug, Clone, Copy)]
pub(super) struct Coefficients {
    /// `gamma_k = sum_{j=1..k} 1/j`.
    pub(super) gamma: [f64; MAX_ORDER + 1],
    /// `alpha_k = (1 - kappa_k) gamma_k`.
    pub(super) alpha: [f64; MAX_ORDER + 1],
    /// `kappa_k gamma_k + 1/(k+1)`: local error constant.
    pub(super) error_const: [f64; MAX_ORDER + 1],
}

impl Coefficients {
    /// Klopfenstein-Shampine NDF `kappa` (S&R Table 1) or zero for BDF.
    pub(super) fn new(ndf: bool) -> Self {
        let kappa_ndf = [0.0, -0.1850, -1.0 / 9.0, -0.0823, -0.0415, 0.0];
        let mut c = Self {
            gamma: [0.0; MAX_ORDER + 1],
            alpha: [0.0; MAX_ORDER + 1],
            error_const: [0.0; MAX_ORDER + 1],
        };
        for k in 0..=MAX_ORDER {
            let kappa = if ndf { kappa_ndf[k] } else { 0.0 };
            if k > 0 {
                c.gamma[k] = c.gamma[k - 1] + 1.0 / k as f64;
            }
            c.alpha[k] = (1.0 - kappa) * c.gamma[k];
            c.error_const[k] = kappa * c.gamma[k] + 1.0 / (k + 1) as f64;
        }
        c
    }
}

/// S&R Sec. 2.3: matrix `R(rho)` with `R_ij = prod_{l=1..i} (l - 1 - rho j) / l`
/// (row 0 all ones) that maps differences at spacing h to spacing `rho h`.
pub(super) fn compute_r(order: usize, factor: f64) -> [[f64; MAX_ORDER + 1]; MAX_ORDER + 1] {
    let mut r = [[0.0; MAX_ORDER + 1]; MAX_ORDER + 1];
    for j in 0..=order {
        r[0][j] = 1.0;
    }
    for i in 1..=order {
        for j in 0..=order {
            let m = (i as f64 - 1.0 - factor * j as f64) / i as f64;
            r[i][j] = r[i - 1][j] * m;
        }
    }
    r
}

/// RMS norm of `x ./ scale` (Hairer-Norsett-Wanner weighted norm).
pub(super) fn rms_norm(x: &[f64], scale: &[f64]) -> f64 {
    let n = x.len().max(1);
    let s: f64 = x.iter().zip(scale).map(|(a, s)| (a / s) * (a / s)).sum();
    (s / n as f64).sqrt()
}

/// Dense LU factors of the Newton matrix `I - c J` (faer, partial pivoting).
pub(super) struct NewtonMatrix {
    pub(super) lu: Mat<f64>,
    pub(super) perm: Vec<usize>,
    pub(super) perm_inv: Vec<usize>,
    pub(super) scratch: MemBuffer,
    pub(super) tmp: Vec<f64>,
    /// `c` of the current factorization, `None` if there is none.
    pub(super) c: Option<f64>,
    /// Newton contraction rate measured with this factorization (CVODE's
    /// `crate`), used to accept a converged first iteration.
    pub(super) rate: Option<f64>,
}

impl NewtonMatrix {
    pub(super) fn new(n: usize) -> Self {
        Self {
            lu: Mat::zeros(n, n),
            perm: vec![0; n],
            perm_inv: vec![0; n],
            scratch: MemBuffer::new(StackReq::new::<usize>(n)),
            tmp: vec![0.0; n],
            c: None,
            rate: None,
        }
    }

    /// Factor `I - c J` in place (sequential: same bits on any machine load).
    pub(super) fn factor(&mut self, jac: MatRef<'_, f64>, c: f64) {
        let n = jac.nrows();
        for j in 0..n {
            for i in 0..n {
                let delta = if i == j { 1.0 } else { 0.0 };
                self.lu[(i, j)] = delta - c * jac[(i, j)];
            }
        }
        lu_in_place(
            self.lu.as_mut(),
            &mut self.perm,
            &mut self.perm_inv,
            Par::Seq,
            MemStack::new(&mut self.scratch),
            Default::default(),
        );
        self.c = Some(c);
        self.rate = None;
    }

    /// Solve `(I - c J) x = b` in place (`P A = L U`).
    pub(super) fn solve(&mut self, b: &mut [f64]) {
        for (i, &p) in self.perm.iter().enumerate() {
            self.tmp[i] = b[p];
        }
        let lu = self.lu.as_ref();
        let mut x = ColMut::from_slice_mut(&mut self.tmp).as_mat_mut();
        solve_unit_lower_triangular_in_place(lu, x.as_mut(), Par::Seq);
        solve_upper_triangular_in_place(lu, x.as_mut(), Par::Seq);
        b.copy_from_slice(&self.tmp);
    }
}

/// Why the last attempt at the current step failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Failure {
    ErrorTest,
    Newton,
    NonFinite,
}

/// Outcome of one Newton solve.
pub(super) struct NewtonOutcome {
    pub(super) converged: bool,
    pub(super) iterations: usize,
    pub(super) non_finite: bool,
}
