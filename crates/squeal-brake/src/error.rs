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
    #[error("the dense eigenvalue solver did not converge")]
    EigenNoConvergence,
    #[error(
        "the frictionless modes have a relative residual of {residual:.1e} (the dense eigensolver lost accuracy)"
    )]
    EigenInaccurate { residual: f64 },
    #[error(
        "the frictionless reference does not belong to this brake (its tangent stiffness differs by {relative:.1e} relative)"
    )]
    ForeignReference { relative: f64 },
    #[error("{what}: expected size {expected}, got {got}")]
    Dimension {
        what: &'static str,
        expected: usize,
        got: usize,
    },
    #[error("contact pair {pair} refers to dof {dof} of a {dofs}-dof brake")]
    PairOutsideModel {
        pair: usize,
        dof: usize,
        dofs: usize,
    },
    #[error(
        "contact pair {pair} uses an element ({law}) whose friction depends on the sliding speed, but the disc's speed is not given: add a disc speed to the scene"
    )]
    NoSurfaceSpeed { pair: usize, law: String },
    #[error("the reduced model has no part named '{name}' (it has {have})")]
    NoPart { name: String, have: String },
    #[error("the {part}'s reduced model has no dof for point {point} in direction {direction}")]
    MissingPointDof {
        part: &'static str,
        point: usize,
        direction: char,
    },
    #[error("the {what} direction has zero length or is not finite")]
    BadDirection { what: &'static str },
    #[error(
        "the sliding direction must be tangent to the contact (normal . sliding = {dot:.3e}); give a direction in the contact plane"
    )]
    SlidingNotTangent { dot: f64 },
    #[error(
        "contact pair {pair}: a contact stiffness per unit area needs the pair's area, but the reduced model has none (node interface): give a point area or stiffnesses per point"
    )]
    NoArea { pair: usize },
    #[error("the pad has no piston points: the load has nowhere to act")]
    NoPistons,
    #[error(transparent)]
    Pairing(#[from] squeal_reduce::ReduceError),
    #[error("the friction values of a sweep must be ascending (value {index} is {value})")]
    FrictionNotAscending { index: usize, value: f64 },
    #[error(
        "the Hopf point could not be resolved: across the bracket [{:.10}, {:.10}] the real part jumps from {:.3e} to {:.3e} 1/s instead of crossing zero (the modes could not be followed; sweep with finer friction steps)",
        bracket.0, bracket.1, real_parts.0, real_parts.1
    )]
    HopfNotResolved {
        bracket: (f64, f64),
        real_parts: (f64, f64),
    },
    #[error(
        "contact pair {pair} is open at the Hopf point's equilibrium: the contact law is not smooth there and the normal form does not apply"
    )]
    OpenAtHopf { pair: usize },
    #[error("a sweep needs at least one friction value")]
    NoFrictionValues,
    #[error(
        "the coalescing pair could not be picked automatically (no Hopf point in the band with the global damping alone): give it by mode numbers"
    )]
    NoPairFound,
    #[error("pair modes ({first}, {second}) are outside the brake's {modes} modes")]
    PairOutOfRange {
        first: usize,
        second: usize,
        modes: usize,
    },
    #[error(
        "{what} needs at least {needed} samples, as many positions as values (got {positions} and {values})"
    )]
    Samples {
        what: &'static str,
        needed: usize,
        positions: usize,
        values: usize,
    },
    #[error("{what} got a non-finite position or value")]
    NonFiniteSample { what: &'static str },
    #[error("circumferential orders up to {max} only (asked {asked})")]
    OrderTooHigh { asked: usize, max: usize },
    #[error("{analysis} needs a diagonal modal damping (eq 13); this brake's is a full matrix")]
    NeedsDiagonalDamping { analysis: &'static str },
    #[error("the {what} must be a positive number (got {value})")]
    NotPositive { what: &'static str, value: f64 },
    #[error("the {what} must be zero or positive (got {value})")]
    Negative { what: &'static str, value: f64 },
}
