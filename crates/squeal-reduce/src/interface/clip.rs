//! Quadrature of a 6-node triangle split at the cuts of the patch grid.
//!
//! # The cuts on one triangle
//!
//! With `(a, b)` a point's coordinates in the plane normal to the axis (origin on the axis), a
//! point lies beyond a cut when a level function `g(a, b)` is positive:
//!
//! - radial cut at radius `c`: `g = a² + b² − c²`;
//! - angular cut at angle `φ`: `g = b cos φ − a sin φ`, the signed distance to the plane
//!   through the axis at `φ` (only tested on triangles on the `φ` side of the axis).
//!
//! A 6-node triangle maps its reference coordinates `(s, t)` (`s, t ≥ 0`, `s + t ≤ 1`) to
//! `(a, b)(s, t) = Σ_k N_k(s, t) (a_k, b_k)`, so on it a cut is the zero set of
//! `G(s, t) = g((a, b)(s, t))`: a quadratic for an angular cut, a quartic for a radial one (a
//! quadratic where the triangle is straight-sided). Two versions of `G` are used:
//!
//! - `ĝ(s, t) = Σ_k N_k(s, t) g(a_k, b_k)`, its quadratic interpolant from the six node values,
//!   decides which cuts cross which (sub-)triangle, the direction of integration and the first
//!   guesses of the roots below. An edge whose three nodes lie on a cut makes `ĝ` vanish along
//!   it: a triangle on either side of a cut that the mesh imprinted is not crossed, whereas the
//!   exact circle would shave off it the sliver between the circle and the quadratic edge that
//!   interpolates it (about `0.03 r (Δφ/2)⁴` wide for an edge spanning `Δφ`). So where the cuts
//!   are mesh edges the patches are made of whole triangles, as they were before clipping.
//! - `G` itself places the cut inside a crossed triangle: every root of `ĝ` is polished by
//!   Newton's method on `G` (two or three steps: `ĝ` differs from `G` by the curvature of the
//!   element, 1e-6 of its size on the coarse meshes), and the pieces' cells are decided by the
//!   sign of `G`. The patch is then the part of the discrete face inside its cell, exactly.
//!
//! # Which cuts cross a triangle
//!
//! `ĝ` in the Bernstein basis of degree 2 over a triangle with vertices `q_i` and edge
//! midpoints `m_ij` has the coefficients `ĝ(q_i)` and `2 ĝ(m_ij) − (ĝ(q_i) + ĝ(q_j)) / 2`; by
//! the convex-hull property `ĝ` lies between their least and greatest. A cut crosses the
//! triangle only if those bounds straddle `±tol` (a length of 1e-9 of the face's outer radius,
//! far above the coordinates' round-off): a triangle that merely touches a cut, along an edge or
//! at a vertex, is not split. The bounds are conservative: a triangle flagged as crossed but
//! not crossed is integrated by the rules below with the same result to round-off.
//!
//! # Integrating the pieces
//!
//! A crossed triangle (or a sub-triangle of it, see below) is integrated as an iterated
//! integral along a direction `d` of the `(s, t)` plane (as Saye 2015 does for implicitly
//! defined domains): with `e ⟂ d`, `p = q₀ + u e + v d` and `ds dt = du dv`,
//!
//! `∫_{cell} f ds dt = ∫ du Σ_pieces ∫_{v_a(u)}^{v_b(u)} f dv`,
//!
//! where along each line `u = const` the pieces are the triangle's chord split at the roots of
//! the crossing cuts (the roots of `ĝ`, quadratics in `v` solved in closed form, polished on
//! `G`), each piece in the cell of its midpoint. The inner integrand is a polynomial of degree 4
//! on a flat face (shape function times the area Jacobian), integrated exactly by 4-point
//! Gauss–Legendre. The outer integrand is smooth between breakpoints where the pieces change:
//! the projections of the vertices, the cuts' crossings of the edges, and where two cuts meet
//! (Newton's method on the two `G`); between breakpoints it is integrated by 10-point
//! Gauss–Legendre. Smoothness needs each crossing cut to be monotone along `d` over the
//! triangle, so that each line meets it at most once and no root appears or vanishes inside an
//! interval: `d` is chosen transverse to the crossing cuts' gradients, and since `∂ĝ/∂d` is
//! linear in `(s, t)` its sign at the three vertices decides monotonicity exactly. Where it
//! fails the triangle is split into four at its edge midpoints and each child treated again
//! (its cuts re-tested), down to 8 levels; a child no cut crosses takes the degree-4 rule of the
//! whole triangle, mapped onto it.
//!
//! Every point of the triangle is counted once, so the weights of all points sum to the
//! reference area, and each cell gets `∫ N_k dA` and `∫ x dA` from the same points: the
//! patch's weights sum to 1 and reproduce its centroid, `Σ w_k x_k = x̄`, to round-off.

