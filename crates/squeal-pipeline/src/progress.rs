//! Progress of the long steps, for whoever shows it: the command line draws bars, a library
//! caller may count, log or ignore ([`Silent`]).
//!
//! A step (the comparison's time integrations, the Floquet multipliers along a branch, a
//! study's parameter values) begins with its number of items; each item is announced as it
//! starts, so a display can say what is running; the step ends once. Items of a parallel step
//! may be announced from several threads.

/// What the pipeline tells about its long steps.
pub trait Progress: Sync {
    /// A step of `total` items begins.
    fn begin(&self, step: &str, total: usize);
    /// An item of the current step starts (the one announced before it, if any, is done).
    fn item(&self, what: &str);
    /// The current step is done.
    fn end(&self);
}

/// Tells nobody.
pub struct Silent;

impl Progress for Silent {
    fn begin(&self, _: &str, _: usize) {}
    fn item(&self, _: &str) {}
    fn end(&self) {}
}
