//! The reference-element trait and the element kinds.
//!
//! A solid element is described once, on its reference domain, by [`ReferenceElement`]: its
//! nodes' reference coordinates in squeal's canonical order, its shape functions and their
//! gradients, its faces as 6-node triangles or 8-node quadrilaterals, the quadrature rules it
//! uses, and how the file formats order its nodes. Everything that maps it to space
//! (Jacobians, element matrices, assembly) is written once, generically, in terms of this
//! trait (the design of fenris: the reference element, the quadrature and the local and
//! global assembly are separate pieces). [`ElementKind`] names the kinds at run time (a mesh
//! stores one block per kind) and gives their data without generics.
//!
//! Isoparametric map: `x(ξ) = Σ_a x_a N_a(ξ)`, Jacobian `J = ∂x/∂ξ = Σ_a x_a ⊗ ∇_ξ N_a`
//! ([`jacobian`]); an element is positively oriented when `det J > 0` everywhere.

use crate::quadrature::Quadrature;

/// A face of an element, by local node numbers: corners first (counter-clockwise seen from
/// outside the element, so that `(x1 - x0) × (x2 - x0)` points out of a positively oriented
/// element), then the midside nodes of edges `(0,1), (1,2), ...` in turn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Face {
    /// A 6-node triangle `[v0, v1, v2, m01, m12, m20]`.
    Tri6([usize; 6]),
    /// An 8-node quadrilateral `[v0, v1, v2, v3, m01, m12, m23, m30]`.
    Quad8([usize; 8]),
}

/// The shape of a face, for messages and for code that reads one shape only.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaceKind {
    /// 6-node triangle.
    Tri6,
    /// 8-node quadrilateral.
    Quad8,
}

impl std::fmt::Display for FaceKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            FaceKind::Tri6 => "6-node triangle",
            FaceKind::Quad8 => "8-node quadrilateral",
        })
    }
}

impl Face {
    /// Local node numbers, corners first.
    pub fn nodes(&self) -> &[usize] {
        match self {
            Face::Tri6(n) => n,
            Face::Quad8(n) => n,
        }
    }

    /// Number of corners (3 or 4).
    pub fn corners(&self) -> usize {
        match self {
            Face::Tri6(_) => 3,
            Face::Quad8(_) => 4,
        }
    }

    /// Triangle or quadrilateral.
    pub fn kind(&self) -> FaceKind {
        match self {
            Face::Tri6(_) => FaceKind::Tri6,
            Face::Quad8(_) => FaceKind::Quad8,
        }
    }
}

/// A quadratic solid element on its reference domain, with `N` nodes.
///
/// Node order ("canonical"): vertices first, then one midside node per edge of [`Self::EDGES`].
/// It is Abaqus's order where Abaqus has the element (C3D10, C3D20, C3D15), VTK's otherwise.
/// The readers convert each file's order to it; [`Self::VTK_ORDER`] converts back for output.
pub trait ReferenceElement<const N: usize>: Sized + 'static {
    /// The run-time name of this element.
    const KIND: ElementKind;
    /// Number of vertices (corner nodes); nodes `VERTICES..N` are midside nodes.
    const VERTICES: usize;
    /// Reference coordinates of the nodes.
    const NODES_REF: [[f64; 3]; N];
    /// Vertex pairs of the edges: midside node `VERTICES + k` sits on edge `EDGES[k]`.
    const EDGES: &'static [[usize; 2]];
    /// The faces, oriented outward ([`Face`]).
    const FACES: &'static [Face];
    /// VTK cell type of the quadratic cell (VTK's `vtkCellType.h`).
    const VTK_CELL_TYPE: u8;
    /// `vtk[i] = canonical[VTK_ORDER[i]]`.
    const VTK_ORDER: [usize; N];
    /// Gmsh element type number (`$Elements`).
    const GMSH_TYPE: i32;
    /// `canonical[i] = gmsh[GMSH_TO_CANONICAL[i]]`.
    const GMSH_TO_CANONICAL: [usize; N];

    /// Shape function values at reference point `xi`.
    fn shape(xi: [f64; 3]) -> [f64; N];

    /// Shape function gradients `dN[a][j] = ∂N_a/∂ξ_j` at reference point `xi`.
    fn shape_gradients(xi: [f64; 3]) -> [[f64; 3]; N];

    /// The stiffness rule of the element (its "full" integration).
    fn stiffness_rule() -> Quadrature;

    /// A reduced stiffness rule where the element has one (the 20-node hexahedron's 2×2×2);
    /// see the element's documentation for when it needs care.
    fn reduced_stiffness_rule() -> Option<Quadrature> {
        None
    }

    /// The consistent-mass rule (exact for elements with a constant `det J`).
    fn mass_rule() -> Quadrature;

    /// The volume of an element with nodes `x` (negative if inverted): by default
    /// `Σ_q w_q det J_q` with the mass rule, which is exact for elements with straight edges.
    fn volume(x: &[[f64; 3]; N]) -> f64 {
        volume::<Self, N>(x, &Self::mass_rule())
    }

    /// Reference points where the quality checks sample `det J`: the nodes and the stiffness
    /// rule's points unless an element says otherwise.
    fn jacobian_samples() -> Vec<[f64; 3]> {
        let mut p = Self::NODES_REF.to_vec();
        p.extend(Self::stiffness_rule().points);
        p
    }
}

