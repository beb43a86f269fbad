//! The reference limit cycle of the comparison (issue #22): the brake's periodic orbit by
//! shooting ([`squeal_ode::shooting`]), instead of a time integration run until the cycle
//! stops drifting.
//!
//! **Unknowns and equations.** The state is the modal `y = [q; q']` of eq (11) in the form of
//! [`BrakeDynamics`]; shooting solves `φ(y₀, T) = y₀` with the phase condition of
//! [`squeal_ode::shooting`] in the weighted norm `W = diag(1, …, 1, 1/ω, …, 1/ω)` (a unit of
//! modal displacement against a unit of modal velocity over ω: the two halves of a harmonic
//! oscillation weigh the same). The start is a cycle already at hand — CHBM's, or a looser
//! time integration's steady cycle — at phase 0: `y₀ = [Φ⁻¹ x(0); Φ⁻¹ x'(0)]`, `T = 2π/ω`.
//!
//! **Monodromy.** Newton's `∂φ/∂y₀` comes from the variational equations of
//! [`crate::floquet`] (eq 11 linearized about a cycle given as a Fourier series), along the
//! series of the current iterate's period ([`ShootingReferenceOptions::monodromy_harmonics`]
//! harmonics), each column at a loose tolerance: an approximation, which only sets the rate of
//! the (linear) convergence; the orbit is where the periodicity residual, computed at the
//! reference tolerance, vanishes. (All columns at once by BDF2 at 256 equal steps along the
//! series took 0.43 s instead of 23 s on the medium brake, but Newton then stalled at a
//! residual of 1.5e-6: the lightly damped modes' phase errors were too large to steer.)
//!
//! **Its own error.** Three checks, each reported:
//! 1. the relative periodicity residual `‖W (φ(y₀,T) - y₀)‖ / A` (how periodic the computed
//!    trajectory is);
//! 2. the same orbit solved again at [`ShootingReferenceOptions::check_rtol`] (Newton from the
//!    reference, its monodromy reused): the difference of the two cycles, phase-aligned, in the
//!    measures of [`crate::cycle::relative_errors`]. The BDF's global error falls with the
//!    tolerance, so the difference bounds the tighter solve's error from above — the stated
//!    error of the reference;
//! 3. the Floquet multiplier 1: on a periodic orbit `M f(y₀) = f(y₀)` exactly (the flow's
//!    direction is carried round unchanged). One column of the variational equations,
//!    integrated with the state along the converged period from `f(y₀)` at
//!    [`ShootingReferenceOptions::floquet_rtol`], gives `‖W (M f - f)‖ / ‖W f‖`: it measures
//!    the orbit and the integration together, as a conservation law would. The multipliers of
//!    Newton's (approximate) monodromy are reported beside it: the one nearest 1 and the
//!    largest other modulus (below 1: the cycle attracts).

use crate::cycle::{Cycle, RelativeErrors, relative_errors, to_modal};
use crate::floquet::{CycleRef, FloquetError, MonodromyOptions, monodromy_matrix};
use crate::timeint::physical_cycle;
use faer::{Mat, c64};
use squeal_brake::dynamics::BrakeDynamics;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::{HarmonicLayout, HbmError, Periodic};
use squeal_ode::{
    Atol, BdfOptions, Flow, OdeSystem, ShootingError, ShootingOptions, shoot, tangent,
};
use std::f64::consts::PI;
use std::time::{Duration, Instant};

