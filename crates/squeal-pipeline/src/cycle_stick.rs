//! `squeal chbm` and `squeal run`'s single limit cycle where the pads stick (issue 24, item 4):
//! when the scene gives the disc's speed and the CHBM cycle's sliding margin is below 1, the
//! permanent-sliding law is wrong for part of the period, and the cycle is recomputed at the
//! same μ with the scene's stick–slip law (`[contact] stick_slip`), as `squeal branch` does
//! for its cycles ([`crate::branch_stick`]):
//!
//! - `"regularized"` (the default): each pair's element made to stick, `F_t(|v|) tanh(v /
//!   v_reg)` with `v_reg` a twentieth of the slowest pair's disc speed, 24 harmonics and the
//!   branch's AFT samples ([`squeal_chbm::stick_dlft::regularized_cycle`]);
//! - `"dlft"`: exact Coulomb stick–slip by the dynamic Lagrangian frequency–time method
//!   ([`squeal_chbm::stick_dlft::dlft_cycle`], docs/stick_slip.md), 24 harmonics; when the
//!   solve from the CHBM cycle stops short, from the V/20 regularized cycle
//!   ([`squeal_chbm::stick_dlft_starts`]), and when that stops short too, continued in μ from
//!   a lower μ where DLFT converges from that μ's own CHBM cycle ([`crate::cycle_walk`], the
//!   branch's walk); if the walk does not reach μ the recomputation fails with its report
//!   instead of giving an approximate cycle.
//!
//! Both start from the CHBM cycle (permanent sliding) at fixed μ. The text says which law, the
//! new frequency and loudest closure with their changes, the new margin and, for DLFT, how
//! much of the period each pair sticks and whether the solve met its tolerance, and for a
//! converged DLFT cycle its stability under the exact law ([`add_stability`]: the Floquet
//! analysis of the non-smooth law that `squeal branch` gives its DLFT cycles,
//! [`squeal_chbm::stick_floquet::brake::dlft_floquet`]); `<out>/chbm/stick_slip.json` has the
//! same.

use crate::branch_dlft::DLFT_STARTS;
use crate::cycle_walk::{SingleWalk, walk_from_below};
use crate::error::{Result, json_text};
use crate::model::Model;
use squeal_brake::analysis::LinearStability as Stability;
use squeal_brake::modal_brake::ModalBrake;
use squeal_chbm::ChbmSolution;
use squeal_chbm::branch::{BranchPoint, pair_cycles};
use squeal_chbm::physics::SlidingMargin;
use squeal_chbm::stick_branch::{StickOptions, point_margin, surface_speeds};
use squeal_chbm::stick_dlft::{DlftCycle, DlftOptions, regularized_cycle};
use squeal_chbm::stick_dlft_starts::dlft_from_starts;
use squeal_chbm::stick_floquet::StickSlipFloquet;
use squeal_chbm::stick_floquet::brake::dlft_floquet;
use squeal_hbm::{HarmonicLayout, PhaseCondition};
use squeal_scene::StickSlipSetting;
use std::path::Path;

/// Harmonics of the recomputed cycle (the branch's sticking default).
const HARMONICS: usize = 24;

/// The single cycle recomputed with the stick–slip law.
pub struct CycleStick {
    /// The law, in words.
    pub law: String,
    /// The CHBM cycle (permanent sliding) as a point, and its margin.
    pub sliding: BranchPoint,
    /// Its sliding margin (below 1).
    pub margin: SlidingMargin,
    /// The recomputed cycle.
    pub cycle: BranchPoint,
    /// Its sliding margin.
    pub stick_margin: SlidingMargin,
    /// DLFT only: the fraction of the period each pair sticks.
    pub stick_fractions: Option<Vec<f64>>,
    /// Whether the solve met its residual tolerance (the residual is in `cycle`).
    pub converged: bool,
    /// DLFT only, when it stopped short: why, and the starts tried
    /// ([`squeal_chbm::stick_dlft_starts::StartedDlft::reason`]).
    pub reason: String,
    /// DLFT only, when the direct starts stopped short and the cycle was continued in μ from
    /// below ([`crate::cycle_walk`]): the walk; with the direct starts' reason in `reason`.
    pub walk: Option<SingleWalk>,
    /// μ0 when the stability analysis found it (else the cycle's μ): the walk's μ are told as
    /// ratios to it.
    pub mu_ref: f64,
    /// DLFT only: the solved cycle (its samples and penalties, for the Floquet analysis).
    pub dlft: Option<DlftCycle>,
    /// The exact law's Floquet analysis of a converged DLFT cycle and its seconds, once
    /// [`add_stability`] ran (`None` before, and for the regularized law).
    pub stability: Option<(std::result::Result<StickSlipFloquet, String>, f64)>,
}

