//! The estimates against closed forms: the baffled circular piston (on-axis pressure, radiated
//! power, convergence with the mesh), the pulsating sphere (ERP against the true power, the
//! monopole sum against the exact field) and the A-weighting table of IEC 61672-1.
//!
//! `cargo test --release -p squeal-acoustics --test acoustics closed_forms:: -- --nocapture` prints the
//! measured values recorded in docs/verification.md.

use super::common;

use common::{Tri6Surface, bessel_j1, disc, sphere};
use squeal_acoustics::{
    Air, Complex64, FaceRule, Facing, RadiatingSurface, Velocity, a_weighting_db, erp, monopoles,
    rayleigh,
};
use std::f64::consts::PI;

const A: f64 = 0.1;
const V0: f64 = 1e-3;

fn surface(s: &Tri6Surface, rule: &FaceRule) -> RadiatingSurface {
    RadiatingSurface::new(&s.nodes, &s.faces, rule).unwrap()
}

/// Uniform normal velocity `V0` at every face node.
fn uniform(s: &RadiatingSurface) -> Vec<Complex64> {
    s.normal_velocity(Velocity::FaceNodes(&vec![
        Complex64::new(V0, 0.0);
        s.faces.len()
    ]))
    .unwrap()
}

/// On the axis of a baffled piston, `p(z) = ρ c v (e^{−ikz} − e^{−ik√(z²+a²)})` (the Rayleigh
/// integral in closed form; its modulus is `2 ρ c v |sin(k/2 (√(z²+a²) − z))|`).
fn piston_on_axis(air: &Air, k: f64, z: f64) -> Complex64 {
    let ra = (z * z + A * A).sqrt();
    let e = |r: f64| Complex64::new((k * r).cos(), -(k * r).sin());
    air.impedance() * V0 * (e(z) - e(ra))
}

fn piston_error(rings: usize, rule: &FaceRule, ka: f64, z: f64) -> f64 {
    let air = Air::default();
    let k = ka / A;
    let omega = k * air.speed_of_sound;
    let s = surface(&disc(A, rings), rule);
    let vn = uniform(&s);
    let p = rayleigh(&air, &s, &vn, omega, [0.0, 0.0, z], Facing::All).unwrap();
    (p - piston_on_axis(&air, k, z)).norm() / (2.0 * air.impedance() * V0)
}

/// The Rayleigh integral of a piston of 24 rings (3,456 faces, degree-4 rule) on its axis, near
/// field (z = a/4 .. 2a, where the pressure has zeros and maxima at ka = 8) and far field
/// (z = 20a, 100a), against the closed form. Error relative to the largest on-axis amplitude
/// 2ρcv: below 1e-6. Reason: the discretization error, O(h⁴) by the convergence test below,
/// is at most 3e-7 on this mesh (ka = 8, z = a/4; printed) and smaller further away; a wrong
/// sign, factor 2π or phase convention gives O(1).
#[test]
fn piston_on_axis_near_and_far() {
    let rule = FaceRule::tri6();
    for ka in [1.0, 4.0, 8.0] {
        for z in [0.25 * A, 0.5 * A, A, 2.0 * A, 20.0 * A, 100.0 * A] {
            let e = piston_error(24, &rule, ka, z);
            println!(
                "piston ka {ka} z/a {:.2}: error / (2 rho c v) = {e:.2e}",
                z / A
            );
            assert!(e < 1e-6, "ka {ka} z/a {}: {e:e}", z / A);
        }
    }
}

/// The Rayleigh integral's error with the face size at z = a/2, ka = 4: pistons of 2, 4, 8,
/// 16 and 32 rings (h ∝ 1/rings). The measured order of convergence between the two finest
/// meshes must be at least 3.5. Reason: the geometry of the quadratic faces is exact inside
/// the disc and O(h³) on its rim (O(h⁴) in area), and the degree-4 rule integrates the smooth
/// integrand to O(h⁴): the orders measured are 1.9, 3.2, 3.6, 3.9 (printed).
#[test]
fn rayleigh_converges_with_the_faces() {
    let rule = FaceRule::tri6();
    let mut last = None;
    let mut rates = Vec::new();
    for rings in [2, 4, 8, 16, 32] {
        let e = piston_error(rings, &rule, 4.0, 0.5 * A);
        if let Some(prev) = last {
            rates.push(f64::log2(prev / e));
        }
        println!(
            "rings {rings:2} ({:5} faces): error {e:.3e}{}",
            disc(A, rings).face_count(),
            rates
                .last()
                .map_or(String::new(), |r| format!(", order {r:.2}"))
        );
        last = Some(e);
    }
    let r = *rates.last().unwrap();
    assert!(r > 3.5, "measured order {r}");
}

