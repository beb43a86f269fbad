//! Helpers shared by the integration tests: mesh perturbations, sparse/dense products, and
//! eigenvalue solvers built on faer (dense: Cholesky + symmetric eigenproblem; sparse:
//! shift-invert subspace iteration with Rayleigh–Ritz, Bathe's algorithm).
#![allow(dead_code)]

use faer::linalg::solvers::Solve;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::sparse::SparseColMat;
use faer::sparse::linalg::matmul::sparse_dense_matmul;
use faer::{Accum, Mat, Par, Side};
use squeal_mesh::Mesh;

pub type Sparse = SparseColMat<usize, f64>;

/// Steel: E = 210 GPa, ν = 0.3, ρ = 7850 kg/m³.
pub fn steel() -> squeal_fe::ElasticMaterial {
    squeal_fe::ElasticMaterial::isotropic(210e9, 0.3, 7850.0)
}

/// Deterministic pseudo-random numbers in [-1, 1) (SplitMix64).
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// Whether each node lies on the boundary of the box mesh (in one of XMIN..ZMAX).
pub fn on_box_boundary(mesh: &Mesh) -> Vec<bool> {
    let mut b = vec![false; mesh.num_nodes()];
    for set in ["XMIN", "XMAX", "YMIN", "YMAX", "ZMIN", "ZMAX"] {
        for &n in mesh.node_set(set).unwrap() {
            b[n as usize] = true;
        }
    }
    b
}

/// Whether each node is a vertex (local index < 4) of some element.
pub fn is_vertex(mesh: &Mesh) -> Vec<bool> {
    let mut v = vec![false; mesh.num_nodes()];
    for el in &mesh.blocks.tet10 {
        for &n in &el[..4] {
            v[n as usize] = true;
        }
    }
    v
}

/// Moves interior vertices by up to `amp` in each direction, then puts every midside node back
/// at its edge midpoint: a distorted mesh of straight-sided elements.
pub fn distort_vertices(mesh: &mut Mesh, amp: f64, seed: u64) {
    let boundary = on_box_boundary(mesh);
    let vertex = is_vertex(mesh);
    let mut rng = Rng(seed);
    for n in 0..mesh.num_nodes() {
        if vertex[n] && !boundary[n] {
            for d in 0..3 {
                mesh.nodes[n][d] += amp * rng.next();
            }
        }
    }
    for el in mesh.blocks.tet10.clone() {
        for (k, [a, b]) in squeal_mesh::tet10::EDGES.iter().enumerate() {
            let (pa, pb) = (mesh.nodes[el[*a] as usize], mesh.nodes[el[*b] as usize]);
            mesh.nodes[el[4 + k] as usize] = std::array::from_fn(|d| 0.5 * (pa[d] + pb[d]));
        }
    }
}

/// Moves midside nodes by up to `amp` in each direction (curved elements): only interior ones
/// if `interior_only`, else all.
pub fn curve_midside(mesh: &mut Mesh, amp: f64, seed: u64, interior_only: bool) {
    let boundary = on_box_boundary(mesh);
    let vertex = is_vertex(mesh);
    let mut rng = Rng(seed);
    for n in 0..mesh.num_nodes() {
        if !vertex[n] && (!interior_only || !boundary[n]) {
            for d in 0..3 {
                mesh.nodes[n][d] += amp * rng.next();
            }
        }
    }
}

/// `y = A x`.
pub fn matvec(a: &Sparse, x: &[f64]) -> Vec<f64> {
    let s = a.symbolic();
    let mut y = vec![0.0; a.nrows()];
    for (c, xc) in x.iter().enumerate().take(a.ncols()) {
        for k in s.col_ptr()[c]..s.col_ptr()[c + 1] {
            y[s.row_idx()[k]] += a.val()[k] * xc;
        }
    }
    y
}

pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

