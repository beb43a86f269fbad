//! Sets chosen by geometry, for meshes that carry no named sets: the boundary faces of a mesh,
//! the faces lying on a cylinder or a plane, the nodes in a box, faces by their normal.
//!
//! A face is a 6-node triangle of a tet10 ([`crate::tet10::FACES`] order), oriented so that
//! its corner normal points out of the part. A face lies on a surface when its three corners
//! do (within a tolerance): corners of a mesh always sit on the geometry, while the midside
//! nodes of a mesh with straight edges sit inside a curved surface by the edge's sagitta. The
//! nodes of a face selection are all six nodes of its faces.
//!
//! Hexahedra, wedges and pyramids have 8-node quadrilateral faces: they count in the
//! boundary test (a triangle shared with a pyramid is interior). [`boundary_quads`] lists the
//! quadrilaterals on the boundary. A geometric [`Rule`] selects a quadrilateral when both its
//! corner triangles `v0 v1 v2` and `v0 v2 v3` meet the rule (on the surface by their corners,
//! facing by their corner normals, in the box by all eight nodes, in the circle by their
//! corner centroids) and adds its eight nodes to the selection's nodes; the selection's
//! `faces` stay the triangles (the reports' face counts and areas are the triangles'). A rule
//! naming a node set takes the set's nodes whatever its faces. [`triangles_only`] refuses,
//! with an [`UnsupportedFace`] error, a node set that covers a quadrilateral, for code that
//! reads triangles only.
//!
//! Every description of a selection a user writes (a surface, a box, an angle, a tolerance)
//! is checked before use; a description that cannot select anything sensible (an axis of
//! zero length, a negative radius, a box whose minimum exceeds its maximum, a tolerance that
//! is not a finite non-negative number) is a [`SelectError`], not a silent empty or complete
//! selection.

use crate::model::Mesh;
use squeal_element::geometry::{cross, dot, sub, unit_or_self as unit};
use squeal_element::{Face as ElementFace, FaceKind};
use std::collections::HashMap;

/// Code that reads 6-node triangle faces met a quadrilateral face.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "{reader} reads 6-node triangle faces; this mesh's face with corner nodes {corners} is an \
     {kind}: not yet supported"
)]
pub struct UnsupportedFace {
    /// What reads the faces ("the contact interface", ...).
    pub reader: String,
    /// The face's shape.
    pub kind: FaceKind,
    /// The file ids of its corners, comma-separated.
    pub corners: String,
}

/// Why a geometric selection cannot be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SelectError {
    /// A point, a direction, a radius or a box bound is not a finite number.
    #[error("{what} is not a finite number")]
    NotFinite {
        /// What it is (e.g. "the cylinder's axis").
        what: &'static str,
    },
    /// A cylinder's axis or a plane's normal has zero length.
    #[error("{what} has zero length")]
    ZeroDirection {
        /// Which direction.
        what: &'static str,
    },
    /// A cylinder's radius is not positive.
    #[error("the cylinder's radius {0} is not positive")]
    BadRadius(f64),
    /// A distance tolerance is negative or not finite.
    #[error("the tolerance {0} is not a finite non-negative distance")]
    BadTolerance(f64),
    /// An angle is outside `0..=180` degrees or not finite.
    #[error("the angle {0} degrees is not between 0 and 180")]
    BadAngle(f64),
    /// A circle's diameter is not positive.
    #[error("the circle's diameter {0} is not positive")]
    BadDiameter(f64),
    /// A rule names a node set the mesh does not have.
    #[error("the mesh has no node set {name} (node sets: {known})")]
    MissingSet {
        /// The set named.
        name: String,
        /// The mesh's node sets, comma-separated, or "none".
        known: String,
    },
    /// A box's minimum exceeds its maximum along an axis.
    #[error(
        "the box's minimum ({}, {}, {}) exceeds its maximum ({}, {}, {}) along axis {axis}: give \
         min below max",
        min[0], min[1], min[2], max[0], max[1], max[2]
    )]
    EmptyBox {
        /// The lower corner.
        min: [f64; 3],
        /// The upper corner.
        max: [f64; 3],
        /// The axis (0, 1, 2) along which `min > max`.
        axis: usize,
    },
}

