//! The constraint of eqs (36)–(47): the equivalent linearization of the contact forces over the
//! cycle (eq 45), the eigenvalue of `J = A + J_NL` (eqs 43–44) that went unstable, and its real
//! part `f2` (eq 47) with its derivative.
//!
//! **Equivalent linearization.** `J_NL` is the Jacobian of eq (42) with respect to the state
//! `Y = [X; X']`, so the fit of eq (45) has a stiffness and a damping part. Each pair's contact
//! force depends on its penetration `δ(t)` only, and friction follows the contact force, so the
//! fit is made pair by pair: `F(t) - F̄ ≈ k (δ(t) - δ̄) + c δ'(t)`, and
//! `J_NL` has eq (19)'s pattern with `K_eq = Σ k_p (g_p + μ h_p) g_pᵀ`,
//! `C_eq = Σ c_p (g_p + μ h_p) g_pᵀ`. Two fits are offered ([`Fit`]):
//! - [`Fit::Fundamental`] (default): the least-squares fit of the cycle's fundamental harmonic,
//!   `k + iωc = F₁ / δ₁` (the describing function). At every root of the harmonic balance
//!   equations, for any number of harmonics, the first-harmonic equations then say exactly that
//!   `iω` is an eigenvalue of `J`: `f2 = 0` at the limit cycle, while at the static solution
//!   `f2 = Re λ > 0`, which is what the constraint must tell apart.
//! - [`Fit::Samples`]: the stiffness-only fit over all AFT samples,
//!   `k = Σ (F_j - F̄)(δ_j - δ̄) / Σ (δ_j - δ̄)²`, `c = 0`: eq (45) taken literally for a
//!   displacement-dependent force; `f2` is then only approximately zero at the limit cycle.
//!
//! Both tend to the tangent stiffness `k_t(δ̄)` of the stability analysis (and `c → 0`) as the
//! amplitude goes to zero.
//!
//! **Eigenvalue.** In the modal coordinates of [`squeal_brake::modal_brake`], `J`'s
//! eigenvalues solve `Q(λ) q = 0`, `Q(λ) = Δ(λ) + U(λ) Vᵀ` with `Δ = diag(λ² + λ d_j + ω_j²)`,
//! `V = Φ_nᵀ G` and `U(λ) = Φ_nᵀ W(λ)`, `w_p = (κ_p - k_s,p) g_p + μ κ_p h_p`, `κ_p = k_p + λ c_p`:
//! a rank-`P` update (`P` contact pairs). Away from the poles of `Δ⁻¹`, `det Q = det Δ · det S`
//! with `S(λ) = I + Vᵀ Δ⁻¹ U(λ)` (`P × P`), so the tracked eigenvalue is refined by Newton's
//! method on `det S` (`λ ← λ - 1 / tr(S⁻¹ S')`), and its right and left vectors come from the
//! null vectors of `S`. Its derivatives: `dλ/dk_p = -(ψᴴ a_p)(b_pᵀ φ) / (ψᴴ Q'(λ) φ)` with
//! `a_p = Φ_nᵀ (g_p + μ h_p)`, `b_p = Φ_nᵀ g_p`, and `dλ/dc_p = λ dλ/dk_p`.

use faer::linalg::matmul::matmul;
use faer::linalg::solvers::Solve;
use faer::{Accum, Mat, Par, c64};
use squeal_brake::modal_brake::ModalBrake;
use squeal_brake::model::contact_law;
use squeal_hbm::{HarmonicLayout, Part, TimeSamples};
use std::f64::consts::PI;

/// Which equivalent linearization of eq (45).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Fit {
    #[default]
    Fundamental,
    Samples,
}

/// Per-pair equivalent stiffness and damping and their gradients in `(U~, ω)`.
#[derive(Clone, Debug)]
pub struct EquivalentLinearization {
    pub k: Vec<f64>,
    pub c: Vec<f64>,
    /// `dk_p / dU~` and `dc_p / dU~` (layout length), per pair.
    pub dk: Vec<Vec<f64>>,
    pub dc: Vec<Vec<f64>>,
    /// `dc_p / dω`.
    pub dc_domega: Vec<f64>,
    /// Fraction of the samples where each pair is open.
    pub open_fraction: Vec<f64>,
}

