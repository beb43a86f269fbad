//! Interface models: how a part's contact points are tied to its mesh.
//!
//! - **node** (the paper's model): each contact point is one mesh node of the `CONTACT` set,
//!   with its three dofs kept as boundary dofs.
//! - **nodal**: every node of the pad's friction face is a contact point, paired with the point
//!   of the disc face it projects onto (node-to-surface contact, module [`nodal`]).
//! - **patch**: the contact face (`CONTACT_FACE`) is split on a grid in radius and angle about
//!   the disc axis (3 × 3 by default) and each contact point moves as the area-weighted mean of
//!   its patch, `r = C u` with `C_pk = (1/A_p) ∫_{patch p} N_k dA` (the RBE3 idea); the point's
//!   force is spread back as `Cᵀ f`. A spring on a single node feels the point compliance of a
//!   3-D continuum, which grows without bound as the mesh is refined; a patch's mean motion
//!   converges.
//!
//! Patches are numbered radius-major from the inner radius and the smallest angle (angles
//! counter-clockwise about the axis), the numbering of the bundled meshes' `CONTACT_PATCH_k`.
//!
//! # The patches
//!
//! The grid spans the face nodes' extent in radius `r₀ .. r₁` and angle `θ₀ .. θ₁` about the
//! axis; its cuts are the circles `r = r₀ + k (r₁ − r₀)/N_r` and the half-planes
//! `θ = θ₀ + k (θ₁ − θ₀)/N_θ` between them, and the first and last ring and sector reach past
//! the extent so that the cells cover the face. Patch `p` is the part of the face (its 6-node
//! boundary triangles, curved edges and all) inside cell `p`: a triangle no cut crosses lies in
//! the cell of its centroid and adds its degree-4 Dunavant integrals whole; a triangle a cut
//! crosses is split along the cuts and each piece adds its integrals to its own patch (module
//! `clip`: which cuts cross, an iterated Gauss rule on the pieces exact to round-off on a flat
//! face's cells). So the disc's and the pad's patches are the same regions of the same surface
//! whatever their meshes, and pair; where the cuts are mesh edges (the bundled meshes imprint
//! the 3 × 3 grid) no triangle is crossed and the patches are those of whole triangles, to the
//! bit. Each patch's sums come from one set of quadrature points,
//!
//! `A_p = Σ_q w_q |J_q|`, `A_p x̄_p = Σ_q w_q |J_q| x(q)`, `A_p C_pk = Σ_q w_q |J_q| N_k(q)`,
//!
//! and `Σ_k N_k = 1`, `x(q) = Σ_k N_k(q) x_k` at every point, so that `Σ_k C_pk = 1` and
//! `Σ_k C_pk x_k = x̄_p` to round-off: the patch's mean motion under a rigid translation is
//! that translation, and its centroid is where its mean motion is taken.

use squeal_element::geometry::{cross, dot, norm, sub};
mod clip;
pub mod face;
pub mod nodal;
pub mod quad_contact;

use face::{Shape, SurfaceFace};

use squeal_mesh::Mesh;
use std::collections::HashMap;

/// Errors of the interface models.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum InterfaceError {
    /// The mesh has no node set of that name (check the set names given for the part).
    #[error("node set {0} is missing from the mesh")]
    MissingSet(String),
    /// The node set exists but holds no node.
    #[error("node set {0} is empty")]
    EmptySet(String),
    /// The contact-face set does not cover a whole element face anywhere, so there is no
    /// surface to cut into patches.
    #[error(
        "node set {set} has no boundary face: no element face has all its nodes (six of a triangle, eight of a quadrilateral) in it"
    )]
    NoFaces {
        /// The contact-face node set.
        set: String,
    },
    /// A cell of the patch grid holds none of the face (the face leaves a cell of its
    /// extent in radius and angle about the axis empty: is the axis the disc's?).
    #[error(
        "patch {patch} of the {radial} x {angular} grid on {set} covers none of the face: the face does not fill its extent in radius and angle about the axis"
    )]
    EmptyPatch {
        /// The contact-face node set.
        set: String,
        /// The empty patch, 1-based.
        patch: usize,
        /// Patches across the radius.
        radial: usize,
        /// Patches around the axis.
        angular: usize,
    },
    /// The axis direction given is the zero vector.
    #[error("the disc axis has zero length")]
    BadAxis,
    /// A pad's friction face does not face the disc face it is to be paired with (nodal
    /// interface).
    #[error("the pad face {pad_face} does not face the disc face {disc_face}: {what}")]
    NotFacing {
        /// The pad's contact-face set.
        pad_face: String,
        /// The disc's contact-face set.
        disc_face: String,
        /// How far off it is and what to check.
        what: String,
    },
}

