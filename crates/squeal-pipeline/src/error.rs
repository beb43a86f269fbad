//! Errors of the pipeline: those of the stages' crates, and the pipeline's own.

use std::path::PathBuf;

/// What stopped a stage of the pipeline.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    #[error(transparent)]
    Scene(#[from] squeal_scene::SceneError),
    /// A mesh file that could not be read (the reader's error names the file and the place).
    #[error("{error}")]
    Mesh {
        path: PathBuf,
        error: squeal_mesh::MeshError,
    },
    #[error("reducing the brake: {0}")]
    Reduce(#[from] squeal_reduce::ReduceError),
    #[error("the reduced model {}: {error}", path.display())]
    Rom {
        path: PathBuf,
        error: squeal_reduce::rom::RomError,
    },
    #[error(transparent)]
    Brake(#[from] squeal_brake::BrakeError),
    #[error("the full model's eigenvalues: {0}")]
    Eigs(#[from] squeal_eigs::EigError),
    #[error(transparent)]
    Chbm(#[from] squeal_chbm::ChbmError),
    #[error(transparent)]
    Floquet(#[from] squeal_chbm::floquet::FloquetError),
    #[error(transparent)]
    Start(#[from] squeal_chbm::start::StartError),
    #[error(transparent)]
    Compare(#[from] squeal_chbm::compare::CompareError),
    #[error(transparent)]
    Hbm(#[from] squeal_hbm::HbmError),
    #[error(transparent)]
    Io(#[from] squeal_io::IoError),
    #[error(transparent)]
    Output(#[from] squeal_io::OutputError),
    #[error(transparent)]
    Folder(#[from] squeal_io::folder::FolderError),
    #[error("{what} {}: {error}", path.display())]
    File {
        what: &'static str,
        path: PathBuf,
        error: std::io::Error,
    },
    #[error(transparent)]
    Vtu(#[from] squeal_mesh::vtu::VtuError),
    #[error(transparent)]
    Face(#[from] squeal_mesh::select::UnsupportedFace),
    #[error(transparent)]
    Report(#[from] squeal_report::ReportError),
    #[error("writing {what}: {error}")]
    Json {
        what: &'static str,
        error: serde_json::Error,
    },
    #[error(
        "the brake has no Hopf point in the band over mu = {from}..{to}: {what} needs one (widen the friction range or the scene's [stability] band)"
    )]
    NoHopfPoint {
        from: f64,
        to: f64,
        what: &'static str,
    },
    #[error(
        "the reduced model of the {part} was written without its basis: reduce again to expand results onto the mesh"
    )]
    NoBasis { part: String },
    #[error("the reduced model has no {part} part")]
    NoPart { part: &'static str },
    #[error(
        "{part}: node {node} of the reduced model is not in the mesh {}: was the model reduced from another mesh?",
        mesh.display()
    )]
    ForeignNode {
        part: String,
        node: u64,
        mesh: PathBuf,
    },
    #[error("{what}: {message}")]
    Input { what: &'static str, message: String },
    /// An error of a stage, named by what the stage was doing.
    #[error("{stage}: {source}")]
    Stage {
        stage: &'static str,
        #[source]
        source: Box<PipelineError>,
    },
    /// A mesh the analysis refuses: what `squeal mesh info` calls an ERROR, or a set the
    /// reduction uses naming ids the file never defined.
    #[error("{}: {message}", path.display())]
    MeshFindings { path: PathBuf, message: String },
    /// An error with what was being done when it happened (the inner error is a field, not a
    /// `source()`: its text is in this message already, and a `{:#}` chain would repeat it).
    #[error("{context}: {error}")]
    Context {
        context: String,
        error: Box<PipelineError>,
    },
}

/// Adds what was being done to an error.
pub trait Context<T> {
    fn with_context(self, context: impl FnOnce() -> String) -> Result<T>;
}

impl<T, E: Into<PipelineError>> Context<T> for std::result::Result<T, E> {
    fn with_context(self, context: impl FnOnce() -> String) -> Result<T> {
        self.map_err(|e| PipelineError::Context {
            context: context(),
            error: Box::new(e.into()),
        })
    }
}

impl PipelineError {
    /// A bad input value the user gave (an argument or an option).
    /// This error as one of the stage doing `stage` ("stability analysis", ...).
    pub fn in_stage(self, stage: &'static str) -> Self {
        PipelineError::Stage {
            stage,
            source: Box::new(self),
        }
    }

    pub fn input(what: &'static str, message: impl std::fmt::Display) -> Self {
        PipelineError::Input {
            what,
            message: message.to_string(),
        }
    }
}

/// Results of the pipeline.
pub type Result<T> = std::result::Result<T, PipelineError>;

/// `serde_json` pretty text, with the error named.
pub fn json_text(value: &serde_json::Value, what: &'static str) -> Result<String> {
    serde_json::to_string_pretty(value).map_err(|error| PipelineError::Json { what, error })
}
