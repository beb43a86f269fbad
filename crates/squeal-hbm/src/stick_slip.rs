//! Exact stick–slip friction in harmonic balance: the dynamic Lagrangian frequency–time method
//! (DLFT) of Nacivet, Pierre, Thouverez & Jézéquel, "A dynamic Lagrangian frequency–time method
//! for the vibration of dry-friction-damped systems", JSV 265 (2003) 201–219, in the
//! velocity-level form of Krack & Gross, *Harmonic Balance for Nonlinear Vibration Problems*,
//! Springer 2019 (NLvib's `HB_residual_friction1D`), extended here to a moving counter-face
//! (a belt, a disc), a normal load that varies over the cycle and a static coefficient above
//! the kinetic one.
//!
//! # Why DLFT, and why on velocities
//! A regularized law (`tanh(v / v_reg)`, `squeal_brake::contact::RegularizedCoulomb`) only
//! approaches Coulomb's law as `v_reg → 0`, and then its force changes over a velocity range
//! the truncated series cannot resolve: harmonic balance needs ever more harmonics and its
//! Jacobian ever stiffer. An event-resolving AFT (locate every stick–slip transition in time
//! and march the hysteresis) is exact too, but its transitions move with the unknowns and it
//! is sequential. DLFT writes the friction force as a Lagrange multiplier augmented by a
//! penalty on the constraint's violation: Coulomb's law is then imposed without any
//! regularization (the only error is harmonic balance's truncation, see Exactness), and every
//! sample is evaluated independently (the breakaway's location between samples borrows the
//! event-resolving idea locally, see Transitions). The
//! displacement-level DLFT of Nacivet et al. imposes "no relative displacement increment" in
//! stick; with a moving counter-face the relative displacement `x - V t` is not periodic, while
//! the relative velocity `γ = V + h·x'` is, so the constraint is imposed on `γ` (Krack & Gross,
//! section 3.4, note on the velocity level): periodic unknowns, no secular term.
//!
//! # Equations
//! The harmonic balance residual without the friction forces is eq. (26) of the CHBM paper,
//! `R_r(U~, ω) = Λ(ω) U~ + F~_nl(U~, ω) - F~_ext` (a [`HarmonicBalance`]: linear part plus
//! every pointwise force, e.g. the normal penalty of eq. 8). Each friction contact `c` adds the
//! force `φ_c(t) h_c` on the left-hand side (`h_c` a direction over the dofs; in the brake `+s`
//! on the disc point and `-s` on the pad point, `φ = F_t` of `squeal_brake::contact`):
//!
//! `R(U~, ω) = R_r(U~, ω) + Σ_c h_c ⊗ Φ~_c`,                                           (S1)
//!
//! with `Φ~_c` the Fourier coefficients (layout of eq. 25) of `φ_c(t)`. The slip velocity is
//! `γ(t) = V + h·x'(t)` (`V` the counter-face speed), whose coefficients are linear in `U~`:
//! `γ~_0 = V`, `γ~_kc = k ω h·U_ks`, `γ~_ks = -k ω h·U_kc`. With `w = h / |h|²` (so that
//! `w·h = 1`) the *predicted multiplier* is
//!
//! `a(t) = -w·r_r(t) + ε γ(t)`,                                                        (S2)
//!
//! `r_r(t)` the time samples of the truncated `R_r`: the force that would keep the contact
//! stuck, plus the penalty `ε γ`. DLFT projects it onto Coulomb's admissible set
//! `[-L(t), L(t)]`, `L = μ N(t)` with `N` the normal load (constant, or eq. 8's penalty of the
//! contact's penetration `δ = g·x + δ0`):
//!
//! `φ(t) = a(t)` (stick) if `|a| ≤ μ_s N`,  `φ(t) = μ N sign a(t)` (slip) otherwise.     (S3)
//!
//! **Exactness.** Project (S1) on `w` at a stick sample: `w·r = w·r_r + φ = ε γ`, so where the
//! time-domain residual vanishes, `γ = 0`: the contact moves with the counter-face, carrying
//! the force `φ = -w·r_r`, the multiplier of the constraint, within `|φ| ≤ μ_s N`. At a slip
//! sample `φ = μ N sign a` and `a = φ + ε γ`, so `sign(a)(|a| - μ N) = ε γ`: the slip velocity
//! has the sign of the force — the friction opposes the relative motion — for any `ε > 0`.
//! Coulomb's law itself is therefore not approximated (no regularization velocity); what
//! remains is harmonic balance's own error: with `H` harmonics only the Galerkin projection of
//! the residual vanishes, not every sample, and the truncated cycle carries the error of a
//! series whose force jumps at the breakaway: measured on the mass on a belt, the period
//! misses by 1.8 % at `H = 5`, 0.77 % at `H = 20` and 0.34 % at `H = 50` (ε = 300,
//! `tests/hbm/stick_slip_belt.rs`).
//!
//! **Static above kinetic: the relay.** With `μ_s > μ` Coulomb's law has memory: a stuck
//! contact stays stuck until its force exceeds `μ_s N`, a sliding one slides until its slip
//! velocity vanishes (`|a| <= μ N` in DLFT: at a slip sample `|a| - μ N = ε γ sign a`). (S3)
//! is applied as this relay, sample by sample in time order round the period (two sweeps:
//! the first settles the state the second starts from). The state is piecewise constant in
//! `U~` and enters the Jacobian as such.
//!
//! # Breakaway
//! Where the contact breaks away the force drops from `μ_s N` to `μ N`, and so does the
//! multiplier prediction `a` (stuck, `a` is the sticking force; sliding, `a = μ N + ε γ` with
//! `γ` starting from 0). The truncated `a(t)` is smooth, so at the cycle it *peaks* at the
//! breakaway: the test `|a| > μ_s N` meets its threshold tangentially, a slight change of `U~`
//! moves the first crossing by many samples or removes it, the residual jumps there, and
//! Levenberg–Marquardt stops at such a jump (measured on the belt before this indicator:
//! central differences exceeded the analytic Jacobian by up to 1e8 at every stall point for
//! `H = 10…50`, the stick run changing by up to 57 of 2048 samples across a 1e-11 step). The
//! breakaway is therefore tested on the sticking force without the contact's own inertia,
//!
//! `b(t) = a(t) - ε γ(t) + m_c h·x''(t)`,  `m_c = h·M h / |h|⁴`,                      (S4)
//!
//! equal to the multiplier wherever the contact truly sticks (`γ = 0`, `h·x'' = 0`), and
//! crossing `μ_s N` transversally: on the mass on a belt `b = k x`, which keeps rising through
//! the breakaway. Dropping `ε γ` keeps the stuck phase's small truncation ripple of `γ` out of
//! the test. Sticking again is tested on `a` itself (it crosses `μ N` transversally where `γ`
//! changes sign). `m_c` is [`FrictionContact::contact_mass`]; 0 gives back the plain test.
//!
//! **Convergence.** With (S4) Levenberg–Marquardt converges on the mass on a belt for every
//! `H` from 5 to 50 and every ε from 1e2 to 3e3 N·s/m (measured: `tests/hbm/stick_slip_belt.rs`);
//! at ε = 300 the period error falls monotonically from 1.8e-2 (H = 5) to 3.4e-3 (H = 50),
//! like `H^-0.88` between 20 and 50: the force jumps at breakaway, so about first order in
//! `1/H` is what the Galerkin truncation gives. On the 2-dof friction oscillator (normal load
//! varying with the motion) it converges at ε = 3e3 for H = 10…50 (period within 1.5e-6 of
//! an event-driven integration at H = 50, `squeal-chbm/tests/chbm/dlft_two_dof.rs`), but for
//! other ε or H = 5 it may still stop at a residual of 1e-7…1e-5 of the load: small jumps
//! remain where a transition's sample state flips (the relay is discontinuous by nature).
//!
//! # Jacobian
//! With `E` the discrete projection onto coefficients and `D` the synthesis (both of
//! [`crate::aft`]), and `G(d) = E diag(d_j) D` the `(2H+1)²` matrix of a sampled weight `d_j`:
//!
//! `∂Φ~/∂z = G(stick) (-w·∂R~_r/∂z + ε ∂γ~/∂z) + Σ_d g_d G(slip · sign a · μ N'(δ)) ∂U~_d/∂z`,
//!
//! `z = (U~, ω)`, `∂R~_r/∂z` the Jacobian of the pointwise harmonic balance (its rows of the dofs
//! of `w`), `N'` the normal load's tangent. The derivative is exact between changes of the
//! stick/slip pattern of the samples.
//!
//! # Transitions
//! Where the state changes between samples `j0` and `j1`, the crossing of `x = |a| - L` (`L`
//! the static limit at breakaway, the kinetic one where the contact sticks again) is located by
//! linear interpolation, `τ = x0 / (x0 - x1)`, and the sample whose cell `[j - 1/2, j + 1/2]`
//! holds it gets the force `θ φ_stick + (1 - θ) φ_slip`, `θ` its stuck share. The force jump at
//! breakaway (`(μ_s - μ) N`) then moves continuously with the crossing instead of by whole
//! samples, and the Jacobian gains `(φ_stick - φ_slip) ∂θ/∂z` with
//! `∂τ = (x0 ∂x1 - x1 ∂x0) / (x0 - x1)²`.
//!
//! # Samples
//! `φ` jumps where a contact starts to slip with `μ_s > μ`, and has kinks elsewhere, so its
//! coefficients decay like `1/k` and aliasing decays like `1/N` only: take `N` well above
//! `2H + 1` ([`default_stick_slip_samples`]: `16 (2H + 1)` rounded up to a power of two).

