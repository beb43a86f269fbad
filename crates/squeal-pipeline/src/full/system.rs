//! The `"system"` interface basis's vectors computed on the full finite-element brake
//! ([`super::FullBrake`], sparse) instead of on the Craig–Bampton brake with every contact-face
//! dof kept (`squeal_brake::interface_system`: a dense decomposition, or a dense partial one,
//! of the reduced brake). Issues 20 and 21: a step towards a reduced model whose parts never
//! form constraint modes for their whole contact face.
//!
//! # The vectors
//!
//! The same as `squeal_brake::interface_system`'s, over the full model's dofs: with `a_p` the
//! normal stiffness `F_n,δ` of pair `p` at the frictionless static equilibrium,
//!
//! `K_t0 = K + Σ_p a_p g_p g_pᵀ` (sparse, symmetric: [`super::FullBrake::stiffness`]),
//!
//! - the real modes `K_t0 φ_j = ω_j² M φ_j` up to a frequency: their count from the inertia of
//!   `K_t0 − ω_c² M` (`squeal_eigs::count_below`), the modes by shift-invert block Lanczos on a
//!   sparse Cholesky factor of `K_t0` (`squeal_eigs::lowest_modes_with_factor`, Sturm-checked);
//! - the friction residuals `r_j = K_t0⁻¹ K_f φ_j` of the modes up to the band's top, `K_f =
//!   Σ_p b_p h_p g_pᵀ` with `b_p` the friction stiffness `F_t,δ` at μ = 1 (less that at μ = 0),
//!   solved with the same factor;
//! - `dx/dμ = K_t0⁻¹ f_t`, `f_t = −Σ_p (F_t,p(μ = 1) − F_t,p(μ = 0)) h_p` at `x_0`;
//! - `x_0`, the frictionless static equilibrium, is the reduced brake's: its contact state and
//!   contact forces come from the reduced brake (as `squeal stability --full` linearizes about
//!   the reduced brake's equilibrium, [`super::onset`]), and its face rows are the reduced
//!   brake's face coordinates themselves (nodal dofs; the constraint modes make the static
//!   response to the contact forces and the pistons' loads exact there).
//!
//! Only the face rows are kept ([`FaceRows`]): for each contact-face dof of the reduced model
//! (a face node's motion along an axis, or along a node frame's direction) its row on the full
//! model, through the ties eliminated between parts ([`super::ties::FullTies::reduce`]).
//!
//! # Against the reduced brake's vectors
//!
//! The reduced brake is the full one projected on the parts' Craig–Bampton bases, so its modes
//! are Rayleigh–Ritz approximations of the full model's (frequencies from above, the gap the
//! fixed-interface modes' truncation). The face bases built from these face rows
//! ([`FullSystemVectors::face_bases`], as `crate::interface_system::face_bases` builds them from
//! the reduced vectors) span the full model's face motion: the projected brake then no longer
//! reproduces the reduced brake's in-band modes to round-off, but its results are those of a
//! basis closer to the full model's (measured: `crates/squeal-pipeline/tests/pipeline/interface_modes.rs`,
//! docs/reduction.md "System vectors from the full model").
//!
//! What this does not do yet: the Craig–Bampton parts still hold their whole contact face as
//! boundary dofs (the reduced model provides the pairs, the equilibrium and the face dofs); the
//! static extension of the kept face vectors alone (`ψ_k = [u_k; −K_II⁻¹ K_IB u_k]`) instead of
//! every face dof's constraint mode is the next step (docs/reduction.md).

use super::{FullBrake, PairVectors, full_error};
use crate::error::Result;
use crate::interface::face_parts;
use crate::model::Model;
use crate::parts::SceneParts;
use faer::Mat;
use squeal_brake::equilibrium::static_equilibrium;
use squeal_brake::model::SparseVec;
use squeal_eigs::{EigOptions, SparseCholesky, count_below, lowest_modes_with_factor};
use squeal_reduce::brake::BrakeInputs;
use squeal_reduce::interface_modes::{InterfaceModes, face_basis_keeping, face_dofs};
use squeal_reduce::rom::{DofLabel, ReducedPart};
use std::time::Instant;

