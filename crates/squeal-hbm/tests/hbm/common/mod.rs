//! Shared helpers for the integration tests: deterministic random numbers, the test
//! forces, and central finite differences.
#![allow(dead_code)]

use faer::Mat;
use squeal_hbm::{FnForce, LocalJacobian, NonlinearForce};

/// xorshift64* generator: deterministic pseudo-random numbers without a dependency.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed.max(1))
    }

    /// Uniform in [-1, 1).
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let v = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d);
        (v >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// Stand-in for the brake contact (eq. 8-9): `pairs` contact pairs, each on four dofs
/// `(x_i, z_i, x_j, z_j)`; gap closure `g = z_i - z_j`; cubic penalty force
/// `fn = kl g + knl g^3` when `g > 0`, zero otherwise; Coulomb friction `mu fn` along x
/// (permanent sliding). Forces: `+fn` on `z_i`, `-fn` on `z_j`, `+mu fn` on `x_i`,
/// `-mu fn` on `x_j`. Pattern: rows `(x_i, z_i, x_j, z_j)` x columns `(z_i, z_j)`.
pub struct ContactPairs {
    pub pairs: usize,
    pub kl: f64,
    pub knl: f64,
    pub mu: f64,
    pattern: Vec<(usize, usize)>,
}

impl ContactPairs {
    pub fn new(pairs: usize, kl: f64, knl: f64, mu: f64) -> Self {
        let mut pattern = Vec::with_capacity(8 * pairs);
        for p in 0..pairs {
            let b = 4 * p;
            for row in 0..4 {
                pattern.push((b + row, b + 1));
                pattern.push((b + row, b + 3));
            }
        }
        Self {
            pairs,
            kl,
            knl,
            mu,
            pattern,
        }
    }

    fn row_weights(&self) -> [f64; 4] {
        [self.mu, 1.0, -self.mu, -1.0]
    }
}

impl NonlinearForce for ContactPairs {
    fn n_dofs(&self) -> usize {
        4 * self.pairs
    }

    fn pattern(&self) -> &[(usize, usize)] {
        &self.pattern
    }

    fn depends_on_velocity(&self) -> bool {
        false
    }

    fn eval(&self, x: &[f64], _xdot: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>) {
        let w = self.row_weights();
        let mut jac = jac;
        for p in 0..self.pairs {
            let b = 4 * p;
            let g = x[b + 1] - x[b + 3];
            if g <= 0.0 {
                continue;
            }
            let fnorm = self.kl * g + self.knl * g * g * g;
            let slope = self.kl + 3.0 * self.knl * g * g;
            for (fr, wr) in f[b..b + 4].iter_mut().zip(w) {
                *fr += wr * fnorm;
            }
            if let Some(j) = jac.as_mut() {
                for (d, wr) in j.dfdx[8 * p..8 * p + 8].chunks_exact_mut(2).zip(w) {
                    d[0] = wr * slope;
                    d[1] = -wr * slope;
                }
            }
        }
    }
}

/// A velocity-dependent, fully coupled two-dof force with a dense pattern:
/// `f0 = x0^2 v1 + x1 v0 + 0.3 x0^3`, `f1 = v0^3 + x0 x1 v1`.
pub fn coupled_velocity_force() -> impl NonlinearForce {
    let pattern = vec![(0, 0), (0, 1), (1, 0), (1, 1)];
    FnForce::new(
        2,
        pattern,
        true,
        |x: &[f64], v: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>| {
            f[0] = x[0] * x[0] * v[1] + x[1] * v[0] + 0.3 * x[0].powi(3);
            f[1] = v[0].powi(3) + x[0] * x[1] * v[1];
            if let Some(j) = jac {
                j.dfdx[0] = 2.0 * x[0] * v[1] + 0.9 * x[0] * x[0];
                j.dfdx[1] = v[0];
                j.dfdx[2] = x[1] * v[1];
                j.dfdx[3] = x[0] * v[1];
                j.dfdxdot[0] = x[1];
                j.dfdxdot[1] = x[0] * x[0];
                j.dfdxdot[2] = 3.0 * v[0] * v[0];
                j.dfdxdot[3] = x[0] * x[1];
            }
        },
    )
}

/// Van der Pol's nonlinear damping `f = x^2 x'` (with `C = -1`).
pub fn van_der_pol_force() -> impl NonlinearForce {
    FnForce::new(
        1,
        vec![(0, 0)],
        true,
        |x: &[f64], v: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>| {
            f[0] = x[0] * x[0] * v[0];
            if let Some(j) = jac {
                j.dfdx[0] = 2.0 * x[0] * v[0];
                j.dfdxdot[0] = x[0] * x[0];
            }
        },
    )
}

/// Duffing's hardening spring `f = g x^3`.
pub fn duffing_force(g: f64) -> impl NonlinearForce {
    FnForce::new(
        1,
        vec![(0, 0)],
        false,
        move |x: &[f64], _v: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>| {
            f[0] = g * x[0].powi(3);
            if let Some(j) = jac {
                j.dfdx[0] = 3.0 * g * x[0] * x[0];
            }
        },
    )
}

/// 1x1 matrix.
pub fn scalar(v: f64) -> Mat<f64> {
    Mat::from_fn(1, 1, |_, _| v)
}

/// Central finite differences of `f: R^n -> R^m` at `x` with step `h`, column-major
/// `m x n`.
pub fn central_differences(
    x: &[f64],
    m: usize,
    h: f64,
    mut f: impl FnMut(&[f64], &mut [f64]),
) -> Mat<f64> {
    let n = x.len();
    let mut jac = Mat::zeros(m, n);
    let (mut xp, mut fp, mut fm) = (x.to_vec(), vec![0.0; m], vec![0.0; m]);
    for j in 0..n {
        xp[j] = x[j] + h;
        f(&xp, &mut fp);
        xp[j] = x[j] - h;
        f(&xp, &mut fm);
        xp[j] = x[j];
        for i in 0..m {
            jac[(i, j)] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    jac
}

/// Largest absolute entry.
pub fn max_abs(a: &Mat<f64>) -> f64 {
    let mut m: f64 = 0.0;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            m = m.max(a[(i, j)].abs());
        }
    }
    m
}

/// Largest absolute entry of `a - b`.
pub fn max_abs_diff(a: &Mat<f64>, b: &Mat<f64>) -> f64 {
    let mut m: f64 = 0.0;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            m = m.max((a[(i, j)] - b[(i, j)]).abs());
        }
    }
    m
}

/// Classical fourth-order Runge-Kutta step for `y' = rhs(t, y)`.
pub fn rk4_step(t: f64, y: &mut [f64], dt: f64, rhs: &impl Fn(f64, &[f64], &mut [f64])) {
    let n = y.len();
    let (mut k1, mut k2, mut k3, mut k4) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut tmp = vec![0.0; n];
    rhs(t, y, &mut k1);
    for i in 0..n {
        tmp[i] = y[i] + 0.5 * dt * k1[i];
    }
    rhs(t + 0.5 * dt, &tmp, &mut k2);
    for i in 0..n {
        tmp[i] = y[i] + 0.5 * dt * k2[i];
    }
    rhs(t + 0.5 * dt, &tmp, &mut k3);
    for i in 0..n {
        tmp[i] = y[i] + dt * k3[i];
    }
    rhs(t + dt, &tmp, &mut k4);
    for i in 0..n {
        y[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
}
