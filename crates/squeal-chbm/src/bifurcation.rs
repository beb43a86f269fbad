//! Stability along a branch of limit cycles and its bifurcations (issue 10, item 3).
//!
//! Each point of a [`LimitCycleBranch`] gets its Floquet exponents by Hill's method
//! ([`crate::floquet::hill`]), the points in parallel (each is independent: the same bits for
//! any thread count). Between two consecutive points the number of unstable exponents (real
//! part beyond the method's own error, the trivial exponent's distance from zero) changes
//! where a multiplier `ρ = e^{σT}` leaves or enters the unit circle. Which way it crosses names
//! the bifurcation (Seydel, *Practical Bifurcation and Stability Analysis*, §7.4):
//!
//! - `ρ → +1` (`Im σ ≈ 0`): a fold of the branch (or a branch point);
//! - `ρ → −1` (`Im σ ≈ ±ω/2`): period doubling;
//! - a complex pair `ρ, ρ̄` leaves the circle elsewhere: Neimark–Sacker, the cycle turns into a
//!   quasi-periodic vibration (a torus) with the second frequency `|Im σ|/2π`.
//!
//! The crossing's parameter is interpolated linearly in the crossing exponent's real part
//! between the two points; the continuation's own fold location ([`crate::branch::Fold`]) is
//! the accurate one for folds.
//!
//! **Overlap.** The continuation is sequential (each point is predicted from the one before)
//! while the points' Floquet analyses are independent. [`follow_from_hopf_with_hill`] hands
//! each point to a task of the thread pool as soon as the continuation accepts it, so that
//! Hill's method runs on the other threads during the continuation instead of after it; the
//! exponents are those of [`hill_along`] on the finished branch, bit for bit.

use crate::branch::follow_from_hopf_observed;
use crate::branch::{BranchOptions, BranchPoint, LimitCycleBranch, Parameter};
use crate::floquet::{CycleRef, Exponent, FloquetError, HillFloquet, HillOptions, hill};
use crate::solve::ChbmError;
use rayon::prelude::*;
use squeal_brake::criticality::NormalForm;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::HarmonicLayout;
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// How a Floquet multiplier crosses the unit circle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BifurcationKind {
    /// Through +1: a fold (turning point) of the branch.
    Fold,
    /// Through −1: period doubling.
    PeriodDoubling,
    /// A complex pair: Neimark–Sacker (torus, quasi-periodic vibration).
    NeimarkSacker,
}

impl std::fmt::Display for BifurcationKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            BifurcationKind::Fold => "fold (multiplier through +1)",
            BifurcationKind::PeriodDoubling => "period doubling (multiplier through -1)",
            BifurcationKind::NeimarkSacker => "Neimark-Sacker (complex pair leaves the circle)",
        })
    }
}

/// A change of stability between two consecutive branch points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bifurcation {
    /// Its kind, from the crossing exponent.
    pub kind: BifurcationKind,
    /// Index of the branch point before it.
    pub after_point: usize,
    /// The parameter, interpolated linearly in the crossing exponent's real part.
    pub parameter: f64,
    /// The crossing exponent on the unstable side.
    pub exponent: Exponent,
    /// Unstable exponents before and after (conjugates counted).
    pub unstable: (usize, usize),
}

impl Bifurcation {
    /// The second frequency of a Neimark–Sacker torus, `|Im σ|/2π` (Hz).
    pub fn torus_frequency_hz(&self) -> f64 {
        self.exponent.sigma.im.abs() / (2.0 * std::f64::consts::PI)
    }
}

/// The cycle of a branch point as the Floquet analyses read it, on `samples` AFT samples per
/// period (`None`: the harmonic balance's default for its harmonics; never fewer).
pub fn cycle_of<'a>(
    mb: &ModalBrake,
    point: &'a BranchPoint,
    samples: Option<usize>,
) -> Result<CycleRef<'a>, FloquetError> {
    let layout = HarmonicLayout::new(mb.nl(), point.harmonics)?;
    layout.check_len("branch point coefficients", point.nl_coeffs.len())?;
    let default = squeal_hbm::default_samples(point.harmonics);
    Ok(CycleRef {
        layout,
        u: &point.nl_coeffs,
        omega: point.omega,
        samples: samples.map_or(default, |s| s.max(default)),
    })
}

/// Hill's exponents at each point of `branch` on `mb`, in parallel. For a branch in μ each
/// point is analysed at its own μ; for other parameters at `mb`'s μ (the parameter enters the
/// constant load only, not the linearization about the cycle).
pub fn hill_along(
    mb: &ModalBrake,
    branch: &LimitCycleBranch,
    samples: Option<usize>,
    opts: &HillOptions,
) -> Vec<Result<HillFloquet, FloquetError>> {
    branch
        .points
        .par_iter()
        .map(|p| hill_at(mb, branch.parameter, p, samples, opts))
        .collect()
}

/// Hill's exponents at one point of a branch in `parameter` (see [`hill_along`]).
fn hill_at(
    mb: &ModalBrake,
    parameter: Parameter,
    p: &BranchPoint,
    samples: Option<usize>,
    opts: &HillOptions,
) -> Result<HillFloquet, FloquetError> {
    let mut mbp = mb.clone();
    if parameter == Parameter::Friction {
        mbp.mu = p.parameter;
    }
    hill(&mbp, &cycle_of(mb, p, samples)?, opts)
}

