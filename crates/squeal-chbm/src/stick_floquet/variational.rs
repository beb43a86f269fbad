//! The variational equations of one phase, `Y' = A(t) Y` with `A = A₀ + [0; Lᵀ] W(t)`, and
//! the solves of the SDIRK stages by Woodbury on the rank-`n_nl` coupling (module docs of
//! [`super`], "Integration").

use super::switches::{Phase, pair_signals, state_at};
use super::{LinearPart, StickSlipCycle, StickSlipModel, mm, mtm};
use faer::Mat;
use faer::linalg::solvers::Solve;
use squeal_hbm::NormalLoad;

/// The pieces of the variational equations that do not change within a phase.
pub(super) struct Phases<'m, 'a> {
    pub(super) model: &'m StickSlipModel<'a>,
    pub(super) n: usize,
    /// `b_p = Lᵀ h_p` (`n × 1` each).
    pub(super) b: Vec<Mat<f64>>,
    /// `h_p` dense (`n_nl`).
    h: Vec<Vec<f64>>,
    /// `g_p` dense (`n_nl`; zero for a constant load).
    g: Vec<Vec<f64>>,
}

impl<'m, 'a> Phases<'m, 'a> {
    pub(super) fn new(model: &'m StickSlipModel<'a>) -> Self {
        let nn = model.lift.nrows();
        let dense = |sv: &[(usize, f64)]| {
            let mut v = vec![0.0; nn];
            for &(i, a) in sv {
                v[i] += a;
            }
            v
        };
        let h: Vec<Vec<f64>> = model.contacts.iter().map(|c| dense(&c.direction)).collect();
        let g = model
            .contacts
            .iter()
            .map(|c| match &c.normal {
                NormalLoad::Constant(_) => vec![0.0; nn],
                NormalLoad::Penalty { normal, .. } => dense(normal),
            })
            .collect();
        let b = h
            .iter()
            .map(|hp| {
                let hm = Mat::from_fn(nn, 1, |i, _| hp[i]);
                mtm(&model.lift, &hm)
            })
            .collect();
        Self {
            model,
            n: model.lift.ncols(),
            b,
            h,
            g,
        }
    }

    /// `B` of the stuck pairs, `(BᵀB)⁻¹`.
    pub(super) fn stuck(&self, phase: &[Phase]) -> Option<(Mat<f64>, Mat<f64>)> {
        let idx: Vec<usize> = (0..phase.len())
            .filter(|&p| phase[p] == Phase::Stick)
            .collect();
        if idx.is_empty() {
            return None;
        }
        let bm = Mat::from_fn(self.n, idx.len(), |i, j| self.b[idx[j]][(i, 0)]);
        let btb = mtm(&bm, &bm);
        let inv = btb
            .partial_piv_lu()
            .solve(Mat::<f64>::identity(idx.len(), idx.len()));
        Some((bm, inv))
    }

    /// `y ← P y` (rows of velocities), `P = I − B (BᵀB)⁻¹ Bᵀ`.
    pub(super) fn project(&self, stuck: &Option<(Mat<f64>, Mat<f64>)>, y: &mut Mat<f64>) {
        if let Some((bm, inv)) = stuck {
            let c = mm(inv, &mtm(bm, y));
            let d = mm(bm, &c);
            for j in 0..y.ncols() {
                for i in 0..y.nrows() {
                    y[(i, j)] -= d[(i, j)];
                }
            }
        }
    }

    /// `W(t)` (`n_nl × 2n`) with `A(t) = A₀ + [0; Lᵀ] W(t)` (module docs).
    pub(super) fn coupling(
        &self,
        cycle: &StickSlipCycle<'_>,
        phase: &[Phase],
        stuck: &Option<(Mat<f64>, Mat<f64>)>,
        t: f64,
    ) -> Mat<f64> {
        let m = self.model;
        let (x, v, a) = state_at(cycle, t);
        let mut j = (m.smooth_jacobian)(&x);
        for (p, c) in m.contacts.iter().enumerate() {
            if let Phase::Slip(s) = phase[p] {
                let (_, _, _, (_, dn)) = pair_signals(c, &x, &v, &a);
                let f = c.mu * s * dn;
                if f != 0.0 {
                    for (r, hr) in self.h[p].iter().enumerate() {
                        if *hr != 0.0 {
                            for (q, gq) in self.g[p].iter().enumerate() {
                                j[(r, q)] += f * hr * gq;
                            }
                        }
                    }
                }
            }
        }
        let jl = mm(&j, &m.lift);
        let n = self.n;
        let nn = m.lift.nrows();
        let mut w = Mat::zeros(nn, 2 * n);
        for c in 0..n {
            for r in 0..nn {
                w[(r, c)] = -jl[(r, c)];
            }
        }
        if let Some((bm, inv)) = stuck {
            // H_s (BᵀB)⁻¹ Bᵀ [K + Lᵀ J L, C].
            let mut t1 = m.stiffness.dense();
            let ljl = mtm(&m.lift, &jl);
            for c in 0..n {
                for r in 0..n {
                    t1[(r, c)] += ljl[(r, c)];
                }
            }
            let bk = mtm(bm, &t1);
            let bc = mtm(bm, &m.damping.dense());
            let idx: Vec<usize> = (0..phase.len())
                .filter(|&p| phase[p] == Phase::Stick)
                .collect();
            let hs = Mat::from_fn(nn, idx.len(), |i, k| self.h[idx[k]][i]);
            let hg = mm(&hs, inv);
            let wx = mm(&hg, &bk);
            let wv = mm(&hg, &bc);
            for c in 0..n {
                for r in 0..nn {
                    w[(r, c)] += wx[(r, c)];
                    w[(r, n + c)] += wv[(r, c)];
                }
            }
        }
        w
    }

