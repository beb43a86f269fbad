//! Which modes couple at μ0: the two frictionless modes of the pair and the unstable mode,
//! expanded on the meshes and summarized by the disc's circumferential orders on the braking
//! face's mid-radius circle, the out-of-plane share, the kinetic energy in the disc and the
//! pad's profile (moved from `study.rs` unchanged; the convergence study reuses [`rings`] and
//! [`summarize`]).

use super::record::CoupledModes;
use crate::error::{PipelineError, Result, json_text};
use crate::model::{Log, Model};
use crate::shapes::expand_complex;
use faer::c64;
use squeal_brake::analysis::LinearStability as Stability;
use squeal_brake::studies::{
    ShapeSummary, circumferential_orders, coupling, energy_share, pad_profile,
};
use squeal_mesh::Mesh;
use squeal_reduce::interface::Axis;
use squeal_reduce::rom::{ReducedModel, ReducedPart};
use std::path::Path;

/// The geometry the shape measures need: the braking-face circle of the disc and the pad's
/// line along its length, with each node's angle about the disc axis.
pub(super) struct Rings {
    axis: Axis,
    /// (node index, angle) on the disc's braking face at mid radius.
    disc: Vec<(usize, f64)>,
    /// (node index, arc length) on the pad's friction face at mid radius.
    pad: Vec<(usize, f64)>,
}

/// `v / |v|`, or the z axis when `v` has no length.
pub(super) fn unit(v: [f64; 3]) -> [f64; 3] {
    squeal_element::geometry::unit(v).unwrap_or([0.0, 0.0, 1.0])
}

pub(super) use squeal_element::geometry::dot;

/// Cylindrical coordinates (axial, radius, angle) about the axis; the angle is measured from
/// the global x axis projected on the disc plane (from +x towards +y for the z axis).
pub(super) fn cylindrical(axis: &Axis, p: [f64; 3]) -> (f64, f64, f64) {
    let e = unit(axis.direction);
    let x = [1.0, 0.0, 0.0];
    let ref_dir = if dot(x, e).abs() > 0.9 {
        [0.0, 1.0, 0.0]
    } else {
        x
    };
    let e1 = unit([
        ref_dir[0] - dot(ref_dir, e) * e[0],
        ref_dir[1] - dot(ref_dir, e) * e[1],
        ref_dir[2] - dot(ref_dir, e) * e[2],
    ]);
    let e2 = [
        e[1] * e1[2] - e[2] * e1[1],
        e[2] * e1[0] - e[0] * e1[2],
        e[0] * e1[1] - e[1] * e1[0],
    ];
    let d = [
        p[0] - axis.origin[0],
        p[1] - axis.origin[1],
        p[2] - axis.origin[2],
    ];
    let (a, u, v) = (dot(d, e), dot(d, e1), dot(d, e2));
    (a, u.hypot(v), v.atan2(u))
}

/// Nodes of `mesh` on the plane `axial` (to 1e-6 of the radius) within the narrowest radial
/// band around `r_mid` (1, 2, 4, 8, 15% of it) dense enough in angle, else the widest band:
/// on a full circle (`closed`) the largest angular gap must be under 7.5° (orders up to 12
/// resolved); on an arc (the pad) there must be 12 nodes at least and no gap over an eighth
/// of the arc. Angles come back increasing (an arc is unwrapped where it has its largest gap).
fn ring_nodes(
    mesh: &Mesh,
    axis: &Axis,
    axial: f64,
    r_mid: f64,
    candidates: &[usize],
    closed: bool,
) -> Vec<(usize, f64)> {
    let on_plane: Vec<(usize, f64, f64)> = candidates
        .iter()
        .map(|&i| (i, cylindrical(axis, mesh.nodes[i])))
        .filter(|(_, c)| (c.0 - axial).abs() <= 1e-6 * r_mid)
        .map(|(i, c)| (i, c.1, c.2))
        .collect();
    let mut best = Vec::new();
    for frac in [0.01, 0.02, 0.04, 0.08, 0.15] {
        let mut ring: Vec<(usize, f64)> = on_plane
            .iter()
            .filter(|(_, r, _)| (r - r_mid).abs() <= frac * r_mid)
            .map(|(i, _, t)| (*i, *t))
            .collect();
        ring.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        let dense = if closed {
            max_gap(&ring) < 7.5f64.to_radians()
        } else {
            ring = unwrap_arc(ring);
            let span = ring.last().map_or(0.0, |l| l.1) - ring.first().map_or(0.0, |f| f.1);
            ring.len() >= 12 && arc_gap(&ring) <= span / 8.0
        };
        best = ring;
        if dense {
            break;
        }
    }
    best
}

/// Largest gap between consecutive angles, around the full circle.
fn max_gap(ring: &[(usize, f64)]) -> f64 {
    if ring.len() < 2 {
        return std::f64::consts::TAU;
    }
    let mut g: f64 = ring[0].1 + std::f64::consts::TAU - ring[ring.len() - 1].1;
    for w in ring.windows(2) {
        g = g.max(w[1].1 - w[0].1);
    }
    g
}

