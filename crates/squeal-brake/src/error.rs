//! Errors of the brake model and its analyses.

/// A contact pair still open at the full clamp force ([`BrakeError::GapsNotClosed`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenPair {
    /// Pair number (1-based).
    pub pair: usize,
    /// Its initial gap `g0` (m; positive: open).
    pub initial_gap: f64,
    /// How far it is still open at the full load, `-δ` (m).
    pub opening: f64,
}

/// `pair 3 open by 12.3 um (initial gap 100.0 um), ...`.
fn open_pairs_text(pairs: &[OpenPair]) -> String {
    pairs
        .iter()
        .map(|p| {
            format!(
                "pair {} open by {:.3} um (initial gap {:.3} um)",
                p.pair,
                p.opening * 1e6,
                p.initial_gap * 1e6
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// What went wrong, in the user's terms.
#[derive(Debug, thiserror::Error)]
pub enum BrakeError {
    /// [`static_equilibrium`](crate::equilibrium::static_equilibrium) found every pair open
    /// (penetration ≤ 0) and the pad moving away from the disc: nothing presses the pad on
    /// the disc (a load of the wrong sign).
    #[error(
        "static equilibrium: the contact is open at every pair (no force holds the pad against the disc); check the piston load's sign and the gaps"
    )]
    ContactOpen,
    /// [`static_equilibrium`](crate::equilibrium::static_equilibrium): at the full clamp force
    /// every pair is still open. The pad's restraints (springs, abutments) carry the whole
    /// load before it reaches the disc; this open state is the model's equilibrium, and the
    /// brake does not brake.
    #[error(
        "static equilibrium: the full clamp force does not close the initial gaps; the pad's restraints carry the whole load before it touches the disc: {}. Reduce the gaps, or set [contact] close_initial_gaps = true to close them as the geometry adjustment of other codes does",
        open_pairs_text(pairs)
    )]
    GapsNotClosed {
        /// Every pair, with its initial gap and its opening at the full load.
        pairs: Vec<OpenPair>,
    },
    /// Newton's method for eq (14) used up
    /// [`NewtonOptions::max_iterations`](crate::equilibrium::NewtonOptions::max_iterations),
    /// or its line search found no step that lowers the residual.
    #[error(
        "static equilibrium: Newton's method did not converge in {iterations} iterations (relative residual {residual:.3e}, wanted {tolerance:.1e})"
    )]
    NewtonFailed {
        /// Newton iterations taken.
        iterations: usize,
        /// Relative residual reached, `||K x + F_nl - F_piston|| / max(||F_piston||, ||F_nl||)`.
        residual: f64,
        /// The relative residual asked for
        /// ([`NewtonOptions::tolerance`](crate::equilibrium::NewtonOptions::tolerance)).
        tolerance: f64,
    },
    /// A Newton step of eq (14) is not finite: the tangent stiffness `K + K_NL` is singular
    /// (a part free to move as a rigid body, a pad held only by open pairs, ...).
    #[error("static equilibrium: the tangent stiffness is singular (is every part held?)")]
    SingularTangent,
    /// [`modal_basis`](crate::modal::modal_basis): the Cholesky factorization of the mass
    /// matrix failed.
    #[error("the mass matrix is not positive definite")]
    MassNotPositive,
    /// [`modal_basis`](crate::modal::modal_basis): an eigenvalue `ω²` of the frictionless
    /// tangent stiffness is ≤ 0 or NaN (a rigid-body or unheld motion at μ = 0).
    #[error(
        "the frictionless tangent stiffness is not positive definite: the brake is not held at mu = 0"
    )]
    StiffnessNotPositive,
    /// faer's dense eigensolver failed: for the frictionless modes, or for the complex
    /// eigenvalues of the state matrix of eq (21).
    #[error("the dense eigenvalue solver did not converge")]
    EigenNoConvergence,
    /// [`modal_basis`](crate::modal::modal_basis): the dense symmetric eigensolver's
    /// residuals exceed `1e-12`, so the frictionless modes cannot be trusted.
    #[error(
        "the frictionless modes have a relative residual of {residual:.1e} (the dense eigensolver lost accuracy)"
    )]
    EigenInaccurate {
        /// Largest residual `||A y - s y||` of the eigenproblem scaled to unit max-norm.
        residual: f64,
    },
    /// [`LinearizedBrake::new`](crate::linearized::LinearizedBrake::new): the reference's
    /// `kt0` is not this brake's `K + Σ_p k0_p g_p g_pᵀ` to `1e-13` relative, so the reference
    /// was computed for another brake (or another contact scaling).
    #[error(
        "the frictionless reference does not belong to this brake (its tangent stiffness differs by {relative:.1e} relative)"
    )]
    ForeignReference {
        /// Largest entry of the difference over the largest entry of `kt0`.
        relative: f64,
    },
    /// A matrix or vector does not have the brake's number of dofs
    /// ([`Brake::validate`](crate::model::Brake::validate),
    /// [`LinearizedBrake::new`](crate::linearized::LinearizedBrake::new)).
    #[error("{what}: expected size {expected}, got {got}")]
    Dimension {
        /// Which matrix or vector.
        what: &'static str,
        /// The brake's number of dofs.
        expected: usize,
        /// Its size (rows, for a matrix).
        got: usize,
    },
    /// [`Brake::validate`](crate::model::Brake::validate): a pair's normal or tangent
    /// vector names a dof beyond the brake's size.
    #[error("contact pair {pair} refers to dof {dof} of a {dofs}-dof brake")]
    PairOutsideModel {
        /// Pair number (1-based).
        pair: usize,
        /// The dof index it names (0-based).
        dof: usize,
        /// The brake's number of dofs.
        dofs: usize,
    },
    /// [`Brake::validate`](crate::model::Brake::validate): a pair's element depends on the
    /// slip velocity but the pair has no
    /// [`surface_speed`](crate::model::ContactPair::surface_speed).
    #[error(
        "contact pair {pair} uses an element ({law}) whose friction depends on the sliding speed, but the disc's speed is not given: add a disc speed to the scene"
    )]
    NoSurfaceSpeed {
        /// Pair number (1-based).
        pair: usize,
        /// The element's [`name`](crate::contact::ContactLaw::name).
        law: String,
    },
    /// [`assemble`](crate::assemble::assemble): the reduced model lacks the `disc` or the
    /// `pad` part.
    #[error("the reduced model has no part named '{name}' (it has {have})")]
    NoPart {
        /// The missing part's name.
        name: String,
        /// The model's part names, quoted and comma-separated.
        have: String,
    },
    /// [`assemble`](crate::assemble::assemble): a contact point has no dof in a direction in
    /// which the contact normal or the sliding direction has a nonzero component.
    #[error(
        "the {part}'s reduced model has no dof for point {point} along [{:.6}, {:.6}, {:.6}] (its dofs leave {:.1e} of that direction out)",
        direction[0], direction[1], direction[2], missing
    )]
    MissingPointDof {
        /// `disc` or `pad`.
        part: &'static str,
        /// The point's number among the part's points (1-based).
        point: usize,
        /// The unit direction asked for.
        direction: [f64; 3],
        /// The length of its part outside the span of the point's dofs.
        missing: f64,
    },
    /// [`assemble`](crate::assemble::assemble): the disc face's normal at a pair is further
    /// from the scene's `[contact] normal` than
    /// [`NORMAL_TOLERANCE_DEG`](crate::assemble::NORMAL_TOLERANCE_DEG).
    #[error(
        "contact pair {pair}: the disc face's normal [{:.4}, {:.4}, {:.4}] is {degrees:.1} degrees from the scene's contact normal: the scene and the mesh disagree (fix [contact] normal, or remove it to take the mesh's normals)",
        mesh[0], mesh[1], mesh[2]
    )]
    NormalDisagrees {
        /// Pair number (1-based).
        pair: usize,
        /// The normal from the mesh.
        mesh: [f64; 3],
        /// Angle to the scene's normal (degrees).
        degrees: f64,
    },
    /// [`assemble`](crate::assemble::assemble): neither point of a pair carries a normal (a
    /// node interface without a contact face) and the scene gives none.
    #[error(
        "contact pair {pair}: the reduced model gives no normal there (no contact face set): give [contact] normal"
    )]
    NoNormal {
        /// Pair number (1-based).
        pair: usize,
    },
    /// [`assemble`](crate::assemble::assemble): tangent sliding at a pair on the disc's axis,
    /// where the rotation's tangent is undefined.
    #[error("contact pair {pair} lies on the disc's axis: the rotation has no tangent there")]
    OnAxis {
        /// Pair number (1-based).
        pair: usize,
    },
    /// [`assemble`](crate::assemble::assemble): tangent sliding needs the disc's sense of
    /// rotation.
    #[error(
        "sliding along the rotation's tangent needs its sense: give [rotation] with axis and sense"
    )]
    NoSense,
    /// [`assemble`](crate::assemble::assemble): a global sliding direction points against the
    /// disc's motion at a pair (the friction would push the pad the wrong way).
    #[error(
        "contact pair {pair}: the sliding direction points against the disc's motion there (cosine {cosine:.3} with the rotation's tangent): reverse it or the rotation's sense"
    )]
    SlidingAgainstRotation {
        /// Pair number (1-based).
        pair: usize,
        /// Cosine of the angle between the sliding direction and the tangent.
        cosine: f64,
    },
    /// [`unit`](crate::assemble::unit): a direction vector is zero or not finite.
    #[error("the {what} direction has zero length or is not finite")]
    BadDirection {
        /// Which direction (`contact normal`, `sliding`).
        what: &'static str,
    },
    /// [`assemble`](crate::assemble::assemble): the unit sliding direction is not
    /// perpendicular to the unit contact normal (`|n · s| > 1e-6`).
    #[error(
        "the sliding direction must be tangent to the contact (normal . sliding = {dot:.3e}); give a direction in the contact plane"
    )]
    SlidingNotTangent {
        /// `n · s` of the unit vectors.
        dot: f64,
    },
    /// [`assemble`](crate::assemble::assemble): the stiffness is
    /// [`Stiffness::PerArea`](crate::assemble::Stiffness::PerArea), but neither point of a pair
    /// has an area and no `point_area` is given.
    #[error(
        "contact pair {pair}: a contact stiffness per unit area needs the pair's area, but the reduced model has none (a node interface without a contact face set): give the parts a contact face, a point area ([contact] point_area in a scene) or stiffnesses per point"
    )]
    NoArea {
        /// Pair number (1-based).
        pair: usize,
    },
    /// [`assemble`](crate::assemble::assemble): a list of initial gaps
    /// ([`InitialGaps::PerPair`](crate::assemble::InitialGaps::PerPair)) does not have one
    /// value per contact pair.
    #[error(
        "{given} initial gaps are given for {pairs} contact pairs: give one value for all pairs or one per pair"
    )]
    GapCount {
        /// Values given.
        given: usize,
        /// Pairs formed.
        pairs: usize,
    },
    /// [`assemble`](crate::assemble::assemble): the pad's reduced model has no point of role
    /// piston.
    #[error("the pad has no piston points: the load has nowhere to act")]
    NoPistons,
    /// [`assemble`](crate::assemble::assemble): a connection between parts names a part or a
    /// coupling point the reduced model does not have ([`crate::connections`]).
    #[error("connection {name}: {what} (reduce the model again)")]
    Connection {
        /// The connection's name.
        name: String,
        /// What is missing.
        what: String,
    },
    /// [`assemble`](crate::assemble::assemble): the disc's and the pad's contact points could
    /// not be paired ([`squeal_reduce::brake::pair_contact_points`]).
    #[error(transparent)]
    Pairing(#[from] squeal_reduce::ReduceError),
    /// [`check_ascending`](crate::sweep::check_ascending): a friction value is not finite or
    /// not greater than the one before it.
    #[error("the friction values of a sweep must be ascending (value {index} is {value})")]
    FrictionNotAscending {
        /// Its position in the list (1-based).
        index: usize,
        /// The value.
        value: f64,
    },
    /// The dense refinement of a crossing ended on a bracket whose ends do not straddle the
    /// threshold, or across which the real part still differs by more than `1e-6 |λ|` and than
    /// the square-root onset of an undamped coalescence allows (a jump between modes rather
    /// than a root, or
    /// [`SweepOptions::max_refinements`](crate::sweep::SweepOptions::max_refinements) used up).
    #[error(
        "the Hopf point could not be resolved: across the bracket [{:.10}, {:.10}] the real part jumps from {:.3e} to {:.3e} 1/s instead of crossing zero (the modes could not be followed; sweep with finer friction steps)",
        bracket.0, bracket.1, real_parts.0, real_parts.1
    )]
    HopfNotResolved {
        /// The final bracket `(μ-, μ+)`.
        bracket: (f64, f64),
        /// `Re λ` (s⁻¹) of the followed modes (the larger of the pair) at its ends.
        real_parts: (f64, f64),
    },
    /// [`Damping::modal`](crate::modal::Damping::modal): extra damping on a mode the basis does
    /// not have.
    #[error("extra damping on mode {mode}, but the brake has {modes} modes")]
    ModeOutOfRange {
        /// The mode asked (1-based).
        mode: usize,
        /// How many modes there are.
        modes: usize,
    },
    /// [`normal_form`](crate::criticality::normal_form): a pair (1-based) is open at the
    /// equilibrium at μ0, where the normal form needs a smooth contact law.
    #[error(
        "contact pair {pair} is open at the Hopf point's equilibrium: the contact law is not smooth there and the normal form does not apply"
    )]
    OpenAtHopf {
        /// The open pair (1-based).
        pair: usize,
    },
    /// [`check_ascending`](crate::sweep::check_ascending): the list of friction values is
    /// empty.
    #[error("a sweep needs at least one friction value")]
    NoFrictionValues,
    /// [`stability`](crate::analysis::stability): pair damping is asked with
    /// [`PairChoice::Auto`](crate::analysis::PairChoice::Auto), and the preliminary sweep found
    /// an in-band Hopf point without a partner branch. (No Hopf point at all is no error: the
    /// brake is stable over the range and the pair damping names no modes.)
    #[error(
        "the coalescing pair could not be picked automatically (the Hopf point's mode has no partner branch with the global damping alone): give it by mode numbers"
    )]
    NoPairFound,
    /// A mode number of the damped pair is not below the number of modes
    /// ([`stability`](crate::analysis::stability)), or an extra damping names a missing mode
    /// ([`Damping::modal`](crate::modal::Damping::modal), then `first == second`).
    #[error("pair modes ({first}, {second}) are outside the brake's {modes} modes")]
    PairOutOfRange {
        /// Mode 1's number (1-based).
        first: usize,
        /// Mode 2's number (1-based).
        second: usize,
        /// Number of modes of the basis.
        modes: usize,
    },
    /// [`circumferential_orders`](crate::studies::circumferential_orders) or
    /// [`pad_profile`](crate::studies::pad_profile): too few samples, or not as many positions
    /// as values.
    #[error(
        "{what} needs at least {needed} samples, as many positions as values (got {positions} and {values})"
    )]
    Samples {
        /// Which analysis.
        what: &'static str,
        /// Fewest samples it accepts.
        needed: usize,
        /// Number of positions given.
        positions: usize,
        /// Number of values given.
        values: usize,
    },
    /// [`circumferential_orders`](crate::studies::circumferential_orders): an angle or a value
    /// is NaN or infinite.
    #[error("{what} got a non-finite position or value")]
    NonFiniteSample {
        /// Which analysis.
        what: &'static str,
    },
    /// [`circumferential_orders`](crate::studies::circumferential_orders): the highest order
    /// asked is not below half its 360 interpolation points.
    #[error("circumferential orders up to {max} only (asked {asked})")]
    OrderTooHigh {
        /// The order asked.
        asked: usize,
        /// The highest order available (179).
        max: usize,
    },
    /// An analysis that assumes a diagonal modal damping `D` (eq 13) was given a full one
    /// ([`other_mode_growth`](crate::studies::other_mode_growth)).
    #[error("{analysis} needs a diagonal modal damping (eq 13); this brake's is a full matrix")]
    NeedsDiagonalDamping {
        /// Which analysis.
        analysis: &'static str,
    },
    /// An analysis not yet written for a stiffness acting on the vibration only
    /// ([`crate::vibration_only`]).
    #[error(
        "{analysis} does not take connectors with vibration_only = true yet (their equilibrium's derivatives would use the whole stiffness): run it without that key"
    )]
    VibrationOnly {
        /// Which analysis.
        analysis: &'static str,
    },
    /// [`scaled_brake`](crate::studies::scaled_brake): a pressure or stiffness factor is not
    /// a finite positive number.
    #[error("the {what} must be a positive number (got {value})")]
    NotPositive {
        /// Which factor.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// [`case_damping`](crate::studies::case_damping): a pair damping factor is negative or
    /// not finite.
    #[error("the {what} must be zero or positive (got {value})")]
    Negative {
        /// Which factor.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// [`crate::sensitivity`]: the unstable mode could not be followed to the Hopf point (the
    /// continuation or Newton's method on `Re λ = τ` failed).
    #[error(
        "the sensitivities could not follow the unstable mode near mu = {mu}: {what} (the Hopf point is too close to a coalescence or the sweep's bracket is too wide)"
    )]
    HopfNotFollowed {
        /// What failed.
        what: &'static str,
        /// The friction value reached.
        mu: f64,
    },
}
