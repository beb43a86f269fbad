use super::*;
use crate::{ElasticMaterial, MaterialTable, assemble};
use squeal_mesh::generate::box_tet10;

#[test]
fn a_restraint_along_coordinate_axes_is_a_plain_restraint() {
    let mesh = box_tet10([1.0, 0.2, 0.2], [4, 1, 1]);
    let nodes = mesh.node_set("XMIN").unwrap().to_vec();
    let skew: Vec<SkewRestraint> = nodes
        .iter()
        .flat_map(|&n| {
            [
                SkewRestraint {
                    node: n,
                    direction: [2.0, 0.0, 0.0],
                },
                SkewRestraint {
                    node: n,
                    direction: [0.0, -1.0, 0.0],
                },
            ]
        })
        .collect();
    let held = HeldNodes::new(&mesh, &[], &skew).unwrap();
    assert!(!held.has_frames());
    assert_eq!(
        held.restraints,
        vec![Restraint::nodes(nodes, [true, true, false])]
    );
}

#[test]
fn a_rotated_bar_held_in_its_own_axes_has_the_frequencies_of_the_straight_one() {
    // A bar along x, its ends held in y and z (one node also in x). Rotated
    // by a general rotation, with the same restraints along the rotated axes, it is the
    // same structure: the same spectrum to round-off, since K' = Tᵀ K T is exact. The
    // straight bar takes the plain path (coordinate axes), the rotated one the frames.
    let straight = box_tet10([1.0, 0.1, 0.1], [6, 1, 1]);
    let (c, s) = (0.6f64, 0.8f64);
    // Rotation: about z by atan2(0.8, 0.6), then about x by 30 degrees.
    let (c2, s2) = (3f64.sqrt() / 2.0, 0.5);
    let rz = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
    let rx = [[1.0, 0.0, 0.0], [0.0, c2, -s2], [0.0, s2, c2]];
    let rot = |p: [f64; 3]| {
        let q: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| rz[i][j] * p[j]).sum());
        std::array::from_fn(|i| (0..3).map(|j| rx[i][j] * q[j]).sum::<f64>())
    };
    let mut rotated = straight.clone();
    for p in &mut rotated.nodes {
        *p = rot(*p);
    }
    let steel = ElasticMaterial::isotropic(210e9, 0.3, 7850.0);
    let mut ends = straight.node_set("XMIN").unwrap().to_vec();
    let first = ends[0];
    ends.extend_from_slice(straight.node_set("XMAX").unwrap());
    let lowest = |mesh: &Mesh, skew: Vec<SkewRestraint>| -> Vec<f64> {
        let held = HeldNodes::new(mesh, &[], &skew).unwrap();
        let dofmap = DofMap::new(mesh, &held.restraints).unwrap();
        let system =
            assemble(mesh, &MaterialTable::uniform(mesh, steel).unwrap(), &dofmap).unwrap();
        let t = DofTransform::new(&dofmap, &held);
        let s = t.system(&dofmap, &system);
        let n = s.k.nrows();
        let dense = |x: &SparseColMat<usize, f64>| {
            let mut d = Mat::<f64>::zeros(n, n);
            for j in 0..n {
                for (i, &v) in x.as_ref().row_idx_of_col(j).zip(x.as_ref().val_of_col(j)) {
                    d[(i, j)] = v;
                }
            }
            d
        };
        let (k, m) = (dense(&s.k), dense(&s.m));
        // M = L Lᵀ, A = L⁻¹ K L⁻ᵀ, its eigenvalues.
        let mut l = Mat::<f64>::zeros(n, n);
        for j in 0..n {
            let d = m[(j, j)] - (0..j).map(|q| l[(j, q)] * l[(j, q)]).sum::<f64>();
            l[(j, j)] = d.sqrt();
            for i in j + 1..n {
                let t = m[(i, j)] - (0..j).map(|q| l[(i, q)] * l[(j, q)]).sum::<f64>();
                l[(i, j)] = t / l[(j, j)];
            }
        }
        let forward = |b: &Mat<f64>| {
            let mut x = b.clone();
            for c in 0..n {
                for i in 0..n {
                    let t = x[(i, c)] - (0..i).map(|q| l[(i, q)] * x[(q, c)]).sum::<f64>();
                    x[(i, c)] = t / l[(i, i)];
                }
            }
            x
        };
        let x = forward(&k);
        let a = forward(&x.transpose().to_owned());
        let a = Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
        let mut ev: Vec<f64> = a.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
        ev.sort_by(f64::total_cmp);
        ev.truncate(6);
        ev
    };
    let along = |dirs: &dyn Fn([f64; 3]) -> [f64; 3]| -> Vec<SkewRestraint> {
        let mut v = Vec::new();
        for &n in &ends {
            for d in [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
                v.push(SkewRestraint {
                    node: n,
                    direction: dirs(d),
                });
            }
        }
        v.push(SkewRestraint {
            node: first,
            direction: dirs([1.0, 0.0, 0.0]),
        });
        v
    };
    let a = lowest(&straight, along(&|d| d));
    let b = lowest(&rotated, along(&rot));
    assert!(
        HeldNodes::new(&rotated, &[], &along(&rot))
            .unwrap()
            .has_frames()
    );
    for (x, y) in a.iter().zip(&b) {
        // Matrices equal up to the rotation's round-off (~1e-16 relative per entry); a
        // low eigenvalue of the dense pencil moves by that times lambda_max / lambda
        // (~1e5 here): measured 5.8e-11 relative at worst, asserted 1e-9.
        assert!((x / y - 1.0).abs() < 1e-9, "{x} vs {y}");
    }
    assert!(a[0] > 1.0, "the bar is held: no rigid mode ({})", a[0]);
}

