//! VTK XML unstructured grids (`.vtu`) for ParaView, and `.pvd` collections for time series.
//!
//! Cells are the quadratic solids: tetrahedra (VTK cell type 24), hexahedra (25,
//! `VTK_QUADRATIC_HEXAHEDRON`), wedges (26, `VTK_QUADRATIC_WEDGE`) and pyramids (27,
//! `VTK_QUADRATIC_PYRAMID`), each written in VTK's node order
//! ([`squeal_element::ReferenceElement::VTK_ORDER`]: the canonical order but for the wedge,
//! which VTK orients the other way). Data arrays are "binary" (base64 of little-endian
//! values with a UInt64 byte-count header, `header_type="UInt64"`), which ParaView reads
//! without any extra library.
//!
//! Every file carries, besides the caller's fields: point data `node_id` (the source file's
//! node ids) and one `UInt8` flag array per node set (`set:<name>`, 1 on members); cell data
//! `element_id` and one flag array per element set.

use crate::model::Mesh;
use squeal_io::{IoError, atomic_write};
use std::io::{self, Write};
use std::path::Path;

/// VTK cell type of the quadratic tetrahedron.
pub const VTK_QUADRATIC_TETRA: u8 = 24;

/// A field on the nodes (`components` values per node, node-major) or on the elements.
#[derive(Clone, Copy, Debug)]
pub struct Field<'a> {
    /// Name of the data array, as ParaView lists it (XML-escaped on writing).
    pub name: &'a str,
    /// 1 for scalars, 3 for vectors (ParaView's "Warp By Vector" takes a 3-component field).
    pub components: usize,
    /// `num_nodes * components` (point fields) or `num_elements * components` (cell fields).
    pub values: &'a [f64],
}