use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Mat, MatMut};

use crate::HbmError;
use crate::force::NonlinearForce;
use crate::hb::{
    HarmonicBalance, HbSolution, PhaseCondition, autonomous_solution, autonomous_start, from_lm,
};
use crate::layout::HarmonicLayout;
use crate::linear::DynamicStiffness;
use crate::lm::{self, LeastSquaresProblem, LmOptions};

mod projection;

pub use projection::ContactState;
use projection::{Projected, Transition, clamp_samples, project_samples};

/// The normal load `N` that bounds a contact's friction force (`|φ| ≤ μ N`).
#[derive(Clone, Debug, PartialEq)]
pub enum NormalLoad {
    /// A fixed load (N), e.g. a mass pressed on a belt.
    Constant(f64),
    /// Eq. (8)'s cubic penalty `N = k_l δ + k_nl δ³` of the penetration `δ = g·x + offset`
    /// (0 when `δ ≤ 0`: an open contact carries no friction).
    Penalty {
        /// `g` as `(dof, coefficient)`.
        normal: Vec<(usize, f64)>,
        /// `δ0` (m): the penetration at `x = 0` (minus the initial gap).
        offset: f64,
        /// `k_l` (N/m).
        k_linear: f64,
        /// `k_nl` (N/m³).
        k_cubic: f64,
    },
}