#[test]
fn the_tangent_of_a_rotation_is_omega_cross_r_normalized() {
    // Axis through (1, 2, 0) along +z (given as (0, 0, 5)); at (4, 6, 5) the arm is
    // (3, 4, 0), radius 5: radial (0.6, 0.8, 0), tangential z x radial = (-0.8, 0.6, 0),
    // velocity at 100 rad/s = 100 (-4, 3, 0). Exact in binary up to one rounding.
    let a = RotationAxis::new([1.0, 2.0, 0.0], [0.0, 0.0, 5.0]).unwrap();
    let p = [4.0, 6.0, 5.0];
    let close = |x: [f64; 3], y: [f64; 3], tol: f64| (0..3).all(|i| (x[i] - y[i]).abs() <= tol);
    assert!((a.radius(p) - 5.0).abs() < 1e-15);
    let [ax, rad, tan] = a.triad(p).unwrap();
    assert_eq!(ax, [0.0, 0.0, 1.0]);
    assert!(close(rad, [0.6, 0.8, 0.0], 1e-15), "{rad:?}");
    assert!(close(tan, [-0.8, 0.6, 0.0], 1e-15), "{tan:?}");
    let v = a.velocity(p, 100.0);
    assert!(close(v, [-400.0, 300.0, 0.0], 1e-12), "{v:?}");
    // The reverse sense: the tangent flips, the radial direction does not.
    let b = RotationAxis::new([1.0, 2.0, -7.0], [0.0, 0.0, -1.0]).unwrap();
    assert!(close(
        b.direction(AxisDirection::Tangential, p).unwrap(),
        [0.8, -0.6, 0.0],
        1e-15
    ));
    assert!(close(
        b.direction(AxisDirection::Radial, p).unwrap(),
        rad,
        1e-15
    ));
    // On the axis there is no radial or tangential direction.
    assert_eq!(
        a.direction(AxisDirection::Tangential, [1.0, 2.0, 9.0]),
        None
    );
    assert_eq!(a.direction(AxisDirection::Axial, [1.0, 2.0, 9.0]), Some(ax));
    assert!(matches!(
        RotationAxis::new([0.0; 3], [0.0; 3]),
        Err(FeError::BadAxis)
    ));
    assert!(matches!(
        RotationAxis::new([f64::NAN, 0.0, 0.0], [0.0, 0.0, 1.0]),
        Err(FeError::BadAxis)
    ));
}

