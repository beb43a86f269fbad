//! Tests of the Gmsh `.msh` reader.
//!
//! Expected counts come from Gmsh itself: `python3 tools/msh-fixtures/count.py FILE...` opens each
//! file with the Gmsh 4.15.2 Python API and counts nodes, elements by type, and per physical
//! group its tet10 (dimension 3) or the distinct nodes of its elements (dimensions 0-2).

use squeal_mesh::msh::{parse, read};
use squeal_mesh::tet10::{EDGES, volume};
use squeal_mesh::{Location, Mesh, MeshError, ReadMesh};
use std::path::{Path, PathBuf};

fn data(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(path)
}

fn read_ok(path: &str) -> ReadMesh {
    match read(&data(path)) {
        Ok(m) => m,
        Err(e) => panic!("{e}"),
    }
}

fn coordinate_sum(mesh: &Mesh) -> f64 {
    mesh.nodes.iter().flatten().sum()
}

fn total_volume(mesh: &Mesh) -> f64 {
    (0..mesh.num_elements())
        .map(|e| volume(&mesh.element_coords(e)))
        .sum()
}

/// Largest distance of a midside node from the midpoint of its edge, over all elements.
fn worst_midside_offset(mesh: &Mesh) -> f64 {
    let mut worst: f64 = 0.0;
    for e in 0..mesh.num_elements() {
        let x = mesh.element_coords(e);
        for (k, [a, b]) in EDGES.iter().enumerate() {
            let m = x[4 + k];
            let d: f64 = (0..3)
                .map(|i| (m[i] - 0.5 * (x[*a][i] + x[*b][i])).powi(2))
                .sum::<f64>()
                .sqrt();
            worst = worst.max(d);
        }
    }
    worst
}

fn diagonal(mesh: &Mesh) -> f64 {
    let (lo, hi) = mesh.bounding_box().unwrap();
    (0..3).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt()
}

/// The files of other projects (see tests/data/outside/README.md): counts from Gmsh
/// (tools/msh-fixtures/count.py), volumes from the geometry.
#[test]
fn outside_files_match_gmsh_counts_and_volumes() {
    // (file, nodes, tet10, Gmsh's sum of all coordinates, exact volume of the geometry)
    let cases = [
        ("outside/fenris-cube_tet10_24.msh", 63, 24, 94.5, 1.0),
        (
            "outside/amfe-gmsh_ascii_v2_tet10.msh",
            113,
            48,
            226.416666666667,
            2.0,
        ),
        (
            "outside/amfe-bar_Tet10_fine.msh",
            34545,
            22432,
            52081.5357480875,
            2.0 * 0.5 * 0.5,
        ),
    ];
    for (file, nodes, tets, sum, exact_volume) in cases {
        let r = read_ok(file);
        let m = &r.mesh;
        assert_eq!(m.num_nodes(), nodes, "{file}");
        assert_eq!(m.num_elements(), tets, "{file}");
        // count.py prints 15 significant digits and sums in another order: 1e-12 relative.
        assert!(
            (coordinate_sum(m) - sum).abs() <= 1e-12 * sum.abs(),
            "{file}: {}",
            coordinate_sum(m)
        );
        // Straight-sided tet10 fill the box exactly; the sum of 22,432 volumes loses ~1e-12.
        assert!(
            (total_volume(m) - exact_volume).abs() < 1e-10,
            "{file}: {}",
            total_volume(m)
        );
        // None of these files has physical groups (all entities have no physical tags, and the
        // MSH 2.2 files give physical tag 0 to every element).
        assert!(
            m.node_sets.is_empty() && m.element_sets.is_empty(),
            "{file}"
        );
        assert!(m.dangling.is_empty(), "{file}");
        assert!(r.warnings.is_empty(), "{file}: {:?}", r.warnings);
    }
}

