//! Bench binary: a 316-state stiff oscillatory system shaped like the
//! reduced brake, integrated for N cycles of 4.4 kHz (default 1000).
//!
//! Model (x: 158 physical dofs, y = (x, v), 316 states):
//! `x'' + C x' + K x + Q_u g(q_u, q_u') + k3 x_0^3 e_0 = 0`, with
//! `K = Q diag(w_j^2) Q^T`, `C = Q diag(2 zeta w_j) Q^T` (Q dense orthogonal:
//! three Householder reflections), 158 modes log-spaced 1 kHz..150 kHz,
//! zeta = 1%; mode u at 4.4 kHz has no linear damping but the van der Pol
//! term `g = -2 eps w_u (1 - q_u^2 / a^2) q_u'` (eps = 0.005, a = 0.5:
//! self-excited, saturating at |q_u| ~ 1); a cubic spring at dof 0 couples
//! all modes. Start: equilibrium + 1e-3 along mode u.
//!
//! Run: `cargo bench -p squeal-ode --bench brake_like [-- CYCLES]`.

use std::time::Instant;

use faer::linalg::matmul::matmul;
use faer::{Accum, ColMut, ColRef, Mat, MatMut, Par};
use squeal_ode::{Atol, Bdf, BdfOptions, OdeSystem, SteadyOptions, run_to_steady_state};

const N_DOF: usize = 158;
const F_UNSTABLE: f64 = 4400.0;
const EPS: f64 = 0.005;
const A_VDP: f64 = 0.5;
const K3: f64 = 1.2e9;

struct BrakeLike {
    k: Mat<f64>,
    c: Mat<f64>,
    /// `[K C]` (N_DOF x 2 N_DOF) for the rhs mat-vec.
    kc: Mat<f64>,
    /// Unstable mode shape (column u of Q).
    qu: Vec<f64>,
    wu: f64,
}

