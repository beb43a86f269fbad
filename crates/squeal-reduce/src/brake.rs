//! The brake: a disc and a pad, from their mesh files to the reduced model of eqs (1)–(7).
//!
//! [`reduce_brake`] reads both meshes (recording their SHA-256), checks that every disc
//! contact point faces a pad contact point, then reduces the disc and the pad with
//! [`reduce_part`](crate::craig_bampton::reduce_part) at the same time, as two tasks of the rayon pool (each part's own parallel
//! work shares the pool with the other's; the results do not depend on the thread count). With [`BrakeInputs::default`] (the bundled setup: disc clamped on `CLAMP`,
//! pad held in-plane on `ABUTMENT` with its `PISTON` nodes' normal dof kept, nine contact points
//! per part, 50 fixed-interface modes) the result is the paper's 158-dof brake:
//! 27 + 50 disc dofs and 27 + 4 + 50 pad dofs (Sec. 2.1).
//!
//! Each part's [`BuildRecord`] is stored in the file, so that [`freshness`] can tell whether an
//! existing `.rom` still matches given inputs (mesh hashes, options, tool version).

use crate::craig_bampton::{
    PartSpec, ReduceError, ReduceOptions, ReduceReport, Stage, reduce_part_coupled,
};
use crate::interface::nodal::{NodalPair, face_nodes, project_pad};
use crate::interface::{Axis, InterfaceError, contact_nodes, patches};
use crate::rom::ReducedPart;
use crate::rom::{
    BuildRecord, ContactSurface, InterfaceKind, InterfacePoint, MeshInfo, PartRole, PointRole,
    Projected, ReducedModel, RomError, RomHeader, VERSION, read_header, sha256_file,
};
use faer::Par;
use serde::{Deserialize, Serialize};
use squeal_eigs::{Backend, EigOptions};
use squeal_element::geometry::unit;
use squeal_fe::frames::AxisDirection;
use squeal_fe::{ElasticMaterial, MaterialTable, NodeSelection, Restraint};
use squeal_mesh::Mesh;
use squeal_mesh::units::UnitSystem;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError, mpsc};
use std::time::{Duration, Instant};

mod freshness;
#[allow(unused_imports)]
use freshness::*;
pub use freshness::{Freshness, freshness, stale_reasons};

mod pairing;
#[allow(unused_imports)]
use pairing::*;
pub use pairing::{PairingTolerance, check_sets, contact_positions, pair_contact_points};

mod load;
#[allow(unused_imports)]
use load::*;

mod kept;
#[allow(unused_imports)]
use kept::*;

mod relay;

mod report;
pub use report::{BrakeReport, PartReport, PointPair};

mod bodies;
#[allow(unused_imports)]
use bodies::*;
pub use bodies::{
    connection_reasons, free_motions_coupled, require_held_coupled, resolve_connections,
};
pub use kept::{forget_kept, kept_dir};
pub use load::{
    LoadedPart, backend_name, load_part, load_part_in, load_part_of, refuse_mesh_errors,
    refuse_shortened_set,
};
use relay::relay;

/// The version written into every `.rom` file; a file made by another version is stale. The
/// suffix is the revision of the numbers a reduction produces: bump it with every change that
/// moves the reduced matrices (fe2: curved tet10 elements integrated with the 24-point rule), so
/// that a cache made by older code is reduced again instead of silently reused.
pub const TOOL_VERSION: &str = concat!("squeal ", env!("CARGO_PKG_VERSION"), "+fe2");

/// Default multiple of the highest frequency of interest below which modes are kept in
/// [`ModeChoice::Auto`] (see `docs/reduction.md` for how the choice moves the frequencies).
pub const DEFAULT_AUTO_FACTOR: f64 = 2.0;

/// Default limit on the fixed-interface modes of one part: the basis is
/// `free dofs x (boundary + modes)` doubles, about 1 GB for 1000 modes of the fine disc.
pub const DEFAULT_MAX_MODES: usize = 1000;

/// Default pairing tolerance, as a fraction of the smallest distance between two of the disc's
/// contact points (the patch size).
pub const DEFAULT_PAIRING_TOLERANCE: f64 = 0.05;

