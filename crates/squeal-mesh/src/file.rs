//! Reading a mesh file's bytes with limits: only a regular file (a device such as `/dev/zero`
//! or a FIFO is an endless stream, and a folder is no file), and at most [`MAX_FILE_BYTES`]
//! (a larger file is almost surely not a mesh of one brake part, and would be read whole into
//! memory before any check).

use crate::MeshError;
use std::io::{Error, ErrorKind, Read};
use std::path::Path;

/// The largest mesh file read (4 GiB): a tet10 mesh of some 20 million nodes in `.inp` text;
/// the fine meshes of this project are under 100 MB.
pub const MAX_FILE_BYTES: u64 = 4 << 30;

fn too_large(n: u64) -> Error {
    Error::new(
        ErrorKind::InvalidInput,
        format!(
            "{n} bytes or more, above the {} GiB a mesh file may have: is this a mesh of one part?",
            MAX_FILE_BYTES >> 30
        ),
    )
}

/// The bytes of the file at `path`, refusing what is not a regular file or is larger than
/// [`MAX_FILE_BYTES`] (also a file that grows past it while read); the reason is the error's
/// text.
pub fn read_limited(path: &Path) -> std::io::Result<Vec<u8>> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            "not a regular file (a folder, a device or a pipe is no input file): give the path of a file",
        ));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(too_large(meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    std::fs::File::open(path)?
        .take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// [`read_limited`] with the file named in the error.
pub(crate) fn read_bytes(path: &Path) -> Result<Vec<u8>, MeshError> {
    read_limited(path).map_err(|error| MeshError::Io {
        file: path.to_path_buf(),
        error,
    })
}
