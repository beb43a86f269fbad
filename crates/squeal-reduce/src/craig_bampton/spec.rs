//! What to keep of one part and how it is held: the input of [`super::reduce_part`].

use crate::interface::Axis;
use crate::rom::{ContactSurface, InterfaceKind, MeshInfo, PartRole};
use squeal_fe::Restraint;
use squeal_fe::frames::AxisDirection;

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
    /// `n · u` on the node's three dofs, labelled [`crate::rom::DofLabel::Along`]); replaces
    /// `normal_direction`.
    pub piston_direction: Option<[f64; 3]>,
    /// Fixed-interface modes kept.
    pub modes: usize,
    /// Tied interfaces inside the part (its meshes merged), eliminated exactly
    /// ([`crate::tie`]).
    pub ties: Vec<crate::tie::Tie>,
    /// Springs to ground on node sets, added to `K` before the reduction ([`crate::tie`]).
    pub supports: Vec<crate::tie::Support>,
    /// Springs between node sets of the part or to ground, in global or local axes, added to
    /// `K` before the reduction ([`crate::springs`]).
    pub springs: Vec<crate::springs::Spring>,
}

impl PartSpec {
    /// A part with only its name, role, mesh and kept modes: held by nothing, a node
    /// interface on no contact set, the paper's 3 × 3 patch grid, the z axis as disc axis and
    /// contact normal, no pistons, ties, supports or springs. Set the rest with struct update
    /// syntax (`PartSpec { restraints, ..PartSpec::new(..) }`).
    pub fn new(name: &str, role: PartRole, mesh: MeshInfo, modes: usize) -> Self {
        Self {
            name: name.into(),
            role,
            mesh,
            restraints: Vec::new(),
            skew_restraints: Vec::new(),
            axis_restraints: Vec::new(),
            interface: InterfaceKind::Node,
            contact_set: String::new(),
            contact_face_set: String::new(),
            facing: None,
            extra_surfaces: Vec::new(),
            grid: [3, 3],
            axis: Axis::default(),
            piston_set: None,
            piston_footprints: Vec::new(),
            normal_direction: 2,
            piston_direction: None,
            modes,
            ties: Vec::new(),
            supports: Vec::new(),
            springs: Vec::new(),
        }
    }

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
