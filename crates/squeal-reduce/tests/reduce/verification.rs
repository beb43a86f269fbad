//! Verification of the reduced coarse parts (issue #4, item 7) against independent
//! computations on the full finite-element model.

use super::common;

use common::{coarse, coarse_brake};
use faer::Mat;
use faer::linalg::solvers::DenseSolveCore;
use squeal_eigs::{EigOptions, SparseCholesky, lowest_modes};
use squeal_fe::{DofMap, MaterialTable, Restraint, assemble};
use squeal_reduce::brake::PartInput;
use squeal_reduce::check::{Boundary, definiteness, dense_eigenvalues, reduced_frequencies};
use squeal_reduce::craig_bampton::hz;
use squeal_reduce::interface::nodal::face_nodes;
use squeal_reduce::interface::{Axis, contact_nodes, patches};
use squeal_reduce::rom::{DofLabel, InterfaceKind, ReducedPart};

/// Restraints of a bundled part.
fn restraints(part: &str) -> Vec<Restraint> {
    if part == "disc" {
        PartInput::disc("").restraints
    } else {
        PartInput::pad("").restraints
    }
}

/// The `count` lowest natural frequencies (Hz) of the full part under `restraints`
/// (shift-invert below zero: the pad keeps its rigid normal translation).
fn full_frequencies(part: &str, restraints: &[Restraint], count: usize) -> Vec<f64> {
    let loaded = coarse(part);
    let materials = MaterialTable::from_mesh(&loaded.mesh, &[]).unwrap();
    let dofmap = DofMap::new(&loaded.mesh, restraints).unwrap();
    let system = assemble(&loaded.mesh, &materials, &dofmap).unwrap();
    let mut opts = EigOptions::default();
    // (2π 100 Hz)²: below every eigenvalue, so K - σM is positive definite.
    opts.shift = -4e5;
    let modes = lowest_modes(system.k.as_ref(), system.m.as_ref(), count, &opts).unwrap();
    modes.values.iter().map(|&w2| hz(w2)).collect()
}

/// Largest relative error of the first `count` elastic frequencies (those above 1 Hz; a
/// rigid motion must be found in both, below 1 Hz).
fn worst_relative_error(reduced: &[f64], full: &[f64], count: usize) -> f64 {
    let mut worst: f64 = 0.0;
    for (r, f) in reduced.iter().zip(full).take(count) {
        if *f < 1.0 {
            assert!(
                *r < 1.0,
                "rigid motion at {f} Hz in the full model, {r} Hz reduced"
            );
            continue;
        }
        worst = worst.max((r - f).abs() / f);
    }
    worst
}

#[test]
fn free_boundary_frequencies_match_the_full_model() {
    for part in ["disc", "pad"] {
        let full = full_frequencies(part, &restraints(part), 20);
        for interface in [InterfaceKind::Patch, InterfaceKind::Node] {
            let reduced = coarse_brake(interface).part(part).unwrap();
            let f = reduced_frequencies(reduced, Boundary::Free).unwrap();
            let err = worst_relative_error(&f, &full, 20);
            eprintln!("{part} {interface:?}: worst free-boundary error {err:.3e}");
            // Craig–Bampton truncation error with 50 fixed-interface modes, measured on the
            // coarse meshes (docs/reduction.md has the table for 10 to 100 modes): disc
            // 2.4e-3 (patch) and 5.2e-4 (node) at its 20th frequency, 8.3 kHz, 0.4 of its
            // 50th fixed-interface one; pad 2.9e-2 (patch) and 2.4e-3 (node) at 14-16 kHz,
            // 0.6 of its 50th. The tolerances leave a factor of 2 for other meshes; a wrong
            // constraint mode or a missed fixed-interface mode gives errors of 10% and more.
            let tolerance = if part == "disc" { 5e-3 } else { 6e-2 };
            assert!(err < tolerance, "{part} {interface:?}: {err:e}");
            // The reduced model is a Rayleigh-Ritz approximation: never below the full one
            // (rigid motions, below 1 Hz, are round-off on both sides).
            for (r, full) in f.iter().zip(&full).take(20).filter(|(_, f)| **f > 1.0) {
                assert!(*r >= full * (1.0 - 1e-9), "{part}: {r} Hz below {full} Hz");
            }
        }
    }
}

