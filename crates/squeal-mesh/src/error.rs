//! Errors and warnings of the mesh readers: each names the file and where in it.

use std::fmt;
use std::path::PathBuf;

/// Where in a file something was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// 1-based line number of a text file.
    Line(usize),
    /// 0-based byte offset in a binary file (or a binary section of one).
    Byte(u64),
    /// The file as a whole (for example, a section that is missing).
    File,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Line(l) => write!(f, ":{l}"),
            Location::Byte(b) => write!(f, ": byte {b}"),
            Location::File => Ok(()),
        }
    }
}

/// A reader's error: the file, the place, and what was expected.
///
/// Each message is complete in `Display`; no variant has a `source()`, so an error chain
/// printed with `{:#}` (anyhow) shows every piece once.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    #[error("cannot read {}: {error}", file.display())]
    Io {
        file: PathBuf,
        error: std::io::Error,
    },
    #[error("{}{location}: {message}", file.display())]
    Invalid {
        file: PathBuf,
        location: Location,
        message: String,
    },
    #[error("{}: unknown mesh format (expected a .inp or .msh file)", file.display())]
    UnknownFormat { file: PathBuf },
}

impl MeshError {
    /// Shorthand for [`MeshError::Invalid`].
    pub fn invalid(
        file: impl Into<PathBuf>,
        location: Location,
        message: impl Into<String>,
    ) -> Self {
        MeshError::Invalid {
            file: file.into(),
            location,
            message: message.into(),
        }
    }
}

/// Something a reader skipped or doubted, without failing.
#[derive(Clone, Debug, PartialEq)]
pub struct Warning {
    pub file: PathBuf,
    pub location: Location,
    pub message: String,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}{}: {}",
            self.file.display(),
            self.location,
            self.message
        )
    }
}
