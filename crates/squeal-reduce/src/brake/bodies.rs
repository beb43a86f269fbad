//! The brake's further parts (bodies: a caliper, a bracket) and the connections between
//! parts: their checks before any reduction, the rigid motions their restraints and coupling
//! sets leave free, and the connections resolved to the reduced parts' coupling points
//! ([`crate::coupling`]).

use super::*;
use crate::coupling::{Connection, ConnectionInput, CouplingSet, End};
use crate::craig_bampton::{
    FreeDofs, boundary_rows, coupling_rows, piston_frames, skew_restraints,
};
use squeal_fe::DofMap;
use squeal_fe::frames::{DofTransform, HeldNodes};

/// Checks the bodies' names and the connections' ends: each end's part exists and keeps the
/// set as a coupling set, and a connection that carries the clamp force starts at a pad's
/// load set.
pub(super) fn validate_bodies(inputs: &BrakeInputs) -> Result<(), ReduceError> {
    let bad = |what: String| Err(ReduceError::Options(what));
    for (i, b) in inputs.bodies.iter().enumerate() {
        if b.name.is_empty() || b.name == "disc" || inputs.pads.iter().any(|p| p.name == b.name) {
            return bad(format!(
                "a part cannot be named '{}' (the disc and the pads have that name)",
                b.name
            ));
        }
        if inputs.bodies[..i].iter().any(|q| q.name == b.name) {
            return bad(format!("two parts are named '{}'", b.name));
        }
    }
    let parts = inputs.parts();
    let coupling = |end: &(String, String), what: &str| -> Result<bool, ReduceError> {
        let Some((_, input)) = parts.iter().find(|p| p.0 == end.0) else {
            return Err(ReduceError::Options(format!(
                "connection {what}: '{}' is not a part (the parts: {})",
                end.0,
                parts.iter().map(|p| p.0).collect::<Vec<_>>().join(", ")
            )));
        };
        match input.couplings.iter().find(|c| c.set == end.1 && !c.nodal) {
            Some(c) => Ok(c.load),
            None => Err(ReduceError::Options(format!(
                "connection {what}: part '{}' keeps no coupling set {}",
                end.0, end.1
            ))),
        }
    };
    for c in &inputs.connections {
        let load = coupling(&c.a, &c.name)?;
        if let Some(b) = &c.b {
            if b.0 == c.a.0 {
                return bad(format!(
                    "connection {}: both ends are on part '{}' (a spring inside a part is a [[springs]] entry)",
                    c.name, b.0
                ));
            }
            coupling(b, &c.name)?;
        }
        if c.load && !load {
            return bad(format!(
                "connection {}: it carries the clamp force, so its first end must be a pad's load set",
                c.name
            ));
        }
        let k = c.stiffness.iter().chain(&c.rotational);
        if k.clone().any(|x| !(x.is_finite() && *x >= 0.0)) || k.clone().all(|x| *x == 0.0) {
            return bad(format!(
                "connection {}: stiffnesses must be finite and >= 0, not all zero",
                c.name
            ));
        }
    }
    Ok(())
}

/// A body's coupling sets exist, are not empty and name no node the file lacks.
pub(super) fn check_body_sets(mesh: &Mesh, input: &PartInput) -> Result<(), ReduceError> {
    for c in &input.couplings {
        let nodes = mesh
            .node_set(&c.set)
            .ok_or_else(|| InterfaceError::MissingSet(c.set.clone()))?;
        if nodes.is_empty() {
            return Err(InterfaceError::EmptySet(c.set.clone()).into());
        }
        refuse_shortened_set(mesh, &c.set)?;
    }
    Ok(())
}

/// [`crate::held::require_held`] with the part's coupling sets counted among its boundary
/// rows: six mean-motion rows per set, which hold every rigid motion of a part that its
/// coupling sets alone hold (a floating caliper).
pub fn require_held_coupled(
    mesh: &Mesh,
    spec: &PartSpec,
    couplings: &[CouplingSet],
) -> Result<(), ReduceError> {
    let motions = free_motions_coupled(mesh, spec, couplings)?;
    match motions.is_empty() {
        true => Ok(()),
        false => Err(crate::held::not_held(spec, &motions)),
    }
}

