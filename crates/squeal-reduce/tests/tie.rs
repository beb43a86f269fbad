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
use squeal_reduce::interface::Axis;
use squeal_reduce::rom::{InterfaceKind, MeshInfo, ReducedPart};
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
        name: "block".into(),
        role: squeal_reduce::rom::PartRole::Pad,
        mesh: MeshInfo {
            path: "block".into(),
            sha256: String::new(),
            nodes: 0,
            elements: 0,
        },
        restraints: match clamp {
            "" => Vec::new(),
            set => vec![Restraint::clamp(set)],
        },
        skew_restraints: Vec::new(),
        axis_restraints: Vec::new(),
        interface: InterfaceKind::Node,
        contact_set: "TIP".into(),
        contact_face_set: "TIP".into(),
        facing: None,
        extra_surfaces: Vec::new(),
        grid: [1, 1],
        axis: Axis::default(),
        piston_set: None,
        piston_footprints: Vec::new(),
        normal_direction: 2,
        piston_direction: None,
        modes,
        ties,
        supports,
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