fn finite(v: [f64; 3], what: &'static str) -> Result<(), SelectError> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(SelectError::NotFinite { what })
    }
}

fn nonzero(v: [f64; 3], what: &'static str) -> Result<(), SelectError> {
    finite(v, what)?;
    if dot(v, v) > 0.0 {
        Ok(())
    } else {
        Err(SelectError::ZeroDirection { what })
    }
}

fn check_tolerance(tolerance: f64) -> Result<(), SelectError> {
    if tolerance.is_finite() && tolerance >= 0.0 {
        Ok(())
    } else {
        Err(SelectError::BadTolerance(tolerance))
    }
}

fn check_box(min: [f64; 3], max: [f64; 3]) -> Result<(), SelectError> {
    finite(min, "the box's minimum")?;
    finite(max, "the box's maximum")?;
    match (0..3).find(|&d| min[d] > max[d]) {
        Some(axis) => Err(SelectError::EmptyBox { min, max, axis }),
        None => Ok(()),
    }
}

/// A 6-node boundary triangle (node indices), outward.
pub type Face = [u32; 6];

/// A surface faces are picked on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Surface {
    /// The cylinder of `radius` about the line through `point` along `axis`.
    Cylinder {
        /// A point on the cylinder's axis.
        point: [f64; 3],
        /// The axis direction (need not be unit).
        axis: [f64; 3],
        /// Radius.
        radius: f64,
    },
    /// The plane through `point` normal to `normal`.
    Plane {
        /// A point of the plane.
        point: [f64; 3],
        /// Its normal (need not be unit).
        normal: [f64; 3],
    },
}

impl Surface {
    /// Checks that the surface is well defined: finite numbers, an axis or normal of nonzero
    /// length, a positive radius.
    pub fn check(&self) -> Result<(), SelectError> {
        match *self {
            Surface::Cylinder {
                point,
                axis,
                radius,
            } => {
                finite(point, "the cylinder's point")?;
                nonzero(axis, "the cylinder's axis")?;
                if radius.is_finite() && radius > 0.0 {
                    Ok(())
                } else {
                    Err(SelectError::BadRadius(radius))
                }
            }
            Surface::Plane { point, normal } => {
                finite(point, "the plane's point")?;
                nonzero(normal, "the plane's normal")
            }
        }
    }

    /// Distance of `p` from the surface (of a surface that passes [`Surface::check`]).
    pub fn distance(&self, p: [f64; 3]) -> f64 {
        match *self {
            Surface::Cylinder {
                point,
                axis,
                radius,
            } => {
                let a = unit(axis);
                let d = sub(p, point);
                let along = dot(d, a);
                let r = (dot(d, d) - along * along).max(0.0).sqrt();
                (r - radius).abs()
            }
            Surface::Plane { point, normal } => dot(sub(p, point), unit(normal)).abs(),
        }
    }
}

/// A boundary face of any shape: its sorted corners (the last `u32::MAX` for a triangle)
/// and its nodes in the element's face order.
type Keyed = ([u32; 4], (usize, ElementFace, [u32; 8]));

/// Every face of every element, counted by its sorted corners.
fn face_counts(mesh: &Mesh) -> HashMap<[u32; 4], (usize, ElementFace, [u32; 8])> {
    let mut seen: HashMap<[u32; 4], (usize, ElementFace, [u32; 8])> = HashMap::new();
    for (kind, range) in mesh.blocks.kinds() {
        let faces = kind.faces();
        for e in range {
            let Some((_, el)) = mesh.blocks.get(e) else {
                continue;
            };
            for f in faces {
                let local = f.nodes();
                let mut nodes = [0u32; 8];
                for (k, &a) in local.iter().enumerate() {
                    nodes[k] = el[a];
                }
                let mut key = [u32::MAX; 4];
                key[..f.corners()].copy_from_slice(&nodes[..f.corners()]);
                key.sort_unstable();
                seen.entry(key)
                    .and_modify(|e| e.0 += 1)
                    .or_insert((1, *f, nodes));
            }
        }
    }
    seen
}

