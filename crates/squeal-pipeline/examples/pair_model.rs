//! Why an undamped pair's μ0 moves with the kept modes: the pair (or triple) of frictionless
//! modes nearest an onset, projected, in the full model and in each reduced brake
//! (docs/verification.md, "The caliper corner's undamped pair").
//!
//! `cargo run --release -p squeal-pipeline --example pair_model -- SCENE MODES LO..HI`, e.g.
//! `brake_caliper.toml 40,80,160 2860..2900`: MODES a comma list of fixed-interface modes per
//! part, `LO..HI` the band (Hz) holding the pair at μ = 0.
//!
//! For each model (the full one and each reduced brake), the modes `Φ` with frequencies in
//! the band at μ = 0 (mass-normalized, real: `K_t(0)` is symmetric) give the projected
//! stiffness `A(μ) = Φᵀ K_t(μ) Φ` at the reduced brake's equilibrium at μ (the same for every
//! kept-mode count: the constraint modes make the static response exact), `K_t(μ)` of each
//! model. For two modes `A = [[ω1² + μ b11, μ b12], [μ b21, ω2² + μ b22]]` turns complex at
//! `(A22 − A11)² + 4 A12 A21 = 0`: the pair's coalescence, which this example bisects for
//! (the projected μ0). It then swaps the pieces: the reduced brake's frequencies `Ω` with the
//! full model's friction part `B(μ) = A(μ) − A(0)` (and the converse), so the change of μ0
//! is split into what the split of the pair and what the coupling make of it.

use faer::Mat;
use squeal_brake::equilibrium::{Equilibrium, NewtonOptions, static_equilibrium};
use squeal_pipeline::full::onset::{spectrum_at, undamped};
use squeal_pipeline::full::{FullBrake, full_brake};
use squeal_pipeline::model::{Model, model_on, quiet};
use squeal_pipeline::parts::{brake_inputs, load_parts};
use squeal_reduce::brake::{ModeChoice, reduce_brake_loaded};
use squeal_scene::Scene;
use std::f64::consts::TAU;
use std::path::PathBuf;

type Error = Box<dyn std::error::Error>;

/// The equilibrium's linearized stiffness of one model, as a function of the equilibrium.
enum Which<'a> {
    Full(&'a FullBrake),
    Reduced,
}

/// `Φᵀ K_t(μ) Φ` of `which` at the equilibrium `eq` (`phi` columns on that model's dofs).
fn projected(
    which: &Which,
    model: &Model,
    eq: &Equilibrium,
    phi: &[Vec<f64>],
) -> Result<Mat<f64>, Error> {
    let mu = eq.mu;
    let kphi: Vec<Vec<f64>> = match which {
        Which::Full(full) => {
            let responses: Vec<_> = model
                .brake
                .pairs
                .iter()
                .map(|p| p.response(&eq.x, None, mu))
                .collect();
            let (k, _) = full.linearized(&responses)?;
            phi.iter()
                .map(|x| {
                    let mut y = vec![0.0; x.len()];
                    for (j, &xj) in x.iter().enumerate() {
                        for (i, &v) in k.row_idx_of_col(j).zip(k.val_of_col(j)) {
                            y[i] += v * xj;
                        }
                    }
                    y
                })
                .collect()
        }
        Which::Reduced => {
            let k = model.brake.tangent_stiffness(&eq.x, mu);
            phi.iter()
                .map(|x| {
                    (0..x.len())
                        .map(|i| (0..x.len()).map(|j| k[(i, j)] * x[j]).sum())
                        .collect()
                })
                .collect()
        }
    };
    let n = phi.len();
    Ok(Mat::from_fn(n, n, |i, j| {
        phi[i].iter().zip(&kphi[j]).map(|(a, b)| a * b).sum()
    }))
}

/// Whether the real `n × n` (2 or 3) matrix `a` has complex eigenvalues.
fn complex(a: &Mat<f64>) -> bool {
    let n = a.nrows();
    let tr = (0..n).map(|i| a[(i, i)]).sum::<f64>() / n as f64;
    let s = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .map(|(i, j)| (a[(i, j)] - if i == j { tr } else { 0.0 }).abs())
        .fold(0.0, f64::max);
    let b = Mat::from_fn(n, n, |i, j| (a[(i, j)] - if i == j { tr } else { 0.0 }) / s);
    match n {
        2 => (b[(0, 0)] - b[(1, 1)]).powi(2) + 4.0 * b[(0, 1)] * b[(1, 0)] < 0.0,
        3 => {
            // λ³ + p λ² + q λ + r, the discriminant negative: one real root, two complex.
            let p = -(b[(0, 0)] + b[(1, 1)] + b[(2, 2)]);
            let m2 = |i: usize, j: usize| b[(i, i)] * b[(j, j)] - b[(i, j)] * b[(j, i)];
            let q = m2(0, 1) + m2(0, 2) + m2(1, 2);
            let det = b[(0, 0)] * m2(1, 2)
                - b[(0, 1)] * (b[(1, 0)] * b[(2, 2)] - b[(1, 2)] * b[(2, 0)])
                + b[(0, 2)] * (b[(1, 0)] * b[(2, 1)] - b[(1, 1)] * b[(2, 0)]);
            let r = -det;
            let d = 18.0 * p * q * r - 4.0 * p.powi(3) * r + p * p * q * q
                - 4.0 * q.powi(3)
                - 27.0 * r * r;
            d < 0.0
        }
        _ => false,
    }
}