/// How many fixed-interface modes each part keeps (eqs 4–5).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ModeChoice {
    /// The `n` lowest (the paper: 50).
    Fixed(usize),
    /// All modes below `factor × fmax_hz`: the fewest a study up to `fmax_hz` needs.
    Auto {
        /// Highest frequency of the study (Hz).
        fmax_hz: f64,
        /// Multiple of `fmax_hz` up to which modes are kept ([`DEFAULT_AUTO_FACTOR`]).
        factor: f64,
    },
}

impl ModeChoice {
    /// [`ModeChoice::Auto`] with [`DEFAULT_AUTO_FACTOR`].
    pub fn auto(fmax_hz: f64) -> Self {
        Self::Auto {
            fmax_hz,
            factor: DEFAULT_AUTO_FACTOR,
        }
    }
}

/// One part: its mesh file and how it is held and tied to the other part.
#[derive(Clone, Debug, PartialEq)]
pub struct PartInput {
    /// Mesh file (`.inp` or `.msh`).
    pub mesh: PathBuf,
    /// The element sets of `mesh` the part is made of, when the file holds an assembly (their
    /// elements, the nodes they use and the sets restricted to them,
    /// [`squeal_mesh::Mesh::part_of_sets`]); empty: the whole file.
    pub elset: Vec<String>,
    /// Tied interfaces inside the part (its meshes merged, [`crate::tie`]).
    pub ties: Vec<crate::tie::Tie>,
    /// Springs to ground on node sets ([`crate::tie`]).
    pub supports: Vec<crate::tie::Support>,
    /// Springs between node sets of the part or to ground ([`crate::springs`]).
    pub springs: Vec<crate::springs::Spring>,
    /// Materials by element set, applied after the mesh's own sections (a `.msh` has none).
    pub material_overrides: Vec<(String, ElasticMaterial)>,
    /// How the part is held: node sets and their clamped directions.
    pub restraints: Vec<Restraint>,
    /// Restraints along global directions that are not coordinate axes: node set and the
    /// directions its nodes are held in (exact, by [`squeal_fe::frames`]).
    pub skew_restraints: Vec<(String, Vec<[f64; 3]>)>,
    /// Restraints relative to the disc's axis ([`BrakeInputs::axis`]): node set and the
    /// directions (axial, radial, tangential at each node) its nodes are held in.
    pub axis_restraints: Vec<(String, Vec<AxisDirection>)>,
    /// Node set of the contact points (node interface).
    pub contact_set: String,
    /// Node set of the contact face (patch interface).
    pub contact_face_set: String,
    /// Node set whose normal dof is kept (the pad's pistons, or the caliper's fingers on an
    /// outboard pad).
    pub piston_set: Option<String>,
    /// The pistons as footprints instead, one node set per piston (the faces it presses on),
    /// each keeping its area-weighted mean motion along the normal
    /// ([`crate::craig_bampton::PartSpec::piston_footprints`]); `piston_set` then names all
    /// their nodes.
    pub piston_footprints: Vec<String>,
    /// The pad `contact_set` / `contact_face_set` face, on a disc braked by several pads
    /// (`None` on a pad, and on a disc braked by one).
    pub facing: Option<String>,
    /// A disc's further contact surfaces, one for each pad after the first.
    pub extra_surfaces: Vec<ContactSurface>,
    /// The unit system the mesh file is written in; [`load_part`]'s caller converts it to SI
    /// ([`reduce_brake`] does), and the `.rom` records it.
    pub units: UnitSystem,
    /// Node sets kept as coupling points, six mean-motion dofs each, where connections to
    /// other parts act ([`crate::coupling`]).
    pub couplings: Vec<crate::coupling::CouplingSet>,
}

impl PartInput {
    /// The bundled disc: clamped on `CLAMP` (all dofs), contact on `CONTACT` / `CONTACT_FACE`.
    pub fn disc(mesh: impl Into<PathBuf>) -> Self {
        Self {
            mesh: mesh.into(),
            elset: Vec::new(),
            ties: Vec::new(),
            supports: Vec::new(),
            springs: Vec::new(),
            material_overrides: Vec::new(),
            restraints: vec![Restraint::clamp("CLAMP")],
            skew_restraints: Vec::new(),
            axis_restraints: Vec::new(),
            contact_set: "CONTACT".into(),
            contact_face_set: "CONTACT_FACE".into(),
            piston_set: None,
            piston_footprints: Vec::new(),
            facing: None,
            extra_surfaces: Vec::new(),
            units: UnitSystem::default(),
            couplings: Vec::new(),
        }
    }

