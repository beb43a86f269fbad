//! Plausibility of a scene's values (issue 22: a mistake gives an error or a warning, never a
//! plausible wrong μ0).
//!
//! **Errors**, for values no brake can have: a friction sweep or list with a negative value
//! (eq (9)'s `μ ≥ 0`; the disc's other sense of rotation is `[rotation] sense`, not a
//! negative μ); a damping pair naming one mode twice (eqs (12)-(13) damp two distinct modes);
//! a modal damping ratio of 1 or more on a mode (critically damped: no vibration to squeal,
//! eq (12)'s `2 ζ ω` is then not a modal damping of a vibrating structure); a line pressure
//! above [`MAX_LINE_PRESSURE_BAR`]; a compression curve with a negative or non-finite
//! pressure or closure, or two points at one closure (the fit of eq (8) would take the mean
//! of two pressures at one closure, hiding a typing error).
//!
//! **Warnings** ([`crate::Scene::plausibility_warnings`]), for values possible but far from
//! a passenger-car brake, each with the file, line and key: a line pressure above
//! [`HIGH_LINE_PRESSURE_BAR`], a modal damping ratio above [`HIGH_DAMPING_RATIO`], an
//! initial gap larger than [`LARGE_GAP_M`], friction above [`HIGH_MU`].

use crate::{CompressionCurve, GapSetting, Result, Scene};
use toml::Spanned;

/// Largest accepted line pressure (bar): 1 GPa, above the compressive strength of any
/// lining and some 40 times the highest brake-line pressures (about 250 bar).
pub const MAX_LINE_PRESSURE_BAR: f64 = 1.0e4;
/// Line pressures above this (bar) draw a warning: the top of hydraulic brake lines.
pub const HIGH_LINE_PRESSURE_BAR: f64 = 250.0;
/// Modal damping ratios above this draw a warning: structural damping of a brake's parts is
/// of the order of 0.1-5 %.
pub const HIGH_DAMPING_RATIO: f64 = 0.2;
/// Initial gaps larger than this (m) draw a warning: pads sit within micrometres of the disc
/// under load; a running clearance is 0.1-0.3 mm.
pub const LARGE_GAP_M: f64 = 1.0e-3;
/// Friction coefficients above this draw a warning: brake linings run at 0.3-0.6.
pub const HIGH_MU: f64 = 1.5;

impl Scene {
    /// The errors of the module docs, at the key's line.
    pub(crate) fn check_plausible(&self) -> Result<()> {
        let f = &self.file;
        let p = &f.piston.line_pressure_bar;
        if *p.get_ref() > MAX_LINE_PRESSURE_BAR {
            return Err(self.error_at(
                "piston.line_pressure_bar",
                p,
                format!(
                    "{} bar is beyond any brake (at most {MAX_LINE_PRESSURE_BAR:e} bar here; brake lines run below {HIGH_LINE_PRESSURE_BAR} bar): give the line pressure in bar",
                    p.get_ref()
                ),
            ));
        }
        let d = &f.damping;
        let global = *d.global_ratio.get_ref();
        if global >= 1.0 {
            return Err(self.error_at(
                "damping.global_ratio",
                &d.global_ratio,
                format!(
                    "{global} is a damping ratio of {:.0} %: a mode damped by 100 % or more does not vibrate; give a ratio below 1 (0.01 for 1 %)",
                    global * 100.0
                ),
            ));
        }
        if let Some(r) = &d.pair_ratios {
            let worst = r.get_ref().iter().fold(0.0_f64, |a, b| a.max(*b));
            if global + worst >= 1.0 {
                return Err(self.error_at(
                    "damping.pair_ratios",
                    r,
                    format!(
                        "with global_ratio {global}, a mode of the pair is damped by {:.0} %: the sum must stay below 1 (0.001 for 0.1 %)",
                        (global + worst) * 100.0
                    ),
                ));
            }
        }
        if let Some((a, b)) = self.pair()?
            && a == b
        {
            return Err(self.error_at(
                "damping.pair",
                &d.pair,
                format!(
                    "names mode {} twice: the pair is the two modes that coalesce, give two different modes (or \"auto\")",
                    a + 1
                ),
            ));
        }
        Ok(())
    }