/// [`crate::held::free_motions`] with the part's coupling sets' six rows each counted.
pub fn free_motions_coupled(
    mesh: &Mesh,
    spec: &PartSpec,
    couplings: &[CouplingSet],
) -> Result<Vec<crate::held::FreeMotion>, ReduceError> {
    let mut held = HeldNodes::new(mesh, &spec.restraints, &skew_restraints(mesh, spec)?)?;
    piston_frames(mesh, spec, &mut held)?;
    let dofmap = DofMap::new(mesh, &held.restraints)?;
    let free = FreeDofs {
        dofmap: &dofmap,
        transform: held.has_frames().then(|| DofTransform::new(&dofmap, &held)),
    };
    let (mut points, mut rows) = boundary_rows(mesh, &free, spec)?;
    coupling_rows(mesh, &free, spec, couplings, &mut points, &mut rows)?;
    let springs = crate::tie::support_springs(mesh, &spec.supports)?;
    let terms = crate::springs::spring_terms(mesh, &spec.springs)?;
    Ok(crate::held::free_motions_of(
        mesh, &free, &held, &rows, &springs, &terms,
    ))
}

/// The connections of `inputs` on the reduced parts: each end's coupling point (the part's
/// mean-motion coupling points are its last points, in the order of its coupling sets).
pub fn resolve_connections(
    inputs: &BrakeInputs,
    parts: &[ReducedPart],
) -> Result<Vec<Connection>, ReduceError> {
    let all = inputs.parts();
    let end = |(part, set): &(String, String)| -> Result<End, ReduceError> {
        let missing = || ReduceError::Invalid {
            part: part.clone(),
            what: format!("no coupling point for set {set}"),
        };
        let input = all.iter().find(|p| p.0 == part).ok_or_else(missing)?.1;
        // The tie sets' nodes (`nodal`) are kept before the mean-motion points.
        let mean: Vec<&CouplingSet> = input.couplings.iter().filter(|c| !c.nodal).collect();
        let k = mean
            .iter()
            .position(|c| c.set == *set)
            .ok_or_else(missing)?;
        let reduced = parts
            .iter()
            .find(|p| p.info.name == *part)
            .ok_or_else(missing)?;
        let first = reduced
            .info
            .points
            .len()
            .checked_sub(mean.len())
            .ok_or_else(missing)?;
        Ok(End {
            part: part.clone(),
            set: set.clone(),
            point: first + k,
        })
    };
    inputs
        .connections
        .iter()
        .map(|c| {
            Ok(Connection {
                name: c.name.clone(),
                a: end(&c.a)?,
                b: c.b.as_ref().map(end).transpose()?,
                stiffness: c.stiffness,
                rotational: c.rotational,
                axes: c.axes,
                load: c.load,
                vibration_only: c.vibration_only,
            })
        })
        .collect()
}

/// Why the connections stored in a `.rom` are not those of `inputs` (empty when they are).
pub fn connection_reasons(stored: &[Connection], inputs: &BrakeInputs) -> Vec<String> {
    let same = |s: &Connection, c: &ConnectionInput| {
        s.name == c.name
            && (s.a.part.as_str(), s.a.set.as_str()) == (c.a.0.as_str(), c.a.1.as_str())
            && s.b.as_ref().map(|b| (b.part.as_str(), b.set.as_str()))
                == c.b.as_ref().map(|b| (b.0.as_str(), b.1.as_str()))
            && s.stiffness == c.stiffness
            && s.rotational == c.rotational
            && s.axes == c.axes
            && s.load == c.load
            && s.vibration_only == c.vibration_only
    };
    let ok = stored.len() == inputs.connections.len()
        && stored
            .iter()
            .zip(&inputs.connections)
            .all(|(s, c)| same(s, c));
    match ok {
        true => Vec::new(),
        false => vec![format!(
            "connections differ ({} in the file, {} asked for, or their ends or stiffnesses changed)",
            stored.len(),
            inputs.connections.len()
        )],
    }
}