/// Largest gap between consecutive angles of an arc (no wrap-around).
fn arc_gap(ring: &[(usize, f64)]) -> f64 {
    ring.windows(2).map(|w| w[1].1 - w[0].1).fold(0.0, f64::max)
}

/// An arc sorted by angle in (-π, π], restarted after its largest gap so that the angles
/// increase along it (an arc across ±π stays in one piece).
fn unwrap_arc(ring: Vec<(usize, f64)>) -> Vec<(usize, f64)> {
    let n = ring.len();
    if n < 2 {
        return ring;
    }
    let tau = std::f64::consts::TAU;
    let gap = |i: usize| {
        if i + 1 < n {
            ring[i + 1].1 - ring[i].1
        } else {
            ring[0].1 + tau - ring[n - 1].1
        }
    };
    let widest = (0..n)
        .max_by(|&a, &b| gap(a).total_cmp(&gap(b)))
        .unwrap_or(n - 1);
    let start = (widest + 1) % n;
    (0..n)
        .map(|k| {
            let (i, t) = ring[(start + k) % n];
            (i, if start + k >= n { t + tau } else { t })
        })
        .collect()
}

pub(super) fn face_set<'a>(part: &ReducedPart, mesh: &'a Mesh) -> Result<&'a [u32]> {
    let name = part
        .info
        .build
        .as_ref()
        .map_or("CONTACT_FACE", |b| b.contact_face_set.as_str());
    mesh.node_set(name).ok_or_else(|| {
        PipelineError::input(
            "mode shapes",
            format!("the {} mesh has no node set {name}", part.info.name),
        )
    })
}

pub(super) fn rings(rom: &ReducedModel, disc: &Mesh, pad: &Mesh) -> Result<Rings> {
    let dp = rom
        .part("disc")
        .ok_or(PipelineError::NoPart { part: "disc" })?;
    let pp = rom
        .pads()
        .first()
        .copied()
        .ok_or(PipelineError::NoPart { part: "pad" })?;
    let axis = dp
        .info
        .build
        .as_ref()
        .map_or_else(Axis::default, |b| b.axis);
    let face = face_set(dp, disc)?;
    if face.is_empty() {
        return Err(PipelineError::input(
            "mode shapes",
            "the disc's contact face set is empty",
        ));
    }
    let cyl: Vec<(f64, f64, f64)> = face
        .iter()
        .map(|&i| cylindrical(&axis, disc.nodes[i as usize]))
        .collect();
    let axial = cyl.iter().map(|c| c.0).sum::<f64>() / cyl.len() as f64;
    let r_lo = cyl.iter().map(|c| c.1).fold(f64::INFINITY, f64::min);
    let r_hi = cyl.iter().map(|c| c.1).fold(0.0, f64::max);
    let r_mid = 0.5 * (r_lo + r_hi);
    let all: Vec<usize> = (0..disc.num_nodes()).collect();
    let disc_ring = ring_nodes(disc, &axis, axial, r_mid, &all, true);
    let pad_face: Vec<usize> = face_set(pp, pad)?.iter().map(|&i| i as usize).collect();
    let pad_axial = pad_face
        .first()
        .map(|&i| cylindrical(&axis, pad.nodes[i]).0)
        .unwrap_or(axial);
    let pad_ring: Vec<(usize, f64)> = ring_nodes(pad, &axis, pad_axial, r_mid, &pad_face, false)
        .into_iter()
        .map(|(i, t)| (i, t * r_mid))
        .collect();
    if disc_ring.len() < 8 || pad_ring.len() < 3 {
        return Err(PipelineError::input(
            "mode shapes",
            format!(
                "too few nodes on the braking-face circle at r = {r_mid:.4} m ({} on the disc, {} on the pad)",
                disc_ring.len(),
                pad_ring.len()
            ),
        ));
    }
    Ok(Rings {
        axis,
        disc: disc_ring,
        pad: pad_ring,
    })
}

