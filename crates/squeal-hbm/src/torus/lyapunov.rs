//! The stability of a torus by its Lyapunov exponents (issue 24, item 1).
//!
//! **Method.** A torus `x(t) = X(ω1 t, ω2 t)` of `ẋ = f(x)` found by harmonic balance is known
//! in closed form along its flow, so its linearization `v̇ = J(θ(t)) v`,
//! `J = ∂f/∂x (X(θ))`, `θ(t) = θ0 + ω t`, is a linear system with quasi-periodic
//! coefficients. Its Lyapunov exponents `λ_i = lim (1/T) log σ_i(Ψ(T))` (`Ψ` the fundamental
//! matrix, `σ_i` its singular values) decide the torus' stability: two of them are zero (the
//! directions along the torus, `∂X/∂θ1` and `∂X/∂θ2`, neither grow nor decay on an ergodic
//! torus), and the torus attracts its neighbourhood when all the others are negative, repels in
//! some direction when one is positive. The `k` largest come from `k` vectors integrated with
//! the flow and re-orthonormalized at every step (Gram–Schmidt, i.e. a QR factorization
//! `V = Q R`): `λ_i ≈ (1/T) Σ log R_ii` (Benettin, Galgani, Giorgilli & Strelcyn 1980,
//! Lyapunov characteristic exponents for smooth dynamical systems, Meccanica 15; the
//! "standard method" of Geist, Parlitz & Lauterborn 1990, Prog. Theor. Phys. 83).
//!
//! **Why not a quasi-periodic Floquet (Hill) analysis.** Hill's matrix on the 2-D basis
//! (Guillot, Lazarus, Thomas, Vergez & Cochelin 2020, JCP 416) gives the exponents modulo the
//! whole lattice `i(k1 ω1 + k2 ω2)`, which is dense on the imaginary axis: its reliable
//! exponents must be sorted out of a set that fills a band, and the sorting is the delicate
//! part. The exponents here need no sorting and no new basis, only the torus and the
//! Jacobian, and converge like `1/T` whatever the torus; the price is the integration time.
//!
//! **Integration.** Classical fourth-order Runge–Kutta with a fixed step `h = T1 / s`,
//! `T1 = 2π/ω1` the fast period, `s` at least [`LyapunovOptions::steps_per_period`] and enough
//! for `h ρ ≤ 2` (`ρ` the spectral radius of `J`, estimated by a power iteration when not
//! given; RK4's stability interval on the imaginary axis is `2√2`, on the negative real axis
//! 2.79). The first [`LyapunovOptions::transient`] fast periods only align the vectors with
//! the growing directions and are not counted.
//!
//! **Accuracy and verdict.** Finite-time exponents err by `O(1/T)`. Two measures of that error
//! come with the answer: the two exponents nearest zero (exactly zero in the limit) and the
//! difference between the estimate over the second half of the record and over all of it.
//! RK4's own error is not part of it: its bound on the fastest rate, `(h ρ)⁵ / (120 h)`
//! ([`LyapunovSpectrum::step_error`]), is far too pessimistic for the slow exponents of a
//! stiff system; it is checked by halving the step. The
//! torus is [`TorusStability::Attracting`] when the largest of the other exponents is below
//! minus that error, [`TorusStability::Unstable`] when above it, otherwise
//! [`TorusStability::Undecided`] (near a bifurcation of the torus, where an exponent crosses
//! zero, no finite run decides).

use crate::error::HbmError;

/// The linearized flow along a torus.
pub trait TorusVariational {
    /// Dimension of the state.
    fn dim(&self) -> usize;
    /// Makes [`Self::apply`] use the Jacobian at the torus' point of angles `theta`.
    fn set_angles(&mut self, theta: [f64; 2]) -> Result<(), HbmError>;
    /// `out = J v`.
    fn apply(&self, v: &[f64], out: &mut [f64]);
    /// `out = J V` for the columns `v[c*n..(c+1)*n]` (`n` = [`Self::dim`]); by default
    /// [`Self::apply`] column by column. An implementation may treat several columns at once
    /// but must give each column the bits [`Self::apply`] gives it (the exponents must not
    /// depend on how the products are grouped).
    fn apply_columns(&self, v: &[f64], out: &mut [f64]) {
        let n = self.dim();
        for (vc, oc) in v.chunks_exact(n).zip(out.chunks_exact_mut(n)) {
            self.apply(vc, oc);
        }
    }
}

/// Controls of [`lyapunov_exponents`].
#[derive(Clone, Debug, PartialEq)]
pub struct LyapunovOptions {
    /// How many of the largest exponents (at least 3: the two of the torus and one across).
    pub exponents: usize,
    /// Fast periods counted.
    pub periods: usize,
    /// Fast periods integrated before counting.
    pub transient: usize,
    /// Fewest RK4 steps per fast period.
    pub steps_per_period: usize,
    /// A bound on the spectral radius of `J` (1/time); `None`: estimated.
    pub max_rate: Option<f64>,
}

impl Default for LyapunovOptions {
    fn default() -> Self {
        Self {
            exponents: 4,
            periods: 400,
            transient: 40,
            steps_per_period: 32,
            max_rate: None,
        }
    }
}

