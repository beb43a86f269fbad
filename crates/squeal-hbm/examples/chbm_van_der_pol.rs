//! CHBM on a self-excited system written by the user: van der Pol's oscillator
//!
//! `x'' - ε (1 - x²) x' + x = 0`, here `M = 1`, `C = -ε`, `K = 1` and the force
//! `f(x, x') = ε x² x'`.
//!
//! Theory. The static solution `x = 0` is unstable: its eigenvalues `λ = ε/2 ± i sqrt(1 - ε²/4)`
//! have a positive real part. Plain harmonic balance also admits `x = 0` as a solution, so a
//! start too small may fall back on it. CHBM (Coudeyras, Sinou & Nacivet 2009) adds the
//! equation `Re λ = 0` for the eigenvalue of the system linearized over the cycle: for one dof
//! the describing function of `ε x² x'` at `x = A cos ωt` is `i ω ε A²/4`, so the cycle's
//! damping `-ε + ε A²/4` vanishes at `A = 2` — the classical first-order amplitude. With more
//! harmonics the cycle converges to the exact one: for `ε = 1` its period is
//! 6.6632868593231 (Hairer, Nørsett & Wanner, Solving ODEs I).
//!
//! Run: `cargo run --release -p squeal-hbm --example chbm_van_der_pol`.

use faer::{Mat, c64};
use squeal_hbm::*;

/// The limit cycle of van der Pol's oscillator with `eps` by CHBM with `harmonics` harmonics:
/// `(period, amplitude of the first harmonic, Re λ at the cycle, LM iterations)`.
pub fn van_der_pol(eps: f64, harmonics: usize) -> Result<(f64, f64, f64, usize), HbmError> {
    let one = |v: f64| Mat::from_fn(1, 1, |_, _| v);
    let linear = MckStiffness::new(one(1.0).as_ref(), one(-eps).as_ref(), one(1.0).as_ref())?;
    let force = FnForce::new(
        1,
        vec![(0, 0)],
        true,
        move |x: &[f64], v: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>| {
            f[0] = eps * x[0] * x[0] * v[0];
            if let Some(j) = jac {
                j.dfdx[0] = 2.0 * eps * x[0] * v[0];
                j.dfdxdot[0] = eps * x[0] * x[0];
            }
        },
    );
    let layout = HarmonicLayout::new(1, harmonics)?;
    // The unstable eigenvalue of the static solution x = 0 and its mode.
    let lambda = c64::new(eps / 2.0, (1.0 - eps * eps / 4.0).sqrt());
    let (k0, c0) = reference_jacobian(&force, &[0.0]);
    let tracker = DenseEigen::new(&linear);
    let mut hb = HarmonicBalance::new(layout, linear, force, vec![0.0; layout.len()], None)?;
    // Eq. (48) from the mode at a small amplitude: CHBM is not drawn back to x = 0.
    let u0 = initial_guess(&layout, &[0.0], &[c64::new(1.0, 0.0)], 0.1, 0)?;
    // f2 = 3 Re λ / Im λ0. Near x = 0 the harmonic balance rows grow like the amplitude A and
    // f2 ≈ (ε/2)(1 - A²/4)/Im λ0 barely changes, so a small weight lets the least-squares
    // solve slide back to x = 0; the weight must exceed 2√2 for the sum of squares to
    // decrease outward from small A (with unit row scales).
    let constraint = ReLambda::new(tracker, k0, c0, lambda, 3.0, lambda.im)?;
    let options = {
        let mut o = LmOptions::default();
        o.abs_tol = 1e-12;
        o
    };
    let phase = PhaseCondition::FirstSineZero { dof: 0 };
    let (sol, _) = solve_chbm(
        &mut hb,
        phase,
        constraint,
        RowScales::default(),
        &u0,
        lambda.im,
        &options,
    )?;
    if !sol.converged {
        return Err(HbmError::NotConverged {
            report: Box::new(sol.report),
        });
    }
    let omega = sol.z[layout.len()];
    let amplitude = layout.amplitude(&sol.z, 1, 0).unwrap_or(0.0);
    Ok((
        2.0 * std::f64::consts::PI / omega,
        amplitude,
        sol.lambda.re,
        sol.report.iterations,
    ))
}

#[allow(dead_code)]
fn main() -> Result<(), HbmError> {
    println!("van der Pol, CHBM from a start of amplitude 0.2 (x = 0 is also a solution)");
    println!(
        "{:>5} {:>3} {:>14} {:>10} {:>10} {:>5}",
        "eps", "H", "period", "A1", "Re lambda", "LM"
    );
    for (eps, h) in [(0.1, 3), (1.0, 5), (1.0, 15)] {
        let (t, a, re, it) = van_der_pol(eps, h)?;
        println!("{eps:>5} {h:>3} {t:>14.10} {a:>10.6} {re:>10.1e} {it:>5}");
    }
    println!("reference period for eps = 1: 6.6632868593 (Hairer, Norsett & Wanner)");
    Ok(())
}
