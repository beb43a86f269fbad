//! The reduction's errors, named in the user's terms.

use crate::interface::InterfaceError;
use squeal_eigs::EigError;
use squeal_fe::FeError;

/// Errors of the reduction, named in the user's terms.
#[derive(Debug, thiserror::Error)]
pub enum ReduceError {
    /// An error in one part, with its mesh file named (the inner error is a field, not a
    /// `source()`, so an error chain prints it once).
    #[error("{}: {error}", path.display())]
    InMesh {
        /// The part's mesh file.
        path: std::path::PathBuf,
        /// What went wrong.
        error: Box<ReduceError>,
    },
    /// The mesh file could not be read.
    #[error(transparent)]
    Mesh(#[from] squeal_mesh::MeshError),
    /// A tie between two parts cannot be made ([`crate::part_tie`]).
    #[error(transparent)]
    PartTie(Box<crate::part_tie::PartTieError>),
    /// A part named by element set cannot be cut out of its file.
    #[error("{}: {error}", path.display())]
    Part {
        /// The assembly file.
        path: std::path::PathBuf,
        /// Why not.
        error: squeal_mesh::part::PartError,
    },
    /// A reduced-model file could not be read or written.
    #[error(transparent)]
    Rom(#[from] crate::rom::RomError),
    /// The inputs of the brake's reduction are inconsistent or out of range.
    #[error("invalid option: {0}")]
    Options(String),
    /// The mesh has what `squeal mesh info` calls an ERROR (inverted elements, elements
    /// naming a node the file never defines, which the reader leaves out): reduced as read,
    /// the part would be another part.
    #[error(
        "{finding} (element ids {ids}): the reduction refuses a mesh with errors; correct the file (`squeal mesh info` lists every finding)"
    )]
    MeshErrors {
        /// The first error finding's message.
        finding: String,
        /// Its first element ids, blank-separated.
        ids: String,
    },
    /// A node set the reduction uses names nodes the file never defines: the reader drops
    /// them, and a mistyped piston id would silently leave a piston out.
    #[error(
        "node set {set} names {count} node id(s) the file never defines ({ids}): without them it is another set; correct the ids in the mesh"
    )]
    ShortenedSet {
        /// The set's name.
        set: String,
        /// How many members are missing.
        count: usize,
        /// The missing ids, blank-separated.
        ids: String,
    },
    /// The disc and the pad have different numbers of contact points, so they cannot be
    /// paired one to one.
    #[error(
        "the disc has {disc} contact points and the pad {pad}: they must pair one to one (same interface sets and grid on both parts)"
    )]
    ContactCountMismatch {
        /// Contact points of the disc.
        disc: usize,
        /// Contact points of the pad.
        pad: usize,
    },
    /// A disc contact point has no pad contact point within the pairing tolerance: the
    /// contact sets of the two parts do not face each other.
    #[error(
        "disc contact point {point} at ({:.6}, {:.6}, {:.6}) m finds no pad contact point within {tolerance:.3e} m (nearest {nearest:.3e} m away): the parts' contact sets do not face each other",
        position[0], position[1], position[2]
    )]
    NoPartner {
        /// The disc's contact point, 1-based.
        point: usize,
        /// Its position (m).
        position: [f64; 3],
        /// Distance to the nearest pad contact point (m).
        nearest: f64,
        /// The pairing tolerance (m).
        tolerance: f64,
    },
    /// Assembling `K` and `M` failed (a material undefined or invalid, a restraint on a
    /// missing node set, an element whose matrix cannot be computed, ...).
    #[error(transparent)]
    Fe(#[from] FeError),
    /// The contact points could not be built from the mesh's sets.
    #[error(transparent)]
    Interface(#[from] InterfaceError),
    /// A part's restraints and boundary coordinates leave rigid-body motions free (found
    /// before any reduction work, [`crate::held`]): its interior stiffness `K_II` would be
    /// singular.
    #[error(
        "{part}: the part is not held: its restraints ({held}) leave {count} rigid-body motion(s) free: {motions}. To hold it, {add}"
    )]
    NotHeld {
        /// The part.
        part: String,
        /// How many motions are free.
        count: usize,
        /// The free motions, as shown ([`crate::held::FreeMotion`]).
        motions: String,
        /// Its restraints and pistons, as given.
        held: String,
        /// What to add.
        add: String,
    },
    /// The interior stiffness `K_II` is singular although the restraints hold every rigid
    /// motion of the part as a whole: a piece of it moves on its own.
    #[error(
        "{part}: the interior stiffness K_II is singular although its restraints ({held}) hold the part as a whole: a piece of the mesh is not connected to the rest by elements, or hangs on a node or an edge (`squeal mesh info` lists the mesh's findings); join it to the rest or hold it too"
    )]
    NotConnected {
        /// The part.
        part: String,
        /// Its restraints and pistons, as given.
        held: String,
    },
    /// The factorization or the eigensolver of a part failed.
    #[error("{part}: eigensolver: {source}")]
    Eigen {
        /// The part.
        part: String,
        /// The eigensolver's error.
        source: EigError,
    },
    /// A contact or piston node is also restrained in a direction whose dof it keeps as a
    /// boundary coordinate.
    #[error(
        "{part}: boundary node {node} at ({:.4}, {:.4}, {:.4}) m ({set}) is restrained in direction {direction}: a boundary dof cannot also be clamped; narrow the restraint (its node set, or the scene's rule for it) so that it leaves the {set} nodes",
        position[0], position[1], position[2]
    )]
    BoundaryRestrained {
        /// The part.
        part: String,
        /// The boundary node set (contact or piston).
        set: String,
        /// The node's id in the mesh.
        node: u64,
        /// The node's coordinates (m): a rule's set has no ids the user wrote.
        position: [f64; 3],
        /// The direction both kept and restrained: `x`, `y` or `z`.
        direction: char,
    },
    /// Two boundary coordinates of a part fall on the same dof: a contact patch has no face
    /// dof of its own in that direction.
    #[error(
        "{part}: contact point {point} has no dof of its own in direction {direction}: the patch shares all its face nodes with its neighbours (refine the mesh or use a coarser grid)"
    )]
    NoMaster {
        /// The part.
        part: String,
        /// The contact point.
        point: usize,
        /// The direction: `x`, `y` or `z`.
        direction: char,
    },
    /// Keeping the modes below a frequency would keep more than the limit on a part's
    /// fixed-interface modes.
    #[error(
        "{part}: {count} fixed-interface modes lie below {below_hz} Hz, more than the limit of {limit}: lower the frequency or raise the limit"
    )]
    TooManyModes {
        /// The part.
        part: String,
        /// The cut-off frequency (Hz).
        below_hz: f64,
        /// Fixed-interface modes below it.
        count: usize,
        /// The most a part may keep.
        limit: usize,
    },
    /// Something else is wrong with a part's reduction (an option out of range, more modes
    /// asked for than the interior has dofs, a basis too large for the memory, a reduced
    /// matrix that is not positive definite, ...): the message says what.
    #[error("{part}: {what}")]
    Invalid {
        /// The part (`brake` for the brake as a whole).
        part: String,
        /// What is wrong.
        what: String,
    },
}

impl ReduceError {
    /// The error itself, without the mesh file [`ReduceError::InMesh`] names.
    pub fn inner(&self) -> &ReduceError {
        match self {
            ReduceError::InMesh { error, .. } => error.inner(),
            other => other,
        }
    }
}
