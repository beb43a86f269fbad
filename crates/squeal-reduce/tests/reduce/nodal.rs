//! The nodal interface (node-to-surface contact, `squeal_reduce::interface::nodal`) on the
//! bundled coarse meshes, as they are and with the pad turned and lifted off the disc so that
//! no pad node lies on a disc node.

// Index loops over the three directions read like the formulas they check.
#![allow(clippy::needless_range_loop)]

use super::common;

use common::{coarse, coarse_inputs};
use squeal_reduce::brake::{LoadedPart, ModeChoice, reduce_brake_loaded};
use squeal_reduce::interface::footprint;
use squeal_reduce::interface::nodal::{contact_face_nodes, face_nodes, project_pad};
use squeal_reduce::rom::{InterfaceKind, PointRole};

/// The bundled contact faces: 50 degrees (65 to 115) of the annulus 85..135 mm at z = 20 mm.
const R: [f64; 2] = [0.085, 0.135];
const THETA_DEG: [f64; 2] = [65.0, 115.0];

/// The pad turned by `degrees` about the z axis and lifted by `lift` (m) along it.
fn moved(mut pad: LoadedPart, degrees: f64, lift: f64) -> LoadedPart {
    let (s, c) = degrees.to_radians().sin_cos();
    for x in &mut pad.mesh.nodes {
        *x = [c * x[0] - s * x[1], s * x[0] + c * x[1], x[2] + lift];
    }
    pad
}

#[test]
fn every_coarse_pad_face_node_pairs_with_areas_summing_to_the_face() {
    let disc = coarse("disc");
    let pad = coarse("pad");
    let face = face_nodes(&pad.mesh, "CONTACT_FACE").unwrap();
    let pairs = project_pad(&disc.mesh, "CONTACT_FACE", &pad.mesh, "CONTACT_FACE").unwrap();
    // Every node of the pad's face that carries a share of a uniform pressure (the 258
    // midside nodes of its 6-node triangles; its 97 corners carry none) is paired.
    let contact = contact_face_nodes(&pad.mesh, "CONTACT_FACE").unwrap();
    assert_eq!((face.len(), contact.len(), pairs.len()), (355, 258, 258));
    for (c, p) in contact.iter().zip(&pairs) {
        assert_eq!((Some(c.node), c.area), (p.pad.node(), p.pad.area));
    }
    // The lumped areas partition the face: their sum against the face's area integrated by
    // the whole triangles' degree-4 rule. The face is flat with curved (quadratic) edges, so
    // the area Jacobian is a quadratic and both are exact: round-off (measured below).
    let total: f64 = face.iter().map(|n| n.area).sum();
    let area = footprint(&pad.mesh, "CONTACT_FACE").unwrap().area;
    let exact = 0.5 * (THETA_DEG[1] - THETA_DEG[0]).to_radians() * (R[1] * R[1] - R[0] * R[0]);
    eprintln!(
        "areas: lumped sum {total:.15e}, face {area:.15e} ({:.1e}), annulus sector {exact:.6e}",
        total / area - 1.0
    );
    assert!((total / area - 1.0).abs() < 1e-14, "{total} vs {area}");
    assert!(face.iter().all(|n| n.area > 0.0));
    // So do the contact points' areas (the edge-midpoint rule is exact for the quadratic
    // area Jacobian of a flat face with curved edges): round-off.
    let shares: f64 = contact.iter().map(|n| n.area).sum();
    eprintln!(
        "contact areas: sum {shares:.15e} ({:.1e})",
        shares / area - 1.0
    );
    assert!((shares / area - 1.0).abs() < 1e-14, "{shares} vs {area}");
    // The meshes touch: pad and disc faces both lie on z = 20 mm, so every gap measured by
    // projection is 0 up to the round-off of coordinates of 0.1 m (1e-17 measured).
    let worst_gap = pairs
        .iter()
        .map(|p| p.projection.gap.abs())
        .fold(0.0, f64::max);
    let worst_out = pairs
        .iter()
        .map(|p| p.projection.outside)
        .fold(0.0, f64::max);
    let outside = pairs.iter().filter(|p| p.projection.outside > 0.0).count();
    eprintln!(
        "largest |gap| {worst_gap:.1e} m; {outside} nodes beyond the disc face's outline, at most {worst_out:.1e} m"
    );
    assert!(worst_gap < 1e-15, "{worst_gap:e}");
    // The meshes do not match: some pad nodes land on a disc node (a shape-function weight
    // within 1e-6 of 1; the files' coordinates agree to about 1e-12 m, not to the bit, so
    // the other weights are round-off), the others between disc nodes (measured: 211 on a
    // disc node, 144 between).
    let on_node = pairs
        .iter()
        .filter(|p| {
            p.projection
                .weights
                .iter()
                .any(|w| (w.1 - 1.0).abs() < 1e-6)
        })
        .count();
    eprintln!("{on_node} pad nodes land on a disc node");
    assert!(on_node < pairs.len());
    // The two faces' outlines are different quadratic interpolations of the same arcs: a pad
    // node on the outline may fall outside the disc's by the arcs' interpolation error
    // (below 1e-5 m, tests/reduce/interface_bundled.rs); every other node projects inside.
    assert!(worst_out < 1e-5, "{worst_out:e}");
    for p in &pairs {
        let sum: f64 = p.projection.weights.iter().map(|w| w.1).sum();
        assert!((sum - 1.0).abs() < 1e-14);
        // The projected point is the shape functions' combination of the disc nodes.
        let mut y = [0.0; 3];
        for &(n, w) in &p.projection.weights {
            for d in 0..3 {
                y[d] += w * disc.mesh.nodes[n as usize][d];
            }
        }
        for d in 0..3 {
            assert!((y[d] - p.projection.point[d]).abs() < 1e-12);
        }
    }
}

