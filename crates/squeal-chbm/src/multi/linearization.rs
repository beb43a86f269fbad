//! The linearization of a motion with several base frequencies and the generalized CHBM's
//! constraints `Re λ_j = 0`, one per unstable eigenvalue (derivation in [`crate::multi`]).
//!
//! The motion is given by its time samples, whatever basis made them: a periodic cycle's
//! samples over one period (one phase each), or a torus' samples on a uniform grid of the
//! angles `(θ_1, θ_2)` (two phases each). Every sample carries the displacement and velocity
//! of the force's dofs and the phase `θ_j` of each base frequency at it; the samples must be
//! uniform in the phases (an AFT grid), so that means over them are the Fourier coefficients:
//! `X_j = mean(2 x e^{-iθ_j})` (the convention `x = Re(X e^{iθ})`, `X = U_c - i U_s` of
//! [`squeal_hbm::DescribingFunction`]), `F_j` the same of the force.

use faer::{Mat, c64};
use squeal_hbm::NonlinearForce;
use squeal_hbm::{EigenTrack, HbmError, LinearUpdate, LinearizedEigen, LocalJacobian};

/// One time sample of a motion: the force's dofs' displacement and velocity, and the phase of
/// each base frequency there (rad).
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// Displacement of the force's dofs.
    pub x: Vec<f64>,
    /// Velocity of the force's dofs.
    pub v: Vec<f64>,
    /// `θ_j` of each base frequency.
    pub phases: Vec<f64>,
}

/// Why a linearization cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum LinearizationError {
    /// No samples, or samples of the wrong sizes.
    #[error(
        "the motion's samples must be non-empty, each with {dofs} displacements and velocities and {phases} phases"
    )]
    Samples {
        /// The force's dofs.
        dofs: usize,
        /// The base frequencies.
        phases: usize,
    },
    /// A base frequency is not a positive finite number.
    #[error("base frequency {index} is {value} rad/s: give positive finite frequencies")]
    Frequency {
        /// Which one.
        index: usize,
        /// Its value.
        value: f64,
    },
}

/// The linearization `N(s) = N_K + s N_C` of a multi-frequency motion (module and
/// [`crate::multi`] documentation), on the force's dofs.
#[derive(Clone, Debug)]
pub struct MultiLinearization {
    /// `N_K`.
    pub n_k: Mat<f64>,
    /// `N_C`.
    pub n_c: Mat<f64>,
    /// The averaged tangent `K̄`, `C̄` it corrects.
    pub k_mean: Mat<f64>,
    /// See `k_mean`.
    pub c_mean: Mat<f64>,
    /// The base frequencies (rad/s).
    pub omegas: Vec<f64>,
    /// The motion's first harmonic at each base frequency.
    pub x: Vec<Vec<c64>>,
    /// The force's first harmonic at each base frequency.
    pub f: Vec<Vec<c64>>,
    /// Base frequencies whose condition was dropped (no amplitude, or dependent on the
    /// others'): for these `N` is the averaged tangent along the motion.
    pub dropped: Vec<usize>,
    /// An `n × 0` matrix: the update's empty low-rank factors.
    empty: Mat<f64>,
}

