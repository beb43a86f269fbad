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
use faer::sparse::{SparseColMat, SparseColMatRef};
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
    // Tolerance: assembly in floating point may break symmetry by rounding only.
    let tol = 1e-10 * scale;
    let sorted = (0..n).all(|j| a.row_idx_of_col_raw(j).is_sorted_by(|x, y| x < y));
    let first_bad = if sorted {
        // Each off-diagonal entry against its mirror, found by binary search (no copies).
        (0..n).into_par_iter().find_map_first(|j| {
            let mirror = |i: usize| {
                let rows = a.row_idx_of_col_raw(i);
                rows.binary_search(&j).map_or(0.0, |k| a.val_of_col(i)[k])
            };
            a.row_idx_of_col(j)
                .zip(a.val_of_col(j))
                .find(|&(i, &v)| i != j && (v - mirror(i)).abs() > tol)
                .map(|(i, _)| (i, j))
        })
    } else {
        unsorted_asymmetry(a, name, tol)?
    };
    match first_bad {
        Some((row, col)) => Err(EigError::NotSymmetric {
            matrix: name,
            row,
            col,
        }),
        None => Ok(()),
    }
}

/// The first entry (row, column) of a matrix with unsorted or repeated row
/// indices that differs from its transposed entry by more than `tol`
/// (columns merged after sorting, duplicates compared one by one).
fn unsorted_asymmetry(
    a: SparseColMatRef<'_, usize, f64>,
    name: &'static str,
    tol: f64,
) -> Result<Option<(usize, usize)>, EigError> {
    let n = a.nrows();
    let t = a
        .transpose()
        .to_col_major()
        .map_err(|e| EigError::Factorization {
            what: format!(
                "transpose of {name}: {}",
                crate::faer_error::describe_faer(e)
            ),
        })?;
    let t = t.as_ref();
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
                return Ok(Some((i, j)));
            }
        }
    }
    Ok(None)
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
        return Err(pair_mismatch(k, m));
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

/// The error for K and M of different shapes.
fn pair_mismatch(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
) -> EigError {
    EigError::DimensionMismatch {
        what: format!(
            "K is {}x{} but M is {}x{}",
            k.nrows(),
            k.ncols(),
            m.nrows(),
            m.ncols()
        ),
    }
}

/// A = K - sigma M on the union of both patterns (rows sorted, duplicates summed).
pub fn shifted(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    sigma: f64,
) -> Result<SparseColMat<usize, f64>, EigError> {
    if k.nrows() != m.nrows() || k.ncols() != m.ncols() {
        return Err(pair_mismatch(k, m));
    }
    let n = k.ncols();
    let mut col_ptr = Vec::with_capacity(n + 1);
    col_ptr.push(0usize);
    let mut row_idx = Vec::with_capacity(k.compute_nnz() + m.compute_nnz());
    let mut val = Vec::with_capacity(row_idx.capacity());
    let sorted_col = |a: SparseColMatRef<'_, usize, f64>, j: usize, scale: f64| {
        let mut c: Vec<(usize, f64)> = a
            .row_idx_of_col(j)
            .zip(a.val_of_col(j))
            .map(|(i, &v)| (i, scale * v))
            .collect();
        if !c.is_sorted_by_key(|e| e.0) {
            c.sort_by_key(|e| e.0);
        }
        c
    };
    for j in 0..n {
        let kc = sorted_col(k, j, 1.0);
        let mc = sorted_col(m, j, -sigma);
        // Merge the two sorted columns, summing equal rows (and duplicates).
        let (mut p, mut q) = (0, 0);
        while p < kc.len() || q < mc.len() {
            let take_k = q == mc.len() || (p < kc.len() && kc[p].0 <= mc[q].0);
            let (i, v) = if take_k {
                p += 1;
                kc[p - 1]
            } else {
                q += 1;
                mc[q - 1]
            };
            if row_idx.len() > col_ptr[j] && row_idx.last() == Some(&i) {
                if let Some(last) = val.last_mut() {
                    *last += v;
                }
            } else {
                row_idx.push(i);
                val.push(v);
            }
        }
        col_ptr.push(row_idx.len());
    }
    let symbolic = faer::sparse::SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
    Ok(SparseColMat::new(symbolic, val))
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

