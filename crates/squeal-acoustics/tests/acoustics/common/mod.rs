//! Test surfaces with closed-form sound fields: a flat disc (the baffled piston) and a sphere,
//! both of 6-node triangles with their midside nodes on the exact geometry.

#![allow(dead_code)]

use std::f64::consts::PI;

/// A surface as plain data: nodes and 6-node faces (`[v0, v1, v2, m01, m12, m20]`).
pub struct Tri6Surface {
    pub nodes: Vec<[f64; 3]>,
    pub faces: Vec<u32>,
}

impl Tri6Surface {
    pub fn face_count(&self) -> usize {
        self.faces.len() / 6
    }
}

/// A disc of radius `a` in the plane z = 0, normal +z: a centre node and `rings` rings of
/// `6 j` nodes at radius `a j / rings`, zipped into triangles; midside nodes at the polar
/// midpoints (on the circle for rim edges).
pub fn disc(a: f64, rings: usize) -> Tri6Surface {
    // Corner nodes in polar coordinates.
    let mut polar = vec![(0.0, 0.0)];
    let mut ring_start = vec![0usize];
    for j in 1..=rings {
        ring_start.push(polar.len());
        let m = 6 * j;
        for i in 0..m {
            polar.push((a * j as f64 / rings as f64, 2.0 * PI * i as f64 / m as f64));
        }
    }
    let ring = |j: usize| -> Vec<usize> {
        let n = if j == 0 { 1 } else { 6 * j };
        (0..n).map(|i| ring_start[j] + i).collect()
    };
    let mut tris: Vec<[usize; 3]> = Vec::new();
    for j in 1..=rings {
        let (inner, outer) = (ring(j - 1), ring(j));
        let (ni, no) = (inner.len(), outer.len());
        let (mut i, mut o) = (0usize, 0usize);
        // Zip by angle: advance whichever ring's next node comes first.
        while i < ni || o < no {
            let ang = |k: usize, n: usize| 2.0 * PI * k as f64 / n as f64;
            let next_o = ang(o + 1, no);
            let next_i = if ni == 1 {
                f64::INFINITY
            } else {
                ang(i + 1, ni)
            };
            if o < no && (next_o <= next_i || i >= ni) {
                tris.push([inner[i % ni], outer[o], outer[(o + 1) % no]]);
                o += 1;
            } else {
                tris.push([inner[i % ni], outer[o % no], inner[(i + 1) % ni]]);
                i += 1;
            }
            if ni == 1 && o == no {
                break;
            }
        }
    }
    let xy = |(r, t): (f64, f64)| [r * t.cos(), r * t.sin(), 0.0];
    let mut nodes: Vec<[f64; 3]> = polar.iter().map(|&p| xy(p)).collect();
    let mut faces = Vec::new();
    for t in tris {
        let mut t = t;
        let p: Vec<[f64; 3]> = t.iter().map(|&k| nodes[k]).collect();
        let cz =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
        if cz < 0.0 {
            t.swap(1, 2);
        }
        let mut face: Vec<u32> = t.iter().map(|&k| k as u32).collect();
        for (u, v) in [(0, 1), (1, 2), (2, 0)] {
            let (p, q) = (polar[t[u]], polar[t[v]]);
            let (mut tp, mut tq) = (p.1, q.1);
            if p.0 == 0.0 {
                tp = tq;
            }
            if q.0 == 0.0 {
                tq = tp;
            }
            if tq - tp > PI {
                tq -= 2.0 * PI;
            } else if tp - tq > PI {
                tq += 2.0 * PI;
            }
            nodes.push(xy((0.5 * (p.0 + q.0), 0.5 * (tp + tq))));
            face.push(nodes.len() as u32 - 1);
        }
        faces.extend(face);
    }
    Tri6Surface { nodes, faces }
}

