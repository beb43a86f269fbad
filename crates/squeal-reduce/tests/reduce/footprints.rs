//! Pistons as footprints on the coarse pad: each footprint keeps one coordinate, its
//! area-weighted mean motion along the normal (`PartSpec::piston_footprints`). Checked
//! against the piston nodes (a footprint of one node is that node, bit for bit) and against
//! the full finite-element model of the pad (frequencies on springs are a Ritz projection's;
//! a static load on a footprint's coordinate is its force spread over the footprint).

use super::common;

use faer::Mat;
use faer::prelude::Solve;
use faer::sparse::{SparseColMat, Triplet};
use squeal_eigs::{EigOptions, SparseCholesky, lowest_modes};
use squeal_fe::{DofMap, MaterialTable, Restraint};
use squeal_mesh::Mesh;
use squeal_reduce::craig_bampton::{PartSpec, ReduceOptions, reduce_part};
use squeal_reduce::interface::{Axis, footprint, patches};
use squeal_reduce::rom::{InterfaceKind, MeshInfo, ReducedPart};

/// The coarse pad with its two 40 mm piston footprints as node sets `FOOT_1`, `FOOT_2`.
fn pad() -> Mesh {
    let mut mesh = common::coarse("pad").mesh;
    common::add_footprints(&mut mesh);
    mesh
}

fn spec(mesh: &Mesh, footprints: Vec<String>, modes: usize) -> PartSpec {
    let inputs = common::coarse_inputs(InterfaceKind::Patch);
    let info = MeshInfo {
        path: "pad_coarse.inp".into(),
        sha256: String::new(),
        nodes: mesh.num_nodes(),
        elements: mesh.num_elements(),
    };
    PartSpec {
        piston_footprints: footprints,
        modes,
        ..inputs.spec("pad", inputs.pad(), info)
    }
}

fn reduce(mesh: &Mesh, spec: &PartSpec) -> ReducedPart {
    let materials = MaterialTable::from_mesh(mesh, &[]).unwrap();
    reduce_part(
        mesh,
        &materials,
        spec,
        &ReduceOptions::default(),
        &mut |_| {},
    )
    .unwrap()
    .0
}

fn footprints() -> Vec<String> {
    vec!["FOOT_1".into(), "FOOT_2".into()]
}

#[test]
fn a_footprint_of_one_node_is_that_piston_node_bit_for_bit() {
    let mut mesh = pad();
    let nodes = mesh.node_set("PISTON").unwrap().to_vec();
    assert_eq!(nodes.len(), 4);
    let mut ones = Vec::new();
    for (k, &n) in nodes.iter().enumerate() {
        let name = format!("ONE_{k}");
        mesh.node_sets.insert(name.clone(), vec![n]);
        ones.push(name);
    }
    let a = reduce(&mesh, &spec(&mesh, Vec::new(), 20));
    let b = reduce(&mesh, &spec(&mesh, ones, 20));
    // The same rows, eliminated dofs and factor: the same bits.
    assert_eq!(a.info.points, b.info.points);
    assert_eq!(a.info.dofs, b.info.dofs);
    assert_eq!(a.k, b.k);
    assert_eq!(a.m, b.m);
    assert_eq!(a.basis, b.basis);
}

/// The pad's free dofs, `K` and `M`, and the rows `C` of its boundary coordinates as the
/// reduction orders them: the 9 contact patches' mean motions (x, y, z each), then the two
/// footprints' mean motion along z.
struct Full {
    dofmap: DofMap,
    k: SparseColMat<usize, f64>,
    m: SparseColMat<usize, f64>,
    rows: Vec<Vec<(usize, f64)>>,
}

fn full(mesh: &Mesh) -> Full {
    let materials = MaterialTable::from_mesh(mesh, &[]).unwrap();
    let dofmap = DofMap::new(mesh, &[Restraint::set("ABUTMENT", [true, true, false])]).unwrap();
    let system = squeal_fe::assemble(mesh, &materials, &dofmap).unwrap();
    let mut rows = Vec::new();
    for p in patches(mesh, "CONTACT_FACE", 3, 3, &Axis::default()).unwrap() {
        for d in 0..3 {
            rows.push(
                p.weights
                    .iter()
                    .map(|&(n, w)| (dofmap.free_dof(n, d).unwrap(), w))
                    .collect(),
            );
        }
    }
    for set in footprints() {
        let f = footprint(mesh, &set).unwrap();
        rows.push(
            f.weights
                .iter()
                .map(|&(n, w)| (dofmap.free_dof(n, 2).unwrap(), w))
                .collect(),
        );
    }
    Full {
        dofmap,
        k: system.k,
        m: system.m,
        rows,
    }
}

