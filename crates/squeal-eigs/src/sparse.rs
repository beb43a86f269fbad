//! Sparse helpers: input checks, K - sigma M, products with symmetric
//! matrices stored with both triangles, and deterministic dense kernels.
//!
//! Determinism: every reduction over the long dimension n is split into
//! chunks of a fixed size ([`CHUNK`]), each chunk is reduced sequentially and
//! the chunk results are summed in chunk order. The bits therefore do not
//! depend on the number of threads.

use crate::EigError;
use faer::linalg::matmul::matmul;
use faer::reborrow::ReborrowMut;
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use faer::{Accum, ColMut, ColRef, Mat, MatMut, MatRef, Par};
use rayon::prelude::*;

/// Rows per chunk in the dense kernels (fixed so that results are thread-count independent).
pub(crate) const CHUNK: usize = 4096;

/// Checks that `a` is square with finite entries and symmetric (both
/// triangles stored). `name` appears in errors.
pub fn check_symmetric(
    a: SparseColMatRef<'_, usize, f64>,
    name: &'static str,
) -> Result<(), EigError> {
    let n = a.nrows();
    if a.ncols() != n {
        return Err(EigError::DimensionMismatch {
            what: format!("{name} is {}x{}, not square", n, a.ncols()),
        });
    }
    let mut scale = 0.0f64;
    for j in 0..n {
        for &v in a.val_of_col(j) {
            if !v.is_finite() {
                return Err(EigError::NonFinite {
                    matrix: name,
                    col: j,
                });
            }
            scale = scale.max(v.abs());
        }
    }
    let t = a
        .transpose()
        .to_col_major()
        .map_err(|e| EigError::Factorization {
            what: format!("transpose of {name}: {e:?}"),
        })?;
    let t = t.as_ref();
    // Tolerance: assembly in floating point may break symmetry by rounding only.
    let tol = 1e-10 * scale;
    for j in 0..n {
        let mut col: Vec<(usize, f64)> = a
            .row_idx_of_col(j)
            .zip(a.val_of_col(j).iter().copied())
            .collect();
        let mut colt: Vec<(usize, f64)> = t
            .row_idx_of_col(j)
            .zip(t.val_of_col(j).iter().copied())
            .collect();
        col.sort_by_key(|p| p.0);
        colt.sort_by_key(|p| p.0);
        let (mut p, mut q) = (0, 0);
        while p < col.len() || q < colt.len() {
            let (i, d) = match (col.get(p), colt.get(q)) {
                (Some(&(i, x)), Some(&(k, y))) if i == k => {
                    p += 1;
                    q += 1;
                    (i, x - y)
                }
                (Some(&(i, x)), Some(&(k, _))) if i < k => {
                    p += 1;
                    (i, x)
                }
                (Some(&(i, x)), None) => {
                    p += 1;
                    (i, x)
                }
                (_, Some(&(k, y))) => {
                    q += 1;
                    (k, y)
                }
                (None, None) => break,
            };
            if d.abs() > tol {
                return Err(EigError::NotSymmetric {
                    matrix: name,
                    row: i,
                    col: j,
                });
            }
        }
    }
    Ok(())
}

/// Checks K and M for the generalized problem: both square, same size,
/// finite, symmetric; M with a positive diagonal.
pub fn check_pair(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
) -> Result<(), EigError> {
    check_symmetric(k, "K")?;
    check_symmetric(m, "M")?;
    if k.nrows() != m.nrows() {
        return Err(EigError::DimensionMismatch {
            what: format!(
                "K is {}x{} but M is {}x{}",
                k.nrows(),
                k.ncols(),
                m.nrows(),
                m.ncols()
            ),
        });
    }
    for j in 0..m.ncols() {
        let d: f64 = m
            .row_idx_of_col(j)
            .zip(m.val_of_col(j))
            .filter(|(i, _)| *i == j)
            .map(|(_, v)| *v)
            .sum();
        if d.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(EigError::MassNotPositive { index: j });
        }
    }
    Ok(())
}

