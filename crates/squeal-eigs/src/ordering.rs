//! Fill-reducing orderings for the sparse Cholesky and LBL^T factorizations.
//!
//! [`FillOrdering::NestedDissection`] is George's nested dissection (SIAM J.
//! Numer. Anal. 10, 1973) with multilevel bisection in the manner of METIS
//! (Karypis & Kumar, SIAM J. Sci. Comput. 20, 1998):
//!
//! 1. the matrix graph is compressed to its node graph: consecutive columns
//!    with the same pattern (the 1-3 dofs of a mesh node) become one vertex
//!    weighted by their count;
//! 2. each (sub)graph is coarsened by heavy-edge matching, bisected on the
//!    coarsest level by greedy graph growing, and the bisection is projected
//!    back level by level with Fiduccia-Mattheyses refinement of the edge cut;
//! 3. the cut edges form a bipartite graph whose minimum vertex cover
//!    (Koenig's theorem, from a maximum matching) is the vertex separator;
//! 4. both halves are dissected recursively (in parallel: they are
//!    independent, so the result does not depend on the thread count), the
//!    separator is numbered after them, and small pieces are ordered by AMD;
//! 5. the dof order is postordered along its elimination tree (same fill,
//!    contiguous subtrees) so that the supernodes are found.
//!
//! Everything is deterministic: no random numbers, ties broken by index.

use crate::EigError;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::SymbolicSparseColMatRef;
use faer::sparse::linalg::amd;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Which fill-reducing ordering the factorizations use.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum FillOrdering {
    /// Approximate minimum degree (faer's AMD).
    Amd,
    /// Nested dissection of the node graph (this module), AMD on small pieces.
    #[default]
    NestedDissection,
}

/// Graph pieces with at most this many vertices (nodes) are ordered by AMD.
const LEAF_VERTICES: usize = 60;
/// Coarsening stops at this many vertices.
const COARSEST: usize = 60;
/// A side of a bisection may hold at most this fraction of the weight.
const MAX_SIDE: f64 = 0.55;
/// FM passes per level at most.
const FM_PASSES: usize = 6;

/// A symmetric graph in compressed rows, without self loops.
#[derive(Debug, Clone, Default)]
struct Graph {
    xadj: Vec<usize>,
    adj: Vec<u32>,
    /// Edge weights, aligned with `adj`.
    ewgt: Vec<u32>,
    /// Vertex weights.
    vwgt: Vec<u32>,
}

impl Graph {
    fn n(&self) -> usize {
        self.vwgt.len()
    }

    fn neighbours(&self, v: usize) -> impl Iterator<Item = (usize, u32)> + '_ {
        let r = self.xadj[v]..self.xadj[v + 1];
        self.adj[r.clone()]
            .iter()
            .zip(&self.ewgt[r])
            .map(|(&u, &w)| (u as usize, w))
    }

    fn total_weight(&self) -> u64 {
        self.vwgt.iter().map(|&w| w as u64).sum()
    }
}

/// Fill-reducing permutation of a symmetric pattern (both triangles, or
/// either: the graph is symmetrized), as `perm[new] = old`.
pub(crate) fn nested_dissection(
    a: SymbolicSparseColMatRef<'_, usize>,
) -> Result<Vec<usize>, EigError> {
    let n = a.ncols();
    let (graph, members) = node_graph(a)?;
    let mut node_order = Vec::with_capacity(graph.n());
    let ids: Vec<u32> = (0..graph.n() as u32).collect();
    dissect(&graph, &ids, &mut node_order)?;
    let mut perm = Vec::with_capacity(n);
    for &v in &node_order {
        perm.extend(members[v as usize].clone());
    }
    Ok(postorder(a, &perm))
}

/// Columns of `a` as sorted, deduplicated index lists of the symmetrized
/// pattern, each including its own index.
fn symmetric_columns(a: SymbolicSparseColMatRef<'_, usize>) -> Vec<Vec<u32>> {
    let n = a.ncols();
    let mut cols: Vec<Vec<u32>> = (0..n).map(|j| vec![j as u32]).collect();
    for j in 0..n {
        for i in a.row_idx_of_col(j) {
            if i != j {
                cols[j].push(i as u32);
                cols[i].push(j as u32);
            }
        }
    }
    for c in &mut cols {
        c.sort_unstable();
        c.dedup();
    }
    cols
}

