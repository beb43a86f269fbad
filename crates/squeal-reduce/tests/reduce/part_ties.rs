//! Ties between separately reduced parts (issue 21, item 3; `squeal_reduce::part_tie`): a
//! 20 × 20 × 40 mm steel block cut in two 20 mm cubes, each reduced by Craig–Bampton on its
//! own with its tied face kept node by node, the upper cube's bottom (slave) tied to the lower
//! one's top (master) by the congruence on the assembled reduced model, against the same block
//! meshed as one part (unreduced, dense). Then the upper cube meshed finer (a non-matching
//! tie) against the matching one, on two mesh levels.

use super::common::blocks;

use blocks::{block_diag, frequencies, spec, steel};
use squeal_fe::{DofMap, Restraint, assemble};
use squeal_mesh::Mesh;
use squeal_mesh::generate::box_tet10_origin;
use squeal_reduce::ReduceError;
use squeal_reduce::coupling::CouplingSet;
use squeal_reduce::craig_bampton::{ReduceOptions, reduce_part_coupled};
use squeal_reduce::part_tie::{
    PartTieError, PartTieInput, TieTransform, check_ties, project_tie, resolve_tie,
};
use squeal_reduce::rom::{DofLabel, ReducedPart};

const L: f64 = 0.02;

/// The block meshed as one part, clamped on z = 0: its frequencies, unreduced.
fn one_block(cells: [usize; 3]) -> Vec<f64> {
    let mesh = box_tet10_origin([0.0; 3], [L, L, 2.0 * L], cells);
    let dofmap = DofMap::new(&mesh, &[Restraint::clamp("ZMIN")]).unwrap();
    let system = assemble(&mesh, &steel(&mesh), &dofmap).unwrap();
    frequencies(&system.k.to_dense(), &system.m.to_dense())
}

/// Free dofs of `mesh` under `restraints` less its `set`'s (the interior the reduction keeps
/// modes of), less one: every fixed-interface mode but the highest (the reduction asks for
/// fewer modes than interior dofs).
fn interior(mesh: &Mesh, restraints: &[Restraint], set: &str) -> usize {
    let dofmap = DofMap::new(mesh, restraints).unwrap();
    dofmap.num_free() - 3 * mesh.node_set(set).unwrap().len() - 1
}

/// Reduces `mesh` keeping `set` node by node.
fn reduce(
    mesh: &Mesh,
    name: &str,
    restraints: Vec<Restraint>,
    set: &str,
    modes: Option<usize>,
) -> Result<ReducedPart, ReduceError> {
    let modes = modes.unwrap_or_else(|| interior(mesh, &restraints, set));
    let couplings = [CouplingSet {
        set: set.into(),
        load: false,
        nodal: true,
    }];
    Ok(reduce_part_coupled(
        mesh,
        &steel(mesh),
        &spec(name, restraints, modes),
        &couplings,
        &ReduceOptions::default(),
        &mut |_| {},
    )?
    .0)
}

/// The lower cube `a` (clamped on z = 0, cells `ca`) and the upper one `b` (cells `cb`), tied
/// b's bottom to a's top, each reduced with `modes` fixed-interface modes (`None`: all):
/// the tied reduced model's frequencies and its size.
fn tied(ca: [usize; 3], cb: [usize; 3], modes: Option<usize>) -> (Vec<f64>, usize) {
    let a = box_tet10_origin([0.0; 3], [L; 3], ca);
    let b = box_tet10_origin([0.0, 0.0, L], [L; 3], cb);
    let pa = reduce(&a, "a", vec![Restraint::clamp("ZMIN")], "ZMAX", modes).unwrap();
    let pb = reduce(&b, "b", Vec::new(), "ZMIN", modes).unwrap();
    let tie = PartTieInput {
        slave: ("b".into(), "ZMIN".into()),
        master: ("a".into(), "ZMAX".into()),
        tolerance: None,
    };
    let projected = project_tie(&tie, &b, &a).unwrap();
    let resolved = resolve_tie(&tie, &projected, &pb, &pa).unwrap();
    let parts = [("a", 0, &pa), ("b", pa.size(), &pb)];
    let offset = |name: &str| parts.iter().find(|p| p.0 == name).map(|p| p.1);
    let dof = |name: &str, point: usize, d: usize| {
        let p = parts.iter().find(|p| p.0 == name)?.2;
        p.info.dofs.iter().position(|l| {
            matches!(*l, DofLabel::Point { point: q, direction }
                if q == point && usize::from(direction) == d)
        })
    };
    let n = pa.size() + pb.size();
    let t = TieTransform::new(n, &[resolved], &offset, &dof).unwrap();
    let k = t.congruence(&block_diag(&pa.k, &pb.k));
    let m = t.congruence(&block_diag(&pa.m, &pb.m));
    (frequencies(&k, &m), t.size())
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b) / b
}