/// The torus' stability from its exponents (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TorusStability {
    /// All exponents but the torus' two are below minus the estimate's error.
    Attracting,
    /// One exponent across the torus is above the estimate's error.
    Unstable,
    /// The largest exponent across the torus is within the estimate's error of zero.
    Undecided,
}

impl std::fmt::Display for TorusStability {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Attracting => "stable",
            Self::Unstable => "unstable",
            Self::Undecided => "not decided",
        })
    }
}

/// The largest Lyapunov exponents of a torus.
#[derive(Clone, Debug, PartialEq)]
pub struct LyapunovSpectrum {
    /// Largest first (1/time).
    pub exponents: Vec<f64>,
    /// The same over the second half of the record only.
    pub second_half: Vec<f64>,
    /// The counted time.
    pub time: f64,
    /// The RK4 step.
    pub step: f64,
    /// Steps taken, transient included.
    pub steps: usize,
    /// The spectral radius of `J` the step was chosen for (1/time).
    pub rate: f64,
}

impl LyapunovSpectrum {
    /// Indices of the two exponents nearest zero: the torus' own directions.
    pub fn tangent(&self) -> [usize; 2] {
        let mut idx: Vec<usize> = (0..self.exponents.len()).collect();
        idx.sort_by(|&a, &b| self.exponents[a].abs().total_cmp(&self.exponents[b].abs()));
        let (a, b) = (idx[0], idx[1]);
        [a.min(b), a.max(b)]
    }

