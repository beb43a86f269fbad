//! Craig–Bampton reduction of one part, eqs (1)–(7).
//!
//! The boundary coordinates `r` are given as rows of a constraint `r = C u` on the part's free
//! dofs: one dof per row for the node interface, the nodal interface's face nodes and the
//! piston nodes, the patch weights of [`crate::interface`] (a weighted mean of a few hundred
//! face dofs) for the patch interface.
//!
//! - A row with one entry `r_b = c u_m` is the paper's partition: the dof `m` is a boundary dof,
//!   `u_m = r_b / c`, and leaves the interior.
//! - The other rows stay constraints `C_P u = r_P` on the interior dofs `v` (all free dofs but the
//!   eliminated ones), so that the interior matrices `K_vv`, `M_vv` keep the sparsity of `K`
//!   whatever the patches couple. Eliminating one master dof per patch row instead (the null-space
//!   form `u = T v + G r`) would put the dense block `Aᵀ K_SS A` of all the patch's face dofs
//!   into `K_vv` and multiply the fill of its factor.
//!
//! With `K_vv = L Lᵀ` factored once (nested dissection, supernodal Cholesky), `X = K_vv⁻¹ C_Pᵀ`
//! and `S = C_P X` (see [`squeal_eigs::ConstrainedFactor`]):
//!
//! - constraint modes, eq (3), the least-energy motion for each unit boundary coordinate: for a
//!   constraint row `p`, `v = X S⁻¹ e_p`; for an eliminated dof `m` (`u_m = 1/c`),
//!   `v = P y - X S⁻¹ C_E e_m / c` with `y = -K_vv⁻¹ K_vm / c` and `P = I - X S⁻¹ C_P` (the
//!   constraint rows' share of `u_m`, `C_E`, moved to the right-hand side);
//! - fixed-interface modes, eqs (4)–(5): the `N` lowest of `K_vv φ = ω² M_vv φ + C_Pᵀ μ`,
//!   `C_P φ = 0` (`r = 0`), mass-normalized, by shift-invert Lanczos with the operator
//!   `P K_vv⁻¹ M_vv` on the same factor, Sturm-checked on the constrained pencil;
//! - eqs (6)–(7): `K̂ = Bᵀ K B`, `M̂ = Bᵀ M B` with the full-space basis `B = [Ψ, Φ]`; `K̂` is
//!   block diagonal (`K̂_CN = Ψᵀ K Φ = 0` to round-off, since `K Ψ` lies in the range of `Cᵀ`
//!   and `C Φ = 0`). For the node interface there are no constraint rows and this is the
//!   paper's partition into `u_B` and `u_I`.
//!
//! A piston's footprint keeps one coordinate, its area-weighted mean motion along the piston
//! direction `r_f = c_f u = Σ_k w_k n · u_k` ([`crate::interface::footprint`]), a constraint row
//! like a contact patch's. With only constraint rows along the normal (footprints and patches)
//! the pad's `K_vv` is singular: nothing but those rows holds it along the normal. The
//! footprints' rows are then added to the factored stiffness as springs,
//! `K' = K + Σ_f ρ_f c_fᵀ c_f` (an augmented Lagrangian), which changes neither kind of mode:
//! on every set `C u = r` the added energy `½ Σ_f ρ_f r_f²` is a constant, so the least-energy
//! constraint modes are those of `K`; on `C u = 0`, `K' u = K u`, so the fixed-interface modes
//! (and the Sturm counts of the constrained pencil) are those of `K`. `K'` is positive
//! definite when the footprints see every motion the restraints leave free (a rigid
//! translation along the normal moves each `r_f` by its length). The projection (eqs 6–7)
//! takes `K` itself. `ρ_f` only scales round-off: the mean diagonal of `K` over the
//! footprint's dofs over `Σ_k c_fk²`, so that the springs add at most that mean to a diagonal
//! entry while a unit translation along the normal meets `ρ_f` (about the footprint's
//! diagonal entries summed). A footprint of one node is that node's dof, eliminated as a
//! piston node's is, and nothing is added. (Eliminating a master dof per footprint instead,
//! `u_k = (r_f − Σ_{i≠k} c_i u_i) / c_k`, spans the same space but changes `M_vv` as well and
//! couples every footprint dof to every neighbour of the master in `K_vv`.)

use crate::interface::nodal::face_nodes;
use crate::interface::{Axis, InterfaceError, contact_nodes, footprint, patches, tributary_areas};
use crate::rom::{
    Basis, ContactSurface, DofLabel, InterfaceKind, InterfacePoint, MaterialInfo, MeshInfo,
    PartInfo, PartRole, PointRole, ReducedPart, RestraintInfo,
};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Accum, Mat, MatRef, Par};
use rayon::prelude::*;
use squeal_eigs::{
    ConstrainedFactor, Constraints, EigError, EigOptions, SparseCholesky, lowest_modes_constrained,
    lowest_modes_with_factor,
};
use squeal_fe::frames::{
    AxisDirection, DofTransform, HeldNodes, NodeFrame, RotationAxis, SkewRestraint,
    orthonormal_completion,
};
use squeal_fe::{DofMap, FeError, MaterialTable, Restraint, assemble};
use squeal_mesh::Mesh;
use std::borrow::Cow;
use std::time::{Duration, Instant};

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
        "{part}: boundary node {node} ({set}) is restrained in direction {direction}: a boundary dof cannot also be clamped"
    )]
    BoundaryRestrained {
        /// The part.
        part: String,
        /// The boundary node set (contact or piston).
        set: String,
        /// The node's id in the mesh.
        node: u64,
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

const AXES: [char; 3] = ['x', 'y', 'z'];

/// What to keep of one part and how it is held.
#[derive(Clone, Debug, PartialEq)]
pub struct PartSpec {
    /// The part's name (`disc`, or the pad's name), used in messages and in the `.rom`.
    pub name: String,
    /// Disc or pad.
    pub role: PartRole,
    /// The mesh file it comes from, as recorded in the `.rom`.
    pub mesh: MeshInfo,
    /// How the part is held: node sets and their clamped directions.
    pub restraints: Vec<Restraint>,
    /// Restraints along global directions that are not coordinate axes: node set and
    /// directions (held exactly in each node's own axes, [`squeal_fe::frames`]).
    pub skew_restraints: Vec<(String, Vec<[f64; 3]>)>,
    /// Restraints relative to the disc's axis `axis`: node set and directions (axial, radial,
    /// tangential at each node, held exactly in the node's own axes).
    pub axis_restraints: Vec<(String, Vec<AxisDirection>)>,
    /// Node or patch interface.
    pub interface: InterfaceKind,
    /// Node set of the contact points (node interface).
    pub contact_set: String,
    /// Node set of the contact face (patch interface).
    pub contact_face_set: String,
    /// The pad `contact_set` / `contact_face_set` face, on a disc braked by several pads.
    pub facing: Option<String>,
    /// Further contact surfaces (a disc braked by several pads: one per further pad).
    pub extra_surfaces: Vec<ContactSurface>,
    /// Patch grid `[radial, angular]`.
    pub grid: [usize; 2],
    /// The disc's axis, about which the patches are cut in radius and angle.
    pub axis: Axis,
    /// Node set whose nodes keep their `normal_direction` dof (the pad's pistons).
    pub piston_set: Option<String>,
    /// The pistons as footprints instead: one node set per piston (the faces it presses on,
    /// given by their nodes), each keeping one coordinate, its area-weighted mean motion along
    /// the piston direction (module docs). A set of one node keeps that node's dof, as a
    /// `piston_set` node does. When not empty, the nodes of `piston_set` are not taken one by
    /// one.
    pub piston_footprints: Vec<String>,
    /// Direction (0 = x, 1 = y, 2 = z) of the piston dofs: the contact normal.
    pub normal_direction: usize,
    /// The piston dofs' unit direction when it is not a coordinate axis (a constraint row
    /// `n · u` on the node's three dofs, labelled [`DofLabel::Along`]); replaces
    /// `normal_direction`.
    pub piston_direction: Option<[f64; 3]>,
    /// Fixed-interface modes kept.
    pub modes: usize,
}

impl PartSpec {
    /// The part's contact surfaces: its own sets first, then the further ones.
    pub fn surfaces(&self) -> Vec<ContactSurface> {
        ContactSurface::list(
            &self.facing,
            &self.contact_set,
            &self.contact_face_set,
            &self.extra_surfaces,
        )
    }
}

/// Options of [`reduce_part`].
#[derive(Clone, Debug, PartialEq)]
pub struct ReduceOptions {
    /// Options of the eigensolver of the fixed-interface modes (backend, shift, tolerance, Sturm check, threads).
    pub eig: EigOptions,
    /// M-orthonormalize the kept modes again after the solve, so that the modal block of `M̂`
    /// is the identity and that of `K̂` is `diag(ω²)` to round-off.
    pub orthonormalize: bool,
    /// Keep the full-space basis in the result (needed to expand results onto the mesh).
    pub keep_basis: bool,
    /// Keep the fixed-interface modes below this frequency (Hz) instead of a fixed number:
    /// their count comes from a Sturm count of `K_vv - (2π f)² M_vv`, and
    /// [`PartSpec::modes`] is then the most that may be kept.
    pub modes_below_hz: Option<f64>,
}

impl Default for ReduceOptions {
    fn default() -> Self {
        Self {
            eig: EigOptions::default(),
            orthonormalize: true,
            keep_basis: true,
            modes_below_hz: None,
        }
    }
}

/// Stages, reported to a progress callback as they start. [`reduce_part`] goes from
/// `Assemble` to `Project`; `Read` and `Write` are the brake-level stages around it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Reading and hashing the mesh file.
    Read,
    /// Assembling the sparse `K` and `M` of the part.
    Assemble,
    /// Building the boundary coordinates (contact and piston points) and the interior.
    Interface,
    /// Ordering and factoring the interior stiffness `K_II`.
    Factor,
    /// The constraint modes, eq (3).
    ConstraintModes,
    /// The fixed-interface modes, eqs (4)–(5).
    Eigensolve,
    /// The projection `K̂ = Bᵀ K B`, `M̂ = Bᵀ M B`, eqs (6)–(7).
    Project,
    /// Writing the `.rom` file.
    Write,
}