/// The layout's Fourier basis at the `nt` samples, block by block: `1`, `cos(2π h j / nt)`,
/// `sin(2π h j / nt)` (row `b` of the result holds block `b`'s `nt` values).
fn basis(layout: &HarmonicLayout, nt: usize) -> Vec<f64> {
    let mut out = vec![0.0; layout.n_blocks() * nt];
    for b in 0..layout.n_blocks() {
        let row = &mut out[b * nt..(b + 1) * nt];
        match layout.block_kind(b) {
            Some((0, _)) => row.fill(1.0),
            Some((h, part)) => {
                for (j, v) in row.iter_mut().enumerate() {
                    let (sn, cs) = (2.0 * PI * (h * j) as f64 / nt as f64).sin_cos();
                    *v = if part == Part::Cos { cs } else { sn };
                }
            }
            None => {}
        }
    }
    out
}

/// Projection of per-sample weights on the layout's Fourier basis (from [`basis`]), times a
/// pair's normal.
fn project(
    layout: &HarmonicLayout,
    basis: &[f64],
    weights: &[f64],
    normal: &[(usize, f64)],
    n: usize,
) -> Vec<f64> {
    let nt = weights.len();
    let mut grad = vec![0.0; layout.len()];
    for b in 0..layout.n_blocks() {
        let proj: f64 = basis[b * nt..(b + 1) * nt]
            .iter()
            .zip(weights)
            .map(|(c, w)| c * w)
            .sum();
        for &(i, g) in normal {
            grad[b * n + i] += g * proj;
        }
    }
    grad
}

/// Eq (45) pair by pair from the AFT samples of the last evaluation.
pub fn equivalent_linearization(
    mb: &ModalBrake,
    layout: &HarmonicLayout,
    s: &TimeSamples,
    omega: f64,
    fit: Fit,
) -> EquivalentLinearization {
    let (n, nt) = (s.n_dofs, s.n_samples);
    let np = mb.pairs.len();
    let mut out = EquivalentLinearization {
        k: Vec::with_capacity(np),
        c: Vec::with_capacity(np),
        dk: Vec::with_capacity(np),
        dc: Vec::with_capacity(np),
        dc_domega: Vec::with_capacity(np),
        open_fraction: Vec::with_capacity(np),
    };
    let mut delta = vec![0.0; nt];
    let mut force = vec![0.0; nt];
    let mut kt = vec![0.0; nt];
    let (cos1, sin1): (Vec<f64>, Vec<f64>) = (0..nt)
        .map(|j| (2.0 * PI * j as f64 / nt as f64).sin_cos())
        .map(|(s, c)| (c, s))
        .unzip();
    let basis = basis(layout, nt);
    for p in &mb.pairs {
        for j in 0..nt {
            delta[j] = p.penetration(&s.x[j * n..(j + 1) * n]);
            let (f, t) = contact_law(delta[j], p.k_linear, p.k_cubic);
            force[j] = f;
            kt[j] = t;
        }
        out.open_fraction
            .push(delta.iter().filter(|d| **d <= 0.0).count() as f64 / nt as f64);
        let dm = delta.iter().sum::<f64>() / nt as f64;
        let fm = force.iter().sum::<f64>() / nt as f64;
        let ss: f64 = delta.iter().map(|d| (d - dm).powi(2)).sum();
        let zero = vec![0.0; layout.len()];
        if ss <= (1e-12 * dm.abs().max(1e-12)).powi(2) * nt as f64 {
            // Zero amplitude: the fit's limit is the tangent stiffness at the mean, no damping.
            out.k.push(contact_law(dm, p.k_linear, p.k_cubic).1);
            out.c.push(0.0);
            out.dk.push(zero.clone());
            out.dc.push(zero);
            out.dc_domega.push(0.0);
            continue;
        }
        match fit {
            Fit::Samples => {
                let kp: f64 = delta
                    .iter()
                    .zip(&force)
                    .map(|(d, f)| (f - fm) * (d - dm))
                    .sum::<f64>()
                    / ss;
                // dk = Σ_j dδ_j (k_t,j δ̃_j + F̃_j - 2 k δ̃_j) / S.
                let w: Vec<f64> = (0..nt)
                    .map(|j| {
                        (kt[j] * (delta[j] - dm) + (force[j] - fm) - 2.0 * kp * (delta[j] - dm))
                            / ss
                    })
                    .collect();
                out.k.push(kp);
                out.c.push(0.0);
                out.dk.push(project(layout, &basis, &w, &p.normal, n));
                out.dc.push(zero);
                out.dc_domega.push(0.0);
            }
            Fit::Fundamental => {
                // First harmonics as complex numbers X = X_c - i X_s (sums over samples; the
                // common factor 2/N cancels in the ratio).
                let d1 = c64::new(
                    (0..nt).map(|j| delta[j] * cos1[j]).sum(),
                    -(0..nt).map(|j| delta[j] * sin1[j]).sum::<f64>(),
                );
                let f1 = c64::new(
                    (0..nt).map(|j| force[j] * cos1[j]).sum(),
                    -(0..nt).map(|j| force[j] * sin1[j]).sum::<f64>(),
                );
                let kc = f1 / d1;
                // dκ = (dF₁ - κ dδ₁) / δ₁ with dF₁ = Σ_j k_t,j dδ_j e_j, dδ₁ = Σ_j dδ_j e_j,
                // e_j = cos θ_j - i sin θ_j: per-sample complex weights w_j = (k_t,j - κ) e_j / δ₁.
                let w: Vec<c64> = (0..nt)
                    .map(|j| (c64::new(kt[j], 0.0) - kc) * c64::new(cos1[j], -sin1[j]) / d1)
                    .collect();
                let wr: Vec<f64> = w.iter().map(|v| v.re).collect();
                let wi: Vec<f64> = w.iter().map(|v| v.im).collect();
                out.k.push(kc.re);
                out.c.push(kc.im / omega);
                out.dk.push(project(layout, &basis, &wr, &p.normal, n));
                out.dc.push(
                    project(layout, &basis, &wi, &p.normal, n)
                        .into_iter()
                        .map(|v| v / omega)
                        .collect(),
                );
                out.dc_domega.push(-kc.im / (omega * omega));
            }
        }
    }
    out
}

