//! Continuation of periodic solutions in a parameter: pseudo-arclength predictor–corrector on
//! the harmonic balance unknowns `z = [U~, ω, p]` (Keller's method; as NLvib, MANLAB and pyHarm
//! do).
//!
//! A [`Family`] gives the `L + 1` equations `R(z) = [eq. (26); phase condition]` in the
//! `L + 2` unknowns and their Jacobian `[∂R/∂(U~, ω), ∂R/∂p]`: a curve of solutions. From a
//! point `z_k` with unit tangent `t_k` (in scaled unknowns `Wz`), the predictor is
//! `z = z_k + s t_k` and the corrector solves the square system
//!
//! `R(z) = 0`,  `t_kᵀ W (z - z_k) = s`
//!
//! by Newton's method, which goes through turning points (folds) of the parameter because the
//! bordered matrix `[[J], [t_kᵀ W]]` stays regular there. The new tangent is the null vector of
//! `J` at the new point, oriented along `t_k`. The step `s` grows or shrinks with the number
//! of Newton iterations (aiming at [`ContinuationOptions::target_iterations`]) and is halved
//! when Newton fails; the branch ends at the parameter range, the point budget, an observer's
//! request, or a step below [`ContinuationOptions::min_step`] (loss of convergence), each
//! reported as what it is ([`Stop`]).

use faer::linalg::solvers::Solve;
use faer::reborrow::ReborrowMut;
use faer::{Mat, MatMut};

use crate::HbmError;
use crate::force::NonlinearForce;
use crate::hb::{HarmonicBalance, PhaseCondition, RowScales};
use crate::layout::HarmonicLayout;
use crate::linear::DynamicStiffness;

/// A one-parameter family of periodic solutions: `R(U~, ω, p) = 0` (`L + 1` equations).
pub trait Family {
    /// The layout of `U~` (its harmonics may change between calls of
    /// [`Family::set_harmonics`]).
    fn layout(&self) -> HarmonicLayout;

    /// `R` at `z = [U~, ω, p]` (`L + 1` values).
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), HbmError>;

    /// `∂R/∂z` (`(L + 1) × (L + 2)`, every entry set).
    fn jacobian(&mut self, z: &[f64], jac: MatMut<'_, f64>) -> Result<(), HbmError>;

    /// Changes the number of harmonics (the caller maps the unknowns between layouts).
    fn set_harmonics(&mut self, harmonics: usize) -> Result<(), HbmError>;
}

/// Controls of [`continue_branch`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct ContinuationOptions {
    /// First arclength step (scaled unknowns).
    pub initial_step: f64,
    /// Smallest step: below it the branch is lost ([`Stop::LostConvergence`]).
    pub min_step: f64,
    /// Largest step.
    pub max_step: f64,
    /// Newton iterations aimed at per point (the step grows when fewer were needed).
    pub target_iterations: usize,
    /// Newton iterations allowed per point before the step is halved.
    pub max_iterations: usize,
    /// Converged when `||R|| <= tolerance` ...
    pub tolerance: f64,
    /// ... and the last Newton step is below this (scaled unknowns).
    pub step_tolerance: f64,
    /// The parameter range; the branch ends when it leaves it.
    pub parameter_range: (f64, f64),
    /// Points at the most.
    pub max_points: usize,
}

impl Default for ContinuationOptions {
    fn default() -> Self {
        Self {
            initial_step: 1e-2,
            min_step: 1e-7,
            max_step: 0.5,
            target_iterations: 4,
            max_iterations: 12,
            tolerance: 1e-9,
            step_tolerance: 1e-10,
            parameter_range: (f64::NEG_INFINITY, f64::INFINITY),
            max_points: 200,
        }
    }
}

/// One converged point of a branch.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// `[U~, ω, p]`.
    pub z: Vec<f64>,
    /// Harmonics of `U~`.
    pub harmonics: usize,
    /// Unit tangent (scaled unknowns), oriented along the branch.
    pub tangent: Vec<f64>,
    /// Newton iterations.
    pub iterations: usize,
    /// Final `||R||`.
    pub residual: f64,
    /// The arclength step that reached it.
    pub step: f64,
}

