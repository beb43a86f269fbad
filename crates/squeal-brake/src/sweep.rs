//! Friction sweeps: equilibrium and spectrum at each μ, modes tracked into branches, and the
//! Hopf point `μ0` (the first crossing of a real part through zero inside the band the model
//! can speak for), refined by root finding.

use crate::equilibrium::{Equilibrium, NewtonOptions, static_equilibrium};
use crate::error::BrakeError;
use crate::modal::{Damping, modal_basis};
use crate::model::Brake;
use crate::spectrum::{Reference, Spectrum, spectrum};
use crate::tracking::{mac, match_modes};
use rayon::prelude::*;

/// The frequency band a result is trusted in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Band {
    /// Highest frequency the reduced model represents: by default the lower of the parts'
    /// highest kept fixed-interface frequencies. Eigenvalues above it are reported but never
    /// define μ0.
    pub valid_max_hz: f64,
    /// A user band (e.g. the squeal band 1–16 kHz), also required for μ0.
    pub user: Option<(f64, f64)>,
}

impl Band {
    /// Whether `f` (Hz) is inside the valid band and the user band.
    pub fn contains(&self, f: f64) -> bool {
        f <= self.valid_max_hz && self.user.is_none_or(|(lo, hi)| f >= lo && f <= hi)
    }
}

/// Controls of a sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepOptions {
    pub band: Band,
    pub newton: NewtonOptions,
    /// Width of the final bracket around μ0.
    pub mu_tolerance: f64,
    /// Spectrum evaluations allowed in the refinement.
    pub max_refinements: usize,
    /// A mode counts as unstable when `Re λ > threshold` (s⁻¹). `None`: `64 ε ω_max`, just
    /// above the eigensolver's round-off on an undamped mode (its error is about `ε ω_max` for
    /// the scaled state matrix of [`crate::spectrum`]). The Hopf point is the root of
    /// `Re λ - threshold`, shifted from that of `Re λ` by `threshold / (dRe λ/dμ)`.
    pub threshold: Option<f64>,
}

impl Default for SweepOptions {
    fn default() -> Self {
        Self {
            band: Band {
                valid_max_hz: f64::INFINITY,
                user: None,
            },
            newton: NewtonOptions::default(),
            mu_tolerance: 1e-8,
            max_refinements: 80,
            threshold: None,
        }
    }
}

/// Equilibrium and spectrum at one μ.
#[derive(Clone, Debug)]
pub struct SweepPoint {
    pub equilibrium: Equilibrium,
    pub spectrum: Spectrum,
}

/// A real part crossing zero upward between two sweep points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    pub branch: usize,
    /// Sweep points bracketing the crossing.
    pub k: usize,
    pub mu_lo: f64,
    pub mu_hi: f64,
    /// Frequency at the upper point.
    pub frequency_hz: f64,
    pub in_band: bool,
}

/// The refined Hopf point.
#[derive(Clone, Debug)]
pub struct Hopf {
    pub mu0: f64,
    /// Frequency of the mode that goes unstable, at μ0 (the coalescence frequency).
    pub frequency_hz: f64,
    /// Branch that goes unstable, and the branch it coalesces with (nearest in frequency).
    pub branch: usize,
    pub partner: Option<usize>,
    /// Final bracket `[μ-, μ+]` with the mode stable at μ- and unstable at μ+, and
    /// `Re λ - threshold` at its ends.
    pub bracket: (f64, f64),
    pub real_part_at_bracket: (f64, f64),
    /// Spectrum evaluations used by the refinement.
    pub evaluations: usize,
    /// Equilibrium and spectrum at the upper end of the bracket, and the mode's index there.
    pub point: SweepPoint,
    pub index: usize,
}

/// A sweep: its points, the branches, every upward crossing, and μ0.
#[derive(Clone, Debug)]
pub struct Sweep {
    pub points: Vec<SweepPoint>,
    /// `branches[b][k]`: index of branch `b` in `points[k].spectrum`.
    pub branches: Vec<Vec<usize>>,
    pub crossings: Vec<Crossing>,
    pub hopf: Option<Hopf>,
}

