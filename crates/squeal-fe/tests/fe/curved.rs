//! Stiffness quadrature of curved tet10 elements (see the module documentation of
//! `squeal_fe::element`): the 4-point rule is exact only for straight-sided elements, so curved
//! ones get the 24-point rule of degree 6. The reference is a collapsed Gauss rule of 12³
//! points (degree 21), shown converged against 16³ and 20³ points: it shares no point or
//! weight with the rules it judges.

use squeal_fe::{
    AssemblyOptions, DofMap, ElasticMaterial, MaterialTable, Quadrature, Restraint,
    STRAIGHT_TOLERANCE, assemble, assemble_with, element_stiffness,
};
use squeal_mesh::{Mesh, tet10};

type Ke = [[f64; 30]; 30];

fn read(name: &str) -> Mesh {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../meshes")
        .join(name);
    squeal_mesh::read(&path).unwrap().mesh
}

fn gauss(n: usize) -> Quadrature {
    Quadrature::collapsed_gauss(n).unwrap()
}

/// `‖a - b‖_F / ‖b‖_F`.
fn relative(a: &Ke, b: &Ke) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for (ra, rb) in a.iter().zip(b) {
        for (x, y) in ra.iter().zip(rb) {
            num += (x - y) * (x - y);
            den += y * y;
        }
    }
    (num / den).sqrt()
}

/// The disc's cast iron (meshes/README.md); the errors are relative, so only ν matters.
fn iron() -> ElasticMaterial {
    ElasticMaterial::isotropic(125e9, 0.25, 7200.0)
}

/// Every curved element of the coarse disc against the reference; the element with the largest
/// midside offset in detail, with the reference's convergence.
#[test]
fn curved_elements_of_the_coarse_disc_against_a_converged_rule() {
    let mesh = read("disc_coarse.inp");
    let c = iron().elasticity().unwrap();
    let (four, rule24, reference) = (
        Quadrature::four_point(),
        Quadrature::twenty_four_point(),
        gauss(12),
    );
    let offsets: Vec<f64> = (0..mesh.num_elements())
        .map(|e| tet10::midside_offset(&mesh.element_coords(e)))
        .collect();
    let most = (0..mesh.num_elements())
        .max_by(|&a, &b| offsets[a].total_cmp(&offsets[b]))
        .unwrap();
    let x = mesh.element_coords(most);
    let k = |rule: &Quadrature| element_stiffness(&x, &c, rule).unwrap();
    let k_ref = k(&reference);
    // Converged: 12³, 16³ and 20³ points agree to round-off (measured 3.7e-15).
    let converged = relative(&k_ref, &k(&gauss(20))).max(relative(&k(&gauss(16)), &k(&gauss(20))));
    let (e4, e24) = (relative(&k(&four), &k_ref), relative(&k(&rule24), &k_ref));
    eprintln!(
        "element {} (midside offset {:.3e}): 4-point {e4:.2e}, 24-point {e24:.2e}, reference 12³ vs 16³/20³ {converged:.1e}",
        mesh.element_ids[most], offsets[most]
    );
    assert!(converged < 1e-13, "reference not converged: {converged:e}");
    // Measured 6.6e-3 and 4.4e-8.
    assert!(
        e4 > 1e-3,
        "4-point error {e4:e}: the element is hardly curved"
    );
    assert!(e24 < 1e-7, "24-point error {e24:e}");

    // All curved elements: the worst relative error of each rule.
    let (mut worst4, mut worst24, mut curved) = (0.0_f64, 0.0_f64, 0);
    for (e, &offset) in offsets.iter().enumerate() {
        if offset <= STRAIGHT_TOLERANCE {
            continue;
        }
        curved += 1;
        let x = mesh.element_coords(e);
        let k_ref = element_stiffness(&x, &c, &reference).unwrap();
        let k4 = element_stiffness(&x, &c, &four).unwrap();
        let k24 = element_stiffness(&x, &c, &rule24).unwrap();
        worst4 = worst4.max(relative(&k4, &k_ref));
        worst24 = worst24.max(relative(&k24, &k_ref));
    }
    eprintln!("{curved} curved elements: worst 4-point {worst4:.2e}, worst 24-point {worst24:.2e}");
    // Measured 929, 1.4e-2 and 5.6e-5 (an element whose det J varies strongly: the integrand
    // is rational). Its effect on the frequencies is bounded by the next test.
    assert_eq!(curved, 929);
    assert!(worst24 < 1e-4, "worst 24-point error {worst24:e}");
}