/// The stability of `c`'s cycle under the exact law, when it is a converged DLFT cycle: the
/// Floquet analysis of the non-smooth law (`squeal_chbm::stick_floquet`, default options), as
/// `squeal branch` gives its DLFT cycles; stored in `c.stability` with its time.
pub fn add_stability(m: &Model, st: &Stability, c: &mut CycleStick) {
    let Some(d) = c.dlft.as_ref().filter(|_| c.converged) else {
        return;
    };
    let t = std::time::Instant::now();
    let mb = ModalBrake::new(&m.brake, &st.reference, d.point.parameter);
    let f = dlft_floquet(&mb, d, &Default::default()).map_err(|e| e.to_string());
    c.stability = Some((f, t.elapsed().as_secs_f64()));
}

/// The CHBM solution `sol` at `mu` as a branch point of `mb`.
pub(crate) fn as_point(mb: &ModalBrake, mu: f64, sol: &ChbmSolution) -> Result<BranchPoint> {
    let layout =
        HarmonicLayout::new(mb.nl(), sol.harmonics).map_err(squeal_chbm::ChbmError::from)?;
    Ok(BranchPoint {
        parameter: mu,
        omega: sol.omega,
        harmonics: sol.harmonics,
        pairs: pair_cycles(mb, &layout, &sol.nl_coeffs),
        truncation: squeal_chbm::branch::truncation(&layout, &sol.nl_coeffs),
        nl_coeffs: sol.nl_coeffs.clone(),
        parameter_rate: 0.0,
        iterations: sol.iterations,
        residual: 0.0,
    })
}