    /// The bundled pad: `ABUTMENT` held in x and y (free only along the normal z), the
    /// `PISTON` nodes' z dof kept, contact on `CONTACT` / `CONTACT_FACE`.
    pub fn pad(mesh: impl Into<PathBuf>) -> Self {
        Self {
            mesh: mesh.into(),
            elset: Vec::new(),
            ties: Vec::new(),
            supports: Vec::new(),
            springs: Vec::new(),
            material_overrides: Vec::new(),
            restraints: vec![Restraint::set("ABUTMENT", [true, true, false])],
            skew_restraints: Vec::new(),
            axis_restraints: Vec::new(),
            contact_set: "CONTACT".into(),
            contact_face_set: "CONTACT_FACE".into(),
            piston_set: Some("PISTON".into()),
            piston_footprints: Vec::new(),
            facing: None,
            extra_surfaces: Vec::new(),
            units: UnitSystem::default(),
            couplings: Vec::new(),
        }
    }
}

impl PartInput {
    /// The part's contact surfaces: its own sets first, then the further ones.
    pub fn surfaces(&self) -> Vec<ContactSurface> {
        ContactSurface::list(
            &self.facing,
            &self.contact_set,
            &self.contact_face_set,
            &self.extra_surfaces,
        )
    }

    /// The index in [`PartInput::surfaces`] of the surface facing pad `pad` of a brake with
    /// `pads` pads: the one named after it, or the only one when the brake has one pad and
    /// the part one surface.
    pub fn surface_index(&self, pad: &str, pads: usize) -> Option<usize> {
        let all = self.surfaces();
        if pads == 1 && all.len() == 1 {
            return Some(0);
        }
        all.iter().position(|s| s.facing.as_deref() == Some(pad))
    }
}

/// A pad of the brake: its name in the model (`pad` for a brake with one pad) and its part.
#[derive(Clone, Debug, PartialEq)]
pub struct PadInput {
    /// The pad's name: the part's name in the `.rom`, the disc surface facing it is named so.
    pub name: String,
    /// Its mesh, sets and restraints.
    pub part: PartInput,
}

/// Everything [`reduce_brake`] needs.
#[derive(Clone, Debug, PartialEq)]
pub struct BrakeInputs {
    /// The disc.
    pub disc: PartInput,
    /// The pads, the first pushed by the pistons (a one-pad brake has one, named `pad`).
    pub pads: Vec<PadInput>,
    /// Node or patch interface, for both parts.
    pub interface: InterfaceKind,
    /// How many fixed-interface modes each part keeps.
    pub modes: ModeChoice,
    /// Most fixed-interface modes a part may keep (bounds the memory of the basis).
    pub max_modes: usize,
    /// Patch grid `[radial, angular]` of the patch interface.
    pub grid: [usize; 2],
    /// The disc's axis: patches are cut in radius and angle about it.
    pub axis: Axis,
    /// Direction of the contact normal (0 = x, 1 = y, 2 = z): the pistons' kept dof.
    pub normal_direction: usize,
    /// The pistons' kept direction when it is not a coordinate axis (then `normal_direction`
    /// is not used): a dof along this unit vector ([`crate::rom::DofLabel::Along`]).
    pub piston_direction: Option<[f64; 3]>,
    /// Eigensolver of the fixed-interface modes (Lanczos or ARPACK).
    pub backend: Backend,
    /// Relative tolerance of the eigensolver's Ritz residuals.
    pub eig_tol: f64,
    /// Make the modal block of `M̂` the identity and that of `K̂` `diag(ω²)` after the solve.
    pub orthonormalize: bool,
    /// Keep each part's basis in the model (needed to expand results onto the meshes).
    pub keep_basis: bool,
    /// Contact points pair when closer than this fraction of the smallest distance between
    /// two of the disc's contact points.
    pub pairing_tolerance: f64,
    /// Further parts (a caliper, a bracket): role body, held by their restraints and their
    /// coupling sets, reduced like the others ([`crate::coupling`]).
    pub bodies: Vec<PadInput>,
    /// Springs between coupling points of two parts or to ground.
    pub connections: Vec<crate::coupling::ConnectionInput>,
    /// Ties between two parts, eliminated on the assembled model ([`crate::part_tie`]); their
    /// sets must be each part's `nodal` coupling sets.
    pub part_ties: Vec<crate::part_tie::PartTieInput>,
    /// Parallelism of the sparse factorizations (the rest runs on rayon in fixed-size
    /// blocks). Their bits do not depend on it; faer's dense kernels on small matrices, which
    /// follow `faer::get_global_parallelism()`, do: set that to `Par::Seq` for results that
    /// are bit-identical for any thread count (`squeal reduce` does).
    pub par: Par,
}

