//! The nodal interface: every node of the pad's friction face is a contact point, paired with
//! the point of the disc face it projects onto (on 8-node faces their Gauss points instead:
//! [`super::quad_contact`]).
//!
//! This is node-to-surface contact (Wriggers, *Computational Contact Mechanics*, 2nd ed.,
//! Springer 2006, Sec. 4.1 and 9.1; Laursen, *Computational Contact and Impact Mechanics*,
//! 2002, Ch. 5): the pad is the slave side, its face nodes `x_k`; the disc is the master
//! surface, its boundary faces (6-node triangles and 8-node quadrilaterals)
//! `X(s, t) = Σ_a N_a(s, t) X_a` over the disc's
//! contact face. Each pad node is paired with its closest-point projection `y_k = X(s̄, t̄)`,
//!
//! `(x_k − X(s̄, t̄)) · ∂X/∂s = (x_k − X(s̄, t̄)) · ∂X/∂t = 0`,
//!
//! so that `x_k − y_k` lies along the disc face's normal at `y_k` (Wriggers' eq 4.3). The
//! disc's side of the pair moves as the face does there, `r_k = Σ_a N_a(s̄, t̄) u_a`: a row
//! `r = C u` over the disc face's nodes, like a patch's row of [`super::patches`] but with the
//! shape functions at one point instead of their mean over a patch. The projection is made
//! once, on the undeformed meshes: the small-sliding form of the method, which is what a
//! linearized stability analysis about a sliding equilibrium uses.
//!
//! # Why node-to-surface and not mortar
//!
//! Mortar methods (Puso & Laursen 2004; Wriggers Ch. 9.2) tie the faces in a weak, integral
//! sense and pass the contact patch test for any pair of meshes, where node-to-surface with
//! one pass does not exactly. Here the pairs are penalty springs with a stiffness per unit
//! area (eq 8), and what the brake needs is that each spring stands for its share of the
//! pad's face and reads the disc's motion where it presses. Node-to-surface gives that with
//! one projection per pad node and no integration over the overlap of two non-matching
//! meshes (a clipping of every pad triangle against every disc triangle under it); the
//! springs' resultant of a uniform closure is exact (the areas partition the face, below)
//! and the pressure's distribution converges with the pad's mesh. Its known defect, that a
//! uniform pressure is not transmitted exactly node by node on non-matching meshes, is an
//! error of the pad's element size, the same order as that of the meshes themselves.
//!
//! # Where the disc's side is kept
//!
//! The disc is reduced with every node of its contact face as a boundary point
//! ([`crate::rom::PointRole::Face`]), and each projected point's motion `Σ_a N_a u_a` is formed
//! from those retained dofs when the brake is assembled. Keeping the projected points
//! themselves as the disc's boundary coordinates (constraint rows `C u = r` on the disc's
//! interior) would fail whenever the pad's face has more nodes than the disc's face under it
//! (the bundled medium meshes: 652 against 618): `3 × 652` rows on `3 × 618` dofs cannot be
//! independent. With the face nodes kept, the reduced disc holds `Σ_a N_a u_a` exactly.
//!
//! # A pad node beyond the disc face
//!
//! The disc face's outline and the pad's need not agree (a face chosen as the disc's
//! triangles under the pad has a ragged outline). A pad node whose projection falls outside
//! the face's triangles is paired with the nearest point of the face (on its boundary): the
//! closest point over all the face's triangles is the constrained minimum of the distance,
//! which is the interior projection where there is one. How far outside it was is kept
//! ([`crate::rom::Projected::outside`]). No tolerance enters the pairing; a pad that does not
//! face the disc is refused ([`check_facing`]).
//!
//! # Tributary areas
//!
//! Each pad node stands for a share `A_k` of the pad's face: its spring is `κ A_k` (eq 8's
//! stiffness per unit area). The consistent nodal areas `∫ N_k dA` are the nodal loads of a
//! uniform unit pressure, and for quadratic faces they are not all positive:
//!
//! - on a flat 6-node triangle of area `A`, `∫ N_k dA = 0` at the corners and `A/3` at the
//!   midside nodes (`∫ L_i (2 L_i − 1) dA = 2·A/6 − A/3 = 0`, `∫ 4 L_a L_b dA = 4·A/12`);
//! - on a flat 8-node quadrilateral (a parallelogram of area `A`, `dA = A/4 ds dt`),
//!   `∫ N_k dA = −A/12` at the corners and `A/3` at the midside nodes
//!   (`¼∫∫ ¼(1+s)(1+t)(s+t−1) ds dt·A/4·4 = −A/12`, `¼∫∫ ½(1−s²)(1+t) ds dt·A = A/3`, and
//!   `4·(−A/12) + 4·A/3 = A`).
//!
//! # Tributary areas of the contact points
//!
//! The springs stand for a bed of stiffness `κ` per unit area under the pad, and what the
//! brake's modes see of it is the bed's energy `½ ∫ κ δ² dA` over the pad face's displacement
//! field `δ` (quadratic on each face), and, at the static equilibrium, the nodal loads of the
//! clamp pressure. Nodal springs `κ A_k` replace the integral by the nodal rule
//! `Σ_k A_k f(x_k)`:
//!
//! - on a 6-node triangle, the contact points' areas ([`contact_face_nodes`]) are the
//!   edge-midpoint rule, `|X_s × X_t|(m_e)/6` at each midside node `m_e` (the reference
//!   triangle's area ½ in three equal weights) and nothing at the corners. On a flat triangle
//!   with straight edges these are the consistent nodal loads of a uniform pressure, `∫ N_k dA`
//!   (0 at corners, `A/3` at midside nodes, above), and the rule is exact for polynomials of
//!   degree 2 (the triangle's three-point rule at its edge midpoints, weights 1/3 of the area:
//!   Zienkiewicz, Taylor & Zhu, *The Finite Element Method: Its Basis and Fundamentals*, 6th
//!   ed., 2005, the table of integration rules for triangles): a flat pad's
//!   area, centroid and second moments, that is a rigid pad's bounce and rocking stiffness on
//!   its springs, are those of the continuous bed on any mesh, and a uniform closure loads the
//!   pad with exactly a uniform pressure. The area element of a flat face with quadratic
//!   edges is a polynomial of degree 2, so the areas still sum to the face's area to
//!   round-off there; on a doubly curved face the sum is the rule's approximation of the area.
//!   A corner with no area is not a contact point (no pair: a pair without a spring would
//!   carry nothing, and laws that need a positive stiffness, such as DLFT's, would refuse it):
//!   the element's midside nodes carry the pressure, as a finite-element code's consistent
//!   pressure loads do, and the corners are interior nodes of the pad's reduction.
//! - The lumped sub-cell areas of [`face_nodes`] (each 6-node triangle cut at its edge
//!   midpoints into four triangles whose areas go a third to each of their nodes: `A/12` at a
//!   corner, `A/4` at a midside node) are positive everywhere but exact for linear functions
//!   only. They were the contact areas until 2026-11-28 and over-state a pad's rocking
//!   stiffness by `O(h²)`: by 50 % on a pad one element long, 12.5 % two elements long (the
//!   tests), 13.2 % on the bundled coarse ventilated pad's radial second moment; and they load
//!   the corners with `A/12` where a uniform pressure loads them with nothing, so a uniform
//!   closure bends each element (at the coarse ventilated brake's equilibrium the corners
//!   1.05 µm less closed than a smooth fit of the closure and the midside nodes 0.51 µm more,
//!   of 22.5 µm; 0.19 and 0.09 µm with the edge-midpoint rule). This error was about a third
//!   of the coarse ventilated brake's μ0 error (docs/reduction.md, "Why the ventilated
//!   brake's μ0 moved with the mesh"). [`face_nodes`] is kept for what needs every node with a
//!   positive share (the disc's face points, springs and ties spread over a face).
//! - On an 8-node quadrilateral `∫ N_k dA` is `−A/12` at the corners (a negative spring, a
//!   softening foundation), and no nodal rule on its eight nodes with positive weights is
//!   exact for quadratics (symmetric weights would need `−A/12` at the corners again). Its
//!   lumped sub-cell areas below are exact for linear functions only (a rigid hex20 pad's
//!   rocking stiffness +75 % on one element, +18.75 % on two, the `O(h²)` error above), so
//!   since 2026-11-28 a pad's 8-node faces carry their contact at their 2 × 2 Gauss points
//!   instead, each a combination of the face's eight nodes, exact for quadratics with
//!   positive weights ([`super::quad_contact`]); [`contact_face_nodes`] keeps the lumped
//!   areas there for comparison.
//!
//! The lumped sub-cell areas ([`face_nodes`]) are cut at each face's edge midpoints
//! ([`super::face::Shape::subcells`]), each sub-cell shared equally by its nodes:
//!
//! - a 6-node triangle splits into four triangles (in reference coordinates: its own
//!   sub-triangles); each node takes a third of each sub-triangle it is a corner of: `A/12` at
//!   a corner and `A/4` at a midside node of a flat triangle (`3·A/12 + 3·A/4 = A`);
//! - an 8-node quadrilateral splits into four corner triangles `[v_k, m_k, m_{k−1}]` (each
//!   `A/8` of a parallelogram) and the central square through its four midside nodes (`A/2`);
//!   each corner triangle's area goes a third to each of its three nodes, the central square's
//!   a quarter to each midside node: `A/24` at a corner and `2·A/24 + A/8 = 5A/24` at a
//!   midside node of a parallelogram (`4·A/24 + 4·5A/24 = A`).
//!
//! They are positive, and they partition the face: `Σ_k A_k` is the face's area to round-off
//! (each sub-cell's area integrated by the degree-4 rule, exact on a flat face of either
//! shape: the area element of a flat serendipity map is a polynomial of degree ≤ 4). A node's
//! normal is the area-weighted mean outward normal over the same sub-cells.
//!
//! # Quadrilateral faces
//!
//! A disc or pad of hexahedra (or the quadrilateral sides of wedges and pyramids) has 8-node
//! faces; the projection onto them is the same closest-point problem on the serendipity map
//! ([`super::face`]): Gauss–Newton from the square's centre for the interior stationary
//! point, else the closest point of its four quadratic edges. A surface may mix both shapes
//! (a wedge-and-hexahedron disc).