/// The disc's axis of rotation: radii and angles are measured about it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Axis {
    /// A point on the axis (m).
    pub origin: [f64; 3],
    /// Direction (need not be unit); angles are counter-clockwise seen from its tip.
    pub direction: [f64; 3],
}

impl Default for Axis {
    /// The z axis through the origin, as in the bundled meshes.
    fn default() -> Self {
        Self {
            origin: [0.0; 3],
            direction: [0.0, 0.0, 1.0],
        }
    }
}

/// A contact patch: its area, centroid and the weights of the face nodes in its mean motion.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    /// 1-based patch number.
    pub number: usize,
    /// Area of the patch (m²).
    pub area: f64,
    /// Area-weighted centroid of the patch (m).
    pub centroid: [f64; 3],
    /// Unit outward normal of the part's face over the patch: the area-weighted mean of the
    /// face's normals.
    pub normal: [f64; 3],
    /// `(node index, weight)`, weights summing to 1, sorted by node index.
    pub weights: Vec<(u32, f64)>,
}

/// Cylindrical coordinates about an axis.
struct Frame {
    origin: [f64; 3],
    e3: [f64; 3],
    e1: [f64; 3],
    e2: [f64; 3],
}

impl Frame {
    /// Frame with `e1` along `reference` projected on the plane normal to the axis.
    fn new(axis: &Axis, reference: [f64; 3]) -> Result<Self, InterfaceError> {
        let e3 = unit(axis.direction).ok_or(InterfaceError::BadAxis)?;
        let mut e1 = sub(reference, scale(e3, dot(reference, e3)));
        if norm(e1) < 1e-12 * norm(reference).max(1.0) {
            e1 = if e3[0].abs() < 0.9 {
                [1.0, 0.0, 0.0]
            } else {
                [0.0, 1.0, 0.0]
            };
            e1 = sub(e1, scale(e3, dot(e1, e3)));
        }
        let e1 = unit(e1).ok_or(InterfaceError::BadAxis)?;
        Ok(Self {
            origin: axis.origin,
            e3,
            e1,
            e2: cross(e3, e1),
        })
    }

    /// `(radius, angle from e1)`.
    fn polar(&self, p: [f64; 3]) -> (f64, f64) {
        let d = sub(p, self.origin);
        let (a, b) = (dot(d, self.e1), dot(d, self.e2));
        let _ = self.e3;
        ((a * a + b * b).sqrt(), b.atan2(a))
    }
}

/// The node interface: the nodes of `set` (e.g. `CONTACT`), ordered by radius then angle about
/// `axis` (radii equal to 1e-9 relative count as equal), matching the patch numbering.
pub fn contact_nodes(mesh: &Mesh, set: &str, axis: &Axis) -> Result<Vec<u32>, InterfaceError> {
    let nodes = mesh
        .node_set(set)
        .ok_or_else(|| InterfaceError::MissingSet(set.into()))?;
    if nodes.is_empty() {
        return Err(InterfaceError::EmptySet(set.into()));
    }
    let mean = mean_point(nodes.iter().map(|&n| mesh.nodes[n as usize]));
    let frame = Frame::new(axis, sub(mean, axis.origin))?;
    let mut keyed: Vec<(f64, f64, u32)> = nodes
        .iter()
        .map(|&n| {
            let (r, t) = frame.polar(mesh.nodes[n as usize]);
            (r, t, n)
        })
        .collect();
    let scale = keyed
        .iter()
        .map(|k| k.0)
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    keyed.sort_by(|a, b| {
        let same_r = (a.0 - b.0).abs() <= 1e-9 * scale;
        let by_r = if same_r {
            std::cmp::Ordering::Equal
        } else {
            a.0.total_cmp(&b.0)
        };
        by_r.then(a.1.total_cmp(&b.1)).then(a.2.cmp(&b.2))
    });
    Ok(keyed.into_iter().map(|k| k.2).collect())
}