/// With every fixed-interface mode kept but the highest of each part (the reduction asks for
/// fewer modes than interior dofs), each part's basis spans its whole space but one direction,
/// so the tied reduced model is the one mesh's model in other coordinates less two dofs
/// (matching meshes: each slave node lands on a master node, weight 1): the lowest 20
/// frequencies agree within 5e-8 relative (measured: 1e-14 … 1e-13, round-off, on the modes
/// the two dropped modes do not touch; at most 1.7e-8 on those they do). With 10 modes per
/// part the frequencies are Rayleigh–Ritz bounds of the one mesh's: at or above them (less
/// 1e-9 for round-off), the first six within 3e-3 (the truncation error measured:
/// 6.7e-5 … 2.2e-3, docs/verification.md).
#[test]
fn two_cubes_tied_are_the_block() {
    let reference = one_block([2, 2, 4]);
    let (all, size) = tied([2, 2, 2], [2, 2, 2], None);
    let mesh = box_tet10_origin([0.0; 3], [L, L, 2.0 * L], [2, 2, 4]);
    let free = DofMap::new(&mesh, &[Restraint::clamp("ZMIN")])
        .unwrap()
        .num_free();
    assert_eq!(
        size + 2,
        free,
        "the tied model keeps the one mesh's dofs but two modes"
    );
    for (i, (f, r)) in all.iter().zip(&reference).take(20).enumerate() {
        let e = relative(*f, *r);
        println!(
            "all modes: mode {}: {f:.6} Hz against {r:.6} Hz ({e:.2e})",
            i + 1
        );
        assert!(e.abs() < 5e-8, "mode {}: {f} against {r}", i + 1);
    }
    let (few, _) = tied([2, 2, 2], [2, 2, 2], Some(10));
    for (i, (f, r)) in few.iter().zip(&reference).take(6).enumerate() {
        let e = relative(*f, *r);
        println!(
            "10 modes: mode {}: {f:.6} Hz against {r:.6} Hz ({e:.2e})",
            i + 1
        );
        assert!(e > -1e-9 && e < 3e-3, "mode {}: {f} against {r}", i + 1);
    }
}

/// The upper cube meshed 1.5 times finer in-plane (slave nodes between the master's: a
/// non-matching tie) against the matching tie, on two levels (cells 2 and 4 per 20 mm
/// in-plane, the slave 3 and 6): the lowest six frequencies' largest relative difference falls
/// with the mesh as the discretization error of quadratic elements does, `h²` (a factor 4 per
/// halving; measured 2.69e-3 then 6.46e-4, a factor 4.2): asserted below 5e-3 on level 1 and
/// below 0.35 of it on level 2 (room for a factor 2.9). 40 modes per part, the same on both
/// models, so the Craig–Bampton error largely cancels in the difference.
#[test]
fn non_matching_tie_converges_to_the_matching_one() {
    let mut gaps = Vec::new();
    for k in [1, 2] {
        let (matching, _) = tied([2 * k, 2 * k, 2 * k], [2 * k, 2 * k, 2 * k], Some(40));
        let (finer, _) = tied([2 * k, 2 * k, 2 * k], [3 * k, 3 * k, 2 * k], Some(40));
        let gap = matching
            .iter()
            .zip(&finer)
            .take(6)
            .map(|(a, b)| relative(*b, *a).abs())
            .fold(0.0, f64::max);
        println!("level {k}: matching {:?}", &matching[..6]);
        println!("level {k}: finer    {:?}", &finer[..6]);
        println!("level {k}: largest relative difference {gap:.3e}");
        gaps.push(gap);
    }
    assert!(gaps[0] < 5e-3, "level 1: {}", gaps[0]);
    assert!(gaps[1] < 0.35 * gaps[0], "{gaps:?}");
}

