//! What to change: the derivatives of the unstable eigenvalue at the Hopf point, and of μ0,
//! with respect to the brake's design parameters, from its left and right eigenvectors.
//!
//! **The eigenvalue's derivative.** The linearized brake of eqs (20)–(21) is the quadratic
//! eigenproblem `Q(λ) φ = 0`, `Q(λ) = λ² M + λ C + K_t(μ)`, with `K_t = K + ∂F_nl/∂x` at the
//! equilibrium of eq (14) and `C` the damping of eq (12) (plus `∂F_nl/∂x'` when a contact
//! element depends on the velocities). Let `ψ` be the left vector, `ψᴴ Q(λ) = 0`. For a
//! parameter `p`, differentiate `Q(λ(p); p) φ(p) = 0` and multiply by `ψᴴ` on the left: the
//! term `ψᴴ Q dφ/dp` vanishes, leaving `ψᴴ (∂Q/∂p + (dλ/dp) Q'(λ)) φ = 0`, so for a simple
//! eigenvalue (`ψᴴ Q'(λ) φ ≠ 0`)
//!
//! `dλ/dp = -ψᴴ (∂Q/∂p) φ / ψᴴ Q'(λ) φ`,  `Q'(λ) = 2 λ M + C`,
//! `∂Q/∂p = λ² ∂M/∂p + λ ∂C/∂p + dK_t/dp`.
//!
//! In the frictionless modal coordinates of [`crate::modal`] (`x = Φ q`) `Φᵀ Q Φ = T(λ)` of
//! [`crate::linearized`], so `φ = Φ x`, `ψ = Φ y` with the modal vectors `x`, `y` of a
//! continued [`Eigenpair`], and the denominator is `yᴴ T'(λ) x`.
//!
//! **Hopf point.** μ0 solves `Re λ(μ0; p) = τ` (τ the sweep's threshold, held fixed), so
//! `dμ0/dp = -(∂Re λ/∂p)/(∂Re λ/∂μ)`, and the frequency there moves by
//! `dω0/dp = ∂Im λ/∂p + (∂Im λ/∂μ) dμ0/dp`.
//!
//! **What depends on what.** Every parameter `p` is a relative change `s` (the value times
//! `1 + s`), so every derivative is `d/ds` at `s = 0` and "1 %" is `s = 0.01`:
//!
//! - a part's Young's modulus: its reduced stiffness block `K_P` scales (a Craig–Bampton basis
//!   does not change when the whole part's modulus does: its constraint modes `-K_ii⁻¹ K_ib`
//!   and fixed-interface mode shapes are invariant, its `K̂` is linear in E), `∂K/∂s = K_P`;
//! - a part's density: `∂M/∂s = M_P` (same argument);
//! - the contact stiffness of a pair: its element's forces scale (as `[contact]
//!   stiffness_scale` does, [`crate::contact::Scaled`]);
//! - the piston load: `F_piston` scales;
//! - a mode's damping ratio ζ_j: `D_jj = 2 ζ_j ω_j` scales;
//! - the friction coefficient μ (reported as `∂λ/∂μ`; μ0 is itself a friction value).
//!
//! The equilibrium's change is **included**: the piston load enters the linearization only
//! through it (`k_t = k_l + 3 k_nl δ²` at the closure δ), and so do much of the effects of the
//! part and contact stiffnesses; holding it would miss what a brake engineer changes the load
//! for. Eq (14) differentiated, `K_t dx/ds = -∂R/∂s` with `R = K x + F_nl(x, μ) - F_piston`,
//! in modal coordinates `T(0) dq/ds = -Φᵀ ∂R/∂s`; the closures then move by
//! `dδ_p/ds = g_pᵀ dx/ds`, and the elements' derivatives with them (their second derivatives
//! in δ are taken by central differences of the element's responses, exact up to round-off
//! for the quadratic stiffness of eq 8). With the contact terms of [`crate::contact`],
//! `Φᵀ (dK_t/ds) Φ = Σ_p (ΔF_n,δ v_p + ΔF_t,δ w_p) v_pᵀ` and `Φᵀ (dC_NL/ds) Φ` likewise
//! (`v_p = Φᵀ g_p`, `w_p = Φᵀ h_p`), so a pair contributes
//! `yᴴ(...)x = (ΔF_n,δ a_p + ΔF_t,δ b_p + λ(ΔF_n,δ' a_p + ΔF_t,δ' b_p)) (v_pᵀ x)
//! + λ (ΔF_n,v a_p + ΔF_t,v b_p)(w_pᵀ x)` with `a_p = v_pᵀ ȳ`, `b_p = w_pᵀ ȳ`. The closures'
//! part is linear in `dq`, so one adjoint solve `T(0)ᵀ α = Σ_p e_p v_p` (`e_p` the pair's
//! contribution per unit closure) gives it for every parameter as `αᵀ (-Φᵀ ∂R/∂s)`.
//!
//! **The damping moves with the modes.** `C = M Φ D Φᵀ M` of eq (12) is defined on the
//! frictionless modes of `(K_t0, M)` (the equilibrium at μ = 0), with `D_jj = 2 ζ_j ω_j`: a
//! change of `K`, `M`, the contact stiffness or the load changes `Φ`, `ω` and so `C`, with the
//! ratios ζ_j held (as the full computation, which forms the basis again, does). With
//! `dΦ = Φ A`, `Φᵀ M Φ = I` gives `A + Aᵀ = -dM̃` (`dM̃ = Φᵀ dM Φ`), the modes' equation
//! gives `A_kj = (dK̃0 - ω_j² dM̃)_kj / (ω_j² - ω_k²)` for `k ≠ j` (`dK̃0 = Φᵀ dK_t0 Φ`) and
//! `dω_j² = (dK̃0 - ω_j² dM̃)_jj`; then
//!
//! `Φᵀ dC Φ = dM̃ D + A D + dD + D Aᵀ + D dM̃`, entry `kj`:
//! `E_kj G_kj + dM̃_kj D_jj`, `E_kj = dK̃0_kj - ω_j² dM̃_kj`,
//!
//! with `G_kj = (D_jj - D_kk)/(ω_j² - ω_k²)` (`= 2ζ/(ω_j + ω_k)` for equal ratios, no
//! cancellation between the near-equal frequencies of a disc doublet) and `G_jj = ζ_j/ω_j`
//! (from `dD_jj = ζ_j dω_j²/ω_j`). Two modes of exactly one frequency with different ratios
//! make `C` depend on the basis chosen inside their eigenspace: their `G` is taken with the
//! mean ratio. `yᴴ Φᵀ dC Φ x = Σ_kj dK̃0_kj B_kj + dM̃_kj H_kj` with `B_kj = ȳ_k x_j G_kj`,
//! `H_kj = ȳ_k x_j (D_jj - ω_j² G_kj)`, evaluated on the physical blocks through
//! `Φ B Φᵀ` and `Φ H Φᵀ` (formed once).

