//! The lowest real modes of a dense symmetric pencil `(K, M)` up to a frequency, without the
//! whole eigendecomposition: a dense shift-invert block Lanczos with a Sturm count, for the
//! system vectors of a large brake ([`crate::interface_system`]).
//!
//! # The method
//!
//! The modes of eq (20)'s frictionless tangent, `K φ = ω² M φ` with `K = K_t0` positive
//! definite (the brake held by its contact springs), are those of the symmetric standard
//! problem
//!
//! `A y = θ y`,  `A = L⁻¹ M L⁻ᵀ`,  `K = L Lᵀ`,  `θ = 1/ω²`,  `φ = ω L⁻ᵀ y`
//!
//! (shift-invert at σ = 0: the lowest modes are `A`'s largest eigenvalues, well separated
//! relative to its spectrum's spread, so a Krylov space of `A` finds them first). A block
//! Krylov space `span{Q₀, A Q₀, A² Q₀, …}` of `b` columns per block is grown with full
//! reorthogonalization (classical Gram–Schmidt twice), and its Rayleigh–Ritz pairs
//! `(θ_j, y_j)` of `Vᵀ A V` are accepted when the explicit residual `‖A y_j − θ_j y_j‖` is below
//! [`TOLERANCE`] `θ_j` for each of the `r` wanted ones. The block carries multiplets of up to
//! `b` copies (a disc's doublets) together.
//!
//! **How many.** `r`, the number of modes with `ω ≤ ω_c`, is not guessed from the Ritz values:
//! it is the Sturm count of `K − ω_c² M` (Sylvester's law of inertia: the number of negative
//! eigenvalues of its dense `L B Lᵀ` factorization with Bunch–Kaufman pivoting equals the number
//! of eigenvalues of the pencil below `ω_c²`), so the partial solve keeps exactly the modes the
//! whole decomposition would, and none is missed in a cluster.
//!
//! **The vectors.** The `r` Ritz vectors are mapped back (`L⁻ᵀ y`) and a last Rayleigh–Ritz
//! step on the pencil itself, `(Φᵀ K Φ, Φᵀ M Φ)` of size `r`, makes them `M`-orthonormal with
//! ascending `ω` exactly as [`crate::modal::modal_basis`] returns them.
//!
//! # Cost
//!
//! The Cholesky factor of `K` (`n³/3` flops, kept for the friction residuals' solves of the
//! caller: one factorization serves both), the `L B Lᵀ` of the Sturm count (`n³/3`), and per
//! Krylov vector two triangular solves and a product with `M` (`4 n²`) and its
//! reorthogonalization (`8 n k` at size `k`), with `k` about `3 r`: [`partial_flops`], against
//! about `13 n³` for the whole decomposition ([`dense_flops`]). On the fine corner (7636 dofs,
//! 100 in-band modes) that is about 15 times fewer.

use crate::dense_par::{add_product, par_for, product};
use crate::error::BrakeError;
use crate::modal::ModalBasis;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Accum, Mat, MatRef, Side};

/// Relative residual `‖A y − θ y‖ / θ` at which a Ritz pair is accepted: its vector is then
/// within about this over the relative gap of the exact one (and its eigenvalue within its
/// square), far below what the interface basis or the sweep resolve.
pub const TOLERANCE: f64 = 1e-11;

/// Columns per Krylov block: multiplets of up to this many copies converge together.
const BLOCK: usize = 8;

/// Flops of the whole dense decomposition of [`crate::modal::modal_basis`] with the LU of the
/// residual solves: Cholesky of `M` and two triangular solves of `n` columns (`2⅓ n³`), the
/// tridiagonalization and vectors (about `9 n³`), the back-substitution (`n³`) and the LU
/// (`⅔ n³`).
pub fn dense_flops(n: usize) -> f64 {
    13.0 * (n as f64).powi(3)
}

/// Flops of the partial solve for `r` modes (module documentation): two factorizations, a
/// Krylov space of `3 r + 2 b` vectors with its reorthogonalization and the final Ritz steps.
pub fn partial_flops(n: usize, r: usize) -> f64 {
    let (n, k) = (n as f64, (3 * r + 2 * BLOCK) as f64);
    2.0 / 3.0 * n.powi(3) + k * 4.0 * n * n + 4.0 * n * k * k + 4.0 * n * n * r as f64
}

