//! A researcher's front door: a friction system from its matrices and contact pairs, and the
//! three questions asked of it — where it turns unstable, which limit cycle it settles on, and
//! how the cycles continue with friction, with their stability.
//!
//! **The problem.** As in NLvib (Krack & Gross, *Harmonic Balance for Nonlinear Vibration
//! Problems*, 2019), a system is its linear part plus a list of nonlinear elements:
//!
//! `M x'' + C x' + K x + Σ_p (F_n,p g_p + F_t,p h_p) = F`,
//!
//! eq (11) of the paper with eq (10)'s contact forces, each pair `p` a closure direction
//! `g_p` (its penetration is `δ_p = g_p · x - g0_p`, `g0_p` the initial gap, positive when
//! open), a sliding direction `h_p` (slip velocity `V_p + h_p · x'`) and a contact law
//! ([`squeal_brake::contact::ContactLaw`]: the paper's [`PenaltyCoulomb`], the velocity-
//! dependent law, or the user's own). [`FrictionSystem::builder`] takes `M`, `C`, `K`;
//! [`Contact`] takes only what the physics needs (`g`, `h`, the law; the gap and the disc's
//! speed when they are not zero), the rest of [`ContactPair`] is for the bundled brake's
//! reports and defaults to zero.
//!
//! **The damping.** The analyses work in the undamped, frictionless modes `Φ` of the system at
//! its frictionless equilibrium (eq 12). `C` enters as `D = Φᵀ C Φ`: kept diagonal when its
//! off-diagonal entries are round-off (below `1e-12 max |D|`: a proportional `C`), which keeps
//! the fast paths of the sweep, otherwise full ([`ModalDamping::Full`]).
//!
//! **The methods.** As in diffsol, the problem is built once and the method is chosen apart:
//! [`FrictionSystem::settings`] holds the controls of every analysis ([`Settings`], defaults
//! for a small system), read by
//! - [`FrictionSystem::hopf`]: the friction sweep and its refined Hopf point μ0 (section 3,
//!   eqs 20–22) — [`squeal_brake::sweep`];
//! - [`FrictionSystem::limit_cycle`]: CHBM at μ from the unstable mode there (section 4, eqs
//!   46–48) — [`crate::solve`](mod@crate::solve);
//! - [`FrictionSystem::branch`]: the branch of limit cycles born at μ0, from the Hopf normal
//!   form, with each cycle's Floquet multipliers by Hill's method and the bifurcations they
//!   show — [`crate::branch`], [`crate::floquet`], [`crate::bifurcation`];
//! - [`FrictionSystem::nonlinear_mode`]: the squeal mode's frequency and modal damping against
//!   its amplitude at μ (extended periodic motion concept), its roots the limit cycles —
//!   [`crate::nlmode`].

use crate::bifurcation::{Bifurcation, bifurcations, follow_from_hopf_with_hill};
use crate::branch::{BranchOptions, LimitCycleBranch};
use crate::floquet::{FloquetError, HillFloquet, HillOptions};
use crate::nlmode::{NlModeError, NlModeOptions, NonlinearMode, nonlinear_mode};
use crate::solve::{ChbmError, ChbmOptions, ChbmSolution, RESTART_AMPLITUDES, solve_with_restarts};
use crate::start::{StartError, start_at};
use faer::{Mat, c64};
use squeal_brake::contact::{ContactLaw, PenaltyCoulomb};
use squeal_brake::criticality::{NormalForm, normal_form};
use squeal_brake::damping::ModalDamping;
use squeal_brake::modal::Damping;
use squeal_brake::modal_brake::ModalBrake;
use squeal_brake::spectrum::Reference;
use squeal_brake::sweep::{Hopf, SweepOptions, reference, sweep};
use squeal_brake::{Brake, BrakeError, ContactPair};
use std::sync::Arc;

