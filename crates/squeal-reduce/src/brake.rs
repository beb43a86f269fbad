//! The brake: a disc and a pad, from their mesh files to the reduced model of eqs (1)–(7).
//!
//! [`reduce_brake`] reads both meshes (recording their SHA-256), checks that every disc
//! contact point faces a pad contact point, then reduces the disc and the pad with
//! [`reduce_part`](crate::craig_bampton::reduce_part) at the same time, as two tasks of the rayon pool (each part's own parallel
//! work shares the pool with the other's; the results do not depend on the thread count). With [`BrakeInputs::default`] (the bundled setup: disc clamped on `CLAMP`,
//! pad held in-plane on `ABUTMENT` with its `PISTON` nodes' normal dof kept, nine contact points
//! per part, 50 fixed-interface modes) the result is the paper's 158-dof brake:
//! 27 + 50 disc dofs and 27 + 4 + 50 pad dofs (Sec. 2.1).
//!
//! Each part's [`BuildRecord`] is stored in the file, so that [`freshness`] can tell whether an
//! existing `.rom` still matches given inputs (mesh hashes, options, tool version).

use crate::craig_bampton::{
    PartSpec, ReduceError, ReduceOptions, ReduceReport, Stage, reduce_part_coupled,
};
use crate::interface::nodal::{NodalPair, face_nodes, project_pad};
use crate::interface::{InterfaceError, contact_nodes, patches};
use crate::rom::ReducedPart;
use crate::rom::{
    BuildRecord, ContactSurface, InterfaceKind, InterfacePoint, MeshInfo, PointRole, Projected,
    ReducedModel, RomError, RomHeader, VERSION, read_header, sha256_file,
};
use squeal_eigs::Backend;
use squeal_fe::{MaterialTable, NodeSelection};
use squeal_mesh::Mesh;
use squeal_mesh::units::UnitSystem;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError, mpsc};
use std::time::{Duration, Instant};

mod freshness;
#[allow(unused_imports)]
use freshness::*;
pub use freshness::{Freshness, freshness, stale_reasons};

mod pairing;
#[allow(unused_imports)]
use pairing::*;
pub use pairing::{PairingTolerance, check_sets, contact_positions, pair_contact_points};

mod load;
#[allow(unused_imports)]
use load::*;

mod kept;
#[allow(unused_imports)]
use kept::*;

mod relay;

mod report;
pub use report::{BrakeReport, PartReport, PointPair};

mod bodies;
/// The inputs of a reduction: the parts, their meshes, sets, restraints and options.
mod inputs;
#[allow(unused_imports)]
use bodies::*;
pub use bodies::{
    connection_reasons, free_motions_coupled, require_held_coupled, resolve_connections,
};
pub use inputs::{BrakeInputs, ModeChoice, PadInput, PartInput};
pub use kept::{forget_kept, kept_dir};
pub use load::{
    LoadedPart, backend_name, load_part, load_part_in, load_part_of, refuse_mesh_errors,
    refuse_shortened_set,
};
use relay::relay;

/// The version written into every `.rom` file; a file made by another version is stale. The
/// suffix is the revision of the numbers a reduction produces: bump it with every change that
/// moves the reduced matrices (fe2: curved tet10 elements integrated with the 24-point rule), so
/// that a cache made by older code is reduced again instead of silently reused.
pub const TOOL_VERSION: &str = concat!("squeal ", env!("CARGO_PKG_VERSION"), "+fe2");

/// Default multiple of the highest frequency of interest below which modes are kept in
/// [`ModeChoice::Auto`] (see `docs/reduction.md` for how the choice moves the frequencies).
pub const DEFAULT_AUTO_FACTOR: f64 = 2.0;

/// Default limit on the fixed-interface modes of one part: the basis is
/// `free dofs x (boundary + modes)` doubles, about 1 GB for 1000 modes of the fine disc.
pub const DEFAULT_MAX_MODES: usize = 1000;

/// Default pairing tolerance, as a fraction of the smallest distance between two of the disc's
/// contact points (the patch size).
pub const DEFAULT_PAIRING_TOLERANCE: f64 = 0.05;

/// Reads the meshes, pairs each pad's contact points with the disc surface facing it and
/// reduces every part. `progress(part, stage)` is told each stage as it starts.
pub fn reduce_brake(
    inputs: &BrakeInputs,
    progress: &mut dyn FnMut(&str, Stage),
) -> Result<(ReducedModel, BrakeReport), ReduceError> {
    inputs.validate()?;
    progress("disc", Stage::Read);
    let disc = load_part_of(&inputs.disc.mesh, &inputs.disc.elset, &inputs.disc.units)?;
    let mut pads = Vec::with_capacity(inputs.pads.len());
    for pad in &inputs.pads {
        progress(&pad.name, Stage::Read);
        let p = &pad.part;
        pads.push(load_part_of(&p.mesh, &p.elset, &p.units)?);
    }
    for body in &inputs.bodies {
        progress(&body.name, Stage::Read);
        let p = &body.part;
        pads.push(load_part_of(&p.mesh, &p.elset, &p.units)?);
    }
    reduce_brake_loaded(inputs, disc, pads, progress)
}

