#![no_main]
//! Fuzzes the Ansys .cdb parser from memory: any bytes must give a mesh or an error, never a
//! panic, a hang or an unbounded allocation; a text cut inside its last line must not read.
use libfuzzer_sys::fuzz_target;
use squeal_mesh::cdb::parse;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    match parse(data, Path::new("fuzz.cdb")) {
        Err(e) => {
            let _ = e.to_string();
        }
        Ok(r) => {
            for w in &r.warnings {
                let _ = w.to_string();
            }
            let last = data.rsplit(|&b| b == b'\n').next().unwrap_or(&[]);
            assert!(
                String::from_utf8_lossy(last).trim().is_empty(),
                "a text ending inside its last line was read"
            );
        }
    }
});
