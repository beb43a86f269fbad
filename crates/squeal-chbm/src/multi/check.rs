//! The two-mode torus against time integration (issue 24, item 5): the full modal equations
//! (eq 11) integrated by squeal-ode's BDF from the torus' state at `θ = 0` (the modal state of
//! [`crate::torus::modal_state`]), a transient dropped, then one pair's closure recorded and
//! measured as the torus' own signal is ([`squeal_hbm::torus::measure`]): the spectral peaks
//! nearest `ω_1` and `ω_2` and the swing envelope over one period of `ω_1`.
//!
//! Started on the torus, the run stays on it when the torus attracts and the balance is
//! accurate; its peaks then sit at `ω_1`, `ω_2` within the truncation's error. When the torus
//! repels, the run leaves it after a time set by its largest Lyapunov exponent across it, and
//! the record says where it went instead.

use super::quasi::TwoModeTorus;
use crate::torus::{closures_along_flow, modal_state};
use squeal_brake::dynamics::BrakeDynamics;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::HbmError;
use squeal_hbm::torus::measure::{Envelope, envelope, peak_frequency};
use squeal_ode::{Atol, Bdf, BdfOptions, OdeError};
use std::time::{Duration, Instant};

/// Controls of [`time_check`].
#[derive(Clone, Debug, PartialEq)]
pub struct TimeCheckOptions {
    /// Periods of `ω_1` dropped, then recorded.
    pub transient: usize,
    /// See `transient`.
    pub record: usize,
    /// Samples per period of `ω_1`.
    pub samples: usize,
    /// BDF's relative tolerance (the absolute one is this times the state's size).
    pub rtol: f64,
    /// BDF's highest order.
    pub max_order: usize,
}

impl Default for TimeCheckOptions {
    fn default() -> Self {
        Self {
            transient: 100,
            record: 400,
            samples: 64,
            rtol: 1e-8,
            max_order: 5,
        }
    }
}

/// Errors of [`time_check`].
#[derive(Debug, thiserror::Error)]
pub enum TimeCheckError {
    /// The torus could not be evaluated.
    #[error(transparent)]
    Hbm(#[from] HbmError),
    /// The integration failed.
    #[error(transparent)]
    Ode(#[from] OdeError),
    /// The record is too short for the measures.
    #[error("the record is too short to measure two spectral peaks and an envelope")]
    Record,
}

/// What the time integration and the torus' own signal show, measured alike.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeCheck {
    /// The pair observed.
    pub pair: usize,
    /// The record's peaks nearest `ω_1` and `ω_2` (rad/s).
    pub bdf_omega: [f64; 2],
    /// The torus' signal's peaks (the measure's own bias: exactly `ω` in the limit).
    pub torus_peaks: [f64; 2],
    /// The record's envelope.
    pub bdf_envelope: Envelope,
    /// The torus' signal's envelope over the same length.
    pub torus_envelope: Envelope,
    /// BDF steps and wall time.
    pub steps: usize,
    /// See `steps`.
    pub wall: Duration,
}

/// The time-integration check of the torus `t` of `mb`'s brake (module docs).
pub fn time_check(
    mb: &ModalBrake,
    t: &TwoModeTorus,
    opts: &TimeCheckOptions,
) -> Result<TimeCheck, TimeCheckError> {
    let start = Instant::now();
    let mut mbm = mb.clone();
    mbm.mu = t.point.mu;
    let w = t.point.omega;
    let tr = t.basis.truncation();
    let y0 = modal_state(&mbm, tr, Some(t.grid), &t.point.coeffs, w, [0.0, 0.0])?;
    let sys = BrakeDynamics::new(&mbm);
    let period = std::f64::consts::TAU / w[0];
    let dt = period / opts.samples as f64;
    let size = y0.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut bo = BdfOptions::default();
    bo.rtol = opts.rtol;
    bo.atol = Atol::Scalar(opts.rtol * size);
    bo.max_order = opts.max_order;
    let (skip, count) = (opts.transient * opts.samples, opts.record * opts.samples);
    let t_end = (skip + count) as f64 * dt;
    let mut bdf = Bdf::new(&sys, 0.0, &y0, t_end, &bo)?;
    let n = mbm.modes();
    let (mut y, mut xn) = (vec![0.0; 2 * n], vec![0.0; mbm.nl()]);
    let mut signal = Vec::with_capacity(count);
    let mut j = 0;
    while !bdf.is_finished() {
        bdf.step()?;
        while j < count {
            let ts = (skip + j) as f64 * dt;
            if ts > bdf.t() {
                break;
            }
            bdf.interpolate(ts, &mut y)?;
            mbm.nonlinear_part(&y[..n], &mut xn);
            signal.push(mbm.pairs[t.pair].penetration(&xn));
            j += 1;
        }
    }
    let hb = closures_along_flow(&mbm, &t.basis, &t.point.coeffs, w, dt, count)?;
    let width = 0.3 * (w[0] - w[1]).abs().min(w[1]);
    let peaks = |s: &[f64]| -> Option<[f64; 2]> {
        Some([
            peak_frequency(s, dt, w[0], width)?,
            peak_frequency(s, dt, w[1], width)?,
        ])
    };
    let hb_pair = &hb[t.pair];
    Ok(TimeCheck {
        pair: t.pair,
        bdf_omega: peaks(&signal).ok_or(TimeCheckError::Record)?,
        torus_peaks: peaks(hb_pair).ok_or(TimeCheckError::Record)?,
        bdf_envelope: envelope(&signal, dt, period).ok_or(TimeCheckError::Record)?,
        torus_envelope: envelope(hb_pair, dt, period).ok_or(TimeCheckError::Record)?,
        steps: bdf.stats().steps,
        wall: start.elapsed(),
    })
}