impl Stage {
    /// All stages in the order they run.
    pub const ALL: [Stage; 8] = [
        Stage::Read,
        Stage::Assemble,
        Stage::Interface,
        Stage::Factor,
        Stage::ConstraintModes,
        Stage::Eigensolve,
        Stage::Project,
        Stage::Write,
    ];

    /// The stage's name as shown to the user (`assemble K, M`, ...).
    pub fn label(&self) -> &'static str {
        match self {
            Stage::Read => "read mesh",
            Stage::Write => "write",
            Stage::Assemble => "assemble K, M",
            Stage::Interface => "interface",
            Stage::Factor => "order and factor K_II",
            Stage::ConstraintModes => "constraint modes",
            Stage::Eigensolve => "fixed-interface modes",
            Stage::Project => "project K, M",
        }
    }
}

/// What the reduction of one part did and cost.
#[derive(Clone, Debug)]
pub struct ReduceReport {
    /// Free dofs of the part (all dofs but the restrained ones).
    pub free_dofs: usize,
    /// Interior dofs `v`: the free dofs but those eliminated as boundary dofs (a patch's
    /// face dofs stay interior, under its constraint row).
    pub interior_dofs: usize,
    /// Boundary coordinates, one constraint mode each.
    pub boundary_dofs: usize,
    /// Fixed-interface modes kept.
    pub modes: usize,
    /// Stored entries of `K` (both triangles).
    pub nnz_k: usize,
    /// Nonzeros of the Cholesky factor of `K_vv`.
    pub nnz_factor: usize,
    /// Bytes held by that factor.
    pub factor_bytes: usize,
    /// The whole of the factor's statistics (fill, flops, times, the split of its solves).
    pub factor: squeal_eigs::FactorStats,
    /// Wall time of each stage, in the order they ran.
    pub timings: Vec<(Stage, Duration)>,
    /// What the eigensolver did (restarts, operator applications, basis size).
    pub eig: squeal_eigs::EigStats,
    /// Sturm check of the kept modes: the bound `ω²` and the number of eigenvalues of the
    /// fixed-interface problem below it (equal to the modes found below it).
    pub sturm: Option<(f64, usize)>,
    /// Largest eigen backward error of the kept modes.
    pub max_residual: f64,
    /// `max |M̂_NN - I|` before re-orthonormalization.
    pub modal_mass_deviation: f64,
    /// `||K̂_CN|| / ||K̂||` (zero in exact arithmetic, eq 6).
    pub coupling: f64,
}

/// One boundary coordinate: `r = Σ c_k u_k` over free dofs.
pub(crate) struct Row {
    point: usize,
    label: DofLabel,
    pub(crate) entries: Vec<(usize, f64)>,
    /// A piston footprint's mean motion (held by a spring in the factored stiffness when it
    /// is a constraint row, see the module docs).
    pub(crate) footprint: bool,
}

/// The free dofs of a part: those of its [`DofMap`], or the kept coordinates of a
/// [`DofTransform`] when some nodes are held along skew directions (such a node's x, y, z have
/// no dof of their own: it cannot be a boundary node).
pub(crate) struct FreeDofs<'a> {
    pub(crate) dofmap: &'a DofMap,
    pub(crate) transform: Option<DofTransform>,
}

impl FreeDofs<'_> {
    fn free_dof(&self, node: u32, d: usize) -> Option<usize> {
        let f = self.dofmap.free_dof(node, d)?;
        match &self.transform {
            None => Some(f),
            Some(t) => t.new_dof(f),
        }
    }

    /// The row `w · u` of node `node` (`w` unit) on the free dofs: the node's dofs along the
    /// non-zero components of `w`, or, for a node in its own axes, its kept coordinates with
    /// `w · e_j` (coefficients below 1e-12 are round-off of the axes and dropped, so that a
    /// node whose first axis is `w` gives a single entry). `None` when `w` has a part the
    /// node's free motions do not reach (a restrained direction).
    fn along(&self, node: u32, w: [f64; 3]) -> Option<Vec<(usize, f64)>> {
        if let Some(t) = &self.transform
            && let Some(kept) = t.kept(node)
        {
            let mut rest = w;
            let mut out = Vec::new();
            for &(dof, e) in kept {
                let c: f64 = (0..3).map(|d| w[d] * e[d]).sum();
                if c.abs() > 1e-12 {
                    out.push((dof, c));
                    for d in 0..3 {
                        rest[d] -= c * e[d];
                    }
                }
            }
            return ((0..3).map(|d| rest[d] * rest[d]).sum::<f64>().sqrt() <= 1e-9).then_some(out);
        }
        (0..3)
            .filter(|&d| w[d] != 0.0)
            .map(|d| Some((self.free_dof(node, d)?, w[d])))
            .collect()
    }

    pub(crate) fn num_free(&self) -> usize {
        self.transform
            .as_ref()
            .map_or(self.dofmap.num_free(), |t| t.num_free())
    }
}

