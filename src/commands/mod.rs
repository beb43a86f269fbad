pub mod chbm;
pub mod compare;
pub mod mesh;
pub mod reduce;
pub mod stability;
pub mod study;