/// A sphere of radius `a` about the origin: the icosahedron's faces cut into `m²` triangles,
/// every node (midsides too) projected onto the sphere; outward normals.
pub fn sphere(a: f64, m: usize) -> Tri6Surface {
    let g = (1.0 + 5f64.sqrt()) / 2.0;
    let v = [
        [-1.0, g, 0.0],
        [1.0, g, 0.0],
        [-1.0, -g, 0.0],
        [1.0, -g, 0.0],
        [0.0, -1.0, g],
        [0.0, 1.0, g],
        [0.0, -1.0, -g],
        [0.0, 1.0, -g],
        [g, 0.0, -1.0],
        [g, 0.0, 1.0],
        [-g, 0.0, -1.0],
        [-g, 0.0, 1.0],
    ];
    let ico = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let proj = |p: [f64; 3]| {
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        p.map(|x| a * x / r)
    };
    let (mut nodes, mut faces) = (Vec::new(), Vec::new());
    for t in ico {
        let (p0, p1, p2) = (v[t[0]], v[t[1]], v[t[2]]);
        // Point of the big triangle at (i, j) steps of 1/m along its edges (unprojected).
        let at = |i: f64, j: f64| {
            let (s, u) = (i / m as f64, j / m as f64);
            std::array::from_fn::<f64, 3, _>(|d| p0[d] + s * (p1[d] - p0[d]) + u * (p2[d] - p0[d]))
        };
        for i in 0..m {
            for j in 0..m - i {
                let (fi, fj) = (i as f64, j as f64);
                let mut tris = vec![[(fi, fj), (fi + 1.0, fj), (fi, fj + 1.0)]];
                if i + j + 1 < m {
                    tris.push([(fi + 1.0, fj), (fi + 1.0, fj + 1.0), (fi, fj + 1.0)]);
                }
                for tr in tris {
                    let c: Vec<(f64, f64)> = tr.to_vec();
                    let mids = [(0, 1), (1, 2), (2, 0)]
                        .map(|(u, w)| (0.5 * (c[u].0 + c[w].0), 0.5 * (c[u].1 + c[w].1)));
                    let base = nodes.len() as u32;
                    for &(x, y) in c.iter().chain(mids.iter()) {
                        nodes.push(proj(at(x, y)));
                    }
                    let mut f: Vec<u32> = (base..base + 6).collect();
                    // Outward: (x1 − x0) × (x2 − x0) along x0.
                    let (x0, x1, x2) = (
                        nodes[f[0] as usize],
                        nodes[f[1] as usize],
                        nodes[f[2] as usize],
                    );
                    let e1 = [x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]];
                    let e2 = [x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]];
                    let n = [
                        e1[1] * e2[2] - e1[2] * e2[1],
                        e1[2] * e2[0] - e1[0] * e2[2],
                        e1[0] * e2[1] - e1[1] * e2[0],
                    ];
                    if n[0] * x0[0] + n[1] * x0[1] + n[2] * x0[2] < 0.0 {
                        // Reverse: [v0, v2, v1, m20, m12, m01].
                        f = vec![f[0], f[2], f[1], f[5], f[4], f[3]];
                    }
                    faces.extend(f);
                }
            }
        }
    }
    Tri6Surface { nodes, faces }
}

/// The Bessel function J1 by its power series Σ (−1)^m (x/2)^{2m+1} / (m! (m+1)!), summed
/// until the terms vanish against the sum: to about 1e-15 relative for |x| ≤ 12 (the largest
/// term there is below 1e3, so the cancellation loses at most 3 of 16 digits).
pub fn bessel_j1(x: f64) -> f64 {
    let h = 0.5 * x;
    let mut term = h;
    let mut sum = term;
    for m in 1..200 {
        let mf = m as f64;
        term *= -h * h / (mf * (mf + 1.0));
        sum += term;
        if term.abs() < 1e-18 * sum.abs().max(1e-300) {
            break;
        }
    }
    sum
}
