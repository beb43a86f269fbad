//! Quasi-periodic harmonic balance against a closed-form torus.
//!
//! Two coupled Hopf normal forms, `z_a = a1 + i b1`, `z_b = a2 + i b2`:
//!
//! `z_a' = (α_a + i ω_a) z_a - (1 + i γ_a) |z_a|² z_a + (i κ_a - δ_a) |z_b|² z_a`,
//! `z_b' = (α_b + i ω_b) z_b - (1 + i γ_b) |z_b|² z_b + (i κ_b - δ_b) |z_a|² z_b`.
//!
//! `z_a = r_a e^{iθ1}`, `z_b = r_b e^{iθ2}` solve them when
//! `r_a² + δ_a r_b² = α_a`, `r_b² + δ_b r_a² = α_b` (real parts) and
//! `ω1 = ω_a - γ_a r_a² + κ_a r_b²`, `ω2 = ω_b - γ_b r_b² + κ_b r_a²` (imaginary parts): an
//! invariant torus whose amplitudes and both frequencies depend on the coupling, in closed form.
//! As a first-order system `C x' + K x + f(x) = 0` (`M = 0`, `C = I`, `K = -L`) the cubic force
//! of a circle is a circle again, so the torus lies in the basis' `(1, 0)` and `(0, 1)`
//! elements exactly: harmonic balance must return it to round-off, whatever the truncation.

// Index loops over the four state components read like the formulas.
#![allow(clippy::needless_range_loop)]

use faer::linalg::solvers::Solve;
use faer::{Mat, c64};
use squeal_hbm::continuation::{
    ContinuationOptions, Control, Family, continue_from, correct_point,
};
use squeal_hbm::torus::{
    LinearBlocks, MckTorus, Square, TorusBalance, TorusBasis, TorusFamily, TorusLinear, TorusPhase,
    TorusScales, Truncation,
};
use squeal_hbm::{FnForce, HbmError, LocalJacobian, Part};

#[derive(Clone, Copy)]
struct Pair {
    omega: [f64; 2],
    gamma: [f64; 2],
    kappa: [f64; 2],
    delta: [f64; 2],
}

const P: Pair = Pair {
    omega: [1.0, 0.6180339887498949],
    gamma: [0.3, -0.2],
    kappa: [0.15, 0.25],
    delta: [0.2, 0.1],
};
const ALPHA_B: f64 = 0.8;

/// `(r_a², r_b², ω1, ω2)` of the closed form at `α_a`.
fn closed_form(alpha_a: f64) -> (f64, f64, f64, f64) {
    let det = 1.0 - P.delta[0] * P.delta[1];
    let ra2 = (alpha_a - P.delta[0] * ALPHA_B) / det;
    let rb2 = (ALPHA_B - P.delta[1] * alpha_a) / det;
    let w1 = P.omega[0] - P.gamma[0] * ra2 + P.kappa[0] * rb2;
    let w2 = P.omega[1] - P.gamma[1] * rb2 + P.kappa[1] * ra2;
    (ra2, rb2, w1, w2)
}

/// `f = -N(x)`: the cubic terms with a sign for `C x' + K x + f = 0`.
fn cubic(x: &[f64], _v: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>) {
    let rho = [x[0] * x[0] + x[1] * x[1], x[2] * x[2] + x[3] * x[3]];
    let mut jac = jac;
    for o in 0..2 {
        let other = 1 - o;
        let (a, b) = (x[2 * o], x[2 * o + 1]);
        let cr = -rho[o] - P.delta[o] * rho[other];
        let ci = -P.gamma[o] * rho[o] + P.kappa[o] * rho[other];
        f[2 * o] = -(cr * a - ci * b);
        f[2 * o + 1] = -(ci * a + cr * b);
        if let Some(j) = jac.as_mut() {
            // d rho[o]/dx = 2 x on its own pair; pattern is dense 4 x 4, row-major.
            for col in 0..4 {
                let own = col / 2 == o;
                let drho = 2.0 * x[col];
                let (dcr, dci) = if own {
                    (-drho, -P.gamma[o] * drho)
                } else {
                    (-P.delta[o] * drho, P.kappa[o] * drho)
                };
                let mut da = dcr * a - dci * b;
                let mut db = dci * a + dcr * b;
                if col == 2 * o {
                    da += cr;
                    db += ci;
                }
                if col == 2 * o + 1 {
                    da -= ci;
                    db += cr;
                }
                j.dfdx[(2 * o) * 4 + col] = -da;
                j.dfdx[(2 * o + 1) * 4 + col] = -db;
            }
        }
    }
}

