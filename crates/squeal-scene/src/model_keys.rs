//! Typed values of `[model]`, `[damping]`, `[piston]` and `[stability]` for the stages that
//! read them, so that nothing outside this crate reads the TOML (issue 19, item 1): the meshes
//! resolved against the scene's folder, the interface as an enum, where a value came from
//! (`file:line` or the default) and errors placed at a key's line.
//! Derived scenes (the studies' variants) are made by the typed setters of [`crate::variant`].

use crate::{Result, Scene, SceneError};
use std::path::PathBuf;
use toml::Spanned;

/// The named keys whose line an error of a later stage can point at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Key {
    /// `[contact] initial_gap`
    InitialGap,
    /// `[contact] normal`
    ContactNormal,
    /// `[damping] pair`
    DampingPair,
    /// `[damping] pair_ratios`
    DampingPairRatios,
    /// `[damping] global_ratio`
    DampingGlobalRatio,
    /// `[sound] microphones`
    Microphones,
}

impl Key {
    /// The key as written in a scene (`section.key`).
    pub fn name(self) -> &'static str {
        match self {
            Key::InitialGap => "contact.initial_gap",
            Key::ContactNormal => "contact.normal",
            Key::DampingPair => "damping.pair",
            Key::DampingPairRatios => "damping.pair_ratios",
            Key::DampingGlobalRatio => "damping.global_ratio",
            Key::Microphones => "sound.microphones",
        }
    }
}

impl Scene {
    /// The disc's mesh file, resolved against the scene's folder.
    pub fn disc_mesh(&self) -> PathBuf {
        self.resolve(&self.file.model.disc)
    }

    /// The pads' names and mesh files, resolved against the scene's folder (see
    /// [`Scene::pads`] for the order).
    pub fn pad_meshes(&self) -> Result<Vec<(String, PathBuf)>> {
        Ok(self
            .pads()?
            .into_iter()
            .map(|(n, p)| (n, self.resolve(&p)))
            .collect())
    }

    /// `[model] disc_elset`: the disc's element sets in its file, when the file holds an
    /// assembly (empty: the whole file is the disc).
    pub fn disc_elset(&self) -> Vec<String> {
        elset_names(self.file.model.disc_elset.as_ref())
    }

    /// The element sets of pad `pad` in its file (`[model] pad_elset` for a one-pad brake,
    /// `[pads.<name>] elset` otherwise), when the file holds an assembly (empty: the whole
    /// file).
    pub fn pad_elset(&self, pad: &str) -> Vec<String> {
        let f = &self.file;
        elset_names(match f.pads.get(pad) {
            Some(p) => p.elset.as_ref(),
            None => f.model.pad_elset.as_ref(),
        })
    }

    /// Checks the element-set keys: a name or a list of names, and `[model] pad_elset` only
    /// with `[model] pad`.
    pub(crate) fn check_elsets(&self) -> Result<()> {
        let f = &self.file;
        let given = [
            ("model.disc_elset", f.model.disc_elset.as_ref()),
            ("model.pad_elset", f.model.pad_elset.as_ref()),
        ]
        .into_iter()
        .chain(f.pads.values().map(|p| ("pads.elset", p.elset.as_ref())));
        for (key, v) in given {
            if let Some(v) = v {
                let names = elset_names(Some(v));
                let count = match v.get_ref() {
                    toml::Value::Array(a) => a.len(),
                    _ => 1,
                };
                if names.is_empty() || names.len() != count {
                    return Err(self.error_at(
                        key,
                        v,
                        "must name an element set of the mesh file, or be a list of them",
                    ));
                }
            }
        }
        if let Some(v) = &f.model.pad_elset
            && f.model.pad.is_none()
        {
            return Err(self.error_at(
                "model.pad_elset",
                v,
                "names the element set of [model] pad, which is not given: with [pads.<name>] tables give elset = \"...\" in each",
            ));
        }
        Ok(())
    }

    /// `[model] modes`: the fixed-interface modes kept per part.
    pub fn modes_per_part(&self) -> usize {
        *self.file.model.modes.get_ref()
    }

    /// `[model] rom`, resolved against the scene's folder, if the scene names one.
    pub fn rom_file(&self) -> Option<PathBuf> {
        self.file.model.rom.as_ref().map(|p| self.resolve(p))
    }

    /// `[damping] global_ratio` (default 1 %).
    pub fn damping_global_ratio(&self) -> f64 {
        *self.file.damping.global_ratio.get_ref()
    }

    /// `[damping] pair_ratios` if given.
    pub fn damping_pair_ratios(&self) -> Option<[f64; 2]> {
        self.file.damping.pair_ratios.as_ref().map(|r| *r.get_ref())
    }