impl Sweep {
    /// Eigenvalue of branch `b` at point `k`.
    pub fn value(&self, b: usize, k: usize) -> faer::c64 {
        self.points[k].spectrum.values[self.branches[b][k]]
    }
}

/// The frictionless reference of eq (12): equilibrium at μ = 0, modal basis, damping.
pub fn reference(
    brake: &Brake,
    damping: &Damping,
    newton: &NewtonOptions,
) -> Result<Reference, BrakeError> {
    let eq = static_equilibrium(brake, 0.0, None, newton)?;
    let kt0 = brake.tangent_stiffness(&eq.x, 0.0);
    let basis = modal_basis(&brake.m, &kt0)?;
    let d = damping.diagonal(&basis);
    Ok(Reference {
        equilibrium: eq,
        kt0,
        basis,
        damping: d,
    })
}

/// Sweeps `mus` (ascending): equilibria by continuation, spectra in parallel, branches by
/// tracking, crossings, and the refined Hopf point.
pub fn sweep(
    brake: &Brake,
    reference: &Reference,
    mus: &[f64],
    opts: &SweepOptions,
) -> Result<Sweep, BrakeError> {
    if mus.is_empty()
        || mus
            .windows(2)
            .any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
    {
        return Err(BrakeError::Invalid(
            "the friction values of a sweep must be ascending".into(),
        ));
    }
    let mut equilibria = Vec::with_capacity(mus.len());
    let mut start: Option<Vec<f64>> = None;
    for &mu in mus {
        let eq = static_equilibrium(brake, mu, start.as_deref(), &opts.newton)?;
        start = Some(eq.x.clone());
        equilibria.push(eq);
    }
    let spectra: Vec<Spectrum> = equilibria
        .par_iter()
        .map(|eq| spectrum(brake, reference, eq))
        .collect::<Result<_, _>>()?;
    let points: Vec<SweepPoint> = equilibria
        .into_iter()
        .zip(spectra)
        .map(|(equilibrium, spectrum)| SweepPoint {
            equilibrium,
            spectrum,
        })
        .collect();
    let branches = track(&points);
    let tau = opts
        .threshold
        .unwrap_or_else(|| default_threshold(reference));
    let crossings = crossings(&points, &branches, opts, tau);
    let mut sweep = Sweep {
        points,
        branches,
        crossings,
        hopf: None,
    };
    if let Some(first) = sweep.crossings.iter().find(|c| c.in_band).copied() {
        sweep.hopf = Some(refine(brake, reference, &sweep, &first, opts, tau)?);
    }
    Ok(sweep)
}

/// Branch indices: branch `b` starts as mode `b` of the first spectrum.
fn track(points: &[SweepPoint]) -> Vec<Vec<usize>> {
    let n = points[0].spectrum.values.len();
    let mut branches: Vec<Vec<usize>> = (0..n).map(|b| vec![b]).collect();
    for k in 1..points.len() {
        let m = match_modes(&points[k - 1].spectrum, &points[k].spectrum);
        for br in branches.iter_mut() {
            let prev = br[k - 1];
            br.push(m[prev]);
        }
    }
    branches
}

/// Every upward crossing of a real part through zero, ordered by μ then frequency.
/// `64 ε ω_max` of the reference's modal basis.
pub fn default_threshold(reference: &Reference) -> f64 {
    let w = reference.basis.omega.iter().copied().fold(0.0, f64::max);
    64.0 * f64::EPSILON * w
}

fn crossings(
    points: &[SweepPoint],
    branches: &[Vec<usize>],
    opts: &SweepOptions,
    tau: f64,
) -> Vec<Crossing> {
    let mut out = Vec::new();
    for (b, br) in branches.iter().enumerate() {
        for k in 0..points.len().saturating_sub(1) {
            let lo = points[k].spectrum.values[br[k]];
            let hi = points[k + 1].spectrum.values[br[k + 1]];
            if lo.re <= tau && hi.re > tau {
                let f = points[k + 1].spectrum.frequency_hz(br[k + 1]);
                out.push(Crossing {
                    branch: b,
                    k,
                    mu_lo: points[k].equilibrium.mu,
                    mu_hi: points[k + 1].equilibrium.mu,
                    frequency_hz: f,
                    in_band: opts.band.contains(f),
                });
            }
        }
    }
    out.sort_by(|a, b| {
        a.mu_lo
            .total_cmp(&b.mu_lo)
            .then(a.frequency_hz.total_cmp(&b.frequency_hz))
    });
    out
}

