//! Steady-state detection for autonomous self-excited oscillators.
//!
//! A scalar observable `g(y)` (e.g. one dof's displacement) is followed along
//! the dense output. Cycles are delimited by successive upward crossings of a
//! level; each cycle's period and peak-to-peak (`max - min`) are measured
//! (crossings by the Illinois method, extrema by golden-section search on the
//! interpolant). The oscillation is declared steady when, over the last
//! `cycles` consecutive cycles, the spread (max - min) of the periods and of
//! the amplitudes is within `rtol` of their mean. The Fourier coefficients of
//! every state over the last cycle are accumulated on the fly from samples at
//! `t_start + j T_prev / N` (`T_prev`: period of the previous cycle, equal to
//! the last one within `rtol` once steady), so nothing but the current cycle's
//! sums is stored.

use std::collections::VecDeque;

use crate::bdf::{Bdf, OdeSystem};
use crate::error::OdeError;
use squeal_hbm::{FourierSums, Periodic};

/// Largest number of samples per cycle accepted.
pub const MAX_SAMPLES_PER_CYCLE: usize = 1 << 16;
/// Largest number of harmonics accepted.
pub const MAX_HARMONICS: usize = 1000;
/// Largest number of sub-intervals per step accepted.
const MAX_SUBDIVISIONS: usize = 1000;
/// Largest window of cycles accepted.
const MAX_WINDOW: usize = 100_000;
/// Golden-section iterations for an extremum (0.618^40 = 4e-9 of a step in
/// time, so the peak value is exact to ~1e-17 relative).
const GOLDEN_ITERATIONS: usize = 40;
/// A cycle whose dip below the level is under this fraction of its rise above it is a
/// spurious double crossing, not a cycle.
const SPURIOUS_DIP: f64 = 1e-3;

/// Iteration cap of the Illinois crossing search.
const CROSSING_ITERATIONS: usize = 100;

/// Options of the steady-state detector.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct SteadyOptions {
    /// Level whose upward crossings delimit cycles (e.g. the equilibrium
    /// value of the observable).
    pub level: f64,
    /// Relative tolerance on the spread of periods and amplitudes.
    pub rtol: f64,
    /// Number of consecutive cycles that must agree (>= 2).
    pub cycles: usize,
    /// Highest harmonic H of the returned Fourier coefficients.
    pub harmonics: usize,
    /// Samples per cycle N for the Fourier sums (> 2 H).
    pub samples_per_cycle: usize,
    /// The observable is sampled at this many equal sub-intervals of each
    /// step to find crossings and extrema (>= 1).
    pub subdivisions: usize,
    /// Cycles whose peak-to-peak (`max - min`) is below this never count as
    /// steady (guards against declaring decayed noise a limit cycle).
    pub min_amplitude: f64,
    /// What the observable is, for messages (e.g. `"penetration rate of the most moving
    /// pair"`).
    pub observable: String,
    /// The observable's unit, for messages (e.g. `"m/s"`).
    pub unit: String,
}

impl Default for SteadyOptions {
    fn default() -> Self {
        Self {
            level: 0.0,
            rtol: 1e-6,
            cycles: 10,
            harmonics: 5,
            samples_per_cycle: 64,
            subdivisions: 4,
            min_amplitude: 0.0,
            observable: "observable g(y)".into(),
            unit: "(the unit of g)".into(),
        }
    }
}

impl SteadyOptions {
    fn validate(&self) -> Result<(), OdeError> {
        let bad = |name: &'static str, reason: &str| {
            Err(OdeError::InvalidOption {
                name,
                reason: reason.into(),
            })
        };
        if !self.level.is_finite() {
            return bad("level", "must be finite");
        }
        if !(self.rtol.is_finite() && self.rtol > 0.0) {
            return bad("rtol", "must be finite and > 0");
        }
        if !(2..=MAX_WINDOW).contains(&self.cycles) {
            return bad("cycles", "must be in 2..=100000");
        }
        if self.harmonics > MAX_HARMONICS {
            return bad("harmonics", "must be <= 1000");
        }
        if !(self.samples_per_cycle > 2 * self.harmonics
            && self.samples_per_cycle <= MAX_SAMPLES_PER_CYCLE)
        {
            return bad("samples_per_cycle", "must be > 2 * harmonics and <= 65536");
        }
        if !(1..=MAX_SUBDIVISIONS).contains(&self.subdivisions) {
            return bad("subdivisions", "must be in 1..=1000");
        }
        if self.min_amplitude.is_nan() || self.min_amplitude < 0.0 {
            return bad("min_amplitude", "must be >= 0");
        }
        Ok(())
    }
}

