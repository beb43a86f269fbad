//! Coordinate systems of bulk data: `CORD2R`, `CORD2C`, `CORD2S` (each defined by three
//! points in another system, `RID`, which may itself be any of them).
//!
//! A `CORD2x` gives points `A` (the origin), `B` (on the local z axis) and `C` (in the local
//! x-z plane) in system `RID` (0 or blank: the basic system). With them in basic coordinates,
//! the local axes are `e_z = (B - A)/|B - A|`, `e_y = e_z × (C - A)/|e_z × (C - A)|`,
//! `e_x = e_y × e_z` (MSC Nastran Quick Reference Guide, CORD2R). A point with local
//! coordinates `q` is at `A + q_x e_x + q_y e_y + q_z e_z`, where `q` is `(X1, X2, X3)` in a
//! rectangular system, `(R cos θ, R sin θ, Z)` for `(R, θ, Z)` in a cylindrical one and
//! `(R sin θ cos φ, R sin θ sin φ, R cos θ)` for `(R, θ, φ)` in a spherical one (angles in
//! degrees).

use squeal_element::geometry::{cross, sub, unit};
/// The kind of a coordinate system.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Rectangular,
    Cylindrical,
    Spherical,
}

/// A `CORD2x` as written: kind, reference system and the points `A`, `B`, `C` in it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Definition {
    pub kind: Kind,
    pub rid: u64,
    pub a: [f64; 3],
    pub b: [f64; 3],
    pub c: [f64; 3],
}

/// A resolved system: origin and unit axes in the basic system.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame {
    pub kind: Kind,
    pub origin: [f64; 3],
    pub axes: [[f64; 3]; 3],
}

impl Frame {
    /// The system of `def`, whose reference system is `reference` (`None`: basic). `None`
    /// if `A`, `B`, `C` do not define axes (coincident or collinear points).
    pub fn new(def: &Definition, reference: Option<&Frame>) -> Option<Frame> {
        let place = |p: [f64; 3]| reference.map_or(p, |r| r.to_basic(p));
        let (a, b, c) = (place(def.a), place(def.b), place(def.c));
        let ez = unit(sub(b, a))?;
        let ey = unit(cross(ez, sub(c, a)))?;
        let ex = cross(ey, ez);
        Some(Frame {
            kind: def.kind,
            origin: a,
            axes: [ex, ey, ez],
        })
    }

    /// Basic coordinates of the point with coordinates `q` in this system.
    pub fn to_basic(self, q: [f64; 3]) -> [f64; 3] {
        let local = match self.kind {
            Kind::Rectangular => q,
            Kind::Cylindrical => {
                let (s, c) = q[1].to_radians().sin_cos();
                [q[0] * c, q[0] * s, q[2]]
            }
            Kind::Spherical => {
                let (st, ct) = q[1].to_radians().sin_cos();
                let (sp, cp) = q[2].to_radians().sin_cos();
                [q[0] * st * cp, q[0] * st * sp, q[0] * ct]
            }
        };
        std::array::from_fn(|d| {
            self.origin[d]
                + local[0] * self.axes[0][d]
                + local[1] * self.axes[1][d]
                + local[2] * self.axes[2][d]
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|d| (a[d] - b[d]).abs() < 1e-14)
    }

    /// A system at (1, 2, 3) turned 90 degrees about z: local x is basic y.
    #[test]
    fn rectangular_cylindrical_and_spherical_points() {
        let def = Definition {
            kind: Kind::Rectangular,
            rid: 0,
            a: [1.0, 2.0, 3.0],
            b: [1.0, 2.0, 4.0],
            c: [1.0, 3.0, 3.0],
        };
        let f = Frame::new(&def, None).unwrap();
        assert!(close(f.to_basic([1.0, 0.0, 0.0]), [1.0, 3.0, 3.0]));
        assert!(close(f.to_basic([0.0, 1.0, 0.0]), [0.0, 2.0, 3.0]));
        let cyl = Frame {
            kind: Kind::Cylindrical,
            ..f
        };
        // r = 2 at 90 degrees: along local y, which is basic -x.
        assert!(close(cyl.to_basic([2.0, 90.0, 1.0]), [-1.0, 2.0, 4.0]));
        let sph = Frame {
            kind: Kind::Spherical,
            ..f
        };
        // theta = 90, phi = 0: along local x (basic y).
        assert!(close(sph.to_basic([2.0, 90.0, 0.0]), [1.0, 4.0, 3.0]));
        // A system defined in the turned one: its origin at local (1, 0, 0).
        let inner = Definition {
            kind: Kind::Rectangular,
            rid: 5,
            a: [1.0, 0.0, 0.0],
            b: [1.0, 0.0, 1.0],
            c: [2.0, 0.0, 0.0],
        };
        let g = Frame::new(&inner, Some(&f)).unwrap();
        assert!(close(g.to_basic([0.0; 3]), [1.0, 3.0, 3.0]));
        assert!(close(g.to_basic([1.0, 0.0, 0.0]), [1.0, 4.0, 3.0]));
        let collinear = Definition {
            c: [1.0, 2.0, 5.0],
            ..def
        };
        assert!(Frame::new(&collinear, None).is_none());
    }
}