    /// `A(t) Y`.
    pub(super) fn apply(&self, w: &Mat<f64>, y: &Mat<f64>) -> Mat<f64> {
        let n = self.n;
        let m = self.model;
        let top = y.subrows(0, n).to_owned();
        let bot = y.subrows(n, n).to_owned();
        let kt = m.stiffness.apply(&top);
        let cb = m.damping.apply(&bot);
        let lw = mtm(&m.lift, &mm(w, y));
        Mat::from_fn(2 * n, y.ncols(), |i, j| {
            if i < n {
                bot[(i, j)]
            } else {
                let r = i - n;
                -kt[(r, j)] - cb[(r, j)] + lw[(r, j)]
            }
        })
    }

    /// `(I − c A₀)⁻¹ R` (`c = γh`): `b = S⁻¹ (r₂ − c K r₁)`, `a = r₁ + c b`,
    /// `S = I + c C + c² K`.
    pub(super) fn solve0(&self, s: &SFactor, c: f64, r: &Mat<f64>) -> Mat<f64> {
        let n = self.n;
        let r1 = r.subrows(0, n).to_owned();
        let kr = self.model.stiffness.apply(&r1);
        let rhs = Mat::from_fn(n, r.ncols(), |i, j| r[(n + i, j)] - c * kr[(i, j)]);
        let b = s.solve(&rhs);
        Mat::from_fn(2 * n, r.ncols(), |i, j| {
            if i < n {
                r1[(i, j)] + c * b[(i, j)]
            } else {
                b[(i - n, j)]
            }
        })
    }

    /// `(I − c A(t))⁻¹ R` by Woodbury on `A = A₀ + U W`, `U = [0; Lᵀ]`.
    pub(super) fn solve(&self, s: &SFactor, c: f64, w: &Mat<f64>, r: &Mat<f64>) -> Mat<f64> {
        let n = self.n;
        let nn = w.nrows();
        let z = self.solve0(s, c, r);
        let u = Mat::from_fn(2 * n, nn, |i, j| {
            if i < n {
                0.0
            } else {
                self.model.lift[(j, i - n)]
            }
        });
        let xu = self.solve0(s, c, &u);
        let mut cap = mm(w, &xu);
        for j in 0..nn {
            for i in 0..nn {
                cap[(i, j)] = if i == j { 1.0 } else { 0.0 } - c * cap[(i, j)];
            }
        }
        let wz = mm(w, &z);
        let y = cap.partial_piv_lu().solve(&wz);
        let corr = mm(&xu, &y);
        Mat::from_fn(2 * n, r.ncols(), |i, j| z[(i, j)] + c * corr[(i, j)])
    }

    pub(super) fn s_factor(&self, c: f64) -> SFactor {
        let m = self.model;
        match (&m.stiffness, &m.damping) {
            (LinearPart::Diagonal(k), LinearPart::Diagonal(d)) => SFactor::Diagonal(
                k.iter()
                    .zip(d)
                    .map(|(k, d)| 1.0 + c * d + c * c * k)
                    .collect(),
            ),
            (k, d) => {
                let (k, d) = (k.dense(), d.dense());
                let s = Mat::from_fn(self.n, self.n, |i, j| {
                    (if i == j { 1.0 } else { 0.0 }) + c * d[(i, j)] + c * c * k[(i, j)]
                });
                SFactor::Dense(s.partial_piv_lu())
            }
        }
    }
}

pub(super) enum SFactor {
    Diagonal(Vec<f64>),
    Dense(faer::linalg::solvers::PartialPivLu<f64>),
}

impl SFactor {
    pub(super) fn solve(&self, r: &Mat<f64>) -> Mat<f64> {
        match self {
            SFactor::Diagonal(d) => Mat::from_fn(r.nrows(), r.ncols(), |i, j| r[(i, j)] / d[i]),
            SFactor::Dense(lu) => lu.solve(r),
        }
    }
}