/// Curved (isoparametric) tet10 of a sphere of radius 0.5: the volume is near 4/3 pi r^3 only if
/// the curved midside nodes are where the canonical ordering says.
#[test]
fn curved_sphere_volume() {
    let r = read_ok("outside/scikit-fem-quadratic_sphere_tet.msh");
    let m = &r.mesh;
    assert_eq!(m.num_nodes(), 1310);
    assert_eq!(m.num_elements(), 722);
    let sum = -8.89215242557163;
    assert!(
        (coordinate_sum(m) - sum).abs() < 1e-12,
        "{}",
        coordinate_sum(m)
    );
    let exact = 4.0 / 3.0 * std::f64::consts::PI * 0.5f64.powi(3);
    // Quadratic boundary faces of a 722-element sphere approximate it to a few 1e-4 relative
    // (measured 1.5e-4); 1e-3 still catches a swap of midside nodes 8 and 9, which changes
    // the volume by far more (checked below).
    let v = total_volume(m);
    assert!(
        (v - exact).abs() < 1e-3 * exact,
        "volume {v}, sphere {exact}"
    );
    let mut swapped = m.clone();
    for el in &mut swapped.blocks.tet10 {
        el.swap(8, 9);
    }
    let vs = total_volume(&swapped);
    assert!(
        (vs - exact).abs() > 1e-2 * exact,
        "swapped ordering gives {vs}: the check above cannot fail"
    );
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
}

/// The box in MSH 4.1 (the first file is the reference of the comparisons).
const BOX_V41: [&str; 5] = [
    "msh/box_v41_ascii.msh",
    "msh/box_v41_binary.msh",
    "msh/box_v41_binary_be.msh",
    "msh/box_v41_parametric_ascii.msh",
    "msh/box_v41_parametric_binary.msh",
];

/// The box in MSH 2.2.
const BOX_V22: [&str; 3] = [
    "msh/box_v22_ascii.msh",
    "msh/box_v22_binary.msh",
    "msh/box_v22_binary_be.msh",
];

fn box_files() -> impl Iterator<Item = &'static str> {
    BOX_V41.into_iter().chain(BOX_V22)
}

/// The box written by Gmsh in every format (tools/msh-fixtures/make_box.py, big-endian copies by
/// swap_endian.py; with and without parametric coordinates) reads into the same mesh, with
/// Gmsh's counts.
#[test]
fn box_formats_read_into_the_same_mesh() {
    let reference = read_ok(BOX_V41[0]).mesh;
    assert_eq!(reference.num_nodes(), 694);
    assert_eq!(reference.num_elements(), 310);
    // Set sizes counted by Gmsh (count.py): element sets are tet10, node sets distinct nodes of
    // the group's elements. The top face's own node block in MSH 4.1 (`2 6 0 131`) holds only
    // its 131 interior nodes: 175 includes the 44 on its boundary curves.
    let element_sets = [("pad", 310), ("pad_again", 310)];
    let node_sets = [("PHYSICAL_1_7", 44), ("corner", 1), ("friction_face", 175)];
    assert_eq!(reference.element_sets.len(), element_sets.len());
    assert_eq!(reference.node_sets.len(), node_sets.len());
    for (name, n) in element_sets {
        assert_eq!(reference.element_sets[name].len(), n, "{name}");
    }
    for (name, n) in node_sets {
        assert_eq!(reference.node_sets[name].len(), n, "{name}");
    }
    let binary = read_ok(BOX_V41[1]).mesh;
    for file in box_files().skip(1) {
        let m = read_ok(file).mesh;
        // ASCII files print 16 significant digits (relative error <= 5e-16); binary files hold
        // the doubles themselves: files of one kind agree to the bit, ASCII and binary to 1e-15.
        let kind = if file.contains("ascii") { 0 } else { 1 };
        let same_kind = [&reference, &binary][kind];
        assert!(
            m.nodes == same_kind.nodes,
            "{file}: coordinates differ from {}",
            BOX_V41[kind]
        );
        let worst = m
            .nodes
            .iter()
            .flatten()
            .zip(reference.nodes.iter().flatten())
            .map(|(a, b)| (a - b).abs() / b.abs().max(f64::MIN_POSITIVE))
            .fold(0.0, f64::max);
        assert!(
            worst <= 1e-15,
            "{file}: relative coordinate difference {worst}"
        );
        assert_eq!(m.node_ids, reference.node_ids, "{file}");
        assert_eq!(m.blocks.tet10, reference.blocks.tet10, "{file}");
        assert_eq!(m.node_sets, reference.node_sets, "{file}");
        assert_eq!(m.element_sets, reference.element_sets, "{file}");
        assert!(m.dangling.is_empty(), "{file}");
    }
    // Element numbers differ between versions (MSH 2 renumbers its records), not within one.
    for group in [&BOX_V41[..], &BOX_V22[..]] {
        let first = read_ok(group[0]).mesh.element_ids;
        for file in &group[1..] {
            assert_eq!(read_ok(file).mesh.element_ids, first, "{file}");
        }
    }
}