/// The cycle `sol` at `mu` recomputed with `law` when its sliding margin is below 1 (`Ok(None)`:
/// no disc speed, or the margin is at least 1; `Err`: it could not be set up, or with DLFT no
/// start nor walk in μ reached a converged cycle, with what was tried).
pub fn recompute(
    m: &Model,
    st: &Stability,
    law: StickSlipSetting,
    mu: f64,
    sol: &ChbmSolution,
) -> std::result::Result<Option<CycleStick>, String> {
    if m.disc.is_none() || m.brake.pairs.iter().any(|p| p.surface_speed.is_none()) {
        return Ok(None);
    }
    let mb = ModalBrake::new(&m.brake, &st.reference, mu);
    let mu_ref = st.sweep.hopf.as_ref().map_or(mu, |h| h.mu0);
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let speeds = surface_speeds(&mb).map_err(|e| err(&e))?;
    let sliding = as_point(&mb, mu, sol).map_err(|e| err(&e))?;
    let margin = point_margin(&mb, &sliding, &speeds).map_err(|e| err(&e))?;
    if margin.sliding() {
        return Ok(None);
    }
    let layout = HarmonicLayout::new(mb.nl(), sol.harmonics).map_err(|e| err(&e))?;
    let PhaseCondition::FirstSineZero { dof } =
        PhaseCondition::strongest_dof(&layout, &sol.nl_coeffs).map_err(|e| err(&e))?;
    let mut o = DlftOptions::default();
    o.harmonics = Some(HARMONICS);
    let mut reason = String::new();
    let mut walk = None;
    let mut dlft = None;
    let (law_text, cycle, converged, fractions) = match law {
        StickSlipSetting::Regularized => {
            let v_min = speeds.iter().copied().fold(f64::INFINITY, f64::min);
            let v_reg = StickOptions::default().regularization * v_min;
            o.samples = Some(StickOptions::default().samples_for(HARMONICS));
            let (c, ok) =
                regularized_cycle(&mb, mu, v_reg, &sliding, dof, &o).map_err(|e| err(&e))?;
            let text = format!(
                "regularized Coulomb (each pair's element F_t(|v|) tanh(v/v_reg)), v_reg = {v_reg:.4e} m/s (1/20 of the slowest pair's disc speed), {HARMONICS} harmonics"
            );
            (text, c, ok, None)
        }
        StickSlipSetting::Dlft { epsilon_factor } => {
            o.epsilon_factor = epsilon_factor;
            // The direct starts get a walk step's iterations: where they converge they took
            // 22-33 (coarse brake at 3 km/h, 1.0364 and 1.0452 mu0); one that stalls runs to
            // the limit, and the walk from below reaches the same converged cycle.
            o.lm.max_iterations = squeal_chbm::stick_dlft_walk::WalkOptions::default().iterations;
            let s =
                dlft_from_starts(&mb, mu, &sliding, dof, &o, &DLFT_STARTS).map_err(|e| err(&e))?;
            reason = s.reason();
            let mut d = s.cycle;
            if !d.converged {
                let (c, w) = walk_from_below(m, st, &mb, mu, &o)?;
                let Some(c) = c else {
                    let ref_name = if mu_ref == mu { "mu" } else { "mu0" };
                    return Err(format!(
                        "exact stick-slip (DLFT) reached no converged cycle at {:.5} {ref_name}: from the CHBM cycle and the V/20 start it stopped short ({reason}); {}; {}",
                        mu / mu_ref,
                        w.text(mu_ref, ref_name),
                        if w.from_mu.is_some() {
                            "the walk did not reach this mu"
                        } else {
                            "no lower mu converged to start a walk from"
                        }
                    ));
                };
                d = c;
                walk = Some(w);
            }
            let text = format!(
                "exact Coulomb stick-slip (dynamic Lagrangian frequency-time method, Nacivet et al. 2003), {HARMONICS} harmonics, {} samples, penalty {epsilon_factor} x default",
                d.samples
            );
            let out = (
                text,
                d.point.clone(),
                d.converged,
                Some(d.stick_fractions.clone()),
            );
            dlft = Some(d);
            out
        }
    };
    let stick_margin = point_margin(&mb, &cycle, &speeds).map_err(|e| err(&e))?;
    Ok(Some(CycleStick {
        law: law_text,
        sliding,
        margin,
        cycle,
        stick_margin,
        stick_fractions: fractions,
        converged,
        reason,
        walk,
        mu_ref,
        dlft,
        stability: None,
    }))
}

/// What the recomputation found, for the terminal.
pub fn text(c: &CycleStick) -> String {
    let (pair, p2p) = c.sliding.loudest();
    let q = &c.cycle;
    let p2q = q.pairs[pair].peak_to_peak();
    let mut s = format!(
        "stick-slip: the sliding margin {:.3} is below 1, so the cycle is recomputed at the same mu with {}:\n  {:.4} Hz (permanent sliding {:.4} Hz, {:+.2e}), pair {} {:.3} um peak to peak (was {:.3} um, {:+.2} %), sliding margin {:.3}",
        c.margin.min,
        c.law,
        q.frequency_hz(),
        c.sliding.frequency_hz(),
        q.omega / c.sliding.omega - 1.0,
        pair + 1,
        p2q * 1e6,
        p2p * 1e6,
        100.0 * (p2q / p2p - 1.0),
        c.stick_margin.min,
    );
    if let Some(f) = &c.stick_fractions {
        let most = f.iter().copied().fold(0.0, f64::max);
        s += &format!(", pairs stick up to {:.1} % of the period", 100.0 * most);
    }
    if let Some(w) = &c.walk {
        let ref_name = if c.mu_ref == q.parameter { "mu" } else { "mu0" };
        s += &format!(
            "\n  DLFT stopped short from the CHBM cycle and the V/20 start at this mu ({}), so the cycle was continued in mu from below, as squeal branch does: {}",
            c.reason,
            w.text(c.mu_ref, ref_name)
        );
    }
    match &c.stability {
        Some((Ok(f), secs)) => {
            s += &format!(
                "\n  stability with the exact law: {}",
                crate::branch_dlft::floquet_words(f, *secs)
            )
        }
        Some((Err(e), _)) => s += &format!("\n  stability with the exact law not computed ({e})"),
        None => {}
    }
    if !c.converged {
        s += &format!(
            "\n  NOTE: the solve stopped short of its tolerance (relative residual {:.1e}): the recomputed cycle is approximate",
            q.residual
        );
        if !c.reason.is_empty() {
            s += &format!(" ({})", c.reason);
        }
    }
    s.push('\n');
    s
}

