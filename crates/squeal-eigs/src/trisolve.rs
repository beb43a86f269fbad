//! Supernodal triangular solves with a Cholesky factor A = P^T L L^T P of
//! faer's supernodal storage, parallel over subtrees of the elimination tree
//! and inside the large supernodes, with result bits that do not depend on
//! the thread count.
//!
//! # The solves
//!
//! The columns of L are grouped into supernodes s: consecutive columns
//! c0 .. c0 + w whose rows below the diagonal block share one pattern P_s.
//! faer stores each as a dense column-major block [L_ss; L_Ps] of
//! w + |P_s| rows. The forward solve L y = b runs over the supernodes in
//! ascending order,
//!
//! ```text
//! y_s = L_ss^-1 b_s,            b_(P_s) <- b_(P_s) - L_Ps y_s,
//! ```
//!
//! and the backward solve L^T x = y in descending order,
//!
//! ```text
//! x_s = L_ss^-T (y_s - L_Ps^T x_(P_s)).
//! ```
//!
//! Both work on the supernode's frontal vector f = [b_s; 0] (forward) or
//! [y_s; x_(P_s)] (backward) of w + |P_s| rows, so that a column of the
//! stored block meets a contiguous piece of f. The diagonal block is taken
//! in panels of [`PANEL`] columns: forward, a panel's triangle is solved
//! column by column and then all rows below the panel are updated by its
//! columns; backward, the panel's columns first take the dot products with
//! everything below the panel, then the triangle is solved upwards. Every
//! row's sum is thus accumulated in one fixed order (by column, ascending
//! forward; by row, ascending backward), however the rows below a panel or
//! the columns of a panel are shared among threads: large supernodes use
//! rayon inside with identical bits.
//!
//! # Parallel subtrees
//!
//! Supernode s writes (forward) or reads (backward) only its own rows and
//! those of P_s, which belong to its ancestors in the supernodal elimination
//! tree (parent: the supernode of the first row of P_s). The tree is split,
//! from the root down, into "top" supernodes and disjoint subtrees of at most
//! 1/[`TASKS`] of the factor's entries each; with a postordered fill ordering
//! (nested dissection here) each subtree is a contiguous range of columns.
//! Forward, the subtrees run in parallel, each adding its updates of top
//! rows into a buffer of its own; the buffers are added to b in subtree
//! order, then the top supernodes run in order. Backward, the top
//! supernodes run first, then the subtrees in parallel, reading the final
//! top rows. The split depends on the factor only, not on the thread count,
//! so neither do the result bits.
//!
//! Right-hand sides are solved in groups of 16 columns stored row by row (one
//! small array per row of the factor), the last group zero-padded to 1, 2, 4,
//! 8 or 16 columns, the groups in parallel. The columns do not mix: a column
//! gets the same bits in a group of any width.
//! Arithmetic is fused multiply-adds (exactly rounded, so the same bits on
//! any instruction set), vectorized by `pulp`'s run-time choice of
//! instruction set (AVX2 with FMA where the processor has it).

// Index loops over rows and over the W columns of a row read like the
// formulas, and let the kernels hoist their bounds checks.
#![allow(clippy::needless_range_loop)]

use faer::MatMut;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use rayon::prelude::*;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::ops::Range;

mod kernels;
#[allow(unused_imports)]
use kernels::*;

/// Columns per panel of a diagonal block.
const PANEL: usize = 32;
/// Subtrees hold at most 1/TASKS of the factor's entries each.
const TASKS: usize = 48;
/// A panel update of at least this many factor entries runs in parallel
/// (only in top supernodes: the subtrees are parallel already).
const PAR_ENTRIES: usize = 1 << 15;
/// Rows per parallel chunk below a panel.
const ROW_CHUNK: usize = 512;
/// "No index" marker of the u32 maps.
const NONE: u32 = u32::MAX;

/// One supernode of the factor: first column, width, pattern below the
/// diagonal block, and the stored column-major block of
/// `ncols + pattern.len()` rows.
#[derive(Clone, Copy)]
struct Supernode<'a> {
    start: usize,
    ncols: usize,
    pattern: &'a [usize],
    l: &'a [f64],
}

impl Supernode<'_> {
    fn nrows(&self) -> usize {
        self.ncols + self.pattern.len()
    }

    /// Column c of the block from row `from` down.
    fn col(&self, c: usize, from: usize) -> &[f64] {
        let nrows = self.nrows();
        &self.l[c * nrows + from..(c + 1) * nrows]
    }
}

