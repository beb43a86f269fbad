pub mod chbm;
pub mod compare;
pub mod fe;
pub mod mesh;
pub mod reduce;
pub mod run;
pub mod stability;
pub mod study;
