//! Stiffness that acts on the vibration about the static equilibrium only
//! ([`Brake::k_vibration`]: a hydraulic piston's seal and fluid column, the `vibration_only`
//! connections of [`crate::connections`]).
//!
//! A caliper's clamp is pressure-controlled: the pad's load is the line pressure times the
//! piston area whatever the piston's stiffness, while the seal and the fluid column resist
//! the piston's vibration. With `K = K_st + K_vib` (`K_vib` the vibration-only part, kept in
//! [`Brake::k`]):
//!
//! - **static equilibrium**, eq (14): `K_st x0 + F_nl(x0) = F_piston` ([`static_brake`]: the
//!   brake with `K_st` in place of `K`, which [`crate::equilibrium`] solves);
//! - **linearized brake**, eqs (18)–(20): `M ẍ + C ẋ + (K + K_NL(x0)) x = 0`: `K_vib` is in
//!   `K`, so every spectrum, sweep and reference sees it unchanged;
//! - **harmonic balance**, eq (26) harmonic by harmonic: harmonic 0 (the mean) reads
//!   `K_st X_0 + F_nl,0 = F_piston`, harmonics `k >= 1` read
//!   `(K − k²ω² M + i k ω C) X_k + F_nl,k = 0`: the spring acts on the harmonics `k >= 1`.
//!
//! **The 0th harmonic in modal coordinates.** [`crate::harmonic`] works in the modes of
//! `K' = K + K_s` (`Φᵀ K' Φ = Ω²`, `Φᵀ M Φ = I`, [`crate::modal_brake`]). There the static
//! stiffness is `Ω² − V`, `V = Φᵀ K_vib Φ`, and its inverse `S = (Ω² − V)⁻¹` replaces `Ω⁻²`
//! of harmonic 0: the receptance of eq (32) on the nonlinear dofs `H_0 = Φ_n S Φ_nᵀ`, the
//! condensed load of eq (33) `Φ_n S Φᵀ F_piston`, the recovery of eq (35)
//! `q_0 = S (Φᵀ F_piston − Φ_nᵀ G_0)`. `K_vib` is non-zero on the few dofs of its
//! connections' ends (`m`, six per end), `K_vib = E K_vv Eᵀ`, so `V = U K_vv Uᵀ` with
//! `U = Φ_vᵀ` (`n × m`, the rows of `Φ` at those dofs) and, by the Woodbury identity,
//!
//! `S b = A⁻¹ b + A⁻¹ U (I − K_vv W)⁻¹ K_vv Uᵀ A⁻¹ b`, `A = Ω²`, `W = Uᵀ A⁻¹ U`
//!
//! (multiply out: `(A − U K_vv Uᵀ) S b = b + U [(I − K_vv W)(I − K_vv W)⁻¹ K_vv − K_vv] Uᵀ A⁻¹ b
//! = b`): an `m × m` factorization instead of an `n × n` one. `I − K_vv W` is singular exactly
//! when `K_st` is (a part the static problem leaves free), which the static equilibrium has
//! refused before.
//!
//! **Time domain.** The equations of [`crate::dynamics`] have no harmonics: there the spring
//! acts about the frictionless equilibrium `x_0` of the reference, `K_vib (x − x_0)`, i.e. the
//! modal load is `Φᵀ (F_piston + K_vib x_0)`
//! ([`ModalBrake::load`](crate::modal_brake::ModalBrake::load)); at μ = 0 its static solution
//! is `x_0`, at other μ it differs from eq (14)'s by `K_vib`'s share of the equilibrium's
//! shift with μ.

use crate::model::Brake;
use faer::linalg::solvers::Solve;
use faer::{Mat, c64};

/// The brake whose stiffness is `K_st = K − K_vib` and without vibration-only stiffness: the
/// one whose eq (14) is the static equilibrium (module docs); `None` when `brake` has no
/// vibration-only stiffness.
pub fn static_brake(brake: &Brake) -> Option<Brake> {
    let kv = brake.k_vibration.as_ref()?;
    Some(Brake {
        m: brake.m.clone(),
        k: &brake.k - kv,
        f_piston: brake.f_piston.clone(),
        pairs: brake.pairs.clone(),
        c: brake.c.clone(),
        k_vibration: None,
    })
}

/// The dofs on which `k` has a non-zero entry in its row or column, ascending.
fn support(k: &Mat<f64>) -> Vec<usize> {
    (0..k.nrows())
        .filter(|&i| (0..k.ncols()).any(|j| k[(i, j)] != 0.0 || k[(j, i)] != 0.0))
        .collect()
}

/// The static flexibility of harmonic 0 in modal coordinates (module docs): `S Φᵀ F_piston`
/// and `S Φ_nᵀ`.
#[derive(Clone, Debug)]
pub struct ModalStatics {
    /// `S Φᵀ F_piston` (modal, length `n`).
    pub load: Vec<f64>,
    /// `S Φ_nᵀ` (`n × n_nl`).
    pub flex_n: Mat<f64>,
}

