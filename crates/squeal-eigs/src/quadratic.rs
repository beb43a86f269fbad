//! Eigenvalues of a sparse quadratic eigenproblem `(λ² M + λ C + K) x = 0` near a segment of
//! the imaginary axis, by shift-invert Arnoldi on its first-order form: the full-model
//! reference of a brake's complex eigenvalues (`K` non-symmetric through friction).
//!
//! **First-order form.** With `y = λ x` the problem is `A z = λ B z`, `z = [x; y]`,
//! `A = [[0, I], [−K, −C]]`, `B = [[I, 0], [0, M]]` (the companion linearization of
//! Tisseur & Meerbergen, *SIAM Review* 43, 2001, §3.4): the same eigenvalues, the eigenvector
//! `z = [x; λ x]`. For a shift `σ` the operator `S = (A − σ B)⁻¹ B` has the eigenvalues
//! `θ = 1 / (λ − σ)`, largest for the `λ` nearest `σ`. Solving `(A − σ B) [u; v] = [b₁; M b₂]`
//! row by row: `v = b₁ + σ u` and `−K u − (C + σ M) v = M b₂`, so
//!
//! `Q(σ) u = −(M b₂ + C b₁ + σ M b₁)`,  `Q(σ) = K + σ C + σ² M`,  `v = b₁ + σ u`:
//!
//! one sparse complex LU of `Q(σ)` (faer's, of the size of the model) per shift, and two
//! triangular solves per Arnoldi step ([`crate::arnoldi`]).
//!
//! **Coverage.** The segment `ω ∈ [ω_lo, ω_hi]` (rad/s) is cut into cells of half-height `h`,
//! one shift `σ_c = i ω_c` at each centre. After every few Arnoldi steps the Ritz values are
//! split: converged (the eigenvalue's error `res / |θ|²`, Saad 2011 §4.8, below `tolerance ×
//! |λ|`) and not. The unconverged ones lie outside the disk `|λ − σ_c| < 1 / |θ|`, so every
//! eigenvalue inside the disk bounded by the nearest unconverged one has been found (those
//! with a larger `|θ|` converge first: Arnoldi's extreme Ritz values). A cell is done when that
//! disk holds its rectangle `|Im λ − ω_c| ≤ h`, `|Re λ| ≤ strip`; a cell whose disk stays
//! smaller at the largest Krylov dimension is cut in two. Each cell keeps the eigenvalues with
//! `Im λ` in its half-open interval, so none is counted twice. Only the upper half plane is
//! searched: for real `K`, `C`, `M` the others are the conjugates.
//!
//! Each eigenpair's backward error `‖Q(λ) x‖ / ((‖K‖ + |λ| ‖C‖ + |λ|² ‖M‖) ‖x‖)` (max-abs
//! norms of the matrices, Euclidean of the vectors; Tisseur 2000) is computed from the
//! matrices themselves, not from the Arnoldi estimate.

use crate::EigError;
use crate::arnoldi::Arnoldi;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use faer::{MatMut, c64};

/// `(λ² M + λ C + K)`: real sparse matrices of one size (`C` may be absent: zero).
#[derive(Clone, Copy)]
pub struct QuadraticPencil<'a> {
    /// Stiffness (may be non-symmetric).
    pub k: SparseColMatRef<'a, usize, f64>,
    /// Damping, `None` for an undamped model.
    pub c: Option<SparseColMatRef<'a, usize, f64>>,
    /// Mass.
    pub m: SparseColMatRef<'a, usize, f64>,
}

/// Controls of [`eigs_on_segment`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct QuadraticOptions {
    /// Largest Krylov dimension per shift.
    pub max_krylov: usize,
    /// Relative error `|Δλ| / |λ|` a Ritz value must reach (Arnoldi's estimate).
    pub tolerance: f64,
    /// Half-height of the cells (rad/s) before any is cut.
    pub cell: f64,
    /// Half-width `|Re λ|` (1/s) of the strip along the segment in which every eigenvalue is
    /// found.
    pub strip: f64,
    /// Cells are not cut below this half-height (rad/s): a cell that needs it is an error.
    pub min_cell: f64,
}

