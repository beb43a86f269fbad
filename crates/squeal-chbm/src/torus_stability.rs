//! The stability of the brake's tori (issue 24, item 1): their Lyapunov exponents
//! ([`squeal_hbm::torus::lyapunov`], [`squeal_hbm::torus::transverse`]) from the linearized
//! modal equations along the torus.
//!
//! The modal equations (eq 11 with the springs moved into the linear part) are
//! `q̈ + D q̇ + Ω² q + Φ_nᵀ G(Φ_n q, Φ_n q̇) = Φᵀ F`; in the state `(q, q̇)` their Jacobian is
//! `J = [[0, I], [-Ω² - Φ_nᵀ K Φ_n, -D - Φ_nᵀ C Φ_n]]` with `K = ∂G/∂x_n`, `C = ∂G/∂ẋ_n` — the
//! Jacobian [`squeal_brake::dynamics::BrakeDynamics`] gives a time integration. On the torus
//! the contact sees the nonlinear dofs only through `y = Q_Rᵀ x_n` (the reduced coordinates of
//! [`crate::torus`]), so `K` and `C` are evaluated at `x_n = Q_R y(θ)`,
//! `ẋ_n = Q_R ẏ(θ)`, with `y(θ)` and `ẏ(θ)` from the torus' Fourier series, and
//! `Φ_nᵀ K Φ_n = (Φ_nᵀ Q_E)(Q_Eᵀ K Q_R)(Q_Rᵀ Φ_n)`: a product by `J` costs `O(n (q_R + q_E))`
//! instead of `O(n²)`. The exponents come out in 1/s.
//!
//! **The small matrix per pair.** A pair's Jacobian terms
//! ([`squeal_brake::model::ContactPair::jacobian_terms`]) are rank one in each block:
//! `K_p = (∂F_n/∂δ g + ∂F_t/∂δ h) gᵀ` and
//! `C_p = (∂F_n/∂δ' g + ∂F_t/∂δ' h) gᵀ + (∂F_n/∂v g + ∂F_t/∂v h) hᵀ` (`g`, `h` the pair's
//! normal and tangential rows), and `K = Σ_p K_p - K_s`. With the pair's projections
//! `Q_Eᵀ g`, `Q_Eᵀ h`, `Q_Rᵀ g`, `Q_Rᵀ h` computed once, `Q_Eᵀ K Q_R` at an angle costs a few
//! `q_E q_R` products per pair instead of forming the `n_nl × n_nl` Jacobian and two matrix
//! products: it is the same matrix to round-off (the test `the_fast_jacobian_is_the_dense_one`
//! in tests/chbm/multi.rs).
//!
//! **The torus' tangent directions** ([`squeal_hbm::torus::transverse::TorusTangents`]): the
//! modal motion on the torus is `q(θ) = Re Σ_e q_e e^{i k_e·θ}`
//! ([`crate::torus::modal_harmonics`], the torus analogue of eq 35), so
//! `∂q/∂θ_i = Re Σ_e i k_{e,i} q_e e^{i k_e·θ}` and
//! `∂q̇/∂θ_i = Re Σ_e (i k_{e,i})(i w_e) q_e e^{i k_e·θ}`, `w_e = k_e·ω`, in closed form.

use crate::torus::{TorusPoint, modal_harmonics};
use faer::{Mat, c64};
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::HbmError;
use squeal_hbm::torus::lyapunov::{
    LyapunovOptions, LyapunovSpectrum, TorusVariational, lyapunov_exponents,
};
use squeal_hbm::torus::transverse::{
    TorusTangents, TransverseOptions, TransverseSpectrum, transverse_exponents,
};
use squeal_hbm::torus::{TorusBasis, Truncation};

/// One pair's projections: `Q_Eᵀ g`, `Q_Eᵀ h` (`q_E` each), `Q_Rᵀ g`, `Q_Rᵀ h` (`q_R` each).
struct PairProjection {
    ge: Vec<f64>,
    he: Vec<f64>,
    gr: Vec<f64>,
    hr: Vec<f64>,
}

