//! `[contact] stick_slip`: the law that replaces permanent sliding where a limit cycle's
//! sliding margin falls below 1 (`squeal branch`, `squeal chbm`, `squeal run`).
//!
//! `stick_slip = "regularized"` (the default): each pair's element made to stick,
//! `F_t(|v|) tanh(v / v_reg)` with `v_reg` a twentieth of the slowest pair's disc speed
//! (`squeal_brake::contact::Sticking`). `stick_slip = "dlft"`, or
//! `{ kind = "dlft", epsilon_factor = 1.0 }`: exact Coulomb stick–slip by the dynamic
//! Lagrangian frequency–time method (`squeal_brake::contact::dlft`), its penalty the default
//! times `epsilon_factor` (> 0; the converged cycle does not depend on it). Both need the
//! disc's speed; DLFT needs the paper's element (`law = "penalty-coulomb"`).

use crate::{Result, Scene, StickSlipSetting};

/// The usage line of the key.
const USAGE: &str = "must be \"regularized\", \"dlft\" or { kind = \"dlft\", epsilon_factor = 1.0 } (epsilon_factor > 0)";

impl Scene {
    /// `[contact] stick_slip` (module documentation): the default when absent, an error naming
    /// the key and what to write for a bad value.
    pub fn stick_slip_law(&self) -> Result<StickSlipSetting> {
        let Some(v) = &self.file.contact.stick_slip else {
            return Ok(StickSlipSetting::Regularized);
        };
        let bad = || self.error_at("contact.stick_slip", v, USAGE);
        match v.get_ref() {
            toml::Value::String(s) if s == "regularized" => Ok(StickSlipSetting::Regularized),
            toml::Value::String(s) if s == "dlft" => Ok(StickSlipSetting::Dlft {
                epsilon_factor: 1.0,
            }),
            toml::Value::Table(t) => {
                let known = ["kind", "epsilon_factor"];
                let kind = t.get("kind").and_then(toml::Value::as_str);
                let factor = match t.get("epsilon_factor") {
                    None => Some(1.0),
                    Some(x) => x
                        .as_float()
                        .or(x.as_integer().map(|i| i as f64))
                        .filter(|x| x.is_finite() && *x > 0.0),
                };
                match (kind, factor) {
                    (Some("dlft"), Some(f)) if t.keys().all(|k| known.contains(&k.as_str())) => {
                        Ok(StickSlipSetting::Dlft { epsilon_factor: f })
                    }
                    (Some("regularized"), _) if t.len() == 1 => Ok(StickSlipSetting::Regularized),
                    _ => Err(bad()),
                }
            }
            _ => Err(bad()),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::{Scene, StickSlipSetting};
    use std::path::Path;

    /// The bundled scene with `stick_slip = value` in `[contact]`.
    fn law(value: &str) -> crate::Result<StickSlipSetting> {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/brake.toml");
        let text = std::fs::read_to_string(&path).unwrap();
        let text = text.replace("[contact]\n", &format!("[contact]\nstick_slip = {value}\n"));
        Scene::parse(&path, text)?.stick_slip_law()
    }

    #[test]
    fn the_stick_slip_law_is_read_and_bad_values_name_the_key() {
        assert_eq!(
            law("\"regularized\"").unwrap(),
            StickSlipSetting::Regularized
        );
        assert_eq!(
            law("\"dlft\"").unwrap(),
            StickSlipSetting::Dlft {
                epsilon_factor: 1.0
            }
        );
        assert_eq!(
            law("{ kind = \"dlft\", epsilon_factor = 4 }").unwrap(),
            StickSlipSetting::Dlft {
                epsilon_factor: 4.0
            }
        );
        for bad in [
            "\"exact\"",
            "{ kind = \"dlft\", epsilon_factor = 0.0 }",
            "{ kind = \"dlft\", eps = 1 }",
        ] {
            let e = law(bad).unwrap_err().to_string();
            assert!(
                e.contains("contact.stick_slip") && e.contains("dlft"),
                "{e}"
            );
        }
    }
}