#[test]
fn fixed_boundary_frequencies_match_the_restrained_full_model() {
    // Node interface: fixing the boundary is restraining the contact nodes (and the pad's
    // piston nodes along z) in the full model.
    let reduced_brake = coarse_brake(InterfaceKind::Node);
    for part in ["disc", "pad"] {
        let loaded = coarse(part);
        let mut held = restraints(part);
        let contact = contact_nodes(&loaded.mesh, "CONTACT", &Axis::default()).unwrap();
        held.push(Restraint::nodes(contact, [true; 3]));
        if part == "pad" {
            let pistons = loaded.mesh.node_set("PISTON").unwrap().to_vec();
            held.push(Restraint::nodes(pistons, [false, false, true]));
        }
        let full = full_frequencies(part, &held, 20);
        let reduced = reduced_brake.part(part).unwrap();
        let dense = reduced_frequencies(reduced, Boundary::Fixed).unwrap();
        for k in 0..20 {
            let stored = reduced.info.fixed_interface_hz[k];
            // Both sides are converged Lanczos eigenvalues (residual tolerance 1e-10, so
            // eigenvalue errors near 1e-16 relative) of the same operator numbered two ways:
            // they agree to round-off; 1e-9 allows for the conditioning of close pairs.
            assert!(
                (stored - full[k]).abs() < 1e-9 * full[k],
                "{part} mode {k}: {stored} vs {}",
                full[k]
            );
            // The modal block of the reduced matrices gives them back (eqs 6-7 with
            // mass-normalized modes).
            assert!((dense[k] - full[k]).abs() < 1e-9 * full[k]);
        }
    }
}

/// The constraint rows `r = C u` of a part's patch interface on its free dofs, plus the
/// piston rows.
fn patch_rows(part: &str, dofmap: &DofMap) -> Vec<Vec<(usize, f64)>> {
    let loaded = coarse(part);
    let mut rows = Vec::new();
    for p in patches(&loaded.mesh, "CONTACT_FACE", 3, 3, &Axis::default()).unwrap() {
        for d in 0..3 {
            rows.push(
                p.weights
                    .iter()
                    .map(|&(n, w)| (dofmap.free_dof(n, d).unwrap(), w))
                    .collect(),
            );
        }
    }
    if part == "pad" {
        for &n in loaded.mesh.node_set("PISTON").unwrap() {
            rows.push(vec![(dofmap.free_dof(n, 2).unwrap(), 1.0)]);
        }
    }
    rows
}

fn modal_columns(part: &ReducedPart) -> Vec<(usize, usize)> {
    part.info
        .dofs
        .iter()
        .enumerate()
        .filter_map(|(c, d)| match d {
            DofLabel::Mode { mode } => Some((c, *mode)),
            _ => None,
        })
        .collect()
}