impl NormalLoad {
    /// `(N, dN/dδ)` at the penetration `d` (ignored by a constant load).
    fn at(&self, d: f64) -> (f64, f64) {
        match self {
            NormalLoad::Constant(n) => (*n, 0.0),
            NormalLoad::Penalty {
                k_linear, k_cubic, ..
            } => {
                if d > 0.0 {
                    (
                        k_linear * d + k_cubic * d.powi(3),
                        k_linear + 3.0 * k_cubic * d * d,
                    )
                } else {
                    (0.0, 0.0)
                }
            }
        }
    }

    fn dofs(&self) -> &[(usize, f64)] {
        match self {
            NormalLoad::Constant(_) => &[],
            NormalLoad::Penalty { normal, .. } => normal,
        }
    }
}

/// One dry-friction contact treated exactly by DLFT (module docs, eqs S1–S3).
#[derive(Clone, Debug, PartialEq)]
pub struct FrictionContact {
    /// `h` as `(dof, coefficient)`: the slip velocity is `γ = V + h·x'` and the friction force
    /// `φ h` stands on the left-hand side (internal force).
    pub direction: Vec<(usize, f64)>,
    /// `V` (m/s): the counter-face's speed along the sliding direction.
    pub sliding_speed: f64,
    /// The normal load.
    pub normal: NormalLoad,
    /// `μ`, the kinetic (sliding) coefficient.
    pub mu: f64,
    /// `μ_s / μ >= 1`, the static coefficient over the kinetic one (1: one coefficient).
    pub static_ratio: f64,
    /// `ε` (N·s/m), the dynamic Lagrangian penalty: any positive value gives the same
    /// converged answer; of the order of the contact's `m ω` converges fastest.
    pub epsilon: f64,
    /// `m_c = h·M h / |h|⁴` (kg), the mass the contact carries along its direction: the
    /// breakaway indicator `b = a + m_c h·x''` drops the contact's own inertia (module docs,
    /// Breakaway). 0 gives the plain memory rule on `a`, whose breakaway is degenerate.
    pub contact_mass: f64,
}

