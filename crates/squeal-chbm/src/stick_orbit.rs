//! Issue #24, items 4–5: a stick–slip cycle of the brake against time integration of the
//! regularized law, with what the integrated orbit does at every pair.
//!
//! [`crate::stick_check`] integrates the full brake with the regularized law
//! `F_t(|v|) tanh(v / v_reg)` ([`crate::stick_branch::sticking_brake`]) from near a harmonic
//! balance cycle to its steady cycle (BDF of order 2, drift of 20-cycle Fourier averages below
//! [`TiOptions::drift_tol`]). This module goes on from where that run ended and **records** the
//! orbit for [`OrbitOptions::record_cycles`] periods of the balance's cycle at
//! [`OrbitOptions::samples_per_cycle`] uniform samples a period (the BDF's dense output), and
//! measures at every sample and pair:
//!
//! - the closure `δ_p = g_p·x_n - g0_p` (open when `δ_p ≤ 0`),
//! - the slip velocity `γ_p = V_p + h_p·x_n'` (the same as the DLFT balance's, eq D3 of
//!   docs/stick_slip.md).
//!
//! **Stuck** is `δ_p > 0` and `|γ_p| ≤ band · v_reg` ([`OrbitOptions::stick_band`]): the
//! regularized law carries a force inside Coulomb's cone, `|F_t| = μ N tanh(|γ|/v_reg)`, only
//! with `|γ|` of a few `v_reg`, so it "sticks" by creeping at `|γ| = v_reg atanh(|F_t|/μN)`;
//! band 3 counts every sample with `|F_t| ≤ tanh 3 μN = 0.995 μN`. A pair that slides through
//! `γ = 0` without sticking also spends `2 band v_reg / |γ'|` in the band: that share vanishes
//! as `v_reg → 0`, so the stuck fraction converges to the exact law's as `v_reg` does.
//! **Reversed** is `δ_p > 0` and `γ_p < -band · v_reg` (the pad outruns the disc: the friction
//! reverses).
//!
//! **Periodicity.** The record is cut into cycles at the upward crossings of the loudest pair's
//! closure through its balance mean (linear interpolation between samples); each cycle gives a
//! period and a peak-to-peak closure. On a periodic orbit they agree from cycle to cycle to the
//! integrator's noise; a modulated (quasi-periodic) or chaotic orbit shows their spread.

use crate::branch::BranchPoint;
use crate::stick_check::{StickCheck, StickCheckError, check_against_integration};
use crate::timeint::{TiError, TiOptions};
use squeal_brake::dynamics::BrakeDynamics;
use squeal_brake::modal_brake::ModalBrake;
use squeal_ode::{Atol, Bdf, BdfOptions, OdeError};

/// Options of [`integrate_orbit`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct OrbitOptions {
    /// The integration to the steady cycle ([`crate::stick_check`]).
    pub ti: TiOptions,
    /// Periods of the balance's cycle recorded after it.
    pub record_cycles: usize,
    /// Uniform samples a period in the record.
    pub samples_per_cycle: usize,
    /// A closed pair is stuck while `|γ| ≤ stick_band · v_reg` (module docs).
    pub stick_band: f64,
}

impl Default for OrbitOptions {
    fn default() -> Self {
        Self {
            ti: TiOptions {
                rtol: 1e-7,
                harmonics: 24,
                ..TiOptions::default()
            },
            record_cycles: 40,
            samples_per_cycle: 4096,
            stick_band: 3.0,
        }
    }
}

/// What the recorded orbit does.
#[derive(Clone, Debug)]
pub struct OrbitRecord {
    /// Fraction of the record each pair is stuck (module docs).
    pub stuck: Vec<f64>,
    /// Fraction of the record each pair is closed and slides backwards.
    pub reversed: Vec<f64>,
    /// Fraction of the record each pair is open.
    pub open: Vec<f64>,
    /// Period of every complete cycle of the record (s).
    pub periods: Vec<f64>,
    /// The loudest pair's peak-to-peak closure in each of them (m).
    pub closures: Vec<f64>,
    /// Each pair's states over the last recorded period, in time order as runs `(state,
    /// fraction of the period)`: `'s'` stuck, `'r'` reversed, `'o'` open, `'f'` sliding forwards.
    pub patterns: Vec<Vec<(char, f64)>>,
}

impl OrbitRecord {
    /// `(min, max)` of `v` (`(NaN, NaN)` when empty).
    fn range(v: &[f64]) -> (f64, f64) {
        v.iter()
            .fold((f64::NAN, f64::NAN), |(lo, hi), &x| (lo.min(x), hi.max(x)))
    }

