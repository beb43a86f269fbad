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
//! chosen as faces (footprints: `circles`, or any rule selecting faces) are each added as a
//! node set of their own, `<name> #k` ([`footprint_names`]), and each keeps its area-weighted
//! mean motion along the normal in the reduction.

use crate::error::{PipelineError, Result};
use crate::model::Log;
use squeal_element::geometry::{dot, unit_or_self as unit};
use squeal_fe::frames::AxisDirection;
use squeal_fe::{ElasticMaterial, FeError, MaterialTable, NodeSelection, Restraint};
use squeal_mesh::Mesh;
use squeal_mesh::select::{self, Face, Rule, Selection, Surface};
use squeal_mesh::units::UnitSystem;
use squeal_reduce::brake::PartInput;
use squeal_reduce::brake::{BrakeInputs, LoadedPart, load_part_of, refuse_shortened_set};
use squeal_reduce::rom::ContactSurface;
use squeal_scene::Scene;
use squeal_scene::sets::Hold;
use squeal_scene::sets::SetRule;

mod inputs;
#[allow(unused_imports)]
use inputs::*;
pub use inputs::{apply_hold, brake_inputs};

mod materials;
#[allow(unused_imports)]
use materials::*;

mod bodies;
pub use bodies::add_bodies;
#[allow(unused_imports)]
use bodies::*;

pub mod left_out;

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
    /// `disc` or the pad's name.
    pub part: String,
    /// The scene key that sets it (`sets.disc.clamp`, `pads.outboard.load`).
    pub key: String,
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
    /// Whether it is a pad's load points (pistons or fingers).
    pub fn is_load(&self) -> bool {
        self.key == PAD_SETS[1].0 || self.key.ends_with(&format!(".{}", PAD_SETS[1].1))
    }

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

/// The parts of a scene, read, converted to SI and with their sets chosen.
#[derive(Debug)]
pub struct SceneParts {
    /// The disc (mesh in SI, with the sets added).
    pub disc: LoadedPart,
    /// The pads with their names (`pad` for a one-pad brake), in the scene's order.
    pub pads: Vec<(String, LoadedPart)>,
    /// The unit system the meshes were read in.
    pub units: UnitSystem,
    /// Disc clamp, then for each pad: the disc contact face under it, its friction face, its
    /// load points (pistons or fingers), its abutments.
    pub sets: Vec<ChosenSet>,
    /// The scene's materials (SI), by element set.
    pub materials: Vec<(String, ElasticMaterial)>,
    /// The sets of `[[supports]]`, `[[ties]]` and `[[springs]]` (keys `supports.<k>.set`,
    /// `ties.<k>.slave`, `ties.<k>.master`, `springs.<k>.set`, `springs.<k>.to`), added to
    /// their parts' meshes.
    pub assembly_sets: Vec<ChosenSet>,
    /// The parts of `[parts.<name>]` (a caliper, a bracket) with their names, in name order.
    pub bodies: Vec<(String, LoadedPart)>,
}

impl SceneParts {
    /// Every part with its name, disc first.
    pub fn all(&self) -> Vec<(&str, &LoadedPart)> {
        std::iter::once(("disc", &self.disc))
            .chain(self.pads.iter().map(|(n, p)| (n.as_str(), p)))
            .collect()
    }

    /// The part named `name`.
    pub fn part(&self, name: &str) -> Option<&LoadedPart> {
        self.all().into_iter().find(|p| p.0 == name).map(|p| p.1)
    }

    /// The chosen set of key `key`.
    pub fn set(&self, key: &str) -> Option<&ChosenSet> {
        self.sets.iter().find(|c| c.key == key)
    }
}

/// What a pad's set is for: the key of a one-pad brake, the key's last part in `[pads]`, and
/// the conventional names looked for in the mesh.
const PAD_SETS: [(&str, &str, &[&str]); 4] = [
    ("sets.pad.friction_face", "friction_face", &["CONTACT_FACE"]),
    ("sets.pad.pistons", "load", &["PISTON", "FINGERS"]),
    ("sets.pad.abutments", "abutments", &["ABUTMENT"]),
    (
        "sets.disc.contact_face",
        "disc_contact_face",
        &["CONTACT_FACE"],
    ),
];