impl FrictionContact {
    fn check(&self, n_dofs: usize) -> Result<(), HbmError> {
        let bad_dof = self
            .direction
            .iter()
            .chain(self.normal.dofs())
            .any(|&(i, a)| i >= n_dofs || !a.is_finite());
        let norm2: f64 = self.direction.iter().map(|&(_, a)| a * a).sum();
        if bad_dof || norm2 <= 0.0 {
            return Err(HbmError::BadOption(
                "friction contact: direction must be nonzero, finite and on existing dofs",
            ));
        }
        let finite = [
            self.sliding_speed,
            self.mu,
            self.static_ratio,
            self.epsilon,
            self.contact_mass,
        ]
        .iter()
        .all(|v| v.is_finite());
        if !finite
            || self.mu < 0.0
            || self.static_ratio < 1.0
            || self.epsilon <= 0.0
            || self.contact_mass < 0.0
        {
            return Err(HbmError::BadOption(
                "friction contact: needs mu >= 0, static_ratio >= 1, epsilon > 0, contact_mass >= 0, finite speed",
            ));
        }
        Ok(())
    }
}

/// `16 (2H + 1)` rounded up to a power of two (module docs, Samples).
pub fn default_stick_slip_samples(n_harmonics: usize) -> usize {
    (16 * (2 * n_harmonics + 1)).next_power_of_two()
}

/// Cosines and sines of one scalar signal's harmonics at the samples: synthesis `D`,
/// projection `E` and the weighted products `E diag(d) D`, from tables of both built once.
struct ScalarBasis {
    h: usize,
    n: usize,
    /// `D[j, b]` (basis function `b`, layout block order 1, cos θ, sin θ, cos 2θ, ..., at
    /// sample `j`) at `j * (2H + 1) + b`.
    dt: Vec<f64>,
    /// `E[b, j]` at `j * (2H + 1) + b`.
    et: Vec<f64>,
}

impl ScalarBasis {
    fn new(h: usize, n: usize) -> Self {
        let nb = 2 * h + 1;
        let (mut dt, mut et) = (vec![0.0; n * nb], vec![0.0; n * nb]);
        for j in 0..n {
            dt[j * nb] = 1.0;
            for k in 1..=h {
                // k j reduced mod n keeps the argument small (exact samples of the same grid).
                let th = 2.0 * std::f64::consts::PI * ((k * j) % n) as f64 / n as f64;
                (dt[j * nb + 2 * k], dt[j * nb + 2 * k - 1]) = th.sin_cos();
            }
            for b in 0..nb {
                let s = if b == 0 { 1.0 } else { 2.0 } / n as f64;
                et[j * nb + b] = s * dt[j * nb + b];
            }
        }
        Self { h, n, dt, et }
    }

    /// Basis function `b` at sample `j`.
    fn d(&self, j: usize, b: usize) -> f64 {
        self.dt[j * (2 * self.h + 1) + b]
    }

    /// Projection weight `E[b, j]`.
    fn e(&self, b: usize, j: usize) -> f64 {
        self.et[j * (2 * self.h + 1) + b]
    }

    fn synthesize(&self, c: &[f64], out: &mut [f64]) {
        let nb = 2 * self.h + 1;
        for (j, o) in out.iter_mut().enumerate() {
            let row = &self.dt[j * nb..j * nb + c.len()];
            *o = c.iter().zip(row).map(|(c, d)| c * d).sum();
        }
    }

    fn project(&self, s: &[f64], out: &mut [f64]) {
        for (b, o) in out.iter_mut().enumerate() {
            *o = (0..self.n).map(|j| self.e(b, j) * s[j]).sum();
        }
    }

    /// `G = E diag(d) D`, `(2H+1)²`: every entry summed over the samples in order (the rows
    /// accumulated contiguously, then copied).
    fn weighted(&self, d: &[f64]) -> Mat<f64> {
        let nb = 2 * self.h + 1;
        let mut g = vec![0.0; nb * nb];
        for (j, &dj) in d.iter().enumerate() {
            if dj == 0.0 {
                continue;
            }
            let (dr, er) = (
                &self.dt[j * nb..(j + 1) * nb],
                &self.et[j * nb..(j + 1) * nb],
            );
            for (a, row) in g.chunks_exact_mut(nb).enumerate() {
                let ea = er[a] * dj;
                for (v, &db) in row.iter_mut().zip(dr) {
                    *v += ea * db;
                }
            }
        }
        Mat::from_fn(nb, nb, |a, b| g[a * nb + b])
    }
}

/// Harmonic balance with exact stick–slip contacts (module docs): a [`HarmonicBalance`] for
/// the linear part and the pointwise forces, plus [`FrictionContact`]s by DLFT.
pub struct StickSlipBalance<L, F> {
    hb: HarmonicBalance<L, F>,
    contacts: Vec<FrictionContact>,
    basis: ScalarBasis,
    rest: Vec<f64>,
    states: Vec<Vec<ContactState>>,
    predicted: Vec<Vec<f64>>,
    clamp: bool,
}

