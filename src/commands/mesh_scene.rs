//! `squeal mesh info --scene scene.toml [--vtu sets.vtu]`: what a scene selects on its meshes
//! (the sets of `[sets]`, by name, by geometry or by default; the unit system; the materials
//! by element set), with counts, areas and centroids, and a VTU of both parts with each
//! selected set as a point flag for ParaView.

use anyhow::{Context, Result};
use squeal_mesh::Mesh;
use squeal_mesh::select::summarize;
use squeal_pipeline::parts::{ChosenSet, Origin, SceneParts, load_parts};
use squeal_scene::Scene;
use std::path::Path;
use std::process::ExitCode;

pub fn info(path: &Path, vtu: Option<&Path>) -> Result<ExitCode> {
    let scene = Scene::read(path)?;
    if let Some(v) = vtu {
        squeal_io::require_extension(v, "vtu", "VTK XML unstructured grids (.vtu)")?;
        let files = scene.input_files()?;
        let inputs: Vec<(&Path, &str)> = files.iter().map(|(p, w)| (p.as_path(), *w)).collect();
        squeal_io::refuse_inputs(v, &inputs)?;
    }
    let parts = load_parts(&scene, &|m: &str| eprintln!("{m}"))?;
    println!("{}", path.display());
    println!(
        "  units     {} ({}); read into SI (m, kg, s, N, Pa)",
        parts.units.name, parts.units.description
    );
    for (name, loaded) in parts.all() {
        println!(
            "  {name:<9} {} ({} nodes, {} elements)",
            loaded.info.path, loaded.info.nodes, loaded.info.elements
        );
    }
    println!("  sets (areas in m^2, centroids in m)");
    for c in &parts.sets {
        print_set(&parts, c);
    }
    print_materials(&parts);
    if let Some(v) = vtu {
        let merged = merged(&parts);
        squeal_mesh::vtu::write_vtu(v, &merged, &[], &[])
            .with_context(|| format!("writing {}", v.display()))?;
        println!(
            "wrote {} (both parts; each set as the point flag set:<part>:<key>, each part as the cell flag set:<part>)",
            v.display()
        );
    }
    Ok(ExitCode::SUCCESS)
}

fn print_set(parts: &SceneParts, c: &ChosenSet) {
    let Some(mesh) = parts.part(&c.part).map(|p| &p.mesh) else {
        return;
    };
    let origin = match &c.origin {
        Origin::Scene(at) => format!("scene, {at}"),
        Origin::Mesh => "the mesh's node set".to_string(),
        Origin::Default => "default".to_string(),
    };
    println!("    {} ({origin}): {}", c.key, c.description);
    for (k, piece) in c.pieces.iter().enumerate() {
        let label = if c.pieces.len() > 1 {
            format!("      piece {}: ", k + 1)
        } else {
            "      ".to_string()
        };
        if let [n] = piece.nodes.as_slice() {
            let (id, x) = (mesh.node_ids[*n as usize], mesh.nodes[*n as usize]);
            println!(
                "{label}node {id} at [{:.6}, {:.6}, {:.6}]",
                x[0], x[1], x[2]
            );
            continue;
        }
        if piece.faces.is_empty() {
            println!("{label}{} nodes, no boundary face", piece.nodes.len());
            continue;
        }
        let s = summarize(mesh, &piece.faces);
        println!(
            "{label}{} nodes, {} faces, area {:.6e}, centroid [{:.6}, {:.6}, {:.6}]",
            piece.nodes.len(),
            s.faces,
            s.area,
            s.centroid[0],
            s.centroid[1],
            s.centroid[2]
        );
    }
}

fn print_materials(parts: &SceneParts) {
    println!("  materials by element set");
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
            println!(
                "    {set:<12} ({name}) {}",
                scene.or_else(file).unwrap_or_else(|| "none".to_string())
            );
        }
    }
}

fn describe(m: &squeal_fe::ElasticMaterial) -> String {
    use squeal_fe::ElasticMaterial as E;
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
            "transversely isotropic about {axis:?}, E_plane = {young_plane:.4e} Pa, E_axial = {young_axial:.4e} Pa, rho = {density} kg/m^3"
        ),
        E::Orthotropic { density, .. } => format!("orthotropic, rho = {density} kg/m^3"),
    }
}

/// Both parts as one mesh: nodes and elements of the disc then the pad, each part an element
/// set (`disc`, `pad`), each chosen set a node set `<part>:<key>` (pistons also per piece).
fn merged(parts: &SceneParts) -> Mesh {
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