/// Finds, in a new spectrum, the mode continuing a tracked one (best eigenvector correlation,
/// ties broken by eigenvalue distance).
fn follow(from: &Spectrum, j: usize, to: &Spectrum) -> usize {
    let l = from.values[j];
    let mut best = (f64::INFINITY, 0);
    for i in 0..to.values.len() {
        let d = (to.values[i] - l).norm() / (0.05 * l.norm()).max(f64::MIN_POSITIVE);
        let c = (1.0 - mac(from, j, to, i)) + d.min(1.0);
        if c < best.0 {
            best = (c, i);
        }
    }
    best.1
}

/// Refines a crossing by the Illinois variant of regula falsi on `Re λ(μ)`, keeping a bracket.
fn refine(
    brake: &Brake,
    reference: &Reference,
    sweep: &Sweep,
    c: &Crossing,
    opts: &SweepOptions,
    tau: f64,
) -> Result<Hopf, BrakeError> {
    let lo_point = &sweep.points[c.k];
    let hi_point = &sweep.points[c.k + 1];
    let mut lo = (c.mu_lo, lo_point.clone(), sweep.branches[c.branch][c.k]);
    let mut hi = (c.mu_hi, hi_point.clone(), sweep.branches[c.branch][c.k + 1]);
    let re = |p: &SweepPoint, j: usize| p.spectrum.values[j].re - tau;
    let (mut f_lo, mut f_hi) = (re(&lo.1, lo.2), re(&hi.1, hi.2));
    let mut side = 0i8;
    let mut evaluations = 0;
    while hi.0 - lo.0 > opts.mu_tolerance && evaluations < opts.max_refinements {
        let mut mu = (lo.0 * f_hi - hi.0 * f_lo) / (f_hi - f_lo);
        // Keep well inside the bracket; fall back to bisection when regula falsi stalls.
        let width = hi.0 - lo.0;
        if !mu.is_finite() || mu <= lo.0 + 0.01 * width || mu >= hi.0 - 0.01 * width {
            mu = 0.5 * (lo.0 + hi.0);
        }
        let eq = static_equilibrium(brake, mu, Some(&lo.1.equilibrium.x), &opts.newton)?;
        let sp = spectrum(brake, reference, &eq)?;
        let j = follow(&lo.1.spectrum, lo.2, &sp);
        let f = sp.values[j].re - tau;
        evaluations += 1;
        let point = SweepPoint {
            equilibrium: eq,
            spectrum: sp,
        };
        if f > 0.0 {
            hi = (mu, point, j);
            f_hi = f;
            if side == 1 {
                f_lo *= 0.5;
            }
            side = 1;
        } else {
            lo = (mu, point, j);
            f_lo = f;
            if side == -1 {
                f_hi *= 0.5;
            }
            side = -1;
        }
    }
    let frequency_hz = hi.1.spectrum.frequency_hz(hi.2);
    // The partner: the other in-band branch nearest in frequency at the upper bracket point
    // of the sweep (where the branch is tracked).
    let k = c.k + 1;
    let partner = (0..sweep.branches.len())
        .filter(|&b| b != c.branch)
        .min_by(|&a, &b| {
            let fa = (sweep.points[k].spectrum.frequency_hz(sweep.branches[a][k]) - c.frequency_hz)
                .abs();
            let fb = (sweep.points[k].spectrum.frequency_hz(sweep.branches[b][k]) - c.frequency_hz)
                .abs();
            fa.total_cmp(&fb)
        });
    Ok(Hopf {
        mu0: 0.5 * (lo.0 + hi.0),
        frequency_hz,
        branch: c.branch,
        partner,
        bracket: (lo.0, hi.0),
        real_part_at_bracket: (re(&lo.1, lo.2), re(&hi.1, hi.2)),
        evaluations,
        index: hi.2,
        point: hi.1,
    })
}
