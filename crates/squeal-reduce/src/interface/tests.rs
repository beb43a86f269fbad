use super::*;
use squeal_mesh::generate::box_tet10_origin;

/// The patches as they were before clipping: each boundary triangle whole in the cell of
/// its centroid.
fn whole_triangle_patches(mesh: &Mesh, face_set: &str, grid: [usize; 2]) -> Vec<Patch> {
    let nodes = mesh.node_set(face_set).unwrap();
    let mean = mean_point(nodes.iter().map(|&n| mesh.nodes[n as usize]));
    let frame = Frame::new(&Axis::default(), mean).unwrap();
    let points = nodes.iter().map(|&n| mesh.nodes[n as usize]);
    let grid = PolarGrid::spanning(frame, points, grid[0], grid[1]);
    let mut acc: Vec<PatchSums> = (0..grid.radial * grid.angular)
        .map(|_| PatchSums::default())
        .collect();
    for face in &boundary_faces_of(mesh, nodes) {
        let x8 = face.coords(mesh);
        let x: [[f64; 3]; 6] = std::array::from_fn(|i| x8[i]);
        assert!(
            grid.cuts_crossing(&x).levels.is_empty(),
            "a cut crosses {face:?}"
        );
        acc[grid.cell_of(triangle_centroid(&x))].add_face(face, &x8);
    }
    acc.into_iter()
        .enumerate()
        .map(|(i, s)| s.finish(i + 1))
        .collect()
}

#[test]
fn clipped_patches_are_whole_triangles_where_the_cuts_are_mesh_edges() {
    // Every bundled contact face imprints the 3 x 3 grid (its CONTACT_PATCH_k): no cut
    // crosses a triangle (asserted in whole_triangle_patches), so clipping must give the
    // patches of whole triangles. Asserted to 1e-12 (areas relative, centroids and
    // weights absolute on 0.1 m and O(0.1)); measured: equal to the bit.
    let root = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
    let mut faces = Vec::new();
    for level in ["coarse", "medium", "fine"] {
        faces.push((format!("disc_{level}.inp"), "CONTACT_FACE"));
        faces.push((format!("pad_{level}.inp"), "CONTACT_FACE"));
        faces.push((format!("two_pad/disc_{level}.inp"), "CONTACT_FACE"));
        faces.push((format!("two_pad/disc_{level}.inp"), "CONTACT_FACE_OUTBOARD"));
        faces.push((format!("two_pad/outboard_{level}.inp"), "CONTACT_FACE"));
    }
    for (file, set) in &faces {
        let mesh = squeal_mesh::read(&root.join(file)).unwrap().mesh;
        for grid in [[3, 3], [1, 1]] {
            let clipped = patches(&mesh, set, grid[0], grid[1], &Axis::default()).unwrap();
            let whole = whole_triangle_patches(&mesh, set, grid);
            assert_eq!(clipped.len(), whole.len());
            let mut worst = 0.0f64;
            for (p, q) in clipped.iter().zip(&whole) {
                worst = worst.max((p.area / q.area - 1.0).abs());
                for d in 0..3 {
                    worst = worst.max((p.centroid[d] - q.centroid[d]).abs());
                }
                assert_eq!(p.weights.len(), q.weights.len());
                for (a, b) in p.weights.iter().zip(&q.weights) {
                    assert_eq!(a.0, b.0);
                    worst = worst.max((a.1 - b.1).abs());
                }
            }
            eprintln!("{file} {set} {grid:?}: largest difference {worst:e}");
            assert!(worst < 1e-12, "{file} {set} {grid:?}: {worst:e}");
        }
    }
}

#[test]
fn dunavant_rule_integrates_degree_four_exactly() {
    // ∫ s^a t^b over the reference triangle = a! b! / (a + b + 2)!.
    let fact = |n: u32| (1..=n).product::<u32>() as f64;
    for a in 0..=4u32 {
        for b in 0..=(4 - a) {
            let q: f64 = DUNAVANT4
                .iter()
                .map(|(s, t, w)| 0.5 * w * s.powi(a as i32) * t.powi(b as i32))
                .sum();
            let exact = fact(a) * fact(b) / fact(a + b + 2);
            // The rule's weights and points are given to 15 digits.
            assert!((q - exact).abs() < 1e-14, "s^{a} t^{b}: {q} vs {exact}");
        }
    }
}