/// The brake's modal equations linearized along a torus (module docs).
pub struct BrakeVariational {
    mb: ModalBrake,
    basis: TorusBasis,
    coeffs: Vec<f64>,
    omega: [f64; 2],
    /// `Q_R` row-major (`n_nl × q_R`).
    qr: Vec<f64>,
    /// `Q_Rᵀ Φ_n` row-major (`q_R × n`) and `Φ_nᵀ Q_E` row-major (`n × q_E`).
    pr: Vec<f64>,
    pe: Vec<f64>,
    pairs: Vec<PairProjection>,
    /// `Q_Eᵀ K_s Q_R` row-major.
    spring: Vec<f64>,
    /// `Q_Eᵀ K Q_R` and `Q_Eᵀ C Q_R` at the current angles, row-major (`q_E × q_R`).
    k: Vec<f64>,
    c: Option<Vec<f64>>,
    ne: usize,
    nr: usize,
    /// Work: `x_n`, `ẋ_n`, `y`, `ẏ`.
    x: Vec<f64>,
    v: Vec<f64>,
    y: Vec<f64>,
    ydot: Vec<f64>,
}

fn row_major(m: &Mat<f64>) -> Vec<f64> {
    (0..m.nrows())
        .flat_map(|i| (0..m.ncols()).map(move |j| m[(i, j)]))
        .collect()
}

/// `Qᵀ s` for a sparse row `s` of the nonlinear dofs.
fn project(q: &Mat<f64>, s: &[(usize, f64)]) -> Vec<f64> {
    (0..q.ncols())
        .map(|k| s.iter().map(|&(i, a)| a * q[(i, k)]).sum())
        .collect()
}

impl BrakeVariational {
    /// The linearization of `mb`'s brake (at the torus' μ) along the torus `point` on `basis`.
    pub fn new(mb: &ModalBrake, basis: &TorusBasis, point: &TorusPoint) -> Result<Self, HbmError> {
        basis.check_len("torus coefficients", point.coeffs.len())?;
        let mut mb = mb.clone();
        mb.mu = point.mu;
        let (qe, qr) = crate::floquet::contact_bases(&mb);
        if qr.ncols() != basis.n_dofs() {
            return Err(HbmError::BadOption(
                "the torus' basis does not match the brake's reduced contact coordinates",
            ));
        }
        let (ne, nr, nn) = (qe.ncols(), qr.ncols(), qr.nrows());
        let pairs = mb
            .pairs
            .iter()
            .map(|p| PairProjection {
                ge: project(&qe, &p.normal),
                he: project(&qe, &p.tangent),
                gr: project(&qr, &p.normal),
                hr: project(&qr, &p.tangent),
            })
            .collect();
        let spring = row_major(&(qe.transpose() * &mb.k_s * &qr));
        let c = mb.velocity_dependent().then(|| vec![0.0; ne * nr]);
        Ok(Self {
            basis: basis.clone(),
            coeffs: point.coeffs.clone(),
            omega: point.omega,
            pr: row_major(&(qr.transpose() * &mb.phi_n)),
            pe: row_major(&(mb.phi_n.transpose() * &qe)),
            qr: row_major(&qr),
            pairs,
            spring,
            k: vec![0.0; ne * nr],
            c,
            ne,
            nr,
            x: vec![0.0; nn],
            v: vec![0.0; nn],
            y: vec![0.0; nr],
            ydot: vec![0.0; nr],
            mb,
        })
    }

    /// `out = Q_R y`.
    fn lift(qr: &[f64], nr: usize, y: &[f64], out: &mut [f64]) {
        for (o, row) in out.iter_mut().zip(qr.chunks_exact(nr)) {
            *o = row.iter().zip(y).map(|(a, b)| a * b).sum();
        }
    }
}

/// Work vectors up to this length live on the stack in [`BrakeVariational`]'s products.
const SMALL: usize = 64;

