//! `[parts.<name>]` and `[[connectors]]`: parts beyond the disc and the pads (a caliper, a
//! bracket, a knuckle) and springs between node sets of two parts or from a set to ground
//! (`squeal_reduce::coupling` derives them).
//!
//! ```toml
//! [parts.caliper]              # Abaqus *PART / an element set of the assembly file
//! mesh = "corner.inp"
//! elset = "CALIPER"            # a name or a list; leave out for the whole file
//!
//! [[connectors]]               # Abaqus *CONNECTOR (CARTESIAN + CARDAN elasticity), Nastran
//! name = "inboard piston"      # CBUSH, Ansys COMBI250/MPC184: a 6-dof spring between the
//! part = "inboard"             # mean motions of two node sets (Abaqus *COUPLING,
//! set = "INBOARD_PISTON"       # *DISTRIBUTING; Nastran RBE3)
//! to_part = "caliper"          # leave out (or "ground") for a spring to ground
//! to_set = "CALIPER_PISTON"
//! stiffness = [5.0e7, 5.0e7, 2.0e8]          # N/m along the axes (or [units] force/length)
//! rotational_stiffness = [1.0e3, 1.0e3, 0.0] # N m/rad about the axes (default 0)
//! axes = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]   # optional: three orthogonal directions
//! vibration_only = true        # optional: the spring acts on the vibration only (below)
//! ```
//!
//! `vibration_only = true` makes the connector's stiffness act on the vibration about the
//! static equilibrium only (the linearized brake, eqs (18)–(20), and the harmonics `k >= 1`
//! of the harmonic balance), not on the static equilibrium of eq (14) nor on the 0th
//! harmonic: a hydraulic piston, whose load on the pad is the line pressure times its area
//! whatever its stiffness, while the seal and the fluid column resist its vibration. It is
//! the spring of an Abaqus `*CONNECTOR` present only in the linear perturbation steps
//! (`*FREQUENCY`, `*COMPLEX FREQUENCY`) after the `*STATIC` preload step, or a Nastran
//! `CBUSH` whose `PBUSHT` gives the stiffness at frequency and 0 at rest. The default is
//! `false`: an elastic connector acts in the static step as well, as `CBUSH` and
//! `*CONNECTOR` do in every tool, and a finger (steel on the backplate) does. A static
//! problem left free by it (a floating caliper whose pistons and fingers are both
//! `vibration_only`) is singular: keep the fingers' stiffness static.
//!
//! Each set a connector names is kept by its part as a coupling point: its area-weighted
//! mean translation and least-squares rotation, six reduced dofs however many nodes it has.
//! A connector whose pad end is the pad's `load` set carries the clamp force (a piston, a
//! finger): the pad is pushed there and the other end pushed back. A connector whose pad end is
//! the pad's `abutments` set replaces the pad's abutment restraint: the pad slides on its
//! bracket through the connector's stiffness (give the axial stiffness 0 for a free slide).
//! `[[springs]]`, `[[supports]]` and `[[ties]]` may name a `[parts.<name>]` part as well.

use crate::sets::SetRule;
use crate::{Result, Scene};
use serde::Deserialize;
use std::path::PathBuf;
use toml::Spanned;

/// `[parts.<name>]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySection {
    /// The mesh file (relative to the scene).
    pub mesh: PathBuf,
    /// The part's element sets in that file: a name or a list (none: the whole file).
    pub elset: Option<Spanned<toml::Value>>,
}

/// `[[connectors]]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConnectorSection {
    /// Its name in messages and in the `.rom` (default `connectors.<k>`).
    pub name: Option<String>,
    /// The first end's part.
    pub part: Spanned<String>,
    /// The first end's node set (a name or a rule as in `[sets]`).
    pub set: Spanned<toml::Value>,
    /// The second end's part, or `"ground"` (the default).
    pub to_part: Option<Spanned<String>>,
    /// The second end's node set.
    pub to_set: Option<Spanned<toml::Value>>,
    /// Stiffness along the axes.
    pub stiffness: Spanned<[f64; 3]>,
    /// Rotational stiffness about the axes (N m/rad, or the `[units]` force × length).
    pub rotational_stiffness: Option<Spanned<[f64; 3]>>,
    /// The axes (default x, y, z).
    pub axes: Option<Spanned<[[f64; 3]; 3]>>,
    /// The spring acts on the vibration about the static equilibrium only (default false).
    pub vibration_only: Option<bool>,
}