/// `K + Σ_b s_b c_bᵀ c_b` (springs `s_b` on the boundary coordinates).
fn with_springs(
    k: &SparseColMat<usize, f64>,
    rows: &[Vec<(usize, f64)>],
    s: &[f64],
) -> SparseColMat<usize, f64> {
    let kr = k.as_ref();
    let mut t = Vec::new();
    for j in 0..k.ncols() {
        for (i, &v) in kr.row_idx_of_col(j).zip(kr.val_of_col(j)) {
            t.push(Triplet::new(i, j, v));
        }
    }
    for (row, &sb) in rows.iter().zip(s) {
        for &(i, ci) in row {
            for &(j, cj) in row {
                t.push(Triplet::new(i, j, sb * ci * cj));
            }
        }
    }
    SparseColMat::try_new_from_triplets(k.nrows(), k.ncols(), &t).unwrap()
}

fn sparse(a: &Mat<f64>) -> SparseColMat<usize, f64> {
    let mut t = Vec::new();
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            if a[(i, j)] != 0.0 {
                t.push(Triplet::new(i, j, a[(i, j)]));
            }
        }
    }
    SparseColMat::try_new_from_triplets(a.nrows(), a.ncols(), &t).unwrap()
}

/// Springs of 1e7 N/m on the contact coordinates (about the bundled contact's 1.25e10 Pa/m
/// times a patch's 5.3e-4 m², 6.6e6 N/m), and `foot` on the footprints'.
fn springs(nb: usize, foot: f64) -> Vec<f64> {
    (0..nb).map(|b| if b < 27 { 1e7 } else { foot }).collect()
}

#[test]
fn footprint_pad_on_springs_is_a_ritz_projection_of_the_full_pad() {
    let mesh = pad();
    let part = reduce(&mesh, &spec(&mesh, footprints(), 30));
    let nb = 29;
    assert_eq!(part.size(), nb + 30);
    // The footprints are points of their own: centroid on the back face, area near pi r².
    for p in &part.info.points[9..] {
        assert_eq!(p.node_id, None);
        let area = p.area.unwrap();
        assert!((p.position[2] - 0.035).abs() < 1e-12, "{:?}", p.position);
        eprintln!(
            "footprint at {:?}, area {area:e} m² (pi r² = {:e})",
            p.position,
            std::f64::consts::PI * 4e-4
        );
    }
    // Rigid translation along z: every z coordinate and both footprints move by 1.
    let r: Vec<f64> = (0..part.size())
        .map(|i| {
            if i < nb && (i >= 27 || i % 3 == 2) {
                1.0
            } else {
                0.0
            }
        })
        .collect();
    let scale = (0..part.size())
        .map(|i| part.k[(i, i)].abs())
        .fold(0.0, f64::max);
    let worst = (0..part.size())
        .map(|i| {
            (0..part.size())
                .map(|j| part.k[(i, j)] * r[j])
                .sum::<f64>()
                .abs()
        })
        .fold(0.0, f64::max);
    eprintln!("|K̂ r_z| / max K̂_ii = {:e}", worst / scale);
    // Round-off of entries of size max K̂_ii summed over the footprints' few hundred dofs.
    assert!(worst / scale < 1e-9, "{}", worst / scale);

    let f = full(&mesh);
    let s = springs(nb, 1e7);
    let k_full = with_springs(&f.k, &f.rows, &s);
    let mut k_red = part.k.clone();
    for (b, sb) in s.iter().enumerate() {
        k_red[(b, b)] += sb;
    }
    let opts = EigOptions::default();
    let nev = 12;
    let full_modes = lowest_modes(k_full.as_ref(), f.m.as_ref(), nev, &opts).unwrap();
    let red_modes = lowest_modes(
        sparse(&k_red).as_ref(),
        sparse(&part.m).as_ref(),
        nev,
        &opts,
    )
    .unwrap();
    let hz = |w2: f64| w2.max(0.0).sqrt() / std::f64::consts::TAU;
    let (mut low, mut worst): (f64, f64) = (0.0, 0.0);
    for (a, b) in full_modes.values.iter().zip(&red_modes.values) {
        let (fa, fb) = (hz(*a), hz(*b));
        eprintln!(
            "full {fa:10.3} Hz  reduced {fb:10.3} Hz  ({:+.3e})",
            fb / fa - 1.0
        );
        // A Ritz projection: never below the full model's (to the solver's 1e-10 or so).
        assert!(fb >= fa * (1.0 - 1e-9), "{fb} < {fa}");
        worst = worst.max(fb / fa - 1.0);
        if fa < 8000.0 {
            low = low.max(fb / fa - 1.0);
        }
    }
    // 30 fixed-interface modes: measured +4.2e-4 to +1.35e-3 for the five modes below 8 kHz
    // (2.9 to 6.9 kHz), up to +2.7e-2 at 13.8 kHz (the usual convergence of Craig-Bampton
    // with the modes kept); asserted 2e-3 and 5e-2.
    assert!(low < 2e-3 && worst < 5e-2, "{low} {worst}");
}