use crate::contact::{Kinematics, Response};
use crate::continuation::{EigenContinuationOptions, Eigenpair, converge, seed};
use crate::damping::ModalDamping;
use crate::equilibrium::{Equilibrium, NewtonOptions, static_equilibrium};
use crate::error::BrakeError;
use crate::linearized::{Coupling, Factor, LinearizedBrake};
use crate::model::Brake;
use crate::spectrum::Reference;
use crate::sweep::Hopf;
use faer::{Mat, c64};
use std::ops::Range;

/// A design parameter, changed relatively (`value × (1 + s)`).
#[derive(Clone, Debug, PartialEq)]
pub enum Parameter {
    /// The friction coefficient μ.
    Friction,
    /// The piston (clamp) force.
    PistonLoad,
    /// The contact stiffness (every force of the element) of these pairs (0-based) together.
    ContactStiffness(Vec<usize>),
    /// The modal damping ratio ζ_j of these frictionless modes (0-based) together.
    ModalDamping(Vec<usize>),
    /// The Young's modulus of the part whose reduced dofs these are: its `K` block scales.
    Stiffness(Range<usize>),
    /// The density of the part whose reduced dofs these are: its `M` block scales.
    Density(Range<usize>),
}

/// The unstable eigenpair at the Hopf point: `Re λ = τ` at `mu` (polished by Newton's method).
#[derive(Clone, Debug)]
pub struct HopfState {
    /// μ0.
    pub mu: f64,
    /// The threshold τ (s⁻¹) the real part crosses.
    pub tau: f64,
    /// The equilibrium at μ0.
    pub equilibrium: Equilibrium,
    /// The eigenpair there, modal coordinates, right and left vectors.
    pub pair: Eigenpair,
    /// Newton steps taken.
    pub iterations: usize,
}