impl Default for BrakeInputs {
    /// The bundled fine meshes, patch interface on a 3 x 3 grid about the z axis, 50 modes.
    fn default() -> Self {
        Self {
            disc: PartInput::disc("meshes/disc_fine.inp"),
            pads: vec![PadInput {
                name: "pad".into(),
                part: PartInput::pad("meshes/pad_fine.inp"),
            }],
            interface: InterfaceKind::Patch,
            modes: ModeChoice::Fixed(50),
            max_modes: DEFAULT_MAX_MODES,
            grid: [3, 3],
            axis: Axis::default(),
            normal_direction: 2,
            piston_direction: None,
            backend: Backend::Lanczos,
            eig_tol: EigOptions::default().tol,
            orthonormalize: true,
            keep_basis: true,
            pairing_tolerance: DEFAULT_PAIRING_TOLERANCE,
            bodies: Vec::new(),
            connections: Vec::new(),
            part_ties: Vec::new(),
            par: Par::rayon(0),
        }
    }
}

impl BrakeInputs {
    /// The bundled setup on the given mesh files.
    pub fn bundled(disc: impl Into<PathBuf>, pad: impl Into<PathBuf>) -> Self {
        Self {
            disc: PartInput::disc(disc),
            pads: vec![PadInput {
                name: "pad".into(),
                part: PartInput::pad(pad),
            }],
            ..Self::default()
        }
    }

    /// The bundled setup turned to a disc axis and contact normal: patches cut about `axis`,
    /// the pad's `ABUTMENT` held in the plane normal to the axis (radially and tangentially,
    /// free along the axis), the pistons' dof along `normal` (the pad's normal). When the axis
    /// and the normal are coordinate axes (to 1e-12) these are the plain restraint and dof of
    /// [`BrakeInputs::bundled`], bit for bit; otherwise the restraint is held in skew axes and
    /// the piston dof is a [`crate::rom::DofLabel::Along`].
    pub fn about(mut self, axis: Axis, normal: [f64; 3]) -> Result<Self, ReduceError> {
        let bad = |what: &str| ReduceError::Options(format!("the {what} has zero length"));
        let a = unit(axis.direction).ok_or_else(|| bad("disc axis"))?;
        let n = unit(normal).ok_or_else(|| bad("contact normal"))?;
        self.axis = axis;
        match coordinate_axis(n) {
            Some(d) => {
                self.normal_direction = d;
                self.piston_direction = None;
            }
            None => self.piston_direction = Some(n),
        }
        for pad in &mut self.pads {
            let pad = &mut pad.part;
            pad.restraints
                .retain(|r| r.nodes != NodeSelection::Set("ABUTMENT".into()));
            pad.skew_restraints.retain(|r| r.0 != "ABUTMENT");
            match coordinate_axis(a) {
                Some(d) => {
                    let mut held = [true; 3];
                    held[d] = false;
                    pad.restraints.push(Restraint::set("ABUTMENT", held));
                }
                None => {
                    let [_, e2, e3] = squeal_fe::frames::orthonormal_completion(a);
                    pad.skew_restraints.push(("ABUTMENT".into(), vec![e2, e3]));
                }
            }
        }
        Ok(self)
    }

    /// The parts with their names, disc first, then the pads, then the bodies in order.
    pub fn parts(&self) -> Vec<(&str, &PartInput)> {
        std::iter::once(("disc", &self.disc))
            .chain(self.pads.iter().map(|p| (p.name.as_str(), &p.part)))
            .chain(self.bodies.iter().map(|p| (p.name.as_str(), &p.part)))
            .collect()
    }