/// Radiated power of the baffled piston, `W = ½ v² ρ c π a² (1 − J1(2ka)/(ka))`, against the
/// far-field intensity `|p|²/(2ρc)` of the Rayleigh integral integrated over a hemisphere of
/// radius 1000a (32 Gauss–Legendre points in cos θ, 16 trapezoid points in φ, both spectrally
/// accurate for this smooth directivity). Tolerance 2e-6 relative: the piston of 12 rings has a
/// pressure error of O(1e-6) (convergence test), the finite radius leaves O((a/r)²) = 1e-6 in
/// the power; measured ≤ 2.3e-7 (printed). Also shows ERP = ½ ρ c v² π a² against W: the
/// piston's radiation efficiency 1 − J1(2ka)/(ka) is 0.12 at ka = 0.5 (ERP 8.3 times too
/// high) and overshoots 1 near ka = 2 (ERP 3% low): ERP is not a strict bound.
#[test]
fn piston_power_on_a_hemisphere() {
    let air = Air::default();
    let s = surface(&disc(A, 12), &FaceRule::tri6());
    let vn = uniform(&s);
    let r = 1000.0 * A;
    let (ct, wt) = squeal_acoustics::rule::gauss_legendre_01(32).unwrap();
    let nphi = 16;
    for ka in [0.5, 2.0, 5.0] {
        let k = ka / A;
        let omega = k * air.speed_of_sound;
        let mut w = 0.0;
        for (c, wc) in ct.iter().zip(&wt) {
            let st = (1.0 - c * c).sqrt();
            for j in 0..nphi {
                let phi = 2.0 * PI * j as f64 / nphi as f64;
                let x = [r * st * phi.cos(), r * st * phi.sin(), r * c];
                let p = rayleigh(&air, &s, &vn, omega, x, Facing::All).unwrap();
                w += p.norm_sqr() / (2.0 * air.impedance()) * wc * (2.0 * PI / nphi as f64) * r * r;
            }
        }
        let exact = 0.5 * V0 * V0 * air.impedance() * PI * A * A * (1.0 - bessel_j1(2.0 * ka) / ka);
        let e = erp(&air, &s, &vn);
        println!(
            "piston ka {ka}: W hemisphere {w:.6e}, closed form {exact:.6e} (rel {:.1e}); ERP / W = {:.4}",
            (w - exact).abs() / exact,
            e / exact
        );
        assert!((w - exact).abs() < 2e-6 * exact, "ka {ka}: {w} vs {exact}");
        // ERP is σ = 1: above the true power, by 1/(1 − J1(2ka)/ka).
        let ratio = 1.0 / (1.0 - bessel_j1(2.0 * ka) / ka);
        assert!((e / exact - ratio).abs() < 1e-4 * ratio);
    }
}

/// On a flat baffled piston in the far field the monopole sum (free field, 4π) is half the
/// Rayleigh integral (baffled, 2π). At z = 100a, ka = 1 and 4, 12 rings: the ratio is 1/2
/// within 1e-3. Reason: lumping each face into its centroid errs by O((k h)²) (k h ≤ 0.4
/// here: ~1e-3 at ka = 4) and O(h²/z²) in distance.
#[test]
fn monopole_sum_is_half_the_baffled_piston() {
    let air = Air::default();
    let s = surface(&disc(A, 12), &FaceRule::tri6());
    let vn = uniform(&s);
    for ka in [1.0, 4.0] {
        let omega = ka / A * air.speed_of_sound;
        let x = [0.0, 0.0, 100.0 * A];
        let pr = rayleigh(&air, &s, &vn, omega, x, Facing::All).unwrap();
        let pm = monopoles(&air, &s, &vn, omega, x).unwrap();
        let ratio = pm / pr;
        println!("piston ka {ka}: monopole / Rayleigh = {ratio:.6}");
        assert!((ratio - 0.5).norm() < 1e-3, "ka {ka}: {ratio}");
    }
}