/// One parameter's effect (per unit relative change `s`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rate {
    /// `dλ/ds` at fixed μ (s⁻¹ and rad/s).
    pub dlambda: c64,
    /// `dμ0/ds` (None for the friction coefficient itself).
    pub dmu0: Option<f64>,
    /// `df0/ds` (Hz): the frequency at the moving Hopf point (at fixed μ for friction).
    pub dfrequency_hz: f64,
}

/// A pair's contact data at one state: its response and the modal projections of the
/// eigenvectors on its directions.
struct PairTerms {
    response: Response,
    penetration: f64,
    /// `v_pᵀ ȳ`, `w_pᵀ ȳ`, `v_pᵀ x`, `w_pᵀ x`.
    a: c64,
    b: c64,
    cx: c64,
    dx: c64,
}

/// The derivatives at one Hopf state, with what every parameter shares formed once.
pub struct Sensitivities<'a> {
    brake: &'a Brake,
    lr: &'a LinearizedBrake,
    state: &'a HopfState,
    /// `yᴴ T'(λ) x`.
    den: c64,
    /// `φ = Φ x`, `ψ = Φ y`.
    phi: Vec<c64>,
    psi: Vec<c64>,
    /// `Φ α` for the closures at μ0 and `Φ α0` for those at μ = 0 (the basis' equilibrium).
    alpha: Vec<c64>,
    alpha0: Vec<c64>,
    pairs: Vec<PairTerms>,
    /// Each pair's response at the reference equilibrium, its `∂F_n,δ/∂δ` there and
    /// `W_p = g_pᵀ (Φ B Φᵀ) g_p`.
    reference: Vec<(Response, f64, c64)>,
    /// `Φ B Φᵀ` and `Φ H Φᵀ` (module documentation), `n × n`.
    pb: Mat<c64>,
    ph: Mat<c64>,
    /// `dλ/dμ`.
    dlambda_dmu: c64,
    /// The reference equilibrium's displacements (μ = 0).
    x0: Vec<f64>,
}

fn dot_real(a: &[f64], b: &[c64]) -> c64 {
    a.iter().zip(b).map(|(p, q)| q * *p).sum()
}

/// `Σ_k v_k z_k` over a sparse physical vector.
fn sparse_dot(v: &[(usize, f64)], z: &[c64]) -> c64 {
    v.iter().map(|&(i, a)| z[i] * a).sum()
}

/// The element's response at closure `delta` (at rest, sliding at its surface speed).
fn response_at(brake: &Brake, p: usize, delta: f64, mu: f64) -> Response {
    let pair = &brake.pairs[p];
    pair.law.response(
        mu,
        &Kinematics {
            penetration: delta,
            penetration_rate: 0.0,
            slip_velocity: pair.surface_speed.unwrap_or(0.0),
        },
    )
}

