//! Harmonic balance equations, eq. (26): `Lambda(omega) U~ + F~_nl(U~, omega) = F~_ext`,
//! for forced systems (known `omega`) and autonomous systems (unknown `omega` plus a phase
//! condition).

use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{MatMut, MatRef};

use crate::HbmError;
use crate::aft::{Aft, TimeSamples};
use crate::force::{NonlinearForce, validate_pattern};
use crate::layout::{HarmonicLayout, Part};
use crate::linear::DynamicStiffness;
use crate::lm::{self, LeastSquaresProblem, LmError, LmOptions, LmReport};

/// The harmonic balance residual of eq. (26) (eq. 34 / `f1` of eq. 46 when `linear` is the
/// condensed `Lambda_eq`) for one layout, one linear part and one nonlinear force.
///
/// This is the building block: [`AutonomousProblem`] and [`ForcedProblem`] wrap it as
/// least-squares problems, and a constrained method adds its own rows (e.g. `f2`, eq. 47)
/// around [`Self::residual`] and [`Self::jacobian`].
pub struct HarmonicBalance<L, F> {
    layout: HarmonicLayout,
    aft: Aft,
    linear: L,
    force: F,
    f_ext: Vec<f64>,
    f_nl: Vec<f64>,
    work: Vec<f64>,
}

impl<L: DynamicStiffness, F: NonlinearForce> HarmonicBalance<L, F> {
    /// Assembles the problem. `f_ext` holds the Fourier coefficients `F~_ext` of the
    /// external force in the layout of eq. (25) (for an autonomous system only block 0, the
    /// static load, may be nonzero). `n_samples` overrides [`crate::default_samples`].
    pub fn new(
        layout: HarmonicLayout,
        linear: L,
        force: F,
        f_ext: Vec<f64>,
        n_samples: Option<usize>,
    ) -> Result<Self, HbmError> {
        let n = layout.n_dofs();
        for (what, got) in [
            ("linear part dofs", linear.n_dofs()),
            ("nonlinear force dofs", force.n_dofs()),
        ] {
            if got != n {
                return Err(HbmError::Dimension {
                    what,
                    expected: n,
                    got,
                });
            }
        }
        validate_pattern(force.pattern(), n)?;
        layout.check_len("external force coefficients", f_ext.len())?;
        if f_ext.iter().any(|v| !v.is_finite()) {
            return Err(HbmError::NonFiniteInput {
                what: "external force coefficients",
            });
        }
        let aft = match n_samples {
            Some(s) => Aft::new(layout, s)?,
            None => Aft::with_default_samples(layout)?,
        };
        let len = layout.len();
        Ok(Self {
            layout,
            aft,
            linear,
            force,
            f_ext,
            f_nl: vec![0.0; len],
            work: vec![0.0; len],
        })
    }

    /// The layout of `U~`.
    pub fn layout(&self) -> HarmonicLayout {
        self.layout
    }

    /// The AFT engine (sample count, time samples of the last evaluation).
    pub fn aft(&self) -> &Aft {
        &self.aft
    }

    /// The AFT engine, mutable (for conversions between coefficients and samples).
    pub fn aft_mut(&mut self) -> &mut Aft {
        &mut self.aft
    }

    /// The linear part `Lambda(omega)`.
    pub fn linear(&self) -> &L {
        &self.linear
    }

    /// The nonlinear force.
    pub fn force(&self) -> &F {
        &self.force
    }

    /// The linear part, mutable (to change a parameter of it, e.g. along a branch).
    pub fn linear_mut(&mut self) -> &mut L {
        &mut self.linear
    }

    /// The nonlinear force, mutable (to change a parameter of it, e.g. the friction
    /// coefficient along a branch).
    pub fn force_mut(&mut self) -> &mut F {
        &mut self.force
    }

    /// The external force coefficients, mutable (e.g. a load scaled along a branch). The
    /// caller keeps them finite.
    pub fn external_force_mut(&mut self) -> &mut [f64] {
        &mut self.f_ext
    }

    /// The external force coefficients `F~_ext`.
    pub fn external_force(&self) -> &[f64] {
        &self.f_ext
    }

    /// True if `F~_ext` has no harmonic content (only the static block 0 is nonzero).
    pub fn is_static_load(&self) -> bool {
        self.f_ext[self.layout.n_dofs()..].iter().all(|&v| v == 0.0)
    }

