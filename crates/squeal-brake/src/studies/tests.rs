use super::*;
use crate::modal::modal_basis;
use crate::spectrum::spectrum_of;

#[test]
fn second_order_growth_matches_the_eigenvalues_of_a_small_system() {
    // Three modes at 1, 1.7, 2.6 krad/s; damping on mode 1 only (the "pair" of this toy);
    // a non-symmetric coupling ε N. The dense eigensolver is the reference: the
    // perturbation is exact to O(ε²), so its relative error on Re λ is of order
    // ε ‖N‖ / (ω_k² - ω_j²) ≈ 1.3e-3 at ε = 0.01 and 4e-3 at ε = 0.03 (measured: 4e-4 at
    // ε = 0.01); 5e-3 at both.
    let omega = [1000.0, 1700.0, 2600.0];
    let basis = modal_basis(
        &Mat::from_fn(3, 3, |i, j| if i == j { 1.0 } else { 0.0 }),
        &Mat::from_fn(3, 3, |i, j| if i == j { omega[i] * omega[i] } else { 0.0 }),
    )
    .unwrap();
    let d = [0.0, 2.0 * 0.01 * 1700.0, 0.0];
    let dm = crate::damping::ModalDamping::Diagonal(d.to_vec());
    let n = [
        [3.0e4, 2.0e5, -1.0e5],
        [-2.5e5, -1.0e4, 1.5e5],
        [0.8e5, -1.2e5, 2.0e4],
    ];
    for eps in [0.01, 0.03] {
        let dk = Mat::from_fn(3, 3, |i, j| eps * n[i][j]);
        let sp = spectrum_of(&basis, &dm, &dk, None, eps).unwrap();
        for j in [0usize, 2] {
            let exact = sp.values[j].re;
            let approx = second_order_real_part(&basis.omega, &d, &dk, j);
            assert!(
                (approx / exact - 1.0).abs() < 5e-3,
                "eps {eps} mode {j}: {approx} vs {exact}"
            );
        }
        // Mode 0: N01 N10 < 0 with the damped mode 1, so it is destabilized.
        assert!(sp.values[0].re > 0.0);
    }
}

#[test]
fn growth_of_an_undamped_mode_scales_with_the_square_of_the_coupling() {
    // The log-log slope of Re λ against ε for ε = 1e-3 .. 1e-2 must be 2 (second order);
    // the next term is O(ε²) relative (N has no diagonal), ≈ (ε ‖N‖/gap)² ≈ 3e-6 at
    // ε = 1e-2: 1e-4 is a safe tolerance.
    let omega = [1000.0, 1700.0];
    let basis = modal_basis(
        &Mat::from_fn(2, 2, |i, j| if i == j { 1.0 } else { 0.0 }),
        &Mat::from_fn(2, 2, |i, j| if i == j { omega[i] * omega[i] } else { 0.0 }),
    )
    .unwrap();
    let dm = crate::damping::ModalDamping::Diagonal(vec![0.0, 34.0]);
    let eps = [1e-3, 2e-3, 5e-3, 1e-2];
    let re: Vec<f64> = eps
        .iter()
        .map(|&e| {
            let dk = Mat::from_fn(2, 2, |i, j| e * [[0.0, 3e5], [-3e5, 0.0]][i][j]);
            spectrum_of(&basis, &dm, &dk, None, e).unwrap().values[0].re
        })
        .collect();
    let slope = log_slope(&eps, &re).unwrap();
    assert!((slope - 2.0).abs() < 1e-4, "slope {slope}, re {re:?}");
}

#[test]
fn circumferential_orders_find_the_nodal_diameters_on_irregular_samples() {
    // cos(3θ + 0.4) + 0.2 cos(5θ) on 150 irregular angles (gaps up to ~3.4°): linear
    // interpolation lowers an order-n amplitude by about (n gap)²/12, 0.3% for n = 5, so
    // the shares are within 0.005 of 1/1.04 and 0.04/1.04 (measured: 2e-4).
    let angles: Vec<f64> = (0..150)
        .map(|k| 2.0 * PI * (k as f64 + 0.4 * ((k * 7919) % 13) as f64 / 13.0) / 150.0)
        .collect();
    let values: Vec<c64> = angles
        .iter()
        .map(|t| c64::new((3.0 * t + 0.4).cos() + 0.2 * (5.0 * t).cos(), 0.0))
        .collect();
    let o = circumferential_orders(&angles, &values, 12).unwrap();
    let (n, share) = o.dominant();
    assert_eq!(n, 3);
    assert!((share - 1.0 / 1.04).abs() < 5e-3, "{:?}", o.shares);
    assert!((o.shares[5] - 0.04 / 1.04).abs() < 5e-3, "{:?}", o.shares);
    // A travelling wave e^{-i4θ} (a complex mode) counts as order 4 too.
    let wave: Vec<c64> = angles
        .iter()
        .map(|t| c64::new((4.0 * t).cos(), -(4.0 * t).sin()))
        .collect();
    let o = circumferential_orders(&angles, &wave, 12).unwrap();
    assert_eq!(o.dominant().0, 4);
    assert!(o.dominant().1 > 0.98, "{:?}", o.shares);
}

