//! NAFEMS FV52, the thick square plate (10 m × 10 m × 1 m, E = 200 GPa, ν = 0.3,
//! ρ = 8000 kg/m³).
//!
//! 1. As specified: `u_z = 0` on the four edges of the bottom face, modes 4 to 10 against
//!    the published frequencies (tests/data/nafems_fv52.csv). A support on a line is not a
//!    well-posed constraint of 3D elasticity (an H¹ displacement has no trace on a curve), so
//!    the bending modes 4–7 soften slowly as the mesh is refined: the benchmark is a
//!    fixed-mesh comparison, as in the vendors' verification manuals.
//! 2. The same plate with the 3D "hard" simple support on the side faces (Srinivas & Rao
//!    1970): the exact solution separates as trigonometric functions in x, y times functions
//!    of z, which a fine 1D discretization through the thickness gives to ~1e-8. There the
//!    tet10 frequencies are upper bounds, converge at the P2 rate, and all ten lowest are
//!    within 1% on a 12×12×3 mesh. Its (1,1) bending mode is 0.16% above NAFEMS's mode 4.

use super::common;
use common::{dense_eigenvalues, hz, lowest_eigenvalues};
use faer::Mat;
use squeal_fe::ElementKind;
use squeal_fe::{DofMap, ElasticMaterial, MaterialTable, Restraint, assemble};
use squeal_mesh::generate::{box_solid, box_tet10};

const E: f64 = 200e9;
const NU: f64 = 0.3;
const RHO: f64 = 8000.0;
const SIDE: f64 = 10.0;
const THICK: f64 = 1.0;

fn reference() -> Vec<(usize, f64)> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/nafems_fv52.csv");
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("mode"))
        .map(|l| {
            let (m, f) = l.split_once(',').unwrap();
            (m.parse().unwrap(), f.parse().unwrap())
        })
        .collect()
}

fn plate(cells: [usize; 3]) -> squeal_mesh::Mesh {
    box_tet10([SIDE, SIDE, THICK], cells)
}

/// Frequencies (Hz) of the ten lowest modes under `restraints`, with `shift` below the
/// spectrum.
fn frequencies(
    mesh: &squeal_mesh::Mesh,
    restraints: &[Restraint],
    shift: f64,
) -> (Vec<f64>, usize) {
    let materials = MaterialTable::uniform(mesh, ElasticMaterial::isotropic(E, NU, RHO)).unwrap();
    let dofs = DofMap::new(mesh, restraints).unwrap();
    let sys = assemble(mesh, &materials, &dofs).unwrap();
    let l = lowest_eigenvalues(&sys.k, &sys.m, 10, shift);
    (l, sys.num_dofs())
}

/// FV52's support: `u_z = 0` on the nodes of the bottom face's four edges.
fn bottom_edges(mesh: &squeal_mesh::Mesh) -> Restraint {
    let mut sides: Vec<u32> = ["XMIN", "XMAX", "YMIN", "YMAX"]
        .iter()
        .flat_map(|s| mesh.node_set(s).unwrap().to_vec())
        .collect();
    sides.sort();
    let edges: Vec<u32> = mesh
        .node_set("ZMIN")
        .unwrap()
        .iter()
        .copied()
        .filter(|v| sides.binary_search(v).is_ok())
        .collect();
    Restraint::nodes(edges, [false, false, true])
}

#[test]
fn nafems_fv52_as_specified() {
    as_specified(ElementKind::Tet10, &[[6, 6, 1], [8, 8, 2]]);
}

