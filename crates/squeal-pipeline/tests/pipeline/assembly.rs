//! Parts taken from one assembly file by element set (issue 21, item 3): the bundled coarse
//! brake's disc and pad written into one file (`meshes/assembly/brake_coarse.inp`, made by
//! `tools/mesh/combine_inp.py` from `meshes/disc_coarse.inp` and `meshes/pad_coarse.inp`)
//! and named in the scene by `[model] disc_elset` and `pad_elset` give the same reduced model
//! and Hopf point, bit for bit, as the two files.

use super::common;

use common::{bundled_scene, meshes};
use squeal_pipeline::model::{build, quiet};
use squeal_scene::Scene;

/// The coarse bundled scene with both parts taken from the assembly file.
fn assembly_scene() -> Scene {
    let base = bundled_scene("coarse");
    let text: String = base
        .text
        .lines()
        .map(|l| {
            if l.starts_with("disc = ") {
                "disc = \"assembly/brake_coarse.inp\"\ndisc_elset = \"DISC\"\n".to_string()
            } else if l.starts_with("pad = ") {
                "pad = \"assembly/brake_coarse.inp\"\npad_elset = \"PAD\"\n".to_string()
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    Scene::parse(&meshes().join("brake_assembly.toml"), text).unwrap()
}

fn out(tag: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("squeal-assembly-{tag}-{}", std::process::id()))
}

#[test]
fn parts_cut_from_one_file_give_the_same_hopf_point_bit_for_bit() {
    // Bits compared: faer's dense kernels sequential, as `squeal` runs them (with faer's
    // default, parallel, their bits may vary: `squeal_reduce::brake::BrakeInputs::par`).
    faer::set_global_parallelism(faer::Par::Seq);
    let separate = build(&bundled_scene("coarse"), &out("separate"), &quiet).unwrap();
    let combined = build(&assembly_scene(), &out("combined"), &quiet).unwrap();
    // The same meshes index for index (only the file ids differ): the same matrices.
    let (a, b) = (&separate.rom, &combined.rom);
    assert_eq!(a.parts.len(), b.parts.len());
    for (p, q) in a.parts.iter().zip(&b.parts) {
        assert_eq!(p.info.full_dofs, q.info.full_dofs, "{}", p.info.name);
        assert!(
            p.k == q.k && p.m == q.m,
            "{}: reduced matrices differ",
            p.info.name
        );
    }
    let mus = bundled_scene("coarse").mu_values().unwrap();
    let sa = squeal_pipeline::stability::analyse(&separate, &mus).unwrap();
    let sb = squeal_pipeline::stability::analyse(&combined, &mus).unwrap();
    let (ha, hb) = (sa.sweep.hopf.unwrap(), sb.sweep.hopf.unwrap());
    eprintln!(
        "mu0 separate {:.15} combined {:.15}, f0 {} {}",
        ha.mu0, hb.mu0, ha.frequency_hz, hb.frequency_hz
    );
    assert_eq!(ha.mu0.to_bits(), hb.mu0.to_bits());
    assert_eq!(ha.frequency_hz.to_bits(), hb.frequency_hz.to_bits());
}

#[test]
fn an_unknown_element_set_is_refused_with_the_file_and_the_sets() {
    let scene = assembly_scene();
    let text = scene
        .text
        .replace("pad_elset = \"PAD\"", "pad_elset = \"PADS\"");
    let scene = Scene::parse(&scene.path, text).unwrap();
    let Err(e) = build(&scene, &out("unknown"), &quiet) else {
        panic!("an unknown element set must be refused")
    };
    let e = e.to_string();
    assert!(
        e.contains("brake_coarse.inp") && e.contains("no element set PADS") && e.contains("PAD"),
        "{e}"
    );
}

/// The coarse pad's back face is the plane z = 35 mm.
const BACK_FACE: &str =
    "{ facing = [0, 0, 1], plane = { point = [0, 0, 0.035], normal = [0, 0, 1] } }";

/// Issue 21 item 4: a pad pressed and held in-plane over its whole back face leaves pitch and
/// roll free and is refused before any reduction; a support stiffness over that face (the
/// piston's and caliper's backing, 5e9 N/m along the normal) holds it, and the brake builds.
#[test]
fn a_pad_held_over_its_back_face_by_a_support_stiffness_builds() {
    let base = bundled_scene("coarse");
    let held = format!(
        "{}\n[sets.pad]\npistons = {BACK_FACE}\nabutments = {BACK_FACE}\n",
        base.text
    );
    let scene = Scene::parse(&base.path, held.clone()).unwrap();
    let Err(e) = build(&scene, &out("unsupported"), &quiet) else {
        panic!("a pad free in pitch and roll must be refused")
    };
    assert!(e.to_string().contains("2 rigid-body motion(s) free"), "{e}");
    let supported = format!(
        "{held}\n[[supports]]\npart = \"pad\"\nset = {BACK_FACE}\nstiffness = [0.0, 0.0, 5.0e9]\n"
    );
    let scene = Scene::parse(&base.path, supported).unwrap();
    let model = match build(&scene, &out("supported"), &quiet) {
        Ok(m) => m,
        Err(e) => panic!("{e}"),
    };
    // The support is recorded with the pad's reduction (a changed stiffness makes it stale).
    let pad = &model.rom.parts[1];
    let record = pad.info.build.as_ref().unwrap();
    assert_eq!(record.supports.len(), 1);
    assert_eq!(record.supports[0].stiffness, [0.0, 0.0, 5.0e9]);
}

/// `[[springs]]` to ground spread by area along z (axes given, permuted) is the support of the
/// same stiffness: the same terms `k w_n (e_z · u_n)²` added to `K`, so the pad's reduced
/// matrices are the same bits; a spring between the pistons' and the abutments' mean motions
/// (the pad's own sets, in tilted axes) holds no more than its rotations and changes `K̂`.
#[test]
fn a_spring_spread_by_area_is_the_support_bit_for_bit() {
    // Bits compared: faer's dense kernels sequential, as `squeal` runs them (with faer's
    // default, parallel, their bits may vary: `squeal_reduce::brake::BrakeInputs::par`).
    faer::set_global_parallelism(faer::Par::Seq);
    let base = bundled_scene("coarse");
    let held = format!(
        "{}\n[sets.pad]\npistons = {BACK_FACE}\nabutments = {BACK_FACE}\n",
        base.text
    );
    let support = format!(
        "{held}\n[[supports]]\npart = \"pad\"\nset = {BACK_FACE}\nstiffness = [0.0, 0.0, 5.0e9]\n"
    );
    let spring = format!(
        "{held}\n[[springs]]\npart = \"pad\"\nset = {BACK_FACE}\nstiffness = [0.0, 5.0e9, 0.0]\naxes = [[1, 0, 0], [0, 0, 1], [0, -1, 0]]\nspread = \"area\"\n"
    );
    let build_of = |text: String, tag: &str| {
        let scene = Scene::parse(&base.path, text).unwrap();
        match build(&scene, &out(tag), &quiet) {
            Ok(m) => m,
            Err(e) => panic!("{e}"),
        }
    };
    let a = build_of(support, "support");
    let b = build_of(spring, "spring");
    let (p, q) = (&a.rom.parts[1], &b.rom.parts[1]);
    assert!(
        p.k == q.k && p.m == q.m,
        "the pad's reduced matrices differ"
    );
    let record = q.info.build.as_ref().unwrap();
    assert_eq!(record.springs.len(), 1);
    assert_eq!(record.springs[0].stiffness, [0.0, 5.0e9, 0.0]);
}
