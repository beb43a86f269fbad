//! The summary of a mesh file that `squeal mesh info` prints: nodes, elements, bounds, node
//! and element sets, materials (the file's and those given on the command line), volume and
//! Jacobian quality, dofs and nonzeros of K and M, the mass, and the quality findings with
//! their ids.
//!
//! A mesh written in another consistent system (`--units mm`: mm, tonne, s, N, MPa) is
//! converted to SI on reading ([`read_in`]), with the `--material` constants given in that
//! system ([`material_in`]); everything is then printed in SI with its unit, and values no
//! structural part has (its size, moduli, densities: [`squeal_mesh::units::plausibility`], as
//! with a scene) are warned about.

use crate::error::{PipelineError, Result};
use squeal_fe::ElasticMaterial;
use squeal_mesh::quality::{self, QualityOptions, Severity};
use squeal_mesh::units::{SYSTEMS, UnitSystem, check_density, check_modulus, plausibility};
use squeal_mesh::{Elastic, Mesh};
use squeal_report::format::fmt_sig;
use std::fmt::Display;
use std::path::Path;
use std::time::Instant;

pub use squeal_mesh::ReadMesh;
pub use squeal_mesh::units::UnitSystem as Units;

/// Reads a mesh file (.inp, .bdf/.nas/.dat, .cdb or .msh) as its reader reads it; the reader's
/// warnings are in [`ReadMesh::warnings`].
pub fn read_mesh(path: &Path) -> Result<ReadMesh> {
    squeal_mesh::read(path).map_err(|error| PipelineError::Mesh {
        path: path.to_path_buf(),
        error,
    })
}

/// Reads the mesh `input` and writes it as VTK XML (`output`: `.vtu`, never over the input)
/// with its node and element sets as flags; the mesh as read is returned for its counts and
/// warnings.
pub fn convert(input: &Path, output: &Path) -> Result<ReadMesh> {
    squeal_io::require_extension(output, "vtu", "VTK XML unstructured grids (.vtu)")?;
    squeal_io::refuse_inputs(output, &[(input, "input mesh")])?;
    let read = read_mesh(input)?;
    squeal_mesh::vtu::write_vtu(output, &read.mesh, &[], &[])?;
    Ok(read)
}

/// Appends `text` and a line break.
fn line(s: &mut String, text: impl Display) {
    s.push_str(&text.to_string());
    s.push('\n');
}

/// The unit system `--units` names: `m` (SI), `mm` (mm, tonne, s, N, MPa: `mm-t-s`), `in`
/// (`in-lbf-s`), or any system's own name ([`SYSTEMS`]).
pub fn units_named(name: &str) -> Result<UnitSystem> {
    let system = match name.trim().to_ascii_lowercase().as_str() {
        "m" => Some(SYSTEMS[0]),
        "mm" => Some(SYSTEMS[1]),
        "in" => Some(SYSTEMS[4]),
        _ => UnitSystem::named(name),
    };
    system.ok_or_else(|| {
        PipelineError::input(
            "--units",
            format!(
                "'{name}' is not a unit system: give m (SI), mm (mm-t-s: mm, tonne, s, N, MPa), in (in-lbf-s) or one of {}",
                UnitSystem::names()
            ),
        )
    })
}

/// A mesh read in `units` converted to SI in place, and the warnings about values no brake
/// part has (its size, its materials' moduli and densities), each naming the file and, when
/// another system would make it plausible, the `--units` that says so.
pub fn read_in(path: &Path, read: &mut ReadMesh, units: &UnitSystem) -> Vec<String> {
    units.to_si(&mut read.mesh);
    plausibility(&read.mesh, units)
        .into_iter()
        .map(|w| format!("{}: {w}{}", path.display(), units_hint(&w)))
        .collect()
}

/// `; give --units <system>` when a warning names a system that would fit.
fn units_hint(warning: &str) -> &'static str {
    match warning.contains("would be plausible") {
        true => " (--units names the file's system)",
        false => "",
    }
}