impl<L: DynamicStiffness, F: NonlinearForce> StickSlipBalance<L, F> {
    /// `hb` plus the friction `contacts`, with `n_samples` time samples per period for the
    /// friction forces (`None`: [`default_stick_slip_samples`]).
    pub fn new(
        hb: HarmonicBalance<L, F>,
        contacts: Vec<FrictionContact>,
        n_samples: Option<usize>,
    ) -> Result<Self, HbmError> {
        let layout = hb.layout();
        for c in &contacts {
            c.check(layout.n_dofs())?;
        }
        let h = layout.n_harmonics();
        let n = n_samples.unwrap_or_else(|| default_stick_slip_samples(h));
        if n < 2 * h + 1 {
            return Err(HbmError::TooFewSamples {
                n_samples: n,
                n_harmonics: h,
                min: 2 * h + 1,
            });
        }
        if n > crate::aft::MAX_SAMPLES {
            return Err(HbmError::TooManySamples {
                n_samples: n,
                per_sample: 1,
                limit: crate::aft::MAX_SAMPLES,
            });
        }
        Ok(Self {
            basis: ScalarBasis::new(h, n),
            rest: vec![0.0; layout.len()],
            states: vec![Vec::new(); contacts.len()],
            predicted: vec![Vec::new(); contacts.len()],
            hb,
            contacts,
            clamp: false,
        })
    }

    /// Project the contacts with one friction coefficient (`static_ratio` 1) by the plain
    /// clamp onto Coulomb's cone instead of the relay (module docs, "One coefficient: the
    /// clamp"); contacts with `μ_s > μ` keep the relay. Off by default.
    pub fn set_clamp(&mut self, on: bool) {
        self.clamp = on;
    }

    /// The layout of `U~`.
    pub fn layout(&self) -> HarmonicLayout {
        self.hb.layout()
    }

    /// The pointwise harmonic balance (linear part and pointwise forces).
    pub fn harmonic_balance(&mut self) -> &mut HarmonicBalance<L, F> {
        &mut self.hb
    }

    /// The friction contacts, mutable (e.g. `mu` along a branch).
    pub fn contacts_mut(&mut self) -> &mut [FrictionContact] {
        &mut self.contacts
    }

    /// Number of time samples of the friction forces.
    pub fn n_samples(&self) -> usize {
        self.basis.n
    }

    /// Stick/slip state of every sample of every contact at the last evaluation.
    pub fn states(&self) -> &[Vec<ContactState>] {
        &self.states
    }

    /// The predicted multiplier `a(t_j)` (S2) of every sample of every contact at the last
    /// evaluation of the residual (its projection gives the friction force; `|a| - μ N` changes
    /// sign where the contact sticks or breaks away, used to locate the transitions between
    /// samples, e.g. by a Floquet analysis of the cycle).
    pub fn predicted_multipliers(&self) -> &[Vec<f64>] {
        &self.predicted
    }

    /// Fraction of the period each contact sticks, at the last evaluation.
    pub fn stick_fractions(&self) -> Vec<f64> {
        self.states
            .iter()
            .map(|s| {
                let stuck = s.iter().filter(|&&x| x == ContactState::Stick).count();
                stuck as f64 / s.len().max(1) as f64
            })
            .collect()
    }

    /// Coefficients (one scalar signal, `2H + 1`) of `dof` in `v` (layout length).
    fn dof_coeffs(&self, v: &[f64], dof: usize) -> Vec<f64> {
        let layout = self.hb.layout();
        (0..layout.n_blocks())
            .map(|b| v[b * layout.n_dofs() + dof])
            .collect()
    }

    /// `γ~` of contact `c` (module docs).
    fn slip_velocity_coeffs(&self, c: &FrictionContact, u: &[f64], omega: f64) -> Vec<f64> {
        let layout = self.hb.layout();
        let n = layout.n_dofs();
        let mut g = vec![0.0; layout.n_blocks()];
        g[0] = c.sliding_speed;
        for k in 1..=layout.n_harmonics() {
            let kw = k as f64 * omega;
            for &(d, hd) in &c.direction {
                g[2 * k - 1] += kw * hd * u[2 * k * n + d];
                g[2 * k] -= kw * hd * u[(2 * k - 1) * n + d];
            }
        }
        g
    }

