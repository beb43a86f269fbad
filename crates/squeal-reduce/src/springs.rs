//! Springs inside a part: between two node sets of the part, or from a node set to ground, with
//! a stiffness along three axes (global, or a local orthonormal frame).
//!
//! A brake corner's parts are held and joined by springs the meshes do not model: the piston's
//! seal (a ring of the piston bore to ground), a caliper finger on a patch of the outboard
//! backplate, the bracket's mounts on the knuckle. A spring of total stiffness `k_d` along the
//! unit axes `e_d` (d = 1..3) adds the strain energy `½ Σ_d k_d (e_d · (ū_a − ū_b))²` between
//! the motions `ū_a`, `ū_b` of its two ends (`ū_b = 0` for ground), so that the stiffness gains
//! the rank-one terms `K += Σ_d k_d c_d c_dᵀ`, `c_d · u = e_d · (ū_a − ū_b)`, on the part's free
//! coordinates, before the Craig–Bampton reduction: the fixed-interface modes, the constraint
//! modes and hence `K̂` (eq. 6) see the spring, the static equilibrium on the clamp path
//! (`K̂ x + F_nl = F`, eq. 11 at rest) and the vibration about it alike. A restrained direction
//! of an end node holds already and adds nothing there.
//!
//! How an end's motion `ū` is taken from its set ([`Spread`]):
//!
//! - **`Mean`**: the area-weighted mean translation `ū = Σ_n α_n u_n` of the set (`α_n` the
//!   nodes' tributary areas over the set's area when it is a face, [`face_nodes`], else equal
//!   shares), as an interpolation element (Nastran's RBE3) does. A piston or a finger acts on a
//!   patch of the backplate as a whole: the spring must neither stiffen the patch (a rigid
//!   link, RBE2, would) nor depend on the mesh (a spring on one node would, and would load the
//!   node with the whole force). The mean is the only form between two sets of different
//!   meshes, and the one for a stiffness given per part rather than per area.
//! - **`Area`** (to ground only): the total shared among the set's nodes in proportion to
//!   their tributary areas, `K += Σ_n Σ_d α_n k_d (e_d · u_n)²`: a uniform elastic foundation
//!   `k_d / A` per unit area, whatever the mesh — a seal gripping the piston over a ring, a pad
//!   held over its back face, a mount's bolted face. It is the `[[supports]]` law
//!   ([`crate::tie`]) with a local frame.
//!
//! - **`Normal`**: a sliding contact held closed about the equilibrium — a pad's abutment on
//!   the bracket. Each node `n` of the set (a face) gets the share `α_n k` (tributary area) of
//!   the normal stiffness `k` (the first stiffness; the other two must be 0) along the normal
//!   `ν` of the face it bears on, and none across it: `K += Σ_n α_n k (ν · (u_n − u_m))²`, where
//!   `u_m = Σ_i N_i(ξ_n) u_i` is the motion of the point of the master face `to` the node
//!   projects onto (the nodal contact's projection, [`Surface::project`], so non-matching
//!   meshes bear; `ν` the master's normal there), or `u_m = 0` and `ν` the node's own face
//!   normal against a rigid (ground) bracket. The tangential direction is free: the linear
//!   model about the equilibrium of a pad that slides on its abutment under the drag (the
//!   sliding abutment of Sinou's and Kung's brake models; a stuck abutment would be a `Mean`
//!   or `Area` spring along all three axes). Friction on the abutment would add a tangential
//!   force `μ_a F_a` that depends on the abutment's normal load at the equilibrium, which the
//!   linear model does not carry; it is not built. Projection tolerance: a node lying farther
//!   than 1 % of the master face's extent from it, or beyond its edge, is refused (as a
//!   tie's default, [`crate::tie`]).
//!
//! A rigid part of mass `m` on a `Mean` or `Area` spring `k` to ground along `e` moves at
//! `ω² = k / m` along `e`; two rigid parts on a `Mean` spring between them at
//! `ω² = k (1/m_a + 1/m_b)`. The held-part check ([`crate::held`]) counts each term `c_d` as a
//! row on the rigid motions: a spring between two sets of one part does not hold its
//! translations (the ends move together) but may hold its rotations.
//!
//! Viscous dampers on the same ends and spreads are [`crate::dampers`]: the same terms with a
//! damping coefficient in the stiffness's place, projected by the part's Craig–Bampton basis
//! after the reduction instead of added before it.

