//! Elasticity matrices against closed forms and against each other, and material assignment
//! from a mesh's sections and overrides.

use squeal_fe::{ElasticMaterial, FeError, MaterialError, MaterialTable, Voigt6};
use squeal_mesh::{Elastic, Material, Section};

/// Largest entry difference relative to the largest entry.
fn rel_diff(a: &Voigt6, b: &Voigt6) -> f64 {
    let scale = a.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    let diff = a
        .iter()
        .flatten()
        .zip(b.iter().flatten())
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    diff / scale
}

/// Strain from stress, `ε = C⁻¹ σ`, by Gaussian elimination (an algorithm independent of
/// the crate's Cholesky).
fn strain(c: &Voigt6, sigma: [f64; 6]) -> [f64; 6] {
    let mut a: Vec<Vec<f64>> = (0..6)
        .map(|i| [c[i].to_vec(), vec![sigma[i]]].concat())
        .collect();
    for k in 0..6 {
        let p = (k..6)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .unwrap();
        a.swap(k, p);
        let pivot = a[k].clone();
        for row in a.iter_mut().skip(k + 1) {
            let f = row[k] / pivot[k];
            for (x, p) in row.iter_mut().zip(&pivot).skip(k) {
                *x -= f * p;
            }
        }
    }
    let mut x = [0.0; 6];
    for i in (0..6).rev() {
        x[i] = (a[i][6] - (i + 1..6).map(|j| a[i][j] * x[j]).sum::<f64>()) / a[i][i];
    }
    x
}