pub fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// Frobenius norm of the stored entries.
pub fn frobenius(a: &Sparse) -> f64 {
    a.val().iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// Dense copy.
pub fn dense(a: &Sparse) -> Mat<f64> {
    let s = a.symbolic();
    let mut d = Mat::<f64>::zeros(a.nrows(), a.ncols());
    for c in 0..a.ncols() {
        for k in s.col_ptr()[c]..s.col_ptr()[c + 1] {
            d[(s.row_idx()[k], c)] += a.val()[k];
        }
    }
    d
}

/// Eigenpairs of a dense symmetric matrix, eigenvalues ascending.
///
/// faer 0.24.4's `self_adjoint_eigen` (divide and conquer, used from n = 128 up) is not scale
/// invariant: on matrices whose norm is far from 1 (FE stiffness ~1e11) its eigenvalues and
/// vectors are off by up to 1e-3 relative, while `self_adjoint_eigenvalues` stays accurate.
/// So the matrix is scaled to unit max-norm first, and the residual is checked.
pub fn sym_eigen(a: &Mat<f64>) -> (Vec<f64>, Mat<f64>) {
    let s = a.norm_max();
    let scaled = Mat::from_fn(a.nrows(), a.ncols(), |i, j| {
        0.5 * (a[(i, j)] + a[(j, i)]) / s
    });
    let evd = scaled.self_adjoint_eigen(Side::Lower).expect("eigen");
    let u = evd.U().to_owned();
    let residual = (&scaled * &u - &u * evd.S()).norm_max();
    assert!(
        residual < 1e-10,
        "dense symmetric eigensolver residual {residual:e}"
    );
    ((0..a.nrows()).map(|i| evd.S()[i] * s).collect(), u)
}

/// Eigenpairs of the dense symmetric-definite pencil `(K, M)`: `M = L Lᵀ`, eigenproblem of
/// `L⁻¹ K L⁻ᵀ`, vectors mapped back by `L⁻ᵀ` (M-orthonormal). Eigenvalues ascending.
pub fn dense_eigen(k: &Mat<f64>, m: &Mat<f64>) -> (Vec<f64>, Mat<f64>) {
    let llt = m.llt(Side::Lower).expect("M positive definite");
    let l = llt.L();
    let mut x = k.clone();
    solve_lower_triangular_in_place(l, x.as_mut(), Par::Seq);
    let mut a = x.transpose().to_owned();
    solve_lower_triangular_in_place(l, a.as_mut(), Par::Seq);
    let (values, mut vecs) = sym_eigen(&a);
    solve_upper_triangular_in_place(l.transpose(), vecs.as_mut(), Par::Seq);
    (values, vecs)
}

/// Eigenvalues only, of the dense pencil.
pub fn dense_eigenvalues(k: &Mat<f64>, m: &Mat<f64>) -> Vec<f64> {
    dense_eigen(k, m).0
}

/// The `count` lowest eigenvalues of `K x = λ M x` by shift-invert subspace iteration
/// (Bathe, Finite Element Procedures, sec. 11.6): factor `K - σ M` once (sparse Cholesky,
/// so `σ` must lie below the spectrum), iterate `Y = (K - σM)⁻¹ M X`, Rayleigh–Ritz on
/// `span(Y)` with the dense solver, until the wanted Ritz values change by less than 1e-9
/// of the largest one (they settle within 3 or 4 iterations on a noise floor of ~1e-11 from
/// the cancellation in `Yᵀ K Y`).
pub fn lowest_eigenvalues(k: &Sparse, m: &Sparse, count: usize, shift: f64) -> Vec<f64> {
    let n = k.nrows();
    let p = (2 * count).max(count + 8).min(n);
    let shifted = faer::sparse::ops::binary_op(k.as_ref(), m.as_ref(), |a, b| {
        a.copied().unwrap_or(0.0) - shift * b.copied().unwrap_or(0.0)
    })
    .unwrap();
    let llt = shifted
        .sp_cholesky(Side::Lower)
        .expect("K - shift M positive definite");
    let mut rng = Rng(7);
    let mut x = Mat::from_fn(n, p, |_, _| rng.next());
    let mut previous = vec![f64::INFINITY; count];
    for _ in 0..200 {
        let mut y = Mat::<f64>::zeros(n, p);
        sparse_dense_matmul(
            y.as_mut(),
            Accum::Replace,
            m.as_ref(),
            x.as_ref(),
            1.0,
            Par::Seq,
        );
        llt.solve_in_place(y.as_mut());
        let mut ky = Mat::<f64>::zeros(n, p);
        let mut my = Mat::<f64>::zeros(n, p);
        sparse_dense_matmul(
            ky.as_mut(),
            Accum::Replace,
            k.as_ref(),
            y.as_ref(),
            1.0,
            Par::Seq,
        );
        sparse_dense_matmul(
            my.as_mut(),
            Accum::Replace,
            m.as_ref(),
            y.as_ref(),
            1.0,
            Par::Seq,
        );
        let kr = y.transpose() * &ky;
        let mr = y.transpose() * &my;
        let kr = Mat::from_fn(p, p, |i, j| 0.5 * (kr[(i, j)] + kr[(j, i)]));
        let mr = Mat::from_fn(p, p, |i, j| 0.5 * (mr[(i, j)] + mr[(j, i)]));
        let (values, q) = dense_eigen(&kr, &mr);
        x = &y * &q;
        let scale = values[..count].iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        let done = (0..count).all(|i| (values[i] - previous[i]).abs() <= 1e-9 * scale);
        previous.copy_from_slice(&values[..count]);
        if done {
            break;
        }
    }
    previous
}

/// Frequency in Hz of an eigenvalue `ω²`.
pub fn hz(lambda: f64) -> f64 {
    lambda.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}

/// Moves interior vertices of a mesh of any element kinds by up to `amp` in each direction,
/// then puts every midside node back at its edge midpoint: a distorted mesh with straight
/// edges.
pub fn distort_solid(mesh: &mut Mesh, amp: f64, seed: u64) {
    let boundary = on_box_boundary(mesh);
    let mut vertex = vec![false; mesh.num_nodes()];
    for (kind, range) in mesh.blocks.kinds() {
        for e in range {
            let (_, c) = mesh.blocks.get(e).unwrap();
            for &n in &c[..kind.vertices()] {
                vertex[n as usize] = true;
            }
        }
    }
    let mut rng = Rng(seed);
    for n in 0..mesh.num_nodes() {
        if vertex[n] && !boundary[n] {
            for d in 0..3 {
                mesh.nodes[n][d] += amp * rng.next();
            }
        }
    }
    for (kind, range) in mesh.blocks.kinds() {
        for e in range {
            let c = mesh.blocks.get(e).unwrap().1.to_vec();
            for (k, [a, b]) in kind.edges().iter().enumerate() {
                let (pa, pb) = (mesh.nodes[c[*a] as usize], mesh.nodes[c[*b] as usize]);
                mesh.nodes[c[kind.vertices() + k] as usize] =
                    std::array::from_fn(|d| 0.5 * (pa[d] + pb[d]));
            }
        }
    }
}

/// An anisotropic material, so that every entry of C takes part (the patch tests).
pub fn lining() -> squeal_fe::ElasticMaterial {
    squeal_fe::ElasticMaterial::TransverselyIsotropic {
        young_plane: 6.0e9,
        poisson_plane: 0.25,
        young_axial: 2.0e9,
        poisson_plane_axial: 0.12,
        shear_axial: 1.1e9,
        axis: [0.2, 0.5, 1.0],
        density: 2500.0,
    }
}

/// The gradient of the patch tests' linear field.
pub const PATCH_A: [[f64; 3]; 3] = [
    [1.0e-3, 2.0e-4, -3.0e-4],
    [-1.0e-4, -5.0e-4, 4.0e-4],
    [2.5e-4, 1.5e-4, 7.0e-4],
];

/// The offset of the patch tests' linear field.
pub const PATCH_B: [f64; 3] = [1e-3, -2e-3, 5e-4];

/// The patch tests' linear field `B + A x`.
pub fn linear_field(x: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| PATCH_B[i] + (0..3).map(|j| PATCH_A[i][j] * x[j]).sum::<f64>())
}
