//! The Nastran and Ansys readers: node orders against the manuals' tables (with each
//! element's volume and Jacobian sign), the same mesh in three formats read to the same bits,
//! field formats and numbers, coordinate systems, materials, sets, includes, and a corpus of
//! broken files.

// Index loops mirror the formulas.
#![allow(clippy::needless_range_loop)]

use squeal_element::{ElementKind, Hex20, Pyramid13, ReferenceElement, Tet10, Wedge15};
use squeal_mesh::{Elastic, Location, Mesh, MeshError, cdb, inp, nastran};
use std::path::{Path, PathBuf};

fn data(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(rel)
}

/// Positions of `corners` then the midpoints of `edges` (0-based vertex pairs).
fn positions(corners: &[[f64; 3]], edges: &[[usize; 2]]) -> Vec<[f64; 3]> {
    let mut p = corners.to_vec();
    for [a, b] in edges {
        p.push(std::array::from_fn(|d| {
            0.5 * (corners[*a][d] + corners[*b][d])
        }));
    }
    p
}

const HEX: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];
const WEDGE: [[f64; 3]; 6] = [
    [0.0, 0.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
];
const PYRAMID: [[f64; 3]; 5] = [
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];
const TET: [[f64; 3]; 4] = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// MSC Nastran Quick Reference Guide, CTETRA, CHEXA, CPENTA, CPYRAM: the edges of the edge
/// grids, in the order of the cards' fields (written from the manual, not from the reader).
fn nastran_element(kind: ElementKind) -> (&'static str, Vec<[f64; 3]>) {
    match kind {
        ElementKind::Tet10 => (
            "CTETRA",
            positions(&TET, &[[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]]),
        ),
        ElementKind::Hex20 => (
            "CHEXA",
            positions(
                &HEX,
                &[
                    [0, 1],
                    [1, 2],
                    [2, 3],
                    [3, 0],
                    [0, 4],
                    [1, 5],
                    [2, 6],
                    [3, 7],
                    [4, 5],
                    [5, 6],
                    [6, 7],
                    [7, 4],
                ],
            ),
        ),
        ElementKind::Wedge15 => (
            "CPENTA",
            positions(
                &WEDGE,
                &[
                    [0, 1],
                    [1, 2],
                    [2, 0],
                    [0, 3],
                    [1, 4],
                    [2, 5],
                    [3, 4],
                    [4, 5],
                    [5, 3],
                ],
            ),
        ),
        ElementKind::Pyramid13 => (
            "CPYRAM",
            positions(
                &PYRAMID,
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
            ),
        ),
    }
}

/// Ansys Element Reference, SOLID186 (letters I..P corners, Q R S T, U V W X, Y Z A B edges)
/// in its four forms, and SOLID187 (I J K L corners, M N O P Q R on I-J, J-K, K-I, I-L, J-L,
/// K-L): the position of each node of the record.
fn ansys_element(kind: ElementKind, solid187: bool) -> Vec<[f64; 3]> {
    let mid =
        |a: [f64; 3], b: [f64; 3]| -> [f64; 3] { std::array::from_fn(|d| 0.5 * (a[d] + b[d])) };
    if solid187 {
        return positions(&TET, &[[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]]);
    }
    // Corners I J K L M N O P of the brick, collapsed as the form says.
    let c: [[f64; 3]; 8] = match kind {
        ElementKind::Hex20 => HEX,
        ElementKind::Wedge15 => {
            let w = WEDGE;
            [w[0], w[1], w[2], w[2], w[3], w[4], w[5], w[5]]
        }
        ElementKind::Pyramid13 => {
            let p = PYRAMID;
            [p[0], p[1], p[2], p[3], p[4], p[4], p[4], p[4]]
        }
        ElementKind::Tet10 => {
            let t = TET;
            [t[0], t[1], t[2], t[2], t[3], t[3], t[3], t[3]]
        }
    };
    let mut p = c.to_vec();
    for [a, b] in [
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
    ] {
        p.push(mid(c[a], c[b]));
    }
    p
}

/// The element's canonical node `i` is at the kind's reference position `i`; mapped by
/// `x -> 2 x + (1, 2, 3)`, its volume is 8 times the reference volume and `det J > 0`
/// everywhere it is sampled (a mirrored order would give a negative volume).
fn assert_canonical(mesh: &Mesh, kind: ElementKind, what: &str) {
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
    let x: Vec<[f64; 3]> = conn
        .iter()
        .map(|&n| std::array::from_fn(|d| 2.0 * mesh.nodes[n as usize][d] + (d + 1) as f64))
        .collect();
    fn check<E: ReferenceElement<N>, const N: usize>(x: &[[f64; 3]], reference: f64) -> (f64, f64) {
        let x: [[f64; 3]; N] = x.try_into().unwrap();
        let (lo, _) = squeal_element::reference::jacobian_range::<E, N>(&x);
        (E::volume(&x) / (8.0 * reference), lo)
    }
    let (ratio, lo) = match kind {
        ElementKind::Tet10 => check::<Tet10, 10>(&x, 1.0 / 6.0),
        ElementKind::Hex20 => check::<Hex20, 20>(&x, 8.0),
        ElementKind::Wedge15 => check::<Wedge15, 15>(&x, 1.0),
        ElementKind::Pyramid13 => check::<Pyramid13, 13>(&x, 4.0 / 3.0),
    };
    // Exact rules on an affine element: the volume to round-off.
    assert!((ratio - 1.0).abs() < 1e-13, "{what}: volume ratio {ratio}");
    assert!(lo > 0.0, "{what}: det J down to {lo}");
}

/// Small field (8 columns), large field (`GRID*`, 16 columns) or free field.
#[derive(Clone, Copy, Debug)]
enum Field {
    Small,
    Large,
    Free,
}

/// A card in the given field format: `values` are the data fields (8 a line).
fn card(name: &str, values: &[String], f: Field) -> String {
    let mut s = String::new();
    for (k, chunk) in values.chunks(8).enumerate() {
        match f {
            Field::Free => {
                s += if k == 0 { name } else { "" };
                for v in chunk {
                    s += &format!(",{v}");
                }
                s += "\n";
            }
            Field::Small => {
                s += &format!("{:<8}", if k == 0 { name } else { "+" });
                for v in chunk {
                    s += &format!("{v:>8}");
                }
                s += "\n";
            }
            Field::Large => {
                for (h, half) in chunk.chunks(4).enumerate() {
                    let head = if k == 0 && h == 0 {
                        format!("{name}*")
                    } else {
                        "*".into()
                    };
                    s += &format!("{head:<8}");
                    for v in half {
                        s += &format!("{v:>16}");
                    }
                    s += "\n";
                }
            }
        }
    }
    s
}

fn bdf_text(name: &str, nodes: &[[f64; 3]], grids: Field, elements: Field) -> String {
    let mut s = String::from("BEGIN BULK\n");
    for (i, p) in nodes.iter().enumerate() {
        let v: Vec<String> = [format!("{}", i + 1), String::new()]
            .into_iter()
            .chain(p.iter().map(|x| format!("{x:.1}")))
            .collect();
        s += &card("GRID", &v, grids);
    }
    let v: Vec<String> = ["1".to_string(), "1".into()]
        .into_iter()
        .chain((1..=nodes.len()).map(|i| i.to_string()))
        .collect();
    s += &card(name, &v, elements);
    s + "PSOLID,1,1\nMAT1,1,2.1+11,,.3,7850.\nENDDATA\n"
}

#[test]
fn nastran_orders_map_to_canonical() {
    for kind in ElementKind::ALL {
        let (name, nodes) = nastran_element(kind);
        for (grids, elements) in [
            (Field::Small, Field::Small),
            (Field::Large, Field::Free),
            (Field::Free, Field::Large),
        ] {
            let text = bdf_text(name, &nodes, grids, elements);
            let what = format!("{name} ({grids:?} grids, {elements:?} element)");
            let r = nastran::parse(text.as_bytes(), Path::new("one.bdf"), &inp::NoIncludes)
                .unwrap_or_else(|e| panic!("{what}: {e}\n{text}"));
            assert_canonical(&r.mesh, kind, &what);
            assert_eq!(r.mesh.element_set("PSOLID_1"), Some(&[0u32][..]), "{what}");
            assert_eq!(r.mesh.element_materials(), vec![Some("MAT_1")], "{what}");
        }
    }
}

/// A `.cdb` of one element: its distinct nodes (by position) and its record.
fn cdb_text(ty: u32, record: &[[f64; 3]]) -> String {
    let mut distinct: Vec<[f64; 3]> = Vec::new();
    let ids: Vec<usize> = record
        .iter()
        .map(|p| match distinct.iter().position(|q| q == p) {
            Some(i) => i + 1,
            None => {
                distinct.push(*p);
                distinct.len()
            }
        })
        .collect();
    let mut s = format!("/PREP7\nET,       1,{ty}\nNBLOCK,6,SOLID\n(3i9,6e21.13e3)\n");
    for (i, p) in distinct.iter().enumerate() {
        s += &format!("{:9}{:9}{:9}", i + 1, 0, 0);
        for x in p {
            s += &format!("{:>21}", format!("{x:.13E}"));
        }
        s += "\n";
    }
    s += "N,R5.3,LOC,       -1,\nEBLOCK,19,SOLID,1,1\n(19i9)\n";
    let rec: Vec<usize> = [1, 1, 1, 1, 0, 0, 0, 0, ids.len(), 0, 1]
        .into_iter()
        .chain(ids)
        .collect();
    for line in rec.chunks(19) {
        s += &line.iter().map(|v| format!("{v:9}")).collect::<String>();
        s += "\n";
    }
    s + "       -1\nMPDATA,R5.0, 1,EX  ,       1, 1,  2.1E+11,\nMPDATA,R5.0, 1,NUXY,       1, 1, 0.3,\n"
}

#[test]
fn ansys_orders_map_to_canonical() {
    for (ty, kind, solid187) in [
        (186, ElementKind::Hex20, false),
        (186, ElementKind::Wedge15, false),
        (186, ElementKind::Pyramid13, false),
        (186, ElementKind::Tet10, false),
        (187, ElementKind::Tet10, true),
    ] {
        let text = cdb_text(ty, &ansys_element(kind, solid187));
        let what = format!("SOLID{ty} as {kind}");
        let r = cdb::parse(text.as_bytes(), Path::new("one.cdb"))
            .unwrap_or_else(|e| panic!("{what}: {e}\n{text}"));
        assert_canonical(&r.mesh, kind, &what);
        assert_eq!(r.mesh.element_materials(), vec![Some("MAT_1")], "{what}");
        assert_eq!(
            r.mesh.materials["MAT_1"].elastic,
            Some(Elastic::Isotropic {
                young: 2.1e11,
                poisson: 0.3
            })
        );
    }
}

fn bits(m: &Mesh) -> Vec<[u64; 3]> {
    m.nodes.iter().map(|p| p.map(f64::to_bits)).collect()
}

/// The bundled coarse pad as .inp (the generator's), .bdf and .cdb (tools/mesh/
/// inp_to_bdf_cdb.py): the same node bits, ids, elements (canonical order), node and element
/// sets, and material constants element by element, bit for bit.
#[test]
fn the_same_mesh_in_three_formats_reads_to_the_same_bits() {
    let pad = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/pad_coarse.inp");
    let a = squeal_mesh::read(&pad).unwrap().mesh;
    for file in ["formats/pad_coarse.bdf", "formats/pad_coarse.cdb"] {
        let r = squeal_mesh::read(&data(file)).unwrap_or_else(|e| panic!("{e}"));
        let b = r.mesh;
        assert!(
            r.warnings
                .iter()
                .all(|w| !w.message.contains("no quadratic")),
            "{file}"
        );
        assert_eq!(bits(&a), bits(&b), "{file}: node coordinates");
        assert_eq!(a.node_ids, b.node_ids, "{file}");
        assert_eq!(a.blocks, b.blocks, "{file}: elements");
        assert_eq!(a.element_ids, b.element_ids, "{file}");
        assert_eq!(a.node_sets, b.node_sets, "{file}: node sets");
        for (name, set) in &a.element_sets {
            assert_eq!(
                b.element_set(name),
                Some(&set[..]),
                "{file}: element set {name}"
            );
        }
        let (ma, mb) = (a.element_materials(), b.element_materials());
        for e in 0..a.num_elements() {
            let (x, y) = (&a.materials[ma[e].unwrap()], &b.materials[mb[e].unwrap()]);
            assert_eq!(x, y, "{file}: material of element {e}");
        }
        assert!(b.dangling.is_empty(), "{file}");
    }
}

#[test]
fn nastran_systems_numbers_materials_and_sets() {
    let text = "\
$ executive and case control are skipped
SOL 103
CEND
BEGIN BULK
$HMNAME MAT 3 \"PAD\"
CORD2R  7       0       1.0     2.0     3.0     1.0     2.0     4.0     +
+       1.0     3.0     3.0
CORD2C,8,7,0.,0.,0.,0.,0.,1.,
,1.,0.,0.
GRID    1       7       1.      0.      0.
GRID,2,8,2.,90.,1.
GRID*   3               0               1.5-1           2.+0            *
*       -2.5E-1
GRID,4,,1.0D+00,,
GRID,5,,,,
SET1,9,1,THRU,3,5
MAT1,1,2.1+11,8.0+10,,7.85+3
MAT1,2,1.0+9,,.25
ENDDATA
GRID,99,,1.,1.,1.
";
    let r = nastran::parse(text.as_bytes(), Path::new("s.bdf"), &inp::NoIncludes).unwrap();
    let m = &r.mesh;
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|d| (a[d] - b[d]).abs() < 1e-14);
    // System 7: origin (1, 2, 3), local x = basic y. System 8 (cylindrical, in 7): r = 2 at
    // 90 degrees lies along 8's y = basic -x, z = 1 along basic z.
    assert!(close(m.nodes[0], [1.0, 3.0, 3.0]), "{:?}", m.nodes[0]);
    assert!(close(m.nodes[1], [-1.0, 2.0, 4.0]), "{:?}", m.nodes[1]);
    assert_eq!(m.nodes[2], [0.15, 2.0, -0.25]);
    assert_eq!(m.nodes[3], [1.0, 0.0, 0.0]);
    assert_eq!(m.num_nodes(), 5, "ENDDATA ends the bulk data");
    assert_eq!(m.node_set("SET1_9"), Some(&[0u32, 1, 2, 4][..]));
    // E and G give NU = E / (2 G) - 1; E and NU as given.
    let e1 = m.materials["MAT_1"];
    assert_eq!(
        e1.elastic,
        Some(Elastic::Isotropic {
            young: 2.1e11,
            poisson: 2.1e11 / 1.6e11 - 1.0
        })
    );
    assert_eq!(e1.density, Some(7850.0));
    assert_eq!(
        m.materials["MAT_2"].elastic,
        Some(Elastic::Isotropic {
            young: 1.0e9,
            poisson: 0.25
        })
    );
    assert!(
        r.warnings
            .iter()
            .any(|w| w.message.contains("no quadratic solid element"))
    );
}