/// The faces met once, in a fixed order (by their sorted corners).
fn once(mesh: &Mesh) -> Vec<Keyed> {
    let mut out: Vec<Keyed> = face_counts(mesh)
        .into_iter()
        .filter(|(_, (count, _, _))| *count == 1)
        .collect();
    out.sort_unstable_by_key(|(k, _)| *k);
    out
}

/// All 6-node triangle boundary faces of a mesh (element faces that belong to one element
/// only), outward, in a fixed order (by their sorted corners). Quadrilateral faces are left
/// out: see [`boundary_quads`].
pub fn boundary_faces(mesh: &Mesh) -> Vec<Face> {
    once(mesh)
        .into_iter()
        .filter(|(_, (_, f, _))| f.kind() == FaceKind::Tri6)
        .map(|(_, (_, _, n))| [n[0], n[1], n[2], n[3], n[4], n[5]])
        .collect()
}

/// All 8-node quadrilateral boundary faces of a mesh (of hexahedra, wedges, pyramids),
/// outward (`[v0, v1, v2, v3, m01, m12, m23, m30]`), in a fixed order.
pub fn boundary_quads(mesh: &Mesh) -> Vec<[u32; 8]> {
    once(mesh)
        .into_iter()
        .filter(|(_, (_, f, _))| f.kind() == FaceKind::Quad8)
        .map(|(_, (_, _, n))| n)
        .collect()
}

/// The quadrilateral boundary faces of `mesh` whose eight nodes are all in `nodes` (all of
/// them with `None`); none for a mesh of tetrahedra.
fn quads_of(mesh: &Mesh, nodes: Option<&[u32]>) -> Vec<[u32; 8]> {
    if mesh.blocks.len() == mesh.blocks.tet10.len() {
        return Vec::new();
    }
    let mut member = vec![nodes.is_none(); mesh.num_nodes()];
    for &n in nodes.unwrap_or(&[]) {
        if let Some(m) = member.get_mut(n as usize) {
            *m = true;
        }
    }
    boundary_quads(mesh)
        .into_iter()
        .filter(|q| q.iter().all(|&n| member[n as usize]))
        .collect()
}

/// A quadrilateral `[v0, v1, v2, v3, m01, m12, m23, m30]` as its two corner triangles
/// `v0 v1 v2` and `v0 v2 v3`, outward, each with the midside nodes of its two quadrilateral
/// edges (and `v0` in the slot of the diagonal's, which has no node): between them they
/// hold the quadrilateral's eight nodes, so that a test on every node (a box) tests them all.
fn quad_halves(q: &[u32; 8]) -> [Face; 2] {
    [
        [q[0], q[1], q[2], q[4], q[5], q[0]],
        [q[0], q[2], q[3], q[6], q[7], q[0]],
    ]
}

/// An [`UnsupportedFace`] error naming `reader` if a quadrilateral boundary face has all its
/// nodes in the node set `nodes` (any order), or, with `nodes == None`, if the mesh has any
/// quadrilateral boundary face.
pub fn triangles_only(
    mesh: &Mesh,
    nodes: Option<&[u32]>,
    reader: &str,
) -> Result<(), UnsupportedFace> {
    if mesh.blocks.len() == mesh.blocks.tet10.len() {
        return Ok(());
    }
    let mut member = vec![nodes.is_none(); mesh.num_nodes()];
    for &n in nodes.unwrap_or(&[]) {
        if let Some(m) = member.get_mut(n as usize) {
            *m = true;
        }
    }
    let quad = boundary_quads(mesh)
        .into_iter()
        .find(|q| q.iter().all(|&n| member.get(n as usize) == Some(&true)));
    match quad {
        None => Ok(()),
        Some(q) => Err(UnsupportedFace {
            reader: reader.to_string(),
            kind: FaceKind::Quad8,
            corners: q[..4]
                .iter()
                .map(|&n| mesh.node_ids[n as usize].to_string())
                .collect::<Vec<_>>()
                .join(", "),
        }),
    }
}

/// The centroid of a face's corners.
pub fn corner_centroid(mesh: &Mesh, face: &Face) -> [f64; 3] {
    let x = |i: usize| mesh.nodes[face[i] as usize];
    std::array::from_fn(|d| (x(0)[d] + x(1)[d] + x(2)[d]) / 3.0)
}