impl MultiLinearization {
    /// From the motion's samples (uniform in every phase) and its base frequencies.
    pub fn from_samples<F: NonlinearForce + ?Sized>(
        force: &F,
        omegas: &[f64],
        samples: &[Sample],
    ) -> Result<Self, LinearizationError> {
        let n = force.n_dofs();
        let m = omegas.len();
        let bad = || LinearizationError::Samples { dofs: n, phases: m };
        if samples.is_empty()
            || samples
                .iter()
                .any(|s| s.x.len() != n || s.v.len() != n || s.phases.len() != m)
        {
            return Err(bad());
        }
        for (index, &value) in omegas.iter().enumerate() {
            if !(value.is_finite() && value > 0.0) {
                return Err(LinearizationError::Frequency { index, value });
            }
        }
        let pattern = force.pattern();
        let velocity = force.depends_on_velocity();
        let (mut k_mean, mut c_mean) = (Mat::<f64>::zeros(n, n), Mat::<f64>::zeros(n, n));
        let mut x = vec![vec![c64::new(0.0, 0.0); n]; m];
        let mut f = vec![vec![c64::new(0.0, 0.0); n]; m];
        let (mut dx, mut dv, mut fs) = (
            vec![0.0; pattern.len()],
            vec![0.0; pattern.len()],
            vec![0.0; n],
        );
        let w = 1.0 / samples.len() as f64;
        for s in samples {
            dx.iter_mut().for_each(|v| *v = 0.0);
            dv.iter_mut().for_each(|v| *v = 0.0);
            fs.iter_mut().for_each(|v| *v = 0.0);
            force.eval(
                &s.x,
                &s.v,
                &mut fs,
                Some(LocalJacobian {
                    dfdx: &mut dx,
                    dfdxdot: &mut dv,
                }),
            );
            for (p, &(i, j)) in pattern.iter().enumerate() {
                k_mean[(i, j)] += w * dx[p];
                if velocity {
                    c_mean[(i, j)] += w * dv[p];
                }
            }
            for j in 0..m {
                let e = c64::new(s.phases[j].cos(), -s.phases[j].sin()) * (2.0 * w);
                for d in 0..n {
                    x[j][d] += e * s.x[d];
                    f[j][d] += e * fs[d];
                }
            }
        }
        Ok(Self::new(k_mean, c_mean, omegas.to_vec(), x, f))
    }

    /// From the averaged tangent `(K̄, C̄)` and each base frequency's first harmonics of the
    /// motion `x[j]` and of the force `f[j]`.
    pub fn new(
        k_mean: Mat<f64>,
        c_mean: Mat<f64>,
        omegas: Vec<f64>,
        x: Vec<Vec<c64>>,
        f: Vec<Vec<c64>>,
    ) -> Self {
        let n = k_mean.nrows();
        let ws = omegas.first().copied().unwrap_or(1.0);
        // Columns of B (length 2n) and of A (length n), kept when independent of the others
        // (Gram–Schmidt twice, with R recorded so that Δ = A R⁻¹ Qᵀ).
        let mut q: Vec<Vec<f64>> = Vec::new();
        let mut a_cols: Vec<Vec<f64>> = Vec::new();
        let mut r_rows: Vec<Vec<f64>> = Vec::new();
        let mut dropped = Vec::new();
        for (j, &wj) in omegas.iter().enumerate() {
            let r = wj / ws;
            let a: Vec<c64> = (0..n)
                .map(|i| {
                    f[j][i]
                        - (0..n)
                            .map(|c| x[j][c] * c64::new(k_mean[(i, c)], wj * c_mean[(i, c)]))
                            .sum::<c64>()
                })
                .collect();
            let b1: Vec<f64> = (0..2 * n)
                .map(|i| {
                    if i < n {
                        x[j][i].re
                    } else {
                        -r * x[j][i - n].im
                    }
                })
                .collect();
            let b2: Vec<f64> = (0..2 * n)
                .map(|i| {
                    if i < n {
                        x[j][i].im
                    } else {
                        r * x[j][i - n].re
                    }
                })
                .collect();
            let a1: Vec<f64> = a.iter().map(|v| v.re).collect();
            let a2: Vec<f64> = a.iter().map(|v| v.im).collect();
            let (q0, a0, r0) = (q.len(), a_cols.len(), r_rows.len());
            let mut ok = true;
            for (b, ac) in [(b1, a1), (b2, a2)] {
                match orthogonalize(&q, b) {
                    Some((qn, coeffs)) => {
                        q.push(qn);
                        a_cols.push(ac);
                        r_rows.push(coeffs);
                    }
                    None => ok = false,
                }
            }
            if !ok {
                q.truncate(q0);
                a_cols.truncate(a0);
                r_rows.truncate(r0);
                dropped.push(j);
            }
        }
        // Δ Q = A R⁻¹ with R upper triangular (column c of R is r_rows[c], length c + 1).
        let k = q.len();
        let mut g: Vec<Vec<f64>> = vec![vec![0.0; n]; k]; // columns of A R⁻¹
        for c in 0..k {
            let mut col = a_cols[c].clone();
            for p in 0..c {
                let rpc = r_rows[c][p];
                for i in 0..n {
                    col[i] -= rpc * g[p][i];
                }
            }
            let rcc = r_rows[c][c];
            g[c] = col.into_iter().map(|v| v / rcc).collect();
        }
        let mut n_k = k_mean.clone();
        let mut n_c = c_mean.clone();
        for c in 0..k {
            for i in 0..n {
                for p in 0..n {
                    n_k[(i, p)] += g[c][i] * q[c][p];
                    n_c[(i, p)] += g[c][i] * q[c][n + p] / ws;
                }
            }
        }
        Self {
            n_k,
            n_c,
            k_mean,
            c_mean,
            omegas,
            x,
            f,
            dropped,
            empty: Mat::zeros(n, 0),
        }
    }

