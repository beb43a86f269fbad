//! The paper's sections 4–5 for a scene: the brake's limit cycle by CHBM from the unstable
//! mode at μ, with the tables, figures and the ParaView series `squeal chbm` writes.

use crate::error::{PipelineError, Result, json_text};
use crate::model::{Log, Model};
use crate::shapes::{Meshes, PartFields, write_brake_vtu};
use squeal_brake::analysis::LinearStability as Stability;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::ChbmOptions;
use squeal_chbm::physics::{SlidingMargin, sliding_margin_of};
use squeal_chbm::start::start_at;
/// The CHBM solution types the pipeline hands out.
pub use squeal_chbm::{ChbmSolution, ChbmStart, Outcome, RESTART_AMPLITUDES};
use squeal_report::{Annotation, Dash, Figure, Panel, Scale, Series, Table, write_svg_and_png};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Where CHBM starts at μ: the equilibrium and the in-band unstable mode of largest growth
/// (on the stability analysis' frictionless reference), and the brake in modal coordinates.
pub fn start(
    m: &Model,
    st: &Stability,
    mu: f64,
    guess: Option<&[f64]>,
) -> Result<(ChbmStart, ModalBrake)> {
    let start = start_at(
        &m.brake,
        &st.reference,
        mu,
        &m.sweep.band,
        &m.sweep.newton,
        guess,
    )?;
    Ok((start, ModalBrake::new(&m.brake, &st.reference, mu)))
}

/// CHBM from each initial amplitude in turn until a limit cycle converges (`log` is told of
/// each attempt that does not); the last attempt when none does.
pub fn solve_with_restarts(
    mb: &ModalBrake,
    start: &ChbmStart,
    opts: &ChbmOptions,
    amplitudes: &[f64],
    log: Log,
) -> Result<(ChbmSolution, f64)> {
    let mut last = None;
    for &a in amplitudes {
        let o = {
            let mut o = opts.clone();
            o.amplitude = a;
            o
        };
        let sol = squeal_chbm::solve(mb, start, &o)?;
        if sol.outcome == Outcome::LimitCycle {
            return Ok((sol, a));
        }
        log(&format!("from initial amplitude p = {a}: {}", sol.outcome));
        last = Some((sol, a));
    }
    last.ok_or_else(|| PipelineError::input("initial amplitudes", "none given"))
}

/// A cycle of the branch at the friction asked for.
pub struct BranchCycle {
    /// Index of the branch point before it.
    pub after_point: usize,
    /// The cycle (nonlinear dofs).
    pub cycle: squeal_chbm::branch::BranchPoint,
    /// Its stability by Hill's method (`None`: not computed, with the reason logged).
    pub stability: Option<squeal_chbm::floquet::CycleStability>,
    /// Its largest Floquet multiplier modulus.
    pub largest_multiplier: Option<f64>,
}

impl BranchCycle {
    /// `"stable"`, `"unstable"`, ... or that it was not computed.
    pub fn verdict(&self) -> String {
        self.stability
            .map_or("stability not computed".to_string(), |s| s.to_string())
    }
}

/// The crossings of `mu` by the branch, one line each (frequency, loudest pair's peak-to-peak
/// closure, stability and largest multiplier), as `squeal chbm` prints them.
pub fn crossings_text(mu: f64, crossings: &[BranchCycle]) -> String {
    let mut s = format!(
        "the branch crosses mu = {mu:.6} {} time(s):\n",
        crossings.len()
    );
    for (k, c) in crossings.iter().enumerate() {
        let (pair, p2p) = c.cycle.loudest();
        let multiplier = c
            .largest_multiplier
            .map_or(String::new(), |r| format!(" (largest multiplier {r:.5})"));
        let _ = writeln!(
            s,
            "  {}. after branch point {}: {:.4} Hz, pair {} {:.3} um peak to peak, {}{multiplier}",
            k + 1,
            c.after_point,
            c.cycle.frequency_hz(),
            pair + 1,
            p2p * 1e6,
            c.verdict(),
        );
    }
    s
}

/// What [`solve_along_branch`] found: every crossing of μ, and CHBM from the chosen one with
/// its start (the equilibrium at μ and the in-band mode nearest the cycle's frequency).
pub type AlongBranch = (Vec<BranchCycle>, Option<(usize, ChbmStart, ChbmSolution)>);