/// The scene key of pad `pad`'s set `k` (0 friction face, 1 load points, 2 abutments, 3 the
/// disc's contact face under it) in a brake with `pads` pads: `sets.pad.friction_face` ... with
/// one pad, `pads.<pad>.friction_face` ... with several.
pub fn pad_key(k: usize, pad: &str, pads: usize) -> String {
    if pads == 1 {
        PAD_SETS[k].0.to_string()
    } else {
        format!("pads.{pad}.{}", PAD_SETS[k].1)
    }
}

/// The footprints of a pad's load set chosen by geometry, one node-set name per piece
/// (`<name> #1`, `<name> #2`, ...), when some piece has more than one node: pistons chosen as
/// faces (`circles`, a plane, a box), each reduced to its area-weighted mean motion along the
/// normal. `None` for a set of the mesh and for pieces of one node each (`points`): those are
/// piston nodes.
pub fn footprint_names(c: &ChosenSet) -> Option<Vec<String>> {
    (c.is_load() && c.by_geometry && c.pieces.iter().any(|p| p.nodes.len() != 1)).then(|| {
        (1..=c.pieces.len())
            .map(|k| format!("{} #{k}", c.name))
            .collect()
    })
}

/// The default distance tolerance of a part: 1e-6 of its largest extent.
fn default_tolerance(mesh: &Mesh) -> f64 {
    mesh.bounding_box().map_or(0.0, |(lo, hi)| {
        1e-6 * (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max)
    })
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
    part: &str,
    key: &str,
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
        part: part.into(),
        key: key.into(),
        name,
        origin: Origin::Scene(given.location.clone()),
        description,
        by_geometry: !named,
        pieces,
    })
}

/// A set from the mesh's own node set `name`.
fn from_mesh(
    part: &str,
    key: &str,
    name: &str,
    mesh: &Mesh,
    boundary: &[Face],
) -> Option<ChosenSet> {
    let rule = Rule::named(name);
    let s = rule.apply(mesh, boundary).ok()?;
    Some(ChosenSet {
        part: part.into(),
        key: key.into(),
        name: name.to_string(),
        origin: Origin::Mesh,
        description: format!("set {name}"),
        by_geometry: false,
        pieces: vec![s],
    })
}

/// A set from a geometric default (faces), named after its key.
fn from_default(part: &str, key: &str, description: String, faces: Vec<Face>) -> Result<ChosenSet> {
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
        part: part.into(),
        key: key.into(),
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
    let mut disc = load_part_of(&scene.disc_mesh(), &scene.disc_elset(), &units)?;
    let mut pads = Vec::new();
    for (name, path) in scene.pad_meshes()? {
        let elset = scene.pad_elset(&name);
        pads.push((name, load_part_of(&path, &elset, &units)?));
    }
    for w in disc
        .warnings
        .iter()
        .chain(pads.iter().flat_map(|p| &p.1.warnings))
    {
        log(&format!("warning: {w}"));
    }
    for w in scene.plausibility_warnings()? {
        log(&format!("warning: {w}"));
    }
    let mut bodies = load_bodies(scene, &units, log)?;
    let sets = {
        let mut meshes: Vec<(&str, &mut Mesh)> = pads
            .iter_mut()
            .map(|(n, p)| (n.as_str(), &mut p.mesh))
            .collect();
        let mut sets = choose_sets(scene, &mut disc.mesh, &mut meshes)?;
        if scene.interface()? == squeal_scene::Interface::Node {
            sets.extend(contact_points_by_geometry(
                scene,
                &sets,
                &mut disc.mesh,
                &mut meshes,
            )?);
        }
        sets
    };
    let assembly_sets = {
        let mut meshes: Vec<(&str, &mut Mesh)> = std::iter::once(("disc", &mut disc.mesh))
            .chain(pads.iter_mut().map(|(n, p)| (n.as_str(), &mut p.mesh)))
            .chain(bodies.iter_mut().map(|(n, p)| (n.as_str(), &mut p.mesh)))
            .collect();
        choose_assembly_sets(scene, &mut meshes)?
    };
    let all: Vec<(&str, &Mesh)> = std::iter::once(("disc", &disc.mesh))
        .chain(pads.iter().map(|(n, p)| (n.as_str(), &p.mesh)))
        .collect();
    check_materials(scene, &materials, &all)?;
    refuse_shortened_sets(&sets, &disc, &pads)?;
    Ok(SceneParts {
        disc,
        pads,
        units,
        sets,
        materials,
        assembly_sets,
        bodies,
    })
}