/// A piston node pushing along a skew direction `n` keeps its three motions in axes of its own
/// whose first is `n` ([`NodeFrame`] with none held), so that its piston coordinate `n · u`
/// is a dof of its own, eliminated like the paper's boundary dofs (a constraint row instead
/// would leave the pad's motion along `n` free in the interior `K_vv`). A piston node that is
/// held along skew directions already keeps its own axes, and the row is taken on those.
pub(crate) fn piston_frames(
    mesh: &Mesh,
    spec: &PartSpec,
    held: &mut HeldNodes,
) -> Result<(), ReduceError> {
    let Some(n) = spec.piston_direction else {
        return Ok(());
    };
    for set in spec.piston_set.iter().chain(&spec.piston_footprints) {
        let nodes = mesh
            .node_set(set)
            .ok_or_else(|| InterfaceError::MissingSet(set.clone()))?;
        for &node in nodes {
            held.frames.entry(node).or_insert(NodeFrame {
                axes: orthonormal_completion(n),
                held: 0,
            });
        }
    }
    Ok(())
}

/// The skew restraints of `spec` on the nodes of `mesh`.
pub(crate) fn skew_restraints(
    mesh: &Mesh,
    spec: &PartSpec,
) -> Result<Vec<SkewRestraint>, ReduceError> {
    let mut out = Vec::new();
    for (set, directions) in &spec.skew_restraints {
        let nodes = mesh
            .node_set(set)
            .ok_or_else(|| InterfaceError::MissingSet(set.clone()))?;
        for &node in nodes {
            for &direction in directions {
                out.push(SkewRestraint { node, direction });
            }
        }
    }
    if !spec.axis_restraints.is_empty() {
        let axis = RotationAxis::new(spec.axis.origin, spec.axis.direction)?;
        for (set, which) in &spec.axis_restraints {
            let nodes = mesh
                .node_set(set)
                .ok_or_else(|| InterfaceError::MissingSet(set.clone()))?;
            out.extend(axis.restraints(mesh, nodes, which)?);
        }
    }
    Ok(out)
}

/// Reduces one part (eqs 1–7): assembles `K` and `M`, builds the boundary rows of the
/// interface, factors the interior stiffness once, solves the constraint modes (eq 3) and the
/// fixed-interface modes (eqs 4–5) with that factor, and projects (eqs 6–7).
///
/// `progress` is told each stage as it starts.
pub fn reduce_part(
    mesh: &Mesh,
    materials: &MaterialTable,
    spec: &PartSpec,
    opts: &ReduceOptions,
    progress: &mut dyn FnMut(Stage),
) -> Result<(ReducedPart, ReduceReport), ReduceError> {
    let part = spec.name.clone();
    let eigen = |source: EigError| ReduceError::Eigen {
        part: part.clone(),
        source,
    };
    let mut timings = Vec::new();
    let clock = |stage: Stage, t: Instant, timings: &mut Vec<(Stage, Duration)>| {
        timings.push((stage, t.elapsed()))
    };

    progress(Stage::Assemble);
    let t = Instant::now();
    let mut held = HeldNodes::new(mesh, &spec.restraints, &skew_restraints(mesh, spec)?)?;
    piston_frames(mesh, spec, &mut held)?;
    let dofmap = DofMap::new(mesh, &held.restraints)?;
    let system = assemble(mesh, materials, &dofmap)?;
    // Nodes held along skew directions: K' = Tᵀ K T, M' = Tᵀ M T on the kept coordinates.
    let free = FreeDofs {
        dofmap: &dofmap,
        transform: held.has_frames().then(|| DofTransform::new(&dofmap, &held)),
    };
    let system = match &free.transform {
        Some(t) => t.system(&dofmap, &system),
        None => system,
    };
    clock(Stage::Assemble, t, &mut timings);

    progress(Stage::Interface);
    let t = Instant::now();
    let (points, rows) = boundary_rows(mesh, &free, spec)?;
    let split = Split::new(&rows, free.num_free(), &part)?;
    // The stiffness factored: K, or K' = K + Σ ρ_f c_fᵀ c_f with footprints (module docs).
    let held_k = footprint_springs(&system.k, &rows, &split);
    let k_factored = held_k.as_ref().unwrap_or(&system.k);
    let (k_interior, m_interior) = (split.interior_of(k_factored), split.interior_of(&system.m));
    let (k_vv, m_vv): (&SparseColMat<usize, f64>, &SparseColMat<usize, f64>) =
        (&k_interior, &m_interior);
    let constraints = split.constraints().map_err(eigen)?;
    clock(Stage::Interface, t, &mut timings);

    progress(Stage::Factor);
    let t = Instant::now();
    let chol = squeal_eigs::CholeskyOptions {
        par: opts.eig.par,
        ..Default::default()
    };
    let factor = SparseCholesky::factorize_with(k_vv.as_ref(), &chol).map_err(|e| match e {
        EigError::NotPositiveDefinite { .. } => {
            let free_motions = crate::held::free_motions_of(mesh, &free, &held, &rows);
            match free_motions.is_empty() {
                false => crate::held::not_held(spec, &free_motions),
                true => ReduceError::NotConnected {
                    part: part.clone(),
                    held: crate::held::describe(spec),
                },
            }
        }
        other => eigen(other),
    })?;
    clock(Stage::Factor, t, &mut timings);

    progress(Stage::ConstraintModes);
    let t = Instant::now();
    let constrained = match constraints.is_empty() {
        true => None,
        false => Some(ConstrainedFactor::new(&factor, &constraints).map_err(eigen)?),
    };
    let psi_v = split
        .constraint_modes(k_factored, &factor, constrained.as_ref())
        .map_err(eigen)?;
    clock(Stage::ConstraintModes, t, &mut timings);

    progress(Stage::Eigensolve);
    let t = Instant::now();
    let factor_stats = factor.stats();
    let sturm = sturm_placement(opts, &factor_stats, spec.modes);
    let modes =
        fixed_interface_modes(k_vv, m_vv, &factor, constrained.as_ref(), spec, opts, sturm)?;
    drop(constrained);
    let modes = match modes.deferred {
        false => modes,
        true => check_deferred(modes, factor, k_vv, m_vv, &constraints, spec, opts)?,
    };
    clock(Stage::Eigensolve, t, &mut timings);

    progress(Stage::Project);
    let t = Instant::now();
    let nb = rows.len();
    let nm = modes.values.len();
    let n = nb + nm;
    let mut basis = try_zeros(free.num_free(), n, &part)?;
    for b in 0..nb {
        split.expand_into(psi_v.col(b), basis.col_mut(b));
        if let Some((m, inv)) = split.eliminated_dof(b) {
            basis[(m, b)] = inv;
        }
    }
    drop(psi_v);
    for j in 0..nm {
        split.expand_into(modes.vectors.col(j), basis.col_mut(nb + j));
    }
    let (mut k_hat, mut m_hat) = project_pair(&system.k, &system.m, &basis);
    let modal_mass_deviation = max_deviation_from_identity(&m_hat, nb);
    if opts.orthonormalize && nm > 0 {
        orthonormalize_modes(&mut basis, &mut k_hat, &mut m_hat, nb, &part)?;
    }
    let coupling = block_norm(&k_hat, 0..nb, nb..n) / frobenius(&k_hat).max(f64::MIN_POSITIVE);
    clock(Stage::Project, t, &mut timings);

    // The basis back on the mesh's x, y, z dofs (a skew-held node's kept coordinates as
    // motions along its axes): the rows `dof_node`, `dof_dir` describe.
    let basis = match &free.transform {
        Some(t) => t.expand_rows(basis.as_ref(), dofmap.num_free()),
        None => basis,
    };
    let dofs: Vec<DofLabel> = rows
        .iter()
        .map(|r| r.label)
        .chain((0..nm).map(|mode| DofLabel::Mode { mode }))
        .collect();
    let fixed_interface_hz: Vec<f64> = modes.values.iter().map(|&w2| hz(w2)).collect();
    let info = PartInfo {
        name: part.clone(),
        role_field: Some(spec.role),
        mesh: spec.mesh.clone(),
        interface: spec.interface,
        materials: material_infos(materials),
        restraints: restraint_infos(mesh, &spec.restraints),
        points,
        dofs,
        fixed_interface_hz,
        full_dofs: dofmap.num_free(),
        has_basis: opts.keep_basis,
        build: None,
    };
    let basis = opts.keep_basis.then(|| {
        let (dof_node, dof_dir): (Vec<u64>, Vec<u8>) = (0..dofmap.num_free())
            .map(|f| {
                let (node, dir) = dofmap.node_dir(f).unwrap_or((0, 0));
                (mesh.node_ids[node as usize], dir as u8)
            })
            .unzip();
        Basis {
            dof_node,
            dof_dir,
            values: basis,
        }
    });
    let report = ReduceReport {
        free_dofs: dofmap.num_free(),
        interior_dofs: split.interior.len(),
        boundary_dofs: nb,
        modes: nm,
        nnz_k: system.nnz_k(),
        nnz_factor: factor_stats.nnz_l,
        factor_bytes: factor_stats.factor_bytes,
        factor: factor_stats,
        timings,
        eig: modes.stats,
        sturm: modes.sturm,
        max_residual: modes.residuals.iter().copied().fold(0.0, f64::max),
        modal_mass_deviation,
        coupling,
    };
    Ok((
        ReducedPart {
            info,
            k: k_hat,
            m: m_hat,
            basis,
        },
        report,
    ))
}