/// Errors of [`shooting_reference`].
#[derive(Debug, thiserror::Error)]
pub enum ShootingReferenceError {
    /// Newton on the orbit failed.
    #[error("shooting at rtol {rtol:e}: {source}")]
    Shooting {
        /// The integration tolerance of the failed solve.
        rtol: f64,
        /// Why.
        source: ShootingError,
    },
    /// The start cycle has no modal state (its dofs do not fit, or `Φ` is singular).
    #[error("the start cycle does not fit the brake's {0} dofs")]
    Start(usize),
    /// A Fourier series did not fit.
    #[error("the reference cycle: {0}")]
    Cycle(#[from] HbmError),
    /// The monodromy matrix along the converged orbit could not be computed.
    #[error("the Floquet check: {0}")]
    Floquet(#[from] FloquetError),
}

/// Options of [`shooting_reference`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct ShootingReferenceOptions {
    /// BDF tolerance of the reference's period (`atol` scaled as in [`crate::timeint`]).
    pub rtol: f64,
    /// The second tolerance of the error estimate (module docs, check 2).
    pub check_rtol: f64,
    /// Highest BDF order of the period's integration.
    pub max_order: usize,
    /// Newton stops at a relative periodicity residual of `tol_factor · rtol`. The residual
    /// cannot fall much below the integration's own noise: about 20–30 rtol on the medium
    /// brake, 100 rtol on the coarse one at 1.1 μ0 (residuals 1.2e-8, 1.06e-8, 1.06e-8,
    /// 9.9e-9 at rtol 1e-10, measured with a factor 100, which cost two needless monodromies).
    pub tol_factor: f64,
    /// Newton iterations at most.
    pub max_iterations: usize,
    /// Newton steps always taken, in both solves. The computed orbit is the fixed point of the
    /// *numerical* period map, `(I - M)⁻¹` times one period's global error away from the exact
    /// one (×18 on the 2-dof model, ×60–90 on the brake, whose leading multipliers are 0.94
    /// and 0.98–0.99): a check solve that stopped at its start, already within its tolerance,
    /// would miss that amplification (measured on the 2-dof model: stated 4.9e-8 against an
    /// actual 3.7e-7), so each solve takes at least these steps towards its own fixed point.
    pub min_iterations: usize,
    /// Harmonics of the reference cycle (its Fourier series over every dof; the modal state's
    /// series must fit [`squeal_hbm`]'s layout limit: 24 for the 316 states of a 158-dof
    /// brake).
    pub harmonics: usize,
    /// Samples per period of that series.
    pub samples: usize,
    /// Harmonics of the iterate's series along which the monodromy is integrated.
    pub monodromy_harmonics: usize,
    /// Tolerances of the variational equations for Newton (it only steers).
    pub newton_monodromy: MonodromyOptions,
    /// BDF tolerance of the Floquet check's column (module docs, check 3; `None`: no check).
    pub floquet_rtol: Option<f64>,
}

impl Default for ShootingReferenceOptions {
    fn default() -> Self {
        Self {
            rtol: 1e-10,
            check_rtol: 1e-9,
            max_order: 5,
            tol_factor: 300.0,
            max_iterations: 12,
            min_iterations: 2,
            harmonics: 24,
            samples: 128,
            monodromy_harmonics: 20,
            newton_monodromy: MonodromyOptions {
                rtol: 1e-6,
                atol: 1e-8,
                max_order: 5,
            },
            floquet_rtol: Some(1e-10),
        }
    }
}

/// The Floquet check of the converged orbit (module docs, check 3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FloquetCheck {
    /// `‖W (M f(y₀) - f(y₀))‖ / ‖W f(y₀)‖` along the converged period (0 on the exact orbit).
    pub tangent_error: f64,
    /// The multiplier of Newton's monodromy nearest 1.
    pub trivial: c64,
    /// The largest modulus among its other multipliers.
    pub leading: f64,
    /// Wall time of the check.
    pub wall: Duration,
}

/// One shooting solve at one tolerance.
#[derive(Clone, Debug)]
pub struct ShootingSolve {
    /// BDF tolerance.
    pub rtol: f64,
    /// The cycle of every physical dof (Fourier series of the converged period).
    pub cycle: Cycle,
    /// Period (s).
    pub period: f64,
    /// The modal state `[q; q']` of the converged period as a Fourier series.
    pub state: Periodic,
    /// Relative periodicity residual of each iterate, the last the solution's.
    pub residuals: Vec<f64>,
    /// Monodromy matrices computed for Newton (not counting one given).
    pub monodromies: usize,
    /// BDF steps of all the periods integrated.
    pub steps: usize,
    /// Wall time.
    pub wall: Duration,
}

impl ShootingSolve {
    /// The solution's relative periodicity residual.
    pub fn residual(&self) -> f64 {
        self.residuals.last().copied().unwrap_or(f64::NAN)
    }
}

/// The reference and its estimated own error.
#[derive(Clone, Debug)]
pub struct ShootingReference {
    /// The solve at [`ShootingReferenceOptions::rtol`]: the reference.
    pub reference: ShootingSolve,
    /// The solve at [`ShootingReferenceOptions::check_rtol`] from it.
    pub check: ShootingSolve,
    /// The difference of the check from the reference on every physical dof: the reference's
    /// stated error (module docs, check 2).
    pub all: RelativeErrors,
    /// The same on the contact dofs.
    pub contact: RelativeErrors,
    /// The Floquet check (`None` when not asked).
    pub floquet: Option<FloquetCheck>,
}

impl ShootingReference {
    /// Wall time of everything the reference took.
    pub fn wall(&self) -> Duration {
        self.reference.wall + self.check.wall + self.floquet.map_or(Duration::ZERO, |f| f.wall)
    }

