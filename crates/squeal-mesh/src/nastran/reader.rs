//! The card interpreter: sorts the cards by kind (bulk data may come in any order), resolves
//! coordinate systems, then fills a [`MeshBuilder`]: grids, solid elements (node order
//! mapped to squeal's), one element set per property, materials, sections and sets.

use super::coord::{Definition, Frame, Kind};
use super::lex::{Card, Lexed, Loc, Named};
use super::number::{int, real, real_or};
use crate::{Elastic, Location, Material, MeshBuilder, MeshError, ReadMesh, Warning};
use squeal_element::ElementKind;
use std::collections::{BTreeMap, HashMap};

/// A solid element card: its squeal kind, its first-order node count (skipped with a
/// warning), and `canonical[i] = nastran[TO_CANONICAL[i]]`.
struct Solid {
    kind: ElementKind,
    linear: usize,
    to_canonical: &'static [usize],
}

/// MSC Nastran Quick Reference Guide, CTETRA: G1-G4 corners, G5-G10 on the edges 1-2, 2-3,
/// 3-1, 1-4, 2-4, 3-4: squeal's (Abaqus C3D10's) order.
const TETRA: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9];
/// CHEXA: G1-G4 and G5-G8 the two faces, G9-G12 on the edges 1-2, 2-3, 3-4, 4-1, G13-G16 on
/// the edges 1-5, 2-6, 3-7, 4-8, G17-G20 on 5-6, 6-7, 7-8, 8-5. squeal (Abaqus C3D20) puts
/// the top face's edges before the vertical ones.
const HEXA: [usize; 20] = [
    0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15,
];
/// CPENTA: G1-G3 and G4-G6 the two triangles, G7-G9 on the edges 1-2, 2-3, 3-1, G10-G12 on
/// 1-4, 2-5, 3-6, G13-G15 on 4-5, 5-6, 6-4. squeal (Abaqus C3D15) puts the top triangle's
/// edges before the vertical ones.
const PENTA: [usize; 15] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 13, 14, 9, 10, 11];
/// CPYRAM: G1-G4 the base, G5 the apex, G6-G9 on the base edges 1-2, 2-3, 3-4, 4-1, G10-G13
/// on 1-5, 2-5, 3-5, 4-5: squeal's (VTK's) order.
const PYRAM: [usize; 13] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12];

fn solid(name: &str) -> Option<Solid> {
    let (kind, linear, to_canonical): (_, _, &'static [usize]) = match name {
        "CTETRA" => (ElementKind::Tet10, 4, &TETRA),
        "CHEXA" => (ElementKind::Hex20, 8, &HEXA),
        "CPENTA" => (ElementKind::Wedge15, 6, &PENTA),
        "CPYRAM" => (ElementKind::Pyramid13, 5, &PYRAM),
        _ => return None,
    };
    Some(Solid {
        kind,
        linear,
        to_canonical,
    })
}

/// The cards squeal reads, in the warning about the others.
const READ: &str =
    "GRID, CORD2R, CORD2C, CORD2S, CTETRA, CHEXA, CPENTA, CPYRAM, PSOLID, MAT1, MAT9, SET1";

/// A coordinate system as defined: read, or of a kind squeal refuses when a grid uses it.
enum System {
    Defined(Definition),
    Refused(&'static str),
}

struct Property {
    mid: u64,
    cordm: i64,
    loc: Loc,
}

struct MaterialCard {
    material: Material,
    /// `MAT9`: the material's axes matter.
    anisotropic: bool,
    loc: Loc,
}

pub(super) struct Reader<'a> {
    lx: &'a Lexed,
    warnings: Vec<Warning>,
    /// Skipped or noted things, one warning per key: (first place, count, message stem).
    once: BTreeMap<String, (Loc, usize, String)>,
}

impl<'a> Reader<'a> {
    pub fn new(lx: &'a Lexed) -> Self {
        Self {
            lx,
            warnings: Vec::new(),
            once: BTreeMap::new(),
        }
    }

    fn err(&self, loc: Loc, message: impl Into<String>) -> MeshError {
        self.lx.error(loc, message)
    }

