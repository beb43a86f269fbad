//! DLFT from more starts when the first stops short (issue 24, item 4; docs/stick_slip.md,
//! "Past 1.05 μ0").
//!
//! **Why.** The DLFT balance is piecewise smooth: its Jacobian is exact between changes of the
//! samples' stick/slip pattern, and Levenberg–Marquardt stops where an iterate's pattern flips
//! (the relay is discontinuous, `squeal_hbm::stick_slip`). Whether it reaches the cycle then
//! depends on the start. On the coarse bundled brake at 3 km/h the time integration of the
//! regularized law is periodic at every μ tried (1.045, 1.054, 1.065 μ0; period and closure
//! the same from cycle to cycle within 2.5e-5), and its cycle approaches the regularized
//! balance's to the integrator's error, so the exact cycle is there to be found. From the
//! 3-harmonic CHBM cycle DLFT stops at residuals of 1e-2 to 5e-1. From the regularized
//! balance's cycles it did not converge at 1.0540 or 1.0649 μ0 (V/20 to V/320: 1e-3 to 3e-2);
//! from the BDF record's own 24-harmonic cycles it converged at 1.0452 μ0 (from V/20),
//! 1.0540 μ0 (from V/320) and 1.0649 μ0 (from V/160), not from every `v_reg`: the solve
//! reaches the cycle only from some starts close to it. The walk below is what squeal can
//! afford per cycle (about 2 s a start); it tells the user what was tried.
//!
//! **What.** [`dlft_from_starts`] solves from the given guess; if that stops short, it walks
//! the regularized law's cycle down in `v_reg` ([`crate::stick_dlft::regularized_cycle`],
//! each from the previous, the fractions of the slowest pair's disc speed given) and solves
//! DLFT from each, until one converges. Every start tried is kept with its residual, so a
//! cycle that still stops short says what was tried.

use crate::branch::BranchPoint;
use crate::stick_branch::{StickError, surface_speeds};
use crate::stick_dlft::{DlftCycle, DlftOptions, dlft_cycle, regularized_cycle};
use squeal_brake::modal_brake::ModalBrake;

/// The regularization velocities the starts walk down, as fractions of the slowest pair's
/// disc speed: V/20 (the branch's), V/40, V/80, V/160 and V/320.
pub const START_FRACTIONS: [f64; 5] = [0.05, 0.025, 0.0125, 0.00625, 0.003125];

/// A DLFT cycle and the starts tried for it.
#[derive(Clone, Debug)]
pub struct StartedDlft {
    /// The converged cycle, or the one of smallest residual.
    pub cycle: DlftCycle,
    /// Every start tried, in order: `None` the guess, `Some(f)` the regularized cycle at
    /// `v_reg = f V_min`; with the DLFT residual reached from it (`NaN`: the regularized
    /// cycle itself did not converge, no DLFT solve).
    pub tried: Vec<(Option<f64>, f64)>,
}

impl StartedDlft {
    /// What was tried, for a cycle that stopped short (empty when it converged).
    pub fn reason(&self) -> String {
        if self.cycle.converged {
            return String::new();
        }
        let starts: Vec<String> = self
            .tried
            .iter()
            .map(|(f, r)| {
                let from = f.map_or("the given cycle".to_string(), |f| {
                    format!("V/{:.0}", 1.0 / f)
                });
                if r.is_nan() {
                    format!("{from} (regularized cycle not converged)")
                } else {
                    format!("{from} {r:.1e}")
                }
            })
            .collect();
        format!(
            "the DLFT balance is piecewise smooth and Levenberg-Marquardt stalls where the samples' stick/slip pattern flips; starts tried (residual reached): {}",
            starts.join(", ")
        )
    }
}

/// The exact stick–slip cycle of `mb` at `mu` from `guess`, and from the regularized cycles
/// at `fractions` of the slowest disc speed when that stops short (module docs).
pub fn dlft_from_starts(
    mb: &ModalBrake,
    mu: f64,
    guess: &BranchPoint,
    phase_dof: usize,
    opts: &DlftOptions,
    fractions: &[f64],
) -> Result<StartedDlft, StickError> {
    let first = dlft_cycle(mb, mu, guess, phase_dof, opts)?;
    let mut tried = vec![(None, first.point.residual)];
    let mut best = first;
    if best.converged {
        return Ok(StartedDlft { cycle: best, tried });
    }
    let v_min = surface_speeds(mb)?
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    let mut g = guess.clone();
    let mut reg_opts = opts.clone();
    reg_opts.samples = opts.samples.or(Some(squeal_hbm::default_stick_slip_samples(
        opts.harmonics.unwrap_or(guess.harmonics),
    )));
    for &f in fractions {
        let (q, ok) = regularized_cycle(mb, mu, f * v_min, &g, phase_dof, &reg_opts)?;
        if !ok {
            tried.push((Some(f), f64::NAN));
            continue;
        }
        let d = dlft_cycle(mb, mu, &q, phase_dof, opts)?;
        tried.push((Some(f), d.point.residual));
        g = q;
        if d.converged || d.point.residual < best.point.residual {
            best = d;
        }
        if best.converged {
            break;
        }
    }
    Ok(StartedDlft { cycle: best, tried })
}