impl Point {
    /// The parameter.
    pub fn parameter(&self) -> f64 {
        self.z[self.z.len() - 1]
    }

    /// ω.
    pub fn omega(&self) -> f64 {
        self.z[self.z.len() - 2]
    }

    /// The parameter's component of the tangent (its sign change marks a fold).
    pub fn parameter_rate(&self) -> f64 {
        self.tangent[self.tangent.len() - 1]
    }
}

/// Why a branch ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Stop {
    /// The parameter left its range.
    ParameterRange,
    /// [`ContinuationOptions::max_points`] points.
    MaxPoints,
    /// Newton failed at every step down to [`ContinuationOptions::min_step`]: the branch could
    /// not be followed further (e.g. a non-smooth event the harmonics cannot resolve).
    LostConvergence {
        /// The last step tried.
        step: f64,
        /// `||R||` at the last failed iterate.
        residual: f64,
    },
    /// The observer asked to stop, with its reason.
    Observer(String),
}

impl std::fmt::Display for Stop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stop::ParameterRange => f.write_str("the parameter left its range"),
            Stop::MaxPoints => f.write_str("the point budget was used"),
            Stop::LostConvergence { step, residual } => write!(
                f,
                "convergence lost: Newton failed down to a step of {step:.1e} (residual {residual:.1e})"
            ),
            Stop::Observer(why) => f.write_str(why),
        }
    }
}

/// What the observer of [`continue_branch`] says after each point.
#[derive(Clone, Debug, PartialEq)]
pub enum Control {
    /// Go on.
    Continue,
    /// Go on with another number of harmonics: the point is corrected again at the new
    /// layout (in the hyperplane normal to its tangent) before the branch goes on.
    Harmonics(usize),
    /// End the branch, for this reason.
    Stop(String),
}

/// A followed branch.
#[derive(Clone, Debug)]
pub struct Branch {
    /// The converged points, in order along the branch.
    pub points: Vec<Point>,
    /// Why it ended.
    pub stop: Stop,
}

