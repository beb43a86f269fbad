//! Whether a part's restraints hold it: the rigid-body motions they leave free, found from the
//! restraints and the boundary coordinates alone, before any assembly or factorization.
//!
//! The reduction factors the interior stiffness `K_vv` (eq. 3's `K_II`, with the footprint
//! springs of [`crate::craig_bampton`]'s module docs): `K'` on the free dofs that are neither
//! restrained nor eliminated as boundary dofs. Extend an interior vector `v` by zero on the
//! eliminated and restrained dofs to `u`; then `vᵀ K_vv v = uᵀ K u + Σ_f ρ_f (c_f u)²`, and since
//! `K` is positive semi-definite, `K_vv v = 0` exactly when `K u = 0` and every footprint row
//! `c_f u = 0`. For a part that is one connected body `K u = 0` means `u` is a rigid motion,
//! `u(x) = t + θ × (x − c)`. So `K_vv` is singular exactly when some rigid motion `(t, θ) ≠ 0`
//! meets every condition
//!
//! - a restrained direction `w` at node `x` (a deleted dof, `w = e_d`, or a held axis of a node
//!   in its own axes): `w · u(x) = w · t + θ · ((x − c) × w) = 0`;
//! - a boundary coordinate eliminated from the interior (a contact node's, a piston node's
//!   dof `w` at `x`): the same row;
//! - a footprint's mean motion `Σ_k c_k w_k · u(x_k) = 0`;
//! - a support's spring along `e_d` at node `x` ([`crate::tie`]): `e_d · u(x) = 0`, since
//!   the spring adds `k (e_d · u)²` to the energy;
//! - a spring's term `k (c · u)²` ([`crate::springs`]): `Σ_n w_n · u(x_n) = 0` (a spring
//!   between two sets of the part cancels on translations and holds rotations only).
//!
//! (A contact patch's mean motion is a constraint on the interior, not part of `K_vv`: it does
//! not hold the part there.) These are the rows `a` of a matrix `A` on the six unknowns
//! `(t, L θ)`, `L` the part's largest extent so that all six are lengths; the motions left free
//! are the null space of `A`, found from the eigenvectors of the 6 × 6 `Σ â âᵀ` (rows scaled to
//! unit length) whose eigenvalues are below `1e-10` of the largest. A held motion has an
//! eigenvalue of at least its rows' count times `(arm / L)²`, well above that for any
//! restraint not set within `1e-5 L` of the axis it must hold; round-off leaves a free
//! motion's eigenvalue near `1e-16` of the largest.
//!
//! The null space is shown in a canonical basis: reduced row echelon form on the rotation
//! components first (x, y, z), so that rotations about coordinate axes are named by their
//! axis, then on the translations. A rotation `(t, θ)` is about the axis along `θ` through
//! `p = c + θ × t / |θ|²` (the point of the axis nearest `c`).
//!
//! A part of several bodies not connected by elements has more rigid motions than these six;
//! this check does not see them, and the factorization still refuses such a part
//! ([`ReduceError::NotConnected`]).

use crate::craig_bampton::{
    FreeDofs, PartSpec, ReduceError, Row, boundary_rows, piston_frames, skew_restraints,
};
use faer::{Mat, Side};
use squeal_element::geometry::{cross, norm};
use squeal_fe::frames::{AxisDirection, DofTransform, HeldNodes};
use squeal_fe::{DofMap, DofStatus};
use squeal_mesh::Mesh;
use std::fmt;

/// A rigid-body motion of a part that its restraints leave free.
#[derive(Clone, Debug, PartialEq)]
pub enum FreeMotion {
    /// A translation along a unit direction.
    Translation {
        /// Unit direction.
        direction: [f64; 3],
    },
    /// A rotation about an axis.
    Rotation {
        /// Unit direction of the axis.
        axis: [f64; 3],
        /// The point of the axis nearest the part's centre of nodes (m in an SI mesh).
        point: [f64; 3],
    },
}

/// Components below this (of a unit vector) are shown as 0.
const ROUND: f64 = 1e-9;

fn direction_name(d: [f64; 3]) -> String {
    match (0..3).find(|&k| (0..3).all(|e| e == k || d[e].abs() <= ROUND)) {
        Some(k) => ["x", "y", "z"][k].to_string(),
        None => format!("({:.4}, {:.4}, {:.4})", d[0], d[1], d[2]),
    }
}

fn clean(x: f64) -> f64 {
    if x.abs() < 1e-12 { 0.0 } else { x }
}

