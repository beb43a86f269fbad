//! Errors, not panics (issue #4, item 8): each bad input is named by a typed error.

use super::common;

use common::{coarse, coarse_inputs, mesh_path};
use squeal_eigs::{EigError, EigOptions};
use squeal_fe::{ElasticMaterial, FeError, MaterialTable, Restraint};
use squeal_mesh::generate::box_tet10;
use squeal_reduce::brake::{
    BrakeInputs, LoadedPart, ModeChoice, reduce_brake, reduce_brake_loaded,
};
use squeal_reduce::craig_bampton::{PartSpec, ReduceError, ReduceOptions, reduce_part};
use squeal_reduce::interface::InterfaceError;
use squeal_reduce::rom::{InterfaceKind, MeshInfo, PartRole};

/// Reduces the coarse brake after `edit` changed the meshes.
fn reduce_edited(
    inputs: &BrakeInputs,
    edit: impl FnOnce(&mut LoadedPart, &mut LoadedPart),
) -> ReduceError {
    let (mut disc, mut pad) = (coarse("disc"), coarse("pad"));
    edit(&mut disc, &mut pad);
    match reduce_brake_loaded(inputs, disc, vec![pad], &mut |_, _| {}) {
        Ok(_) => panic!("the reduction should have failed"),
        Err(ReduceError::InMesh { path, error }) => {
            // An error of one part names its mesh file.
            assert!(path.ends_with("disc_coarse.inp") || path.ends_with("pad_coarse.inp"));
            *error
        }
        Err(e) => e,
    }
}

/// Issue 12: "node set PISTON is missing from the mesh" did not say which mesh. The message
/// now starts with the file.
#[test]
fn a_missing_node_set_names_the_mesh_file() {
    let patch = coarse_inputs(InterfaceKind::Patch);
    let (disc, mut pad) = (coarse("disc"), coarse("pad"));
    pad.mesh.node_sets.remove("PISTON");
    let e = reduce_brake_loaded(&patch, disc, vec![pad], &mut |_, _| {}).unwrap_err();
    let shown = e.to_string();
    assert!(
        shown.contains("pad_coarse.inp: node set PISTON is missing"),
        "{shown}"
    );
    assert!(matches!(
        e.inner(),
        ReduceError::Interface(InterfaceError::MissingSet(s)) if s == "PISTON"
    ));
}

#[test]
fn a_missing_node_set_is_named() {
    let patch = coarse_inputs(InterfaceKind::Patch);
    let e = reduce_edited(&patch, |_, pad| {
        pad.mesh.node_sets.remove("CONTACT_FACE");
    });
    assert!(
        matches!(&e, ReduceError::Interface(InterfaceError::MissingSet(s)) if s == "CONTACT_FACE"),
        "{e}"
    );
    let e = reduce_edited(&patch, |disc, _| {
        disc.mesh.node_sets.remove("CLAMP");
    });
    assert!(
        matches!(&e, ReduceError::Interface(InterfaceError::MissingSet(s)) if s == "CLAMP"),
        "{e}"
    );
    let e = reduce_edited(&patch, |_, pad| {
        pad.mesh.node_sets.remove("PISTON");
    });
    assert!(e.to_string().contains("PISTON"), "{e}");
}

#[test]
fn an_empty_node_set_is_named() {
    let node = coarse_inputs(InterfaceKind::Node);
    let e = reduce_edited(&node, |disc, _| {
        disc.mesh.node_sets.insert("CONTACT".into(), Vec::new());
    });
    assert!(
        matches!(&e, ReduceError::Interface(InterfaceError::EmptySet(s)) if s == "CONTACT"),
        "{e}"
    );
    let e = reduce_edited(&node, |_, pad| {
        pad.mesh.node_sets.insert("PISTON".into(), Vec::new());
    });
    assert!(
        matches!(&e, ReduceError::Interface(InterfaceError::EmptySet(s)) if s == "PISTON"),
        "{e}"
    );
}

#[test]
fn a_clamped_boundary_node_is_refused() {
    for interface in [InterfaceKind::Node, InterfaceKind::Patch] {
        let e = reduce_edited(&coarse_inputs(interface), |disc, _| {
            let contact = disc.mesh.node_set("CONTACT").unwrap()[4];
            disc.mesh.node_sets.get_mut("CLAMP").unwrap().push(contact);
        });
        assert!(
            matches!(&e, ReduceError::BoundaryRestrained { part, direction: 'x', .. } if part == "disc"),
            "{interface:?}: {e}"
        );
        // Issue 22: the node is placed (a rule's set has no ids the user wrote), at its own
        // coordinates in the mesh, and the fix is said.
        let ReduceError::BoundaryRestrained { position, node, .. } = &e else {
            unreachable!()
        };
        let disc = coarse("disc");
        let i = disc.mesh.node_ids.iter().position(|id| id == node).unwrap();
        assert_eq!(*position, disc.mesh.nodes[i], "{e}");
        let at = format!(
            "boundary node {node} at ({:.4}, {:.4}, {:.4}) m (",
            position[0], position[1], position[2]
        );
        let text = e.to_string();
        assert!(
            text.contains(&at) && text.contains("narrow the restraint"),
            "{text}"
        );
    }
    // A piston node held along the normal, the direction it keeps.
    let mut inputs = coarse_inputs(InterfaceKind::Patch);
    inputs.pad_mut().restraints = vec![Restraint::set("PISTON", [false, false, true])];
    let e = reduce_edited(&inputs, |_, _| {});
    assert!(
        matches!(&e, ReduceError::BoundaryRestrained { set, direction: 'z', .. } if set == "PISTON"),
        "{e}"
    );
}

