//! VTU output (being written).