    fn note(&mut self, key: &str, loc: Loc, stem: impl FnOnce() -> String) {
        self.once
            .entry(key.to_string())
            .and_modify(|e| e.1 += 1)
            .or_insert_with(|| (loc, 1, stem()));
    }

    /// A positive id in field `i`.
    fn id(&self, card: &Card, i: usize, what: &str) -> Result<u64, MeshError> {
        let s = card.get(i);
        match int(s) {
            Some(v) if v > 0 => Ok(v as u64),
            _ => Err(self.err(
                card.loc_of(i),
                format!(
                    "{} needs {what} as a positive integer, found '{}'",
                    card.name,
                    shown(s)
                ),
            )),
        }
    }

    /// A non-negative integer in field `i`, blank meaning `default`.
    fn int_or(&self, card: &Card, i: usize, default: i64, what: &str) -> Result<i64, MeshError> {
        let s = card.get(i);
        if s.is_empty() {
            return Ok(default);
        }
        int(s).ok_or_else(|| {
            self.err(
                card.loc_of(i),
                format!(
                    "{} needs {what} as an integer, found '{}'",
                    card.name,
                    shown(s)
                ),
            )
        })
    }

    /// A real in field `i`, blank meaning `default`.
    fn real_or(&self, card: &Card, i: usize, default: f64, what: &str) -> Result<f64, MeshError> {
        let s = card.get(i);
        real_or(s, default).ok_or_else(|| {
            self.err(
                card.loc_of(i),
                format!(
                    "{} needs {what} as a real number (such as 2.1E11 or 2.1+11), found '{}'",
                    card.name,
                    shown(s)
                ),
            )
        })
    }

    fn optional_real(&self, card: &Card, i: usize, what: &str) -> Result<Option<f64>, MeshError> {
        if card.get(i).is_empty() {
            return Ok(None);
        }
        self.real_or(card, i, 0.0, what).map(Some)
    }

