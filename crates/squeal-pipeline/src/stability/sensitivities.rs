//! What to change: the derivatives of the unstable mode's eigenvalue and of μ0 with respect to
//! the brake's parameters at the Hopf point ([`squeal_brake::sensitivity`]), ranked as
//! "change X by 1 %: μ0 moves by …" (`sensitivities.csv`, `sensitivities.json`, and the lines
//! `squeal stability` prints).

use crate::error::{Result, json_text};
use crate::model::Model;
use squeal_brake::analysis::LinearStability as Stability;
use squeal_brake::linearized::LinearizedBrake;
use squeal_brake::sensitivity::{HopfState, Parameter, Rate, Sensitivities, hopf_state};
use squeal_report::Table;
use std::fmt::Write as _;
use std::path::Path;

/// One parameter's row.
#[derive(Clone, Debug)]
pub struct Row {
    /// What is changed, in words (`Young's modulus of disc`).
    pub name: String,
    /// Its kind (`contact_stiffness`, `damping_ratio`, `youngs_modulus`, `density`,
    /// `piston_load`).
    pub kind: &'static str,
    /// The parameter.
    pub parameter: Parameter,
    /// Its derivatives per unit relative change.
    pub rate: Rate,
}

impl Row {
    /// How far μ0 moves for a 1 % increase.
    pub fn mu0_per_percent(&self) -> f64 {
        0.01 * self.rate.dmu0.unwrap_or(0.0)
    }
}

/// The ranked sensitivities at the Hopf point.
#[derive(Clone, Debug)]
pub struct Ranked {
    /// The polished Hopf point they are taken at.
    pub state: HopfState,
    /// `dλ/dμ` there (s⁻¹ and rad/s per unit μ).
    pub dlambda_dmu: faer::c64,
    /// `|x||y| / |yᴴ T'(λ) x|`: the eigenvalue's condition.
    pub condition: f64,
    /// Every parameter, largest `|dμ0/ds|` first.
    pub rows: Vec<Row>,
    /// Wall time (s).
    pub seconds: f64,
}

/// The parameters of a model: the contact stiffness (all pairs, each pad, each pair), the
/// piston load, each part's Young's modulus and density, the damping ratio of every mode
/// together and of each.
pub fn parameters(m: &Model, st: &Stability) -> Vec<(String, &'static str, Parameter)> {
    let np = m.brake.pairs.len();
    let mut out = vec![(
        "contact stiffness, every pair".to_string(),
        "contact_stiffness",
        Parameter::ContactStiffness((0..np).collect()),
    )];
    if m.layout.pads.len() > 1 {
        for (name, _) in &m.layout.pads {
            let pairs = (0..np).filter(|&p| m.pairs[p].pad == *name).collect();
            out.push((
                format!("contact stiffness, pad {name}"),
                "contact_stiffness",
                Parameter::ContactStiffness(pairs),
            ));
        }
    }
    for p in 0..np {
        out.push((
            format!("contact stiffness, pair {}", p + 1),
            "contact_stiffness",
            Parameter::ContactStiffness(vec![p]),
        ));
    }
    out.push((
        "piston load".to_string(),
        "piston_load",
        Parameter::PistonLoad,
    ));
    let parts = std::iter::once(("disc".to_string(), m.layout.disc.clone()))
        .chain(m.layout.pads.iter().cloned());
    for (name, r) in parts {
        out.push((
            format!("Young's modulus of {name}"),
            "youngs_modulus",
            Parameter::Stiffness(r.clone()),
        ));
        out.push((
            format!("density of {name}"),
            "density",
            Parameter::Density(r),
        ));
    }
    let n = st.reference.basis.omega.len();
    out.push((
        "damping ratio of every mode".to_string(),
        "damping_ratio",
        Parameter::ModalDamping((0..n).collect()),
    ));
    for j in 0..n {
        out.push((
            format!(
                "damping ratio of mode {} ({:.1} Hz)",
                j + 1,
                st.reference.basis.omega[j] / std::f64::consts::TAU
            ),
            "damping_ratio",
            Parameter::ModalDamping(vec![j]),
        ));
    }
    out
}

