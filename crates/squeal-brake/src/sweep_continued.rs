//! The continuation sweep ([`SweepMethod::Continuation`](crate::sweep::SweepMethod::Continuation)): from a dense eigen-decomposition
//! at the first friction value, every eigenpair is continued to the next one
//! ([`crate::continuation`]); a step whose continued spectrum fails its checks is halved, and
//! after [`EigenContinuationOptions::max_halvings`](crate::continuation::EigenContinuationOptions::max_halvings) halvings computed densely and matched by
//! correlation (the module documentation of [`crate::sweep`]).

use crate::continuation::{Eigenpair, agrees_with, continue_all, seed, validate};
use crate::equilibrium::{Equilibrium, static_equilibrium};
use crate::error::BrakeError;
use crate::linearized::{Coupling, LinearizedBrake};
use crate::model::Brake;
use crate::spectrum::{Reference, Spectrum, eigenvalues_of, spectrum_of};
use crate::sweep::{
    SweepOptions, SweepPoint, SweepProgress, SweepStats, SweptPoints, crossed_in_band,
};
use crate::tracking::match_modes;
use faer::{Mat, c64};
use rayon::prelude::*;

/// Points and branches with [`SweepMethod::Continuation`](crate::sweep::SweepMethod::Continuation).
/// The continued points of `mus`; with `stop_at = Some(τ)` they end at the first point where a
/// branch has crossed `Re λ = τ` in the band since the previous one.
pub(crate) fn continued_points(
    brake: &Brake,
    reference: &Reference,
    lr: &LinearizedBrake,
    mus: &[f64],
    opts: &SweepOptions,
    stop_at: Option<f64>,
    progress: SweepProgress,
) -> Result<SweptPoints, BrakeError> {
    let mut walker = Walker {
        brake,
        reference,
        lr,
        opts,
        stats: SweepStats::default(),
    };
    let check_every = opts.continuation.check_every;
    let mut state = walker.start(mus[0])?;
    let mut points = Vec::with_capacity(mus.len());
    let mut branches: Vec<Vec<usize>> = vec![Vec::with_capacity(mus.len()); state.pairs.len()];
    for (k, &mu) in mus.iter().enumerate() {
        if k > 0 {
            let mut next = walker.step(&state, mu)?;
            if check_every > 0 && k % check_every == 0 {
                walker.check(&mut next, &state)?;
            }
            state = next;
        }
        let (point, position) = sweep_point(&state);
        for (b, br) in branches.iter_mut().enumerate() {
            br.push(position[b]);
        }
        points.push(point);
        progress(points.len(), mus.len());
        if let Some(tau) = stop_at
            && crossed_in_band(&points, &branches, opts, tau)
        {
            break;
        }
    }
    Ok((points, branches, walker.stats))
}

/// A point of the continuation: equilibrium, coupling, and eigenpairs by branch.
pub(crate) struct State {
    pub eq: Equilibrium,
    pub c: Coupling,
    pub pairs: Vec<Eigenpair>,
}

/// The sweep point of a state (eigenvalues ascending in frequency, as [`spectrum_of`] orders
/// them) and the position of each branch in it.
pub(crate) fn sweep_point(state: &State) -> (SweepPoint, Vec<usize>) {
    let pairs = &state.pairs;
    let n = pairs.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        pairs[a]
            .lambda
            .im
            .total_cmp(&pairs[b].lambda.im)
            .then(a.cmp(&b))
    });
    let mut position = vec![0; n];
    for (i, &b) in order.iter().enumerate() {
        position[b] = i;
    }
    let rows = pairs.first().map_or(0, |p| p.right.len());
    let spectrum = Spectrum {
        mu: state.eq.mu,
        values: order.iter().map(|&b| pairs[b].lambda).collect(),
        modes: Mat::from_fn(rows, n, |i, j| pairs[order[j]].right[i]),
        ritz: None,
    };
    let point = SweepPoint {
        equilibrium: state.eq.clone(),
        spectrum,
    };
    (point, position)
}

/// Eigenpairs as a [`Spectrum`] in branch order (for matching by correlation).
fn branch_spectrum(mu: f64, pairs: &[Eigenpair]) -> Spectrum {
    let rows = pairs.first().map_or(0, |p| p.right.len());
    Spectrum {
        mu,
        values: pairs.iter().map(|p| p.lambda).collect(),
        modes: Mat::from_fn(rows, pairs.len(), |i, j| pairs[j].right[i]),
        ritz: None,
    }
}

/// Walks the friction values: equilibria, continued eigenpairs, halvings and fallbacks.
pub(crate) struct Walker<'a> {
    pub brake: &'a Brake,
    pub reference: &'a Reference,
    pub lr: &'a LinearizedBrake,
    pub opts: &'a SweepOptions,
    pub stats: SweepStats,
}

