//! Shared test systems (included by the test files with `mod common;`).
#![allow(dead_code)]

use faer::MatMut;
use squeal_ode::OdeSystem;

/// y' = A y for a constant dense A.
pub struct Linear {
    pub a: Vec<Vec<f64>>,
}

impl OdeSystem for Linear {
    fn dim(&self) -> usize {
        self.a.len()
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        for (i, row) in self.a.iter().enumerate() {
            dy[i] = row.iter().zip(y).map(|(a, y)| a * y).sum();
        }
    }
    fn jacobian(&self, _t: f64, _y: &[f64], mut jac: MatMut<'_, f64>) {
        for (i, row) in self.a.iter().enumerate() {
            for (j, a) in row.iter().enumerate() {
                jac[(i, j)] = *a;
            }
        }
    }
}

/// Complex pair lambda = a +- i b as a real 2x2 system:
/// u' = a u - b v, v' = b u + a v; from (1, 0): e^{a t} (cos b t, sin b t).
pub fn complex_pair(a: f64, b: f64) -> Linear {
    Linear {
        a: vec![vec![a, -b], vec![b, a]],
    }
}

pub fn complex_pair_exact(a: f64, b: f64, t: f64) -> [f64; 2] {
    let r = (a * t).exp();
    [r * (b * t).cos(), r * (b * t).sin()]
}

/// Van der Pol x'' - mu (1 - x^2) x' + x = 0 as y = (x, x').
pub struct VanDerPol {
    pub mu: f64,
}

impl OdeSystem for VanDerPol {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = self.mu * (1.0 - y[0] * y[0]) * y[1] - y[0];
    }
    fn jacobian(&self, _t: f64, y: &[f64], mut jac: MatMut<'_, f64>) {
        jac[(0, 0)] = 0.0;
        jac[(0, 1)] = 1.0;
        jac[(1, 0)] = -2.0 * self.mu * y[0] * y[1] - 1.0;
        jac[(1, 1)] = self.mu * (1.0 - y[0] * y[0]);
    }
}

/// Robertson's chemical kinetics (Hairer & Wanner II, Sec. IV.1).
pub struct Robertson;

impl OdeSystem for Robertson {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
        dy[2] = 3e7 * y[1] * y[1];
        dy[1] = -dy[0] - dy[2];
    }
    fn jacobian(&self, _t: f64, y: &[f64], mut jac: MatMut<'_, f64>) {
        jac[(0, 0)] = -0.04;
        jac[(0, 1)] = 1e4 * y[2];
        jac[(0, 2)] = 1e4 * y[1];
        jac[(2, 0)] = 0.0;
        jac[(2, 1)] = 6e7 * y[1];
        jac[(2, 2)] = 0.0;
        jac[(1, 0)] = 0.04;
        jac[(1, 1)] = -1e4 * y[2] - 6e7 * y[1];
        jac[(1, 2)] = -1e4 * y[1];
    }
}
