//! The scene as written: one serde struct per TOML section, with each value's source span kept for errors. Nothing outside this crate reads them; [`Scene`](crate::Scene)'s methods turn them into typed values.

use super::*;

/// The scene as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    pub title: Option<String>,
    pub model: ModelSection,
    pub contact: ContactSection,
    pub friction: FrictionSection,
    pub piston: PistonSection,
    #[serde(default)]
    pub damping: DampingSection,
    #[serde(default)]
    pub stability: StabilitySection,
    #[serde(default)]
    pub chbm: ChbmSection,
    /// `[disc]`: the disc's rotation speed, for the sliding check of every limit cycle (the
    /// older form of `[rotation]`).
    #[serde(default)]
    pub disc: DiscSection,
    /// `[rotation]`: the disc's axis, sense and speed.
    pub rotation: Option<RotationSection>,
    /// `[units]`: the unit system of the meshes and of the scene's keys without a unit in
    /// their name (see [`sets`]).
    #[serde(default)]
    pub units: sets::UnitsSection,
    /// `[sets.disc]`, `[sets.pad]`: the node sets the reduction uses, by name or by geometry.
    #[serde(default)]
    pub sets: sets::SetsSection,
    /// `[materials.<ELEMENT_SET>]`: materials by element set, replacing the meshes' own.
    #[serde(default)]
    pub materials: std::collections::BTreeMap<String, sets::MaterialSpec>,
    /// `[pads.<name>]`: the pads of a brake with more than one (instead of `[model] pad`), in
    /// the order of their names.
    #[serde(default)]
    pub pads: std::collections::BTreeMap<String, PadSection>,
    /// `[reduction]`: an interface reduction beyond Craig–Bampton ([`reduction`]).
    #[serde(default)]
    pub reduction: reduction::ReductionSection,
    /// `[sound]`: microphones and air ([`crate::sound`]).
    #[serde(default)]
    pub sound: crate::sound::SoundSection,
    /// `[[supports]]`: springs to ground on node sets of a part ([`crate::assembly`]).
    #[serde(default)]
    pub supports: Vec<crate::assembly::SupportSection>,
    /// `[[ties]]`: tied interfaces inside a part ([`crate::assembly`]).
    #[serde(default)]
    pub ties: Vec<crate::assembly::TieSection>,
    /// `[[springs]]`: springs between node sets of a part or to ground ([`crate::springs`]).
    #[serde(default)]
    pub springs: Vec<crate::springs::SpringSection>,
    /// `[[dampers]]`: viscous dampers between node sets of a part or to ground
    /// ([`crate::dampers`]).
    #[serde(default)]
    pub dampers: Vec<crate::dampers::DamperSection>,
    /// `[parts.<name>]`: parts beyond the disc and the pads ([`crate::parts_keys`]).
    #[serde(default)]
    pub parts: std::collections::BTreeMap<String, crate::parts_keys::BodySection>,
    /// `[[connectors]]`: springs between node sets of two parts or to ground
    /// ([`crate::parts_keys`]).
    #[serde(default)]
    pub connectors: Vec<crate::parts_keys::ConnectorSection>,
}

/// `[pads.<name>]`: one pad of a brake with several (an inboard pad pushed by the pistons, an
/// outboard pad pulled by the caliper's fingers). Every pad is pressed on the disc by the
/// same clamp force (a floating caliper's fingers react the pistons' force).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PadSection {
    /// Its mesh, relative to the scene.
    pub mesh: PathBuf,
    /// The pad as an element set (or a list of them) of `mesh`, when that file holds an
    /// assembly.
    pub elset: Option<Spanned<toml::Value>>,
    /// Where the clamp force enters: the pistons' or the fingers' points (a node set or a
    /// rule, as `[sets.pad] pistons`); default `PISTON`.
    pub load: Option<Spanned<toml::Value>>,
    /// Its friction face (default: `[sets.pad] friction_face`, else `CONTACT_FACE`, else the
    /// face towards the disc).
    pub friction_face: Option<Spanned<toml::Value>>,
    /// Its abutments (default: `[sets.pad] abutments`, else `ABUTMENT`).
    pub abutments: Option<Spanned<toml::Value>>,
    /// What its abutments hold (default: `[sets.pad] abutments_hold`, else the plane normal
    /// to the axis).
    pub abutments_hold: Option<Spanned<toml::Value>>,
    /// The disc face it presses on (default: for the first pad `[sets.disc] contact_face`,
    /// else `CONTACT_FACE`; for the others the pad's friction face projected on the disc).
    pub disc_contact_face: Option<Spanned<toml::Value>>,
    /// The disc's contact nodes under it for the node interface (default `CONTACT` for the
    /// first pad, `CONTACT_<NAME>` for the others).
    pub disc_contact: Option<Spanned<String>>,
}

