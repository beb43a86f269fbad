//! Linear elastic materials and the assignment of materials to elements.
//!
//! Stresses and strains are in Voigt notation, Abaqus order `11, 22, 33, 12, 13, 23`, with
//! engineering shear strains (`γ_12 = 2 ε_12`), so that `σ = C ε` and the strain energy density
//! is `½ εᵀ C ε`.
//!
//! Poisson's ratios follow Abaqus' convention for engineering constants: `ν_ij` is the strain
//! in direction `j` caused by a stress in direction `i`, `ε_j = -ν_ij σ_i / E_i`, and
//! `ν_ij / E_i = ν_ji / E_j`.

use crate::error::{FeError, MaterialError};
use serde::{Deserialize, Serialize};
use squeal_mesh::{Elastic, Material, Mesh};

/// A 6×6 elasticity matrix in Voigt notation (order `11, 22, 33, 12, 13, 23`).
pub type Voigt6 = [[f64; 6]; 6];

/// A linear elastic material with its density.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum ElasticMaterial {
    /// Young's modulus `young` (Pa), Poisson's ratio `poisson`, density (kg/m³).
    Isotropic {
        young: f64,
        poisson: f64,
        density: f64,
    },
    /// Transversely isotropic about the unit vector `axis` (for a pad lining: the pad's
    /// normal). In the plane normal to the axis: `young_plane` (E_p), `poisson_plane` (ν_p),
    /// shear modulus `E_p / (2 (1 + ν_p))`. Along the axis: `young_axial` (E_a). Coupling:
    /// `poisson_plane_axial` is ν_pa in Abaqus' convention, the axial strain caused by an
    /// in-plane stress, `ε_a = -ν_pa σ_p / E_p` (Abaqus' ν_13 = ν_23 with axis 3); the
    /// reciprocal is `ν_ap = ν_pa E_a / E_p`. `shear_axial` is G_a = G_13 = G_23.
    TransverselyIsotropic {
        young_plane: f64,
        poisson_plane: f64,
        young_axial: f64,
        poisson_plane_axial: f64,
        shear_axial: f64,
        axis: [f64; 3],
        density: f64,
    },
    /// Orthotropic in the global axes, Abaqus `*ELASTIC, TYPE=ENGINEERING CONSTANTS`:
    /// `e = [E1, E2, E3]`, `nu = [ν12, ν13, ν23]`, `g = [G12, G13, G23]`.
    Orthotropic {
        e: [f64; 3],
        nu: [f64; 3],
        g: [f64; 3],
        density: f64,
    },
}

impl ElasticMaterial {
    /// An isotropic material.
    pub fn isotropic(young: f64, poisson: f64, density: f64) -> Self {
        Self::Isotropic {
            young,
            poisson,
            density,
        }
    }

    /// Converts a material read from a mesh file. `Err` names what is missing.
    pub fn from_mesh_material(m: &Material) -> Result<Self, &'static str> {
        let density = m.density.ok_or("density (*DENSITY)")?;
        match m.elastic.ok_or("elastic constants (*ELASTIC)")? {
            Elastic::Isotropic { young, poisson } => Ok(Self::Isotropic {
                young,
                poisson,
                density,
            }),
            Elastic::EngineeringConstants { e, nu, g } => {
                Ok(Self::Orthotropic { e, nu, g, density })
            }
        }
    }

    /// Density (kg/m³).
    pub fn density(&self) -> f64 {
        match *self {
            Self::Isotropic { density, .. }
            | Self::TransverselyIsotropic { density, .. }
            | Self::Orthotropic { density, .. } => density,
        }
    }

    /// The elasticity matrix `C` (σ = C ε), checked to be finite and positive definite, with a
    /// positive density.
    pub fn elasticity(&self) -> Result<Voigt6, MaterialError> {
        let density = self.density();
        let c = match *self {
            Self::Isotropic { young, poisson, .. } => {
                check_finite(&[young, poisson])?;
                isotropic_stiffness(young, poisson)
            }
            Self::Orthotropic { e, nu, g, .. } => {
                check_finite(&[e, nu, g].concat())?;
                invert_spd(&orthotropic_compliance(e, nu, g))?
            }
            Self::TransverselyIsotropic {
                young_plane,
                poisson_plane,
                young_axial,
                poisson_plane_axial,
                shear_axial,
                axis,
                ..
            } => {
                check_finite(&[
                    young_plane,
                    poisson_plane,
                    young_axial,
                    poisson_plane_axial,
                    shear_axial,
                ])?;
                check_finite(&axis)?;
                let g_plane = young_plane / (2.0 * (1.0 + poisson_plane));
                let local = orthotropic_compliance(
                    [young_plane, young_plane, young_axial],
                    [poisson_plane, poisson_plane_axial, poisson_plane_axial],
                    [g_plane, shear_axial, shear_axial],
                );
                let c_local = invert_spd(&local)?;
                rotate(&c_local, &frame_with_axis(axis)?)
            }
        };
        check_finite(&[density])?;
        if density <= 0.0 {
            return Err(MaterialError::NonPositiveDensity(density));
        }
        if c.iter().flatten().any(|v| !v.is_finite()) || cholesky6(&c).is_none() {
            return Err(MaterialError::NotPositiveDefinite);
        }
        Ok(c)
    }
}

