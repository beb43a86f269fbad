//! From a scene to the objects of the analyses: the reduced model (cached in a .rom file and
//! rebuilt when its meshes or options change), the brake of eq (11), its damping and band.

use crate::scene::Scene;
use anyhow::{Context, Result};
use squeal_brake::Brake;
use squeal_brake::analysis::{DampingSpec, PairChoice};
use squeal_brake::assemble::{BrakeParams, Layout, Pairing, Stiffness, assemble};
use squeal_brake::sweep::{Band, SweepOptions};
use squeal_fe::{MaterialTable, Restraint};
use squeal_reduce::craig_bampton::{PartSpec, ReduceOptions, Stage, reduce_part};
use squeal_reduce::interface::Axis;
use squeal_reduce::rom::{InterfaceKind, MeshInfo, ReducedModel, sha256_file};
use std::path::{Path, PathBuf};

/// Everything an analysis of the scene needs.
pub struct Setup {
    pub rom: ReducedModel,
    pub rom_path: PathBuf,
    pub brake: Brake,
    pub layout: Layout,
    pub pairs: Vec<Pairing>,
    pub params: BrakeParams,
    pub damping: DampingSpec,
    pub sweep: SweepOptions,
    /// Meshes of the parts, as files.
    pub disc_mesh: PathBuf,
    pub pad_mesh: PathBuf,
}

/// The part specifications of the bundled brake layout.
fn part_specs(scene: &Scene, disc: &Path, pad: &Path) -> Result<[PartSpec; 2]> {
    let m = &scene.file.model;
    let interface = if m.interface.get_ref() == "node" {
        InterfaceKind::Node
    } else {
        InterfaceKind::Patch
    };
    let info = |p: &Path| -> Result<MeshInfo> {
        Ok(MeshInfo {
            path: p.display().to_string(),
            sha256: sha256_file(p)?,
            nodes: 0,
            elements: 0,
        })
    };
    let spec = |name: &str, mesh: MeshInfo, restraints, piston: Option<String>| PartSpec {
        name: name.into(),
        mesh,
        restraints,
        interface,
        contact_set: "CONTACT".into(),
        contact_face_set: "CONTACT_FACE".into(),
        grid: [3, 3],
        axis: Axis::default(),
        piston_set: piston,
        normal_direction: 2,
        modes: *m.modes.get_ref(),
    };
    Ok([
        spec("disc", info(disc)?, vec![Restraint::clamp("CLAMP")], None),
        spec(
            "pad",
            info(pad)?,
            vec![Restraint::set("ABUTMENT", [true, true, false])],
            Some("PISTON".into()),
        ),
    ])
}

/// Whether a stored model was made from these meshes with these options.
fn matches(rom: &ReducedModel, specs: &[PartSpec; 2]) -> bool {
    specs.iter().all(|s| {
        rom.part(&s.name).is_some_and(|p| {
            p.info.mesh.sha256 == s.mesh.sha256
                && p.info.interface == s.interface
                && p.info.fixed_interface_hz.len() == s.modes
                && p.basis.is_some()
        })
    })
}

/// Loads the scene's reduced model, or reduces the meshes (and stores the result) when it is
/// missing or was made from other meshes or options.
pub fn reduced_model(scene: &Scene, out: &Path, verbose: bool) -> Result<(ReducedModel, PathBuf)> {
    let m = &scene.file.model;
    let (disc, pad) = (scene.resolve(&m.disc), scene.resolve(&m.pad));
    let rom_path = match &m.rom {
        Some(p) => scene.resolve(p),
        None => out.join("brake.rom"),
    };
    let specs = part_specs(scene, &disc, &pad)?;
    if rom_path.exists()
        && let Ok(rom) = ReducedModel::read(&rom_path)
        && matches(&rom, &specs)
    {
        if verbose {
            eprintln!("reduced model: {} (up to date)", rom_path.display());
        }
        return Ok((rom, rom_path));
    }
    if verbose {
        eprintln!(
            "reduced model: reducing {} and {} ...",
            disc.display(),
            pad.display()
        );
    }
    let mut parts = Vec::new();
    for (spec, path) in specs.into_iter().zip([&disc, &pad]) {
        let read = crate::commands::mesh::read_mesh(path)?;
        let materials = MaterialTable::from_mesh(&read.mesh, &[])
            .with_context(|| format!("materials of {}", path.display()))?;
        let mut spec = spec;
        spec.mesh.nodes = read.mesh.num_nodes();
        spec.mesh.elements = read.mesh.num_elements();
        let name = spec.name.clone();
        let t = std::time::Instant::now();
        let (part, _) = reduce_part(
            &read.mesh,
            &materials,
            &spec,
            &ReduceOptions::default(),
            &mut |stage: Stage| {
                if verbose {
                    eprintln!("  {name}: {}", stage.label());
                }
            },
        )
        .with_context(|| format!("reducing the {name} ({})", path.display()))?;
        if verbose {
            eprintln!(
                "  {name}: {} dofs in {:.1} s",
                part.size(),
                t.elapsed().as_secs_f64()
            );
        }
        parts.push(part);
    }
    let rom = ReducedModel {
        tool_version: env!("CARGO_PKG_VERSION").into(),
        parts,
    };
    rom.write(&rom_path)
        .with_context(|| format!("writing {}", rom_path.display()))?;
    Ok((rom, rom_path))
}

/// Builds the brake, its damping and sweep options from a scene.
pub fn setup(scene: &Scene, out: &Path, verbose: bool) -> Result<Setup> {
    let (rom, rom_path) = reduced_model(scene, out, verbose)?;
    let f = &scene.file;
    let (kl, knl, _) = scene.stiffness()?;
    let params = BrakeParams {
        normal: *f.contact.normal.get_ref(),
        sliding: *f.friction.sliding_direction.get_ref(),
        stiffness: Stiffness::PerArea {
            linear: kl,
            cubic: knl,
            point_area: None,
        },
        pairing_tolerance: *f.contact.pairing_tolerance.get_ref(),
        piston_force: f.piston.line_pressure_bar.get_ref() * 1e5 * f.piston.area.get_ref(),
    };
    let (brake, layout, pairs) = assemble(&rom, &params).context("assembling the brake")?;
    let damping = DampingSpec {
        global_ratio: *f.damping.global_ratio.get_ref(),
        pair: match scene.pair()? {
            None => PairChoice::Auto,
            Some((a, b)) => PairChoice::Modes(a, b),
        },
        pair_ratios: f
            .damping
            .pair_ratios
            .as_ref()
            .map_or([0.0, 0.0], |r| *r.get_ref()),
    };
    let valid = rom
        .parts
        .iter()
        .filter_map(|p| p.info.fixed_interface_hz.last().copied())
        .fold(f64::INFINITY, f64::min);
    let sweep = SweepOptions {
        band: Band {
            valid_max_hz: valid,
            user: f
                .stability
                .band_hz
                .as_ref()
                .map(|b| (b.get_ref()[0], b.get_ref()[1])),
        },
        ..SweepOptions::default()
    };
    let m = &f.model;
    Ok(Setup {
        rom,
        rom_path,
        brake,
        layout,
        pairs,
        params,
        damping,
        sweep,
        disc_mesh: scene.resolve(&m.disc),
        pad_mesh: scene.resolve(&m.pad),
    })
}

/// The default output folder of a scene: `out/<scene stem>`.
pub fn default_out(scene: &Path) -> PathBuf {
    let stem = scene
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    PathBuf::from("out").join(stem)
}