impl Default for QuadraticOptions {
    fn default() -> Self {
        Self {
            max_krylov: 80,
            tolerance: 1e-11,
            cell: 2.0 * std::f64::consts::PI * 500.0,
            strip: 2.0 * std::f64::consts::PI * 50.0,
            min_cell: 2.0 * std::f64::consts::PI * 1.0,
        }
    }
}

/// One eigenpair of the quadratic problem.
#[derive(Clone, Debug)]
pub struct QuadraticEigenpair {
    /// λ (1/s).
    pub value: c64,
    /// `x`, unit Euclidean norm.
    pub vector: Vec<c64>,
    /// Backward error of `(λ, x)` (see the module docs).
    pub backward_error: f64,
}

/// The eigenvalues found on a segment.
#[derive(Clone, Debug)]
pub struct SegmentEigs {
    /// The eigenpairs, by increasing `Im λ`.
    pub pairs: Vec<QuadraticEigenpair>,
    /// Shifts used (cells, after cutting).
    pub shifts: usize,
    /// Arnoldi steps (solves with a factor) over all shifts.
    pub steps: usize,
    /// Largest backward error over the pairs.
    pub worst_backward_error: f64,
}

/// Adds `alpha A x` to `out` (`A` real sparse, `x` complex).
fn add_product(out: &mut [c64], a: SparseColMatRef<'_, usize, f64>, x: &[c64], alpha: c64) {
    for (j, &xj) in x.iter().enumerate() {
        let s = alpha * xj;
        for (i, &v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
            out[i] += s * v;
        }
    }
}

fn max_abs(a: SparseColMatRef<'_, usize, f64>) -> f64 {
    (0..a.ncols())
        .flat_map(|j| a.val_of_col(j).iter().map(|v| v.abs()))
        .fold(0.0, f64::max)
}

impl<'a> QuadraticPencil<'a> {
    /// The pencil, its sizes and entries checked.
    pub fn new(
        k: SparseColMatRef<'a, usize, f64>,
        c: Option<SparseColMatRef<'a, usize, f64>>,
        m: SparseColMatRef<'a, usize, f64>,
    ) -> Result<Self, EigError> {
        let n = k.nrows();
        for (name, a) in [("K", Some(k)), ("C", c), ("M", Some(m))] {
            let Some(a) = a else { continue };
            if a.nrows() != n || a.ncols() != n {
                return Err(EigError::DimensionMismatch {
                    what: format!(
                        "{name} is {}x{}, K is {n}x{}",
                        a.nrows(),
                        a.ncols(),
                        k.ncols()
                    ),
                });
            }
            if let Some(col) = (0..n).find(|&j| a.val_of_col(j).iter().any(|v| !v.is_finite())) {
                return Err(EigError::NonFinite { matrix: name, col });
            }
        }
        Ok(Self { k, c, m })
    }

    /// Number of dofs.
    pub fn size(&self) -> usize {
        self.k.nrows()
    }

    /// `Q(σ) = K + σ C + σ² M` as a complex sparse matrix.
    pub fn at(&self, sigma: c64) -> Result<SparseColMat<usize, c64>, EigError> {
        let n = self.size();
        let mut t = Vec::new();
        let mut push = |a: SparseColMatRef<'_, usize, f64>, f: c64| {
            for j in 0..n {
                for (i, &v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
                    t.push(Triplet::new(i, j, f * v));
                }
            }
        };
        push(self.k, c64::new(1.0, 0.0));
        if let Some(c) = self.c {
            push(c, sigma);
        }
        push(self.m, sigma * sigma);
        SparseColMat::try_new_from_triplets(n, n, &t).map_err(|e| EigError::Factorization {
            what: format!(
                "Q(sigma) from triplets: {}",
                crate::faer_error::describe_creation(e)
            ),
        })
    }

    /// `Q(λ) x`.
    pub fn apply(&self, lambda: c64, x: &[c64]) -> Vec<c64> {
        let mut out = vec![c64::new(0.0, 0.0); self.size()];
        add_product(&mut out, self.k, x, c64::new(1.0, 0.0));
        if let Some(c) = self.c {
            add_product(&mut out, c, x, lambda);
        }
        add_product(&mut out, self.m, x, lambda * lambda);
        out
    }

    /// The backward error of `(λ, x)` (module docs).
    pub fn backward_error(&self, lambda: c64, x: &[c64]) -> f64 {
        let r = self.apply(lambda, x);
        let norm = |v: &[c64]| v.iter().map(|a| a.norm_sqr()).sum::<f64>().sqrt();
        let l = lambda.norm();
        let scale = max_abs(self.k) + l * self.c.map_or(0.0, max_abs) + l * l * max_abs(self.m);
        norm(&r) / (scale * norm(x)).max(f64::MIN_POSITIVE)
    }
}