/// The same benchmark with 20-node hexahedra (one per cell). The line support is singular
/// and softens every mesh's bending modes without bound, so the published frequencies are
/// met at the benchmark's mesh size (6×6×1, the coarse meshes of the published runs): there
/// hex20 is within 3.5%. On 8×8×2 the bending modes soften further (mode 7 to −5.7%, past
/// the 5% that tet10 keeps there) and only the in-plane mode 8 and the softening are
/// asserted.
#[test]
fn nafems_fv52_as_specified_with_hex20() {
    as_specified(ElementKind::Hex20, &[[6, 6, 1]]);
    let reference = reference();
    let mut bending = Vec::new();
    for cells in [[6, 6, 1], [8, 8, 2]] {
        let mesh = box_solid(ElementKind::Hex20, [SIDE, SIDE, THICK], cells);
        let (l, _) = frequencies(&mesh, &[bottom_edges(&mesh)], -1e3);
        let f: Vec<f64> = l.iter().map(|&v| hz(v)).collect();
        let f8 = reference
            .iter()
            .find(|(m, _)| *m == 8)
            .map(|r| r.1)
            .unwrap();
        assert!(
            (f[7] / f8 - 1.0).abs() < 0.01,
            "{cells:?} mode 8: {} Hz",
            f[7]
        );
        bending.push([f[3], f[4], f[6]]);
    }
    assert!(
        (0..3).all(|i| bending[1][i] < bending[0][i]),
        "bending modes {bending:?}"
    );
}

fn as_specified(kind: ElementKind, meshes: &[[usize; 3]]) {
    let reference = reference();
    // 6×6×1 cells: elements of 1.67 m, the size of the published parabolic-tet runs of this
    // benchmark; then 8×8×2.
    let mut bending = Vec::new();
    for &cells in meshes {
        let mesh = box_solid(kind, [SIDE, SIDE, THICK], cells);
        let (l, dofs) = frequencies(&mesh, &[bottom_edges(&mesh)], -1e3);
        // Three in-plane rigid motions at round-off (~1e-16 λ_max ≈ 1e-3) against λ_4 ≈ 8e4.
        assert!(
            l[..3].iter().all(|v| v.abs() < 1e-6 * l[3]),
            "rigid modes {:?}",
            &l[..3]
        );
        let f: Vec<f64> = l.iter().map(|&v| hz(v)).collect();
        for &(mode, f_ref) in &reference {
            let err = f[mode - 1] / f_ref - 1.0;
            eprintln!(
                "FV52 {kind} {cells:?} ({dofs} dofs): mode {mode}: {:.3} Hz, reference {f_ref} Hz, {:+.2}%",
                f[mode - 1],
                100.0 * err
            );
            // Mode 8 is an in-plane mode that does not load the line support: mesh-converged,
            // within 1%. The bending modes bear on the line support: within 5% (published
            // tet10 and hex20 runs of FV52 are 1–3% off on meshes of this size).
            let tol = if mode == 8 { 0.01 } else { 0.05 };
            assert!(
                err.abs() < tol,
                "{cells:?} mode {mode}: {:.3} Hz vs {f_ref} Hz",
                f[mode - 1]
            );
        }
        bending.push([f[3], f[4], f[6]]);
    }
    // The line support weakens under refinement: bending modes 4, 5 and 7 drop.
    assert!(
        bending
            .windows(2)
            .all(|w| (0..3).all(|i| w[1][i] < w[0][i])),
        "bending modes {bending:?}"
    );
}

/// Isotropic elasticity matrix (Voigt 11, 22, 33, 12, 13, 23), written out here.
fn hooke() -> [[f64; 6]; 6] {
    let lambda = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
    let g = E / (2.0 * (1.0 + NU));
    let mut c = [[0.0; 6]; 6];
    for i in 0..3 {
        c[i][..3].fill(lambda);
        c[i][i] = lambda + 2.0 * g;
        c[i + 3][i + 3] = g;
    }
    c
}