    /// Interprets every card.
    pub fn run(mut self) -> Result<ReadMesh, MeshError> {
        let lx = self.lx;
        let mut systems: HashMap<u64, (System, Loc)> = HashMap::new();
        let mut grids = Vec::new();
        let mut elements = Vec::new();
        let mut properties: BTreeMap<u64, Property> = BTreeMap::new();
        let mut materials: BTreeMap<u64, MaterialCard> = BTreeMap::new();
        let mut sets = Vec::new();
        for card in &lx.cards {
            match card.name.as_str() {
                "GRID" => grids.push(card),
                "CORD2R" | "CORD2C" | "CORD2S" => {
                    let (id, def) = self.cord2(card)?;
                    self.unique(
                        &mut systems,
                        id,
                        (System::Defined(def), card.loc),
                        card,
                        "coordinate system",
                    )?;
                }
                "CORD1R" | "CORD1C" | "CORD1S" | "CORD3G" | "CORD3R" => {
                    let id = self.id(card, 0, "the coordinate system id CID")?;
                    let why = if card.name.starts_with("CORD1") {
                        "defines its axes by three grid points"
                    } else {
                        "is a general or convective system"
                    };
                    self.unique(
                        &mut systems,
                        id,
                        (System::Refused(why), card.loc),
                        card,
                        "coordinate system",
                    )?;
                }
                "PSOLID" => {
                    let pid = self.id(card, 0, "the property id PID")?;
                    let mid = self.id(card, 1, "the material id MID")?;
                    let cordm = self.int_or(card, 2, 0, "the material system CORDM")?;
                    let p = Property {
                        mid,
                        cordm,
                        loc: card.loc,
                    };
                    if let Some(first) = properties.insert(pid, p) {
                        return Err(self.twice(card, "property", pid, first.loc));
                    }
                }
                "MAT1" | "MAT9" => {
                    let mid = self.id(card, 0, "the material id MID")?;
                    let m = if card.name == "MAT1" {
                        self.mat1(card)?
                    } else {
                        self.mat9(card)?
                    };
                    if let Some(first) = materials.insert(mid, m) {
                        return Err(self.twice(card, "material", mid, first.loc));
                    }
                }
                "SET1" => sets.push(card),
                "GRDSET" => {
                    if !matches!(card.get(1), "" | "0") || !matches!(card.get(5), "" | "0") {
                        return Err(self.err(card.loc, "GRDSET gives default coordinate systems (CP, CD), which squeal does not read: give them on each GRID"));
                    }
                    self.note("GRDSET", card.loc, || {
                        "skipped GRDSET (defaults of the grids' constraints)".into()
                    });
                }
                name if solid(name).is_some() => elements.push(card),
                name => {
                    let name = name.to_string();
                    self.note(&format!("card {name}"), card.loc, || {
                        format!("skipped cards of type {name}: squeal reads only {READ}")
                    });
                }
            }
        }
        let frames = self.frames(&systems)?;
        let mut b = MeshBuilder::new();
        for card in grids {
            self.grid(card, &systems, &frames, &mut b)?;
        }
        let mut by_property: BTreeMap<u64, Vec<u64>> = BTreeMap::new();
        for card in elements {
            self.element(card, &mut b, &mut by_property)?;
        }
        let names = self.names()?;
        let name_of = |named: Named, id: u64, default: String| {
            names.get(&(named, id)).cloned().unwrap_or(default)
        };
        for (&mid, m) in &materials {
            b.set_material(
                &name_of(Named::Material, mid, format!("MAT_{mid}")),
                m.material,
            );
        }
        for (pid, ids) in by_property {
            let set = name_of(Named::Property, pid, format!("PSOLID_{pid}"));
            b.add_to_element_set(&set, ids);
            let Some(p) = properties.get(&pid) else {
                let loc = lx.cards.first().map_or(Loc { src: 0, line: 1 }, |c| c.loc);
                self.warnings.push(lx.warning(loc, format!("elements name property {pid}, which no PSOLID defines: they have no material")));
                continue;
            };
            match materials.get(&p.mid) {
                None => self.warnings.push(lx.warning(
                    p.loc,
                    format!(
                        "PSOLID {pid} names material {}, which no MAT1 or MAT9 defines",
                        p.mid
                    ),
                )),
                Some(m) if m.anisotropic && p.cordm != 0 => {
                    return Err(self.err(p.loc, format!("PSOLID {pid} gives the material axes CORDM = {} for the MAT9 material {}: squeal takes material constants in the basic axes; give them there (CORDM = 0 or blank)", p.cordm, p.mid)));
                }
                Some(_) => {}
            }
            b.add_section(
                &set,
                &name_of(Named::Material, p.mid, format!("MAT_{}", p.mid)),
            );
        }
        for card in sets {
            self.set1(card, &names, &mut b)?;
        }
        self.finish(b)
    }

    fn unique<T>(
        &self,
        map: &mut HashMap<u64, (T, Loc)>,
        id: u64,
        v: (T, Loc),
        card: &Card,
        what: &str,
    ) -> Result<(), MeshError> {
        if let Some(first) = map.get(&id) {
            return Err(self.twice(card, what, id, first.1));
        }
        map.insert(id, v);
        Ok(())
    }

    fn twice(&self, card: &Card, what: &str, id: u64, first: Loc) -> MeshError {
        self.err(
            card.loc,
            format!(
                "{what} {id} is defined twice (first at {}:{})",
                self.lx.path(first).display(),
                first.line
            ),
        )
    }

    /// `CORD2R/C/S, CID, RID, A1, A2, A3, B1, B2, B3, C1, C2, C3`.
    fn cord2(&self, card: &Card) -> Result<(u64, Definition), MeshError> {
        let id = self.id(card, 0, "the coordinate system id CID")?;
        let rid = self.int_or(card, 1, 0, "the reference system RID")?;
        let rid = u64::try_from(rid).map_err(|_| {
            self.err(
                card.loc,
                format!("{} {id}: RID must be 0 or positive", card.name),
            )
        })?;
        let mut p = [0.0; 9];
        for (k, v) in p.iter_mut().enumerate() {
            *v = self.real_or(card, 2 + k, 0.0, "the points A, B, C")?;
        }
        let kind = match card.name.as_str() {
            "CORD2R" => Kind::Rectangular,
            "CORD2C" => Kind::Cylindrical,
            _ => Kind::Spherical,
        };
        Ok((
            id,
            Definition {
                kind,
                rid,
                a: [p[0], p[1], p[2]],
                b: [p[3], p[4], p[5]],
                c: [p[6], p[7], p[8]],
            },
        ))
    }

