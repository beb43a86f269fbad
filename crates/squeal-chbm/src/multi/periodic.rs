//! The periodic part of the generalized CHBM: one CHBM cycle per unstable mode, and which of
//! them attracts (derivation in [`crate::multi`]).
//!
//! For each unstable mode `j` at μ, CHBM (eqs 46–48) from that mode's eigenvector gives the
//! cycle on which mode `j` alone oscillates. It is the brake's answer when it attracts: Hill's
//! Floquet exponents ([`crate::floquet::hill`]) all have `Re σ < 0`. The other unstable modes'
//! eigenvalues `λ_k`, followed from the static solution to the cycle's averaged linearization
//! ([`super::linearization`], no amplitude along `k`), say the same in the generalized CHBM's
//! terms: `Re λ_k < 0` when the cycle of `j` quenches mode `k`. Both are reported; the verdict
//! takes Hill's (the averaged linearization drops the cycle's parametric excitation).

use super::linearization::{MultiLinearization, Sample};
use crate::floquet::{CycleRef, CycleStability, FloquetError, HillFloquet, HillOptions, hill};
use crate::solve::{ChbmError, ChbmOptions, ChbmSolution, ChbmStart, Outcome, solve_with_restarts};
use faer::Mat;
use faer::c64;
use squeal_brake::harmonic::{BrakeEigen, ContactForce};
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::{HarmonicLayout, HbmError, LinearUpdate, LinearizedEigen, reference_jacobian};
use std::f64::consts::PI;

/// One unstable mode's CHBM cycle with the verdicts on it.
#[derive(Debug)]
pub struct ModeCycle {
    /// Index of the mode among the unstable ones (largest growth first).
    pub mode: usize,
    /// The static eigenvalue it starts from.
    pub lambda0: c64,
    /// The CHBM solution from that mode.
    pub solution: ChbmSolution,
    /// Hill's exponents on it (`None` when CHBM found no limit cycle).
    pub floquet: Option<Result<HillFloquet, FloquetError>>,
    /// For every unstable mode `k` (in order; the cycle's own `k = mode` included), its
    /// eigenvalue under the cycle's averaged linearization (the cycle's own is `iω` at the
    /// root). `None` when CHBM found no limit cycle or an eigenvalue was lost.
    pub others: Option<Vec<c64>>,
}

impl ModeCycle {
    /// Hill's verdict, when there is one.
    pub fn stability(&self) -> Option<CycleStability> {
        match &self.floquet {
            Some(Ok(f)) => Some(f.stability()),
            _ => None,
        }
    }
}

/// What the periodic part says about the answer.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Exactly one mode's cycle attracts: that mode wins, the answer is periodic.
    Periodic {
        /// The winning mode.
        mode: usize,
    },
    /// Several cycles attract: the start decides which one the brake settles on.
    Multistable {
        /// The modes whose cycles attract.
        modes: Vec<usize>,
    },
    /// No cycle attracts and none is marginal: every mode grows on the others' cycles, the
    /// answer is quasi-periodic (the torus harmonic balance, not computed here).
    QuasiPeriodic,
    /// A cycle did not converge, Hill's analysis failed, or a verdict is marginal.
    Undecided,
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Verdict::Periodic { mode } => write!(f, "periodic: mode {} wins", mode + 1),
            Verdict::Multistable { modes } => {
                let list: Vec<String> = modes.iter().map(|m| (m + 1).to_string()).collect();
                write!(
                    f,
                    "multistable: the cycles of modes {} attract",
                    list.join(", ")
                )
            }
            Verdict::QuasiPeriodic => {
                f.write_str("quasi-periodic: no single-mode cycle attracts (torus needed)")
            }
            Verdict::Undecided => f.write_str("undecided (a cycle or its Floquet analysis failed)"),
        }
    }
}

/// The CHBM cycle of each unstable mode in `starts` (from [`super::unstable_modes`]), with
/// Hill's exponents and the other modes' eigenvalues on it.
pub fn mode_cycles(
    mb: &ModalBrake,
    starts: &[ChbmStart],
    opts: &ChbmOptions,
    amplitudes: &[f64],
    hill_options: &HillOptions,
) -> Result<Vec<ModeCycle>, ChbmError> {
    let lambdas0: Vec<c64> = starts.iter().map(|s| s.lambda).collect();
    let x0: Vec<f64> = match starts.first() {
        Some(s) => mb.nl_dofs.iter().map(|&d| s.equilibrium[d]).collect(),
        None => return Ok(Vec::new()),
    };
    let mut out = Vec::with_capacity(starts.len());
    for (mode, start) in starts.iter().enumerate() {
        let (solution, _, _, _) = solve_with_restarts(mb, start, opts, amplitudes)?;
        let converged = solution.outcome == Outcome::LimitCycle;
        let (floquet, others) = if converged {
            let layout = HarmonicLayout::new(mb.nl(), solution.harmonics)?;
            let cycle = CycleRef {
                layout,
                u: &solution.nl_coeffs,
                omega: solution.omega,
                samples: solution.samples,
            };
            (
                Some(hill(mb, &cycle, hill_options)),
                eigenvalues_on_cycle(mb, &cycle, &x0, &lambdas0).ok(),
            )
        } else {
            (None, None)
        };
        out.push(ModeCycle {
            mode,
            lambda0: start.lambda,
            solution,
            floquet,
            others,
        });
    }
    Ok(out)
}

