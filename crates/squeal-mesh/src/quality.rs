//! Quality checks (being written).