/// A zeroed work slice of length `len`: `stack`'s head when it fits, else `heap`.
fn work<'a>(stack: &'a mut [f64; SMALL], heap: &'a mut Vec<f64>, len: usize) -> &'a mut [f64] {
    if len <= SMALL {
        &mut stack[..len]
    } else {
        heap.resize(len, 0.0);
        heap
    }
}

/// `m += a bᵀ` (`m` row-major, `a.len()` rows).
fn add_outer(m: &mut [f64], s: f64, a: &[f64], b: &[f64]) {
    if s == 0.0 {
        return;
    }
    for (row, ai) in m.chunks_exact_mut(b.len()).zip(a) {
        let f = s * ai;
        row.iter_mut().zip(b).for_each(|(r, bj)| *r += f * bj);
    }
}

impl TorusVariational for BrakeVariational {
    fn dim(&self) -> usize {
        2 * self.mb.modes()
    }

    fn set_angles(&mut self, theta: [f64; 2]) -> Result<(), HbmError> {
        let nr = self.nr;
        self.basis
            .displacement_at(&self.coeffs, theta, &mut self.y)?;
        Self::lift(&self.qr, nr, &self.y, &mut self.x);
        let velocity = self.c.is_some();
        if velocity {
            self.basis
                .velocity_at(&self.coeffs, self.omega, theta, &mut self.ydot)?;
            Self::lift(&self.qr, nr, &self.ydot, &mut self.v);
        }
        self.k
            .iter_mut()
            .zip(&self.spring)
            .for_each(|(k, s)| *k = -s);
        if let Some(c) = self.c.as_mut() {
            c.fill(0.0);
        }
        for (p, pp) in self.mb.pairs.iter().zip(&self.pairs) {
            let kin = p.kinematics(&self.x, velocity.then_some(self.v.as_slice()));
            let r = p.law.response(self.mb.mu, &kin);
            let [n_d, n_r, n_v] = r.normal_derivatives;
            let [t_d, t_r, t_v] = r.tangential_derivatives;
            add_outer(&mut self.k, n_d, &pp.ge, &pp.gr);
            add_outer(&mut self.k, t_d, &pp.he, &pp.gr);
            if let Some(c) = self.c.as_mut() {
                add_outer(c, n_r, &pp.ge, &pp.gr);
                add_outer(c, t_r, &pp.he, &pp.gr);
                add_outer(c, n_v, &pp.ge, &pp.hr);
                add_outer(c, t_v, &pp.he, &pp.hr);
            }
        }
        Ok(())
    }

    fn apply(&self, v: &[f64], out: &mut [f64]) {
        let n = self.mb.modes();
        let (q, qd) = v.split_at(n);
        let (oq, ov) = out.split_at_mut(n);
        oq.copy_from_slice(qd);
        self.mb.damping.apply(qd, ov);
        for j in 0..n {
            ov[j] = -ov[j] - self.mb.omega[j] * self.mb.omega[j] * q[j];
        }
        // b = K_r (Q_Rᵀ Φ_n q) + C_r (Q_Rᵀ Φ_n q̇); out -= (Φ_nᵀ Q_E) b.
        let (ne, nr) = (self.ne, self.nr);
        let dot = |row: &[f64], x: &[f64]| row.iter().zip(x).map(|(a, b)| a * b).sum::<f64>();
        // Small work vectors on the stack (the brake's q_E, q_R are tens), else on the heap.
        let (mut sb, mut sa) = ([0.0; SMALL], [0.0; SMALL]);
        let (mut hb, mut ha) = (Vec::new(), Vec::new());
        let b = work(&mut sb, &mut hb, ne);
        let a = work(&mut sa, &mut ha, nr);
        for (ai, r) in a.iter_mut().zip(self.pr.chunks_exact(n)) {
            *ai = dot(r, q);
        }
        for (bi, row) in b.iter_mut().zip(self.k.chunks_exact(nr)) {
            *bi = dot(row, a);
        }
        if let Some(c) = &self.c {
            for (ai, r) in a.iter_mut().zip(self.pr.chunks_exact(n)) {
                *ai = dot(r, qd);
            }
            for (bi, row) in b.iter_mut().zip(c.chunks_exact(nr)) {
                *bi += dot(row, a);
            }
        }
        for (o, row) in ov.iter_mut().zip(self.pe.chunks_exact(ne)) {
            *o -= dot(row, b);
        }
    }

