//! The scene's `[units]`, `[sets.disc]`, `[sets.pad]` and `[materials.<SET>]`.
//!
//! # Units
//! `[units] system = "mm-t-s"` (or `"SI"`, the default, `"mm-kg-ms"`, `"mm-g-ms"`,
//! `"in-lbf-s"`; see [`squeal_mesh::units::SYSTEMS`]) says in which consistent system the
//! meshes' coordinates and materials, the `[materials]` constants and every scene key without
//! a unit in its name are written (lengths such as `contact.pairing_tolerance`,
//! `contact.initial_gap`, `rotation.point`, `rotation.rolling_radius`, `disc.rolling_radius`,
//! `disc.axis_origin`, the points, radii and tolerances of `[sets]`; areas such as
//! `piston.area`; `contact.k_*_per_area`). Everything is converted to SI on reading. Keys
//! with a unit in their name (`line_pressure_bar`, `compression_curve`'s `pressure_mpa` and
//! `closure_um`, `vehicle_speed_kmh`, `band_hz`) keep that unit whatever the system.
//!
//! # Sets
//! Each set the reduction needs is either the name of a node set of the mesh or a geometric
//! rule ([`squeal_mesh::select::Rule`]): the boundary faces meeting every criterion given,
//!
//! ```toml
//! [sets.disc]
//! clamp = "CLAMP"                                  # a named node set
//! contact_face = { facing = [0, 0, 1], plane = { point = [0, 0, 0.02], normal = [0, 0, 1] },
//!                  box = { min = [-0.07, 0.08, 0.0], max = [0.07, 0.14, 0.03] } }
//! [sets.pad]
//! friction_face = { facing = [0, 0, -1], angle = 1.0 }
//! pistons = { facing = [0, 0, 1], circles = [ { centre = [0.024, 0.107, 0.035], diameter = 0.04 },
//!                                             { centre = [-0.024, 0.107, 0.035], diameter = 0.04 } ] }
//! abutments = { box = { min = [-1, -1, 0.03], max = [1, 1, 0.035] }, facing = [1, 0, 0], angle = 90 }
//! ```
//!
//! Criteria: `set` (a node set the faces must lie in), `cylinder = { point, axis, radius }`,
//! `plane = { point, normal }` (corners within `tolerance`), `box = { min, max }` (all six
//! nodes inside), `facing = [x, y, z]` with `angle` (degrees, default 1), `circles` (pistons
//! only: one piston per circle, faces whose corner centroid is within the circle in the face's
//! plane), `points = [[x, y, z], ...]` (pistons only: one piston point per point, the node of
//! the selected faces nearest it, for meshes without a node set of piston points) and
//! `tolerance` (default: 1e-6 of the part's largest extent). A list of rules is
//! their union (for pistons: one piston per rule, as per circle). A key left out takes
//! the mesh's conventional set when it has one (`CLAMP`, `CONTACT_FACE`, `PISTON`,
//! `ABUTMENT`), else the geometric default of the generator's brake (see
//! [`SetsSection`]); the pipeline resolves those (they need the meshes).

use crate::{Scene, SceneError};
use serde::Deserialize;
use squeal_fe::ElasticMaterial;
use squeal_mesh::select::{Circle, Rule, Surface};
use squeal_mesh::units::UnitSystem;
use toml::Spanned;

type Result<T> = std::result::Result<T, SceneError>;

/// `[units]`.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct UnitsSection {
    /// The system's name (`"SI"` by default).
    pub system: Option<Spanned<String>>,
}

/// `[sets]`: `[sets.disc]` and `[sets.pad]`.
///
/// Defaults when a key is left out and the mesh lacks the conventional set (n is
/// `contact.normal`, from the disc into the pad, else the `[rotation]` axis):
/// - disc `clamp`: the boundary faces facing -n on the disc's lowest plane along n (the hub
///   flange's seat of the generator's hat disc);
/// - pad `friction_face`: the boundary faces facing -n on the pad's lowest plane along n;
/// - disc `contact_face`: the disc's boundary faces facing +n (within 1 degree) whose corner
///   centroid lies under the pad's friction face (its projection along n falls inside one of
///   the friction face's triangles);
/// - pad `pistons`, `abutments`: no geometric default (a pad's back and sides do not say where a
///   caliper holds them): the mesh needs `PISTON` / `ABUTMENT` sets or the scene the keys.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct SetsSection {
    /// `patch_grid = [radial, angular]`: the contact patches of the patch interface, cut in
    /// radius and angle about the disc axis on each part's contact face (3 x 3 by default).
    /// Each patch is the part of the face inside its cell (a triangle that crosses a cut is
    /// clipped there; one that only touches a cut, as where the mesh imprinted the grid, stays
    /// whole), so the disc's and the pad's patches are the same regions of the footprint on
    /// any grid, whether or not the two meshes match, and pair by their centroids.
    pub patch_grid: Option<Spanned<[usize; 2]>>,
    #[serde(default)]
    pub disc: DiscSets,
    #[serde(default)]
    pub pad: PadSets,
}