/// A connector, typed: its ends' parts and set rules, stiffnesses in SI, orthonormal axes.
#[derive(Clone, Debug)]
pub struct ConnectorSpec {
    /// Its name.
    pub name: String,
    /// The first end's part.
    pub part: String,
    /// The first end's set (key `connectors.<k>.set`).
    pub set: SetRule,
    /// The second end (part and set, key `connectors.<k>.to_set`); `None`: ground.
    pub to: Option<(String, SetRule)>,
    /// N/m along the axes.
    pub stiffness: [f64; 3],
    /// N m/rad about the axes.
    pub rotational: [f64; 3],
    /// Orthonormal axes (rows).
    pub axes: [[f64; 3]; 3],
    /// `vibration_only`: the stiffness acts on the vibration about the static equilibrium
    /// only, not on the static equilibrium (the clamp force).
    pub vibration_only: bool,
}

impl Scene {
    /// `[parts.<name>]`: the further parts' names and mesh files (as written), in name order.
    pub fn bodies(&self) -> Vec<(String, PathBuf)> {
        self.file
            .parts
            .iter()
            .map(|(n, p)| (n.clone(), p.mesh.clone()))
            .collect()
    }

    /// The element sets of part `name` of `[parts]` (empty: the whole file).
    pub fn body_elset(&self, name: &str) -> Vec<String> {
        match self.file.parts.get(name).and_then(|p| p.elset.as_ref()) {
            Some(v) => match v.get_ref() {
                toml::Value::String(s) if !s.trim().is_empty() => vec![s.trim().to_string()],
                toml::Value::Array(a) => a
                    .iter()
                    .filter_map(|x| x.as_str().map(str::trim).filter(|s| !s.is_empty()))
                    .map(String::from)
                    .collect(),
                _ => Vec::new(),
            },
            None => Vec::new(),
        }
    }

    /// `[[connectors]]`, typed, in the order written.
    pub fn connectors(&self) -> Result<Vec<ConnectorSpec>> {
        let u = self.units()?;
        let per_length = u.force() / u.length;
        let per_radian = u.force() * u.length;
        let mut out = Vec::new();
        for (k, c) in self.file.connectors.iter().enumerate() {
            let key = |f: &str| format!("connectors.{}.{f}", k + 1);
            let part = self.check_part(&key("part"), &c.part)?;
            let rule = |f: &str, v: &Spanned<toml::Value>| {
                self.set_rule(&key(f), Some(v), false)?
                    .ok_or_else(|| self.error_at(&key(f), v, "must select a node set"))
            };
            let set = rule("set", &c.set)?;
            let to = match (&c.to_part, &c.to_set) {
                (None, None) => None,
                (Some(p), None) if p.get_ref().trim() == "ground" => None,
                (Some(p), Some(s)) => {
                    let name = self.check_part(&key("to_part"), p)?;
                    if name == part {
                        return Err(self.error_at(
                            &key("to_part"),
                            p,
                            "both ends are on one part: a spring inside a part is a [[springs]] entry",
                        ));
                    }
                    Some((name, rule("to_set", s)?))
                }
                (Some(p), None) => {
                    return Err(self.error_at(
                        &key("to_part"),
                        p,
                        "give to_set, the node set of the other part the connector holds",
                    ));
                }
                (None, Some(s)) => {
                    return Err(self.error_at(
                        &key("to_set"),
                        s,
                        "give to_part, the part this set is on (or leave both out for ground)",
                    ));
                }
            };
            let bad = |v: &Spanned<[f64; 3]>, what: &str| -> Result<[f64; 3]> {
                let k3 = *v.get_ref();
                if k3.iter().any(|x| !(x.is_finite() && *x >= 0.0)) {
                    return Err(self.error_at(
                        &key(what),
                        v,
                        "must be three stiffnesses >= 0 along the axes",
                    ));
                }
                Ok(k3)
            };
            let stiffness = bad(&c.stiffness, "stiffness")?;
            let rotational = match &c.rotational_stiffness {
                Some(v) => bad(v, "rotational_stiffness")?,
                None => [0.0; 3],
            };
            if stiffness.iter().chain(&rotational).all(|x| *x == 0.0) {
                return Err(self.error_at(
                    &key("stiffness"),
                    &c.stiffness,
                    "the connector has no stiffness at all: give a stiffness > 0 along some axis",
                ));
            }
            let axes = match &c.axes {
                Some(a) => crate::springs::orthonormal(*a.get_ref())
                    .map_err(|m| self.error_at(&key("axes"), a, m))?,
                None => [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            };
            out.push(ConnectorSpec {
                name: c
                    .name
                    .clone()
                    .unwrap_or_else(|| format!("connectors.{}", k + 1)),
                part,
                set,
                to,
                stiffness: stiffness.map(|x| x * per_length),
                rotational: rotational.map(|x| x * per_radian),
                axes,
                vibration_only: c.vibration_only.unwrap_or(false),
            });
        }
        Ok(out)
    }
}
