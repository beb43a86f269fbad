//! The plain-data interface: both velocity inputs, 8-node quadrilaterals, the levels of a
//! periodic motion and the refusals.

use squeal_acoustics::{
    AcousticsError, Air, Complex64, FaceRule, Facing, Harmonic, RadiatingSurface, Velocity,
    a_weighting_db, erp, rayleigh, sound, spl_db,
};

/// A 2 x 1 m rectangle in z = 0 as two 8-node quads, normal +z.
fn rectangle() -> (Vec<[f64; 3]>, Vec<u32>) {
    let nodes = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [2.0, 1.0, 0.0],
        [0.5, 0.0, 0.0],
        [1.5, 0.0, 0.0],
        [0.5, 1.0, 0.0],
        [1.5, 1.0, 0.0],
        [0.0, 0.5, 0.0],
        [1.0, 0.5, 0.0],
        [2.0, 0.5, 0.0],
    ];
    // Corners counterclockwise from +z, then midsides of 0-1, 1-2, 2-3, 3-0.
    let faces = vec![0, 1, 4, 3, 6, 11, 8, 10, 1, 2, 5, 4, 7, 12, 9, 11];
    (nodes, faces)
}

/// Quad8 faces: area 2 exactly (an affine map: 1e-14 is round-off of 18 terms), +z normals, and the same
/// normal velocity from a 3-D nodal velocity along z as from the face-node normal values
/// (1e-15: the same sums).
#[test]
fn quad8_faces_and_both_velocity_inputs() {
    let (nodes, faces) = rectangle();
    let s = RadiatingSurface::new(&nodes, &faces, &FaceRule::quad8(3).unwrap()).unwrap();
    assert!((s.area() - 2.0).abs() < 1e-14, "{}", s.area() - 2.0);
    assert!(s.points.iter().all(|p| (p.normal[2] - 1.0).abs() < 1e-15));
    let v = Complex64::new(0.3, -0.4);
    let zero = Complex64::new(0.0, 0.0);
    let a = s
        .normal_velocity(Velocity::FaceNodes(&vec![v; faces.len()]))
        .unwrap();
    let b = s
        .normal_velocity(Velocity::Nodal(&vec![[zero, zero, v]; nodes.len()]))
        .unwrap();
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).norm() < 1e-15);
    }
    let air = Air::default();
    // ERP = ½ ρ c |v|² A.
    let e = erp(&air, &s, &a);
    assert!((e - 0.5 * air.impedance() * 0.25 * 2.0).abs() < 1e-12 * e);
}

/// The overall level of two harmonics is the power sum of their A-weighted rms levels
/// (1e-9 dB: the same formula reassembled), and the ERP adds over harmonics.
#[test]
fn levels_of_a_periodic_motion() {
    let (nodes, faces) = rectangle();
    let s = RadiatingSurface::new(&nodes, &faces, &FaceRule::quad8(4).unwrap()).unwrap();
    let air = Air::default();
    let v1 = vec![Complex64::new(1e-4, 0.0); faces.len()];
    let v2 = vec![Complex64::new(0.0, 3e-5); faces.len()];
    let w = 2.0 * std::f64::consts::PI * 2000.0;
    let harmonics = [
        Harmonic {
            order: 1,
            omega: w,
            velocity: Velocity::FaceNodes(&v1),
        },
        Harmonic {
            order: 2,
            omega: 2.0 * w,
            velocity: Velocity::FaceNodes(&v2),
        },
    ];
    let mic = [[1.0, 0.5, 0.5]];
    let out = sound(&air, &s, &harmonics, &mic, Facing::All).unwrap();
    let mut ms = 0.0;
    for (h, hs) in harmonics.iter().zip(&out.harmonics) {
        let vn = s.normal_velocity(h.velocity).unwrap();
        let p = rayleigh(&air, &s, &vn, h.omega, mic[0], Facing::All).unwrap();
        assert!((p - hs.rayleigh[0]).norm() < 1e-15 * p.norm());
        let l = spl_db(p.norm() / 2f64.sqrt()) + a_weighting_db(hs.frequency_hz);
        ms += 10f64.powf(l / 10.0);
    }
    assert!((out.rayleigh_dba[0] - 10.0 * ms.log10()).abs() < 1e-9);
    let sum: f64 = out.harmonics.iter().map(|h| h.erp_w).sum();
    assert!((out.erp_w - sum).abs() < 1e-15 * sum);
}

/// Inputs that cannot be used are errors, not numbers.
#[test]
fn refusals() {
    let (nodes, faces) = rectangle();
    let rule = FaceRule::quad8(2).unwrap();
    let s = RadiatingSurface::new(&nodes, &faces, &rule).unwrap();
    let air = Air::default();
    assert!(matches!(
        RadiatingSurface::new(&nodes, &faces[..15], &rule),
        Err(AcousticsError::Length { .. })
    ));
    let mut bad = faces.clone();
    bad[3] = 99;
    assert!(matches!(
        RadiatingSurface::new(&nodes, &bad, &rule),
        Err(AcousticsError::NodeOutOfRange {
            face: 0,
            node: 99,
            ..
        })
    ));
    let mut flat = nodes.clone();
    for p in &mut flat {
        p[1] = 0.0;
    }
    assert!(matches!(
        RadiatingSurface::new(&flat, &faces, &rule),
        Err(AcousticsError::DegenerateFace { .. })
    ));
    assert!(s.normal_velocity(Velocity::FaceNodes(&[])).is_err());
    let vn = vec![Complex64::new(1.0, 0.0); s.points.len()];
    let on = s.points[0].position;
    assert!(matches!(
        rayleigh(&air, &s, &vn, 1e3, on, Facing::All),
        Err(AcousticsError::MicrophoneOnSurface { .. })
    ));
    let thin = Air {
        density: 0.0,
        ..Air::default()
    };
    let v = vec![Complex64::new(1.0, 0.0); faces.len()];
    let h = [Harmonic {
        order: 1,
        omega: 1e3,
        velocity: Velocity::FaceNodes(&v),
    }];
    assert!(sound(&thin, &s, &h, &[[0.0, 0.0, 1.0]], Facing::All).is_err());
    let h0 = [Harmonic { omega: 0.0, ..h[0] }];
    assert!(sound(&air, &s, &h0, &[[0.0, 0.0, 1.0]], Facing::All).is_err());
}
