//! The Lyapunov exponents of a torus (`squeal_hbm::torus::lyapunov`) against the closed form of
//! two coupled Hopf normal forms (the system of tests/hbm/torus.rs):
//!
//! `z_a' = (α_a + i ω_a) z_a - (1 + i γ_a) |z_a|² z_a + (i κ_a - δ_a) |z_b|² z_a`, and the same
//! with `a ↔ b`. In polar form `z = r e^{iθ}` the radii obey
//! `r_a' = r_a (α_a - r_a² - δ_a r_b²)`, `r_b' = r_b (α_b - r_b² - δ_b r_a²)`, independent of
//! the angles, and the angles' rates depend on the radii only. On the torus
//! (`r_a² + δ_a r_b² = α_a`, `r_b² + δ_b r_a² = α_b`) the linearization is therefore block
//! triangular with constant blocks: the exponents are `0, 0` (the angles) and the eigenvalues
//! of `J_r = [[-2 r_a², -2 δ_a r_a r_b], [-2 δ_b r_a r_b, -2 r_b²]]` (real, as
//! `δ_a δ_b > 0`). Lyapunov exponents do not depend on the (bounded) change of coordinates,
//! so these are the exponents of the Cartesian system integrated here. With weak coupling
//! (`δ_a δ_b < 1`) both are negative: the torus attracts; with strong coupling
//! (`δ_a δ_b > 1`, `det J_r < 0`) one is positive: the torus is a saddle.

use squeal_hbm::HbmError;
use squeal_hbm::torus::lyapunov::{
    LyapunovOptions, TorusStability, TorusVariational, lyapunov_exponents,
};
use squeal_hbm::torus::transverse::{
    TorusTangents, TransverseOptions, tangent_defect, transverse_exponents,
};

#[derive(Clone, Copy)]
struct Coupled {
    alpha: [f64; 2],
    omega: [f64; 2],
    gamma: [f64; 2],
    kappa: [f64; 2],
    delta: [f64; 2],
}

impl Coupled {
    /// `(r_a², r_b²)` on the torus.
    fn radii2(&self) -> [f64; 2] {
        let det = 1.0 - self.delta[0] * self.delta[1];
        [
            (self.alpha[0] - self.delta[0] * self.alpha[1]) / det,
            (self.alpha[1] - self.delta[1] * self.alpha[0]) / det,
        ]
    }

    /// Both frequencies of the torus.
    fn frequencies(&self) -> [f64; 2] {
        let r = self.radii2();
        [
            self.omega[0] - self.gamma[0] * r[0] + self.kappa[0] * r[1],
            self.omega[1] - self.gamma[1] * r[1] + self.kappa[1] * r[0],
        ]
    }

    /// The nonzero exponents in closed form, largest first.
    fn exponents(&self) -> [f64; 2] {
        let r = self.radii2();
        let (a, d) = (-2.0 * r[0], -2.0 * r[1]);
        let bc = 4.0 * self.delta[0] * self.delta[1] * r[0] * r[1];
        let (m, s) = (0.5 * (a + d), (0.25 * (a - d) * (a - d) + bc).sqrt());
        [m + s, m - s]
    }

    /// The Jacobian of the Cartesian system `(a1, b1, a2, b2)` at `x`, row-major.
    fn jacobian(&self, x: &[f64; 4]) -> [[f64; 4]; 4] {
        let rho = [x[0] * x[0] + x[1] * x[1], x[2] * x[2] + x[3] * x[3]];
        let mut j = [[0.0; 4]; 4];
        for o in 0..2 {
            let other = 1 - o;
            let (i, k) = (2 * o, 2 * o + 1);
            let (a, b) = (x[i], x[k]);
            let cr = self.alpha[o] - rho[o] - self.delta[o] * rho[other];
            let ci = self.omega[o] - self.gamma[o] * rho[o] + self.kappa[o] * rho[other];
            for col in 0..4 {
                let drho = 2.0 * x[col];
                let (dcr, dci) = if col / 2 == o {
                    (-drho, -self.gamma[o] * drho)
                } else {
                    (-self.delta[o] * drho, self.kappa[o] * drho)
                };
                // a' = cr a - ci b, b' = ci a + cr b.
                j[i][col] = dcr * a - dci * b;
                j[k][col] = dci * a + dcr * b;
            }
            j[i][i] += cr;
            j[i][k] -= ci;
            j[k][i] += ci;
            j[k][k] += cr;
        }
        j
    }
}

