//! Eq (14): the static equilibrium `K x0 + F_nl(x0) = F_piston`, sliding at friction μ.
//!
//! Newton's method on the full reduced brake with a backtracking line search on the residual
//! norm, started "with the contact closed": at the first iteration open pairs use their linear
//! stiffness `k_l`, so that a start at `x = 0` (zero penetration) has a non-singular tangent.

use crate::error::BrakeError;
use crate::model::Brake;
use faer::Mat;
use faer::linalg::solvers::Solve;

/// Convergence controls of the Newton iteration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOptions {
    /// Converged when `||K x + F_nl - F_piston|| <= tolerance * max(||F_piston||, ||F_nl||)`:
    /// relative to the forces being balanced (the contact forces carry the load even when a
    /// preload, not the piston, closes the contact).
    pub tolerance: f64,
    /// Newton iterations allowed before [`BrakeError::NewtonFailed`].
    pub max_iterations: usize,
    /// Halvings of the step allowed by the line search.
    pub max_halvings: usize,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 60,
            max_halvings: 40,
        }
    }
}

/// A converged static equilibrium.
#[derive(Clone, Debug, PartialEq)]
pub struct Equilibrium {
    /// Friction coefficient μ the brake slides at.
    pub mu: f64,
    /// `x0` of eq (14).
    pub x: Vec<f64>,
    /// Newton iterations taken.
    pub iterations: usize,
    /// Final `||K x + F_nl - F_piston|| / max(||F_piston||, ||F_nl||)`.
    pub residual: f64,
    /// Penetration of each pair at `x0` (positive: closed).
    pub penetrations: Vec<f64>,
}

impl Equilibrium {
    /// Number of pairs in contact.
    pub fn closed_pairs(&self) -> usize {
        self.penetrations.iter().filter(|d| **d > 0.0).count()
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// Solves eq (14) at friction `mu`, from `start` (or from `x = 0`, contact closed).
pub fn static_equilibrium(
    brake: &Brake,
    mu: f64,
    start: Option<&[f64]>,
    opts: &NewtonOptions,
) -> Result<Equilibrium, BrakeError> {
    let n = brake.size();
    let force_scale = |x: &[f64]| {
        let mut f = vec![0.0; n];
        brake.add_nonlinear_force(x, None, mu, &mut f);
        norm(&brake.f_piston).max(norm(&f)).max(f64::MIN_POSITIVE)
    };
    let mut x: Vec<f64> = start.map(<[f64]>::to_vec).unwrap_or_else(|| vec![0.0; n]);
    let mut r = brake.static_residual(&x, mu);
    let mut rn = norm(&r);
    let mut scale = force_scale(&x);
    let mut it = 0;
    while rn > opts.tolerance * scale {
        if it == opts.max_iterations {
            return Err(BrakeError::NewtonFailed {
                iterations: it,
                residual: rn / scale,
                tolerance: opts.tolerance,
            });
        }
        let closed_start = it == 0 && start.is_none();
        if !closed_start && brake.penetrations(&x).iter().all(|d| *d <= 0.0) {
            return Err(BrakeError::ContactOpen);
        }
        let jac = &brake.k + brake.nonlinear_jacobian(&x, mu, closed_start).0;
        let rhs = Mat::from_fn(n, 1, |i, _| -r[i]);
        let dx = jac.partial_piv_lu().solve(&rhs);
        if (0..n).any(|i| !dx[(i, 0)].is_finite()) {
            return Err(BrakeError::SingularTangent);
        }
        // Backtracking line search on ||r||.
        let mut step = 1.0;
        let mut accepted = false;
        for _ in 0..=opts.max_halvings {
            let trial: Vec<f64> = (0..n).map(|i| x[i] + step * dx[(i, 0)]).collect();
            let rt = brake.static_residual(&trial, mu);
            let rtn = norm(&rt);
            if rtn < rn || rtn <= opts.tolerance * force_scale(&trial) {
                scale = force_scale(&trial);
                x = trial;
                r = rt;
                rn = rtn;
                accepted = true;
                break;
            }
            step *= 0.5;
        }
        it += 1;
        if !accepted {
            if brake.penetrations(&x).iter().all(|d| *d <= 0.0) {
                return Err(BrakeError::ContactOpen);
            }
            return Err(BrakeError::NewtonFailed {
                iterations: it,
                residual: rn / scale,
                tolerance: opts.tolerance,
            });
        }
    }
    let penetrations = brake.penetrations(&x);
    if penetrations.iter().all(|d| *d <= 0.0) {
        return Err(BrakeError::ContactOpen);
    }
    Ok(Equilibrium {
        mu,
        x,
        iterations: it,
        residual: rn / scale,
        penetrations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::PenaltyCoulomb;
    use crate::model::ContactPair;
    use std::sync::Arc;

    /// A pad (mass on a spring to ground? no: free in z) pressed on a disc held by a spring.
    fn pad_on_disc(force: f64) -> Brake {
        // dofs: 0 disc z (spring kd to ground), 1 pad z (free), 2 pad x (spring kx), 3 disc x.
        let kd = 1e8;
        let mut k = Mat::zeros(4, 4);
        k[(0, 0)] = kd;
        k[(2, 2)] = 5e7;
        k[(3, 3)] = 2e8;
        let pair = ContactPair {
            disc_point: 0,
            pad_point: 0,
            position: [0.0; 3],
            normal_direction: [0.0, 0.0, 1.0],
            sliding_direction: [1.0, 0.0, 0.0],
            normal: vec![(0, 1.0), (1, -1.0)],
            tangent: vec![(3, 1.0), (2, -1.0)],
            gap: 0.0,
            surface_speed: None,
            law: Arc::new(PenaltyCoulomb {
                k_linear: 1e7,
                k_cubic: 1e17,
            }),
        };
        Brake {
            m: Mat::identity(4, 4),
            k,
            f_piston: vec![0.0, -force, 0.0, 0.0],
            pairs: vec![pair],
        }
    }

    #[test]
    fn equilibrium_balances_the_piston_force() {
        let force = 300.0;
        let b = pad_on_disc(force);
        let mu = 0.4;
        let eq = static_equilibrium(&b, mu, None, &NewtonOptions::default()).unwrap();
        assert!(eq.residual <= 1e-10);
        // Independent check: the contact force equals the piston force (the pad is free in z),
        // so k_l d + k_nl d^3 = F; solve the scalar cubic by bisection.
        let (mut lo, mut hi) = (0.0f64, 1e-3f64);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if 1e7 * mid + 1e17 * mid.powi(3) > force {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        // The cubic's root is found to round-off by 200 bisections.
        assert!(
            (eq.penetrations[0] - lo).abs() < 1e-12 * lo.max(1e-9) + 1e-18,
            "{} vs {lo}",
            eq.penetrations[0]
        );
        // Disc z: -F / kd (pushed down); friction: disc x = -mu F / k, pad x = +mu F / k.
        assert!((eq.x[0] + force / 1e8).abs() < 1e-12 * force / 1e8 * 1e3);
        assert!((eq.x[3] + mu * force / 2e8).abs() < 1e-9 * mu * force / 2e8);
        assert!((eq.x[2] - mu * force / 5e7).abs() < 1e-9 * mu * force / 5e7);
    }

    #[test]
    fn pulling_the_pad_away_is_an_error_not_an_answer() {
        let b = pad_on_disc(-300.0);
        let r = static_equilibrium(&b, 0.4, None, &NewtonOptions::default());
        assert!(
            matches!(
                r,
                Err(BrakeError::ContactOpen) | Err(BrakeError::SingularTangent)
            ),
            "{r:?}"
        );
    }
}
