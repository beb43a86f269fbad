//! The linearized brake of eqs (20)–(21) as a quadratic eigenproblem with a low-rank coupling.
//!
//! In the frictionless modal coordinates of [`crate::spectrum`] (`Φᵀ M Φ = I`,
//! `Φᵀ K_t0 Φ = Ω²`, `Φᵀ C Φ = D`) the brake linearized about its equilibrium at friction μ is
//!
//! `T(λ) q = (λ² I + λ D + Ω² + U Vᵀ) q = 0`,
//!
//! because the tangent stiffness of eqs (18)–(20) differs from the frictionless one only through
//! the contact pairs: `K_t(μ) - K_t0 = Σ_p [(k_p - k0_p) g_p + μ k_p h_p] g_pᵀ`, with `k_p` the
//! tangent contact stiffness `dF_c/dδ` of eq (8) at the equilibrium and `k0_p` its value at the
//! frictionless reference. So `ΔK = Φᵀ (K_t - K_t0) Φ = U Vᵀ` with, per pair `p`,
//!
//! - `v_p = Φᵀ g_p` (fixed: it does not depend on μ),
//! - `u_p = (k_p - k0_p) Φᵀ g_p + μ k_p Φᵀ h_p`,
//!
//! a rank of at most `P` (the number of pairs). `D` and `Ω` are diagonal, so `T(λ)` is a diagonal
//! plus a rank-`P` matrix: products with it cost `O(n P)` and solves `O(n P²)`
//! ([`LowRank::factor`]), instead of the `O(n³)` of a dense eigen-decomposition.

use crate::equilibrium::Equilibrium;
use crate::model::{Brake, contact_law};
use crate::spectrum::Reference;
use faer::{Mat, c64};

/// The fixed part of `T(λ)`: `Ω`, `D`, `V = Φᵀ G`, `Φᵀ H` and the reference stiffnesses.
#[derive(Clone, Debug)]
pub struct LowRank {
    /// ω_j (rad/s) and `D_jj` (s⁻¹).
    pub omega: Vec<f64>,
    pub damping: Vec<f64>,
    /// Number of contact pairs `P`.
    pairs: usize,
    /// `Φᵀ g_p` and `Φᵀ h_p`, column-major `n × P` (column `p` at `p n..(p + 1) n`).
    v: Vec<f64>,
    h: Vec<f64>,
    /// `k0_p`, `k_l` and `k_nl` per pair.
    k0: Vec<f64>,
    k_cubic: Vec<f64>,
    /// `max ω_j²`, `max D_jj`, `||V||_F`: the scale of `T(λ)` for relative residuals.
    omega2_max: f64,
    damping_max: f64,
    v_norm: f64,
}

/// The μ-dependent part of `T(λ)`: `U` at one equilibrium.
#[derive(Clone, Debug)]
pub struct Coupling {
    pub mu: f64,
    /// Tangent contact stiffness `k_p`, contact force `F_c,p` and penetration `δ_p` per pair.
    pub stiffness: Vec<f64>,
    pub force: Vec<f64>,
    pub penetration: Vec<f64>,
    /// `U`, column-major `n × P`.
    u: Vec<f64>,
    u_norm: f64,
}

/// Relative agreement required between `reference.kt0` and `K + Σ k0_p g_p g_pᵀ`: a few ulps
/// of the largest entry (both are the same sums of the same terms).
const CONSISTENCY: f64 = 1e-13;

