//! Quadrature rules on the reference elements.
//!
//! Weights include the reference volume, so they sum to the reference element's volume:
//! `∫ f ≈ Σ w_i f(p_i)`.
//!
//! - Tetrahedron `{ξ, η, ζ ≥ 0, ξ + η + ζ ≤ 1}` (volume 1/6): the symmetric rules of degree
//!   1, 2, 5 and 6, and collapsed Gauss rules of any degree. For a tet10 element the stiffness
//!   integrand `Bᵀ D B det J` has degree 2 on a straight-sided element (det J constant), the
//!   consistent-mass integrand `N_a N_b det J` degree 4.
//! - Hexahedron `[-1, 1]³` (volume 8): tensor products of Gauss–Legendre rules
//!   ([`Quadrature::hex_gauss`]); `n` points per axis integrate degree `2n - 1` in each
//!   variable.
//! - Wedge (triangle `{ξ, η ≥ 0, ξ + η ≤ 1}` × `ζ ∈ [-1, 1]`, volume 1): a collapsed Gauss
//!   rule on the triangle times Gauss–Legendre along `ζ` ([`Quadrature::wedge_gauss`]).
//! - Pyramid (base `[-1, 1]²` at `ζ = 0`, apex `(0, 0, 1)`, volume 4/3): the cube
//!   `[-1, 1]² × [0, 1]` collapsed onto the apex ([`Quadrature::pyramid_gauss`]), which turns
//!   the rational shape functions of the 13-node pyramid into polynomials.

/// Points (reference coordinates) and weights of a rule, and the polynomial degree it
/// integrates exactly (total degree on the tetrahedron, degree in each variable on the
/// hexahedron, see each constructor).
#[derive(Clone, Debug, PartialEq)]
pub struct Quadrature {
    /// Reference coordinates of the points.
    pub points: Vec<[f64; 3]>,
    /// Weights, summing to the reference element's volume.
    pub weights: Vec<f64>,
    /// The degree the rule integrates exactly.
    pub degree: usize,
}

/// A rule that cannot be built.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum QuadratureError {
    /// Gauss rules are built with 1 to 32 points per axis.
    #[error("quadrature with {0} Gauss points per axis is not supported (1..=32)")]
    Order(usize),
}

fn check_order(n: usize) -> Result<(), QuadratureError> {
    if (1..=32).contains(&n) {
        Ok(())
    } else {
        Err(QuadratureError::Order(n))
    }
}

/// The point with barycentric coordinates `l` (the first one is `1 - ξ - η - ζ`).
fn from_barycentric(l: [f64; 4]) -> [f64; 3] {
    [l[1], l[2], l[3]]
}

/// The four points `(a, a, a, 1 - 3a)` and permutations.
fn orbit4(a: f64) -> [[f64; 3]; 4] {
    std::array::from_fn(|i| {
        let mut l = [a; 4];
        l[i] = 1.0 - 3.0 * a;
        from_barycentric(l)
    })
}

/// The six points `(b, b, 1/2 - b, 1/2 - b)` and permutations.
fn orbit6(b: f64) -> [[f64; 3]; 6] {
    const PAIRS: [[usize; 2]; 6] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];
    PAIRS.map(|[i, j]| {
        let mut l = [0.5 - b; 4];
        l[i] = b;
        l[j] = b;
        from_barycentric(l)
    })
}

/// The twelve points `(a, a, b, c)` and permutations, `c = 1 - 2a - b` (all distinct when
/// `a`, `b`, `c` are).
fn orbit12(a: f64, b: f64) -> [[f64; 3]; 12] {
    let c = 1.0 - 2.0 * a - b;
    // Positions of b and c among the four barycentric coordinates; the other two hold a.
    const PLACES: [[usize; 2]; 12] = [
        [0, 1],
        [0, 2],
        [0, 3],
        [1, 0],
        [1, 2],
        [1, 3],
        [2, 0],
        [2, 1],
        [2, 3],
        [3, 0],
        [3, 1],
        [3, 2],
    ];
    PLACES.map(|[ib, ic]| {
        let mut l = [a; 4];
        l[ib] = b;
        l[ic] = c;
        from_barycentric(l)
    })
}

