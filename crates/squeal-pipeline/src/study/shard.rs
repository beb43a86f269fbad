//! A study split into shards that a batch scheduler (a Slurm job array, GNU parallel) runs on
//! many machines, and their merge.
//!
//! A study is a list of independent units ([`units`]): the description of the modes that
//! couple at μ0, each non-nominal case of the pressure, stiffness and damping studies, each
//! damping case of the paradox study, and for the mesh study each mesh level (its patch and
//! node contact together: the node-contact brake takes its contact laws from the patch brake
//! of the same level, so splitting them would reduce the patch model twice). Unit `u`
//! (0-based, in the order of [`units`]) belongs to shard `u mod n + 1` of `n` (round-robin:
//! the cases of a study cost about the same, and neighbours go to different shards).
//!
//! Every shard of a non-mesh study also computes the nominal brake's sweep, which every case
//! is normalized by (and the damping cases take their pair from): it is repeated once per
//! shard, and the merge checks that all shards found the same one, bit for bit.
//!
//! A shard writes `<out>/study/shards/<kind>-<i>-of-<n>.json` ([`ShardFile`]): the study,
//! which shard, what it was computed from ([`Identity`]: the SHA-256 of the scene and mesh
//! files, the friction values, the mesh levels), the nominal outcome and its units' results.
//! The merge reads all `n`, refuses a missing, mixed or stale one with a message that names
//! it, and hands the results in unit order to the writer the unsplit run uses.

use super::record::{F, Nominal, UnitResult};
use super::{Kind, name};
use crate::error::{PipelineError, Result};
use serde::{Deserialize, Serialize};
use squeal_brake::studies::{Case, damping_cases, pressure_cases, stiffness_cases};
use squeal_scene::Scene;
use std::path::{Path, PathBuf};

/// Which share of a study a run computes: shard `index` (1-based) of `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// The whole study (the unsplit run).
    pub const WHOLE: Shard = Shard { index: 1, count: 1 };

    /// Parses `i/n` (1 ≤ i ≤ n), e.g. `2/4`; the error says what is wrong.
    pub fn parse(s: &str) -> std::result::Result<Shard, String> {
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| format!("'{s}' is not i/n (e.g. 2/4: the second of four shards)"))?;
        let num = |t: &str, what: &str| {
            t.trim()
                .parse::<usize>()
                .map_err(|_| format!("'{s}': the {what} '{t}' is not a whole number"))
        };
        let (index, count) = (num(i, "shard number")?, num(n, "shard count")?);
        if count == 0 {
            return Err(format!("'{s}': the shard count must be at least 1"));
        }
        if index == 0 {
            return Err(format!(
                "'{s}': shards are numbered from 1 (1/{count} to {count}/{count})"
            ));
        }
        if index > count {
            return Err(format!(
                "'{s}': there is no shard {index} of {count} (1/{count} to {count}/{count})"
            ));
        }
        Ok(Shard { index, count })
    }

    /// Whether unit `u` (0-based) is this shard's: round-robin.
    pub fn owns(&self, u: usize) -> bool {
        u % self.count + 1 == self.index
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// One independent piece of a study.
#[derive(Clone, Debug, PartialEq)]
pub enum Unit {
    /// The shapes of the two modes that couple at the nominal μ0.
    CoupledModes,
    /// A non-nominal case of the pressure, stiffness or damping study.
    Case(Kind, Case),
    /// A damping case of the paradox study (index into its three).
    Paradox(usize),
    /// A mesh level, patch and node contact.
    Level(String),
}

impl Unit {
    /// The unit's name in a shard file, e.g. `damping/4` (case 4), `mesh/fine`.
    pub fn key(&self) -> String {
        match self {
            Unit::CoupledModes => "coupled_modes".into(),
            Unit::Case(k, c) => format!("{}/{}", name(*k), c.number),
            Unit::Paradox(i) => format!("paradox/{}", i + 1),
            Unit::Level(l) => format!("mesh/{l}"),
        }
    }
}

/// The studies `kind` stands for (`all`: pressure, stiffness, damping, paradox).
pub fn studies(kind: Kind) -> Vec<Kind> {
    match kind {
        Kind::All => vec![
            Kind::Pressure,
            Kind::Stiffness,
            Kind::Damping,
            Kind::Paradox,
        ],
        k => vec![k],
    }
}

/// The cases of a parametric study (case 1, the nominal, included).
pub fn cases(kind: Kind) -> Vec<Case> {
    match kind {
        Kind::Pressure => pressure_cases(),
        Kind::Stiffness => stiffness_cases(),
        Kind::Damping => damping_cases(),
        _ => Vec::new(),
    }
}

/// The paradox study's damping cases.
pub const PARADOX_CASES: usize = 3;

/// The units of a study, in the order shards are dealt them and the writer reads them.
pub fn units(kind: Kind, levels: &[String]) -> Vec<Unit> {
    if kind == Kind::Mesh {
        return levels.iter().cloned().map(Unit::Level).collect();
    }
    let mut u = vec![Unit::CoupledModes];
    for k in studies(kind) {
        if k == Kind::Paradox {
            u.extend((0..PARADOX_CASES).map(Unit::Paradox));
        } else {
            u.extend(
                cases(k)
                    .into_iter()
                    .filter(|c| c.number != 1)
                    .map(|c| Unit::Case(k, c)),
            );
        }
    }
    u
}

/// What a study's results were computed from: a shard whose identity differs from the
/// merge's is stale (the scene or a mesh changed since) or from another command line.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Identity {
    /// SHA-256 of the scene file.
    pub scene_sha256: String,
    /// SHA-256 of the mesh files the study reads (disc and pad; of every level for the mesh
    /// study), in that order.
    pub mesh_sha256: Vec<String>,
    /// The friction values (`--mu`).
    pub mu: Vec<F>,
    /// The mesh levels (`--levels`; empty but for the mesh study).
    pub levels: Vec<String>,
}