/// `z` with `U~` mapped from `from` harmonics to `to` (dropped or zero harmonics).
pub fn remap(z: &[f64], n_dofs: usize, from: usize, to: usize) -> Vec<f64> {
    let (lf, lt) = (n_dofs * (2 * from + 1), n_dofs * (2 * to + 1));
    let mut out = vec![0.0; lt + 2];
    let m = lf.min(lt);
    out[..m].copy_from_slice(&z[..m]);
    out[lt] = z[lf];
    out[lt + 1] = z[lf + 1];
    out
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// What a corrector run gave.
enum Correction {
    /// The point, its Newton iterations and `||R||`.
    Converged(Vec<f64>, usize, f64),
    /// No convergence; the last `||R||`.
    Failed(f64),
}

/// Newton on `R(z) = 0` plus one more equation `c · z = target` (`c` a row).
fn correct<F: Family>(
    family: &mut F,
    z0: &[f64],
    row: &[f64],
    target: f64,
    w: &[f64],
    opts: &ContinuationOptions,
) -> Result<Correction, HbmError> {
    let n = z0.len();
    let mut z = z0.to_vec();
    let mut r = vec![0.0; n - 1];
    let mut jac = Mat::<f64>::zeros(n, n);
    let mut last = f64::INFINITY;
    for it in 1..=opts.max_iterations {
        family.residual(&z, &mut r)?;
        let extra = row.iter().zip(&z).map(|(a, b)| a * b).sum::<f64>() - target;
        last = norm(&r);
        if !last.is_finite() {
            return Ok(Correction::Failed(last));
        }
        family.jacobian(&z, jac.as_mut().subrows_mut(0, n - 1))?;
        for (j, &c) in row.iter().enumerate() {
            jac[(n - 1, j)] = c;
        }
        let rhs = Mat::from_fn(n, 1, |i, _| if i < n - 1 { -r[i] } else { -extra });
        let dz = jac.partial_piv_lu().solve(&rhs);
        if (0..n).any(|i| !dz[(i, 0)].is_finite()) {
            return Ok(Correction::Failed(last));
        }
        for (i, v) in z.iter_mut().enumerate() {
            *v += dz[(i, 0)];
        }
        let step = (0..n)
            .map(|i| (w[i] * dz[(i, 0)]).powi(2))
            .sum::<f64>()
            .sqrt();
        if last <= opts.tolerance && step <= opts.step_tolerance {
            family.residual(&z, &mut r)?;
            return Ok(Correction::Converged(z, it, norm(&r)));
        }
        if step <= opts.step_tolerance {
            family.residual(&z, &mut r)?;
            let rn = norm(&r);
            if rn <= opts.tolerance {
                return Ok(Correction::Converged(z, it, rn));
            }
        }
    }
    Ok(Correction::Failed(last))
}

/// Newton on the family's equations plus `row · z = value` (e.g. a fixed amplitude, or a
/// fixed parameter) from `z0`: the converged point, or `None` when Newton fails within
/// [`ContinuationOptions::max_iterations`]. `w` weights the unknowns as in
/// [`continue_branch`] (for the step tolerance). The returned point's tangent is oriented along
/// `along`.
pub fn correct_point<F: Family>(
    family: &mut F,
    z0: &[f64],
    row: &[f64],
    value: f64,
    w: &[f64],
    along: &[f64],
    opts: &ContinuationOptions,
) -> Result<Option<Point>, HbmError> {
    match correct(family, z0, row, value, w, opts)? {
        Correction::Converged(z, iterations, residual) => {
            let tangent = tangent(family, &z, w, along)?;
            Ok(Some(Point {
                z,
                harmonics: family.layout().n_harmonics(),
                tangent,
                iterations,
                residual,
                step: 0.0,
            }))
        }
        Correction::Failed(_) => Ok(None),
    }
}

/// The unit tangent at `z` (null vector of `J`, in scaled unknowns), oriented along `along`.
fn tangent<F: Family>(
    family: &mut F,
    z: &[f64],
    w: &[f64],
    along: &[f64],
) -> Result<Vec<f64>, HbmError> {
    let n = z.len();
    let mut jac = Mat::<f64>::zeros(n, n);
    family.jacobian(z, jac.as_mut().subrows_mut(0, n - 1))?;
    // In scaled unknowns ζ = W z: J W⁻¹ t = 0, with the bordering row `along`.
    for j in 0..n {
        for i in 0..n - 1 {
            jac[(i, j)] /= w[j];
        }
        jac[(n - 1, j)] = along[j];
    }
    let rhs = Mat::from_fn(n, 1, |i, _| if i == n - 1 { 1.0 } else { 0.0 });
    let t = jac.partial_piv_lu().solve(&rhs);
    let mut t: Vec<f64> = (0..n).map(|i| t[(i, 0)]).collect();
    let s = norm(&t);
    if !(s.is_finite() && s > 0.0) {
        return Err(HbmError::SingularTangent);
    }
    for v in &mut t {
        *v /= s;
    }
    Ok(t)
}

/// Follows the branch of `family` from the solution `z0` (converged, `[U~, ω, p]`) in the
/// direction `direction` (scaled unknowns: its sign selects the way along the branch),
/// weighting the unknowns by `w` (e.g. the inverse of their typical sizes). `observer` is
/// told every point (the first is `z0`) and may ask for other harmonics or to stop.
pub fn continue_branch<F: Family>(
    family: &mut F,
    z0: &[f64],
    direction: &[f64],
    weights: impl Fn(&HarmonicLayout) -> Vec<f64>,
    opts: &ContinuationOptions,
    observer: impl FnMut(&Point) -> Control,
) -> Result<Branch, HbmError> {
    let w = weights(&family.layout());
    let t = tangent(family, z0, &w, direction)?;
    let start = Point {
        z: z0.to_vec(),
        harmonics: family.layout().n_harmonics(),
        tangent: t,
        iterations: 0,
        residual: 0.0,
        step: 0.0,
    };
    continue_from(family, start, weights, opts, observer)
}

/// [`continue_branch`] from a point that carries its tangent (e.g. from [`correct_point`]).
pub fn continue_from<F: Family>(
    family: &mut F,
    start: Point,
    weights: impl Fn(&HarmonicLayout) -> Vec<f64>,
    opts: &ContinuationOptions,
    mut observer: impl FnMut(&Point) -> Control,
) -> Result<Branch, HbmError> {
    let mut w = weights(&family.layout());
    let mut z = start.z.clone();
    let mut t = start.tangent.clone();
    let mut points = Vec::new();
    let mut step = opts.initial_step;
    let mut point = start;
    loop {
        // The observer may change the harmonics: the point is corrected again at fixed
        // parameter, then the branch goes on from it.
        let mut control = observer(&point);
        while let Control::Harmonics(h) = control {
            let layout = family.layout();
            let zr = remap(&point.z, layout.n_dofs(), layout.n_harmonics(), h);
            family.set_harmonics(h)?;
            w = weights(&family.layout());
            // Corrected in the hyperplane normal to the tangent through the point: well posed
            // at a fold, where a fixed parameter is not.
            let along = remap(&point.tangent, layout.n_dofs(), layout.n_harmonics(), h);
            let row: Vec<f64> = along.iter().zip(&w).map(|(t, w)| t * w).collect();
            let value = row.iter().zip(&zr).map(|(a, b)| a * b).sum::<f64>();
            match correct(family, &zr, &row, value, &w, opts)? {
                Correction::Converged(zc, it, res) => {
                    let tc = tangent(family, &zc, &w, &along)?;
                    point = Point {
                        z: zc,
                        harmonics: h,
                        tangent: tc,
                        iterations: point.iterations + it,
                        residual: res,
                        step: point.step,
                    };
                    control = observer(&point);
                }
                Correction::Failed(res) => {
                    points.push(point);
                    return Ok(Branch {
                        points,
                        stop: Stop::LostConvergence {
                            step: 0.0,
                            residual: res,
                        },
                    });
                }
            }
        }
        z.clone_from(&point.z);
        t.clone_from(&point.tangent);
        points.push(point.clone());
        if let Control::Stop(why) = control {
            return Ok(Branch {
                points,
                stop: Stop::Observer(why),
            });
        }
        let p = z[z.len() - 1];
        if p < opts.parameter_range.0 || p > opts.parameter_range.1 {
            return Ok(Branch {
                points,
                stop: Stop::ParameterRange,
            });
        }
        if points.len() >= opts.max_points {
            return Ok(Branch {
                points,
                stop: Stop::MaxPoints,
            });
        }
        // Predictor and corrector, halving the step until Newton converges.
        let n = z.len();
        let (zc, it, res) = loop {
            let pred: Vec<f64> = (0..n).map(|i| z[i] + step * t[i] / w[i]).collect();
            // t_kᵀ W (z - z_k) = s  ⇔  Σ t_i w_i z_i = s + Σ t_i w_i z_k,i.
            let row: Vec<f64> = (0..n).map(|i| t[i] * w[i]).collect();
            let target = step + row.iter().zip(&z).map(|(a, b)| a * b).sum::<f64>();
            match correct(family, &pred, &row, target, &w, opts)? {
                Correction::Converged(zc, it, res) => break (zc, it, res),
                Correction::Failed(res) => {
                    step *= 0.5;
                    if step < opts.min_step {
                        return Ok(Branch {
                            points,
                            stop: Stop::LostConvergence {
                                step,
                                residual: res,
                            },
                        });
                    }
                }
            }
        };
        let tc = tangent(family, &zc, &w, &t)?;
        let used = step;
        let factor = (opts.target_iterations as f64 / it.max(1) as f64).clamp(0.5, 2.0);
        step = (step * factor).clamp(opts.min_step, opts.max_step);
        point = Point {
            z: zc,
            harmonics: family.layout().n_harmonics(),
            tangent: tc,
            iterations: it,
            residual: res,
            step: used,
        };
    }
}

/// A [`Family`] from a harmonic balance and a parameter: `build(h)` makes the harmonic
/// balance with `h` harmonics, `set(hb, p)` puts the parameter into it. The equations are
/// eq. (26) divided by `scales.force` and the phase condition `U1s[dof] / scales.phase`;
/// `∂R/∂p` is taken by central differences of the residual (`step` in `p`), which is exact
/// up to round-off when the residual is linear in `p` (friction in Coulomb's law, a load).
pub struct HbFamily<L, F, B, S> {
    build: B,
    set: S,
    hb: HarmonicBalance<L, F>,
    phase_dof: usize,
    scales: RowScales,
    step: f64,
    work: Vec<f64>,
}

impl<L, F, B, S> HbFamily<L, F, B, S>
where
    L: DynamicStiffness,
    F: NonlinearForce,
    B: FnMut(usize) -> Result<HarmonicBalance<L, F>, HbmError>,
    S: FnMut(&mut HarmonicBalance<L, F>, f64) -> Result<(), HbmError>,
{
    /// The family with `harmonics` harmonics to start with.
    pub fn new(
        mut build: B,
        set: S,
        harmonics: usize,
        phase: PhaseCondition,
        scales: RowScales,
        step: f64,
    ) -> Result<Self, HbmError> {
        let hb = build(harmonics)?;
        let PhaseCondition::FirstSineZero { dof } = phase;
        phase.index(&hb.layout())?;
        Ok(Self {
            build,
            set,
            hb,
            phase_dof: dof,
            scales,
            step,
            work: Vec::new(),
        })
    }

    /// The harmonic balance at its current parameter.
    pub fn harmonic_balance(&mut self) -> &mut HarmonicBalance<L, F> {
        &mut self.hb
    }

    fn rows(&mut self, z: &[f64], p: f64, r: &mut [f64]) -> Result<(), HbmError> {
        let layout = self.hb.layout();
        let l = layout.len();
        (self.set)(&mut self.hb, p)?;
        self.hb.residual(&z[..l], z[l], &mut r[..l])?;
        for v in &mut r[..l] {
            *v /= self.scales.force;
        }
        let i = PhaseCondition::FirstSineZero {
            dof: self.phase_dof,
        }
        .index(&layout)?;
        r[l] = z[i] / self.scales.phase;
        Ok(())
    }
}

impl<L, F, B, S> Family for HbFamily<L, F, B, S>
where
    L: DynamicStiffness,
    F: NonlinearForce,
    B: FnMut(usize) -> Result<HarmonicBalance<L, F>, HbmError>,
    S: FnMut(&mut HarmonicBalance<L, F>, f64) -> Result<(), HbmError>,
{
    fn layout(&self) -> HarmonicLayout {
        self.hb.layout()
    }

    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), HbmError> {
        let p = z[z.len() - 1];
        self.rows(z, p, r)
    }

    fn jacobian(&mut self, z: &[f64], mut jac: MatMut<'_, f64>) -> Result<(), HbmError> {
        let layout = self.hb.layout();
        let l = layout.len();
        let p = z[l + 1];
        // ∂R/∂p by central differences.
        let h = self.step * p.abs().max(1.0);
        let mut rp = vec![0.0; l + 1];
        let mut rm = vec![0.0; l + 1];
        self.rows(z, p + h, &mut rp)?;
        self.rows(z, p - h, &mut rm)?;
        for i in 0..=l {
            jac[(i, l + 1)] = (rp[i] - rm[i]) / (2.0 * h);
        }
        (self.set)(&mut self.hb, p)?;
        self.work.resize(l, 0.0);
        let mut jw = std::mem::take(&mut self.work);
        self.hb.jacobian(
            &z[..l],
            z[l],
            jac.rb_mut().submatrix_mut(0, 0, l, l),
            &mut jw,
        )?;
        let inv = 1.0 / self.scales.force;
        for i in 0..l {
            jac[(i, l)] = jw[i] * inv;
            for j in 0..l {
                jac[(i, j)] *= inv;
            }
        }
        self.work = jw;
        let idx = PhaseCondition::FirstSineZero {
            dof: self.phase_dof,
        }
        .index(&layout)?;
        for j in 0..=l {
            jac[(l, j)] = 0.0;
        }
        jac[(l, idx)] = 1.0 / self.scales.phase;
        jac[(l, l + 1)] = 0.0;
        Ok(())
    }

    fn set_harmonics(&mut self, harmonics: usize) -> Result<(), HbmError> {
        self.hb = (self.build)(harmonics)?;
        Ok(())
    }
}