/// The element kinds squeal reads, in the order of a mesh's blocks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ElementKind {
    /// 10-node tetrahedron ([`crate::tet10`]).
    Tet10,
    /// 20-node hexahedron ([`crate::hex20`]).
    Hex20,
    /// 15-node wedge (triangular prism, [`crate::wedge15`]).
    Wedge15,
    /// 13-node pyramid ([`crate::pyramid13`]).
    Pyramid13,
}

/// Runs `$body` with `$e` the element type and `$n` its node count for the kind `$kind`.
#[macro_export]
macro_rules! with_element {
    ($kind:expr, $e:ident, $n:ident => $body:expr) => {
        match $kind {
            $crate::ElementKind::Tet10 => {
                #[allow(dead_code)]
                type $e = $crate::tet10::Tet10;
                const $n: usize = 10;
                $body
            }
            $crate::ElementKind::Hex20 => {
                #[allow(dead_code)]
                type $e = $crate::hex20::Hex20;
                const $n: usize = 20;
                $body
            }
            $crate::ElementKind::Wedge15 => {
                #[allow(dead_code)]
                type $e = $crate::wedge15::Wedge15;
                const $n: usize = 15;
                $body
            }
            $crate::ElementKind::Pyramid13 => {
                #[allow(dead_code)]
                type $e = $crate::pyramid13::Pyramid13;
                const $n: usize = 13;
                $body
            }
        }
    };
}

impl ElementKind {
    /// Every kind, in block order.
    pub const ALL: [ElementKind; 4] = [
        ElementKind::Tet10,
        ElementKind::Hex20,
        ElementKind::Wedge15,
        ElementKind::Pyramid13,
    ];

    /// Number of nodes.
    pub fn nodes(self) -> usize {
        with_element!(self, E, N => N)
    }