use super::face::{self, Shape, SurfaceFace};
use super::quad_contact::{ContactPoint, contact_points};
use super::{DUNAVANT4, InterfaceError, dot, face_triangles, norm, sub, unit};
use squeal_mesh::Mesh;
use std::collections::BTreeMap;

/// Shape-function weights below this are dropped from a projected point's row (the others
/// are scaled to sum to 1): a pad node on a disc node gets that node alone instead of six
/// entries, five of them round-off.
const NEGLIGIBLE_WEIGHT: f64 = 1e-12;

/// A projection inside a face is accepted when its reference coordinates are not beyond the
/// domain by more than this (round-off of a point on an edge).
const INSIDE_TOLERANCE: f64 = 1e-10;

/// Less than this share of the pad's face (by area) projecting inside the disc face means
/// the pad does not face it ([`check_facing`]).
pub const MIN_FACING_SHARE: f64 = 0.5;

/// A node of a contact face with its lumped tributary area and normal.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceNode {
    /// Node index in the mesh.
    pub node: u32,
    /// Tributary area (m²): its share of each sub-cell it is a node of (module docs).
    pub area: f64,
    /// Unit outward normal: the area-weighted mean over those sub-cells.
    pub normal: [f64; 3],
}

/// The nodes of the boundary faces of `face_set`, in node order, with their lumped
/// tributary areas and normals (module docs).
pub fn face_nodes(mesh: &Mesh, face_set: &str) -> Result<Vec<FaceNode>, InterfaceError> {
    let (_, faces) = face_triangles(mesh, face_set)?;
    let mut acc: BTreeMap<u32, (f64, [f64; 3])> = BTreeMap::new();
    for f in &faces {
        let x = f.coords(mesh);
        for (cell, sharing) in f.shape.subcells() {
            let (area, normal) = subtriangle_integrals(f.shape, &x, cell);
            let parts = sharing.len() as f64;
            for k in sharing {
                let e = acc.entry(f.nodes[k]).or_insert((0.0, [0.0; 3]));
                e.0 += area / parts;
                for d in 0..3 {
                    e.1[d] += normal[d] / parts;
                }
            }
        }
    }
    Ok(acc
        .into_iter()
        .map(|(node, (area, normal))| FaceNode {
            node,
            area,
            normal: unit(normal).unwrap_or([0.0; 3]),
        })
        .collect())
}