/// The patch interface: `face_set` split on a `radial x angular` grid about `axis`, each
/// patch the part of the face inside its cell (module docs).
pub fn patches(
    mesh: &Mesh,
    face_set: &str,
    radial: usize,
    angular: usize,
    axis: &Axis,
) -> Result<Vec<Patch>, InterfaceError> {
    let (nodes, faces) = face_triangles(mesh, face_set)?;
    let mean = mean_point(nodes.iter().map(|&n| mesh.nodes[n as usize]));
    let frame = Frame::new(axis, sub(mean, axis.origin))?;
    let grid = PolarGrid::spanning(
        frame,
        nodes.iter().map(|&n| mesh.nodes[n as usize]),
        radial,
        angular,
    );
    let rules = clip::Rules::new();
    let mut acc: Vec<PatchSums> = (0..grid.radial * grid.angular)
        .map(|_| PatchSums::default())
        .collect();
    for face in &faces {
        let x = face.coords(mesh);
        for half in halves(face.shape) {
            add_half(&grid, &rules, &mut acc, face, &x, &half);
        }
    }
    acc.into_iter()
        .enumerate()
        .map(|(i, s)| {
            if s.area <= 0.0 {
                return Err(InterfaceError::EmptyPatch {
                    set: face_set.into(),
                    patch: i + 1,
                    radial: grid.radial,
                    angular: grid.angular,
                });
            }
            Ok(s.finish(i + 1))
        })
        .collect()
}

/// A piston's footprint: the whole of `face_set` (its boundary triangles, as for a contact
/// face) as one patch, whose weights give the footprint's area-weighted mean motion
/// `r = Σ_k w_k u_k`, `w_k = (1/A) ∫ N_k dA` (the RBE3 idea): a force `F` on `r` is the
/// consistent nodal load of the pressure `F / A` over the footprint, `F w_k` at node `k`.
pub fn footprint(mesh: &Mesh, face_set: &str) -> Result<Patch, InterfaceError> {
    let (_, faces) = face_triangles(mesh, face_set)?;
    let mut sums = PatchSums::default();
    for face in &faces {
        sums.add_face(face, &face.coords(mesh));
    }
    Ok(sums.finish(1))
}

/// The patch grid on a face: `radial` rings between the radii `r[0]`, `r[1]` and `angular`
/// sectors between the angles `t[0]`, `t[1]` about the axis (the face nodes' extent), the
/// first and last ring and sector open outwards so that the cells cover the whole face.
struct PolarGrid {
    frame: Frame,
    r: [f64; 2],
    t: [f64; 2],
    radial: usize,
    angular: usize,
    /// The radial cuts between rings, `r₀ + k (r₁ − r₀) / radial`, `k = 1 .. radial − 1`.
    radii: Vec<f64>,
    /// The angular cuts between sectors.
    angles: Vec<f64>,
    /// A length below which a triangle touches a cut rather than crosses it: 1e-9 of the
    /// face's outer radius.
    tol: f64,
}

/// The cuts of the grid on one triangle.
struct TriangleCuts {
    /// Radial cuts the whole triangle lies beyond.
    rings_beyond: usize,
    /// Angular cuts the whole triangle lies beyond.
    sectors_beyond: usize,
    /// The cuts that cross it, as level functions on it.
    levels: Vec<clip::Level>,
    /// Its nodes' coordinates in the plane normal to the axis, from the axis.
    planar: [[f64; 2]; 6],
}

impl PolarGrid {
    /// The grid over the extent of `points` (a face's nodes) in radius and angle.
    fn spanning(
        frame: Frame,
        points: impl Iterator<Item = [f64; 3]>,
        radial: usize,
        angular: usize,
    ) -> Self {
        let (mut r, mut t) = (
            [f64::INFINITY, f64::NEG_INFINITY],
            [f64::INFINITY, f64::NEG_INFINITY],
        );
        for p in points {
            let (rp, tp) = frame.polar(p);
            r = [r[0].min(rp), r[1].max(rp)];
            t = [t[0].min(tp), t[1].max(tp)];
        }
        let (radial, angular) = (radial.max(1), angular.max(1));
        let cuts = |[lo, hi]: [f64; 2], n: usize| -> Vec<f64> {
            (1..n)
                .map(|k| lo + (hi - lo) * k as f64 / n as f64)
                .collect()
        };
        Self {
            radii: cuts(r, radial),
            angles: cuts(t, angular),
            tol: 1e-9 * r[1].abs(),
            frame,
            r,
            t,
            radial,
            angular,
        }
    }

