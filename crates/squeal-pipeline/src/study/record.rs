//! The per-unit results of a study as plain data that goes through JSON unchanged: what a
//! shard file carries, and what the tables and figures are written from, split or not.
//!
//! Exactness: a finite `f64` is written by `serde_json` as the shortest decimal that reads
//! back to the same value (ryu), and read back correctly rounded — hence to the same bits —
//! with the `float_roundtrip` feature this crate turns on (without it, `serde_json` reads
//! about 30 % of random bit patterns back off in the last bits). Non-finite values, which JSON numbers
//! cannot hold, are written as the strings `"NaN"`, `"inf"` and `"-inf"` ([`F`]). The tests
//! below check both on edge values and on a million random bit patterns.

use faer::c64;
use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use squeal_brake::studies::{BranchCurve, Case, CaseOutcome, GrowthRow};

/// An `f64` that reads back from JSON with the same bits (NaN comes back as the canonical
/// NaN). Equality compares bits, so `-0.0 != 0.0` and NaN equals NaN: two shards agree only
/// if their values are identical.
#[derive(Clone, Copy, Debug)]
pub struct F(pub f64);

impl PartialEq for F {
    fn eq(&self, other: &Self) -> bool {
        self.0.to_bits() == other.0.to_bits()
    }
}

impl Serialize for F {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let v = self.0;
        if v.is_finite() {
            s.serialize_f64(v)
        } else if v.is_nan() {
            s.serialize_str("NaN")
        } else if v > 0.0 {
            s.serialize_str("inf")
        } else {
            s.serialize_str("-inf")
        }
    }
}

struct FVisitor;

impl Visitor<'_> for FVisitor {
    type Value = F;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a number, or \"NaN\", \"inf\", \"-inf\"")
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<F, E> {
        Ok(F(v))
    }
    // serde_json writes every f64 with a decimal point or exponent; integers are accepted for
    // hand-written files and are exact up to 2^53.
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<F, E> {
        Ok(F(v as f64))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<F, E> {
        Ok(F(v as f64))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<F, E> {
        match v {
            "NaN" => Ok(F(f64::NAN)),
            "inf" => Ok(F(f64::INFINITY)),
            "-inf" => Ok(F(f64::NEG_INFINITY)),
            _ => Err(E::invalid_value(de::Unexpected::Str(v), &self)),
        }
    }
}

impl<'de> Deserialize<'de> for F {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<F, D::Error> {
        d.deserialize_any(FVisitor)
    }
}

fn fs(v: &[f64]) -> Vec<F> {
    v.iter().copied().map(F).collect()
}

fn unf(v: &[F]) -> Vec<f64> {
    v.iter().map(|x| x.0).collect()
}

/// A study case ([`Case`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseRecord {
    pub number: usize,
    pub label: String,
    pub pressure: F,
    pub stiffness: F,
    pub pair_factors: [F; 2],
}

/// A tracked branch ([`BranchCurve`]); eigenvalues as `[re, im]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CurveRecord {
    pub basis_mode: usize,
    pub mu: Vec<F>,
    pub values: Vec<[F; 2]>,
}

/// What the tables and figures read of a case's outcome ([`CaseOutcome`] without its list of
/// crossings, which no study output shows).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct OutcomeRecord {
    pub case: CaseRecord,
    pub mu0: Option<F>,
    pub frequency_hz: Option<F>,
    pub pair: Option<(usize, usize)>,
    pub pair_hz: Option<(F, F)>,
    pub unstable: Option<CurveRecord>,
    pub partner: Option<CurveRecord>,
}

impl From<&CaseOutcome> for OutcomeRecord {
    fn from(o: &CaseOutcome) -> Self {
        let curve = |c: &BranchCurve| CurveRecord {
            basis_mode: c.basis_mode,
            mu: fs(&c.mu),
            values: c.values.iter().map(|v| [F(v.re), F(v.im)]).collect(),
        };
        let c = &o.case;
        OutcomeRecord {
            case: CaseRecord {
                number: c.number,
                label: c.label.clone(),
                pressure: F(c.pressure),
                stiffness: F(c.stiffness),
                pair_factors: c.pair_factors.map(F),
            },
            mu0: o.mu0.map(F),
            frequency_hz: o.frequency_hz.map(F),
            pair: o.pair,
            pair_hz: o.pair_hz.map(|(a, b)| (F(a), F(b))),
            unstable: o.unstable.as_ref().map(curve),
            partner: o.partner.as_ref().map(curve),
        }
    }
}

impl OutcomeRecord {
    /// The outcome the writers read (its `crossings` empty).
    pub fn outcome(&self) -> CaseOutcome {
        let curve = |c: &CurveRecord| BranchCurve {
            basis_mode: c.basis_mode,
            mu: unf(&c.mu),
            values: c.values.iter().map(|v| c64::new(v[0].0, v[1].0)).collect(),
        };
        let c = &self.case;
        CaseOutcome {
            case: Case {
                number: c.number,
                label: c.label.clone(),
                pressure: c.pressure.0,
                stiffness: c.stiffness.0,
                pair_factors: c.pair_factors.map(|f| f.0),
            },
            mu0: self.mu0.map(|v| v.0),
            frequency_hz: self.frequency_hz.map(|v| v.0),
            pair: self.pair,
            pair_hz: self.pair_hz.map(|(a, b)| (a.0, b.0)),
            unstable: self.unstable.as_ref().map(curve),
            partner: self.partner.as_ref().map(curve),
            crossings: Vec::new(),
        }
    }
}

