//! The reduced brake of eq (11) from a reduced model: disc and pad stacked, contact points
//! paired by position ([`squeal_reduce::brake::pair_contact_points`], the one pairing of the
//! workspace; with the nodal interface each disc point is the projection of a pad node and
//! pairs with it, its motion the disc face's shape functions there on the disc's face
//! points), a contact element per pair, the piston load.
//!
//! Each pair's geometry comes from the model, not from a global frame:
//!
//! - **normal** `n_p`: the outward normal of the disc face under the disc's contact point
//!   (area-weighted over its patch, or over a node's tributary cell), stored in the `.rom`
//!   (format 3); else the pad point's normal reversed; else the scene's normal. A normal the
//!   scene gives is checked against every pair's ([`NORMAL_TOLERANCE_DEG`]).
//! - **sliding direction** `s_p`: with [`SlidingRule::Tangent`], the direction the disc's
//!   surface moves in at the pair, `t = σ a × (x_p - c)` (axis `a` through `c`, sense
//!   `σ = ±1`; Abaqus' `*MOTION`, Ansys' `CMROTATE`), projected into the contact plane,
//!   `s_p = (t - (t·n_p) n_p) / |…|`; with [`SlidingRule::Global`], one direction projected
//!   the same way (refused when it leaves the plane by more than 1e-6, or points against the
//!   rotation where the sense is known).
//! - **surface speed** `V_p = Ω (σ a × (x_p - c)) · s_p`, `Ω r_p` for tangent sliding on a
//!   face normal to the axis, when the speed is known.
//! - **piston**: the load pushes the pad towards the disc: a piston point with one dof (the
//!   piston's axis, a coordinate axis or a `DofLabel::Along`) pushes along it, towards the
//!   disc, and its axis must be within [`NORMAL_TOLERANCE_DEG`] of the pads' mean normal
//!   `Σ A_p n_p / |Σ A_p n_p|`; a point with several dofs pushes along `-n` itself. The
//!   clamp force is shared equally by the pad's piston points: a piston node, or a piston's
//!   footprint, whose one dof is the footprint's area-weighted mean motion (its share then
//!   acts as the consistent nodal loads of a uniform pressure over the footprint, by the
//!   reduction's constraint modes: `ψ_bᵀ (F Σ_k w_k n e_k) = F δ_bf`).
//!
//! A rigid motion of the meshes with the scene's axis, point and normal moved alike moves every
//! one of these with it, so the brake's spectrum does not change.
//!
//! Each pair's initial gap `g0` ([`InitialGaps`]) is measured from the geometry by default:
//! the normal distance `n · (x_pad - x_disc)` between the paired points (the patch centroids
//! of the patch interface), positive when the pad point lies off the disc surface. It may be
//! given instead (one value, or one per pair), or closed (`g0 = 0` whatever the geometry, as
//! Abaqus' contact adjustment and Ansys' contact offset do); [`Pairing`] keeps both the
//! geometric and the gap used.

use crate::contact::{Law, LawSpec};
use crate::error::BrakeError;
use crate::model::{Brake, ContactPair, SparseVec};
use faer::Mat;
use squeal_element::geometry::dot;
use squeal_fe::frames::RotationAxis;
use squeal_reduce::brake::{PairingTolerance, pair_contact_points};
use squeal_reduce::rom::{DofLabel, PointRole, ReducedModel, ReducedPart};

/// Largest angle (degrees) between the disc face's normal at a pair and a normal the scene
/// gives: beyond it the scene and the mesh disagree (a wrong axis, a reversed normal). Disc
/// faces are flat, so their patch normals agree with the true one to round-off; 5 degrees
/// still lets a faceted or slightly coned face through.
pub const NORMAL_TOLERANCE_DEG: f64 = 5.0;

/// Largest length of a load direction outside the span of a point's dofs (the part of the
/// load that would be lost): round-off of normals taken from a mesh.
const SPAN_TOLERANCE: f64 = 1e-9;

/// How the disc's surface slides under the pad.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SlidingRule {
    /// The tangent of the disc's rotation at each pair (needs [`BrakeParams::rotation`] with
    /// a sense).
    Tangent,
    /// One global direction at every pair (the paper's choice).
    Global([f64; 3]),
}