/// One complete cycle of the observable, between two upward crossings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleRecord {
    /// Upward crossing that starts the cycle.
    pub t_start: f64,
    /// Time to the next upward crossing.
    pub period: f64,
    /// Largest value of the observable in the cycle, and when.
    pub max: f64,
    /// Time of `max`.
    pub t_max: f64,
    /// Smallest value of the observable in the cycle.
    pub min: f64,
    /// Time of `min`.
    pub t_min: f64,
}

impl CycleRecord {
    /// The peak-to-peak `max - min` (outputs call it peak-to-peak; an amplitude there is half
    /// of it).
    pub fn amplitude(&self) -> f64 {
        self.max - self.min
    }
}

/// Result of [`run_to_steady_state`].
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyState {
    /// Period of the last cycle.
    pub period: f64,
    /// Peak-to-peak (`max - min`) of the observable over the last cycle.
    pub amplitude: f64,
    /// Start (upward crossing) of the last cycle.
    pub t_start: f64,
    /// Number of complete cycles seen since the start.
    pub cycles: usize,
    /// The last `cycles` cycle records, oldest first.
    pub window: Vec<CycleRecord>,
    /// Fourier coefficients of all states over the last cycle, with time origin
    /// `t_start` (eq. 23 of the CHBM paper: `y_i(t_start + τ)` at phase `θ = ω τ`).
    pub fourier: Periodic,
}

/// A sample of the observable.
#[derive(Debug, Clone, Copy)]
struct Sample {
    t: f64,
    g: f64,
}

/// The running cycle: start and extrema so far.
#[derive(Debug, Clone, Copy)]
struct OpenCycle {
    t_start: f64,
    max: Sample,
    min: Sample,
}

/// Follows an observable along a [`Bdf`] run, step by step: cycle records,
/// Fourier sums and the steadiness test. [`run_to_steady_state`] drives it;
/// use it directly to watch the cycles (e.g. growth rates) yourself.
pub struct OscillationMonitor<G> {
    observable: G,
    opts: SteadyOptions,
    y: Vec<f64>,
    /// Last two observable samples (older first).
    prev: [Option<Sample>; 2],
    open: Option<OpenCycle>,
    window: VecDeque<CycleRecord>,
    completed: usize,
    /// The running cycle's Fourier sums (none until a period is known).
    fourier: Option<FourierSums>,
    dim: usize,
}

impl<G: FnMut(&[f64]) -> f64> OscillationMonitor<G> {
    /// A monitor for a system of dimension `dim`.
    pub fn new(dim: usize, observable: G, opts: &SteadyOptions) -> Result<Self, OdeError> {
        opts.validate()?;
        if dim == 0 || dim > crate::bdf::MAX_DIM {
            return Err(OdeError::InvalidOption {
                name: "dim",
                reason: "system dimension out of range".into(),
            });
        }
        Ok(Self {
            observable,
            opts: opts.clone(),
            y: vec![0.0; dim],
            prev: [None, None],
            open: None,
            window: VecDeque::with_capacity(opts.cycles),
            completed: 0,
            fourier: None,
            dim,
        })
    }

    /// The last complete cycles (at most `cycles`), oldest first.
    pub fn window(&self) -> &VecDeque<CycleRecord> {
        &self.window
    }

    /// Number of complete cycles seen.
    pub fn cycles_completed(&self) -> usize {
        self.completed
    }

    /// The error of an oscillation still not steady at time `t`, with the last cycle seen.
    pub fn not_steady(&self, t: f64) -> OdeError {
        let last = self.window.back().copied();
        OdeError::NotSteady {
            t,
            cycles: self.completed,
            last_period: last.map_or(f64::NAN, |r| r.period),
            last_peak_to_peak: last.map_or(f64::NAN, |r| r.amplitude()),
            observable: self.opts.observable.clone(),
            unit: self.opts.unit.clone(),
        }
    }

    /// Observable at `t` on the current step's interpolant.
    fn g_at<S: OdeSystem>(&mut self, bdf: &Bdf<S>, t: f64) -> Result<f64, OdeError> {
        bdf.eval_polynomial(t, &mut self.y);
        let g = (self.observable)(&self.y);
        if g.is_finite() {
            Ok(g)
        } else {
            Err(OdeError::NonFinite {
                what: "observable",
                t,
            })
        }
    }

