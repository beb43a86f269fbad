//! The eigensolver front end: the `nev` lowest eigenpairs of
//! K phi = w^2 M phi (eqs. 4-5 of Coudeyras et al. 2009: fixed-interface
//! modes, mass-normalized), by shift-invert about a shift sigma below the
//! lowest eigenvalue, with a Sturm check for missed eigenvalues.

use crate::EigError;
use crate::block::{BlockParams, block_lanczos};
use crate::cholesky::{CholeskyOptions, FactorAnalysis, FactorStats, SparseCholesky};
use crate::constraint::{ConstrainedFactor, Constraints};
use crate::inertia::count_below_unchecked;
use crate::lanczos::{LanczosParams, Locked, ShiftInvert, Watch, thick_restart_lanczos};
use crate::sparse::{check_pair, dot, norm1, sym_matmul, sym_matvec};
use faer::sparse::SparseColMatRef;
use faer::{Col, Mat, Par};
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

mod residual;
#[allow(unused_imports)]
use residual::*;
pub use residual::{backward_errors, sturm_check, sturm_check_with};
pub(crate) use residual::{normalize, residuals, sturm_bound};

/// Which eigensolver runs the shift-invert iteration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Backend {
    /// Thick-restart Lanczos of this crate (pure Rust, always available).
    #[default]
    Lanczos,
    /// ARPACK dsaupd_/dseupd_ in mode 3 (needs the cargo feature `arpack`).
    Arpack,
}

/// Options of [`lowest_modes`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct EigOptions {
    /// Shift sigma: must lie below the lowest eigenvalue so that K - sigma M
    /// is positive definite. 0 for a held structure; negative (e.g. -1e-2 of
    /// the first flexible w^2) for a free one with rigid-body modes.
    pub shift: f64,
    /// Relative tolerance on the Ritz residual ||OP y - theta y||_M / |theta|
    /// (ARPACK's criterion); eigenvalue errors are about its square.
    pub tol: f64,
    /// Maximum number of restart cycles.
    pub max_iter: usize,
    /// Lanczos basis size; default max(2 * nwanted + 1, 20) for the
    /// single-vector method and ARPACK, max(3 * nwanted, nwanted + 4 *
    /// block_size, 20) for the block method; capped at n.
    pub ncv: Option<usize>,
    /// Vectors per block of the block Lanczos method (backend
    /// [`Backend::Lanczos`]): OP is applied to this many vectors at once,
    /// which costs several times less per vector than single solves. The
    /// block used is min(block_size, ncv - nwanted); 1 (or a basis too small
    /// for a block) runs the single-vector thick-restart Lanczos.
    pub block_size: usize,
    /// Solver backend.
    pub backend: Backend,
    /// Count the eigenvalues below a bound just above the highest one kept
    /// (inertia of K - bound M from a sparse LBL^T factorization) and fail
    /// with [`EigError::MissedEigenvalues`] if the solver missed any. Costs
    /// one more factorization.
    pub sturm_check: bool,
    /// Extra eigenpairs computed above the `nev` wanted, so that the Sturm
    /// bound can be put in a gap of the spectrum even when the nev-th
    /// eigenvalue is part of a multiplet (up to `guard + 1` copies). The
    /// Lanczos backend converges them to a residual estimate of 1e-6 only
    /// (their eigenvalues to about 1e-12), enough to place the bound.
    pub guard: usize,
    /// Spectrum slicing: with more than this many pairs wanted (nev plus
    /// guards), the Lanczos backend finds them over several shifts, at most
    /// this many new pairs per shift (shifted block Lanczos of Grimes, Lewis
    /// & Simon, with LBL^T factors at the later shifts and their inertia as
    /// the Sturm counts); 0: one shift. One shift's basis of 3 nev vectors
    /// costs n nev^2 to orthogonalize and 24 n nev bytes; on the fine disc
    /// one shift was still faster at nev = 200 (560 solves against 704 over
    /// two shifts), hence the default of 300.
    pub slice: usize,
    /// Let the Sturm check run beside the iteration once the Ritz values
    /// place its bound. Its LBL^T factorization is then held in memory at the
    /// same time as the Cholesky factor; without, it follows the iteration.
    pub sturm_beside: bool,
    /// Seed of the start vector (results are deterministic for a given seed).
    pub seed: u64,
    /// Parallelism of the factorizations.
    pub par: Par,
}

