//! What a brake reduction reports: its contact point pairs and each part's read and reduction
//! times ([`super::reduce_brake`]).

use super::*;

/// A disc contact point and the pad contact point it faces (the brake's contact pair, with its
/// geometry and element, is `squeal_brake::ContactPair`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointPair {
    /// Index among the disc's contact points (0-based, the order of its `dofs`).
    pub disc_point: usize,
    /// Index among the pad's contact points.
    pub pad_point: usize,
    /// Distance between the two (m).
    pub distance: f64,
}

/// What [`reduce_brake`](super::reduce_brake) did and cost.
#[derive(Clone, Debug)]
pub struct BrakeReport {
    /// Disc, then pad.
    pub parts: Vec<PartReport>,
    /// The disc's contact points paired with the pad's.
    pub pairs: Vec<PointPair>,
    /// Pairing tolerance in metres (0 for the nodal interface, which pairs by projection).
    pub pairing_tolerance: f64,
    /// Wall time of the whole reduction, reading the meshes included.
    pub total: Duration,
}

/// One part's share of a [`BrakeReport`].
#[derive(Clone, Debug)]
pub struct PartReport {
    /// The part's name.
    pub name: String,
    /// The mesh it was reduced from.
    pub mesh: MeshInfo,
    /// The mesh reader's warnings.
    pub warnings: Vec<String>,
    /// Time spent reading and hashing the mesh.
    pub read_time: Duration,
    /// What [`crate::craig_bampton::reduce_part`] did and cost (empty when `reused`).
    pub reduce: ReduceReport,
    /// Taken from the reductions an earlier run kept ([`reduce_brake_keeping`](super::reduce_brake_keeping)), not reduced.
    pub reused: bool,
}

impl PartReport {
    /// Time of a stage (read included).
    pub fn time(&self, stage: Stage) -> Duration {
        if stage == Stage::Read {
            return self.read_time;
        }
        self.reduce
            .timings
            .iter()
            .filter(|(s, _)| *s == stage)
            .map(|(_, d)| *d)
            .sum()
    }
}
