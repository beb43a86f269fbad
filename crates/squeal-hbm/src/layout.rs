//! The multi-harmonic vector of eq. (25) and point evaluation of the truncated series of eq. (23).

use crate::HbmError;

/// Upper bound on `n_dofs * (2 H + 1)`: the dense Jacobian of that size must fit in memory
/// (16384^2 doubles = 2 GiB).
pub const MAX_COEFFICIENTS: usize = 16_384;

/// Which half of a harmonic block pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// `U_k^C`, the coefficient of `cos(k omega t)` (the only part for `k = 0`).
    Cos,
    /// `U_k^S`, the coefficient of `sin(k omega t)` (`k >= 1`).
    Sin,
}

/// Eq. (25): `U~ = [U0c, U1c, U1s, ..., UHc, UHs]`, each block holding `n` dofs.
///
/// Block `b` holds harmonic `k = (b + 1) / 2`: block 0 is the mean `U0c`, block `2k - 1` is
/// `Ukc`, block `2k` is `Uks`. Entry `i` of block `b` sits at index `b * n + i`, so
/// the coefficient vector has `n (2 H + 1)` entries and
/// `x_i(t) = U0c_i + sum_k (Ukc_i cos(k w t) + Uks_i sin(k w t))` (eq. 23).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HarmonicLayout {
    n_dofs: usize,
    n_harmonics: usize,
}

impl HarmonicLayout {
    /// A layout of `n_dofs` dofs and harmonics `0..=n_harmonics`.
    ///
    /// Fails if `n_dofs == 0` or if `n_dofs (2 H + 1)` exceeds [`MAX_COEFFICIENTS`].
    pub fn new(n_dofs: usize, n_harmonics: usize) -> Result<Self, HbmError> {
        if n_dofs == 0 {
            return Err(HbmError::NoDofs);
        }
        let len = n_harmonics
            .checked_mul(2)
            .and_then(|b| b.checked_add(1))
            .and_then(|blocks| blocks.checked_mul(n_dofs));
        match len {
            Some(len) if len <= MAX_COEFFICIENTS => Ok(Self {
                n_dofs,
                n_harmonics,
            }),
            _ => Err(HbmError::LayoutTooLarge {
                n_dofs,
                n_harmonics,
                limit: MAX_COEFFICIENTS,
            }),
        }
    }

    /// Number of dofs `n` per block.
    pub fn n_dofs(&self) -> usize {
        self.n_dofs
    }

    /// Highest harmonic `H` (the paper's `N_h`).
    pub fn n_harmonics(&self) -> usize {
        self.n_harmonics
    }

    /// Number of blocks, `2 H + 1`.
    pub fn n_blocks(&self) -> usize {
        2 * self.n_harmonics + 1
    }

    /// Length of the coefficient vector, `n (2 H + 1)`.
    pub fn len(&self) -> usize {
        self.n_dofs * self.n_blocks()
    }

    /// Never true (a layout has at least one dof); present for API symmetry with `len`.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Block index of harmonic `k`, part `part`; `None` if `k > H` or `(0, Sin)`.
    pub fn block(&self, k: usize, part: Part) -> Option<usize> {
        match (k, part) {
            (0, Part::Cos) => Some(0),
            (0, Part::Sin) => None,
            (k, _) if k > self.n_harmonics => None,
            (k, Part::Cos) => Some(2 * k - 1),
            (k, Part::Sin) => Some(2 * k),
        }
    }

    /// Harmonic number and part of block `b` (inverse of [`Self::block`]); `None` if out of range.
    pub fn block_kind(&self, b: usize) -> Option<(usize, Part)> {
        if b >= self.n_blocks() {
            None
        } else if b == 0 {
            Some((0, Part::Cos))
        } else if b % 2 == 1 {
            Some((b.div_ceil(2), Part::Cos))
        } else {
            Some((b / 2, Part::Sin))
        }
    }

    /// Index in `U~` of dof `dof`, harmonic `k`, part `part`; `None` if out of range.
    pub fn index(&self, k: usize, part: Part, dof: usize) -> Option<usize> {
        if dof >= self.n_dofs {
            return None;
        }
        self.block(k, part).map(|b| b * self.n_dofs + dof)
    }

    /// Index range of block `b` in `U~`.
    pub fn block_range(&self, b: usize) -> std::ops::Range<usize> {
        b * self.n_dofs..(b + 1) * self.n_dofs
    }

    /// Amplitude `sqrt(Ukc_i^2 + Uks_i^2)` of harmonic `k >= 1` of dof `i` (`|U0c_i|` for `k = 0`).
    /// `None` if out of range or if `u` is shorter than the layout.
    pub fn amplitude(&self, u: &[f64], k: usize, dof: usize) -> Option<f64> {
        let c = *u.get(self.index(k, Part::Cos, dof)?)?;
        if k == 0 {
            return Some(c.abs());
        }
        let s = *u.get(self.index(k, Part::Sin, dof)?)?;
        Some(c.hypot(s))
    }

    /// Eq. (23) at one phase `theta = omega t`: `out_i = x_i(theta / omega)`.
    pub fn displacement_at(&self, u: &[f64], theta: f64, out: &mut [f64]) -> Result<(), HbmError> {
        self.check(u, out)?;
        let n = self.n_dofs;
        out.copy_from_slice(&u[..n]);
        for k in 1..=self.n_harmonics {
            let (s, c) = (k as f64 * theta).sin_cos();
            let uc = &u[(2 * k - 1) * n..2 * k * n];
            let us = &u[2 * k * n..(2 * k + 1) * n];
            for i in 0..n {
                out[i] += uc[i] * c + us[i] * s;
            }
        }
        Ok(())
    }

