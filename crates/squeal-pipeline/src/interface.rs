//! `[reduction] interface = "cc"`: the brake on each part's characteristic constraint (CC)
//! modes instead of its contact face's nodal dofs (`"system"`, the face motion of the brake's
//! own modes, is in `crate::interface_system` and shares [`auto`] and [`at_count`] from here) (the maths and the choice of basis:
//! `squeal_reduce::interface_modes`; the brake's projection, contact forces still evaluated at
//! every pair: `squeal_brake::interface_reduced`).
//!
//! **How many modes.** `interface_modes = n` keeps the `n` lowest CC modes of each part (all
//! of them if it has fewer). `"auto"` chooses by convergence of what the analysis reports:
//! starting from [`FIRST_LEVEL`] modes per part and doubling, it runs the scene's stability
//! sweep at each count and keeps the first count `k_i` at which the frictionless frequencies
//! in the band, μ0 and its frequency all moved by less than `interface_tolerance` (relative)
//! from `k_{i-1}` (no Hopf point at two counts does not count as settled: too few modes
//! stiffen the interface and can push the onset out of the swept range), or every CC mode (the
//! unreduced-interface model in other coordinates) when no count before settles. Each count's
//! μ0, frequency, size and time are kept in [`InterfaceSummary`] and written by `squeal
//! stability` (its text and `summary.json`), so the choice can be checked.
//!
//! **Further parts.** A scene's `[parts.<name>]` (a caliper, a bracket) have no contact face:
//! their dofs (after their ties' slaves are eliminated) are kept whole, and the connectors'
//! springs and the ties reach the disc and the pads through coordinates that every basis here
//! keeps as they are (coupling points, tie nodes), so only the disc's and the pads' contact
//! faces are reduced ([`face_parts`], `squeal_brake::interface_reduced`).

use crate::error::{PipelineError, Result};
use crate::model::{Log, Model};
use squeal_brake::interface_reduced::project_brake;
use squeal_brake::sweep::{PROJECT_ABOVE, SweepMethod};
use squeal_reduce::interface_modes::{
    InterfaceModes, characteristic_constraint_modes_loaded, transformed_part,
};
use squeal_reduce::rom::{PartRole, ReducedModel, ReducedPart};
use squeal_scene::Scene;
use squeal_scene::reduction::{InterfaceBasis, InterfaceModeCount};
use std::fmt::Write as _;
use std::time::Instant;

/// The CC modes per part of `"auto"`'s first count; doubled until converged.
pub const FIRST_LEVEL: usize = 10;

/// One count of CC modes and what the brake gave with it.
#[derive(Clone, Debug)]
pub struct InterfaceLevel {
    /// Face vectors kept per part (disc, then the pads).
    pub kept: Vec<usize>,
    /// What the basis held at this level, in words.
    pub basis: String,
    /// The brake's reduced size.
    pub dofs: usize,
    /// μ0 and its frequency (Hz), when the sweep found a Hopf point (`"auto"` only).
    pub hopf: Option<(f64, f64)>,
    /// Whether the stability sweep ran at this count.
    pub swept: bool,
    /// `"system"`'s `"auto"`: the largest relative change of an in-band eigenvalue from the
    /// level before at the checked friction values (`crate::interface_check`); `None` for the
    /// first level and for the other choices.
    pub change: Option<f64>,
    /// Seconds to build this count's brake and sweep it.
    pub seconds: f64,
}

/// What the interface reduction kept, and why.
#[derive(Clone, Debug)]
pub struct InterfaceSummary {
    /// The basis, in words.
    pub method: String,
    /// The parts' names and their contact-face dofs before the reduction.
    pub face_dofs: Vec<(String, usize)>,
    /// The brake's size before the reduction.
    pub dofs_before: usize,
    /// `Some(tolerance)` for `"auto"`.
    pub tolerance: Option<f64>,
    /// Every count tried, ascending.
    pub levels: Vec<InterfaceLevel>,
    /// The count kept (index into `levels`).
    pub chosen: usize,
    /// Why that count.
    pub reason: String,
    /// The friction values the levels' eigenvalues were compared at (`"system"`'s `"auto"`;
    /// empty when the levels were swept or the count was fixed).
    pub checked_mus: Vec<f64>,
}