fn sha256(path: &Path) -> Result<String> {
    squeal_reduce::rom::sha256_file(path).map_err(|error| PipelineError::Rom {
        path: path.to_path_buf(),
        error,
    })
}

impl Identity {
    /// The identity of a study of `scene` over `mus` (`meshes`: the mesh files it reads).
    pub fn of(scene: &Scene, meshes: &[PathBuf], mus: &[f64], levels: &[String]) -> Result<Self> {
        Ok(Identity {
            scene_sha256: sha256(&scene.path)?,
            mesh_sha256: meshes.iter().map(|p| sha256(p)).collect::<Result<_>>()?,
            mu: mus.iter().copied().map(F).collect(),
            levels: levels.to_vec(),
        })
    }

    /// Why `self` (a shard's) is not `now` (the merge's), and what to do, when it is not.
    fn differs(&self, now: &Identity) -> Option<String> {
        if self.scene_sha256 != now.scene_sha256 {
            return Some(
                "stale shard: the scene file has changed since it was computed; run the shards again"
                    .into(),
            );
        }
        if self.mesh_sha256 != now.mesh_sha256 {
            return Some(
                "stale shard: a mesh file has changed since it was computed; run the shards again"
                    .into(),
            );
        }
        if self.mu != now.mu {
            let r = |m: &[F]| match (m.first(), m.last()) {
                (Some(a), Some(b)) => format!("{} values from {} to {}", m.len(), a.0, b.0),
                _ => "no values".into(),
            };
            return Some(format!(
                "it was computed over other friction values ({}; the merge asks for {}): give the merge the shards' --mu, or run the shards again with this one",
                r(&self.mu),
                r(&now.mu)
            ));
        }
        if self.levels != now.levels {
            return Some(format!(
                "it was computed for the mesh levels {} (the merge asks for {}): give the merge the shards' --levels, or run the shards again with these",
                self.levels.join(","),
                now.levels.join(",")
            ));
        }
        None
    }
}

/// A shard's results, as its file holds them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ShardFile {
    /// [`FORMAT`].
    pub format: String,
    /// The study (`--kind`).
    pub kind: String,
    pub shard: Shard,
    /// The version of squeal that computed it ([`squeal_reduce::brake::TOOL_VERSION`]); the
    /// merge refuses a shard of another version.
    pub squeal_version: String,
    pub identity: Identity,
    /// The nominal brake (every study but the mesh study).
    pub nominal: Option<Nominal>,
    /// The shard's units, in unit order.
    pub units: Vec<UnitEntry>,
}

/// A unit's name ([`Unit::key`]) and result.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct UnitEntry {
    pub unit: String,
    pub result: UnitResult,
}

/// The format tag of a shard file.
pub const FORMAT: &str = "squeal study shard, version 1";

/// `<dir>/shards/<kind>-<i>-of-<n>.json` (`dir` is `<out>/study`).
pub fn path(dir: &Path, kind: Kind, shard: Shard) -> PathBuf {
    dir.join("shards").join(format!(
        "{}-{}-of-{}.json",
        name(kind),
        shard.index,
        shard.count
    ))
}

/// Writes a shard file (atomically).
pub fn write(path: &Path, file: &ShardFile) -> Result<()> {
    if let Some(dir) = path.parent() {
        super::create_dir(dir)?;
    }
    let text = serde_json::to_string(file).map_err(|error| PipelineError::Json {
        what: "the shard file",
        error,
    })?;
    squeal_io::atomic_write_bytes(path, text.as_bytes())?;
    Ok(())
}

