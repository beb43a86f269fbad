//! Linear constraints C x = 0 on the eigenvectors: the fixed-interface
//! problem of a Craig-Bampton reduction whose boundary coordinates are
//! weighted means of many dofs (contact patches), r = C u held at zero.
//!
//! # The constrained pencil
//!
//! With C (p x n, full row rank) the problem is
//!
//! ```text
//! K phi = lambda M phi + C^T mu,    C phi = 0,
//! ```
//!
//! the stationary points of the Rayleigh quotient on null(C); its
//! eigenvectors are M-orthogonal.
//!
//! # Shift-invert
//!
//! With A = K - sigma M positive definite (a Cholesky factor of it),
//! X = A^-1 C^T and S = C X (p x p, positive definite), the saddle-point
//! system
//!
//! ```text
//! [A  C^T] [x ]   [M b]
//! [C   0 ] [mu] = [ 0 ]
//! ```
//!
//! has the solution x = P A^-1 M b with P = I - X S^-1 C, so that the
//! operator OP = P A^-1 M maps into null(C) (C P = 0) and is self-adjoint in
//! the M inner product: for x_v = OP v and x_w = OP w,
//! x_v^T M w = x_v^T (A x_w + C^T mu_w) = x_v^T A x_w, symmetric in v and w
//! because C x_v = 0. Its nonzero eigenvalues are theta = 1 / (lambda - sigma)
//! of the constrained pencil, so shift-invert Lanczos runs unchanged on OP,
//! with every basis vector in null(C); a vector that is not (a random start
//! vector) is brought there by P. One application costs one solve with the
//! factor and products with the n x p matrix X: the sparsity of A is that of
//! K, whatever the constraints couple (eliminating one dof per constraint
//! instead, as a null-space basis does, joins all dofs of a row into a dense
//! block of the reduced matrix and multiplies the fill of its factor).
//!
//! # Constraint modes
//!
//! Column j of X S^-1 minimizes x^T A x under C x = e_j (Lagrange:
//! A x = C^T mu and C x = e_j give mu = S^-1 e_j). With sigma = 0 these are
//! the static constraint modes of eq. (3) of Coudeyras et al. for the
//! constrained coordinates.
//!
//! # Sturm count
//!
//! Let Z span null(C). The eigenvalues of the constrained pencil below b are
//! the negative eigenvalues of Z^T (K - b M) Z. With A_b = K - b M
//! nonsingular and B = [A_b C^T; C 0] the bordered matrix,
//! In(B) = In(Z^T A_b Z) + (p, 0, p) for C of full row rank (Chabrillac &
//! Crouzeix, Linear Algebra Appl. 63, 1984), and In(B) = In(A_b) +
//! In(-C A_b^-1 C^T) (Haynsworth's inertia additivity of the Schur
//! complement). Hence
//!
//! ```text
//! nu(Z^T A_b Z) = nu(A_b) - nu(C A_b^-1 C^T):
//! ```
//!
//! one LBL^T factorization of A_b (its inertia, see [`crate::inertia`]), p
//! solves with it, and the inertia of a p x p matrix.

use crate::EigError;
use crate::cholesky::SparseCholesky;
use crate::lanczos::ShiftSolve;
use crate::sparse::update_rows;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{
    LltRegularization, cholesky_in_place, cholesky_in_place_scratch,
};
use faer::linalg::solvers::Solve;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Accum, Mat, MatMut, MatRef, Par};

/// A pivot of S = C A^-1 C^T (squared) below this fraction of its diagonal
/// entry means dependent constraint rows.
const DEPENDENT_ROWS: f64 = 1e-12;

/// The rows of C: `rows[i]` lists `(column, value)` of row i.
#[derive(Debug, Clone, PartialEq)]
pub struct Constraints {
    n: usize,
    rows: Vec<Vec<(usize, f64)>>,
}

impl Constraints {
    /// Constraints on vectors of length `n`; entries of a row may repeat a
    /// column (they add up).
    pub fn new(n: usize, rows: Vec<Vec<(usize, f64)>>) -> Result<Self, EigError> {
        for row in &rows {
            for &(j, v) in row {
                if j >= n {
                    return Err(EigError::DimensionMismatch {
                        what: format!("constraint column {j} for vectors of length {n}"),
                    });
                }
                if !v.is_finite() {
                    return Err(EigError::NonFinite {
                        matrix: "C",
                        col: j,
                    });
                }
            }
        }
        Ok(Self { n, rows })
    }

