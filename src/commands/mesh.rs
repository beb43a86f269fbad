//! `squeal mesh info` and `squeal mesh convert`.

use anyhow::{Context, Result, bail};
use clap::Subcommand;
use squeal_mesh::quality::{self, QualityOptions, Severity};
use squeal_mesh::{Elastic, Mesh, ReadMesh};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

#[derive(Subcommand)]
pub enum MeshCommand {
    /// Nodes, elements, sets, materials, volume and quality findings of each mesh; with
    /// --scene, the sets and materials a scene selects on its meshes
    Info {
        /// Mesh files (.inp or .msh)
        #[arg(required_unless_present = "scene", conflicts_with = "scene")]
        files: Vec<PathBuf>,
        /// List what a scene selects on its meshes ([sets], [units], [materials]): counts,
        /// areas and centroids of each set
        #[arg(long)]
        scene: Option<PathBuf>,
        /// With --scene: write both parts with the selected sets as point flags (.vtu, for
        /// ParaView)
        #[arg(long, requires = "scene")]
        vtu: Option<PathBuf>,
        /// List every id of each finding instead of the first few
        #[arg(long)]
        all_ids: bool,
        #[command(flatten)]
        materials: crate::commands::fe::MaterialArgs,
    },
    /// Write a mesh as VTK XML (.vtu) for ParaView, with node and element sets as flags
    Convert {
        /// Input mesh (.inp or .msh)
        input: PathBuf,
        /// Output file (.vtu)
        output: PathBuf,
    },
}