use crate::error::ReduceError;
use crate::interface::InterfaceError;
use crate::interface::nodal::{Surface, face_nodes};
use squeal_mesh::Mesh;

/// How a spring's end takes its motion from its node set (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Spread {
    /// The set's area-weighted mean translation (an interpolation element).
    Mean,
    /// Shared over the set's nodes by tributary area (to ground only).
    Area,
    /// Along the normal of the face borne on only, shared by tributary area: a sliding
    /// abutment (module docs).
    Normal,
}

/// A spring of a part (module docs).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Spring {
    /// Node set of the first end.
    pub set: String,
    /// Node set of the second end, on the same part; `None`: ground.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub to: Option<String>,
    /// Total stiffness along the three axes (N/m).
    pub stiffness: [f64; 3],
    /// The axes, as three orthonormal unit vectors; `None`: x, y, z.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axes: Option<[[f64; 3]; 3]>,
    /// How the ends' motions are taken from their sets.
    pub spread: Spread,
}

/// One rank-one term `k (c · u)²` of the springs' energy (twice it), `c · u = Σ w · u_node`.
#[derive(Clone, Debug, PartialEq)]
pub struct SpringTerm {
    /// Stiffness (N/m).
    pub k: f64,
    /// The node (index into the mesh) and the vector `w` its displacement is dotted with.
    pub entries: Vec<(u32, [f64; 3])>,
}

/// How far the axes may be from orthonormal (round-off of three written unit vectors).
const ORTHONORMAL: f64 = 1e-9;

/// What a [`Spring`] stands for in messages: a spring (stiffness, N/m) or a damper (its
/// damping coefficient in the stiffness's place, N s/m; [`crate::dampers`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Element {
    /// A spring.
    Spring,
    /// A viscous damper.
    Damper,
}

impl Element {
    fn noun(self) -> &'static str {
        match self {
            Element::Spring => "spring",
            Element::Damper => "damper",
        }
    }

    fn value(self) -> &'static str {
        match self {
            Element::Spring => "stiffness",
            Element::Damper => "damping",
        }
    }

    fn unit(self) -> &'static str {
        match self {
            Element::Spring => "N/m",
            Element::Damper => "N s/m",
        }
    }
}

fn spring_error(e: Element, s: &Spring, message: impl std::fmt::Display) -> ReduceError {
    let to = s.to.as_deref().unwrap_or("ground");
    ReduceError::Options(format!("{} from {} to {to}: {message}", e.noun(), s.set))
}

/// The shares `α_n` of a set's nodes: tributary areas over the set's area when it is a face,
/// else equal.
fn shares(mesh: &Mesh, set: &str) -> Result<Vec<(u32, f64)>, ReduceError> {
    let nodes = mesh
        .node_set(set)
        .ok_or_else(|| InterfaceError::MissingSet(set.to_string()))?;
    if nodes.is_empty() {
        return Err(ReduceError::Options(format!("node set {set} is empty")));
    }
    Ok(match face_nodes(mesh, set) {
        Ok(face) if !face.is_empty() => {
            let total: f64 = face.iter().map(|f| f.area).sum();
            face.iter().map(|f| (f.node, f.area / total)).collect()
        }
        _ => nodes
            .iter()
            .map(|&n| (n, 1.0 / nodes.len() as f64))
            .collect(),
    })
}

/// Checks a spring's numbers: stiffnesses finite, `>= 0`, not all zero; axes orthonormal; an
/// `Area` spring goes to ground.
fn check(e: Element, s: &Spring) -> Result<(), ReduceError> {
    let k = s.stiffness;
    if k.iter().any(|x| !(x.is_finite() && *x >= 0.0)) || k.iter().all(|x| *x == 0.0) {
        return Err(spring_error(
            e,
            s,
            format!(
                "{} [{}, {}, {}] {} must be three values >= 0, not all zero",
                e.value(),
                k[0],
                k[1],
                k[2],
                e.unit()
            ),
        ));
    }
    if let Some(a) = &s.axes {
        for i in 0..3 {
            for j in 0..3 {
                let d: f64 = (0..3).map(|c| a[i][c] * a[j][c]).sum();
                let want = if i == j { 1.0 } else { 0.0 };
                if (d - want).abs() > ORTHONORMAL || d.is_nan() {
                    return Err(spring_error(
                        e,
                        s,
                        format!(
                            "axes {} and {} have dot product {d:.3e}, not {want}: give three orthonormal unit vectors",
                            i + 1,
                            j + 1
                        ),
                    ));
                }
            }
        }
    }
    if s.spread == Spread::Normal && (k[1] != 0.0 || k[2] != 0.0 || s.axes.is_some()) {
        return Err(spring_error(
            e,
            s,
            format!(
                "a sliding abutment (normal spread) has one {}, along the normal of the face it bears on: give [value, 0, 0] and no axes",
                e.value()
            ),
        ));
    }
    if s.spread == Spread::Area && s.to.is_some() {
        return Err(spring_error(
            e,
            s,
            format!(
                "a {} spread by area goes to ground; between two sets use the mean spread",
                e.noun()
            ),
        ));
    }
    Ok(())
}