impl LowRank {
    /// The low-rank form of the brake about `reference`. `None` when `reference.kt0` is not the
    /// brake's tangent stiffness at `reference.equilibrium` with μ = 0 (then `K_t - K_t0` is not
    /// of low rank), or when the sizes disagree.
    pub fn new(brake: &Brake, reference: &Reference) -> Option<Self> {
        let n = brake.size();
        let basis = &reference.basis;
        if basis.omega.len() != n
            || reference.damping.len() != n
            || basis.phi.nrows() != n
            || reference.equilibrium.x.len() != n
        {
            return None;
        }
        let x0 = &reference.equilibrium.x;
        let k0: Vec<f64> = brake
            .pairs
            .iter()
            .map(|p| contact_law(p.penetration(x0), p.k_linear, p.k_cubic).1)
            .collect();
        if !consistent(brake, reference, &k0) {
            return None;
        }
        let np = brake.pairs.len();
        let phi = &basis.phi;
        let mut v = vec![0.0; n * np];
        let mut h = vec![0.0; n * np];
        for (p, pair) in brake.pairs.iter().enumerate() {
            for j in 0..n {
                v[p * n + j] = pair.normal.iter().map(|&(i, g)| g * phi[(i, j)]).sum();
                h[p * n + j] = pair.tangent.iter().map(|&(i, s)| s * phi[(i, j)]).sum();
            }
        }
        let v_norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
        Some(Self {
            omega2_max: basis.omega.iter().map(|w| w * w).fold(0.0, f64::max),
            damping_max: reference
                .damping
                .iter()
                .map(|d| d.abs())
                .fold(0.0, f64::max),
            omega: basis.omega.clone(),
            damping: reference.damping.clone(),
            pairs: np,
            v,
            h,
            k0,
            k_cubic: brake.pairs.iter().map(|p| p.k_cubic).collect(),
            v_norm,
        })
    }

    /// Number of modes `n`.
    pub fn size(&self) -> usize {
        self.omega.len()
    }

    /// Number of contact pairs `P` (the rank of the coupling).
    pub fn pairs(&self) -> usize {
        self.pairs
    }

    /// `U` at the equilibrium `eq` (which holds μ).
    pub fn coupling(&self, brake: &Brake, eq: &Equilibrium) -> Coupling {
        let (n, np) = (self.size(), self.pairs);
        let mut stiffness = Vec::with_capacity(np);
        let mut force = Vec::with_capacity(np);
        let mut penetration = Vec::with_capacity(np);
        for p in &brake.pairs {
            let d = p.penetration(&eq.x);
            let (f, k) = contact_law(d, p.k_linear, p.k_cubic);
            stiffness.push(k);
            force.push(f);
            penetration.push(d);
        }
        let mut u = vec![0.0; n * np];
        for p in 0..np {
            for j in 0..n {
                let i = p * n + j;
                u[i] = (stiffness[p] - self.k0[p]) * self.v[i] + eq.mu * stiffness[p] * self.h[i];
            }
        }
        let u_norm = u.iter().map(|a| a * a).sum::<f64>().sqrt();
        Coupling {
            mu: eq.mu,
            stiffness,
            force,
            penetration,
            u,
            u_norm,
        }
    }

    /// `ΔK = U Vᵀ` as a dense `n × n` matrix (for the dense eigen-decomposition).
    pub fn stiffness_change(&self, c: &Coupling) -> Mat<f64> {
        let (n, np) = (self.size(), self.pairs);
        Mat::from_fn(n, n, |i, j| {
            (0..np).map(|p| c.u[p * n + i] * self.v[p * n + j]).sum()
        })
    }

    /// `δ_j(λ) = λ² + D_jj λ + ω_j²`, the diagonal of `T(λ)` without the coupling.
    pub fn delta(&self, j: usize, l: c64) -> c64 {
        l * l + l * self.damping[j] + self.omega[j] * self.omega[j]
    }

    /// `δ_j'(λ) = 2λ + D_jj`: `T'(λ)` is diagonal.
    pub fn delta_prime(&self, j: usize, l: c64) -> c64 {
        l * 2.0 + self.damping[j]
    }

    /// A bound on `||T(λ)||` for relative residuals.
    pub fn scale(&self, c: &Coupling, l: c64) -> f64 {
        let a = l.norm();
        a * a + self.damping_max * a + self.omega2_max + c.u_norm * self.v_norm
    }

    /// `T(λ) x`.
    pub fn apply(&self, c: &Coupling, l: c64, x: &[c64]) -> Vec<c64> {
        let z = self.project(&self.v, x);
        (0..self.size())
            .map(|j| self.delta(j, l) * x[j] + self.row_dot(&c.u, j, &z))
            .collect()
    }

    /// `T(λ)ᴴ y = (Δ̄ + V Uᵀ) y`.
    pub fn apply_adjoint(&self, c: &Coupling, l: c64, y: &[c64]) -> Vec<c64> {
        let w = self.project(&c.u, y);
        (0..self.size())
            .map(|j| self.delta(j, l).conj() * y[j] + self.row_dot(&self.v, j, &w))
            .collect()
    }