/// `(r(+) - r(-)) / (2h)` of the six derivatives.
fn difference(plus: &Response, minus: &Response, h: f64) -> [f64; 6] {
    let d = |a: f64, b: f64| (a - b) / (2.0 * h);
    [
        d(plus.normal_derivatives[0], minus.normal_derivatives[0]),
        d(
            plus.tangential_derivatives[0],
            minus.tangential_derivatives[0],
        ),
        d(plus.normal_derivatives[1], minus.normal_derivatives[1]),
        d(
            plus.tangential_derivatives[1],
            minus.tangential_derivatives[1],
        ),
        d(plus.normal_derivatives[2], minus.normal_derivatives[2]),
        d(
            plus.tangential_derivatives[2],
            minus.tangential_derivatives[2],
        ),
    ]
}

/// The six derivatives of a response `[n_δ, t_δ, n_δ', t_δ', n_v, t_v]`.
fn derivatives(r: &Response) -> [f64; 6] {
    difference(r, &Response::default(), 0.5)
}

/// Central-difference step in the closure: small against the closure, exact for eq (8)'s
/// stiffness, quadratic in δ.
fn closure_step(delta: f64) -> f64 {
    1e-3 * delta.abs()
}

impl PairTerms {
    /// The pair's contribution to `yᴴ (∂T/∂s) x` for a change `d` of its six derivatives.
    fn kernel(&self, d: &[f64; 6], l: c64) -> c64 {
        let [n_d, t_d, n_r, t_r, n_v, t_v] = *d;
        (self.a * n_d + self.b * t_d + l * (self.a * n_r + self.b * t_r)) * self.cx
            + l * (self.a * n_v + self.b * t_v) * self.dx
    }
}

/// `T(0)⁻ᵀ r` mapped to physical coordinates (`Φ α`); `T(0)` is real, so its adjoint solve
/// is the transposed one.
fn adjoint_physical(lr: &LinearizedBrake, c: &Coupling, phi: &Mat<f64>, r: &[c64]) -> Vec<c64> {
    let f: Factor = lr.factor(c, c64::new(0.0, 0.0));
    let conj: Vec<c64> = r.iter().map(|v| v.conj()).collect();
    let a: Vec<c64> = f
        .solve_adjoint(lr, c, &conj)
        .iter()
        .map(|v| v.conj())
        .collect();
    physical(phi, &a)
}

/// `Φ q`.
fn physical(phi: &Mat<f64>, q: &[c64]) -> Vec<c64> {
    (0..phi.nrows())
        .map(|i| (0..phi.ncols()).map(|j| q[j] * phi[(i, j)]).sum())
        .collect()
}