/// `[sets.disc]`.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct DiscSets {
    /// Nodes clamped in all directions.
    pub clamp: Option<Spanned<toml::Value>>,
    /// The directions the clamp holds (default: all): a list of `"axial"`, `"radial"`,
    /// `"tangential"` (relative to the rotation axis at each node) and global directions.
    pub clamp_hold: Option<Spanned<toml::Value>>,
    /// The face the pad's friction face lies on (patch interface).
    pub contact_face: Option<Spanned<toml::Value>>,
}

/// `[sets.pad]`.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct PadSets {
    /// The face that rubs on the disc (patch interface).
    pub friction_face: Option<Spanned<toml::Value>>,
    /// Where the pistons push: a named node set (one piston point per node) or `circles`.
    pub pistons: Option<Spanned<toml::Value>>,
    /// Nodes held in the plane of the disc (free along the normal).
    pub abutments: Option<Spanned<toml::Value>>,
    /// The directions the abutments hold (default `["radial", "tangential"]`: the plane
    /// normal to the axis), as `clamp_hold`.
    pub abutments_hold: Option<Spanned<toml::Value>>,
}

/// A direction a restraint holds its nodes in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Hold {
    /// Along the rotation axis.
    Axial,
    /// Away from the axis, at each node.
    Radial,
    /// Along the rotation's motion, at each node.
    Tangential,
    /// One global unit direction.
    Global([f64; 3]),
}

/// A set the scene gives: its key (`sets.disc.clamp`), where it is written (`file:line`) and
/// its rules (one, or one per piston circle), in SI.
#[derive(Clone, Debug, PartialEq)]
pub struct SetRule {
    /// The key, e.g. `sets.pad.pistons`.
    pub key: String,
    /// `file:line` of the key.
    pub location: String,
    /// The rules (one, one per item of a list, or for pistons given by circles one per
    /// circle), whose union is the set. A rule's tolerance is 0 when the scene gives none:
    /// [`SetRule::tolerance_given`] tells, and the caller picks one from the part's size.
    pub rules: Vec<Rule>,
    /// Whether the scene gave `tolerance` (else the caller picks one from the part's size).
    pub tolerance_given: bool,
}

/// `[materials.<ELEMENT_SET>]`: an isotropic material (`young`, `poisson`, `density`) or a
/// transversely isotropic one (`young_plane`, `poisson_plane`, `young_axial`,
/// `poisson_plane_axial`, `shear_axial`, `axis` (default `contact.normal`, else the `[rotation]` axis), `density`), in the
/// scene's units (stress and density units of `[units]`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    pub young: Option<Spanned<f64>>,
    pub poisson: Option<Spanned<f64>>,
    pub density: Option<Spanned<f64>>,
    pub young_plane: Option<Spanned<f64>>,
    pub poisson_plane: Option<Spanned<f64>>,
    pub young_axial: Option<Spanned<f64>>,
    pub poisson_plane_axial: Option<Spanned<f64>>,
    pub shear_axial: Option<Spanned<f64>>,
    pub axis: Option<Spanned<[f64; 3]>>,
}

/// Looks a key up in a rule table.
fn number(v: &toml::Value) -> Option<f64> {
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64))
}

fn vec3(v: &toml::Value) -> Option<[f64; 3]> {
    let a = v.as_array()?;
    if a.len() != 3 {
        return None;
    }
    Some([number(&a[0])?, number(&a[1])?, number(&a[2])?])
}

impl Scene {
    /// The unit system of `[units]` (SI without one).
    pub fn units(&self) -> Result<UnitSystem> {
        match &self.file.units.system {
            None => Ok(UnitSystem::default()),
            Some(s) => UnitSystem::named(s.get_ref()).ok_or_else(|| {
                self.error_at(
                    "units.system",
                    s,
                    format!(
                        "'{}' is not a unit system squeal knows; use one of {}",
                        s.get_ref(),
                        UnitSystem::names()
                    ),
                )
            }),
        }
    }

