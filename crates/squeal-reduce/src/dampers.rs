//! Viscous dampers inside a part: between two node sets of the part, or from a node set to
//! ground, with a damping coefficient along three axes, projected by the part's Craig–Bampton
//! basis.
//!
//! A damper is a spring's twin ([`crate::springs`]): the same ends, axes and spreads
//! ([`Spread`]), with a damping coefficient `c_d` (N s/m) in the stiffness's place. Its
//! dissipation function `½ Σ_d c_d (e_d · (u̇_a − u̇_b))²` (Rayleigh's, the dashpot's) gives the
//! viscous force `−C u̇` with the rank-one terms `C = Σ_d c_d w_d w_dᵀ`, `w_d · u = e_d · (ū_a −
//! ū_b)`, exactly the terms [`crate::springs::spring_terms`] builds for a stiffness: the mean
//! (an interpolation element, Nastran's RBE3 with a CDAMP/CBUSH `B`, Abaqus' DASHPOT on a
//! distributing coupling), the tributary-area share to ground (a viscous foundation, Abaqus'
//! distributed dashpots) and the normal of a sliding abutment.
//!
//! **Projection.** The reduction does not change: the fixed-interface and constraint modes
//! come from `K` and `M` alone (eqs 1–5), and the damper enters as eqs (6)–(7) project `K`
//! and `M`, by the basis `T = [T_C T_φ]` the `.rom` keeps (`u = T q`):
//! `Ĉ = Tᵀ C T = Σ_terms c r rᵀ` with `r = Tᵀ w`, `r_j = Σ_(n, d) w_(n,d) T_((n,d), j)` over the
//! term's node directions (a restrained direction has no row: its velocity is zero and it
//! adds nothing). A damper therefore changes no reduction and needs no new one; the part must
//! have been written with its basis. The reduced brake stacks the parts' `Ĉ` as it stacks
//! `K̂` and `M̂` (`squeal_brake::model::Brake::c`) and adds `Φᵀ Ĉ Φ` to the modal damping
//! (`squeal_brake::damping`).
//!
//! A rigid part of mass `m` on a `mean` spring `k` and a `mean` damper `c` to ground along `e`
//! moves along `e` as one degree of freedom, `λ = −c/(2m) ± i √(k/m − c²/(4m²))`, as long as
//! the part's elastic modes are far above `√(k/m)` (`crates/squeal-reduce/tests/reduce/dampers.rs`).

use crate::error::ReduceError;
use crate::rom::ReducedPart;
pub use crate::springs::Spread;
use crate::springs::{Element, Spring, SpringTerm, terms_of};
use faer::Mat;
use squeal_mesh::Mesh;
use std::collections::HashMap;

/// A viscous damper of a part (module docs).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Damper {
    /// Node set of the first end.
    pub set: String,
    /// Node set of the second end, on the same part; `None`: ground.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub to: Option<String>,
    /// Total damping coefficient along the three axes (N s/m).
    pub damping: [f64; 3],
    /// The axes, as three orthonormal unit vectors; `None`: x, y, z.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axes: Option<[[f64; 3]; 3]>,
    /// How the ends' velocities are taken from their sets.
    pub spread: Spread,
}

impl Damper {
    /// The spring of the same ends, axes and spread with `damping` as its stiffness.
    fn as_spring(&self) -> Spring {
        Spring {
            set: self.set.clone(),
            to: self.to.clone(),
            stiffness: self.damping,
            axes: self.axes,
            spread: self.spread,
        }
    }
}

/// The rank-one terms `c (w · u̇)²` of `dampers` on `mesh` (module docs), damper by damper, axis
/// by axis (axes without damping left out); each term's `k` is the damping coefficient.
pub fn damper_terms(mesh: &Mesh, dampers: &[Damper]) -> Result<Vec<SpringTerm>, ReduceError> {
    let springs: Vec<Spring> = dampers.iter().map(Damper::as_spring).collect();
    terms_of(Element::Damper, mesh, &springs)
}

/// `Ĉ = Tᵀ C T` of `dampers` on `part`, reduced from `mesh` (module docs): `n × n`, symmetric,
/// with `n` the part's reduced dofs. Refused when the part was written without its basis.
pub fn reduced_damping(
    mesh: &Mesh,
    part: &ReducedPart,
    dampers: &[Damper],
) -> Result<Mat<f64>, ReduceError> {
    let name = &part.info.name;
    let basis = part.basis.as_ref().ok_or_else(|| {
        ReduceError::Options(format!(
            "the {name} was reduced without its basis (--no-basis): a damper is projected by the Craig–Bampton basis; reduce it again with the basis"
        ))
    })?;
    let terms = damper_terms(mesh, dampers)?;
    let row: HashMap<(u64, u8), usize> = basis
        .dof_node
        .iter()
        .zip(&basis.dof_dir)
        .enumerate()
        .map(|(r, (&node, &dir))| ((node, dir), r))
        .collect();
    let n = part.size();
    let t = &basis.values;
    let mut c = Mat::<f64>::zeros(n, n);
    let mut r = vec![0.0; n];
    for term in &terms {
        r.iter_mut().for_each(|x| *x = 0.0);
        for &(node, w) in &term.entries {
            let id = *mesh.node_ids.get(node as usize).ok_or_else(|| {
                ReduceError::Options(format!("damper node {node} is not in the {name}'s mesh"))
            })?;
            for (d, &wd) in w.iter().enumerate().filter(|(_, wd)| **wd != 0.0) {
                if let Some(&i) = row.get(&(id, d as u8)) {
                    for (j, rj) in r.iter_mut().enumerate() {
                        *rj += wd * t[(i, j)];
                    }
                }
            }
        }
        // The lower triangle, mirrored below: symmetric to the bit.
        for j in 0..n {
            let f = term.k * r[j];
            for i in j..n {
                c[(i, j)] += f * r[i];
            }
        }
    }
    for j in 0..n {
        for i in 0..j {
            c[(i, j)] = c[(j, i)];
        }
    }
    Ok(c)
}