/// 3×3 inverse by Gauss-Jordan elimination with partial pivoting.
fn inverse(a: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut m = [[0.0; 6]; 3];
    for i in 0..3 {
        m[i][..3].copy_from_slice(&a[i]);
        m[i][3 + i] = 1.0;
    }
    for c in 0..3 {
        let p = (c..3)
            .max_by(|&x, &y| m[x][c].abs().total_cmp(&m[y][c].abs()))
            .unwrap();
        m.swap(c, p);
        let d = m[c][c];
        for v in m[c].iter_mut() {
            *v /= d;
        }
        for r in 0..3 {
            if r != c {
                let f = m[r][c];
                for k in 0..6 {
                    m[r][k] -= f * m[c][k];
                }
            }
        }
    }
    std::array::from_fn(|i| std::array::from_fn(|j| m[i][3 + j]))
}

/// An orthotropic MAT9 (the stiffness of known engineering constants) reads back to those
/// constants to round-off; a coupled one, and MAT9 in other material axes, are refused.
#[test]
fn mat9_orthotropic_reads_as_engineering_constants() {
    let (e, nu, g) = (
        [1.0e10, 5.0e9, 2.0e9],
        [0.3, 0.2, 0.25],
        [4.0e9, 3.0e9, 2.0e9],
    );
    let s = [
        [1.0 / e[0], -nu[0] / e[0], -nu[1] / e[0]],
        [-nu[0] / e[0], 1.0 / e[1], -nu[2] / e[1]],
        [-nu[1] / e[0], -nu[2] / e[1], 1.0 / e[2]],
    ];
    let c = inverse(s);
    // G11 G12 G13 G14 G15 G16 G22 / G23 ... G36 / G44 ... G66 RHO (G44 = G12, G55 = G23,
    // G66 = G13).
    let f = |v: f64| format!("{v:e}");
    let text = format!(
        "MAT9,4,{},{},{},,,,{}\n,{},,,,{},,,\n,{},,,{},,{},1500.\nPSOLID,1,4\n",
        f(c[0][0]),
        f(c[0][1]),
        f(c[0][2]),
        f(c[1][1]),
        f(c[1][2]),
        f(c[2][2]),
        f(g[0]),
        f(g[2]),
        f(g[1])
    );
    let r = nastran::parse(text.as_bytes(), Path::new("m.bdf"), &inp::NoIncludes).unwrap();
    let Some(Elastic::EngineeringConstants {
        e: e2,
        nu: nu2,
        g: g2,
    }) = r.mesh.materials["MAT_4"].elastic
    else {
        panic!("not orthotropic")
    };
    // Two 3x3 inversions of a matrix with condition number ~10: round-off of ~1e-15.
    for k in 0..3 {
        assert!(
            (e2[k] / e[k] - 1.0).abs() < 1e-13,
            "E{k}: {} {}",
            e2[k],
            e[k]
        );
        assert!((nu2[k] / nu[k] - 1.0).abs() < 1e-13, "nu{k}");
        assert_eq!(g2[k], g[k]);
    }
    assert_eq!(r.mesh.materials["MAT_4"].density, Some(1500.0));
    let coupled = "MAT9,4,1.+10,,,5.+8,,,1.+10\n,,,,,1.+10,,,\n,1.+9,,,1.+9,,1.+9\n";
    let err = nastran::parse(coupled.as_bytes(), Path::new("c.bdf"), &inp::NoIncludes)
        .unwrap_err()
        .to_string();
    assert!(
        err.starts_with("c.bdf:1: MAT9 4 couples shear and extension (G14 not zero)"),
        "{err}"
    );
    let axes = text.replace(
        "PSOLID,1,4",
        "PSOLID,1,4,2\nCTETRA,1,1,1,2,3,4,5,6\n,7,8,9,10",
    );
    let err = nastran::parse(axes.as_bytes(), Path::new("a.bdf"), &inp::NoIncludes)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("a.bdf:4: PSOLID 1 gives the material axes CORDM = 2"),
        "{err}"
    );
}

