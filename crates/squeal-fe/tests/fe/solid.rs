//! The 20-node hexahedron, 15-node wedge and 13-node pyramid: patch tests on distorted
//! meshes, exact consistent mass, the hex20's zero-energy modes under reduced integration,
//! and hex20 and tet10 meshes of one block converging to the same frequencies.

// Index loops mirror the formulas (coordinates, Voigt pairs).
#![allow(clippy::needless_range_loop)]

use super::common;
use common::{
    PATCH_A as A, distort_solid, dot, linear_field, lining, lowest_eigenvalues, matvec,
    on_box_boundary, steel,
};
use squeal_fe::{
    AssemblyOptions, DofMap, ElementKind, MaterialTable, ReferenceElement, assemble, assemble_with,
    strain_of,
};
use squeal_mesh::generate::box_solid;
use squeal_mesh::{BlockVisitor, Mesh};

const KINDS: [ElementKind; 3] = [
    ElementKind::Hex20,
    ElementKind::Wedge15,
    ElementKind::Pyramid13,
];

const EPS: [f64; 6] = [
    A[0][0],
    A[1][1],
    A[2][2],
    A[0][1] + A[1][0],
    A[0][2] + A[2][0],
    A[1][2] + A[2][1],
];

/// The largest strain error at the stiffness rule's points over every element.
struct StrainCheck<'a> {
    mesh: &'a Mesh,
    field: &'a [[f64; 3]],
    worst: f64,
}

impl BlockVisitor for StrainCheck<'_> {
    type Error = squeal_fe::ElementError;
    fn block<E: ReferenceElement<N>, const N: usize>(
        &mut self,
        _first: usize,
        conn: &[[u32; N]],
    ) -> Result<(), Self::Error> {
        for c in conn {
            let x = self.mesh.coords(c);
            let u: [[f64; 3]; N] = std::array::from_fn(|a| self.field[c[a] as usize]);
            for p in E::stiffness_rule().points {
                let s = strain_of::<E, N>(&x, &u, p)?;
                for k in 0..6 {
                    self.worst = self.worst.max((s[k] - EPS[k]).abs());
                }
            }
        }
        Ok(())
    }
}

/// Irons's patch test, as patch.rs does it for tet10: on a mesh whose interior vertices are
/// moved by up to `amp` (edges kept straight), a linear field gives its constant strain at
/// every quadrature point, no residual `K u` at interior nodes, and the strain energy
/// `V εᵀ C ε / 2`.
fn patch_test(kind: ElementKind, amp: f64, options: &AssemblyOptions) -> (f64, f64, f64) {
    let mut mesh = box_solid(kind, [1.0, 0.8, 0.6], [3, 3, 3]);
    distort_solid(&mut mesh, amp, 11);
    let materials = MaterialTable::uniform(&mesh, lining()).unwrap();
    let c = materials.entries[0].elasticity;
    let dofs = DofMap::new(&mesh, &[]).unwrap();
    let sys = assemble_with(&mesh, &materials, &dofs, options).unwrap();
    let field: Vec<[f64; 3]> = mesh.nodes.iter().map(|&x| linear_field(x)).collect();
    let u = dofs.restrict(&field);
    let mut strain = StrainCheck {
        mesh: &mesh,
        field: &field,
        worst: 0.0,
    };
    mesh.blocks.visit(&mut strain).unwrap();
    let (sym, val) = (sys.k.symbolic(), sys.k.val());
    let r = matvec(&sys.k, &u);
    let mut row_abs = vec![0.0; u.len()];
    for (col, uc) in u.iter().enumerate() {
        for k in sym.col_ptr()[col]..sym.col_ptr()[col + 1] {
            row_abs[sym.row_idx()[k]] += (val[k] * uc).abs();
        }
    }
    let boundary = on_box_boundary(&mesh);
    let mut worst = 0.0_f64;
    for f in 0..u.len() {
        let (node, _) = dofs.node_dir(f).unwrap();
        if !boundary[node as usize] {
            worst = worst.max(r[f].abs() / row_abs[f]);
        }
    }
    let energy = dot(&u, &r);
    let exact: f64 = 0.48
        * (0..6)
            .map(|i| (0..6).map(|j| EPS[i] * c[i][j] * EPS[j]).sum::<f64>())
            .sum::<f64>();
    (strain.worst, worst, energy / exact - 1.0)
}

