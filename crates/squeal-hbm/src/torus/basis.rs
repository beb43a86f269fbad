//! The truncated two-dimensional Fourier basis of a quasi-periodic motion on an invariant
//! torus: eq. (23) with two base frequencies.
//!
//! A quasi-periodic motion with base frequencies `ω1`, `ω2` is `x(t) = X(ω1 t, ω2 t)` with `X`
//! `2π`-periodic in each torus angle `θ1`, `θ2`. Its truncated series is
//!
//! `X(θ) = U0 + Σ_k (Uc_k cos(k·θ) + Us_k sin(k·θ))`,  `k = (k1, k2)`, `k·θ = k1 θ1 + k2 θ2`,
//!
//! over the wave numbers `k` of one half plane (`k1 > 0`, or `k1 = 0` and `k2 > 0`: `-k`
//! gives the same functions), chosen by total order `|k1| + |k2| <= H` or by a box
//! `|k1| <= H1`, `|k2| <= H2`. The coefficient vector keeps the block structure of eq. (25):
//! block 0 is `U0`, element `e >= 1` (wave number `k_e`) has the cosine block `2e - 1` and the
//! sine block `2e`, each of `n` dofs; element `e` moves at the angular frequency
//! `w_e = k_e·ω = k1 ω1 + k2 ω2` (of either sign).

use crate::HbmError;
use crate::layout::{MAX_COEFFICIENTS, Part};

/// Which wave numbers `k = (k1, k2)` the basis keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Truncation {
    /// `|k1| + |k2| <= H`.
    TotalOrder(usize),
    /// `|k1| <= H1` and `|k2| <= H2`.
    Box(usize, usize),
}

impl Truncation {
    fn keeps(self, k1: i64, k2: i64) -> bool {
        match self {
            Truncation::TotalOrder(h) => k1.unsigned_abs() + k2.unsigned_abs() <= h as u64,
            Truncation::Box(h1, h2) => {
                k1.unsigned_abs() <= h1 as u64 && k2.unsigned_abs() <= h2 as u64
            }
        }
    }

    /// Largest `|k1|` and `|k2|` kept.
    pub fn max_orders(self) -> (usize, usize) {
        match self {
            Truncation::TotalOrder(h) => (h, h),
            Truncation::Box(h1, h2) => (h1, h2),
        }
    }
}

/// The basis: `n` dofs and the wave numbers of one half plane (element 0 is `(0, 0)`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TorusBasis {
    n_dofs: usize,
    truncation: Truncation,
    waves: Vec<[i64; 2]>,
}

impl TorusBasis {
    /// The basis of `n_dofs` dofs and the wave numbers `truncation` keeps, ordered by total
    /// order, then `k1`, then `k2`. Fails without dofs, without any wave number beyond
    /// `(0, 0)`, or above [`MAX_COEFFICIENTS`] coefficients.
    pub fn new(n_dofs: usize, truncation: Truncation) -> Result<Self, HbmError> {
        if n_dofs == 0 {
            return Err(HbmError::NoDofs);
        }
        let (h1, h2) = truncation.max_orders();
        let (h1, h2) = (h1 as i64, h2 as i64);
        let mut waves = vec![[0, 0]];
        for k1 in 0..=h1 {
            for k2 in -h2..=h2 {
                if (k1 > 0 || k2 > 0) && truncation.keeps(k1, k2) {
                    waves.push([k1, k2]);
                }
            }
        }
        waves[1..].sort_by_key(|k| (k[0].abs() + k[1].abs(), k[0], k[1]));
        let blocks = 2 * waves.len() - 1;
        match n_dofs.checked_mul(blocks) {
            Some(len) if len <= MAX_COEFFICIENTS && waves.len() > 1 => Ok(Self {
                n_dofs,
                truncation,
                waves,
            }),
            _ => Err(HbmError::LayoutTooLarge {
                n_dofs,
                n_harmonics: blocks / 2,
                limit: MAX_COEFFICIENTS,
            }),
        }
    }