    /// `yᴴ T(λ) x` and `yᴴ T'(λ) x`: the Rayleigh functional's Newton step is their ratio.
    pub fn rayleigh(&self, c: &Coupling, l: c64, x: &[c64], y: &[c64]) -> (c64, c64) {
        let mut num = c64::new(0.0, 0.0);
        let mut den = c64::new(0.0, 0.0);
        for j in 0..self.size() {
            let yx = y[j].conj() * x[j];
            num += yx * self.delta(j, l);
            den += yx * self.delta_prime(j, l);
        }
        let vx = self.project(&self.v, x);
        let uy = self.project(&c.u, y);
        for p in 0..self.pairs {
            num += uy[p].conj() * vx[p];
        }
        (num, den)
    }

    /// `yᴴ (dU/dμ) Vᵀ x`: the derivative of `yᴴ T(λ) x` with μ at fixed λ, for the rates
    /// `dk_p/dμ` of the contact stiffnesses.
    pub fn mu_derivative(&self, c: &Coupling, dk: &[f64], x: &[c64], y: &[c64]) -> c64 {
        let np = self.pairs;
        let vx = self.project(&self.v, x);
        let vy = self.project(&self.v, y);
        let hy = self.project(&self.h, y);
        // du_p/dμ = dk_p v_p + (k_p + μ dk_p) h_p.
        (0..np)
            .map(|p| {
                let a = vy[p].conj() * dk[p] + hy[p].conj() * (c.stiffness[p] + c.mu * dk[p]);
                a * vx[p]
            })
            .sum()
    }

    /// Rates `dk_p/dμ` of the tangent contact stiffnesses along the equilibrium path: with
    /// `K_t dx/dμ = -Σ_q F_c,q h_q` (eq 14 differentiated) and `Φᵀ K_t Φ = T(0)`,
    /// `dδ/dμ = -Vᵀ T(0)⁻¹ Φᵀ H F_c`, and `dk_p/dμ = 6 k_nl,p δ_p dδ_p/dμ` (eq 8) on closed pairs.
    pub fn stiffness_rates(&self, c: &Coupling) -> Vec<f64> {
        let (n, np) = (self.size(), self.pairs);
        let zero = c64::new(0.0, 0.0);
        let b: Vec<c64> = (0..n)
            .map(|j| {
                let s: f64 = (0..np).map(|p| self.h[p * n + j] * c.force[p]).sum();
                c64::new(-s, 0.0)
            })
            .collect();
        let dx = self.factor(c, zero).solve(self, c, &b);
        let dd = self.project(&self.v, &dx);
        (0..np)
            .map(|p| {
                if c.penetration[p] > 0.0 {
                    6.0 * self.k_cubic[p] * c.penetration[p] * dd[p].re
                } else {
                    0.0
                }
            })
            .collect()
    }

    /// The traces `tr A` and `tr A²` of the scaled state matrix of [`crate::spectrum`]
    /// `A = [[0, Ω], [-(Ω + ΔK Ω⁻¹), -D]]`: the sums of its `2n` eigenvalues and of their
    /// squares. `tr A = -Σ D_jj`, `tr A² = Σ D_jj² - 2 Σ ω_j² - 2 tr ΔK`, `tr ΔK = Σ_p u_pᵀ v_p`.
    pub fn traces(&self, c: &Coupling) -> (f64, f64) {
        let tr_a = -self.damping.iter().sum::<f64>();
        let tr_dk: f64 = c.u.iter().zip(&self.v).map(|(a, b)| a * b).sum();
        let d2: f64 = self.damping.iter().map(|d| d * d).sum();
        let w2: f64 = self.omega.iter().map(|w| w * w).sum();
        (tr_a, d2 - 2.0 * w2 - 2.0 * tr_dk)
    }

    /// `Mᵀ x` for a column-major `n × P` matrix `M` (`x` complex).
    fn project(&self, m: &[f64], x: &[c64]) -> Vec<c64> {
        m.chunks_exact(self.size())
            .map(|col| {
                let (mut re, mut im) = (0.0, 0.0);
                for (a, xj) in col.iter().zip(x) {
                    re += a * xj.re;
                    im += a * xj.im;
                }
                c64::new(re, im)
            })
            .collect()
    }

