#![no_main]
//! Fuzzes the .msh parser from memory: any bytes (ASCII or binary) must give a mesh or an
//! error, never a panic, a hang or an unbounded allocation.
use libfuzzer_sys::fuzz_target;
use squeal_mesh::msh::parse;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    match parse(data, Path::new("fuzz.msh")) {
        // Formatting errors and warnings must not panic either.
        Err(e) => {
            let _ = e.to_string();
        }
        Ok(r) => {
            for w in &r.warnings {
                let _ = w.to_string();
            }
        }
    }
});
