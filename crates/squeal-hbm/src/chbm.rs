//! The Constrained Harmonic Balance Method (Coudeyras, Sinou & Nacivet 2009, section 4) for
//! any linear part and any [`NonlinearForce`]: the constraint `f2 = Re λ` of eq. (47), where λ
//! is the eigenvalue of the system linearized *over the cycle* (eqs. 36–45) that continues
//! the unstable eigenvalue of the static solution.
//!
//! **The linearization over the cycle (describing function).** Let `X = U1c - i U1s` and
//! `F = F1c - i F1s` be the complex first harmonics of the motion and of the nonlinear force
//! on the force's dofs, and `J₀(λ) = K₀ + λ C₀` a reference linearization of the force (its
//! Jacobians at the static solution). The equivalent linearization is the smallest change of
//! `J₀` that reproduces the cycle's fundamental force exactly,
//!
//! `N(iω) X = F`:  `N(iω) = J₀(iω) + a Xᴴ / |X|²`,  `a = F - J₀(iω) X`
//!
//! (the rank-one secant update of Broyden's method). For one dof it is the classical
//! describing function `F / X`; as the amplitude goes to zero it tends to the tangent
//! linearization, so at the static solution λ is the unstable eigenvalue and `f2 = Re λ > 0`.
//! Split into stiffness and damping, `N(λ) = N_K + λ N_C` with
//! `N_K = K₀ + Re(a Xᴴ)/|X|²`, `N_C = C₀ + Im(a Xᴴ)/(ω |X|²)`. At every root of the harmonic
//! balance equations, for any number of harmonics, the first-harmonic rows say
//! `Z(ω) X + F = 0`, i.e. `[Z(ω) + N(iω)] X = 0`: `iω` is an eigenvalue and `f2 = 0` exactly.
//! The paper's eq. (45) fits a stiffness per contact pair over the time samples instead;
//! that needs the force's structure and makes `f2` only nearly zero at the cycle.
//!
//! **The eigenvalue and its derivatives.** The linear part tracks the eigenvalue of
//! `Z(λ) + N(λ)` nearest the previous one ([`LinearizedEigen`]) and returns its right and
//! left vectors on the force's dofs, `φ`, `ψ`, and `σ = ψᴴ T'(λ) φ` (in the normalization of
//! the full system). First-order perturbation then gives, for any unknown θ of the harmonic
//! balance, `dλ/dθ = -ψᴴ (∂N(λ)/∂θ) φ / σ`. With `α = (1 - iλ/ω)/2`, `β = (1 + iλ/ω)/2`,
//! `ψᴴ (N - J₀) φ = [α (ψᴴa)(Xᴴφ) + β (ψᴴā)(Xᵀφ)] / |X|²`, whose derivatives need only
//! `dF/dθ` (the first-harmonic rows of the force's harmonic balance Jacobian) and `dX/dθ`.

use faer::linalg::solvers::Solve;
use faer::{Mat, MatMut, MatRef, c64};

use crate::HbmError;
use crate::force::{LocalJacobian, NonlinearForce};
use crate::hb::{CycleConstraint, CycleEval, ForceDerivatives};
use crate::layout::HarmonicLayout;
use crate::linear::MckStiffness;

/// An eigenvalue of the linearized system with its vectors on the nonlinear force's dofs.
#[derive(Clone, Debug, PartialEq)]
pub struct EigenTrack {
    pub lambda: c64,
    /// `φ` restricted to the force's dofs.
    pub right: Vec<c64>,
    /// `ψ` restricted to the force's dofs.
    pub left: Vec<c64>,
    /// `σ = ψᴴ T'(λ) φ` over the whole system.
    pub slope: c64,
}

/// An update `N(λ) = N_K + λ N_C` on the force's dofs, as a reference plus a low-rank
/// correction: `N_K = K₀ + L_K Rᵀ`, `N_C = C₀ + L_C Rᵀ` (`R`, `L_K`, `L_C` with a few columns).
/// The reference is the same from one call to the next within a solve, so an implementation
/// can prepare it once.
#[derive(Clone, Copy, Debug)]
pub struct LinearUpdate<'a> {
    pub k0: MatRef<'a, f64>,
    pub c0: MatRef<'a, f64>,
    pub left_k: MatRef<'a, f64>,
    pub left_c: MatRef<'a, f64>,
    pub right: MatRef<'a, f64>,
}