/// The sets hold what the geometry says: the named point is the origin, the named surface is the
/// top face z = 0.02, the unnamed curves are the edges of the bottom face z = 0.
#[test]
fn box_sets_match_the_geometry() {
    let m = read_ok("msh/box_v41_binary_be.msh").mesh;
    let corner = &m.node_sets["corner"];
    assert_eq!(m.nodes[corner[0] as usize], [0.0, 0.0, 0.0]);
    // Gmsh places the nodes of a plane face exactly on it (coordinates copied from the CAD).
    for &n in &m.node_sets["friction_face"] {
        assert!((m.nodes[n as usize][2] - 0.02).abs() < 1e-15);
    }
    for &n in &m.node_sets["PHYSICAL_1_7"] {
        let [x, y, z] = m.nodes[n as usize];
        assert!(z.abs() < 1e-15);
        let on_edge = x.abs() < 1e-15
            || (x - 0.1).abs() < 1e-15
            || y.abs() < 1e-15
            || (y - 0.06).abs() < 1e-15;
        assert!(on_edge, "{x} {y}");
    }
    // Both volume groups hold the single volume: every element.
    assert_eq!(m.element_sets["pad"], (0..310).collect::<Vec<u32>>());
}

/// MSH 2 writes each tet10 once per physical group (twice here, as Gmsh's own reader counts:
/// 620); the reader keeps one element per node list and says so.
#[test]
fn msh2_repeated_elements_are_read_once() {
    for file in BOX_V22 {
        let r = read_ok(file);
        assert_eq!(r.mesh.num_elements(), 310, "{file}");
        let repeats: Vec<_> = r
            .warnings
            .iter()
            .filter(|w| w.message.contains("repeat"))
            .collect();
        assert_eq!(repeats.len(), 1, "{file}: {:?}", r.warnings);
        assert!(
            repeats[0].message.starts_with("310 solid element records"),
            "{}",
            repeats[0].message
        );
    }
}

/// Straight-sided elements: after reading (and permuting Gmsh's order to the canonical one),
/// every midside node sits at the midpoint of its canonical edge.
#[test]
fn midside_nodes_sit_at_edge_midpoints() {
    let files = [
        "outside/fenris-cube_tet10_24.msh",
        "outside/amfe-gmsh_ascii_v2_tet10.msh",
        "outside/amfe-bar_Tet10_fine.msh",
        "msh/one_tet_v22.msh",
        "msh/one_tet_v41.msh",
    ];
    for file in files.into_iter().chain(box_files()) {
        let m = read_ok(file).mesh;
        // Gmsh computes midpoints in doubles and prints 16-17 digits: offsets are ~1e-16 of the
        // size; a node on the wrong edge is off by a good fraction of an edge (> 1e-3 of the size).
        let off = worst_midside_offset(&m);
        assert!(
            off < 1e-12 * diagonal(&m),
            "{file}: midside node {off} from its edge midpoint"
        );
    }
    // The check can fail: undoing the permutation puts nodes 8 and 9 on the wrong edges.
    let mut m = read_ok("msh/one_tet_v22.msh").mesh;
    m.blocks.tet10[0].swap(8, 9);
    assert!(worst_midside_offset(&m) > 0.1);
}