/// The node graph: consecutive columns with equal patterns are one vertex.
/// Returns the graph and the columns of each vertex.
fn node_graph(a: SymbolicSparseColMatRef<'_, usize>) -> Result<(Graph, Vec<Vec<usize>>), EigError> {
    let n = a.ncols();
    if n >= u32::MAX as usize {
        return Err(EigError::InvalidOption {
            what: format!("nested dissection: order {n} exceeds the u32 index range"),
        });
    }
    let cols = symmetric_columns(a);
    let mut vertex_of = vec![0u32; n];
    let mut members: Vec<Vec<usize>> = Vec::new();
    for j in 0..n {
        if j > 0 && cols[j] == cols[j - 1] {
            vertex_of[j] = vertex_of[j - 1];
            if let Some(last) = members.last_mut() {
                last.push(j);
            }
        } else {
            vertex_of[j] = members.len() as u32;
            members.push(vec![j]);
        }
    }
    let nv = members.len();
    let mut xadj = Vec::with_capacity(nv + 1);
    xadj.push(0);
    let mut adj = Vec::new();
    for m in &members {
        let mut nb: Vec<u32> = cols[m[0]].iter().map(|&i| vertex_of[i as usize]).collect();
        nb.dedup();
        let me = vertex_of[m[0]];
        adj.extend(nb.into_iter().filter(|&u| u != me));
        xadj.push(adj.len());
    }
    let ewgt = vec![1; adj.len()];
    let vwgt = members.iter().map(|m| m.len() as u32).collect();
    Ok((
        Graph {
            xadj,
            adj,
            ewgt,
            vwgt,
        },
        members,
    ))
}

/// Appends to `out` the nested-dissection order of `g`, whose vertex v is
/// `ids[v]` in the caller's numbering.
fn dissect(g: &Graph, ids: &[u32], out: &mut Vec<u32>) -> Result<(), EigError> {
    if g.n() <= LEAF_VERTICES {
        return order_leaf(g, ids, out);
    }
    let side = bisect(g);
    let sep = separator(g, &side);
    let mut part = side;
    for &v in &sep {
        part[v] = 2;
    }
    let count = |p: u8| part.iter().filter(|&&x| x == p).count();
    if count(0) == 0 || count(1) == 0 {
        return order_leaf(g, ids, out);
    }
    let (g0, ids0) = induced(g, ids, &part, 0);
    let (g1, ids1) = induced(g, ids, &part, 1);
    let mut out0 = Vec::with_capacity(g0.n());
    let mut out1 = Vec::with_capacity(g1.n());
    let (r0, r1) = rayon::join(
        || dissect(&g0, &ids0, &mut out0),
        || dissect(&g1, &ids1, &mut out1),
    );
    r0?;
    r1?;
    out.extend(out0);
    out.extend(out1);
    out.extend(sep.iter().map(|&v| ids[v]));
    Ok(())
}

/// The subgraph of the vertices with `part[v] == p`, and their ids.
fn induced(g: &Graph, ids: &[u32], part: &[u8], p: u8) -> (Graph, Vec<u32>) {
    let mut local = vec![u32::MAX; g.n()];
    let mut sub_ids = Vec::new();
    let mut vwgt = Vec::new();
    for v in 0..g.n() {
        if part[v] == p {
            local[v] = sub_ids.len() as u32;
            sub_ids.push(ids[v]);
            vwgt.push(g.vwgt[v]);
        }
    }
    let mut xadj = Vec::with_capacity(sub_ids.len() + 1);
    xadj.push(0);
    let mut adj = Vec::new();
    let mut ewgt = Vec::new();
    for v in (0..g.n()).filter(|&v| part[v] == p) {
        for (u, w) in g.neighbours(v) {
            if part[u] == p {
                adj.push(local[u]);
                ewgt.push(w);
            }
        }
        xadj.push(adj.len());
    }
    (
        Graph {
            xadj,
            adj,
            ewgt,
            vwgt,
        },
        sub_ids,
    )
}