    /// Eq. (26): `r = Lambda(omega) u + F~_nl(u, omega) - F~_ext`.
    pub fn residual(&mut self, u: &[f64], omega: f64, r: &mut [f64]) -> Result<(), HbmError> {
        self.evaluate(u, omega, r).map(|_| ())
    }

    /// [`Self::residual`], returning what this very evaluation computed on the way: the
    /// nonlinear force's coefficients `F~_nl` and its time samples. A constraint on the cycle
    /// (CHBM's, eq. 47) reads them from here, never from a previous call.
    pub fn evaluate(
        &mut self,
        u: &[f64],
        omega: f64,
        r: &mut [f64],
    ) -> Result<Evaluation<'_>, HbmError> {
        self.layout.check_len("residual", r.len())?;
        self.aft.forces(&self.force, u, omega, &mut self.f_nl)?;
        for ((ri, &f), &e) in r.iter_mut().zip(&self.f_nl).zip(&self.f_ext) {
            *ri = f - e;
        }
        self.linear.add_apply(&self.layout, omega, u, r);
        Ok(Evaluation {
            force: &self.f_nl,
            samples: self.aft.samples(),
        })
    }

    /// Jacobian of eq. (26): `jac_u = Lambda(omega) + dF~_nl/dU~` (square, layout length,
    /// overwritten) and `jac_omega = (dLambda/domega) u + dF~_nl/domega` (overwritten).
    pub fn jacobian(
        &mut self,
        u: &[f64],
        omega: f64,
        mut jac_u: MatMut<'_, f64>,
        jac_omega: &mut [f64],
    ) -> Result<(), HbmError> {
        self.force_jacobian(u, omega, jac_u.rb_mut(), jac_omega)?;
        self.add_linear_jacobian(u, omega, jac_u, jac_omega);
        Ok(())
    }

    /// The nonlinear part of [`Self::jacobian`] alone: `jac_u = dF~_nl/dU~`,
    /// `jac_omega = dF~_nl/domega` (both overwritten); returns the force's coefficients and
    /// samples of the same evaluation.
    pub fn force_jacobian(
        &mut self,
        u: &[f64],
        omega: f64,
        jac_u: MatMut<'_, f64>,
        jac_omega: &mut [f64],
    ) -> Result<Evaluation<'_>, HbmError> {
        self.aft
            .forces_and_jacobian(&self.force, u, omega, &mut self.work, jac_u, jac_omega)?;
        Ok(Evaluation {
            force: &self.work,
            samples: self.aft.samples(),
        })
    }

    /// Adds the linear part `Lambda(omega)` to `jac_u` and `(dLambda/domega) u` to
    /// `jac_omega`.
    pub fn add_linear_jacobian(
        &mut self,
        u: &[f64],
        omega: f64,
        jac_u: MatMut<'_, f64>,
        jac_omega: &mut [f64],
    ) {
        self.linear
            .add_jacobian(&self.layout, omega, u, jac_u, jac_omega);
    }
}

/// What one residual evaluation computed besides the residual (borrowed from the harmonic
/// balance until its next evaluation).
#[derive(Clone, Copy, Debug)]
pub struct Evaluation<'a> {
    /// `F~_nl(U~, omega)` (layout of eq. 25).
    pub force: &'a [f64],
    /// The AFT time samples of this evaluation.
    pub samples: TimeSamples<'a>,
}

/// What a cycle constraint sees of one evaluation: the unknowns and the nonlinear force's
/// coefficients computed from them.
#[derive(Clone, Copy, Debug)]
pub struct CycleEval<'a> {
    pub layout: HarmonicLayout,
    /// `U~`.
    pub u: &'a [f64],
    pub omega: f64,
    /// `F~_nl(U~, omega)`.
    pub force: &'a [f64],
    /// The AFT time samples of the evaluation.
    pub samples: TimeSamples<'a>,
}

/// The nonlinear force's derivatives at a [`CycleEval`]: `dF~_nl/dU~` (layout length
/// square) and `dF~_nl/domega`.
#[derive(Clone, Copy, Debug)]
pub struct ForceDerivatives<'a> {
    pub du: MatRef<'a, f64>,
    pub domega: &'a [f64],
}

