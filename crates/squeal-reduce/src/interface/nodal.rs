//! The nodal interface: every node of the pad's friction face is a contact point, paired with
//! the point of the disc face it projects onto.
//!
//! This is node-to-surface contact (Wriggers, *Computational Contact Mechanics*, 2nd ed.,
//! Springer 2006, Sec. 4.1 and 9.1; Laursen, *Computational Contact and Impact Mechanics*,
//! 2002, Ch. 5): the pad is the slave side, its face nodes `x_k`; the disc is the master
//! surface, its 6-node boundary triangles `X(s, t) = Σ_a N_a(s, t) X_a` over the disc's
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
//! stiffness per unit area). The consistent nodal areas `∫ N_k dA` of 6-node triangles are
//! zero at the corners of a flat triangle (and negative on a distorted one), which would
//! leave every corner node without a spring, free to pass through the disc. The areas are
//! lumped instead: each triangle is split at its edge midpoints into four (in reference
//! coordinates: the 6-node triangle's own sub-triangles), and each node takes a third of the
//! area of each sub-triangle it is a corner of (`A/12` at a corner and `A/4` at a midside node
//! of a flat triangle). They are positive, and they partition the face: `Σ_k A_k` is the face's
//! area to round-off (each sub-triangle's area integrated by the degree-4 rule, exact on a
//! flat face). A node's normal is the area-weighted mean outward normal over the same
//! sub-triangles.

use super::{DUNAVANT4, InterfaceError, dot, face_triangles, map_point, norm, sub, unit};
use squeal_mesh::Mesh;
use std::collections::BTreeMap;

/// Shape-function weights below this are dropped from a projected point's row (the others
/// are scaled to sum to 1): a pad node on a disc node gets that node alone instead of six
/// entries, five of them round-off.
const NEGLIGIBLE_WEIGHT: f64 = 1e-12;

/// A projection inside a triangle is accepted when its area coordinates are not below this
/// (round-off of a point on an edge).
const INSIDE_TOLERANCE: f64 = 1e-10;

/// Less than this share of the pad's face (by area) projecting inside the disc face means
/// the pad does not face it ([`check_facing`]).
pub const MIN_FACING_SHARE: f64 = 0.5;

/// A node of a contact face with its lumped tributary area and normal.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceNode {
    /// Node index in the mesh.
    pub node: u32,
    /// Tributary area (m²): a third of each sub-triangle it is a corner of (module docs).
    pub area: f64,
    /// Unit outward normal: the area-weighted mean over those sub-triangles.
    pub normal: [f64; 3],
}