/// The unit outward normal of a face's corner triangle.
pub fn corner_normal(mesh: &Mesh, face: &Face) -> [f64; 3] {
    let x = |i: usize| mesh.nodes[face[i] as usize];
    unit(cross(sub(x(1), x(0)), sub(x(2), x(0))))
}

/// The faces among `faces` whose three corners lie within `tolerance` of `surface`.
pub fn faces_on(
    mesh: &Mesh,
    faces: &[Face],
    surface: &Surface,
    tolerance: f64,
) -> Result<Vec<Face>, SelectError> {
    surface.check()?;
    check_tolerance(tolerance)?;
    Ok(faces
        .iter()
        .filter(|f| {
            f[..3]
                .iter()
                .all(|&n| surface.distance(mesh.nodes[n as usize]) <= tolerance)
        })
        .copied()
        .collect())
}

/// The nodes of the boundary faces of `mesh` that lie on `surface` (within `tolerance`, by
/// their corners): e.g. the clamp as the nodes on the bore of a disc. Sorted and unique.
pub fn nodes_on(mesh: &Mesh, surface: &Surface, tolerance: f64) -> Result<Vec<u32>, SelectError> {
    let faces = faces_on(mesh, &boundary_faces(mesh), surface, tolerance)?;
    Ok(face_nodes(&faces))
}

/// The faces among `faces` whose outward corner normal makes an angle of at most
/// `angle_deg` with `direction(centroid)` (a direction that may vary over the part, e.g. the
/// tangent of a rotation). A face where `direction` is zero or not finite is not selected.
pub fn faces_facing(
    mesh: &Mesh,
    faces: &[Face],
    direction: impl Fn([f64; 3]) -> [f64; 3],
    angle_deg: f64,
) -> Result<Vec<Face>, SelectError> {
    if !(0.0..=180.0).contains(&angle_deg) {
        return Err(SelectError::BadAngle(angle_deg));
    }
    let cos = angle_deg.to_radians().cos();
    Ok(faces
        .iter()
        .filter(|f| {
            let d = direction(corner_centroid(mesh, f));
            if !d.iter().all(|x| x.is_finite()) || dot(d, d) == 0.0 {
                return false;
            }
            dot(corner_normal(mesh, f), unit(d)) >= cos
        })
        .copied()
        .collect())
}

/// The sorted, unique nodes of faces.
pub fn face_nodes(faces: &[Face]) -> Vec<u32> {
    let mut v: Vec<u32> = faces.iter().flatten().copied().collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// The nodes used by an element that lie in the box `[min, max]` (inclusive).
pub fn nodes_in_box(mesh: &Mesh, min: [f64; 3], max: [f64; 3]) -> Result<Vec<u32>, SelectError> {
    check_box(min, max)?;
    let used = mesh.used_nodes();
    Ok((0..mesh.num_nodes() as u32)
        .filter(|&n| {
            let p = mesh.nodes[n as usize];
            used[n as usize] && (0..3).all(|d| p[d] >= min[d] && p[d] <= max[d])
        })
        .collect())
}

/// The faces whose six nodes all lie in the box `[min, max]` (inclusive).
pub fn faces_in_box(
    mesh: &Mesh,
    faces: &[Face],
    min: [f64; 3],
    max: [f64; 3],
) -> Result<Vec<Face>, SelectError> {
    check_box(min, max)?;
    Ok(faces
        .iter()
        .filter(|f| {
            f.iter().all(|&n| {
                let p = mesh.nodes[n as usize];
                (0..3).all(|d| p[d] >= min[d] && p[d] <= max[d])
            })
        })
        .copied()
        .collect())
}

/// The faces whose six nodes are all in the node set `nodes` (sorted), as boundary faces.
pub fn faces_of_set(mesh: &Mesh, faces: &[Face], nodes: &[u32]) -> Vec<Face> {
    let mut member = vec![false; mesh.num_nodes()];
    for &n in nodes {
        if let Some(m) = member.get_mut(n as usize) {
            *m = true;
        }
    }
    faces
        .iter()
        .filter(|f| f.iter().all(|&n| member[n as usize]))
        .copied()
        .collect()
}

/// A circle on a face of a part (a piston's footprint on a pad's back face): the faces whose
/// corner centroid lies within `diameter / 2` of `centre`, measured in the face's plane, and
/// whose plane passes within the rule's tolerance of `centre`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Circle {
    /// The circle's centre, on the face.
    pub centre: [f64; 3],
    /// Its diameter.
    pub diameter: f64,
}