/// Extra equations on a periodic solution, appended to the harmonic balance residual of an
/// [`AutonomousProblem`]: CHBM's `f2` of eq. (47) is one ([`crate::ReLambda`]).
pub trait CycleConstraint {
    /// Number of rows added.
    fn rows(&self) -> usize;

    /// The rows' values at `eval`.
    fn residual(&mut self, eval: &CycleEval<'_>, out: &mut [f64]) -> Result<(), HbmError>;

    /// The rows' derivatives (`rows x (layout length + 1)`, columns `[U~, omega]`, every entry
    /// set) at `eval`, where the force's derivatives are `d`.
    fn jacobian(
        &mut self,
        eval: &CycleEval<'_>,
        d: &ForceDerivatives<'_>,
        out: MatMut<'_, f64>,
    ) -> Result<(), HbmError>;
}

/// No extra equation: plain autonomous harmonic balance.
#[derive(Clone, Copy, Debug, Default)]
pub struct Unconstrained;

impl CycleConstraint for Unconstrained {
    fn rows(&self) -> usize {
        0
    }

    fn residual(&mut self, _: &CycleEval<'_>, _: &mut [f64]) -> Result<(), HbmError> {
        Ok(())
    }

    fn jacobian(
        &mut self,
        _: &CycleEval<'_>,
        _: &ForceDerivatives<'_>,
        _: MatMut<'_, f64>,
    ) -> Result<(), HbmError> {
        Ok(())
    }
}

/// Phase condition that removes the time-shift invariance of an autonomous solution.
///
/// `FirstSineZero { dof }` imposes `U1s[dof] = 0`: the first harmonic of `dof` is a pure
/// cosine. It is safe because a time shift `t -> t + phi/omega` rotates every pair
/// `(Ukc, Uks)` by `k phi` (see [`HarmonicLayout::shift_phase`]), so every periodic
/// solution whose first harmonic on `dof` is nonzero has exactly two shifts satisfying it
/// (with `U1c[dof]` of either sign, half a period apart); the condition is linear and
/// its row is a unit vector, so it never degrades the conditioning. It fails only if the
/// first harmonic of `dof` vanishes on the sought cycle: choose a dof that moves in the
/// unstable mode ([`PhaseCondition::strongest_dof`] picks the largest first harmonic of a
/// guess).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PhaseCondition {
    /// `U1s[dof] = 0`.
    FirstSineZero {
        /// The dof whose first sine coefficient is fixed to zero.
        dof: usize,
    },
}

impl PhaseCondition {
    /// `FirstSineZero` on the dof with the largest first-harmonic amplitude in `u`.
    pub fn strongest_dof(layout: &HarmonicLayout, u: &[f64]) -> Result<Self, HbmError> {
        layout.check_len("coefficients", u.len())?;
        let mut best = (0, f64::NEG_INFINITY);
        for dof in 0..layout.n_dofs() {
            let a = layout.amplitude(u, 1, dof).unwrap_or(0.0);
            if a > best.1 {
                best = (dof, a);
            }
        }
        Ok(PhaseCondition::FirstSineZero { dof: best.0 })
    }

    /// Index in `U~` of the constrained coefficient.
    pub fn index(&self, layout: &HarmonicLayout) -> Result<usize, HbmError> {
        let PhaseCondition::FirstSineZero { dof } = *self;
        layout
            .index(1, Part::Sin, dof)
            .ok_or(HbmError::BadPhaseCondition {
                dof,
                n_dofs: layout.n_dofs(),
                n_harmonics: layout.n_harmonics(),
            })
    }
}

/// A converged harmonic balance solution.
#[derive(Clone, Debug, PartialEq)]
pub struct HbSolution {
    /// Fourier coefficients `U~` (layout of eq. 25).
    pub coeffs: Vec<f64>,
    /// Fundamental angular frequency `omega` (rad/s).
    pub omega: f64,
    /// The Levenberg-Marquardt report (history, iteration count).
    pub report: LmReport,
}

impl HbSolution {
    /// Period `T = 2 pi / omega`.
    pub fn period(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.omega
    }
}

/// How the rows of an [`AutonomousProblem`] are scaled: the harmonic balance rows are
/// divided by `force` (a force level, e.g. the static load's norm) and the phase row by
/// `phase` (a displacement level), so that both are of order one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RowScales {
    pub force: f64,
    pub phase: f64,
}

