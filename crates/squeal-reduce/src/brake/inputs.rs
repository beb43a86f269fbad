//! The inputs of a brake's reduction ([`super::reduce_brake`]): which parts, their meshes,
//! sets, restraints, interface and mode choice, and the options they become.

use super::bodies::validate_bodies;
use super::load::backend_name;
use super::{
    DEFAULT_AUTO_FACTOR, DEFAULT_MAX_MODES, DEFAULT_PAIRING_TOLERANCE, coordinate_axis,
    selection_name,
};
use crate::craig_bampton::{PartSpec, ReduceError, ReduceOptions};
use crate::interface::Axis;
use crate::rom::{BuildRecord, ContactSurface, InterfaceKind, MeshInfo, PartRole};
use faer::Par;
use serde::{Deserialize, Serialize};
use squeal_eigs::{Backend, EigOptions};
use squeal_element::geometry::unit;
use squeal_fe::frames::AxisDirection;
use squeal_fe::{ElasticMaterial, NodeSelection, Restraint};
use squeal_mesh::units::UnitSystem;
use std::path::PathBuf;

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
    /// The unit system the mesh file is written in; [`load_part`](super::load_part)'s caller converts it to SI
    /// ([`reduce_brake`](super::reduce_brake) does), and the `.rom` records it.
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

/// Everything [`reduce_brake`](super::reduce_brake) needs.
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

    pub(super) fn reduce_options(&self) -> ReduceOptions {
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

    /// The [`PartSpec`] [`reduce_brake`](super::reduce_brake) reduces part `input`, named `name`, with (read from the
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
