//! DLFT cycles continued in μ from the last converged one (issue 24, item 4;
//! docs/stick_slip.md, "Past 1.05 μ0: continuation in μ").
//!
//! **Why.** The DLFT balance (`squeal_brake::contact::dlft`, eqs D1–D4) is piecewise smooth:
//! the projection (D4) onto Coulomb's cone is a clamp, so the residual is continuous with a
//! Jacobian that is exact between changes of the samples' stick/slip pattern and jumps across
//! them (an element of Clarke's generalized Jacobian, the one `squeal_hbm::stick_slip`
//! forms). Levenberg–Marquardt with that Jacobian is a generalized Gauss–Newton method: near a
//! root where every such element is regular it converges like Newton's method (the local
//! theory of semismooth Newton methods, Qi & Sun, Math. Prog. 58 (1993) 353–367), but from
//! farther away its model of the residual is the wrong piece wherever the pattern flips, and
//! on the coarse brake at 3 km/h past 1.05 μ0 it reached the exact cycle only from starts
//! within about 1e-4 of it (docs/stick_slip.md). That is a local basin, not a missing cycle.
//!
//! **What.** The exact cycle moves continuously with μ, so the last converged cycle is a start
//! close to the next μ's when the step in μ is small. [`dlft_walk`] steps from converged cycles
//! towards a target μ: the start of each step is the secant through the last two converged
//! cycles (the previous one alone for the first step), extrapolated in μ with the phase
//! condition's dof fixed (both carry `U1s[phase_dof] = 0`, so their coefficients are
//! comparable); a step that stops short is halved and retried, a converged one lengthens the
//! next by [`WalkOptions::grow`]. The secant's error is second order in the step, so the steps
//! can grow where the branch is straight; where a pair's stick phase appears or vanishes the
//! branch has a kink and the steps shrink. It stops when the step falls below
//! [`WalkOptions::min_step`] (the cycle then is the last converged one, short of the target).
//! Every solve is an ordinary [`dlft_cycle`] with its converged-residual rule (1e-9 of the
//! largest static pair force, and the phase condition met to 1e-6 rad when the solve stopped
//! short of its own tolerance), so a cycle the walk returns is as exact as one from any start.

use crate::branch::BranchPoint;
use crate::stick_branch::StickError;
use crate::stick_dlft::{DlftCycle, DlftOptions, dlft_cycle};
use squeal_brake::modal_brake::ModalBrake;

/// Controls of [`dlft_walk`]; steps are fractions of the target μ.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct WalkOptions {
    /// The first step.
    pub first_step: f64,
    /// Give up below this step.
    pub min_step: f64,
    /// The largest step.
    pub max_step: f64,
    /// Factor on the step after a converged one.
    pub grow: f64,
    /// Levenberg–Marquardt iterations per step (a start within reach converges in a few; one
    /// that stalls is cut short and the step halved).
    pub iterations: usize,
}

impl Default for WalkOptions {
    fn default() -> Self {
        Self {
            first_step: 2e-3,
            min_step: 1e-4,
            max_step: 2e-2,
            grow: 1.5,
            iterations: 40,
        }
    }
}

/// What [`dlft_walk`] reached.
#[derive(Clone, Debug)]
pub struct Walked {
    /// The cycle at the target μ if `reached`, else the last converged one (`None`: no step
    /// converged).
    pub cycle: Option<DlftCycle>,
    /// Whether the target μ was reached with a converged cycle.
    pub reached: bool,
    /// Every solve: its μ, relative residual and whether it converged.
    pub solves: Vec<(f64, f64, bool)>,
}

/// The start at `mu` extrapolated from `prev` (one or two converged cycles, the last nearest).
fn predict(prev: &[BranchPoint], mu: f64) -> BranchPoint {
    let b = &prev[prev.len() - 1];
    let mut g = b.clone();
    g.parameter = mu;
    if let [a, b] = &prev[prev.len().saturating_sub(2)..] {
        let dm = b.parameter - a.parameter;
        if dm != 0.0 && a.nl_coeffs.len() == b.nl_coeffs.len() {
            let s = (mu - b.parameter) / dm;
            for ((g, &x), &y) in g.nl_coeffs.iter_mut().zip(&a.nl_coeffs).zip(&b.nl_coeffs) {
                *g = y + s * (y - x);
            }
            g.omega = b.omega + s * (b.omega - a.omega);
        }
    }
    g
}

/// The DLFT cycle of `mb` at `mu`, continued from the converged cycles `prev` (one or two,
/// ordered in μ towards `mu`, each carrying its μ as `parameter`) with the phase condition on
/// `phase_dof` (module docs).
pub fn dlft_walk(
    mb: &ModalBrake,
    prev: &[BranchPoint],
    mu: f64,
    phase_dof: usize,
    opts: &DlftOptions,
    walk: &WalkOptions,
) -> Result<Walked, StickError> {
    let (Some(last), true) = (prev.last(), prev.len() <= 2) else {
        return Err(StickError::BadOption(
            "the walk starts from one or two converged cycles",
        ));
    };
    if !(walk.min_step > 0.0 && walk.first_step >= walk.min_step && walk.grow >= 1.0) {
        return Err(StickError::BadOption(
            "walk steps must be positive and growing",
        ));
    }
    let mut o = opts.clone();
    o.lm.max_iterations = walk.iterations;
    let mut pts: Vec<BranchPoint> = prev.to_vec();
    let mut best: Option<DlftCycle> = None;
    let mut solves = Vec::new();
    let mut step = walk.first_step * mu.abs();
    let dir = (mu - last.parameter).signum();
    loop {
        let at = pts[pts.len() - 1].parameter;
        let left = (mu - at).abs();
        if left == 0.0 {
            break;
        }
        let next = if left <= step * 1.000_001 {
            mu
        } else {
            at + dir * step
        };
        let d = dlft_cycle(mb, next, &predict(&pts, next), phase_dof, &o)?;
        solves.push((next, d.point.residual, d.converged));
        if d.converged {
            let mut p = d.point.clone();
            p.parameter = next;
            pts.push(p);
            if pts.len() > 2 {
                pts.remove(0);
            }
            best = Some(d);
            step = (step * walk.grow).min(walk.max_step * mu.abs());
        } else {
            step *= 0.5;
            if step < walk.min_step * mu.abs() {
                break;
            }
        }
    }
    let reached = best.is_some() && pts[pts.len() - 1].parameter == mu;
    Ok(Walked {
        cycle: best,
        reached,
        solves,
    })
}
