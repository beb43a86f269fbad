//! squeal-eigs: sparse Cholesky factorization and the lowest modes of
//! K phi = w^2 M phi for the Craig-Bampton reduction (Coudeyras, Sinou,
//! Nacivet, JSV 2009, eqs. 3-5).
//!
//! Input convention: K and M are `faer::sparse::SparseColMat<usize, f64>`
//! storing BOTH triangles (full symmetric storage), as squeal-fe assembles
//! them. A matrix holding one triangle only is rejected with
//! [`EigError::NotSymmetric`].
//!
//! - [`SparseCholesky`]: sparse Cholesky (faer) with a fill-reducing ordering
//!   ([`FillOrdering`]: nested dissection of the node graph by default, or
//!   AMD), multi-RHS solves, [`SparseCholesky::constraint_modes`] for
//!   T_C = -K_II^-1 K_IB (eq. 3).
//!   Its solves are our own supernodal triangular solves, parallel over
//!   subtrees of the elimination tree with thread-count independent bits.
//! - [`lowest_modes`] / [`lowest_modes_with_factor`]: shift-invert block
//!   Lanczos (pure Rust, default; [`EigOptions::block_size`] = 1 gives the
//!   single-vector thick-restart Lanczos) or ARPACK (feature `arpack`), with
//!   a Sturm check that runs beside the iteration once the Ritz values place
//!   its bound. Above [`EigOptions::slice`] wanted pairs the spectrum is
//!   sliced over several shifts (shifted block Lanczos with LBL^T factors).
//! - [`Constraints`] / [`ConstrainedFactor`] / [`lowest_modes_constrained`]:
//!   the same for eigenvectors constrained to C x = 0 (projected
//!   shift-invert operator, constraint modes, constrained Sturm counts).
//! - [`count_below`] / [`count_below_constrained`] / [`inertia`]: Sturm
//!   counts from a sparse LBL^T (inside the eigensolver on the factor's
//!   symbolic analysis or ordering).
//! - [`arnoldi`]: a complex Arnoldi factorization for shift-invert solvers of non-symmetric
//!   problems; [`quadratic`]: the eigenvalues of a sparse quadratic eigenproblem
//!   `(λ² M + λ C + K) x = 0` near a segment of the imaginary axis (the full-model brake).
//! - [`model_problems`]: matrices with known spectra for tests and benchmarks.

pub mod arnoldi;
mod block;
mod cholesky;
mod constraint;
pub mod dense;
mod error;
pub mod faer_error;
mod inertia;
mod lanczos;
pub mod model_problems;
mod ordering;
pub mod quadratic;
mod slicing;
mod solver;
mod sparse;
mod trisolve;

#[cfg(feature = "arpack")]
mod arpack;

pub use cholesky::{CholeskyOptions, FactorAnalysis, FactorStats, SparseCholesky};
pub use constraint::{ConstrainedFactor, Constraints};
pub use error::EigError;
pub use inertia::{Inertia, count_below, count_below_constrained, inertia};
pub use ordering::FillOrdering;
pub use solver::{
    Backend, EigOptions, EigStats, Modes, backward_errors, lowest_modes, lowest_modes_constrained,
    lowest_modes_with_factor, sturm_check, sturm_check_with,
};
pub use sparse::{check_pair, check_symmetric, shifted};
