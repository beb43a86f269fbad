//! The parametric stability studies of the paper's sections 6.2–6.4 (piston pressure, contact
//! stiffness, modal damping: Tables 4–6, Figures 9–11 (a, b)), the damping-induced
//! destabilization at vanishing friction, the mesh-convergence study (`study/mesh.rs`), the
//! identification of the modes that couple at μ0 (`study/coupled.rs`), and the convergence study of
//! μ0 under refinement of the contact, the kept modes and the mesh ([`convergence`]).
//!
//! Everything goes to `<out>/study/`: a CSV (and Markdown) table per study, the branches of
//! every case as CSV, and the overlaid figures as SVG and PNG.
//!
//! A study is a list of independent units (the cases, the mesh levels: [`shard`]) computed
//! into plain records ([`record`]), then written by one writer ([`write()`]). The unsplit run
//! ([`run`]) computes every unit and writes; a shard ([`run_shard`]) computes its share and
//! stores the records in a JSON file; the merge ([`merge`]) reads the shards and calls the
//! same writer, so both give the same files, bit for bit.

pub mod convergence;
mod coupled;
mod mesh;
mod paradox;
pub mod record;
pub mod shard;
pub mod verdict;

pub use shard::Shard;

use crate::error::{PipelineError, Result};
use crate::model::{Log, build, damping_spec};
use faer::c64;
use rayon::prelude::*;
use record::{F, Nominal, OutcomeRecord, UnitResult};
use shard::{Collected, Identity, ShardFile, Unit, UnitEntry};
use squeal_brake::Brake;
use squeal_brake::analysis::stability;
use squeal_brake::studies::{BranchCurve, Case, CaseOutcome, outcome, run_case};
use squeal_report::format::{fmt_sci, fmt_sig};
use squeal_report::{
    Annotation, Dash, Figure, Layout, Panel, Series, Table, palette_color, write_svg_and_png,
};
use squeal_scene::Scene;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Which study to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Piston pressure 0.8, 1, 1.2 of nominal (paper Table 4, Figure 9)
    Pressure,
    /// Both contact stiffnesses 0.7, 1, 1.3 of nominal (Table 5, Figure 10)
    Stiffness,
    /// Pair damping D1/D2 of Table 6 (Figure 11)
    Damping,
    /// Damping on the pair alone vs with the global part, at vanishing friction
    Paradox,
    /// mu0 on the coarse, medium and fine meshes, patch and node contact (slow)
    Mesh,
    /// pressure, stiffness, damping and paradox (not mesh)
    All,
    /// mu0 under refinement of the contact, the kept modes and the mesh, with a verdict
    Convergence,
}

impl Kind {
    /// Every study with its name and a line of help (the command line's choices).
    pub const CHOICES: [(Kind, &'static str, &'static str); 7] = [
        (
            Kind::Pressure,
            "pressure",
            "piston pressure 0.8, 1, 1.2 of nominal (paper Table 4, Figure 9)",
        ),
        (
            Kind::Stiffness,
            "stiffness",
            "both contact stiffnesses 0.7, 1, 1.3 of nominal (Table 5, Figure 10)",
        ),
        (
            Kind::Damping,
            "damping",
            "pair damping D1/D2 of Table 6 (Figure 11)",
        ),
        (
            Kind::Paradox,
            "paradox",
            "damping on the pair alone vs with the global part, at vanishing friction",
        ),
        (
            Kind::Mesh,
            "mesh",
            "mu0 on the coarse, medium and fine meshes, patch and node contact (slow)",
        ),
        (
            Kind::All,
            "all",
            "pressure, stiffness, damping and paradox (not mesh)",
        ),
        (
            Kind::Convergence,
            "convergence",
            "mu0 under refinement of the contact, the kept modes and the mesh, with a verdict (slow)",
        ),
    ];
}

/// Runs the study `kind` of a scene over the friction values `mus` (the mesh study over the
/// mesh `levels`) and writes its tables and figures to `<out>/study`.
pub fn run(
    scene: &Scene,
    out: &Path,
    kind: Kind,
    mus: &[f64],
    levels: &[String],
    log: Log,
) -> Result<()> {
    if kind == Kind::Convergence {
        let opts = convergence::Options {
            levels: levels.to_vec(),
            ..Default::default()
        };
        return convergence::run(scene, out, mus, &opts, log).map(|_| ());
    }
    let file = compute(scene, out, kind, mus, levels, Shard::WHOLE, log)?;
    let results = shard::collect(kind, levels, vec![file])?;
    write(kind, &results, &out.join("study"), log)
}