    /// Process the last accepted step of `bdf` (call after every step, and
    /// once before the first). Returns the steady state once it is reached.
    pub fn observe<S: OdeSystem>(&mut self, bdf: &Bdf<S>) -> Result<Option<SteadyState>, OdeError> {
        let (t0, t1) = (bdf.t_prev(), bdf.t());
        if self.prev[1].is_none() || t1 <= t0 {
            let g = self.g_at(bdf, t1)?;
            self.prev[1] = Some(Sample { t: t1, g });
            return Ok(None);
        }
        let m = self.opts.subdivisions;
        for k in 1..=m {
            let t = if k == m {
                t1
            } else {
                t0 + (t1 - t0) * k as f64 / m as f64
            };
            let g = self.g_at(bdf, t)?;
            let cur = Sample { t, g };
            self.track_extremum(bdf, cur)?;
            if let Some(steady) = self.check_crossing(bdf, cur)? {
                return Ok(Some(steady));
            }
            self.prev = [self.prev[1], Some(cur)];
        }
        self.take_samples(bdf, t1, true)?;
        Ok(None)
    }

    /// Refine a local max/min bracketed by the last three samples and fold
    /// it (and the raw sample) into the open cycle.
    fn track_extremum<S: OdeSystem>(&mut self, bdf: &Bdf<S>, cur: Sample) -> Result<(), OdeError> {
        if let (Some(a), Some(b)) = (self.prev[0], self.prev[1]) {
            if b.g >= a.g && b.g > cur.g {
                let peak = self.golden(bdf, a.t, cur.t, 1.0)?;
                self.fold(peak);
            } else if b.g <= a.g && b.g < cur.g {
                let trough = self.golden(bdf, a.t, cur.t, -1.0)?;
                self.fold(trough);
            }
        }
        self.fold(cur);
        Ok(())
    }

    fn fold(&mut self, s: Sample) {
        if let Some(c) = self.open.as_mut() {
            if s.g > c.max.g {
                c.max = s;
            }
            if s.g < c.min.g {
                c.min = s;
            }
        }
    }

    /// Golden-section search for the max of `sign * g` on `[a, b]`.
    fn golden<S: OdeSystem>(
        &mut self,
        bdf: &Bdf<S>,
        a: f64,
        b: f64,
        sign: f64,
    ) -> Result<Sample, OdeError> {
        let r = 0.5 * (5f64.sqrt() - 1.0);
        let (mut a, mut b) = (a, b);
        let mut x1 = b - r * (b - a);
        let mut x2 = a + r * (b - a);
        let mut f1 = sign * self.g_at(bdf, x1)?;
        let mut f2 = sign * self.g_at(bdf, x2)?;
        for _ in 0..GOLDEN_ITERATIONS {
            if f1 >= f2 {
                b = x2;
                x2 = x1;
                f2 = f1;
                x1 = b - r * (b - a);
                f1 = sign * self.g_at(bdf, x1)?;
            } else {
                a = x1;
                x1 = x2;
                f1 = f2;
                x2 = a + r * (b - a);
                f2 = sign * self.g_at(bdf, x2)?;
            }
        }
        Ok(if f1 >= f2 {
            Sample {
                t: x1,
                g: sign * f1,
            }
        } else {
            Sample {
                t: x2,
                g: sign * f2,
            }
        })
    }

    /// An upward crossing of the level between the last sample and `cur`
    /// closes the open cycle and opens the next.
    fn check_crossing<S: OdeSystem>(
        &mut self,
        bdf: &Bdf<S>,
        cur: Sample,
    ) -> Result<Option<SteadyState>, OdeError> {
        let level = self.opts.level;
        let Some(last) = self.prev[1] else {
            return Ok(None);
        };
        if !(last.g < level && cur.g >= level) {
            return Ok(None);
        }
        if let Some(open) = self.open {
            // A cycle must dip below the level. Consecutive steps' interpolants differ by
            // the local error at their common end, so a step ending just past a crossing can
            // show a second crossing a round-off later: such a "cycle" rises but never dips,
            // and is ignored (the open cycle goes on).
            let rise = (open.max.g - level).max(0.0);
            if level - open.min.g <= SPURIOUS_DIP * rise {
                return Ok(None);
            }
        }
        let tc = self.crossing(bdf, last, cur)?;
        self.take_samples(bdf, tc, false)?;
        let mut steady = None;
        let mut period = None;
        if let Some(open) = self.open {
            let record = CycleRecord {
                t_start: open.t_start,
                period: tc - open.t_start,
                max: open.max.g,
                t_max: open.max.t,
                min: open.min.g,
                t_min: open.min.t,
            };
            period = Some(record.period);
            if self.window.len() == self.opts.cycles {
                self.window.pop_front();
            }
            self.window.push_back(record);
            self.completed += 1;
            if self.is_steady() {
                steady = Some(SteadyState {
                    period: record.period,
                    amplitude: record.amplitude(),
                    t_start: record.t_start,
                    cycles: self.completed,
                    window: self.window.iter().copied().collect(),
                    fourier: self.fourier.as_ref().map(FourierSums::periodic).ok_or(
                        OdeError::InvalidOption {
                            name: "samples_per_cycle",
                            reason: "no Fourier sums for the closed cycle".into(),
                        },
                    )?,
                });
            }
        }
        let start = Sample { t: tc, g: level };
        self.open = Some(OpenCycle {
            t_start: tc,
            max: start,
            min: start,
        });
        self.fourier = match period {
            Some(p) => Some(
                FourierSums::new(
                    self.dim,
                    self.opts.harmonics,
                    self.opts.samples_per_cycle,
                    1,
                    tc,
                    p,
                )
                .map_err(|e| OdeError::InvalidOption {
                    name: "harmonics",
                    reason: e.to_string(),
                })?,
            ),
            None => None,
        };
        Ok(steady)
    }