#[test]
fn a_turned_and_shifted_axis_gives_the_turned_directions() {
    // Unit quaternion along (1, 2, 3, 4): a general rotation R. Axis z through the origin
    // against axis R z through c, at points p and R p + c: the triads are R times the
    // first ones. Entries of R and the shifted coordinates carry round-off ~1e-16 each;
    // asserted 1e-14 (absolute, on unit vectors; measured 1.7e-15 at worst) over a 5 x 7
    // grid of radii and angles. And the tangent is omega x r normalized at each of them.
    let n = 30f64.sqrt();
    let (w, x, y, z) = (1.0 / n, 2.0 / n, 3.0 / n, 4.0 / n);
    let r = [
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
    ];
    let rot =
        |p: [f64; 3]| -> [f64; 3] { std::array::from_fn(|i| (0..3).map(|j| r[i][j] * p[j]).sum()) };
    let c = [0.3, -1.2, 0.7];
    let plain = RotationAxis::new([0.0; 3], [0.0, 0.0, 1.0]).unwrap();
    let moved = RotationAxis::new(c, rot([0.0, 0.0, 1.0])).unwrap();
    let mut worst = 0.0f64;
    for i in 0..5 {
        for j in 0..7 {
            let (rad, th) = (0.05 + 0.025 * i as f64, 0.9 * j as f64);
            let p = [rad * th.cos(), rad * th.sin(), 0.01 * j as f64];
            let rp = rot(p);
            let q = [rp[0] + c[0], rp[1] + c[1], rp[2] + c[2]];
            let t0 = plain.triad(p).unwrap();
            let t1 = moved.triad(q).unwrap();
            for k in 0..3 {
                let e = rot(t0[k]);
                for d in 0..3 {
                    worst = worst.max((t1[k][d] - e[d]).abs());
                }
            }
            let v = moved.velocity(q, 1.0);
            let vn = dot(v, v).sqrt();
            for d in 0..3 {
                worst = worst.max((t1[2][d] - v[d] / vn).abs());
            }
            assert!((moved.radius(q) - rad).abs() < 1e-15);
        }
    }
    assert!(worst < 1e-14, "{worst:e}");
}

#[test]
fn a_pad_held_radially_about_a_skew_axis_gets_its_own_frames() {
    // Nodes of a box held radially and tangentially about a skew axis: each gets a frame
    // whose two held axes are its radial and tangential directions, and the kept axis is
    // the rotation axis. A node on the axis is an error, not a silent restraint.
    let mesh = box_tet10([1.0, 0.2, 0.2], [2, 1, 1]);
    let axis = RotationAxis::new([-0.5, -0.5, 0.0], [1.0, 1.0, 1.0]).unwrap();
    let nodes = mesh.node_set("XMAX").unwrap().to_vec();
    let skew = axis
        .restraints(
            &mesh,
            &nodes,
            &[AxisDirection::Radial, AxisDirection::Tangential],
        )
        .unwrap();
    let held = HeldNodes::new(&mesh, &[], &skew).unwrap();
    assert_eq!(held.frames.len(), nodes.len());
    for (&n, f) in &held.frames {
        assert_eq!(f.held, 2);
        let kept = f.axes[2];
        // The kept axis is +-the rotation axis, to round-off of Gram-Schmidt.
        assert!(
            (dot(kept, axis.axis()).abs() - 1.0).abs() < 1e-14,
            "node {n}"
        );
    }
    assert!(matches!(
        axis.restraints(&mesh, &[u32::MAX], &[AxisDirection::Axial]),
        Err(FeError::NodeOutOfRange {
            index: u32::MAX,
            ..
        })
    ));
    // An axis through a node: that node has no radial direction.
    let through = RotationAxis::new(mesh.nodes[nodes[0] as usize], [1.0, 0.0, 0.0]).unwrap();
    assert!(matches!(
        through.restraints(&mesh, &nodes[..1], &[AxisDirection::Radial]),
        Err(FeError::BadDirection { node }) if node == nodes[0]
    ));
    assert_eq!(
        through
            .restraints(&mesh, &nodes[..1], &[AxisDirection::Axial])
            .unwrap()[0]
            .direction,
        [1.0, 0.0, 0.0]
    );
}