/// out = V^T w (V is n x p), reduced in fixed chunks of rows (see [`inner`]).
pub fn project(v: MatRef<'_, f64>, w: ColRef<'_, f64>) -> Vec<f64> {
    let out = inner(v, w.as_mat());
    (0..v.ncols()).map(|i| out[(i, 0)]).collect()
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

/// V S as a new n x k matrix (row chunks in parallel, see [`update_rows`]).
pub fn combination(v: MatRef<'_, f64>, s: MatRef<'_, f64>) -> Mat<f64> {
    let mut out = Mat::zeros(v.nrows(), s.ncols());
    update_rows(out.as_mut(), v, s, Accum::Replace, 1.0);
    out
}

/// Euclidean dot product, reduced in fixed chunks.
pub fn dot(x: ColRef<'_, f64>, y: ColRef<'_, f64>) -> f64 {
    project(x.as_mat(), y)[0]
}

/// V^T W (V is n x p, W is n x q), reduced in fixed chunks of rows, the
/// chunk results summed in chunk order.
pub fn inner(v: MatRef<'_, f64>, w: MatRef<'_, f64>) -> Mat<f64> {
    let n = v.nrows();
    let (p, q) = (v.ncols(), w.ncols());
    let nchunks = n.div_ceil(CHUNK);
    let partials: Vec<Mat<f64>> = (0..nchunks)
        .into_par_iter()
        .map(|c| {
            let r0 = c * CHUNK;
            let len = CHUNK.min(n - r0);
            let mut out = Mat::<f64>::zeros(p, q);
            matmul(
                out.as_mut(),
                Accum::Replace,
                v.subrows(r0, len).transpose(),
                w.subrows(r0, len),
                1.0,
                Par::Seq,
            );
            out
        })
        .collect();
    let mut out = Mat::<f64>::zeros(p, q);
    for part in &partials {
        out += part;
    }
    out
}

/// Y = A X for a symmetric A stored with both triangles and a block of
/// columns X, as a gather over the columns of A (each entry of Y is summed
/// in the stored order, so the result is thread-count independent).
pub fn sym_matmul(a: SparseColMatRef<'_, usize, f64>, x: MatRef<'_, f64>) -> Mat<f64> {
    let n = a.ncols();
    let b = x.ncols();
    let mut y = Mat::zeros(n, b);
    if b == 0 || n == 0 {
        return y;
    }
    // X row by row (a row of A X then sums contiguous rows of X), rows in parallel.
    let mut xt = vec![0.0; n * b];
    xt.par_chunks_mut(CHUNK * b)
        .enumerate()
        .for_each(|(chunk, rows)| {
            for (o, row) in rows.chunks_exact_mut(b).enumerate() {
                for (c, v) in row.iter_mut().enumerate() {
                    *v = x[(chunk * CHUNK + o, c)];
                }
            }
        });
    let xt = &xt;
    row_blocks(y.as_mut(), CHUNK)
        .into_par_iter()
        .enumerate()
        .for_each(|(chunk, out)| match b {
            4 => gather_rows::<4>(a, xt, chunk * CHUNK, out),
            8 => gather_rows::<8>(a, xt, chunk * CHUNK, out),
            16 => gather_rows::<16>(a, xt, chunk * CHUNK, out),
            _ => gather_rows_any(a, xt, chunk * CHUNK, out),
        });
    y
}

/// `m` cut into blocks of `rows` rows (the last may be shorter), in order.
fn row_blocks(mut m: MatMut<'_, f64>, rows: usize) -> Vec<MatMut<'_, f64>> {
    let mut blocks = Vec::with_capacity(m.nrows().div_ceil(rows.max(1)));
    while m.nrows() > 0 {
        let len = rows.min(m.nrows());
        let (top, bottom) = m.split_at_row_mut(len);
        blocks.push(top);
        m = bottom;
    }
    blocks
}

/// [`gather_rows`] for any number of columns.
fn gather_rows_any(
    a: SparseColMatRef<'_, usize, f64>,
    xt: &[f64],
    first: usize,
    mut out: MatMut<'_, f64>,
) {
    let b = out.ncols();
    let mut acc = vec![0.0; b];
    for o in 0..out.nrows() {
        acc.fill(0.0);
        for (r, v) in a.row_idx_of_col(first + o).zip(a.val_of_col(first + o)) {
            for (y, xv) in acc.iter_mut().zip(&xt[r * b..r * b + b]) {
                *y += v * xv;
            }
        }
        for (c, &v) in acc.iter().enumerate() {
            out[(o, c)] = v;
        }
    }
}

/// Rows `first..` of Y = A X into the block `out` of Y from
/// X in row-major `xt`: a fixed-width accumulator the compiler vectorizes.
fn gather_rows<const B: usize>(
    a: SparseColMatRef<'_, usize, f64>,
    xt: &[f64],
    first: usize,
    mut out: MatMut<'_, f64>,
) {
    for o in 0..out.nrows() {
        let i = first + o;
        let mut acc = [0.0f64; B];
        for (r, &v) in a.row_idx_of_col(i).zip(a.val_of_col(i)) {
            let Some(xr) = xt.get(r * B..r * B + B) else {
                continue;
            };
            for (y, x) in acc.iter_mut().zip(xr) {
                *y += v * x;
            }
        }
        for (c, &v) in acc.iter().enumerate() {
            out[(o, c)] = v;
        }
    }
}
