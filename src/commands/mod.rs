pub mod mesh;
pub mod reduce;
