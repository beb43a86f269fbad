//! `[reduction]`: how far the reduced model is reduced beyond Craig–Bampton.
//!
//! ```toml
//! [reduction]
//! interface = "system"        # "none" (the default); "system": each contact face's motion
//!                             # restricted to that of the assembled brake's real modes,
//!                             # friction residual and static vectors; "cc": characteristic
//!                             # constraint modes of each part's contact face (nodal contact)
//! interface_modes = "auto"    # "auto" (by convergence of mu0 and its frequency) or a number
//!                             # of CC modes per part
//! interface_tolerance = 1e-3  # "auto": the relative change of mu0 and of its frequency
//!                             # between two counts below which the larger count is kept
//! ```

use crate::{Result, Scene};
use serde::Deserialize;
use toml::Spanned;

/// Default relative tolerance of the interface modes' convergence.
pub const DEFAULT_INTERFACE_TOLERANCE: f64 = 1e-3;

/// `[reduction]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReductionSection {
    /// `"none"` or `"cc"`.
    #[serde(default = "default_interface")]
    pub interface: Spanned<String>,
    /// `"auto"` or a positive number of CC modes per part.
    #[serde(default = "default_modes")]
    pub interface_modes: Spanned<toml::Value>,
    /// Relative tolerance of `"auto"`.
    #[serde(default = "default_tolerance")]
    pub interface_tolerance: Spanned<f64>,
}

impl Default for ReductionSection {
    fn default() -> Self {
        Self {
            interface: default_interface(),
            interface_modes: default_modes(),
            interface_tolerance: default_tolerance(),
        }
    }
}

fn default_interface() -> Spanned<String> {
    Spanned::new(0..0, "none".into())
}
fn default_modes() -> Spanned<toml::Value> {
    Spanned::new(0..0, toml::Value::String("auto".into()))
}
fn default_tolerance() -> Spanned<f64> {
    Spanned::new(0..0, DEFAULT_INTERFACE_TOLERANCE)
}

/// How many CC modes each part keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InterfaceModeCount {
    /// Doubled until μ0 and its frequency change by less than `tolerance` (relative).
    Auto {
        /// Relative change of μ0 and of its frequency.
        tolerance: f64,
    },
    /// This many per part (at most the part's contact-face dofs).
    Fixed(usize),
}

/// Which vectors span the contact faces' motion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InterfaceBasis {
    /// Characteristic constraint modes of each part's face (`"cc"`).
    Cc,
    /// The face rows of the assembled brake's real modes, friction residual and static
    /// vectors (`"system"`).
    System,
}

/// The interface reduction a scene asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InterfaceReduction {
    /// How many modes.
    pub modes: InterfaceModeCount,
    /// Which basis.
    pub basis: InterfaceBasis,
}

impl Scene {
    /// `[reduction] interface`: `None` without an interface reduction, else its mode count.
    pub fn interface_reduction(&self) -> Result<Option<InterfaceReduction>> {
        let r = &self.file.reduction;
        let basis = match r.interface.get_ref().as_str() {
            "none" => return Ok(None),
            "cc" => InterfaceBasis::Cc,
            "system" => InterfaceBasis::System,
            other => {
                return Err(self.error_at(
                    "reduction.interface",
                    &r.interface,
                    format!("'{other}' is not 'none', 'system' or 'cc'"),
                ));
            }
        };
        let iface = self.file.model.interface.get_ref();
        if iface != "nodal" && iface != "node" {
            return Err(self.error_at(
                "reduction.interface",
                &r.interface,
                format!(
                    "an interface reduction reduces contact faces kept node by node: it needs model.interface = \"nodal\" (this scene has \"{iface}\")"
                ),
            ));
        }
        let tolerance = *r.interface_tolerance.get_ref();
        if !(tolerance > 0.0 && tolerance <= 0.1) {
            return Err(self.error_at(
                "reduction.interface_tolerance",
                &r.interface_tolerance,
                format!("must be in (0, 0.1] (got {tolerance})"),
            ));
        }
        let v = &r.interface_modes;
        let modes = match v.get_ref() {
            toml::Value::String(s) if s == "auto" => InterfaceModeCount::Auto { tolerance },
            toml::Value::Integer(n) if *n >= 1 => InterfaceModeCount::Fixed(*n as usize),
            _ => {
                return Err(self.error_at(
                    "reduction.interface_modes",
                    v,
                    "must be \"auto\" or a number of modes >= 1",
                ));
            }
        };
        Ok(Some(InterfaceReduction { modes, basis }))
    }
}