    /// The multiplier prediction (S2) at the samples and the projection (S3), with the normal
    /// loads; `self.rest` must hold `R_r`.
    #[allow(clippy::type_complexity)]
    fn predict(
        &self,
        c: &FrictionContact,
        u: &[f64],
        omega: f64,
    ) -> (Vec<f64>, Projected, Vec<(f64, f64)>) {
        let norm2: f64 = c.direction.iter().map(|&(_, a)| a * a).sum();
        let mut ac = self.slip_velocity_coeffs(c, u, omega);
        for v in ac.iter_mut() {
            *v *= c.epsilon;
        }
        for &(d, hd) in &c.direction {
            let r = self.dof_coeffs(&self.rest, d);
            for (v, rb) in ac.iter_mut().zip(&r) {
                *v -= hd / norm2 * rb;
            }
        }
        let nt = self.basis.n;
        let mut a = vec![0.0; nt];
        self.basis.synthesize(&ac, &mut a);
        let mut dc = vec![0.0; ac.len()];
        if let NormalLoad::Penalty { normal, offset, .. } = &c.normal {
            dc[0] = *offset;
            for &(d, gd) in normal {
                for (v, ub) in dc.iter_mut().zip(self.dof_coeffs(u, d)) {
                    *v += gd * ub;
                }
            }
        }
        let mut delta = vec![0.0; nt];
        self.basis.synthesize(&dc, &mut delta);
        let load: Vec<(f64, f64)> = delta.iter().map(|&d| c.normal.at(d)).collect();
        let mut bc = ac.clone();
        for (v, g) in bc.iter_mut().zip(self.slip_velocity_coeffs(c, u, omega)) {
            *v -= c.epsilon * g;
        }
        let layout = self.hb.layout();
        let n = layout.n_dofs();
        for k in 1..=layout.n_harmonics() {
            let kw2 = (k as f64 * omega).powi(2);
            for &(d, hd) in &c.direction {
                bc[2 * k - 1] -= c.contact_mass * kw2 * hd * u[(2 * k - 1) * n + d];
                bc[2 * k] -= c.contact_mass * kw2 * hd * u[2 * k * n + d];
            }
        }
        let mut b = vec![0.0; nt];
        self.basis.synthesize(&bc, &mut b);
        let p = if self.clamp && c.static_ratio == 1.0 {
            clamp_samples(&a, &load, c.mu)
        } else {
            project_samples(&a, &b, &load, c.mu, c.static_ratio)
        };
        (a, p, load)
    }

    fn prepare(&mut self, u: &[f64], omega: f64) -> Result<(), HbmError> {
        let mut rest = std::mem::take(&mut self.rest);
        let r = self.hb.residual(u, omega, &mut rest);
        self.rest = rest;
        r
    }

    /// The transition term of the Jacobian: `E_(:, jb) (φ_stick - φ_slip) ∂θ/∂z` with the
    /// stuck share `θ` moving with the crossing `τ = x0 / (x0 - x1)`, `∂θ = ±∂τ`.
    fn add_transition(
        &self,
        c: &FrictionContact,
        e: &Transition,
        [qa, qb]: [&Mat<f64>; 2],
        load: &[(f64, f64)],
        dphi: &mut Mat<f64>,
    ) {
        let q = if e.breakaway { qb } else { qa };
        let layout = self.hb.layout();
        let (n, nb, cols) = (layout.n_dofs(), layout.n_blocks(), q.ncols());
        let ls = e.coefficient;
        // ∂x_j/∂z = sign a_j ∂a_j/∂z - (L/N) N'_j ∂δ_j/∂z.
        let dg = |j: usize, sign: f64| -> Vec<f64> {
            let mut v: Vec<f64> = (0..cols)
                .map(|col| {
                    sign * (0..nb)
                        .map(|b| self.basis.d(j, b) * q[(b, col)])
                        .sum::<f64>()
                })
                .collect();
            for &(d, gd) in c.normal.dofs() {
                for b in 0..nb {
                    v[b * n + d] -= ls * load[j].1 * gd * self.basis.d(j, b);
                }
            }
            v
        };
        let (dg0, dg1) = (dg(e.j0, e.sign[0]), dg(e.j1, e.sign[1]));
        let [g0, g1] = e.x;
        let den = (g1 - g0) * (g1 - g0);
        for col in 0..cols {
            let dtau = (g0 * dg1[col] - g1 * dg0[col]) / den;
            if dtau == 0.0 {
                continue;
            }
            for a in 0..nb {
                dphi[(a, col)] += self.basis.e(a, e.blended) * e.jump * dtau;
            }
        }
    }

