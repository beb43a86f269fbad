//! `*MATERIAL`, `*ELASTIC`, `*DENSITY` and `*SOLID SECTION`: the materials of the element sets.

use super::*;

impl<'a> Reader<'a> {
    /// `*MATERIAL, NAME=`.
    pub(super) fn material(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["NAME"]);
        let name = self.required(kw, "NAME")?;
        if self
            .materials
            .iter()
            .any(|m| m.name.eq_ignore_ascii_case(name))
        {
            return Err(self.err(kw.loc, format!("material {name} is defined twice")));
        }
        self.materials.push(MaterialDef {
            name: name.to_string(),
            material: Material::default(),
        });
        self.material = Some(self.materials.len() - 1);
        Ok(())
    }

    pub(super) fn current_material(&self, kw: &Keyword) -> Result<usize, MeshError> {
        self.material
            .ok_or_else(|| self.err(kw.loc, format!("*{} must follow *MATERIAL", kw.name)))
    }

    /// Reals of the data lines following a material option: at least `min` fields must be
    /// present on the first line(s); values are taken in order across lines until `want`
    /// are read. Returns the values and the number of lines left over (temperature
    /// dependence, which squeal ignores).
    pub(super) fn option_values(
        &mut self,
        kw: &Keyword,
        want: usize,
        names: &[&str],
    ) -> Result<(Vec<f64>, usize), MeshError> {
        let mut vals = Vec::with_capacity(want);
        let mut extra = 0;
        while let Some(d) = self.next_data() {
            if vals.len() >= want {
                extra += 1;
                continue;
            }
            for f in fields(self.lx.text(d)) {
                if vals.len() == want {
                    break; // a temperature or field variable
                }
                let what = names[vals.len()];
                let v = if f.is_empty() {
                    None
                } else {
                    Some(real(f).ok_or_else(|| {
                        self.err(
                            d.loc,
                            format!("expected {what} as a number, found '{}'", excerpt(f)),
                        )
                    })?)
                };
                vals.push(v.unwrap_or(0.0));
            }
        }
        if vals.len() < want {
            return Err(self.err(
                kw.loc,
                format!(
                    "*{} needs {want} value{} ({}), found {}",
                    kw.name,
                    if want == 1 { "" } else { "s" },
                    names.join(", "),
                    vals.len()
                ),
            ));
        }
        Ok((vals, extra))
    }

    /// `*ELASTIC`: `TYPE=ISOTROPIC` (E, nu) or `TYPE=ENGINEERING CONSTANTS` (E1, E2, E3, nu12,
    /// nu13, nu23, G12, G13, G23 over two lines).
    pub(super) fn elastic(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["TYPE", "MODULI", "DEPENDENCIES"]);
        let m = self.current_material(kw)?;
        let ty = self
            .name_param(kw, "TYPE")?
            .unwrap_or("ISOTROPIC")
            .split_whitespace()
            .collect::<String>()
            .to_ascii_uppercase();
        let elastic = match ty.as_str() {
            "ISOTROPIC" | "ISO" => {
                let (v, extra) = self.option_values(kw, 2, &["E", "nu"])?;
                self.warn_temperature(kw, extra);
                Elastic::Isotropic {
                    young: v[0],
                    poisson: v[1],
                }
            }
            "ENGINEERINGCONSTANTS" => {
                let names = [
                    "E1", "E2", "E3", "nu12", "nu13", "nu23", "G12", "G13", "G23",
                ];
                let (v, extra) = self.option_values(kw, 9, &names)?;
                self.warn_temperature(kw, extra);
                Elastic::EngineeringConstants {
                    e: [v[0], v[1], v[2]],
                    nu: [v[3], v[4], v[5]],
                    g: [v[6], v[7], v[8]],
                }
            }
            other => {
                return Err(self.err(
                    kw.loc,
                    format!("*ELASTIC, TYPE={other} is not supported (expected ISOTROPIC or ENGINEERING CONSTANTS)"),
                ));
            }
        };
        self.materials[m].material.elastic = Some(elastic);
        Ok(())
    }

    pub(super) fn warn_temperature(&mut self, kw: &Keyword, extra_lines: usize) {
        if extra_lines > 0 {
            self.warn(kw.loc, format!("*{} has more data lines (temperature-dependent data?): squeal uses the first set of values", kw.name));
        }
    }

    /// `*DENSITY`.
    pub(super) fn density(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["DEPENDENCIES"]);
        let m = self.current_material(kw)?;
        let (v, extra) = self.option_values(kw, 1, &["the density"])?;
        self.warn_temperature(kw, extra);
        self.materials[m].material.density = Some(v[0]);
        Ok(())
    }

    /// `*SOLID SECTION, ELSET=, MATERIAL=`.
    pub(super) fn solid_section(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["ELSET", "MATERIAL", "ORIENTATION", "CONTROLS"]);
        if kw.flag("COMPOSITE") {
            return Err(self.err(kw.loc, "*SOLID SECTION, COMPOSITE is not supported"));
        }
        let elset = self.required(kw, "ELSET")?;
        let material = self.required(kw, "MATERIAL")?;
        if let Some(o) = self.name_param(kw, "ORIENTATION")? {
            self.warn(
                kw.loc,
                format!(
                    "ORIENTATION={o} ignored: squeal takes material constants in the global axes"
                ),
            );
        }
        self.skip_data();
        let t = self.target();
        self.store_mut(t).sections.push(SectionRef {
            element_set: elset.to_string(),
            material: material.to_string(),
            loc: kw.loc,
        });
        Ok(())
    }
}
