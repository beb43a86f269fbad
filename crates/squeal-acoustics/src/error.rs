//! Typed errors of the acoustic estimates: inputs that do not fit together or cannot describe
//! a radiating surface. None is silently turned into a number.

use thiserror::Error;

/// Everything that can go wrong in `squeal-acoustics`.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum AcousticsError {
    /// A list given by the caller does not have the length the surface needs.
    #[error("{what} has {got} entries, {expected} expected")]
    Length {
        /// Which list.
        what: &'static str,
        /// The length needed.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// A face refers to a node that is not in the node list.
    #[error("face {face} refers to node {node}, but there are {nodes} nodes")]
    NodeOutOfRange {
        /// The face (0-based).
        face: usize,
        /// The node index it holds.
        node: u32,
        /// Number of nodes.
        nodes: usize,
    },
    /// A face whose area element vanishes (or is not finite) at a quadrature point: its
    /// nodes are collinear, repeated or not finite.
    #[error("face {face} is degenerate: area element {jacobian:e} at quadrature point {point}")]
    DegenerateFace {
        /// The face (0-based).
        face: usize,
        /// The quadrature point (0-based).
        point: usize,
        /// `|∂x/∂ξ × ∂x/∂η|` there.
        jacobian: f64,
    },
    /// A parameter that must be a finite positive number is not.
    #[error("{what} must be a finite positive number, got {value}")]
    Parameter {
        /// Which parameter.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// A microphone at a quadrature point or face centroid of the surface, where the
    /// integrals are singular.
    #[error("microphone at ({}, {}, {}) m lies on the radiating surface: move it off the surface", at[0], at[1], at[2])]
    MicrophoneOnSurface {
        /// The microphone's position (m).
        at: [f64; 3],
    },
    /// A quadrature rule that cannot be built.
    #[error("quadrature rule: {0}")]
    Rule(String),
}

/// Results of this crate.
pub type Result<T> = std::result::Result<T, AcousticsError>;