/// The 4-point rule's error grows like the midside offset δ (first order: the degree-3 term
/// of the integrand), which sets the tolerance below which an element counts as straight; the
/// 24-point rule's error falls much faster.
#[test]
fn the_four_point_error_grows_like_the_midside_offset() {
    let mesh = read("disc_coarse.inp");
    let c = iron().elasticity().unwrap();
    let straight = (0..mesh.num_elements())
        .find(|&e| tet10::midside_offset(&mesh.element_coords(e)) < 1e-13)
        .unwrap();
    let x0 = mesh.element_coords(straight);
    let mut ratios = Vec::new();
    for delta in [1e-2, 1e-3, 1e-4, 1e-6, 1e-8] {
        // Each midside node moved by δ times its edge's length in a fixed oblique direction.
        let mut x = x0;
        for (k, &[a, b]) in tet10::EDGES.iter().enumerate() {
            let len = (0..3)
                .map(|d| (x0[b][d] - x0[a][d]).powi(2))
                .sum::<f64>()
                .sqrt();
            let dir = [1.0 + k as f64, 2.0 - k as f64, 0.5 * k as f64 - 1.0];
            let n = dir.iter().map(|v| v * v).sum::<f64>().sqrt();
            for d in 0..3 {
                x[4 + k][d] += delta * len * dir[d] / n;
            }
        }
        let k_ref = element_stiffness(&x, &c, &gauss(12)).unwrap();
        let e4 = relative(
            &element_stiffness(&x, &c, &Quadrature::four_point()).unwrap(),
            &k_ref,
        );
        let e24 = relative(
            &element_stiffness(&x, &c, &Quadrature::twenty_four_point()).unwrap(),
            &k_ref,
        );
        eprintln!(
            "δ = {delta:.0e}: 4-point {e4:.2e} ({:.2} δ), 24-point {e24:.2e}",
            e4 / delta
        );
        ratios.push(e4 / delta);
        if delta <= 1e-3 {
            // Round-off (1e-15) plus the high-order remainder (measured 4e-13 at 1e-3).
            assert!(e24 < 1e-11, "δ = {delta:e}: 24-point error {e24:e}");
        }
    }
    // First order down to δ = 1e-8, where the error is still 1e6 times round-off: the ratio
    // e4/δ is constant to 10 % (measured 0.31 at every δ for this element and direction).
    let (lo, hi) = ratios[1..]
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(l, h), &r| (l.min(r), h.max(r)));
    assert!(hi / lo < 1.1 && hi < 1.0, "e4/δ = {ratios:?}");
}

/// Straight-sided elements keep the 4-point rule, bit for bit; curved ones get the 24-point
/// rule.
#[test]
fn straight_elements_keep_the_four_point_bits() {
    let straight = squeal_mesh::generate::box_tet10([0.3, 0.1, 0.1], [3, 1, 1]);
    let materials = MaterialTable::uniform(&straight, iron()).unwrap();
    let dofs = DofMap::new(&straight, &[Restraint::clamp("XMIN")]).unwrap();
    let four_only = {
        let mut o = AssemblyOptions::default();
        o.straight_tolerance = f64::INFINITY;
        o
    };
    let a = assemble(&straight, &materials, &dofs).unwrap();
    let b = assemble_with(&straight, &materials, &dofs, &four_only).unwrap();
    assert!(
        a.k.val()
            .iter()
            .zip(b.k.val())
            .all(|(x, y)| x.to_bits() == y.to_bits())
    );
    let disc = read("disc_coarse.inp");
    let options = AssemblyOptions::default();
    let mut seen = [false; 2];
    for e in 0..disc.num_elements() {
        let x = disc.element_coords(e);
        let curved = tet10::midside_offset(&x) > STRAIGHT_TOLERANCE;
        let expect = if curved {
            Quadrature::twenty_four_point()
        } else {
            Quadrature::four_point()
        };
        assert_eq!(*options.stiffness_rule_for(&x), expect);
        seen[curved as usize] = true;
    }
    assert_eq!(seen, [true, true]);
}