/// A 40 x 10 x 10 mm steel bar of 4 x 1 x 1 cells.
fn bar_spec(contact: &str, restraints: Vec<Restraint>, modes: usize) -> PartSpec {
    PartSpec {
        restraints,
        contact_set: contact.into(),
        contact_face_set: contact.into(),
        grid: [1, 1],
        ..PartSpec::new("bar", PartRole::Pad, MeshInfo::in_memory("bar"), modes)
    }
}

fn bar() -> (squeal_mesh::Mesh, MaterialTable) {
    let mut mesh = box_tet10([0.04, 0.01, 0.01], [4, 1, 1]);
    // One node as the only boundary: the corner at the origin.
    let corner = (0..mesh.num_nodes() as u32)
        .find(|&n| mesh.nodes[n as usize] == [0.0; 3])
        .unwrap();
    mesh.node_sets.insert("CORNER".into(), vec![corner]);
    let steel = ElasticMaterial::isotropic(210e9, 0.3, 7850.0);
    let materials = MaterialTable::uniform(&mesh, steel).unwrap();
    (mesh, materials)
}

#[test]
fn a_part_that_is_not_held_has_a_singular_interior_stiffness() {
    // Held at one node only, the bar can still rotate about it: K_II is singular.
    let (mesh, materials) = bar();
    let spec = bar_spec("CORNER", Vec::new(), 5);
    let e = reduce_part(
        &mesh,
        &materials,
        &spec,
        &ReduceOptions::default(),
        &mut |_| {},
    )
    .unwrap_err();
    assert!(
        matches!(&e, ReduceError::NotHeld { part, .. } if part == "bar"),
        "{e}"
    );
    assert!(e.to_string().contains("not held"), "{e}");
}

#[test]
fn a_solver_that_does_not_converge_is_an_error() {
    let (mesh, materials) = bar();
    let spec = bar_spec("XMIN", Vec::new(), 20);
    let opts = ReduceOptions {
        eig: {
            let mut o = EigOptions::default();
            // One restart cycle with a basis barely larger than the modes wanted.
            o.max_iter = 1;
            o.ncv = Some(24);
            o
        },
        ..ReduceOptions::default()
    };
    let e = reduce_part(&mesh, &materials, &spec, &opts, &mut |_| {}).unwrap_err();
    assert!(
        matches!(
            &e,
            ReduceError::Eigen {
                source: EigError::NotConverged { .. },
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn too_many_modes_below_the_cutoff_is_an_error() {
    let (mesh, materials) = bar();
    let spec = bar_spec("XMIN", Vec::new(), 3);
    let opts = ReduceOptions {
        modes_below_hz: Some(1e6),
        ..ReduceOptions::default()
    };
    let e = reduce_part(&mesh, &materials, &spec, &opts, &mut |_| {}).unwrap_err();
    assert!(
        matches!(e, ReduceError::TooManyModes { limit: 3, count, .. } if count > 3),
        "{e}"
    );
}

#[test]
fn contact_points_without_a_partner_are_named() {
    let node = coarse_inputs(InterfaceKind::Node);
    // The pad moved 5 mm along x: no disc contact point faces a pad one any more
    // (tolerance 5% of the 17 mm spacing).
    let e = reduce_edited(&node, |_, pad| {
        for x in &mut pad.mesh.nodes {
            x[0] += 0.005;
        }
    });
    assert!(
        matches!(e, ReduceError::NoPartner { point: 1, nearest, .. } if (nearest - 0.005).abs() < 1e-9),
        "{e}"
    );
    // One contact node fewer on the pad.
    let e = reduce_edited(&node, |_, pad| {
        pad.mesh.node_sets.get_mut("CONTACT").unwrap().pop();
    });
    assert!(
        matches!(e, ReduceError::ContactCountMismatch { disc: 9, pad: 8 }),
        "{e}"
    );
}

#[test]
fn bad_options_and_files_are_named() {
    let mut inputs = coarse_inputs(InterfaceKind::Patch);
    inputs.normal_direction = 3;
    assert!(matches!(inputs.validate(), Err(ReduceError::Options(_))));
    let mut inputs = coarse_inputs(InterfaceKind::Patch);
    inputs.modes = ModeChoice::Auto {
        fmax_hz: -1.0,
        factor: 2.0,
    };
    assert!(matches!(inputs.validate(), Err(ReduceError::Options(_))));
    inputs.modes = ModeChoice::Fixed(5000);
    assert!(matches!(inputs.validate(), Err(ReduceError::Options(_))));
    // A mesh file that is not there.
    let mut inputs = coarse_inputs(InterfaceKind::Patch);
    inputs.pad_mut().mesh = mesh_path("no_such_pad.inp");
    let e = reduce_brake(&inputs, &mut |_, _| {}).unwrap_err();
    assert!(matches!(e, ReduceError::Mesh(_)), "{e}");
    assert!(e.to_string().contains("no_such_pad.inp"), "{e}");
    // A material override on an element set the mesh does not have.
    let mut inputs = coarse_inputs(InterfaceKind::Patch);
    inputs.disc.material_overrides = vec![(
        "ROTOR".into(),
        ElasticMaterial::isotropic(125e9, 0.26, 7200.0),
    )];
    let e = reduce_edited(&inputs, |_, _| {});
    assert!(
        matches!(&e, ReduceError::Fe(FeError::UnknownElementSet(s)) if s == "ROTOR"),
        "{e}"
    );
}