    /// BDF steps of the periods integrated and of Newton's variational equations.
    pub fn steps(&self) -> usize {
        self.reference.steps + self.check.steps
    }
}

/// The nonlinear dofs' displacement series of a modal state series `[q; v]` (`u = Φ_n q`, per
/// block), for the variational equations.
fn nl_series(mb: &ModalBrake, state: &Periodic) -> Result<(HarmonicLayout, Vec<f64>), HbmError> {
    let (n, nn) = (mb.modes(), mb.nl());
    let layout = HarmonicLayout::new(nn, state.harmonics())?;
    let mut u = vec![0.0; layout.len()];
    for b in 0..layout.n_blocks() {
        for i in 0..nn {
            u[b * nn + i] = (0..n)
                .map(|j| mb.phi_n[(i, j)] * state.coeffs[b * 2 * n + j])
                .sum();
        }
    }
    Ok((layout, u))
}

/// `∂φ/∂y₀` along the series of a period's trajectory (module docs), and its BDF steps.
fn monodromy_along(
    mb: &ModalBrake,
    state: &Periodic,
    harmonics: usize,
    opts: &MonodromyOptions,
) -> Result<(Mat<f64>, usize), FloquetError> {
    let state = state.with_harmonics(harmonics.min(state.harmonics()))?;
    let (layout, u) = nl_series(mb, &state)?;
    let cycle = CycleRef {
        layout,
        u: &u,
        omega: state.omega,
        samples: 4 * layout.n_harmonics() + 8,
    };
    monodromy_matrix(mb, &cycle, opts)
}

/// The modal start `[Φ⁻¹ x(0); Φ⁻¹ x'(0)]` of a cycle and the scale of its modal coordinates
/// (largest first-harmonic amplitude, for the absolute tolerances).
fn start_of(mb: &ModalBrake, c: &Cycle) -> Result<(Vec<f64>, f64), ShootingReferenceError> {
    let n = mb.modes();
    if c.n_dofs() != n {
        return Err(ShootingReferenceError::Start(n));
    }
    let x: Vec<f64> = (0..n).map(|d| c.value_at(d, 0.0, false)).collect();
    let v: Vec<f64> = (0..n).map(|d| c.value_at(d, 0.0, true)).collect();
    let y0 =
        BrakeDynamics::state_from_physical(mb, &x, &v).ok_or(ShootingReferenceError::Start(n))?;
    let first: Vec<f64> = (0..2 * n)
        .map(|i| {
            let (a, b) = c.x.harmonic(1, i % n);
            if i < n { a } else { b }
        })
        .collect();
    let q = to_modal(mb, &first);
    let scale = (0..n).map(|j| q[j].hypot(q[n + j])).fold(0.0, f64::max);
    Ok((y0, scale))
}

/// Shooting options at `rtol` for a cycle at `omega` with modal scale `q_scale`.
fn options_at(
    opts: &ShootingReferenceOptions,
    n: usize,
    rtol: f64,
    omega: f64,
    q_scale: f64,
) -> ShootingOptions {
    let atol_q = rtol * q_scale;
    {
        let mut o = ShootingOptions::default();
        o.bdf = {
            let mut o = BdfOptions::default();
            o.rtol = rtol;
            o.atol = Atol::PerComponent(
                (0..2 * n)
                    .map(|i| if i < n { atol_q } else { atol_q * omega })
                    .collect(),
            );
            o.max_order = opts.max_order;
            o
        };
        o.weights = (0..2 * n)
            .map(|i| if i < n { 1.0 } else { 1.0 / omega })
            .collect();
        o.tol = opts.tol_factor * rtol;
        o.max_iterations = opts.max_iterations;
        o.min_iterations = opts.min_iterations;
        o.harmonics = opts.harmonics;
        o.samples = opts.samples;
        o
    }
}

/// One solve from `(y0, period)`; `first` is the monodromy to steer with, if any (else one
/// along the first period's trajectory); returns the solve, the start and the matrix last used.
fn solve_at(
    mb: &ModalBrake,
    (y0, period, q_scale): (&[f64], f64, f64),
    rtol: f64,
    first: Option<&Mat<f64>>,
    opts: &ShootingReferenceOptions,
) -> Result<(ShootingSolve, Vec<f64>, Mat<f64>), ShootingReferenceError> {
    let t0 = Instant::now();
    let n = mb.modes();
    let sys = BrakeDynamics::new(mb);
    let so = options_at(opts, n, rtol, 2.0 * PI / period, q_scale);
    let (mut extra_steps, mut computed) = (0, 0);
    let mut given = first.cloned();
    let mut provider = |_: &[f64], _: f64, fl: &Flow| -> Result<Mat<f64>, FloquetError> {
        if let Some(m) = given.take() {
            return Ok(m);
        }
        let (m, steps) = monodromy_along(
            mb,
            &fl.trajectory,
            opts.monodromy_harmonics,
            &opts.newton_monodromy,
        )?;
        extra_steps += steps;
        computed += 1;
        Ok(m)
    };
    let orbit = shoot(&sys, y0, period, &so, &mut provider)
        .map_err(|source| ShootingReferenceError::Shooting { rtol, source })?;
    let cycle = physical_cycle(mb, &orbit.flow.trajectory)?;
    let solve = ShootingSolve {
        rtol,
        cycle,
        period: orbit.period,
        state: orbit.flow.trajectory,
        residuals: orbit.residuals,
        monodromies: computed,
        steps: orbit.steps + extra_steps,
        wall: t0.elapsed(),
    };
    Ok((solve, orbit.x0, orbit.monodromy))
}

