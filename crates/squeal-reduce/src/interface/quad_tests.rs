//! The interface models on 8-node quadrilateral faces (hex20 meshes).

use super::face::{Shape, SurfaceFace, map_point};
use super::nodal::{Surface, face_nodes};
use super::{Axis, footprint, patches};
use squeal_element::ElementKind;
use squeal_element::geometry::{dot, norm, sub};
use squeal_mesh::Mesh;
use squeal_mesh::generate::box_solid;

/// A hex20 box with its top face as node set `F`.
fn hex_box(lengths: [f64; 3], cells: [usize; 3]) -> Mesh {
    let mut mesh = box_solid(ElementKind::Hex20, lengths, cells);
    let face = mesh.node_set("ZMAX").unwrap().to_vec();
    mesh.node_sets.insert("F".into(), face);
    mesh
}

#[test]
fn lumped_areas_of_a_flat_quad8_face_partition_it_with_a_24th_at_corners() {
    // A 2 x 1 face meshed 4 x 2: every quadrilateral a 0.5 x 0.5 square (A = 1/4), so the
    // lumped areas are A/24 per corner and 5A/24 per midside node of each face they belong
    // to (module docs of `nodal`); the degree-4 rule is exact on flat faces: round-off.
    let mesh = hex_box([2.0, 1.0, 0.1], [4, 2, 1]);
    let nodes = face_nodes(&mesh, "F").unwrap();
    let total: f64 = nodes.iter().map(|n| n.area).sum();
    assert!((total - 2.0).abs() < 1e-14, "total {total}");
    assert_eq!(nodes.len(), 5 * 3 + 4 * 3 + 5 * 2);
    let at = |x: f64, y: f64| {
        nodes
            .iter()
            .find(|n| {
                let p = mesh.nodes[n.node as usize];
                (p[0] - x).abs() < 1e-12 && (p[1] - y).abs() < 1e-12
            })
            .unwrap()
    };
    for n in &nodes {
        assert!(n.area > 0.0 && (n.normal[2] - 1.0).abs() < 1e-14);
    }
    let a = 0.25;
    // The face's corner: one quadrilateral.
    assert!((at(0.0, 0.0).area - a / 24.0).abs() < 1e-16);
    // An interior corner node: four quadrilaterals.
    assert!((at(0.5, 0.5).area - 4.0 * a / 24.0).abs() < 1e-16);
    // An interior midside node: two quadrilaterals.
    assert!((at(0.75, 0.5).area - 2.0 * 5.0 * a / 24.0).abs() < 1e-15);
}

#[test]
fn lumped_areas_of_a_distorted_flat_quad8_face_still_sum_to_its_area() {
    // The interior nodes of the top face moved in its plane (corners and midsides by
    // different amounts, so the quadrilaterals are no longer parallelograms and their edges
    // are curved): the face's outline, and so its area 2, are unchanged; each sub-cell's area
    // is still integrated exactly (a flat serendipity face's area element is of degree ≤ 4),
    // so the sum is the area to round-off, and every lumped area stays positive.
    let mut mesh = hex_box([2.0, 1.0, 0.1], [4, 2, 1]);
    let top = mesh.node_set("F").unwrap().to_vec();
    for &n in &top {
        let p = mesh.nodes[n as usize];
        let interior = p[0] > 1e-9 && p[0] < 2.0 - 1e-9 && p[1] > 1e-9 && p[1] < 1.0 - 1e-9;
        if interior {
            let (dx, dy) = ((7.0 * p[1] + 3.0 * p[0]).sin(), (5.0 * p[0]).cos());
            mesh.nodes[n as usize] = [p[0] + 0.04 * dx, p[1] + 0.04 * dy, p[2]];
        }
    }
    let nodes = face_nodes(&mesh, "F").unwrap();
    let total: f64 = nodes.iter().map(|n| n.area).sum();
    assert!((total - 2.0).abs() < 1e-13, "total {total}");
    assert!(nodes.iter().all(|n| n.area > 0.0));
    // The footprint (whole-face 3 x 3 Gauss rule) agrees: both exact.
    let whole = footprint(&mesh, "F").unwrap();
    assert!((whole.area - 2.0).abs() < 1e-13, "{}", whole.area);
    let w: f64 = whole.weights.iter().map(|w| w.1).sum();
    assert!((w - 1.0).abs() < 1e-14);
}

/// The hex20 box bent onto the cylinder of radius `r` about the y axis: `(x, y, z)` goes to
/// `((r + z) sin(x/r), y, (r + z) cos(x/r))`, so the top face (z = h) is curved.
fn bent(mut mesh: Mesh, r: f64) -> Mesh {
    for p in &mut mesh.nodes {
        let (s, c) = (p[0] / r).sin_cos();
        *p = [(r + p[2]) * s, p[1], (r + p[2]) * c];
    }
    mesh
}

