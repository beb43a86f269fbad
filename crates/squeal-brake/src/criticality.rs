//! Criticality of the Hopf point: the first Lyapunov coefficient `l1` of the brake at μ0 and
//! the small-amplitude asymptote of the branch of limit cycles born there.
//!
//! In the frictionless modal coordinates the brake (eq 11) is `y' = f(y, μ)` with
//! `y = [q; v]`, `f = [v; Φᵀ F_piston - D v - Ω² q - Φᵀ F_nl(Φ q, Φ v)]` (the contact springs
//! of `K_t0` moved into `Ω²` and out of the force, which changes nothing below: they are
//! linear). While every pair is closed the contact law is smooth, and at the Hopf point
//! `(y0, μ0)` the Jacobian `A = [[0, I], [-K̃, -C̃]]` (`K̃ = Ω² + ΔK`, `C̃ = D + ΔC` of
//! [`crate::linearized`]) has the eigenvalues `±iω0`. With the multilinear forms of the
//! nonlinear force, `B(a, b) = ∂²f[a, b]`, `C(a, b, c) = ∂³f[a, b, c]`, the cubic coefficient
//! of the Hopf normal form `ż = iω0 z + c1 z |z|²` is (Kuznetsov, *Elements of Applied
//! Bifurcation Theory*, 3rd ed., eq 5.39)
//!
//! `c1 = ½ ⟨p, C(q, q, q̄)⟩ - ⟨p, B(q, A⁻¹ B(q, q̄))⟩ + ½ ⟨p, B(q̄, (2iω0 - A)⁻¹ B(q, q))⟩`,
//!
//! with `A q = iω0 q`, `Aᵀ p = -iω0 p`, `⟨p, q⟩ = p̄ᵀ q = 1`, and `l1 = Re c1 / ω0`.
//!
//! **In the brake's terms.** With the quadratic eigenpair `T(iω0) x = 0`, `yᴴ T(iω0) = 0` of
//! [`crate::linearized`], `q = [x; iω0 x]` and `p = [(-iω0 + C̃ᵀ) y; y]`, and `⟨p, q⟩ =
//! yᴴ T'(iω0) x` (normalized to 1). `B` and `C` act on the velocity rows only, so the inverses
//! reduce to `A⁻¹ [0; r] = [-T(0)⁻¹ r; 0]` (with a vibration-only stiffness `K_vib` left out
//! of `T(0)`, as the harmonic balance's mean has it: [`crate::vibration_only`]) and `(2iω0 - A)⁻¹ [0; r] = [u; 2iω0 u]` with
//! `u = T(2iω0)⁻¹ r`, solved with the linearized brake's factorization. Each pair's force
//! `F_n g + F_t h` depends on `s = (δ, δ', v)`, linear in the state, so
//! `B(a, b) = -Φᵀ Σ_p (g_p ∂²F_n + h_p ∂²F_t)[s_a, s_b]` and likewise `C` with third
//! derivatives; those of the element are taken by central differences of its analytic first
//! derivatives (exact up to round-off for the cubic penalty law, whose stiffness is quadratic
//! in δ).
//!
//! **The asymptote.** With `σ' + iω' = dλ/dμ` at μ0, the cycle near μ0 has
//! `|z|² = -σ' (μ - μ0) / Re c1`, it exists for `μ - μ0` of the sign of `-σ' Re c1` —
//! above μ0 (supercritical, `l1 < 0` for `σ' > 0`) or below (subcritical, `l1 > 0`) — with
//! `y ≈ y0 + 2 Re(z q e^{iωt})` and `ω ≈ ω0 + (ω' - σ' Im c1 / Re c1)(μ - μ0)`.

use crate::contact::{Kinematics, Response};
use crate::continuation::{EigenContinuationOptions, seed};
use crate::equilibrium::{Equilibrium, NewtonOptions, static_equilibrium};
use crate::error::BrakeError;
use crate::linearized::{Coupling, LinearizedBrake};
use crate::model::{Brake, ContactPair, dot_sparse};
use crate::spectrum::{Reference, spectrum};
use crate::sweep::PROJECT_ABOVE;
use faer::c64;

