//! The pad's contact points of the nodal interface: the nodes of its 6-node triangles that
//! carry a share of a uniform pressure, and the Gauss points of its 8-node quadrilaterals.
//!
//! # Why Gauss points on 8-node faces
//!
//! The contact springs stand for a bed of stiffness `κ` per unit area under the pad: what the
//! brake's modes see of it is `½ ∫ κ δ² dA` over the pad face's displacement `δ`, and what
//! the static equilibrium sees is the bed's resultant and moments. A rule of contact points
//! `Σ_q A_q f(x_q)` that is exact for quadratic `f` gives a rigid pad's bounce and rocking
//! stiffness on its springs (`κ ∫ dA`, `κ ∫ (x − x̄)² dA`) and a uniform closure's load exactly,
//! on any mesh (module [`super::nodal`], "Tributary areas of the contact points").
//!
//! On a 6-node triangle the edge-midpoint rule does this with the face's own midside nodes
//! as points ([`super::nodal::contact_face_nodes`]). On the 8-node serendipity quadrilateral
//! no rule on its nodes does with positive weights: the consistent loads of a uniform
//! pressure are `−A/12` at the corners (a negative spring), and the lumped sub-cell areas
//! (`A/24` at corners, `5A/24` at midside nodes) are exact for linear functions only, an
//! `O(h²)` error in the rocking stiffness (tests: +75 % on a pad one element long, +18.75 %
//! on two, +4.69 % on four).
//!
//! So on an 8-node face the contact points are the face's Gauss points, as in
//! segment-to-segment and Gauss-point-to-surface contact, where the contact integrals are
//! evaluated at the quadrature points of the slave (here the pad's) faces (Simo, Wriggers &
//! Taylor, *A perturbed Lagrangian formulation for the finite element solution of contact
//! problems*, CMAME 50, 1985; Wriggers, *Computational Contact Mechanics*, 2nd ed., Springer
//! 2006, Ch. 9); Ansys' surface-to-surface contact elements detect contact at Gauss points by
//! default, two on the quadratic edge of CONTA172 and 2 × 2 on the quadrilateral of CONTA173
//! (*Mechanical APDL Theory Reference*, Release 18.2, Sec. 13.172 and 13.173). Point `q` at
//! reference coordinates `(s_q, t_q)` has
//!
//! - position `x_q = Σ_a N_a(s_q, t_q) x_a` and pad motion `u_q = Σ_a N_a(s_q, t_q) u_a`: the
//!   pair's pad side is a combination of the face's eight nodes, as its disc side is of the
//!   disc face's nodes ([`super::nodal`]), so all eight stay boundary dofs of the pad's
//!   reduction;
//! - area `A_q = w_q |X_s × X_t|(s_q, t_q)` and normal `X_s × X_t / |…|` there;
//! - an initial gap and a disc side measured by projecting `x_q` onto the disc face.
//!
//! The rule is Gauss–Legendre ([`QUAD_RULE`]: 2 points in each direction): `n` points
//! integrate polynomials of degree `2n − 1` in each of `s`, `t` exactly (Zienkiewicz, Taylor
//! & Zhu, *The Finite Element Method: Its Basis and Fundamentals*, 6th ed., 2005, Ch. 6,
//! numerical integration).
//! 2 × 2 is the lowest order exact for quadratics (degree 3 in each variable; one point is
//! exact for linear functions only): on a parallelogram face, where `x(s, t)` is affine,
//! `f(x)` quadratic is quadratic in `(s, t)` and `|X_s × X_t|` constant, so a rigid pad's
//! bounce and rocking stiffness and a uniform closure's resultant and moments are exact, as
//! the triangles' edge-midpoint rule makes them. Its weights are positive (`A/4` each on a
//! parallelogram). It is not exact for the bed's energy of the face's own deformation
//! (`δ²` of a serendipity field has degree 4 in each variable; 3 × 3 is), but that is the
//! pad's stiffness against a short wave of its face, which the pad's own elements carry;
//! four pairs per face against about three face nodes per face (a hexahedral face mesh has
//! one corner and two midside nodes per face) keep the number of pairs near the nodes'
//! where 3 × 3 would triple it (every pair is evaluated at every AFT sample of the nonlinear
//! analysis).

use super::face::{self, Shape};
use super::nodal::{FaceNode, contact_face_nodes, face_nodes};
use super::{InterfaceError, face_triangles, norm, unit};
use squeal_mesh::Mesh;
use std::collections::BTreeSet;

/// The rule of the pads' 8-node faces (module docs): 2 × 2 Gauss points.
pub const QUAD_RULE: QuadRule = QuadRule::Gauss2;

/// How the contact points of a pad's 8-node faces are placed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QuadRule {
    /// At the face's nodes, with the lumped sub-cell areas of [`face_nodes`] (exact for
    /// linear functions only; the rule before 2026-11-28, kept for comparison).
    Lumped,
    /// At the face's 2 × 2 Gauss points (module docs): exact for degree 3 in each of `s`, `t`.
    Gauss2,
    /// At the face's 3 × 3 Gauss points: exact for degree 5 in each of `s`, `t`.
    Gauss3,
}

