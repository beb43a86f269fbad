//! The squeal pipeline as a library a researcher can call: scene → reduced model → brake →
//! stability → start → CHBM → comparison, each stage computed once and passed in memory
//! ([`Pipeline`]), and the files each stage writes (tables, figures, shapes for ParaView).
//!
//! ```no_run
//! use squeal_pipeline::{Pipeline, model::quiet};
//! use squeal_scene::Scene;
//! let scene = Scene::read("meshes/brake.toml".as_ref())?;
//! let p = Pipeline::new(scene, "out/brake".into(), &quiet)?;
//! let mu0 = p.mu0()?;                                  // reduction (cached), sweep, Hopf point
//! let (start, modal) = p.chbm_start(1.02 * mu0)?;      // the unstable mode there, no new sweep
//! let sol = squeal_chbm::solve(&modal, &start, &Default::default())?;
//! println!("{} at {:.2} Hz", sol.outcome, sol.omega / std::f64::consts::TAU);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! - [`model`]: the scene's reduced model (cached in a `.rom`) and brake.
//! - [`parts`]: the scene's meshes in SI with their sets chosen by name or geometry and
//!   their materials.
//! - [`stability`], [`branch`], [`chbm`], [`compare`], [`study`]: the analyses and their
//!   outputs.
//! - [`shapes`]: reduced vectors expanded onto the meshes (VTU); [`pictures`]: the same as
//!   images for the report.
//! - [`sound`]: how loud a limit cycle is (ERP, dB(A) at a microphone).
//! - [`report`]: the report of a run.

// Index loops over dofs read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

pub mod branch;
pub mod branch_dlft;
pub mod branch_stick;
pub mod branch_torus;
pub mod branch_two_mode;
pub mod caveats;
pub mod chbm;
pub mod compare;
pub mod cycle;
pub mod cycle_stick;
pub mod cycle_walk;
pub mod dampers;
mod error;
pub mod fe_export;
pub mod folder;
pub mod full;
pub mod interface;
pub mod interface_check;
pub mod interface_system;
pub mod mesh_info;
pub mod model;
pub mod nlmode;
pub mod parts;
pub mod pictures;
pub mod progress;
pub mod reduce;
pub mod report;
pub mod restraints;
pub mod scene_sets;
pub mod shapes;
pub mod sound;
mod sound_quads;
pub mod stability;
pub mod stages;
pub mod study;
pub mod two_mode;

pub use error::{PipelineError, Result};

use model::{Log, Model};
use progress::{Progress, Silent};
use squeal_brake::analysis::LinearStability as Stability;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::ChbmStart;
use squeal_scene::Scene;
use std::cell::{OnceCell, RefCell};
use std::path::PathBuf;
use std::time::Instant;

/// A scene's analyses, each computed once on first use and kept.
pub struct Pipeline<'a> {
    pub scene: Scene,
    /// The output folder.
    pub out: PathBuf,
    /// The friction values of the stability sweep.
    pub mus: Vec<f64>,
    log: Log<'a>,
    progress: &'a dyn Progress,
    model: OnceCell<Model>,
    stability: OnceCell<Stability>,
    timings: RefCell<Vec<(String, f64)>>,
    /// How the limit cycles' sound is estimated: the air and the microphones of the scene's
    /// `[sound]` (none: the default one, [`sound::default_microphone`]).
    pub sound: sound::SoundOptions,
}

impl<'a> Pipeline<'a> {
    /// The pipeline of `scene` writing into `out`, sweeping the scene's friction values;
    /// `log` is told what happens.
    ///
    /// The outputs are checked first: `out` must be a folder that can be written, and the
    /// reduced model's file must end in `.rom` and be neither the scene nor a mesh.
    pub fn new(scene: Scene, out: PathBuf, log: Log<'a>) -> Result<Self> {
        let mus = scene.mu_values()?;
        model::check_outputs(&scene, &out)?;
        let sound = sound::SoundOptions::of_scene(&scene)?;
        Ok(Self {
            scene,
            out,
            mus,
            log,
            progress: &Silent,
            model: OnceCell::new(),
            stability: OnceCell::new(),
            timings: RefCell::new(Vec::new()),
            sound,
        })
    }

    /// The same pipeline sweeping `mus` instead (checked: finite and ascending).
    pub fn with_mus(mut self, mus: Vec<f64>) -> Result<Self> {
        squeal_brake::sweep::check_ascending(&mus)?;
        self.mus = mus;
        Ok(self)
    }

    /// The same pipeline telling `progress` about its long steps.
    pub fn with_progress(mut self, progress: &'a dyn Progress) -> Self {
        self.progress = progress;
        self
    }

    /// The log this pipeline reports to.
    pub fn log(&self) -> Log<'a> {
        self.log
    }

    /// Where this pipeline tells its progress.
    pub fn progress(&self) -> &'a dyn Progress {
        self.progress
    }

    /// Wall time of each stage computed so far (s).
    pub fn timings(&self) -> Vec<(String, f64)> {
        self.timings.borrow().clone()
    }

    /// Records a stage's wall time.
    pub fn record(&self, stage: &str, seconds: f64) {
        self.timings.borrow_mut().push((stage.to_string(), seconds));
    }

    fn timed<T>(&self, stage: &str, f: impl FnOnce() -> Result<T>) -> Result<T> {
        let t = Instant::now();
        let v = f()?;
        self.record(stage, t.elapsed().as_secs_f64());
        Ok(v)
    }

    /// The reduced model (reduced, or read from its cache) and the brake.
    pub fn model(&self) -> Result<&Model> {
        if let Some(m) = self.model.get() {
            return Ok(m);
        }
        let m = self.timed("reduced model and brake", || {
            model::build(&self.scene, &self.out, self.log)
        })?;
        // The scene's own microphones, checked against the brake as `--mic` is.
        let scene_mics = self.scene.sound()?.microphones;
        sound::check_microphones(&self.scene, &m, &scene_mics, self.log).map_err(|e| {
            let message = match e {
                PipelineError::Input { message, .. } => message,
                other => other.to_string(),
            };
            PipelineError::from(
                self.scene
                    .error_at_key(squeal_scene::Key::Microphones, message),
            )
        })?;
        Ok(self.model.get_or_init(|| m))
    }

    /// The stability analysis: damping, friction sweep, Hopf point (one sweep per pipeline).
    pub fn stability(&self) -> Result<&Stability> {
        if let Some(s) = self.stability.get() {
            return Ok(s);
        }
        let m = self.model()?;
        let st = self
            .timed("stability sweep", || {
                stability::analyse_with(m, &self.mus, self.progress)
            })
            .map_err(|e| model::at_damping_key(&self.scene, e))?;
        Ok(self.stability.get_or_init(|| st))
    }

    /// The Hopf point μ0, or an error saying there is none in the band.
    pub fn mu0(&self) -> Result<f64> {
        let st = self.stability()?;
        st.sweep
            .hopf
            .as_ref()
            .map(|h| h.mu0)
            .ok_or(PipelineError::NoHopfPoint {
                from: self.mus[0],
                to: self.mus[self.mus.len() - 1],
                what: "a limit cycle",
            })
    }

    /// Where CHBM (or a time integration) starts at μ: the equilibrium, the in-band unstable
    /// mode of largest growth, and the brake in modal coordinates, on the stability analysis'
    /// frictionless reference (no new sweep).
    pub fn chbm_start(&self, mu: f64) -> Result<(ChbmStart, ModalBrake)> {
        let m = self.model()?;
        let st = self.stability()?;
        chbm::start(m, st, mu, None)
    }
}