    /// The patch grid `[radial, angular]` of `[sets] patch_grid` (3 x 3 by default), checked
    /// to have 1 to 10000 cells.
    pub fn patch_grid(&self) -> Result<[usize; 2]> {
        match &self.file.sets.patch_grid {
            None => Ok([3, 3]),
            Some(g) => {
                let [r, a] = *g.get_ref();
                if r == 0 || a == 0 || r.saturating_mul(a) > 10_000 {
                    return Err(self.error_at(
                        "sets.patch_grid",
                        g,
                        "must be [radial, angular], each at least 1, at most 10000 patches",
                    ));
                }
                Ok([r, a])
            }
        }
    }

    /// Metres per length unit of the scene.
    pub fn length_unit(&self) -> Result<f64> {
        Ok(self.units()?.length)
    }

    /// The sets the scene gives, in the order disc clamp, disc contact face, pad friction
    /// face, pad pistons, pad abutments; `None` for a key left out.
    pub fn set_rules(&self) -> Result<[Option<SetRule>; 5]> {
        let (d, p) = (&self.file.sets.disc, &self.file.sets.pad);
        Ok([
            self.set_rule("sets.disc.clamp", d.clamp.as_ref(), false)?,
            self.set_rule("sets.disc.contact_face", d.contact_face.as_ref(), false)?,
            self.set_rule("sets.pad.friction_face", p.friction_face.as_ref(), false)?,
            self.set_rule("sets.pad.pistons", p.pistons.as_ref(), true)?,
            self.set_rule("sets.pad.abutments", p.abutments.as_ref(), false)?,
        ])
    }

    /// The sets of pad `pad` (`first`: the first of the brake's pads), in the order friction
    /// face, load points, abutments, disc contact face, each with the key it comes from: its
    /// `[pads.<pad>]` key, else the `[sets.pad]` key (the load points: only for the first pad,
    /// as `pistons`), else for the first pad the `[sets.disc] contact_face`; `None` for a set
    /// nothing gives.
    pub fn pad_set_rules(&self, pad: &str, first: bool) -> Result<[Option<(String, SetRule)>; 4]> {
        let (d, p) = (&self.file.sets.disc, &self.file.sets.pad);
        let table = self.file.pads.get(pad);
        let pick = |own: Option<&Spanned<toml::Value>>,
                    own_key: &str,
                    shared: Option<&Spanned<toml::Value>>,
                    shared_key: &str,
                    pistons: bool|
         -> Result<Option<(String, SetRule)>> {
            let (key, value) = match (own, shared) {
                (Some(v), _) => (format!("pads.{pad}.{own_key}"), v),
                (None, Some(v)) => (shared_key.to_string(), v),
                (None, None) => return Ok(None),
            };
            Ok(self.set_rule(&key, Some(value), pistons)?.map(|r| (key, r)))
        };
        Ok([
            pick(
                table.and_then(|t| t.friction_face.as_ref()),
                "friction_face",
                p.friction_face.as_ref(),
                "sets.pad.friction_face",
                false,
            )?,
            pick(
                table.and_then(|t| t.load.as_ref()),
                "load",
                p.pistons.as_ref().filter(|_| first),
                "sets.pad.pistons",
                true,
            )?,
            pick(
                table.and_then(|t| t.abutments.as_ref()),
                "abutments",
                p.abutments.as_ref(),
                "sets.pad.abutments",
                false,
            )?,
            pick(
                table.and_then(|t| t.disc_contact_face.as_ref()),
                "disc_contact_face",
                d.contact_face.as_ref().filter(|_| first),
                "sets.disc.contact_face",
                false,
            )?,
        ])
    }

    /// `[sets.disc] clamp_hold`, if given.
    pub fn clamp_hold(&self) -> Result<Option<Vec<Hold>>> {
        self.file
            .sets
            .disc
            .clamp_hold
            .as_ref()
            .map(|v| self.hold("sets.disc.clamp_hold", v))
            .transpose()
    }