    /// (S1): `r = R_r(u, ω) + Σ_c h_c ⊗ Φ~_c`.
    pub fn residual(&mut self, u: &[f64], omega: f64, r: &mut [f64]) -> Result<(), HbmError> {
        let layout = self.hb.layout();
        layout.check_len("residual", r.len())?;
        self.prepare(u, omega)?;
        r.copy_from_slice(&self.rest);
        let n = layout.n_dofs();
        let mut phi = vec![0.0; layout.n_blocks()];
        for ci in 0..self.contacts.len() {
            let c = &self.contacts[ci];
            let (a, p, _) = self.predict(c, u, omega);
            self.basis.project(&p.force, &mut phi);
            for &(d, hd) in &c.direction {
                for (b, f) in phi.iter().enumerate() {
                    r[b * n + d] += hd * f;
                }
            }
            self.states[ci] = p.state;
            self.predicted[ci] = a;
        }
        if r.iter().any(|v| !v.is_finite()) {
            return Err(HbmError::NonFiniteForce { sample: 0 });
        }
        Ok(())
    }

    /// The Jacobian of (S1) (module docs): `jac_u` (square, layout length) and `jac_omega`,
    /// both overwritten.
    pub fn jacobian(
        &mut self,
        u: &[f64],
        omega: f64,
        mut jac_u: MatMut<'_, f64>,
        jac_omega: &mut [f64],
    ) -> Result<(), HbmError> {
        let layout = self.hb.layout();
        let (len, n, nb) = (layout.len(), layout.n_dofs(), layout.n_blocks());
        self.prepare(u, omega)?;
        self.hb.jacobian(u, omega, jac_u.rb_mut(), jac_omega)?;
        // Every contact's rows first (they read the pointwise Jacobian), then added.
        let mut adds: Vec<(usize, f64, Mat<f64>)> = Vec::new();
        for c in &self.contacts {
            let (_, p, load) = self.predict(c, u, omega);
            let norm2: f64 = c.direction.iter().map(|&(_, a)| a * a).sum();
            // q = -w·∂R_r/∂z + ε ∂γ~/∂z = ∂a~/∂z, (2H+1) x (len + 1).
            let mut q = Mat::<f64>::zeros(nb, len + 1);
            for &(d, hd) in &c.direction {
                let wd = hd / norm2;
                // Column by column (the matrices are column-major); each entry gets the same
                // operations in the same order as row by row.
                for col in 0..len {
                    let src = jac_u.rb().col(col);
                    let mut dst = q.col_mut(col);
                    for b in 0..nb {
                        dst[b] -= wd * src[b * n + d];
                    }
                }
                for b in 0..nb {
                    q[(b, len)] -= wd * jac_omega[b * n + d];
                }
                for k in 1..=layout.n_harmonics() {
                    let kw = k as f64 * omega;
                    let e = c.epsilon * hd;
                    q[(2 * k - 1, 2 * k * n + d)] += e * kw;
                    q[(2 * k, (2 * k - 1) * n + d)] -= e * kw;
                    q[(2 * k - 1, len)] += e * k as f64 * u[2 * k * n + d];
                    q[(2 * k, len)] -= e * k as f64 * u[(2 * k - 1) * n + d];
                }
            }
            // q_b = ∂b~/∂z: q plus the contact's inertia m_c h·x'' (module docs, Breakaway).
            let mut qb = q.clone();
            for k in 1..=layout.n_harmonics() {
                let (kf, kw2) = (k as f64, (k as f64 * omega).powi(2));
                for &(d, hd) in &c.direction {
                    let m = c.contact_mass * hd;
                    let (ic, is) = ((2 * k - 1) * n + d, 2 * k * n + d);
                    let e = c.epsilon * hd;
                    qb[(2 * k - 1, is)] -= e * k as f64 * omega;
                    qb[(2 * k, ic)] += e * k as f64 * omega;
                    qb[(2 * k - 1, len)] -= e * kf * u[is];
                    qb[(2 * k, len)] += e * kf * u[ic];
                    qb[(2 * k - 1, ic)] -= m * kw2;
                    qb[(2 * k, is)] -= m * kw2;
                    qb[(2 * k - 1, len)] -= 2.0 * m * kf * kf * omega * u[ic];
                    qb[(2 * k, len)] -= 2.0 * m * kf * kf * omega * u[is];
                }
            }
            let mut dphi = self.basis.weighted(&p.stick_weight) * &q;
            let normal = c.normal.dofs();
            if !normal.is_empty() && p.slip_slope.iter().any(|&s| s != 0.0) {
                let gs = self.basis.weighted(&p.slip_slope);
                for &(d, gd) in normal {
                    for a in 0..nb {
                        for b in 0..nb {
                            dphi[(a, b * n + d)] += gd * gs[(a, b)];
                        }
                    }
                }
            }
            for e in &p.transitions {
                self.add_transition(c, e, [&q, &qb], &load, &mut dphi);
            }
            for &(d, hd) in &c.direction {
                adds.push((d, hd, dphi.clone()));
            }
        }
        for (d, hd, dphi) in adds {
            for col in 0..len {
                let src = dphi.col(col);
                let mut dst = jac_u.rb_mut().col_mut(col);
                for b in 0..nb {
                    dst[b * n + d] += hd * src[b];
                }
            }
            for b in 0..nb {
                jac_omega[b * n + d] += hd * dphi[(b, len)];
            }
        }
        Ok(())
    }
}

