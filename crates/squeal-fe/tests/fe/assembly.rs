//! Global assembly: against a naive dense assembly, bit-for-bit independence of the thread
//! count, exact symmetry, and the sparsity pattern.

use super::common;
use common::{Sparse, curve_midside, steel};
use squeal_fe::{
    AssemblyOptions, DofMap, ElasticMaterial, MaterialTable, Quadrature, Restraint, System,
    assemble, element_mass, element_stiffness,
};
use squeal_mesh::generate::box_tet10;

/// Naive reference: dense matrices, each element scattered through the dof map, with the
/// element's stiffness rule (4-point if straight, 24-point if curved: `tests/fe/curved.rs`).
fn dense_reference(
    mesh: &squeal_mesh::Mesh,
    materials: &MaterialTable,
    dofs: &DofMap,
) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let n = dofs.num_free();
    let (mut k, mut m) = (vec![vec![0.0; n]; n], vec![vec![0.0; n]; n]);
    let options = AssemblyOptions::default();
    for e in 0..mesh.num_elements() {
        let x = mesh.element_coords(e);
        let mat = materials.of_element(e).unwrap();
        let rule = options.stiffness_rule_for(&x);
        let ke = element_stiffness(&x, &mat.elasticity, rule).unwrap();
        let me = element_mass(&x, mat.material.density(), &Quadrature::fourteen_point()).unwrap();
        let map: Vec<Option<usize>> = (0..30)
            .map(|i| dofs.free_dof(mesh.blocks.tet10[e][i / 3], i % 3))
            .collect();
        for i in 0..30 {
            for j in 0..30 {
                if let (Some(r), Some(c)) = (map[i], map[j]) {
                    k[r][c] += ke[i][j];
                    m[r][c] += me[i][j];
                }
            }
        }
    }
    (k, m)
}

fn compare(sparse: &Sparse, dense: &[Vec<f64>], what: &str) {
    let d = common::dense(sparse);
    let scale = dense.iter().flatten().fold(0.0_f64, |a, v| a.max(v.abs()));
    for (r, row) in dense.iter().enumerate() {
        for (c, v) in row.iter().enumerate() {
            // Same element contributions summed in ascending element order by both: agreement
            // to round-off (in fact to the bit); entries missing from the pattern read as 0.
            assert!(
                (d[(r, c)] - v).abs() <= 1e-15 * scale,
                "{what}[{r}][{c}]: {} vs {v}",
                d[(r, c)]
            );
        }
    }
}

fn two_materials(mesh: &mut squeal_mesh::Mesh) -> MaterialTable {
    let half = mesh.num_elements() as u32 / 2;
    mesh.element_sets.insert("HALF".into(), (0..half).collect());
    let lining = ElasticMaterial::TransverselyIsotropic {
        young_plane: 6.0e9,
        poisson_plane: 0.25,
        young_axial: 2.0e9,
        poisson_plane_axial: 0.12,
        shear_axial: 1.1e9,
        axis: [0.0, 0.6, 0.8],
        density: 2500.0,
    };
    MaterialTable::from_mesh(mesh, &[("ALL".into(), steel()), ("HALF".into(), lining)]).unwrap()
}

#[test]
fn sparse_assembly_equals_naive_dense_assembly() {
    let mut mesh = box_tet10([0.2, 0.1, 0.05], [3, 2, 2]);
    curve_midside(&mut mesh, 0.002, 31, false);
    let materials = two_materials(&mut mesh);
    let restraints = [
        Restraint::clamp("XMIN"),
        Restraint::set("ZMAX", [true, true, false]),
        Restraint::set("YMIN", [false, false, true]),
    ];
    let dofs = DofMap::new(&mesh, &restraints).unwrap();
    let sys = assemble(&mesh, &materials, &dofs).unwrap();
    let (k, m) = dense_reference(&mesh, &materials, &dofs);
    compare(&sys.k, &k, "K");
    compare(&sys.m, &m, "M");
    // The patterns are exactly the free (node, dir) pairs of nodes sharing an element, all
    // direction pairs for K, equal directions for M (counted here from the connectivity).
    let mut pairs = std::collections::BTreeSet::new();
    for el in &mesh.blocks.tet10 {
        for &a in el {
            for &b in el {
                pairs.insert((a, b));
            }
        }
    }
    let nfree = |v: u32| dofs.node_dofs(v).iter().flatten().count();
    let expect_k: usize = pairs.iter().map(|&(a, b)| nfree(a) * nfree(b)).sum();
    let expect_m: usize = pairs
        .iter()
        .map(|&(a, b)| {
            (0..3)
                .filter(|&d| dofs.free_dof(a, d).is_some() && dofs.free_dof(b, d).is_some())
                .count()
        })
        .sum();
    assert_eq!((sys.nnz_k(), sys.nnz_m()), (expect_k, expect_m));
}

