//! Viscous dampers projected by the Craig–Bampton basis ([`squeal_reduce::dampers`]): a free
//! steel cube on springs over its bottom face and a dashpot under it moves vertically as one
//! damped degree of freedom, `λ = −c/(2m) ± i √(k/m − c²/(4m²))`.

use faer::{Mat, Side, c64};
use squeal_fe::{ElasticMaterial, MaterialTable};
use squeal_mesh::Mesh;
use squeal_mesh::generate::box_tet10_origin;
use squeal_reduce::craig_bampton::{PartSpec, ReduceOptions, reduce_part};
use squeal_reduce::dampers::{Damper, Spread, reduced_damping};
use squeal_reduce::rom::{MeshInfo, PartRole, ReducedPart};
use squeal_reduce::tie::Support;

const STEEL: (f64, f64, f64) = (210e9, 0.3, 7850.0);

fn add_node_set(mesh: &mut Mesh, name: &str, x: [f64; 3]) {
    let n = (0..mesh.num_nodes() as u32)
        .find(|&n| (0..3).all(|d| (mesh.nodes[n as usize][d] - x[d]).abs() < 1e-12))
        .expect("a node there");
    mesh.node_sets.insert(name.into(), vec![n]);
}

fn spec(supports: Vec<Support>, modes: usize) -> PartSpec {
    PartSpec {
        contact_set: "TIP".into(),
        contact_face_set: "TIP".into(),
        grid: [1, 1],
        supports,
        ..PartSpec::new("block", PartRole::Pad, MeshInfo::in_memory("block"), modes)
    }
}

fn reduce(mesh: &Mesh, spec: &PartSpec, keep_basis: bool) -> ReducedPart {
    let steel = MaterialTable::uniform(mesh, ElasticMaterial::isotropic(STEEL.0, STEEL.1, STEEL.2))
        .unwrap();
    let o = ReduceOptions {
        keep_basis,
        ..Default::default()
    };
    reduce_part(mesh, &steel, spec, &o, &mut |_| {}).unwrap().0
}

/// The eigenvalues of `λ² M + λ C + K` with `Im λ > 0`, from the inverse of the first-order
/// form, `A⁻¹ = [[−K⁻¹ C, −K⁻¹ M], [I, 0]]` (eigenvalues `1/λ`): the lowest modes, which
/// this test is about, are then its largest eigenvalues, computed to round-off of `|A⁻¹|`
/// instead of being swamped by the stiff elastic modes (`|A| ~ ω_max²`).
fn quadratic_eigenvalues(m: &Mat<f64>, c: &Mat<f64>, k: &Mat<f64>) -> Vec<c64> {
    let n = m.nrows();
    let llt = k.llt(Side::Lower).unwrap();
    use faer::linalg::solvers::Solve;
    let (kc, km) = (llt.solve(c), llt.solve(m));
    let a = Mat::from_fn(2 * n, 2 * n, |i, j| match (i < n, j < n) {
        (true, true) => -kc[(i, j)],
        (true, false) => -km[(i, j - n)],
        (false, true) => {
            if i - n == j {
                1.0
            } else {
                0.0
            }
        }
        (false, false) => 0.0,
    });
    a.eigenvalues()
        .unwrap()
        .into_iter()
        .map(|mu| 1.0 / mu)
        .filter(|l| l.im > 0.0)
        .collect()
}

#[test]
fn a_cube_on_a_spring_and_a_dashpot_is_a_damped_single_dof() {
    let a = 0.02;
    let mut m = box_tet10_origin([0.0; 3], [a, a, a], [2, 2, 2]);
    add_node_set(&mut m, "TIP", [a, a, a]);
    let mass = STEEL.2 * a * a * a;
    // 100 Hz vertically, far below the cube's first elastic mode (about 80 kHz).
    let w0 = 2.0 * std::f64::consts::PI * 100.0;
    let k = mass * w0 * w0;
    let held = spec(
        vec![Support {
            set: "ZMIN".into(),
            stiffness: [k, k, k],
        }],
        20,
    );
    let part = reduce(&m, &held, true);
    for (zeta, spread) in [
        (0.1, Spread::Mean),
        (0.1, Spread::Area),
        (0.7, Spread::Mean),
    ] {
        let damper = Damper {
            set: "ZMIN".into(),
            to: None,
            damping: [0.0, 0.0, 2.0 * zeta * mass * w0],
            axes: None,
            spread,
        };
        let c = reduced_damping(&m, &part, &[damper]).unwrap();
        // Ĉ is symmetric by construction (a sum of c r rᵀ).
        for i in 0..c.nrows() {
            for j in 0..i {
                assert_eq!(c[(i, j)], c[(j, i)]);
            }
        }
        let values = quadratic_eigenvalues(&part.m, &c, &part.k);
        let exact = c64::new(-zeta * w0, w0 * (1.0 - zeta * zeta).sqrt());
        let l = values
            .iter()
            .copied()
            .min_by(|x, y| (x - exact).norm().total_cmp(&(y - exact).norm()))
            .unwrap();
        let error = (l - exact).norm() / exact.norm();
        eprintln!("zeta {zeta} {spread:?}: {l} against {exact} ({error:.2e})");
        // The elastic cube couples with the vertical motion by about (f0 / f_elastic)² ≈ 2e-6
        // (the spring-only test of tests/reduce/tie.rs: the same order); measured 1.2e-6 (ζ = 0.1,
        // both spreads) and 2.3e-6 (ζ = 0.7), asserted 1e-5.
        assert!(
            error < 1e-5,
            "zeta {zeta} {spread:?}: {l} vs {exact} ({error:.2e})"
        );
    }
    // Without the basis there is nothing to project on.
    let bare = reduce(&m, &held, false);
    let damper = Damper {
        set: "ZMIN".into(),
        to: None,
        damping: [1.0, 0.0, 0.0],
        axes: None,
        spread: Spread::Mean,
    };
    let e = reduced_damping(&m, &bare, std::slice::from_ref(&damper))
        .unwrap_err()
        .to_string();
    assert!(e.contains("without its basis"), "{e}");
    // A damper's numbers are checked as a spring's, in its own words.
    let e = reduced_damping(
        &m,
        &part,
        &[Damper {
            damping: [0.0; 3],
            ..damper
        }],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("damper from ZMIN to ground: damping [0, 0, 0] N s/m"),
        "{e}"
    );
}
