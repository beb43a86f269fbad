//! Element matrices against independent computations: the consistent mass by exact
//! integration of barycentric polynomials, the stiffness by a different quadrature.

use squeal_fe::{ElasticMaterial, ElementError, Quadrature, element_mass, element_stiffness};
use squeal_mesh::tet10::{EDGES, NODES_REF};

/// A straight-sided, positively oriented element with midside nodes at edge midpoints.
fn element(v: [[f64; 3]; 4]) -> [[f64; 3]; 10] {
    std::array::from_fn(|i| {
        if i < 4 {
            v[i]
        } else {
            let [a, b] = EDGES[i - 4];
            std::array::from_fn(|d| 0.5 * (v[a][d] + v[b][d]))
        }
    })
}

const V: [[f64; 3]; 4] = [
    [0.1, 0.0, 0.05],
    [1.1, 0.2, 0.0],
    [0.3, 0.9, 0.1],
    [0.2, 0.3, 1.2],
];

fn tet_volume(v: &[[f64; 3]; 4]) -> f64 {
    let d = |a: usize| [v[a][0] - v[0][0], v[a][1] - v[0][1], v[a][2] - v[0][2]];
    squeal_mesh::tet10::det3(&[d(1), d(2), d(3)]).abs() / 6.0
}

fn factorial(n: u32) -> f64 {
    (1..=n).map(f64::from).product()
}

/// A shape function as a polynomial in the barycentric coordinates: (coefficient, exponents).
fn shape_poly(i: usize) -> Vec<(f64, [u32; 4])> {
    let unit = |k: usize, p: u32| {
        let mut e = [0; 4];
        e[k] = p;
        e
    };
    if i < 4 {
        vec![(2.0, unit(i, 2)), (-1.0, unit(i, 1))]
    } else {
        let [a, b] = EDGES[i - 4];
        let mut e = [0; 4];
        e[a] = 1;
        e[b] = 1;
        vec![(4.0, e)]
    }
}

/// ∫_T Π L_k^{α_k} dV = 6 V α! / (|α| + 3)! (Eisenberg & Malvern 1973).
fn integrate(poly: &[(f64, [u32; 4])], volume: f64) -> f64 {
    poly.iter()
        .map(|(c, e)| {
            c * 6.0 * volume * e.iter().map(|&k| factorial(k)).product::<f64>()
                / factorial(e.iter().sum::<u32>() + 3)
        })
        .sum()
}

fn product(p: &[(f64, [u32; 4])], q: &[(f64, [u32; 4])]) -> Vec<(f64, [u32; 4])> {
    p.iter()
        .flat_map(|(a, ea)| {
            q.iter()
                .map(move |(b, eb)| (a * b, std::array::from_fn(|k| ea[k] + eb[k])))
        })
        .collect()
}

#[test]
fn consistent_mass_matches_exact_barycentric_integrals() {
    let rho = 2700.0;
    let x = element(V);
    let vol = tet_volume(&V);
    let m = element_mass(&x, rho, &Quadrature::fourteen_point()).unwrap();
    for a in 0..10 {
        for b in 0..10 {
            let exact = rho * integrate(&product(&shape_poly(a), &shape_poly(b)), vol);
            for d in 0..3 {
                // Exact rule; entries of size ρV/420·O(1): round-off ~1e-16 relative to ρV.
                assert!(
                    (m[3 * a + d][3 * b + d] - exact).abs() < 1e-14 * rho * vol,
                    "m[{a}][{b}]"
                );
                assert_eq!(m[3 * a + d][3 * b + (d + 1) % 3], 0.0);
            }
        }
    }
    // The textbook values (Zienkiewicz): vertex diagonal ρV·6/420, vertex–vertex ρV/420,
    // midside diagonal ρV·32/420.
    assert!((m[0][0] * 420.0 / (rho * vol) - 6.0).abs() < 1e-12);
    assert!((m[0][3] * 420.0 / (rho * vol) - 1.0).abs() < 1e-12);
    assert!((m[12][12] * 420.0 / (rho * vol) - 32.0).abs() < 1e-12);
}

#[test]
fn stiffness_is_quadrature_independent_on_straight_elements() {
    let c = ElasticMaterial::isotropic(210e9, 0.3, 7850.0)
        .elasticity()
        .unwrap();
    let x = element(V);
    let k4 = element_stiffness(&x, &c, &Quadrature::four_point()).unwrap();
    let k64 = element_stiffness(&x, &c, &Quadrature::collapsed_gauss(4).unwrap()).unwrap();
    let scale = k4.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    for i in 0..30 {
        for j in 0..30 {
            // Both rules are exact for the degree-2 integrand: round-off only.
            assert!((k4[i][j] - k64[i][j]).abs() < 1e-13 * scale, "K[{i}][{j}]");
            assert_eq!(k4[i][j], k4[j][i]);
        }
    }
}

#[test]
fn reference_element_stiffness_has_unit_scaling() {
    // Scaling the element by s scales K by s (K ~ E·L): an independent check of the
    // Jacobian handling.
    let c = ElasticMaterial::isotropic(1.0, 0.25, 1.0)
        .elasticity()
        .unwrap();
    let rule = Quadrature::four_point();
    let k1 = element_stiffness(&NODES_REF, &c, &rule).unwrap();
    let scaled = NODES_REF.map(|p| p.map(|v| 3.0 * v));
    let k3 = element_stiffness(&scaled, &c, &rule).unwrap();
    for i in 0..30 {
        for j in 0..30 {
            assert!(
                (k3[i][j] - 3.0 * k1[i][j]).abs() < 1e-14 * 3.0,
                "K[{i}][{j}]"
            );
        }
    }
}

#[test]
fn inverted_element_is_an_error() {
    let mut x = element(V);
    x.swap(1, 2);
    // Swap the midside nodes consistently so that only the orientation changes.
    x.swap(4, 6);
    x.swap(8, 9);
    let c = ElasticMaterial::isotropic(1.0, 0.25, 1.0)
        .elasticity()
        .unwrap();
    match element_stiffness(&x, &c, &Quadrature::four_point()) {
        Err(ElementError::NonPositiveJacobian { det, .. }) => assert!(det < 0.0),
        other => panic!("expected an error, got {:?}", other.map(|k| k[0][0])),
    }
}