use super::{DUNAVANT4, tri6_shape};

/// Levels of subdivision of a crossed triangle before the iterated rule is used regardless of
/// monotonicity (a leaf of level 8 has 1/65536 of the triangle's area).
const MAX_DEPTH: usize = 8;

/// Newton's method on `G` stops at a step this small (reference coordinates: 1e-12 of the
/// triangle). `G = a² + b² − c²` is found to about 1e-16 c², so that its roots are known to
/// about 1e-16 c² / |∇G|, some 1e-14 where the elements are 0.1 mm wide.
const ROOT_STEP: f64 = 1e-12;

/// The family of a cut: radial cuts separate rings of patches, angular cuts separate sectors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Family {
    /// A circle `ρ = c` about the axis.
    Radial,
    /// A half-plane through the axis at an angle.
    Angular,
}

/// Where a triangle lies with respect to a cut, from the Bernstein bounds of `ĝ`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Side {
    /// `ĝ ≥ −tol` everywhere and `ĝ > tol` somewhere.
    Above,
    /// `ĝ ≤ tol` everywhere and `ĝ < −tol` somewhere.
    Below,
    /// `|ĝ| ≤ tol` everywhere: a sliver lying on the cut.
    Within,
    /// The bounds reach past both `−tol` and `tol`: the cut may cross the triangle.
    Crosses,
}

/// The side of a triangle with respect to a cut, from `ĝ` at its vertices and edge midpoints
/// (`[q0, q1, q2, m01, m12, m20]`, the 6-node triangle's node order).
pub(super) fn side_of(values: &[f64; 6], tol: f64) -> Side {
    let [g0, g1, g2, g01, g12, g20] = *values;
    let bernstein = [
        g0,
        g1,
        g2,
        2.0 * g01 - 0.5 * (g0 + g1),
        2.0 * g12 - 0.5 * (g1 + g2),
        2.0 * g20 - 0.5 * (g2 + g0),
    ];
    let lo = bernstein.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = bernstein.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    match (lo >= -tol, hi <= tol) {
        (true, true) => Side::Within,
        (true, false) => Side::Above,
        (false, true) => Side::Below,
        (false, false) => Side::Crosses,
    }
}

/// A cut of the grid as a level function of a point's coordinates `(a, b)` in the plane
/// normal to the axis (origin on the axis): positive beyond the cut.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Cut {
    /// `g = a² + b² − c²`.
    Radial {
        /// The cut's radius `c`.
        radius: f64,
    },
    /// `g = b cos φ − a sin φ`: the signed distance to the plane through the axis at `φ`.
    Angular {
        /// `sin φ`.
        sin: f64,
        /// `cos φ`.
        cos: f64,
    },
}

impl Cut {
    fn family(&self) -> Family {
        match self {
            Cut::Radial { .. } => Family::Radial,
            Cut::Angular { .. } => Family::Angular,
        }
    }

    /// `g` at the planar point `p`.
    pub fn level(&self, p: [f64; 2]) -> f64 {
        self.level_and_gradient(p).0
    }

    /// `g` and `∂g/∂(a, b)` at `p`.
    fn level_and_gradient(&self, [a, b]: [f64; 2]) -> (f64, [f64; 2]) {
        match *self {
            Cut::Radial { radius } => (a * a + b * b - radius * radius, [2.0 * a, 2.0 * b]),
            Cut::Angular { sin, cos } => (b * cos - a * sin, [-sin, cos]),
        }
    }
}