impl Default for RowScales {
    fn default() -> Self {
        Self {
            force: 1.0,
            phase: 1.0,
        }
    }
}

/// Autonomous harmonic balance as a least-squares problem in `z = [U~, omega]`: residual
/// `[eq. (26) / force; U1s[dof] / phase; constraint rows]` (`n (2H+1) + 1 + rows` rows).
/// With [`Unconstrained`] it is square; CHBM adds `f2` of eq. (47) ([`crate::ReLambda`]).
pub struct AutonomousProblem<'a, L, F, C = Unconstrained> {
    hb: &'a mut HarmonicBalance<L, F>,
    phase_index: usize,
    scales: RowScales,
    constraint: C,
    jac_omega: Vec<f64>,
    history: Vec<RowNorms>,
}

/// One residual evaluation of an [`AutonomousProblem`], for convergence histories (the
/// paper's Figures 6–7).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RowNorms {
    /// `||eq. (26)|| / force scale`.
    pub harmonic_balance: f64,
    /// The frequency of the evaluated point.
    pub omega: f64,
    /// The constraint rows' norm.
    pub constraint: f64,
}

impl<'a, L: DynamicStiffness, F: NonlinearForce> AutonomousProblem<'a, L, F, Unconstrained> {
    /// Wraps `hb` with a phase condition; fails if the external force is periodic.
    pub fn new(hb: &'a mut HarmonicBalance<L, F>, phase: PhaseCondition) -> Result<Self, HbmError> {
        Self::constrained(hb, phase, Unconstrained, RowScales::default())
    }
}

impl<'a, L: DynamicStiffness, F: NonlinearForce, C: CycleConstraint>
    AutonomousProblem<'a, L, F, C>
{
    /// Wraps `hb` with a phase condition, row scales and a constraint.
    pub fn constrained(
        hb: &'a mut HarmonicBalance<L, F>,
        phase: PhaseCondition,
        constraint: C,
        scales: RowScales,
    ) -> Result<Self, HbmError> {
        if !hb.is_static_load() {
            return Err(HbmError::PeriodicForcingWithUnknownFrequency);
        }
        for (what, v) in [("force scale", scales.force), ("phase scale", scales.phase)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(HbmError::BadScale { what, value: v });
            }
        }
        let phase_index = phase.index(&hb.layout)?;
        let len = hb.layout.len();
        Ok(Self {
            hb,
            phase_index,
            scales,
            constraint,
            jac_omega: vec![0.0; len],
            history: Vec::new(),
        })
    }

    /// Every residual evaluation so far.
    pub fn history(&self) -> &[RowNorms] {
        &self.history
    }

    /// The constraint (e.g. for its diagnostics after a solve).
    pub fn constraint(&self) -> &C {
        &self.constraint
    }

    /// The constraint and the evaluation history, giving up the problem.
    pub fn into_parts(self) -> (C, Vec<RowNorms>) {
        (self.constraint, self.history)
    }

    /// The harmonic balance.
    pub fn harmonic_balance(&mut self) -> &mut HarmonicBalance<L, F> {
        self.hb
    }
}