    fn apply_columns(&self, v: &[f64], out: &mut [f64]) {
        let dim = 2 * self.mb.modes();
        for (vg, og) in v.chunks(LANES * dim).zip(out.chunks_mut(LANES * dim)) {
            self.apply_lanes(vg, og);
        }
    }
}

/// Columns [`BrakeVariational::apply_columns`] multiplies together.
const LANES: usize = 4;

/// `out[l] += Σ_t m[i, t] x[t][l]` for every row `i` of `m` (row-major, `x.len()` columns) and
/// lane `l`, each lane summed in the order of a plain dot product from `-0.0` (what `Sum` for
/// `f64` does): lane `l` of row `i` gets the bits of `row · x_l`. `out[i]` must hold `-0.0`
/// for a plain product.
fn rows_times_lanes(m: &[f64], x: &[[f64; LANES]], out: &mut [[f64; LANES]]) {
    for (o, row) in out.iter_mut().zip(m.chunks_exact(x.len())) {
        let mut acc = *o;
        for (a, xt) in row.iter().zip(x) {
            for l in 0..LANES {
                acc[l] += a * xt[l];
            }
        }
        *o = acc;
    }
}

impl BrakeVariational {
    /// `out = J V` for up to [`LANES`] columns `v` at once: each column the bits of
    /// [`TorusVariational::apply`] (every sum in the same order), with each row of the
    /// projections read once for all columns and the columns' sums independent.
    fn apply_lanes(&self, v: &[f64], out: &mut [f64]) {
        let n = self.mb.modes();
        let cols = v.len() / (2 * n);
        let (ne, nr) = (self.ne, self.nr);
        // The columns' q and q̇ side by side: `qt[t][l]` is column l's q_t.
        let mut qt = vec![[0.0; LANES]; n];
        let mut qdt = vec![[0.0; LANES]; n];
        for (l, (vc, oc)) in v
            .chunks_exact(2 * n)
            .zip(out.chunks_exact_mut(2 * n))
            .enumerate()
        {
            let (q, qd) = vc.split_at(n);
            let (oq, ov) = oc.split_at_mut(n);
            oq.copy_from_slice(qd);
            self.mb.damping.apply(qd, ov);
            for j in 0..n {
                ov[j] = -ov[j] - self.mb.omega[j] * self.mb.omega[j] * q[j];
                qt[j][l] = q[j];
                qdt[j][l] = qd[j];
            }
        }
        let mut a = vec![[-0.0; LANES]; nr];
        let mut b = vec![[-0.0; LANES]; ne];
        rows_times_lanes(&self.pr, &qt, &mut a);
        rows_times_lanes(&self.k, &a, &mut b);
        if let Some(c) = &self.c {
            a.fill([-0.0; LANES]);
            rows_times_lanes(&self.pr, &qdt, &mut a);
            // `b_i += row · a` adds the finished dot product, as `apply` does.
            let mut bc = vec![[-0.0; LANES]; ne];
            rows_times_lanes(c, &a, &mut bc);
            for (bi, ci) in b.iter_mut().zip(&bc) {
                for l in 0..LANES {
                    bi[l] += ci[l];
                }
            }
        }
        let mut d = vec![[-0.0; LANES]; n];
        rows_times_lanes(&self.pe, &b, &mut d);
        for (l, oc) in out.chunks_exact_mut(2 * n).enumerate().take(cols) {
            for (o, dj) in oc[n..].iter_mut().zip(&d) {
                *o -= dj[l];
            }
        }
    }
}

