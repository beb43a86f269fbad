//! The 2-dof friction oscillator of Hoffmann et al. (2002) on a belt at low speed, with exact
//! Coulomb friction: its constants, the right-hand side of each phase (sliding with the
//! friction's sign, stuck to the belt) and the switching functions of the event-driven
//! integration that `dlft_two_dof.rs` and `dlft_floquet.rs` take as their reference (the
//! physics is in `dlft_two_dof.rs`'s module doc).

use faer::Mat;
use squeal_hbm::*;

pub const M: f64 = 1.0;
pub const C: f64 = 2.0;
pub const K11: f64 = 1.0e4;
pub const K12: f64 = -2.0e3;
pub const K22: f64 = 6.0e3;
pub const KC: f64 = 5.0e3;
pub const N0: f64 = 10.0;
pub const MU: f64 = 0.6;
pub const V: f64 = 0.01;

/// `N(y)`.
pub fn normal(y: f64) -> f64 {
    N0 - KC * y
}

/// The stuck force on `x` (`x' = V`, `x'' = 0`): `c V + K11 x + K12 y`.
pub fn stuck_force(s: &[f64; 4]) -> f64 {
    C * V + K11 * s[0] + K12 * s[1]
}

/// Right-hand side in phase `stick` (sliding: `sign` the friction's sign).
pub fn rhs(s: &[f64; 4], stick: bool, sign: f64) -> [f64; 4] {
    let fy = -(C * s[3] + K12 * s[0] + (K22 + KC) * s[1]) / M;
    if stick {
        return [V, s[3], 0.0, fy];
    }
    let phi = sign * MU * normal(s[1]);
    let fx = (phi - C * s[2] - K11 * s[0] - K12 * s[1]) / M;
    [s[2], s[3], fx, fy]
}

/// One classical Runge–Kutta step of order 4 in the phase `stick` (`sign`: the friction's sign).
pub fn rk4(s: &[f64; 4], dt: f64, stick: bool, sign: f64) -> [f64; 4] {
    let add = |a: &[f64; 4], k: &[f64; 4], h: f64| std::array::from_fn(|i| a[i] + h * k[i]);
    let k1 = rhs(s, stick, sign);
    let k2 = rhs(&add(s, &k1, dt / 2.0), stick, sign);
    let k3 = rhs(&add(s, &k2, dt / 2.0), stick, sign);
    let k4 = rhs(&add(s, &k3, dt), stick, sign);
    std::array::from_fn(|i| s[i] + dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}

/// The switching function of the current phase: stuck, `μ_s N - |φ_stuck|` (switch where it
/// turns negative); sliding, `sign γ` times `γ` (switch where it turns negative).
pub fn event(s: &[f64; 4], stick: bool, sign: f64) -> f64 {
    if stick {
        MU * normal(s[1]) - stuck_force(s).abs()
    } else {
        sign * (V - s[2])
    }
}

/// The stiffness of the sliding system without friction: the springs and the contact's `k_c`.
pub fn stiffness() -> Mat<f64> {
    Mat::from_fn(2, 2, |i, j| match (i, j) {
        (0, 0) => K11,
        (1, 1) => K22 + KC,
        _ => K12,
    })
}

/// The oscillator's harmonic balance with exact stick–slip (DLFT) at `h` harmonics, penalty
/// `epsilon`: the normal load `N0 - k_c y` as a penalty on the belt, friction on `x`.
pub fn balance(h: usize, epsilon: f64) -> StickSlipBalance<MckStiffness, impl NonlinearForce> {
    let layout = HarmonicLayout::new(2, h).unwrap();
    let m = Mat::from_fn(2, 2, |i, j| if i == j { M } else { 0.0 });
    let c = Mat::from_fn(2, 2, |i, j| if i == j { C } else { 0.0 });
    let k = stiffness();
    let linear = MckStiffness::new(m.as_ref(), c.as_ref(), k.as_ref()).unwrap();
    let none = FnForce::new(
        2,
        vec![],
        false,
        |_: &[f64], _: &[f64], _: &mut [f64], _: Option<LocalJacobian<'_>>| {},
    );
    let hb = HarmonicBalance::new(layout, linear, none, vec![0.0; layout.len()], None).unwrap();
    let contact = FrictionContact {
        direction: vec![(0, -1.0)],
        sliding_speed: V,
        normal: NormalLoad::Penalty {
            normal: vec![(1, -1.0)],
            offset: N0 / KC,
            k_linear: KC,
            k_cubic: 0.0,
        },
        mu: MU,
        static_ratio: 1.0,
        epsilon,
        contact_mass: M,
    };
    StickSlipBalance::new(hb, vec![contact], None).unwrap()
}