/// Natural frequency (Hz) of an eigenvalue `ω²` (negative round-off clipped to 0).
pub fn hz(omega2: f64) -> f64 {
    omega2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}

/// The eigenvalue `ω² = (2π f)²` of a frequency in Hz.
pub fn omega2(hz: f64) -> f64 {
    (2.0 * std::f64::consts::PI * hz).powi(2)
}

/// Fixed-interface modes as found: eigenvalues, vectors, residuals, and the Sturm check made.
struct FixedModes {
    values: Vec<f64>,
    vectors: Mat<f64>,
    residuals: Vec<f64>,
    /// The guard eigenvalues above `values` (for a Sturm check made later).
    guard_values: Vec<f64>,
    stats: squeal_eigs::EigStats,
    /// Sturm bound `ω²` and the count of eigenvalues below it.
    sturm: Option<(f64, usize)>,
    /// The Sturm check is still to be made ([`SturmPlacement::Deferred`]).
    deferred: bool,
}

/// Where the Sturm check of the fixed-interface modes runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum SturmPlacement {
    /// Beside the Lanczos iteration (a second factor in memory at the same time).
    Beside,
    /// After the iteration, with the Cholesky factor still held (the eigensolver's own check,
    /// which finds missed eigenvalues by locked restarts).
    After,
    /// After the iteration, with the Cholesky factor's values freed first
    /// ([`check_deferred`]): the peak memory holds one factor.
    Deferred,
}