    /// Row `j` of a column-major `n × P` matrix times `z`.
    fn row_dot(&self, m: &[f64], j: usize, z: &[c64]) -> c64 {
        let n = self.size();
        (0..self.pairs).map(|p| z[p] * m[p * n + j]).sum()
    }

    /// Factors `T(λ)` for solves with it and with its adjoint ([`Bordered`]).
    pub fn factor(&self, c: &Coupling, l: c64) -> Bordered {
        let (n, np) = (self.size(), self.pairs);
        let delta: Vec<c64> = (0..n).map(|j| self.delta(j, l)).collect();
        let near = nearest(&delta, NEAR.min(n));
        let m = near.len();
        let s = schur(self, c, &delta, &near);
        let size = m + np;
        let mut a = vec![c64::new(0.0, 0.0); size * size];
        let mut at = vec![c64::new(0.0, 0.0); size * size];
        for (r, &j) in near.iter().enumerate() {
            a[r * size + r] = delta[j];
            at[r * size + r] = delta[j];
            for p in 0..np {
                a[r * size + m + p] = c64::new(c.u[p * n + j], 0.0);
                a[(m + p) * size + r] = c64::new(-self.v[p * n + j], 0.0);
                at[r * size + m + p] = c64::new(self.v[p * n + j], 0.0);
                at[(m + p) * size + r] = c64::new(-c.u[p * n + j], 0.0);
            }
        }
        for p in 0..np {
            for q in 0..np {
                a[(m + p) * size + m + q] = s[p * np + q];
                at[(m + p) * size + m + q] = s[q * np + p];
            }
        }
        Bordered {
            delta,
            near,
            lu: SmallLu::new(size, a),
            lu_t: SmallLu::new(size, at),
        }
    }
}

/// Whether `reference.kt0` is `K + Σ k0_p g_p g_pᵀ` to round-off.
fn consistent(brake: &Brake, reference: &Reference, k0: &[f64]) -> bool {
    let n = brake.size();
    let kt0 = &reference.kt0;
    if kt0.nrows() != n || kt0.ncols() != n {
        return false;
    }
    let mut expected = brake.k.clone();
    for (p, pair) in brake.pairs.iter().enumerate() {
        for &(c, gc) in &pair.normal {
            for &(r, gr) in &pair.normal {
                expected[(r, c)] += k0[p] * gr * gc;
            }
        }
    }
    let mut scale = 0.0f64;
    let mut diff = 0.0f64;
    for j in 0..n {
        for i in 0..n {
            scale = scale.max(kt0[(i, j)].abs());
            diff = diff.max((kt0[(i, j)] - expected[(i, j)]).abs());
        }
    }
    diff <= CONSISTENCY * scale
}

/// Modes kept out of the Schur complement of [`Bordered`]: those nearest to λ, whose `1/δ_j`
/// would be large (a disc doublet and its neighbours).
const NEAR: usize = 4;

