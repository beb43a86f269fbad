//! `*PART`, `*ASSEMBLY` and `*INSTANCE` (with its placement): where each part's nodes and elements go.

use super::*;

impl<'a> Reader<'a> {
    /// `*PART, NAME=`.
    pub(super) fn part(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["NAME"]);
        if self.context != Context::Model {
            return Err(self.err(kw.loc, "*PART inside another *PART or *ASSEMBLY (close it with *END PART / *END ASSEMBLY first)"));
        }
        let name = self.required(kw, "NAME")?;
        if let Some(p) = self
            .parts
            .iter()
            .find(|p| p.name.eq_ignore_ascii_case(name))
        {
            return Err(self.err(
                kw.loc,
                format!(
                    "part {name} is defined twice (first at line {})",
                    p.loc.line
                ),
            ));
        }
        self.parts.push(Part {
            name: name.to_string(),
            store: Store::default(),
            loc: kw.loc,
            instanced: false,
        });
        self.context = Context::Part(self.parts.len() - 1);
        Ok(())
    }

    /// `*ASSEMBLY`.
    pub(super) fn assembly(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["NAME"]);
        if self.context != Context::Model {
            return Err(self.err(kw.loc, "*ASSEMBLY inside a *PART or another *ASSEMBLY"));
        }
        if let Some(first) = self.assembly {
            return Err(self.err(
                kw.loc,
                format!("a second *ASSEMBLY (the first is at line {})", first.line),
            ));
        }
        self.assembly = Some(kw.loc);
        self.context = Context::Assembly;
        Ok(())
    }

    /// `*INSTANCE, NAME=, PART=` and its optional translation and rotation lines.
    pub(super) fn instance(&mut self, kw: &'a Keyword) -> Result<(), MeshError> {
        self.check_params(kw, &["NAME", "PART", "INSTANCE", "LIBRARY"]);
        if self.context != Context::Assembly {
            return Err(self.err(
                kw.loc,
                "*INSTANCE outside *ASSEMBLY (or inside another *INSTANCE)",
            ));
        }
        if kw.flag("INSTANCE") || kw.flag("LIBRARY") {
            return Err(self.err(kw.loc, "instances imported from a previous analysis (INSTANCE=, LIBRARY=) are not supported"));
        }
        let name = self.required(kw, "NAME")?;
        let part = self.required(kw, "PART")?;
        if let Some(x) = self
            .instances
            .iter()
            .find(|x| x.name.eq_ignore_ascii_case(name))
        {
            return Err(self.err(
                kw.loc,
                format!(
                    "instance {name} is defined twice (first at line {})",
                    x.loc.line
                ),
            ));
        }
        let p = self
            .parts
            .iter()
            .position(|x| x.name.eq_ignore_ascii_case(part))
            .ok_or_else(|| {
                self.err(
                    kw.loc,
                    format!("part {part} is not defined (before this line)"),
                )
            })?;
        if (self.instances.len() as u64 + 1)
            .checked_mul(INSTANCE_STRIDE)
            .and_then(|o| o.checked_add(INSTANCE_STRIDE))
            .is_none()
        {
            return Err(self.err(kw.loc, "too many instances to renumber"));
        }
        let placement = self.placement()?;
        self.parts[p].instanced = true;
        let store = self.parts[p].store.clone();
        self.instances.push(Instance {
            name: name.to_string(),
            store,
            placement,
            loc: kw.loc,
        });
        self.context = Context::Instance(self.instances.len() - 1);
        Ok(())
    }

    /// The optional `*INSTANCE` data lines: translation, then rotation.
    pub(super) fn placement(&mut self) -> Result<Placement, MeshError> {
        let mut p = Placement::default();
        if let Some(d) = self.next_data() {
            let t = self.reals::<3>(d, 0, "a translation 'x, y, z'")?;
            p.translation = t;
        }
        if let Some(d) = self.next_data() {
            let r = self.reals::<7>(d, 7, "a rotation 'ax, ay, az, bx, by, bz, angle'")?;
            if r[6] != 0.0 {
                p.rotation = Some(
                    Rotation::about_axis([r[0], r[1], r[2]], [r[3], r[4], r[5]], r[6]).ok_or_else(
                        || self.err(d.loc, "the rotation axis points a and b coincide"),
                    )?,
                );
            }
        }
        Ok(p)
    }

    /// Up to `N` reals (blank = 0) from a data line that must have at least `min` fields.
    pub(super) fn reals<const N: usize>(
        &self,
        d: &DataLine,
        min: usize,
        what: &str,
    ) -> Result<[f64; N], MeshError> {
        let text = self.lx.text(d);
        let mut v = [0.0; N];
        let mut n = 0;
        for f in fields(text) {
            if n == N {
                return Err(self.err(
                    d.loc,
                    format!("expected {what}, found more numbers: '{}'", excerpt(text)),
                ));
            }
            v[n] = real_or_zero(f).ok_or_else(|| {
                self.err(d.loc, format!("expected {what}, found '{}'", excerpt(f)))
            })?;
            n += 1;
        }
        if n < min {
            return Err(self.err(d.loc, format!("expected {what}, found '{}'", excerpt(text))));
        }
        Ok(v)
    }
}
