#![no_main]
//! Fuzzes the scene-file reader from memory: any bytes must give a scene or an error, never
//! a panic, a hang or an unbounded allocation; every accessor a command calls on a scene that
//! read (friction values, contact stiffness, the damped pair, the rotation, the normal and the
//! sliding) must also give a value or an error.
use libfuzzer_sys::fuzz_target;
use squeal_scene::Scene;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data).into_owned();
    match Scene::parse(Path::new("fuzz.toml"), text) {
        // Formatting the error must not panic either.
        Err(e) => {
            let _ = e.to_string();
        }
        Ok(scene) => {
            let _ = scene.mu_values().map_err(|e| e.to_string());
            let _ = scene.stiffness().map_err(|e| e.to_string());
            let _ = scene.pair().map_err(|e| e.to_string());
            let _ = scene.rotation().map_err(|e| e.to_string());
            let _ = scene.normal().map_err(|e| e.to_string());
            let _ = scene.sliding().map_err(|e| e.to_string());
            let _ = scene.disc_angular_speed().map_err(|e| e.to_string());
        }
    }
});