    /// The first pad (the one the pistons push).
    pub fn pad(&self) -> &PartInput {
        &self.pads[0].part
    }

    /// The first pad, to change.
    pub fn pad_mut(&mut self) -> &mut PartInput {
        &mut self.pads[0].part
    }

    /// The record stored with part `input` in the `.rom` file.
    pub fn record(&self, input: &PartInput) -> BuildRecord {
        BuildRecord {
            restraints: input
                .restraints
                .iter()
                .map(|r| (selection_name(&r.nodes), r.directions))
                .collect(),
            skew_restraints: input.skew_restraints.clone(),
            axis_restraints: input.axis_restraints.clone(),
            piston_direction: self.piston_direction,
            material_overrides: input.material_overrides.clone(),
            contact_set: input.contact_set.clone(),
            contact_face_set: input.contact_face_set.clone(),
            piston_set: input.piston_set.clone(),
            piston_footprints: input.piston_footprints.clone(),
            facing: input.facing.clone(),
            extra_surfaces: input.extra_surfaces.clone(),
            grid: self.grid,
            axis: self.axis,
            normal_direction: self.normal_direction,
            modes: self.modes,
            max_modes: self.max_modes,
            backend: backend_name(self.backend).into(),
            eig_tol: self.eig_tol,
            orthonormalize: self.orthonormalize,
            units: (!input.units.is_si()).then(|| input.units.name.to_string()),
            elset: input.elset.clone(),
            ties: input.ties.clone(),
            supports: input.supports.clone(),
            springs: input.springs.clone(),
            couplings: input.couplings.clone(),
        }
    }

    /// Checks the options that do not need the meshes.
    pub fn validate(&self) -> Result<(), ReduceError> {
        let bad = |what: String| Err(ReduceError::Options(what));
        if self.pads.is_empty() {
            return bad("the brake has no pad".into());
        }
        for (i, p) in self.pads.iter().enumerate() {
            if p.name.is_empty() || p.name == "disc" {
                return bad(format!("a pad cannot be named '{}'", p.name));
            }
            if self.pads[..i].iter().any(|q| q.name == p.name) {
                return bad(format!("two pads are named '{}'", p.name));
            }
            if self.disc.surface_index(&p.name, self.pads.len()).is_none() {
                return bad(format!(
                    "the disc has no contact surface facing pad '{}' (a disc braked by {} pads needs one surface per pad, named after it)",
                    p.name,
                    self.pads.len()
                ));
            }
        }
        if self.normal_direction > 2 {
            return bad(format!(
                "normal direction {} is not 0 (x), 1 (y) or 2 (z)",
                self.normal_direction
            ));
        }
        if self.grid[0] == 0
            || self.grid[1] == 0
            || self.grid[0].saturating_mul(self.grid[1]) > 10_000
        {
            return bad(format!(
                "patch grid {} x {} must have 1 to 10000 cells",
                self.grid[0], self.grid[1]
            ));
        }
        match self.modes {
            ModeChoice::Fixed(n) if n > self.max_modes => {
                return bad(format!(
                    "{n} modes asked for, more than the limit of {}",
                    self.max_modes
                ));
            }
            ModeChoice::Auto { fmax_hz, factor }
                if !(fmax_hz.is_finite()
                    && fmax_hz > 0.0
                    && factor.is_finite()
                    && factor > 0.0) =>
            {
                return bad(format!(
                    "automatic mode choice needs a positive fmax and factor (got {fmax_hz} Hz, x{factor})"
                ));
            }
            _ => {}
        }
        if !(self.pairing_tolerance > 0.0 && self.pairing_tolerance.is_finite()) {
            return bad(format!(
                "pairing tolerance {} must be a positive fraction",
                self.pairing_tolerance
            ));
        }
        if !(self.eig_tol > 0.0 && self.eig_tol < 1.0) {
            return bad(format!(
                "eigensolver tolerance {} must be in (0, 1)",
                self.eig_tol
            ));
        }
        validate_bodies(self)
    }

