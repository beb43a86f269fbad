//! Scene files: one TOML file describing a brake study (meshes, reduction, contact, friction,
//! piston load, damping, analyses). Paths are relative to the scene file.
//!
//! `[units]`, `[sets.disc]`, `[sets.pad]` and `[materials.<SET>]` are read by [`sets`]: the
//! unit system of the meshes and of the keys without a unit in their name, the node sets of
//! the reduction by name or by geometry, and materials by element set.
//!
//! Unknown keys are errors (a misspelt key must not be silently ignored); values that parse but
//! make no physical sense are errors naming the file, the key and its line ([`SceneError`]).
//! Derived values that need a little arithmetic live here too: the least-squares fit of the
//! pad's compression curve to eq (8)'s `p = κ_l δ + κ_nl δ³` ([`fit_cubic`]), friction
//! ranges ([`parse_range`]), the disc's rotation ([`Scene::rotation`]) and how the disc slides
//! under the pad ([`Scene::sliding`]).
//!
//! **Rotation.** `[rotation]` gives the disc's axis (`axis`, a direction, and `point`, a point
//! on it, the origin by default), the sense (`sense = "counterclockwise"` or `"clockwise"`,
//! as seen from the tip of `axis` looking back along it: counterclockwise is the right-hand
//! rule about `axis`) and optionally the speed (`rpm`, or `vehicle_speed_kmh` with
//! `rolling_radius`). Nothing else assumes the disc turns about z or through the origin: the
//! contact normals come from the mesh (the disc face under each contact point), the patch grid
//! is cut about this axis, and by default the disc slides under the pad along the tangent of
//! its rotation at each contact point (`[friction] sliding = "tangent"`, the convention of
//! Abaqus' `*MOTION` and Ansys' `CMROTATE`). The older `[disc]` section (speed and
//! `axis_origin`, the axis along `contact.normal`, no sense) still reads; a scene with both is
//! refused.

mod checks;
mod model_keys;
pub mod reduction;
pub mod sets;
pub mod variant;
pub use variant::{Interface, MESH_LEVELS, level_path};

pub use model_keys::Key;

pub use checks::{
    HIGH_DAMPING_RATIO, HIGH_LINE_PRESSURE_BAR, HIGH_MU, LARGE_GAP_M, MAX_LINE_PRESSURE_BAR,
};

use serde::Deserialize;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// What is wrong with a scene file, with the file and, where a value is at fault, its key and
/// line.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file cannot be read (the reason is in the message, and not also a `source()`, so
    /// an error chain shows it once).
    #[error("reading scene {}: {error}", path.display())]
    Read {
        path: PathBuf,
        error: std::io::Error,
    },
    /// Not TOML, or not a scene's layout: `file:line:column: message`.
    #[error("{location}: {message}")]
    Syntax { location: String, message: String },
    /// Bytes that are not UTF-8 text, at `file:line`.
    #[error("{location}: not UTF-8 text (save the scene as UTF-8)")]
    Encoding { location: String },
    /// A value at fault: `file:line: key: message` (no line for a default value).
    #[error("{location}: {key}: {message}")]
    Value {
        location: String,
        key: String,
        message: String,
    },
    /// A section that needs one of several keys.
    #[error("{}: {message}", path.display())]
    Section { path: PathBuf, message: String },
}

type Result<T> = std::result::Result<T, SceneError>;

/// Largest angle (degrees) between a `[contact] normal` and the `[rotation] axis` (either
/// way): a disc's braking faces are normal to its axis, so a larger angle is a scene that
/// contradicts itself (the axis or the normal of another orientation of the mesh). The brake
/// checks the normal against the mesh's faces with the same 5 degrees.
pub const NORMAL_AXIS_TOLERANCE_DEG: f64 = 5.0;

/// The scene as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    pub title: Option<String>,
    pub model: ModelSection,
    pub contact: ContactSection,
    pub friction: FrictionSection,
    pub piston: PistonSection,
    #[serde(default)]
    pub damping: DampingSection,
    #[serde(default)]
    pub stability: StabilitySection,
    #[serde(default)]
    pub chbm: ChbmSection,
    /// `[disc]`: the disc's rotation speed, for the sliding check of every limit cycle (the
    /// older form of `[rotation]`).
    #[serde(default)]
    pub disc: DiscSection,
    /// `[rotation]`: the disc's axis, sense and speed.
    pub rotation: Option<RotationSection>,
    /// `[units]`: the unit system of the meshes and of the scene's keys without a unit in
    /// their name (see [`sets`]).
    #[serde(default)]
    pub units: sets::UnitsSection,
    /// `[sets.disc]`, `[sets.pad]`: the node sets the reduction uses, by name or by geometry.
    #[serde(default)]
    pub sets: sets::SetsSection,
    /// `[materials.<ELEMENT_SET>]`: materials by element set, replacing the meshes' own.
    #[serde(default)]
    pub materials: std::collections::BTreeMap<String, sets::MaterialSpec>,
    /// `[pads.<name>]`: the pads of a brake with more than one (instead of `[model] pad`), in
    /// the order of their names.
    #[serde(default)]
    pub pads: std::collections::BTreeMap<String, PadSection>,
    /// `[reduction]`: an interface reduction beyond Craig–Bampton ([`reduction`]).
    #[serde(default)]
    pub reduction: reduction::ReductionSection,
}

/// `[pads.<name>]`: one pad of a brake with several (an inboard pad pushed by the pistons, an
/// outboard pad pulled by the caliper's fingers). Every pad is pressed on the disc by the
/// same clamp force (a floating caliper's fingers react the pistons' force).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PadSection {
    /// Its mesh, relative to the scene.
    pub mesh: PathBuf,
    /// Where the clamp force enters: the pistons' or the fingers' points (a node set or a
    /// rule, as `[sets.pad] pistons`); default `PISTON`.
    pub load: Option<Spanned<toml::Value>>,
    /// Its friction face (default: `[sets.pad] friction_face`, else `CONTACT_FACE`, else the
    /// face towards the disc).
    pub friction_face: Option<Spanned<toml::Value>>,
    /// Its abutments (default: `[sets.pad] abutments`, else `ABUTMENT`).
    pub abutments: Option<Spanned<toml::Value>>,
    /// What its abutments hold (default: `[sets.pad] abutments_hold`, else the plane normal
    /// to the axis).
    pub abutments_hold: Option<Spanned<toml::Value>>,
    /// The disc face it presses on (default: for the first pad `[sets.disc] contact_face`,
    /// else `CONTACT_FACE`; for the others the pad's friction face projected on the disc).
    pub disc_contact_face: Option<Spanned<toml::Value>>,
    /// The disc's contact nodes under it for the node interface (default `CONTACT` for the
    /// first pad, `CONTACT_<NAME>` for the others).
    pub disc_contact: Option<Spanned<String>>,
}

