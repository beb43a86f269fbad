//! The parts' materials: the scene's against the meshes', with units and plausibility checked.

use super::*;

/// Every `[materials]` set exists in a part, and every element of both parts has a
/// material: otherwise an error listing the element sets still without one and the key
/// that would give it.
pub(super) fn check_materials(
    scene: &Scene,
    materials: &[(String, ElasticMaterial)],
    parts: &[(&str, &Mesh)],
) -> Result<()> {
    for (set, _) in materials {
        if !parts.iter().any(|(_, m)| m.element_set(set).is_some()) {
            let known: Vec<String> = parts
                .iter()
                .flat_map(|(p, m)| m.element_sets.keys().map(move |k| format!("{k} ({p})")))
                .collect();
            return Err(PipelineError::Input {
                what: "scene materials",
                message: format!(
                    "{}: [materials.{set}]: neither mesh has an element set {set} (element sets: {})",
                    scene.path.display(),
                    if known.is_empty() {
                        "none".into()
                    } else {
                        known.join(", ")
                    }
                ),
            });
        }
    }
    let mut lacking = Vec::new();
    for (part, mesh) in parts {
        let mine = overrides_for(materials, mesh);
        match MaterialTable::from_mesh(mesh, &mine) {
            Ok(_) => {}
            Err(FeError::NoMaterial { .. }) => {
                let mut covered = vec![false; mesh.num_elements()];
                for s in &mesh.sections {
                    if let Some(set) = mesh.element_set(&s.element_set)
                        && mesh
                            .materials
                            .keys()
                            .any(|k| k.eq_ignore_ascii_case(&s.material))
                    {
                        set.iter().for_each(|&e| covered[e as usize] = true);
                    }
                }
                for (set, _) in &mine {
                    if let Some(es) = mesh.element_set(set) {
                        es.iter().for_each(|&e| covered[e as usize] = true);
                    }
                }
                let mut named = false;
                for (name, es) in &mesh.element_sets {
                    let bare = es.iter().filter(|&&e| !covered[e as usize]).count();
                    if bare > 0 {
                        named = true;
                        lacking.push(format!(
                            "{name} ({part}, {bare} elements): add [materials.{name}] with young, poisson, density"
                        ));
                    }
                }
                if !named {
                    let bare = covered.iter().filter(|c| !**c).count();
                    lacking.push(format!(
                        "{bare} elements of the {part} in no element set: give the mesh element sets (Gmsh physical volumes, Abaqus ELSET) to assign materials to"
                    ));
                }
            }
            Err(e) => {
                return Err(PipelineError::Input {
                    what: "materials",
                    message: format!("the {part} mesh: {e}"),
                });
            }
        }
    }
    if !lacking.is_empty() {
        return Err(PipelineError::Input {
            what: "materials",
            message: format!(
                "{}: elements without a material (the mesh gives none, nor does the scene):\n  {}",
                scene.path.display(),
                lacking.join("\n  ")
            ),
        });
    }
    Ok(())
}