impl<L: DynamicStiffness, F: NonlinearForce, C: CycleConstraint> LeastSquaresProblem
    for AutonomousProblem<'_, L, F, C>
{
    type Error = HbmError;

    fn n_params(&self) -> usize {
        self.hb.layout.len() + 1
    }

    fn n_residuals(&self) -> usize {
        self.hb.layout.len() + 1 + self.constraint.rows()
    }

    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), HbmError> {
        let len = self.hb.layout.len();
        check_len("unknowns [U~, omega]", len + 1, z.len())?;
        check_len("residual", self.n_residuals(), r.len())?;
        let (u, omega) = (&z[..len], z[len]);
        let layout = self.hb.layout;
        let (rows, rest) = r.split_at_mut(len);
        let eval = match self.hb.evaluate(u, omega, rows) {
            Ok(e) => e,
            Err(HbmError::NonFiniteForce { .. }) => {
                // A bad trial point, not a failure: LM rejects the step and raises the damping.
                r.fill(f64::NAN);
                return Ok(());
            }
            Err(e) => return Err(e),
        };
        let cycle = CycleEval {
            layout,
            u,
            omega,
            force: eval.force,
            samples: eval.samples,
        };
        rest[0] = u[self.phase_index] / self.scales.phase;
        self.constraint.residual(&cycle, &mut rest[1..])?;
        let inv = 1.0 / self.scales.force;
        for v in rows.iter_mut() {
            *v *= inv;
        }
        let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
        self.history.push(RowNorms {
            harmonic_balance: norm(rows),
            omega,
            constraint: norm(&rest[1..]),
        });
        Ok(())
    }

    fn jacobian(&mut self, z: &[f64], mut jac: MatMut<'_, f64>) -> Result<(), HbmError> {
        let len = self.hb.layout.len();
        check_len("unknowns [U~, omega]", len + 1, z.len())?;
        check_len("Jacobian rows", self.n_residuals(), jac.nrows())?;
        check_len("Jacobian columns", len + 1, jac.ncols())?;
        let (u, omega) = (&z[..len], z[len]);
        let rows = self.constraint.rows();
        {
            let (mut top, bottom) = jac.rb_mut().split_at_row_mut(len);
            let layout = self.hb.layout;
            let eval = self.hb.force_jacobian(
                u,
                omega,
                top.rb_mut().subcols_mut(0, len),
                &mut self.jac_omega,
            )?;
            if rows > 0 {
                // The constraint reads the force and its derivatives of this very point.
                let cycle = CycleEval {
                    layout,
                    u,
                    omega,
                    force: eval.force,
                    samples: eval.samples,
                };
                let d = ForceDerivatives {
                    du: top.rb().subcols(0, len),
                    domega: &self.jac_omega,
                };
                self.constraint
                    .jacobian(&cycle, &d, bottom.subrows_mut(1, rows))?;
            }
        }
        self.hb.add_linear_jacobian(
            u,
            omega,
            jac.rb_mut().submatrix_mut(0, 0, len, len),
            &mut self.jac_omega,
        );
        let inv = 1.0 / self.scales.force;
        for i in 0..len {
            jac[(i, len)] = self.jac_omega[i];
        }
        for j in 0..=len {
            for v in jac.rb_mut().col_mut(j).subrows_mut(0, len).iter_mut() {
                *v *= inv;
            }
            jac[(len, j)] = 0.0;
        }
        jac[(len, self.phase_index)] = 1.0 / self.scales.phase;
        Ok(())
    }
}

/// Forced harmonic balance at a fixed `omega` as a square least-squares problem in `U~`.
pub struct ForcedProblem<'a, L, F> {
    hb: &'a mut HarmonicBalance<L, F>,
    omega: f64,
    jac_omega: Vec<f64>,
}

impl<'a, L: DynamicStiffness, F: NonlinearForce> ForcedProblem<'a, L, F> {
    /// Wraps `hb` at the excitation frequency `omega` (finite, > 0).
    pub fn new(hb: &'a mut HarmonicBalance<L, F>, omega: f64) -> Result<Self, HbmError> {
        if !(omega.is_finite() && omega > 0.0) {
            return Err(HbmError::BadFrequency { omega });
        }
        let len = hb.layout.len();
        Ok(Self {
            hb,
            omega,
            jac_omega: vec![0.0; len],
        })
    }
}

impl<L: DynamicStiffness, F: NonlinearForce> LeastSquaresProblem for ForcedProblem<'_, L, F> {
    type Error = HbmError;

    fn n_params(&self) -> usize {
        self.hb.layout.len()
    }

    fn n_residuals(&self) -> usize {
        self.hb.layout.len()
    }

    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), HbmError> {
        nan_on_nonfinite(self.hb.residual(z, self.omega, r), r)
    }

    fn jacobian(&mut self, z: &[f64], jac: MatMut<'_, f64>) -> Result<(), HbmError> {
        self.hb.jacobian(z, self.omega, jac, &mut self.jac_omega)
    }
}

fn check_len(what: &'static str, expected: usize, got: usize) -> Result<(), HbmError> {
    if expected == got {
        Ok(())
    } else {
        Err(HbmError::Dimension {
            what,
            expected,
            got,
        })
    }
}