/// Computes shard `shard` of the study ([`shard`]) and writes its results to
/// `<out>/study/shards/<kind>-<i>-of-<n>.json`, whose path it returns.
pub fn run_shard(
    scene: &Scene,
    out: &Path,
    kind: Kind,
    mus: &[f64],
    levels: &[String],
    shard: Shard,
    log: Log,
) -> Result<PathBuf> {
    not_split(kind)?;
    let file = compute(scene, out, kind, mus, levels, shard, log)?;
    let path = shard::path(&out.join("study"), kind, shard);
    shard::write(&path, &file)?;
    Ok(path)
}

/// Merges the shards of the study in `<out>/study/shards` (all of one split, computed from
/// this scene, its meshes, `mus` and `levels`) and writes the tables and figures the unsplit
/// run writes, by the same writer. Returns the number of shards.
pub fn merge(
    scene: &Scene,
    out: &Path,
    kind: Kind,
    mus: &[f64],
    levels: &[String],
    log: Log,
) -> Result<usize> {
    not_split(kind)?;
    let dir = out.join("study");
    let id = identity(scene, kind, mus, levels)?;
    let files = shard::read_all(&dir, kind, &id)?;
    let n = files.len();
    log(&format!("merging {n} shards of the {} study", name(kind)));
    let results = shard::collect(kind, levels, files)?;
    write(kind, &results, &dir, log)?;
    Ok(n)
}

/// The convergence study is not split into shards: each level's reduction is cached, and a
/// rerun reuses them.
fn not_split(kind: Kind) -> Result<()> {
    if kind == Kind::Convergence {
        return Err(PipelineError::input(
            "--kind convergence",
            "the convergence study is not split into shards: run it without --shard and --merge (its reduced models are cached in <out>/study/convergence, so a rerun reduces nothing again)",
        ));
    }
    Ok(())
}

/// What the study's results depend on (the merge refuses shards computed from anything else).
fn identity(scene: &Scene, kind: Kind, mus: &[f64], levels: &[String]) -> Result<Identity> {
    if kind == Kind::Mesh {
        return Identity::of(scene, &mesh::level_meshes(scene, levels)?, mus, levels);
    }
    Identity::of(scene, &scene.mesh_files()?, mus, &[])
}

/// Computes the units of the study that `shard` owns (all of them for [`Shard::WHOLE`]).
fn compute(
    scene: &Scene,
    out: &Path,
    kind: Kind,
    mus: &[f64],
    levels: &[String],
    shard: Shard,
    log: Log,
) -> Result<ShardFile> {
    // Inputs are checked before any work: the mesh study's files, the damping study's ratios.
    let id = identity(scene, kind, mus, levels)?;
    check_pair_ratios(scene, kind)?;
    let all = shard::units(kind, levels);
    let total = all.len();
    let mine: Vec<Unit> = all
        .into_iter()
        .enumerate()
        .filter(|(u, _)| shard.owns(*u))
        .map(|(_, unit)| unit)
        .collect();
    if shard != Shard::WHOLE {
        log(&format!(
            "shard {shard} of the {} study: {} of its {total} units ({})",
            name(kind),
            mine.len(),
            mine.iter().map(Unit::key).collect::<Vec<_>>().join(", ")
        ));
    }
    let (nominal, results) = if kind == Kind::Mesh {
        (
            None,
            mesh::mesh_units(scene, &out.join("study/mesh"), mus, &mine, log)?,
        )
    } else {
        let (n, r) = study_units(scene, out, mus, &mine, log)?;
        (Some(n), r)
    };
    Ok(ShardFile {
        format: shard::FORMAT.into(),
        kind: name(kind).into(),
        shard,
        squeal_version: squeal_reduce::brake::TOOL_VERSION.into(),
        identity: id,
        nominal,
        units: mine
            .iter()
            .zip(results)
            .map(|(u, result)| UnitEntry {
                unit: u.key(),
                result,
            })
            .collect(),
    })
}

/// The damping study scales the scene's pair ratios: they must not all be zero.
fn check_pair_ratios(scene: &Scene, kind: Kind) -> Result<()> {
    if !shard::studies(kind).contains(&Kind::Damping)
        || damping_spec(scene)?.pair_ratios.iter().any(|r| *r != 0.0)
    {
        return Ok(());
    }
    let msg = "the damping study scales the pair ratios: give damping.pair_ratios > 0 (e.g. [0.001, 0.001])";
    Err(scene
        .error_at_key(squeal_scene::Key::DampingPairRatios, msg)
        .into())
}

