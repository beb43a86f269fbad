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
    /// The file given to a reader could not be read from disk (a missing or unreadable
    /// `*INCLUDE` is [`MeshError::Invalid`] instead, at the including line).
    #[error("cannot read {}: {error}", file.display())]
    Io {
        /// The file that could not be read.
        file: PathBuf,
        /// The operating system's error.
        error: std::io::Error,
    },
    /// The file's content is not a mesh the reader accepts: truncated or malformed records,
    /// bad numbers, duplicate ids, unsupported versions or parameters, ...
    #[error("{}{location}: {message}", file.display())]
    Invalid {
        /// The file at fault (for `.inp`, the included file when the fault is in one).
        file: PathBuf,
        /// Where in that file.
        location: Location,
        /// What was expected and what was found.
        message: String,
    },
    /// [`crate::read`] was given a file whose extension is none of `.inp`, `.msh`, `.bdf`,
    /// `.nas`, `.dat`, `.cdb` (ASCII case-insensitive).
    #[error("{}: unknown mesh format (expected a .inp, .msh, .bdf, .nas, .dat or .cdb file)", file.display())]
    UnknownFormat {
        /// The file that was given.
        file: PathBuf,
    },
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
    /// The file it concerns (for `.inp`, the included file when it is in one).
    pub file: PathBuf,
    /// Where in that file.
    pub location: Location,
    /// What was skipped or doubted, and why.
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
