//! MatrixMarket files (NIST format): `coordinate real general|symmetric` for sparse matrices,
//! `array real general` for dense ones. 1-based indices, as the format requires.

use crate::{IoError, atomic_write};
use std::path::Path;

/// Symmetry written in the header of a coordinate file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Symmetry {
    /// Every stored entry is written.
    General,
    /// Only entries with `row >= col` are written; readers mirror them.
    Symmetric,
}

/// A sparse matrix in compressed-column form: column `c` holds rows
/// `row_idx[col_ptr[c]..col_ptr[c + 1]]` with the matching `values`.
#[derive(Clone, Copy, Debug)]
pub struct CscRef<'a> {
    pub nrows: usize,
    pub ncols: usize,
    pub col_ptr: &'a [usize],
    pub row_idx: &'a [usize],
    pub values: &'a [f64],
}

/// Writes a sparse matrix. With [`Symmetry::Symmetric`] only the lower triangle is written.
pub fn write_csc(path: &Path, a: CscRef, symmetry: Symmetry, comment: &str) -> Result<(), IoError> {
    let CscRef {
        nrows,
        ncols,
        col_ptr,
        row_idx,
        values,
    } = a;
    let keep = |r: usize, c: usize| symmetry == Symmetry::General || r >= c;
    let nnz = (0..ncols)
        .map(|c| {
            row_idx[col_ptr[c]..col_ptr[c + 1]]
                .iter()
                .filter(|&&r| keep(r, c))
                .count()
        })
        .sum::<usize>();
    let sym = match symmetry {
        Symmetry::General => "general",
        Symmetry::Symmetric => "symmetric",
    };
    atomic_write(path, |w| {
        writeln!(w, "%%MatrixMarket matrix coordinate real {sym}")?;
        for line in comment.lines() {
            writeln!(w, "% {line}")?;
        }
        writeln!(w, "{nrows} {ncols} {nnz}")?;
        for c in 0..ncols {
            for k in col_ptr[c]..col_ptr[c + 1] {
                let r = row_idx[k];
                if keep(r, c) {
                    writeln!(w, "{} {} {:e}", r + 1, c + 1, values[k])?;
                }
            }
        }
        Ok(())
    })
}

/// Writes a dense matrix stored column-major (`values[r + c * nrows]`).
pub fn write_dense(
    path: &Path,
    nrows: usize,
    ncols: usize,
    values: &[f64],
    comment: &str,
) -> Result<(), IoError> {
    atomic_write(path, |w| {
        writeln!(w, "%%MatrixMarket matrix array real general")?;
        for line in comment.lines() {
            writeln!(w, "% {line}")?;
        }
        writeln!(w, "{nrows} {ncols}")?;
        for v in values.iter().take(nrows * ncols) {
            writeln!(w, "{v:e}")?;
        }
        Ok(())
    })
}

/// A matrix read back from a MatrixMarket file, as triplets (0-based).
#[derive(Clone, Debug, PartialEq)]
pub struct Triplets {
    pub nrows: usize,
    pub ncols: usize,
    /// `(row, col, value)`; symmetric files are expanded to both triangles.
    pub entries: Vec<(usize, usize, f64)>,
}

/// Reads a `coordinate real` or `array real` MatrixMarket file.
pub fn read(path: &Path) -> Result<Triplets, IoError> {
    let text = std::fs::read_to_string(path).map_err(|error| IoError::Read {
        path: path.to_path_buf(),
        error,
    })?;
    let perr = |line: usize, message: String| IoError::Parse {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut lines = text.lines().enumerate();
    let (_, header) = lines.next().ok_or_else(|| perr(1, "empty file".into()))?;
    let h: Vec<String> = header
        .split_whitespace()
        .map(str::to_ascii_lowercase)
        .collect();
    if h.len() != 5 || h[0] != "%%matrixmarket" || h[1] != "matrix" || h[3] != "real" {
        return Err(perr(
            1,
            format!("expected '%%MatrixMarket matrix coordinate|array real ...', found '{header}'"),
        ));
    }
    let coordinate = match h[2].as_str() {
        "coordinate" => true,
        "array" => false,
        other => return Err(perr(1, format!("unknown storage '{other}'"))),
    };
    let symmetric = match h[4].as_str() {
        "general" => false,
        "symmetric" => true,
        other => return Err(perr(1, format!("unsupported symmetry '{other}'"))),
    };
    let mut data = lines.filter(|(_, l)| !l.trim_start().starts_with('%') && !l.trim().is_empty());
    let (sline, size) = data
        .next()
        .ok_or_else(|| perr(2, "missing size line".into()))?;
    let nums: Vec<usize> = size
        .split_whitespace()
        .map(|t| {
            t.parse::<usize>()
                .map_err(|_| perr(sline + 1, format!("bad size '{t}'")))
        })
        .collect::<Result<_, _>>()?;
    let mut out = Triplets {
        nrows: 0,
        ncols: 0,
        entries: Vec::new(),
    };
    if coordinate {
        let [nrows, ncols, _nnz] = nums[..] else {
            return Err(perr(sline + 1, "expected 'rows cols nnz'".into()));
        };
        out.nrows = nrows;
        out.ncols = ncols;
        for (i, l) in data {
            let t: Vec<&str> = l.split_whitespace().collect();
            let bad = || perr(i + 1, format!("expected 'row col value', found '{l}'"));
            if t.len() != 3 {
                return Err(bad());
            }
            let r: usize = t[0].parse().map_err(|_| bad())?;
            let c: usize = t[1].parse().map_err(|_| bad())?;
            let v: f64 = t[2].parse().map_err(|_| bad())?;
            if r == 0 || c == 0 || r > nrows || c > ncols {
                return Err(perr(
                    i + 1,
                    format!("index ({r}, {c}) outside {nrows} x {ncols}"),
                ));
            }
            out.entries.push((r - 1, c - 1, v));
            if symmetric && r != c {
                out.entries.push((c - 1, r - 1, v));
            }
        }
    } else {
        let [nrows, ncols] = nums[..] else {
            return Err(perr(sline + 1, "expected 'rows cols'".into()));
        };
        out.nrows = nrows;
        out.ncols = ncols;
        for (k, (i, l)) in data.enumerate() {
            let v: f64 = l
                .trim()
                .parse()
                .map_err(|_| perr(i + 1, format!("bad number '{l}'")))?;
            if nrows == 0 || k >= nrows * ncols {
                return Err(perr(i + 1, "more values than rows x cols".into()));
            }
            out.entries.push((k % nrows, k / nrows, v));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symmetric_round_trip() {
        // [[2, -1], [-1, 3]] in CSC, both triangles stored.
        let dir = std::env::temp_dir().join(format!("squeal-mtx-{}", std::process::id()));
        let path = dir.join("k.mtx");
        let a = CscRef {
            nrows: 2,
            ncols: 2,
            col_ptr: &[0, 2, 4],
            row_idx: &[0, 1, 0, 1],
            values: &[2.0, -1.0, -1.0, 3.0],
        };
        write_csc(&path, a, Symmetry::Symmetric, "test").unwrap();
        let t = read(&path).unwrap();
        let mut e = t.entries.clone();
        e.sort_by_key(|a| (a.0, a.1));
        assert_eq!(
            e,
            vec![(0, 0, 2.0), (0, 1, -1.0), (1, 0, -1.0), (1, 1, 3.0)]
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