/// The tracked eigenvalue of `J`, its vectors (modal coordinates) and derivatives.
#[derive(Clone, Debug)]
pub struct Tracked {
    pub lambda: c64,
    pub right: Vec<c64>,
    pub left: Vec<c64>,
    pub dlambda_dk: Vec<c64>,
    pub dlambda_dc: Vec<c64>,
    pub newton_steps: usize,
}

/// Why the eigenvalue could not be tracked.
#[derive(Debug, thiserror::Error)]
#[error("the eigenvalue of the equivalent linearization could not be followed from {from}: {why}")]
pub struct TrackError {
    pub from: c64,
    pub why: String,
}

/// The constraint's fixed data: `Φ_nᵀ g_p`, `Φ_nᵀ h_p`, frequencies, damping.
pub struct Eigenproblem {
    pub mu: f64,
    omega: Vec<f64>,
    damping: Vec<f64>,
    /// `n × P`: `Φ_nᵀ g_p` and `Φ_nᵀ h_p`.
    gm: Mat<f64>,
    hm: Mat<f64>,
    k_s: Vec<f64>,
}

impl Eigenproblem {
    pub fn new(mb: &ModalBrake) -> Self {
        let n = mb.modes();
        let np = mb.pairs.len();
        let proj = |v: &[(usize, f64)], j: usize| {
            v.iter().map(|&(i, a)| a * mb.phi_n[(i, j)]).sum::<f64>()
        };
        let gm = Mat::from_fn(n, np, |j, p| proj(&mb.pairs[p].normal, j));
        let hm = Mat::from_fn(n, np, |j, p| proj(&mb.pairs[p].tangent, j));
        Self::from_parts(
            mb.mu,
            mb.omega.clone(),
            mb.damping.clone(),
            gm,
            hm,
            mb.pairs.iter().map(|p| p.k_reference).collect(),
        )
    }

    fn from_parts(
        mu: f64,
        omega: Vec<f64>,
        damping: Vec<f64>,
        gm: Mat<f64>,
        hm: Mat<f64>,
        k_s: Vec<f64>,
    ) -> Self {
        Self {
            mu,
            omega,
            damping,
            gm,
            hm,
            k_s,
        }
    }

    /// `U(λ)` and `U'(λ)` for pair stiffnesses `k` and dampings `c`.
    fn u(&self, k: &[f64], c: &[f64], l: c64) -> (Mat<c64>, Mat<c64>) {
        let (n, np) = (self.gm.nrows(), self.gm.ncols());
        let u = Mat::from_fn(n, np, |j, p| {
            let kappa = l * c[p] + k[p];
            (kappa - self.k_s[p]) * self.gm[(j, p)] + kappa * (self.mu * self.hm[(j, p)])
        });
        let du = Mat::from_fn(n, np, |j, p| {
            c64::new(c[p] * (self.gm[(j, p)] + self.mu * self.hm[(j, p)]), 0.0)
        });
        (u, du)
    }