/// Chooses the sets of the scene's `[[supports]]` and `[[ties]]` on their parts and adds them
/// to the meshes as node sets (a set of the mesh by name is used as is).
fn choose_assembly_sets(scene: &Scene, meshes: &mut [(&str, &mut Mesh)]) -> Result<Vec<ChosenSet>> {
    let mut wanted: Vec<(String, squeal_scene::sets::SetRule)> = Vec::new();
    for s in scene.supports()? {
        wanted.push((s.part, s.set));
    }
    for t in scene.ties()? {
        wanted.push((t.part.clone(), t.slave));
        wanted.push((t.master_part.unwrap_or(t.part), t.master));
    }
    for s in scene.springs()? {
        wanted.push((s.part.clone(), s.set));
        wanted.extend(s.to.map(|to| (s.part, to)));
    }
    for d in scene.dampers()? {
        wanted.push((d.part.clone(), d.set));
        wanted.extend(d.to.map(|to| (d.part, to)));
    }
    for c in scene.connectors()? {
        wanted.push((c.part, c.set));
        wanted.extend(c.to);
    }
    let mut out = Vec::with_capacity(wanted.len());
    for (part, rule) in wanted {
        let Some((_, mesh)) = meshes.iter_mut().find(|m| m.0 == part) else {
            continue;
        };
        let boundary = select::boundary_faces(mesh);
        let c = from_scene(&part, &rule.key.clone(), &rule, mesh, &boundary)?;
        if c.by_geometry && mesh.node_set(&c.name).is_none() {
            mesh.node_sets.insert(c.name.clone(), c.nodes());
        }
        out.push(c);
    }
    Ok(out)
}

/// Refuses a node set of a mesh that the reduction uses (a clamp, contact face, pistons or
/// abutments chosen by name) when the file names in it a node it never defines: checked here,
/// before the cached model's freshness, so that a model reduced from such a set is not
/// called up to date. (A mesh with errors is refused on reading, [`load_part_of`].)
fn refuse_shortened_sets(
    sets: &[ChosenSet],
    disc: &LoadedPart,
    pads: &[(String, LoadedPart)],
) -> Result<()> {
    for c in sets.iter().filter(|c| !c.by_geometry) {
        let part = std::iter::once(("disc", disc))
            .chain(pads.iter().map(|(n, p)| (n.as_str(), p)))
            .find(|p| p.0 == c.part);
        if let Some((_, part)) = part {
            refuse_shortened_set(&part.mesh, &c.name).map_err(|e| PipelineError::MeshFindings {
                path: part.info.path.clone().into(),
                message: format!("{}: {e}", c.key),
            })?;
        }
    }
    Ok(())
}

