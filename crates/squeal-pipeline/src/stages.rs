//! The stages as the commands run them, and `squeal run`'s plan: each stage computes (through
//! [`Pipeline`], once), tells what it found through the pipeline's log (the command line's
//! standard output), writes its folder, and returns its result. The command line only parses
//! flags into the plans and chooses the exit code.
//!
//! [`run`] is the whole job: reduced model → stability → (when the brake has a Hopf point) the
//! branch of limit cycles → the scene's limit cycle by CHBM → its comparison with time
//! integration → the report, in that order, with each stage's time recorded for the report.

use crate::branch::{self, BranchAnalysis, BranchOptions, HillOptions};
use crate::compare::{self, CompareSettings, CompareSummary};
use crate::cycle::{CyclePlan, CycleStart, LimitCycle};
use crate::error::{PipelineError, Result};
use crate::report::{self, RunResults, build};
use crate::{Pipeline, chbm, stability};
use squeal_chbm::{ChbmSolution, ChbmStart, Outcome};
use squeal_scene::CycleFriction;
use std::time::Instant;

/// Tells a block of text (lines ending in `\n`) through the pipeline's log, a line at a time.
fn tell(p: &Pipeline, text: &str) {
    for line in text.strip_suffix('\n').unwrap_or(text).split('\n') {
        (p.log())(line);
    }
}

/// The stability stage: the verdict first (a stable brake, "stable for mu in [a, b]", is an
/// answer, not an error), the contact pairs, the sweep's summary and the Hopf point's
/// criticality; the tables, figures and (with `vtu`) ParaView shapes in `<out>/stability`.
pub fn stability_stage(p: &Pipeline, vtu: bool) -> Result<stability::Verdict> {
    let m = p.model()?;
    let t = Instant::now();
    let st = p
        .stability()
        .map_err(|e| e.in_stage("stability analysis"))?;
    let verdict = stability::verdict(m, st);
    tell(p, &format!("{verdict}\n"));
    tell(p, &stability::pairs_text(m));
    let dir = p.out.join("stability");
    tell(
        p,
        &stability::summary_text(m, st, t.elapsed().as_secs_f64()),
    );
    match stability::normal_form(m, st) {
        Ok(Some(nf)) => tell(p, &stability::criticality_text(m, st, &nf)),
        Ok(None) => {}
        Err(e) => tell(
            p,
            &format!("criticality of the Hopf point not computed: {e}\n"),
        ),
    }
    stability::write_tables(&dir, m, st)?;
    stability::write_figures(&dir, st, m)?;
    tell(p, &stability::write_makeup(&dir, m, st, p.log())?);
    if vtu {
        let vtm = stability::write_shapes(&dir, m, st, p.log())?;
        tell(
            p,
            &format!(
                "mode shape and equilibria for ParaView: {}\n",
                vtm.display()
            ),
        );
    }
    tell(p, &format!("results in {}\n", dir.display()));
    Ok(verdict)
}

/// The branch stage: the branch of limit cycles from the Hopf point with each cycle's Floquet
/// stability and sound level, with the cycles at the multiples `at` of μ0, into
/// `<out>/branch`; `None` when the brake has no Hopf point.
pub fn branch_stage(
    p: &Pipeline,
    opts: &BranchOptions,
    at: &[f64],
) -> Result<Option<BranchAnalysis>> {
    branch_stage_with(p, opts, at, &crate::branch_torus::TorusPlan::off())
}

/// [`branch_stage`] continuing past the Neimark–Sacker points onto the torus branches as
/// `torus` says ([`crate::branch_torus`]).
pub fn branch_stage_with(
    p: &Pipeline,
    opts: &BranchOptions,
    at: &[f64],
    torus: &crate::branch_torus::TorusPlan,
) -> Result<Option<BranchAnalysis>> {
    let m = p.model()?;
    let st = p
        .stability()
        .map_err(|e| e.in_stage("stability analysis"))?;
    let t = Instant::now();
    let mus: Vec<f64> = match &st.sweep.hopf {
        Some(h) => at.iter().map(|r| r * h.mu0).collect(),
        None => Vec::new(),
    };
    let Some(mut a) = branch::analyse(m, st, opts, &HillOptions::default(), &mus, p.log())? else {
        tell(
            p,
            "no Hopf point in the band of the friction sweep: no branch of limit cycles\n",
        );
        return Ok(None);
    };
    p.record("branch and its stability", t.elapsed().as_secs_f64());
    if torus.enabled {
        let t = Instant::now();
        a.tori = crate::branch_torus::follow(m, st, &a, opts, torus, p.log());
        p.record(
            "torus branches and their stability",
            t.elapsed().as_secs_f64(),
        );
    }
    let t = Instant::now();
    a.two_mode = crate::branch_two_mode::run(p, st, &a);
    if a.two_mode.is_some() {
        p.record(
            "second unstable mode: the generalized CHBM",
            t.elapsed().as_secs_f64(),
        );
    }
    let t = Instant::now();
    a.stick = crate::branch_stick::recompute(m, st, &a, opts, &Default::default(), p.log());
    let dlft = crate::branch_dlft::recompute(m, st, &a, p.scene.stick_slip_law()?);
    if let Some(r) = a.stick.as_mut() {
        r.dlft = dlft;
    }
    if a.stick.is_some() {
        p.record("branch with sticking contact", t.elapsed().as_secs_f64());
    }
    let t = Instant::now();
    (a.levels, a.microphone) =
        crate::sound::branch_levels_or_log(&p.scene, m, st, &a, opts.samples, &p.sound, p.log());
    p.record("sound of the branch's cycles", t.elapsed().as_secs_f64());
    tell(p, &branch::summary_text(&a));
    let dir = p.out.join("branch");
    branch::write(&dir, &a)?;
    if let Some(Ok(r)) = a.two_mode.as_ref().map(|s| &s.answer) {
        crate::two_mode::write(&dir, r)?;
    }
    tell(p, &format!("results in {}\n", dir.display()));
    Ok(Some(a))
}