/// The hand-written one-tet files: the tet10 ends up in canonical order, node for node.
#[test]
fn one_tet_in_canonical_order() {
    for file in ["msh/one_tet_v22.msh", "msh/one_tet_v41.msh"] {
        let r = read_ok(file);
        let m = &r.mesh;
        // Gmsh's order has node 9 (1-based) on edge (2,3) and node 10 on edge (1,3) (0-based
        // vertices); canonical has (1,3) before (2,3): ids 10 then 9.
        assert_eq!(m.element_ids, vec![2]);
        let ids: Vec<u64> = m.blocks.tet10[0]
            .iter()
            .map(|&i| m.node_ids[i as usize])
            .collect();
        assert_eq!(ids, vec![1, 2, 3, 4, 5, 6, 7, 8, 10, 9], "{file}");
        // The reference tetrahedron has volume 1/6 (exact in floating point up to round-off).
        assert!((total_volume(m) - 1.0 / 6.0).abs() < 1e-15);
        assert_eq!(m.element_sets["solid"], vec![0]);
    }
    // MSH 2.2 file: the triangle of group "face" gives its six nodes.
    let m = read_ok("msh/one_tet_v22.msh").mesh;
    let face: Vec<u64> = m.node_sets["face"]
        .iter()
        .map(|&i| m.node_ids[i as usize])
        .collect();
    assert_eq!(face, vec![1, 2, 3, 5, 6, 7]);
}

fn parse_str(text: &str) -> Result<ReadMesh, MeshError> {
    parse(text.as_bytes(), Path::new("inline.msh"))
}

const HEAD_22: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
const TET_NODES_22: &str = "$Nodes\n10\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 0.5 0 0\n6 0.5 0.5 0\n\
                            7 0 0.5 0\n8 0 0 0.5\n9 0 0.5 0.5\n10 0.5 0 0.5\n$EndNodes\n";

/// Groups of different dimensions with one name; unnamed groups; a line and a surface sharing a
/// name form one node set (with a warning), a volume and a surface sharing one do not clash.
#[test]
fn group_names() {
    let text = format!(
        "{HEAD_22}$PhysicalNames\n4\n1 5 \"fixed\"\n2 6 \"fixed\"\n2 7 \"pad\"\n3 8 \"pad\"\n$EndPhysicalNames\n\
         {TET_NODES_22}$Elements\n5\n\
         1 8 2 5 1 1 2 5\n\
         2 9 2 6 1 1 3 4 7 9 8\n\
         3 9 2 7 1 2 3 4 6 9 10\n\
         4 15 2 9 1 4\n\
         5 11 2 8 1 1 2 3 4 5 6 7 8 9 10\n$EndElements\n"
    );
    let r = parse_str(&text).unwrap();
    let m = &r.mesh;
    let ids = |set: &[u32]| -> Vec<u64> { set.iter().map(|&i| m.node_ids[i as usize]).collect() };
    // Nodes of the line (1 2 5) and of triangle 2 (1 3 4 7 9 8), sorted by index = by id here.
    assert_eq!(ids(&m.node_sets["fixed"]), vec![1, 2, 3, 4, 5, 7, 8, 9]);
    assert_eq!(ids(&m.node_sets["pad"]), vec![2, 3, 4, 6, 9, 10]);
    assert_eq!(m.element_sets["pad"], vec![0]);
    assert_eq!(ids(&m.node_sets["PHYSICAL_0_9"]), vec![4]);
    let shared: Vec<_> = r
        .warnings
        .iter()
        .filter(|w| w.message.contains("share the name"))
        .collect();
    assert_eq!(shared.len(), 1, "{:?}", r.warnings);
    assert!(shared[0].message.contains("\"fixed\""));
}