/// A selection rule as a scene states it: a named node set, or boundary faces narrowed by
/// every criterion given (all must hold).
///
/// - `set` alone: the node set itself (its nodes; its faces are the boundary faces with all
///   six nodes in it).
/// - any geometric criterion (`surface`, `bbox`, `facing`, `circle`, possibly with `set`):
///   the boundary faces meeting all of them; the nodes are those faces' nodes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Rule {
    /// A node set of the mesh (ASCII case-insensitive).
    pub set: Option<String>,
    /// Faces whose corners lie on this cylinder or plane (within `tolerance`).
    pub surface: Option<Surface>,
    /// Faces whose six nodes lie in this box `(min, max)`.
    pub bbox: Option<([f64; 3], [f64; 3])>,
    /// Faces whose outward normal is within `angle` degrees of `direction`: `(direction,
    /// angle)`.
    pub facing: Option<([f64; 3], f64)>,
    /// Faces inside this circle.
    pub circle: Option<Circle>,
    /// Only the node of the selected faces nearest this point (a piston point picked by
    /// position: the faces' node with the smallest distance, the lowest index on a tie).
    pub nearest: Option<[f64; 3]>,
    /// Distance tolerance of `surface` and `circle` (mesh length units).
    pub tolerance: f64,
}

/// What a [`Rule`] selects: boundary faces and nodes (sorted, unique).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Selection {
    /// The boundary faces (for a named set: those with all six nodes in it).
    pub faces: Vec<Face>,
    /// The nodes.
    pub nodes: Vec<u32>,
}

impl Rule {
    /// The rule on a named set only.
    pub fn named(set: &str) -> Self {
        Self {
            set: Some(set.to_string()),
            ..Self::default()
        }
    }

    /// Whether the rule has a geometric criterion (else it is a named set).
    pub fn is_geometric(&self) -> bool {
        self.surface.is_some()
            || self.bbox.is_some()
            || self.facing.is_some()
            || self.circle.is_some()
            || self.nearest.is_some()
    }

    /// Checks every criterion (finite numbers, non-zero directions, a positive radius or
    /// diameter, an angle in 0..=180, a non-empty box, a finite non-negative tolerance).
    pub fn check(&self) -> Result<(), SelectError> {
        check_tolerance(self.tolerance)?;
        if let Some(s) = &self.surface {
            s.check()?;
        }
        if let Some((min, max)) = self.bbox {
            check_box(min, max)?;
        }
        if let Some((d, angle)) = self.facing {
            nonzero(d, "the facing direction")?;
            if !(0.0..=180.0).contains(&angle) {
                return Err(SelectError::BadAngle(angle));
            }
        }
        if let Some(c) = self.circle {
            finite(c.centre, "the circle's centre")?;
            if !(c.diameter.is_finite() && c.diameter > 0.0) {
                return Err(SelectError::BadDiameter(c.diameter));
            }
        }
        if let Some(p) = self.nearest {
            finite(p, "the piston point")?;
        }
        Ok(())
    }

    /// The faces among `faces` that meet the rule's geometric criteria.
    fn filter(&self, mesh: &Mesh, mut faces: Vec<Face>) -> Result<Vec<Face>, SelectError> {
        if let Some(s) = &self.surface {
            faces = faces_on(mesh, &faces, s, self.tolerance)?;
        }
        if let Some((min, max)) = self.bbox {
            faces = faces_in_box(mesh, &faces, min, max)?;
        }
        if let Some((d, angle)) = self.facing {
            faces = faces_facing(mesh, &faces, |_| d, angle)?;
        }
        if let Some(c) = self.circle {
            faces.retain(|f| in_circle(mesh, f, &c, self.tolerance));
        }
        Ok(faces)
    }