/// [`BrakeVariational`] with the torus' tangent directions in closed form (module docs).
pub struct BrakeTangentFlow {
    flow: BrakeVariational,
    /// Each Fourier element's wave numbers, frequency and modal amplitudes.
    waves: Vec<([i64; 2], f64, Vec<c64>)>,
}

impl BrakeTangentFlow {
    /// The linearization along the torus `point` on `basis` (AFT grid `grid`, `None`: the
    /// basis' default) of `mb`'s brake, with the modal amplitudes of every Fourier element.
    pub fn new(
        mb: &ModalBrake,
        basis: &TorusBasis,
        grid: Option<[usize; 2]>,
        point: &TorusPoint,
    ) -> Result<Self, HbmError> {
        let flow = BrakeVariational::new(mb, basis, point)?;
        let truncation: Truncation = basis.truncation();
        let (b, q) = modal_harmonics(&flow.mb, truncation, grid, &point.coeffs, point.omega)?;
        let waves = q
            .into_iter()
            .enumerate()
            .map(|(e, qe)| (b.wave(e), b.frequency(e, point.omega), qe))
            .collect();
        Ok(Self { flow, waves })
    }
}

impl TorusVariational for BrakeTangentFlow {
    fn dim(&self) -> usize {
        self.flow.dim()
    }

    fn set_angles(&mut self, theta: [f64; 2]) -> Result<(), HbmError> {
        self.flow.set_angles(theta)
    }

    fn apply(&self, v: &[f64], out: &mut [f64]) {
        self.flow.apply(v, out)
    }

    fn apply_columns(&self, v: &[f64], out: &mut [f64]) {
        self.flow.apply_columns(v, out)
    }
}

impl TorusTangents for BrakeTangentFlow {
    fn tangents(&self, theta: [f64; 2], t1: &mut [f64], t2: &mut [f64]) -> Result<(), HbmError> {
        let n = self.flow.mb.modes();
        HbmError::check_dimension("tangent direction", 2 * n, t1.len())?;
        HbmError::check_dimension("tangent direction", 2 * n, t2.len())?;
        t1.fill(0.0);
        t2.fill(0.0);
        for (k, w, q) in &self.waves {
            let phase = k[0] as f64 * theta[0] + k[1] as f64 * theta[1];
            let (s, c) = phase.sin_cos();
            let rot = c64::new(c, s);
            for (i, t) in [(0, &mut *t1), (1, &mut *t2)] {
                let ki = k[i] as f64;
                if ki == 0.0 {
                    continue;
                }
                // ∂/∂θ_i of Re(q e^{iφ}) = Re(i k_i q e^{iφ}); of the velocity Re(-k_i w q e^{iφ}).
                for j in 0..n {
                    let z = q[j] * rot;
                    t[j] += -ki * z.im;
                    t[n + j] += -ki * w * z.re;
                }
            }
        }
        Ok(())
    }
}

/// The Lyapunov exponents of the torus `point` (on `basis`) of `mb`'s brake, in 1/s, by the
/// standard method ([`squeal_hbm::torus::lyapunov`]: every exponent integrated, the tangent
/// ones included): what `squeal branch` uses.
pub fn torus_lyapunov(
    mb: &ModalBrake,
    basis: &TorusBasis,
    point: &TorusPoint,
    opts: &LyapunovOptions,
) -> Result<LyapunovSpectrum, HbmError> {
    let mut sys = BrakeVariational::new(mb, basis, point)?;
    lyapunov_exponents(&mut sys, point.omega, opts)
}

/// The largest transverse Lyapunov exponents of the torus `point` (on `basis`, AFT grid
/// `grid`) of `mb`'s brake, in 1/s, with the torus' tangent directions known
/// ([`squeal_hbm::torus::transverse`]). Not what `squeal branch` uses: on the medium brake its
/// short records misjudged tori (docs/benchmarks.md); `squeal branch` uses [`torus_lyapunov`].
pub fn torus_transverse(
    mb: &ModalBrake,
    basis: &TorusBasis,
    grid: Option<[usize; 2]>,
    point: &TorusPoint,
    opts: &TransverseOptions,
) -> Result<TransverseSpectrum, HbmError> {
    let mut sys = BrakeTangentFlow::new(mb, basis, grid, point)?;
    transverse_exponents(&mut sys, point.omega, opts)
}

