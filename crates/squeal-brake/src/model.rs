//! The reduced nonlinear brake, eq (11): `M x'' + C x' + K x + F_nl(x) = F_piston`.
//!
//! Each contact pair `p` joins a disc point and a pad point. Its penetration is
//! `δ_p = g_p · x + gap_p` (positive when the pad presses into the disc: eq (8)'s `U_i - U_j`,
//! measured along the contact normal), where `g_p` holds `+n` on the disc point's dofs and
//! `-n` on the pad point's (n the unit normal from the disc into the pad). Eq (8):
//! `F_c = k_l δ + k_nl δ³` for `δ > 0`, else 0. Eq (9), permanent sliding at constant μ: the
//! friction force is `μ F_c` along the direction `s` in which the disc surface slides under the
//! pad. As internal forces on the left of eq (11) (the way `K x` enters), eq (10) reads
//!
//! `F_nl(x) = Σ_p F_c(δ_p) (g_p + μ h_p)`,
//!
//! with `h_p = +s` on the disc point's dofs and `-s` on the pad point's: the disc drags the pad
//! along `s`, the pad holds the disc back. Its Jacobian, eqs (18)–(19), is
//! `K_NL = Σ_p k_t(δ_p) (g_p + μ h_p) g_pᵀ` with the tangent contact stiffness
//! `k_t = k_l + 3 k_nl δ²` (0 when open): non-symmetric through friction.

use faer::Mat;

/// A sparse vector over the brake's dofs: `(dof, value)`.
pub type SparseVec = Vec<(usize, f64)>;

/// One disc-pad contact pair.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactPair {
    /// Index of the disc's contact point and of the pad's.
    pub disc_point: usize,
    pub pad_point: usize,
    /// Where the pair sits (the disc point's position).
    pub position: [f64; 3],
    /// `g_p`: `δ_p = g_p · x + gap`.
    pub normal: SparseVec,
    /// `h_p`: the friction force is `μ F_c h_p` (on the left of eq 11).
    pub tangent: SparseVec,
    /// Initial penetration (m); 0 when the points coincide.
    pub gap: f64,
    /// `k_l` (N/m) and `k_nl` (N/m³) of eq (8).
    pub k_linear: f64,
    pub k_cubic: f64,
}

impl ContactPair {
    /// Penetration `δ = g · x + gap`.
    pub fn penetration(&self, x: &[f64]) -> f64 {
        self.gap + dot_sparse(&self.normal, x)
    }

    /// Penetration rate `δ' = g · x'`.
    pub fn penetration_rate(&self, v: &[f64]) -> f64 {
        dot_sparse(&self.normal, v)
    }
}

/// `Σ v_k x_k` over a sparse vector.
pub fn dot_sparse(v: &SparseVec, x: &[f64]) -> f64 {
    v.iter().map(|&(i, a)| a * x[i]).sum()
}

/// Eq (8): contact force and tangent stiffness `(F_c, dF_c/dδ)` at penetration `δ`.
pub fn contact_law(delta: f64, k_linear: f64, k_cubic: f64) -> (f64, f64) {
    if delta > 0.0 {
        (
            k_linear * delta + k_cubic * delta.powi(3),
            k_linear + 3.0 * k_cubic * delta * delta,
        )
    } else {
        (0.0, 0.0)
    }
}

/// The reduced brake: linear part, contact pairs, piston load.
#[derive(Clone, Debug)]
pub struct Brake {
    /// Reduced mass and stiffness (disc dofs, then pad dofs).
    pub m: Mat<f64>,
    pub k: Mat<f64>,
    /// `F_piston` of eq (11).
    pub f_piston: Vec<f64>,
    pub pairs: Vec<ContactPair>,
}

