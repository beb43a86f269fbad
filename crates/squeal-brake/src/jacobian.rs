//! The contact Jacobians of [`crate::model::contact_jacobians`] on pairs whose vectors cover
//! most of their dofs (an interface-reduced brake: every pair's `g_p`, `h_p` is dense over
//! the interface coordinates), as column blocks of rank-one updates on rayon's threads, each
//! entry's terms summed in the order of the pair-by-pair loop: the same bits as that loop, on
//! any thread count.
//!
//! The loop adds, pair after pair, `(∂F_n/∂δ · g_r) · g_c` and then `(∂F_t/∂δ · h_r) · g_c`
//! to entry `(r, c)` (and to `∂F/∂x'` the rate terms, then the slip-velocity terms with `h_c`),
//! each as a separate rounding (no fused multiply-add), starting from `+0`. Here every pair's
//! vectors are spread over the union `S` of the pairs' dofs with zeros elsewhere; a zero term
//! adds `±0`, which leaves every sum as it was (a sum started at `+0` is never `-0`, and
//! `x ± 0 = x` otherwise), so each entry of `S × S` is the same sequence of roundings, and
//! the entries outside stay `+0`. The terms of one column are independent of every other
//! column's, so splitting the columns among threads does not change a bit.
//!
//! The dense form does `2 P |S|²` such updates (`4 P |S|²` with the rate terms), contiguous
//! and vectorized, where the loop does `Σ_p (|g_p| + |h_p|) |g_p|` of them, each through a
//! bounds-checked index into the matrix; it is used when its count is at most
//! [`LOOP_COST`] times the loop's (a pair of the interface-reduced ventilated brake is dense
//! over the disc's and its own pad's coordinates, not the other pad's: at a bar of 2 the medium
//! brake stayed in the loop, 6 % of its run's samples, docs/benchmarks.md), and only when
//! every derivative is finite (a zero times an infinite derivative would be `NaN` where the
//! loop writes nothing).

use crate::contact::Response;
use crate::model::ContactPair;
use faer::Mat;
use rayon::prelude::*;

/// How many dense updates cost as much as one of the loop's scattered ones, about: the
/// dense form is taken up to this many times the loop's count.
const LOOP_COST: f64 = 8.0;

/// Columns per block handed to a thread.
const COLUMNS: usize = 16;
/// Rows per block of a column's updates (a block of `COLUMNS` columns of this height stays in
/// the first-level cache).
const ROWS: usize = 256;

/// The pairs' vectors spread over the union of their dofs.
struct Spread {
    /// The union of the pairs' dofs, ascending.
    dofs: Vec<usize>,
    /// `g_p` on `dofs`, pair by pair (`dofs.len()` entries each).
    g: Vec<f64>,
    /// `h_p` on `dofs`, pair by pair.
    h: Vec<f64>,
}

impl Spread {
    /// The spread vectors when the dense form pays and reproduces the loop (no dof twice in a
    /// vector); `None` otherwise.
    fn of(pairs: &[ContactPair], n: usize, velocity: bool) -> Option<Spread> {
        // The vector that last had each dof: a dof twice in one vector is a duplicate.
        let mut stamp = vec![usize::MAX; n];
        let mut dofs: Vec<usize> = Vec::new();
        let mut looped = 0.0f64;
        for (p, pair) in pairs.iter().enumerate() {
            for (k, v) in [&pair.normal, &pair.tangent].into_iter().enumerate() {
                let id = 2 * p + k;
                for &(d, _) in v {
                    if d >= n || stamp[d] == id {
                        return None;
                    }
                    if stamp[d] == usize::MAX {
                        dofs.push(d);
                    }
                    stamp[d] = id;
                }
            }
            let (g, h) = (pair.normal.len() as f64, pair.tangent.len() as f64);
            looped += (g + h) * if velocity { g + h } else { g };
        }
        let m = dofs.len() as f64;
        let terms = if velocity { 4.0 } else { 2.0 };
        if pairs.is_empty() || terms * pairs.len() as f64 * m * m > LOOP_COST * looped {
            return None;
        }
        dofs.sort_unstable();
        let m = dofs.len();
        let mut local = vec![usize::MAX; n];
        for (i, &d) in dofs.iter().enumerate() {
            local[d] = i;
        }
        let mut g = vec![0.0; m * pairs.len()];
        let mut h = vec![0.0; m * pairs.len()];
        for (p, pair) in pairs.iter().enumerate() {
            for &(d, a) in &pair.normal {
                g[p * m + local[d]] = a;
            }
            for &(d, a) in &pair.tangent {
                h[p * m + local[d]] = a;
            }
        }
        Some(Spread { dofs, g, h })
    }
}

