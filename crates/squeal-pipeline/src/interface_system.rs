//! `[reduction] interface = "system"`: each part's contact-face motion restricted to that of
//! the assembled brake's real modes at the frictionless static equilibrium, of their friction
//! residual vectors and of the static equilibrium and its derivative in μ (the vectors and
//! their maths: `squeal_brake::interface_system`; the face basis:
//! `squeal_reduce::interface_modes::face_basis`; the projection, contact forces still
//! evaluated at every pair: `squeal_brake::interface_reduced`).
//!
//! **Why not the CC modes.** Measured on the coarse nodal brake (docs/reduction.md): the
//! characteristic constraint modes of each face, free, loaded by the contact springs or of
//! the assembled boundary, converge slowly (largest in-band frequency error 5e-3 with 320 of
//! 1065 per part, μ0 off by 5e-3 with 160); the face motion of the brake's own in-band modes
//! spans what they need exactly (frequencies to 2e-7, μ0 to 2e-4 with 61 modes).
//!
//! **How many.** `interface_modes = n`: the `n` lowest real modes, with the friction residual
//! vectors of those in the band. `"auto"`: the in-band modes alone, then with their friction
//! residual vectors, then the modes up to 2, 4, … times the band's top with those residuals,
//! keeping the first whose in-band eigenvalues at the sweep's first, middle and last friction
//! value moved by less than `interface_tolerance` (default 5e-3, relative) from the level
//! before (`crate::interface_check`: no sweep per level). Under `"auto"` only the modes a
//! level uses are computed, when it is built: those in the band first, those below 2, 4, …
//! times its top for the later levels (`squeal_brake::interface_system::system_vectors_to`:
//! a partial eigensolve where its flop estimate says it is cheaper, else all of them); a
//! fixed count takes the whole decomposition.

use crate::error::Result;
use crate::interface::{Candidate, Head, at_count, face_parts, fixed};
use crate::model::{Log, Model};
use squeal_brake::interface_system::{SystemVectors, system_vectors, system_vectors_to};
use squeal_reduce::interface_modes::{InterfaceModes, face_basis_keeping, face_dofs};
use squeal_scene::Scene;
use squeal_scene::reduction::InterfaceModeCount;
use std::time::Instant;

/// The model with a `"system"` interface reduction.
pub fn apply(scene: &Scene, model: &Model, log: Log, count: InterfaceModeCount) -> Result<Model> {
    let t = Instant::now();
    let top = band_top(model);
    let tau = std::f64::consts::TAU;
    let below = |v: &SystemVectors, f: f64| v.modes.omega.iter().filter(|w| **w / tau <= f).count();
    let (brake, newton) = (&model.brake, &model.sweep.newton);
    // A fixed count may ask for modes above the band: the whole decomposition. "auto" starts
    // with the modes in the band (a partial solve where cheaper) and asks for more level by
    // level.
    let vectors = match count {
        InterfaceModeCount::Fixed(_) => system_vectors(brake, newton, top)?,
        InterfaceModeCount::Auto { .. } => system_vectors_to(brake, newton, top, top)?,
    };
    let in_band = vectors.residuals.ncols();
    let how = if vectors.complete() {
        "all"
    } else {
        "partial eigensolve:"
    };
    log(&format!(
        "interface reduction: {how} {} real modes of the brake ({in_band} below {top:.0} Hz) with their friction residual and static vectors in {:.1} s",
        vectors.modes.omega.len(),
        t.elapsed().as_secs_f64()
    ));
    let face_dofs = face_parts(&model.rom)
        .map(|p| (p.info.name.clone(), face_dofs(p).len()))
        .collect();
    let head = Head {
        method: "the face motion of the assembled brake's real modes at the frictionless equilibrium, their friction residual vectors and the static equilibrium with its derivative in mu".into(),
        face_dofs,
    };
    let total = vectors.modes.omega.len();
    let candidate = |v: &SystemVectors, modes: usize, residuals: usize| -> Result<Candidate> {
        let bases = face_bases(model, v, modes, residuals)?;
        Ok(Candidate {
            model: at_count(model, &bases, usize::MAX)?,
            kept: bases.iter().map(InterfaceModes::count).collect(),
            basis: format!(
                "{modes} brake modes + {residuals} friction residuals + 2 static vectors"
            ),
        })
    };
    match count {
        InterfaceModeCount::Fixed(n) => {
            let n = n.min(total);
            let reason = format!("interface_modes = {n} in {}", scene.path.display());
            fixed(model, head, candidate(&vectors, n, n.min(in_band))?, reason)
        }
        InterfaceModeCount::Auto { tolerance } => {
            // (modes, residuals): the band alone, with residuals, then 2, 4, ... times its top
            // (the modes for those computed when a level asks for them).
            let mut step = 0usize;
            let mut factor = 1.0;
            let mut previous = in_band;
            let mut finished = vectors.complete() && in_band >= total;
            let levels = std::iter::from_fn(|| -> Option<Result<Candidate>> {
                step += 1;
                match step {
                    1 => return Some(candidate(&vectors, in_band, 0)),
                    2 => return Some(candidate(&vectors, in_band, in_band)),
                    _ => {}
                }
                while !finished {
                    factor *= 2.0;
                    let fresh;
                    let source = if vectors.complete() {
                        &vectors
                    } else {
                        match system_vectors_to(brake, newton, top, factor * top) {
                            Ok(v) => fresh = v,
                            Err(e) => return Some(Err(e.into())),
                        }
                        &fresh
                    };
                    let modes = below(source, factor * top).max(in_band);
                    finished = source.complete() && modes >= source.modes.omega.len();
                    if modes > previous {
                        previous = modes;
                        return Some(candidate(source, modes, in_band));
                    }
                }
                None
            });
            let what = format!(
                "the {in_band} in-band brake modes, then with their friction residuals, then the modes below 2, 4, ... x {top:.0} Hz"
            );
            let mus = scene.mu_values()?;
            crate::interface_check::auto(model, &mus, log, head, levels, tolerance, &what)
        }
    }
}

/// The band's top (Hz): the scene's band's upper end, or the valid band's when lower.
fn band_top(model: &Model) -> f64 {
    let b = model.sweep.band;
    b.user
        .map_or(b.valid_max_hz, |(_, hi)| hi.min(b.valid_max_hz))
}

/// The first dof of face part `name` (the disc, or a pad by its name) in the reduced
/// brake's layout.
pub(crate) fn part_start(model: &Model, name: &str) -> Result<usize> {
    if name == "disc" {
        return Ok(model.layout.disc.start);
    }
    model
        .layout
        .pads
        .iter()
        .find(|p| p.0 == name)
        .map(|p| p.1.start)
        .ok_or(crate::error::PipelineError::NoPart { part: "pad" })
}

/// Each part's face basis: the face rows of the system vectors, M̂_cc-orthonormalized (the
/// disc's and the pads', [`face_parts`]: the further parts keep their dofs).
pub fn face_bases(
    model: &Model,
    vectors: &SystemVectors,
    modes: usize,
    residuals: usize,
) -> Result<Vec<InterfaceModes>> {
    let columns = vectors.columns(modes, residuals);
    face_parts(&model.rom)
        .map(|part| {
            let start = part_start(model, &part.info.name)?;
            let rows = face_dofs(part);
            let v = faer::Mat::from_fn(rows.len(), columns.ncols(), |i, j| {
                columns[(start + rows[i], j)]
            });
            // The static vectors (the last two columns) exactly: the reduced brake's
            // equilibrium is then the unreduced one (`face_basis_keeping`).
            Ok(face_basis_keeping(part, &v, 2)?)
        })
        .collect()
}