    /// The faces and nodes of `mesh` the rule selects; `boundary` are the mesh's
    /// [`boundary_faces`] (computed once by the caller for several rules).
    pub fn apply(&self, mesh: &Mesh, boundary: &[Face]) -> Result<Selection, SelectError> {
        self.check()?;
        let named = match &self.set {
            Some(name) => Some(mesh.node_set(name).ok_or_else(|| SelectError::MissingSet {
                name: name.clone(),
                known: if mesh.node_sets.is_empty() {
                    "none".into()
                } else {
                    mesh.node_sets
                        .keys()
                        .cloned()
                        .collect::<Vec<_>>()
                        .join(", ")
                },
            })?),
            None => None,
        };
        let mut faces = match named {
            Some(nodes) => faces_of_set(mesh, boundary, nodes),
            None => boundary.to_vec(),
        };
        if !self.is_geometric() {
            return Ok(Selection {
                faces,
                nodes: named
                    .map(<[u32]>::to_vec)
                    .unwrap_or_else(|| face_nodes(boundary)),
            });
        }
        let quads = quads_of(mesh, named);
        faces = self.filter(mesh, faces)?;
        let mut nodes = face_nodes(&faces);
        if !quads.is_empty() {
            // A quadrilateral is selected when both its corner triangles are (module docs).
            let halves: Vec<Face> = quads.iter().flat_map(quad_halves).collect();
            let mut kept = self.filter(mesh, halves)?;
            kept.sort_unstable();
            let selected =
                |q: &[u32; 8]| quad_halves(q).iter().all(|h| kept.binary_search(h).is_ok());
            nodes.extend(quads.iter().filter(|q| selected(q)).flatten());
            nodes.sort_unstable();
            nodes.dedup();
        }
        if let Some(p) = self.nearest {
            let d = |n: u32| {
                let q = sub(mesh.nodes[n as usize], p);
                dot(q, q)
            };
            let best = nodes
                .iter()
                .copied()
                .min_by(|&a, &b| d(a).total_cmp(&d(b)).then(a.cmp(&b)));
            return Ok(Selection {
                faces: Vec::new(),
                nodes: best.into_iter().collect(),
            });
        }
        Ok(Selection { faces, nodes })
    }
}

/// Whether a face's corner centroid is inside `circle` (in the face's plane) and the face's
/// plane passes within `tolerance` of the circle's centre.
fn in_circle(mesh: &Mesh, face: &Face, circle: &Circle, tolerance: f64) -> bool {
    let n = corner_normal(mesh, face);
    let d = sub(corner_centroid(mesh, face), circle.centre);
    let off = dot(d, n);
    let in_plane = sub(d, n.map(|x| x * off));
    off.abs() <= tolerance && dot(in_plane, in_plane).sqrt() <= 0.5 * circle.diameter
}

fn fmt3(v: [f64; 3]) -> String {
    format!("[{}, {}, {}]", v[0], v[1], v[2])
}

impl std::fmt::Display for Rule {
    /// A canonical description, e.g. `set CLAMP` or `plane point [0, 0, -0.035] normal [0, 0,
    /// -1] tol 1e-9 & facing [0, 0, -1] within 1 deg`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut parts = Vec::new();
        if let Some(s) = &self.set {
            parts.push(format!("set {s}"));
        }
        match self.surface {
            Some(Surface::Cylinder {
                point,
                axis,
                radius,
            }) => parts.push(format!(
                "cylinder point {} axis {} radius {radius} tol {:e}",
                fmt3(point),
                fmt3(axis),
                self.tolerance
            )),
            Some(Surface::Plane { point, normal }) => parts.push(format!(
                "plane point {} normal {} tol {:e}",
                fmt3(point),
                fmt3(normal),
                self.tolerance
            )),
            None => {}
        }
        if let Some((min, max)) = self.bbox {
            parts.push(format!("box {} .. {}", fmt3(min), fmt3(max)));
        }
        if let Some((d, a)) = self.facing {
            parts.push(format!("facing {} within {a} deg", fmt3(d)));
        }
        if let Some(c) = self.circle {
            parts.push(format!(
                "circle centre {} diameter {} tol {:e}",
                fmt3(c.centre),
                c.diameter,
                self.tolerance
            ));
        }
        if let Some(p) = self.nearest {
            parts.push(format!("node nearest {}", fmt3(p)));
        }
        if parts.is_empty() {
            parts.push("all boundary faces".into());
        }
        f.write_str(&parts.join(" & "))
    }
}

