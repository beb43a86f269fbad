//! The reduced nonlinear brake, eq (11): `M x'' + C x' + K x + F_nl(x, x') = F_piston`.
//!
//! Each contact pair `p` joins a disc point and a pad point and carries its own geometry: the
//! unit normal `n_p` from the disc into the pad and the unit sliding direction `s_p` in which
//! the disc surface moves under the pad, as sparse vectors over the brake's dofs: `g_p` holds
//! `+n_p` on the disc point's dofs and `-n_p` on the pad point's, `h_p` holds `+s_p` and `-s_p`.
//! The penetration is `δ_p = g_p · x - g0_p` (eq (8)'s `U_i - U_j` along the normal less the
//! pair's initial gap `g0_p`, positive when closed), the slip velocity `v_p = V_p + h_p · x'` with `V_p` the disc's surface speed
//! there. A contact element ([`crate::contact::ContactLaw`]) gives the normal force `F_n` and
//! the friction force `F_t` of the pair; as internal forces on the left of eq (11) (the way
//! `K x` enters), eq (10) reads
//!
//! `F_nl(x, x') = Σ_p F_n,p g_p + F_t,p h_p`:
//!
//! the disc drags the pad along `s_p`, the pad holds the disc back. For the paper's element
//! (`F_t = μ F_n`) this is `Σ_p F_c(δ_p) (g_p + μ h_p)`, and its Jacobian, eqs (18)–(19), is
//! `K_NL = Σ_p k_t(δ_p) (g_p + μ h_p) g_pᵀ` with the tangent contact stiffness `k_t`:
//! non-symmetric through friction. The general Jacobians are in [`crate::contact`].

use crate::contact::{Kinematics, Law, Response};
use crate::error::BrakeError;
use faer::Mat;

/// A sparse vector over the brake's dofs: `(dof, value)`.
pub type SparseVec = Vec<(usize, f64)>;

/// `Σ v_k x_k` over a sparse vector.
pub fn dot_sparse(v: &[(usize, f64)], x: &[f64]) -> f64 {
    v.iter().map(|&(i, a)| a * x[i]).sum()
}

/// One disc–pad contact pair.
#[derive(Clone, Debug)]
pub struct ContactPair {
    /// Index of the disc's contact point among the disc part's points.
    pub disc_point: usize,
    /// Index of the pad's contact point among the pad part's points.
    pub pad_point: usize,
    /// Where the pair sits: the disc point's position (m).
    pub position: [f64; 3],
    /// Unit normal `n` from the disc into the pad.
    pub normal_direction: [f64; 3],
    /// Unit sliding direction `s` of the disc surface under the pad.
    pub sliding_direction: [f64; 3],
    /// `g_p`: `δ_p = g_p · x - g0`.
    pub normal: SparseVec,
    /// `h_p`: the friction force acts along `h_p`, the slip velocity is `V + h_p · x'`.
    pub tangent: SparseVec,
    /// The initial gap `g0` (m): how far the pair is open at `x = 0`, positive when open,
    /// negative for an initial interference, 0 when the points coincide. The closure is
    /// `δ = g · x - g0 = n · (u_disc - u_pad) - g0`: the relative normal approach of the pad
    /// towards the disc less the initial gap.
    pub initial_gap: f64,
    /// `V_p`: the disc's surface speed at the pair along `s` (m/s), when known.
    pub surface_speed: Option<f64>,
    /// The contact element.
    pub law: Law,
}

impl ContactPair {
    /// Penetration `δ = g · x - g0`.
    pub fn penetration(&self, x: &[f64]) -> f64 {
        // The same bits as `-g0 + g · x`: negation and subtraction are exact, addition commutes.
        dot_sparse(&self.normal, x) - self.initial_gap
    }