    /// Window full, spreads within `rtol`, amplitude large enough, and the
    /// Fourier sums of the cycle just closed are complete.
    fn is_steady(&self) -> bool {
        if self.window.len() < self.opts.cycles
            || !self.fourier.as_ref().is_some_and(FourierSums::complete)
        {
            return false;
        }
        let spread_ok = |v: &dyn Fn(&CycleRecord) -> f64| {
            let (mut lo, mut hi, mut sum) = (f64::INFINITY, f64::NEG_INFINITY, 0.0);
            for r in &self.window {
                let x = v(r);
                lo = lo.min(x);
                hi = hi.max(x);
                sum += x;
            }
            let mean = sum / self.window.len() as f64;
            hi - lo <= self.opts.rtol * mean.abs()
        };
        let amp_ok = self
            .window
            .iter()
            .all(|r| r.amplitude() >= self.opts.min_amplitude && r.amplitude() > 0.0);
        amp_ok && spread_ok(&|r| r.period) && spread_ok(&|r| r.amplitude())
    }

    /// Illinois (modified regula falsi) for `g(t) = level` in `(a, b]`.
    fn crossing<S: OdeSystem>(
        &mut self,
        bdf: &Bdf<S>,
        a: Sample,
        b: Sample,
    ) -> Result<f64, OdeError> {
        let level = self.opts.level;
        let (mut ta, mut fa) = (a.t, a.g - level);
        let (mut tb, mut fb) = (b.t, b.g - level);
        if fb == 0.0 {
            return Ok(tb);
        }
        let mut side = 0i8;
        for _ in 0..CROSSING_ITERATIONS {
            let width = tb - ta;
            if width <= 4.0 * f64::EPSILON * tb.abs().max(ta.abs()) {
                break;
            }
            let mut t = (ta * fb - tb * fa) / (fb - fa);
            if !(t > ta && t < tb) {
                t = 0.5 * (ta + tb);
            }
            let f = self.g_at(bdf, t)? - level;
            if f == 0.0 {
                return Ok(t);
            }
            if f < 0.0 {
                ta = t;
                fa = f;
                if side == -1 {
                    fb *= 0.5;
                }
                side = -1;
            } else {
                tb = t;
                fb = f;
                if side == 1 {
                    fa *= 0.5;
                }
                side = 1;
            }
        }
        Ok((ta * fb - tb * fa) / (fb - fa))
    }

    /// Fourier samples due up to `t_limit` (strictly before it when
    /// `inclusive` is false).
    fn take_samples<S: OdeSystem>(
        &mut self,
        bdf: &Bdf<S>,
        t_limit: f64,
        inclusive: bool,
    ) -> Result<(), OdeError> {
        while let Some(ts) = self.fourier.as_ref().and_then(FourierSums::next_time) {
            let due = if inclusive {
                ts <= t_limit
            } else {
                ts < t_limit
            };
            if !due {
                break;
            }
            bdf.eval_polynomial(ts, &mut self.y);
            if !self.y.iter().all(|v| v.is_finite()) {
                return Err(OdeError::NonFinite {
                    what: "dense output",
                    t: ts,
                });
            }
            if let Some(f) = self.fourier.as_mut() {
                f.add(&self.y);
            }
        }
        Ok(())
    }
}

/// Integrate with `bdf` until the oscillation of `observable` is steady (see
/// the module doc), or fail with [`OdeError::NotSteady`] at `bdf`'s end time.
pub fn run_to_steady_state<S: OdeSystem, G: FnMut(&[f64]) -> f64>(
    bdf: &mut Bdf<S>,
    observable: G,
    opts: &SteadyOptions,
) -> Result<SteadyState, OdeError> {
    let mut monitor = OscillationMonitor::new(bdf.dim(), observable, opts)?;
    monitor.observe(bdf)?;
    while !bdf.is_finished() {
        bdf.step()?;
        if let Some(steady) = monitor.observe(bdf)? {
            return Ok(steady);
        }
    }
    Err(monitor.not_steady(bdf.t()))
}
