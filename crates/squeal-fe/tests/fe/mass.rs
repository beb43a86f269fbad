//! Total mass and second moments from the consistent mass matrix, on straight and curved
//! meshes, against volumes computed independently.

use super::common;
use common::{curve_midside, distort_vertices, dot, matvec};
use squeal_fe::{
    DofMap, ElasticMaterial, MaterialTable, Quadrature, Summary, assemble, mesh_volume, total_mass,
};
use squeal_mesh::{Mesh, generate::box_tet10, tet10};
use std::collections::BTreeMap;

const RHO: f64 = 7300.0;
const L: [f64; 3] = [0.4, 0.3, 0.2];

fn cast_iron() -> ElasticMaterial {
    ElasticMaterial::isotropic(110e9, 0.26, RHO)
}

/// `uᵀ M u` for a per-node field, with no restraints.
fn kinetic(mesh: &Mesh, field: &[[f64; 3]]) -> f64 {
    let materials = MaterialTable::uniform(mesh, cast_iron()).unwrap();
    let dofs = DofMap::new(mesh, &[]).unwrap();
    let sys = assemble(mesh, &materials, &dofs).unwrap();
    let u = dofs.restrict(field);
    dot(&u, &matvec(&sys.m, &u))
}

fn translation(mesh: &Mesh, d: usize) -> Vec<[f64; 3]> {
    mesh.nodes
        .iter()
        .map(|_| std::array::from_fn(|i| if i == d { 1.0 } else { 0.0 }))
        .collect()
}

#[test]
fn translation_mass_is_rho_times_volume_on_a_distorted_mesh() {
    let mut mesh = box_tet10(L, [4, 3, 2]);
    distort_vertices(&mut mesh, 0.01, 21);
    let exact = RHO * L[0] * L[1] * L[2];
    for d in 0..3 {
        let m = kinetic(&mesh, &translation(&mesh, d));
        // Degree-5 rule on a degree-4 integrand: exact up to round-off of ~1e4 summed terms.
        assert!(
            (m / exact - 1.0).abs() < 1e-13,
            "direction {d}: {m} vs {exact}"
        );
    }
    // Second moment about the centroid's z axis: ρ ∫ (x'² + y'²) = ρ V (a² + b²) / 12, the
    // rotation field being linear and so interpolated exactly.
    let c = [L[0] / 2.0, L[1] / 2.0, L[2] / 2.0];
    let rot: Vec<[f64; 3]> = mesh
        .nodes
        .iter()
        .map(|x| [-(x[1] - c[1]), x[0] - c[0], 0.0])
        .collect();
    let jz = kinetic(&mesh, &rot);
    let exact_jz = exact * (L[0] * L[0] + L[1] * L[1]) / 12.0;
    assert!(
        (jz / exact_jz - 1.0).abs() < 1e-13,
        "J_z {jz} vs {exact_jz}"
    );
}

#[test]
fn curved_interior_elements_keep_the_box_mass() {
    // Moving only interior midside nodes curves the elements but keeps the boundary, so the
    // elements still tile the box exactly.
    let mut mesh = box_tet10(L, [4, 3, 2]);
    curve_midside(&mut mesh, 0.01, 8, true);
    let exact = RHO * L[0] * L[1] * L[2];
    let m = kinetic(&mesh, &translation(&mesh, 1));
    // uᵀ M u = ρ ∫ det J, a cubic, integrated exactly by the degree-5 rule.
    assert!((m / exact - 1.0).abs() < 1e-13, "{m} vs {exact}");
    // The elements really are curved: their volumes differ from the straight ones.
    let straight = box_tet10(L, [4, 3, 2]);
    let changed = (0..mesh.num_elements())
        .filter(|&e| {
            (tet10::volume(&mesh.element_coords(e)) / tet10::volume(&straight.element_coords(e))
                - 1.0)
                .abs()
                > 1e-3
        })
        .count();
    assert!(
        changed > mesh.num_elements() / 2,
        "only {changed} elements changed volume"
    );
}

