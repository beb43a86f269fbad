//! Results onto the meshes: reduced vectors expanded with the Craig–Bampton basis and written
//! as VTU (one file per part, grouped by a `.vtm` multiblock that ParaView opens at once).

use anyhow::{Context, Result, anyhow, bail};
use faer::c64;
use squeal_io::atomic_write;
use squeal_mesh::Mesh;
use squeal_mesh::vtu::{Field, write_vtu};
use squeal_reduce::rom::ReducedPart;
use std::path::{Path, PathBuf};

/// `u = basis · x` on the mesh's nodes: `3 × num_nodes` values, zero where restrained.
pub fn expand(part: &ReducedPart, mesh: &Mesh, x: &[f64]) -> Result<Vec<f64>> {
    let basis = part.basis.as_ref().ok_or_else(|| {
        anyhow!("the reduced model of the {} was written without its basis: reduce again to expand results", part.info.name)
    })?;
    if x.len() != part.size() {
        bail!(
            "{}: {} reduced values for {} dofs",
            part.info.name,
            x.len(),
            part.size()
        );
    }
    let index = mesh.node_index_map();
    let mut field = vec![0.0; 3 * mesh.num_nodes()];
    for r in 0..basis.values.nrows() {
        let node = *index.get(&basis.dof_node[r]).ok_or_else(|| {
            anyhow!("{}: node {} of the reduced model is not in the mesh: was it reduced from another mesh?", part.info.name, basis.dof_node[r])
        })?;
        let u: f64 = (0..x.len()).map(|j| basis.values[(r, j)] * x[j]).sum();
        field[3 * node as usize + basis.dof_dir[r] as usize] = u;
    }
    Ok(field)
}

/// A field to write on both parts: name and per-part reduced vectors (real).
pub struct PartFields<'a> {
    pub name: &'a str,
    /// Reduced vector of the whole brake (disc dofs then pad dofs).
    pub brake: Vec<f64>,
}

/// Writes `dir/<stem>_disc.vtu`, `dir/<stem>_pad.vtu` and `dir/<stem>.vtm`, with each named
/// field expanded on both meshes. Returns the .vtm path.
pub fn write_brake_vtu(
    dir: &Path,
    stem: &str,
    parts: [(&ReducedPart, &Mesh, std::ops::Range<usize>); 2],
    fields: &[PartFields],
) -> Result<PathBuf> {
    let mut files = Vec::new();
    for (part, mesh, range) in parts {
        let expanded: Vec<Vec<f64>> = fields
            .iter()
            .map(|f| expand(part, mesh, &f.brake[range.clone()]))
            .collect::<Result<_>>()?;
        let vtu_fields: Vec<Field> = fields
            .iter()
            .zip(&expanded)
            .map(|(f, v)| Field {
                name: f.name,
                components: 3,
                values: v,
            })
            .collect();
        let file = format!("{stem}_{}.vtu", part.info.name);
        write_vtu(&dir.join(&file), mesh, &vtu_fields, &[])
            .with_context(|| format!("writing {file}"))?;
        files.push((part.info.name.clone(), file));
    }
    let vtm = dir.join(format!("{stem}.vtm"));
    atomic_write(&vtm, |w| {
        writeln!(w, r#"<?xml version="1.0"?>"#)?;
        writeln!(
            w,
            r#"<VTKFile type="vtkMultiBlockDataSet" version="1.0" byte_order="LittleEndian">"#
        )?;
        writeln!(w, "<vtkMultiBlockDataSet>")?;
        for (i, (name, file)) in files.iter().enumerate() {
            writeln!(w, r#"<DataSet index="{i}" name="{name}" file="{file}"/>"#)?;
        }
        writeln!(w, "</vtkMultiBlockDataSet>")?;
        writeln!(w, "</VTKFile>")
    })?;
    Ok(vtm)
}

/// A complex mode scaled so that its largest component is 1 and real.
pub fn normalize_mode(x: &[c64]) -> Vec<c64> {
    let big = x
        .iter()
        .copied()
        .max_by(|a, b| a.norm().total_cmp(&b.norm()))
        .unwrap_or(c64::new(1.0, 0.0));
    let s = if big.norm() > 0.0 {
        c64::new(1.0, 0.0) / big
    } else {
        c64::new(1.0, 0.0)
    };
    x.iter().map(|v| v * s).collect()
}
