//! MatrixMarket export of `K` and `M` with the dof map, for MATLAB and Python users.

use crate::dofmap::DofMap;
use crate::error::FeError;
use faer::sparse::SparseColMat;
use squeal_io::mtx::{CscRef, Symmetry, write_csc};
use std::path::Path;

/// Writes `<stem>_K.mtx` and `<stem>_M.mtx` (MatrixMarket `coordinate real symmetric`, lower
/// triangle, 1-based) and `<stem>_dofs.csv` (header `dof,node,direction`: the 1-based row of
/// the matrices, the node's id in the mesh file, the direction 1 = x, 2 = y, 3 = z) into
/// `dir`, each file atomically.
///
/// Python (SciPy):
/// ```text
/// import numpy as np, scipy.io
/// K = scipy.io.mmread("disc_K.mtx").tocsc()   # full symmetric matrix
/// M = scipy.io.mmread("disc_M.mtx").tocsc()
/// dofs = np.loadtxt("disc_dofs.csv", delimiter=",", skiprows=1, dtype=int)
/// # row i of K (0-based) is node dofs[i, 1], direction dofs[i, 2]
/// ```
/// MATLAB (`mmread.m` from math.nist.gov/MatrixMarket also works):
/// ```text
/// T = readmatrix('disc_K.mtx', 'FileType', 'text', 'CommentStyle', '%');
/// n = T(1, 1);  T = T(2:end, :);
/// K = sparse(T(:, 1), T(:, 2), T(:, 3), n, n);  K = K + tril(K, -1)';
/// dofs = readmatrix('disc_dofs.csv');             % columns: dof, node, direction
/// ```
pub fn write_matrix_market(
    dir: &Path,
    stem: &str,
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    dofmap: &DofMap,
) -> Result<(), FeError> {
    let note = |what: &str| {
        format!(
            "squeal-fe {what} over {} free dofs, node-major; row i is described by line i of {stem}_dofs.csv",
            dofmap.num_free()
        )
    };
    write_one(
        &dir.join(format!("{stem}_K.mtx")),
        k,
        &note("stiffness K (N/m)"),
    )?;
    write_one(
        &dir.join(format!("{stem}_M.mtx")),
        m,
        &note("consistent mass M (kg)"),
    )?;
    let path = dir.join(format!("{stem}_dofs.csv"));
    squeal_io::atomic_write(&path, |w| {
        writeln!(w, "dof,node,direction")?;
        for f in 0..dofmap.num_free() {
            if let Some((node, d)) = dofmap.node_dir(f) {
                let id = dofmap.node_id(node).unwrap_or(u64::from(node));
                writeln!(w, "{},{},{}", f + 1, id, d + 1)?;
            }
        }
        Ok(())
    })?;
    Ok(())
}

fn write_one(path: &Path, a: &SparseColMat<usize, f64>, comment: &str) -> Result<(), FeError> {
    let s = a.symbolic();
    let csc = CscRef {
        nrows: a.nrows(),
        ncols: a.ncols(),
        col_ptr: s.col_ptr(),
        row_idx: s.row_idx(),
        values: a.val(),
    };
    write_csc(path, csc, Symmetry::Symmetric, comment)?;
    Ok(())
}