    /// The pair's state at displacements `x` and velocities `v` (`None`: at rest).
    pub fn kinematics(&self, x: &[f64], v: Option<&[f64]>) -> Kinematics {
        let (rate, slip) = v.map_or((0.0, 0.0), |v| {
            (dot_sparse(&self.normal, v), dot_sparse(&self.tangent, v))
        });
        Kinematics {
            penetration: self.penetration(x),
            penetration_rate: rate,
            slip_velocity: self.surface_speed.unwrap_or(0.0) + slip,
        }
    }

    /// The element's forces and derivatives at `(x, v)`.
    pub fn response(&self, x: &[f64], v: Option<&[f64]>, mu: f64) -> Response {
        self.law.response(mu, &self.kinematics(x, v))
    }

    /// Adds `F_n g + F_t h` to `out`.
    pub fn add_force(&self, r: &Response, out: &mut [f64]) {
        if r.normal != 0.0 {
            for &(i, g) in &self.normal {
                out[i] += r.normal * g;
            }
        }
        if r.tangential != 0.0 {
            for &(i, h) in &self.tangent {
                out[i] += r.tangential * h;
            }
        }
    }

    /// Calls `entry(row, col, ∂F/∂x, ∂F/∂x')` for every term of the pair's Jacobians (module
    /// [`crate::contact`]); a `(row, col)` may come more than once: the terms add up.
    pub fn jacobian_terms(&self, r: &Response, mut entry: impl FnMut(usize, usize, f64, f64)) {
        let [n_d, n_r, n_v] = r.normal_derivatives;
        let [t_d, t_r, t_v] = r.tangential_derivatives;
        for &(c, gc) in &self.normal {
            for &(row, gr) in &self.normal {
                entry(row, c, n_d * gr * gc, n_r * gr * gc);
            }
            for &(row, hr) in &self.tangent {
                entry(row, c, t_d * hr * gc, t_r * hr * gc);
            }
        }
        if n_v != 0.0 || t_v != 0.0 {
            for &(c, hc) in &self.tangent {
                for &(row, gr) in &self.normal {
                    entry(row, c, 0.0, n_v * gr * hc);
                }
                for &(row, hr) in &self.tangent {
                    entry(row, c, 0.0, t_v * hr * hc);
                }
            }
        }
    }

    /// The same pair with its dofs renumbered by `map` (e.g. onto the nonlinear dofs).
    pub fn renumbered(&self, map: impl Fn(usize) -> usize) -> ContactPair {
        let re = |v: &SparseVec| v.iter().map(|&(i, a)| (map(i), a)).collect();
        ContactPair {
            normal: re(&self.normal),
            tangent: re(&self.tangent),
            ..self.clone()
        }
    }
}

/// Adds `F_nl(x, x')` of `pairs` (eq 10) to `out`.
pub fn add_contact_forces(
    pairs: &[ContactPair],
    x: &[f64],
    v: Option<&[f64]>,
    mu: f64,
    out: &mut [f64],
) {
    for p in pairs {
        p.add_force(&p.response(x, v, mu), out);
    }
}

/// The Jacobians `∂F_nl/∂x` and `∂F_nl/∂x'` of `pairs` at `(x, x')` as dense `n × n`
/// matrices (eqs 18–19 and their damping counterpart); the second is `None` when no element
/// depends on the velocities there. With `closed_start`, an open pair gets the derivatives of
/// its element just after closing (`δ = 0⁺`), to start Newton's method with the contact
/// closed.
pub fn contact_jacobians(
    pairs: &[ContactPair],
    n: usize,
    x: &[f64],
    v: Option<&[f64]>,
    mu: f64,
    closed_start: bool,
) -> (Mat<f64>, Option<Mat<f64>>) {
    let responses: Vec<Response> = pairs
        .iter()
        .map(|p| {
            let mut kin = p.kinematics(x, v);
            if closed_start && kin.penetration <= 0.0 {
                // Derivatives just after closing; the force itself is not used here.
                kin.penetration = f64::MIN_POSITIVE;
            }
            p.law.response(mu, &kin)
        })
        .collect();
    // Pairs dense over their dofs (an interface-reduced brake): the same sums by column
    // blocks (crate::jacobian, the same bits).
    if let Some(k) = crate::jacobian::dense_jacobians(pairs, &responses, n) {
        return k;
    }
    looped_jacobians(pairs, responses, n)
}

