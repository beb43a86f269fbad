//! The reduced brake of eq (11) from a reduced model: disc and pad stacked, contact points
//! paired by position, per-pair contact stiffness, piston load.

use crate::error::BrakeError;
use crate::model::{Brake, ContactPair, SparseVec};
use faer::Mat;
use squeal_reduce::rom::{DofLabel, PointRole, ReducedModel, ReducedPart};

/// Contact stiffness: per contact point, or per unit area (then multiplied by each pair's
/// tributary area: the patch area for the patch interface).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stiffness {
    /// `k_l` (N/m) and `k_nl` (N/m³) of every pair.
    PerPoint { linear: f64, cubic: f64 },
    /// `κ_l` (Pa/m) and `κ_nl` (Pa/m³): `k = κ A` with `A` the pair's area; `point_area`
    /// is used where the model has no patch areas (node interface).
    PerArea {
        linear: f64,
        cubic: f64,
        point_area: Option<f64>,
    },
}

/// Physical parameters of the brake around the reduced model.
#[derive(Clone, Debug, PartialEq)]
pub struct BrakeParams {
    /// Unit normal from the disc into the pad.
    pub normal: [f64; 3],
    /// Direction in which the disc surface slides under the pad.
    pub sliding: [f64; 3],
    pub stiffness: Stiffness,
    /// Contact points pair up when closer than this (m).
    pub pairing_tolerance: f64,
    /// Total piston force (N) pressing the pad on the disc, shared equally by the piston dofs.
    pub piston_force: f64,
}

/// How a pair was formed.
#[derive(Clone, Debug, PartialEq)]
pub struct Pairing {
    pub disc_point: usize,
    pub pad_point: usize,
    pub distance: f64,
    pub area: Option<f64>,
    pub k_linear: f64,
    pub k_cubic: f64,
}

/// Index of each part's dofs in the brake: the disc first, then the pad.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    pub disc: std::ops::Range<usize>,
    pub pad: std::ops::Range<usize>,
}

fn part<'a>(rom: &'a ReducedModel, name: &str) -> Result<&'a ReducedPart, BrakeError> {
    rom.part(name)
        .ok_or_else(|| BrakeError::Invalid(format!("the reduced model has no part named '{name}'")))
}

/// The dof index (within the part) of point `p`'s direction `d`.
fn point_dof(part: &ReducedPart, p: usize, d: u8) -> Option<usize> {
    part.info.dofs.iter().position(|l| {
        *l == DofLabel::Point {
            point: p,
            direction: d,
        }
    })
}

fn unit(v: [f64; 3], what: &str) -> Result<[f64; 3], BrakeError> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if !(n > 0.0 && n.is_finite()) {
        return Err(BrakeError::Invalid(format!(
            "the {what} direction has zero length"
        )));
    }
    Ok(v.map(|x| x / n))
}