    /// Dofs per block.
    pub fn n_dofs(&self) -> usize {
        self.n_dofs
    }

    /// The truncation.
    pub fn truncation(&self) -> Truncation {
        self.truncation
    }

    /// Number of elements (wave numbers, `(0, 0)` included).
    pub fn n_waves(&self) -> usize {
        self.waves.len()
    }

    /// Wave number of element `e`.
    pub fn wave(&self, e: usize) -> [i64; 2] {
        self.waves[e]
    }

    /// All wave numbers, element order.
    pub fn waves(&self) -> &[[i64; 2]] {
        &self.waves
    }

    /// The element of wave number `k` or of `-k` (with `true` when it is `-k`, whose sine
    /// coefficient changes sign); `None` if neither is kept.
    pub fn element(&self, k: [i64; 2]) -> Option<(usize, bool)> {
        let (k, flip) = if k[0] > 0 || (k[0] == 0 && k[1] >= 0) {
            (k, false)
        } else {
            ([-k[0], -k[1]], true)
        };
        self.waves.iter().position(|w| *w == k).map(|e| (e, flip))
    }

    /// Number of blocks, `2 E - 1`.
    pub fn n_blocks(&self) -> usize {
        2 * self.waves.len() - 1
    }

    /// Length of the coefficient vector.
    pub fn len(&self) -> usize {
        self.n_dofs * self.n_blocks()
    }

    /// Never true; for symmetry with `len`.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Block of element `e`, part `part` (`None` for the sine of element 0 or out of range).
    pub fn block(&self, e: usize, part: Part) -> Option<usize> {
        match (e, part) {
            (0, Part::Cos) => Some(0),
            (0, Part::Sin) => None,
            (e, _) if e >= self.waves.len() => None,
            (e, Part::Cos) => Some(2 * e - 1),
            (e, Part::Sin) => Some(2 * e),
        }
    }

    /// Index of dof `dof`, element `e`, part `part` in the coefficient vector.
    pub fn index(&self, e: usize, part: Part, dof: usize) -> Option<usize> {
        if dof >= self.n_dofs {
            return None;
        }
        self.block(e, part).map(|b| b * self.n_dofs + dof)
    }

    /// Angular frequency `k_e·ω` of element `e`.
    pub fn frequency(&self, e: usize, omega: [f64; 2]) -> f64 {
        let k = self.waves[e];
        k[0] as f64 * omega[0] + k[1] as f64 * omega[1]
    }

    /// `sqrt(Uc² + Us²)` of dof `dof`, element `e >= 1` (`|U0|` for `e = 0`).
    pub fn amplitude(&self, u: &[f64], e: usize, dof: usize) -> Option<f64> {
        let c = *u.get(self.index(e, Part::Cos, dof)?)?;
        if e == 0 {
            return Some(c.abs());
        }
        let s = *u.get(self.index(e, Part::Sin, dof)?)?;
        Some(c.hypot(s))
    }

    /// `X(θ)` at the torus angles `theta` into `out` (one value per dof).
    pub fn displacement_at(
        &self,
        u: &[f64],
        theta: [f64; 2],
        out: &mut [f64],
    ) -> Result<(), HbmError> {
        self.check(u, out)?;
        let n = self.n_dofs;
        out.copy_from_slice(&u[..n]);
        for (e, k) in self.waves.iter().enumerate().skip(1) {
            let (s, c) = (k[0] as f64 * theta[0] + k[1] as f64 * theta[1]).sin_cos();
            for i in 0..n {
                out[i] += u[(2 * e - 1) * n + i] * c + u[2 * e * n + i] * s;
            }
        }
        Ok(())
    }