    /// Every defined system in basic axes, following `RID` chains (a loop is an error).
    fn frames(
        &self,
        systems: &HashMap<u64, (System, Loc)>,
    ) -> Result<HashMap<u64, Frame>, MeshError> {
        let mut frames: HashMap<u64, Frame> = HashMap::new();
        let mut ids: Vec<u64> = systems.keys().copied().collect();
        ids.sort_unstable();
        for start in ids {
            let mut chain = vec![start];
            // Walk down to a system whose reference is resolved (or basic).
            loop {
                let id = *chain.last().unwrap_or(&start);
                let (System::Defined(def), loc) = &systems[&id] else {
                    break;
                };
                if def.rid == 0 || frames.contains_key(&def.rid) {
                    break;
                }
                if chain.contains(&def.rid) {
                    let path: Vec<String> =
                        chain.iter().chain([&def.rid]).map(u64::to_string).collect();
                    return Err(self.err(
                        *loc,
                        format!(
                            "coordinate systems reference each other in a loop: {}",
                            path.join(" -> ")
                        ),
                    ));
                }
                match systems.get(&def.rid) {
                    Some(_) => chain.push(def.rid),
                    None => return Err(self.err(
                        *loc,
                        format!(
                            "coordinate system {id} is defined in system {}, which is not defined",
                            def.rid
                        ),
                    )),
                }
            }
            for &id in chain.iter().rev() {
                let (sys, loc) = &systems[&id];
                let System::Defined(def) = sys else { continue };
                let reference = match def.rid {
                    0 => None,
                    r => match frames.get(&r) {
                        Some(f) => Some(*f),
                        None => return Err(self.err(*loc, format!("coordinate system {id} is defined in system {r}, which squeal cannot place (see its error)"))),
                    },
                };
                let frame = Frame::new(def, reference.as_ref()).ok_or_else(|| {
                    self.err(*loc, format!("coordinate system {id}: its points A, B, C do not define axes (two coincide or all three are on a line)"))
                })?;
                frames.insert(id, frame);
            }
        }
        Ok(frames)
    }

    /// `GRID, ID, CP, X1, X2, X3, CD, PS, SEID`.
    fn grid(
        &mut self,
        card: &Card,
        systems: &HashMap<u64, (System, Loc)>,
        frames: &HashMap<u64, Frame>,
        b: &mut MeshBuilder,
    ) -> Result<(), MeshError> {
        let id = self.id(card, 0, "the grid id")?;
        let cp = self.int_or(card, 1, 0, "the coordinate system CP")?;
        let mut x = [0.0; 3];
        for (d, v) in x.iter_mut().enumerate() {
            *v = self.real_or(card, 2 + d, 0.0, "the coordinates X1, X2, X3")?;
        }
        if cp != 0 {
            let key = u64::try_from(cp).unwrap_or(u64::MAX);
            x = match (frames.get(&key), systems.get(&key)) {
                (Some(f), _) => f.to_basic(x),
                (None, Some((System::Refused(why), _))) => return Err(self.err(card.loc_of(1), format!("GRID {id} is given in coordinate system {cp}, which {why}: squeal reads CORD2R, CORD2C and CORD2S; export the grids in one of those or in the basic system"))),
                _ => return Err(self.err(card.loc_of(1), format!("GRID {id} is given in coordinate system {cp}, which is not defined"))),
            };
            if !x.iter().all(|v| v.is_finite()) {
                return Err(self.err(
                    card.loc,
                    format!("GRID {id} is placed at a point that is not finite"),
                ));
            }
        }
        let cd = self.int_or(card, 5, 0, "the displacement system CD")?;
        if cd != 0 {
            self.note("CD", card.loc, || "the displacement coordinate systems (GRID CD) are ignored: squeal reads no loads or constraints from the file and takes displacements in the basic axes".into());
        }
        if !card.get(6).is_empty() {
            self.note("PS", card.loc, || "the permanent constraints of the grids (GRID PS) are ignored: the scene gives the restraints".into());
        }
        b.add_node(id, x).map_err(|m| self.err(card.loc, m))
    }

