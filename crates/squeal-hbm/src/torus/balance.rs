//! The quasi-periodic harmonic balance equations and their Jacobian in `(U, ω1, ω2)`, the two
//! phase conditions, and the one-parameter family that [`crate::continuation`] follows.
//!
//! For each element `e` (frequency `w_e = k_e·ω`) the rows are the real and imaginary parts of
//! `A(w_e) X_e + B(w_e) F_e(U, ω) - E_e` ([`super::linear`]): with `T = [[Re B, Im B],
//! [-Im B, Re B]]`, the real form of multiplication by `B`,
//!
//! `∂R_e/∂U = [[Re A, Im A], [-Im A, Re A]] (on e's own block) + T ∂F_e/∂U`,
//! `∂R_e/∂ω_r = k_{e,r} (A'(w_e) X_e + B'(w_e) F_e)_real + T ∂F_e/∂ω_r`.
//!
//! **Phase conditions.** A torus solution stays one under any shift `θ -> θ + φ` of its two
//! angles ([`super::TorusBasis::shift_phase`] rotates element `e` by `k_e·φ`), a
//! two-parameter invariance. Two conditions `Us[e1, d1] = 0`, `Us[e2, d2] = 0` remove it when
//! the wave numbers `k_e1`, `k_e2` are independent (each shift then moves at least one of the
//! two sines): usually `e1 = (1, 0)` on a dof of the cycle and `e2` an element with `k2 = ±1` on
//! a dof of the modulation. Both frequencies are unknowns, so the equations are square: `L`
//! balance rows plus two phase rows in `L + 2` unknowns, plus the parameter of a family.

use faer::linalg::matmul::matmul;
use faer::reborrow::ReborrowMut;
use faer::{Accum, Mat, MatMut, Par, c64};

use super::aft::{TorusAft, default_grid};
use super::basis::TorusBasis;
use super::force::TorusForce;
use super::linear::{LinearBlocks, TorusLinear};
use crate::HbmError;
use crate::continuation::Family;
use crate::layout::{HarmonicLayout, Part};

/// The linear blocks of one element at the last frequencies.
struct ElementBlocks {
    a: Mat<c64>,
    da: Mat<c64>,
    b: Mat<c64>,
    db: Mat<c64>,
}

/// The quasi-periodic harmonic balance of one basis, linear part and force.
pub struct TorusBalance<L, F> {
    basis: TorusBasis,
    aft: TorusAft,
    linear: L,
    force: F,
    f_ext: Vec<f64>,
    f_nl: Vec<f64>,
    df: Mat<f64>,
    dfw: [Vec<f64>; 2],
    blocks: Vec<ElementBlocks>,
    cached: Option<[f64; 2]>,
}

impl<L: TorusLinear, F: TorusForce> TorusBalance<L, F> {
    /// Assembles the equations; `f_ext` (`n` per block) is the external load, `grid` the AFT
    /// grid (`None`: [`default_grid`]).
    pub fn new(
        basis: TorusBasis,
        linear: L,
        force: F,
        f_ext: Vec<f64>,
        grid: Option<[usize; 2]>,
    ) -> Result<Self, HbmError> {
        let (n, m) = (basis.n_dofs(), linear.n_forces());
        for (what, expected, got) in [
            ("linear part dofs", n, linear.n_dofs()),
            ("torus force inputs", n, force.n_inputs()),
            ("torus force outputs", m, force.n_outputs()),
        ] {
            if expected != got {
                return Err(HbmError::Dimension {
                    what,
                    expected,
                    got,
                });
            }
        }
        if linear.force_map_is_identity() && m != n {
            return Err(HbmError::Dimension {
                what: "force components of an identity force map",
                expected: n,
                got: m,
            });
        }
        basis.check_len("external load", f_ext.len())?;
        if f_ext.iter().any(|v| !v.is_finite()) {
            return Err(HbmError::NonFiniteInput {
                what: "external load",
            });
        }
        let aft = TorusAft::new(basis.clone(), grid.unwrap_or_else(|| default_grid(&basis)))?;
        let nb = basis.n_blocks();
        let blocks = (0..basis.n_waves())
            .map(|_| ElementBlocks {
                a: Mat::zeros(n, n),
                da: Mat::zeros(n, n),
                b: Mat::zeros(n, m),
                db: Mat::zeros(n, m),
            })
            .collect();
        Ok(Self {
            aft,
            linear,
            force,
            f_ext,
            f_nl: vec![0.0; m * nb],
            df: Mat::zeros(m * nb, n * nb),
            dfw: [vec![0.0; m * nb], vec![0.0; m * nb]],
            blocks,
            cached: None,
            basis,
        })
    }

    /// The basis.
    pub fn basis(&self) -> &TorusBasis {
        &self.basis
    }