/// The nodes of the boundary faces of `face_set` that carry a share of a uniform pressure,
/// in node order, with that share as their area and [`face_nodes`]' normals: on a 6-node
/// triangle the edge-midpoint rule, `|X_s × X_t|(m_e) / 6` at each midside node and nothing
/// at the corners (module docs, "Tributary areas of the contact points"); on an 8-node
/// quadrilateral the lumped sub-cell areas of [`face_nodes`]. A node with no share (a corner
/// of 6-node triangles only) is not a contact point.
pub fn contact_face_nodes(mesh: &Mesh, face_set: &str) -> Result<Vec<FaceNode>, InterfaceError> {
    let (_, faces) = face_triangles(mesh, face_set)?;
    let mut area: BTreeMap<u32, f64> = BTreeMap::new();
    for f in &faces {
        let x = f.coords(mesh);
        match f.shape {
            Shape::Tri6 => {
                for k in 3..6 {
                    let (_, _, dn) = face::map_point(f.shape, &x, f.shape.reference()[k]);
                    *area.entry(f.nodes[k]).or_insert(0.0) += norm(dn) / 6.0;
                }
            }
            Shape::Quad8 => {
                for (cell, sharing) in f.shape.subcells() {
                    let (a, _) = subtriangle_integrals(f.shape, &x, cell);
                    for k in &sharing {
                        *area.entry(f.nodes[*k]).or_insert(0.0) += a / sharing.len() as f64;
                    }
                }
            }
        }
    }
    Ok(face_nodes(mesh, face_set)?
        .into_iter()
        .filter_map(|n| {
            let a = area.get(&n.node).copied().filter(|a| *a > 0.0)?;
            Some(FaceNode { area: a, ..n })
        })
        .collect())
}

