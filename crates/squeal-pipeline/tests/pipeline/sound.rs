//! The sound of a limit cycle on the coarse bundled brake: the surface velocity of each
//! harmonic against the time derivative of the expanded displacement, and the radiating faces.

use super::common;

use squeal_pipeline::shapes::{Meshes, expand};
use squeal_pipeline::sound::{BrakeSurface, SoundOptions};
use squeal_pipeline::{Pipeline, model::quiet};

/// CHBM's cycle at 1.02 μ0: `Σ_k Re(V_k e^{ikωt})` on the radiating nodes (the basis rows of
/// the surface nodes times the reduced velocity amplitudes, [`BrakeSurface::velocities`])
/// against the central difference of the displacement expanded on the meshes by
/// [`shapes::expand`] (every basis row, another code path), at 5 instants of the period.
/// Tolerance 1e-5 of the largest speed: the central difference with step 1e-4 period errs by
/// (kωδ)²/6 ≤ 1e-5 for the cycle's top harmonic; a wrong sign, harmonic or row gives O(1).
/// Doubling the oscillation raises every level by 20 log10 2 = 6.02 dB (1e-9: linearity).
#[test]
fn surface_velocity_is_the_derivative_of_the_expanded_cycle() {
    let out = std::env::temp_dir().join(format!("squeal-test-sound-{}", std::process::id()));
    let p = Pipeline::new(common::bundled_scene("coarse"), out, &quiet).unwrap();
    let m = p.model().unwrap();
    let mu0 = p.mu0().unwrap();
    let (start, modal) = p.chbm_start(1.02 * mu0).unwrap();
    let sol = squeal_chbm::solve(&modal, &start, &Default::default()).unwrap();
    assert_eq!(sol.outcome, squeal_chbm::Outcome::LimitCycle);
    let surface = BrakeSurface::new(&p.scene, m, &quiet).unwrap();
    let (h, w, n) = (sol.harmonics, sol.omega, m.brake.size());
    let v = surface.velocities(&sol.coeffs, h, w).unwrap();
    let meshes = Meshes::read(m, &quiet).unwrap();
    let parts = meshes.parts(m).unwrap();
    let period = std::f64::consts::TAU / w;
    let delta = 1e-4 * period;
    let x_at = |t: f64| -> Vec<f64> {
        (0..n)
            .map(|d| {
                (1..=h).fold(sol.coeffs[d], |s, k| {
                    let th = k as f64 * w * t;
                    s + sol.coeffs[(2 * k - 1) * n + d] * th.cos()
                        + sol.coeffs[2 * k * n + d] * th.sin()
                })
            })
            .collect()
    };
    let (mut worst, mut largest) = (0.0f64, 0.0f64);
    for j in 0..5 {
        let t = period * j as f64 / 5.0;
        let (xp, xm) = (x_at(t + delta), x_at(t - delta));
        let fields: Vec<Vec<f64>> = parts
            .iter()
            .map(|pm| {
                let dx: Vec<f64> = pm
                    .range
                    .clone()
                    .map(|d| (xp[d] - xm[d]) / (2.0 * delta))
                    .collect();
                expand(pm.part, pm.mesh, pm.path, &dx).unwrap()
            })
            .collect();
        for (s, &(part, node)) in surface.mesh_nodes.iter().enumerate() {
            for d in 0..3 {
                let mut u = 0.0;
                for k in 1..=h {
                    let e = squeal_acoustics::Complex64::from_polar(1.0, k as f64 * w * t);
                    u += (v[k - 1][s][d] * e).re;
                }
                let fd = fields[part][3 * node as usize + d];
                worst = worst.max((u - fd).abs());
                largest = largest.max(fd.abs());
            }
        }
    }
    println!("largest surface speed {largest:.3e} m/s, worst difference {worst:.2e}");
    assert!(
        largest > 0.0 && worst < 1e-5 * largest,
        "{worst} of {largest}"
    );
    // The pad radiates without its friction face; the disc with all its boundary.
    let pad_faces = surface.faces_per_part[1].1;
    let all = squeal_mesh::select::boundary_faces(&meshes.pads[0]).len();
    assert!(pad_faces > 0 && pad_faces < all, "{pad_faces} of {all}");
    // Linearity.
    let so = SoundOptions::default();
    let s1 = surface.cycle_sound(&sol.coeffs, h, w, &so).unwrap();
    let doubled: Vec<f64> = sol
        .coeffs
        .iter()
        .enumerate()
        .map(|(i, c)| if i < n { *c } else { 2.0 * c })
        .collect();
    let s2 = surface.cycle_sound(&doubled, h, w, &so).unwrap();
    let six = 20.0 * 2f64.log10();
    assert!((s2.rayleigh_dba[0] - s1.rayleigh_dba[0] - six).abs() < 1e-9);
    assert!((s2.erp_db - s1.erp_db - six).abs() < 1e-9);
    println!(
        "1.02 mu0: {:.1} dB(A) (Rayleigh), {:.1} dB(A) (monopoles), ERP {:.1} dB",
        s1.rayleigh_dba[0], s1.monopole_dba[0], s1.erp_db
    );
}
