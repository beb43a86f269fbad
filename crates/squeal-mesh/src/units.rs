//! Consistent unit systems, as Abaqus users choose them: a mesh written in millimetres with
//! moduli in MPa and densities in t/mm³ is read into SI (m, kg, s, N, Pa) by scaling its
//! coordinates and its materials ([`UnitSystem::to_si`]); [`plausibility`] warns when the
//! numbers of a mesh read as SI look like another system's (a steel modulus of 2.1e5 "Pa", a
//! density of 7.85e-9 "kg/m³", a 280 m brake disc).

use crate::model::{Elastic, Mesh};

/// A consistent system of units: length, mass and time (force, stress and density follow).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitSystem {
    /// The name used in scene files (e.g. `"mm-t-s"`).
    pub name: &'static str,
    /// What it is, for messages (e.g. `"mm, t, s, N, MPa"`).
    pub description: &'static str,
    /// Metres per length unit.
    pub length: f64,
    /// Kilograms per mass unit.
    pub mass: f64,
    /// Seconds per time unit.
    pub time: f64,
}

/// The unit systems a scene may name. The first is SI.
pub const SYSTEMS: [UnitSystem; 5] = [
    UnitSystem {
        name: "SI",
        description: "m, kg, s, N, Pa; density kg/m^3",
        length: 1.0,
        mass: 1.0,
        time: 1.0,
    },
    UnitSystem {
        name: "mm-t-s",
        description: "mm, tonne, s, N, MPa; density t/mm^3 (steel 7.85e-9)",
        length: 1e-3,
        mass: 1e3,
        time: 1.0,
    },
    UnitSystem {
        name: "mm-kg-ms",
        description: "mm, kg, ms, kN, GPa; density kg/mm^3 (steel 7.85e-6)",
        length: 1e-3,
        mass: 1.0,
        time: 1e-3,
    },
    UnitSystem {
        name: "mm-g-ms",
        description: "mm, g, ms, N, MPa; density g/mm^3 (steel 7.85e-3)",
        length: 1e-3,
        mass: 1e-3,
        time: 1e-3,
    },
    UnitSystem {
        name: "in-lbf-s",
        description: "in, lbf s^2/in, s, lbf, psi; density lbf s^2/in^4 (steel 7.35e-4)",
        length: 0.0254,
        mass: 4.448_221_615_260_5 / 0.0254,
        time: 1.0,
    },
];

impl Default for UnitSystem {
    fn default() -> Self {
        SYSTEMS[0]
    }
}

impl UnitSystem {
    /// The system of a name (ASCII case-insensitive; `mm-t-s-N-MPa` and the like, with the
    /// force and stress units appended, are accepted too).
    pub fn named(name: &str) -> Option<Self> {
        let n = name.trim().to_ascii_lowercase();
        SYSTEMS.iter().copied().find(|s| {
            let own = s.name.to_ascii_lowercase();
            n == own || n.starts_with(&format!("{own}-"))
        })
    }

