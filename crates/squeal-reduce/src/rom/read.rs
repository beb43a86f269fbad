//! Reading a `.rom` back: its header, then its arrays streamed in file order straight into
//! their matrices, the checksum taken on the way.
//!
//! The file is never held whole in memory. Reading it whole and then converting each array
//! needed the file's size twice: the fine corner's 5.9 GB model peaked near 12 GB when read
//! back (docs/benchmarks.md). Now the arrays are read [`CHUNK_BYTES`] at a time, so reading
//! costs the model's own size plus one chunk. A file and its bytes in memory
//! ([`ReducedModel::from_bytes`], the fuzz target's and tests' entry) go through the same
//! parser.

use super::*;
use std::io::{BufReader, ErrorKind, Read};

/// Bytes read from the file per step while its arrays are converted.
const CHUNK_BYTES: usize = 4 << 20;

impl ReducedModel {
    /// Reads a model written by [`ReducedModel::write`], streaming its arrays from the file.
    pub fn read(path: &Path) -> Result<Self, RomError> {
        let io = |error| RomError::Io {
            path: path.to_path_buf(),
            error,
        };
        let file = std::fs::File::open(path).map_err(io)?;
        let len = file.metadata().map_err(io)?.len();
        parse(BufReader::with_capacity(CHUNK_BYTES, file), len, path)
    }

    /// Parses a model from bytes; `path` only names the source in errors.
    pub fn from_bytes(bytes: &[u8], path: &Path) -> Result<Self, RomError> {
        parse(bytes, bytes.len() as u64, path)
    }
}

/// Reads only the JSON header of a reduced-model file (not its arrays). The header's layout
/// is checked as [`ReducedModel::read`] checks it, with the file's length: a file cut short
/// (a copy or download that stopped) has a complete header and is caught here, not when its
/// arrays are read.
pub fn read_header(path: &Path) -> Result<RomHeader, RomError> {
    let io = |error| RomError::Io {
        path: path.to_path_buf(),
        error,
    };
    let mut file = std::fs::File::open(path).map_err(io)?;
    let len = file.metadata().map_err(io)?.len();
    let metadata = read_metadata(&mut file, len, path)?;
    parse_header(squeal_json(&metadata, path)?, path)
}

/// An array as read: a matrix, or the raw bytes of any other array.
enum Loaded {
    Mat(Mat<f64>),
    Raw {
        dtype: Dtype,
        shape: Vec<usize>,
        data: Vec<u8>,
    },
}

/// The whole model from a reader positioned at the file's start; `len` is the file's length.
fn parse(mut r: impl Read, len: u64, path: &Path) -> Result<ReducedModel, RomError> {
    let bad = |message: String| RomError::Format {
        path: path.to_path_buf(),
        message,
    };
    let metadata = read_metadata(&mut r, len, path)?;
    let header = parse_header(squeal_json(&metadata, path)?, path)?;
    let mut crc = crc32fast::Hasher::new();
    let mut arrays = HashMap::new();
    for name in metadata.offset_keys() {
        let info = metadata
            .info(&name)
            .ok_or_else(|| bad(format!("array {name} has no entry")))?;
        let loaded = load(&mut r, info, &mut crc).map_err(|error| match error.kind() {
            ErrorKind::UnexpectedEof => bad(format!("the file ended inside array {name}")),
            _ => RomError::Io {
                path: path.to_path_buf(),
                error,
            },
        })?;
        arrays.insert(name, loaded);
    }
    if let Some(recorded) = &header.arrays_crc32 {
        let found = format!("{:08x}", crc.finalize());
        if !found.eq_ignore_ascii_case(recorded) {
            return Err(RomError::Damaged {
                path: path.to_path_buf(),
                message: format!("the arrays' CRC-32 is {found}, the file records {recorded}"),
            });
        }
    }
    let mut parts = Vec::with_capacity(header.parts.len());
    for info in header.parts {
        parts.push(part(&mut arrays, info, path)?);
    }
    Ok(ReducedModel {
        tool_version: header.tool_version,
        parts,
        connections: header.connections,
        ties: header.ties,
    })
}