/// `[rotation]`: the axis the disc turns about, the sense, and (optionally) the speed.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotationSection {
    /// Direction of the axis (need not be unit).
    pub axis: Spanned<[f64; 3]>,
    /// A point of the axis (m); the origin by default.
    pub point: Option<Spanned<[f64; 3]>>,
    /// `"counterclockwise"` (the right-hand rule about `axis`) or `"clockwise"`, seen from the
    /// tip of `axis`.
    pub sense: Spanned<String>,
    /// Disc speed (revolutions per minute).
    pub rpm: Option<Spanned<f64>>,
    /// Vehicle speed (km/h); needs `rolling_radius`.
    pub vehicle_speed_kmh: Option<Spanned<f64>>,
    /// The wheel's effective rolling radius (m): the disc turns at `v / r`.
    pub rolling_radius: Option<Spanned<f64>>,
}

/// The disc's rotation, resolved: `ω = sense · Ω · axis` about the line through `point`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rotation {
    /// A point of the axis (m).
    pub point: [f64; 3],
    /// Unit direction of the axis.
    pub axis: [f64; 3],
    /// +1 when the disc turns by the right-hand rule about `axis` (counterclockwise seen from
    /// its tip), -1 the other way; 0 when the scene gives no sense (the older `[disc]`).
    pub sense: f64,
    /// Angular speed `Ω` (rad/s), when the scene gives one.
    pub angular_speed: Option<f64>,
}

/// How the disc's surface slides under the pad.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sliding {
    /// Along the tangent of the rotation at each contact point (needs `[rotation]`).
    Tangent,
    /// Along one global unit direction at every point (the paper's choice).
    Global([f64; 3]),
}

/// `[disc]`: how fast the disc turns, as `rpm` or as `vehicle_speed_kmh` with the wheel's
/// `rolling_radius`; optional (without it the sliding margin of a cycle is not reported). The
/// disc turns about the axis through `axis_origin` along `contact.normal`; a pair's surface
/// speed is the angular speed times its distance from that axis.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct DiscSection {
    /// Disc speed (revolutions per minute).
    pub rpm: Option<Spanned<f64>>,
    /// Vehicle speed (km/h); needs `rolling_radius`.
    pub vehicle_speed_kmh: Option<Spanned<f64>>,
    /// The wheel's effective rolling radius (m, or the `[units]` length): the disc turns at
    /// `v / r`.
    pub rolling_radius: Option<Spanned<f64>>,
    /// A point of the disc's axis (m, or the `[units]` length); the origin by default.
    pub axis_origin: Option<Spanned<[f64; 3]>>,
}

/// `[chbm]`: the scene's limit cycle, the one every command computes (read it through
/// [`Scene::cycle`]).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChbmSection {
    /// Friction of the limit cycle as a multiple of the Hopf point μ0.
    pub mu_ratio: Option<Spanned<f64>>,
    /// Friction of the limit cycle itself.
    pub mu: Option<Spanned<f64>>,
    #[serde(default = "default_harmonics")]
    pub harmonics: Spanned<usize>,
}

impl Default for ChbmSection {
    fn default() -> Self {
        Self {
            mu_ratio: None,
            mu: None,
            harmonics: default_harmonics(),
        }
    }
}

/// The friction of a scene's limit cycle when the scene gives none: just above the Hopf
/// point, the paper's choice for its Table 1.
pub const DEFAULT_CYCLE_MU_RATIO: f64 = 1.02;

/// Where a scene's limit cycle is computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CycleFriction {
    /// At this friction coefficient.
    Mu(f64),
    /// At this multiple of the Hopf point μ0.
    Ratio(f64),
}

impl CycleFriction {
    /// The friction coefficient, given the Hopf point `mu0` (asked for only by a ratio).
    pub fn mu<E>(
        self,
        mu0: impl FnOnce() -> std::result::Result<f64, E>,
    ) -> std::result::Result<f64, E> {
        match self {
            CycleFriction::Mu(m) => Ok(m),
            CycleFriction::Ratio(r) => Ok(r * mu0()?),
        }
    }
}

/// The scene's limit cycle: where, and with how many harmonics (eq 23).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CycleSpec {
    pub at: CycleFriction,
    pub harmonics: usize,
}

fn default_harmonics() -> Spanned<usize> {
    Spanned::new(0..0, 3)
}

/// `[model]`: the meshes and their reduction.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSection {
    pub disc: PathBuf,
    /// The one pad of a one-pad brake; a brake with several pads names them in `[pads]`.
    pub pad: Option<PathBuf>,
    /// `patch` (default) or `node`.
    #[serde(default = "default_interface")]
    pub interface: Spanned<String>,
    /// Fixed-interface modes per part.
    #[serde(default = "default_modes")]
    pub modes: Spanned<usize>,
    /// Where the reduced model is kept (relative to the scene); default: in the output folder.
    pub rom: Option<PathBuf>,
}

fn default_interface() -> Spanned<String> {
    Spanned::new(0..0, "patch".into())
}
fn default_modes() -> Spanned<usize> {
    Spanned::new(0..0, 50)
}