impl LinearUpdate<'_> {
    /// `(N_K, N_C)` as dense matrices.
    pub fn dense(&self) -> (Mat<f64>, Mat<f64>) {
        let rt = self.right.transpose();
        (
            self.k0.to_owned() + self.left_k * rt,
            self.c0.to_owned() + self.left_c * rt,
        )
    }
}

/// A linear part that can follow an eigenvalue of itself plus an update on the force's dofs.
pub trait LinearizedEigen {
    /// The eigenvalue of `Z(λ) + N_K + λ N_C` (`Z(λ) = λ² M + λ C + K` the linear part, the
    /// update square on the force's dofs) that continues the one followed so far, or the one
    /// nearest `guess` on the first call.
    fn track(&mut self, update: &LinearUpdate<'_>, guess: c64) -> Result<EigenTrack, HbmError>;
}

/// The force's Jacobians `(∂f/∂x, ∂f/∂ẋ)` at `x` with `ẋ = 0`, as dense matrices: the
/// reference linearization `J₀` at a static solution.
pub fn reference_jacobian<F: NonlinearForce + ?Sized>(
    force: &F,
    x: &[f64],
) -> (Mat<f64>, Mat<f64>) {
    let n = force.n_dofs();
    let pattern = force.pattern();
    let (mut dx, mut dv) = (vec![0.0; pattern.len()], vec![0.0; pattern.len()]);
    let mut f = vec![0.0; n];
    force.eval(
        x,
        &vec![0.0; n],
        &mut f,
        Some(LocalJacobian {
            dfdx: &mut dx,
            dfdxdot: &mut dv,
        }),
    );
    let (mut k, mut c) = (Mat::zeros(n, n), Mat::zeros(n, n));
    for (p, &(i, j)) in pattern.iter().enumerate() {
        k[(i, j)] += dx[p];
        if force.depends_on_velocity() {
            c[(i, j)] += dv[p];
        }
    }
    (k, c)
}

/// The describing-function linearization of one cycle (module documentation).
#[derive(Clone, Debug)]
pub struct DescribingFunction {
    /// `N_K`, `N_C` (square on the force's dofs).
    pub n_k: Mat<f64>,
    pub n_c: Mat<f64>,
    /// The correction to `J₀` as `N_K - K₀ = L_K Rᵀ`, `N_C - C₀ = L_C Rᵀ` with
    /// `R = [x_r, x_i]`, `L_K = [a_r, a_i] / |X|²`, `L_C = [a_i, -a_r] / (ω |X|²)` (no columns
    /// at zero amplitude).
    pub left_k: Mat<f64>,
    pub left_c: Mat<f64>,
    pub right: Mat<f64>,
    /// `X`, `F`, `a = F - J₀(iω) X` and `|X|²`.
    x: Vec<c64>,
    a: Vec<c64>,
    norm2: f64,
}

fn first_harmonic(layout: &HarmonicLayout, v: &[f64]) -> Vec<c64> {
    let n = layout.n_dofs();
    (0..n).map(|d| c64::new(v[n + d], -v[2 * n + d])).collect()
}

/// `J₀(iω) x = (K₀ + iω C₀) x`.
fn apply_reference(k0: &Mat<f64>, c0: &Mat<f64>, omega: f64, x: &[c64]) -> Vec<c64> {
    let n = x.len();
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| x[j] * c64::new(k0[(i, j)], omega * c0[(i, j)]))
                .sum()
        })
        .collect()
}

impl DescribingFunction {
    /// `N` at the cycle `(U~, ω)` whose force coefficients are `force`, about `J₀ = (k0, c0)`.
    pub fn new(
        layout: &HarmonicLayout,
        u: &[f64],
        omega: f64,
        force: &[f64],
        k0: &Mat<f64>,
        c0: &Mat<f64>,
    ) -> Self {
        let n = layout.n_dofs();
        let x = first_harmonic(layout, u);
        let f = first_harmonic(layout, force);
        let jx = apply_reference(k0, c0, omega, &x);
        let a: Vec<c64> = f.iter().zip(&jx).map(|(f, j)| f - j).collect();
        let norm2: f64 = x.iter().map(|v| v.norm_sqr()).sum();
        let (mut n_k, mut n_c) = (k0.clone(), c0.clone());
        let cols = if norm2 > 0.0 && norm2.is_finite() {
            2
        } else {
            0
        };
        // Re(a Xᴴ) = a_r x_rᵀ + a_i x_iᵀ and Im(a Xᴴ) = a_i x_rᵀ - a_r x_iᵀ.
        let right = Mat::from_fn(n, cols, |i, c| if c == 0 { x[i].re } else { x[i].im });
        let left_k = Mat::from_fn(n, cols, |i, c| {
            (if c == 0 { a[i].re } else { a[i].im }) / norm2
        });
        let left_c = Mat::from_fn(n, cols, |i, c| {
            (if c == 0 { a[i].im } else { -a[i].re }) / (omega * norm2)
        });
        if cols > 0 {
            for i in 0..n {
                for j in 0..n {
                    // a_i conj(x_j) / |X|².
                    let p = a[i] * x[j].conj() / norm2;
                    n_k[(i, j)] += p.re;
                    n_c[(i, j)] += p.im / omega;
                }
            }
        }
        Self {
            n_k,
            n_c,
            left_k,
            left_c,
            right,
            x,
            a,
            norm2,
        }
    }