    /// The modal stiffness and damping changes `(ΔK, ΔC)` (dense, `n × n`), for a full
    /// eigen-decomposition.
    pub fn modal_change(&self, k: &[f64], c: &[f64]) -> (Mat<f64>, Mat<f64>) {
        let (n, np) = (self.gm.nrows(), self.gm.ncols());
        let uk = Mat::from_fn(n, np, |j, p| {
            (k[p] - self.k_s[p]) * self.gm[(j, p)] + self.mu * k[p] * self.hm[(j, p)]
        });
        let uc = Mat::from_fn(n, np, |j, p| {
            c[p] * (self.gm[(j, p)] + self.mu * self.hm[(j, p)])
        });
        (&uk * self.gm.transpose(), &uc * self.gm.transpose())
    }

    fn delta(&self, l: c64) -> Vec<c64> {
        (0..self.omega.len())
            .map(|j| l * l + l * self.damping[j] + self.omega[j] * self.omega[j])
            .collect()
    }

    /// Newton's method on `det S(λ)` from `guess`; then vectors and derivatives.
    pub fn track(&self, k: &[f64], c: &[f64], guess: c64) -> Result<Tracked, TrackError> {
        let (n, np) = (self.gm.nrows(), self.gm.ncols());
        let fail = |why: String| TrackError { from: guess, why };
        let mut l = guess;
        let mut steps = 0;
        loop {
            let (u, du) = self.u(k, c, l);
            let d = self.delta(l);
            let (s, ds) = self.secular(&u, &du, &d, l);
            let x = s.partial_piv_lu().solve(&ds);
            let tr: c64 = (0..np).map(|i| x[(i, i)]).sum();
            if !(tr.re.is_finite() && tr.im.is_finite()) || tr.norm() == 0.0 {
                return Err(fail(format!("singular secular matrix at λ = {l}")));
            }
            let step = c64::new(1.0, 0.0) / tr;
            l -= step;
            steps += 1;
            if step.norm() <= 1e-13 * l.norm() {
                break;
            }
            if steps >= 40 {
                return Err(fail(format!(
                    "Newton did not converge (last step {:.2e})",
                    step.norm()
                )));
            }
            if (l - guess).norm() > 0.5 * guess.norm() {
                return Err(fail(format!("Newton wandered to λ = {l}")));
            }
        }
        let (u, du) = self.u(k, c, l);
        let d = self.delta(l);
        let (s, _) = self.secular(&u, &du, &d, l);
        // Null vectors of S by one step of inverse iteration each.
        let ones = Mat::<c64>::from_fn(np, 1, |_, _| c64::new(1.0, 0.0));
        let y = s.partial_piv_lu().solve(&ones);
        let z = s.adjoint().to_owned().partial_piv_lu().solve(&ones);
        // φ = -Δ⁻¹ U y, ψ = -Δ⁻ᴴ V z (V = Gm, real).
        let right: Vec<c64> = (0..n)
            .map(|j| -(0..np).map(|p| y[(p, 0)] * u[(j, p)]).sum::<c64>() / d[j])
            .collect();
        let left: Vec<c64> = (0..n)
            .map(|j| -(0..np).map(|p| z[(p, 0)] * self.gm[(j, p)]).sum::<c64>() / d[j].conj())
            .collect();
        // ψᴴ Q'(λ) φ with Q' = diag(2λ + d_j) + U' Vᵀ.
        let vphi: Vec<c64> = (0..np)
            .map(|p| (0..n).map(|j| right[j] * self.gm[(j, p)]).sum())
            .collect();
        let mut denom: c64 = (0..n)
            .map(|j| left[j].conj() * (l * 2.0 + self.damping[j]) * right[j])
            .sum();
        for p in 0..np {
            let a: c64 = (0..n).map(|j| left[j].conj() * du[(j, p)]).sum();
            denom += a * vphi[p];
        }
        let dlambda_dk: Vec<c64> = (0..np)
            .map(|p| {
                let a: c64 = (0..n)
                    .map(|j| left[j].conj() * (self.gm[(j, p)] + self.mu * self.hm[(j, p)]))
                    .sum();
                -(a * vphi[p]) / denom
            })
            .collect();
        let dlambda_dc = dlambda_dk.iter().map(|v| v * l).collect();
        Ok(Tracked {
            lambda: l,
            right,
            left,
            dlambda_dk,
            dlambda_dc,
            newton_steps: steps,
        })
    }