/// `[contact]`: eq (8)'s law and how points pair.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSection {
    /// Normal from the disc into the pad; optional: every pair takes the disc face's normal
    /// from the reduced model, and a normal given here is a check on it.
    pub normal: Option<Spanned<[f64; 3]>>,
    /// Disc and pad points pair when closer than this (m, or the `[units]` length).
    #[serde(default = "default_pairing")]
    pub pairing_tolerance: Spanned<f64>,
    /// A pad compression curve to fit `p = κ_l δ + κ_nl δ³` to.
    pub compression_curve: Option<CompressionCurve>,
    /// Or the stiffnesses per unit area directly (Pa/m, Pa/m³, or the `[units]` stress per
    /// length and per length cubed).
    pub k_linear_per_area: Option<Spanned<f64>>,
    pub k_cubic_per_area: Option<Spanned<f64>>,
    /// Scale factor on both stiffnesses (for studies: 0.7, 1, 1.3).
    #[serde(default = "one")]
    pub stiffness_scale: Spanned<f64>,
    /// Area (m², or the `[units]` area) a contact point stands for where the reduced model
    /// gives none (a node interface on parts without a contact face set).
    pub point_area: Option<Spanned<f64>>,
    /// Initial gap (m; positive: open, negative: interference) of every pair, or a list of
    /// one per pair in pair order; without it each pair's gap is measured from the geometry.
    pub initial_gap: Option<Spanned<toml::Value>>,
    /// `true`: every initial gap is closed (set to zero), as Abaqus' contact adjustment and
    /// Ansys' contact offset do; the geometric gaps are reported as the adjustment.
    pub close_initial_gaps: Option<Spanned<bool>>,
    /// The contact law ([`Scene::contact_law`]): `"penalty-coulomb"` (the default) or a table
    /// `{ kind = "velocity-dependent", static_ratio, decay_speed_m_per_s }`.
    pub law: Option<Spanned<toml::Value>>,
}

/// The contact law a scene asks for (`[contact] law`); both use eq (8)'s penalty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ContactLawSetting {
    /// Coulomb friction, eqs (8)–(10).
    PenaltyCoulomb,
    /// `μ(v) = μ (r + (1 - r)(1 - e^(-v/v0)))` of the sliding speed `v`.
    VelocityDependent {
        /// `r = μ_s / μ_d`.
        static_ratio: f64,
        /// `v0` (m/s).
        decay_speed: f64,
    },
}

/// The pairs' initial gaps a scene asks for (`[contact] initial_gap`, `close_initial_gaps`).
#[derive(Clone, Debug, PartialEq)]
pub enum GapSetting {
    /// Measured from the geometry at pairing (the default).
    Geometric,
    /// One gap (m) for every pair.
    Uniform(f64),
    /// One gap (m) per pair, in pair order.
    PerPair(Vec<f64>),
    /// Every gap closed.
    Closed,
}

fn default_pairing() -> Spanned<f64> {
    Spanned::new(0..0, 1e-3)
}
fn one() -> Spanned<f64> {
    Spanned::new(0..0, 1.0)
}

/// Measured (or assumed) pad compression: contact pressure against closure.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompressionCurve {
    pub pressure_mpa: Spanned<Vec<f64>>,
    pub closure_um: Spanned<Vec<f64>>,
}

/// `[friction]`: eq (9).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSection {
    /// The older place of `[chbm] mu`: the friction of the scene's limit cycle.
    pub mu: Option<Spanned<f64>>,
    /// `"tangent"` (the default: the tangent of the rotation at each contact point) or a
    /// global direction `[x, y, z]`.
    pub sliding: Option<Spanned<toml::Value>>,
    /// The older form of a global `sliding` direction.
    pub sliding_direction: Option<Spanned<[f64; 3]>>,
}

/// `[piston]`: the clamp load.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PistonSection {
    /// Hydraulic line pressure (bar).
    pub line_pressure_bar: Spanned<f64>,
    /// Total piston area (m², or the `[units]` area).
    pub area: Spanned<f64>,
}

/// `[damping]`: eqs (12)–(13).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DampingSection {
    #[serde(default = "default_global")]
    pub global_ratio: Spanned<f64>,
    /// `"auto"` or `[mode1, mode2]` (1-based frictionless mode numbers).
    #[serde(default = "default_pair")]
    pub pair: Spanned<toml::Value>,
    /// Ratios ζ1 (stable Mode 1), ζ2 (unstable Mode 2) added on the pair.
    #[serde(default)]
    pub pair_ratios: Option<Spanned<[f64; 2]>>,
}

impl Default for DampingSection {
    fn default() -> Self {
        Self {
            global_ratio: default_global(),
            pair: default_pair(),
            pair_ratios: None,
        }
    }
}

fn default_global() -> Spanned<f64> {
    Spanned::new(0..0, 0.01)
}
fn default_pair() -> Spanned<toml::Value> {
    Spanned::new(0..0, toml::Value::String("auto".into()))
}

/// `[stability]`.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct StabilitySection {
    /// `"start..end/count"` or a list of values.
    pub mu: Option<Spanned<toml::Value>>,
    /// The band μ0 must lie in (Hz), besides the model's valid band.
    pub band_hz: Option<Spanned<[f64; 2]>>,
}

/// A scene read from a file: the parsed values plus where it came from.
#[derive(Debug)]
pub struct Scene {
    pub path: PathBuf,
    pub text: String,
    pub file: SceneFile,
}

/// `file:line:column` of byte `at` of `text` (1-based, the column in characters), or `file`
/// alone without a place.
fn location(path: &Path, text: &str, at: Option<usize>) -> String {
    let Some(at) = at.map(|a| a.min(text.len())) else {
        return path.display().to_string();
    };
    let before = text.get(..at).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    format!("{}:{line}:{column}", path.display())
}

impl Scene {
    /// Reads and validates a scene file.
    pub fn read(path: &Path) -> Result<Scene> {
        // A regular file of bounded size: not an endless stream such as /dev/zero.
        let bytes = squeal_mesh::file::read_limited(path).map_err(|error| SceneError::Read {
            path: path.to_path_buf(),
            error,
        })?;
        let text = String::from_utf8(bytes).map_err(|e| {
            let good = &e.as_bytes()[..e.utf8_error().valid_up_to()];
            let line = good.iter().filter(|&&b| b == b'\n').count() + 1;
            SceneError::Encoding {
                location: format!("{}:{line}", path.display()),
            }
        })?;
        Self::parse(path, text)
    }