#[cfg(test)]
mod tests {
    //! The grouped evaluations must give the bits of the single ones: `squeal branch`'s tori,
    //! their envelopes and exponents must not change with how the products are grouped.
    use super::*;
    use crate::torus::{TorusPoint, closures_along_flow};
    use crate::{Contact, FrictionSystem};
    use squeal_brake::contact::VelocityDependent;

    /// Three 2-dof friction oscillators side by side: two penalty–Coulomb pairs (displacement
    /// only) and a velocity-weakening one (so the damping-like block `C` of the Jacobian is
    /// used); 6 nonlinear dofs, so that rows are left over after groups of 4.
    fn brake() -> ModalBrake {
        let m = Mat::<f64>::identity(6, 6);
        let c = Mat::from_fn(6, 6, |i, j| if i == j { 20.0 } else { 0.0 });
        let d = [1.0e6, 1.0e6, 4.0e6, 1.0e7, 1.3e6, 1.1e6];
        let k = Mat::from_fn(6, 6, |i, j| {
            if i == j {
                d[i]
            } else if i / 2 == j / 2 && i / 2 != 1 {
                1.0e5
            } else {
                0.0
            }
        });
        let a =
            Contact::penalty_coulomb(&[(1, 1.0)], &[(0, -1.0)], 3.0e5, 7.5e11).initial_gap(-2.0e-4);
        let law = VelocityDependent {
            k_linear: 2.0e7,
            k_cubic: 0.0,
            static_ratio: 1.6,
            decay_speed: 0.5,
        };
        let b = Contact::new(&[(3, -1.0)], &[(2, 1.0)], law).surface_speed(1.0);
        let e =
            Contact::penalty_coulomb(&[(5, 1.0)], &[(4, -1.0)], 2.0e5, 5.0e11).initial_gap(-1.0e-4);
        let sys = FrictionSystem::builder(m, c, k)
            .contact(a)
            .contact(b)
            .contact(e)
            .load(vec![0.0, 0.0, 0.0, -500.0, 0.0, 0.0])
            .build()
            .unwrap();
        ModalBrake::new(sys.brake(), sys.reference(), 0.3)
    }

    /// A quasi-periodic motion in the reduced coordinates (not a torus of the brake: the
    /// products only need some motion), with every coefficient non-zero.
    fn point(basis: &TorusBasis) -> TorusPoint {
        TorusPoint {
            mu: 0.3,
            omega: [1.1e3, 1.7e2],
            coeffs: (0..basis.len())
                .map(|i| 1e-5 * (((i * 7919) % 23) as f64 - 11.3) / (1 + i / 8) as f64)
                .collect(),
            pairs: Vec::new(),
            iterations: 0,
            residual: 0.0,
            parameter_rate: 0.0,
        }
    }

    #[test]
    fn grouped_products_are_the_single_products_bit_for_bit() {
        let mb = brake();
        let (_, qr) = crate::floquet::contact_bases(&mb);
        let basis = TorusBasis::new(qr.ncols(), Truncation::Box(3, 2)).unwrap();
        let mut sys = BrakeVariational::new(&mb, &basis, &point(&basis)).unwrap();
        assert!(
            sys.c.is_some(),
            "the velocity law must exercise J's C block"
        );
        let dim = sys.dim();
        // 9 columns: two full groups of 4 and a group of 1.
        let cols = 9;
        let v: Vec<f64> = (0..dim * cols)
            .map(|i| ((i * 37 % 101) as f64 - 50.0) * 1e-2)
            .collect();
        for theta in [[0.0, 0.0], [0.7, 2.1], [4.0, 5.5]] {
            sys.set_angles(theta).unwrap();
            let mut grouped = vec![f64::NAN; dim * cols];
            sys.apply_columns(&v, &mut grouped);
            let mut single = vec![f64::NAN; dim];
            for c in 0..cols {
                sys.apply(&v[c * dim..(c + 1) * dim], &mut single);
                let g = &grouped[c * dim..(c + 1) * dim];
                // Exactly equal (tolerance zero): the grouping must not reorder any sum.
                for (i, (a, b)) in g.iter().zip(&single).enumerate() {
                    assert_eq!(a.to_bits(), b.to_bits(), "column {c}, row {i}: {a} vs {b}");
                }
            }
        }
    }