impl InterfaceSummary {
    /// The count kept.
    pub fn chosen(&self) -> &InterfaceLevel {
        &self.levels[self.chosen]
    }

    /// The lines `squeal stability` prints.
    pub fn text(&self) -> String {
        let mut out = String::new();
        let parts: Vec<String> = self
            .face_dofs
            .iter()
            .zip(&self.chosen().kept)
            .map(|((n, d), k)| format!("{n} {k} of {d}"))
            .collect();
        let _ = writeln!(
            out,
            "interface reduction: {} ({}; {}); {} dofs instead of {}: {}",
            self.method,
            self.chosen().basis,
            parts.join(", "),
            self.chosen().dofs,
            self.dofs_before,
            self.reason
        );
        if !self.checked_mus.is_empty() {
            let _ = writeln!(
                out,
                "  basis | face vectors per part | dofs | change of the in-band eigenvalues | s"
            );
            for l in &self.levels {
                let _ = writeln!(
                    out,
                    "  {} | {} | {} | {} | {:.1}",
                    l.basis,
                    joined(&l.kept),
                    l.dofs,
                    l.change.map_or("-".into(), |d| format!("{d:.2e}")),
                    l.seconds
                );
            }
        }
        if self.levels.iter().any(|l| l.swept) {
            let _ = writeln!(
                out,
                "  basis | face vectors per part | dofs | mu0 | frequency (Hz) | s"
            );
            for l in &self.levels {
                let (mu, f) = l.hopf.map_or(("-".into(), "-".into()), |(m, f)| {
                    (format!("{m:.6}"), format!("{f:.2}"))
                });
                let _ = writeln!(
                    out,
                    "  {} | {} | {} | {mu} | {f} | {:.1}",
                    l.basis,
                    l.kept
                        .iter()
                        .map(usize::to_string)
                        .collect::<Vec<_>>()
                        .join("+"),
                    l.dofs,
                    l.seconds
                );
            }
        }
        out
    }

    /// Its record in `summary.json`.
    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({
            "method": self.method,
            "contact_face_dofs": self.face_dofs.iter().map(|(n, d)| serde_json::json!({"part": n, "dofs": d})).collect::<Vec<_>>(),
            "dofs_before": self.dofs_before,
            "dofs": self.chosen().dofs,
            "kept_per_part": self.chosen().kept,
            "tolerance": self.tolerance,
            "reason": self.reason,
            "checked_mus": self.checked_mus,
            "levels": self.levels.iter().map(|l| serde_json::json!({
                "kept_per_part": l.kept,
                "basis": l.basis,
                "dofs": l.dofs,
                "mu0": l.hopf.map(|h| h.0),
                "frequency_hz": l.hopf.map(|h| h.1),
                "swept": l.swept,
                "eigenvalue_change": l.change,
                "seconds": l.seconds,
            })).collect::<Vec<_>>(),
        })
    }
}

/// `1+2+3`.
fn joined(kept: &[usize]) -> String {
    kept.iter()
        .map(usize::to_string)
        .collect::<Vec<_>>()
        .join("+")
}

/// One candidate of an interface reduction: the model, the face vectors kept per part and
/// what they are.
pub struct Candidate {
    /// The reduced model.
    pub model: Model,
    /// Face vectors kept per part (disc, then the pads).
    pub kept: Vec<usize>,
    /// What the basis holds, in words.
    pub basis: String,
}

/// The model with the scene's interface reduction applied (the model itself without one).
pub fn apply(scene: &Scene, model: Model, log: Log) -> Result<Model> {
    Ok(apply_to(scene, &model, log)?.unwrap_or(model))
}

/// The interface-reduced model of `model` the scene asks for, `None` when it asks for none.
pub fn apply_to(scene: &Scene, model: &Model, log: Log) -> Result<Option<Model>> {
    let Some(choice) = scene.interface_reduction()? else {
        return Ok(None);
    };
    if choice.basis == InterfaceBasis::System {
        return crate::interface_system::apply(scene, model, log, choice.modes).map(Some);
    }
    reduced_by_cc_modes(scene, model, log, choice.modes).map(Some)
}

