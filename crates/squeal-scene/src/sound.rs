//! `[sound]`: where the limit cycles are heard and in what air.
//!
//! ```toml
//! [sound]
//! microphones = [[0.0, 0.354, 0.353]]  # positions in the meshes' frame, in the [units] length;
//!                                      # leave out for the default (0.5 m from the disc's centre,
//!                                      # 45 degrees off its axis towards the pad)
//! air_density = 1.2                    # kg/m^3 whatever the [units] (default 1.2: 20 °C, 1 atm)
//! speed_of_sound = 343.0               # m/s whatever the [units] (default 343)
//! radiating = ["disc"]                 # the parts whose surfaces radiate (default: the disc
//!                                      # and every pad, each pad less its friction face)
//! ```
//!
//! The command lines' `--mic x,y,z` (metres) replaces the scene's microphones.

use crate::{Result, Scene};
use serde::Deserialize;
use toml::Spanned;

/// Air density (kg/m³) at about 20 °C and 1 atm.
pub const DEFAULT_AIR_DENSITY: f64 = 1.2;
/// Speed of sound (m/s) in that air.
pub const DEFAULT_SPEED_OF_SOUND: f64 = 343.0;

/// `[sound]` as written.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct SoundSection {
    /// Microphone positions in the `[units]` length.
    pub microphones: Option<Spanned<Vec<[f64; 3]>>>,
    /// kg/m³.
    pub air_density: Option<Spanned<f64>>,
    /// m/s.
    pub speed_of_sound: Option<Spanned<f64>>,
    /// Part names (`"disc"`, the pads' names).
    pub radiating: Option<Spanned<Vec<String>>>,
}

/// What `[sound]` asks for, in SI.
#[derive(Clone, Debug, PartialEq)]
pub struct SoundSetting {
    /// Microphone positions (m); empty: the pipeline's default microphone.
    pub microphones: Vec<[f64; 3]>,
    /// Air density (kg/m³).
    pub air_density: f64,
    /// Speed of sound (m/s).
    pub speed_of_sound: f64,
    /// The parts whose surfaces radiate; `None`: all of them.
    pub radiating: Option<Vec<String>>,
}

impl Scene {
    /// `[sound]` in SI, checked: finite microphone coordinates; an air density in (0, 100]
    /// kg/m³ and a speed of sound in (0, 10000] m/s (air is 1.2 and 343; larger values are
    /// another medium or a unit mistake).
    pub fn sound(&self) -> Result<SoundSetting> {
        let s = &self.file.sound;
        let mut microphones = Vec::new();
        if let Some(v) = &s.microphones {
            let scale = self.length_unit()?;
            if v.get_ref().is_empty() {
                return Err(self.error_at(
                    "sound.microphones",
                    v,
                    "is empty: give at least one [x, y, z], or leave the key out for the default",
                ));
            }
            for p in v.get_ref() {
                if !p.iter().all(|x| x.is_finite()) {
                    return Err(self.error_at(
                        "sound.microphones",
                        v,
                        "has a coordinate that is not a finite number",
                    ));
                }
                microphones.push(p.map(|x| x * scale));
            }
        }
        let value = |key: &str, v: &Option<Spanned<f64>>, default: f64, max: f64, unit: &str| {
            let Some(v) = v else { return Ok(default) };
            let x = *v.get_ref();
            if x > 0.0 && x <= max {
                Ok(x)
            } else {
                Err(self.error_at(
                    key,
                    v,
                    format!(
                        "must be positive and at most {max} {unit} (got {x}; air is {default})"
                    ),
                ))
            }
        };
        let radiating = match &s.radiating {
            None => None,
            Some(v) => {
                let pads = self.pads()?;
                let known = |n: &str| n == "disc" || pads.iter().any(|(p, _)| p == n);
                if v.get_ref().is_empty() {
                    return Err(self.error_at(
                        "sound.radiating",
                        v,
                        "is empty: name at least one part, or leave the key out for all",
                    ));
                }
                if let Some(bad) = v.get_ref().iter().find(|n| !known(n)) {
                    let names: Vec<&str> = std::iter::once("disc")
                        .chain(pads.iter().map(|(p, _)| p.as_str()))
                        .collect();
                    return Err(self.error_at(
                        "sound.radiating",
                        v,
                        format!(
                            "'{bad}' is not a part of this brake (its parts: {})",
                            names.join(", ")
                        ),
                    ));
                }
                Some(v.get_ref().clone())
            }
        };
        Ok(SoundSetting {
            radiating,
            microphones,
            air_density: value(
                "sound.air_density",
                &s.air_density,
                DEFAULT_AIR_DENSITY,
                100.0,
                "kg/m^3",
            )?,
            speed_of_sound: value(
                "sound.speed_of_sound",
                &s.speed_of_sound,
                DEFAULT_SPEED_OF_SOUND,
                1.0e4,
                "m/s",
            )?,
        })
    }
}