/// faer's supernodal factor: symbolic structure and values.
#[derive(Clone, Copy)]
pub(crate) struct Factor<'a> {
    pub symbolic: &'a SymbolicSupernodalCholesky<usize>,
    pub values: &'a [f64],
}

impl<'a> Factor<'a> {
    fn supernode(&self, s: usize) -> Supernode<'a> {
        let v = self.symbolic.col_ptr_for_val();
        Supernode {
            l: &self.values[v[s]..v[s + 1]],
            ..structure(self.symbolic, s)
        }
    }
}

/// Supernode s without its values.
fn structure(sym: &SymbolicSupernodalCholesky<usize>, s: usize) -> Supernode<'_> {
    let start = sym.supernode_begin()[s];
    let p0 = sym.col_ptr_for_row_idx()[s];
    Supernode {
        start,
        ncols: sym.supernode_end()[s] - start,
        pattern: &sym.row_idx()[p0..p0 + sym.nnz_per_super()[s]],
        l: &[],
    }
}

/// A subtree solved as one task.
#[derive(Debug, Clone)]
struct Task {
    /// Its supernodes (a contiguous range, children before parents).
    supernodes: Range<usize>,
    /// Its columns (= rows of x it owns).
    rows: Range<usize>,
    /// Top rows (compact numbering) its forward solve updates, ascending.
    touched: Vec<u32>,
    /// Compact top row -> position in `touched` (NONE if untouched).
    local: Vec<u32>,
}

/// How the supernodes of one factor are shared among tasks; made once per
/// symbolic factorization.
#[derive(Debug, Clone)]
pub(crate) struct SolvePlan {
    tasks: Vec<Task>,
    /// Supernodes outside every task, ascending.
    top: Vec<usize>,
    /// Row -> compact index among the rows of top supernodes (NONE otherwise).
    top_pos: Vec<u32>,
    /// Compact index -> row.
    top_rows: Vec<usize>,
    /// Rows of the tallest supernode (scratch size).
    max_rows: usize,
    /// Fraction of the factor's entries in top supernodes.
    top_fraction: f64,
}

impl SolvePlan {
    /// Splits the supernodal elimination tree of `factor` into top
    /// supernodes and subtree tasks (see the module documentation).
    pub(crate) fn new(symbolic: &SymbolicSupernodalCholesky<usize>) -> Self {
        let ns = symbolic.n_supernodes();
        let n = symbolic.nrows();
        let begin = symbolic.supernode_begin();
        let end = symbolic.supernode_end();
        let mut of_col = vec![0u32; n];
        for s in 0..ns {
            of_col[begin[s]..end[s]].fill(s as u32);
        }
        let nnz_per = symbolic.nnz_per_super();
        let cp = symbolic.col_ptr_for_row_idx();
        let rows = symbolic.row_idx();
        let parent: Vec<usize> = (0..ns)
            .map(|s| {
                rows[cp[s]..cp[s] + nnz_per[s]]
                    .iter()
                    .min()
                    .map_or(usize::MAX, |&r| of_col[r] as usize)
            })
            .collect();
        let entries = |s: usize| (end[s] - begin[s]) * (end[s] - begin[s] + nnz_per[s]);
        let mut subtree: Vec<usize> = (0..ns).map(entries).collect();
        let mut first = (0..ns).collect::<Vec<_>>();
        let mut count = vec![1usize; ns];
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); ns];
        let mut ordered = true;
        for s in 0..ns {
            let p = parent[s];
            if p == usize::MAX {
                continue;
            }
            if p <= s {
                ordered = false;
                continue;
            }
            subtree[p] += subtree[s];
            first[p] = first[p].min(first[s]);
            count[p] += count[s];
            children[p].push(s);
        }
        let total: usize = (0..ns).map(entries).sum();
        let max_rows = (0..ns)
            .map(|s| structure(symbolic, s).nrows())
            .max()
            .unwrap_or(0);
        let serial = |max_rows| Self {
            tasks: Vec::new(),
            top: (0..ns).collect(),
            top_pos: Vec::new(),
            top_rows: Vec::new(),
            max_rows,
            top_fraction: 1.0,
        };
        if !ordered {
            return serial(max_rows);
        }
        // Split the largest subtree until every subtree is small enough.
        let limit = (total / TASKS).max(1);
        let mut heap: BinaryHeap<(usize, Reverse<usize>)> = (0..ns)
            .filter(|&s| parent[s] == usize::MAX)
            .map(|s| (subtree[s], Reverse(s)))
            .collect();
        let mut top = Vec::new();
        let mut roots = Vec::new();
        while let Some((work, Reverse(s))) = heap.pop() {
            if work <= limit || children[s].is_empty() {
                roots.push(s);
            } else {
                top.push(s);
                heap.extend(children[s].iter().map(|&c| (subtree[c], Reverse(c))));
            }
        }
        // A subtree must be a contiguous range of supernodes (postorder).
        if roots.iter().any(|&r| count[r] != r - first[r] + 1) {
            return serial(max_rows);
        }
        top.sort_unstable();
        roots.sort_unstable();
        let mut top_pos = vec![NONE; n];
        let mut top_rows = Vec::new();
        for &s in &top {
            for r in begin[s]..end[s] {
                top_pos[r] = top_rows.len() as u32;
                top_rows.push(r);
            }
        }
        let n_top = top_rows.len();
        let tasks = roots
            .iter()
            .map(|&r| {
                let supernodes = first[r]..r + 1;
                let cols = begin[first[r]]..end[r];
                let mut touched: Vec<u32> = supernodes
                    .clone()
                    .flat_map(|s| structure(symbolic, s).pattern.iter())
                    .filter(|&&row| row >= cols.end)
                    .map(|&row| top_pos[row])
                    .collect();
                touched.sort_unstable();
                touched.dedup();
                let mut local = vec![NONE; n_top];
                for (k, &t) in touched.iter().enumerate() {
                    local[t as usize] = k as u32;
                }
                Task {
                    supernodes,
                    rows: cols,
                    touched,
                    local,
                }
            })
            .collect::<Vec<_>>();
        // A top row left unmapped would mean a broken tree: solve serially.
        if tasks.iter().flat_map(|t| &t.touched).any(|&t| t == NONE) {
            return serial(max_rows);
        }
        let top_entries: usize = top.iter().map(|&s| entries(s)).sum();
        Self {
            tasks,
            top,
            top_pos,
            top_rows,
            max_rows,
            top_fraction: top_entries as f64 / total.max(1) as f64,
        }
    }

    /// Subtree tasks and the fraction of the factor's entries outside them.
    pub(crate) fn shape(&self) -> (usize, f64) {
        (self.tasks.len(), self.top_fraction)
    }
}

