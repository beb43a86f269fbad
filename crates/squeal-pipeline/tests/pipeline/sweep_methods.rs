//! The sweep methods against each other on the coarse bundled brake (158 dofs, 316
//! eigenvalues per friction value): continuation of eigenpairs (the default for brakes of this
//! size) must give the dense eigen-decomposition's eigenvalues, branch by branch, the same
//! crossings and the same Hopf point; the projected sweep (the default for large brakes) must
//! stay within the tolerance its truncation was checked to.

use super::common;

use squeal_brake::sweep::{SweepMethod, sweep};

#[test]
fn continuation_agrees_with_dense_eigen_decompositions() {
    let c = common::coarse();
    let mus = common::mus(0.0, 1.0, 101);
    let cont = common::options(c);
    let dense = {
        let mut o = cont;
        o.method = SweepMethod::Dense;
        o
    };
    let sc = sweep(&c.model.brake, &c.reference, &mus, &cont).unwrap();
    let sd = sweep(&c.model.brake, &c.reference, &mus, &dense).unwrap();
    assert_eq!(sc.branches.len(), sd.branches.len());
    // Continuation converges each eigenpair to a residual at round-off relative to ||T(λ)||,
    // as backward stable as the dense solver: measured 3.4e-14 relative on this brake (the
    // sweep_table bench). 1e-9 leaves room for a conditioned pair near a coalescence; a
    // swapped branch or a lost eigenvalue is off by O(1).
    let mut worst = 0.0f64;
    for k in 0..mus.len() {
        for br in 0..sc.branches.len() {
            let (a, b) = (sc.value(br, k), sd.value(br, k));
            worst = worst.max((a - b).norm() / b.norm());
        }
    }
    eprintln!("largest relative eigenvalue difference: {worst:.2e}");
    assert!(worst < 1e-9, "{worst:e}");
    assert_eq!(sc.crossings.len(), sd.crossings.len());
    for (a, b) in sc.crossings.iter().zip(&sd.crossings) {
        assert_eq!((a.branch, a.k, a.in_band), (b.branch, b.k, b.in_band));
    }
    let (hc, hd) = (sc.hopf.unwrap(), sd.hopf.unwrap());
    // Both refine μ0 to a bracket of 1e-8 (SweepOptions::mu_tolerance).
    assert!((hc.mu0 - hd.mu0).abs() < 2e-8, "{} vs {}", hc.mu0, hd.mu0);
    assert!((hc.frequency_hz / hd.frequency_hz - 1.0).abs() < 1e-8);
}

#[test]
fn the_sweep_to_the_hopf_point_is_the_whole_sweeps_beginning() {
    // `sweep_to_hopf` (the preliminary sweep that names the coalescing pair) must stop right
    // after the first in-band crossing with the same points, bit for bit, and the same Hopf
    // point and partner as the whole sweep: it runs the same continuation and only stops.
    use squeal_brake::sweep::sweep_to_hopf;
    let c = common::coarse();
    let mus = common::mus(0.0, 1.0, 101);
    let opts = common::options(c);
    let whole = sweep(&c.model.brake, &c.reference, &mus, &opts).unwrap();
    let early = sweep_to_hopf(&c.model.brake, &c.reference, &mus, &opts).unwrap();
    let first = whole.crossings.iter().find(|x| x.in_band).unwrap();
    assert_eq!(
        early.points.len(),
        first.k + 2,
        "ends at the point after the crossing"
    );
    for (k, (a, b)) in early.points.iter().zip(&whole.points).enumerate() {
        assert_eq!(a.spectrum.values, b.spectrum.values, "point {k}");
    }
    let (he, hw) = (early.hopf.unwrap(), whole.hopf.unwrap());
    assert_eq!(he.mu0.to_bits(), hw.mu0.to_bits());
    assert_eq!((he.branch, he.partner), (hw.branch, hw.partner));
}

