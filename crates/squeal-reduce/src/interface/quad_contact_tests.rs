//! The pad's contact points on 8-node faces ([`super::quad_contact`]): a rigid hex20 pad's
//! bounce and rocking stiffness on its contact springs against the continuous spring bed, the
//! lumped rule's `O(h²)` error beside them, a curved face's area, and the 6-node faces' points
//! unchanged.

use super::nodal::{contact_face_nodes, face_nodes};
use super::quad_contact::{ContactPoint, QuadRule, combined_nodes, contact_points_with};
use squeal_element::ElementKind;
use squeal_mesh::Mesh;
use squeal_mesh::generate::{box_solid, box_tet10_origin};

/// A box of `kind` elements with its top face as node set `F`.
fn solid_box(kind: ElementKind, lengths: [f64; 3], cells: [usize; 3]) -> Mesh {
    let mut mesh = box_solid(kind, lengths, cells);
    let face = mesh.node_set("ZMAX").unwrap().to_vec();
    mesh.node_sets.insert("F".into(), face);
    mesh
}

/// `Σ A_q f(x_q)`.
fn moment(points: &[ContactPoint], f: impl Fn([f64; 3]) -> f64) -> f64 {
    points.iter().map(|p| p.area * f(p.position)).sum()
}

/// The relative errors of a rule's bounce stiffness and rocking stiffness about `x = cx` and
/// `y = cy` against `exact` (area and the two second moments).
fn stiffness_errors(points: &[ContactPoint], c: [f64; 2], exact: [f64; 3]) -> [f64; 3] {
    [
        moment(points, |_| 1.0) / exact[0] - 1.0,
        moment(points, |x| (x[0] - c[0]).powi(2)) / exact[1] - 1.0,
        moment(points, |x| (x[1] - c[1]).powi(2)) / exact[2] - 1.0,
    ]
}

#[test]
fn a_rigid_hex20_pad_on_its_gauss_points_has_the_exact_bounce_and_rocking_stiffness() {
    // A rigid flat pad on springs κ A_q at its contact points: bounce stiffness κ Σ A_q,
    // rocking stiffness about the face centre's y axis κ Σ A_q (x_q − 1)² (and x likewise);
    // the continuous bed κ per unit area on the 2 x 1 face gives κ A = 2κ,
    // κ ∫ (x − 1)² dA = 2κ/3, κ ∫ (y − 1/2)² dA = κ/6. The 2 × 2 and 3 × 3 Gauss rules are
    // exact for quadratics on these square faces: asserted to 1e-14 relative on 1 x 1, 2 x 1
    // and 4 x 2 cell grids (a pad one, two and four elements long). The lumped sub-cell areas
    // (A/24 at corners, 5A/24 at midside nodes) are exact for linear functions only: their
    // rocking stiffness about y is 7/4 of the bed's on one element (Σ = 4·A/24 + 2·5A/24 at
    // |x − 1| = 1: 7A/12 against A/3), and the error falls as h² (asserted: each halving of
    // the element divides it by 4, to 1e-12).
    let exact = [2.0, 2.0 / 3.0, 1.0 / 6.0];
    let mut lumped = Vec::new();
    for cells in [[1, 1, 1], [2, 1, 1], [4, 2, 1]] {
        let mesh = solid_box(ElementKind::Hex20, [2.0, 1.0, 0.1], cells);
        for rule in [QuadRule::Gauss2, QuadRule::Gauss3] {
            let points = contact_points_with(&mesh, "F", rule).unwrap();
            let e = stiffness_errors(&points, [1.0, 0.5], exact);
            assert!(
                e.iter().all(|e| e.abs() < 1e-14),
                "{rule:?} {cells:?}: {e:?}"
            );
            assert!(points.iter().all(|p| p.area > 0.0 && p.node().is_none()));
        }
        let points = contact_points_with(&mesh, "F", QuadRule::Lumped).unwrap();
        let e = stiffness_errors(&points, [1.0, 0.5], exact);
        // The lumped areas still sum to the face's (a linear function: exact).
        assert!(e[0].abs() < 1e-14, "{e:?}");
        lumped.push(e[1]);
    }
    println!("lumped areas, rocking stiffness about y, relative error: {lumped:?}");
    assert!((lumped[0] - 0.75).abs() < 1e-12, "{lumped:?}");
    assert!((lumped[1] - 0.75 / 4.0).abs() < 1e-12, "{lumped:?}");
    assert!((lumped[2] - 0.75 / 16.0).abs() < 1e-12, "{lumped:?}");
}