/// The Sturm check beside the iteration when the options allow it (`EigOptions::sturm_beside`)
/// and a second factor fits in the memory available now (Linux: `MemAvailable` of
/// `/proc/meminfo`; elsewhere it is taken to fit), else after it with the Cholesky factor
/// freed. The results do not depend on the choice (only the reported Sturm bound may).
fn sturm_placement(
    opts: &ReduceOptions,
    factor: &squeal_eigs::FactorStats,
    modes: usize,
) -> SturmPlacement {
    if !opts.eig.sturm_beside {
        return SturmPlacement::Deferred;
    }
    // The LBL^T's values and its copy of K - b M, and the Lanczos basis (about 3 x modes).
    let need = factor.factor_bytes + 16 * factor.nnz_a + 8 * factor.n * 3 * modes;
    let available = std::fs::read_to_string("/proc/meminfo").ok().and_then(|s| {
        s.lines()
            .find_map(|l| l.strip_prefix("MemAvailable:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<usize>().ok())
            .map(|kb| kb * 1024)
    });
    match available {
        // A quarter kept free for the other part and the allocator.
        Some(bytes) if need > bytes / 4 * 3 => SturmPlacement::Deferred,
        _ => SturmPlacement::Beside,
    }
}

/// The deferred Sturm check: frees the factor's values, counts the eigenvalues below a bound
/// placed among the modes and their guards with an LBLᵀ on the factor's analysis, and if some
/// were missed (rare), factors again and solves with the eigensolver's own check.
fn check_deferred(
    mut modes: FixedModes,
    factor: SparseCholesky,
    k_vv: &SparseColMat<usize, f64>,
    m_vv: &SparseColMat<usize, f64>,
    constraints: &Constraints,
    spec: &PartSpec,
    opts: &ReduceOptions,
) -> Result<FixedModes, ReduceError> {
    let eigen = |source: EigError| ReduceError::Eigen {
        part: spec.name.clone(),
        source,
    };
    let analysis = factor.into_analysis();
    let t = Instant::now();
    let c = (!constraints.is_empty()).then_some(constraints);
    let all: Vec<f64> = modes
        .values
        .iter()
        .chain(&modes.guard_values)
        .copied()
        .collect();
    let (k, m) = (k_vv.as_ref(), m_vv.as_ref());
    match squeal_eigs::sturm_check_with(k, m, &all, modes.values.len(), Some(&analysis), c) {
        Ok(found) => {
            modes.sturm = Some(found);
            modes.stats.sturm = Some(found);
            modes.stats.sturm_time = t.elapsed();
            modes.deferred = false;
            Ok(modes)
        }
        Err(EigError::MissedEigenvalues { .. }) => {
            let chol = squeal_eigs::CholeskyOptions {
                par: opts.eig.par,
                ..Default::default()
            };
            let factor = analysis.factorize(k, &chol).map_err(eigen)?;
            let constrained = match c {
                None => None,
                Some(c) => Some(ConstrainedFactor::new(&factor, c).map_err(eigen)?),
            };
            let after = SturmPlacement::After;
            fixed_interface_modes(k_vv, m_vv, &factor, constrained.as_ref(), spec, opts, after)
        }
        Err(e) => Err(eigen(e)),
    }
}

/// Eqs (4)–(5): the fixed-interface modes of `K_vv φ = ω² M_vv φ` with the factor of `K_vv`,
/// mass-normalized. A fixed number (`spec.modes`), or with `opts.modes_below_hz` all those
/// below that frequency (counted by a Sturm count; at most `spec.modes`, else an error).
fn fixed_interface_modes(
    k_vv: &SparseColMat<usize, f64>,
    m_vv: &SparseColMat<usize, f64>,
    factor: &SparseCholesky,
    constrained: Option<&ConstrainedFactor<'_>>,
    spec: &PartSpec,
    opts: &ReduceOptions,
    sturm: SturmPlacement,
) -> Result<FixedModes, ReduceError> {
    let part = &spec.name;
    let eigen = |source: EigError| ReduceError::Eigen {
        part: part.clone(),
        source,
    };
    let n = k_vv.nrows();
    let mut eig_opts = EigOptions {
        shift: 0.0,
        sturm_beside: sturm == SturmPlacement::Beside,
        ..opts.eig
    };
    let deferred = sturm == SturmPlacement::Deferred && opts.eig.sturm_check;
    if deferred {
        eig_opts.sturm_check = false;
    }
    let mut below = None;
    let nm = match opts.modes_below_hz {
        None => spec.modes,
        Some(f) => {
            if !(f.is_finite() && f > 0.0) {
                return Err(ReduceError::Invalid {
                    part: part.clone(),
                    what: format!("the mode cut-off frequency {f} Hz is not a positive number"),
                });
            }
            let bound = omega2(f);
            let (k, m) = (k_vv.as_ref(), m_vv.as_ref());
            let count = match constrained {
                None => squeal_eigs::count_below(k, m, bound),
                Some(c) => squeal_eigs::count_below_constrained(k, m, c.constraints(), bound),
            }
            .map_err(eigen)?;
            if count > spec.modes {
                return Err(ReduceError::TooManyModes {
                    part: part.clone(),
                    below_hz: f,
                    count,
                    limit: spec.modes,
                });
            }
            // The count is itself the Sturm check: the solver's own one is not needed
            // unless the solve misses a mode below the bound.
            eig_opts.sturm_check = false;
            below = Some((bound, count));
            count
        }
    };
    if nm == 0 {
        return Ok(FixedModes {
            values: Vec::new(),
            vectors: Mat::zeros(n, 0),
            residuals: Vec::new(),
            guard_values: Vec::new(),
            stats: Default::default(),
            sturm: below,
            deferred: false,
        });
    }
    let dim = n - constrained.map_or(0, |c| c.constraints().len());
    if nm >= dim {
        return Err(ReduceError::Invalid {
            part: part.clone(),
            what: format!("{nm} fixed-interface modes asked for, the interior has {dim} free dofs"),
        });
    }
    let solve = |eig_opts: &EigOptions| {
        let (k, m) = (k_vv.as_ref(), m_vv.as_ref());
        match constrained {
            None => lowest_modes_with_factor(k, m, factor, nm, eig_opts),
            Some(c) => lowest_modes_constrained(k, m, c, nm, eig_opts),
        }
        .map_err(eigen)
    };
    let modes = solve(&eig_opts)?;
    let modes = match below {
        Some((bound, _)) if modes.values.iter().any(|&v| v >= bound) => {
            // A mode below the bound was missed: solve again with the solver's Sturm check,
            // which finds missed copies of multiple eigenvalues by locked restarts.
            eig_opts.sturm_check = true;
            solve(&eig_opts)?
        }
        _ => modes,
    };
    Ok(FixedModes {
        sturm: below.or(modes.stats.sturm),
        // The count below the cut-off is itself the Sturm check.
        deferred: deferred && below.is_none(),
        values: modes.values,
        vectors: modes.vectors,
        residuals: modes.residuals,
        guard_values: modes.guard_values,
        stats: modes.stats,
    })
}

/// A zeroed dense matrix, or an error naming the part when the memory is not there.
fn try_zeros(rows: usize, cols: usize, part: &str) -> Result<Mat<f64>, ReduceError> {
    let too_big = || ReduceError::Invalid {
        part: part.into(),
        what: format!("cannot allocate the {rows} x {cols} reduction basis"),
    };
    let count = rows.checked_mul(cols).ok_or_else(too_big)?;
    let mut probe: Vec<f64> = Vec::new();
    probe.try_reserve_exact(count).map_err(|_| too_big())?;
    drop(probe);
    Ok(Mat::zeros(rows, cols))
}

/// Boundary points and rows: contact points (3 rows each), then piston nodes (1 row each).
pub(crate) fn boundary_rows(
    mesh: &Mesh,
    dofmap: &FreeDofs,
    spec: &PartSpec,
) -> Result<(Vec<InterfacePoint>, Vec<Row>), ReduceError> {
    let part = &spec.name;
    let mut points = Vec::new();
    let mut rows = Vec::new();
    let restrained = |set: &str, node: u32, d: usize| ReduceError::BoundaryRestrained {
        part: part.clone(),
        set: set.into(),
        node: mesh.node_ids[node as usize],
        direction: AXES[d],
    };
    for surface in spec.surfaces() {
        match spec.interface {
            InterfaceKind::Node => {
                let nodes = contact_nodes(mesh, &surface.contact_set, &spec.axis)?;
                // Each node stands for its tributary share of the contact face, when the part has
                // one: the area its contact stiffness per unit area is multiplied by. A part has
                // none when the set is missing or names nodes with no boundary face among them (a
                // point contact whose face set is its contact set): its points carry no area, and
                // a scene's `[contact] point_area` gives them one.
                let cells = match tributary_areas(mesh, &surface.contact_face_set, &nodes) {
                    Ok(cells) => Some(cells),
                    Err(InterfaceError::MissingSet(_) | InterfaceError::NoFaces { .. }) => None,
                    Err(e) => return Err(e.into()),
                };
                for (k, node) in nodes.into_iter().enumerate() {
                    let p = points.len();
                    let cell = cells.as_ref().map(|c| c[k]);
                    points.push(InterfacePoint {
                        role: PointRole::Contact,
                        node_id: Some(mesh.node_ids[node as usize]),
                        patch: None,
                        position: mesh.nodes[node as usize],
                        area: cell.map(|c| c.0),
                        normal: cell.map(|c| c.1),
                        surface: surface.facing.clone(),
                        projected: None,
                    });
                    for d in 0..3 {
                        let dof = dofmap
                            .free_dof(node, d)
                            .ok_or_else(|| restrained(&surface.contact_set, node, d))?;
                        rows.push(Row {
                            point: p,
                            label: point_label(p, d),
                            entries: vec![(dof, 1.0)],
                            footprint: false,
                        });
                    }
                }
            }
            InterfaceKind::Nodal => {
                // Every node of the face, its three dofs kept: the pad's contact points, the
                // disc's face points that its projected contact points combine
                // ([`crate::interface::nodal`]; the brake adds those).
                let role = match spec.role {
                    PartRole::Disc => PointRole::Face,
                    PartRole::Pad => PointRole::Contact,
                };
                for node in face_nodes(mesh, &surface.contact_face_set)? {
                    let p = points.len();
                    points.push(InterfacePoint {
                        role,
                        node_id: Some(mesh.node_ids[node.node as usize]),
                        patch: None,
                        position: mesh.nodes[node.node as usize],
                        area: Some(node.area),
                        normal: Some(node.normal),
                        surface: surface.facing.clone(),
                        projected: None,
                    });
                    for d in 0..3 {
                        let dof = dofmap
                            .free_dof(node.node, d)
                            .ok_or_else(|| restrained(&surface.contact_face_set, node.node, d))?;
                        rows.push(Row {
                            point: p,
                            label: point_label(p, d),
                            entries: vec![(dof, 1.0)],
                            footprint: false,
                        });
                    }
                }
            }
            InterfaceKind::Patch => {
                let patches = patches(
                    mesh,
                    &surface.contact_face_set,
                    spec.grid[0],
                    spec.grid[1],
                    &spec.axis,
                )?;
                for patch in patches {
                    let p = points.len();
                    points.push(InterfacePoint {
                        role: PointRole::Contact,
                        node_id: None,
                        patch: Some(patch.number),
                        position: patch.centroid,
                        area: Some(patch.area),
                        normal: Some(patch.normal),
                        surface: surface.facing.clone(),
                        projected: None,
                    });
                    for d in 0..3 {
                        // A restrained face node would pin the patch's mean motion: refuse it,
                        // as for a restrained contact node.
                        let mut entries = Vec::with_capacity(patch.weights.len());
                        for &(node, w) in &patch.weights {
                            let dof = dofmap
                                .free_dof(node, d)
                                .ok_or_else(|| restrained(&surface.contact_face_set, node, d))?;
                            entries.push((dof, w));
                        }
                        rows.push(Row {
                            point: p,
                            label: point_label(p, d),
                            entries,
                            footprint: false,
                        });
                    }
                }
            }
        }
    }
    // A piston node's row: its dof along the piston direction (label, entries, normal).
    type PistonRow = (DofLabel, Vec<(usize, f64)>, Option<[f64; 3]>);
    let piston_row = |set: &str, node: u32, p: usize| -> Result<PistonRow, ReduceError> {
        match spec.piston_direction {
            None => {
                let d = spec.normal_direction;
                let dof = dofmap
                    .free_dof(node, d)
                    .ok_or_else(|| restrained(set, node, d))?;
                Ok((point_label(p, d), vec![(dof, 1.0)], None))
            }
            Some(n) => {
                // `r = n · u`: the node's own first axis (`piston_frames`).
                let entries = dofmap.along(node, n).ok_or_else(|| {
                    let d = (0..3)
                        .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
                        .unwrap_or(2);
                    restrained(set, node, d)
                })?;
                Ok((
                    DofLabel::Along {
                        point: p,
                        direction: n,
                    },
                    entries,
                    Some(n),
                ))
            }
        }
    };
    let node_piston = |set: &str,
                       node: u32,
                       points: &mut Vec<InterfacePoint>,
                       rows: &mut Vec<Row>|
     -> Result<(), ReduceError> {
        let p = points.len();
        let (label, entries, normal) = piston_row(set, node, p)?;
        points.push(InterfacePoint {
            role: PointRole::Piston,
            node_id: Some(mesh.node_ids[node as usize]),
            patch: None,
            position: mesh.nodes[node as usize],
            area: None,
            normal,
            surface: None,
            projected: None,
        });
        rows.push(Row {
            point: p,
            label,
            entries,
            footprint: false,
        });
        Ok(())
    };
    if !spec.piston_footprints.is_empty() {
        for set in &spec.piston_footprints {
            let nodes = mesh
                .node_set(set)
                .ok_or_else(|| InterfaceError::MissingSet(set.clone()))?;
            match nodes {
                [] => return Err(InterfaceError::EmptySet(set.clone()).into()),
                &[node] => node_piston(set, node, &mut points, &mut rows)?,
                _ => {
                    let print = footprint(mesh, set)?;
                    let p = points.len();
                    let mut label = point_label(p, spec.normal_direction);
                    let mut entries = Vec::new();
                    for &(node, w) in &print.weights {
                        let (l, e, _) = piston_row(set, node, p)?;
                        label = l;
                        entries.extend(e.into_iter().map(|(dof, c)| (dof, c * w)));
                    }
                    let direction = match spec.piston_direction {
                        Some(n) => n,
                        None => {
                            let mut e = [0.0; 3];
                            e[spec.normal_direction.min(2)] = 1.0;
                            e
                        }
                    };
                    points.push(InterfacePoint {
                        role: PointRole::Piston,
                        node_id: None,
                        patch: None,
                        position: print.centroid,
                        area: Some(print.area),
                        normal: Some(direction),
                        surface: None,
                        projected: None,
                    });
                    rows.push(Row {
                        point: p,
                        label,
                        entries,
                        footprint: true,
                    });
                }
            }
        }
    } else if let Some(set) = &spec.piston_set {
        let nodes = mesh
            .node_set(set)
            .ok_or_else(|| InterfaceError::MissingSet(set.clone()))?;
        if nodes.is_empty() {
            return Err(InterfaceError::EmptySet(set.clone()).into());
        }
        for &node in nodes {
            node_piston(set, node, &mut points, &mut rows)?;
        }
    }
    Ok((points, rows))
}

/// `K + Σ_f ρ_f c_fᵀ c_f` over the footprint rows `c_f` that are constraint rows (module docs),
/// or `None` when there are none. `ρ_f` is the mean of `K`'s diagonal over the row's dofs
/// over `Σ_k c_fk²`. Both triangles are stored, each column's rows ascending; an entry both in
/// `K` and added is `K`'s plus the footprints' in row order (the same bits for any thread
/// count).
fn footprint_springs(
    k: &SparseColMat<usize, f64>,
    rows: &[Row],
    split: &Split,
) -> Option<SparseColMat<usize, f64>> {
    let n = k.ncols();
    let kr = k.as_ref();
    let diagonal = |j: usize| {
        kr.row_idx_of_col(j)
            .zip(kr.val_of_col(j))
            .find(|&(i, _)| i == j)
            .map_or(0.0, |(_, &v)| v)
    };
    let mut added: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    let mut any = false;
    for (r, kind) in rows.iter().zip(&split.kinds) {
        if !r.footprint || !matches!(kind, RowKind::Constraint(_)) {
            continue;
        }
        let norm2: f64 = r.entries.iter().map(|&(_, c)| c * c).sum();
        if norm2 <= 0.0 {
            continue;
        }
        let mean =
            r.entries.iter().map(|&(f, _)| diagonal(f)).sum::<f64>() / r.entries.len() as f64;
        let rho = mean / norm2;
        for &(j, cj) in &r.entries {
            for &(i, ci) in &r.entries {
                added[j].push((i, rho * ci * cj));
            }
        }
        any = true;
    }
    if !any {
        return None;
    }
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut row_idx = Vec::with_capacity(kr.compute_nnz());
    let mut val = Vec::with_capacity(kr.compute_nnz());
    col_ptr.push(0);
    for (j, more) in added.iter_mut().enumerate() {
        let mut column: Vec<(usize, f64)> = kr
            .row_idx_of_col(j)
            .zip(kr.val_of_col(j))
            .map(|(i, &v)| (i, v))
            .collect();
        if !more.is_empty() {
            column.append(more);
            // Stable: K's entry first, then the footprints' in row order.
            column.sort_by_key(|e| e.0);
        }
        for (i, v) in column {
            match row_idx.last() {
                Some(&last) if last == i && row_idx.len() > col_ptr[j] => {
                    if let Some(x) = val.last_mut() {
                        *x += v;
                    }
                }
                _ => {
                    row_idx.push(i);
                    val.push(v);
                }
            }
        }
        col_ptr.push(row_idx.len());
    }
    Some(SparseColMat::new(
        SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx),
        val,
    ))
}

/// The label of point `p`'s dof along coordinate axis `d`.
fn point_label(p: usize, d: usize) -> DofLabel {
    DofLabel::Point {
        point: p,
        direction: d as u8,
    }
}

/// How each boundary row enters: a dof of its own (`u_m = r_b / c`) or a constraint row on the
/// interior dofs.
#[derive(Clone, Copy, Debug)]
enum RowKind {
    /// The dof `m` and `1 / c`.
    Eliminated { dof: usize, inv: f64 },
    /// Index among the constraint rows.
    Constraint(usize),
}

/// The boundary rows split into eliminated dofs and constraints, and the interior numbering.
struct Split {
    kinds: Vec<RowKind>,
    /// Free dofs of the interior (all but the eliminated ones), ascending; `interior_index[f]`
    /// their position.
    interior: Vec<usize>,
    interior_index: Vec<Option<usize>>,
    /// Constraint rows on the interior dofs (`C_P`, interior numbering) and their entries on
    /// eliminated dofs (`C_E`: boundary row of the dof, coefficient).
    constraint_rows: Vec<Vec<(usize, f64)>>,
    constraint_eliminated: Vec<Vec<(usize, f64)>>,
}

impl Split {
    fn new(rows: &[Row], n_free: usize, part: &str) -> Result<Self, ReduceError> {
        let mut owner: Vec<Option<usize>> = vec![None; n_free];
        let mut kinds = Vec::with_capacity(rows.len());
        let mut n_constraints = 0;
        for (b, r) in rows.iter().enumerate() {
            let single = match r.entries.as_slice() {
                &[(dof, c)] if c != 0.0 => Some((dof, c)),
                _ => None,
            };
            kinds.push(match single {
                Some((dof, c)) => {
                    // Two rows on one dof are the same coordinate twice.
                    if owner[dof].replace(b).is_some() {
                        return Err(ReduceError::NoMaster {
                            part: part.into(),
                            point: r.point,
                            direction: match r.label {
                                DofLabel::Point { direction, .. } => {
                                    AXES[direction.min(2) as usize]
                                }
                                _ => 'n',
                            },
                        });
                    }
                    RowKind::Eliminated { dof, inv: 1.0 / c }
                }
                None => {
                    n_constraints += 1;
                    RowKind::Constraint(n_constraints - 1)
                }
            });
        }
        let interior: Vec<usize> = (0..n_free).filter(|&f| owner[f].is_none()).collect();
        let mut interior_index = vec![None; n_free];
        for (i, &f) in interior.iter().enumerate() {
            interior_index[f] = Some(i);
        }
        let mut constraint_rows = Vec::with_capacity(n_constraints);
        let mut constraint_eliminated = Vec::with_capacity(n_constraints);
        for (r, kind) in rows.iter().zip(&kinds) {
            if let RowKind::Constraint(_) = kind {
                let (mut on_interior, mut on_eliminated) = (Vec::new(), Vec::new());
                for &(f, w) in &r.entries {
                    match (interior_index[f], owner[f]) {
                        (Some(i), _) => on_interior.push((i, w)),
                        (None, Some(b)) => on_eliminated.push((b, w)),
                        (None, None) => {}
                    }
                }
                constraint_rows.push(on_interior);
                constraint_eliminated.push(on_eliminated);
            }
        }
        Ok(Self {
            kinds,
            interior,
            interior_index,
            constraint_rows,
            constraint_eliminated,
        })
    }

    /// The constraint rows `C_P` on the interior dofs.
    fn constraints(&self) -> Result<Constraints, EigError> {
        Constraints::new(self.interior.len(), self.constraint_rows.clone())
    }

    /// The dof of an eliminated boundary row and `1 / c`.
    fn eliminated_dof(&self, b: usize) -> Option<(usize, f64)> {
        match self.kinds[b] {
            RowKind::Eliminated { dof, inv } => Some((dof, inv)),
            RowKind::Constraint(_) => None,
        }
    }

    /// Eq (3): the interior part of the constraint modes, one column per boundary row (see the
    /// module documentation), from the factor of `K_vv` and, if there are constraint rows, its
    /// constrained form.
    fn constraint_modes(
        &self,
        k: &SparseColMat<usize, f64>,
        factor: &SparseCholesky,
        constrained: Option<&ConstrainedFactor<'_>>,
    ) -> Result<Mat<f64>, EigError> {
        let eliminated: Vec<(usize, usize, f64)> = (0..self.kinds.len())
            .filter_map(|b| self.eliminated_dof(b).map(|(m, inv)| (b, m, inv)))
            .collect();
        // y = -K_vv⁻¹ K_vm / c for every eliminated dof.
        let mut y = Mat::<f64>::zeros(self.interior.len(), eliminated.len());
        let kr = k.as_ref();
        for (e, &(_, m, inv)) in eliminated.iter().enumerate() {
            for (r, &v) in kr.row_idx_of_col(m).zip(kr.val_of_col(m)) {
                if let Some(i) = self.interior_index[r] {
                    y[(i, e)] -= v * inv;
                }
            }
        }
        factor.solve_in_place(y.as_mut())?;
        let mut out = Mat::<f64>::zeros(self.interior.len(), self.kinds.len());
        let (y, x) = match constrained {
            None => (y, None),
            Some(c) => {
                // P y - X S⁻¹ C_E e_m / c, and X S⁻¹ for the constraint rows.
                let mut y = y;
                c.project(y.as_mut());
                let column = |b: usize| eliminated.iter().position(|&(row, _, _)| row == b);
                let g = Mat::from_fn(self.constraint_rows.len(), eliminated.len(), |p, e| {
                    self.constraint_eliminated[p]
                        .iter()
                        .filter(|&&(b, _)| column(b) == Some(e))
                        .map(|&(_, w)| w * eliminated[e].2)
                        .sum()
                });
                let y = &y - c.correction(g.as_ref())?;
                let q = self.constraint_rows.len();
                (y, Some(c.correction(Mat::<f64>::identity(q, q).as_ref())?))
            }
        };
        let mut next_eliminated = 0;
        for (b, kind) in self.kinds.iter().enumerate() {
            match (kind, &x) {
                (RowKind::Eliminated { .. }, _) => {
                    out.col_mut(b).copy_from(y.col(next_eliminated));
                    next_eliminated += 1;
                }
                (RowKind::Constraint(p), Some(x)) => out.col_mut(b).copy_from(x.col(*p)),
                (RowKind::Constraint(_), None) => {}
            }
        }
        Ok(out)
    }

    /// `X_II`: `x` itself when no dof is eliminated (no copy of a large matrix), else
    /// [`Split::extract_interior`].
    fn interior_of<'x>(
        &self,
        x: &'x SparseColMat<usize, f64>,
    ) -> Cow<'x, SparseColMat<usize, f64>> {
        if self.interior.len() == x.ncols() {
            Cow::Borrowed(x)
        } else {
            Cow::Owned(self.extract_interior(x))
        }
    }

    /// `X_II` as a sparse matrix (rows and columns of the interior dofs).
    fn extract_interior(&self, x: &SparseColMat<usize, f64>) -> SparseColMat<usize, f64> {
        let n = self.interior.len();
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        let mut val = Vec::new();
        col_ptr.push(0);
        let xr = x.as_ref();
        for &f in &self.interior {
            for (r, &v) in xr.row_idx_of_col(f).zip(xr.val_of_col(f)) {
                if let Some(i) = self.interior_index[r] {
                    row_idx.push(i);
                    val.push(v);
                }
            }
            col_ptr.push(row_idx.len());
        }
        SparseColMat::new(
            SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx),
            val,
        )
    }

    /// Writes an interior vector into the interior dofs of `out` (a full free-dof vector whose
    /// eliminated dofs are left as they are).
    fn expand_into(&self, v: faer::ColRef<'_, f64>, mut out: faer::ColMut<'_, f64>) {
        for (i, &f) in self.interior.iter().enumerate() {
            out[f] = v[i];
        }
    }
}

