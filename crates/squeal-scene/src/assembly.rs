//! `[[supports]]` and `[[ties]]`: springs to ground and tied interfaces inside a part.
//!
//! ```toml
//! [[supports]]            # a spring to ground (the piston's seal, a finger, a bracket mount)
//! part = "pad"            # "disc", "pad" (a one-pad brake) or a [pads.<name>] name
//! set = "BACK_FACE"       # a node set, or a rule as in [sets] (e.g. a plane with facing)
//! stiffness = [0.0, 0.0, 2.0e7]   # total N/m along x, y, z (or the [units] force/length)
//!
//! [[ties]]                # a bonded interface: slave nodes move with the master face
//! part = "pad"            # the part holding both surfaces (a list of element sets in elset)
//! slave = "SHIM_TOP"      # node set or rule
//! master = "BACKPLATE_BACK"
//! tolerance = 1.0e-4      # optional (the [units] length): default 1 % of the master's size
//!
//! [[ties]]                # a bonded interface between two separately reduced parts
//! part = "shim"           # the slave's part: a [parts.<name>] part
//! slave = "SHIM_FRONT"    # its node set or rule
//! master_part = "inboard" # the master's part (any part); leave out for a tie inside `part`
//! master = "BACKPLATE_BACK"
//! ```
//!
//! With `master_part`, both sets stay physical boundary dofs of their parts' Craig–Bampton
//! reductions and the tie is eliminated exactly on the assembled reduced brake
//! (`squeal_reduce::part_tie`): the meshes need not match.
//!
//! The reduction shares a support's stiffness over its set by tributary area and adds it to
//! the part's stiffness before the Craig–Bampton reduction; a tie's constraints are
//! eliminated exactly before it (`squeal_reduce::tie`).

use crate::sets::SetRule;
use crate::{Result, Scene};
use serde::Deserialize;
use toml::Spanned;

/// `[[supports]]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SupportSection {
    /// The part: `disc`, `pad` or a pad's name.
    pub part: Spanned<String>,
    /// A node set or a rule.
    pub set: Spanned<toml::Value>,
    /// Total stiffness along x, y, z.
    pub stiffness: Spanned<[f64; 3]>,
}

/// `[[ties]]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TieSection {
    /// The part holding both surfaces.
    pub part: Spanned<String>,
    /// The slave surface: a node set or a rule.
    pub slave: Spanned<toml::Value>,
    /// The master face: a node set or a rule.
    pub master: Spanned<toml::Value>,
    /// Largest distance of a slave node from the master face.
    pub tolerance: Option<Spanned<f64>>,
    /// The master face's part when it is not `part`: a tie between two parts.
    pub master_part: Option<Spanned<String>>,
}

/// A support, typed: the part, its set's rules and the stiffness in N/m.
#[derive(Clone, Debug)]
pub struct SupportSpec {
    /// `disc` or the pad's name.
    pub part: String,
    /// The set (key `supports.<k>.set`).
    pub set: SetRule,
    /// Total stiffness along x, y, z (N/m).
    pub stiffness: [f64; 3],
}

/// A tie, typed.
#[derive(Clone, Debug)]
pub struct TieSpec {
    /// `disc` or the pad's name.
    pub part: String,
    /// The slave surface (key `ties.<k>.slave`).
    pub slave: SetRule,
    /// The master face (key `ties.<k>.master`).
    pub master: SetRule,
    /// Tolerance (m), if given.
    pub tolerance: Option<f64>,
    /// The master's part when it is another part than `part` (key `ties.<k>.master_part`):
    /// a tie between two separately reduced parts; `None`: both surfaces on `part`.
    pub master_part: Option<String>,
}

impl Scene {
    /// The part names a support or tie may name: `disc` and the pads'.
    /// Three spring stiffnesses (`along`: what they act along, for the message), each finite
    /// and `>= 0`, not all zero.
    pub(crate) fn check_stiffness(
        &self,
        key: &str,
        stiffness: &Spanned<[f64; 3]>,
        along: &str,
    ) -> Result<[f64; 3]> {
        let k = *stiffness.get_ref();
        if k.iter().any(|x| !(x.is_finite() && *x >= 0.0)) || k.iter().all(|x| *x == 0.0) {
            return Err(self.error_at(
                key,
                stiffness,
                format!("must be three stiffnesses >= 0 ({along}), not all zero"),
            ));
        }
        Ok(k)
    }

    pub(crate) fn check_part(&self, key: &str, part: &Spanned<String>) -> Result<String> {
        let names: Vec<String> = std::iter::once("disc".to_string())
            .chain(self.pads()?.into_iter().map(|p| p.0))
            .chain(self.bodies().into_iter().map(|p| p.0))
            .collect();
        let name = part.get_ref().trim();
        if !names.iter().any(|n| n == name) {
            return Err(self.error_at(
                key,
                part,
                format!("'{name}' is not a part (the parts: {})", names.join(", ")),
            ));
        }
        Ok(name.to_string())
    }

    /// `[[supports]]`, typed, in the order written.
    pub fn supports(&self) -> Result<Vec<SupportSpec>> {
        let u = self.units()?;
        let per_length = u.force() / u.length;
        let mut out = Vec::new();
        for (k, s) in self.file.supports.iter().enumerate() {
            let key = |f: &str| format!("supports.{}.{f}", k + 1);
            let part = self.check_part(&key("part"), &s.part)?;
            let stiffness = self.check_stiffness(&key("stiffness"), &s.stiffness, "x, y, z")?;
            let set = self
                .set_rule(&key("set"), Some(&s.set), false)?
                .ok_or_else(|| self.error_at(&key("set"), &s.set, "must select a node set"))?;
            out.push(SupportSpec {
                part,
                set,
                stiffness: stiffness.map(|x| x * per_length),
            });
        }
        Ok(out)
    }

    /// `[[ties]]`, typed, in the order written.
    pub fn ties(&self) -> Result<Vec<TieSpec>> {
        let l = self.length_unit()?;
        let mut out = Vec::new();
        for (k, t) in self.file.ties.iter().enumerate() {
            let key = |f: &str| format!("ties.{}.{f}", k + 1);
            let part = self.check_part(&key("part"), &t.part)?;
            let rule = |f: &str, v: &Spanned<toml::Value>| {
                self.set_rule(&key(f), Some(v), false)?
                    .ok_or_else(|| self.error_at(&key(f), v, "must select a node set"))
            };
            if let Some(tol) = &t.tolerance {
                self.positive(&key("tolerance"), tol)?;
            }
            let master_part = match &t.master_part {
                Some(m) => Some(self.check_part(&key("master_part"), m)?).filter(|m| *m != part),
                None => None,
            };
            if master_part.is_some() && !self.bodies().iter().any(|b| b.0 == part) {
                return Err(self.error_at(
                    &key("part"),
                    &t.part,
                    format!(
                        "the slave of a tie between parts must be a [parts.<name>] part, not '{part}': make the set on '{part}' the master (master_part = \"{part}\") and the other part's set the slave"
                    ),
                ));
            }
            out.push(TieSpec {
                master_part,
                part,
                slave: rule("slave", &t.slave)?,
                master: rule("master", &t.master)?,
                tolerance: t.tolerance.as_ref().map(|v| v.get_ref() * l),
            });
        }
        Ok(out)
    }
}