    #[test]
    fn spring_rows_side_by_side_are_the_modal_brakes_force_bit_for_bit() {
        let mb = brake();
        let (qe, qr) = crate::floquet::contact_bases(&mb);
        let rc = crate::torus::ReducedContact::new(&mb, qe, qr);
        let nn = mb.nl();
        assert_eq!(nn % 4, 2, "rows must be left over after the groups of 4");
        let springs = (0..nn).flat_map(|i| (0..nn).map(move |j| (i, j)));
        // The preloaded pairs' springs (one normal dof each: diagonal entries).
        assert!(springs.filter(|&(i, j)| mb.k_s[(i, j)] != 0.0).count() >= 2);
        for s in [1.0, -0.3, 2.5] {
            let x: Vec<f64> = (0..nn).map(|i| s * 1e-5 * (i as f64 - 1.7)).collect();
            let v: Vec<f64> = (0..nn).map(|i| s * 1e-2 * (2.0 - i as f64)).collect();
            let (mut a, mut b) = (vec![0.0; nn], vec![0.0; nn]);
            rc.reduced_force(&x, Some(&v), &mut a);
            mb.add_reduced_force(&x, Some(&v), &mut b);
            // Exactly equal (tolerance zero): the same sums in the same order.
            for (i, (p, q)) in a.iter().zip(&b).enumerate() {
                assert_eq!(p.to_bits(), q.to_bits(), "dof {i}: {p} vs {q}");
            }
        }
    }

    #[test]
    fn all_pairs_closures_at_once_are_each_pairs_own_bit_for_bit() {
        let mb = brake();
        let (_, qr) = crate::floquet::contact_bases(&mb);
        let truncation = Truncation::Box(3, 2);
        let basis = TorusBasis::new(qr.ncols(), truncation).unwrap();
        let p = point(&basis);
        let (dt, samples) = (1e-4, 50);
        let got = closures_along_flow(&mb, &basis, &p.coeffs, p.omega, dt, samples).unwrap();
        // Each pair on its own: its scalar series evaluated sample by sample.
        let nr = qr.ncols();
        let scalar = TorusBasis::new(1, truncation).unwrap();
        assert_eq!(got.len(), mb.pairs.len());
        for (pair, signal) in mb.pairs.iter().zip(&got) {
            let row: Vec<f64> = (0..nr)
                .map(|k| pair.normal.iter().map(|&(i, g)| g * qr[(i, k)]).sum())
                .collect();
            let series: Vec<f64> = (0..basis.n_blocks())
                .map(|b| {
                    let v: f64 = (0..nr).map(|k| row[k] * p.coeffs[b * nr + k]).sum();
                    if b == 0 { v - pair.initial_gap } else { v }
                })
                .collect();
            assert_eq!(signal.len(), samples);
            let mut val = [0.0];
            for (j, s) in signal.iter().enumerate() {
                let t = j as f64 * dt;
                scalar
                    .displacement_at(&series, [p.omega[0] * t, p.omega[1] * t], &mut val)
                    .unwrap();
                // Exactly equal (tolerance zero): the same sums in the same order.
                assert_eq!(
                    s.to_bits(),
                    val[0].to_bits(),
                    "sample {j}: {s} vs {}",
                    val[0]
                );
            }
        }
    }
}