    /// The update about the reference `(k0, c0)` this linearization was made with.
    pub fn update<'a>(&'a self, k0: &'a Mat<f64>, c0: &'a Mat<f64>) -> LinearUpdate<'a> {
        LinearUpdate {
            k0: k0.as_ref(),
            c0: c0.as_ref(),
            left_k: self.left_k.as_ref(),
            left_c: self.left_c.as_ref(),
            right: self.right.as_ref(),
        }
    }
}

/// CHBM's constraint `f2 = weight · Re λ / scale` (eq. 47), with λ followed by a
/// [`LinearizedEigen`] through the describing-function linearization of each cycle.
pub struct ReLambda<T> {
    tracker: T,
    k0: Mat<f64>,
    c0: Mat<f64>,
    weight: f64,
    scale: f64,
    lambda: c64,
    /// The last evaluation: `(z, N, track)`, reused by the Jacobian at the same point.
    last: Option<(Vec<f64>, DescribingFunction, EigenTrack)>,
    /// λ at every residual evaluation.
    lambdas: Vec<c64>,
}

impl<T: LinearizedEigen> ReLambda<T> {
    /// The constraint about the reference linearization `(k0, c0)` (see
    /// [`reference_jacobian`]), starting from the eigenvalue `lambda` of the static solution,
    /// with `f2 = weight Re λ / scale` (e.g. `scale = Im λ`, so that `f2` is a damping ratio).
    pub fn new(
        tracker: T,
        k0: Mat<f64>,
        c0: Mat<f64>,
        lambda: c64,
        weight: f64,
        scale: f64,
    ) -> Result<Self, HbmError> {
        if !(scale.is_finite() && scale > 0.0) {
            return Err(HbmError::BadScale {
                what: "eigenvalue scale",
                value: scale,
            });
        }
        if !(weight.is_finite() && weight > 0.0) {
            return Err(HbmError::BadScale {
                what: "constraint weight",
                value: weight,
            });
        }
        Ok(Self {
            tracker,
            k0,
            c0,
            weight,
            scale,
            lambda,
            last: None,
            lambdas: Vec::new(),
        })
    }

    /// λ at every residual evaluation so far.
    pub fn lambdas(&self) -> &[c64] {
        &self.lambdas
    }

    /// The eigenvalue at the last evaluation.
    pub fn lambda(&self) -> c64 {
        self.lambda
    }

    /// The tracker.
    pub fn tracker(&self) -> &T {
        &self.tracker
    }

    fn z_of(eval: &CycleEval<'_>) -> Vec<f64> {
        let mut z = eval.u.to_vec();
        z.push(eval.omega);
        z
    }

    fn evaluate(
        &mut self,
        eval: &CycleEval<'_>,
    ) -> Result<(DescribingFunction, EigenTrack), HbmError> {
        let df = DescribingFunction::new(
            &eval.layout,
            eval.u,
            eval.omega,
            eval.force,
            &self.k0,
            &self.c0,
        );
        let t = self
            .tracker
            .track(&df.update(&self.k0, &self.c0), self.lambda)?;
        self.lambda = t.lambda;
        Ok((df, t))
    }
}

impl<T: LinearizedEigen> CycleConstraint for ReLambda<T> {
    fn rows(&self) -> usize {
        1
    }

    fn residual(&mut self, eval: &CycleEval<'_>, out: &mut [f64]) -> Result<(), HbmError> {
        let (df, t) = self.evaluate(eval)?;
        out[0] = self.weight * t.lambda.re / self.scale;
        self.lambdas.push(t.lambda);
        self.last = Some((Self::z_of(eval), df, t));
        Ok(())
    }

