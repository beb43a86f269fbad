//! The linear limit of the nonlinear mode: the extended periodic motion concept on the tangent
//! linearization at the static equilibrium, solved densely in modal coordinates.
//!
//! Linearized about the equilibrium `x_n0`, the contact force is `K_c x_n + C_c x_n'`
//! (its Jacobians there, the springs `K_s` already in `Ω²`) and a motion `Re(q e^{iωt})`
//! with the artificial damping `-2ζω q'` satisfies
//!
//! `[A(ω) - ω² (1 + 2iζ) I] q = 0`,  `A(ω) = Ω² + iω D + Φ_nᵀ (K_c + iω C_c) Φ_n`:
//!
//! `ν = ω² (1 + 2iζ)` is an eigenvalue of `A(ω)`. With `A` independent of ω (no damping, no
//! velocity-dependent law) that is one dense eigenvalue problem, `ω² = Re ν`,
//! `ζ = Im ν / (2 Re ν)`. Otherwise the fixed point `ω ← sqrt(Re ν(ω))` contracts with the
//! factor `|dν/dω| / (2ω) ≈ max |D| / (2ω)` (about the modal damping ratio): a few
//! iterations reach round-off.
//!
//! **Against the eigenvalue λ of the brake** (`T(λ) = λ² + λ (D + Φ_nᵀC_cΦ_n) + Ω² + Φ_nᵀK_cΦ_n`):
//! when the damping is mass-proportional, `D = c I`, and the law does not depend on velocities,
//! `A(ω) = iωc + K̃` and `ν - iωc = ω² + 2iζω² - iωc` must be an eigenvalue `κ` of `K̃`, whose
//! `λ` solve `λ² + cλ + κ = 0`: exactly
//!
//! `ω² = Re κ`,  `ζ = (Im κ + cω) / (2ω²)`,  `κ = -λ (λ + c)`.
//!
//! With any other damping the two differ by `O(ζ |D| / ω)` (the term `σ (D + C_c)` of
//! `T(σ + iω) ≈ T(iω) + σ T'(iω)` that the artificial mass-proportional damping leaves out).

use faer::{Mat, c64};
use squeal_brake::harmonic::ContactForce;
use squeal_brake::modal_brake::ModalBrake;
use squeal_hbm::reference_jacobian;

/// The linearized nonlinear mode at the equilibrium.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearMode {
    /// ω (rad/s).
    pub omega: f64,
    /// ζ, the modal damping ratio of the artificial term (negative: unstable).
    pub zeta: f64,
    /// The mode in modal coordinates, `|q| = 1`.
    pub shape: Vec<c64>,
    /// Fixed-point iterations.
    pub iterations: usize,
}

/// Why the linear mode could not be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LinearModeError {
    /// The dense eigensolver failed.
    #[error("the dense eigenvalue solver did not converge on the linearized brake")]
    Eigen,
    /// The fixed point did not settle, or `Re ν <= 0`.
    #[error(
        "the linear mode's frequency did not settle (last omega {omega} rad/s): the followed eigenvalue is not oscillating"
    )]
    NoFixedPoint {
        /// The last ω.
        omega: f64,
    },
}

/// `A(ω)` (module documentation).
fn matrix(mb: &ModalBrake, kc: &Mat<f64>, cc: &Mat<f64>, omega: f64) -> Mat<c64> {
    let (n, nn) = (mb.modes(), mb.nl());
    let p = &mb.phi_n;
    let j = Mat::<c64>::from_fn(nn, nn, |r, c| c64::new(kc[(r, c)], omega * cc[(r, c)]));
    let pj = Mat::<c64>::from_fn(n, nn, |a, c| (0..nn).map(|r| j[(r, c)] * p[(r, a)]).sum());
    Mat::<c64>::from_fn(n, n, |a, b| {
        let mut v: c64 = (0..nn).map(|c| pj[(a, c)] * p[(c, b)]).sum();
        v += c64::new(0.0, omega * mb.damping.entry(a, b));
        if a == b {
            v += mb.omega[a] * mb.omega[a];
        }
        v
    })
}

/// The linear mode at the static equilibrium `x_n0` (nonlinear dofs) that continues the
/// brake's eigenvalue `lambda` (`ν` starts nearest `-λ²`).
pub fn linear_mode(
    mb: &ModalBrake,
    x_n0: &[f64],
    lambda: c64,
) -> Result<LinearMode, LinearModeError> {
    let (kc, cc) = reference_jacobian(&ContactForce::new(mb), x_n0);
    let mut nu = -(lambda * lambda);
    let mut omega = lambda.im.abs();
    for it in 1..=60 {
        let a = matrix(mb, &kc, &cc, omega);
        let evd = a.eigen().map_err(|_| LinearModeError::Eigen)?;
        let s = evd.S();
        let k = (0..s.dim())
            .min_by(|&p, &q| (s[p] - nu).norm().total_cmp(&(s[q] - nu).norm()))
            .ok_or(LinearModeError::Eigen)?;
        nu = s[k];
        if !(nu.re > 0.0 && nu.re.is_finite()) {
            return Err(LinearModeError::NoFixedPoint { omega });
        }
        let next = nu.re.sqrt();
        let done = (next - omega).abs() <= 1e-14 * next;
        omega = next;
        if done || it == 60 {
            if !done {
                return Err(LinearModeError::NoFixedPoint { omega });
            }
            let u = evd.U();
            let mut shape: Vec<c64> = (0..s.dim()).map(|i| u[(i, k)]).collect();
            let scale = super::epmc::norm(&shape);
            for v in &mut shape {
                *v /= scale;
            }
            return Ok(LinearMode {
                omega,
                zeta: nu.im / (2.0 * nu.re),
                shape,
                iterations: it,
            });
        }
    }
    Err(LinearModeError::NoFixedPoint { omega })
}
