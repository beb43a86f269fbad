//! The reduced brake of eq (11) from a reduced model: disc and pad stacked, contact points
//! paired by position ([`squeal_reduce::brake::pair_contact_points`], the one pairing of the
//! workspace), a contact element per pair, the piston load.
//!
//! Each pair's initial gap `g0` ([`InitialGaps`]) is measured from the geometry by default:
//! the normal distance `n · (x_pad - x_disc)` between the paired points (the patch centroids
//! of the patch interface), positive when the pad point lies off the disc surface. It may be
//! given instead (one value, or one per pair), or closed (`g0 = 0` whatever the geometry, as
//! Abaqus' contact adjustment and Ansys' contact offset do); [`Pairing`] keeps both the
//! geometric and the gap used.

use crate::contact::{Law, PenaltyCoulomb};
use crate::error::BrakeError;
use crate::model::{Brake, ContactPair, SparseVec};
use faer::Mat;
use squeal_reduce::brake::{PairingTolerance, pair_contact_points};
use squeal_reduce::rom::{DofLabel, PointRole, ReducedModel, ReducedPart};
use std::sync::Arc;

/// Contact stiffness of eq (8): per contact point, or per unit area (then multiplied by each
/// pair's tributary area: the patch area for the patch interface).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stiffness {
    /// `k_l` (N/m) and `k_nl` (N/m³) of every pair.
    PerPoint {
        /// `k_l` (N/m).
        linear: f64,
        /// `k_nl` (N/m³).
        cubic: f64,
    },
    /// `κ_l` (Pa/m) and `κ_nl` (Pa/m³): `k = κ A` with `A` the pair's area; `point_area`
    /// is used where the model has no patch areas (node interface).
    PerArea {
        /// `κ_l` (Pa/m).
        linear: f64,
        /// `κ_nl` (Pa/m³).
        cubic: f64,
        /// Area (m²) of a pair whose points carry none.
        point_area: Option<f64>,
    },
}

/// Where the pairs' initial gaps `g0` (m; positive: open) come from.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum InitialGaps {
    /// Measured at pairing: `g0 = n · (x_pad - x_disc)` of the paired points.
    #[default]
    Geometric,
    /// The same `g0` for every pair (m), whatever the geometry.
    Uniform(f64),
    /// One `g0` per pair (m), in pair order.
    PerPair(Vec<f64>),
    /// Every `g0` set to zero (the geometric gaps are reported as the adjustment).
    Closed,
}

/// Physical parameters of the brake around the reduced model.
#[derive(Clone, Debug, PartialEq)]
pub struct BrakeParams {
    /// Unit normal from the disc into the pad.
    pub normal: [f64; 3],
    /// Direction in which the disc surface slides under the pad.
    pub sliding: [f64; 3],
    /// Contact stiffness of every pair's element.
    pub stiffness: Stiffness,
    /// How close paired contact points must be.
    pub pairing_tolerance: PairingTolerance,
    /// Total piston force (N) pressing the pad on the disc, shared equally by the pad's piston
    /// points, each pushed along `-normal`.
    pub piston_force: f64,
    /// The disc's surface speed under the pad (m/s), when known.
    pub surface_speed: Option<f64>,
    /// The pairs' initial gaps.
    pub initial_gaps: InitialGaps,
}

/// How a pair was formed.
#[derive(Clone, Debug)]
pub struct Pairing {
    /// Index of the disc's point among the disc part's points.
    pub disc_point: usize,
    /// Index of the pad's point among the pad part's points.
    pub pad_point: usize,
    /// Distance between the two points (m).
    pub distance: f64,
    /// The pair's area (m²): the mean of the two points' areas, or the one given.
    pub area: Option<f64>,
    /// The normal distance `n · (x_pad - x_disc)` of the two points (m): the geometric gap.
    pub geometric_gap: f64,
    /// The initial gap `g0` the pair is given (m; positive: open), from [`InitialGaps`].
    pub initial_gap: f64,
    /// The pair's contact element.
    pub law: Law,
}

/// Index of each part's dofs in the brake: the disc first, then the pad.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// The disc's dofs, `0..n_disc`.
    pub disc: std::ops::Range<usize>,
    /// The pad's dofs, after the disc's.
    pub pad: std::ops::Range<usize>,
}

fn part<'a>(rom: &'a ReducedModel, name: &str) -> Result<&'a ReducedPart, BrakeError> {
    rom.part(name).ok_or_else(|| BrakeError::NoPart {
        name: name.into(),
        have: rom
            .parts
            .iter()
            .map(|p| format!("'{}'", p.info.name))
            .collect::<Vec<_>>()
            .join(", "),
    })
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

/// `v / |v|`; [`BrakeError::BadDirection`] naming `what` if `v` is zero or not finite.
pub fn unit(v: [f64; 3], what: &'static str) -> Result<[f64; 3], BrakeError> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if !(n > 0.0 && n.is_finite()) {
        return Err(BrakeError::BadDirection { what });
    }
    Ok(v.map(|x| x / n))
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Indices of a part's points of a role.
fn points_of(p: &ReducedPart, role: PointRole) -> Vec<usize> {
    (0..p.info.points.len())
        .filter(|&i| p.info.points[i].role == role)
        .collect()
}