impl<'a> Sensitivities<'a> {
    /// Forms the shared quantities at the Hopf state (`O(n³)` once, for `Φ B Φᵀ`).
    pub fn new(
        brake: &'a Brake,
        reference: &Reference,
        lr: &'a LinearizedBrake,
        state: &'a HopfState,
    ) -> Result<Self, BrakeError> {
        if brake.k_vibration.is_some() {
            return Err(BrakeError::VibrationOnly {
                analysis: "the sensitivity analysis",
            });
        }
        let d = lr
            .damping
            .diagonal()
            .ok_or(BrakeError::NeedsDiagonalDamping {
                analysis: "the sensitivity analysis",
            })?;
        let n = lr.size();
        let (x, y, l) = (&state.pair.right, &state.pair.left, state.pair.lambda);
        let c = lr.coupling(brake, &state.equilibrium);
        let (_, den) = lr.rayleigh(&c, l, x, y);
        let basis = &reference.basis;
        let phi = physical(&basis.phi, x);
        let psi = physical(&basis.phi, y);
        let (vg, vh) = lr.contact_columns();
        let col = |m: &[f64], p: usize| m[p * n..(p + 1) * n].to_vec();
        let yc: Vec<c64> = y.iter().map(|v| v.conj()).collect();
        let pairs: Vec<PairTerms> = (0..brake.pairs.len())
            .map(|p| PairTerms {
                response: c.responses[p],
                penetration: c.penetration[p],
                a: dot_real(&col(vg, p), &yc),
                b: dot_real(&col(vh, p), &yc),
                cx: dot_real(&col(vg, p), x),
                dx: dot_real(&col(vh, p), x),
            })
            .collect();
        // e_p: the contribution per unit closure of pair p; α = T(0)⁻ᵀ Σ e_p v_p.
        let mut r = vec![c64::new(0.0, 0.0); n];
        for (p, t) in pairs.iter().enumerate() {
            let e = closure_kernel(brake, p, t, state.mu, l);
            for (j, rj) in r.iter_mut().enumerate() {
                *rj += e * vg[p * n + j];
            }
        }
        let alpha = adjoint_physical(lr, &c, &basis.phi, &r);
        // The damping's part: B, H, then Φ B Φᵀ, Φ H Φᵀ.
        let w = &lr.omega;
        let zeta: Vec<f64> = (0..n).map(|j| d[j] / (2.0 * w[j])).collect();
        let g = |k: usize, j: usize| -> f64 {
            if k == j {
                zeta[j] / w[j]
            } else if zeta[j] == zeta[k] || w[j] == w[k] {
                (zeta[j] + zeta[k]) / (w[j] + w[k])
            } else {
                (d[j] - d[k]) / ((w[j] - w[k]) * (w[j] + w[k]))
            }
        };
        let b = Mat::<c64>::from_fn(n, n, |k, j| yc[k] * x[j] * g(k, j));
        let h = Mat::<c64>::from_fn(n, n, |k, j| yc[k] * x[j] * (d[j] - w[j] * w[j] * g(k, j)));
        let pc = Mat::<c64>::from_fn(n, n, |i, j| c64::new(basis.phi[(i, j)], 0.0));
        let pb = &pc * &b * pc.transpose();
        let ph = &pc * &h * pc.transpose();
        // The reference (μ = 0) closures and W_p.
        let c0 = lr.coupling(brake, &reference.equilibrium);
        let mut refs = Vec::with_capacity(brake.pairs.len());
        let mut r0 = vec![c64::new(0.0, 0.0); n];
        for (p, pair) in brake.pairs.iter().enumerate() {
            let delta = c0.penetration[p];
            let hstep = closure_step(delta);
            let kdd = if delta > 0.0 {
                let plus = response_at(brake, p, delta + hstep, 0.0);
                let minus = response_at(brake, p, delta - hstep, 0.0);
                difference(&plus, &minus, hstep)[0]
            } else {
                0.0
            };
            let wp: c64 = pair
                .normal
                .iter()
                .map(|&(i, gi)| {
                    pair.normal
                        .iter()
                        .map(|&(j, gj)| pb[(i, j)] * (gi * gj))
                        .sum::<c64>()
                })
                .sum();
            let e = l * wp * kdd;
            for (j, rj) in r0.iter_mut().enumerate() {
                *rj += e * vg[p * n + j];
            }
            refs.push((c0.responses[p], kdd, wp));
        }
        let alpha0 = adjoint_physical(lr, &c0, &basis.phi, &r0);
        let mut s = Self {
            brake,
            lr,
            state,
            den,
            phi,
            psi,
            alpha,
            alpha0,
            pairs,
            reference: refs,
            pb,
            ph,
            dlambda_dmu: c64::new(0.0, 0.0),
            x0: reference.equilibrium.x.clone(),
        };
        s.dlambda_dmu = s.numerator(&Parameter::Friction) / -s.den;
        if state.mu != 0.0 {
            s.dlambda_dmu /= state.mu;
        }
        Ok(s)
    }

    /// `dλ/dμ` at the Hopf point.
    pub fn dlambda_dmu(&self) -> c64 {
        self.dlambda_dmu
    }