#[test]
fn tributary_areas_split_a_face_between_its_nearest_nodes() {
    // A 1 x 1 face at z = 0.1 meshed 6 x 6; four "contact nodes" at the centres of its
    // quadrants, which are mesh nodes (0.25 and 0.75 are not grid lines of a 6-division:
    // take 1/6-multiples, 2/6 and 4/6, and the cells are then split at x, y = 1/2).
    let mut mesh = box_tet10_origin([0.0, 0.0, 0.0], [1.0, 1.0, 0.1], [6, 6, 1]);
    let face = mesh.node_set("ZMAX").unwrap().to_vec();
    mesh.node_sets.insert("CONTACT_FACE".into(), face.clone());
    let at = |x: f64, y: f64| {
        *face
            .iter()
            .find(|&&n| {
                let p = mesh.nodes[n as usize];
                (p[0] - x).abs() < 1e-12 && (p[1] - y).abs() < 1e-12
            })
            .unwrap()
    };
    let nodes = [
        at(2.0 / 6.0, 2.0 / 6.0),
        at(4.0 / 6.0, 2.0 / 6.0),
        at(2.0 / 6.0, 4.0 / 6.0),
        at(4.0 / 6.0, 4.0 / 6.0),
    ];
    let cells = tributary_areas(&mesh, "CONTACT_FACE", &nodes).unwrap();
    // The bisectors x = 1/2 and y = 1/2 are mesh lines, so every quadrature point falls
    // strictly inside one quadrant: each node gets a quarter of the unit face, exactly
    // up to the round-off of the straight triangles' areas.
    for (area, normal) in &cells {
        assert!((area - 0.25).abs() < 1e-14, "area {area}");
        // The outward normal of the top face; the midside nodes' z carry round-off.
        assert!((normal[2] - 1.0).abs() < 1e-15 && normal[0].hypot(normal[1]) < 1e-15);
    }
}

#[test]
fn a_footprint_spreads_a_force_as_a_uniform_pressure() {
    // A 1 x 1 face at z = 0.1 meshed 4 x 4 as one footprint.
    let mut mesh = box_tet10_origin([0.0, 0.0, 0.0], [1.0, 1.0, 0.1], [4, 4, 1]);
    let face = mesh.node_set("ZMAX").unwrap().to_vec();
    mesh.node_sets.insert("FOOT".into(), face);
    let f = footprint(&mesh, "FOOT").unwrap();
    // Straight-sided triangles: the area and the weights are exact to round-off.
    assert!((f.area - 1.0).abs() < 1e-14, "area {}", f.area);
    assert!((f.normal[2] - 1.0).abs() < 1e-14);
    let total: f64 = f.weights.iter().map(|w| w.1).sum();
    assert!((total - 1.0).abs() < 1e-14, "weights sum to {total}");
    // The consistent load of a uniform pressure on 6-node triangles: nothing at the
    // corners (∫ N_corner dA = 0), A/3 of each triangle at its midside nodes.
    for &(n, w) in &f.weights {
        let p = mesh.nodes[n as usize];
        let on_grid = |x: f64| (4.0 * x - (4.0 * x).round()).abs() < 1e-9;
        if on_grid(p[0]) && on_grid(p[1]) {
            assert!(w.abs() < 1e-15, "corner node {n}: weight {w}");
        } else {
            assert!(w > 0.0, "midside node {n}: weight {w}");
        }
    }
    assert!((f.centroid[0] - 0.5).abs() < 1e-14 && (f.centroid[1] - 0.5).abs() < 1e-14);
}

#[test]
fn patches_of_an_annular_footprint_partition_its_area() {
    // A flat box face stands in for a footprint: 1 x 1 face at z = 0.1 centred on +y,
    // far from the axis so that radius and angle bins are non-degenerate.
    let mut mesh = box_tet10_origin([-0.5, 2.0, 0.0], [1.0, 1.0, 0.1], [6, 6, 1]);
    let face = mesh.node_set("ZMAX").unwrap().to_vec();
    mesh.node_sets.insert("CONTACT_FACE".into(), face);
    let p = patches(&mesh, "CONTACT_FACE", 3, 3, &Axis::default()).unwrap();
    assert_eq!(p.len(), 9);
    let total: f64 = p.iter().map(|q| q.area).sum();
    // Straight-sided triangles: areas are exact to round-off.
    assert!((total - 1.0).abs() < 1e-13, "total area {total}");
    for q in &p {
        let s: f64 = q.weights.iter().map(|w| w.1).sum();
        assert!(
            (s - 1.0).abs() < 1e-13,
            "weights of patch {} sum to {s}",
            q.number
        );
        // The mean motion of a rigid translation is that translation: Σ w_k x_k = centroid.
        let mut c = [0.0; 3];
        for &(n, w) in &q.weights {
            for d in 0..3 {
                c[d] += w * mesh.nodes[n as usize][d];
            }
        }
        for d in 0..3 {
            assert!((c[d] - q.centroid[d]).abs() < 1e-12);
        }
    }
    // Patch 1: inner radius, smallest angle (x > 0 side for a footprint on +y).
    assert!(p[0].centroid[0] > 0.0 && p[0].centroid[1] < p[8].centroid[1]);
    assert!(p[2].centroid[0] < 0.0);
}
