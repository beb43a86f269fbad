//! Shooting ([`squeal_ode::shoot`]) on two systems whose limit cycle is known to more digits
//! than the test asks: the Hopf normal form (a circle of radius `√μ`, period `2π/ω`, Floquet
//! multipliers `1` and `e^{-2μT}`, all exact) and the van der Pol oscillator at `μ = 1`, whose
//! period is published to 29 digits.

use super::common;

use common::VanDerPol;
use faer::MatMut;
use squeal_ode::{Atol, BdfOptions, OdeSystem, ShootingOptions, shoot, variational_monodromy};
use std::f64::consts::PI;

/// `z' = (μ + iω) z - |z|² z` in real form: the circle `|z| = √μ`, run at angular speed ω.
struct Hopf {
    mu: f64,
    omega: f64,
}

impl OdeSystem for Hopf {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let r2 = y[0] * y[0] + y[1] * y[1];
        dy[0] = (self.mu - r2) * y[0] - self.omega * y[1];
        dy[1] = self.omega * y[0] + (self.mu - r2) * y[1];
    }
    fn jacobian(&self, _t: f64, y: &[f64], mut jac: MatMut<'_, f64>) {
        let (x, v) = (y[0], y[1]);
        let r2 = x * x + v * v;
        jac[(0, 0)] = self.mu - r2 - 2.0 * x * x;
        jac[(0, 1)] = -self.omega - 2.0 * x * v;
        jac[(1, 0)] = self.omega - 2.0 * x * v;
        jac[(1, 1)] = self.mu - r2 - 2.0 * v * v;
    }
}

fn options(rtol: f64) -> ShootingOptions {
    {
        let mut o = ShootingOptions::default();
        o.bdf = {
            let mut o = BdfOptions::default();
            o.rtol = rtol;
            o.atol = Atol::Scalar(rtol * 1e-2);
            o
        };
        o.tol = 1e-12;
        o
    }
}

/// The monodromy for Newton: the variational equations at a looser tolerance (it only steers).
fn loose(rtol: f64) -> BdfOptions {
    {
        let mut o = BdfOptions::default();
        o.rtol = rtol;
        o.atol = Atol::Scalar(rtol * 1e-2);
        o
    }
}

#[test]
fn the_hopf_normal_forms_cycle_is_its_circle_to_1e_10() {
    let sys = Hopf {
        mu: 0.25,
        omega: 3.0,
    };
    let (radius, period) = (0.5, 2.0 * PI / 3.0);
    let mono = loose(1e-8);
    let orbit = shoot(&sys, &[0.7, -0.2], 2.3, &options(1e-13), &mut |x, t, _| {
        variational_monodromy(&sys, x, t, &mono)
    })
    .unwrap();
    // The radius and the period are exact numbers; BDF at rtol 1e-13 over one period gives
    // them to about 1e-12 (measured below), so 1e-10 is the claim with room.
    let r = orbit.x0[0].hypot(orbit.x0[1]);
    assert!((r - radius).abs() < 1e-10, "radius {r}");
    assert!(
        (orbit.period / period - 1.0).abs() < 1e-10,
        "period {} against {period}",
        orbit.period
    );
    // Every sample of the trajectory is on the circle: its first harmonic has the radius as
    // amplitude and nothing else is left (the mean and the higher harmonics vanish).
    let traj = &orbit.flow.trajectory;
    let (c, s) = traj.harmonic(1, 0);
    assert!(
        (c.hypot(s) - radius).abs() < 1e-10,
        "first harmonic {c}, {s}"
    );
    for k in 2..=traj.harmonics() {
        let (c, s) = traj.harmonic(k, 0);
        assert!(c.hypot(s) < 1e-10, "harmonic {k}: {c}, {s}");
    }
    assert!(orbit.residual <= 1e-12, "residual {}", orbit.residual);
    // The Floquet multipliers of the converged orbit: 1 (the phase) and e^{-2μT} (the radius
    // relaxes at rate 2μ), to the accuracy of the variational equations at rtol 1e-11.
    let m = variational_monodromy(&sys, &orbit.x0, orbit.period, &loose(1e-11)).unwrap();
    let evd = m.eigen().unwrap();
    let mut rho: Vec<f64> = (0..2).map(|i| evd.S()[i].re).collect();
    rho.sort_by(f64::total_cmp);
    let contraction = (-2.0 * sys.mu * period).exp();
    eprintln!(
        "Hopf: radius {:e} off, period {:e} off, residual {:e}, multipliers {:e} and {:e} off",
        r - radius,
        orbit.period / period - 1.0,
        orbit.residual,
        rho[1] - 1.0,
        rho[0] - contraction
    );
    assert!((rho[1] - 1.0).abs() < 1e-8, "trivial multiplier {}", rho[1]);
    assert!(
        (rho[0] - contraction).abs() < 1e-8,
        "{} against {contraction}",
        rho[0]
    );
}

/// The period of the van der Pol cycle at μ = 1, published to 29 digits
/// (6.6632868593231301896996820305), here to the f64 nearest.
const VDP_PERIOD: f64 = 6.663_286_859_323_13;
/// Its largest `x` (published to 15 digits).
const VDP_AMPLITUDE: f64 = 2.008_619_860_874_84;

#[test]
fn the_van_der_pol_period_is_the_published_one_to_1e_10() {
    let sys = VanDerPol { mu: 1.0 };
    let mono = loose(1e-8);
    let orbit = shoot(&sys, &[2.0, 0.0], 6.5, &options(1e-13), &mut |x, t, _| {
        variational_monodromy(&sys, x, t, &mono)
    })
    .unwrap();
    let rel = orbit.period / VDP_PERIOD - 1.0;
    assert!(rel.abs() < 1e-10, "period {} ({rel:e} off)", orbit.period);
    // The phase condition keeps the start where the flow crossed it first: x' = 0, the
    // maximum of x, whose published value (Hairer, Nørsett & Wanner I, Sec. II.10, as in
    // `stiff`'s test) is 2.00861986087484 to the 15 digits given.
    assert!(orbit.x0[1].abs() < 1e-10, "start {:?}", orbit.x0);
    let amplitude = orbit.x0[0] - VDP_AMPLITUDE;
    assert!(
        amplitude.abs() < 1e-10,
        "max x {} ({amplitude:e} off)",
        orbit.x0[0]
    );
    // Chord iterations on the start's monodromy (it is not recomputed while the residual
    // falls fast enough): the start is 0.16 off the period, the residual falls by 3.3x to
    // 65x per step (measured; 42x once near) down to 1.4e-13. Each step must at least halve it.
    assert!(
        orbit.residuals.windows(2).all(|w| w[1] < 0.5 * w[0]),
        "{:?}",
        orbit.residuals
    );
    eprintln!(
        "van der Pol: period {} ({rel:e} off), max x {amplitude:e} off, residuals {:?}",
        orbit.period, orbit.residuals
    );
}