/// CHBM at `mu` reached along the branch of limit cycles from the Hopf point (issue 10,
/// item 5): the branch is followed with CHBM's harmonics up to `mu`, every crossing of `mu` is
/// corrected and its stability computed, and CHBM starts from the chosen one — the first
/// stable crossing, else the first — below μ0 as well as above. The chosen index is `None`
/// when the branch does not reach `mu`: no limit cycle of the branch there.
pub fn solve_along_branch(
    m: &Model,
    st: &Stability,
    mu: f64,
    opts: &ChbmOptions,
    log: Log,
) -> Result<AlongBranch> {
    use squeal_chbm::bifurcation::cycle_of;
    use squeal_chbm::branch::{BranchOptions, Harmonics, cycles_at, follow_from_hopf};
    use squeal_chbm::floquet::{CycleStability as Verdict, HillOptions, hill};
    let Some(nf) = crate::stability::normal_form(m, st)? else {
        let sw = &st.sweep.points;
        return Err(PipelineError::NoHopfPoint {
            from: sw.first().map_or(f64::NAN, |p| p.equilibrium.mu),
            to: sw.last().map_or(f64::NAN, |p| p.equilibrium.mu),
            what: "a limit cycle along the branch",
        });
    };
    let mb = &ModalBrake::new(&m.brake, &st.reference, mu);
    let ratio = mu / nf.mu0;
    let bopts = {
        let mut o = BranchOptions::default();
        o.harmonics = Harmonics::Fixed(opts.harmonics);
        o.samples = opts.samples;
        o.range = (ratio.min(0.5) * 0.99, ratio.max(1.3) * 1.01);
        o
    };
    let mb0 = ModalBrake::new(&m.brake, &st.reference, nf.mu0);
    let branch = follow_from_hopf(&mb0, &nf, &bopts)?;
    log(&format!(
        "branch with {} harmonics: {} cycles in {:.2} s ({})",
        opts.harmonics,
        branch.points.len(),
        branch.time.as_secs_f64(),
        branch.stop
    ));
    let mut crossings = Vec::new();
    for (after_point, cycle) in cycles_at(&mb0, &branch, mu, &bopts)? {
        let f = cycle_of(&mb0, &cycle, opts.samples)
            .and_then(|c| hill(mb, &c, &HillOptions::default()));
        if let Err(e) = &f {
            log(&format!(
                "stability of the branch cycle after point {after_point} not computed: {e}"
            ));
        }
        crossings.push(BranchCycle {
            after_point,
            stability: f.as_ref().ok().map(|f| f.stability()),
            largest_multiplier: f.as_ref().ok().map(|f| f.largest_multiplier()),
            cycle,
        });
    }
    let chosen = crossings
        .iter()
        .position(|c| c.stability == Some(Verdict::Stable))
        .or(if crossings.is_empty() { None } else { Some(0) });
    let Some(i) = chosen else {
        return Ok((crossings, None));
    };
    let c = &crossings[i].cycle;
    let guess = squeal_chbm::Guess {
        nl_coeffs: &c.nl_coeffs,
        omega: c.omega,
        lambda: faer::c64::new(0.0, c.omega),
    };
    let start = squeal_chbm::start::start_near(
        &m.brake,
        &st.reference,
        mu,
        &m.sweep.band,
        &m.sweep.newton,
        c.omega,
    )?;
    let sol = squeal_chbm::solve_from_guess(mb, &start, opts, Some(guess))?;
    Ok((crossings, Some((i, start, sol))))
}

/// Physical dof of a point's direction in the brake: of the disc, of a pad by its name, or of
/// the first pad (`"pad"` in a brake whose pads have other names).
pub fn point_dof(m: &Model, part: &str, role_contact_index: usize, direction: u8) -> Option<usize> {
    let (name, offset) = if part == "disc" {
        ("disc", m.layout.disc.start)
    } else {
        let (name, range) = m
            .layout
            .pads
            .iter()
            .find(|p| p.0 == part)
            .or_else(|| m.layout.pads.first().filter(|_| part == "pad"))?;
        (name.as_str(), range.start)
    };
    let rp = m.rom.part(name)?;
    // Interface modes ([reduction] interface): no coordinate is one point's motion.
    if rp.info.dofs.len() != rp.size() {
        return None;
    }
    let point = rp
        .info
        .points
        .iter()
        .enumerate()
        .filter(|(_, pt)| pt.role == squeal_reduce::rom::PointRole::Contact)
        .nth(role_contact_index)?
        .0;
    rp.info
        .dofs
        .iter()
        .position(|l| *l == squeal_reduce::rom::DofLabel::Point { point, direction })
        .map(|d| offset + d)
}

