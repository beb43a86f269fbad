//! Issue #11, item 1: nothing assumes the disc turns about z through the origin. The coarse
//! bundled brake moved by a rigid motion (its meshes in memory, the scene's axis, point and
//! normal moved alike) is the same brake: the same Hopf point μ0 and the same frequencies.
//! With per-point tangent sliding, the moved brake exercises every piece that depends on the
//! orientation: the patch grid cut about the axis, the pad held in the plane normal to a skew
//! axis (node frames, `squeal_fe::frames`), the piston dofs along a skew normal
//! (`DofLabel::Along`), each pair's normal from the disc face and its tangent from the axis.

use squeal_brake::analysis::LinearStability as Stability;
use squeal_pipeline::model::{brake_inputs, model_on};
use squeal_reduce::brake::{LoadedPart, load_part, reduce_brake_loaded};
use squeal_reduce::rom::DofLabel;
use squeal_scene::Scene;
use std::path::PathBuf;

fn meshes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes")
}

/// A rigid motion `p -> R p + t`.
struct Motion {
    r: [[f64; 3]; 3],
    t: [f64; 3],
}

impl Motion {
    fn vector(&self, v: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|i| (0..3).map(|j| self.r[i][j] * v[j]).sum())
    }
    fn point(&self, p: [f64; 3]) -> [f64; 3] {
        let q = self.vector(p);
        std::array::from_fn(|i| q[i] + self.t[i])
    }
}

/// The rotation by `angle` about the unit `axis` (Rodrigues).
fn rotation(axis: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let k = axis.map(|x| x / n);
    let (c, s) = (angle.cos(), angle.sin());
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let cross = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
            let id = if i == j { 1.0 } else { 0.0 };
            c * id + s * cross[i][j] + (1.0 - c) * k[i] * k[j]
        })
    })
}

fn vec_text(v: [f64; 3]) -> String {
    format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2])
}

/// The coarse bundled scene with tangent sliding and a narrow sweep around μ0, moved by `m`.
fn scene(m: &Motion) -> Scene {
    let path = meshes().join("brake_coarse.toml");
    let mut text = std::fs::read_to_string(meshes().join("brake.toml")).unwrap();
    for (from, to) in [
        (
            "disc = \"disc_medium.inp\"",
            "disc = \"disc_coarse.inp\"".into(),
        ),
        (
            "pad = \"pad_medium.inp\"",
            "pad = \"pad_coarse.inp\"".into(),
        ),
        (
            "axis = [0.0, 0.0, 1.0]",
            format!("axis = {}", vec_text(m.vector([0.0, 0.0, 1.0]))),
        ),
        (
            "point = [0.0, 0.0, 0.0]",
            format!("point = {}", vec_text(m.point([0.0; 3]))),
        ),
        (
            "normal = [0.0, 0.0, 1.0]",
            format!("normal = {}", vec_text(m.vector([0.0, 0.0, 1.0]))),
        ),
        (
            "sliding_direction = [1.0, 0.0, 0.0]",
            "sliding = \"tangent\"".into(),
        ),
        // 31 values around μ0 = 0.466 (tangent sliding) instead of 201 over [0, 1]: the
        // Hopf point is refined to the same bracket either way.
        ("mu = \"0..1/201\"", "mu = \"0.3..0.6/31\"".into()),
    ] {
        assert!(text.contains(from), "meshes/brake.toml lost '{from}'");
        text = text.replacen(from, &to, 1);
    }
    Scene::parse(&path, text).unwrap()
}

fn moved(path: &str, m: &Motion) -> LoadedPart {
    let mut part = load_part(&meshes().join(path)).unwrap();
    for p in &mut part.mesh.nodes {
        *p = m.point(*p);
    }
    part
}

/// The coarse brake of `scene` on the coarse meshes moved by `m`.
fn reduce_moved(scene: &Scene, m: &Motion) -> squeal_reduce::rom::ReducedModel {
    reduce_brake_loaded(
        &brake_inputs(scene).unwrap(),
        moved("disc_coarse.inp", m),
        vec![moved("pad_coarse.inp", m)],
        &mut |_, _| {},
    )
    .unwrap()
    .0
}