/// [`reduce_brake`] on meshes already read, the pads in the order of `inputs.pads`, then the
/// bodies in the order of `inputs.bodies` (the mesh paths of `inputs` are not opened).
pub fn reduce_brake_loaded(
    inputs: &BrakeInputs,
    disc: LoadedPart,
    pads: Vec<LoadedPart>,
    progress: &mut dyn FnMut(&str, Stage),
) -> Result<(ReducedModel, BrakeReport), ReduceError> {
    reduce_brake_keeping(inputs, disc, pads, None, progress)
}

/// [`reduce_brake_loaded`], keeping finished reductions in the folder `keep` when another
/// part fails, and taking parts kept there by an earlier run instead of reducing them again
/// ([`kept_dir`]; the kept reductions' docs are in `brake/kept.rs`). `None`: nothing kept or
/// taken.
pub fn reduce_brake_keeping(
    inputs: &BrakeInputs,
    disc: LoadedPart,
    pads: Vec<LoadedPart>,
    keep: Option<&Path>,
    progress: &mut dyn FnMut(&str, Stage),
) -> Result<(ReducedModel, BrakeReport), ReduceError> {
    let t0 = Instant::now();
    inputs.validate()?;
    if pads.len() != inputs.pads.len() + inputs.bodies.len() {
        return Err(ReduceError::Options(format!(
            "{} pad and body meshes read for {} pads and {} bodies",
            pads.len(),
            inputs.pads.len(),
            inputs.bodies.len()
        )));
    }
    // Errors in a part name its mesh file.
    let in_mesh = |input: &PartInput| {
        let path = input.mesh.clone();
        move |e: ReduceError| ReduceError::InMesh {
            path,
            error: Box::new(e),
        }
    };
    let loaded: Vec<LoadedPart> = std::iter::once(disc).chain(pads).collect();
    let parts = inputs.parts();
    for (part, (name, input)) in loaded.iter().zip(&parts) {
        match inputs.bodies.iter().any(|b| b.name == *name) {
            true => check_body_sets(&part.mesh, input).map_err(in_mesh(input))?,
            false => check_sets(&part.mesh, name, input, inputs).map_err(in_mesh(input))?,
        }
    }
    // Every part held before any part is reduced (a pad left free no longer costs the disc's
    // reduction first).
    for (part, (name, input)) in loaded.iter().zip(&parts) {
        let spec = inputs.spec(name, input, part.info.clone());
        require_held_coupled(&part.mesh, &spec, &input.couplings).map_err(in_mesh(input))?;
    }
    // Ties between parts: checked and projected before any reduction.
    let tie_projections = {
        let meshes: Vec<(&str, &Mesh)> = parts
            .iter()
            .zip(&loaded)
            .map(|((name, _), part)| (*name, &part.mesh))
            .collect();
        let bodies: Vec<&str> = inputs.bodies.iter().map(|b| b.name.as_str()).collect();
        for t in &inputs.part_ties {
            for (part, set) in [&t.slave, &t.master] {
                let kept = parts.iter().any(|(name, input)| {
                    name == part && input.couplings.iter().any(|c| c.nodal && c.set == *set)
                });
                if !kept && parts.iter().any(|(name, _)| name == part) {
                    return Err(ReduceError::Options(format!(
                        "tie of {} on {} to {} on {}: part '{part}' does not keep the set {set} node by node (add it to the part's couplings with nodal = true)",
                        t.slave.1, t.slave.0, t.master.1, t.master.0
                    )));
                }
            }
        }
        crate::part_tie::project_ties(&inputs.part_ties, &meshes, &bodies)?
    };
    let mut pairs = Vec::new();
    let mut tolerance = 0.0;
    // Nodal interface: each pad's face nodes projected onto the disc face under it, before
    // any reduction (a pad that does not face the disc is refused here).
    let projections = if inputs.interface == InterfaceKind::Nodal {
        nodal_projections(inputs, &loaded).map_err(in_mesh(&inputs.disc))?
    } else {
        Vec::new()
    };
    // The disc's contact points, surface by surface in the order of its reduced points.
    let surfaces = inputs.disc.surfaces();
    let mut disc_points = Vec::with_capacity(surfaces.len());
    for surface in surfaces.iter().filter(|_| projections.is_empty()) {
        disc_points.push(
            contact_positions(&loaded[0].mesh, surface, inputs).map_err(in_mesh(&inputs.disc))?,
        );
    }
    for (pad, part) in inputs
        .pads
        .iter()
        .zip(&loaded[1..])
        .filter(|_| projections.is_empty())
    {
        let k = inputs
            .disc
            .surface_index(&pad.name, inputs.pads.len())
            .ok_or_else(|| ReduceError::Options(format!("no disc surface faces {}", pad.name)))?;
        let offset: usize = disc_points[..k].iter().map(Vec::len).sum();
        let pad_surface = pad.part.surfaces().swap_remove(0);
        let pad_points =
            contact_positions(&part.mesh, &pad_surface, inputs).map_err(in_mesh(&pad.part))?;
        let (p, t) = pair_contact_points(
            &disc_points[k],
            &pad_points,
            PairingTolerance::Relative(inputs.pairing_tolerance),
        )?;
        pairs.extend(p.into_iter().map(|mut c| {
            c.disc_point += offset;
            c
        }));
        tolerance = f64::max(tolerance, t);
    }
    let opts = inputs.reduce_options();
    // Parts an earlier run finished and kept, still standing for them.
    let taken: Vec<Option<ReducedPart>> = loaded
        .iter()
        .zip(&parts)
        .map(|(part, (name, input))| {
            keep.and_then(|dir| take_kept(dir, name, input, inputs, &part.info.sha256))
        })
        .collect();
    let (tx, rx) = mpsc::channel::<(usize, Stage)>();
    let slots: Vec<Mutex<Option<Reduced>>> = parts.iter().map(|_| Mutex::new(None)).collect();
    rayon::in_place_scope(|scope| {
        for (k, (((part, (name, input)), slot), taken)) in loaded
            .into_iter()
            .zip(&parts)
            .zip(&slots)
            .zip(taken)
            .enumerate()
        {
            let tx = tx.clone();
            let opts = &opts;
            scope.spawn(move |_| {
                let mut tell = |stage| {
                    // The receiver lives until every part is done.
                    let _ = tx.send((k, stage));
                };
                let reduced = match taken {
                    Some(kept) => Ok((kept, reused_report(name, part))),
                    None => reduce_loaded(inputs, name, input, part, opts, &mut tell),
                };
                *slot.lock().unwrap_or_else(PoisonError::into_inner) = Some(reduced);
            });
        }
        drop(tx);
        relay(&rx, &mut |k, stage| progress(parts[k].0, stage));
    });
    let mut results = Vec::with_capacity(parts.len());
    for (slot, (_, input)) in slots.into_iter().zip(&parts) {
        let reduced = slot.into_inner().unwrap_or_else(PoisonError::into_inner);
        results.push(
            reduced
                .ok_or_else(|| ReduceError::Invalid {
                    part: "brake".into(),
                    what: "a part's reduction ended without a result".into(),
                })
                .and_then(|r| r)
                .map_err(in_mesh(input)),
        );
    }
    let (done, failed): (Vec<_>, Vec<_>) = results.into_iter().partition(Result::is_ok);
    let done: Vec<(ReducedPart, PartReport)> = done.into_iter().flatten().collect();
    if let Some(Err(e)) = failed.into_iter().next() {
        // Keep what finished (and was not taken from the folder already) for the next run.
        if let Some(dir) = keep {
            let fresh: Vec<&ReducedPart> = done
                .iter()
                .filter(|(_, report)| !report.reused)
                .map(|(part, _)| part)
                .collect();
            if !fresh.is_empty() {
                keep_parts(dir, &fresh)?;
            }
        }
        return Err(e);
    }
    let (mut reduced_parts, reports): (Vec<_>, Vec<_>) = done.into_iter().unzip();
    if !projections.is_empty() {
        pairs = attach_projections(&mut reduced_parts, projections)?;
    }
    let connections = resolve_connections(inputs, &reduced_parts)?;
    let ties = crate::part_tie::resolve_ties(&inputs.part_ties, &tie_projections, &reduced_parts)?;
    let model = ReducedModel {
        tool_version: TOOL_VERSION.into(),
        parts: reduced_parts,
        connections,
        ties,
    };
    let read: Duration = reports.iter().map(|r| r.read_time).sum();
    let report = BrakeReport {
        parts: reports,
        pairs,
        pairing_tolerance: tolerance,
        total: t0.elapsed() + read,
    };
    Ok((model, report))
}

/// A reduced part and its report, or why not.
type Reduced = Result<(ReducedPart, PartReport), ReduceError>;

/// Reduces one read part with the brake's options.
fn reduce_loaded(
    inputs: &BrakeInputs,
    name: &str,
    input: &PartInput,
    loaded: LoadedPart,
    opts: &ReduceOptions,
    progress: &mut dyn FnMut(Stage),
) -> Reduced {
    let materials = MaterialTable::from_mesh(&loaded.mesh, &input.material_overrides)?;
    let spec = inputs.spec(name, input, loaded.info.clone());
    let (mut part, reduce) = reduce_part_coupled(
        &loaded.mesh,
        &materials,
        &spec,
        &input.couplings,
        opts,
        progress,
    )?;
    part.info.build = Some(inputs.record(input));
    let report = PartReport {
        name: name.into(),
        mesh: loaded.info,
        warnings: loaded.warnings,
        read_time: loaded.read_time,
        reduce,
        reused: false,
    };
    Ok((part, report))
}