/// Why an analysis of a [`FrictionSystem`] failed.
#[derive(Debug, thiserror::Error)]
pub enum SystemError {
    /// `C` is not the size of `M`.
    #[error("the damping matrix is {rows} x {cols}, the mass matrix {n} x {n}: give C of M's size")]
    DampingSize {
        /// Rows of `C`.
        rows: usize,
        /// Columns of `C`.
        cols: usize,
        /// Rows of `M`.
        n: usize,
    },
    /// The system itself (sizes, equilibrium, modes, spectra).
    #[error(transparent)]
    Brake(#[from] BrakeError),
    /// No unstable mode to start CHBM from.
    #[error(transparent)]
    Start(#[from] StartError),
    /// The harmonic balance or the branch.
    #[error(transparent)]
    Chbm(#[from] ChbmError),
    /// The nonlinear mode ([`crate::nlmode`]).
    #[error(transparent)]
    NlMode(#[from] NlModeError),
    /// The sweep found no Hopf point.
    #[error(
        "no mode turns unstable for mu in [{from}, {to}]: widen Settings::friction_range (or check the friction coupling)"
    )]
    NoHopf {
        /// Lower end of the sweep.
        from: f64,
        /// Upper end of the sweep.
        to: f64,
    },
}

/// One contact pair, by what its physics needs.
#[derive(Clone, Debug)]
pub struct Contact {
    pair: ContactPair,
}

impl Contact {
    /// A pair closing along `normal` (`δ = g · x`, positive when closed) and sliding along
    /// `tangent` (the friction force acts along `h`), with the element `law`.
    pub fn new(
        normal: &[(usize, f64)],
        tangent: &[(usize, f64)],
        law: impl ContactLaw + 'static,
    ) -> Self {
        Self {
            pair: ContactPair {
                disc_point: 0,
                pad_point: 0,
                position: [0.0; 3],
                normal_direction: [0.0; 3],
                sliding_direction: [0.0; 3],
                normal: normal.to_vec(),
                tangent: tangent.to_vec(),
                initial_gap: 0.0,
                surface_speed: None,
                law: Arc::new(law),
            },
        }
    }

    /// [`Contact::new`] with the paper's element: `F_n = k_l δ + k_nl δ³` (N/m, N/m³) when
    /// closed, `F_t = μ F_n` (eqs 8–9).
    pub fn penalty_coulomb(
        normal: &[(usize, f64)],
        tangent: &[(usize, f64)],
        k_linear: f64,
        k_cubic: f64,
    ) -> Self {
        Self::new(normal, tangent, PenaltyCoulomb { k_linear, k_cubic })
    }

    /// The initial gap `g0` (m): `δ = g · x - g0`; negative for a preloaded (interfering) pair.
    pub fn initial_gap(mut self, g0: f64) -> Self {
        self.pair.initial_gap = g0;
        self
    }

    /// The disc's surface speed `V` at the pair (m/s), for laws that depend on the slip
    /// velocity `V + h · x'`.
    pub fn surface_speed(mut self, speed: f64) -> Self {
        self.pair.surface_speed = Some(speed);
        self
    }

    /// The pair as the brake holds it.
    pub fn pair(&self) -> &ContactPair {
        &self.pair
    }
}

/// The controls of every analysis of a [`FrictionSystem`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Settings {
    /// Friction values `[from, to]` the Hopf point is searched in (default `[0, 2]`).
    pub friction_range: (f64, f64),
    /// Points of that sweep, ends included (default 41).
    pub sweep_points: usize,
    /// The sweep: its band (every frequency by default), Newton's controls for the equilibria,
    /// μ0's tolerance.
    pub sweep: SweepOptions,
    /// CHBM's harmonics and tolerances.
    pub chbm: ChbmOptions,
    /// The initial amplitudes CHBM tries in turn ([`RESTART_AMPLITUDES`]).
    pub restart_amplitudes: Vec<f64>,
    /// The branch's harmonics, range (as factors on μ0) and step control.
    pub branch: BranchOptions,
    /// Hill's method for the Floquet multipliers along the branch.
    pub hill: HillOptions,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            friction_range: (0.0, 2.0),
            sweep_points: 41,
            sweep: SweepOptions::default(),
            chbm: ChbmOptions::default(),
            restart_amplitudes: RESTART_AMPLITUDES.to_vec(),
            branch: BranchOptions::default(),
            hill: HillOptions::default(),
        }
    }
}

