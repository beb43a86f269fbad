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
//! With thousands of boundary coordinates (the nodal interface's face nodes) `Ψ` is the bulk
//! of the memory: the fixed-interface modes are solved first, `B` is allocated once at its
//! size, the constraint modes are solved into its first columns in blocks, and eqs (6)–(7)
//! are formed in blocks of columns of the lower triangle, `K̂_BB` as the Schur complement on
//! the boundary rows' dofs (the private module `blocked`, `craig_bampton/blocked.rs`).
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

pub use crate::error::ReduceError;
use crate::interface::nodal::face_nodes;
use crate::interface::quad_contact::{combined_nodes, contact_points};
use crate::interface::{InterfaceError, contact_nodes, footprint, patches, tributary_areas};
use crate::rom::{
    Basis, DofLabel, InterfaceKind, InterfacePoint, MaterialInfo, PartInfo, PartRole, PointRole,
    ReducedPart, RestraintInfo,
};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Accum, Mat, MatRef, Par};
use rayon::prelude::*;
use squeal_eigs::{
    ConstrainedFactor, Constraints, EigError, EigOptions, SparseCholesky, lowest_modes_constrained,
    lowest_modes_with_factor,
};
use squeal_fe::frames::{
    DofTransform, HeldNodes, NodeFrame, RotationAxis, SkewRestraint, orthonormal_completion,
};
use squeal_fe::{DofMap, MaterialTable, Restraint};
use squeal_mesh::Mesh;
use std::borrow::Cow;
use std::time::{Duration, Instant};

mod boundary;
#[allow(unused_imports)]
use boundary::*;

mod coupled;
pub(crate) use coupled::coupling_rows;
mod blocked;
mod fixed;
mod spec;
pub(crate) use boundary::boundary_rows;
#[allow(unused_imports)]
use fixed::*;
pub use spec::PartSpec;