    /// Relative spread `(max - min) / mean` of the cycles' periods.
    pub fn period_spread(&self) -> f64 {
        let (lo, hi) = Self::range(&self.periods);
        (hi - lo) / mean(&self.periods)
    }

    /// Relative spread of the cycles' peak-to-peak closures.
    pub fn closure_spread(&self) -> f64 {
        let (lo, hi) = Self::range(&self.closures);
        (hi - lo) / mean(&self.closures)
    }

    /// Mean period of the record's cycles (s).
    pub fn mean_period(&self) -> f64 {
        mean(&self.periods)
    }

    /// Mean peak-to-peak closure of the loudest pair (m).
    pub fn mean_closure(&self) -> f64 {
        mean(&self.closures)
    }
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// The integration to the steady cycle and the record after it.
#[derive(Debug)]
pub struct StickOrbit {
    /// The run to the steady cycle against the balance ([`crate::stick_check`]).
    pub check: StickCheck,
    /// The record, or the integrator's error that stopped it.
    pub record: Result<OrbitRecord, OdeError>,
    /// BDF steps of the record.
    pub record_steps: usize,
}

/// The record's running sums (module docs).
struct Recorder<'a> {
    mb: &'a ModalBrake,
    pair: usize,
    level: f64,
    band: f64,
    dt: f64,
    xn: Vec<f64>,
    vn: Vec<f64>,
    counts: [Vec<usize>; 3],
    samples: usize,
    last: Option<(f64, f64)>,
    crossings: Vec<f64>,
    extrema: Vec<(f64, f64)>,
    /// Every pair's state at the last `per_cycle` samples (a ring).
    last_cycle: Vec<Vec<u8>>,
    per_cycle: usize,
}

impl Recorder<'_> {
    /// Takes the modal state `y` at time `t`.
    fn take(&mut self, t: f64, y: &[f64]) {
        let n = self.mb.modes();
        let pn = &self.mb.phi_n;
        for i in 0..self.mb.nl() {
            self.xn[i] = (0..n).map(|j| pn[(i, j)] * y[j]).sum();
            self.vn[i] = (0..n).map(|j| pn[(i, j)] * y[n + j]).sum();
        }
        self.samples += 1;
        for (k, p) in self.mb.pairs.iter().enumerate() {
            let d = p.penetration(&self.xn);
            let g = p.surface_speed.unwrap_or(0.0)
                + p.tangent.iter().map(|&(i, h)| h * self.vn[i]).sum::<f64>();
            let state = if d <= 0.0 {
                2
            } else if g.abs() <= self.band {
                0
            } else if g < 0.0 {
                1
            } else {
                3
            };
            self.last_cycle[k][(self.samples - 1) % self.per_cycle] = state as u8;
            if state < 3 {
                self.counts[state][k] += 1;
            }
        }
        let d = self.mb.pairs[self.pair].penetration(&self.xn) - self.level;
        if let Some((t0, d0)) = self.last
            && d0 < 0.0
            && d >= 0.0
        {
            self.crossings.push(t0 + self.dt * d0 / (d0 - d));
            self.extrema.push((d, d));
        }
        if let Some(e) = self.extrema.last_mut() {
            e.0 = e.0.min(d);
            e.1 = e.1.max(d);
        }
        self.last = Some((t, d));
    }

    fn finish(self) -> OrbitRecord {
        let frac = |c: &Vec<usize>| {
            c.iter()
                .map(|&k| k as f64 / self.samples.max(1) as f64)
                .collect()
        };
        let cycles = self.crossings.len().saturating_sub(1);
        let n = self.per_cycle;
        let first = self.samples % n;
        let patterns = self
            .last_cycle
            .iter()
            .map(|ring| {
                let mut runs: Vec<(char, f64)> = Vec::new();
                for j in 0..n {
                    let c = ['s', 'r', 'o', 'f'][ring[(first + j) % n] as usize];
                    match runs.last_mut() {
                        Some(r) if r.0 == c => r.1 += 1.0 / n as f64,
                        _ => runs.push((c, 1.0 / n as f64)),
                    }
                }
                runs
            })
            .collect();
        OrbitRecord {
            patterns,
            stuck: frac(&self.counts[0]),
            reversed: frac(&self.counts[1]),
            open: frac(&self.counts[2]),
            periods: self.crossings.windows(2).map(|w| w[1] - w[0]).collect(),
            closures: self.extrema[..cycles].iter().map(|e| e.1 - e.0).collect(),
        }
    }
}

