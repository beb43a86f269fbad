use super::*;

#[test]
fn the_default_pairing_tolerance_is_one_millimetre_in_any_units() {
    // The default is in metres (1e-3); only a value the file gives is in its units.
    let base = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/brake.toml"),
    )
    .unwrap();
    let without: String = base
        .lines()
        .filter(|l| !l.starts_with("pairing_tolerance"))
        .map(|l| format!("{l}\n"))
        .collect();
    let mm = format!("{without}\n[units]\nsystem = \"mm-t-s\"\n");
    let path = Path::new("/scenes/brake.toml");
    for text in [without.clone(), mm.clone()] {
        let s = Scene::parse(path, text).unwrap();
        assert_eq!(s.pairing_tolerance().unwrap(), 1e-3);
    }
    let given = mm.replace("[contact]\n", "[contact]\npairing_tolerance = 0.5\n");
    let s = Scene::parse(path, given).unwrap();
    assert_eq!(
        s.pairing_tolerance().unwrap(),
        0.5e-3,
        "0.5 mm given in mm-t-s"
    );
}

#[test]
fn cubic_fit_recovers_an_exact_law() {
    // p = 1.25e10 d + 2e19 d^3 sampled exactly: the fit must return it to round-off.
    let d: Vec<f64> = (1..=8).map(|k| k as f64 * 5e-6).collect();
    let p: Vec<f64> = d.iter().map(|x| 1.25e10 * x + 2e19 * x.powi(3)).collect();
    let f = fit_cubic(&d, &p).unwrap();
    assert!(
        (f.linear / 1.25e10 - 1.0).abs() < 1e-10 && (f.cubic / 2e19 - 1.0).abs() < 1e-9,
        "{f:?}"
    );
    assert!(f.relative_rms < 1e-12);
}

fn bundled() -> (PathBuf, String) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/brake.toml");
    let base = std::fs::read_to_string(&path).unwrap();
    (path, base)
}

#[test]
fn the_disc_speed_comes_from_rpm_or_from_the_vehicle_speed() {
    let (path, base) = bundled();
    // The bundled scene has a [rotation] without a speed; the older [disc] form is read
    // from a scene without [rotation].
    let start = base.find("[rotation]").unwrap();
    let end = base[start..]
        .find("\n[")
        .map_or(base.len(), |e| start + e + 1);
    let no_rotation = format!("{}{}", &base[..start], &base[end..]);
    let with = |extra: &str| Scene::parse(&path, format!("{no_rotation}\n{extra}"));
    assert_eq!(with("").unwrap().disc_angular_speed().unwrap(), None);
    // 60 rpm is one turn a second: 2π rad/s, to round-off.
    let w = with("[disc]\nrpm = 60.0")
        .unwrap()
        .disc_angular_speed()
        .unwrap();
    assert!((w.unwrap() - 2.0 * std::f64::consts::PI).abs() < 1e-12);
    // 36 km/h = 10 m/s on a 0.25 m wheel: 40 rad/s, to round-off.
    let s = with("[disc]\nvehicle_speed_kmh = 36.0\nrolling_radius = 0.25").unwrap();
    assert!((s.disc_angular_speed().unwrap().unwrap() - 40.0).abs() < 1e-12);
    assert!(with("[disc]\nrpm = -1.0").is_err());
    assert!(with("[disc]\nvehicle_speed_kmh = 36.0").is_err());
    assert!(with("[disc]\nrpm = 60.0\nrolling_radius = 0.25").is_err());
    // The same speed in [rotation].
    let r = Scene::parse(
        &path,
        base.replace("[rotation]\n", "[rotation]\nrpm = 60.0\n"),
    )
    .unwrap()
    .rotation()
    .unwrap()
    .unwrap();
    assert!((r.angular_speed.unwrap() - 2.0 * std::f64::consts::PI).abs() < 1e-12);
}

