pub mod branch;
pub mod chbm;
pub mod compare;
pub mod fe;
pub mod mesh;
pub mod mesh_scene;
pub mod mic;
pub mod nlmode;
pub mod reduce;
pub mod run;
pub mod stability;
pub mod study;

/// `--force`: write into an output folder holding files no squeal run wrote.
pub static FORCE: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