/// `∫ dA` and `∫ n dA` over the part of the face `x` whose reference coordinates form the
/// triangle `q` (degree-4 rule mapped onto it).
fn subtriangle_integrals(shape: Shape, x: &[[f64; 3]; 8], q: [[f64; 2]; 3]) -> (f64, [f64; 3]) {
    let e1 = [q[1][0] - q[0][0], q[1][1] - q[0][1]];
    let e2 = [q[2][0] - q[0][0], q[2][1] - q[0][1]];
    let jac = (e1[0] * e2[1] - e1[1] * e2[0]).abs();
    let (mut area, mut normal) = (0.0, [0.0; 3]);
    for (a, b, w) in DUNAVANT4 {
        let st = [0, 1].map(|i| q[0][i] + a * e1[i] + b * e2[i]);
        let (_, _, dn) = face::map_point(shape, x, st);
        let weight = 0.5 * w * jac;
        area += weight * norm(dn);
        for d in 0..3 {
            normal[d] += weight * dn[d];
        }
    }
    (area, normal)
}

/// A contact face ready for closest-point queries: its faces, their nodes' coordinates and a
/// box around each (holding the curved face: the box of its Bézier control points).
pub struct Surface {
    faces: Vec<SurfaceFace>,
    coords: Vec<[[f64; 3]; 8]>,
    boxes: Vec<[[f64; 3]; 2]>,
}

