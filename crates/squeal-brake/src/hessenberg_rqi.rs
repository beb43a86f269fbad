//! One eigenpair of the scaled state matrix near a known one, by Rayleigh quotient iteration
//! on its Hessenberg form: the cost of a Hessenberg reduction and a few `O(n²)` solves instead
//! of a whole eigen-decomposition.
//!
//! The refinement of a Hopf point (`crate::hopf::regula_falsi`) reads, at each friction
//! value it tries, the eigenvalues of two branches only, which it already knows at a nearby
//! friction value. A dense eigen-decomposition of the `2n × 2n` scaled state matrix `A` of
//! [`crate::spectrum`] with vectors costs a Hessenberg reduction (`10/3 (2n)³`), the QR
//! iteration with accumulated Schur vectors and the eigenvectors (measured on the medium
//! ventilated brake's 990 × 990 projected state matrix: 0.38 s with vectors, 0.25 s without,
//! 0.065 s for the Hessenberg reduction alone, docs/benchmarks.md). Here:
//!
//! 1. `A = Q H Qᵀ`, `H` upper Hessenberg, `Q` a product of Householder reflections kept in
//!    factored form (faer's `hessenberg_in_place`);
//! 2. from a known eigenpair `(λ₀, z₀)` of the matrix at a nearby friction value, `y = Qᵀ z₀`,
//!    `σ = λ₀`, Rayleigh quotient iteration on `H`: `(H - σ I) w = y` by Gaussian elimination
//!    with partial pivoting, which on a Hessenberg matrix costs `O(n²)` (one row below the
//!    diagonal per column), then `σ ← σ + wᴴ y / wᴴ w` (the Rayleigh quotient of `w`:
//!    `wᴴ H w / wᴴ w = σ + wᴴ (H - σ I) w / wᴴ w`), `y ← w / ‖w‖`, until the residual
//!    `‖(H - σ I) y‖` is at round-off, `c ε ‖H‖` (the backward error of any stable
//!    eigensolver, so that `σ` is an eigenvalue to round-off: for a non-normal matrix the
//!    iteration converges quadratically, Parlett, *The Symmetric Eigenvalue Problem*, and
//!    Ostrowski's analysis for the non-normal case);
//! 3. `z = Q y` (`O(n²)`), and the modal vector `q = Ω⁻¹ z₁`, normalized to `Σ |q|² = 1`, as in
//!    [`crate::spectrum::modal_spectrum`]. The state vector of a mode `q` with eigenvalue `λ`
//!    is `z = [Ω q; λ q]` (`q' = λ q`), which gives the start from a known mode.
//!
//! A pivot that is exactly zero (`σ` an eigenvalue to the last bit) is replaced by `ε ‖H‖`, as
//! LAPACK's `xHSEIN` does, so the elimination never divides by zero. Which eigenvalue the
//! iteration lands on is not guaranteed: the caller checks it (`crate::projected_hopf`).

use crate::damping::ModalDamping;
use crate::spectrum::state_matrix_of;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd::hessenberg::{hessenberg_in_place, hessenberg_in_place_scratch};
use faer::linalg::householder::{
    apply_block_householder_sequence_on_the_left_in_place_scratch,
    apply_block_householder_sequence_on_the_left_in_place_with_conj,
    apply_block_householder_sequence_transpose_on_the_left_in_place_scratch,
    apply_block_householder_sequence_transpose_on_the_left_in_place_with_conj,
};
use faer::linalg::qr::no_pivoting::factor::recommended_block_size;
use faer::{Conj, Mat, Par, c64};

/// Most Rayleigh quotient steps (the iteration converges in 2-4 from a neighbouring
/// friction value's eigenpair).
const MAX_STEPS: usize = 12;

/// Residual `‖(H - σ I) y‖∞ / (‖H‖₁ ‖y‖∞)` at which `σ` is an eigenvalue to round-off.
const CONVERGED: f64 = 1e3 * f64::EPSILON;