/// The nominal brake's sweep (every case is normalized by its Hopf point, the damping cases
/// damp its pair), then the units, in parallel.
fn study_units(
    scene: &Scene,
    out: &Path,
    mus: &[f64],
    units: &[Unit],
    log: Log,
) -> Result<(Nominal, Vec<UnitResult>)> {
    let s = build(scene, out, log)?;
    let t = Instant::now();
    let st = stability(&s.brake, &s.damping, mus, &s.sweep)?;
    let nominal = outcome(&Case::default(), &st);
    let (Some(mu0), Some(f0), Some(pair)) = (nominal.mu0, nominal.frequency_hz, nominal.pair)
    else {
        return Err(PipelineError::NoHopfPoint {
            from: mus[0],
            to: mus[mus.len() - 1],
            what: "the studies are normalized by the nominal Hopf point and",
        });
    };
    log(&format!(
        "nominal: mu0 = {mu0:.6} at {f0:.1} Hz ({:.1} s); Mode 1 = frictionless mode #{}, Mode 2 = #{}",
        t.elapsed().as_secs_f64(),
        pair.0 + 1,
        pair.1 + 1
    ));
    let grid = paradox::paradox_grid(mus);
    log(&format!("{} units in parallel ...", units.len()));
    let t = Instant::now();
    let results = units
        .par_iter()
        .map(|u| -> Result<UnitResult> {
            let t = Instant::now();
            let r = match u {
                Unit::CoupledModes => {
                    UnitResult::CoupledModes(coupled::coupled_modes(&s, &st, log)?)
                }
                Unit::Case(k, case) => {
                    // Table 6 damps the same two modes in every case: the nominal's pair.
                    let p = (*k == Kind::Damping).then_some(pair);
                    let o =
                        run_case(&s.brake, &s.damping, case, p, mus, &s.sweep).map_err(|e| {
                            PipelineError::Context {
                                context: format!(
                                    "{} study, case {} ({})",
                                    name(*k),
                                    case.number,
                                    case.label
                                ),
                                error: Box::new(PipelineError::input("stability", e)),
                            }
                        })?;
                    UnitResult::Case(OutcomeRecord::from(&o))
                }
                Unit::Paradox(i) => {
                    UnitResult::Paradox(paradox::paradox_case(&s, pair, &grid, *i)?)
                }
                Unit::Level(l) => {
                    return Err(PipelineError::input(
                        "study",
                        format!("mesh level {l} outside the mesh study"),
                    ));
                }
            };
            log(&format!(
                "  {}: {:.1} s",
                u.key(),
                t.elapsed().as_secs_f64()
            ));
            Ok(r)
        })
        .collect::<Result<Vec<_>>>()?;
    log(&format!("units: {:.1} s", t.elapsed().as_secs_f64()));
    let nominal = Nominal {
        outcome: OutcomeRecord::from(&nominal),
        piston_force: F(s.params.piston_force),
        contact_stiffness: F(contact_stiffness(&s.brake)),
        pair_ratios: s.damping.pair_ratios.map(F),
    };
    Ok((nominal, results))
}

/// The total linear contact stiffness at first touch (for eq (8), the sum of the `k_l`).
fn contact_stiffness(brake: &Brake) -> f64 {
    brake
        .pairs
        .iter()
        .map(|p| {
            let touch = squeal_brake::Kinematics {
                penetration: f64::MIN_POSITIVE,
                ..Default::default()
            };
            p.law.response(0.0, &touch).normal_derivatives[0]
        })
        .sum()
}

