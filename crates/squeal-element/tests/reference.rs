//! Every element against the properties its shape functions, faces, rules and node orders
//! must have, checked the same way for each.

// Index loops mirror the formulas (coordinates, Voigt pairs).
#![allow(clippy::needless_range_loop)]

use squeal_element::reference::{jacobian_range, volume};
use squeal_element::{
    Face, Hex20, Pyramid13, Quadrature, ReferenceElement, Tet10, Wedge15, det3, with_element,
};

/// A point strictly inside each reference domain.
fn inside<E: ReferenceElement<N>, const N: usize>() -> [f64; 3] {
    match E::KIND {
        squeal_element::ElementKind::Tet10 => [0.13, 0.21, 0.37],
        squeal_element::ElementKind::Hex20 => [0.31, -0.57, 0.23],
        squeal_element::ElementKind::Wedge15 => [0.22, 0.41, -0.36],
        squeal_element::ElementKind::Pyramid13 => [0.17, -0.29, 0.38],
    }
}

fn reference_volume<E: ReferenceElement<N>, const N: usize>() -> f64 {
    match E::KIND {
        squeal_element::ElementKind::Tet10 => 1.0 / 6.0,
        squeal_element::ElementKind::Hex20 => 8.0,
        squeal_element::ElementKind::Wedge15 => 1.0,
        squeal_element::ElementKind::Pyramid13 => 4.0 / 3.0,
    }
}

fn check<E: ReferenceElement<N>, const N: usize>() {
    let name = E::KIND.name();
    // Nodal: N_a(x_b) = δ_ab, exactly (the values are sums of exact products).
    for (b, p) in E::NODES_REF.iter().enumerate() {
        let n = E::shape(*p);
        for (a, v) in n.iter().enumerate() {
            let expect = if a == b { 1.0 } else { 0.0 };
            assert!((v - expect).abs() < 1e-15, "{name}: N_{a}(node {b}) = {v}");
        }
    }
    // Partition of unity and linear completeness: Σ N_a = 1, Σ N_a ξ_a = ξ; the gradients
    // of both are 0 and the identity (round-off of sums of ~20 terms of size ~1).
    let xi = inside::<E, N>();
    let n = E::shape(xi);
    let g = E::shape_gradients(xi);
    assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14, "{name}: Σ N");
    for d in 0..3 {
        let x: f64 = n.iter().zip(&E::NODES_REF).map(|(v, p)| v * p[d]).sum();
        assert!((x - xi[d]).abs() < 1e-14, "{name}: Σ N ξ_{d}");
        let gs: f64 = g.iter().map(|r| r[d]).sum();
        assert!(gs.abs() < 1e-13, "{name}: Σ ∂N/∂ξ_{d} = {gs}");
    }
    assert!(
        (det3(&squeal_element::jacobian::<E, N>(&E::NODES_REF, xi)) - 1.0).abs() < 1e-13,
        "{name}: the reference element maps to itself"
    );
    // Gradients against central differences (error ~h² f''' + round-off/h ~ 1e-10).
    let h = 1e-6;
    for j in 0..3 {
        let (mut a, mut b) = (xi, xi);
        a[j] += h;
        b[j] -= h;
        let (na, nb) = (E::shape(a), E::shape(b));
        for i in 0..N {
            let fd = (na[i] - nb[i]) / (2.0 * h);
            assert!(
                (fd - g[i][j]).abs() < 1e-8,
                "{name}: dN{i}/dξ{j}: {fd} vs {}",
                g[i][j]
            );
        }
    }
    // Midside nodes at their edges' midpoints.
    for (k, [a, b]) in E::EDGES.iter().enumerate() {
        let m = E::NODES_REF[E::VERTICES + k];
        for d in 0..3 {
            assert_eq!(
                m[d],
                0.5 * (E::NODES_REF[*a][d] + E::NODES_REF[*b][d]),
                "{name}"
            );
        }
    }
    assert_eq!(E::VERTICES + E::EDGES.len(), N, "{name}");
    // Node orders are permutations.
    for perm in [&E::VTK_ORDER, &E::GMSH_TO_CANONICAL] {
        let mut p = perm.to_vec();
        p.sort_unstable();
        assert_eq!(p, (0..N).collect::<Vec<_>>(), "{name}");
    }
    check_faces::<E, N>();
    // Rules: the volume of the reference element (exact: det J = 1), positive weights.
    for rule in [E::stiffness_rule(), E::mass_rule()]
        .into_iter()
        .chain(E::reduced_stiffness_rule())
    {
        let v = volume::<E, N>(&E::NODES_REF, &rule);
        assert!(
            (v / reference_volume::<E, N>() - 1.0).abs() < 1e-14,
            "{name}: {v}"
        );
        assert!(rule.weights.iter().all(|&w| w > 0.0), "{name}");
    }
    let (lo, hi) = jacobian_range::<E, N>(&E::NODES_REF);
    assert!(
        (lo - 1.0).abs() < 1e-13 && (hi - 1.0).abs() < 1e-13,
        "{name}: {lo} {hi}"
    );
}