    fn jacobian(
        &mut self,
        eval: &CycleEval<'_>,
        d: &ForceDerivatives<'_>,
        mut out: MatMut<'_, f64>,
    ) -> Result<(), HbmError> {
        let z = Self::z_of(eval);
        let (df, t) = match self.last.take() {
            Some((zl, df, t)) if zl == z => (df, t),
            _ => self.evaluate(eval)?,
        };
        let grad = gradient(eval, d, &df, &t, &self.k0, &self.c0);
        let s = self.weight / self.scale;
        for (j, g) in grad.iter().enumerate() {
            out[(0, j)] = s * g;
        }
        self.last = Some((z, df, t));
        Ok(())
    }
}

/// `d(Re λ)/dθ` for `θ = [U~, ω]` (module documentation).
fn gradient(
    eval: &CycleEval<'_>,
    d: &ForceDerivatives<'_>,
    df: &DescribingFunction,
    t: &EigenTrack,
    k0: &Mat<f64>,
    c0: &Mat<f64>,
) -> Vec<f64> {
    let layout = &eval.layout;
    let (n, len, w) = (layout.n_dofs(), layout.len(), eval.omega);
    let mut grad = vec![0.0; len + 1];
    if !(df.norm2 > 0.0 && df.norm2.is_finite()) {
        return grad;
    }
    let (psi, phi, l) = (&t.left, &t.right, t.lambda);
    let dot_h = |a: &[c64], b: &[c64]| a.iter().zip(b).map(|(p, q)| p.conj() * q).sum::<c64>();
    let dot_t = |a: &[c64], b: &[c64]| a.iter().zip(b).map(|(p, q)| p * q).sum::<c64>();
    let (x, a, s) = (&df.x, &df.a, df.norm2);
    let big_a = dot_h(psi, a);
    let big_a2 = dot_h(psi, &a.iter().map(|v| v.conj()).collect::<Vec<_>>());
    let big_b = dot_h(x, phi);
    let big_b2 = dot_t(x, phi);
    let i = c64::new(0.0, 1.0);
    let alpha = (c64::new(1.0, 0.0) - i * l / w) * 0.5;
    let beta = (c64::new(1.0, 0.0) + i * l / w) * 0.5;
    let g = (alpha * big_a * big_b + beta * big_a2 * big_b2) / s;
    // ψᴴ J₀(iω) and ψᵀ J₀(iω) as rows, for the J₀ dX terms.
    let j0 = |r: usize, c: usize| c64::new(k0[(r, c)], w * c0[(r, c)]);
    let p_h: Vec<c64> = (0..n)
        .map(|c| (0..n).map(|r| psi[r].conj() * j0(r, c)).sum())
        .collect();
    let p_t: Vec<c64> = (0..n)
        .map(|c| (0..n).map(|r| psi[r] * j0(r, c)).sum())
        .collect();
    let mut d_f = vec![c64::new(0.0, 0.0); n];
    for (col, slot) in grad.iter_mut().enumerate() {
        // dF (first harmonic of the force's derivative) and dX for this unknown.
        for (dd, dfd) in d_f.iter_mut().enumerate() {
            *dfd = if col < len {
                c64::new(d.du[(n + dd, col)], -d.du[(2 * n + dd, col)])
            } else {
                c64::new(d.domega[n + dd], -d.domega[2 * n + dd])
            };
        }
        // dX = e_k (a U1c entry) or -i e_k (a U1s entry); none for ω.
        let dx: Option<(usize, c64)> = if (n..2 * n).contains(&col) {
            Some((col - n, c64::new(1.0, 0.0)))
        } else if (2 * n..3 * n).contains(&col) {
            Some((col - 2 * n, c64::new(0.0, -1.0)))
        } else {
            None
        };
        // dA = ψᴴ da, dA' = conj(ψᵀ da), da = dF - J₀(iω) dX - i dω C₀ X.
        let mut da_h = dot_h(psi, &d_f);
        let mut da_t = dot_t(psi, &d_f);
        let (mut db, mut db2, mut ds) = (c64::new(0.0, 0.0), c64::new(0.0, 0.0), 0.0);
        if let Some((k, e)) = dx {
            da_h -= p_h[k] * e;
            da_t -= p_t[k] * e;
            db = e.conj() * phi[k];
            db2 = e * phi[k];
            ds = 2.0 * (x[k].conj() * e).re;
        }
        let (mut dalpha, mut dbeta) = (c64::new(0.0, 0.0), c64::new(0.0, 0.0));
        if col == len {
            let c0x: Vec<c64> = (0..n)
                .map(|r| (0..n).map(|c| x[c] * c0[(r, c)]).sum())
                .collect();
            da_h -= i * dot_h(psi, &c0x);
            da_t -= i * dot_t(psi, &c0x);
            dalpha = i * l / (2.0 * w * w);
            dbeta = -dalpha;
        }
        let da2 = da_t.conj();
        let dg = (alpha * (da_h * big_b + big_a * db)
            + beta * (da2 * big_b2 + big_a2 * db2)
            + dalpha * big_a * big_b
            + dbeta * big_a2 * big_b2)
            / s
            - g * ds / s;
        *slot = (-dg / t.slope).re;
    }
    grad
}