    /// Time derivative of eq. (23) at phase `theta = omega t`:
    /// `out_i = sum_k k omega (-Ukc_i sin(k theta) + Uks_i cos(k theta))`.
    pub fn velocity_at(
        &self,
        u: &[f64],
        omega: f64,
        theta: f64,
        out: &mut [f64],
    ) -> Result<(), HbmError> {
        self.check(u, out)?;
        let n = self.n_dofs;
        out.fill(0.0);
        for k in 1..=self.n_harmonics {
            let (s, c) = (k as f64 * theta).sin_cos();
            let kw = k as f64 * omega;
            let uc = &u[(2 * k - 1) * n..2 * k * n];
            let us = &u[2 * k * n..(2 * k + 1) * n];
            for i in 0..n {
                out[i] += kw * (us[i] * c - uc[i] * s);
            }
        }
        Ok(())
    }

    /// Shifts the periodic signal in time: on return `u` describes `x(t + phi / omega)`.
    ///
    /// Each harmonic pair is rotated by `k phi`:
    /// `Ukc' = Ukc cos(k phi) + Uks sin(k phi)`, `Uks' = Uks cos(k phi) - Ukc sin(k phi)`.
    /// A time shift of a solution of an autonomous system is again a solution; this is the
    /// invariance that a phase condition removes.
    pub fn shift_phase(&self, u: &mut [f64], phi: f64) -> Result<(), HbmError> {
        self.check_len("coefficients", u.len())?;
        let n = self.n_dofs;
        for k in 1..=self.n_harmonics {
            let (s, c) = (k as f64 * phi).sin_cos();
            let (head, tail) = u.split_at_mut(2 * k * n);
            let uc = &mut head[(2 * k - 1) * n..];
            let us = &mut tail[..n];
            for i in 0..n {
                let (a, b) = (uc[i], us[i]);
                uc[i] = a * c + b * s;
                us[i] = b * c - a * s;
            }
        }
        Ok(())
    }

    /// Shifts `u` in time (see [`Self::shift_phase`]) so that the first sine coefficient of
    /// `dof` is zero and its first cosine coefficient is non-negative. Returns the shift `phi`.
    pub fn align_phase(&self, u: &mut [f64], dof: usize) -> Result<f64, HbmError> {
        self.check_len("coefficients", u.len())?;
        let (Some(ic), Some(is)) = (self.index(1, Part::Cos, dof), self.index(1, Part::Sin, dof))
        else {
            return Err(HbmError::BadPhaseCondition {
                dof,
                n_dofs: self.n_dofs,
                n_harmonics: self.n_harmonics,
            });
        };
        let phi = u[is].atan2(u[ic]);
        self.shift_phase(u, phi)?;
        u[is] = 0.0;
        Ok(phi)
    }

    fn check(&self, u: &[f64], out: &[f64]) -> Result<(), HbmError> {
        self.check_len("coefficients", u.len())?;
        HbmError::check_dimension("output (one value per dof)", self.n_dofs, out.len())
    }

    /// An error naming `what` unless `got` is the layout's length.
    pub fn check_len(&self, what: &'static str, got: usize) -> Result<(), HbmError> {
        HbmError::check_dimension(what, self.len(), got)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_indices_follow_eq_25() {
        let l = HarmonicLayout::new(3, 2).unwrap();
        assert_eq!(l.len(), 15);
        assert_eq!(l.index(0, Part::Cos, 2), Some(2));
        assert_eq!(l.index(1, Part::Cos, 0), Some(3));
        assert_eq!(l.index(1, Part::Sin, 1), Some(7));
        assert_eq!(l.index(2, Part::Sin, 2), Some(14));
        assert_eq!(l.index(3, Part::Cos, 0), None);
        assert_eq!(l.index(0, Part::Sin, 0), None);
        for b in 0..l.n_blocks() {
            let (k, p) = l.block_kind(b).unwrap();
            assert_eq!(l.block(k, p), Some(b));
        }
        assert!(HarmonicLayout::new(0, 1).is_err());
        assert!(HarmonicLayout::new(usize::MAX, usize::MAX).is_err());
    }

    #[test]
    fn shift_phase_is_a_time_shift() {
        // x(t + phi/w) evaluated directly must match the rotated coefficients; the two
        // differ only by rounding (a few ulps of O(1) values), hence 1e-13.
        let l = HarmonicLayout::new(2, 3).unwrap();
        let mut u: Vec<f64> = (0..l.len())
            .map(|i| ((i * 7 + 3) % 11) as f64 - 5.0)
            .collect();
        let (theta, phi) = (0.37, 1.1);
        let mut direct = vec![0.0; 2];
        l.displacement_at(&u, theta + phi, &mut direct).unwrap();
        l.shift_phase(&mut u, phi).unwrap();
        let mut shifted = vec![0.0; 2];
        l.displacement_at(&u, theta, &mut shifted).unwrap();
        for i in 0..2 {
            assert!((direct[i] - shifted[i]).abs() < 1e-13);
        }
    }
}
