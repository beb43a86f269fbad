//! Read-time benchmark of the .msh reader (being written).
fn main() {}
