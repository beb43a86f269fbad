//! (S3) sample by sample: the relay of Coulomb's law with a static coefficient (module docs of
//! [`super`], "Static above kinetic: the relay" and "Breakaway") and the blending of the
//! samples where the state changes (Transitions).

/// Stick or slip at one time sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactState {
    /// The contact moves with the counter-face (`γ = 0`).
    Stick,
    /// It slides (`|φ| = μ N`).
    Slip,
}

/// A transition between samples `j0` and `j1` (stick to slip at `|a| = μ_s N`, or slip to
/// stick at `|a| = μ N`), located between them where `x = |a| - L` crosses zero (module docs,
/// Transitions).
#[derive(Clone, Copy, Debug)]
pub(super) struct Transition {
    pub(super) j0: usize,
    pub(super) j1: usize,
    /// The blended sample (`j1` when the crossing lies in its cell, else `j0`).
    pub(super) blended: usize,
    /// `(φ_stick - φ_slip) dθ/dτ` at the blended sample (`θ` its stuck share).
    pub(super) jump: f64,
    /// `x` at `j0` and `j1` (opposite signs).
    pub(super) x: [f64; 2],
    /// `sign a` at `j0` and `j1`.
    pub(super) sign: [f64; 2],
    /// The limit's coefficient `L / N` (`μ_s` or `μ`).
    pub(super) coefficient: f64,
    /// Stick to slip (located on the breakaway indicator `b`, else on `a`).
    pub(super) breakaway: bool,
}

/// What (S2)–(S3) give at every sample of one contact.
pub(super) struct Projected {
    pub(super) state: Vec<ContactState>,
    /// `φ(t_j)`.
    pub(super) force: Vec<f64>,
    /// Weight of `∂a/∂z` in `∂φ_j/∂z` (1 stuck, 0 sliding, the stuck share at a breakaway).
    pub(super) stick_weight: Vec<f64>,
    /// `sign a(t_j) μ N'(δ_j)` times the sliding share (0 on stuck samples).
    pub(super) slip_slope: Vec<f64>,
    pub(super) transitions: Vec<Transition>,
}

/// (S3) as the plain projection onto Coulomb's cone at every sample, `φ_j = clamp(a_j, -μ N_j,
/// μ N_j)`, without memory (module docs of [`super`], "One coefficient: the clamp"): a
/// piecewise linear, continuous function of `(a, N)`; the derivative taken on the sample's own
/// piece (1 in `a` where stuck, `sign a μ N'` where sliding) is an element of its
/// B-subdifferential, and there are no transitions to blend.
pub(super) fn clamp_samples(a: &[f64], load: &[(f64, f64)], mu: f64) -> Projected {
    let n = a.len();
    let mut p = Projected {
        state: vec![ContactState::Stick; n],
        force: vec![0.0; n],
        stick_weight: vec![0.0; n],
        slip_slope: vec![0.0; n],
        transitions: Vec::new(),
    };
    for j in 0..n {
        if a[j].abs() <= mu * load[j].0 {
            p.force[j] = a[j];
            p.stick_weight[j] = 1.0;
        } else {
            p.state[j] = ContactState::Slip;
            p.force[j] = a[j].signum() * mu * load[j].0;
            p.slip_slope[j] = a[j].signum() * mu * load[j].1;
        }
    }
    p
}

/// (S3) with the memory rule and the breakaway blending of the module docs. `a` is the
/// multiplier prediction (S2), `b` the breakaway indicator (module docs, Breakaway), `load[j]`
/// is `(N, N')` at sample `j`.
pub(super) fn project_samples(
    a: &[f64],
    b: &[f64],
    load: &[(f64, f64)],
    mu: f64,
    ratio: f64,
) -> Projected {
    let n = a.len();
    // The relay: stuck until |b| > μ_s N, sliding until |a| <= μ N. Two sweeps round the
    // period: the first settles the state the second starts from.
    let next = |prev: ContactState, j: usize| match prev {
        ContactState::Stick if b[j].abs() > ratio * mu * load[j].0 => ContactState::Slip,
        ContactState::Slip if a[j].abs() <= mu * load[j].0 => ContactState::Stick,
        s => s,
    };
    let mut prev = ContactState::Stick;
    for j in 0..n {
        prev = next(prev, j);
    }
    let mut state = vec![ContactState::Stick; n];
    for (j, s) in state.iter_mut().enumerate() {
        prev = next(prev, j);
        *s = prev;
    }
    let mut p = Projected {
        force: vec![0.0; n],
        stick_weight: vec![0.0; n],
        slip_slope: vec![0.0; n],
        transitions: Vec::new(),
        state,
    };
    let slip = |j: usize| a[j].signum() * mu * load[j].0;
    for j in 0..n {
        match p.state[j] {
            ContactState::Stick => {
                p.force[j] = a[j];
                p.stick_weight[j] = 1.0;
            }
            ContactState::Slip => {
                p.force[j] = slip(j);
                p.slip_slope[j] = a[j].signum() * mu * load[j].1;
            }
        }
    }
    for j1 in 0..n {
        let j0 = (j1 + n - 1) % n;
        let (s0, s1) = (p.state[j0], p.state[j1]);
        if s0 == s1 {
            continue;
        }
        // Breakaway at |b| = μ_s N (θ grows with τ), or sticking at |a| = μ N (θ falls).
        let (coefficient, orientation, ind) = if s0 == ContactState::Stick {
            (ratio * mu, 1.0, b)
        } else {
            (mu, -1.0, a)
        };
        let x = |j: usize| ind[j].abs() - coefficient * load[j].0;
        let (x0, x1) = (x(j0), x(j1));
        if x0 == x1 || x0 * x1 > 0.0 {
            continue;
        }
        // The crossing at j0 + τ; cell j spans [j - 1/2, j + 1/2]; θ the stuck share.
        let tau = x0 / (x0 - x1);
        let (blended, theta) = match (orientation > 0.0, tau >= 0.5) {
            (true, true) => (j1, tau - 0.5),
            (true, false) => (j0, 0.5 + tau),
            (false, true) => (j1, 1.5 - tau),
            (false, false) => (j0, 0.5 - tau),
        };
        let (fst, fsl) = (a[blended], slip(blended));
        p.force[blended] = theta * fst + (1.0 - theta) * fsl;
        p.stick_weight[blended] = theta;
        p.slip_slope[blended] = (1.0 - theta) * a[blended].signum() * mu * load[blended].1;
        p.transitions.push(Transition {
            j0,
            j1,
            blended,
            jump: orientation * (fst - fsl),
            x: [x0, x1],
            sign: [ind[j0].signum(), ind[j1].signum()],
            coefficient,
            breakaway: orientation > 0.0,
        });
    }
    p
}