/// One part from the arrays read, its matrices checked for shape and finite values.
fn part(
    arrays: &mut HashMap<String, Loaded>,
    info: PartInfo,
    path: &Path,
) -> Result<ReducedPart, RomError> {
    let bad = |message: String| RomError::Format {
        path: path.to_path_buf(),
        message,
    };
    let n = info.dofs.len();
    let name = info.name.clone();
    let k = take_mat(arrays, &format!("{name}.K"), (n, n)).map_err(bad)?;
    let m = take_mat(arrays, &format!("{name}.M"), (n, n)).map_err(bad)?;
    let basis = if arrays.contains_key(&format!("{name}.basis")) {
        let values =
            take_mat(arrays, &format!("{name}.basis"), (info.full_dofs, n)).map_err(bad)?;
        let dof_node = take_vec(
            arrays,
            &format!("{name}.dof_node"),
            Dtype::U64,
            info.full_dofs,
        )
        .map_err(bad)?
        .chunks_exact(8)
        .map(|c| u64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
        .collect();
        let dof_dir = take_vec(
            arrays,
            &format!("{name}.dof_dir"),
            Dtype::U8,
            info.full_dofs,
        )
        .map_err(bad)?;
        Some(Basis {
            dof_node,
            dof_dir,
            values,
        })
    } else {
        None
    };
    for (what, a) in [("K", &k), ("M", &m)]
        .into_iter()
        .chain(basis.as_ref().map(|b| ("basis", &b.values)))
    {
        if let Some((i, j)) = first_non_finite(a) {
            return Err(RomError::Damaged {
                path: path.to_path_buf(),
                message: format!(
                    "array {name}.{what} holds {} at row {}, column {}",
                    a[(i, j)],
                    i + 1,
                    j + 1
                ),
            });
        }
    }
    let info = PartInfo {
        has_basis: basis.is_some(),
        ..info
    };
    Ok(ReducedPart { info, k, m, basis })
}

/// The safetensors table of a file: its length, its JSON, each array's type, shape and byte
/// range, checked to tile the data exactly (safetensors' own checks) and to end where the file
/// does.
fn read_metadata(r: &mut impl Read, len: u64, path: &Path) -> Result<Metadata, RomError> {
    let bad = |message: String| RomError::Format {
        path: path.to_path_buf(),
        message,
    };
    let mut n = [0u8; 8];
    r.read_exact(&mut n)
        .map_err(|e| bad(format!("no header length: {e}")))?;
    let n = u64::from_le_bytes(n);
    if n > MAX_HEADER_BYTES {
        return Err(bad(format!(
            "header of {n} bytes, more than the {MAX_HEADER_BYTES} accepted"
        )));
    }
    if 8 + n > len {
        return Err(bad(format!(
            "header cut short: the file has {len} bytes, its header alone {}",
            8 + n
        )));
    }
    let mut json = vec![0u8; n as usize];
    r.read_exact(&mut json)
        .map_err(|e| bad(format!("header cut short: {e}")))?;
    let metadata: Metadata =
        serde_json::from_slice(&json).map_err(|e| bad(format!("header: {e}")))?;
    let expected = 8 + n + metadata.data_len() as u64;
    if len < expected {
        return Err(bad(format!(
            "the file is cut short: {len} bytes, its header describes {expected}"
        )));
    }
    if len > expected {
        let extra = len - expected;
        let unit = if extra == 1 { "byte" } else { "bytes" };
        return Err(bad(format!(
            "{extra} {unit} follow the arrays its header describes ({expected} bytes)"
        )));
    }
    Ok(metadata)
}

/// The `squeal` entry of the table's `__metadata__`.
fn squeal_json<'a>(metadata: &'a Metadata, path: &Path) -> Result<&'a str, RomError> {
    metadata
        .metadata()
        .as_ref()
        .and_then(|m| m.get("squeal"))
        .map(String::as_str)
        .ok_or_else(|| RomError::Format {
            path: path.to_path_buf(),
            message: "no squeal header in __metadata__".into(),
        })
}

