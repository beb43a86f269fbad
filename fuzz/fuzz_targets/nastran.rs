#![no_main]
//! Fuzzes the Nastran bulk data parser from memory: any bytes must give a mesh or an error,
//! never a panic, a hang or an unbounded allocation. Includes resolve to "not found".
//!
//! One property is checked beyond that: a text whose last line has content (other than a `$`
//! comment) and no line break was cut off, and must not read.
use libfuzzer_sys::fuzz_target;
use squeal_mesh::inp::NoIncludes;
use squeal_mesh::nastran::parse;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    match parse(data, Path::new("fuzz.bdf"), &NoIncludes) {
        Err(e) => {
            let _ = e.to_string();
        }
        Ok(r) => {
            for w in &r.warnings {
                let _ = w.to_string();
            }
            let last = data.rsplit(|&b| b == b'\n').next().unwrap_or(&[]);
            let last = String::from_utf8_lossy(last);
            let last = last.trim();
            assert!(
                last.is_empty() || last.starts_with('$'),
                "a text ending inside the line {last:?} was read"
            );
        }
    }
});