/// One part's face rows of the full model's system vectors.
#[derive(Clone, Debug)]
pub struct FaceRows {
    /// The part's name.
    pub part: String,
    /// The modes' face rows (one column per mode, ascending).
    pub modes: Mat<f64>,
    /// The friction residuals' face rows (one column per in-band mode).
    pub residuals: Mat<f64>,
    /// `x_0`'s and `dx/dμ`'s face rows (two columns).
    pub statics: Mat<f64>,
}

/// The full model's system vectors, their face rows only.
#[derive(Clone, Debug)]
pub struct FullSystemVectors {
    /// The real modes' `ω_j` (rad/s), ascending: every mode below the asked frequency.
    pub omega: Vec<f64>,
    /// How many of the lowest modes have friction residuals (those up to the band's top).
    pub in_band: usize,
    /// Each face part's rows ([`face_parts`]' order: the disc, then the pads).
    pub faces: Vec<FaceRows>,
    /// Wall time (s) of the whole computation.
    pub seconds: f64,
    /// The full model's size.
    pub dofs: usize,
}

/// `Σ_i a_i x_i` over a sparse vector.
fn dot(a: &SparseVec, x: &[f64]) -> f64 {
    a.iter().map(|&(i, v)| v * x[i]).sum()
}

/// `out += s a` for a sparse `a`.
fn axpy(a: &SparseVec, s: f64, out: &mut [f64]) {
    if s != 0.0 {
        for &(i, v) in a {
            out[i] += s * v;
        }
    }
}