#[test]
fn isotropic_matches_lame_form() {
    let (e, nu) = (210e9, 0.3);
    let c = ElasticMaterial::isotropic(e, nu, 7850.0)
        .elasticity()
        .unwrap();
    // Uniaxial stress: ε11 = σ/E, ε22 = ε33 = -ν σ/E; pure shear γ12 = τ/G.
    let eps = strain(&c, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    // Elimination on a 6×6 with condition number ~3: round-off ~1e-15 relative.
    assert!((eps[0] * e - 1.0).abs() < 1e-13);
    assert!((eps[1] * e + nu).abs() < 1e-13 && (eps[2] * e + nu).abs() < 1e-13);
    let g = e / (2.0 * (1.0 + nu));
    let eps = strain(&c, [0.0, 0.0, 0.0, 1.0, 0.0, 0.0]);
    assert!((eps[3] * g - 1.0).abs() < 1e-13);
}

#[test]
fn degenerate_anisotropic_forms_reduce_to_isotropic() {
    let (e, nu, rho) = (70e9, 0.33, 2700.0);
    let g = e / (2.0 * (1.0 + nu));
    let iso = ElasticMaterial::isotropic(e, nu, rho).elasticity().unwrap();
    let ortho = ElasticMaterial::Orthotropic {
        e: [e; 3],
        nu: [nu; 3],
        g: [g; 3],
        density: rho,
    };
    let trans = ElasticMaterial::TransverselyIsotropic {
        young_plane: e,
        poisson_plane: nu,
        young_axial: e,
        poisson_plane_axial: nu,
        shear_axial: g,
        axis: [0.3, -0.5, 0.8],
        density: rho,
    };
    // Compliance inversion and a rotation by an arbitrary frame: a few ulps per operation.
    assert!(rel_diff(&iso, &ortho.elasticity().unwrap()) < 1e-13);
    assert!(rel_diff(&iso, &trans.elasticity().unwrap()) < 1e-13);
}

/// A pad lining: soft through the thickness.
fn lining(axis: [f64; 3]) -> ElasticMaterial {
    ElasticMaterial::TransverselyIsotropic {
        young_plane: 6.0e9,
        poisson_plane: 0.25,
        young_axial: 2.0e9,
        poisson_plane_axial: 0.12,
        shear_axial: 1.1e9,
        axis,
        density: 2500.0,
    }
}

#[test]
fn transversely_isotropic_about_z_equals_abaqus_engineering_constants() {
    let (ep, nup, ea, nupa, ga) = (6.0e9, 0.25, 2.0e9, 0.12, 1.1e9);
    let gp = ep / (2.0 * (1.0 + nup));
    let ortho = ElasticMaterial::Orthotropic {
        e: [ep, ep, ea],
        nu: [nup, nupa, nupa],
        g: [gp, ga, ga],
        density: 2500.0,
    };
    let t = lining([0.0, 0.0, 2.0]).elasticity().unwrap();
    // Same compliance, the rotation is the identity up to the in-plane frame: round-off only.
    assert!(rel_diff(&t, &ortho.elasticity().unwrap()) < 1e-13);
    // Axis x: E1 = E_a, E2 = E3 = E_p. Abaqus ν12 = ν_ap = ν_pa E_a / E_p (reciprocity),
    // ν13 = ν_ap, ν23 = ν_p; G12 = G13 = G_a, G23 = G_p.
    let nuap = nupa * ea / ep;
    let ortho_x = ElasticMaterial::Orthotropic {
        e: [ea, ep, ep],
        nu: [nuap, nuap, nup],
        g: [ga, ga, gp],
        density: 2500.0,
    };
    let tx = lining([-1.0, 0.0, 0.0]).elasticity().unwrap();
    assert!(rel_diff(&tx, &ortho_x.elasticity().unwrap()) < 1e-13);
}

#[test]
fn transversely_isotropic_about_oblique_axis_has_the_stated_moduli() {
    let (ep, nup, ea, nupa, ga) = (6.0e9, 0.25, 2.0e9, 0.12, 1.1e9);
    let a = {
        let v = [1.0_f64, 2.0, 2.0];
        v.map(|x| x / 3.0)
    };
    // p: a unit vector normal to a; q = a × p.
    let p = [2.0 / 3.0, 1.0 / 3.0, -2.0 / 3.0];
    let q = [
        a[1] * p[2] - a[2] * p[1],
        a[2] * p[0] - a[0] * p[2],
        a[0] * p[1] - a[1] * p[0],
    ];
    let c = lining(a).elasticity().unwrap();
    // Voigt stress of the tensor u⊗v + v⊗u (scaled) and the normal strain along w.
    let stress = |u: [f64; 3], v: [f64; 3]| {
        let s = |i: usize, j: usize| 0.5 * (u[i] * v[j] + u[j] * v[i]);
        [s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(0, 2), s(1, 2)]
    };
    let along = |eps: [f64; 6], u: [f64; 3], v: [f64; 3]| {
        // u·ε·v with tensor shear ε_ij = γ_ij / 2.
        let t = [
            [eps[0], eps[3] / 2.0, eps[4] / 2.0],
            [eps[3] / 2.0, eps[1], eps[5] / 2.0],
            [eps[4] / 2.0, eps[5] / 2.0, eps[2]],
        ];
        (0..3)
            .map(|i| (0..3).map(|j| u[i] * t[i][j] * v[j]).sum::<f64>())
            .sum::<f64>()
    };
    // Elimination and rotation round-off: 1e-12 relative to compliances of order 1/E.
    let tol = 1e-12;
    // Uniaxial stress along the axis: ε_aa = 1/E_a, lateral ε_pp = -ν_ap/E_a = -ν_pa/E_p.
    let e = strain(&c, stress(a, a));
    assert!((along(e, a, a) * ea - 1.0).abs() < tol);
    assert!((along(e, p, p) * ep + nupa).abs() < tol);
    // Uniaxial stress in the plane: ε_pp = 1/E_p, ε_qq = -ν_p/E_p, ε_aa = -ν_pa/E_p.
    let e = strain(&c, stress(p, p));
    assert!((along(e, p, p) * ep - 1.0).abs() < tol);
    assert!((along(e, q, q) * ep + nup).abs() < tol);
    assert!((along(e, a, a) * ep + nupa).abs() < tol);
    // Shear τ = a·σ·p = 1/2 in the a–p plane: tensor strain ε_ap = τ / (2 G_a) = 1 / (4 G_a).
    let e = strain(&c, stress(a, p));
    assert!((4.0 * along(e, a, p) * ga - 1.0).abs() < tol);
}

#[test]
fn invalid_constants_are_typed_errors() {
    let bad = |m: ElasticMaterial| m.elasticity().unwrap_err();
    assert_eq!(
        bad(ElasticMaterial::isotropic(210e9, 0.5, 7850.0)),
        MaterialError::NotPositiveDefinite
    );
    assert_eq!(
        bad(ElasticMaterial::isotropic(210e9, 0.6, 7850.0)),
        MaterialError::NotPositiveDefinite
    );
    assert_eq!(
        bad(ElasticMaterial::isotropic(210e9, -1.2, 7850.0)),
        MaterialError::NotPositiveDefinite
    );
    assert_eq!(
        bad(ElasticMaterial::isotropic(-1e9, 0.3, 7850.0)),
        MaterialError::NotPositiveDefinite
    );
    assert_eq!(
        bad(ElasticMaterial::isotropic(210e9, 0.3, 0.0)),
        MaterialError::NonPositiveDensity(0.0)
    );
    assert_eq!(
        bad(ElasticMaterial::isotropic(f64::NAN, 0.3, 1.0)),
        MaterialError::NotFinite
    );
    assert_eq!(bad(lining([0.0; 3])), MaterialError::ZeroAxis);
    // ν12² < E1/E2 violated: ν12 = 2 with E1 = E2.
    let ortho = ElasticMaterial::Orthotropic {
        e: [1e9; 3],
        nu: [2.0, 0.1, 0.1],
        g: [1e8; 3],
        density: 1.0,
    };
    assert_eq!(bad(ortho), MaterialError::NotPositiveDefinite);
    // Each ν² < E_i/E_j holds, but 1 - ν12ν21 - ν23ν32 - ν13ν31 - 2ν21ν32ν13 = -2.888 < 0.
    let ortho = ElasticMaterial::Orthotropic {
        e: [1e9; 3],
        nu: [0.9, 0.9, 0.9],
        g: [1e8; 3],
        density: 1.0,
    };
    assert_eq!(bad(ortho), MaterialError::NotPositiveDefinite);
}

/// A 2×1×1 box whose elements 0..6 are set LEFT and 6..12 set RIGHT.
fn two_part_mesh() -> squeal_mesh::Mesh {
    let mut mesh = squeal_mesh::generate::box_tet10([2.0, 1.0, 1.0], [2, 1, 1]);
    mesh.element_sets.insert("LEFT".into(), (0..6).collect());
    mesh.element_sets.insert("RIGHT".into(), (6..12).collect());
    let steel = Material {
        elastic: Some(Elastic::Isotropic {
            young: 210e9,
            poisson: 0.3,
        }),
        density: Some(7850.0),
    };
    mesh.materials.insert("Steel".into(), steel);
    mesh.sections.push(Section {
        element_set: "LEFT".into(),
        material: "STEEL".into(),
    });
    mesh
}

#[test]
fn sections_and_overrides_assign_materials() {
    let mut mesh = two_part_mesh();
    // RIGHT has no section yet: its first element (file id 7) is reported.
    match MaterialTable::from_mesh(&mesh, &[]) {
        Err(FeError::NoMaterial { element, others }) => assert_eq!((element, others), (7, 5)),
        other => panic!("expected NoMaterial, got {other:?}"),
    }
    let pad = ElasticMaterial::isotropic(5e9, 0.25, 2500.0);
    let t = MaterialTable::from_mesh(&mesh, &[("right".into(), pad)]).unwrap();
    assert_eq!(t.of_element(0).unwrap().name, "Steel");
    assert_eq!(t.of_element(11).unwrap().material, pad);
    // An override of ALL after RIGHT wins everywhere; an unknown set is an error.
    let alu = ElasticMaterial::isotropic(70e9, 0.33, 2700.0);
    let t = MaterialTable::from_mesh(&mesh, &[("RIGHT".into(), pad), ("ALL".into(), alu)]).unwrap();
    assert_eq!(t.entries.len(), 1);
    assert!(
        t.element_entry
            .iter()
            .all(|&i| t.entries[i as usize].material == alu)
    );
    assert!(matches!(
        MaterialTable::from_mesh(&mesh, &[("NOPE".into(), pad)]),
        Err(FeError::UnknownElementSet(_))
    ));
    // A section whose material lacks a density is an error only if some element keeps it.
    mesh.materials.insert(
        "Rubber".into(),
        Material {
            elastic: Some(Elastic::Isotropic {
                young: 1e7,
                poisson: 0.45,
            }),
            density: None,
        },
    );
    mesh.sections.push(Section {
        element_set: "RIGHT".into(),
        material: "Rubber".into(),
    });
    assert!(matches!(
        MaterialTable::from_mesh(&mesh, &[]),
        Err(FeError::IncompleteMaterial { .. })
    ));
    assert!(MaterialTable::from_mesh(&mesh, &[("RIGHT".into(), pad)]).is_ok());
    // An invalid override is named by its set.
    let bad = ElasticMaterial::isotropic(1e9, 0.5, 1.0);
    match MaterialTable::from_mesh(&mesh, &[("RIGHT".into(), bad)]) {
        Err(e @ FeError::InvalidMaterial { .. }) => {
            // Printed once, also in an error chain (`{:#}`, as the CLI prints).
            let chain = format!("{:#}", anyhow::Error::from(e));
            assert_eq!(chain.matches("not positive definite").count(), 1, "{chain}");
            assert!(chain.starts_with("material 'RIGHT': "), "{chain}");
        }
        other => panic!("expected InvalidMaterial, got {other:?}"),
    }
}

#[test]
fn engineering_constants_from_the_mesh_become_orthotropic() {
    let mut mesh = two_part_mesh();
    let e = [10e9, 20e9, 30e9];
    let nu = [0.2, 0.25, 0.3];
    let g = [4e9, 5e9, 6e9];
    mesh.materials.insert(
        "Ortho".into(),
        Material {
            elastic: Some(Elastic::EngineeringConstants { e, nu, g }),
            density: Some(1500.0),
        },
    );
    mesh.sections.push(Section {
        element_set: "RIGHT".into(),
        material: "Ortho".into(),
    });
    let t = MaterialTable::from_mesh(&mesh, &[]).unwrap();
    let c = t.of_element(6).unwrap().elasticity;
    // Abaqus convention: stress σ1 gives ε2 = -ν12 σ1/E1; σ3 gives ε2 = -ν23 E2... via
    // reciprocity ν32 = ν23 E3/E2, so ε2 = -ν32 σ3 / E3 = -ν23 σ3 / E2.
    let eps = strain(&c, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    assert!((eps[0] * e[0] - 1.0).abs() < 1e-13);
    assert!((eps[1] * e[0] + nu[0]).abs() < 1e-13);
    assert!((eps[2] * e[0] + nu[1]).abs() < 1e-13);
    let eps = strain(&c, [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
    assert!((eps[1] * e[1] + nu[2]).abs() < 1e-13);
    let eps = strain(&c, [0.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
    assert!((eps[5] * g[2] - 1.0).abs() < 1e-13);
}
