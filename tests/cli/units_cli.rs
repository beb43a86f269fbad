//! Issue 21, item 5: `squeal mesh info` and `squeal fe export` read a mesh in the units it is
//! written in (`--units`), take `--material` in those units, print SI with its unit, and warn
//! on values no brake part has without a scene, as they do with one.
//!
//! Before: no `--units`; the bundled pad written in mm (mm, tonne, s, N, MPa) printed "E =
//! 2.0000e3 Pa", its volume in mm^3 labelled m^3 and its mass 1e3 times too small in kg, with
//! no warning. The reference is the same pad in SI (meshes/pad_coarse.inp): the mm file is
//! that file with coordinates x 1e3, moduli x 1e-6 and densities x 1e-12, so converted back it
//! must give the same volume and mass to round-off (1e-12 relative: a handful of roundings
//! of each coordinate and constant by 1e3 steps; a wrong conversion is off by powers of 1e3).

use super::common;

use common::{root, squeal, temp_dir};
use std::path::{Path, PathBuf};

/// meshes/pad_coarse.inp rewritten in mm, tonne, s, N, MPa.
fn pad_in_mm(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(root().join("meshes/pad_coarse.inp")).unwrap();
    let mut out = String::new();
    let mut block = "";
    for l in text.lines() {
        if l.starts_with('*') {
            block = match l.split(',').next().unwrap().trim() {
                "*NODE" => "node",
                "*ELASTIC" => "elastic",
                "*DENSITY" => "density",
                _ => "",
            };
            out.push_str(l);
        } else {
            let v: Vec<&str> = l.split(',').map(str::trim).collect();
            let scaled = |x: &str, f: f64| format!("{:e}", x.parse::<f64>().unwrap() * f);
            let line = match block {
                "node" => format!(
                    "{}, {}, {}, {}",
                    v[0],
                    scaled(v[1], 1e3),
                    scaled(v[2], 1e3),
                    scaled(v[3], 1e3)
                ),
                "elastic" => format!("{}, {}", scaled(v[0], 1e-6), v[1]),
                "density" => scaled(v[0], 1e-12),
                _ => l.to_string(),
            };
            out.push_str(&line);
        }
        out.push('\n');
    }
    let path = dir.join("pad_mm.inp");
    std::fs::write(&path, out).unwrap();
    path
}

/// The number after `key` on the line that starts with it (`  mass      1.234e0 kg`).
fn value(text: &str, key: &str) -> f64 {
    let l = text
        .lines()
        .find(|l| l.trim_start().starts_with(key))
        .unwrap_or_else(|| panic!("no {key} in {text}"));
    l.trim_start()[key.len()..]
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs()
}

#[test]
fn mesh_info_reads_a_mesh_in_mm_and_prints_si() {
    let dir = temp_dir("units", "mesh-info");
    let mm = pad_in_mm(&dir);
    let si = root().join("meshes/pad_coarse.inp");
    let reference = squeal(&["mesh", "info", si.to_str().unwrap()]);
    let reference = String::from_utf8_lossy(&reference.stdout).into_owned();

    let o = squeal(&["mesh", "info", mm.to_str().unwrap(), "--units", "mm"]);
    let (out, err) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(!err.contains("warning"), "{err}");
    for key in ["volume", "mass"] {
        assert!(
            close(value(&out, key), value(&reference, key)),
            "{key}: {out} against {reference}"
        );
    }
    assert!(out.contains("read as mm-t-s"), "{out}");
    assert!(out.contains("E = 2.1000e11 Pa"), "{out}");
    // Densities with 6 significant digits (7850 x 1e-12 x 1e12 is 7849.999999999999).
    assert!(out.contains("rho = 7850.00 kg/m^3"), "{out}");

    // --material in the same units: MPa and t/mm^3.
    let o = squeal(&[
        "mesh",
        "info",
        mm.to_str().unwrap(),
        "--units",
        "mm",
        "--material",
        "BACKPLATE=2.1e5,0.3,7.85e-9",
        "--material",
        "LINING=2e3,0.25,2.5e-9",
    ]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0));
    assert!(
        out.contains("E = 2.1000e11 Pa, nu = 0.3, rho = 7850.00 kg/m^3"),
        "{out}"
    );
    assert!(
        close(value(&out, "mass"), value(&reference, "mass")),
        "{out}"
    );

    // Without --units the mm file is read as SI: a warning for its size and each material,
    // naming the system that fits.
    let o = squeal(&["mesh", "info", mm.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0));
    for says in [
        "pad_mm.inp: the mesh is",
        "Young's modulus 2.1000e5 Pa",
        "density 7.8500e-9 kg/m^3",
        "mm-t-s",
        "--units",
    ] {
        assert!(err.contains(says), "{says}: {err}");
    }
    // A --material in Pa on a mesh read in mm is 1e6 too stiff: warned about.
    let o = squeal(&[
        "mesh",
        "info",
        mm.to_str().unwrap(),
        "--units",
        "mm",
        "--material",
        "BACKPLATE=2.1e11,0.3,7.85e-9",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--material BACKPLATE: Young's modulus 2.1000e17 Pa"),
        "{err}"
    );
    // An unknown system is an error naming the ones there are.
    let o = squeal(&["mesh", "info", mm.to_str().unwrap(), "--units", "cm"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("--units") && err.contains("mm-t-s"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Each stored entry of a MatrixMarket file (row, column, value).
fn entries(path: &Path) -> Vec<(usize, usize, f64)> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with('%'))
        .skip(1)
        .map(|l| {
            let v: Vec<&str> = l.split_whitespace().collect();
            (
                v[0].parse().unwrap(),
                v[1].parse().unwrap(),
                v[2].parse().unwrap(),
            )
        })
        .collect()
}

#[test]
fn fe_export_of_a_mesh_in_mm_gives_the_si_matrices() {
    let dir = temp_dir("units", "fe-export");
    let mm = pad_in_mm(&dir);
    let si = root().join("meshes/pad_coarse.inp");
    let (a, b) = (dir.join("si"), dir.join("mm"));
    let o = squeal(&[
        "fe",
        "export",
        si.to_str().unwrap(),
        "-o",
        a.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0));
    let o = squeal(&[
        "fe",
        "export",
        mm.to_str().unwrap(),
        "--units",
        "mm",
        "-o",
        b.to_str().unwrap(),
    ]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(out.contains("K in N/m and M in kg"), "{out}");
    for (x, y) in [
        ("pad_coarse_K.mtx", "pad_mm_K.mtx"),
        ("pad_coarse_M.mtx", "pad_mm_M.mtx"),
    ] {
        let (ex, ey) = (entries(&a.join(x)), entries(&b.join(y)));
        assert_eq!(ex.len(), ey.len());
        // Relative to the largest entry: an entry of round-off size may differ in its digits.
        let big = ex.iter().fold(0.0f64, |m, e| m.max(e.2.abs()));
        for (p, q) in ex.iter().zip(&ey) {
            assert!(
                p.0 == q.0 && p.1 == q.1 && (p.2 - q.2).abs() <= 1e-12 * big,
                "{x}: {p:?} against {q:?}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
