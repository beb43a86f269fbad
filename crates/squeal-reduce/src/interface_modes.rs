//! Interface reduction: characteristic constraint (CC) modes of a part's contact face.
//!
//! # Why
//!
//! With nodal contact (`[model] interface = "nodal"`) every node of a contact face keeps its
//! three dofs as Craig–Bampton boundary coordinates (eqs (1)–(7) of Coudeyras, Sinou & Nacivet
//! 2009): the coarse bundled brake has 3 × 355 face dofs on the disc and as many on the pad,
//! 2234 reduced dofs in all, and the count grows with every refinement of the contact. The
//! motion of a contact face in the band of interest is smooth on the scale of its nodes, so a
//! few interface shapes carry it.
//!
//! # Which basis, and why this one
//!
//! Two bases are in use: the characteristic constraint modes of each component's interface
//! (Castanier, Tan & Pierre, "Characteristic constraint modes for component mode synthesis",
//! AIAA Journal 39(6), 2001, pp. 1182–1187), and a system-level basis of the assembled
//! structure's real modes with the contact springs at equilibrium, as commercial complex
//! eigenvalue analysis (CEA) projects onto. We take the CC modes, per part, for three reasons:
//!
//! 1. They keep the brake block-diagonal by part: each part's coordinates stay its own, so its
//!    shapes expand onto its mesh with its own basis, energies are shared by part, and the
//!    static equilibrium under friction (which moves with μ) is still solved with the parts'
//!    fixed-interface modes and interface shapes — a system-mode basis taken at μ = 0 would
//!    need static correction vectors for the μ-dependent equilibrium.
//! 2. They are a Rayleigh–Ritz projection of the Craig–Bampton model: the frictionless brake's
//!    frequencies converge from above, monotonically in the number kept (checked in the tests),
//!    and with every CC mode kept the model is the unreduced-interface one up to a change of
//!    coordinates.
//! 3. They need nothing of the contact law: the contact forces are still evaluated at every
//!    contact node and projected (below), whatever the element.
//!
//! # The maths
//!
//! A part's Craig–Bampton coordinates are `q = [x_c; x_p; η]`: the contact face's nodal dofs
//! `x_c` (for the disc the face points its projected contact points are formed from, for a
//! pad its contact points), the other kept boundary dofs `x_p` (the pistons) and the
//! fixed-interface modal amplitudes `η`; the reduced matrices are `K̂`, `M̂` of eqs (6)–(7).
//! The CC modes are the eigenvectors of the face partition of these matrices — the interface's
//! own stiffness and mass, the interior statically condensed and the other boundary dofs held:
//!
//! `K̂_cc ψ_j = λ_j M̂_cc ψ_j`,  `ψ_jᵀ M̂_cc ψ_k = δ_jk`,  `λ_1 ≤ λ_2 ≤ …`
//!
//! (`K̂_cc` is the Guyan stiffness of the face, `M̂_cc` its constraint-mode mass). The brake
//! uses the face *loaded by its contact* ([`characteristic_constraint_modes_loaded`]):
//! `(K̂_cc + K_s,cc) ψ = λ M̂_cc ψ`, `K_s = Σ_p k_t,p g_p g_pᵀ` the pairs' tangent springs at
//! the frictionless static equilibrium restricted to this part (the other part held, as the
//! other boundary dofs are). Measured on the coarse nodal brake (solved at unit norm, see
//! the solver's comment): 1.1e-2, 6.8e-3, 5.5e-3 in the worst of the 61 frictionless
//! frequencies below 16 kHz with 80, 160, 320 modes per part, `docs/reduction.md` — slow; the
//! pipeline's `"system"` basis ([`face_basis`] of the brake's own modes) is what converges.
//! Keeping the
//! `k` lowest, `x_c ≈ Ψ_k ξ`, the part's coordinates become `q = T q'`, `q' = [ξ; x_p; η]`,
//!
//! `T = [Ψ_k 0 0; 0 I 0; 0 0 I]`,  `K' = Tᵀ K̂ T`, `M' = Tᵀ M̂ T`,
//!
//! and its basis on the mesh `Φ' = Φ T`. The pencil is solved densely: `M̂_cc = L Lᵀ`,
//! `A = L⁻¹ K̂_cc L⁻ᵀ = Y Λ Yᵀ`, `Ψ = L⁻ᵀ Y`.
//!
//! A contact pair's closure `δ_p = g_pᵀ x − g0_p` (the brake's eq (8) with `g_p` over the
//! stacked parts' coordinates, [`squeal_brake`'s model]) becomes `δ_p = (Tᵀ g_p)ᵀ x' − g0_p`,
//! and eq (10)'s forces `Σ_p F_n,p g_p + F_t,p h_p` project to `Σ_p F_n,p Tᵀg_p + F_t,p Tᵀh_p`:
//! each pair's element is still evaluated at its own node from its own closure and slip, only
//! its vectors are expressed in the reduced coordinates. The pistons' load `F_piston` acts on
//! `x_p`, which `T` keeps, so `Tᵀ F_piston = F_piston`.
//!
//! How many CC modes each part keeps is chosen by convergence of the brake's results, not
//! here: see the pipeline's `interface` module.