/// Builds a [`FrictionSystem`]: `M`, `C`, `K`, the contact pairs and the static load.
#[derive(Clone, Debug)]
pub struct SystemBuilder {
    m: Mat<f64>,
    c: Mat<f64>,
    k: Mat<f64>,
    load: Option<Vec<f64>>,
    pairs: Vec<ContactPair>,
}

impl SystemBuilder {
    /// Adds a contact pair.
    pub fn contact(mut self, contact: Contact) -> Self {
        self.pairs.push(contact.pair);
        self
    }

    /// The static load `F` (N), e.g. the piston's (default: none).
    pub fn load(mut self, f: Vec<f64>) -> Self {
        self.load = Some(f);
        self
    }

    /// The system with [`Settings::default`]: its frictionless equilibrium, modes and modal
    /// damping computed (module documentation).
    pub fn build(self) -> Result<FrictionSystem, SystemError> {
        let n = self.m.nrows();
        if self.c.nrows() != n || self.c.ncols() != n {
            return Err(SystemError::DampingSize {
                rows: self.c.nrows(),
                cols: self.c.ncols(),
                n,
            });
        }
        let brake = Brake {
            f_piston: self.load.unwrap_or_else(|| vec![0.0; n]),
            c: None,
            k_vibration: None,
            m: self.m,
            k: self.k,
            pairs: self.pairs,
        };
        brake.validate()?;
        let settings = Settings::default();
        let mut reference = reference(&brake, &Damping::default(), &settings.sweep.newton)?;
        reference.damping = modal_damping(&reference, &self.c);
        Ok(FrictionSystem {
            brake,
            reference,
            settings,
        })
    }
}

/// `D = Φᵀ C Φ`, diagonal when its off-diagonal entries are round-off.
fn modal_damping(reference: &Reference, c: &Mat<f64>) -> ModalDamping {
    let phi = &reference.basis.phi;
    let d = phi.transpose() * c * phi;
    let n = d.nrows();
    let largest = d.norm_max();
    let off = (0..n)
        .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
        .map(|(i, j)| d[(i, j)].abs())
        .fold(0.0, f64::max);
    if off <= 1e-12 * largest {
        ModalDamping::Diagonal((0..n).map(|j| d[(j, j)]).collect())
    } else {
        ModalDamping::Full(d)
    }
}

/// A branch of limit cycles with its Floquet analysis.
#[derive(Debug)]
pub struct Branch {
    /// The Hopf normal form it starts from (μ0, ω0, the first Lyapunov coefficient).
    pub normal_form: NormalForm,
    /// The cycles along it.
    pub branch: LimitCycleBranch,
    /// Hill's exponents and multipliers at each cycle.
    pub floquet: Vec<Result<HillFloquet, FloquetError>>,
    /// Where a multiplier crosses the unit circle.
    pub bifurcations: Vec<Bifurcation>,
}

impl Branch {
    /// The Floquet multipliers `ρ = e^{σT}` of cycle `i` found by Hill's method (the trivial
    /// one, 1 in exact arithmetic, included), largest modulus first; `None` when its analysis
    /// failed.
    pub fn multipliers(&self, i: usize) -> Option<Vec<c64>> {
        let f = self.floquet.get(i)?.as_ref().ok()?;
        Some(f.exponents.iter().map(|e| e.multiplier).collect())
    }
}