#[test]
fn a_turned_and_lifted_pad_pairs_every_node() {
    // Turned by 0.37 degrees the pad's nodes fall between the disc's (the coarse meshes'
    // elements span about 5 degrees) and the face's radial edge at 115 degrees overhangs the
    // disc face's by up to 0.135 sin(0.37°) = 0.87 mm, beyond the 5% of the patch spacing
    // that pairing by position allows; lifted by 0.1 mm, the gap of the third-party
    // brake.
    let (turn, lift) = (0.37, 1e-4);
    let disc = coarse("disc");
    let pad = moved(coarse("pad"), turn, lift);
    let pairs = project_pad(&disc.mesh, "CONTACT_FACE", &pad.mesh, "CONTACT_FACE").unwrap();
    assert_eq!(pairs.len(), 258);
    // Pairs inside the disc face landing on a disc node (one weight).
    let on_disc_node = pairs
        .iter()
        .filter(|p| p.projection.outside == 0.0 && p.projection.weights.len() == 1)
        .count();
    let mut worst_gap: f64 = 0.0;
    let mut worst_edge: f64 = 0.0;
    let mut beyond = 0;
    for p in &pairs {
        let x = p.pad.position;
        // The faces are flat: every gap is the lift (round-off of 0.02 m: 1e-17).
        worst_gap = worst_gap.max((p.projection.gap - lift).abs());
        let phi = x[1].atan2(x[0]).to_degrees();
        if phi > THETA_DEG[1] + 1e-9 {
            // Beyond the disc face's straight radial edge at 115 degrees: paired with the
            // nearest point of that edge, r sin δ away in the face's plane (δ = φ − 115°),
            // where the foot of the perpendicular, at radius r cos δ, lies on the edge; the
            // node at the inner radius has its foot inside 85 mm, off the edge, and goes to
            // the face's corner, 2 r sin(δ/2) away.
            beyond += 1;
            let r = x[0].hypot(x[1]);
            let delta = (phi - THETA_DEG[1]).to_radians();
            let expected = if r * delta.cos() < R[0] {
                2.0 * r * (0.5 * delta).sin()
            } else {
                r * delta.sin()
            };
            worst_edge = worst_edge.max((p.projection.outside - expected).abs());
            assert!(p.projection.outside > 0.0);
        }
    }
    eprintln!(
        "turned {turn} deg, lifted {lift} m: {} pairs, {on_disc_node} on a disc node, {beyond} beyond the radial edge (outside distance within {worst_edge:.1e} m of r sin), gaps within {worst_gap:.1e} m of the lift",
        pairs.len()
    );
    assert!(beyond > 0);
    // Turned, no pad node inside the disc face lands on a disc node (163 of the 355 do on
    // the meshes as they are).
    assert_eq!(on_disc_node, 0);
    assert!(worst_gap < 1e-15, "{worst_gap:e}");
    // Straight edges: the distance to the edge is exact to round-off of the coordinates.
    assert!(worst_edge < 1e-12, "{worst_edge:e}");
}