/// Unknown sections are skipped with one warning each; non-tet10 3D elements with one warning
/// per type; references to undefined nodes reach `Mesh::dangling`.
#[test]
fn skipped_sections_types_and_dangling_nodes() {
    let text = format!(
        "{HEAD_22}$Comments\nhello\n$EndComments\n{TET_NODES_22}\
         $NodeData\n1\n\"u\"\n$EndNodeData\n$Elements\n4\n\
         1 4 2 0 1 1 2 3 4\n\
         2 4 2 0 1 1 2 3 4\n\
         3 5 2 0 1 1 2 3 4 5 6 7 8\n\
         4 11 2 0 1 1 2 3 4 5 6 7 8 9 99\n$EndElements\n$Periodic\n0\n$EndPeriodic\n"
    );
    let r = parse_str(&text).unwrap();
    let messages: Vec<&str> = r.warnings.iter().map(|w| w.message.as_str()).collect();
    for (fragment, line) in [
        ("skipped section $Comments", 4),
        ("skipped section $NodeData", 20),
        ("skipped section $Periodic", 31),
        ("skipped 2 elements of type 4 (Tetrahedron 4)", 26),
        ("skipped 1 elements of type 5 (Hexahedron 8)", 28),
    ] {
        let w: Vec<_> = r
            .warnings
            .iter()
            .filter(|w| w.message.contains(fragment))
            .collect();
        assert_eq!(w.len(), 1, "{fragment}: {messages:?}");
        assert_eq!(w[0].location, Location::Line(line), "{fragment}");
    }
    // The tet10 names node 99, never defined: dropped and listed.
    assert_eq!(r.mesh.num_elements(), 0);
    assert_eq!(
        r.mesh.dangling,
        vec![squeal_mesh::Dangling::ElementNode {
            element: 4,
            node: 99
        }]
    );
}

/// MSH 4.1 without `$Entities`: elements still read, their entity's groups unknown (warned).
#[test]
fn msh41_without_entities() {
    let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n\
                0 0 0\n1 0 0\n0 1 0\n$EndNodes\n$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n";
    let r = parse_str(text).unwrap();
    assert_eq!(r.mesh.num_nodes(), 3);
    assert!(r.mesh.node_sets.is_empty());
    let w: Vec<_> = r
        .warnings
        .iter()
        .filter(|w| w.message.contains("missing from $Entities"))
        .collect();
    assert_eq!(w.len(), 1, "{:?}", r.warnings);
    assert!(
        w[0].message.contains("(1, first: dimension 2, tag 1)"),
        "{}",
        w[0].message
    );
}