impl Walker<'_> {
    /// Equilibrium at `mu` by Newton's method from `from`.
    pub fn equilibrium(&self, mu: f64, from: &Equilibrium) -> Result<Equilibrium, BrakeError> {
        static_equilibrium(self.brake, mu, Some(&from.x), &self.opts.newton)
    }

    /// The first point: equilibrium from scratch, dense spectrum.
    fn start(&mut self, mu: f64) -> Result<State, BrakeError> {
        let eq = static_equilibrium(self.brake, mu, None, &self.opts.newton)?;
        let c = self.lr.coupling(self.brake, &eq);
        let pairs = self.dense(&c, None)?;
        Ok(State { eq, c, pairs })
    }

    /// Eigenpairs at `c` by the dense solver, in the branch order of `prev` (matched by
    /// correlation and eigenvalue distance, [`match_modes`]) or in ascending frequency.
    pub fn dense(
        &mut self,
        c: &Coupling,
        prev: Option<&[Eigenpair]>,
    ) -> Result<Vec<Eigenpair>, BrakeError> {
        self.stats.dense += 1;
        let (dk, dc) = self.lr.dense_change(c);
        let sp = spectrum_of(
            &self.reference.basis,
            &self.reference.damping,
            &dk,
            dc.as_ref(),
            c.mu,
        )?;
        let order: Vec<usize> = match prev {
            Some(p) => match_modes(&branch_spectrum(c.mu, p), &sp),
            None => (0..sp.values.len()).collect(),
        };
        let copts = &self.opts.continuation;
        Ok(order
            .par_iter()
            .map(|&i| {
                let right: Vec<c64> = (0..sp.modes.nrows()).map(|r| sp.modes[(r, i)]).collect();
                seed(self.lr, c, sp.values[i], right, copts)
            })
            .collect())
    }

    /// The next point at `mu`: continued from `from`, or dense when continuation fails.
    pub fn step(&mut self, from: &State, mu: f64) -> Result<State, BrakeError> {
        let eq = self.equilibrium(mu, &from.eq)?;
        let c = self.lr.coupling(self.brake, &eq);
        self.step_to(from, eq, c)
    }

    /// The next point at a given equilibrium and coupling.
    pub fn step_to(
        &mut self,
        from: &State,
        eq: Equilibrium,
        c: Coupling,
    ) -> Result<State, BrakeError> {
        let pairs = match self.advance(from, &eq, &c, 0)? {
            Some(p) => p,
            None => self.dense(&c, Some(&from.pairs))?,
        };
        Ok(State { eq, c, pairs })
    }

    /// Continues `from` to `(eq, c)`, halving the step while the result is rejected; `None`
    /// after [`EigenContinuationOptions::max_halvings`](crate::continuation::EigenContinuationOptions::max_halvings) halvings.
    fn advance(
        &mut self,
        from: &State,
        eq: &Equilibrium,
        c: &Coupling,
        depth: usize,
    ) -> Result<Option<Vec<Eigenpair>>, BrakeError> {
        let copts = &self.opts.continuation;
        if let Some((pairs, steps)) = continue_all(self.lr, c, &from.pairs, copts) {
            self.stats.iterations += steps;
            if validate(self.lr, c, &from.pairs, &pairs, copts).is_ok() {
                self.stats.continued += 1;
                return Ok(Some(pairs));
            }
        }
        self.stats.rejected += 1;
        if depth >= copts.max_halvings {
            return Ok(None);
        }
        let mid_eq = self.equilibrium(0.5 * (from.eq.mu + eq.mu), &from.eq)?;
        let mid_c = self.lr.coupling(self.brake, &mid_eq);
        let Some(pairs) = self.advance(from, &mid_eq, &mid_c, depth + 1)? else {
            return Ok(None);
        };
        let mid = State {
            eq: mid_eq,
            c: mid_c,
            pairs,
        };
        self.advance(&mid, eq, c, depth + 1)
    }

    /// Compares a continued point with a dense eigenvalue solve; on disagreement replaces it
    /// by the dense eigenpairs matched to `prev`.
    fn check(&mut self, state: &mut State, prev: &State) -> Result<(), BrakeError> {
        self.stats.checks += 1;
        let (dk, dc) = self.lr.dense_change(&state.c);
        let dense = eigenvalues_of(
            &self.reference.basis,
            &self.reference.damping,
            &dk,
            dc.as_ref(),
        )?;
        if !agrees_with(&state.pairs, &dense, self.opts.continuation.check_tolerance) {
            state.pairs = self.dense(&state.c, Some(&prev.pairs))?;
        }
        Ok(())
    }
}