/// The sensitivities at the sweep's Hopf point; `None` without one.
pub fn compute(m: &Model, st: &Stability) -> Result<Option<Ranked>> {
    let Some(h) = &st.sweep.hopf else {
        return Ok(None);
    };
    let t = std::time::Instant::now();
    let lr = LinearizedBrake::new(&m.brake, &st.reference)?;
    let tau = super::threshold(m, st);
    let opts = &m.sweep;
    let state = hopf_state(&m.brake, &lr, h, tau, &opts.newton, &opts.continuation)?;
    let s = Sensitivities::new(&m.brake, &st.reference, &lr, &state)?;
    let mut rows: Vec<Row> = parameters(m, st)
        .into_iter()
        .map(|(name, kind, parameter)| Row {
            rate: s.rate(&parameter),
            name,
            kind,
            parameter,
        })
        .collect();
    rows.sort_by(|a, b| {
        b.mu0_per_percent()
            .abs()
            .total_cmp(&a.mu0_per_percent().abs())
    });
    let (dlambda_dmu, condition) = (s.dlambda_dmu(), s.condition());
    Ok(Some(Ranked {
        state,
        dlambda_dmu,
        condition,
        rows,
        seconds: t.elapsed().as_secs_f64(),
    }))
}

/// The ranked table's first `count` rows and the friction slope, as `squeal stability`
/// prints them.
pub fn text(r: &Ranked, count: usize) -> String {
    let mut out = String::new();
    let mu0 = r.state.mu;
    let _ = writeln!(
        out,
        "what moves mu0 = {mu0:.8} (left and right eigenvectors at the polished Hopf point, equilibrium change included; {:.2} s): dRe(lambda)/dmu = {:.4e} 1/s, df/dmu = {:.4e} Hz",
        r.seconds,
        r.dlambda_dmu.re,
        r.dlambda_dmu.im / std::f64::consts::TAU
    );
    let _ = writeln!(
        out,
        "  change by +1 %                         mu0 moves by        (%)   Re(lambda) by (1/s)   f0 by (Hz)"
    );
    for row in r.rows.iter().take(count) {
        let d = row.mu0_per_percent();
        let _ = writeln!(
            out,
            "  {:<38} {:>+12.4e} {:>+9.4} {:>+18.4e} {:>+12.4}",
            row.name,
            d,
            100.0 * d / mu0,
            0.01 * row.rate.dlambda.re,
            0.01 * row.rate.dfrequency_hz
        );
    }
    let _ = writeln!(
        out,
        "  ({} parameters in sensitivities.csv; a larger mu0 is a quieter brake)",
        r.rows.len()
    );
    out
}

/// `sensitivities.csv` and `sensitivities.json`.
pub fn write(dir: &Path, r: &Ranked) -> Result<()> {
    let mut t = Table::new([
        "rank",
        "parameter",
        "kind",
        "dmu0_per_percent",
        "dmu0_relative_per_percent",
        "dre_lambda_per_percent_per_s",
        "dfrequency_per_percent_hz",
        "dre_lambda_ds_per_s",
        "dim_lambda_ds_rad_per_s",
        "dmu0_ds",
    ]);
    let mu0 = r.state.mu;
    for (k, row) in r.rows.iter().enumerate() {
        let d = row.mu0_per_percent();
        t.push_row([
            (k + 1).to_string(),
            row.name.clone(),
            row.kind.to_string(),
            format!("{d:e}"),
            format!("{:e}", d / mu0),
            format!("{:e}", 0.01 * row.rate.dlambda.re),
            format!("{:e}", 0.01 * row.rate.dfrequency_hz),
            format!("{:e}", row.rate.dlambda.re),
            format!("{:e}", row.rate.dlambda.im),
            format!("{:e}", row.rate.dmu0.unwrap_or(f64::NAN)),
        ]);
    }
    t.write_csv(&dir.join("sensitivities.csv"))?;
    let json = serde_json::json!({
        "mu0": mu0,
        "frequency_hz": r.state.pair.lambda.im / std::f64::consts::TAU,
        "threshold_per_s": r.state.tau,
        "newton_steps": r.state.iterations,
        "dre_lambda_dmu_per_s": r.dlambda_dmu.re,
        "dfrequency_dmu_hz": r.dlambda_dmu.im / std::f64::consts::TAU,
        "eigenvalue_condition": r.condition,
        "equilibrium": "included: each parameter moves the static equilibrium at mu0 and the frictionless one the modes and damping are taken at",
        "parameters": "relative changes s (value x (1 + s)); per_percent = 0.01 d/ds",
        "rows": r.rows.iter().map(|row| serde_json::json!({
            "parameter": row.name,
            "kind": row.kind,
            "dmu0_per_percent": row.mu0_per_percent(),
            "dre_lambda_per_percent_per_s": 0.01 * row.rate.dlambda.re,
            "dfrequency_per_percent_hz": 0.01 * row.rate.dfrequency_hz,
        })).collect::<Vec<_>>(),
    });
    squeal_io::atomic_write_bytes(
        &dir.join("sensitivities.json"),
        json_text(&json, "the sensitivities")?.as_bytes(),
    )?;
    Ok(())
}