use crate::craig_bampton::{ReduceError, hz};
use crate::rom::{Basis, DofLabel, PointRole, ReducedPart};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par, Side};
use squeal_eigs::dense::cholesky_lower;

/// A part's characteristic constraint modes: the eigenvectors of its contact face's
/// partition `(K̂_cc, M̂_cc)`, all of them, lowest first.
#[derive(Clone, Debug)]
pub struct InterfaceModes {
    /// The part's name.
    pub part: String,
    /// The part's reduced dofs that are contact-face motions (`x_c`), ascending.
    pub face_dofs: Vec<usize>,
    /// `Ψ`: `face_dofs.len()` rows, one column per mode, `M̂_cc`-orthonormal.
    pub psi: Mat<f64>,
    /// `λ_j = ω_j²` (rad²/s²), ascending.
    pub lambda: Vec<f64>,
    /// The part's reduced size before the change of coordinates.
    pub size: usize,
}

/// The reduced dofs of a part that move its contact face: `Point` dofs of its contact points
/// (a pad) or of its face points (a disc with nodal contact). Pistons (and a disc's projected
/// contact points, which own no dofs) are not among them.
pub fn face_dofs(part: &ReducedPart) -> Vec<usize> {
    let points = &part.info.points;
    part.info
        .dofs
        .iter()
        .enumerate()
        .filter(|(_, l)| match l {
            DofLabel::Point { point, .. } | DofLabel::Along { point, .. } => points
                .get(*point)
                .is_some_and(|p| matches!(p.role, PointRole::Contact | PointRole::Face)),
            DofLabel::Mode { .. } | DofLabel::Rotation { .. } => false,
        })
        .map(|(d, _)| d)
        .collect()
}

/// The CC modes of `part`'s contact face: the pencil `(K̂_cc, M̂_cc)` solved densely.
pub fn characteristic_constraint_modes(part: &ReducedPart) -> Result<InterfaceModes, ReduceError> {
    characteristic_constraint_modes_loaded(part, None)
}

