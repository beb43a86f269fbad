//! `[[springs]]`: springs inside a part, between two node sets or from a set to ground, in
//! global or local axes (`squeal_reduce::springs` derives them).
//!
//! ```toml
//! [[springs]]             # a caliper finger on the outboard backplate, a piston seal, a mount
//! part = "outboard"       # "disc", "pad" (a one-pad brake) or a [pads.<name>] name
//! set = "FINGER_PATCH"    # one end: a node set, or a rule as in [sets]
//! to = "FINGER_TIP"       # the other end on the same part (a set or a rule), or "ground"
//!                         # (the default)
//! stiffness = [2.0e7, 2.0e7, 5.0e7]   # total N/m along the axes (or the [units]
//!                                     # force/length)
//! axes = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]   # optional: three orthogonal directions
//! spread = "mean"         # "mean" (default): between the sets' area-weighted mean motions;
//!                         # "area": shared over the set by tributary area (to ground only);
//!                         # "normal": a sliding abutment, stiffness [k, 0, 0] along the
//!                         # normal of the face `to` (or of the set's own face against a rigid
//!                         # bracket), free across it
//! ```
//!
//! `axes` are made unit length and then orthonormal (Gram–Schmidt, in the order given); two
//! given directions more than 1e-6 from orthogonal (cosine) are refused. Viscous damping on
//! a spring (`damping`) is refused with the way to give it: a `[[dampers]]` entry on the same
//! ends ([`crate::dampers`]).

use crate::sets::SetRule;
use crate::{Result, Scene};
use serde::Deserialize;
use toml::Spanned;

/// `[[springs]]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringSection {
    /// The part holding both ends.
    pub part: Spanned<String>,
    /// The first end: a node set or a rule.
    pub set: Spanned<toml::Value>,
    /// The second end on the same part, or `"ground"` (the default).
    pub to: Option<Spanned<toml::Value>>,
    /// Total stiffness along the three axes.
    pub stiffness: Spanned<[f64; 3]>,
    /// The axes, three directions (default x, y, z).
    pub axes: Option<Spanned<[[f64; 3]; 3]>>,
    /// `"mean"` or `"area"`.
    pub spread: Option<Spanned<String>>,
    /// Viscous damping: refused (module docs).
    pub damping: Option<Spanned<toml::Value>>,
}

/// How a spring meets its sets (`squeal_reduce::springs::Spread`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpringSpread {
    /// Between the sets' area-weighted mean motions.
    Mean,
    /// Shared by tributary area, to ground.
    Area,
    /// A sliding abutment: along the normal of the face borne on, by tributary area.
    Normal,
}

/// A spring, typed: its part, the rules of its ends, stiffness in N/m, orthonormal axes.
#[derive(Clone, Debug)]
pub struct SpringSpec {
    /// `disc` or the pad's name.
    pub part: String,
    /// The first end (key `springs.<k>.set`).
    pub set: SetRule,
    /// The second end (key `springs.<k>.to`); `None`: ground.
    pub to: Option<SetRule>,
    /// Total stiffness along the axes (N/m).
    pub stiffness: [f64; 3],
    /// Orthonormal axes (rows), if given.
    pub axes: Option<[[f64; 3]; 3]>,
    /// How it meets its sets.
    pub spread: SpringSpread,
}

/// Largest cosine between two given axes.
const ORTHOGONAL: f64 = 1e-6;

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The axes made orthonormal (Gram–Schmidt in the order given), or what is wrong with them.
pub(crate) fn orthonormal(axes: [[f64; 3]; 3]) -> std::result::Result<[[f64; 3]; 3], String> {
    let mut out = [[0.0; 3]; 3];
    for (i, a) in axes.iter().enumerate() {
        let n = dot(*a, *a).sqrt();
        if !(n.is_finite() && n > 0.0) {
            return Err(format!("axis {} has no direction", i + 1));
        }
        let mut v = a.map(|x| x / n);
        for (j, e) in out.iter().take(i).enumerate() {
            let c = dot(v, *e);
            if c.abs() > ORTHOGONAL {
                return Err(format!(
                    "axes {} and {} are not orthogonal (cosine {c:.3e}): give three orthogonal directions",
                    j + 1,
                    i + 1
                ));
            }
            for d in 0..3 {
                v[d] -= c * e[d];
            }
        }
        let n = dot(v, v).sqrt();
        out[i] = v.map(|x| x / n);
    }
    Ok(out)
}

