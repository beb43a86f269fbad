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
pub mod sound;
pub mod variant;
pub use variant::{Interface, MESH_LEVELS, level_path};

pub use model_keys::Key;

pub use checks::{
    HIGH_DAMPING_RATIO, HIGH_LINE_PRESSURE_BAR, HIGH_MU, LARGE_GAP_M, MAX_LINE_PRESSURE_BAR,
};

use serde::Deserialize;
use std::path::{Path, PathBuf};
use toml::Spanned;

mod fit;
#[allow(unused_imports)]
use fit::*;
pub use fit::{Fit, fit_cubic, parse_range};

mod file;
pub use file::StickSlipSetting;
#[allow(unused_imports)]
use file::*;
pub use file::{
    ChbmSection, CompressionCurve, ContactLawSetting, ContactSection, CycleFriction, CycleSpec,
    DEFAULT_CYCLE_MU_RATIO, DampingSection, DiscSection, FrictionSection, GapSetting, ModelSection,
    PadSection, PistonSection, Rotation, RotationSection, SceneFile, Sliding, StabilitySection,
};

mod contact_keys;
mod stick_law_keys;
mod stick_slip_keys;

pub mod assembly;
pub mod dampers;
pub mod parts_keys;
pub mod springs;

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
        files.extend(self.bodies().iter().map(|(_, p)| self.resolve(p)));
        Ok(files)
    }

    /// The files the scene reads with what each is (`scene file`, `disc mesh`, `pad mesh` (a
    /// pad's, named with several pads: `inboard pad mesh`), `caliper mesh` for a further part
    /// `[parts.caliper]`): what an output must not overwrite.
    pub fn input_files(&self) -> Result<Vec<(PathBuf, String)>> {
        let pads = self.pads()?;
        let one = pads.len() == 1;
        let mut out = vec![
            (self.path.clone(), "scene file".to_string()),
            (self.resolve(&self.file.model.disc), "disc mesh".to_string()),
        ];
        out.extend(pads.iter().map(|(name, p)| {
            let what = if one {
                "pad mesh".to_string()
            } else {
                format!("{name} pad mesh")
            };
            (self.resolve(p), what)
        }));
        out.extend(
            self.bodies()
                .iter()
                .map(|(name, p)| (self.resolve(p), format!("{name} mesh"))),
        );
        Ok(out)
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
        self.sound()?;
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
        self.check_elsets()?;
        self.supports()?;
        self.ties()?;
        self.springs()?;
        self.dampers()?;
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

#[cfg(test)]
mod tests;
