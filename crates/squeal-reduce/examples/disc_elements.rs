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
//! tet10) from coarse to fine. Each hex20 mode is matched with the tet10 mode of largest MAC
//! on the nodes both meshes share (every hex20 node is a tet10 node at the same point; the
//! tetrahedra add the face- and cell-diagonal midside nodes), so modes that change order
//! between the meshes are still compared with their own kind; a disc's doublets are two modes
//! of one frequency in any rotation, so a doublet member may match either tet10 member, whose
//! frequencies are equal to the doublet's split. The table gives the pair's frequencies, the
//! MAC and the relative gap `tet10/hex20 − 1`. Both elements are conforming displacement
//! elements with exact consistent mass, so their frequencies are upper bounds that fall with
//! refinement; if both converge to the same limit the gap shrinks at each level.

use faer::Mat;
use squeal_eigs::{EigOptions, lowest_modes};
use squeal_fe::{DofMap, MaterialTable, Restraint, assemble};
use squeal_reduce::craig_bampton::hz;
use std::collections::HashMap;
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

/// How many of the clamped disc's lowest frequencies are compared.
const COUNT: usize = 24;

/// The clamped disc of one file: its lowest `COUNT` frequencies (Hz), and each mode's
/// displacements (x, y, z) at every node, by the node's position.
struct Disc {
    hz: Vec<f64>,
    nodes: usize,
    shapes: HashMap<[u64; 3], Vec<[f64; 3]>>,
}

/// The modes of the clamped disc in `path`.
fn frequencies(path: &Path) -> Result<Disc, String> {
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
    Ok(Disc {
        hz: modes.values.iter().map(|&w2| hz(w2)).collect(),
        nodes: disc.num_nodes(),
        shapes: shapes(&disc, &dofs, &modes.vectors),
    })
}

/// Each node's displacements in every mode, keyed by the bits of its coordinates (both
/// meshes of a level write a shared node with the same digits, so it parses to the same bits).
fn shapes(
    mesh: &squeal_mesh::Mesh,
    dofs: &DofMap,
    vectors: &Mat<f64>,
) -> HashMap<[u64; 3], Vec<[f64; 3]>> {
    let mut out = HashMap::new();
    for (n, x) in mesh.nodes.iter().enumerate() {
        let u = (0..vectors.ncols())
            .map(|j| {
                let mut v = [0.0; 3];
                for (d, vd) in v.iter_mut().enumerate() {
                    if let Some(i) = dofs.free_dof(n as u32, d) {
                        *vd = vectors[(i, j)];
                    }
                }
                v
            })
            .collect();
        out.insert(x.map(f64::to_bits), u);
    }
    out
}

/// MAC of `a`'s mode `i` and `b`'s mode `j` over the nodes both have.
fn mac(a: &Disc, i: usize, b: &Disc, j: usize) -> f64 {
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (key, ua) in &a.shapes {
        if let Some(ub) = b.shapes.get(key) {
            for d in 0..3 {
                ab += ua[i][d] * ub[j][d];
                aa += ua[i][d] * ua[i][d];
                bb += ub[j][d] * ub[j][d];
            }
        }
    }
    ab * ab / (aa * bb)
}

/// For each of `hex`'s modes, the `tet` mode of largest MAC and that MAC.
fn matches(hex: &Disc, tet: &Disc) -> Vec<(usize, f64)> {
    (0..hex.hz.len())
        .map(|i| {
            (0..tet.hz.len())
                .map(|j| (j, mac(hex, i, tet, j)))
                .fold((0, -1.0), |best, c| if c.1 > best.1 { c } else { best })
        })
        .collect()
}

fn main() -> ExitCode {
    let files: Vec<String> = std::env::args().skip(1).collect();
    if files.is_empty() || !files.len().is_multiple_of(2) {
        eprintln!("usage: disc_elements HEX20_COARSE TET10_COARSE [HEX20_NEXT TET10_NEXT ...]");
        return ExitCode::FAILURE;
    }
    let mut levels = Vec::new();
    for pair in files.chunks(2) {
        let mut both = Vec::new();
        for f in pair {
            let t = Instant::now();
            match frequencies(Path::new(f)) {
                Ok(disc) => {
                    eprintln!(
                        "{f}: {} disc nodes, {COUNT} modes in {:.1} s",
                        disc.nodes,
                        t.elapsed().as_secs_f64()
                    );
                    both.push(disc);
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::FAILURE;
                }
            }
        }
        let m = matches(&both[0], &both[1]);
        levels.push((both, m));
    }
    let mut head = String::from("| mode |");
    let mut rule = String::from("|---|");
    for (k, (l, _)) in levels.iter().enumerate() {
        head.push_str(&format!(
            " L{k} hex20 ({} n) | L{k} tet10 ({} n) | MAC | gap |",
            l[0].nodes, l[1].nodes
        ));
        rule.push_str("---|---|---|---|");
    }
    println!("{head}\n{rule}");
    let mut worst = vec![0.0_f64; levels.len()];
    for m in 0..COUNT {
        let mut row = format!("| {} |", m + 1);
        for (k, (l, pairs)) in levels.iter().enumerate() {
            let (j, mac) = pairs[m];
            let (h, t) = (l[0].hz[m], l[1].hz[j]);
            let gap = t / h - 1.0;
            worst[k] = worst[k].max(gap.abs());
            row.push_str(&format!(
                " {h:.2} | {t:.2} (#{}) | {mac:.3} | {gap:+.2e} |",
                j + 1
            ));
        }
        println!("{row}");
    }
    for (k, w) in worst.iter().enumerate() {
        println!("level {k}: largest |tet10/hex20 - 1| over the {COUNT} modes {w:.2e}");
    }
    ExitCode::SUCCESS
}
