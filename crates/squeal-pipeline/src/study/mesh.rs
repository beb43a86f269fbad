//! The mesh-convergence study: μ0 on the coarse, medium and fine meshes with patch and node
//! contact (moved from `study.rs`; the scene variants are now built by the scene's typed
//! setters, [`Scene::variant`], instead of by editing its fields with made-up spans).

use super::record::{F, MeshOutcome, MeshRow, UnitResult};
use super::shard::Unit;
use super::{create_dir, no_hopf_point, opt};
use crate::error::{Context, PipelineError, Result};
use crate::model::{Log, Model, build, reduced_model, valid_max_hz};
use rayon::prelude::*;
use squeal_brake::Brake;
use squeal_brake::analysis::{DampingSpec, stability};
use squeal_brake::assemble::{Stiffness, assemble};
use squeal_brake::studies::{Case, outcome};
use squeal_brake::sweep::SweepOptions;
use squeal_reduce::rom::ReducedModel;
use squeal_report::{Figure, Panel, Scale, Series, Table, write_svg_and_png};
use squeal_scene::{Interface, Scene};
use std::path::{Path, PathBuf};

struct MeshModel {
    level: String,
    interface: &'static str,
    nodes: usize,
    brake: Brake,
    damping: DampingSpec,
    sweep: SweepOptions,
}

/// The scene with the meshes of `level`, the interface `interface` and its reduced model cached
/// in the study folder: a typed variant of the scene ([`Scene::variant`]).
fn variant(scene: &Scene, level: &str, interface: Interface, dir: &Path) -> Result<Scene> {
    let mut v = scene.variant()?;
    v.set_mesh_level(level)?;
    v.set_interface(interface);
    v.set_rom(&dir.join(format!("brake_{level}_{}.rom", interface.name())));
    Ok(v)
}

/// The disc and pad mesh files of every level, checked to exist (before the first, slow,
/// reduction starts).
pub(super) fn level_meshes(scene: &Scene, levels: &[String]) -> Result<Vec<PathBuf>> {
    crate::parts::left_out::refuse_levels(scene)?;
    if levels.is_empty() {
        return Err(PipelineError::input(
            "--levels",
            "give at least one mesh level",
        ));
    }
    let mut meshes = Vec::new();
    for level in levels {
        meshes.extend(scene.level_mesh_files(level)?);
    }
    let missing: Vec<String> = meshes
        .iter()
        .filter(|p| !p.is_file())
        .map(|p| p.display().to_string())
        .collect();
    if !missing.is_empty() {
        return Err(PipelineError::input(
            "--kind mesh",
            format!(
                "mesh files not found: {} (the scene's meshes must end in _<level>; --levels chooses the levels)",
                missing.join(", ")
            ),
        ));
    }
    Ok(meshes)
}

fn total_nodes(rom: &ReducedModel) -> usize {
    rom.parts.iter().map(|p| p.info.mesh.nodes).sum()
}