/// A cut crossing one triangle: the cut and `ĝ(s, t)`, the quadratic interpolant of its level
/// function on the triangle.
#[derive(Clone, Copy, Debug)]
pub(super) struct Level {
    /// `ĝ = c₀ + c₁ s + c₂ t + c₃ s² + c₄ s t + c₅ t²`.
    coeffs: [f64; 6],
    /// Values of `ĝ` within `±tol` count as on the cut.
    tol: f64,
    cut: Cut,
}

impl Level {
    /// `ĝ` of `cut` from its values `g` at the triangle's nodes `[v0, v1, v2, m01, m12, m20]`:
    /// the 6-node shape functions expanded in monomials.
    pub fn interpolating(cut: Cut, g: [f64; 6], tol: f64) -> Self {
        let coeffs = [
            g[0],
            -3.0 * g[0] - g[1] + 4.0 * g[3],
            -3.0 * g[0] - g[2] + 4.0 * g[5],
            2.0 * g[0] + 2.0 * g[1] - 4.0 * g[3],
            4.0 * (g[0] - g[3] + g[4] - g[5]),
            2.0 * g[0] + 2.0 * g[2] - 4.0 * g[5],
        ];
        Self { coeffs, tol, cut }
    }

    fn family(&self) -> Family {
        self.cut.family()
    }

    /// `ĝ(p)`.
    fn value(&self, p: [f64; 2]) -> f64 {
        let c = &self.coeffs;
        let [s, t] = p;
        c[0] + s * (c[1] + c[3] * s + c[4] * t) + t * (c[2] + c[5] * t)
    }

    /// `∇ĝ(p)`.
    fn gradient(&self, p: [f64; 2]) -> [f64; 2] {
        let c = &self.coeffs;
        let [s, t] = p;
        [
            c[1] + 2.0 * c[3] * s + c[4] * t,
            c[2] + c[4] * s + 2.0 * c[5] * t,
        ]
    }

    /// `ĝ(p + w d) = α w² + β w + γ`: `[α, β, γ]`.
    fn along(&self, p: [f64; 2], d: [f64; 2]) -> [f64; 3] {
        let c = &self.coeffs;
        let alpha = c[3] * d[0] * d[0] + c[4] * d[0] * d[1] + c[5] * d[1] * d[1];
        [alpha, dot2(self.gradient(p), d), self.value(p)]
    }

    /// The side of the sub-triangle `q` of the reference triangle.
    fn side_on(&self, q: &[[f64; 2]; 3]) -> Side {
        let m = |i: usize, j: usize| mid(q[i], q[j]);
        let values = [q[0], q[1], q[2], m(0, 1), m(1, 2), m(2, 0)].map(|p| self.value(p));
        side_of(&values, self.tol)
    }

    /// Whether `ĝ` is strictly monotone along `d` over `q`: `∂ĝ/∂d` is linear, so its sign at
    /// the vertices is its sign everywhere.
    fn monotone_along(&self, q: &[[f64; 2]; 3], d: [f64; 2]) -> bool {
        let slopes = q.map(|p| dot2(self.gradient(p), d));
        slopes.iter().all(|&v| v > 0.0) || slopes.iter().all(|&v| v < 0.0)
    }
}

/// The triangle's map to the plane normal to the axis, `(a, b)(s, t) = Σ_k N_k (a_k, b_k)`,
/// on which the cuts' level functions are evaluated exactly.
pub(super) struct PlanarMap<'a> {
    /// `(a_k, b_k)` of the six nodes.
    pub nodes: &'a [[f64; 2]; 6],
}

