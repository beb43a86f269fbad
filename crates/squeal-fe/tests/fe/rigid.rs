//! A free part has exactly six zero-energy modes: the rigid motions.

use super::common;
use common::{curve_midside, distort_vertices, frobenius, matvec, norm, steel};
use squeal_fe::{DofMap, MaterialTable, assemble};
use squeal_mesh::generate::box_tet10;

/// Rigid motions about the point `c`: three translations, three rotations `ω × (x - c)`.
fn rigid_motions(nodes: &[[f64; 3]], c: [f64; 3]) -> Vec<Vec<[f64; 3]>> {
    let mut out = Vec::new();
    for d in 0..3 {
        out.push(
            nodes
                .iter()
                .map(|_| std::array::from_fn(|i| if i == d { 1.0 } else { 0.0 }))
                .collect(),
        );
    }
    for d in 0..3 {
        let mut w = [0.0; 3];
        w[d] = 1.0;
        out.push(
            nodes
                .iter()
                .map(|x| {
                    let r = [x[0] - c[0], x[1] - c[1], x[2] - c[2]];
                    [
                        w[1] * r[2] - w[2] * r[1],
                        w[2] * r[0] - w[0] * r[2],
                        w[0] * r[1] - w[1] * r[0],
                    ]
                })
                .collect(),
        );
    }
    out
}

#[test]
fn rigid_motions_have_zero_energy_on_curved_elements() {
    let mut mesh = box_tet10([0.3, 0.2, 0.1], [4, 3, 2]);
    distort_vertices(&mut mesh, 0.005, 3);
    curve_midside(&mut mesh, 0.003, 4, false);
    let materials = MaterialTable::uniform(&mesh, steel()).unwrap();
    let dofs = DofMap::new(&mesh, &[]).unwrap();
    let sys = assemble(&mesh, &materials, &dofs).unwrap();
    let knorm = frobenius(&sys.k);
    for (i, field) in rigid_motions(&mesh.nodes, [0.1, 0.05, 0.02])
        .iter()
        .enumerate()
    {
        let u = dofs.restrict(field);
        let ratio = norm(&matvec(&sys.k, &u)) / (knorm * norm(&u));
        eprintln!("rigid motion {i}: |K u| / (|K| |u|) = {ratio:.2e}");
        // Isoparametric elements reproduce rigid motions exactly, whatever the curvature or
        // the quadrature: only round-off remains, ~1e-16 per product.
        assert!(
            ratio < 1e-14,
            "rigid motion {i}: |K u| / (|K| |u|) = {ratio:e}"
        );
    }
    // A stretch and a bending shape store energy.
    let stretch: Vec<[f64; 3]> = mesh.nodes.iter().map(|x| [x[0], 0.0, 0.0]).collect();
    let bend: Vec<[f64; 3]> = mesh.nodes.iter().map(|x| [0.0, 0.0, x[0] * x[0]]).collect();
    for field in [stretch, bend] {
        let u = dofs.restrict(&field);
        let ratio = norm(&matvec(&sys.k, &u)) / (knorm * norm(&u));
        eprintln!("deforming field: |K u| / (|K| |u|) = {ratio:.2e}");
        assert!(ratio > 1e-4, "a deforming field looks rigid: {ratio:e}");
    }
}

#[test]
fn exactly_six_zero_eigenvalues() {
    let mut mesh = box_tet10([0.3, 0.2, 0.1], [2, 2, 2]);
    curve_midside(&mut mesh, 0.004, 5, false);
    let materials = MaterialTable::uniform(&mesh, steel()).unwrap();
    let dofs = DofMap::new(&mesh, &[]).unwrap();
    let sys = assemble(&mesh, &materials, &dofs).unwrap();
    let ev = common::sym_eigen(&common::dense(&sys.k)).0;
    let max = ev[ev.len() - 1];
    // Zero eigenvalues come out at round-off, ~1e-16 λ_max times the dimension; the smallest
    // elastic one of this coarse, stubby block is far above 1e-6 λ_max.
    eprintln!(
        "lowest eigenvalues / max: {:?}",
        ev[..8]
            .iter()
            .map(|l| format!("{:.2e}", l / max))
            .collect::<Vec<_>>()
    );
    let zeros = ev.iter().filter(|&&l| l.abs() < 1e-12 * max).count();
    assert_eq!(zeros, 6, "eigenvalues {:?}", &ev[..8]);
    assert!(
        ev[6] > 1e-6 * max,
        "seventh eigenvalue {:e} of {max:e}",
        ev[6]
    );
}