impl fmt::Display for FreeMotion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FreeMotion::Translation { direction } => {
                write!(f, "translation along {}", direction_name(*direction))
            }
            FreeMotion::Rotation { axis, point } => write!(
                f,
                "rotation about {} through ({:.6}, {:.6}, {:.6}) m",
                direction_name(*axis),
                clean(point[0]),
                clean(point[1]),
                clean(point[2])
            ),
        }
    }
}

/// The rigid-body motions of `mesh` that the restraints and boundary coordinates of `spec`
/// leave free (module docs), in the canonical basis: rotations first (about x, y, z when the
/// free rotations are about coordinate axes), then translations. Empty when the part is held.
/// Errors: a set `spec` names is missing, or an interface error, as the reduction would give.
pub fn free_motions(mesh: &Mesh, spec: &PartSpec) -> Result<Vec<FreeMotion>, ReduceError> {
    let mut held = HeldNodes::new(mesh, &spec.restraints, &skew_restraints(mesh, spec)?)?;
    piston_frames(mesh, spec, &mut held)?;
    let dofmap = DofMap::new(mesh, &held.restraints)?;
    let free = FreeDofs {
        dofmap: &dofmap,
        transform: held.has_frames().then(|| DofTransform::new(&dofmap, &held)),
    };
    let (_, rows) = boundary_rows(mesh, &free, spec)?;
    let springs = crate::tie::support_springs(mesh, &spec.supports)?;
    let terms = crate::springs::spring_terms(mesh, &spec.springs)?;
    Ok(free_motions_of(mesh, &free, &held, &rows, &springs, &terms))
}

/// [`free_motions`], as an error naming them and what to add when there are any.
pub fn require_held(mesh: &Mesh, spec: &PartSpec) -> Result<(), ReduceError> {
    let free = free_motions(mesh, spec)?;
    match free.is_empty() {
        true => Ok(()),
        false => Err(not_held(spec, &free)),
    }
}

/// The error of part `spec` with rigid motions `free` left free: the motions, the part's
/// restraints and what to add.
pub fn not_held(spec: &PartSpec, free: &[FreeMotion]) -> ReduceError {
    let motions = free
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("; ");
    let mut add = Vec::new();
    let translations: Vec<String> = free
        .iter()
        .filter_map(|m| match m {
            FreeMotion::Translation { direction } => Some(direction_name(*direction)),
            _ => None,
        })
        .collect();
    if !translations.is_empty() {
        add.push(format!(
            "hold some nodes along {} (a restraint, or pistons pressing along it)",
            translations.join(" and ")
        ));
    }
    if free
        .iter()
        .any(|m| matches!(m, FreeMotion::Rotation { .. }))
    {
        add.push(
            "hold nodes away from each axis in the direction the rotation moves them \
             (a point at x moves along axis × (x − point)): press or hold the part at two or \
             more places on either side of the axis (several pistons or footprints, a \
             restraint along the normal on a second set) rather than over one face whose \
             mean motion is all that is kept"
                .to_string(),
        );
    }
    ReduceError::NotHeld {
        part: spec.name.clone(),
        count: free.len(),
        motions,
        held: describe(spec),
        add: add.join("; "),
    }
}

