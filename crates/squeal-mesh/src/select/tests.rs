use super::*;
use crate::generate::{box_tet10, box_tet10_origin};
use std::f64::consts::PI;

#[test]
fn the_faces_of_a_box_are_found_by_plane_normal_and_box() {
    let mesh = box_tet10([1.0, 2.0, 3.0], [2, 3, 2]);
    let faces = boundary_faces(&mesh);
    // 2 triangles per cell face: 2 (2*3 + 2*2 + 3*2) cells = 32 faces.
    assert_eq!(faces.len(), 2 * 2 * (2 * 3 + 2 * 2 + 3 * 2));
    let top_plane = Surface::Plane {
        point: [0.0, 0.0, 3.0],
        normal: [0.0, 0.0, 1.0],
    };
    let top = faces_on(&mesh, &faces, &top_plane, 1e-12).unwrap();
    assert_eq!(face_nodes(&top), mesh.node_set("ZMAX").unwrap());
    assert_eq!(
        nodes_on(&mesh, &top_plane, 1e-12).unwrap(),
        mesh.node_set("ZMAX").unwrap()
    );
    let facing_up = faces_facing(&mesh, &faces, |_| [0.0, 0.0, 1.0], 1.0).unwrap();
    assert_eq!(facing_up, top);
    // A direction that vanishes selects nothing.
    assert!(
        faces_facing(&mesh, &faces, |_| [0.0; 3], 180.0)
            .unwrap()
            .is_empty()
    );
    let xmin = faces_in_box(&mesh, &faces, [-1.0; 3], [0.0, 9.0, 9.0]).unwrap();
    assert_eq!(face_nodes(&xmin), mesh.node_set("XMIN").unwrap());
    assert_eq!(
        nodes_in_box(&mesh, [-1.0; 3], [0.0, 9.0, 9.0]).unwrap(),
        mesh.node_set("XMIN").unwrap()
    );
    assert_eq!(
        faces_of_set(&mesh, &faces, mesh.node_set("XMIN").unwrap()),
        xmin
    );
    // Flat straight-sided faces: the degree-4 rule is exact, so area and centroid are
    // exact up to round-off (a few ulps of the sums of 12 faces).
    let s = summarize(&mesh, &top);
    assert_eq!((s.faces, s.nodes), (12, 5 * 7));
    assert!((s.area - 2.0).abs() < 1e-14, "{}", s.area);
    for (c, e) in s.centroid.iter().zip([0.5, 1.0, 3.0]) {
        assert!((c - e).abs() < 1e-14, "{:?}", s.centroid);
    }
    let all = summarize(&mesh, &faces);
    assert!((all.area - 2.0 * (2.0 + 3.0 + 6.0)).abs() < 1e-13);
}

/// A general rotation (unit quaternion along (1, 2, 3, 4)).
fn rotation() -> [[f64; 3]; 3] {
    let n = 30f64.sqrt();
    let (w, x, y, z) = (1.0 / n, 2.0 / n, 3.0 / n, 4.0 / n);
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

fn apply(r: &[[f64; 3]; 3], p: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|j| r[i][j] * p[j]).sum())
}

