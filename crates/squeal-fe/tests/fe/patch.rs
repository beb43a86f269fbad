//! Patch test (Irons): a linear displacement field on a distorted mesh gives constant strain
//! in every element, zero residual `K u` at interior nodes, and strain energy `V εᵀ C ε / 2`.

use super::common;
use common::{PATCH_A as A, distort_vertices, linear_field, lining, on_box_boundary};
use squeal_fe::{DofMap, MaterialTable, Quadrature, assemble, strain_at};
use squeal_mesh::generate::box_tet10;

#[test]
fn linear_field_passes_the_patch_test() {
    let mut mesh = box_tet10([1.0, 0.8, 0.6], [3, 3, 3]);
    distort_vertices(&mut mesh, 0.04, 11);
    let materials = MaterialTable::uniform(&mesh, lining()).unwrap();
    let c = materials.entries[0].elasticity;
    let dofs = DofMap::new(&mesh, &[]).unwrap();
    let sys = assemble(&mesh, &materials, &dofs).unwrap();
    let field: Vec<[f64; 3]> = mesh.nodes.iter().map(|&x| linear_field(x)).collect();
    let u = dofs.restrict(&field);

    // Constant strain ε = sym(A) (engineering shear) at every quadrature point of every element.
    let eps = [
        A[0][0],
        A[1][1],
        A[2][2],
        A[0][1] + A[1][0],
        A[0][2] + A[2][0],
        A[1][2] + A[2][1],
    ];
    let rule = Quadrature::fourteen_point();
    for e in 0..mesh.num_elements() {
        let x = mesh.element_coords(e);
        let ue: [[f64; 3]; 10] = std::array::from_fn(|a| field[mesh.blocks.tet10[e][a] as usize]);
        for p in &rule.points {
            let s = strain_at(&x, &ue, *p).unwrap();
            for k in 0..6 {
                // Gradients of a field of size ~1e-3 over elements of size ~0.3: round-off
                // ~1e-18 absolute, 1e-15 relative to the largest strain.
                assert!(
                    (s[k] - eps[k]).abs() < 1e-15,
                    "element {e} strain {k}: {} vs {}",
                    s[k],
                    eps[k]
                );
            }
        }
    }

    // K u vanishes at interior nodes, to round-off of the row sums Σ_j |K_ij u_j|.
    let (sym, val) = (sys.k.symbolic(), sys.k.val());
    let mut r = vec![0.0; u.len()];
    let mut row_abs = vec![0.0; u.len()];
    for (col, uc) in u.iter().enumerate() {
        for k in sym.col_ptr()[col]..sym.col_ptr()[col + 1] {
            r[sym.row_idx()[k]] += val[k] * uc;
            row_abs[sym.row_idx()[k]] += (val[k] * uc).abs();
        }
    }
    let boundary = on_box_boundary(&mesh);
    let mut worst = 0.0_f64;
    let mut interior = 0;
    for f in 0..u.len() {
        let (node, _) = dofs.node_dir(f).unwrap();
        if !boundary[node as usize] {
            interior += 1;
            worst = worst.max(r[f].abs() / row_abs[f]);
        }
    }
    eprintln!("{interior} interior dofs, worst residual / row sum {worst:.2e}");
    assert!(interior > 100);
    // Sums of ~100 terms that cancel: relative round-off a few 1e-16; 1e-13 leaves margin.
    assert!(worst < 1e-13, "interior residual {worst:e} of the row sums");

    // Strain energy ½ uᵀ K u = ½ V εᵀ C ε: the box keeps its volume under interior distortion,
    // and the 4-point rule is exact on straight-sided elements.
    let energy = common::dot(&u, &r);
    let volume = 1.0 * 0.8 * 0.6;
    let exact: f64 = volume
        * (0..6)
            .map(|i| (0..6).map(|j| eps[i] * c[i][j] * eps[j]).sum::<f64>())
            .sum::<f64>();
    eprintln!("strain energy relative error {:.2e}", energy / exact - 1.0);
    assert!(
        (energy / exact - 1.0).abs() < 1e-12,
        "energy {energy} vs {exact}"
    );
}
