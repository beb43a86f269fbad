//! The interface models on the bundled meshes.

use squeal_reduce::interface::{Axis, contact_nodes, patches};
use std::path::PathBuf;

fn mesh(name: &str) -> squeal_mesh::Mesh {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../meshes")
        .join(name);
    squeal_mesh::read(&path).unwrap().mesh
}

#[test]
fn patches_follow_the_generator_patch_sets_and_pair_up() {
    let disc = mesh("disc_coarse.inp");
    let pad = mesh("pad_coarse.inp");
    let axis = Axis::default();
    let pd = patches(&disc, "CONTACT_FACE", 3, 3, &axis).unwrap();
    let pp = patches(&pad, "CONTACT_FACE", 3, 3, &axis).unwrap();
    for (part, m, p) in [("disc", &disc, &pd), ("pad", &pad, &pp)] {
        for q in p.iter() {
            // The generator's patch sets hold the nodes of each patch (its edges included):
            // our grid split must put every weighted node inside the same-numbered set.
            let set = m.node_set(&format!("CONTACT_PATCH_{}", q.number)).unwrap();
            for (n, _) in &q.weights {
                assert!(
                    set.binary_search(n).is_ok(),
                    "{part} patch {}: node {} outside",
                    q.number,
                    m.node_ids[*n as usize]
                );
            }
        }
        // Footprint area: 50 degrees of the annulus 85..135 mm; the curved P2 edges follow
        // the arcs, so the error is that of quadratic arc interpolation (< 1e-5 here).
        let area: f64 = p.iter().map(|q| q.area).sum();
        let exact = 0.5 * 50f64.to_radians() * (0.135f64.powi(2) - 0.085f64.powi(2));
        assert!(
            (area / exact - 1.0).abs() < 1e-5,
            "{part} area {area} vs {exact}"
        );
    }
    for (a, b) in pd.iter().zip(&pp) {
        let d: f64 = (0..3)
            .map(|k| (a.centroid[k] - b.centroid[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        // Same grid, same footprint, both meshes follow the arcs: centroids agree to the
        // discretisation of the arcs, far below the 17 mm patch size.
        assert!(d < 1e-5, "patch {}: centroids {d} m apart", a.number);
    }
}

#[test]
fn contact_nodes_come_in_patch_order() {
    for name in ["disc_coarse.inp", "pad_coarse.inp"] {
        let m = mesh(name);
        let nodes = contact_nodes(&m, "CONTACT", &Axis::default()).unwrap();
        for (k, n) in nodes.iter().enumerate() {
            let set = m.node_set(&format!("CONTACT_PATCH_{}", k + 1)).unwrap();
            assert!(
                set.binary_search(n).is_ok(),
                "{name}: contact node {k} not in patch {}",
                k + 1
            );
        }
    }
}

/// Gauss–Legendre rule of `n` points on [0, 1] (Newton on P_n; converged to round-off).
fn gauss_legendre_01(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let legendre = |x: f64| {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let k = k as f64;
                    (p0, p1) = (p1, ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k);
                }
                (p1, n as f64 * (x * p1 - p0) / (x * x - 1.0))
            };
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            for _ in 0..100 {
                let (p, dp) = legendre(x);
                x -= p / dp;
                if (p / dp).abs() < 1e-16 {
                    break;
                }
            }
            let (_, dp) = legendre(x);
            (0.5 * (1.0 + x), 1.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// The cells of an `n_r x n_t` grid on the annular sector r0..r1, t0..t1 (the bundled
/// footprint) for the face `set` of `mesh`: area and first moments `∫ (x, y) dA`, each the
/// closed form plus the slivers between the true circles `r = R` and the quadratic edges that
/// stand for them where the patches' edges are mesh edges (the face's arcs r0 and r1, and the
/// radial cuts the mesh imprinted), `± ∫ (ρ_b(θ)² − R²)/2 dθ` and
/// `± ∫ (ρ_b(θ)³ − R³)/3 (cos θ, sin θ) dθ` along each such edge (1-D Gauss–Legendre, split at
/// the grid's angles). Returns `(closed form, with the slivers)`, each `[area, mx, my]` per
/// patch in the patch numbering.
fn annular_cells(
    mesh: &squeal_mesh::Mesh,
    set: &str,
    grid: [usize; 2],
) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    use squeal_mesh::select::{boundary_faces, faces_of_set};
    let (r0, r1) = (0.085f64, 0.135f64);
    let (t0, t1) = (65f64.to_radians(), 115f64.to_radians());
    let [n_r, n_t] = grid;
    let ring = |i: usize| r0 + (r1 - r0) * i as f64 / n_r as f64;
    let sector = |j: usize| t0 + (t1 - t0) * j as f64 / n_t as f64;
    let mut exact = Vec::new();
    for i in 0..n_r {
        for j in 0..n_t {
            let (ra, rb, fa, fb) = (ring(i), ring(i + 1), sector(j), sector(j + 1));
            exact.push([
                0.5 * (fb - fa) * (rb * rb - ra * ra),
                (rb.powi(3) - ra.powi(3)) / 3.0 * (fb.sin() - fa.sin()),
                (rb.powi(3) - ra.powi(3)) / 3.0 * (fa.cos() - fb.cos()),
            ]);
        }
    }
    // Boundary edges of the face: (vertex, midside, vertex) used by one face triangle.
    let nodes = mesh.node_set(set).unwrap();
    let tris = faces_of_set(mesh, &boundary_faces(mesh), nodes);
    let mut edges = std::collections::HashMap::new();
    for t in &tris {
        for (a, m, b) in [(0, 3, 1), (1, 4, 2), (2, 5, 0)] {
            let key = (t[a].min(t[b]), t[a].max(t[b]));
            edges.entry(key).or_insert((t[a], t[m], t[b], 0)).3 += 1;
        }
    }
    let xy = |n: u32| {
        let p = mesh.nodes[n as usize];
        [p[0], p[1]]
    };
    let radius = |p: [f64; 2]| p[0].hypot(p[1]);
    let rule = gauss_legendre_01(20);
    let mut sliver = exact.clone();
    for &(a, m, b, _) in edges.values() {
        let (pa, pm, pb) = (xy(a), xy(m), xy(b));
        // An edge with both ends on r0, r1 or a radial cut: the patches' edge there is the
        // quadratic edge, the cell's the circle; the sliver between them moves from the ring
        // outside the circle (sign −1) to the one inside (+1). Other edges are inside a cell
        // or straight radial sides (exact).
        let Some(k) = (0..=n_r).find(|&k| {
            (radius(pa) - ring(k)).abs() < 1e-12 && (radius(pb) - ring(k)).abs() < 1e-12
        }) else {
            continue;
        };
        let arc = ring(k);
        let rings: Vec<(usize, f64)> = [(k.wrapping_sub(1), 1.0), (k, -1.0)]
            .into_iter()
            .filter(|&(i, _)| i < n_r)
            .collect();
        // The quadratic edge and its tangent at τ.
        let at = |tau: f64| {
            let l = [
                (1.0 - tau) * (1.0 - 2.0 * tau),
                4.0 * tau * (1.0 - tau),
                tau * (2.0 * tau - 1.0),
            ];
            let dl = [4.0 * tau - 3.0, 4.0 - 8.0 * tau, 4.0 * tau - 1.0];
            let p = [0, 1].map(|c| l[0] * pa[c] + l[1] * pm[c] + l[2] * pb[c]);
            let dp = [0, 1].map(|c| dl[0] * pa[c] + dl[1] * pm[c] + dl[2] * pb[c]);
            (p, dp)
        };
        let angle = |tau: f64| {
            let p = at(tau).0;
            p[1].atan2(p[0])
        };
        // Split at the grid's angles (θ is monotone along an arc edge).
        let mut cuts = vec![0.0, 1.0];
        for j in 1..n_t {
            let phi = sector(j);
            let (mut lo, mut hi) = (0.0, 1.0);
            if (angle(lo) - phi) * (angle(hi) - phi) >= 0.0 {
                continue;
            }
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if (angle(lo) - phi) * (angle(mid) - phi) <= 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            cuts.push(0.5 * (lo + hi));
        }
        cuts.sort_by(f64::total_cmp);
        let orientation = (angle(1.0) - angle(0.0)).signum();
        for w in cuts.windows(2) {
            let (ta, tb) = (w[0], w[1]);
            let j =
                ((0.5 * (angle(ta) + angle(tb)) - t0) / (t1 - t0) * n_t as f64).floor() as usize;
            for &(x, wx) in &rule {
                let tau = ta + (tb - ta) * x;
                let (p, dp) = at(tau);
                let rho = radius(p);
                let theta = p[1].atan2(p[0]);
                // dθ = (x y' − y x') / ρ² dτ
                let dtheta = (p[0] * dp[1] - p[1] * dp[0]) / (rho * rho) * (tb - ta) * wx;
                for &(i, sign) in &rings {
                    let w = sign * orientation * dtheta;
                    let cell = &mut sliver[i * n_t + j.min(n_t - 1)];
                    cell[0] += w * (rho * rho - arc * arc) / 2.0;
                    cell[1] += w * (rho.powi(3) - arc.powi(3)) / 3.0 * theta.cos();
                    cell[2] += w * (rho.powi(3) - arc.powi(3)) / 3.0 * theta.sin();
                }
            }
        }
    }
    (exact, sliver)
}

#[test]
fn clipped_patches_are_the_annular_sector_cells() {
    // The bundled contact faces are the flat annular sector r = 85..135 mm, 65..115 degrees
    // (z = 20 mm). On any grid, each clipped patch must be that cell of the discrete face: the
    // closed-form annular-sector cell plus the slivers between the true circles and the
    // quadratic edges that stand for them (the face's arcs, and the imprinted 3 x 3 arcs when
    // they are cuts), which the test integrates along those edges. The cuts inside the face
    // are exact and the pieces of crossed triangles are integrated to round-off, so the two
    // agree to round-off: measured at most 9e-15 relative in area and 1e-15 m in centroid,
    // except on the coarse disc's 4 x 4 grid (5.5e-12 and 8e-14 m): its nodes on the 90°
    // line lie up to 5e-13 m off it, within the 1e-9 r1 (1.4e-10 m) by which a mesh edge on a
    // cut counts as the cut, and its triangles there are kept whole. Asserted 1e-10 and
    // 1e-12 m. Against the closed form alone the patches differ by the arcs'
    // discretisation, which converges with the mesh: measured at most 4.3e-6 of a patch's
    // area (coarse), 8.1e-7 (medium), 4.8e-8 (fine); asserted 1e-5, 2e-6, 1e-7.
    for (level, arcs) in [("coarse", 1e-5), ("medium", 2e-6), ("fine", 1e-7)] {
        for part in ["disc", "pad"] {
            let m = mesh(&format!("{part}_{level}.inp"));
            for grid in [[1, 1], [3, 3], [4, 4], [2, 5], [5, 7]] {
                let p = patches(&m, "CONTACT_FACE", grid[0], grid[1], &Axis::default()).unwrap();
                let (closed, cells) = annular_cells(&m, "CONTACT_FACE", grid);
                let (mut d_area, mut d_centroid, mut d_closed) = (0.0f64, 0.0f64, 0.0f64);
                for (q, (c, e)) in p.iter().zip(cells.iter().zip(&closed)) {
                    let centroid = [c[1] / c[0], c[2] / c[0]];
                    d_area = d_area.max((q.area / c[0] - 1.0).abs());
                    d_closed = d_closed.max((q.area / e[0] - 1.0).abs());
                    d_centroid = d_centroid
                        .max((q.centroid[0] - centroid[0]).hypot(q.centroid[1] - centroid[1]));
                    assert!((q.centroid[2] - 0.02).abs() < 1e-15, "{:?}", q.centroid);
                    // The weights are the integrals' own: they sum to 1 and reproduce the
                    // centroid (round-off of about 100 terms of size 0.1).
                    let sum: f64 = q.weights.iter().map(|w| w.1).sum();
                    assert!((sum - 1.0).abs() < 1e-13, "{sum}");
                    for d in 0..3 {
                        let x: f64 = q
                            .weights
                            .iter()
                            .map(|&(n, w)| w * m.nodes[n as usize][d])
                            .sum();
                        assert!((x - q.centroid[d]).abs() < 1e-14, "{x} vs {:?}", q.centroid);
                    }
                }
                eprintln!(
                    "{part}_{level} {grid:?}: area {d_area:.1e}, centroid {d_centroid:.1e} m off the cells; area {d_closed:.1e} off the closed form"
                );
                assert!(
                    d_area < 1e-10 && d_centroid < 1e-12,
                    "{part}_{level} {grid:?}"
                );
                assert!(d_closed < arcs, "{part}_{level} {grid:?}: {d_closed:e}");
            }
        }
    }
}
