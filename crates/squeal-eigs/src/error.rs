//! Typed errors of the crate.

use thiserror::Error;

/// Everything that can go wrong in a factorization or an eigensolve.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum EigError {
    /// A matrix is not square, or K and M (or a right-hand side) do not match.
    #[error("dimension mismatch: {what}")]
    DimensionMismatch {
        /// Which shapes disagree, in words.
        what: String,
    },
    /// A matrix holds NaN or infinity.
    #[error("matrix {matrix} has a non-finite entry in column {col}")]
    NonFinite {
        /// "K", "M" or "A".
        matrix: &'static str,
        /// Column of the first offending entry.
        col: usize,
    },
    /// The matrix is not stored with both triangles, or is not symmetric.
    #[error(
        "matrix {matrix} is not symmetric at ({row}, {col}): both triangles must be stored \
         (a MatrixMarket 'symmetric' file holds only one)"
    )]
    NotSymmetric {
        /// "K", "M" or "A".
        matrix: &'static str,
        /// Row of the first offending entry.
        row: usize,
        /// Column of the first offending entry.
        col: usize,
    },
    /// The mass matrix has a diagonal entry that is not positive.
    #[error("mass matrix diagonal entry {index} is not positive")]
    MassNotPositive {
        /// Dof index.
        index: usize,
    },
    /// Cholesky met a non-positive pivot: the matrix (K - sigma M) is not
    /// positive definite. For K_II with sigma = 0 this means the part is not
    /// held (rigid-body motion left free): K_II is singular.
    #[error(
        "matrix is not positive definite (non-positive pivot at column {column}); \
         for K - sigma M: the shift is not below the lowest eigenvalue, or K is singular \
         (structure not held)"
    )]
    NotPositiveDefinite {
        /// Column (in the input numbering) where the factorization broke down.
        column: usize,
    },
    /// The shift hits an eigenvalue: the LBL^T factorization met an exactly
    /// singular pivot, so the inertia is undefined.
    #[error("shift {sigma} is an eigenvalue (singular pivot): inertia undefined")]
    SingularShift {
        /// The shift.
        sigma: f64,
    },
    /// The factorization given to the eigensolver is not one of K - sigma M.
    #[error("factorization does not match K - sigma M (relative check error {error:e})")]
    FactorMismatch {
        /// ||x - F^-1 (K - sigma M) x|| / ||x|| for a test vector x.
        error: f64,
    },
    /// More eigenvalues were asked for than the problem has (or the basis allows).
    #[error("asked for {requested} eigenvalues, at most {available} available")]
    TooManyRequested {
        /// Number asked for.
        requested: usize,
        /// Number available.
        available: usize,
    },
    /// An option is out of range.
    #[error("invalid option: {what}")]
    InvalidOption {
        /// What is wrong, in words.
        what: String,
    },
    /// The iteration did not converge within `max_iter` restarts.
    #[error(
        "eigensolver did not converge: {converged} of {requested} eigenpairs after {iterations} \
         iterations (worst residual estimate {worst:e})"
    )]
    NotConverged {
        /// Eigenpairs that reached the tolerance.
        converged: usize,
        /// Eigenpairs asked for (including the Sturm guard values).
        requested: usize,
        /// Restart cycles done.
        iterations: usize,
        /// Residual estimates ||OP y - theta y||_M / |theta| of the wanted Ritz pairs.
        residuals: Vec<f64>,
        /// Largest of `residuals`.
        worst: f64,
    },
    /// The Sturm count (inertia of K - bound M) disagrees with the number of
    /// eigenvalues the solver found below the bound: some were missed.
    #[error(
        "Sturm check failed: {expected} eigenvalues lie below {bound:e} but the solver found \
         {found}"
    )]
    MissedEigenvalues {
        /// The bound (just above the highest eigenvalue kept).
        bound: f64,
        /// Eigenvalues below `bound` according to the Sturm count.
        expected: usize,
        /// Eigenvalues below `bound` the solver found.
        found: usize,
    },
    /// The constraint rows are linearly dependent (or one is zero): C A^-1 C^T
    /// is singular.
    #[error(
        "constraint rows are linearly dependent (row {row} adds nothing to the rows before it)"
    )]
    DependentConstraints {
        /// First row found dependent on the ones before it.
        row: usize,
    },
    /// The dense eigensolver of the projected problem failed.
    #[error("dense projected eigenproblem failed to converge")]
    DenseEigen,
    /// faer could not allocate or compute the symbolic analysis.
    #[error("sparse factorization failed: {what}")]
    Factorization {
        /// faer's message.
        what: String,
    },
    /// ARPACK returned an error code (see the dsaupd/dseupd documentation).
    #[error("ARPACK {routine} returned info = {info}")]
    Arpack {
        /// "dsaupd" or "dseupd".
        routine: &'static str,
        /// ARPACK's info code.
        info: i32,
    },
    /// The requested backend was not compiled in.
    #[error("backend {0} is not compiled in (enable the cargo feature)")]
    BackendUnavailable(&'static str),
}