/// Which way the branch of limit cycles leaves the Hopf point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Criticality {
    /// `l1 < 0`: a stable cycle grows from zero on the side where the equilibrium is unstable.
    Supercritical,
    /// `l1 > 0`: an unstable cycle exists on the side where the equilibrium is stable; squeal
    /// can start there after a large enough disturbance.
    Subcritical,
    /// `l1 = 0` (or not a number): the cubic normal form does not decide. A contact law
    /// without a cubic term whose contact stays closed (a linear law, `k_nl = 0`) makes the
    /// forces of eq (11) linear near the equilibrium, so `c1 = 0`; the cycles' side is then
    /// set by higher orders than this analysis computes.
    Degenerate,
}

/// What a degenerate Hopf point ([`Criticality::Degenerate`]) means and what to add, for
/// messages.
pub const DEGENERATE_HINT: &str = "l1 = 0: the normal form is degenerate and says nothing about the limit cycles (a linear contact law, k_nl = 0, gives this); add a cubic contact stiffness (k_cubic_per_area > 0, or a compression curve that stiffens with closure) to get a branch of limit cycles";

impl std::fmt::Display for Criticality {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Criticality::Supercritical => "supercritical",
            Criticality::Subcritical => "subcritical",
            Criticality::Degenerate => "degenerate",
        })
    }
}

/// The Hopf normal form of the brake at μ0.
#[derive(Clone, Debug)]
pub struct NormalForm {
    /// The Hopf point's friction coefficient.
    pub mu0: f64,
    /// `ω0` (rad/s).
    pub omega0: f64,
    /// `c1` of the normal form (s⁻¹ per unit `|z|²`).
    pub c1: c64,
    /// The first Lyapunov coefficient `Re c1 / ω0`.
    pub l1: f64,
    /// `dλ/dμ` of the critical eigenvalue at μ0 (s⁻¹).
    pub dlambda_dmu: c64,
    /// The equilibrium at μ0.
    pub equilibrium: Equilibrium,
    /// `x` of `q = [x; iω0 x]` (modal coordinates), normalized with `yᴴ T'(iω0) x = 1`.
    pub mode: Vec<c64>,
}

impl NormalForm {
    /// Super- or subcritical (from the sign of `l1` and of `σ'`: the side of μ0 where the
    /// cycle exists against the side where the equilibrium is unstable); degenerate when
    /// `l1` is zero or not a number.
    pub fn criticality(&self) -> Criticality {
        if self.l1 < 0.0 {
            Criticality::Supercritical
        } else if self.l1 > 0.0 {
            Criticality::Subcritical
        } else {
            Criticality::Degenerate
        }
    }

    /// `|z|²` of the cycle at `mu` by the normal form, `None` on the side where there is none.
    pub fn radius_squared(&self, mu: f64) -> Option<f64> {
        let r2 = -self.dlambda_dmu.re * (mu - self.mu0) / self.c1.re;
        (r2 > 0.0 && r2.is_finite()).then_some(r2)
    }

    /// The cycle's angular frequency at `mu` by the normal form.
    pub fn omega_at(&self, mu: f64) -> f64 {
        let shift = self.dlambda_dmu.im - self.dlambda_dmu.re * self.c1.im / self.c1.re;
        self.omega0 + shift * (mu - self.mu0)
    }

    /// The first harmonic of every modal coordinate of the cycle at `mu`, as complex amplitudes
    /// `X` (the motion is `Re(X e^{iωt})`): `2 z x` with `|z|` from [`Self::radius_squared`].
    pub fn first_harmonic(&self, mu: f64) -> Option<Vec<c64>> {
        let r = self.radius_squared(mu)?.sqrt();
        Some(self.mode.iter().map(|v| v * (2.0 * r)).collect())
    }
}

/// Second and third derivatives of an element's `(F_n, F_t)` in `s = (δ, δ', v)` at a state,
/// by central differences of its analytic first derivatives.
struct Derivatives {
    /// `[force][i][j]`: `∂²F/∂s_i∂s_j` for `F_n` (0) and `F_t` (1).
    second: [[[f64; 3]; 3]; 2],
    /// `[force][i][j][k]`.
    third: [[[[f64; 3]; 3]; 3]; 2],
}

fn gradient(r: &Response) -> [[f64; 3]; 2] {
    [r.normal_derivatives, r.tangential_derivatives]
}

