//! The same disc meshed in 20-node hexahedra (with 15-node wedges at the bore) and in 10-node
//! tetrahedra, refined together: do both converge to the same natural frequencies? (Issue 21's
//! verification: "the same disc meshed in hex20 and in tet10 converging to the same
//! frequencies".)
//!
//! The meshes come from the brake-corner generator, which places every node of both element
//! kinds on the same map of (r, θ, z), so the two meshes of one level describe the same
//! geometry (edges along θ are quadratic arcs in both):
//!
//! ```sh
//! for d in hex20 tet10; do
//!   python3 tools/mesh/corner_meshes.py --levels coarse medium fine --disc $d --out DIR
//! done
//! cargo run --release -p squeal-reduce --example disc_elements -- \
//!   DIR/corner_coarse.inp DIR/corner_coarse_tetdisc.inp \
//!   DIR/corner_medium.inp DIR/corner_medium_tetdisc.inp \
//!   DIR/corner_fine.inp DIR/corner_fine_tetdisc.inp
//! ```
//!
//! Each file's element set `DISC` is taken as a part, clamped on `DISC_CLAMP` (the bore), and
//! its `COUNT` lowest frequencies are computed by shift-invert Lanczos on the assembled K and M
//! (the solver squeal's Craig–Bampton reduction uses). The files are given in pairs (hex20,
//! tet10) from coarse to fine; the table gives each pair's frequencies and their relative gap
//! `tet10/hex20 − 1`. Both elements are conforming displacement elements with exact consistent
//! mass, so their frequencies are upper bounds that fall with refinement; if both converge to
//! the same limit the gap shrinks at each level.

use squeal_eigs::{EigOptions, lowest_modes};
use squeal_fe::{DofMap, MaterialTable, Restraint, assemble};
use squeal_reduce::craig_bampton::hz;
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

/// How many of the clamped disc's lowest frequencies are compared.
const COUNT: usize = 24;

/// The lowest `COUNT` frequencies (Hz) of the clamped disc in `path`, and its node count.
fn frequencies(path: &Path) -> Result<(Vec<f64>, usize), String> {
    let read = squeal_mesh::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let disc = read
        .mesh
        .part("DISC")
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let materials = MaterialTable::from_mesh(&disc, &[]).map_err(|e| e.to_string())?;
    let dofs = DofMap::new(&disc, &[Restraint::set("DISC_CLAMP", [true; 3])])
        .map_err(|e| e.to_string())?;
    let system = assemble(&disc, &materials, &dofs).map_err(|e| e.to_string())?;
    let mut opts = EigOptions::default();
    // Below the clamped disc's lowest frequency (about 500 Hz): ω² = 4e5 is 100 Hz.
    opts.shift = -4e5;
    let modes = lowest_modes(system.k.as_ref(), system.m.as_ref(), COUNT, &opts)
        .map_err(|e| e.to_string())?;
    Ok((
        modes.values.iter().map(|&w2| hz(w2)).collect(),
        disc.num_nodes(),
    ))
}

fn main() -> ExitCode {
    let files: Vec<String> = std::env::args().skip(1).collect();
    if files.is_empty() || files.len() % 2 != 0 {
        eprintln!("usage: disc_elements HEX20_COARSE TET10_COARSE [HEX20_NEXT TET10_NEXT ...]");
        return ExitCode::FAILURE;
    }
    let mut levels = Vec::new();
    for pair in files.chunks(2) {
        let mut both = Vec::new();
        for f in pair {
            let t = Instant::now();
            match frequencies(Path::new(f)) {
                Ok((fr, nodes)) => {
                    eprintln!(
                        "{f}: {nodes} disc nodes, {COUNT} modes in {:.1} s",
                        t.elapsed().as_secs_f64()
                    );
                    both.push((fr, nodes));
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::FAILURE;
                }
            }
        }
        levels.push(both);
    }
    let mut head = String::from("| mode |");
    let mut rule = String::from("|---|");
    for (k, l) in levels.iter().enumerate() {
        head.push_str(&format!(
            " L{k} hex20 ({} n) | L{k} tet10 ({} n) | gap |",
            l[0].1, l[1].1
        ));
        rule.push_str("---|---|---|");
    }
    println!("{head}\n{rule}");
    let mut worst = vec![0.0_f64; levels.len()];
    for m in 0..COUNT {
        let mut row = format!("| {} |", m + 1);
        for (k, l) in levels.iter().enumerate() {
            let (h, t) = (l[0].0[m], l[1].0[m]);
            let gap = t / h - 1.0;
            worst[k] = worst[k].max(gap.abs());
            row.push_str(&format!(" {h:.2} | {t:.2} | {gap:+.2e} |"));
        }
        println!("{row}");
    }
    for (k, w) in worst.iter().enumerate() {
        println!("level {k}: largest |tet10/hex20 - 1| over the {COUNT} modes {w:.2e}");
    }
    ExitCode::SUCCESS
}
