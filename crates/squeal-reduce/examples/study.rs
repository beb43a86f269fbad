//! The tables of docs/reduction.md: Craig–Bampton accuracy against the full model, the mesh
//! convergence of node and patch contact, the fixed-interface frequencies of each part at
//! each mesh level, and the automatic mode choice.
//!
//! ```sh
//! cargo run --release -p squeal-reduce --example study -- modes coarse medium
//! cargo run --release -p squeal-reduce --example study -- convergence coarse medium fine
//! cargo run --release -p squeal-reduce --example study -- auto medium
//! ```
//! Reduced models are cached in `target/study/` (delete it to recompute).

use faer::Mat;
use squeal_eigs::{EigOptions, lowest_modes};
use squeal_fe::{DofMap, MaterialTable, Restraint, assemble};
use squeal_reduce::brake::{
    BrakeInputs, Freshness, ModeChoice, PartInput, freshness, reduce_brake,
};
use squeal_reduce::check::{Boundary, dense_eigenvalues, reduced_frequencies};
use squeal_reduce::craig_bampton::hz;
use squeal_reduce::rom::{DofLabel, InterfaceKind, PointRole, ReducedModel, ReducedPart};
use std::path::PathBuf;

const PARTS: [&str; 2] = ["disc", "pad"];
const INTERFACES: [InterfaceKind; 2] = [InterfaceKind::Patch, InterfaceKind::Node];

fn mesh(part: &str, level: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../meshes")
        .join(format!("{part}_{level}.inp"))
}

fn cache_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target/study");
    std::fs::create_dir_all(&dir).expect("cache folder");
    dir
}

/// The brake reduced with `inputs`, from the cache when it is fresh.
fn brake(inputs: &BrakeInputs, tag: &str) -> ReducedModel {
    let path = cache_dir().join(format!("{tag}.rom"));
    if freshness(&path, inputs).expect("freshness") == Freshness::Fresh {
        return ReducedModel::read(&path).expect("cached rom");
    }
    let t = std::time::Instant::now();
    let (model, _) = reduce_brake(inputs, &mut |_, _| {}).expect("reduction");
    eprintln!("  reduced {tag} in {:.1} s", t.elapsed().as_secs_f64());
    model.write(&path).expect("write cache");
    model
}

fn inputs(level: &str, interface: InterfaceKind, modes: ModeChoice) -> BrakeInputs {
    BrakeInputs {
        interface,
        modes,
        keep_basis: false,
        ..BrakeInputs::bundled(mesh("disc", level), mesh("pad", level))
    }
}

/// The `count` lowest frequencies (Hz) of the full part under its own restraints.
fn full_frequencies(part: &str, level: &str, count: usize) -> Vec<f64> {
    full_frequencies_held(part, level, count, false)
}

/// As [`full_frequencies`]; with `boundary_held` also the contact nodes (all directions) and
/// the piston nodes (z) restrained: the node interface's fixed boundary.
fn full_frequencies_held(part: &str, level: &str, count: usize, boundary_held: bool) -> Vec<f64> {
    let input = if part == "disc" {
        PartInput::disc(mesh(part, level))
    } else {
        PartInput::pad(mesh(part, level))
    };
    let m = squeal_mesh::read(&input.mesh).expect("mesh").mesh;
    let materials = MaterialTable::from_mesh(&m, &[]).expect("materials");
    let mut restraints = input.restraints.clone();
    if boundary_held {
        restraints.push(Restraint::set("CONTACT", [true; 3]));
        if input.piston_set.is_some() {
            restraints.push(Restraint::set("PISTON", [false, false, true]));
        }
    }
    let dofmap = DofMap::new(&m, &restraints).expect("dofs");
    let system = assemble(&m, &materials, &dofmap).expect("assembly");
    let opts = {
        let mut o = EigOptions::default();
        o.shift = -4e5;
        o
    };
    let modes =
        lowest_modes(system.k.as_ref(), system.m.as_ref(), count, &opts).expect("full modes");
    modes.values.iter().map(|&w2| hz(w2)).collect()
}

