//! The friction sweep on a projection of the linearized brake: the standard reduction of
//! commercial complex-eigenvalue analysis, with its truncation checked.
//!
//! In the frictionless modal coordinates of [`crate::modal`] the brake linearized at a state is
//! `T(λ) q = (λ² I + λ (D + ΔC) + Ω² + ΔK) q = 0` (eqs 20–21, [`crate::linearized`]), with
//! `ΔK = U₀ Vᵀ`, `ΔC = U₁ Vᵀ` acting through the contact directions `v_p = Φᵀ g_p`,
//! `w_p = Φᵀ h_p`. It is projected (Galerkin, `q = Q a`, `Qᵀ T(λ) Q a = 0`) on a basis `Q`
//! with orthonormal columns: the `m` lowest modes, those below a cut-off `f_c` above the
//! band, and the static correction of the dropped ones (`t`), the vectors
//! `Ω_t⁻² [v_p, w_p]_t` (the dropped modes' static response to the contact forces:
//! "residual flexibility", without which the local contact stiffness converges slowly, as the
//! frequency ratio squared), with the next terms of the dropped modes' dynamic response
//! `(Ω_t² + λ²)⁻¹ = Ω_t⁻² - λ² Ω_t⁻⁴ + …` ([`ProjectionOptions::correction_terms`]: `Ω_t⁻⁴ [v_p,
//! w_p]_t`, …), orthonormalized and turned to diagonalize `Qᵀ Ω² Q` (a small
//! symmetric eigenproblem, `Θ²`). The projected problem is then of the same form, with
//! frequencies `[Ω_m, Θ]`, damping `Qᵀ D Q` and coupling `(Qᵀ U)(Qᵀ V)ᵀ`, and is solved densely
//! through the scaled state matrix of [`crate::spectrum`] at `O(k³)` per friction value
//! (`k = m + 2P` per correction term at most).
//!
//! The correction vectors can be compressed ([`ProjectionOptions::compression`]): the dropped
//! modes' dynamic flexibility at the contact, `F ↦ (Ω_t² + λ²)⁻¹ [V, W]_t F`, is represented
//! on the span of its terms `Ω_t⁻²ᵏ [V, W]_t` weighted by `ω_top^{2(k-1)}` (their size at the
//! band's top); its left singular vectors of small singular value carry responses a
//! contact force excites only weakly, and dropping those below a fraction of the largest
//! keeps the flexibility to that fraction with fewer vectors (`k` enters the cost cubed). The
//! check below judges the compressed basis like any other.
//!
//! The equilibrium of eq (14) at each μ is not projected: it is the brake's own, as in the
//! other methods.
//!
//! The equilibria of a large brake are found by the Newton iteration of
//! [`crate::equilibrium`] with its steps solved in the modal basis: `Φᵀ K_t Φ = T(0) = Ω² +
//! U₀ Vᵀ`, so `K_t⁻¹ b = Φ T(0)⁻¹ Φᵀ b`, a diagonal plus rank-`P` solve ([`crate::linearized`])
//! and two products with `Φ`, `O(n² + n P²)` instead of the `O(n³)` of a dense LU. Each
//! starts from the linear extrapolation of the two equilibria before it (error `O(Δμ²)`: one
//! Newton iteration per point instead of two on the 1998-dof brake, each a few passes over
//! `n × n` matrices), from the last one when that fails. The Hopf point's regula falsi and
//! the normal form of a large brake ([`crate::criticality`]) take the same modal steps. On a
//! brake with as many contact pairs as a third of its dofs (an interface-reduced brake with
//! nodal contact) the rank-`P` solve costs more than a dense LU of `K_t`, and the steps are
//! dense (`dense_steps_cheaper`).
//!
//! The Hopf point of a projected sweep is refined by regula falsi on the two followed
//! eigenvalues, each carried from the last evaluation by Rayleigh iteration on the projected
//! state matrix's Hessenberg form ([`crate::projected_hopf`], [`crate::hessenberg_rqi`]):
//! a Hessenberg reduction and a few `O(k²)` solves per evaluation instead of a whole
//! eigen-decomposition with vectors.
//!
//! The truncation neglects the dynamics of the dropped modes beyond the terms kept (with one,
//! `T_tt(λ)⁻¹` against `Ω_t⁻²`, a relative `ω²/ω_t²`); it is small when they lie well above
//! the band, but how small depends on the contact. So the basis is chosen by convergence
//! (`choose`): starting at `f_c = first_cutoff · f_top` (`f_top` the top of the band) with one
//! correction term, each in-band eigenvalue of the projection at a few friction values of the
//! sweep is carried to the unprojected brake by the exact Rayleigh iteration of
//! [`crate::continuation`] (started from the projected eigenvector lifted to the modal
//! coordinates); the largest relative distance `|λ_k - λ| / |λ|` must be below
//! [`ProjectionOptions::tolerance`], else a correction term is added, then `f_c` grows by
//! [`ProjectionOptions::growth`], and the check is repeated (at worst up to every mode: the
//! projection is then the brake itself).
//! On a brake with many contact directions for its size (an interface-reduced brake with
//! nodal contact: 510 dofs, 360 pairs on the medium ventilated brake) each Rayleigh step
//! factors a rank-`P` update of about the brake's size, and the in-band eigenvalues are
//! checked instead against the unprojected brake's from one dense eigenvalue-only
//! decomposition per checked friction value (the nearest of them to each projected one),
//! whichever the flop counts say is cheaper (`dense_reference`); computed once, they serve
//! every trial.
//! What was kept and checked is reported in [`Projection`]. A basis of as many vectors as the
//! brake has modes (the kept modes and as many independent correction vectors as modes
//! dropped: a brake with more contact directions than dofs, such as an interface-reduced one
//! with nodal contact) spans them all; its projection is a change of coordinates with the
//! brake's own eigenvalues, and is not checked (0 values compared, deviation 0).
//!
//! A projection cannot hold an eigenvalue of the unprojected brake that is absent from it; one
//! would have to come from a mode above the cut-off pulled into the band by the contact, which
//! the growth of the cut-off until convergence makes ever less likely, and which the check does
//! not exclude.