/// A `--material` given in `units` (modulus in its stress unit, density in its density unit)
/// in SI, and the warnings about a modulus or density no structural solid has.
pub fn material_in(
    set: &str,
    m: ElasticMaterial,
    units: &UnitSystem,
) -> (ElasticMaterial, Vec<String>) {
    let si = match m {
        ElasticMaterial::Isotropic {
            young,
            poisson,
            density,
        } => ElasticMaterial::isotropic(young * units.stress(), poisson, density * units.density()),
        other => other,
    };
    let what = format!("--material {set}");
    let mut warnings = Vec::new();
    if let ElasticMaterial::Isotropic { young, density, .. } = si {
        for w in [
            check_modulus(&what, young, units),
            check_density(&what, density, units),
        ]
        .into_iter()
        .flatten()
        {
            let hint = units_hint(&w);
            warnings.push(format!("{w}{hint}"));
        }
    }
    (si, warnings)
}

/// Every `--material` of `list` in SI ([`material_in`]), and the warnings about them.
pub fn materials_in(
    list: &[(String, ElasticMaterial)],
    units: &UnitSystem,
) -> (Vec<(String, ElasticMaterial)>, Vec<String>) {
    let mut warnings = Vec::new();
    let si = list
        .iter()
        .map(|(set, m)| {
            let (si, w) = material_in(set, *m, units);
            warnings.extend(w);
            (set.clone(), si)
        })
        .collect();
    (si, warnings)
}

/// One mesh's summary, and whether the quality checks found errors. `read` is in SI (read in
/// `units`, [`read_in`]); the summary says in which system the file was read.
pub fn summary_text(
    path: &Path,
    read: &ReadMesh,
    elapsed: std::time::Duration,
    all_ids: bool,
    overrides: &[(String, ElasticMaterial)],
    units: &UnitSystem,
) -> Result<(String, bool)> {
    let mut s = String::new();
    let errors = summary(&mut s, path, read, elapsed, all_ids, overrides, units)?;
    Ok((s, errors))
}