impl Derivatives {
    fn of(pair: &ContactPair, mu: f64, k: &Kinematics, velocity_scale: f64) -> Self {
        let base = [k.penetration, k.penetration_rate, k.slip_velocity];
        let steps = [
            1e-3 * k.penetration.abs().max(1e-12),
            1e-3 * velocity_scale,
            1e-3 * velocity_scale,
        ];
        let at = |offsets: [f64; 3]| {
            let s = Kinematics {
                penetration: base[0] + offsets[0],
                penetration_rate: base[1] + offsets[1],
                slip_velocity: base[2] + offsets[2],
            };
            gradient(&pair.law.response(mu, &s))
        };
        let shift = |j: usize, t: f64| {
            let mut o = [0.0; 3];
            o[j] = t;
            o
        };
        // H(offset)[f][i][j] = ∂/∂s_j of ∂F_f/∂s_i at base + offset.
        let hessian = |offset: [f64; 3]| {
            let mut h = [[[0.0; 3]; 3]; 2];
            for j in 0..3 {
                let (mut a, mut b) = (offset, offset);
                a[j] += steps[j];
                b[j] -= steps[j];
                let (ga, gb) = (at(a), at(b));
                for f in 0..2 {
                    for i in 0..3 {
                        h[f][i][j] = (ga[f][i] - gb[f][i]) / (2.0 * steps[j]);
                    }
                }
            }
            h
        };
        let second = hessian([0.0; 3]);
        let mut third = [[[[0.0; 3]; 3]; 3]; 2];
        for kk in 0..3 {
            let (hp, hm) = (
                hessian(shift(kk, steps[kk])),
                hessian(shift(kk, -steps[kk])),
            );
            for f in 0..2 {
                for i in 0..3 {
                    for j in 0..3 {
                        third[f][i][j][kk] = (hp[f][i][j] - hm[f][i][j]) / (2.0 * steps[kk]);
                    }
                }
            }
        }
        Self { second, third }
    }
}

/// The state vectors the forms act on, as physical displacement and velocity.
struct State {
    x: Vec<c64>,
    v: Vec<c64>,
}

/// `s = (g·x, g·v, h·v)` of a pair for a (complex) state.
fn pair_state(p: &ContactPair, a: &State) -> [c64; 3] {
    let dot = |w: &[(usize, f64)], z: &[c64]| w.iter().map(|&(i, c)| z[i] * c).sum::<c64>();
    [
        dot(&p.normal, &a.x),
        dot(&p.normal, &a.v),
        dot(&p.tangent, &a.v),
    ]
}

/// The brake's forms `B`, `C` at the equilibrium, in modal coordinates.
struct Forms<'a> {
    brake: &'a Brake,
    phi: &'a faer::Mat<f64>,
    derivatives: Vec<Derivatives>,
}

impl Forms<'_> {
    /// A modal state `(q, v)` as physical displacement and velocity.
    fn physical(&self, q: &[c64], v: &[c64]) -> State {
        let n = q.len();
        let map = |z: &[c64]| -> Vec<c64> {
            (0..n)
                .map(|i| (0..n).map(|j| z[j] * self.phi[(i, j)]).sum())
                .collect()
        };
        State {
            x: map(q),
            v: map(v),
        }
    }

    /// `-Φᵀ Σ_p (g_p w_n,p + h_p w_t,p)` for per-pair weights.
    fn output(&self, weights: &[[c64; 2]]) -> Vec<c64> {
        let n = self.phi.nrows();
        let mut f = vec![c64::new(0.0, 0.0); n];
        for (p, w) in self.brake.pairs.iter().zip(weights) {
            for &(i, g) in &p.normal {
                f[i] += w[0] * g;
            }
            for &(i, h) in &p.tangent {
                f[i] += w[1] * h;
            }
        }
        (0..n)
            .map(|j| -(0..n).map(|i| f[i] * self.phi[(i, j)]).sum::<c64>())
            .collect()
    }

    /// `B(a, b)`: the velocity rows (the displacement rows are zero).
    fn b(&self, a: &State, b: &State) -> Vec<c64> {
        self.per_pair(|p, d| {
            let (sa, sb) = (pair_state(p, a), pair_state(p, b));
            let mut out = [c64::new(0.0, 0.0); 2];
            for (f, o) in out.iter_mut().enumerate() {
                for i in 0..3 {
                    for j in 0..3 {
                        *o += sa[i] * sb[j] * d.second[f][i][j];
                    }
                }
            }
            out
        })
    }

    /// `C(a, b, c)`: the velocity rows.
    fn c(&self, a: &State, b: &State, c: &State) -> Vec<c64> {
        self.per_pair(|p, d| {
            let (sa, sb, sc) = (pair_state(p, a), pair_state(p, b), pair_state(p, c));
            let mut out = [c64::new(0.0, 0.0); 2];
            for (f, o) in out.iter_mut().enumerate() {
                for i in 0..3 {
                    for j in 0..3 {
                        for k in 0..3 {
                            *o += sa[i] * sb[j] * sc[k] * d.third[f][i][j][k];
                        }
                    }
                }
            }
            out
        })
    }

    /// [`Self::output`] of the weights `weight(pair, its derivatives)`.
    fn per_pair(&self, weight: impl Fn(&ContactPair, &Derivatives) -> [c64; 2]) -> Vec<c64> {
        let w: Vec<[c64; 2]> = (self.brake.pairs.iter().zip(&self.derivatives))
            .map(|(p, d)| weight(p, d))
            .collect();
        self.output(&w)
    }
}