/// The free rigid motions of a part whose free dofs are `free`, held as `held`, with boundary
/// rows `rows` (module docs).
pub(crate) fn free_motions_of(
    mesh: &Mesh,
    free: &FreeDofs,
    held: &HeldNodes,
    rows: &[Row],
    springs: &std::collections::BTreeMap<u32, [f64; 3]>,
    terms: &[crate::springs::SpringTerm],
) -> Vec<FreeMotion> {
    let used = mesh.used_nodes();
    let (centre, length) = centre_and_length(mesh, &used);
    let mut gram = [[0.0f64; 6]; 6];
    let mut add = |a: [f64; 6]| {
        let n2: f64 = a.iter().map(|x| x * x).sum();
        if n2 > 0.0 && n2.is_finite() {
            for i in 0..6 {
                for j in 0..6 {
                    gram[i][j] += a[i] * a[j] / n2;
                }
            }
        }
    };
    let row_of = |node: u32, w: [f64; 3]| -> [f64; 6] {
        let x = mesh.nodes[node as usize];
        let r = [x[0] - centre[0], x[1] - centre[1], x[2] - centre[2]];
        let m = cross(r, w);
        [
            w[0],
            w[1],
            w[2],
            m[0] / length,
            m[1] / length,
            m[2] / length,
        ]
    };
    let dofmap = free.dofmap;
    for node in (0..mesh.num_nodes()).filter(|&n| used[n]) {
        for d in 0..3 {
            if dofmap.status(node as u32, d) == DofStatus::Restrained {
                add(row_of(node as u32, unit_axis(d)));
            }
        }
    }
    for (&node, frame) in &held.frames {
        for axis in frame.axes.iter().take(frame.held) {
            add(row_of(node, *axis));
        }
    }
    // A support's spring holds its node along each direction it has stiffness in.
    for (&node, k) in springs {
        for d in (0..3).filter(|&d| k[d] > 0.0) {
            add(row_of(node, unit_axis(d)));
        }
    }
    // A spring's term `k (c · u)²` holds the motions with `c · u ≠ 0` ([`crate::springs`]):
    // between two sets of the part, not its translations.
    for term in terms {
        let mut a = [0.0; 6];
        for &(node, w) in &term.entries {
            let b = row_of(node, w);
            (0..6).for_each(|i| a[i] += b[i]);
        }
        // Cancelled to round-off (a translation between two sets of the part): holds nothing.
        let size: f64 = term
            .entries
            .iter()
            .map(|e| e.1.iter().map(|x| x.abs()).sum::<f64>())
            .sum();
        if a.iter().map(|x| x.abs()).sum::<f64>() > 1e-12 * size {
            add(a);
        }
    }
    let physical = physical_coordinates(free);
    for r in rows {
        let holds = r.footprint || matches!(r.entries.as_slice(), &[(_, c)] if c != 0.0);
        if !holds {
            continue;
        }
        let mut a = [0.0; 6];
        for &(q, c) in &r.entries {
            if let Some(&(node, w)) = physical.get(q) {
                let b = row_of(node, w);
                (0..6).for_each(|i| a[i] += c * b[i]);
            }
        }
        add(a);
    }
    null_motions(&gram, centre, length)
}

/// The node and physical direction of each free coordinate of `free`.
fn physical_coordinates(free: &FreeDofs) -> Vec<(u32, [f64; 3])> {
    let dofmap = free.dofmap;
    let mut out = vec![(0u32, [0.0; 3]); free.num_free()];
    for f in 0..dofmap.num_free() {
        let Some((node, dir)) = dofmap.node_dir(f) else {
            continue;
        };
        match &free.transform {
            None => out[f] = (node, unit_axis(dir)),
            Some(t) => {
                if let Some(n) = t.new_dof(f) {
                    out[n] = (node, unit_axis(dir));
                } else if let Some(kept) = t.kept(node) {
                    for &(n, e) in kept {
                        out[n] = (node, e);
                    }
                }
            }
        }
    }
    out
}

fn unit_axis(d: usize) -> [f64; 3] {
    let mut e = [0.0; 3];
    e[d] = 1.0;
    e
}

/// The mean of the used nodes and the largest extent of their bounding box (1 if none).
fn centre_and_length(mesh: &Mesh, used: &[bool]) -> ([f64; 3], f64) {
    let mut sum = [0.0; 3];
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let mut count = 0usize;
    for (x, _) in mesh.nodes.iter().zip(used).filter(|(_, u)| **u) {
        for d in 0..3 {
            sum[d] += x[d];
            lo[d] = lo[d].min(x[d]);
            hi[d] = hi[d].max(x[d]);
        }
        count += 1;
    }
    if count == 0 {
        return ([0.0; 3], 1.0);
    }
    let length = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    (
        sum.map(|s| s / count as f64),
        if length > 0.0 { length } else { 1.0 },
    )
}

/// Relative size under which an eigenvalue of the Gram matrix counts as zero (module docs).
const NULL_TOLERANCE: f64 = 1e-10;
/// Pivot size (of unit null vectors) under which a component counts as zero in the echelon
/// form.
const PIVOT_TOLERANCE: f64 = 1e-6;