#[test]
fn the_bore_of_a_turned_and_shifted_sector_is_the_cylinder_of_its_inner_radius() {
    // An annular sector r in [0.05, 0.15] m, theta in [0, 60 deg], z in [0, 0.02] m from a
    // box in (r, theta, z) with every node (midside nodes too) mapped onto the curved
    // geometry, then turned by a general rotation and shifted: its axis is the line
    // through `c` along `r e_z`.
    let (r_in, r_out, span, h) = (0.05, 0.15, PI / 3.0, 0.02);
    let mut mesh = box_tet10_origin([r_in, 0.0, 0.0], [r_out - r_in, span, h], [3, 6, 2]);
    let rot = rotation();
    let c = [0.3, -1.2, 0.7];
    for p in &mut mesh.nodes {
        let [r, t, z] = *p;
        let q = apply(&rot, [r * t.cos(), r * t.sin(), z]);
        *p = [q[0] + c[0], q[1] + c[1], q[2] + c[2]];
    }
    let axis = apply(&rot, [0.0, 0.0, 3.0]);
    // Any point of the axis will do.
    let on_axis = [
        c[0] - 2.0 * axis[0],
        c[1] - 2.0 * axis[1],
        c[2] - 2.0 * axis[2],
    ];
    let faces = boundary_faces(&mesh);
    let cylinder = |radius| Surface::Cylinder {
        point: on_axis,
        axis,
        radius,
    };
    // Corners on the bore are at r_in to round-off of coordinates ~1 (~1e-16); the next
    // ring of nodes is 0.1/6 m away, so 1e-12 separates them with room to spare.
    let bore = faces_on(&mesh, &faces, &cylinder(r_in), 1e-12).unwrap();
    assert_eq!(bore.len(), 2 * 6 * 2);
    assert_eq!(face_nodes(&bore), mesh.node_set("XMIN").unwrap());
    assert_eq!(
        nodes_on(&mesh, &cylinder(r_in), 1e-12).unwrap(),
        mesh.node_set("XMIN").unwrap()
    );
    let rim = faces_on(&mesh, &faces, &cylinder(r_out), 1e-12).unwrap();
    assert_eq!(face_nodes(&rim), mesh.node_set("XMAX").unwrap());
    // The bore's faces are quadratic interpolants of the arc (10 degrees a face): the
    // area is r_in span h to the interpolation error, which is of order dtheta^4 (measured
    // -9.6e-7 relative, asserted 1e-5); its centroid is on the bisector at
    // r_in sin(span/2)/(span/2) from the axis, at mid-height (measured 7.0e-7 r_in off,
    // asserted 1e-5 r_in).
    let s = summarize(&mesh, &bore);
    let exact = r_in * span * h;
    assert!((s.area / exact - 1.0).abs() < 1e-5, "{} vs {exact}", s.area);
    let rc = r_in * (span / 2.0).sin() / (span / 2.0);
    let local = [rc * (span / 2.0).cos(), rc * (span / 2.0).sin(), h / 2.0];
    let q = apply(&rot, local);
    for d in 0..3 {
        assert!(
            (s.centroid[d] - (q[d] + c[d])).abs() < 1e-5 * r_in,
            "{:?}",
            s.centroid
        );
    }
    // The end plane theta = 0 by its normal and by a plane through the axis; the bore
    // by its outward normal, which points at the axis.
    let end_normal = apply(&rot, [0.0, -1.0, 0.0]);
    let end = faces_on(
        &mesh,
        &faces,
        &Surface::Plane {
            point: on_axis,
            normal: end_normal,
        },
        1e-12,
    )
    .unwrap();
    assert_eq!(face_nodes(&end), mesh.node_set("YMIN").unwrap());
    assert_eq!(
        faces_facing(&mesh, &faces, |_| end_normal, 1.0).unwrap(),
        end
    );
    let towards_axis = |p: [f64; 3]| {
        let d = [on_axis[0] - p[0], on_axis[1] - p[1], on_axis[2] - p[2]];
        let a = unit(axis);
        let along = dot(d, a);
        [
            d[0] - along * a[0],
            d[1] - along * a[1],
            d[2] - along * a[2],
        ]
    };
    // A face normal on the bore is within half a face's angle (5 deg) of the direction
    // to the axis at its centroid; 6 deg takes them all and nothing else.
    let inward = faces_facing(&mesh, &faces, towards_axis, 6.0).unwrap();
    assert_eq!(inward, bore);
}

#[test]
fn selections_that_cannot_mean_anything_are_errors() {
    let mesh = box_tet10([1.0; 3], [1, 1, 1]);
    let faces = boundary_faces(&mesh);
    let cyl = |axis, radius| Surface::Cylinder {
        point: [0.0; 3],
        axis,
        radius,
    };
    assert_eq!(
        faces_on(&mesh, &faces, &cyl([0.0; 3], 1.0), 0.0),
        Err(SelectError::ZeroDirection {
            what: "the cylinder's axis"
        })
    );
    assert_eq!(
        nodes_on(&mesh, &cyl([0.0, 0.0, 1.0], -1.0), 0.0),
        Err(SelectError::BadRadius(-1.0))
    );
    assert!(matches!(
        faces_on(&mesh, &faces, &cyl([0.0, 0.0, 1.0], 1.0), f64::NAN),
        Err(SelectError::BadTolerance(_))
    ));
    let plane = Surface::Plane {
        point: [0.0; 3],
        normal: [f64::NAN, 0.0, 1.0],
    };
    assert_eq!(
        plane.check(),
        Err(SelectError::NotFinite {
            what: "the plane's normal"
        })
    );
    assert!(matches!(
        nodes_in_box(&mesh, [0.0, 1.0, 0.0], [1.0, 0.5, 1.0]),
        Err(SelectError::EmptyBox { axis: 1, .. })
    ));
    assert_eq!(
        faces_facing(&mesh, &faces, |_| [1.0, 0.0, 0.0], 200.0),
        Err(SelectError::BadAngle(200.0))
    );
}