/// Autonomous stick–slip harmonic balance as a square least-squares problem in
/// `z = [U~, ω]`: `[(S1) / force_scale; U1s[dof]]`.
pub struct StickSlipProblem<'a, L, F> {
    ssb: &'a mut StickSlipBalance<L, F>,
    phase_index: usize,
    force_scale: f64,
    jac_omega: Vec<f64>,
}

impl<'a, L: DynamicStiffness, F: NonlinearForce> StickSlipProblem<'a, L, F> {
    /// Wraps `ssb` with a phase condition; the residual rows are divided by `force_scale`.
    pub fn new(
        ssb: &'a mut StickSlipBalance<L, F>,
        phase: PhaseCondition,
        force_scale: f64,
    ) -> Result<Self, HbmError> {
        if !(force_scale.is_finite() && force_scale > 0.0) {
            return Err(HbmError::BadScale {
                what: "force scale",
                value: force_scale,
            });
        }
        if !ssb.hb.is_static_load() {
            return Err(HbmError::PeriodicForcingWithUnknownFrequency);
        }
        let layout = ssb.layout();
        Ok(Self {
            phase_index: phase.index(&layout)?,
            jac_omega: vec![0.0; layout.len()],
            ssb,
            force_scale,
        })
    }
}

impl<L: DynamicStiffness, F: NonlinearForce> LeastSquaresProblem for StickSlipProblem<'_, L, F> {
    type Error = HbmError;

    fn n_params(&self) -> usize {
        self.ssb.layout().len() + 1
    }

    fn n_residuals(&self) -> usize {
        self.ssb.layout().len() + 1
    }

    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), HbmError> {
        let len = self.ssb.layout().len();
        let (rows, last) = r.split_at_mut(len);
        match self.ssb.residual(&z[..len], z[len], rows) {
            Err(HbmError::NonFiniteForce { .. }) => {
                r.fill(f64::NAN);
                return Ok(());
            }
            other => other?,
        }
        for v in rows.iter_mut() {
            *v /= self.force_scale;
        }
        last[0] = z[self.phase_index];
        Ok(())
    }

    fn jacobian(&mut self, z: &[f64], mut jac: MatMut<'_, f64>) -> Result<(), HbmError> {
        let len = self.ssb.layout().len();
        self.ssb.jacobian(
            &z[..len],
            z[len],
            jac.rb_mut().submatrix_mut(0, 0, len, len),
            &mut self.jac_omega,
        )?;
        let inv = 1.0 / self.force_scale;
        for i in 0..len {
            jac[(i, len)] = self.jac_omega[i] * inv;
        }
        // Column by column: the matrix is column-major.
        for j in 0..len {
            for v in jac.rb_mut().col_mut(j).iter_mut().take(len) {
                *v *= inv;
            }
        }
        for j in 0..=len {
            jac[(len, j)] = 0.0;
        }
        jac[(len, self.phase_index)] = 1.0;
        Ok(())
    }
}

/// A limit cycle with stick–slip contacts: unknowns `U~` and `ω`, equations (S1) plus the
/// phase condition, from the guess `u0`, `omega0` (shifted in time to satisfy the phase
/// condition first). `force_scale` divides the residual rows (a force level of the problem).
pub fn solve_stick_slip<L: DynamicStiffness, F: NonlinearForce>(
    ssb: &mut StickSlipBalance<L, F>,
    phase: PhaseCondition,
    u0: &[f64],
    omega0: f64,
    force_scale: f64,
    options: &LmOptions,
) -> Result<HbSolution, HbmError> {
    let len = ssb.layout().len();
    let z0 = autonomous_start(&ssb.layout(), phase, u0, omega0)?;
    let mut problem = StickSlipProblem::new(ssb, phase, force_scale)?;
    let report = lm::solve(&mut problem, &z0, options).map_err(from_lm)?;
    Ok(autonomous_solution(report, len))
}
