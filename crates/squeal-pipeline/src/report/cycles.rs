//! The report's sections on the limit cycle, the branch and the comparison with time integration.

use super::*;

pub(super) fn chbm_section(
    r: &RunResults<'_>,
    meshes: Option<&Meshes>,
    pics: &Path,
    log: Log,
) -> Result<Option<Section>> {
    let Some(lc) = r.chbm else {
        return Ok(None);
    };
    let heading = "Limit cycle (CHBM, sections 4-5)".to_string();
    let Some(s) = lc.cycle() else {
        return Ok(Some(Section {
            heading,
            text: format!(
                "No limit cycle at the scene's friction μ = {}: {}.",
                fmt_sig(lc.mu, 6),
                no_cycle_reason(lc)
            ),
            figures: Vec::new(),
            tables: Vec::new(),
            after: String::new(),
        }));
    };
    let mu = lc.mu;
    let m = r.model;
    let mut figures = Vec::new();
    if let Some(meshes) = meshes {
        match write_cycle_animation(pics, "cycle", m, meshes, s, 20) {
            Ok((file, scale)) => figures.push((
                PathBuf::from(PICTURES).join(file),
                format!(
                    "The limit cycle, animated (one period in 20 frames, displacements about the mean exaggerated {scale:.0} times; colour: oscillation magnitude over its largest). The same cycle for ParaView: [chbm/cycle.pvd](chbm/cycle.pvd)"
                ),
            )),
            Err(e) => log(&format!("report: the animation failed: {e}")),
        }
    }
    figures.push((
        PathBuf::from("chbm/limit_cycles"),
        "Phase portraits of a pad and a disc contact point, normal direction (the paper's Figure 4)".into(),
    ));
    figures.push((
        PathBuf::from("chbm/convergence"),
        "Convergence of Re λ (a) and of the harmonic-balance residual (b); the dashed line marks the switch from one harmonic to all (the paper's Figures 6-7)".into(),
    ));
    let mut t = Table::new(["quantity", "value"]);
    let f = s.omega / std::f64::consts::TAU;
    for (label, value) in [
        ("friction μ", fmt_sig(mu, 6)),
        ("harmonics", s.harmonics.to_string()),
        ("frequency (Hz)", fmt_sig(f, 8)),
        ("‖f1‖ / ‖F_eq‖", fmt_sig(s.f1, 3)),
        ("Re λ (1/s)", fmt_sig(s.re_lambda, 3)),
        ("Levenberg–Marquardt iterations", s.iterations.to_string()),
        ("time (ms)", fmt_sig(s.time.as_secs_f64() * 1e3, 3)),
        ("outcome", s.outcome.to_string()),
    ] {
        t.push_row([label.to_string(), value]);
    }
    let mut pairs = Table::new([
        "pair",
        "closure amplitude (µm)",
        "sliding-velocity amplitude (mm/s)",
        "open over the cycle (%)",
    ]);
    for (p, c, v, open) in pair_motion(m, s) {
        pairs.push_row([
            (p + 1).to_string(),
            format!("{:.3}", c * 1e6),
            format!("{:.2}", v * 1e3),
            format!("{:.1}", 100.0 * open),
        ]);
    }
    let stability = lc.chosen.map_or(String::new(), |i| {
        format!(
            " It was reached along the branch of limit cycles from the Hopf point; its Floquet stability (Hill's method): {}.",
            lc.crossings[i].verdict()
        )
    });
    Ok(Some(Section {
        heading,
        text: format!(
            "The periodic self-excited vibration at the scene's friction ([chbm] in the scene), by the Constrained Harmonic \
             Balance Method.{stability} Amplitudes are half the peak-to-peak relative \
             motion of the pad and disc points of each pair (normal: closure; tangential: \
             sliding velocity). Files: [chbm/coefficients.csv](chbm/coefficients.csv) (Fourier \
             coefficients of every dof), [chbm/chbm.json](chbm/chbm.json)."
        ),
        figures,
        tables: vec![
            (
                pairs.align_numbers_right(),
                "The limit cycle at each contact pair".into(),
            ),
            (t, "CHBM solution".into()),
        ],
        after: String::new(),
    }))
}