    /// `S(λ) = I + Vᵀ Δ⁻¹ U(λ)` and `S'(λ) = Vᵀ (Δ⁻¹ U' - Δ⁻² Δ' U)`.
    ///
    /// Both are `Vᵀ T` for complex `n × P` matrices `T` (`Δ⁻¹ U`, resp. `Δ⁻¹ U' - Δ⁻² Δ' U`),
    /// with `V = Φ_nᵀ G` real: one real product `Vᵀ [Re T, Im T, Re T', Im T']`.
    fn secular(&self, u: &Mat<c64>, du: &Mat<c64>, d: &[c64], l: c64) -> (Mat<c64>, Mat<c64>) {
        let (n, np) = (u.nrows(), u.ncols());
        let mut t = Mat::<f64>::zeros(n, 4 * np);
        for j in 0..n {
            let inv = c64::new(1.0, 0.0) / d[j];
            let dinv = -(l * 2.0 + self.damping[j]) * inv * inv;
            for b in 0..np {
                let v = inv * u[(j, b)];
                let dv = dinv * u[(j, b)] + inv * du[(j, b)];
                t[(j, b)] = v.re;
                t[(j, np + b)] = v.im;
                t[(j, 2 * np + b)] = dv.re;
                t[(j, 3 * np + b)] = dv.im;
            }
        }
        let mut p = Mat::<f64>::zeros(np, 4 * np);
        matmul(
            p.as_mut(),
            Accum::Replace,
            self.gm.transpose(),
            t.as_ref(),
            1.0,
            Par::Seq,
        );
        let s = Mat::from_fn(np, np, |a, b| {
            c64::new(f64::from(u8::from(a == b)) + p[(a, b)], p[(a, np + b)])
        });
        let ds = Mat::from_fn(np, np, |a, b| {
            c64::new(p[(a, 2 * np + b)], p[(a, 3 * np + b)])
        });
        (s, ds)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3-mode system with one contact pair: the tracked eigenvalue agrees with a dense
    /// eigen-decomposition of the state matrix, and dλ/dk with a finite difference.
    #[test]
    fn tracked_eigenvalue_and_derivative_match_a_dense_solve() {
        let ep = Eigenproblem::from_parts(
            0.6,
            vec![900.0, 1000.0, 1700.0],
            vec![5.0, 5.0, 8.0],
            Mat::from_fn(3, 1, |j, _| [0.8, -0.5, 0.3][j]),
            Mat::from_fn(3, 1, |j, _| [0.4, 0.7, -0.2][j]),
            vec![2.0e5],
        );
        let k = [3.0e5];
        let c = [40.0];
        // Dense reference: eigenvalues of [[0, I], [-(Ω² + ΔK), -(D + ΔC)]].
        let (dk, dc) = ep.modal_change(&k, &c);
        let a = Mat::<f64>::from_fn(6, 6, |i, j| match (i < 3, j < 3) {
            (true, true) => 0.0,
            (true, false) => (i == j - 3) as u8 as f64,
            (false, true) => -(if i - 3 == j { ep.omega[j].powi(2) } else { 0.0 } + dk[(i - 3, j)]),
            (false, false) => -(if i == j { ep.damping[i - 3] } else { 0.0 } + dc[(i - 3, j - 3)]),
        });
        let ev = a.eigen().unwrap();
        let s = ev.S();
        let guess = c64::new(0.0, 1000.0);
        let t = ep.track(&k, &c, guess).unwrap();
        let nearest = (0..6)
            .map(|i| s[i])
            .min_by(|x, y| (x - guess).norm().total_cmp(&(y - guess).norm()))
            .unwrap();
        // Both are backward stable on a matrix of norm ~ω² = 3e6: agreement to ~1e-12 ω.
        assert!(
            (t.lambda - nearest).norm() < 1e-9 * nearest.norm(),
            "{} vs {nearest}",
            t.lambda
        );
        let h = 1.0;
        let tp = ep.track(&[k[0] + h], &c, t.lambda).unwrap();
        let tm = ep.track(&[k[0] - h], &c, t.lambda).unwrap();
        let fd = (tp.lambda - tm.lambda) / (2.0 * h);
        // Central differences with h = 1 N/m on k = 3e5: truncation ~ (h/k)^2 relative.
        assert!(
            (fd - t.dlambda_dk[0]).norm() < 1e-6 * fd.norm(),
            "{fd} vs {}",
            t.dlambda_dk[0]
        );
        let hc = 1e-3;
        let tp = ep.track(&k, &[c[0] + hc], t.lambda).unwrap();
        let tm = ep.track(&k, &[c[0] - hc], t.lambda).unwrap();
        let fd = (tp.lambda - tm.lambda) / (2.0 * hc);
        assert!(
            (fd - t.dlambda_dc[0]).norm() < 1e-6 * fd.norm(),
            "{fd} vs {}",
            t.dlambda_dc[0]
        );
    }
}
