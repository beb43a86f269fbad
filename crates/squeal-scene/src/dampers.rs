//! `[[dampers]]`: viscous dampers inside a part, between two node sets or from a set to
//! ground, in global or local axes, with the ends and spreads of `[[springs]]`
//! (`squeal_reduce::dampers` projects them by the part's Craig–Bampton basis).
//!
//! ```toml
//! [[dampers]]             # a piston seal's viscous loss, a shim's, a mount's
//! part = "pad"            # "disc", "pad" (a one-pad brake) or a [pads.<name>] name
//! set = "PISTON"          # one end: a node set, or a rule as in [sets]
//! to = "ground"           # the other end on the same part (a set or a rule), or "ground"
//!                         # (the default)
//! damping = [0.0, 0.0, 40.0]   # total N s/m along the axes (or the [units]
//!                              # force * time / length)
//! axes = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]   # optional: three orthogonal directions
//! spread = "mean"         # "mean" (default), "area" (to ground), "normal" (a sliding
//!                         # abutment: [c, 0, 0] along the normal), as for [[springs]]
//! ```
//!
//! A damper is Nastran's CDAMP/CBUSH `B` or Abaqus' DASHPOT (and `*DASHPOT` on a coupling) on
//! the same ends as a `[[springs]]` entry's: a spring and a dashpot in parallel (CBUSH with `K`
//! and `B`) are one `[[springs]]` and one `[[dampers]]` with the same `part`, `set`, `to`,
//! `axes` and `spread`. It adds viscous damping to the reduced brake beside the modal damping
//! of `[damping]`, in every analysis.

use crate::sets::SetRule;
use crate::springs::{Ends, SpringSpread, Wording};
use crate::{Result, Scene};
use serde::Deserialize;
use toml::Spanned;

/// `[[dampers]]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DamperSection {
    /// The part holding both ends.
    pub part: Spanned<String>,
    /// The first end: a node set or a rule.
    pub set: Spanned<toml::Value>,
    /// The second end on the same part, or `"ground"` (the default).
    pub to: Option<Spanned<toml::Value>>,
    /// Total damping coefficient along the three axes.
    pub damping: Spanned<[f64; 3]>,
    /// The axes, three directions (default x, y, z).
    pub axes: Option<Spanned<[[f64; 3]; 3]>>,
    /// `"mean"`, `"area"` or `"normal"`.
    pub spread: Option<Spanned<String>>,
}

/// A damper, typed: its part, the rules of its ends, damping in N s/m, orthonormal axes.
#[derive(Clone, Debug)]
pub struct DamperSpec {
    /// `disc` or the pad's name.
    pub part: String,
    /// The first end (key `dampers.<k>.set`).
    pub set: SetRule,
    /// The second end (key `dampers.<k>.to`); `None`: ground.
    pub to: Option<SetRule>,
    /// Total damping coefficient along the axes (N s/m).
    pub damping: [f64; 3],
    /// Orthonormal axes (rows), if given.
    pub axes: Option<[[f64; 3]; 3]>,
    /// How it meets its sets.
    pub spread: SpringSpread,
}