/// [`LinearizedEigen`] for a dense `M`, `C`, `K` whose every dof carries the force: the
/// eigenvalues of the state matrix `[[0, I], [-M⁻¹ K̃, -M⁻¹ C̃]]` (`K̃ = K + N_K`,
/// `C̃ = C + N_C`) by a dense decomposition at each call, the one nearest the last kept, and
/// its left vector from the decomposition of the transpose. For small systems (examples,
/// tests).
pub struct DenseEigen {
    m: Mat<f64>,
    c: Mat<f64>,
    k: Mat<f64>,
    last: Option<c64>,
}

impl DenseEigen {
    /// For the linear part of `stiffness`.
    pub fn new(stiffness: &MckStiffness) -> Self {
        Self {
            m: stiffness.mass().to_owned(),
            c: stiffness.damping().to_owned(),
            k: stiffness.stiffness().to_owned(),
            last: None,
        }
    }
}

impl LinearizedEigen for DenseEigen {
    fn track(&mut self, update: &LinearUpdate<'_>, guess: c64) -> Result<EigenTrack, HbmError> {
        let (n_k, n_c) = update.dense();
        let n = self.m.nrows();
        let from = self.last.unwrap_or(guess);
        let lost = |why: &str| HbmError::EigenvalueLost {
            from,
            why: why.into(),
        };
        let minv = self.m.partial_piv_lu().solve(Mat::<f64>::identity(n, n));
        let kt = Mat::from_fn(n, n, |i, j| self.k[(i, j)] + n_k[(i, j)]);
        let ct = Mat::from_fn(n, n, |i, j| self.c[(i, j)] + n_c[(i, j)]);
        let (mk, mc) = (&minv * &kt, &minv * &ct);
        let a = Mat::from_fn(2 * n, 2 * n, |i, j| match (i < n, j < n) {
            (true, true) => 0.0,
            (true, false) => f64::from(u8::from(i == j - n)),
            (false, true) => -mk[(i - n, j)],
            (false, false) => -mc[(i - n, j - n)],
        });
        let evd = a
            .eigen()
            .map_err(|_| lost("the dense eigensolver did not converge"))?;
        let s = evd.S();
        let k = (0..2 * n)
            .min_by(|&p, &q| (s[p] - from).norm().total_cmp(&(s[q] - from).norm()))
            .ok_or_else(|| lost("the system has no eigenvalue"))?;
        let l = s[k];
        let u = evd.U();
        let mut right: Vec<c64> = (0..n).map(|i| u[(i, k)]).collect();
        let norm = right.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
        for v in &mut right {
            *v /= norm;
        }
        // ψ from the left eigenvector w of the state matrix (an eigenvector of Aᵀ for the
        // same λ): with wᴴ = [aᴴ, bᴴ], ψᴴ = bᴴ M⁻¹ solves ψᴴ T(λ) = 0, so ψ = M⁻ᵀ b̄.
        let at = a.transpose().to_owned();
        let evd_t = at
            .eigen()
            .map_err(|_| lost("the dense eigensolver did not converge"))?;
        let st = evd_t.S();
        let kt = (0..2 * n)
            .min_by(|&p, &q| (st[p] - l).norm().total_cmp(&(st[q] - l).norm()))
            .ok_or_else(|| lost("the system has no eigenvalue"))?;
        let ut = evd_t.U();
        let b = Mat::<c64>::from_fn(n, 1, |i, _| ut[(n + i, kt)].conj());
        let minv_t = Mat::<c64>::from_fn(n, n, |i, j| c64::new(minv[(j, i)], 0.0));
        let psi = &minv_t * &b;
        let norm = (0..n).map(|i| psi[(i, 0)].norm_sqr()).sum::<f64>().sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return Err(lost("the left eigenvector vanished"));
        }
        let left: Vec<c64> = (0..n).map(|i| psi[(i, 0)] / norm).collect();
        let slope: c64 = (0..n)
            .map(|i| {
                left[i].conj()
                    * (0..n)
                        .map(|j| right[j] * (l * 2.0 * self.m[(i, j)] + ct[(i, j)]))
                        .sum::<c64>()
            })
            .sum();
        self.last = Some(l);
        Ok(EigenTrack {
            lambda: l,
            right,
            left,
            slope,
        })
    }
}