/// The shift-invert operator `S = (A − σ B)⁻¹ B` at one shift (module docs).
struct ShiftInvert<'p, 'a> {
    pencil: &'p QuadraticPencil<'a>,
    sigma: c64,
    lu: faer::sparse::linalg::solvers::Lu<usize, c64>,
}

impl<'p, 'a> ShiftInvert<'p, 'a> {
    fn new(pencil: &'p QuadraticPencil<'a>, sigma: c64) -> Result<Self, EigError> {
        let q = pencil.at(sigma)?;
        let lu = q.sp_lu().map_err(|e| EigError::Factorization {
            what: format!(
                "LU of K + sigma C + sigma^2 M at sigma = {sigma}: {}",
                crate::faer_error::describe_lu(e)
            ),
        })?;
        Ok(Self { pencil, sigma, lu })
    }

    fn apply(&self, b: &[c64]) -> Vec<c64> {
        let n = self.pencil.size();
        let (b1, b2) = b.split_at(n);
        let zero = c64::new(0.0, 0.0);
        let mut r = vec![zero; n];
        add_product(&mut r, self.pencil.m, b2, c64::new(-1.0, 0.0));
        if let Some(c) = self.pencil.c {
            add_product(&mut r, c, b1, c64::new(-1.0, 0.0));
        }
        add_product(&mut r, self.pencil.m, b1, -self.sigma);
        self.lu
            .solve_in_place(MatMut::from_column_major_slice_mut(&mut r, n, 1));
        let mut out = r.clone();
        out.extend((0..n).map(|i| b1[i] + self.sigma * r[i]));
        out
    }
}

/// A cell of the segment: `Im λ ∈ [lo, hi)` (rad/s).
#[derive(Clone, Copy, Debug)]
struct Cell {
    lo: f64,
    hi: f64,
}

/// The eigenpairs found in one cell, or `None` when its disk did not cover it.
fn solve_cell(
    pencil: &QuadraticPencil<'_>,
    cell: Cell,
    last: bool,
    opts: &QuadraticOptions,
    arnoldi: &mut Arnoldi,
    steps: &mut usize,
) -> Result<Option<Vec<QuadraticEigenpair>>, EigError> {
    let h = 0.5 * (cell.hi - cell.lo);
    let centre = c64::new(0.0, 0.5 * (cell.hi + cell.lo));
    let need = (h * h + opts.strip * opts.strip).sqrt();
    let op = ShiftInvert::new(pencil, centre)?;
    let apply = |b: &[c64]| op.apply(b);
    arnoldi.restart();
    let max = arnoldi.max_steps();
    let n = pencil.size();
    let mut check = 12.min(max);
    loop {
        while arnoldi.steps() < check && !arnoldi.is_invariant() {
            arnoldi.step(&apply);
        }
        let ritz = arnoldi.ritz()?;
        let mut radius = f64::INFINITY;
        let mut found = Vec::new();
        for r in ritz {
            if r.value.norm() == 0.0 {
                continue;
            }
            let lambda = centre + c64::new(1.0, 0.0) / r.value;
            if r.residual / r.value.norm_sqr() <= opts.tolerance * lambda.norm() {
                let inside =
                    lambda.im >= cell.lo && (lambda.im < cell.hi || last && lambda.im <= cell.hi);
                if inside && (lambda - centre).norm() <= need {
                    found.push((lambda, r.coefficients));
                }
            } else {
                radius = radius.min((lambda - centre).norm());
            }
        }
        let done = radius >= need || arnoldi.is_invariant();
        if done || arnoldi.steps() >= max {
            *steps += arnoldi.steps();
            if !done {
                return Ok(None);
            }
            let pairs = found
                .into_iter()
                .map(|(value, y)| {
                    let mut x = arnoldi.vector(&y);
                    x.truncate(n);
                    let nx = x.iter().map(|a| a.norm_sqr()).sum::<f64>().sqrt();
                    let x: Vec<c64> = x.iter().map(|a| a / nx).collect();
                    QuadraticEigenpair {
                        backward_error: pencil.backward_error(value, &x),
                        value,
                        vector: x,
                    }
                })
                .collect();
            return Ok(Some(pairs));
        }
        check = (check + 4).min(max);
    }
}