#[test]
fn linear_fields_pass_the_patch_test_on_distorted_meshes() {
    for kind in KINDS {
        let (strain, residual, energy) = patch_test(kind, 0.04, &AssemblyOptions::default());
        eprintln!(
            "{kind}: strain error {strain:.1e}, interior residual / row sum {residual:.1e}, \
             energy relative error {energy:.1e}"
        );
        // As patch.rs: strains ~1e-3 to round-off (1e-15 absolute); residuals are sums of
        // ~100-400 terms that cancel (a few 1e-16 relative each; 1e-13 leaves margin); the
        // energy is exact where the rule integrates det J exactly (1e-12).
        assert!(strain < 1e-15, "{kind}: strain error {strain:e}");
        assert!(residual < 1e-13, "{kind}: interior residual {residual:e}");
        assert!(energy.abs() < 1e-12, "{kind}: energy error {energy:e}");
    }
}

/// Total mass `ρ V` and the kinetic energy of rigid motions, exactly, from the consistent
/// mass of each kind: `uᵀ M u` for a unit translation is `ρ V`, for a unit rotation about
/// z through the origin `ρ ∫ (x² + y²) dV = ρ V (Lx² + Ly²) / 3` on `[0, Lx] × [0, Ly] × [0, Lz]`
/// (the rotation is linear, so the elements interpolate it exactly).
#[test]
fn consistent_mass_is_exact() {
    let (lx, ly, lz) = (1.0, 0.8, 0.6);
    let rho = 7850.0;
    for kind in KINDS {
        let mesh = box_solid(kind, [lx, ly, lz], [3, 2, 2]);
        let materials = MaterialTable::uniform(&mesh, steel()).unwrap();
        let dofs = DofMap::new(&mesh, &[]).unwrap();
        let sys = assemble(&mesh, &materials, &dofs).unwrap();
        let v = lx * ly * lz;
        let translation = dofs.restrict(&vec![[0.0, 1.0, 0.0]; mesh.num_nodes()]);
        let rotation: Vec<[f64; 3]> = mesh.nodes.iter().map(|x| [-x[1], x[0], 0.0]).collect();
        let rotation = dofs.restrict(&rotation);
        let m_t = dot(&translation, &matvec(&sys.m, &translation));
        let m_r = dot(&rotation, &matvec(&sys.m, &rotation));
        let total =
            squeal_fe::total_mass(&mesh, &materials, &squeal_fe::Quadrature::fourteen_point())
                .unwrap();
        let e_t = m_t / (rho * v) - 1.0;
        let e_r = m_r / (rho * v * (lx * lx + ly * ly) / 3.0) - 1.0;
        let e_m = total / (rho * v) - 1.0;
        eprintln!("{kind}: translation {e_t:.1e}, rotation {e_r:.1e}, total mass {e_m:.1e}");
        // Sums of ~1e4 positive and negative entries (a quadratic element's consistent mass
        // has negative ones): round-off ~1e-15 relative; 1e-13 leaves margin.
        for e in [e_t, e_r, e_m] {
            assert!(e.abs() < 1e-13, "{kind}: {e_t:e} {e_r:e} {e_m:e}");
        }
    }
}

/// Number of eigenvalues of the free `K` (against `M`) below `1e-8` of the largest.
fn zero_modes(mesh: &Mesh, reduced: bool) -> usize {
    let materials = MaterialTable::uniform(mesh, steel()).unwrap();
    let dofs = DofMap::new(mesh, &[]).unwrap();
    let options = {
        let mut o = AssemblyOptions::default();
        o.reduced_integration = reduced;
        o
    };
    let sys = assemble_with(mesh, &materials, &dofs, &options).unwrap();
    let l = common::dense_eigenvalues(&common::dense(&sys.k), &common::dense(&sys.m));
    let top = l.iter().fold(0.0_f64, |a, &v| a.max(v));
    // Rigid motions sit at round-off, ~1e-16 λ_max; the softest deformation modes of these
    // meshes at ~1e-2 λ_max: 1e-8 separates them with margin on both sides.
    l.iter().filter(|&&v| v.abs() < 1e-8 * top).count()
}