    /// The AFT engine.
    pub fn aft_mut(&mut self) -> &mut TorusAft {
        &mut self.aft
    }

    /// The linear part.
    pub fn linear_mut(&mut self) -> &mut L {
        self.cached = None;
        &mut self.linear
    }

    /// The force.
    pub fn force(&self) -> &F {
        &self.force
    }

    /// The force, mutable (a parameter along a branch).
    pub fn force_mut(&mut self) -> &mut F {
        &mut self.force
    }

    /// The external load, mutable.
    pub fn external_load_mut(&mut self) -> &mut [f64] {
        &mut self.f_ext
    }

    /// The force's coefficients of the last evaluation (`m` per block).
    pub fn force_coefficients(&self) -> &[f64] {
        &self.f_nl
    }

    fn update_blocks(&mut self, omega: [f64; 2]) {
        if self.cached == Some(omega) {
            return;
        }
        for (e, blk) in self.blocks.iter_mut().enumerate() {
            let w = self.basis.frequency(e, omega);
            self.linear.blocks(
                w,
                LinearBlocks {
                    a: blk.a.as_mut(),
                    da: blk.da.as_mut(),
                    b: blk.b.as_mut(),
                    db: blk.db.as_mut(),
                },
            );
        }
        self.cached = Some(omega);
    }

    /// The complex amplitude `Uc - i Us` of element `e` of a vector with `width` per block.
    fn complex(v: &[f64], e: usize, width: usize) -> Vec<c64> {
        (0..width)
            .map(|i| {
                let c = v[(2 * e).saturating_sub(1) * width + i];
                let s = if e == 0 { 0.0 } else { v[2 * e * width + i] };
                c64::new(c, -s)
            })
            .collect()
    }

    /// `A X + B F` of element `e` (`dA`, `dB` with `derivative`).
    fn apply(&self, e: usize, x: &[c64], f: &[c64], derivative: bool) -> Vec<c64> {
        let blk = &self.blocks[e];
        let (a, b) = if derivative {
            (&blk.da, &blk.db)
        } else {
            (&blk.a, &blk.b)
        };
        let n = x.len();
        let identity = self.linear.force_map_is_identity();
        (0..n)
            .map(|i| {
                let mut v: c64 = (0..n).map(|j| a[(i, j)] * x[j]).sum();
                if identity {
                    if !derivative {
                        v += f[i];
                    }
                } else {
                    v += (0..f.len()).map(|j| b[(i, j)] * f[j]).sum::<c64>();
                }
                v
            })
            .collect()
    }

    /// Writes the real rows of a complex value of element `e` into `r` (`n` per block).
    fn write_rows(r: &mut [f64], e: usize, n: usize, v: &[c64], scale: f64) {
        for i in 0..n {
            r[(2 * e).saturating_sub(1) * n + i] += scale * v[i].re;
            if e > 0 {
                r[2 * e * n + i] -= scale * v[i].im;
            }
        }
    }

    /// The residual `R(U, ω)` (length of the basis).
    pub fn residual(&mut self, u: &[f64], omega: [f64; 2], r: &mut [f64]) -> Result<(), HbmError> {
        self.basis.check_len("residual", r.len())?;
        let mut f = std::mem::take(&mut self.f_nl);
        let out = self.aft.forces(&self.force, u, omega, &mut f);
        self.f_nl = f;
        out?;
        self.update_blocks(omega);
        let (n, m) = (self.basis.n_dofs(), self.linear.n_forces());
        r.iter_mut().zip(&self.f_ext).for_each(|(ri, e)| *ri = -e);
        for e in 0..self.basis.n_waves() {
            let x = Self::complex(u, e, n);
            let f = Self::complex(&self.f_nl, e, m);
            let v = self.apply(e, &x, &f, false);
            Self::write_rows(r, e, n, &v, 1.0);
        }
        Ok(())
    }

    /// `jac_u = ∂R/∂U` (square, overwritten) and `jac_w[r] = ∂R/∂ω_r` (overwritten).
    pub fn jacobian(
        &mut self,
        u: &[f64],
        omega: [f64; 2],
        mut jac_u: MatMut<'_, f64>,
        jac_w: [&mut [f64]; 2],
    ) -> Result<(), HbmError> {
        let (n, m) = (self.basis.n_dofs(), self.linear.n_forces());
        let len = self.basis.len();
        if jac_u.nrows() != len || jac_u.ncols() != len {
            return Err(HbmError::Dimension {
                what: "torus Jacobian (rows x cols)",
                expected: len * len,
                got: jac_u.nrows() * jac_u.ncols(),
            });
        }
        {
            let [w1, w2] = &mut self.dfw;
            self.aft.forces_and_jacobian(
                &self.force,
                u,
                omega,
                &mut self.f_nl,
                self.df.as_mut(),
                [w1.as_mut_slice(), w2.as_mut_slice()],
            )?;
        }
        self.update_blocks(omega);
        let identity = self.linear.force_map_is_identity();
        if identity {
            jac_u.copy_from(&self.df);
        } else {
            jac_u.fill(0.0);
        }
        let [jw1, jw2] = jac_w;
        jw1.fill(0.0);
        jw2.fill(0.0);
        for e in 0..self.basis.n_waves() {
            self.element_jacobian(e, n, m, u, jac_u.rb_mut(), [&mut *jw1, &mut *jw2]);
        }
        Ok(())
    }

