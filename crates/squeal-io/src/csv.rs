//! Minimal CSV output: a header and rows of numbers, written atomically.

use crate::{IoError, atomic_write};
use std::path::Path;

/// Writes a CSV table with a header line and one row per entry of `rows`.
/// Numbers are written with Rust's shortest round-trip formatting, so they read back bit-exact.
pub fn write_csv(path: &Path, header: &[&str], rows: &[Vec<f64>]) -> Result<(), IoError> {
    atomic_write(path, |w| {
        writeln!(w, "{}", header.join(","))?;
        for row in rows {
            let mut first = true;
            for v in row {
                if !first {
                    write!(w, ",")?;
                }
                first = false;
                write!(w, "{v:e}")?;
            }
            writeln!(w)?;
        }
        Ok(())
    })
}