impl ModalStatics {
    /// `S` applied to the modal load `load` and to `Φ_nᵀ`, for the modes `phi` (physical ×
    /// modes), their frequencies `omega` (rad/s) and the vibration-only stiffness `k_vib`
    /// (physical), by the Woodbury identity of the module docs.
    pub fn new(
        phi: &Mat<f64>,
        phi_n: &Mat<f64>,
        omega: &[f64],
        k_vib: &Mat<f64>,
        load: &[f64],
    ) -> Self {
        let n = omega.len();
        let dofs = support(k_vib);
        let m = dofs.len();
        let kvv = Mat::from_fn(m, m, |a, b| k_vib[(dofs[a], dofs[b])]);
        // U = Φ_vᵀ (n × m); A⁻¹ = Ω⁻².
        let u = Mat::from_fn(n, m, |j, a| phi[(dofs[a], j)]);
        let inv_a: Vec<f64> = omega.iter().map(|w| 1.0 / (w * w)).collect();
        let w = Mat::from_fn(m, m, |a, b| {
            (0..n)
                .map(|j| u[(j, a)] * inv_a[j] * u[(j, b)])
                .sum::<f64>()
        });
        let cap = Mat::<f64>::identity(m, m) - &kvv * &w;
        let lu = cap.partial_piv_lu();
        // S B for the columns of B (n × c).
        let apply = |b: &Mat<f64>| -> Mat<f64> {
            let ab = Mat::from_fn(n, b.ncols(), |j, c| inv_a[j] * b[(j, c)]);
            let t = &kvv * (u.transpose() * &ab);
            let y = lu.solve(&t);
            let uy = &u * &y;
            Mat::from_fn(n, b.ncols(), |j, c| ab[(j, c)] + inv_a[j] * uy[(j, c)])
        };
        let rhs = Mat::from_fn(n, 1, |j, _| load[j]);
        let s_load = apply(&rhs);
        let flex_n = apply(&phi_n.transpose().to_owned());
        Self {
            load: (0..n).map(|j| s_load[(j, 0)]).collect(),
            flex_n,
        }
    }

    /// `H_0 = Φ_n S Φ_nᵀ`, the 0th harmonic's receptance on the nonlinear dofs.
    pub fn receptance(&self, phi_n: &Mat<f64>) -> Mat<f64> {
        phi_n * &self.flex_n
    }

    /// `Φ_n S Φᵀ F_piston`: the nonlinear dofs' static displacement under the load alone.
    pub fn load_on_nonlinear(&self, phi_n: &Mat<f64>) -> Vec<f64> {
        (0..phi_n.nrows())
            .map(|i| {
                (0..self.load.len())
                    .map(|j| phi_n[(i, j)] * self.load[j])
                    .sum()
            })
            .collect()
    }

    /// `q_0 = S (Φᵀ F_piston − Φ_nᵀ G_0)` for the 0th harmonic `g0` of the nonlinear force.
    pub fn mean(&self, g0: &[f64]) -> Vec<f64> {
        (0..self.load.len())
            .map(|j| {
                self.load[j]
                    - (0..g0.len())
                        .map(|i| self.flex_n[(j, i)] * g0[i])
                        .sum::<f64>()
            })
            .collect()
    }
}