fn check_finite(values: &[f64]) -> Result<(), MaterialError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(MaterialError::NotFinite)
    }
}

/// Isotropic Hooke's law with Lamé constants `λ = E ν / ((1 + ν)(1 - 2ν))`, `μ = E / (2 (1 + ν))`.
fn isotropic_stiffness(young: f64, poisson: f64) -> Voigt6 {
    let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
    let mu = young / (2.0 * (1.0 + poisson));
    let mut c = [[0.0; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = lambda;
        }
        c[i][i] = lambda + 2.0 * mu;
        c[i + 3][i + 3] = mu;
    }
    c
}

/// Orthotropic compliance `S` (ε = S σ) from Abaqus engineering constants:
/// `S_ii = 1/E_i`, `S_ij = -ν_ij / E_i`, shear `1/G_ij`.
fn orthotropic_compliance(e: [f64; 3], nu: [f64; 3], g: [f64; 3]) -> Voigt6 {
    let mut s = [[0.0; 6]; 6];
    for i in 0..3 {
        s[i][i] = 1.0 / e[i];
        s[i + 3][i + 3] = 1.0 / g[i];
    }
    let pairs = [(0, 1, nu[0]), (0, 2, nu[1]), (1, 2, nu[2])];
    for (i, j, nu_ij) in pairs {
        s[i][j] = -nu_ij / e[i];
        s[j][i] = s[i][j];
    }
    s
}

/// Lower Cholesky factor of a symmetric 6×6 matrix; `None` unless positive definite.
fn cholesky6(a: &Voigt6) -> Option<Voigt6> {
    let mut l = [[0.0; 6]; 6];
    for j in 0..6 {
        let d = a[j][j] - (0..j).map(|k| l[j][k] * l[j][k]).sum::<f64>();
        if !(d > 0.0 && d.is_finite()) {
            return None;
        }
        l[j][j] = d.sqrt();
        for i in j + 1..6 {
            l[i][j] = (a[i][j] - (0..j).map(|k| l[i][k] * l[j][k]).sum::<f64>()) / l[j][j];
        }
    }
    Some(l)
}

/// Inverse of a symmetric positive definite 6×6 matrix by Cholesky, symmetrized.
fn invert_spd(a: &Voigt6) -> Result<Voigt6, MaterialError> {
    if a.iter().flatten().any(|v| !v.is_finite()) {
        return Err(MaterialError::NotPositiveDefinite);
    }
    let l = cholesky6(a).ok_or(MaterialError::NotPositiveDefinite)?;
    let mut inv = [[0.0; 6]; 6];
    for col in 0..6 {
        // Solve L y = e_col, then Lᵀ x = y.
        let mut y = [0.0; 6];
        for i in 0..6 {
            let rhs = if i == col { 1.0 } else { 0.0 };
            y[i] = (rhs - (0..i).map(|k| l[i][k] * y[k]).sum::<f64>()) / l[i][i];
        }
        let mut x = [0.0; 6];
        for i in (0..6).rev() {
            x[i] = (y[i] - (i + 1..6).map(|k| l[k][i] * x[k]).sum::<f64>()) / l[i][i];
        }
        for i in 0..6 {
            inv[i][col] = x[i];
        }
    }
    for i in 0..6 {
        for j in i + 1..6 {
            let v = 0.5 * (inv[i][j] + inv[j][i]);
            inv[i][j] = v;
            inv[j][i] = v;
        }
    }
    Ok(inv)
}

