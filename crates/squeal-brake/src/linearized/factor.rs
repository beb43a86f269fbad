//! Solves with the linearized brake's matrix at one λ: a dense LU for small models, a bordered solve of the modal diagonal plus the contact coupling (Schur complement) for large ones.

use super::*;
use squeal_eigs::dense::SmallLu;

/// `T(λ)` factored for solves.
pub enum Factor {
    /// Diagonal `D`: the bordered system of a diagonal plus rank-`r` matrix.
    Bordered(Bordered),
    /// Full `D`: a dense LU factorization.
    Dense(DenseFactor),
}

impl Factor {
    /// `T(λ)⁻¹ b`.
    pub fn solve(&self, lr: &LinearizedBrake, c: &Coupling, b: &[c64]) -> Vec<c64> {
        match self {
            Factor::Bordered(f) => f.solve(lr, c, b, false),
            Factor::Dense(f) => f.solve(b, false),
        }
    }

    /// `T(λ)⁻ᴴ b`.
    pub fn solve_adjoint(&self, lr: &LinearizedBrake, c: &Coupling, b: &[c64]) -> Vec<c64> {
        match self {
            Factor::Bordered(f) => f.solve(lr, c, b, true),
            Factor::Dense(f) => f.solve(b, true),
        }
    }
}

/// `T(λ)` as a dense complex matrix, LU-factored with partial pivoting (full `D`).
pub struct DenseFactor {
    pub(super) lu: faer::linalg::solvers::PartialPivLu<c64>,
    pub(super) lu_adjoint: faer::linalg::solvers::PartialPivLu<c64>,
}

impl DenseFactor {
    pub(super) fn new(lr: &LinearizedBrake, c: &Coupling, l: c64) -> Self {
        let n = lr.size();
        let u: Vec<Vec<c64>> = (0..c.rank)
            .map(|p| {
                let mut z = vec![c64::new(0.0, 0.0); c.rank];
                z[p] = c64::new(1.0, 0.0);
                lr.apply_u(c, l, &z)
            })
            .collect();
        let t = Mat::<c64>::from_fn(n, n, |i, j| {
            let mut s = l * lr.damping.entry(i, j);
            if i == j {
                s += l * l + lr.omega[i] * lr.omega[i];
            }
            for (p, up) in u.iter().enumerate() {
                s += up[i] * c.v[p * n + j];
            }
            s
        });
        Self::of(t)
    }

    /// `T(λ) = Δ(λ) + U(λ) Vᵀ` with a diagonal `D` (`Δ_jj = λ² + λ d_j + ω_j²`, `U(λ) = U₀ +
    /// λ U₁`), formed by one matrix product `U(λ) Vᵀ` (`n² r`, sequential, so the same bits on
    /// any thread count) and LU-factored: for a coupling whose rank reaches the size, where
    /// [`Bordered`]'s `(m + r)`-square system would be larger than `T` itself
    /// ([`LinearizedBrake::factor`]).
    pub(super) fn low_rank(lr: &LinearizedBrake, c: &Coupling, d: &[f64], l: c64) -> Self {
        let n = lr.size();
        let r = c.rank;
        let u = Mat::<c64>::from_fn(n, r, |i, p| {
            let a = c64::new(c.u0[p * n + i], 0.0);
            match &c.u1 {
                Some(u1) => a + l * u1[p * n + i],
                None => a,
            }
        });
        let vt = Mat::<c64>::from_fn(r, n, |p, j| c64::new(c.v[p * n + j], 0.0));
        let mut t = Mat::<c64>::zeros(n, n);
        faer::linalg::matmul::matmul(
            t.as_mut(),
            faer::Accum::Replace,
            u.as_ref(),
            vt.as_ref(),
            c64::new(1.0, 0.0),
            faer::Par::Seq,
        );
        for j in 0..n {
            t[(j, j)] += l * l + l * d[j] + lr.omega[j] * lr.omega[j];
        }
        Self::of(t)
    }

    /// `t` and its adjoint LU-factored.
    fn of(t: Mat<c64>) -> Self {
        let th = t.adjoint().to_owned();
        Self {
            lu: t.partial_piv_lu(),
            lu_adjoint: th.partial_piv_lu(),
        }
    }

    pub(super) fn solve(&self, b: &[c64], adjoint: bool) -> Vec<c64> {
        let rhs = Mat::<c64>::from_fn(b.len(), 1, |i, _| b[i]);
        let x = if adjoint {
            self.lu_adjoint.solve(&rhs)
        } else {
            self.lu.solve(&rhs)
        };
        (0..b.len()).map(|i| x[(i, 0)]).collect()
    }
}

