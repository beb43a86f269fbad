//! The interface models on the bundled coarse meshes.

use squeal_reduce::interface::{Axis, contact_nodes, patches};
use std::path::PathBuf;

fn mesh(name: &str) -> squeal_mesh::Mesh {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../meshes")
        .join(name);
    squeal_mesh::read(&path).unwrap().mesh
}

#[test]
fn patches_follow_the_generator_patch_sets_and_pair_up() {
    let disc = mesh("disc_coarse.inp");
    let pad = mesh("pad_coarse.inp");
    let axis = Axis::default();
    let pd = patches(&disc, "CONTACT_FACE", 3, 3, &axis).unwrap();
    let pp = patches(&pad, "CONTACT_FACE", 3, 3, &axis).unwrap();
    for (part, m, p) in [("disc", &disc, &pd), ("pad", &pad, &pp)] {
        for q in p.iter() {
            // The generator's patch sets hold the nodes of each patch (its edges included):
            // our grid split must put every weighted node inside the same-numbered set.
            let set = m.node_set(&format!("CONTACT_PATCH_{}", q.number)).unwrap();
            for (n, _) in &q.weights {
                assert!(
                    set.binary_search(n).is_ok(),
                    "{part} patch {}: node {} outside",
                    q.number,
                    m.node_ids[*n as usize]
                );
            }
        }
        // Footprint area: 50 degrees of the annulus 85..135 mm; the curved P2 edges follow
        // the arcs, so the error is that of quadratic arc interpolation (< 1e-5 here).
        let area: f64 = p.iter().map(|q| q.area).sum();
        let exact = 0.5 * 50f64.to_radians() * (0.135f64.powi(2) - 0.085f64.powi(2));
        assert!(
            (area / exact - 1.0).abs() < 1e-5,
            "{part} area {area} vs {exact}"
        );
    }
    for (a, b) in pd.iter().zip(&pp) {
        let d: f64 = (0..3)
            .map(|k| (a.centroid[k] - b.centroid[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        // Same grid, same footprint, both meshes follow the arcs: centroids agree to the
        // discretisation of the arcs, far below the 17 mm patch size.
        assert!(d < 1e-5, "patch {}: centroids {d} m apart", a.number);
    }
}

#[test]
fn contact_nodes_come_in_patch_order() {
    for name in ["disc_coarse.inp", "pad_coarse.inp"] {
        let m = mesh(name);
        let nodes = contact_nodes(&m, "CONTACT", &Axis::default()).unwrap();
        for (k, n) in nodes.iter().enumerate() {
            let set = m.node_set(&format!("CONTACT_PATCH_{}", k + 1)).unwrap();
            assert!(
                set.binary_search(n).is_ok(),
                "{name}: contact node {k} not in patch {}",
                k + 1
            );
        }
    }
}