/// AMD order of a small piece (faer's AMD on its pattern).
fn order_leaf(g: &Graph, ids: &[u32], out: &mut Vec<u32>) -> Result<(), EigError> {
    let n = g.n();
    if n <= 2 {
        out.extend_from_slice(ids);
        return Ok(());
    }
    let mut row_idx = Vec::with_capacity(g.adj.len() + n);
    let mut col_ptr = Vec::with_capacity(n + 1);
    col_ptr.push(0usize);
    for v in 0..n {
        let mut c: Vec<usize> = g.neighbours(v).map(|(u, _)| u).collect();
        c.push(v);
        c.sort_unstable();
        row_idx.extend(c);
        col_ptr.push(row_idx.len());
    }
    let nnz = row_idx.len();
    let pattern = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
    let mut perm = vec![0usize; n];
    let mut inv = vec![0usize; n];
    let fail = |what: &str| EigError::Factorization {
        what: format!("nested dissection leaf AMD: {what}"),
    };
    let mut mem = MemBuffer::try_new(amd::order_maybe_unsorted_scratch::<usize>(n, nnz))
        .map_err(|_| fail("out of memory"))?;
    amd::order_maybe_unsorted(
        &mut perm,
        &mut inv,
        pattern,
        amd::Control::default(),
        MemStack::new(&mut mem),
    )
    .map_err(|e| fail(&crate::faer_error::describe_faer(e)))?;
    out.extend(perm.iter().map(|&p| ids[p]));
    Ok(())
}

/// Multilevel bisection: side 0 or 1 for every vertex.
fn bisect(g: &Graph) -> Vec<u8> {
    let mut levels: Vec<(Graph, Vec<u32>)> = Vec::new();
    let mut current = g.clone();
    while current.n() > COARSEST {
        let (coarse, map) = coarsen(&current);
        // Stop when matching no longer shrinks the graph much (e.g. a star).
        if coarse.n() as f64 > 0.9 * current.n() as f64 {
            break;
        }
        levels.push((std::mem::replace(&mut current, coarse), map));
    }
    let mut side = initial_partition(&current);
    refine(&current, &mut side);
    while let Some((fine, map)) = levels.pop() {
        side = map.iter().map(|&c| side[c as usize]).collect();
        refine(&fine, &mut side);
    }
    side
}

/// Heavy-edge matching (vertices visited by ascending degree, ties by
/// index); returns the coarse graph and the coarse vertex of each vertex.
fn coarsen(g: &Graph) -> (Graph, Vec<u32>) {
    let n = g.n();
    let max_vwgt = (g.total_weight() / 20).max(1);
    let mut visit: Vec<usize> = (0..n).collect();
    visit.sort_by_key(|&v| (g.xadj[v + 1] - g.xadj[v], v));
    let mut mate = vec![u32::MAX; n];
    for &v in &visit {
        if mate[v] != u32::MAX {
            continue;
        }
        let mut best: Option<(u32, usize)> = None;
        for (u, w) in g.neighbours(v) {
            let fits = (g.vwgt[u] + g.vwgt[v]) as u64 <= max_vwgt;
            if mate[u] == u32::MAX && u != v && fits && best.is_none_or(|(bw, _)| w > bw) {
                best = Some((w, u));
            }
        }
        let u = best.map_or(v, |(_, u)| u);
        mate[v] = u as u32;
        mate[u] = v as u32;
    }
    let mut map = vec![u32::MAX; n];
    let mut nc = 0u32;
    for v in 0..n {
        if map[v] == u32::MAX {
            map[v] = nc;
            map[mate[v] as usize] = nc;
            nc += 1;
        }
    }
    let nc = nc as usize;
    let mut vwgt = vec![0u32; nc];
    let mut first = vec![u32::MAX; nc];
    for v in 0..n {
        vwgt[map[v] as usize] += g.vwgt[v];
        if first[map[v] as usize] == u32::MAX {
            first[map[v] as usize] = v as u32;
        }
    }
    let mut xadj = Vec::with_capacity(nc + 1);
    xadj.push(0);
    let mut adj = Vec::new();
    let mut ewgt: Vec<u32> = Vec::new();
    let mut slot = vec![usize::MAX; nc];
    for (c, &v) in first.iter().enumerate() {
        let start = adj.len();
        let v = v as usize;
        let m = mate[v] as usize;
        let both = if m == v { vec![v] } else { vec![v, m] };
        for x in both {
            for (u, w) in g.neighbours(x) {
                let cu = map[u] as usize;
                if cu == c {
                    continue;
                }
                if slot[cu] == usize::MAX || slot[cu] < start {
                    slot[cu] = adj.len();
                    adj.push(cu as u32);
                    ewgt.push(w);
                } else {
                    ewgt[slot[cu]] += w;
                }
            }
        }
        xadj.push(adj.len());
    }
    (
        Graph {
            xadj,
            adj,
            ewgt,
            vwgt,
        },
        map,
    )
}