/// Modes kept out of the Schur complement of [`Bordered`]: those nearest to λ, whose `1/δ_j`
/// would be large (a disc doublet and its neighbours).
pub(super) const NEAR: usize = 4;

/// Indices of the `m` smallest `|δ_j|` (ties to the lower index), ascending by index.
pub(super) fn nearest(delta: &[c64], m: usize) -> Vec<usize> {
    // Insertion into a short sorted list: `m` is a handful, `n` a few hundred.
    let mut best: Vec<(f64, usize)> = Vec::with_capacity(m + 1);
    for (j, d) in delta.iter().enumerate() {
        let a = d.norm_sqr();
        if best.len() == m && best.last().is_some_and(|&(b, _)| a >= b) {
            continue;
        }
        let at = best.partition_point(|&(b, _)| b <= a);
        best.insert(at, (a, j));
        best.truncate(m);
    }
    let mut out: Vec<usize> = best.into_iter().map(|(_, j)| j).collect();
    out.sort_unstable();
    out
}

/// `Σ a_j b_j` in four interleaved partial sums (vectorizable, in a fixed order).
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0f64; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// `T(λ) = Δ + U Vᵀ` (diagonal `D`) factored for solves: the modes nearest to λ stay
/// unknowns next to `z = Vᵀ x`, the others are eliminated (their `δ_j` is far from zero):
///
/// `[[Δ_J, U_J], [-V_Jᵀ, S]] [x_J; z] = [b_J; Σ_{j∉J} v_j b_j / δ_j]`,
/// `x_j = (b_j - u_jᵀ z) / δ_j` for `j ∉ J`,
///
/// with the Schur complement `S = I + Σ_{j∉J} v_j u_jᵀ / δ_j` (`r × r`). The adjoint uses the
/// same blocks with `U` and `V` exchanged (`Tᵀ = Δ + V Uᵀ`). Keeping the nearest modes in the
/// small system avoids dividing by a `δ_j` that vanishes where λ meets a mode barely touched
/// by the contact. `U = U₀ + λ U₁` is complex when `U₁ ≠ 0`.
pub struct Bordered {
    pub(super) delta: Vec<c64>,
    pub(super) near: Vec<usize>,
    /// `U(λ)` split into real and imaginary parts (column-major `n × r`) when `U₁ ≠ 0`; else
    /// `U = U₀`, read from the coupling.
    pub(super) u_lambda: Option<(Vec<f64>, Vec<f64>)>,
    pub(super) lu: SmallLu,
    pub(super) lu_t: SmallLu,
}

/// Column `p` (of `n` entries) of a column-major matrix, and of its imaginary part if any.
pub(super) fn column<'a>(
    re: &'a [f64],
    im: &'a [f64],
    p: usize,
    n: usize,
) -> (&'a [f64], Option<&'a [f64]>) {
    (&re[p * n..(p + 1) * n], im.get(p * n..(p + 1) * n))
}

/// `Σ_j x_j m_j` over a column `m` (real, or complex `re + i im`), summed in order of `j`.
pub(super) fn dot_column(x: &[c64], (re, im): (&[f64], Option<&[f64]>)) -> c64 {
    let mut s = c64::new(0.0, 0.0);
    match im {
        None => {
            for (a, &m) in x.iter().zip(re) {
                s += c64::new(a.re * m, a.im * m);
            }
        }
        Some(im) => {
            for ((a, &mr), &mi) in x.iter().zip(re).zip(im) {
                s += a * c64::new(mr, mi);
            }
        }
    }
    s
}

/// `acc_j += a m_j` over a column `m` (real, or complex `re + i im`).
pub(super) fn add_column(acc: &mut [c64], a: c64, (re, im): (&[f64], Option<&[f64]>)) {
    match im {
        None => {
            for (o, &m) in acc.iter_mut().zip(re) {
                *o += c64::new(a.re * m, a.im * m);
            }
        }
        Some(im) => {
            for ((o, &mr), &mi) in acc.iter_mut().zip(re).zip(im) {
                *o += a * c64::new(mr, mi);
            }
        }
    }
}

