use super::*;

/// The LU wrapper solves a nonsymmetric system: residual at rounding level.
#[test]
fn newton_matrix_solves() {
    let n = 7;
    let jac = Mat::from_fn(n, n, |i, j| {
        ((i * 7 + j * 3) % 5) as f64 - 2.0 + (i == j) as u8 as f64
    });
    let c = 0.37;
    let mut nm = NewtonMatrix::new(n);
    nm.factor(jac.as_ref(), c);
    let x_true: Vec<f64> = (0..n).map(|i| (i as f64 + 1.0).sin()).collect();
    let mut b = vec![0.0; n];
    for i in 0..n {
        b[i] = x_true[i] - c * (0..n).map(|j| jac[(i, j)] * x_true[j]).sum::<f64>();
    }
    nm.solve(&mut b);
    for i in 0..n {
        // Well-conditioned 7x7: 1e-12 is ~1e4 ulp of slack.
        assert!(
            (b[i] - x_true[i]).abs() < 1e-12,
            "{i}: {} vs {}",
            b[i],
            x_true[i]
        );
    }
}

/// change_d with factor rho, then 1/rho, is the identity (the polynomial
/// is re-expressed exactly); tolerance: rounding of 6x6 products.
#[test]
fn change_d_round_trip() {
    struct Zero;
    impl OdeSystem for Zero {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, _t: f64, _y: &[f64], dy: &mut [f64]) {
            dy.fill(0.0);
        }
        fn jacobian(&self, _t: f64, _y: &[f64], mut jac: MatMut<'_, f64>) {
            jac.fill(0.0);
        }
    }
    let opts = BdfOptions::default();
    let mut b = Bdf::new(Zero, 0.0, &[1.0, 2.0], 1.0, &opts).unwrap();
    b.order = 5;
    for (i, v) in b.d.iter_mut().enumerate() {
        *v = (i as f64 * 0.7).cos();
    }
    let before = b.d.clone();
    b.change_d(0.37);
    b.change_d(1.0 / 0.37);
    for i in 0..12 {
        assert!((b.d[i] - before[i]).abs() < 1e-11, "{i}");
    }
}