/// Solves A X = B in place for the columns of `rhs` (input numbering),
/// where A = P^T L L^T P with `perm[new] = old`.
pub(crate) fn solve(plan: &SolvePlan, factor: Factor<'_>, inv: &[usize], rhs: MatMut<'_, f64>) {
    let mut groups = Vec::new();
    let mut rest = rhs;
    while rest.ncols() > 0 {
        let c = rest.ncols().min(16);
        let (left, right) = rest.split_at_col_mut(c);
        groups.push(left);
        rest = right;
    }
    // Each group is one pass over the factor: the last one is padded with zero columns to the
    // next kernel width rather than split.
    groups.into_par_iter().for_each(|g| match g.ncols() {
        9.. => solve_group::<16>(plan, factor, inv, g),
        5.. => solve_group::<8>(plan, factor, inv, g),
        3.. => solve_group::<4>(plan, factor, inv, g),
        2 => solve_group::<2>(plan, factor, inv, g),
        _ => solve_group::<1>(plan, factor, inv, g),
    });
}

/// One group of at most W columns: gather into rows of the permuted order
/// (`inv[old] = new`, zeros beyond the group's columns), forward and
/// backward solve, scatter back.
fn solve_group<const W: usize>(
    plan: &SolvePlan,
    factor: Factor<'_>,
    inv: &[usize],
    mut rhs: MatMut<'_, f64>,
) {
    let n = inv.len();
    let mut x = vec![[0.0; W]; n];
    for j in 0..rhs.ncols() {
        let col = rhs.rb().col(j);
        for (old, &new) in inv.iter().enumerate() {
            x[new][j] = col[old];
        }
    }
    forward(plan, factor, &mut x);
    backward(plan, factor, &mut x);
    for j in 0..rhs.ncols() {
        let mut col = rhs.rb_mut().col_mut(j);
        for (old, &new) in inv.iter().enumerate() {
            col[old] = x[new][j];
        }
    }
}

/// The rows of x owned by each task, in task order.
fn task_slices<'x, const W: usize>(
    plan: &'x SolvePlan,
    x: &'x mut [[f64; W]],
) -> Vec<(&'x Task, &'x mut [[f64; W]])> {
    let mut out = Vec::with_capacity(plan.tasks.len());
    let mut rest = x;
    let mut at = 0;
    for t in &plan.tasks {
        let (_, tail) = rest.split_at_mut(t.rows.start - at);
        let (mine, tail) = tail.split_at_mut(t.rows.len());
        out.push((t, mine));
        rest = tail;
        at = t.rows.end;
    }
    out
}

