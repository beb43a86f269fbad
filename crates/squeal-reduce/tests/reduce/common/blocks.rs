//! Fixtures of the part tests (`parts.rs`, `part_ties.rs`): steel, a body's reduction
//! specification with nothing but its restraints and mode count, dense frequencies and a
//! block-diagonal assembly.

#![allow(dead_code)]

use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::{Mat, Par, Side};
use squeal_fe::{ElasticMaterial, MaterialTable, Restraint};
use squeal_mesh::Mesh;
use squeal_reduce::craig_bampton::PartSpec;
use squeal_reduce::rom::{MeshInfo, PartRole};

pub fn steel(mesh: &Mesh) -> MaterialTable {
    MaterialTable::uniform(mesh, ElasticMaterial::isotropic(210e9, 0.3, 7850.0)).unwrap()
}

pub fn spec(name: &str, restraints: Vec<Restraint>, modes: usize) -> PartSpec {
    PartSpec {
        restraints,
        grid: [1, 1],
        ..PartSpec::new(name, PartRole::Body, MeshInfo::in_memory(name), modes)
    }
}

/// Frequencies (Hz) of `K x = ω² M x`, ascending (dense: `M = L Lᵀ`).
pub fn frequencies(k: &Mat<f64>, m: &Mat<f64>) -> Vec<f64> {
    let l = m.llt(Side::Lower).unwrap().L().to_owned();
    let mut x = k.clone();
    solve_lower_triangular_in_place(l.as_ref(), x.as_mut(), Par::Seq);
    let mut y = x.transpose().to_owned();
    solve_lower_triangular_in_place(l.as_ref(), y.as_mut(), Par::Seq);
    let y = Mat::from_fn(y.nrows(), y.ncols(), |i, j| 0.5 * (y[(i, j)] + y[(j, i)]));
    y.self_adjoint_eigenvalues(Side::Lower)
        .unwrap()
        .into_iter()
        .map(|w2| w2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
        .collect()
}

pub fn block_diag(a: &Mat<f64>, b: &Mat<f64>) -> Mat<f64> {
    let (na, nb) = (a.nrows(), b.nrows());
    Mat::from_fn(na + nb, na + nb, |i, j| match (i < na, j < na) {
        (true, true) => a[(i, j)],
        (false, false) => b[(i - na, j - na)],
        _ => 0.0,
    })
}
