//! Issue #24, item 4: the branch of limit cycles where the pads stick.
//!
//! **When.** The paper's contact element keeps the friction force at `μ F_n` in one direction
//! (eq 9, permanent sliding). It holds while the disc's surface outruns every pad point's
//! tangential vibration: the sliding margin `V_p / max_θ |h_p·x'(θ)|` of
//! [`crate::physics`] above 1 at every pair. The cycles of a branch grow with μ, so at a
//! given disc speed the margin falls along the branch, and past the first point where it is
//! below 1 the permanent-sliding cycles are not physical: for part of the period the slip
//! velocity `v = V + h·x'` would be negative while the friction force still drags the pad
//! forward.
//!
//! **The law that sticks.** From the last point with a margin of at least 1 (the first point,
//! when the whole branch is below 1), every pair's element `F_t(δ, δ', v)` is replaced by
//! [`Sticking`]: `F_t(δ, δ', |v|) tanh(v / v_reg)`, the regularized Coulomb law for the
//! paper's element (the friction force follows the sign of the slip velocity, and "sticking"
//! is creep at slip velocities of order `v_reg`). The regularization velocity is a fraction
//! ([`StickOptions::regularization`]) of the slowest pair's disc surface speed `V_min`: the
//! transitions of the force then last a fixed fraction of the period whatever the disc
//! speed, so the harmonics needed to resolve them do not grow as the disc slows down. At
//! margin 1 the tangential velocity's amplitude is `V`, so the force's transition takes a
//! phase of about `v_reg / V` radians of the cycle, and `H` harmonics resolve features of
//! `2π / H`: `v_reg = V/20` needs `H` of a few tens. Both are stated in the report, and the
//! answer's convergence in each is measured by recomputing with `v_reg` halved and with more
//! harmonics (docs/stick_slip.md).
//!
//! **The recomputed branch.** The start point's Fourier coefficients are padded with zeros to
//! [`StickOptions::harmonics`] and the branch is continued from it in μ with the sticking
//! elements ([`crate::branch::follow_from_point`]), in the direction the permanent-sliding
//! branch went, to the same end of its μ range. Every point of the permanent-sliding branch
//! past the start whose margin is below 1 is then recomputed: the sticking branch's crossing of
//! its μ ([`cycles_at`]), with the new cycle's frequency, loudest closure, sliding margin and
//! Floquet exponents (Hill's method with the sticking elements' velocity terms,
//! [`crate::floquet`]).
//!
//! The branch's continuation and Floquet exponents need a smooth law, so the branch uses the
//! regularized one; exact stick–slip (the dynamic Lagrangian, `squeal_brake::contact::dlft`)
//! recomputes cycles at fixed μ ([`crate::stick_dlft`]).