/// The system vectors of `model`'s brake on its full model `full` (built from `parts` and
/// `inputs`): the modes up to `modes_to_hz` (at least those up to `residuals_to_hz`), the
/// friction residuals of those up to `residuals_to_hz`, the static vectors (module docs).
pub fn full_system_vectors(
    parts: &SceneParts,
    inputs: &BrakeInputs,
    full: &FullBrake,
    model: &Model,
    residuals_to_hz: f64,
    modes_to_hz: f64,
) -> Result<FullSystemVectors> {
    let t = Instant::now();
    let brake = &model.brake;
    if brake.k_vibration.is_some() {
        return Err(full_error(
            "the system vectors on the full model do not yet take connectors on the vibration only",
        ));
    }
    let n = full.size();
    let eq = static_equilibrium(brake, 0.0, None, &model.sweep.newton)?;
    let at = |mu: f64| -> Vec<_> {
        brake
            .pairs
            .iter()
            .map(|p| p.response(&eq.x, None, mu))
            .collect()
    };
    let (r0, r1) = (at(0.0), at(1.0));
    let a: Vec<f64> = r0.iter().map(|r| r.normal_derivatives[0]).collect();
    let kt0 = full.stiffness(&a, &[])?;
    let factor = SparseCholesky::factorize(kt0.as_ref())?;
    let tau = std::f64::consts::TAU;
    let to_hz = modes_to_hz.max(residuals_to_hz);
    let count = count_below(kt0.as_ref(), full.m.as_ref(), (tau * to_hz).powi(2))?;
    let (omega, phi) = if count == 0 {
        (Vec::new(), Mat::zeros(n, 0))
    } else {
        // Shift 0: K_t0 is positive definite (the brake is held; its factor solved above).
        let opts = EigOptions::default();
        let modes = lowest_modes_with_factor(kt0.as_ref(), full.m.as_ref(), &factor, count, &opts)?;
        let omega = modes.values.iter().map(|l| l.max(0.0).sqrt()).collect();
        (omega, modes.vectors)
    };
    let in_band = omega
        .iter()
        .filter(|w: &&f64| **w / tau <= residuals_to_hz)
        .count();
    // K_f φ_j = Σ_p b_p h_p (g_pᵀ φ_j), b_p the friction part of F_t,δ.
    let b: Vec<f64> = r0
        .iter()
        .zip(&r1)
        .map(|(z, o)| o.tangential_derivatives[0] - z.tangential_derivatives[0])
        .collect();
    let mut rhs = Mat::<f64>::zeros(n, in_band);
    for j in 0..in_band {
        let col = phi.col_as_slice(j);
        let out = rhs.col_as_slice_mut(j);
        for (p, (g, h)) in full.normal.iter().zip(&full.tangent).enumerate() {
            axpy(h, b[p] * dot(g, col), out);
        }
    }
    let residuals = if in_band > 0 {
        factor.solve(rhs.as_ref())?
    } else {
        rhs
    };
    // f_t = −Σ_p (F_t,p(μ = 1) − F_t,p(μ = 0)) h_p: dx/dμ = K_t0⁻¹ f_t.
    let mut ft = Mat::<f64>::zeros(n, 1);
    for (p, h) in full.tangent.iter().enumerate() {
        axpy(
            h,
            -(r1[p].tangential - r0[p].tangential),
            ft.col_as_slice_mut(0),
        );
    }
    let dx = factor.solve(ft.as_ref())?;
    let finite =
        |m: &Mat<f64>| (0..m.ncols()).all(|j| (0..m.nrows()).all(|i| m[(i, j)].is_finite()));
    if !finite(&residuals) || !finite(&dx) || !finite(&phi) {
        return Err(full_error(
            "the system vectors on the full model are not finite",
        ));
    }
    let mut vectors = PairVectors::new(parts, inputs, model, &full.parts)?;
    let faces = face_parts(&model.rom)
        .map(|part| {
            let rows = face_rows(&mut vectors, full, part)?;
            let start = crate::interface_system::part_start(model, &part.info.name)?;
            let dofs = face_dofs(part);
            let pick = |a: &Mat<f64>| {
                Mat::from_fn(rows.len(), a.ncols(), |i, j| {
                    rows[i].iter().map(|&(k, v)| v * a[(k, j)]).sum::<f64>()
                })
            };
            let mut statics = Mat::zeros(rows.len(), 2);
            let dxs = pick(&dx);
            for i in 0..rows.len() {
                statics[(i, 0)] = eq.x[start + dofs[i]];
                statics[(i, 1)] = dxs[(i, 0)];
            }
            Ok(FaceRows {
                part: part.info.name.clone(),
                modes: pick(&phi),
                residuals: pick(&residuals),
                statics,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(FullSystemVectors {
        omega,
        in_band,
        faces,
        seconds: t.elapsed().as_secs_f64(),
        dofs: n,
    })
}

/// Each face dof's row on the full model: the motion of its node along its direction.
fn face_rows(
    vectors: &mut PairVectors<'_>,
    full: &FullBrake,
    part: &ReducedPart,
) -> Result<Vec<SparseVec>> {
    let name = part.info.name.as_str();
    face_dofs(part)
        .into_iter()
        .map(|d| {
            let (point, w) = match part.info.dofs.get(d) {
                Some(DofLabel::Point { point, direction }) => {
                    let mut w = [0.0; 3];
                    w[usize::from(*direction).min(2)] = 1.0;
                    (*point, w)
                }
                Some(DofLabel::Along { point, direction }) => (*point, *direction),
                _ => {
                    return Err(full_error(format!(
                        "a face dof of the {name} is not a point's"
                    )));
                }
            };
            let id = part
                .info
                .points
                .get(point)
                .and_then(|p| p.node_id)
                .ok_or_else(|| full_error(format!("a face point of the {name} has no node")))?;
            let node = vectors.node(name, id)?;
            let row = vectors.along(name, node, w, 1.0)?;
            Ok(match &full.ties {
                Some(t) => t.reduce(&row),
                None => row,
            })
        })
        .collect()
}

impl FullSystemVectors {
    /// Each face part's basis from the face rows of the `modes` lowest modes, the residuals of
    /// the `residuals` lowest and the two static vectors (kept exactly), as
    /// `crate::interface_system::face_bases` builds them from the reduced brake's vectors.
    pub fn face_bases(
        &self,
        model: &Model,
        modes: usize,
        residuals: usize,
    ) -> Result<Vec<InterfaceModes>> {
        face_parts(&model.rom)
            .zip(&self.faces)
            .map(|(part, f)| {
                let nm = modes.min(f.modes.ncols());
                let nr = residuals.min(f.residuals.ncols());
                let v = Mat::from_fn(f.modes.nrows(), nm + nr + 2, |i, j| {
                    if j < nm {
                        f.modes[(i, j)]
                    } else if j < nm + nr {
                        f.residuals[(i, j - nm)]
                    } else {
                        f.statics[(i, j - nm - nr)]
                    }
                });
                Ok(face_basis_keeping(part, &v, 2)?)
            })
            .collect()
    }
}