    /// What pad `pad`'s abutments hold, if given: its `[pads.<pad>] abutments_hold`, else
    /// `[sets.pad] abutments_hold`.
    pub fn abutments_hold(&self, pad: &str) -> Result<Option<Vec<Hold>>> {
        let own = self
            .file
            .pads
            .get(pad)
            .and_then(|t| t.abutments_hold.as_ref());
        match (own, self.file.sets.pad.abutments_hold.as_ref()) {
            (Some(v), _) => self
                .hold(&format!("pads.{pad}.abutments_hold"), v)
                .map(Some),
            (None, Some(v)) => self.hold("sets.pad.abutments_hold", v).map(Some),
            (None, None) => Ok(None),
        }
    }

    /// A list of held directions: `"axial"`, `"radial"`, `"tangential"` or `[x, y, z]`.
    fn hold(&self, key: &str, value: &Spanned<toml::Value>) -> Result<Vec<Hold>> {
        let bad = |m: &str| self.error_at(key, value, m);
        let form =
            "must be a list of \"axial\", \"radial\", \"tangential\" or directions [x, y, z]";
        let items = value.get_ref().as_array().ok_or_else(|| bad(form))?;
        if items.is_empty() {
            return Err(bad(form));
        }
        let mut out = Vec::with_capacity(items.len());
        for item in items {
            out.push(match item {
                toml::Value::String(s) => match s.as_str() {
                    "axial" => Hold::Axial,
                    "radial" => Hold::Radial,
                    "tangential" => Hold::Tangential,
                    _ => return Err(bad(form)),
                },
                v => {
                    let d = vec3(v).ok_or_else(|| bad(form))?;
                    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                    if !(n.is_finite() && n > 0.0) {
                        return Err(bad("a held direction must be non-zero"));
                    }
                    Hold::Global(d.map(|x| x / n))
                }
            });
        }
        Ok(out)
    }

    fn location(&self, value: &Spanned<toml::Value>) -> String {
        match self.error_at("", value, "") {
            SceneError::Value { location, .. } => location,
            _ => self.path.display().to_string(),
        }
    }

    /// One `[sets]` key as rules in SI.
    pub(crate) fn set_rule(
        &self,
        key: &str,
        value: Option<&Spanned<toml::Value>>,
        pistons: bool,
    ) -> Result<Option<SetRule>> {
        let Some(value) = value else {
            return Ok(None);
        };
        let (rules, tolerance_given) = match value.get_ref() {
            toml::Value::Array(items) if !items.is_empty() => {
                let mut rules = Vec::new();
                let mut given = true;
                for item in items {
                    let (r, g) = self.rules_of(key, value, item, pistons)?;
                    rules.extend(r);
                    given &= g;
                }
                (rules, given)
            }
            v => self.rules_of(key, value, v, pistons)?,
        };
        Ok(Some(SetRule {
            key: key.to_string(),
            location: self.location(value),
            rules,
            tolerance_given,
        }))
    }