    /// A compression curve's points: finite, pressures and closures zero or positive, no
    /// two points at one closure.
    pub(crate) fn check_curve(&self, curve: &CompressionCurve) -> Result<()> {
        let (p, d) = (&curve.pressure_mpa, &curve.closure_um);
        for (key, v) in [("pressure_mpa", p), ("closure_um", d)] {
            if let Some((i, x)) = v
                .get_ref()
                .iter()
                .enumerate()
                .find(|(_, x)| !(x.is_finite() && **x >= 0.0))
            {
                return Err(self.error_at(
                    &format!("contact.compression_curve.{key}"),
                    v,
                    format!(
                        "point {} is {x}: a compression curve has finite pressures and closures, zero or positive",
                        i + 1
                    ),
                ));
            }
        }
        let mut order: Vec<usize> = (0..d.get_ref().len()).collect();
        order.sort_by(|&i, &j| d.get_ref()[i].total_cmp(&d.get_ref()[j]));
        if let Some(w) = order
            .windows(2)
            .find(|w| d.get_ref()[w[0]] == d.get_ref()[w[1]])
        {
            let (i, j) = (w[0].min(w[1]), w[0].max(w[1]));
            return Err(self.error_at(
                "contact.compression_curve.closure_um",
                d,
                format!(
                    "points {} and {} are both at closure {} um: a curve has one pressure per closure (remove one, or correct the closure)",
                    i + 1,
                    j + 1,
                    d.get_ref()[i]
                ),
            ));
        }
        Ok(())
    }

    /// Warnings about values possible but implausible for a brake (see the module docs),
    /// each `file:line: key: message`.
    pub fn plausibility_warnings(&self) -> Result<Vec<String>> {
        let f = &self.file;
        let mut out = Vec::new();
        let p = &f.piston.line_pressure_bar;
        if *p.get_ref() > HIGH_LINE_PRESSURE_BAR {
            out.push({
                let k = "piston.line_pressure_bar";
                self.warning(k, p, format!("{} bar is above the {HIGH_LINE_PRESSURE_BAR} bar of the highest brake-line pressures: check the value and its unit (bar)", p.get_ref()))
            });
        }
        let g = &f.damping.global_ratio;
        if *g.get_ref() > HIGH_DAMPING_RATIO {
            out.push({
                let k = "damping.global_ratio";
                self.warning(k, g, format!("{} is {:.0} % modal damping on every mode; brake parts have 0.1-5 % (0.01 is 1 %)", g.get_ref(), g.get_ref() * 100.0))
            });
        }
        if let Some(r) = &f.damping.pair_ratios
            && r.get_ref().iter().any(|x| *x > HIGH_DAMPING_RATIO)
        {
            out.push({
                let k = "damping.pair_ratios";
                self.warning(
                    k,
                    r,
                    format!(
                        "a ratio above {HIGH_DAMPING_RATIO} ({:.0} %) on a mode of the pair; the paper's ratios are of 0.1 % (0.001)",
                        HIGH_DAMPING_RATIO * 100.0
                    ),
                )
            });
        }
        let largest = match self.initial_gaps()? {
            GapSetting::Uniform(g) => g.abs(),
            GapSetting::PerPair(g) => g.iter().fold(0.0, |a: f64, b| a.max(b.abs())),
            GapSetting::Geometric | GapSetting::Closed => 0.0,
        };
        if largest > LARGE_GAP_M
            && let Some(v) = &f.contact.initial_gap
        {
            out.push({
                let k = "contact.initial_gap";
                self.warning(k, v, format!("a gap of {largest:e} m: a pad under load sits within micrometres of the disc (running clearance 0.1-0.3 mm); check the value and the [units] length"))
            });
        }
        let mus = self.mu_values()?;
        let top = mus.iter().fold(0.0_f64, |a, b| a.max(*b));
        if top > HIGH_MU {
            let v = f.stability.mu.as_ref();
            out.push({
                let k = "stability.mu";
                let m = format!("the sweep reaches mu = {top}; brake linings run at 0.3-0.6");
                match v {
                    Some(v) => self.warning(k, v, m),
                    None => format!("{}: {k}: {m}", self.path.display()),
                }
            });
        }
        Ok(out)
    }

    /// `file:line: key: message` of a value, for a warning.
    fn warning<T>(&self, key: &str, v: &Spanned<T>, message: impl std::fmt::Display) -> String {
        self.error_at(key, v, message).to_string()
    }
}

/// A friction sweep's values must be zero or positive: `Err` names the first negative one.
pub(crate) fn non_negative_mus(mus: &[f64]) -> std::result::Result<(), String> {
    match mus.iter().find(|m| **m < 0.0) {
        Some(m) => Err(format!(
            "friction {m} is negative: eq (9) takes mu >= 0 (the disc's other sense of rotation is [rotation] sense, not a negative mu); start the sweep at 0 or above"
        )),
        None => Ok(()),
    }
}
