//! What a scene selects on its meshes, as `squeal mesh info --scene` prints it: the sets of
//! `[sets]` (by name, by geometry or by default) with their counts, areas and centroids, the
//! unit system, the materials by element set; and both parts as one mesh with each selected
//! set as a node set, for a VTU that ParaView shows.

use crate::error::Result;
use crate::parts::{ChosenSet, Origin, SceneParts};
use squeal_mesh::Mesh;
use squeal_mesh::select::{Selection, boundary_quads, summarize};
use squeal_reduce::interface::face::{Shape, SurfaceFace, map_point};
use squeal_scene::Scene;
use std::fmt::Write;
use std::path::Path;

/// `writeln!` into a `String` (which cannot fail).
macro_rules! outln {
    ($s:expr, $($arg:tt)*) => {{
        let _ = writeln!($s, $($arg)*);
    }};
}

/// Refuses a `--vtu` output that is not a `.vtu` or would overwrite one of the scene's inputs.
pub fn check_vtu_output(scene: &Scene, vtu: &Path) -> Result<()> {
    squeal_io::require_extension(vtu, "vtu", "VTK XML unstructured grids (.vtu)")?;
    let files = scene.input_files()?;
    let inputs: Vec<(&Path, &str)> = files
        .iter()
        .map(|(p, w)| (p.as_path(), w.as_str()))
        .collect();
    squeal_io::refuse_inputs(vtu, &inputs)?;
    Ok(())
}

/// The listing of `parts` (the scene `path`'s): units, parts, sets, materials.
pub fn text(path: &Path, parts: &SceneParts) -> String {
    let mut s = String::new();
    outln!(s, "{}", path.display());
    outln!(
        s,
        "  units     {} ({}); read into SI (m, kg, s, N, Pa)",
        parts.units.name,
        parts.units.description
    );
    for (name, loaded) in parts.all() {
        outln!(
            s,
            "  {name:<9} {} ({} nodes, {} elements)",
            loaded.info.path,
            loaded.info.nodes,
            loaded.info.elements
        );
    }
    outln!(s, "  sets (areas in m^2, centroids in m)");
    for c in &parts.sets {
        set_text(&mut s, parts, c);
    }
    materials_text(&mut s, parts);
    s
}

/// Writes both parts as one VTU ([`merged`]).
pub fn write_vtu(parts: &SceneParts, vtu: &Path) -> Result<()> {
    squeal_mesh::vtu::write_vtu(vtu, &merged(parts), &[], &[])?;
    Ok(())
}

fn set_text(s: &mut String, parts: &SceneParts, c: &ChosenSet) {
    let Some(mesh) = parts.part(&c.part).map(|p| &p.mesh) else {
        return;
    };
    let origin = match &c.origin {
        Origin::Scene(at) => format!("scene, {at}"),
        Origin::Mesh => "the mesh's node set".to_string(),
        Origin::Default => "default".to_string(),
    };
    outln!(s, "    {} ({origin}): {}", c.key, c.description);
    for (k, piece) in c.pieces.iter().enumerate() {
        let label = if c.pieces.len() > 1 {
            format!("      piece {}: ", k + 1)
        } else {
            "      ".to_string()
        };
        if let [n] = piece.nodes.as_slice() {
            let (id, x) = (mesh.node_ids[*n as usize], mesh.nodes[*n as usize]);
            outln!(
                s,
                "{label}node {id} at [{:.6}, {:.6}, {:.6}]",
                x[0],
                x[1],
                x[2]
            );
            continue;
        }
        outln!(s, "{label}{}", piece_text(mesh, piece));
    }
}

/// A piece's nodes and boundary faces: its 6-node triangles and the 8-node quadrilaterals
/// (of hex20, wedge15, pyramid13 elements) whose nodes are all in it, with their area and
/// area centroid.
fn piece_text(mesh: &Mesh, piece: &Selection) -> String {
    let quads = quads_in(mesh, &piece.nodes);
    if piece.faces.is_empty() && quads.is_empty() {
        return format!("{} nodes, no boundary face", piece.nodes.len());
    }
    let tri = summarize(mesh, &piece.faces);
    let (mut area, mut moment) = (tri.area, tri.centroid.map(|c| c * tri.area));
    if piece.faces.is_empty() {
        moment = [0.0; 3];
    }
    for q in &quads {
        let x = SurfaceFace::quad8(*q).coords(mesh);
        for (st, w) in Shape::Quad8.rule() {
            let (_, p, n) = map_point(Shape::Quad8, &x, st);
            let da = w * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            area += da;
            for d in 0..3 {
                moment[d] += da * p[d];
            }
        }
    }
    let c = moment.map(|m| m / area);
    format!(
        "{} nodes, {} faces, area {:.6e}, centroid [{:.6}, {:.6}, {:.6}]",
        piece.nodes.len(),
        tri.faces + quads.len(),
        area,
        c[0],
        c[1],
        c[2]
    )
}

/// The 8-node quadrilateral boundary faces with all their nodes in `nodes`; none on a mesh of
/// tetrahedra.
fn quads_in(mesh: &Mesh, nodes: &[u32]) -> Vec<[u32; 8]> {
    if mesh.blocks.len() == mesh.blocks.tet10.len() {
        return Vec::new();
    }
    let mut member = vec![false; mesh.num_nodes()];
    for &n in nodes {
        if let Some(m) = member.get_mut(n as usize) {
            *m = true;
        }
    }
    boundary_quads(mesh)
        .into_iter()
        .filter(|q| q.iter().all(|&n| member[n as usize]))
        .collect()
}