/// A point projected onto a [`Surface`].
#[derive(Clone, Debug, PartialEq)]
pub struct Projection {
    /// The projected point `X(s̄, t̄)` (m).
    pub point: [f64; 3],
    /// The face's unit outward normal there.
    pub normal: [f64; 3],
    /// `(node, weight)`: the shape functions at the projected point (weights below
    /// 1e-12 dropped, the rest summing to 1), by node.
    pub weights: Vec<(u32, f64)>,
    /// Distance from the projected point to the given point (m).
    pub distance: f64,
    /// `n · (x − X)`: the gap along the face's normal (m), positive off the face.
    pub gap: f64,
    /// 0 when the projection falls inside the face's faces; else the length of `x − X`
    /// in the face's tangent plane at `X`: how far beyond the face's boundary `x` lies (m).
    pub outside: f64,
}

impl Surface {
    /// The boundary faces of `face_set`.
    pub fn new(mesh: &Mesh, face_set: &str) -> Result<Self, InterfaceError> {
        let (_, faces) = face_triangles(mesh, face_set)?;
        let coords: Vec<[[f64; 3]; 8]> = faces.iter().map(|f| f.coords(mesh)).collect();
        let boxes = faces
            .iter()
            .zip(&coords)
            .map(|(f, x)| bezier_box(f.shape, x))
            .collect();
        Ok(Self {
            faces,
            coords,
            boxes,
        })
    }

    /// The closest point of the face to `x` (module docs): over the faces in order of the
    /// distance to their boxes, until a box lies farther than the best point found; ties go
    /// to the face first in that order (then by index), so the result does not depend on
    /// anything but the meshes.
    pub fn project(&self, x: [f64; 3]) -> Projection {
        let mut order: Vec<(f64, usize)> = self
            .boxes
            .iter()
            .enumerate()
            .map(|(i, b)| (box_distance(b, x), i))
            .collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut best: Option<(f64, usize, [f64; 2], bool)> = None;
        for (lower, i) in order {
            if best.is_some_and(|b| lower > b.0) {
                break;
            }
            let shape = self.faces[i].shape;
            let (st, inside) = closest_on_face(shape, &self.coords[i], x);
            let (_, xp, _) = face::map_point(shape, &self.coords[i], st);
            let d = norm(sub(x, xp));
            if best.is_none_or(|b| d < b.0) {
                best = Some((d, i, st, inside));
            }
        }
        // A surface has at least one face (`face_triangles` refuses an empty one).
        let (distance, i, st, inside) = best.unwrap_or((f64::INFINITY, 0, [0.0; 2], false));
        let shape = self.faces[i].shape;
        let (n, point, dn) = face::map_point(shape, &self.coords[i], st);
        let normal = unit(dn).unwrap_or([0.0; 3]);
        let gap = dot(normal, sub(x, point));
        let outside = if inside {
            0.0
        } else {
            (distance * distance - gap * gap).max(0.0).sqrt()
        };
        Projection {
            point,
            normal,
            weights: row(self.faces[i].nodes(), &n),
            distance,
            gap,
            outside,
        }
    }
}

/// The kept shape-function weights of one point, by node (module docs).
fn row(nodes: &[u32], n: &[f64; 8]) -> Vec<(u32, f64)> {
    let mut kept: Vec<(u32, f64)> = nodes
        .iter()
        .zip(n)
        .filter(|(_, w)| w.abs() > NEGLIGIBLE_WEIGHT)
        .map(|(&k, &w)| (k, w))
        .collect();
    let sum: f64 = kept.iter().map(|k| k.1).sum();
    for k in &mut kept {
        k.1 /= sum;
    }
    kept.sort_by_key(|k| k.0);
    kept
}