#[test]
fn projection_onto_a_curved_quad8_face_is_the_closest_point() {
    // A face curved in one direction (radius 0.3 m across 0.2 m): the projection of points
    // off it (above, below, beyond an edge) against a brute-force zooming
    // search over every face's reference square (below). The Newton point must be no farther
    // than the search's best point (a search can only be worse than the minimum) and within
    // 1e-9 relative of it (the search's resolution, 1e-9 of the reference square, enters the
    // distance quadratically at a smooth minimum and linearly at a boundary one).
    let mesh = bent(hex_box([0.2, 0.1, 0.02], [4, 2, 1]), 0.3);
    let surface = Surface::new(&mesh, "F").unwrap();
    let faces = super::boundary_faces_of(&mesh, mesh.node_set("F").unwrap());
    assert!(faces.iter().all(|f| f.shape == Shape::Quad8) && faces.len() == 8);
    // The reference: on every face a 101 x 101 grid of its reference square, then eight
    // zooms by 10 about the best point (a 21 x 21 grid each): the minimum to ~1e-12 m where
    // it is smooth, or the best corner/edge point where the minimum is on the boundary.
    let brute = |x: [f64; 3]| {
        let mut best = f64::INFINITY;
        for f in &faces {
            let c = f.coords(&mesh);
            let d = |st: [f64; 2]| norm(sub(x, map_point(Shape::Quad8, &c, st).1));
            let (mut centre, mut half, mut n) = ([0.0, 0.0], 1.0, 50);
            for _ in 0..9 {
                let mut local = (f64::INFINITY, centre);
                for i in 0..=2 * n {
                    for j in 0..=2 * n {
                        let st = [
                            (centre[0] + half * (i as f64 / n as f64 - 1.0)).clamp(-1.0, 1.0),
                            (centre[1] + half * (j as f64 / n as f64 - 1.0)).clamp(-1.0, 1.0),
                        ];
                        let v = d(st);
                        if v < local.0 {
                            local = (v, st);
                        }
                    }
                }
                centre = local.1;
                best = best.min(local.0);
                half /= 10.0;
                n = 10;
            }
        }
        best
    };
    let r_top = 0.32;
    for (angle, y, lift) in [
        (0.1, 0.03, 0.004),
        (0.27, 0.071, -0.003),
        (0.05, 0.0, 0.01),
        (0.36, 0.05, 0.002),
    ] {
        let x = [
            (r_top + lift) * f64::sin(angle),
            y,
            (r_top + lift) * f64::cos(angle),
        ];
        let p = surface.project(x);
        let reference = brute(x);
        eprintln!(
            "x {x:?}: Newton {:.12e} brute force {reference:.12e} gap {:.6e} outside {:.3e}",
            p.distance, p.gap, p.outside
        );
        assert!(p.distance <= reference * (1.0 + 1e-12), "{p:?}");
        assert!(p.distance >= reference * (1.0 - 1e-9), "{p:?}");
        let sum: f64 = p.weights.iter().map(|w| w.1).sum();
        assert!((sum - 1.0).abs() < 1e-14);
        if angle * 0.3 < 0.2 {
            // Over the face: the gap is the lift to the circle's faceting (the quad8's
            // quadratic edges follow the arc of 0.05/0.3 rad to r θ⁴/… ≈ 1e-6 m).
            assert_eq!(p.outside, 0.0);
            assert!((p.gap - lift).abs() < 2e-6, "gap {} lift {lift}", p.gap);
            // Stationary: x − X is along the normal.
            let r = sub(x, p.point);
            assert!((norm(r) - dot(r, p.normal).abs()) < 1e-12 * norm(r).max(1e-3));
        } else {
            assert!(p.outside > 0.0);
        }
    }
}

#[test]
fn patches_of_a_quad8_face_match_the_face_split_as_triangles() {
    // A flat annular sector meshed with quadrilaterals (a hex20 box bent about the z axis:
    // its top face is flat, its edges arcs): the 3 x 3 patches from the quadrilateral faces
    // against the exact sector areas. The cuts at a third of the radius and angle range do
    // not fall on mesh lines (5 x 7 cells), so faces are clipped: the patch areas are exact
    // only to the clipping's interpolation of the cut on a quadrilateral's half (`add_half`:
    // a quadratic level function on a half whose map is cubic), an error of the mesh's order:
    // 1.4e-5 relative measured on these 10 mm x 8.6 degree faces, 5e-5 allowed.
    let mut mesh = hex_box([0.05, 0.06, 0.01], [5, 7, 1]);
    let (r0, t0) = (0.085, 1.2);
    for p in &mut mesh.nodes {
        let (r, t) = (r0 + p[0], t0 + p[1] / 0.1);
        *p = [r * t.cos(), r * t.sin(), p[2]];
    }
    let ps = patches(&mesh, "F", 3, 3, &Axis::default()).unwrap();
    let dr = 0.05 / 3.0;
    let dt = 0.6 / 3.0;
    let mut total = 0.0;
    for p in &ps {
        let ring = (p.number - 1) / 3;
        let (a, b) = (r0 + ring as f64 * dr, r0 + (ring + 1) as f64 * dr);
        let exact = 0.5 * dt * (b * b - a * a);
        let err = (p.area / exact - 1.0).abs();
        eprintln!(
            "patch {}: {:.9e} exact {exact:.9e} ({err:.1e})",
            p.number, p.area
        );
        assert!(err < 5e-5, "patch {} off by {err:.1e}", p.number);
        let w: f64 = p.weights.iter().map(|w| w.1).sum();
        assert!((w - 1.0).abs() < 1e-13);
        total += p.area;
    }
    // The patches partition the face: their sum is the quadrilaterals' area, whose edges
    // (quadratic arcs) differ from the sector's by the faceting, 1e-6 here.
    let sector = 0.5 * 0.6 * ((r0 + 0.05).powi(2) - r0 * r0);
    assert!((total / sector - 1.0).abs() < 1e-6, "{total} vs {sector}");
    let whole = footprint(&mesh, "F").unwrap().area;
    assert!((total / whole - 1.0).abs() < 1e-13);
}

#[test]
fn a_surface_face_keeps_its_nodes() {
    let f = SurfaceFace::tri6([1, 2, 3, 4, 5, 6]);
    assert_eq!(f.nodes(), &[1, 2, 3, 4, 5, 6]);
    assert_eq!(SurfaceFace::quad8([0; 8]).node_count(), 8);
}