fn pattern() -> Vec<(usize, usize)> {
    (0..4).flat_map(|r| (0..4).map(move |c| (r, c))).collect()
}

/// `K = -L(α_a)`, `C = I`, `M = 0`.
fn matrices(alpha_a: f64) -> (Mat<f64>, Mat<f64>, Mat<f64>) {
    let mut k = Mat::<f64>::zeros(4, 4);
    for (o, (al, om)) in [(alpha_a, P.omega[0]), (ALPHA_B, P.omega[1])]
        .into_iter()
        .enumerate()
    {
        let (i, j) = (2 * o, 2 * o + 1);
        k[(i, i)] = -al;
        k[(j, j)] = -al;
        k[(i, j)] = om;
        k[(j, i)] = -om;
    }
    (Mat::zeros(4, 4), Mat::identity(4, 4), k)
}

type Force = Square<FnForce<fn(&[f64], &[f64], &mut [f64], Option<LocalJacobian<'_>>)>>;

fn force() -> Force {
    Square(FnForce::new(
        4,
        pattern(),
        false,
        cubic as fn(&[f64], &[f64], &mut [f64], Option<LocalJacobian<'_>>),
    ))
}

fn mck_balance(alpha_a: f64, t: Truncation) -> TorusBalance<MckTorus, Force> {
    let basis = TorusBasis::new(4, t).unwrap();
    let (m, c, k) = matrices(alpha_a);
    let linear = MckTorus::new(m.as_ref(), c.as_ref(), k.as_ref()).unwrap();
    let len = basis.len();
    TorusBalance::new(basis, linear, force(), vec![0.0; len], None).unwrap()
}

fn set_alpha(b: &mut TorusBalance<MckTorus, Force>, alpha: f64) -> Result<(), HbmError> {
    let (m, c, k) = matrices(alpha);
    *b.linear_mut() = MckTorus::new(m.as_ref(), c.as_ref(), k.as_ref())?;
    Ok(())
}

/// A guess near the torus (20 % off in amplitude, 5 % in frequency, with some content in
/// every element), and the phase conditions on `a1` at `(1, 0)` and `a2` at `(0, 1)`.
fn guess(basis: &TorusBasis, alpha_a: f64) -> (Vec<f64>, TorusPhase) {
    let (ra2, rb2, w1, w2) = closed_form(alpha_a);
    let mut u: Vec<f64> = (0..basis.len())
        .map(|i| 1e-3 * ((i * 7 % 13) as f64 - 6.0))
        .collect();
    let e10 = basis.element([1, 0]).unwrap().0;
    let e01 = basis.element([0, 1]).unwrap().0;
    for (e, d, r) in [(e10, 0, ra2.sqrt()), (e01, 2, rb2.sqrt())] {
        u[basis.index(e, Part::Cos, d).unwrap()] = 1.2 * r;
        u[basis.index(e, Part::Sin, d).unwrap()] = 0.0;
        u[basis.index(e, Part::Sin, d + 1).unwrap()] = 0.8 * r;
    }
    u.extend([1.05 * w1, 0.95 * w2, alpha_a]);
    (
        u,
        TorusPhase {
            conditions: [(e10, 0), (e01, 2)],
        },
    )
}

fn fix_parameter(len: usize, value: f64) -> (Vec<f64>, f64) {
    let mut row = vec![0.0; len];
    row[len - 1] = 1.0;
    (row, value)
}

fn check_torus(basis: &TorusBasis, z: &[f64], alpha_a: f64, tol: f64) {
    let (ra2, rb2, w1, w2) = closed_form(alpha_a);
    let l = basis.len();
    assert!((z[l] - w1).abs() < tol, "ω1 {} vs {w1}", z[l]);
    assert!((z[l + 1] - w2).abs() < tol, "ω2 {} vs {w2}", z[l + 1]);
    let e10 = basis.element([1, 0]).unwrap().0;
    let e01 = basis.element([0, 1]).unwrap().0;
    let mut expected = vec![0.0; l];
    expected[basis.index(e10, Part::Cos, 0).unwrap()] = ra2.sqrt();
    expected[basis.index(e10, Part::Sin, 1).unwrap()] = ra2.sqrt();
    expected[basis.index(e01, Part::Cos, 2).unwrap()] = rb2.sqrt();
    expected[basis.index(e01, Part::Sin, 3).unwrap()] = rb2.sqrt();
    for i in 0..l {
        assert!(
            (z[i] - expected[i]).abs() < tol,
            "coefficient {i}: {} vs {}",
            z[i],
            expected[i]
        );
    }
}

#[test]
fn closed_form_torus_by_total_order_and_box() {
    // Newton from 20 % off must land on the closed form to round-off (1e-12: the equations
    // are exact in any truncation that holds (1, 0) and (0, 1), and Newton's last step is
    // below 1e-10 of O(1) unknowns).
    for t in [Truncation::TotalOrder(3), Truncation::Box(2, 2)] {
        let alpha_a = 1.0;
        let balance = mck_balance(alpha_a, t);
        let basis = balance.basis().clone();
        let (z0, phase) = guess(&basis, alpha_a);
        let scales = TorusScales {
            balance: 1.0,
            phase: 1.0,
        };
        let mut fam = TorusFamily::new(balance, set_alpha, phase, scales, 1e-6).unwrap();
        let w = vec![1.0; z0.len()];
        let (row, value) = fix_parameter(z0.len(), alpha_a);
        let opts = {
            let mut o = ContinuationOptions::default();
            o.max_iterations = 30;
            o
        };
        let p = correct_point(&mut fam, &z0, &row, value, &w, &row, &opts)
            .unwrap()
            .expect("Newton converges from the guess");
        check_torus(&basis, &p.z, alpha_a, 1e-12);
    }
}

#[test]
fn jacobian_matches_finite_differences() {
    // Central differences of step 1e-6 on O(1) unknowns: truncation error ~1e-12 (cubic
    // force), round-off ~1e-16/1e-6 = 1e-10; 1e-7 leaves a margin, and any wrong sign or
    // misplaced block would be O(1). Checked at a point off the torus so that every element
    // couples.
    let mut balance = mck_balance(0.7, Truncation::TotalOrder(3));
    let basis = balance.basis().clone();
    let (mut z, _) = guess(&basis, 0.7);
    for (i, v) in z.iter_mut().enumerate().take(basis.len()) {
        *v += 0.05 * ((i * 5 % 11) as f64 - 5.0) / 5.0;
    }
    fd_check(&mut balance, &z, 1e-7);
}

fn fd_check<L: TorusLinear, F: squeal_hbm::torus::TorusForce>(
    balance: &mut TorusBalance<L, F>,
    z: &[f64],
    tol: f64,
) {
    let l = balance.basis().len();
    let omega = [z[l], z[l + 1]];
    let mut jac = Mat::<f64>::zeros(l, l);
    let (mut j1, mut j2) = (vec![0.0; l], vec![0.0; l]);
    balance
        .jacobian(&z[..l], omega, jac.as_mut(), [&mut j1, &mut j2])
        .unwrap();
    let h = 1e-6;
    let (mut rp, mut rm) = (vec![0.0; l], vec![0.0; l]);
    let mut worst: f64 = 0.0;
    for col in 0..l + 2 {
        let mut zp = z[..l + 2].to_vec();
        let mut zm = zp.clone();
        zp[col] += h;
        zm[col] -= h;
        balance
            .residual(&zp[..l], [zp[l], zp[l + 1]], &mut rp)
            .unwrap();
        balance
            .residual(&zm[..l], [zm[l], zm[l + 1]], &mut rm)
            .unwrap();
        for row in 0..l {
            let fd = (rp[row] - rm[row]) / (2.0 * h);
            let an = match col {
                c if c < l => jac[(row, c)],
                c if c == l => j1[row],
                _ => j2[row],
            };
            worst = worst.max((fd - an).abs());
        }
    }
    assert!(worst < tol, "largest Jacobian error {worst:e}");
}

/// The same system in receptance form: `A = I`, `B(w) = (K + i w C)^-1`, so the unknowns
/// satisfy `X + B F = 0`, the dynamic stiffness' equations multiplied by `B`.
struct Receptance {
    k: Mat<f64>,
}

impl TorusLinear for Receptance {
    fn n_dofs(&self) -> usize {
        4
    }
    fn n_forces(&self) -> usize {
        4
    }
    fn blocks(&mut self, w: f64, mut out: LinearBlocks<'_>) {
        let d = Mat::<c64>::from_fn(4, 4, |i, j| {
            c64::new(self.k[(i, j)], if i == j { w } else { 0.0 })
        });
        let b = d.partial_piv_lu().solve(Mat::<c64>::identity(4, 4));
        // dB/dw = -B (dD/dw) B, dD/dw = i I.
        let bb = &b * &b;
        let db = Mat::<c64>::from_fn(4, 4, |i, j| bb[(i, j)] * c64::new(0.0, -1.0));
        for i in 0..4 {
            for j in 0..4 {
                out.a[(i, j)] = c64::new(if i == j { 1.0 } else { 0.0 }, 0.0);
                out.da[(i, j)] = c64::new(0.0, 0.0);
                out.b[(i, j)] = b[(i, j)];
                out.db[(i, j)] = db[(i, j)];
            }
        }
    }
}

#[test]
fn receptance_form_gives_the_same_torus() {
    // Same tolerances as the dynamic-stiffness form: the receptance form's equations are
    // those multiplied by the (regular) receptance, with the same root.
    let alpha_a = 0.9;
    let basis = TorusBasis::new(4, Truncation::TotalOrder(3)).unwrap();
    let (_, _, k) = matrices(alpha_a);
    let len = basis.len();
    let mut balance = TorusBalance::new(
        basis.clone(),
        Receptance { k },
        force(),
        vec![0.0; len],
        None,
    )
    .unwrap();
    let (z0, phase) = guess(&basis, alpha_a);
    let mut zc = z0.clone();
    for (i, v) in zc.iter_mut().enumerate().take(len) {
        *v += 0.05 * ((i * 5 % 11) as f64 - 5.0) / 5.0;
    }
    fd_check(&mut balance, &zc, 1e-7);
    let scales = TorusScales {
        balance: 1.0,
        phase: 1.0,
    };
    let mut fam = TorusFamily::new(
        balance,
        |_: &mut TorusBalance<Receptance, Force>, _| Ok(()),
        phase,
        scales,
        1e-6,
    )
    .unwrap();
    let (row, value) = fix_parameter(z0.len(), alpha_a);
    let opts = {
        let mut o = ContinuationOptions::default();
        o.max_iterations = 30;
        o
    };
    let p = correct_point(
        &mut fam,
        &z0,
        &row,
        value,
        &vec![1.0; z0.len()],
        &row,
        &opts,
    )
    .unwrap()
    .expect("Newton converges");
    check_torus(&basis, &p.z, alpha_a, 1e-12);
}

#[test]
fn torus_branch_in_a_parameter() {
    // Pseudo-arclength continuation of the torus in α_a from 1.0 down to 0.3: every point on
    // the closed form to 1e-9 (the corrector's tolerance on the residual, the residual's
    // Jacobian being O(1)).
    let alpha_a = 1.0;
    let balance = mck_balance(alpha_a, Truncation::TotalOrder(3));
    let basis = balance.basis().clone();
    let (z0, phase) = guess(&basis, alpha_a);
    let scales = TorusScales {
        balance: 1.0,
        phase: 1.0,
    };
    let mut fam = TorusFamily::new(balance, set_alpha, phase, scales, 1e-6).unwrap();
    let w = vec![1.0; z0.len()];
    let (row, value) = fix_parameter(z0.len(), alpha_a);
    let opts = {
        let mut o = ContinuationOptions::default();
        o.max_iterations = 30;
        o.max_step = 0.1;
        o.parameter_range = (0.3, 2.0);
        o
    };
    let along: Vec<f64> = row.iter().map(|v| -v).collect();
    let start = correct_point(&mut fam, &z0, &row, value, &w, &along, &opts)
        .unwrap()
        .unwrap();
    assert_eq!(fam.layout().len(), basis.len());
    let branch = continue_from(
        &mut fam,
        start,
        |_| vec![1.0; basis.len() + 3],
        &opts,
        |_| Control::Continue,
    )
    .unwrap();
    assert!(branch.points.len() > 5);
    let last = branch.points.last().unwrap().parameter();
    assert!(last < 0.3 + 1e-9, "branch ended at {last}");
    for p in &branch.points {
        check_torus(&basis, &p.z, p.parameter(), 1e-9);
    }
}

/// `f = -ε (1 - x_i²) ẋ_i + κ (x_i - x_j)`-type velocity-dependent coupling on the same 4 dofs.
fn pumped(x: &[f64], v: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>) {
    let eps = 0.3;
    let mut jac = jac;
    for i in 0..4 {
        let j = (i + 1) % 4;
        f[i] = -eps * (1.0 - x[i] * x[i]) * v[i] + 0.2 * x[j] * v[j];
        if let Some(jc) = jac.as_mut() {
            jc.dfdx[i * 4 + i] = 2.0 * eps * x[i] * v[i];
            jc.dfdx[i * 4 + j] = 0.2 * v[j];
            jc.dfdxdot[i * 4 + i] = -eps * (1.0 - x[i] * x[i]);
            jc.dfdxdot[i * 4 + j] = 0.2 * x[j];
        }
    }
}

#[test]
fn velocity_dependent_jacobian_matches_finite_differences() {
    // The velocity terms of the 2-D AFT Jacobian (through D', and dF/dω1, dF/dω2) against
    // central differences; tolerance as for the displacement terms (polynomial force of degree
    // 3: truncation error ~1e-12, round-off ~1e-10).
    let basis = TorusBasis::new(4, Truncation::Box(3, 2)).unwrap();
    let (m, c, k) = matrices(0.7);
    let m = Mat::<f64>::from_fn(4, 4, |i, j| if i == j { 1.0 } else { 0.0 * m[(i, j)] });
    let linear = MckTorus::new(m.as_ref(), c.as_ref(), k.as_ref()).unwrap();
    let f = Square(FnForce::new(
        4,
        pattern(),
        true,
        pumped as fn(&[f64], &[f64], &mut [f64], Option<LocalJacobian<'_>>),
    ));
    let len = basis.len();
    let mut balance = TorusBalance::new(basis.clone(), linear, f, vec![0.0; len], None).unwrap();
    let (mut z, _) = guess(&basis, 0.7);
    for (i, v) in z.iter_mut().enumerate().take(len) {
        *v += 0.05 * ((i * 5 % 11) as f64 - 5.0) / 5.0;
    }
    fd_check(&mut balance, &z, 1e-7);
}
