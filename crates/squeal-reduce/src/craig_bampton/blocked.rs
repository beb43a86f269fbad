//! The constraint modes (eq (3)) and the projection (eqs (6)–(7)) of a part with thousands of
//! boundary coordinates, in blocks of columns, so that the dense constraint modes are held once:
//! as the first `n_B` columns of the part's basis `B = [Ψ, Φ]` itself.
//!
//! # Constraint modes in blocks, straight into the basis
//!
//! Eq (3)'s constraint modes are one solve with the interior factor per boundary coordinate
//! ([`super`]'s module docs: `v = P y − X S⁻¹ C_E e_m / c` with `y = −K_vv⁻¹ K_vm / c` for an
//! eliminated dof `m`, `v = X S⁻¹ e_p` for a constraint row `p`). The columns do not mix, so
//! they are taken [`MODE_BLOCK`] at a time: each block's right-hand sides are formed, solved
//! with the supernodal factor (groups of 16 columns, each column the same bits in a group of
//! any width: `squeal_eigs`' triangular solves), projected, and written into the block's columns
//! of `B` on the free dofs (the eliminated dof `m` gets `1 / c`). The peak holds `B` and one
//! block of `n_v × MODE_BLOCK`, instead of `Ψ_v`, its right-hand sides and `B` (three
//! `n × n_B` blocks).
//!
//! # The projection, eqs (6)–(7), in blocks
//!
//! `K̂ = Bᵀ K B` and `M̂ = Bᵀ M B` are symmetric: only the lower triangle is formed, a block
//! `J` of [`PROJECT_BLOCK`] columns at a time, `W = X B_J` (sparse times dense, `n × |J|`) and
//! `X̂[j ≥ j0, J] = B[:, j ≥ j0]ᵀ W` (dense, BLAS-3), then mirrored: half the flops of the
//! full product and one block `W` at a time instead of a row-major copy of `B`.
//!
//! The constraint-mode block of `K̂` is the Schur complement: each constraint mode is the
//! least-energy motion for its boundary coordinate, so `K Ψ = Cᵀ Λ` (the interior rows of
//! `K_vv ψ_v + K_vm u_m` vanish up to the constraint rows' multipliers, eq (3)) lies on the
//! dofs `S` that the boundary rows `C` touch (the eliminated dofs and the constraint rows'
//! entries). Hence `K̂_BB = Ψᵀ K Ψ = Ψ_Sᵀ (K Ψ)_S`, for the node interface
//! `K_BB − K_Bv K_vv⁻¹ K_vB`: `(K Ψ)_S` is `|S|` sparse rows of `K` times `Ψ`, and the dense
//! product has `|S|` rows instead of `n`. The two forms differ by `Ψ_vᵀ r` with `r` the
//! interior residual of the solves, round-off. The modal columns are formed from all rows:
//! `K̂_NN = Φᵀ K Φ` and the coupling `K̂_NB = Φᵀ K Ψ = (K Φ)ᵀ Ψ` (`n_M n_B N` multiply-adds),
//! so that the reported coupling, zero in exact arithmetic (eq (6): `K Ψ = Cᵀ Λ`, `C Φ = 0`),
//! still measures the solves' round-off (on `S` alone it would be exactly zero for eliminated
//! boundary dofs, where `Φ` vanishes).
//!
//! Every sum runs in an order fixed by the block sizes, not by the thread count: the result
//! is the same bits for any number of threads.

use super::*;

/// Boundary coordinates per block of constraint modes: a multiple of the triangular solve's
/// 16-column groups (no zero-padded group inside the run).
pub(super) const MODE_BLOCK: usize = 256;

/// Basis columns per block `J` of the projection.
pub(super) const PROJECT_BLOCK: usize = 256;

/// Rows of `X̂` per task of the dense product `B[:, rows]ᵀ W` (fixed: the bits do not depend on
/// the thread count).
const OUT_ROWS: usize = 128;