    /// A scene from its text, as if read from `path` (paths in it are relative to `path`'s
    /// folder; errors name `path`).
    pub fn parse(path: &Path, text: String) -> Result<Scene> {
        let file: SceneFile = toml::from_str(&text).map_err(|e| SceneError::Syntax {
            location: location(path, &text, e.span().map(|r| r.start)),
            message: e.message().trim_end().to_string(),
        })?;
        let scene = Scene {
            path: path.to_path_buf(),
            text,
            file,
        };
        scene.validate()?;
        Ok(scene)
    }

    /// The folder paths in the scene are relative to.
    pub fn dir(&self) -> PathBuf {
        self.path
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default()
    }

    /// A path from the scene, made relative to the working directory.
    pub fn resolve(&self, p: &Path) -> PathBuf {
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            self.dir().join(p)
        }
    }

    /// `file:line: key: message` for a spanned value.
    pub fn error_at<T>(
        &self,
        key: &str,
        value: &Spanned<T>,
        message: impl std::fmt::Display,
    ) -> SceneError {
        let span = value.span();
        let location = if span.is_empty() && span.start == 0 {
            self.path.display().to_string()
        } else {
            let line = self.text[..span.start.min(self.text.len())]
                .matches('\n')
                .count()
                + 1;
            format!("{}:{line}", self.path.display())
        };
        SceneError::Value {
            location,
            key: key.to_string(),
            message: message.to_string(),
        }
    }

    /// An error about a whole section.
    pub fn section_error(&self, message: impl std::fmt::Display) -> SceneError {
        SceneError::Section {
            path: self.path.clone(),
            message: message.to_string(),
        }
    }

    fn positive(&self, key: &str, v: &Spanned<f64>) -> Result<()> {
        let x = *v.get_ref();
        if !(x.is_finite() && x > 0.0) {
            return Err(self.error_at(key, v, format!("must be a positive number (got {x})")));
        }
        Ok(())
    }

    fn non_negative(&self, key: &str, v: &Spanned<f64>) -> Result<()> {
        let x = *v.get_ref();
        if !(x.is_finite() && x >= 0.0) {
            return Err(self.error_at(key, v, format!("must be zero or positive (got {x})")));
        }
        Ok(())
    }

    fn direction(&self, key: &str, v: &Spanned<[f64; 3]>) -> Result<[f64; 3]> {
        let d = *v.get_ref();
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if !(n.is_finite() && n > 0.0) {
            return Err(self.error_at(key, v, "must be a non-zero direction [x, y, z]"));
        }
        Ok(d.map(|x| x / n))
    }

    /// The pads: `("pad", [model] pad)` for a one-pad brake, else the `[pads]` tables in the
    /// order of their names, with their meshes relative to the scene.
    pub fn pads(&self) -> Result<Vec<(String, PathBuf)>> {
        let f = &self.file;
        match (&f.model.pad, f.pads.is_empty()) {
            (Some(p), true) => Ok(vec![("pad".into(), p.clone())]),
            (None, false) => Ok(f
                .pads
                .iter()
                .map(|(name, p)| (name.clone(), p.mesh.clone()))
                .collect()),
            (Some(_), false) => Err(self.section_error(
                "[model] pad and [pads] are both given: a one-pad brake names its pad in [model] pad, a brake with several in [pads.<name>] tables (remove one)",
            )),
            (None, true) => Err(self.section_error(
                "no pad: give [model] pad = \"pad.inp\" or [pads.<name>] tables with mesh = \"...\"",
            )),
        }
    }

    /// The mesh files the scene reads, resolved: the disc's, then each pad's.
    pub fn mesh_files(&self) -> Result<Vec<PathBuf>> {
        let mut files = vec![self.resolve(&self.file.model.disc)];
        files.extend(self.pads()?.iter().map(|(_, p)| self.resolve(p)));
        Ok(files)
    }

    /// The files the scene reads with what each is (`scene file`, `disc mesh`, `pad mesh`):
    /// what an output must not overwrite.
    pub fn input_files(&self) -> Result<Vec<(PathBuf, &'static str)>> {
        let meshes = self.mesh_files()?;
        Ok(std::iter::once((self.path.clone(), "scene file"))
            .chain(
                meshes
                    .into_iter()
                    .enumerate()
                    .map(|(i, p)| (p, if i == 0 { "disc mesh" } else { "pad mesh" })),
            )
            .collect())
    }

    fn validate(&self) -> Result<()> {
        let f = &self.file;
        self.pads()?;
        for name in f.pads.keys() {
            if name == "disc" || name.is_empty() {
                return Err(
                    self.section_error(format!("[pads.{name}]: a pad cannot be named '{name}'"))
                );
            }
        }
        let iface = f.model.interface.get_ref().as_str();
        if !["patch", "node", "nodal"].contains(&iface) {
            return Err(self.error_at(
                "model.interface",
                &f.model.interface,
                format!("'{iface}' is not 'patch', 'node' or 'nodal'"),
            ));
        }
        self.interface_reduction()?;
        if *f.model.modes.get_ref() == 0 {
            return Err(self.error_at("model.modes", &f.model.modes, "must be at least 1"));
        }
        let rotation = self.rotation()?;
        let normal = self.normal()?;
        if let (Some(r), Some(n), Some(given)) = (rotation, normal, &f.contact.normal) {
            // The pads of a disc brake press on faces normal to the disc's axis.
            let cos = (r.axis[0] * n[0] + r.axis[1] * n[1] + r.axis[2] * n[2]).abs();
            let degrees = cos.clamp(-1.0, 1.0).acos().to_degrees();
            if degrees > NORMAL_AXIS_TOLERANCE_DEG {
                return Err(self.error_at(
                    "contact.normal",
                    given,
                    format!(
                        "is {degrees:.1} degrees from rotation.axis: the pad presses on a disc face normal to the axis (fix one of the two, or remove normal to take the mesh's)"
                    ),
                ));
            }
        }
        match self.sliding()? {
            Sliding::Global(d) => {
                if let Some(n) = normal {
                    let dot = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
                    if dot.abs() > 1e-6 {
                        return Err(self.sliding_error(
                            "must be tangent to the contact (orthogonal to contact.normal)",
                        ));
                    }
                }
            }
            Sliding::Tangent => match rotation {
                Some(r) if r.sense != 0.0 => {}
                _ => {
                    return Err(self.section_error(
                        "[friction] sliding = \"tangent\" (the default) needs a [rotation] section with axis and sense; or give a global direction, e.g. sliding = [1.0, 0.0, 0.0]",
                    ));
                }
            },
        }
        self.positive("contact.pairing_tolerance", &f.contact.pairing_tolerance)?;
        self.positive("contact.stiffness_scale", &f.contact.stiffness_scale)?;
        if let Some(a) = &f.contact.point_area {
            self.positive("contact.point_area", a)?;
        }
        match (
            &f.contact.compression_curve,
            &f.contact.k_linear_per_area,
            &f.contact.k_cubic_per_area,
        ) {
            (Some(_), None, None) => {
                self.stiffness()?;
            }
            (None, Some(kl), Some(kn)) => {
                self.positive("contact.k_linear_per_area", kl)?;
                self.non_negative("contact.k_cubic_per_area", kn)?;
            }
            _ => {
                return Err(self.section_error(
                    "[contact] needs either compression_curve or both k_linear_per_area and k_cubic_per_area",
                ));
            }
        }
        self.initial_gaps()?;
        self.positive("piston.line_pressure_bar", &f.piston.line_pressure_bar)?;
        self.positive("piston.area", &f.piston.area)?;
        self.non_negative("damping.global_ratio", &f.damping.global_ratio)?;
        self.pair()?;
        if let Some(r) = &f.damping.pair_ratios
            && r.get_ref().iter().any(|x| !(x.is_finite() && *x >= 0.0))
        {
            return Err(self.error_at("damping.pair_ratios", r, "must be two ratios >= 0"));
        }
        if let Some(b) = &f.stability.band_hz {
            let [lo, hi] = *b.get_ref();
            if !(lo >= 0.0 && hi > lo) {
                return Err(self.error_at(
                    "stability.band_hz",
                    b,
                    "must be [low, high] with 0 <= low < high",
                ));
            }
        }
        self.mu_values()?;
        self.check_plausible()?;
        self.cycle()?;
        self.disc_angular_speed()?;
        self.units()?;
        self.set_rules()?;
        self.patch_grid()?;
        self.materials()?;
        Ok(())
    }

    /// The scene's limit cycle, the one `squeal chbm`, `squeal run` and the report compute:
    /// at `[chbm] mu` or at `[chbm] mu_ratio` × μ0 (one of the two; `[friction] mu` is the
    /// older spelling of `[chbm] mu`), else at [`DEFAULT_CYCLE_MU_RATIO`] × μ0, with
    /// `[chbm] harmonics` harmonics.
    pub fn cycle(&self) -> Result<CycleSpec> {
        let c = &self.file.chbm;
        let h = *c.harmonics.get_ref();
        if h == 0 || h > 50 {
            return Err(self.error_at("chbm.harmonics", &c.harmonics, "must be between 1 and 50"));
        }
        for (key, v) in [
            ("chbm.mu", &c.mu),
            ("friction.mu", &self.file.friction.mu),
            ("chbm.mu_ratio", &c.mu_ratio),
        ] {
            if let Some(v) = v {
                self.positive(key, v)?;
            }
        }
        let mu = match (&c.mu, &self.file.friction.mu) {
            (Some(m), Some(old)) => {
                return Err(self.error_at(
                    "friction.mu",
                    old,
                    format!(
                        "gives the limit cycle's friction a second time ([chbm] mu = {} is the place for it): remove one",
                        m.get_ref()
                    ),
                ));
            }
            (Some(m), None) => Some(("chbm.mu", m)),
            (None, Some(old)) => Some(("friction.mu", old)),
            (None, None) => None,
        };
        let at = match (mu, &c.mu_ratio) {
            (Some((key, m)), Some(r)) => {
                return Err(self.error_at(
                    key,
                    m,
                    format!(
                        "is given with chbm.mu_ratio = {}: both say where the limit cycle is; give one (mu for a friction coefficient, mu_ratio for a multiple of the Hopf point mu0)",
                        r.get_ref()
                    ),
                ));
            }
            (Some((_, m)), None) => CycleFriction::Mu(*m.get_ref()),
            (None, Some(r)) => CycleFriction::Ratio(*r.get_ref()),
            (None, None) => CycleFriction::Ratio(DEFAULT_CYCLE_MU_RATIO),
        };
        Ok(CycleSpec { at, harmonics: h })
    }

    /// The disc's angular speed (rad/s) from `[rotation]` (or the older `[disc]`), `None`
    /// when the scene gives none.
    pub fn disc_angular_speed(&self) -> Result<Option<f64>> {
        Ok(self.rotation()?.and_then(|r| r.angular_speed))
    }

    /// A speed from `rpm`, or `vehicle_speed_kmh` with `rolling_radius` (keys under `section`).
    fn speed(
        &self,
        section: &str,
        rpm: &Option<Spanned<f64>>,
        vehicle: &Option<Spanned<f64>>,
        radius: &Option<Spanned<f64>>,
    ) -> Result<Option<f64>> {
        match (rpm, vehicle, radius) {
            (None, None, None) => Ok(None),
            (Some(r), None, None) => {
                self.positive(&format!("{section}.rpm"), r)?;
                Ok(Some(r.get_ref() * 2.0 * std::f64::consts::PI / 60.0))
            }
            (None, Some(v), Some(r)) => {
                self.positive(&format!("{section}.vehicle_speed_kmh"), v)?;
                self.positive(&format!("{section}.rolling_radius"), r)?;
                Ok(Some(
                    v.get_ref() / 3.6 / (r.get_ref() * self.length_unit()?),
                ))
            }
            _ => Err(self.section_error(format!(
                "[{section}] takes either rpm, or vehicle_speed_kmh with rolling_radius"
            ))),
        }
    }

    /// The disc's rotation: from `[rotation]`, or from the older `[disc]` (axis along
    /// `contact.normal`, the z axis without one, through `axis_origin`; no sense); `None`
    /// when the scene has neither.
    pub fn rotation(&self) -> Result<Option<Rotation>> {
        let f = &self.file;
        let d = &f.disc;
        let old = d.rpm.is_some()
            || d.vehicle_speed_kmh.is_some()
            || d.rolling_radius.is_some()
            || d.axis_origin.is_some();
        let unit = self.length_unit()?;
        // A point in the scene's length unit, in metres.
        let finite_point = |key: &str, p: &Spanned<[f64; 3]>| -> Result<[f64; 3]> {
            let x = *p.get_ref();
            if !x.iter().all(|v| v.is_finite()) {
                return Err(self.error_at(key, p, "must be a point [x, y, z] of finite numbers"));
            }
            Ok(x.map(|v| v * unit))
        };
        match &f.rotation {
            Some(r) => {
                if old {
                    return Err(self.section_error(
                        "both [rotation] and [disc] are given: [disc] is the older form of [rotation]; move its rpm (or vehicle_speed_kmh and rolling_radius) into [rotation] and its axis_origin to [rotation] point, and delete [disc]",
                    ));
                }
                let axis = self.direction("rotation.axis", &r.axis)?;
                let point = match &r.point {
                    Some(p) => finite_point("rotation.point", p)?,
                    None => [0.0; 3],
                };
                let sense = match r.sense.get_ref().as_str() {
                    "counterclockwise" => 1.0,
                    "clockwise" => -1.0,
                    other => {
                        return Err(self.error_at(
                            "rotation.sense",
                            &r.sense,
                            format!(
                                "'{other}' is neither \"counterclockwise\" (the right-hand rule about axis) nor \"clockwise\", as seen from the tip of axis"
                            ),
                        ));
                    }
                };
                let angular_speed =
                    self.speed("rotation", &r.rpm, &r.vehicle_speed_kmh, &r.rolling_radius)?;
                Ok(Some(Rotation {
                    point,
                    axis,
                    sense,
                    angular_speed,
                }))
            }
            None if old => {
                let axis = match &f.contact.normal {
                    Some(n) => self.direction("contact.normal", n)?,
                    None => [0.0, 0.0, 1.0],
                };
                let point = match &d.axis_origin {
                    Some(p) => finite_point("disc.axis_origin", p)?,
                    None => [0.0; 3],
                };
                let angular_speed =
                    self.speed("disc", &d.rpm, &d.vehicle_speed_kmh, &d.rolling_radius)?;
                Ok(Some(Rotation {
                    point,
                    axis,
                    sense: 0.0,
                    angular_speed,
                }))
            }
            None => Ok(None),
        }
    }

    /// The unit normal `[contact] normal` gives, `None` when it is not given.
    pub fn normal(&self) -> Result<Option<[f64; 3]>> {
        self.file
            .contact
            .normal
            .as_ref()
            .map(|n| self.direction("contact.normal", n))
            .transpose()
    }

    /// The direction from the disc into the pad as the scene gives it, for what must be known
    /// before the meshes are read (the default sets, a transversely isotropic material's
    /// axis): `[contact] normal`, else the `[rotation]` axis, else z (the bundled layout). Give
    /// `[contact] normal` when the pad lies on the face the axis points away from.
    pub fn contact_direction(&self) -> Result<[f64; 3]> {
        if let Some(n) = self.normal()? {
            return Ok(n);
        }
        Ok(self.rotation()?.map_or([0.0, 0.0, 1.0], |r| r.axis))
    }

    /// An error on the global sliding direction, at its key and line.
    fn sliding_error(&self, message: &str) -> SceneError {
        let fr = &self.file.friction;
        match (&fr.sliding, &fr.sliding_direction) {
            (Some(v), _) => self.error_at("friction.sliding", v, message),
            (None, Some(d)) => self.error_at("friction.sliding_direction", d, message),
            (None, None) => self.section_error(format!("[friction] sliding: {message}")),
        }
    }

    /// How the disc slides under the pad: `[friction] sliding` (`"tangent"`, the default, or
    /// a direction) or the older `sliding_direction`; both at once are refused.
    pub fn sliding(&self) -> Result<Sliding> {
        let fr = &self.file.friction;
        match (&fr.sliding, &fr.sliding_direction) {
            (Some(_), Some(d)) => Err(self.error_at(
                "friction.sliding_direction",
                d,
                "is the older form of friction.sliding: give one of the two",
            )),
            (None, Some(d)) => Ok(Sliding::Global(
                self.direction("friction.sliding_direction", d)?,
            )),
            (None, None) => Ok(Sliding::Tangent),
            (Some(v), None) => match v.get_ref() {
                toml::Value::String(s) if s == "tangent" => Ok(Sliding::Tangent),
                toml::Value::Array(a) if a.len() == 3 => {
                    let d: Vec<f64> = a
                        .iter()
                        .filter_map(|x| x.as_float().or(x.as_integer().map(|i| i as f64)))
                        .collect();
                    let d: [f64; 3] = d.try_into().map_err(|_| {
                        self.error_at("friction.sliding", v, "must be three numbers [x, y, z]")
                    })?;
                    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                    if !(n.is_finite() && n > 0.0) {
                        return Err(self.error_at(
                            "friction.sliding",
                            v,
                            "must be a non-zero direction [x, y, z]",
                        ));
                    }
                    Ok(Sliding::Global(d.map(|x| x / n)))
                }
                _ => Err(self.error_at(
                    "friction.sliding",
                    v,
                    "must be \"tangent\" (the tangent of the disc's rotation at each contact point) or a global direction [x, y, z]",
                )),
            },
        }
    }

    /// The pairs' initial gaps in metres: `[contact] initial_gap` (a number or a list of
    /// numbers, in the `[units]` length), `close_initial_gaps = true`, or neither (measured
    /// from the geometry). Both together
    /// are refused: closing the gaps one gives is a contradiction.
    pub fn initial_gaps(&self) -> Result<GapSetting> {
        let c = &self.file.contact;
        let close = c.close_initial_gaps.as_ref().is_some_and(|b| *b.get_ref());
        let Some(v) = &c.initial_gap else {
            return Ok(if close {
                GapSetting::Closed
            } else {
                GapSetting::Geometric
            });
        };
        if close {
            return Err(self.error_at(
                "contact.initial_gap",
                v,
                "is given together with close_initial_gaps = true, which sets every gap to zero: keep one of the two",
            ));
        }
        // In the scene's length unit (metres by default), returned in metres.
        let unit = self.length_unit()?;
        let number = |x: &toml::Value| {
            let g = x.as_float().or(x.as_integer().map(|i| i as f64));
            g.map(|g| g * unit)
        };
        let bad = || {
            self.error_at(
                "contact.initial_gap",
                v,
                "must be a gap in metres, or in the [units] length (positive: open, e.g. 1.0e-4 for 0.1 mm in SI), or a list of one per contact pair",
            )
        };
        match v.get_ref() {
            toml::Value::Array(a) => {
                let g: Vec<f64> = a.iter().filter_map(number).collect();
                if g.len() != a.len() || g.is_empty() || g.iter().any(|x| !x.is_finite()) {
                    return Err(bad());
                }
                Ok(GapSetting::PerPair(g))
            }
            x => match number(x) {
                Some(g) if g.is_finite() => Ok(GapSetting::Uniform(g)),
                _ => Err(bad()),
            },
        }
    }

    /// The contact law of `[contact] law`: `"penalty-coulomb"` (also the default), or
    /// `{ kind = "velocity-dependent", static_ratio = r, decay_speed_m_per_s = v0 }` (`r > 0`,
    /// `v0 > 0` in m/s whatever the `[units]`), which needs the disc's speed (`[rotation] rpm`
    /// or `vehicle_speed_kmh`).
    pub fn contact_law(&self) -> Result<ContactLawSetting> {
        let Some(v) = &self.file.contact.law else {
            return Ok(ContactLawSetting::PenaltyCoulomb);
        };
        let usage = "must be \"penalty-coulomb\" or { kind = \"velocity-dependent\", static_ratio = 1.2, decay_speed_m_per_s = 0.5 } (r = mu_static/mu_dynamic > 0, v0 > 0 in m/s)";
        let table = match v.get_ref() {
            toml::Value::String(s) if s == "penalty-coulomb" => {
                return Ok(ContactLawSetting::PenaltyCoulomb);
            }
            toml::Value::Table(t) => t,
            _ => return Err(self.error_at("contact.law", v, usage)),
        };
        let number = |key: &str| {
            table
                .get(key)
                .and_then(|x| x.as_float().or(x.as_integer().map(|i| i as f64)))
                .filter(|x| x.is_finite() && *x > 0.0)
        };
        let kind = table.get("kind").and_then(toml::Value::as_str);
        let known = ["kind", "static_ratio", "decay_speed_m_per_s"];
        match (kind, number("static_ratio"), number("decay_speed_m_per_s")) {
            (Some("penalty-coulomb"), ..) if table.len() == 1 => {
                Ok(ContactLawSetting::PenaltyCoulomb)
            }
            (Some("velocity-dependent"), Some(r), Some(v0))
                if table.keys().all(|k| known.contains(&k.as_str())) =>
            {
                if self.disc_angular_speed()?.is_none() {
                    return Err(self.error_at(
                        "contact.law",
                        v,
                        "velocity-dependent friction needs the disc's speed: give [rotation] rpm (or vehicle_speed_kmh and rolling_radius)",
                    ));
                }
                Ok(ContactLawSetting::VelocityDependent {
                    static_ratio: r,
                    decay_speed: v0,
                })
            }
            _ => Err(self.error_at("contact.law", v, usage)),
        }
    }

    /// `contact.pairing_tolerance` in metres: a given value is in the `[units]` length; the
    /// default is 1 mm whatever the units (it has no span: it was not written in the file).
    pub fn pairing_tolerance(&self) -> Result<f64> {
        let t = &self.file.contact.pairing_tolerance;
        if t.span() == (0..0) {
            return Ok(*t.get_ref());
        }
        Ok(t.get_ref() * self.length_unit()?)
    }

    /// `contact.point_area` in m².
    pub fn point_area(&self) -> Result<Option<f64>> {
        let a = self.units()?.area();
        Ok(self
            .file
            .contact
            .point_area
            .as_ref()
            .map(|p| p.get_ref() * a))
    }

    /// The clamp force (N): `piston.line_pressure_bar` (bar) times `piston.area` (in the
    /// scene's area unit).
    pub fn piston_force(&self) -> Result<f64> {
        let p = &self.file.piston;
        Ok(p.line_pressure_bar.get_ref() * 1e5 * p.area.get_ref() * self.units()?.area())
    }

    /// Contact stiffness per unit area `(κ_l, κ_nl)` in Pa/m and Pa/m³, scaled, and the fit
    /// report if fitted (given directly, they are in the scene's stress per length and stress
    /// per length cubed).
    pub fn stiffness(&self) -> Result<(f64, f64, Option<Fit>)> {
        let c = &self.file.contact;
        let scale = *c.stiffness_scale.get_ref();
        if let (Some(kl), Some(kn)) = (&c.k_linear_per_area, &c.k_cubic_per_area) {
            let u = self.units()?;
            let (kl_si, kn_si) = (u.stress() / u.length, u.stress() / u.length.powi(3));
            // `+ 0.0` turns a -0 into 0: a linear law either way, without a minus sign.
            return Ok((
                kl.get_ref() * kl_si * scale,
                kn.get_ref() * kn_si * scale + 0.0,
                None,
            ));
        }
        let curve = c.compression_curve.as_ref().ok_or_else(|| {
            self.section_error(
                "[contact] needs either compression_curve or both k_linear_per_area and k_cubic_per_area",
            )
        })?;
        let (p, d) = (curve.pressure_mpa.get_ref(), curve.closure_um.get_ref());
        if p.len() != d.len() || p.len() < 2 {
            return Err(self.error_at(
                "contact.compression_curve",
                &curve.pressure_mpa,
                "needs at least two (pressure, closure) points, as many of each",
            ));
        }
        self.check_curve(curve)?;
        let fit = fit_cubic(
            &d.iter().map(|x| x * 1e-6).collect::<Vec<_>>(),
            &p.iter().map(|x| x * 1e6).collect::<Vec<_>>(),
        )
        .ok_or_else(|| {
            self.error_at(
                "contact.compression_curve",
                &curve.closure_um,
                "cannot fit p = k1 d + k3 d^3 to these points",
            )
        })?;
        if !(fit.linear > 0.0 && fit.cubic >= 0.0) {
            return Err(self.error_at(
                "contact.compression_curve",
                &curve.closure_um,
                format!(
                    "the fit gives k_l = {:.3e} Pa/m, k_nl = {:.3e} Pa/m^3: both must be positive",
                    fit.linear, fit.cubic
                ),
            ));
        }
        Ok((fit.linear * scale, fit.cubic * scale + 0.0, Some(fit)))
    }

    /// The pair choice (0-based modes).
    pub fn pair(&self) -> Result<Option<(usize, usize)>> {
        let v = &self.file.damping.pair;
        match v.get_ref() {
            toml::Value::String(s) if s == "auto" => Ok(None),
            toml::Value::Array(a) if a.len() == 2 => {
                let m: Vec<i64> = a.iter().filter_map(toml::Value::as_integer).collect();
                if m.len() != 2 || m.iter().any(|x| *x < 1) {
                    return Err(self.error_at(
                        "damping.pair",
                        v,
                        "must be \"auto\" or two mode numbers >= 1",
                    ));
                }
                Ok(Some(((m[0] - 1) as usize, (m[1] - 1) as usize)))
            }
            _ => Err(self.error_at("damping.pair", v, "must be \"auto\" or [mode1, mode2]")),
        }
    }

    /// Friction values of the sweep.
    pub fn mu_values(&self) -> Result<Vec<f64>> {
        match &self.file.stability.mu {
            None => Ok(parse_range("0..1/201").unwrap_or_default()),
            Some(v) => match v.get_ref() {
                toml::Value::String(s) => {
                    parse_range(s).map_err(|e| self.error_at("stability.mu", v, e))
                }
                toml::Value::Array(a) => {
                    let m: Vec<f64> = a
                        .iter()
                        .filter_map(|x| x.as_float().or(x.as_integer().map(|i| i as f64)))
                        .collect();
                    if m.len() != a.len() || m.is_empty() || m.windows(2).any(|w| w[1] <= w[0]) {
                        return Err(self.error_at("stability.mu", v, "must be ascending numbers"));
                    }
                    checks::non_negative_mus(&m)
                        .map_err(|e| self.error_at("stability.mu", v, e))?;
                    Ok(m)
                }
                _ => Err(self.error_at(
                    "stability.mu",
                    v,
                    "must be \"start..end/count\" (e.g. \"0..1/201\") or a list",
                )),
            },
        }
    }
}