    fn reduce_options(&self) -> ReduceOptions {
        ReduceOptions {
            eig: {
                let mut o = EigOptions::default();
                o.backend = self.backend;
                o.tol = self.eig_tol;
                o.par = self.par;
                o
            },
            orthonormalize: self.orthonormalize,
            keep_basis: self.keep_basis,
            modes_below_hz: match self.modes {
                ModeChoice::Fixed(_) => None,
                ModeChoice::Auto { fmax_hz, factor } => Some(fmax_hz * factor),
            },
        }
    }

    /// The [`PartSpec`] [`reduce_brake`] reduces part `input`, named `name`, with (read from the
    /// mesh described by `mesh`).
    pub fn spec(&self, name: &str, input: &PartInput, mesh: MeshInfo) -> PartSpec {
        PartSpec {
            name: name.into(),
            role: if name == "disc" {
                PartRole::Disc
            } else if self.bodies.iter().any(|b| b.name == name) {
                PartRole::Body
            } else {
                PartRole::Pad
            },
            mesh,
            restraints: input.restraints.clone(),
            skew_restraints: input.skew_restraints.clone(),
            axis_restraints: input.axis_restraints.clone(),
            interface: self.interface,
            contact_set: input.contact_set.clone(),
            contact_face_set: input.contact_face_set.clone(),
            facing: input.facing.clone(),
            extra_surfaces: input.extra_surfaces.clone(),
            grid: self.grid,
            axis: self.axis,
            piston_set: input.piston_set.clone(),
            piston_footprints: input.piston_footprints.clone(),
            normal_direction: self.normal_direction,
            piston_direction: self.piston_direction,
            modes: match self.modes {
                ModeChoice::Fixed(n) => n,
                ModeChoice::Auto { .. } => self.max_modes,
            },
            ties: input.ties.clone(),
            supports: input.supports.clone(),
            springs: input.springs.clone(),
        }
    }
}

/// Reads the meshes, pairs each pad's contact points with the disc surface facing it and
/// reduces every part. `progress(part, stage)` is told each stage as it starts.
pub fn reduce_brake(
    inputs: &BrakeInputs,
    progress: &mut dyn FnMut(&str, Stage),
) -> Result<(ReducedModel, BrakeReport), ReduceError> {
    inputs.validate()?;
    progress("disc", Stage::Read);
    let disc = load_part_of(&inputs.disc.mesh, &inputs.disc.elset, &inputs.disc.units)?;
    let mut pads = Vec::with_capacity(inputs.pads.len());
    for pad in &inputs.pads {
        progress(&pad.name, Stage::Read);
        let p = &pad.part;
        pads.push(load_part_of(&p.mesh, &p.elset, &p.units)?);
    }
    for body in &inputs.bodies {
        progress(&body.name, Stage::Read);
        let p = &body.part;
        pads.push(load_part_of(&p.mesh, &p.elset, &p.units)?);
    }
    reduce_brake_loaded(inputs, disc, pads, progress)
}

/// [`reduce_brake`] on meshes already read, the pads in the order of `inputs.pads`, then the
/// bodies in the order of `inputs.bodies` (the mesh paths of `inputs` are not opened).
pub fn reduce_brake_loaded(
    inputs: &BrakeInputs,
    disc: LoadedPart,
    pads: Vec<LoadedPart>,
    progress: &mut dyn FnMut(&str, Stage),
) -> Result<(ReducedModel, BrakeReport), ReduceError> {
    reduce_brake_keeping(inputs, disc, pads, None, progress)
}

