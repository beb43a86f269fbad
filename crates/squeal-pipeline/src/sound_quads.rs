//! The radiating surface's 8-node quadrilateral faces (of hexahedra, wedges and pyramids)
//! beside its 6-node triangles ([`crate::sound`]).
//!
//! A brake of tetrahedra only keeps the triangles' Dunavant rule (its figures unchanged). A
//! surface with quadrilaterals is integrated with nine points on every face: the collapsed
//! 3 × 3 Gauss rule on the triangles and 3 × 3 Gauss–Legendre on the quadrilaterals, both
//! exact to degree 4 on their reference domains (the area of a flat face of either shape,
//! and `∫ N_i dA` on it); a triangle's node list is padded to eight with its first node, whose
//! two extra shape values are 0 ([`RadiatingSurface::with_rules`]).

use crate::parts::{SceneParts, pad_key};
use squeal_acoustics::{AcousticsError, FaceRule, RadiatingSurface};
use squeal_mesh::Mesh;
use squeal_mesh::select::{self, Face};

/// The disc's quadrilateral boundary faces; a pad's without those of its friction face.
pub(crate) fn radiating_quads(
    sp: &SceneParts,
    mesh: &Mesh,
    name: &str,
    npads: usize,
) -> Vec<[u32; 8]> {
    let quads = select::boundary_quads(mesh);
    if name == "disc" || quads.is_empty() {
        return quads;
    }
    let Some(friction) = sp.set(&pad_key(0, name, npads)).map(|s| s.nodes()) else {
        return quads;
    };
    quads
        .into_iter()
        .filter(|q| !q.iter().all(|n| friction.binary_search(n).is_ok()))
        .collect()
}

/// The faces' nodes (sorted mesh indices), and the triangles and quadrilaterals renumbered
/// onto them from `first`.
pub(crate) fn renumber(
    tris: &[Face],
    quads: &[[u32; 8]],
    first: usize,
) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let mut local = select::face_nodes(tris);
    if !quads.is_empty() {
        local.extend(quads.iter().flatten());
        local.sort_unstable();
        local.dedup();
    }
    // Every node of a face is in `local`, made from the same faces.
    let at = |n: &u32| (first + local.binary_search(n).unwrap_or(0)) as u32;
    let t = tris.iter().flat_map(|f| f.iter().map(at)).collect();
    let q = quads.iter().flat_map(|f| f.iter().map(at)).collect();
    (local, t, q)
}

/// The surface of 6-node triangles `tris` and 8-node quadrilaterals `quads` (node indices
/// into `nodes`), nine points a face (module docs).
pub(crate) fn mixed_surface(
    nodes: &[[f64; 3]],
    tris: &[u32],
    quads: &[u32],
) -> Result<RadiatingSurface, AcousticsError> {
    let rules = [FaceRule::tri6_gauss(3)?, FaceRule::quad8(3)?];
    let mut faces = Vec::with_capacity(tris.len() / 6 * 8 + quads.len());
    let mut which = Vec::with_capacity(tris.len() / 6 + quads.len() / 8);
    for t in tris.chunks_exact(6) {
        faces.extend_from_slice(t);
        faces.extend([t[0], t[0]]);
        which.push(0);
    }
    for q in quads.chunks_exact(8) {
        faces.extend_from_slice(q);
        which.push(1);
    }
    RadiatingSurface::with_rules(nodes, &faces, 8, &rules, &which)
}

#[cfg(test)]
mod tests {
    use super::*;
    use squeal_element::ElementKind;
    use squeal_mesh::generate::box_solid;

    #[test]
    fn a_box_of_hexahedra_radiates_from_its_six_faces() {
        // The boundary of a 0.2 x 0.1 x 0.05 box in hex20 (quadrilaterals only) and in wedge15
        // (triangles on two sides, quadrilaterals on four): the area is 2(ab + bc + ca) to
        // round-off (flat faces, rules exact to degree 4), and the normal velocity of a rigid
        // translation along x is ±1 on the x faces and 0 elsewhere.
        for kind in [ElementKind::Hex20, ElementKind::Wedge15] {
            let mesh = box_solid(kind, [0.2, 0.1, 0.05], [4, 2, 1]);
            let tris = select::boundary_faces(&mesh);
            let quads = select::boundary_quads(&mesh);
            let (local, t, q) = renumber(&tris, &quads, 0);
            let x: Vec<[f64; 3]> = local.iter().map(|&n| mesh.nodes[n as usize]).collect();
            let s = mixed_surface(&x, &t, &q).unwrap();
            let exact = 2.0 * (0.2 * 0.1 + 0.1 * 0.05 + 0.05 * 0.2);
            assert!(
                (s.area() / exact - 1.0).abs() < 1e-13,
                "{kind}: {}",
                s.area()
            );
            let one = squeal_acoustics::Complex64::new(1.0, 0.0);
            let zero = squeal_acoustics::Complex64::new(0.0, 0.0);
            let u = vec![[one, zero, zero]; x.len()];
            let vn = s
                .normal_velocity(squeal_acoustics::Velocity::Nodal(&u))
                .unwrap();
            for (p, v) in s.points.iter().zip(&vn) {
                assert!((v.re - p.normal[0]).abs() < 1e-14, "{kind}");
            }
            // The volume velocity of the translation: zero (a closed surface), to round-off.
            let flux: f64 = s.points.iter().zip(&vn).map(|(p, v)| p.area * v.re).sum();
            assert!(flux.abs() < 1e-15, "{kind}: {flux}");
        }
    }
}