    /// The cell (0-based patch) holding the point `p`.
    fn cell_of(&self, p: [f64; 3]) -> usize {
        let bin = |v: f64, [lo, hi]: [f64; 2], n: usize| -> usize {
            let f = if hi > lo { (v - lo) / (hi - lo) } else { 0.0 };
            ((f * n as f64).floor().max(0.0) as usize).min(n - 1)
        };
        let (r, t) = self.frame.polar(p);
        bin(r, self.r, self.radial) * self.angular + bin(t, self.t, self.angular)
    }

    /// The cuts crossing the 6-node triangle `x` (see [`clip`]): radial cuts by
    /// `ĝ = ρ² − c²` (tolerance `2 c tol`), angular cuts by the signed distance to their
    /// half-plane (tolerance `tol`). An angular cut is only tested on a triangle whose six
    /// nodes lie on its side of the axis (the plane through the axis also holds the opposite
    /// half-plane, at `φ + π`); a triangle on a cut within the tolerance goes by its centroid.
    fn cuts_crossing(&self, x: &[[f64; 3]; 6]) -> TriangleCuts {
        let f = &self.frame;
        let (r_mid, t_mid) = f.polar(triangle_centroid(x));
        let planar = x.map(|p| {
            let d = sub(p, f.origin);
            [dot(d, f.e1), dot(d, f.e2)]
        });
        let mut cuts = TriangleCuts {
            rings_beyond: 0,
            sectors_beyond: 0,
            levels: Vec::new(),
            planar,
        };
        for &radius in &self.radii {
            let cut = clip::Cut::Radial { radius };
            let g = planar.map(|p| cut.level(p));
            let tol = 2.0 * radius * self.tol;
            match clip::side_of(&g, tol) {
                clip::Side::Above => cuts.rings_beyond += 1,
                clip::Side::Below => {}
                clip::Side::Within => cuts.rings_beyond += usize::from(r_mid > radius),
                clip::Side::Crosses => cuts.levels.push(clip::Level::interpolating(cut, g, tol)),
            }
        }
        for &phi in &self.angles {
            let (sin, cos) = phi.sin_cos();
            let cut = clip::Cut::Angular { sin, cos };
            let on_its_side = planar.iter().all(|[a, b]| a * cos + b * sin > 0.0);
            let g = planar.map(|p| cut.level(p));
            let side = if on_its_side {
                clip::side_of(&g, self.tol)
            } else {
                clip::Side::Within
            };
            match side {
                clip::Side::Above => cuts.sectors_beyond += 1,
                clip::Side::Below => {}
                clip::Side::Within => cuts.sectors_beyond += usize::from(t_mid > phi),
                clip::Side::Crosses => cuts
                    .levels
                    .push(clip::Level::interpolating(cut, g, self.tol)),
            }
        }
        cuts
    }
}

/// Tributary areas of contact nodes on a contact face: every point of the face (the 6-point
/// rule of each boundary triangle of `face_set`) belongs to the nearest of `nodes` (ties to the
/// first), so the areas partition the face (a Voronoi split of it). This is the area a node
/// interface's contact point stands for: its contact stiffness per unit area times this area
/// is its spring. On the bundled meshes, whose contact nodes sit at the centres of the 3 × 3
/// patches, these cells are close to the patches (equal where the patch edges are bisectors).
///
/// Returns each node's area and the unit outward normal of its cell (the area-weighted mean of
/// the face's normals there; `[0, 0, 0]` for a node whose cell is empty).
pub fn tributary_areas(
    mesh: &Mesh,
    face_set: &str,
    nodes: &[u32],
) -> Result<Vec<(f64, [f64; 3])>, InterfaceError> {
    let (_, faces) = face_triangles(mesh, face_set)?;
    let centres: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.nodes[n as usize]).collect();
    let mut areas = vec![0.0; nodes.len()];
    let mut normals = vec![[0.0; 3]; nodes.len()];
    for f in &faces {
        let x = f.coords(mesh);
        for (st, w) in f.shape.rule() {
            let (_, xp, dn) = face::map_point(f.shape, &x, st);
            let dn = scale(dn, w);
            let da = norm(dn);
            let nearest = centres
                .iter()
                .enumerate()
                .map(|(k, c)| (k, norm(sub(xp, *c))))
                .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
            if let Some((k, _)) = nearest {
                areas[k] += da;
                for d in 0..3 {
                    normals[k][d] += dn[d];
                }
            }
        }
    }
    Ok(areas
        .into_iter()
        .zip(normals)
        .map(|(a, n)| (a, unit(n).unwrap_or([0.0; 3])))
        .collect())
}