/// The pulsating sphere (radius a, uniform radial velocity v): true power
/// `W = ½ ρ c v² 4π a² (ka)²/(1 + (ka)²)`, ERP `½ ρ c v² 4π a²`: ERP / W = (1 + (ka)²)/(ka)²
/// (101 at ka = 0.1, 2 at ka = 1). Tolerance 1e-5 relative: the area of the 1,280-face
/// icosphere of 6-node triangles (printed).
#[test]
fn erp_overestimates_the_pulsating_sphere() {
    let air = Air::default();
    let s = surface(&sphere(A, 8), &FaceRule::tri6());
    let area_err = (s.area() - 4.0 * PI * A * A).abs() / (4.0 * PI * A * A);
    println!(
        "sphere of {} faces: area error {area_err:.1e}",
        s.face_count()
    );
    let vn = uniform(&s);
    for ka in [0.1, 1.0, 3.0] {
        let sigma = ka * ka / (1.0 + ka * ka);
        let w = 0.5 * air.impedance() * V0 * V0 * 4.0 * PI * A * A * sigma;
        let e = erp(&air, &s, &vn);
        println!(
            "sphere ka {ka}: ERP / W = {:.4} (1/sigma = {:.4})",
            e / w,
            1.0 / sigma
        );
        assert!((e / w * sigma - 1.0).abs() < 1e-5);
    }
}

/// The monopole sum of a pulsating sphere against the exact field
/// `p(r) = ρ c v (a/r) (ika/(1 + ika)) e^{−ik(r−a)}`. The sum over the sphere of free-field
/// sources is, in the limit of small faces, `ρ c v (a/r) i sin(ka) e^{−ikr}` (the uniform
/// monopole layer): at r = 10a it must match that within 1e-3. Reason: lumping each face into
/// its centroid errs by O((kh)²): measured 2.4e-6 at ka = 0.1 and 3.4e-4 at ka = 1 (1,280
/// faces), the factor 100 of (kh)². Its ratio to the exact field,
/// |(1 + ika) sin(ka)/(ka)|, is 1.003 at ka = 0.1 (a compact source: the monopole sum is
/// right) and 1.19 at ka = 1 (it neglects the sphere's own scattering: +1.5 dB).
#[test]
fn monopole_sum_of_the_pulsating_sphere() {
    let air = Air::default();
    let s = surface(&sphere(A, 8), &FaceRule::tri6());
    let vn = uniform(&s);
    let r = 10.0 * A;
    let x = [0.3 * r, -0.4 * r, (1.0f64 - 0.25).sqrt() * r];
    for ka in [0.1, 1.0] {
        let k = ka / A;
        let omega = k * air.speed_of_sound;
        let pm = monopoles(&air, &s, &vn, omega, x).unwrap();
        let e = |t: f64| Complex64::new(t.cos(), -t.sin());
        let layer = air.impedance() * V0 * (A / r) * Complex64::new(0.0, ka.sin()) * e(k * r);
        let exact = air.impedance() * V0 * (A / r) * Complex64::new(0.0, ka)
            / Complex64::new(1.0, ka)
            * e(k * (r - A));
        let to_layer = (pm - layer).norm() / layer.norm();
        println!(
            "sphere ka {ka}: |monopole sum - layer| / |layer| = {to_layer:.1e}, |monopole| / |exact| = {:.4}",
            pm.norm() / exact.norm()
        );
        assert!(to_layer < 1e-3, "ka {ka}: {to_layer:e}");
        let expected = (1.0 + ka * ka).sqrt() * ka.sin() / ka;
        assert!((pm.norm() / exact.norm() - expected).abs() < 1e-3 * expected);
    }
}

/// IEC 61672-1:2013 Table 3, A-weighting at the base-ten exact frequencies 1000·10^{n/10}
/// Hz, n = −20..13 (10 Hz to 20 kHz): the table's values are the formula's rounded to 0.1 dB,
/// so they must agree within 0.05 dB (+1e-3 for the constants' own rounding). 1 kHz is 0 dB
/// within 0.01 (A1000 = −2.000 is given to 3 decimals); 100 Hz −19.1, 10 kHz −2.5.
#[test]
fn a_weighting_matches_iec_61672() {
    let table = [
        -70.4, -63.4, -56.7, -50.5, -44.7, -39.4, -34.6, -30.2, -26.2, -22.5, -19.1, -16.1, -13.4,
        -10.9, -8.6, -6.6, -4.8, -3.2, -1.9, -0.8, 0.0, 0.6, 1.0, 1.2, 1.3, 1.2, 1.0, 0.5, -0.1,
        -1.1, -2.5, -4.3, -6.6, -9.3,
    ];
    for (i, t) in table.iter().enumerate() {
        let f = 1000.0 * 10f64.powf((i as f64 - 20.0) / 10.0);
        let a = a_weighting_db(f);
        assert!((a - t).abs() <= 0.051, "{f} Hz: {a} vs {t}");
    }
    assert!(a_weighting_db(1000.0).abs() < 0.01);
    assert!((a_weighting_db(100.0) + 19.1).abs() <= 0.051);
    assert!((a_weighting_db(10_000.0) + 2.5).abs() <= 0.051);
}
