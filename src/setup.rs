//! From a scene to the objects of the analyses: the reduced model (cached in a .rom file and
//! rebuilt when its meshes or options change), the brake of eq (11), its damping and band.

use crate::scene::Scene;
use anyhow::{Context, Result};
use squeal_brake::Brake;
use squeal_brake::analysis::{DampingSpec, PairChoice};
use squeal_brake::assemble::{BrakeParams, Layout, Pairing, Stiffness, assemble};
use squeal_brake::sweep::{Band, SweepOptions};
use squeal_reduce::brake::{BrakeInputs, Freshness, ModeChoice, freshness, reduce_brake};
use squeal_reduce::craig_bampton::Stage;
use squeal_reduce::rom::{InterfaceKind, ReducedModel};
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

/// The reduction inputs of a scene: the bundled layout (disc clamped on `CLAMP`, pad held in
/// plane on `ABUTMENT`, pistons on `PISTON`, contact on `CONTACT` / `CONTACT_FACE`) on the
/// scene's meshes, interface and mode count.
pub fn brake_inputs(scene: &Scene) -> BrakeInputs {
    let m = &scene.file.model;
    let mut inputs = BrakeInputs::bundled(scene.resolve(&m.disc), scene.resolve(&m.pad));
    inputs.interface = if m.interface.get_ref() == "node" {
        InterfaceKind::Node
    } else {
        InterfaceKind::Patch
    };
    inputs.modes = ModeChoice::Fixed(*m.modes.get_ref());
    inputs
}

/// Loads the scene's reduced model, or reduces the meshes (and stores the result) when it is
/// missing or stale (other meshes, by SHA-256, other options, another tool version).
pub fn reduced_model(scene: &Scene, out: &Path, verbose: bool) -> Result<(ReducedModel, PathBuf)> {
    let rom_path = match &scene.file.model.rom {
        Some(p) => scene.resolve(p),
        None => out.join("brake.rom"),
    };
    let inputs = brake_inputs(scene);
    match freshness(&rom_path, &inputs).context("checking the reduced model")? {
        Freshness::Fresh => {
            if verbose {
                eprintln!("reduced model: {} (up to date)", rom_path.display());
            }
            let rom = ReducedModel::read(&rom_path)
                .with_context(|| format!("reading {}", rom_path.display()))?;
            return Ok((rom, rom_path));
        }
        Freshness::Stale(reasons) if verbose => {
            eprintln!(
                "reduced model: {} is stale ({}); reducing again",
                rom_path.display(),
                reasons.join("; ")
            )
        }
        _ => {}
    }
    if verbose {
        eprintln!(
            "reduced model: reducing {} and {} ...",
            inputs.disc.mesh.display(),
            inputs.pad.mesh.display()
        );
    }
    let t = std::time::Instant::now();
    let (rom, _) = reduce_brake(&inputs, &mut |part: &str, stage: Stage| {
        if verbose {
            eprintln!("  {part}: {}", stage.label());
        }
    })
    .context("reducing the brake")?;
    if verbose {
        eprintln!(
            "  reduced to {} dofs in {:.1} s",
            rom.size(),
            t.elapsed().as_secs_f64()
        );
    }
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