/// A = K - sigma M on the union of both patterns (rows sorted, duplicates summed).
pub fn shifted(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    sigma: f64,
) -> Result<SparseColMat<usize, f64>, EigError> {
    if k.nrows() != m.nrows() || k.ncols() != m.ncols() {
        return Err(EigError::DimensionMismatch {
            what: format!(
                "K is {}x{} but M is {}x{}",
                k.nrows(),
                k.ncols(),
                m.nrows(),
                m.ncols()
            ),
        });
    }
    let n = k.ncols();
    let mut triplets = Vec::with_capacity(k.compute_nnz() + m.compute_nnz());
    for j in 0..n {
        for (i, &v) in k.row_idx_of_col(j).zip(k.val_of_col(j)) {
            triplets.push(Triplet::new(i, j, v));
        }
        for (i, &v) in m.row_idx_of_col(j).zip(m.val_of_col(j)) {
            triplets.push(Triplet::new(i, j, -sigma * v));
        }
    }
    SparseColMat::try_new_from_triplets(n, n, &triplets).map_err(|e| EigError::Factorization {
        what: format!("assembling K - sigma M: {e:?}"),
    })
}

/// y = A x for a symmetric A stored with both triangles, as a gather over
/// columns (column i of A is row i): each y_i is summed in the stored order,
/// so the result is thread-count independent.
pub fn sym_matvec(a: SparseColMatRef<'_, usize, f64>, x: ColRef<'_, f64>, mut y: ColMut<'_, f64>) {
    let n = a.ncols();
    let ys = y.rb_mut().try_as_col_major_mut().map(|c| c.as_slice_mut());
    let body = |i: usize| -> f64 {
        a.row_idx_of_col(i)
            .zip(a.val_of_col(i))
            .map(|(r, v)| v * x[r])
            .sum()
    };
    match ys {
        Some(ys) => ys.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
            for (o, yi) in out.iter_mut().enumerate() {
                *yi = body(c * CHUNK + o);
            }
        }),
        None => {
            for i in 0..n {
                y[i] = body(i);
            }
        }
    }
}

/// Matrix 1-norm (max column sum of |a_ij|); equals the inf-norm for symmetric A.
pub fn norm1(a: SparseColMatRef<'_, usize, f64>) -> f64 {
    (0..a.ncols())
        .map(|j| a.val_of_col(j).iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// out = V^T w (V is n x p), reduced in fixed chunks of rows.
pub fn project(v: MatRef<'_, f64>, w: ColRef<'_, f64>) -> Vec<f64> {
    let n = v.nrows();
    let p = v.ncols();
    let nchunks = n.div_ceil(CHUNK);
    let partials: Vec<Mat<f64>> = (0..nchunks)
        .into_par_iter()
        .map(|c| {
            let r0 = c * CHUNK;
            let len = CHUNK.min(n - r0);
            let mut out = Mat::<f64>::zeros(p, 1);
            matmul(
                out.as_mut(),
                Accum::Replace,
                v.subrows(r0, len).transpose(),
                w.subrows(r0, len).as_mat(),
                1.0,
                Par::Seq,
            );
            out
        })
        .collect();
    let mut out = vec![0.0; p];
    for part in &partials {
        for (o, i) in out.iter_mut().zip(0..p) {
            *o += part[(i, 0)];
        }
    }
    out
}

/// w <- w - V h, row chunks in parallel (each row is independent).
pub fn subtract_combination(w: ColMut<'_, f64>, v: MatRef<'_, f64>, h: &[f64]) {
    let hc = faer::ColRef::from_slice(h);
    update_rows(w.as_mat_mut(), v, hc.as_mat(), Accum::Add, -1.0);
}

/// out <- V S (or out += alpha V S), row chunks in parallel.
pub fn update_rows(
    out: MatMut<'_, f64>,
    v: MatRef<'_, f64>,
    s: MatRef<'_, f64>,
    accum: Accum,
    alpha: f64,
) {
    let n = out.nrows();
    let nchunks = n.div_ceil(CHUNK);
    let mut pieces = Vec::with_capacity(nchunks);
    let mut rest = out;
    for c in 0..nchunks {
        let len = CHUNK.min(n - c * CHUNK);
        let (top, bot) = rest.split_at_row_mut(len);
        pieces.push((c * CHUNK, top));
        rest = bot;
    }
    pieces.into_par_iter().for_each(|(r0, piece)| {
        let len = piece.nrows();
        matmul(piece, accum, v.subrows(r0, len), s, alpha, Par::Seq);
    });
}

/// Euclidean dot product, reduced in fixed chunks.
pub fn dot(x: ColRef<'_, f64>, y: ColRef<'_, f64>) -> f64 {
    project(x.as_mat(), y)[0]
}
