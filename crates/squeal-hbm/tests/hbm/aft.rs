//! AFT (eq. 29): exact projection of trigonometric polynomials, the predicted aliasing when
//! too few samples are used, and the analytic Jacobians against finite differences.

use super::common;

use common::*;
use faer::Mat;
use squeal_hbm::*;

fn cube() -> impl NonlinearForce {
    FnForce::new(
        1,
        vec![(0, 0)],
        false,
        |x: &[f64], _v: &[f64], f: &mut [f64], _j: Option<LocalJacobian<'_>>| {
            f[0] = x[0].powi(3);
        },
    )
}

fn aft_forces(h: usize, n_samples: usize, u: &[f64]) -> Vec<f64> {
    let layout = HarmonicLayout::new(1, h).unwrap();
    let mut aft = Aft::new(layout, n_samples).unwrap();
    let mut out = vec![0.0; layout.len()];
    aft.forces(&cube(), u, 1.0, &mut out).unwrap();
    out
}

fn assert_close(got: &[f64], want: &[f64], tol: f64) {
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!((g - w).abs() <= tol, "entry {i}: got {g}, want {w}");
    }
}

#[test]
fn cos_cubed_is_exact_with_enough_samples() {
    // cos^3 = 3/4 cos + 1/4 cos 3: with N >= 4H+1 the retained harmonics are exact; only
    // rounding of O(1) sums over a few samples remains, hence 1e-15.
    assert_close(
        &aft_forces(1, 5, &[0.0, 1.0, 0.0]),
        &[0.0, 0.75, 0.0],
        1e-15,
    );
    assert_close(
        &aft_forces(1, 16, &[0.0, 1.0, 0.0]),
        &[0.0, 0.75, 0.0],
        1e-15,
    );
    let u3 = [0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let want3 = [0.0, 0.75, 0.0, 0.0, 0.0, 0.25, 0.0];
    assert_close(&aft_forces(3, 13, &u3), &want3, 1e-15);
}

#[test]
fn cos_cubed_aliases_as_predicted_with_too_few_samples() {
    // N = 4 < 4H+1 = 5: harmonic 3 folds onto |3 - 4| = 1, so F1c = 3/4 + 1/4 = 1.
    assert_close(&aft_forces(1, 4, &[0.0, 1.0, 0.0]), &[0.0, 1.0, 0.0], 1e-15);
    // N = 3: harmonic 3 folds onto 0, so the mean reads 1/4 and F1c stays 3/4.
    assert_close(
        &aft_forces(1, 3, &[0.0, 1.0, 0.0]),
        &[0.25, 0.75, 0.0],
        1e-15,
    );
}

/// Complex Fourier coefficients `c[m + off]`, `m = -M..=M`, as (re, im) pairs.
type Spectrum = Vec<(f64, f64)>;

fn to_spectrum(layout: &HarmonicLayout, u: &[f64], dof: usize, max: usize) -> Spectrum {
    let mut c = vec![(0.0, 0.0); 2 * max + 1];
    c[max] = (u[layout.index(0, Part::Cos, dof).unwrap()], 0.0);
    for k in 1..=layout.n_harmonics() {
        let a = u[layout.index(k, Part::Cos, dof).unwrap()];
        let b = u[layout.index(k, Part::Sin, dof).unwrap()];
        c[max + k] = (a / 2.0, -b / 2.0);
        c[max - k] = (a / 2.0, b / 2.0);
    }
    c
}

/// Product of two series by discrete convolution (truncated to `|m| <= max`).
fn convolve(a: &Spectrum, b: &Spectrum) -> Spectrum {
    let max = (a.len() - 1) / 2;
    let mut c = vec![(0.0, 0.0); a.len()];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            let m = i as isize + j as isize - 2 * max as isize;
            if m.unsigned_abs() <= max {
                let t = &mut c[(m + max as isize) as usize];
                t.0 += x.0 * y.0 - x.1 * y.1;
                t.1 += x.0 * y.1 + x.1 * y.0;
            }
        }
    }
    c
}

fn add(a: &Spectrum, b: &Spectrum, s: f64) -> Spectrum {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x.0 + s * y.0, x.1 + s * y.1))
        .collect()
}

/// Cos/sin coefficients of harmonic k, summing every m congruent to +-k modulo `fold`
/// (`fold = 0`: no folding, the exact continuous coefficients).
fn coefficients(c: &Spectrum, k: usize, fold: usize) -> (f64, f64) {
    let max = (c.len() - 1) / 2;
    let mut z = (0.0, 0.0);
    for (idx, v) in c.iter().enumerate() {
        let m = idx as isize - max as isize;
        let hit = if fold == 0 {
            m == k as isize
        } else {
            (m - k as isize).rem_euclid(fold as isize) == 0
        };
        if hit {
            z.0 += v.0;
            z.1 += v.1;
        }
    }
    if k == 0 {
        (z.0, 0.0)
    } else {
        (2.0 * z.0, -2.0 * z.1)
    }
}

