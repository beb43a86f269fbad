//! Structured meshes of boxes, for tests and convergence studies.
//!
//! [`box_tet10`]: each of the `nx × ny × nz` hexahedral cells is split into six tetrahedra
//! around its main diagonal (Kuhn's subdivision, conforming across cells), and midside nodes
//! are placed at the edge midpoints, so every element is straight-sided and positively
//! oriented. [`box_solid`] fills each cell with one 20-node hexahedron, two 15-node wedges
//! (the cell's square cut along a diagonal, extruded along z) or six 13-node pyramids (one on
//! each face, apex at the cell's centre), every element the affine image of its reference
//! element, positively oriented.

use crate::builder::MeshBuilder;
use crate::model::Mesh;
use crate::tet10::{EDGES, det3};
use squeal_element::ElementKind;

/// A tet10 mesh of the box `[0, lengths[0]] × [0, lengths[1]] × [0, lengths[2]]` with
/// `cells[d]` hexahedral cells along axis `d` (0 counts as 1), each split into six
/// tetrahedra (module documentation). Node ids are 1-based positions on the grid of
/// half-cells (not consecutive), element ids `1..=6 nx ny nz`. Node sets
/// `XMIN, XMAX, YMIN, YMAX, ZMIN, ZMAX` (the six faces) and element set `ALL`.
pub fn box_tet10(lengths: [f64; 3], cells: [usize; 3]) -> Mesh {
    box_tet10_origin([0.0; 3], lengths, cells)
}

/// As [`box_tet10`], with the box's lowest corner at `origin`.
pub fn box_tet10_origin(origin: [f64; 3], lengths: [f64; 3], cells: [usize; 3]) -> Mesh {
    let [nx, ny, nz] = cells.map(|c| c.max(1));
    // Points live on the doubled grid (2nx+1)(2ny+1)(2nz+1); only the used ones become nodes.
    let (gx, gy) = (2 * nx + 1, 2 * ny + 1);
    let grid_id = |i: usize, j: usize, k: usize| (i + gx * (j + gy * k)) as u64 + 1;
    let coord = |i: usize, j: usize, k: usize| {
        [
            origin[0] + lengths[0] * i as f64 / (2 * nx) as f64,
            origin[1] + lengths[1] * j as f64 / (2 * ny) as f64,
            origin[2] + lengths[2] * k as f64 / (2 * nz) as f64,
        ]
    };
    const PERMS: [[usize; 3]; 6] = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    let mut b = MeshBuilder::new();
    let mut used = std::collections::BTreeSet::new();
    let mut elements = Vec::new();
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                for perm in PERMS {
                    // Vertices on the doubled grid.
                    let mut v = [[2 * i, 2 * j, 2 * k]; 4];
                    for s in 0..3 {
                        v[s + 1] = v[s];
                        v[s + 1][perm[s]] += 2;
                    }
                    let x: [[f64; 3]; 4] = v.map(|p| coord(p[0], p[1], p[2]));
                    let d = |a: usize| [x[a][0] - x[0][0], x[a][1] - x[0][1], x[a][2] - x[0][2]];
                    if det3(&[d(1), d(2), d(3)]) < 0.0 {
                        v.swap(1, 2);
                    }
                    let mut ids = [0u64; 10];
                    for (n, p) in v.iter().enumerate() {
                        ids[n] = grid_id(p[0], p[1], p[2]);
                        used.insert(*p);
                    }
                    for (e, [a, c]) in EDGES.iter().enumerate() {
                        let m = [
                            (v[*a][0] + v[*c][0]) / 2,
                            (v[*a][1] + v[*c][1]) / 2,
                            (v[*a][2] + v[*c][2]) / 2,
                        ];
                        ids[4 + e] = grid_id(m[0], m[1], m[2]);
                        used.insert(m);
                    }
                    elements.push(ids);
                }
            }
        }
    }
    let mut faces: [Vec<u64>; 6] = Default::default();
    // Node ids in grid order (k, j, i), for reproducible numbering.
    let mut ordered: Vec<[usize; 3]> = used.into_iter().collect();
    ordered.sort_by_key(|p| (p[2], p[1], p[0]));
    for p in ordered {
        let id = grid_id(p[0], p[1], p[2]);
        // Ids are unique by construction.
        let _ = b.add_node(id, coord(p[0], p[1], p[2]));
        let bounds = [(p[0], 2 * nx), (p[1], 2 * ny), (p[2], 2 * nz)];
        for (d, (c, max)) in bounds.iter().enumerate() {
            if *c == 0 {
                faces[2 * d].push(id);
            }
            if c == max {
                faces[2 * d + 1].push(id);
            }
        }
    }
    for (e, ids) in elements.into_iter().enumerate() {
        let _ = b.add_element(e as u64 + 1, ids);
    }
    for (name, ids) in ["XMIN", "XMAX", "YMIN", "YMAX", "ZMIN", "ZMAX"]
        .iter()
        .zip(faces)
    {
        b.add_to_node_set(name, ids);
    }
    b.add_to_element_set("ALL", 1..=(6 * nx * ny * nz) as u64);
    b.finish()
}