/// The part with only its boundary dofs and the first `n` modes.
fn truncated(part: &ReducedPart, n: usize) -> ReducedPart {
    let keep: Vec<usize> = part
        .info
        .dofs
        .iter()
        .enumerate()
        .filter(|(_, d)| !matches!(d, DofLabel::Mode { mode } if *mode >= n))
        .map(|(i, _)| i)
        .collect();
    let sub = |a: &Mat<f64>| Mat::from_fn(keep.len(), keep.len(), |i, j| a[(keep[i], keep[j])]);
    let mut info = part.info.clone();
    info.dofs = keep.iter().map(|&i| part.info.dofs[i]).collect();
    info.fixed_interface_hz.truncate(n);
    ReducedPart {
        info,
        k: sub(&part.k),
        m: sub(&part.m),
        basis: None,
    }
}

fn relative_errors(reduced: &[f64], full: &[f64]) -> Vec<f64> {
    reduced
        .iter()
        .zip(full)
        .filter(|(_, f)| **f > 1.0)
        .map(|(r, f)| (r - f).abs() / f)
        .collect()
}

/// Free-boundary error of the first 20 frequencies against the full model, for 10 to 100
/// fixed-interface modes.
fn modes_study(level: &str) {
    println!("\n### Free-boundary frequencies against the full model, {level} meshes\n");
    println!("Largest relative error of the first 20 natural frequencies of each part with its");
    println!("boundary coordinates free (the pad's rigid normal translation excluded).\n");
    println!("| modes | disc, patch | disc, node | pad, patch | pad, node |");
    println!("|---|---|---|---|---|");
    let full: Vec<Vec<f64>> = PARTS
        .iter()
        .map(|p| full_frequencies(p, level, 20))
        .collect();
    let models: Vec<ReducedModel> = INTERFACES
        .iter()
        .map(|&i| {
            brake(
                &inputs(level, i, ModeChoice::Fixed(100)),
                &format!("{level}-{i:?}-100"),
            )
        })
        .collect();
    for n in [10, 20, 50, 100] {
        let mut row = format!("| {n} |");
        for (k, part) in PARTS.iter().enumerate() {
            for model in &models {
                let p = truncated(model.part(part).expect("part"), n);
                let f = reduced_frequencies(&p, Boundary::Free).expect("frequencies");
                let worst = relative_errors(&f, &full[k])
                    .into_iter()
                    .fold(0.0, f64::max);
                row += &format!(" {worst:.1e} |");
            }
        }
        println!("{row}");
    }
    println!("\nFixed boundary, node interface: largest relative error of the first min(N, 20)");
    println!("fixed-interface frequencies against the full model with the contact nodes (and the");
    println!("pad's piston nodes along z) restrained.\n");
    println!("| modes | disc | pad |");
    println!("|---|---|---|");
    let held: Vec<Vec<f64>> = PARTS
        .iter()
        .map(|p| full_frequencies_held(p, level, 20, true))
        .collect();
    for n in [10, 20, 50, 100] {
        let mut row = format!("| {n} |");
        for (k, part) in PARTS.iter().enumerate() {
            let p = truncated(models[1].part(part).expect("part"), n);
            let f = reduced_frequencies(&p, Boundary::Fixed).expect("frequencies");
            let worst = relative_errors(&f, &held[k])
                .into_iter()
                .fold(0.0, f64::max);
            row += &format!(" {worst:.1e} |");
        }
        println!("{row}");
    }
    println!("\nPer frequency, 50 modes (Hz; relative error):\n");
    println!("| # | disc full | disc patch | disc node | pad full | pad patch | pad node |");
    println!("|---|---|---|---|---|---|---|");
    let per: Vec<Vec<Vec<f64>>> = PARTS
        .iter()
        .map(|part| {
            models
                .iter()
                .map(|m| {
                    reduced_frequencies(&truncated(m.part(part).expect("part"), 50), Boundary::Free)
                        .expect("f")
                })
                .collect()
        })
        .collect();
    for j in 0..20 {
        let mut row = format!("| {} |", j + 1);
        for (k, _) in PARTS.iter().enumerate() {
            let f = full[k][j];
            row += &format!(" {f:.1} |");
            for r in &per[k] {
                let e = if f > 1.0 {
                    format!("{:.1e}", (r[j] - f) / f)
                } else {
                    "rigid".into()
                };
                row += &format!(" {:.1} ({e}) |", r[j]);
            }
        }
        println!("{row}");
    }
}

/// Tangent contact stiffness per unit area at the bundled scene's nominal pressure
/// (meshes/brake.toml: k_l + 3 k_nl d² at d = 25 µm).
const CONTACT_STIFFNESS: f64 = 1.25e10 + 3.0 * 2.0e19 * 25e-6 * 25e-6;