/// The Cholesky factor `L` of `K` (`K = L Lᵀ`), `None` when `K` is not positive definite.
pub fn cholesky(k: &Mat<f64>) -> Option<Mat<f64>> {
    crate::dense_par::cholesky(k)
}

/// The number of eigenvalues of the pencil `(K, M)` below `sigma` (both symmetric, `M`
/// positive definite): the negative eigenvalues of `K − σ M` (module documentation).
pub fn count_below(k: &Mat<f64>, m: &Mat<f64>, sigma: f64) -> usize {
    let n = k.nrows();
    let shifted = Mat::from_fn(n, n, |i, j| k[(i, j)] - sigma * m[(i, j)]);
    let (d, e) = crate::dense_par::lblt_blocks(shifted);
    let mut negative = 0;
    let mut i = 0;
    while i < n {
        if i + 1 < n && e[i] != 0.0 {
            // A 2 x 2 block: one of each sign when its determinant is negative.
            let det = d[i] * d[i + 1] - e[i] * e[i];
            negative += if det < 0.0 {
                1
            } else if d[i] < 0.0 {
                2
            } else {
                0
            };
            i += 2;
        } else {
            negative += usize::from(d[i] < 0.0);
            i += 1;
        }
    }
    negative
}

/// The `r` lowest modes of `(k, m)`, ascending and `M`-orthonormal, from the Cholesky factor
/// `l` of `k` (module documentation; `r` from [`count_below`]); `None` when the Krylov space
/// reaches its cap without converging (the caller then takes the whole decomposition).
pub fn lowest_modes(
    m: &Mat<f64>,
    k: &Mat<f64>,
    l: &Mat<f64>,
    r: usize,
) -> Result<Option<ModalBasis>, BrakeError> {
    let n = m.nrows();
    if r == 0 {
        return Ok(Some(ModalBasis {
            phi: Mat::zeros(n, 0),
            omega: Vec::new(),
        }));
    }
    let Some(y) = krylov(m, l.as_ref(), r) else {
        return Ok(None);
    };
    // φ = L⁻ᵀ y, then the Rayleigh–Ritz step on the pencil itself.
    let mut phi = y;
    solve_upper_triangular_in_place(l.transpose(), phi.as_mut(), par_for(n));
    let kr = product(phi.transpose(), product(k.as_ref(), phi.as_ref()).as_ref());
    let mr = product(phi.transpose(), product(m.as_ref(), phi.as_ref()).as_ref());
    let small = crate::modal::modal_basis(&symmetric(&mr), &symmetric(&kr))?;
    let phi = product(phi.as_ref(), small.phi.as_ref());
    Ok(Some(ModalBasis {
        phi,
        omega: small.omega,
    }))
}

/// `(a + aᵀ) / 2`.
fn symmetric(a: &Mat<f64>) -> Mat<f64> {
    Mat::from_fn(a.nrows(), a.ncols(), |i, j| 0.5 * (a[(i, j)] + a[(j, i)]))
}

/// `A x = L⁻¹ M L⁻ᵀ x` for the columns of `x`.
fn apply(m: &Mat<f64>, l: MatRef<'_, f64>, x: MatRef<'_, f64>) -> Mat<f64> {
    let mut y = x.to_owned();
    let par = par_for(l.nrows());
    solve_upper_triangular_in_place(l.transpose(), y.as_mut(), par);
    let mut z = product(m.as_ref(), y.as_ref());
    solve_lower_triangular_in_place(l, z.as_mut(), par);
    z
}

/// A deterministic start block (splitmix64 values in `[-1, 1)`): the same bits every run.
fn start_block(n: usize, b: usize, seed: u64) -> Mat<f64> {
    let mut next = uniform(seed);
    Mat::from_fn(n, b, |_, _| next())
}