    /// The velocity `ω1 ∂X/∂θ1 + ω2 ∂X/∂θ2` at `theta` into `out`.
    pub fn velocity_at(
        &self,
        u: &[f64],
        omega: [f64; 2],
        theta: [f64; 2],
        out: &mut [f64],
    ) -> Result<(), HbmError> {
        self.check(u, out)?;
        let n = self.n_dofs;
        out.fill(0.0);
        for (e, k) in self.waves.iter().enumerate().skip(1) {
            let (s, c) = (k[0] as f64 * theta[0] + k[1] as f64 * theta[1]).sin_cos();
            let w = self.frequency(e, omega);
            for i in 0..n {
                out[i] += w * (u[2 * e * n + i] * c - u[(2 * e - 1) * n + i] * s);
            }
        }
        Ok(())
    }

    /// Shifts the torus angles: on return `u` describes `X(θ + φ)`. Element `e` is rotated by
    /// `k_e·φ` (as [`crate::HarmonicLayout::shift_phase`] for one angle); a shifted solution of
    /// an autonomous system is again one, the invariance the two phase conditions remove.
    pub fn shift_phase(&self, u: &mut [f64], phi: [f64; 2]) -> Result<(), HbmError> {
        self.check_len("coefficients", u.len())?;
        let n = self.n_dofs;
        for (e, k) in self.waves.iter().enumerate().skip(1) {
            let (s, c) = (k[0] as f64 * phi[0] + k[1] as f64 * phi[1]).sin_cos();
            for i in 0..n {
                let (a, b) = (u[(2 * e - 1) * n + i], u[2 * e * n + i]);
                u[(2 * e - 1) * n + i] = a * c + b * s;
                u[2 * e * n + i] = b * c - a * s;
            }
        }
        Ok(())
    }

    fn check(&self, u: &[f64], out: &[f64]) -> Result<(), HbmError> {
        self.check_len("coefficients", u.len())?;
        HbmError::check_dimension("output (one value per dof)", self.n_dofs, out.len())
    }

    /// An error naming `what` unless `got` is the basis' length.
    pub fn check_len(&self, what: &'static str, got: usize) -> Result<(), HbmError> {
        HbmError::check_dimension(what, self.len(), got)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_and_lookup() {
        // Total order H: 2H² + 2H + 1 lattice points, half of the others plus (0, 0).
        let b = TorusBasis::new(2, Truncation::TotalOrder(3)).unwrap();
        // 2·9 + 2·3 + 1 = 25 lattice points: (25 - 1) / 2 + 1 = 13 elements.
        assert_eq!(b.n_waves(), 13);
        assert_eq!(b.wave(1), [0, 1]);
        assert_eq!(b.wave(2), [1, 0]);
        assert_eq!(b.element([-1, 0]), Some((2, true)));
        assert_eq!(b.element([2, -1]).map(|e| b.wave(e.0)), Some([2, -1]));
        assert_eq!(b.element([3, 1]), None);
        let bx = TorusBasis::new(1, Truncation::Box(2, 1)).unwrap();
        assert_eq!(bx.n_waves(), (5 * 3 - 1) / 2 + 1);
        assert!(TorusBasis::new(1, Truncation::TotalOrder(0)).is_err());
    }

    #[test]
    fn shift_is_an_angle_shift() {
        // Direct evaluation at θ + φ against the rotated coefficients: rounding only.
        let b = TorusBasis::new(2, Truncation::Box(2, 2)).unwrap();
        let mut u: Vec<f64> = (0..b.len())
            .map(|i| ((i * 7 + 3) % 11) as f64 - 5.0)
            .collect();
        let (theta, phi) = ([0.37, -1.2], [1.1, 0.4]);
        let (mut direct, mut shifted) = (vec![0.0; 2], vec![0.0; 2]);
        b.displacement_at(&u, [theta[0] + phi[0], theta[1] + phi[1]], &mut direct)
            .unwrap();
        b.shift_phase(&mut u, phi).unwrap();
        b.displacement_at(&u, theta, &mut shifted).unwrap();
        for i in 0..2 {
            assert!((direct[i] - shifted[i]).abs() < 1e-12);
        }
    }
}