/// The disc's rotation: axis, sense, speed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiscRotation {
    /// The axis (a point and a unit direction).
    pub axis: RotationAxis,
    /// +1: the right-hand rule about the axis; -1: the other way; 0: not known.
    pub sense: f64,
    /// `Ω` (rad/s), when known.
    pub angular_speed: Option<f64>,
}

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
    /// The normal from the disc into the pad the scene gives, if any: used at pairs whose
    /// points carry no normal, and checked against those that do.
    pub normal: Option<[f64; 3]>,
    /// How the disc surface slides under the pad.
    pub sliding: SlidingRule,
    /// The disc's rotation, when known (needed by [`SlidingRule::Tangent`]).
    pub rotation: Option<DiscRotation>,
    /// Contact stiffness of every pair's element (its normal part, eq 8).
    pub stiffness: Stiffness,
    /// Which contact law every pair gets (its friction part).
    pub law: LawSpec,
    /// How close paired contact points must be.
    pub pairing_tolerance: PairingTolerance,
    /// Total piston force (N) pressing the pad on the disc, shared equally by the pad's piston
    /// points (piston nodes or footprints), each pushed towards the disc along the pads' mean
    /// normal.
    pub piston_force: f64,
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
    /// The pad's name (`pad` in a one-pad brake).
    pub pad: String,
    /// Distance between the two points (m).
    pub distance: f64,
    /// The pair's area (m²): the mean of the two points' areas, or the one given.
    pub area: Option<f64>,
    /// Unit normal from the disc into the pad at the pair.
    pub normal: [f64; 3],
    /// Unit sliding direction at the pair.
    pub sliding: [f64; 3],
    /// The normal distance `n · (x_pad - x_disc)` of the two points (m): the geometric gap.
    pub geometric_gap: f64,
    /// The initial gap `g0` the pair is given (m; positive: open), from [`InitialGaps`].
    pub initial_gap: f64,
    /// The pair's contact element.
    pub law: Law,
}

/// Index of each part's dofs in the brake: the disc first, then the pads in the model's order.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// The disc's dofs, `0..n_disc`.
    pub disc: std::ops::Range<usize>,
    /// Every pad's name and dofs, after the disc's (at least one pad).
    pub pads: Vec<(String, std::ops::Range<usize>)>,
}

impl Layout {
    /// The first pad's dofs.
    pub fn pad(&self) -> std::ops::Range<usize> {
        self.pads
            .first()
            .map_or(self.disc.end..self.disc.end, |p| p.1.clone())
    }

    /// All the pads' dofs: from the disc's end to the last pad's last.
    pub fn all_pads(&self) -> std::ops::Range<usize> {
        self.disc.end..self.pads.last().map_or(self.disc.end, |p| p.1.end)
    }
}

fn part<'a>(rom: &'a ReducedModel, name: &str) -> Result<&'a ReducedPart, BrakeError> {
    rom.part(name).ok_or_else(|| no_part(rom, name))
}

/// The error of a model without part `name`, listing the parts it has.
fn no_part(rom: &ReducedModel, name: &str) -> BrakeError {
    BrakeError::NoPart {
        name: name.into(),
        have: rom
            .parts
            .iter()
            .map(|p| format!("'{}'", p.info.name))
            .collect::<Vec<_>>()
            .join(", "),
    }
}

/// `v / |v|`; [`BrakeError::BadDirection`] naming `what` if `v` is zero or not finite.
pub fn unit(v: [f64; 3], what: &'static str) -> Result<[f64; 3], BrakeError> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if !(n > 0.0 && n.is_finite()) {
        return Err(BrakeError::BadDirection { what });
    }
    Ok(v.map(|x| x / n))
}

/// Indices of a part's points of a role.
fn points_of(p: &ReducedPart, role: PointRole) -> Vec<usize> {
    (0..p.info.points.len())
        .filter(|&i| p.info.points[i].role == role)
        .collect()
}

