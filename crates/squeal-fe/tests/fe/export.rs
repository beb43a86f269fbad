//! MatrixMarket export read back with squeal-io's reader, and the dof-map CSV.

use super::common;
use common::steel;
use squeal_fe::{DofMap, MaterialTable, Restraint, assemble, write_matrix_market};
use squeal_mesh::generate::box_tet10;

#[test]
fn matrices_and_dof_map_round_trip() {
    let mesh = box_tet10([0.2, 0.1, 0.1], [2, 1, 1]);
    let materials = MaterialTable::uniform(&mesh, steel()).unwrap();
    let dofs = DofMap::new(
        &mesh,
        &[
            Restraint::clamp("XMIN"),
            Restraint::set("XMAX", [false, true, false]),
        ],
    )
    .unwrap();
    let sys = assemble(&mesh, &materials, &dofs).unwrap();
    let dir = std::env::temp_dir().join(format!("squeal-fe-export-{}", std::process::id()));
    write_matrix_market(&dir, "box", &sys.k, &sys.m, &dofs).unwrap();

    for (name, a) in [("box_K.mtx", &sys.k), ("box_M.mtx", &sys.m)] {
        let t = squeal_io::mtx::read(&dir.join(name)).unwrap();
        assert_eq!((t.nrows, t.ncols), (dofs.num_free(), dofs.num_free()));
        // The reader mirrors the lower triangle: all stored entries come back, bit for bit
        // (shortest round-trip formatting).
        let mut read: Vec<(usize, usize, u64)> = t
            .entries
            .iter()
            .map(|&(r, c, v)| (r, c, v.to_bits()))
            .collect();
        read.sort();
        let s = a.symbolic();
        let mut stored = Vec::new();
        for c in 0..a.ncols() {
            for k in s.col_ptr()[c]..s.col_ptr()[c + 1] {
                stored.push((s.row_idx()[k], c, a.val()[k].to_bits()));
            }
        }
        stored.sort();
        assert_eq!(read, stored, "{name}");
    }

    let csv = std::fs::read_to_string(dir.join("box_dofs.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("dof,node,direction"));
    let rows: Vec<Vec<u64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), dofs.num_free());
    let index = mesh.node_index_map();
    for (f, row) in rows.iter().enumerate() {
        // 1-based dof and direction, node by file id.
        assert_eq!(row[0], f as u64 + 1);
        let node = index[&row[1]];
        assert_eq!(dofs.free_dof(node, row[2] as usize - 1), Some(f));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