    /// The rules of one rule value `v` (a set name or a table of criteria; a table with
    /// `circles` gives one rule per circle) and whether it gives its tolerance.
    fn rules_of(
        &self,
        key: &str,
        value: &Spanned<toml::Value>,
        v: &toml::Value,
        pistons: bool,
    ) -> Result<(Vec<Rule>, bool)> {
        let l = self.length_unit()?;
        let bad = |m: String| self.error_at(key, value, m);
        let mut points = Vec::new();
        let (rule, circles, tolerance_given) = match v {
            toml::Value::String(s) if !s.trim().is_empty() => {
                (Rule::named(s.trim()), Vec::new(), false)
            }
            toml::Value::Table(t) => {
                let mut rule = Rule::default();
                let mut circles = Vec::new();
                let mut angle = None;
                let mut tolerance = None;
                for (k, v) in t {
                    let what = |form: &str| bad(format!("{k} must be {form}"));
                    match k.as_str() {
                        "set" => {
                            rule.set = Some(
                                v.as_str()
                                    .ok_or_else(|| what("the name of a node set"))?
                                    .to_string(),
                            )
                        }
                        "cylinder" | "plane" => {
                            if rule.surface.is_some() {
                                return Err(bad("give one of cylinder and plane, not both".into()));
                            }
                            rule.surface = Some(surface(k, v, l).map_err(&bad)?);
                        }
                        "box" => {
                            let form = "{ min = [x, y, z], max = [x, y, z] }";
                            let tb = v.as_table().ok_or_else(|| what(form))?;
                            let (min, max) = (
                                tb.get("min").and_then(vec3).ok_or_else(|| what(form))?,
                                tb.get("max").and_then(vec3).ok_or_else(|| what(form))?,
                            );
                            if tb.len() != 2 {
                                return Err(what(form));
                            }
                            rule.bbox = Some((min.map(|x| x * l), max.map(|x| x * l)));
                        }
                        "facing" => {
                            rule.facing =
                                Some((vec3(v).ok_or_else(|| what("a direction [x, y, z]"))?, 1.0))
                        }
                        "angle" => {
                            angle = Some(number(v).ok_or_else(|| what("an angle in degrees"))?)
                        }
                        "tolerance" => {
                            tolerance = Some(number(v).ok_or_else(|| what("a distance"))? * l)
                        }
                        "circles" if pistons => {
                            let form = "a list of { centre = [x, y, z], diameter = d }";
                            for c in v.as_array().ok_or_else(|| what(form))? {
                                let tc = c.as_table().ok_or_else(|| what(form))?;
                                let centre =
                                    tc.get("centre").and_then(vec3).ok_or_else(|| what(form))?;
                                let diameter = tc
                                    .get("diameter")
                                    .and_then(number)
                                    .ok_or_else(|| what(form))?;
                                if tc.len() != 2 {
                                    return Err(what(form));
                                }
                                circles.push(Circle {
                                    centre: centre.map(|x| x * l),
                                    diameter: diameter * l,
                                });
                            }
                            if circles.is_empty() {
                                return Err(what(form));
                            }
                        }
                        "points" if pistons => {
                            let form = "a list of points [[x, y, z], ...]";
                            for p in v.as_array().ok_or_else(|| what(form))? {
                                points.push(vec3(p).ok_or_else(|| what(form))?.map(|x| x * l));
                            }
                            if points.is_empty() {
                                return Err(what(form));
                            }
                        }
                        other => {
                            return Err(bad(format!(
                                "unknown criterion '{other}' (criteria: set, cylinder, plane, box, facing, angle, tolerance{})",
                                if pistons { ", circles, points" } else { "" }
                            )));
                        }
                    }
                }
                match (angle, &mut rule.facing) {
                    (Some(a), Some(f)) => f.1 = a,
                    (Some(_), None) => return Err(bad("angle goes with facing".into())),
                    _ => {}
                }
                if !circles.is_empty() && !points.is_empty() {
                    return Err(bad(
                        "give circles (footprints) or points (piston points), not both".into(),
                    ));
                }
                if !rule.is_geometric()
                    && circles.is_empty()
                    && points.is_empty()
                    && rule.set.is_none()
                {
                    return Err(bad(
                        "needs a set name or at least one criterion (set, cylinder, plane, box, facing)".into(),
                    ));
                }
                rule.tolerance = tolerance.unwrap_or(0.0);
                (rule, circles, tolerance.is_some())
            }
            _ => {
                return Err(bad(
                    "must be the name of a node set, a table of criteria (e.g. { facing = [0, 0, -1] }) or a list of them".into(),
                ));
            }
        };
        rule.check().map_err(|e| bad(e.to_string()))?;
        let rules = if !points.is_empty() {
            points
                .into_iter()
                .map(|p| {
                    let r = Rule {
                        nearest: Some(p),
                        ..rule.clone()
                    };
                    r.check().map_err(|e| bad(e.to_string()))?;
                    Ok(r)
                })
                .collect::<Result<Vec<_>>>()?
        } else if circles.is_empty() {
            vec![rule]
        } else {
            circles
                .into_iter()
                .map(|c| {
                    let r = Rule {
                        circle: Some(c),
                        ..rule.clone()
                    };
                    r.check().map_err(|e| bad(e.to_string()))?;
                    Ok(r)
                })
                .collect::<Result<Vec<_>>>()?
        };
        Ok((rules, tolerance_given))
    }

