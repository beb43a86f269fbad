#![no_main]
// Placeholder: the msh reader's fuzz target is being written.
use libfuzzer_sys::fuzz_target;
fuzz_target!(|_data: &[u8]| {});