/// The point's dofs and their unit directions: a `Point` label's coordinate axis, an
/// `Along` label's vector.
fn point_dofs(part: &ReducedPart, point: usize) -> Vec<(usize, [f64; 3])> {
    part.info
        .dofs
        .iter()
        .enumerate()
        .filter_map(|(k, l)| match *l {
            DofLabel::Point {
                point: p,
                direction,
            } if p == point => {
                let mut e = [0.0; 3];
                e[direction.min(2) as usize] = 1.0;
                Some((k, e))
            }
            DofLabel::Along {
                point: p,
                direction,
            } if p == point => Some((k, direction)),
            _ => None,
        })
        .collect()
}

/// `sign · Σ_k (w · e_k) e_{dof k}` over a point's dofs, offset by `shift`: the motion of the
/// point along `w` (its generalized force for a force along `w`). The point's dofs must be
/// orthonormal (coordinate axes, or one `Along` vector) and span `w` to [`SPAN_TOLERANCE`],
/// else part of the motion or load would be lost.
fn along(
    part: &ReducedPart,
    name: &'static str,
    point: usize,
    w: [f64; 3],
    shift: usize,
    sign: f64,
) -> Result<SparseVec, BrakeError> {
    let mut v = Vec::new();
    let mut rest = w;
    // A direction computed from the mesh (a face normal, a tangent) has round-off components
    // of 1e-17 where it lies along a dof's axis: they are dropped, so that such a pair keeps
    // one entry per direction instead of three (every contact force and its Jacobian costs in
    // proportion), and the direction moves by no more than 64 ε.
    let negligible = 64.0 * f64::EPSILON * dot(w, w).sqrt();
    for (dof, e) in point_dofs(part, point) {
        let c = dot(w, e);
        for d in 0..3 {
            rest[d] -= c * e[d];
        }
        if c.abs() > negligible {
            v.push((shift + dof, sign * c));
        }
    }
    let missing = dot(rest, rest).sqrt();
    if missing > SPAN_TOLERANCE * dot(w, w).sqrt() {
        return Err(BrakeError::MissingPointDof {
            part: name,
            point: point + 1,
            direction: w,
            missing,
        });
    }
    Ok(v)
}

/// The motion along `w` of disc point `point`: [`along`] its own dofs, or for a projected
/// point of the nodal interface `Σ_k c_k (w · u_k)` over the face points it combines
/// ([`squeal_reduce::rom::Projected`]), entries of a dof summed in the order of the weights.
fn disc_along(disc: &ReducedPart, point: usize, w: [f64; 3]) -> Result<SparseVec, BrakeError> {
    match &disc.info.points[point].projected {
        None => along(disc, "disc", point, w, 0, 1.0),
        Some(p) => combined_along(disc, "disc", &p.weights, w, 0, 1.0),
    }
}

/// The motion along `w` of pad point `point` (its generalized force times `sign`, offset by
/// `shift`): [`along`] its own dofs, or for a Gauss point of an 8-node face
/// ([`squeal_reduce::rom::InterfacePoint::combines`]) `Σ_k c_k (w · u_k)` over the face
/// points it combines.
fn pad_along(
    pad: &ReducedPart,
    point: usize,
    w: [f64; 3],
    shift: usize,
    sign: f64,
) -> Result<SparseVec, BrakeError> {
    match &pad.info.points[point].combines {
        None => along(pad, "pad", point, w, shift, sign),
        Some(c) => combined_along(pad, "pad", c, w, shift, sign),
    }
}

/// `Σ_k c_k` [`along`]`(k)` over `weights` `(k, c_k)`, entries of a dof summed in the order
/// of the weights.
fn combined_along(
    part: &ReducedPart,
    name: &'static str,
    weights: &[(usize, f64)],
    w: [f64; 3],
    shift: usize,
    sign: f64,
) -> Result<SparseVec, BrakeError> {
    let mut v: SparseVec = Vec::new();
    for &(k, c) in weights {
        for (dof, e) in along(part, name, k, w, shift, sign)? {
            match v.iter_mut().find(|x| x.0 == dof) {
                Some(x) => x.1 += c * e,
                None => v.push((dof, c * e)),
            }
        }
    }
    Ok(v)
}