/// The linearized flow along the closed-form torus `z_a = r_a e^{iθ1}`, `z_b = r_b e^{iθ2}`.
struct Along {
    sys: Coupled,
    jac: [[f64; 4]; 4],
}

impl TorusVariational for Along {
    fn dim(&self) -> usize {
        4
    }

    fn set_angles(&mut self, theta: [f64; 2]) -> Result<(), HbmError> {
        let r = self.sys.radii2().map(f64::sqrt);
        let x = [
            r[0] * theta[0].cos(),
            r[0] * theta[0].sin(),
            r[1] * theta[1].cos(),
            r[1] * theta[1].sin(),
        ];
        self.jac = self.sys.jacobian(&x);
        Ok(())
    }

    fn apply(&self, v: &[f64], out: &mut [f64]) {
        for (o, row) in out.iter_mut().zip(&self.jac) {
            *o = row.iter().zip(v).map(|(a, b)| a * b).sum();
        }
    }
}

impl TorusTangents for Along {
    fn tangents(&self, theta: [f64; 2], t1: &mut [f64], t2: &mut [f64]) -> Result<(), HbmError> {
        let r = self.sys.radii2().map(f64::sqrt);
        t1.copy_from_slice(&[-r[0] * theta[0].sin(), r[0] * theta[0].cos(), 0.0, 0.0]);
        t2.copy_from_slice(&[0.0, 0.0, -r[1] * theta[1].sin(), r[1] * theta[1].cos()]);
        Ok(())
    }
}

/// The transverse exponents (the tangents carried) against the
/// closed form; the error estimate must cover the actual error and the verdict must be right.
fn check_transverse(sys: Coupled, verdict: TorusStability) {
    let mut along = Along {
        sys,
        jac: [[0.0; 4]; 4],
    };
    let [lp, lm] = sys.exponents();
    let want = [lp.max(lm), lp.min(lm)];
    // The closed-form tangents solve the linearized equations: the defect is the central
    // difference's, O((ω dt)²) ~ 1e-5 relative.
    let d = tangent_defect(&mut along, sys.frequencies(), [0.3, 1.1]).unwrap();
    assert!(d[0] < 1e-5 && d[1] < 1e-5, "tangent defect {d:?}");
    // Only the carried way: the projected one (carry_tangents = false) erred by 4.3e-3 on the
    // weakly coupled torus with an estimate of 4e-13 (8.7e-6 on the saddle), measured
    // 2026-11-28: its bias is not in its estimate even on an exact torus (docs/verification.md).
    let carry = true;
    {
        let opts = TransverseOptions {
            carry_tangents: carry,
            ..TransverseOptions::default()
        };
        let s = transverse_exponents(&mut along, sys.frequencies(), &opts).unwrap();
        let err = (s.transverse() - want[0]).abs();
        eprintln!(
            "carry {carry}: transverse {:?} +- {:?} (tangent {:?}) over {} periods, closed form {want:?}: error {err:.2e}",
            s.exponents, s.errors, s.tangent, s.periods
        );
        // The record stops once |λ| > 2 e. Here the radii are constant along the torus, so
        // the finite-time part of the error (what e estimates) is ~1e-15 and RK4's own error
        // (h ≈ 0.2: measured 9.2e-6 and 4.8e-5, of the order of (h λ)⁵/(120 h)) is all there
        // is: e leaves it out, as the module docs say; 1e-4 covers it.
        assert!(
            err <= s.uncertainty() + 1e-4,
            "error {err:.2e} over the estimate {:.2e} + 1e-4",
            s.uncertainty()
        );
        // The run stops at |λ| > 2 e, so an honest e leaves at most half of |λ| as error.
        assert!(err < 0.5 * want[0].abs(), "error {err:.2e}");
        assert_eq!(s.stability(), verdict);
        assert_eq!(s.exponents.len(), 2);
        assert_eq!(s.tangent.len(), if carry { 2 } else { 0 });
    }
}