/// A mesh of the box `[0, lengths[0]] × [0, lengths[1]] × [0, lengths[2]]` with `cells[d]`
/// cells along axis `d` (0 counts as 1), each filled with elements of `kind` (module
/// documentation; tet10 gives [`box_tet10`]). Node ids are 1-based positions on a grid of
/// quarter-cells, element ids `1..`. Node sets `XMIN, XMAX, YMIN, YMAX, ZMIN, ZMAX` and
/// element set `ALL`, as [`box_tet10`].
pub fn box_solid(kind: ElementKind, lengths: [f64; 3], cells: [usize; 3]) -> Mesh {
    if kind == ElementKind::Tet10 {
        return box_tet10(lengths, cells);
    }
    let [nx, ny, nz] = cells.map(|c| c.max(1));
    let q = [4 * nx, 4 * ny, 4 * nz];
    let grid_id = |p: [usize; 3]| (p[0] + (q[0] + 1) * (p[1] + (q[1] + 1) * p[2])) as u64 + 1;
    let maps = cell_maps(kind);
    let mut used = std::collections::BTreeSet::new();
    let mut elements: Vec<Vec<u64>> = Vec::new();
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                for map in &maps {
                    let ids = kind
                        .nodes_ref()
                        .iter()
                        .map(|r| {
                            // Cell coordinates of the node, times 4: integers by construction.
                            let local = map(*r);
                            let p: [usize; 3] = std::array::from_fn(|d| {
                                4 * [i, j, k][d] + (4.0 * local[d]).round() as usize
                            });
                            used.insert(p);
                            grid_id(p)
                        })
                        .collect();
                    elements.push(ids);
                }
            }
        }
    }
    let mut b = MeshBuilder::new();
    let mut faces: [Vec<u64>; 6] = Default::default();
    let mut ordered: Vec<[usize; 3]> = used.into_iter().collect();
    ordered.sort_by_key(|p| (p[2], p[1], p[0]));
    for p in ordered {
        let id = grid_id(p);
        let x = std::array::from_fn(|d| lengths[d] * p[d] as f64 / q[d] as f64);
        // Ids are unique by construction.
        let _ = b.add_node(id, x);
        for d in 0..3 {
            if p[d] == 0 {
                faces[2 * d].push(id);
            }
            if p[d] == q[d] {
                faces[2 * d + 1].push(id);
            }
        }
    }
    let count = elements.len() as u64;
    for (e, ids) in elements.into_iter().enumerate() {
        let _ = b.add_typed(e as u64 + 1, kind, &ids);
    }
    for (name, ids) in ["XMIN", "XMAX", "YMIN", "YMAX", "ZMIN", "ZMAX"]
        .iter()
        .zip(faces)
    {
        b.add_to_node_set(name, ids);
    }
    b.add_to_element_set("ALL", 1..=count);
    b.finish()
}

/// A map from reference coordinates to cell coordinates (`[0, 1]³`).
type CellMap = Box<dyn Fn([f64; 3]) -> [f64; 3]>;

/// The affine maps of the reference element onto the elements of one cell, each with a
/// positive Jacobian.
fn cell_maps(kind: ElementKind) -> Vec<CellMap> {
    match kind {
        ElementKind::Tet10 | ElementKind::Hex20 => {
            vec![Box::new(|r: [f64; 3]| r.map(|v| 0.5 * (v + 1.0)))]
        }
        ElementKind::Wedge15 => vec![
            Box::new(|r: [f64; 3]| [r[0], r[1], 0.5 * (r[2] + 1.0)]),
            // The other half of the square, turned by 180 degrees about z.
            Box::new(|r: [f64; 3]| [1.0 - r[0], 1.0 - r[1], 0.5 * (r[2] + 1.0)]),
        ],
        ElementKind::Pyramid13 => {
            // Base on the face whose inward normal is w, (u, v, w) right-handed.
            let frames: [[usize; 3]; 3] = [[0, 1, 2], [1, 2, 0], [2, 0, 1]];
            let mut maps: Vec<CellMap> = Vec::new();
            for [u, v, w] in frames {
                for sign in [1.0, -1.0] {
                    // Inward normal sign * e_w; swapping u and v for the opposite face keeps
                    // the frame right-handed.
                    let (u, v) = if sign > 0.0 { (u, v) } else { (v, u) };
                    maps.push(Box::new(move |r: [f64; 3]| {
                        let mut p = [0.5; 3];
                        p[u] += 0.5 * r[0];
                        p[v] += 0.5 * r[1];
                        p[w] += sign * 0.5 * (r[2] - 1.0);
                        p
                    }));
                }
            }
            maps
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tet10::volume;

    #[test]
    fn box_volume_and_counts() {
        let m = box_tet10([2.0, 1.0, 0.5], [3, 2, 1]);
        assert_eq!(m.num_elements(), 36);
        // Nodes of a Kuhn tet10 mesh: the doubled grid minus the points no edge reaches.
        let total: f64 = (0..m.num_elements())
            .map(|e| volume(&m.element_coords(e)))
            .sum();
        assert!((total - 1.0).abs() < 1e-14, "volume {total}");
        for e in 0..m.num_elements() {
            assert!(volume(&m.element_coords(e)) > 0.0);
        }
        assert!(m.dangling.is_empty());
        assert_eq!(m.node_sets["XMIN"].len(), 5 * 3);
    }

    /// Every kind fills the box: the volume is exact, every element positively oriented and
    /// affine (min/max det J = 1), and no node is left unused.
    #[test]
    fn solid_boxes_fill_the_box() {
        for (kind, per_cell) in [
            (ElementKind::Hex20, 1),
            (ElementKind::Wedge15, 2),
            (ElementKind::Pyramid13, 6),
        ] {
            let m = box_solid(kind, [2.0, 1.0, 0.5], [3, 2, 2]);
            assert_eq!(m.num_elements(), 12 * per_cell, "{kind}");
            let r = crate::quality::check(&m, &crate::quality::QualityOptions::default());
            assert!(r.findings.is_empty(), "{kind}: {:?}", r.findings);
            // Sums of ~100 exact-rule volumes: round-off.
            assert!(
                (r.volume - 1.0).abs() < 1e-13,
                "{kind}: volume {}",
                r.volume
            );
            assert!((r.worst_jacobian_ratio - 1.0).abs() < 1e-12, "{kind}");
        }
    }
}