impl Split {
    /// Eq (3) into the first `n_B` columns of `basis` (free-dof rows, zero on entry), in blocks
    /// of `block` boundary coordinates (module docs).
    pub(super) fn constraint_modes_into(
        &self,
        k: &SparseColMat<usize, f64>,
        factor: &SparseCholesky,
        constrained: Option<&ConstrainedFactor<'_>>,
        mut basis: faer::MatMut<'_, f64>,
        block: usize,
    ) -> Result<(), EigError> {
        let nb = self.kinds.len();
        let kr = k.as_ref();
        // One buffer for every block's right-hand sides, zeroed in place: a fresh `n_v × block`
        // allocation per block (300 MB on the fine corner's disc) came back from the kernel
        // as new pages each time, zeroed by page faults (docs/benchmarks.md, the fine corner on
        // main: page zeroing was 12 % of the samples of the disc's constraint modes).
        let mut y_buf = Mat::<f64>::zeros(self.interior.len(), block.max(1).min(nb));
        let mut b0 = 0;
        while b0 < nb {
            let b1 = (b0 + block.max(1)).min(nb);
            // The block's eliminated dofs (row b, dof m, 1 / c) and constraint rows (row b, p).
            let mut eliminated = Vec::new();
            let mut constraint = Vec::new();
            for b in b0..b1 {
                match self.kinds[b] {
                    RowKind::Eliminated { dof, inv } => eliminated.push((b, dof, inv)),
                    RowKind::Constraint(p) => constraint.push((b, p)),
                }
            }
            // y = -K_vv⁻¹ K_vm / c.
            let mut y = y_buf.as_mut().subcols_mut(0, eliminated.len());
            y.fill(0.0);
            for (e, &(_, m, inv)) in eliminated.iter().enumerate() {
                for (r, &v) in kr.row_idx_of_col(m).zip(kr.val_of_col(m)) {
                    if let Some(i) = self.interior_index[r] {
                        y[(i, e)] -= v * inv;
                    }
                }
            }
            if !eliminated.is_empty() {
                factor.solve_in_place(y.as_mut())?;
            }
            let mut x = None;
            if let Some(c) = constrained {
                // P y - X S⁻¹ C_E e_m / c, and X S⁻¹ e_p for the constraint rows.
                if !eliminated.is_empty() {
                    c.project(y.as_mut());
                    let g = Mat::from_fn(self.constraint_rows.len(), eliminated.len(), |p, e| {
                        let (row, _, inv) = eliminated[e];
                        self.constraint_eliminated[p]
                            .iter()
                            .filter(|&&(b, _)| b == row)
                            .map(|&(_, w)| w * inv)
                            .sum()
                    });
                    y -= c.correction(g.as_ref())?;
                }
                if !constraint.is_empty() {
                    let unit =
                        Mat::from_fn(self.constraint_rows.len(), constraint.len(), |i, j| {
                            if i == constraint[j].1 { 1.0 } else { 0.0 }
                        });
                    x = Some(c.correction(unit.as_ref())?);
                }
            }
            for (e, &(b, m, inv)) in eliminated.iter().enumerate() {
                self.expand_into(y.as_ref().col(e), basis.as_mut().col_mut(b));
                basis[(m, b)] = inv;
            }
            if let Some(x) = &x {
                for (j, &(b, _)) in constraint.iter().enumerate() {
                    self.expand_into(x.col(j), basis.as_mut().col_mut(b));
                }
            }
            b0 = b1;
        }
        Ok(())
    }

    /// The free dofs the boundary rows touch (`S` of the module docs), ascending.
    pub(super) fn support(&self, rows: &[Row]) -> Vec<usize> {
        let mut s: Vec<usize> = rows
            .iter()
            .flat_map(|r| r.entries.iter().map(|&(f, _)| f))
            .collect();
        s.sort_unstable();
        s.dedup();
        s
    }
}

/// Eqs (6)–(7) in blocks (module docs): `K̂` with its first `nb` columns from the rows
/// `support` only (the Schur complement), `M̂` from all rows; both symmetric.
pub(super) fn project_blocked(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    basis: MatRef<'_, f64>,
    nb: usize,
    support: &[usize],
    block: usize,
) -> (Mat<f64>, Mat<f64>) {
    let n = basis.ncols();
    let mut k_hat = Mat::<f64>::zeros(n, n);
    let mut m_hat = Mat::<f64>::zeros(n, n);
    let b_support = Mat::from_fn(support.len(), n, |i, j| basis[(support[i], j)]);
    let schur = Some((support, b_support.as_ref()));
    lower_blocks(k, basis, schur, 0..nb, (None, nb), block, &mut k_hat);
    drop(b_support);
    // The modal columns from all rows, from the top row: `K̂_NN` and the coupling `K̂_BN`
    // above it, moved below the diagonal for `mirror`.
    lower_blocks(k, basis, None, nb..n, (Some(0), n), block, &mut k_hat);
    for j in nb..n {
        for i in 0..nb {
            k_hat[(j, i)] = k_hat[(i, j)];
        }
    }
    lower_blocks(m, basis, None, 0..n, (None, n), block, &mut m_hat);
    (mirror(k_hat), mirror(m_hat))
}

