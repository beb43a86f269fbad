//! Model problems with known spectra, for tests and benchmarks.
//!
//! - The linear finite-element bar (2-node elements, consistent mass):
//!   K = (EA/h) tridiag(-1, 2, -1), M = (rho A h / 6) tridiag(1, 4, 1). With
//!   EA = rho A = 1 its eigenvalues are
//!   lambda_k = (6 / h^2) (1 - cos t_k) / (2 + cos t_k), t_k = k pi h / L,
//!   k = 1..n for fixed-fixed ends and k = 0..n_el for free-free ends.
//! - Tensor-product (trilinear hexahedron, 27-point stencil) box:
//!   K = Kx (x) My (x) Mz + Mx (x) Ky (x) Mz + Mx (x) My (x) Kz,
//!   M = Mx (x) My (x) Mz with fixed-fixed bars in each direction; its
//!   eigenvalues are lambda_x,i + lambda_y,j + lambda_z,k (separation of
//!   variables), so a square or cube grid has multiple eigenvalues.
//! - A 3-dof-per-node variant (an anisotropic stiffness per component plus
//!   a coupling C (x) M) with the pattern of a 3D solid mesh, for benchmarks.

use faer::sparse::{SparseColMat, SymbolicSparseColMat};

/// Boundary condition of the 1D bar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ends {
    /// Both ends fixed: the n_el - 1 interior nodes are the unknowns.
    Fixed,
    /// Both ends free: all n_el + 1 nodes are unknowns (one zero eigenvalue).
    Free,
}

/// A pair of matrices (K, M), both triangles stored.
#[derive(Debug, Clone)]
pub struct Pencil {
    /// Stiffness.
    pub k: SparseColMat<usize, f64>,
    /// Mass.
    pub m: SparseColMat<usize, f64>,
}

/// 1D bar of length `length` with `n_el` linear elements (EA = rho A = 1).
pub fn bar(n_el: usize, length: f64, ends: Ends) -> Pencil {
    let h = length / n_el as f64;
    let n = match ends {
        Ends::Fixed => n_el.saturating_sub(1),
        Ends::Free => n_el + 1,
    };
    let end_weight = |i: usize| match ends {
        Ends::Free if i == 0 || i + 1 == n => 1.0,
        _ => 2.0,
    };
    let k = tridiagonal(n, |i| end_weight(i) / h, -1.0 / h);
    let m = tridiagonal(n, |i| end_weight(i) * 2.0 * h / 6.0, h / 6.0);
    Pencil { k, m }
}

/// Exact eigenvalues of [`bar`], ascending.
pub fn bar_eigenvalues(n_el: usize, length: f64, ends: Ends) -> Vec<f64> {
    let h = length / n_el as f64;
    let ks: Vec<usize> = match ends {
        Ends::Fixed => (1..n_el).collect(),
        Ends::Free => (0..=n_el).collect(),
    };
    ks.iter()
        .map(|&k| {
            let t = k as f64 * std::f64::consts::PI / n_el as f64;
            6.0 / (h * h) * (1.0 - t.cos()) / (2.0 + t.cos())
        })
        .collect()
}

/// Scalar trilinear box with `dims[d]` interior nodes along direction d on
/// edge lengths `lengths`, all faces fixed.
pub fn box_scalar(dims: [usize; 3], lengths: [f64; 3]) -> Pencil {
    let alpha = [[1.0; 3]];
    let coupling = [[0.0]];
    tensor_box::<1>(dims, lengths, &alpha, &coupling)
}

/// Exact eigenvalues of [`box_scalar`], ascending.
pub fn box_scalar_eigenvalues(dims: [usize; 3], lengths: [f64; 3]) -> Vec<f64> {
    let e: Vec<Vec<f64>> = (0..3)
        .map(|d| bar_eigenvalues(dims[d] + 1, lengths[d], Ends::Fixed))
        .collect();
    let mut out = Vec::with_capacity(dims.iter().product());
    for x in &e[0] {
        for y in &e[1] {
            for z in &e[2] {
                out.push(x + y + z);
            }
        }
    }
    out.sort_by(f64::total_cmp);
    out
}

/// 3 dofs per node on a trilinear box: component c has stiffness
/// `sum_d alpha[c][d] (Kd (x) others' M)`, plus the coupling `C (x) M` with
/// `C = [[2,1,0],[1,2,1],[0,1,2]]` (positive definite), as in a 3D solid.
/// 81 nonzeros per row in the interior, like a hexahedral elasticity matrix.
pub fn box_vector(dims: [usize; 3], lengths: [f64; 3]) -> Pencil {
    let alpha = [[1.0, 0.8, 0.6], [0.7, 1.0, 0.9], [0.5, 0.6, 1.0]];
    let coupling = [[2.0, 1.0, 0.0], [1.0, 2.0, 1.0], [0.0, 1.0, 2.0]];
    tensor_box::<3>(dims, lengths, &alpha, &coupling)
}