/// How labels name the first pad: `pad` in a one-pad brake, else e.g. `inboard pad`.
pub fn first_pad_label(m: &Model) -> String {
    match m.layout.pads.as_slice() {
        [(name, _), _, ..] => format!("{name} pad"),
        _ => "pad".to_string(),
    }
}

/// A solution as the lines `squeal chbm` prints: outcome, frequency, residuals, checks,
/// contact state and the amplitudes of three contact dofs.
pub fn solution_text(m: &Model, start: &ChbmStart, s: &ChbmSolution) -> String {
    let mut out = String::new();
    let f = s.omega / (2.0 * std::f64::consts::PI);
    let _ = writeln!(
        out,
        "CHBM, {} harmonics, {} time samples: {}",
        s.harmonics, s.samples, s.outcome
    );
    let _ = writeln!(
        out,
        "  frequency {:.4} Hz ({:+.4} Hz from the linear mode it started from, {:.4} Hz)",
        f,
        f - start.lambda.im / (2.0 * std::f64::consts::PI),
        start.lambda.im / (2.0 * std::f64::consts::PI)
    );
    let _ = writeln!(
        out,
        "  residuals: ||f1||/||F_eq|| = {:.2e}, Re lambda = {:.2e} 1/s (|Re|/omega = {:.1e}); {} LM iterations ({}) in {:.1} ms",
        s.f1,
        s.re_lambda,
        s.re_lambda.abs() / s.omega,
        s.iterations,
        s.stop,
        s.time.as_secs_f64() * 1e3
    );
    let _ = writeln!(
        out,
        "  checks: aliasing (2x samples) {:.1e}, recovery of the nonlinear dofs {:.1e}",
        s.aliasing, s.recovery_error
    );
    let open: Vec<String> = s
        .open_fraction
        .iter()
        .enumerate()
        .filter(|(_, f)| **f > 0.0)
        .map(|(i, f)| format!("pair {} open {:.0}% of the cycle", i + 1, f * 100.0))
        .collect();
    let _ = writeln!(
        out,
        "  contact: {}",
        if open.is_empty() {
            "closed over the whole cycle".into()
        } else {
            open.join(", ")
        }
    );
    let _ = writeln!(out, "  sliding: {}", sliding_text(&sliding(m, s)));
    let mut t = Table::new(["dof", "mean (um)", "H1 (um)", "H2 (um)", "H3 (um)"]);
    let pad = first_pad_label(m);
    for (name, part, dir) in [
        (format!("{pad} contact 5, normal"), "pad", 2u8),
        ("disc contact 5, normal".to_string(), "disc", 2),
        (format!("{pad} contact 5, sliding"), "pad", 0),
    ] {
        if let Some(d) = point_dof(m, part, 4, dir) {
            let mut row = vec![name];
            for k in 0..=3.min(s.harmonics) {
                row.push(format!(
                    "{:+.4}",
                    if k == 0 {
                        s.coeffs[d]
                    } else {
                        s.amplitude(d, k)
                    } * 1e6
                ));
            }
            t.push_row(row);
        }
    }
    out.push_str(&t.to_text());
    out
}

/// The sliding margin of a solution when the scene gives the disc's speed: `Ok(None)` without
/// one, `Err` (in words) when the cycle cannot be measured.
pub fn sliding(m: &Model, s: &ChbmSolution) -> std::result::Result<Option<SlidingMargin>, String> {
    let Some(disc) = &m.disc else {
        return Ok(None);
    };
    let c = s.cycle().map_err(|e| e.to_string())?;
    let all: Vec<usize> = (0..c.n_dofs()).collect();
    sliding_margin_of(
        &m.brake.pairs,
        &all,
        &c,
        &disc.surface_speeds(&m.brake.pairs),
    )
    .map(Some)
    .map_err(|e| e.to_string())
}