/// `stick_slip.json` in `dir`.
pub fn write(dir: &Path, c: &CycleStick) -> Result<()> {
    let (pair, _) = c.sliding.loudest();
    let json = serde_json::json!({
        "law": c.law,
        "margin_before": c.margin.min,
        "margin_after": c.stick_margin.min,
        "frequency_hz_before": c.sliding.frequency_hz(),
        "frequency_hz_after": c.cycle.frequency_hz(),
        "loudest_pair": pair + 1,
        "peak_to_peak_m_before": c.sliding.pairs[pair].peak_to_peak(),
        "peak_to_peak_m_after": c.cycle.pairs[pair].peak_to_peak(),
        "stick_fractions": c.stick_fractions,
        "converged": c.converged,
        "relative_residual": c.cycle.residual,
        "harmonics": c.cycle.harmonics,
        "layout": "nl_coefficients[b * n_nl + dof] on the nonlinear dofs, blocks b = [0c, 1c, 1s, 2c, 2s, ...] (eq 25)",
        "nl_coefficients": c.cycle.nl_coeffs,
        "walk": c.walk.as_ref().map(|w| w.json()),
        "direct_starts": if c.walk.is_some() { Some(&c.reason) } else { None },
        "stability": c.stability.as_ref().map(|(f, secs)| match f {
            Ok(f) => serde_json::json!({
                "verdict": f.stability().to_string(),
                "leading_exponent_re": f.leading().map(|e| e.sigma.re),
                "leading_exponent_im": f.leading().map(|e| e.sigma.im.abs()),
                "error": f.error(),
                "seconds": secs,
            }),
            Err(e) => serde_json::json!({ "error_text": e }),
        }),
    });
    squeal_io::atomic_write_bytes(
        &dir.join("stick_slip.json"),
        json_text(&json, "the stick-slip cycle")?.as_bytes(),
    )?;
    Ok(())
}

/// The single-cycle stage's part: the cycle `sol` of `p` at `mu` recomputed with the scene's
/// stick–slip law when its margin is below 1, written to `dir`; the text to tell (`None`:
/// nothing to recompute). A recomputation that fails is told, not an error of the stage.
pub fn stage(
    p: &crate::Pipeline,
    mu: f64,
    sol: &ChbmSolution,
    dir: &Path,
) -> Result<Option<String>> {
    let law = p.scene.stick_slip_law()?;
    let m = p.model()?;
    let st = p.stability()?;
    match recompute(m, st, law, mu, sol) {
        Ok(None) => Ok(None),
        Ok(Some(mut c)) => {
            add_stability(m, st, &mut c);
            write(dir, &c)?;
            Ok(Some(text(&c)))
        }
        Err(e) => {
            // No stale cycle of an earlier run next to this one's: the file says what failed.
            let name = match law {
                StickSlipSetting::Regularized => "regularized",
                StickSlipSetting::Dlft { .. } => "dlft",
            };
            let json = serde_json::json!({ "law": name, "error": e });
            squeal_io::atomic_write_bytes(
                &dir.join("stick_slip.json"),
                json_text(&json, "the stick-slip failure")?.as_bytes(),
            )?;
            Ok(Some(format!(
                "stick-slip: the sliding margin is below 1 but the cycle could not be recomputed with the stick-slip law: {e}\n"
            )))
        }
    }
}