/// A contact point of a pad's friction face.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactPoint {
    /// Position (m).
    pub position: [f64; 3],
    /// Area it stands for (m²).
    pub area: f64,
    /// Unit outward normal of the pad's face there.
    pub normal: [f64; 3],
    /// `(node, weight)`: the point's motion `Σ w u_node`; one node with weight 1 for a face
    /// node, the face's eight shape functions for a Gauss point.
    pub nodes: Vec<(u32, f64)>,
}

impl ContactPoint {
    /// The mesh node the point is, when it is one.
    pub fn node(&self) -> Option<u32> {
        match self.nodes.as_slice() {
            [(n, w)] if *w == 1.0 => Some(*n),
            _ => None,
        }
    }

    fn at_node(mesh: &Mesh, n: FaceNode) -> Self {
        Self {
            position: mesh.nodes[n.node as usize],
            area: n.area,
            normal: n.normal,
            nodes: vec![(n.node, 1.0)],
        }
    }
}

/// The Gauss–Legendre points and weights on `[−1, 1]` of the rule.
fn gauss_legendre(rule: QuadRule) -> Vec<(f64, f64)> {
    match rule {
        QuadRule::Lumped => Vec::new(),
        QuadRule::Gauss2 => {
            let a = 1.0 / 3.0f64.sqrt();
            vec![(-a, 1.0), (a, 1.0)]
        }
        QuadRule::Gauss3 => {
            let b = 0.6f64.sqrt();
            vec![(-b, 5.0 / 9.0), (0.0, 8.0 / 9.0), (b, 5.0 / 9.0)]
        }
    }
}

/// The pad's contact points on `face_set` with the default rule ([`QUAD_RULE`]).
pub fn contact_points(mesh: &Mesh, face_set: &str) -> Result<Vec<ContactPoint>, InterfaceError> {
    contact_points_with(mesh, face_set, QUAD_RULE)
}

/// The pad's contact points on `face_set`: first the face nodes that carry a share of a
/// uniform pressure on its 6-node triangles (the midside nodes, in node order, exactly as
/// [`contact_face_nodes`] gives them on a face of triangles only), then, with
/// [`QuadRule::Gauss2`] or [`QuadRule::Gauss3`], the Gauss points of its 8-node quadrilaterals face by face (in the
/// order of [`super::boundary_faces_of`]), `s` outer, `t` inner. With [`QuadRule::Lumped`]
/// the quadrilaterals' nodes carry their lumped areas instead ([`contact_face_nodes`]).
pub fn contact_points_with(
    mesh: &Mesh,
    face_set: &str,
    rule: QuadRule,
) -> Result<Vec<ContactPoint>, InterfaceError> {
    if rule == QuadRule::Lumped {
        return Ok(contact_face_nodes(mesh, face_set)?
            .into_iter()
            .map(|n| ContactPoint::at_node(mesh, n))
            .collect());
    }
    let (_, faces) = face_triangles(mesh, face_set)?;
    let line = gauss_legendre(rule);
    // The triangles' midside nodes: their edge-midpoint areas, without the quadrilaterals'.
    let mut triangle_nodes = BTreeSet::new();
    for f in faces.iter().filter(|f| f.shape == Shape::Tri6) {
        triangle_nodes.extend(f.nodes[3..6].iter().copied());
    }
    let mut out: Vec<ContactPoint> = Vec::new();
    if !triangle_nodes.is_empty() {
        let areas = triangle_areas(mesh, &faces);
        for n in face_nodes(mesh, face_set)? {
            if let Some(&a) = areas.get(&n.node).filter(|a| **a > 0.0) {
                out.push(ContactPoint::at_node(mesh, FaceNode { area: a, ..n }));
            }
        }
    }
    for f in faces.iter().filter(|f| f.shape == Shape::Quad8) {
        let x = f.coords(mesh);
        for &(s, ws) in &line {
            for &(t, wt) in &line {
                let (n, point, dn) = face::map_point(Shape::Quad8, &x, [s, t]);
                out.push(ContactPoint {
                    position: point,
                    area: ws * wt * norm(dn),
                    normal: unit(dn).unwrap_or([0.0; 3]),
                    nodes: f.nodes.iter().copied().zip(n).collect(),
                });
            }
        }
    }
    Ok(out)
}

/// The edge-midpoint areas of the 6-node triangles among `faces`, by midside node (module
/// [`super::nodal`]; the same sums in the same order as [`contact_face_nodes`]).
fn triangle_areas(
    mesh: &Mesh,
    faces: &[face::SurfaceFace],
) -> std::collections::BTreeMap<u32, f64> {
    let mut area = std::collections::BTreeMap::new();
    for f in faces.iter().filter(|f| f.shape == Shape::Tri6) {
        let x = f.coords(mesh);
        for k in 3..6 {
            let (_, _, dn) = face::map_point(f.shape, &x, f.shape.reference()[k]);
            *area.entry(f.nodes[k]).or_insert(0.0) += norm(dn) / 6.0;
        }
    }
    area
}

/// The nodes of `points` that are not contact points themselves but move some (the nodes of
/// the 8-node faces under Gauss points), ascending: the pad keeps them as boundary points.
pub fn combined_nodes(points: &[ContactPoint]) -> Vec<u32> {
    let own: BTreeSet<u32> = points.iter().filter_map(ContactPoint::node).collect();
    let mut out = BTreeSet::new();
    for p in points.iter().filter(|p| p.node().is_none()) {
        out.extend(p.nodes.iter().map(|n| n.0).filter(|n| !own.contains(n)));
    }
    out.into_iter().collect()
}