/// A slave node off the master surface is refused with its distance and what to check; a
/// slave tied twice and a slave that is also a master are refused by name; a restrained slave
/// node is refused by the reduction that would keep it.
#[test]
fn bad_ties_are_refused() {
    let a = box_tet10_origin([0.0; 3], [L; 3], [2, 2, 2]);
    // 1 mm above a's top: 5 % of the cube, beyond the default 1 % of the master's extent.
    let b = box_tet10_origin([0.0, 0.0, L + 1e-3], [L; 3], [2, 2, 2]);
    let tie = PartTieInput {
        slave: ("b".into(), "ZMIN".into()),
        master: ("a".into(), "ZMAX".into()),
        tolerance: None,
    };
    let e = project_tie(&tie, &b, &a).unwrap_err();
    let text = e.to_string();
    assert!(
        matches!(
            &e,
            ReduceError::PartTie(b) if matches!(**b, PartTieError::OffSurface { distance, .. }
                if (distance - 1e-3).abs() < 1e-12)
        ),
        "{text}"
    );
    assert!(
        text.contains("1.000e-3 m from the master surface"),
        "{text}"
    );
    assert!(
        text.contains("check that the two sets face each other"),
        "{text}"
    );
    assert!(!text.contains('{') && !text.contains("Some("), "{text}");
    // With a tolerance above the gap, it ties.
    let loose = PartTieInput {
        tolerance: Some(2e-3),
        ..tie.clone()
    };
    assert_eq!(project_tie(&loose, &b, &a).unwrap().len(), 25);

    let sets = |part: &str, set: &str| -> Vec<u64> {
        let mesh = if part == "a" { &a } else { &b };
        mesh.node_set(set)
            .unwrap()
            .iter()
            .map(|&n| mesh.node_ids[n as usize])
            .collect()
    };
    let twice = [tie.clone(), tie.clone()];
    let e = check_ties(&twice, &["a", "b"], &["a", "b"], &sets).unwrap_err();
    assert!(
        matches!(&e, ReduceError::PartTie(b) if matches!(**b, PartTieError::TiedTwice { .. })),
        "{e}"
    );
    assert!(e.to_string().contains("is a slave of two ties"), "{e}");
    let chained = [
        tie.clone(),
        PartTieInput {
            slave: ("a".into(), "ZMAX".into()),
            master: ("b".into(), "ZMAX".into()),
            tolerance: None,
        },
    ];
    let e = check_ties(&chained, &["a", "b"], &["a", "b"], &sets).unwrap_err();
    assert!(
        matches!(&e, ReduceError::PartTie(b) if matches!(**b, PartTieError::Chained { .. })),
        "{e}"
    );
    let e = check_ties(std::slice::from_ref(&tie), &["a", "b"], &["a"], &sets).unwrap_err();
    assert!(
        matches!(&e, ReduceError::PartTie(b) if matches!(**b, PartTieError::SlaveNotBody { .. })),
        "{e}"
    );
    assert!(e.to_string().contains("further part"), "{e}");

    // A slave set clamped: its kept dofs would be held.
    let e = reduce(&b, "b", vec![Restraint::clamp("ZMIN")], "ZMIN", Some(5)).unwrap_err();
    assert!(matches!(e, ReduceError::BoundaryRestrained { .. }), "{e}");
    assert!(!e.to_string().contains("Some("), "{e}");
}
