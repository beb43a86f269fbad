//! The scene's parts as the reduction sees them: both meshes read in the scene's `[units]` and
//! converted to SI, the node sets of `[sets]` chosen by name or by geometry, and the
//! materials of `[materials]`.
//!
//! Each set the reduction needs (disc clamp and contact face, pad friction face, pistons and
//! abutments) comes from, in this order: the scene's key; the mesh's conventional set
//! (`CLAMP`, `CONTACT_FACE`, `PISTON`, `ABUTMENT`); a geometric default
//! ([`squeal_scene::sets::SetsSection`] lists them). A set chosen by geometry is added to the
//! mesh as a node set named after its key and rule (`sets.disc.clamp = plane point ...`),
//! so the `.rom` records the rule and a changed rule makes a cached model stale. Pistons
//! chosen by geometry (footprints) are listed but not yet reduced ([`brake_inputs`]).

use crate::error::{PipelineError, Result};
use crate::model::Log;
use squeal_fe::{ElasticMaterial, FeError, MaterialTable, NodeSelection, Restraint};
use squeal_mesh::Mesh;
use squeal_mesh::select::{self, Face, Rule, Selection, Surface};
use squeal_mesh::units::UnitSystem;
use squeal_reduce::brake::{BrakeInputs, LoadedPart, load_part_in};
use squeal_scene::Scene;
use squeal_scene::sets::SetRule;

/// Where a chosen set comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Origin {
    /// The scene's key, at `file:line`.
    Scene(String),
    /// The mesh's own node set of the conventional name.
    Mesh,
    /// The geometric default.
    Default,
}

/// A set the reduction uses, as chosen.
#[derive(Clone, Debug)]
pub struct ChosenSet {
    /// `disc` or `pad`.
    pub part: &'static str,
    /// The scene key that sets it (`sets.disc.clamp`).
    pub key: &'static str,
    /// The node-set name the reduction is given (the mesh's own, or one added for a
    /// geometric choice).
    pub name: String,
    /// Where it comes from.
    pub origin: Origin,
    /// What selects it (a set name or the rules), for listings.
    pub description: String,
    /// Whether geometry chose it (else a node set of the mesh is used as is).
    pub by_geometry: bool,
    /// The selection: one piece, or one per piston.
    pub pieces: Vec<Selection>,
}