impl Brake {
    /// Number of dofs.
    pub fn size(&self) -> usize {
        self.m.nrows()
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

    /// Eq (10): adds `F_nl(x)` to `out`.
    pub fn add_nonlinear_force(&self, x: &[f64], mu: f64, out: &mut [f64]) {
        for p in &self.pairs {
            let (f, _) = contact_law(p.penetration(x), p.k_linear, p.k_cubic);
            if f != 0.0 {
                for &(i, g) in &p.normal {
                    out[i] += f * g;
                }
                for &(i, h) in &p.tangent {
                    out[i] += mu * f * h;
                }
            }
        }
    }

    /// Eqs (18)–(19): the Jacobian `K_NL = Σ k_t (g + μ h) gᵀ` at `x`. Pairs in `assume_closed`
    /// (if given) use `k_l` when open, to start Newton "with the contact closed".
    pub fn nonlinear_jacobian(&self, x: &[f64], mu: f64, assume_closed: bool) -> Mat<f64> {
        let n = self.size();
        let mut j = Mat::zeros(n, n);
        for p in &self.pairs {
            let delta = p.penetration(x);
            let (_, mut kt) = contact_law(delta, p.k_linear, p.k_cubic);
            if assume_closed && delta <= 0.0 {
                kt = p.k_linear;
            }
            add_pair_stiffness(&mut j, p, kt, mu);
        }
        j
    }

    /// Residual of eq (14): `K x + F_nl(x) - F_piston`.
    pub fn static_residual(&self, x: &[f64], mu: f64) -> Vec<f64> {
        let n = self.size();
        let mut r: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| self.k[(i, j)] * x[j]).sum::<f64>())
            .collect();
        self.add_nonlinear_force(x, mu, &mut r);
        for i in 0..n {
            r[i] -= self.f_piston[i];
        }
        r
    }

    /// Tangent stiffness `K + K_NL(x, μ)` (eq 20).
    pub fn tangent_stiffness(&self, x: &[f64], mu: f64) -> Mat<f64> {
        &self.k + self.nonlinear_jacobian(x, mu, false)
    }
}

/// Adds `k (g + μ h) gᵀ` of one pair to `j`.
pub fn add_pair_stiffness(j: &mut Mat<f64>, p: &ContactPair, k: f64, mu: f64) {
    if k == 0.0 {
        return;
    }
    for &(c, gc) in &p.normal {
        for &(r, gr) in &p.normal {
            j[(r, c)] += k * gr * gc;
        }
        for &(r, hr) in &p.tangent {
            j[(r, c)] += k * mu * hr * gc;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one_pair() -> Brake {
        // dofs: 0 disc x, 1 disc z, 2 pad x, 3 pad z; normal +z, sliding +x.
        let pair = ContactPair {
            disc_point: 0,
            pad_point: 0,
            position: [0.0; 3],
            normal: vec![(1, 1.0), (3, -1.0)],
            tangent: vec![(0, 1.0), (2, -1.0)],
            gap: 1e-5,
            k_linear: 2e6,
            k_cubic: 3e15,
        };
        Brake {
            m: Mat::identity(4, 4),
            k: Mat::identity(4, 4),
            f_piston: vec![0.0; 4],
            pairs: vec![pair],
        }
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let b = one_pair();
        let x = [1e-6, 2e-6, -3e-6, -4e-6];
        let mu = 0.37;
        let j = b.nonlinear_jacobian(&x, mu, false);
        let h = 1e-11;
        for c in 0..4 {
            let (mut xp, mut xm) = (x, x);
            xp[c] += h;
            xm[c] -= h;
            let (mut fp, mut fm) = ([0.0; 4], [0.0; 4]);
            b.add_nonlinear_force(&xp, mu, &mut fp);
            b.add_nonlinear_force(&xm, mu, &mut fm);
            for r in 0..4 {
                let fd = (fp[r] - fm[r]) / (2.0 * h);
                // Central differences of a cubic: error ~ k_nl h^2 ~ 3e-7 relative to k_l.
                assert!(
                    (fd - j[(r, c)]).abs() <= 1e-6 * b.pairs[0].k_linear,
                    "J[{r},{c}] {} vs {fd}",
                    j[(r, c)]
                );
            }
        }
        // Friction couples the x rows to the normal motion only: eq (19)'s pattern.
        assert!(j[(0, 1)] > 0.0 && j[(2, 1)] < 0.0 && j[(1, 0)] == 0.0 && j[(0, 0)] == 0.0);
    }

    #[test]
    fn open_contact_carries_no_force() {
        assert_eq!(contact_law(-1e-9, 1e6, 1e15), (0.0, 0.0));
        assert_eq!(contact_law(0.0, 1e6, 1e15), (0.0, 0.0));
        let (f, k) = contact_law(1e-5, 1e6, 1e15);
        assert!((f - (10.0 + 1e-15 * 1e15)).abs() < 1e-12 && (k - (1e6 + 3e5)).abs() < 1e-6);
    }
}