/// The shape measures of a brake mode `x` (reduced coordinates, disc then pad).
pub(super) fn summarize(
    s: &Model,
    meshes: (&Mesh, &Mesh),
    r: &Rings,
    x: &[c64],
    f_hz: f64,
) -> Result<ShapeSummary> {
    let dp = s
        .rom
        .part("disc")
        .ok_or(PipelineError::NoPart { part: "disc" })?;
    let pp = s
        .rom
        .pads()
        .first()
        .copied()
        .ok_or(PipelineError::NoPart { part: "pad" })?;
    let e = unit(r.axis.direction);
    let ud = expand_complex(dp, meshes.0, &s.disc_mesh, &x[s.layout.disc.clone()])?;
    let pad_path = s
        .pad_meshes
        .first()
        .map(|p| p.1.as_path())
        .unwrap_or(Path::new(""));
    let up = expand_complex(pp, meshes.1, pad_path, &x[s.layout.pad()])?;
    let axial = |u: &[c64], i: usize| u[3 * i] * e[0] + u[3 * i + 1] * e[1] + u[3 * i + 2] * e[2];
    let w: Vec<c64> = r.disc.iter().map(|&(i, _)| axial(&ud, i)).collect();
    let angles: Vec<f64> = r.disc.iter().map(|&(_, t)| t).collect();
    let orders = circumferential_orders(&angles, &w, 12)?;
    let total: f64 = r
        .disc
        .iter()
        .map(|&(i, _)| (0..3).map(|d| ud[3 * i + d].norm_sqr()).sum::<f64>())
        .sum();
    let out: f64 = w.iter().map(|v| v.norm_sqr()).sum();
    let wp: Vec<c64> = r.pad.iter().map(|&(i, _)| axial(&up, i)).collect();
    let sp: Vec<f64> = r.pad.iter().map(|&(_, s)| s).collect();
    Ok(ShapeSummary {
        frequency_hz: f_hz,
        disc_energy: energy_share(&s.brake.m, x, s.layout.disc.clone()),
        orders,
        out_of_plane: if total > 0.0 { out / total } else { 0.0 },
        pad: pad_profile(&sp, &wp)?,
    })
}

/// Which modes couple at μ0 (the text and JSON [`write_coupled_modes`] writes): the two
/// frictionless modes of the pair and the unstable mode at μ0, expanded on the meshes. `None`
/// when the sweep has no Hopf point or pair.
pub(super) fn coupled_modes(s: &Model, st: &Stability, log: Log) -> Result<Option<CoupledModes>> {
    let (Some(h), Some((m1, m2))) = (&st.sweep.hopf, st.pair) else {
        return Ok(None);
    };
    let disc = s.read_mesh(&s.disc_mesh, log)?;
    let pad = match s.pad_meshes.first() {
        Some((_, p)) => s.read_mesh(p, log)?,
        None => return Err(PipelineError::NoPart { part: "pad" }),
    };
    let r = rings(&s.rom, &disc, &pad)?;
    let basis = &st.reference.basis;
    let real = |m: usize| -> Vec<c64> {
        (0..basis.phi.nrows())
            .map(|i| c64::new(basis.phi[(i, m)], 0.0))
            .collect()
    };
    let hz = |m: usize| basis.omega[m] / (2.0 * std::f64::consts::PI);
    let mode1 = summarize(s, (&disc, &pad), &r, &real(m1), hz(m1))?;
    let mode2 = summarize(s, (&disc, &pad), &r, &real(m2), hz(m2))?;
    let unstable = summarize(
        s,
        (&disc, &pad),
        &r,
        &h.point.spectrum.shape(basis, h.index),
        h.frequency_hz,
    )?;
    let verdict = coupling(&mode1, &mode2);
    let text = format!(
        "Coupled modes at mu0 = {:.6} (shapes expanded on the meshes; disc: out-of-plane motion on the braking face's mid-radius circle, {} nodes, largest gap {:.1} deg; pad: {} friction-face nodes along its length):\n  Mode 1 (frictionless #{}, stays stable): {}\n  Mode 2 (frictionless #{}, goes unstable): {}\n  unstable mode at mu0: {}\n  => {}\n",
        h.mu0,
        r.disc.len(),
        max_gap(&r.disc).to_degrees(),
        r.pad.len(),
        m1 + 1,
        mode1.describe(),
        m2 + 1,
        mode2.describe(),
        unstable.describe(),
        verdict
    );
    let json = |name: &str, m: Option<usize>, v: &ShapeSummary| {
        serde_json::json!({
            "mode": name,
            "frictionless_mode_1based": m.map(|m| m + 1),
            "frequency_hz": v.frequency_hz,
            "nodal_diameters": v.nodal_diameters(),
            "order_shares": v.orders.shares,
            "out_of_plane_share": v.out_of_plane,
            "disc_kinetic_energy_share": v.disc_energy,
            "pad": v.pad_kind(),
            "pad_straight_line_share": v.pad.rigid_share,
            "pad_sign_changes": v.pad.sign_changes,
        })
    };
    let all = serde_json::json!({
        "mu0": h.mu0,
        "verdict": verdict,
        "modes": [json("Mode 1", Some(m1), &mode1), json("Mode 2", Some(m2), &mode2), json("unstable at mu0", None, &unstable)],
    });
    Ok(Some(CoupledModes {
        text,
        json: json_text(&all, "the coupled modes")?,
    }))
}

/// Prints and writes which modes couple at μ0 (`coupled_modes.txt`, `.json`).
pub(super) fn write_coupled_modes(m: &CoupledModes, dir: &Path, log: Log) -> Result<()> {
    log(&format!("\n{}", m.text));
    squeal_io::atomic_write_bytes(&dir.join("coupled_modes.txt"), m.text.as_bytes())?;
    squeal_io::atomic_write_bytes(&dir.join("coupled_modes.json"), m.json.as_bytes())?;
    Ok(())
}