impl ChosenSet {
    /// All nodes of its pieces, sorted and unique.
    pub fn nodes(&self) -> Vec<u32> {
        let mut v: Vec<u32> = self.pieces.iter().flat_map(|p| p.nodes.clone()).collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// All faces of its pieces.
    pub fn faces(&self) -> Vec<Face> {
        self.pieces.iter().flat_map(|p| p.faces.clone()).collect()
    }
}

/// Both parts of a scene, read, converted to SI and with their sets chosen.
#[derive(Debug)]
pub struct SceneParts {
    /// The disc (mesh in SI, with the sets added).
    pub disc: LoadedPart,
    /// The pad.
    pub pad: LoadedPart,
    /// The unit system the meshes were read in.
    pub units: UnitSystem,
    /// Disc clamp, disc contact face, pad friction face, pad pistons, pad abutments.
    pub sets: Vec<ChosenSet>,
    /// The scene's materials (SI), by element set.
    pub materials: Vec<(String, ElasticMaterial)>,
}

/// The keys, parts and conventional names of the sets, in [`Scene::set_rules`]'s order.
const SETS: [(&str, &str, &str); 5] = [
    ("disc", "sets.disc.clamp", "CLAMP"),
    ("disc", "sets.disc.contact_face", "CONTACT_FACE"),
    ("pad", "sets.pad.friction_face", "CONTACT_FACE"),
    ("pad", "sets.pad.pistons", "PISTON"),
    ("pad", "sets.pad.abutments", "ABUTMENT"),
];

/// The default distance tolerance of a part: 1e-6 of its largest extent.
fn default_tolerance(mesh: &Mesh) -> f64 {
    mesh.bounding_box().map_or(0.0, |(lo, hi)| {
        1e-6 * (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max)
    })
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|x| x / n)
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The boundary faces facing `-n` (within 1 degree) on the part's lowest plane along `n`.
fn lowest_face_rule(mesh: &Mesh, n: [f64; 3]) -> Rule {
    let used = mesh.used_nodes();
    let lo = mesh
        .nodes
        .iter()
        .zip(&used)
        .filter(|(_, u)| **u)
        .map(|(p, _)| dot(*p, n))
        .fold(f64::INFINITY, f64::min);
    Rule {
        surface: Some(Surface::Plane {
            point: n.map(|x| x * lo),
            normal: n,
        }),
        facing: Some((n.map(|x| -x), 1.0)),
        tolerance: default_tolerance(mesh),
        ..Rule::default()
    }
}

/// The disc's boundary faces facing `n` (within 1 degree) whose corner centroid, projected
/// along `n`, falls inside one of the pad's friction-face triangles (their corners); of
/// those, the ones nearest the pad (the highest along `n`, within the disc's tolerance).
fn projected_faces(
    disc: &Mesh,
    boundary: &[Face],
    pad: &Mesh,
    friction: &[Face],
    n: [f64; 3],
) -> Vec<Face> {
    let Ok(up) = select::faces_facing(disc, boundary, |_| n, 1.0) else {
        return Vec::new();
    };
    // A frame (e1, e2) of the plane normal to n.
    let a = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = unit([
        a[0] - dot(a, n) * n[0],
        a[1] - dot(a, n) * n[1],
        a[2] - dot(a, n) * n[2],
    ]);
    let e2 = [
        n[1] * e1[2] - n[2] * e1[1],
        n[2] * e1[0] - n[0] * e1[2],
        n[0] * e1[1] - n[1] * e1[0],
    ];
    let flat = |p: [f64; 3]| [dot(p, e1), dot(p, e2)];
    let tris: Vec<[[f64; 2]; 3]> = friction
        .iter()
        .map(|f| std::array::from_fn(|i| flat(pad.nodes[f[i] as usize])))
        .collect();
    let inside = |q: [f64; 2]| {
        tris.iter().any(|t| {
            let d = (t[1][0] - t[0][0]) * (t[2][1] - t[0][1])
                - (t[2][0] - t[0][0]) * (t[1][1] - t[0][1]);
            if d == 0.0 {
                return false;
            }
            let l1 = ((q[0] - t[0][0]) * (t[2][1] - t[0][1])
                - (t[2][0] - t[0][0]) * (q[1] - t[0][1]))
                / d;
            let l2 = ((t[1][0] - t[0][0]) * (q[1] - t[0][1])
                - (q[0] - t[0][0]) * (t[1][1] - t[0][1]))
                / d;
            // A centroid on a shared edge of the pad's triangles counts (1e-9 of the area
            // coordinates: round-off of coordinates of the pad's size).
            let eps = 1e-9;
            l1 >= -eps && l2 >= -eps && l1 + l2 <= 1.0 + eps
        })
    };
    let under: Vec<(Face, f64)> = up
        .into_iter()
        .filter_map(|f| {
            let c = select::corner_centroid(disc, &f);
            inside(flat(c)).then_some((f, dot(c, n)))
        })
        .collect();
    let top = under.iter().map(|u| u.1).fold(f64::NEG_INFINITY, f64::max);
    let tol = default_tolerance(disc);
    under
        .into_iter()
        .filter(|u| u.1 >= top - tol)
        .map(|u| u.0)
        .collect()
}

fn describe_rules(rules: &[Rule]) -> String {
    rules
        .iter()
        .map(Rule::to_string)
        .collect::<Vec<_>>()
        .join(" | ")
}

/// The error of a set that cannot be chosen.
fn set_error(key: &str, at: &str, message: impl std::fmt::Display) -> PipelineError {
    PipelineError::Input {
        what: "scene sets",
        message: format!("{at}: {key}: {message}"),
    }
}

/// Applies the scene's rules for one key on `mesh`.
fn from_scene(
    part: &'static str,
    key: &'static str,
    given: &SetRule,
    mesh: &Mesh,
    boundary: &[Face],
) -> Result<ChosenSet> {
    let tolerance = default_tolerance(mesh);
    let mut pieces = Vec::new();
    let mut rules = Vec::new();
    for r in &given.rules {
        let mut r = r.clone();
        if !given.tolerance_given {
            r.tolerance = tolerance;
        }
        let s = r
            .apply(mesh, boundary)
            .map_err(|e| set_error(key, &given.location, format!("on the {part} mesh: {e}")))?;
        if s.nodes.is_empty() {
            return Err(set_error(
                key,
                &given.location,
                format!("selects nothing on the {part} mesh ({r})"),
            ));
        }
        pieces.push(s);
        rules.push(r);
    }
    let description = describe_rules(&rules);
    let named = rules.len() == 1 && !rules[0].is_geometric();
    let name = match (&rules[0].set, named) {
        (Some(s), true) => s.clone(),
        _ => format!("{key} = {description}"),
    };
    Ok(ChosenSet {
        part,
        key,
        name,
        origin: Origin::Scene(given.location.clone()),
        description,
        by_geometry: !named,
        pieces,
    })
}

/// A set from the mesh's own node set `name`.
fn from_mesh(
    part: &'static str,
    key: &'static str,
    name: &str,
    mesh: &Mesh,
    boundary: &[Face],
) -> Option<ChosenSet> {
    let rule = Rule::named(name);
    let s = rule.apply(mesh, boundary).ok()?;
    Some(ChosenSet {
        part,
        key,
        name: name.to_string(),
        origin: Origin::Mesh,
        description: format!("set {name}"),
        by_geometry: false,
        pieces: vec![s],
    })
}

/// A set from a geometric default (faces), named after its key.
fn from_default(
    part: &'static str,
    key: &'static str,
    description: String,
    faces: Vec<Face>,
) -> Result<ChosenSet> {
    if faces.is_empty() {
        return Err(set_error(
            key,
            "default",
            format!(
                "the {part} mesh has no conventional set for it and the default ({description}) selects nothing: give {key} in the scene"
            ),
        ));
    }
    Ok(ChosenSet {
        part,
        key,
        name: format!("{key} = {description}"),
        origin: Origin::Default,
        description,
        by_geometry: true,
        pieces: vec![Selection {
            nodes: select::face_nodes(&faces),
            faces,
        }],
    })
}

/// Reads the scene's meshes in its units and chooses their sets (see the module docs). The
/// readers' and the unit checks' warnings go to `log`.
pub fn load_parts(scene: &Scene, log: Log) -> Result<SceneParts> {
    let units = scene.units()?;
    let materials = scene.materials()?;
    for w in scene.material_warnings()? {
        log(&format!("warning: {w}"));
    }
    let m = &scene.file.model;
    let mut disc = load_part_in(&scene.resolve(&m.disc), &units)?;
    let mut pad = load_part_in(&scene.resolve(&m.pad), &units)?;
    for w in disc.warnings.iter().chain(&pad.warnings) {
        log(&format!("warning: {w}"));
    }
    let sets = choose_sets(scene, &mut disc.mesh, &mut pad.mesh)?;
    check_materials(
        scene,
        &materials,
        &[("disc", &disc.mesh), ("pad", &pad.mesh)],
    )?;
    Ok(SceneParts {
        disc,
        pad,
        units,
        sets,
        materials,
    })
}

/// The direction from the disc into the pad that the geometric defaults use: `[contact]
/// normal` when the scene gives one; else the `[rotation]` axis (or z), turned to point from
/// the disc's centroid towards the pad's (the axis' sign is free: the same disc turns
/// clockwise about `a` and counterclockwise about `-a`).
fn default_direction(scene: &Scene, disc: &Mesh, pad: &Mesh) -> Result<[f64; 3]> {
    if let Some(n) = scene.normal()? {
        return Ok(unit(n));
    }
    let a = unit(scene.contact_direction()?);
    let centroid = |m: &Mesh| {
        let k = m.nodes.len().max(1) as f64;
        m.nodes.iter().fold([0.0; 3], |c, x| {
            [c[0] + x[0] / k, c[1] + x[1] / k, c[2] + x[2] / k]
        })
    };
    let (cd, cp) = (centroid(disc), centroid(pad));
    let side: f64 = (0..3).map(|i| a[i] * (cp[i] - cd[i])).sum();
    Ok(if side < 0.0 { a.map(|x| -x) } else { a })
}

/// Chooses the sets of the scene on both meshes (in SI) and adds those chosen by geometry to
/// the meshes as node sets (see the module docs). Returns them in the order disc clamp, disc
/// contact face, pad friction face, pad pistons, pad abutments.
pub fn choose_sets(scene: &Scene, disc: &mut Mesh, pad: &mut Mesh) -> Result<Vec<ChosenSet>> {
    let rules = scene.set_rules()?;
    let n = default_direction(scene, disc, pad)?;
    let disc_faces = select::boundary_faces(disc);
    let pad_faces = select::boundary_faces(pad);
    let mut chosen: Vec<ChosenSet> = Vec::with_capacity(5);
    // Pad first: the disc's default contact face is the pad's friction face projected.
    for k in [2, 3, 4, 0, 1] {
        let (part, key, conventional) = SETS[k];
        let (mesh, boundary) = if part == "disc" {
            (&*disc, &disc_faces)
        } else {
            (&*pad, &pad_faces)
        };
        let set = if let Some(given) = &rules[k] {
            from_scene(part, key, given, mesh, boundary)?
        } else if let Some(s) = from_mesh(part, key, conventional, mesh, boundary) {
            s
        } else {
            match k {
                0 | 2 => {
                    // Both face away from the pad side: the disc's hub seat and the pad's
                    // friction face are each part's lowest faces along n.
                    let rule = lowest_face_rule(mesh, n);
                    let faces = rule
                        .apply(mesh, boundary)
                        .map_err(|e| set_error(key, "default", e))?;
                    from_default(part, key, rule.to_string(), faces.faces)?
                }
                1 => {
                    let friction = chosen
                        .iter()
                        .find(|c| c.key == "sets.pad.friction_face")
                        .map(ChosenSet::faces)
                        .unwrap_or_default();
                    let faces = projected_faces(mesh, boundary, pad, &friction, n);
                    from_default(
                        part,
                        key,
                        format!("faces facing {n:?} under the pad's friction face"),
                        faces,
                    )?
                }
                _ => {
                    return Err(set_error(
                        key,
                        &scene.path.display().to_string(),
                        format!(
                            "the pad mesh has no {conventional} node set and there is no geometric default: give {key} = \"SET\" or a rule, e.g. {key} = {{ facing = [0, 0, 1], circles = [{{ centre = [x, y, z], diameter = d }}] }}"
                        ),
                    ));
                }
            }
        };
        chosen.push(set);
    }
    // Back to the scene's order.
    chosen.sort_by_key(|c| SETS.iter().position(|s| s.1 == c.key));
    for c in &chosen {
        let mesh = if c.part == "disc" {
            &mut *disc
        } else {
            &mut *pad
        };
        if c.origin != Origin::Mesh && mesh.node_set(&c.name).is_none() {
            mesh.node_sets.insert(c.name.clone(), c.nodes());
        }
    }
    Ok(chosen)
}

/// Every `[materials]` set exists in a part, and every element of both parts has a
/// material: otherwise an error listing the element sets still without one and the key
/// that would give it.
fn check_materials(
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

/// The scene's materials whose element set `mesh` has.
fn overrides_for(
    materials: &[(String, ElasticMaterial)],
    mesh: &Mesh,
) -> Vec<(String, ElasticMaterial)> {
    materials
        .iter()
        .filter(|(s, _)| mesh.element_set(s).is_some())
        .cloned()
        .collect()
}

/// The reduction inputs of a scene on its parts: the bundled layout (disc clamped, pad held
/// in plane on its abutments with the pistons' normal dof kept) with the chosen sets, the
/// scene's materials and units, interface and mode count.
///
/// Pistons chosen by geometry (footprints such as `circles`) are refused here: the reduction
/// keeps one normal dof per piston node and eliminates it, which is what holds the pad along
/// the normal while its interior is factored. A footprint's load spread by area would be a
/// mean-motion row (as a contact patch is), a constraint rather than an eliminated dof, and
/// with only those the pad's interior stiffness is singular (measured: "the pad is not
/// held" with two 40 mm footprints on the coarse pad). `squeal mesh info --scene` lists and
/// draws them; the reduction needs a node set of piston points.
pub fn brake_inputs(scene: &Scene, parts: &SceneParts) -> Result<BrakeInputs> {
    if let Some(p) = parts
        .sets
        .iter()
        .find(|c| c.key == "sets.pad.pistons" && c.by_geometry)
    {
        return Err(set_error(
            p.key,
            match &p.origin {
                Origin::Scene(at) => at,
                _ => "scene",
            },
            "pistons chosen by geometry (footprints) are listed and drawn by `squeal mesh info --scene`, but the reduction does not take them yet: it needs a node set of piston points (one normal dof each), e.g. pistons = \"PISTON\"",
        ));
    }
    let mut inputs = crate::model::brake_inputs(scene)?;
    let name = |key: &str| {
        parts
            .sets
            .iter()
            .find(|c| c.key == key)
            .map(|c| c.name.clone())
            .unwrap_or_default()
    };
    inputs.disc.restraints = vec![Restraint::clamp(&name("sets.disc.clamp"))];
    inputs.disc.contact_face_set = name("sets.disc.contact_face");
    inputs.pad.contact_face_set = name("sets.pad.friction_face");
    inputs.pad.piston_set = Some(name("sets.pad.pistons"));
    // The abutments stay held as `model::brake_inputs` holds `ABUTMENT`: in the plane normal
    // to the disc's axis (in skew node axes when the axis is skew), now on the chosen nodes.
    let abutments = name("sets.pad.abutments");
    for r in &mut inputs.pad.restraints {
        if r.nodes == NodeSelection::Set("ABUTMENT".into()) {
            r.nodes = NodeSelection::Set(abutments.clone());
        }
    }
    for (set, _) in &mut inputs.pad.skew_restraints {
        if set == "ABUTMENT" {
            set.clone_from(&abutments);
        }
    }
    inputs.disc.material_overrides = overrides_for(&parts.materials, &parts.disc.mesh);
    inputs.pad.material_overrides = overrides_for(&parts.materials, &parts.pad.mesh);
    inputs.grid = scene.patch_grid()?;
    inputs.disc.units = parts.units;
    inputs.pad.units = parts.units;
    Ok(inputs)
}