fn shard_error(path: &Path, message: impl std::fmt::Display) -> PipelineError {
    PipelineError::input(
        "merging the shards",
        format!("{}: {message}", path.display()),
    )
}

fn read(path: &Path) -> Result<ShardFile> {
    let text = std::fs::read_to_string(path).map_err(|error| PipelineError::File {
        what: "reading the shard",
        path: path.to_path_buf(),
        error,
    })?;
    let file: ShardFile = serde_json::from_str(&text)
        .map_err(|e| shard_error(path, format!("not a squeal shard file ({e})")))?;
    if file.format != FORMAT {
        return Err(shard_error(
            path,
            format!("format '{}', this squeal reads '{FORMAT}'", file.format),
        ));
    }
    Ok(file)
}

/// `<kind>-<i>-of-<n>.json` -> (i, n).
fn parse_name(file: &str, kind: Kind) -> Option<(usize, usize)> {
    let rest = file
        .strip_prefix(name(kind))?
        .strip_prefix('-')?
        .strip_suffix(".json")?;
    let (i, n) = rest.split_once("-of-")?;
    let (i, n): (usize, usize) = (i.parse().ok()?, n.parse().ok()?);
    // Only the names `path` writes: `damping-01-of-2.json` is not shard 1 of 2.
    (format!("{}-{i}-of-{n}.json", name(kind)) == file).then_some((i, n))
}

/// Reads and checks the `n` shard files of study `kind` in `<dir>/shards`: all present, from
/// one split, of this study, computed from `identity`, agreeing on the nominal brake. In
/// shard order.
pub fn read_all(dir: &Path, kind: Kind, identity: &Identity) -> Result<Vec<ShardFile>> {
    let folder = dir.join("shards");
    let entries = std::fs::read_dir(&folder).map_err(|error| PipelineError::File {
        what: "reading the shards' folder (run the shards first: squeal study ... --shard i/n)",
        path: folder.clone(),
        error,
    })?;
    let mut found: Vec<(usize, usize, PathBuf)> = Vec::new();
    for e in entries.flatten() {
        let file = e.file_name().to_string_lossy().into_owned();
        if let Some((i, n)) = parse_name(&file, kind) {
            found.push((i, n, e.path()));
        }
    }
    found.sort();
    let Some(&(_, n, _)) = found.first() else {
        return Err(PipelineError::input(
            "merging the shards",
            format!(
                "no shard of the {} study in {} (files {}-<i>-of-<n>.json): run squeal study ... --kind {} --shard i/n first",
                name(kind),
                folder.display(),
                name(kind),
                name(kind)
            ),
        ));
    };
    let mut counts: Vec<usize> = found.iter().map(|f| f.1).collect();
    counts.sort_unstable();
    counts.dedup();
    if counts.len() > 1 {
        return Err(PipelineError::input(
            "merging the shards",
            format!(
                "{} holds shards of the {} study from splits into {} shards: remove the files of the splits you do not want to merge",
                folder.display(),
                name(kind),
                counts
                    .iter()
                    .map(|c| c.to_string())
                    .collect::<Vec<_>>()
                    .join(" and ")
            ),
        ));
    }
    if let Some((i, _, p)) = found.iter().find(|f| f.0 == 0 || f.0 > n) {
        return Err(shard_error(
            p,
            format!("there is no shard {i} of {n}: remove the file"),
        ));
    }
    // At most a few missing are named: a stray `-of-99999999999` must not list them all.
    let missing: Vec<String> = (1..=n)
        .filter(|i| !found.iter().any(|f| f.0 == *i))
        .take(20)
        .map(|i| format!("{i}/{n}"))
        .collect();
    if !missing.is_empty() {
        return Err(PipelineError::input(
            "merging the shards",
            format!(
                "shard {} of the {} study missing in {} (expected {}-<i>-of-{n}.json): run squeal study ... --kind {} --shard {} first",
                missing.join(", "),
                name(kind),
                folder.display(),
                name(kind),
                name(kind),
                missing[0]
            ),
        ));
    }
    let mut files = Vec::with_capacity(n);
    for (i, _, p) in &found {
        let file = read(p)?;
        let want = Shard {
            index: *i,
            count: n,
        };
        if file.kind != name(kind) || file.shard != want {
            return Err(shard_error(
                p,
                format!(
                    "it holds shard {} of the {} study, its name says {want} of the {} study: was it renamed?",
                    file.shard,
                    file.kind,
                    name(kind)
                ),
            ));
        }
        if file.squeal_version != squeal_reduce::brake::TOOL_VERSION {
            return Err(shard_error(
                p,
                format!(
                    "it was computed by {}, this is {}: run every shard with one build",
                    file.squeal_version,
                    squeal_reduce::brake::TOOL_VERSION
                ),
            ));
        }
        if let Some(why) = file.identity.differs(identity) {
            return Err(shard_error(p, why));
        }
        if let Some(first) = files.first().map(|f: &ShardFile| &f.nominal)
            && *first != file.nominal
        {
            return Err(shard_error(
                p,
                "its nominal Hopf point differs from shard 1's, bit for bit: the shards were computed by different builds of squeal (or on machines whose arithmetic differs); run them with one build",
            ));
        }
        files.push(file);
    }
    Ok(files)
}