#[test]
fn pad_profiles_tell_rocking_from_bending() {
    // Exact shapes on 41 points: a tilt is all "rigid" (share 1 to round-off) with one
    // sign change; the first free-free beam bending shape is mostly not a straight line
    // and changes sign twice.
    let s: Vec<f64> = (0..41).map(|k| -0.05 + 0.0025 * k as f64).collect();
    let tilt: Vec<c64> = s.iter().map(|x| c64::new(0.0, 2.0 * x)).collect();
    let p = pad_profile(&s, &tilt).unwrap();
    assert_eq!(p.sign_changes, 1);
    assert!((p.rigid_share - 1.0).abs() < 1e-12, "{p:?}");
    // Free-free beam mode 1 of length L: βL = 4.7300, nodes at 0.224 L and 0.776 L.
    let (l, b) = (0.1, 4.730_040_745 / 0.1);
    let sigma = 0.982_502_215;
    let bend: Vec<c64> = s
        .iter()
        .map(|x| {
            let u = b * (x + 0.05);
            let v = u.cosh() + u.cos() - sigma * (u.sinh() + u.sin());
            c64::new(v, 0.0)
        })
        .collect();
    let p = pad_profile(&s, &bend).unwrap();
    assert_eq!(p.sign_changes, 2, "{p:?} (L = {l})");
    assert!(p.rigid_share < 0.2, "{p:?}");
}

#[test]
fn energy_share_of_a_block_diagonal_mass() {
    // M = diag(2, 3 | 5): x = (1, i | 1) puts 2 + 3 = 5 of the total 10 in the first block.
    let m = Mat::from_fn(3, 3, |i, j| if i == j { [2.0, 3.0, 5.0][i] } else { 0.0 });
    let x = [c64::new(1.0, 0.0), c64::new(0.0, 1.0), c64::new(1.0, 0.0)];
    assert!((energy_share(&m, &x, 0..2) - 0.5).abs() < 1e-15);
}

#[test]
fn scaling_changes_only_the_piston_force_and_the_contact_stiffness() {
    // Factors multiply exactly (one rounding each).
    use crate::model::ContactPair;
    let b = Brake {
        m: Mat::from_fn(2, 2, |i, j| if i == j { 1.0 } else { 0.0 }),
        k: Mat::from_fn(2, 2, |i, j| if i == j { 1e6 } else { 0.0 }),
        f_piston: vec![0.0, -300.0],
        c: None,
        k_vibration: None,
        pairs: vec![ContactPair {
            disc_point: 0,
            pad_point: 0,
            position: [0.0; 3],
            normal_direction: [0.0, 0.0, 1.0],
            sliding_direction: [1.0, 0.0, 0.0],
            normal: vec![(1, 1.0)],
            tangent: vec![(0, 1.0)],
            initial_gap: 0.0,
            surface_speed: None,
            law: std::sync::Arc::new(crate::contact::PenaltyCoulomb {
                k_linear: 2e6,
                k_cubic: 4e15,
            }),
        }],
    };
    let s = scaled_brake(&b, 0.8, 1.3).unwrap();
    assert_eq!(s.f_piston, vec![0.0, -300.0 * 0.8]);
    let k = crate::contact::Kinematics {
        penetration: 1e-5,
        ..Default::default()
    };
    let (r0, r1) = (
        b.pairs[0].law.response(0.5, &k),
        s.pairs[0].law.response(0.5, &k),
    );
    assert_eq!(r1.normal, 1.3 * r0.normal);
    assert_eq!(r1.normal_derivatives[0], 1.3 * r0.normal_derivatives[0]);
    assert_eq!(s.k, b.k);
    assert!(scaled_brake(&b, -1.0, 1.0).is_err() && scaled_brake(&b, 1.0, f64::NAN).is_err());
}

#[test]
fn the_paper_case_lists() {
    // Tables 4-6 of the paper: the values and the case numbers.
    let p: Vec<(usize, f64)> = pressure_cases()
        .iter()
        .map(|c| (c.number, c.pressure))
        .collect();
    assert_eq!(p, vec![(1, 1.0), (5, 0.8), (6, 1.2)]);
    let k: Vec<(usize, f64)> = stiffness_cases()
        .iter()
        .map(|c| (c.number, c.stiffness))
        .collect();
    assert_eq!(k, vec![(1, 1.0), (7, 0.7), (8, 1.3)]);
    let d: Vec<f64> = damping_cases()
        .iter()
        .map(|c| c.pair_factors[0] / c.pair_factors[1])
        .collect();
    assert_eq!(d, vec![1.0, 1.0, 1.0, 0.5, 0.2, 2.0, 5.0]);
    let grid = small_friction_grid();
    assert_eq!(grid.len(), 11);
    assert!(grid.windows(2).all(|w| w[1] > w[0]) && grid[10] == 0.1);
}