/// Six-point degree-4 rule on the reference triangle (Dunavant): area coordinates
/// `(L1, L2, L3)` and weights summing to 1.
const TRI6: [([f64; 3], f64); 6] = {
    const A: f64 = 0.445_948_490_915_965;
    const WA: f64 = 0.223_381_589_678_011;
    const B: f64 = 0.091_576_213_509_771;
    const WB: f64 = 0.109_951_743_655_322;
    [
        ([1.0 - 2.0 * A, A, A], WA),
        ([A, 1.0 - 2.0 * A, A], WA),
        ([A, A, 1.0 - 2.0 * A], WA),
        ([1.0 - 2.0 * B, B, B], WB),
        ([B, 1.0 - 2.0 * B, B], WB),
        ([B, B, 1.0 - 2.0 * B], WB),
    ]
};

/// Position and area element `|dx/dxi x dx/deta|` of a 6-node face at area coordinates `l`
/// (corners `a, b, c` at `L1, L2, L3 = 1`; midsides `ab, bc, ca`).
fn face_point(mesh: &Mesh, face: &Face, l: [f64; 3]) -> ([f64; 3], f64) {
    let [l1, l2, l3] = l;
    let n = [
        l1 * (2.0 * l1 - 1.0),
        l2 * (2.0 * l2 - 1.0),
        l3 * (2.0 * l3 - 1.0),
        4.0 * l1 * l2,
        4.0 * l2 * l3,
        4.0 * l3 * l1,
    ];
    // xi = L2, eta = L3, L1 = 1 - xi - eta.
    let dxi = [
        -(4.0 * l1 - 1.0),
        4.0 * l2 - 1.0,
        0.0,
        4.0 * (l1 - l2),
        4.0 * l3,
        -4.0 * l3,
    ];
    let deta = [
        -(4.0 * l1 - 1.0),
        0.0,
        4.0 * l3 - 1.0,
        -4.0 * l2,
        4.0 * l2,
        4.0 * (l1 - l3),
    ];
    let (mut x, mut a, mut b) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    for (k, &node) in face.iter().enumerate() {
        let p = mesh.nodes[node as usize];
        for d in 0..3 {
            x[d] += n[k] * p[d];
            a[d] += dxi[k] * p[d];
            b[d] += deta[k] * p[d];
        }
    }
    let c = cross(a, b);
    (x, dot(c, c).sqrt())
}

/// What a face selection covers: how many faces and nodes, the area, and the area centroid
/// (of the quadratic faces, by a degree-4 rule: exact for flat straight-sided faces).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceSummary {
    /// Number of faces.
    pub faces: usize,
    /// Number of distinct nodes of the faces.
    pub nodes: usize,
    /// Total area (mesh units squared).
    pub area: f64,
    /// Area centroid (`[NaN; 3]` for an empty selection).
    pub centroid: [f64; 3],
}

/// The area of a 6-node face (quadratic geometry, degree-4 rule).
pub fn face_area(mesh: &Mesh, face: &Face) -> f64 {
    TRI6.iter()
        .map(|&(l, w)| 0.5 * w * face_point(mesh, face, l).1)
        .sum()
}

/// Counts, area and centroid of a face selection, for reports such as a listing of what a
/// scene selects.
pub fn summarize(mesh: &Mesh, faces: &[Face]) -> FaceSummary {
    let (mut area, mut moment) = (0.0, [0.0; 3]);
    for f in faces {
        for &(l, w) in &TRI6 {
            let (x, da) = face_point(mesh, f, l);
            let wa = 0.5 * w * da;
            area += wa;
            for d in 0..3 {
                moment[d] += wa * x[d];
            }
        }
    }
    FaceSummary {
        faces: faces.len(),
        nodes: face_nodes(faces).len(),
        area,
        centroid: if faces.is_empty() {
            [f64::NAN; 3]
        } else {
            moment.map(|m| m / area)
        },
    }
}

#[cfg(test)]
mod tests;