/// A study's results gathered from its shards, in unit order.
pub struct Collected {
    pub nominal: Option<Nominal>,
    pub results: Vec<(Unit, UnitResult)>,
}

/// Gathers every unit of the study from the shard that owns it (`files` in shard order, one
/// file for the unsplit run); a unit missing or in the wrong shard is an error.
pub fn collect(kind: Kind, levels: &[String], files: Vec<ShardFile>) -> Result<Collected> {
    let n = files.len();
    let nominal = files.first().and_then(|f| f.nominal.clone());
    if kind != Kind::Mesh && nominal.is_none() {
        return Err(PipelineError::input(
            "merging the shards",
            "shard 1 has no nominal outcome",
        ));
    }
    let mut entries: Vec<std::vec::IntoIter<UnitEntry>> =
        files.into_iter().map(|f| f.units.into_iter()).collect();
    let mut results = Vec::new();
    for (u, unit) in units(kind, levels).into_iter().enumerate() {
        let owner = u % n;
        let key = unit.key();
        match entries[owner].next() {
            Some(e) if e.unit == key => results.push((unit, e.result)),
            other => {
                return Err(PipelineError::input(
                    "merging the shards",
                    format!(
                        "shard {}/{n} should hold the unit {key} next, it holds {}",
                        owner + 1,
                        other.map_or("nothing more".into(), |e| e.unit)
                    ),
                ));
            }
        }
    }
    for (i, mut rest) in entries.into_iter().enumerate() {
        if let Some(e) = rest.next() {
            return Err(PipelineError::input(
                "merging the shards",
                format!(
                    "shard {}/{n} holds the unit {} that is not in the study",
                    i + 1,
                    e.unit
                ),
            ));
        }
    }
    Ok(Collected { nominal, results })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_names_a_shard_is_written_under_are_read() {
        assert_eq!(
            parse_name("damping-1-of-2.json", Kind::Damping),
            Some((1, 2))
        );
        assert_eq!(parse_name("damping-01-of-2.json", Kind::Damping), None);
        assert_eq!(parse_name("damping-1-of-+2.json", Kind::Damping), None);
        assert_eq!(parse_name("pressure-1-of-2.json", Kind::Damping), None);
    }

    #[test]
    fn shard_arguments_are_checked() {
        assert_eq!(Shard::parse("2/3"), Ok(Shard { index: 2, count: 3 }));
        assert_eq!(Shard::parse(" 1 / 1 "), Ok(Shard::WHOLE));
        for (bad, says) in [
            ("0/3", "numbered from 1"),
            ("4/3", "no shard 4 of 3"),
            ("1/0", "at least 1"),
            ("0/0", "at least 1"),
            ("2", "not i/n"),
            ("a/3", "'a' is not a whole number"),
            ("-1/3", "not a whole number"),
        ] {
            let e = Shard::parse(bad).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }

    #[test]
    fn every_unit_belongs_to_exactly_one_shard_round_robin() {
        let all = units(Kind::All, &[]);
        // Coupled modes, 2 pressure, 2 stiffness, 6 damping and 3 paradox cases.
        assert_eq!(all.len(), 14);
        for n in 1..=5 {
            for u in 0..all.len() {
                let owners: Vec<usize> = (1..=n)
                    .filter(|&i| Shard { index: i, count: n }.owns(u))
                    .collect();
                assert_eq!(owners, vec![u % n + 1]);
            }
        }
        let keys: Vec<String> = all.iter().map(Unit::key).collect();
        assert_eq!(keys[0], "coupled_modes");
        assert_eq!(keys[1], "pressure/5");
        assert_eq!(keys[13], "paradox/3");
        let levels = ["coarse".to_string(), "fine".to_string()];
        let mesh: Vec<String> = units(Kind::Mesh, &levels).iter().map(Unit::key).collect();
        assert_eq!(mesh, ["mesh/coarse", "mesh/fine"]);
    }

    #[test]
    fn shard_names_parse_only_for_their_study() {
        assert_eq!(
            parse_name("damping-2-of-3.json", Kind::Damping),
            Some((2, 3))
        );
        assert_eq!(parse_name("damping-2-of-3.json", Kind::Pressure), None);
        assert_eq!(parse_name("damping-2-of-3.json.tmp", Kind::Damping), None);
        assert_eq!(parse_name("all-x-of-3.json", Kind::All), None);
    }
}