#[test]
fn the_rotation_section_gives_axis_point_and_sense() {
    let (path, base) = bundled();
    let r = Scene::parse(&path, base.clone())
        .unwrap()
        .rotation()
        .unwrap()
        .unwrap();
    // The bundled disc turns clockwise about +z (seen from +z): under the pad (+y) its
    // surface moves along +x, the paper's global direction.
    assert_eq!(
        (r.axis, r.point, r.sense),
        ([0.0, 0.0, 1.0], [0.0; 3], -1.0)
    );
    let edit = |from: &str, to: &str| {
        assert!(base.contains(from), "{from}");
        Scene::parse(&path, base.replacen(from, to, 1))
    };
    let about_y = base
        .replacen(
            "axis = [0.0, 0.0, 1.0]\npoint = [0.0, 0.0, 0.0]",
            "axis = [0.0, 2.0, 0.0]\npoint = [0.1, 0, 0.3]",
            1,
        )
        .replacen("normal = [0.0, 0.0, 1.0]", "normal = [0.0, 1.0, 0.0]", 1)
        .replacen(
            "sliding_direction = [1.0, 0.0, 0.0]",
            "sliding = \"tangent\"",
            1,
        );
    let r = Scene::parse(&path, about_y)
        .unwrap()
        .rotation()
        .unwrap()
        .unwrap();
    // A direction is made unit exactly when it is a multiple of a coordinate axis.
    assert_eq!((r.axis, r.point), ([0.0, 1.0, 0.0], [0.1, 0.0, 0.3]));
    // The axis turned to y with the normal left along z: refused.
    let e = edit("axis = [0.0, 0.0, 1.0]", "axis = [0.0, 1.0, 0.0]").unwrap_err();
    assert!(e.to_string().contains("90.0 degrees"), "{e}");
    let e = edit("sense = \"clockwise\"", "sense = \"cw\"").unwrap_err();
    assert!(e.to_string().contains("rotation.sense"), "{e}");
    assert!(edit("axis = [0.0, 0.0, 1.0]", "axis = [0.0, 0.0, 0.0]").is_err());
    // A normal 10 degrees from the axis: refused; 3 degrees (a coned face) passes.
    let tilted = |deg: f64| {
        let a = deg.to_radians();
        edit(
            "normal = [0.0, 0.0, 1.0]",
            &format!("normal = [0.0, {:?}, {:?}]", a.sin(), a.cos()),
        )
    };
    let e = tilted(10.0).unwrap_err();
    assert!(
        e.to_string().contains("10.0 degrees from rotation.axis"),
        "{e}"
    );
    assert!(tilted(3.0).is_ok());
    // The normal reversed (from the pad into the disc) is along the axis too: the mesh's
    // normals decide the sign, and the brake checks the given one against them.
    assert!(edit("normal = [0.0, 0.0, 1.0]", "normal = [0.0, 0.0, -1.0]").is_ok());
    // [rotation] and the older [disc] at once: refused, naming both.
    let e = Scene::parse(&path, format!("{base}\n[disc]\nrpm = 60.0")).unwrap_err();
    assert!(e.to_string().contains("[disc] is the older form"), "{e}");
}

#[test]
fn sliding_is_the_tangent_by_default_or_a_global_direction() {
    let (path, base) = bundled();
    let line = "sliding_direction = [1.0, 0.0, 0.0]";
    assert!(base.contains(line));
    let s = |text: String| Scene::parse(&path, text).map(|s| s.sliding().unwrap());
    assert_eq!(s(base.clone()).unwrap(), Sliding::Global([1.0, 0.0, 0.0]));
    assert_eq!(s(base.replace(line, "")).unwrap(), Sliding::Tangent);
    assert_eq!(
        s(base.replace(line, "sliding = \"tangent\"")).unwrap(),
        Sliding::Tangent
    );
    assert_eq!(
        s(base.replace(line, "sliding = [2, 0, 0]")).unwrap(),
        Sliding::Global([1.0, 0.0, 0.0])
    );
    // Both forms at once, a direction along the normal, a word that is not "tangent".
    for bad in [
        format!("{line}\nsliding = \"tangent\""),
        "sliding = [0.0, 0.0, 1.0]".into(),
        "sliding = \"radial\"".into(),
    ] {
        assert!(s(base.replace(line, &bad)).is_err(), "{bad}");
    }
    // Tangent sliding without [rotation]: refused with a message saying what to add.
    let start = base.find("[rotation]").unwrap();
    let end = base[start..]
        .find("\n[")
        .map_or(base.len(), |e| start + e + 1);
    let no_rotation = format!("{}{}", &base[..start], &base[end..]);
    let e = Scene::parse(&path, no_rotation.replace(line, "")).unwrap_err();
    assert!(e.to_string().contains("needs a [rotation]"), "{e}");
}