use crate::continuation::{Eigenpair, converge};
use crate::damping::ModalDamping;
use crate::equilibrium::Equilibrium;
use crate::error::BrakeError;
use crate::linearized::{Coupling, LinearizedBrake};
use crate::model::Brake;
pub(crate) use crate::projected_equilibrium::equilibrium;
use crate::projected_equilibrium::{modal_newton, predicted};
use crate::spectrum::{Reference, Ritz, Spectrum, modal_eigenvalues, modal_spectrum};
use crate::sweep::{
    SweepOptions, SweepPoint, SweepProgress, SweepStats, SweepTimings, SweptPoints, crossed_in_band,
};
use crate::tracking::match_modes_blocked;
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par, Side, c64};
use rayon::prelude::*;
use std::sync::Arc;
use std::time::Instant;

/// Controls of the projected sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct ProjectionOptions {
    /// Largest relative distance `|λ_k - λ| / |λ|` allowed between an in-band eigenvalue of
    /// the projection and the unprojected brake's at the checked friction values.
    pub tolerance: f64,
    /// The first cut-off, as a multiple of the top of the band.
    pub first_cutoff: f64,
    /// Factor on the cut-off after a failed check.
    pub growth: f64,
    /// Friction values of the sweep the truncation is checked at (evenly spread over it, its
    /// ends included).
    pub checks: usize,
    /// Most terms of the dropped modes' response kept per contact direction: `Ω_t⁻² a`,
    /// `Ω_t⁻⁴ a`, ... (the static correction and the first terms of `(Ω_t² + λ²)⁻¹ a` in
    /// powers of `λ²`, module documentation). The first projection tried has one; a failed
    /// check adds the next before the cut-off grows.
    pub correction_terms: usize,
    /// Correction vectors kept: the left singular vectors of the `t × 2P·terms` matrix of
    /// the terms (term `k` scaled by `ω_top^{2(k-1)}`, its weight at the band's top) whose
    /// singular value is above this fraction of the largest; `0` keeps them all (only
    /// dependent ones dropped).
    pub compression: f64,
    /// Refine the Hopf point by Rayleigh iteration on the two followed eigenpairs
    /// ([`crate::projected_hopf`]); `false`: a whole decomposition at each evaluation (the
    /// former way, kept for comparison).
    pub rayleigh_refinement: bool,
}

impl Default for ProjectionOptions {
    fn default() -> Self {
        Self {
            // A relative 1e-5 of |λ| ~ 2.5e4 rad/s (4 kHz) is 0.25 rad/s, on frequencies that
            // approach each other at some 1e3-1e4 rad/s per unit μ before they coalesce: μ0
            // within about 1e-4 (measured: tests/pipeline/sweep_methods.rs in squeal-pipeline).
            tolerance: 1e-5,
            first_cutoff: 1.5,
            growth: 1.25,
            checks: 3,
            correction_terms: 2,
            compression: 0.0,
            rayleigh_refinement: true,
        }
    }
}