    /// `|x| |y| / |yᴴ T'(λ) x|`: the eigenvalue's condition (large near a coalescence).
    pub fn condition(&self) -> f64 {
        let norm = |v: &[c64]| v.iter().map(|a| a.norm_sqr()).sum::<f64>().sqrt();
        norm(&self.state.pair.right) * norm(&self.state.pair.left) / self.den.norm()
    }

    /// The derivatives with respect to a relative change of `p`.
    pub fn rate(&self, p: &Parameter) -> Rate {
        let dl = self.numerator(p) / -self.den;
        let two_pi = std::f64::consts::TAU;
        if *p == Parameter::Friction {
            return Rate {
                dlambda: dl,
                dmu0: None,
                dfrequency_hz: dl.im / two_pi,
            };
        }
        let dmu0 = -dl.re / self.dlambda_dmu.re;
        Rate {
            dlambda: dl,
            dmu0: Some(dmu0),
            dfrequency_hz: (dl.im + self.dlambda_dmu.im * dmu0) / two_pi,
        }
    }

    /// `yᴴ (∂T/∂s) x` for a relative change of `p`.
    fn numerator(&self, p: &Parameter) -> c64 {
        let l = self.state.pair.lambda;
        let brake = self.brake;
        let mu = self.state.mu;
        let x_eq = &self.state.equilibrium.x;
        let x0 = &self.x0;
        let zero = c64::new(0.0, 0.0);
        // `Σ_ab m_ab u_a z_b` over a block, and `zᵀ m u` products.
        let block = |m: &Mat<f64>, r: &Range<usize>, left: &[c64], right: &[c64]| -> c64 {
            let mut s = zero;
            for a in r.clone() {
                for b in r.clone() {
                    s += left[a] * right[b] * m[(a, b)];
                }
            }
            s
        };
        let psic: Vec<c64> = self.psi.iter().map(|v| v.conj()).collect();
        let block_pb = |m: &Mat<f64>, r: &Range<usize>, pm: &Mat<c64>| -> c64 {
            let mut s = zero;
            for a in r.clone() {
                for b in r.clone() {
                    s += pm[(a, b)] * m[(a, b)];
                }
            }
            s
        };
        let matvec = |m: &Mat<f64>, r: &Range<usize>, z: &[f64]| -> Vec<(usize, f64)> {
            r.clone()
                .map(|a| (a, r.clone().map(|b| m[(a, b)] * z[b]).sum()))
                .collect()
        };
        match p {
            Parameter::Friction => {
                // Directly (fixed closures) and through the equilibrium: R_s = μ F_t,μ h.
                let eps = 1e-4 * mu.abs().max(1e-2);
                let mut s = zero;
                for (q, t) in self.pairs.iter().enumerate() {
                    let plus = response_at(brake, q, t.penetration, mu + eps);
                    let minus = response_at(brake, q, t.penetration, mu - eps);
                    let d = difference(&plus, &minus, eps).map(|v| v * mu);
                    s += t.kernel(&d, l);
                    s -= sparse_dot(&brake.pairs[q].tangent, &self.alpha)
                        * (mu * t.response.tangential_mu);
                }
                s
            }
            Parameter::PistonLoad => {
                let f: c64 = brake
                    .f_piston
                    .iter()
                    .zip(&self.alpha)
                    .map(|(fi, a)| a * *fi)
                    .sum();
                let f0: c64 = brake
                    .f_piston
                    .iter()
                    .zip(&self.alpha0)
                    .map(|(fi, a)| a * *fi)
                    .sum();
                f + f0
            }
            Parameter::ContactStiffness(list) => {
                let mut s = zero;
                for &q in list {
                    let t = &self.pairs[q];
                    let pair = &brake.pairs[q];
                    s += t.kernel(&derivatives(&t.response), l);
                    s -= sparse_dot(&pair.normal, &self.alpha) * t.response.normal
                        + sparse_dot(&pair.tangent, &self.alpha) * t.response.tangential;
                    let (r0, _, wp) = &self.reference[q];
                    s += l * wp * r0.normal_derivatives[0];
                    s -= sparse_dot(&pair.normal, &self.alpha0) * r0.normal
                        + sparse_dot(&pair.tangent, &self.alpha0) * r0.tangential;
                }
                s
            }
            Parameter::ModalDamping(modes) => {
                let (x, y) = (&self.state.pair.right, &self.state.pair.left);
                let d = self.lr.damping.diagonal().unwrap_or(&[]);
                modes.iter().map(|&j| l * y[j].conj() * x[j] * d[j]).sum()
            }
            Parameter::Stiffness(r) => {
                let k = &brake.k;
                let mut s = block(k, r, &psic, &self.phi);
                s -= matvec(k, r, x_eq)
                    .iter()
                    .map(|&(a, v)| self.alpha[a] * v)
                    .sum::<c64>();
                s += l * block_pb(k, r, &self.pb);
                s -= matvec(k, r, x0)
                    .iter()
                    .map(|&(a, v)| self.alpha0[a] * v)
                    .sum::<c64>();
                s
            }
            Parameter::Density(r) => {
                let m = &brake.m;
                l * l * block(m, r, &psic, &self.phi) + l * block_pb(m, r, &self.ph)
            }
        }
    }
}