impl Bordered {
    pub(super) fn new(lr: &LinearizedBrake, c: &Coupling, d: &[f64], l: c64) -> Self {
        let n = lr.size();
        let r = c.rank;
        let delta: Vec<c64> = (0..n)
            .map(|j| l * l + l * d[j] + lr.omega[j] * lr.omega[j])
            .collect();
        let near = nearest(&delta, NEAR.min(n));
        let m = near.len();
        let u_lambda: Option<(Vec<f64>, Vec<f64>)> = c.u1.as_ref().map(|u1| {
            (
                c.u0.iter().zip(u1).map(|(a, b)| a + l.re * b).collect(),
                u1.iter().map(|b| l.im * b).collect(),
            )
        });
        let (u_re, u_im): (&[f64], &[f64]) = match &u_lambda {
            Some((re, im)) => (re, im),
            None => (&c.u0, &[]),
        };
        let u_at = |i: usize| c64::new(u_re[i], u_im.get(i).copied().unwrap_or(0.0));
        let s = schur(n, r, &c.v, u_re, u_im, &delta, &near);
        let size = m + r;
        let mut a = vec![c64::new(0.0, 0.0); size * size];
        let mut at = vec![c64::new(0.0, 0.0); size * size];
        for (row, &j) in near.iter().enumerate() {
            a[row * size + row] = delta[j];
            at[row * size + row] = delta[j];
            for p in 0..r {
                a[row * size + m + p] = u_at(p * n + j);
                a[(m + p) * size + row] = c64::new(-c.v[p * n + j], 0.0);
                at[row * size + m + p] = c64::new(c.v[p * n + j], 0.0);
                at[(m + p) * size + row] = -u_at(p * n + j);
            }
        }
        for p in 0..r {
            for q in 0..r {
                a[(m + p) * size + m + q] = s[p * r + q];
                at[(m + p) * size + m + q] = s[q * r + p];
            }
        }
        Bordered {
            delta,
            near,
            u_lambda,
            lu: SmallLu::new(size, a),
            lu_t: SmallLu::new(size, at),
        }
    }

    /// Solves `T x = b` or, with `adjoint`, `Tᴴ x = b` (as `Tᵀ x̄ = b̄`, `Tᵀ = Δ + V Uᵀ`). The
    /// sums over the modes run along the columns of `U` and `V` (contiguous), each in the
    /// order of the modes.
    pub(super) fn solve(
        &self,
        lr: &LinearizedBrake,
        c: &Coupling,
        b: &[c64],
        adjoint: bool,
    ) -> Vec<c64> {
        let (n, r) = (lr.size(), c.rank);
        let b: Vec<c64> = if adjoint {
            b.iter().map(|v| v.conj()).collect()
        } else {
            b.to_vec()
        };
        let (u_re, u_im): (&[f64], &[f64]) = match &self.u_lambda {
            Some((re, im)) => (re, im),
            None => (&c.u0, &[]),
        };
        // (Δ + L Rᵀ) x = b with (L, R) = (U, V), or (V, U) for the transpose.
        let u_col = |p: usize| column(u_re, u_im, p, n);
        let v_col = |p: usize| column(&c.v, &[], p, n);
        let (left, right): (&dyn Fn(usize) -> _, &dyn Fn(usize) -> _) = if adjoint {
            (&v_col, &u_col)
        } else {
            (&u_col, &v_col)
        };
        let m = self.near.len();
        // b_j / δ_j off the near modes, 0 on them (which adds nothing to the sums below).
        let mut inv_b: Vec<c64> = b.iter().zip(&self.delta).map(|(bj, d)| bj / d).collect();
        let mut rhs = vec![c64::new(0.0, 0.0); m + r];
        for (i, &j) in self.near.iter().enumerate() {
            rhs[i] = b[j];
            inv_b[j] = c64::new(0.0, 0.0);
        }
        for p in 0..r {
            rhs[m + p] = dot_column(&inv_b, right(p));
        }
        if adjoint {
            self.lu_t.solve(&mut rhs);
        } else {
            self.lu.solve(&mut rhs);
        }
        let mut lz = vec![c64::new(0.0, 0.0); n];
        for (p, &zp) in rhs[m..].iter().enumerate() {
            add_column(&mut lz, zp, left(p));
        }
        let mut x: Vec<c64> = inv_b
            .iter()
            .zip(&lz)
            .zip(&self.delta)
            .map(|((ib, l), d)| ib - l / d)
            .collect();
        for (i, &j) in self.near.iter().enumerate() {
            x[j] = rhs[i];
        }
        if adjoint {
            for v in &mut x {
                *v = v.conj();
            }
        }
        x
    }
}