/// Builds the brake; returns it with its dof layout and the pairing report.
pub fn assemble(
    rom: &ReducedModel,
    params: &BrakeParams,
) -> Result<(Brake, Layout, Vec<Pairing>), BrakeError> {
    let disc = part(rom, "disc")?;
    let pad = part(rom, "pad")?;
    let (nd, np) = (disc.size(), pad.size());
    let n = nd + np;
    let layout = Layout {
        disc: 0..nd,
        pad: nd..n,
    };
    let m = block_diag(&disc.m, &pad.m);
    let k = block_diag(&disc.k, &pad.k);
    let normal = unit(params.normal, "contact normal")?;
    let sliding = unit(params.sliding, "sliding")?;
    let dot = normal[0] * sliding[0] + normal[1] * sliding[1] + normal[2] * sliding[2];
    if dot.abs() > 1e-6 {
        return Err(BrakeError::Invalid(format!(
            "the sliding direction must be tangent to the contact (normal . sliding = {dot:.3e})"
        )));
    }
    let contacts = |p: &ReducedPart| -> Vec<usize> {
        (0..p.info.points.len())
            .filter(|&i| p.info.points[i].role == PointRole::Contact)
            .collect()
    };
    let (dc, pc) = (contacts(disc), contacts(pad));
    if dc.is_empty() || dc.len() != pc.len() {
        return Err(BrakeError::Invalid(format!(
            "the disc has {} contact points and the pad {}: they must pair one to one",
            dc.len(),
            pc.len()
        )));
    }
    let mut used = vec![false; pc.len()];
    let mut pairs = Vec::new();
    let mut report = Vec::new();
    for &i in &dc {
        let xi = disc.info.points[i].position;
        let (j, dist) = pc
            .iter()
            .enumerate()
            .filter(|(k, _)| !used[*k])
            .map(|(k, &j)| {
                let xj = pad.info.points[j].position;
                (
                    k,
                    ((xi[0] - xj[0]).powi(2) + (xi[1] - xj[1]).powi(2) + (xi[2] - xj[2]).powi(2))
                        .sqrt(),
                )
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .ok_or_else(|| BrakeError::Invalid("no pad contact point left to pair".into()))?;
        if dist > params.pairing_tolerance {
            return Err(BrakeError::Invalid(format!(
                "disc contact point {} at ({:.6}, {:.6}, {:.6}) finds no pad point within {} m (nearest {dist:.3e} m)",
                i + 1,
                xi[0],
                xi[1],
                xi[2],
                params.pairing_tolerance
            )));
        }
        used[j] = true;
        let j = pc[j];
        let area = match (disc.info.points[i].area, pad.info.points[j].area) {
            (Some(a), Some(b)) => Some(0.5 * (a + b)),
            (a, b) => a.or(b),
        };
        let (kl, knl) = match params.stiffness {
            Stiffness::PerPoint { linear, cubic } => (linear, cubic),
            Stiffness::PerArea {
                linear,
                cubic,
                point_area,
            } => {
                let a = area.or(point_area).ok_or_else(|| {
                    BrakeError::Invalid(
                        "contact stiffness per unit area needs patch areas or a point area".into(),
                    )
                })?;
                (linear * a, cubic * a)
            }
        };
        let mut g: SparseVec = Vec::new();
        let mut h: SparseVec = Vec::new();
        for d in 0..3u8 {
            let di = point_dof(disc, i, d)
                .ok_or_else(|| BrakeError::Invalid(format!("disc point {i} lacks dof {d}")))?;
            let pj = point_dof(pad, j, d)
                .ok_or_else(|| BrakeError::Invalid(format!("pad point {j} lacks dof {d}")))?;
            let (nn, ss) = (normal[d as usize], sliding[d as usize]);
            if nn != 0.0 {
                g.push((di, nn));
                g.push((nd + pj, -nn));
            }
            if ss != 0.0 {
                h.push((di, ss));
                h.push((nd + pj, -ss));
            }
        }
        let gap = (0..3)
            .map(|d| normal[d] * (pad.info.points[j].position[d] - xi[d]))
            .sum::<f64>();
        report.push(Pairing {
            disc_point: i,
            pad_point: j,
            distance: dist,
            area,
            k_linear: kl,
            k_cubic: knl,
        });
        // A pad point below the disc surface (along n) starts in interference: gap = -(x_pad - x_disc)·n.
        pairs.push(ContactPair {
            disc_point: i,
            pad_point: j,
            position: xi,
            normal: g,
            tangent: h,
            gap: -gap,
            k_linear: kl,
            k_cubic: knl,
        });
    }
    let mut f_piston = vec![0.0; n];
    let pistons: Vec<usize> = (0..pad.info.points.len())
        .filter(|&i| pad.info.points[i].role == PointRole::Piston)
        .collect();
    if pistons.is_empty() {
        return Err(BrakeError::Invalid("the pad has no piston points".into()));
    }
    let share = params.piston_force / pistons.len() as f64;
    for &p in &pistons {
        for d in 0..3u8 {
            if let Some(dof) = point_dof(pad, p, d) {
                // The piston pushes the pad toward the disc: along -n.
                f_piston[nd + dof] -= share * normal[d as usize];
            }
        }
    }
    Ok((
        Brake {
            m,
            k,
            f_piston,
            pairs,
        },
        layout,
        report,
    ))
}

fn block_diag(a: &Mat<f64>, b: &Mat<f64>) -> Mat<f64> {
    let (na, nb) = (a.nrows(), b.nrows());
    Mat::from_fn(na + nb, na + nb, |i, j| match (i < na, j < na) {
        (true, true) => a[(i, j)],
        (false, false) => b[(i - na, j - na)],
        _ => 0.0,
    })
}