/// The pairs of the nodal interface, where the disc's points `dc` (facing this pad) are
/// projections of the pad's contact points `pc`: each with the pad point it was projected
/// from, as indices into `dc` and `pc`. `None` when the disc's points are not projections.
fn projected_pairs(
    disc: &ReducedPart,
    dc: &[usize],
    pad: &ReducedPart,
    pc: &[usize],
) -> Option<Vec<squeal_reduce::brake::PointPair>> {
    let mut out = Vec::with_capacity(dc.len());
    for (a, &i) in dc.iter().enumerate() {
        let p = disc.info.points[i].projected.as_ref()?;
        let b = pc.iter().position(|&j| j == p.pad_point)?;
        let (x, y) = (
            disc.info.points[i].position,
            pad.info.points[pc[b]].position,
        );
        out.push(squeal_reduce::brake::PointPair {
            disc_point: a,
            pad_point: b,
            distance: (0..3).map(|d| (x[d] - y[d]).powi(2)).sum::<f64>().sqrt(),
        });
    }
    Some(out)
}

fn angle_deg(a: [f64; 3], b: [f64; 3]) -> f64 {
    dot(a, b).clamp(-1.0, 1.0).acos().to_degrees()
}

/// The unit normal from the disc into the pad at pair `pair` (1-based): the disc point's
/// normal, else the pad point's reversed, else the scene's; checked against the scene's.
fn pair_normal(
    disc_normal: Option<[f64; 3]>,
    pad_normal: Option<[f64; 3]>,
    scene: Option<[f64; 3]>,
    pair: usize,
) -> Result<[f64; 3], BrakeError> {
    let mesh = disc_normal
        .and_then(|n| unit(n, "contact normal").ok())
        .or_else(|| pad_normal.and_then(|n| unit(n.map(|x| -x), "contact normal").ok()));
    match (mesh, scene) {
        (Some(m), Some(s)) => {
            let degrees = angle_deg(m, s);
            if degrees > NORMAL_TOLERANCE_DEG {
                return Err(BrakeError::NormalDisagrees {
                    pair,
                    mesh: m,
                    degrees,
                });
            }
            Ok(m)
        }
        (Some(m), None) => Ok(m),
        (None, Some(s)) => Ok(s),
        (None, None) => Err(BrakeError::NoNormal { pair }),
    }
}

/// `v` with its component along the unit `n` removed, made unit; `None` when nothing is left.
fn in_plane(v: [f64; 3], n: [f64; 3]) -> Option<[f64; 3]> {
    let c = dot(v, n);
    unit(std::array::from_fn(|d| v[d] - c * n[d]), "sliding").ok()
}

/// The sliding direction and surface speed at a pair at `x` with normal `n` (module docs).
fn pair_sliding(
    params: &BrakeParams,
    x: [f64; 3],
    n: [f64; 3],
    pair: usize,
) -> Result<([f64; 3], Option<f64>), BrakeError> {
    // The disc's surface velocity per unit Ω, σ a × (x - c), when the sense is known.
    let motion = params
        .rotation
        .filter(|r| r.sense != 0.0)
        .map(|r| r.axis.velocity(x, r.sense));
    let s = match params.sliding {
        SlidingRule::Tangent => {
            let t = motion.ok_or(BrakeError::NoSense)?;
            in_plane(t, n).ok_or(BrakeError::OnAxis { pair })?
        }
        SlidingRule::Global(g) => {
            let g = unit(g, "sliding")?;
            let d = dot(n, g);
            if d.abs() > 1e-6 {
                return Err(BrakeError::SlidingNotTangent { dot: d });
            }
            let s = in_plane(g, n).ok_or(BrakeError::SlidingNotTangent { dot: d })?;
            if let Some(t) = motion.and_then(|t| unit(t, "sliding").ok()) {
                let cosine = dot(s, t);
                if cosine <= 0.0 {
                    return Err(BrakeError::SlidingAgainstRotation { pair, cosine });
                }
            }
            s
        }
    };
    let speed = params.rotation.and_then(|r| {
        let w = r.angular_speed?;
        Some(match motion {
            Some(m) => w * dot(m, s),
            None => w.abs() * r.axis.radius(x),
        })
    });
    Ok((s, speed))
}