/// An orthonormal frame `q` (columns `q[.][k]` are the local axes in global coordinates) whose
/// third axis is `axis` normalized.
fn frame_with_axis(axis: [f64; 3]) -> Result<[[f64; 3]; 3], MaterialError> {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    if n.is_nan() || n <= 0.0 {
        return Err(MaterialError::ZeroAxis);
    }
    let e3 = axis.map(|v| v / n);
    // Start from the global axis least aligned with e3.
    let k = (0..3).fold(0, |best, i| {
        if e3[i].abs() < e3[best].abs() {
            i
        } else {
            best
        }
    });
    let mut h = [0.0; 3];
    h[k] = 1.0;
    let d = h[0] * e3[0] + h[1] * e3[1] + h[2] * e3[2];
    let t = [h[0] - d * e3[0], h[1] - d * e3[1], h[2] - d * e3[2]];
    let tn = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
    let e1 = t.map(|v| v / tn);
    let e2 = [
        e3[1] * e1[2] - e3[2] * e1[1],
        e3[2] * e1[0] - e3[0] * e1[2],
        e3[0] * e1[1] - e3[1] * e1[0],
    ];
    Ok(std::array::from_fn(|i| [e1[i], e2[i], e3[i]]))
}

/// Voigt index of the symmetric tensor index pair `(i, j)` (order `11, 22, 33, 12, 13, 23`).
const VOIGT: [[usize; 3]; 3] = [[0, 3, 4], [3, 1, 5], [4, 5, 2]];
/// Tensor index pair of each Voigt index.
const PAIR: [[usize; 2]; 6] = [[0, 0], [1, 1], [2, 2], [0, 1], [0, 2], [1, 2]];

/// Rotates a stiffness given in the local frame `q` to global axes:
/// `C_ijkl = q_ip q_jq q_kr q_ls C'_pqrs` (with engineering shear strains the Voigt entries are
/// the tensor components themselves).
fn rotate(c_local: &Voigt6, q: &[[f64; 3]; 3]) -> Voigt6 {
    let mut c = [[0.0; 6]; 6];
    for (big_i, [i, j]) in PAIR.iter().enumerate() {
        for (big_j, [k, l]) in PAIR.iter().enumerate() {
            let mut sum = 0.0;
            for p in 0..3 {
                for qq in 0..3 {
                    for r in 0..3 {
                        for s in 0..3 {
                            let f = q[*i][p] * q[*j][qq] * q[*k][r] * q[*l][s];
                            sum += f * c_local[VOIGT[p][qq]][VOIGT[r][s]];
                        }
                    }
                }
            }
            c[big_i][big_j] = sum;
        }
    }
    for i in 0..6 {
        for j in i + 1..6 {
            let v = 0.5 * (c[i][j] + c[j][i]);
            c[i][j] = v;
            c[j][i] = v;
        }
    }
    c
}

/// A material in use, with its elasticity matrix checked.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialEntry {
    /// The mesh's material name, or for an override the element set's name.
    pub name: String,
    pub material: ElasticMaterial,
    pub elasticity: Voigt6,
}

impl MaterialEntry {
    /// Checks the material (named `name` in errors).
    pub fn new(name: &str, material: ElasticMaterial) -> Result<Self, FeError> {
        let elasticity = material
            .elasticity()
            .map_err(|error| FeError::InvalidMaterial {
                material: name.to_string(),
                error,
            })?;
        Ok(Self {
            name: name.to_string(),
            material,
            elasticity,
        })
    }
}

