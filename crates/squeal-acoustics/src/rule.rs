//! Reference faces with their quadrature: the shape functions of an `N`-node face and their
//! derivatives evaluated at the quadrature points of the reference face, with the weights.
//!
//! A face of the surface maps the reference face to space by `x(ξ, η) = Σ_i N_i(ξ, η) x_i`;
//! its area element is `dA = |∂x/∂ξ × ∂x/∂η| dξ dη`, its unit normal the same cross product
//! normalized (outward when the face's nodes run counterclockwise seen from outside, as
//! squeal's boundary faces do). Any face type fits: a rule is plain data (node count, and per
//! point the shape values, their two derivatives and the weight).
//!
//! - [`FaceRule::tri6`]: the 6-node triangle of a tet10's face (`[v0, v1, v2, m01, m12, m20]`,
//!   squeal-mesh's order), with Dunavant's 6-point degree-4 rule.
//! - [`FaceRule::tri6_gauss`]: the same face with an `n × n` collapsed Gauss–Legendre rule
//!   (Duffy), exact for polynomials of degree `2n − 2` on the triangle: a reference of any
//!   accuracy.
//! - [`FaceRule::quad8`]: the 8-node serendipity quadrilateral of a hex20's face (corners
//!   counterclockwise, then the midside nodes of edges 0-1, 1-2, 2-3, 3-0) with `n × n`
//!   Gauss–Legendre points.

use crate::error::{AcousticsError, Result};

/// One quadrature point of a reference face.
#[derive(Clone, Debug, PartialEq)]
pub struct RulePoint {
    /// Reference coordinates `(ξ, η)`.
    pub xi: [f64; 2],
    /// Shape function values `N_i` (one per face node).
    pub shape: Vec<f64>,
    /// `∂N_i/∂ξ` and `∂N_i/∂η` (one pair per face node).
    pub gradient: Vec<[f64; 2]>,
    /// The weight (reference area included: the weights of a triangle sum to 1/2, of the
    /// square `[-1, 1]²` to 4).
    pub weight: f64,
}

/// A face type and its quadrature.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceRule {
    /// Nodes per face.
    pub nodes: usize,
    /// The quadrature points.
    pub points: Vec<RulePoint>,
}

impl FaceRule {
    /// The 6-node triangle with Dunavant's 6-point rule of degree 4 (the rule squeal-mesh
    /// integrates face areas with).
    pub fn tri6() -> Self {
        const A: f64 = 0.445_948_490_915_965;
        const WA: f64 = 0.223_381_589_678_011;
        const B: f64 = 0.091_576_213_509_771;
        const WB: f64 = 0.109_951_743_655_322;
        let pts = [
            (A, A, WA),
            (1.0 - 2.0 * A, A, WA),
            (A, 1.0 - 2.0 * A, WA),
            (B, B, WB),
            (1.0 - 2.0 * B, B, WB),
            (B, 1.0 - 2.0 * B, WB),
        ];
        Self {
            nodes: 6,
            points: pts
                .iter()
                .map(|&(xi, eta, w)| tri6_point(xi, eta, 0.5 * w))
                .collect(),
        }
    }

    /// The 6-node triangle with the collapsed `n × n` Gauss–Legendre rule: `ξ = u`,
    /// `η = v (1 − u)` on `[0, 1]²`, weight `(1 − u) w_u w_v` (exact to degree `2n − 2`).
    pub fn tri6_gauss(n: usize) -> Result<Self> {
        let (x, w) = gauss_legendre_01(n)?;
        let mut points = Vec::with_capacity(n * n);
        for i in 0..n {
            for j in 0..n {
                let (u, v) = (x[i], x[j]);
                points.push(tri6_point(u, v * (1.0 - u), (1.0 - u) * w[i] * w[j]));
            }
        }
        Ok(Self { nodes: 6, points })
    }

    /// The 8-node serendipity quadrilateral on `[-1, 1]²` with `n × n` Gauss–Legendre points.
    pub fn quad8(n: usize) -> Result<Self> {
        let (x, w) = gauss_legendre_01(n)?;
        let mut points = Vec::with_capacity(n * n);
        for i in 0..n {
            for j in 0..n {
                let (xi, eta) = (2.0 * x[i] - 1.0, 2.0 * x[j] - 1.0);
                points.push(quad8_point(xi, eta, 4.0 * w[i] * w[j]));
            }
        }
        Ok(Self { nodes: 8, points })
    }
}