/// `(T − Φᵀ K_vib Φ)⁻¹ b` in modal coordinates from a solver `solve` of `T` (complex), by the
/// Woodbury identity of the module docs with `A = T`: `m + 1` solves with `T` and an `m × m`
/// factorization. The zero-frequency solve of the normal form ([`crate::criticality`]) with
/// the vibration-only stiffness out, as the harmonic balance's 0th harmonic has it.
pub fn solve_static(
    phi: &Mat<f64>,
    k_vib: &Mat<f64>,
    solve: impl Fn(&[c64]) -> Vec<c64>,
    b: &[c64],
) -> Vec<c64> {
    let n = b.len();
    let dofs = support(k_vib);
    let m = dofs.len();
    let kvv = Mat::from_fn(m, m, |a, c| c64::new(k_vib[(dofs[a], dofs[c])], 0.0));
    // Y = T⁻¹ U, U = Φ_vᵀ (n × m).
    let columns: Vec<Vec<c64>> = (0..m)
        .map(|a| {
            solve(
                &(0..n)
                    .map(|j| c64::new(phi[(dofs[a], j)], 0.0))
                    .collect::<Vec<_>>(),
            )
        })
        .collect();
    let y = Mat::from_fn(n, m, |j, a| columns[a][j]);
    let z = solve(b);
    // W = Uᵀ Y, Uᵀ z.
    let ut = |v: &dyn Fn(usize) -> c64, a: usize| -> c64 {
        (0..n).map(|j| v(j) * phi[(dofs[a], j)]).sum()
    };
    let w = Mat::from_fn(m, m, |a, c| ut(&|j| y[(j, c)], a));
    let utz = Mat::from_fn(m, 1, |a, _| ut(&|j| z[j], a));
    let cap = Mat::<c64>::identity(m, m) - &kvv * &w;
    let t = cap.partial_piv_lu().solve(&kvv * &utz);
    let yt = &y * &t;
    (0..n).map(|j| z[j] + yt[(j, 0)]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The complex solve against the dense `(T − Φᵀ K_vib Φ)⁻¹ b` for a complex diagonal `T`:
    /// 1e-12 of the solution's size (a 5 × 5 solve's round-off).
    #[test]
    fn the_static_solve_matches_the_dense_one() {
        let n = 5;
        let t: Vec<c64> = (0..n)
            .map(|j| c64::new(1e4 * (j as f64 + 1.0), 300.0 * j as f64))
            .collect();
        let phi = Mat::from_fn(n, n, |i, j| {
            ((i * 3 + j * 2) % 5) as f64 * 0.2 + f64::from(u8::from(i == j))
        });
        let mut kv = Mat::zeros(n, n);
        for (a, c, v) in [(0, 0, 4e3), (2, 2, 4e3), (0, 2, -4e3), (2, 0, -4e3)] {
            kv[(a, c)] = v;
        }
        let b: Vec<c64> = (0..n).map(|j| c64::new(j as f64 - 2.0, 0.5)).collect();
        let got = solve_static(
            &phi,
            &kv,
            |v| v.iter().zip(&t).map(|(a, d)| a / d).collect(),
            &b,
        );
        let v = phi.transpose() * &kv * &phi;
        let a = Mat::from_fn(n, n, |i, j| {
            (if i == j { t[i] } else { c64::new(0.0, 0.0) }) - c64::new(v[(i, j)], 0.0)
        });
        let want = a.partial_piv_lu().solve(Mat::from_fn(n, 1, |i, _| b[i]));
        let size = (0..n).map(|i| want[(i, 0)].norm()).fold(0.0, f64::max);
        for i in 0..n {
            assert!((got[i] - want[(i, 0)]).norm() <= 1e-12 * size, "{i}");
        }
        // The spring matters.
        assert!((got[0] - b[0] / t[0]).norm() > 1e-6 * size);
    }

    /// `S` by Woodbury against the dense inverse of `Ω² − Φᵀ K_vib Φ` on a 5-dof system:
    /// equal to 1e-12 relative (round-off of a 5 × 5 solve with a condition of about 10).
    #[test]
    fn woodbury_matches_the_dense_inverse() {
        let n = 5;
        let omega: Vec<f64> = (0..n).map(|j| 100.0 * (j as f64 + 1.0)).collect();
        // Any invertible Φ: the identity need not be M-orthonormal here, S is algebraic.
        let phi = Mat::from_fn(n, n, |i, j| {
            ((i * 7 + j * 3) % 5) as f64 * 0.1 + f64::from(u8::from(i == j))
        });
        let mut kv = Mat::zeros(n, n);
        // One spring of 3e3 between dofs 1 and 3.
        for (a, b, v) in [(1, 1, 3e3), (3, 3, 3e3), (1, 3, -3e3), (3, 1, -3e3)] {
            kv[(a, b)] = v;
        }
        let phi_n = Mat::from_fn(2, n, |i, j| phi[([0, 3][i], j)]);
        let load: Vec<f64> = (0..n).map(|j| j as f64 - 1.5).collect();
        let s = ModalStatics::new(&phi, &phi_n, &omega, &kv, &load);
        let v = phi.transpose() * &kv * &phi;
        let a = Mat::from_fn(n, n, |i, j| {
            f64::from(u8::from(i == j)) * omega[i] * omega[i] - v[(i, j)]
        });
        let dense = a.partial_piv_lu().solve(Mat::<f64>::identity(n, n));
        let want_load: Vec<f64> = (0..n)
            .map(|j| (0..n).map(|k| dense[(j, k)] * load[k]).sum())
            .collect();
        let want_flex = Mat::from_fn(n, 2, |j, i| {
            (0..n).map(|k| dense[(j, k)] * phi_n[(i, k)]).sum::<f64>()
        });
        let scale_load = want_load.iter().fold(0.0, |a: f64, b| a.max(b.abs()));
        let scale_flex = (0..n)
            .flat_map(|j| [want_flex[(j, 0)], want_flex[(j, 1)]])
            .fold(0.0, |a: f64, b| a.max(b.abs()));
        for j in 0..n {
            assert!(
                (s.load[j] - want_load[j]).abs() <= 1e-12 * scale_load,
                "load {j}"
            );
            for i in 0..2 {
                let d = s.flex_n[(j, i)] - want_flex[(j, i)];
                assert!(d.abs() <= 1e-12 * scale_flex, "flex {j} {i}");
            }
        }
        // The spring matters: S differs from Ω⁻² by far more than the tolerance.
        assert!((s.load[1] - load[1] / omega[1].powi(2)).abs() > 1e-6 * scale_load);
    }
}