impl Default for EigOptions {
    fn default() -> Self {
        Self {
            shift: 0.0,
            tol: 1e-10,
            max_iter: 300,
            ncv: None,
            block_size: 8,
            backend: Backend::Lanczos,
            sturm_check: true,
            sturm_beside: true,
            slice: 300,
            guard: 3,
            seed: 1,
            par: faer::get_global_parallelism(),
        }
    }
}

/// What the solve cost.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EigStats {
    /// Restart cycles (ARPACK: "Arnoldi update iterations").
    pub iterations: usize,
    /// Restarts (iterations - 1).
    pub restarts: usize,
    /// Applications of OP = (K - sigma M)^-1 M (sparse triangular solve pairs).
    pub operator_applications: usize,
    /// Basis size used.
    pub ncv: usize,
    /// Block size used in the first round (1: single-vector Lanczos, also
    /// for ARPACK).
    pub block: usize,
    /// Eigenpairs computed (nev + guard, plus any found in later rounds).
    pub computed: usize,
    /// Solver rounds: 1, plus one per locked restart after a Sturm miss
    /// (single-vector Krylov methods find extra copies of a multiple
    /// eigenvalue only through rounding; the Sturm count tells how many are
    /// missing and a restart with the found vectors locked finds them).
    pub rounds: usize,
    /// Factorization of K - sigma M, if this call made it.
    pub factor: Option<FactorStats>,
    /// Time of the iteration, including Sturm checks (without the first factorization).
    pub solve_time: Duration,
    /// Sturm bound and the count of eigenvalues below it, if checked.
    pub sturm: Option<(f64, usize)>,
    /// Shifts used (1 unless the spectrum was sliced).
    pub shifts: usize,
    /// Time of the Sturm check (its LBL^T factorization and count), whether
    /// it ran beside the iteration or after it.
    pub sturm_time: Duration,
    /// Whether the Sturm check ran beside the iteration (its bound chosen
    /// from Ritz values converged early enough), so that its time is not
    /// part of [`EigStats::solve_time`] on a machine with a core to spare.
    pub sturm_beside: bool,
    /// Of the iteration time, the triangular solves with the factor (the
    /// rest is orthogonalization, products with M, restarts).
    pub operator_time: Duration,
    /// Of the iteration time, the products with M.
    pub mass_time: Duration,
    /// Of the iteration time, the Ritz pairs of the projected matrix and the
    /// restarts (block Lanczos).
    pub ritz_time: Duration,
    /// Total wall time of the call.
    pub time: Duration,
}

/// The lowest eigenpairs.
#[derive(Debug, Clone)]
pub struct Modes {
    /// Eigenvalues w^2, ascending.
    pub values: Vec<f64>,
    /// Eigenvectors as columns, M-orthonormal: phi^T M phi = I.
    pub vectors: Mat<f64>,
    /// Normwise backward errors ||K phi - w^2 M phi|| / ((||K|| + w^2 ||M||) ||phi||)
    /// (1-norms of the matrices, 2-norms of vectors; Higham & Higham 1998),
    /// meaningful for rigid-body (w^2 = 0) modes too.
    pub residuals: Vec<f64>,
    /// The guard eigenvalues computed above the `nev` returned (see
    /// [`EigOptions::guard`]), ascending, accurate to about 1e-12: with
    /// `values` they place the bound of a Sturm check made later
    /// ([`sturm_check_with`]).
    pub guard_values: Vec<f64>,
    /// Costs.
    pub stats: EigStats,
}