/// The first μ in `(lo, hi)` where `a(μ)` turns complex, bisected to 1e-9 relative.
fn onset(
    a: &dyn Fn(f64) -> Result<Mat<f64>, Error>,
    lo: f64,
    hi: f64,
) -> Result<Option<f64>, Error> {
    if !complex(&a(hi)?) || complex(&a(lo)?) {
        return Ok(None);
    }
    let (mut lo, mut hi) = (lo, hi);
    while hi - lo > 1e-9 * hi {
        let mid = 0.5 * (lo + hi);
        if complex(&a(mid)?) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(Some(0.5 * (lo + hi)))
}

/// The full model's modes at μ = 0 in `band` (Hz): real, mass-normalized, with their
/// frequencies.
fn full_modes(
    full: &FullBrake,
    model: &Model,
    band: (f64, f64),
) -> Result<(Vec<f64>, Vec<Vec<f64>>), Error> {
    let opts = squeal_pipeline::full::onset::FullOptions::default();
    let (s, _) = spectrum_at(full, model, 0.0, band, None, &opts.quadratic, &|_, _| {})?;
    let mut hz = Vec::new();
    let mut phi = Vec::new();
    for p in &s.eigs.pairs {
        let big = p
            .vector
            .iter()
            .copied()
            .max_by(|a, b| a.norm().total_cmp(&b.norm()))
            .unwrap_or_default();
        let turn = big.conj() / big.norm();
        let x: Vec<f64> = p.vector.iter().map(|v| (v * turn).re).collect();
        let mut mx = vec![0.0; x.len()];
        for (j, &xj) in x.iter().enumerate() {
            for (i, &v) in full.m.row_idx_of_col(j).zip(full.m.val_of_col(j)) {
                mx[i] += v * xj;
            }
        }
        let norm = x.iter().zip(&mx).map(|(a, b)| a * b).sum::<f64>().sqrt();
        hz.push(p.value.im / TAU);
        phi.push(x.iter().map(|v| v / norm).collect());
    }
    Ok((hz, phi))
}

/// The reduced brake's frictionless modes in `band` (Hz).
fn reduced_modes(model: &Model, band: (f64, f64)) -> Result<(Vec<f64>, Vec<Vec<f64>>), Error> {
    let st = squeal_brake::analysis::stability(&model.brake, &undamped(), &[0.0], &model.sweep)?;
    let b = &st.reference.basis;
    let mut hz = Vec::new();
    let mut phi = Vec::new();
    for (j, w) in b.omega.iter().enumerate() {
        let f = w / TAU;
        if f >= band.0 && f <= band.1 {
            hz.push(f);
            phi.push((0..b.phi.nrows()).map(|i| b.phi[(i, j)]).collect());
        }
    }
    Ok((hz, phi))
}

fn main() -> Result<(), Error> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize| args.get(i).cloned().ok_or("SCENE MODES LO..HI");
    let scene = Scene::read(&PathBuf::from(arg(0)?))?.variant()?;
    let (lo, hi) = arg(2)?
        .split_once("..")
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .ok_or("LO..HI")?;
    let band: (f64, f64) = (lo.parse()?, hi.parse()?);
    let parts = load_parts(&scene, &quiet)?;
    let inputs0 = brake_inputs(&scene, &parts)?;
    let newton = NewtonOptions::default();
    let mut full_side: Option<(FullBrake, Vec<f64>, Vec<Vec<f64>>)> = None;
    let mut rows = Vec::new();
    for c in arg(1)?.split(',') {
        let mut inputs = inputs0.clone();
        inputs.modes = ModeChoice::Fixed(c.parse()?);
        let (rom, _) = reduce_brake_loaded(
            &inputs,
            parts.disc.clone(),
            parts
                .pads
                .iter()
                .chain(&parts.bodies)
                .map(|p| p.1.clone())
                .collect(),
            &mut |_, _| {},
        )?;
        let model = model_on(&scene, rom, PathBuf::from("in-memory.rom"))?;
        if full_side.is_none() {
            let full = full_brake(&parts, &inputs, &model)?;
            let (hz, phi) = full_modes(&full, &model, band)?;
            full_side = Some((full, hz, phi));
        }
        let Some((full, fhz, fphi)) = full_side.as_ref() else {
            unreachable!()
        };
        let (rhz, rphi) = reduced_modes(&model, band)?;
        if rhz.len() != fhz.len() {
            return Err(format!(
                "{} reduced and {} full modes in the band",
                rhz.len(),
                fhz.len()
            )
            .into());
        }
        let eq = |mu: f64| static_equilibrium(&model.brake, mu, None, &newton);
        let a_full = |mu: f64| -> Result<Mat<f64>, Error> {
            projected(&Which::Full(full), &model, &eq(mu)?, fphi)
        };
        let a_red = |mu: f64| -> Result<Mat<f64>, Error> {
            projected(&Which::Reduced, &model, &eq(mu)?, &rphi)
        };
        let (f0, r0) = (a_full(0.0)?, a_red(0.0)?);
        // Swaps: reduced Ω with the full friction part, and the converse.
        let red_omega_full_b =
            |mu: f64| -> Result<Mat<f64>, Error> { Ok(&r0 + (a_full(mu)? - &f0)) };
        let full_omega_red_b =
            |mu: f64| -> Result<Mat<f64>, Error> { Ok(&f0 + (a_red(mu)? - &r0)) };
        let (lo, hi) = (0.02, 0.4);
        let mf = onset(&a_full, lo, hi)?;
        let mr = onset(&a_red, lo, hi)?;
        let ms1 = onset(&red_omega_full_b, lo, hi)?;
        let ms2 = onset(&full_omega_red_b, lo, hi)?;
        let b = |a: &dyn Fn(f64) -> Result<Mat<f64>, Error>,
                 a0: &Mat<f64>|
         -> Result<Mat<f64>, Error> {
            Ok((a(0.13)? - a0) * faer::Scale(1.0 / 0.13))
        };
        let (bf, br) = (b(&a_full, &f0)?, b(&a_red, &r0)?);
        println!("modes {c}: reduced {} dofs", model.brake.size());
        println!("  mu = 0: full {:?} Hz, reduced {:?} Hz", fhz, rhz);
        let split = |h: &[f64]| (h[1] - h[0]) / (0.5 * (h[0] + h[1]));
        println!(
            "  split of the first two: full {:.6e}, reduced {:.6e} ({:+.3e}); frequencies reduced/full - 1: {}",
            split(fhz),
            split(&rhz),
            split(&rhz) / split(fhz) - 1.0,
            rhz.iter()
                .zip(fhz.iter())
                .map(|(r, f)| format!("{:+.3e}", r / f - 1.0))
                .collect::<Vec<_>>()
                .join(", ")
        );
        let n = fhz.len();
        let cells = |m: &Mat<f64>| {
            (0..n)
                .map(|i| {
                    (0..n)
                        .map(|j| format!("{:+.5e}", m[(i, j)]))
                        .collect::<Vec<_>>()
                        .join(" ")
                })
                .collect::<Vec<_>>()
                .join(" | ")
        };
        println!("  B = (A(0.13) - A(0)) / 0.13: full  {}", cells(&bf));
        println!("                                reduced {}", cells(&br));
        if n == 2 {
            // Invariant under a turn of the pair's basis (a near-degenerate pair's modes turn
            // with any small change of the model): tr B and det B.
            let (tr, det) = (
                |m: &Mat<f64>| m[(0, 0)] + m[(1, 1)],
                |m: &Mat<f64>| m[(0, 0)] * m[(1, 1)] - m[(0, 1)] * m[(1, 0)],
            );
            println!(
                "  tr B: full {:.6e}, reduced {:.6e} ({:+.3e}); det B: full {:.6e}, reduced {:.6e} ({:+.3e})",
                tr(&bf),
                tr(&br),
                tr(&br) / tr(&bf) - 1.0,
                det(&bf),
                det(&br),
                det(&br) / det(&bf) - 1.0
            );
            let k = |m: &Mat<f64>| (-m[(0, 1)] * m[(1, 0)]).sqrt();
            println!(
                "  sqrt(-b12 b21): full {:.6e}, reduced {:.6e} ({:+.3e}); b22 - b11: full {:.6e}, reduced {:.6e}",
                k(&bf),
                k(&br),
                k(&br) / k(&bf) - 1.0,
                bf[(1, 1)] - bf[(0, 0)],
                br[(1, 1)] - br[(0, 0)]
            );
        }
        let rel = |a: Option<f64>, b: Option<f64>| match (a, b) {
            (Some(a), Some(b)) => format!("{:+.3e}", a / b - 1.0),
            _ => "-".into(),
        };
        println!(
            "  projected mu0: full {mf:?}, reduced {mr:?} ({}); reduced Omega + full B {ms1:?} ({}); full Omega + reduced B {ms2:?} ({})",
            rel(mr, mf),
            rel(ms1, mf),
            rel(ms2, mf)
        );
        rows.push((c.to_string(), mf, mr));
    }
    Ok(())
}