/// One pair's contribution to a block: `(row vector, column vector)` products in order.
struct Pair<'a> {
    /// `∂F/∂· · g` or `∂F/∂· · h` (rows), scaled, with the vector of the columns.
    terms: Vec<(Vec<f64>, &'a [f64])>,
}

/// `∂F_nl/∂x` and `∂F_nl/∂x'` as [`crate::model::contact_jacobians`] forms them from the
/// pairs' `responses`, when the dense form applies (module documentation); `None` otherwise.
pub(crate) fn dense_jacobians(
    pairs: &[ContactPair],
    responses: &[Response],
    n: usize,
) -> Option<(Mat<f64>, Option<Mat<f64>>)> {
    let finite = responses.iter().all(|r| {
        r.normal_derivatives
            .iter()
            .chain(&r.tangential_derivatives)
            .all(|d| d.is_finite())
    });
    let velocity = responses.iter().any(Response::has_velocity_terms);
    if !finite {
        return None;
    }
    let s = Spread::of(pairs, n, velocity)?;
    let m = s.dofs.len();
    let scaled = |a: f64, v: &[f64]| -> Vec<f64> { v.iter().map(|x| a * x).collect() };
    // The loop's terms for one matrix, pair by pair; pairs whose terms are all zero add
    // nothing (module documentation).
    let build = |rate: bool| -> Vec<Pair<'_>> {
        responses
            .iter()
            .enumerate()
            .filter_map(|(p, r)| {
                let (g, h) = (&s.g[p * m..(p + 1) * m], &s.h[p * m..(p + 1) * m]);
                let [n_d, n_r, n_v] = r.normal_derivatives;
                let [t_d, t_r, t_v] = r.tangential_derivatives;
                let mut terms = Vec::new();
                if rate {
                    for (a, row, col) in [(n_r, g, g), (t_r, h, g), (n_v, g, h), (t_v, h, h)] {
                        if a != 0.0 {
                            terms.push((scaled(a, row), col));
                        }
                    }
                } else {
                    for (a, row) in [(n_d, g), (t_d, h)] {
                        if a != 0.0 {
                            terms.push((scaled(a, row), g));
                        }
                    }
                }
                (!terms.is_empty()).then_some(Pair { terms })
            })
            .collect()
    };
    let kx = assemble(&build(false), &s.dofs, n);
    let kv = velocity.then(|| assemble(&build(true), &s.dofs, n));
    Some((kx, kv))
}

