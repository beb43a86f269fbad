//! A tie between two separately reduced parts through the whole pipeline, on the bundled
//! corner (`meshes/corner/brake_tied.toml`: the outboard pad's abutments bonded to the
//! bracket's ears, `[[ties]]` with `master_part`): the scene's tie reaches the reduction (both
//! sets kept node by node, the pad's abutment restraint dropped), the reduced brake has the
//! slave nodes' dofs eliminated, its frictionless modes are all held, and `--full` refuses the
//! tie with a message instead of building another brake. The accuracy of the tie itself is
//! verified on two cubes against one block (`squeal-reduce`'s `part_ties` test).

use squeal_brake::analysis::stability;
use squeal_fe::NodeSelection;
use squeal_pipeline::full::full_brake;
use squeal_pipeline::full::onset::undamped;
use squeal_pipeline::model::{model_on, quiet};
use squeal_pipeline::parts::{brake_inputs, load_parts};
use squeal_reduce::brake::reduce_brake_loaded;
use squeal_scene::Scene;
use std::path::PathBuf;

#[test]
fn corner_with_a_tied_abutment() {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes/corner/brake_tied.toml");
    let scene = Scene::read(&path).unwrap();
    let parts = load_parts(&scene, &quiet).unwrap();
    let inputs = brake_inputs(&scene, &parts).unwrap();
    assert_eq!(inputs.part_ties.len(), 1);
    let tie = &inputs.part_ties[0];
    assert_eq!(
        tie.slave,
        ("bracket".into(), "BRACKET_ABUTMENT_OUTBOARD".into())
    );
    assert_eq!(tie.master, ("outboard".into(), "OUTBOARD_ABUTMENT".into()));
    let outboard = &inputs
        .pads
        .iter()
        .find(|p| p.name == "outboard")
        .unwrap()
        .part;
    assert!(
        outboard
            .couplings
            .iter()
            .any(|c| c.nodal && c.set == "OUTBOARD_ABUTMENT")
    );
    assert!(
        !outboard
            .restraints
            .iter()
            .any(|r| r.nodes == NodeSelection::Set("OUTBOARD_ABUTMENT".into())),
        "the tied abutment is not also restrained"
    );
    let (rom, _) = reduce_brake_loaded(
        &inputs,
        parts.disc.clone(),
        parts
            .pads
            .iter()
            .chain(&parts.bodies)
            .map(|p| p.1.clone())
            .collect(),
        &mut |_, _| {},
    )
    .unwrap();
    let slaves = parts
        .bodies
        .iter()
        .find(|b| b.0 == "bracket")
        .unwrap()
        .1
        .mesh
        .node_set("BRACKET_ABUTMENT_OUTBOARD")
        .unwrap()
        .len();
    assert_eq!(rom.ties.len(), 1);
    assert_eq!(rom.ties[0].links.len(), slaves);
    // Each link's weights are the master face's shape functions: they sum to 1.
    for l in &rom.ties[0].links {
        let s: f64 = l.masters.iter().map(|m| m.1).sum();
        assert!((s - 1.0).abs() < 1e-12, "{s}");
    }
    let stacked: usize = rom.parts.iter().map(|p| p.size()).sum();
    let model = model_on(&scene, rom, PathBuf::from("in-memory.rom")).unwrap();
    assert_eq!(model.brake.size(), stacked - 3 * slaves);
    // Held: every frictionless mode above 1 Hz (the lowest measured 32.6 Hz on brake_caliper).
    let st = stability(&model.brake, &undamped(), &[0.0], &model.sweep).unwrap();
    let lowest = st.reference.basis.omega[0] / std::f64::consts::TAU;
    println!(
        "{slaves} slave nodes, {stacked} stacked dofs, lowest frictionless mode {lowest:.3} Hz"
    );
    assert!(lowest > 1.0, "{lowest}");
    let e = full_brake(&parts, &inputs, &model)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("master_part") && e.contains("does not build"),
        "{e}"
    );
}

/// A tie between parts whose slave is a pad is refused by the scene at its key, with the way
/// out (swap master and slave); a master_part that is not a part is refused likewise.
#[test]
fn a_pad_slave_is_refused_at_its_key() {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes/corner/brake_tied.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let swapped = text.replace(
        "part = \"bracket\"\nslave = \"BRACKET_ABUTMENT_OUTBOARD\"\nmaster_part = \"outboard\"\nmaster = \"OUTBOARD_ABUTMENT\"",
        "part = \"outboard\"\nslave = \"OUTBOARD_ABUTMENT\"\nmaster_part = \"bracket\"\nmaster = \"BRACKET_ABUTMENT_OUTBOARD\"",
    );
    assert_ne!(swapped, text);
    let e = refusal(&path, swapped);
    assert!(
        e.contains("brake_tied.toml:") && e.contains("ties.3.part"),
        "{e}"
    );
    assert!(
        e.contains("must be a [parts.<name>] part") && e.contains("master_part = \"outboard\""),
        "{e}"
    );
    let unknown = text.replace("master_part = \"outboard\"", "master_part = \"knuckle\"");
    let e = refusal(&path, unknown);
    assert!(e.contains("'knuckle' is not a part"), "{e}");
}

/// The error of scene `text` (read as `path`), on reading or on its ties.
fn refusal(path: &std::path::Path, text: String) -> String {
    match Scene::parse(path, text) {
        Ok(scene) => match scene.ties() {
            Ok(_) => panic!("the scene reads"),
            Err(e) => e.to_string(),
        },
        Err(e) => e.to_string(),
    }
}
