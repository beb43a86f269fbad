//! Typed errors of the harmonic balance core.

use crate::lm::{LmReport, LmStop};

/// Everything that can go wrong when building or solving a harmonic balance problem.
#[derive(Debug, thiserror::Error)]
pub enum HbmError {
    /// A layout needs at least one dof.
    #[error("a harmonic layout needs at least one dof")]
    NoDofs,
    /// The layout would exceed [`crate::MAX_COEFFICIENTS`] (the dense Jacobian must fit in memory).
    #[error(
        "layout of {n_dofs} dofs x (2*{n_harmonics}+1) blocks exceeds the limit of {limit} coefficients"
    )]
    LayoutTooLarge {
        /// Requested number of dofs.
        n_dofs: usize,
        /// Requested number of harmonics.
        n_harmonics: usize,
        /// The limit on `n_dofs * (2 * n_harmonics + 1)`.
        limit: usize,
    },
    /// Too few time samples: the transforms need `n_samples >= 2 H + 1` to be invertible.
    #[error(
        "{n_samples} time samples cannot resolve {n_harmonics} harmonics (need at least {min})"
    )]
    TooFewSamples {
        /// Requested number of samples.
        n_samples: usize,
        /// Number of harmonics of the layout.
        n_harmonics: usize,
        /// The minimum, `2 H + 1`.
        min: usize,
    },
    /// Too many time samples (memory bound on the time-domain buffers).
    #[error(
        "{n_samples} time samples x {per_sample} values per sample exceeds the limit of {limit}"
    )]
    TooManySamples {
        /// Requested number of samples.
        n_samples: usize,
        /// Values stored per sample (displacements, velocities, forces, Jacobian entries).
        per_sample: usize,
        /// The limit on the product.
        limit: usize,
    },
    /// A slice or matrix argument has the wrong length or shape.
    #[error("{what}: expected length {expected}, got {got}")]
    Dimension {
        /// Which argument.
        what: &'static str,
        /// Expected length.
        expected: usize,
        /// Actual length.
        got: usize,
    },
    /// The Jacobian sparsity pattern of a nonlinear force names a dof outside `0..n`.
    #[error("Jacobian pattern entry ({row}, {col}) is outside a {n_dofs}-dof force")]
    PatternOutOfRange {
        /// Row (force component).
        row: usize,
        /// Column (displacement or velocity component).
        col: usize,
        /// Number of dofs of the force.
        n_dofs: usize,
    },
    /// The Jacobian sparsity pattern lists the same entry twice.
    #[error("Jacobian pattern entry ({row}, {col}) is listed twice")]
    PatternDuplicate {
        /// Row (force component).
        row: usize,
        /// Column (displacement or velocity component).
        col: usize,
    },
    /// The nonlinear force returned a NaN or infinite value at a time sample.
    #[error("nonlinear force is not finite at time sample {sample}")]
    NonFiniteForce {
        /// Index `j` of the sample `t_j = j T / N`.
        sample: usize,
    },
    /// A matrix or vector given by the caller contains NaN or infinity.
    #[error("{what} contains a non-finite value")]
    NonFiniteInput {
        /// Which argument.
        what: &'static str,
    },
    /// The frequency must be finite and positive.
    #[error("frequency omega = {omega} must be finite and > 0")]
    BadFrequency {
        /// The offending value.
        omega: f64,
    },
    /// The phase condition names a dof outside the layout, or the layout has no harmonic.
    #[error(
        "phase condition on dof {dof} is impossible for {n_dofs} dofs and {n_harmonics} harmonics"
    )]
    BadPhaseCondition {
        /// Requested dof.
        dof: usize,
        /// Dofs of the layout.
        n_dofs: usize,
        /// Harmonics of the layout.
        n_harmonics: usize,
    },
    /// With an unknown frequency the external force must be static (only the `U0c` block).
    #[error("external force has harmonic content but the frequency is unknown")]
    PeriodicForcingWithUnknownFrequency,
    /// Invalid solver options.
    #[error("invalid solver option: {0}")]
    BadOption(&'static str),
    /// A row scale that is not a positive number.
    #[error("the {what} of the residual rows must be a positive number (got {value})")]
    BadScale {
        /// Which scale.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// The eigenvalue the CHBM constraint follows could not be followed.
    #[error(
        "the eigenvalue of the equivalent linearization could not be followed from {from:.6e}: {why}"
    )]
    EigenvalueLost {
        /// The last eigenvalue that was known.
        from: faer::c64,
        /// What failed.
        why: String,
    },
    /// The Levenberg-Marquardt solver stopped without meeting the residual tolerance.
    /// The report holds the last iterate and the full history.
    #[error("harmonic balance did not converge ({stop}); last residual norm {residual_norm:e}", stop = .report.stop, residual_norm = .report.residual_norm)]
    NotConverged {
        /// The solver report (last iterate, history, stop reason).
        report: Box<LmReport>,
    },
    /// The tangent of a branch is not defined: the bordered Jacobian is singular (a branch
    /// point, or a family whose equations do not depend on the parameter).
    #[error("the branch's tangent is not defined (singular bordered Jacobian)")]
    SingularTangent,
    /// A family's parameter could not be put into its equations.
    #[error("the continuation parameter could not be set to {value}: {why}")]
    Parameter {
        /// The parameter value asked.
        value: f64,
        /// What failed.
        why: String,
    },
    /// The residual was NaN or infinite at the initial guess.
    #[error("residual is not finite at the initial guess")]
    NonFiniteStart,
    /// The Jacobian was NaN or infinite at an accepted iterate.
    #[error("Jacobian is not finite at iteration {iteration}")]
    NonFiniteJacobian {
        /// Trial count when it happened.
        iteration: usize,
    },
}

impl HbmError {
    /// The stop reason if the solver ran but did not converge.
    pub fn stop_reason(&self) -> Option<LmStop> {
        match self {
            HbmError::NotConverged { report } => Some(report.stop),
            _ => None,
        }
    }
}

impl HbmError {
    /// `Ok` when `got == expected`, else [`HbmError::Dimension`] naming `what`.
    pub fn check_dimension(
        what: &'static str,
        expected: usize,
        got: usize,
    ) -> Result<(), HbmError> {
        if got == expected {
            Ok(())
        } else {
            Err(HbmError::Dimension {
                what,
                expected,
                got,
            })
        }
    }
}