/// The rank-one terms of `springs` on `mesh` (module docs), spring by spring, axis by axis
/// (axes without stiffness left out).
pub fn spring_terms(mesh: &Mesh, springs: &[Spring]) -> Result<Vec<SpringTerm>, ReduceError> {
    terms_of(Element::Spring, mesh, springs)
}

/// [`spring_terms`] of springs or dampers (`e`, for the messages).
pub(crate) fn terms_of(
    e: Element,
    mesh: &Mesh,
    springs: &[Spring],
) -> Result<Vec<SpringTerm>, ReduceError> {
    const GLOBAL: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut out = Vec::new();
    for s in springs {
        check(e, s)?;
        if s.spread == Spread::Normal {
            out.extend(normal_terms(e, mesh, s)?);
            continue;
        }
        let axes = s.axes.unwrap_or(GLOBAL);
        let a = shares(mesh, &s.set)?;
        let b = match &s.to {
            Some(to) => shares(mesh, to)?,
            None => Vec::new(),
        };
        for (e, &k) in axes.iter().zip(&s.stiffness).filter(|(_, k)| **k > 0.0) {
            if s.spread == Spread::Area {
                out.extend(a.iter().map(|&(n, w)| SpringTerm {
                    k: k * w,
                    entries: vec![(n, *e)],
                }));
            } else {
                out.push(SpringTerm {
                    k,
                    entries: a
                        .iter()
                        .map(|&(n, w)| (n, e.map(|x| w * x)))
                        .chain(b.iter().map(|&(n, w)| (n, e.map(|x| -w * x))))
                        .collect(),
                });
            }
        }
    }
    Ok(out)
}

/// The terms of a sliding abutment (`Spread::Normal`, module docs).
fn normal_terms(e: Element, mesh: &Mesh, s: &Spring) -> Result<Vec<SpringTerm>, ReduceError> {
    let face = face_nodes(mesh, &s.set)?;
    if face.is_empty() {
        return Err(spring_error(
            e,
            s,
            "a sliding abutment needs a face: the set has no boundary faces",
        ));
    }
    let total: f64 = face.iter().map(|f| f.area).sum();
    let k = s.stiffness[0];
    let Some(to) = &s.to else {
        return Ok(face
            .iter()
            .map(|f| SpringTerm {
                k: k * f.area / total,
                entries: vec![(f.node, f.normal)],
            })
            .collect());
    };
    let surface = Surface::new(mesh, to)?;
    let master = mesh
        .node_set(to)
        .ok_or_else(|| InterfaceError::MissingSet(to.clone()))?;
    let tolerance = 0.01 * crate::tie::extent(mesh, master);
    let mut out = Vec::with_capacity(face.len());
    for f in &face {
        let p = surface.project(mesh.nodes[f.node as usize]);
        if p.distance > tolerance || p.outside > tolerance {
            return Err(spring_error(
                e,
                s,
                format!(
                    "node {} lies {:.3e} m from the face it bears on ({:.3e} m beyond its edge), more than 1 % of that face's extent ({tolerance:.3e} m): check the sets",
                    mesh.node_ids[f.node as usize], p.distance, p.outside
                ),
            ));
        }
        let nu = p.normal;
        let mut entries = vec![(f.node, nu)];
        entries.extend(p.weights.iter().map(|&(i, w)| (i, nu.map(|x| -w * x))));
        out.push(SpringTerm {
            k: k * f.area / total,
            entries,
        });
    }
    Ok(out)
}