/// Shape values and gradients of the 6-node triangle at `(ξ, η)`, barycentric
/// `L = (1 − ξ − η, ξ, η)`: corners `L_i (2 L_i − 1)`, midsides `4 L_a L_b`.
fn tri6_point(xi: f64, eta: f64, weight: f64) -> RulePoint {
    let l = [1.0 - xi - eta, xi, eta];
    // dL/dξ, dL/dη.
    let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
    let mut shape = Vec::with_capacity(6);
    let mut gradient = Vec::with_capacity(6);
    for i in 0..3 {
        shape.push(l[i] * (2.0 * l[i] - 1.0));
        let g = 4.0 * l[i] - 1.0;
        gradient.push([g * dl[i][0], g * dl[i][1]]);
    }
    for (a, b) in [(0, 1), (1, 2), (2, 0)] {
        shape.push(4.0 * l[a] * l[b]);
        gradient.push([
            4.0 * (dl[a][0] * l[b] + l[a] * dl[b][0]),
            4.0 * (dl[a][1] * l[b] + l[a] * dl[b][1]),
        ]);
    }
    RulePoint {
        xi: [xi, eta],
        shape,
        gradient,
        weight,
    }
}

/// Shape values and gradients of the 8-node serendipity quadrilateral at `(ξ, η)`.
fn quad8_point(xi: f64, eta: f64, weight: f64) -> RulePoint {
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let mut shape = Vec::with_capacity(8);
    let mut gradient = Vec::with_capacity(8);
    for &(a, b) in &corners {
        let (p, q) = (1.0 + a * xi, 1.0 + b * eta);
        let s = a * xi + b * eta - 1.0;
        shape.push(0.25 * p * q * s);
        gradient.push([0.25 * a * q * (s + p), 0.25 * b * p * (s + q)]);
    }
    // Midsides of edges 0-1 (η = −1), 1-2 (ξ = 1), 2-3 (η = 1), 3-0 (ξ = −1).
    for &(a, b, along_xi) in &[
        (0.0, -1.0, true),
        (1.0, 0.0, false),
        (0.0, 1.0, true),
        (-1.0, 0.0, false),
    ] {
        if along_xi {
            let q = 1.0 + b * eta;
            shape.push(0.5 * (1.0 - xi * xi) * q);
            gradient.push([-xi * q, 0.5 * (1.0 - xi * xi) * b]);
        } else {
            let p = 1.0 + a * xi;
            shape.push(0.5 * (1.0 - eta * eta) * p);
            gradient.push([0.5 * (1.0 - eta * eta) * a, -eta * p]);
        }
    }
    RulePoint {
        xi: [xi, eta],
        shape,
        gradient,
        weight,
    }
}

/// Gauss–Legendre nodes (ascending) and weights on `[0, 1]` (`1 ≤ n ≤ 200`): squeal-element's
/// rule, the one the element quadratures use.
pub fn gauss_legendre_01(n: usize) -> Result<(Vec<f64>, Vec<f64>)> {
    if n == 0 || n > 200 {
        return Err(AcousticsError::Rule(format!(
            "{n} Gauss-Legendre points: between 1 and 200 can be made"
        )));
    }
    Ok(squeal_element::quadrature::gauss_legendre_unit(n))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Partition of unity and zero-sum gradients hold at every point of every rule (to
    /// round-off: sums of O(1) terms).
    #[test]
    fn shapes_sum_to_one() {
        for r in [
            FaceRule::tri6(),
            FaceRule::tri6_gauss(5).unwrap(),
            FaceRule::quad8(3).unwrap(),
        ] {
            for p in &r.points {
                assert_eq!(p.shape.len(), r.nodes);
                assert!((p.shape.iter().sum::<f64>() - 1.0).abs() < 1e-14);
                for d in 0..2 {
                    assert!(p.gradient.iter().map(|g| g[d]).sum::<f64>().abs() < 1e-13);
                }
            }
        }
    }

    /// The weights integrate monomials exactly up to the rule's degree: ∫ ξ^a η^b over the
    /// triangle is a! b! / (a + b + 2)!. Tolerance 1e-14: round-off of a sum of ≤ 100 terms.
    #[test]
    fn triangle_rules_are_exact_to_their_degree() {
        let fact = |n: u32| (1..=n).map(f64::from).product::<f64>();
        for (rule, degree) in [
            (FaceRule::tri6(), 4),
            (FaceRule::tri6_gauss(6).unwrap(), 10),
        ] {
            for a in 0..=degree {
                for b in 0..=(degree - a) {
                    let exact = fact(a) * fact(b) / fact(a + b + 2);
                    let got: f64 = rule
                        .points
                        .iter()
                        .map(|p| p.weight * p.xi[0].powi(a as i32) * p.xi[1].powi(b as i32))
                        .sum();
                    assert!(
                        (got - exact).abs() < 1e-14,
                        "degree {degree}, xi^{a} eta^{b}: {got} vs {exact}"
                    );
                }
            }
        }
    }

    /// Gauss–Legendre on [0, 1] integrates x^k exactly for k ≤ 2n − 1 (1e-15: round-off).
    #[test]
    fn gauss_legendre_degree() {
        for n in [1, 2, 5, 12] {
            let (x, w) = gauss_legendre_01(n).unwrap();
            for k in 0..2 * n {
                let got: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(k as i32)).sum();
                assert!((got - 1.0 / (k as f64 + 1.0)).abs() < 1e-15, "n {n} k {k}");
            }
        }
        assert!(gauss_legendre_01(0).is_err());
    }
}