    /// Element `e`'s rows of the Jacobian (module docs).
    #[allow(clippy::too_many_arguments)]
    fn element_jacobian(
        &self,
        e: usize,
        n: usize,
        m: usize,
        u: &[f64],
        mut jac_u: MatMut<'_, f64>,
        jac_w: [&mut [f64]; 2],
    ) {
        let blk = &self.blocks[e];
        let (rc, rs) = ((2 * e).saturating_sub(1) * n, 2 * e * n);
        let fc = (2 * e).saturating_sub(1) * m;
        // Linear part on the element's own block.
        for i in 0..n {
            for j in 0..n {
                let a = blk.a[(i, j)];
                jac_u[(rc + i, rc + j)] += a.re;
                if e > 0 {
                    jac_u[(rc + i, rs + j)] += a.im;
                    jac_u[(rs + i, rc + j)] -= a.im;
                    jac_u[(rs + i, rs + j)] += a.re;
                }
            }
        }
        // The force through T = [[Re B, Im B], [-Im B, Re B]].
        let identity = self.linear.force_map_is_identity();
        let rows = if e == 0 { 1 } else { 2 };
        if !identity {
            let t = Mat::<f64>::from_fn(rows * n, rows * m, |i, j| {
                let b = blk.b[(i % n, j % m)];
                match (i / n, j / m) {
                    (0, 0) | (1, 1) => b.re,
                    (0, 1) => b.im,
                    _ => -b.im,
                }
            });
            let df = self.df.as_ref().subrows(fc, rows * m);
            matmul(
                jac_u.rb_mut().subrows_mut(rc, rows * n),
                Accum::Add,
                &t,
                df,
                1.0,
                Par::Seq,
            );
        }
        // Frequency derivatives.
        let k = self.basis.wave(e);
        let x = Self::complex(u, e, n);
        let f = Self::complex(&self.f_nl, e, m);
        let dv = self.apply(e, &x, &f, true);
        for (r, jw) in jac_w.into_iter().enumerate() {
            if k[r] != 0 {
                Self::write_rows(jw, e, n, &dv, k[r] as f64);
            }
            let dfw = &self.dfw[r];
            for i in 0..rows * n {
                let v: f64 = if identity {
                    dfw[fc + i]
                } else {
                    (0..rows * m)
                        .map(|j| {
                            let b = blk.b[(i % n, j % m)];
                            let t = match (i / n, j / m) {
                                (0, 0) | (1, 1) => b.re,
                                (0, 1) => b.im,
                                _ => -b.im,
                            };
                            t * dfw[fc + j]
                        })
                        .sum()
                };
                jw[rc + i] += v;
            }
        }
    }
}

/// The two phase conditions `Us[e1, d1] = 0`, `Us[e2, d2] = 0` (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TorusPhase {
    /// `(element, dof)` of each condition.
    pub conditions: [(usize, usize); 2],
}

impl TorusPhase {
    /// The coefficient indices of the two sines; fails when an element has no sine or the two
    /// wave numbers are dependent (the conditions would not fix both angles).
    pub fn indices(&self, basis: &TorusBasis) -> Result<[usize; 2], HbmError> {
        let bad = |(e, d): (usize, usize)| HbmError::BadPhaseCondition {
            dof: d,
            n_dofs: basis.n_dofs(),
            n_harmonics: e,
        };
        let [a, b] = self.conditions;
        let ia = basis.index(a.0, Part::Sin, a.1).ok_or_else(|| bad(a))?;
        let ib = basis.index(b.0, Part::Sin, b.1).ok_or_else(|| bad(b))?;
        let (ka, kb) = (basis.wave(a.0), basis.wave(b.0));
        if ka[0] * kb[1] - ka[1] * kb[0] == 0 {
            return Err(bad(b));
        }
        Ok([ia, ib])
    }
}

/// How the rows of a [`TorusFamily`] are scaled: balance rows divided by `balance`, phase rows
/// by `phase` (a displacement level).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TorusScales {
    /// Level of the balance rows.
    pub balance: f64,
    /// Level of the phase rows.
    pub phase: f64,
}