/// Every eigenvalue `λ` of the pencil with `Im λ ∈ [omega_lo, omega_hi]` and
/// `|Re λ| ≤ opts.strip` (module docs), `progress(done, total)` told after each cell (the
/// total grows when a cell is cut).
pub fn eigs_on_segment(
    pencil: &QuadraticPencil<'_>,
    omega_lo: f64,
    omega_hi: f64,
    opts: &QuadraticOptions,
    progress: &dyn Fn(usize, usize),
) -> Result<SegmentEigs, EigError> {
    let ordered = omega_lo.is_finite() && omega_hi.is_finite() && omega_lo < omega_hi;
    if !ordered || omega_lo < 0.0 {
        return Err(EigError::InvalidOption {
            what: format!("segment [{omega_lo}, {omega_hi}] rad/s: need 0 <= lo < hi"),
        });
    }
    let valid = opts.cell > 0.0 && opts.min_cell > 0.0 && opts.strip >= 0.0;
    if !valid || opts.max_krylov < 16 || opts.tolerance.is_nan() || opts.tolerance <= 0.0 {
        return Err(EigError::InvalidOption {
            what: "quadratic eigensolver: cell, min_cell > 0, strip >= 0, tolerance > 0 and a \
                   Krylov dimension of at least 16"
                .to_string(),
        });
    }
    let count = ((omega_hi - omega_lo) / (2.0 * opts.cell)).ceil().max(1.0) as usize;
    let width = (omega_hi - omega_lo) / count as f64;
    // Cells to do, in order of increasing frequency (a stack, the lowest on top).
    let mut todo: Vec<Cell> = (0..count)
        .rev()
        .map(|c| Cell {
            lo: omega_lo + c as f64 * width,
            hi: if c + 1 == count {
                omega_hi
            } else {
                omega_lo + (c + 1) as f64 * width
            },
        })
        .collect();
    let mut arnoldi = Arnoldi::new(2 * pencil.size(), opts.max_krylov.min(2 * pencil.size()));
    let (mut pairs, mut steps, mut shifts, mut total) = (Vec::new(), 0, 0, count);
    while let Some(cell) = todo.pop() {
        let last = cell.hi == omega_hi;
        shifts += 1;
        match solve_cell(pencil, cell, last, opts, &mut arnoldi, &mut steps)? {
            Some(found) => pairs.extend(found),
            None if 0.5 * (cell.hi - cell.lo) >= 2.0 * opts.min_cell => {
                let mid = 0.5 * (cell.lo + cell.hi);
                todo.push(Cell {
                    lo: mid,
                    hi: cell.hi,
                });
                todo.push(Cell {
                    lo: cell.lo,
                    hi: mid,
                });
                total += 2;
            }
            None => {
                return Err(EigError::InvalidOption {
                    what: format!(
                        "the eigenvalues near {:.1} rad/s are too dense for {} Krylov vectors \
                         even on a cell of half-height {:.2} rad/s: raise the Krylov dimension",
                        0.5 * (cell.lo + cell.hi),
                        opts.max_krylov,
                        0.5 * (cell.hi - cell.lo)
                    ),
                });
            }
        }
        progress(shifts, total);
    }
    pairs.sort_by(|a: &QuadraticEigenpair, b| a.value.im.total_cmp(&b.value.im));
    let worst = pairs.iter().map(|p| p.backward_error).fold(0.0, f64::max);
    Ok(SegmentEigs {
        pairs,
        shifts,
        steps,
        worst_backward_error: worst,
    })
}
