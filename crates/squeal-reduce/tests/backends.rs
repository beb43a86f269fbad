//! The two eigensolver backends give the same reduced brake (run with `--features arpack`).

#![cfg(feature = "arpack")]

#[path = "reduce/common/mod.rs"]
mod common;

use common::{coarse_brake, coarse_inputs, reduce};
use squeal_eigs::Backend;
use squeal_reduce::rom::InterfaceKind;

#[test]
fn lanczos_and_arpack_agree_on_all_fifty_frequencies() {
    let lanczos = coarse_brake(InterfaceKind::Patch);
    let arpack = reduce(&squeal_reduce::brake::BrakeInputs {
        backend: Backend::Arpack,
        ..coarse_inputs(InterfaceKind::Patch)
    });
    for (a, b) in lanczos.parts.iter().zip(&arpack.parts) {
        assert_eq!(a.info.fixed_interface_hz.len(), 50);
        for (k, (fa, fb)) in a
            .info
            .fixed_interface_hz
            .iter()
            .zip(&b.info.fixed_interface_hz)
            .enumerate()
        {
            // Both solve to a Ritz residual of 1e-10, so eigenvalue errors are far below
            // 1e-12; 1e-9 is the agreement criterion.
            assert!(
                (fa - fb).abs() < 1e-9 * fa,
                "{} mode {k}: {fa} vs {fb}",
                a.info.name
            );
        }
        // The constraint modes do not involve the eigensolver: the same bits.
        let nb = a.size() - 50;
        for i in 0..nb {
            for j in 0..nb {
                assert_eq!(a.k[(i, j)], b.k[(i, j)]);
            }
        }
    }
}
