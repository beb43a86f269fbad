//! Tied interfaces and supports with stiffness ([`squeal_reduce::tie`], issue 21 items 3–4).
//!
//! - A steel block 40 x 20 x 20 mm, clamped at x = 0, as two halves tied at x = 20 mm
//!   against the same block meshed as one: on matching meshes the tie is the shared node,
//!   so the Craig–Bampton model is the one-mesh model to round-off; on non-matching meshes
//!   the tie may differ from the one-mesh block by no more than the meshes' own
//!   discretization error.
//! - A free steel cube on springs over its bottom face: its vertical rigid-body frequency is
//!   `sqrt(k / m) / 2π`.

use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::{Mat, Par, Side};
use squeal_element::ElementKind;
use squeal_fe::{ElasticMaterial, MaterialTable, Restraint};
use squeal_mesh::Mesh;
use squeal_mesh::generate::{box_solid, box_tet10_origin};
use squeal_reduce::craig_bampton::{PartSpec, ReduceOptions, reduce_part};
use squeal_reduce::rom::{MeshInfo, PartRole, ReducedPart};
use squeal_reduce::tie::{Support, Tie};

const STEEL: (f64, f64, f64) = (210e9, 0.3, 7850.0);

fn steel(mesh: &Mesh) -> MaterialTable {
    MaterialTable::uniform(mesh, ElasticMaterial::isotropic(STEEL.0, STEEL.1, STEEL.2)).unwrap()
}

/// Two meshes as one, each with its own nodes; `b`'s ids offset past `a`'s, the sets of
/// each prefixed `A_` and `B_`.
fn merged(a: &Mesh, b: &Mesh) -> Mesh {
    let mut m = a.clone();
    let (off_n, off_e) = (a.num_nodes() as u32, a.num_elements() as u32);
    let id_n = a.node_ids.iter().max().copied().unwrap_or(0);
    let id_e = a.element_ids.iter().max().copied().unwrap_or(0);
    m.nodes.extend(&b.nodes);
    m.node_ids.extend(b.node_ids.iter().map(|i| i + id_n));
    m.blocks
        .tet10
        .extend(b.blocks.tet10.iter().map(|c| c.map(|n| n + off_n)));
    m.blocks
        .hex20
        .extend(b.blocks.hex20.iter().map(|c| c.map(|n| n + off_n)));
    m.element_ids.extend(b.element_ids.iter().map(|i| i + id_e));
    m.node_sets = a
        .node_sets
        .iter()
        .map(|(k, v)| (format!("A_{k}"), v.clone()))
        .chain(
            b.node_sets
                .iter()
                .map(|(k, v)| (format!("B_{k}"), v.iter().map(|n| n + off_n).collect())),
        )
        .collect();
    m.element_sets.clear();
    m.element_sets
        .insert("ALL".into(), (0..off_e + b.num_elements() as u32).collect());
    m
}

/// Adds node set `name` holding the node at `x`.
fn add_node_set(mesh: &mut Mesh, name: &str, x: [f64; 3]) {
    let n = (0..mesh.num_nodes() as u32)
        .find(|&n| (0..3).all(|d| (mesh.nodes[n as usize][d] - x[d]).abs() < 1e-12))
        .expect("a node there");
    mesh.node_sets.insert(name.into(), vec![n]);
}

fn spec(clamp: &str, ties: Vec<Tie>, supports: Vec<Support>, modes: usize) -> PartSpec {
    PartSpec {
        restraints: match clamp {
            "" => Vec::new(),
            set => vec![Restraint::clamp(set)],
        },
        contact_set: "TIP".into(),
        contact_face_set: "TIP".into(),
        grid: [1, 1],
        ties,
        supports,
        ..PartSpec::new("block", PartRole::Pad, MeshInfo::in_memory("block"), modes)
    }
}

fn reduce(mesh: &Mesh, spec: &PartSpec) -> ReducedPart {
    reduce_part(
        mesh,
        &steel(mesh),
        spec,
        &ReduceOptions::default(),
        &mut |_| {},
    )
    .unwrap()
    .0
}