/// Reduces the moved coarse meshes and runs the stability analysis of the moved scene; also
/// says whether the pad's piston dofs are skew (`DofLabel::Along`).
fn stability(m: &Motion) -> (Stability, bool) {
    let scene = scene(m);
    let rom = reduce_moved(&scene, m);
    let skew = rom.parts.iter().any(|p| {
        p.info
            .dofs
            .iter()
            .any(|l| matches!(l, DofLabel::Along { .. }))
    });
    let model = model_on(&scene, rom, PathBuf::from("in-memory.rom")).unwrap();
    let st = squeal_pipeline::stability::analyse(&model, &scene.mu_values().unwrap()).unwrap();
    (st, skew)
}

/// Largest relative difference between the frequencies (ascending) of every sweep point.
fn frequency_difference(a: &Stability, b: &Stability) -> f64 {
    let mut worst = 0.0f64;
    assert_eq!(a.sweep.points.len(), b.sweep.points.len());
    for (p, q) in a.sweep.points.iter().zip(&b.sweep.points) {
        assert_eq!(p.spectrum.values.len(), q.spectrum.values.len());
        for (x, y) in p.spectrum.values.iter().zip(&q.spectrum.values) {
            worst = worst.max((x.im - y.im).abs() / x.im.abs().max(1.0));
        }
    }
    worst
}

fn compare(a: &Stability, b: &Stability, what: &str) {
    let (ha, hb) = (
        a.sweep.hopf.as_ref().unwrap(),
        b.sweep.hopf.as_ref().unwrap(),
    );
    eprintln!(
        "{what}: mu0 {:.12} vs {:.12} (diff {:.1e}), f0 {:.6} vs {:.6} Hz (rel diff {:.1e}), pair {:?} vs {:?}, spectra rel diff {:.1e}",
        ha.mu0,
        hb.mu0,
        (ha.mu0 - hb.mu0).abs(),
        ha.frequency_hz,
        hb.frequency_hz,
        (ha.frequency_hz / hb.frequency_hz - 1.0).abs(),
        a.pair,
        b.pair,
        frequency_difference(a, b)
    );
    // The same modes coalesce.
    assert_eq!(a.pair, b.pair, "{what}: coalescing pair");
    // μ0 is refined to a bracket of ~5e-9 by bisection on the sign of Re λ; the moved brake's
    // matrices differ from the original's by round-off (~1e-13 relative, the frames' and
    // normals' trigonometry), which moves μ0 by ~1e-12 unless a bisection step lands within
    // round-off of the root. 1e-10 allows the round-off and would catch any modelling
    // difference (tangent against global sliding moves μ0 by ~1e-2).
    assert!(
        (ha.mu0 - hb.mu0).abs() < 1e-10,
        "{what}: mu0 {} vs {}",
        ha.mu0,
        hb.mu0
    );
    // The frequencies at μ0 and at every sweep point: round-off of the reduced matrices,
    // 1e-9 relative (the eigensolver's own accuracy on these 158-dof spectra is ~1e-12).
    assert!(
        (ha.frequency_hz / hb.frequency_hz - 1.0).abs() < 1e-9,
        "{what}: f0 {} vs {}",
        ha.frequency_hz,
        hb.frequency_hz
    );
    let d = frequency_difference(a, b);
    assert!(d < 1e-9, "{what}: spectra differ by {d:.2e} relative");
}

const IDENTITY: Motion = Motion {
    r: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    t: [0.0; 3],
};

#[test]
fn a_rigidly_moved_brake_has_the_same_hopf_point_and_frequencies() {
    let (reference, plain) = stability(&IDENTITY);
    assert!(!plain);
    // An arbitrary rotation (0.7 rad about [1, 2, 3]) and translation: the axis, the normal
    // and the abutment's plane are skew, the piston dof is a DofLabel::Along.
    let skew = Motion {
        r: rotation([1.0, 2.0, 3.0], 0.7),
        t: [0.12, -0.31, 0.057],
    };
    let (moved, along) = stability(&skew);
    // The moved pad's piston dofs are along its skew normal: the skew path was taken.
    assert!(along);
    compare(&reference, &moved, "rotated and translated");
}