/// The material of every element.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialTable {
    /// The materials in use.
    pub entries: Vec<MaterialEntry>,
    /// Index into `entries` of each element.
    pub element_entry: Vec<u32>,
}

impl MaterialTable {
    /// One material for every element.
    pub fn uniform(mesh: &Mesh, material: ElasticMaterial) -> Result<Self, FeError> {
        let entry = MaterialEntry::new("uniform", material)?;
        Ok(Self {
            entries: vec![entry],
            element_entry: vec![0; mesh.num_elements()],
        })
    }

    /// Materials from the mesh's sections (the last section covering an element wins, as in
    /// Abaqus), then `overrides` (element set name, material) applied in order, later ones
    /// winning. Set and material names are matched ASCII case-insensitively.
    ///
    /// Errors: an override naming no element set; an invalid material; a section's material
    /// undefined or incomplete (only if some element ends up using it); an element left
    /// without a material (named by its file id).
    pub fn from_mesh(
        mesh: &Mesh,
        overrides: &[(String, ElasticMaterial)],
    ) -> Result<Self, FeError> {
        // Candidates: sections first, invalid ones kept as errors until known to be used.
        let mut candidates: Vec<Result<MaterialEntry, FeError>> = Vec::new();
        let mut assigned: Vec<Option<u32>> = vec![None; mesh.num_elements()];
        for section in &mesh.sections {
            let Some(set) = mesh.element_set(&section.element_set) else {
                continue;
            };
            candidates.push(section_material(
                mesh,
                &section.material,
                &section.element_set,
            ));
            assign(&mut assigned, set, candidates.len() - 1);
        }
        for (set_name, material) in overrides {
            let set = mesh
                .element_set(set_name)
                .ok_or_else(|| FeError::UnknownElementSet(set_name.clone()))?;
            candidates.push(Ok(MaterialEntry::new(set_name, *material)?));
            assign(&mut assigned, set, candidates.len() - 1);
        }
        let missing: Vec<usize> = (0..assigned.len())
            .filter(|&e| assigned[e].is_none())
            .collect();
        if let Some(&first) = missing.first() {
            return Err(FeError::NoMaterial {
                element: mesh.element_ids[first],
                others: missing.len() - 1,
            });
        }
        // Keep the candidates some element ends up with, in order; an invalid one is an error
        // only then.
        let mut used = vec![false; candidates.len()];
        for &c in assigned.iter().flatten() {
            used[c as usize] = true;
        }
        let mut remap = vec![0u32; candidates.len()];
        let mut entries = Vec::new();
        for (c, candidate) in candidates.into_iter().enumerate() {
            if used[c] {
                remap[c] = entries.len() as u32;
                entries.push(candidate?);
            }
        }
        let element_entry = assigned
            .iter()
            .flatten()
            .map(|&c| remap[c as usize])
            .collect();
        Ok(Self {
            entries,
            element_entry,
        })
    }

    /// The material of element `e` (index), `None` if out of range.
    pub fn of_element(&self, e: usize) -> Option<&MaterialEntry> {
        self.entries.get(*self.element_entry.get(e)? as usize)
    }
}

fn assign(assigned: &mut [Option<u32>], set: &[u32], candidate: usize) {
    for &e in set {
        if let Some(slot) = assigned.get_mut(e as usize) {
            *slot = Some(candidate as u32);
        }
    }
}

/// The material a section names, converted and checked.
fn section_material(mesh: &Mesh, name: &str, element_set: &str) -> Result<MaterialEntry, FeError> {
    let (key, material) = mesh
        .materials
        .iter()
        .find(|(k, _)| k.eq_ignore_ascii_case(name))
        .ok_or_else(|| FeError::UnknownMaterial {
            material: name.to_string(),
            element_set: element_set.to_string(),
        })?;
    let elastic = ElasticMaterial::from_mesh_material(material).map_err(|missing| {
        FeError::IncompleteMaterial {
            material: key.clone(),
            missing,
        }
    })?;
    MaterialEntry::new(key, elastic)
}