    /// The names of all systems, for messages.
    pub fn names() -> String {
        SYSTEMS
            .iter()
            .map(|s| format!("\"{}\" ({})", s.name, s.description))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Whether this is SI (no conversion).
    pub fn is_si(&self) -> bool {
        self.length == 1.0 && self.mass == 1.0 && self.time == 1.0
    }

    /// Newtons per force unit.
    pub fn force(&self) -> f64 {
        self.mass * self.length / (self.time * self.time)
    }

    /// Pascals per stress unit.
    pub fn stress(&self) -> f64 {
        self.force() / (self.length * self.length)
    }

    /// kg/m³ per density unit.
    pub fn density(&self) -> f64 {
        self.mass / (self.length * self.length * self.length)
    }

    /// m² per area unit.
    pub fn area(&self) -> f64 {
        self.length * self.length
    }

    /// Converts a mesh written in this system to SI in place: coordinates, elastic constants
    /// and densities.
    pub fn to_si(&self, mesh: &mut Mesh) {
        if self.is_si() {
            return;
        }
        for p in &mut mesh.nodes {
            *p = p.map(|x| x * self.length);
        }
        let (s, r) = (self.stress(), self.density());
        for m in mesh.materials.values_mut() {
            m.elastic = m.elastic.map(|e| match e {
                Elastic::Isotropic { young, poisson } => Elastic::Isotropic {
                    young: young * s,
                    poisson,
                },
                Elastic::EngineeringConstants { e, nu, g } => Elastic::EngineeringConstants {
                    e: e.map(|v| v * s),
                    nu,
                    g: g.map(|v| v * s),
                },
            });
            m.density = m.density.map(|d| d * r);
        }
    }
}

/// Young's moduli (Pa) of structural solids lie in this range (soft elastomers to diamond).
pub const PLAUSIBLE_MODULUS: (f64, f64) = (1e6, 1.5e12);
/// Densities (kg/m³) of structural solids (foams to tungsten).
pub const PLAUSIBLE_DENSITY: (f64, f64) = (10.0, 25e3);
/// Largest extent (m) of a brake part (a motorcycle disc to a railway disc).
pub const PLAUSIBLE_SIZE: (f64, f64) = (5e-3, 3.0);

/// What a value in SI would be in the other systems, for a warning: the systems in which it
/// would be plausible, `in` the given range.
fn other_systems(
    value_si: f64,
    per_unit: impl Fn(&UnitSystem) -> f64,
    range: (f64, f64),
) -> String {
    let fits: Vec<&str> = SYSTEMS
        .iter()
        .filter(|s| {
            let v = value_si * per_unit(s);
            v >= range.0 && v <= range.1
        })
        .map(|s| s.name)
        .collect();
    if fits.is_empty() {
        String::new()
    } else {
        format!(
            "; it would be plausible if the file were in {} units",
            fits.join(" or ")
        )
    }
}

/// A modulus (Pa) outside [`PLAUSIBLE_MODULUS`], said as a warning naming `what`.
pub fn check_modulus(what: &str, young_si: f64, given_in: &UnitSystem) -> Option<String> {
    let (lo, hi) = PLAUSIBLE_MODULUS;
    (!(young_si >= lo && young_si <= hi)).then(|| {
        format!(
            "{what}: Young's modulus {young_si:.4e} Pa (read as {}) is not that of a structural solid ({lo:.0e}..{hi:.0e} Pa){}",
            given_in.name,
            other_systems(young_si / given_in.stress(), |s| s.stress(), PLAUSIBLE_MODULUS)
        )
    })
}

/// A density (kg/m³) outside [`PLAUSIBLE_DENSITY`], said as a warning naming `what`.
pub fn check_density(what: &str, density_si: f64, given_in: &UnitSystem) -> Option<String> {
    let (lo, hi) = PLAUSIBLE_DENSITY;
    (!(density_si >= lo && density_si <= hi)).then(|| {
        format!(
            "{what}: density {density_si:.4e} kg/m^3 (read as {}) is not that of a structural solid ({lo:.0e}..{hi:.0e} kg/m^3){}",
            given_in.name,
            other_systems(density_si / given_in.density(), |s| s.density(), PLAUSIBLE_DENSITY)
        )
    })
}

/// Warnings about a mesh in SI whose numbers look like another unit system's: its size, its
/// materials' moduli and densities. `given_in` is the system it was read in.
pub fn plausibility(mesh: &Mesh, given_in: &UnitSystem) -> Vec<String> {
    let mut out = Vec::new();
    if let Some((lo, hi)) = mesh.bounding_box() {
        let size = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
        let (a, b) = PLAUSIBLE_SIZE;
        if !(size >= a && size <= b) {
            out.push(format!(
                "the mesh is {size:.4e} m across (read as {}), not the size of a brake part ({a:.0e}..{b} m){}",
                given_in.name,
                other_systems(size / given_in.length, |s| s.length, PLAUSIBLE_SIZE)
            ));
        }
    }
    for (name, m) in &mesh.materials {
        let young = match m.elastic {
            Some(Elastic::Isotropic { young, .. }) => Some(young),
            Some(Elastic::EngineeringConstants { e, .. }) => {
                Some(e.iter().copied().fold(0.0, f64::max))
            }
            None => None,
        };
        if let Some(w) = young.and_then(|y| check_modulus(&format!("material {name}"), y, given_in))
        {
            out.push(w);
        }
        if let Some(w) = m
            .density
            .and_then(|d| check_density(&format!("material {name}"), d, given_in))
        {
            out.push(w);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Material;

    #[test]
    fn the_systems_are_consistent() {
        let mmts = UnitSystem::named("mm-t-s-N-MPa").unwrap();
        // N and MPa exactly: 1 t mm / s^2 = 1 N, 1 N/mm^2 = 1 MPa; 1 t/mm^3 = 1e12 kg/m^3.
        assert!((mmts.force() - 1.0).abs() < 1e-15 && (mmts.stress() - 1e6).abs() < 1e-9);
        assert!((mmts.density() / 1e12 - 1.0).abs() < 1e-15);
        let mmkgms = UnitSystem::named("MM-KG-MS").unwrap();
        // kN and GPa.
        assert!((mmkgms.force() / 1e3 - 1.0).abs() < 1e-15);
        assert!((mmkgms.stress() / 1e9 - 1.0).abs() < 1e-15);
        let inch = UnitSystem::named("in-lbf-s").unwrap();
        // 1 lbf = 4.4482216152605 N (exact by definition), 1 psi = 6894.757... Pa.
        assert!((inch.force() / 4.448_221_615_260_5 - 1.0).abs() < 1e-15);
        assert!((inch.stress() / 6_894.757_293_168 - 1.0).abs() < 1e-12);
        assert!(UnitSystem::named("furlong").is_none());
    }

    #[test]
    fn a_millimetre_mesh_in_si_has_its_volume_times_1e_minus_9_and_the_same_mass() {
        let mut mesh = crate::generate::box_tet10([280.0, 280.0, 20.0], [3, 3, 2]);
        mesh.materials.insert(
            "STEEL".into(),
            Material {
                elastic: None,
                density: Some(7.85e-9),
            },
        );
        let volume = |m: &Mesh| -> f64 {
            m.blocks
                .tet10
                .iter()
                .map(|e| crate::tet10::volume(&e.map(|n| m.nodes[n as usize])))
                .sum()
        };
        let v_mm = volume(&mesh);
        let m_t = v_mm * mesh.materials["STEEL"].density.unwrap();
        UnitSystem::named("mm-t-s-N-MPa").unwrap().to_si(&mut mesh);
        let v_m = volume(&mesh);
        let m_kg = v_m * mesh.materials["STEEL"].density.unwrap();
        // Coordinates scale by 1e-3 exactly up to one rounding each: the volume (sums of
        // 108 element volumes ~1e4 mm^3) agrees to a few ulps; 1e-14 relative asserted.
        assert!((v_m / (v_mm * 1e-9) - 1.0).abs() < 1e-14, "{v_m} vs {v_mm}");
        assert!((v_m / (0.28 * 0.28 * 0.02) - 1.0).abs() < 1e-14, "{v_m}");
        // The same body: 12.3088 kg = 1000 x 0.0123088 t, to round-off.
        assert!((m_kg / (1e3 * m_t) - 1.0).abs() < 1e-14, "{m_kg} vs {m_t}");
        assert!((m_kg - 7850.0 * 0.28 * 0.28 * 0.02).abs() < 1e-12);
    }

    #[test]
    fn a_millimetre_steel_read_as_si_is_flagged() {
        let mut mesh = crate::generate::box_tet10([280.0, 280.0, 20.0], [1, 1, 1]);
        mesh.materials.insert(
            "STEEL".into(),
            Material {
                elastic: Some(Elastic::Isotropic {
                    young: 2.1e5,
                    poisson: 0.3,
                }),
                density: Some(7.85e-9),
            },
        );
        let si = UnitSystem::default();
        let w = plausibility(&mesh, &si);
        assert_eq!(w.len(), 3, "{w:?}");
        assert!(w.iter().all(|m| m.contains("mm-t-s")), "{w:?}");
        // Read in mm-t-s it is a 0.28 m steel part: no warning.
        let mmts = UnitSystem::named("mm-t-s").unwrap();
        mmts.to_si(&mut mesh);
        assert!(plausibility(&mesh, &mmts).is_empty());
        let steel = mesh.materials["STEEL"];
        // 2.1e5 MPa = 2.1e11 Pa and 7.85e-9 t/mm^3 = 7850 kg/m^3, to round-off.
        assert!(
            matches!(steel.elastic, Some(Elastic::Isotropic { young, .. }) if (young / 2.1e11 - 1.0).abs() < 1e-15)
        );
        assert!((steel.density.unwrap() / 7850.0 - 1.0).abs() < 1e-15);
    }
}