/// Running integrals of one patch.
#[derive(Default)]
struct PatchSums {
    area: f64,
    moment: [f64; 3],
    /// `∫ n dA` (outward).
    normal: [f64; 3],
    weights: HashMap<u32, f64>,
}

impl PatchSums {
    /// Adds `∫ N_k dA` and `∫ x dA` of one face (its rule, [`Shape::rule`]: exact for the
    /// shape functions times the area Jacobian of a flat face, curved edges included, and
    /// accurate to the mesh's order on a curved face).
    fn add_face(&mut self, face: &SurfaceFace, x: &[[f64; 3]; 8]) {
        for (st, w) in face.shape.rule() {
            let (n, xp, dn) = face::map_point(face.shape, x, st);
            self.add_point(face, &n, xp, dn, w);
        }
    }

    /// Adds one quadrature point of a face: shape function values `n`, position `xp`,
    /// `dn = ∂x/∂s × ∂x/∂t` and reference weight `w` (`dA = w |dn|`).
    fn add_point(&mut self, face: &SurfaceFace, n: &[f64; 8], xp: [f64; 3], dn: [f64; 3], w: f64) {
        let da = w * norm(dn);
        self.area += da;
        for d in 0..3 {
            self.normal[d] += w * dn[d];
        }
        for d in 0..3 {
            self.moment[d] += da * xp[d];
        }
        for (a, &node) in face.nodes().iter().enumerate() {
            *self.weights.entry(node).or_default() += da * n[a];
        }
    }

    /// Adds a piece of a face.
    fn add_piece(&mut self, face: &SurfaceFace, piece: &PieceSums) {
        self.area += piece.area;
        for d in 0..3 {
            self.normal[d] += piece.normal[d];
            self.moment[d] += piece.moment[d];
        }
        for (a, &node) in face.nodes().iter().enumerate() {
            *self.weights.entry(node).or_default() += piece.weights[a];
        }
    }

    fn finish(self, number: usize) -> Patch {
        let mut weights: Vec<(u32, f64)> = self
            .weights
            .into_iter()
            .map(|(k, v)| (k, v / self.area))
            .collect();
        weights.sort_by_key(|w| w.0);
        Patch {
            number,
            area: self.area,
            centroid: self.moment.map(|m| m / self.area),
            normal: unit(self.normal).unwrap_or([0.0; 3]),
            weights,
        }
    }
}

/// Integrals over the part of one triangle in one patch: `∫ dA`, `∫ x dA`, `∫ n dA` and
/// `∫ N_k dA` of its six nodes.
#[derive(Default)]
struct PieceSums {
    area: f64,
    moment: [f64; 3],
    normal: [f64; 3],
    weights: [f64; 8],
}

impl PieceSums {
    /// Adds one quadrature point, as [`PatchSums::add_point`].
    fn add_point(&mut self, n: &[f64; 8], xp: [f64; 3], dn: [f64; 3], w: f64) {
        let da = w * norm(dn);
        self.area += da;
        for d in 0..3 {
            self.normal[d] += w * dn[d];
            self.moment[d] += da * xp[d];
        }
        for a in 0..8 {
            self.weights[a] += da * n[a];
        }
    }
}