/// The direction from the disc into the pad that the geometric defaults use: `[contact]
/// normal` when the scene gives one; else the `[rotation]` axis (or z), turned to point from
/// the disc's centroid towards the pad's (the axis' sign is free: the same disc turns
/// clockwise about `a` and counterclockwise about `-a`).
fn default_direction(scene: &Scene, disc: &Mesh, pad: &Mesh, pads: usize) -> Result<[f64; 3]> {
    if let Some(n) = scene.normal()?
        && pads == 1
    {
        return Ok(unit(n));
    }
    // With several pads the normal's line is kept, its sign taken towards each pad.
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

/// Chooses the sets of the scene on the disc and the pads (in SI) and adds those chosen by
/// geometry to the meshes as node sets (see the module docs). Returns them in the order disc
/// clamp, then for each pad the disc contact face under it, its friction face, its load
/// points and its abutments.
pub fn choose_sets(
    scene: &Scene,
    disc: &mut Mesh,
    pads: &mut [(&str, &mut Mesh)],
) -> Result<Vec<ChosenSet>> {
    let rules = scene.set_rules()?;
    // Geometric rules select 6-node triangles and refuse a surface of quadrilaterals
    // (`Rule::apply`); node sets of the mesh are taken whatever their faces.
    let disc_faces = select::boundary_faces(disc);
    let count = pads.len();
    let mut chosen: Vec<ChosenSet> = Vec::with_capacity(1 + 4 * count);
    let mut towards = Vec::with_capacity(count);
    for (_, pad) in pads.iter() {
        towards.push(default_direction(scene, disc, pad, count)?);
    }
    // The clamp: the disc's hub seat is its lowest face along the first pad's direction.
    let key = "sets.disc.clamp";
    chosen.push(if let Some(given) = &rules[0] {
        from_scene("disc", key, given, disc, &disc_faces)?
    } else if let Some(s) = from_mesh("disc", key, "CLAMP", disc, &disc_faces) {
        s
    } else {
        let rule = lowest_face_rule(disc, towards[0]);
        let faces = rule
            .apply(disc, &disc_faces)
            .map_err(|e| set_error(key, "default", e))?;
        from_default("disc", key, rule.to_string(), faces.faces)?
    });
    for (i, (name, pad)) in pads.iter().enumerate() {
        let n = towards[i];
        let pad_faces = select::boundary_faces(pad);
        let given = scene.pad_set_rules(name, i == 0)?;
        let mut mine: Vec<ChosenSet> = Vec::with_capacity(4);
        for (k, (_, _, conventional)) in PAD_SETS.iter().enumerate() {
            let on_disc = k == 3;
            let (mesh, boundary, part): (&Mesh, &[Face], &str) = if on_disc {
                (&*disc, &disc_faces, "disc")
            } else {
                (&**pad, &pad_faces, name)
            };
            // The disc face under a further pad is conventionally CONTACT_FACE_<NAME>.
            let own = format!("CONTACT_FACE_{}", name.to_uppercase());
            let names: Vec<&str> = match (on_disc, i) {
                (true, 0) => conventional.to_vec(),
                (true, _) => vec![own.as_str()],
                (false, _) => conventional.to_vec(),
            };
            let key = match &given[k] {
                Some((key, _)) => key.clone(),
                None => pad_key(k, name, count),
            };
            let set = if let Some((key, rule)) = &given[k] {
                from_scene(part, key, rule, mesh, boundary)?
            } else if let Some(s) = names
                .iter()
                .find_map(|c| from_mesh(part, &key, c, mesh, boundary))
            {
                s
            } else {
                match k {
                    // The pad's friction face is its lowest face along n.
                    0 => {
                        let rule = lowest_face_rule(mesh, n);
                        let faces = rule
                            .apply(mesh, boundary)
                            .map_err(|e| set_error(&key, "default", e))?;
                        from_default(part, &key, rule.to_string(), faces.faces)?
                    }
                    3 => {
                        let friction = mine[0].faces();
                        let faces = projected_faces(mesh, boundary, pad, &friction, n);
                        from_default(
                            part,
                            &key,
                            format!(
                                "faces facing ({:.3}, {:.3}, {:.3}) under the {name}'s friction face",
                                n[0], n[1], n[2]
                            ),
                            faces,
                        )?
                    }
                    _ => {
                        return Err(set_error(
                            &key,
                            &scene.path.display().to_string(),
                            format!(
                                "the {name} mesh has no {} node set and there is no geometric default: give {key} = \"SET\" or a rule, e.g. {key} = {{ facing = [0, 0, 1], points = [[x, y, z], ...] }} (the node nearest each point)",
                                conventional.join(" or ")
                            ),
                        ));
                    }
                }
            };
            mine.push(set);
        }
        // The scene's order: the disc face first.
        mine.rotate_right(1);
        chosen.extend(mine);
    }
    for c in &chosen {
        let mesh: &mut Mesh = if c.part == "disc" {
            &mut *disc
        } else {
            match pads.iter_mut().find(|p| p.0 == c.part) {
                Some(p) => &mut *p.1,
                None => continue,
            }
        };
        if c.origin != Origin::Mesh && mesh.node_set(&c.name).is_none() {
            mesh.node_sets.insert(c.name.clone(), c.nodes());
        }
        for (name, piece) in footprint_names(c)
            .unwrap_or_default()
            .into_iter()
            .zip(&c.pieces)
        {
            mesh.node_sets
                .entry(name)
                .or_insert_with(|| piece.nodes.clone());
        }
    }
    Ok(chosen)
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