    /// `N(iω) X` for a complex vector (a check of the conditions `N(iω_j) X_j = F_j`).
    pub fn apply(&self, omega: f64, v: &[c64]) -> Vec<c64> {
        let n = v.len();
        (0..n)
            .map(|i| {
                (0..n)
                    .map(|c| v[c] * c64::new(self.n_k[(i, c)], omega * self.n_c[(i, c)]))
                    .sum()
            })
            .collect()
    }

    /// The update a [`LinearizedEigen`] takes: `N` itself as the reference, no low-rank part.
    pub fn update(&self) -> LinearUpdate<'_> {
        LinearUpdate {
            k0: self.n_k.as_ref(),
            c0: self.n_c.as_ref(),
            left_k: self.empty.as_ref(),
            left_c: self.empty.as_ref(),
            right: self.empty.as_ref(),
        }
    }
}

/// `b` minus its projections on the orthonormal `q` (twice), normalized, with the
/// coefficients `[qᵀb…, |rest|]`; `None` when nothing is left (below `1e-10 |b|`).
fn orthogonalize(q: &[Vec<f64>], mut b: Vec<f64>) -> Option<(Vec<f64>, Vec<f64>)> {
    let size = b.iter().map(|v| v * v).sum::<f64>().sqrt();
    if !(size > 0.0 && size.is_finite()) {
        return None;
    }
    let mut coeffs = vec![0.0; q.len() + 1];
    for _ in 0..2 {
        for (c, qc) in q.iter().enumerate() {
            let d: f64 = qc.iter().zip(&b).map(|(a, v)| a * v).sum();
            coeffs[c] += d;
            b.iter_mut().zip(qc).for_each(|(v, a)| *v -= d * a);
        }
    }
    let rest = b.iter().map(|v| v * v).sum::<f64>().sqrt();
    if rest <= 1e-10 * size {
        return None;
    }
    coeffs[q.len()] = rest;
    Some((b.into_iter().map(|v| v / rest).collect(), coeffs))
}

/// The generalized CHBM's constraints: one eigenvalue per unstable mode, each followed from its
/// static value by its own tracker through the linearizations of successive motions; the
/// residual of mode `j` is `Re λ_j / |Im λ_j⁰|` (a damping ratio).
pub struct ModeConstraints<T> {
    trackers: Vec<T>,
    lambdas: Vec<c64>,
    scales: Vec<f64>,
}

impl<T: LinearizedEigen> ModeConstraints<T> {
    /// One tracker per unstable eigenvalue `lambdas0[j]` of the static solution.
    pub fn new(trackers: Vec<T>, lambdas0: &[c64]) -> Self {
        Self {
            scales: lambdas0.iter().map(|l| l.im.abs().max(1e-300)).collect(),
            lambdas: lambdas0.to_vec(),
            trackers,
        }
    }

    /// The eigenvalues followed so far (the last evaluation's).
    pub fn lambdas(&self) -> &[c64] {
        &self.lambdas
    }

    /// Follows every eigenvalue to the linearization `lin` and returns the residuals
    /// `Re λ_j / |Im λ_j⁰|`, with the tracks (vectors on the force's dofs, for gradients).
    pub fn evaluate(
        &mut self,
        lin: &MultiLinearization,
    ) -> Result<(Vec<f64>, Vec<EigenTrack>), HbmError> {
        let update = lin.update();
        let mut tracks = Vec::with_capacity(self.trackers.len());
        for (j, t) in self.trackers.iter_mut().enumerate() {
            let tr = t.track(&update, self.lambdas[j])?;
            self.lambdas[j] = tr.lambda;
            tracks.push(tr);
        }
        let r = self
            .lambdas
            .iter()
            .zip(&self.scales)
            .map(|(l, s)| l.re / s)
            .collect();
        Ok((r, tracks))
    }
}