impl PlanarMap<'_> {
    /// `G(p) = g((a, b)(p))` and its gradient in `(s, t)`.
    fn level_and_gradient(&self, cut: &Cut, p: [f64; 2]) -> (f64, [f64; 2]) {
        let (n, ds, dt) = tri6_shape(p[0], p[1]);
        let (mut x, mut xs, mut xt) = ([0.0; 2], [0.0; 2], [0.0; 2]);
        for k in 0..6 {
            for c in 0..2 {
                x[c] += n[k] * self.nodes[k][c];
                xs[c] += ds[k] * self.nodes[k][c];
                xt[c] += dt[k] * self.nodes[k][c];
            }
        }
        let (g, grad) = cut.level_and_gradient(x);
        (g, [dot2(grad, xs), dot2(grad, xt)])
    }

    /// Newton's method on `G(start + w dir) = 0` from `w`: the root near `w`, or `w` where a
    /// step is impossible.
    fn root_near(&self, cut: &Cut, start: [f64; 2], dir: [f64; 2], mut w: f64) -> f64 {
        for _ in 0..8 {
            let (g, grad) =
                self.level_and_gradient(cut, [start[0] + w * dir[0], start[1] + w * dir[1]]);
            let slope = dot2(grad, dir);
            let step = g / slope;
            if !step.is_finite() {
                break;
            }
            w -= step;
            if step.abs() <= ROOT_STEP {
                break;
            }
        }
        w
    }

    /// Roots of `G(start + w dir)` in `[lo, hi]`: the roots of `ĝ` there (and a little beyond,
    /// where `G` and `ĝ` differ), polished on `G`.
    fn roots_along(
        &self,
        level: &Level,
        start: [f64; 2],
        dir: [f64; 2],
        lo: f64,
        hi: f64,
        slack: f64,
    ) -> impl Iterator<Item = f64> {
        let guesses = quadratic_roots(level.along(start, dir));
        let polished = guesses.map(|w| {
            if w >= lo - slack && w <= hi + slack {
                self.root_near(&level.cut, start, dir, w)
            } else {
                f64::NAN
            }
        });
        polished.into_iter().filter(move |w| *w >= lo && *w <= hi)
    }
}

/// Gauss–Legendre points and weights on `[-1, 1]`, ascending (the elements' own rule).
fn gauss_legendre<const N: usize>() -> [(f64, f64); N] {
    let (x, w) = squeal_element::quadrature::gauss_legendre(N);
    std::array::from_fn(|i| (x[i], w[i]))
}

/// The quadrature rules of the iterated integral.
pub(super) struct Rules {
    /// Across the cuts, within a piece: exact to degree 7.
    inner: [(f64, f64); 4],
    /// Along the cuts, between breakpoints.
    outer: [(f64, f64); 10],
}

impl Rules {
    pub fn new() -> Self {
        Self {
            inner: gauss_legendre::<4>(),
            outer: gauss_legendre::<10>(),
        }
    }
}

/// A quadrature point of the split triangle: reference coordinates, weight (reference
/// measure, `ds dt`), and how many radial and how many angular cuts of the triangle's `levels`
/// it lies beyond.
#[derive(Clone, Copy, Debug)]
pub(super) struct Point {
    pub st: [f64; 2],
    pub weight: f64,
    pub radial_beyond: usize,
    pub angular_beyond: usize,
}

/// One triangle being split: its planar map, the cuts crossing it, the rules.
struct Splitter<'a, E> {
    map: PlanarMap<'a>,
    levels: &'a [Level],
    rules: &'a Rules,
    emit: E,
}

/// Quadrature of the reference triangle of `planar` split at the cuts of `levels`: every
/// point is passed to `emit` with the cuts it lies beyond. The weights of all points sum to the
/// reference area 1/2 (to round-off), and each cell's points integrate polynomials of degree 4
/// over the cell's part of the triangle to the accuracy set out in the module docs.
pub(super) fn split_quadrature(
    planar: &[[f64; 2]; 6],
    levels: &[Level],
    rules: &Rules,
    emit: impl FnMut(Point),
) {
    let mut splitter = Splitter {
        map: PlanarMap { nodes: planar },
        levels,
        rules,
        emit,
    };
    let state = vec![None; levels.len()];
    splitter.integrate_subtriangle([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], &state, 0);
}