/// `Σ_p Σ_terms row ⊗ col` on `dofs × dofs`, each entry summed in the pairs' and terms' order,
/// spread into an `n × n` matrix.
fn assemble(pairs: &[Pair<'_>], dofs: &[usize], n: usize) -> Mat<f64> {
    let m = dofs.len();
    let mut local = vec![0.0; m * m];
    local
        .par_chunks_mut(m * COLUMNS)
        .enumerate()
        .for_each(|(block, out)| {
            let first = block * COLUMNS;
            let width = out.len() / m;
            for r0 in (0..m).step_by(ROWS) {
                let r1 = (r0 + ROWS).min(m);
                for pair in pairs {
                    for (row, col) in &pair.terms {
                        let row = &row[r0..r1];
                        for (j, &c) in col[first..first + width].iter().enumerate() {
                            let o = &mut out[j * m + r0..j * m + r1];
                            for (o, a) in o.iter_mut().zip(row) {
                                *o += a * c;
                            }
                        }
                    }
                }
            }
        });
    let mut k = Mat::<f64>::zeros(n, n);
    for (j, &dj) in dofs.iter().enumerate() {
        let col = k.col_as_slice_mut(dj);
        for (i, &di) in dofs.iter().enumerate() {
            col[di] = local[j * m + i];
        }
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::looped_jacobians;
    use crate::model::tests::one_pair;

    /// A reproducible value in `[-1, 1)` (a linear congruential sequence).
    fn next(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// `count` pairs dense over dofs of `1..n` (dof 0 in no pair), with responses: some pairs
    /// open (zero derivatives), the rate and slip terms on some when `velocity`.
    fn dense_pairs(n: usize, count: usize, velocity: bool) -> (Vec<ContactPair>, Vec<Response>) {
        let mut s = 7u64;
        let mut pairs = Vec::new();
        let mut responses = Vec::new();
        for p in 0..count {
            let mut pair = one_pair(0.0);
            // Both vectors over a "disc" (dofs 1..n/3) and one of two "pads" (the pairs in
            // turn), as on an interface-reduced two-pad brake, in a shuffled order (the loop's
            // order of terms within a pair does not matter for an entry: each dof once).
            let own = |d: &usize| *d < n / 3 || (*d < 2 * n / 3) == (p % 2 == 0);
            pair.normal = (1..n)
                .rev()
                .filter(own)
                .map(|d| (d, next(&mut s)))
                .collect();
            pair.tangent = (1..n).filter(own).map(|d| (d, next(&mut s))).collect();
            pairs.push(pair);
            let open = p % 5 == 3;
            let k = |s: &mut u64| if open { 0.0 } else { 1e7 * next(s) };
            let v = |s: &mut u64| if velocity && p % 3 == 1 { next(s) } else { 0.0 };
            responses.push(Response {
                normal_derivatives: [k(&mut s), v(&mut s), v(&mut s)],
                tangential_derivatives: [k(&mut s), v(&mut s), v(&mut s)],
                ..Response::default()
            });
        }
        (pairs, responses)
    }

    fn bits(m: &Mat<f64>) -> Vec<u64> {
        (0..m.ncols())
            .flat_map(|j| (0..m.nrows()).map(move |i| (i, j)))
            .map(|(i, j)| m[(i, j)].to_bits())
            .collect()
    }

    /// The dense form gives the loop's every bit (exact: the same roundings in the same order,
    /// module documentation), on 1, 2 and 3 threads, with and without the rate terms, on a
    /// size that leaves partial column and row blocks (300 dofs: 18 blocks of 16 and 12, one
    /// of 256 rows and 44).
    #[test]
    fn dense_form_has_the_loops_bits_on_any_thread_count() {
        for velocity in [false, true] {
            let (pairs, responses) = dense_pairs(300, 23, velocity);
            let (kx, kv) = looped_jacobians(&pairs, responses.clone(), 300);
            assert_eq!(kv.is_some(), velocity);
            for threads in [1, 2, 3] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let (dx, dv) = pool
                    .install(|| dense_jacobians(&pairs, &responses, 300))
                    .expect("dense pairs take the dense form");
                assert!(bits(&dx) == bits(&kx), "dK/dx, {threads} threads");
                match (&dv, &kv) {
                    (Some(a), Some(b)) => assert!(bits(a) == bits(b), "dK/dv, {threads}"),
                    (None, None) => {}
                    _ => panic!("dK/dv present in one form only"),
                }
            }
            // Row and column 0 (no pair's dof) stay +0, as in the loop.
            assert_eq!(kx[(0, 5)].to_bits(), 0.0f64.to_bits());
        }
    }

    /// Pairs with a few dofs each among many (a brake without interface reduction) keep the
    /// loop: spread over the union of their dofs they would cost far more (exact decision,
    /// no tolerance).
    #[test]
    fn sparse_pairs_keep_the_loop() {
        let pairs: Vec<ContactPair> = (0..50)
            .map(|p| one_pair(0.0).renumbered(|d| 4 * p + d))
            .collect();
        let responses = vec![
            Response {
                normal_derivatives: [1e6, 0.0, 0.0],
                ..Response::default()
            };
            50
        ];
        assert!(dense_jacobians(&pairs, &responses, 200).is_none());
    }
}