/// The model reduced on its faces' characteristic constraint modes.
fn reduced_by_cc_modes(
    scene: &Scene,
    model: &Model,
    log: Log,
    count: InterfaceModeCount,
) -> Result<Model> {
    let t = Instant::now();
    let modes = loaded_modes(model)?;
    log(&format!(
        "interface reduction: CC modes of {} in {:.1} s",
        modes
            .iter()
            .map(|m| format!("{} ({} face dofs)", m.part, m.count()))
            .collect::<Vec<_>>()
            .join(", "),
        t.elapsed().as_secs_f64()
    ));
    let most = modes.iter().map(InterfaceModes::count).max().unwrap_or(0);
    let face_dofs = modes.iter().map(|m| (m.part.clone(), m.count())).collect();
    let head = Head {
        method: "characteristic constraint modes of each part's contact face (Castanier, Tan & Pierre 2001)".into(),
        face_dofs,
    };
    let candidate = |k: usize| -> Result<Candidate> {
        Ok(Candidate {
            model: at_count(model, &modes, k)?,
            kept: kept(&modes, k),
            basis: format!("{k} CC modes per part"),
        })
    };
    match count {
        InterfaceModeCount::Fixed(k) => {
            let reason = format!("interface_modes = {k} in {}", scene.path.display());
            fixed(model, head, candidate(k)?, reason)
        }
        InterfaceModeCount::Auto { tolerance } => {
            let levels = std::iter::successors(Some(FIRST_LEVEL.min(most)), |&k| {
                (k < most).then(|| (2 * k).min(most))
            })
            .map(candidate);
            let what = format!("{FIRST_LEVEL}, {}, ... CC modes per part", 2 * FIRST_LEVEL);
            auto(scene, model, log, head, levels, tolerance, &what)
        }
    }
}

/// The parts of a summary known before any level: the method and the faces' sizes.
pub struct Head {
    /// The basis, in words (with its reference).
    pub method: String,
    /// Each part's name and contact-face dofs.
    pub face_dofs: Vec<(String, usize)>,
}

impl Head {
    /// The summary of a choice among `levels` (tried in order, the last one kept).
    pub fn summary(
        &self,
        dofs_before: usize,
        tolerance: Option<f64>,
        levels: Vec<InterfaceLevel>,
        reason: String,
        checked_mus: Vec<f64>,
    ) -> InterfaceSummary {
        InterfaceSummary {
            method: self.method.clone(),
            face_dofs: self.face_dofs.clone(),
            dofs_before,
            tolerance,
            chosen: levels.len().saturating_sub(1),
            levels,
            reason,
            checked_mus,
        }
    }
}

/// A fixed count: the candidate, not swept.
pub fn fixed(model: &Model, head: Head, c: Candidate, reason: String) -> Result<Model> {
    let t = Instant::now();
    let level = InterfaceLevel {
        kept: c.kept,
        basis: c.basis,
        dofs: c.model.brake.size(),
        hopf: None,
        swept: false,
        change: None,
        seconds: t.elapsed().as_secs_f64(),
    };
    let mut m = c.model;
    m.interface = Some(head.summary(model.brake.size(), None, vec![level], reason, Vec::new()));
    Ok(m)
}