/// `[rotation]`: the axis the disc turns about, the sense, and (optionally) the speed.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotationSection {
    /// Direction of the axis (need not be unit).
    pub axis: Spanned<[f64; 3]>,
    /// A point of the axis (m); the origin by default.
    pub point: Option<Spanned<[f64; 3]>>,
    /// `"counterclockwise"` (the right-hand rule about `axis`) or `"clockwise"`, seen from the
    /// tip of `axis`.
    pub sense: Spanned<String>,
    /// Disc speed (revolutions per minute).
    pub rpm: Option<Spanned<f64>>,
    /// Vehicle speed (km/h); needs `rolling_radius`.
    pub vehicle_speed_kmh: Option<Spanned<f64>>,
    /// The wheel's effective rolling radius (m): the disc turns at `v / r`.
    pub rolling_radius: Option<Spanned<f64>>,
}

/// The disc's rotation, resolved: `ω = sense · Ω · axis` about the line through `point`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rotation {
    /// A point of the axis (m).
    pub point: [f64; 3],
    /// Unit direction of the axis.
    pub axis: [f64; 3],
    /// +1 when the disc turns by the right-hand rule about `axis` (counterclockwise seen from
    /// its tip), -1 the other way; 0 when the scene gives no sense (the older `[disc]`).
    pub sense: f64,
    /// Angular speed `Ω` (rad/s), when the scene gives one.
    pub angular_speed: Option<f64>,
}

/// How the disc's surface slides under the pad.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sliding {
    /// Along the tangent of the rotation at each contact point (needs `[rotation]`).
    Tangent,
    /// Along one global unit direction at every point (the paper's choice).
    Global([f64; 3]),
}

/// `[disc]`: how fast the disc turns, as `rpm` or as `vehicle_speed_kmh` with the wheel's
/// `rolling_radius`; optional (without it the sliding margin of a cycle is not reported). The
/// disc turns about the axis through `axis_origin` along `contact.normal`; a pair's surface
/// speed is the angular speed times its distance from that axis.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct DiscSection {
    /// Disc speed (revolutions per minute).
    pub rpm: Option<Spanned<f64>>,
    /// Vehicle speed (km/h); needs `rolling_radius`.
    pub vehicle_speed_kmh: Option<Spanned<f64>>,
    /// The wheel's effective rolling radius (m, or the `[units]` length): the disc turns at
    /// `v / r`.
    pub rolling_radius: Option<Spanned<f64>>,
    /// A point of the disc's axis (m, or the `[units]` length); the origin by default.
    pub axis_origin: Option<Spanned<[f64; 3]>>,
}

/// `[chbm]`: the scene's limit cycle, the one every command computes (read it through
/// [`Scene::cycle`]).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChbmSection {
    /// Friction of the limit cycle as a multiple of the Hopf point μ0.
    pub mu_ratio: Option<Spanned<f64>>,
    /// Friction of the limit cycle itself.
    pub mu: Option<Spanned<f64>>,
    #[serde(default = "default_harmonics")]
    pub harmonics: Spanned<usize>,
}

impl Default for ChbmSection {
    fn default() -> Self {
        Self {
            mu_ratio: None,
            mu: None,
            harmonics: default_harmonics(),
        }
    }
}

/// The friction of a scene's limit cycle when the scene gives none: just above the Hopf
/// point, the paper's choice for its Table 1.
pub const DEFAULT_CYCLE_MU_RATIO: f64 = 1.02;

/// Where a scene's limit cycle is computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CycleFriction {
    /// At this friction coefficient.
    Mu(f64),
    /// At this multiple of the Hopf point μ0.
    Ratio(f64),
}