use crate::bifurcation::cycle_of;
use crate::branch::{
    BranchOptions, BranchPoint, Harmonics, LimitCycleBranch, Parameter, cycles_at,
    follow_from_point,
};
use crate::cycle::Cycle;
use crate::floquet::{FloquetError, HillFloquet, HillOptions, hill};
use crate::physics::{SlidingMargin, sliding_margin_of};
use crate::solve::ChbmError;
use rayon::prelude::*;
use squeal_brake::contact::Sticking;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::{HarmonicLayout, HbmError};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Why the sticking branch could not be computed.
#[derive(Debug, thiserror::Error)]
pub enum StickError {
    /// A pair has no disc surface speed: the scene gives no disc speed.
    #[error(
        "contact pair {pair} has no disc surface speed: give the disc's speed ([rotation] rpm, or vehicle_speed_kmh with rolling_radius) to check and treat stick-slip"
    )]
    NoSurfaceSpeed {
        /// The pair (1-based).
        pair: usize,
    },
    /// A regularization or harmonics option is out of range (what and why).
    #[error("stick-slip option {0}")]
    BadOption(&'static str),
    /// The harmonic balance or the continuation.
    #[error(transparent)]
    Chbm(#[from] ChbmError),
    /// The exact stick–slip law (DLFT) cannot be set up on the brake.
    #[error(transparent)]
    Dlft(#[from] squeal_brake::contact::dlft::DlftError),
}

impl From<HbmError> for StickError {
    fn from(e: HbmError) -> Self {
        Self::Chbm(e.into())
    }
}

/// Controls of [`follow_sticking`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct StickOptions {
    /// `v_reg` as a fraction of the slowest pair's disc surface speed (default 1/20).
    pub regularization: f64,
    /// Harmonics of the sticking branch (default 24; the start point's when it has more).
    pub harmonics: usize,
    /// AFT samples per period (default: 4 times the harmonic balance's default, so that the
    /// steep friction force is not aliased).
    pub samples: Option<usize>,
    /// Hill's method at the recomputed cycles.
    pub hill: HillOptions,
}

impl Default for StickOptions {
    fn default() -> Self {
        Self {
            regularization: 0.05,
            harmonics: 24,
            samples: None,
            hill: HillOptions::default(),
        }
    }
}

impl StickOptions {
    /// The AFT samples used with `h` harmonics.
    pub fn samples_for(&self, h: usize) -> usize {
        self.samples
            .unwrap_or(4 * squeal_hbm::default_samples(h))
            .max(squeal_hbm::default_samples(h))
    }
}

/// A cycle of the permanent-sliding branch recomputed with the sticking elements.
#[derive(Debug)]
pub struct StickCycle {
    /// Index of the permanent-sliding branch's point.
    pub point: usize,
    /// Its μ.
    pub mu: f64,
    /// Its sliding margin (below 1).
    pub margin: SlidingMargin,
    /// The recomputed cycle at the same μ (`None`: the sticking branch does not reach it).
    pub cycle: Option<BranchPoint>,
    /// The recomputed cycle's sliding margin.
    pub stick_margin: Option<SlidingMargin>,
    /// The recomputed cycle's Floquet exponents (Hill's method).
    pub floquet: Option<Result<HillFloquet, FloquetError>>,
}

/// The sticking part of a branch (module documentation).
#[derive(Debug)]
pub struct StickBranch {
    /// The sliding margin of every point of the permanent-sliding branch.
    pub margins: Vec<SlidingMargin>,
    /// `v_reg` (m/s).
    pub regularization_speed: f64,
    /// The slowest pair's disc surface speed (m/s).
    pub slowest_surface_speed: f64,
    /// Harmonics and AFT samples of the sticking branch.
    pub harmonics: usize,
    /// AFT samples per period.
    pub samples: usize,
    /// The permanent-sliding point the sticking branch starts from.
    pub start: usize,
    /// The branch continued with the sticking elements.
    pub branch: LimitCycleBranch,
    /// The recomputed cycles.
    pub cycles: Vec<StickCycle>,
    /// Wall time of the sticking branch and the recomputed cycles.
    pub time: Duration,
}

/// The disc's surface speed at each pair of `mb` (m/s).
pub fn surface_speeds(mb: &ModalBrake) -> Result<Vec<f64>, StickError> {
    mb.pairs
        .iter()
        .enumerate()
        .map(|(i, p)| {
            p.surface_speed
                .map(f64::abs)
                .ok_or(StickError::NoSurfaceSpeed { pair: i + 1 })
        })
        .collect()
}

/// The sliding margin of a branch point of `mb` at the surface speeds `speeds`.
pub fn point_margin(
    mb: &ModalBrake,
    p: &BranchPoint,
    speeds: &[f64],
) -> Result<SlidingMargin, HbmError> {
    let nl = mb.nl();
    let c = Cycle::from_coefficients(p.harmonics, p.omega, nl, p.nl_coeffs.clone())?;
    let all: Vec<usize> = (0..nl).collect();
    sliding_margin_of(&mb.pairs, &all, &c, speeds)
}

/// The sliding margin of every point of `branch`, a branch of `mb`.
pub fn branch_margins(
    mb: &ModalBrake,
    branch: &LimitCycleBranch,
) -> Result<Vec<SlidingMargin>, StickError> {
    let speeds = surface_speeds(mb)?;
    Ok(branch
        .points
        .iter()
        .map(|p| point_margin(mb, p, &speeds))
        .collect::<Result<Vec<_>, _>>()?)
}

/// `mb` with every pair's element made to stick with the regularization velocity `v_reg`.
pub fn sticking_brake(mb: &ModalBrake, v_reg: f64) -> Result<ModalBrake, StickError> {
    if !(v_reg.is_finite() && v_reg > 0.0) {
        return Err(StickError::BadOption(
            "v_reg must be a positive number of m/s",
        ));
    }
    surface_speeds(mb)?;
    let mut out = mb.clone();
    for p in &mut out.pairs {
        p.law = Arc::new(Sticking {
            inner: p.law.clone(),
            regularization_speed: v_reg,
        });
    }
    Ok(out)
}

/// `p`'s coefficients padded with zero harmonics up to `h`.
fn padded(mb: &ModalBrake, p: &BranchPoint, h: usize) -> Result<BranchPoint, HbmError> {
    let layout = HarmonicLayout::new(mb.nl(), h.max(p.harmonics))?;
    let mut q = p.clone();
    q.nl_coeffs.resize(layout.len(), 0.0);
    q.harmonics = layout.n_harmonics();
    Ok(q)
}

/// The sticking part of `branch` (a branch in μ of `mb`, followed with `bopts`): `Ok(None)`
/// when every point's sliding margin is at least 1 (permanent sliding holds all along).
pub fn follow_sticking(
    mb: &ModalBrake,
    branch: &LimitCycleBranch,
    bopts: &BranchOptions,
    opts: &StickOptions,
) -> Result<Option<StickBranch>, StickError> {
    let t0 = Instant::now();
    if !(opts.regularization.is_finite() && opts.regularization > 0.0) {
        return Err(StickError::BadOption(
            "regularization must be a positive fraction of the disc speed",
        ));
    }
    let speeds = surface_speeds(mb)?;
    let margins = branch_margins(mb, branch)?;
    let Some(first) = margins.iter().position(|m| !m.sliding()) else {
        return Ok(None);
    };
    let start = first.saturating_sub(1);
    let v_min = speeds.iter().copied().fold(f64::INFINITY, f64::min);
    let v_reg = opts.regularization * v_min;
    let smb = sticking_brake(mb, v_reg)?;
    let p0 = padded(mb, &branch.points[start], opts.harmonics)?;
    let h = p0.harmonics;
    let samples = opts.samples_for(h);
    let direction = if first > start {
        branch.points[first].parameter - p0.parameter
    } else {
        p0.parameter_rate
    };
    let mu0 = branch.hopf.map_or(p0.parameter, |hp| hp.mu0);
    let sopts = {
        let mut o = bopts.clone();
        o.harmonics = Harmonics::Fixed(h);
        o.samples = Some(samples);
        o.range = (
            bopts.range.0 * mu0 / p0.parameter,
            bopts.range.1 * mu0 / p0.parameter,
        );
        o
    };
    let stick = follow_from_point(
        &smb,
        &p0,
        branch.phase_dof,
        Parameter::Friction,
        direction,
        &sopts,
    )?;
    let mut cycles = Vec::new();
    for (i, m) in margins.iter().enumerate().skip(start + 1) {
        if m.sliding() {
            continue;
        }
        let mu = branch.points[i].parameter;
        let cycle = cycles_at(&smb, &stick, mu, &sopts)?
            .into_iter()
            .next()
            .map(|c| c.1);
        let stick_margin = match &cycle {
            Some(c) => Some(point_margin(&smb, c, &speeds)?),
            None => None,
        };
        cycles.push(StickCycle {
            point: i,
            mu,
            margin: m.clone(),
            cycle,
            stick_margin,
            floquet: None,
        });
    }
    let hill_opts = &opts.hill;
    let floquet: Vec<_> = cycles
        .par_iter()
        .map(|c| {
            c.cycle.as_ref().map(|p| {
                let mut mbp = smb.clone();
                mbp.mu = p.parameter;
                hill(&mbp, &cycle_of(&smb, p, Some(samples))?, hill_opts)
            })
        })
        .collect();
    for (c, f) in cycles.iter_mut().zip(floquet) {
        c.floquet = f;
    }
    Ok(Some(StickBranch {
        margins,
        regularization_speed: v_reg,
        slowest_surface_speed: v_min,
        harmonics: h,
        samples,
        start,
        branch: stick,
        cycles,
        time: t0.elapsed(),
    }))
}
