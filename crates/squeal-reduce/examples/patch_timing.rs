//! Wall time of the patch interface (`interface::patches`) on the bundled meshes: the contact
//! face of each part cut on a few grids, best of several runs (the mesh is read once; the
//! timing covers finding the face's triangles and integrating the patches).
//!
//! ```sh
//! cargo run --release -p squeal-reduce --example patch_timing -- fine
//! ```
//!
//! Measured on 2 shared cores (best of 5, three runs): the 3 x 3 grid, whose cuts are mesh
//! edges, takes what the whole-triangle patches took before clipping, disc 0.43 ms (coarse) and
//! 5.9 ms (fine, 855 face triangles; most of it finding the face among the disc's elements),
//! pad 0.22 and 2.0 ms. Clipping adds about 10 µs per crossed triangle: fine disc 4 x 4
//! 7.6 ms, 2 x 5 6.9 ms, 5 x 7 9.1 ms (371 triangles crossed); fine pad 4.0, 3.4, 5.2 ms.

use squeal_reduce::interface::{Axis, patches};
use std::path::PathBuf;
use std::time::Instant;

fn main() {
    let levels: Vec<String> = std::env::args().skip(1).collect();
    let levels = if levels.is_empty() {
        vec!["fine".to_string()]
    } else {
        levels
    };
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
    for level in &levels {
        for part in ["disc", "pad"] {
            let path = root.join(format!("{part}_{level}.inp"));
            let mesh = match squeal_mesh::read(&path) {
                Ok(m) => m.mesh,
                Err(e) => {
                    eprintln!("{}: {e}", path.display());
                    std::process::exit(1);
                }
            };
            for grid in [[3, 3], [4, 4], [2, 5], [5, 7]] {
                let mut best = f64::INFINITY;
                let mut area = 0.0;
                for _ in 0..5 {
                    let t = Instant::now();
                    match patches(&mesh, "CONTACT_FACE", grid[0], grid[1], &Axis::default()) {
                        Ok(p) => area = p.iter().map(|q| q.area).sum::<f64>(),
                        Err(e) => {
                            println!("{part}_{level} {grid:?}: {e}");
                            break;
                        }
                    }
                    best = best.min(t.elapsed().as_secs_f64());
                }
                if best.is_finite() {
                    println!(
                        "{part}_{level} {grid:?}: {:.2} ms (face area {area:.9e} m^2)",
                        best * 1e3
                    );
                }
            }
        }
    }
}