/// Each face: its nodes lie on one plane of the reference element, its midside nodes are
/// the midpoints of its corner pairs in turn, its normal points out (away from the
/// centroid), its shape functions vanish on it for every node not on it (conformity), and
/// together the faces cover every edge twice.
fn check_faces<E: ReferenceElement<N>, const N: usize>() {
    let name = E::KIND.name();
    let x = E::NODES_REF;
    let centroid: [f64; 3] = std::array::from_fn(|d| {
        x[..E::VERTICES].iter().map(|p| p[d]).sum::<f64>() / E::VERTICES as f64
    });
    let mut edge_uses = vec![0; E::EDGES.len()];
    for face in E::FACES {
        let nodes = face.nodes();
        let c = face.corners();
        let sub = |a: usize, b: usize| -> [f64; 3] { std::array::from_fn(|d| x[a][d] - x[b][d]) };
        let (u, v) = (sub(nodes[1], nodes[0]), sub(nodes[2], nodes[0]));
        let nrm = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let dot = |p: [f64; 3]| (0..3).map(|d| p[d] * nrm[d]).sum::<f64>();
        let off: [f64; 3] = std::array::from_fn(|d| x[nodes[0]][d] - centroid[d]);
        assert!(dot(off) > 0.0, "{name}: face {nodes:?} points inward");
        for &a in nodes {
            assert!(
                dot(sub(a, nodes[0])).abs() < 1e-15,
                "{name}: face {nodes:?} not planar"
            );
        }
        for k in 0..c {
            let (a, b, m) = (nodes[k], nodes[(k + 1) % c], nodes[c + k]);
            for d in 0..3 {
                assert_eq!(x[m][d], 0.5 * (x[a][d] + x[b][d]), "{name}: face {nodes:?}");
            }
            let e = E::EDGES
                .iter()
                .position(|&[p, q]| (p, q) == (a, b) || (p, q) == (b, a))
                .unwrap_or_else(|| panic!("{name}: face edge ({a}, {b}) is no edge"));
            edge_uses[e] += 1;
        }
        // Conformity: at points of the face, the functions of nodes off the face vanish.
        let pts: Vec<[f64; 3]> = (0..5)
            .map(|s| {
                let w: Vec<f64> = (0..c).map(|k| 1.0 + ((s * 7 + k * 3) % 5) as f64).collect();
                let tot: f64 = w.iter().sum();
                std::array::from_fn(|d| (0..c).map(|k| w[k] * x[nodes[k]][d]).sum::<f64>() / tot)
            })
            .collect();
        for p in pts {
            let n = E::shape(p);
            for a in (0..N).filter(|a| !nodes.contains(a)) {
                assert!(
                    n[a].abs() < 1e-14,
                    "{name}: N_{a} = {} on face {nodes:?}",
                    n[a]
                );
            }
        }
        assert!(matches!(face, Face::Tri6(_) | Face::Quad8(_)));
    }
    assert!(
        edge_uses.iter().all(|&u| u == 2),
        "{name}: edges {edge_uses:?}"
    );
}

#[test]
fn every_element_is_consistent() {
    check::<Tet10, 10>();
    check::<Hex20, 20>();
    check::<Wedge15, 15>();
    check::<Pyramid13, 13>();
}