/// Files held in memory, for include tests.
struct Memory(Vec<(&'static str, &'static str)>);

impl inp::IncludeResolver for Memory {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        self.0
            .iter()
            .find(|(p, _)| Path::new(p) == path)
            .map(|(_, t)| t.as_bytes().to_vec())
            .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::NotFound, "not in memory"))
    }
}

#[test]
fn nastran_includes_are_relative_and_loops_are_named() {
    let main = b"BEGIN BULK\nGRID,1,,0.,0.,0.\nINCLUDE 'sub/\n  b.bdf'\nGRID,4,,0.,0.,0.\n";
    let files = Memory(vec![
        ("m/sub/b.bdf", "GRID,2,,1.,0.,0.\nINCLUDE '../c/c.bdf'\n"),
        ("m/sub/../c/c.bdf", "GRID,3,,2.,0.,0.\n"),
    ]);
    let r = nastran::parse(main, Path::new("m/main.bdf"), &files).unwrap();
    assert_eq!(r.mesh.node_ids, vec![1, 2, 3, 4]);
    let looping = Memory(vec![("m/sub/b.bdf", "INCLUDE '../main.bdf'\n")]);
    let e = nastran::parse(main, Path::new("m/main.bdf"), &looping)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("m/sub/b.bdf:1: include loop: m/main.bdf -> m/sub/b.bdf -> m/sub/../main.bdf"),
        "{e}"
    );
    let e = nastran::parse(main, Path::new("m/main.bdf"), &inp::NoIncludes)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("m/main.bdf:3: cannot read included file m/sub/b.bdf"),
        "{e}"
    );
}