#[test]
fn patch_fixed_interface_modes_solve_the_constrained_eigenproblem() {
    // Eqs (4)-(5) with the patch interface: K φ - ω² M φ = Cᵀ λ and C φ = 0. The reduction
    // solves them with a projected shift-invert operator on the interior dofs; here they are
    // checked on the full mesh dofs.
    let reduced_brake = coarse_brake(InterfaceKind::Patch);
    for part in ["disc", "pad"] {
        let loaded = coarse(part);
        let materials = MaterialTable::from_mesh(&loaded.mesh, &[]).unwrap();
        let dofmap = DofMap::new(&loaded.mesh, &restraints(part)).unwrap();
        let system = assemble(&loaded.mesh, &materials, &dofmap).unwrap();
        let rows = patch_rows(part, &dofmap);
        let reduced = reduced_brake.part(part).unwrap();
        let basis = &reduced.basis.as_ref().unwrap().values;
        let n = basis.nrows();
        let nc = rows.len();
        // C Cᵀ, to project residuals off the range of Cᵀ.
        let mut cct = Mat::<f64>::zeros(nc, nc);
        let mut dense_c = Mat::<f64>::zeros(nc, n);
        for (i, r) in rows.iter().enumerate() {
            for &(f, w) in r {
                dense_c[(i, f)] += w;
            }
        }
        for i in 0..nc {
            for j in 0..nc {
                cct[(i, j)] = (0..n).map(|f| dense_c[(i, f)] * dense_c[(j, f)]).sum();
            }
        }
        let cct_inv = cct.partial_piv_lu().inverse();
        for (col, mode) in modal_columns(reduced).into_iter().take(20) {
            let phi = basis.col(col).to_owned();
            let w2 = (2.0 * std::f64::consts::PI * reduced.info.fixed_interface_hz[mode]).powi(2);
            let c_phi = &dense_c * &phi;
            let scale = phi.norm_max();
            // The constraint is eliminated exactly: C φ is round-off of the weights times φ.
            assert!(
                c_phi.norm_max() < 1e-13 * scale,
                "{part} mode {mode}: C phi"
            );
            let k_phi = &system.k * &phi;
            let r = &k_phi - (&system.m * &phi) * faer::Scale(w2);
            let lambda = &cct_inv * (&dense_c * &r);
            let r_perp = &r - &(dense_c.transpose() * &lambda);
            let rel = r_perp.norm_l2() / k_phi.norm_l2();
            // A converged Ritz pair of the constrained problem (residual tolerance 1e-10
            // in the M-norm) leaves a residual near 1e-10 of ||K φ||; a wrong elimination
            // leaves O(1).
            assert!(rel < 1e-8, "{part} mode {mode}: residual {rel:e}");
        }
    }
}

#[test]
fn static_block_is_the_guyan_condensation_computed_from_the_full_flexibility() {
    // Second way for the disc (held by its clamp, so K is invertible): the Guyan stiffness
    // of the boundary coordinates r = C u is (C K⁻¹ Cᵀ)⁻¹ (minimum strain energy for given
    // r), from one factorization of the full K and a dense inverse.
    let loaded = coarse("disc");
    let materials = MaterialTable::from_mesh(&loaded.mesh, &[]).unwrap();
    let dofmap = DofMap::new(&loaded.mesh, &restraints("disc")).unwrap();
    let system = assemble(&loaded.mesh, &materials, &dofmap).unwrap();
    let factor = SparseCholesky::factorize(system.k.as_ref()).unwrap();
    for interface in [
        InterfaceKind::Patch,
        InterfaceKind::Node,
        InterfaceKind::Nodal,
    ] {
        let rows: Vec<Vec<(usize, f64)>> = match interface {
            InterfaceKind::Patch => patch_rows("disc", &dofmap),
            // Every node of the contact face, three dofs each.
            InterfaceKind::Nodal => face_nodes(&loaded.mesh, "CONTACT_FACE")
                .unwrap()
                .into_iter()
                .flat_map(|f| (0..3).map(move |d| (f.node, d)))
                .map(|(node, d)| vec![(dofmap.free_dof(node, d).unwrap(), 1.0)])
                .collect(),
            InterfaceKind::Node => contact_nodes(&loaded.mesh, "CONTACT", &Axis::default())
                .unwrap()
                .into_iter()
                .flat_map(|node| (0..3).map(move |d| (node, d)))
                .map(|(node, d)| vec![(dofmap.free_dof(node, d).unwrap(), 1.0)])
                .collect(),
        };
        let nb = rows.len();
        let n = dofmap.num_free();
        let mut ct = Mat::<f64>::zeros(n, nb);
        for (i, r) in rows.iter().enumerate() {
            for &(f, w) in r {
                ct[(f, i)] += w;
            }
        }
        let x = factor.solve(ct.as_ref()).unwrap();
        let flexibility = ct.transpose() * &x;
        let guyan = flexibility.partial_piv_lu().inverse();
        let reduced = coarse_brake(interface).part("disc").unwrap();
        let kcc = reduced.k.submatrix(0, 0, nb, nb);
        let scale = guyan.norm_max();
        let diff = (kcc - &guyan).norm_max() / scale;
        eprintln!("disc {interface:?}: Guyan difference {diff:.2e}");
        // Two factorizations and a dense inverse of a 27 x 27 flexibility whose condition
        // number is below 1e4 here: agreement to about 1e-12, asserted at 1e-9.
        assert!(diff < 1e-9, "{interface:?}: {diff:e}");
    }
}

