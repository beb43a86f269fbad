//! Criterion benches: residual and Jacobian of eq. (26) for a 36-dof stand-in of the brake's
//! nonlinear dofs (9 cubic unilateral contact pairs with friction, eqs. 8-9) at H = 1, 3,
//! 5, 10; full solves (van der Pol H = 7, forced 36-dof contact H = 3).
//!
//! Run: `nice cargo bench -p squeal-hbm --bench hbm`

#[path = "../tests/hbm/common/mod.rs"]
mod common;

use std::hint::black_box;
use std::time::Duration;

use common::{ContactPairs, scalar, van_der_pol_force};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use faer::Mat;
use squeal_hbm::*;

const N_DOFS: usize = 36;

/// A 36-dof chain (M = I, K = 100 tridiag(-1, 2, -1), Rayleigh C = 0.01 M + 0.002 K) with
/// 9 contact pairs on consecutive dof quadruples (kl = 20, knl = 1e4, mu = 0.3), a static
/// load 0.2 closing every contact and a harmonic load 0.5 cos(3 t) on the first tangential
/// dof. The forced H = 3 solution opens the contacts at about 15 % of the samples.
fn contact_system(h: usize) -> HarmonicBalance<MckStiffness, ContactPairs> {
    let n = N_DOFS;
    let layout = HarmonicLayout::new(n, h).unwrap();
    let m = Mat::<f64>::identity(n, n);
    let k = Mat::from_fn(n, n, |i, j| match i.abs_diff(j) {
        0 => 200.0,
        1 => -100.0,
        _ => 0.0,
    });
    let c = Mat::from_fn(n, n, |i, j| 0.01 * m[(i, j)] + 0.002 * k[(i, j)]);
    let linear = MckStiffness::new(m.as_ref(), c.as_ref(), k.as_ref()).unwrap();
    let force = ContactPairs::new(N_DOFS / 4, 20.0, 1e4, 0.3);
    let mut f_ext = vec![0.0; layout.len()];
    for p in 0..N_DOFS / 4 {
        f_ext[4 * p + 1] = 0.2;
        f_ext[4 * p + 3] = -0.2;
    }
    f_ext[layout.index(1, Part::Cos, 0).unwrap()] = 0.5;
    HarmonicBalance::new(layout, linear, force, f_ext, None).unwrap()
}

/// A deterministic state with partial contact opening.
fn state(layout: &HarmonicLayout) -> Vec<f64> {
    let mut u: Vec<f64> = (0..layout.len())
        .map(|i| 0.004 * (((i * 37) % 17) as f64 / 8.0 - 1.0))
        .collect();
    for p in 0..N_DOFS / 4 {
        u[4 * p + 1] = 0.005;
        u[4 * p + 3] = -0.005;
    }
    u
}

fn residual_and_jacobian(c: &mut Criterion) {
    let mut group = c.benchmark_group("contact36");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    for h in [1, 3, 5, 10] {
        let mut hb = contact_system(h);
        let layout = hb.layout();
        let u = state(&layout);
        let len = layout.len();
        let mut r = vec![0.0; len];
        let mut jac = Mat::zeros(len, len);
        let mut jac_w = vec![0.0; len];
        group.bench_with_input(BenchmarkId::new("residual", h), &h, |b, _| {
            b.iter(|| hb.residual(black_box(&u), 3.0, &mut r).unwrap())
        });
        group.bench_with_input(BenchmarkId::new("jacobian", h), &h, |b, _| {
            b.iter(|| {
                hb.jacobian(black_box(&u), 3.0, jac.as_mut(), &mut jac_w)
                    .unwrap()
            })
        });
    }
    group.finish();
}

fn solves(c: &mut Criterion) {
    let mut group = c.benchmark_group("solve");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_millis(500));

    let layout = HarmonicLayout::new(1, 7).unwrap();
    let linear = MckStiffness::new(
        scalar(1.0).as_ref(),
        scalar(-1.0).as_ref(),
        scalar(1.0).as_ref(),
    )
    .unwrap();
    let mut vdp = HarmonicBalance::new(
        layout,
        linear,
        van_der_pol_force(),
        vec![0.0; layout.len()],
        None,
    )
    .unwrap();
    let mut u0 = vec![0.0; layout.len()];
    u0[layout.index(1, Part::Cos, 0).unwrap()] = 2.0;
    let phase = PhaseCondition::FirstSineZero { dof: 0 };
    group.bench_function("van_der_pol_H7", |b| {
        b.iter(|| {
            solve_autonomous(&mut vdp, phase, black_box(&u0), 1.0, &LmOptions::default()).unwrap()
        })
    });

    let mut hb = contact_system(3);
    let u0 = state(&hb.layout());
    let sol = solve_forced(&mut hb, 3.0, &u0, &LmOptions::default()).unwrap();
    println!(
        "forced contact36 H=3: {} unknowns, {} LM trials, {} Jacobians, |r| = {:.2e}",
        hb.layout().len(),
        sol.report.iterations,
        sol.report.jacobian_evaluations,
        sol.report.residual_norm
    );
    group.bench_function("forced_contact36_H3", |b| {
        b.iter(|| solve_forced(&mut hb, 3.0, black_box(&u0), &LmOptions::default()).unwrap())
    });
    group.finish();
}

criterion_group!(benches, residual_and_jacobian, solves);
criterion_main!(benches);