/// Broken files (tests/data/broken/{nastran,cdb}/MANIFEST): each gives its error at the
/// file and line listed (or reads, with a warning containing the fragment), never a panic.
#[test]
fn broken_files_give_located_errors() {
    for dir in ["broken/nastran", "broken/cdb"] {
        let text = std::fs::read_to_string(data(dir).join("MANIFEST")).unwrap();
        let mut listed = vec!["MANIFEST".to_string()];
        for line in text
            .lines()
            .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        {
            let cols: Vec<&str> = line.split(" | ").collect();
            assert_eq!(cols.len(), 3, "bad manifest line {line}");
            let (file, place, fragment) = (cols[0], cols[1], cols[2]);
            listed.push(file.to_string());
            let path = data(dir).join(file);
            let result = std::panic::catch_unwind(|| squeal_mesh::read(&path))
                .unwrap_or_else(|_| panic!("{file}: the reader panicked"));
            match (place, result) {
                ("ok", Ok(r)) => assert!(
                    r.warnings.iter().any(|w| w.message.contains(fragment)),
                    "{file}: no warning '{fragment}' in {:#?}",
                    r.warnings
                ),
                ("ok", Err(e)) => panic!("{file}: expected a mesh, got {e}"),
                (_, Ok(_)) => panic!("{file}: expected an error"),
                (place, Err(e)) => {
                    let shown = e.to_string();
                    let MeshError::Invalid {
                        file: f,
                        location,
                        message,
                    } = e
                    else {
                        panic!("{file}: expected MeshError::Invalid, got {shown}")
                    };
                    let (err_file, at) = place.rsplit_once(':').unwrap();
                    let loc = if at == "-" {
                        Location::File
                    } else {
                        Location::Line(at.parse().unwrap())
                    };
                    assert!(
                        f.ends_with(err_file),
                        "{file}: error names {} not {err_file}",
                        f.display()
                    );
                    assert_eq!(location, loc, "{file}: {shown}");
                    assert!(
                        message.contains(fragment),
                        "{file}: '{message}' lacks '{fragment}'"
                    );
                }
            }
        }
        for f in std::fs::read_dir(data(dir)).unwrap() {
            let name = f.unwrap().file_name().into_string().unwrap();
            assert!(
                listed.contains(&name) || name.ends_with(".inc"),
                "{dir}/{name} is not in the manifest"
            );
        }
    }
}

/// Cutting a valid file anywhere inside a line is an error, never a panic and never a
/// different mesh read as if complete.
#[test]
fn every_cut_inside_a_line_is_an_error() {
    for file in ["formats/pad_coarse.bdf", "formats/pad_coarse.cdb"] {
        let bytes = std::fs::read(data(file)).unwrap();
        let path = data(file);
        for cut in (1..bytes.len()).step_by(997) {
            let head = &bytes[..cut];
            // A cut at a line end, or inside a comment line, leaves a shorter complete file.
            let last = head.rsplit(|&b| b == b'\n').next().unwrap_or(&[]);
            let last = String::from_utf8_lossy(last);
            if last.trim().is_empty() || last.trim_start().starts_with('$') {
                continue;
            }
            let r = std::panic::catch_unwind(|| {
                if file.ends_with(".bdf") {
                    nastran::parse(head, &path, &inp::NoIncludes)
                } else {
                    cdb::parse(head, &path)
                }
            })
            .unwrap_or_else(|_| panic!("{file} cut at {cut}: panic"));
            assert!(r.is_err(), "{file} cut at byte {cut} read");
        }
    }
}