/// A one-parameter family of tori: unknowns `z = [U, ω1, ω2, p]`, equations
/// `[R / balance; Us[e1,d1] / phase; Us[e2,d2] / phase]` (`L + 2` rows in `L + 3` unknowns), for
/// [`crate::continuation::continue_from`] and [`crate::continuation::correct_point`].
///
/// The continuation sees the unknowns `U` as a [`HarmonicLayout`] of `L` dofs and no harmonic
/// (it uses only the layout's length; the torus' basis never changes along a branch, so
/// [`Family::set_harmonics`] refuses). `∂R/∂p` is a central difference of step
/// `step · max(|p|, 1)`, exact up to round-off when `R` is linear in `p` (a friction
/// coefficient of Coulomb's law, a load).
pub struct TorusFamily<L, F, S> {
    balance: TorusBalance<L, F>,
    set: S,
    phase: [usize; 2],
    scales: TorusScales,
    step: f64,
    work: Vec<f64>,
}

impl<L, F, S> TorusFamily<L, F, S>
where
    L: TorusLinear,
    F: TorusForce,
    S: FnMut(&mut TorusBalance<L, F>, f64) -> Result<(), HbmError>,
{
    /// The family of `balance` in the parameter `set` puts into it.
    pub fn new(
        balance: TorusBalance<L, F>,
        set: S,
        phase: TorusPhase,
        scales: TorusScales,
        step: f64,
    ) -> Result<Self, HbmError> {
        for (what, v) in [
            ("balance scale", scales.balance),
            ("phase scale", scales.phase),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(HbmError::BadScale { what, value: v });
            }
        }
        let phase = phase.indices(balance.basis())?;
        Ok(Self {
            balance,
            set,
            phase,
            scales,
            step,
            work: Vec::new(),
        })
    }

    /// The equations at their current parameter.
    pub fn balance(&mut self) -> &mut TorusBalance<L, F> {
        &mut self.balance
    }

    fn rows(&mut self, z: &[f64], p: f64, r: &mut [f64]) -> Result<(), HbmError> {
        let l = self.balance.basis().len();
        (self.set)(&mut self.balance, p)?;
        self.balance
            .residual(&z[..l], [z[l], z[l + 1]], &mut r[..l])?;
        r[..l].iter_mut().for_each(|v| *v /= self.scales.balance);
        r[l] = z[self.phase[0]] / self.scales.phase;
        r[l + 1] = z[self.phase[1]] / self.scales.phase;
        Ok(())
    }
}

impl<L, F, S> Family for TorusFamily<L, F, S>
where
    L: TorusLinear,
    F: TorusForce,
    S: FnMut(&mut TorusBalance<L, F>, f64) -> Result<(), HbmError>,
{
    fn layout(&self) -> HarmonicLayout {
        // L ≤ MAX_COEFFICIENTS was checked by the basis, so this layout exists.
        HarmonicLayout::new(self.balance.basis().len(), 0)
            .unwrap_or_else(|_| unreachable!("the basis length is within the layout limit"))
    }

    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), HbmError> {
        let p = z[z.len() - 1];
        match self.rows(z, p, r) {
            Err(HbmError::NonFiniteForce { .. }) => {
                r.fill(f64::NAN);
                Ok(())
            }
            other => other,
        }
    }

    fn jacobian(&mut self, z: &[f64], mut jac: MatMut<'_, f64>) -> Result<(), HbmError> {
        let l = self.balance.basis().len();
        let p = z[l + 2];
        let h = self.step * p.abs().max(1.0);
        let (mut rp, mut rm) = (vec![0.0; l + 2], vec![0.0; l + 2]);
        self.rows(z, p + h, &mut rp)?;
        self.rows(z, p - h, &mut rm)?;
        for i in 0..l + 2 {
            jac[(i, l + 2)] = (rp[i] - rm[i]) / (2.0 * h);
        }
        (self.set)(&mut self.balance, p)?;
        self.work.resize(2 * l, 0.0);
        let (w1, w2) = self.work.split_at_mut(l);
        self.balance.jacobian(
            &z[..l],
            [z[l], z[l + 1]],
            jac.rb_mut().submatrix_mut(0, 0, l, l),
            [w1, w2],
        )?;
        let inv = 1.0 / self.scales.balance;
        for i in 0..l {
            jac[(i, l)] = w1[i] * inv;
            jac[(i, l + 1)] = w2[i] * inv;
            for j in 0..l {
                jac[(i, j)] *= inv;
            }
        }
        for row in [l, l + 1] {
            for j in 0..l + 2 {
                jac[(row, j)] = 0.0;
            }
        }
        jac[(l, self.phase[0])] = 1.0 / self.scales.phase;
        jac[(l + 1, self.phase[1])] = 1.0 / self.scales.phase;
        Ok(())
    }

    fn set_harmonics(&mut self, _harmonics: usize) -> Result<(), HbmError> {
        Err(HbmError::BadOption(
            "a torus family keeps its basis along the branch",
        ))
    }
}