/// A branch from [`follow_from_hopf_with_hill`] with its exponents.
pub struct BranchWithHill {
    /// The branch, as [`crate::branch::follow_from_hopf`] returns it.
    pub branch: LimitCycleBranch,
    /// Hill's exponents at each point, as [`hill_along`] returns them.
    pub floquet: Vec<Result<HillFloquet, FloquetError>>,
    /// Wall time from the continuation's end to the last exponents: what the Floquet analyses
    /// add to the continuation's own time.
    pub floquet_tail: Duration,
}

/// [`crate::branch::follow_from_hopf`] and [`hill_along`] overlapped (module docs): inside a
/// [`rayon::scope`], the continuation runs on one thread and each point it accepts is a task
/// for the others; the points it kept without telling (see
/// [`follow_from_hopf_observed`]) are analysed after it. With one thread the tasks run
/// after the continuation.
pub fn follow_from_hopf_with_hill(
    mb: &ModalBrake,
    nf: &NormalForm,
    opts: &BranchOptions,
    hill_opts: &HillOptions,
) -> Result<BranchWithHill, ChbmError> {
    type Done = (usize, BranchPoint, Result<HillFloquet, FloquetError>);
    let (tx, rx) = mpsc::channel::<Done>();
    let (branch, end) = rayon::scope(|scope| {
        let mut told = 0;
        let branch = follow_from_hopf_observed(mb, nf, opts, &mut |p| {
            let (i, p, tx) = (told, p.clone(), tx.clone());
            told += 1;
            scope.spawn(move |_| {
                let f = hill_at(mb, Parameter::Friction, &p, opts.samples, hill_opts);
                // The receiver outlives the scope: sending cannot fail.
                let _ = tx.send((i, p, f));
            });
        });
        (branch, Instant::now())
    });
    let branch = branch?;
    drop(tx);
    let mut floquet: Vec<Option<Result<HillFloquet, FloquetError>>> =
        branch.points.iter().map(|_| None).collect();
    for (i, p, f) in rx.try_iter() {
        // Only a task's own point: a told point is the branch's point of the same index.
        if branch.points.get(i) == Some(&p) {
            floquet[i] = Some(f);
        }
    }
    let floquet = floquet
        .into_par_iter()
        .zip(&branch.points)
        .map(|(f, p)| {
            f.unwrap_or_else(|| hill_at(mb, Parameter::Friction, p, opts.samples, hill_opts))
        })
        .collect();
    Ok(BranchWithHill {
        branch,
        floquet,
        floquet_tail: end.elapsed(),
    })
}

/// The non-trivial exponents of `f` whose real part is beyond its error.
fn unstable(f: &HillFloquet) -> Vec<Exponent> {
    f.exponents
        .iter()
        .copied()
        .filter(|e| !e.trivial && e.sigma.re > f.trivial_error)
        .collect()
}

/// The kind of a crossing by exponent `e` on a cycle of frequency `omega`.
pub fn kind_of(e: &Exponent, omega: f64) -> BifurcationKind {
    let r = e.sigma.im.abs() / omega;
    if r < 0.02 {
        BifurcationKind::Fold
    } else if r > 0.48 {
        BifurcationKind::PeriodDoubling
    } else {
        BifurcationKind::NeimarkSacker
    }
}

/// The stability changes along `branch` from the exponents of [`hill_along`] (points whose
/// analysis failed are skipped: no bifurcation is claimed across them).
pub fn bifurcations(
    branch: &LimitCycleBranch,
    floquet: &[Result<HillFloquet, FloquetError>],
) -> Vec<Bifurcation> {
    let mut out = Vec::new();
    let ok: Vec<(usize, &HillFloquet)> = floquet
        .iter()
        .enumerate()
        .filter_map(|(i, f)| f.as_ref().ok().map(|f| (i, f)))
        .collect();
    for w in ok.windows(2) {
        let ((i, a), (j, b)) = (w[0], w[1]);
        let (ua, ub) = (unstable(a), unstable(b));
        if ua.len() == ub.len() {
            continue;
        }
        // The crossing exponent: the unstable side's smallest real part.
        let (side, other, point) = if ub.len() > ua.len() {
            (&ub, a, &branch.points[j])
        } else {
            (&ua, b, &branch.points[i])
        };
        let Some(e) = side
            .iter()
            .copied()
            .min_by(|x, y| x.sigma.re.total_cmp(&y.sigma.re))
        else {
            continue;
        };
        let kind = kind_of(&e, point.omega);
        // Its partner on the stable side: the nearest exponent in imaginary part among those
        // not unstable there.
        let partner = other
            .exponents
            .iter()
            .filter(|x| !x.trivial && x.sigma.re <= other.trivial_error)
            .min_by(|x, y| {
                (x.sigma.im - e.sigma.im)
                    .abs()
                    .total_cmp(&(y.sigma.im - e.sigma.im).abs())
            })
            .map(|x| x.sigma.re);
        let (pa, pb) = (branch.points[i].parameter, branch.points[j].parameter);
        let parameter = match partner {
            Some(re_stable) => {
                let (ra, rb) = if ub.len() > ua.len() {
                    (re_stable, e.sigma.re)
                } else {
                    (e.sigma.re, re_stable)
                };
                if rb != ra {
                    pa + (pb - pa) * (-ra / (rb - ra)).clamp(0.0, 1.0)
                } else {
                    0.5 * (pa + pb)
                }
            }
            None => 0.5 * (pa + pb),
        };
        out.push(Bifurcation {
            kind,
            after_point: i,
            parameter,
            exponent: e,
            unstable: (ua.len(), ub.len()),
        });
    }
    out
}