    /// A solid element: `EID, PID, G1, G2, ...` with all its edge grids or none.
    fn element(
        &mut self,
        card: &Card,
        b: &mut MeshBuilder,
        by_property: &mut BTreeMap<u64, Vec<u64>>,
    ) -> Result<(), MeshError> {
        let Some(s) = solid(&card.name) else {
            return Ok(());
        };
        let eid = self.id(card, 0, "the element id EID")?;
        let pid = match card.get(1) {
            "" => eid,
            _ => self.id(card, 1, "the property id PID")?,
        };
        let n = s.kind.nodes();
        let mut grids = vec![0u64; n];
        for (k, g) in grids.iter_mut().enumerate() {
            let f = card.get(2 + k);
            *g = match f {
                "" | "0" => 0,
                _ => self.id(card, 2 + k, &format!("grid G{}", k + 1))?,
            };
        }
        if let Some(k) = (2 + n..card.fields.len()).find(|&k| !card.get(k).is_empty()) {
            return Err(self.err(
                card.loc_of(k),
                format!(
                    "{} {eid} has more than {n} grids ('{}' in data field {}): a {} has {n}",
                    card.name,
                    shown(card.get(k)),
                    k + 2,
                    s.kind
                ),
            ));
        }
        let given = grids.iter().filter(|&&g| g != 0).count();
        if grids[..s.linear].contains(&0) {
            return Err(self.err(
                card.loc,
                format!(
                    "{} {eid} lacks a corner grid (G1 to G{})",
                    card.name, s.linear
                ),
            ));
        }
        if given == s.linear {
            b.skip_element(eid);
            let name = card.name.clone();
            self.note(&format!("linear {name}"), card.loc, || {
                format!("skipped elements of type {name} with {} grids (first order): squeal reads quadratic solids, with every edge grid", s.linear)
            });
            return Ok(());
        }
        if given != n {
            return Err(self.err(card.loc, format!("{} {eid} has {given} of its {n} grids: squeal reads quadratic elements with every edge grid (or, skipped, first-order ones without any)", card.name)));
        }
        let nodes: Vec<u64> = s.to_canonical.iter().map(|&k| grids[k]).collect();
        b.add_typed(eid, s.kind, &nodes)
            .map_err(|m| self.err(card.loc, m))?;
        by_property.entry(pid).or_default().push(eid);
        Ok(())
    }

    /// `MAT1, MID, E, G, NU, RHO, A, TREF, GE`: two of E, G, NU give the third (Nastran's
    /// rule); all three must agree to 1%, as squeal's isotropic material has two constants.
    fn mat1(&mut self, card: &Card) -> Result<MaterialCard, MeshError> {
        let mid = card.get(0).to_string();
        let e = self.optional_real(card, 1, "Young's modulus E")?;
        let g = self.optional_real(card, 2, "the shear modulus G")?;
        let nu = self.optional_real(card, 3, "Poisson's ratio NU")?;
        let rho = self.optional_real(card, 4, "the density RHO")?;
        let (young, poisson) = match (e, g, nu) {
            (Some(e), None, Some(nu)) => (e, nu),
            (Some(e), Some(g), None) => (e, e / (2.0 * g) - 1.0),
            (None, Some(g), Some(nu)) => (2.0 * (1.0 + nu) * g, nu),
            (Some(e), None, None) => {
                self.warnings.push(self.lx.warning(
                    card.loc,
                    format!("MAT1 {mid} gives E only: Poisson's ratio is 0 (Nastran's rule)"),
                ));
                (e, 0.0)
            }
            (Some(e), Some(g), Some(nu)) => {
                let implied = e / (2.0 * (1.0 + nu));
                if ((g - implied) / implied).abs() > 0.01 {
                    return Err(self.err(card.loc, format!("MAT1 {mid} gives E = {e:e}, G = {g:e} and NU = {nu}, but E / (2 (1 + NU)) = {implied:e}: squeal's isotropic material has two constants; leave G blank (or give a consistent one)")));
                }
                (e, nu)
            }
            _ => {
                return Err(self.err(
                    card.loc,
                    format!(
                        "MAT1 {mid} needs two of E, G and NU (with E), found no Young's modulus"
                    ),
                ));
            }
        };
        if !card.get(7).is_empty() && real(card.get(7)) != Some(0.0) {
            self.note("GE", card.loc, || "the structural damping GE of the materials is ignored: the scene's [damping] gives the damping".into());
        }
        Ok(MaterialCard {
            material: Material {
                elastic: Some(Elastic::Isotropic { young, poisson }),
                density: rho,
            },
            anisotropic: false,
            loc: card.loc,
        })
    }