/// A box holding the curved face: of its corners and, for each edge `a, b` with midside
/// node `m`, the quadratic edge's Bézier control point `2 m − (a + b)/2` (by the
/// convex-hull property it holds the edge), widened for a quadrilateral by its interior's
/// bulge beyond its edges.
///
/// A 6-node triangle is a quadratic Bézier triangle whose control points are these, so the
/// box holds it. The serendipity quadrilateral's interior is the bilinear blend of its edges
/// (Coons' patch) less the bilinear interpolant of its corners; the blend lies within the
/// boxes of its edges plus the difference between its edges' and its corners' bilinear parts,
/// which is bounded by the largest edge bulge `|2 m − (a + b)|/2`: the box is widened by that
/// on every side.
fn bezier_box(shape: Shape, x: &[[f64; 3]; 8]) -> [[f64; 3]; 2] {
    let corners = match shape {
        Shape::Tri6 => 3,
        Shape::Quad8 => 4,
    };
    let mut pts: Vec<[f64; 3]> = x[..corners].to_vec();
    let mut bulge: f64 = 0.0;
    for k in 0..corners {
        let (a, b, m) = (k, (k + 1) % corners, corners + k);
        let p: [f64; 3] = std::array::from_fn(|d| 2.0 * x[m][d] - 0.5 * (x[a][d] + x[b][d]));
        bulge = bulge.max(norm(sub(p, x[m])));
        pts.push(p);
    }
    let widen = if shape == Shape::Quad8 { bulge } else { 0.0 };
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in pts {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d] - widen);
            hi[d] = hi[d].max(p[d] + widen);
        }
    }
    [lo, hi]
}

/// Distance from `x` to the box `b` (0 inside).
fn box_distance(b: &[[f64; 3]; 2], x: [f64; 3]) -> f64 {
    let mut s = 0.0;
    for d in 0..3 {
        let e = (b[0][d] - x[d]).max(x[d] - b[1][d]).max(0.0);
        s += e * e;
    }
    s.sqrt()
}

/// The reference coordinates of the point of the face `x` closest to `p`, and whether it is
/// an interior stationary point (else the closest point of its edges).
fn closest_on_face(shape: Shape, x: &[[f64; 3]; 8], p: [f64; 3]) -> ([f64; 2], bool) {
    if let Some(st) = interior_projection(shape, x, p) {
        return (st, true);
    }
    // The constrained minimum lies on an edge: the best of the edges' minima.
    let mut best = ([0.0; 2], f64::INFINITY);
    for (a, b) in shape.edges() {
        let st = closest_on_edge(shape, x, p, a, b);
        let (_, xp, _) = face::map_point(shape, x, st);
        let d = norm(sub(p, xp));
        if d < best.1 {
            best = (st, d);
        }
    }
    (best.0, false)
}

/// Gauss–Newton on the stationarity of `|p − X(s, t)|²` from the reference domain's centre:
/// the interior projection, if it converges inside the face. On a flat triangle with straight
/// edges `X` is affine and one step lands on it; on a quadrilateral (bilinear at least) it
/// converges quadratically near a point where `x − X` is small against the face's curvature
/// radius.
fn interior_projection(shape: Shape, x: &[[f64; 3]; 8], p: [f64; 3]) -> Option<[f64; 2]> {
    let mut st = shape.centre();
    for _ in 0..30 {
        let (_, [xp, xs, xt]) = face::tangents(shape, x, st);
        let r = sub(p, xp);
        let (a, b, c) = (dot(xs, xs), dot(xs, xt), dot(xt, xt));
        let (f, g) = (dot(xs, r), dot(xt, r));
        let det = a * c - b * b;
        if det.is_nan() || det <= 0.0 {
            return None;
        }
        let step = [(c * f - b * g) / det, (a * g - b * f) / det];
        st = [st[0] + step[0], st[1] + step[1]];
        st = shape.keep(st);
        if step[0].abs().max(step[1].abs()) <= 1e-14 {
            let inside = shape.contains(st, INSIDE_TOLERANCE);
            // A point on an edge within round-off is put on it.
            return inside.then(|| shape.clamp(st));
        }
    }
    None
}

