//! Following modes across a parameter sweep so that branches never swap.
//!
//! Consecutive spectra are matched by minimising a cost that combines the eigenvector
//! correlation (the modal assurance criterion `MAC = |q_aᴴ q_b|²` of unit modal vectors, in
//! mass-orthonormal coordinates) with the distance between eigenvalues, relative to the
//! eigenvalue's magnitude. The correlation separates modes that cross in frequency; the
//! distance separates the two modes of a coalescing pair, whose shapes become alike at the
//! coalescence. Mutually best matches are taken first; the rest is solved as an assignment
//! problem (Hungarian algorithm).

use crate::spectrum::Spectrum;
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par, c64};

/// `|aᴴ b|²` for unit vectors stored as columns `ja` of `a` and `jb` of `b`.
pub fn mac(a: &Spectrum, ja: usize, b: &Spectrum, jb: usize) -> f64 {
    let n = a.modes.nrows();
    let mut s = c64::new(0.0, 0.0);
    for i in 0..n {
        s += a.modes[(i, ja)].conj() * b.modes[(i, jb)];
    }
    s.norm_sqr()
}

/// Matching cost of mode `i` of `prev` and mode `j` of `next`, in `[0, 2]`.
fn cost(prev: &Spectrum, i: usize, next: &Spectrum, j: usize) -> f64 {
    cost_of(prev.values[i], next.values[j], mac(prev, i, next, j))
}

/// The matching cost of eigenvalues `li`, `lj` whose modes correlate by `mac`.
pub(crate) fn cost_of(li: c64, lj: c64, mac: f64) -> f64 {
    let d = (lj - li).norm() / (0.05 * li.norm()).max(f64::MIN_POSITIVE);
    (1.0 - mac) + d.min(1.0)
}

/// For each mode of `prev`, the index of the matching mode of `next` (a permutation).
pub fn match_modes(prev: &Spectrum, next: &Spectrum) -> Vec<usize> {
    let n = prev.values.len();
    let costs: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| cost(prev, i, next, j)).collect())
        .collect();
    assign(costs)
}

/// [`match_modes`] with every correlation from one product `Q_prevᴴ Q_next` (a blocked
/// matrix product, sequential: the bits do not depend on the thread count). The correlations
/// differ from [`mac`]'s sums by round-off only; for the spectra of a large brake (a projected
/// sweep's hundreds of modes) this is the difference between `n³` scalar steps and a
/// vectorized product.
pub fn match_modes_blocked(prev: &Spectrum, next: &Spectrum) -> Vec<usize> {
    let n = prev.values.len();
    let mut g = Mat::<c64>::zeros(n, n);
    matmul(
        g.as_mut(),
        Accum::Replace,
        prev.modes.adjoint(),
        next.modes.as_ref(),
        c64::new(1.0, 0.0),
        Par::Seq,
    );
    let costs: Vec<Vec<f64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| cost_of(prev.values[i], next.values[j], g[(i, j)].norm_sqr()))
                .collect()
        })
        .collect();
    assign(costs)
}

/// The permutation of least total cost: mutually best matches first, the rest by the
/// Hungarian algorithm.
fn assign(costs: Vec<Vec<f64>>) -> Vec<usize> {
    let n = costs.len();
    let best_j: Vec<usize> = costs.iter().map(|row| argmin(row)).collect();
    let best_i: Vec<usize> = (0..n)
        .map(|j| argmin(&(0..n).map(|i| costs[i][j]).collect::<Vec<_>>()))
        .collect();
    let mut assign = vec![usize::MAX; n];
    let mut taken = vec![false; n];
    for i in 0..n {
        let j = best_j[i];
        if best_i[j] == i && costs[i][j] < 0.25 {
            assign[i] = j;
            taken[j] = true;
        }
    }
    let rows: Vec<usize> = (0..n).filter(|&i| assign[i] == usize::MAX).collect();
    let cols: Vec<usize> = (0..n).filter(|&j| !taken[j]).collect();
    if !rows.is_empty() {
        let sub: Vec<Vec<f64>> = rows
            .iter()
            .map(|&i| cols.iter().map(|&j| costs[i][j]).collect())
            .collect();
        for (r, c) in hungarian(&sub).into_iter().enumerate() {
            assign[rows[r]] = cols[c];
        }
    }
    assign
}

