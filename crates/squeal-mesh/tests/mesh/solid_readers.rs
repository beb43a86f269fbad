//! The readers' node orders for the 20-node hexahedron, 15-node wedge and 13-node pyramid,
//! and the VTU writer's: each mapping is tested on one element whose nodes sit at the
//! reference positions the format's documentation gives them (tables written out here from
//! the Abaqus, Gmsh and VTK manuals, not from squeal's permutations), so a node read into
//! the wrong place shows as a coordinate mismatch.

// Index loops mirror the formulas (coordinates, Voigt pairs).
#![allow(clippy::needless_range_loop)]

use squeal_mesh::generate::box_solid;
use squeal_mesh::{ElementKind, MeshBuilder, inp, msh, vtu};
use std::path::Path;

/// Positions of `corners` then the midpoints of `edges`, as a format lists its nodes.
fn positions(corners: &[[f64; 3]], edges: &[[usize; 2]]) -> Vec<[f64; 3]> {
    let mut p = corners.to_vec();
    for [a, b] in edges {
        p.push(std::array::from_fn(|d| {
            0.5 * (corners[*a][d] + corners[*b][d])
        }));
    }
    p
}

const HEX_CORNERS: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];
/// Abaqus C3D20 (Abaqus Analysis User's Guide, "Three-dimensional solid element library"):
/// nodes 9-12 on the bottom edges 1-2, 2-3, 3-4, 4-1, 13-16 on the top ones, 17-20 on the
/// vertical edges 1-5, ..., 4-8. VTK's quadratic hexahedron is the same.
const HEX_EDGES_ABAQUS: [[usize; 2]; 12] = [
    [0, 1],
    [1, 2],
    [2, 3],
    [3, 0],
    [4, 5],
    [5, 6],
    [6, 7],
    [7, 4],
    [0, 4],
    [1, 5],
    [2, 6],
    [3, 7],
];
/// Gmsh's 20-node hexahedron (Gmsh reference manual, "Node ordering").
const HEX_EDGES_GMSH: [[usize; 2]; 12] = [
    [0, 1],
    [0, 3],
    [0, 4],
    [1, 2],
    [1, 5],
    [2, 3],
    [2, 6],
    [3, 7],
    [4, 5],
    [4, 7],
    [5, 6],
    [6, 7],
];
const WEDGE_CORNERS: [[f64; 3]; 6] = [
    [0.0, 0.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
];
/// Abaqus C3D15: 7-9 on the bottom triangle's edges 1-2, 2-3, 3-1, 10-12 on the top's,
/// 13-15 on the vertical edges.
const WEDGE_EDGES_ABAQUS: [[usize; 2]; 9] = [
    [0, 1],
    [1, 2],
    [2, 0],
    [3, 4],
    [4, 5],
    [5, 3],
    [0, 3],
    [1, 4],
    [2, 5],
];
/// Gmsh's 15-node prism.
const WEDGE_EDGES_GMSH: [[usize; 2]; 9] = [
    [0, 1],
    [0, 2],
    [0, 3],
    [1, 2],
    [1, 4],
    [2, 5],
    [3, 4],
    [3, 5],
    [4, 5],
];
const PYRAMID_CORNERS: [[f64; 3]; 5] = [
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];
/// Gmsh's 13-node pyramid.
const PYRAMID_EDGES_GMSH: [[usize; 2]; 8] = [
    [0, 1],
    [0, 3],
    [0, 4],
    [1, 2],
    [1, 4],
    [2, 3],
    [2, 4],
    [3, 4],
];

/// The mesh's single element has its canonical node `i` at the kind's reference position `i`.
fn assert_canonical(mesh: &squeal_mesh::Mesh, kind: ElementKind, what: &str) {
    assert_eq!(mesh.num_elements(), 1, "{what}");
    let (k, conn) = mesh.blocks.get(0).unwrap();
    assert_eq!(k, kind, "{what}");
    for (i, &n) in conn.iter().enumerate() {
        assert_eq!(
            mesh.nodes[n as usize],
            kind.nodes_ref()[i],
            "{what}: canonical node {i}"
        );
    }
}

fn inp_text(ty: &str, nodes: &[[f64; 3]]) -> String {
    let mut s = String::from("*NODE\n");
    for (i, p) in nodes.iter().enumerate() {
        s += &format!("{}, {}, {}, {}\n", i + 1, p[0], p[1], p[2]);
    }
    s += &format!("*ELEMENT, TYPE={ty}, ELSET=E\n");
    // At most 16 entries on a data line: the id and 15 nodes, the rest on the next line.
    let ids: Vec<String> = (1..=nodes.len()).map(|i| i.to_string()).collect();
    let (first, rest) = ids.split_at(ids.len().min(15));
    s += &format!("1, {}", first.join(", "));
    if !rest.is_empty() {
        s += &format!(",\n{}", rest.join(", "));
    }
    s + "\n"
}

#[test]
fn abaqus_orders_are_canonical() {
    let cases = [
        (
            "C3D20",
            ElementKind::Hex20,
            positions(&HEX_CORNERS, &HEX_EDGES_ABAQUS),
        ),
        (
            "C3D20R",
            ElementKind::Hex20,
            positions(&HEX_CORNERS, &HEX_EDGES_ABAQUS),
        ),
        (
            "C3D15",
            ElementKind::Wedge15,
            positions(&WEDGE_CORNERS, &WEDGE_EDGES_ABAQUS),
        ),
    ];
    for (ty, kind, nodes) in cases {
        let text = inp_text(ty, &nodes);
        let r = inp::parse(text.as_bytes(), Path::new("one.inp"), &inp::NoIncludes)
            .unwrap_or_else(|e| panic!("{ty}: {e}\n{text}"));
        assert_canonical(&r.mesh, kind, ty);
        assert_eq!(r.mesh.element_set("E"), Some(&[0u32][..]), "{ty}");
    }
    // A record one node short is an error naming the count.
    let nodes = positions(&HEX_CORNERS, &HEX_EDGES_ABAQUS);
    let text = inp_text("C3D20", &nodes[..19]);
    let err = inp::parse(text.as_bytes(), Path::new("short.inp"), &inp::NoIncludes)
        .unwrap_err()
        .to_string();
    assert!(err.contains("has 19 node ids; C3D20 needs 20"), "{err}");
}

fn msh_text(code: i32, nodes: &[[f64; 3]]) -> String {
    let mut s = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n");
    s += &format!("{}\n", nodes.len());
    for (i, p) in nodes.iter().enumerate() {
        s += &format!("{} {} {} {}\n", i + 1, p[0], p[1], p[2]);
    }
    s += &format!("$EndNodes\n$Elements\n1\n1 {code} 2 7 1");
    for i in 0..nodes.len() {
        s += &format!(" {}", i + 1);
    }
    s + "\n$EndElements\n"
}

#[test]
fn gmsh_orders_map_to_canonical() {
    let cases = [
        (
            17,
            ElementKind::Hex20,
            positions(&HEX_CORNERS, &HEX_EDGES_GMSH),
        ),
        (
            18,
            ElementKind::Wedge15,
            positions(&WEDGE_CORNERS, &WEDGE_EDGES_GMSH),
        ),
        (
            19,
            ElementKind::Pyramid13,
            positions(&PYRAMID_CORNERS, &PYRAMID_EDGES_GMSH),
        ),
    ];
    for (code, kind, nodes) in cases {
        let text = msh_text(code, &nodes);
        let r = msh::parse(text.as_bytes(), Path::new("one.msh"))
            .unwrap_or_else(|e| panic!("type {code}: {e}"));
        assert_canonical(&r.mesh, kind, &format!("Gmsh type {code}"));
        // Physical volume 7 becomes an element set holding the element.
        assert_eq!(
            r.mesh.element_set("PHYSICAL_3_7"),
            Some(&[0u32][..]),
            "{code}"
        );
    }
}

/// Decodes the base64 payload of the data array `name` of a VTU file (after its 8-byte
/// length header).
fn vtu_array(text: &str, name: &str) -> Vec<u8> {
    let tag = format!(r#"Name="{name}""#);
    let at = text.find(&tag).unwrap_or_else(|| panic!("no array {name}"));
    let start = at + text[at..].find('>').unwrap() + 1;
    let end = start + text[start..].find('<').unwrap();
    let mut bits = 0u32;
    let mut n = 0;
    let mut out = Vec::new();
    for c in text[start..end].bytes().filter(|&c| c != b'=') {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            _ => 63,
        };
        bits = (bits << 6) | u32::from(v);
        n += 6;
        if n >= 8 {
            n -= 8;
            out.push((bits >> n) as u8);
        }
    }
    out[8..].to_vec()
}

/// VTK (VTK User's Guide, "Nonlinear types"; vtkQuadraticHexahedron, vtkQuadraticWedge,
/// vtkQuadraticPyramid): the written cells have VTK's type codes, their midside nodes on
/// VTK's edges, and VTK's orientation: the hexahedron's and the pyramid's base `(0, 1, 2, 3)`
/// with its right-hand normal towards the other vertices, the wedge's triangle `(0, 1, 2)`
/// with its normal pointing *away* from `(3, 4, 5)`.
#[test]
fn vtu_cells_are_in_vtk_order() {
    let quad_edges: &[[usize; 2]] = &HEX_EDGES_ABAQUS;
    let cases: [(ElementKind, u8, &[[usize; 2]], f64); 3] = [
        (ElementKind::Hex20, 25, quad_edges, 1.0),
        (
            ElementKind::Wedge15,
            26,
            &[
                [0, 1],
                [1, 2],
                [2, 0],
                [3, 4],
                [4, 5],
                [5, 3],
                [0, 3],
                [1, 4],
                [2, 5],
            ],
            -1.0,
        ),
        (
            ElementKind::Pyramid13,
            27,
            &[
                [0, 1],
                [1, 2],
                [2, 3],
                [3, 0],
                [0, 4],
                [1, 4],
                [2, 4],
                [3, 4],
            ],
            1.0,
        ),
    ];
    let dir = std::env::temp_dir().join(format!("squeal-vtu-solid-{}", std::process::id()));
    for (kind, code, edges, side) in cases {
        let mesh = box_solid(kind, [1.0, 1.0, 1.0], [1, 1, 1]);
        let path = dir.join(format!("{code}.vtu"));
        vtu::write_vtu(&path, &mesh, &[], &[]).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let types = vtu_array(&text, "types");
        assert!(types.iter().all(|&t| t == code), "{kind}: types {types:?}");
        let conn: Vec<i64> = vtu_array(&text, "connectivity")
            .chunks(8)
            .map(|b| i64::from_le_bytes(b.try_into().unwrap()))
            .collect();
        let n = kind.nodes();
        assert_eq!(conn.len(), n * mesh.num_elements(), "{kind}");
        for cell in conn.chunks(n) {
            let p: Vec<[f64; 3]> = cell.iter().map(|&i| mesh.nodes[i as usize]).collect();
            let v = kind.vertices();
            for (k, [a, b]) in edges.iter().enumerate() {
                for d in 0..3 {
                    let mid = 0.5 * (p[*a][d] + p[*b][d]);
                    assert!(
                        (p[v + k][d] - mid).abs() < 1e-15,
                        "{kind}: VTK node {}",
                        v + k
                    );
                }
            }
            let sub =
                |a: usize, b: usize| -> [f64; 3] { std::array::from_fn(|d| p[a][d] - p[b][d]) };
            let (e1, e2) = (sub(1, 0), sub(2, 0));
            let nrm = [
                e1[1] * e2[2] - e1[2] * e2[1],
                e1[2] * e2[0] - e1[0] * e2[2],
                e1[0] * e2[1] - e1[1] * e2[0],
            ];
            let other = sub(if kind == ElementKind::Wedge15 { 3 } else { 4 }, 0);
            let s: f64 = (0..3).map(|d| nrm[d] * other[d]).sum();
            assert!(s * side > 0.0, "{kind}: VTK orientation");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A mixed mesh keeps one block per kind, indices block after block, whatever the order in
/// the file.
#[test]
fn builder_orders_blocks_by_kind() {
    let mut b = MeshBuilder::new();
    for i in 1..=20u64 {
        b.add_node(i, [i as f64, 0.0, 0.0]).unwrap();
    }
    let hex: Vec<u64> = (1..=20).collect();
    b.add_typed(5, ElementKind::Hex20, &hex).unwrap();
    b.add_element(9, [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]).unwrap();
    b.add_typed(7, ElementKind::Wedge15, &hex[..15]).unwrap();
    assert!(b.add_typed(5, ElementKind::Pyramid13, &hex[..13]).is_err());
    assert!(b.add_typed(8, ElementKind::Pyramid13, &hex[..12]).is_err());
    b.add_to_element_set("S", [7, 5]);
    let m = b.finish();
    assert_eq!(m.element_ids, vec![9, 5, 7]);
    assert_eq!(m.blocks.kinds().len(), 3);
    assert_eq!(m.element_set("S"), Some(&[1u32, 2][..]));
    let err = m.only_tet10("the test").unwrap_err().to_string();
    assert!(err.contains("20-node hexahedron (element 5)"), "{err}");
}

/// Code that reads triangles refuses a surface of quadrilaterals with a message that says
/// so, and accepts triangles of any kind.
#[test]
fn quadrilateral_faces_are_refused_where_triangles_are_read() {
    use squeal_mesh::select::{boundary_faces, boundary_quads, triangles_only};
    let hex = box_solid(ElementKind::Hex20, [1.0, 1.0, 1.0], [2, 2, 2]);
    assert_eq!(boundary_quads(&hex).len(), 24);
    assert!(boundary_faces(&hex).is_empty());
    let err = triangles_only(&hex, None, "the contact interface")
        .unwrap_err()
        .to_string();
    assert!(
        err.starts_with("the contact interface reads 6-node triangle faces; this mesh's face")
            && err.ends_with("is an 8-node quadrilateral: not yet supported"),
        "{err}"
    );
    // A wedge box's top is made of triangles: accepted; its sides are quadrilaterals.
    let wedge = box_solid(ElementKind::Wedge15, [1.0, 1.0, 1.0], [2, 2, 1]);
    let top = wedge.node_set("ZMAX").unwrap();
    assert!(triangles_only(&wedge, Some(top), "the contact interface").is_ok());
    assert!(triangles_only(&wedge, wedge.node_set("XMIN"), "the contact interface").is_err());
    // 2 x 2 cells, two wedges each: 8 triangles on the bottom, 8 on the top.
    assert_eq!(boundary_faces(&wedge).len(), 16);
    let tet = box_solid(ElementKind::Tet10, [1.0, 1.0, 1.0], [1, 1, 1]);
    assert!(triangles_only(&tet, None, "the contact interface").is_ok());
}
