//! `*NSET` and `*ELSET` (with `GENERATE` and members by set name or instance) and the ends of blocks.

use super::*;

impl<'a> Reader<'a> {
    /// `*NSET` / `*ELSET`, with or without `GENERATE`, at part, instance or assembly level.
    pub(super) fn set(&mut self, kw: &'a Keyword, kind: Kind) -> Result<(), MeshError> {
        let pname = match kind {
            Kind::Node => "NSET",
            Kind::Element => "ELSET",
        };
        self.check_params(
            kw,
            &[
                pname, "GENERATE", "INSTANCE", "UNSORTED", "INTERNAL", "INPUT", "ELSET",
            ],
        );
        let name = self.required(kw, pname)?;
        if kind == Kind::Node && kw.flag("ELSET") {
            return Err(self.err(
                kw.loc,
                "*NSET with ELSET= (the nodes of an element set) is not supported",
            ));
        }
        let generate = kw.flag("GENERATE");
        let dest = self.target();
        let (src, offset) = match self.name_param(kw, "INSTANCE")? {
            None => (dest, 0),
            Some(inst) => {
                if self.context != Context::Assembly {
                    return Err(self.err(kw.loc, "INSTANCE= names an instance only at assembly level (inside *ASSEMBLY, outside *INSTANCE)"));
                }
                let i = self.find_instance(inst).ok_or_else(|| {
                    self.err(
                        kw.loc,
                        format!("instance {inst} is not defined (before this line)"),
                    )
                })?;
                (Target::Instance(i), Self::offset(i))
            }
        };
        let mut members = BTreeSet::new();
        let mut missing = 0u64;
        while let Some(d) = self.next_data() {
            if generate {
                missing =
                    missing.saturating_add(self.generate(d, kind, src, offset, &mut members)?);
            } else {
                for f in fields(self.lx.text(d)) {
                    if !f.is_empty() {
                        self.member(f, kind, src, offset, d.loc, &mut members)?;
                    }
                }
            }
        }
        if missing > 0 {
            let noun = kind.noun();
            self.warn(
                kw.loc,
                format!("GENERATE ranges of set {name} name {missing} {noun} labels that are not defined (before this line): they are left out"),
            );
        }
        self.store_mut(dest)
            .sets_mut(kind)
            .entry(name)
            .ids
            .extend(members);
        Ok(())
    }

    /// One `start, end[, step]` line of a `GENERATE` set: adds the labels in the range that
    /// are defined in `src` and returns how many in the range are not. The work is bounded
    /// by the number of labels defined, not by the size of the range.
    pub(super) fn generate(
        &mut self,
        d: &DataLine,
        kind: Kind,
        src: Target,
        offset: u64,
        out: &mut BTreeSet<u64>,
    ) -> Result<u64, MeshError> {
        let text = self.lx.text(d);
        let mut v = [0u64; 3];
        let mut n = 0;
        for f in fields(text) {
            if n == 3 {
                return Err(self.err(
                    d.loc,
                    format!(
                        "expected GENERATE data 'start, end[, step]', found '{}'",
                        excerpt(text)
                    ),
                ));
            }
            v[n] = label(f).ok_or_else(|| {
                self.err(d.loc, format!("expected GENERATE data 'start, end[, step]' as non-negative integers, found '{}'", excerpt(f)))
            })?;
            n += 1;
        }
        if n < 2 {
            return Err(self.err(
                d.loc,
                format!(
                    "expected GENERATE data 'start, end[, step]', found '{}'",
                    excerpt(text)
                ),
            ));
        }
        let (start, end, step) = (v[0], v[1], if n == 3 { v[2] } else { 1 });
        if step == 0 {
            return Err(self.err(d.loc, "GENERATE step is 0; expected a positive step"));
        }
        if end < start {
            return Err(self.err(
                d.loc,
                format!("GENERATE range ends ({end}) before it starts ({start})"),
            ));
        }
        // In u128: 0 to u64::MAX has 2^64 members, one more than a u64 holds.
        let members = u128::from(end - start) / u128::from(step) + 1;
        let count = match u64::try_from(members) {
            Ok(c) if c <= MAX_GENERATE => c,
            _ => {
                return Err(self.err(
                    d.loc,
                    format!("GENERATE range {start} to {end} step {step} has {members} members, more than the {MAX_GENERATE} a mesh can hold"),
                ));
            }
        };
        let store = self.store(src);
        let mut found = 0u64;
        if count <= store.count(kind) as u64 {
            let mut id = start;
            loop {
                if store.has(kind, id) {
                    out.insert(id + offset);
                    found += 1;
                }
                match id.checked_add(step) {
                    Some(next) if next <= end => id = next,
                    _ => break,
                }
            }
        } else {
            for id in store
                .labels(kind)
                .filter(|&id| id >= start && id <= end && (id - start) % step == 0)
            {
                out.insert(id + offset);
                found += 1;
            }
        }
        Ok(count.saturating_sub(found))
    }

    /// One member of a set's data line: a label, a set name, or (at assembly level)
    /// `instance.label` / `instance.set`.
    pub(super) fn member(
        &self,
        token: &str,
        kind: Kind,
        src: Target,
        offset: u64,
        loc: Loc,
        out: &mut BTreeSet<u64>,
    ) -> Result<(), MeshError> {
        let noun = kind.noun();
        if token.starts_with(|c: char| c.is_ascii_digit() || matches!(c, '+' | '-' | '.')) {
            let id = label(token).ok_or_else(|| {
                self.err(
                    loc,
                    format!(
                        "expected a {noun} label or a set name, found '{}'",
                        excerpt(token)
                    ),
                )
            })?;
            if src != Target::Global {
                self.check_instance_label(id, loc)?;
            }
            out.insert(id + offset);
            return Ok(());
        }
        let name = token.trim_matches('"');
        if let Some(set) = self.store(src).sets(kind).get(name) {
            out.extend(set.ids.iter().map(|&v| v + offset));
            return Ok(());
        }
        if src == Target::Global
            && let Some((inst, rest)) = name.split_once('.')
            && let Some(i) = self.find_instance(inst)
        {
            let off = Self::offset(i);
            if let Some(id) = label(rest) {
                self.check_instance_label(id, loc)?;
                out.insert(id + off);
                return Ok(());
            }
            if let Some(set) = self.instances[i].store.sets(kind).get(rest) {
                out.extend(set.ids.iter().map(|&v| v + off));
                return Ok(());
            }
            return Err(self.err(
                loc,
                format!("instance {inst} has no {noun} set '{rest}' (before this line)"),
            ));
        }
        Err(self.err(
            loc,
            format!(
                "{noun} set '{}' is not defined (before this line)",
                excerpt(name)
            ),
        ))
    }

    pub(super) fn check_instance_label(&self, id: u64, loc: Loc) -> Result<(), MeshError> {
        if id >= INSTANCE_STRIDE {
            return Err(self.err(
                loc,
                format!(
                    "label {id} is too large for a part or instance (at most {})",
                    INSTANCE_STRIDE - 1
                ),
            ));
        }
        Ok(())
    }

    /// `*END PART`, `*END ASSEMBLY`, `*END INSTANCE`.
    pub(super) fn end(
        &mut self,
        kw: &Keyword,
        open: impl Fn(Context) -> bool,
        outer: Context,
        opener: &str,
    ) -> Result<(), MeshError> {
        if !open(self.context) {
            return Err(self.err(kw.loc, format!("*{} without an open {opener}", kw.name)));
        }
        self.context = outer;
        Ok(())
    }
}