/// The lower triangle of `Bᵀ X B` in the columns `cols`, a block `J` (first column `j0`) of
/// `block` columns at a time, rows `out_rows = (start, end)` (`start` the diagonal `j0` when
/// `None`): `W = (X B_J)` on the rows `rows` of `X` (all when `None`; else with the rows of `B`
/// they select, given as a dense copy) and `out[start ≤ j < end, J] = B_rowsᵀ[j, :] W`.
fn lower_blocks(
    x: &SparseColMat<usize, f64>,
    basis: MatRef<'_, f64>,
    rows: Option<(&[usize], MatRef<'_, f64>)>,
    cols: std::ops::Range<usize>,
    out_rows: (Option<usize>, usize),
    block: usize,
    out: &mut Mat<f64>,
) {
    let xr = x.as_ref();
    let mut j0 = cols.start;
    while j0 < cols.end {
        let j1 = (j0 + block.max(1)).min(cols.end);
        // W = X B_J on the chosen rows; X symmetric with both triangles stored, so row i of X
        // is its column i, summed in stored order.
        let (row_list, left) = match rows {
            Some((r, b)) => (Some(r), b),
            None => (None, basis),
        };
        let nrows = row_list.map_or(basis.nrows(), <[usize]>::len);
        let w = sparse_times_block(xr, basis.subcols(j0, j1 - j0), row_list, nrows);
        // out[top..row_end, J] = left[:, top..row_end]ᵀ W, OUT_ROWS rows of out per task.
        let (top, row_end) = (out_rows.0.unwrap_or(j0), out_rows.1);
        let target = out.as_mut().submatrix_mut(top, j0, row_end - top, j1 - j0);
        let mut pieces = Vec::new();
        let mut rest = target;
        let mut start = top;
        while rest.nrows() > 0 {
            let len = OUT_ROWS.min(rest.nrows());
            let (piece, bottom) = rest.split_at_row_mut(len);
            pieces.push((start, piece));
            rest = bottom;
            start += len;
        }
        pieces.into_par_iter().for_each(|(start, piece)| {
            let len = piece.nrows();
            faer::linalg::matmul::matmul(
                piece,
                Accum::Replace,
                left.subcols(start, len).transpose(),
                w.as_ref(),
                1.0,
                Par::Seq,
            );
        });
        j0 = j1;
    }
}

/// `W = X B_J` on `nrows` rows of `X` (`rows[r]`, or `r` itself when `None`), `X` symmetric
/// with both triangles stored (row `i` of `X` is its column `i`).
///
/// Row by row: `B_J` is first copied row-major (`|J|` contiguous values per dof), then each
/// row of `W` is `Σ_q x_iq B_J[q, :]` over `X`'s column `i` in stored order, `X` read once per
/// block. Each entry is the same sum, in the same order, of the same products as the dot
/// product `Σ_q x_iq b_q` of one column at a time (started at `-0.0`, as `Iterator::sum`), so
/// the bits are the same; that form read all of `X` and gathered from `B` once per column
/// (`|J|` times per block) and was a third of the fine corner disc's projection
/// (docs/benchmarks.md, "The fine corner on main, where its time goes").
fn sparse_times_block(
    xr: faer::sparse::SparseColMatRef<'_, usize, f64>,
    block: MatRef<'_, f64>,
    rows: Option<&[usize]>,
    nrows: usize,
) -> Mat<f64> {
    let width = block.ncols();
    let n = block.nrows();
    let mut bt = vec![0.0; n * width];
    bt.par_chunks_mut(width * ROW_TASK)
        .enumerate()
        .for_each(|(t, chunk)| {
            let r0 = t * ROW_TASK;
            let len = chunk.len() / width.max(1);
            for c in 0..width {
                let col = block.col(c);
                for r in 0..len {
                    chunk[r * width + c] = col[r0 + r];
                }
            }
        });
    let mut w = Mat::<f64>::zeros(nrows, width);
    let mut pieces = Vec::new();
    let mut rest = w.as_mut();
    let mut start = 0;
    while rest.nrows() > 0 {
        let len = ROW_TASK.min(rest.nrows());
        let (piece, bottom) = rest.split_at_row_mut(len);
        pieces.push((start, piece));
        rest = bottom;
        start += len;
    }
    pieces.into_par_iter().for_each(|(start, mut piece)| {
        let mut acc = vec![-0.0; width];
        for r in 0..piece.nrows() {
            let i = rows.map_or(start + r, |l| l[start + r]);
            acc.fill(-0.0);
            for (q, &v) in xr.row_idx_of_col(i).zip(xr.val_of_col(i)) {
                let b = &bt[q * width..(q + 1) * width];
                for (a, &bq) in acc.iter_mut().zip(b) {
                    *a += v * bq;
                }
            }
            for (c, &a) in acc.iter().enumerate() {
                piece[(r, c)] = a;
            }
        }
    });
    w
}

/// Rows of `W` (and of the row-major copy of `B_J`) per task of [`sparse_times_block`].
const ROW_TASK: usize = 256;

/// The symmetric matrix whose lower triangle is that of `a`.
fn mirror(mut a: Mat<f64>) -> Mat<f64> {
    for j in 0..a.ncols() {
        for i in 0..j {
            a[(i, j)] = a[(j, i)];
        }
    }
    a
}

#[cfg(test)]
#[path = "blocked_tests.rs"]
mod tests;
