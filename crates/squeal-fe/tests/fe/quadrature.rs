//! Quadrature rules against the analytic moments of the unit tetrahedron:
//! ∫ ξ^a η^b ζ^c = a! b! c! / (a + b + c + 3)!.

use squeal_fe::Quadrature;

fn factorial(n: u32) -> f64 {
    (1..=n).map(f64::from).product()
}

fn exact(a: u32, b: u32, c: u32) -> f64 {
    factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3)
}

/// Largest relative error over all monomials of total degree `deg`.
fn worst_error(rule: &Quadrature, deg: u32) -> f64 {
    let mut worst = 0.0_f64;
    for a in 0..=deg {
        for b in 0..=deg - a {
            let c = deg - a - b;
            let q =
                rule.integrate(|p| p[0].powi(a as i32) * p[1].powi(b as i32) * p[2].powi(c as i32));
            worst = worst.max((q / exact(a, b, c) - 1.0).abs());
        }
    }
    worst
}

fn check(rule: &Quadrature, name: &str) {
    for deg in 0..=rule.degree as u32 {
        let err = worst_error(rule, deg);
        // A few dozen rounded products summed: relative error within 1e-13 (a constant given
        // to 20 digits and rounded to f64 is off by at most 1.1e-16 relative).
        assert!(err < 1e-13, "{name}: degree {deg} monomials off by {err:e}");
    }
    // The claimed degree is tight: some monomial of the next degree is not exact.
    let next = worst_error(rule, rule.degree as u32 + 1);
    assert!(
        next > 1e-6,
        "{name}: degree {} unexpectedly exact ({next:e})",
        rule.degree + 1
    );
    for p in &rule.points {
        assert!(
            p.iter().all(|&v| v >= 0.0) && p.iter().sum::<f64>() <= 1.0,
            "{name}: point {p:?} outside"
        );
    }
}

#[test]
fn centroid_rule_is_exactly_degree_1() {
    check(&Quadrature::centroid(), "centroid");
}

#[test]
fn four_point_rule_is_exactly_degree_2() {
    check(&Quadrature::four_point(), "4-point");
}

#[test]
fn fourteen_point_rule_is_exactly_degree_5() {
    let rule = Quadrature::fourteen_point();
    assert_eq!(rule.len(), 14);
    assert!(rule.weights.iter().all(|&w| w > 0.0));
    check(&rule, "14-point");
}

#[test]
fn collapsed_gauss_rules_reach_degree_2n_minus_3() {
    for n in 2..=6 {
        let rule = Quadrature::collapsed_gauss(n).unwrap();
        assert_eq!(rule.degree, 2 * n - 3);
        check(&rule, &format!("collapsed Gauss n = {n}"));
    }
    assert!(Quadrature::collapsed_gauss(0).is_err());
    assert!(Quadrature::collapsed_gauss(33).is_err());
}

#[test]
fn twenty_four_point_rule_is_exactly_degree_6() {
    let rule = Quadrature::twenty_four_point();
    assert_eq!(rule.len(), 24);
    assert!(rule.weights.iter().all(|&w| w > 0.0));
    // 24 distinct points.
    for (i, p) in rule.points.iter().enumerate() {
        for q in &rule.points[..i] {
            assert!(p != q, "point {p:?} repeated");
        }
    }
    check(&rule, "24-point");
}