    /// Number of constraints p.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Length n of the vectors constrained.
    pub fn n(&self) -> usize {
        self.n
    }

    /// C X (p x k).
    pub fn apply(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        Mat::from_fn(self.len(), x.ncols(), |i, j| {
            self.rows[i].iter().map(|&(c, v)| v * x[(c, j)]).sum()
        })
    }

    /// C^T as a dense n x p matrix.
    pub fn transpose_dense(&self) -> Mat<f64> {
        let mut ct = Mat::zeros(self.n, self.len());
        for (i, row) in self.rows.iter().enumerate() {
            for &(c, v) in row {
                ct[(c, i)] += v;
            }
        }
        ct
    }

    /// r - C^T (C C^T)^-1 C r for each column r: the part of a residual that
    /// no constraint force C^T mu explains (least squares).
    pub(crate) fn remove_forces(&self, r: MatMut<'_, f64>) -> Result<(), EigError> {
        if self.is_empty() {
            return Ok(());
        }
        let ct = self.transpose_dense();
        let cct = self.apply(ct.as_ref());
        let l = dense_cholesky(cct)?;
        let mut g = self.apply(r.as_ref());
        spd_solve(l.as_ref(), g.as_mut());
        update_rows(r, ct.as_ref(), g.as_ref(), Accum::Add, -1.0);
        Ok(())
    }
}

/// X = A^-1 C^T and a factorization of S = C X for one factorization of
/// A = K - sigma M: the projector P = I - X S^-1 C and the correction
/// X S^-1 G. S is positive definite when A is (Cholesky), indefinite when
/// the shift lies inside the spectrum (LU with partial pivoting).
#[derive(Debug, Clone)]
pub(crate) struct Projector {
    constraints: Constraints,
    x: Mat<f64>,
    /// S = C X, symmetrized.
    schur: Mat<f64>,
    s: SchurFactor,
}

/// A factorization of the small matrix S = C A^-1 C^T.
#[derive(Debug, Clone)]
enum SchurFactor {
    /// Lower Cholesky factor.
    Cholesky(Mat<f64>),
    /// Partial-pivoting LU (A indefinite).
    Lu(faer::linalg::solvers::PartialPivLu<f64>),
}

impl Projector {
    /// X = A^-1 C^T by `solve` (applied to C^T in place), then S = C X.
    pub(crate) fn new(
        constraints: &Constraints,
        solve: &dyn ShiftSolve,
        definite: bool,
    ) -> Result<Self, EigError> {
        if constraints.n() != solve.order() {
            return Err(EigError::DimensionMismatch {
                what: format!(
                    "constraints on vectors of length {}, factor of order {}",
                    constraints.n(),
                    solve.order()
                ),
            });
        }
        let mut x = constraints.transpose_dense();
        solve.solve_in_place(x.as_mut())?;
        let s = constraints.apply(x.as_ref());
        let p = s.nrows();
        let schur = Mat::from_fn(p, p, |i, j| 0.5 * (s[(i, j)] + s[(j, i)]));
        let s = schur.clone();
        let s = match definite {
            true => SchurFactor::Cholesky(dense_cholesky(s)?),
            false => {
                let scale = s.norm_max();
                let lu = s.partial_piv_lu();
                let u = lu.U();
                let small = |i: usize| u[(i, i)].abs() <= DEPENDENT_ROWS * scale;
                let bad = (0..p).find(|&i| small(i) || u[(i, i)].is_nan());
                if let Some(row) = bad {
                    return Err(EigError::DependentConstraints { row });
                }
                SchurFactor::Lu(lu)
            }
        };
        Ok(Self {
            constraints: constraints.clone(),
            x,
            schur,
            s,
        })
    }

    /// S = C A^-1 C^T (its inertia enters the constrained Sturm count).
    pub(crate) fn schur(&self) -> &Mat<f64> {
        &self.schur
    }

    /// Number of constraints.
    pub(crate) fn len(&self) -> usize {
        self.constraints.len()
    }

    /// H <- S^-1 H.
    fn solve_s(&self, h: Mat<f64>) -> Mat<f64> {
        match &self.s {
            SchurFactor::Cholesky(l) => {
                let mut h = h;
                spd_solve(l.as_ref(), h.as_mut());
                h
            }
            SchurFactor::Lu(lu) => lu.solve(&h),
        }
    }