/// Footprint area of the bundled meshes: 50° of the annulus 85..135 mm.
fn footprint() -> f64 {
    0.5 * 50f64.to_radians() * (0.135f64.powi(2) - 0.085f64.powi(2))
}

/// The pad on normal springs to a rigid disc: the lowest `count` frequencies (Hz).
fn pad_on_springs(pad: &ReducedPart, count: usize) -> Vec<f64> {
    let mut k = pad.k.clone();
    for (i, d) in pad.info.dofs.iter().enumerate() {
        if let DofLabel::Point {
            point,
            direction: 2,
        } = *d
            && pad.info.points[point].role == PointRole::Contact
        {
            let area = pad.info.points[point].area.unwrap_or(footprint() / 9.0);
            k[(i, i)] += CONTACT_STIFFNESS * area;
        }
    }
    let values = dense_eigenvalues(&k, &pad.m, "pad").expect("pad on springs");
    values.into_iter().take(count).map(hz).collect()
}

/// Normal Guyan stiffness (N/m) of the central contact point (patch 5) of a part.
fn central_stiffness(part: &ReducedPart) -> f64 {
    let centre = part
        .info
        .dofs
        .iter()
        .position(|d| {
            *d == DofLabel::Point {
                point: 4,
                direction: 2,
            }
        })
        .expect("point 5, z");
    part.k[(centre, centre)]
}

fn convergence_study(levels: &[String]) {
    let models: Vec<Vec<ReducedModel>> = levels
        .iter()
        .map(|level| {
            INTERFACES
                .iter()
                .map(|&i| {
                    brake(
                        &inputs(level, i, ModeChoice::Fixed(50)),
                        &format!("{level}-{i:?}-50"),
                    )
                })
                .collect()
        })
        .collect();
    println!("\n### Mesh convergence: node against patch contact\n");
    println!("Normal stiffness of the central contact point (K̂_CC, N/m) and the three lowest");
    println!(
        "frequencies (Hz) of the reduced pad (50 modes) on its nine contact springs against a"
    );
    println!("rigid disc, k = {CONTACT_STIFFNESS:.3e} Pa/m x patch area per point.\n");
    println!("| mesh | interface | disc K_zz | pad K_zz | pad on springs f1 | f2 | f3 |");
    println!("|---|---|---|---|---|---|---|");
    for (level, pair) in levels.iter().zip(&models) {
        for (interface, model) in INTERFACES.iter().zip(pair) {
            let disc = model.part("disc").expect("disc");
            let pad = model.part("pad").expect("pad");
            let f = pad_on_springs(pad, 3);
            println!(
                "| {level} | {} | {:.3e} | {:.3e} | {:.1} | {:.1} | {:.1} |",
                format!("{interface:?}").to_lowercase(),
                central_stiffness(disc),
                central_stiffness(pad),
                f[0],
                f[1],
                f[2]
            );
        }
    }
    println!("\n### The 20 lowest fixed-interface frequencies (Hz), patch interface\n");
    let mut head = "| # |".to_string();
    let mut rule = "|---|".to_string();
    for part in PARTS {
        for level in levels {
            head += &format!(" {part} {level} |");
            rule += "---|";
        }
    }
    println!("{head}\n{rule}");
    for j in 0..20 {
        let mut row = format!("| {} |", j + 1);
        for part in PARTS {
            for pair in &models {
                let f = pair[0].part(part).expect("part").info.fixed_interface_hz[j];
                row += &format!(" {f:.1} |");
            }
        }
        println!("{row}");
    }
    println!("\nSame with the node interface:\n");
    println!("{head}\n{rule}");
    for j in 0..20 {
        let mut row = format!("| {} |", j + 1);
        for part in PARTS {
            for pair in &models {
                let f = pair[1].part(part).expect("part").info.fixed_interface_hz[j];
                row += &format!(" {f:.1} |");
            }
        }
        println!("{row}");
    }
}