/// `e_p`: pair `p`'s contribution to `yᴴ (∂T/∂δ_p) x` per unit closure.
fn closure_kernel(brake: &Brake, p: usize, t: &PairTerms, mu: f64, l: c64) -> c64 {
    if t.penetration <= 0.0 {
        return c64::new(0.0, 0.0);
    }
    let h = closure_step(t.penetration);
    let plus = response_at(brake, p, t.penetration + h, mu);
    let minus = response_at(brake, p, t.penetration - h, mu);
    t.kernel(&difference(&plus, &minus, h), l)
}

/// `dλ/dμ` of an eigenpair at coupling `c` (as the Hopf refinement takes it).
fn friction_slope(
    brake: &Brake,
    lr: &LinearizedBrake,
    c: &Coupling,
    p: &Eigenpair,
) -> Result<c64, BrakeError> {
    let (du0, du1) = lr.mu_rates(brake, c)?;
    let (_, den) = lr.rayleigh(c, p.lambda, &p.right, &p.left);
    let num = lr.coupling_derivative(c, &du0, du1.as_deref(), p.lambda, &p.right, &p.left);
    Ok(-num / den)
}

/// Most Newton steps of [`polish`].
const MAX_NEWTON: usize = 12;

/// Newton's method on `Re λ(μ) = τ` from `(mu, eq, pair)`, the eigenpair continued exactly
/// ([`crate::continuation`]) and the equilibrium solved again at each step; stops when the
/// step is below `4 ε μ`.
pub fn polish(
    brake: &Brake,
    lr: &LinearizedBrake,
    start: (f64, &Equilibrium, &Eigenpair),
    tau: f64,
    newton: &NewtonOptions,
    opts: &EigenContinuationOptions,
) -> Result<HopfState, BrakeError> {
    let (mut mu, eq, pair) = start;
    let mut eq = eq.clone();
    let mut pair = pair.clone();
    let lost = |what, mu| BrakeError::HopfNotFollowed { what, mu };
    for it in 0..=MAX_NEWTON {
        if eq.mu != mu {
            eq = static_equilibrium(brake, mu, Some(&eq.x), newton)?;
        }
        let c = lr.coupling(brake, &eq);
        pair = converge(lr, &c, &pair, opts)
            .ok_or(lost("the eigenpair did not converge", mu))?
            .0;
        let slope = friction_slope(brake, lr, &c, &pair)?.re;
        let step = (pair.lambda.re - tau) / slope;
        if !step.is_finite() {
            return Err(lost("dRe(lambda)/dmu is zero or not finite", mu));
        }
        if step.abs() <= 4.0 * f64::EPSILON * mu.abs() || it == MAX_NEWTON {
            if step.abs() > 1e-9 * mu.abs() {
                return Err(lost("Newton's method did not converge", mu));
            }
            return Ok(HopfState {
                mu,
                tau,
                equilibrium: eq,
                pair,
                iterations: it,
            });
        }
        mu -= step;
    }
    Err(lost("Newton's method did not converge", mu))
}