/// Writes a study's tables and figures from its units' results (in unit order): the one
/// writer of the unsplit run and of the merge, so that both give the same files.
pub fn write(kind: Kind, results: &Collected, dir: &Path, log: Log) -> Result<()> {
    create_dir(dir)?;
    let mismatch = |u: &Unit| {
        PipelineError::input(
            "study",
            format!("the result of unit {} is of another kind", u.key()),
        )
    };
    if kind == Kind::Mesh {
        let mut levels = Vec::new();
        for (u, r) in &results.results {
            match (u, r) {
                (Unit::Level(l), UnitResult::Level(rows)) => levels.push((l.as_str(), rows)),
                _ => return Err(mismatch(u)),
            }
        }
        return mesh::write_mesh(&levels, dir, log);
    }
    let nominal = results
        .nominal
        .as_ref()
        .ok_or_else(|| PipelineError::input("study", "no nominal outcome"))?;
    let mut cases: Vec<(Kind, &OutcomeRecord)> = Vec::new();
    let mut paradox = Vec::new();
    for (u, r) in &results.results {
        match (u, r) {
            (Unit::CoupledModes, UnitResult::CoupledModes(m)) => {
                if let Some(m) = m {
                    coupled::write_coupled_modes(m, dir, log)?;
                }
            }
            (Unit::Case(k, _), UnitResult::Case(o)) => cases.push((*k, o)),
            (Unit::Paradox(_), UnitResult::Paradox(p)) => paradox.push(p),
            _ => return Err(mismatch(u)),
        }
    }
    for k in shard::studies(kind) {
        if k == Kind::Paradox {
            paradox::write_paradox(&paradox, dir, log)?;
        } else {
            let mine: Vec<&OutcomeRecord> =
                cases.iter().filter(|c| c.0 == k).map(|c| c.1).collect();
            write_parametric(k, nominal, &mine, dir, log)?;
        }
    }
    if kind == Kind::All {
        log("(the mesh study runs only with --kind mesh: it reduces six models)");
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Pressure, stiffness, damping (Tables 4-6, Figures 9-11 (a, b))

fn name(kind: Kind) -> &'static str {
    Kind::CHOICES
        .iter()
        .find(|c| c.0 == kind)
        .map_or("study", |c| c.1)
}

/// Writes one parametric study from its non-nominal cases' outcomes (in case order): the
/// nominal outcome is case 1 of every table.
fn write_parametric(
    kind: Kind,
    nominal: &Nominal,
    others: &[&OutcomeRecord],
    dir: &Path,
    log: Log,
) -> Result<()> {
    let nominal_outcome = nominal.outcome.outcome();
    let mut others = others.iter();
    let mut outcomes = Vec::new();
    for case in shard::cases(kind) {
        if case.number == 1 {
            outcomes.push(CaseOutcome {
                case,
                ..nominal_outcome.clone()
            });
        } else {
            let o = others.next().ok_or_else(|| {
                PipelineError::input(
                    "study",
                    format!("{} study: no result for case {}", name(kind), case.number),
                )
            })?;
            outcomes.push(o.outcome());
        }
    }
    let table = case_table(kind, nominal, &outcomes, &nominal_outcome);
    log(&format!("\n{}", study_title(kind)));
    log(&table.to_text());
    let stem = name(kind);
    table.write_csv(&dir.join(format!("{stem}.csv")))?;
    squeal_io::atomic_write_bytes(
        &dir.join(format!("{stem}.md")),
        table.to_markdown().as_bytes(),
    )?;
    branch_table(&outcomes, &nominal_outcome)
        .write_csv(&dir.join(format!("{stem}_branches.csv")))?;
    case_figure(kind, &outcomes, &nominal_outcome, &dir.join(stem), log)?;
    Ok(())
}

fn study_title(kind: Kind) -> &'static str {
    match kind {
        Kind::Pressure => {
            "Piston pressure (paper Table 4): Hopf point and frequency at the crossing"
        }
        Kind::Stiffness => "Contact stiffness k_l, k_nl (paper Table 5)",
        _ => {
            "Pair damping D1 (Mode 1), D2 (Mode 2) in units of the scene's pair ratios (paper Table 6)"
        }
    }
}

fn opt(x: Option<f64>, digits: usize) -> String {
    x.map_or("-".into(), |v| fmt_sig(v, digits))
}