#[test]
fn a_trapezoidal_hex20_pad_is_exact_too() {
    // The 2 x 1 box's face sheared into a trapezoid, x' = x (1 + a y): each element's face is
    // a flat quadrilateral with straight edges (the map is bilinear, which the serendipity
    // face reproduces), x' is bilinear in (s, t) and the area element linear, so a quadratic
    // times it has degree 3 in each of s, t: 2 × 2 Gauss is still exact (1e-13). The
    // face is 0 ≤ y ≤ 1, 0 ≤ x' ≤ 2 (1 + a y): area 2 + a, and
    // ∫ (x' − 1)² dA = ∫₀¹ ((1 + 2 a y)³ + 1)/3 dy = ((1 + 2a)⁴ − 1)/(24 a) + 1/3,
    // ∫ (y − ½)² dA = ∫₀¹ 2 (1 + a y)(y − ½)² dy = 1/6 + a/12.
    let a: f64 = 0.3;
    let exact = [
        2.0 + a,
        ((1.0 + 2.0 * a).powi(4) - 1.0) / (24.0 * a) + 1.0 / 3.0,
        1.0 / 6.0 + a / 12.0,
    ];
    for cells in [[1, 1, 1], [3, 2, 1]] {
        let mut mesh = solid_box(ElementKind::Hex20, [2.0, 1.0, 0.1], cells);
        for x in &mut mesh.nodes {
            x[0] *= 1.0 + a * x[1];
        }
        let points = contact_points_with(&mesh, "F", QuadRule::Gauss2).unwrap();
        let e = stiffness_errors(&points, [1.0, 0.5], exact);
        assert!(e.iter().all(|e| e.abs() < 1e-13), "{cells:?}: {e:?}");
        let lumped = contact_points_with(&mesh, "F", QuadRule::Lumped).unwrap();
        let el = stiffness_errors(&lumped, [1.0, 0.5], exact);
        println!("trapezoid {cells:?}: Gauss 2x2 {e:?}, lumped {el:?}");
        assert!(el[1] > 1e-2, "{el:?}");
    }
}

#[test]
fn gauss_points_combine_every_node_of_their_face() {
    // On a 4 x 2 hex20 face every one of its 5·3 + 4·3 + 5·2 = 37 nodes is combined by some
    // Gauss point (all kept as boundary points), each point's weights are its face's shape
    // functions (summing to 1, reproducing its position: round-off of coordinates of 1) and
    // there are four points per face.
    let mesh = solid_box(ElementKind::Hex20, [2.0, 1.0, 0.1], [4, 2, 1]);
    let points = contact_points_with(&mesh, "F", QuadRule::Gauss2).unwrap();
    assert_eq!(points.len(), 4 * 8);
    assert_eq!(
        combined_nodes(&points),
        mesh.node_set("F").unwrap().to_vec()
    );
    for p in &points {
        assert_eq!(p.nodes.len(), 8);
        let sum: f64 = p.nodes.iter().map(|n| n.1).sum();
        assert!((sum - 1.0).abs() < 1e-15);
        for d in 0..3 {
            let x: f64 = p
                .nodes
                .iter()
                .map(|&(n, w)| w * mesh.nodes[n as usize][d])
                .sum();
            assert!((x - p.position[d]).abs() < 1e-15);
        }
        assert!((p.normal[2] - 1.0).abs() < 1e-15);
    }
}

#[test]
fn a_curved_hex20_face_has_the_cylinders_area_to_fourth_order() {
    // The box 1 x 0.5 x 0.1 bent about the y axis onto radii 1.0..1.1 over 1 rad: its top
    // face is the cylinder r = 1.1 over 1 rad and 0.5 wide, area 0.55. The faces interpolate
    // the arcs quadratically and 2 × 2 Gauss integrates their area element: both errors are
    // O(h⁴). Measured (print): 2.16e-5 relative on 2 elements around, 1.35e-6 on 4, 8.5e-8
    // on 8; asserted below 3e-5, 2e-6, 1.2e-7 and each halving dividing the error by more
    // than 14 (16 for h⁴).
    let exact = 1.1 * 1.0 * 0.5;
    let mut errors = Vec::new();
    for n in [2, 4, 8] {
        let mut mesh = solid_box(ElementKind::Hex20, [1.0, 0.5, 0.1], [n, 1, 1]);
        for x in &mut mesh.nodes {
            let (r, phi) = (1.0 + x[2], x[0]);
            *x = [r * phi.sin(), x[1], r * phi.cos()];
        }
        let points = contact_points_with(&mesh, "F", QuadRule::Gauss2).unwrap();
        errors.push((moment(&points, |_| 1.0) / exact - 1.0).abs());
        // Each point's normal is radial to the faces' interpolation error.
        for p in &points {
            let r = p.position[0].hypot(p.position[2]);
            let radial = [p.position[0] / r, 0.0, p.position[2] / r];
            let c: f64 = (0..3).map(|d| radial[d] * p.normal[d]).sum();
            assert!(c > 1.0 - 1e-3, "{c}");
        }
    }
    println!("curved face area, relative error on 2, 4, 8 elements: {errors:?}");
    assert!(
        errors[0] < 3e-5 && errors[1] < 2e-6 && errors[2] < 1.2e-7,
        "{errors:?}"
    );
    assert!(errors[0] / errors[1] > 14.0 && errors[1] / errors[2] > 14.0);
}

#[test]
fn six_node_faces_keep_their_midside_points_to_the_bit() {
    // On a tet10 face the contact points are the edge-midpoint rule's midside nodes, exactly
    // as before Gauss points (same positions, areas and normals, same order): the tet10
    // brakes' results do not move.
    let mut mesh = box_tet10_origin([0.0, 0.0, 0.0], [2.0, 1.0, 0.1], [4, 2, 1]);
    let face = mesh.node_set("ZMAX").unwrap().to_vec();
    mesh.node_sets.insert("F".into(), face);
    let points = contact_points_with(&mesh, "F", QuadRule::Gauss2).unwrap();
    let nodes = contact_face_nodes(&mesh, "F").unwrap();
    assert_eq!(points.len(), nodes.len());
    for (p, n) in points.iter().zip(&nodes) {
        assert_eq!(p.node(), Some(n.node));
        assert_eq!(
            (p.area, p.normal, p.position),
            (n.area, n.normal, mesh.nodes[n.node as usize])
        );
    }
    assert!(combined_nodes(&points).is_empty());
    assert!(face_nodes(&mesh, "F").unwrap().len() > points.len());
}