/// Where a forward step adds its updates of pattern rows.
enum Updates<'a, const W: usize> {
    /// All rows in the array being solved.
    All,
    /// Rows below `end` in the task's own array, top rows in the task's
    /// buffer (through the compact top numbering and the task's map).
    Buffer {
        end: usize,
        top_pos: &'a [u32],
        local: &'a [u32],
        buf: &'a mut [[f64; W]],
    },
}

/// Where a backward step reads pattern rows.
enum Reads<'a, const W: usize> {
    /// All rows in the array being solved.
    All,
    /// Rows below `end` in the task's own array, top rows (final) in `top`.
    Top {
        end: usize,
        top_pos: &'a [u32],
        top: &'a [[f64; W]],
    },
}

/// L y = b.
fn forward<const W: usize>(plan: &SolvePlan, factor: Factor<'_>, x: &mut [[f64; W]]) {
    let arch = pulp::Arch::new();
    let buffers: Vec<Vec<[f64; W]>> = task_slices(plan, x)
        .into_par_iter()
        .map(|(task, own)| {
            let mut buf = vec![[0.0; W]; task.touched.len()];
            arch.dispatch(Steps {
                factor,
                supernodes: task.supernodes.clone(),
                own,
                base: task.rows.start,
                rows: Phase::Forward(Updates::Buffer {
                    end: task.rows.end,
                    top_pos: &plan.top_pos,
                    local: &task.local,
                    buf: &mut buf,
                }),
                max_rows: plan.max_rows,
                parallel: false,
            });
            buf
        })
        .collect();
    for (task, buf) in plan.tasks.iter().zip(&buffers) {
        for (&t, b) in task.touched.iter().zip(buf) {
            add(&mut x[plan.top_rows[t as usize]], b);
        }
    }
    arch.dispatch(Steps {
        factor,
        supernodes: plan.top.iter().copied(),
        own: x,
        base: 0,
        rows: Phase::Forward(Updates::All),
        max_rows: plan.max_rows,
        parallel: true,
    });
}

/// L^T x = y.
fn backward<const W: usize>(plan: &SolvePlan, factor: Factor<'_>, x: &mut [[f64; W]]) {
    let arch = pulp::Arch::new();
    arch.dispatch(Steps {
        factor,
        supernodes: plan.top.iter().rev().copied(),
        own: &mut *x,
        base: 0,
        rows: Phase::Backward(Reads::All),
        max_rows: plan.max_rows,
        parallel: true,
    });
    let top: Vec<[f64; W]> = plan.top_rows.iter().map(|&r| x[r]).collect();
    task_slices(plan, x)
        .into_par_iter()
        .for_each(|(task, own)| {
            arch.dispatch(Steps {
                factor,
                supernodes: task.supernodes.clone().rev(),
                own,
                base: task.rows.start,
                rows: Phase::Backward(Reads::Top {
                    end: task.rows.end,
                    top_pos: &plan.top_pos,
                    top: &top,
                }),
                max_rows: plan.max_rows,
                parallel: false,
            })
        });
}

/// Forward or backward steps of a sequence of supernodes on `own` (rows
/// `base..`), as a unit of work compiled for the instruction set `pulp`
/// picks at run time (closures would not be: they are not inlined into its
/// dispatch).
struct Steps<'a, 'b, I, const W: usize> {
    factor: Factor<'a>,
    supernodes: I,
    own: &'b mut [[f64; W]],
    base: usize,
    rows: Phase<'b, W>,
    max_rows: usize,
    parallel: bool,
}

/// Which solve, with where its pattern rows live.
enum Phase<'b, const W: usize> {
    Forward(Updates<'b, W>),
    Backward(Reads<'b, W>),
}

impl<I: Iterator<Item = usize>, const W: usize> pulp::WithSimd for Steps<'_, '_, I, W> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let mut f = vec![[0.0; W]; self.max_rows];
        let (own, base, parallel) = (self.own, self.base, self.parallel);
        match self.rows {
            Phase::Forward(mut updates) => {
                for s in self.supernodes {
                    let sn = self.factor.supernode(s);
                    forward_supernode(sn, own, base, &mut updates, &mut f, parallel);
                }
            }
            Phase::Backward(reads) => {
                for s in self.supernodes {
                    let sn = self.factor.supernode(s);
                    backward_supernode(sn, own, base, &reads, &mut f, parallel);
                }
            }
        }
    }
}