/// The broken-file corpus (tools/msh-fixtures/make_broken.py): each file fails with an error
/// that names the file, the place and what was wrong; line numbers refer to the templates in
/// make_broken.py, byte offsets to field boundaries computed there.
#[test]
fn broken_files_fail_with_located_errors() {
    // Byte offsets: see the comments of make_broken.py, which asserts them from the layout.
    let cases: &[(&str, Location, &str)] = &[
        (
            "bad_byte_order_mark.msh",
            Location::Byte(20),
            "expected the byte-order mark",
        ),
        (
            "bad_number.msh",
            Location::Line(18),
            "expected the z coordinate, found `0.5x`",
        ),
        (
            "binary_data_size_4.msh",
            Location::Line(2),
            "data size 4 is not supported",
        ),
        (
            "binary_garbage.msh",
            Location::Byte(47),
            "declared, but the",
        ),
        (
            "dimension_mismatch.msh",
            Location::Line(41),
            "has dimension 3, but the block's entity has dimension 2",
        ),
        (
            "duplicate_node.msh",
            Location::Line(17),
            "node 6 is defined twice",
        ),
        ("garbage.msh", Location::Line(1), "not a Gmsh .msh file"),
        (
            "huge_count.msh",
            Location::Line(14),
            "18446744073709551615 nodes declared",
        ),
        (
            "huge_count_binary.msh",
            Location::Byte(50),
            "2147483647 elements declared",
        ),
        (
            "huge_count_v22.msh",
            Location::Line(10),
            "4000000000 nodes declared",
        ),
        (
            "huge_tags_binary.msh",
            Location::Byte(52),
            "3 elements in the block declared",
        ),
        (
            "missing_end_elements.msh",
            Location::Line(26),
            "unexpected end of file: expected $EndElements",
        ),
        (
            "missing_end_nodes.msh",
            Location::Line(21),
            "expected $EndNodes, found `$Elements`",
        ),
        ("msh_version_1.msh", Location::Line(1), "MSH version 1"),
        (
            "nan_coordinate.msh",
            Location::Line(18),
            "expected the z coordinate, found `nan`",
        ),
        // Hand-written (not by make_broken.py): a first-order mesh, one 4-node tetrahedron.
        (
            "no_tet10.msh",
            Location::File,
            "no quadratic solid element (Abaqus C3D10, C3D20, C3D20R, C3D15; Gmsh types 11, 17, \
             18, 19; Nastran CTETRA, CHEXA, CPENTA, CPYRAM with edge grids; Ansys SOLID186, \
             SOLID187) in the file, which has 4 nodes; skipped 1 elements of type 4 (Tetrahedron 4): \
             squeal reads only quadratic solids (types 11, 17, 18, 19); mesh with Mesh.ElementOrder = 2",
        ),
        (
            "node_total_mismatch.msh",
            Location::Line(14),
            "declares 11 nodes, but the blocks hold 10",
        ),
        (
            "not_msh.msh",
            Location::Line(1),
            "expected $MeshFormat, found `*HEADING`",
        ),
        (
            "stray_end.msh",
            Location::Line(9),
            "closes a section that was never opened",
        ),
        (
            "truncated_ascii.msh",
            Location::Line(25),
            "unexpected end of file: expected an element line",
        ),
        (
            "truncated_binary_v22.msh",
            Location::Byte(141),
            "694 nodes declared, but the 2800 bytes left",
        ),
        (
            "truncated_binary_v41.msh",
            Location::Byte(2025 + 16),
            "unexpected end of file: expected the header",
        ),
        (
            "truncated_binary_v41_elements.msh",
            Location::Byte(29954),
            "310 elements in the block declared",
        ),
        (
            "unclosed_comments.msh",
            Location::Line(27),
            "missing $EndComments",
        ),
        (
            "unknown_element_type.msh",
            Location::Line(25),
            "unknown element type 200",
        ),
        (
            "unquoted_name.msh",
            Location::Line(6),
            "expected a name in double quotes",
        ),
        (
            "version_3.msh",
            Location::Line(2),
            "unsupported MSH version 3.0",
        ),
        (
            "version_4_0.msh",
            Location::Line(2),
            "unsupported MSH version 4",
        ),
        (
            "wrong_node_count.msh",
            Location::Line(25),
            "has 9 fields after its 2 tags, expected 10 node tags",
        ),
        (
            "wrong_node_count_v41.msh",
            Location::Line(42),
            "has 9 node tags, expected 10",
        ),
    ];
    let dir = data("broken/msh");
    let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    on_disk.sort();
    let listed: Vec<String> = cases.iter().map(|c| c.0.to_string()).collect();
    assert_eq!(on_disk, listed, "every corpus file has an expectation");
    let mut failures = Vec::new();
    for &(name, location, fragment) in cases {
        let path = dir.join(name);
        let err = match read(&path) {
            Ok(_) => {
                failures.push(format!("{name}: read without error"));
                continue;
            }
            Err(e) => e,
        };
        let shown = err.to_string();
        let MeshError::Invalid {
            file,
            location: got,
            message,
        } = &err
        else {
            failures.push(format!("{name}: not an Invalid error: {shown}"));
            continue;
        };
        let ok = file == &path
            && *got == location
            && message.contains(fragment)
            && shown.starts_with(&path.display().to_string())
            && shown.contains(&format!("{location}: "));
        if !ok {
            failures.push(format!(
                "{name}: expected {location:?} `{fragment}`, got {got:?}: {shown}"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every prefix of a file (ASCII and binary, both versions) either reads or fails with an error;
/// nothing panics.
#[test]
fn truncations_never_panic() {
    for file in [
        "msh/one_tet_v41.msh",
        "msh/one_tet_v22.msh",
        "msh/box_v41_binary.msh",
        "msh/box_v22_binary_be.msh",
        "msh/box_v22_ascii.msh",
        "msh/box_v41_ascii.msh",
        "msh/box_v41_parametric_binary.msh",
        "outside/scikit-fem-quadratic_sphere_tet.msh",
    ] {
        let bytes = std::fs::read(data(file)).unwrap();
        let step = (bytes.len() / 400).max(1);
        for len in (0..bytes.len()).step_by(step) {
            let r = parse(&bytes[..len], Path::new(file));
            // Only the cut of the final newline leaves a whole file; any other cut leaves a
            // section open or missing.
            if len + 1 < bytes.len() {
                assert!(r.is_err(), "{file} cut at {len} read without error");
            }
        }
    }
}