/// A projection tried: the modes kept and the largest relative eigenvalue distance found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trial {
    /// Frictionless modes kept.
    pub kept_modes: usize,
    /// Static-correction vectors added.
    pub residual_vectors: usize,
    /// The highest kept frictionless frequency (Hz).
    pub cutoff_hz: f64,
    /// Largest `|λ_k - λ| / |λ|` over the in-band eigenvalues at the checked friction values
    /// (infinite when one did not converge on the unprojected brake).
    pub deviation: f64,
}

/// The projection a sweep used, and how its truncation was checked.
#[derive(Clone, Debug, PartialEq)]
pub struct Projection {
    /// Frictionless modes kept (the lowest ones).
    pub kept_modes: usize,
    /// Correction vectors added (at most two per contact pair and correction term).
    pub residual_vectors: usize,
    /// Dofs of the brake (the modes there are).
    pub modes: usize,
    /// The highest kept frictionless frequency (Hz).
    pub cutoff_hz: f64,
    /// The top of the band the projection serves (Hz; infinite: no band, every mode kept).
    pub band_top_hz: f64,
    /// Friction values the truncation was checked at.
    pub checked_mus: Vec<f64>,
    /// In-band eigenvalues compared there, over all checked values.
    pub checked_values: usize,
    /// Largest `|λ_k - λ| / |λ|` of the kept projection.
    pub deviation: f64,
    /// [`ProjectionOptions::tolerance`].
    pub tolerance: f64,
    /// Every projection tried, the kept one last.
    pub trials: Vec<Trial>,
    /// The basis, its frequencies `[Ω_m, Θ]` and damping `Qᵀ D Q`.
    basis: Basis,
    /// The equilibria at `checked_mus`, in turn from the frictionless one (for
    /// [`crate::sweep::sweep_after`]).
    checked_equilibria: Vec<Equilibrium>,
}

/// A projection basis with what the projected problem needs of it.
#[derive(Clone, Debug, PartialEq)]
struct Basis {
    ritz: Arc<Ritz>,
    omega: Vec<f64>,
    damping: ModalDamping,
}

/// The top of the band (Hz): the lower of the valid band's top and the user band's.
fn band_top(opts: &SweepOptions) -> f64 {
    let b = &opts.band;
    b.user
        .map_or(b.valid_max_hz, |(_, hi)| hi.min(b.valid_max_hz))
}

/// Modes with `ω_j <= 2π f` (the basis is ascending), at least one.
fn modes_below(omega: &[f64], f: f64) -> usize {
    omega
        .partition_point(|&w| w <= std::f64::consts::TAU * f)
        .max(1)
}

/// Indices of `mus` the truncation is checked at: `checks` of them evenly spread, ends
/// included.
fn check_indices(len: usize, checks: usize) -> Vec<usize> {
    let k = checks.max(1).min(len);
    let mut out: Vec<usize> = (0..k)
        .map(|i| {
            if k == 1 {
                len - 1
            } else {
                i * (len - 1) / (k - 1)
            }
        })
        .collect();
    out.dedup();
    out
}