/// The scaled state matrix of a modal problem in Hessenberg form.
pub struct HessenbergForm {
    /// `ω_j` of the modal coordinates.
    omega: Vec<f64>,
    /// `H` in the upper Hessenberg part, the Householder vectors of `Q` below the subdiagonal
    /// (faer's layout).
    reduced: Mat<f64>,
    /// The Householder block factors of `Q`.
    factors: Mat<f64>,
    /// `‖H‖₁` (the largest column sum).
    norm: f64,
}

impl HessenbergForm {
    /// The state matrix of frequencies `omega`, damping `d` and changes `dk`, `dc`
    /// ([`crate::spectrum::modal_spectrum`]'s problem), reduced (sequentially: the bits do
    /// not depend on the thread count).
    pub fn new(
        omega: &[f64],
        damping: &ModalDamping,
        dk: &Mat<f64>,
        dc: Option<&Mat<f64>>,
    ) -> Self {
        let a = state_matrix_of(omega, damping, dk, dc);
        let (reduced, factors) = hessenberg(a);
        let size = reduced.nrows();
        let norm = (0..size)
            .map(|j| (0..size.min(j + 2)).map(|i| reduced[(i, j)].abs()).sum())
            .fold(0.0, f64::max);
        Self {
            omega: omega.to_vec(),
            reduced,
            factors,
            norm,
        }
    }

    /// The eigenpair `(λ, q)` reached by Rayleigh quotient iteration from the mode `q0` of
    /// eigenvalue `lambda0` (module documentation); `None` when the residual does not reach
    /// round-off in `MAX_STEPS` steps.
    pub fn rayleigh(&self, lambda0: c64, q0: &[c64]) -> Option<(c64, Vec<c64>)> {
        let n = self.omega.len();
        let size = self.reduced.nrows();
        // z0 = [Ω q0; λ0 q0], then y = Qᵀ z0.
        let z0: Vec<c64> = (0..size)
            .map(|i| {
                if i < n {
                    self.omega[i] * q0[i]
                } else {
                    lambda0 * q0[i - n]
                }
            })
            .collect();
        let mut y = self.apply(z0, true);
        normalize(&mut y);
        let mut sigma = lambda0;
        for _ in 0..MAX_STEPS {
            if self.residual(sigma, &y) <= CONVERGED {
                let z = self.apply(y, false);
                return Some((sigma, self.modal(&z)));
            }
            let lu = HessenbergLu::new(&self.reduced, sigma, f64::EPSILON * self.norm);
            let mut w = y.clone();
            lu.solve(&mut w);
            let (mut wy, mut ww) = (c64::new(0.0, 0.0), 0.0);
            for (a, b) in w.iter().zip(&y) {
                wy += a.conj() * b;
                ww += a.norm_sqr();
            }
            if !(ww.is_finite() && ww > 0.0) {
                return None;
            }
            sigma += wy / ww;
            y = w;
            normalize(&mut y);
        }
        None
    }

    /// `‖(H - σ I) y‖∞ / (‖H‖₁ ‖y‖∞)`.
    fn residual(&self, sigma: c64, y: &[c64]) -> f64 {
        let size = y.len();
        let mut worst = 0.0f64;
        for i in 0..size {
            let mut s = -sigma * y[i];
            for (j, yj) in y.iter().enumerate().skip(i.saturating_sub(1)) {
                s += self.reduced[(i, j)] * yj;
            }
            worst = worst.max(s.norm());
        }
        let scale = y.iter().map(|v| v.norm()).fold(0.0, f64::max);
        worst / (self.norm * scale).max(f64::MIN_POSITIVE)
    }