/// The Jacobians of [`contact_jacobians`] from the pairs' responses, pair by pair, term by
/// term.
pub(crate) fn looped_jacobians(
    pairs: &[ContactPair],
    responses: Vec<Response>,
    n: usize,
) -> (Mat<f64>, Option<Mat<f64>>) {
    let mut kx = Mat::zeros(n, n);
    let mut kv: Option<Mat<f64>> = None;
    for (p, r) in pairs.iter().zip(responses) {
        if r.has_velocity_terms() && kv.is_none() {
            kv = Some(Mat::zeros(n, n));
        }
        p.jacobian_terms(&r, |row, col, dx, dv| {
            kx[(row, col)] += dx;
            if let Some(c) = kv.as_mut() {
                c[(row, col)] += dv;
            }
        });
    }
    (kx, kv)
}

/// The reduced brake: linear part, contact pairs, piston load.
#[derive(Clone, Debug)]
pub struct Brake {
    /// Reduced mass matrix `M` of eq (11) (the parts' dofs one after the other).
    pub m: Mat<f64>,
    /// Reduced stiffness matrix `K` of eq (11), without the contact.
    pub k: Mat<f64>,
    /// `F_piston` of eq (11) (N), on the pad's piston dofs.
    pub f_piston: Vec<f64>,
    /// The disc–pad contact pairs whose forces make `F_nl` of eq (10).
    pub pairs: Vec<ContactPair>,
    /// A physical viscous damping matrix `C` of the reduced brake (N s/m on point dofs),
    /// symmetric: the dampers between sets and to ground projected by the parts' Craig–Bampton
    /// bases (`squeal_reduce::dampers`); `None`: none. It is added to the modal damping of
    /// eq (12) where the reduced damping matrix is formed, [`crate::sweep::reference`]
    /// (`D = D_modal + Φᵀ C Φ`), so every analysis that takes `D` from the reference sees it.
    pub c: Option<Mat<f64>>,
    /// The part of `k` that acts on the vibration about the static equilibrium only (the
    /// `vibration_only` connections: a hydraulic piston's seal and fluid column), `None`:
    /// none. It is in `k` (so the linearized brake of eqs (18)–(20) and the harmonics
    /// `k >= 1` of the harmonic balance see it) and taken out of the static equilibrium of
    /// eq (14) and of the 0th harmonic ([`crate::vibration_only`]).
    pub k_vibration: Option<Mat<f64>>,
}

impl Brake {
    /// Number of dofs.
    pub fn size(&self) -> usize {
        self.m.nrows()
    }

    /// Checks what every analysis assumes: square matrices of one size, a load of that size,
    /// pairs inside it, and a surface speed wherever an element needs the slip velocity.
    pub fn validate(&self) -> Result<(), BrakeError> {
        let n = self.size();
        for (what, got) in [
            ("mass matrix columns", self.m.ncols()),
            ("stiffness matrix rows", self.k.nrows()),
            ("stiffness matrix columns", self.k.ncols()),
        ] {
            if got != n {
                return Err(BrakeError::Dimension {
                    what,
                    expected: n,
                    got,
                });
            }
        }
        if let Some(kv) = &self.k_vibration {
            for (what, got) in [
                ("vibration-only stiffness rows", kv.nrows()),
                ("vibration-only stiffness columns", kv.ncols()),
            ] {
                if got != n {
                    return Err(BrakeError::Dimension {
                        what,
                        expected: n,
                        got,
                    });
                }
            }
        }
        if let Some(c) = &self.c {
            for (what, got) in [
                ("damping matrix rows", c.nrows()),
                ("damping matrix columns", c.ncols()),
            ] {
                if got != n {
                    return Err(BrakeError::Dimension {
                        what,
                        expected: n,
                        got,
                    });
                }
            }
        }
        if self.f_piston.len() != n {
            return Err(BrakeError::Dimension {
                what: "piston load",
                expected: n,
                got: self.f_piston.len(),
            });
        }
        for (p, pair) in self.pairs.iter().enumerate() {
            if let Some(&(d, _)) = pair
                .normal
                .iter()
                .chain(&pair.tangent)
                .find(|(d, _)| *d >= n)
            {
                return Err(BrakeError::PairOutsideModel {
                    pair: p + 1,
                    dof: d,
                    dofs: n,
                });
            }
            if pair.law.uses_slip_velocity() && pair.surface_speed.is_none() {
                return Err(BrakeError::NoSurfaceSpeed {
                    pair: p + 1,
                    law: pair.law.name(),
                });
            }
        }
        Ok(())
    }

