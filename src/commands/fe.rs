//! `squeal fe export`: sparse K and M of a mesh as MatrixMarket files, for MATLAB and Python.

use crate::commands::mesh::read_mesh;
use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand};
use squeal_fe::{DofMap, ElasticMaterial, MaterialTable, Restraint, assemble, write_matrix_market};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

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
    pub fn system(&self) -> Result<squeal_mesh::units::UnitSystem> {
        match &self.units {
            None => Ok(squeal_mesh::units::UnitSystem::default()),
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
    pub fn overrides_in(
        &self,
        units: &squeal_mesh::units::UnitSystem,
    ) -> Result<Vec<(String, ElasticMaterial)>> {
        let mut out = Vec::new();
        for (set, m) in self.overrides()? {
            let (si, warnings) = squeal_pipeline::mesh_info::material_in(&set, m, units);
            for w in warnings {
                eprintln!("warning: {w}");
            }
            out.push((set, si));
        }
        Ok(out)
    }

    /// Parses `SET=E,nu,rho` entries.
    pub fn overrides(&self) -> Result<Vec<(String, ElasticMaterial)>> {
        self.materials
            .iter()
            .map(|s| {
                let (set, values) = s
                    .split_once('=')
                    .with_context(|| format!("--material '{s}': expected SET=E,nu,rho"))?;
                let v: Vec<f64> = values
                    .split(',')
                    .map(|x| x.trim().parse::<f64>())
                    .collect::<Result<_, _>>()
                    .with_context(|| format!("--material '{s}': E, nu and rho must be numbers"))?;
                let [e, nu, rho] = v[..] else {
                    bail!("--material '{s}': expected three values E,nu,rho")
                };
                let m = ElasticMaterial::isotropic(e, nu, rho);
                // The same checks as the reduction's: E > 0, -1 < nu < 0.5, rho > 0.
                m.elasticity()
                    .with_context(|| format!("--material '{s}'"))?;
                Ok((set.trim().to_string(), m))
            })
            .collect()
    }
}

/// Parses `--clamp SET` and `--restrain SET:xyz` into restraints.
pub fn restraints(clamp: &[String], restrain: &[String]) -> Result<Vec<Restraint>> {
    let mut out: Vec<Restraint> = clamp.iter().map(|s| Restraint::clamp(s)).collect();
    for r in restrain {
        let (set, dirs) = r
            .split_once(':')
            .with_context(|| format!("--restrain '{r}': expected SET:xyz"))?;
        let mut d = [false; 3];
        for c in dirs.chars() {
            match c.to_ascii_lowercase() {
                'x' => d[0] = true,
                'y' => d[1] = true,
                'z' => d[2] = true,
                _ => bail!("--restrain '{r}': directions are letters among x, y, z"),
            }
        }
        out.push(Restraint::set(set, d));
    }
    Ok(out)
}

pub fn run(cmd: FeCommand) -> Result<ExitCode> {
    let FeCommand::Export(args) = cmd;
    if args.format != "mtx" {
        bail!(
            "--format '{}': only 'mtx' (MatrixMarket) is written",
            args.format
        );
    }
    squeal_io::require_folder(&args.out)?;
    let units = args.units.system()?;
    let mut read = read_mesh(&args.mesh)?;
    for w in squeal_pipeline::mesh_info::read_in(&args.mesh, &mut read, &units) {
        eprintln!("warning: {w}");
    }
    let mesh = read.mesh;
    let materials = MaterialTable::from_mesh(&mesh, &args.materials.overrides_in(&units)?)
        .with_context(|| {
            format!(
                "materials of {} (a .msh has none: give --material SET=E,nu,rho)",
                args.mesh.display()
            )
        })?;
    let dofmap = DofMap::new(&mesh, &restraints(&args.clamp, &args.restrain)?)?;
    let t = Instant::now();
    let system = assemble(&mesh, &materials, &dofmap)?;
    let assembled = t.elapsed();
    let stem = args
        .mesh
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "mesh".into());
    write_matrix_market(&args.out, &stem, &system.k, &system.m, &dofmap)?;
    println!(
        "{} free dofs ({} restrained), K {} and M {} stored nonzeros, assembled in {:.3} s",
        dofmap.num_free(),
        dofmap.num_restrained(),
        system.nnz_k(),
        system.nnz_m(),
        assembled.as_secs_f64()
    );
    println!(
        "K in N/m and M in kg (SI; the mesh read as {}: {})",
        units.name, units.description
    );
    for f in ["K.mtx", "M.mtx", "dofs.csv"] {
        println!("wrote {}", args.out.join(format!("{stem}_{f}")).display());
    }
    Ok(ExitCode::SUCCESS)
}
