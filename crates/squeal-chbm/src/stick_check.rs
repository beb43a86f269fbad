//! The check of a sticking cycle ([`crate::stick_branch`]) against time integration of the
//! same law: the full brake (every mode, [`crate::timeint`], variable-step BDF of order 2 —
//! implicit, as the regularized friction's slope `μ F_n / v_reg` near zero slip is stiff)
//! started near the harmonic balance cycle and run to its steady cycle.
//!
//! **Start.** The cycle's mean and first harmonic: `x(0) = x̄ + Re ψ`, `x'(0) = Re(iω ψ)` with
//! `ψ = U1c - i U1s` over every dof (eq 35's recovery of the linear dofs), that is
//! [`TiStart::from_mode`] with `λ = iω`, the mode `ψ` and a perturbation that makes its scale
//! factor 1. The higher harmonics are left to the integration: a stable cycle attracts it.
//!
//! **Measures.** The period of the integrated steady cycle against `2π/ω`, and the loudest
//! pair's peak-to-peak closure of both, each from its Fourier coefficients on the same
//! number of harmonics ([`TiOptions::harmonics`]: the harmonic balance's coefficients are
//! truncated to them, so that both sides measure the same thing).

use crate::branch::{BranchPoint, full_cycle, pair_cycles};
use crate::solve::ChbmError;
use crate::timeint::{TiError, TiOptions, TiRun, TiStart, integrate_from};
use faer::c64;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::HarmonicLayout;

/// Why the check could not run.
#[derive(Debug, thiserror::Error)]
pub enum StickCheckError {
    /// The harmonic balance side (the cycle's recovery).
    #[error(transparent)]
    Chbm(#[from] ChbmError),
    /// The integration could not start.
    #[error(transparent)]
    Ti(#[from] TiError),
}

/// The harmonic balance cycle against the integrated one.
#[derive(Debug)]
pub struct StickCheck {
    /// `2π/ω` of the harmonic balance cycle (s).
    pub hb_period: f64,
    /// The loudest pair (0-based) of the harmonic balance cycle.
    pub pair: usize,
    /// Its peak-to-peak closure on [`TiOptions::harmonics`] harmonics (m).
    pub hb_closure: f64,
    /// The integrated steady cycle's period (s; `None`: not steady).
    pub ti_period: Option<f64>,
    /// The same pair's peak-to-peak closure of the integrated cycle (m).
    pub ti_closure: Option<f64>,
    /// The integration itself.
    pub run: TiRun,
}

/// Integrates `mb` (at `point`'s μ) from near the cycle `point` to its steady cycle and
/// measures both (module documentation).
pub fn check_against_integration(
    mb: &ModalBrake,
    point: &BranchPoint,
    samples: Option<usize>,
    opts: &TiOptions,
) -> Result<StickCheck, StickCheckError> {
    let mut mbp = mb.clone();
    mbp.mu = point.parameter;
    let n = mbp.modes();
    let full = full_cycle(&mbp, point, samples)?;
    let mean = full[..n].to_vec();
    let mode: Vec<c64> = (0..n)
        .map(|d| c64::new(full[n + d], -full[2 * n + d]))
        .collect();
    // The perturbation that makes the start's scale factor ε = 1 (TiStart::from_mode).
    let x_n: Vec<f64> = mbp.nl_dofs.iter().map(|&d| mean[d]).collect();
    let psi_n: Vec<c64> = mbp.nl_dofs.iter().map(|&d| mode[d]).collect();
    let (mut gmax, mut pen) = (0.0f64, f64::INFINITY);
    for p in &mbp.pairs {
        let g: c64 = p.normal.iter().map(|&(k, a)| psi_n[k] * a).sum();
        gmax = gmax.max(g.norm());
        let d = p.penetration(&x_n);
        if d > 0.0 {
            pen = pen.min(d);
        }
    }
    let start = TiStart::from_mode(&mbp, c64::new(0.0, point.omega), &mode, &mean, gmax / pen)?;
    let run = integrate_from(&mbp, &start, opts)?;
    let h = opts.harmonics.min(point.harmonics);
    let closure_of = |u: &[f64]| -> Result<Vec<f64>, ChbmError> {
        let layout = HarmonicLayout::new(mbp.nl(), h)?;
        let len = layout.len();
        Ok(pair_cycles(&mbp, &layout, &u[..len])
            .iter()
            .map(|c| c.peak_to_peak())
            .collect())
    };
    let hb = closure_of(&point.nl_coeffs)?;
    let pair = hb
        .iter()
        .enumerate()
        .fold((0, 0.0), |a, (i, &c)| if c > a.1 { (i, c) } else { a })
        .0;
    let (ti_period, ti_closure) = match &run.steady {
        Some(s) => {
            let nl = s.cycle.restrict(&mbp.nl_dofs).map_err(ChbmError::from)?;
            let c = closure_of(&nl.x.coeffs)?;
            (Some(s.period), Some(c[pair]))
        }
        None => (None, None),
    };
    Ok(StickCheck {
        hb_period: 2.0 * std::f64::consts::PI / point.omega,
        pair,
        hb_closure: hb[pair],
        ti_period,
        ti_closure,
        run,
    })
}