/// Deterministic values in `[-1, 1)` from `seed` (splitmix64): the same bits every run (the
/// start blocks here, and test matrices).
pub fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = s;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// Orthonormalizes the columns of `w` against the columns of `v` (block classical
/// Gram–Schmidt, twice) and among themselves (modified Gram–Schmidt, twice); columns that
/// vanish (dependent) are replaced by fresh start vectors, orthonormalized the same way.
fn orthonormalize(v: MatRef<'_, f64>, w: &mut Mat<f64>, seed: &mut u64) {
    let n = w.nrows();
    let before: Vec<f64> = (0..w.ncols()).map(|j| w.col(j).norm_l2()).collect();
    for _ in 0..2 {
        if v.ncols() > 0 {
            let c = product(v.transpose(), w.as_ref());
            add_product(w.as_mut(), Accum::Add, v, c.as_ref(), -1.0);
        }
    }
    for j in 0..w.ncols() {
        let mut reference = before[j];
        for _ in 0..4 {
            for _ in 0..2 {
                within(w, j);
            }
            let after = w.col(j).norm_l2();
            if after > 1e-8 * reference && after > 0.0 {
                let s = 1.0 / after;
                w.col_mut(j).iter_mut().for_each(|x| *x *= s);
                break;
            }
            // Dependent on the space: a fresh direction, made orthogonal to it.
            *seed += 1;
            let mut fresh = start_block(n, 1, *seed);
            for _ in 0..2 {
                if v.ncols() > 0 {
                    let c = product(v.transpose(), fresh.as_ref());
                    add_product(fresh.as_mut(), Accum::Add, v, c.as_ref(), -1.0);
                }
            }
            reference = fresh.col(0).norm_l2();
            w.col_mut(j).copy_from(fresh.col(0));
        }
    }
}

/// Removes from column `j` of `w` its components along the (orthonormal) columns before it.
fn within(w: &mut Mat<f64>, j: usize) {
    let n = w.nrows();
    for i in 0..j {
        let d: f64 = (0..n).map(|r| w[(r, i)] * w[(r, j)]).sum();
        for r in 0..n {
            let a = w[(r, i)];
            w[(r, j)] -= d * a;
        }
    }
}

/// The `r` dominant eigenvectors `y` of `A` (columns, the largest `θ` first), or `None` when
/// the space reaches its cap (`min(n, 8 r + 4 b)`) first.
fn krylov(m: &Mat<f64>, l: MatRef<'_, f64>, r: usize) -> Option<Mat<f64>> {
    let n = m.nrows();
    let b = BLOCK.min(n);
    let cap = n.min(8 * r + 4 * b);
    let mut seed = 0x5EED_u64;
    let mut v = Mat::<f64>::zeros(n, 0);
    let mut av = Mat::<f64>::zeros(n, 0);
    let mut block = start_block(n, b, seed);
    orthonormalize(v.as_ref(), &mut block, &mut seed);
    loop {
        let a_block = apply(m, l, block.as_ref());
        v = concat(&v, &block);
        av = concat(&av, &a_block);
        let k = v.ncols();
        if k >= r + b || k >= cap {
            if let Some(y) = converged(&v, &av, r) {
                return Some(y);
            }
            if k >= cap {
                return None;
            }
        }
        let take = b.min(cap - k);
        let mut next = a_block.subcols(0, take).to_owned();
        orthonormalize(v.as_ref(), &mut next, &mut seed);
        block = next;
    }
}

/// `[a, b]` side by side.
fn concat(a: &Mat<f64>, b: &Mat<f64>) -> Mat<f64> {
    let (n, ka) = (a.nrows().max(b.nrows()), a.ncols());
    Mat::from_fn(n, ka + b.ncols(), |i, j| {
        if j < ka { a[(i, j)] } else { b[(i, j - ka)] }
    })
}

