#![no_main]
//! Fuzzes the .inp parser from memory: any bytes must give a mesh or an error, never a
//! panic, a hang or an unbounded allocation. Includes resolve to "not found".
use libfuzzer_sys::fuzz_target;
use squeal_mesh::inp::{NoIncludes, parse};
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    if let Err(e) = parse(data, Path::new("fuzz.inp"), &NoIncludes) {
        // Formatting the error must not panic either.
        let _ = e.to_string();
    }
});