/// The hex20's 2×2×2 rule leaves a single element with six spurious zero-energy modes
/// (12 zero eigenvalues); a row of two elements still has three, a 2×2×2 block none. The
/// full rule never has them.
#[test]
fn reduced_hex20_has_hourglass_modes_in_one_element_only() {
    let one = box_solid(ElementKind::Hex20, [1.0, 1.0, 1.0], [1, 1, 1]);
    let two = box_solid(ElementKind::Hex20, [2.0, 1.0, 1.0], [2, 1, 1]);
    let eight = box_solid(ElementKind::Hex20, [1.0, 1.0, 1.0], [2, 2, 2]);
    let counts = [
        zero_modes(&one, false),
        zero_modes(&one, true),
        zero_modes(&two, true),
        zero_modes(&eight, true),
    ];
    eprintln!(
        "zero modes: one element full {}, reduced {}; 2 x 1 x 1 reduced {}; 2 x 2 x 2 reduced {}",
        counts[0], counts[1], counts[2], counts[3]
    );
    // Counts of zero eigenvalues are exact integers: the values measured.
    assert_eq!(
        counts,
        [6, 12, 9, 6],
        "full; reduced: one element, 2 x 1 x 1, 2 x 2 x 2"
    );
}

/// The same free block (0.5 × 0.3 × 0.2 m, steel) meshed with hex20 and with tet10: both
/// give upper bounds (conforming elements, consistent mass) that fall with refinement and
/// meet: the largest gap between the two falls from 1.7e-2 to 2.1e-3 as the cells halve.
/// (A single mode's gap need not fall: mode 11's grows from 1.6e-3 to 2.0e-3, the two
/// families approaching from above at different rates.)
#[test]
fn hex20_and_tet10_blocks_converge_to_the_same_frequencies() {
    let lengths = [0.5, 0.3, 0.2];
    let freqs = |kind: ElementKind, k: usize| -> Vec<f64> {
        let mesh = box_solid(kind, lengths, [5 * k, 3 * k, 2 * k]);
        let materials = MaterialTable::uniform(&mesh, steel()).unwrap();
        let dofs = DofMap::new(&mesh, &[]).unwrap();
        let sys = assemble(&mesh, &materials, &dofs).unwrap();
        let l = lowest_eigenvalues(&sys.k, &sys.m, 12, -1e5);
        l[6..].iter().map(|&v| common::hz(v)).collect()
    };
    let (h1, h2) = (freqs(ElementKind::Hex20, 1), freqs(ElementKind::Hex20, 2));
    let (t1, t2) = (freqs(ElementKind::Tet10, 1), freqs(ElementKind::Tet10, 2));
    let (mut worst1, mut worst2) = (0.0_f64, 0.0_f64);
    for m in 0..6 {
        let gap1 = (h1[m] - t1[m]).abs() / t2[m];
        let gap2 = (h2[m] - t2[m]).abs() / t2[m];
        eprintln!(
            "mode {}: hex20 {:.2} -> {:.2} Hz, tet10 {:.2} -> {:.2} Hz, gap {:.2e} -> {:.2e}",
            m + 7,
            h1[m],
            h2[m],
            t1[m],
            t2[m],
            gap1,
            gap2
        );
        // Refinement lowers both (upper bounds; 1e-9 allows for the eigensolver's
        // round-off) and closes the gap between them.
        assert!(
            h2[m] < h1[m] * (1.0 + 1e-9) && t2[m] < t1[m] * (1.0 + 1e-9),
            "mode {}",
            m + 7
        );
        // On the finer meshes the two element families agree to 0.3% (measured up to 2.1e-3).
        assert!(gap2 < 3e-3, "mode {}: gap {gap2:e}", m + 7);
        worst1 = worst1.max(gap1);
        worst2 = worst2.max(gap2);
    }
    // The largest gap shrinks by more than half as the cells halve (measured 1.7e-2 to
    // 2.1e-3).
    assert!(
        worst2 < 0.5 * worst1,
        "largest gap {worst1:e} -> {worst2:e}"
    );
}