#[test]
fn a_static_load_on_a_footprint_is_its_force_spread_over_the_footprint() {
    let mesh = pad();
    let part = reduce(&mesh, &spec(&mesh, footprints(), 10));
    let nb = 29;
    let f = full(&mesh);
    // Held by springs on the contact patches only; 1500 N pushing the first footprint
    // towards the disc (-z), none on the second.
    let s = springs(nb, 0.0);
    let force = -1500.0;
    let k_full = with_springs(&f.k, &f.rows, &s);
    let chol = SparseCholesky::factorize(k_full.as_ref()).unwrap();
    let mut u = Mat::<f64>::zeros(f.dofmap.num_free(), 1);
    // Consistent nodal loads of the footprint's uniform pressure: F w_k along z.
    for &(i, w) in &f.rows[27] {
        u[(i, 0)] += force * w;
    }
    let total: f64 = f.rows[27].iter().map(|e| e.1).sum();
    assert!((total - 1.0).abs() < 1e-12, "weights sum to {total}");
    chol.solve_in_place(u.as_mut()).unwrap();
    // Reduced: (K̂ + springs) q = F e_27.
    let n = part.size();
    let mut k_red = part.k.clone();
    for (b, sb) in s.iter().enumerate() {
        k_red[(b, b)] += sb;
    }
    let q = k_red
        .llt(faer::Side::Lower)
        .unwrap()
        .solve(Mat::from_fn(n, 1, |i, _| if i == 27 { force } else { 0.0 }));
    // The boundary coordinates: C u against q.
    let mut worst_r: f64 = 0.0;
    let r_scale = (0..nb).map(|b| q[(b, 0)].abs()).fold(0.0, f64::max);
    for (b, row) in f.rows.iter().enumerate() {
        let cu: f64 = row.iter().map(|&(i, w)| w * u[(i, 0)]).sum();
        worst_r = worst_r.max((cu - q[(b, 0)]).abs() / r_scale);
    }
    // The field: B q against u.
    let basis = &part.basis.as_ref().unwrap().values;
    let bq = basis * &q;
    let u_scale = (0..u.nrows()).map(|i| u[(i, 0)].abs()).fold(0.0, f64::max);
    let worst_u = (0..u.nrows())
        .map(|i| (bq[(i, 0)] - u[(i, 0)]).abs())
        .fold(0.0, f64::max)
        / u_scale;
    // The modal coordinates carry no static load (C φ = 0, K̂_CN = 0).
    let modal = (nb..n).map(|j| q[(j, 0)].abs()).fold(0.0, f64::max);
    eprintln!(
        "footprint z motion {:e} m; |C u - r| / max|r| = {worst_r:e}; |B q - u| / max|u| = {worst_u:e}; max |q_modal| = {modal:e}",
        q[(27, 0)]
    );
    // Exact in exact arithmetic (the constraint modes span the static response to loads and
    // springs in the range of Cᵀ): round-off of two factorizations of a K with entries up to
    // 1e11 N/m and condition ~1e8.
    assert!(worst_r < 1e-8 && worst_u < 1e-8, "{worst_r} {worst_u}");
}