/// The Floquet check of the orbit `(y0, period)` (module docs, check 3), with the multipliers
/// of Newton's monodromy `m`.
fn floquet_check(
    mb: &ModalBrake,
    (y0, period): (&[f64], f64),
    so: &ShootingOptions,
    m: &Mat<f64>,
) -> Result<FloquetCheck, ShootingReferenceError> {
    let t0 = Instant::now();
    let sys = BrakeDynamics::new(mb);
    let mut f = vec![0.0; y0.len()];
    sys.rhs(0.0, y0, &mut f);
    let w = &so.weights;
    let norm = |v: &[f64]| -> f64 {
        v.iter()
            .zip(w)
            .map(|(a, b)| (a * b).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    // The column's absolute tolerance: the state's, scaled from the orbit to `f`'s size.
    let column_atol = so.bdf.rtol * norm(&f);
    let mf = tangent(&sys, y0, period, &f, &so.bdf, column_atol).map_err(|e| {
        ShootingReferenceError::Shooting {
            rtol: so.bdf.rtol,
            source: e.into(),
        }
    })?;
    let diff: Vec<f64> = mf.iter().zip(&f).map(|(a, b)| a - b).collect();
    let tangent_error = norm(&diff) / norm(&f);
    let evd = m.eigen().map_err(|_| FloquetError::Eigen {
        what: "Newton's monodromy matrix",
    })?;
    let s = evd.S();
    let rho: Vec<c64> = (0..m.nrows()).map(|i| s[i]).collect();
    let distance = |z: c64| (z - 1.0).norm();
    let k = (0..rho.len())
        .min_by(|&a, &b| distance(rho[a]).total_cmp(&distance(rho[b])))
        .unwrap_or(0);
    let leading = (0..rho.len())
        .filter(|&i| i != k)
        .map(|i| rho[i].norm())
        .fold(0.0, f64::max);
    Ok(FloquetCheck {
        tangent_error,
        trivial: rho.get(k).copied().unwrap_or(c64::new(f64::NAN, 0.0)),
        leading,
        wall: t0.elapsed(),
    })
}

/// The reference cycle of the comparison at the friction of `mb` by shooting from `start` (a
/// cycle of every physical dof near the orbit: CHBM's, or a time integration's), with its
/// estimated own error (module docs). `phase_dof` is the physical dof on which the check is
/// aligned with the reference.
pub fn shooting_reference(
    mb: &ModalBrake,
    start: &Cycle,
    phase_dof: usize,
    opts: &ShootingReferenceOptions,
) -> Result<ShootingReference, ShootingReferenceError> {
    let (y0, q_scale) = start_of(mb, start)?;
    let period = 2.0 * PI / start.omega();
    let (reference, x_ref, m) = solve_at(mb, (&y0, period, q_scale), opts.rtol, None, opts)?;
    let (mut check, _, _) = solve_at(
        mb,
        (&x_ref, reference.period, q_scale),
        opts.check_rtol,
        Some(&m),
        opts,
    )?;
    check.cycle.align_to(&reference.cycle, phase_dof);
    let all_dofs: Vec<usize> = (0..mb.modes()).collect();
    let all = relative_errors(&check.cycle, &reference.cycle, &all_dofs);
    let contact = relative_errors(&check.cycle, &reference.cycle, &mb.nl_dofs);
    let floquet = match opts.floquet_rtol {
        Some(rtol) => {
            let omega = 2.0 * PI / reference.period;
            let so = options_at(opts, mb.modes(), rtol, omega, q_scale);
            Some(floquet_check(mb, (&x_ref, reference.period), &so, &m)?)
        }
        None => None,
    };
    Ok(ShootingReference {
        reference,
        check,
        all,
        contact,
        floquet,
    })
}
