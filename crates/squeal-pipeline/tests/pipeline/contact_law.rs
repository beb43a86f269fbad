//! Issue #19, item 5: the scene chooses the contact law (`[contact] law`), run end to end on
//! the coarse bundled brake (scene → reduced model → brake → damping → sweep → μ0).
//!
//! The velocity-dependent law `F_t = μ s(v) F_n`, `s(v) = r + (1 - r)(1 - e^(-v/v0))`, changes
//! the brake in two ways at once: the level `μ s(V_p)` of friction at each pair's sliding speed
//! `V_p` (the bundled pairs sit 0.09–0.13 m from the axis: 0.56–0.79 m/s at 60 rpm), and the
//! slope `μ s'(V_p) F_n`, a damping along the sliding direction (negative for a falling curve,
//! `r > 1`). The physics predicts the slope's sign effect: negative damping destabilizes. To
//! see the slope apart from the level, each velocity-dependent brake is compared with the same
//! brake whose coefficients are frozen at the steady sliding speeds (the same `μ s(V_p)` at
//! every pair, no slope): a falling curve must lower μ0 below the frozen brake's, a rising
//! one raise it.

use super::common;

use squeal_brake::Brake;
use squeal_brake::contact::{ContactLaw, Kinematics, Law, Parameter, Response};
use squeal_pipeline::model::{Model, model_on, quiet, reduced_model};
use squeal_scene::Scene;
use std::sync::{Arc, OnceLock};

/// The coarse reduced model, reduced once and shared by the scene variants.
fn rom() -> &'static (squeal_reduce::rom::ReducedModel, std::path::PathBuf) {
    static ROM: OnceLock<(squeal_reduce::rom::ReducedModel, std::path::PathBuf)> = OnceLock::new();
    ROM.get_or_init(|| {
        let out = std::env::temp_dir().join(format!("squeal-law-coarse-{}", std::process::id()));
        reduced_model(&common::bundled_scene("coarse"), &out, &quiet).unwrap()
    })
}

/// The coarse bundled scene turning at 60 rpm with `law` (a TOML value) as `[contact] law`.
fn scene(law: &str) -> Scene {
    let base = common::bundled_scene_with("coarse", &format!("law = {law}"));
    let text = base.text.replacen(
        "sense = \"clockwise\"",
        "sense = \"clockwise\"\nrpm = 60.0",
        1,
    );
    assert_ne!(text, base.text, "meshes/brake.toml lost its rotation sense");
    Scene::parse(&base.path, text).unwrap()
}

fn model(law: &str) -> Model {
    let (rom, path) = rom();
    model_on(&scene(law), rom.clone(), path.clone()).unwrap()
}

fn velocity_dependent(r: f64, v0: f64) -> String {
    format!(
        "{{ kind = \"velocity-dependent\", static_ratio = {r:?}, decay_speed_m_per_s = {v0:?} }}"
    )
}

/// A law evaluated at a fixed slip velocity: the same forces in steady sliding, no slope.
#[derive(Debug)]
struct Frozen {
    inner: Law,
    speed: f64,
}

impl ContactLaw for Frozen {
    fn response(&self, mu: f64, k: &Kinematics) -> Response {
        let mut r = self.inner.response(
            mu,
            &Kinematics {
                slip_velocity: self.speed,
                ..*k
            },
        );
        r.normal_derivatives[2] = 0.0;
        r.tangential_derivatives[2] = 0.0;
        r
    }

    fn name(&self) -> String {
        format!("{} frozen at {} m/s", self.inner.name(), self.speed)
    }

    fn parameters(&self) -> Vec<Parameter> {
        self.inner.parameters()
    }
}

/// The brake of `m` with every pair's law frozen at its surface speed.
fn frozen(m: &Model) -> Model {
    let mut brake: Brake = m.brake.clone();
    for p in &mut brake.pairs {
        let speed = p.surface_speed.expect("the scene gives the disc's speed");
        p.law = Arc::new(Frozen {
            inner: p.law.clone(),
            speed,
        });
    }
    let (rom, path) = rom();
    let mut out = model_on(&scene("\"penalty-coulomb\""), rom.clone(), path.clone()).unwrap();
    out.brake = brake;
    out
}

/// μ0 and its frequency (Hz) from the scene's stability analysis (pair damping found
/// automatically, as `squeal stability` does) over μ in [0.3, 0.6].
fn hopf(m: &Model) -> (f64, f64) {
    let st = squeal_pipeline::stability::analyse(m, &common::mus(0.3, 0.6, 31)).unwrap();
    let h = st.sweep.hopf.expect("a Hopf point in 0.3..0.6");
    (h.mu0, h.frequency_hz)
}

#[test]
fn the_scene_chooses_the_law_and_a_falling_friction_curve_destabilizes() {
    // Penalty–Coulomb by name is the default brake: μ0 = 0.46182 on the coarse meshes
    // (docs/verification.md), and the same bits with or without the key.
    let named = hopf(&model("\"penalty-coulomb\""));
    let (rom, path) = rom();
    let plain = model_on(&common::bundled_scene("coarse"), rom.clone(), path.clone()).unwrap();
    let (default, _) = hopf(&plain);
    assert_eq!(named.0, default);
    assert!((named.0 - 0.46182).abs() < 5e-6, "{named:?}");
    for (r, v0) in [(1.25, 0.3), (0.75, 0.3)] {
        let vd = model(&velocity_dependent(r, v0));
        assert!(
            vd.brake.pairs.iter().all(|p| p.law.uses_slip_velocity()),
            "the scene's law reached every pair"
        );
        let (mu0, f) = hopf(&vd);
        let (still, f_still) = hopf(&frozen(&vd));
        eprintln!(
            "r {r}, v0 {v0}: mu0 {mu0:.8} ({f:.3} Hz), frozen {still:.8} ({f_still:.3} Hz), penalty-coulomb {:.8}",
            named.0
        );
        // The same mode goes unstable (the slope shifts it, it does not pick another).
        assert!((f / named.1 - 1.0).abs() < 1e-2, "{f} Hz vs {} Hz", named.1);
        // μ0 is refined to 1e-8; the slope's shift is far above that.
        if r > 1.0 {
            assert!(mu0 < still - 1e-6, "falling: {mu0} vs frozen {still}");
        } else {
            assert!(mu0 > still + 1e-6, "rising: {mu0} vs frozen {still}");
        }
    }
}

#[test]
fn a_law_the_scene_cannot_read_is_refused_with_its_key_and_line() {
    // A misspelt kind, a missing parameter, a non-positive one, an unknown key: all name
    // `contact.law` at its line and say what it takes.
    for law in [
        "\"coulomb\"",
        "{ kind = \"velocity-dependent\", static_ratio = 1.2 }",
        "{ kind = \"velocity-dependent\", static_ratio = -1.0, decay_speed_m_per_s = 0.1 }",
        "{ kind = \"velocity-dependent\", static_ratio = 1.2, decay_speed_m_per_s = 0.1, v1 = 2 }",
    ] {
        let s = scene(law);
        let line = s
            .text
            .lines()
            .position(|l| l.starts_with("law = "))
            .unwrap()
            + 1;
        let e = s.contact_law().unwrap_err().to_string();
        assert!(
            e.contains(&format!(":{line}: contact.law: must be")),
            "{law}: {e}"
        );
    }
    // Velocity-dependent friction without the disc's speed: told where to give it.
    let s =
        common::bundled_scene_with("coarse", &format!("law = {}", velocity_dependent(1.2, 0.1)));
    let e = s.contact_law().unwrap_err().to_string();
    assert!(e.contains("[rotation] rpm"), "{e}");
}