#[test]
fn reduced_matrices_are_definite_with_the_pads_normal_translation_free() {
    for interface in [InterfaceKind::Patch, InterfaceKind::Node] {
        let brake = coarse_brake(interface);
        for part in &brake.parts {
            let d = definiteness(part).unwrap();
            let name = &part.info.name;
            eprintln!("{name} {interface:?}: {d:?}");
            // Symmetrized on output: exactly symmetric.
            assert_eq!(d.k_asymmetry, 0.0);
            assert_eq!(d.m_asymmetry, 0.0);
            // M̂ = Bᵀ M B with a basis of full column rank: positive definite, with a
            // condition number far from round-off (1e-9 of its largest eigenvalue).
            assert!(d.m_min > 1e-9 * d.m_max, "{name}: M min {:e}", d.m_min);
            // K̂ positive semi-definite: its negative eigenvalues are round-off (1e-12 of
            // the largest).
            assert!(d.k_min > -1e-12 * d.k_max, "{name}: K min {:e}", d.k_min);
            let expected = if name == "pad" { 1 } else { 0 };
            assert_eq!(d.k_zero, expected, "{name}: rigid motions of K̂");
        }
        // The pad's zero-energy motion is its normal translation: every z boundary
        // coordinate (contact points and pistons) moves by 1, modal amplitudes 0.
        let pad = brake.part("pad").unwrap();
        let n = pad.size();
        let t = Mat::<f64>::from_fn(n, 1, |i, _| match pad.info.dofs[i] {
            DofLabel::Point { direction: 2, .. } => 1.0,
            _ => 0.0,
        });
        let kt = &pad.k * &t;
        let kmax = (0..n).map(|i| pad.k[(i, i)]).fold(0.0, f64::max);
        // Rows of K̂ sum to round-off of the diagonal (1e-9 of it: the boundary block is
        // 31 x 31 with entries up to 1e10 N/m).
        assert!(kt.norm_max() < 1e-9 * kmax, "K t = {:e}", kt.norm_max());
        // Its lowest free-boundary frequency is that rigid motion (0 Hz).
        let f = reduced_frequencies(pad, Boundary::Free).unwrap();
        assert!(f[0] < 1.0 && f[1] > 1000.0, "pad: {} Hz, {} Hz", f[0], f[1]);
    }
}

#[test]
fn modal_blocks_are_the_identity_and_omega_squared() {
    for interface in [InterfaceKind::Patch, InterfaceKind::Node] {
        for part in &coarse_brake(interface).parts {
            let modes = modal_columns(part);
            let nb = part.size() - modes.len();
            for &(i, mi) in &modes {
                let w2 = (2.0 * std::f64::consts::PI * part.info.fixed_interface_hz[mi]).powi(2);
                for &(j, _) in &modes {
                    let m_target = if i == j { 1.0 } else { 0.0 };
                    let k_target = if i == j { w2 } else { 0.0 };
                    // Re-orthonormalized: M̂_NN = I to round-off; K̂_NN = diag(ω²) to the
                    // eigen residual tolerance (1e-10) times the largest ω².
                    assert!((part.m[(i, j)] - m_target).abs() < 1e-12);
                    assert!((part.k[(i, j)] - k_target).abs() < 1e-8 * w2.max(part.k[(j, j)]));
                }
                // Eq (6): no coupling between constraint modes and fixed-interface modes.
                for b in 0..nb {
                    assert!(part.k[(b, i)].abs() < 1e-10 * part.k[(b, b)]);
                }
            }
            let f = reduced_frequencies(part, Boundary::Fixed).unwrap();
            let values = dense_eigenvalues(&part.k, &part.m, &part.info.name).unwrap();
            assert_eq!(values.len(), part.size());
            assert_eq!(f.len(), modes.len());
        }
    }
}
