//! Results onto the meshes: reduced vectors expanded with the Craig–Bampton basis and written
//! as VTU (one file per part, grouped by a `.vtm` multiblock that ParaView opens at once).

use crate::error::{PipelineError, Result};
use faer::c64;
use squeal_io::atomic_write;
use squeal_mesh::Mesh;
use squeal_mesh::vtu::{Field, write_vtu};
use squeal_reduce::rom::ReducedPart;
use std::path::{Path, PathBuf};

/// `u = basis · x` on the mesh's nodes: `3 × num_nodes` values, zero where restrained.
pub fn expand(part: &ReducedPart, mesh: &Mesh, mesh_path: &Path, x: &[f64]) -> Result<Vec<f64>> {
    let basis = part.basis.as_ref().ok_or_else(|| PipelineError::NoBasis {
        part: part.info.name.clone(),
    })?;
    if x.len() != part.size() {
        return Err(PipelineError::input(
            "expanding a reduced vector",
            format!(
                "{}: {} reduced values for {} dofs",
                part.info.name,
                x.len(),
                part.size()
            ),
        ));
    }
    let index = mesh.node_index_map();
    let mut field = vec![0.0; 3 * mesh.num_nodes()];
    for r in 0..basis.values.nrows() {
        let node = *index
            .get(&basis.dof_node[r])
            .ok_or_else(|| PipelineError::ForeignNode {
                part: part.info.name.clone(),
                node: basis.dof_node[r],
                mesh: mesh_path.to_path_buf(),
            })?;
        let u: f64 = (0..x.len()).map(|j| basis.values[(r, j)] * x[j]).sum();
        field[3 * node as usize + basis.dof_dir[r] as usize] = u;
    }
    Ok(field)
}

/// `u = basis · x` for a complex reduced vector (real and imaginary parts expanded apart).
pub fn expand_complex(
    part: &ReducedPart,
    mesh: &Mesh,
    mesh_path: &Path,
    x: &[c64],
) -> Result<Vec<c64>> {
    let re = expand(
        part,
        mesh,
        mesh_path,
        &x.iter().map(|v| v.re).collect::<Vec<_>>(),
    )?;
    let im = expand(
        part,
        mesh,
        mesh_path,
        &x.iter().map(|v| v.im).collect::<Vec<_>>(),
    )?;
    Ok(re
        .into_iter()
        .zip(im)
        .map(|(a, b)| c64::new(a, b))
        .collect())
}

/// One part of the brake for the writers: its reduced model, mesh (and file), and the range
/// of its dofs in the brake.
pub struct PartMesh<'a> {
    pub part: &'a ReducedPart,
    pub mesh: &'a Mesh,
    pub path: &'a Path,
    pub range: std::ops::Range<usize>,
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
    parts: &[PartMesh<'_>],
    fields: &[PartFields],
) -> Result<PathBuf> {
    let mut files = Vec::new();
    for p in parts {
        let (part, mesh) = (p.part, p.mesh);
        let expanded: Vec<Vec<f64>> = fields
            .iter()
            .map(|f| expand(part, mesh, p.path, &f.brake[p.range.clone()]))
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
        write_vtu(&dir.join(&file), mesh, &vtu_fields, &[])?;
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

/// The disc and pad meshes of a model, read once for the writers.
pub struct Meshes {
    pub disc: Mesh,
    /// The pads' meshes, in the brake's order.
    pub pads: Vec<Mesh>,
    disc_path: PathBuf,
    pad_paths: Vec<(String, PathBuf)>,
}

impl Meshes {
    /// Reads every mesh of `m`.
    pub fn read(m: &crate::model::Model, log: crate::model::Log) -> Result<Self> {
        let what = "the pictures and VTU files";
        if let Some(w) = crate::parts::left_out::left_out(&m.rom, what) {
            log(&w);
        }
        Ok(Self {
            disc: m.read_mesh(&m.disc_mesh, log)?,
            pads: m
                .pad_meshes
                .iter()
                .map(|(_, p)| m.read_mesh(p, log))
                .collect::<Result<_>>()?,
            disc_path: m.disc_mesh.clone(),
            pad_paths: m.pad_meshes.clone(),
        })
    }

    /// The parts for [`write_brake_vtu`], disc first.
    pub fn parts<'a>(&'a self, m: &'a crate::model::Model) -> Result<Vec<PartMesh<'a>>> {
        let disc = m
            .rom
            .part("disc")
            .ok_or(PipelineError::NoPart { part: "disc" })?;
        let mut parts = vec![PartMesh {
            part: disc,
            mesh: &self.disc,
            path: &self.disc_path,
            range: m.layout.disc.clone(),
        }];
        for ((mesh, (name, path)), (_, range)) in
            self.pads.iter().zip(&self.pad_paths).zip(&m.layout.pads)
        {
            let part = m
                .rom
                .part(name)
                .ok_or(PipelineError::NoPart { part: "pad" })?;
            parts.push(PartMesh {
                part,
                mesh,
                path,
                range: range.clone(),
            });
        }
        Ok(parts)
    }
}