/// Sum of the weights of edges between the two sides.
fn cut(g: &Graph, side: &[u8]) -> u64 {
    let mut c = 0u64;
    for v in 0..g.n() {
        for (u, w) in g.neighbours(v) {
            if side[u] != side[v] {
                c += w as u64;
            }
        }
    }
    c / 2
}

/// Greedy graph growing from a few pseudo-peripheral seeds; the best
/// refined cut wins.
fn initial_partition(g: &Graph) -> Vec<u8> {
    let n = g.n();
    let mut best: Option<(u64, Vec<u8>)> = None;
    let mut seed = 0usize;
    let tries = 4.min(n);
    for t in 0..tries {
        let start = if t == 0 {
            pseudo_peripheral(g, 0)
        } else {
            (seed + t * n / tries) % n
        };
        seed = start;
        let mut side = grow(g, start);
        refine(g, &mut side);
        let c = cut(g, &side);
        if best.as_ref().is_none_or(|(bc, _)| c < *bc) {
            best = Some((c, side));
        }
    }
    best.map_or_else(|| vec![0; n], |(_, s)| s)
}

/// Breadth-first search levels from `start` (unreached: usize::MAX) and the last vertex reached.
fn bfs(g: &Graph, start: usize) -> (Vec<usize>, usize) {
    let mut level = vec![usize::MAX; g.n()];
    let mut queue = std::collections::VecDeque::new();
    level[start] = 0;
    queue.push_back(start);
    let mut last = start;
    while let Some(v) = queue.pop_front() {
        last = v;
        for (u, _) in g.neighbours(v) {
            if level[u] == usize::MAX {
                level[u] = level[v] + 1;
                queue.push_back(u);
            }
        }
    }
    (level, last)
}

/// A vertex far from `start` (repeated BFS to the farthest vertex).
fn pseudo_peripheral(g: &Graph, start: usize) -> usize {
    let mut v = start;
    let mut depth = 0;
    for _ in 0..4 {
        let (level, last) = bfs(g, v);
        if level[last] <= depth {
            break;
        }
        depth = level[last];
        v = last;
    }
    v
}

/// Side 0 grown by BFS from `start` until it holds half the weight (other
/// components are entered in index order if one is not enough).
fn grow(g: &Graph, start: usize) -> Vec<u8> {
    let n = g.n();
    let half = g.total_weight() / 2;
    let mut side = vec![1u8; n];
    let mut queued = vec![false; n];
    let mut queue = std::collections::VecDeque::new();
    let mut weight = 0u64;
    let mut next_unvisited = 0usize;
    queue.push_back(start);
    queued[start] = true;
    while weight < half {
        let Some(v) = queue.pop_front() else {
            while next_unvisited < n && queued[next_unvisited] {
                next_unvisited += 1;
            }
            if next_unvisited == n {
                break;
            }
            queued[next_unvisited] = true;
            queue.push_back(next_unvisited);
            continue;
        };
        side[v] = 0;
        weight += g.vwgt[v] as u64;
        for (u, _) in g.neighbours(v) {
            if !queued[u] {
                queued[u] = true;
                queue.push_back(u);
            }
        }
    }
    side
}