    /// A short name for messages: "10-node tetrahedron", ...
    pub fn name(self) -> &'static str {
        match self {
            ElementKind::Tet10 => "10-node tetrahedron",
            ElementKind::Hex20 => "20-node hexahedron",
            ElementKind::Wedge15 => "15-node wedge",
            ElementKind::Pyramid13 => "13-node pyramid",
        }
    }

    /// Number of vertices ([`ReferenceElement::VERTICES`]).
    pub fn vertices(self) -> usize {
        with_element!(self, E, N => <E as ReferenceElement<N>>::VERTICES)
    }

    /// Vertex pairs of the midside nodes' edges ([`ReferenceElement::EDGES`]).
    pub fn edges(self) -> &'static [[usize; 2]] {
        with_element!(self, E, N => <E as ReferenceElement<N>>::EDGES)
    }

    /// Reference coordinates of the nodes ([`ReferenceElement::NODES_REF`]).
    pub fn nodes_ref(self) -> &'static [[f64; 3]] {
        with_element!(self, E, N => &<E as ReferenceElement<N>>::NODES_REF)
    }

    /// The faces ([`ReferenceElement::FACES`]).
    pub fn faces(self) -> &'static [Face] {
        with_element!(self, E, N => <E as ReferenceElement<N>>::FACES)
    }

    /// VTK cell type ([`ReferenceElement::VTK_CELL_TYPE`]).
    pub fn vtk_cell_type(self) -> u8 {
        with_element!(self, E, N => <E as ReferenceElement<N>>::VTK_CELL_TYPE)
    }

    /// [`ReferenceElement::VTK_ORDER`].
    pub fn vtk_order(self) -> &'static [usize] {
        with_element!(self, E, N => &<E as ReferenceElement<N>>::VTK_ORDER)
    }

    /// Gmsh element type ([`ReferenceElement::GMSH_TYPE`]).
    pub fn gmsh_type(self) -> i32 {
        with_element!(self, E, N => <E as ReferenceElement<N>>::GMSH_TYPE)
    }

    /// [`ReferenceElement::GMSH_TO_CANONICAL`].
    pub fn gmsh_to_canonical(self) -> &'static [usize] {
        with_element!(self, E, N => &<E as ReferenceElement<N>>::GMSH_TO_CANONICAL)
    }

    /// The kind of a Gmsh element type number, if squeal reads it.
    pub fn from_gmsh_type(code: i32) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.gmsh_type() == code)
    }
}

impl std::fmt::Display for ElementKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Jacobian `J[i][j] = ∂x_i/∂ξ_j` of the isoparametric map at `xi`.
pub fn jacobian<E: ReferenceElement<N>, const N: usize>(
    x: &[[f64; 3]; N],
    xi: [f64; 3],
) -> [[f64; 3]; 3] {
    let g = E::shape_gradients(xi);
    let mut j = [[0.0; 3]; 3];
    for (n, gn) in g.iter().enumerate() {
        for r in 0..3 {
            for c in 0..3 {
                j[r][c] += x[n][r] * gn[c];
            }
        }
    }
    j
}

/// Determinant of a 3×3 matrix.
pub fn det3(m: &[[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// Volume `Σ_q w_q det J_q` of an element with the rule `rule` (negative for an inverted
/// element).
pub fn volume<E: ReferenceElement<N>, const N: usize>(x: &[[f64; 3]; N], rule: &Quadrature) -> f64 {
    rule.points
        .iter()
        .zip(&rule.weights)
        .map(|(p, w)| w * det3(&jacobian::<E, N>(x, *p)))
        .sum()
}

/// Min and max of `det J` over [`ReferenceElement::jacobian_samples`].
pub fn jacobian_range<E: ReferenceElement<N>, const N: usize>(x: &[[f64; 3]; N]) -> (f64, f64) {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for p in E::jacobian_samples() {
        let d = det3(&jacobian::<E, N>(x, p));
        lo = lo.min(d);
        hi = hi.max(d);
    }
    (lo, hi)
}

/// How far an element is from straight-sided: the largest distance of a midside node from the
/// midpoint of its edge, relative to that edge's length (0 for straight edges; infinite for
/// an edge of zero length).
pub fn midside_offset<E: ReferenceElement<N>, const N: usize>(x: &[[f64; 3]; N]) -> f64 {
    let mut worst = 0.0_f64;
    for (k, &[a, b]) in E::EDGES.iter().enumerate() {
        let m = E::VERTICES + k;
        let sq = |f: &dyn Fn(usize) -> f64| (0..3).map(|d| f(d).powi(2)).sum::<f64>();
        let off = sq(&|d| x[m][d] - 0.5 * (x[a][d] + x[b][d]));
        let len = sq(&|d| x[b][d] - x[a][d]);
        let r = (off / len).sqrt();
        worst = worst.max(if r.is_nan() { f64::INFINITY } else { r });
    }
    worst
}
