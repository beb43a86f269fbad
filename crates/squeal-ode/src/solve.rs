//! `solve`: integrate and return the solution at chosen output times.

use crate::bdf::{Bdf, OdeSystem};
use crate::error::OdeError;
use crate::options::{BdfOptions, BdfStats};

/// States at the requested output times.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Output times (as requested).
    pub t: Vec<f64>,
    /// `y[k]` is the state at `t[k]` (dense output).
    pub y: Vec<Vec<f64>>,
    /// Counters of the whole run.
    pub stats: BdfStats,
}

/// Integrate `system` from `y0` at `t0` and return the states at `t_out`
/// (non-decreasing, all `>= t0`; the run ends at the last one). Only the
/// requested states are stored.
pub fn solve<S: OdeSystem>(
    system: S,
    t0: f64,
    y0: &[f64],
    t_out: &[f64],
    options: &BdfOptions,
) -> Result<Solution, OdeError> {
    let invalid = |reason: &str| OdeError::InvalidOption {
        name: "t_out",
        reason: reason.into(),
    };
    let Some(&t_end) = t_out.last() else {
        return Err(invalid("must not be empty"));
    };
    if t_out.iter().any(|t| !t.is_finite() || *t < t0) || t_out.windows(2).any(|w| w[1] < w[0]) {
        return Err(invalid("must be finite, >= t0 and non-decreasing"));
    }
    let mut y = Vec::with_capacity(t_out.len());
    let mut k = 0;
    while k < t_out.len() && t_out[k] == t0 {
        y.push(y0.to_vec());
        k += 1;
    }
    if k == t_out.len() {
        return Ok(Solution {
            t: t_out.to_vec(),
            y,
            stats: BdfStats::default(),
        });
    }
    let mut bdf = Bdf::new(system, t0, y0, t_end, options)?;
    let mut buf = vec![0.0; y0.len()];
    while k < t_out.len() {
        bdf.step()?;
        while k < t_out.len() && t_out[k] <= bdf.t() {
            bdf.interpolate(t_out[k], &mut buf)?;
            y.push(buf.clone());
            k += 1;
        }
    }
    Ok(Solution {
        t: t_out.to_vec(),
        y,
        stats: *bdf.stats(),
    })
}