/// The `nev` lowest eigenpairs of K phi = w^2 M phi (K, M symmetric with
/// both triangles stored, M positive definite), by shift-invert about
/// `opts.shift`: factorizes K - sigma M, then calls [`lowest_modes_with_factor`].
pub fn lowest_modes(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    nev: usize,
    opts: &EigOptions,
) -> Result<Modes, EigError> {
    let t0 = Instant::now();
    check_pair(k, m)?;
    check_options(opts)?;
    let chol = CholeskyOptions {
        par: opts.par,
        ..Default::default()
    };
    let factor = SparseCholesky::factorize_shifted(k, m, opts.shift, &chol)?;
    let pencil = FactoredPencil {
        k,
        m,
        factor: &factor,
        constrained: None,
    };
    let mut modes = solve_checked(pencil, nev, opts)?;
    modes.stats.factor = Some(factor.stats());
    modes.stats.time = t0.elapsed();
    Ok(modes)
}

/// As [`lowest_modes`], reusing an existing Cholesky factor of
/// K - opts.shift * M (e.g. the factor of K_II made for the constraint modes,
/// with shift 0). A factor of another matrix is detected (one test solve)
/// and reported as [`EigError::FactorMismatch`].
pub fn lowest_modes_with_factor(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    factor: &SparseCholesky,
    nev: usize,
    opts: &EigOptions,
) -> Result<Modes, EigError> {
    let pencil = FactoredPencil {
        k,
        m,
        factor,
        constrained: None,
    };
    with_factor(pencil, nev, opts)
}

/// The `nev` lowest eigenpairs of K phi = w^2 M phi + C^T mu with C phi = 0
/// (see [`ConstrainedFactor`]), by shift-invert about `opts.shift` with the
/// constrained operator of `constrained`, made from a Cholesky factor of
/// K - opts.shift * M. The Sturm check counts the constrained eigenvalues;
/// [`Modes::residuals`] are backward errors of the residuals with the
/// constraint forces C^T mu removed (least squares).
pub fn lowest_modes_constrained(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    constrained: &ConstrainedFactor<'_>,
    nev: usize,
    opts: &EigOptions,
) -> Result<Modes, EigError> {
    let pencil = FactoredPencil {
        k,
        m,
        factor: constrained.factor(),
        constrained: Some(constrained),
    };
    with_factor(pencil, nev, opts)
}

/// The pencil K - λM with a Cholesky factor of K - σM (σ = `opts.shift`) and, for the
/// constrained problem, its constrained operator: what every solve below works on.
#[derive(Clone, Copy)]
pub(crate) struct FactoredPencil<'a> {
    pub k: SparseColMatRef<'a, usize, f64>,
    pub m: SparseColMatRef<'a, usize, f64>,
    pub factor: &'a SparseCholesky,
    pub constrained: Option<&'a ConstrainedFactor<'a>>,
}

impl<'a> FactoredPencil<'a> {
    /// The constraints `C φ = 0`, if any.
    pub fn constraints(&self) -> Option<&'a Constraints> {
        self.constrained.map(ConstrainedFactor::constraints)
    }

    /// How many eigenpairs the (constrained) pencil has: its size less the constraints.
    pub fn dim(&self) -> usize {
        let n = self.k.nrows();
        n.saturating_sub(self.constraints().map_or(0, Constraints::len))
    }
}

/// Checks, then [`solve_checked`] with a factor given by the caller.
fn with_factor(
    pencil: FactoredPencil<'_>,
    nev: usize,
    opts: &EigOptions,
) -> Result<Modes, EigError> {
    let FactoredPencil {
        k,
        m,
        factor,
        constrained: _,
    } = pencil;
    let t0 = Instant::now();
    check_pair(k, m)?;
    check_options(opts)?;
    check_factor(k, m, factor, opts.shift)?;
    let mut modes = solve_checked(pencil, nev, opts)?;
    modes.stats.time = t0.elapsed();
    Ok(modes)
}

fn check_options(opts: &EigOptions) -> Result<(), EigError> {
    let bad = |what: String| Err(EigError::InvalidOption { what });
    if !opts.shift.is_finite() {
        return bad(format!("shift {} is not finite", opts.shift));
    }
    if !(opts.tol > 0.0 && opts.tol < 1.0) {
        return bad(format!("tol {} must be in (0, 1)", opts.tol));
    }
    if opts.max_iter == 0 {
        return bad("max_iter must be at least 1".into());
    }
    Ok(())
}