#[test]
fn random_cubic_polynomial_matches_spectral_convolution() {
    // f0 = x0^3 + 2 x0 x1^2, f1 = x0^2 x1 - x1^3 on two dofs with H = 3: the reference is the
    // convolution of the complex spectra (an independent algorithm). With N = 13 = 4H+1 the
    // AFT is exact (rounding only: 1e-13 on O(1) values). With N = 12 the content at
    // m = -9 folds onto harmonic 3 and nowhere else, which the folded spectrum predicts.
    let layout = HarmonicLayout::new(2, 3).unwrap();
    let mut rng = Rng::new(7);
    let u: Vec<f64> = (0..layout.len()).map(|_| rng.next()).collect();
    let force = FnForce::new(
        2,
        vec![(0, 0), (0, 1), (1, 0), (1, 1)],
        false,
        |x: &[f64], _v: &[f64], f: &mut [f64], _j: Option<LocalJacobian<'_>>| {
            f[0] = x[0].powi(3) + 2.0 * x[0] * x[1] * x[1];
            f[1] = x[0] * x[0] * x[1] - x[1].powi(3);
        },
    );
    let max = 9;
    let (c0, c1) = (
        to_spectrum(&layout, &u, 0, max),
        to_spectrum(&layout, &u, 1, max),
    );
    let (c00, c11) = (convolve(&c0, &c0), convolve(&c1, &c1));
    let f0 = add(&convolve(&c00, &c0), &convolve(&c0, &c11), 2.0);
    let f1 = add(&convolve(&c00, &c1), &convolve(&c11, &c1), -1.0);

    for (n_samples, fold) in [(13, 0), (64, 0), (12, 12)] {
        let mut aft = Aft::new(layout, n_samples).unwrap();
        let mut out = vec![0.0; layout.len()];
        aft.forces(&force, &u, 1.0, &mut out).unwrap();
        for (dof, spec) in [(0, &f0), (1, &f1)] {
            for k in 0..=3 {
                let (want_c, want_s) = coefficients(spec, k, fold);
                let got_c = out[layout.index(k, Part::Cos, dof).unwrap()];
                assert!(
                    (got_c - want_c).abs() < 1e-13,
                    "N={n_samples} dof {dof} k={k} cos: {got_c} vs {want_c}"
                );
                if k > 0 {
                    let got_s = out[layout.index(k, Part::Sin, dof).unwrap()];
                    assert!(
                        (got_s - want_s).abs() < 1e-13,
                        "N={n_samples} dof {dof} k={k} sin: {got_s} vs {want_s}"
                    );
                }
            }
        }
    }
    // The aliasing at N = 12 is real, not a rounding effect: harmonic 3 moves visibly.
    let exact = coefficients(&f0, 3, 0);
    let folded = coefficients(&f0, 3, 12);
    assert!((exact.0 - folded.0).abs() + (exact.1 - folded.1).abs() > 1e-3);
}

/// Analytic `dF/dU`, `dF/domega` against central differences of [`Aft::forces`].
fn check_aft_jacobian(
    force: &impl NonlinearForce,
    layout: HarmonicLayout,
    n_samples: usize,
    u: &[f64],
    omega: f64,
    tol: f64,
) {
    let len = layout.len();
    let mut aft = Aft::new(layout, n_samples).unwrap();
    let mut out = vec![0.0; len];
    let mut jac = Mat::zeros(len, len);
    let mut jac_w = vec![0.0; len];
    aft.forces_and_jacobian(force, u, omega, &mut out, jac.as_mut(), &mut jac_w)
        .unwrap();
    let mut plain = vec![0.0; len];
    aft.forces(force, u, omega, &mut plain).unwrap();
    assert_eq!(
        out, plain,
        "forces_and_jacobian and forces must agree bit for bit"
    );

    let h = 1e-6;
    let fd = central_differences(u, len, h, |x, f| aft.forces(force, x, omega, f).unwrap());
    let scale = max_abs(&fd).max(1.0);
    let err = max_abs_diff(&jac, &fd);
    assert!(
        err <= tol * scale,
        "dF/dU: max error {err:e} vs scale {scale:e}"
    );

    let fd_w = central_differences(&[omega], len, h, |w, f| {
        aft.forces(force, u, w[0], f).unwrap()
    });
    let mut err_w: f64 = 0.0;
    for i in 0..len {
        err_w = err_w.max((fd_w[(i, 0)] - jac_w[i]).abs());
    }
    assert!(err_w <= tol * scale, "dF/domega: max error {err_w:e}");
}

#[test]
fn contact_jacobian_matches_finite_differences() {
    // Two contact pairs (8 dofs), H = 3, default N = 32, static closure 0.3 plus random
    // harmonics of size 0.3 so that the contact opens for part of the cycle. Central
    // differences with h = 1e-6: truncation ~ h^2 |f'''| ~ 1e-11 and rounding
    // ~ eps |F| / h ~ 1e-9 relative, far below the 1e-6 tolerance unless a sample sits
    // within h of the kink (not the case for this seed).
    let force = ContactPairs::new(2, 10.0, 50.0, 0.4);
    let layout = HarmonicLayout::new(8, 3).unwrap();
    let mut rng = Rng::new(11);
    let mut u: Vec<f64> = (0..layout.len()).map(|_| 0.3 * rng.next()).collect();
    for p in 0..2 {
        u[4 * p + 1] = 0.2;
        u[4 * p + 3] = -0.1;
    }
    check_aft_jacobian(&force, layout, default_samples(3), &u, 1.3, 1e-6);
}