/// The CC modes of the face loaded by a stiffness `K_s` on the part's reduced dofs (`size ×
/// size`; only its face block is used): the pencil `(K̂_cc + K_s,cc, M̂_cc)`. With `K_s` the
/// contact springs' tangent stiffness at the frictionless equilibrium, the other part held,
/// the modes are the face's shapes under its contact rather than free of it.
pub fn characteristic_constraint_modes_loaded(
    part: &ReducedPart,
    springs: Option<&Mat<f64>>,
) -> Result<InterfaceModes, ReduceError> {
    let name = part.info.name.clone();
    let invalid = |what: String| ReduceError::Invalid {
        part: name.clone(),
        what,
    };
    let c = face_dofs(part);
    if c.is_empty() {
        return Err(invalid(
            "no contact-face dofs to reduce (a patch interface has nothing to gain)".into(),
        ));
    }
    let nc = c.len();
    let extra = |i: usize, j: usize| springs.map_or(0.0, |s| s[(c[i], c[j])] + s[(c[j], c[i])]);
    let k = Mat::from_fn(nc, nc, |i, j| {
        0.5 * (part.k[(c[i], c[j])] + part.k[(c[j], c[i])] + extra(i, j))
    });
    let m = Mat::from_fn(nc, nc, |i, j| {
        0.5 * (part.m[(c[i], c[j])] + part.m[(c[j], c[i])])
    });
    let l = cholesky_lower(&m)
        .ok_or_else(|| invalid("the contact face's mass M_cc is not positive definite".into()))?;
    // A = L⁻¹ K L⁻ᵀ: X = L⁻¹ K, then A = L⁻¹ Xᵀ (K symmetric).
    let mut x = k;
    solve_lower_triangular_in_place(l.as_ref(), x.as_mut(), Par::Seq);
    let mut a = x.transpose().to_owned();
    solve_lower_triangular_in_place(l.as_ref(), a.as_mut(), Par::Seq);
    // faer 0.24.4's dense self-adjoint eigensolver loses accuracy above ~128 rows when the
    // matrix norm is far from 1 (the brake's `modal_basis` says the same): unscaled, the
    // coarse disc face's lowest 40 CC modes came out with relative residuals up to 0.95, so
    // "the lowest k" were not the lowest and the brake's error stalled near 2e-2. Solved at
    // unit max-norm, each pair's residual is checked.
    let scale = a.norm_max().max(f64::MIN_POSITIVE);
    let a = Mat::from_fn(nc, nc, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]) / scale);
    let evd = a
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| invalid("the dense eigensolver of the CC modes did not converge".into()))?;
    let worst = largest_residual(&a, evd.U(), evd.S());
    if worst.is_nan() || worst > RESIDUAL_TOLERANCE {
        return Err(invalid(format!(
            "the CC modes' eigenpairs are inaccurate (largest residual {worst:.1e} of the unit-norm pencil)"
        )));
    }
    let mut psi = evd.U().to_owned();
    solve_upper_triangular_in_place(l.transpose(), psi.as_mut(), Par::Seq);
    fix_signs(&mut psi);
    let lambda = (0..nc).map(|j| evd.S()[j] * scale).collect();
    Ok(InterfaceModes {
        part: part.info.name.clone(),
        face_dofs: c,
        psi,
        lambda,
        size: part.size(),
    })
}

/// Largest residual `‖A y − s y‖` of an eigendecomposition of a symmetric `A` of unit max-norm
/// accepted for the CC modes (the brake's own modal basis asks 1e-12 of its smaller pencils).
pub const RESIDUAL_TOLERANCE: f64 = 1e-10;