/// The limit-cycle stage: the cycle of `plan`, how it was reached and what it is (with its
/// sound level), written to `<out>/chbm` (and, with `vtu`, as a ParaView time series).
pub fn cycle_stage(p: &Pipeline, plan: &CyclePlan, vtu: bool) -> Result<LimitCycle> {
    let what = match plan.start {
        CycleStart::Branch => "the branch of limit cycles starts at the Hopf point",
        CycleStart::Guessed { .. } => "the limit cycle's friction",
    };
    let mu = match plan.at {
        CycleFriction::Mu(m) => m,
        CycleFriction::Ratio(_) => p.cycle_mu(plan.at).map_err(|e| e.in_stage(what))?,
    };
    if plan.start == CycleStart::Branch {
        let mu0 = p.mu0().map_err(|e| e.in_stage(what))?;
        tell(
            p,
            &format!(
                "Hopf point mu0 = {mu0:.6}; limit cycle at mu = {mu:.6} ({:.4} mu0), along the branch from the Hopf point\n",
                mu / mu0
            ),
        );
    } else if let Some(h) = &p.stability()?.sweep.hopf {
        tell(
            p,
            &format!(
                "Hopf point mu0 = {:.6}; limit cycle at mu = {mu:.6} ({:.4} mu0)\n",
                h.mu0,
                mu / h.mu0
            ),
        );
    }
    let lc = p.limit_cycle(plan).map_err(|e| {
        e.in_stage(if plan.start == CycleStart::Branch {
            "the branch of limit cycles"
        } else {
            "the start at mu"
        })
    })?;
    tell(p, &how_reached(&lc, plan));
    if let Some((start, sol)) = &lc.solved {
        write_solution(p, lc.mu, start, sol, vtu)?;
    }
    Ok(lc)
}

/// How CHBM reached the cycle: the branch's crossings of μ and the one it started from, or
/// the unstable mode and the initial amplitude of the guessed start.
fn how_reached(lc: &LimitCycle, plan: &CyclePlan) -> String {
    let mu = lc.mu;
    match (&plan.start, &lc.solved) {
        (CycleStart::Branch, _) if lc.crossings.is_empty() => format!(
            "the branch of limit cycles ({} harmonics) does not reach mu = {mu:.6}: the brake has no limit cycle of this branch there (see squeal branch for where it has)\n",
            plan.options.harmonics
        ),
        (CycleStart::Branch, _) => {
            let mut s = chbm::crossings_text(mu, &lc.crossings);
            if let Some(i) = lc.chosen {
                s += &format!(
                    "CHBM starts from cycle {} ({})\n",
                    i + 1,
                    lc.crossings[i].verdict()
                );
            }
            s
        }
        (CycleStart::Guessed { amplitudes }, Some((start, sol))) => {
            let l = start.lambda;
            let mut s = format!(
                "unstable mode at mu: lambda = {:.3} + {:.3}i (growth {:.3} 1/s, {:.2} Hz)\n",
                l.re,
                l.im,
                l.re,
                l.im / std::f64::consts::TAU
            );
            if sol.outcome == Outcome::LimitCycle
                && amplitudes.len() > 1
                && let Some(a) = lc.amplitude
            {
                s += &format!("(initial amplitude p = {a} of the smallest static penetration)\n");
            }
            s
        }
        (CycleStart::Guessed { .. }, None) => String::new(),
    }
}

