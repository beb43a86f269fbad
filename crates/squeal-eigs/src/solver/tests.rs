use super::*;

/// Ritz values theta of OP = (K - sigma M)^-1 M for eigenvalues `lambda` (shift 0).
fn thetas(lambda: &[f64]) -> Vec<f64> {
    lambda.iter().map(|l| 1.0 / l).collect()
}

#[test]
fn early_bound_needs_accurate_ritz_values_clear_of_it() {
    // Two wanted eigenvalues, a gap of 50 % above: the bound goes halfway, at 2.5.
    let lambda = [1.0, 2.0, 3.0, 4.0];
    let theta = thetas(&lambda);
    assert_eq!(early_bound(&theta, &[1e-8; 4], 2, 0.0), Some(2.5));
    // Residual estimates up to EARLY_ESTIMATE are trusted: 2.5 is 0.5 from 2 and 3,
    // far beyond 2 e |lambda| = 6e-3.
    assert_eq!(early_bound(&theta, &[1e-3; 4], 2, 0.0), Some(2.5));
    // Above it, the Ritz values are not trusted yet (the guard pairs may still move).
    assert_eq!(early_bound(&theta, &[1e-8, 1e-8, 2e-3, 1e-8], 2, 0.0), None);
    // Only the pairs up to the first above the bound matter.
    assert_eq!(
        early_bound(&theta, &[1e-8, 1e-8, 1e-8, 1.0], 2, 0.0),
        Some(2.5)
    );
    // A narrow gap (1e-4 relative, above SAME_EIGENVALUE) that the Ritz values' error
    // bounds (2 e |lambda| = 4e-3) do not resolve: no early bound...
    let close = [1.0, 2.0, 2.0002, 4.0];
    assert_eq!(early_bound(&thetas(&close), &[1e-3; 4], 2, 0.0), None);
    // ...but one once they have converged (the bound sits halfway in the gap).
    let bound = early_bound(&thetas(&close), &[1e-9; 4], 2, 0.0).unwrap();
    assert!((bound - 2.0001).abs() < 1e-12, "bound {bound}");
}