/// One line on the sliding margin, with a warning below 1.
pub fn sliding_text(m: &std::result::Result<Option<SlidingMargin>, String>) -> String {
    match m {
        Ok(None) => "not checked (the scene gives no disc speed: [rotation] rpm, or vehicle_speed_kmh with rolling_radius)".into(),
        Err(e) => format!("not checked: {e}"),
        Ok(Some(m)) => format!(
            "disc surface speed / largest tangential vibration velocity = {:.3} at pair {} (smallest over the pairs){}",
            m.min,
            m.pair + 1,
            if m.sliding() {
                ""
            } else {
                "\n  WARNING: below 1 the pad sticks to the disc for part of the cycle: this permanent-sliding cycle is not physical there; it is recomputed below with the scene's stick-slip law ([contact] stick_slip)"
            }
        ),
    }
}

/// `coefficients.csv`, `history.csv`, `chbm.json` and the figures (limit cycles, convergence).
pub fn write_solution(dir: &Path, m: &Model, mu: f64, s: &ChbmSolution) -> Result<()> {
    let n = m.brake.size();
    let mut coeffs = Table::new(["dof", "harmonic", "cos", "sin"]);
    for d in 0..n {
        coeffs.push_row([
            d.to_string(),
            "0".into(),
            format!("{:e}", s.coeffs[d]),
            "0".into(),
        ]);
        for k in 1..=s.harmonics {
            coeffs.push_row([
                d.to_string(),
                k.to_string(),
                format!("{:e}", s.coeffs[(2 * k - 1) * n + d]),
                format!("{:e}", s.coeffs[2 * k * n + d]),
            ]);
        }
    }
    coeffs.write_csv(&dir.join("coefficients.csv"))?;
    let mut hist = Table::new([
        "evaluation",
        "harmonics",
        "f1_relative",
        "re_lambda",
        "omega",
    ]);
    for (i, e) in s.evaluations.iter().enumerate() {
        hist.push_row([
            i.to_string(),
            e.harmonics.to_string(),
            format!("{:e}", e.f1),
            format!("{:e}", e.re_lambda),
            format!("{}", e.omega),
        ]);
    }
    hist.write_csv(&dir.join("history.csv"))?;
    let json = serde_json::json!({
        "outcome": s.outcome.to_string(),
        "converged": matches!(s.outcome, Outcome::LimitCycle),
        "mu": mu,
        "harmonics": s.harmonics,
        "samples": s.samples,
        "frequency_hz": s.omega / (2.0 * std::f64::consts::PI),
        "omega": s.omega,
        "f1_relative": s.f1,
        "re_lambda": s.re_lambda,
        "iterations": s.iterations,
        "time_ms": s.time.as_secs_f64() * 1e3,
        "open_fraction": s.open_fraction,
        "sliding_margin": sliding(m, s).ok().flatten().map(|g| serde_json::json!({
            "min": g.min,
            "pair": g.pair + 1,
            "margins": g.margins,
            "max_tangential_velocity": g.max_tangential_velocity,
        })),
        "aliasing": s.aliasing,
        "layout": "coefficients[b * n + dof], blocks b = [0c, 1c, 1s, 2c, 2s, ...] (eq 25); x(t) = sum_k Ukc cos(k w t) + Uks sin(k w t)",
        "dofs": n,
        "coefficients": s.coeffs,
    });
    squeal_io::atomic_write_bytes(
        &dir.join("chbm.json"),
        json_text(&json, "the CHBM solution")?.as_bytes(),
    )?;
    // Figures: limit cycles, histories, power per harmonic.
    let mut panels = Vec::new();
    for (title, part) in [
        (
            format!("(a) {} contact point 5, normal", first_pad_label(m)),
            "pad",
        ),
        ("(b) disc contact point 5, normal".to_string(), "disc"),
    ] {
        if let Some(d) = point_dof(m, part, 4, 2) {
            panels.push(Panel {
                title,
                x_label: "displacement (m)".into(),
                y_label: "velocity (m/s)".into(),
                series: vec![Series::line(
                    format!("CHBM {} harmonics", s.harmonics),
                    cycle_points(s, d, 256),
                )],
                ..Panel::default()
            });
        }
    }
    write_svg_and_png(
        &Figure {
            title: "Limit cycles (the paper's Figure 4)".into(),
            panels,
            ..Figure::default()
        },
        &dir.join("limit_cycles"),
    )?;
    let res: Vec<(f64, f64)> = s
        .evaluations
        .iter()
        .enumerate()
        .map(|(i, e)| (i as f64, e.f1))
        .collect();
    let rel: Vec<(f64, f64)> = s
        .evaluations
        .iter()
        .enumerate()
        .map(|(i, e)| (i as f64, e.re_lambda))
        .collect();
    // Where the ladder switches from one harmonic to all of them: a marked line on both
    // panels (the residual jumps there).
    let switches: Vec<Annotation> = s
        .evaluations
        .windows(2)
        .enumerate()
        .filter(|(_, w)| w[0].harmonics != w[1].harmonics)
        .map(|(i, w)| Annotation::VLine {
            x: i as f64 + 0.5,
            label: format!("{} → {} harmonics", w[0].harmonics, w[1].harmonics),
            dash: Dash::Dashed,
        })
        .collect();
    let fig = Figure {
        title: "Convergence (the paper's Figures 6-7)".into(),
        panels: vec![
            Panel {
                title: "(a) real part of the tracked eigenvalue".into(),
                x_label: "residual evaluation".into(),
                y_label: "Re λ (1/s)".into(),
                series: vec![Series::line_markers("Re λ", rel)],
                annotations: switches.clone(),
                ..Panel::default()
            },
            Panel {
                title: "(b) harmonic balance residual".into(),
                x_label: "residual evaluation".into(),
                y_label: "‖f1‖ / ‖F_eq‖".into(),
                y_scale: Scale::Log,
                series: vec![Series::line_markers("f1", res)],
                annotations: switches,
                ..Panel::default()
            },
        ],
        ..Figure::default()
    };
    write_svg_and_png(&fig, &dir.join("convergence"))?;
    Ok(())
}