    /// X S^-1 G (n x k) for G (p x k).
    pub(crate) fn correction(&self, g: MatRef<'_, f64>) -> Result<Mat<f64>, EigError> {
        if g.nrows() != self.constraints.len() {
            return Err(EigError::DimensionMismatch {
                what: format!(
                    "{} rows for {} constraints",
                    g.nrows(),
                    self.constraints.len()
                ),
            });
        }
        let h = self.solve_s(g.to_owned());
        let mut out = Mat::zeros(self.x.nrows(), g.ncols());
        update_rows(
            out.as_mut(),
            self.x.as_ref(),
            h.as_ref(),
            Accum::Replace,
            1.0,
        );
        Ok(out)
    }

    /// Y <- P Y = Y - X S^-1 C Y: into null(C).
    pub(crate) fn project(&self, mut y: MatMut<'_, f64>) {
        if self.constraints.is_empty() {
            return;
        }
        let h = self.solve_s(self.constraints.apply(y.as_ref()));
        update_rows(y.as_mut(), self.x.as_ref(), h.as_ref(), Accum::Add, -1.0);
    }
}

/// A Cholesky factor of A = K - sigma M with constraints: X = A^-1 C^T and
/// the Cholesky factor of S = C X, for the constrained shift-invert operator
/// and the constraint modes (see the module documentation).
#[derive(Debug, Clone)]
pub struct ConstrainedFactor<'a> {
    factor: &'a SparseCholesky,
    constraints: &'a Constraints,
    projector: Projector,
}

impl<'a> ConstrainedFactor<'a> {
    /// Solves A X = C^T (p columns) and factors S = C X. Dependent (or zero)
    /// constraint rows are [`EigError::DependentConstraints`].
    pub fn new(factor: &'a SparseCholesky, constraints: &'a Constraints) -> Result<Self, EigError> {
        let projector = Projector::new(constraints, factor, true)?;
        Ok(Self {
            factor,
            constraints,
            projector,
        })
    }

    /// The Cholesky factor of A.
    pub fn factor(&self) -> &'a SparseCholesky {
        self.factor
    }

    /// The constraints.
    pub fn constraints(&self) -> &'a Constraints {
        self.constraints
    }

    /// The projector of the constrained operator.
    pub(crate) fn projector(&self) -> &Projector {
        &self.projector
    }

    /// X S^-1 G (n x k) for G (p x k). With G = I: the constraint modes.
    pub fn correction(&self, g: MatRef<'_, f64>) -> Result<Mat<f64>, EigError> {
        self.projector.correction(g)
    }

    /// Y <- P Y = Y - X S^-1 C Y: into null(C).
    pub fn project(&self, y: MatMut<'_, f64>) {
        self.projector.project(y)
    }
}

/// Lower Cholesky factor of a small symmetric positive definite matrix
/// (faer's dense kernel, sequential), or [`EigError::DependentConstraints`]
/// at a pivot that lost all but 12 digits to cancellation.
fn dense_cholesky(mut a: Mat<f64>) -> Result<Mat<f64>, EigError> {
    let p = a.nrows();
    let diag: Vec<f64> = (0..p).map(|i| a[(i, i)]).collect();
    let req = cholesky_in_place_scratch::<f64>(p, Par::Seq, Default::default());
    let mut mem = MemBuffer::try_new(req).map_err(|_| EigError::Factorization {
        what: "cannot allocate a dense Cholesky workspace".into(),
    })?;
    let result = cholesky_in_place(
        a.as_mut(),
        LltRegularization::default(),
        Par::Seq,
        MemStack::new(&mut mem),
        Default::default(),
    );
    let bad = (0..p).find(|&i| {
        let d = a[(i, i)];
        !(d.is_finite() && d * d > DEPENDENT_ROWS * diag[i].abs())
    });
    match (result, bad) {
        (Ok(_), None) => Ok(a),
        (_, Some(row)) => Err(EigError::DependentConstraints { row }),
        (Err(_), None) => Err(EigError::DependentConstraints { row: 0 }),
    }
}

/// B <- (L L^T)^-1 B.
fn spd_solve(l: MatRef<'_, f64>, mut b: MatMut<'_, f64>) {
    solve_lower_triangular_in_place(l, b.as_mut(), Par::Seq);
    solve_upper_triangular_in_place(l.transpose(), b.as_mut(), Par::Seq);
}