fn bits(s: &System) -> (Vec<u64>, Vec<u64>, Vec<usize>, Vec<usize>) {
    (
        s.k.val().iter().map(|v| v.to_bits()).collect(),
        s.m.val().iter().map(|v| v.to_bits()).collect(),
        s.k.symbolic().row_idx().to_vec(),
        s.m.symbolic().row_idx().to_vec(),
    )
}

#[test]
fn same_bits_for_any_thread_count_and_exact_symmetry() {
    // 2304 elements: more than one assembly chunk.
    let mut mesh = box_tet10([0.8, 0.8, 0.6], [8, 8, 6]);
    curve_midside(&mut mesh, 0.003, 41, false);
    let materials = two_materials(&mut mesh);
    let dofs = DofMap::new(&mesh, &[Restraint::set("ZMIN", [false, false, true])]).unwrap();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| assemble(&mesh, &materials, &dofs).unwrap())
    };
    let one = run(1);
    let reference = bits(&one);
    for threads in [2, 3] {
        assert!(
            bits(&run(threads)) == reference,
            "{threads} threads differ from 1 thread"
        );
    }
    for a in [&one.k, &one.m] {
        let s = a.symbolic();
        for c in 0..a.ncols() {
            let rows = &s.row_idx()[s.col_ptr()[c]..s.col_ptr()[c + 1]];
            assert!(
                rows.windows(2).all(|w| w[0] < w[1]),
                "column {c} not sorted"
            );
            for (k, &r) in rows.iter().enumerate() {
                let t = &s.row_idx()[s.col_ptr()[r]..s.col_ptr()[r + 1]];
                let pos = t.binary_search(&c).expect("pattern symmetric");
                assert_eq!(
                    a.val()[s.col_ptr()[r] + pos].to_bits(),
                    a.val()[s.col_ptr()[c] + k].to_bits()
                );
            }
        }
    }
}

#[test]
fn bad_inputs_are_errors() {
    let mesh = box_tet10([1.0, 1.0, 1.0], [1, 1, 1]);
    let other = box_tet10([1.0, 1.0, 1.0], [2, 1, 1]);
    let materials = MaterialTable::uniform(&mesh, steel()).unwrap();
    let dofs = DofMap::new(&mesh, &[]).unwrap();
    assert!(matches!(
        assemble(&other, &materials, &dofs),
        Err(squeal_fe::FeError::TableMismatch { .. })
    ));
    let m2 = MaterialTable::uniform(&other, steel()).unwrap();
    assert!(matches!(
        assemble(&other, &m2, &dofs),
        Err(squeal_fe::FeError::DofMapMismatch { .. })
    ));
    // A hand-made table pointing past its entries.
    let mut broken = materials.clone();
    broken.element_entry[2] = 5;
    assert!(matches!(
        assemble(&mesh, &broken, &dofs),
        Err(squeal_fe::FeError::MaterialIndex {
            element: 3,
            index: 5,
            entries: 1
        })
    ));
    // An inverted element is named by its file id.
    let mut inverted = mesh.clone();
    let el = &mut inverted.blocks.tet10[3];
    el.swap(1, 2);
    el.swap(4, 6);
    el.swap(8, 9);
    match assemble(&inverted, &materials, &dofs) {
        Err(e @ squeal_fe::FeError::Element { element: 4, .. }) => {
            // The message is printed once, also in an error chain (`{:#}`, as the CLI prints).
            let chain = format!("{:#}", anyhow::Error::from(e));
            assert_eq!(chain.matches("Jacobian determinant").count(), 1, "{chain}");
            assert!(chain.starts_with("element 4: "), "{chain}");
        }
        other => panic!(
            "expected an element error of element 4, got {:?}",
            other.map(|s| s.num_dofs())
        ),
    }
}
