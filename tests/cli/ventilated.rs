//! End to end on the bundled ventilated two-pad brake (`meshes/ventilated/brake.toml`, coarse
//! meshes): a vaned hat disc and two pads meshed separately (non-matching meshes at both
//! contacts), paired by nodal contact. The scene runs as bundled but on a short friction range
//! (`--mu 0..0.2/3`, below its Hopf point): its whole stability run (μ0 = 0.33739633 at
//! 3735.96 Hz, 0.33739598 before the interface basis kept its static vectors exactly; since the contact points are the pads' midside nodes with the consistent loads of
//! a uniform pressure, 0.29976078 at 3683.61 Hz before; docs/reduction.md, "The ventilated brake") takes about 4 minutes on this
//! project's shared 2-core machine, too long for a test; what is asserted is what nodal
//! contact must do with separately meshed parts, and the frictionless pair that coalesces.

use super::common;

use common::{root, temp_dir};

/// Contact points of each coarse pad: the midside nodes of its friction face (`CONTACT_FACE`,
/// 52 nodes in both, meshes/README.md, of which 17 are corners of its 6-node triangles and
/// carry no share of the pressure: crates/squeal-reduce/src/interface/nodal.rs).
const FACE_NODES: usize = 35;

#[test]
fn the_ventilated_brake_pairs_every_pad_face_node_and_keeps_its_frictionless_pair() {
    let dir = temp_dir("ventilated", "coarse");
    let scene = root().join("meshes/ventilated/brake.toml");
    let out_dir = dir.join("out");
    let args = [
        "stability",
        scene.to_str().unwrap(),
        "--mu",
        "0..0.2/3",
        "--out",
        out_dir.to_str().unwrap(),
        "--no-vtu",
    ];
    let stdout = common::run_ok(&args);

    // Every pad face node is a pair, paired with the disc face under its pad by projection: the
    // faces were written on the same planes (z = 0, 0.023 m), so the projection distance and
    // the gap are round-off of 0.1 m coordinates (measured at most 5.9e-17 m), asserted below
    // 1e-12 m; a pad node missing the disc face would be 1e-3 m or more away.
    let csv = std::fs::read_to_string(out_dir.join("stability/equilibrium.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    for pad in ["inboard", "outboard"] {
        let n = rows.iter().filter(|r| r.last() == Some(&pad)).count();
        assert_eq!(n, FACE_NODES, "{pad} pairs");
    }
    for r in &rows {
        let gap: f64 = r[3].parse().unwrap();
        assert!(gap.abs() < 1e-12, "pair {}: geometric gap {gap} m", r[0]);
    }
    // Beyond 40 pairs `squeal stability` prints one line per pad: its pair count and largest
    // projection distance.
    let per_pad: Vec<(usize, f64)> = stdout
        .lines()
        .skip_while(|l| !l.starts_with("contact pairs"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            let count = f.get(1)?.parse().ok()?;
            let at = f.iter().position(|w| *w == "<=")?;
            Some((count, f.get(at + 1)?.parse().ok()?))
        })
        .collect();
    assert_eq!(per_pad.len(), 2, "pad lines in\n{stdout}");
    for (count, distance) in &per_pad {
        assert_eq!(*count, FACE_NODES, "pairs of a pad in\n{stdout}");
        assert!(
            *distance < 1e-12,
            "largest projection distance {distance} m"
        );
    }
    // Both pads carry the clamp force (printed to 1 mN; the equilibrium balances it to 1e-13)
    // and every pair is closed at the frictionless equilibrium.
    let line = stdout
        .lines()
        .find(|l| l.trim_start().starts_with("pad resultants"))
        .unwrap_or_else(|| panic!("no pad resultants in\n{stdout}"));
    assert!(
        line.contains("inboard 3000.522 N, outboard 3000.522 N"),
        "{line}"
    );
    assert!(
        stdout.contains(&format!("{0} of {0} pairs closed", 2 * FACE_NODES)),
        "{stdout}"
    );

    // At mu = 0 the brake has the two pad modes that coalesce at the Hopf point of the whole
    // run (branches 14 and 15 there, 3663.77 and 3764.26 Hz with the scene's damping; 3623.43
    // and 3709.93 Hz with the lumped sub-cell areas before 2026-11-28).
    // Every step is deterministic, but the projected sweep's basis is chosen by checks at the
    // sweep's own friction values, each to 1e-5 of |lambda|: 1e-4 allows another basis.
    let branches = std::fs::read_to_string(out_dir.join("stability/branches.csv")).unwrap();
    let at_zero: Vec<f64> = branches
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|r| r[0] == "0")
        .map(|r| r[3].parse().unwrap())
        .collect();
    for want in PAIR_HZ {
        let near = at_zero
            .iter()
            .copied()
            .min_by(|a, b| (a - want).abs().total_cmp(&(b - want).abs()))
            .unwrap();
        assert!(
            (near - want).abs() < 1e-4 * want,
            "{want} Hz: nearest {near} Hz"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The coalescing pair's frequencies at mu = 0 (Hz), from the whole run's `stability.csv`.
const PAIR_HZ: [f64; 2] = [3663.770812142519, 3764.2607615404945];