/// Rows per block in the sums of [`project`]: fixed, so that the bits of the result do not
/// depend on the thread count.
const ROW_BLOCK: usize = 4096;

/// Eqs (6)–(7): `K̂ = Bᵀ K B` and `M̂ = Bᵀ M B` for sparse symmetric `K`, `M` (both
/// triangles stored) and dense `B`, symmetrized. Blocks of rows run in parallel: in each, a
/// row `i` of `X B` sums the stored entries of column `i` of `X` (its row `i`) in stored
/// order, and the block adds `B_blockᵀ (X B)_block`; the blocks' sums are added in order.
/// The result is the same bits for any number of threads.
fn project_pair(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    basis: &Mat<f64>,
) -> (Mat<f64>, Mat<f64>) {
    let (rows, n) = (basis.nrows(), basis.ncols());
    // Row-major copy of B: a row of X B is then a sum of contiguous rows of B.
    let mut b_rows = vec![0.0; rows * n];
    for j in 0..n {
        for (i, &v) in basis.col(j).iter().enumerate() {
            b_rows[i * n + j] = v;
        }
    }
    let starts: Vec<usize> = (0..rows).step_by(ROW_BLOCK).collect();
    let project = |x: &SparseColMat<usize, f64>| {
        let xr = x.as_ref();
        let partials: Vec<Mat<f64>> = starts
            .par_iter()
            .map(|&r0| {
                let len = ROW_BLOCK.min(rows - r0);
                let mut xb = vec![0.0; len * n];
                for (i, out) in (r0..r0 + len).zip(xb.chunks_exact_mut(n.max(1))) {
                    for (r, &v) in xr.row_idx_of_col(i).zip(xr.val_of_col(i)) {
                        for (o, b) in out.iter_mut().zip(&b_rows[r * n..(r + 1) * n]) {
                            *o += v * b;
                        }
                    }
                }
                let block = MatRef::from_row_major_slice(&b_rows[r0 * n..(r0 + len) * n], len, n);
                let xb = MatRef::from_row_major_slice(&xb, len, n);
                let mut p = Mat::<f64>::zeros(n, n);
                faer::linalg::matmul::matmul(
                    p.as_mut(),
                    Accum::Replace,
                    block.transpose(),
                    xb,
                    1.0,
                    Par::Seq,
                );
                p
            })
            .collect();
        let mut p = Mat::<f64>::zeros(n, n);
        for part in &partials {
            p += part;
        }
        Mat::from_fn(n, n, |i, j| 0.5 * (p[(i, j)] + p[(j, i)]))
    };
    (project(k), project(m))
}