impl Quadrature {
    /// One point at the centroid, degree 1.
    pub fn centroid() -> Self {
        Self {
            points: vec![[0.25; 3]],
            weights: vec![1.0 / 6.0],
            degree: 1,
        }
    }

    /// The 4-point rule of degree 2 (Hammer, Marlowe & Stroud 1956; Abaqus C3D10's stiffness
    /// rule): barycentric `(a, a, a, 1 - 3a)` with `a = (5 - √5)/20`. Exact for the stiffness
    /// of straight-sided tet10 elements.
    pub fn four_point() -> Self {
        let a = (5.0 - 5.0_f64.sqrt()) / 20.0;
        Self {
            points: orbit4(a).to_vec(),
            weights: vec![1.0 / 24.0; 4],
            degree: 2,
        }
    }

    /// The 14-point rule of degree 5 with positive weights (Walkington 2000, "Quadrature on
    /// simplices of arbitrary dimension", Keast's rule #6). Exact for the consistent mass of
    /// straight-sided tet10 elements (degree 4). Constants re-derived to 25 digits from the six
    /// moment equations of the invariant polynomials of degree ≤ 5, rounded to f64.
    pub fn fourteen_point() -> Self {
        const A1: f64 = 0.092_735_250_310_891_22;
        const A2: f64 = 0.310_885_919_263_300_6;
        const B: f64 = 0.045_503_704_125_649_65;
        const W1: f64 = 0.012_248_840_519_393_659;
        const W2: f64 = 0.018_781_320_953_002_643;
        const W3: f64 = 0.007_091_003_462_846_911;
        let mut points = orbit4(A1).to_vec();
        points.extend(orbit4(A2));
        points.extend(orbit6(B));
        let mut weights = vec![W1; 4];
        weights.extend([W2; 4]);
        weights.extend([W3; 6]);
        Self {
            points,
            weights,
            degree: 5,
        }
    }

    /// The 24-point rule of degree 6 with positive weights (Keast 1986, "Moderate-degree
    /// tetrahedral quadrature formulas", rule #7): three orbits `(a, a, a, 1 - 3a)` and one
    /// orbit `(a, a, b, 1 - 2a - b)` of 12 points. Constants re-derived to 25 digits by Newton's
    /// method on the 84 moment equations of the monomials of degree ≤ 6 (residual 1e-41),
    /// rounded to f64; the last weight is 9/1120. For the stiffness of curved tet10 elements
    /// (see `squeal_fe::element`).
    pub fn twenty_four_point() -> Self {
        const A: [f64; 3] = [
            0.214_602_871_259_152_03,
            0.040_673_958_534_611_35,
            0.322_337_890_142_275_5,
        ];
        const W: [f64; 3] = [
            0.006_653_791_709_694_582,
            0.001_679_535_175_886_774,
            0.009_226_196_923_942_454,
        ];
        const A12: f64 = 0.063_661_001_875_017_53;
        const B12: f64 = 0.269_672_331_458_315_8;
        let mut points = Vec::with_capacity(24);
        let mut weights = Vec::with_capacity(24);
        for (a, w) in A.iter().zip(W) {
            points.extend(orbit4(*a));
            weights.extend([w; 4]);
        }
        points.extend(orbit12(A12, B12));
        weights.extend([9.0 / 1120.0; 12]);
        Self {
            points,
            weights,
            degree: 6,
        }
    }

