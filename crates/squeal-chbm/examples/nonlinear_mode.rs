//! The complex nonlinear mode of the 2-dof friction oscillator (extended periodic motion
//! concept, Krack 2015), and its limit cycle where the modal damping vanishes.
//!
//! Theory. The oscillator of `friction_oscillator.rs`: `M = I`, `C = c I` (`c = 20 s⁻¹`),
//! `K = [[1e6, 1e5], [1e5, 1e6]]`, one pair with the cubic penalty `F_n = k_l δ + k_nl δ³`
//! (`δ = x1 - g0`, preloaded) and Coulomb friction `F_t = μ F_n` along `-e0`. Above the Hopf
//! point μ0 one mode grows. The EPMC asks, for every amplitude `a` of that mode, which
//! *periodic* motion it would have if a viscous damping `-2ζω M x'` were added:
//!
//! `x'' + (c - 2ζω) x' + K x + F_nl(x) = 0`,  `x` periodic of frequency ω, `|q_1| = a`.
//!
//! *Linear limit.* Linearized at the equilibrium (`K̃ = K + K_c`, `K_c` the contact's tangent
//! with friction's `-μ k_t` in `K̃[0][1]`), a motion `Re(φ e^{iωt})` needs
//! `[K̃ + iω(c - 2ζω) - ω²] φ = 0`: `κ = ω² + 2iζω² - iωc` is an eigenvalue of `K̃`. The brake's
//! eigenvalues `λ` solve `λ² + cλ + κ = 0` with the same `κ`, so `κ = -λ(λ + c)` and
//! **exactly** `ω² = Re κ`, `ζ = (Im κ + cω) / (2ω²)`: with mass-proportional damping the
//! EPMC's linear limit is the eigenvalue itself, re-expressed. (For `μ > μ0`, `Re λ > 0`
//! gives `ζ < 0`: negative damping, the squeal mode grows.)
//!
//! *Small amplitude.* The cubic contact term adds, through the describing function of the
//! fundamental, a stiffness `3/4 k_nl |δ_1|²`-like hardening and, via friction's coupling,
//! a damping change `ζ2 a²` (the normal form's `Re c1`); with these stiffnesses a stiffer
//! contact raises the flutter threshold, so ζ grows with `a` (`ζ2 > 0`, supercritical,
//! `l1 < 0`).
//!
//! *Limit cycle.* Where `ζ(a) = 0` the artificial term vanishes and the EPMC's motion is an
//! exact periodic solution of the oscillator's equations: the limit cycle that CHBM finds at
//! the same μ with the same harmonics. The test checks all three: the linear limit against
//! `κ = -λ(λ + c)`, the zero-damping point against CHBM (frequency and amplitude), and the
//! sign of `ζ2` against the Lyapunov coefficient.
//!
//! Run: `cargo run --release -p squeal-chbm --example nonlinear_mode`.

use faer::Mat;
use squeal_chbm::nlmode::{NlModeOptions, NonlinearMode, log_spaced};
use squeal_chbm::{Contact, FrictionSystem, SystemError};

/// The damping rate `c` (s⁻¹) of `C = c I`.
pub const C: f64 = 20.0;

/// The oscillator: `M`, `C`, `K` and its one contact pair.
pub fn system() -> Result<FrictionSystem, SystemError> {
    let m = Mat::<f64>::identity(2, 2);
    let c = Mat::from_fn(2, 2, |i, j| if i == j { C } else { 0.0 });
    let k = Mat::from_fn(2, 2, |i, j| [[1.0e6, 1.0e5], [1.0e5, 1.0e6]][i][j]);
    let pair = Contact::penalty_coulomb(&[(1, 1.0)], &[(0, -1.0)], 3.0e5, 7.5e11);
    FrictionSystem::builder(m, c, k)
        .contact(pair.initial_gap(-2.0e-4))
        .build()
}

/// The nonlinear mode at `mu` over `amplitudes` (fractions of the opening amplitude).
pub fn run(
    system: &FrictionSystem,
    mu: f64,
    amplitudes: Vec<f64>,
) -> Result<NonlinearMode, SystemError> {
    let opts = {
        let mut o = NlModeOptions::default();
        o.amplitudes = amplitudes;
        o
    };
    system.nonlinear_mode(mu, &opts)
}