/// Normwise backward error of one solve with the factor, for a fixed vector:
/// about 1e-16 for the right factor, large for another matrix.
pub(crate) fn check_factor(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    factor: &SparseCholesky,
    sigma: f64,
) -> Result<(), EigError> {
    let n = k.nrows();
    if factor.n() != n {
        return Err(EigError::DimensionMismatch {
            what: format!("factor is {}, K is {n}", factor.n()),
        });
    }
    // A y = K y - sigma M y, without assembling A.
    let apply = |y: &Col<f64>| {
        let mut ky = Col::<f64>::zeros(n);
        let mut my = Col::<f64>::zeros(n);
        sym_matvec(k, y.as_ref(), ky.as_mut());
        sym_matvec(m, y.as_ref(), my.as_mut());
        Col::<f64>::from_fn(n, |i| ky[i] - sigma * my[i])
    };
    let x = Col::<f64>::from_fn(n, |i| 1.0 + ((i * 7919) % 101) as f64 / 101.0);
    let b = apply(&x);
    let mut y = b.clone();
    factor.solve_col_in_place(&mut y)?;
    let ay = apply(&y);
    let norm_a = norm1(k) + sigma.abs() * norm1(m);
    let err = (&ay - &b).norm_l2() / (norm_a * y.norm_l2() + b.norm_l2());
    // Tolerance: a backward-stable solve gives ~1e-16; a factor of a matrix
    // differing by a relative 1e-8 or more is not the one asked for.
    if err.is_finite() && err <= 1e-9 {
        Ok(())
    } else {
        Err(EigError::FactorMismatch { error: err })
    }
}

/// A Sturm count made beside the iteration: its bound, the count (or the
/// error), and its time.
type EarlyCount = (f64, Result<usize, EigError>, Duration);

