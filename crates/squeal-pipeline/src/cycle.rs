//! The scene's limit cycle: one rule for where it is computed and how CHBM starts, so that
//! `squeal chbm`, `squeal run` and a library user of [`Pipeline`] get the same cycle from the
//! same scene, bit for bit.
//!
//! **Where.** The scene says it once ([`Scene::cycle`]): at `[chbm] mu`, or at
//! `[chbm] mu_ratio` × μ0, else at 1.02 μ0; the command line may override it (`--mu`,
//! `--mu-ratio`) and the harmonics (`--harmonics`), never silently: [`CyclePlan::of_scene`]
//! then the overrides.
//!
//! **How it starts.** By default from the branch of limit cycles followed from the Hopf point
//! to μ ([`CycleStart::Branch`]: every crossing of μ is corrected and its Floquet stability
//! computed, CHBM starts from the first stable one), which reaches cycles below μ0 as well
//! (between a fold and μ0) and never mistakes a non-converged iterate for a cycle; or from the
//! paper's eq (48), the unstable mode at a guessed amplitude, tried at each amplitude in turn
//! ([`CycleStart::Guessed`]).

use crate::Pipeline;
use crate::chbm::{BranchCycle, solve_along_branch, solve_with_restarts};
use crate::error::{PipelineError, Result};
use squeal_chbm::{ChbmOptions, ChbmSolution, ChbmStart, Outcome};
use squeal_scene::{CycleFriction, Scene};
use std::time::Instant;

/// How CHBM starts at μ.
#[derive(Clone, Debug, PartialEq)]
pub enum CycleStart {
    /// From the branch of limit cycles followed from the Hopf point to μ (the default).
    Branch,
    /// From eq (48) at each of these initial amplitudes in turn (fractions of the smallest
    /// static penetration) until one converges.
    Guessed { amplitudes: Vec<f64> },
}

/// Which limit cycle to compute and how.
#[derive(Clone, Debug)]
pub struct CyclePlan {
    /// Where.
    pub at: CycleFriction,
    /// CHBM's options (harmonics, AFT samples, ladder).
    pub options: ChbmOptions,
    /// How CHBM starts.
    pub start: CycleStart,
}

impl CyclePlan {
    /// The scene's limit cycle ([`Scene::cycle`]), started from the branch.
    pub fn of_scene(scene: &Scene) -> Result<Self> {
        let spec = scene.cycle()?;
        Ok(Self {
            at: spec.at,
            options: {
                let mut o = ChbmOptions::default();
                o.harmonics = spec.harmonics;
                o
            },
            start: CycleStart::Branch,
        })
    }
}

/// A computed limit cycle and how it was reached.
pub struct LimitCycle {
    /// The friction it was computed at.
    pub mu: f64,
    /// The Hopf point μ0 (`None` when the sweep found none: a guessed start at an absolute
    /// friction does not need it).
    pub mu0: Option<f64>,
    /// Every crossing of μ by the branch, with its stability (empty for a guessed start).
    pub crossings: Vec<BranchCycle>,
    /// The crossing CHBM started from.
    pub chosen: Option<usize>,
    /// The initial amplitude of the guessed start that converged (or the last one tried).
    pub amplitude: Option<f64>,
    /// CHBM's start and its solution; `None` when the branch does not reach μ (no limit cycle
    /// of this branch there).
    pub solved: Option<(ChbmStart, ChbmSolution)>,
}

impl LimitCycle {
    /// The solution when it is a limit cycle; never a non-converged iterate.
    pub fn cycle(&self) -> Option<&ChbmSolution> {
        self.solved
            .as_ref()
            .map(|(_, s)| s)
            .filter(|s| s.outcome == Outcome::LimitCycle)
    }
}

impl Pipeline<'_> {
    /// The friction a plan asks for: its own, or its ratio times μ0.
    pub fn cycle_mu(&self, at: CycleFriction) -> Result<f64> {
        at.mu(|| self.mu0())
    }

    /// The limit cycle of `plan` (the reduced model, the sweep and the Hopf point computed on
    /// the way as needed, and kept).
    pub fn limit_cycle(&self, plan: &CyclePlan) -> Result<LimitCycle> {
        let mu = self.cycle_mu(plan.at)?;
        let m = self.model()?;
        let st = self.stability()?;
        let mu0 = st.sweep.hopf.as_ref().map(|h| h.mu0);
        let t = Instant::now();
        let lc = match &plan.start {
            CycleStart::Branch => {
                if mu0.is_none() {
                    self.mu0()?;
                }
                let (crossings, chosen) = solve_along_branch(m, st, mu, &plan.options, self.log())?;
                self.record("CHBM along the branch", t.elapsed().as_secs_f64());
                let (chosen, solved) = match chosen {
                    Some((i, start, sol)) => (Some(i), Some((start, sol))),
                    None => (None, None),
                };
                LimitCycle {
                    mu,
                    mu0,
                    crossings,
                    chosen,
                    amplitude: None,
                    solved,
                }
            }
            CycleStart::Guessed { amplitudes } => {
                if amplitudes.is_empty() {
                    return Err(PipelineError::input("initial amplitudes", "none given"));
                }
                let (start, modal) = self.chbm_start(mu)?;
                let (sol, a) =
                    solve_with_restarts(&modal, &start, &plan.options, amplitudes, self.log())?;
                self.record("CHBM", t.elapsed().as_secs_f64());
                LimitCycle {
                    mu,
                    mu0,
                    crossings: Vec::new(),
                    chosen: None,
                    amplitude: Some(a),
                    solved: Some((start, sol)),
                }
            }
        };
        Ok(lc)
    }
}
