//! Variants of a scene for the studies: the same scene with its meshes at another level, another
//! contact interface or patch grid, another number of kept modes, or its reduced model kept
//! elsewhere. Each is a typed change of the parsed scene ([`Scene::variant`] re-reads the text
//! the scene came from, then the setters change one field each), never an edit of the TOML.
//!
//! A value set here was not written in the file: it carries the empty span, like a default, so
//! that an error about it names the scene file but no line (there is none to name).

use crate::{Result, Scene, SceneError};
use std::path::{Path, PathBuf};
use toml::Spanned;

/// The contact interface of `[model] interface`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interface {
    /// Each contact point the mean motion of one cell of the patch grid (the default).
    Patch,
    /// Each contact point one mesh node (the paper's).
    Node,
    /// Every node of the pad's friction face paired with its projection on the disc face.
    Nodal,
}

impl Interface {
    /// The name the scene file uses.
    pub fn name(self) -> &'static str {
        match self {
            Interface::Patch => "patch",
            Interface::Node => "node",
            Interface::Nodal => "nodal",
        }
    }
}

/// The mesh levels the bundled meshes come in, coarsest first (`disc_coarse.inp`, ...).
pub const MESH_LEVELS: [&str; 3] = ["coarse", "medium", "fine"];

/// `dir/disc_medium.inp` at level `coarse`: `dir/disc_coarse.inp`; `None` for a file not named
/// `<name>_<level>.<ext>`.
pub fn level_path(p: &Path, level: &str) -> Option<PathBuf> {
    let stem = p.file_stem()?.to_string_lossy().into_owned();
    let (base, _) = stem.rsplit_once('_')?;
    let ext = p
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    Some(p.with_file_name(format!("{base}_{level}{ext}")))
}

/// The level of a mesh file `<name>_<level>.<ext>`: the part of its stem after the last `_`.
fn level_of(p: &Path) -> Option<String> {
    let stem = p.file_stem()?.to_string_lossy().into_owned();
    stem.rsplit_once('_').map(|(_, l)| l.to_string())
}

impl Scene {
    /// An independent copy of the scene, parsed again from its text.
    pub fn variant(&self) -> Result<Scene> {
        Scene::parse(&self.path, self.text.clone())
    }

    /// The contact interface of `[model] interface`.
    pub fn interface(&self) -> Result<Interface> {
        let i = &self.file.model.interface;
        match i.get_ref().as_str() {
            "patch" => Ok(Interface::Patch),
            "node" => Ok(Interface::Node),
            "nodal" => Ok(Interface::Nodal),
            other => Err(self.error_at(
                "model.interface",
                i,
                format!("\"{other}\" is not an interface: give \"patch\", \"node\" or \"nodal\""),
            )),
        }
    }

    /// Sets `[model] interface`.
    pub fn set_interface(&mut self, interface: Interface) {
        self.file.model.interface = Spanned::new(0..0, interface.name().to_string());
    }

    /// Sets `[model] modes`, the fixed-interface modes kept per part.
    pub fn set_modes(&mut self, modes: usize) {
        self.file.model.modes = Spanned::new(0..0, modes);
    }

    /// Sets `[sets] patch_grid` (radial, angular), checked as [`Scene::patch_grid`] checks it.
    pub fn set_patch_grid(&mut self, grid: [usize; 2]) -> Result<()> {
        self.file.sets.patch_grid = Some(Spanned::new(0..0, grid));
        self.patch_grid().map(|_| ())
    }

    /// Sets `[model] rom`, where the reduced model is kept (made absolute, so that it does not
    /// depend on the scene's folder).
    pub fn set_rom(&mut self, rom: &Path) {
        self.file.model.rom = Some(std::path::absolute(rom).unwrap_or_else(|_| rom.to_path_buf()));
    }