    /// `[stability] band_hz` if given.
    pub fn band_hz(&self) -> Option<(f64, f64)> {
        self.file
            .stability
            .band_hz
            .as_ref()
            .map(|b| (b.get_ref()[0], b.get_ref()[1]))
    }

    /// `[piston] line_pressure_bar` and `area` (m², or the `[units]` area) as written.
    pub fn piston_pressure_and_area(&self) -> (f64, f64) {
        let p = &self.file.piston;
        (*p.line_pressure_bar.get_ref(), *p.area.get_ref())
    }

    /// Where `key`'s value came from, for outputs: `file:line`, or `the default: <file> gives
    /// no [section] key` when the scene leaves it out.
    pub fn origin(&self, key: Key) -> String {
        match self.span_of(key) {
            Some(span) if span != (0..0) => {
                format!("{}:{}", self.path.display(), self.line(span.start))
            }
            _ => {
                let (section, name) = key.name().split_once('.').unwrap_or(("", key.name()));
                format!(
                    "the default: {} gives no [{section}] {name}",
                    self.path.display()
                )
            }
        }
    }

    /// An error of a later stage caused by `key`'s value, at the key's line (the scene as a
    /// whole when the key is not written).
    pub fn error_at_key(&self, key: Key, message: impl std::fmt::Display) -> SceneError {
        match self.span_of(key).filter(|s| *s != (0..0)) {
            Some(span) => self.error_at(key.name(), &Spanned::new(span, ()), message),
            None => self.section_error(format!("{}: {message}", key.name())),
        }
    }

    fn span_of(&self, key: Key) -> Option<std::ops::Range<usize>> {
        let f = &self.file;
        match key {
            Key::InitialGap => f.contact.initial_gap.as_ref().map(|v| v.span()),
            Key::ContactNormal => f.contact.normal.as_ref().map(|v| v.span()),
            Key::DampingPair => Some(f.damping.pair.span()),
            Key::DampingPairRatios => f.damping.pair_ratios.as_ref().map(|v| v.span()),
            Key::DampingGlobalRatio => Some(f.damping.global_ratio.span()),
            Key::Microphones => f.sound.microphones.as_ref().map(|v| v.span()),
        }
    }

    fn line(&self, offset: usize) -> usize {
        self.text[..offset.min(self.text.len())]
            .matches('\n')
            .count()
            + 1
    }
}

/// The names of an element-set value: a string, or a list of non-empty strings.
fn elset_names(v: Option<&Spanned<toml::Value>>) -> Vec<String> {
    match v.map(|v| v.get_ref()) {
        Some(toml::Value::String(s)) if !s.trim().is_empty() => vec![s.trim().to_string()],
        Some(toml::Value::Array(a)) => a
            .iter()
            .filter_map(|x| x.as_str().map(str::trim).filter(|s| !s.is_empty()))
            .map(String::from)
            .collect(),
        _ => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bundled scene, as if it were /s/brake.toml, with `edit` applied to its text.
    fn bundled(edit: impl Fn(String) -> String) -> Scene {
        let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
        let text = std::fs::read_to_string(dir.join("brake.toml")).expect("the bundled scene");
        Scene::parse(std::path::Path::new("/s/brake.toml"), edit(text)).unwrap()
    }

    #[test]
    fn meshes_and_origins() {
        let s = bundled(|t| t);
        assert_eq!(s.disc_mesh(), PathBuf::from("/s/disc_medium.inp"));
        // The line of `global_ratio = 0.01` in meshes/brake.toml.
        let line = s
            .text
            .lines()
            .position(|l| l.starts_with("global_ratio"))
            .unwrap()
            + 1;
        assert_eq!(
            s.origin(Key::DampingGlobalRatio),
            format!("/s/brake.toml:{line}")
        );
        let e = s
            .error_at_key(Key::DampingGlobalRatio, "too high")
            .to_string();
        assert!(e.contains(&format!("/s/brake.toml:{line}")), "{e}");
        assert_eq!(s.damping_pair_ratios(), Some([0.001, 0.001]));
        // Left out: the default, and an error about the key names the file.
        let s = bundled(|t| t.replace("pair_ratios = [0.001, 0.001]", ""));
        assert_eq!(
            s.origin(Key::DampingPairRatios),
            "the default: /s/brake.toml gives no [damping] pair_ratios"
        );
        let e = s.error_at_key(Key::DampingPairRatios, "needed").to_string();
        assert!(
            e.contains("/s/brake.toml") && e.contains("damping.pair_ratios"),
            "{e}"
        );
    }
}