/// [`reduce_brake_loaded`], keeping finished reductions in the folder `keep` when another
/// part fails, and taking parts kept there by an earlier run instead of reducing them again
/// ([`kept_dir`]; the kept reductions' docs are in `brake/kept.rs`). `None`: nothing kept or
/// taken.
pub fn reduce_brake_keeping(
    inputs: &BrakeInputs,
    disc: LoadedPart,
    pads: Vec<LoadedPart>,
    keep: Option<&Path>,
    progress: &mut dyn FnMut(&str, Stage),
) -> Result<(ReducedModel, BrakeReport), ReduceError> {
    let t0 = Instant::now();
    inputs.validate()?;
    if pads.len() != inputs.pads.len() + inputs.bodies.len() {
        return Err(ReduceError::Options(format!(
            "{} pad and body meshes read for {} pads and {} bodies",
            pads.len(),
            inputs.pads.len(),
            inputs.bodies.len()
        )));
    }
    // Errors in a part name its mesh file.
    let in_mesh = |input: &PartInput| {
        let path = input.mesh.clone();
        move |e: ReduceError| ReduceError::InMesh {
            path,
            error: Box::new(e),
        }
    };
    let loaded: Vec<LoadedPart> = std::iter::once(disc).chain(pads).collect();
    let parts = inputs.parts();
    for (part, (name, input)) in loaded.iter().zip(&parts) {
        match inputs.bodies.iter().any(|b| b.name == *name) {
            true => check_body_sets(&part.mesh, input).map_err(in_mesh(input))?,
            false => check_sets(&part.mesh, name, input, inputs).map_err(in_mesh(input))?,
        }
    }
    // Every part held before any part is reduced (a pad left free no longer costs the disc's
    // reduction first).
    for (part, (name, input)) in loaded.iter().zip(&parts) {
        let spec = inputs.spec(name, input, part.info.clone());
        require_held_coupled(&part.mesh, &spec, &input.couplings).map_err(in_mesh(input))?;
    }
    // Ties between parts: checked and projected before any reduction.
    let tie_projections = {
        let meshes: Vec<(&str, &Mesh)> = parts
            .iter()
            .zip(&loaded)
            .map(|((name, _), part)| (*name, &part.mesh))
            .collect();
        let bodies: Vec<&str> = inputs.bodies.iter().map(|b| b.name.as_str()).collect();
        for t in &inputs.part_ties {
            for (part, set) in [&t.slave, &t.master] {
                let kept = parts.iter().any(|(name, input)| {
                    name == part && input.couplings.iter().any(|c| c.nodal && c.set == *set)
                });
                if !kept && parts.iter().any(|(name, _)| name == part) {
                    return Err(ReduceError::Options(format!(
                        "tie of {} on {} to {} on {}: part '{part}' does not keep the set {set} node by node (add it to the part's couplings with nodal = true)",
                        t.slave.1, t.slave.0, t.master.1, t.master.0
                    )));
                }
            }
        }
        crate::part_tie::project_ties(&inputs.part_ties, &meshes, &bodies)?
    };
    let mut pairs = Vec::new();
    let mut tolerance = 0.0;
    // Nodal interface: each pad's face nodes projected onto the disc face under it, before
    // any reduction (a pad that does not face the disc is refused here).
    let projections = if inputs.interface == InterfaceKind::Nodal {
        nodal_projections(inputs, &loaded).map_err(in_mesh(&inputs.disc))?
    } else {
        Vec::new()
    };
    // The disc's contact points, surface by surface in the order of its reduced points.
    let surfaces = inputs.disc.surfaces();
    let mut disc_points = Vec::with_capacity(surfaces.len());
    for surface in surfaces.iter().filter(|_| projections.is_empty()) {
        disc_points.push(
            contact_positions(&loaded[0].mesh, surface, inputs).map_err(in_mesh(&inputs.disc))?,
        );
    }
    for (pad, part) in inputs
        .pads
        .iter()
        .zip(&loaded[1..])
        .filter(|_| projections.is_empty())
    {
        let k = inputs
            .disc
            .surface_index(&pad.name, inputs.pads.len())
            .ok_or_else(|| ReduceError::Options(format!("no disc surface faces {}", pad.name)))?;
        let offset: usize = disc_points[..k].iter().map(Vec::len).sum();
        let pad_surface = pad.part.surfaces().swap_remove(0);
        let pad_points =
            contact_positions(&part.mesh, &pad_surface, inputs).map_err(in_mesh(&pad.part))?;
        let (p, t) = pair_contact_points(
            &disc_points[k],
            &pad_points,
            PairingTolerance::Relative(inputs.pairing_tolerance),
        )?;
        pairs.extend(p.into_iter().map(|mut c| {
            c.disc_point += offset;
            c
        }));
        tolerance = f64::max(tolerance, t);
    }
    let opts = inputs.reduce_options();
    // Parts an earlier run finished and kept, still standing for them.
    let taken: Vec<Option<ReducedPart>> = loaded
        .iter()
        .zip(&parts)
        .map(|(part, (name, input))| {
            keep.and_then(|dir| take_kept(dir, name, input, inputs, &part.info.sha256))
        })
        .collect();
    let (tx, rx) = mpsc::channel::<(usize, Stage)>();
    let slots: Vec<Mutex<Option<Reduced>>> = parts.iter().map(|_| Mutex::new(None)).collect();
    rayon::in_place_scope(|scope| {
        for (k, (((part, (name, input)), slot), taken)) in loaded
            .into_iter()
            .zip(&parts)
            .zip(&slots)
            .zip(taken)
            .enumerate()
        {
            let tx = tx.clone();
            let opts = &opts;
            scope.spawn(move |_| {
                let mut tell = |stage| {
                    // The receiver lives until every part is done.
                    let _ = tx.send((k, stage));
                };
                let reduced = match taken {
                    Some(kept) => Ok((kept, reused_report(name, part))),
                    None => reduce_loaded(inputs, name, input, part, opts, &mut tell),
                };
                *slot.lock().unwrap_or_else(PoisonError::into_inner) = Some(reduced);
            });
        }
        drop(tx);
        relay(&rx, &mut |k, stage| progress(parts[k].0, stage));
    });
    let mut results = Vec::with_capacity(parts.len());
    for (slot, (_, input)) in slots.into_iter().zip(&parts) {
        let reduced = slot.into_inner().unwrap_or_else(PoisonError::into_inner);
        results.push(
            reduced
                .ok_or_else(|| ReduceError::Invalid {
                    part: "brake".into(),
                    what: "a part's reduction ended without a result".into(),
                })
                .and_then(|r| r)
                .map_err(in_mesh(input)),
        );
    }
    let (done, failed): (Vec<_>, Vec<_>) = results.into_iter().partition(Result::is_ok);
    let done: Vec<(ReducedPart, PartReport)> = done.into_iter().flatten().collect();
    if let Some(Err(e)) = failed.into_iter().next() {
        // Keep what finished (and was not taken from the folder already) for the next run.
        if let Some(dir) = keep {
            let fresh: Vec<&ReducedPart> = done
                .iter()
                .filter(|(_, report)| !report.reused)
                .map(|(part, _)| part)
                .collect();
            if !fresh.is_empty() {
                keep_parts(dir, &fresh)?;
            }
        }
        return Err(e);
    }
    let (mut reduced_parts, reports): (Vec<_>, Vec<_>) = done.into_iter().unzip();
    if !projections.is_empty() {
        pairs = attach_projections(&mut reduced_parts, projections)?;
    }
    let connections = resolve_connections(inputs, &reduced_parts)?;
    let ties = crate::part_tie::resolve_ties(&inputs.part_ties, &tie_projections, &reduced_parts)?;
    let model = ReducedModel {
        tool_version: TOOL_VERSION.into(),
        parts: reduced_parts,
        connections,
        ties,
    };
    let read: Duration = reports.iter().map(|r| r.read_time).sum();
    let report = BrakeReport {
        parts: reports,
        pairs,
        pairing_tolerance: tolerance,
        total: t0.elapsed() + read,
    };
    Ok((model, report))
}

/// A reduced part and its report, or why not.
type Reduced = Result<(ReducedPart, PartReport), ReduceError>;

/// Reduces one read part with the brake's options.
fn reduce_loaded(
    inputs: &BrakeInputs,
    name: &str,
    input: &PartInput,
    loaded: LoadedPart,
    opts: &ReduceOptions,
    progress: &mut dyn FnMut(Stage),
) -> Reduced {
    let materials = MaterialTable::from_mesh(&loaded.mesh, &input.material_overrides)?;
    let spec = inputs.spec(name, input, loaded.info.clone());
    let (mut part, reduce) = reduce_part_coupled(
        &loaded.mesh,
        &materials,
        &spec,
        &input.couplings,
        opts,
        progress,
    )?;
    part.info.build = Some(inputs.record(input));
    let report = PartReport {
        name: name.into(),
        mesh: loaded.info,
        warnings: loaded.warnings,
        read_time: loaded.read_time,
        reduce,
        reused: false,
    };
    Ok((part, report))
}