/// A friction system ready for analysis (module documentation).
#[derive(Clone, Debug)]
pub struct FrictionSystem {
    brake: Brake,
    reference: Reference,
    /// The controls of the analyses.
    pub settings: Settings,
}

impl FrictionSystem {
    /// A builder from the mass, damping and stiffness matrices (all `n × n`).
    pub fn builder(m: Mat<f64>, c: Mat<f64>, k: Mat<f64>) -> SystemBuilder {
        SystemBuilder {
            m,
            c,
            k,
            load: None,
            pairs: Vec::new(),
        }
    }

    /// The system as the brake's analyses see it.
    pub fn brake(&self) -> &Brake {
        &self.brake
    }

    /// Its frictionless equilibrium, modes and modal damping.
    pub fn reference(&self) -> &Reference {
        &self.reference
    }

    /// The Hopf point: the first crossing of an eigenvalue into the right half-plane over
    /// [`Settings::friction_range`], refined to [`SweepOptions::mu_tolerance`].
    pub fn hopf(&self) -> Result<Hopf, SystemError> {
        let (from, to) = self.settings.friction_range;
        let n = self.settings.sweep_points.max(2);
        let mus: Vec<f64> = (0..n)
            .map(|k| from + (to - from) * k as f64 / (n - 1) as f64)
            .collect();
        sweep(&self.brake, &self.reference, &mus, &self.settings.sweep)?
            .hopf
            .ok_or(SystemError::NoHopf { from, to })
    }

    /// The limit cycle at friction `mu` by CHBM, from the most unstable mode there (eq 48);
    /// its [`ChbmSolution::outcome`] says whether both of eqs (46)–(47) were met.
    pub fn limit_cycle(&self, mu: f64) -> Result<ChbmSolution, SystemError> {
        let s = &self.settings;
        let start = start_at(
            &self.brake,
            &self.reference,
            mu,
            &s.sweep.band,
            &s.sweep.newton,
            None,
        )?;
        let mb = ModalBrake::new(&self.brake, &self.reference, mu);
        Ok(solve_with_restarts(&mb, &start, &s.chbm, &s.restart_amplitudes)?.0)
    }

    /// The complex nonlinear mode of the squeal mode (the most unstable one) at friction `mu`
    /// by the extended periodic motion concept: frequency, modal damping and harmonics against
    /// the modal amplitude, and the limit cycles where the damping vanishes
    /// ([`crate::nlmode`]).
    pub fn nonlinear_mode(
        &self,
        mu: f64,
        options: &NlModeOptions,
    ) -> Result<NonlinearMode, SystemError> {
        let s = &self.settings;
        let start = start_at(
            &self.brake,
            &self.reference,
            mu,
            &s.sweep.band,
            &s.sweep.newton,
            None,
        )?;
        let mb = ModalBrake::new(&self.brake, &self.reference, mu);
        Ok(nonlinear_mode(&mb, &start, options)?)
    }

    /// The Hopf normal form at the Hopf point ([`squeal_brake::criticality`]).
    pub fn normal_form(&self) -> Result<NormalForm, SystemError> {
        let h = self.hopf()?;
        let guess = h.point.spectrum.values[h.index];
        Ok(normal_form(
            &self.brake,
            &self.reference,
            h.mu0,
            guess,
            &self.settings.sweep.newton,
        )?)
    }

    /// The branch of limit cycles born at the Hopf point, each cycle with its Floquet
    /// multipliers, and the bifurcations along it.
    pub fn branch(&self) -> Result<Branch, SystemError> {
        let nf = self.normal_form()?;
        let mb = ModalBrake::new(&self.brake, &self.reference, nf.mu0);
        let s = &self.settings;
        let b = follow_from_hopf_with_hill(&mb, &nf, &s.branch, &s.hill)?;
        Ok(Branch {
            bifurcations: bifurcations(&b.branch, &b.floquet),
            normal_form: nf,
            branch: b.branch,
            floquet: b.floquet,
        })
    }
}
