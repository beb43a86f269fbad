//! The blocked constraint modes and projection against the unblocked ones of
//! [`super::super::boundary`] on a small part.

use super::*;
use squeal_fe::{ElasticMaterial, assemble};
use squeal_mesh::generate::box_tet10;

/// Largest entry of `a - b` over the largest of `b`.
fn relative(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> f64 {
    let mut diff: f64 = 0.0;
    let mut size: f64 = 0.0;
    for j in 0..b.ncols() {
        for i in 0..b.nrows() {
            diff = diff.max((a[(i, j)] - b[(i, j)]).abs());
            size = size.max(b[(i, j)].abs());
        }
    }
    diff / size
}

/// A 4 x 4 x 2-cell steel block held by its bottom face's dofs (eliminated boundary dofs),
/// with two constraint rows: the mean z motion of the top face's nodes, and a row on a bottom
/// (eliminated) dof and a top dof together (`C_E` of the module docs). Six fixed-interface modes.
/// The blocked constraint modes (blocks of 5 boundary coordinates: eliminated and constraint
/// rows mixed in a block) and the blocked projection (blocks of 7 columns, `K̂_BB` as the
/// Schur complement) against the unblocked ones: the basis and `K̂`, `M̂` agree to 1e-12 of
/// their largest entry. The columns are the same solves (the triangular solve gives a column
/// the same bits in a group of any width); what differs is the order of the sums in the
/// projection and the Schur form's omitted `Ψ_vᵀ r` (the solves' residual), round-off of a
/// few hundred terms: 1.5e-16 and 5.9e-17 measured. A wrong or missing block is an O(1) error.
#[test]
fn blocked_constraint_modes_and_projection_match_unblocked() {
    let mesh = box_tet10([0.1, 0.1, 0.02], [4, 4, 2]);
    let materials =
        MaterialTable::uniform(&mesh, ElasticMaterial::isotropic(210e9, 0.3, 7800.0)).unwrap();
    let dofmap = DofMap::new(&mesh, &[]).unwrap();
    let system = assemble(&mesh, &materials, &dofmap).unwrap();
    let n_free = dofmap.num_free();
    let z = |node: usize| mesh.nodes[node][2];
    let bottom: Vec<u32> = (0..mesh.nodes.len())
        .filter(|&i| z(i) < 1e-9)
        .map(|i| i as u32)
        .collect();
    let top: Vec<u32> = (0..mesh.nodes.len())
        .filter(|&i| z(i) > 0.02 - 1e-9)
        .map(|i| i as u32)
        .collect();
    let mut rows = Vec::new();
    for &node in &bottom {
        for d in 0..3 {
            let dof = dofmap.free_dof(node, d).unwrap();
            let label = boundary::point_label(rows.len() / 3, d);
            rows.push(Row {
                point: rows.len() / 3,
                label,
                entries: vec![(dof, 1.0)],
                footprint: false,
            });
        }
    }
    let w = 1.0 / top.len() as f64;
    let mean_z: Vec<(usize, f64)> = top
        .iter()
        .map(|&node| (dofmap.free_dof(node, 2).unwrap(), w))
        .collect();
    // Put the constraint rows among the eliminated ones, so that blocks mix both kinds.
    let p = rows.len() / 3;
    rows.insert(
        7,
        Row {
            point: p,
            label: boundary::point_label(p, 2),
            entries: mean_z,
            footprint: false,
        },
    );
    let mixed = vec![
        (dofmap.free_dof(bottom[3], 0).unwrap(), 0.5),
        (dofmap.free_dof(top[2], 0).unwrap(), 0.5),
    ];
    rows.insert(
        12,
        Row {
            point: p + 1,
            label: boundary::point_label(p + 1, 0),
            entries: mixed,
            footprint: false,
        },
    );

    let split = Split::new(&rows, n_free, "block").unwrap();
    let k_vv = split.interior_of(&system.k);
    let m_vv = split.interior_of(&system.m);
    let factor =
        SparseCholesky::factorize_with(k_vv.as_ref().as_ref(), &Default::default()).unwrap();
    let constraints = split.constraints().unwrap();
    let constrained = ConstrainedFactor::new(&factor, &constraints).unwrap();
    let modes = lowest_modes_constrained(
        k_vv.as_ref().as_ref(),
        m_vv.as_ref().as_ref(),
        &constrained,
        6,
        &EigOptions::default(),
    )
    .unwrap();
    let (nb, nm) = (rows.len(), modes.values.len());
    assert_eq!(nm, 6);

    // Unblocked: Ψ_v whole, then the basis, then the row-major projection.
    let psi_v = split
        .constraint_modes(&system.k, &factor, Some(&constrained))
        .unwrap();
    let mut reference = Mat::<f64>::zeros(n_free, nb + nm);
    for b in 0..nb {
        split.expand_into(psi_v.col(b), reference.col_mut(b));
        if let Some((m, inv)) = split.eliminated_dof(b) {
            reference[(m, b)] = inv;
        }
    }
    for j in 0..nm {
        split.expand_into(modes.vectors.col(j), reference.col_mut(nb + j));
    }
    let (k_ref, m_ref) = project_pair(&system.k, &system.m, &reference);

    // Blocked.
    let mut basis = Mat::<f64>::zeros(n_free, nb + nm);
    split
        .constraint_modes_into(&system.k, &factor, Some(&constrained), basis.as_mut(), 5)
        .unwrap();
    for j in 0..nm {
        split.expand_into(modes.vectors.col(j), basis.col_mut(nb + j));
    }
    let support = split.support(&rows);
    let (k_hat, m_hat) = project_blocked(&system.k, &system.m, basis.as_ref(), nb, &support, 7);

    let basis_error = relative(basis.as_ref(), reference.as_ref());
    let k_error = relative(k_hat.as_ref(), k_ref.as_ref());
    let m_error = relative(m_hat.as_ref(), m_ref.as_ref());
    eprintln!("basis {basis_error:.2e}, K {k_error:.2e}, M {m_error:.2e} (nb {nb}, nm {nm})");
    assert!(basis_error <= 1e-12, "basis {basis_error:e}");
    assert!(k_error <= 1e-12, "K {k_error:e}");
    assert!(m_error <= 1e-12, "M {m_error:e}");
    // The eliminated dofs' columns of Ψ: the same bits in blocks of 5 as in one block.
    let mut whole = Mat::<f64>::zeros(n_free, nb + nm);
    split
        .constraint_modes_into(&system.k, &factor, None, whole.as_mut(), nb)
        .unwrap();
    let mut pieces = Mat::<f64>::zeros(n_free, nb + nm);
    split
        .constraint_modes_into(&system.k, &factor, None, pieces.as_mut(), 5)
        .unwrap();
    assert!(
        whole == pieces,
        "the unconstrained solves differ between block sizes"
    );
    // W = X B_J row by row: the same bits as the dot product of one column at a time (each
    // entry the same products summed in the same order), on all rows and on the support.
    let mr = system.m.as_ref();
    let by_column = |rows: &[usize]| {
        Mat::from_fn(rows.len(), 7, |r, c| {
            let b = basis.col(3 + c);
            mr.row_idx_of_col(rows[r])
                .zip(mr.val_of_col(rows[r]))
                .map(|(q, &v)| v * b[q])
                .sum::<f64>()
        })
    };
    let all: Vec<usize> = (0..n_free).collect();
    let w = sparse_times_block(mr, basis.subcols(3, 7), None, n_free);
    assert!(
        w == by_column(&all),
        "W = M B_J differs from the column form"
    );
    let w = sparse_times_block(mr, basis.subcols(3, 7), Some(&support), support.len());
    assert!(w == by_column(&support), "W on the support differs");
}