fn materials_text(s: &mut String, parts: &SceneParts) {
    outln!(s, "  materials by element set");
    for (name, loaded) in parts.all() {
        let m = &loaded.mesh;
        for set in m.element_sets.keys() {
            let scene = parts
                .materials
                .iter()
                .find(|(s, _)| s.eq_ignore_ascii_case(set))
                .map(|(_, mat)| format!("scene: {}", describe(mat)));
            let file = || {
                m.sections
                    .iter()
                    .rev()
                    .find(|s| s.element_set.eq_ignore_ascii_case(set))
                    .map(|s| format!("mesh: material {}", s.material))
            };
            outln!(
                s,
                "    {set:<12} ({name}) {}",
                scene.or_else(file).unwrap_or_else(|| "none".to_string())
            );
        }
    }
}

fn describe(m: &squeal_fe::ElasticMaterial) -> String {
    use squeal_fe::ElasticMaterial as E;
    let v = |a: [f64; 3]| format!("[{}, {}, {}]", a[0], a[1], a[2]);
    match *m {
        E::Isotropic {
            young,
            poisson,
            density,
        } => format!("isotropic, E = {young:.4e} Pa, nu = {poisson}, rho = {density} kg/m^3"),
        E::TransverselyIsotropic {
            young_plane,
            young_axial,
            axis,
            density,
            ..
        } => format!(
            "transversely isotropic about {}, E_plane = {young_plane:.4e} Pa, E_axial = {young_axial:.4e} Pa, rho = {density} kg/m^3",
            v(axis)
        ),
        E::Orthotropic { density, .. } => format!("orthotropic, rho = {density} kg/m^3"),
    }
}

/// Both parts as one mesh: nodes and elements of the disc then the pad, each part an element
/// set (`disc`, `pad`), each chosen set a node set `<part>:<key>` (pistons also per piece).
pub fn merged(parts: &SceneParts) -> Mesh {
    let mut out = Mesh::default();
    let all = parts.all();
    let mut n0s = Vec::with_capacity(all.len());
    for (_, loaded) in &all {
        n0s.push(out.nodes.len() as u32);
        out.nodes.extend(&loaded.mesh.nodes);
        out.node_ids.extend(&loaded.mesh.node_ids);
    }
    // Elements block by block (the mesh's index order), each part's in turn within a block.
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); all.len()];
    for kind in squeal_mesh::ElementKind::ALL {
        for (p, (_, loaded)) in all.iter().enumerate() {
            let m = &loaded.mesh;
            let first = m.blocks.first(kind);
            for e in first..first + m.blocks.count(kind) {
                if let Some((_, conn)) = m.blocks.get(e) {
                    let shifted: Vec<u32> = conn.iter().map(|n| n + n0s[p]).collect();
                    members[p].push(out.element_ids.len() as u32);
                    out.blocks.push(kind, &shifted);
                    out.element_ids.push(m.element_ids[e]);
                }
            }
        }
    }
    for (p, (name, _)) in all.iter().enumerate() {
        let (name, n0) = (*name, n0s[p]);
        out.element_sets
            .insert(name.to_string(), std::mem::take(&mut members[p]));
        for c in parts.sets.iter().filter(|c| c.part == name) {
            // `sets.disc.clamp` -> clamp; `pads.outboard.load` -> outboard.load.
            let key = match c.key.strip_prefix("pads.") {
                Some(k) => k,
                None => c.key.rsplit('.').next().unwrap_or(&c.key),
            };
            let shift = |v: &[u32]| v.iter().map(|n| n + n0).collect::<Vec<u32>>();
            out.node_sets
                .insert(format!("{name}:{key}"), shift(&c.nodes()));
            if c.pieces.len() > 1 {
                for (k, p) in c.pieces.iter().enumerate() {
                    out.node_sets
                        .insert(format!("{name}:{key}:{}", k + 1), shift(&p.nodes));
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use squeal_mesh::ElementKind;
    use squeal_mesh::generate::box_solid;

    /// A named node set on the x = 0 face of a hex20 box (0.02 x 0.03 x 0.04 m, 2 x 3 x 4
    /// cells): its 12 quadrilateral faces, area 0.03 * 0.04 and centroid [0, 0.015, 0.02]
    /// (flat faces: the 3 x 3 Gauss rule integrates their area exactly, so round-off only).
    #[test]
    fn a_set_of_quadrilateral_faces_is_counted_with_its_area() {
        let mesh = box_solid(ElementKind::Hex20, [0.02, 0.03, 0.04], [2, 3, 4]);
        let nodes: Vec<u32> = (0..mesh.num_nodes() as u32)
            .filter(|&n| mesh.nodes[n as usize][0].abs() < 1e-12)
            .collect();
        let piece = Selection {
            faces: Vec::new(),
            nodes,
        };
        let text = piece_text(&mesh, &piece);
        // 3 x 4 cells on the face: corner grid 4 x 5, midside nodes 3 x 5 + 4 x 4: 51 nodes.
        assert!(text.starts_with("51 nodes, 12 faces, area "), "{text}");
        let area: f64 = text
            .split("area ")
            .nth(1)
            .and_then(|t| t.split(',').next())
            .and_then(|t| t.parse().ok())
            .unwrap();
        // Printed to 7 significant digits.
        assert!((area / (0.03 * 0.04) - 1.0).abs() < 1e-6, "{text}");
        assert!(
            text.ends_with("centroid [0.000000, 0.015000, 0.020000]"),
            "{text}"
        );
        let none = Selection {
            faces: Vec::new(),
            nodes: vec![0],
        };
        assert_eq!(piece_text(&mesh, &none), "1 nodes, no boundary face");
    }
}
