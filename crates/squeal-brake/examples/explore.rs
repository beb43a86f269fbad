use squeal_brake::assemble::{BrakeParams, Stiffness, assemble};
use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::modal::Damping;
use squeal_brake::sweep::{Band, SweepOptions, reference, sweep};
use squeal_fe::{MaterialTable, Restraint};
use squeal_reduce::craig_bampton::{PartSpec, ReduceOptions, reduce_part};
use squeal_reduce::interface::Axis;
use squeal_reduce::rom::{InterfaceKind, MeshInfo, ReducedModel};
use std::path::PathBuf;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let level = args.get(1).cloned().unwrap_or("coarse".into());
    let interface = if args.get(2).map(|s| s.as_str()) == Some("node") {
        InterfaceKind::Node
    } else {
        InterfaceKind::Patch
    };
    let sign: f64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1.0);
    let rom_path = PathBuf::from(format!("/tmp/brake_{level}_{interface:?}.rom"));
    let rom = if rom_path.exists() {
        ReducedModel::read(&rom_path).unwrap()
    } else {
        let mut parts = Vec::new();
        for name in ["disc", "pad"] {
            let file = format!("{name}_{level}.inp");
            let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
                .join("../../meshes")
                .join(&file);
            let mesh = squeal_mesh::read(&path).unwrap().mesh;
            let (restraints, piston) = if name == "disc" {
                (vec![Restraint::clamp("CLAMP")], None)
            } else {
                (
                    vec![Restraint::set("ABUTMENT", [true, true, false])],
                    Some("PISTON".to_string()),
                )
            };
            let info = MeshInfo {
                path: file,
                sha256: String::new(),
                nodes: mesh.num_nodes(),
                elements: mesh.num_elements(),
            };
            let spec = PartSpec {
                name: name.into(),
                mesh: info,
                restraints,
                interface,
                contact_set: "CONTACT".into(),
                contact_face_set: "CONTACT_FACE".into(),
                grid: [3, 3],
                axis: Axis::default(),
                piston_set: piston,
                normal_direction: 2,
                modes: 50,
            };
            let materials = MaterialTable::from_mesh(&mesh, &[]).unwrap();
            let t = std::time::Instant::now();
            let (part, _) = reduce_part(
                &mesh,
                &materials,
                &spec,
                &ReduceOptions::default(),
                &mut |_| {},
            )
            .unwrap();
            eprintln!(
                "{name}: reduced in {:.1?}; f_max {:.0} Hz",
                t.elapsed(),
                part.info.fixed_interface_hz.last().unwrap()
            );
            parts.push(part);
        }
        let rom = ReducedModel {
            tool_version: "explore".into(),
            parts,
        };
        rom.write(&rom_path).unwrap();
        rom
    };
    let footprint = 0.5 * 50f64.to_radians() * (0.135f64.powi(2) - 0.085f64.powi(2));
    let params = BrakeParams {
        normal: [0.0, 0.0, 1.0],
        sliding: [sign, 0.0, 0.0],
        stiffness: Stiffness::PerArea {
            linear: 1.25e10,
            cubic: 2.0e19,
            point_area: Some(footprint / 9.0),
        },
        pairing_tolerance: 1e-3,
        piston_force: 3000.0,
    };
    let (brake, _layout, pairs) = assemble(&rom, &params).unwrap();
    for p in &pairs {
        eprintln!(
            "pair disc {} pad {} dist {:.1e} area {:?} kl {:.3e}",
            p.disc_point, p.pad_point, p.distance, p.area, p.k_linear
        );
    }
    let damping = Damping {
        global_ratio: 0.01,
        extra: vec![],
    };
    let newton = NewtonOptions::default();
    let r = reference(&brake, &damping, &newton).unwrap();
    eprintln!(
        "eq0: iters {} res {:.1e} pen {:?}",
        r.equilibrium.iterations,
        r.equilibrium.residual,
        r.equilibrium
            .penetrations
            .iter()
            .map(|d| format!("{:.1}um", d * 1e6))
            .collect::<Vec<_>>()
    );
    let fvalid = rom
        .parts
        .iter()
        .map(|p| *p.info.fixed_interface_hz.last().unwrap())
        .fold(f64::INFINITY, f64::min);
    let opts = SweepOptions {
        band: Band {
            valid_max_hz: fvalid,
            user: Some((1000.0, 16000.0)),
        },
        ..Default::default()
    };
    let mus: Vec<f64> = (0..=200).map(|k| k as f64 * 1.0 / 200.0).collect();
    let t = std::time::Instant::now();
    let s = sweep(&brake, &r, &mus, &opts).unwrap();
    eprintln!("sweep {:.2?}, valid band < {:.0} Hz", t.elapsed(), fvalid);
    for c in s.crossings.iter().take(12) {
        eprintln!(
            "crossing b{} mu [{:.3},{:.3}] f {:.0} Hz in_band {}",
            c.branch, c.mu_lo, c.mu_hi, c.frequency_hz, c.in_band
        );
    }
    if let Some(h) = &s.hopf {
        eprintln!(
            "HOPF mu0 = {:.8} f = {:.1} Hz evals {} partner {:?}",
            h.mu0, h.frequency_hz, h.evaluations, h.partner
        );
    }
}