/// The parts of a `[[springs]]` or `[[dampers]]` entry that both share: its ends, axes and
/// spread, and its three values (`(span, key, values)`: stiffness or damping).
pub(crate) struct Ends<'a> {
    pub set: &'a Spanned<toml::Value>,
    pub to: &'a Option<Spanned<toml::Value>>,
    pub axes: &'a Option<Spanned<[[f64; 3]; 3]>>,
    pub spread: &'a Option<Spanned<String>>,
    pub values: (&'a Spanned<[f64; 3]>, &'static str, [f64; 3]),
}

/// The messages of [`Scene::ends`] that name the kind of entry.
pub(crate) struct Wording {
    /// A sliding abutment given values across its normal.
    pub normal_values: &'static str,
    /// A sliding abutment given axes.
    pub normal_axes: &'static str,
    /// An area spread given a second end.
    pub area_to: &'static str,
}

/// [`Ends`], typed.
pub(crate) struct TypedEnds {
    pub set: SetRule,
    pub to: Option<SetRule>,
    pub axes: Option<[[f64; 3]; 3]>,
    pub spread: SpringSpread,
}

impl Scene {
    /// The ends, axes and spread of the entry whose keys `key` names, checked together (a
    /// sliding abutment has one value, along the normal it finds, and no axes; an area spread
    /// goes to ground).
    pub(crate) fn ends(
        &self,
        key: &dyn Fn(&str) -> String,
        e: Ends<'_>,
        w: &Wording,
    ) -> Result<TypedEnds> {
        let axes = match e.axes {
            Some(a) => {
                Some(orthonormal(*a.get_ref()).map_err(|m| self.error_at(&key("axes"), a, m))?)
            }
            None => None,
        };
        let rule = |f: &str, v: &Spanned<toml::Value>| {
            self.set_rule(&key(f), Some(v), false)?
                .ok_or_else(|| self.error_at(&key(f), v, "must select a node set"))
        };
        let to = match e.to {
            Some(v) if v.get_ref().as_str() == Some("ground") => None,
            Some(v) => Some(rule("to", v)?),
            None => None,
        };
        let spread = match e.spread.as_ref().map(|v| (v, v.get_ref().trim())) {
            None | Some((_, "mean")) => SpringSpread::Mean,
            Some((_, "area")) => SpringSpread::Area,
            Some((_, "normal")) => SpringSpread::Normal,
            Some((v, other)) => {
                return Err(self.error_at(
                    &key("spread"),
                    v,
                    format!("'{other}' is not \"mean\", \"area\" or \"normal\""),
                ));
            }
        };
        let (span, name, values) = e.values;
        if spread == SpringSpread::Normal && (values[1] != 0.0 || values[2] != 0.0) {
            return Err(self.error_at(&key(name), span, w.normal_values));
        }
        if let (SpringSpread::Normal, Some(a)) = (spread, e.axes) {
            return Err(self.error_at(&key("axes"), a, w.normal_axes));
        }
        if spread == SpringSpread::Area
            && let (Some(v), Some(_)) = (e.spread, &to)
        {
            return Err(self.error_at(&key("spread"), v, w.area_to));
        }
        Ok(TypedEnds {
            set: rule("set", e.set)?,
            to,
            axes,
            spread,
        })
    }
    /// `[[springs]]`, typed, in the order written.
    pub fn springs(&self) -> Result<Vec<SpringSpec>> {
        let u = self.units()?;
        let per_length = u.force() / u.length;
        let mut out = Vec::new();
        for (k, s) in self.file.springs.iter().enumerate() {
            let key = |f: &str| format!("springs.{}.{f}", k + 1);
            if let Some(d) = &s.damping {
                return Err(self.error_at(
                    &key("damping"),
                    d,
                    "a spring has no damping: give the dashpot as a [[dampers]] entry with the same part, set, to, axes and spread (damping = [..] in N s/m), as a Nastran CBUSH's B or an Abaqus DASHPOT beside the spring",
                ));
            }
            let part = self.check_part(&key("part"), &s.part)?;
            let stiffness =
                self.check_stiffness(&key("stiffness"), &s.stiffness, "along the axes")?;
            let ends = self.ends(
                &key,
                Ends {
                    set: &s.set,
                    to: &s.to,
                    axes: &s.axes,
                    spread: &s.spread,
                    values: (&s.stiffness, "stiffness", stiffness),
                },
                &Wording {
                    normal_values: "a sliding abutment (spread = \"normal\") has one stiffness, along the normal: give [k, 0, 0]",
                    normal_axes: "a sliding abutment takes the normal of the face it bears on: leave out axes",
                    area_to: "a spring spread by area goes to ground: leave out `to`, or use spread = \"mean\" between two sets",
                },
            )?;
            out.push(SpringSpec {
                part,
                set: ends.set,
                to: ends.to,
                stiffness: stiffness.map(|x| x * per_length),
                axes: ends.axes,
                spread: ends.spread,
            });
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::{SpringSpread, orthonormal};
    use crate::Scene;
    use std::path::Path;

    /// The bundled brake's scene with `extra` appended, in `units`' system.
    fn scene(extra: &str) -> std::result::Result<Scene, String> {
        let base = std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/brake.toml"),
        )
        .unwrap();
        let s = Scene::parse(Path::new("/scenes/brake.toml"), format!("{base}\n{extra}"))
            .map_err(|e| e.to_string())?;
        s.springs().map_err(|e| e.to_string())?;
        Ok(s)
    }

    #[test]
    fn springs_are_typed_in_si_with_their_ends_and_axes() {
        let s = scene(
            "[[springs]]\npart = \"pad\"\nset = \"PISTON\"\nto = \"ABUTMENT\"\nstiffness = [1.0, 2.0, 3.0]\naxes = [[0, 2, 0], [-1, 0, 0], [0, 0, 1]]\n\n[[springs]]\npart = \"disc\"\nset = \"CLAMP\"\nstiffness = [0, 0, 5]\nspread = \"area\"\n[units]\nsystem = \"mm-t-s\"\n",
        )
        .unwrap();
        let v = s.springs().unwrap();
        assert_eq!(v.len(), 2);
        // N/mm to N/m.
        assert_eq!(v[0].stiffness, [1e3, 2e3, 3e3]);
        assert_eq!(
            v[0].axes,
            Some([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
        );
        assert_eq!(v[0].spread, SpringSpread::Mean);
        assert_eq!(
            v[0].to.as_ref().map(|t| t.key.as_str()),
            Some("springs.1.to")
        );
        assert!(v[1].to.is_none() && v[1].spread == SpringSpread::Area);
    }

    #[test]
    fn a_wrong_spring_names_its_key_and_line() {
        let head = "[[springs]]\npart = \"pad\"\nset = \"PISTON\"\n";
        let cases = [
            (
                "stiffness = [1, 1, 1]\ndamping = [1, 1, 1]\n",
                "springs.1.damping",
            ),
            ("stiffness = [0, 0, 0]\n", "not all zero"),
            (
                "stiffness = [1, 1, 1]\nto = \"ABUTMENT\"\nspread = \"area\"\n",
                "goes to ground",
            ),
            (
                "stiffness = [1, 1, 1]\nspread = \"rigid\"\n",
                "is not \"mean\", \"area\" or \"normal\"",
            ),
            (
                "stiffness = [1, 1, 0]\nspread = \"normal\"\n",
                "give [k, 0, 0]",
            ),
            (
                "stiffness = [1, 1, 1]\naxes = [[1, 0, 0], [1, 1, 0], [0, 0, 1]]\n",
                "not orthogonal",
            ),
        ];
        for (tail, want) in cases {
            let e = scene(&format!("{head}{tail}")).unwrap_err();
            assert!(e.contains(want) && e.contains("brake.toml:"), "{want}: {e}");
        }
        let e = scene("[[springs]]\npart = \"caliper\"\nset = \"X\"\nstiffness = [1, 1, 1]\n")
            .unwrap_err();
        assert!(e.contains("'caliper' is not a part"), "{e}");
    }

    #[test]
    fn axes_are_made_orthonormal_and_skew_ones_refused() {
        let c = 30f64.to_radians().cos();
        let s = 30f64.to_radians().sin();
        // Written to 4 digits: within 1e-6 of orthogonal after scaling, made exact.
        let a = orthonormal([[2.0 * c, 2.0 * s, 0.0], [-s, c, 0.0], [0.0, 0.0, 3.0]]).unwrap();
        for i in 0..3 {
            for j in 0..3 {
                let d: f64 = (0..3).map(|k| a[i][k] * a[j][k]).sum();
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((d - want).abs() < 1e-15, "{i} {j} {d}");
            }
        }
        let e = orthonormal([[1.0, 0.0, 0.0], [0.1, 1.0, 0.0], [0.0, 0.0, 1.0]]).unwrap_err();
        assert!(e.contains("axes 1 and 2 are not orthogonal"), "{e}");
        let e = orthonormal([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0; 3]]).unwrap_err();
        assert!(e.contains("axis 3 has no direction"), "{e}");
    }
}