/// The sweep's Hopf point polished ([`polish`]) from the upper end of its bracket.
pub fn hopf_state(
    brake: &Brake,
    lr: &LinearizedBrake,
    hopf: &Hopf,
    tau: f64,
    newton: &NewtonOptions,
    opts: &EigenContinuationOptions,
) -> Result<HopfState, BrakeError> {
    let eq = &hopf.point.equilibrium;
    let c = lr.coupling(brake, eq);
    let sp = &hopf.point.spectrum;
    let pair = seed(lr, &c, sp.values[hopf.index], sp.modal(hopf.index), opts);
    polish(brake, lr, (eq.mu, eq, &pair), tau, newton, opts)
}

/// The modal damping ratios `ζ_j = D_jj / 2ω_j` of a reference (diagonal `D`).
pub fn damping_ratios(reference: &Reference) -> Result<Vec<f64>, BrakeError> {
    let d = reference
        .damping
        .diagonal()
        .ok_or(BrakeError::NeedsDiagonalDamping {
            analysis: "the sensitivity analysis",
        })?;
    Ok(d.iter()
        .zip(&reference.basis.omega)
        .map(|(d, w)| d / (2.0 * w))
        .collect())
}

/// The full computation the derivatives are checked against: the frictionless reference of
/// `brake` formed again with the ratios `zeta` (`D_jj = 2 ζ_j ω_j` on its own modes), the
/// eigenpair of `base` carried over (its physical vectors put on the new modes,
/// `q = Φᵀ M φ`) and continued to the equilibrium at `base.mu`, then Newton's method to the
/// new Hopf point. Returns `λ` at `base.mu` and the new Hopf state.
pub fn recompute(
    brake: &Brake,
    zeta: &[f64],
    base_reference: &Reference,
    base: &HopfState,
    newton: &NewtonOptions,
    opts: &EigenContinuationOptions,
) -> Result<(c64, HopfState), BrakeError> {
    let mut reference = crate::sweep::reference(brake, &Default::default(), newton)?;
    reference.damping = ModalDamping::Diagonal(
        zeta.iter()
            .zip(&reference.basis.omega)
            .map(|(z, w)| 2.0 * z * w)
            .collect(),
    );
    let lr = LinearizedBrake::new(brake, &reference)?;
    let old = &base_reference.basis.phi;
    let new = &reference.basis.phi;
    let mphi_t = (&brake.m * new).transpose().to_owned();
    let carry = |q: &[c64]| -> Vec<c64> {
        let v = physical(old, q);
        (0..new.ncols())
            .map(|j| (0..v.len()).map(|i| v[i] * mphi_t[(j, i)]).sum())
            .collect()
    };
    let start = Eigenpair {
        lambda: base.pair.lambda,
        right: carry(&base.pair.right),
        left: carry(&base.pair.left),
    };
    let eq = static_equilibrium(brake, base.mu, Some(&base.equilibrium.x), newton)?;
    let c = lr.coupling(brake, &eq);
    let pair = converge(&lr, &c, &start, opts)
        .ok_or(BrakeError::HopfNotFollowed {
            what: "the carried eigenpair did not converge",
            mu: base.mu,
        })?
        .0;
    let lambda = pair.lambda;
    let state = polish(brake, &lr, (base.mu, &eq, &pair), base.tau, newton, opts)?;
    Ok((lambda, state))
}