#[test]
fn initial_gaps_are_one_value_a_list_or_closed() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/brake.toml");
    let base = std::fs::read_to_string(&path).unwrap();
    let with = |extra: &str| {
        Scene::parse(
            &path,
            base.replace("[contact]\n", &format!("[contact]\n{extra}\n")),
        )
    };
    let gaps = |extra: &str| with(extra).unwrap().initial_gaps().unwrap();
    assert_eq!(gaps(""), GapSetting::Geometric);
    assert_eq!(gaps("initial_gap = 1.0e-4"), GapSetting::Uniform(1e-4));
    assert_eq!(gaps("initial_gap = 0"), GapSetting::Uniform(0.0));
    assert_eq!(
        gaps("initial_gap = [1.0e-4, 0, -2.0e-6]"),
        GapSetting::PerPair(vec![1e-4, 0.0, -2e-6])
    );
    assert_eq!(gaps("close_initial_gaps = true"), GapSetting::Closed);
    assert_eq!(gaps("close_initial_gaps = false"), GapSetting::Geometric);
    for bad in [
        "initial_gap = \"0.1 mm\"",
        "initial_gap = []",
        "initial_gap = [1.0e-4, \"x\"]",
        "initial_gap = nan",
        "initial_gap = 1.0e-4\nclose_initial_gaps = true",
    ] {
        let e = with(bad).unwrap_err().to_string();
        // The error names the key and its line in the scene.
        assert!(
            e.contains("contact.initial_gap") && e.contains("brake.toml:"),
            "{e}"
        );
    }
}

#[test]
fn ranges_parse_like_linspace() {
    assert_eq!(
        parse_range("0..1/5").unwrap(),
        vec![0.0, 0.25, 0.5, 0.75, 1.0]
    );
    assert_eq!(parse_range(" 0.2 .. 0.3 / 2").unwrap(), vec![0.2, 0.3]);
    for bad in [
        "1..0/5", "0..1", "a..1/3", "0..1/1", "0..nan/3", "0..1/2.5", "0.5/3", "",
    ] {
        assert!(parse_range(bad).is_err(), "{bad}");
    }
}

/// `0:0.5:100` swept 0-0.5 in 100 steps where MATLAB reads 0 to 100 in steps of 0.5: the
/// colon form is refused, and the message shows the form that is read.
#[test]
fn the_ambiguous_colon_form_is_refused() {
    for old in ["0:0.5:100", "0:1:201", "0:1"] {
        let e = parse_range(old).unwrap_err();
        assert!(e.contains("ambiguous") && e.contains("0..1/201"), "{e}");
    }
}

#[test]
fn scene_materials_are_read_in_the_scene_units() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/brake.toml");
    let base = std::fs::read_to_string(&path).unwrap();
    let lining = "[units]\nsystem = \"mm-t-s\"\n[materials.LINING]\nyoung_plane = 5000\npoisson_plane = 0.25\n\
                  young_axial = 2000\npoisson_plane_axial = 0.2\nshear_axial = 1000\ndensity = 2.5e-9\n\
                  [materials.DISC]\nyoung = 125e3\npoisson = 0.26\ndensity = 7.2e-9";
    let s = Scene::parse(&path, format!("{base}\n{lining}")).unwrap();
    let m = s.materials().unwrap();
    // BTreeMap order: DISC, LINING. MPa -> Pa and t/mm^3 -> kg/m^3 by the exact factors
    // 1e6 and 1e12: one rounding each.
    let rel = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-15;
    match m[0].1 {
        squeal_fe::ElasticMaterial::Isotropic { young, density, .. } => {
            assert!(rel(young, 125e9) && rel(density, 7200.0), "{:?}", m[0]);
        }
        ref other => panic!("{other:?}"),
    }
    match m[1].1 {
        squeal_fe::ElasticMaterial::TransverselyIsotropic {
            young_plane,
            young_axial,
            shear_axial,
            axis,
            density,
            ..
        } => {
            assert!(rel(young_plane, 5e9) && rel(young_axial, 2e9) && rel(shear_axial, 1e9));
            assert!(rel(density, 2500.0));
            // The axis defaults to contact.normal.
            assert_eq!(axis, [0.0, 0.0, 1.0]);
        }
        ref other => panic!("{other:?}"),
    }
    assert!(s.material_warnings().unwrap().is_empty());
}