/// Fiduccia-Mattheyses refinement of a bisection's edge cut under the
/// balance constraint (each side at most `MAX_SIDE` of the weight).
fn refine(g: &Graph, side: &mut [u8]) {
    let n = g.n();
    let total = g.total_weight();
    let max_w = ((MAX_SIDE * total as f64) as u64).max(total / 2 + 1);
    let mut weight = [0u64; 2];
    for v in 0..n {
        weight[side[v] as usize] += g.vwgt[v] as u64;
    }
    // gain[v]: cut reduction if v changes side.
    let gain_of = |side: &[u8], v: usize| -> i64 {
        g.neighbours(v)
            .map(|(u, w)| {
                if side[u] != side[v] {
                    w as i64
                } else {
                    -(w as i64)
                }
            })
            .sum()
    };
    let mut gain: Vec<i64> = (0..n).map(|v| gain_of(side, v)).collect();
    let mut cur = cut(g, side) as i64;
    for _ in 0..FM_PASSES {
        let start_cut = cur;
        let start_imb = imbalance(&weight, max_w);
        let mut locked = vec![false; n];
        let mut heap = BinaryHeap::new();
        for v in 0..n {
            let boundary = g.neighbours(v).any(|(u, _)| side[u] != side[v]);
            if boundary || weight[side[v] as usize] > max_w {
                heap.push((gain[v], Reverse(v)));
            }
        }
        let mut moves: Vec<usize> = Vec::new();
        let mut best = (start_imb, start_cut, 0usize);
        let limit = 50 + n / 50;
        let mut since_best = 0usize;
        while let Some((gv, Reverse(v))) = heap.pop() {
            if locked[v] || gv != gain[v] {
                continue;
            }
            let from = side[v] as usize;
            let to = 1 - from;
            let w = g.vwgt[v] as u64;
            let fixes_balance = weight[from] > max_w;
            if weight[to] + w > max_w && !fixes_balance {
                continue;
            }
            locked[v] = true;
            side[v] = to as u8;
            weight[from] -= w;
            weight[to] += w;
            cur -= gv;
            gain[v] = -gv;
            for (u, ew) in g.neighbours(v) {
                let d = 2 * ew as i64;
                gain[u] += if side[u] as usize == to { -d } else { d };
                if !locked[u] {
                    heap.push((gain[u], Reverse(u)));
                }
            }
            moves.push(v);
            let state = (imbalance(&weight, max_w), cur, moves.len());
            if (state.0, state.1) < (best.0, best.1) {
                best = state;
                since_best = 0;
            } else {
                since_best += 1;
                if since_best > limit {
                    break;
                }
            }
        }
        // Roll back the moves after the best state.
        for &v in moves[best.2..].iter().rev() {
            let from = side[v] as usize;
            let to = 1 - from;
            side[v] = to as u8;
            weight[from] -= g.vwgt[v] as u64;
            weight[to] += g.vwgt[v] as u64;
            for (u, ew) in g.neighbours(v) {
                let d = 2 * ew as i64;
                gain[u] += if side[u] as usize == to { -d } else { d };
            }
            gain[v] = -gain[v];
        }
        cur = best.1;
        if best.2 == 0 || (best.1 >= start_cut && best.0 >= start_imb) {
            break;
        }
    }
}

/// Weight above the allowed side weight (0 when balanced).
fn imbalance(weight: &[u64; 2], max_w: u64) -> u64 {
    weight[0].saturating_sub(max_w) + weight[1].saturating_sub(max_w)
}

