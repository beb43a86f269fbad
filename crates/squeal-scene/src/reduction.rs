//! `[reduction]`: how far the reduced model is reduced beyond Craig–Bampton.
//!
//! ```toml
//! [reduction]
//! interface = "system"        # "none"; "system": each contact face's motion restricted to
//!                             # that of the assembled brake's real modes, friction residual
//!                             # and static vectors; "cc": characteristic constraint modes of
//!                             # each part's contact face. Default: "system" with nodal
//!                             # contact, "none" with patch contact (nothing to reduce)
//! interface_modes = "auto"    # "auto" (by convergence) or a number of modes
//! interface_tolerance = 5e-3  # "auto": "system", the relative change of the in-band
//!                             # eigenvalues at the sweep's first, middle and last friction
//!                             # value between two levels (default 5e-3); "cc", of mu0 and
//!                             # its frequency between two counts (default 1e-3)
//! ```
//!
//! **Why `"system"` is the default with nodal contact.** Nodal contact keeps every contact
//! node's dofs as Craig–Bampton boundary, so the reduced brake grows with the pairs (2234 dofs
//! on the coarse one-pad brake, 2939 on the medium ventilated one); the `"system"` basis keeps
//! each face's motion to the brake's in-band real modes, their friction residuals and the
//! static vectors (267 and 510 dofs), with μ0 within 3e-5 and 1e-6 of the unreduced-interface
//! brake's on the coarse one-pad and ventilated brakes, and its level is chosen by comparing
//! eigenvalues at three friction values instead of whole sweeps (docs/reduction.md, "Interface
//! reduction").

use crate::{Result, Scene};
use serde::Deserialize;
use toml::Spanned;

/// Default relative tolerance of the CC modes' convergence (`"cc"`): the change of μ0 and its
/// frequency between two counts.
pub const DEFAULT_INTERFACE_TOLERANCE: f64 = 1e-3;

/// Default relative tolerance of `"system"`'s levels: the largest change of an in-band
/// eigenvalue, `|Δλ| / |λ|`, between two levels at the sweep's first, middle and last friction
/// value. Measured from the in-band modes alone to those with their friction residuals:
/// 2.1e-3, 1.5e-4, 2.6e-4 on the coarse one-pad, coarse and medium ventilated nodal brakes,
/// while μ0 moved by 2.2e-4, 7e-5, 6e-6 between the same levels (the worst eigenvalue, far
/// past the onset, is 10-40 times more sensitive than μ0), and the second level's μ0 is within
/// 3e-5 and 2e-7 of the unreduced interface's (docs/reduction.md, "The default with nodal
/// contact").
pub const DEFAULT_SYSTEM_TOLERANCE: f64 = 5e-3;

/// `[reduction]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReductionSection {
    /// `"none"`, `"system"` or `"cc"`; absent: `"system"` with nodal contact, else `"none"`.
    #[serde(default)]
    pub interface: Option<Spanned<String>>,
    /// `"auto"` or a positive number of CC modes per part.
    #[serde(default = "default_modes")]
    pub interface_modes: Spanned<toml::Value>,
    /// Relative tolerance of `"auto"` (absent: the basis's default).
    #[serde(default)]
    pub interface_tolerance: Option<Spanned<f64>>,
}

impl Default for ReductionSection {
    fn default() -> Self {
        Self {
            interface: None,
            interface_modes: default_modes(),
            interface_tolerance: None,
        }
    }
}

fn default_modes() -> Spanned<toml::Value> {
    Spanned::new(0..0, toml::Value::String("auto".into()))
}

/// How many CC modes each part keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InterfaceModeCount {
    /// By convergence: `"cc"` doubles its count until μ0 and its frequency change by less than
    /// `tolerance` (relative); `"system"` adds to its basis until the in-band eigenvalues at
    /// three friction values change by less than `tolerance` (relative).
    Auto {
        /// Relative change of μ0 and of its frequency (`"cc"`), of the eigenvalues
        /// (`"system"`).
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
    /// Absent, nodal contact takes `"system"` with `"auto"` (module documentation), with parts
    /// beyond the disc and the pads too (`[parts.*]`, `[[connectors]]`: their dofs are kept
    /// whole, only the contact faces are reduced), and patch contact none.
    pub fn interface_reduction(&self) -> Result<Option<InterfaceReduction>> {
        let r = &self.file.reduction;
        let iface = self.file.model.interface.get_ref();
        let nodal = iface == "nodal" || iface == "node";
        let Some(written) = &r.interface else {
            if !nodal {
                return Ok(None);
            }
            return self.interface_count(InterfaceBasis::System).map(|modes| {
                Some(InterfaceReduction {
                    modes,
                    basis: InterfaceBasis::System,
                })
            });
        };
        let basis = match written.get_ref().as_str() {
            "none" => return Ok(None),
            "cc" => InterfaceBasis::Cc,
            "system" => InterfaceBasis::System,
            other => {
                return Err(self.error_at(
                    "reduction.interface",
                    written,
                    format!("'{other}' is not 'none', 'system' or 'cc'"),
                ));
            }
        };
        if !nodal {
            return Err(self.error_at(
                "reduction.interface",
                written,
                format!(
                    "an interface reduction reduces contact faces kept node by node: it needs model.interface = \"nodal\" (this scene has \"{iface}\")"
                ),
            ));
        }
        let modes = self.interface_count(basis)?;
        Ok(Some(InterfaceReduction { modes, basis }))
    }

    /// `interface_modes` and `interface_tolerance` (the basis's default when absent).
    fn interface_count(&self, basis: InterfaceBasis) -> Result<InterfaceModeCount> {
        let r = &self.file.reduction;
        let tolerance = match &r.interface_tolerance {
            None if basis == InterfaceBasis::System => DEFAULT_SYSTEM_TOLERANCE,
            None => DEFAULT_INTERFACE_TOLERANCE,
            Some(t) => {
                let tolerance = *t.get_ref();
                if !(tolerance > 0.0 && tolerance <= 0.1) {
                    return Err(self.error_at(
                        "reduction.interface_tolerance",
                        t,
                        format!("must be in (0, 0.1] (got {tolerance})"),
                    ));
                }
                tolerance
            }
        };
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
        Ok(modes)
    }
}
