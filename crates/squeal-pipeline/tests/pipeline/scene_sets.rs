//! The scene's `[sets]`, `[units]` and `[materials]` on the bundled coarse meshes: sets chosen
//! by geometry are the named sets, a Gmsh `.msh` with its materials from the scene reduces as
//! the `.inp` does, a millimetre scene reduces as the SI one, and what is missing or makes no
//! sense is an error naming the key.

use squeal_mesh::Mesh;
use squeal_pipeline::model::{build, quiet, reduced_model};
use squeal_pipeline::parts::{Origin, choose_sets, load_parts};
use squeal_reduce::interface::{Axis, patches};
use squeal_reduce::rom::{PointRole, ReducedModel};
use squeal_scene::Scene;
use std::path::{Path, PathBuf};

fn meshes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes")
}

/// `meshes/brake.toml` with the given meshes, `modes` fixed-interface modes and `extra`
/// appended, read as if it were `<dir>/scene.toml`.
fn scene_in(dir: &Path, disc: &str, pad: &str, modes: usize, extra: &str) -> Result<Scene, String> {
    let text = std::fs::read_to_string(meshes().join("brake.toml")).unwrap();
    let text: String = text
        .lines()
        .map(|l| {
            if l.starts_with("disc = ") {
                format!("disc = \"{disc}\"\n")
            } else if l.starts_with("pad = ") {
                format!("pad = \"{pad}\"\n")
            } else if l.starts_with("modes = ") {
                format!("modes = {modes}\n")
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    Scene::parse(&dir.join("scene.toml"), format!("{text}\n{extra}\n")).map_err(|e| e.to_string())
}

fn read(name: &str) -> Mesh {
    squeal_mesh::read(&meshes().join(name)).unwrap().mesh
}

/// The abutments of the bundled pad as geometry: the backplate's (z = 30..35 mm) end faces,
/// the planes through the z axis at 65 and 115 degrees.
fn abutment_rule() -> String {
    let plane = |deg: f64| {
        let t = deg.to_radians();
        format!(
            "{{ plane = {{ point = [0, 0, 0], normal = [{}, {}, 0] }}, box = {{ min = [-1, -1, 0.0299999], max = [1, 1, 0.0350001] }} }}",
            -t.sin(),
            t.cos()
        )
    };
    format!("abutments = [{}, {}]", plane(65.0), plane(115.0))
}

#[test]
fn sets_chosen_by_geometry_are_the_named_sets_of_the_bundled_meshes() {
    // The coarse meshes, and the medium ones whose disc and pad differ inside the footprint
    // (618 and 652 face nodes): the disc's default contact face is found under the pad's
    // friction face without shared nodes.
    for level in ["coarse", "medium"] {
        named_sets_by_geometry(level);
    }
}

fn named_sets_by_geometry(level: &str) {
    let disc0 = read(&format!("disc_{level}.inp"));
    let pad0 = read(&format!("pad_{level}.inp"));
    let rules = format!(
        "[sets.disc]\nclamp = {{ plane = {{ point = [0, 0, -0.035], normal = [0, 0, 1] }}, facing = [0, 0, -1] }}\n\
         [sets.pad]\nfriction_face = {{ plane = {{ point = [0, 0, 0.02], normal = [0, 0, 1] }}, facing = [0, 0, -1], angle = 0.5 }}\n{}",
        abutment_rule()
    );
    // Explicit rules on the meshes as they are (their named sets present but not used), then
    // the defaults on meshes stripped of every node set but PISTON (no default for it).
    let explicit = scene_in(&meshes(), "disc_coarse.inp", "pad_coarse.inp", 8, &rules).unwrap();
    let defaults = scene_in(
        &meshes(),
        "disc_coarse.inp",
        "pad_coarse.inp",
        8,
        &format!("[sets.pad]\n{}", abutment_rule()),
    )
    .unwrap();
    for (scene, strip) in [(&explicit, false), (&defaults, true)] {
        let (mut disc, mut pad) = (disc0.clone(), pad0.clone());
        if strip {
            disc.node_sets.clear();
            pad.node_sets.retain(|k, _| k == "PISTON");
        }
        let chosen = choose_sets(scene, &mut disc, &mut [("pad", &mut pad)]).unwrap();
        let named = [
            (&disc0, "CLAMP"),
            (&disc0, "CONTACT_FACE"),
            (&pad0, "CONTACT_FACE"),
            (&pad0, "PISTON"),
            (&pad0, "ABUTMENT"),
        ];
        for (c, (mesh, name)) in chosen.iter().zip(named) {
            // PISTON is always the mesh's, and so is the disc's contact face when the mesh
            // keeps it (the explicit scene gives no rule for it); every other set comes from a
            // rule or a default.
            let from_mesh = c.origin == Origin::Mesh;
            let expected = name == "PISTON" || (!strip && c.key == "sets.disc.contact_face");
            assert_eq!(from_mesh, expected, "{}: {:?}", c.key, c.origin);
            assert_eq!(
                c.nodes(),
                mesh.node_set(name).unwrap(),
                "{} vs {name}",
                c.key
            );
        }
        // The patches of the chosen faces are the named faces' patches, to the bit: the same
        // nodes give the same triangles in the same order (asserted to 1e-12 relative, well
        // inside the 1e-9).
        for (mesh, named_mesh, chosen_set) in
            [(&disc, &disc0, &chosen[1]), (&pad, &pad0, &chosen[2])]
        {
            let a = patches(mesh, &chosen_set.name, 3, 3, &Axis::default()).unwrap();
            let b = patches(named_mesh, "CONTACT_FACE", 3, 3, &Axis::default()).unwrap();
            for (p, q) in a.iter().zip(&b) {
                assert!(
                    (p.area / q.area - 1.0).abs() < 1e-12,
                    "{} {}",
                    p.area,
                    q.area
                );
                for d in 0..3 {
                    assert!((p.centroid[d] - q.centroid[d]).abs() < 1e-12 * 0.14);
                }
            }
            assert_eq!(a.len(), 9);
        }
    }
}

/// The coarse meshes, with `modes` modes, reduced in a fresh folder.
fn reduce(scene: &Scene, tag: &str) -> ReducedModel {
    let out = std::env::temp_dir().join(format!("squeal-scene-sets-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).unwrap();
    let (rom, _) = reduced_model(scene, &out, &quiet).unwrap();
    let _ = std::fs::remove_dir_all(&out);
    rom
}

/// Largest relative difference of the parts' fixed-interface frequencies and reduced
/// matrices (relative to each matrix's largest entry). A fixed-interface mode's sign is
/// arbitrary (the eigensolver's start vector decides it), and it flips the sign of its row and
/// column of the coupling block of `M̂`: entries are compared in magnitude.
fn difference(a: &ReducedModel, b: &ReducedModel) -> f64 {
    let mut worst: f64 = 0.0;
    for (p, q) in a.parts.iter().zip(&b.parts) {
        for (f, g) in p
            .info
            .fixed_interface_hz
            .iter()
            .zip(&q.info.fixed_interface_hz)
        {
            worst = worst.max((f / g - 1.0).abs());
        }
        for (x, y) in [(&p.k, &q.k), (&p.m, &q.m)] {
            assert_eq!((x.nrows(), x.ncols()), (y.nrows(), y.ncols()));
            let mut scale: f64 = 0.0;
            let mut diff: f64 = 0.0;
            for j in 0..x.ncols() {
                for i in 0..x.nrows() {
                    scale = scale.max(x[(i, j)].abs());
                    diff = diff.max((x[(i, j)].abs() - y[(i, j)].abs()).abs());
                }
            }
            worst = worst.max(diff / scale);
        }
    }
    worst
}

const MATERIALS: &str = "[materials.DISC]\nyoung = 125e9\npoisson = 0.26\ndensity = 7200\n\
[materials.LINING]\nyoung = 2e9\npoisson = 0.25\ndensity = 2500\n\
[materials.BACKPLATE]\nyoung = 210e9\npoisson = 0.3\ndensity = 7850\n";

/// Writes `meshes/<name>` scaled to mm-t-s (coordinates x 1e3, moduli x 1e-6, densities x
/// 1e-12) into `dir`.
fn to_millimetres(name: &str, dir: &Path) {
    let text = std::fs::read_to_string(meshes().join(name)).unwrap();
    let mut out = String::new();
    let mut block = "";
    for line in text.lines() {
        if line.starts_with('*') {
            block = if line.starts_with("*NODE") {
                "node"
            } else if line.starts_with("*ELASTIC") {
                "elastic"
            } else if line.starts_with("*DENSITY") {
                "density"
            } else {
                ""
            };
            out += line;
            out += "\n";
            continue;
        }
        let v: Vec<&str> = line.split(',').map(str::trim).collect();
        let num = |s: &str| s.parse::<f64>().unwrap();
        let scaled = match block {
            "node" => format!(
                "{}, {}, {}, {}",
                v[0],
                num(v[1]) * 1e3,
                num(v[2]) * 1e3,
                num(v[3]) * 1e3
            ),
            "elastic" => format!("{}, {}", num(v[0]) * 1e-6, v[1]),
            "density" => format!("{}", num(v[0]) * 1e-12),
            _ => line.to_string(),
        };
        out += &scaled;
        out += "\n";
    }
    std::fs::write(dir.join(name), out).unwrap();
}

#[test]
fn a_msh_with_scene_materials_and_a_millimetre_scene_reduce_as_the_si_inp() {
    let si = scene_in(&meshes(), "disc_coarse.inp", "pad_coarse.inp", 8, "").unwrap();
    let reference = reduce(&si, "inp");
    // The .msh: the same nodes (ids and coordinates to the bit) and elements, no materials;
    // the scene gives the .inp's. Assembly and reduction see the same numbers: measured 0
    // difference; asserted 1e-12 relative (an element order differing between the files
    // would move sums by round-off only).
    let msh = scene_in(&meshes(), "disc_coarse.msh", "pad_coarse.msh", 8, MATERIALS).unwrap();
    let d = difference(&reference, &reduce(&msh, "msh"));
    eprintln!("msh vs inp: largest relative difference {d:e}");
    assert!(d < 1e-12, "msh vs inp: {d:e}");
    // Sets by geometry reach the reduction: the same nodes as the named sets, so the same
    // model (measured 0 difference, asserted 1e-12), and the .rom records each rule in its
    // set's name, so that another rule makes a kept model stale.
    let rules = format!(
        "[sets.disc]\nclamp = {{ plane = {{ point = [0, 0, -0.035], normal = [0, 0, 1] }}, facing = [0, 0, -1] }}\n\
         [sets.pad]\nfriction_face = {{ facing = [0, 0, -1], angle = 0.5 }}\n{}",
        abutment_rule()
    );
    let geometric = scene_in(&meshes(), "disc_coarse.inp", "pad_coarse.inp", 8, &rules).unwrap();
    let by_rules = reduce(&geometric, "rules");
    let d = difference(&reference, &by_rules);
    eprintln!("sets by geometry vs named: largest relative difference {d:e}");
    assert!(d < 1e-12, "rules vs named: {d:e}");
    let build = by_rules.part("disc").unwrap().info.build.clone().unwrap();
    assert!(
        build.restraints[0]
            .0
            .starts_with("sets.disc.clamp = plane point [0, 0, -0.035]"),
        "{:?}",
        build.restraints
    );
    let pad_build = by_rules.part("pad").unwrap().info.build.clone().unwrap();
    assert!(
        pad_build
            .contact_face_set
            .starts_with("sets.pad.friction_face = facing [0, 0, -1] within 0.5 deg")
    );
    // Without the materials the .msh is refused, with every element set and its key.
    let bare = scene_in(&meshes(), "disc_coarse.msh", "pad_coarse.msh", 8, "").unwrap();
    let e = load_parts(&bare, &quiet).unwrap_err().to_string();
    for key in [
        "[materials.DISC]",
        "[materials.LINING]",
        "[materials.BACKPLATE]",
    ] {
        assert!(e.contains(key), "{e}");
    }
    // mm-t-s: coordinates x 1e3, moduli x 1e-6, densities x 1e-12, converted back on reading;
    // each value is off by one rounding in each direction, so the model agrees to round-off
    // amplified by the eigen-solves: measured 2.5e-13, asserted 1e-9 relative.
    let dir = std::env::temp_dir().join(format!("squeal-scene-mm-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    to_millimetres("disc_coarse.inp", &dir);
    to_millimetres("pad_coarse.inp", &dir);
    let mm = scene_in(
        &dir,
        "disc_coarse.inp",
        "pad_coarse.inp",
        8,
        "[units]\nsystem = \"mm-t-s\"",
    )
    .unwrap();
    let d = difference(&reference, &reduce(&mm, "mm"));
    eprintln!("mm-t-s vs SI: largest relative difference {d:e}");
    assert!(d < 1e-9, "mm vs SI: {d:e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn scene_keys_without_a_unit_in_their_name_are_in_the_scene_units() {
    let mm = scene_in(
        &meshes(),
        "disc_coarse.inp",
        "pad_coarse.inp",
        8,
        "[units]\nsystem = \"mm-t-s-N-MPa\"",
    )
    .unwrap();
    let si = scene_in(&meshes(), "disc_coarse.inp", "pad_coarse.inp", 8, "").unwrap();
    // The same numbers read as mm: lengths 1e-3, areas 1e-6 of SI's; the compression curve
    // (MPa, um) and the line pressure (bar) keep their units. Exact up to one rounding.
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    assert!(
        rel(
            mm.pairing_tolerance().unwrap(),
            1e-3 * si.pairing_tolerance().unwrap()
        ) < 1e-15
    );
    assert!(
        rel(
            mm.piston_force().unwrap(),
            1e-6 * si.piston_force().unwrap()
        ) < 1e-15
    );
    assert!(rel(mm.stiffness().unwrap().0, si.stiffness().unwrap().0) < 1e-15);
    // A steel in mm-t-s numbers read as SI is flagged, naming the system it fits.
    let steel = "[materials.DISC]\nyoung = 2.1e5\npoisson = 0.3\ndensity = 7.85e-9";
    let w = scene_in(&meshes(), "disc_coarse.inp", "pad_coarse.inp", 8, steel)
        .unwrap()
        .material_warnings()
        .unwrap();
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(w.iter().all(|m| m.contains("mm-t-s")), "{w:?}");
}

#[test]
fn rules_and_materials_that_make_no_sense_are_errors_naming_key_and_line() {
    let m = meshes();
    let bad =
        |extra: &str| scene_in(&m, "disc_coarse.inp", "pad_coarse.inp", 8, extra).unwrap_err();
    // The scene's text has brake.toml's lines, then a blank line, then `extra`: its second
    // line is line n + 3 of the whole.
    let n = std::fs::read_to_string(m.join("brake.toml"))
        .unwrap()
        .lines()
        .count();
    let e = bad(
        "[sets.disc]\nclamp = { cylinder = { point = [0, 0, 0], axis = [0, 0, 1], radius = -1 } }",
    );
    assert!(
        e.contains(&format!("scene.toml:{}: sets.disc.clamp", n + 3)) && e.contains("radius -1"),
        "{e}"
    );
    let e = bad("[sets.pad]\nfriction_face = { facing = [0, 0, 0] }");
    assert!(
        e.contains("sets.pad.friction_face") && e.contains("zero length"),
        "{e}"
    );
    let e = bad("[sets.pad]\nfriction_face = { sphere = 1 }");
    assert!(e.contains("unknown criterion 'sphere'"), "{e}");
    let e = bad("[sets.pad]\nabutments = { angle = 3 }");
    assert!(e.contains("angle goes with facing"), "{e}");
    let e = bad("[units]\nsystem = \"furlong\"");
    assert!(e.contains("units.system") && e.contains("mm-t-s"), "{e}");
    let e = bad("[materials.DISC]\nyoung = 125e9\npoisson = 0.6\ndensity = 7200");
    assert!(
        e.contains("materials.DISC") && e.contains("positive definite"),
        "{e}"
    );
    let e = bad("[materials.LINING]\nyoung_plane = 5e9\npoisson_plane = 0.2\ndensity = 2500");
    assert!(e.contains("needs young_axial"), "{e}");
    // A set name the mesh lacks, a rule that selects nothing, a material for no element set:
    // errors once the meshes are read.
    let later = |extra: &str| {
        let s = scene_in(&m, "disc_coarse.inp", "pad_coarse.inp", 8, extra).unwrap();
        load_parts(&s, &quiet).unwrap_err().to_string()
    };
    let e = later("[sets.disc]\nclamp = \"HUB\"");
    assert!(
        e.contains("sets.disc.clamp") && e.contains("no node set HUB"),
        "{e}"
    );
    let e = later("[sets.disc]\nclamp = { plane = { point = [0, 0, -1], normal = [0, 0, 1] } }");
    assert!(e.contains("selects nothing"), "{e}");
    // A pad without PISTON and no pistons key: no default, the key to add.
    let mut disc = read("disc_coarse.inp");
    let mut pad = read("pad_coarse.inp");
    pad.node_sets.retain(|k, _| k != "PISTON");
    let s = scene_in(&m, "disc_coarse.inp", "pad_coarse.inp", 8, "").unwrap();
    let e = choose_sets(&s, &mut disc, &mut [("pad", &mut pad)])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("sets.pad.pistons") && e.contains("no PISTON or FINGERS node set"),
        "{e}"
    );
    let e = later("[materials.ROTOR]\nyoung = 125e9\npoisson = 0.26\ndensity = 7200");
    assert!(
        e.contains("[materials.ROTOR]") && e.contains("DISC (disc)"),
        "{e}"
    );
}

#[test]
fn pistons_as_circles_reduce_to_one_footprint_coordinate_each() {
    // The bundled pistons' centres (r = 110 mm at 77.5 and 102.5 deg, on the back face
    // z = 35 mm), 40 mm diameter, on the coarse brake with 50 modes per part: the brake of
    // the pinned results (tests/cli/regression.rs) with its four PISTON nodes replaced by two
    // footprints.
    let (x, y) = (
        0.11 * 77.5f64.to_radians().cos(),
        0.11 * 77.5f64.to_radians().sin(),
    );
    let circles = format!(
        "[sets.pad]\npistons = {{ facing = [0, 0, 1], circles = [{{ centre = [{x}, {y}, 0.035], diameter = 0.04 }}, {{ centre = [{}, {y}, 0.035], diameter = 0.04 }}] }}",
        -x
    );
    let s = scene_in(&meshes(), "disc_coarse.inp", "pad_coarse.inp", 50, &circles).unwrap();
    let parts = load_parts(&s, &quiet).unwrap();
    let pistons = &parts.sets[3];
    assert_eq!(pistons.pieces.len(), 2);
    let disc_area = std::f64::consts::PI * 0.02 * 0.02;
    for (k, piece) in pistons.pieces.iter().enumerate() {
        let sum = squeal_mesh::select::summarize(&parts.pads[0].1.mesh, &piece.faces);
        // Faces whose corner centroid lies in the circle cover it to about a row of the
        // coarse pad's 13 mm faces: asserted within 50 % of pi d^2 / 4; the centroid lies on
        // the back face and within a face size (13 mm) of the circle's centre.
        assert!(
            (sum.area / disc_area - 1.0).abs() < 0.5,
            "{} vs {disc_area}",
            sum.area
        );
        assert!(
            (sum.centroid[2] - 0.035).abs() < 1e-12,
            "{:?}",
            sum.centroid
        );
        let cx = if k == 0 { x } else { -x };
        assert!(
            (sum.centroid[0] - cx).hypot(sum.centroid[1] - y) < 0.013,
            "{:?}",
            sum.centroid
        );
    }
    let inputs = squeal_pipeline::parts::brake_inputs(&s, &parts).unwrap();
    let feet = &inputs.pads[0].part.piston_footprints;
    assert_eq!(feet.len(), 2);
    assert!(
        feet[0].ends_with(" #1") && feet[1].ends_with(" #2"),
        "{feet:?}"
    );

    let out = std::env::temp_dir().join(format!("squeal-scene-sets-feet-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let model = build(&s, &out, &quiet).unwrap();
    let _ = std::fs::remove_dir_all(&out);
    // The pad keeps 27 contact coordinates, one per footprint, and its 50 modes.
    let pad = &model.rom.parts[1];
    assert_eq!(pad.size(), 27 + 2 + 50);
    let feet: Vec<_> = pad
        .info
        .points
        .iter()
        .filter(|p| p.role == PointRole::Piston)
        .collect();
    assert_eq!(feet.len(), 2);
    for p in &feet {
        let area = p.area.unwrap();
        println!("footprint at {:?}: area {area:.4e} m²", p.position);
        assert_eq!(p.node_id, None);
        assert!((area / disc_area - 1.0).abs() < 0.5, "{area}");
    }
    let st = squeal_pipeline::stability::analyse(&model, &s.mu_values().unwrap()).unwrap();
    let h = st.sweep.hopf.unwrap();
    let forces = &st.reference.equilibrium.normal_forces;
    println!(
        "footprints: mu0 = {:.10} at {:.6} Hz (4 PISTON nodes: 0.46182266 at 4061.48 Hz); contact forces {forces:.1?} N",
        h.mu0, h.frequency_hz
    );
    // The clamp force reaches the contact whole: the 9 pairs carry the scene's 1.194e6 Pa on
    // 2.513e-3 m², 3000.5 N (measured 3000.5 N), to the equilibrium's tolerance.
    let total: f64 = forces.iter().sum();
    assert!((total / (11.94e5 * 2.513e-3) - 1.0).abs() < 1e-6, "{total}");
    // Measured 0.44460108 at 4042.88 Hz: 3.7 % below the PISTON brake's μ0 and 18.6 Hz lower.
    // The reduction is not what moves it (footprints_and_piston_nodes_agree_with_linear_contact):
    // the preload is spread differently, two 40 mm pressures centred near r = 110 mm instead
    // of four point loads at r = 90 and 130 mm (the footprints' edges), so the pairs' static
    // forces, and with the cubic contact law their tangent stiffnesses, differ (middle row
    // 307/297/307 N with the nodes, 366/364/346 N here; outer 309/303/309 and 277/268/261 N).
    // Asserted to the sweep's 1e-8 bracket on μ0 (1e-7: the footprint rows' round-off) and
    // 1e-6 of the frequency.
    assert!((h.mu0 - 0.444_601_08).abs() < 1e-7, "{}", h.mu0);
    assert!(
        (h.frequency_hz / 4_042.875_558 - 1.0).abs() < 1e-6,
        "{}",
        h.frequency_hz
    );

    // Pistons as pieces with several nodes but no face cannot spread a load: refused.
    let sets = "[sets.pad]\npistons = [{ set = \"PISTON\" }, { set = \"PISTON\" }]";
    let s = scene_in(&meshes(), "disc_coarse.inp", "pad_coarse.inp", 8, sets).unwrap();
    let parts = load_parts(&s, &quiet).unwrap();
    let e = squeal_pipeline::parts::brake_inputs(&s, &parts)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("no boundary face") && e.contains("sets.pad.pistons"),
        "{e}"
    );
}

#[test]
fn footprints_and_piston_nodes_agree_with_linear_contact() {
    // With a linear contact law (k_nl = 0) the static preload does not enter the linearized
    // brake (every pair stays closed), so two brakes that differ only by how the pad's load
    // enters differ only by their reduction bases: the same physics (the pistons carry no
    // stiffness), the pad's constraint modes for 4 nodes or for 2 footprints.
    let (x, y) = (
        0.11 * 77.5f64.to_radians().cos(),
        0.11 * 77.5f64.to_radians().sin(),
    );
    let circles = format!(
        "[sets.pad]\npistons = {{ facing = [0, 0, 1], circles = [{{ centre = [{x}, {y}, 0.035], diameter = 0.04 }}, {{ centre = [{}, {y}, 0.035], diameter = 0.04 }}] }}",
        -x
    );
    let mut hopf = Vec::new();
    for (tag, extra) in [("nodes", String::new()), ("feet", circles)] {
        let s = scene_in(&meshes(), "disc_coarse.inp", "pad_coarse.inp", 50, &extra).unwrap();
        let text = s.text.replace(
            "compression_curve = ",
            "k_linear_per_area = 1.25e10\nk_cubic_per_area = 0.0\n# compression_curve = ",
        );
        let s = Scene::parse(&s.path, text).unwrap();
        let out = std::env::temp_dir().join(format!(
            "squeal-scene-sets-linear-{tag}-{}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&out);
        let model = build(&s, &out, &quiet).unwrap();
        let _ = std::fs::remove_dir_all(&out);
        let st = squeal_pipeline::stability::analyse(&model, &s.mu_values().unwrap()).unwrap();
        let h = st.sweep.hopf.unwrap();
        println!(
            "linear contact, {tag}: mu0 = {:.8} at {:.2} Hz",
            h.mu0, h.frequency_hz
        );
        hopf.push((h.mu0, h.frequency_hz));
    }
    // Measured 0.65608834 at 2403.49 Hz (nodes) and 0.65603593 at 2403.60 Hz (footprints):
    // -8.0e-5 and +4.6e-5 relative (with this softer contact the first in-band instability is
    // another pair than the 4 kHz one). Asserted within 5e-4: the reduction bases' difference,
    // an order below the 3.7 % the preload moves μ0 by with the cubic law.
    let (a, b) = (hopf[0], hopf[1]);
    assert!((b.0 / a.0 - 1.0).abs() < 5e-4, "{a:?} {b:?}");
    assert!((b.1 / a.1 - 1.0).abs() < 5e-4, "{a:?} {b:?}");
}

/// The patches of `grid` on the disc and pad meshes `levels` (bundled levels): the largest
/// distance between paired centroids, the pairing tolerance, and the largest paired area
/// difference as a fraction of a mean patch.
fn paired_patches(levels: [&str; 2], grid: [usize; 2]) -> Result<(f64, f64, f64), String> {
    use squeal_reduce::brake::{PairingTolerance, contact_positions, pair_contact_points};
    let extra = format!("[sets]\npatch_grid = [{}, {}]", grid[0], grid[1]);
    let (disc, pad) = (
        format!("disc_{}.inp", levels[0]),
        format!("pad_{}.inp", levels[1]),
    );
    let s = scene_in(&meshes(), &disc, &pad, 8, &extra).unwrap();
    let parts = load_parts(&s, &quiet).unwrap();
    let inputs = squeal_pipeline::parts::brake_inputs(&s, &parts).unwrap();
    assert_eq!(inputs.grid, grid);
    let d = contact_positions(&parts.disc.mesh, &inputs.disc.surfaces()[0], &inputs).unwrap();
    let p = contact_positions(&parts.pads[0].1.mesh, &inputs.pad().surfaces()[0], &inputs).unwrap();
    let (pairs, tol) =
        pair_contact_points(&d, &p, PairingTolerance::Relative(0.05)).map_err(|e| e.to_string())?;
    assert_eq!(pairs.len(), grid[0] * grid[1]);
    let worst = pairs.iter().map(|q| q.distance).fold(0.0, f64::max);
    let cut = |mesh, set: &str| patches(mesh, set, grid[0], grid[1], &Axis::default()).unwrap();
    let da = cut(&parts.disc.mesh, &inputs.disc.contact_face_set);
    let pa = cut(&parts.pads[0].1.mesh, &inputs.pad().contact_face_set);
    let mean = da.iter().map(|x| x.area).sum::<f64>() / pairs.len() as f64;
    let area = pairs
        .iter()
        .map(|q| (da[q.disc_point].area - pa[q.pad_point].area).abs() / mean)
        .fold(0.0, f64::max);
    eprintln!(
        "disc {} pad {} {grid:?}: worst centroid distance {worst:.3e} m (tolerance {tol:.3e} m), worst area difference {area:.3e} of a mean patch",
        levels[0], levels[1]
    );
    Ok((worst, tol, area))
}

#[test]
fn patch_grids_pair_on_matching_and_non_matching_meshes() {
    // Each patch is the part of its part's contact face inside its cell (triangles are
    // clipped at the cuts), so the disc's and the pad's patches are the same regions of the
    // same footprint whatever the meshes and the grid, and pair far inside the reduction's
    // tolerance (5 % of the patch spacing, 0.50 to 0.85 mm). What is left between partners is
    // the meshes' own difference: the footprint's arcs are quadratic edges through different
    // nodes at different levels (and the 3 x 3 patches' arcs, which are mesh edges), and the
    // interior nodes of the coarse (and of the medium) disc and pad, placed by the mesher for
    // each part, differ by up to 5e-10 m. Measured, worst over the grids 3 x 3, 1 x 1, 4 x 4,
    // 2 x 5 and 5 x 7 (centroid distance; area difference of a mean patch):
    // - coarse disc and pad (same vertices, other diagonals): 9.2e-11 m; 1.4e-8;
    // - medium disc and pad (different inside the footprint): 3.1e-9 m; 4.9e-7;
    // - coarse disc, medium pad: 2.1e-8 m; 3.4e-6; medium disc, coarse pad: 2.1e-8 m; 3.4e-6.
    // Asserted 1e-9 m and 1e-7, 1e-8 m and 2e-6, 1e-7 m and 1e-5. Before clipping, patches
    // took whole triangles by their centroids: coarse 4 x 4 and medium 2 x 5 did not pair
    // (4.6 mm and 0.96 mm off) and coarse 2 x 5 differed by 0.8 % of a patch.
    for (levels, distance, area) in [
        (["coarse", "coarse"], 1e-9, 1e-7),
        (["medium", "medium"], 1e-8, 2e-6),
        (["coarse", "medium"], 1e-7, 1e-5),
        (["medium", "coarse"], 1e-7, 1e-5),
    ] {
        for grid in [[3, 3], [1, 1], [4, 4], [2, 5], [5, 7]] {
            let (d, _, a) = paired_patches(levels, grid).unwrap();
            assert!(
                d < distance && a < area,
                "{levels:?} {grid:?}: {d:e} m, {a:e}"
            );
        }
    }
    let bad = scene_in(
        &meshes(),
        "disc_medium.inp",
        "pad_medium.inp",
        8,
        "[sets]\npatch_grid = [0, 3]",
    )
    .unwrap_err();
    assert!(bad.contains("sets.patch_grid"), "{bad}");
}

#[test]
fn the_defaults_do_not_depend_on_the_sign_of_the_rotation_axis() {
    // Without [contact] normal the defaults take the rotation axis, turned towards the pad:
    // the bundled disc described as turning counterclockwise about -z (the same motion as
    // clockwise about +z) must give the named clamp and contact faces, not the pad's back face
    // (exact node lists).
    let text = std::fs::read_to_string(meshes().join("brake.toml")).unwrap();
    let flipped: String = text
        .lines()
        .filter(|l| !l.starts_with("normal = "))
        .map(|l| match l {
            "axis = [0.0, 0.0, 1.0]" => "axis = [0.0, 0.0, -1.0]\n".to_string(),
            "sense = \"clockwise\"" => "sense = \"counterclockwise\"\n".to_string(),
            _ => format!("{l}\n"),
        })
        .collect();
    assert!(flipped.contains("axis = [0.0, 0.0, -1.0]") && flipped.contains("counterclockwise"));
    let flipped = flipped
        .replace("disc_medium.inp", "disc_coarse.inp")
        .replace("pad_medium.inp", "pad_coarse.inp");
    let scene = Scene::parse(
        &meshes().join("scene.toml"),
        format!("{flipped}\n[sets.pad]\n{}\n", abutment_rule()),
    )
    .unwrap();
    assert!(scene.normal().unwrap().is_none());
    let (disc0, pad0) = (read("disc_coarse.inp"), read("pad_coarse.inp"));
    let (mut disc, mut pad) = (disc0.clone(), pad0.clone());
    disc.node_sets.clear();
    pad.node_sets.retain(|k, _| k == "PISTON");
    let chosen = choose_sets(&scene, &mut disc, &mut [("pad", &mut pad)]).unwrap();
    for (c, (mesh, name)) in chosen.iter().zip([
        (&disc0, "CLAMP"),
        (&disc0, "CONTACT_FACE"),
        (&pad0, "CONTACT_FACE"),
    ]) {
        assert_eq!(
            c.nodes(),
            mesh.node_set(name).unwrap(),
            "{} vs {name}",
            c.key
        );
    }
}

/// A copy of `src` without its node sets (`*NSET` blocks): a mesh "with nothing but the
/// volumes", its element sets and materials kept.
fn strip_node_sets(src: &Path, dst: &Path) {
    let mut out = String::new();
    let mut skip = false;
    for line in std::fs::read_to_string(src).unwrap().lines() {
        if line.starts_with('*') {
            skip = line.to_ascii_uppercase().starts_with("*NSET");
        }
        if !skip {
            out.push_str(line);
            out.push('\n');
        }
    }
    std::fs::write(dst, out).unwrap();
}

#[test]
fn a_two_pad_brake_without_node_sets_reduces_as_the_named_sets() {
    // The coarse two-pad brake of meshes/two_pad, as named sets and as a scene written by hand
    // for meshes stripped of every node set: the clamp, both friction faces and both disc
    // faces by the defaults (lowest faces towards each pad, the friction faces projected on
    // the disc), pistons and fingers by `points`, abutments by boxes and facing; with the
    // node interface also the contact points (each face's node nearest each patch centroid:
    // on these meshes the patch-centre nodes of the CONTACT sets).
    for interface in ["patch", "node"] {
        two_pad_without_node_sets(interface);
    }
}

fn two_pad_without_node_sets(interface: &str) {
    let two = meshes().join("two_pad");
    let text = std::fs::read_to_string(two.join("brake.toml"))
        .unwrap()
        .replace("_medium", "_coarse")
        .replace("modes = 50", "modes = 8")
        .replace(
            "interface = \"patch\"",
            &format!("interface = \"{interface}\""),
        );
    let named = Scene::parse(&two.join("scene.toml"), text.clone()).unwrap();
    let dir = std::env::temp_dir().join(format!(
        "squeal-two-pad-nosets-{interface}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (src, dst) in [
        (two.join("disc_coarse.inp"), "disc_coarse.inp"),
        (meshes().join("pad_coarse.inp"), "inboard.inp"),
        (two.join("outboard_coarse.inp"), "outboard.inp"),
    ] {
        strip_node_sets(&src, &dir.join(dst));
    }
    // Piston and finger points: r = 90/130 and 93/133 mm at 77.5 and 102.5 degrees.
    let points = |r: [f64; 2], z: f64| {
        let mut v = Vec::new();
        for r in r {
            for deg in [77.5f64, 102.5] {
                let t = deg.to_radians();
                v.push(format!(
                    "[{}, {}, {z}]",
                    1e-3 * r * t.cos(),
                    1e-3 * r * t.sin()
                ));
            }
        }
        v.join(", ")
    };
    let ends = |lo: f64, hi: f64| {
        [65.0f64, 115.0]
            .map(|deg| {
                let t = deg.to_radians();
                format!(
                    "{{ plane = {{ point = [0, 0, 0], normal = [{}, {}, 0] }}, box = {{ min = [-1, -1, {}], max = [1, 1, {}] }} }}",
                    -t.sin(),
                    t.cos(),
                    lo - 1e-7,
                    hi + 1e-7
                )
            })
            .join(", ")
    };
    let start = text.find("[pads.inboard]").unwrap();
    let end = text.find("[rotation]").unwrap();
    let pads = format!(
        "[pads.inboard]\nmesh = \"inboard.inp\"\nload = {{ facing = [0, 0, 1], points = [{}] }}\nabutments = [{}]\n\n\
         [pads.outboard]\nmesh = \"outboard.inp\"\nload = {{ facing = [0, 0, -1], points = [{}] }}\nabutments = [{}]\n\n",
        points([90.0, 130.0], 0.035),
        ends(0.030, 0.035),
        points([93.0, 133.0], -0.015),
        ends(-0.015, -0.010)
    );
    let bare = format!("{}{pads}{}", &text[..start], &text[end..]);
    let bare = Scene::parse(&dir.join("scene.toml"), bare).unwrap();
    let parts = load_parts(&bare, &quiet).unwrap();
    for c in &parts.sets {
        assert_ne!(c.origin, Origin::Mesh, "{}: {:?}", c.key, c.origin);
    }
    let (a, b) = (
        reduce(&named, &format!("two-named-{interface}")),
        reduce(&bare, &format!("two-bare-{interface}")),
    );
    let names =
        |m: &ReducedModel| -> Vec<String> { m.parts.iter().map(|p| p.info.name.clone()).collect() };
    assert_eq!(names(&a), ["disc", "inboard", "outboard"]);
    assert_eq!(names(&a), names(&b));
    // Measured 0 (the same nodes, faces and piston points in the same order): asserted to
    // round-off of a sum taken in another order.
    let d = difference(&a, &b);
    println!(
        "two-pad brake, {interface} interface, named sets against geometry: largest difference {d:.1e}"
    );
    assert!(d < 1e-12, "{d:e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn restraints_given_about_the_axis_or_globally_hold_as_the_default() {
    let m = meshes();
    let scene = |extra: &str| scene_in(&m, "disc_coarse.inp", "pad_coarse.inp", 8, extra).unwrap();
    let base = reduce(&scene(""), "hold-base");
    // The same restraints written out: the clamp in all three axis directions is the plain
    // clamp, the abutments held along x and y (coordinate axes) the plain restraint: the
    // same .rom bit for bit (measured 0).
    let same = reduce(
        &scene(
            "[sets.disc]\nclamp_hold = [\"axial\", \"radial\", \"tangential\"]\n\
             [sets.pad]\nabutments_hold = [[1, 0, 0], [0, 1, 0]]",
        ),
        "hold-same",
    );
    assert_eq!(difference(&base, &same), 0.0);
    // Radial and tangential at each node span the same plane as x and y: the same
    // constrained space in other node axes, so the same reduced brake to round-off (measured
    // 6.4e-14 on the fixed-interface frequencies and the matrices; asserted 1e-10).
    let axis = reduce(
        &scene("[sets.pad]\nabutments_hold = [\"radial\", \"tangential\"]"),
        "hold-axis",
    );
    let d = difference(&base, &axis);
    println!("abutments held radially and tangentially against x and y: {d:.1e}");
    assert!(d < 1e-10, "{d:e}");
    // Held tangentially only, the pad is free to slide radially on its abutments: another
    // brake (its lowest fixed-interface mode drops from 10253.66 to 9020.08 Hz, measured;
    // asserted: by more than 1 %).
    let loose = reduce(
        &scene("[sets.pad]\nabutments_hold = [\"tangential\"]"),
        "hold-loose",
    );
    let (f0, f1) = (
        base.parts[1].info.fixed_interface_hz[0],
        loose.parts[1].info.fixed_interface_hz[0],
    );
    println!(
        "pad's lowest fixed-interface mode: held in plane {f0:.2} Hz, tangentially only {f1:.2} Hz"
    );
    assert!(f1 < 0.99 * f0, "{f0} {f1}");
    // A hold that is not a direction is an error naming the key and line.
    let e = scene_in(
        &m,
        "disc_coarse.inp",
        "pad_coarse.inp",
        8,
        "[sets.pad]\nabutments_hold = [\"sideways\"]",
    )
    .and_then(|s| {
        s.abutments_hold("pad")
            .map(|_| ())
            .map_err(|e| e.to_string())
    })
    .unwrap_err();
    assert!(
        e.contains("sets.pad.abutments_hold") && e.contains("\"radial\""),
        "{e}"
    );
}

#[test]
fn a_disc_contact_face_under_sets_disc_is_the_first_pads_only() {
    // `[sets.disc] contact_face` names the disc face under the first pad; the outboard pad
    // keeps its own (CONTACT_FACE_OUTBOARD, the conventional name).
    let two = meshes().join("two_pad");
    let text = std::fs::read_to_string(two.join("brake.toml"))
        .unwrap()
        .replace("_medium", "_coarse")
        .replace("disc_contact_face = \"CONTACT_FACE_OUTBOARD\"\n", "");
    let scene = Scene::parse(
        &two.join("scene.toml"),
        format!("{text}\n[sets.disc]\ncontact_face = \"CONTACT_FACE\"\n"),
    )
    .unwrap();
    let parts = load_parts(&scene, &quiet).unwrap();
    let inputs = squeal_pipeline::parts::brake_inputs(&scene, &parts).unwrap();
    assert_eq!(inputs.disc.contact_face_set, "CONTACT_FACE");
    assert_eq!(inputs.disc.facing.as_deref(), Some("inboard"));
    let extra: Vec<(&str, &str)> = inputs
        .disc
        .extra_surfaces
        .iter()
        .map(|s| {
            (
                s.facing.as_deref().unwrap_or(""),
                s.contact_face_set.as_str(),
            )
        })
        .collect();
    assert_eq!(extra, [("outboard", "CONTACT_FACE_OUTBOARD")]);
}