/// Minimum vertex cover of the cut edges (Koenig: from a maximum matching
/// of the bipartite graph side 0 - side 1), as the vertex separator.
fn separator(g: &Graph, side: &[u8]) -> Vec<usize> {
    let n = g.n();
    let left: Vec<usize> = (0..n)
        .filter(|&v| side[v] == 0 && g.neighbours(v).any(|(u, _)| side[u] == 1))
        .collect();
    let cross = |v: usize| {
        g.neighbours(v)
            .filter(move |&(u, _)| side[u] != side[v])
            .map(|(u, _)| u)
    };
    let mut mate = vec![usize::MAX; n];
    // Kuhn's augmenting paths, iterative depth-first search.
    let mut visited = vec![usize::MAX; n];
    for (round, &root) in left.iter().enumerate() {
        // Quick greedy match first.
        if let Some(u) = cross(root).find(|&u| mate[u] == usize::MAX) {
            mate[root] = u;
            mate[u] = root;
            continue;
        }
        let mut stack: Vec<(usize, Vec<usize>)> = vec![(root, cross(root).collect())];
        visited[root] = round;
        let mut found = None;
        while let Some((v, cands)) = stack.last_mut() {
            let v = *v;
            let Some(u) = cands.pop() else {
                stack.pop();
                continue;
            };
            if visited[u] == round {
                continue;
            }
            visited[u] = round;
            let w = mate[u];
            if w == usize::MAX {
                found = Some(u);
                let _ = v;
                break;
            }
            if visited[w] != round {
                visited[w] = round;
                stack.push((w, cross(w).collect()));
            }
        }
        if let Some(mut u) = found {
            // Flip the path: the stack holds the left vertices along it.
            while let Some((v, _)) = stack.pop() {
                let prev = mate[v];
                mate[v] = u;
                mate[u] = v;
                if prev == usize::MAX {
                    break;
                }
                u = prev;
            }
        }
    }
    // Z: reachable from unmatched left vertices by alternating paths.
    let mut in_z = vec![false; n];
    let mut queue: Vec<usize> = left
        .iter()
        .copied()
        .filter(|&v| mate[v] == usize::MAX)
        .collect();
    for &v in &queue {
        in_z[v] = true;
    }
    while let Some(v) = queue.pop() {
        for u in cross(v) {
            if !in_z[u] {
                in_z[u] = true;
                let w = mate[u];
                if w != usize::MAX && !in_z[w] {
                    in_z[w] = true;
                    queue.push(w);
                }
            }
        }
    }
    let mut cover: Vec<usize> = left.iter().copied().filter(|&v| !in_z[v]).collect();
    cover.extend((0..n).filter(|&u| side[u] == 1 && in_z[u]));
    cover.sort_unstable();
    cover
}

/// Postorders `perm` (new -> old) along the elimination tree of the
/// permuted pattern: the same fill, with every subtree numbered contiguously.
fn postorder(a: SymbolicSparseColMatRef<'_, usize>, perm: &[usize]) -> Vec<usize> {
    let n = perm.len();
    let mut inv = vec![0usize; n];
    for (new, &old) in perm.iter().enumerate() {
        inv[old] = new;
    }
    // Liu's algorithm on the symmetrized pattern: for column k (new), all
    // rows i < k of its pattern; rows are found from both triangles.
    let mut lower: Vec<Vec<usize>> = vec![Vec::new(); n];
    for j in 0..a.ncols() {
        for i in a.row_idx_of_col(j) {
            let (ni, nj) = (inv[i], inv[j]);
            if ni < nj {
                lower[nj].push(ni);
            } else if nj < ni {
                lower[ni].push(nj);
            }
        }
    }
    let mut parent = vec![usize::MAX; n];
    let mut ancestor = vec![usize::MAX; n];
    for (k, rows) in lower.iter().enumerate() {
        for &i0 in rows {
            let mut i = i0;
            while ancestor[i] != usize::MAX && ancestor[i] != k {
                let next = ancestor[i];
                ancestor[i] = k;
                i = next;
            }
            if ancestor[i] == usize::MAX {
                ancestor[i] = k;
                parent[i] = k;
            }
        }
    }
    drop(lower);
    let mut head = vec![usize::MAX; n];
    let mut next = vec![usize::MAX; n];
    for j in (0..n).rev() {
        if parent[j] != usize::MAX {
            next[j] = head[parent[j]];
            head[parent[j]] = j;
        }
    }
    let mut out = Vec::with_capacity(n);
    let mut stack = Vec::new();
    for root in (0..n).filter(|&j| parent[j] == usize::MAX) {
        stack.push(root);
        while let Some(&v) = stack.last() {
            let c = head[v];
            if c == usize::MAX {
                stack.pop();
                out.push(perm[v]);
            } else {
                head[v] = next[c];
                stack.push(c);
            }
        }
    }
    out
}
