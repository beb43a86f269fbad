//! `squeal fe export`: the sparse stiffness and mass matrices of one mesh as MatrixMarket files
//! (lower triangle, K in N/m and M in kg) with the dof map as CSV, for MATLAB, SciPy or Julia.
//!
//! The mesh is read in the unit system the user names and converted to SI
//! ([`crate::mesh_info::read_in`]); the materials are the file's, or `SET=E,nu,rho` given on
//! the command line ([`parse_material`], in the same units); restraints are node sets held in
//! all or some directions ([`parse_restraints`]). The matrices are those of the reduction's
//! own assembly ([`squeal_fe::assemble`]): what a user checks against their own code is what
//! the pipeline reduces.

use crate::error::{PipelineError, Result};
use crate::mesh_info::read_in;
use squeal_fe::{DofMap, MaterialTable, assemble, write_matrix_market};
use squeal_mesh::units::UnitSystem;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

pub use squeal_fe::{ElasticMaterial, Restraint};

/// What to export.
#[derive(Clone, Debug, Default)]
#[non_exhaustive]
pub struct ExportRequest {
    /// The mesh file.
    pub mesh: PathBuf,
    /// The output folder.
    pub out: PathBuf,
    /// Node sets held ([`parse_restraints`]).
    pub restraints: Vec<Restraint>,
    /// Materials by element set, in the units of `units`, overriding the file's.
    pub materials: Vec<(String, ElasticMaterial)>,
    /// The unit system the mesh and `materials` are written in.
    pub units: UnitSystem,
}

impl ExportRequest {
    /// Exports `mesh` into `out` with the file's materials, nothing held, in SI.
    pub fn new(mesh: PathBuf, out: PathBuf) -> Self {
        Self {
            mesh,
            out,
            ..Self::default()
        }
    }
}

/// What was written.
#[derive(Clone, Debug)]
pub struct ExportReport {
    /// Free and restrained dofs.
    pub free: usize,
    pub restrained: usize,
    /// Stored nonzeros of K and M.
    pub nnz_k: usize,
    pub nnz_m: usize,
    /// Wall time of the assembly.
    pub assembled: Duration,
    /// The files written: `<stem>_K.mtx`, `<stem>_M.mtx`, `<stem>_dofs.csv`.
    pub files: Vec<PathBuf>,
    /// The reader's warnings and those about implausible values in these units.
    pub warnings: Vec<String>,
}

/// Assembles K and M of `req.mesh` and writes them into `req.out`.
pub fn export(req: &ExportRequest) -> Result<ExportReport> {
    squeal_io::require_folder(&req.out)?;
    let mut read = crate::mesh_info::read_mesh(&req.mesh)?;
    let mut warnings: Vec<String> = read.warnings.iter().map(|w| w.to_string()).collect();
    warnings.extend(read_in(&req.mesh, &mut read, &req.units));
    let (overrides, w) = crate::mesh_info::materials_in(&req.materials, &req.units);
    warnings.extend(w);
    let mesh = read.mesh;
    let materials = MaterialTable::from_mesh(&mesh, &overrides).map_err(|e| {
        PipelineError::input(
            "--material",
            format!(
                "materials of {}: {e} (a .msh has none: give --material SET=E,nu,rho)",
                req.mesh.display()
            ),
        )
    })?;
    let dofmap = DofMap::new(&mesh, &req.restraints).map_err(|e| in_file(&req.mesh, e))?;
    let t = Instant::now();
    let system = assemble(&mesh, &materials, &dofmap).map_err(|e| in_file(&req.mesh, e))?;
    let assembled = t.elapsed();
    let stem = req
        .mesh
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "mesh".into());
    write_matrix_market(&req.out, &stem, &system.k, &system.m, &dofmap)
        .map_err(|e| in_file(&req.out, e))?;
    Ok(ExportReport {
        free: dofmap.num_free(),
        restrained: dofmap.num_restrained(),
        nnz_k: system.nnz_k(),
        nnz_m: system.nnz_m(),
        assembled,
        files: ["K.mtx", "M.mtx", "dofs.csv"]
            .iter()
            .map(|f| req.out.join(format!("{stem}_{f}")))
            .collect(),
        warnings,
    })
}

/// An error of reading or assembling `path`, with the file named.
fn in_file(path: &Path, e: impl std::fmt::Display) -> PipelineError {
    PipelineError::MeshFindings {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// `--clamp SET` (all three directions) and `--restrain SET:xyz` (the letters' directions) as
/// restraints.
pub fn parse_restraints(clamp: &[String], restrain: &[String]) -> Result<Vec<Restraint>> {
    let mut out: Vec<Restraint> = clamp.iter().map(|s| Restraint::clamp(s)).collect();
    for r in restrain {
        let bad = |m: &str| PipelineError::input("--restrain", format!("'{r}' {m}"));
        let (set, dirs) = r.split_once(':').ok_or_else(|| bad("is not SET:xyz"))?;
        let mut d = [false; 3];
        for c in dirs.chars() {
            match c.to_ascii_lowercase() {
                'x' => d[0] = true,
                'y' => d[1] = true,
                'z' => d[2] = true,
                _ => return Err(bad("names a direction that is not x, y or z")),
            }
        }
        out.push(Restraint::set(set, d));
    }
    Ok(out)
}

/// `SET=E,nu,rho`: an isotropic material of an element set, checked as the reduction checks
/// it (E > 0, -1 < nu < 0.5, rho > 0); the values are in the units the command is given.
pub fn parse_material(s: &str) -> Result<(String, ElasticMaterial)> {
    let bad = |m: String| PipelineError::input("--material", format!("'{s}' {m}"));
    let (set, values) = s
        .split_once('=')
        .ok_or_else(|| bad("is not SET=E,nu,rho".into()))?;
    let v: Vec<f64> = values
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| bad("has an E, nu or rho that is not a number".into()))?;
    let [e, nu, rho] = v[..] else {
        return Err(bad("does not give three values E,nu,rho".into()));
    };
    let m = ElasticMaterial::isotropic(e, nu, rho);
    m.elasticity()
        .map_err(|e| bad(format!("is not a material: {e}")))?;
    Ok((set.trim().to_string(), m))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn restraints_and_materials_parse_and_refuse() {
        let r = parse_restraints(&["CLAMP".into()], &["ABUT:xZ".into()]).unwrap();
        assert_eq!(r.len(), 2);
        assert!(parse_restraints(&[], &["ABUT".into()]).is_err());
        assert!(parse_restraints(&[], &["ABUT:xw".into()]).is_err());
        let (set, m) = parse_material("DISC = 125e9, 0.26, 7200").unwrap();
        assert_eq!(set, "DISC");
        assert_eq!(m, ElasticMaterial::isotropic(125e9, 0.26, 7200.0));
        for bad in [
            "DISC",
            "DISC=1,2",
            "DISC=a,0.3,1",
            "DISC=1e9,0.5,7000",
            "D=-1,0.3,1",
        ] {
            let e = parse_material(bad).unwrap_err().to_string();
            assert!(e.starts_with("--material: '"), "{e}");
        }
    }
}