/// Errors of the VTU writer.
#[derive(Debug, thiserror::Error)]
pub enum VtuError {
    /// A field's `values` do not hold `components` values per node (point fields) or per
    /// element (cell fields); nothing was written.
    #[error("field '{name}' has {len} values; expected {expected} ({count} x {components})")]
    FieldLength {
        /// The field's name.
        name: String,
        /// Number of values given.
        len: usize,
        /// Number of values expected, `count * components`.
        expected: usize,
        /// Number of nodes or elements of the mesh.
        count: usize,
        /// The field's components per node or element.
        components: usize,
    },
    /// Writing the file failed (the previous file at the path, if any, is untouched).
    #[error(transparent)]
    Io(#[from] IoError),
}

/// Writes `mesh` with point and cell fields to `path` (atomically).
pub fn write_vtu(
    path: &Path,
    mesh: &Mesh,
    point_fields: &[Field],
    cell_fields: &[Field],
) -> Result<(), VtuError> {
    check_lengths(point_fields, mesh.num_nodes())?;
    check_lengths(cell_fields, mesh.num_elements())?;
    atomic_write(path, |w| write_document(w, mesh, point_fields, cell_fields))?;
    Ok(())
}

fn check_lengths(fields: &[Field], count: usize) -> Result<(), VtuError> {
    for f in fields {
        let expected = count * f.components;
        if f.values.len() != expected {
            return Err(VtuError::FieldLength {
                name: f.name.to_string(),
                len: f.values.len(),
                expected,
                count,
                components: f.components,
            });
        }
    }
    Ok(())
}

fn write_document(
    w: &mut dyn Write,
    mesh: &Mesh,
    point_fields: &[Field],
    cell_fields: &[Field],
) -> io::Result<()> {
    let (n, e) = (mesh.num_nodes(), mesh.num_elements());
    writeln!(w, r#"<?xml version="1.0"?>"#)?;
    writeln!(
        w,
        r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">"#
    )?;
    writeln!(w, "<UnstructuredGrid>")?;
    writeln!(w, r#"<Piece NumberOfPoints="{n}" NumberOfCells="{e}">"#)?;

    writeln!(w, "<PointData>")?;
    for f in point_fields {
        data_array(w, "Float64", f.name, f.components, &le_bytes_f64(f.values))?;
    }
    let ids: Vec<u8> = mesh.node_ids.iter().flat_map(|v| v.to_le_bytes()).collect();
    data_array(w, "UInt64", "node_id", 1, &ids)?;
    for (name, set) in &mesh.node_sets {
        data_array(w, "UInt8", &format!("set:{name}"), 1, &flags(n, set))?;
    }
    writeln!(w, "</PointData>")?;

    writeln!(w, "<CellData>")?;
    for f in cell_fields {
        data_array(w, "Float64", f.name, f.components, &le_bytes_f64(f.values))?;
    }
    let ids: Vec<u8> = mesh
        .element_ids
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    data_array(w, "UInt64", "element_id", 1, &ids)?;
    for (name, set) in &mesh.element_sets {
        data_array(w, "UInt8", &format!("set:{name}"), 1, &flags(e, set))?;
    }
    writeln!(w, "</CellData>")?;

    writeln!(w, "<Points>")?;
    let coords: Vec<f64> = mesh.nodes.iter().flatten().copied().collect();
    data_array(w, "Float64", "Points", 3, &le_bytes_f64(&coords))?;
    writeln!(w, "</Points>")?;

    writeln!(w, "<Cells>")?;
    let (mut conn, mut offsets, mut types) = (Vec::new(), Vec::new(), Vec::with_capacity(e));
    let mut end = 0i64;
    for (kind, range) in mesh.blocks.kinds() {
        let order = kind.vtk_order();
        for el in range.filter_map(|i| mesh.blocks.get(i)).map(|(_, c)| c) {
            conn.extend(order.iter().flat_map(|&a| i64::from(el[a]).to_le_bytes()));
            end += order.len() as i64;
            offsets.extend(end.to_le_bytes());
            types.push(kind.vtk_cell_type());
        }
    }
    data_array(w, "Int64", "connectivity", 1, &conn)?;
    data_array(w, "Int64", "offsets", 1, &offsets)?;
    data_array(w, "UInt8", "types", 1, &types)?;
    writeln!(w, "</Cells>")?;

    writeln!(w, "</Piece>")?;
    writeln!(w, "</UnstructuredGrid>")?;
    writeln!(w, "</VTKFile>")
}

fn flags(count: usize, members: &[u32]) -> Vec<u8> {
    let mut f = vec![0u8; count];
    for &m in members {
        f[m as usize] = 1;
    }
    f
}

fn le_bytes_f64(v: &[f64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

fn data_array(
    w: &mut dyn Write,
    ty: &str,
    name: &str,
    components: usize,
    bytes: &[u8],
) -> io::Result<()> {
    write!(
        w,
        r#"<DataArray type="{ty}" Name="{}" NumberOfComponents="{components}" format="binary">"#,
        xml_escape(name)
    )?;
    let mut block = (bytes.len() as u64).to_le_bytes().to_vec();
    block.extend_from_slice(bytes);
    w.write_all(base64(&block).as_bytes())?;
    writeln!(w, "</DataArray>")
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Standard base64 (RFC 4648) with padding.
fn base64(bytes: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let v = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        out.push(T[(v >> 18) as usize & 63] as char);
        out.push(T[(v >> 12) as usize & 63] as char);
        out.push(if chunk.len() > 1 {
            T[(v >> 6) as usize & 63] as char
        } else {
            '='
        });
        out.push(if chunk.len() > 2 {
            T[v as usize & 63] as char
        } else {
            '='
        });
    }
    out
}

/// Writes a ParaView collection (`.pvd`) listing `(time, file)` entries; file paths are
/// written as given (make them relative to the .pvd's folder).
pub fn write_pvd(path: &Path, entries: &[(f64, String)]) -> Result<(), IoError> {
    atomic_write(path, |w| {
        writeln!(w, r#"<?xml version="1.0"?>"#)?;
        writeln!(
            w,
            r#"<VTKFile type="Collection" version="1.0" byte_order="LittleEndian">"#
        )?;
        writeln!(w, "<Collection>")?;
        for (t, file) in entries {
            writeln!(
                w,
                r#"<DataSet timestep="{t:e}" part="0" file="{}"/>"#,
                xml_escape(file)
            )?;
        }
        writeln!(w, "</Collection>")?;
        writeln!(w, "</VTKFile>")
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::box_tet10;

    #[test]
    fn base64_matches_rfc4648_vectors() {
        // RFC 4648 section 10 test vectors.
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, enc) in cases {
            assert_eq!(base64(plain.as_bytes()), enc);
        }
    }

    #[test]
    fn writes_fields_and_rejects_wrong_lengths() {
        let m = box_tet10([1.0, 1.0, 1.0], [1, 1, 1]);
        let dir = std::env::temp_dir().join(format!("squeal-vtu-{}", std::process::id()));
        let path = dir.join("box.vtu");
        let disp: Vec<f64> = m.nodes.iter().flat_map(|p| [p[0], 0.0, 0.0]).collect();
        write_vtu(
            &path,
            &m,
            &[Field {
                name: "u",
                components: 3,
                values: &disp,
            }],
            &[],
        )
        .unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains(&format!(
            r#"NumberOfPoints="{}" NumberOfCells="6""#,
            m.num_nodes()
        )));
        assert!(text.contains(r#"Name="set:XMIN""#));
        assert!(text.contains(r#"Name="u" NumberOfComponents="3""#));
        let bad = write_vtu(
            &path,
            &m,
            &[Field {
                name: "u",
                components: 3,
                values: &disp[1..],
            }],
            &[],
        );
        assert!(matches!(bad, Err(VtuError::FieldLength { .. })));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