/// Eq. (48): the start `U0 = x0`, `U1c = 2 p Re ψ`, `U1s = -2 p Im ψ` (the unstable mode
/// `ψ` at amplitude `p` around the static solution `x0`, on the force's dofs), shifted in
/// time so that the first sine of `phase_dof` is zero.
pub fn initial_guess(
    layout: &HarmonicLayout,
    x0: &[f64],
    mode: &[c64],
    p: f64,
    phase_dof: usize,
) -> Result<Vec<f64>, HbmError> {
    let n = layout.n_dofs();
    for (what, got) in [("static solution", x0.len()), ("mode", mode.len())] {
        if got != n {
            return Err(HbmError::Dimension {
                what,
                expected: n,
                got,
            });
        }
    }
    let mut u = vec![0.0; layout.len()];
    u[..n].copy_from_slice(x0);
    if layout.n_harmonics() >= 1 {
        for d in 0..n {
            u[n + d] = 2.0 * p * mode[d].re;
            u[2 * n + d] = -2.0 * p * mode[d].im;
        }
        layout.align_phase(&mut u, phase_dof)?;
    }
    Ok(u)
}

/// A CHBM solve's outcome (the cycle is the last iterate even when not converged).
#[derive(Clone, Debug)]
pub struct ChbmResult {
    /// `[U~, ω]`.
    pub z: Vec<f64>,
    /// The followed eigenvalue at `z` (evaluated there after the solve).
    pub lambda: c64,
    /// Whether Levenberg–Marquardt met its residual tolerance.
    pub converged: bool,
    pub report: crate::lm::LmReport,
    /// Every residual evaluation, and the eigenvalue at each.
    pub history: Vec<crate::hb::RowNorms>,
    pub lambdas: Vec<c64>,
}

/// Solves CHBM, `[f1; phase; f2] = 0` with [`ReLambda`], from `u0`, `omega0` by
/// Levenberg–Marquardt. A solve that stops without meeting the tolerance is returned with
/// `converged = false` and its last iterate; any other failure is an error.
pub fn solve_chbm<L, F, T>(
    hb: &mut crate::hb::HarmonicBalance<L, F>,
    phase: crate::hb::PhaseCondition,
    constraint: ReLambda<T>,
    scales: crate::hb::RowScales,
    u0: &[f64],
    omega0: f64,
    options: &crate::lm::LmOptions,
) -> Result<(ChbmResult, ReLambda<T>), HbmError>
where
    L: crate::linear::DynamicStiffness,
    F: NonlinearForce,
    T: LinearizedEigen,
{
    hb.layout().check_len("initial guess", u0.len())?;
    if !(omega0.is_finite() && omega0 > 0.0) {
        return Err(HbmError::BadFrequency { omega: omega0 });
    }
    let mut z0 = u0.to_vec();
    z0.push(omega0);
    let mut problem = crate::hb::AutonomousProblem::constrained(hb, phase, constraint, scales)?;
    let (report, converged) = match crate::lm::solve(&mut problem, &z0, options) {
        Ok(r) => (r, true),
        Err(crate::lm::LmError::NotConverged { report }) => (*report, false),
        Err(e) => return Err(crate::hb::from_lm(e)),
    };
    // LM's last evaluation may be a rejected trial: evaluate the final point once more, so
    // that the constraint's eigenvalue is that of the returned cycle.
    let mut r = vec![0.0; crate::lm::LeastSquaresProblem::n_residuals(&problem)];
    crate::lm::LeastSquaresProblem::residual(&mut problem, &report.x, &mut r)?;
    let (constraint, history) = problem.into_parts();
    Ok((
        ChbmResult {
            z: report.x.clone(),
            lambda: constraint.lambda(),
            converged,
            report,
            history,
            lambdas: constraint.lambdas().to_vec(),
        },
        constraint,
    ))
}