/// The `r` dominant Ritz vectors of the space `v` (with `av = A v`) when each has its residual
/// below [`TOLERANCE`] `θ`, else `None`.
fn converged(v: &Mat<f64>, av: &Mat<f64>, r: usize) -> Option<Mat<f64>> {
    let k = v.ncols();
    let t = product(v.transpose(), av.as_ref());
    let t = symmetric(&t);
    let scale = t.norm_max().max(f64::MIN_POSITIVE);
    let ts = Mat::from_fn(k, k, |i, j| t[(i, j)] / scale);
    let evd = ts.self_adjoint_eigen(Side::Lower).ok()?;
    // Ascending θ: the wanted are the last r, taken largest first.
    let s: Vec<usize> = (k - r..k).rev().collect();
    let z = Mat::from_fn(k, r, |i, j| evd.U()[(i, s[j])]);
    let theta: Vec<f64> = s.iter().map(|&j| evd.S()[j] * scale).collect();
    let y = product(v.as_ref(), z.as_ref());
    let ay = product(av.as_ref(), z.as_ref());
    let floor = 1e3 * f64::EPSILON * theta[0];
    let ok = (0..r).all(|j| {
        let res = (0..y.nrows())
            .map(|i| (ay[(i, j)] - theta[j] * y[(i, j)]).powi(2))
            .sum::<f64>()
            .sqrt();
        theta[j] > 0.0 && res <= (TOLERANCE * theta[j]).max(floor)
    });
    ok.then_some(y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Par;

    /// A dense pencil with known modes, `K = M V diag(ω²) Vᵀ M` with `V` `M`-orthonormal and an
    /// exact doublet (modes 10 and 11 share `ω`): the count and the partial solve against the
    /// whole decomposition of the same pencil.
    #[test]
    fn partial_modes_are_the_dense_ones() {
        let n = 120;
        // M: SPD, dense (diagonal dominant); K: the modes of a chain with a repeated value.
        let m = Mat::from_fn(n, n, |i, j| {
            if i == j {
                2.0 + 0.01 * i as f64
            } else {
                0.3 / (1.0 + (i as f64 - j as f64).abs()).powi(2)
            }
        });
        let w2: Vec<f64> = (0..n)
            .map(|i| {
                // A doublet: modes 9 and 10 share their value.
                let k = if i == 10 { 9 } else { i };
                1e6 * (1.0 + k as f64).powi(2)
            })
            .collect();
        // K = M V diag(ω²) Vᵀ M with V M-orthonormal: the pencil's modes are V's columns.
        // V = L⁻ᵀ U (M = L Lᵀ, U orthonormal) is M-orthonormal.
        let mut v = start_block(n, n, 7);
        orthonormalize(Mat::<f64>::zeros(n, 0).as_ref(), &mut v, &mut 8);
        let lm = cholesky(&m).unwrap();
        solve_upper_triangular_in_place(lm.transpose(), v.as_mut(), Par::Seq);
        let mv = &m * &v;
        let k = Mat::from_fn(n, n, |i, j| {
            (0..n).map(|c| mv[(i, c)] * w2[c] * mv[(j, c)]).sum()
        });
        let k = symmetric(&k);
        let cut = (1e6f64 * 30.5f64.powi(2)).sqrt();
        let r = count_below(&k, &m, cut * cut);
        // ω² = 1e6 (i+1)² below 1e6 · 30.5² for i = 0..29, mode 10 taking mode 9's value
        // (the doublet) instead of its own: 30 values, the doublet's two among them.
        assert_eq!(r, 30);
        let l = cholesky(&k).unwrap();
        let p = lowest_modes(&m, &k, &l, r).unwrap().unwrap();
        let d = crate::modal::modal_basis(&m, &k).unwrap();
        for j in 0..r {
            // Frequencies to 1e-10 relative: TOLERANCE's square is far below, the dense
            // solve's residual 1e-12 of the unit-norm problem above.
            assert!((p.omega[j] - d.omega[j]).abs() <= 1e-10 * d.omega[j], "{j}");
        }
        // Span: the partial modes lie in the dense in-band span, M-norm of what is outside.
        let dp = Mat::from_fn(n, r, |i, j| d.phi[(i, j)]);
        let c = dp.transpose() * (&m * &p.phi);
        let out = &p.phi - &dp * &c;
        let g = out.transpose() * (&m * &out);
        let worst = (0..r)
            .map(|j| g[(j, j)].max(0.0).sqrt())
            .fold(0.0, f64::max);
        // An M-unit vector's component outside: 1e-8 (TOLERANCE over the relative gap, 0.03).
        assert!(worst <= 1e-8, "{worst:e}");
    }
}
