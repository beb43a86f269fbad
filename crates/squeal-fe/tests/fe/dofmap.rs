//! The dof map: counts under restraints, both directions of the map, unused nodes.

use squeal_fe::{DofMap, DofStatus, FeError, Restraint};
use squeal_mesh::generate::box_tet10;

#[test]
fn clamp_and_partial_restraints_remove_the_right_dofs() {
    let mut mesh = box_tet10([1.0, 1.0, 1.0], [2, 2, 2]);
    // A node no element uses.
    mesh.nodes.push([9.0, 9.0, 9.0]);
    mesh.node_ids.push(100_000);
    let n = mesh.num_nodes();
    let xmin = mesh.node_set("XMIN").unwrap().to_vec();
    let zmax = mesh.node_set("ZMAX").unwrap().to_vec();
    let shared = xmin.iter().filter(|v| zmax.contains(v)).count();
    let unused = n as u32 - 1;
    let restraints = [
        Restraint::clamp("xmin"),
        Restraint::set("ZMAX", [true, true, false]),
        Restraint::nodes(vec![unused], [true; 3]),
    ];
    let map = DofMap::new(&mesh, &restraints).unwrap();
    // Counting by set sizes (5×5 nodes per face, 5 shared by XMIN and ZMAX): XMIN loses 3 per
    // node, ZMAX 2 per node not already clamped, the unused node has none.
    let expect_restrained = 3 * xmin.len() + 2 * (zmax.len() - shared);
    assert_eq!((xmin.len(), zmax.len(), shared), (25, 25, 5));
    assert_eq!(map.num_restrained(), expect_restrained);
    assert_eq!(map.num_free(), 3 * (n - 1) - expect_restrained);
    assert_eq!(map.status(unused, 0), DofStatus::Unused);
    assert_eq!(map.status(xmin[0], 2), DofStatus::Restrained);
    // Both ways round, and node-major increasing order.
    let mut last = None;
    for f in 0..map.num_free() {
        let (node, dir) = map.node_dir(f).unwrap();
        assert_eq!(map.free_dof(node, dir), Some(f));
        let g = 3 * node as usize + dir;
        assert!(last.is_none_or(|l| l < g));
        last = Some(g);
    }
    assert_eq!(map.node_dir(map.num_free()), None);
    let z_only = zmax.iter().find(|v| !xmin.contains(v)).copied().unwrap();
    let dofs = map.node_dofs(z_only);
    assert!(dofs[0].is_none() && dofs[1].is_none() && dofs[2].is_some());
    // expand / restrict round trip.
    let v: Vec<f64> = (0..map.num_free()).map(|i| i as f64).collect();
    assert_eq!(map.restrict(&map.expand(&v)), v);
}

#[test]
fn bad_restraints_are_errors() {
    let mesh = box_tet10([1.0, 1.0, 1.0], [1, 1, 1]);
    assert!(matches!(
        DofMap::new(&mesh, &[Restraint::clamp("ABUTMENT")]),
        Err(FeError::UnknownNodeSet(_))
    ));
    let r = Restraint::nodes(vec![10_000], [true; 3]);
    assert!(matches!(
        DofMap::new(&mesh, &[r]),
        Err(FeError::NodeOutOfRange { index: 10_000, .. })
    ));
}