/// The issue's failing case: a mesh rotated so that the disc turns about y failed with "the
/// patch grid is too coarse" (the grid was cut about z). The rotation by -90 degrees about x
/// takes z to y exactly, so every restraint and dof stays on coordinate axes.
#[test]
fn a_brake_whose_disc_turns_about_y_runs() {
    let about_y = Motion {
        r: [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]],
        t: [0.0, 0.0, 0.0],
    };
    assert_eq!(about_y.vector([0.0, 0.0, 1.0]), [0.0, 1.0, 0.0]);
    compare(&stability(&IDENTITY).0, &stability(&about_y).0, "about y");
}

/// A scene that contradicts its mesh is refused when the brake is built, naming the pair: a
/// global sliding direction against the rotation's sense, a normal 10 degrees off the disc
/// face's (the check's limit is 5 degrees; the disc face's own normals are exact to 1e-16).
#[test]
fn a_scene_that_contradicts_the_mesh_is_refused() {
    let path = meshes().join("brake_coarse.toml");
    let base = std::fs::read_to_string(meshes().join("brake.toml"))
        .unwrap()
        .replacen("disc_medium.inp", "disc_coarse.inp", 1)
        .replacen("pad_medium.inp", "pad_coarse.inp", 1);
    let scene = Scene::parse(&path, base.clone()).unwrap();
    let rom = reduce_moved(&scene, &IDENTITY);
    let build = |text: String| {
        let scene = Scene::parse(&path, text).unwrap();
        model_on(&scene, rom.clone(), PathBuf::from("in-memory.rom")).map(|_| ())
    };
    assert!(build(base.clone()).is_ok());
    // The disc turning the other way under a sliding direction of +x.
    let e = build(base.replacen("sense = \"clockwise\"", "sense = \"counterclockwise\"", 1))
        .unwrap_err()
        .to_string();
    assert!(e.contains("against the disc's motion"), "{e}");
    // Without [rotation] (no axis to check the normal against in the scene), a normal tilted
    // by 10 degrees about x: the mesh's faces disagree.
    let start = base.find("[rotation]").unwrap();
    let end = start + base[start..].find("\n[").unwrap() + 1;
    let a = 10f64.to_radians();
    let tilted = format!("{}{}", &base[..start], &base[end..]).replacen(
        "normal = [0.0, 0.0, 1.0]",
        &format!("normal = [0.0, {:?}, {:?}]", a.sin(), a.cos()),
        1,
    );
    // Issue 22: the check's message names the scene file and the key's line.
    let line = tilted
        .lines()
        .position(|l| l.starts_with("normal = [0.0, 0.17"))
        .unwrap()
        + 1;
    let e = build(tilted).unwrap_err().to_string();
    assert!(
        e.contains("is 10.0 degrees from the scene's contact normal"),
        "{e}"
    );
    assert!(
        e.starts_with(&format!("{}:{line}:", path.display())) && e.contains("contact.normal"),
        "{e}"
    );
}

/// A `[contact] normal` a few degrees off the mesh's (inside the 5 degree check) is accepted
/// when the scene is read and must also build: the pistons keep their dof along the scene's
/// normal and push along it, however the mesh's faces point (before, the load was required to
/// lie along the mesh's normal to 1e-9 and a 3 degree tilt failed with a missing piston dof).
#[test]
fn a_normal_a_few_degrees_off_the_mesh_builds() {
    let path = meshes().join("brake_coarse.toml");
    let a = 3f64.to_radians();
    let text = std::fs::read_to_string(meshes().join("brake.toml"))
        .unwrap()
        .replacen("disc_medium.inp", "disc_coarse.inp", 1)
        .replacen("pad_medium.inp", "pad_coarse.inp", 1)
        .replacen(
            "normal = [0.0, 0.0, 1.0]",
            &format!("normal = [0.0, {:?}, {:?}]", a.sin(), a.cos()),
            1,
        );
    let scene = Scene::parse(&path, text).unwrap();
    let rom = reduce_moved(&scene, &IDENTITY);
    let m = model_on(&scene, rom, PathBuf::from("in-memory.rom")).unwrap();
    // Each of the 4 pistons pushes its share of the clamp force along its own (tilted) dof,
    // towards the disc: the generalized forces add up to the clamp force (to round-off).
    let f: f64 = m.brake.f_piston.iter().sum::<f64>().abs();
    let expected = scene.piston_force().unwrap();
    assert!(
        f > 0.0 && (f / expected - 1.0).abs() < 1e-12,
        "{f} vs {expected}"
    );
}