/// The Table 4/5/6 analogue.
fn case_table(
    kind: Kind,
    constants: &Nominal,
    outcomes: &[CaseOutcome],
    nominal: &CaseOutcome,
) -> Table {
    let mut header: Vec<&str> = vec!["case"];
    match kind {
        Kind::Pressure => header.extend(["value", "piston_force_n"]),
        Kind::Stiffness => header.extend(["value", "k_l_sum_n_per_m"]),
        _ => header.extend(["d1", "d2", "d1_over_d2", "zeta1", "zeta2"]),
    }
    header.extend([
        "mu0",
        "mu0_over_nominal",
        "frequency_hz",
        "frequency_shift_hz",
        "mode1",
        "mode1_hz",
        "mode2",
        "mode2_hz",
    ]);
    let mut t = Table::new(header);
    let force = constants.piston_force.0;
    let kl = constants.contact_stiffness.0;
    let (mu_n, f_n) = (nominal.mu0, nominal.frequency_hz);
    for o in outcomes {
        let c = &o.case;
        let mut row = vec![c.number.to_string()];
        match kind {
            Kind::Pressure => row.extend([c.label.clone(), fmt_sig(force * c.pressure, 4)]),
            Kind::Stiffness => row.extend([c.label.clone(), fmt_sci(kl * c.stiffness, 4)]),
            _ => row.extend([
                fmt_sig(c.pair_factors[0], 2),
                fmt_sig(c.pair_factors[1], 2),
                fmt_sig(c.pair_factors[0] / c.pair_factors[1], 2),
                fmt_sig(constants.pair_ratios[0].0 * c.pair_factors[0], 2),
                fmt_sig(constants.pair_ratios[1].0 * c.pair_factors[1], 2),
            ]),
        }
        row.extend([
            opt(o.mu0, 6),
            opt(o.mu0.zip(mu_n).map(|(a, b)| a / b), 4),
            opt(o.frequency_hz, 6),
            opt(o.frequency_hz.zip(f_n).map(|(a, b)| a - b), 3),
            o.pair.map_or("-".into(), |p| format!("#{}", p.0 + 1)),
            opt(o.pair_hz.map(|p| p.0), 5),
            o.pair.map_or("-".into(), |p| format!("#{}", p.1 + 1)),
            opt(o.pair_hz.map(|p| p.1), 5),
        ]);
        t.push_row(row);
    }
    t.align_numbers_right()
}

/// Every case's Mode 2 and Mode 1 branches against μ.
fn branch_table(outcomes: &[CaseOutcome], nominal: &CaseOutcome) -> Table {
    let mu_n = nominal.mu0.unwrap_or(1.0);
    let mut t = Table::new([
        "case",
        "mu",
        "mu_over_mu0_nominal",
        "re_mode2_per_s",
        "f_mode2_hz",
        "re_mode1_per_s",
        "f_mode1_hz",
    ]);
    for o in outcomes {
        let Some(u) = &o.unstable else { continue };
        for k in 0..u.mu.len() {
            let p = o.partner.as_ref().map(|p| p.values[k]);
            t.push_row([
                o.case.number.to_string(),
                format!("{}", u.mu[k]),
                format!("{}", u.mu[k] / mu_n),
                format!("{:e}", u.values[k].re),
                format!("{}", u.values[k].im / (2.0 * std::f64::consts::PI)),
                p.map_or(String::new(), |v| format!("{:e}", v.re)),
                p.map_or(String::new(), |v| {
                    format!("{}", v.im / (2.0 * std::f64::consts::PI))
                }),
            ]);
        }
    }
    t
}

/// The x window of the figures: around μ/μ0 = 1, wide enough for every case's Hopf point.
fn window(outcomes: &[CaseOutcome], mu_n: f64) -> (f64, f64) {
    let r: Vec<f64> = outcomes
        .iter()
        .filter_map(|o| o.mu0)
        .map(|m| m / mu_n)
        .collect();
    let lo = r.iter().copied().fold(0.7f64, |a, b| a.min(b - 0.15));
    let hi = r.iter().copied().fold(1.3f64, |a, b| a.max(b + 0.15));
    (lo.max(0.0), hi)
}

fn curve_points(
    c: &BranchCurve,
    mu_n: f64,
    win: (f64, f64),
    f: impl Fn(c64) -> f64,
) -> Vec<(f64, f64)> {
    c.mu.iter()
        .zip(&c.values)
        .map(|(m, v)| (m / mu_n, f(*v)))
        .filter(|(x, _)| *x >= win.0 && *x <= win.1)
        .collect()
}