/// Runs the backend, post-processes and Sturm-checks. The Sturm count runs
/// beside the iteration as soon as the Ritz values place its bound (see
/// [`early_bound`]); if the converged values then leave the bound in a gap
/// with at least `nev` values below it, the count checks them, else a count
/// at a bound from the converged values follows the iteration.
fn solve_checked(
    pencil: FactoredPencil<'_>,
    nev: usize,
    opts: &EigOptions,
) -> Result<Modes, EigError> {
    let FactoredPencil {
        k,
        m,
        factor,
        constrained,
    } = pencil;
    let (constraints, dim) = (pencil.constraints(), pencil.dim());
    if nev == 0 || nev > dim {
        return Err(EigError::TooManyRequested {
            requested: nev,
            available: dim,
        });
    }
    let nwant = nev.saturating_add(opts.guard).min(dim);
    if opts.backend == Backend::Lanczos
        && opts.slice > 0
        && nwant > opts.slice
        && opts.ncv.is_none()
    {
        return crate::slicing::solve_sliced(pencil, nev, opts);
    }
    let ncv = match opts.ncv {
        Some(c) => c.min(dim),
        None => default_ncv(nwant, opts).min(dim),
    };
    if ncv < nwant || (ncv == nwant && ncv < dim) {
        return Err(EigError::InvalidOption {
            what: format!("ncv {ncv} must exceed nev + guard = {nwant} (or equal {dim})"),
        });
    }
    let t0 = Instant::now();
    let mut op = ShiftInvert {
        m,
        factor,
        constraint: constrained.map(ConstrainedFactor::projector),
        locked: None,
        solve_time: Default::default(),
        mass_time: Default::default(),
        ritz_time: Default::default(),
    };
    let early: Mutex<Option<EarlyCount>> = Mutex::new(None);
    let raw = rayon::in_place_scope(|scope| {
        let mut started = !(opts.sturm_check && opts.sturm_beside);
        let early = &early;
        let mut watch = |theta: &[f64], estimates: &[f64]| {
            if started {
                return true;
            }
            if let Some(bound) = early_bound(theta, estimates, nev, opts.shift) {
                started = true;
                scope.spawn(move |_| {
                    let t = Instant::now();
                    let count = count_below_unchecked(
                        k,
                        m,
                        bound,
                        opts.par,
                        Some(factor.analysis()),
                        constraints,
                    );
                    let done = (bound, count, t.elapsed());
                    *early.lock().unwrap_or_else(PoisonError::into_inner) = Some(done);
                });
            }
            started
        };
        let raw = run_backend(&op, (nev, nwant), ncv, opts, &mut watch)?;
        // Normalized and checked while the Sturm count started beside the iteration goes
        // on: the scope waits for it only after this.
        let (values, vectors) = normalize(m, raw.values, raw.vectors);
        let first = match values.len() >= nev {
            true => Some(residuals(
                k,
                m,
                constraints,
                &values[..nev],
                &vectors.subcols(0, nev).to_owned(),
            )?),
            false => None,
        };
        Ok::<_, EigError>((
            raw.block,
            raw.iterations,
            raw.applications,
            values,
            vectors,
            first,
        ))
    });
    let (block, mut iterations, mut applications, mut values, mut vectors, first) = raw?;
    let mut sturm = None;
    let mut sturm_time = Duration::ZERO;
    let mut sturm_beside = false;
    let mut rounds = 1;
    let mut pending = early.into_inner().unwrap_or_else(PoisonError::into_inner);
    if opts.sturm_check {
        loop {
            let checked = match pending.take() {
                Some((bound, count, time)) if separated(bound, &values, nev) => {
                    sturm_time += time;
                    sturm_beside = true;
                    count.and_then(|c| compare_count(bound, c, &values))
                }
                _ => {
                    let t1 = Instant::now();
                    let (bound, _) = sturm_bound(&values, nev);
                    let count = count_below_unchecked(
                        k,
                        m,
                        bound,
                        opts.par,
                        Some(factor.analysis()),
                        constraints,
                    );
                    sturm_time += t1.elapsed();
                    count.and_then(|c| compare_count(bound, c, &values))
                }
            };
            match checked {
                Ok(found) => {
                    sturm = Some(found);
                    break;
                }
                Err(EigError::MissedEigenvalues {
                    expected, found, ..
                }) if expected > found && rounds < MAX_ROUNDS => {
                    // Lock what was found and look for the missing ones
                    // (typically further copies of a multiple eigenvalue).
                    rounds += 1;
                    let dim = dim - vectors.ncols();
                    let more = (expected - found).saturating_add(opts.guard).min(dim);
                    let ncv_more = (2 * more + 1).max(20).min(dim);
                    if more == 0 || (more == ncv_more && ncv_more < dim) {
                        return Err(EigError::MissedEigenvalues {
                            bound: f64::NAN,
                            expected,
                            found,
                        });
                    }
                    op.locked = Some(Locked {
                        x: vectors.clone(),
                        mx: m * &vectors,
                    });
                    let sharp = (expected - found).min(more);
                    let extra = run_backend(&op, (sharp, more), ncv_more, opts, &mut |_, _| true)?;
                    iterations += extra.iterations;
                    applications += extra.applications;
                    let (v2, x2) = normalize(m, extra.values, extra.vectors);
                    (values, vectors) = merge(values, vectors, v2, x2);
                }
                Err(e) => return Err(e),
            }
        }
    }
    let solve_time = t0.elapsed();
    // The guards beyond nev only place the Sturm bound: their residuals are
    // neither returned nor held to the tolerance. Pairs found in later rounds
    // change the first nev: their residuals are computed again.
    let residuals = match first.filter(|_| rounds == 1) {
        Some(first) => first,
        None => residuals(
            k,
            m,
            constraints,
            &values[..nev],
            &vectors.subcols(0, nev).to_owned(),
        )?,
    };
    // Tolerance: the backward error is about tol times sqrt(cond(M)) (M-norm
    // to 2-norm); 1e4 tol leaves room for cond(M) up to 1e8 before a pair
    // that the solver called converged is rejected as not converged.
    let limit = 1e4 * opts.tol.max(f64::EPSILON);
    if residuals.iter().any(|r| r.is_nan() || *r > limit) {
        let worst = residuals.iter().copied().fold(0.0, f64::max);
        let converged = residuals.iter().filter(|r| **r <= limit).count();
        return Err(EigError::NotConverged {
            converged,
            requested: nev,
            iterations,
            residuals,
            worst,
        });
    }
    let stats = EigStats {
        iterations,
        restarts: iterations.saturating_sub(rounds),
        operator_applications: applications,
        ncv,
        block,
        computed: values.len(),
        rounds,
        solve_time,
        shifts: 1,
        sturm,
        sturm_time,
        sturm_beside,
        operator_time: op.solve_time.get(),
        mass_time: op.mass_time.get(),
        ritz_time: op.ritz_time.get(),
        ..Default::default()
    };
    Ok(Modes {
        values: values[..nev].to_vec(),
        vectors: vectors.subcols(0, nev).to_owned(),
        residuals,
        guard_values: values[nev..].to_vec(),
        stats,
    })
}