    /// `Q v` (`transpose`: `Qᵀ v`) for a complex `v`, its real and imaginary parts as two
    /// real columns (sequential).
    fn apply(&self, v: Vec<c64>, transpose: bool) -> Vec<c64> {
        let size = self.reduced.nrows();
        if size < 2 {
            return v;
        }
        let mut m = Mat::from_fn(size, 2, |i, j| if j == 0 { v[i].re } else { v[i].im });
        let bs = self.factors.nrows();
        let basis = self.reduced.as_ref().submatrix(1, 0, size - 1, size - 1);
        let target = m.as_mut().submatrix_mut(1, 0, size - 1, 2);
        if transpose {
            let req = apply_block_householder_sequence_transpose_on_the_left_in_place_scratch::<f64>(
                size - 1,
                bs,
                2,
            );
            apply_block_householder_sequence_transpose_on_the_left_in_place_with_conj(
                basis,
                self.factors.as_ref(),
                Conj::No,
                target,
                Par::Seq,
                MemStack::new(&mut MemBuffer::new(req)),
            );
        } else {
            let req = apply_block_householder_sequence_on_the_left_in_place_scratch::<f64>(
                size - 1,
                bs,
                2,
            );
            apply_block_householder_sequence_on_the_left_in_place_with_conj(
                basis,
                self.factors.as_ref(),
                Conj::No,
                target,
                Par::Seq,
                MemStack::new(&mut MemBuffer::new(req)),
            );
        }
        (0..size).map(|i| c64::new(m[(i, 0)], m[(i, 1)])).collect()
    }

    /// The unit modal vector `q = Ω⁻¹ z₁` of a state vector `z`.
    fn modal(&self, z: &[c64]) -> Vec<c64> {
        let mut q: Vec<c64> = self.omega.iter().zip(z).map(|(w, v)| v / *w).collect();
        let norm = q.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
        let inv = 1.0 / norm.max(f64::MIN_POSITIVE);
        q.iter_mut().for_each(|v| *v *= inv);
        q
    }
}

/// Scales `y` to a largest entry of modulus 1.
fn normalize(y: &mut [c64]) {
    let scale = y.iter().map(|v| v.norm()).fold(0.0, f64::max);
    let inv = 1.0 / scale.max(f64::MIN_POSITIVE);
    y.iter_mut().for_each(|v| *v *= inv);
}

/// The Hessenberg reduction of `a` in faer's layout (Hessenberg part and reflectors in the
/// returned matrix, block factors beside), sequential.
fn hessenberg(mut a: Mat<f64>) -> (Mat<f64>, Mat<f64>) {
    let size = a.nrows();
    if size < 2 {
        return (a, Mat::zeros(1, 0));
    }
    let bs = recommended_block_size::<f64>(size - 1, size - 1);
    let mut factors = Mat::<f64>::zeros(bs, size - 1);
    let scratch = hessenberg_in_place_scratch::<f64>(size, bs, Par::Seq, Default::default());
    hessenberg_in_place(
        a.as_mut(),
        factors.as_mut(),
        Par::Seq,
        MemStack::new(&mut MemBuffer::new(scratch)),
        Default::default(),
    );
    (a, factors)
}

/// `H - σ I = P L U` of an upper Hessenberg `H` (the part on and above the subdiagonal of
/// `reduced`) by Gaussian elimination with partial pivoting: at column `k` only rows `k` and
/// `k + 1` hold entries, so `L` has one multiplier per column and the pivoting is a choice
/// between two rows.
struct HessenbergLu {
    /// `U`, row by row (row `k` from column `k`).
    u: Vec<Vec<c64>>,
    /// Multiplier of column `k` and whether rows `k`, `k + 1` were swapped first.
    steps: Vec<(c64, bool)>,
}