    /// The dofs on which the nonlinear forces act (the union of the pairs' normal and
    /// tangent supports), ascending: the "nonlinear dofs" of the condensation (eq 30).
    pub fn nonlinear_dofs(&self) -> Vec<usize> {
        let mut d: Vec<usize> = self
            .pairs
            .iter()
            .flat_map(|p| p.normal.iter().chain(&p.tangent).map(|e| e.0))
            .collect();
        d.sort_unstable();
        d.dedup();
        d
    }

    /// Penetration of every pair.
    pub fn penetrations(&self, x: &[f64]) -> Vec<f64> {
        self.pairs.iter().map(|p| p.penetration(x)).collect()
    }

    /// Eq (10): adds `F_nl(x, x')` to `out` (`v = None`: at rest).
    pub fn add_nonlinear_force(&self, x: &[f64], v: Option<&[f64]>, mu: f64, out: &mut [f64]) {
        add_contact_forces(&self.pairs, x, v, mu, out);
    }

    /// Eqs (18)–(19) at rest: `K_NL = ∂F_nl/∂x` and, when an element depends on the
    /// velocities, `C_NL = ∂F_nl/∂x'`.
    pub fn nonlinear_jacobian(
        &self,
        x: &[f64],
        mu: f64,
        closed_start: bool,
    ) -> (Mat<f64>, Option<Mat<f64>>) {
        contact_jacobians(&self.pairs, self.size(), x, None, mu, closed_start)
    }

    /// Residual of eq (14): `K x + F_nl(x) - F_piston`.
    pub fn static_residual(&self, x: &[f64], mu: f64) -> Vec<f64> {
        self.static_residual_at(x, mu, 1.0)
    }

    /// Residual of eq (14) under a fraction `load` of the piston force:
    /// `K x + F_nl(x) - load F_piston` (the load continuation's; `load = 1` is eq (14)).
    pub fn static_residual_at(&self, x: &[f64], mu: f64, load: f64) -> Vec<f64> {
        let n = self.size();
        // `(K x)_i = Σ_j K_ij x_j` summed in the order of j from the neutral element of
        // `f64::sum`, as a row's `sum()` would, but column by column (contiguous in `K`).
        let zero: f64 = std::iter::empty::<f64>().sum();
        let mut r = vec![zero; n];
        for (j, xj) in x.iter().enumerate().take(n) {
            let col = self.k.col(j);
            for (i, ri) in r.iter_mut().enumerate() {
                *ri += col[i] * xj;
            }
        }
        self.add_nonlinear_force(x, None, mu, &mut r);
        for i in 0..n {
            r[i] -= load * self.f_piston[i];
        }
        r
    }

    /// Tangent stiffness `K + K_NL(x, μ)` (eq 20).
    pub fn tangent_stiffness(&self, x: &[f64], mu: f64) -> Mat<f64> {
        &self.k + self.nonlinear_jacobian(x, mu, false).0
    }