/// Largest residual estimate of a Ritz pair trusted to place the Sturm
/// bound beside the iteration. A Ritz value theta with relative residual
/// estimate e is within e |theta| of an eigenvalue of OP (Bauer-Fike for a
/// self-adjoint operator; about e^2 once converged), so its
/// lambda = sigma + 1 / theta is within about e |lambda - sigma| of one:
/// [`early_bound`] asks the bound to stand twice that far from every Ritz
/// value it separates. The count itself is compared with the converged
/// values ([`separated`], [`compare_count`]), so a looser estimate only
/// risks a second count after the iteration, never a wrong verdict; 1e-3
/// starts the count about a second earlier on the fine disc than the
/// guards' tolerance 1e-6 did (docs/benchmarks.md).
const EARLY_ESTIMATE: f64 = 1e-3;

/// A Sturm bound from Ritz values theta (descending, of OP = (K - sigma
/// M)^-1 M) during the iteration: the bound [`sturm_bound`] places in the
/// eigenvalues lambda = sigma + 1 / theta, if it falls in a gap between two
/// Ritz values, every Ritz pair up to the first above it has a residual
/// estimate of at most [`EARLY_ESTIMATE`], and the bound is further from each
/// of these Ritz values than twice its error bound.
fn early_bound(theta: &[f64], estimates: &[f64], nev: usize, shift: f64) -> Option<f64> {
    let count = theta.iter().take_while(|&&t| t > 0.0).count();
    let lambda: Vec<f64> = theta[..count].iter().map(|t| shift + 1.0 / t).collect();
    if lambda.len() <= nev {
        return None;
    }
    let (bound, below) = sturm_bound(&lambda, nev);
    let trusted = estimates.get(..=below)?;
    let accurate = trusted
        .iter()
        .zip(&lambda)
        .all(|(&e, &l)| e <= EARLY_ESTIMATE && (l - bound).abs() > 2.0 * e * (l - shift).abs());
    (below < lambda.len() && accurate).then_some(bound)
}

/// Whether a Sturm bound chosen during the iteration checks the converged
/// `values` (ascending): at least `nev` of them below it and none within
/// [`SAME_EIGENVALUE`] of it (on the scale of [`sturm_bound`]).
fn separated(bound: f64, values: &[f64], nev: usize) -> bool {
    let vmax = values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let below = values.iter().filter(|&&v| v < bound).count();
    let clear = values.iter().all(|&v| {
        let scale = v
            .abs()
            .max(bound.abs())
            .max(1e-3 * vmax)
            .max(f64::MIN_POSITIVE);
        (v - bound).abs() > 0.5 * SAME_EIGENVALUE * scale
    });
    below >= nev && clear
}

/// The Sturm check's verdict: `count` eigenvalues lie below `bound`; the
/// computed `values` must have as many there.
fn compare_count(bound: f64, count: usize, values: &[f64]) -> Result<(f64, usize), EigError> {
    let found = values.iter().filter(|&&v| v < bound).count();
    if count == found {
        Ok((bound, count))
    } else {
        Err(EigError::MissedEigenvalues {
            bound,
            expected: count,
            found,
        })
    }
}