impl<E: FnMut(Point)> Splitter<'_, E> {
    /// The sub-triangle `q`; `parent[k]` is `Some(beyond)` for a cut that does not cross the
    /// parent, `None` for one that may.
    fn integrate_subtriangle(&mut self, q: [[f64; 2]; 3], parent: &[Option<bool>], depth: usize) {
        let mut state = parent.to_vec();
        let mut crossing = Vec::new();
        let centre = centroid(&q);
        for (k, level) in self.levels.iter().enumerate() {
            if state[k].is_some() {
                continue;
            }
            match level.side_on(&q) {
                Side::Above => state[k] = Some(true),
                Side::Below => state[k] = Some(false),
                Side::Within => {
                    state[k] = Some(self.map.level_and_gradient(&level.cut, centre).0 > 0.0)
                }
                Side::Crosses => crossing.push(k),
            }
        }
        if crossing.is_empty() {
            let (radial_beyond, angular_beyond) = self.count_beyond(&state, centre);
            let jac = cross2(sub2(q[1], q[0]), sub2(q[2], q[0])).abs();
            for (a, b, w) in DUNAVANT4 {
                let st =
                    [0, 1].map(|i| q[0][i] + a * (q[1][i] - q[0][i]) + b * (q[2][i] - q[0][i]));
                (self.emit)(Point {
                    st,
                    weight: 0.5 * w * jac,
                    radial_beyond,
                    angular_beyond,
                });
            }
            return;
        }
        let d = self.transverse_direction(&crossing, centre);
        let monotone = d.is_some_and(|d| {
            crossing
                .iter()
                .all(|&k| self.levels[k].monotone_along(&q, d))
        });
        if !monotone && depth < MAX_DEPTH {
            let m = [mid(q[0], q[1]), mid(q[1], q[2]), mid(q[2], q[0])];
            for child in [
                [q[0], m[0], m[2]],
                [m[0], q[1], m[1]],
                [m[2], m[1], q[2]],
                [m[1], m[2], m[0]],
            ] {
                self.integrate_subtriangle(child, &state, depth + 1);
            }
            return;
        }
        self.integrate_along(&q, &state, &crossing, d.unwrap_or([1.0, 0.0]));
    }

    /// A unit direction of the `(s, t)` plane across all the crossing cuts: of the unit
    /// gradients of their `ĝ` at `p` and the normalised sums and differences of two, the one
    /// whose least |cosine| with a gradient is greatest. `None` where a gradient vanishes.
    fn transverse_direction(&self, crossing: &[usize], p: [f64; 2]) -> Option<[f64; 2]> {
        let normals: Vec<[f64; 2]> = crossing
            .iter()
            .map(|&k| unit2(self.levels[k].gradient(p)))
            .collect::<Option<_>>()?;
        let mut candidates = normals.clone();
        for (i, a) in normals.iter().enumerate() {
            for b in &normals[i + 1..] {
                candidates.extend(unit2([a[0] + b[0], a[1] + b[1]]));
                candidates.extend(unit2([a[0] - b[0], a[1] - b[1]]));
            }
        }
        let worst = |d: &[f64; 2]| {
            normals
                .iter()
                .map(|n| dot2(*n, *d).abs())
                .fold(f64::INFINITY, f64::min)
        };
        candidates
            .into_iter()
            .map(|d| (worst(&d), d))
            .max_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, d)| d)
    }

    /// The iterated integral over `q` along `d` (module docs).
    fn integrate_along(
        &mut self,
        q: &[[f64; 2]; 3],
        state: &[Option<bool>],
        crossing: &[usize],
        d: [f64; 2],
    ) {
        const EDGES: [(usize, usize); 3] = [(0, 1), (1, 2), (2, 0)];
        let e = [-d[1], d[0]];
        let uv = q.map(|p| {
            let r = sub2(p, q[0]);
            [dot2(e, r), dot2(d, r)]
        });
        let size = EDGES
            .iter()
            .map(|&(i, j)| norm2(sub2(q[j], q[i])))
            .fold(0.0, f64::max);
        // Roots of ĝ are looked for this far (reference units) beyond an interval, where the
        // polished root of G may still fall inside.
        let slack = 1e-3 * size;
        let mut breaks: Vec<f64> = uv.iter().map(|w| w[0]).collect();
        for (i, j) in EDGES {
            let dq = sub2(q[j], q[i]);
            let length = norm2(dq);
            for &k in crossing {
                for tau in self
                    .map
                    .roots_along(&self.levels[k], q[i], dq, 0.0, 1.0, slack / length)
                {
                    breaks.push(uv[i][0] + tau * (uv[j][0] - uv[i][0]));
                }
            }
        }
        for (n, &k) in crossing.iter().enumerate() {
            for &l in &crossing[n + 1..] {
                if self.levels[k].family() != self.levels[l].family()
                    && let Some(p) = self.meeting_point(&self.levels[k].cut, &self.levels[l].cut, q)
                {
                    breaks.push(dot2(e, sub2(p, q[0])));
                }
            }
        }
        let (u_lo, u_hi) = (
            uv.iter().map(|w| w[0]).fold(f64::INFINITY, f64::min),
            uv.iter().map(|w| w[0]).fold(f64::NEG_INFINITY, f64::max),
        );
        for b in &mut breaks {
            *b = b.clamp(u_lo, u_hi);
        }
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        let mut pieces: Vec<f64> = Vec::new();
        for w in breaks.windows(2) {
            let (ua, ub) = (w[0], w[1]);
            if ub <= ua {
                continue;
            }
            for &(xi, wxi) in &self.rules.outer {
                let u = 0.5 * (ua + ub) + 0.5 * (ub - ua) * xi;
                let wu = 0.5 * (ub - ua) * wxi;
                // The chord of the triangle along d at this u.
                let (mut v_lo, mut v_hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for (i, j) in EDGES {
                    let (ui, uj) = (uv[i][0], uv[j][0]);
                    if ui != uj && (u - ui) * (u - uj) <= 0.0 {
                        let tau = (u - ui) / (uj - ui);
                        let v = uv[i][1] + tau * (uv[j][1] - uv[i][1]);
                        v_lo = v_lo.min(v);
                        v_hi = v_hi.max(v);
                    }
                }
                if v_hi.partial_cmp(&v_lo) != Some(std::cmp::Ordering::Greater) {
                    continue;
                }
                let start = [0, 1].map(|c| q[0][c] + u * e[c] + v_lo * d[c]);
                let length = v_hi - v_lo;
                pieces.clear();
                pieces.push(0.0);
                for &k in crossing {
                    pieces.extend(self.map.roots_along(
                        &self.levels[k],
                        start,
                        d,
                        0.0,
                        length,
                        slack,
                    ));
                }
                pieces.push(length);
                pieces.sort_by(f64::total_cmp);
                for w in pieces.windows(2) {
                    let (va, vb) = (w[0], w[1]);
                    if vb <= va {
                        continue;
                    }
                    let at = |v: f64| [start[0] + v * d[0], start[1] + v * d[1]];
                    let (radial_beyond, angular_beyond) =
                        self.count_beyond(state, at(0.5 * (va + vb)));
                    for &(eta, weta) in &self.rules.inner {
                        (self.emit)(Point {
                            st: at(0.5 * (va + vb) + 0.5 * (vb - va) * eta),
                            weight: wu * 0.5 * (vb - va) * weta,
                            radial_beyond,
                            angular_beyond,
                        });
                    }
                }
            }
        }
    }

    /// How many radial and angular cuts the point `p` lies beyond: the fixed side of a cut that
    /// does not cross the current sub-triangle, else the sign of `G` at `p`.
    fn count_beyond(&self, state: &[Option<bool>], p: [f64; 2]) -> (usize, usize) {
        let mut n = (0, 0);
        for (level, s) in self.levels.iter().zip(state) {
            if s.unwrap_or_else(|| self.map.level_and_gradient(&level.cut, p).0 > 0.0) {
                match level.family() {
                    Family::Radial => n.0 += 1,
                    Family::Angular => n.1 += 1,
                }
            }
        }
        n
    }

    /// Where the cuts `a` and `b` meet inside `q` (Newton's method on their `G` from its
    /// centroid), if they do.
    fn meeting_point(&self, a: &Cut, b: &Cut, q: &[[f64; 2]; 3]) -> Option<[f64; 2]> {
        let mut p = centroid(q);
        let mut converged = false;
        for _ in 0..50 {
            let ((fa, ga), (fb, gb)) = (
                self.map.level_and_gradient(a, p),
                self.map.level_and_gradient(b, p),
            );
            let det = ga[0] * gb[1] - ga[1] * gb[0];
            let step = [
                (-fa * gb[1] + fb * ga[1]) / det,
                (-ga[0] * fb + gb[0] * fa) / det,
            ];
            if !(step[0].is_finite() && step[1].is_finite()) {
                return None;
            }
            p = [p[0] + step[0], p[1] + step[1]];
            if step[0].abs().max(step[1].abs()) <= ROOT_STEP {
                converged = true;
                break;
            }
        }
        // Barycentric coordinates of p in q: inside up to round-off.
        let area = cross2(sub2(q[1], q[0]), sub2(q[2], q[0]));
        let l1 = cross2(sub2(p, q[0]), sub2(q[2], q[0])) / area;
        let l2 = cross2(sub2(q[1], q[0]), sub2(p, q[0])) / area;
        let inside = l1 >= -1e-12 && l2 >= -1e-12 && l1 + l2 <= 1.0 + 1e-12;
        (converged && inside).then_some(p)
    }
}