    /// A collapsed (Duffy / Stroud conical) product of `n`-point Gauss–Legendre rules:
    /// `ξ = u, η = (1-u) v, ζ = (1-u)(1-v) w`, Jacobian `(1-u)²(1-v)`. Positive weights,
    /// `n³` points, exact to degree `2n - 3` (a monomial of degree `p` becomes a polynomial of
    /// degree `p + 2` in `u`). For curved elements, whose integrands have higher degree.
    pub fn collapsed_gauss(n: usize) -> Result<Self, QuadratureError> {
        check_order(n)?;
        let (x, w) = gauss_legendre_unit(n);
        let mut points = Vec::with_capacity(n * n * n);
        let mut weights = Vec::with_capacity(n * n * n);
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    let (u, v, t) = (x[i], x[j], x[k]);
                    points.push([u, (1.0 - u) * v, (1.0 - u) * (1.0 - v) * t]);
                    weights.push(w[i] * w[j] * w[k] * (1.0 - u) * (1.0 - u) * (1.0 - v));
                }
            }
        }
        Ok(Self {
            points,
            weights,
            degree: (2 * n).saturating_sub(3),
        })
    }

    /// The product of `n`-point Gauss–Legendre rules on the hexahedron `[-1, 1]³`: `n³`
    /// points, exact for polynomials of degree `2n - 1` in each variable. For the 20-node
    /// hexahedron: `n = 3` is the full rule (exact stiffness of a parallelepiped, whose
    /// integrand has degree 4 in each variable), `n = 2` the reduced one (see
    /// [`crate::hex20`] for its zero-energy modes).
    pub fn hex_gauss(n: usize) -> Result<Self, QuadratureError> {
        check_order(n)?;
        Ok(Self::hex_product(n))
    }

    /// [`Quadrature::hex_gauss`] for `n` known to be in `1..=32`.
    pub(crate) fn hex_product(n: usize) -> Self {
        let (x, w) = gauss_legendre(n);
        let mut points = Vec::with_capacity(n * n * n);
        let mut weights = Vec::with_capacity(n * n * n);
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    points.push([x[i], x[j], x[k]]);
                    weights.push(w[i] * w[j] * w[k]);
                }
            }
        }
        Self {
            points,
            weights,
            degree: 2 * n - 1,
        }
    }

    /// A rule on the wedge `{ξ, η ≥ 0, ξ + η ≤ 1} × [-1, 1]`: the triangle collapsed from the
    /// square (`ξ = u`, `η = (1 - u) v`, Jacobian `1 - u`, `n_tri²` points, exact to total
    /// degree `2 n_tri - 2` in `(ξ, η)`) times `n_line` Gauss–Legendre points along `ζ`
    /// (degree `2 n_line - 1`). `degree` is the smaller of the two.
    pub fn wedge_gauss(n_tri: usize, n_line: usize) -> Result<Self, QuadratureError> {
        check_order(n_tri)?;
        check_order(n_line)?;
        Ok(Self::wedge_product(n_tri, n_line))
    }

    /// [`Quadrature::wedge_gauss`] for orders known to be in `1..=32`.
    pub(crate) fn wedge_product(n_tri: usize, n_line: usize) -> Self {
        let (u, wu) = gauss_legendre_unit(n_tri);
        let (z, wz) = gauss_legendre(n_line);
        let mut points = Vec::with_capacity(n_tri * n_tri * n_line);
        let mut weights = Vec::with_capacity(n_tri * n_tri * n_line);
        for k in 0..n_line {
            for i in 0..n_tri {
                for j in 0..n_tri {
                    points.push([u[i], (1.0 - u[i]) * u[j], z[k]]);
                    weights.push(wu[i] * wu[j] * (1.0 - u[i]) * wz[k]);
                }
            }
        }
        Self {
            points,
            weights,
            degree: (2 * n_tri - 2).min(2 * n_line - 1),
        }
    }

    /// A rule on the pyramid (base `[-1, 1]²` at `ζ = 0`, apex `(0, 0, 1)`): the cube
    /// `(u, v, w) ∈ [-1, 1]² × [0, 1]` collapsed onto the apex, `ξ = u (1 - w)`,
    /// `η = v (1 - w)`, `ζ = w`, Jacobian `(1 - w)²`, with `n_base` Gauss–Legendre points
    /// along `u` and `v` and `n_axis` along `w`. A polynomial of degree `p` in `(ξ, η, ζ)`
    /// becomes one of degree `p` in `u` and `v` and `p + 2` in `w`; `degree` is the largest
    /// `p` integrated exactly. The 13-node pyramid's rational shape functions and their
    /// gradients are polynomials in `(u, v, w)` (see [`crate::pyramid13`]).
    pub fn pyramid_gauss(n_base: usize, n_axis: usize) -> Result<Self, QuadratureError> {
        check_order(n_base)?;
        check_order(n_axis)?;
        Ok(Self::pyramid_product(n_base, n_axis))
    }

    /// [`Quadrature::pyramid_gauss`] for orders known to be in `1..=32`.
    pub(crate) fn pyramid_product(n_base: usize, n_axis: usize) -> Self {
        let (x, wx) = gauss_legendre(n_base);
        let (t, wt) = gauss_legendre_unit(n_axis);
        let mut points = Vec::with_capacity(n_base * n_base * n_axis);
        let mut weights = Vec::with_capacity(n_base * n_base * n_axis);
        for k in 0..n_axis {
            let s = 1.0 - t[k];
            for j in 0..n_base {
                for i in 0..n_base {
                    points.push([x[i] * s, x[j] * s, t[k]]);
                    weights.push(wx[i] * wx[j] * wt[k] * s * s);
                }
            }
        }
        Self {
            points,
            weights,
            degree: (2 * n_base - 1).min((2 * n_axis - 1).saturating_sub(2)),
        }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether the rule has no point.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// `Σ w_i f(p_i)`.
    pub fn integrate(&self, f: impl Fn([f64; 3]) -> f64) -> f64 {
        self.points
            .iter()
            .zip(&self.weights)
            .map(|(p, w)| w * f(*p))
            .sum()
    }
}