/// Frequencies (Hz) of the reduced model `K̂ x = ω² M̂ x`, ascending (dense: `M̂ = L Lᵀ`,
/// eigenvalues of `L⁻¹ K̂ L⁻ᵀ`).
fn frequencies(p: &ReducedPart) -> Vec<f64> {
    let l = p.m.llt(Side::Lower).unwrap().L().to_owned();
    let mut x = p.k.clone();
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

/// The block as one mesh with `cells` cells, clamped at x = 0, tip node at (40, 0, 0) mm.
fn one_block(cells: [usize; 3]) -> (Mesh, PartSpec) {
    let mut m = box_tet10_origin([0.0; 3], [0.04, 0.02, 0.02], cells);
    add_node_set(&mut m, "TIP", [0.04, 0.0, 0.0]);
    (m, spec("XMIN", vec![], vec![], 20))
}

/// The block as two halves of `a` and `b` cells, the second's x = 20 mm face (slave) tied
/// to the first's (master).
fn tied_block(a: [usize; 3], b: [usize; 3]) -> (Mesh, PartSpec) {
    let left = box_tet10_origin([0.0; 3], [0.02, 0.02, 0.02], a);
    let right = box_tet10_origin([0.02, 0.0, 0.0], [0.02, 0.02, 0.02], b);
    let mut m = merged(&left, &right);
    add_node_set(&mut m, "TIP", [0.04, 0.0, 0.0]);
    let tie = Tie {
        slave: "B_XMIN".into(),
        master: "A_XMAX".into(),
        tolerance: None,
    };
    (m, spec("A_XMIN", vec![tie], vec![], 20))
}

fn worst_relative(a: &[f64], b: &[f64], n: usize) -> f64 {
    a.iter()
        .zip(b)
        .take(n)
        .map(|(x, y)| (x / y - 1.0).abs())
        .fold(0.0, f64::max)
}

#[test]
fn a_block_tied_on_matching_meshes_is_the_block_meshed_as_one() {
    let (one, one_spec) = one_block([4, 2, 2]);
    let (tied, tied_spec) = tied_block([2, 2, 2], [2, 2, 2]);
    let (p, q) = (reduce(&one, &one_spec), reduce(&tied, &tied_spec));
    let (f1, f2) = (frequencies(&p), frequencies(&q));
    let fixed = worst_relative(&p.info.fixed_interface_hz, &q.info.fixed_interface_hz, 20);
    let reduced = worst_relative(&f1[..10], &f2[..10], 10);
    eprintln!(
        "matching tie: first frequencies {:.3} / {:.3} Hz; worst relative difference: fixed-interface {fixed:.2e}, reduced model {reduced:.2e}",
        f1[0], f2[0]
    );
    // The same stiffness and mass after eliminating the shared nodes: only the sums'
    // order differs (round-off, ~1e-15 on K; 1e-9 leaves the eigensolver's tolerance).
    assert_eq!(
        q.info.full_dofs,
        p.info.full_dofs + 3 * 25,
        "the slave's own dofs"
    );
    assert!(
        fixed < 1e-9,
        "fixed-interface frequencies differ by {fixed:.2e}"
    );
    assert!(
        reduced < 1e-9,
        "reduced-model frequencies differ by {reduced:.2e}"
    );
}

#[test]
fn a_block_tied_on_non_matching_meshes_is_within_the_meshes_own_error() {
    // The right half meshed finer (3 x 3 cells on the tie face against 2 x 2).
    let (tied, tied_spec) = tied_block([2, 2, 2], [2, 3, 3]);
    let tied = frequencies(&reduce(&tied, &tied_spec));
    let (coarse, s) = one_block([4, 2, 2]);
    let coarse = frequencies(&reduce(&coarse, &s));
    let (fine, s) = one_block([4, 3, 3]);
    let fine = frequencies(&reduce(&fine, &s));
    let mesh_error = worst_relative(&coarse, &fine, 6);
    let tie_error = worst_relative(&tied, &fine, 6);
    eprintln!(
        "non-matching tie: first frequencies tied {:.3}, one mesh 2x2 {:.3}, 3x3 {:.3} Hz; worst of the first six: tied vs one mesh 3x3 {tie_error:.2e}, one mesh 2x2 vs 3x3 {mesh_error:.2e}",
        tied[0], coarse[0], fine[0]
    );
    // The tie adds no error beyond the meshes' own: the tied block (half of it on the
    // coarser mesh) is nearer the finer one-mesh block than the coarser one-mesh block is.
    assert!(
        tie_error < mesh_error,
        "tied block off by {tie_error:.2e}, more than the meshes' own {mesh_error:.2e}"
    );
}

#[test]
fn a_cube_on_springs_moves_at_sqrt_k_over_m() {
    let a = 0.02;
    let mut m = box_tet10_origin([0.0; 3], [a, a, a], [2, 2, 2]);
    add_node_set(&mut m, "TIP", [a, a, a]);
    let mass = STEEL.2 * a * a * a;
    // 100 Hz vertically, far below the cube's first elastic mode (about 80 kHz).
    let f0 = 100.0;
    let k = mass * (2.0 * std::f64::consts::PI * f0).powi(2);
    let support = Support {
        set: "ZMIN".into(),
        stiffness: [k, k, k],
    };
    // Without the support the cube is free: refused before any reduction.
    let free = spec("", vec![], vec![], 20);
    // (The tip node's three dofs, kept as boundary dofs, hold its translations.)
    let e = squeal_reduce::held::require_held(&m, &free).unwrap_err();
    assert!(e.to_string().contains("3 rigid-body motion(s) free"), "{e}");
    let held = spec("", vec![], vec![support], 20);
    squeal_reduce::held::require_held(&m, &held).unwrap();
    let f = frequencies(&reduce(&m, &held));
    // The vertical translation: the mode nearest f0 (the lateral ones couple with rocking
    // on the springs below the centre of mass and lie elsewhere).
    let vertical = f
        .iter()
        .copied()
        .min_by(|x, y| (x - f0).abs().total_cmp(&(y - f0).abs()))
        .unwrap();
    let error = (vertical / f0 - 1.0).abs();
    eprintln!(
        "cube on springs: {vertical:.9} Hz against sqrt(k/m)/2pi = {f0} Hz ({error:.2e}); six lowest {:?}",
        &f[..6]
    );
    // The elastic cube's coupling moves it by about (f0 / f_elastic)² ≈ 2e-6.
    assert!(
        error < 1e-4,
        "vertical rigid-body frequency off by {error:.2e}"
    );
}

/// A rotation of the coordinate axes: 30 degrees about z, then 20 degrees about the new x
/// (rows: the three unit vectors).
fn tilted_axes() -> [[f64; 3]; 3] {
    let (a, b) = (30f64.to_radians(), 20f64.to_radians());
    let e1 = [a.cos(), a.sin(), 0.0];
    let e2 = [-a.sin() * b.cos(), a.cos() * b.cos(), b.sin()];
    let e3 = [a.sin() * b.sin(), -a.cos() * b.sin(), b.cos()];
    [e1, e2, e3]
}

/// Frequencies (Hz) of rigid cubes of side `side` and density `rho` centred at `centres` on the
/// rank-one spring terms `terms` (mesh node positions in `mesh`): `K = Σ k r rᵀ` with `r` the
/// term's row on each cube's `(t, θ)` about its centre, `M = diag(m, m, m, m s²/6, ...)`.
fn rigid_cubes_hz(
    mesh: &Mesh,
    terms: &[squeal_reduce::springs::SpringTerm],
    centres: &[[f64; 3]],
    side: f64,
    rho: f64,
) -> Vec<f64> {
    let n = 6 * centres.len();
    let body = |x: [f64; 3]| {
        (0..centres.len())
            .find(|&b| (0..3).all(|d| (x[d] - centres[b][d]).abs() <= 0.5 * side + 1e-12))
            .expect("a node of one cube")
    };
    let mut k = Mat::<f64>::zeros(n, n);
    for t in terms {
        let mut r = vec![0.0; n];
        for &(node, w) in &t.entries {
            let x = mesh.nodes[node as usize];
            let b = body(x);
            let c = centres[b];
            let arm = [x[0] - c[0], x[1] - c[1], x[2] - c[2]];
            let m = [
                arm[1] * w[2] - arm[2] * w[1],
                arm[2] * w[0] - arm[0] * w[2],
                arm[0] * w[1] - arm[1] * w[0],
            ];
            for d in 0..3 {
                r[6 * b + d] += w[d];
                r[6 * b + 3 + d] += m[d];
            }
        }
        for i in 0..n {
            for j in 0..n {
                k[(i, j)] += t.k * r[i] * r[j];
            }
        }
    }
    let mass = rho * side.powi(3);
    let diag: Vec<f64> = (0..n)
        .map(|i| {
            if i % 6 < 3 {
                mass
            } else {
                mass * side * side / 6.0
            }
        })
        .collect();
    let a = Mat::from_fn(n, n, |i, j| k[(i, j)] / (diag[i] * diag[j]).sqrt());
    a.self_adjoint_eigenvalues(Side::Lower)
        .unwrap()
        .into_iter()
        .map(|w2| w2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
        .collect()
}

#[test]
fn two_cubes_on_springs_in_tilted_axes_move_as_rigid_bodies() {
    use squeal_reduce::springs::{Spread, spring_terms};
    let a = 0.02;
    let cube_a = box_tet10_origin([0.0; 3], [a, a, a], [2, 2, 2]);
    let cube_b = box_tet10_origin([0.03, 0.0, 0.0], [a, a, a], [2, 2, 2]);
    let mut m = merged(&cube_a, &cube_b);
    add_node_set(&mut m, "TIP", [0.0, 0.0, a]);
    let mass = STEEL.2 * a * a * a;
    // Spring rates near 100 Hz for a cube, far below its first elastic mode (about 80 kHz).
    let k0 = mass * (2.0 * std::f64::consts::PI * 100.0).powi(2);
    let axes = Some(tilted_axes());
    let springs = vec![
        // Cube A on a foundation in tilted axes, cube B on one in x, y, z.
        squeal_reduce::springs::Spring {
            set: "A_ZMIN".into(),
            to: None,
            stiffness: [k0, 2.0 * k0, 3.0 * k0],
            axes,
            spread: Spread::Area,
        },
        squeal_reduce::springs::Spring {
            set: "B_ZMIN".into(),
            to: None,
            stiffness: [1.5 * k0, 0.7 * k0, 2.5 * k0],
            axes: None,
            spread: Spread::Area,
        },
        // The two joined between their facing sides' mean motions, in tilted axes.
        squeal_reduce::springs::Spring {
            set: "A_XMAX".into(),
            to: Some("B_XMIN".into()),
            stiffness: [4.0 * k0, 0.5 * k0, 1.2 * k0],
            axes,
            spread: Spread::Mean,
        },
    ];
    let spec = PartSpec {
        springs: springs.clone(),
        ..spec("", vec![], vec![], 30)
    };
    // Without the springs: two free bodies, refused (the six motions of the whole are free).
    let bare = spec.clone();
    let bare = PartSpec {
        springs: Vec::new(),
        ..bare
    };
    assert!(squeal_reduce::held::require_held(&m, &bare).is_err());
    squeal_reduce::held::require_held(&m, &spec).unwrap();
    let f = frequencies(&reduce(&m, &spec));
    let terms = spring_terms(&m, &springs).unwrap();
    let reference = rigid_cubes_hz(&m, &terms, &[[0.01; 3], [0.04, 0.01, 0.01]], a, STEEL.2);
    let worst = worst_relative(&f[..12], &reference, 12);
    eprintln!(
        "two cubes on springs: reduced {:.6?} Hz, rigid {:.6?} Hz; worst relative {worst:.2e}",
        &f[..12],
        reference
    );
    // The cubes' elasticity lowers each rigid frequency by about (f / f_elastic)² ≈
    // (300 / 80000)² ≈ 1.4e-5; the Craig–Bampton error (30 modes) is far below.
    assert!(
        reference[0] > 20.0 && reference[11] < 1000.0,
        "{reference:?}"
    );
    assert!(worst < 1e-4, "rigid-body frequencies off by {worst:.2e}");
    // The same springs in global axes give other frequencies (the frame must matter).
    let global: Vec<_> = springs
        .iter()
        .map(|s| squeal_reduce::springs::Spring {
            axes: None,
            ..s.clone()
        })
        .collect();
    let moved = rigid_cubes_hz(
        &m,
        &spring_terms(&m, &global).unwrap(),
        &[[0.01; 3], [0.04, 0.01, 0.01]],
        a,
        STEEL.2,
    );
    assert!(worst_relative(&moved, &reference, 12) > 1e-2);
}

#[test]
fn a_spring_between_two_sides_of_a_cube_holds_its_rocking_only() {
    use squeal_reduce::springs::{Spread, Spring};
    let a = 0.02;
    let mut m = box_tet10_origin([0.0; 3], [a, a, a], [2, 2, 2]);
    add_node_set(&mut m, "TIP", [a, a, a]);
    let k = 1e6;
    let between = Spring {
        set: "ZMIN".into(),
        to: Some("ZMAX".into()),
        stiffness: [k, k, k],
        axes: None,
        spread: Spread::Mean,
    };
    // The corner node (a, a, a), a boundary node, holds the translations there.
    let s = spec("", vec![], vec![], 10);
    let free = |springs: Vec<Spring>| {
        squeal_reduce::held::free_motions(
            &m,
            &PartSpec {
                springs,
                ..s.clone()
            },
        )
        .unwrap()
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
    };
    assert_eq!(free(Vec::new()).len(), 3);
    // The two faces' mean motions differ under a rocking about x or y only: the twist about
    // the vertical through the corner stays free (both faces' centres move alike).
    let left = free(vec![between.clone()]);
    eprintln!("spring between the faces leaves free: {left:?}");
    assert_eq!(left.len(), 1, "{left:?}");
    assert!(
        left[0].starts_with("rotation about z through (0.020000, 0.020000, 0.010000)"),
        "{left:?}"
    );
    // To ground on the bottom face's mean: free is the rotation about the line through the
    // corner and the bottom face's centre (0.01, 0.01, 0), direction (1, 1, 2) / sqrt 6.
    let ground = Spring {
        to: None,
        ..between.clone()
    };
    let left = free(vec![ground.clone()]);
    eprintln!("spring to ground leaves free: {left:?}");
    assert_eq!(left.len(), 1, "{left:?}");
    assert!(
        left[0].starts_with("rotation about (0.4082, 0.4082, 0.8165)"),
        "{left:?}"
    );
    // Both: held.
    assert!(free(vec![between, ground]).is_empty());
}

#[test]
fn springs_are_checked() {
    use squeal_reduce::springs::{Spread, Spring, spring_terms};
    let m = box_tet10_origin([0.0; 3], [0.02; 3], [1, 1, 1]);
    let spring = Spring {
        set: "ZMIN".into(),
        to: None,
        stiffness: [1.0, 0.0, 0.0],
        axes: None,
        spread: Spread::Area,
    };
    let bad = |s: Spring| spring_terms(&m, &[s]).unwrap_err().to_string();
    let e = bad(Spring {
        stiffness: [0.0; 3],
        ..spring.clone()
    });
    assert!(e.contains("not all zero"), "{e}");
    let e = bad(Spring {
        axes: Some([[1.0, 0.0, 0.0], [0.6, 0.8, 0.0], [0.0, 0.0, 1.0]]),
        ..spring.clone()
    });
    assert!(e.contains("orthonormal"), "{e}");
    let e = bad(Spring {
        to: Some("ZMAX".into()),
        ..spring.clone()
    });
    assert!(e.contains("mean spread"), "{e}");
    // Area shares sum to the total: a 1 N/m foundation's terms sum to 1.
    let total: f64 = spring_terms(&m, &[spring])
        .unwrap()
        .iter()
        .map(|t| t.k)
        .sum();
    assert!((total - 1.0).abs() < 1e-14, "{total}");
}

/// A 20 mm steel cube (the pad) bearing with its x = 20 mm face on a clamped steel block (the
/// bracket) through a sliding abutment of normal stiffness `k_n`, and held on a foundation
/// along y and z under its bottom face: it moves along x at `sqrt(k_n / m)`, and along z at
/// `sqrt(k_z / m)` whatever `k_n` (the abutment does not hold it across its normal).
#[test]
fn a_cube_slides_on_its_abutment_and_bears_along_the_normal_only() {
    use squeal_reduce::springs::{Spread, Spring};
    let a = 0.02;
    let pad = box_tet10_origin([0.0; 3], [a, a, a], [2, 2, 2]);
    // The bracket meshed otherwise (3 x 3 cells on the face borne on against 2 x 2).
    let bracket = box_tet10_origin([a, 0.0, 0.0], [a, a, a], [1, 3, 3]);
    let mut m = merged(&pad, &bracket);
    add_node_set(&mut m, "TIP", [0.0, 0.0, a]);
    let mass = STEEL.2 * a * a * a;
    let k_of = |hz: f64| mass * (2.0 * std::f64::consts::PI * hz).powi(2);
    let (fx, fy, fz) = (100.0, 60.0, 150.0);
    let abutment = Spring {
        set: "A_XMAX".into(),
        to: Some("B_XMIN".into()),
        stiffness: [k_of(fx), 0.0, 0.0],
        axes: None,
        spread: Spread::Normal,
    };
    let foundation = Spring {
        set: "A_ZMIN".into(),
        to: None,
        stiffness: [0.0, k_of(fy), k_of(fz)],
        axes: None,
        spread: Spread::Area,
    };
    let spec_with = |springs: Vec<Spring>| PartSpec {
        springs,
        ..spec("B_XMAX", vec![], vec![], 30)
    };
    let nearest = |f: &[f64], f0: f64| {
        f.iter()
            .copied()
            .min_by(|x, y| (x - f0).abs().total_cmp(&(y - f0).abs()))
            .unwrap()
    };
    let f = frequencies(&reduce(
        &m,
        &spec_with(vec![abutment.clone(), foundation.clone()]),
    ));
    let (along, across) = (nearest(&f, fx), nearest(&f, fz));
    eprintln!(
        "sliding abutment: along the normal {along:.6} Hz (sqrt(k_n/m): {fx}), vertical {across:.6} Hz (sqrt(k_z/m): {fz}); lowest {:?}",
        &f[..6]
    );
    // Elastic coupling of the cube and the bracket: (f / f_elastic)² ≈ (150 / 80000)² ≈ 4e-6.
    for (got, want) in [(along, fx), (across, fz)] {
        assert!(
            (got / want - 1.0).abs() < 1e-4,
            "{got} Hz against {want} Hz"
        );
    }
    // Stuck instead (the same stiffness along all three axes between the faces' means): the
    // vertical mode is stiffened away from sqrt(k_z / m).
    let stuck = Spring {
        stiffness: [k_of(fx); 3],
        spread: Spread::Mean,
        ..abutment
    };
    let f = frequencies(&reduce(&m, &spec_with(vec![stuck, foundation])));
    assert!(
        f.iter().all(|x| (x / fz - 1.0).abs() > 1e-2),
        "a stuck abutment must move the vertical mode: {:?}",
        &f[..8]
    );
}

/// A hex20 box of `lengths` and `cells` moved by `origin`.
fn hex_box(origin: [f64; 3], lengths: [f64; 3], cells: [usize; 3]) -> Mesh {
    let mut m = box_solid(ElementKind::Hex20, lengths, cells);
    for x in &mut m.nodes {
        *x = std::array::from_fn(|d| x[d] + origin[d]);
    }
    m
}

/// The block of hex20 elements as one mesh and as two halves tied on their 8-node faces (the
/// right half's x = 20 mm face, slave, to the left half's, master).
fn hex_blocks(a: [usize; 3], b: [usize; 3], one: [usize; 3]) -> [(Mesh, PartSpec); 2] {
    let mut whole = hex_box([0.0; 3], [0.04, 0.02, 0.02], one);
    add_node_set(&mut whole, "TIP", [0.04, 0.0, 0.0]);
    let left = hex_box([0.0; 3], [0.02, 0.02, 0.02], a);
    let right = hex_box([0.02, 0.0, 0.0], [0.02, 0.02, 0.02], b);
    let mut tied = merged(&left, &right);
    add_node_set(&mut tied, "TIP", [0.04, 0.0, 0.0]);
    let tie = Tie {
        slave: "B_XMIN".into(),
        master: "A_XMAX".into(),
        tolerance: None,
    };
    [
        (whole, spec("XMIN", vec![], vec![], 20)),
        (tied, spec("A_XMIN", vec![tie], vec![], 20)),
    ]
}

#[test]
fn a_hex20_block_tied_on_quad8_faces_is_the_block_meshed_as_one() {
    // Matching meshes: every slave node of the 8-node faces projects onto a master node
    // (weight 1, the others below 1e-12 dropped), so the tie is the shared node and the
    // reduced models agree to round-off, as for tet10 (1e-9: the eigensolver's tolerance).
    let [(one, s1), (tied, s2)] = hex_blocks([2, 2, 2], [2, 2, 2], [4, 2, 2]);
    let (p, q) = (reduce(&one, &s1), reduce(&tied, &s2));
    let (f1, f2) = (frequencies(&p), frequencies(&q));
    let fixed = worst_relative(&p.info.fixed_interface_hz, &q.info.fixed_interface_hz, 20);
    let reduced = worst_relative(&f1[..10], &f2[..10], 10);
    eprintln!(
        "hex20 matching tie: first frequencies {:.3} / {:.3} Hz; worst relative difference: fixed-interface {fixed:.2e}, reduced model {reduced:.2e}",
        f1[0], f2[0]
    );
    // The slave face's 21 nodes (2 x 2 quad8: 9 corners, 12 midsides) are extra dofs.
    assert_eq!(q.info.full_dofs, p.info.full_dofs + 3 * 21);
    assert!(
        fixed < 1e-9,
        "fixed-interface frequencies differ by {fixed:.2e}"
    );
    assert!(
        reduced < 1e-9,
        "reduced-model frequencies differ by {reduced:.2e}"
    );
}

#[test]
fn a_hex20_block_tied_on_non_matching_quad8_faces_is_within_the_meshes_own_error() {
    // The right half finer (3 x 3 quadrilaterals on the tie face against 2 x 2): the slave
    // nodes fall inside the master's 8-node faces. The tied block must be nearer the finer
    // one-mesh block than the coarser one-mesh block is (the tie adds no error beyond the
    // meshes' own).
    let [_, (tied, s)] = hex_blocks([2, 2, 2], [2, 3, 3], [4, 2, 2]);
    let tied = frequencies(&reduce(&tied, &s));
    let [(coarse, s), _] = hex_blocks([2, 2, 2], [2, 2, 2], [4, 2, 2]);
    let coarse = frequencies(&reduce(&coarse, &s));
    let [(fine, s), _] = hex_blocks([2, 3, 3], [2, 3, 3], [4, 3, 3]);
    let fine = frequencies(&reduce(&fine, &s));
    let mesh_error = worst_relative(&coarse, &fine, 6);
    let tie_error = worst_relative(&tied, &fine, 6);
    eprintln!(
        "hex20 non-matching tie: first frequencies tied {:.3}, one mesh 2x2 {:.3}, 3x3 {:.3} Hz; worst of the first six: tied vs 3x3 {tie_error:.2e}, 2x2 vs 3x3 {mesh_error:.2e}",
        tied[0], coarse[0], fine[0]
    );
    assert!(
        tie_error < mesh_error,
        "tied block off by {tie_error:.2e}, more than the meshes' own {mesh_error:.2e}"
    );
}