/// Real roots of `α w² + β w + γ` (NaN for none), by the stable closed form: no cancellation
/// between `−β` and the square root.
fn quadratic_roots([a, b, c]: [f64; 3]) -> [f64; 2] {
    let mut roots = [f64::NAN; 2];
    if a == 0.0 {
        if b != 0.0 {
            roots[0] = -c / b;
        }
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let q = -0.5 * (b + disc.sqrt().copysign(b));
            if q != 0.0 {
                roots = [q / a, c / q];
            } else {
                roots[0] = 0.0;
            }
        }
    }
    roots
}

fn centroid(q: &[[f64; 2]; 3]) -> [f64; 2] {
    [0, 1].map(|i| (q[0][i] + q[1][i] + q[2][i]) / 3.0)
}
fn mid(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]
}
fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}
fn dot2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
fn norm2(a: [f64; 2]) -> f64 {
    dot2(a, a).sqrt()
}
fn cross2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
fn unit2(a: [f64; 2]) -> Option<[f64; 2]> {
    let n = norm2(a);
    (n > 0.0 && n.is_finite()).then(|| [a[0] / n, a[1] / n])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reference triangle as its own plane: `(a, b) = (s, t)`.
    const REFERENCE: [[f64; 2]; 6] = [
        [0.0, 0.0],
        [1.0, 0.0],
        [0.0, 1.0],
        [0.5, 0.0],
        [0.5, 0.5],
        [0.0, 0.5],
    ];

    fn interpolant(cut: Cut) -> Level {
        Level::interpolating(cut, REFERENCE.map(|p| cut.level(p)), 1e-12)
    }

    /// `∫ 1, ∫ s, ∫ t` over the points beyond each (radial, angular) count of cuts.
    fn moments(levels: &[Level]) -> std::collections::BTreeMap<(usize, usize), [f64; 3]> {
        let mut m = std::collections::BTreeMap::new();
        split_quadrature(&REFERENCE, levels, &Rules::new(), |p: Point| {
            let e: &mut [f64; 3] = m.entry((p.radial_beyond, p.angular_beyond)).or_default();
            e[0] += p.weight;
            e[1] += p.weight * p.st[0];
            e[2] += p.weight * p.st[1];
        });
        m
    }

    #[test]
    fn gauss_legendre_rules_integrate_their_degree_exactly() {
        // N points: exact for x^k, k <= 2N - 1: ∫_{-1}^{1} x^k = 2 / (k + 1) for even k.
        fn check<const N: usize>() {
            let rule = gauss_legendre::<N>();
            for k in 0..2 * N {
                let q: f64 = rule.iter().map(|(x, w)| w * x.powi(k as i32)).sum();
                let exact = if k % 2 == 0 {
                    2.0 / (k as f64 + 1.0)
                } else {
                    0.0
                };
                // Round-off of the sum of N terms.
                assert!((q - exact).abs() < 1e-15, "N = {N}, x^{k}: {q} vs {exact}");
            }
        }
        check::<4>();
        check::<10>();
    }

    #[test]
    fn a_straight_cut_splits_the_triangle_exactly() {
        // The angular cut at −45° about an axis through (s, t) = (1/4, 1/4) (the planar map
        // shifts the reference triangle by −(1/4, 1/4)): g = (s + t − 1/2)/√2, the line that
        // cuts off the corner triangle of area 1/8 with centroid (1/6, 1/6).
        let shifted = REFERENCE.map(|[s, t]| [s - 0.25, t - 0.25]);
        let phi = -std::f64::consts::FRAC_PI_4;
        let cut = Cut::Angular {
            sin: phi.sin(),
            cos: phi.cos(),
        };
        let lvl = Level::interpolating(cut, shifted.map(|p| cut.level(p)), 1e-12);
        let mut m = std::collections::BTreeMap::<usize, [f64; 2]>::new();
        split_quadrature(&shifted, &[lvl], &Rules::new(), |p: Point| {
            let e = m.entry(p.angular_beyond).or_default();
            e[0] += p.weight;
            e[1] += p.weight * p.st[0];
        });
        let (near, far) = (m[&0], m[&1]);
        // A polynomial domain integrated by exact rules: round-off only.
        assert!((near[0] - 0.125).abs() < 1e-15, "{near:?}");
        assert!((near[1] / near[0] - 1.0 / 6.0).abs() < 1e-15);
        assert!((far[0] - 0.375).abs() < 1e-15, "{far:?}");
        assert!((near[0] + far[0] - 0.5).abs() < 1e-15);
    }

    #[test]
    fn a_circle_and_a_ray_cut_the_triangle_into_quarter_disc_halves() {
        // a² + b² = 1/4 (a quarter disc of radius 1/2 in the corner, away from s + t = 1) and
        // the ray at 45° through its centre: each half has area π/32 and first moments
        // (r³/3) sin 45° and (r³/3)(1 − cos 45°) (polar integration over 0..45° and 45..90°).
        let circle = interpolant(Cut::Radial { radius: 0.5 });
        let phi = std::f64::consts::FRAC_PI_4;
        let ray = interpolant(Cut::Angular {
            sin: phi.sin(),
            cos: phi.cos(),
        });
        let m = moments(&[circle, ray]);
        let r3 = 0.125 / 3.0;
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let below = m[&(0, 0)]; // inside the circle, below the ray (t < s)
        let above = m[&(0, 1)]; // inside the circle, above it
        let pi32 = std::f64::consts::PI / 32.0;
        // Curved boundary: the outer Gauss rule integrates the circle's root v(u), a square
        // root, between breakpoints (measured 1e-17).
        for (got, s_moment, t_moment) in [
            (below, r3 * h, r3 * (1.0 - h)),
            (above, r3 * (1.0 - h), r3 * h),
        ] {
            assert!((got[0] - pi32).abs() < 1e-14, "{got:?} vs {pi32}");
            assert!((got[1] - s_moment).abs() < 1e-14, "{got:?}");
            assert!((got[2] - t_moment).abs() < 1e-14, "{got:?}");
        }
        let total: f64 = m.values().map(|v| v[0]).sum();
        assert!((total - 0.5).abs() < 1e-15);
    }

    #[test]
    fn a_cut_along_an_edge_does_not_split_the_triangle() {
        // The ray at 0° is the edge v0-v1 (b = t = 0): the triangle touches it, lies beyond
        // it, and is not split.
        let cut = Cut::Angular { sin: 0.0, cos: 1.0 };
        let g = REFERENCE.map(|p| cut.level(p));
        assert_eq!(side_of(&g, 1e-12), Side::Above);
        let m = moments(&[interpolant(cut)]);
        assert_eq!(m.len(), 1);
        // The degree-4 rule of the whole triangle: its weights are given to 15 digits.
        assert!((m[&(0, 1)][0] - 0.5).abs() < 2e-15, "{m:?}");
    }
}
