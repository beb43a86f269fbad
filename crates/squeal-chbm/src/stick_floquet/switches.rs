//! The switches of a DLFT cycle's pairs, located between the balance's time samples (module
//! docs of [`super`], "Phases from the DLFT cycle").

use super::StickSlipCycle;
use super::StickSlipModel;
use crate::floquet::FloquetError;
use squeal_hbm::{ContactState, FrictionContact, NormalLoad};
use std::f64::consts::PI;

/// A pair's phase.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Phase {
    Open,
    Stick,
    /// Sliding with the force's sign.
    Slip(f64),
}

/// A switch of one pair at time `t` into `to`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Switch {
    pub(super) t: f64,
    pub(super) pair: usize,
    pub(super) to: Phase,
}

/// The cycle's signals of one pair at a time: `(δ, γ, γ', N)`.
pub(super) fn pair_signals(
    c: &FrictionContact,
    x: &[f64],
    v: &[f64],
    acc: &[f64],
) -> (f64, f64, f64, (f64, f64)) {
    let dot = |sv: &[(usize, f64)], y: &[f64]| sv.iter().map(|&(i, a)| a * y[i]).sum::<f64>();
    let (delta, load) = match &c.normal {
        NormalLoad::Constant(n) => (1.0, (*n, 0.0)),
        NormalLoad::Penalty {
            normal,
            offset,
            k_linear,
            k_cubic,
        } => {
            let d = dot(normal, x) + offset;
            let l = if d > 0.0 {
                (
                    k_linear * d + k_cubic * d.powi(3),
                    k_linear + 3.0 * k_cubic * d * d,
                )
            } else {
                (0.0, 0.0)
            };
            (d, l)
        }
    };
    (
        delta,
        c.sliding_speed + dot(&c.direction, v),
        dot(&c.direction, acc),
        load,
    )
}

/// `x_n`, `x_n'`, `x_n''` at time `t`.
pub(super) fn state_at(cycle: &StickSlipCycle<'_>, t: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let l = &cycle.layout;
    let nn = l.n_dofs();
    let (mut x, mut v, mut a) = (vec![0.0; nn], vec![0.0; nn], vec![0.0; nn]);
    let theta = cycle.omega * t;
    x.copy_from_slice(&cycle.u[..nn]);
    for k in 1..=l.n_harmonics() {
        let kw = k as f64 * cycle.omega;
        let (s, co) = (k as f64 * theta).sin_cos();
        let uc = &cycle.u[(2 * k - 1) * nn..2 * k * nn];
        let us = &cycle.u[2 * k * nn..(2 * k + 1) * nn];
        for i in 0..nn {
            let p = uc[i] * co + us[i] * s;
            x[i] += p;
            v[i] += kw * (-uc[i] * s + us[i] * co);
            a[i] -= kw * kw * p;
        }
    }
    (x, v, a)
}

/// Every pair's switches over one period, sorted by time, and each pair's phase at `t = 0`.
pub(super) fn switches(
    model: &StickSlipModel<'_>,
    cycle: &StickSlipCycle<'_>,
) -> Result<(Vec<Switch>, Vec<Phase>), FloquetError> {
    let np = model.contacts.len();
    if cycle.states.len() != np || cycle.predicted.len() != np {
        return Err(FloquetError::BadOption(
            "one state and multiplier record per friction contact",
        ));
    }
    let ns = cycle.states.first().map_or(0, |s| s.len());
    if ns < 2
        || cycle.states.iter().any(|s| s.len() != ns)
        || cycle.predicted.iter().any(|s| s.len() != ns)
    {
        return Err(FloquetError::BadOption(
            "the contacts' state records must have the same number of samples, at least 2",
        ));
    }
    let period = 2.0 * PI / cycle.omega;
    let dt = period / ns as f64;
    // (δ, γ, |a| − μN) per pair per sample.
    let mut sig = vec![Vec::with_capacity(ns); np];
    let mut phases = vec![Vec::with_capacity(ns); np];
    for j in 0..ns {
        let (x, v, a) = state_at(cycle, j as f64 * dt);
        for (p, c) in model.contacts.iter().enumerate() {
            let (d, g, _, (n, _)) = pair_signals(c, &x, &v, &a);
            let pa = cycle.predicted[p][j];
            sig[p].push((d, g, pa.abs() - c.mu * n));
            phases[p].push(if d <= 0.0 {
                Phase::Open
            } else if cycle.states[p][j] == ContactState::Stick {
                Phase::Stick
            } else {
                Phase::Slip(if pa >= 0.0 { 1.0 } else { -1.0 })
            });
        }
    }
    let frac = |a: f64, b: f64| {
        if (a - b).abs() > 0.0 && a * b <= 0.0 {
            (a / (a - b)).clamp(0.0, 1.0)
        } else {
            0.5
        }
    };
    let mut out = Vec::new();
    for p in 0..np {
        for j in 0..ns {
            let k = (j + 1) % ns;
            let (from, to) = (phases[p][j], phases[p][k]);
            if from == to {
                continue;
            }
            let (s0, s1) = (sig[p][j], sig[p][k]);
            let tau = match (from, to) {
                (Phase::Open, _) | (_, Phase::Open) => frac(s0.0, s1.0),
                (Phase::Slip(_), Phase::Slip(_)) => frac(s0.1, s1.1),
                _ => frac(s0.2, s1.2),
            };
            out.push(Switch {
                t: (j as f64 + tau) * dt,
                pair: p,
                to,
            });
        }
    }
    out.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.pair.cmp(&b.pair)));
    let start = phases.iter().map(|ph| ph[0]).collect();
    Ok((out, start))
}
