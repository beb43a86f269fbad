//! The brake of eq (11) in interface-reduced coordinates: each part's coordinates changed by
//! its own `T_I` (`q_I = T_I q'_I`, e.g. the characteristic constraint modes of its contact
//! face, `squeal_reduce::interface_modes`), the whole brake by the block-diagonal
//! `T = diag(T_disc, T_pad, …)`:
//!
//! `M' = Tᵀ M T`, `K' = Tᵀ K T`, `F'_piston = Tᵀ F_piston`, and every pair's `g'_p = Tᵀ g_p`,
//! `h'_p = Tᵀ h_p`.
//!
//! **Further parts.** The dofs after the last pad's (`[parts.<name>]`: a caliper, a bracket,
//! with their ties' slave dofs already eliminated, `crate::connections::eliminate_ties`) have no
//! contact face to reduce: their block of `T` is the identity, `T = diag(T_disc, T_pad, …, I)`.
//! The connectors' springs and the ties' couplings are entries of the assembled `K` (and
//! `K_vib`, `C`) between those dofs and the pads' non-face dofs (coupling points, tie nodes),
//! which every `T_I` keeps as identity columns too, so `Tᵀ K T` carries them exactly; what a
//! tie's slave follows on a pad's contact face is restricted with that face, as the face itself
//! is. `T` is still a Rayleigh–Ritz basis of the whole brake: no frictionless frequency falls
//! below the unreduced brake's.
//!
//! The pairs keep their elements, gaps, normals and surface speeds: the closure
//! `δ_p = g'_pᵀ x' − g0_p` and the slip `V_p + h'_pᵀ x'̇` are the same numbers as
//! `g_pᵀ (T x') − g0_p` and `V_p + h_pᵀ (T x'̇)`, so the contact force of eq (10) is still
//! evaluated at every pair and projected, `Tᵀ F_nl(T x', T x'̇)`. With `T` square and
//! invertible the brake is the same brake in other coordinates (its spectrum to round-off:
//! tested below).

use crate::assemble::Layout;
use crate::error::BrakeError;
use crate::model::{Brake, SparseVec};
use faer::Mat;