    /// The largest exponent across the torus (all but [`Self::tangent`]).
    pub fn transverse(&self) -> f64 {
        let t = self.tangent();
        (0..self.exponents.len())
            .filter(|i| !t.contains(i))
            .map(|i| self.exponents[i])
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// RK4's error in the exponents: its local error on the fastest rate, `(h ρ)⁵ / 120`
    /// relative, per step `h`, with `ρ` the larger of the spectral radius and the largest
    /// exponent's size.
    pub fn step_error(&self) -> f64 {
        let fastest = self.exponents.iter().fold(self.rate, |a, l| a.max(l.abs()));
        let hr = self.step * fastest;
        hr.powi(5) / (120.0 * self.step)
    }

    /// The error of the finite-time estimate: the larger of the tangent exponents' distance
    /// from zero and the change between the second half's estimate and the whole record's.
    /// RK4's own error is not in it ([`Self::step_error`] bounds it for the fastest rate,
    /// far too pessimistically for the slow exponents of a stiff system; check it by halving
    /// [`LyapunovOptions::steps_per_period`]).
    pub fn uncertainty(&self) -> f64 {
        let t = self.tangent();
        let drift = self
            .exponents
            .iter()
            .zip(&self.second_half)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        self.exponents[t[0]]
            .abs()
            .max(self.exponents[t[1]].abs())
            .max(drift)
    }

    /// The verdict (module docs).
    pub fn stability(&self) -> TorusStability {
        let (l, e) = (self.transverse(), self.uncertainty());
        if l < -e {
            TorusStability::Attracting
        } else if l > e {
            TorusStability::Unstable
        } else {
            TorusStability::Undecided
        }
    }
}

/// The spectral radius of `J` at the current angles: `(|J^m v| / |v|)^(1/m)` for `m` products,
/// which tends to it from any start with a component along the dominant eigenvectors.
pub(super) fn spectral_radius<S: TorusVariational>(sys: &S) -> f64 {
    let n = sys.dim();
    // A fixed start with every component nonzero (results do not depend on any seed).
    let mut v: Vec<f64> = (0..n)
        .map(|i| 1.0 + 0.5 * ((i * 7919) % 13) as f64)
        .collect();
    normalize(&mut v);
    let mut w = vec![0.0; n];
    let m = 60;
    let mut log_sum = 0.0;
    for _ in 0..m {
        sys.apply(&v, &mut w);
        let g = normalize(&mut w);
        if g == 0.0 {
            return 0.0;
        }
        log_sum += g.ln();
        std::mem::swap(&mut v, &mut w);
    }
    (log_sum / m as f64).exp()
}

/// Scales `v` to unit length; its old length.
pub(super) fn normalize(v: &mut [f64]) -> f64 {
    let g = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if g > 0.0 {
        v.iter_mut().for_each(|x| *x /= g);
    }
    g
}

/// Modified Gram–Schmidt on the columns `v[c*n..(c+1)*n]`: `log R_cc` into `logs`.
fn orthonormalize(v: &mut [f64], n: usize, logs: &mut [f64]) {
    let k = logs.len();
    for c in 0..k {
        for p in 0..c {
            let (head, tail) = v.split_at_mut(c * n);
            let q = &head[p * n..(p + 1) * n];
            let col = &mut tail[..n];
            let d: f64 = q.iter().zip(col.iter()).map(|(a, b)| a * b).sum();
            col.iter_mut().zip(q).for_each(|(x, qi)| *x -= d * qi);
        }
        logs[c] = normalize(&mut v[c * n..(c + 1) * n]).ln();
    }
}

/// `out = J v` for the columns of `v` (each of length `n`, the state's dimension).
pub(super) fn apply_all<S: TorusVariational>(sys: &S, v: &[f64], out: &mut [f64], n: usize) {
    debug_assert_eq!(n, sys.dim());
    sys.apply_columns(v, out);
}

/// The `opts.exponents` largest Lyapunov exponents of the torus of frequencies `omega` whose
/// linearized flow is `sys` (module docs), from the angles `θ = 0`.
pub fn lyapunov_exponents<S: TorusVariational>(
    sys: &mut S,
    omega: [f64; 2],
    opts: &LyapunovOptions,
) -> Result<LyapunovSpectrum, HbmError> {
    let n = sys.dim();
    let k = opts.exponents;
    if k < 3 || k > n {
        return Err(HbmError::BadOption(
            "Lyapunov exponents: at least 3, and no more than the state's dimension",
        ));
    }
    if opts.periods < 2 || opts.steps_per_period == 0 {
        return Err(HbmError::BadOption(
            "Lyapunov exponents: at least 2 periods and one step per period",
        ));
    }
    if !(omega[0].is_finite() && omega[0] > 0.0 && omega[1].is_finite()) {
        return Err(HbmError::BadOption(
            "Lyapunov exponents: the frequencies must be finite, the first positive",
        ));
    }
    sys.set_angles([0.0, 0.0])?;
    let rho = match opts.max_rate {
        Some(r) => r,
        None => spectral_radius(sys),
    };
    let period = std::f64::consts::TAU / omega[0];
    let per = opts
        .steps_per_period
        .max((period * rho / 2.0).ceil() as usize);
    let h = period / per as f64;
    // Start vectors: unit vectors spread over the state (a fixed, deterministic choice).
    let mut v = vec![0.0; n * k];
    for c in 0..k {
        for i in 0..n {
            v[c * n + i] = if (i + c) % k == 0 {
                1.0
            } else {
                0.1 / (1 + i) as f64
            };
        }
    }
    let mut logs = vec![0.0; k];
    orthonormalize(&mut v, n, &mut logs);
    let (mut k1, mut k2, mut k3, mut k4) = (
        vec![0.0; n * k],
        vec![0.0; n * k],
        vec![0.0; n * k],
        vec![0.0; n * k],
    );
    let mut tmp = vec![0.0; n * k];
    let (mut sum, mut sum_half) = (vec![0.0; k], vec![0.0; k]);
    let (start, total) = (opts.transient * per, (opts.transient + opts.periods) * per);
    let half = start + opts.periods / 2 * per;
    let theta = |s: usize, frac: f64| {
        let t = (s as f64 + frac) * h;
        [omega[0] * t, omega[1] * t]
    };
    for s in 0..total {
        // The angles at the step's start are set: θ = 0 before the first step, the last
        // step's end `theta(s - 1, 1.0)` after (the same bits as `theta(s, 0.0)`: integer
        // plus 1.0 is exact).
        apply_all(sys, &v, &mut k1, n);
        sys.set_angles(theta(s, 0.5))?;
        axpy(&v, 0.5 * h, &k1, &mut tmp);
        apply_all(sys, &tmp, &mut k2, n);
        axpy(&v, 0.5 * h, &k2, &mut tmp);
        apply_all(sys, &tmp, &mut k3, n);
        sys.set_angles(theta(s, 1.0))?;
        axpy(&v, h, &k3, &mut tmp);
        apply_all(sys, &tmp, &mut k4, n);
        for i in 0..n * k {
            v[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        orthonormalize(&mut v, n, &mut logs);
        if logs.iter().any(|l| !l.is_finite()) {
            return Err(HbmError::BadOption(
                "Lyapunov exponents: the tangent vectors overflowed or collapsed (step too large?)",
            ));
        }
        if s >= start {
            sum.iter_mut().zip(&logs).for_each(|(a, l)| *a += l);
        }
        if s >= half {
            sum_half.iter_mut().zip(&logs).for_each(|(a, l)| *a += l);
        }
    }
    let time = (total - start) as f64 * h;
    let time_half = (total - half) as f64 * h;
    let mut exponents: Vec<f64> = sum.iter().map(|s| s / time).collect();
    let mut second_half: Vec<f64> = sum_half.iter().map(|s| s / time_half).collect();
    // Gram–Schmidt gives them largest first in the limit; sort the finite-time values alike.
    let mut order: Vec<usize> = (0..k).collect();
    order.sort_by(|&a, &b| exponents[b].total_cmp(&exponents[a]));
    exponents = order.iter().map(|&i| exponents[i]).collect();
    second_half = order.iter().map(|&i| second_half[i]).collect();
    Ok(LyapunovSpectrum {
        exponents,
        second_half,
        time,
        step: h,
        steps: total,
        rate: rho,
    })
}

/// `out = v + a x`.
pub(super) fn axpy(v: &[f64], a: f64, x: &[f64], out: &mut [f64]) {
    for ((o, vi), xi) in out.iter_mut().zip(v).zip(x) {
        *o = vi + a * xi;
    }
}
