//! The bundled scene (`meshes/brake.toml`) on another mesh level, built by the production
//! builder ([`squeal_pipeline::model::build`]): the coarse brake of the sweep tests and the
//! benchmarks (158 dofs: patch contact, 50 fixed-interface modes per part, the compression
//! curve's `k_l = 1.25e10 Pa/m`, `k_nl = 2.0e19 Pa/m³`, 3 kN of piston force).

#![allow(dead_code)]

use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::modal::Damping;
use squeal_brake::spectrum::Reference;
use squeal_brake::sweep::{SweepOptions, reference};
use squeal_pipeline::model::{Model, build, quiet};
use squeal_scene::Scene;
use std::path::PathBuf;
use std::sync::OnceLock;

/// The repository's `meshes` folder.
pub fn meshes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes")
}

/// `meshes/brake.toml` with its disc and pad at `level`, read as if it were
/// `meshes/brake_<level>.toml` (paths stay relative to `meshes`).
pub fn bundled_scene(level: &str) -> Scene {
    bundled_scene_with(level, "")
}

/// The coarse bundled scene at `kmh` on a 0.3 m wheel (the scene's commented speed lines
/// switched on).
pub fn bundled_scene_at_speed(kmh: f64) -> Scene {
    let base = bundled_scene("coarse");
    let text = base
        .text
        .replacen(
            "# vehicle_speed_kmh = 5.0",
            &format!("vehicle_speed_kmh = {kmh:?}"),
            1,
        )
        .replacen("# rolling_radius = 0.3", "rolling_radius = 0.3", 1);
    assert_ne!(text, base.text, "meshes/brake.toml lost its speed lines");
    Scene::parse(&base.path, text).unwrap()
}

/// [`bundled_scene`] with `contact` (TOML lines) added to its `[contact]` section.
pub fn bundled_scene_with(level: &str, contact: &str) -> Scene {
    let path = meshes().join("brake.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut replaced = 0;
    let text: String = text
        .lines()
        .map(|l| {
            for part in ["disc", "pad"] {
                if l.starts_with(&format!("{part} = ")) {
                    replaced += 1;
                    return format!("{part} = \"{part}_{level}.inp\"\n");
                }
            }
            if l == "[contact]" && !contact.is_empty() {
                return format!("{l}\n{contact}\n");
            }
            format!("{l}\n")
        })
        .collect();
    // A test must not silently run the scene's own (medium) meshes.
    assert_eq!(replaced, 2, "meshes/brake.toml lost its disc/pad lines");
    Scene::parse(&meshes().join(format!("brake_{level}.toml")), text).unwrap()
}

/// The coarse brake and its frictionless reference with the scene's global damping only.
pub struct Coarse {
    pub model: Model,
    pub reference: Reference,
}

fn make() -> Coarse {
    let scene = bundled_scene("coarse");
    let out = std::env::temp_dir().join(format!("squeal-pipeline-coarse-{}", std::process::id()));
    let model = build(&scene, &out, &quiet).unwrap();
    let damping = Damping {
        global_ratio: model.damping.global_ratio,
        extra: vec![],
    };
    let reference = reference(&model.brake, &damping, &NewtonOptions::default()).unwrap();
    Coarse { model, reference }
}

/// The coarse brake, built on first use (a few seconds).
pub fn coarse() -> &'static Coarse {
    static BRAKE: OnceLock<Coarse> = OnceLock::new();
    BRAKE.get_or_init(make)
}

/// Sweep options of the bundled scene on the coarse brake.
pub fn options(c: &Coarse) -> SweepOptions {
    c.model.sweep
}

/// `count` friction values evenly spaced on `[lo, hi]`.
pub fn mus(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    (0..count)
        .map(|k| lo + (hi - lo) * k as f64 / (count - 1) as f64)
        .collect()
}

/// Best-of-`reps` wall time of `f` (s) and its last result: the benches' timer.
pub fn best<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..reps.max(1) {
        let t = std::time::Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    (best, out.expect("at least one repetition"))
}

/// The limit cycle at `mu` by CHBM from the pipeline's unstable mode, with restarts, as
/// `squeal chbm` solves it.
pub fn chbm_cycle(p: &squeal_pipeline::Pipeline, mu: f64) -> squeal_chbm::ChbmSolution {
    let (m, st) = (p.model().unwrap(), p.stability().unwrap());
    let (start, mb) = squeal_pipeline::chbm::start(m, st, mu, None).unwrap();
    squeal_pipeline::chbm::solve_with_restarts(
        &mb,
        &start,
        &squeal_chbm::ChbmOptions::default(),
        &squeal_chbm::RESTART_AMPLITUDES,
        &quiet,
    )
    .unwrap()
    .0
}
