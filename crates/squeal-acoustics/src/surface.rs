//! The radiating surface as the integrals see it: every quadrature point of every face with
//! its position `y_q`, outward unit normal `n_q` and area weight `dA_q = w_q |∂x/∂ξ × ∂x/∂η|`,
//! computed once from the nodes, the faces and a [`FaceRule`]; and the normal velocity at those
//! points from nodal data, `v_n(y_q) = Σ_i N_i(q) v_n,i` (per face node) or
//! `v_n(y_q) = n_q · Σ_i N_i(q) v_i` (3-D nodal velocity).

use crate::error::{AcousticsError, Result};
use crate::rule::FaceRule;
use num_complex::Complex64;
use squeal_element::geometry::{cross, dot};

/// One quadrature point of the surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Its face (0-based).
    pub face: u32,
    /// Position `y_q` (m).
    pub position: [f64; 3],
    /// Outward unit normal.
    pub normal: [f64; 3],
    /// Area weight `dA_q` (m²).
    pub area: f64,
}

/// The velocity of the surface at one angular frequency, as nodal data.
#[derive(Clone, Copy, Debug)]
pub enum Velocity<'a> {
    /// The complex normal velocity (m/s, along the face's outward normal) at each node of each
    /// face, face by face in the faces' node order (`faces × nodes per face` values).
    FaceNodes(&'a [Complex64]),
    /// The complex 3-D velocity (m/s) of each node of the surface's node list.
    Nodal(&'a [[Complex64; 3]]),
}

/// Faces of `N` nodes over a node list, with their quadrature points.
#[derive(Clone, Debug)]
pub struct RadiatingSurface {
    /// Nodes per face.
    pub nodes_per_face: usize,
    /// Node indices of each face, face after face.
    pub faces: Vec<u32>,
    /// Number of nodes of the node list the faces index.
    pub node_count: usize,
    /// The face rules' shape values, one row of `nodes_per_face` per rule point, rule after
    /// rule (a rule of fewer nodes padded with zeros).
    pub shape: Vec<f64>,
    /// Each face's rule (index into the rules the surface was made with; all 0 for one rule).
    pub face_rule: Vec<u8>,
    /// Rule points per face.
    pub points_per_face: usize,
    /// Every quadrature point, face after face.
    pub points: Vec<SurfacePoint>,
}

impl RadiatingSurface {
    /// The surface of `faces` (`rule.nodes` node indices per face, face after face) over
    /// `nodes`, integrated with `rule`.
    pub fn new(nodes: &[[f64; 3]], faces: &[u32], rule: &FaceRule) -> Result<Self> {
        let npf = rule.nodes;
        let count = faces.len() / npf.max(1);
        Self::with_rules(
            nodes,
            faces,
            npf,
            std::slice::from_ref(rule),
            &vec![0; count],
        )
    }

    /// The surface of faces of several shapes: `nodes_per_face` node indices per face, face
    /// after face, face `f` integrated with `rules[face_rule[f]]`. A rule of fewer nodes than
    /// `nodes_per_face` reads the face's first nodes (the others, any valid node, get shape
    /// value 0: e.g. a 6-node triangle padded to 8 with its first node, beside 8-node
    /// quadrilaterals). Every rule must have the same number of points (e.g.
    /// [`FaceRule::tri6_gauss`]`(3)` and [`FaceRule::quad8`]`(3)`, nine each, both exact to
    /// degree 4 on their reference domain).
    pub fn with_rules(
        nodes: &[[f64; 3]],
        faces: &[u32],
        nodes_per_face: usize,
        rules: &[FaceRule],
        face_rule: &[u8],
    ) -> Result<Self> {
        let npf = nodes_per_face;
        let n_faces = face_rule.len();
        if npf == 0 || faces.len() != n_faces * npf {
            return Err(AcousticsError::Length {
                what: "face node list",
                expected: n_faces * npf.max(1),
                got: faces.len(),
            });
        }
        let nq = rules.first().map_or(0, |r| r.points.len());
        for rule in rules {
            if rule.points.len() != nq || rule.nodes > npf {
                return Err(AcousticsError::Rule(format!(
                    "a rule of {} points on {}-node faces among rules of {nq} points on {npf}-node faces",
                    rule.points.len(),
                    rule.nodes
                )));
            }
            for p in &rule.points {
                if p.shape.len() != rule.nodes || p.gradient.len() != rule.nodes {
                    return Err(AcousticsError::Rule(format!(
                        "a point has {} shape values for {}-node faces",
                        p.shape.len(),
                        rule.nodes
                    )));
                }
            }
        }
        if let Some(&r) = face_rule.iter().find(|&&r| r as usize >= rules.len()) {
            return Err(AcousticsError::Rule(format!(
                "a face names rule {r} of {}",
                rules.len()
            )));
        }
        let mut points = Vec::with_capacity(n_faces * nq);
        for f in 0..n_faces {
            let rule = &rules[face_rule[f] as usize];
            let face = &faces[f * npf..(f + 1) * npf];
            let mut x = Vec::with_capacity(npf);
            for &n in face {
                let p = nodes
                    .get(n as usize)
                    .ok_or(AcousticsError::NodeOutOfRange {
                        face: f,
                        node: n,
                        nodes: nodes.len(),
                    })?;
                x.push(*p);
            }
            for (q, rp) in rule.points.iter().enumerate() {
                let (mut y, mut a, mut b) = ([0.0; 3], [0.0; 3], [0.0; 3]);
                for i in 0..rule.nodes {
                    for d in 0..3 {
                        y[d] += rp.shape[i] * x[i][d];
                        a[d] += rp.gradient[i][0] * x[i][d];
                        b[d] += rp.gradient[i][1] * x[i][d];
                    }
                }
                let c = cross(a, b);
                let jac = dot(c, c).sqrt();
                if !(jac.is_finite() && jac > 0.0 && y.iter().all(|v| v.is_finite())) {
                    return Err(AcousticsError::DegenerateFace {
                        face: f,
                        point: q,
                        jacobian: jac,
                    });
                }
                points.push(SurfacePoint {
                    face: f as u32,
                    position: y,
                    normal: c.map(|v| v / jac),
                    area: rp.weight * jac,
                });
            }
        }
        let shape = rules
            .iter()
            .flat_map(|r| r.points.iter())
            .flat_map(|p| (0..npf).map(|i| p.shape.get(i).copied().unwrap_or(0.0)))
            .collect();
        Ok(Self {
            nodes_per_face: npf,
            faces: faces.to_vec(),
            node_count: nodes.len(),
            shape,
            face_rule: face_rule.to_vec(),
            points_per_face: nq,
            points,
        })
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.faces.len() / self.nodes_per_face
    }

    /// Total area (m²).
    pub fn area(&self) -> f64 {
        self.points.iter().map(|p| p.area).sum()
    }

    /// The normal velocity at every quadrature point (m/s).
    pub fn normal_velocity(&self, v: Velocity) -> Result<Vec<Complex64>> {
        let (npf, nq) = (self.nodes_per_face, self.points_per_face);
        match v {
            Velocity::FaceNodes(vn) => {
                check_len("face-node normal velocities", self.faces.len(), vn.len())?;
                Ok(self
                    .points
                    .iter()
                    .enumerate()
                    .map(|(k, p)| {
                        let (f, q) = (p.face as usize, k % nq);
                        let row = self.face_rule[f] as usize * nq + q;
                        let n = &self.shape[row * npf..(row + 1) * npf];
                        (0..npf).map(|i| vn[f * npf + i] * n[i]).sum()
                    })
                    .collect())
            }
            Velocity::Nodal(u) => {
                check_len("nodal velocities", self.node_count, u.len())?;
                Ok(self
                    .points
                    .iter()
                    .enumerate()
                    .map(|(k, p)| {
                        let (f, q) = (p.face as usize, k % nq);
                        let row = self.face_rule[f] as usize * nq + q;
                        let n = &self.shape[row * npf..(row + 1) * npf];
                        let mut s = Complex64::new(0.0, 0.0);
                        for i in 0..npf {
                            let ui = &u[self.faces[f * npf + i] as usize];
                            let un =
                                ui[0] * p.normal[0] + ui[1] * p.normal[1] + ui[2] * p.normal[2];
                            s += un * n[i];
                        }
                        s
                    })
                    .collect())
            }
        }
    }
}

fn check_len(what: &'static str, expected: usize, got: usize) -> Result<()> {
    if expected == got {
        Ok(())
    } else {
        Err(AcousticsError::Length {
            what,
            expected,
            got,
        })
    }
}