/// Tridiagonal symmetric n x n matrix with diagonal `diag(i)` and constant off-diagonal.
fn tridiagonal(n: usize, diag: impl Fn(usize) -> f64, off: f64) -> SparseColMat<usize, f64> {
    let mut col_ptr = vec![0usize];
    let mut row_idx = Vec::with_capacity(3 * n);
    let mut val = Vec::with_capacity(3 * n);
    for j in 0..n {
        if j > 0 {
            row_idx.push(j - 1);
            val.push(off);
        }
        row_idx.push(j);
        val.push(diag(j));
        if j + 1 < n {
            row_idx.push(j + 1);
            val.push(off);
        }
        col_ptr.push(row_idx.len());
    }
    SparseColMat::new(
        SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx),
        val,
    )
}

/// Entries of the 1D fixed-fixed bar matrices between nodes i and i + d (d in -1..=1).
fn bar_entry(h: f64, d: isize) -> (f64, f64) {
    if d == 0 {
        (2.0 / h, 4.0 * h / 6.0)
    } else {
        (-1.0 / h, h / 6.0)
    }
}

/// Assembles the tensor-product box with `NC` components per node, directly
/// in compressed columns (rows sorted).
fn tensor_box<const NC: usize>(
    dims: [usize; 3],
    lengths: [f64; 3],
    alpha: &[[f64; 3]; NC],
    coupling: &[[f64; NC]; NC],
) -> Pencil {
    let [nx, ny, nz] = dims;
    let h = [0, 1, 2].map(|d| lengths[d] / (dims[d] + 1) as f64);
    let nodes = nx * ny * nz;
    let n = nodes * NC;
    let mut col_ptr = Vec::with_capacity(n + 1);
    col_ptr.push(0usize);
    let mut row_idx = Vec::with_capacity(n * 27 * NC);
    let mut kv = Vec::with_capacity(n * 27 * NC);
    let mut mv = Vec::with_capacity(n * 27 * NC);
    let idx = |i: usize, j: usize, k: usize| i + nx * (j + ny * k);
    for node in 0..nodes {
        let (i, j, k) = (node % nx, (node / nx) % ny, node / (nx * ny));
        let p = [i as isize, j as isize, k as isize];
        for c in 0..NC {
            for dk in -1..=1isize {
                for dj in -1..=1isize {
                    for di in -1..=1isize {
                        let q = [p[0] + di, p[1] + dj, p[2] + dk];
                        if (0..3).any(|d| q[d] < 0 || q[d] >= dims[d] as isize) {
                            continue;
                        }
                        let e = [di, dj, dk];
                        let ent = [0, 1, 2].map(|d| bar_entry(h[d], e[d]));
                        let mass = ent[0].1 * ent[1].1 * ent[2].1;
                        let qn = idx(q[0] as usize, q[1] as usize, q[2] as usize);
                        for (c2, &couple) in coupling[c].iter().enumerate() {
                            let mut kval = couple * mass;
                            if c == c2 {
                                kval += alpha[c][0] * ent[0].0 * ent[1].1 * ent[2].1
                                    + alpha[c][1] * ent[0].1 * ent[1].0 * ent[2].1
                                    + alpha[c][2] * ent[0].1 * ent[1].1 * ent[2].0;
                            }
                            row_idx.push(qn * NC + c2);
                            kv.push(kval);
                            mv.push(if c == c2 { mass } else { 0.0 });
                        }
                    }
                }
            }
            col_ptr.push(row_idx.len());
        }
    }
    let sym = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
    let k = SparseColMat::new(sym.clone(), kv);
    let m = drop_zeros(SparseColMat::new(sym, mv));
    Pencil { k, m }
}

/// Removes explicit zeros (the mass of a vector problem does not couple components).
fn drop_zeros(a: SparseColMat<usize, f64>) -> SparseColMat<usize, f64> {
    let n = a.ncols();
    let mut col_ptr = vec![0usize];
    let mut row_idx = Vec::new();
    let mut val = Vec::new();
    for j in 0..n {
        for (i, &v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
            if v != 0.0 {
                row_idx.push(i);
                val.push(v);
            }
        }
        col_ptr.push(row_idx.len());
    }
    SparseColMat::new(
        SymbolicSparseColMat::new_checked(a.nrows(), n, col_ptr, None, row_idx),
        val,
    )
}