/// The pair's contact element: the law `spec` with the stiffnesses from the scene's stiffness
/// and the pair's area.
fn element(
    stiffness: &Stiffness,
    spec: &LawSpec,
    area: Option<f64>,
    pair: usize,
) -> Result<Law, BrakeError> {
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
    Ok(spec.element(k_linear, k_cubic))
}

/// Builds the brake; returns it with its dof layout and the pairing report. The disc's dofs
/// come first, then each pad's, in the model's order; each pad's contact points pair with the
/// disc's points of the surface facing it (all of the disc's in a one-pad brake), and each
/// pad's load points share the clamp force (a floating caliper: the fingers react the
/// pistons).
pub fn assemble(
    rom: &ReducedModel,
    params: &BrakeParams,
) -> Result<(Brake, Layout, Vec<Pairing>), BrakeError> {
    let disc = part(rom, "disc")?;
    let pads = rom.pads();
    if pads.is_empty() {
        return Err(no_part(rom, "pad"));
    }
    let nd = disc.size();
    let mut layout = Layout {
        disc: 0..nd,
        pads: Vec::with_capacity(pads.len()),
    };
    let mut start = nd;
    for p in &pads {
        layout
            .pads
            .push((p.info.name.clone(), start..start + p.size()));
        start += p.size();
    }
    // The bodies (a caliper, a bracket) after the last pad: dofs `layout.all_pads().end..n`.
    let n = start + rom.bodies().iter().map(|b| b.size()).sum::<usize>();
    let scene_normal = params
        .normal
        .map(|n| unit(n, "contact normal"))
        .transpose()?;
    let disc_contact = points_of(disc, PointRole::Contact);
    let position = |p: &ReducedPart, i: usize| p.info.points[i].position;
    let mut pairs = Vec::new();
    let mut report = Vec::new();
    let mut f_piston = vec![0.0; n];
    for (pad, (_, range)) in pads.iter().zip(&layout.pads) {
        let name = pad.info.name.as_str();
        let np0 = range.start;
        // The disc's points facing this pad: those of its surface, or all of them when the
        // disc has one surface.
        let dc: Vec<usize> = disc_contact
            .iter()
            .copied()
            .filter(|&i| match &disc.info.points[i].surface {
                Some(s) => s == name,
                None => pads.len() == 1,
            })
            .collect();
        let pc = points_of(pad, PointRole::Contact);
        let matched = match projected_pairs(disc, &dc, pad, &pc) {
            Some(m) => m,
            None => {
                pair_contact_points(
                    &dc.iter().map(|&i| position(disc, i)).collect::<Vec<_>>(),
                    &pc.iter().map(|&j| position(pad, j)).collect::<Vec<_>>(),
                    params.pairing_tolerance,
                )?
                .0
            }
        };
        // Σ A_p n_p: this pad's mean normal, its load's direction.
        let mut pad_normal = [0.0; 3];
        for m in &matched {
            let k = pairs.len();
            let (i, j) = (dc[m.disc_point], pc[m.pad_point]);
            let area = match (disc.info.points[i].area, pad.info.points[j].area) {
                (Some(a), Some(b)) => Some(0.5 * (a + b)),
                (a, b) => a.or(b),
            };
            let law = element(&params.stiffness, &params.law, area, k + 1)?;
            let xi = position(disc, i);
            let normal = pair_normal(
                disc.info.points[i].normal,
                pad.info.points[j].normal,
                scene_normal.filter(|_| pads.len() == 1),
                k + 1,
            )?;
            let (sliding, surface_speed) = pair_sliding(params, xi, normal, k + 1)?;
            let mut g = disc_along(disc, i, normal)?;
            g.extend(pad_along(pad, j, normal, np0, -1.0)?);
            let mut h = disc_along(disc, i, sliding)?;
            h.extend(pad_along(pad, j, sliding, np0, -1.0)?);
            // A pad point below the disc surface (along n) starts in interference.
            let geometric_gap = (0..3)
                .map(|d| normal[d] * (position(pad, j)[d] - xi[d]))
                .sum::<f64>();
            let w = area.unwrap_or(1.0);
            for d in 0..3 {
                pad_normal[d] += w * normal[d];
            }
            report.push(Pairing {
                disc_point: i,
                pad_point: j,
                pad: name.to_string(),
                distance: m.distance,
                area,
                normal,
                sliding,
                geometric_gap,
                initial_gap: 0.0,
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
                initial_gap: 0.0,
                surface_speed,
                law,
            });
        }
        let normal = unit(pad_normal, "contact normal")?;
        add_load(pad, normal, np0, params.piston_force, &mut f_piston)?;
    }
    if let InitialGaps::PerPair(g) = &params.initial_gaps
        && g.len() != pairs.len()
    {
        return Err(BrakeError::GapCount {
            given: g.len(),
            pairs: pairs.len(),
        });
    }
    for (k, (pair, r)) in pairs.iter_mut().zip(&mut report).enumerate() {
        r.initial_gap = match &params.initial_gaps {
            InitialGaps::Geometric => r.geometric_gap,
            InitialGaps::Uniform(g) => *g,
            InitialGaps::PerPair(g) => g[k],
            InitialGaps::Closed => 0.0,
        };
        pair.initial_gap = r.initial_gap;
    }
    let blocks: Vec<&ReducedPart> = std::iter::once(disc)
        .chain(pads.iter().copied())
        .chain(rom.bodies())
        .collect();
    let mut brake = Brake {
        m: block_diag(&blocks.iter().map(|p| &p.m).collect::<Vec<_>>()),
        k: block_diag(&blocks.iter().map(|p| &p.k).collect::<Vec<_>>()),
        f_piston,
        c: None,
        k_vibration: None,
        pairs,
    };
    crate::connections::add_connections(
        rom,
        &blocks,
        &mut brake.k,
        &mut brake.k_vibration,
        &mut brake.f_piston,
    )?;
    crate::connections::eliminate_ties(rom, &blocks, layout.all_pads().end, &mut brake)?;
    brake.validate()?;
    Ok((brake, layout, report))
}