/// Volume by the divergence theorem, `V = ⅓ ∮ x·n dA`, over the boundary faces (6-node
/// triangles found as faces used by one element), with a collapsed 4×4 Gauss rule on the
/// triangle (exact for the degree-4 integrand `x · (x_s × x_t)`).
fn surface_volume(mesh: &Mesh) -> f64 {
    let mut faces: BTreeMap<[u32; 3], (usize, [u32; 6])> = BTreeMap::new();
    for el in &mesh.blocks.tet10 {
        for f in tet10::FACES {
            let nodes: [u32; 6] = f.map(|i| el[i]);
            let mut key = [nodes[0], nodes[1], nodes[2]];
            key.sort();
            faces.entry(key).or_insert((0, nodes)).0 += 1;
        }
    }
    let g = [
        (-0.861_136_311_594_052_6, 0.347_854_845_137_453_8),
        (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    ];
    let gauss: Vec<(f64, f64)> = g
        .iter()
        .flat_map(|&(x, w)| [(0.5 * (1.0 + x), 0.5 * w), (0.5 * (1.0 - x), 0.5 * w)])
        .collect();
    let mut v = 0.0;
    for (count, nodes) in faces.values() {
        if *count != 1 {
            continue;
        }
        let x: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.nodes[n as usize]).collect();
        for &(u, wu) in &gauss {
            for &(t, wt) in &gauss {
                let (s, t, jac) = (u, (1.0 - u) * t, 1.0 - u);
                let l = [1.0 - s - t, s, t];
                // P2 triangle: vertices, then midsides 01, 12, 20.
                let n = [
                    l[0] * (2.0 * l[0] - 1.0),
                    l[1] * (2.0 * l[1] - 1.0),
                    l[2] * (2.0 * l[2] - 1.0),
                    4.0 * l[0] * l[1],
                    4.0 * l[1] * l[2],
                    4.0 * l[2] * l[0],
                ];
                // dN/ds and dN/dt with dl0 = (-1, -1), dl1 = (1, 0), dl2 = (0, 1).
                let ds = [
                    -(4.0 * l[0] - 1.0),
                    4.0 * l[1] - 1.0,
                    0.0,
                    4.0 * (l[0] - l[1]),
                    4.0 * l[2],
                    -4.0 * l[2],
                ];
                let dt = [
                    -(4.0 * l[0] - 1.0),
                    0.0,
                    4.0 * l[2] - 1.0,
                    -4.0 * l[1],
                    4.0 * l[1],
                    4.0 * (l[0] - l[2]),
                ];
                let comb = |c: &[f64; 6]| -> [f64; 3] {
                    std::array::from_fn(|d| (0..6).map(|i| c[i] * x[i][d]).sum())
                };
                let (p, xs, xt) = (comb(&n), comb(&ds), comb(&dt));
                let cross = [
                    xs[1] * xt[2] - xs[2] * xt[1],
                    xs[2] * xt[0] - xs[0] * xt[2],
                    xs[0] * xt[1] - xs[1] * xt[0],
                ];
                v += wu * wt * jac * (p[0] * cross[0] + p[1] * cross[1] + p[2] * cross[2]) / 3.0;
            }
        }
    }
    v
}

#[test]
fn curved_boundary_mass_matches_the_divergence_theorem() {
    let mut mesh = box_tet10(L, [4, 3, 2]);
    curve_midside(&mut mesh, 0.01, 9, false);
    let v_surface = surface_volume(&mesh);
    // The boundary moved: the volume is no longer the box's.
    let v_box = L[0] * L[1] * L[2];
    assert!(
        (v_surface / v_box - 1.0).abs() > 1e-4,
        "volume unchanged: {v_surface}"
    );
    // Sanity of the surface integral itself: on the straight box it gives the box volume.
    let straight = surface_volume(&box_tet10(L, [4, 3, 2]));
    assert!(
        (straight / v_box - 1.0).abs() < 1e-13,
        "straight box: {straight}"
    );
    let m = kinetic(&mesh, &translation(&mesh, 2));
    // Both sides are exact integrations of polynomials; only round-off differs.
    assert!(
        (m / (RHO * v_surface) - 1.0).abs() < 1e-13,
        "{m} vs {}",
        RHO * v_surface
    );
    // The mesh crate's Keast volume and the summaries agree too.
    let keast: f64 = (0..mesh.num_elements())
        .map(|e| tet10::volume(&mesh.element_coords(e)))
        .sum();
    assert!((keast / v_surface - 1.0).abs() < 1e-13);
    let rule = Quadrature::fourteen_point();
    assert!((mesh_volume(&mesh, &rule).unwrap() / v_surface - 1.0).abs() < 1e-13);
    let materials = MaterialTable::uniform(&mesh, cast_iron()).unwrap();
    assert!((total_mass(&mesh, &materials, &rule).unwrap() / m - 1.0).abs() < 1e-13);
}

#[test]
fn summary_counts_and_mass_with_restraints() {
    let mesh = box_tet10(L, [2, 2, 2]);
    let materials = MaterialTable::uniform(&mesh, cast_iron()).unwrap();
    let dofs = DofMap::new(&mesh, &[squeal_fe::Restraint::clamp("XMIN")]).unwrap();
    let sys = assemble(&mesh, &materials, &dofs).unwrap();
    let s = Summary::new(&mesh, &materials, &dofs, &sys).unwrap();
    // 5×5×5 nodes, 25 clamped on XMIN.
    assert_eq!((s.nodes, s.free_dofs, s.restrained_dofs), (125, 300, 75));
    assert_eq!(s.nnz_k, sys.k.val().len());
    // The mass includes the clamped nodes' share: ρ V exactly (straight elements).
    assert!((s.mass / (RHO * L[0] * L[1] * L[2]) - 1.0).abs() < 1e-13);
    assert!(s.to_string().contains("300 free dofs"));
}