#[test]
fn velocity_jacobian_matches_finite_differences_even_when_aliased() {
    // Dense velocity-dependent coupling (two dofs), H = 4. The analytic Jacobian is the
    // exact derivative of the discrete map, so it must match with the default N = 64, with
    // the exact bound N = 17, and with the aliased minimum N = 9 alike. Same FD error
    // budget as above (smooth polynomial force: truncation ~1e-11).
    let force = coupled_velocity_force();
    let layout = HarmonicLayout::new(2, 4).unwrap();
    let mut rng = Rng::new(5);
    let u: Vec<f64> = (0..layout.len()).map(|_| 0.5 * rng.next()).collect();
    for n_samples in [default_samples(4), 17, 9] {
        check_aft_jacobian(&force, layout, n_samples, &u, 0.8, 1e-6);
    }
}

#[test]
fn harmonic_balance_jacobian_matches_finite_differences() {
    // Full residual of eq. (26) with random dense M, C, K (non-symmetric K, as with
    // friction) and the velocity-dependent force: checks Lambda(omega) of eq. (27)-(28)
    // and d Lambda / d omega as well as the AFT part. FD budget as above.
    let n = 2;
    let layout = HarmonicLayout::new(n, 3).unwrap();
    let mut rng = Rng::new(3);
    let m = Mat::from_fn(n, n, |i, j| {
        if i == j {
            1.0 + 0.5 * rng.next().abs()
        } else {
            0.1
        }
    });
    let c = Mat::from_fn(n, n, |_, _| 0.2 * rng.next());
    let k = Mat::from_fn(n, n, |_, _| 2.0 * rng.next());
    let linear = MckStiffness::new(m.as_ref(), c.as_ref(), k.as_ref()).unwrap();
    let f_ext: Vec<f64> = (0..layout.len()).map(|_| rng.next()).collect();
    let mut hb =
        HarmonicBalance::new(layout, linear, coupled_velocity_force(), f_ext, None).unwrap();
    let u: Vec<f64> = (0..layout.len()).map(|_| 0.5 * rng.next()).collect();
    let omega = 1.7;
    let len = layout.len();
    let mut jac = Mat::zeros(len, len);
    let mut jac_w = vec![0.0; len];
    hb.jacobian(&u, omega, jac.as_mut(), &mut jac_w).unwrap();

    let mut z = u.clone();
    z.push(omega);
    let fd = central_differences(&z, len, 1e-6, |z, r| {
        hb.residual(&z[..len], z[len], r).unwrap()
    });
    let scale = max_abs(&fd);
    let mut err: f64 = 0.0;
    for i in 0..len {
        for j in 0..len {
            err = err.max((fd[(i, j)] - jac[(i, j)]).abs());
        }
        err = err.max((fd[(i, len)] - jac_w[i]).abs());
    }
    assert!(err <= 1e-7 * scale, "max error {err:e}, scale {scale:e}");
}

#[test]
fn bad_inputs_are_typed_errors() {
    let layout = HarmonicLayout::new(2, 2).unwrap();
    let mut aft = Aft::with_default_samples(layout).unwrap();
    let mut out = vec![0.0; layout.len()];
    // Force on the wrong number of dofs.
    assert!(matches!(
        aft.forces(&cube(), &vec![0.0; layout.len()], 1.0, &mut out),
        Err(HbmError::Dimension { .. })
    ));
    // Wrong coefficient length.
    let force = coupled_velocity_force();
    assert!(matches!(
        aft.forces(&force, &[0.0; 3], 1.0, &mut out),
        Err(HbmError::Dimension { .. })
    ));
    // Non-finite force output is reported with its sample.
    let nan = FnForce::new(
        2,
        vec![],
        false,
        |_x: &[f64], _v: &[f64], f: &mut [f64], _j: Option<LocalJacobian<'_>>| {
            f[1] = f64::NAN;
        },
    );
    assert!(matches!(
        aft.forces(&nan, &vec![0.0; layout.len()], 1.0, &mut out),
        Err(HbmError::NonFiniteForce { sample: 0 })
    ));
    // Pattern outside the dofs.
    let bad = FnForce::new(
        2,
        vec![(0, 5)],
        false,
        |_x: &[f64], _v: &[f64], _f: &mut [f64], _j: Option<LocalJacobian<'_>>| {},
    );
    assert!(matches!(
        aft.forces(&bad, &vec![0.0; layout.len()], 1.0, &mut out),
        Err(HbmError::PatternOutOfRange { .. })
    ));
}