    /// The brake with every contact element's forces times `factor` ([`crate::contact::scaled`]).
    pub fn with_contact_scale(&self, factor: f64) -> Brake {
        let mut b = self.clone();
        for p in &mut b.pairs {
            p.law = crate::contact::scaled(&p.law, factor);
        }
        b
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::contact::PenaltyCoulomb;
    use std::sync::Arc;

    pub(crate) fn one_pair(initial_gap: f64) -> ContactPair {
        // dofs: 0 disc x, 1 disc z, 2 pad x, 3 pad z; normal +z, sliding +x.
        ContactPair {
            disc_point: 0,
            pad_point: 0,
            position: [0.0; 3],
            normal_direction: [0.0, 0.0, 1.0],
            sliding_direction: [1.0, 0.0, 0.0],
            normal: vec![(1, 1.0), (3, -1.0)],
            tangent: vec![(0, 1.0), (2, -1.0)],
            initial_gap,
            surface_speed: None,
            law: Arc::new(PenaltyCoulomb {
                k_linear: 2e6,
                k_cubic: 3e15,
            }),
        }
    }

    fn brake() -> Brake {
        Brake {
            m: Mat::identity(4, 4),
            k: Mat::identity(4, 4),
            f_piston: vec![0.0; 4],
            c: None,
            k_vibration: None,
            pairs: vec![one_pair(-1e-5)],
        }
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let b = brake();
        let x = [1e-6, 2e-6, -3e-6, -4e-6];
        let mu = 0.37;
        let (j, c) = b.nonlinear_jacobian(&x, mu, false);
        assert!(c.is_none(), "the paper's element has no velocity terms");
        let h = 1e-11;
        for col in 0..4 {
            let (mut xp, mut xm) = (x, x);
            xp[col] += h;
            xm[col] -= h;
            let (mut fp, mut fm) = ([0.0; 4], [0.0; 4]);
            b.add_nonlinear_force(&xp, None, mu, &mut fp);
            b.add_nonlinear_force(&xm, None, mu, &mut fm);
            for r in 0..4 {
                let fd = (fp[r] - fm[r]) / (2.0 * h);
                // Central differences of a cubic: error ~ k_nl h^2 ~ 3e-7 relative to k_l.
                assert!(
                    (fd - j[(r, col)]).abs() <= 1e-6 * 2e6,
                    "J[{r},{col}] {} vs {fd}",
                    j[(r, col)]
                );
            }
        }
        // Friction couples the x rows to the normal motion only: eq (19)'s pattern.
        assert!(j[(0, 1)] > 0.0 && j[(2, 1)] < 0.0 && j[(1, 0)] == 0.0 && j[(0, 0)] == 0.0);
    }

    #[test]
    fn a_closed_start_gives_an_open_pair_its_closing_stiffness() {
        let b = Brake {
            pairs: vec![one_pair(1e-5)],
            ..brake()
        };
        let x = [0.0; 4];
        assert_eq!(b.nonlinear_jacobian(&x, 0.5, false).0[(1, 1)], 0.0);
        let (j, _) = b.nonlinear_jacobian(&x, 0.5, true);
        // k_l + 3 k_nl δ² at δ = 0⁺ is k_l to the last bit.
        assert_eq!(j[(1, 1)], 2e6);
        assert_eq!(j[(0, 1)], 0.5 * 2e6);
    }

    #[test]
    fn an_element_that_needs_the_disc_speed_is_refused_without_it() {
        #[derive(Debug)]
        struct NeedsSpeed;
        impl crate::contact::ContactLaw for NeedsSpeed {
            fn response(&self, _: f64, _: &Kinematics) -> Response {
                Response::default()
            }
            fn uses_slip_velocity(&self) -> bool {
                true
            }
            fn name(&self) -> String {
                "test".into()
            }
            fn parameters(&self) -> Vec<crate::contact::Parameter> {
                vec![]
            }
        }
        let mut b = brake();
        b.pairs[0].law = Arc::new(NeedsSpeed);
        assert!(matches!(
            b.validate(),
            Err(BrakeError::NoSurfaceSpeed { pair: 1, .. })
        ));
        b.pairs[0].surface_speed = Some(10.0);
        assert!(b.validate().is_ok());
    }
}