/// The brake and its layout in the coordinates `x = T x'`, `T = diag(blocks, I)` with one block
/// per part in the layout's order (disc, then the pads), block `I` having as many rows as part
/// `I` has dofs, and the identity on the further parts' dofs after the last pad's (module
/// docs).
pub fn project_brake(
    brake: &Brake,
    layout: &Layout,
    blocks: &[Mat<f64>],
) -> Result<(Brake, Layout), BrakeError> {
    let ranges: Vec<std::ops::Range<usize>> = std::iter::once(layout.disc.clone())
        .chain(layout.pads.iter().map(|p| p.1.clone()))
        .collect();
    if blocks.len() != ranges.len() {
        return Err(BrakeError::Dimension {
            what: "interface-reduction blocks (one per part)",
            expected: ranges.len(),
            got: blocks.len(),
        });
    }
    let n = brake.size();
    let ends = ranges.last().map_or(0, |r| r.end);
    if ends > n {
        return Err(BrakeError::Dimension {
            what: "dofs of the brake's layout",
            expected: n,
            got: ends,
        });
    }
    let mut new_ranges = Vec::with_capacity(ranges.len());
    let mut start = 0;
    for (r, b) in ranges.iter().zip(blocks) {
        if b.nrows() != r.len() {
            return Err(BrakeError::Dimension {
                what: "rows of a part's interface-reduction block",
                expected: r.len(),
                got: b.nrows(),
            });
        }
        new_ranges.push(start..start + b.ncols());
        start += b.ncols();
    }
    // The further parts' dofs, kept as they are: `ends..n` becomes `start..r`.
    let rest = n - ends;
    let r = start + rest;
    let mut t = Mat::zeros(n, r);
    for ((old, new), b) in ranges.iter().zip(&new_ranges).zip(blocks) {
        for j in 0..b.ncols() {
            for i in 0..b.nrows() {
                t[(old.start + i, new.start + j)] = b[(i, j)];
            }
        }
    }
    for k in 0..rest {
        t[(ends + k, start + k)] = 1.0;
    }
    let project = |a: &Mat<f64>| t.transpose() * (a * &t);
    // The part of each old dof: its block, its row there and the block's new columns.
    let part_of = |d: usize| ranges.iter().position(|r| r.contains(&d));
    let vector = |v: &SparseVec| -> SparseVec {
        let mut dense = vec![0.0; r];
        for &(d, a) in v {
            let Some(p) = part_of(d) else {
                // A further part's dof: the identity block.
                dense[start + d - ends] += a;
                continue;
            };
            let (b, row) = (&blocks[p], d - ranges[p].start);
            for j in 0..b.ncols() {
                dense[new_ranges[p].start + j] += a * b[(row, j)];
            }
        }
        dense
            .into_iter()
            .enumerate()
            .filter(|(_, x)| *x != 0.0)
            .collect()
    };
    let f_piston = (0..r)
        .map(|j| (0..n).map(|i| t[(i, j)] * brake.f_piston[i]).sum())
        .collect();
    let pairs = brake
        .pairs
        .iter()
        .map(|p| {
            let mut q = p.clone();
            q.normal = vector(&p.normal);
            q.tangent = vector(&p.tangent);
            q
        })
        .collect();
    let symmetric = |a: Mat<f64>| Mat::from_fn(r, r, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    let projected = Brake {
        m: symmetric(project(&brake.m)),
        k: symmetric(project(&brake.k)),
        f_piston,
        c: brake.c.as_ref().map(|c| symmetric(project(c))),
        k_vibration: brake.k_vibration.as_ref().map(|k| symmetric(project(k))),
        pairs,
    };
    let layout = Layout {
        disc: new_ranges[0].clone(),
        pads: layout
            .pads
            .iter()
            .zip(&new_ranges[1..])
            .map(|((name, _), range)| (name.clone(), range.clone()))
            .collect(),
    };
    Ok((projected, layout))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ContactPair;

    /// A disc with dofs 0..3 and a pad with dofs 3..5, one pair: normal on disc dof 1 and
    /// pad dof 3, sliding on disc dof 0 and pad dof 4.
    fn brake() -> (Brake, Layout) {
        let pair = ContactPair {
            disc_point: 0,
            pad_point: 0,
            position: [0.0; 3],
            normal_direction: [0.0, 0.0, 1.0],
            sliding_direction: [1.0, 0.0, 0.0],
            normal: vec![(1, 1.0), (3, -1.0)],
            tangent: vec![(0, 1.0), (4, -1.0)],
            initial_gap: 1e-6,
            surface_speed: None,
            law: std::sync::Arc::new(crate::contact::PenaltyCoulomb {
                k_linear: 2e6,
                k_cubic: 3e15,
            }),
        };
        let n = 5;
        let k = Mat::from_fn(n, n, |i, j| {
            let same = (i < 3) == (j < 3);
            if i == j {
                4.0 + i as f64
            } else if same && i.abs_diff(j) == 1 {
                -1.0
            } else {
                0.0
            }
        });
        let m = Mat::from_fn(n, n, |i, j| if i == j { 1.0 + 0.1 * i as f64 } else { 0.0 });
        let mut f = vec![0.0; n];
        f[4] = -2.0;
        let b = Brake {
            m,
            k,
            f_piston: f,
            c: None,
            k_vibration: None,
            pairs: vec![pair],
        };
        let layout = Layout {
            disc: 0..3,
            pads: vec![("pad".into(), 3..5)],
        };
        (b, layout)
    }

    fn rotation(n: usize, angle: f64) -> Mat<f64> {
        let (c, s) = (angle.cos(), angle.sin());
        Mat::from_fn(n, n, |i, j| match (i, j) {
            (0, 0) | (1, 1) => c,
            (0, 1) => -s,
            (1, 0) => s,
            _ if i == j => 1.0,
            _ => 0.0,
        })
    }

    #[test]
    fn an_invertible_change_of_coordinates_keeps_closures_and_energies() {
        let (b, layout) = brake();
        let blocks = [rotation(3, 0.3), rotation(2, -0.7)];
        let (p, l) = project_brake(&b, &layout, &blocks).unwrap();
        assert_eq!((l.disc.clone(), l.pad()), (0..3, 3..5));
        // x = T x' for some x': the closures and the energies agree to round-off
        // (a few ulps of the O(1) entries).
        let xp = [0.3, -0.2, 0.5, 0.1, -0.4];
        let mut x = [0.0; 5];
        for (i, xi) in x.iter_mut().enumerate() {
            let (blk, off, nb) = if i < 3 { (0, 0, 3) } else { (1, 3, 2) };
            *xi = (0..nb)
                .map(|j| blocks[blk][(i - off, j)] * xp[off + j])
                .sum();
        }
        let pair: &ContactPair = &p.pairs[0];
        assert!((pair.penetration(&xp) - b.pairs[0].penetration(&x)).abs() < 1e-15);
        let energy = |a: &Mat<f64>, v: &[f64]| -> f64 {
            (0..v.len())
                .map(|i| (0..v.len()).map(|j| v[i] * a[(i, j)] * v[j]).sum::<f64>())
                .sum()
        };
        assert!((energy(&p.k, &xp) - energy(&b.k, &x)).abs() < 1e-13);
        assert!((energy(&p.m, &xp) - energy(&b.m, &x)).abs() < 1e-13);
        // The load's work: F'·x' = F·x.
        let w = |f: &[f64], v: &[f64]| f.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
        assert!((w(&p.f_piston, &xp) - w(&b.f_piston, &x)).abs() < 1e-15);
    }

    #[test]
    fn a_truncated_block_shrinks_its_part_only() {
        let (b, layout) = brake();
        let keep_two = Mat::from_fn(3, 2, |i, j| if i == j { 1.0 } else { 0.0 });
        let (p, l) = project_brake(&b, &layout, &[keep_two, Mat::identity(2, 2)]).unwrap();
        assert_eq!((p.size(), l.disc.clone(), l.pad()), (4, 0..2, 2..4));
        // The pair's disc dof 1 is kept (column 1), its pad dof 3 became 2.
        assert_eq!(p.pairs[0].normal, vec![(1, 1.0), (2, -1.0)]);
        assert!(project_brake(&b, &layout, &[Mat::identity(3, 3)]).is_err());
    }

    /// The brake of [`brake`] with a further part of two dofs (5, 6) after the pad's: a
    /// connector spring `k_c` between pad dof 4 and dof 5, a spring to ground on dof 6 and one
    /// between 5 and 6, and a load on dof 6.
    fn with_further_part() -> (Brake, Layout) {
        let (b, layout) = brake();
        let n = 7;
        let kc = 3.0;
        let mut k = Mat::from_fn(n, n, |i, j| if i < 5 && j < 5 { b.k[(i, j)] } else { 0.0 });
        for (i, j, v) in [(4, 4, kc), (5, 5, kc), (4, 5, -kc), (5, 4, -kc)] {
            k[(i, j)] += v;
        }
        for (i, j, v) in [
            (5, 5, 2.0),
            (6, 6, 2.0),
            (5, 6, -2.0),
            (6, 5, -2.0),
            (6, 6, 5.0),
        ] {
            k[(i, j)] += v;
        }
        let m = Mat::from_fn(n, n, |i, j| match (i, j) {
            _ if i < 5 && j < 5 => b.m[(i, j)],
            _ if i == j => 0.7 + 0.1 * i as f64,
            _ => 0.0,
        });
        let mut f = b.f_piston.clone();
        f.extend([0.0, 1.5]);
        let brake = Brake {
            m,
            k,
            f_piston: f,
            c: None,
            k_vibration: None,
            pairs: b.pairs,
        };
        (brake, layout)
    }

    #[test]
    fn further_parts_keep_their_dofs_and_their_springs() {
        let (b, layout) = with_further_part();
        // Square, invertible blocks: the same brake in other coordinates, the further part's
        // two dofs last and untouched.
        let blocks = [rotation(3, 0.3), rotation(2, -0.7)];
        let (p, l) = project_brake(&b, &layout, &blocks).unwrap();
        assert_eq!((p.size(), l.all_pads()), (7, 3..5));
        let xp = [0.3, -0.2, 0.5, 0.1, -0.4, 0.25, -0.6];
        let mut x = xp;
        for (i, xi) in x.iter_mut().enumerate().take(5) {
            let (blk, off, nb) = if i < 3 { (0, 0, 3) } else { (1, 3, 2) };
            *xi = (0..nb)
                .map(|j| blocks[blk][(i - off, j)] * xp[off + j])
                .sum();
        }
        let energy = |a: &Mat<f64>, v: &[f64]| -> f64 {
            (0..v.len())
                .map(|i| (0..v.len()).map(|j| v[i] * a[(i, j)] * v[j]).sum::<f64>())
                .sum()
        };
        // Energies of O(1) terms: a few ulps.
        assert!((energy(&p.k, &xp) - energy(&b.k, &x)).abs() < 1e-13);
        assert!((energy(&p.m, &xp) - energy(&b.m, &x)).abs() < 1e-13);
        // The further part's block is the original, bit for bit (identity columns), and its
        // load stays where it was.
        for i in 5..7 {
            for j in 5..7 {
                assert_eq!(p.k[(i, j)], b.k[(i, j)]);
                assert_eq!(p.m[(i, j)], b.m[(i, j)]);
            }
        }
        assert_eq!(p.f_piston[6], 1.5);
        // The connector between pad dof 4 and dof 5: on the pad's rotated coordinates.
        assert!((p.k[(3, 5)] - (-3.0 * blocks[1][(1, 0)])).abs() < 1e-15);
        assert!((p.k[(4, 5)] - (-3.0 * blocks[1][(1, 1)])).abs() < 1e-15);
        // A truncated disc: the further part's dofs move up by one, whole.
        let keep_two = Mat::from_fn(3, 2, |i, j| if i == j { 1.0 } else { 0.0 });
        let (q, lq) = project_brake(&b, &layout, &[keep_two, Mat::identity(2, 2)]).unwrap();
        assert_eq!((q.size(), lq.all_pads()), (6, 2..4));
        assert_eq!(q.k[(3, 4)], -3.0);
        assert_eq!((q.k[(4, 5)], q.f_piston[5]), (-2.0, 1.5));
        // A layout longer than the brake is refused.
        let short = Brake {
            m: Mat::identity(4, 4),
            k: Mat::identity(4, 4),
            f_piston: vec![0.0; 4],
            c: None,
            k_vibration: None,
            pairs: Vec::new(),
        };
        assert!(project_brake(&short, &layout, &blocks).is_err());
    }
}