/// The `i`-th root `t` of `P_n` (descending in `i`) and `P_n'(t)`: Newton's method on the
/// three-term recurrence of the Legendre polynomials, from the Tricomi initial guesses.
fn legendre_root(n: usize, i: usize) -> (f64, f64) {
    let mut t = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
    for _ in 0..100 {
        let (p, d) = legendre(n, t);
        let step = p / d;
        t -= step;
        if step.abs() < 1e-16 {
            break;
        }
    }
    (t, legendre(n, t).1)
}

/// Gauss–Legendre points (ascending) and weights on `[0, 1]`, the roots of `P_n` by Newton
/// from Tricomi's estimates, to machine precision.
pub fn gauss_legendre_unit(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    for i in 0..n {
        let (t, d) = legendre_root(n, i);
        // Weights 2 / ((1 - t²) P_n'(t)²) on [-1, 1], halved for [0, 1].
        x[i] = 0.5 * (1.0 - t);
        w[i] = 1.0 / ((1.0 - t * t) * d * d);
    }
    (x, w)
}

/// Gauss–Legendre points and weights on `[-1, 1]`, ascending and symmetric bit for bit (the
/// upper half mirrors the lower one, the middle point of an odd rule is 0).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        let (t, d) = legendre_root(n, i);
        let wi = 2.0 / ((1.0 - t * t) * d * d);
        // Roots descend with i: the i-th largest is t, the i-th smallest -t.
        x[i] = -t;
        x[n - 1 - i] = t;
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    if n % 2 == 1 {
        x[n / 2] = 0.0;
    }
    (x, w)
}

/// `P_n(t)` and `P_n'(t)`.
fn legendre(n: usize, t: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, t);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * t * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    let d = n as f64 * (t * p1 - p0) / (t * t - 1.0);
    (p1, d)
}