fn max_deviation_from_identity(m: &Mat<f64>, from: usize) -> f64 {
    let n = m.nrows();
    let mut worst: f64 = 0.0;
    for i in from..n {
        for j in from..n {
            let target = if i == j { 1.0 } else { 0.0 };
            worst = worst.max((m[(i, j)] - target).abs());
        }
    }
    worst
}

/// Re-orthonormalizes the modal columns in the mass metric: with `Φᵀ M Φ = L Lᵀ`,
/// `Φ ← Φ L⁻ᵀ`, and `K̂ ← Sᵀ K̂ S`, `M̂ ← Sᵀ M̂ S` with `S = diag(I, L⁻ᵀ)` (the projection
/// of eqs 6–7 on the new basis, done on the small matrices).
fn orthonormalize_modes(
    basis: &mut Mat<f64>,
    k_hat: &mut Mat<f64>,
    m_hat: &mut Mat<f64>,
    nb: usize,
    part: &str,
) -> Result<(), ReduceError> {
    let n = basis.ncols();
    let nm = n - nb;
    let mnn = Mat::from_fn(nm, nm, |i, j| m_hat[(nb + i, nb + j)]);
    let l = dense_cholesky(&mnn).ok_or_else(|| ReduceError::Invalid {
        part: part.into(),
        what: "the modal block of the reduced mass is not positive definite".into(),
    })?;
    // L⁻¹ by forward substitution on the identity; S = diag(I, L⁻ᵀ).
    let mut linv = Mat::<f64>::zeros(nm, nm);
    for c in 0..nm {
        for i in c..nm {
            let mut s = if i == c { 1.0 } else { 0.0 };
            for k in c..i {
                s -= l[(i, k)] * linv[(k, c)];
            }
            linv[(i, c)] = s / l[(i, i)];
        }
    }
    let s = Mat::from_fn(n, n, |i, j| match (i < nb, j < nb) {
        (true, true) if i == j => 1.0,
        (false, false) => linv[(j - nb, i - nb)],
        _ => 0.0,
    });
    // Φ L⁻ᵀ, row by row, blocks of rows in parallel.
    let mut blocks = Vec::new();
    let mut rest = basis.subcols_mut(nb, nm);
    while rest.nrows() > 0 {
        let len = ROW_BLOCK.min(rest.nrows());
        let (top, bottom) = rest.split_at_row_mut(len);
        blocks.push(top);
        rest = bottom;
    }
    blocks.into_par_iter().for_each(|mut phi| {
        let mut row = vec![0.0; nm];
        for r in 0..phi.nrows() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = (j..nm).map(|k| phi[(r, k)] * linv[(k, j)]).sum();
            }
            for (j, &x) in row.iter().enumerate() {
                phi[(r, j)] = x;
            }
        }
    });
    let congruence = |a: &Mat<f64>| {
        let mut t = Mat::<f64>::zeros(n, n);
        faer::linalg::matmul::matmul(t.as_mut(), Accum::Replace, a, &s, 1.0, Par::Seq);
        let mut out = Mat::<f64>::zeros(n, n);
        faer::linalg::matmul::matmul(
            out.as_mut(),
            Accum::Replace,
            s.transpose(),
            &t,
            1.0,
            Par::Seq,
        );
        Mat::from_fn(n, n, |i, j| 0.5 * (out[(i, j)] + out[(j, i)]))
    };
    *k_hat = congruence(k_hat);
    *m_hat = congruence(m_hat);
    Ok(())
}