/// Frequency in Hz of the 20 lowest modes of the coarse disc clamped on CLAMP.
fn disc_frequencies(mesh: &Mesh, options: &AssemblyOptions) -> Vec<f64> {
    let materials = MaterialTable::from_mesh(mesh, &[]).unwrap();
    let dofs = DofMap::new(mesh, &[Restraint::clamp("CLAMP")]).unwrap();
    let sys = assemble_with(mesh, &materials, &dofs, options).unwrap();
    // Shift-invert Lanczos, residual tolerance 1e-10: eigenvalue errors ~1e-20, and the
    // Sturm count guarantees no mode is missed.
    let modes = squeal_eigs::lowest_modes(
        sys.k.as_ref(),
        sys.m.as_ref(),
        20,
        &squeal_eigs::EigOptions::default(),
    )
    .unwrap();
    modes
        .values
        .iter()
        .map(|l| l.sqrt() / (2.0 * std::f64::consts::PI))
        .collect()
}

/// The coarse disc's 20 lowest clamped frequencies: the 4-point rule everywhere (before), the
/// default (24-point on curved elements) and the reference (12³-point collapsed Gauss on
/// every element; 10³ points agree with it to 5e-13).
#[test]
fn coarse_disc_frequencies_against_an_exactly_integrated_stiffness() {
    let mesh = read("disc_coarse.inp");
    let everywhere = |rule: Quadrature| {
        let mut o = AssemblyOptions::default();
        o.stiffness_rule = rule;
        o.straight_tolerance = f64::INFINITY;
        o
    };
    let f_ref = disc_frequencies(&mesh, &everywhere(gauss(12)));
    let f_old = disc_frequencies(&mesh, &everywhere(Quadrature::four_point()));
    let f_new = disc_frequencies(&mesh, &AssemblyOptions::default());
    let worst = |f: &[f64]| {
        f.iter()
            .zip(&f_ref)
            .map(|(a, b)| (a / b - 1.0).abs())
            .fold(0.0_f64, f64::max)
    };
    eprintln!("mode, reference (Hz), 4-point, default: relative errors");
    for i in 0..20 {
        eprintln!(
            "{:2} {:10.4} {:+.2e} {:+.2e}",
            i + 1,
            f_ref[i],
            f_old[i] / f_ref[i] - 1.0,
            f_new[i] / f_ref[i] - 1.0
        );
    }
    // The mass keeps its 14-point rule (degree 5) on curved elements, where its integrand has
    // degree 7: the exact mass (8³-point collapsed Gauss, degree 13) moves nothing that counts.
    let exact_mass = {
        let mut o = everywhere(gauss(12));
        o.mass_rule = gauss(8);
        o
    };
    let e_mass = worst(&disc_frequencies(&mesh, &exact_mass));
    let (e_old, e_new) = (worst(&f_old), worst(&f_new));
    eprintln!("worst: 4-point {e_old:.2e}, default {e_new:.2e}; exact mass {e_mass:.1e}");
    // Measured 7.5e-4 (the "up to 7e-4"), 5.7e-8 and 1.0e-11.
    assert!((5e-4..1e-3).contains(&e_old), "4-point: {e_old:e}");
    assert!(e_new < 2e-7, "default: {e_new:e}");
    assert!(e_mass < 1e-9, "exact mass: {e_mass:e}");
}

/// How many elements of each bundled mesh are curved, and that their straight elements are off
/// by round-off only (≤ 1e-12; measured ≤ 4.1e-14). The least curved elements (disc_fine:
/// offset 1.0e-8) sit at the tolerance, where the 4-point rule's error (~0.3 δ = 3e-9) is
/// negligible whichever rule they get.
#[test]
fn bundled_meshes_split_cleanly_into_straight_and_curved() {
    for name in [
        "disc_coarse.inp",
        "disc_medium.inp",
        "disc_fine.inp",
        "pad_coarse.inp",
        "pad_medium.inp",
        "pad_fine.inp",
    ] {
        let mesh = read(name);
        let offsets: Vec<f64> = (0..mesh.num_elements())
            .map(|e| tet10::midside_offset(&mesh.element_coords(e)))
            .collect();
        let curved = offsets.iter().filter(|&&o| o > STRAIGHT_TOLERANCE).count();
        let straight_max = offsets
            .iter()
            .filter(|&&o| o <= STRAIGHT_TOLERANCE)
            .fold(0.0_f64, |a, &o| a.max(o));
        let curved_min = offsets
            .iter()
            .filter(|&&o| o > STRAIGHT_TOLERANCE)
            .fold(f64::INFINITY, |a, &o| a.min(o));
        eprintln!(
            "{name}: {curved} of {} elements curved; straight offsets ≤ {straight_max:.1e}, curved ≥ {curved_min:.1e}",
            mesh.num_elements()
        );
        assert!(curved > 0, "{name}: no curved element");
        assert!(
            straight_max <= 1e-12,
            "{name}: straight offsets up to {straight_max:e}"
        );
    }
}