/// `p = κ_l δ + κ_nl δ³` fitted by least squares to `(δ_i, p_i)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    pub linear: f64,
    pub cubic: f64,
    /// RMS of the pressure residual relative to the largest pressure.
    pub relative_rms: f64,
}

/// Least-squares fit of `p = a d + b d³` (2×2 normal equations).
pub fn fit_cubic(d: &[f64], p: &[f64]) -> Option<Fit> {
    let (mut s11, mut s13, mut s33, mut t1, mut t3) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (&x, &y) in d.iter().zip(p) {
        let x3 = x * x * x;
        s11 += x * x;
        s13 += x * x3;
        s33 += x3 * x3;
        t1 += x * y;
        t3 += x3 * y;
    }
    let det = s11 * s33 - s13 * s13;
    if !(det.is_finite() && det.abs() > 1e-300) {
        return None;
    }
    let a = (t1 * s33 - t3 * s13) / det;
    let b = (s11 * t3 - s13 * t1) / det;
    let pmax = p
        .iter()
        .map(|x| x.abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let rms = (d
        .iter()
        .zip(p)
        .map(|(&x, &y)| (a * x + b * x.powi(3) - y).powi(2))
        .sum::<f64>()
        / d.len() as f64)
        .sqrt();
    Some(Fit {
        linear: a,
        cubic: b,
        relative_rms: rms / pmax,
    })
}

/// `"start..end/count"` → `count` evenly spaced values from `start` to `end`, both included
/// (MATLAB's `linspace(start, end, count)`), e.g. `0..1/201`: friction coefficients, so a
/// negative start is refused.
///
/// The colon form `a:b:c` is refused with a message: it reads as `start:end:count` here but as
/// `start:step:end` in MATLAB, so `0:0.5:100` would silently sweep 0–0.5.
pub fn parse_range(s: &str) -> std::result::Result<Vec<f64>, String> {
    let example = "e.g. 0..1/201 for 201 values from 0 to 1";
    if s.contains(':') {
        return Err(format!(
            "'{s}': the colon form is ambiguous (start:end:count, or MATLAB's start:step:end); write start..end/count, {example}"
        ));
    }
    let bad = || format!("'{s}' is not start..end/count ({example})");
    let (span, count) = s.split_once('/').ok_or_else(bad)?;
    let (a, b) = span.split_once("..").ok_or_else(bad)?;
    let a: f64 = a.trim().parse().map_err(|_| bad())?;
    let b: f64 = b.trim().parse().map_err(|_| bad())?;
    let n: usize = count.trim().parse().map_err(|_| bad())?;
    if !(a.is_finite() && b.is_finite()) {
        return Err(format!("'{s}': start and end must be finite numbers"));
    }
    if b <= a {
        return Err(format!("'{s}': start must be below end"));
    }
    checks::non_negative_mus(&[a]).map_err(|e| format!("'{s}': {e}"))?;
    if !(2..=100_000).contains(&n) {
        return Err(format!("'{s}': count must be between 2 and 100000"));
    }
    Ok((0..n)
        .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
        .collect())
}

#[cfg(test)]
mod tests;