/// Degree-4, 6-point rule on the reference triangle (Dunavant 1985): `(s, t, weight)`, weights
/// summing to 1 (multiply by the reference area 1/2).
const DUNAVANT4: [(f64, f64, f64); 6] = [
    (
        0.445_948_490_915_965,
        0.445_948_490_915_965,
        0.223_381_589_678_011,
    ),
    (
        0.445_948_490_915_965,
        0.108_103_018_168_070,
        0.223_381_589_678_011,
    ),
    (
        0.108_103_018_168_070,
        0.445_948_490_915_965,
        0.223_381_589_678_011,
    ),
    (
        0.091_576_213_509_771,
        0.091_576_213_509_771,
        0.109_951_743_655_322,
    ),
    (
        0.091_576_213_509_771,
        0.816_847_572_980_459,
        0.109_951_743_655_322,
    ),
    (
        0.816_847_572_980_459,
        0.091_576_213_509_771,
        0.109_951_743_655_322,
    ),
];

/// 6-node triangle `[v0, v1, v2, m01, m12, m20]`: values and derivatives in `(s, t)`.
fn tri6_shape(s: f64, t: f64) -> ([f64; 6], [f64; 6], [f64; 6]) {
    let l = [1.0 - s - t, s, t];
    let dl_ds = [-1.0, 1.0, 0.0];
    let dl_dt = [-1.0, 0.0, 1.0];
    let edges = [(0, 1), (1, 2), (2, 0)];
    let mut n = [0.0; 6];
    let mut ds = [0.0; 6];
    let mut dt = [0.0; 6];
    for i in 0..3 {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
        ds[i] = (4.0 * l[i] - 1.0) * dl_ds[i];
        dt[i] = (4.0 * l[i] - 1.0) * dl_dt[i];
    }
    for (k, (a, b)) in edges.iter().enumerate() {
        n[3 + k] = 4.0 * l[*a] * l[*b];
        ds[3 + k] = 4.0 * (dl_ds[*a] * l[*b] + l[*a] * dl_ds[*b]);
        dt[3 + k] = 4.0 * (dl_dt[*a] * l[*b] + l[*a] * dl_dt[*b]);
    }
    (n, ds, dt)
}

fn triangle_centroid(x: &[[f64; 3]; 6]) -> [f64; 3] {
    let (n, _, _) = tri6_shape(1.0 / 3.0, 1.0 / 3.0);
    let mut c = [0.0; 3];
    for a in 0..6 {
        for d in 0..3 {
            c[d] += n[a] * x[a][d];
        }
    }
    c
}

/// The nodes of face set `face_set` and its boundary faces (6-node triangles and 8-node
/// quadrilaterals); an error when the set is missing, empty or holds no boundary face.
fn face_triangles<'m>(
    mesh: &'m Mesh,
    face_set: &str,
) -> Result<(&'m [u32], Vec<SurfaceFace>), InterfaceError> {
    let nodes = mesh
        .node_set(face_set)
        .ok_or_else(|| InterfaceError::MissingSet(face_set.into()))?;
    if nodes.is_empty() {
        return Err(InterfaceError::EmptySet(face_set.into()));
    }
    let faces = boundary_faces_of(mesh, nodes);
    if faces.is_empty() {
        return Err(InterfaceError::NoFaces {
            set: face_set.into(),
        });
    }
    Ok((nodes, faces))
}

/// Element faces whose nodes are all in `set` and that belong to a single element (boundary
/// faces): the 6-node triangles (in the order of [`squeal_mesh::select::boundary_faces`]),
/// then the 8-node quadrilaterals (of [`squeal_mesh::select::boundary_quads`]).
pub fn boundary_faces_of(mesh: &Mesh, set: &[u32]) -> Vec<SurfaceFace> {
    use squeal_mesh::select::{boundary_faces, boundary_quads, faces_of_set};
    let mut out: Vec<SurfaceFace> = faces_of_set(mesh, &boundary_faces(mesh), set)
        .into_iter()
        .map(SurfaceFace::tri6)
        .collect();
    if mesh.blocks.len() == mesh.blocks.tet10.len() {
        return out;
    }
    let mut member = vec![false; mesh.num_nodes()];
    for &n in set {
        if let Some(m) = member.get_mut(n as usize) {
            *m = true;
        }
    }
    out.extend(
        boundary_quads(mesh)
            .into_iter()
            .filter(|q| q.iter().all(|&n| member[n as usize]))
            .map(SurfaceFace::quad8),
    );
    out
}