/// `"auto"`: sweeps each candidate of `levels` in turn (ascending) and keeps the first whose
/// frictionless in-band frequencies, μ0 and μ0's frequency moved by less than `tolerance`
/// from the one before, or the last.
pub fn auto(
    scene: &Scene,
    model: &Model,
    log: Log,
    head: Head,
    levels: impl Iterator<Item = Result<Candidate>>,
    tolerance: f64,
    what: &str,
) -> Result<Model> {
    let mus = scene.mu_values()?;
    let mut done: Vec<InterfaceLevel> = Vec::new();
    let mut previous: Option<Vec<f64>> = None;
    let mut last: Option<Model> = None;
    let finish = |m: Model, done: Vec<InterfaceLevel>, reason: String| {
        let mut m = m;
        m.interface = Some(head.summary(
            model.brake.size(),
            Some(tolerance),
            done,
            reason,
            Vec::new(),
        ));
        m
    };
    for c in levels {
        let t = Instant::now();
        let c = c?;
        let m = c.model;
        let st = crate::stability::analyse(&m, &mus)?;
        let hopf = st.sweep.hopf.as_ref().map(|h| (h.mu0, h.frequency_hz));
        let tau = std::f64::consts::TAU;
        let frictionless: Vec<f64> = st
            .reference
            .basis
            .omega
            .iter()
            .map(|w| w / tau)
            .filter(|&f| m.sweep.band.contains(f))
            .collect();
        let level = InterfaceLevel {
            kept: c.kept,
            basis: c.basis,
            dofs: m.brake.size(),
            hopf,
            swept: true,
            change: None,
            seconds: t.elapsed().as_secs_f64(),
        };
        log(&format!(
            "  {}, {} dofs: {} ({:.1} s)",
            level.basis,
            level.dofs,
            hopf.map_or("no Hopf point".into(), |(mu, f)| format!(
                "mu0 = {mu:.6} at {f:.2} Hz"
            )),
            level.seconds
        ));
        let settled = previous
            .as_ref()
            .filter(|prev| same_frequencies(prev, &frictionless, tolerance))
            .and(done.last())
            .and_then(|prev| agree(prev.hopf, hopf, tolerance));
        previous = Some(frictionless);
        done.push(level);
        if let Some(why) = settled {
            let reason = format!(
                "the first of {what} at which the frictionless frequencies in the band and the Hopf point settled: {why} from the one before (tolerance {tolerance:e}, [reduction] interface_tolerance)"
            );
            return Ok(finish(m, done, reason));
        }
        last = Some(m);
    }
    let m = last.ok_or(PipelineError::NoPart { part: "disc" })?;
    let reason = format!(
        "none of {what} settled to {tolerance:e} before the last: the last kept (the most the basis offers)"
    );
    Ok(finish(m, done, reason))
}

/// The parts whose contact face an interface reduction reduces: the disc and the pads, in the
/// rom's order (the further parts, `[parts.<name>]`, have none and are kept whole).
pub fn face_parts(rom: &ReducedModel) -> impl Iterator<Item = &ReducedPart> {
    rom.parts.iter().filter(|p| p.info.role() != PartRole::Body)
}

/// Each part's CC modes with the contact springs' tangent stiffness at the frictionless
/// static equilibrium on its face (the other part held), in the rom's part order (the disc and
/// the pads: [`face_parts`]).
pub fn loaded_modes(model: &Model) -> Result<Vec<InterfaceModes>> {
    let eq = squeal_brake::equilibrium::static_equilibrium(
        &model.brake,
        0.0,
        None,
        &model.sweep.newton,
    )?;
    let (ks, _) = model.brake.nonlinear_jacobian(&eq.x, 0.0, false);
    let ranges: Vec<(&str, std::ops::Range<usize>)> =
        std::iter::once(("disc", model.layout.disc.clone()))
            .chain(
                model
                    .layout
                    .pads
                    .iter()
                    .map(|p| (p.0.as_str(), p.1.clone())),
            )
            .collect();
    face_parts(&model.rom)
        .map(|part| {
            let r = ranges
                .iter()
                .find(|(n, _)| *n == part.info.name)
                .map(|x| x.1.clone())
                .ok_or(PipelineError::NoPart { part: "pad" })?;
            let block = faer::Mat::from_fn(r.len(), r.len(), |i, j| ks[(r.start + i, r.start + j)]);
            Ok(characteristic_constraint_modes_loaded(part, Some(&block))?)
        })
        .collect()
}

/// Why two counts' Hopf points agree to `tol` (relative, in μ0 and in frequency), or `None`.
fn agree(a: Option<(f64, f64)>, b: Option<(f64, f64)>, tol: f64) -> Option<String> {
    match (a, b) {
        // No Hopf point at two counts is no evidence: a stiff interface (too few modes) can
        // push the onset out of the swept range.
        (None, None) => None,
        (Some((m0, f0)), Some((m1, f1))) => {
            let (dm, df) = ((m1 - m0).abs() / m1.abs(), (f1 - f0).abs() / f1.abs());
            (dm <= tol && df <= tol)
                .then(|| format!("mu0 moved by {dm:.1e} and its frequency by {df:.1e} (relative)"))
        }
        _ => None,
    }
}