/// Indices of the `m` smallest `|δ_j|` (ties to the lower index), ascending by index.
fn nearest(delta: &[c64], m: usize) -> Vec<usize> {
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

/// `S = I + Σ_{j ∉ near} v_j u_jᵀ / δ_j` (`P × P`, row-major): `S_ab = δ_ab + Σ_j V_ja U_jb
/// w_j` with `w_j = 1/δ_j` (0 for the near modes), as dot products over the modes.
fn schur(lr: &LowRank, c: &Coupling, delta: &[c64], near: &[usize]) -> Vec<c64> {
    let (n, np) = (lr.size(), lr.pairs);
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
    let mut s = vec![c64::new(0.0, 0.0); np * np];
    for a in 0..np {
        let va = &lr.v[a * n..(a + 1) * n];
        for j in 0..n {
            t_re[j] = va[j] * w_re[j];
            t_im[j] = va[j] * w_im[j];
        }
        for b in 0..np {
            let ub = &c.u[b * n..(b + 1) * n];
            let one = if a == b { 1.0 } else { 0.0 };
            s[a * np + b] = c64::new(one + dot(&t_re, ub), dot(&t_im, ub));
        }
    }
    s
}

/// `Σ a_j b_j` in four interleaved partial sums (vectorizable, in a fixed order).
fn dot(a: &[f64], b: &[f64]) -> f64 {
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

/// `T(λ)` factored for solves: the modes nearest to λ stay unknowns next to `z = Vᵀ x`, the
/// others are eliminated (their `δ_j` is far from zero):
///
/// `[[Δ_J, U_J], [-V_Jᵀ, S]] [x_J; z] = [b_J; Σ_{j∉J} v_j b_j / δ_j]`,
/// `x_j = (b_j - u_jᵀ z) / δ_j` for `j ∉ J`,
///
/// with `S` of [`schur`]. The adjoint uses the same blocks with `U` and `V` exchanged (`Tᵀ =
/// Δ + V Uᵀ`). Keeping the nearest modes in the small system avoids dividing by a `δ_j` that
/// vanishes where λ meets a mode barely touched by the contact.
pub struct Bordered {
    delta: Vec<c64>,
    near: Vec<usize>,
    lu: SmallLu,
    lu_t: SmallLu,
}

impl Bordered {
    /// `T(λ)⁻¹ b`.
    pub fn solve(&self, lr: &LowRank, c: &Coupling, b: &[c64]) -> Vec<c64> {
        self.solve_with(lr, &c.u, &lr.v, &self.lu, b)
    }

    /// `T(λ)⁻ᴴ b`: `Tᵀ ȳ = b̄` with `Tᵀ = Δ + V Uᵀ`.
    pub fn solve_adjoint(&self, lr: &LowRank, c: &Coupling, b: &[c64]) -> Vec<c64> {
        let bc: Vec<c64> = b.iter().map(|v| v.conj()).collect();
        let y = self.solve_with(lr, &lr.v, &c.u, &self.lu_t, &bc);
        y.into_iter().map(|v| v.conj()).collect()
    }

    /// Solves `(Δ + L Rᵀ) x = b` with the factored bordered matrix of that pair.
    fn solve_with(&self, lr: &LowRank, l: &[f64], r: &[f64], lu: &SmallLu, b: &[c64]) -> Vec<c64> {
        let (n, np) = (lr.size(), lr.pairs);
        let m = self.near.len();
        let mut rhs = vec![c64::new(0.0, 0.0); m + np];
        for (i, &j) in self.near.iter().enumerate() {
            rhs[i] = b[j];
        }
        let mut inv_b = vec![c64::new(0.0, 0.0); b.len()];
        for j in 0..b.len() {
            if self.near.contains(&j) {
                continue;
            }
            inv_b[j] = b[j] / self.delta[j];
            for p in 0..np {
                rhs[m + p] += inv_b[j] * r[p * n + j];
            }
        }
        lu.solve(&mut rhs);
        let z = &rhs[m..];
        let mut x = vec![c64::new(0.0, 0.0); b.len()];
        for j in 0..b.len() {
            if let Some(i) = self.near.iter().position(|&k| k == j) {
                x[j] = rhs[i];
            } else {
                let lz: c64 = (0..np).map(|p| z[p] * l[p * n + j]).sum();
                x[j] = inv_b[j] - lz / self.delta[j];
            }
        }
        x
    }
}

/// A small dense complex LU factorization with partial pivoting, after scaling rows and then
/// columns to unit largest entry (by powers of two, which round nothing): the bordered matrix
/// mixes entries of order `ω²`, `k_p` and 1. A zero pivot is replaced by `ε` times the largest
/// entry, as inverse iteration does at an exact eigenvalue: the solve then returns a large
/// multiple of the null vector, which is what is wanted.
struct SmallLu {
    n: usize,
    a: Vec<c64>,
    perm: Vec<usize>,
    row_scale: Vec<f64>,
    col_scale: Vec<f64>,
}

/// `|Re z| + |Im z|`: a norm as good as `|z|` for pivoting and scaling, without a square root.
fn abs1(z: c64) -> f64 {
    z.re.abs() + z.im.abs()
}

/// The power of two nearest to `1 / m` (1 for a zero or non-finite `m`).
fn inverse_power_of_two(m: f64) -> f64 {
    if m > 0.0 && m.is_finite() {
        (-m.log2().round()).exp2()
    } else {
        1.0
    }
}

impl SmallLu {
    fn new(n: usize, mut a: Vec<c64>) -> Self {
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
                for c in 0..n {
                    a.swap(k * n + c, piv * n + c);
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
                for c in k + 1..n {
                    let v = a[k * n + c];
                    a[i * n + c] -= f * v;
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

    fn solve(&self, b: &mut [c64]) {
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