/// `(x(t), x'(t))` of dof `d` over one period.
pub fn cycle_points(s: &ChbmSolution, d: usize, samples: usize) -> Vec<(f64, f64)> {
    let n = s.coeffs.len() / (2 * s.harmonics + 1);
    (0..=samples)
        .map(|j| {
            let th = 2.0 * std::f64::consts::PI * j as f64 / samples as f64;
            let mut x = s.coeffs[d];
            let mut v = 0.0;
            for k in 1..=s.harmonics {
                let (c, sn) = (s.coeffs[(2 * k - 1) * n + d], s.coeffs[2 * k * n + d]);
                let kf = k as f64;
                x += c * (kf * th).cos() + sn * (kf * th).sin();
                v += s.omega * kf * (-c * (kf * th).sin() + sn * (kf * th).cos());
            }
            (x, v)
        })
        .collect()
}

/// Writes `frames` snapshots of the limit cycle on both meshes and a `.pvd` collection;
/// returns the `.pvd` path.
pub fn write_cycle_vtu(
    dir: &Path,
    m: &Model,
    s: &ChbmSolution,
    frames: usize,
    log: Log,
) -> Result<PathBuf> {
    let meshes = Meshes::read(m, log)?;
    let parts = meshes.parts(m)?;
    let n = m.brake.size();
    let period = 2.0 * std::f64::consts::PI / s.omega;
    let mut entries = Vec::new();
    let frames_dir = dir.join("cycle");
    for f in 0..frames {
        let th = 2.0 * std::f64::consts::PI * f as f64 / frames as f64;
        let x: Vec<f64> = (0..n)
            .map(|d| {
                let mut v = s.coeffs[d];
                for k in 1..=s.harmonics {
                    let kf = k as f64;
                    v += s.coeffs[(2 * k - 1) * n + d] * (kf * th).cos()
                        + s.coeffs[2 * k * n + d] * (kf * th).sin();
                }
                v
            })
            .collect();
        let mean: Vec<f64> = (0..n).map(|d| s.coeffs[d]).collect();
        let dynamic: Vec<f64> = x.iter().zip(&mean).map(|(a, b)| a - b).collect();
        let stem = format!("cycle_{f:03}");
        let fields = [
            PartFields {
                name: "displacement",
                brake: x,
            },
            PartFields {
                name: "oscillation",
                brake: dynamic,
            },
        ];
        write_brake_vtu(&frames_dir, &stem, &parts, &fields)?;
        entries.push((
            period * f as f64 / frames as f64,
            format!("cycle/{stem}.vtm"),
        ));
    }
    let pvd = dir.join("cycle.pvd");
    squeal_mesh::vtu::write_pvd(&pvd, &entries)?;
    Ok(pvd)
}