/// Whether two counts' frictionless frequencies in the band agree: as many, each within
/// `tol` (relative).
fn same_frequencies(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol * y.abs())
}

/// The CC modes each part keeps at count `k`.
fn kept(modes: &[InterfaceModes], k: usize) -> Vec<usize> {
    modes.iter().map(|m| k.min(m.count())).collect()
}

/// The model on `k` CC modes per part: its brake projected, its reduced parts (their matrices
/// and bases, for the shapes on the meshes) in the same coordinates.
pub fn at_count(model: &Model, modes: &[InterfaceModes], k: usize) -> Result<Model> {
    let blocks: Vec<(String, faer::Mat<f64>)> = modes
        .iter()
        .map(|m| (m.part.clone(), m.transformation(k)))
        .collect();
    at_blocks(model, &blocks)
}

/// The model in the coordinates `q_I = T_I q'_I` of each part, `blocks` holding each part's
/// name and `T_I` (rows: the part's reduced dofs): its brake projected, its reduced parts
/// (their matrices and bases, for the shapes on the meshes) in the same coordinates.
pub fn at_blocks(model: &Model, blocks: &[(String, faer::Mat<f64>)]) -> Result<Model> {
    // The brake's parts in the layout's order, each with its block.
    let order: Vec<&str> = std::iter::once("disc")
        .chain(model.layout.pads.iter().map(|p| p.0.as_str()))
        .collect();
    let ordered = order
        .iter()
        .map(|name| {
            blocks
                .iter()
                .find(|b| b.0 == *name)
                .map(|b| b.1.clone())
                .ok_or(PipelineError::NoPart { part: "pad" })
        })
        .collect::<Result<Vec<_>>>()?;
    let (brake, layout) = project_brake(&model.brake, &model.layout, &ordered)?;
    // The sweep's continuation borders `T(λ)` with one column per pair (258 on the coarse
    // nodal brake), whatever the size: each of its `2n` eigenpairs then costs a complex LU
    // of about the pair count per friction value, so on a brake with more than a quarter as
    // many pairs as dofs a dense eigen-decomposition per friction value is cheaper
    // (`SweepMethod::Dense`; above `PROJECT_ABOVE` dofs `Auto` projects, as for any brake).
    // Measured on the coarse nodal one-pad brake's 264-dof system level with 258 pairs
    // (`squeal stability` of its scene, one slot): continuation 16.7 s per friction value,
    // the dense sweep's 201 values 81.6 s in all (its first value's set-up included).
    let mut sweep = model.sweep;
    if sweep.method == SweepMethod::Auto
        && 4 * brake.pairs.len() > brake.size()
        && brake.size() <= PROJECT_ABOVE
    {
        sweep.method = SweepMethod::Dense;
    }
    // Each part's `Φ T` from the model's own part, not from a clone of the whole model: a
    // nodal disc's basis `Φ` is gigabytes (docs/benchmarks.md, the Craig–Bampton step with
    // thousands of boundary points). A further part is kept as it is (`T = I`).
    let parts = model
        .rom
        .parts
        .iter()
        .map(|part| {
            if part.info.role() == PartRole::Body {
                return Ok(part.clone());
            }
            let block = blocks
                .iter()
                .find(|b| b.0 == part.info.name)
                .ok_or(PipelineError::NoPart { part: "pad" })?;
            Ok(transformed_part(part, &block.1))
        })
        .collect::<Result<Vec<_>>>()?;
    let rom = squeal_reduce::rom::ReducedModel {
        tool_version: model.rom.tool_version.clone(),
        parts,
        connections: model.rom.connections.clone(),
        ties: model.rom.ties.clone(),
    };
    Ok(Model {
        rom,
        rom_path: model.rom_path.clone(),
        brake,
        layout,
        pairs: model.pairs.clone(),
        params: model.params.clone(),
        damping: model.damping,
        damping_from: model.damping_from.clone(),
        sweep,
        disc_mesh: model.disc_mesh.clone(),
        pad_meshes: model.pad_meshes.clone(),
        disc: model.disc,
        units: model.units,
        interface: None,
        normal_forms: Default::default(),
    })
}