#[test]
fn the_projected_sweep_to_the_hopf_point_is_the_whole_projected_sweeps_beginning() {
    // The projected `sweep_to_hopf` ends with the chunk of 8 friction values (spectra computed
    // together) that holds the first in-band crossing: its points, branches and Hopf point must
    // be the whole projected sweep's, bit for bit (same projection, same matching of each point
    // to the one before).
    use squeal_brake::sweep::sweep_to_hopf;
    let c = common::coarse();
    let mus = common::mus(0.0, 1.0, 101);
    let mut opts = common::options(c);
    opts.method = SweepMethod::Projected;
    let whole = sweep(&c.model.brake, &c.reference, &mus, &opts).unwrap();
    let early = sweep_to_hopf(&c.model.brake, &c.reference, &mus, &opts).unwrap();
    let first = whole.crossings.iter().find(|x| x.in_band).unwrap();
    let end = ((first.k + 1) / 8 + 1) * 8;
    assert_eq!(
        early.points.len(),
        end.min(mus.len()),
        "crossing at {}",
        first.k
    );
    assert!(early.points.len() < whole.points.len());
    for (k, (a, b)) in early.points.iter().zip(&whole.points).enumerate() {
        assert_eq!(a.spectrum.values, b.spectrum.values, "point {k}");
    }
    for (a, b) in early.branches.iter().zip(&whole.branches) {
        assert_eq!(a[..], b[..early.points.len()]);
    }
    let (he, hw) = (early.hopf.unwrap(), whole.hopf.unwrap());
    assert_eq!(he.mu0.to_bits(), hw.mu0.to_bits());
    assert_eq!((he.branch, he.partner), (hw.branch, hw.partner));
}

#[test]
fn the_projected_sweep_agrees_with_continuation_within_its_checked_tolerance() {
    // The coarse brake projected on its modes below 1.5 x 16 kHz plus the static correction
    // of the others (105 + 18 vectors of 158 dofs): its check against the unprojected brake
    // at mu = 0, 0.5, 1 measured 3.3e-6, so a tolerance of 1e-5 keeps that projection. Every
    // in-band eigenvalue at every one of the 101 points is then compared with the exact
    // continuation's (the reference: converged to round-off, 3.4e-14 from dense solves).
    use squeal_brake::projected::ProjectionOptions;
    let c = common::coarse();
    let mus = common::mus(0.0, 1.0, 101);
    let exact = common::options(c);
    let projected = {
        let mut o = exact;
        o.method = SweepMethod::Projected;
        o.projection = {
            let mut o = ProjectionOptions::default();
            o.tolerance = 1e-5;
            o
        };
        o
    };
    let se = sweep(&c.model.brake, &c.reference, &mus, &exact).unwrap();
    let sp = sweep(&c.model.brake, &c.reference, &mus, &projected).unwrap();
    let p = sp
        .projection
        .as_ref()
        .expect("a projected sweep reports its projection");
    assert!(se.projection.is_none());
    eprintln!(
        "kept {} modes + {} vectors, deviation {:.2e} at {:?}",
        p.kept_modes, p.residual_vectors, p.deviation, p.checked_mus
    );
    assert!(
        p.kept_modes < c.model.brake.size(),
        "the projection truncates"
    );
    assert!(p.deviation <= 1e-5, "{:e}", p.deviation);
    // Each in-band projected eigenvalue against the nearest exact one at the same point.
    let mut worst = 0.0f64;
    for (a, b) in sp.points.iter().zip(&se.points) {
        for (j, l) in a.spectrum.values.iter().enumerate() {
            if !exact.band.contains(a.spectrum.frequency_hz(j)) {
                continue;
            }
            let d = b
                .spectrum
                .values
                .iter()
                .map(|e| (e - l).norm() / e.norm())
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(d);
        }
    }
    eprintln!("largest in-band relative eigenvalue difference over the sweep: {worst:.2e}");
    // Measured 3.27e-6, the checked deviation itself: the check at three friction values
    // saw the worst point. A truncation worse between the checked values than at them would
    // exceed the tolerance the projection was accepted at.
    assert!(worst <= 1e-5, "{worst:e}");
    let (hp, he) = (sp.hopf.unwrap(), se.hopf.unwrap());
    eprintln!(
        "mu0 {} vs {}, {} vs {} Hz",
        hp.mu0, he.mu0, hp.frequency_hz, he.frequency_hz
    );
    // Measured: mu0 1.4e-7 apart, frequencies 3e-10 relative. A relative error of 1e-5 on
    // frequencies that approach at ~1e4 rad/s per unit mu bounds mu0's shift by ~3e-5.
    assert!((hp.mu0 - he.mu0).abs() < 3e-5, "{} vs {}", hp.mu0, he.mu0);
    assert!((hp.frequency_hz / he.frequency_hz - 1.0).abs() < 1e-5);
}