#[test]
fn a_pad_off_the_disc_is_refused_naming_the_distance() {
    let disc = coarse("disc");
    // Turned by 60 degrees: the pad lies next to the disc face, not over it.
    let pad = moved(coarse("pad"), 60.0, 0.0);
    let e = project_pad(&disc.mesh, "CONTACT_FACE", &pad.mesh, "CONTACT_FACE").unwrap_err();
    let text = e.to_string();
    eprintln!("{text}");
    assert!(text.contains("projects onto the disc face") && text.contains(" m beyond"));
    // Lifted by 0.2 m (a mesh in mm read as m would be far worse): refused by the gap.
    let pad = moved(coarse("pad"), 0.0, 0.2);
    let text = project_pad(&disc.mesh, "CONTACT_FACE", &pad.mesh, "CONTACT_FACE")
        .unwrap_err()
        .to_string();
    eprintln!("{text}");
    assert!(text.contains("same units"), "{text}");
}

#[test]
fn the_reduced_brake_keeps_every_face_node_and_pairs_each_pad_node() {
    // The turned and lifted pad, reduced with 10 modes per part (the layout does not depend
    // on the count).
    let mut inputs = coarse_inputs(InterfaceKind::Nodal);
    inputs.modes = ModeChoice::Fixed(10);
    let pad = moved(coarse("pad"), 0.37, 1e-4);
    let (model, report) =
        reduce_brake_loaded(&inputs, coarse("disc"), vec![pad], &mut |_, _| {}).unwrap();
    let disc = model.part("disc").unwrap();
    let pad = model.part("pad").unwrap();
    let count = |p: &squeal_reduce::rom::ReducedPart, role: PointRole| {
        p.info.points.iter().filter(|q| q.role == role).count()
    };
    let disc_face = face_nodes(&coarse("disc").mesh, "CONTACT_FACE")
        .unwrap()
        .len();
    // The pad's contact points: the 258 midside nodes of its friction face.
    assert_eq!(count(pad, PointRole::Contact), 258);
    assert_eq!(count(disc, PointRole::Face), disc_face);
    assert_eq!(count(disc, PointRole::Contact), 258);
    // 3 dofs per disc face node and per pad contact point, 4 pistons, 10 modes each.
    assert_eq!(disc.size(), 3 * disc_face + 10);
    assert_eq!(pad.size(), 3 * 258 + 4 + 10);
    eprintln!(
        "reduced nodal brake: disc {} + pad {} = {} dofs ({disc_face} disc face nodes, 258 pad contact points)",
        disc.size(),
        pad.size(),
        model.size()
    );
    assert_eq!(report.pairs.len(), 258);
    for (k, pair) in report.pairs.iter().enumerate() {
        assert_eq!(pair.disc_point, k);
        let p = disc
            .info
            .points
            .iter()
            .filter(|q| q.role == PointRole::Contact)
            .nth(k)
            .unwrap();
        let proj = p.projected.as_ref().unwrap();
        assert_eq!(proj.pad, "pad");
        // Each weight names a disc face point.
        for &(i, _) in &proj.weights {
            assert_eq!(disc.info.points[i].role, PointRole::Face);
        }
        // The pair's area is the pad node's.
        assert_eq!(p.area, pad.info.points[proj.pad_point].area);
    }
}
