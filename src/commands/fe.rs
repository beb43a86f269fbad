//! `squeal fe export`: sparse K and M of a mesh as MatrixMarket files, for MATLAB and Python.

use anyhow::{Result, bail};
use clap::{Args, Subcommand};
use squeal_pipeline::fe_export::{ElasticMaterial, ExportRequest, Restraint, export};
use squeal_pipeline::mesh_info::Units;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Subcommand)]
pub enum FeCommand {
    /// Write K and M (MatrixMarket, lower triangle) and the dof map (CSV)
    Export(ExportArgs),
}

#[derive(Args)]
pub struct ExportArgs {
    /// Mesh file (.inp or .msh)
    pub mesh: PathBuf,
    /// Output format (only MatrixMarket for now)
    #[arg(long, default_value = "mtx")]
    pub format: String,
    /// Output folder
    #[arg(long, short, default_value = ".")]
    pub out: PathBuf,
    /// Clamp a node set (all three directions); repeatable
    #[arg(long)]
    pub clamp: Vec<String>,
    /// Restrain a node set in some directions, e.g. ABUTMENT:xy; repeatable
    #[arg(long)]
    pub restrain: Vec<String>,
    #[command(flatten)]
    pub materials: MaterialArgs,
    #[command(flatten)]
    pub units: UnitsArg,
}

/// The unit system a mesh file (and `--material`) is written in.
#[derive(Args, Clone, Default)]
pub struct UnitsArg {
    /// The consistent unit system of the mesh file and of --material: m (SI, the default), mm
    /// (mm, tonne, s, N, MPa; density t/mm^3), in (in, lbf, psi), or mm-kg-ms, mm-g-ms;
    /// everything is converted to SI and shown in SI
    #[arg(long)]
    pub units: Option<String>,
}

impl UnitsArg {
    /// The system named (SI when none is).
    pub fn system(&self) -> Result<Units> {
        match &self.units {
            None => Ok(Units::default()),
            Some(name) => Ok(squeal_pipeline::mesh_info::units_named(name)?),
        }
    }
}

/// Materials given on the command line (a Gmsh .msh carries none).
#[derive(Args, Clone, Default)]
pub struct MaterialArgs {
    /// Isotropic material of an element set: SET=E,nu,rho (Pa, -, kg/m^3, or the units of
    /// --units where the command takes it: MPa and t/mm^3 with --units mm), e.g.
    /// DISC=125e9,0.26,7200; repeatable; overrides the mesh's own
    #[arg(long = "material")]
    pub materials: Vec<String>,
}

impl MaterialArgs {
    /// Parses `SET=E,nu,rho` entries given in `units`, in SI; a modulus or density no
    /// structural solid has is warned about on stderr.
    pub fn overrides_in(&self, units: &Units) -> Result<Vec<(String, ElasticMaterial)>> {
        let (si, warnings) = squeal_pipeline::mesh_info::materials_in(&self.overrides()?, units);
        for w in warnings {
            eprintln!("warning: {w}");
        }
        Ok(si)
    }

    /// Parses `SET=E,nu,rho` entries.
    pub fn overrides(&self) -> Result<Vec<(String, ElasticMaterial)>> {
        self.materials
            .iter()
            .map(|s| Ok(squeal_pipeline::fe_export::parse_material(s)?))
            .collect()
    }
}

/// Parses `--clamp SET` and `--restrain SET:xyz` into restraints.
pub fn restraints(clamp: &[String], restrain: &[String]) -> Result<Vec<Restraint>> {
    Ok(squeal_pipeline::fe_export::parse_restraints(
        clamp, restrain,
    )?)
}

pub fn run(cmd: FeCommand) -> Result<ExitCode> {
    let FeCommand::Export(args) = cmd;
    if args.format != "mtx" {
        bail!(
            "--format '{}': only 'mtx' (MatrixMarket) is written",
            args.format
        );
    }
    let units = args.units.system()?;
    let mut req = ExportRequest::new(args.mesh.clone(), args.out.clone());
    req.restraints = restraints(&args.clamp, &args.restrain)?;
    req.materials = args.materials.overrides()?;
    req.units = units;
    let done = export(&req)?;
    for w in &done.warnings {
        eprintln!("warning: {w}");
    }
    println!(
        "{} free dofs ({} restrained), K {} and M {} stored nonzeros, assembled in {:.3} s",
        done.free,
        done.restrained,
        done.nnz_k,
        done.nnz_m,
        done.assembled.as_secs_f64()
    );
    println!(
        "K in N/m and M in kg (SI; the mesh read as {}: {})",
        units.name, units.description
    );
    for f in &done.files {
        println!("wrote {}", f.display());
    }
    Ok(ExitCode::SUCCESS)
}