/// The point of the face's edge from reference point `a` to `b` closest to `p`: Newton's
/// method on `(X(τ) − p) · X'(τ) = 0` along the (quadratic) edge, kept in `[0, 1]`, compared
/// with the edge's ends.
fn closest_on_edge(
    shape: Shape,
    x: &[[f64; 3]; 8],
    p: [f64; 3],
    a: [f64; 2],
    b: [f64; 2],
) -> [f64; 2] {
    let at = |tau: f64| [a[0] + tau * (b[0] - a[0]), a[1] + tau * (b[1] - a[1])];
    let e = [b[0] - a[0], b[1] - a[1]];
    let dist = |tau: f64| {
        let (_, xp, _) = face::map_point(shape, x, at(tau));
        norm(sub(p, xp))
    };
    // X is quadratic along the edge: its second derivative is constant, from the difference
    // of the first derivatives at the ends.
    let (_, [_, xs0, xt0]) = face::tangents(shape, x, a);
    let (_, [_, xs1, xt1]) = face::tangents(shape, x, b);
    let d2: [f64; 3] = std::array::from_fn(|k| (xs1[k] - xs0[k]) * e[0] + (xt1[k] - xt0[k]) * e[1]);
    let mut tau = 0.5;
    for _ in 0..30 {
        let (_, [xp, xs, xt]) = face::tangents(shape, x, at(tau));
        let d1: [f64; 3] = std::array::from_fn(|k| xs[k] * e[0] + xt[k] * e[1]);
        let r = sub(xp, p);
        let g = dot(r, d1);
        let h = dot(d1, d1) + dot(r, d2);
        if h.is_nan() || h <= 0.0 {
            break;
        }
        let step = g / h;
        tau = (tau - step).clamp(0.0, 1.0);
        if step.abs() <= 1e-14 {
            break;
        }
    }
    let best = [tau, 0.0, 1.0]
        .into_iter()
        .map(|t| (dist(t), t))
        .min_by(|u, v| u.0.total_cmp(&v.0))
        .map_or(tau, |m| m.1);
    at(best)
}

/// A pad contact point paired with its projection onto the disc face.
#[derive(Clone, Debug, PartialEq)]
pub struct NodalPair {
    /// The pad's contact point (a face node, or a Gauss point of an 8-node face:
    /// [`super::quad_contact`]), its area and normal.
    pub pad: ContactPoint,
    /// Its projection onto the disc face.
    pub projection: Projection,
}

/// Projects every node of the pad's face `pad_face` onto the disc's face `disc_face`
/// (module docs), the pairs in the pad's node order; refused by [`check_facing`] when the
/// pad does not face the disc.
pub fn project_pad(
    disc: &Mesh,
    disc_face: &str,
    pad: &Mesh,
    pad_face: &str,
) -> Result<Vec<NodalPair>, InterfaceError> {
    let surface = Surface::new(disc, disc_face)?;
    let pairs: Vec<NodalPair> = contact_points(pad, pad_face)?
        .into_iter()
        .map(|point| {
            let projection = surface.project(point.position);
            NodalPair {
                pad: point,
                projection,
            }
        })
        .collect();
    check_facing(&pairs, pad, pad_face, disc_face)?;
    Ok(pairs)
}