pub fn run(cmd: MeshCommand) -> Result<ExitCode> {
    match cmd {
        MeshCommand::Info {
            files,
            scene: Some(scene),
            vtu,
            materials,
            ..
        } => {
            debug_assert!(files.is_empty());
            if !materials.materials.is_empty() {
                bail!(
                    "--material does not go with --scene: give the materials in the scene's [materials.<SET>]"
                );
            }
            crate::commands::mesh_scene::info(&scene, vtu.as_deref())
        }
        MeshCommand::Info {
            files,
            all_ids,
            materials,
            ..
        } => {
            let overrides = materials.overrides()?;
            // Everything is read and checked before anything is printed: a bad file or a
            // --material that fits none of the meshes is an error, not a footnote.
            let mut read = Vec::with_capacity(files.len());
            for f in &files {
                let t = Instant::now();
                let mesh = read_mesh(f)?;
                read.push((f, mesh, t.elapsed()));
            }
            for (set, _) in &overrides {
                if !read
                    .iter()
                    .any(|(_, r, _)| r.mesh.element_set(set).is_some())
                {
                    let known: Vec<&str> = read
                        .iter()
                        .flat_map(|(_, r, _)| r.mesh.element_sets.keys().map(String::as_str))
                        .collect();
                    bail!(
                        "--material {set}=...: no element set {set} in {} (element sets: {})",
                        files
                            .iter()
                            .map(|f| f.display().to_string())
                            .collect::<Vec<_>>()
                            .join(", "),
                        if known.is_empty() {
                            "none".to_string()
                        } else {
                            known.join(", ")
                        }
                    );
                }
            }
            let mut any_error = false;
            for (k, (f, mesh, elapsed)) in read.iter().enumerate() {
                if k > 0 {
                    println!();
                }
                any_error |= info(f, mesh, *elapsed, all_ids, &overrides)?;
            }
            // 4, not 2: clap exits 2 on a usage error.
            Ok(if any_error {
                ExitCode::from(4)
            } else {
                ExitCode::SUCCESS
            })
        }
        MeshCommand::Convert { input, output } => {
            squeal_io::require_extension(&output, "vtu", "VTK XML unstructured grids (.vtu)")?;
            squeal_io::refuse_inputs(&output, &[(&input, "input mesh")])?;
            let read = read_mesh(&input)?;
            squeal_mesh::vtu::write_vtu(&output, &read.mesh, &[], &[])
                .with_context(|| format!("writing {}", output.display()))?;
            println!(
                "wrote {} ({} nodes, {} quadratic tetrahedra)",
                output.display(),
                read.mesh.num_nodes(),
                read.mesh.num_elements()
            );
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// Reads a mesh and prints the reader's warnings to stderr.
pub fn read_mesh(path: &Path) -> Result<ReadMesh> {
    let read =
        squeal_mesh::read(path).with_context(|| format!("reading mesh {}", path.display()))?;
    for w in &read.warnings {
        eprintln!("warning: {w}");
    }
    Ok(read)
}

/// Prints one mesh's summary; returns whether the quality checks found errors.
fn info(
    path: &Path,
    read: &ReadMesh,
    elapsed: std::time::Duration,
    all_ids: bool,
    overrides: &[(String, squeal_fe::ElasticMaterial)],
) -> Result<bool> {
    let m = &read.mesh;
    println!("{}", path.display());
    println!(
        "  read in {:.3} s ({} warning(s))",
        elapsed.as_secs_f64(),
        read.warnings.len()
    );
    println!("  nodes     {:>10}", m.num_nodes());
    println!("  elements  {:>10}  (10-node tetrahedra)", m.num_elements());
    if let Some((lo, hi)) = m.bounding_box() {
        println!(
            "  bounds    x [{:.6}, {:.6}]  y [{:.6}, {:.6}]  z [{:.6}, {:.6}]",
            lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]
        );
    }
    print_sets(m);
    print_materials(m, overrides);
    let report = quality::check(m, &QualityOptions::default());
    println!("  volume    {:.9e} m^3", report.volume);
    println!(
        "  worst Jacobian ratio (min/max det J) {:.4}",
        report.worst_jacobian_ratio
    );
    if !report.has_errors() {
        print_fe(m, overrides)?;
    }
    if report.findings.is_empty() {
        println!("  quality   no findings");
    }
    for f in &report.findings {
        let tag = match f.severity {
            Severity::Error => "ERROR",
            Severity::Warning => "warning",
        };
        println!("  {tag}: {}", f.message);
        if !f.ids.is_empty() {
            println!("      ids: {}", format_ids(&f.ids, all_ids));
        }
    }
    Ok(report.has_errors())
}

/// Degrees of freedom, nonzeros of K and M (free part, no restraints) and the mass. A
/// material given with `--material` that is invalid (E <= 0, nu outside (-1, 0.5), ...) is an
/// error, as in `squeal reduce`.
fn print_fe(m: &Mesh, overrides: &[(String, squeal_fe::ElasticMaterial)]) -> Result<()> {
    use squeal_fe::{DofMap, ElasticMaterial, MaterialTable, Summary, assemble};
    let mine: Vec<(String, ElasticMaterial)> = overrides
        .iter()
        .filter(|(set, _)| m.element_set(set).is_some())
        .cloned()
        .collect();
    let (materials, known) = match MaterialTable::from_mesh(m, &mine) {
        Ok(t) => (t, true),
        Err(e) if !mine.is_empty() => {
            return Err(anyhow::anyhow!("--material: {e}"));
        }
        // The sparsity pattern does not depend on the material: count it with a placeholder.
        Err(_) => match MaterialTable::uniform(m, ElasticMaterial::isotropic(1.0, 0.3, 1.0)) {
            Ok(t) => (t, false),
            Err(e) => {
                println!("  fe        not assembled: {e}");
                return Ok(());
            }
        },
    };
    let t = Instant::now();
    let result = DofMap::new(m, &[])
        .map_err(anyhow::Error::from)
        .and_then(|dofs| {
            let system = assemble(m, &materials, &dofs)?;
            Ok(Summary::new(m, &materials, &dofs, &system)?)
        });
    match result {
        Ok(s) => {
            println!(
                "  fe        {} dofs (free part), K {} and M {} stored nonzeros, assembled in {:.3} s",
                s.free_dofs,
                s.nnz_k,
                s.nnz_m,
                t.elapsed().as_secs_f64()
            );
            if known {
                println!("  mass      {:.6e} kg", s.mass);
            } else {
                println!(
                    "  mass      unknown: not every element has a material (give --material SET=E,nu,rho)"
                );
            }
        }
        Err(e) => println!("  fe        not assembled: {e:#}"),
    }
    Ok(())
}

fn print_sets(m: &Mesh) {
    if !m.node_sets.is_empty() {
        println!("  node sets");
        for (name, set) in &m.node_sets {
            println!("    {name:<24} {:>8} nodes", set.len());
        }
    }
    if !m.element_sets.is_empty() {
        let materials: Vec<(&str, &str)> = m
            .sections
            .iter()
            .map(|s| (s.element_set.as_str(), s.material.as_str()))
            .collect();
        println!("  element sets");
        for (name, set) in &m.element_sets {
            let mat = materials
                .iter()
                .rev()
                .find(|(es, _)| es.eq_ignore_ascii_case(name))
                .map(|(_, mat)| format!("  material {mat}"))
                .unwrap_or_default();
            println!("    {name:<24} {:>8} elements{mat}", set.len());
        }
    }
}

fn print_materials(m: &Mesh, overrides: &[(String, squeal_fe::ElasticMaterial)]) {
    let given: Vec<&(String, squeal_fe::ElasticMaterial)> = overrides
        .iter()
        .filter(|(set, _)| m.element_set(set).is_some())
        .collect();
    if !given.is_empty() {
        println!("  materials given with --material (they replace the file's on their sets)");
        for (set, mat) in given {
            println!("    {set:<24} {}", describe(mat));
        }
    }
    if m.materials.is_empty() {
        if overrides.is_empty() {
            println!("  materials none in the file (give them on the command line or in a scene)");
        }
        return;
    }
    println!("  materials in the file");
    for (name, mat) in &m.materials {
        let elastic = match mat.elastic {
            Some(Elastic::Isotropic { young, poisson }) => {
                format!("E = {young:.4e} Pa, nu = {poisson}")
            }
            Some(Elastic::EngineeringConstants { e, nu, g }) => format!(
                "E1,E2,E3 = {:.3e},{:.3e},{:.3e} Pa; nu12,nu13,nu23 = {},{},{}; G12,G13,G23 = {:.3e},{:.3e},{:.3e} Pa",
                e[0], e[1], e[2], nu[0], nu[1], nu[2], g[0], g[1], g[2]
            ),
            None => "no elastic constants".to_string(),
        };
        let rho = mat
            .density
            .map(|r| format!(", rho = {r} kg/m^3"))
            .unwrap_or_else(|| ", no density".into());
        println!("    {name:<24} {elastic}{rho}");
    }
}

/// `E = .. Pa, nu = .., rho = .. kg/m^3` of a material given on the command line.
fn describe(m: &squeal_fe::ElasticMaterial) -> String {
    match *m {
        squeal_fe::ElasticMaterial::Isotropic {
            young,
            poisson,
            density,
        } => format!("E = {young:.4e} Pa, nu = {poisson}, rho = {density} kg/m^3"),
        _ => "anisotropic".to_string(),
    }
}

fn format_ids(ids: &[u64], all: bool) -> String {
    const SHOWN: usize = 12;
    let shown: Vec<String> = ids
        .iter()
        .take(if all { ids.len() } else { SHOWN })
        .map(u64::to_string)
        .collect();
    let more = if !all && ids.len() > SHOWN {
        format!(" ... ({} in all; --all-ids lists them)", ids.len())
    } else {
        String::new()
    };
    format!("{}{more}", shown.join(" "))
}