/// Adds pad `pad`'s share of the clamp force `force` (N) to `f` (the pad's dofs from `start`),
/// spread equally over its load points (pistons or fingers), each pushing the pad towards the
/// disc: along its one dof (the piston's axis), within [`NORMAL_TOLERANCE_DEG`] of the pad's
/// mean normal `normal`, or along `-normal` for a point with several dofs.
fn add_load(
    pad: &ReducedPart,
    normal: [f64; 3],
    start: usize,
    force: f64,
    f: &mut [f64],
) -> Result<(), BrakeError> {
    let pistons = points_of(pad, PointRole::Piston);
    if pistons.is_empty() {
        return Err(BrakeError::NoPistons);
    }
    let share = force / pistons.len() as f64;
    let aligned = NORMAL_TOLERANCE_DEG.to_radians().cos();
    for &p in &pistons {
        match point_dofs(pad, p).as_slice() {
            // The piston's own axis (its one dof): it pushes along it, towards the disc. The
            // axis is the scene's normal or rotation axis, within NORMAL_TOLERANCE_DEG of the
            // mesh's, so a few degrees between the two do not refuse the brake.
            [(dof, e)] => {
                let c = dot(*e, normal);
                if c.abs() < aligned {
                    return Err(BrakeError::MissingPointDof {
                        part: "pad",
                        point: p + 1,
                        direction: normal,
                        missing: (1.0 - c * c).max(0.0).sqrt(),
                    });
                }
                f[start + dof] -= share * c.signum();
            }
            // Several dofs: the piston pushes the pad toward the disc, along -n; the point's
            // dofs must span the normal, or part of the load would be lost.
            _ => {
                for (dof, w) in along(pad, "pad", p, normal, start, -1.0)? {
                    f[dof] += share * w;
                }
            }
        }
    }
    Ok(())
}

fn block_diag(blocks: &[&Mat<f64>]) -> Mat<f64> {
    let n: usize = blocks.iter().map(|b| b.nrows()).sum();
    let mut out = Mat::zeros(n, n);
    let mut at = 0;
    for b in blocks {
        let k = b.nrows();
        out.as_mut()
            .submatrix_mut(at, at, k, k)
            .copy_from(b.as_ref());
        at += k;
    }
    out
}