/// The Hopf normal form of `brake` at `mu0`, for the critical eigenvalue nearest `guess`
/// (`iω0` of the sweep's Hopf point). Fails when a pair is open at the equilibrium (the
/// contact law is not smooth there) or the eigenvalue cannot be polished. Above
/// [`PROJECT_ABOVE`] dofs the equilibrium's Newton steps are solved in the modal basis and the
/// critical eigenpair starts from a projection ([`crate::projected`]) instead of the dense
/// spectrum of the whole brake; both end on the same exact eigenpair of `T(λ)`
/// ([`normal_form_with`]).
pub fn normal_form(
    brake: &Brake,
    reference: &Reference,
    mu0: f64,
    guess: c64,
    newton: &NewtonOptions,
) -> Result<NormalForm, BrakeError> {
    let large = brake.size() > PROJECT_ABOVE;
    normal_form_with(brake, reference, mu0, guess, newton, large)
}

/// [`normal_form`], the equilibrium and critical eigenpair found as for a large brake
/// (`large`: modal Newton steps, a projection's eigenpair converged on the whole brake) or as
/// for a small one (dense Newton steps, the dense spectrum) whatever the size.
pub fn normal_form_with(
    brake: &Brake,
    reference: &Reference,
    mu0: f64,
    guess: c64,
    newton: &NewtonOptions,
    large: bool,
) -> Result<NormalForm, BrakeError> {
    let lin = LinearizedBrake::new(brake, reference)?;
    let eq = if large {
        // Newton steps in the modal basis from the frictionless equilibrium, as the
        // projected sweep's (a dense LU of a large brake per step is the cost otherwise).
        crate::projected::equilibrium(brake, reference, &lin, mu0, None, newton)?
    } else {
        static_equilibrium(brake, mu0, None, newton)?
    };
    if let Some(p) = eq.penetrations.iter().position(|d| *d <= 0.0) {
        return Err(BrakeError::OpenAtHopf { pair: p + 1 });
    }
    let c = lin.coupling(brake, &eq);
    let copts = EigenContinuationOptions::default();
    let pair = if large {
        // The critical eigenpair from a projection, converged on the whole brake (the dense
        // spectrum of a brake of thousands of dofs would cost minutes).
        crate::projected::nearest_pair(&lin, reference, &c, guess, &copts)?
            .ok_or(BrakeError::EigenNoConvergence)?
    } else {
        // The critical eigenpair from the dense spectrum, polished with its left vector.
        let sp = spectrum(brake, reference, &eq)?;
        let j = (0..sp.values.len())
            .min_by(|&a, &b| {
                (sp.values[a] - guess)
                    .norm()
                    .total_cmp(&(sp.values[b] - guess).norm())
            })
            .ok_or(BrakeError::EigenNoConvergence)?;
        let right: Vec<c64> = (0..sp.modes.nrows()).map(|r| sp.modes[(r, j)]).collect();
        seed(&lin, &c, sp.values[j], right, &copts)
    };
    let l = pair.lambda;
    let omega0 = l.im;
    // dλ/dμ along the equilibrium path.
    let (du0, du1) = lin.mu_rates(brake, &c)?;
    let (_, slope) = lin.rayleigh(&c, l, &pair.right, &pair.left);
    let dlambda =
        -lin.coupling_derivative(&c, &du0, du1.as_deref(), l, &pair.right, &pair.left) / slope;
    // Normalize yᴴ T'(λ) x = 1 (⟨p, q⟩ = 1): scale x.
    let x: Vec<c64> = pair.right.iter().map(|v| v / slope).collect();
    let y = &pair.left;
    let n = x.len();
    let derivatives = brake
        .pairs
        .iter()
        .map(|p| {
            let k = p.kinematics(&eq.x, None);
            // Velocities of the cycle are ω0 times its displacements: a scale for the steps.
            let scale = omega0 * k.penetration.abs().max(1e-12);
            Derivatives::of(p, mu0, &k, scale)
        })
        .collect();
    let forms = Forms {
        brake,
        phi: &reference.basis.phi,
        derivatives,
    };
    let conj = |z: &[c64]| z.iter().map(|v| v.conj()).collect::<Vec<_>>();
    let times = |z: &[c64], s: c64| z.iter().map(|v| v * s).collect::<Vec<_>>();
    let iw = c64::new(0.0, omega0);
    let q = forms.physical(&x, &times(&x, iw));
    let qb = forms.physical(&conj(&x), &times(&conj(&x), iw.conj()));
    let inner = |r: &[c64]| y.iter().zip(r).map(|(a, b)| a.conj() * b).sum::<c64>();
    // ⟨p, C(q, q, q̄)⟩.
    let term_c = inner(&forms.c(&q, &q, &qb));
    // A⁻¹ [0; B(q, q̄)] = [-T(0)⁻¹ B(q, q̄); 0].
    let r1 = forms.b(&q, &qb);
    // The mean's response: without a vibration-only stiffness, as the 0th harmonic.
    let u1 = match &brake.k_vibration {
        Some(kv) => crate::vibration_only::solve_static(
            &reference.basis.phi,
            kv,
            |b| solve(&lin, &c, c64::new(0.0, 0.0), b),
            &r1,
        ),
        None => solve(&lin, &c, c64::new(0.0, 0.0), &r1),
    };
    let s1 = forms.physical(
        &times(&u1, c64::new(-1.0, 0.0)),
        &vec![c64::new(0.0, 0.0); n],
    );
    let term_b1 = inner(&forms.b(&q, &s1));
    // (2iω0 - A)⁻¹ [0; B(q, q)] = [u; 2iω0 u], T(2iω0) u = B(q, q).
    let r2 = forms.b(&q, &q);
    let u2 = solve(&lin, &c, iw * 2.0, &r2);
    let s2 = forms.physical(&u2, &times(&u2, iw * 2.0));
    let term_b2 = inner(&forms.b(&qb, &s2));
    let c1 = term_c * 0.5 - term_b1 + term_b2 * 0.5;
    Ok(NormalForm {
        mu0,
        omega0,
        c1,
        l1: c1.re / omega0,
        dlambda_dmu: dlambda,
        equilibrium: eq,
        mode: x,
    })
}

/// `T(λ)⁻¹ b`.
fn solve(lin: &LinearizedBrake, c: &Coupling, l: c64, b: &[c64]) -> Vec<c64> {
    lin.factor(c, l).solve(lin, c, b)
}

/// The closure `δ_p` of a pair for a modal state's displacement `q` (physical `x = Φ q`,
/// complex): `g_p · Φ q`.
pub fn pair_closure(pair: &ContactPair, phi: &faer::Mat<f64>, q: &[c64]) -> c64 {
    let n = q.len();
    let x: Vec<c64> = (0..n)
        .map(|i| (0..n).map(|j| q[j] * phi[(i, j)]).sum())
        .collect();
    let re: Vec<f64> = x.iter().map(|v| v.re).collect();
    let im: Vec<f64> = x.iter().map(|v| v.im).collect();
    c64::new(dot_sparse(&pair.normal, &re), dot_sparse(&pair.normal, &im))
}