    /// `MAT9, MID, G11, G12, ..., G66, RHO`: the upper triangle of the 6×6 stiffness in the
    /// order xx, yy, zz, xy, yz, zx. squeal's finite elements have orthotropic materials, so a
    /// MAT9 without shear couplings is read as engineering constants (the normal block
    /// inverted to the compliance: `E_i = 1/S_ii`, `ν_ij = -S_ij/S_ii`; `G12 = G44`,
    /// `G23 = G55`, `G13 = G66`); any coupling is refused.
    fn mat9(&mut self, card: &Card) -> Result<MaterialCard, MeshError> {
        let mid = card.get(0).to_string();
        const NAMES: [&str; 21] = [
            "G11", "G12", "G13", "G14", "G15", "G16", "G22", "G23", "G24", "G25", "G26", "G33",
            "G34", "G35", "G36", "G44", "G45", "G46", "G55", "G56", "G66",
        ];
        let mut g = [0.0; 21];
        for (k, v) in g.iter_mut().enumerate() {
            *v = self.real_or(card, 1 + k, 0.0, NAMES[k])?;
        }
        let at = |name: &str| NAMES.iter().position(|n| *n == name).map_or(0.0, |k| g[k]);
        let coupled: Vec<&str> = [
            "G14", "G15", "G16", "G24", "G25", "G26", "G34", "G35", "G36", "G45", "G46", "G56",
        ]
        .into_iter()
        .filter(|n| at(n) != 0.0)
        .collect();
        if !coupled.is_empty() {
            return Err(self.err(card.loc, format!("MAT9 {mid} couples shear and extension ({} not zero): squeal's finite elements have isotropic, transversely isotropic and orthotropic materials only; give an orthotropic MAT9 (only G11, G12, G13, G22, G23, G33, G44, G55, G66) or the scene's [materials]", coupled.join(", "))));
        }
        let c = [
            [at("G11"), at("G12"), at("G13")],
            [at("G12"), at("G22"), at("G23")],
            [at("G13"), at("G23"), at("G33")],
        ];
        let det = crate::tet10::det3(&c);
        let cof = |i: usize, j: usize| {
            let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
            let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
            c[r0][c0] * c[r1][c1] - c[r0][c1] * c[r1][c0]
        };
        // S = C^-1 = cofactor matrix / det (C symmetric).
        let s = |i: usize, j: usize| cof(i, j) / det;
        let shear = [at("G44"), at("G66"), at("G55")];
        let e = [1.0 / s(0, 0), 1.0 / s(1, 1), 1.0 / s(2, 2)];
        let positive = det > 0.0 && e.iter().chain(&shear).all(|v| *v > 0.0 && v.is_finite());
        if !positive {
            return Err(self.err(card.loc, format!("MAT9 {mid} is not positive definite (its normal block has determinant {det:e}, or a shear term G44, G55, G66 is not positive): check the constants")));
        }
        let nu = [-s(0, 1) / s(0, 0), -s(0, 2) / s(0, 0), -s(1, 2) / s(1, 1)];
        let rho = self.optional_real(card, 22, "the density RHO")?;
        Ok(MaterialCard {
            material: Material {
                elastic: Some(Elastic::EngineeringConstants { e, nu, g: shear }),
                density: rho,
            },
            anisotropic: true,
            loc: card.loc,
        })
    }

