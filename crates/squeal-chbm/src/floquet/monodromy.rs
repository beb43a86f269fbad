//! Floquet multipliers from the monodromy matrix: the variational equations integrated over one period (the second method, against which Hill's method is checked).

use super::*;

/// The variational equations in first-order form `[y; y']' = A(t) [y; y']`.
pub(super) struct Variational<'a> {
    pub(super) mb: &'a ModalBrake,
    pub(super) cycle: CycleRef<'a>,
    pub(super) velocity: bool,
}

impl Variational<'_> {
    pub(super) fn jacobians(&self, t: f64) -> (Mat<f64>, Option<Mat<f64>>) {
        let nn = self.mb.nl();
        let (mut x, mut v) = (vec![0.0; nn], vec![0.0; nn]);
        let theta = self.cycle.omega * t;
        // The layout and length were checked by `monodromy`.
        let _ = self
            .cycle
            .layout
            .displacement_at(self.cycle.u, theta, &mut x);
        let _ = self
            .cycle
            .layout
            .velocity_at(self.cycle.u, self.cycle.omega, theta, &mut v);
        self.mb
            .reduced_jacobians(&x, self.velocity.then_some(&v[..]))
    }

    /// `Φ_nᵀ J Φ_n` (modal, `n × n`).
    pub(super) fn modal(&self, j: &Mat<f64>) -> Mat<f64> {
        let pn = &self.mb.phi_n;
        let jp = j * pn;
        pn.transpose() * &jp
    }
}

impl OdeSystem for Variational<'_> {
    fn dim(&self) -> usize {
        2 * self.mb.modes()
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.mb.modes();
        let nn = self.mb.nl();
        let (q, v) = y.split_at(n);
        let (jx, jv) = self.jacobians(t);
        let pn = &self.mb.phi_n;
        let xn: Vec<f64> = (0..nn)
            .map(|i| (0..n).map(|j| pn[(i, j)] * q[j]).sum())
            .collect();
        let vn: Vec<f64> = (0..nn)
            .map(|i| (0..n).map(|j| pn[(i, j)] * v[j]).sum())
            .collect();
        let mut g: Vec<f64> = (0..nn)
            .map(|i| (0..nn).map(|j| jx[(i, j)] * xn[j]).sum())
            .collect();
        if let Some(jv) = &jv {
            for (i, gi) in g.iter_mut().enumerate() {
                *gi += (0..nn).map(|j| jv[(i, j)] * vn[j]).sum::<f64>();
            }
        }
        dy[..n].copy_from_slice(v);
        for k in 0..n {
            let mut a = -self.mb.omega[k].powi(2) * q[k];
            match self.mb.damping.diagonal() {
                Some(d) => a -= d[k] * v[k],
                None => {
                    a -= (0..n)
                        .map(|j| self.mb.damping.entry(k, j) * v[j])
                        .sum::<f64>()
                }
            }
            a -= (0..nn).map(|i| pn[(i, k)] * g[i]).sum::<f64>();
            dy[n + k] = a;
        }
    }

    fn jacobian(&self, t: f64, _y: &[f64], jac: faer::MatMut<'_, f64>) {
        let (jx, jv) = self.jacobians(t);
        let kv = jv.as_ref().map(|m| self.modal(m));
        state_jacobian(self.mb, &self.modal(&jx), kv.as_ref(), jac);
    }
}

/// The monodromy matrix's result.
#[derive(Clone, Debug)]
pub struct MonodromyFloquet {
    /// All `2n` exponents (principal logarithms of the multipliers over `T`), `Re σ`
    /// descending.
    pub exponents: Vec<Exponent>,
    /// BDF steps over all columns.
    pub steps: usize,
    /// Wall time.
    pub time: Duration,
}

impl MonodromyFloquet {
    /// The non-trivial exponent of largest real part.
    pub fn leading(&self) -> Option<Exponent> {
        self.exponents.iter().copied().find(|e| !e.trivial)
    }
}

/// Options of [`monodromy`]: the BDF tolerances of each column's integration.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct MonodromyOptions {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance (the columns start as unit vectors).
    pub atol: f64,
    /// Highest BDF order.
    pub max_order: usize,
}

impl Default for MonodromyOptions {
    fn default() -> Self {
        Self {
            rtol: 1e-10,
            atol: 1e-12,
            max_order: 5,
        }
    }
}

/// The monodromy matrix of the variational equations along `cycle`, each of its `2n` columns
/// integrated over one period by [`squeal_ode`]'s BDF (in parallel; the bits do not depend on
/// the thread count), and the BDF steps over all columns.
pub fn monodromy_matrix(
    mb: &ModalBrake,
    cycle: &CycleRef<'_>,
    opts: &MonodromyOptions,
) -> Result<(Mat<f64>, usize), FloquetError> {
    cycle
        .layout
        .check_len("cycle coefficients", cycle.u.len())?;
    let sys = Variational {
        mb,
        cycle: *cycle,
        velocity: mb.velocity_dependent(),
    };
    let dim = sys.dim();
    let period = 2.0 * PI / cycle.omega;
    let bdf_opts = {
        let mut o = BdfOptions::default();
        o.rtol = opts.rtol;
        o.atol = Atol::Scalar(opts.atol);
        o.max_order = opts.max_order;
        o
    };
    let columns: Vec<Result<(Vec<f64>, usize), FloquetError>> = (0..dim)
        .into_par_iter()
        .map(|c| {
            let mut y0 = vec![0.0; dim];
            y0[c] = 1.0;
            let mut bdf = Bdf::new(&sys, 0.0, &y0, period, &bdf_opts)?;
            while !bdf.is_finished() {
                bdf.step()?;
            }
            Ok((bdf.y().to_vec(), bdf.stats().steps))
        })
        .collect();
    let mut m = Mat::<f64>::zeros(dim, dim);
    let mut steps = 0;
    for (c, col) in columns.into_iter().enumerate() {
        let (y, s) = col?;
        steps += s;
        for (i, v) in y.iter().enumerate() {
            m[(i, c)] = *v;
        }
    }
    Ok((m, steps))
}

/// Floquet multipliers from the monodromy matrix of the variational equations
/// ([`monodromy_matrix`]).
pub fn monodromy(
    mb: &ModalBrake,
    cycle: &CycleRef<'_>,
    opts: &MonodromyOptions,
) -> Result<MonodromyFloquet, FloquetError> {
    let t0 = Instant::now();
    let (m, steps) = monodromy_matrix(mb, cycle, opts)?;
    let dim = m.nrows();
    let period = 2.0 * PI / cycle.omega;
    let evd = m.eigen().map_err(|_| FloquetError::Eigen {
        what: "monodromy matrix",
    })?;
    let s = evd.S();
    let mut exponents: Vec<Exponent> = (0..dim)
        .map(|i| {
            let rho = s[i];
            Exponent {
                sigma: rho.ln() / period,
                multiplier: rho,
                trivial: false,
            }
        })
        .collect();
    // The trivial multiplier: the one nearest 1.
    if let Some(i) = (0..dim).min_by(|&a, &b| {
        (exponents[a].multiplier - 1.0)
            .norm()
            .total_cmp(&(exponents[b].multiplier - 1.0).norm())
    }) {
        exponents[i].trivial = true;
    }
    exponents.sort_by(|a, b| b.sigma.re.total_cmp(&a.sigma.re));
    Ok(MonodromyFloquet {
        exponents,
        steps,
        time: t0.elapsed(),
    })
}