const AXES: [char; 3] = ['x', 'y', 'z'];

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
        Stage::Eigensolve,
        Stage::ConstraintModes,
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
#[derive(Clone, Debug, Default)]
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
    pub(crate) fn along(&self, node: u32, w: [f64; 3]) -> Option<Vec<(usize, f64)>> {
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

    /// The row `w · u` of node `node` on the free coordinates with the share of `w` along
    /// restrained directions left out (their motion is zero): for springs, which may reach a
    /// held node.
    pub(crate) fn along_free(&self, node: u32, w: [f64; 3]) -> Vec<(usize, f64)> {
        if let Some(t) = &self.transform
            && let Some(kept) = t.kept(node)
        {
            let size = w.iter().map(|x| x.abs()).fold(0.0, f64::max);
            return kept
                .iter()
                .filter_map(|&(dof, e)| {
                    let c: f64 = (0..3).map(|d| w[d] * e[d]).sum();
                    (c.abs() > 1e-12 * size).then_some((dof, c))
                })
                .collect();
        }
        (0..3)
            .filter(|&d| w[d] != 0.0)
            .filter_map(|d| Some((self.free_dof(node, d)?, w[d])))
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
    reduce_part_coupled(mesh, materials, spec, &[], opts, progress)
}

/// [`reduce_part`] with coupling sets: each node set of `couplings` keeps its mean motion,
/// six boundary coordinates appended after the contact and piston points
/// ([`crate::coupling`]).
pub fn reduce_part_coupled(
    mesh: &Mesh,
    materials: &MaterialTable,
    spec: &PartSpec,
    couplings: &[crate::coupling::CouplingSet],
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
    let crate::unreduced::Assembly {
        held,
        dofmap,
        transform,
        ties: _,
        system,
        springs,
        spring_terms,
    } = crate::unreduced::assemble_kept(mesh, materials, spec)?;
    let free = FreeDofs {
        dofmap: &dofmap,
        transform,
    };
    clock(Stage::Assemble, t, &mut timings);

    progress(Stage::Interface);
    let t = Instant::now();
    let (mut points, mut rows) = boundary_rows(mesh, &free, spec)?;
    coupled::coupling_rows(mesh, &free, spec, couplings, &mut points, &mut rows)?;
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
    let chol = {
        let mut o = squeal_eigs::CholeskyOptions::default();
        o.par = opts.eig.par;
        o
    };
    let factor = SparseCholesky::factorize_with(k_vv.as_ref(), &chol).map_err(|e| match e {
        EigError::NotPositiveDefinite { .. } => {
            let free_motions =
                crate::held::free_motions_of(mesh, &free, &held, &rows, &springs, &spring_terms);
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

    // The fixed-interface modes first, so that the basis `[Ψ, Φ]` is allocated once at its
    // size and the constraint modes are solved straight into it (`blocked`); the deferred
    // Sturm check, which frees the factor, after the constraint modes.
    let t = Instant::now();
    let constrained = match constraints.is_empty() {
        true => None,
        false => Some(ConstrainedFactor::new(&factor, &constraints).map_err(eigen)?),
    };
    let constrained_time = t.elapsed();

    progress(Stage::Eigensolve);
    let t = Instant::now();
    let factor_stats = factor.stats();
    let sturm = sturm_placement(opts, &factor_stats, spec.modes);
    let modes =
        fixed_interface_modes(k_vv, m_vv, &factor, constrained.as_ref(), spec, opts, sturm)?;
    let eigensolve_time = t.elapsed();

    progress(Stage::ConstraintModes);
    let t = Instant::now();
    let nb = rows.len();
    let nm = modes.values.len();
    let n = nb + nm;
    let mut basis = try_zeros(free.num_free(), n, &part)?;
    split
        .constraint_modes_into(
            k_factored,
            &factor,
            constrained.as_ref(),
            basis.as_mut(),
            blocked::MODE_BLOCK,
        )
        .map_err(eigen)?;
    drop(constrained);
    let constraint_modes_time = constrained_time + t.elapsed();

    let t = Instant::now();
    let mut modes = match modes.deferred {
        false => {
            drop(factor);
            modes
        }
        true => check_deferred(modes, factor, k_vv, m_vv, &constraints, spec, opts)?,
    };
    timings.push((Stage::Eigensolve, eigensolve_time + t.elapsed()));
    timings.push((Stage::ConstraintModes, constraint_modes_time));

    progress(Stage::Project);
    let t = Instant::now();
    for j in 0..nm {
        split.expand_into(modes.vectors.col(j), basis.col_mut(nb + j));
    }
    modes.vectors = Mat::zeros(0, 0);
    let support = split.support(&rows);
    let (mut k_hat, mut m_hat) = blocked::project_blocked(
        &system.k,
        &system.m,
        basis.as_ref(),
        nb,
        &support,
        blocked::PROJECT_BLOCK,
    );
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

/// Refuses a tied (slave) node that is restrained or in axes of its own: its motion is its
/// masters' (module docs of [`crate::tie`]).
pub(crate) fn refuse_held_slaves(
    mesh: &Mesh,
    dofmap: &DofMap,
    held: &HeldNodes,
    ties: &std::collections::BTreeMap<u32, Vec<(u32, f64)>>,
) -> Result<(), ReduceError> {
    for &s in ties.keys() {
        let restrained = (0..3).any(|d| dofmap.status(s, d) == squeal_fe::DofStatus::Restrained);
        if restrained || held.frames.contains_key(&s) {
            return Err(ReduceError::Options(format!(
                "node {} is tied (on a slave surface) and also restrained or kept as a piston: hold or press the master part instead, or make the held surface the master",
                mesh.node_ids[s as usize]
            )));
        }
    }
    Ok(())
}

/// `K` plus the supports' springs: `k_d (w · u)²` for each supported node and direction
/// `w = e_d` with `k_d > 0`, on the free coordinates (a node in its own axes through its kept
/// coordinates; a restrained direction holds already and adds nothing).
pub(crate) fn add_springs(
    k: &SparseColMat<usize, f64>,
    free: &FreeDofs,
    springs: &std::collections::BTreeMap<u32, [f64; 3]>,
) -> SparseColMat<usize, f64> {
    let mut added: Vec<Vec<(usize, f64)>> = vec![Vec::new(); k.ncols()];
    for (&node, kd) in springs {
        for d in (0..3).filter(|&d| kd[d] > 0.0) {
            let mut w = [0.0; 3];
            w[d] = 1.0;
            let Some(a) = free.along(node, w) else {
                continue;
            };
            for &(j, cj) in &a {
                for &(i, ci) in &a {
                    added[j].push((i, kd[d] * ci * cj));
                }
            }
        }
    }
    with_added(k, added)
}

/// `K` plus the springs' rank-one terms `k c cᵀ` ([`crate::springs`]) on the free coordinates:
/// each entry `w · u_n` through the node's free dofs (a node in its own axes through its kept
/// coordinates), a restrained direction's share left out (its motion is zero). A tied (slave)
/// node is refused: its motion is its masters'.
pub(crate) fn add_spring_terms(
    mesh: &Mesh,
    k: &SparseColMat<usize, f64>,
    free: &FreeDofs,
    ties: &std::collections::BTreeMap<u32, Vec<(u32, f64)>>,
    terms: &[crate::springs::SpringTerm],
) -> Result<SparseColMat<usize, f64>, ReduceError> {
    let mut added: Vec<Vec<(usize, f64)>> = vec![Vec::new(); k.ncols()];
    for term in terms {
        let mut c: Vec<(usize, f64)> = Vec::new();
        for &(node, w) in &term.entries {
            if ties.contains_key(&node) {
                return Err(ReduceError::Options(format!(
                    "node {} carries a spring and is tied (on a slave surface): put the spring on the master surface",
                    mesh.node_ids[node as usize]
                )));
            }
            c.extend(free.along_free(node, w));
        }
        for &(j, cj) in &c {
            for &(i, ci) in &c {
                added[j].push((i, term.k * ci * cj));
            }
        }
    }
    Ok(with_added(k, added))
}

/// Natural frequency (Hz) of an eigenvalue `ω²` (negative round-off clipped to 0).
pub fn hz(omega2: f64) -> f64 {
    omega2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}

/// The eigenvalue `ω² = (2π f)²` of a frequency in Hz.
pub fn omega2(hz: f64) -> f64 {
    (2.0 * std::f64::consts::PI * hz).powi(2)
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