    /// The names comments give, by (kind, id); a name given to two ids is an error.
    fn names(&self) -> Result<HashMap<(Named, u64), String>, MeshError> {
        let mut out: HashMap<(Named, u64), String> = HashMap::new();
        let mut seen: HashMap<(u8, String), (u64, Loc)> = HashMap::new();
        for (named, id, name, loc) in &self.lx.names {
            let class = match named {
                Named::Property => 0,
                Named::Material => 1,
                Named::Set(_) => 2,
            };
            if let Some((other, first)) = seen.get(&(class, name.to_ascii_uppercase()))
                && other != id
            {
                return Err(self.err(*loc, format!("the name comment gives the name {name} to {id}, and {}:{} gave it to {other}: give each property, material and set its own name", self.lx.path(*first).display(), first.line)));
            }
            seen.insert((class, name.to_ascii_uppercase()), (*id, *loc));
            out.insert((*named, *id), name.clone());
            if let Named::Set(_) = named {
                out.insert((Named::Set(0), *id), name.clone());
            }
        }
        Ok(out)
    }

    /// `SET1, SID, ID1, ID2, ...` with `ID1 THRU ID2` ranges: a node set (an element set if a
    /// `$HMSET` comment says so), named by its `$HMSET` comment or `SET1_<sid>`.
    fn set1(
        &mut self,
        card: &Card,
        names: &HashMap<(Named, u64), String>,
        b: &mut MeshBuilder,
    ) -> Result<(), MeshError> {
        let sid = self.id(card, 0, "the set id SID")?;
        let elements = names.contains_key(&(Named::Set(2), sid));
        let name = names
            .get(&(Named::Set(0), sid))
            .cloned()
            .unwrap_or_else(|| format!("SET1_{sid}"));
        let tokens: Vec<(usize, &str)> = (1..card.fields.len())
            .map(|k| (k, card.get(k)))
            .filter(|(_, t)| !t.is_empty())
            .collect();
        let mut ids = Vec::new();
        let mut k = 0;
        while k < tokens.len() {
            let (i, t) = tokens[k];
            if t.eq_ignore_ascii_case("THRU") {
                let (Some(&from), Some(&(j, _))) = (ids.last(), tokens.get(k + 1)) else {
                    return Err(self.err(
                        card.loc_of(i),
                        format!("SET1 {sid}: THRU needs an id before and after it"),
                    ));
                };
                let to = self.id(card, j, "the id after THRU")?;
                if to < from {
                    return Err(self.err(
                        card.loc_of(j),
                        format!("SET1 {sid}: the range {from} THRU {to} ends before it starts"),
                    ));
                }
                let defined = |id: u64| {
                    if elements {
                        b.has_element(id)
                    } else {
                        b.has_node(id)
                    }
                };
                // Bounded by the ids defined, not by the range's size.
                let count = if to - from < 10_000_000 {
                    let mut n = 0u64;
                    for id in from + 1..=to {
                        if defined(id) {
                            ids.push(id);
                            n += 1;
                        }
                    }
                    (to - from) - n
                } else {
                    return Err(self.err(card.loc_of(j), format!("SET1 {sid}: the range {from} THRU {to} has more than 10 million ids: list the ids, or split the range")));
                };
                if count > 0 {
                    self.warnings.push(self.lx.warning(card.loc_of(j), format!("SET1 {sid}: {count} ids of the range {from} THRU {to} are not defined: they are left out")));
                }
                k += 2;
                continue;
            }
            ids.push(self.id(card, i, "the ids of its members")?);
            k += 1;
        }
        if elements {
            b.add_to_element_set(&name, ids);
        } else {
            b.add_to_node_set(&name, ids);
        }
        Ok(())
    }

    fn finish(mut self, b: MeshBuilder) -> Result<ReadMesh, MeshError> {
        for (loc, count, stem) in std::mem::take(&mut self.once).into_values() {
            let times = match count {
                1 => "once".to_string(),
                n => format!("{n} times, the first here"),
            };
            self.warnings
                .push(self.lx.warning(loc, format!("{stem} ({times})")));
        }
        if b.num_elements() == 0 {
            self.warnings.push(Warning {
                file: self.lx.sources[0].clone(),
                location: Location::File,
                message: crate::NO_TET10.to_string(),
            });
        }
        Ok(ReadMesh {
            mesh: b.finish(),
            warnings: self.warnings,
        })
    }
}

/// At most 24 characters of a field, for messages.
fn shown(s: &str) -> String {
    s.chars().take(24).collect()
}