/// Reference coordinates of the six nodes `[v0, v1, v2, m01, m12, m20]`.
const REFERENCE: [[f64; 2]; 6] = [
    [0.0, 0.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [0.5, 0.0],
    [0.5, 0.5],
    [0.0, 0.5],
];

/// The four sub-triangles of a 6-node triangle, as local node indices.
const SUBTRIANGLES: [[usize; 3]; 4] = [[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]];

/// The nodes of the boundary triangles of `face_set`, in node order, with their lumped
/// tributary areas and normals (module docs).
pub fn face_nodes(mesh: &Mesh, face_set: &str) -> Result<Vec<FaceNode>, InterfaceError> {
    let (_, triangles) = face_triangles(mesh, face_set)?;
    let mut acc: BTreeMap<u32, (f64, [f64; 3])> = BTreeMap::new();
    for tri in &triangles {
        let x: [[f64; 3]; 6] = std::array::from_fn(|i| mesh.nodes[tri[i] as usize]);
        for sub_tri in SUBTRIANGLES {
            let (area, normal) = subtriangle_integrals(&x, sub_tri.map(|k| REFERENCE[k]));
            for k in sub_tri {
                let e = acc.entry(tri[k]).or_insert((0.0, [0.0; 3]));
                e.0 += area / 3.0;
                for d in 0..3 {
                    e.1[d] += normal[d] / 3.0;
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

/// `∫ dA` and `∫ n dA` over the part of the 6-node triangle `x` whose reference coordinates
/// form the triangle `q` (degree-4 rule mapped onto it).
fn subtriangle_integrals(x: &[[f64; 3]; 6], q: [[f64; 2]; 3]) -> (f64, [f64; 3]) {
    let e1 = [q[1][0] - q[0][0], q[1][1] - q[0][1]];
    let e2 = [q[2][0] - q[0][0], q[2][1] - q[0][1]];
    let jac = (e1[0] * e2[1] - e1[1] * e2[0]).abs();
    let (mut area, mut normal) = (0.0, [0.0; 3]);
    for (a, b, w) in DUNAVANT4 {
        let st = [0, 1].map(|i| q[0][i] + a * e1[i] + b * e2[i]);
        let (_, _, dn) = map_point(x, st);
        let weight = 0.5 * w * jac;
        area += weight * norm(dn);
        for d in 0..3 {
            normal[d] += weight * dn[d];
        }
    }
    (area, normal)
}

/// A contact face ready for closest-point queries: its triangles, their nodes' coordinates
/// and a box around each (holding the curved triangle: the box of its quadratic Bézier
/// control points).
pub struct Surface {
    triangles: Vec<[u32; 6]>,
    coords: Vec<[[f64; 3]; 6]>,
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
    /// 0 when the projection falls inside the face's triangles; else the length of `x − X`
    /// in the face's tangent plane at `X`: how far beyond the face's boundary `x` lies (m).
    pub outside: f64,
}

impl Surface {
    /// The boundary triangles of `face_set`.
    pub fn new(mesh: &Mesh, face_set: &str) -> Result<Self, InterfaceError> {
        let (_, triangles) = face_triangles(mesh, face_set)?;
        let coords: Vec<[[f64; 3]; 6]> = triangles
            .iter()
            .map(|t| std::array::from_fn(|i| mesh.nodes[t[i] as usize]))
            .collect();
        let boxes = coords.iter().map(bezier_box).collect();
        Ok(Self {
            triangles,
            coords,
            boxes,
        })
    }

    /// The closest point of the face to `x` (module docs): over the triangles in order of
    /// the distance to their boxes, until a box lies farther than the best point found; ties
    /// go to the triangle first in that order (then by index), so the result does not depend
    /// on anything but the meshes.
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
            let (st, inside) = closest_on_triangle(&self.coords[i], x);
            let (_, xp, _) = map_point(&self.coords[i], st);
            let d = norm(sub(x, xp));
            if best.is_none_or(|b| d < b.0) {
                best = Some((d, i, st, inside));
            }
        }
        // A surface has at least one triangle (`face_triangles` refuses an empty one).
        let (distance, i, st, inside) = best.unwrap_or((f64::INFINITY, 0, [0.0; 2], false));
        let (n, point, dn) = map_point(&self.coords[i], st);
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
            weights: row(&self.triangles[i], &n),
            distance,
            gap,
            outside,
        }
    }
}

/// The kept shape-function weights of one point, by node (module docs).
fn row(nodes: &[u32; 6], n: &[f64; 6]) -> Vec<(u32, f64)> {
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

/// The box of the quadratic triangle's Bézier control points (the nodes at the corners,
/// `2 m − (a + b)/2` for an edge `a, b` with midside node `m`): by the convex-hull property it
/// holds the whole curved triangle.
fn bezier_box(x: &[[f64; 3]; 6]) -> [[f64; 3]; 2] {
    let edges = [(0, 1, 3), (1, 2, 4), (2, 0, 5)];
    let mut pts = vec![x[0], x[1], x[2]];
    for (a, b, m) in edges {
        pts.push(std::array::from_fn(|d| {
            2.0 * x[m][d] - 0.5 * (x[a][d] + x[b][d])
        }));
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in pts {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
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

/// The reference coordinates of the point of the 6-node triangle `x` closest to `p`, and
/// whether it is an interior stationary point (else the closest point of its edges).
fn closest_on_triangle(x: &[[f64; 3]; 6], p: [f64; 3]) -> ([f64; 2], bool) {
    if let Some(st) = interior_projection(x, p) {
        return (st, true);
    }
    // The constrained minimum lies on an edge: the best of the three edges' minima.
    let edges: [([f64; 2], [f64; 2]); 3] = [
        ([0.0, 0.0], [1.0, 0.0]),
        ([1.0, 0.0], [0.0, 1.0]),
        ([0.0, 1.0], [0.0, 0.0]),
    ];
    let mut best = ([0.0; 2], f64::INFINITY);
    for (a, b) in edges {
        let st = closest_on_edge(x, p, a, b);
        let (_, xp, _) = map_point(x, st);
        let d = norm(sub(p, xp));
        if d < best.1 {
            best = (st, d);
        }
    }
    (best.0, false)
}

/// Gauss–Newton on the stationarity of `|p − X(s, t)|²` from the centroid: the interior
/// projection, if it converges inside the triangle. On a flat triangle with straight edges
/// `X` is affine and one step lands on it.
fn interior_projection(x: &[[f64; 3]; 6], p: [f64; 3]) -> Option<[f64; 2]> {
    let mut st = [1.0 / 3.0, 1.0 / 3.0];
    for _ in 0..30 {
        let (xs, xt, xp) = tangents(x, st);
        let r = sub(p, xp);
        let (a, b, c) = (dot(xs, xs), dot(xs, xt), dot(xt, xt));
        let (f, g) = (dot(xs, r), dot(xt, r));
        let det = a * c - b * b;
        if det.is_nan() || det <= 0.0 {
            return None;
        }
        let step = [(c * f - b * g) / det, (a * g - b * f) / det];
        st = [st[0] + step[0], st[1] + step[1]];
        // Keep the iterate near the triangle: far outside, the quadratic map may fold.
        st = st.map(|v| v.clamp(-1.0, 2.0));
        if step[0].abs().max(step[1].abs()) <= 1e-14 {
            let inside = st[0] >= -INSIDE_TOLERANCE
                && st[1] >= -INSIDE_TOLERANCE
                && st[0] + st[1] <= 1.0 + INSIDE_TOLERANCE;
            return inside.then(|| {
                // A point on an edge within round-off is put on it.
                let s = st[0].max(0.0);
                let t = st[1].max(0.0);
                let over = (s + t - 1.0).max(0.0);
                [s - 0.5 * over, t - 0.5 * over]
            });
        }
    }
    None
}

/// The point of the triangle's edge from reference point `a` to `b` closest to `p`: Newton's
/// method on `(X(τ) − p) · X'(τ) = 0` along the (quadratic) edge, kept in `[0, 1]`, compared
/// with the edge's ends.
fn closest_on_edge(x: &[[f64; 3]; 6], p: [f64; 3], a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let at = |tau: f64| [a[0] + tau * (b[0] - a[0]), a[1] + tau * (b[1] - a[1])];
    let e = [b[0] - a[0], b[1] - a[1]];
    let dist = |tau: f64| {
        let (_, xp, _) = map_point(x, at(tau));
        norm(sub(p, xp))
    };
    let mut tau = 0.5;
    for _ in 0..30 {
        let (xs, xt, xp) = tangents(x, at(tau));
        let d1: [f64; 3] = std::array::from_fn(|k| xs[k] * e[0] + xt[k] * e[1]);
        let r = sub(xp, p);
        let g = dot(r, d1);
        // X is quadratic along the edge: its second derivative is constant, from the
        // difference of the first derivatives at the ends.
        let (xs0, xt0, _) = tangents(x, a);
        let (xs1, xt1, _) = tangents(x, b);
        let d2: [f64; 3] =
            std::array::from_fn(|k| (xs1[k] - xs0[k]) * e[0] + (xt1[k] - xt0[k]) * e[1]);
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

/// `∂X/∂s`, `∂X/∂t` and `X` of the 6-node triangle `x` at `st`.
fn tangents(x: &[[f64; 3]; 6], st: [f64; 2]) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let (n, ds, dt) = super::tri6_shape(st[0], st[1]);
    let (mut xs, mut xt, mut xp) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    for k in 0..6 {
        for d in 0..3 {
            xs[d] += ds[k] * x[k][d];
            xt[d] += dt[k] * x[k][d];
            xp[d] += n[k] * x[k][d];
        }
    }
    (xs, xt, xp)
}

/// A pad face node paired with its projection onto the disc face.
#[derive(Clone, Debug, PartialEq)]
pub struct NodalPair {
    /// The pad's face node, its area and normal.
    pub pad: FaceNode,
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
    let pairs: Vec<NodalPair> = face_nodes(pad, pad_face)?
        .into_iter()
        .map(|node| {
            let projection = surface.project(pad.nodes[node.node as usize]);
            NodalPair {
                pad: node,
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
        let x = pad.nodes[p.pad.node as usize];
        for d in 0..3 {
            lo[d] = lo[d].min(x[d]);
            hi[d] = hi[d].max(x[d]);
        }
    }
    let width = norm(sub(hi, lo));
    let farthest = pairs
        .iter()
        .max_by(|a, b| a.projection.gap.abs().total_cmp(&b.projection.gap.abs()));
    let node_id = |p: &NodalPair| pad.node_ids.get(p.pad.node as usize).copied().unwrap_or(0);
    if let Some(far) = farthest
        && far.projection.gap.abs() > width
    {
        return Err(InterfaceError::NotFacing {
            pad_face: pad_face.into(),
            disc_face: disc_face.into(),
            what: format!(
                "pad node {} lies {:.3e} m from the disc face along its normal, more than the pad face is wide ({width:.3e} m): check that the pad sits on the disc in the meshes' common frame and that both meshes are in the same units",
                node_id(far),
                far.projection.gap.abs()
            ),
        });
    }
    if inside.is_nan() || inside < MIN_FACING_SHARE * total {
        let worst = pairs
            .iter()
            .max_by(|a, b| a.projection.outside.total_cmp(&b.projection.outside));
        let (id, outside) = worst.map_or((0, 0.0), |w| (node_id(w), w.projection.outside));
        return Err(InterfaceError::NotFacing {
            pad_face: pad_face.into(),
            disc_face: disc_face.into(),
            what: format!(
                "only {:.1}% of the pad face's area projects onto the disc face (at least {:.0}% must); pad node {id} lies {outside:.3e} m beyond the disc face's edge: check that the disc face set is the face under this pad and that the pad sits over it",
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