/// Chooses the modes to keep by convergence (module documentation).
pub(crate) fn choose(
    brake: &Brake,
    reference: &Reference,
    lr: &LinearizedBrake,
    mus: &[f64],
    opts: &SweepOptions,
    before: Option<&Projection>,
) -> Result<Projection, BrakeError> {
    let omega = &lr.omega;
    let n = omega.len();
    let top = band_top(opts);
    let hz = |m: usize| omega[m - 1] / std::f64::consts::TAU;
    let mut out = Projection {
        kept_modes: n,
        residual_vectors: 0,
        modes: n,
        cutoff_hz: hz(n),
        band_top_hz: top,
        checked_mus: Vec::new(),
        checked_values: 0,
        deviation: 0.0,
        tolerance: opts.projection.tolerance,
        trials: Vec::new(),
        basis: basis(lr, reference, n, 0, None)?,
        checked_equilibria: Vec::new(),
    };
    if !top.is_finite() {
        return Ok(out);
    }
    let mut couplings = Vec::new();
    for (i, k) in check_indices(mus.len(), opts.projection.checks)
        .into_iter()
        .enumerate()
    {
        // The same friction values as `before`'s checks so far: its equilibria, the same
        // bits (crate::sweep::sweep_after).
        let same = before.is_some_and(|b| {
            b.checked_equilibria.len() > i
                && out.checked_mus[..]
                    .iter()
                    .chain([&mus[k]])
                    .zip(&b.checked_mus)
                    .all(|(a, b)| a.to_bits() == b.to_bits())
        });
        let eq = match before.filter(|_| same) {
            Some(b) => b.checked_equilibria[i].clone(),
            None => {
                let from = out.checked_equilibria.last().map(|e| e.x.as_slice());
                equilibrium(brake, reference, lr, mus[k], from, &opts.newton)?
            }
        };
        couplings.push(lr.coupling(brake, &eq));
        out.checked_mus.push(mus[k]);
        out.checked_equilibria.push(eq);
    }
    // The unprojected eigenvalues when dense solves are cheaper, computed at the first check.
    let mut exact: Option<Option<Vec<Vec<c64>>>> = None;
    let mut cutoff = opts.projection.first_cutoff * top;
    let most = opts.projection.correction_terms;
    let compression = (opts.projection.compression > 0.0)
        .then_some((opts.projection.compression, std::f64::consts::TAU * top));
    let mut terms = most.min(1);
    loop {
        let m = modes_below(omega, cutoff).min(n);
        let b = basis(lr, reference, m, terms, compression)?;
        let s = b.ritz.residual.ncols();
        // A basis of as many orthonormal vectors as the brake has modes spans them all: the
        // projection is a change of coordinates, with the brake's own eigenvalues (the case of
        // a brake with more contact directions than dofs, e.g. an interface-reduced one), and
        // is not checked.
        let (deviation, count) = if m + s == n {
            (0.0, 0)
        } else {
            if exact.is_none() {
                exact = Some(dense_reference(lr, &couplings, opts)?);
            }
            let dense = exact.as_ref().and_then(|e| e.as_deref());
            deviation(lr, &b, &couplings, dense, opts)?
        };
        out.trials.push(Trial {
            kept_modes: m,
            residual_vectors: s,
            cutoff_hz: hz(m),
            deviation,
        });
        (out.kept_modes, out.residual_vectors, out.cutoff_hz) = (m, s, hz(m));
        (out.deviation, out.checked_values, out.basis) = (deviation, count, b);
        if deviation <= opts.projection.tolerance || m == n || m + s == n {
            return Ok(out);
        }
        // One more correction term first (4P more vectors at most: cheaper than the modes a
        // higher cut-off takes in, on the brakes measured); then a higher cut-off, until it
        // takes in at least one more mode.
        if terms < most {
            terms += 1;
            continue;
        }
        while modes_below(omega, cutoff) <= m {
            cutoff *= opts.projection.growth.max(1.01);
        }
    }
}

/// Vectors whose norm falls below this fraction of their own in the orthogonalization are
/// dependent on the others and dropped.
const DEPENDENT: f64 = 1e-8;

/// The basis of the `m` lowest modes and the static correction of the others (module
/// documentation); `compression = Some((fraction, ω_top))`: the correction's dominant
/// directions ([`ProjectionOptions::compression`]).
fn basis(
    lr: &LinearizedBrake,
    reference: &Reference,
    m: usize,
    terms: usize,
    compression: Option<(f64, f64)>,
) -> Result<Basis, BrakeError> {
    let t = lr.size() - m;
    let cols = match compression {
        None => orthonormal_corrections(lr, m, terms),
        Some((fraction, w_top)) => dominant_corrections(lr, m, terms, fraction, w_top)?,
    };
    let s = cols.len();
    let r_hat = Mat::from_fn(t, s, |i, k| cols[k][i]);
    // Qᵀ Ω² Q on the residual block, scaled to unit norm for the eigensolver (as in
    // crate::modal), diagonalized: R = R̂ Z, Θ² its eigenvalues.
    let k_rr = Mat::from_fn(s, s, |a, b| {
        (0..t)
            .map(|i| r_hat[(i, a)] * lr.omega[m + i] * lr.omega[m + i] * r_hat[(i, b)])
            .sum::<f64>()
    });
    let scale = k_rr.norm_max().max(f64::MIN_POSITIVE);
    let sym = Mat::from_fn(s, s, |a, b| 0.5 * (k_rr[(a, b)] + k_rr[(b, a)]) / scale);
    let evd = sym
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| BrakeError::EigenNoConvergence)?;
    let residual = &r_hat * evd.U();
    let mut omega: Vec<f64> = lr.omega[..m].to_vec();
    omega.extend((0..s).map(|k| (evd.S()[k] * scale).max(0.0).sqrt()));
    let ritz = Arc::new(Ritz { kept: m, residual });
    let damping = project_damping(&reference.damping, &ritz);
    Ok(Basis {
        ritz,
        omega,
        damping,
    })
}

