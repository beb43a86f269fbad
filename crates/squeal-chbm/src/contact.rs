//! The contact and friction forces of eqs (8)–(10) on the nonlinear dofs, as seen by the AFT
//! scheme of eq (29): `G(x_n) = F_nl(x_n) - K_s x_n` (the springs `K_s` live in the linear part,
//! see [`crate::condensed`]).

use squeal_brake::modal_brake::ModalBrake;
use squeal_brake::model::contact_law;
use squeal_hbm::{LocalJacobian, NonlinearForce};
use std::collections::BTreeMap;

/// `G(x_n)` for the harmonic balance.
pub struct ContactForce {
    mb: ModalBrake,
    pattern: Vec<(usize, usize)>,
    /// Per pair: for each (row, col) of `k_t (g + μh) gᵀ`, its pattern index and coefficient.
    entries: Vec<Vec<(usize, f64)>>,
    /// `(pattern index, -K_s[r][c])`.
    springs: Vec<(usize, f64)>,
}

impl ContactForce {
    pub fn new(mb: &ModalBrake) -> Self {
        let mut index: BTreeMap<(usize, usize), usize> = BTreeMap::new();
        let mut coeffs: Vec<Vec<((usize, usize), f64)>> = Vec::new();
        for p in &mb.pairs {
            let mut list = Vec::new();
            for &(c, gc) in &p.normal {
                for &(r, gr) in &p.normal {
                    list.push(((r, c), gr * gc));
                }
                for &(r, hr) in &p.tangent {
                    list.push(((r, c), mb.mu * hr * gc));
                }
            }
            for (rc, _) in &list {
                index.insert(*rc, 0);
            }
            coeffs.push(list);
        }
        let nn = mb.nl();
        for r in 0..nn {
            for c in 0..nn {
                if mb.k_s[(r, c)] != 0.0 {
                    index.insert((r, c), 0);
                }
            }
        }
        let pattern: Vec<(usize, usize)> = index.keys().copied().collect();
        for (k, v) in index.values_mut().enumerate() {
            *v = k;
        }
        let entries = coeffs
            .into_iter()
            .map(|l| l.into_iter().map(|(rc, v)| (index[&rc], v)).collect())
            .collect();
        let springs = (0..nn)
            .flat_map(|r| (0..nn).map(move |c| (r, c)))
            .filter(|&(r, c)| mb.k_s[(r, c)] != 0.0)
            .map(|(r, c)| (index[&(r, c)], -mb.k_s[(r, c)]))
            .collect();
        Self {
            mb: mb.clone(),
            pattern,
            entries,
            springs,
        }
    }

    pub fn modal_brake(&self) -> &ModalBrake {
        &self.mb
    }
}

impl NonlinearForce for ContactForce {
    fn n_dofs(&self) -> usize {
        self.mb.nl()
    }

    fn pattern(&self) -> &[(usize, usize)] {
        &self.pattern
    }

    fn depends_on_velocity(&self) -> bool {
        false
    }

    fn eval(&self, x: &[f64], _xdot: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>) {
        self.mb.add_reduced_force(x, f);
        if let Some(j) = jac {
            for (p, entries) in self.mb.pairs.iter().zip(&self.entries) {
                let (_, kt) = contact_law(p.penetration(x), p.k_linear, p.k_cubic);
                if kt != 0.0 {
                    for &(idx, v) in entries {
                        j.dfdx[idx] += kt * v;
                    }
                }
            }
            for &(idx, v) in &self.springs {
                j.dfdx[idx] += v;
            }
        }
    }
}