pub(super) fn branch_section(branch: Option<&crate::branch::BranchAnalysis>) -> Section {
    let Some(a) = branch else {
        return Section {
            heading: "Branch of limit cycles".into(),
            text:
                "The branch of limit cycles was not followed in this run (`squeal branch` does it)."
                    .into(),
            ..Section::default()
        };
    };
    let b = &a.branch;
    let mu0 = a.mu0();
    let mut events = Table::new(["event", "μ", "μ/μ0", "details"]);
    for f in &b.folds {
        events.push_row([
            "fold".to_string(),
            fmt_sig(f.parameter, 6),
            fmt_sig(f.parameter / mu0, 6),
            format!(
                "{:.1} Hz, pair closure {} µm peak to peak{}",
                f.omega / std::f64::consts::TAU,
                fmt_sig(f.closure * 1e6, 3),
                if f.refined {
                    ""
                } else {
                    "; between two points (a contact opens there)"
                }
            ),
        ]);
    }
    for bi in &a.bifurcations {
        let kind = match bi.kind {
            squeal_chbm::bifurcation::BifurcationKind::Fold => "stability change: fold".to_string(),
            squeal_chbm::bifurcation::BifurcationKind::PeriodDoubling => {
                "stability change: period doubling".to_string()
            }
            squeal_chbm::bifurcation::BifurcationKind::NeimarkSacker => format!(
                "stability change: Neimark–Sacker, second frequency {:.0} Hz",
                bi.torus_frequency_hz()
            ),
        };
        events.push_row([
            kind,
            fmt_sig(bi.parameter, 6),
            fmt_sig(bi.parameter / mu0, 6),
            format!(
                "unstable Floquet exponents {} → {}",
                bi.unstable.0, bi.unstable.1
            ),
        ]);
    }
    let pair = a.loudest_pair();
    let mut pts = Table::new([
        "μ/μ0",
        "frequency (Hz)",
        "harmonics",
        &format!("pair {} closure p2p (µm)", pair + 1),
        "largest open fraction (%)",
        "largest |multiplier|",
        "stability",
    ]);
    let n = b.points.len();
    for i in crate::branch::shown_points(n, 12) {
        let p = &b.points[i];
        let (rho, verdict) = match &a.floquet[i] {
            Ok(f) => (
                format!("{:.5}", f.largest_multiplier()),
                f.stability().to_string(),
            ),
            Err(e) => ("–".into(), format!("not computed ({e})")),
        };
        pts.push_row([
            format!("{:.5}", p.parameter / mu0),
            format!("{:.1}", p.frequency_hz()),
            p.harmonics.to_string(),
            fmt_sig(p.pairs[pair].peak_to_peak() * 1e6, 4),
            format!("{:.0}", 100.0 * p.largest_open_fraction()),
            rho,
            verdict,
        ]);
    }
    let mut tables = vec![
        (
            events,
            "Folds and stability changes along the branch".into(),
        ),
        (
            pts.align_numbers_right(),
            "Cycles along the branch (a selection; every one is in branch.csv)".into(),
        ),
    ];
    let mut after: String =
        "Hill's method's own error is the trivial exponent's distance from zero (column \
                hill_error_per_s of branch.csv); a cycle whose leading exponent is within it is \
                reported as marginal."
            .into();
    if let Some((text, table)) = crate::branch_stick::report_part(a) {
        after.push_str("\n\n");
        after.push_str(&text);
        if let Some(t) = table {
            tables.push((t, "Cycles recomputed with contact that sticks (branch/branch_stick.csv: the sticking branch)".into()));
        }
    }
    Section {
        heading: "Branch of limit cycles and their stability".into(),
        text: format!(
            "Every periodic vibration born at the Hopf point, followed in μ through its folds by \
             pseudo-arclength continuation of the harmonic balance (harmonics adapted along the \
             branch), each with its Floquet multipliers by Hill's method: a cycle is stable when \
             every multiplier lies inside the unit circle. {} cycles in {:.1} s, multipliers \
             alongside, done {:.1} s after them; the branch ended because {}. Files: [branch/branch.csv](branch/branch.csv), \
             [branch/branch.json](branch/branch.json).",
            n,
            b.time.as_secs_f64(),
            a.floquet_time.as_secs_f64(),
            b.stop
        ),
        figures: vec![(
            PathBuf::from("branch/branch"),
            "Bifurcation diagram: the loudest pair's peak-to-peak closure (a, and near μ0 in b), \
             the frequency (c) and the largest open fraction (d) against μ; stable cycles solid, \
             unstable dashed"
                .into(),
        )],
        tables,
        after,
    }
}

pub(super) fn compare_section(compare: Option<&CompareSummary>) -> Section {
    let Some(c) = compare else {
        return Section {
            heading: "CHBM against time integration".into(),
            text: "Not run (`squeal run --no-compare`): `squeal compare` makes it.".into(),
            ..Section::default()
        };
    };
    let mut figures = Vec::new();
    let mut tables = Vec::new();
    let mut after = String::new();
    for l in &c.levels {
        let dir = PathBuf::from("compare").join(&l.folder);
        figures.push((
            dir.join("limit_cycles"),
            format!(
                "At {} μ0: CHBM's limit cycles over the reference limit cycle (the paper's Figure 4)",
                fmt_sig(l.ratio, 4)
            ),
        ));
        figures.push((
            dir.join("speed_accuracy"),
            format!("At {} μ0: wall time against error", fmt_sig(l.ratio, 4)),
        ));
        tables.push((
            l.table1.clone(),
            format!(
                "At {} μ0 (μ = {}): errors against the reference limit cycle (the paper's Table 1)",
                fmt_sig(l.ratio, 4),
                fmt_sig(l.mu, 6)
            ),
        ));
        tables.push((
            l.table2.clone(),
            format!(
                "At {} μ0: cost and storage (the paper's Table 2)",
                fmt_sig(l.ratio, 4)
            ),
        ));
        if !l.failures.is_empty() {
            after.push_str(&format!(
                "What did not converge at {} μ0:\n\n",
                fmt_sig(l.ratio, 4)
            ));
            for f in &l.failures {
                after.push_str(&format!("- {f}\n"));
            }
            after.push('\n');
        }
        let links: Vec<String> = l
            .files
            .iter()
            .map(|f| format!("[{f}]({})", dir.join(f).display()))
            .collect();
        after.push_str(&format!(
            "Files at {} μ0: {}.\n\n",
            fmt_sig(l.ratio, 4),
            links.join(", ")
        ));
    }
    Section {
        heading: "CHBM against time integration".into(),
        text: format!(
            "CHBM and variable-step BDF time integration of the whole brake (from the unstable \
             equilibrium to its steady cycle, at the tolerances a user would choose) checked \
             against the reference limit cycle, the brake's periodic orbit by shooting with its \
             own error stated. Errors: {}.",
            c.error_definition
        ),
        figures,
        tables,
        after,
    }
}