impl HessenbergLu {
    fn new(reduced: &Mat<f64>, sigma: c64, tiny: f64) -> Self {
        let size = reduced.nrows();
        let tiny = c64::new(tiny.max(f64::MIN_POSITIVE), 0.0);
        let entry = |i: usize, j: usize| {
            let h = c64::new(reduced[(i, j)], 0.0);
            if i == j { h - sigma } else { h }
        };
        let mut steps = Vec::with_capacity(size.saturating_sub(1));
        let mut u: Vec<Vec<c64>> = Vec::with_capacity(size);
        // The pending row: row k of the partially eliminated matrix, from column k.
        let mut row: Vec<c64> = (0..size).map(|j| entry(0, j)).collect();
        for k in 0..size {
            if k + 1 == size {
                if row[0].norm() == 0.0 {
                    row[0] = tiny;
                }
                u.push(row);
                break;
            }
            let below: Vec<c64> = (k..size).map(|j| entry(k + 1, j)).collect();
            let swap = below[0].norm() > row[0].norm();
            let (mut top, mut bottom) = if swap { (below, row) } else { (row, below) };
            if top[0].norm() == 0.0 {
                top[0] = tiny;
            }
            let l = bottom[0] / top[0];
            for j in 1..top.len() {
                let t = top[j];
                bottom[j] -= l * t;
            }
            steps.push((l, swap));
            u.push(top);
            bottom.remove(0);
            row = bottom;
        }
        Self { u, steps }
    }

    /// `x ← (H - σ I)⁻¹ x`.
    fn solve(&self, x: &mut [c64]) {
        let size = x.len();
        for (k, &(l, swap)) in self.steps.iter().enumerate() {
            if swap {
                x.swap(k, k + 1);
            }
            let t = x[k];
            x[k + 1] -= l * t;
        }
        for k in (0..size).rev() {
            let row = &self.u[k];
            let mut s = x[k];
            for (j, &r) in row.iter().enumerate().skip(1) {
                s -= r * x[k + j];
            }
            x[k] = s / row[0];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::modal_spectrum;

    /// A damped modal problem with a non-symmetric (friction-like) stiffness change `s dk`.
    fn problem(n: usize, s: f64) -> (Vec<f64>, ModalDamping, Mat<f64>) {
        let omega: Vec<f64> = (0..n).map(|j| 1e3 * (1.0 + j as f64 * 0.7)).collect();
        let d = ModalDamping::Diagonal(omega.iter().map(|w| 0.02 * w).collect());
        let dk = Mat::from_fn(n, n, |i, j| {
            let v = s * 1e5 * ((i * 7 + j * 3) % 11) as f64 / 11.0;
            if i < j { v } else { -0.5 * v }
        });
        (omega, d, dk)
    }

    #[test]
    fn rayleigh_iteration_from_a_neighbouring_pair_lands_on_the_dense_solvers() {
        // Every eigenpair of the problem at s = 1, started from the dense solver's pair at
        // s = 0.98 (a neighbouring friction value), must land on the dense solver's pair at
        // s = 1: the eigenvalue within 1e-12 relative (both are backward stable, ε ‖A‖ ≈
        // 2e-12 on ‖A‖ ≈ 1e4; the eigenvalues of this problem are well separated, so their
        // condition numbers are O(1)), the shape's correlation |q_aᴴ q_b|² 1 to 1e-10.
        let n = 12;
        let (omega, d, dk0) = problem(n, 0.98);
        let (_, _, dk1) = problem(n, 1.0);
        let before = modal_spectrum(&omega, &d, &dk0, None, 0.0).unwrap();
        let after = modal_spectrum(&omega, &d, &dk1, None, 0.0).unwrap();
        let h = HessenbergForm::new(&omega, &d, &dk1, None);
        for j in 0..n {
            let q0: Vec<c64> = (0..n).map(|i| before.modes[(i, j)]).collect();
            let (l, q) = h.rayleigh(before.values[j], &q0).expect("converges");
            let e = after.values[j];
            assert!((l - e).norm() <= 1e-12 * e.norm(), "{l} against {e}");
            let mut s = c64::new(0.0, 0.0);
            for i in 0..n {
                s += after.modes[(i, j)].conj() * q[i];
            }
            assert!(
                (s.norm_sqr() - 1.0).abs() < 1e-10,
                "mode {j}: {}",
                s.norm_sqr()
            );
        }
    }
}