/// Term `k` (from 1) of the dropped modes' response to contact direction `src` of pair `p`:
/// `Ω_t⁻²ᵏ a_t` on the modes from `m` on.
fn correction_term(lr: &LinearizedBrake, src: &[f64], p: usize, m: usize, k: usize) -> Vec<f64> {
    let n = lr.size();
    (0..n - m)
        .map(|i| src[p * n + m + i] / (lr.omega[m + i] * lr.omega[m + i]).powi(k as i32))
        .collect()
}

/// Every correction vector, orthonormalized (modified Gram-Schmidt, twice; dependent ones
/// dropped).
fn orthonormal_corrections(lr: &LinearizedBrake, m: usize, terms: usize) -> Vec<Vec<f64>> {
    let (vg, vh) = lr.contact_columns();
    // Ω_t⁻²ᵏ [v_p, w_p]_t, k = 1..terms, orthonormalized (modified Gram-Schmidt, twice).
    let mut cols: Vec<Vec<f64>> = Vec::new();
    for (k, p) in (1..=terms).flat_map(|k| (0..lr.pairs()).map(move |p| (k, p))) {
        for src in [vg, vh] {
            let mut a = correction_term(lr, src, p, m, k);
            let before = a.iter().map(|x| x * x).sum::<f64>().sqrt();
            for _ in 0..2 {
                for c in &cols {
                    let d: f64 = c.iter().zip(&a).map(|(x, y)| x * y).sum();
                    a.iter_mut().zip(c).for_each(|(y, x)| *y -= d * x);
                }
            }
            let after = a.iter().map(|x| x * x).sum::<f64>().sqrt();
            if after > DEPENDENT * before && after > 0.0 {
                a.iter_mut().for_each(|y| *y /= after);
                cols.push(a);
            }
        }
    }
    cols
}

/// The dominant directions of the correction vectors: the left singular vectors of
/// `[ω_top^{2(k-1)} Ω_t⁻²ᵏ [v_p, w_p]_t]` (all pairs and terms) whose singular value exceeds
/// `fraction` of the largest. Term `k` enters the response at the band's top `ω_top` with the
/// weight `ω_top^{2(k-1)}` (`(Ω_t² + λ²)⁻¹` expanded in `λ²`), so the scaled terms compare
/// as the parts of one dynamic flexibility there.
fn dominant_corrections(
    lr: &LinearizedBrake,
    m: usize,
    terms: usize,
    fraction: f64,
    w_top: f64,
) -> Result<Vec<Vec<f64>>, BrakeError> {
    let (vg, vh) = lr.contact_columns();
    let mut raw: Vec<Vec<f64>> = Vec::new();
    for k in 1..=terms {
        let weight = w_top.powi(2 * (k as i32 - 1));
        for p in 0..lr.pairs() {
            for src in [vg, vh] {
                let mut a = correction_term(lr, src, p, m, k);
                a.iter_mut().for_each(|y| *y *= weight);
                raw.push(a);
            }
        }
    }
    let t = lr.size() - m;
    if raw.is_empty() || t == 0 {
        return Ok(Vec::new());
    }
    let a = Mat::from_fn(t, raw.len(), |i, j| raw[j][i]);
    let svd = a.thin_svd().map_err(|_| BrakeError::EigenNoConvergence)?;
    let s = svd.S().column_vector();
    let largest = (0..s.nrows()).map(|j| s[j]).fold(0.0, f64::max);
    let u = svd.U();
    Ok((0..s.nrows())
        .filter(|&j| s[j] > fraction * largest && s[j] > 0.0)
        .map(|j| (0..t).map(|i| u[(i, j)]).collect())
        .collect())
}