impl CycleFriction {
    /// The friction coefficient, given the Hopf point `mu0` (asked for only by a ratio).
    pub fn mu<E>(
        self,
        mu0: impl FnOnce() -> std::result::Result<f64, E>,
    ) -> std::result::Result<f64, E> {
        match self {
            CycleFriction::Mu(m) => Ok(m),
            CycleFriction::Ratio(r) => Ok(r * mu0()?),
        }
    }
}

/// The scene's limit cycle: where, and with how many harmonics (eq 23).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CycleSpec {
    pub at: CycleFriction,
    pub harmonics: usize,
}

pub(super) fn default_harmonics() -> Spanned<usize> {
    Spanned::new(0..0, 3)
}

/// `[model]`: the meshes and their reduction.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSection {
    pub disc: PathBuf,
    /// The one pad of a one-pad brake; a brake with several pads names them in `[pads]`.
    pub pad: Option<PathBuf>,
    /// `patch` (default) or `node`.
    #[serde(default = "default_interface")]
    pub interface: Spanned<String>,
    /// Fixed-interface modes per part.
    #[serde(default = "default_modes")]
    pub modes: Spanned<usize>,
    /// Where the reduced model is kept (relative to the scene); default: in the output folder.
    pub rom: Option<PathBuf>,
    /// The disc as an element set of `disc`'s file, when that file holds an assembly (the
    /// disc and pads as element sets, as CAE tools export them).
    /// (A list of element sets makes one part of them all, e.g. a pad and its tied shim.)
    pub disc_elset: Option<Spanned<toml::Value>>,
    /// The pad of a one-pad brake as an element set (or a list of them) of `pad`'s file.
    pub pad_elset: Option<Spanned<toml::Value>>,
}

pub(super) fn default_interface() -> Spanned<String> {
    Spanned::new(0..0, "patch".into())
}
pub(super) fn default_modes() -> Spanned<usize> {
    Spanned::new(0..0, 50)
}

/// `[contact]`: eq (8)'s law and how points pair.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSection {
    /// Normal from the disc into the pad; optional: every pair takes the disc face's normal
    /// from the reduced model, and a normal given here is a check on it.
    pub normal: Option<Spanned<[f64; 3]>>,
    /// Disc and pad points pair when closer than this (m, or the `[units]` length).
    #[serde(default = "default_pairing")]
    pub pairing_tolerance: Spanned<f64>,
    /// A pad compression curve to fit `p = κ_l δ + κ_nl δ³` to.
    pub compression_curve: Option<CompressionCurve>,
    /// Or the stiffnesses per unit area directly (Pa/m, Pa/m³, or the `[units]` stress per
    /// length and per length cubed).
    pub k_linear_per_area: Option<Spanned<f64>>,
    pub k_cubic_per_area: Option<Spanned<f64>>,
    /// Scale factor on both stiffnesses (for studies: 0.7, 1, 1.3).
    #[serde(default = "one")]
    pub stiffness_scale: Spanned<f64>,
    /// Area (m², or the `[units]` area) a contact point stands for where the reduced model
    /// gives none (a node interface on parts without a contact face set).
    pub point_area: Option<Spanned<f64>>,
    /// Initial gap (m; positive: open, negative: interference) of every pair, or a list of
    /// one per pair in pair order; without it each pair's gap is measured from the geometry.
    pub initial_gap: Option<Spanned<toml::Value>>,
    /// `true`: every initial gap is closed (set to zero), as Abaqus' contact adjustment and
    /// Ansys' contact offset do; the geometric gaps are reported as the adjustment.
    pub close_initial_gaps: Option<Spanned<bool>>,
    /// The contact law ([`Scene::contact_law`]): `"penalty-coulomb"` (the default) or a table
    /// `{ kind = "velocity-dependent", static_ratio, decay_speed_m_per_s }`.
    pub law: Option<Spanned<toml::Value>>,
    /// The law that replaces permanent sliding where a cycle's sliding margin falls below 1
    /// ([`Scene::stick_slip_law`]): `"regularized"` (the default) or `"dlft"`.
    pub stick_slip: Option<Spanned<toml::Value>>,
}