/// The node-contact brake of a level: each pair's stiffness per area times the area of the
/// patch whose centre its node is (from the patch brake of the same meshes), so both contacts
/// carry the same total stiffness.
fn node_brake(rom: &ReducedModel, patch: &Model) -> Result<Brake> {
    let params = squeal_brake::assemble::BrakeParams {
        stiffness: match patch.params.stiffness {
            Stiffness::PerArea { linear, cubic, .. } => Stiffness::PerArea {
                linear,
                cubic,
                point_area: Some(1.0),
            },
            other => other,
        },
        ..patch.params.clone()
    };
    let (mut brake, _, _) =
        assemble(rom, &params).with_context(|| "assembling the node-contact brake".into())?;
    for p in &mut brake.pairs {
        let near = patch
            .brake
            .pairs
            .iter()
            .min_by(|a, b| dist(a.position, p.position).total_cmp(&dist(b.position, p.position)))
            .ok_or_else(|| {
                PipelineError::input("mesh study", "the patch brake has no contact pairs")
            })?;
        let d = dist(near.position, p.position);
        if d > 0.25 * min_spacing(&patch.brake) {
            return Err(PipelineError::input(
                "mesh study",
                format!(
                    "node contact point at ({:.4}, {:.4}, {:.4}) is {d:.2e} m from the nearest patch centre: the node and patch interfaces do not match",
                    p.position[0], p.position[1], p.position[2]
                ),
            ));
        }
        p.law = near.law.clone();
    }
    Ok(brake)
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

fn min_spacing(b: &Brake) -> f64 {
    let mut m = f64::INFINITY;
    for (i, p) in b.pairs.iter().enumerate() {
        for q in &b.pairs[i + 1..] {
            m = m.min(dist(p.position, q.position));
        }
    }
    m
}

/// Computes the mesh study's levels among `units`: each level's patch and node models
/// (reduced one after the other, cached in `mdir`), then their sweeps in parallel.
pub(super) fn mesh_units(
    scene: &Scene,
    mdir: &Path,
    mus: &[f64],
    units: &[Unit],
    log: Log,
) -> Result<Vec<UnitResult>> {
    if !scene.dampers()?.is_empty() {
        // The node-interface brake of each level is assembled here without them.
        return Err(PipelineError::input(
            "mesh study",
            "[[dampers]] are not carried into the node-interface models of the mesh study yet: leave them out of the scene for the study",
        ));
    }
    create_dir(mdir)?;
    let mut models = Vec::new();
    for u in units {
        let Unit::Level(level) = u else {
            return Err(PipelineError::input(
                "mesh study",
                format!("unit {} is not a mesh level", u.key()),
            ));
        };
        // Reductions one after the other (each is parallel inside and needs the memory).
        let pv = variant(scene, level, Interface::Patch, mdir)?;
        let ps = build(&pv, mdir, log).with_context(|| format!("{level} meshes, patch"))?;
        let nv = variant(scene, level, Interface::Node, mdir)?;
        let (nrom, _) =
            reduced_model(&nv, mdir, log).with_context(|| format!("{level} meshes, node"))?;
        let nb = node_brake(&nrom, &ps)?;
        // The damping comes from the scene's [damping] alone: the same on every level.
        models.push(MeshModel {
            level: level.clone(),
            interface: "node",
            nodes: total_nodes(&nrom),
            brake: nb,
            damping: ps.damping,
            sweep: {
                let mut o = ps.sweep;
                o.band = squeal_brake::sweep::Band {
                    valid_max_hz: valid_max_hz(&nrom),
                    ..ps.sweep.band
                };
                o
            },
        });
        models.push(MeshModel {
            level: level.clone(),
            interface: "patch",
            nodes: total_nodes(&ps.rom),
            brake: ps.brake,
            damping: ps.damping,
            sweep: ps.sweep,
        });
    }
    log(&format!(
        "mesh study: {} stability analyses in parallel ...",
        models.len()
    ));
    let rows: Vec<MeshRow> = models
        .par_iter()
        .map(|m| {
            let r = stability(&m.brake, &m.damping, mus, &m.sweep)
                .with_context(|| format!("{} meshes, {} contact", m.level, m.interface))
                .map(|st| outcome(&Case::default(), &st));
            MeshRow {
                interface: m.interface.into(),
                nodes: m.nodes,
                outcome: match r {
                    Ok(o) => MeshOutcome::Found {
                        mu0: o.mu0.map(F),
                        frequency_hz: o.frequency_hz.map(F),
                        pair: o.pair,
                        pair_hz: o.pair_hz.map(|(a, b)| (F(a), F(b))),
                    },
                    // A model without a Hopf point in the band is a result (node contact on
                    // fine meshes), not a failure of the study: the row says so. Any other
                    // error is a failure, and the row says that.
                    Err(e) if no_hopf_point(&e) => MeshOutcome::NoHopfPoint(e.to_string()),
                    Err(e) => MeshOutcome::Failed(e.to_string()),
                },
            }
        })
        .collect();
    // Two models (node, patch) per level.
    Ok(rows
        .chunks(2)
        .map(|c| UnitResult::Level(c.to_vec()))
        .collect())
}

/// Writes the mesh study from its levels' models (in level order).
pub(super) fn write_mesh(levels: &[(&str, &Vec<MeshRow>)], dir: &Path, log: Log) -> Result<()> {
    let mut t = Table::new([
        "level",
        "interface",
        "nodes",
        "mu0",
        "frequency_hz",
        "mode1",
        "mode1_hz",
        "mode2",
        "mode2_hz",
        "mu0_change_from_previous_level",
        "frequency_change_from_previous_level",
    ]);
    // (interface, (dofs, mu0) points, (dofs, frequency) points)
    #[allow(clippy::type_complexity)]
    let mut points: Vec<(&'static str, Vec<(f64, f64)>, Vec<(f64, f64)>)> =
        vec![("patch", vec![], vec![]), ("node", vec![], vec![])];
    let mut failures = Vec::new();
    for iface in ["patch", "node"] {
        let mut prev: Option<(f64, f64)> = None;
        for (level, rows) in levels {
            let Some(m) = rows.iter().find(|r| r.interface == iface) else {
                return Err(PipelineError::input(
                    "mesh study",
                    format!("no {iface}-contact result for the {level} meshes"),
                ));
            };
            let (mu0, frequency_hz, pair, pair_hz) = match &m.outcome {
                MeshOutcome::Found {
                    mu0,
                    frequency_hz,
                    pair,
                    pair_hz,
                } => (
                    mu0.map(|v| v.0),
                    frequency_hz.map(|v| v.0),
                    *pair,
                    pair_hz.map(|(a, b)| (a.0, b.0)),
                ),
                MeshOutcome::NoHopfPoint(e) | MeshOutcome::Failed(e) => {
                    let none = matches!(m.outcome, MeshOutcome::NoHopfPoint(_));
                    failures.push(if none {
                        format!("{level} meshes, {iface}: no Hopf point in the band ({e})")
                    } else {
                        format!("{level} meshes, {iface}: the analysis failed: {e}")
                    });
                    let mut row = vec![level.to_string(), iface.to_string(), m.nodes.to_string()];
                    row.push(if none { "none" } else { "failed" }.into());
                    row.extend(std::iter::repeat_n("-".to_string(), 7));
                    t.push_row(row);
                    prev = None;
                    continue;
                }
            };
            let change = |now: Option<f64>, before: Option<f64>| {
                now.zip(before).map_or("-".into(), |(a, b)| {
                    format!("{:+.2}%", 100.0 * (a / b - 1.0))
                })
            };
            t.push_row([
                level.to_string(),
                iface.to_string(),
                m.nodes.to_string(),
                opt(mu0, 6),
                opt(frequency_hz, 6),
                pair.map_or("-".into(), |p| format!("#{}", p.0 + 1)),
                opt(pair_hz.map(|p| p.0), 5),
                pair.map_or("-".into(), |p| format!("#{}", p.1 + 1)),
                opt(pair_hz.map(|p| p.1), 5),
                change(mu0, prev.map(|p| p.0)),
                change(frequency_hz, prev.map(|p| p.1)),
            ]);
            if let (Some(mu0), Some(f)) = (mu0, frequency_hz) {
                prev = Some((mu0, f));
                let k = usize::from(iface == "node");
                points[k].1.push((m.nodes as f64, mu0));
                points[k].2.push((m.nodes as f64, f));
            } else {
                prev = None;
            }
        }
    }
    let t = t.align_numbers_right();
    log("\nMesh convergence of the Hopf point (patch and node contact):");
    log(&t.to_text());
    for f in &failures {
        log(f);
    }
    t.write_csv(&dir.join("mesh.csv"))?;
    squeal_io::atomic_write_bytes(&dir.join("mesh.md"), t.to_markdown().as_bytes())?;
    let panel = |title: &str, y: &str, k: usize| Panel {
        title: title.into(),
        x_label: "nodes (disc + pad)".into(),
        y_label: y.into(),
        x_scale: Scale::Log,
        series: points
            .iter()
            .map(|p| {
                Series::line_markers(
                    format!("{} contact", p.0),
                    if k == 0 { p.1.clone() } else { p.2.clone() },
                )
            })
            .collect(),
        ..Panel::default()
    };
    let fig = Figure {
        title: "Mesh convergence of the Hopf point".into(),
        panels: vec![
            panel("(a) mu0", "mu0", 0),
            panel("(b) frequency at mu0", "frequency (Hz)", 1),
        ],
        ..Figure::default()
    };
    write_svg_and_png(&fig, &dir.join("mesh"))?;
    Ok(())
}