/// A non-finite force is a bad trial point, not a failure: report it as a NaN residual so
/// that Levenberg-Marquardt rejects the step and increases the damping.
fn nan_on_nonfinite(result: Result<(), HbmError>, r: &mut [f64]) -> Result<(), HbmError> {
    match result {
        Err(HbmError::NonFiniteForce { .. }) => {
            r.fill(f64::NAN);
            Ok(())
        }
        other => other,
    }
}

pub(crate) fn from_lm(e: LmError<HbmError>) -> HbmError {
    match e {
        LmError::BadOption(s) | LmError::BadSize(s) => HbmError::BadOption(s),
        LmError::NonFiniteStart => HbmError::NonFiniteStart,
        LmError::NonFiniteJacobian { iteration } => HbmError::NonFiniteJacobian { iteration },
        LmError::Problem(e) => e,
        LmError::NotConverged { report } => HbmError::NotConverged { report },
    }
}

/// Solves the autonomous system `M x'' + C x' + K x + f_nl(x, x') = f_static` for a limit
/// cycle: unknowns `U~` and `omega`, equations (26) plus the phase condition.
///
/// `u0`, `omega0` are the caller's initial guess (amplitude and frequency, e.g. from the
/// unstable mode, eq. 48). If the guess has a nonzero first harmonic on the phase dof it is
/// first shifted in time to satisfy the phase condition (an equivalent guess).
///
/// Caveat: the static equilibrium (all harmonics zero, any `omega`) also solves these
/// equations; a guess too small may converge to it. Check the first-harmonic amplitude of
/// the result, or use a constrained method (the paper's CHBM) that excludes it.
pub fn solve_autonomous<L: DynamicStiffness, F: NonlinearForce>(
    hb: &mut HarmonicBalance<L, F>,
    phase: PhaseCondition,
    u0: &[f64],
    omega0: f64,
    options: &LmOptions,
) -> Result<HbSolution, HbmError> {
    let len = hb.layout().len();
    let z0 = autonomous_start(&hb.layout(), phase, u0, omega0)?;
    let mut problem = AutonomousProblem::new(hb, phase)?;
    let report = lm::solve(&mut problem, &z0, options).map_err(from_lm)?;
    Ok(autonomous_solution(report, len))
}

/// The unknowns `[U, ω]` an autonomous solve starts from: the guess checked (its length, finite
/// values, a positive frequency) and shifted in time so that it meets the phase condition.
pub(crate) fn autonomous_start(
    layout: &HarmonicLayout,
    phase: PhaseCondition,
    u0: &[f64],
    omega0: f64,
) -> Result<Vec<f64>, HbmError> {
    if !(omega0.is_finite() && omega0 > 0.0) {
        return Err(HbmError::BadFrequency { omega: omega0 });
    }
    layout.check_len("initial guess", u0.len())?;
    if u0.iter().any(|v| !v.is_finite()) {
        return Err(HbmError::NonFiniteInput {
            what: "initial guess",
        });
    }
    let PhaseCondition::FirstSineZero { dof } = phase;
    let mut z0 = u0.to_vec();
    if layout.amplitude(&z0, 1, dof).is_some_and(|a| a > 0.0) {
        layout.align_phase(&mut z0, dof)?;
    }
    z0.push(omega0);
    Ok(z0)
}

/// The coefficients and frequency of an autonomous solve's last iterate (`len` coefficients,
/// then ω).
pub(crate) fn autonomous_solution(report: lm::LmReport, len: usize) -> HbSolution {
    HbSolution {
        coeffs: report.x[..len].to_vec(),
        omega: report.x[len],
        report,
    }
}

/// Solves the forced system at the excitation frequency `omega` from the guess `u0`.
pub fn solve_forced<L: DynamicStiffness, F: NonlinearForce>(
    hb: &mut HarmonicBalance<L, F>,
    omega: f64,
    u0: &[f64],
    options: &LmOptions,
) -> Result<HbSolution, HbmError> {
    hb.layout().check_len("initial guess", u0.len())?;
    if u0.iter().any(|v| !v.is_finite()) {
        return Err(HbmError::NonFiniteInput {
            what: "initial guess",
        });
    }
    let mut problem = ForcedProblem::new(hb, omega)?;
    let report = lm::solve(&mut problem, u0, options).map_err(from_lm)?;
    Ok(HbSolution {
        coeffs: report.x.clone(),
        omega,
        report,
    })
}