/// Natural frequencies (Hz) of the simply supported plate (side faces: normal stress free,
/// tangential and vertical displacement zero) for half-wave numbers `(m, n)`:
/// `u_x = U(z) cos px sin qy`, `u_y = V(z) sin px cos qy`, `u_z = W(z) sin px sin qy`,
/// `p = mπ/a`, `q = nπ/a`. The strains are then `(-pU, -qV, W', qU + pV, U' + pW, V' + qW)`
/// times orthogonal trigonometric factors, and the energies reduce to 1D integrals in z,
/// discretized with `ne` quadratic elements (4-point Gauss). For `m = 0` only `U` survives,
/// for `n = 0` only `V`.
fn srinivas_frequencies(m: usize, n: usize, ne: usize) -> Vec<f64> {
    let (p, q) = (
        m as f64 * std::f64::consts::PI / SIDE,
        n as f64 * std::f64::consts::PI / SIDE,
    );
    let c = hooke();
    let size = 3 * (2 * ne + 1);
    let (mut k, mut mm) = (Mat::<f64>::zeros(size, size), Mat::<f64>::zeros(size, size));
    let gauss = [
        (-0.861_136_311_594_052_6, 0.347_854_845_137_453_8),
        (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
        (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
        (0.861_136_311_594_052_6, 0.347_854_845_137_453_8),
    ];
    let le = THICK / ne as f64;
    for e in 0..ne {
        for (g, w) in gauss {
            let s = 0.5 * (g + 1.0);
            let wq = 0.5 * w * le;
            let nf = [
                2.0 * (s - 0.5) * (s - 1.0),
                -4.0 * s * (s - 1.0),
                2.0 * s * (s - 0.5),
            ];
            let dn = [
                (4.0 * s - 3.0) / le,
                (4.0 - 8.0 * s) / le,
                (4.0 * s - 1.0) / le,
            ];
            // b[row][local dof], local dof = 3 node + (U, V, W).
            let mut b = [[0.0; 9]; 6];
            for a in 0..3 {
                b[0][3 * a] = -p * nf[a];
                b[1][3 * a + 1] = -q * nf[a];
                b[2][3 * a + 2] = dn[a];
                b[3][3 * a] = q * nf[a];
                b[3][3 * a + 1] = p * nf[a];
                b[4][3 * a] = dn[a];
                b[4][3 * a + 2] = p * nf[a];
                b[5][3 * a + 1] = dn[a];
                b[5][3 * a + 2] = q * nf[a];
            }
            for i in 0..9 {
                for j in 0..9 {
                    let (gi, gj) = (3 * (2 * e) + i, 3 * (2 * e) + j);
                    let mut v = 0.0;
                    for r in 0..6 {
                        for t in 0..6 {
                            v += b[r][i] * c[r][t] * b[t][j];
                        }
                    }
                    k[(gi, gj)] += wq * v;
                    if i % 3 == j % 3 {
                        mm[(gi, gj)] += wq * RHO * nf[i / 3] * nf[j / 3];
                    }
                }
            }
        }
    }
    let keep: Vec<usize> = (0..size)
        .filter(|i| match (m, n) {
            (0, _) => i % 3 == 0,
            (_, 0) => i % 3 == 1,
            _ => true,
        })
        .collect();
    let pick = |a: &Mat<f64>| Mat::from_fn(keep.len(), keep.len(), |i, j| a[(keep[i], keep[j])]);
    dense_eigenvalues(&pick(&k), &pick(&mm))
        .into_iter()
        .map(hz)
        .collect()
}

/// The lowest `count` frequencies over all `(m, n)` families with `m, n ≤ 4`.
fn srinivas_spectrum(count: usize, ne: usize) -> Vec<f64> {
    let mut all = Vec::new();
    for m in 0..=4 {
        for n in 0..=4 {
            if m + n > 0 {
                all.extend(srinivas_frequencies(m, n, ne).into_iter().take(4));
            }
        }
    }
    all.sort_by(f64::total_cmp);
    all.truncate(count);
    all
}

/// The hard simple support: on x = 0, a the displacements y and z are zero, on y = 0, a
/// the displacements x and z.
fn hard_support() -> [Restraint; 4] {
    [
        Restraint::set("XMIN", [false, true, true]),
        Restraint::set("XMAX", [false, true, true]),
        Restraint::set("YMIN", [true, false, true]),
        Restraint::set("YMAX", [true, false, true]),
    ]
}

#[test]
fn semi_analytical_reference_is_converged() {
    let coarse = srinivas_spectrum(10, 20);
    let fine = srinivas_spectrum(10, 40);
    for (a, b) in coarse.iter().zip(&fine) {
        // P2 in z: frequency error ~ h^4; 20 elements are within ~1e-7 of 40 (1e-6 allowed),
        // and 40 within ~1e-8 of the limit.
        assert!((a / b - 1.0).abs() < 1e-6, "{a} vs {b}");
    }
    // The first one is the (1,1) bending mode, 0.16% above NAFEMS's 45.897 Hz.
    assert!((fine[0] / 45.897 - 1.0).abs() < 0.005, "{}", fine[0]);
}

#[test]
fn hard_supported_plate_converges_at_the_p2_rate() {
    let exact = srinivas_spectrum(10, 40);
    eprintln!(
        "3D semi-analytical (Hz): {:?}",
        exact.iter().map(|f| format!("{f:.3}")).collect::<Vec<_>>()
    );
    let levels = [1, 2, 3];
    let mut errors = Vec::new();
    for k in levels {
        let cells = [4 * k, 4 * k, k];
        let (l, dofs) = frequencies(&plate(cells), &hard_support(), 0.0);
        let errs: Vec<f64> = l
            .iter()
            .zip(&exact)
            .map(|(&v, f)| hz(v) / f - 1.0)
            .collect();
        eprintln!(
            "hard support {cells:?} ({dofs} dofs): {:?}",
            l.iter()
                .zip(&errs)
                .map(|(&v, e)| format!("{:.3} Hz {:+.3}%", hz(v), 100.0 * e))
                .collect::<Vec<_>>()
        );
        // Conforming elements and consistent mass: Rayleigh–Ritz upper bounds.
        assert!(
            errs.iter().all(|&e| e > -1e-9),
            "{cells:?}: below the exact value"
        );
        errors.push(errs);
    }
    // Rate of the frequency error, mode by mode, between the two finer meshes (h ∝ 1/k):
    // P2 and a smooth solution give h^4; 3 allows for the pre-asymptotic range.
    for (mode, (e2, e3)) in errors[1].iter().zip(&errors[2]).enumerate() {
        let p = (e2 / e3).ln() / 1.5_f64.ln();
        eprintln!("mode {}: rate {p:.2}", mode + 1);
        // The in-plane shear pair (155 Hz, uniform through the thickness) is nearly exact
        // already; its error is round-off sized and has no rate.
        if *e3 > 1e-5 {
            assert!((3.0..=5.0).contains(&p), "mode {}: rate {p}", mode + 1);
        }
    }
    // On the 12×12×3 mesh all ten modes are within 1%.
    let worst = errors[2].iter().fold(0.0_f64, |a, &e| a.max(e));
    assert!(worst < 0.01, "worst error {:.3}%", 100.0 * worst);
}

/// The hard-supported plate with hex20 on 8×8×2 cells: upper bounds of the semi-analytical
/// frequencies, all ten within 1%.
#[test]
fn hex20_hard_supported_plate_is_an_upper_bound_within_one_percent() {
    let exact = srinivas_spectrum(10, 40);
    let mesh = box_solid(ElementKind::Hex20, [SIDE, SIDE, THICK], [8, 8, 2]);
    let (l, dofs) = frequencies(&mesh, &hard_support(), 0.0);
    let errs: Vec<f64> = l
        .iter()
        .zip(&exact)
        .map(|(&v, f)| hz(v) / f - 1.0)
        .collect();
    eprintln!(
        "hex20 hard support [8, 8, 2] ({dofs} dofs): {:?}",
        l.iter()
            .zip(&errs)
            .map(|(&v, e)| format!("{:.3} Hz {:+.4}%", hz(v), 100.0 * e))
            .collect::<Vec<_>>()
    );
    // Conforming elements and consistent mass: Rayleigh–Ritz upper bounds (1e-9 allows for
    // the eigensolver's round-off).
    assert!(
        errs.iter().all(|&e| e > -1e-9),
        "below the exact value: {errs:?}"
    );
    let worst = errs.iter().fold(0.0_f64, |a, &e| a.max(e));
    assert!(worst < 0.01, "worst error {:.3}%", 100.0 * worst);
}