/// `Qᵀ D Q` (diagonal when nothing is added to the kept modes, or nothing is damped there).
fn project_damping(d: &ModalDamping, ritz: &Ritz) -> ModalDamping {
    let (m, r) = (ritz.kept, &ritz.residual);
    let s = r.ncols();
    let lifted = |k: usize| -> Vec<f64> {
        // Column k of Q in modal coordinates.
        let n = m + r.nrows();
        let mut q = vec![0.0; n];
        if k < m {
            q[k] = 1.0;
        } else {
            for i in 0..r.nrows() {
                q[m + i] = r[(i, k - m)];
            }
        }
        q
    };
    if s == 0 {
        return d.leading(m);
    }
    let n = m + r.nrows();
    let cols: Vec<Vec<f64>> = (0..m + s).map(lifted).collect();
    let mut dq = vec![0.0; n];
    let dcols: Vec<Vec<f64>> = cols
        .iter()
        .map(|c| {
            d.apply(c, &mut dq);
            dq.clone()
        })
        .collect();
    ModalDamping::Full(Mat::from_fn(m + s, m + s, |a, b| {
        cols[a].iter().zip(&dcols[b]).map(|(x, y)| x * y).sum()
    }))
}

/// The spectrum of the projection on `b` at the coupling `c`.
fn project(b: &Basis, c: &Coupling, n: usize) -> Result<Spectrum, BrakeError> {
    let (dk, dc) = projected_change(b, c, n);
    let mut sp = modal_spectrum(&b.omega, &b.damping, &dk, dc.as_ref(), c.mu)?;
    sp.ritz = Some(b.ritz.clone());
    Ok(sp)
}

/// The changes `Qᵀ ΔK Q` and `Qᵀ ΔC Q` of the projection on `b` at the coupling `c`.
fn projected_change(b: &Basis, c: &Coupling, n: usize) -> (Mat<f64>, Option<Mat<f64>>) {
    let (v, u0, u1) = c.columns();
    let r = c.rank();
    let k = b.omega.len();
    // Qᵀ X of the n x r columns X = [X_m; X_t]: [X_m; Rᵀ X_t], by blocked products
    // (sequential: the bits do not depend on the thread count). A brake with as many
    // contact directions as dofs (nodal contact) has r ~ n: these products cost as much as a
    // sweep point's eigen-decomposition when summed entry by entry.
    let (m, res) = (b.ritz.kept, &b.ritz.residual);
    let on = |x: &[f64]| -> Mat<f64> {
        let x = faer::MatRef::from_column_major_slice(x, n, r);
        let mut out = Mat::<f64>::zeros(k, r);
        out.as_mut()
            .submatrix_mut(0, 0, m, r)
            .copy_from(x.submatrix(0, 0, m, r));
        matmul(
            out.as_mut().submatrix_mut(m, 0, k - m, r),
            Accum::Replace,
            res.transpose(),
            x.submatrix(m, 0, n - m, r),
            1.0,
            Par::Seq,
        );
        out
    };
    let vq = on(v);
    let product = |uq: Mat<f64>| {
        let mut out = Mat::<f64>::zeros(k, k);
        matmul(
            out.as_mut(),
            Accum::Replace,
            uq.as_ref(),
            vq.transpose(),
            1.0,
            Par::Seq,
        );
        out
    };
    let dk = product(on(u0));
    let dc = u1.map(|u1| product(on(u1)));
    (dk, dc)
}