/// Integrates `smb` (a brake whose pairs carry the regularized law at `v_reg`,
/// [`crate::stick_branch::sticking_brake`]) from near `point` to its steady cycle, compares
/// it with `point` ([`check_against_integration`]), then records the orbit (module docs). The
/// record starts where the run ended, steady or not, so a run that finds no steady cycle
/// still says what the orbit does.
pub fn integrate_orbit(
    smb: &ModalBrake,
    v_reg: f64,
    point: &BranchPoint,
    samples: Option<usize>,
    opts: &OrbitOptions,
) -> Result<StickOrbit, StickCheckError> {
    if !(v_reg > 0.0 && opts.stick_band > 0.0) || opts.samples_per_cycle < 16 {
        return Err(StickCheckError::Ti(TiError::Ode(OdeError::InvalidOption {
            name: "stick_band",
            reason: "v_reg and the band must be positive, at least 16 samples a period".into(),
        })));
    }
    let check = check_against_integration(smb, point, samples, &opts.ti)?;
    let mut mbp = smb.clone();
    mbp.mu = point.parameter;
    let start = check.run.continuation();
    let period = check.hb_period;
    let dt = period / opts.samples_per_cycle as f64;
    let t_end = period * opts.record_cycles as f64;
    let bdf_opts = {
        let mut o = BdfOptions::default();
        o.rtol = opts.ti.rtol;
        o.atol = Atol::PerComponent(start.atol(&opts.ti));
        o.max_order = opts.ti.max_order;
        o.max_steps = opts.ti.max_steps;
        o
    };
    // The loudest pair's closure is cut at its balance mean.
    let pair = check.pair;
    let level = point.pairs[pair].mean;
    let mut rec = Recorder {
        mb: &mbp,
        pair,
        level,
        band: opts.stick_band * v_reg,
        dt,
        xn: vec![0.0; mbp.nl()],
        vn: vec![0.0; mbp.nl()],
        counts: std::array::from_fn(|_| vec![0; mbp.pairs.len()]),
        samples: 0,
        last: None,
        crossings: Vec::new(),
        extrema: Vec::new(),
        last_cycle: vec![vec![3; opts.samples_per_cycle]; mbp.pairs.len()],
        per_cycle: opts.samples_per_cycle,
    };
    let sys = BrakeDynamics::new(&mbp);
    let mut y = vec![0.0; start.y0.len()];
    let mut steps = 0;
    let record = (|| -> Result<(), OdeError> {
        let mut bdf = Bdf::new(&sys, 0.0, &start.y0, t_end, &bdf_opts)?;
        let mut k = 0usize;
        while !bdf.is_finished() {
            bdf.step()?;
            while (k as f64) * dt <= bdf.t() {
                let t = k as f64 * dt;
                bdf.interpolate(t.max(bdf.t_prev()), &mut y)?;
                rec.take(t, &y);
                k += 1;
            }
        }
        steps = bdf.stats().steps;
        Ok(())
    })();
    Ok(StickOrbit {
        check,
        record: record.map(|()| rec.finish()),
        record_steps: steps,
    })
}

/// The integrated steady cycle of `check` (if any) as a point of `mb` at μ `mu`: its nonlinear
/// dofs' Fourier coefficients ([`TiOptions::harmonics`]) with the phase turned so that
/// `U1s[phase_dof] = 0`, a start for the balances ([`crate::stick_dlft::dlft_cycle`]).
pub fn steady_point(
    mb: &ModalBrake,
    mu: f64,
    check: &StickCheck,
    phase_dof: usize,
) -> Result<Option<BranchPoint>, crate::solve::ChbmError> {
    let Some(s) = &check.run.steady else {
        return Ok(None);
    };
    let nl = s.cycle.restrict(&mb.nl_dofs)?;
    let layout = squeal_hbm::HarmonicLayout::new(mb.nl(), nl.x.harmonics())?;
    let mut u = nl.x.coeffs.clone();
    layout.align_phase(&mut u, phase_dof)?;
    let mut mbp = mb.clone();
    mbp.mu = mu;
    Ok(Some(BranchPoint {
        parameter: mu,
        omega: nl.omega(),
        harmonics: layout.n_harmonics(),
        pairs: crate::branch::pair_cycles(&mbp, &layout, &u),
        truncation: crate::branch::truncation(&layout, &u),
        nl_coeffs: u,
        parameter_rate: 0.0,
        iterations: 0,
        residual: 0.0,
    }))
}
