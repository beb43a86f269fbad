//! Errors of the brake model and its analyses.

/// What went wrong, in the user's terms.
#[derive(Debug, thiserror::Error)]
pub enum BrakeError {
    #[error(
        "static equilibrium: the contact is open at every pair (no force holds the pad against the disc); check the piston load's sign and the gaps"
    )]
    ContactOpen,
    #[error(
        "static equilibrium: Newton's method did not converge in {iterations} iterations (relative residual {residual:.3e}, wanted {tolerance:.1e})"
    )]
    NewtonFailed {
        iterations: usize,
        residual: f64,
        tolerance: f64,
    },
    #[error("static equilibrium: the tangent stiffness is singular (is every part held?)")]
    SingularTangent,
    #[error("the mass matrix is not positive definite")]
    MassNotPositive,
    #[error(
        "the frictionless tangent stiffness is not positive definite: the brake is not held at mu = 0"
    )]
    StiffnessNotPositive,
    #[error("the eigenvalue solver failed: {0}")]
    Eigen(String),
    #[error("{0}")]
    Invalid(String),
}