/// The unprojected brake's eigenvalues at each of `couplings` by a dense eigenvalue-only
/// decomposition of its state matrix, when that costs less than carrying each in-band
/// eigenvalue to it by Rayleigh iteration (module documentation); else `None`.
fn dense_reference(
    lr: &LinearizedBrake,
    couplings: &[Coupling],
    opts: &SweepOptions,
) -> Result<Option<Vec<Vec<c64>>>, BrakeError> {
    let n = lr.size() as f64;
    let tau = std::f64::consts::TAU;
    let in_band = lr
        .omega
        .iter()
        .filter(|w| opts.band.contains(**w / tau))
        .count() as f64;
    let r = couplings.iter().map(Coupling::rank).max().unwrap_or(0) as f64;
    // Flops: the Hessenberg reduction and QR iteration of the 2n x 2n state matrix, about
    // 13 (2n)^3; a Rayleigh iteration, about three steps each factoring the complex
    // diagonal-plus-rank-r T(lambda) and its adjoint, 4 x 2 (n r^2 + r^3) per step.
    let dense = 104.0 * n.powi(3);
    let rayleigh = in_band * 24.0 * (n * r * r + r.powi(3));
    if dense >= rayleigh {
        return Ok(None);
    }
    couplings
        .par_iter()
        .map(|c| {
            let (dk, dc) = lr.dense_change(c);
            modal_eigenvalues(&lr.omega, &lr.damping, &dk, dc.as_ref())
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

/// The largest relative distance between the in-band eigenvalues of the projection on `b`
/// and the unprojected brake's at `couplings` (the nearest of `exact`, its eigenvalues there,
/// when given; else each carried to it by Rayleigh iteration), and how many were compared.
fn deviation(
    lr: &LinearizedBrake,
    b: &Basis,
    couplings: &[Coupling],
    exact: Option<&[Vec<c64>]>,
    opts: &SweepOptions,
) -> Result<(f64, usize), BrakeError> {
    let n = lr.size();
    let mut worst = 0.0f64;
    let mut count = 0;
    for (i, c) in couplings.iter().enumerate() {
        let sp = project(b, c, n)?;
        let in_band: Vec<usize> = (0..sp.values.len())
            .filter(|&j| opts.band.contains(sp.frequency_hz(j)))
            .collect();
        count += in_band.len();
        if let Some(exact) = exact {
            for &j in &in_band {
                let l = sp.values[j];
                let d = exact[i]
                    .iter()
                    .map(|e| (e - l).norm() / e.norm())
                    .fold(f64::INFINITY, f64::min);
                worst = worst.max(d);
            }
            continue;
        }
        let starts: Vec<Eigenpair> = in_band
            .iter()
            .map(|&j| {
                let right = sp.modal(j);
                let left = right.iter().map(|v| v.conj()).collect();
                Eigenpair {
                    lambda: sp.values[j],
                    right,
                    left,
                }
            })
            .collect();
        let distances: Vec<f64> = starts
            .par_iter()
            .map(|p| match converge(lr, c, p, &opts.continuation) {
                Some((exact, _)) => (exact.lambda - p.lambda).norm() / exact.lambda.norm(),
                None => f64::INFINITY,
            })
            .collect();
        worst = distances.into_iter().fold(worst, f64::max);
    }
    Ok((worst, count))
}

/// The spectrum of the projection `p` at the coupling `c`.
pub(crate) fn spectrum(
    lr: &LinearizedBrake,
    p: &Projection,
    c: &Coupling,
) -> Result<Spectrum, BrakeError> {
    project(&p.basis, c, lr.size())
}

/// The projected problem at a coupling: frequencies `[Ω_m, Θ]`, damping `Qᵀ D Q`, the changes
/// `Qᵀ ΔK Q`, `Qᵀ ΔC Q`, and the basis.
pub(crate) type Problem<'a> = (
    &'a [f64],
    &'a ModalDamping,
    Mat<f64>,
    Option<Mat<f64>>,
    Arc<Ritz>,
);

/// The projected problem of `p` at `c` (for [`crate::projected_hopf`]).
pub(crate) fn problem<'a>(lr: &LinearizedBrake, p: &'a Projection, c: &Coupling) -> Problem<'a> {
    let b = &p.basis;
    let (dk, dc) = projected_change(b, c, lr.size());
    (&b.omega, &b.damping, dk, dc, b.ritz.clone())
}

/// The eigenpair nearest `guess` of the brake at the coupling `c`, from a projection on the
/// modes below `1.5 |guess|` and two terms of the others' correction (the first projection
/// [`choose`] tries), carried to the unprojected brake by the Rayleigh iteration of
/// [`crate::continuation`]: the eigenpair without a dense eigen-decomposition of the whole
/// brake. `None` when the iteration does not converge or lands more than `1e-3 |guess|` away
/// (the projection is then too coarse to say which eigenvalue is meant).
pub(crate) fn nearest_pair(
    lr: &LinearizedBrake,
    reference: &Reference,
    c: &Coupling,
    guess: c64,
    opts: &crate::continuation::EigenContinuationOptions,
) -> Result<Option<Eigenpair>, BrakeError> {
    let n = lr.size();
    let m = modes_below(&lr.omega, 1.5 * guess.norm() / std::f64::consts::TAU).min(n);
    let b = basis(lr, reference, m, 2, None)?;
    let sp = project(&b, c, n)?;
    let Some(j) = (0..sp.values.len()).min_by(|&a, &b| {
        (sp.values[a] - guess)
            .norm()
            .total_cmp(&(sp.values[b] - guess).norm())
    }) else {
        return Ok(None);
    };
    let right = sp.modal(j);
    let start = Eigenpair {
        lambda: sp.values[j],
        left: right.iter().map(|v| v.conj()).collect(),
        right,
    };
    Ok(converge(lr, c, &start, opts)
        .map(|(p, _)| p)
        .filter(|p| (p.lambda - guess).norm() <= 1e-3 * guess.norm()))
}

