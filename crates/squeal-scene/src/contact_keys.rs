//! The scene's disc rotation, sliding direction, initial gaps, contact law and pairing: each key read once into a typed value, with the key's line in every error.

use super::*;

impl Scene {
    /// The disc's angular speed (rad/s) from `[rotation]` (or the older `[disc]`), `None`
    /// when the scene gives none.
    pub fn disc_angular_speed(&self) -> Result<Option<f64>> {
        Ok(self.rotation()?.and_then(|r| r.angular_speed))
    }

    /// A speed from `rpm`, or `vehicle_speed_kmh` with `rolling_radius` (keys under `section`).
    pub(super) fn speed(
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
    pub(super) fn sliding_error(&self, message: &str) -> SceneError {
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
        if let Some(law) = self.regularized_coulomb_law() {
            return law;
        }
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
}