/// Default basis size: max(2 nwant + 1, 20) for single-vector Lanczos and
/// ARPACK; max(3 nwant, nwant + 4 block, 20) for the block method, whose
/// polynomial degree per restart is ncv / block (a basis of 2 nwant makes
/// it restart too often on the brake meshes).
pub(crate) fn default_ncv(nwant: usize, opts: &EigOptions) -> usize {
    let single = (2 * nwant + 1).max(20);
    if opts.backend == Backend::Lanczos && opts.block_size > 1 {
        (3 * nwant)
            .max(nwant.saturating_add(4 * opts.block_size))
            .max(single)
    } else {
        single
    }
}

/// Solver rounds at most: the first plus locked restarts after Sturm misses.
const MAX_ROUNDS: usize = 4;

/// Runs the chosen backend for `nwant` eigenpairs, the first `nsharp` of them
/// to the tolerance and the rest as guards (see [`GUARD_TOL`](crate::lanczos::GUARD_TOL); ARPACK takes
/// all to the tolerance).
fn run_backend(
    op: &ShiftInvert<'_>,
    (nsharp, nwant): (usize, usize),
    ncv: usize,
    opts: &EigOptions,
    watch: Watch<'_>,
) -> Result<RawModes, EigError> {
    match opts.backend {
        Backend::Lanczos => run_lanczos(op, (nsharp, nwant), ncv, opts, watch),
        Backend::Arpack => run_arpack(op, nwant, ncv, opts),
    }
}

/// Joins two sets of eigenpairs, sorted ascending (stable).
pub(crate) fn merge(
    v1: Vec<f64>,
    x1: Mat<f64>,
    v2: Vec<f64>,
    x2: Mat<f64>,
) -> (Vec<f64>, Mat<f64>) {
    let values: Vec<f64> = v1.iter().chain(&v2).copied().collect();
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let n = x1.nrows();
    let n1 = v1.len();
    let vectors = Mat::from_fn(n, order.len(), |i, c| {
        let j = order[c];
        if j < n1 { x1[(i, j)] } else { x2[(i, j - n1)] }
    });
    (order.iter().map(|&j| values[j]).collect(), vectors)
}

/// Eigenpairs as returned by a backend (any order, any scaling).
pub(crate) struct RawModes {
    pub values: Vec<f64>,
    pub vectors: Mat<f64>,
    pub iterations: usize,
    pub applications: usize,
    /// Block size used (1: single vector).
    pub block: usize,
}

fn run_lanczos(
    op: &ShiftInvert<'_>,
    (nsharp, nwant): (usize, usize),
    ncv: usize,
    opts: &EigOptions,
    watch: Watch<'_>,
) -> Result<RawModes, EigError> {
    let block = opts.block_size.min(ncv.saturating_sub(nwant));
    let mut blocked = None;
    if block > 1 {
        let params = BlockParams {
            nwant,
            nsharp,
            by_magnitude: false,
            ncv,
            block,
            tol: opts.tol,
            max_iter: opts.max_iter,
            seed: opts.seed,
        };
        blocked = block_lanczos(op, &params, &mut *watch)?;
    }
    let (out, block) = match blocked {
        Some(out) => (out, block),
        None => {
            let params = LanczosParams {
                nwant,
                nsharp,
                ncv,
                tol: opts.tol,
                max_iter: opts.max_iter,
                seed: opts.seed,
            };
            (thick_restart_lanczos(op, &params, watch)?, 1)
        }
    };
    Ok(RawModes {
        values: out.theta.iter().map(|t| opts.shift + 1.0 / t).collect(),
        vectors: out.vectors,
        iterations: out.iterations,
        applications: out.applications,
        block,
    })
}

#[cfg(feature = "arpack")]
fn run_arpack(
    op: &ShiftInvert<'_>,
    nwant: usize,
    ncv: usize,
    opts: &EigOptions,
) -> Result<RawModes, EigError> {
    crate::arpack::shift_invert(op, nwant, ncv, opts.shift, opts.tol, opts.max_iter)
}

#[cfg(not(feature = "arpack"))]
fn run_arpack(
    _op: &ShiftInvert<'_>,
    _nwant: usize,
    _ncv: usize,
    _opts: &EigOptions,
) -> Result<RawModes, EigError> {
    Err(EigError::BackendUnavailable("arpack"))
}

#[cfg(test)]
mod tests;