fn argmin(v: &[f64]) -> usize {
    let mut best = 0;
    for (k, x) in v.iter().enumerate() {
        if *x < v[best] {
            best = k;
        }
    }
    best
}

/// Minimum-cost assignment of a square cost matrix (Kuhn–Munkres, O(n³), with potentials):
/// returns the column assigned to each row.
pub fn hungarian(cost: &[Vec<f64>]) -> Vec<usize> {
    let n = cost.len();
    let inf = f64::INFINITY;
    // 1-based arrays as in the classic formulation; column 0 is a sentinel.
    let mut u = vec![0.0; n + 1];
    let mut v = vec![0.0; n + 1];
    let mut p = vec![0usize; n + 1];
    let mut way = vec![0usize; n + 1];
    for i in 1..=n {
        p[0] = i;
        let mut j0 = 0;
        let mut minv = vec![inf; n + 1];
        let mut used = vec![false; n + 1];
        loop {
            used[j0] = true;
            let i0 = p[j0];
            let mut delta = inf;
            let mut j1 = 0;
            for j in 1..=n {
                if !used[j] {
                    let cur = cost[i0 - 1][j - 1] - u[i0] - v[j];
                    if cur < minv[j] {
                        minv[j] = cur;
                        way[j] = j0;
                    }
                    if minv[j] < delta {
                        delta = minv[j];
                        j1 = j;
                    }
                }
            }
            for j in 0..=n {
                if used[j] {
                    u[p[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
            if p[j0] == 0 {
                break;
            }
        }
        loop {
            let j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
            if j0 == 0 {
                break;
            }
        }
    }
    let mut ans = vec![0usize; n];
    for j in 1..=n {
        if p[j] > 0 {
            ans[p[j] - 1] = j - 1;
        }
    }
    ans
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hungarian_finds_the_optimum_of_a_small_problem() {
        // Brute force over all 4! permutations is the independent reference.
        let c = vec![
            vec![9.0, 2.0, 7.0, 8.0],
            vec![6.0, 4.0, 3.0, 7.0],
            vec![5.0, 8.0, 1.0, 8.0],
            vec![7.0, 6.0, 9.0, 4.0],
        ];
        let a = hungarian(&c);
        let total: f64 = a.iter().enumerate().map(|(i, &j)| c[i][j]).sum();
        let mut best = f64::INFINITY;
        let perms = [
            [0, 1, 2, 3],
            [0, 1, 3, 2],
            [0, 2, 1, 3],
            [0, 2, 3, 1],
            [0, 3, 1, 2],
            [0, 3, 2, 1],
            [1, 0, 2, 3],
            [1, 0, 3, 2],
            [1, 2, 0, 3],
            [1, 2, 3, 0],
            [1, 3, 0, 2],
            [1, 3, 2, 0],
            [2, 0, 1, 3],
            [2, 0, 3, 1],
            [2, 1, 0, 3],
            [2, 1, 3, 0],
            [2, 3, 0, 1],
            [2, 3, 1, 0],
            [3, 0, 1, 2],
            [3, 0, 2, 1],
            [3, 1, 0, 2],
            [3, 1, 2, 0],
            [3, 2, 0, 1],
            [3, 2, 1, 0],
        ];
        for p in perms {
            best = f64::min(best, p.iter().enumerate().map(|(i, &j)| c[i][j]).sum());
        }
        assert_eq!(total, best);
        assert_eq!(total, 13.0);
    }
}
