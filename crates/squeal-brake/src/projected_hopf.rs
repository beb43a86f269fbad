//! The Hopf point of a projected sweep ([`crate::projected`]) refined by Rayleigh iteration on
//! the two followed eigenpairs instead of whole eigen-decompositions.
//!
//! The refinement of `crate::hopf::regula_falsi` evaluates the projected problem at each of
//! its friction values only to read the real parts of two branches (the crossing one and its
//! partner), which it follows from one evaluation to the next by [`crate::tracking`]'s cost
//! `(1 - MAC) + min(d, 1)` (`d` the eigenvalue distance over `5 %` of `|λ|`). Each evaluation
//! here reduces the projected state matrix to Hessenberg form and carries each followed
//! eigenpair from the last evaluation (at first, the sweep point below the crossing) to the new
//! friction value by Rayleigh quotient iteration ([`crate::hessenberg_rqi`]): the eigenvalues
//! are the matrix's to round-off, as a whole decomposition's are, so regula falsi takes the
//! same steps. The spectrum handed to it holds the two followed modes only.
//!
//! The iteration could land on another eigenvalue than the one a whole decomposition and the
//! tracking cost would follow. An evaluation is therefore accepted only when each pair is
//! within `5 %` of `|λ|` of its start with a shape correlated by more than [`SAME_SHAPE`], and
//! the two are apart by more than [`APART`] of `|λ|` (near an undamped coalescence they merge,
//! and the iteration cannot tell them apart); otherwise the evaluation is a whole
//! decomposition, the followed modes picked in it by the tracking cost, as before.
//!
//! The refinement's last point becomes the Hopf point's [`crate::sweep::Hopf::point`]: its
//! spectrum is then computed whole (`complete`), so that the Hopf point carries every
//! eigenvalue and shape, as with the other methods.

use crate::error::BrakeError;
use crate::hessenberg_rqi::HessenbergForm;
use crate::linearized::{Coupling, LinearizedBrake};
use crate::model::Brake;
use crate::projected::Projection;
use crate::spectrum::Spectrum;
use crate::sweep::{Crossing, Hopf, Sweep, partner};
use crate::tracking::cost_of;
use faer::{Mat, c64};
use std::cell::{Cell, RefCell};

/// Least correlation `|q₀ᴴ q|²` of a carried shape with its start.
pub const SAME_SHAPE: f64 = 0.5;

/// Least distance of the two followed eigenvalues, relative to `|λ|`.
pub const APART: f64 = 1e-6;

/// The followed eigenpairs of a refinement (eigenvalue and modal vector on the projection's
/// basis), as of its last evaluation, and how many evaluations were whole decompositions.
pub(crate) struct Followed {
    pairs: RefCell<Vec<(c64, Vec<c64>)>>,
    /// Evaluations that fell back on a whole decomposition.
    pub whole: Cell<usize>,
}

/// The followed branches' eigenpairs at the sweep point below crossing `c` (the crossing
/// branch and its partner, as `crate::hopf::regula_falsi` follows them).
pub(crate) fn followed(sweep: &Sweep, c: &Crossing) -> Followed {
    let mut branches = vec![c.branch];
    branches.extend(partner(sweep, c));
    let sp = &sweep.points[c.k].spectrum;
    let pairs = branches
        .iter()
        .map(|&b| {
            let j = sweep.branches[b][c.k];
            (sp.values[j], column(&sp.modes, j))
        })
        .collect();
    Followed {
        pairs: RefCell::new(pairs),
        whole: Cell::new(0),
    }
}

fn column(m: &Mat<c64>, j: usize) -> Vec<c64> {
    (0..m.nrows()).map(|i| m[(i, j)]).collect()
}

/// `|aᴴ b|²` of two unit vectors.
fn correlation(a: &[c64], b: &[c64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| x.conj() * y)
        .sum::<c64>()
        .norm_sqr()
}

/// The followed modes of the projection `p` at the coupling `c` (module documentation): a
/// spectrum of those modes only, or the whole one when the iteration is not accepted.
pub(crate) fn spectrum_near(
    lr: &LinearizedBrake,
    p: &Projection,
    c: &Coupling,
    followed: &Followed,
) -> Result<Spectrum, BrakeError> {
    let (omega, damping, dk, dc, ritz) = crate::projected::problem(lr, p, c);
    let h = HessenbergForm::new(omega, damping, &dk, dc.as_ref());
    let starts = followed.pairs.borrow().clone();
    let carried: Option<Vec<(c64, Vec<c64>)>> = starts
        .iter()
        .map(|(l0, q0)| {
            h.rayleigh(*l0, q0).filter(|(l, q)| {
                (l - l0).norm() <= 0.05 * l0.norm() && correlation(q0, q) > SAME_SHAPE
            })
        })
        .collect();
    let apart = |v: &[(c64, Vec<c64>)]| {
        v.iter().enumerate().all(|(a, x)| {
            v[a + 1..]
                .iter()
                .all(|y| (x.0 - y.0).norm() > APART * x.0.norm())
        })
    };
    if let Some(pairs) = carried.filter(|v| apart(v)) {
        let k = omega.len();
        let sp = Spectrum {
            mu: c.mu,
            values: pairs.iter().map(|p| p.0).collect(),
            modes: Mat::from_fn(k, pairs.len(), |i, j| pairs[j].1[i]),
            ritz: Some(ritz),
        };
        *followed.pairs.borrow_mut() = pairs;
        return Ok(sp);
    }
    followed.whole.set(followed.whole.get() + 1);
    let sp = crate::projected::spectrum(lr, p, c)?;
    // The followed modes in the whole spectrum, by the tracking cost.
    let pairs = starts
        .iter()
        .filter_map(|(l0, q0)| {
            (0..sp.values.len())
                .map(|j| {
                    let q = column(&sp.modes, j);
                    (cost_of(*l0, sp.values[j], correlation(q0, &q)), j)
                })
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .map(|(_, j)| (sp.values[j], column(&sp.modes, j)))
        })
        .collect();
    *followed.pairs.borrow_mut() = pairs;
    Ok(sp)
}

/// Replaces the spectrum of the Hopf point `h` (from [`spectrum_near`]) by the whole one at
/// its equilibrium, the unstable mode found in it as the eigenvalue nearest the refinement's.
pub(crate) fn complete(
    brake: &Brake,
    lr: &LinearizedBrake,
    p: &Projection,
    h: &mut Hopf,
) -> Result<(), BrakeError> {
    let c = lr.coupling(brake, &h.point.equilibrium);
    let full = crate::projected::spectrum(lr, p, &c)?;
    let target = h.point.spectrum.values[h.index];
    let Some(index) = (0..full.values.len()).min_by(|&a, &b| {
        (full.values[a] - target)
            .norm()
            .total_cmp(&(full.values[b] - target).norm())
    }) else {
        return Err(BrakeError::EigenNoConvergence);
    };
    h.index = index;
    h.frequency_hz = full.frequency_hz(index);
    h.point.spectrum = full;
    Ok(())
}