/// Friction values whose equilibria are found in turn before their spectra are computed in
/// parallel: the progress count moves once per chunk.
const CHUNK: usize = 8;

/// Points and branches of the projected sweep: equilibria in turn, projected spectra (in
/// parallel, each alone: the bits do not depend on the thread count), branches by correlation.
/// With `stop_at = Some(τ)` the sweep ends with the chunk in which a branch first crosses
/// `Re λ = τ` in the band (the points and branches up to there are the whole sweep's: each
/// step's matching depends only on the points before it).
#[allow(clippy::too_many_arguments)]
pub(crate) fn points(
    brake: &Brake,
    reference: &Reference,
    lr: &LinearizedBrake,
    p: &Projection,
    mus: &[f64],
    opts: &SweepOptions,
    stop_at: Option<f64>,
    progress: SweepProgress,
    timings: &mut SweepTimings,
    known: &[SweepPoint],
) -> Result<SweptPoints, BrakeError> {
    // How many of `known`'s points are at `mus`' first friction values, in order: their
    // equilibria are the ones found here (crate::sweep::sweep_after).
    let same = known
        .iter()
        .zip(mus)
        .take_while(|(p, mu)| p.equilibrium.mu.to_bits() == mu.to_bits())
        .count();
    let mut points: Vec<SweepPoint> = Vec::with_capacity(mus.len());
    let mut branches: Vec<Vec<usize>> = Vec::new();
    for chunk in mus.chunks(CHUNK) {
        let t = Instant::now();
        let mut equilibria: Vec<Equilibrium> = Vec::with_capacity(chunk.len());
        for &mu in chunk {
            let index = points.len() + equilibria.len();
            if index < same {
                equilibria.push(known[index].equilibrium.clone());
                continue;
            }
            let mut recent = points
                .iter()
                .map(|p| &p.equilibrium)
                .chain(&equilibria)
                .rev();
            let (last, before) = (recent.next(), recent.next());
            let from = last.map(|e| e.x.as_slice());
            let eq = match last.zip(before).map(|(a, b)| predicted(a, b, mu)) {
                // The predicted start, else the last equilibrium's.
                Some(x) => match modal_newton(brake, lr, reference, mu, &x, &opts.newton) {
                    Ok(eq) => eq,
                    Err(_) => equilibrium(brake, reference, lr, mu, from, &opts.newton)?,
                },
                None => equilibrium(brake, reference, lr, mu, from, &opts.newton)?,
            };
            equilibria.push(eq);
        }
        timings.equilibria += t.elapsed();
        let t = Instant::now();
        let spectra: Vec<Spectrum> = equilibria
            .par_iter()
            .map(|eq| spectrum(lr, p, &lr.coupling(brake, eq)))
            .collect::<Result<_, _>>()?;
        timings.spectra += t.elapsed();
        let mut crossed = false;
        for (equilibrium, spectrum) in equilibria.into_iter().zip(spectra) {
            points.push(SweepPoint {
                equilibrium,
                spectrum,
            });
            let t = Instant::now();
            extend_branches(&mut branches, &points);
            timings.tracking += t.elapsed();
            crossed |= stop_at.is_some_and(|tau| crossed_in_band(&points, &branches, opts, tau));
        }
        progress(points.len(), mus.len());
        if crossed {
            break;
        }
    }
    let stats = SweepStats {
        dense: points.len(),
        ..SweepStats::default()
    };
    Ok((points, branches, stats))
}

/// The branches of `points` with its last point matched to the one before (as
/// `crate::sweep::track_by` does for all of them at once, with the blocked correlation).
fn extend_branches(branches: &mut Vec<Vec<usize>>, points: &[SweepPoint]) {
    let k = points.len() - 1;
    if k == 0 {
        let n = points[0].spectrum.values.len();
        *branches = (0..n).map(|b| vec![b]).collect();
        return;
    }
    let m = match_modes_blocked(&points[k - 1].spectrum, &points[k].spectrum);
    for br in branches.iter_mut() {
        let prev = br[k - 1];
        br.push(m[prev]);
    }
}
