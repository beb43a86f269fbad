pub mod mesh;
pub mod reduce;
pub mod stability;