/// Deterministic xorshift64* in [-1, 1).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let r = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D);
        (r >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

impl BrakeLike {
    fn new() -> Self {
        let n = N_DOF;
        // Q = H1 H2 H3 applied to the identity.
        let mut q = Mat::<f64>::identity(n, n);
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
        for _ in 0..3 {
            let v: Vec<f64> = (0..n).map(|_| rng.next()).collect();
            let vv: f64 = v.iter().map(|x| x * x).sum();
            for j in 0..n {
                let dot: f64 = (0..n).map(|i| v[i] * q[(i, j)]).sum();
                for i in 0..n {
                    q[(i, j)] -= 2.0 * v[i] * dot / vv;
                }
            }
        }
        let mut w: Vec<f64> = (0..n)
            .map(|j| {
                let f = 1000.0 * 150f64.powf(j as f64 / (n - 1) as f64);
                2.0 * std::f64::consts::PI * f
            })
            .collect();
        let u = w
            .iter()
            .enumerate()
            .min_by(|a, b| {
                let da = (a.1 - 2.0 * std::f64::consts::PI * F_UNSTABLE).abs();
                let db = (b.1 - 2.0 * std::f64::consts::PI * F_UNSTABLE).abs();
                da.total_cmp(&db)
            })
            .map_or(0, |(j, _)| j);
        w[u] = 2.0 * std::f64::consts::PI * F_UNSTABLE;
        let zeta: Vec<f64> = (0..n).map(|j| if j == u { 0.0 } else { 0.01 }).collect();
        let k = Mat::from_fn(n, n, |i, j| {
            (0..n).map(|m| q[(i, m)] * w[m] * w[m] * q[(j, m)]).sum()
        });
        let c = Mat::from_fn(n, n, |i, j| {
            (0..n)
                .map(|m| q[(i, m)] * 2.0 * zeta[m] * w[m] * q[(j, m)])
                .sum()
        });
        let qu = (0..n).map(|i| q[(i, u)]).collect();
        let kc = Mat::from_fn(
            n,
            2 * n,
            |i, j| if j < n { k[(i, j)] } else { c[(i, j - n)] },
        );
        Self {
            k,
            c,
            kc,
            qu,
            wu: w[u],
        }
    }

    fn modal_u(&self, x: &[f64]) -> f64 {
        self.qu.iter().zip(x).map(|(a, b)| a * b).sum()
    }
}

impl OdeSystem for BrakeLike {
    fn dim(&self) -> usize {
        2 * N_DOF
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let n = N_DOF;
        let (x, v) = y.split_at(n);
        let (q, qd) = (self.modal_u(x), self.modal_u(v));
        let g = -2.0 * EPS * self.wu * (1.0 - q * q / (A_VDP * A_VDP)) * qd;
        let (dx, dv) = dy.split_at_mut(n);
        dx.copy_from_slice(v);
        matmul(
            ColMut::from_slice_mut(dv).as_mat_mut(),
            Accum::Replace,
            self.kc.as_ref(),
            ColRef::from_slice(y).as_mat(),
            -1.0,
            Par::Seq,
        );
        for (d, q) in dv.iter_mut().zip(&self.qu) {
            *d -= q * g;
        }
        dy[n] -= K3 * x[0] * x[0] * x[0];
    }
    fn jacobian(&self, _t: f64, y: &[f64], mut jac: MatMut<'_, f64>) {
        let n = N_DOF;
        let (x, v) = y.split_at(n);
        let (q, qd) = (self.modal_u(x), self.modal_u(v));
        let a2 = A_VDP * A_VDP;
        let dg_dq = 4.0 * EPS * self.wu * q * qd / a2;
        let dg_dqd = -2.0 * EPS * self.wu * (1.0 - q * q / a2);
        jac.fill(0.0);
        for j in 0..n {
            jac[(j, n + j)] = 1.0;
            for i in 0..n {
                let outer = self.qu[i] * self.qu[j];
                jac[(n + i, j)] = -self.k[(i, j)] - dg_dq * outer;
                jac[(n + i, n + j)] = -self.c[(i, j)] - dg_dqd * outer;
            }
        }
        jac[(n, 0)] -= 3.0 * K3 * x[0] * x[0];
    }
}

fn options(sys: &BrakeLike, rtol: f64, max_order: usize) -> BdfOptions {
    // Absolute tolerance: 1% of a unit modal amplitude's scale, times rtol.
    let atol: Vec<f64> = (0..2 * N_DOF)
        .map(|i| {
            if i < N_DOF {
                1e-2 * rtol
            } else {
                1e-2 * rtol * sys.wu
            }
        })
        .collect();
    {
        let mut o = BdfOptions::default();
        o.rtol = rtol;
        o.atol = Atol::PerComponent(atol);
        o.max_order = max_order;
        o
    }
}

fn initial(sys: &BrakeLike) -> Vec<f64> {
    let mut y0 = vec![0.0; 2 * N_DOF];
    for (y, q) in y0.iter_mut().zip(&sys.qu) {
        *y = 1e-3 * q;
    }
    y0
}

fn main() {
    let cycles: f64 = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(1000.0);
    let steady_only = std::env::args().any(|a| a == "steady");
    let sys = BrakeLike::new();
    let t_end = cycles / F_UNSTABLE;
    if steady_only {
        for &(rtol, max_order) in &[(1e-6, 2), (1e-8, 5)] {
            steady_run(&sys, t_end, rtol, max_order);
        }
        return;
    }
    println!(
        "316-state brake-like system, {cycles} cycles of {F_UNSTABLE} Hz (t_end = {t_end:.4} s)"
    );
    println!(
        "{:>6} {:>5} {:>9} {:>10} {:>9} {:>9} {:>7} {:>7} {:>9} {:>10}",
        "rtol", "order", "wall [s]", "steps", "steps/cyc", "rej(err)", "rej(N)", "jac", "LU", "rhs"
    );
    for &(rtol, max_order) in &[(1e-6, 2), (1e-8, 2), (1e-6, 5), (1e-8, 5)] {
        let opts = options(&sys, rtol, max_order);
        let start = Instant::now();
        let mut bdf = match Bdf::new(&sys, 0.0, &initial(&sys), t_end, &opts) {
            Ok(b) => b,
            Err(e) => {
                println!("{rtol:>6.0e} {max_order:>5} failed to start: {e}");
                continue;
            }
        };
        let mut failure = None;
        while !bdf.is_finished() {
            if let Err(e) = bdf.step() {
                failure = Some(e);
                break;
            }
        }
        let wall = start.elapsed().as_secs_f64();
        let s = bdf.stats();
        println!(
            "{rtol:>6.0e} {max_order:>5} {wall:>9.2} {:>10} {:>9.1} {:>9} {:>7} {:>7} {:>9} {:>10}   orders {:?}",
            s.steps,
            s.steps as f64 / (bdf.t() * F_UNSTABLE),
            s.rejected_error,
            s.rejected_newton,
            s.jac_evals,
            s.lu_decomps,
            s.rhs_evals,
            s.order_histogram
        );
        if let Some(e) = failure {
            println!("        stopped: {e}");
        }
        println!(
            "        final modal amplitude q_u = {:.6}",
            sys.modal_u(bdf.y())
        );
    }
    // Steady-state detection on q_u.
    for &(rtol, max_order) in &[(1e-6, 2), (1e-8, 5)] {
        steady_run(&sys, t_end, rtol, max_order);
    }
}

/// Run to the steady limit cycle (spread 1e-4 over 10 cycles) and print it.
fn steady_run(sys: &BrakeLike, t_end: f64, rtol: f64, max_order: usize) {
    let opts = options(sys, rtol, max_order);
    let start = Instant::now();
    let result = Bdf::new(sys, 0.0, &initial(sys), t_end, &opts).and_then(|mut bdf| {
        let steady = {
            let mut o = SteadyOptions::default();
            o.rtol = 1e-4;
            o.cycles = 10;
            o.harmonics = 3;
            o
        };
        let r = run_to_steady_state(&mut bdf, |y: &[f64]| sys.modal_u(&y[..N_DOF]), &steady);
        r.map(|s| (s, *bdf.stats()))
    });
    let wall = start.elapsed().as_secs_f64();
    match result {
        Ok((s, st)) => println!(
            "steady state (rtol {rtol:.0e}, max order {max_order}, spread 1e-4 over 10 cycles): \
             {} cycles, frequency {:.4} Hz, q_u peak-to-peak {:.6}, {wall:.2} s wall, {} steps",
            s.cycles,
            1.0 / s.period,
            s.amplitude,
            st.steps
        ),
        Err(e) => println!("steady state not reached ({wall:.2} s wall): {e}"),
    }
}