fn run(sys: Coupled) -> (Vec<f64>, f64, TorusStability, f64, f64) {
    let mut along = Along {
        sys,
        jac: [[0.0; 4]; 4],
    };
    let opts = LyapunovOptions::default();
    let s = lyapunov_exponents(&mut along, sys.frequencies(), &opts).unwrap();
    eprintln!(
        "exponents {:?} (second half {:?}), transverse {:.6}, uncertainty {:.2e}, closed form {:?}, time {:.0}, step {:.3}",
        s.exponents,
        s.second_half,
        s.transverse(),
        s.uncertainty(),
        sys.exponents(),
        s.time,
        s.step
    );
    (
        s.exponents.clone(),
        s.transverse(),
        s.stability(),
        s.uncertainty(),
        s.step_error(),
    )
}

/// The measured exponents against the closed form: `(0, 0, λ+, λ-)` sorted, largest first.
fn check(sys: Coupled, verdict: TorusStability) {
    let (got, transverse, stability, uncertainty, s_step) = run(sys);
    let [lp, lm] = sys.exponents();
    let mut want = vec![0.0, 0.0, lp, lm];
    want.sort_by(|a, b| b.total_cmp(a));
    let err = got
        .iter()
        .zip(&want)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    // Finite-time exponents err by O(1/T): the bounded oscillation of log |v| along the torus
    // over T ≈ 2500 time units, a few 1e-4 here; RK4 at h ≈ 0.2 adds ~(h ρ)^4 / T, far less.
    assert!(
        err < 2e-3,
        "exponents {got:?} vs closed form {want:?}: {err:.2e}"
    );
    // The finite-time uncertainty leaves out RK4's error (measured here: 1.7e-5 and 1.3e-4 at
    // h ≈ 0.2, about (h λ)⁵/(120 h)); with RK4's bound added it covers the actual error.
    assert!(
        uncertainty + s_step >= err,
        "uncertainty {uncertainty:.2e} + step error {s_step:.2e} under the error {err:.2e}"
    );
    assert!((transverse - lp.max(lm)).abs() < 2e-3);
    assert_eq!(stability, verdict);
}

#[test]
fn weakly_coupled_torus_attracts() {
    let sys = Coupled {
        alpha: [1.0, 0.8],
        omega: [1.0, 0.6180339887498949],
        gamma: [0.3, -0.2],
        kappa: [0.15, 0.25],
        delta: [0.2, 0.1],
    };
    check(sys, TorusStability::Attracting);
    check_transverse(sys, TorusStability::Attracting);
}

#[test]
fn strongly_coupled_torus_is_a_saddle() {
    let sys = Coupled {
        alpha: [0.8, 0.8],
        omega: [1.0, 0.6180339887498949],
        gamma: [0.3, -0.2],
        kappa: [0.15, 0.25],
        delta: [2.0, 2.0],
    };
    assert!(sys.radii2().iter().all(|r| *r > 0.0));
    check(sys, TorusStability::Unstable);
    check_transverse(sys, TorusStability::Unstable);
}

#[test]
fn bad_options_are_errors() {
    let sys = Coupled {
        alpha: [1.0, 0.8],
        omega: [1.0, 0.6],
        gamma: [0.0; 2],
        kappa: [0.0; 2],
        delta: [0.2, 0.1],
    };
    let mut along = Along {
        sys,
        jac: [[0.0; 4]; 4],
    };
    let mut o = LyapunovOptions {
        exponents: 2,
        ..LyapunovOptions::default()
    };
    assert!(lyapunov_exponents(&mut along, [1.0, 0.6], &o).is_err());
    o.exponents = 5;
    assert!(lyapunov_exponents(&mut along, [1.0, 0.6], &o).is_err());
    assert!(lyapunov_exponents(&mut along, [f64::NAN, 0.6], &LyapunovOptions::default()).is_err());
}