/// Largest `‖A y_j − s_j y_j‖` over the eigenpairs.
fn largest_residual(
    a: &Mat<f64>,
    y: faer::MatRef<'_, f64>,
    s: faer::diag::DiagRef<'_, f64>,
) -> f64 {
    let ay = a * y;
    (0..a.nrows())
        .map(|j| {
            (0..a.nrows())
                .map(|i| (ay[(i, j)] - s[j] * y[(i, j)]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max)
}

impl InterfaceModes {
    /// Number of CC modes (= contact-face dofs).
    pub fn count(&self) -> usize {
        self.lambda.len()
    }

    /// The CC modes' frequencies `√λ_j / 2π` (Hz).
    pub fn frequencies_hz(&self) -> Vec<f64> {
        self.lambda.iter().map(|&l| hz(l)).collect()
    }

    /// `T` keeping the `keep` lowest CC modes (at most all): `size × (keep + others)`, the CC
    /// amplitudes `ξ` first, then the part's other dofs (pistons, modal amplitudes) in their
    /// order, each an identity column.
    pub fn transformation(&self, keep: usize) -> Mat<f64> {
        let keep = keep.min(self.count());
        let others: Vec<usize> = (0..self.size)
            .filter(|d| self.face_dofs.binary_search(d).is_err())
            .collect();
        let mut t = Mat::zeros(self.size, keep + others.len());
        for j in 0..keep {
            for (i, &d) in self.face_dofs.iter().enumerate() {
                t[(d, j)] = self.psi[(i, j)];
            }
        }
        for (j, &d) in others.iter().enumerate() {
            t[(d, keep + j)] = 1.0;
        }
        t
    }
}

/// The part in the coordinates `q = T q'`: `K' = Tᵀ K̂ T`, `M' = Tᵀ M̂ T` (symmetrized) and its
/// basis `Φ T`. Its [`crate::rom::PartInfo`] is kept as it was (points, labels and frequencies
/// of the Craig–Bampton model): `info.dofs` then no longer labels the coordinates, which its
/// length (different from [`ReducedPart::size`]) tells.
pub fn transformed_part(part: &ReducedPart, t: &Mat<f64>) -> ReducedPart {
    let project = |a: &Mat<f64>| {
        let b = t.transpose() * (a * t);
        let n = b.nrows();
        Mat::from_fn(n, n, |i, j| 0.5 * (b[(i, j)] + b[(j, i)]))
    };
    ReducedPart {
        info: part.info.clone(),
        k: project(&part.k),
        m: project(&part.m),
        basis: part.basis.as_ref().map(|b| Basis {
            dof_node: b.dof_node.clone(),
            dof_dir: b.dof_dir.clone(),
            values: &b.values * t,
        }),
    }
}

/// Relative size below which a direction of the Gram matrix `Vᵀ M̂_cc V` of face vectors is
/// taken as already spanned by the others (its square root: 1e-5 of the largest, in the
/// `M̂_cc` norm of unit-normalized columns) and dropped.
pub const SPAN_TOLERANCE: f64 = 1e-10;

/// The face basis spanned by `vectors` (one column per vector over `part`'s contact-face
/// dofs, in [`face_dofs`] order; e.g. the face motion of the assembled brake's modes): each
/// column scaled to unit `M̂_cc` norm, `M̂_cc`-orthonormalized through the eigenvectors of its
/// Gram matrix `G = Vᵀ M̂_cc V = Q D Qᵀ` (directions with `d < SPAN_TOLERANCE · d_max` dropped:
/// a face restriction of system vectors is often rank-deficient), `W = V Q D^{-1/2}`, then the
/// Rayleigh–Ritz modes of the face partition on that span, `(Wᵀ K̂_cc W) y = λ y`, `Ψ = W Y`,
/// lowest first. The result is used as the part's [`InterfaceModes`], all of them kept.
pub fn face_basis(part: &ReducedPart, vectors: &Mat<f64>) -> Result<InterfaceModes, ReduceError> {
    face_basis_keeping(part, vectors, 0)
}

/// Below this `M̂_cc` norm (of a unit column) a kept vector's part outside the span of the
/// others is round-off, and not added ([`face_basis_keeping`]).
pub const KEPT_RESIDUAL: f64 = 1e-12;

/// [`face_basis`], with the last `exact` columns of `vectors` in the span exactly: the Gram
/// matrix's dropped directions may hold up to about `√SPAN_TOLERANCE` (1e-5) of a vector, and a
/// vector that must be represented exactly (the static equilibrium `x_0` of the `"system"`
/// basis: without it the reduced brake's equilibrium, hence its contact springs, differ from
/// the unreduced brake's, 2.6e-4 of the largest normal force on the caliper corner, and its
/// frequencies are no longer bounded by the unreduced ones) has that part, `M̂_cc`-orthogonal
/// to the kept directions, added as a direction of its own when its norm is above
/// [`KEPT_RESIDUAL`].
pub fn face_basis_keeping(
    part: &ReducedPart,
    vectors: &Mat<f64>,
    exact: usize,
) -> Result<InterfaceModes, ReduceError> {
    let name = part.info.name.clone();
    let invalid = |what: String| ReduceError::Invalid {
        part: name.clone(),
        what,
    };
    let c = face_dofs(part);
    let (nc, nv) = (c.len(), vectors.ncols());
    if nc == 0 || vectors.nrows() != nc || nv == 0 {
        return Err(invalid(format!(
            "{nv} face vectors of {} rows for {nc} contact-face dofs",
            vectors.nrows()
        )));
    }
    let sym = |a: &Mat<f64>| Mat::from_fn(nc, nc, |i, j| 0.5 * (a[(c[i], c[j])] + a[(c[j], c[i])]));
    let (k, m) = (sym(&part.k), sym(&part.m));
    let mv = &m * vectors;
    let norm: Vec<f64> = (0..nv)
        .map(|j| {
            (0..nc)
                .map(|i| vectors[(i, j)] * mv[(i, j)])
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let v = Mat::from_fn(nc, nv, |i, j| {
        if norm[j] > 0.0 {
            vectors[(i, j)] / norm[j]
        } else {
            0.0
        }
    });
    let g = v.transpose() * (&m * &v);
    let (d, q) =
        symmetric_eigen(&g).ok_or_else(|| invalid("the face vectors' Gram matrix".into()))?;
    let top = d.iter().cloned().fold(0.0, f64::max);
    let kept: Vec<usize> = (0..nv).filter(|&j| d[j] > SPAN_TOLERANCE * top).collect();
    let w = Mat::from_fn(nc, kept.len(), |i, col| {
        let j = kept[col];
        (0..nv).map(|l| v[(i, l)] * q[(l, j)]).sum::<f64>() / d[j].sqrt()
    });
    let w = with_exact(w, &v, &m, exact.min(nv));
    let a = w.transpose() * (&k * &w);
    let (lambda, y) =
        symmetric_eigen(&a).ok_or_else(|| invalid("the face basis' Rayleigh–Ritz modes".into()))?;
    let mut psi = &w * &y;
    fix_signs(&mut psi);
    Ok(InterfaceModes {
        part: part.info.name.clone(),
        face_dofs: c,
        psi,
        lambda,
        size: part.size(),
    })
}

/// `w` (`M`-orthonormal columns) with the part of each of the last `exact` columns of `v` (unit
/// `M` norm) outside its span added as a column of its own, `M`-orthonormalized (twice, for
/// the round-off of one pass), when its norm is above [`KEPT_RESIDUAL`].
fn with_exact(mut w: Mat<f64>, v: &Mat<f64>, m: &Mat<f64>, exact: usize) -> Mat<f64> {
    let nc = v.nrows();
    for j in v.ncols() - exact..v.ncols() {
        let mut r = Mat::from_fn(nc, 1, |i, _| v[(i, j)]);
        for _ in 0..2 {
            let c = w.transpose() * (m * &r);
            r -= &w * &c;
        }
        let norm = (r.transpose() * (m * &r))[(0, 0)].max(0.0).sqrt();
        if norm > KEPT_RESIDUAL {
            let cols = w.ncols();
            w = Mat::from_fn(nc, cols + 1, |i, col| {
                if col < cols {
                    w[(i, col)]
                } else {
                    r[(i, 0)] / norm
                }
            });
        }
    }
    w
}

/// Eigenvalues (ascending) and eigenvectors of a symmetric matrix, solved at unit max-norm and
/// checked to [`RESIDUAL_TOLERANCE`]; `None` when the solver fails or is inaccurate.
fn symmetric_eigen(a: &Mat<f64>) -> Option<(Vec<f64>, Mat<f64>)> {
    let n = a.nrows();
    let scale = a.norm_max().max(f64::MIN_POSITIVE);
    let s = Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]) / scale);
    let evd = s.self_adjoint_eigen(Side::Lower).ok()?;
    (largest_residual(&s, evd.U(), evd.S()) <= RESIDUAL_TOLERANCE).then(|| {
        (
            (0..n).map(|j| evd.S()[j] * scale).collect(),
            evd.U().to_owned(),
        )
    })
}

/// A sign per column, so that results do not depend on the eigensolver's: the largest entry
/// positive.
fn fix_signs(psi: &mut Mat<f64>) {
    let n = psi.nrows();
    for j in 0..psi.ncols() {
        let (mut big, mut at) = (0.0f64, 0);
        for i in 0..n {
            if psi[(i, j)].abs() > big {
                big = psi[(i, j)].abs();
                at = i;
            }
        }
        if psi[(at, j)] < 0.0 {
            for i in 0..n {
                psi[(i, j)] = -psi[(i, j)];
            }
        }
    }
}