#[allow(dead_code)]
fn main() -> Result<(), SystemError> {
    let system = system()?;
    let mu0 = system.hopf()?.mu0;
    let mode = run(&system, 1.01 * mu0, log_spaced(1e-3, 1.0, 25))?;
    println!(
        "mu = 1.01 mu0 = {:.8}; linear limit: f = {:.6} Hz, zeta = {:.6e}",
        1.01 * mu0,
        mode.linear.omega / std::f64::consts::TAU,
        mode.linear.zeta
    );
    println!(
        "{:>12} {:>14} {:>14} {:>10} {:>5}",
        "a", "f (Hz)", "zeta", "residual", "iter"
    );
    for p in &mode.points {
        println!(
            "{:12.4e} {:14.8} {:14.6e} {:10.2e} {:5}",
            p.a,
            p.omega / std::f64::consts::TAU,
            p.zeta,
            p.residual,
            p.iterations
        );
    }
    for c in &mode.cycles {
        println!(
            "limit cycle: a = {:.6e}, f = {:.8} Hz ({})",
            c.point.a,
            c.point.omega / std::f64::consts::TAU,
            if c.stable() { "stable" } else { "unstable" }
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::c64;
    use squeal_brake::criticality::Criticality;
    use squeal_chbm::Outcome;

    #[test]
    fn the_linear_limit_is_the_eigenvalue() {
        // At a = 1e-5 of the opening amplitude the cubic term's share of (ω, ζ) is ~1e-12
        // relative (it goes with a²: 2e-7 in ω and 4e-7 in ζ at 1e-2, `main`'s table). LM
        // stops at 1e-10 of the scaled residual, the harmonics' rows scaled by the motion's
        // own force: ζ enters those rows with a slope of about 2, so ζ is met to ~1e-10
        // absolute and ω to ~1e-10 relative. The reference κ = -λ(λ + c) is exact (module
        // docs) and λ comes from the dense eigenvalues of the linearized system.
        let system = system().unwrap();
        let mu0 = system.hopf().unwrap().mu0;
        let mode = run(&system, 1.01 * mu0, vec![1e-5, 2e-5]).unwrap();
        let l = mode.lambda;
        let kappa = -(l * (l + c64::new(C, 0.0)));
        let omega = kappa.re.sqrt();
        let zeta = (kappa.im + C * omega) / (2.0 * omega * omega);
        // The dense linear mode (the continuation's start) against κ: round-off.
        assert!((mode.linear.omega / omega - 1.0).abs() < 1e-12);
        assert!((mode.linear.zeta - zeta).abs() < 1e-12);
        for p in &mode.points {
            assert!(
                (p.omega / omega - 1.0).abs() < 1e-8,
                "{} vs {omega}",
                p.omega
            );
            assert!((p.zeta - zeta).abs() < 1e-9, "{} vs {zeta}", p.zeta);
        }
    }

    #[test]
    fn the_zero_damping_point_is_the_chbm_cycle_and_the_criticality_is_l1s() {
        // The EPMC at ζ = 0 and CHBM solve the same harmonic balance equations (3 harmonics,
        // the same AFT samples) to 1e-10 and 1e-9 of the force scale: the frequencies agree
        // to far better than 1e-6, and so does the first harmonic of the normal dof.
        let system = system().unwrap();
        let mu0 = system.hopf().unwrap().mu0;
        let mu = 1.01 * mu0;
        // Up to the opening amplitude: the stable cycle is the one root of ζ there.
        let mode = run(&system, mu, log_spaced(1e-2, 1.0, 30)).unwrap();
        assert!(mode.stopped.is_none(), "{:?}", mode.stopped);
        assert_eq!(mode.cycles.len(), 1);
        let cycle = &mode.cycles[0];
        assert!(cycle.point.zeta.abs() <= 1e-13 && cycle.stable());
        let chbm = system.limit_cycle(mu).unwrap();
        assert_eq!(chbm.outcome, Outcome::LimitCycle);
        assert!(
            (cycle.point.omega / chbm.omega - 1.0).abs() < 1e-6,
            "{} vs {}",
            cycle.point.omega,
            chbm.omega
        );
        let n = 2;
        let amp = |u: &[f64], d: usize| u[n + d].hypot(u[2 * n + d]);
        let (a_epmc, a_chbm) = (amp(&cycle.point.coeffs, 1), chbm.amplitude(1, 1));
        assert!((a_epmc / a_chbm - 1.0).abs() < 1e-6, "{a_epmc} vs {a_chbm}");
        let nf = system.normal_form().unwrap();
        assert_eq!(nf.criticality(), Criticality::Supercritical);
        assert_eq!(mode.criticality(), nf.criticality());
    }
}