/// Tells a solution and writes it to `<out>/chbm`.
fn write_solution(
    p: &Pipeline,
    mu: f64,
    start: &ChbmStart,
    sol: &ChbmSolution,
    vtu: bool,
) -> Result<()> {
    let m = p.model()?;
    tell(p, &chbm::solution_text(m, start, sol));
    if sol.outcome == Outcome::LimitCycle {
        tell(
            p,
            &crate::sound::solution_sound_text(&p.scene, m, sol, &p.sound, p.log()),
        );
    }
    let dir = p.out.join("chbm");
    chbm::write_solution(&dir, m, mu, sol)?;
    if sol.outcome == Outcome::LimitCycle
        && let Some(t) = crate::cycle_stick::stage(p, mu, sol, &dir)?
    {
        tell(p, &t);
    }
    if vtu
        && matches!(
            sol.outcome,
            Outcome::LimitCycle | Outcome::LimitCycleUnconstrained
        )
    {
        let pvd = chbm::write_cycle_vtu(&dir, m, sol, 24, p.log())?;
        tell(
            p,
            &format!("limit cycle for ParaView (24 frames): {}\n", pvd.display()),
        );
    }
    tell(p, &format!("results in {}\n", dir.display()));
    Ok(())
}

/// The comparison stage: CHBM against time integration into `<out>/compare`.
pub fn compare_stage(p: &Pipeline, settings: &CompareSettings) -> Result<CompareSummary> {
    let dir = p.out.join("compare");
    let t = Instant::now();
    let summary = compare::run(p, None, settings, &dir)?;
    p.record("comparison", t.elapsed().as_secs_f64());
    tell(p, &format!("\nresults in {}\n", dir.display()));
    Ok(summary)
}

/// What `squeal run` does beyond the scene: the branch's options, the limit cycle's plan and
/// the comparison's settings (`None`: no comparison, the slowest stage).
#[derive(Clone, Debug)]
pub struct RunPlan {
    pub branch: BranchOptions,
    pub cycle: CyclePlan,
    pub compare: Option<CompareSettings>,
}

impl RunPlan {
    /// The scene's plan: the default branch, the scene's limit cycle and the default
    /// comparison.
    pub fn of_scene(p: &Pipeline) -> Result<Self> {
        Ok(Self {
            branch: BranchOptions::default(),
            cycle: CyclePlan::of_scene(&p.scene)?,
            compare: Some(CompareSettings::default()),
        })
    }
}

/// What a whole run found.
pub struct RunOutcome {
    pub verdict: stability::Verdict,
    pub branch: Option<BranchAnalysis>,
    pub cycle: Option<LimitCycle>,
    pub compare: Option<CompareSummary>,
    /// The notes of the report's build (figures left out and why).
    pub report_notes: Vec<String>,
}

/// The whole job of `plan` on `p`'s scene, ending with the report in `p.out` (see the module
/// documentation). A stable brake skips the stages that need a Hopf point.
pub fn run(p: &Pipeline, plan: &RunPlan) -> Result<RunOutcome> {
    if let Some(c) = &plan.compare {
        c.validate()?;
    }
    // An earlier run's report must not describe this run's files if this run stops early.
    let removed = crate::folder::remove_earlier(&p.out, report::is_report_file);
    if !removed.is_empty() {
        tell(
            p,
            &format!(
                "removed the earlier run's report ({} files); this run writes its own at the end\n",
                removed.len()
            ),
        );
    }
    tell(p, "== 1. reduced model\n");
    p.model()?;
    tell(p, "\n== 2. stability\n");
    let verdict = stability_stage(p, true)?;
    let (mut branch, mut cycle, mut compare) = (None, None, None);
    if verdict.is_stable() {
        tell(
            p,
            &format!(
                "\n== 3-5. skipped: {verdict}; without a Hopf point there is no limit cycle to follow, solve or compare\n"
            ),
        );
    } else {
        tell(p, "\n== 3. branch of limit cycles and their stability\n");
        branch = branch_stage(p, &plan.branch, &[])?;
        tell(p, "\n== 4. limit cycle (CHBM)\n");
        cycle = Some(cycle_stage(p, &plan.cycle, true)?);
        if let Some(settings) = &plan.compare {
            tell(p, "\n== 5. CHBM against time integration\n");
            compare = Some(compare_stage(p, settings)?);
        }
    }
    tell(p, "\n== 6. report\n");
    let timings = p.timings();
    let results = RunResults {
        scene: &p.scene,
        model: p.model()?,
        stability: p.stability()?,
        branch: branch.as_ref(),
        chbm: cycle.as_ref(),
        compare: compare.as_ref(),
        timings: &timings,
        sound: &p.sound,
    };
    let report_notes = build(&results, &p.out, p.log())
        .map_err(|e| e.in_stage("the report's pictures"))?
        .write(&p.out)
        .map_err(|e| PipelineError::from(e).in_stage("writing the report"))?;
    Ok(RunOutcome {
        verdict,
        branch,
        cycle,
        compare,
        report_notes,
    })
}