impl Scene {
    /// `[[dampers]]`, typed, in the order written.
    pub fn dampers(&self) -> Result<Vec<DamperSpec>> {
        let u = self.units()?;
        let per_speed = u.force() * u.time / u.length;
        let mut out = Vec::new();
        for (k, s) in self.file.dampers.iter().enumerate() {
            let key = |f: &str| format!("dampers.{}.{f}", k + 1);
            let part = self.check_part(&key("part"), &s.part)?;
            let c = *s.damping.get_ref();
            if c.iter().any(|x| !(x.is_finite() && *x >= 0.0)) || c.iter().all(|x| *x == 0.0) {
                return Err(self.error_at(
                    &key("damping"),
                    &s.damping,
                    "must be three damping coefficients >= 0 (N s/m along the axes), not all zero",
                ));
            }
            let ends = self.ends(
                &key,
                Ends {
                    set: &s.set,
                    to: &s.to,
                    axes: &s.axes,
                    spread: &s.spread,
                    values: (&s.damping, "damping", c),
                },
                &Wording {
                    normal_values: "a damper on a sliding abutment (spread = \"normal\") acts along the normal only: give [c, 0, 0]",
                    normal_axes: "a damper on a sliding abutment takes the normal of the face it bears on: leave out axes",
                    area_to: "a damper spread by area goes to ground: leave out `to`, or use spread = \"mean\" between two sets",
                },
            )?;
            out.push(DamperSpec {
                part,
                set: ends.set,
                to: ends.to,
                damping: c.map(|x| x * per_speed),
                axes: ends.axes,
                spread: ends.spread,
            });
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use crate::Scene;
    use crate::springs::SpringSpread;
    use std::path::Path;

    /// The bundled brake's scene with `extra` appended.
    fn scene(extra: &str) -> std::result::Result<Scene, String> {
        let base = std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/brake.toml"),
        )
        .unwrap();
        let s = Scene::parse(Path::new("/scenes/brake.toml"), format!("{base}\n{extra}"))
            .map_err(|e| e.to_string())?;
        s.dampers().map_err(|e| e.to_string())?;
        Ok(s)
    }

    #[test]
    fn dampers_are_typed_in_si_with_their_ends_and_axes() {
        let s = scene(
            "[[dampers]]\npart = \"pad\"\nset = \"PISTON\"\nto = \"ABUTMENT\"\ndamping = [1.0, 2.0, 3.0]\naxes = [[0, 2, 0], [-1, 0, 0], [0, 0, 1]]\n\n[[dampers]]\npart = \"disc\"\nset = \"CLAMP\"\ndamping = [0, 0, 5]\nspread = \"area\"\n[units]\nsystem = \"mm-t-s\"\n",
        )
        .unwrap();
        let v = s.dampers().unwrap();
        assert_eq!(v.len(), 2);
        // N s/mm to N s/m: the mm-t-s force unit is 1 N, so 1 N s/mm = 1e3 N s/m.
        assert_eq!(v[0].damping, [1e3, 2e3, 3e3]);
        assert_eq!(
            v[0].axes,
            Some([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
        );
        assert_eq!(v[0].spread, SpringSpread::Mean);
        assert_eq!(
            v[0].to.as_ref().map(|t| t.key.as_str()),
            Some("dampers.1.to")
        );
        assert!(v[1].to.is_none() && v[1].spread == SpringSpread::Area);
    }

    #[test]
    fn a_wrong_damper_names_its_key_and_line() {
        let head = "[[dampers]]\npart = \"pad\"\nset = \"PISTON\"\n";
        let cases = [
            ("damping = [0, 0, 0]\n", "dampers.1.damping", "not all zero"),
            (
                "damping = [1, -1, 0]\n",
                "dampers.1.damping",
                "not all zero",
            ),
            (
                "damping = [1, 1, 1]\nto = \"ABUTMENT\"\nspread = \"area\"\n",
                "dampers.1.spread",
                "goes to ground",
            ),
            (
                "damping = [1, 1, 1]\nspread = \"rigid\"\n",
                "dampers.1.spread",
                "is not \"mean\", \"area\" or \"normal\"",
            ),
            (
                "damping = [1, 1, 0]\nspread = \"normal\"\n",
                "dampers.1.damping",
                "give [c, 0, 0]",
            ),
            (
                "damping = [1, 1, 1]\naxes = [[1, 0, 0], [1, 1, 0], [0, 0, 1]]\n",
                "dampers.1.axes",
                "not orthogonal",
            ),
            (
                "damping = [1, 1, 1]\nstiffness = [1, 1, 1]\n",
                "stiffness",
                "unknown field",
            ),
        ];
        for (tail, key, want) in cases {
            let e = scene(&format!("{head}{tail}")).unwrap_err();
            assert!(
                e.contains(want) && e.contains(key) && e.contains("brake.toml:"),
                "{want}: {e}"
            );
        }
        let e = scene("[[dampers]]\npart = \"caliper\"\nset = \"X\"\ndamping = [1, 1, 1]\n")
            .unwrap_err();
        assert!(e.contains("'caliper' is not a part"), "{e}");
    }
}
