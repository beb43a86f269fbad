//! `[contact] law = { kind = "regularized-coulomb", ... }`: the contact law that sticks and
//! slips (`squeal_brake::contact::RegularizedCoulomb`).
//!
//! Keys (all in m/s or dimensionless, whatever the `[units]`):
//! `regularization_speed_m_per_s` (`v_reg`, default 1e-3 m/s: the friction force reaches
//! 99.9 % of `μ F_n` at 3.8 `v_reg`), `static_ratio` (`μ_s / μ ≥ 1`, default 1) and
//! `static_speed_m_per_s` (`v_s`, default 10 `v_reg`, over which the coefficient falls from
//! `μ_s` to `μ`). The law depends on the slip velocity, so the scene must give the disc's
//! speed (`[rotation] rpm`, or `vehicle_speed_kmh` and `rolling_radius`).

use crate::{ContactLawSetting, Result, Scene};

/// The usage line of the law's table.
const USAGE: &str = "{ kind = \"regularized-coulomb\", regularization_speed_m_per_s = 1e-3, static_ratio = 1.0, static_speed_m_per_s = 1e-2 } (every key but kind optional; speeds > 0 in m/s, static_ratio >= 1)";

/// Default regularization velocity (m/s), as `squeal_brake::contact::DEFAULT_REGULARIZATION_SPEED`.
const DEFAULT_REGULARIZATION_SPEED: f64 = 1.0e-3;

impl Scene {
    /// The regularized Coulomb law if `[contact] law` is a table of that kind: `None` for any
    /// other law, an error naming the key and what to write for a bad value.
    pub(crate) fn regularized_coulomb_law(&self) -> Option<Result<ContactLawSetting>> {
        let v = self.file.contact.law.as_ref()?;
        let table = v.get_ref().as_table()?;
        if table.get("kind").and_then(toml::Value::as_str) != Some("regularized-coulomb") {
            return None;
        }
        let known = [
            "kind",
            "regularization_speed_m_per_s",
            "static_ratio",
            "static_speed_m_per_s",
        ];
        let number = |key: &str, default: f64| match table.get(key) {
            None => Some(default),
            Some(x) => x
                .as_float()
                .or(x.as_integer().map(|i| i as f64))
                .filter(|x| x.is_finite() && *x > 0.0),
        };
        let v_reg = number("regularization_speed_m_per_s", DEFAULT_REGULARIZATION_SPEED);
        let ratio = number("static_ratio", 1.0).filter(|r| *r >= 1.0);
        let v_s = v_reg.and_then(|v| number("static_speed_m_per_s", 10.0 * v));
        let all_known = table.keys().all(|k| known.contains(&k.as_str()));
        let (Some(v_reg), Some(ratio), Some(v_s), true) = (v_reg, ratio, v_s, all_known) else {
            return Some(Err(self.error_at(
                "contact.law",
                v,
                format!("must be {USAGE}"),
            )));
        };
        Some(match self.disc_angular_speed() {
            Err(e) => Err(e),
            Ok(None) => Err(self.error_at(
                "contact.law",
                v,
                "regularized Coulomb friction needs the disc's speed: give [rotation] rpm (or vehicle_speed_kmh and rolling_radius)",
            )),
            Ok(Some(_)) => Ok(ContactLawSetting::RegularizedCoulomb {
                regularization_speed: v_reg,
                static_ratio: ratio,
                static_speed: v_s,
            }),
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::{ContactLawSetting, Scene};
    use std::path::Path;

    /// The bundled scene with `law` in `[contact]` and, if `speed`, 5 km/h on a 0.3 m wheel.
    fn scene(law: &str, speed: bool) -> crate::Result<Scene> {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/brake.toml");
        let mut text = std::fs::read_to_string(&path).unwrap();
        text = text.replace("[contact]\n", &format!("[contact]\nlaw = {law}\n"));
        if speed {
            text = text.replace(
                "sense = \"clockwise\"\n",
                "sense = \"clockwise\"\nvehicle_speed_kmh = 5.0\nrolling_radius = 0.3\n",
            );
        }
        Scene::parse(&path, text)
    }

    #[test]
    fn the_regularized_law_is_read_with_its_defaults_and_bad_values_name_the_key() {
        let law = |text: &str, speed: bool| scene(text, speed).and_then(|s| s.contact_law());
        // Defaults: v_reg = 1 mm/s, one coefficient, v_s = 10 v_reg (exact constants).
        assert_eq!(
            law("{ kind = \"regularized-coulomb\" }", true).unwrap(),
            ContactLawSetting::RegularizedCoulomb {
                regularization_speed: 1e-3,
                static_ratio: 1.0,
                static_speed: 1e-2,
            }
        );
        assert_eq!(
            law(
                "{ kind = \"regularized-coulomb\", regularization_speed_m_per_s = 1e-4, static_ratio = 1.25, static_speed_m_per_s = 5e-3 }",
                true
            )
            .unwrap(),
            ContactLawSetting::RegularizedCoulomb {
                regularization_speed: 1e-4,
                static_ratio: 1.25,
                static_speed: 5e-3,
            }
        );
        for bad in [
            "{ kind = \"regularized-coulomb\", static_ratio = 0.9 }",
            "{ kind = \"regularized-coulomb\", regularization_speed_m_per_s = -1.0 }",
            "{ kind = \"regularized-coulomb\", v1 = 2 }",
        ] {
            let e = law(bad, true).unwrap_err().to_string();
            assert!(
                e.contains("contact.law") && e.contains("regularized-coulomb"),
                "{e}"
            );
        }
        let e = law("{ kind = \"regularized-coulomb\" }", false)
            .unwrap_err()
            .to_string();
        assert!(e.contains("disc's speed"), "{e}");
    }
}