    /// The materials of `[materials]` in SI: `(element set, material)`, each checked as
    /// `squeal reduce --material` checks its own (a positive definite elasticity, a positive
    /// density). `normal` is the default axis of a transversely isotropic material.
    pub fn materials(&self) -> Result<Vec<(String, ElasticMaterial)>> {
        let units = self.units()?;
        let (s, rho) = (units.stress(), units.density());
        let normal = self.contact_direction()?;
        let mut out = Vec::new();
        for (set, m) in &self.file.materials {
            let key = |k: &str| format!("materials.{set}.{k}");
            let first = [
                &m.young,
                &m.poisson,
                &m.density,
                &m.young_plane,
                &m.poisson_plane,
                &m.young_axial,
                &m.poisson_plane_axial,
                &m.shear_axial,
            ]
            .into_iter()
            .flatten()
            .next();
            let Some(anchor) = first else {
                return Err(self.section_error(format!(
                    "[materials.{set}] needs young, poisson, density (isotropic) or young_plane, poisson_plane, young_axial, poisson_plane_axial, shear_axial, density (transversely isotropic)"
                )));
            };
            let need = |v: &Option<Spanned<f64>>, k: &str| -> Result<f64> {
                v.as_ref().map(|x| *x.get_ref()).ok_or_else(|| {
                    self.error_at(&format!("materials.{set}"), anchor, format!("needs {k}"))
                })
            };
            let density = need(&m.density, "density")? * rho;
            let iso = m.young.is_some() || m.poisson.is_some();
            let trans = [
                &m.young_plane,
                &m.poisson_plane,
                &m.young_axial,
                &m.poisson_plane_axial,
                &m.shear_axial,
            ]
            .iter()
            .any(|v| v.is_some())
                || m.axis.is_some();
            let material = match (iso, trans) {
                (true, true) => {
                    return Err(self.error_at(
                        &format!("materials.{set}"),
                        anchor,
                        "give either young and poisson (isotropic) or the transversely isotropic constants, not both",
                    ));
                }
                (true, false) => ElasticMaterial::Isotropic {
                    young: need(&m.young, "young")? * s,
                    poisson: need(&m.poisson, "poisson")?,
                    density,
                },
                (false, _) => ElasticMaterial::TransverselyIsotropic {
                    young_plane: need(&m.young_plane, "young_plane")? * s,
                    poisson_plane: need(&m.poisson_plane, "poisson_plane")?,
                    young_axial: need(&m.young_axial, "young_axial")? * s,
                    poisson_plane_axial: need(&m.poisson_plane_axial, "poisson_plane_axial")?,
                    shear_axial: need(&m.shear_axial, "shear_axial")? * s,
                    axis: m.axis.as_ref().map_or(normal, |a| *a.get_ref()),
                    density,
                },
            };
            if let Err(e) = material.elasticity() {
                return Err(self.error_at(
                    &key(if iso { "young" } else { "young_plane" }),
                    anchor,
                    e,
                ));
            }
            out.push((set.clone(), material));
        }
        Ok(out)
    }

    /// Warnings about the scene's own materials whose SI values look like another unit
    /// system's (a steel E of 2.1e5 read as pascals).
    pub fn material_warnings(&self) -> Result<Vec<String>> {
        let units = self.units()?;
        let mut out = Vec::new();
        for (set, m) in self.materials()? {
            let young = match m {
                ElasticMaterial::Isotropic { young, .. } => young,
                ElasticMaterial::TransverselyIsotropic {
                    young_plane,
                    young_axial,
                    ..
                } => young_plane.max(young_axial),
                ElasticMaterial::Orthotropic { e, .. } => e.iter().copied().fold(0.0, f64::max),
            };
            let what = format!("{}: [materials.{set}]", self.path.display());
            out.extend(squeal_mesh::units::check_modulus(&what, young, &units));
            out.extend(squeal_mesh::units::check_density(
                &what,
                m.density(),
                &units,
            ));
        }
        Ok(out)
    }
}

/// `cylinder = { point, axis, radius }` or `plane = { point, normal }`, lengths times `l`.
fn surface(kind: &str, v: &toml::Value, l: f64) -> std::result::Result<Surface, String> {
    let form = if kind == "cylinder" {
        "{ point = [x, y, z], axis = [x, y, z], radius = r }"
    } else {
        "{ point = [x, y, z], normal = [x, y, z] }"
    };
    let err = || format!("{kind} must be {form}");
    let t = v.as_table().ok_or_else(err)?;
    let point = t
        .get("point")
        .and_then(vec3)
        .ok_or_else(err)?
        .map(|x| x * l);
    if kind == "cylinder" {
        if t.len() != 3 {
            return Err(err());
        }
        Ok(Surface::Cylinder {
            point,
            axis: t.get("axis").and_then(vec3).ok_or_else(err)?,
            radius: t.get("radius").and_then(number).ok_or_else(err)? * l,
        })
    } else {
        if t.len() != 2 {
            return Err(err());
        }
        Ok(Surface::Plane {
            point,
            normal: t.get("normal").and_then(vec3).ok_or_else(err)?,
        })
    }
}
