//! What a scene selects on its meshes, as `squeal mesh info --scene` prints it: the sets of
//! `[sets]` (by name, by geometry or by default) with their counts, areas and centroids, the
//! unit system, the materials by element set; and both parts as one mesh with each selected
//! set as a node set, for a VTU that ParaView shows.

use crate::error::Result;
use crate::parts::{ChosenSet, Origin, SceneParts};
use squeal_mesh::Mesh;
use squeal_mesh::select::summarize;
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
    let inputs: Vec<(&Path, &str)> = files.iter().map(|(p, w)| (p.as_path(), *w)).collect();
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
        if piece.faces.is_empty() {
            outln!(s, "{label}{} nodes, no boundary face", piece.nodes.len());
            continue;
        }
        let sum = summarize(mesh, &piece.faces);
        outln!(
            s,
            "{label}{} nodes, {} faces, area {:.6e}, centroid [{:.6}, {:.6}, {:.6}]",
            piece.nodes.len(),
            sum.faces,
            sum.area,
            sum.centroid[0],
            sum.centroid[1],
            sum.centroid[2]
        );
    }
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
