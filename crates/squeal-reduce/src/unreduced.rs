//! A part's unreduced stiffness and mass, assembled as the Craig–Bampton reduction assembles
//! them before it reduces (the reference the reduction is measured against, `squeal stability
//! --full`).
//!
//! [`unreduced_part`] is the assembly stage of [`crate::craig_bampton::reduce_part_coupled`]
//! itself (both call one function), without the reduction that follows:
//!
//! 1. the held nodes: the part's restraints, its restraints in node frames (skew directions and
//!    directions relative to the disc's axis) and the pistons' own axes;
//! 2. `K`, `M` on the free dofs, then, for nodes in their own axes and tied (slave) nodes, the
//!    congruence `K' = Tᵀ K T`, `M' = Tᵀ M T` on the kept coordinates
//!    ([`squeal_fe::frames::DofTransform::with_ties`]; ties eliminated, [`crate::tie`]);
//! 3. the supports' springs and the `[[springs]]`' rank-one terms `k c cᵀ` on the kept
//!    coordinates ([`crate::tie`], [`crate::springs`]).
//!
//! The Craig–Bampton basis `B` of the part lives on these kept coordinates, and the reduced
//! matrices are `K̂ = Bᵀ K' B`, `M̂ = Bᵀ M' B` (eqs 6–7), so the reduced part is this part
//! projected on `B` (Rayleigh–Ritz): its frequencies bound these from above.
//!
//! A motion of a node along `w` is a row on the kept coordinates ([`Coordinates::along`], the
//! reduction's own rows for its contact points); a coupling set's six mean-motion rows are
//! those of [`crate::coupling`] ([`UnreducedPart::coupling_rows`], the reduction's rows), and
//! a viscous damper's terms `c (w · u̇)²` are the springs' on the same coordinates
//! ([`UnreducedPart::damping`]).

use crate::ReduceError;
use crate::coupling::CouplingSet;
use crate::craig_bampton::{
    FreeDofs, PartSpec, add_spring_terms, add_springs, coupling_rows, piston_frames,
    refuse_held_slaves, skew_restraints,
};
use faer::sparse::SparseColMat;
use squeal_fe::frames::{DofTransform, HeldNodes};
use squeal_fe::{DofMap, MaterialTable, System, assemble};
use squeal_mesh::Mesh;
use std::collections::BTreeMap;

/// A part's unreduced `K'`, `M'` on its kept coordinates (module docs).
pub struct UnreducedPart {
    /// The free dofs of the mesh (before the transform).
    pub dofmap: DofMap,
    /// The map to the kept coordinates, when some node is in its own axes or tied.
    transform: Option<DofTransform>,
    /// The tied (slave) nodes and their masters' weights.
    ties: BTreeMap<u32, Vec<(u32, f64)>>,
    /// `K'` (with the supports and springs) and `M'` on the kept coordinates.
    pub system: System,
}

/// The kept coordinates of an [`UnreducedPart`], to write motions of its nodes on them.
pub struct Coordinates<'a>(FreeDofs<'a>);

impl Coordinates<'_> {
    /// The row `w · u` of node `node` (`w` a unit vector) on the kept coordinates, as the
    /// reduction writes a contact point's row; `None` when `w` has a part along a restrained
    /// direction of the node, or the node is tied (its motion is its masters').
    pub fn along(&self, node: u32, w: [f64; 3]) -> Option<Vec<(usize, f64)>> {
        self.0.along(node, w)
    }
}

/// The assembly stage's products (module docs, steps 1–3), shared by the reduction
/// ([`crate::craig_bampton::reduce_part_coupled`]) and [`unreduced_part`].
pub(crate) struct Assembly {
    /// The held nodes (restraints, node frames, piston axes).
    pub(crate) held: HeldNodes,
    /// The free dofs of the mesh (before the transform).
    pub(crate) dofmap: DofMap,
    /// The map to the kept coordinates, when some node is in its own axes or tied.
    pub(crate) transform: Option<DofTransform>,
    /// The tied (slave) nodes and their masters' weights.
    pub(crate) ties: BTreeMap<u32, Vec<(u32, f64)>>,
    /// `K'` (with the supports and springs) and `M'` on the kept coordinates.
    pub(crate) system: System,
    /// The supports' springs by node.
    pub(crate) springs: BTreeMap<u32, [f64; 3]>,
    /// The `[[springs]]`' rank-one terms.
    pub(crate) spring_terms: Vec<crate::springs::SpringTerm>,
}

