//! The stages that run on rayon's threads give the same bits on one thread and on two: the
//! `"system"` interface basis of a brake large enough for faer's dense kernels to split their
//! work (its static equilibrium by dense Newton steps, the Sturm count, the Cholesky factor,
//! the block Lanczos and the residual solves: `squeal_brake::dense_par`) with dense pairs.

use faer::Mat;
use squeal_brake::contact::PenaltyCoulomb;
use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::interface_system::{SystemVectors, system_vectors_to};
use squeal_brake::model::{Brake, ContactPair};
use std::sync::Arc;

/// A brake of 640 dofs: `K` a stiff chain (its modes from 7.5 kHz up) whose first eight dofs
/// are soft and nearly free of it (eight modes of 1.6 to 4.5 kHz, well apart, as a brake's
/// in-band modes are from the rest), with weak dense coupling everywhere, `M` diagonal, 100
/// pairs whose `g` and `h` reach 40 dofs each (an interface-reduced brake's pairs reach all
/// of them), every pair in interference at rest, a piston load on the last dof.
fn brake() -> Brake {
    let n = 640;
    let soft = 8;
    let mut next = squeal_brake::partial_modes::uniform(11);
    let weak = Mat::from_fn(n, n, |_, _| next());
    let k = Mat::from_fn(n, n, |i, j| {
        let chain = if i == j && i < soft {
            1e6 * (1.0 + i as f64)
        } else if i == j {
            4e7 * (1.0 + 0.01 * i as f64)
        } else if i.abs_diff(j) == 1 && i.max(j) > soft {
            -1e7
        } else if i.abs_diff(j) == 1 {
            -1e4
        } else {
            0.0
        };
        chain + 1e2 * (weak[(i, j)] + weak[(j, i)])
    });
    let m = Mat::from_fn(
        n,
        n,
        |i, j| if i == j { 0.01 + 1e-5 * i as f64 } else { 0.0 },
    );
    let mut f_piston = vec![0.0; n];
    f_piston[n - 1] = -50.0;
    let pairs = (0..100)
        .map(|p| {
            let dofs = |shift: usize| (0..40).map(move |q| (p * 6 + q * 13 + shift) % n);
            ContactPair {
                disc_point: p,
                pad_point: p,
                position: [0.0; 3],
                normal_direction: [0.0, 0.0, 1.0],
                sliding_direction: [1.0, 0.0, 0.0],
                normal: dofs(0).map(|i| (i, 0.1 * next())).collect(),
                tangent: dofs(5).map(|i| (i, 0.1 * next())).collect(),
                initial_gap: -1e-6,
                surface_speed: None,
                law: Arc::new(PenaltyCoulomb {
                    k_linear: 2e5,
                    k_cubic: 3e14,
                }),
            }
        })
        .collect();
    Brake {
        m,
        k,
        f_piston,
        c: None,
        k_vibration: None,
        pairs,
    }
}

/// Every number of the system vectors, as bits.
fn bits(v: &SystemVectors) -> Vec<u64> {
    let mats = [&v.modes.phi, &v.residuals];
    mats.iter()
        .flat_map(|a| (0..a.ncols()).flat_map(move |j| (0..a.nrows()).map(move |i| a[(i, j)])))
        .chain(v.modes.omega.iter().copied())
        .chain(v.statics.iter().flatten().copied())
        .map(f64::to_bits)
        .collect()
}

#[test]
fn the_system_basis_has_the_same_bits_on_one_and_two_threads() {
    faer::set_global_parallelism(faer::Par::Seq);
    let b = brake();
    let newton = NewtonOptions::default();
    let run = |threads: usize| -> SystemVectors {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        // The eight soft modes (below 4.6 kHz), not the chain's (from 7.5 kHz): the partial
        // eigensolve (its flops far below the whole decomposition's).
        let top = 6000.0;
        pool.install(|| system_vectors_to(&b, &newton, top, top))
            .unwrap()
    };
    let one = run(1);
    assert!(
        !one.complete(),
        "the partial eigensolve, not the whole decomposition"
    );
    assert!(
        one.modes.omega.len() >= 8,
        "{} modes",
        one.modes.omega.len()
    );
    let two = run(2);
    assert!(bits(&one) == bits(&two), "other bits on two threads");
}