/// The nominal brake's outcome and the constants the case tables print: computed by every
/// shard (the studies are normalized by it), and identical in all of them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Nominal {
    pub outcome: OutcomeRecord,
    /// Piston force of eq (11) (N).
    pub piston_force: F,
    /// Sum of the pairs' linear contact stiffnesses `k_l` of eq (8) at first touch (N/m).
    pub contact_stiffness: F,
    /// The scene's pair damping ratios of eq (13).
    pub pair_ratios: [F; 2],
}

/// The growth of the modes outside the pair at one friction value ([`GrowthRow`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GrowthRecord {
    pub mu: F,
    pub max_ratio: F,
    pub real_part: F,
    pub frequency_hz: F,
    pub basis_mode: usize,
    pub unstable: usize,
    pub predicted_ratio: F,
}

impl From<&GrowthRow> for GrowthRecord {
    fn from(r: &GrowthRow) -> Self {
        GrowthRecord {
            mu: F(r.mu),
            max_ratio: F(r.max_ratio),
            real_part: F(r.real_part),
            frequency_hz: F(r.frequency_hz),
            basis_mode: r.basis_mode,
            unstable: r.unstable,
            predicted_ratio: F(r.predicted_ratio),
        }
    }
}

impl GrowthRecord {
    pub fn row(&self) -> GrowthRow {
        GrowthRow {
            mu: self.mu.0,
            max_ratio: self.max_ratio.0,
            real_part: self.real_part.0,
            frequency_hz: self.frequency_hz.0,
            basis_mode: self.basis_mode,
            unstable: self.unstable,
            predicted_ratio: self.predicted_ratio.0,
        }
    }
}

/// One damping case of the paradox study.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParadoxRecord {
    pub label: String,
    pub global_ratio: F,
    pub pair_ratios: [F; 2],
    pub rows: Vec<GrowthRecord>,
    /// First in-band crossing: μ0, frequency, frictionless mode (0-based), whether it is the
    /// pair's.
    pub hopf: Option<(F, F, usize, bool)>,
}

/// How one model of the mesh study ended.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum MeshOutcome {
    /// The Hopf point: μ0, frequency, the pair (0-based) and its frictionless frequencies.
    Found {
        mu0: Option<F>,
        frequency_hz: Option<F>,
        pair: Option<(usize, usize)>,
        pair_hz: Option<(F, F)>,
    },
    /// No Hopf point in the band (a result, e.g. node contact on fine meshes): the message.
    NoHopfPoint(String),
    /// The analysis failed: the message.
    Failed(String),
}

/// One model (a mesh level with one contact interface) of the mesh study.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeshRow {
    pub interface: String,
    /// Nodes of the disc and pad meshes.
    pub nodes: usize,
    pub outcome: MeshOutcome,
}

/// The shapes of the modes that couple at μ0, as written: the text and the JSON.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CoupledModes {
    pub text: String,
    pub json: String,
}

/// The result of one unit of a study ([`super::shard::Unit`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum UnitResult {
    /// `None` when the nominal sweep has no pair to describe.
    CoupledModes(Option<CoupledModes>),
    Case(OutcomeRecord),
    Paradox(ParadoxRecord),
    /// The level's models, node contact then patch contact.
    Level(Vec<MeshRow>),
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip(v: f64) -> f64 {
        let text = serde_json::to_string(&F(v)).unwrap();
        serde_json::from_str::<F>(&text).unwrap().0
    }

    #[test]
    fn floats_round_trip_through_json_with_their_bits() {
        // Edge values: signed zero, the smallest subnormal, the largest finite, values whose
        // shortest decimal has 17 digits, and the non-finite ones (NaN is compared as NaN).
        let edges = [
            0.0,
            -0.0,
            f64::from_bits(1),
            f64::MIN_POSITIVE,
            f64::MAX,
            f64::MIN,
            0.1 + 0.2,
            1.0 / 3.0,
            2.0f64.powi(53) + 2.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for v in edges {
            assert_eq!(round_trip(v).to_bits(), v.to_bits(), "{v:e}");
        }
        assert!(round_trip(f64::NAN).is_nan());
        // A million random bit patterns (xorshift64, fixed seed): every finite one must come
        // back with the same bits. Without serde_json's float_roundtrip feature 296,493 of
        // these 999,505 came back off in the last digits (measured with serde_json 1.0 and its
        // default features, e.g. 1.0715660391465826e-75 read as ...825e-75).
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut checked = 0;
        for _ in 0..1_000_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = f64::from_bits(x);
            if v.is_finite() {
                assert_eq!(round_trip(v).to_bits(), x, "{v:e}");
                checked += 1;
            }
        }
        // About 1/2048 of the patterns are non-finite (all-ones exponent).
        assert!(checked > 999_000, "{checked}");
    }

    #[test]
    fn bad_float_strings_are_refused() {
        assert!(serde_json::from_str::<F>("\"infinity\"").is_err());
        assert!(serde_json::from_str::<F>("null").is_err());
    }
}