/// Steps 1–3 of the module docs for the part of `mesh` described by `spec`.
pub(crate) fn assemble_kept(
    mesh: &Mesh,
    materials: &MaterialTable,
    spec: &PartSpec,
) -> Result<Assembly, ReduceError> {
    let mut held = HeldNodes::new(mesh, &spec.restraints, &skew_restraints(mesh, spec)?)?;
    piston_frames(mesh, spec, &mut held)?;
    let dofmap = DofMap::new(mesh, &held.restraints)?;
    let ties = crate::tie::tie_constraints(mesh, &spec.ties)?;
    refuse_held_slaves(mesh, &dofmap, &held, &ties)?;
    let system = assemble(mesh, materials, &dofmap)?;
    // Nodes held along skew directions and tied nodes: K' = Tᵀ K T, M' = Tᵀ M T on the kept
    // coordinates.
    let free = FreeDofs {
        dofmap: &dofmap,
        transform: (held.has_frames() || !ties.is_empty())
            .then(|| DofTransform::with_ties(&dofmap, &held, &ties)),
    };
    let mut system = match &free.transform {
        Some(t) => t.system(&dofmap, &system),
        None => system,
    };
    let springs = crate::tie::support_springs(mesh, &spec.supports)?;
    if !springs.is_empty() {
        system.k = add_springs(&system.k, &free, &springs);
    }
    let spring_terms = crate::springs::spring_terms(mesh, &spec.springs)?;
    if !spring_terms.is_empty() {
        system.k = add_spring_terms(mesh, &system.k, &free, &ties, &spring_terms)?;
    }
    let transform = free.transform;
    Ok(Assembly {
        held,
        dofmap,
        transform,
        ties,
        system,
        springs,
        spring_terms,
    })
}

/// Assembles the part of `mesh` described by `spec` as the reduction does (module docs).
pub fn unreduced_part(
    mesh: &Mesh,
    materials: &MaterialTable,
    spec: &PartSpec,
) -> Result<UnreducedPart, ReduceError> {
    let a = assemble_kept(mesh, materials, spec)?;
    Ok(UnreducedPart {
        dofmap: a.dofmap,
        transform: a.transform,
        ties: a.ties,
        system: a.system,
    })
}

impl UnreducedPart {
    /// Number of kept coordinates.
    pub fn num_free(&self) -> usize {
        self.system.k.ncols()
    }

    /// Number of tied (slave) nodes.
    pub fn tied_nodes(&self) -> usize {
        self.ties.len()
    }

    /// The kept coordinates, to write node motions on.
    pub fn coordinates(&self) -> Coordinates<'_> {
        Coordinates(FreeDofs {
            dofmap: &self.dofmap,
            transform: self.transform.clone(),
        })
    }

    /// The six mean-motion rows (translations x, y, z, rotations about x, y, z) of each of
    /// `couplings`, in order, on the kept coordinates: the rows the reduction keeps as the
    /// coupling points' boundary coordinates ([`crate::coupling`]).
    pub fn coupling_rows(
        &self,
        mesh: &Mesh,
        spec: &PartSpec,
        couplings: &[CouplingSet],
    ) -> Result<Vec<Vec<(usize, f64)>>, ReduceError> {
        let free = self.coordinates().0;
        let (mut points, mut rows) = (Vec::new(), Vec::new());
        coupling_rows(mesh, &free, spec, couplings, &mut points, &mut rows)?;
        Ok(rows.into_iter().map(|r| r.entries).collect())
    }

    /// The damping matrix `Σ c (w · u̇)²` of `dampers` on the kept coordinates (the terms of
    /// [`crate::dampers::damper_terms`] written as the springs' are): symmetric, positive
    /// semi-definite. A damper on a tied (slave) node is refused, as a spring there is.
    pub fn damping(
        &self,
        mesh: &Mesh,
        dampers: &[crate::dampers::Damper],
    ) -> Result<SparseColMat<usize, f64>, ReduceError> {
        let n = self.num_free();
        let zero = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &[])
            .map_err(|e| ReduceError::Options(format!("an empty {n} x {n} matrix: {e}")))?;
        let terms = crate::dampers::damper_terms(mesh, dampers)?;
        let free = self.coordinates().0;
        add_spring_terms(mesh, &zero, &free, &self.ties, &terms)
    }
}