/// The contact law a scene asks for (`[contact] law`); both use eq (8)'s penalty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ContactLawSetting {
    /// Coulomb friction, eqs (8)–(10).
    PenaltyCoulomb,
    /// `μ(v) = μ (r + (1 - r)(1 - e^(-v/v0)))` of the sliding speed `v`.
    VelocityDependent {
        /// `r = μ_s / μ_d`.
        static_ratio: f64,
        /// `v0` (m/s).
        decay_speed: f64,
    },
    /// `F_t = μ F_n s(|v|) tanh(v / v_reg)`, `s(v) = 1 + (r - 1) e^(-v/v_s)`
    /// (`stick_slip_keys`).
    RegularizedCoulomb {
        /// `v_reg` (m/s).
        regularization_speed: f64,
        /// `r = μ_s / μ`.
        static_ratio: f64,
        /// `v_s` (m/s).
        static_speed: f64,
    },
}

/// The law that treats stick–slip where a cycle's sliding margin falls below 1
/// (`[contact] stick_slip`, `stick_law_keys`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum StickSlipSetting {
    /// Each pair's element made to stick with `tanh(v / v_reg)` (the branch's `v_reg`: a
    /// twentieth of the slowest pair's disc surface speed).
    #[default]
    Regularized,
    /// Exact Coulomb stick–slip by the dynamic Lagrangian frequency–time method, its penalty
    /// the default times `epsilon_factor`.
    Dlft {
        /// Factor on the default penalty ε (any positive value: the same converged cycle).
        epsilon_factor: f64,
    },
}

/// The pairs' initial gaps a scene asks for (`[contact] initial_gap`, `close_initial_gaps`).
#[derive(Clone, Debug, PartialEq)]
pub enum GapSetting {
    /// Measured from the geometry at pairing (the default).
    Geometric,
    /// One gap (m) for every pair.
    Uniform(f64),
    /// One gap (m) per pair, in pair order.
    PerPair(Vec<f64>),
    /// Every gap closed.
    Closed,
}

pub(super) fn default_pairing() -> Spanned<f64> {
    Spanned::new(0..0, 1e-3)
}
pub(super) fn one() -> Spanned<f64> {
    Spanned::new(0..0, 1.0)
}

/// Measured (or assumed) pad compression: contact pressure against closure.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompressionCurve {
    pub pressure_mpa: Spanned<Vec<f64>>,
    pub closure_um: Spanned<Vec<f64>>,
}

/// `[friction]`: eq (9).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSection {
    /// The older place of `[chbm] mu`: the friction of the scene's limit cycle.
    pub mu: Option<Spanned<f64>>,
    /// `"tangent"` (the default: the tangent of the rotation at each contact point) or a
    /// global direction `[x, y, z]`.
    pub sliding: Option<Spanned<toml::Value>>,
    /// The older form of a global `sliding` direction.
    pub sliding_direction: Option<Spanned<[f64; 3]>>,
}

/// `[piston]`: the clamp load.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PistonSection {
    /// Hydraulic line pressure (bar).
    pub line_pressure_bar: Spanned<f64>,
    /// Total piston area (m², or the `[units]` area).
    pub area: Spanned<f64>,
}

/// `[damping]`: eqs (12)–(13).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DampingSection {
    #[serde(default = "default_global")]
    pub global_ratio: Spanned<f64>,
    /// `"auto"` or `[mode1, mode2]` (1-based frictionless mode numbers).
    #[serde(default = "default_pair")]
    pub pair: Spanned<toml::Value>,
    /// Ratios ζ1 (stable Mode 1), ζ2 (unstable Mode 2) added on the pair.
    #[serde(default)]
    pub pair_ratios: Option<Spanned<[f64; 2]>>,
}

impl Default for DampingSection {
    fn default() -> Self {
        Self {
            global_ratio: default_global(),
            pair: default_pair(),
            pair_ratios: None,
        }
    }
}

pub(super) fn default_global() -> Spanned<f64> {
    Spanned::new(0..0, 0.01)
}
pub(super) fn default_pair() -> Spanned<toml::Value> {
    Spanned::new(0..0, toml::Value::String("auto".into()))
}

/// `[stability]`.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct StabilitySection {
    /// `"start..end/count"` or a list of values.
    pub mu: Option<Spanned<toml::Value>>,
    /// The band μ0 must lie in (Hz), besides the model's valid band.
    pub band_hz: Option<Spanned<[f64; 2]>>,
}
