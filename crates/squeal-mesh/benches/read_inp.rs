//! Read-time benchmark of the .inp reader (being written).
fn main() {}