#[test]
fn kinds_dispatch_to_their_elements() {
    for kind in squeal_element::ElementKind::ALL {
        let n = with_element!(kind, E, N => {
            assert_eq!(<E as ReferenceElement<N>>::KIND, kind);
            N
        });
        assert_eq!(kind.nodes(), n);
        assert_eq!(kind.vtk_order().len(), n);
        assert_eq!(
            squeal_element::ElementKind::from_gmsh_type(kind.gmsh_type()),
            Some(kind)
        );
    }
}

/// The exactness claims of the element docs: on an element with an affine map (a distorted
/// parallelepiped, a wedge with a parallelogram cross-section, a pyramid on a
/// parallelogram), the full stiffness-type integrand `∂N_a/∂ξ_i ∂N_b/∂ξ_j` and the mass
/// integrand `N_a N_b` are integrated exactly: the same as a rule of twice the points to
/// round-off.
#[test]
fn rules_are_exact_where_the_docs_say() {
    fn grads<E: ReferenceElement<N>, const N: usize>(rule: &Quadrature) -> Vec<f64> {
        let mut out = vec![0.0; N * N * 9];
        for (p, w) in rule.points.iter().zip(&rule.weights) {
            let g = E::shape_gradients(*p);
            for a in 0..N {
                for b in 0..N {
                    for i in 0..3 {
                        for j in 0..3 {
                            out[((a * N + b) * 3 + i) * 3 + j] += w * g[a][i] * g[b][j];
                        }
                    }
                }
            }
        }
        out
    }
    fn masses<E: ReferenceElement<N>, const N: usize>(rule: &Quadrature) -> Vec<f64> {
        let mut out = vec![0.0; N * N];
        for (p, w) in rule.points.iter().zip(&rule.weights) {
            let n = E::shape(*p);
            for a in 0..N {
                for b in 0..N {
                    out[a * N + b] += w * n[a] * n[b];
                }
            }
        }
        out
    }
    fn worst(a: &[f64], b: &[f64]) -> f64 {
        let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        a.iter()
            .zip(b)
            .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs() / scale))
    }
    let q = |r: Result<Quadrature, _>| r.unwrap();
    let cases = [
        (
            "hex20",
            worst(
                &grads::<Hex20, 20>(&Hex20::stiffness_rule()),
                &grads::<Hex20, 20>(&q(Quadrature::hex_gauss(6))),
            ),
            worst(
                &masses::<Hex20, 20>(&Hex20::mass_rule()),
                &masses::<Hex20, 20>(&q(Quadrature::hex_gauss(8))),
            ),
        ),
        (
            "wedge15",
            worst(
                &grads::<Wedge15, 15>(&Wedge15::stiffness_rule()),
                &grads::<Wedge15, 15>(&q(Quadrature::wedge_gauss(6, 6))),
            ),
            worst(
                &masses::<Wedge15, 15>(&Wedge15::mass_rule()),
                &masses::<Wedge15, 15>(&q(Quadrature::wedge_gauss(8, 8))),
            ),
        ),
        (
            "pyramid13",
            worst(
                &grads::<Pyramid13, 13>(&Pyramid13::stiffness_rule()),
                &grads::<Pyramid13, 13>(&q(Quadrature::pyramid_gauss(6, 8))),
            ),
            worst(
                &masses::<Pyramid13, 13>(&Pyramid13::mass_rule()),
                &masses::<Pyramid13, 13>(&q(Quadrature::pyramid_gauss(6, 10))),
            ),
        ),
    ];
    for (name, k, m) in cases {
        eprintln!("{name}: stiffness-type integrals {k:.1e}, mass {m:.1e} from the finer rule");
        // Exact rules differ from finer exact rules by round-off (sums of ~100 terms).
        assert!(k < 1e-13 && m < 1e-13, "{name}: {k:e} {m:e}");
    }
    // And the reduced 2×2×2 rule of the hex20 is not exact (it is reduced on purpose).
    let reduced = worst(
        &grads::<Hex20, 20>(&Hex20::reduced_stiffness_rule().unwrap()),
        &grads::<Hex20, 20>(&q(Quadrature::hex_gauss(6))),
    );
    assert!(reduced > 1e-3, "{reduced}");
}
