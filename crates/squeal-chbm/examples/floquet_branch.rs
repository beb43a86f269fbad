//! The branch of limit cycles of a subcritical friction oscillator, with the Floquet
//! multipliers that say which cycles a brake can settle on.
//!
//! Theory. The 2-dof oscillator of `friction_oscillator.rs` with `K = [[1e6, 2e5], [2e5, 8e5]]`
//! turns unstable at μ0 by mode coupling, but its Hopf point is subcritical: the first
//! Lyapunov coefficient `l1 = Re c1 / ω0` of the normal form `ż = iω0 z + c1 z|z|²` is positive,
//! so the cycles born at μ0 exist *below* μ0, where the equilibrium is still stable, and they
//! are unstable (they separate the equilibrium's basin from the large cycles'). Followed in μ
//! by pseudo-arclength continuation of the harmonic balance equations (eq 26 with a phase
//! condition; Seydel, *Practical Bifurcation and Stability Analysis*, ch. 4), the branch turns
//! at a fold μ_fold < μ0 into large stable cycles: from μ_fold on a large enough disturbance
//! makes the brake squeal, from μ0 on it squeals by itself (hysteresis).
//!
//! Stability. A small perturbation `y` of a cycle of period `T` obeys `y' = A(t) y` with
//! `T`-periodic `A`; Floquet's theorem writes its solutions as `e^{σt} p(t)`, `p` periodic. The
//! multipliers `ρ = e^{σT}` (eigenvalues of the monodromy matrix) decide: one is always 1 (the
//! time shift along the cycle), and the cycle is stable when all others lie inside the unit
//! circle. Hill's method finds the exponents σ as eigenvalues of the harmonic balance Jacobian
//! extended by `σ` (`squeal_chbm::floquet`). At a fold a real multiplier passes through +1.
//!
//! Run: `cargo run --release -p squeal-chbm --example floquet_branch`.

use faer::Mat;
use squeal_chbm::branch::Harmonics;
use squeal_chbm::system::Branch;
use squeal_chbm::{Contact, FrictionSystem, SystemError};

/// The branch of the subcritical oscillator from its Hopf point, 15 harmonics, with Hill's
/// multipliers at every cycle.
pub fn run() -> Result<Branch, SystemError> {
    let m = Mat::<f64>::identity(2, 2);
    let c = Mat::from_fn(2, 2, |i, j| if i == j { 20.0 } else { 0.0 });
    let k = Mat::from_fn(2, 2, |i, j| [[1.0e6, 2.0e5], [2.0e5, 0.8e6]][i][j]);
    let pair = Contact::penalty_coulomb(&[(1, 1.0)], &[(0, -1.0)], 3.0e5, 7.5e11);
    let mut system = FrictionSystem::builder(m, c, k)
        .contact(pair.initial_gap(-2.0e-4))
        .build()?;
    system.settings.branch.harmonics = Harmonics::Fixed(15);
    system.settings.branch.range = (0.3, 1.5);
    system.branch()
}

#[allow(dead_code)]
fn main() -> Result<(), SystemError> {
    let b = run()?;
    let nf = &b.normal_form;
    println!(
        "mu0 = {:.8}, l1 = {:+.4} ({})",
        nf.mu0,
        nf.l1,
        nf.criticality()
    );
    println!(
        "{:>10} {:>12} {:>14} {:>12}",
        "mu/mu0", "f (Hz)", "closure (m)", "max |rho|"
    );
    for (i, p) in b.branch.points.iter().enumerate().step_by(4) {
        let rho = b.floquet[i]
            .as_ref()
            .map_or(f64::NAN, |f| f.largest_multiplier());
        println!(
            "{:>10.6} {:>12.5} {:>14.6e} {rho:>12.6}",
            p.parameter / nf.mu0,
            p.frequency_hz(),
            p.loudest().1
        );
    }
    for f in &b.branch.folds {
        println!("fold at mu/mu0 = {:.6}", f.parameter / nf.mu0);
    }
    for bi in &b.bifurcations {
        println!("{} at mu/mu0 = {:.6}", bi.kind, bi.parameter / nf.mu0);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use squeal_chbm::bifurcation::BifurcationKind;
    use squeal_chbm::floquet::CycleStability;

    #[test]
    fn the_subcritical_branch_is_unstable_up_to_its_fold_and_stable_after() {
        let b = run().unwrap();
        let nf = &b.normal_form;
        assert!(nf.l1 > 0.0, "subcritical: l1 = {}", nf.l1);
        // The fold: 0.98882 μ0 in docs/verification.md (the hand-built oscillator of
        // tests/chbm/branch.rs, 15 harmonics); it moves by 5e-6 μ0 from 7 to 25 harmonics, and this
        // system's modal damping differs from that one's by round-off only: 1e-5.
        let fold = b.branch.folds[0].parameter / nf.mu0;
        assert!((fold - 0.98882).abs() < 1e-5, "fold at {fold} mu0");
        let first = b.branch.folds[0].after_point;
        for i in 0..first.min(b.branch.points.len()) {
            // Before the fold: one real multiplier outside the unit circle (by more than Hill's
            // own error, the trivial exponent's distance from 0, times T: ~1e-6 here).
            let f = b.floquet[i].as_ref().unwrap();
            assert!(f.largest_multiplier() > 1.0, "point {i}: {:?}", f.leading());
        }
        // After it, up to the next fold (where a multiplier leaves through +1 again), no
        // multiplier is outside the circle beyond Hill's error (marginal at worst).
        let next = b
            .branch
            .folds
            .get(1)
            .map_or(b.branch.points.len(), |f| f.after_point);
        for i in first + 2..next {
            let f = b.floquet[i].as_ref().unwrap();
            assert_ne!(
                f.stability(),
                CycleStability::Unstable,
                "point {i}: {:?}",
                f.leading()
            );
        }
        // The first stability change is a fold (a real multiplier through +1), found by the
        // multipliers independently of the continuation's tangent: in the same step of the
        // branch as the continuation's fold. (Its parameter is interpolated linearly in the
        // exponent between the step's two points; at this nonsmooth turn, where the contact
        // starts to open, that is good to the step only.)
        let bi = &b.bifurcations[0];
        assert_eq!(bi.kind, BifurcationKind::Fold);
        assert_eq!(bi.after_point, first, "{bi:?}");
        // The trivial multiplier is 1: Hill's own accuracy on it, ~1e-6 measured.
        let rho = b.multipliers(0).unwrap();
        let trivial = rho
            .iter()
            .map(|r| (r - 1.0).norm())
            .fold(f64::INFINITY, f64::min);
        assert!(trivial < 1e-4, "trivial multiplier off 1 by {trivial:e}");
    }
}