/// The samples of a periodic cycle over one period (one phase each).
pub fn cycle_samples(cycle: &CycleRef<'_>) -> Result<Vec<Sample>, HbmError> {
    let n = cycle.layout.n_dofs();
    let s = cycle.samples.max(1);
    (0..s)
        .map(|k| {
            let theta = 2.0 * PI * k as f64 / s as f64;
            let (mut x, mut v) = (vec![0.0; n], vec![0.0; n]);
            cycle.layout.displacement_at(cycle.u, theta, &mut x)?;
            cycle
                .layout
                .velocity_at(cycle.u, cycle.omega, theta, &mut v)?;
            Ok(Sample {
                x,
                v,
                phases: vec![theta],
            })
        })
        .collect()
}

/// Steps of the homotopy from the static linearization to the cycle's.
const HOMOTOPY_STEPS: usize = 10;

/// The eigenvalues continuing each of `lambdas0` (static, at the equilibrium `x0` of the
/// force's dofs) under the averaged linearization `N` of `cycle`, each followed by its own
/// tracker along `J₀ + t (N - J₀)`, `t = 0.1, 0.2, …, 1` (`J₀` the static tangent), so that a
/// large change of the linearization over the cycle does not jump to another mode.
pub fn eigenvalues_on_cycle(
    mb: &ModalBrake,
    cycle: &CycleRef<'_>,
    x0: &[f64],
    lambdas0: &[c64],
) -> Result<Vec<c64>, HbmError> {
    let force = ContactForce::new(mb);
    let samples = cycle_samples(cycle)?;
    let lin = MultiLinearization::from_samples(&force, &[cycle.omega], &samples).map_err(|e| {
        HbmError::EigenvalueLost {
            from: lambdas0.first().copied().unwrap_or(c64::new(0.0, 0.0)),
            why: e.to_string(),
        }
    })?;
    eigenvalues_under(mb, &force, &lin, x0, lambdas0)
}

/// The eigenvalues continuing each of `lambdas0` (static, at the equilibrium `x0` of the
/// force's dofs) under the linearization `lin` of a motion, each followed by its own tracker
/// along `J₀ + t (N - J₀)`, `t = 0.1, 0.2, …, 1` (as [`eigenvalues_on_cycle`]).
pub fn eigenvalues_under(
    mb: &ModalBrake,
    force: &ContactForce,
    lin: &MultiLinearization,
    x0: &[f64],
    lambdas0: &[c64],
) -> Result<Vec<c64>, HbmError> {
    let (k0, c0) = reference_jacobian(force, x0);
    let n = k0.nrows();
    let empty = Mat::<f64>::zeros(n, 0);
    lambdas0
        .iter()
        .map(|&l| {
            let mut t = BrakeEigen::new(mb, None);
            let mut last = l;
            for step in 1..=HOMOTOPY_STEPS {
                let s = step as f64 / HOMOTOPY_STEPS as f64;
                let k = Mat::from_fn(n, n, |i, j| k0[(i, j)] + s * (lin.n_k[(i, j)] - k0[(i, j)]));
                let c = Mat::from_fn(n, n, |i, j| c0[(i, j)] + s * (lin.n_c[(i, j)] - c0[(i, j)]));
                let update = LinearUpdate {
                    k0: k.as_ref(),
                    c0: c.as_ref(),
                    left_k: empty.as_ref(),
                    left_c: empty.as_ref(),
                    right: empty.as_ref(),
                };
                last = t.track(&update, last)?.lambda;
            }
            Ok(last)
        })
        .collect()
}

/// The verdict of the cycles (Hill's stability of each).
pub fn verdict(cycles: &[ModeCycle]) -> Verdict {
    let mut stable = Vec::new();
    for c in cycles {
        match c.stability() {
            Some(CycleStability::Stable) => stable.push(c.mode),
            Some(CycleStability::Unstable) => {}
            _ => return Verdict::Undecided,
        }
    }
    match stable.len() {
        0 => Verdict::QuasiPeriodic,
        1 => Verdict::Periodic { mode: stable[0] },
        _ => Verdict::Multistable { modes: stable },
    }
}