/// The reference triangles a face is integrated and clipped on, in the face's own reference
/// coordinates: the triangle itself, or the quadrilateral's two halves across its diagonal
/// from `(−1, −1)` to `(1, 1)`.
fn halves(shape: Shape) -> Vec<[[f64; 2]; 3]> {
    match shape {
        Shape::Tri6 => vec![[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]],
        Shape::Quad8 => vec![
            [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0]],
            [[-1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]],
        ],
    }
}

/// Adds the part of `face` over the reference triangle `half` (see [`halves`]) to the patches.
///
/// The grid's cuts are tested on, and clipped against, the 6-node triangle through the face's
/// points at the six nodes of `half` (for a 6-node face, the face itself; for a quadrilateral,
/// its half interpolated quadratically: exact where the quadrilateral's map is quadratic on the
/// half, as on a parallelogram, and otherwise placing a cut within the map's cubic remainder,
/// an error of the mesh's order). Every quadrature point is then mapped by the face's own map,
/// so `Σ_k C_pk = 1` and the centroids hold as for triangles (module docs).
fn add_half(
    grid: &PolarGrid,
    rules: &clip::Rules,
    acc: &mut [PatchSums],
    face: &SurfaceFace,
    x: &[[f64; 3]; 8],
    half: &[[f64; 2]; 3],
) {
    let e1 = [half[1][0] - half[0][0], half[1][1] - half[0][1]];
    let e2 = [half[2][0] - half[0][0], half[2][1] - half[0][1]];
    let jac = (e1[0] * e2[1] - e1[1] * e2[0]).abs();
    let to_face = |st: [f64; 2]| [0, 1].map(|i| half[0][i] + st[0] * e1[i] + st[1] * e2[i]);
    let x6: [[f64; 3]; 6] = match face.shape {
        Shape::Tri6 => std::array::from_fn(|i| x[i]),
        Shape::Quad8 => std::array::from_fn(|i| {
            let r = Shape::Tri6.reference()[i];
            face::map_point(face.shape, x, to_face(r)).1
        }),
    };
    let cuts = grid.cuts_crossing(&x6);
    if cuts.levels.is_empty() {
        let cell = &mut acc[grid.cell_of(triangle_centroid(&x6))];
        if face.shape == Shape::Tri6 {
            cell.add_face(face, x);
        } else {
            for (s, t, w) in DUNAVANT4 {
                let (n, xp, dn) = face::map_point(face.shape, x, to_face([s, t]));
                cell.add_point(face, &n, xp, dn, 0.5 * w * jac);
            }
        }
        return;
    }
    // The half's pieces, summed apart and added to their patches once.
    let mut pieces: Vec<(usize, PieceSums)> = Vec::new();
    clip::split_quadrature(&cuts.planar, &cuts.levels, rules, |q: clip::Point| {
        let ring = cuts.rings_beyond + q.radial_beyond;
        let sector = cuts.sectors_beyond + q.angular_beyond;
        let cell = ring * grid.angular + sector;
        let k = match pieces.iter().position(|p| p.0 == cell) {
            Some(k) => k,
            None => {
                pieces.push((cell, PieceSums::default()));
                pieces.len() - 1
            }
        };
        let (n, xp, dn) = face::map_point(face.shape, x, to_face(q.st));
        pieces[k].1.add_point(&n, xp, dn, q.weight * jac);
    });
    for (cell, piece) in pieces {
        acc[cell].add_piece(face, &piece);
    }
}

fn mean_point(points: impl Iterator<Item = [f64; 3]>) -> [f64; 3] {
    let mut s = [0.0; 3];
    let mut n = 0usize;
    for p in points {
        for d in 0..3 {
            s[d] += p[d];
        }
        n += 1;
    }
    s.map(|v| v / n.max(1) as f64)
}

fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    a.map(|v| v * s)
}
fn unit(a: [f64; 3]) -> Option<[f64; 3]> {
    let n = norm(a);
    (n > 0.0 && n.is_finite()).then(|| scale(a, 1.0 / n))
}
#[cfg(test)]
mod contact_area_tests;
#[cfg(test)]
mod quad_contact_tests;
#[cfg(test)]
mod quad_tests;
#[cfg(test)]
mod tests;