/// Refuses a pad that does not face the disc face: less than [`MIN_FACING_SHARE`] of its
/// face's area projects inside the disc face, or a pad node lies farther from the disc face
/// along its normal than the pad face is wide (a pad in the wrong place or in other units).
pub fn check_facing(
    pairs: &[NodalPair],
    pad: &Mesh,
    pad_face: &str,
    disc_face: &str,
) -> Result<(), InterfaceError> {
    let total: f64 = pairs.iter().map(|p| p.pad.area).sum();
    let inside: f64 = pairs
        .iter()
        .filter(|p| p.projection.outside == 0.0)
        .map(|p| p.pad.area)
        .sum();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in pairs {
        let x = p.pad.position;
        for d in 0..3 {
            lo[d] = lo[d].min(x[d]);
            hi[d] = hi[d].max(x[d]);
        }
    }
    let width = norm(sub(hi, lo));
    let farthest = pairs
        .iter()
        .max_by(|a, b| a.projection.gap.abs().total_cmp(&b.projection.gap.abs()));
    // A face node by its id; a Gauss point of an 8-node face by its face's first node.
    let name = |p: &NodalPair| {
        let n = p.pad.nodes.first().map_or(0, |n| n.0);
        let id = pad.node_ids.get(n as usize).copied().unwrap_or(0);
        match p.pad.node() {
            Some(_) => format!("pad node {id}"),
            None => format!("a Gauss point of the pad's face with node {id}"),
        }
    };
    if let Some(far) = farthest
        && far.projection.gap.abs() > width
    {
        return Err(InterfaceError::NotFacing {
            pad_face: pad_face.into(),
            disc_face: disc_face.into(),
            what: format!(
                "{} lies {:.3e} m from the disc face along its normal, more than the pad face is wide ({width:.3e} m): check that the pad sits on the disc in the meshes' common frame and that both meshes are in the same units",
                name(far),
                far.projection.gap.abs()
            ),
        });
    }
    if inside.is_nan() || inside < MIN_FACING_SHARE * total {
        let worst = pairs
            .iter()
            .max_by(|a, b| a.projection.outside.total_cmp(&b.projection.outside));
        let (id, outside) = worst.map_or((String::new(), 0.0), |w| (name(w), w.projection.outside));
        return Err(InterfaceError::NotFacing {
            pad_face: pad_face.into(),
            disc_face: disc_face.into(),
            what: format!(
                "only {:.1}% of the pad face's area projects onto the disc face (at least {:.0}% must); {id} lies {outside:.3e} m beyond the disc face's edge: check that the disc face set is the face under this pad and that the pad sits over it",
                (100.0 * inside / total.max(f64::MIN_POSITIVE)).max(0.0),
                100.0 * MIN_FACING_SHARE
            ),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use squeal_mesh::generate::box_tet10_origin;

    #[test]
    fn lumped_areas_partition_a_flat_face_with_a_twelfth_at_corners() {
        // A 2 x 1 face meshed 4 x 2: straight-sided triangles, so every sub-triangle's area is
        // exact and the lumped areas are A/12 per corner and A/4 per midside node of each
        // triangle they belong to.
        let mut mesh = box_tet10_origin([0.0, 0.0, 0.0], [2.0, 1.0, 0.1], [4, 2, 1]);
        let face = mesh.node_set("ZMAX").unwrap().to_vec();
        mesh.node_sets.insert("F".into(), face);
        let nodes = face_nodes(&mesh, "F").unwrap();
        let total: f64 = nodes.iter().map(|n| n.area).sum();
        assert!((total - 2.0).abs() < 1e-14, "total {total}");
        for n in &nodes {
            assert!(n.area > 0.0);
            assert!((n.normal[2] - 1.0).abs() < 1e-14);
        }
        // A midside node inside the face: on an edge shared by two triangles of area 1/8
        // (each 0.5 x 0.5 cell is split in two), so 2 × (1/8)/4 = 1/16.
        let p = nodes
            .iter()
            .find(|n| {
                let x = mesh.nodes[n.node as usize];
                (x[0] - 0.75).abs() < 1e-12 && (x[1] - 0.5).abs() < 1e-12
            })
            .unwrap();
        assert!((p.area - 1.0 / 16.0).abs() < 1e-15, "{}", p.area);
    }

    #[test]
    fn a_point_beyond_the_face_goes_to_its_edge() {
        let mut mesh = box_tet10_origin([0.0, 0.0, 0.0], [1.0, 1.0, 0.1], [3, 3, 1]);
        let face = mesh.node_set("ZMAX").unwrap().to_vec();
        mesh.node_sets.insert("F".into(), face);
        let s = Surface::new(&mesh, "F").unwrap();
        // Above the face: straight down, 1e-4 off.
        let p = s.project([0.3, 0.55, 0.1001]);
        assert!((p.gap - 1e-4).abs() < 1e-15 && p.outside == 0.0, "{p:?}");
        assert!((p.point[0] - 0.3).abs() < 1e-15 && (p.point[1] - 0.55).abs() < 1e-15);
        let sum: f64 = p.weights.iter().map(|w| w.1).sum();
        assert!((sum - 1.0).abs() < 1e-15);
        // 2 mm beyond the edge x = 1: to the edge, 2 mm outside.
        let q = s.project([1.002, 0.4, 0.1]);
        assert!((q.point[0] - 1.0).abs() < 1e-15 && (q.point[1] - 0.4).abs() < 1e-14);
        assert!((q.outside - 0.002).abs() < 1e-14, "{q:?}");
    }
}
