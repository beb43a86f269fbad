//! The file's arrays: matrices and raw bytes written row by row with their CRC-32 (read back by [`super::read`]; docs/rom-format.md).

use super::*;

/// An array of the file: a matrix (written row by row, little-endian) or raw bytes.
pub(super) enum Array<'a> {
    Mat(&'a Mat<f64>),
    U64(Vec<u8>),
    U8(&'a [u8]),
}

impl Array<'_> {
    pub(super) fn dtype(&self) -> Dtype {
        match self {
            Array::Mat(_) => Dtype::F64,
            Array::U64(_) => Dtype::U64,
            Array::U8(_) => Dtype::U8,
        }
    }

    pub(super) fn shape(&self) -> Vec<usize> {
        match self {
            Array::Mat(m) => vec![m.nrows(), m.ncols()],
            Array::U64(b) => vec![b.len() / 8],
            Array::U8(b) => vec![b.len()],
        }
    }

    /// Bytes in the file.
    pub(super) fn len(&self) -> usize {
        match self {
            Array::Mat(m) => m.nrows() * m.ncols() * 8,
            Array::U64(b) => b.len(),
            Array::U8(b) => b.len(),
        }
    }

    /// Writes the bytes; a matrix [`ROWS_PER_WRITE`] rows at a time.
    pub(super) fn write(&self, w: &mut dyn Write) -> std::io::Result<()> {
        let m = match self {
            Array::Mat(m) => m,
            Array::U64(b) => return w.write_all(b),
            Array::U8(b) => return w.write_all(b),
        };
        // Row-major bytes from the column-major matrix, [`TILE_ROWS`] rows at a time: each
        // column's piece of those rows is read contiguously and its values written to the
        // tile's rows. A row at a time (`m[(i, j)]` for every `j`) jumped a column's length per
        // value: 18 % of the samples while the fine corner's system basis ran beside the write
        // (docs/benchmarks.md, "The fine corner on main, where its time goes").
        let ncols = m.ncols();
        let mut buf = vec![0u8; ROWS_PER_WRITE.min(m.nrows()) * ncols * 8];
        for first in (0..m.nrows()).step_by(ROWS_PER_WRITE) {
            let rows = ROWS_PER_WRITE.min(m.nrows() - first);
            for t0 in (0..rows).step_by(TILE_ROWS) {
                let t1 = (t0 + TILE_ROWS).min(rows);
                for j in 0..ncols {
                    let col = &m.col_as_slice(j)[first + t0..first + t1];
                    for (i, v) in (t0..t1).zip(col) {
                        let at = (i * ncols + j) * 8;
                        buf[at..at + 8].copy_from_slice(&v.to_le_bytes());
                    }
                }
            }
            w.write_all(&buf[..rows * ncols * 8])?;
        }
        Ok(())
    }
}

/// The position of a matrix's first value that is not finite (NaN or infinite), column by
/// column.
pub(super) fn first_non_finite(a: &Mat<f64>) -> Option<(usize, usize)> {
    (0..a.ncols())
        .flat_map(|j| (0..a.nrows()).map(move |i| (i, j)))
        .find(|&(i, j)| !a[(i, j)].is_finite())
}

/// Feeds what is written to a CRC-32.
pub(super) struct CrcWriter(pub(super) crc32fast::Hasher);

impl Write for CrcWriter {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.update(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Rows of a matrix transposed together by [`Array::write`] (their values of one column: four
/// cache lines read, 32 rows of the output written).
const TILE_ROWS: usize = 32;

/// Rows of a matrix converted per write by [`Array::write`].
pub(super) const ROWS_PER_WRITE: usize = 4096;

/// The file: its header, then the arrays in order.
pub(super) fn write_file(
    w: &mut dyn Write,
    header: &[u8],
    arrays: &[Named],
) -> std::io::Result<()> {
    w.write_all(header)?;
    arrays.iter().try_for_each(|(_, a)| a.write(w))
}

/// SHA-256 of a file, as lowercase hex, read a megabyte at a time (a mesh or a model of
/// gigabytes is never held whole).
pub fn sha256_file(path: &Path) -> Result<String, RomError> {
    use sha2::{Digest, Sha256};
    use std::io::Read;
    let io = |error| RomError::Io {
        path: path.to_path_buf(),
        error,
    };
    let mut file = std::fs::File::open(path).map_err(io)?;
    let mut hasher = Sha256::new();
    let mut buf = vec![0u8; 1 << 20];
    loop {
        match file.read(&mut buf) {
            Ok(0) => break,
            Ok(k) => hasher.update(&buf[..k]),
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(io(e)),
        }
    }
    let digest = hasher.finalize();
    Ok(digest.iter().map(|b| format!("{b:02x}")).collect())
}

/// A tensor's shape as `(a, b, …)`.
pub(super) fn shape_text(shape: &[usize]) -> String {
    let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    format!("({})", dims.join(", "))
}