    /// The mesh level of the scene: the common `_<level>` suffix of its disc's and pads' mesh
    /// files, when they all have the same one.
    pub fn mesh_level(&self) -> Result<Option<String>> {
        let files = self.mesh_files()?;
        let levels: Vec<Option<String>> = files.iter().map(|p| level_of(p)).collect();
        Ok(match levels.first() {
            Some(Some(l)) if levels.iter().all(|x| x.as_deref() == Some(l.as_str())) => {
                Some(l.clone())
            }
            _ => None,
        })
    }

    /// The mesh files of the scene at `level` (disc, then each pad), whether they exist or not.
    pub fn level_mesh_files(&self, level: &str) -> Result<Vec<PathBuf>> {
        self.mesh_files()?
            .iter()
            .map(|p| {
                level_path(p, level).ok_or_else(|| SceneError::Section {
                    path: self.path.clone(),
                    message: format!(
                        "{}: a study of mesh levels needs mesh files named <name>_<level> (e.g. disc_medium.inp)",
                        p.display()
                    ),
                })
            })
            .collect()
    }

    /// Sets the disc's and every pad's mesh to the file of the same name at `level` (absolute
    /// paths); each must exist.
    pub fn set_mesh_level(&mut self, level: &str) -> Result<()> {
        let abs = |p: PathBuf| std::path::absolute(&p).unwrap_or(p);
        let files = self.level_mesh_files(level)?;
        if let Some(missing) = files.iter().find(|p| !p.is_file()) {
            return Err(SceneError::Section {
                path: self.path.clone(),
                message: format!(
                    "mesh file not found at level {level}: {} (the scene's meshes must end in _<level>)",
                    missing.display()
                ),
            });
        }
        let mut files = files.into_iter().map(abs);
        if let Some(p) = files.next() {
            self.file.model.disc = p;
        }
        if self.file.model.pad.is_some() {
            self.file.model.pad = files.next();
        } else {
            // [pads] in the order Scene::pads lists them (the map's).
            for (pad, p) in self.file.pads.values_mut().zip(files) {
                pad.mesh = p;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Scene {
        let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
        Scene::read(&dir.join("brake.toml")).expect("the bundled scene")
    }

    #[test]
    fn a_variant_changes_the_typed_fields_and_leaves_the_scene_alone() {
        let s = scene();
        assert_eq!(s.mesh_level().unwrap().as_deref(), Some("medium"));
        let mut v = s.variant().unwrap();
        v.set_mesh_level("coarse").unwrap();
        v.set_interface(Interface::Nodal);
        v.set_modes(75);
        v.set_patch_grid([3, 5]).unwrap();
        assert_eq!(v.mesh_level().unwrap().as_deref(), Some("coarse"));
        assert!(v.file.model.disc.ends_with("meshes/disc_coarse.inp"));
        assert!(v.file.model.disc.is_absolute());
        assert_eq!(v.interface().unwrap(), Interface::Nodal);
        assert_eq!(*v.file.model.modes.get_ref(), 75);
        assert_eq!(v.patch_grid().unwrap(), [3, 5]);
        // The original is untouched.
        assert_eq!(s.interface().unwrap(), Interface::Patch);
        assert_eq!(s.patch_grid().unwrap(), [3, 3]);
        assert_eq!(*s.file.model.modes.get_ref(), 50);
        // A level without files and a bad grid are errors naming what to do.
        let e = v.set_mesh_level("huge").unwrap_err().to_string();
        assert!(e.contains("disc_huge.inp") && e.contains("_<level>"), "{e}");
        let e = v.set_patch_grid([0, 3]).unwrap_err().to_string();
        assert!(e.contains("sets.patch_grid"), "{e}");
    }

    #[test]
    fn level_paths_replace_the_last_suffix() {
        let p = Path::new("/m/disc_two_medium.inp");
        assert_eq!(
            level_path(p, "fine"),
            Some(PathBuf::from("/m/disc_two_fine.inp"))
        );
        assert_eq!(level_path(Path::new("/m/disc.inp"), "fine"), None);
    }
}