/// Parses and checks the `squeal` header JSON.
fn parse_header(json: &str, path: &Path) -> Result<RomHeader, RomError> {
    let bad = |message: String| RomError::Format {
        path: path.to_path_buf(),
        message,
    };
    let header: RomHeader = serde_json::from_str(json).map_err(|e| bad(format!("header: {e}")))?;
    if header.format != FORMAT {
        return Err(bad(format!("format '{}' is not '{FORMAT}'", header.format)));
    }
    if header.version > VERSION {
        return Err(RomError::Version {
            path: path.to_path_buf(),
            found: header.version,
        });
    }
    Ok(header)
}

/// Reads the next array: a 2-D F64 array into a matrix, [`CHUNK_BYTES`] of its rows at a
/// time (row-major bytes into the column-major matrix), anything else as its bytes.
fn load(
    r: &mut impl Read,
    info: &TensorInfo,
    crc: &mut crc32fast::Hasher,
) -> std::io::Result<Loaded> {
    if info.dtype != Dtype::F64 || info.shape.len() != 2 {
        let mut data = vec![0u8; info.data_offsets.1 - info.data_offsets.0];
        r.read_exact(&mut data)?;
        crc.update(&data);
        return Ok(Loaded::Raw {
            dtype: info.dtype,
            shape: info.shape.clone(),
            data,
        });
    }
    let (rows, cols) = (info.shape[0], info.shape[1]);
    let mut m = Mat::zeros(rows, cols);
    if rows == 0 || cols == 0 {
        return Ok(Loaded::Mat(m));
    }
    let per = (CHUNK_BYTES / (8 * cols)).clamp(1, rows);
    let mut buf = vec![0u8; per * cols * 8];
    for first in (0..rows).step_by(per) {
        let count = per.min(rows - first);
        let bytes = &mut buf[..count * cols * 8];
        r.read_exact(bytes)?;
        crc.update(bytes);
        for j in 0..cols {
            let col = &mut m.col_as_slice_mut(j)[first..first + count];
            for (i, v) in col.iter_mut().enumerate() {
                let at = (i * cols + j) * 8;
                *v = f64::from_le_bytes(bytes[at..at + 8].try_into().unwrap_or([0; 8]));
            }
        }
    }
    Ok(Loaded::Mat(m))
}

/// Takes the matrix `name` of shape `shape` out of the arrays read.
fn take_mat(
    arrays: &mut HashMap<String, Loaded>,
    name: &str,
    shape: (usize, usize),
) -> Result<Mat<f64>, String> {
    match arrays.remove(name) {
        None => Err(format!("array {name} is not in the file")),
        Some(Loaded::Raw {
            dtype, shape: s, ..
        }) => Err(format!(
            "array {name}: expected a 2-D F64 array, found {dtype} of shape {}",
            shape_text(&s)
        )),
        Some(Loaded::Mat(m)) if (m.nrows(), m.ncols()) != shape => Err(format!(
            "array {name}: expected shape ({}, {}), found ({}, {})",
            shape.0,
            shape.1,
            m.nrows(),
            m.ncols()
        )),
        Some(Loaded::Mat(m)) => Ok(m),
    }
}

/// Takes the 1-D array `name` of type `dtype` and length `len` out of the arrays read.
fn take_vec(
    arrays: &mut HashMap<String, Loaded>,
    name: &str,
    dtype: Dtype,
    len: usize,
) -> Result<Vec<u8>, String> {
    let found = |d: Dtype, s: &[usize]| {
        format!(
            "array {name}: expected {dtype} of shape ({len}), found {d} of shape {}",
            shape_text(s)
        )
    };
    match arrays.remove(name) {
        None => Err(format!("array {name} is not in the file")),
        Some(Loaded::Mat(m)) => Err(found(Dtype::F64, &[m.nrows(), m.ncols()])),
        Some(Loaded::Raw {
            dtype: d,
            shape,
            data,
        }) if d == dtype && shape == [len] => Ok(data),
        Some(Loaded::Raw {
            dtype: d, shape, ..
        }) => Err(found(d, &shape)),
    }
}