#[test]
fn a_rule_is_a_named_set_or_the_faces_meeting_all_its_criteria() {
    let mut mesh = box_tet10([1.0, 2.0, 3.0], [2, 4, 3]);
    let faces = boundary_faces(&mesh);
    // A named set: its nodes, and the faces with all six nodes in it.
    let named = Rule::named("zmax").apply(&mesh, &faces).unwrap();
    assert_eq!(named.nodes, mesh.node_set("ZMAX").unwrap());
    assert_eq!(named.faces.len(), 2 * 2 * 4);
    // The same set by plane and by facing, and their intersection with a box: the half
    // y <= 1 of the top (two of four cell rows), 8 faces of area 1.
    let top = Rule {
        surface: Some(Surface::Plane {
            point: [0.0, 0.0, 3.0],
            normal: [0.0, 0.0, 1.0],
        }),
        facing: Some(([0.0, 0.0, 1.0], 1.0)),
        tolerance: 1e-12,
        ..Rule::default()
    };
    assert_eq!(top.apply(&mesh, &faces).unwrap(), named);
    let half = Rule {
        bbox: Some(([-1.0; 3], [2.0, 1.0, 4.0])),
        ..top.clone()
    };
    let s = half.apply(&mesh, &faces).unwrap();
    let sum = summarize(&mesh, &s.faces);
    assert_eq!(sum.faces, 8);
    assert!((sum.area - 1.0).abs() < 1e-14 && (sum.centroid[1] - 0.5).abs() < 1e-14);
    // A circle of diameter 1.2 about (0.5, 1, 3): the faces whose corner centroid is
    // within 0.6 of it in the top plane. Cells are 0.5 x 0.5; each cell's two triangles
    // have centroids (1/6, 1/3) of a cell from its corners. Counted by hand: the four
    // cells around the centre put both triangles inside (8 faces).
    let circle = Rule {
        circle: Some(Circle {
            centre: [0.5, 1.0, 3.0],
            diameter: 1.2,
        }),
        ..top.clone()
    };
    let c = circle.apply(&mesh, &faces).unwrap();
    for f in &c.faces {
        let g = corner_centroid(&mesh, f);
        assert!(((g[0] - 0.5).powi(2) + (g[1] - 1.0).powi(2)).sqrt() <= 0.6);
    }
    assert_eq!(c.faces.len(), 8);
    // A missing set is an error naming the sets there are.
    mesh.node_sets.retain(|k, _| k == "XMIN");
    assert_eq!(
        Rule::named("CLAMP").apply(&mesh, &faces),
        Err(SelectError::MissingSet {
            name: "CLAMP".into(),
            known: "XMIN".into()
        })
    );
    assert_eq!(
        Rule {
            circle: Some(Circle {
                centre: [0.0; 3],
                diameter: 0.0
            }),
            ..Rule::default()
        }
        .check(),
        Err(SelectError::BadDiameter(0.0))
    );
}

#[test]
fn geometric_rules_select_the_quadrilaterals_of_hexahedra_and_wedges() {
    // A box of hex20 (quadrilaterals only) and of wedge15 (triangles on z = 0 and z = top,
    // quadrilaterals on the sides): each face of the box chosen by plane and facing, by a box
    // and by a circle is exactly the generator's node set of that face.
    use crate::generate::box_solid;
    use squeal_element::ElementKind;
    for kind in [ElementKind::Hex20, ElementKind::Wedge15] {
        let mesh = box_solid(kind, [1.0, 2.0, 0.5], [2, 3, 2]);
        let boundary = boundary_faces(&mesh);
        let on = |point: [f64; 3], normal: [f64; 3]| Rule {
            surface: Some(Surface::Plane { point, normal }),
            facing: Some((normal, 1.0)),
            tolerance: 1e-9,
            ..Rule::default()
        };
        for (name, point, normal) in [
            ("XMAX", [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
            ("YMIN", [0.0, 0.0, 0.0], [0.0, -1.0, 0.0]),
            ("ZMAX", [0.0, 0.0, 0.5], [0.0, 0.0, 1.0]),
        ] {
            let s = on(point, normal).apply(&mesh, &boundary).unwrap();
            assert_eq!(s.nodes, mesh.node_set(name).unwrap(), "{kind} {name}");
        }
        let xmin = Rule {
            bbox: Some(([-1.0; 3], [0.0, 9.0, 9.0])),
            ..Rule::default()
        };
        let s = xmin.apply(&mesh, &boundary).unwrap();
        assert_eq!(s.nodes, mesh.node_set("XMIN").unwrap(), "{kind} box");
        // A circle holding the whole x = 1 face (its corner centroids within 1.2 m of its
        // centre) selects it and nothing of the faces beside it (not in its plane).
        let circle = Rule {
            circle: Some(Circle {
                centre: [1.0, 1.0, 0.25],
                diameter: 2.4,
            }),
            tolerance: 1e-9,
            ..Rule::default()
        };
        let s = circle.apply(&mesh, &boundary).unwrap();
        assert_eq!(s.nodes, mesh.node_set("XMAX").unwrap(), "{kind} circle");
    }
}