/// The null space of `gram` (on `(t, L θ)`) as motions, in the canonical basis.
fn null_motions(gram: &[[f64; 6]; 6], centre: [f64; 3], length: f64) -> Vec<FreeMotion> {
    let g = Mat::<f64>::from_fn(6, 6, |i, j| gram[i][j]);
    let Ok(evd) = g.self_adjoint_eigen(Side::Lower) else {
        return Vec::new();
    };
    let largest = (0..6).map(|i| evd.S()[i]).fold(0.0, f64::max);
    // Rows of the null basis, columns ordered (Lθx, Lθy, Lθz, tx, ty, tz): rotations first.
    let mut basis: Vec<[f64; 6]> = (0..6)
        .filter(|&i| evd.S()[i] <= NULL_TOLERANCE * largest)
        .map(|i| {
            let u = |k: usize| evd.U()[(k, i)];
            [u(3), u(4), u(5), u(0), u(1), u(2)]
        })
        .collect();
    reduce_rows(&mut basis);
    basis
        .into_iter()
        .filter_map(|b| {
            let phi = [b[0], b[1], b[2]];
            let t = [b[3], b[4], b[5]];
            let nphi = norm(phi);
            if nphi > PIVOT_TOLERANCE {
                let theta = phi.map(|x| x / length);
                let n2 = norm(theta).powi(2);
                let m = cross(theta, t);
                Some(FreeMotion::Rotation {
                    axis: sign_up(phi.map(|x| x / nphi)),
                    point: [0, 1, 2].map(|d| centre[d] + m[d] / n2),
                })
            } else {
                let nt = norm(t);
                (nt > PIVOT_TOLERANCE).then(|| FreeMotion::Translation {
                    direction: sign_up(t.map(|x| x / nt)),
                })
            }
        })
        .collect()
}

/// `d` or `-d`, whichever has its largest component positive.
fn sign_up(d: [f64; 3]) -> [f64; 3] {
    let k = (0..3)
        .max_by(|&a, &b| d[a].abs().total_cmp(&d[b].abs()))
        .unwrap_or(0);
    if d[k] < 0.0 { d.map(|x| -x) } else { d }
}

/// Reduced row echelon form of `rows` in place (partial pivoting, pivots below
/// [`PIVOT_TOLERANCE`] skipped), components below it set to zero.
fn reduce_rows(rows: &mut [[f64; 6]]) {
    let mut top = 0;
    for col in 0..6 {
        if top == rows.len() {
            break;
        }
        let Some(p) =
            (top..rows.len()).max_by(|&a, &b| rows[a][col].abs().total_cmp(&rows[b][col].abs()))
        else {
            break;
        };
        if rows[p][col].abs() <= PIVOT_TOLERANCE {
            continue;
        }
        rows.swap(top, p);
        let pivot = rows[top][col];
        rows[top] = rows[top].map(|x| x / pivot);
        for r in 0..rows.len() {
            if r != top {
                let f = rows[r][col];
                let pr = rows[top];
                rows[r] = std::array::from_fn(|k| rows[r][k] - f * pr[k]);
            }
        }
        top += 1;
    }
    for r in rows.iter_mut() {
        for x in r.iter_mut() {
            if x.abs() <= PIVOT_TOLERANCE * 1e-3 {
                *x = 0.0;
            }
        }
    }
}

/// A part's restraints as the scene or the options give them (`node set CLAMP held along x,
/// y, z`, `node set ABUTMENT held radial, tangential`) and its pistons, for messages.
pub(crate) fn describe(spec: &PartSpec) -> String {
    use squeal_fe::NodeSelection;
    let axes = |d: &[bool; 3]| -> Vec<&str> {
        (0..3)
            .filter(|&i| d[i])
            .map(|i| ["x", "y", "z"][i])
            .collect()
    };
    let mut out: Vec<String> = spec
        .restraints
        .iter()
        .map(|r| {
            let nodes = match &r.nodes {
                NodeSelection::Set(s) => format!("node set {s}"),
                NodeSelection::Indices(v) => format!("{} nodes given by index", v.len()),
            };
            format!("{nodes} held along {}", axes(&r.directions).join(", "))
        })
        .collect();
    for (set, dirs) in &spec.skew_restraints {
        out.push(format!(
            "node set {set} held along {} skew direction(s)",
            dirs.len()
        ));
    }
    for (set, dirs) in &spec.axis_restraints {
        let names: Vec<&str> = dirs
            .iter()
            .map(|d| match d {
                AxisDirection::Axial => "axial",
                AxisDirection::Radial => "radial",
                AxisDirection::Tangential => "tangential",
            })
            .collect();
        out.push(format!("node set {set} held {}", names.join(", ")));
    }
    if !spec.piston_footprints.is_empty() {
        out.push(format!(
            "the mean normal motion of {} piston footprint(s) kept",
            spec.piston_footprints.len()
        ));
    } else if let Some(p) = &spec.piston_set {
        out.push(format!("the normal motion of the nodes of {p} kept"));
    }
    if out.is_empty() {
        return "no restraint".into();
    }
    out.join("; ")
}