/// Two panels (Re λ, f against μ/μ0) for a set of cases: Mode 2 solid, Mode 1 dashed, one
/// colour per case, the Hopf points as markers.
fn case_panels(
    outcomes: &[&CaseOutcome],
    colors: &[usize],
    mu_n: f64,
    letters: (&str, &str),
    what: &str,
) -> (Panel, Panel) {
    let win = window(
        &outcomes.iter().map(|o| (*o).clone()).collect::<Vec<_>>(),
        mu_n,
    );
    let two_pi = 2.0 * std::f64::consts::PI;
    let mut re = Panel {
        title: format!(
            "({}) real parts{what}: Mode 2 solid, Mode 1 dashed",
            letters.0
        ),
        x_label: "mu / mu0 (nominal)".into(),
        y_label: "Re(lambda) (1/s)".into(),
        ..Panel::default()
    };
    let mut fr = Panel {
        title: format!("({}) frequencies{what}", letters.1),
        x_label: "mu / mu0 (nominal)".into(),
        y_label: "frequency (Hz)".into(),
        ..Panel::default()
    };
    for (o, &ci) in outcomes.iter().zip(colors) {
        let color = palette_color(ci);
        let label = format!("{}: {}", o.case.number, o.case.label);
        if let Some(u) = &o.unstable {
            re.series.push(
                Series::line(label.clone(), curve_points(u, mu_n, win, |v| v.re)).with_color(color),
            );
            fr.series.push(
                Series::line(label, curve_points(u, mu_n, win, |v| v.im / two_pi))
                    .with_color(color),
            );
        }
        if let Some(p) = &o.partner {
            re.series.push(
                Series::line("", curve_points(p, mu_n, win, |v| v.re))
                    .with_color(color)
                    .with_dash(Dash::Dashed),
            );
            fr.series.push(
                Series::line("", curve_points(p, mu_n, win, |v| v.im / two_pi))
                    .with_color(color)
                    .with_dash(Dash::Dashed),
            );
        }
        if let (Some(m), Some(f)) = (o.mu0, o.frequency_hz) {
            re.series
                .push(Series::markers("", vec![(m / mu_n, 0.0)]).with_color(color));
            fr.series
                .push(Series::markers("", vec![(m / mu_n, f)]).with_color(color));
        }
    }
    re.annotations.push(Annotation::HLine {
        y: 0.0,
        label: String::new(),
        dash: Dash::Dotted,
    });
    (re, fr)
}

fn case_figure(
    kind: Kind,
    outcomes: &[CaseOutcome],
    nominal: &CaseOutcome,
    stem: &Path,
    log: Log,
) -> Result<()> {
    let mu_n = nominal.mu0.unwrap_or(1.0);
    let all: Vec<&CaseOutcome> = outcomes.iter().collect();
    let colors: Vec<usize> = (0..all.len()).collect();
    let fig = match kind {
        Kind::Damping => {
            // Figure 11: (a, b) equally damped cases 1-3, (c, d) case 1 and the unequal ones.
            let pick = |nums: &[usize]| -> (Vec<&CaseOutcome>, Vec<usize>) {
                all.iter()
                    .enumerate()
                    .filter(|(_, o)| nums.contains(&o.case.number))
                    .map(|(i, o)| (*o, i))
                    .unzip()
            };
            let (eq, ceq) = pick(&[1, 2, 3]);
            let (ne, cne) = pick(&[1, 4, 5, 6, 7]);
            let (a, b) = case_panels(&eq, &ceq, mu_n, ("a", "b"), ", equal damping");
            let (c, d) = case_panels(&ne, &cne, mu_n, ("c", "d"), ", unequal damping");
            Figure {
                title: "Pair damping D1/D2 (paper Figure 11)".into(),
                panels: vec![a, b, c, d],
                layout: Layout::Grid { columns: 2 },
                ..Figure::default()
            }
        }
        _ => {
            let (a, b) = case_panels(&all, &colors, mu_n, ("a", "b"), "");
            let title = if kind == Kind::Pressure {
                "Piston pressure (paper Figure 9 (a, b))"
            } else {
                "Contact stiffness (paper Figure 10 (a, b))"
            };
            Figure {
                title: title.into(),
                panels: vec![a, b],
                ..Figure::default()
            }
        }
    };
    for n in write_svg_and_png(&fig, stem)? {
        log(&format!("note: {n}"));
    }
    Ok(())
}

/// Creates a folder (and its parents), naming it in the error.
pub(crate) fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|error| PipelineError::File {
        what: "creating the folder",
        path: dir.to_path_buf(),
        error,
    })
}

/// Whether an analysis stopped because the brake has no Hopf point in the band (a result),
/// rather than because something failed.
fn no_hopf_point(e: &PipelineError) -> bool {
    match e {
        PipelineError::Context { error, .. } => no_hopf_point(error),
        PipelineError::Brake(squeal_brake::BrakeError::NoPairFound)
        | PipelineError::NoHopfPoint { .. } => true,
        _ => false,
    }
}