#[test]
fn auto_continues_the_bundled_brakes_and_projects_larger_ones() {
    // The bundled brakes (158 and 266 dofs) keep the continuation their pinned numbers come
    // from (tests/cli/regression.rs); above PROJECT_ABOVE the sweep projects.
    use squeal_brake::sweep::PROJECT_ABOVE;
    assert_eq!(SweepMethod::default(), SweepMethod::Auto);
    for n in [158, 266, PROJECT_ABOVE] {
        assert_eq!(SweepMethod::Auto.resolve(n), SweepMethod::Continuation);
    }
    assert_eq!(
        SweepMethod::Auto.resolve(PROJECT_ABOVE + 1),
        SweepMethod::Projected
    );
    assert_eq!(SweepMethod::Dense.resolve(5000), SweepMethod::Dense);
}

#[test]
fn the_normal_form_of_a_large_brake_is_the_dense_ones() {
    // Above PROJECT_ABOVE dofs the normal form finds the equilibrium at mu0 by Newton steps in
    // the modal basis and the critical eigenpair from a projection converged on the whole
    // brake, instead of dense LUs and the dense spectrum; forced on the coarse brake, both
    // paths must give the same normal form. The eigenpair is converged to round-off either
    // way; the equilibria agree to Newton's tolerance (1e-10 of the forces) or better, which
    // bounds the change of omega0 and dlambda/dmu, and l1 (third derivatives of the contact
    // law by central differences along the state) moves somewhat more.
    use squeal_brake::criticality::normal_form_with;
    let c = common::coarse();
    let mus = common::mus(0.0, 1.0, 101);
    let opts = common::options(c);
    let s = sweep(&c.model.brake, &c.reference, &mus, &opts).unwrap();
    let h = s.hopf.unwrap();
    let guess = faer::c64::new(0.0, std::f64::consts::TAU * h.frequency_hz);
    let b = &c.model.brake;
    let dense = normal_form_with(b, &c.reference, h.mu0, guess, &opts.newton, false).unwrap();
    let large = normal_form_with(b, &c.reference, h.mu0, guess, &opts.newton, true).unwrap();
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    let (dw, dl1) = (rel(large.omega0, dense.omega0), rel(large.l1, dense.l1));
    let ds = (large.dlambda_dmu - dense.dlambda_dmu).norm() / dense.dlambda_dmu.norm();
    eprintln!(
        "omega0 {:.2e}, l1 {:.2e} ({} vs {}), dlambda/dmu {:.2e}",
        dw, dl1, large.l1, dense.l1, ds
    );
    // Measured: omega0 1.4e-16, dlambda/dmu 4.5e-13, l1 2.3e-11 relative. The bounds leave
    // three orders for other machines' round-off and stay far below what a wrong eigenpair
    // (another mode: O(1e-2) in omega0) or another equilibrium would give.
    assert!(dw < 1e-12, "{dw:e}");
    assert!(ds < 1e-9, "{ds:e}");
    assert!(dl1 < 1e-8, "{dl1:e}");
    assert_eq!(large.criticality(), dense.criticality());
}