fn summary(
    s: &mut String,
    path: &Path,
    read: &ReadMesh,
    elapsed: std::time::Duration,
    all_ids: bool,
    overrides: &[(String, ElasticMaterial)],
    units: &UnitSystem,
) -> Result<bool> {
    let m = &read.mesh;
    line(s, format_args!("{}", path.display()));
    line(
        s,
        format_args!(
            "  read in {:.3} s ({} warning(s))",
            elapsed.as_secs_f64(),
            read.warnings.len()
        ),
    );
    line(
        s,
        format_args!(
            "  units     read as {} ({}), shown in SI{}",
            units.name,
            units.description,
            if units.is_si() {
                " (--units mm for a file in mm, tonne, N, MPa)"
            } else {
                ""
            }
        ),
    );
    line(s, format_args!("  nodes     {:>10}", m.num_nodes()));
    // A tet10 mesh keeps its line as it was; a mesh with other kinds counts each.
    let kinds = if m.blocks.len() == m.blocks.tet10.len() {
        "10-node tetrahedra".to_string()
    } else {
        m.blocks
            .kinds()
            .into_iter()
            .map(|(kind, range)| format!("{} {}", range.len(), plural(kind)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    line(
        s,
        format_args!("  elements  {:>10}  ({kinds})", m.num_elements()),
    );
    if let Some((lo, hi)) = m.bounding_box() {
        line(
            s,
            format_args!(
                "  bounds    x [{:.6}, {:.6}]  y [{:.6}, {:.6}]  z [{:.6}, {:.6}] m",
                lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]
            ),
        );
    }
    sets(s, m);
    bodies(s, m);
    materials(s, m, overrides);
    let report = quality::check(m, &QualityOptions::default());
    line(s, format_args!("  volume    {:.9e} m^3", report.volume));
    line(
        s,
        format_args!(
            "  worst Jacobian ratio (min/max det J) {:.4}",
            report.worst_jacobian_ratio
        ),
    );
    let bad_materials = material_errors(m);
    if !report.has_errors() && bad_materials.is_empty() {
        fe(s, m, overrides)?;
    }
    if report.findings.is_empty() && bad_materials.is_empty() {
        line(s, format_args!("  quality   no findings"));
    }
    for e in &bad_materials {
        line(s, format_args!("  ERROR: {e}"));
    }
    for f in &report.findings {
        let tag = match f.severity {
            Severity::Error => "ERROR",
            Severity::Warning => "warning",
        };
        line(s, format_args!("  {tag}: {}", f.message));
        if !f.ids.is_empty() {
            line(
                s,
                format_args!("      ids: {}", format_ids(&f.ids, all_ids)),
            );
        }
    }
    Ok(report.has_errors() || !bad_materials.is_empty())
}

/// The file's materials whose constants no material has (E <= 0, nu outside (-1, 0.5),
/// density <= 0, a value not finite; what the finite-element stage refuses), one line each.
fn material_errors(m: &Mesh) -> Vec<String> {
    m.materials
        .iter()
        .filter_map(|(name, mat)| {
            let material = ElasticMaterial::from_mesh_material(mat).ok()?;
            let e = material.elasticity().err()?;
            Some(format!(
                "material {name} ({}): {e}",
                describe_file_material(mat)
            ))
        })
        .collect()
}

/// A file material's constants as `materials` lists them.
fn describe_file_material(mat: &squeal_mesh::Material) -> String {
    let elastic = match mat.elastic {
        Some(Elastic::Isotropic { young, poisson }) => format!("E = {young:e} Pa, nu = {poisson}"),
        Some(Elastic::EngineeringConstants { e, nu, g }) => {
            let list = |v: [f64; 3]| v.map(|x| x.to_string()).join(", ");
            format!(
                "E1,E2,E3 = {} Pa, nu12,nu13,nu23 = {}, G12,G13,G23 = {} Pa",
                list(e),
                list(nu),
                list(g)
            )
        }
        None => "no elastic constants".into(),
    };
    match mat.density {
        Some(rho) => format!("{elastic}, rho = {rho} kg/m^3"),
        None => elastic,
    }
}

/// Degrees of freedom, nonzeros of K and M (free part, no restraints) and the mass. A
/// material given with `--material` that is invalid (E <= 0, nu outside (-1, 0.5), ...) is an
/// error, as in `squeal reduce`.
fn fe(s: &mut String, m: &Mesh, overrides: &[(String, ElasticMaterial)]) -> Result<()> {
    use squeal_fe::{DofMap, MaterialTable, Summary, assemble};
    let mine: Vec<(String, ElasticMaterial)> = overrides
        .iter()
        .filter(|(set, _)| m.element_set(set).is_some())
        .cloned()
        .collect();
    let (materials, known) = match MaterialTable::from_mesh(m, &mine) {
        Ok(t) => (t, true),
        Err(e) if !mine.is_empty() => {
            return Err(PipelineError::input("--material", e));
        }
        // The sparsity pattern does not depend on the material: count it with a placeholder.
        Err(_) => match MaterialTable::uniform(m, ElasticMaterial::isotropic(1.0, 0.3, 1.0)) {
            Ok(t) => (t, false),
            Err(e) => {
                line(s, format_args!("  fe        not assembled: {e}"));
                return Ok(());
            }
        },
    };
    let t = Instant::now();
    let result = DofMap::new(m, &[]).and_then(|dofs| {
        let system = assemble(m, &materials, &dofs)?;
        Summary::new(m, &materials, &dofs, &system)
    });
    match result {
        Ok(sum) => {
            line(
                s,
                format_args!(
                    "  fe        {} dofs (free part), K {} and M {} stored nonzeros, assembled in {:.3} s",
                    sum.free_dofs,
                    sum.nnz_k,
                    sum.nnz_m,
                    t.elapsed().as_secs_f64()
                ),
            );
            if known {
                line(s, format_args!("  mass      {:.6e} kg", sum.mass));
            } else {
                line(
                    s,
                    format_args!(
                        "  mass      unknown: not every element has a material (give --material SET=E,nu,rho)"
                    ),
                );
            }
        }
        Err(e) => line(s, format_args!("  fe        not assembled: {e}")),
    }
    Ok(())
}

fn sets(s: &mut String, m: &Mesh) {
    if !m.node_sets.is_empty() {
        line(s, format_args!("  node sets"));
        for (name, set) in &m.node_sets {
            line(s, format_args!("    {name:<24} {:>8} nodes", set.len()));
        }
    }
    if !m.element_sets.is_empty() {
        let materials: Vec<(&str, &str)> = m
            .sections
            .iter()
            .map(|sec| (sec.element_set.as_str(), sec.material.as_str()))
            .collect();
        line(s, format_args!("  element sets"));
        for (name, set) in &m.element_sets {
            let mat = materials
                .iter()
                .rev()
                .find(|(es, _)| es.eq_ignore_ascii_case(name))
                .map(|(_, mat)| format!("  material {mat}"))
                .unwrap_or_default();
            line(
                s,
                format_args!("    {name:<24} {:>8} elements{mat}", set.len()),
            );
        }
    }
}

/// The bodies of the file (connected components of its elements) and the element sets that
/// are each: a file of several bodies is an assembly, whose parts a scene takes by element set
/// (`[model] disc_elset`, `pad_elset`, `[pads.<name>] elset`).
fn bodies(s: &mut String, m: &Mesh) {
    let found = squeal_mesh::part::bodies(m);
    line(
        s,
        format_args!(
            "  bodies    {:>10}  (connected components of elements){}",
            found.len(),
            if found.len() > 1 {
                ": an assembly; a scene takes a part by its element set"
            } else {
                ""
            }
        ),
    );
    if found.len() < 2 {
        return;
    }
    for (k, b) in found.iter().enumerate() {
        let whole: Vec<&str> = b
            .sets
            .iter()
            .filter(|(_, w)| *w)
            .map(|(n, _)| n.as_str())
            .collect();
        let partly: Vec<&str> = b
            .sets
            .iter()
            .filter(|(_, w)| !*w)
            .map(|(n, _)| n.as_str())
            .collect();
        let mut sets = match whole.is_empty() {
            true => "no element set is the whole body".to_string(),
            false => format!("element set(s) {}", whole.join(", ")),
        };
        if !partly.is_empty() {
            sets.push_str(&format!("; part of {}", partly.join(", ")));
        }
        line(
            s,
            format_args!(
                "    body {:<3} {:>8} elements {:>8} nodes (first element {}): {sets}",
                k + 1,
                b.elements,
                b.nodes,
                b.first_element
            ),
        );
    }
}

fn materials(s: &mut String, m: &Mesh, overrides: &[(String, ElasticMaterial)]) {
    let given: Vec<&(String, ElasticMaterial)> = overrides
        .iter()
        .filter(|(set, _)| m.element_set(set).is_some())
        .collect();
    if !given.is_empty() {
        line(
            s,
            format_args!(
                "  materials given with --material (they replace the file's on their sets)"
            ),
        );
        for (set, mat) in given {
            line(s, format_args!("    {set:<24} {}", describe(mat)));
        }
    }
    if m.materials.is_empty() {
        if overrides.is_empty() {
            line(
                s,
                format_args!(
                    "  materials none in the file (give them on the command line or in a scene)"
                ),
            );
        }
        return;
    }
    line(s, format_args!("  materials in the file"));
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
            .map(|r| format!(", rho = {} kg/m^3", fmt_sig(r, 6)))
            .unwrap_or_else(|| ", no density".into());
        line(s, format_args!("    {name:<24} {elastic}{rho}"));
    }
}

/// `E = .. Pa, nu = .., rho = .. kg/m^3` of a material given on the command line.
fn describe(m: &ElasticMaterial) -> String {
    match *m {
        ElasticMaterial::Isotropic {
            young,
            poisson,
            density,
        } => format!(
            "E = {young:.4e} Pa, nu = {poisson}, rho = {} kg/m^3",
            fmt_sig(density, 6)
        ),
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

/// The plural of an element kind's name, for the summary line.
fn plural(kind: squeal_mesh::ElementKind) -> &'static str {
    match kind {
        squeal_mesh::ElementKind::Tet10 => "10-node tetrahedra",
        squeal_mesh::ElementKind::Hex20 => "20-node hexahedra",
        squeal_mesh::ElementKind::Wedge15 => "15-node wedges",
        squeal_mesh::ElementKind::Pyramid13 => "13-node pyramids",
    }
}