/// The brake at rest without friction: disc and pad joined by normal springs between
/// paired contact points (same index: both parts number their patches alike), natural
/// frequencies (Hz) ascending.
fn brake_frequencies(model: &ReducedModel) -> Vec<f64> {
    let disc = model.part("disc").expect("disc");
    let pad = model.part("pad").expect("pad");
    let (nd, np) = (disc.size(), pad.size());
    let n = nd + np;
    let mut k = Mat::<f64>::zeros(n, n);
    let mut m = Mat::<f64>::zeros(n, n);
    for (off, p) in [(0, disc), (nd, pad)] {
        for i in 0..p.size() {
            for j in 0..p.size() {
                k[(off + i, off + j)] = p.k[(i, j)];
                m[(off + i, off + j)] = p.m[(i, j)];
            }
        }
    }
    let z_dof = |p: &ReducedPart, point: usize| {
        p.info
            .dofs
            .iter()
            .position(|d| {
                *d == DofLabel::Point {
                    point,
                    direction: 2,
                }
            })
            .expect("z dof")
    };
    for (point, q) in disc.info.points.iter().enumerate() {
        if q.role != PointRole::Contact {
            continue;
        }
        let area = q.area.unwrap_or(footprint() / 9.0);
        let s = CONTACT_STIFFNESS * area;
        let (i, j) = (z_dof(disc, point), nd + z_dof(pad, point));
        k[(i, i)] += s;
        k[(j, j)] += s;
        k[(i, j)] -= s;
        k[(j, i)] -= s;
    }
    dense_eigenvalues(&k, &m, "brake")
        .expect("brake")
        .into_iter()
        .map(hz)
        .collect()
}

/// `--modes auto --fmax F`: modes kept, the error of the free-boundary frequencies below F
/// against the full parts, and that of the frictionless brake's frequencies below F against
/// the brake reduced with factor 4.
fn auto_study(level: &str, fmax: f64) {
    println!("\n### Automatic mode choice, {level} meshes, fmax = {fmax} Hz\n");
    println!("Modes kept below factor x fmax (patch interface); largest relative error of the");
    println!(
        "free-boundary frequencies of each part below fmax against the full model, and of the"
    );
    println!("frictionless brake's frequencies below fmax (disc and pad on the contact springs)");
    println!("against the same brake reduced with factor 4.\n");
    println!("| factor | disc modes | pad modes | disc error | pad error | brake error |");
    println!("|---|---|---|---|---|---|");
    let full: Vec<Vec<f64>> = PARTS
        .iter()
        .map(|p| full_frequencies(p, level, 80))
        .collect();
    let reduce = |factor: f64| {
        let choice = ModeChoice::Auto {
            fmax_hz: fmax,
            factor,
        };
        brake(
            &inputs(level, InterfaceKind::Patch, choice),
            &format!("{level}-auto-{factor}"),
        )
    };
    let reference: Vec<f64> = brake_frequencies(&reduce(4.0))
        .into_iter()
        .filter(|&f| f < fmax)
        .collect();
    for factor in [1.0, 1.5, 2.0, 3.0] {
        let model = reduce(factor);
        let mut row = format!("| {factor} |");
        for part in PARTS {
            row += &format!(
                " {} |",
                model
                    .part(part)
                    .expect("part")
                    .info
                    .fixed_interface_hz
                    .len()
            );
        }
        for (k, part) in PARTS.iter().enumerate() {
            let below: Vec<f64> = full[k].iter().copied().filter(|&f| f < fmax).collect();
            assert!(
                below.len() < full[k].len(),
                "{part}: more than 80 modes below fmax"
            );
            let f =
                reduced_frequencies(model.part(part).expect("part"), Boundary::Free).expect("f");
            let worst = relative_errors(&f, &below).into_iter().fold(0.0, f64::max);
            row += &format!(" {worst:.1e} |");
        }
        let f = brake_frequencies(&model);
        let worst = relative_errors(&f, &reference)
            .into_iter()
            .fold(0.0, f64::max);
        row += &format!(" {worst:.1e} |");
        println!("{row}");
    }
    println!(
        "\n({} brake frequencies below fmax; the lowest {:.1} Hz.)",
        reference.len(),
        reference.first().copied().unwrap_or(0.0)
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let levels: Vec<String> = args.iter().skip(1).cloned().collect();
    match args.first().map(String::as_str) {
        Some("modes") => levels.iter().for_each(|l| modes_study(l)),
        Some("convergence") => convergence_study(&levels),
        Some("auto") => levels.iter().for_each(|l| auto_study(l, 10_000.0)),
        _ => eprintln!("usage: study modes|convergence|auto LEVEL..."),
    }
}