/// `S = I + Σ_{j ∉ near} v_j u_jᵀ / δ_j` (`r × r`, row-major): `S_ab = δ_ab + Σ_j V_ja U_jb
/// w_j` with `w_j = 1/δ_j` (0 for the near modes), as dot products over the modes.
pub(super) fn schur(
    n: usize,
    r: usize,
    v: &[f64],
    u_re: &[f64],
    u_im: &[f64],
    delta: &[c64],
    near: &[usize],
) -> Vec<c64> {
    let mut w_re = vec![0.0; n];
    let mut w_im = vec![0.0; n];
    for j in 0..n {
        if !near.contains(&j) {
            let w = c64::new(1.0, 0.0) / delta[j];
            w_re[j] = w.re;
            w_im[j] = w.im;
        }
    }
    let mut t_re = vec![0.0; n];
    let mut t_im = vec![0.0; n];
    let mut s = vec![c64::new(0.0, 0.0); r * r];
    for a in 0..r {
        let va = &v[a * n..(a + 1) * n];
        for j in 0..n {
            t_re[j] = va[j] * w_re[j];
            t_im[j] = va[j] * w_im[j];
        }
        for b in 0..r {
            let ub = &u_re[b * n..(b + 1) * n];
            let one = if a == b { 1.0 } else { 0.0 };
            let mut re = one + dot(&t_re, ub);
            let mut im = dot(&t_im, ub);
            if !u_im.is_empty() {
                let ui = &u_im[b * n..(b + 1) * n];
                re -= dot(&t_im, ui);
                im += dot(&t_re, ui);
            }
            s[a * r + b] = c64::new(re, im);
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A brake of `n` modes (diagonal damping) and a rank-`r` coupling with `U₁ ≠ 0`, from a
    /// fixed linear congruential sequence.
    fn brake(n: usize, r: usize) -> (LinearizedBrake, Coupling) {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let omega: Vec<f64> = (0..n).map(|j| 1000.0 * (1.0 + j as f64)).collect();
        let d: Vec<f64> = (0..n).map(|j| 0.02 * omega[j]).collect();
        let lr = LinearizedBrake::modal(omega, ModalDamping::Diagonal(d));
        let v: Vec<f64> = (0..n * r).map(|_| next()).collect();
        let u0: Vec<f64> = (0..n * r).map(|_| 1e5 * next()).collect();
        let u1: Vec<f64> = (0..n * r).map(|_| 10.0 * next()).collect();
        (lr, Coupling::from_columns(0.4, v, u0, Some(u1), n))
    }

    fn rel(a: &[c64], b: &[c64]) -> f64 {
        let d: f64 = a.iter().zip(b).map(|(x, y)| (x - y).norm_sqr()).sum();
        let s: f64 = b.iter().map(|y| y.norm_sqr()).sum();
        (d / s).sqrt()
    }

    /// With more pairs than modes `factor` forms `T` itself; its solves must be those of the
    /// bordered system (the same matrix, another elimination) and solve `T x = b` and
    /// `Tᴴ y = b`. Both are backward stable on a `T` of condition about 1e3 here, so 1e-10
    /// leaves a margin of 1e3 over the round-off; a wrong entry of `U Vᵀ` or of the diagonal
    /// is off by order one.
    #[test]
    fn a_coupling_of_rank_above_the_size_is_factored_whole_with_the_bordered_solves() {
        let (n, r) = (12, 20);
        let (lr, c) = brake(n, r);
        let d = lr.damping.diagonal().unwrap().to_vec();
        let l = c64::new(-30.0, 2.0e3 * std::f64::consts::TAU);
        let b: Vec<c64> = (0..n)
            .map(|j| c64::new(1.0 + j as f64, 0.5 - j as f64))
            .collect();
        let whole = lr.factor(&c, l);
        assert!(matches!(whole, Factor::Dense(_)));
        let bordered = Bordered::new(&lr, &c, &d, l);
        let x = whole.solve(&lr, &c, &b);
        assert!(rel(&x, &bordered.solve(&lr, &c, &b, false)) < 1e-10);
        assert!(rel(&lr.apply(&c, l, &x), &b) < 1e-10);
        let y = whole.solve_adjoint(&lr, &c, &b);
        assert!(rel(&y, &bordered.solve(&lr, &c, &b, true)) < 1e-10);
        assert!(rel(&lr.apply_adjoint(&c, l, &y), &b) < 1e-10);
    }

    /// Below the size the bordered system stays (the pinned brakes' bits).
    #[test]
    fn a_coupling_of_rank_below_the_size_keeps_the_bordered_system() {
        let (lr, c) = brake(30, 10);
        let l = c64::new(-30.0, 5.0e3);
        assert!(matches!(lr.factor(&c, l), Factor::Bordered(_)));
    }
}