/// Lower Cholesky factor `L` of a small symmetric positive definite matrix (`A = L Lᵀ`,
/// textbook column order), or `None` at a pivot that is not positive.
pub(crate) fn dense_cholesky(a: &Mat<f64>) -> Option<Mat<f64>> {
    let n = a.nrows();
    let mut l = Mat::<f64>::zeros(n, n);
    for j in 0..n {
        let mut d = a[(j, j)];
        for k in 0..j {
            d -= l[(j, k)] * l[(j, k)];
        }
        if !(d > 0.0 && d.is_finite()) {
            return None;
        }
        let d = d.sqrt();
        l[(j, j)] = d;
        for i in j + 1..n {
            let mut s = a[(i, j)];
            for k in 0..j {
                s -= l[(i, k)] * l[(j, k)];
            }
            l[(i, j)] = s / d;
        }
    }
    Some(l)
}

fn block_norm(a: &Mat<f64>, rows: std::ops::Range<usize>, cols: std::ops::Range<usize>) -> f64 {
    let mut s = 0.0;
    for i in rows {
        for j in cols.clone() {
            s += a[(i, j)] * a[(i, j)];
        }
    }
    s.sqrt()
}

fn frobenius(a: &Mat<f64>) -> f64 {
    block_norm(a, 0..a.nrows(), 0..a.ncols())
}

fn material_infos(materials: &MaterialTable) -> Vec<MaterialInfo> {
    let mut count = vec![0usize; materials.entries.len()];
    for &e in &materials.element_entry {
        if let Some(c) = count.get_mut(e as usize) {
            *c += 1;
        }
    }
    materials
        .entries
        .iter()
        .zip(count)
        .map(|(e, elements)| MaterialInfo {
            name: e.name.clone(),
            elements,
            material: e.material,
        })
        .collect()
}

fn restraint_infos(mesh: &Mesh, restraints: &[Restraint]) -> Vec<RestraintInfo> {
    restraints
        .iter()
        .map(|r| {
            let (name, nodes) = match &r.nodes {
                squeal_fe::NodeSelection::Set(s) => {
                    (s.clone(), mesh.node_set(s).map_or(0, <[u32]>::len))
                }
                squeal_fe::NodeSelection::Indices(v) => ("(nodes)".to_string(), v.len()),
            };
            RestraintInfo {
                node_set: name,
                directions: r.directions,
                nodes,
            }
        })
        .collect()
}