/// `Σ_d w_d e_{dof(d)}` over a point's three dofs, offset by `shift`.
fn along(
    part: &ReducedPart,
    name: &'static str,
    point: usize,
    w: [f64; 3],
    shift: usize,
    sign: f64,
) -> Result<SparseVec, BrakeError> {
    let mut v = Vec::new();
    for d in 0..3u8 {
        if w[d as usize] == 0.0 {
            continue;
        }
        let dof = point_dof(part, point, d).ok_or(BrakeError::MissingPointDof {
            part: name,
            point: point + 1,
            direction: ['x', 'y', 'z'][d as usize],
        })?;
        v.push((shift + dof, sign * w[d as usize]));
    }
    Ok(v)
}

/// The pair's contact stiffnesses from the scene's stiffness and the pair's area.
fn element(stiffness: &Stiffness, area: Option<f64>, pair: usize) -> Result<Law, BrakeError> {
    let (k_linear, k_cubic) = match *stiffness {
        Stiffness::PerPoint { linear, cubic } => (linear, cubic),
        Stiffness::PerArea {
            linear,
            cubic,
            point_area,
        } => {
            let a = area.or(point_area).ok_or(BrakeError::NoArea { pair })?;
            (linear * a, cubic * a)
        }
    };
    Ok(Arc::new(PenaltyCoulomb { k_linear, k_cubic }))
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
    let normal = unit(params.normal, "contact normal")?;
    let sliding = unit(params.sliding, "sliding")?;
    let d = dot(normal, sliding);
    if d.abs() > 1e-6 {
        return Err(BrakeError::SlidingNotTangent { dot: d });
    }
    let (dc, pc) = (
        points_of(disc, PointRole::Contact),
        points_of(pad, PointRole::Contact),
    );
    let position = |p: &ReducedPart, i: usize| p.info.points[i].position;
    let (matched, _) = pair_contact_points(
        &dc.iter().map(|&i| position(disc, i)).collect::<Vec<_>>(),
        &pc.iter().map(|&j| position(pad, j)).collect::<Vec<_>>(),
        params.pairing_tolerance,
    )?;
    if let InitialGaps::PerPair(g) = &params.initial_gaps
        && g.len() != matched.len()
    {
        return Err(BrakeError::GapCount {
            given: g.len(),
            pairs: matched.len(),
        });
    }
    let mut pairs = Vec::with_capacity(matched.len());
    let mut report = Vec::with_capacity(matched.len());
    for (k, m) in matched.iter().enumerate() {
        let (i, j) = (dc[m.disc_point], pc[m.pad_point]);
        let area = match (disc.info.points[i].area, pad.info.points[j].area) {
            (Some(a), Some(b)) => Some(0.5 * (a + b)),
            (a, b) => a.or(b),
        };
        let law = element(&params.stiffness, area, k + 1)?;
        let mut g = along(disc, "disc", i, normal, 0, 1.0)?;
        g.extend(along(pad, "pad", j, normal, nd, -1.0)?);
        let mut h = along(disc, "disc", i, sliding, 0, 1.0)?;
        h.extend(along(pad, "pad", j, sliding, nd, -1.0)?);
        let xi = position(disc, i);
        // A pad point below the disc surface (along n) starts in interference.
        let geometric_gap = (0..3)
            .map(|d| normal[d] * (position(pad, j)[d] - xi[d]))
            .sum::<f64>();
        let initial_gap = match &params.initial_gaps {
            InitialGaps::Geometric => geometric_gap,
            InitialGaps::Uniform(g) => *g,
            InitialGaps::PerPair(g) => g[k],
            InitialGaps::Closed => 0.0,
        };
        let gap = -initial_gap;
        report.push(Pairing {
            disc_point: i,
            pad_point: j,
            distance: m.distance,
            area,
            geometric_gap,
            initial_gap,
            law: law.clone(),
        });
        pairs.push(ContactPair {
            disc_point: i,
            pad_point: j,
            position: xi,
            normal_direction: normal,
            sliding_direction: sliding,
            normal: g,
            tangent: h,
            gap,
            surface_speed: params.surface_speed,
            law,
        });
    }
    let pistons = points_of(pad, PointRole::Piston);
    if pistons.is_empty() {
        return Err(BrakeError::NoPistons);
    }
    let mut f_piston = vec![0.0; n];
    let share = params.piston_force / pistons.len() as f64;
    for &p in &pistons {
        // The piston pushes the pad toward the disc: along -n. Every direction of the normal
        // needs its dof, or part of the load would be lost.
        for (dof, w) in along(pad, "pad", p, normal, nd, -1.0)? {
            f_piston[dof] += share * w;
        }
    }
    let brake = Brake {
        m: block_diag(&disc.m, &pad.m),
        k: block_diag(&disc.k, &pad.k),
        f_piston,
        pairs,
    };
    brake.validate()?;
    Ok((brake, layout, report))
}

fn block_diag(a: &Mat<f64>, b: &Mat<f64>) -> Mat<f64> {
    let (na, nb) = (a.nrows(), b.nrows());
    Mat::from_fn(na + nb, na + nb, |i, j| match (i < na, j < na) {
        (true, true) => a[(i, j)],
        (false, false) => b[(i - na, j - na)],
        _ => 0.0,
    })
}
